"""Point descriptors from the Laplace–Beltrami spectrum: HKS, WKS and GPS.

All three are functions of the eigenpairs ``(lam_i, phi_i)`` of ``W phi = lam A phi`` with
A-orthonormal ``phi`` (docs/maths.md, "The A inner product"), so they are invariant under rigid
motions and vertex permutations, and (up to discretisation) under isometric deformations:

* **HKS** (Sun, Ovsjanikov, Guibas 2009): ``h_t(x) = sum_i exp(-lam_i t) phi_i(x)^2``, the heat
  kept at ``x`` after time ``t``. On the unit sphere ``h_t = sum_l (2l+1)/(4 pi) exp(-l(l+1) t)``
  at every point.
* **WKS** (Aubry, Schlickewei, Cremers 2011): a log-normal band-pass filter of width ``sigma``
  around the log-energy ``e``, normalised per energy: ``w_e(x) = sum_i g_e(lam_i) phi_i(x)^2 /
  sum_i g_e(lam_i)`` with ``g_e(lam) = exp(-(e - log lam)^2 / (2 sigma^2))``. ``lam_0 = 0`` is
  skipped (its log is undefined and the constant carries no information).
* **GPS** (Rustamov 2007): ``x -> (phi_1(x)/sqrt(lam_1), phi_2(x)/sqrt(lam_2), ...)``, an
  embedding whose Euclidean distances approximate the commute-time distance. Unlike HKS and WKS
  it depends on the signs of the eigenvectors (and on rotations inside repeated eigenvalues).

Default times and energies are derived from the spectrum itself, so they follow the scale of the
shape: scaling a surface by ``s`` scales every ``lam`` by ``1/s^2`` and the default times by
``s^2``, and HKS changes only by the factor ``1/s^2`` of ``phi^2``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Integer, Number, Relation, Satisfies, validated
from ..geometry._mesh import MeshError
from ..spectral._spectrum import Spectrum

__all__ = ["hks", "wks", "gps", "hks_times", "wks_energies"]

# h_t is dominated by a single term exp(-lam t) once exp(-lam t) ~ 1e-4 of the rest:
# t = 4 ln(10) / lam is where the term of eigenvalue lam has decayed to 1e-4 (Sun et al. 2009).
_DECADES = 4.0 * np.log(10.0)


def _spectrum(minimum: int) -> tuple[Satisfies, Satisfies]:
    """The constraints on ``spectrum``: a Spectrum with at least ``minimum`` eigenpairs."""
    return (
        Satisfies(lambda s: isinstance(s, Spectrum),
                  message="spectrum must be a Spectrum (from lbo_notebooks.eigenbasis), got {type}."),
        Satisfies(lambda s: s.k >= minimum, message=f"this descriptor needs at least {minimum} eigenpairs; "
                  f"compute eigenbasis(mesh, k) with k >= {minimum}."),
    )


def _check_connected(spectrum: Spectrum) -> Spectrum:
    """The data check that stays in the body: a second eigenvalue of 0 means several components."""
    if spectrum.values[1] <= 1e-9 * abs(spectrum.values[-1]):  # a zero eigenvalue up to round-off
        raise MeshError(
            "the second eigenvalue is not positive: the mesh has several connected components. "
            "Keep the largest one with lbo_notebooks.clean_mesh(mesh, keep_largest_component=True)."
        )
    return spectrum


def _grid(values: ArrayLike) -> NDArray[np.float64]:
    return np.atleast_1d(np.asarray(values, dtype=np.float64))


_GRID = Satisfies(
    lambda v: (a := _grid(v)).ndim == 1 and a.size > 0 and bool(np.all(np.isfinite(a))),
    convert=_grid,
    none=True,
    message=lambda name, v: f"{name} must be a non-empty 1-D sequence of finite numbers, got shape {_grid(v).shape}.",
)
_POSITIVE = Number(0, open_low=True)


@validated(spectrum=_spectrum(2), n_times=Integer(1))
def hks_times(spectrum: Spectrum, n_times: int = 16) -> NDArray[np.float64]:
    """Default HKS times: ``n_times`` log-spaced between ``4 ln 10 / lam_max`` and ``4 ln 10 / lam_1``.

    Below the first time every eigenfunction has contributed and the HKS is nearly the local
    Gaussian curvature; beyond the last only ``phi_0`` and ``phi_1`` are left.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> t = hks_times(eigenbasis(shapes.icosphere(3), 16), 4)
    >>> bool(abs(t[-1] - 4 * np.log(10) / 2) < 0.05)   # lam_1 = 2 on the unit sphere
    True
    """
    _check_connected(spectrum)
    lam = spectrum.values
    return np.geomspace(_DECADES / lam[-1], _DECADES / lam[1], n_times)


@validated(
    spectrum=_spectrum(2),
    times=(_GRID, Satisfies(lambda t: t is None or bool(np.all(t > 0)), message="HKS times must be positive.")),
)
def hks(spectrum: Spectrum, times: ArrayLike | None = None, *, n_times: int = 16) -> NDArray[np.float64]:
    """Heat kernel signature ``h_t(x) = sum_i exp(-lam_i t) phi_i(x)^2``, shape (n, len(times)).

    Parameters
    ----------
    spectrum : Spectrum
        Eigenpairs with A-orthonormal vectors (all ``k`` are used: truncation error is
        ``exp(-lam_k t)``, negligible for the default times).
    times : array-like, optional
        Positive diffusion times. Default :func:`hks_times` with ``n_times`` values.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> h = hks(eigenbasis(shapes.icosphere(4), 49), [0.5])
    >>> exact = sum((2 * l + 1) / (4 * np.pi) * np.exp(-l * (l + 1) * 0.5) for l in range(7))
    >>> bool(abs(h / exact - 1).max() < 1e-2)
    True
    """
    t = hks_times(spectrum, n_times) if times is None else times
    _check_connected(spectrum)
    lam = np.maximum(spectrum.values, 0.0)  # lam_0 is 0 up to round-off
    return (spectrum.vectors**2) @ np.exp(-np.outer(lam, t))


@validated(spectrum=_spectrum(3), n_energies=Integer(1), sigma_factor=_POSITIVE)
def wks_energies(
    spectrum: Spectrum, n_energies: int = 100, *, sigma_factor: float = 7.0
) -> tuple[NDArray[np.float64], float]:
    """Default WKS log-energies and width: log-spaced over ``(log lam_1, log lam_max)``.

    The grid is shrunk by ``2 sigma`` at both ends so each band sees eigenvalues on both sides;
    ``sigma = sigma_factor * step`` (Aubry et al. 2011).

    Returns
    -------
    energies : ndarray, shape (n_energies,)
    sigma : float
    """
    _check_connected(spectrum)
    lo, hi = np.log(spectrum.values[1]), np.log(spectrum.values[-1])
    sigma = sigma_factor * (hi - lo) / n_energies
    return np.linspace(lo + 2 * sigma, hi - 2 * sigma, n_energies), float(sigma)


@validated(
    spectrum=_spectrum(3),
    energies=_GRID,
    sigma=(
        Number(0, open_low=True, none=True),
        Relation(lambda energies, sigma, **_: energies is None or sigma is not None,
                 "with explicit energies pass sigma too (a few grid steps in log-energy)."),
    ),
)
def wks(
    spectrum: Spectrum,
    energies: ArrayLike | None = None,
    *,
    n_energies: int = 100,
    sigma: float | None = None,
) -> NDArray[np.float64]:
    """Wave kernel signature, shape (n, len(energies)).

    ``w_e(x) = sum_{i>=1} g_e(lam_i) phi_i(x)^2 / sum_{i>=1} g_e(lam_i)``,
    ``g_e(lam) = exp(-(e - log lam)^2 / (2 sigma^2))``.

    Parameters
    ----------
    spectrum : Spectrum
    energies : array-like, optional
        Log-energies ``e``. Default :func:`wks_energies` with ``n_energies`` values (then the
        default ``sigma`` comes with them).
    sigma : float, optional
        Band width in log-energy, a few grid steps. Default from :func:`wks_energies`; required
        with explicit ``energies``.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(3), 36)
    >>> w = wks(s, n_energies=8)
    >>> w.shape, bool(np.ptp(w, axis=0).max() < 0.05 * w.max())   # nearly constant on the sphere
    ((642, 8), True)
    """
    _check_connected(spectrum)
    if energies is None:
        e, default_sigma = wks_energies(spectrum, n_energies)
        sigma = default_sigma if sigma is None else sigma
    else:
        e = energies
    assert sigma is not None  # with explicit energies the table asks for sigma
    log_lam = np.log(spectrum.values[1:])
    g = np.exp(-((e[None, :] - log_lam[:, None]) ** 2) / (2.0 * sigma**2))
    return (spectrum.vectors[:, 1:] ** 2) @ (g / g.sum(axis=0))


@validated(
    spectrum=_spectrum(2),
    k=Integer(2, lambda spectrum, **_: spectrum.k, none=True,
              what=lambda spectrum, **_: f"an integer between 2 and spectrum.k={spectrum.k}"),
)
def gps(spectrum: Spectrum, k: int | None = None) -> NDArray[np.float64]:
    """Global point signature ``(phi_1/sqrt(lam_1), ..., phi_{k-1}/sqrt(lam_{k-1}))``, shape (n, k-1).

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(3), 10)
    >>> gps(s, 4).shape
    (642, 3)
    """
    _check_connected(spectrum)
    if k is None:
        k = spectrum.k
    return spectrum.vectors[:, 1:k] / np.sqrt(spectrum.values[1:k])
