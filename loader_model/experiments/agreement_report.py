"""The report's tables of means AND scatter: the calibrated steps per cell, the plausible machines.

Both read the shipped fidelity budget (``data/fidelity_budget.json``, ``make fidelity`` or
``make fidelity-update``) and apply the rule of :mod:`~loader_model.experiments.agreement`:
a cell agrees when its mean change lies within 10 pp of the paper's and its trial scatter
within a factor 2 of the one the paper's Δ and p imply (an upper bound where p = 0.0000).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from loader_model.experiments.tables import Rows

__all__ = ["agreement_text", "calibrated_cell_rows", "machine_rows"]


def _paper(cell: dict[str, Any]) -> str:
    bound = "≤ " if cell["paper_sd_bound"] else ""
    return f"{cell['paper']:+.1f} ({bound}{cell['paper_sd']:.1f})"


def _model(cell: dict[str, Any]) -> str:
    marks = ("" if abs(cell["change"] - cell["paper"]) <= 10.0 else "*") + (
        "" if cell["scatter_agrees"] else "†"
    )
    return f"{cell['change']:+.1f} ± {cell['se']:.1f} ({cell['sd']:.1f}){marks}"


def calibrated_cell_rows(steps: Sequence[dict[str, Any]]) -> Rows | None:
    """Per cell the paper's Δ (implied SD) and each calibrated step's Δ ± standard error (SD);
    None if no calibrated step carries its scatter."""
    fits = [s for s in steps if s.get("held_out_kmh") is not None and "scatter_within" in s]
    if not fits:
        return None
    rows: Rows = [
        [
            "cell (speed/load/controller)",
            "paper Δ [%] (implied SD [%])",
            *(f"{s['label'].removeprefix('+ ')}: Δ ± SE [%] (SD [%])" for s in fits),
        ]
    ]
    for key, cell in fits[0]["cells"].items():
        rows.append([key, _paper(cell), *(_model(s["cells"][key]) for s in fits)])
    rows.append(
        [
            "within 10 pp / scatter within ×2 / both (held out)",
            "",
            *(
                f"{s['within']} / {s['scatter_within']} / {s['both_within']} of {s['count']} "
                f"({s['held_out_within']} / {s['held_out_scatter_within']} / "
                f"{s['held_out_both_within']} of {s['held_out_count']})"
                for s in fits
            ),
        ]
    )
    return rows


def _share(value: float) -> str:
    return "-" if not np.isfinite(value) else f"{100 * value:.0f} %"


def machine_rows(machines: dict[str, Any]) -> Rows:
    """Per cell the shares of plausible machines whose mean, scatter and both agree."""
    rows: Rows = [
        [
            "cell (speed/load/controller)",
            "paper Δ [%] (implied SD [%])",
            "mean within 10 pp",
            "scatter within ×2",
            "both",
            "machines (failed)",
            "median SE of a machine's Δ [pp]",
        ]
    ]
    for key, cell in machines["cells"].items():
        rows.append(
            [
                key,
                _paper(cell),
                _share(cell["mean_share"]),
                _share(cell["scatter_share"]),
                _share(cell["both_share"]),
                f"{cell['count']} ({cell['failed']})",
                f"{cell['se_median']:.1f}",
            ]
        )
    return rows


def agreement_text(budget: dict[str, Any]) -> tuple[str, dict[str, Rows]]:
    """Markdown of both tables (what the budget has of them) and the tables for the CSV files."""
    from loader_model.experiments.report import markdown_table

    parts, tables = [], {}
    cells = calibrated_cell_rows(budget["steps"])
    if cells is not None:
        fits = [s for s in budget["steps"] if s.get("held_out_kmh") is not None]
        largest = max(s.get("largest_se", float("nan")) for s in fits)
        tables["calibrated_cells"] = cells
        parts += [
            "Each calibrated step per cell, means and scatter (the same trials as the budget "
            f"table; largest standard error of a mean {largest:.1f} pp). SD: the pooled trial "
            "standard deviation in % of the baseline mean; the paper's is the one its Δ and p "
            "imply (scatter section; ≤: an upper bound, p = 0.0000). * mean more than 10 pp "
            "from the paper's; † scatter more than a factor 2 from the paper's:\n",
            markdown_table(cells) + "\n",
        ]
    machines = budget.get("machines")
    if machines is not None:
        tables["machine_agreement"] = machine_rows(machines)
        parts += [
            f"Means and scatter of {machines['machines']} plausible machines (a Latin "
            "hypercube over the same ranges), each on the whole Table 6 matrix with "
            f"{machines['trials']} trials per group (seed {machines['seed']}): per cell the "
            "share whose mean change lies within 10 pp of the paper's, whose scatter lies within "
            "a factor 2 of the paper's implied one, and both. With so few trials a machine's "
            "own mean is uncertain by the median standard error shown (trials stopped by the "
            f"validity checks: {machines.get('stopped', 0)}; machines the parameter files "
            f"refused: {machines.get('refused', 0)}).\n",
            markdown_table(tables["machine_agreement"]) + "\n",
        ]
    return "\n".join(parts), tables
