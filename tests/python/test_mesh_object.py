"""tests/python/test_mesh_object.py — polydec.Mesh: validated once and accepted by every operator
function with results identical to the (V, F) route, refinements cached per (rule, planarity),
one face type everywhere, boundary vertices and loops, pickling (keeping the coordinate
precision), and the planarity rule: Python and the command line give the same matrices on the
same file."""

import pickle

import numpy as np
import pytest

import polydec
from conftest import relative_difference, shared_mesh


def same_sparse(A, B):
    return A.shape == B.shape and (A != B).nnz == 0


def test_mesh_equals_free_functions_and_caches_one_refinement_per_rule():
    V, F = polydec.hex_grid(7, 6)
    V = V + 0.01 * np.sin(7 * V[:, [1, 2, 0]])  # non-planar hexagons
    mesh = polydec.Mesh(V, F)
    assert mesh.n_cached_refinements == 0
    S = polydec.stiffness(mesh)
    assert mesh.n_cached_refinements == 1
    assert same_sparse(S, polydec.stiffness(V, F))
    assert same_sparse(S, mesh.stiffness())
    S2, M2 = mesh.laplacian(mass="galerkin")
    assert same_sparse(S2, S) and same_sparse(M2, polydec.mass(V, F))
    assert same_sparse(mesh.gradient(), polydec.gradient(V, F))
    assert same_sparse(polydec.divergence(mesh), polydec.divergence(V, F))
    assert mesh.n_cached_refinements == 1  # the same refinement served all of them
    P = polydec.prolongation(mesh, virtual_vertex="centroid")
    assert mesh.n_cached_refinements == 2
    assert np.allclose(P.toarray()[mesh.n_vertices:].sum(axis=1), 1)
    assert same_sparse(P, polydec.prolongation(V, F, virtual_vertex="centroid"))
    polydec.stiffness(mesh, planarity=1e-3)
    assert mesh.n_cached_refinements == 3
    # the cached refinement is the one the operators use: its weights are P's rows
    r = mesh.refinement()
    idx, off = mesh.faces
    P0 = polydec.prolongation(mesh).toarray()
    for f in (0, 5, mesh.n_faces - 1):
        row = P0[mesh.n_vertices + f]
        assert np.allclose(row[idx[off[f]:off[f + 1]]], r["weights"][off[f]:off[f + 1]], rtol=0, atol=1e-15)
    assert np.allclose(r["virtual_points"], P0[mesh.n_vertices:] @ V, rtol=0, atol=1e-14)


def test_with_positions_starts_a_new_cache():
    mesh = polydec.hex_grid(4, 4)
    mesh.stiffness()
    V2 = mesh.positions + 0.05 * np.sin(5 * mesh.positions[:, [1, 2, 0]])
    moved = mesh.with_positions(V2)
    assert moved.n_cached_refinements == 0 and mesh.n_cached_refinements == 1
    assert same_sparse(moved.stiffness(), polydec.stiffness(V2, mesh.faces))
    assert not same_sparse(moved.stiffness(), mesh.stiffness())
    with pytest.raises(ValueError, match="rows"):
        mesh.with_positions(V2[:-1])


def test_solvers_take_a_mesh():
    mesh = polydec.hex_sphere(2)
    V, F = mesh
    e1, _ = polydec.spectrum(mesh, 5)
    e2, _ = polydec.spectrum(V, F, 5)
    assert np.allclose(e1, e2, rtol=1e-9, atol=1e-12)
    d1 = polydec.HeatGeodesics(mesh).distance(0)
    d2 = polydec.HeatGeodesics(V, F).distance(0)
    assert np.array_equal(d1, d2)
    assert np.array_equal(polydec.mean_curvature(mesh), polydec.mean_curvature(V, F))
    with pytest.raises(TypeError, match="keyword"):
        polydec.stiffness(mesh, "ours")


def test_one_face_type_everywhere(tmp_path):
    made = [polydec.quad_grid(2, 3), polydec.hex_grid(3, 3), polydec.hex_sphere(1), polydec.torus(5, 4),
            polydec.genus2(0), polydec.uv_sphere(3, 5), polydec.cube_sphere(2), polydec.triangle_grid(2, 2),
            polydec.dual(polydec.quad_grid(2, 2)), polydec.catmull_clark(polydec.quad_grid(1, 1)),
            polydec.hex_grid_volume(2, 1, 1).boundary_surface()]
    polydec.write_mesh(tmp_path / "m.obj", made[1])
    made.append(polydec.read_mesh(tmp_path / "m.obj"))
    for m in made:
        assert isinstance(m, polydec.Mesh)
        V, F = m
        assert isinstance(F, tuple) and len(F) == 2
        assert all(isinstance(a, np.ndarray) and a.dtype == np.int64 and a.ndim == 1 for a in F)
        assert F[1][0] == 0 and F[1][-1] == F[0].size and F[1].size == m.n_faces + 1
        assert V.shape == (m.n_vertices, 3) and V.dtype == np.float64
    vf = polydec.hex_grid_volume(2, 1, 1).faces
    assert all(a.dtype == np.int64 for a in vf)
    with pytest.raises(ValueError, match="one size"):
        polydec.hex_grid(3, 3).face_array()
    assert polydec.quad_grid(2, 1).face_array().tolist() == polydec.quad_grid(2, 1).face_list()


def test_boundary_vertices_and_loops():
    g = polydec.quad_grid(4, 3)
    b = g.boundary_vertices
    X = g.positions
    on_side = (X[:, 0] == 0) | (X[:, 0] == 1) | (X[:, 1] == 0) | (X[:, 1] == 1)
    assert np.array_equal(b, on_side)
    (loop,) = g.boundary_loops
    assert sorted(loop.tolist()) == np.flatnonzero(on_side).tolist()
    edges = {tuple(e) for e in g.edges.tolist()}
    for a, c in zip(loop, np.roll(loop, -1)):  # consecutive loop vertices are boundary edges
        assert (min(a, c), max(a, c)) in edges
    # interior on the left: the loop runs counter-clockwise around the (counter-clockwise) grid
    P = X[loop, :2]
    assert 0.5 * np.sum(P[:, 0] * np.roll(P[:, 1], -1) - np.roll(P[:, 0], -1) * P[:, 1]) > 0
    # an open cylinder: two loops of n; a closed surface: none
    n = 8
    t = 2 * np.pi * np.arange(n) / n
    V = np.vstack([np.c_[np.cos(t), np.sin(t), np.zeros(n)], np.c_[np.cos(t), np.sin(t), np.ones(n)]])
    F = [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    cyl = polydec.Mesh(V, F)
    assert sorted(len(l) for l in cyl.boundary_loops) == [n, n] and cyl.boundary_vertices.all()
    assert polydec.torus(6, 4).boundary_loops == [] and not polydec.torus(6, 4).boundary_vertices.any()


def test_pickle_mesh_and_volume_mesh(tmp_path):
    mesh = polydec.Mesh(*polydec.hex_grid(4, 4))
    mesh.stiffness()
    back = pickle.loads(pickle.dumps(mesh))
    assert np.array_equal(back.positions, mesh.positions)
    assert all(np.array_equal(a, b) for a, b in zip(back.faces, mesh.faces))
    assert same_sparse(back.stiffness(), mesh.stiffness())
    # a read mesh keeps what its digits resolve through pickling
    path = write_six_digit_grid(tmp_path)
    read = polydec.read_mesh(path)
    assert read.coordinate_noise > 0
    again = pickle.loads(pickle.dumps(read))
    assert again.coordinate_noise == read.coordinate_noise
    assert same_sparse(again.stiffness(), read.stiffness())
    vm = polydec.jitter_interior(polydec.truncated_octahedra_volume(2), 0.2)
    vb = pickle.loads(pickle.dumps(vm))
    assert np.array_equal(vb.cell_volumes, vm.cell_volumes) and vb.n_faces == vm.n_faces
    assert same_sparse(polydec.volume_stiffness(vb), polydec.volume_stiffness(vm))


def write_six_digit_grid(tmp_path, name="grid.off"):
    """A 6 x 6 quad grid of [0, 1]^2, its vertices moved by up to 0.03 in the plane (generic quads)
    and by up to 2e-7 out of it, written with 7 decimals: as the file's digits tell, every quad is
    planar; as exact doubles, none is."""
    V, F = polydec.quad_grid(6, 6)
    rng = np.random.default_rng(3)
    V = V.copy()
    V[:, :2] += rng.uniform(-0.03, 0.03, (V.shape[0], 2))
    V[:, 2] = 2e-7 * rng.uniform(-1, 1, V.shape[0])
    path = tmp_path / name
    with open(path, "w") as f:
        f.write(f"OFF\n{V.shape[0]} {len(F[1]) - 1} 0\n")
        for x in V:
            f.write(" ".join(f"{c:.7f}" for c in x) + "\n")
        idx, off = F
        for a, b in zip(off[:-1], off[1:]):
            f.write(f"{b - a} " + " ".join(map(str, idx[a:b])) + "\n")
    return path


def read_mtx(path):
    import scipy.io

    return scipy.io.mmread(str(path)).tocsc()


def test_python_and_command_line_agree_on_a_file(tmp_path, cli):
    path = write_six_digit_grid(tmp_path)
    cli("operators", path, "--out", tmp_path / "cli")
    S_cli = read_mtx(tmp_path / "cli" / "S.mtx")
    mesh = polydec.read_mesh(path)
    assert relative_difference(mesh.stiffness(), S_cli) < 1e-12
    # the same doubles taken as exact are non-planar quads: other weights, another S
    exact = polydec.stiffness(mesh, planarity="exact")
    assert relative_difference(exact, S_cli) > 1e-3
    assert same_sparse(exact, polydec.stiffness(*mesh))  # what arrays mean
    # a fixed tolerance, both sides
    cli("--planarity-tolerance", "1e-9", "operators", path, "--out", tmp_path / "tol")
    assert relative_difference(polydec.stiffness(mesh, planarity=1e-9), read_mtx(tmp_path / "tol" / "S.mtx")) < 1e-12


def test_amo_quad_agrees_with_the_command_line(tmp_path, cli):
    path = shared_mesh("amo_quad.off")
    cli("operators", path, "--out", tmp_path)
    S_cli, M_cli = read_mtx(tmp_path / "S.mtx"), read_mtx(tmp_path / "M.mtx")
    mesh = polydec.read_mesh(path)
    S, M = mesh.laplacian(mass="galerkin")
    assert abs(S - S_cli).max() <= 1e-12 * abs(S_cli).max()
    assert abs(M - M_cli).max() <= 1e-12 * abs(M_cli).max()
