"""tests/python/test_meshio.py — from_meshio / to_meshio (skipped without meshio: Debian's
python3-meshio): surfaces of mixed polygon blocks in block order, volumes of tetra, hexahedron,
wedge, pyramid and polyhedron blocks with their exact volumes, lower-dimensional blocks skipped
and counted, round trips through meshio and through a VTU file; VolumeMesh from cell arrays."""

import numpy as np
import pytest

import polydec

meshio = pytest.importorskip("meshio", reason="meshio is not installed (Debian: python3-meshio)")


def test_surface_blocks_in_block_order():
    V = np.array([[0, 0], [1, 0], [2, 0], [0, 1], [1, 1], [2, 1], [3, 0.5], [1.5, 2], [0.5, 2]], float)
    cells = [("vertex", [[7]]), ("quad", [[0, 1, 4, 3]]), ("triangle", [[1, 2, 5], [1, 5, 4], [2, 6, 5]]),
             ("polygon", [[3, 4, 5, 7, 8]]), ("line", [[0, 1], [1, 2]])]
    mesh, skipped = polydec.from_meshio(meshio.Mesh(V, cells), return_skipped=True)
    assert skipped == {"vertex": 1, "line": 2}
    assert mesh.face_list() == [[0, 1, 4, 3], [1, 2, 5], [1, 5, 4], [2, 6, 5], [3, 4, 5, 7, 8]]
    assert np.array_equal(mesh.positions[:, :2], V) and not mesh.positions[:, 2].any()
    assert (polydec.stiffness(mesh) != polydec.stiffness(V, mesh.face_list())).nnz == 0


def test_mixed_polygon_sizes_round_trip(tmp_path):
    mesh = polydec.add_noise(polydec.hex_grid(4, 3), 0.05)
    m = polydec.to_meshio(mesh, point_data={"x": mesh.positions[:, 0]}, cell_data={"f": np.arange(mesh.n_faces)})
    assert sum(len(b.data) for b in m.cells) == mesh.n_faces
    assert np.array_equal(np.concatenate(m.cell_data["f"]), np.arange(mesh.n_faces))
    back = polydec.from_meshio(m)
    assert np.array_equal(back.positions, mesh.positions)
    assert all(np.array_equal(a, b) for a, b in zip(back.faces, mesh.faces))
    # through a file ParaView reads (VTU, binary)
    meshio.write(tmp_path / "s.vtu", m)
    again = polydec.from_meshio(meshio.read(tmp_path / "s.vtu"))
    assert np.array_equal(again.positions, mesh.positions) and again.face_list() == mesh.face_list()


# Unit cube [0,1]^3 as a hexahedron, the cube [1,2] x [0,1]^2 as two wedges and a pyramid on top of
# the first cube, all in VTK's vertex order.
P = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1],
              [2, 0, 0], [2, 1, 0], [2, 0, 1], [2, 1, 1], [0.5, 0.5, 2]], float)
HEX = [[0, 1, 2, 3, 4, 5, 6, 7]]
WEDGES = [[1, 9, 8, 5, 11, 10], [1, 2, 9, 5, 6, 11]]  # base normal away from the top triangle
PYRAMID = [[4, 5, 6, 7, 12]]


def test_volume_blocks_exact_volumes():
    for kind, cells, volume in (("hexahedron", HEX, 1.0), ("wedge", WEDGES[:1], 0.5), ("pyramid", PYRAMID, 1 / 3)):
        m = polydec.VolumeMesh.from_cells(P, cells, kind)
        assert m.n_cells == 1 and abs(m.volume - volume) < 1e-15 and m.cell_volumes[0] > 0
    tet = polydec.VolumeMesh.from_cells(np.eye(4, 3, k=-1), [[0, 1, 2, 3]], "tetra")
    assert abs(tet.volume - 1 / 6) < 1e-15
    m = meshio.Mesh(P, [("hexahedron", HEX), ("quad", [[0, 3, 2, 1]]), ("wedge", WEDGES), ("pyramid", PYRAMID),
                        ("triangle", [[1, 9, 8]]), ("line", [[0, 1]])])
    vm, skipped = polydec.from_meshio(m, return_skipped=True)
    assert skipped == {"quad": 1, "triangle": 1, "line": 1}
    assert vm.n_cells == 4 and abs(vm.volume - (2 + 1 / 3)) < 1e-14 and (vm.cell_volumes > 0).all()
    assert np.allclose(vm.cell_volumes, [1, 0.5, 0.5, 1 / 3], rtol=0, atol=1e-15)
    # the shared faces were recognized: hexahedron/wedge (a quad), hexahedron/pyramid (a quad), wedge/wedge
    assert int((vm.face_cells[:, 1] >= 0).sum()) == 3
    S = polydec.volume_stiffness(vm)
    assert abs(S @ np.ones(vm.n_vertices)).max() < 1e-12 * abs(S).max()


def test_volume_round_trip_and_polyhedra(tmp_path):
    vm = polydec.jitter_interior(polydec.truncated_octahedra_volume(2), 0.2)
    m = polydec.to_meshio(vm)
    assert all(b.type.startswith("polyhedron") for b in m.cells)
    back = polydec.from_meshio(m)
    assert np.allclose(back.cell_volumes, vm.cell_volumes, rtol=1e-14, atol=0)
    S1, S2 = polydec.volume_stiffness(vm), polydec.volume_stiffness(back)
    assert abs(S1 - S2).max() <= 1e-13 * abs(S1).max()
    meshio.write(tmp_path / "v.vtu", m)
    again = polydec.from_meshio(meshio.read(tmp_path / "v.vtu"))
    assert again.n_cells == vm.n_cells and abs(again.volume - vm.volume) < 1e-13


def test_cell_blocks_straight_into_laplacian():
    m = meshio.Mesh(P, [("hexahedron", HEX), ("quad", [[0, 3, 2, 1]])])
    with pytest.raises(ValueError, match="from_meshio"):
        polydec.laplacian(m.points, m.cells)
    with pytest.raises(ValueError, match="from_meshio"):
        polydec.laplacian(m.points, [c.data for c in m.cells])


def test_refused_cells():
    with pytest.raises(ValueError, match="not supported"):
        polydec.from_meshio(meshio.Mesh(P, [("triangle6", [[0, 1, 2, 3, 4, 5]])]))
    with pytest.raises(ValueError, match="no surface or volume"):
        polydec.from_meshio(meshio.Mesh(P, [("line", [[0, 1]])]))
    with pytest.raises(polydec.InvalidMeshError, match="cell 0"):
        polydec.VolumeMesh.from_cells(P, [[0, 1, 2, 3, 4, 5, 6, 99]], "hexahedron")
    with pytest.raises(ValueError, match="8"):
        polydec.VolumeMesh.from_cells(P, [[0, 1, 2, 3]], "hexahedron")
