"""meshd.request(): a meshd.v1.MeshRequest from Python values, so that nobody writes textproto.

    req = meshd.request(meshd.circle(1) - meshd.circle(0.3), h0=0.05)
    req = meshd.request(domain, h0=0.02, size=meshd.graded(hole, 1, 4, 2),
                        backend="cpu", snapshot_every=10, dptol=0.0005)
    req = meshd.request(meshd.box((0, 0, 0), (2, 1, 1)) - meshd.sphere(0.4, (1, 0.5, 0.5)),
                        h0=0.1)                        # a volume: tetrahedra
"""

from meshd.geometry import as_shape_proto
from meshd.size_field import size_field, size_field3
from meshd.solid import Solid, as_solid_proto
from meshd.v1 import geometry3d_pb2, geometry_pb2, request_pb2

BACKENDS = {"auto": request_pb2.JobOptions.BACKEND_AUTO,
            "gpu": request_pb2.JobOptions.BACKEND_GPU,
            "cpu": request_pb2.JobOptions.BACKEND_CPU}
BACKEND_NAMES = {value: name for name, value in BACKENDS.items()}

# DistMeshParams' fields, taken from the message so that a new one needs no change here.
PARAMS = tuple(f.name for f in request_pb2.DistMeshParams.DESCRIPTOR.fields)


def request(geometry, h0, size=None, *, gradation=None, bbox=None, fixed_points=(),
            auto_corners=None, auto_features=None, seed=0, backend="auto", priority=0,
            snapshot_every=0, snapshot_max_nodes=0, timeout_s=0.0, label="", **params):
    """A MeshRequest. The server checks every value and names the field it refuses.

    geometry      a Shape (meshd.circle(...) and friends) or a meshd.v1.Shape: triangles; or a
                  Solid (meshd.sphere(...), meshd.extrude(...), ...) or a meshd.v1.Shape3: a
                  volume, meshed with tetrahedra (on the server's CPU engine)
    h0            edge length where h(p) = 1, in length units, > 0
    size          size field: meshd.uniform(v), meshd.graded(...), meshd.grid(...), a list of
                  them, or a number
    gradation     the edge length may grow by at most this much per length unit, (0, 10]
    bbox          ((x0, y0), (x1, y1)), box of the initial points; needed for unbounded trees
    fixed_points  #F by 2, nodes kept exactly
    auto_corners  polygon and rectangle corners and boundary crossings become fixed (default on)
    auto_features a volume's corners and sharp edges become fixed (default on)
    seed          seed of the initial points' rejection
    backend       "auto", "gpu" or "cpu"
    priority      -10..10, higher first
    snapshot_every   stream a snapshot every k iterations (0: none); for a live plot
    snapshot_max_nodes  snapshots only while the mesh has at most this many nodes
    timeout_s     Submit only: seconds the job may take, queue included (0: no limit)
    label         free text shown by jobs()
    **params      DistMeshParams: dptol, ttol, fscale, deltat, geps, density_control_interval,
                  max_iterations, cleanup, momentum, multilevel
    """
    unknown = sorted(set(params) - set(PARAMS))
    if unknown:
        raise TypeError(f"meshd.request: unknown parameter(s) {', '.join(unknown)}; "
                        f"DistMesh's are {', '.join(PARAMS)}")
    if backend not in BACKENDS:
        raise ValueError(f"backend: one of {', '.join(BACKENDS)}, not {backend!r}")

    req = request_pb2.MeshRequest(h0=float(h0), seed=int(seed))
    if isinstance(geometry, (Solid, geometry3d_pb2.Shape3)):
        plane_only = {"gradation": gradation, "bbox": bbox, "auto_corners": auto_corners,
                      "fixed_points": list(fixed_points) or None}
        given = [name for name, value in plane_only.items() if value is not None]
        if given:
            raise ValueError(f"{', '.join(given)}: plane requests only, not with a Solid")
        req.volume.geometry.CopyFrom(as_solid_proto(geometry))
        if size is not None:
            req.volume.size.CopyFrom(size_field3(size))
        if auto_features is not None:
            req.volume.auto_features = bool(auto_features)
        size = gradation = None
    else:
        if auto_features is not None:
            raise ValueError("auto_features: volume requests only (use auto_corners)")
        req.geometry.CopyFrom(as_shape_proto(geometry))
    if size is not None:
        req.size.CopyFrom(size_field(size))
    if gradation is not None:
        req.size.gradation = float(gradation)
    if bbox is not None:
        (x0, y0), (x1, y1) = bbox
        req.bbox.min.CopyFrom(geometry_pb2.Vec2(x=float(x0), y=float(y0)))
        req.bbox.max.CopyFrom(geometry_pb2.Vec2(x=float(x1), y=float(y1)))
    for x, y in fixed_points:
        req.fixed_points.append(geometry_pb2.Vec2(x=float(x), y=float(y)))
    if auto_corners is not None:
        req.auto_corners = bool(auto_corners)
    for name, value in params.items():
        setattr(req.params, name, value)

    # Only values that differ from the defaults, so that an all-default request carries no
    # options message at all, like one parsed from text that does not mention it.
    options = {"backend": BACKENDS[backend], "priority": int(priority),
               "snapshot_every": int(snapshot_every),
               "snapshot_max_nodes": int(snapshot_max_nodes), "timeout_s": float(timeout_s),
               "label": label}
    for name, value in options.items():
        if value:
            setattr(req.options, name, value)
    return req
