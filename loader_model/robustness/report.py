"""The study's report: how much each controller helps, how often it hurts or fails, what matters.

Every run has a category (:mod:`~loader_model.robustness.outcomes`): ``"evaluated"``, or why it is
not counted: unstable on the linearised plant, diverged, stopped outside the model's validity,
failed otherwise, a persistent oscillation after the road, the pump at its limit for much of the
run, or no baseline to compare with. Per controller against the same sample's baseline:

- how many samples fell in each category;
- the probability of worse comfort over every sample (but those without a baseline), **each
  failure counted as worse**, and among the evaluated samples only (change > 0), each with a
  95 % Wilson interval;
- the distribution of the a_total change in % (Eq. 50) over the evaluated samples only: mean,
  5 %, 50 % and 95 % quantiles (a failed or unstable run's a_total is no improvement);
- the worst evaluated cases (largest change) with their conditions;
- sensitivity over the evaluated samples: Spearman rank correlation (``scipy.stats.spearmanr``) of
  the change with every input that varies (uncertain parameters, driven speed, bucket load as
  0 empty / 1 full); a global, monotone measure that needs no special design (Sobol indices
  would need a Saltelli design of N (d + 2) samples);
- the gains' stability margin: the largest real part of the plant-and-skyhook poles per sample
  (positive: the linearised closed loop is unstable);
- the pump's time at its displacement limit and the highest piston-side pressure (runs that ran);
- the failures' reasons.
"""

from __future__ import annotations

import math
from collections import Counter
from typing import Any

import numpy as np

from loader_model.robustness.outcomes import (
    CATEGORIES,
    FAILURES,
    SATURATION_DUTY_LIMIT,
    UNSTABLE_POLE_REAL,
    categorise,
)
from loader_model.robustness.study import Study
from loader_model.simulation.settling import TAIL_WINDOW_S

__all__ = ["controller_summary", "report_text", "wilson_interval"]


def wilson_interval(successes: int, count: int, z: float = 1.959964) -> tuple[float, float]:
    """95 % Wilson score interval of a proportion (NaN, NaN for no trials)."""
    if count == 0:
        return math.nan, math.nan
    p = successes / count
    centre = (p + z * z / (2 * count)) / (1 + z * z / count)
    half = z * math.sqrt(p * (1 - p) / count + z * z / (4 * count * count)) / (1 + z * z / count)
    return max(0.0, centre - half), min(1.0, centre + half)


def _inputs(study: Study, rows: list[dict[str, Any]]) -> dict[str, np.ndarray]:
    inputs = {path: np.array([r[path] for r in rows]) for path, _ in study.parameters}
    inputs["speed_kmh (driven)"] = np.array([r["speed_kmh"] * r["speed_factor"] for r in rows])
    if len(study.loads) > 1:
        inputs["load (full = 1)"] = np.array([float(r["load"] == "full") for r in rows])
    return inputs


def _finite(values: list) -> np.ndarray:
    array = np.array(values, dtype=float)
    return array[np.isfinite(array)]


def _categorised(study: Study, table: Any) -> list[dict[str, Any]]:
    """The table's rows with their ``category`` (computed if the table has none)."""
    rows = table.to_pylist()
    if rows and all(r.get("category") for r in rows):
        return rows
    categories = categorise(rows, study.duration_s)
    return [r | {"category": c} for r, c in zip(rows, categories, strict=True)]


def controller_summary(study: Study, table: Any, controller: str) -> dict[str, Any]:
    """Statistics of one controller against the baseline (module notes) as a dict.

    ``counts``: samples per category (every one of
    :data:`~loader_model.robustness.outcomes.CATEGORIES`); ``p_worse_all``: worse or failed
    over the samples except ``"no-baseline"`` ones (``compared``); ``p_worse``: worse among the
    ``evaluated``.
    """
    from scipy.stats import spearmanr

    rows = [r for r in _categorised(study, table) if r["controller"] == controller]
    counts = Counter({category: 0 for category in CATEGORIES})
    counts.update(r["category"] for r in rows)
    ok = [r for r in rows if r["category"] == "evaluated" and math.isfinite(r["change_percent"])]
    change = np.array([r["change_percent"] for r in ok])
    worse = int(np.sum(change > 0))
    failures = sum(counts[c] for c in FAILURES)
    compared = len(rows) - counts["no-baseline"]
    sensitivity = {}
    if len(ok) >= 3 and np.ptp(change) > 0:  # a constant change has no rank correlation
        for name, values in _inputs(study, ok).items():
            if np.ptp(values) > 0:
                sensitivity[name] = float(spearmanr(values, change).statistic)
    poles = np.array([r["max_pole_real"] for r in rows], dtype=float)
    poles = poles[np.isfinite(poles)]
    ran = [r for r in rows if not r["failed"]]
    return {
        "controller": controller,
        "samples": len(rows),
        "counts": counts,
        "evaluated": len(ok),
        "compared": compared,
        "failures": failures,
        "failed": sum(r["failed"] for r in rows),
        "reasons": Counter(r["reason"].split(";")[0][:120] for r in rows if r["failed"]),
        "settle_not_assessed": len(ran) - _finite([r.get("settle_ratio") for r in ran]).size,
        "change": change,
        "p_worse": worse / len(ok) if ok else math.nan,
        "p_worse_interval": wilson_interval(worse, len(ok)),
        "p_worse_all": (worse + failures) / compared if compared else math.nan,
        "p_worse_all_interval": wilson_interval(worse + failures, compared),
        "worst": sorted(ok, key=lambda r: -r["change_percent"])[:3],
        "sensitivity": dict(sorted(sensitivity.items(), key=lambda kv: -abs(kv[1]))),
        "max_pole_real": poles,
        "pump_saturation_s": _finite([r["pump_saturation_s"] for r in ran]),
        "p_A_max_Pa": _finite([r["p_A_max_Pa"] for r in ran]),
    }


_LABELS = {
    "evaluated": "evaluated",
    "unstable": "unstable on the linearised plant",
    "diverged": "diverged",
    "outside-validity": "stopped outside the model's validity",
    "failed": "failed otherwise",
    "persistent-oscillation": "persistent oscillation after the road",
    "pump-saturated": f"pump at its limit for more than {100 * SATURATION_DUTY_LIMIT:g} % of the run",
    "no-baseline": "no baseline to compare with",
}


def _counts(counts: Counter) -> str:
    return ", ".join(f"{counts[c]} {_LABELS[c]}" for c in CATEGORIES)


def _quantiles(values: np.ndarray) -> str:
    if values.size == 0:
        return "no evaluated sample"
    q5, q50, q95 = np.quantile(values, [0.05, 0.5, 0.95])
    return f"mean {values.mean():+.1f} %, 5 % {q5:+.1f}, median {q50:+.1f}, 95 % {q95:+.1f}"


def report_text(study: Study, table: Any, gains: dict | None = None) -> str:
    """The Markdown report of a finished study (module notes).

    Parameters
    ----------
    study : Study
        The study the table belongs to.
    table : pyarrow.Table
        Its result table (:func:`~loader_model.robustness.engine.run_study`).
    gains : dict, optional
        K_fb per controller and load (:func:`~loader_model.robustness.engine.read_gains`),
        listed when given.

    Returns
    -------
    str
        Markdown, one section per controller against the baseline.
    """
    lines = [
        f"# Robustness study: {study.name}",
        "",
        f"{study.samples} samples ({study.sampling}, seed {study.seed}), {study.duration_s:g} s "
        f"runs on the {'paper course' if study.road == 'course' else 'ISO 8608 road'} "
        f"(class {study.road_class}), speeds {list(study.speeds_kmh)} km/h "
        f"± {100 * study.speed_spread:g} %, loads {list(study.loads)}; varied: "
        f"{', '.join(p for p, _ in study.parameters) or 'nothing'}.",
        "Change of a_total (ISO 2631-1, Eq. 50) against the same sample's baseline.",
    ]
    base = [r for r in _categorised(study, table) if r["controller"] == "baseline"]
    base_counts = Counter(r["category"] for r in base)
    lines.append(
        f"Baseline runs: {len(base)}, "
        + ", ".join(f"{base_counts[c]} {_LABELS[c]}" for c in CATEGORIES if base_counts[c])
        + "."
    )
    lines.append(
        "A run is counted in the a_total statistics only if it is evaluated: a run unstable on "
        "the linearised plant, diverged, stopped outside the model's validity, failed, "
        "oscillating on after the road or with the pump at its limit for more than "
        f"{100 * SATURATION_DUTY_LIMIT:g} % of the run is its own category and counts as worse comfort "
        "in the probability over all samples."
    )
    for controller in study.controllers[1:]:
        s = controller_summary(study, table, controller)
        low, high = s["p_worse_interval"]
        all_low, all_high = s["p_worse_all_interval"]
        no_baseline = s["counts"]["no-baseline"]
        left_out = f"; {no_baseline} samples without a baseline left out" if no_baseline else ""
        lines += [
            "",
            f"## {controller}",
            "",
            f"- samples: {s['samples']}: {_counts(s['counts'])}",
            f"- probability of worse comfort: {s['p_worse_all']:.3f} over all {s['compared']} "
            f"samples, the {s['failures']} failures counted as worse (95 % CI "
            f"{all_low:.3f}-{all_high:.3f}{left_out}); {s['p_worse']:.3f} among the "
            f"{s['evaluated']} evaluated samples (95 % CI {low:.3f}-{high:.3f})",
            f"- change of a_total over the evaluated samples: {_quantiles(s['change'])} "
            f"({s['evaluated']} samples)",
            f"- failed runs: {s['failed']}"
            + "".join(f"\n  - {n} × {reason}" for reason, n in s["reasons"].most_common(3)),
        ]
        if s["settle_not_assessed"]:
            lines.append(
                f"- decay after the road not assessed on {s['settle_not_assessed']} runs (they "
                f"end less than {2 * TAIL_WINDOW_S:g} s after the road's last excitation: "
                "set a longer duration_s)"
            )
        if s["pump_saturation_s"].size and s["p_A_max_Pa"].size:
            lines.append(
                f"- pump at its limit on {np.mean(s['pump_saturation_s'] > 0):.1%} of the runs "
                f"(mean {s['pump_saturation_s'].mean():.3f} s per run); highest p_A "
                f"{s['p_A_max_Pa'].max() / 1e5:.1f} bar"
            )
        for load, gain in (gains or {}).get(controller, {}).items():
            lines.append(f"- K_fb ({load}): [{', '.join(f'{g:.4g}' for g in gain)}]")
        if s["max_pole_real"].size:
            poles = s["max_pole_real"]
            lines.append(
                f"- stability margin (max Re of the plant-and-skyhook poles, rad/s): median "
                f"{np.median(poles):+.4f}, worst {poles.max():+.4f}; unstable on "
                f"{np.mean(poles > UNSTABLE_POLE_REAL):.1%} of the samples"
            )
        if s["sensitivity"]:
            ranked = ", ".join(f"{k} {v:+.2f}" for k, v in list(s["sensitivity"].items())[:5])
            lines.append(f"- Spearman rank correlation with the change: {ranked}")
        for r in s["worst"]:
            varied = ", ".join(f"{p} = {r[p]:.4g}" for p, _ in study.parameters)
            lines.append(
                f"- worst: sample {r['sample']}: {r['change_percent']:+.1f} % at "
                f"{r['speed_kmh'] * r['speed_factor']:.2f} km/h, load {r['load']}"
                + (f"; {varied}" if varied else "")
            )
    return "\n".join(lines) + "\n"
