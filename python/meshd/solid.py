"""3D geometry builders: a CSG tree of solids written as Python expressions, built as the
meshd.v1.Shape3 message the server reads in a volume request.

    part = (meshd.box((-1, -1, -1), (1, 1, 1)).named("box")
            - meshd.sphere(0.5).named("ball"))
    shaft = meshd.cylinder(0.2, 3).rotate(90, axis=(1, 0, 0))
    gear = meshd.extrude(meshd.circle(1) - meshd.circle(0.3), height=0.4)
    ring = meshd.revolve(meshd.circle(0.3, center=(1, 0)))        # a torus
    part = meshd.polyhedron(stl.points, stl.cells_dict["triangle"])  # a closed triangle surface

`a | b` is the union, `a & b` the intersection, `a - b` the difference, as for plane shapes.
Lengths are in the request's length unit, angles in degrees. Solids are immutable.
"""

from meshd.geometry import (TreeNode, as_node_proto, as_shape_proto, difference_node,
                            nary_node, primitive_node)
from meshd.v1 import geometry3d_pb2


def _vec3(xyz, what):
    """A Vec3 from any three numbers; `what` names the argument in the error."""
    try:
        x, y, z = (float(v) for v in xyz)
    except (TypeError, ValueError):
        raise TypeError(f"{what}: expected a point (x, y, z), got {xyz!r}") from None
    return geometry3d_pb2.Vec3(x=x, y=y, z=z)


class Solid(TreeNode):
    """One node of the 3D geometry tree, a meshd.v1.Shape3."""

    __slots__ = ()
    MESSAGE = geometry3d_pb2.Shape3

    def __or__(self, other):
        return union(self, other)

    def __and__(self, other):
        return intersection(self, other)

    def __sub__(self, other):
        return difference(self, other)

    def translate(self, offset):
        """This solid moved by offset (dx, dy, dz)."""
        return self._wrapped("translate",
                             lambda t: t.offset.CopyFrom(_vec3(offset, "offset")))

    def rotate(self, angle_deg, axis=(0.0, 0.0, 1.0), center=(0.0, 0.0, 0.0)):
        """This solid turned by angle_deg degrees (right-handed) about the line through center
        along axis."""
        def fill(r):
            r.angle_deg = float(angle_deg)
            r.axis.CopyFrom(_vec3(axis, "axis"))
            r.center.CopyFrom(_vec3(center, "center"))
        return self._wrapped("rotate", fill)

    def scale(self, factor, center=(0.0, 0.0, 0.0)):
        """This solid scaled by factor (> 0) about center."""
        def fill(s):
            s.factor = float(factor)
            s.center.CopyFrom(_vec3(center, "center"))
        return self._wrapped("scale", fill)


def as_solid_proto(solid):
    """A meshd.v1.Shape3 from a Solid or a meshd.v1.Shape3 message (copied)."""
    return as_node_proto(solid, Solid)


def _primitive(kind, name, fill):
    return primitive_node(Solid, kind, name, fill)


# ---- primitives -------------------------------------------------------------------------------

def sphere(radius=1.0, center=(0.0, 0.0, 0.0), name=None):
    """The ball of radius (> 0) about center."""
    def fill(s):
        s.center.CopyFrom(_vec3(center, "center"))
        s.radius = float(radius)
    return _primitive("sphere", name, fill)


def box(min, max, name=None):  # noqa: A002 (the proto's field names)
    """The axis-aligned box from corner min (x0, y0, z0) to corner max (x1, y1, z1)."""
    def fill(b):
        b.min.CopyFrom(_vec3(min, "min"))
        b.max.CopyFrom(_vec3(max, "max"))
    return _primitive("box", name, fill)


def cylinder(radius, height, base_center=(0.0, 0.0, 0.0), name=None):
    """The capped cylinder along +z from base_center: radius and height > 0."""
    def fill(c):
        c.base_center.CopyFrom(_vec3(base_center, "base_center"))
        c.radius = float(radius)
        c.height = float(height)
    return _primitive("cylinder", name, fill)


def cone(bottom_radius, top_radius, height, base_center=(0.0, 0.0, 0.0), name=None):
    """The cone or frustum along +z from base_center: radii >= 0, not both 0; height > 0."""
    def fill(c):
        c.base_center.CopyFrom(_vec3(base_center, "base_center"))
        c.bottom_radius = float(bottom_radius)
        c.top_radius = float(top_radius)
        c.height = float(height)
    return _primitive("cone", name, fill)


def torus(major_radius, minor_radius, center=(0.0, 0.0, 0.0), name=None):
    """The ring torus about the z axis through center: major_radius > minor_radius > 0."""
    def fill(t):
        t.center.CopyFrom(_vec3(center, "center"))
        t.major_radius = float(major_radius)
        t.minor_radius = float(minor_radius)
    return _primitive("torus", name, fill)


def half_space(normal, offset=0.0, name=None):
    """The half-space dot(normal, p) <= offset; cut it off with bounded solids."""
    def fill(h):
        h.normal.CopyFrom(_vec3(normal, "normal"))
        h.offset = float(offset)
    return _primitive("half_space", name, fill)


def extrude(profile, height, name=None):
    """A plane Shape (meshd.circle(...) and friends) in the xy plane extruded along +z from 0 to
    height (> 0); its rims and the vertical edges at its corners stay sharp."""
    def fill(e):
        e.profile.CopyFrom(as_shape_proto(profile))
        e.height = float(height)
    return _primitive("extrusion", name, fill)


def revolve(profile, name=None):
    """A plane Shape revolved about the z axis: its x is the distance from the axis, its y the
    height. A solid that reaches the axis needs a profile symmetric about it."""
    def fill(r):
        r.profile.CopyFrom(as_shape_proto(profile))
    return _primitive("revolution", name, fill)


# ---- operations -------------------------------------------------------------------------------

def polyhedron(vertices, triangles, name=None):
    """The solid inside a closed triangle surface: vertices an (n, 3) array of finite
    coordinates, triangles an (m, 3) array of indices into them, every triangle turned the same
    way (either way), closed and manifold; e.g. from a file read with meshio,
    `polyhedron(m.points, m.cells_dict["triangle"])`. Edges where faces meet at more than 35
    degrees stay sharp."""
    import numpy as np  # noqa: PLC0415 (only polyhedra need NumPy)
    v = np.asarray(vertices, dtype=np.float64)
    t = np.asarray(triangles)
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"vertices must be an (n, 3) array (got shape {v.shape})")
    if t.ndim != 2 or t.shape[1] != 3 or not np.issubdtype(t.dtype, np.integer):
        raise ValueError(f"triangles must be an (m, 3) integer array (got {t.dtype} {t.shape})")
    if t.size and (t.min() < 0 or t.max() >= len(v)):
        raise ValueError(f"triangles must index vertices in [0, {len(v)})")

    def fill(p):
        p.SetInParent()  # set even where both arrays are empty, so that the server names them
        p.vertices.extend(v.ravel().tolist())
        p.triangles.extend(t.astype(np.uint32).ravel().tolist())
    return _primitive("polyhedron", name, fill)


def _nary(kind, solids):
    return Solid(nary_node(geometry3d_pb2.Shape3, kind, [as_solid_proto(s) for s in solids]))


def union(*solids):
    """The union of one or more solids (also `a | b`)."""
    return _nary("union", solids)


def intersection(*solids):
    """The intersection of one or more solids (also `a & b`)."""
    return _nary("intersection", solids)


def difference(base, *subtract):
    """base minus every solid of subtract (also `a - b`)."""
    return Solid(difference_node(geometry3d_pb2.Shape3, as_solid_proto(base),
                                 [as_solid_proto(s) for s in subtract]))
