r"""Seal friction of the lift cylinders from pressures and motion (section 4.1.1, Table 4).

Measured friction (Eq. 44 corrected). Eq. 31 gives the actuator force
F_act = A_p (p_A − α p_B) − F_f; Newton's law for the equivalent load (F_L pushing the piston
in) gives A_p (p_A − α p_B) − F_f − F_L = m_eq ẍ, hence

.. math:: F_f = A_p (p_A - \alpha p_B) - F_L - m_{eq} \ddot{x}_{act}.

**Erratum:** Eq. 44 as printed, F_f = m_eq ẍ + F_L − A_p (p_A − α p_B), has the opposite sign
of Eq. 31; with it the identified friction would oppose Table 4's positive f_v.

Friction model (Eq. 46 as read in errata 10): the pressure-dependent Coulomb part
takes the sign of the velocity with the same tanh as the Stribeck part,

.. math::

    F_f = \big(f_s e^{-\tau_s |v|} + f_C p_A\big) \tanh(\gamma v) + f_v v,

v = ẋ_act the extension rate in m/s (positive extending), p_A the piston-side gauge pressure in
Pa. Printed literally, f_C p_A would be a force of the same sign whatever the motion.

The law is not written again here: it is the plant's
:func:`loader_model.plant.components.seal_friction`, evaluated through a CasADi Function with
its gradient by automatic differentiation, so estimator and plant share one model.

For fixed (τ_s, γ) the model is linear in (f_s, f_C, f_v): the estimator projects those out
(variable projection, Golub and Pereyra 1973), searches (log τ_s, log γ) first on a grid then by
``scipy.optimize.least_squares`` on the projected residual, and polishes all five coefficients
together by least squares (minimising the sum of squared errors, as the paper). Covariance and
intervals come from the Jacobian of all five at the optimum (:mod:`.regression`, with Bartlett
lags for the filter-correlated residuals).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache, lru_cache

import casadi as ca
import numpy as np
from scipy.optimize import least_squares

from loader_model.identification.regression import (
    LinearFit,
    fit_summary,
    sandwich_covariance,
)

__all__ = [
    "FRICTION_NAMES",
    "fit_friction",
    "friction_force",
    "friction_jacobian",
    "measured_friction",
]

#: Coefficient order of the friction fit: f_s [N], tau_s [s/m], gamma [s/m], f_c [N/Pa],
#: f_v [N s/m] (the order of Table 4).
FRICTION_NAMES = ("f_s", "tau_s", "gamma", "f_c", "f_v")


def measured_friction(
    area_m2: float,
    alpha: float,
    p_a: np.ndarray,
    p_b: np.ndarray,
    load_force_n: np.ndarray,
    inertial_force_n: np.ndarray,
) -> np.ndarray:
    """F_f = A_p (p_A − α p_B) − F_L − m_eq ẍ in N (Eq. 44, sign corrected from Eq. 31).

    ``inertial_force_n`` is m_eq ẍ, or with the lever at each sample
    :meth:`~.equivalent.EquivalentCylinder.inertial_force`.
    """
    return area_m2 * (p_a - alpha * p_b) - load_force_n - inertial_force_n


def _thin(smooth: Smoother, step: int) -> Smoother:
    return lambda columns: smooth(columns)[::step]


@cache
def _law() -> ca.Function:
    """The plant's friction law and its gradient in the coefficients, one sample (SX)."""
    from loader_model.plant.components import seal_friction

    c = ca.SX.sym("c", 5)  # FRICTION_NAMES order
    v, p_a = ca.SX.sym("v"), ca.SX.sym("p_a")
    force = seal_friction(c[0], c[1], c[2], c[3], c[4], p_a, v)
    return ca.Function("seal_friction_law", [c, v, p_a], [force, ca.gradient(force, c)])


@lru_cache(maxsize=8)
def _mapped(n: int) -> ca.Function:
    """:func:`_law` over n samples, the coefficients shared (CasADi ``map``, serial)."""
    return _law().map("seal_friction_law_map", "serial", n, [0], [])


def _evaluate(coefficients: np.ndarray, v: np.ndarray, p_a: np.ndarray) -> list[np.ndarray]:
    """(F_f (n,), gradient (5, n)) at n samples, through a buffer (no conversions)."""
    v = np.ascontiguousarray(v, dtype=float).ravel()
    p_a = np.ascontiguousarray(p_a, dtype=float).ravel()
    c = np.ascontiguousarray(coefficients, dtype=float)
    force, gradient = np.empty(v.size), np.empty((v.size, 5))  # (5, n) column-major
    buffer, trigger = _mapped(v.size).buffer()
    for i, array in enumerate((c, v, p_a)):
        buffer.set_arg(i, memoryview(array))
    for i, array in enumerate((force, gradient)):
        buffer.set_res(i, memoryview(array))
    trigger()
    return [force, gradient.T]


def _basis(v: np.ndarray, p_a: np.ndarray, tau_s: float, gamma: float) -> np.ndarray:
    """Columns ∂F_f/∂(f_s, f_C, f_v): F_f is linear in them (exact for any coefficients)."""
    gradient = _evaluate(np.array([1.0, tau_s, gamma, 1.0, 1.0]), v, p_a)[1]
    return gradient[[0, 3, 4]].T


def friction_force(coefficients: np.ndarray, v: np.ndarray, p_a: np.ndarray) -> np.ndarray:
    """F_f of Eq. 46 (errata 10 reading) for coefficients in :data:`FRICTION_NAMES` order.

    Evaluates the plant's own law (:func:`loader_model.plant.components.seal_friction`).
    """
    return _evaluate(coefficients, v, p_a)[0]


def friction_jacobian(coefficients: np.ndarray, v: np.ndarray, p_a: np.ndarray) -> np.ndarray:
    """∂F_f/∂(f_s, τ_s, γ, f_C, f_v) of the plant's law (CasADi AD), shape (n, 5)."""
    return _evaluate(coefficients, v, p_a)[1].T


Smoother = Callable[[np.ndarray], np.ndarray]


def _identity(columns: np.ndarray) -> np.ndarray:
    return columns


def _projected(
    log_nonlinear: np.ndarray, v: np.ndarray, p_a: np.ndarray, f: np.ndarray, smooth: Smoother
) -> tuple[np.ndarray, np.ndarray]:
    tau_s, gamma = np.exp(log_nonlinear)
    basis = smooth(_basis(v, p_a, tau_s, gamma))
    linear = np.linalg.lstsq(basis, f, rcond=None)[0]
    return linear, f - basis @ linear


def fit_friction(
    v: np.ndarray,
    p_a: np.ndarray,
    friction: np.ndarray,
    *,
    smooth: Smoother | None = None,
    lags: int = 0,
    level: float = 0.95,
    tau_s_range: tuple[float, float] = (1.0, 1000.0),
    gamma_range: tuple[float, float] = (0.1, 1000.0),
) -> LinearFit:
    """Identify (f_s, τ_s, γ, f_C, f_v) of Eq. 46 from measured friction (Table 4).

    Parameters
    ----------
    v : numpy.ndarray
        Cylinder extension rate ẋ_act in m/s.
    p_a : numpy.ndarray
        Piston-side gauge pressure in Pa.
    friction : numpy.ndarray
        Measured friction force F_f in N (:func:`measured_friction`).
    smooth : callable, optional
        Linear filter applied to the model's columns (shape (n, k) -> (m, k)) before comparing
        with ``friction`` (length m): the filter the measured friction went through, so that
        model and data are filtered alike (:mod:`.pipeline`). ``v`` and ``p_a`` then have the
        unfiltered length n. Default: none (all arrays of one length).
    lags : int
        Bartlett lags of the covariance (:mod:`.pipeline` uses four derivative-filter windows).
    level : float
        Confidence level of the intervals.
    tau_s_range, gamma_range : (float, float)
        Search ranges of τ_s and γ in s/m (a log-spaced grid, then a bounded local search).

    Returns
    -------
    LinearFit
        Coefficients in :data:`FRICTION_NAMES` order (SI units), R², s, intervals.
    """
    v, p_a, friction = (np.asarray(a, dtype=float) for a in (v, p_a, friction))
    smooth = smooth or _identity
    if friction.size < 10:
        raise ValueError(f"friction fit needs at least 10 samples; got {friction.size}")
    if np.ptp(np.sign(v)) < 2.0:
        raise ValueError("friction fit needs both extending (v > 0) and retracting (v < 0) motion")
    coarse = _identity if smooth is _identity else _thin(smooth, max(1, friction.size // 5000))
    step = max(1, friction.size // 5000)  # the grid only needs a rough start
    lo = np.log([tau_s_range[0], gamma_range[0]])
    hi = np.log([tau_s_range[1], gamma_range[1]])
    best = (np.inf, None)
    for log_tau in np.linspace(lo[0], hi[0], 13):
        for log_gamma in np.linspace(lo[1], hi[1], 15):
            point = np.array([log_tau, log_gamma])
            if smooth is _identity:
                _, r = _projected(point, v[::step], p_a[::step], friction[::step], _identity)
            else:
                _, r = _projected(point, v, p_a, friction[::step], coarse)
            cost = float(r @ r)
            if cost < best[0]:
                best = (cost, point)
    search = least_squares(
        lambda q: _projected(q, v, p_a, friction, smooth)[1],
        best[1],
        bounds=(lo, hi),
        x_scale=1.0,
        xtol=1e-12,
        ftol=1e-12,
        gtol=1e-12,
    )
    linear, _ = _projected(search.x, v, p_a, friction, smooth)
    tau_s, gamma = np.exp(search.x)
    start = np.array([linear[0], tau_s, gamma, linear[1], linear[2]])
    typical = np.abs(start) + np.array([1.0, 1e-3, 1e-3, 1e-12, 1.0])

    def model(c: np.ndarray) -> np.ndarray:
        return smooth(friction_force(c, v, p_a)[:, None])[:, 0]

    polish = least_squares(
        lambda c: model(c * typical) - friction,
        start / typical,
        jac=lambda c: smooth(friction_jacobian(c * typical, v, p_a)) * typical,
        method="lm",
        xtol=1e-15,
        ftol=1e-15,
        gtol=1e-15,
    )
    values = polish.x * typical
    residuals = friction - model(values)
    jacobian = smooth(friction_jacobian(values, v, p_a))
    n = friction.size
    scale = float(np.sqrt(residuals @ residuals / (n - 5)))
    column = np.linalg.norm(jacobian, axis=0)
    covariance = sandwich_covariance(
        jacobian / column, residuals / scale if scale > 0 else residuals, np.ones(n), scale, lags
    ) / np.outer(column, column)
    return fit_summary(
        FRICTION_NAMES,
        friction,
        values,
        residuals,
        covariance,
        scale=scale,
        weights=np.ones(n),
        method="least squares, variable projection over (tau_s, gamma)"
        + "".join(
            f"; {name} at its search bound {bound:g} s/m (interval not meaningful)"
            for name, value, low, high in zip(
                ("tau_s", "gamma"), np.exp(search.x), np.exp(lo), np.exp(hi), strict=True
            )
            for bound in (low, high)
            if abs(np.log(value / bound)) < 1e-6
        )
        + ("" if smooth is _identity else ", model filtered like the data"),
        level=level,
    )
