"""polydec._convert — the input forms the package accepts, converted exactly to what the C++ core
takes: positions as a C-contiguous (|V|, 3) float64 array, faces as flat int32 (indices, offsets).
Nothing is truncated or rounded silently: a conversion that would change a value raises."""

import numbers

import numpy as np

from . import _polydec

_INT32_MAX = np.iinfo(np.int32).max


def positions(V):
    """(|V|, 3) float64 C-contiguous copy-or-view of V; (|V|, 2) gets z = 0.

    Integer and float16/32 positions are converted exactly; a value that float64 cannot hold
    exactly (huge integers, long double) raises ValueError; complex, bool, strings raise TypeError.
    """
    a = np.asarray(V)
    if a.dtype.kind not in "iuf":
        raise TypeError(f"positions must be real numbers, got an array of dtype {a.dtype}")
    if a.ndim != 2 or a.shape[1] not in (2, 3):
        raise ValueError(f"positions must have shape (|V|, 3) (or (|V|, 2) for z = 0), got {a.shape}")
    if a.dtype != np.float64:
        b = a.astype(np.float64)
        if a.dtype.kind in "iu":
            exact = a.size == 0 or int(np.abs(a.astype(object)).max()) <= 2**53
        else:
            exact = np.array_equal(b.astype(a.dtype), a, equal_nan=True)
        if not exact:
            bad = int(np.argwhere(b.astype(a.dtype) != a)[0][0]) if a.dtype.kind == "f" else _first_big_int(a)
            raise ValueError(
                f"positions of dtype {a.dtype} are not exactly representable in float64 (vertex {bad}); "
                "convert them explicitly if rounding is intended"
            )
        a = b
    if a.shape[1] == 2:
        a = np.hstack([a, np.zeros((a.shape[0], 1))])
    return np.ascontiguousarray(a, dtype=np.float64)


def _first_big_int(a):
    big = np.abs(a.astype(object)) > 2**53
    return int(np.argwhere(big)[0][0])


def _integers(a, what):
    a = np.asarray(a)
    if a.size == 0:
        return np.zeros(0, dtype=np.int64)
    if a.dtype.kind not in "iu":
        raise TypeError(f"{what} must be integers, got dtype {a.dtype}")
    return a


def _is_flat(faces):
    return (
        isinstance(faces, tuple)
        and len(faces) == 2
        and all(isinstance(x, np.ndarray) and x.ndim == 1 for x in faces)
    )


def _mesh_error(element, index, message):
    err = _polydec.InvalidMeshError(message)
    err.element = element
    err.index = int(index)
    return err


def lists(F, bound, element="face", item="vertex"):
    """Flat int32 (indices, offsets) of a list of index lists F (faces of vertices, cells of
    half-faces), each index checked against [0, bound).

    Accepted forms: a sequence of lists (each a sequence of indices; lengths may differ), an
    (|F|, k) integer array, or the flat form: a tuple of two 1-D integer numpy arrays
    (indices, offsets) with offsets[0] = 0, offsets[-1] = len(indices), list f =
    indices[offsets[f]:offsets[f+1]]. Any integer dtype. Raises InvalidMeshError (a ValueError)
    naming the `element` for an index outside [0, bound).
    """
    if _is_flat(F):
        idx = _integers(F[0], f"{element} indices")
        off = _integers(F[1], f"{element} offsets")
        if off.size == 0 or off[0] != 0 or off[-1] != idx.size:
            raise ValueError(f"flat {element}s: offsets must start at 0 and end at len(indices)")
        steps = np.diff(off.astype(np.int64))
        if np.any(steps < 0):
            f = int(np.argmax(steps < 0))
            raise _mesh_error(element, f, f"{element} {f} has negative size (offsets decrease)")
    elif isinstance(F, np.ndarray):
        if F.ndim != 2:
            raise ValueError(f"a {element} array must have shape (n, k), got {F.shape}; use a list of lists or "
                             "(indices, offsets) for mixed sizes")
        idx = _integers(F, f"{element}s").reshape(-1)
        off = np.arange(F.shape[0] + 1, dtype=np.int64) * F.shape[1]
    else:
        _refuse_blocks(F, element)
        try:
            F = list(F)
            sizes = [len(f) for f in F]
        except TypeError:
            raise TypeError(f"{element}s must be a list of lists, an (n, k) integer array or (indices, offsets)") from None
        flat = [v for f in F for v in f]
        if not all(isinstance(v, (numbers.Integral, np.integer)) and not isinstance(v, bool) for v in flat):
            raise TypeError(f"{element}s must hold integer {item} indices")
        if any(abs(int(v)) > 2**62 for v in flat):
            raise ValueError(f"{item} index too large")
        idx = np.array(flat, dtype=np.int64)
        off = np.concatenate([[0], np.cumsum(sizes, dtype=np.int64)])
    if off.size - 1 > _INT32_MAX or idx.size > _INT32_MAX:
        raise ValueError(f"too many {element}s for polydec (32-bit indices)")
    if idx.size:
        bad = (idx < 0) | (idx >= bound)
        if np.any(bad):
            pos = int(np.argmax(bad))
            f = int(np.searchsorted(off, pos, side="right") - 1)
            raise _mesh_error(element, f, f"{element} {f} refers to {item} {int(idx[pos])}, outside [0, {bound})")
    return np.ascontiguousarray(idx, dtype=np.int32), np.ascontiguousarray(off, dtype=np.int32)


def _refuse_blocks(F, element):
    """ValueError for meshio cells (CellBlocks, or their .data arrays in a list) given as faces:
    blocks of different cell types are not one list of faces."""
    if hasattr(F, "type") and hasattr(F, "data"):
        F = [F]
    if not isinstance(F, (list, tuple)) or not F:  # (a generator's first face must not be consumed)
        return
    first = F[0]
    if hasattr(first, "type") and hasattr(first, "data"):
        raise ValueError(f"{element}s given as meshio CellBlocks: build the mesh with polydec.from_meshio(m) "
                         "(it concatenates the blocks in order and skips lower-dimensional ones)")
    if isinstance(first, np.ndarray) and first.ndim == 2:
        raise ValueError(f"{element}s given as a list of 2-D arrays (cell blocks?): concatenate them into one "
                         "list of faces, or use polydec.from_meshio(m) for a meshio mesh")


def faces(F, n_vertices):
    """Flat int32 (indices, offsets) of the faces F, checked against n_vertices (lists() with
    element "face", item "vertex": a sequence of faces, an (|F|, k) array or the flat tuple)."""
    return lists(F, n_vertices)


def mesh(V, F):
    """(positions, indices, offsets) for the C++ core."""
    X = positions(V)
    idx, off = faces(F, X.shape[0])
    return X, idx, off


def faces_out(indices, offsets, form):
    """The faces of a returned mesh: form "auto" (an (|F|, k) int64 array when every face has k
    vertices, else the flat tuple), "array", "flat" or "list"."""
    idx = np.asarray(indices, dtype=np.int64)
    off = np.asarray(offsets, dtype=np.int64)
    sizes = np.diff(off)
    uniform = sizes.size > 0 and np.all(sizes == sizes[0])
    if form == "flat" or (form == "auto" and not uniform):
        return idx, off
    if form in ("auto", "array"):
        if not uniform:
            raise ValueError("face_array() needs faces of one size; use the flat faces or face_list()")
        return idx.reshape(-1, int(sizes[0]))
    if form == "list":
        return [idx[off[f]:off[f + 1]].tolist() for f in range(sizes.size)]
    raise ValueError(f"faces must be 'auto', 'array', 'flat' or 'list', got {form!r}")


def lumped_flag(mass):
    """True for mass="lumped", False for "galerkin" (or "unlumped", the command line's word)."""
    if mass == "lumped":
        return True
    if mass in ("galerkin", "unlumped"):
        return False
    raise ValueError(f"mass must be 'lumped' or 'galerkin', got {mass!r}")


def heat_distance(solver, n_vertices, s, return_diagnostics):
    """A heat-geodesics solver's distances from the sources s, and its diagnostics dict with
    return_diagnostics (HeatGeodesics and VolumeHeatGeodesics)."""
    s = sources(s, n_vertices)
    return solver.distance_with_diagnostics(s) if return_diagnostics else solver.distance(s)


def heat_distances(solver, n_vertices, sources_, block, out):
    """A heat-geodesics solver's distances from each source, (n_vertices, k): a new array, or
    written into `out`, a writeable float64 array of that shape with contiguous columns
    (Fortran order, or a column slice of such an array), which is returned."""
    s = sources(sources_, n_vertices)
    block = size(block, "block", 1)
    if out is None:
        return solver.distances(s, block)
    if not isinstance(out, np.ndarray) or out.dtype != np.float64 or out.shape != (n_vertices, len(s)):
        raise ValueError(f"out must be a float64 array of shape ({n_vertices}, {len(s)}), got "
                         f"{getattr(out, 'dtype', type(out).__name__)} {getattr(out, 'shape', '')}")
    if not out.flags.writeable or (out.size > 0 and out.strides[0] != out.itemsize):
        raise ValueError("out must be writeable with contiguous columns (Fortran order)")
    solver.distances_into(s, out, block)
    return out


def sources(s, n_vertices):
    """A non-empty list of vertex indices in [0, n_vertices)."""
    a = np.atleast_1d(np.asarray(s))
    if a.size == 0:
        raise ValueError("at least one source vertex is needed")
    if a.dtype.kind not in "iu" or a.ndim != 1:
        raise TypeError("sources must be a vertex index or a 1-D sequence of vertex indices")
    bad = (a < 0) | (a >= n_vertices)
    if np.any(bad):
        v = int(a[int(np.argmax(bad))])
        raise ValueError(f"source vertex {v} outside [0, {n_vertices})")
    return [int(v) for v in a]


def size(n, what, minimum=0):
    """n as an int when it is an integer (any integer type) of at least `minimum`; ValueError for
    a fractional, non-numeric or too small value (quad_grid(2.7, 2) must not silently build 2)."""
    if isinstance(n, bool) or not isinstance(n, (numbers.Integral, np.integer)):
        raise ValueError(f"{what} must be an integer, got {n!r}")
    if int(n) < minimum:
        raise ValueError(f"{what} must be at least {minimum}, got {int(n)}")
    return int(n)


def threads(t):
    """A thread count: an integer >= 0, 0 meaning all hardware threads."""
    return size(t, "threads (0: all hardware threads)")


def positive(x, what):
    """x as a float when it is finite and positive, else ValueError."""
    try:
        v = float(x)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a positive number, got {x!r}") from None
    if not (np.isfinite(v) and v > 0):
        raise ValueError(f"{what} must be positive and finite, got {x!r}")
    return v


def planarity(p):
    """The planarity rule as the extension takes it: None -> -1 (the mesh's coordinate precision:
    a read file's digits, the doubles themselves for arrays), "exact" -> 0 (the doubles taken as
    exact even for a read mesh), a number T in (0, 1) -> T (faces whose out-of-plane extent is at
    most T of their size count as planar, the command line's --planarity-tolerance T)."""
    if p is None:
        return -1.0
    if isinstance(p, str):
        if p == "exact":
            return 0.0
        raise ValueError(f"planarity must be None, 'exact' or a tolerance in (0, 1), got {p!r}")
    v = positive(p, "planarity tolerance")
    if v >= 1:
        raise ValueError(f"planarity tolerance must be below 1, got {p!r}")
    return v


def existing_file(path):
    """os.fspath(path), after checking that the file exists: MeshFileNotFoundError (a FileError and
    a FileNotFoundError) otherwise."""
    import errno
    import os

    p = os.fspath(path)
    if not os.path.exists(p):
        raise MeshFileNotFoundError(errno.ENOENT, "no such file", p)
    return p


class MeshFileNotFoundError(_polydec.FileError, FileNotFoundError):
    """A mesh file that does not exist: both polydec.FileError and FileNotFoundError (errno
    ENOENT, filename the path; str() "PATH: no such file" as FileError's messages)."""

    def __init__(self, errno_, reason, filename):
        super().__init__(errno_, reason, filename)
        self.line, self.byte_offset, self.reason = 0, -1, reason

    def __str__(self):
        return f"{self.filename}: {self.reason}"
