"""Statistics of Table 6: mean change of a_total against the baseline, its 95 % interval, p-value.

The paper says "t-test p-values compared to the baseline" without naming the test. Used here:
Welch's two-sample t-test (unequal variances, two-sided) of the controller's trials against the
baseline's trials of the same speed and load (:func:`scipy.stats.ttest_ind` with
``equal_var=False``). The change is 100 (mean(a) / mean(a_base) − 1) %; its confidence interval
is the Welch interval of the difference of means, divided by the baseline mean (the baseline
mean's own uncertainty in the denominator is neglected, a first-order interval).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats

__all__ = ["Comparison", "compare_with_baseline", "mean_interval"]


@dataclass(frozen=True)
class Comparison:
    """Change of a controller's mean against the baseline's.

    Attributes
    ----------
    change_percent : float
        100 (mean / baseline mean − 1).
    low_percent, high_percent : float
        95 % confidence interval of the change (Welch), in %.
    p_value : float
        Two-sided p-value of Welch's t-test (NaN if both samples have zero variance).
    """

    change_percent: float
    low_percent: float
    high_percent: float
    p_value: float


def _sample(values: object, name: str) -> np.ndarray:
    array = np.asarray(values, dtype=float).ravel()
    if array.size < 2 or not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must hold at least 2 finite numbers; got {array.size} values")
    return array


def mean_interval(values: object, confidence: float = 0.95) -> tuple[float, float, float]:
    """Mean and its Student-t confidence interval (low, high) of ``values``."""
    array = _sample(values, "values")
    mean = float(array.mean())
    half = float(
        stats.t.ppf(0.5 + confidence / 2, array.size - 1) * array.std(ddof=1) / np.sqrt(array.size)
    )
    return mean, mean - half, mean + half


def compare_with_baseline(
    baseline: object, treated: object, confidence: float = 0.95
) -> Comparison:
    """Welch comparison of ``treated`` with ``baseline`` (module notes).

    Parameters
    ----------
    baseline, treated : array_like
        a_total of the trials, m/s² (at least 2 each).
    confidence : float
        Level of the interval.

    Returns
    -------
    Comparison
    """
    base = _sample(baseline, "baseline")
    other = _sample(treated, "treated")
    va, vb = other.var(ddof=1) / other.size, base.var(ddof=1) / base.size
    difference = float(other.mean() - base.mean())
    standard_error = float(np.sqrt(va + vb))
    if standard_error > 0.0:
        dof = (va + vb) ** 2 / (va**2 / (other.size - 1) + vb**2 / (base.size - 1))
        half = float(stats.t.ppf(0.5 + confidence / 2, dof) * standard_error)
        p_value = float(stats.ttest_ind(other, base, equal_var=False).pvalue)
    else:
        half, p_value = 0.0, float("nan")
    scale = 100.0 / float(base.mean())
    return Comparison(
        difference * scale, (difference - half) * scale, (difference + half) * scale, p_value
    )
