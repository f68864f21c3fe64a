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


def _write_meshio(mesh, path, file_format):
    """meshio's write, with .msh meaning Gmsh's MSH 4.1 in ASCII (meshio would guess ANSYS)."""
    options = {}
    if file_format is None and str(path).endswith(".msh"):
        file_format, options = "gmsh", {"binary": False}
    mesh.write(path, file_format=file_format, **options)


def _job_fields(done, job_id):
    """The fields a mesh takes from its job's Done event (all empty without one)."""
    return {"quality": Quality.from_proto(done.quality) if done is not None else None,
            "stats": RunStats.from_proto(done.stats) if done is not None else None,
            "job_id": job_id,
            "backend": BACKEND_NAMES.get(done.backend, "") if done is not None else "",
            "device": done.device if done is not None else ""}


def _from_proto(cls, message):
    return cls(**{f.name: getattr(message, f.name) for f in fields(cls)})


@dataclass(frozen=True)
class Quality:
    """Radius ratio 2 r_in / R_circ over the triangles (3 r_in / R_circ over a volume's
    tetrahedra; 1 equilateral, 0 degenerate); histogram[k] counts q in [k/10, (k+1)/10). A
    volume's report has the dihedral angles' range, its volume and how far its surface nodes
    lie from the boundary at most, a plane's the smallest angle."""
    q_min: float
    q_mean: float
    min_angle_deg: float
    histogram: tuple
    min_dihedral_deg: float = 0.0
    max_dihedral_deg: float = 0.0
    volume: float = 0.0
    max_surface_offset: float = 0.0

    @classmethod
    def from_proto(cls, q):
        return cls(q.q_min, q.q_mean, q.min_angle_deg, tuple(q.histogram), q.min_dihedral_deg,
                   q.max_dihedral_deg, q.volume, q.max_surface_offset)


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
            **_job_fields(done, job_id))

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
        triangles' quality as cell data (as meshd's VTU writer has it). The lines come one cell
        block per boundary group. Points get z = 0, which most formats need."""
        points = np.zeros((len(self.points), 3))
        points[:, :2] = self.points
        # Gmsh entities, which meshio's MSH 4.1 writer takes from the nodes: the surface 1 and
        # one curve per boundary group; a node lies on the curve of an edge it starts, else
        # inside the surface. The writer groups the nodes by entity, so a .msh read back has
        # the same nodes and triangles in another order.
        group_tags = self.boundary_tags + DOMAIN_PHYSICAL_TAG + 1
        dim_tags = np.tile([2, DOMAIN_PHYSICAL_TAG], (len(self.points), 1))
        dim_tags[self.boundary_edges[:, 0]] = np.column_stack(
            [np.ones_like(group_tags), group_tags])
        return _meshio_mesh(points, ("triangle", self.triangles, self.triangle_quality()),
                            ("line", self.boundary_edges, self.boundary_tags),
                            self.boundary_names, 2, dim_tags)

    def write(self, path, file_format=None):
        """Writes the mesh with meshio; the format follows the extension (.vtu, .xdmf, ...),
        .msh meaning Gmsh's MSH 4.1 (meshio would guess ANSYS)."""
        _write_meshio(self.to_meshio(), path, file_format)

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
            **_job_fields(done, job_id))

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

    def tetrahedron_quality(self):
        """#M radius ratios 3 r_in / R_circ (1 regular, 0 flat, negative inverted), as the
        server's Quality counts them: q = 6 (6V) |6V| / (2S |C|), S the faces' area and
        C = u^2 (v x w) + v^2 (w x u) + w^2 (u x v) for the edges u, v, w from the first node."""
        p = self.points[self.tetrahedra]
        u, v, w = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]
        vw, wu, uv = np.cross(v, w), np.cross(w, u), np.cross(u, v)
        six_volume = np.einsum("ij,ij->i", u, vw)
        twice_area = (np.linalg.norm(vw, axis=1) + np.linalg.norm(wu, axis=1)
                      + np.linalg.norm(uv, axis=1)
                      + np.linalg.norm(np.cross(v - u, w - u), axis=1))
        circum = ((u * u).sum(1)[:, None] * vw + (v * v).sum(1)[:, None] * wu
                  + (w * w).sum(1)[:, None] * uv)
        with np.errstate(divide="ignore", invalid="ignore"):
            q = (6.0 * six_volume * np.abs(six_volume)
                 / (twice_area * np.linalg.norm(circum, axis=1)))
        return np.nan_to_num(q)

    def to_meshio(self):
        """A meshio.Mesh: tetrahedra and boundary triangles with gmsh:physical /
        gmsh:geometrical tags, gmsh:dim_tags and field_data naming the groups (so .msh keeps
        them), and the tetrahedra's quality as cell data (NaN on the faces), as Mesh.to_meshio
        and meshd's VTU writer have them. The triangles come one cell block per group."""
        # Gmsh entities, as in Mesh.to_meshio: the volume 1 and one surface per boundary group;
        # a node of a boundary face lies on that face's surface, any other inside the volume.
        group_tags = self.boundary_tags + DOMAIN_PHYSICAL_TAG + 1
        dim_tags = np.tile([3, DOMAIN_PHYSICAL_TAG], (len(self.points), 1))
        dim_tags[self.boundary_faces.ravel()] = np.repeat(
            np.column_stack([np.full_like(group_tags, 2), group_tags]), 3, axis=0)
        return _meshio_mesh(self.points, ("tetra", self.tetrahedra, self.tetrahedron_quality()),
                            ("triangle", self.boundary_faces, self.boundary_tags),
                            self.boundary_names, 3, dim_tags)

    def write(self, path, file_format=None):
        """Writes the mesh with meshio, as Mesh.write does (.msh: Gmsh's MSH 4.1)."""
        _write_meshio(self.to_meshio(), path, file_format)

    def __repr__(self):
        q = f", q_min {self.quality.q_min:.3f}" if self.quality else ""
        return (f"meshd.TetMesh({len(self.points)} nodes, {len(self.tetrahedra)} tetrahedra, "
                f"{len(self.boundary_faces)} boundary faces in {len(self.boundary_names)} "
                f"groups{q})")


def _meshio_mesh(points, domain, boundary, names, dim, dim_tags):
    """The meshio.Mesh of to_meshio: domain = (cell type, cells, quality) of dimension dim,
    boundary = (cell type, cells, group of each) of dimension dim - 1. The boundary cells come
    one block per group, since meshio's MSH writer makes each block one Gmsh entity and takes
    its tags from the block's first cell; a block per group keeps every group's physical tag."""
    import meshio  # optional: pip install meshio, Debian python3-meshio

    domain_type, domain_cells, quality = domain
    boundary_type, boundary_cells, boundary_tags = boundary
    blocks = [(domain_type, domain_cells.astype(np.int64))]
    tags = [np.full(len(domain_cells), DOMAIN_PHYSICAL_TAG, dtype=np.int32)]
    qualities = [quality]
    field_data = {DOMAIN_GROUP_NAME: np.array([DOMAIN_PHYSICAL_TAG, dim])}
    for i, name in enumerate(names):
        tag = i + DOMAIN_PHYSICAL_TAG + 1
        field_data[name] = np.array([tag, dim - 1])
        cells = boundary_cells[boundary_tags == i]
        if len(cells):
            blocks.append((boundary_type, cells.astype(np.int64)))
            tags.append(np.full(len(cells), tag, dtype=np.int32))
            qualities.append(np.full(len(cells), np.nan))
    return meshio.Mesh(points, blocks,
                       cell_data={"gmsh:physical": tags, "gmsh:geometrical": tags,
                                  "quality": qualities},
                       point_data={"gmsh:dim_tags": dim_tags}, field_data=field_data)


def mesh_from_proto(data, done=None, job_id=""):
    """A Mesh, or a TetMesh for a volume's result (MeshData.dimension 3)."""
    cls = TetMesh if data.dimension == 3 else Mesh
    return cls.from_proto(data, done, job_id=job_id)
