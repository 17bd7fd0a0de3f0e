"""bench/python_overhead.py — Python call overhead against the C++ call for one assembly of
FINE SPHERE (one Catmull-Clark step of HEX SPHERE, projected; HEX SPHERE = dual of
../shared/data/unit-sphere.off, projected; without the file, one Catmull-Clark step of
hex_sphere(5) projected, 61,440 quads), in one run, interleaved rounds: the C++ figure is
`polydec operators FINE.ply --repeat 3 --json` per round (refine + S, M, lumped M; load and
validation excluded; its wall and thread-CPU medians); the Python figures are, on a polydec.Mesh
validated once, the extension call for the same three matrices with the refinement rebuilt every
call (the C++ call's work: target under 1.5x) and with it cached (the Mesh's normal second call),
the same two with the previous call's result alive until the next call returns (as the C++ loop
keeps its previous matrices, and as `ops = f(...)` in a user's loop does; the first two drop it),
then polydec.laplacian(mesh, mass="galerkin") (S and M, public, cached refinement) and
polydec.laplacian(V, F, ...) from arrays (conversion and validation every call), all medians of N.
The extension hands the matrices to scipy without copying them. With --keep-freed-memory the Python
process first calls polydec.keep_freed_memory() (the explicit opt-in: glibc keeps freed memory for
reuse instead of returning it to the system, so a call faults no fresh pages in; the CLI runs with
glibc's defaults); see docs/benchmarks.md.
Usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py build/polydec [N] [--keep-freed-memory]"""

import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np

import polydec


def seconds(fn):
    """(wall seconds, CPU seconds of this thread) of fn(); the work runs in this thread (threads=1)."""
    t0, c0 = time.perf_counter(), time.thread_time()
    fn()
    return time.perf_counter() - t0, time.thread_time() - c0


def main():
    args = [a for a in sys.argv[1:] if a != "--keep-freed-memory"]
    keep = len(args) < len(sys.argv) - 1
    cli = args[0]
    n = int(args[1]) if len(args) > 1 else 10
    if keep and not polydec.keep_freed_memory():
        sys.exit("keep_freed_memory: not available (not glibc)")
    data = pathlib.Path(__file__).resolve().parents[2] / "shared" / "data" / "unit-sphere.off"
    if data.exists():
        name = "FINE SPHERE"
        hexs = polydec.project_to_unit_sphere(polydec.dual(polydec.read_mesh(data)))
    else:
        name = "catmull_clark(hex_sphere(5)), projected"
        hexs = polydec.hex_sphere(5)
    mesh = polydec.project_to_unit_sphere(polydec.catmull_clark(hexs))
    V, F = mesh
    parts = {"S", "M", "M_lumped"}
    h = mesh._h

    def cold():
        h.clear_refinements()
        return polydec._polydec.operators(h, "ours", parts, 1, -1.0)

    # The C++ loop keeps the previous matrices until the new ones are built (its heap is never
    # trimmed in between); "cold_kept" and "warm_kept" hold the previous result the same way, as
    # `ops = f(...)` in a user's loop does, where "cold" and "warm" drop it before the next call.
    last = [None]

    def kept(fn):
        def call():
            last[0] = fn()
        return call

    rows = {"cold": [], "warm": [], "cold_kept": [], "warm_kept": [], "public": [], "arrays": []}
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "fine_sphere.ply"
        polydec.write_mesh(path, mesh, binary=True)
        cpp = []
        for _ in range(n):  # interleaved: each round one C++ run (median of 3 inside) and each Python call
            out = subprocess.run([cli, "operators", str(path), "--repeat", "3", "--json"], check=True,
                                 capture_output=True, text=True).stdout
            j = json.loads(out)
            cpp.append((j["median_ms"] / 1e3, j["median_thread_cpu_ms"] / 1e3))
            rows["cold"].append(seconds(cold))
            rows["warm"].append(seconds(lambda: polydec._polydec.operators(h, "ours", parts, 1, -1.0)))
            last[0] = None
            rows["cold_kept"].append(seconds(kept(cold)))
            rows["cold_kept"].append(seconds(kept(cold)))
            rows["warm_kept"].append(seconds(kept(lambda: polydec._polydec.operators(h, "ours", parts, 1, -1.0))))
            rows["warm_kept"].append(seconds(kept(lambda: polydec._polydec.operators(h, "ours", parts, 1, -1.0))))
            last[0] = None
            rows["public"].append(seconds(lambda: polydec.laplacian(mesh, mass="galerkin")))
            rows["arrays"].append(seconds(lambda: polydec.laplacian(V, F, mass="galerkin")))
    glibc = (" (polydec.keep_freed_memory() in Python)" if keep else
             " (MALLOC_TRIM/MMAP_THRESHOLD_ set)" if os.environ.get("MALLOC_TRIM_THRESHOLD_") else "")
    print(f"{name}: {mesh.n_vertices} vertices, {mesh.n_faces} faces; medians of {n} interleaved rounds{glibc}; "
          f"load average {os.getloadavg()[0]:.1f}; wall time, and CPU time of the calling thread (robust to a "
          "busy machine)")
    c = [1e3 * float(np.median([x[i] for x in cpp])) for i in (0, 1)]
    print(f"C++ (polydec operators --repeat 3, refine + S, M, lumped M): {c[0]:.1f} ms, CPU {c[1]:.1f} ms")
    labels = {"cold": "Python, Mesh, S, M, lumped M, refinement rebuilt",
              "warm": "Python, Mesh, S, M, lumped M, refinement cached",
              "cold_kept": "Python, the same, refinement rebuilt, previous result kept as the C++ loop keeps it",
              "warm_kept": "Python, the same, refinement cached, previous result kept",
              "public": "Python, polydec.laplacian(mesh, mass='galerkin') (S, M)",
              "arrays": "Python, polydec.laplacian(V, F, mass='galerkin') from arrays"}
    for k, label in labels.items():
        w, t = (1e3 * float(np.median([x[i] for x in rows[k]])) for i in (0, 1))
        print(f"{label}: {w:.1f} ms ({w / c[0]:.2f}x), CPU {t:.1f} ms ({t / c[1]:.2f}x)")


if __name__ == "__main__":
    main()
