"""What became of each run of a study: evaluated, or one of the failure categories.

A run enters the a_total statistics of the report only if it is ``"evaluated"``. Every other run
has its own category, the first of these that applies:

- ``"unstable"``: the gain's designed closed loop (plant and skyhook, linearised at the sample's
  static equilibrium, :func:`~loader_model.robustness.gains.max_pole_real`) has a pole with a real
  part above :data:`UNSTABLE_POLE_REAL` (Table 3 as printed, k_φ = −0.22, has one at +0.03 to
  +0.05 rad/s on the skid-steer's sampled plants). Whatever the nonlinear run then does, the
  design is not a stable loop on this plant, so its a_total is no improvement.
- ``"diverged"``: the integration left the finite numbers
  (:class:`~loader_model.simulation.validity_check.SimulationError`).
- ``"outside-validity"``: the run stopped where it left the model's range of validity
  (:class:`~loader_model.simulation.validity_check.ModelValidityError`: tip-over, the boom past
  an end stop, airborne, a seat shock above 50 g).
- ``"failed"``: anything else that stopped the run (the sampled plant fails the parameter checks,
  the ISO 2631 evaluation refuses the signal); the reason is in the table.
- ``"persistent-oscillation"``: the pitch acceleration does not decay after the road's
  excitation ends (:func:`settle_ratio` above :data:`PERSISTENCE_RATIO` and above the same
  sample's baseline's ratio): a limit cycle or a loop too lightly damped to count as ride control.
- ``"pump-saturated"``: the pump command at its displacement limit for more than
  :data:`SATURATION_DUTY_LIMIT` of the run: the controller spends the run against its limit, not
  controlling.
- ``"no-baseline"``: the controller's run is fine but the same sample's baseline run is not
  evaluated, so there is nothing to compare it with.

The baseline's own row is ``"evaluated"``, ``"diverged"``, ``"outside-validity"`` or ``"failed"``:
it is the reference its sample's comparisons are made against (its decay judges the others').
``settle_ratio`` is NaN (not assessed) when the run ends less than 4 × :data:`SETTLE_WINDOW_S`
after the excitation: a study sees persistence only with runs that go on past the road's end.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np

__all__ = [
    "CATEGORIES",
    "FAILURES",
    "PERSISTENCE_RATIO",
    "SATURATION_DUTY_LIMIT",
    "SETTLE_WINDOW_S",
    "UNSTABLE_POLE_REAL",
    "categorise",
    "settle_ratio",
]

#: Every category, the evaluated one first (module notes).
CATEGORIES: tuple[str, ...] = (
    "evaluated",
    "unstable",
    "diverged",
    "outside-validity",
    "failed",
    "persistent-oscillation",
    "pump-saturated",
    "no-baseline",
)
#: The categories that count as a failure of the controller on that sample.
FAILURES: tuple[str, ...] = CATEGORIES[1:-1]
#: Largest real part of a loop pole [rad/s] still counted as stable: 1e-6 rad/s is a time
#: constant of 11 days, far below any pole the designs place (their margin is 0.1 rad/s).
UNSTABLE_POLE_REAL = 1e-6
#: Length w [s] of the two windows of :func:`settle_ratio`; the run must go on 4 w after the
#: excitation, so the windows are at least one w apart.
SETTLE_WINDOW_S = 1.0
#: A settle ratio above this (and above the same sample's baseline's) is a persistent oscillation.
#: Measured on the skid-steer's paper course (9 and 18 km/h, both loads): with runs that end 4 s
#: after the road, the baseline, whose 4.7 Hz boom mode is the least damped, 0.23-0.39, the
#: shipped controllers and designs 0.001-0.16; on the example study with 20 s runs, the baseline
#: 0.003-0.075, every other decaying run at most 0.005, the limit cycles 0.93 (twice the robust
#: gain) and 1.28-3.72 (designed gains, stable on their linearised plants, and one virtual
#: accumulator run).
PERSISTENCE_RATIO = 0.5
#: Largest share of the run the pump command may spend at its limit: beyond it the loop is mostly
#: a bang-bang one, not the linear design. On the shipped example study (10 s runs) the designed
#: gains reach at most 9.8 % (output-feedback LQR).
SATURATION_DUTY_LIMIT = 0.2
#: The simulator's errors (the first word of a row's ``reason``) and their categories.
_RUN_ERRORS = {"SimulationError": "diverged", "ModelValidityError": "outside-validity"}
#: Road input rate [m/s] below which the road counts as flat (the courses' flat parts are 0).
_FLAT_M_S = 1e-9


def settle_ratio(result: Any, window_s: float = SETTLE_WINDOW_S) -> float:
    """How much of the pitch motion is left at the end of the run, after the excitation.

    .. math:: r = \\frac{\\mathrm{rms}\\,\\ddot\\theta_1 \\text{ over } [T - w, T]}
                       {\\mathrm{rms}\\,\\ddot\\theta_1 \\text{ over } [t_e + w, t_e + 2 w]}

    with T the run's end and t_e the end of the excitation: the last sample in which any road
    input rate ``wd_*`` of the run is non-zero. The first second after t_e is skipped: it holds
    the tail of the last obstacle's forced response (measured on the skid-steer at 18 km/h, empty,
    with twice the robust gain: 6.9 rad/s² in the first second, then 3.0-3.6 rad/s² in every
    second to the end of a 20 s run, a limit cycle). A decaying response gives r well below 1, a
    limit cycle about 1.

    Parameters
    ----------
    result : SimulationResult
        The run (columns ``thetadd_1`` [rad/s²], the seat's pitch axis, and
        ``wd_<axle><x|y>`` [m/s]).
    window_s : float
        Window length w in s.

    Returns
    -------
    float
        r, or NaN if the run ends less than 4 w after the excitation (not assessed), 0 if the
        first window holds no motion at all.
    """
    time = np.asarray(result.time_s, dtype=float)
    rates = [np.asarray(result[n]) for n in result.names if n.startswith("wd_")]
    moving = np.any(np.abs(np.column_stack(rates)) > _FLAT_M_S, axis=1) if rates else None
    end = time[np.flatnonzero(moving)[-1]] if moving is not None and moving.any() else time[0]
    if time[-1] - end < 4.0 * window_s:
        return math.nan
    from loader_model.simulation.result import seat_signal_names

    pitch = np.asarray(result[seat_signal_names()["pitch"]], dtype=float)
    first = pitch[(time > end + window_s) & (time <= end + 2.0 * window_s)]
    last = pitch[time > time[-1] - window_s]
    first_rms = float(np.sqrt(np.mean(first**2)))
    last_rms = float(np.sqrt(np.mean(last**2)))
    return last_rms / first_rms if first_rms > 0.0 else 0.0


def _value(row: dict[str, Any], name: str) -> float:
    """A numeric column of a row; NaN if missing or null."""
    value = row.get(name)
    return math.nan if value is None else float(value)


def _error_category(row: dict[str, Any]) -> str:
    """``"evaluated"`` for a run that ran, else the category of the error that stopped it."""
    if not row["failed"]:
        return "evaluated"
    return _RUN_ERRORS.get(str(row.get("reason") or "").split(":", 1)[0], "failed")


def _run_category(row: dict[str, Any], duration_s: float, baseline_ratio: float) -> str:
    """The category of a controller's run (module notes), without the comparison."""
    if _value(row, "max_pole_real") > UNSTABLE_POLE_REAL:  # False for NaN: no gain, no check
        return "unstable"
    if row["failed"]:
        return _error_category(row)
    ratio = _value(row, "settle_ratio")
    if ratio > PERSISTENCE_RATIO and not ratio <= baseline_ratio:  # NaN baseline: not compared
        return "persistent-oscillation"
    if _value(row, "pump_saturation_s") > SATURATION_DUTY_LIMIT * duration_s:
        return "pump-saturated"
    return "evaluated"


def categorise(rows: Iterable[dict[str, Any]], duration_s: float) -> list[str]:
    """The category (module notes) of each row of a result table, in order.

    Parameters
    ----------
    rows : iterable of dict
        Rows of :func:`~loader_model.robustness.table.result_schema` (a missing
        ``settle_ratio`` counts as not assessed), baseline rows named ``"baseline"``.
    duration_s : float
        The study's run length in s (for the pump's saturation duty).

    Returns
    -------
    list of str
        One of :data:`CATEGORIES` per row.
    """
    rows = list(rows)
    baselines = {r["sample"]: r for r in rows if r["controller"] == "baseline"}
    base_ratio = {s: _value(r, "settle_ratio") for s, r in baselines.items()}
    compared = {s for s, r in baselines.items() if not r["failed"] and _value(r, "a_total") > 0}
    categories = []
    for row in rows:
        if row["controller"] == "baseline":
            categories.append(_error_category(row))
            continue
        category = _run_category(row, duration_s, base_ratio.get(row["sample"], math.nan))
        if category == "evaluated" and row["sample"] not in compared:
            category = "no-baseline"
        categories.append(category)
    return categories
