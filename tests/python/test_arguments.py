"""tests/python/test_arguments.py — argument checks: ValueError for sizes that are not integers,
threads < 0 (0 is the documented "all threads"), non-positive heat time step factors, bad
planarity rules; generator size limits refusing before building; FileNotFoundError (and
FileError) for a missing file; meshio's cell blocks passed as faces."""

import numpy as np
import pytest

import polydec


@pytest.mark.parametrize("make", [
    lambda: polydec.quad_grid(2.7, 2), lambda: polydec.triangle_grid(2, "3"), lambda: polydec.hex_grid(True, 2),
    lambda: polydec.cube_sphere(2.0), lambda: polydec.hex_sphere(1.5), lambda: polydec.torus(6.5, 4),
    lambda: polydec.genus2(-1), lambda: polydec.uv_sphere(1, 8), lambda: polydec.hex_grid_volume(2, 2.5, 2),
    lambda: polydec.truncated_octahedra_volume(0), lambda: polydec.tet_grid_volume(1, 1, 1.2),
])
def test_sizes_must_be_integers_in_range(make):
    with pytest.raises(ValueError):
        make()


@pytest.mark.parametrize("make", [lambda: polydec.hex_sphere(40), lambda: polydec.hex_sphere(12),
                                  lambda: polydec.genus2(30), lambda: polydec.quad_grid(20000, 20000),
                                  lambda: polydec.uv_sphere(100000, 100000), lambda: polydec.cube_sphere(10 ** 5),
                                  lambda: polydec.torus(10 ** 5, 10 ** 4), lambda: polydec.hex_grid(10 ** 5, 10 ** 4)])
def test_generators_refuse_huge_meshes(make):
    with pytest.raises(ValueError, match="at most 1e\\+08"):
        make()


def test_largest_allowed_generator_sizes_are_the_documented_ones():
    # hex_sphere(level) has 20 4^level vertices: level 11 (8.4e7) passes the limit, 12 does not;
    # the check is by the count, so one small level shows the formula
    assert polydec.hex_sphere(2).n_vertices == 20 * 4 ** 2
    assert polydec.genus2(1).n_faces == 4 * polydec.genus2(0).n_faces


def test_threads():
    mesh = polydec.hex_grid(5, 5)
    for bad in (-3, -1, 1.5):
        with pytest.raises(ValueError, match="threads"):
            polydec.stiffness(mesh, threads=bad)
        with pytest.raises(ValueError, match="threads"):
            polydec.volume_stiffness(polydec.hex_grid_volume(2, 2, 2), threads=bad)
    assert (polydec.stiffness(mesh, threads=0) != polydec.stiffness(mesh, threads=1)).nnz == 0


@pytest.mark.parametrize("factor", [0, -1.0, float("nan"), float("inf"), "x"])
def test_heat_time_step_factor_must_be_positive(factor):
    with pytest.raises(ValueError, match="time_step_factor"):
        polydec.HeatGeodesics(polydec.quad_grid(3, 3), time_step_factor=factor)
    with pytest.raises(ValueError, match="time_step_factor"):
        polydec.VolumeHeatGeodesics(polydec.hex_grid_volume(2, 2, 2), time_step_factor=factor)


@pytest.mark.parametrize("p", [-1e-5, 0, 1.0, 2, "file", float("nan")])
def test_planarity_rule_values(p):
    with pytest.raises(ValueError, match="planarity"):
        polydec.stiffness(polydec.quad_grid(2, 2), planarity=p)


def test_other_counts():
    mesh = polydec.hex_sphere(1)
    with pytest.raises(ValueError):
        polydec.spectrum(mesh, 2.5)
    with pytest.raises(ValueError):
        polydec.spectrum(mesh, 0)
    with pytest.raises(ValueError):
        polydec.HeatGeodesics(mesh).distances([0, 1], block=0)


def test_missing_file(tmp_path):
    for read in (polydec.read_mesh, polydec.read_volume_mesh):
        with pytest.raises(FileNotFoundError) as e:
            read(tmp_path / "nope.obj")
        assert isinstance(e.value, polydec.FileError) and isinstance(e.value, ValueError)
        assert e.value.filename == str(tmp_path / "nope.obj") and "no such file" in str(e.value)
    # a file that exists but is broken stays a FileError, not a FileNotFoundError
    (tmp_path / "bad.obj").write_text("v 0 0 0\nf 1 2 3\n")
    with pytest.raises(polydec.FileError) as e:
        polydec.read_mesh(tmp_path / "bad.obj")
    assert not isinstance(e.value, FileNotFoundError)


class FakeBlock:  # what meshio's CellBlock looks like to polydec (type and data)
    def __init__(self, type_, data):
        self.type, self.data = type_, np.asarray(data)


def test_cell_blocks_as_faces_are_refused_with_a_hint():
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]], float)
    blocks = [FakeBlock("quad", [[0, 1, 2, 3]]), FakeBlock("triangle", [[1, 4, 2]])]
    with pytest.raises(ValueError, match="from_meshio"):
        polydec.laplacian(V, blocks)
    with pytest.raises(ValueError, match="from_meshio"):
        polydec.laplacian(V, [b.data for b in blocks])
