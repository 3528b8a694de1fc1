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
  excitation ends, by the rule of the design check
  (:class:`~loader_model.simulation.settling.SettleMeasure`: in the run's last second θ̈1 is
  above :data:`~loader_model.simulation.settling.REST_FLOOR_RAD_S2` and keeps more than
  :data:`~loader_model.simulation.settling.PERSISTENCE_RATIO` of the second before), and it
  decays slower than the same sample's baseline: a limit cycle or a loop too lightly damped to
  count as ride control.
- ``"pump-saturated"``: the pump command at its displacement limit for more than
  :data:`SATURATION_DUTY_LIMIT` of the run: the controller spends the run against its limit, not
  controlling.
- ``"no-baseline"``: the controller's run is fine but the same sample's baseline run is not
  evaluated, so there is nothing to compare it with.

The baseline's own row is ``"evaluated"``, ``"diverged"``, ``"outside-validity"`` or ``"failed"``:
it is the reference its sample's comparisons are made against (its decay judges the others').
``settle_ratio`` (the last second's r.m.s. over the second before) and ``settle_tail_rms`` are
NaN (not assessed) when the run ends less than two seconds after the excitation: a study sees
persistence only with runs that go on past the road's end.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np

from loader_model.simulation.settling import SettleMeasure, settle_measure

__all__ = [
    "CATEGORIES",
    "FAILURES",
    "SATURATION_DUTY_LIMIT",
    "UNSTABLE_POLE_REAL",
    "categorise",
    "settle_columns",
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
#: Largest share of the run the pump command may spend at its limit: beyond it the loop is mostly
#: a bang-bang one, not the linear design. On the shipped example study (10 s runs) the designed
#: gains reach at most 9.8 % (output-feedback LQR).
SATURATION_DUTY_LIMIT = 0.2
#: The simulator's errors (the first word of a row's ``reason``) and their categories.
_RUN_ERRORS = {"SimulationError": "diverged", "ModelValidityError": "outside-validity"}


def settle_columns(result: Any) -> dict[str, float]:
    """The decay after the road's excitation of a run, as the result table's columns.

    Parameters
    ----------
    result : SimulationResult
        The run (its time, θ̈1 and exogenous-input columns).

    Returns
    -------
    dict
        ``settle_ratio``: the r.m.s. of θ̈1 in the run's last second over that in the second
        before; ``settle_tail_rms``: the last second's r.m.s. [rad/s²]; both NaN when the run ends
        less than two seconds after the excitation
        (:func:`~loader_model.simulation.settling.settle_measure`).
    """
    measure = settle_measure(np.asarray(result.time_s, dtype=float), result.columns)
    if not measure.judged:  # math.nan itself, as every missing value of a row
        return dict.fromkeys(("settle_ratio", "settle_tail_rms"), math.nan)
    return {"settle_ratio": measure.decay_ratio, "settle_tail_rms": measure.tail_rms}


def _persistent(row: dict[str, Any], baseline_ratio: float) -> bool:
    """The settling rule on a row's columns, and slower than its baseline (module notes)."""
    ratio, tail = _value(row, "settle_ratio"), _value(row, "settle_tail_rms")
    measure = SettleMeasure(math.nan, math.nan, tail / ratio if ratio > 0 else math.inf, tail)
    return measure.persistent and not ratio <= baseline_ratio  # NaN baseline: not compared


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
    if _persistent(row, baseline_ratio):
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
