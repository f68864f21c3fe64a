"""Geometry builders: a CSG tree of shapes written as Python expressions, built as the
meshd.v1.Shape message the server reads.

    domain = (meshd.rectangle((-1, -1), (1, 1)).named("outer")
              - meshd.circle(0.5).named("hole"))
    ring = meshd.circle(1) - meshd.circle(0.3)
    lens = meshd.circle(1, center=(-0.5, 0)) & meshd.circle(1, center=(0.5, 0))
    tooth = meshd.rectangle((0.9, -0.1), (1.2, 0.1)).rotate(30)

`a | b` is the union, `a & b` the intersection, `a - b` the difference; chains of the same
operation become one n-ary node. Lengths are in the request's length unit, angles in degrees.
Shapes are immutable: every operation returns a new one.
"""

from meshd.v1 import geometry_pb2


def _vec2(xy, what):
    """A Vec2 from any pair of numbers; `what` names the argument in the error."""
    try:
        x, y = (float(v) for v in xy)
    except (TypeError, ValueError):
        raise TypeError(f"{what}: expected a point (x, y), got {xy!r}") from None
    return geometry_pb2.Vec2(x=x, y=y)


class TreeNode:
    """What a node of either geometry tree is (Shape in the plane, meshd.Solid in space): an
    immutable wrapper of its proto message, of type MESSAGE. `proto` is a copy: changing it leaves
    the node alone."""

    __slots__ = ("_proto",)
    MESSAGE = None

    def __init__(self, proto):
        self._proto = proto

    @property
    def proto(self):
        copy = self.MESSAGE()
        copy.CopyFrom(self._proto)
        return copy

    @property
    def kind(self):
        """Which of the proto's kinds this node is: "circle", "sphere", "union", ..."""
        return self._proto.WhichOneof("kind")

    @property
    def name(self):
        return self._proto.name

    def named(self, name):
        """This node with a boundary-group name: the primitives at or below it that have no name
        of their own put their boundary in group `name`."""
        proto = self.proto
        proto.name = name
        return type(self)(proto)

    def _wrapped(self, kind, fill):
        """A new node of `kind` (a transform) over this one; fill(node) sets its parameters."""
        proto = self.MESSAGE()
        node = getattr(proto, kind)
        fill(node)
        node.shape.CopyFrom(self._proto)
        return type(self)(proto)

    def __repr__(self):
        from google.protobuf import text_format
        text = text_format.MessageToString(self._proto, as_one_line=True)
        return f"meshd.{type(self).__name__}({text})"


def as_node_proto(node, cls):
    """A copy of the proto of `node`, a `cls` (a TreeNode class) or its MESSAGE."""
    if isinstance(node, cls):
        return node.proto
    if isinstance(node, cls.MESSAGE):
        copy = cls.MESSAGE()
        copy.CopyFrom(node)
        return copy
    raise TypeError(f"expected a meshd.{cls.__name__}, got {type(node).__name__}")


def primitive_node(cls, kind, name, fill):
    """A `cls` whose proto is the primitive `kind`; fill(primitive) sets its parameters."""
    proto = cls.MESSAGE()
    if name:
        proto.name = name
    fill(getattr(proto, kind))
    return cls(proto)


class Shape(TreeNode):
    """One node of the plane geometry tree, a meshd.v1.Shape."""

    __slots__ = ()
    MESSAGE = geometry_pb2.Shape

    # ---- operations ---------------------------------------------------------------------------

    def __or__(self, other):
        return union(self, other)

    def __and__(self, other):
        return intersection(self, other)

    def __sub__(self, other):
        return difference(self, other)

    # ---- transforms ---------------------------------------------------------------------------

    def translate(self, offset):
        """This shape moved by offset (dx, dy)."""
        return self._wrapped("translate",
                             lambda t: t.offset.CopyFrom(_vec2(offset, "offset")))

    def rotate(self, angle_deg, center=(0.0, 0.0)):
        """This shape turned counter-clockwise by angle_deg degrees about center."""
        def fill(r):
            r.angle_deg = float(angle_deg)
            r.center.CopyFrom(_vec2(center, "center"))
        return self._wrapped("rotate", fill)

    def scale(self, factor, center=(0.0, 0.0)):
        """This shape scaled by factor (> 0) about center."""
        def fill(s):
            s.factor = float(factor)
            s.center.CopyFrom(_vec2(center, "center"))
        return self._wrapped("scale", fill)


def as_shape_proto(shape):
    """A meshd.v1.Shape from a Shape or a meshd.v1.Shape message (copied)."""
    return as_node_proto(shape, Shape)


def _primitive(kind, name, fill):
    return primitive_node(Shape, kind, name, fill)


# ---- primitives -------------------------------------------------------------------------------

def circle(radius=1.0, center=(0.0, 0.0), name=None):
    """The disk of radius (> 0) about center."""
    def fill(c):
        c.center.CopyFrom(_vec2(center, "center"))
        c.radius = float(radius)
    return _primitive("circle", name, fill)


def rectangle(min, max, name=None):  # noqa: A002 (the proto's field names)
    """The axis-aligned rectangle from corner min (x0, y0) to corner max (x1, y1)."""
    def fill(r):
        r.min.CopyFrom(_vec2(min, "min"))
        r.max.CopyFrom(_vec2(max, "max"))
    return _primitive("rectangle", name, fill)


def polygon(vertices, name=None):
    """The simple polygon through vertices: #V by 2 (a list of (x, y) or a numpy array), either
    orientation, the first vertex not repeated at the end."""
    def fill(p):
        for i, xy in enumerate(vertices):
            p.vertices.append(_vec2(xy, f"vertices[{i}]"))
    return _primitive("polygon", name, fill)


def ellipse(semi_axis_x, semi_axis_y, center=(0.0, 0.0), name=None):
    """The axis-aligned ellipse with these semi axes (> 0) about center."""
    def fill(e):
        e.center.CopyFrom(_vec2(center, "center"))
        e.semi_axis_x = float(semi_axis_x)
        e.semi_axis_y = float(semi_axis_y)
    return _primitive("ellipse", name, fill)


def half_plane(normal, offset=0.0, name=None):
    """The half-plane dot(normal, p) <= offset. Unbounded: the request needs a bbox."""
    def fill(h):
        h.normal.CopyFrom(_vec2(normal, "normal"))
        h.offset = float(offset)
    return _primitive("half_plane", name, fill)


def distance_grid(values, spacing=1.0, origin=(0.0, 0.0), name=None):
    """A signed distance sampled on a regular grid (DistMesh's dmatrix), e.g. the distance
    transform of a segmented image: values is #rows by #columns (a numpy array or nested lists),
    negative inside, in the request's length unit; values[j, i] lies at
    (origin.x + i * dx, origin.y + j * dy), rows counted upwards (np.flipud an image first).
    spacing: d or (dx, dy), > 0. The domain is where the bilinear interpolant is negative,
    within the grid's box."""
    import numpy as np
    grid = np.asarray(values, dtype=np.float32)
    if grid.ndim != 2 or min(grid.shape) < 2:
        raise ValueError(f"values: expected a 2-D array of at least 2 x 2, got shape {grid.shape}")
    dx, dy = (spacing, spacing) if np.ndim(spacing) == 0 else spacing

    def fill(g):
        g.ny, g.nx = grid.shape
        g.origin.CopyFrom(_vec2(origin, "origin"))
        g.spacing.x, g.spacing.y = float(dx), float(dy)
        g.values.extend(grid.ravel().tolist())
    return _primitive("distance_grid", name, fill)


# ---- operations -------------------------------------------------------------------------------

def nary_node(message_type, kind, operands):
    """A union or intersection node (a new message_type: Shape or Shape3) of the operand protos;
    an unnamed operand of the same kind is merged in (a named one keeps its node, since its name
    applies to its own primitives only)."""
    if not operands:
        raise ValueError(f"{kind} of no shapes")
    proto = message_type()
    children = getattr(proto, kind).shapes
    for child in operands:
        if child.WhichOneof("kind") == kind and not child.name:
            children.extend(getattr(child, kind).shapes)
        else:
            children.append(child)
    return proto


def difference_node(message_type, base, subtract):
    """base minus every proto of subtract, as a new message_type; an unnamed difference as base
    is extended rather than nested."""
    proto = message_type()
    if base.WhichOneof("kind") == "difference" and not base.name:
        proto.difference.CopyFrom(base.difference)
    else:
        proto.difference.base.CopyFrom(base)
    for child in subtract:
        proto.difference.subtract.append(child)
    return proto


def _nary(kind, shapes):
    return Shape(nary_node(geometry_pb2.Shape, kind, [as_shape_proto(s) for s in shapes]))


def _solids_of(first):
    """meshd.solid when the first operand is a solid, so that meshd.union and friends combine
    solids as they do shapes; else None."""
    from meshd import solid  # imports this module: not at the top
    return solid if isinstance(first, (solid.Solid, solid.geometry3d_pb2.Shape3)) else None


def union(*shapes):
    """The union of one or more shapes, or of solids (also `a | b`)."""
    solids = _solids_of(shapes[0]) if shapes else None
    return solids.union(*shapes) if solids else _nary("union", shapes)


def intersection(*shapes):
    """The intersection of one or more shapes, or of solids (also `a & b`)."""
    solids = _solids_of(shapes[0]) if shapes else None
    return solids.intersection(*shapes) if solids else _nary("intersection", shapes)


def difference(base, *subtract):
    """base minus every shape of subtract (also `a - b`; `a - b - c` is one node); base and
    subtract may be solids instead."""
    solids = _solids_of(base)
    if solids:
        return solids.difference(base, *subtract)
    return Shape(difference_node(geometry_pb2.Shape, as_shape_proto(base),
                                 [as_shape_proto(s) for s in subtract]))
