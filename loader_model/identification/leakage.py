r"""Seal leakage and fluid compressibility from pump flow and motion (section 4.1.2, Table 5).

Eq. 36 rearranged to be linear in its coefficients, as the paper's Eq. 48 (used as printed):

.. math::

    Q_A - \dot{x}_{act} A_p = C + \frac{1}{K_{oil}} V_A \dot{p}_A
        + k_{Lp} (p_A - p_B) + k_{Lv} \dot{x}_{act}

with Q_A = V_p n the pump flow to both cylinders (displacement × shaft speed), A_p the total
piston area, V_A the total piston-side volume at the current position (:mod:`.equivalent`), and
C a constant flow offset: the bias of the flow estimate from the swash-plate angle, not a plant
parameter.

Sign convention: Eq. 47 prints Q_L = k_Lp (p_A − p_B) − k_Lv ẋ, but substituting it into Eq. 36
gives −k_Lv ẋ on the right of Eq. 48, which prints +k_Lv ẋ. Table 5's k_Lv = −5.0e-4 m² was
identified in the form of Eq. 48, so this package (and the team's plant) uses
Q_L = k_Lp (p_A − p_B) + k_Lv ẋ.

The fit is robust (Tukey bisquare IRLS, :mod:`.regression`), as the paper's: the flow estimate
and the numerical derivatives carry noise and occasional gross errors. K_oil is reported as the
reciprocal of the fitted 1/K_oil; its interval is the reciprocal of that of 1/K_oil (a monotone
map, exact for the interval) and is unbounded if the latter contains zero.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from loader_model.identification.regression import LinearFit, robust_linear_fit

__all__ = ["LEAKAGE_NAMES", "LeakageFit", "fit_leakage", "leakage_design"]

#: Coefficient order of the Eq. 48 regression: C [m³/s], 1/K_oil [1/Pa], k_Lp [m³/(s·Pa)],
#: k_Lv [m²].
LEAKAGE_NAMES = ("C", "inv_K_oil", "k_Lp", "k_Lv")


def leakage_design(
    volume_a_m3: np.ndarray, dp_a: np.ndarray, p_a: np.ndarray, p_b: np.ndarray, v: np.ndarray
) -> np.ndarray:
    """Regressors of Eq. 48: columns 1, V_A ṗ_A, p_A − p_B, ẋ (shape (n, 4))."""
    return np.column_stack((np.ones_like(v), volume_a_m3 * dp_a, p_a - p_b, v))


@dataclass(frozen=True)
class LeakageFit:
    """Result of :func:`fit_leakage`: the Eq. 48 regression and K_oil with its interval.

    Attributes
    ----------
    regression : LinearFit
        Coefficients :data:`LEAKAGE_NAMES` with R², s, intervals.
    bulk_modulus : float
        K_oil = 1 / (1/K_oil) in Pa.
    bulk_modulus_interval : (float, float)
        Interval of K_oil in Pa (reciprocal of the 1/K_oil interval; inf if it contains 0).
    """

    regression: LinearFit
    bulk_modulus: float
    bulk_modulus_interval: tuple[float, float]


def fit_leakage(
    flow_m3_s: np.ndarray,
    v: np.ndarray,
    area_m2: float,
    volume_a_m3: np.ndarray,
    dp_a: np.ndarray,
    p_a: np.ndarray,
    p_b: np.ndarray,
    *,
    robust: bool = True,
    lags: int = 0,
    level: float = 0.95,
) -> LeakageFit:
    """Identify C, 1/K_oil, k_Lp, k_Lv of Eq. 48 (Table 5).

    Parameters
    ----------
    flow_m3_s : numpy.ndarray
        Pump flow Q_A to the piston sides in m³/s.
    v : numpy.ndarray
        Extension rate ẋ_act in m/s.
    area_m2 : float
        Total piston area A_p in m².
    volume_a_m3 : numpy.ndarray
        Total piston-side volume V_A in m³.
    dp_a : numpy.ndarray
        Pressure rate ṗ_A in Pa/s.
    p_a, p_b : numpy.ndarray
        Chamber pressures in Pa.
    robust : bool
        Bisquare IRLS (True, the paper's choice) or ordinary least squares (for comparison).
    lags : int
        Bartlett lags of the covariance.
    level : float
        Confidence level.
    """
    arrays = [np.asarray(a, dtype=float) for a in (flow_m3_s, v, volume_a_m3, dp_a, p_a, p_b)]
    flow, v, volume, dp_a, p_a, p_b = arrays
    if flow.size < 10:
        raise ValueError(f"leakage fit needs at least 10 samples; got {flow.size}")
    fit = robust_linear_fit(
        leakage_design(volume, dp_a, p_a, p_b, v),
        flow - area_m2 * v,
        LEAKAGE_NAMES,
        robust=robust,
        lags=lags,
        level=level,
    )
    i = LEAKAGE_NAMES.index("inv_K_oil")
    low, high = fit.low[i], fit.high[i]
    interval = (1.0 / high, 1.0 / low) if low > 0.0 else (1.0 / high, np.inf)
    if high <= 0.0:
        interval = (-np.inf, np.inf)
    return LeakageFit(fit, float(1.0 / fit.values[i]), (float(interval[0]), float(interval[1])))
