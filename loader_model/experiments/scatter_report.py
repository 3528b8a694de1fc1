"""The report's scatter section: Table 6's implied trial scatter beside the model's, and the
model's means from many trials, read from the shipped study (``data/table6_scatter.csv``,
:mod:`~loader_model.experiments.scatter_study`), never recomputed by the report."""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from typing import Any

from loader_model.experiments.report import FIDELITY_POINTS, markdown_table
from loader_model.experiments.scatter import PAPER_TRIALS, ImpliedScatter, paper_implied_scatter
from loader_model.experiments.tables import Rows

__all__ = ["FACTOR", "SE_GOAL_PP", "scatter_rows_for_report", "scatter_section"]

#: The model's scatter "agrees" with the paper's within this factor either way.
FACTOR = 2.0
#: Goal for the standard error of the model's mean change, percentage points.
SE_GOAL_PP = 2.0


def _paper_sd(implied: ImpliedScatter) -> str:
    if implied.upper_bound:
        return f"≤ {implied.sd_percent:.1f}"
    return f"{implied.sd_percent:.1f} [{implied.low_percent:.1f}, {implied.high_percent:.1f}]"


def _ratio(model_sd: float, implied: ImpliedScatter) -> tuple[str, bool]:
    """model SD / paper SD as text, and whether it is within :data:`FACTOR` (for an upper
    bound: only a ratio below the factor is decided, and it counts as within)."""
    ratio = model_sd / implied.sd_percent
    if implied.upper_bound:
        return f"≥ {ratio:.1f}", ratio <= FACTOR
    return f"{ratio:.1f}", 1.0 / FACTOR <= ratio <= FACTOR


def _trials_needed(row: dict[str, Any]) -> int:
    """Trials per group for a standard error of :data:`SE_GOAL_PP` (the SE falls as 1/√n)."""
    return max(2, math.ceil(int(row["trials"]) * (row["se_pp"] / SE_GOAL_PP) ** 2))


def scatter_rows_for_report(rows: Sequence[dict[str, Any]]) -> tuple[Rows, dict[str, int]]:
    """The table of the section and its counts.

    Parameters
    ----------
    rows : sequence of dict
        The study's rows (:func:`~loader_model.experiments.scatter_study.read_scatter`).

    Returns
    -------
    rows : list of list of str
        Header first, one row per cell.
    counts : dict
        ``cells``, ``within`` (model mean of many trials within 10 pp of the paper),
        ``within_four`` (the first four trials' mean), ``scatter_within`` (scatter ratio
        within :data:`FACTOR`), ``se_met`` (standard error <= :data:`SE_GOAL_PP`), ``failed``.
    """
    from loader_model.experiments.table6 import LOAD_LABELS, PAPER_TABLE_6, SPEED_LABELS

    implied = paper_implied_scatter()
    trials = sorted({int(r["trials"]) for r in rows})
    table: Rows = [
        [
            "speed",
            "load",
            "controller",
            "paper Δ [%] (p)",
            "paper's implied SD [%]",
            f"model SD [%] ({'/'.join(map(str, trials))} trials)",
            "ratio model / paper",
            "model SD controller / baseline [%]",
            "model Δ ± SE [%]",
            f"trials for SE ≤ {SE_GOAL_PP:g} pp",
            "|Δ − Δ_paper| [pp]",
            f"model, first {PAPER_TRIALS} trials: Δ [95 % CI] [%]",
            f"model, first {PAPER_TRIALS} trials: SD [%]",
        ]
    ]
    counts = dict.fromkeys(
        ("cells", "within", "within_four", "scatter_within", "se_met", "failed"), 0
    )
    for r in rows:
        key = (float(r["speed_kmh"]), r["load"], r["controller"])
        paper = PAPER_TABLE_6[(SPEED_LABELS[key[0]], LOAD_LABELS[key[1]])][key[2]]
        ratio, inside = _ratio(r["sd_pct"], implied[key])
        distance = abs(r["change_pct"] - paper[0])
        counts["cells"] += 1
        counts["within"] += distance <= FIDELITY_POINTS
        counts["within_four"] += abs(r["four_change_pct"] - paper[0]) <= FIDELITY_POINTS
        counts["scatter_within"] += inside
        counts["se_met"] += r["se_pp"] <= SE_GOAL_PP
        counts["failed"] += r["failed_controller"] + r["failed_baseline"]
        table.append(
            [
                f"{key[0]:g} km/h",
                key[1],
                key[2],
                f"{paper[0]:+.1f} ({paper[1]:.4f})",
                _paper_sd(implied[key]),
                f"{r['sd_pct']:.1f}",
                ratio,
                f"{r['sd_controller_pct']:.1f} / {r['sd_baseline_pct']:.1f}",
                f"{r['change_pct']:+.1f} ± {r['se_pp']:.1f}",
                str(_trials_needed(r)),
                f"{distance:.1f}",
                f"{r['four_change_pct']:+.1f} [{r['four_low_pct']:+.1f}, {r['four_high_pct']:+.1f}]",
                f"{r['four_sd_pct']:.1f}",
            ]
        )
    return table, counts


def _cause(rows: Sequence[dict[str, Any]]) -> str:
    """The paragraph on why the model scatters at 9 km/h, with the shipped SDs."""
    at9 = [r for r in rows if float(r["speed_kmh"]) == 9.0 and r["load"] == "empty"]
    if not at9:
        return ""
    controllers = [r["sd_controller_pct"] for r in at9]
    return (
        "\n\n**Why the model scatters at 9 km/h.** At 9 km/h with the empty bucket the "
        f"baseline's trials scatter by {at9[0]['sd_baseline_pct']:.1f} % and the controllers' by "
        f"{min(controllers):.1f}-{max(controllers):.1f} %. After each board the model's "
        "tyres leave the ground in turn (front, rear, front: a pitch hop at about 1.5 Hz); "
        "about 1 % above the nominal speed the hops of one board last until the next one, "
        "and the baseline's a_total steps up by 10-45 % and turns irregular. The trials' "
        "speed spread (σ 2 %) straddles that step, so they fall into two regimes; with the "
        "full bucket the step lies 2.5-4 % above the nominal speed and few trials reach "
        "it. With the tyres' vertical damping at the top of its plausible range (20 kN s/m) "
        "the step and most of the scatter vanish. `python -m loader_model.experiments."
        "scatter_cause` prints a_total over the speed (the reproduction page of the guide "
        "shows both curves)."
    )


def _study_seed(header: dict[str, str]) -> int | None:
    match = re.search(r"--seed (\d+)", header.get("command", ""))
    return None if match is None else int(match.group(1))


def scatter_section(
    study: tuple[dict[str, str], list[dict[str, Any]]] | None,
    four_trial_changes: dict[tuple[float, str, str], float] | None = None,
    seed: int | None = None,
) -> tuple[str, Rows | None]:
    """The report's Markdown section on scatter and its table (None without a study).

    Parameters
    ----------
    study : (header, rows) or None
        The shipped study (:func:`~loader_model.experiments.scatter_study.shipped_scatter`).
    four_trial_changes : dict, optional
        This run's Table 6 changes, (speed, load, controller) -> %, from four trials per
        group: with the study's ``seed`` the section states how far the file's first four
        trials are from this run (a check that the file is current).
    seed : int, optional
        The base seed of ``four_trial_changes``.

    Returns
    -------
    text : str
    rows : list of list of str or None
    """
    title = "## Scatter: the model's trial-to-trial spread beside the paper's\n"
    if study is None or not study[1]:
        return title + "\nNot shipped: run `make scatter`.\n", None
    header, rows = study
    table, counts = scatter_rows_for_report(rows)
    trials = sorted({int(r["trials"]) for r in rows})
    largest_se = max(r["se_pp"] for r in rows)
    needed = max(_trials_needed(r) for r in rows)
    parts = [
        title,
        "Table 6 gives each cell's mean change Δ and a t-test p over 4 + 4 trials. Under "
        "Welch's two-sided t-test with equal group sizes (n = 4) and equal variances "
        "(ν = 2n − 2 = 6 degrees of freedom) and normal trial-to-trial variation, they fix the "
        "machine's trial standard deviation in percent of the baseline mean: "
        "s = |Δ| / (t₁₋ₚ/₂,₆ · √(2/4)). The brackets give s over the rounding of the printed p "
        "(± 5·10⁻⁵); a printed p = 0.0000 says only p < 5·10⁻⁵, so s is an upper bound there "
        "and the ratio a lower one. The model's SD is the pooled standard deviation of its "
        "baseline and controller trials in the same units (each group's beside it); its mean "
        "change comes from "
        f"{'/'.join(map(str, trials))} trials per group, with the standard error of the "
        "delta method on the ratio of means, and the trials a standard error of "
        f"{SE_GOAL_PP:g} pp needs (the standard error falls as 1/√n). The last two columns are "
        "the same study's first "
        f"four trials, the trials of `loader-model reproduce --seed {_study_seed(header)}`: "
        f"what {PAPER_TRIALS} "
        "trials give.\n",
        markdown_table(table) + "\n",
        f"**With {'/'.join(map(str, trials))} trials per group, {counts['within']} of "
        f"{counts['cells']} cells lie within {FIDELITY_POINTS:g} pp of the paper** (largest "
        f"standard error {largest_se:.1f} pp; {counts['se_met']} of {counts['cells']} cells "
        f"at most {SE_GOAL_PP:g} pp, which takes up to {needed} trials per group); with the "
        f"first four trials, {counts['within_four']} of "
        f"{counts['cells']}. The model's scatter is within a factor of {FACTOR:g} of the "
        f"paper's in {counts['scatter_within']} of {counts['cells']} cells.",
    ]
    if counts["failed"]:
        parts.append(
            f" {counts['failed']} trials (baseline trials counted once per cell) left the "
            "model's range of validity and are left out."
        )
    if four_trial_changes and seed is not None and seed == _study_seed(header):
        gaps = [
            abs(four_trial_changes[k] - r["four_change_pct"])
            for r in rows
            if (k := (float(r["speed_kmh"]), r["load"], r["controller"])) in four_trial_changes
        ]
        if gaps:
            parts.append(
                f" This run's Table 6 and the file's first four trials differ by at most "
                f"{max(gaps):.2g} pp."
            )
    parts.append(_cause(rows))
    parts.append(
        f"\n\nMade by `{header.get('command', '?')}` (`make scatter`) on {header.get('date', '?')} "
        f"in {header.get('wall_time_s', '?')} s; shipped as `loader_model/data/table6_scatter.csv`.\n"
    )
    return "\n".join([title, parts[1], parts[2], "".join(parts[3:])]), table
