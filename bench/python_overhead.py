"""bench/python_overhead.py — Python call overhead against the C++ call for one assembly of
FINE SPHERE (one Catmull-Clark step of HEX SPHERE, projected; HEX SPHERE = dual of
../shared/data/unit-sphere.off, projected), in one run: the C++ figure is `polydec operators
FINE.ply --repeat N --json` (refine + S, M, lumped M; load excluded), the Python figures are
polydec.laplacian(V, F, mass="galerkin") end to end (input conversion, mesh validation,
assembly, scipy matrices) and the bare extension call on converted arrays, both medians of N.
Usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py build/polydec [N]"""

import json
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np

import polydec


def median_ms(fn, n):
    t = []
    for _ in range(n):
        t0 = time.perf_counter()
        fn()
        t.append(time.perf_counter() - t0)
    return 1e3 * float(np.median(t))


def main():
    cli = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 10
    data = pathlib.Path(__file__).resolve().parents[2] / "shared" / "data" / "unit-sphere.off"
    hexs = polydec.project_to_unit_sphere(*polydec.dual(*polydec.read_mesh(data)))
    V, F = polydec.project_to_unit_sphere(*polydec.catmull_clark(*hexs))
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "fine_sphere.ply"
        polydec.write_mesh(path, V, F, binary=True)
        out = subprocess.run([cli, "operators", str(path), "--repeat", str(n), "--json"], check=True,
                             capture_output=True, text=True).stdout
        cpp = json.loads(out)["median_ms"]
        X, idx, off = polydec._convert.mesh(V, F)
        parts = {"S", "M", "M_lumped"}
        bare = median_ms(lambda: polydec._polydec.operators(X, idx, off, "ours", parts, 1), n)
        full = median_ms(lambda: polydec._polydec.operators(*polydec._convert.mesh(V, F), "ours", parts, 1), n)
        public = median_ms(lambda: polydec.laplacian(V, F, mass="galerkin"), n)
    print(f"FINE SPHERE: {V.shape[0]} vertices, {F.shape[0]} faces; medians of {n}")
    print(f"C++ (polydec operators --repeat): {cpp:.1f} ms")
    print(f"Python, extension call on converted arrays: {bare:.1f} ms ({bare / cpp:.2f}x)")
    print(f"Python, conversion + extension call (S, M, lumped M): {full:.1f} ms ({full / cpp:.2f}x)")
    print(f"Python, polydec.laplacian(V, F, mass='galerkin') (S, M): {public:.1f} ms ({public / cpp:.2f}x)")


if __name__ == "__main__":
    main()
