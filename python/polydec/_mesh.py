"""polydec._mesh — the surface Mesh class: a polygon mesh validated once (the C++ Mesh), with its
virtual refinement built on first use per (virtual-vertex rule, planarity rule) and kept, accepted
by every operator function in place of (V, F). Imported into polydec."""

import numpy as np

from . import _convert, _polydec


class Mesh:
    """A validated polygon mesh (dec/mesh/mesh.h): positions and polygonal faces; immutable.

    Mesh(V, F) validates once (InvalidMeshError, a ValueError, naming the face, vertex or edge);
    read_mesh, the generators and the transformations return a Mesh too. Every operator function
    takes it in place of (V, F) (polydec.stiffness(mesh), ...; the common ones are also methods:
    mesh.stiffness(), ...), without validating again, and the virtual refinement (paper eq. 10:
    the virtual vertices and fan triangles) is built on the first call for a given
    virtual-vertex rule and planarity rule and kept for the next ones.

    Faces are returned in one form everywhere: the flat tuple (indices, offsets) of two int64
    arrays, face f = indices[offsets[f]:offsets[f + 1]] (face_array() and face_list() convert).
    `V, F = mesh` unpacks (positions, faces).

    A mesh read from a file keeps what the file's digits resolve (its coordinate precision,
    docs/operators.md "Planar or not"), so its matrices equal the command line's on that file;
    a mesh built from arrays takes the doubles as exact. planarity=... overrides either.

    >>> mesh = polydec.Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
    >>> mesh.n_vertices, mesh.n_faces, mesh.n_edges
    (4, 1, 4)
    >>> mesh.faces
    (array([0, 1, 2, 3]), array([0, 4]))
    """

    def __init__(self, V, F, planarity=None):
        """From positions V (|V|, 3) (or (|V|, 2): z = 0) and faces F (a list of vertex lists, an
        (|F|, k) integer array or the flat tuple (indices, offsets)). planarity: the mesh's own
        planarity rule (None: the doubles are exact; a tolerance T in (0, 1))."""
        X, idx, off = _convert.mesh(V, F)
        p = _convert.planarity(planarity)
        self._h = _polydec.Mesh.from_arrays(X, idx, off, 0.0, max(p, 0.0))

    @classmethod
    def _wrap(cls, h):
        mesh = cls.__new__(cls)
        mesh._h = h
        return mesh

    @classmethod
    def read(cls, path):
        """read_mesh(path)."""
        from . import read_mesh

        return read_mesh(path)

    # ---------------------------------------------------------------------------------- arrays

    def _arrays(self):
        a = self.__dict__.get("_a")
        if a is None:
            X, idx, off = self._h.arrays
            X = np.ascontiguousarray(X)
            idx, off = np.asarray(idx, dtype=np.int64), np.asarray(off, dtype=np.int64)
            for x in (X, idx, off):
                x.flags.writeable = False
            a = self._a = (X, idx, off)
        return a

    @property
    def positions(self):
        """(|V|, 3) float64, read-only."""
        return self._arrays()[0]

    @property
    def faces(self):
        """The faces as the flat tuple (indices, offsets), two read-only int64 arrays."""
        return self._arrays()[1:]

    def face_array(self):
        """The faces as an (|F|, k) int64 array; ValueError unless every face has k vertices."""
        return _convert.faces_out(*self.faces, "array")

    def face_list(self):
        """The faces as a list of lists of vertex indices."""
        return _convert.faces_out(*self.faces, "list")

    def __iter__(self):
        return iter((self.positions, self.faces))

    def with_positions(self, V):
        """The same faces with new positions (|V|, 3), validated against nothing new (the
        connectivity is shared); refinements are built afresh."""
        return Mesh._wrap(self._h.with_positions(_convert.positions(V)))

    def with_planarity(self, planarity):
        """The same mesh with another planarity rule of its own ("exact": the doubles are exact;
        a tolerance T in (0, 1): faces whose out-of-plane extent is at most T of their size are
        planar, as the command line's --planarity-tolerance T)."""
        p = _convert.planarity(planarity)
        if p < 0:
            return self
        return Mesh._wrap(self._h.with_planarity(p))

    # -------------------------------------------------------------------------------- topology

    n_vertices = property(lambda self: self._h.n_vertices, doc="Number of vertices.")
    n_faces = property(lambda self: self._h.n_faces, doc="Number of faces.")
    n_edges = property(lambda self: self._h.n_edges, doc="Number of edges.")
    n_halfedges = property(lambda self: self._h.n_halfedges, doc="Number of face corners (halfedges).")
    n_components = property(lambda self: self._h.n_components, doc="Number of connected components.")
    n_unreferenced_vertices = property(lambda self: self._h.n_unreferenced_vertices,
                                       doc="Vertices in no face.")
    euler_characteristic = property(lambda self: self._h.euler_characteristic, doc="|V| - |E| + |F|.")
    mean_edge_length = property(lambda self: self._h.mean_edge_length, doc="Mean edge length.")
    bounding_box_diagonal = property(lambda self: self._h.bounding_box_diagonal,
                                     doc="Length of the bounding box's diagonal.")
    coordinate_noise = property(lambda self: self._h.coordinate_noise,
                                doc="What the coordinates resolve, relative to the mesh's size (0: exact doubles).")

    @property
    def edges(self):
        """(|E|, 2) int32, rows (i, j) with i < j in lexicographic order (the edge numbering)."""
        return self._h.edges

    @property
    def boundary_vertices(self):
        """(|V|,) bool: the vertices on a boundary loop.

        >>> int(np.count_nonzero(polydec.quad_grid(3, 3).boundary_vertices))
        12
        """
        return self._h.boundary_vertices

    @property
    def boundary_loops(self):
        """The boundary loops, each an int32 array of vertex indices in the order of the loop's
        halfedges (the mesh's interior on the left).

        >>> [len(loop) for loop in polydec.quad_grid(3, 2).boundary_loops]
        [10]
        """
        return self._h.boundary_loops

    # ------------------------------------------------------------------------------ refinement

    def refinement(self, virtual_vertex="squared-area", planarity=None, threads=1):
        """The virtual refinement for a virtual-vertex rule and planarity rule, built on the first
        call and cached -> dict: weights (one per corner, aligned with faces[0]; each face's sum
        to 1), virtual_points (|F|, 3), degenerate_fan_triangles, inverted_fan_triangles,
        faces_affected.

        >>> mesh = polydec.quad_grid(2, 2)
        >>> r = mesh.refinement()
        >>> r["virtual_points"][0].tolist(), mesh.n_cached_refinements
        ([0.25, 0.25, 0.0], 1)
        """
        return self._h.refine(str(virtual_vertex), _convert.planarity(planarity), _convert.threads(threads))

    @property
    def n_cached_refinements(self):
        """How many refinements the mesh holds (one per virtual-vertex rule and planarity rule used)."""
        return self._h.n_cached_refinements

    # ------------------------------------------------------------------------------- operators

    def stiffness(self, laplacian="ours", threads=1, planarity=None):
        """polydec.stiffness(self, ...)."""
        from . import stiffness

        return stiffness(self, laplacian=laplacian, threads=threads, planarity=planarity)

    def mass(self, laplacian="ours", threads=1, planarity=None):
        """polydec.mass(self, ...)."""
        from . import mass

        return mass(self, laplacian=laplacian, threads=threads, planarity=planarity)

    def lumped_mass(self, laplacian="ours", threads=1, planarity=None):
        """polydec.lumped_mass(self, ...)."""
        from . import lumped_mass

        return lumped_mass(self, laplacian=laplacian, threads=threads, planarity=planarity)

    def laplacian(self, laplacian="ours", mass="lumped", threads=1, planarity=None):
        """polydec.laplacian(self, ...) -> (S, M)."""
        from . import laplacian as f

        return f(self, laplacian=laplacian, mass=mass, threads=threads, planarity=planarity)

    def gradient(self, laplacian="ours", planarity=None):
        """polydec.gradient(self, ...)."""
        from . import gradient

        return gradient(self, laplacian=laplacian, planarity=planarity)

    def divergence(self, laplacian="ours", planarity=None):
        """polydec.divergence(self, ...)."""
        from . import divergence

        return divergence(self, laplacian=laplacian, planarity=planarity)

    def prolongation(self, virtual_vertex="squared-area", planarity=None):
        """polydec.prolongation(self, ...)."""
        from . import prolongation

        return prolongation(self, virtual_vertex=virtual_vertex, planarity=planarity)

    def info(self):
        """polydec.mesh_info(self)."""
        from . import mesh_info

        return mesh_info(self)

    # ------------------------------------------------------------------------------- the rest

    def __reduce__(self):
        X, idx, off = self._arrays()
        return _unpickle, (np.array(X), np.array(idx), np.array(off), self._h.coordinate_noise,
                           self._h.planarity_tolerance)

    def __repr__(self):
        return f"Mesh({self.n_vertices} vertices, {self.n_faces} faces, {self.n_edges} edges)"


def _unpickle(X, idx, off, noise, planarity_tolerance):
    return Mesh._wrap(_polydec.Mesh.from_arrays(np.ascontiguousarray(X, dtype=np.float64),
                                                np.ascontiguousarray(idx, dtype=np.int32),
                                                np.ascontiguousarray(off, dtype=np.int32), float(noise),
                                                float(planarity_tolerance)))


def handle(V, F, planarity=None):
    """The extension's mesh for a Mesh (F None) or for (V, F) (validated now)."""
    if isinstance(V, Mesh):
        if F is not None:
            raise TypeError("with a polydec.Mesh, pass the other arguments by keyword (got a second positional "
                            f"argument {type(F).__name__})")
        return V._h
    if F is None:
        raise TypeError(f"faces are needed with positions (or pass a polydec.Mesh), got {type(V).__name__} alone")
    return Mesh(V, F)._h


def shift(V, F, x):
    """(V, F, x) of a call f(mesh, x) or f(V, F, x): with a Mesh first and x not given, the
    second positional argument is x."""
    if isinstance(V, Mesh) and F is not None and x is None:
        return V, None, F
    return V, F, x
