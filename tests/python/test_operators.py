"""tests/python/test_operators.py — the operators from Python equal the C++ library's (written by
`polydec operators` / `polydec dec` as Matrix Market, 17 digits) on the paper's meshes to 1e-14
relative; sign, null space and the factorizations S = D G = -d0^T star1 d0, d1 d0 = 0; the
Laplacian variants by name."""

import numpy as np
import pytest
import scipy.io
import scipy.sparse

import polydec
from conftest import relative_difference, shared_mesh

PAPER_MESHES = ["quad-sphere.off", "noisy-sphere.off", "L-plane.obj", "tetris.obj", "tetris_2.obj",
                "suzanne-half.obj", "amo_quad.off", "bunny-hexa.off"]


def mmread(path):
    """A Matrix Market "coordinate real general" file as csc_matrix: header by hand, the entries
    by numpy's C parser (scipy.io.mmread, used on the small files, is pure Python and too slow
    for HEX SPHERE's matrices)."""
    with open(path) as f:
        header = f.readline()
        line = f.readline()
        while line.startswith("%"):
            line = f.readline()
        rows, cols, nnz = map(int, line.split())
        body = np.array(f.read().split(), dtype=np.float64)
    assert header.split()[1:4] == ["matrix", "coordinate", "real"] and body.size == 3 * nnz, path
    t = body.reshape(-1, 3)
    A = scipy.sparse.coo_matrix((t[:, 2], (t[:, 0].astype(np.int64) - 1, t[:, 1].astype(np.int64) - 1)),
                                shape=(rows, cols))
    if nnz < 20000:
        assert (A.tocsc() != scipy.sparse.csc_matrix(scipy.io.mmread(str(path)))).nnz == 0, path
    return A.tocsc()


def assert_same(A, path, what):
    B = mmread(path)
    assert scipy.sparse.isspmatrix_csc(A) and A.dtype == np.float64, what
    assert A.shape == B.shape, what
    assert relative_difference(A, B) <= 1e-14, what


@pytest.mark.parametrize("name", PAPER_MESHES)
def test_operators_equal_the_cpp_library(name, cli, tmp_path):
    # Arrays are exact doubles to the library (no coordinate precision travels with V and F), so
    # the CLI reads a 17-digit copy: the file itself would carry the precision its digits resolve,
    # which decides which nearly planar faces count as planar (docs/operators.md).
    path = shared_mesh(name)
    cli("convert", path, tmp_path / "exact.ply")
    cli("operators", tmp_path / "exact.ply", "--out", tmp_path)
    V, F = polydec.read_mesh(path)
    S, M = polydec.laplacian(V, F, mass="galerkin")
    assert_same(S, tmp_path / "S.mtx", "S")
    assert_same(M, tmp_path / "M.mtx", "M")
    assert_same(polydec.stiffness(V, F), tmp_path / "S.mtx", "stiffness")
    assert_same(polydec.mass(V, F), tmp_path / "M.mtx", "mass")
    assert_same(polydec.lumped_mass(V, F), tmp_path / "M_lumped.mtx", "lumped mass")
    assert_same(polydec.laplacian(V, F)[1], tmp_path / "M_lumped.mtx", "laplacian's lumped mass")
    assert_same(polydec.gradient(V, F), tmp_path / "G.mtx", "G")
    assert_same(polydec.divergence(V, F), tmp_path / "D.mtx", "D")
    assert_same(polydec.prolongation(V, F), tmp_path / "P.mtx", "P")


def test_hex_sphere_operators_equal_the_cpp_library(cli, tmp_path):
    """HEX SPHERE (the paper's Tables 2-3): dual of unit-sphere.off, projected, built in C++ by
    `polydec convert` and in Python by dual + project_to_unit_sphere."""
    path = shared_mesh("unit-sphere.off")
    cli("convert", path, tmp_path / "hex.ply", "--dual", "--unit-sphere")
    cli("operators", tmp_path / "hex.ply", "--out", tmp_path)
    V, F = polydec.project_to_unit_sphere(*polydec.dual(*polydec.read_mesh(path)))
    V2, F2 = polydec.read_mesh(tmp_path / "hex.ply")
    assert np.array_equal(V, V2)
    S, M = polydec.laplacian(V, F)
    assert_same(S, tmp_path / "S.mtx", "S")
    assert_same(M, tmp_path / "M_lumped.mtx", "lumped M")


@pytest.mark.parametrize("name", ["L-plane.obj", "tetris.obj", "quad-sphere.off"])
def test_dec_pieces_equal_the_cpp_library(name, cli, tmp_path):
    path = shared_mesh(name)
    cli("dec", path, "--out", tmp_path)
    V, F = polydec.read_mesh(path)
    d = polydec.dec_operators(V, F)
    for key in ["d0", "d1", "star0", "star1", "star2", "P0", "P1", "P2"]:
        assert_same(d[key], tmp_path / f"{key}.mtx", key)
    assert_same(polydec.d0(V, F), tmp_path / "d0.mtx", "d0()")
    assert_same(polydec.d1(V, F), tmp_path / "d1.mtx", "d1()")
    assert_same(polydec.star0(V, F), tmp_path / "star0.mtx", "star0()")
    assert_same(polydec.star1(V, F), tmp_path / "star1.mtx", "star1()")
    assert_same(polydec.star2(V, F), tmp_path / "star2.mtx", "star2()")
    assert_same(polydec.P0(V, F), tmp_path / "P0.mtx", "P0()")
    assert_same(polydec.P1(V, F), tmp_path / "P1.mtx", "P1()")
    assert_same(polydec.P2(V, F), tmp_path / "P2.mtx", "P2()")
    pairs, triples = polydec.cells(V, F)
    assert np.array_equal(pairs, np.loadtxt(tmp_path / "edges.txt", dtype=np.int64, ndmin=2))
    assert np.array_equal(triples, np.loadtxt(tmp_path / "triangles.txt", dtype=np.int64, ndmin=2))


def test_sign_and_null_space_a_user_can_copy():
    # S is negative semi-definite with the constants in its null space; M sums to the area.
    V, F = polydec.hex_sphere(2)
    S, M = polydec.laplacian(V, F)
    ones = np.ones(V.shape[0])
    scale = abs(S).sum(axis=1).max()
    assert np.abs(S @ ones).max() <= 1e-12 * scale            # S 1 = 0
    assert abs(S - S.T).max() <= 1e-14 * scale                 # symmetric
    rng = np.random.default_rng(0)
    x = rng.standard_normal(V.shape[0])
    assert x @ (S @ x) < 0                                     # x^T S x <= 0 (negative semi-definite)
    assert np.all(M.diagonal() > 0)
    assert abs(M.sum() - 4 * np.pi) < 0.02 * 4 * np.pi         # the unit sphere's area, coarsely
    # Linear precision in the plane: S applied to a linear function vanishes at interior vertices.
    Vg, Fg = planar_noise(*polydec.hex_grid(8, 7), 0.2)
    Sg = polydec.stiffness(Vg, Fg)
    u = 2 * Vg[:, 0] - 3 * Vg[:, 1]
    assert np.abs((Sg @ u)[interior_of_unit_square(Vg)]).max() <= 1e-12 * abs(Sg).max()


def interior_of_unit_square(V):
    """Vertices of a mesh of [0,1]^2 off the square's sides."""
    return np.all((V[:, :2] > 1e-12) & (V[:, :2] < 1 - 1e-12), axis=1)


def planar_noise(V, F, amplitude, seed=3):
    """In-plane random moves of the interior vertices of a mesh of [0,1]^2 by up to amplitude
    times the mean vertex spacing; the square's sides stay put (the area stays 1)."""
    rng = np.random.default_rng(seed)
    h = 1.0 / np.sqrt(V.shape[0])
    W = V.copy()
    inside = interior_of_unit_square(V)
    W[inside, :2] += amplitude * h * rng.uniform(-1, 1, size=(inside.sum(), 2))
    return W, F


def test_dec_identities():
    V, F = polydec.add_noise(*polydec.hex_grid(5, 4), 0.1)
    d = polydec.dec_operators(V, F)
    S = polydec.stiffness(V, F)
    scale = abs(S).max()
    assert abs(d["d1"] @ d["d0"]).max() == 0                                      # d1 d0 = 0 exactly
    assert abs(S + d["d0"].T @ d["star1"] @ d["d0"]).max() <= 1e-12 * scale      # S = -d0^T star1 d0
    assert abs(polydec.divergence(V, F) @ polydec.gradient(V, F) - S).max() <= 1e-12 * scale  # S = D G
    assert abs(d["star0"] - polydec.mass(V, F)).max() <= 1e-14 * abs(d["star0"]).max()
    assert np.allclose(d["star0_lumped"], polydec.lumped_mass(V, F).diagonal(), rtol=1e-14, atol=0)
    assert np.allclose(polydec.star0(V, F, lumped=True).diagonal(), d["star0_lumped"], rtol=1e-14, atol=0)
    P = polydec.prolongation(V, F)
    assert np.allclose(P @ np.ones(V.shape[0]), 1, rtol=0, atol=1e-14)            # affine weights
    assert np.array_equal(d["pairs"][d["is_edge"]], polydec.mesh_info(V, F)["edge_list"])


@pytest.mark.parametrize("spec", ["ours", "centroid", "abs-area", "convex", "trace-min", "triangulated-minarea",
                                  "triangulated-maxminangle", "intrinsic-delaunay", "aw11:0.5", "degoes20:1"])
def test_every_variant_by_name(spec):
    V, F = planar_noise(*polydec.hex_grid(4, 4), 0.2)
    S, M = polydec.laplacian(V, F, laplacian=spec)
    n = V.shape[0]
    assert S.shape == (n, n) and M.shape == (n, n)
    scale = abs(S).max()
    assert np.abs(S @ np.ones(n)).max() <= 1e-12 * scale
    assert abs(S - S.T).max() <= 1e-12 * scale
    assert np.linalg.eigvalsh(S.toarray()).max() <= 1e-12 * scale
    # Every method's lumped mass sums to the area of the unit square (planar mesh).
    assert abs(M.sum() - 1) <= 1e-12


def test_variants_differ_and_parameters_matter():
    V, F = planar_noise(*polydec.hex_grid(4, 4), 0.2)
    S0 = polydec.stiffness(V, F)
    assert relative_difference(polydec.stiffness(V, F, laplacian="centroid"), S0) > 1e-6
    assert relative_difference(polydec.stiffness(V, F, laplacian="aw11:0.1"),
                               polydec.stiffness(V, F, laplacian="aw11:2")) > 1e-6
    with pytest.raises(ValueError, match="aw11"):
        polydec.stiffness(V, F, laplacian="aw11")          # missing parameter
    with pytest.raises(ValueError):
        polydec.stiffness(V, F, laplacian="no-such-method")
    with pytest.raises(ValueError, match="no Galerkin mass"):
        polydec.mass(V, F, laplacian="aw11:0.5")
    names = polydec.laplacian_names()
    assert "ours" in names and any(n.startswith("aw11") for n in names)


def test_refined_lives_on_the_refined_mesh():
    V, F = polydec.hex_grid(3, 3)
    S = polydec.stiffness(V, F, laplacian="refined")
    nf = len(F[1]) - 1 if isinstance(F, tuple) else len(F)
    assert S.shape == (V.shape[0] + nf,) * 2


def test_threads_give_identical_results():
    V, F = polydec.add_noise(*polydec.cube_sphere(12), 0.1)
    S1, M1 = polydec.laplacian(V, F, mass="galerkin", threads=1)
    S2, M2 = polydec.laplacian(V, F, mass="galerkin", threads=2)
    assert (S1 != S2).nnz == 0 and (M1 != M2).nnz == 0


def test_gradient_of_a_linear_function_is_constant():
    V, F = planar_noise(*polydec.hex_grid(5, 5), 0.2)
    G = polydec.gradient(V, F)
    g = (G @ (V @ np.array([1.0, -2.0, 0.0]))).reshape(-1, 3)
    assert np.abs(g - [1.0, -2.0, 0.0]).max() <= 1e-12


def test_mesh_complex_bundle_equals_the_command_line_and_holds_its_identities(cli, tmp_path):
    # A generated non-planar hexagon/pentagon mesh with boundary: no shared data needed.
    V, F = polydec.add_noise(*polydec.hex_grid(5, 4), 0.1)
    path = tmp_path / "hexagons.obj"
    polydec.write_mesh(str(path), V, F)
    cli("dec", path, "--complex", "mesh", "--out", tmp_path / "dec")
    V, F = polydec.read_mesh(str(path))
    D = polydec.surface_dec(V, F, complex="mesh")
    assert D["complex"] == "mesh" and len(D["d"]) == 2 and len(D["P"]) == 3 and len(D["star"]) == 3
    for k, name in enumerate(["d0", "d1"]):
        assert_same(D["d"][k], tmp_path / "dec" / f"{name}.mtx", name)
    for k in range(3):
        assert_same(D["P"][k], tmp_path / "dec" / f"P{k}.mtx", f"P{k}")
        assert_same(D["star"][k], tmp_path / "dec" / f"star{k}.mtx", f"star{k}")
    assert np.array_equal(D["edges"], np.loadtxt(tmp_path / "dec" / "edges.txt", dtype=np.int64, ndmin=2))
    with open(tmp_path / "dec" / "faces.txt") as f:
        assert [list(map(int, line.split())) for line in f] == [list(face) for face in D["faces"]]
    d0, d1 = D["d"]
    star0, star1, star2 = D["star"]
    S = polydec.stiffness(V, F)
    assert d0.shape == (D["edges"].shape[0], V.shape[0]) and d1.shape == (len(D["faces"]), d0.shape[0])
    assert abs(d1 @ d0).max() == 0
    assert abs(S + d0.T @ star1 @ d0).max() <= 1e-12 * abs(S).max()
    # Positive definite: the smallest eigenvalues of star1 and star2 are positive.
    assert np.linalg.eigvalsh(star1.toarray()).min() > 0
    assert star2.nnz == star2.shape[0] and star2.diagonal().min() > 0    # diagonal
    # The complete complex through the same function keeps the paper's cells.
    C = polydec.surface_dec(V, F, complex="complete", max_degree=1)
    pairs, _ = polydec.cells(V, F)
    assert np.array_equal(C["pairs"], pairs) and len(C["d"]) == 1
    with pytest.raises(ValueError):
        polydec.surface_dec(V, F, complex="full")
