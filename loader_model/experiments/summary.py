"""The report's first section: what the model reproduces of Table 6, in plain words.

Everything is computed from this run's Table 6 cells and the shipped fidelity budget
(:mod:`~loader_model.experiments.fidelity`): which cells lie within the fidelity criterion, which
significant findings of the paper keep their sign, the cells furthest off, the modelling step that
moved the comparison most, and the cells whose sign the estimated parameters cannot decide.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import pairwise
from typing import Any

from loader_model.experiments.report import FIDELITY_POINTS
from loader_model.experiments.table6 import Table6Cell

__all__ = ["SIGNIFICANCE", "summary_section"]

#: p-value below which a change counts as significant (the paper's reading of its Table 6).
SIGNIFICANCE = 0.05

_SPEED = {9.0: "9 km/h", 18.0: "18 km/h"}


def _name(cell: Table6Cell) -> str:
    speed = _SPEED.get(cell.speed_kmh, f"{cell.speed_kmh:g} km/h")
    return f"{cell.controller}, {speed} {cell.load}"


def _cell_text(cell: Table6Cell) -> str:
    m = cell.model
    return (
        f"{_name(cell)}: model {m.change_percent:+.1f} % "
        f"[{m.low_percent:+.1f}, {m.high_percent:+.1f}], paper {cell.paper_change_percent:+.1f} %"
    )


def _sign(value: float) -> int:
    return (value > 0) - (value < 0)


def _budget_lines(budget: dict[str, Any] | None) -> list[str]:
    if budget is None:
        return ["- The fidelity budget (`make fidelity`) is not shipped: causes not measured."]
    steps = [s for s in budget["steps"] if s.get("held_out_kmh") is None]
    lines = []
    moves = [
        (
            abs(b["within"] - a["within"])
            + abs(b["significant_in_sign"] - a["significant_in_sign"]),
            a,
            b,
        )
        for a, b in pairwise(steps)
    ]
    if moves:
        _, before, after = max(moves, key=lambda m: m[0])
        lines.append(
            f"- **The modelling step that moved the comparison most** (fidelity budget below): "
            f"“{after['label'].lstrip('+ ')}” took the cells within {FIDELITY_POINTS:g} pp from "
            f"{before['within']} to {after['within']} of {after['count']} and the paper's "
            f"significant findings kept in sign from {before['significant_in_sign']} to "
            f"{after['significant_in_sign']} of {after['significant_count']}."
        )
    for fit in (s for s in budget["steps"] if s.get("held_out_kmh") is not None):
        scatter = (
            f"; its trial scatter lies within a factor 2 of the paper's implied one in "
            f"{fit['scatter_within']} of {fit['count']} cells ({fit['held_out_scatter_within']} "
            f"of the held-out), mean and scatter both in {fit['both_within']}"
            if "scatter_within" in fit
            else ""
        )
        lines.append(
            f"- **What the estimated parameters can reach**: “{fit['label'].lstrip('+ ')}” brings "
            f"{fit['within']} of {fit['count']} cells within {FIDELITY_POINTS:g} pp, the held-out "
            f"{fit['held_out_kmh']:g} km/h cells {fit['held_out_within']} of "
            f"{fit['held_out_count']}{scatter}."
        )
    uncertainty = budget.get("uncertainty")
    if uncertainty:
        cells = uncertainty["cells"]
        undecided = sorted(k for k, c in cells.items() if c["share"] < 0.5)
        lines.append(
            f"- **Signs the published data cannot decide**: in {len(undecided)} of {len(cells)} "
            f"cells fewer than half of {uncertainty.get('samples', 'the')} plausible machines "
            "(the estimated parameters drawn over their ranges) show the paper's sign"
            + (f" ({', '.join(undecided)})." if undecided else ".")
        )
    return lines


def _gain_line(cells: Sequence[Table6Cell]) -> str:
    """How far the skyhook's change is from the virtual accumulator's, model and paper."""
    by_key = {(c.speed_kmh, c.load, c.controller): c for c in cells}
    model, paper = [], []
    for (speed, load, controller), cell in by_key.items():
        if controller != "skyhook" or (speed, load, "virtual-accumulator") not in by_key:
            continue
        other = by_key[(speed, load, "virtual-accumulator")]
        model.append(abs(cell.model.change_percent - other.model.change_percent))
        paper.append(abs(cell.paper_change_percent - other.paper_change_percent))
    if not model:
        return ""
    return (
        f"- **The skyhook's gains act weakly on this model**: its change differs from the "
        f"virtual accumulator's (the same pressure loop without K_fb) by at most "
        f"{max(model):.1f} pp per condition, where the paper measured up to {max(paper):.1f} pp "
        "(cause analysis below)."
    )


def summary_section(
    cells: Sequence[Table6Cell], budget: dict[str, Any] | None, comfort: str = ""
) -> str:
    """Markdown of the summary: the Table 6 cells' agreement, the misses and their causes.

    Parameters
    ----------
    cells : sequence of Table6Cell
        The cells that have a paper value (this run's Table 6).
    budget : dict or None
        The shipped fidelity budget (:func:`~loader_model.experiments.fidelity_report.
        shipped_budget`), None if absent.
    comfort : str
        A sentence on the absolute levels, appended as the last item.

    Returns
    -------
    str
        The section, starting with its heading.
    """
    if not cells:
        raise ValueError("summary_section needs the Table 6 cells that have a paper value")
    within = [c for c in cells if c.within <= FIDELITY_POINTS]
    off = sorted((c for c in cells if c.within > FIDELITY_POINTS), key=lambda c: -c.within)
    significant = [c for c in cells if c.paper_p_value < SIGNIFICANCE]
    same_sign = [
        c for c in significant if _sign(c.model.change_percent) == _sign(c.paper_change_percent)
    ]
    confirmed = [c for c in same_sign if c.model.p_value < SIGNIFICANCE]
    reversed_ = [
        c
        for c in significant
        if _sign(c.model.change_percent) == -_sign(c.paper_change_percent)
        and c.model.p_value < SIGNIFICANCE
    ]
    lines = [
        "## Summary\n",
        f"**{len(within)} of {len(cells)} cells of Table 6 lie within {FIDELITY_POINTS:g} "
        "percentage points of the paper's change of a_total.** Of the paper's "
        f"{len(significant)} significant changes (p < {SIGNIFICANCE:g}) the model has "
        f"{len(same_sign)} with the same sign ({len(confirmed)} of them significant too) and "
        f"{len(reversed_)} significantly reversed.\n",
        "- **Reproduced** (within the criterion): "
        + ("; ".join(_cell_text(c) for c in within) if within else "none")
        + ".",
        "- **Not reproduced**, furthest first: "
        + ("; ".join(_cell_text(c) for c in off[:4]) if off else "none")
        + (f"; and {len(off) - 4} more (Table 6 below)." if len(off) > 4 else "."),
    ]
    if reversed_:
        lines.append(
            "- **Reversed** (the model significant with the opposite sign): "
            + "; ".join(_name(c) for c in reversed_)
            + "."
        )
    lines.append("\nWhy, as far as measured:\n")
    lines += _budget_lines(budget)
    gain = _gain_line(cells)
    if gain:
        lines.append(gain)
    if comfort:
        lines.append(f"- **Absolute levels**: {comfort.strip()}")
    return "\n".join(lines) + "\n"
