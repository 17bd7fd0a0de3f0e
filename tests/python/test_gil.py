"""tests/python/test_gil.py — the GIL is released during assembly, factorization and solves.

Two checks. (1) A pure-Python thread keeps counting while polydec works in another thread: with
the GIL held it would be frozen for the whole call (it gets at most a switch interval, 5 ms),
so its count during the call is compared with its count alone over as long; robust on a busy
machine. (2) The wall-time check: two threads assembling concurrently finish in clearly less
than twice one thread's time (median of a few repetitions, < 1.6x). It needs two free cores, so
it first times a control that certainly runs in parallel (hashlib releases the GIL) and is
skipped, saying so, when the control takes more than 1.3x (no two free cores: a machine busy with
other work). CTest runs this file with RUN_SERIAL for that reason."""

import hashlib
import os
import threading
import time

import numpy as np
import pytest

import polydec


@pytest.fixture(scope="module")
def big_mesh():
    """61440 quads (one Catmull-Clark step of hex_sphere(5)), converted once: the timed calls are
    the extension's, not the input conversion."""
    V, F = polydec.catmull_clark(*polydec.hex_sphere(5))
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
            polydec._polydec.operators(X, idx, off, "ours", {"S", "M", "M_lumped", "G"}, 1)

    during, alone = _count_during(work, 0.2)
    assert during > 0.1 * alone, f"spinner rate during assembly {during:.0f}/s, alone {alone:.0f}/s"


def test_python_threads_run_during_factorization_and_solves(big_mesh):
    X, idx, off = big_mesh
    heat = {}

    def factor():
        heat["h"] = polydec._polydec.HeatGeodesics(X, idx, off, "ours", 1.0, True, True)

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


def _median_time(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def _ratio_two_threads(fn, repeat):
    """Median wall time of fn in two concurrent threads over that of fn alone."""
    def two():
        ts = [threading.Thread(target=fn) for _ in range(2)]
        for t in ts:
            t.start()
        for t in ts:
            t.join()

    fn()
    one = _median_time(fn, repeat)
    return _median_time(two, repeat) / one, one


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="needs two cores")
def test_two_threads_assemble_in_parallel(big_mesh):
    """Two threads assembling take clearly less than twice one thread's time. A wall-time ratio
    needs two free cores for the whole measurement: each attempt is bracketed by a control (two
    hashing threads, GIL released) before and after, and counts only when both controls show
    free cores; up to three attempts; skipped when none counts. With the GIL held the ratio is
    about 2 in every counted attempt, so the test still fails then."""
    data = os.urandom(16 << 20)

    def control():
        for _ in range(4):
            hashlib.sha256(data).digest()

    X, idx, off = big_mesh

    def assemble():
        for _ in range(2):
            polydec._polydec.operators(X, idx, off, "ours", {"S", "M", "M_lumped"}, 1)

    counted = []
    for _ in range(3):
        before, _ = _ratio_two_threads(control, 3)
        ratio, one = _ratio_two_threads(assemble, 5)
        after, _ = _ratio_two_threads(control, 3)
        if max(before, after) > 1.3:
            continue
        counted.append((ratio, one, before, after))
        if ratio < 1.6:
            return
    if not counted:
        pytest.skip("no two free cores during any attempt (controls above 1.3x); the spinner tests above "
                    "still check the GIL")
    ratio, one, before, after = counted[-1]
    raise AssertionError(f"two threads took {ratio:.2f}x one thread's {one:.3f} s in each of {len(counted)} "
                         f"attempts with free cores (controls {before:.2f}x, {after:.2f}x)")
