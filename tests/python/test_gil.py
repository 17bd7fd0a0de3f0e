"""tests/python/test_gil.py — the GIL is released during assembly, factorization and solves.

A pure-Python thread keeps counting while polydec works in another thread: with the GIL held it
would be frozen for the whole call (it gets at most a switch interval, 5 ms), so its count during
the call must be more than a tenth of its count alone over as long; robust on a busy machine. The
wall time of two threads assembling concurrently against one is a benchmark,
bench/python_threads.py (docs/benchmarks.md), not a test."""

import threading
import time

import pytest

import polydec


@pytest.fixture(scope="module")
def big_mesh():
    """61440 quads (one Catmull-Clark step of hex_sphere(5)) as arrays, converted once: the calls
    measured are the extension's (validation of a new Mesh, refinement, assembly), not the input
    conversion."""
    V, F = polydec.catmull_clark(polydec.hex_sphere(5))
    return polydec._convert.mesh(V, F)


def _count_during(work, seconds_alone):
    """(count of a pure-Python spinning thread during work(), its count alone for as long)."""
    state = {"n": 0, "stop": False}

    def spin():
        while not state["stop"]:
            state["n"] += 1

    t = threading.Thread(target=spin)
    t.start()
    try:
        time.sleep(seconds_alone)
        n0 = state["n"]
        t0 = time.perf_counter()
        time.sleep(seconds_alone)
        alone = (state["n"] - n0) / (time.perf_counter() - t0)
        n1 = state["n"]
        t1 = time.perf_counter()
        work()
        during = (state["n"] - n1) / (time.perf_counter() - t1)
    finally:
        state["stop"] = True
        t.join()
    return during, alone


def test_python_threads_run_during_assembly(big_mesh):
    X, idx, off = big_mesh

    def work():
        for _ in range(3):
            h = polydec._polydec.Mesh.from_arrays(X, idx, off, 0.0, 0.0)
            polydec._polydec.operators(h, "ours", {"S", "M", "M_lumped", "G"}, 1, -1.0)

    during, alone = _count_during(work, 0.2)
    assert during > 0.1 * alone, f"spinner rate during assembly {during:.0f}/s, alone {alone:.0f}/s"


def test_python_threads_run_during_factorization_and_solves(big_mesh):
    X, idx, off = big_mesh
    heat = {}

    def factor():
        h = polydec._polydec.Mesh.from_arrays(X, idx, off, 0.0, 0.0)
        heat["h"] = polydec._polydec.HeatGeodesics(h, "ours", 1.0, True, True, -1.0)

    during, alone = _count_during(factor, 0.2)
    assert during > 0.1 * alone, f"spinner rate during factorization {during:.0f}/s, alone {alone:.0f}/s"

    def solve():
        for s in range(10):
            heat["h"].distance([s])

    during, alone = _count_during(solve, 0.2)
    assert during > 0.1 * alone, f"spinner rate during solves {during:.0f}/s, alone {alone:.0f}/s"


def test_python_threads_run_during_volume_work():
    """Volume meshes: generation and validation, assembly, factorization and solves."""
    mesh = polydec.hex_grid_volume(20, 20, 20, jitter=0.2)
    heat = {}

    def work():
        polydec.hex_grid_volume(20, 20, 20, jitter=0.2)
        polydec.volume_operators(mesh, "ours", {"S", "M", "G", "D"})
        heat["h"] = polydec.VolumeHeatGeodesics(mesh)
        for s in range(5):
            heat["h"].distance(s)

    during, alone = _count_during(work, 0.2)
    assert during > 0.1 * alone, f"spinner rate during volume work {during:.0f}/s, alone {alone:.0f}/s"
