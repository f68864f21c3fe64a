"""A finished mesh as numpy arrays, with the statistics of the job that made it.

Arrays, as in meshd.v1.MeshData (integer indices, counter-clockwise triangles):
    points          #N by 2 float64, in the request's length unit
    triangles       #M by 3 int32, node indices, counter-clockwise
    boundary_edges  #E by 2 int32, node indices, the domain on each edge's left
    boundary_tags   #E int32, each edge's group: an index into boundary_names
    boundary_names  the group names (the request's shape names, or "circle1", ...)

Physical groups, as meshd's own MSH and VTU writers number them: "domain" is 1 (the triangles,
dimension 2) and boundary group i is i + 2 (dimension 1). A volume's result is a TetMesh.
"""

from dataclasses import dataclass, fields

import numpy as np

from meshd.request import BACKEND_NAMES

DOMAIN_PHYSICAL_TAG = 1
DOMAIN_GROUP_NAME = "domain"


def _from_proto(cls, message):
    return cls(**{f.name: getattr(message, f.name) for f in fields(cls)})


@dataclass(frozen=True)
class Quality:
    """Radius ratio 2 r_in / R_circ over the triangles (3 r_in / R_circ over a volume's
    tetrahedra; 1 equilateral, 0 degenerate); histogram[k] counts q in [k/10, (k+1)/10). A
    volume's report has the dihedral angles' range and its volume, a plane's the smallest
    angle."""
    q_min: float
    q_mean: float
    min_angle_deg: float
    histogram: tuple
    min_dihedral_deg: float = 0.0
    max_dihedral_deg: float = 0.0
    volume: float = 0.0

    @classmethod
    def from_proto(cls, q):
        return cls(q.q_min, q.q_mean, q.min_angle_deg, tuple(q.histogram), q.min_dihedral_deg,
                   q.max_dihedral_deg, q.volume)


@dataclass(frozen=True)
class RunStats:
    """How the job ran (meshd.v1.RunStats); times in seconds."""
    iterations: int
    converged: bool
    levels: int
    retriangulations: int
    full_triangulations: int
    flips: int
    repair_fallbacks: int
    density_removed: int
    cleanup_removed: int
    t_triangulation: float
    t_forces: float
    t_cleanup: float
    t_mesh: float
    queue_wait_s: float
    fold_refills: int
    fixed_nodes: int = 0
    sliver_moves: int = 0
    t_slivers: float = 0.0

    @classmethod
    def from_proto(cls, stats):
        return _from_proto(cls, stats)


@dataclass(frozen=True, eq=False)
class Mesh:
    """A job's mesh: the arrays of the module's docstring, the job's quality and run statistics
    (None for a mesh built from MeshData alone), and where it ran."""
    points: np.ndarray
    triangles: np.ndarray
    boundary_edges: np.ndarray
    boundary_tags: np.ndarray
    boundary_names: list
    quality: Quality = None
    stats: RunStats = None
    job_id: str = ""
    backend: str = ""
    device: str = ""

    @classmethod
    def from_proto(cls, data, done=None, job_id=""):
        """A Mesh from a meshd.v1.MeshData and, when given, the job's Done event."""
        return cls(
            points=np.array(data.points, dtype=np.float64).reshape(-1, 2),
            triangles=np.array(data.triangles, dtype=np.int32).reshape(-1, 3),
            boundary_edges=np.array(data.boundary_edges, dtype=np.int32).reshape(-1, 2),
            boundary_tags=np.array(data.boundary_tags, dtype=np.int32),
            boundary_names=list(data.boundary_names),
            quality=Quality.from_proto(done.quality) if done is not None else None,
            stats=RunStats.from_proto(done.stats) if done is not None else None,
            job_id=job_id,
            backend=BACKEND_NAMES.get(done.backend, "") if done is not None else "",
            device=done.device if done is not None else "")

    @property
    def boundary_groups(self):
        """{name: #k by 2 edges} for every boundary group."""
        return {name: self.boundary_edges[self.boundary_tags == i]
                for i, name in enumerate(self.boundary_names)}

    def areas(self):
        """#M signed triangle areas (positive: counter-clockwise)."""
        p = self.points[self.triangles]
        e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        return 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])

    def triangle_quality(self):
        """#M radius ratios 2 r_in / R_circ (1 equilateral, 0 degenerate)."""
        p = self.points[self.triangles]
        a = np.linalg.norm(p[:, 1] - p[:, 2], axis=1)
        b = np.linalg.norm(p[:, 2] - p[:, 0], axis=1)
        c = np.linalg.norm(p[:, 0] - p[:, 1], axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            q = (b + c - a) * (c + a - b) * (a + b - c) / (a * b * c)
        return np.nan_to_num(q)

    def to_meshio(self):
        """A meshio.Mesh: triangles and boundary lines, with gmsh:physical / gmsh:geometrical
        tags, gmsh:dim_tags and field_data naming the groups (so .msh keeps them), and the
        triangles' quality as cell data (as meshd's VTU writer has it). Points get z = 0, which
        most formats need."""
        import meshio  # optional: pip install meshio, Debian python3-meshio

        points = np.zeros((len(self.points), 3))
        points[:, :2] = self.points
        group_tags = self.boundary_tags + DOMAIN_PHYSICAL_TAG + 1
        domain_tags = np.full(len(self.triangles), DOMAIN_PHYSICAL_TAG, dtype=np.int32)
        # Gmsh entities, which meshio's MSH 4.1 writer takes from the nodes: the surface 1 and
        # one curve per boundary group; a node lies on the curve of an edge it starts, else
        # inside the surface. The writer groups the nodes by entity, so a .msh read back has
        # the same nodes and triangles in another order.
        dim_tags = np.tile([2, DOMAIN_PHYSICAL_TAG], (len(self.points), 1))
        dim_tags[self.boundary_edges[:, 0]] = np.column_stack(
            [np.ones_like(group_tags), group_tags])
        field_data = {DOMAIN_GROUP_NAME: np.array([DOMAIN_PHYSICAL_TAG, 2])}
        for i, name in enumerate(self.boundary_names):
            field_data[name] = np.array([i + DOMAIN_PHYSICAL_TAG + 1, 1])
        return meshio.Mesh(
            points,
            [("triangle", self.triangles.astype(np.int64)),
             ("line", self.boundary_edges.astype(np.int64))],
            cell_data={"gmsh:physical": [domain_tags, group_tags],
                       "gmsh:geometrical": [domain_tags, group_tags],
                       "quality": [self.triangle_quality(),
                                   np.full(len(self.boundary_edges), np.nan)]},
            point_data={"gmsh:dim_tags": dim_tags},
            field_data=field_data)

    def write(self, path, file_format=None):
        """Writes the mesh with meshio; the format follows the extension (.vtu, .xdmf, ...),
        .msh meaning Gmsh's MSH 4.1 (meshio would guess ANSYS)."""
        options = {}
        if file_format is None and str(path).endswith(".msh"):
            file_format, options = "gmsh", {"binary": False}
        self.to_meshio().write(path, file_format=file_format, **options)

    def __repr__(self):
        q = f", q_min {self.quality.q_min:.3f}" if self.quality else ""
        return (f"meshd.Mesh({len(self.points)} nodes, {len(self.triangles)} triangles, "
                f"{len(self.boundary_edges)} boundary edges in {len(self.boundary_names)} "
                f"groups{q})")


@dataclass(frozen=True, eq=False)
class TetMesh:
    """A volume job's mesh (MeshData of dimension 3):
        points          #N by 3 float64, in the request's length unit
        tetrahedra      #M by 4 int32, positively oriented (a, b, c counter-clockwise from d)
        boundary_faces  #F by 3 int32, counter-clockwise seen from outside
        boundary_tags   #F int32, each face's group: an index into boundary_names
        boundary_names  the group names (the request's solid names, or "sphere1", ...)
    with the job's quality and run statistics (None for a mesh built from MeshData alone).
    Physical groups as meshd's writers number them: "domain" 1 (the tetrahedra, dimension 3),
    boundary group i is i + 2 (dimension 2)."""
    points: np.ndarray
    tetrahedra: np.ndarray
    boundary_faces: np.ndarray
    boundary_tags: np.ndarray
    boundary_names: list
    quality: Quality = None
    stats: RunStats = None
    job_id: str = ""
    backend: str = ""
    device: str = ""

    @classmethod
    def from_proto(cls, data, done=None, job_id=""):
        """A TetMesh from a meshd.v1.MeshData of dimension 3 and, when given, its Done event."""
        return cls(
            points=np.array(data.points, dtype=np.float64).reshape(-1, 3),
            tetrahedra=np.array(data.tetrahedra, dtype=np.int32).reshape(-1, 4),
            boundary_faces=np.array(data.boundary_faces, dtype=np.int32).reshape(-1, 3),
            boundary_tags=np.array(data.boundary_tags, dtype=np.int32),
            boundary_names=list(data.boundary_names),
            quality=Quality.from_proto(done.quality) if done is not None else None,
            stats=RunStats.from_proto(done.stats) if done is not None else None,
            job_id=job_id,
            backend=BACKEND_NAMES.get(done.backend, "") if done is not None else "",
            device=done.device if done is not None else "")

    @property
    def boundary_groups(self):
        """{name: #k by 3 faces} for every boundary group."""
        return {name: self.boundary_faces[self.boundary_tags == i]
                for i, name in enumerate(self.boundary_names)}

    def volumes(self):
        """#M signed tetrahedron volumes (positive: positively oriented)."""
        p = self.points[self.tetrahedra]
        return np.einsum("ij,ij->i", p[:, 1] - p[:, 0],
                         np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0])) / 6.0

    def to_meshio(self):
        """A meshio.Mesh: tetrahedra and boundary triangles with gmsh:physical /
        gmsh:geometrical tags and field_data naming the groups (so .msh keeps them)."""
        import meshio  # optional: pip install meshio, Debian python3-meshio

        group_tags = self.boundary_tags + DOMAIN_PHYSICAL_TAG + 1
        domain_tags = np.full(len(self.tetrahedra), DOMAIN_PHYSICAL_TAG, dtype=np.int32)
        dim_tags = np.tile([3, DOMAIN_PHYSICAL_TAG], (len(self.points), 1))
        dim_tags[self.boundary_faces[:, 0]] = np.column_stack(
            [np.full_like(group_tags, 2), group_tags])
        field_data = {DOMAIN_GROUP_NAME: np.array([DOMAIN_PHYSICAL_TAG, 3])}
        for i, name in enumerate(self.boundary_names):
            field_data[name] = np.array([i + DOMAIN_PHYSICAL_TAG + 1, 2])
        return meshio.Mesh(
            self.points,
            [("tetra", self.tetrahedra.astype(np.int64)),
             ("triangle", self.boundary_faces.astype(np.int64))],
            cell_data={"gmsh:physical": [domain_tags, group_tags],
                       "gmsh:geometrical": [domain_tags, group_tags]},
            point_data={"gmsh:dim_tags": dim_tags},
            field_data=field_data)

    def write(self, path, file_format=None):
        """Writes the mesh with meshio, as Mesh.write does."""
        options = {}
        if file_format is None and str(path).endswith(".msh"):
            file_format, options = "gmsh", {"binary": False}
        self.to_meshio().write(path, file_format=file_format, **options)

    def __repr__(self):
        q = f", q_min {self.quality.q_min:.3f}" if self.quality else ""
        return (f"meshd.TetMesh({len(self.points)} nodes, {len(self.tetrahedra)} tetrahedra, "
                f"{len(self.boundary_faces)} boundary faces in {len(self.boundary_names)} "
                f"groups{q})")


def mesh_from_proto(data, done=None, job_id=""):
    """A Mesh, or a TetMesh for a volume's result (MeshData.dimension 3)."""
    cls = TetMesh if data.dimension == 3 else Mesh
    return cls.from_proto(data, done, job_id=job_id)
