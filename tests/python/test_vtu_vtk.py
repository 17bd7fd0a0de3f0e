"""tests/python/test_vtu_vtk.py — the .vtu files polydec writes, read by VTK itself (Debian's
python3-vtk9, vtkXMLUnstructuredGridReader): point and cell counts, cell types (standard cells as
such, other polyhedra as type 42), each cell's volume as VTK computes it (vtkCellSizeFilter)
against polydec's, positions and point data bit-exact; the zlib-compressed files of `polydec convert
--compress`; surfaces with their scalars. Skipped with a message when VTK's Python bindings are not
installed."""

import numpy as np
import pytest

import polydec

vtk = pytest.importorskip("vtk", reason="VTK's Python bindings are absent (apt-get install python3-vtk9)")
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

# Cells with planar faces only (a jittered hexahedron's volume depends on how its warped faces are
# filled: VTK triangulates them, polydec uses face points).
MESHES = {
    "hex": (lambda: polydec.hex_grid_volume(3, 2, 2), 12),
    "tet": (lambda: polydec.tet_grid_volume(2, 2, 2, jitter=0.2), 10),
    "pyramids": (lambda: polydec.pyramid_grid_volume(2, 2, 2), 14),
    "truncated": (lambda: polydec.truncated_octahedra_volume(2), 42),
}


def read_vtu(path):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(str(path))
    r.Update()
    return r.GetOutput()


@pytest.mark.parametrize("name", sorted(MESHES))
def test_vtk_reads_our_volume_vtu(name, tmp_path):
    make, cell_type = MESHES[name]
    mesh = make()
    u = np.sin(3 * mesh.positions[:, 0]) / 7
    path = tmp_path / "m.vtu"
    mesh.write(str(path), {"u": u})
    g = read_vtu(path)
    assert g.GetNumberOfPoints() == mesh.n_vertices
    assert g.GetNumberOfCells() == mesh.n_cells
    assert np.array_equal(vtk_to_numpy(g.GetPoints().GetData()), mesh.positions)
    types = {g.GetCellType(c) for c in range(g.GetNumberOfCells())}
    assert types == {cell_type}
    assert np.array_equal(vtk_to_numpy(g.GetPointData().GetArray("u")), u)
    sizes = vtk.vtkCellSizeFilter()
    sizes.SetInputData(g)
    sizes.ComputeVolumeOn()
    sizes.Update()
    volumes = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume"))
    scale = np.abs(mesh.cell_volumes).max()
    assert np.abs(volumes - mesh.cell_volumes).max() <= 1e-12 * scale
    assert abs(volumes.sum() - mesh.volume) <= 1e-12 * abs(mesh.volume)


@pytest.mark.parametrize("name", ["hex", "truncated"])
def test_vtk_reads_our_compressed_vtu(name, tmp_path, cli):
    """polydec convert --compress: appended raw data in zlib blocks (ParaView's default), as VTK reads it."""
    mesh = MESHES[name][0]()
    source, out = tmp_path / "m.vtk", tmp_path / "m.vtu"
    mesh.write(str(source))
    cli("convert", source, out, "--compress")
    assert 'compressor="vtkZLibDataCompressor"' in out.read_text(errors="replace")
    g = read_vtu(out)
    assert g.GetNumberOfPoints() == mesh.n_vertices
    assert g.GetNumberOfCells() == mesh.n_cells
    assert np.array_equal(vtk_to_numpy(g.GetPoints().GetData()), mesh.positions)
    assert {g.GetCellType(c) for c in range(g.GetNumberOfCells())} == {MESHES[name][1]}
    sizes = vtk.vtkCellSizeFilter()
    sizes.SetInputData(g)
    sizes.ComputeVolumeOn()
    sizes.Update()
    volumes = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume"))
    assert abs(volumes.sum() - mesh.volume) <= 1e-12 * abs(mesh.volume)


def test_vtk_reads_our_surface_vtu(tmp_path):
    mesh = polydec.hex_grid(3, 3)
    V, F = mesh.positions, mesh.face_list()  # hexagons and boundary polygons: VTK polygons
    scalars = {"height": V[:, 0] * 0.25 - V[:, 1]}
    for binary in (False, True):
        path = tmp_path / f"s{int(binary)}.vtu"
        polydec.write_mesh(str(path), V, F, scalars, binary=binary)
        g = read_vtu(path)
        assert g.GetNumberOfPoints() == len(V)
        assert g.GetNumberOfCells() == len(F)
        assert [g.GetCell(c).GetNumberOfPoints() for c in range(len(F))] == [len(f) for f in F]
        assert np.array_equal(vtk_to_numpy(g.GetPoints().GetData()), V)
        assert np.array_equal(vtk_to_numpy(g.GetPointData().GetArray("height")), scalars["height"])
        back, _ = polydec.read_mesh(str(path))
        assert np.array_equal(back, V)
