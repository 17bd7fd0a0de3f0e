"""tests/python/test_volumes.py — polyhedral volume meshes from Python: the operators equal the C++
library's (written by `polydec operators` / `polydec dec` on ../shared/data/volume) to 1e-12
relative; S symmetric, S 1 = 0, linear precision at the interior vertices of jittered meshes,
S = D G = -d0^T star1 d0, d1 d0 = d2 d1 = 0 exactly; the Neumann spectrum's 0 with a constant
vector; heat geodesics equal to the CLI's; Poisson exact on linear functions; the Hodge
decomposition's harmonic dimension (0 on a cube, 1 on a solid torus); meshes from arrays, files
and errors naming the file, cell or face; the refinement a VolumeMesh keeps gives bitwise the
results of a fresh one and is not pickled."""

import pickle
import re

import numpy as np
import pytest
import scipy.sparse

import polydec
from conftest import relative_difference, shared_mesh
from test_operators import mmread

METHODS = ["ours", "polylaplace", "diamond"]


def generated():
    return {
        "hex": polydec.hex_grid_volume(3, 3, 3, jitter=0.3, seed=7),
        "tet": polydec.tet_grid_volume(2, 2, 2, jitter=0.2),
        "pyramids": polydec.pyramid_grid_volume(2, 2, 2, jitter=0.2),
        "truncated": polydec.truncated_octahedra_volume(2, jitter=0.2),
        "cuboctahedra": polydec.cuboctahedra_volume(2, jitter=0.2),
        "torus": polydec.hex_torus_volume(8, 2),
        "ball": polydec.hex_ball_volume(3),
    }


MESHES = generated()


def norm(A):
    return scipy.sparse.linalg.norm(A) if scipy.sparse.issparse(A) else np.linalg.norm(A)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("name", list(MESHES))
def test_stiffness_and_mass_properties(name, method):
    mesh = MESHES[name]
    d = polydec.volume_operators(mesh, method)
    S, M, ml = d["S"], d["M"], d["M_lumped"]
    n = mesh.n_vertices
    assert scipy.sparse.isspmatrix_csc(S) and S.shape == (n, n) and S.dtype == np.float64
    assert norm(S - S.T) <= 1e-14 * norm(S)
    assert np.abs(S @ np.ones(n)).max() <= 1e-13 * abs(S).max()
    x = np.random.default_rng(1).standard_normal(n)
    assert x @ (S @ x) < 0
    assert norm(M - M.T) <= 1e-14 * norm(M)
    assert np.allclose(np.asarray(M.sum(axis=1)).ravel(), ml, rtol=1e-12, atol=0)
    if name != "ball":  # planar boundary faces: the sub-tetrahedra fill exactly the mesh's volume
        assert abs(ml.sum() - mesh.volume) <= 1e-12 * mesh.volume
    assert relative_difference(d["D"] @ d["G"], S) <= 1e-12
    assert relative_difference(polydec.volume_stiffness(mesh, method), S) == 0
    Sl, Ml = polydec.volume_laplacian(mesh, method)
    assert np.array_equal(Ml.diagonal(), ml) and relative_difference(Sl, S) == 0


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("name", ["hex", "tet", "pyramids", "truncated", "cuboctahedra"])
def test_linear_precision_at_interior_vertices(name, method):
    mesh = MESHES[name]
    S = polydec.volume_stiffness(mesh, method)
    X = mesh.positions
    inner = ~mesh.boundary_vertices
    assert inner.sum() > 0
    for u in (X[:, 0], X @ np.array([0.3, -1.2, 0.7]) + 2.0):
        r = S @ u
        assert np.abs(r[inner]).max() <= 1e-11 * abs(S).max() * np.abs(u).max(), (name, method)


def test_jittered_hex_grid_is_not_a_hex_grid():
    """The linear-precision test above is not trivial: the interior vertices moved."""
    a, b = polydec.hex_grid_volume(3, 3, 3), MESHES["hex"]
    moved = np.linalg.norm(a.positions - b.positions, axis=1)
    assert np.all(moved[b.boundary_vertices] == 0) and np.all(moved[~b.boundary_vertices] > 0)


VOLUME_FILES = ["cube_hexahedron_2.ovm", "cube_pyramids_2.ovm", "cube_truncated_2.ovm", "cube_tetrahedron_1.ovm",
                "noisycube.ovm"]


@pytest.mark.parametrize("cell_point", ["squared-volume", "polylaplace"])
@pytest.mark.parametrize("name", VOLUME_FILES)
def test_operators_equal_the_cpp_library(name, cell_point, cli, tmp_path):
    path = shared_mesh("volume/" + name)
    cli("operators", path, "--cell-point", cell_point, "--out", tmp_path)
    mesh = polydec.read_volume_mesh(path)
    d = polydec.volume_operators(mesh, "ours" if cell_point == "squared-volume" else "polylaplace")
    for key in ["S", "M", "M_lumped"]:
        A = d[key] if key != "M_lumped" else scipy.sparse.diags(d[key])
        B = mmread(tmp_path / f"{key}.mtx")
        assert A.shape == B.shape
        assert relative_difference(A, B) <= 1e-12, key


@pytest.mark.parametrize("name", ["cube_hexahedron_1.ovm", "cube_pyramids_2.ovm", "cube_tetrahedron_1.ovm"])
def test_dec_equals_the_cpp_library(name, cli, tmp_path):
    path = shared_mesh("volume/" + name)
    cli("dec", path, "--out", tmp_path)
    mesh = polydec.read_volume_mesh(path)
    d = polydec.volume_dec(mesh)
    assert d["max_degree"] == polydec.volume_dec_max_degree(mesh)
    for k in range(d["max_degree"] + 1):
        keys = [f"P{k}", f"star{k}"] + ([f"d{k}"] if k < d["max_degree"] else [])
        for key in keys:
            assert relative_difference(d[key], mmread(tmp_path / f"{key}.mtx")) <= 1e-12, key
    for key, file in [("pairs", "edges.txt"), ("triples", "triangles.txt"), ("quads", "tetrahedra.txt")]:
        if key in d:
            assert np.array_equal(d[key], np.loadtxt(tmp_path / file, dtype=np.int64, ndmin=2)), key


@pytest.mark.parametrize("name", ["hex", "tet", "pyramids", "cuboctahedra", "torus"])
def test_dec_exact_sequence_and_factorization(name):
    mesh = MESHES[name]
    d = polydec.volume_dec(mesh)
    assert d["max_degree"] == 3
    for a, b in [("d1", "d0"), ("d2", "d1")]:
        prod = (d[a] @ d[b]).tocoo()
        assert prod.shape == (d[a].shape[0], d[b].shape[1])
        assert np.all(prod.data == 0), f"{a} {b}"
    assert np.all(np.isin(d["d0"].data, [-1.0, 1.0]))
    S, M = polydec.volume_stiffness(mesh), polydec.volume_mass(mesh)
    assert relative_difference(-d["d0"].T @ d["star1"] @ d["d0"], S) <= 1e-12
    assert relative_difference(d["star0"], M) <= 1e-12
    assert d["pairs"].shape == (d["d0"].shape[0], 2) and d["quads"].shape == (d["d2"].shape[0], 4)


def test_dec_degree_limited_by_cell_size():
    mesh = polydec.truncated_octahedra_volume(1)
    k = polydec.volume_dec_max_degree(mesh)
    assert k < 3
    d = polydec.volume_dec(mesh)
    assert d["max_degree"] == k and f"d{k}" not in d and f"star{k}" in d
    with pytest.raises(ValueError, match="cell"):
        polydec.volume_dec(mesh, max_degree=3)


def test_dec_on_the_mesh_complex_has_every_degree_and_definite_stars():
    mesh = polydec.truncated_octahedra_volume(1)          # 24-vertex cells
    d = polydec.volume_dec(mesh, complex="mesh")
    assert d["complex"] == "mesh" and d["max_degree"] == 3
    d0, d1, d2 = d["d"]
    assert d0.shape[0] == d["edges"].shape[0] and d1.shape[0] == len(d["faces"]) and d2.shape[0] == len(d["cells"])
    assert abs(d1 @ d0).max() == 0 and abs(d2 @ d1).max() == 0
    S = polydec.volume_stiffness(mesh)
    assert abs(S + d0.T @ d["star"][1] @ d0).max() <= 1e-12 * abs(S).max()
    for k in (1, 2, 3):
        assert np.linalg.eigvalsh(d["star"][k].toarray()).min() > 0
    assert d["star"][3].nnz == d2.shape[0]                 # diagonal
    for c, halffaces in enumerate(d["cells"]):
        for h in halffaces:
            assert d2[c, h // 2] == (1 if h % 2 == 0 else -1)


@pytest.mark.parametrize("method", METHODS)
def test_neumann_spectrum_starts_at_zero_with_a_constant(method):
    mesh = MESHES["hex"]
    evals, evecs = polydec.volume_spectrum(mesh, 6, method)
    assert np.all(np.diff(evals) >= 0)
    assert abs(evals[0]) <= 1e-8 * evals[1]
    v = evecs[:, 0]
    assert np.abs(v - v.mean()).max() <= 1e-8 * abs(v.mean())
    S, M = polydec.volume_laplacian(mesh, method)
    assert np.abs(evecs.T @ M @ evecs - np.eye(6)).max() <= 1e-8
    assert np.abs(S @ evecs + M @ evecs * evals).max() <= 1e-7 * abs(S).max()


def test_dirichlet_spectrum_of_the_ball_converges_to_the_analytic_one():
    """hex_ball_volume(n): the first Dirichlet eigenvalue of the unit ball, pi^2, within 5% at n = 8
    (measured 3.7%, Galerkin mass), the error at least halved from n = 4 to n = 8 (measured 0.147
    -> 0.037); the boundary rows of the eigenvectors are zero."""
    lam, l, n = polydec.ball_eigenvalues(4, "dirichlet")
    assert abs(lam[0] - np.pi**2) <= 1e-12 * np.pi**2 and l[0] == 0 and n[0] == 1
    err = []
    for size in (4, 8):
        mesh = polydec.hex_ball_volume(size)
        evals, evecs = polydec.volume_spectrum(mesh, 2, boundary="dirichlet", mass="galerkin")
        assert np.all(evecs[mesh.boundary_vertices] == 0)
        err.append(abs(evals[0] - lam[0]) / lam[0])
    assert err[1] <= 0.05 and err[1] <= 0.5 * err[0]
    lam_n = polydec.ball_eigenvalues(4)[0]
    assert lam_n[0] == 0 and np.all(lam_n[1:4] == lam_n[1])  # l = 1 three times


def parse_vtk_point_data(path, name):
    text = open(path).read()
    n = int(re.search(r"POINT_DATA (\d+)", text).group(1))
    tail = text.split(f"SCALARS {name} double 1", 1)[1].split("LOOKUP_TABLE default", 1)[1]
    return np.array(tail.split()[:n], dtype=np.float64)


@pytest.mark.parametrize("method", ["ours", "diamond"])
@pytest.mark.parametrize("name", ["cube_pyramids_2.ovm", "cube_truncated_2.ovm"])
def test_heat_geodesics_equal_the_cli(name, method, cli, tmp_path):
    path = shared_mesh("volume/" + name)
    cli("geodesics", path, "--source", 0, "--source", 5, "--laplacian", method, "--out", tmp_path / "d.vtk")
    expected = parse_vtk_point_data(tmp_path / "d.vtk", "distance")
    h = polydec.VolumeHeatGeodesics(polydec.read_volume_mesh(path), method)
    d = h.distance([0, 5])
    assert d.shape == expected.shape and min(d[0], d[5]) == 0
    assert np.abs(d - expected).max() <= 1e-12 * np.abs(expected).max()


def test_heat_geodesics_approximate_euclidean_distance():
    mesh = polydec.hex_grid_volume(8, 8, 8, jitter=0.2)
    d = polydec.VolumeHeatGeodesics(mesh).distance(0)
    e = np.linalg.norm(mesh.positions - mesh.positions[0], axis=1)
    assert np.sqrt(np.mean((d - e) ** 2)) <= 0.05 * e.max()
    with pytest.raises(ValueError, match="source vertex"):
        polydec.VolumeHeatGeodesics(mesh).distance(mesh.n_vertices)


@pytest.mark.parametrize("method", METHODS)
def test_poisson_is_exact_on_linear_functions(method):
    mesh = polydec.hex_grid_volume(3, 3, 3, jitter=0.3)
    r = polydec.volume_poisson(mesh, lambda X: X @ np.array([1.0, -2.0, 0.5]) + 1, np.zeros(mesh.n_vertices), method)
    scale = np.abs(r["exact"]).max()
    assert np.abs(r["solution"] - r["exact"]).max() <= 1e-10 * scale
    assert r["n_boundary"] == int(mesh.boundary_vertices.sum())


def test_franke_poisson_error_decreases():
    e = [polydec.volume_franke_poisson(polydec.hex_grid_volume(n, n, n))["l2_error"] for n in (4, 8)]
    assert e[1] < 0.5 * e[0]


@pytest.mark.parametrize("name,betti,complex", [("hex", 0, "complete"), ("torus", 1, "complete"),
                                                ("hex", 0, "mesh"), ("torus", 1, "mesh")])
def test_hodge_decomposition(name, betti, complex):
    mesh = polydec.hex_grid_volume(2, 2, 2, jitter=0.2) if name == "hex" else polydec.hex_torus_volume(6, 1)
    h = polydec.VolumeHodgeDecomposer(mesh, complex=complex)
    if complex == "mesh":
        assert np.array_equal(h.pairs, polydec.volume_dec(mesh, 1, complex="mesh")["edges"])
    assert h.harmonic_basis.shape == (h.pairs.shape[0], betti)
    omega = np.random.default_rng(3).standard_normal(h.pairs.shape[0])
    p = h.decompose(omega)
    scale = np.abs(omega).max()
    assert np.abs(p.exact + p.coexact + p.harmonic - omega).max() <= 1e-10 * scale
    assert np.abs(h.d0 @ p.potential - p.exact).max() <= 1e-10 * scale
    S1 = h.star1
    norm2 = p.norm**2
    for a, b in [(p.exact, p.coexact), (p.exact, p.harmonic), (p.coexact, p.harmonic)]:
        assert abs(a @ S1 @ b) <= 1e-9 * norm2
    if betti:
        assert p.norm_harmonic > 1e-3 * p.norm


# ------------------------------------------------------------------------------- meshes and files

def test_mesh_from_cells_and_soup_equal_the_generated_one():
    mesh = polydec.pyramid_grid_volume(2, 1, 1, jitter=0.1)
    cells = [mesh.cell_faces(c) for c in range(mesh.n_cells)]
    a = polydec.VolumeMesh(mesh.positions, cells)
    b = polydec.VolumeMesh.from_soup(mesh.positions, mesh.faces, mesh.cells)
    S = polydec.volume_stiffness(mesh)
    for m in (a, b):
        assert (m.n_vertices, m.n_edges, m.n_faces, m.n_cells) == (mesh.n_vertices, mesh.n_edges, mesh.n_faces,
                                                                   mesh.n_cells)
        assert relative_difference(polydec.volume_stiffness(m), S) <= 1e-14
    assert np.array_equal(b.cells[0], mesh.cells[0])


def test_one_cube_from_arrays():
    V = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]
    quads = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    mesh = polydec.VolumeMesh(V, [quads])
    assert (mesh.n_vertices, mesh.n_edges, mesh.n_faces, mesh.n_cells) == (8, 12, 6, 1)
    assert mesh.volume == pytest.approx(1.0, rel=1e-14)
    inward = polydec.VolumeMesh(V, [[q[::-1] for q in quads]])  # flipped once to outward
    assert inward.volume == pytest.approx(1.0, rel=1e-14)
    assert np.all(mesh.boundary_vertices) and np.all((mesh.face_cells == -1).sum(axis=1) == 1)
    Vs, Fs = mesh.boundary_surface()
    assert polydec.lumped_mass(Vs, Fs).diagonal().sum() == pytest.approx(6.0, rel=1e-14)
    cube = np.array(quads)[None]  # (1, 6, 4) array form
    assert polydec.VolumeMesh(V, cube).n_faces == 6


def test_mesh_errors_name_the_cell():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    tets = [[[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]]
    assert polydec.VolumeMesh(V, tets).n_cells == 1
    with pytest.raises(polydec.InvalidMeshError, match=r"cell 0, face 2 refers to vertex 7") as e:
        polydec.VolumeMesh(V, [[[0, 2, 1], [0, 1, 3], [1, 2, 7], [0, 3, 2]]])
    assert e.value.element == "cell" and e.value.index == 0
    with pytest.raises(polydec.InvalidMeshError, match=r"cell 1, face 0 has 2 vertices"):
        polydec.VolumeMesh(V, tets + [[[0, 1], [1, 2, 3]]])
    with pytest.raises(polydec.InvalidMeshError, match="cell 0"):  # an open cell
        polydec.VolumeMesh(V, [tets[0][:3]])
    with pytest.raises(polydec.InvalidMeshError, match="half-face 9"):
        polydec.VolumeMesh.from_soup(V, [f for f in tets[0]], [[0, 2, 4, 9]])
    with pytest.raises(TypeError, match="VolumeMesh"):
        polydec.volume_stiffness(V)
    with pytest.raises(ValueError, match="ours, polylaplace, diamond"):
        polydec.volume_stiffness(MESHES["tet"], "cotan")


def test_meshes_without_cells_raise_instead_of_crashing():
    for mesh in (polydec.VolumeMesh(np.zeros((0, 3)), []), polydec.VolumeMesh(np.zeros((3, 3)), [])):
        assert mesh.n_cells == 0 and polydec.volume_stiffness(mesh).nnz == 0
        with pytest.raises(polydec.InvalidMeshError, match="no cells"):
            polydec.VolumeHodgeDecomposer(mesh)
        with pytest.raises(ValueError, match="k = 1"):
            polydec.volume_spectrum(mesh, 1)
        with pytest.raises(ValueError, match="boundary"):
            polydec.volume_franke_poisson(mesh)


@pytest.mark.parametrize("ext", ["ovm", "vtk", "mesh"])
def test_write_and_read_back(ext, tmp_path):
    mesh = polydec.tet_grid_volume(2, 2, 1, jitter=0.3) if ext == "mesh" else MESHES["truncated"]
    path = tmp_path / f"m.{ext}"
    mesh.write(path)
    back = polydec.read_volume_mesh(path)
    assert np.array_equal(back.positions, mesh.positions)
    assert relative_difference(polydec.volume_stiffness(back), polydec.volume_stiffness(mesh)) <= 1e-14


def test_write_point_data(tmp_path):
    mesh = MESHES["pyramids"]
    x = mesh.positions[:, 0] * 0.1
    polydec.write_volume_mesh(tmp_path / "p.vtk", mesh, {"x": x})
    assert np.array_equal(parse_vtk_point_data(tmp_path / "p.vtk", "x"), x)
    assert polydec.read_volume_mesh(tmp_path / "p.vtk").n_cells == mesh.n_cells
    with pytest.raises(polydec.FileError):
        polydec.write_volume_mesh(tmp_path / "p.ovm", mesh, {"x": x})


def test_broken_files_raise_file_errors_naming_the_file(tmp_path):
    good = tmp_path / "good.ovm"
    MESHES["hex"].write(good)
    lines = good.read_text().splitlines()
    broken = tmp_path / "broken.ovm"
    broken.write_text("\n".join(lines[: len(lines) // 2]) + "\n")
    with pytest.raises(polydec.FileError, match=r"broken\.ovm") as e:
        polydec.read_volume_mesh(broken)
    assert isinstance(e.value, OSError) and isinstance(e.value, ValueError)
    assert e.value.filename == str(broken)
    bad = tmp_path / "bad.ovm"
    bad.write_text(good.read_text().replace("\n0 0 0\n", "\n0 zero 0\n", 1))
    with pytest.raises(polydec.FileError, match=r"bad\.ovm:\d+") as e:
        polydec.read_volume_mesh(bad)
    assert e.value.line > 0
    with pytest.raises(polydec.FileError, match="missing.vtk"):
        polydec.read_volume_mesh(tmp_path / "missing.vtk")


def test_generators_and_jitter():
    assert polydec.hex_grid_volume(2, 3, 4).n_cells == 24
    assert polydec.tet_grid_volume(1, 1, 1).n_cells == 6
    assert polydec.pyramid_grid_volume(1, 1, 1).n_cells == 6
    assert polydec.truncated_octahedra_volume(2).n_cells == 8 + 27
    assert polydec.cuboctahedra_volume(2).n_cells == 72
    t = polydec.hex_torus_volume(8, 2)
    assert t.n_vertices - t.n_edges + t.n_faces - t.n_cells == 0
    for m in (polydec.hex_grid_volume(2, 2, 2), polydec.truncated_octahedra_volume(2)):
        assert m.volume == pytest.approx(1.0, rel=1e-12)
    a = polydec.hex_grid_volume(3, 3, 3)
    j1, j2 = polydec.jitter_interior(a, 0.3, seed=7), MESHES["hex"]
    assert np.array_equal(j1.positions, j2.positions)
    assert j1.volume == pytest.approx(1.0, rel=1e-12)
    assert np.allclose(np.linalg.norm(polydec.hex_ball_volume(3).positions[polydec.hex_ball_volume(3).boundary_vertices],
                                      axis=1), 1.0, rtol=1e-14)
    with pytest.raises(ValueError, match="at least 1"):
        polydec.hex_grid_volume(0, 1, 1)
    with pytest.raises(ValueError, match="jitter"):
        polydec.jitter_interior(a, -1.0)


def test_volume_operators_threads_give_identical_results():
    # Threads only split meshes of at least 2 x 2048 cells; the results are bitwise those of one thread.
    mesh = polydec.hex_grid_volume(16, 16, 17, jitter=0.2, seed=3)
    one = polydec.volume_operators(mesh, "ours", {"S", "M", "M_lumped", "G"}, threads=1)
    for threads in (2, 0):
        mesh.clear_refinements()  # the refinement too is built on `threads` threads
        many = polydec.volume_operators(mesh, "ours", {"S", "M", "M_lumped", "G"}, threads=threads)
        for part in ("S", "M", "G"):
            assert (one[part] != many[part]).nnz == 0
            assert np.array_equal(one[part].indices, many[part].indices)
        assert np.array_equal(one["M_lumped"], many["M_lumped"])
    with pytest.raises(ValueError):
        polydec.volume_operators(mesh, "ours", {"S"}, threads=-1)


def bitwise_equal(A, B):
    """Same sparsity pattern and the same doubles, bit for bit (or equal dense arrays)."""
    if not scipy.sparse.issparse(A):
        return np.array_equal(np.asarray(A), np.asarray(B))
    return (A.shape == B.shape and np.array_equal(A.indptr, B.indptr) and np.array_equal(A.indices, B.indices)
            and np.array_equal(A.data.view(np.int64), B.data.view(np.int64)))


@pytest.mark.parametrize("method", METHODS)
def test_kept_refinement_gives_bitwise_the_results_of_a_fresh_one(method):
    # Polyhedra with non-planar faces, so that face and cell points matter; a pickled copy holds no
    # refinement, so its first call is the uncached route (a fresh refinement per call).
    mesh = polydec.truncated_octahedra_volume(2, jitter=0.2, seed=5)
    parts = {"S", "M", "M_lumped", "G", "D"}
    assert mesh.n_cached_refinements == 0
    first = polydec.volume_operators(mesh, method, parts)
    assert mesh.n_cached_refinements == 1
    again = polydec.volume_operators(mesh, method, parts)
    S, M = polydec.volume_laplacian(mesh, method, mass="galerkin")
    assert mesh.n_cached_refinements == 1
    fresh = pickle.loads(pickle.dumps(mesh))
    assert fresh.n_cached_refinements == 0
    reference = polydec.volume_operators(fresh, method, parts)
    for part in ("S", "M", "M_lumped", "G", "D"):
        assert bitwise_equal(first[part], reference[part]), part
        assert bitwise_equal(again[part], reference[part]), part
    assert bitwise_equal(S, reference["S"]) and bitwise_equal(M, reference["M"])
    # The solvers on the kept refinement equal theirs on fresh meshes.
    fresh = lambda: pickle.loads(pickle.dumps(mesh))  # noqa: E731
    d = polydec.VolumeHeatGeodesics(mesh, method).distance([0, 5])
    assert bitwise_equal(d, polydec.VolumeHeatGeodesics(fresh(), method).distance([0, 5]))
    evals, evecs = polydec.volume_spectrum(mesh, 4, method)
    evals_f, evecs_f = polydec.volume_spectrum(fresh(), 4, method)
    assert bitwise_equal(evals, evals_f) and bitwise_equal(evecs, evecs_f)
    linear = lambda X: X[:, 0] - 2 * X[:, 2]  # noqa: E731
    zero = lambda X: np.zeros(len(X))  # noqa: E731
    p = polydec.volume_poisson(mesh, linear, zero, method)
    assert bitwise_equal(p["solution"], polydec.volume_poisson(fresh(), linear, zero, method)["solution"])
    f = polydec.volume_franke_poisson(mesh, method)
    assert bitwise_equal(f["solution"], polydec.volume_franke_poisson(fresh(), method)["solution"])
    assert mesh.n_cached_refinements == 1


def test_kept_refinements_one_per_cell_point_rule_and_not_pickled():
    mesh = polydec.cuboctahedra_volume(2, jitter=0.2)
    size = len(pickle.dumps(mesh))
    polydec.volume_stiffness(mesh, "ours")
    polydec.volume_stiffness(mesh, "diamond")  # the same squared-volume refinement
    assert mesh.n_cached_refinements == 1
    polydec.volume_mass(mesh, "polylaplace")
    assert mesh.n_cached_refinements == 2
    D = polydec.volume_dec(mesh, cell_point="polylaplace")
    assert mesh.n_cached_refinements == 2
    reference = polydec.volume_dec(pickle.loads(pickle.dumps(mesh)), cell_point="polylaplace")
    assert D["max_degree"] == reference["max_degree"] >= 1
    for key in reference:
        if scipy.sparse.issparse(reference[key]):
            assert bitwise_equal(D[key], reference[key]), key
    for complex in ("mesh", "complete"):
        h = polydec.VolumeHodgeDecomposer(mesh, cell_point="polylaplace", complex=complex)
        h_fresh = polydec.VolumeHodgeDecomposer(pickle.loads(pickle.dumps(mesh)), cell_point="polylaplace",
                                                complex=complex)
        assert bitwise_equal(h.star1, h_fresh.star1) and bitwise_equal(h.d0, h_fresh.d0), complex
        omega = np.sin(np.arange(h.pairs.shape[0]))
        assert np.array_equal(h.decompose(omega).exact, h_fresh.decompose(omega).exact), complex
    assert mesh.n_cached_refinements == 2
    assert len(pickle.dumps(mesh)) == size  # the refinements stay out of the pickle
    back = pickle.loads(pickle.dumps(mesh))
    assert back.n_cached_refinements == 0
    assert bitwise_equal(polydec.volume_stiffness(back), polydec.volume_stiffness(mesh))
    mesh.clear_refinements()
    assert mesh.n_cached_refinements == 0
    # A cache serves only its own mesh.
    with pytest.raises(ValueError, match="another volume mesh"):
        polydec._polydec.volume_operators(back._m, "ours", {"S"}, 1, mesh._refinements())
