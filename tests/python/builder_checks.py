#!/usr/bin/env python3
"""The installed meshd package without a server: geometry builders and meshd.request() against
the repository's example requests, error parsing, and the event decoder's checks.

    builder_checks.py --examples DIR       (run with the interpreter the package is installed in)
"""

import argparse
import hashlib
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_runner import run_checks  # noqa: E402

import grpc  # noqa: E402
import numpy as np  # noqa: E402
from google.protobuf import text_format  # noqa: E402

import meshd  # noqa: E402
from meshd.errors import error_for_status  # noqa: E402
from meshd.events import EventDecoder  # noqa: E402
from meshd.v1 import mesh_pb2, request_pb2, service_pb2  # noqa: E402


def read_example(examples, name):
    with open(os.path.join(examples, name)) as f:
        return text_format.Parse(f.read(), request_pb2.MeshRequest())


def same(built, expected, what):
    assert built == expected, (f"{what} differs:\nbuilt:\n{text_format.MessageToString(built)}"
                               f"expected:\n{text_format.MessageToString(expected)}")


def test_installed_package(examples):
    # Imported from the venv, not from a source folder, with stubs the build generated.
    assert meshd.__file__.startswith(sys.prefix), f"meshd from {meshd.__file__}"
    stubs = os.path.dirname(request_pb2.__file__)
    assert os.path.basename(stubs) == "v1" and stubs.startswith(sys.prefix), stubs
    assert "h0" in request_pb2.MeshRequest.DESCRIPTOR.fields_by_name
    assert hasattr(meshd.aio, "Client") and callable(meshd.Client)


def test_examples_from_builders(examples):
    """G2, G5 and the ring of meshctl's --circle/--hole, built in Python, equal their files."""
    outer = meshd.rectangle((-1, -1), (1, 1)).named("outer")
    g2 = meshd.request(outer - meshd.circle(0.5).named("hole"), h0=0.04, auto_corners=True)
    same(g2, read_example(examples, "g2_square_hole.textproto"), "G2")
    g5 = meshd.request(outer - meshd.circle(0.5, name="hole"), h0=0.025,
                       size=meshd.graded(meshd.circle(0.5), h_min=1, slope=4, h_max=2),
                       auto_corners=True)
    same(g5, read_example(examples, "g5_graded_hole.textproto"), "G5")
    g1 = meshd.request(meshd.circle(1), h0=0.04)
    expected = read_example(examples, "g1_disk.textproto")
    assert g1.geometry.circle.radius == expected.geometry.circle.radius and g1.h0 == expected.h0


def test_operators(examples):
    a, b, c = meshd.circle(1), meshd.rectangle((0, 0), (1, 1)), meshd.ellipse(2, 1)
    u = (a | b) | c
    assert u.kind == "union" and len(u.proto.union.shapes) == 3, u
    i = a & b & c
    assert i.kind == "intersection" and len(i.proto.intersection.shapes) == 3, i
    d = a - b - c
    assert d.kind == "difference" and len(d.proto.difference.subtract) == 2, d
    assert d.proto.difference.base == a.proto
    # A named operand keeps its own node: its name covers its own primitives only.
    named = (a | b).named("pair") | c
    assert [s.WhichOneof("kind") for s in named.proto.union.shapes] == ["union", "ellipse"]
    assert (a - b).named("x") - c != a - b - c
    # Shapes are values: an operation leaves its operands alone.
    assert a.proto == meshd.circle(1).proto and not a.name


def test_primitives_and_transforms(examples):
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    p = meshd.polygon(square, name="sq").proto
    assert p.name == "sq" and [(v.x, v.y) for v in p.polygon.vertices] == [tuple(v) for v in square]
    h = meshd.half_plane((0, 1), 0.5).proto.half_plane
    assert (h.normal.x, h.normal.y, h.offset) == (0, 1, 0.5)
    e = meshd.ellipse(2, 1, center=(1, 2)).proto.ellipse
    assert (e.semi_axis_x, e.semi_axis_y, e.center.x, e.center.y) == (2, 1, 1, 2)
    t = meshd.circle(1).translate((2, 3)).rotate(30, center=(1, 1)).scale(2).proto
    assert t.scale.factor == 2 and t.scale.shape.rotate.angle_deg == 30
    assert t.scale.shape.rotate.center.x == 1
    moved = t.scale.shape.rotate.shape.translate
    assert (moved.offset.x, moved.offset.y, moved.shape.circle.radius) == (2, 3, 1)
    # A distance grid: rows of the array are rows of the grid, from the origin upwards.
    sdf = np.array([[-1.0, -0.5, 0.25], [0.5, 1.0, 2.0]])
    g = meshd.distance_grid(sdf, spacing=(0.5, 2), origin=(1, -1), name="img").proto
    assert g.name == "img" and (g.distance_grid.nx, g.distance_grid.ny) == (3, 2)
    dg = g.distance_grid
    assert (dg.spacing.x, dg.spacing.y, dg.origin.x) == (0.5, 2, 1)
    assert list(g.distance_grid.values) == [-1.0, -0.5, 0.25, 0.5, 1.0, 2.0]
    assert meshd.distance_grid([[-1, 1], [1, 1]], spacing=0.1).proto.distance_grid.spacing.y == 0.1
    try:
        meshd.distance_grid([1.0, -1.0])
        raise AssertionError("a 1-D grid was accepted")
    except ValueError:
        pass
    for bad in (lambda: meshd.circle(1, center=(1,)), lambda: meshd.polygon([(0, 0), "ab"])):
        try:
            bad()
            raise AssertionError("a malformed point was accepted")
        except TypeError:
            pass


def test_request_fields(examples):
    hole = meshd.circle(0.3)
    req = meshd.request(meshd.circle(1) - hole, h0=0.05,
                        size=[meshd.graded(hole, 1, 3, 2), 1.5], bbox=((-1, -1), (1, 1)),
                        fixed_points=[(0.5, 0)], auto_corners=False, seed=7, backend="cpu",
                        priority=3, snapshot_every=10, timeout_s=30, label="ring",
                        dptol=0.002, max_iterations=500, cleanup=False)
    assert [t.WhichOneof("kind") for t in req.size.terms] == ["distance", "uniform"]
    assert req.size.terms[1].uniform.value == 1.5 and req.size.terms[0].distance.slope == 3
    assert (req.bbox.max.x, req.fixed_points[0].x, req.seed) == (1, 0.5, 7)
    assert req.HasField("auto_corners") and not req.auto_corners
    assert req.options.backend == request_pb2.JobOptions.BACKEND_CPU
    assert (req.options.priority, req.options.snapshot_every, req.options.label) == (3, 10, "ring")
    assert req.params.dptol == 0.002 and req.params.max_iterations == 500
    assert req.params.HasField("cleanup") and not req.params.HasField("ttol")
    for kwargs, error in (({"dtpol": 1}, TypeError), ({"backend": "tpu"}, ValueError)):
        try:
            meshd.request(hole, h0=0.1, **kwargs)
            raise AssertionError(f"request accepted {kwargs}")
        except error as e:
            assert list(kwargs)[0] in str(e) or "tpu" in str(e), str(e)


def test_size_grid(examples):
    """meshd.grid: a 2-D array indexed [j, i] becomes a GridSize row by row; gradation goes to
    the size field; meshd.feature fills a FeatureSize."""
    h = [[1, 2, 3], [4, 5, 6]]  # 2 rows (y), 3 columns (x)
    req = meshd.request(meshd.rectangle((0, 0), (2, 1)), h0=0.1,
                        size=[meshd.grid(h, origin=(0, 0), spacing=(1, 1)), 2], gradation=0.3)
    g = req.size.terms[0].grid
    assert (g.nx, g.ny, g.spacing.x, g.spacing.y) == (3, 2, 1, 1), g
    assert list(g.values) == [1, 2, 3, 4, 5, 6], list(g.values)
    assert req.size.terms[1].uniform.value == 2 and req.size.gradation == 0.3
    assert meshd.grid(h, (0, 0), 0.5).grid.spacing.y == 0.5
    f = meshd.feature(3, h_min=0.5, h_max=10).feature
    assert (f.elements, f.h_min, f.h_max) == (3, 0.5, 10), f
    try:
        meshd.grid([1, 2, 3], (0, 0), 1)
        raise AssertionError("a 1-D grid was accepted")
    except ValueError as e:
        assert "2-D" in str(e), str(e)


def test_error_parsing(examples):
    path = "geometry.difference.subtract[0].circle.radius"
    e = error_for_status(grpc.StatusCode.INVALID_ARGUMENT, f"{path}: must be finite and > 0 (got -0.5)")
    assert isinstance(e, meshd.InvalidArgument) and isinstance(e, meshd.MeshdError)
    assert (e.field, e.reason) == (path, "must be finite and > 0 (got -0.5)"), (e.field, e.reason)
    assert e.code == grpc.StatusCode.INVALID_ARGUMENT and path in str(e)
    for code, message, cls in (
            (grpc.StatusCode.UNAVAILABLE, "the server is shutting down", meshd.Unavailable),
            (grpc.StatusCode.INTERNAL, "internal error: x: y", meshd.Internal),
            (grpc.StatusCode.UNAUTHENTICATED, "wrong bearer token", meshd.Unauthenticated),
            (grpc.StatusCode.ABORTED, "", meshd.MeshdError)):
        e = error_for_status(code, message)
        assert type(e) is cls and e.field is None and e.code == code, (code, message, e.field)
    e = error_for_status(grpc.StatusCode.NOT_FOUND, "job_id: no job 'x' on this server")
    assert isinstance(e, meshd.NotFound) and e.field == "job_id"


def result_events(mesh, chunk_bytes):
    """The result part of a stream for mesh: chunks of chunk_bytes, then done."""
    payload = mesh.SerializeToString()
    events = []
    pieces = [payload[i:i + chunk_bytes] for i in range(0, len(payload), chunk_bytes)]
    for k, piece in enumerate(pieces):
        e = service_pb2.MeshEvent(job_id="j1")
        e.result_chunk.index, e.result_chunk.count = k, len(pieces)
        e.result_chunk.offset, e.result_chunk.total_bytes = k * chunk_bytes, len(payload)
        e.result_chunk.data = piece
        events.append(e)
    done = service_pb2.MeshEvent(job_id="j1")
    done.done.result_bytes = len(payload)
    done.done.result_sha256 = hashlib.sha256(payload).hexdigest()
    done.done.nodes, done.done.triangles = 3, 1
    return events + [done]


def test_event_decoder(examples):
    data = mesh_pb2.MeshData(points=[0, 0, 1, 0, 0, 1], triangles=[0, 1, 2],
                             boundary_edges=[0, 1, 1, 2, 2, 0], boundary_tags=[0, 0, 1],
                             boundary_names=["a", "b"])
    decoder = EventDecoder()
    decoded = [decoder.feed(e) for e in result_events(data, 10)]
    assert all(e is None for e in decoded[:-1]) and isinstance(decoded[-1], meshd.Done)
    mesh = decoder.finish().mesh
    assert mesh.points.shape == (3, 2) and mesh.triangles.tolist() == [[0, 1, 2]]
    assert mesh.boundary_groups["a"].tolist() == [[0, 1], [1, 2]] and mesh.areas()[0] == 0.5
    # A volume's result (dimension 3): one regular tetrahedron, its four faces in two groups.
    corners = [[1, 1, 1], [-1, -1, 1], [-1, 1, -1], [1, -1, -1]]
    tet = mesh_pb2.MeshData(points=np.ravel(corners).tolist(), tetrahedra=[0, 1, 2, 3],
                            boundary_faces=[1, 3, 2, 0, 2, 3, 0, 3, 1, 0, 1, 2],
                            boundary_tags=[0, 1, 1, 1], boundary_names=["base", "sides"],
                            dimension=3)
    decoder = EventDecoder()
    for e in result_events(tet, 16):
        decoder.feed(e)
    mesh = decoder.finish().mesh
    assert isinstance(mesh, meshd.TetMesh), type(mesh)
    assert mesh.points.shape == (4, 3) and mesh.points.dtype == np.float64, mesh.points
    assert mesh.tetrahedra.shape == (1, 4) and mesh.tetrahedra.dtype == np.int32, mesh.tetrahedra
    assert mesh.boundary_faces.shape == (4, 3) and len(mesh.boundary_groups["sides"]) == 3
    assert abs(mesh.volumes()[0] - 8 / 3) < 1e-12, mesh.volumes()
    assert abs(mesh.tetrahedron_quality()[0] - 1) < 1e-12, mesh.tetrahedron_quality()
    flipped = meshd.TetMesh.from_proto(tet)
    flipped.tetrahedra[:] = [[1, 0, 2, 3]]
    assert flipped.volumes()[0] < 0 and flipped.tetrahedron_quality()[0] < 0
    # Out of order, a wrong checksum, no done: each is BadResult.
    events = result_events(data, 10)
    swapped, corrupt = events[1:2] + events[:1] + events[2:], [e.__deepcopy__() for e in events]
    corrupt[0].result_chunk.data = b"\0" * len(corrupt[0].result_chunk.data)
    for name, stream in (("swapped", swapped), ("corrupt", corrupt), ("no done", events[:-1])):
        decoder = EventDecoder()
        try:
            for e in stream:
                decoder.feed(e)
            decoder.finish()
            raise AssertionError(f"{name} stream accepted")
        except meshd.BadResult as e:
            assert e.code == grpc.StatusCode.DATA_LOSS, e


def test_volume_builders(examples):
    """Solids and volume requests: the cube minus a ball equals its example file; extrusions,
    revolutions, transforms and a graded size about a solid; plane-only arguments refused."""
    part = meshd.box((-1, -1, -1), (1, 1, 1), name="box") - meshd.sphere(0.5, name="ball")
    same(meshd.request(part, h0=0.1),
         read_example(examples, "volumes/box_minus_sphere.textproto"), "box minus sphere")
    gear = meshd.extrude(meshd.circle(1) - meshd.circle(0.3), height=0.4).rotate(90, axis=(1, 0, 0))
    req = meshd.request(gear | meshd.revolve(meshd.circle(0.2, center=(1, 0))), h0=0.05,
                        size=[meshd.graded(meshd.sphere(0.2), 1, 3, 3), 2], auto_features=False)
    assert not req.HasField("geometry") and req.volume.auto_features is False
    shapes = req.volume.geometry.union.shapes
    assert shapes[0].rotate.shape.extrusion.height == 0.4, shapes[0]
    assert shapes[0].rotate.axis.x == 1 and shapes[1].revolution.profile.circle.radius == 0.2
    terms = req.volume.size.terms
    assert terms[0].distance.shape.sphere.radius == 0.2 and terms[1].uniform.value == 2, terms
    for bad in ({"bbox": ((0, 0), (1, 1))}, {"auto_corners": True}, {"gradation": 0.1},
                {"size": meshd.feature(3, 1, 2)}):
        try:
            meshd.request(part, h0=0.1, **bad)
            raise AssertionError(f"{bad} accepted with a solid")
        except (ValueError, TypeError):
            pass
    try:
        meshd.request(meshd.circle(1), h0=0.1, auto_features=True)
        raise AssertionError("auto_features accepted with a plane shape")
    except ValueError:
        pass
    try:
        meshd.request(meshd.circle(1), h0=0.1, size=meshd.graded(meshd.sphere(0.2), 1, 3, 3))
        raise AssertionError("a volume's size term accepted with a plane shape")
    except TypeError as e:
        assert "volume" in str(e), e
    try:
        meshd.sphere(1) | meshd.circle(1)
        raise AssertionError("a solid united with a plane shape")
    except TypeError:
        pass


def test_volume_requests(examples):
    """A ball and a cube minus a ball, field by field, as the server reads them; meshd.union,
    intersection and difference take solids as the operators do."""
    ball = meshd.request(meshd.sphere(1, name="sphere"), h0=0.087)
    expected = read_example(examples, "volumes/ball.textproto")
    assert not ball.HasField("geometry") and ball.HasField("volume"), ball
    assert ball.h0 == expected.h0 and ball.volume.geometry.name == "sphere", ball
    sphere = ball.volume.geometry.sphere
    assert sphere.radius == expected.volume.geometry.sphere.radius == 1, ball
    assert (sphere.center.x, sphere.center.y, sphere.center.z) == (0, 0, 0), ball
    assert not ball.volume.HasField("size") and not ball.volume.HasField("auto_features"), ball
    assert not ball.HasField("options") and not ball.HasField("params"), ball

    part = meshd.box((-1, -1, -1), (1, 1, 1)).named("box") - meshd.sphere(0.5).named("ball")
    req = meshd.request(part, h0=0.1, size=meshd.graded(meshd.sphere(0.5), h_min=1, slope=2,
                                                        h_max=3),
                        auto_features=True, backend="cpu", dptol=0.002)
    d = req.volume.geometry.difference
    assert d.base.name == "box" and d.base.box.max.z == 1 and d.base.box.min.x == -1, d
    assert len(d.subtract) == 1 and d.subtract[0].name == "ball", d
    assert d.subtract[0].sphere.radius == 0.5, d
    (term,) = req.volume.size.terms
    assert term.distance.shape.sphere.radius == 0.5 and term.distance.slope == 2, term
    assert (term.distance.h_min, term.distance.h_max) == (1, 3), term
    assert req.volume.auto_features and req.params.dptol == 0.002, req
    assert req.options.backend == request_pb2.JobOptions.BACKEND_CPU, req
    assert not req.HasField("size"), "a volume's size went into the plane's field"

    a, b, c = meshd.sphere(1), meshd.box((0, 0, 0), (1, 1, 1)), meshd.torus(2, 0.5)
    assert meshd.union(a, b, c).proto == (a | b | c).proto
    assert meshd.intersection(a, b).proto == (a & b).proto
    assert meshd.difference(a, b, c).proto == (a - b - c).proto
    assert isinstance(meshd.union(a, b), meshd.Solid) and len((a | b | c).proto.union.shapes) == 3
    moved = meshd.cone(1, 0, 2, base_center=(0, 0, -1)).rotate(90, axis=(0, 1, 0),
                                                                center=(1, 0, 0))
    r = moved.scale(2, center=(0, 0, 1)).translate((1, 2, 3)).proto.translate
    assert (r.offset.x, r.offset.y, r.offset.z) == (1, 2, 3), r
    assert r.shape.scale.factor == 2 and r.shape.scale.center.z == 1, r
    rot = r.shape.scale.shape.rotate
    assert rot.angle_deg == 90 and rot.axis.y == 1 and rot.center.x == 1, rot
    assert rot.shape.cone.top_radius == 0 and rot.shape.cone.base_center.z == -1, rot
    h = meshd.half_space((0, 0, 2), 1).proto.half_space
    assert h.normal.z == 2 and h.offset == 1, h
    cyl = meshd.cylinder(0.5, 2, base_center=(1, 1, 0)).proto.cylinder
    assert (cyl.radius, cyl.height, cyl.base_center.x) == (0.5, 2, 1), cyl
    assert meshd.torus(2, 0.5, center=(0, 0, 1)).proto.torus.center.z == 1


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--examples", required=True)
    args = parser.parse_args()
    return run_checks([test_installed_package, test_examples_from_builders, test_operators,
                       test_primitives_and_transforms, test_request_fields, test_size_grid,
                       test_error_parsing, test_volume_builders, test_volume_requests,
                       test_event_decoder], args.examples)


if __name__ == "__main__":
    sys.exit(main())
