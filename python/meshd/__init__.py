"""meshd: a Python client of the meshd DistMesh service.

    import meshd
    client = meshd.Client("127.0.0.1:50051")
    mesh = client.generate(meshd.request(meshd.circle(1) - meshd.circle(0.3), h0=0.05),
                           progress=True)
    mesh.points, mesh.triangles          # #N by 2 float64, #M by 3 int32
    mesh.to_meshio().write("ring.vtu")
    part = meshd.box((-1, -1, -1), (1, 1, 1)) - meshd.sphere(0.5)
    tets = client.generate(meshd.request(part, h0=0.2))   # a TetMesh: points #N by 3 float64,
    tets.tetrahedra, tets.boundary_faces                 # #M by 4 and #F by 3 int32

Geometry: circle, rectangle, polygon, ellipse, half_plane, distance_grid (a numpy array of
signed distances); | & - and union, intersection, difference; .translate(), .rotate(),
.scale(), .named(). Volumes (tetrahedra, a TetMesh): sphere, box, cylinder, cone, torus,
half_space, extrude(shape, height), revolve(shape), a Solid combined and moved the same way.
Size: uniform, graded (about a Shape, or a Solid for a volume), grid, feature. Requests:
request(). Results: Mesh, TetMesh, Quality, RunStats. Clients: Client and aio.Client. Events:
Queued, Started, Progress, Snapshot, Done. Errors: MeshdError and its subclasses. The meshd.v1
messages and stubs are generated from the repository's proto/ when the package is built.
"""

from meshd import aio
from meshd.client import Client
from meshd.connection import tls_credentials
from meshd.errors import (BadResult, Cancelled, DeadlineExceeded, FailedPrecondition, Internal,
                          InvalidArgument, MeshdError, NotFound, PermissionDenied,
                          ResourceExhausted, Unauthenticated, Unavailable)
from meshd.events import Done, Progress, Queued, Snapshot, Started
from meshd.geometry import (Shape, circle, difference, distance_grid, ellipse, half_plane,
                            intersection, polygon, rectangle, union)
from meshd.job_info import JobInfo
from meshd.mesh import Mesh, Quality, RunStats, TetMesh
from meshd.request import request
from meshd.size_field import feature, graded, grid, uniform
from meshd.solid import (Solid, box, cone, cylinder, extrude, half_space, polyhedron, revolve,
                         sphere, torus)
from meshd.v1 import geometry3d_pb2, geometry_pb2, mesh_pb2, request_pb2, service_pb2

__version__ = "0.1.0"

__all__ = [
    "aio", "Client", "tls_credentials",
    "MeshdError", "InvalidArgument", "NotFound", "Unavailable", "DeadlineExceeded", "Cancelled",
    "ResourceExhausted", "FailedPrecondition", "Unauthenticated", "PermissionDenied", "Internal",
    "BadResult",
    "Queued", "Started", "Progress", "Snapshot", "Done",
    "Shape", "circle", "rectangle", "polygon", "ellipse", "half_plane", "distance_grid", "union",
    "intersection", "difference",
    "Solid", "sphere", "box", "cylinder", "cone", "torus", "half_space", "extrude", "revolve",
    "polyhedron",
    "JobInfo", "Mesh", "TetMesh", "Quality", "RunStats", "request", "uniform", "graded", "grid",
    "feature", "geometry_pb2", "geometry3d_pb2", "mesh_pb2", "request_pb2", "service_pb2",
]
