"""The study's report: how much each controller helps, how often it hurts, and what matters.

From the result table (:mod:`~loader_model.robustness.table`), per controller against the same
sample's baseline:

- the distribution of the a_total change in % (Eq. 50): mean, 5 %, 50 % and 95 % quantiles;
- the probability that the controller makes comfort worse (change > 0), with a 95 % Wilson
  interval over the samples;
- the worst cases (largest change) with their conditions;
- sensitivity: Spearman rank correlation (``scipy.stats.spearmanr``) of the change with every
  input that varies (uncertain parameters, driven speed, bucket load as 0 empty / 1 full); a
  global, monotone measure that needs no special design (Sobol indices would need a Saltelli
  design of N (d + 2) samples);
- the gains' stability margin: the largest real part of the plant-and-skyhook poles per sample
  (positive: the linearised closed loop is unstable) and the share of unstable samples;
- the pump's time at its displacement limit and the highest piston-side pressure;
- the failures and their reasons.
"""

from __future__ import annotations

import math
from collections import Counter
from typing import Any

import numpy as np

from loader_model.robustness.study import Study

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


def controller_summary(study: Study, table: Any, controller: str) -> dict[str, Any]:
    """Statistics of one controller against the baseline (module notes) as a dict."""
    from scipy.stats import spearmanr

    rows = [r for r in table.to_pylist() if r["controller"] == controller]
    ok = [r for r in rows if not r["failed"] and math.isfinite(r["change_percent"])]
    change = np.array([r["change_percent"] for r in ok])
    worse = int(np.sum(change > 0))
    sensitivity = {}
    if len(ok) >= 3:
        for name, values in _inputs(study, ok).items():
            if np.ptp(values) > 0:
                sensitivity[name] = float(spearmanr(values, change).statistic)
    poles = np.array([r["max_pole_real"] for r in rows], dtype=float)
    poles = poles[np.isfinite(poles)]
    return {
        "controller": controller,
        "samples": len(rows),
        "evaluated": len(ok),
        "failed": sum(r["failed"] for r in rows),
        "reasons": Counter(r["reason"].split(";")[0][:120] for r in rows if r["failed"]),
        "change": change,
        "p_worse": worse / len(ok) if ok else math.nan,
        "p_worse_interval": wilson_interval(worse, len(ok)),
        "worst": sorted(ok, key=lambda r: -r["change_percent"])[:3],
        "sensitivity": dict(sorted(sensitivity.items(), key=lambda kv: -abs(kv[1]))),
        "max_pole_real": poles,
        "pump_saturation_s": _finite([r["pump_saturation_s"] for r in ok]),
        "p_A_max_Pa": _finite([r["p_A_max_Pa"] for r in ok]),
    }


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
    base = [r for r in table.to_pylist() if r["controller"] == "baseline"]
    failed_base = sum(r["failed"] for r in base)
    lines.append(f"Baseline runs failed: {failed_base} of {len(base)}.")
    for controller in study.controllers[1:]:
        s = controller_summary(study, table, controller)
        low, high = s["p_worse_interval"]
        lines += [
            "",
            f"## {controller}",
            "",
            f"- change of a_total: {_quantiles(s['change'])} ({s['evaluated']} samples)",
            f"- probability of worse comfort: {s['p_worse']:.3f} (95 % CI {low:.3f}-{high:.3f})",
            f"- failed runs: {s['failed']}"
            + "".join(f"\n  - {n} × {reason}" for reason, n in s["reasons"].most_common(3)),
        ]
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
                f"{np.mean(poles > 0):.1%} of the samples"
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
