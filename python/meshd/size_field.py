"""Size fields: the relative edge length h(p), the minimum of its terms; the wanted edge length
at p is h0 * h(p).

    meshd.uniform(1)                                   # h = 1 everywhere (the default)
    meshd.graded(hole, h_min=1, slope=4, h_max=2)      # G5: fine at the hole, coarser away
    size=[meshd.graded(hole, 1, 4, 2), meshd.uniform(1.5)]   # the minimum of both
"""

from meshd.geometry import as_shape_proto
from meshd.v1 import geometry_pb2


def uniform(value=1.0):
    """A SizeTerm h = value (> 0) everywhere."""
    term = geometry_pb2.SizeTerm()
    term.uniform.value = float(value)
    return term


def graded(shape, h_min, slope, h_max):
    """A SizeTerm growing with the distance to shape: h = min(h_max, h_min + slope * |d(p)|).
    h_min > 0; slope >= 0, relative size per length unit; h_max >= h_min."""
    term = geometry_pb2.SizeTerm()
    term.distance.shape.CopyFrom(as_shape_proto(shape))
    term.distance.h_min = float(h_min)
    term.distance.slope = float(slope)
    term.distance.h_max = float(h_max)
    return term


def size_field(size):
    """A SizeField from a SizeField, one SizeTerm, a number (uniform) or a list of those terms."""
    if isinstance(size, geometry_pb2.SizeField):
        return size
    field = geometry_pb2.SizeField()
    terms = size if isinstance(size, (list, tuple)) else [size]
    for term in terms:
        if isinstance(term, (int, float)):
            term = uniform(term)
        if not isinstance(term, geometry_pb2.SizeTerm):
            raise TypeError(f"size: expected meshd.uniform(...) or meshd.graded(...), got "
                            f"{type(term).__name__}")
        field.terms.append(term)
    return field
