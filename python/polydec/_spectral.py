"""polydec._spectral — spectra of Whitney 1- and 2-forms on polygon meshes and of 1-, 2- and 3-forms
on volume meshes (form_spectrum, docs/spectral.md, docs/volumes.md) and the spectral shape tools
computed from 0-form eigenpairs (heat and wave kernel signatures, biharmonic and diffusion
distances, low-pass filter), which take the (evals, evecs) of polydec.spectrum or
polydec.volume_spectrum. Imported into polydec."""

import numpy as np

from . import _convert, _polydec


def form_spectrum(V, F=None, k=None, degree=1, mass="lumped", tolerance=1e-10, max_iterations=1000, decompose=True,
                  complex="complete", planarity=None):
    """The k smallest eigenpairs of the Hodge Laplacian on Whitney `degree`-forms (1 or 2):
    1-forms K1 w = lambda star1 w, K1 = d1^T star2 d1 + star1 d0 M0^-1 d0^T star1 (M0 the lumped
    star0, or mass="galerkin" the Galerkin one); 2-forms K2 u = lambda star2 u. -> dict:
    eigenvalues (k,) ascending >= 0, eigenvectors (|C_degree|, k) coarse cochains on cells()[0]
    (pairs) or cells()[1] (triples), star-orthonormal; with decompose=True the Hodge parts exact,
    coexact, harmonic (same shape, summing to the eigenvectors), their star norms norm_exact,
    norm_coexact, norm_harmonic (k,) and kinds (the part of largest norm per eigenform:
    "exact", "co-exact", "harmonic"); rank (dimension of the Whitney forms), shift, n_converged,
    n_solves, method, degenerate_fan_triangles. SolverError when the solver fails.
    complex="mesh": on the mesh's own edges (degree 1) or faces (degree 2), positive definite stars
    (surface_dec(V, F, "mesh")); the eigenvectors are then (|E|, k) or (|F|, k).
    form_spectrum(mesh, k, ...) or form_spectrum(V, F, k, ...).
    A polydec.VolumeMesh: degree 1, 2 or 3, K_k = star_k d_{k-1} M^-1 d_{k-1}^T star_k +
    d_k^T star_{k+1} d_k on volume_dec(mesh, complex=complex) (docs/volumes.md); eigenvectors on the
    mesh's edges, faces, cells (complex="mesh") or the complete complex's pairs, triples, quads.

    >>> s = polydec.form_spectrum(polydec.torus(12, 8), 3, complex="mesh")
    >>> s["kinds"][:2]
    ['harmonic', 'harmonic']
    """
    from ._mesh import handle, shift
    from ._volume import VolumeMesh

    if isinstance(V, VolumeMesh):
        if F is not None:
            if k is not None:
                raise TypeError("form_spectrum(volume_mesh, k, ...): no faces argument for a volume mesh")
            k = F
        return _polydec.volume_form_spectrum(V._m, int(degree), _convert.size(k, "k", 1), _convert.lumped_flag(mass),
                                             float(tolerance), int(max_iterations), bool(decompose), str(complex))
    V, F, k = shift(V, F, k)
    return _polydec.form_spectrum(handle(V, F), int(degree), _convert.size(k, "k", 1), _convert.lumped_flag(mass),
                                  float(tolerance), int(max_iterations), bool(decompose), str(complex),
                                  _convert.planarity(planarity))


def _pairs(evals, evecs):
    return np.asarray(evals, dtype=np.float64).reshape(-1), np.asarray(evecs, dtype=np.float64)


def hks_times(evals, evecs, n=100):
    """The standard heat kernel signature times: n log-spaced in [4 ln 10 / lambda_max, 4 ln 10 / lambda_1].

    >>> evals, evecs = polydec.spectrum(polydec.hex_sphere(2), 10)
    >>> t = polydec.hks_times(evals, evecs, 5)
    >>> len(t), bool(t[0] < t[-1])
    (5, True)
    """
    return _polydec.hks_times(*_pairs(evals, evecs), int(n))


def heat_kernel_signature(evals, evecs, times=None, n=100):
    """HKS(x, t) = sum_i exp(-lambda_i t) phi_i(x)^2 (Sun, Ovsjanikov, Guibas 2009), (|V|, |times|);
    times=None: hks_times(evals, evecs, n).

    >>> evals, evecs = polydec.spectrum(polydec.hex_sphere(2), 10)
    >>> polydec.heat_kernel_signature(evals, evecs).shape
    (320, 100)
    """
    e, U = _pairs(evals, evecs)
    t = hks_times(e, U, n) if times is None else np.asarray(times, dtype=np.float64).reshape(-1)
    return _polydec.heat_kernel_signature(e, U, t)


def wave_kernel_signature(evals, evecs, energies=None, sigma=None, n=100):
    """WKS(x, e) (Aubry, Schlickewei, Cremers 2011) at log energies e with Gaussian width sigma,
    (|V|, |energies|); energies=None: the standard n log energies and their sigma.

    >>> evals, evecs = polydec.spectrum(polydec.hex_sphere(2), 10)
    >>> polydec.wave_kernel_signature(evals, evecs, n=20).shape
    (320, 20)
    """
    e, U = _pairs(evals, evecs)
    if energies is None:
        energies, s = _polydec.wks_samples(e, U, int(n))
        sigma = s if sigma is None else sigma
    if sigma is None:
        raise ValueError("sigma is needed with explicit energies")
    return _polydec.wave_kernel_signature(e, U, np.asarray(energies, dtype=np.float64).reshape(-1), float(sigma))


def biharmonic_distance(evals, evecs, source, k=0):
    """Biharmonic distance (Lipman, Rustamov, Funkhouser 2010) from vertex `source` to every vertex
    with the first k eigenpairs (0: all) -> (|V|,).

    >>> evals, evecs = polydec.spectrum(polydec.hex_sphere(2), 10)
    >>> d = polydec.biharmonic_distance(evals, evecs, 0)
    >>> float(d[0]), bool(d.max() > 0)
    (0.0, True)
    """
    return _polydec.biharmonic_distance(*_pairs(evals, evecs), int(source), int(k))


def diffusion_distance(evals, evecs, t, source, k=0):
    """Diffusion distance at time t > 0 (Coifman, Lafon 2006) from vertex `source`, first k
    eigenpairs (0: all) -> (|V|,).

    >>> evals, evecs = polydec.spectrum(polydec.hex_sphere(2), 10)
    >>> d = polydec.diffusion_distance(evals, evecs, 0.1, 0)
    >>> float(d[0]), bool(d.max() > 0)
    (0.0, True)
    """
    return _polydec.diffusion_distance(*_pairs(evals, evecs), float(t), int(source), int(k))


def lowpass_filter(evals, evecs, lumped_mass, X, k):
    """Positions X (|V|, 3) projected onto the first k eigenvectors in the M inner product,
    sum_{i<k} phi_i phi_i^T M X (Vallet, Levy 2008); lumped_mass: the diagonal the spectrum used
    (a (|V|,) vector or a diagonal sparse matrix).

    >>> m = polydec.hex_sphere(2)
    >>> evals, evecs = polydec.spectrum(m, 4)
    >>> X1 = polydec.lowpass_filter(evals, evecs, polydec.lumped_mass(m), m.positions, 1)
    >>> bool(np.allclose(X1, X1[0]))
    True
    """
    import scipy.sparse

    m = lumped_mass.diagonal() if scipy.sparse.issparse(lumped_mass) else lumped_mass
    return _polydec.lowpass_filter(*_pairs(evals, evecs), np.asarray(m, dtype=np.float64).reshape(-1),
                                   _convert.positions(X), int(k))
