"""bench/volume_form_spectra.py — convergence of the Hodge Laplacian spectra of 0-, 1-, 2- and 3-forms
on the box [0, pi]^3 with natural boundary conditions, both DEC complexes, against the analytic
spectrum (docs/feec.md, "Spectra of the box [0, pi]^3").

Analytic spectrum (absolute boundary conditions: the normal parts of w and of dw vanish): a k-form
eigenform is w = f dx_I, |I| = k, f = prod_i s_i(m_i x_i) with s_i = sin, m_i >= 1 for i in I and
s_j = cos, m_j >= 0 for the other axes; eigenvalue |m|^2. These products are complete in L^2, so
the multiplicity of lambda in degree k is the number of (I, m) with |m|^2 = lambda. Zero appears
only for k = 0 (the constant: b0 = 1, b1 = b2 = b3 = 0), and for every lambda > 0 the alternating
sum of the multiplicities over k = 0..3 vanishes (exact sequence: each eigenvalue of degree k is
exact, the d-image of a degree k - 1 one, or co-exact, mapped by d to degree k + 1); the script
checks both before comparing.

The meshes are written by the script as VTK legacy files: hexahedral grids n^3 (optionally
jittered: interior vertices moved by a seeded uniform vector in the ball of radius JITTER h) and
Kuhn tetrahedral grids (6 tetrahedra a cube; there the two complexes coincide). Each spectrum is
`polydec spectrum MESH --form K --complex C --k KK --json` (K = 0: `polydec spectrum MESH --k KK
--json`, the lumped-mass function spectrum, which is also the exact part of the 1-form spectrum,
lumped star0 by default); the error of one mesh and degree is the largest relative error of the
first N non-zero eigenvalues, ascending, with multiplicity (one table per N of --n-eigs); rate = log(e_coarse / e_fine) /
log(h_coarse / h_fine), h = pi / n.

Usage: /usr/bin/python3 bench/volume_form_spectra.py POLYDEC_CLI [--family hex|hex-jitter|tet]
         [--mesh-n 4,6,8,12,16] [--complete-n 2,3,4] [--degrees 0,1,2,3] [--n-eigs 10,30]
         [--jitter 0.2] [--seed 1] [--json OUT.json] [--workdir DIR]
       /usr/bin/python3 bench/volume_form_spectra.py --report OUT.json [MORE.json ...]   (tables only)
The complete complex builds a dense reduced basis (volume_form_span, dense QR of P_k): 2- and
3-forms take about a minute at n = 4 and it refuses larger meshes, so its sequence is short."""

import argparse
import itertools
import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile
import time


def analytic_spectrum(degree, count, box=math.pi):
    """The `count` smallest eigenvalues (with multiplicity, ascending) of the Hodge Laplacian on
    `degree`-forms of [0, box]^3 with natural boundary conditions."""
    scale = (math.pi / box) ** 2
    m_max = int(math.isqrt(count)) + 4
    while True:
        values = []
        for axes in itertools.combinations(range(3), degree):
            for m in itertools.product(range(m_max + 1), repeat=3):
                if all(m[i] >= 1 for i in axes):
                    values.append(scale * (m[0] ** 2 + m[1] ** 2 + m[2] ** 2))
        values.sort()
        # complete below m_max^2: every m with |m|^2 < (m_max + 1)^2 has been listed
        if len(values) >= count and values[count - 1] < scale * (m_max + 1) ** 2:
            return values[:count]
        m_max *= 2


def coexact1_spectrum(count):
    """The `count` smallest co-exact 1-form eigenvalues: the 1-form multiset minus the non-zero
    0-form one (the exact 1-forms are the d-images of the 0-form eigenfunctions)."""
    total = count + 60
    ones = analytic_spectrum(1, total)
    zeros = [v for v in analytic_spectrum(0, 2 * total) if 0 < v <= ones[-1]]
    out = list(ones)
    for v in zeros:
        if v in out:
            out.remove(v)
    return [v for v in out if v < ones[-1]][:count]


def nonzero_clusters(degree, count):
    """[(value, first index, end index)] of the distinct non-zero analytic values, indices into the
    ascending non-zero list, covering at least `count` entries."""
    values = [v for v in analytic_spectrum(degree, count + 60) if v > 0]
    out = []
    for i, v in enumerate(values):
        if out and out[-1][0] == v:
            out[-1][2] = i + 1
        else:
            if out and out[-1][2] >= count:
                break
            out.append([v, i, i + 1])
    return out


def whole_clusters(degree, count):
    """The largest m <= count that ends a cluster of equal analytic values (at least the first cluster)."""
    ends = [c[2] for c in nonzero_clusters(degree, count)]
    inside = [e for e in ends if e <= count]
    return inside[-1] if inside else ends[0]


def cluster_range(degree, index):
    """(first, end) indices of the index-th distinct non-zero analytic value."""
    c = nonzero_clusters(degree, 1)
    count = 1
    while len(c) <= index:
        count *= 2
        c = nonzero_clusters(degree, count)
    return c[index][1], c[index][2]


def check_analytic(limit=40):
    """Betti numbers and the exact-sequence identity of the analytic spectra (up to lambda = limit)."""
    mult = []
    for degree in range(4):
        counts = {}
        for v in analytic_spectrum(degree, 4000):
            if v <= limit:
                counts[v] = counts.get(v, 0) + 1
        mult.append(counts)
    betti = [mult[k].get(0, 0) for k in range(4)]
    assert betti == [1, 0, 0, 0], betti
    for v in set().union(*mult):
        if v > 0:
            alt = sum((-1) ** k * mult[k].get(v, 0) for k in range(4))
            assert alt == 0, (v, [mult[k].get(v, 0) for k in range(4)])
    return betti


def write_vtk(path, points, cells, cell_type):
    with open(path, "w") as f:
        f.write("# vtk DataFile Version 3.0\nbox [0, pi]^3\nASCII\nDATASET UNSTRUCTURED_GRID\n")
        f.write(f"POINTS {len(points)} double\n")
        for p in points:
            f.write("%.17g %.17g %.17g\n" % tuple(p))
        f.write(f"CELLS {len(cells)} {sum(len(c) + 1 for c in cells)}\n")
        for c in cells:
            f.write(f"{len(c)} " + " ".join(map(str, c)) + "\n")
        f.write(f"CELL_TYPES {len(cells)}\n" + f"{cell_type}\n" * len(cells))


def grid_points(n, jitter, seed):
    h = math.pi / n
    rng = random.Random(seed)
    points = []
    for k in range(n + 1):
        for j in range(n + 1):
            for i in range(n + 1):
                p = [i * h, j * h, k * h]
                if jitter > 0 and 0 < i < n and 0 < j < n and 0 < k < n:
                    while True:  # uniform in the ball of radius jitter * h
                        u = [rng.uniform(-1, 1) for _ in range(3)]
                        if sum(x * x for x in u) <= 1:
                            break
                    p = [p[a] + jitter * h * u[a] for a in range(3)]
                points.append(p)
    return points


def hex_grid(path, n, jitter=0.0, seed=1):
    def idx(i, j, k):
        return i + (n + 1) * (j + (n + 1) * k)

    cells = []
    for k, j, i in itertools.product(range(n), repeat=3):
        cells.append([idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
                      idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1), idx(i, j + 1, k + 1)])
    write_vtk(path, grid_points(n, jitter, seed), cells, 12)


def tet_grid(path, n, jitter=0.0, seed=1):
    """Kuhn subdivision: each cube into the 6 tetrahedra 000, e_a, e_a + e_b, 111 (a, b, c a permutation)."""
    points = grid_points(n, jitter, seed)

    def idx(i, j, k):
        return i + (n + 1) * (j + (n + 1) * k)

    def volume(t):
        a, b, c, d = (points[v] for v in t)
        u, v, w = ([b[x] - a[x] for x in range(3)], [c[x] - a[x] for x in range(3)], [d[x] - a[x] for x in range(3)])
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                u[2] * (v[0] * w[1] - v[1] * w[0]))

    cells = []
    for k, j, i in itertools.product(range(n), repeat=3):
        for perm in itertools.permutations(range(3)):
            c = [0, 0, 0]
            t = [idx(i, j, k)]
            for a in perm:
                c[a] += 1
                t.append(idx(i + c[0], j + c[1], k + c[2]))
            if volume(t) < 0:
                t[2], t[3] = t[3], t[2]
            cells.append(t)
    write_vtk(path, points, cells, 10)


def spectrum(cli, mesh, degree, complex_, k):
    args = [cli, "spectrum", mesh, "--k", str(k), "--json"]
    if degree > 0:
        args += ["--form", str(degree), "--complex", complex_]
    t = time.monotonic()
    r = subprocess.run(args, capture_output=True, text=True)
    seconds = time.monotonic() - t
    limit = re.search(r"must lie in \[1, (\d+)\)", r.stderr)
    if r.returncode != 0 and limit and int(limit.group(1)) > 1:  # a small mesh: all it has
        return spectrum(cli, mesh, degree, complex_, int(limit.group(1)) - 1)
    if r.returncode != 0:
        return None, seconds, r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"exit {r.returncode}"
    return json.loads(r.stdout), seconds, ""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cli", nargs="?", help="the polydec program")
    ap.add_argument("--report", nargs="+", metavar="RUNS.json", help="print the tables of earlier --json files only")
    ap.add_argument("--family", default="hex", choices=["hex", "hex-jitter", "tet"])
    ap.add_argument("--mesh-n", default="4,6,8,12,16")
    ap.add_argument("--complete-n", default="2,3,4")
    ap.add_argument("--degrees", default="0,1,2,3")
    ap.add_argument("--n-eigs", default="10,30", help="N values of the error table (the largest is computed)")
    ap.add_argument("--jitter", type=float, default=0.2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json")
    ap.add_argument("--workdir")
    a = ap.parse_args()

    print("analytic Betti numbers b0..b3:", check_analytic(), "; alternating sums of multiplicities vanish")
    degrees = [int(x) for x in a.degrees.split(",")]
    n_eigs = [int(x) for x in a.n_eigs.split(",")]
    if a.report:
        runs = []
        for path in a.report:
            with open(path) as f:
                runs += json.load(f)
        return report(runs, degrees, n_eigs)
    if not a.cli:
        ap.error("the polydec program is needed unless --report is given")
    work = a.workdir or tempfile.mkdtemp(prefix="volume_form_spectra_")
    os.makedirs(work, exist_ok=True)
    n_max = max(n_eigs)
    runs = []
    for complex_, ns in (("mesh", a.mesh_n), ("complete", a.complete_n)):
        for n in [int(x) for x in ns.split(",") if x]:
            path = os.path.join(work, f"{a.family}_{n}.vtk")
            if not os.path.exists(path):
                jitter = a.jitter if a.family == "hex-jitter" else 0.0
                (tet_grid if a.family == "tet" else hex_grid)(path, n, jitter, a.seed)
            for degree in degrees:
                if degree == 0 and complex_ == "complete":
                    continue  # the function spectrum is the same on both complexes (one S, one M)
                zeros_expected = 1 if degree == 0 else 0
                k = n_max + zeros_expected
                data, seconds, error = spectrum(a.cli, path, degree, complex_, k)
                row = {"family": a.family, "complex": complex_ if degree else "-", "n": n, "h": math.pi / n,
                       "degree": degree, "seconds": round(seconds, 2)}
                if data is None:
                    row["error"] = error
                    print(f"{complex_:8s} n={n:3d} degree {degree}: failed ({error})", flush=True)
                    runs.append(row)
                    continue
                ev = sorted(data["eigenvalues"])
                zero = 1e-8
                n_zero = sum(1 for v in ev if abs(v) < zero)
                exact = analytic_spectrum(degree, k)
                nonzero_h = [v for v in ev if abs(v) >= zero][:n_max]
                nonzero_a = [v for v in exact if v > 0][:n_max]
                rel = [abs(x - y) / y for x, y in zip(nonzero_h, nonzero_a)]
                row.update({"zeros": n_zero, "zeros_expected": zeros_expected, "eigenvalues": nonzero_h,
                            "analytic": nonzero_a, "relative_error": rel, "max_relative_error": max(rel),
                            "kinds": [p.get("kind") for p in data.get("eigenpairs", [])]})
                runs.append(row)
                if a.json:  # after every run, so that an interrupted study keeps what it has
                    with open(a.json, "w") as f:
                        json.dump(runs, f, indent=1)
                print(f"{complex_ if degree else '-':8s} n={n:3d} degree {degree}: zeros {n_zero} (expected "
                      f"{zeros_expected}), max rel. error of the first {len(rel)} non-zero {max(rel):.4g} "
                      f"({seconds:.1f} s)", flush=True)

    if a.json:
        with open(a.json, "w") as f:
            json.dump(runs, f, indent=1)
    return report(runs, degrees, n_eigs)


def report(runs, degrees, n_eigs):
    """Prints the error tables of `runs`; 1 when a run's zero eigenvalues differ from the Betti numbers."""
    def table(title, error_of, only_degrees=None):
        print(f"\n{title}; rate against the previous n:")
        print("| family | complex | degree | n | h | error | rate |")
        for complex_ in ("-", "mesh", "complete"):
            for degree in only_degrees or degrees:
                prev = None
                for r in runs:
                    if r["complex"] != complex_ or r["degree"] != degree or "relative_error" not in r:
                        continue
                    e = error_of(r)
                    if e is None:
                        continue
                    rate = "" if prev is None else f"{math.log(prev[1] / e) / math.log(prev[0] / r['h']):.2f}"
                    print(f"| {r['family']} | {complex_} | {degree} | {r['n']} | {r['h']:.4f} | {e:.3e} | {rate} |")
                    prev = (r["h"], e)

    for count in n_eigs:
        def first(r, count=count):
            m = whole_clusters(r["degree"], count)
            return max(r["relative_error"][:m]) if len(r["relative_error"]) >= m else None
        table(f"largest relative error of the first {count} non-zero eigenvalues (with multiplicity; "
              f"cut to whole clusters of equal analytic value)", first)
    for band in range(3):
        def one(r, band=band):
            lo, hi = cluster_range(r["degree"], band)
            return max(r["relative_error"][lo:hi]) if len(r["relative_error"]) >= hi else None
        table(f"largest relative error in cluster {band + 1} (the {band + 1}. distinct non-zero analytic value)", one)
    # Co-exact 1-forms (the curl-curl eigenproblem): the exact ones are the 0-form spectrum on both
    # complexes (one S), so this is where the complexes differ.
    for count in (5, 11):  # 2 x3, 3 x2 (, 5 x6): whole clusters
        coexact = coexact1_spectrum(count)

        def coexact_error(r, coexact=coexact):
            values = [v for v, kind in zip(r["eigenvalues"], r.get("kinds", [])) if kind == "co-exact"]
            if len(values) < len(coexact):
                return None
            return max(abs(x - y) / y for x, y in zip(values, coexact))
        table(f"co-exact 1-forms: largest relative error of the first {count} "
              f"({', '.join(f'{v:g}' for v in coexact)})", coexact_error, [1])
    bad = [r for r in runs if "zeros" in r and r["zeros"] != r["zeros_expected"]]
    if bad:
        print("zero eigenvalues differ from the Betti numbers:", [(r["complex"], r["n"], r["degree"]) for r in bad])
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
