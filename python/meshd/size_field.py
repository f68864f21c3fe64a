"""Size fields: the relative edge length h(p), the minimum of its terms; the wanted edge length
at p is h0 * h(p).

    meshd.uniform(1)                                   # h = 1 everywhere (the default)
    meshd.graded(hole, h_min=1, slope=4, h_max=2)      # G5: fine at the hole, coarser away
    size=[meshd.graded(hole, 1, 4, 2), meshd.uniform(1.5)]   # the minimum of both
    meshd.grid(h, origin=(0, 0), spacing=0.1)          # h[j, i] at (0.1 i, 0.1 j), bilinear
    meshd.feature(3, h_min=0.5, h_max=10)              # 3 edges across narrow channels
    meshd.graded(meshd.sphere(0.2), 1, 3, 3)           # a volume's: fine near the ball
"""

import numpy as np

from meshd.geometry import as_shape_proto
from meshd.solid import Solid, as_solid_proto
from meshd.v1 import geometry3d_pb2, geometry_pb2


def uniform(value=1.0):
    """A SizeTerm h = value (> 0) everywhere."""
    term = geometry_pb2.SizeTerm()
    term.uniform.value = float(value)
    return term


def graded(shape, h_min, slope, h_max):
    """A SizeTerm growing with the distance to shape: h = min(h_max, h_min + slope * |d(p)|).
    h_min > 0; slope >= 0, relative size per length unit; h_max >= h_min. A Solid gives the
    volume's term (a SizeTerm3), a plane Shape the plane's."""
    if isinstance(shape, (Solid, geometry3d_pb2.Shape3)):
        term = geometry3d_pb2.SizeTerm3()
        term.distance.shape.CopyFrom(as_solid_proto(shape))
        term.distance.h_min = float(h_min)
        term.distance.slope = float(slope)
        term.distance.h_max = float(h_max)
        return term
    term = geometry_pb2.SizeTerm()
    term.distance.shape.CopyFrom(as_shape_proto(shape))
    term.distance.h_min = float(h_min)
    term.distance.slope = float(slope)
    term.distance.h_max = float(h_max)
    return term


def grid(values, origin, spacing):
    """A SizeTerm given on a regular grid and read by bilinear interpolation; outside the grid
    the border values extend. values: a 2-D array (or nested lists) indexed [j, i], each finite
    and > 0, at least 2 x 2; sample [j, i] lies at (origin[0] + i * dx, origin[1] + j * dy), row
    j counted upwards from the origin (flip an image's rows first: values[::-1]). spacing: d or
    (dx, dy), > 0. The server limits the values of a request's grids together (default 16
    million)."""
    a = np.asarray(values, dtype=np.float32)
    if a.ndim != 2 or a.shape[0] < 2 or a.shape[1] < 2:
        raise ValueError(f"grid: values must be 2-D, at least 2 x 2 (got shape {a.shape})")
    dx, dy = (spacing, spacing) if np.isscalar(spacing) else spacing
    term = geometry_pb2.SizeTerm()
    term.grid.ny, term.grid.nx = a.shape
    term.grid.origin.CopyFrom(geometry_pb2.Vec2(x=float(origin[0]), y=float(origin[1])))
    term.grid.spacing.CopyFrom(geometry_pb2.Vec2(x=float(dx), y=float(dy)))
    term.grid.values.extend(np.ascontiguousarray(a).ravel().tolist())
    return term


def feature(elements, h_min, h_max):
    """A SizeTerm from the domain's local feature size: about `elements` edges (>= 1) across its
    narrow parts, h = clamp(2 (|d| + d_MA) / (elements * h0), h_min, h_max), d the distance to
    the boundary and d_MA to the medial axis; h_min > 0, h_max >= h_min."""
    term = geometry_pb2.SizeTerm()
    term.feature.elements = float(elements)
    term.feature.h_min = float(h_min)
    term.feature.h_max = float(h_max)
    return term


def size_field3(size):
    """A volume's SizeField3 from a SizeField3, one term, a number (uniform) or a list of them:
    uniform terms and graded ones about a Solid (grids and feature sizes are plane only)."""
    if isinstance(size, geometry3d_pb2.SizeField3):
        return size
    field = geometry3d_pb2.SizeField3()
    for term in size if isinstance(size, (list, tuple)) else [size]:
        if isinstance(term, (int, float)):
            term = uniform(term)
        if isinstance(term, geometry_pb2.SizeTerm) and term.WhichOneof("kind") == "uniform":
            field.terms.add().uniform.CopyFrom(term.uniform)
        elif isinstance(term, geometry3d_pb2.SizeTerm3):
            field.terms.append(term)
        else:
            raise TypeError("size of a volume: expected meshd.uniform(...) or "
                            "meshd.graded(solid, ...), got a plane-only term or "
                            f"{type(term).__name__}")
    return field


def size_field(size):
    """A SizeField from a SizeField, one SizeTerm, a number (uniform) or a list of those terms."""
    if isinstance(size, geometry_pb2.SizeField):
        return size
    field = geometry_pb2.SizeField()
    terms = size if isinstance(size, (list, tuple)) else [size]
    for term in terms:
        if isinstance(term, (int, float)):
            term = uniform(term)
        if isinstance(term, (geometry3d_pb2.SizeTerm3, geometry3d_pb2.SizeField3)):
            raise TypeError("size of a plane shape: meshd.graded(solid, ...) grades a volume; "
                            "grade about a plane Shape, or mesh a Solid")
        if not isinstance(term, geometry_pb2.SizeTerm):
            raise TypeError(f"size: expected meshd.uniform(...), meshd.graded(...), "
                            f"meshd.grid(...) or meshd.feature(...), got {type(term).__name__}")
        field.terms.append(term)
    return field
