"""Trial-to-trial scatter of Table 6: the one the paper's Δ and p imply, and the model's.

Table 6 gives, per cell, the mean change Δ of a_total against the baseline and the p-value of a
t-test over n = 4 trials per group. With the assumptions below, Δ and p fix the trial-to-trial
standard deviation s of a_total that the machine showed, in percent of the baseline mean:

.. math::

    s = \\frac{|\\Delta|}{t_{1 - p/2,\\,\\nu} \\sqrt{2 / n}}, \\qquad \\nu = 2 n - 2 = 6,

:math:`t_{q,\\nu}` the Student quantile. Assumptions (the paper names none of them):

- Welch's two-sample t-test, two-sided (as :mod:`~loader_model.experiments.statistics` uses);
- equal group sizes, n = 4 trials of the controller and 4 of the baseline (section 5.3);
- equal variances in both groups, so that Welch's degrees of freedom are exactly 2 n − 2 and its
  standard error is s √(2 / n); with unequal variances s is their root mean square;
- normal trial-to-trial variation, so that the statistic follows Student's t;
- Δ in percent of the baseline mean, so s is too (the baseline mean's own uncertainty is
  neglected, as in the paper's change).

Table 6 prints p to four decimals: a printed p stands for [p − 5e-5, p + 5e-5], which gives s a
range (:attr:`ImpliedScatter.low_percent`, :attr:`ImpliedScatter.high_percent`). A printed
p = 0.0000 says only p < 5e-5: s is then an upper bound (:attr:`ImpliedScatter.upper_bound`).

The model's side (:func:`model_scatter`) takes many trials per group: the pooled standard
deviation in the same units, and the mean change with its standard error from the delta method
on the ratio of the means.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import stats

__all__ = [
    "PAPER_TRIALS",
    "ImpliedScatter",
    "ModelScatter",
    "implied_scatter",
    "model_scatter",
    "paper_implied_scatter",
]

#: Trials per group of the paper's Table 6 (section 5.3).
PAPER_TRIALS = 4
#: Half the last printed digit of Table 6's p-values.
_P_ROUNDING = 5e-5


@dataclass(frozen=True)
class ImpliedScatter:
    """The trial standard deviation that a Table 6 cell's Δ and p imply (module notes).

    Attributes
    ----------
    sd_percent : float
        s at the printed p (at p = 5e-5 when the printed p is 0), % of the baseline mean.
    low_percent, high_percent : float
        s over the printed p's rounding interval; ``low_percent`` is 0 when p = 0 is printed.
    upper_bound : bool
        True when the printed p is 0: the paper's scatter is at most ``sd_percent``.
    dof : float
        Degrees of freedom of the t quantile (2 n − 2).
    """

    sd_percent: float
    low_percent: float
    high_percent: float
    upper_bound: bool
    dof: float


def _sd_at(change: float, p_value: float, trials: int) -> float:
    """s from |Δ| and an exact p (module notes)."""
    quantile = float(stats.t.isf(p_value / 2.0, 2 * trials - 2))
    return abs(change) / (quantile * np.sqrt(2.0 / trials))


def implied_scatter(
    change_percent: float, p_value: float, trials: int = PAPER_TRIALS
) -> ImpliedScatter:
    """The trial-to-trial standard deviation that a printed Δ and p imply.

    Parameters
    ----------
    change_percent : float
        Mean change of a_total against the baseline, % (Table 6), finite and not 0.
    p_value : float
        The two-sided p-value as printed with four decimals, in [0, 1).
    trials : int
        Trials per group, >= 2 (the paper: 4).

    Returns
    -------
    ImpliedScatter

    Raises
    ------
    ValueError
        If an argument is outside the ranges above.
    """
    if not np.isfinite(change_percent) or change_percent == 0.0:
        raise ValueError(f"change_percent must be finite and not 0; got {change_percent!r}")
    if not np.isfinite(p_value) or not 0.0 <= p_value < 1.0:
        raise ValueError(f"p_value must be in [0, 1); got {p_value!r}")
    if isinstance(trials, bool) or not isinstance(trials, int) or trials < 2:
        raise ValueError(f"trials must be an integer >= 2; got {trials!r}")
    upper = p_value < _P_ROUNDING / 2  # printed as 0.0000
    central = _sd_at(change_percent, max(p_value, _P_ROUNDING), trials)
    high = _sd_at(change_percent, min(p_value + _P_ROUNDING, 1.0 - 1e-12), trials)
    low = 0.0 if upper else _sd_at(change_percent, p_value - _P_ROUNDING, trials)
    return ImpliedScatter(central, low, high, upper, float(2 * trials - 2))


def paper_implied_scatter() -> dict[tuple[float, str, str], ImpliedScatter]:
    """:func:`implied_scatter` of every cell of Table 6.

    Returns
    -------
    dict
        (speed in km/h, load, controller) -> ImpliedScatter.
    """
    from loader_model.experiments.table6 import LOAD_LABELS, PAPER_TABLE_6, SPEED_LABELS

    speeds = {label: speed for speed, label in SPEED_LABELS.items()}
    loads = {label: load for load, label in LOAD_LABELS.items()}
    return {
        (speeds[speed], loads[load], controller): implied_scatter(change, p_value)
        for (speed, load), row in PAPER_TABLE_6.items()
        for controller, (change, p_value) in row.items()
    }


@dataclass(frozen=True)
class ModelScatter:
    """The model's scatter and mean change in one cell, from many trials per group.

    Attributes
    ----------
    trials_controller, trials_baseline : int
        Trials of each group.
    baseline_mean_m_s2 : float
        Mean a_total of the baseline, m/s².
    sd_percent : float
        Pooled trial standard deviation (equal sizes: √((s_c² + s_b²) / 2)), % of the baseline
        mean: the quantity the paper's Δ and p imply (:func:`implied_scatter`).
    sd_controller_percent, sd_baseline_percent : float
        The two groups' standard deviations, % of the baseline mean.
    change_percent : float
        100 (mean / baseline mean − 1).
    standard_error_pp : float
        Standard error of the change in percentage points (delta method on the ratio of means).
    """

    trials_controller: int
    trials_baseline: int
    baseline_mean_m_s2: float
    sd_percent: float
    sd_controller_percent: float
    sd_baseline_percent: float
    change_percent: float
    standard_error_pp: float


def model_scatter(baseline: object, treated: object) -> ModelScatter:
    """Scatter and mean change of ``treated`` against ``baseline`` (module notes).

    The pooled standard deviation weighs each group's variance by its degrees of freedom (with
    equal sizes, the root mean square of the two). The standard error of the change r − 1,
    r = mean(treated) / mean(baseline), is the delta method's:
    100 √(s_c² / n_c + r² s_b² / n_b) / mean(baseline).

    Parameters
    ----------
    baseline, treated : array_like
        a_total of the trials, m/s², at least 2 finite values each.

    Returns
    -------
    ModelScatter

    Raises
    ------
    ValueError
        If a sample has fewer than 2 values or a value that is not finite, or the baseline mean
        is not positive.
    """
    base = np.asarray(baseline, dtype=float).ravel()
    other = np.asarray(treated, dtype=float).ravel()
    for name, sample in (("baseline", base), ("treated", other)):
        if sample.size < 2 or not np.all(np.isfinite(sample)):
            raise ValueError(
                f"{name} must hold at least 2 values, all finite; got {sample.size} values"
            )
    mean = float(base.mean())
    if mean <= 0.0:
        raise ValueError(f"baseline mean must be > 0; got {mean!r}")
    ratio = float(other.mean()) / mean
    sb, sc = float(base.std(ddof=1)), float(other.std(ddof=1))
    nb, nc = base.size, other.size
    pooled = float(np.sqrt(((nc - 1) * sc**2 + (nb - 1) * sb**2) / (nc + nb - 2)))
    return ModelScatter(
        trials_controller=int(nc),
        trials_baseline=int(nb),
        baseline_mean_m_s2=mean,
        sd_percent=100.0 * pooled / mean,
        sd_controller_percent=100.0 * sc / mean,
        sd_baseline_percent=100.0 * sb / mean,
        change_percent=100.0 * (ratio - 1.0),
        standard_error_pp=100.0 * float(np.sqrt(sc**2 / nc + ratio**2 * sb**2 / nb)) / mean,
    )
