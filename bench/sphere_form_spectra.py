"""bench/sphere_form_spectra.py — the 1- and 2-form Hodge Laplacian spectra of the unit sphere on
both complexes against l(l+1), on a refinement sequence: hex_sphere(level) with 5% noise, projected
(the meshes of the test "unit sphere: 1- and 2-form spectra of both complexes approach l(l+1)"),
levels 2, 3, 4 by default. Prints, per complex and level, the largest relative error of bands
l = 1, 2, 3 (1-forms: the 2(2l+1) copies; 2-forms: the 2l+1 after the zero) and the observed rate
against the previous level (log of the error ratio over log of the edge-length ratio, h ~ faces^-1/2).
Usage: PYTHONPATH=build/python /usr/bin/python3 bench/sphere_form_spectra.py [LEVELS...]"""

import math
import sys

import numpy as np

import polydec


def band_errors(values, start, bands, copies):
    """Largest relative error of each band l = 1..bands against l(l+1), its copies * (2l+1) values from `start`."""
    out, i = [], start
    for l in range(1, bands + 1):
        n = copies * (2 * l + 1)
        exact = l * (l + 1)
        out.append(float(np.max(np.abs(np.asarray(values[i:i + n]) - exact)) / exact))
        i += n
    return out


def main():
    levels = [int(a) for a in sys.argv[1:]] or [2, 3, 4]
    for complex_ in ("complete", "mesh"):
        previous = None
        for level in levels:
            mesh = polydec.project_to_unit_sphere(polydec.add_noise(polydec.hex_sphere(level), amplitude=0.05, seed=7))
            s1 = polydec.form_spectrum(mesh, k=30, degree=1, decompose=False, complex=complex_)
            s2 = polydec.form_spectrum(mesh, k=16, degree=2, decompose=False, complex=complex_)
            zeros = int(np.sum(np.abs(s2["eigenvalues"]) < 1e-8))
            e1 = band_errors(s1["eigenvalues"], 0, 3, 2)
            e2 = band_errors(s2["eigenvalues"], 1, 3, 1)
            n_faces = mesh.n_faces
            row = f"{complex_:8s} level {level} {n_faces:6d} faces: 1-forms " + ", ".join(f"{e:.4g}" for e in e1)
            row += "; 2-forms " + ", ".join(f"{e:.4g}" for e in e2) + f" (2-form zeros {zeros})"
            if previous is not None:
                h_ratio = math.sqrt(n_faces / previous[0])
                r1 = [math.log(a / b) / math.log(h_ratio) for a, b in zip(previous[1], e1)]
                r2 = [math.log(a / b) / math.log(h_ratio) for a, b in zip(previous[2], e2)]
                row += "; rates " + ", ".join(f"{r:.2f}" for r in r1) + " / " + ", ".join(f"{r:.2f}" for r in r2)
            print(row, flush=True)
            previous = (n_faces, e1, e2)


if __name__ == "__main__":
    main()
