"""tests/python/test_spectral.py — spectra of Whitney forms (form_spectrum) and the spectral shape
tools from Python: harmonic forms counted by the genus, star-orthonormal eigenforms whose Hodge
parts sum to them, HKS against its defining sum, symmetric spectral distances vanishing at the
source, the one-eigenvector low-pass filter giving the mass centroid; the diamond Laplacian's sign,
null space and mass."""

import numpy as np
import pytest

import polydec
from conftest import relative_difference


@pytest.mark.parametrize("degree", [1, 2])
def test_form_spectrum_on_a_torus(degree):
    V, F = polydec.torus(12, 8)
    r = polydec.form_spectrum(V, F, 4, degree=degree)
    evals, W = r["eigenvalues"], r["eigenvectors"]
    assert np.all(np.diff(evals) >= 0) and evals[-1] > 0
    dec = polydec.dec_operators(V, F)
    star = dec["star1"] if degree == 1 else dec["star2"]
    assert W.shape == (star.shape[0], 4)
    assert np.abs(W.T @ star @ W - np.eye(4)).max() <= 1e-8
    assert np.abs(r["exact"] + r["coexact"] + r["harmonic"] - W).max() <= 1e-8 * np.abs(W).max()
    # genus 1: two harmonic 1-forms, one harmonic 2-form (the area form) on a closed surface
    n_zero = int(np.sum(evals <= 1e-8 * evals[-1]))
    assert n_zero == (2 if degree == 1 else 1)
    assert all(k == "harmonic" for k in r["kinds"][:n_zero])


@pytest.mark.parametrize("degree", [1, 2])
def test_form_spectrum_on_the_mesh_complex(degree):
    V, F = polydec.torus(12, 8)
    r = polydec.form_spectrum(V, F, 4, degree=degree, complex="mesh")
    D = polydec.surface_dec(V, F, complex="mesh")
    star = D["star"][degree]
    W = r["eigenvectors"]
    assert W.shape == (star.shape[0], 4) and r["rank"] == star.shape[0]
    assert np.abs(W.T @ star @ W - np.eye(4)).max() <= 1e-8
    n_zero = int(np.sum(r["eigenvalues"] <= 1e-8 * r["eigenvalues"][-1]))
    assert n_zero == (2 if degree == 1 else 1)


def test_form_spectrum_rejects_a_bad_degree():
    with pytest.raises(ValueError, match="degree"):
        polydec.form_spectrum(*polydec.quad_grid(3, 3), 2, degree=3)


@pytest.mark.parametrize("degree", [1, 2, 3])
def test_form_spectrum_on_a_volume_mesh(degree):
    # A hexahedral solid torus: b1 = 1, b2 = b3 = 0; eigenvectors star-orthonormal on the mesh's
    # edges, faces or cells, and d0 maps the function eigenpairs to 1-form ones.
    mesh = polydec.hex_torus_volume(8, 2)
    r = polydec.form_spectrum(mesh, 8, degree=degree, complex="mesh")
    D = polydec.volume_dec(mesh, complex="mesh")
    star = D["star"][degree]
    W = r["eigenvectors"]
    assert W.shape == (star.shape[0], 8) and r["rank"] == star.shape[0]
    assert np.abs(W.T @ star @ W - np.eye(8)).max() <= 1e-8
    ev = r["eigenvalues"]
    n_zero = int(np.sum(ev <= 1e-8 * ev[-1]))
    assert n_zero == (1 if degree == 1 else 0)
    if degree == 1:
        evals, _ = polydec.volume_spectrum(mesh, 4)
        for lam in evals[1:]:
            if lam < ev[-1] * (1 - 1e-6):
                assert np.min(np.abs(ev - lam)) <= 1e-8 * lam
    with pytest.raises(ValueError, match="degree"):
        polydec.form_spectrum(mesh, 2, degree=4)


@pytest.fixture(scope="module")
def sphere_spectrum():
    V, F = polydec.cube_sphere(4)
    evals, evecs = polydec.spectrum(V, F, 12)
    return V, F, evals, evecs


def test_heat_kernel_signature_is_its_sum(sphere_spectrum):
    V, F, evals, evecs = sphere_spectrum
    t = polydec.hks_times(evals, evecs, 5)
    assert t[0] == pytest.approx(4 * np.log(10) / evals[-1], rel=1e-12)
    hks = polydec.heat_kernel_signature(evals, evecs, t)
    direct = (evecs**2) @ np.exp(-np.outer(evals, t))
    assert relative_difference(hks, direct) <= 1e-12
    assert polydec.heat_kernel_signature(evals, evecs, n=7).shape == (V.shape[0], 7)
    wks = polydec.wave_kernel_signature(evals, evecs, n=6)
    assert wks.shape == (V.shape[0], 6) and np.all(np.isfinite(wks)) and np.all(wks >= 0)


@pytest.mark.parametrize("which", ["biharmonic", "diffusion"])
def test_spectral_distances_are_symmetric(sphere_spectrum, which):
    V, F, evals, evecs = sphere_spectrum

    def dist(s):
        if which == "biharmonic":
            return polydec.biharmonic_distance(evals, evecs, s)
        return polydec.diffusion_distance(evals, evecs, 0.05, s)

    d0, d7 = dist(0), dist(7)
    assert d0[0] == 0 and d7[7] == 0 and np.all(d0 >= 0)
    assert d0[7] == pytest.approx(d7[0], rel=1e-12)
    with pytest.raises(ValueError, match="out of range"):
        dist(V.shape[0])


def test_lowpass_with_one_eigenvector_is_the_mass_centroid(sphere_spectrum):
    V, F, evals, evecs = sphere_spectrum
    m = polydec.lumped_mass(V, F)
    X = polydec.lowpass_filter(evals, evecs, m, V, 1)
    centroid = (m.diagonal() @ V) / m.diagonal().sum()
    assert np.abs(X - centroid).max() <= 1e-10
    assert np.abs(polydec.lowpass_filter(evals, evecs, m.diagonal(), V, 12) - V).max() < np.abs(V).max()


def test_spectral_tools_reject_unsorted_eigenvalues(sphere_spectrum):
    V, F, evals, evecs = sphere_spectrum
    with pytest.raises(ValueError, match="ascending"):
        polydec.hks_times(evals[::-1], evecs[:, ::-1])


def test_diamond_laplacian_on_polygons():
    V, F = polydec.hex_grid(6, 5)
    S, M = polydec.laplacian(V, F, "diamond", mass="galerkin")
    n = V.shape[0]
    assert relative_difference(S, S.T) <= 1e-14
    assert np.abs(S @ np.ones(n)).max() <= 1e-12 * abs(S).max()
    assert M.sum() == pytest.approx(1.0, rel=1e-12)  # the unit square's area
    evals, _ = polydec.spectrum(V, F, 3, "diamond")
    assert abs(evals[0]) <= 1e-8 * evals[1]
