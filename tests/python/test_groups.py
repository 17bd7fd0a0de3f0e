"""tests/python/test_groups.py — polydec.read_mesh_groups on the gmsh fixtures of tests/data/msh
(written by gmsh 4.8.4, tests/data/msh/make_fixtures.sh): group vertex sets against the geometry,
element sets and skipped counts, the docstring example, files without groups."""

import doctest

import numpy as np

import polydec
from polydec import _groups
from conftest import TEST_DATA

MSH = TEST_DATA / "msh"


def test_volume_groups_match_the_geometry():
    for name in ("tet_41_ascii.msh", "tet_22_binary.msh"):
        m = polydec.read_volume_mesh(str(MSH / name))
        X = m.positions
        groups = polydec.read_mesh_groups(MSH / name)
        assert sorted(groups) == ["corner", "edge", "left", "solid"]
        assert groups["left"].dtype == np.int32
        assert groups["left"].tolist() == np.flatnonzero(X[:, 0] == 0).tolist()
        assert groups["edge"].tolist() == np.flatnonzero((X[:, 0] == 0) & (X[:, 1] == 0)).tolist()
        assert groups["solid"].tolist() == list(range(44))
        vertices, elements, skipped = polydec.read_mesh_groups(MSH / name, with_elements=True)
        assert elements["solid"].tolist() == list(range(90))
        assert skipped == {"lines": 2, "points": 1, "triangles": 14}


def test_surface_groups_and_other_formats(tmp_path):
    V, F = polydec.read_mesh(MSH / "quad_41_binary.msh")
    groups = polydec.read_mesh_groups(MSH / "quad_41_binary.msh")
    assert groups["left"].tolist() == np.flatnonzero(V[:, 0] == 0).tolist()
    assert groups["origin"].tolist() == np.flatnonzero(np.all(V == 0, axis=1)).tolist()
    assert len(groups["plate"]) == len(V)
    path = tmp_path / "q.obj"
    polydec.write_mesh(path, V, F)
    assert polydec.read_mesh_groups(path) == {}


def test_docstring_example():
    assert doctest.testmod(_groups).failed == 0
