r"""Regression statistics shared by the estimators: fits, R², s, covariances and intervals.

Two estimators:

- ordinary least squares (friction, Eq. 46, as the paper: "multiple least-squares regression");
- robust regression by iteratively reweighted least squares with **Tukey's bisquare** weights
  (tuning constant 4.685, 95 % efficiency under Gaussian noise), started from a Huber fit
  (c = 1.345, convex, so the start is unique) and with the scale re-estimated every iteration
  from the median absolute deviation of the residuals, σ = MAD / 0.6745 (leakage, Eq. 48; the
  paper: "a robust regression algorithm was used"). Bisquare is the default of MATLAB's
  ``robustfit``, the likely tool of a 2009 study; being redescending, it gives gross outliers
  (sensor drop-outs) zero weight, where Huber's bounded weight still lets one-sided outliers
  bias the fit.

Covariances are sandwich estimates for M-estimators (Huber 1981, sec. 7.6),

.. math::

    \widehat{\mathrm{Cov}}(\hat\beta) = \sigma^2 B^{-1} M B^{-1}, \quad
    B = \sum_i \psi'(u_i) x_i x_i^\top, \quad
    M = \frac{n}{n - p} \Big(\Gamma_0 + \sum_{l=1}^{L} \big(1 - \tfrac{l}{L+1}\big)
        (\Gamma_l + \Gamma_l^\top)\Big), \quad
    \Gamma_l = \sum_i \psi(u_i)\psi(u_{i-l}) x_i x_{i-l}^\top,

u_i = r_i/σ, with ψ(u) = u (least squares) or the robust ψ. The Bartlett-weighted lags
(Newey and West 1987) up to L account for residuals that are correlated over L samples, as
filtered signals are (:mod:`.pipeline` takes L = four filter windows); L = 0 is the classic
formula.
Intervals are ±t_{n−p, 1−α/2} standard errors.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import stats

__all__ = [
    "BISQUARE_TUNING",
    "HUBER_TUNING",
    "LinearFit",
    "bisquare_psi",
    "confidence_halfwidth",
    "fit_summary",
    "huber_psi",
    "mad_scale",
    "robust_linear_fit",
    "sandwich_covariance",
]

#: Tukey bisquare tuning constant (95 % Gaussian efficiency).
BISQUARE_TUNING = 4.685
#: Huber tuning constant (95 % Gaussian efficiency).
HUBER_TUNING = 1.345
_MAD_TO_SIGMA = 0.6744897501960817  # Φ⁻¹(3/4)


def huber_psi(u: np.ndarray, c: float = HUBER_TUNING) -> tuple[np.ndarray, np.ndarray]:
    """Huber's ψ(u) = clip(u, −c, c) and its derivative ψ'(u)."""
    return np.clip(u, -c, c), (np.abs(u) <= c).astype(float)


def bisquare_psi(u: np.ndarray, c: float = BISQUARE_TUNING) -> tuple[np.ndarray, np.ndarray]:
    """Tukey's ψ(u) = u (1 − (u/c)²)² for |u| < c, else 0, and its derivative ψ'(u)."""
    z = u / c
    inside = np.abs(z) < 1.0
    psi = np.where(inside, u * (1.0 - z**2) ** 2, 0.0)
    dpsi = np.where(inside, (1.0 - z**2) * (1.0 - 5.0 * z**2), 0.0)
    return psi, dpsi


def mad_scale(residuals: np.ndarray) -> float:
    """Robust scale σ = median(|r − median r|) / 0.6745 (consistent for Gaussian noise)."""
    r = np.asarray(residuals, dtype=float)
    return float(np.median(np.abs(r - np.median(r))) / _MAD_TO_SIGMA)


def sandwich_covariance(
    design: np.ndarray, psi: np.ndarray, dpsi: np.ndarray, scale: float, lags: int = 0
) -> np.ndarray:
    """Covariance σ² B⁻¹ M B⁻¹ of an M-estimate (see the module docstring), Bartlett lags."""
    n, p = design.shape
    bread = design.T @ (dpsi[:, None] * design)
    scores = psi[:, None] * design
    meat = scores.T @ scores
    for lag in range(1, min(lags, n - 1) + 1):
        gamma = scores[lag:].T @ scores[:-lag]
        meat += (1.0 - lag / (lags + 1.0)) * (gamma + gamma.T)
    meat *= n / (n - p)
    bread_inv = np.linalg.inv(bread)
    return scale**2 * bread_inv @ meat @ bread_inv


def confidence_halfwidth(standard_errors: np.ndarray, dof: int, level: float) -> np.ndarray:
    """Half-width t_{dof, (1+level)/2} · standard error of two-sided intervals."""
    return stats.t.ppf(0.5 + level / 2.0, dof) * np.asarray(standard_errors)


@dataclass(frozen=True)
class LinearFit:
    """Coefficients of a regression with its statistics (Tables 4, 5).

    Attributes
    ----------
    names : tuple of str
        Coefficient names, in the order of ``values``.
    values, covariance : numpy.ndarray
        Estimates and their covariance (sandwich, see module docstring).
    low, high : numpy.ndarray
        Confidence interval bounds at ``level``.
    level : float
        Confidence level of the intervals, e.g. 0.95.
    r_squared : float
        1 − Σ r² / Σ (y − ȳ)² of the fit's residuals r (all samples).
    s : float
        Standard deviation of the residuals, sqrt(Σ r² / (n − p)); for a robust fit the robust
        scale σ (MAD) is ``scale``.
    scale : float
        The residual scale used for the weights and the covariance.
    residuals : numpy.ndarray
        y − model.
    weights : numpy.ndarray
        Final IRLS weights (all 1 for least squares).
    method : str
        "least squares" or the robust loss used.
    """

    names: tuple[str, ...]
    values: np.ndarray
    covariance: np.ndarray
    low: np.ndarray
    high: np.ndarray
    level: float
    r_squared: float
    s: float
    scale: float
    residuals: np.ndarray
    weights: np.ndarray
    method: str

    @property
    def standard_errors(self) -> np.ndarray:
        """Square roots of the covariance diagonal."""
        return np.sqrt(np.diag(self.covariance))

    def value(self, name: str) -> float:
        """The estimate named ``name``."""
        return float(self.values[self.names.index(name)])


def fit_summary(
    names: Sequence[str],
    y: np.ndarray,
    values: np.ndarray,
    residuals: np.ndarray,
    covariance: np.ndarray,
    *,
    scale: float,
    weights: np.ndarray,
    method: str,
    level: float,
) -> LinearFit:
    """Bundle estimates with R², s and t-intervals into a :class:`LinearFit`."""
    n, p = y.size, len(names)
    half = confidence_halfwidth(np.sqrt(np.diag(covariance)), n - p, level)
    total = float(np.sum((y - np.mean(y)) ** 2))
    return LinearFit(
        names=tuple(names),
        values=values,
        covariance=covariance,
        low=values - half,
        high=values + half,
        level=level,
        r_squared=1.0 - float(residuals @ residuals) / total,
        s=float(np.sqrt(residuals @ residuals / (n - p))),
        scale=scale,
        residuals=residuals,
        weights=weights,
        method=method,
    )


def robust_linear_fit(
    design: np.ndarray,
    y: np.ndarray,
    names: Sequence[str],
    *,
    robust: bool = True,
    lags: int = 0,
    level: float = 0.95,
    max_iterations: int = 100,
    tolerance: float = 1e-10,
) -> LinearFit:
    """Fit y ≈ X β by bisquare IRLS (``robust``) or ordinary least squares.

    Columns of X are scaled to unit norm inside the solver (the leakage regressors differ by
    15 orders of magnitude); results are in the original units.

    Parameters
    ----------
    design : numpy.ndarray
        X, shape (n, p).
    y : numpy.ndarray
        Observations, shape (n,).
    names : sequence of str
        p coefficient names.
    robust : bool
        Bisquare IRLS from a Huber start (True) or least squares (False).
    lags : int
        Bartlett lags of the covariance (0: independent residuals).
    level : float
        Confidence level of the intervals.
    """
    design = np.asarray(design, dtype=float)
    y = np.asarray(y, dtype=float)
    norms = np.linalg.norm(design, axis=0)
    if np.any(norms == 0.0):
        raise ValueError(f"a regressor is identically zero: {np.asarray(names)[norms == 0.0]}")
    x = design / norms
    rank = np.linalg.matrix_rank(x)
    if rank < x.shape[1]:
        raise ValueError(
            f"the regressors {', '.join(names)} are linearly dependent (rank {rank} of "
            f"{x.shape[1]}): the signals they are built from do not vary independently in this "
            "record (a constant pressure, position or flow); record a run that moves them"
        )
    beta = np.linalg.lstsq(x, y, rcond=None)[0]
    weights = np.ones_like(y)
    scale = float(np.sqrt(np.sum((y - x @ beta) ** 2) / (y.size - x.shape[1])))
    psi_function = None
    if robust:
        for psi_function in (huber_psi, bisquare_psi):
            for _ in range(max_iterations):
                residuals = y - x @ beta
                scale = mad_scale(residuals)
                if scale == 0.0:
                    break
                u = residuals / scale
                psi, _ = psi_function(u)
                weights = np.where(u != 0.0, psi / np.where(u != 0.0, u, 1.0), 1.0)
                root = np.sqrt(weights)
                new = np.linalg.lstsq(x * root[:, None], y * root, rcond=None)[0]
                step = np.max(np.abs(new - beta)) / max(np.max(np.abs(beta)), 1e-300)
                beta = new
                if step < tolerance:
                    break
    residuals = y - x @ beta
    if psi_function is None:
        psi, dpsi = residuals / scale if scale > 0 else residuals, np.ones_like(y)
    else:
        psi, dpsi = psi_function(residuals / scale if scale > 0 else residuals)
    covariance = sandwich_covariance(x, psi, dpsi, scale, lags) / np.outer(norms, norms)
    return fit_summary(
        names,
        y,
        beta / norms,
        residuals,
        covariance,
        scale=scale,
        weights=weights,
        method="robust IRLS, Tukey bisquare c = 4.685, MAD scale" if robust else "least squares",
        level=level,
    )
