"""The report's "what differs from the paper and why" section, from the measured tables.

Every number here is formatted from this run's tables or from the shipped fidelity budget
(:mod:`~loader_model.experiments.fidelity`, ``data/fidelity_budget.json``); the few quoted as
"measured on the earlier model" are one-off runs on the model before the circuit states, kept with that label.
"""

from __future__ import annotations

from typing import Any

from loader_model.experiments.report import FIDELITY_POINTS, markdown_table
from loader_model.experiments.tables import Rows

__all__ = ["discrepancy_section"]


def _covered(rows: Rows) -> str:
    """How many paper values lie in the identified 95 % intervals, e.g. ``"2 of 5"``."""
    hits = 0
    for row in rows[1:]:
        low, high = (float(v) for v in row[3].strip("[]").split(","))
        hits += low <= float(row[4]) <= high
    return f"{hits} of {len(rows) - 1}"


def _row9(step: dict[str, Any]) -> str:
    cells = step["cells"]
    return " / ".join(
        f"{cells[f'9/empty/{c}']['change']:+.1f}"
        for c in ("passive", "virtual-accumulator", "skyhook")
    )


def _steps_text(budget: dict[str, Any]) -> list[str]:
    steps = budget["steps"]
    lines = []
    previous = None
    for step in steps:
        if step.get("held_out_kmh") is not None:
            continue
        moved = (
            ""
            if previous is None
            else f" (from {previous['within']}; 9 km/h empty row from {_row9(previous)} %)"
        )
        lines.append(
            f"   - {step['label']}: {step['within']} of {step['count']} cells within "
            f"{FIDELITY_POINTS:g} pp{moved}; 9 km/h empty row {_row9(step)} %; "
            f"{step['significant_in_sign']} of {step['significant_count']} significant "
            "findings in sign."
        )
        previous = step
    return lines


def _off_cells(step: dict[str, Any]) -> str:
    off = [
        f"{key} ({cell['change']:+.1f} against {cell['paper']:+.1f} %)"
        for key, cell in step["cells"].items()
        if abs(cell["change"] - cell["paper"]) > FIDELITY_POINTS
    ]
    return "; ".join(off) if off else "none"


def _uncertain(budget: dict[str, Any]) -> str:
    cells = budget["uncertainty"]["cells"]
    low = [f"{k} {100 * c['share']:.0f} %" for k, c in cells.items() if c["share"] < 0.5]
    high = [f"{k} {100 * c['share']:.0f} %" for k, c in cells.items() if c["share"] >= 0.9]
    return (
        f"cells where fewer than half the plausible machines show the paper's sign: "
        f"{'; '.join(low) or 'none'}; cells where at least 90 % do: {'; '.join(high) or 'none'}"
    )


def discrepancy_section(
    tables: dict[str, Rows], within: int, count: int, lifts: float, budget: dict[str, Any] | None
) -> str:
    """Markdown section: measured discrepancies and their causes, as far as found."""
    lines = ["## What differs from the paper and why\n"]
    lines.append(
        f"1. **With the sourced parameter files** {within} of {count} cells lie within "
        f"{FIDELITY_POINTS:g} percentage points of the paper (Table 6 above). Nothing is tuned "
        "per condition; the default parameter files stay sourced."
    )
    if budget is not None:
        fits = [s for s in budget["steps"] if s.get("held_out_kmh") is not None]
        lines.append(
            "2. **What each step of the fidelity budget did** (the budget table above, cumulative):"
        )
        lines += _steps_text(budget)
        for fit in fits:
            lines.append(
                f"   - {fit['label']}: {fit['within']} of {fit['count']} cells, the held-out "
                f"{fit['held_out_kmh']:g} km/h cells {fit['held_out_within']} of "
                f"{fit['held_out_count']}; {fit['significant_in_sign']} of "
                f"{fit['significant_count']} significant findings in sign. Cells still more "
                f"than {FIDELITY_POINTS:g} pp off: {_off_cells(fit)}."
            )
        lines.append(
            "3. **How sure the signs are**: over the estimated parameters' plausible ranges "
            f"(uncertainty table above), {_uncertain(budget)}. Where the share is low, the "
            "published data cannot decide the sign on this model: it turns on what the "
            "parameter files only estimate (accumulator, tyre damping, seat)."
        )
    lines += [
        "4. **The load-holding valves were the main cause of the old reversal** (errata 11): "
        "read as a cylinder leak, Table 5's k_Lp = 2.87e-11 m³/(s·Pa) was a series damper on the "
        "boom support (corner about 34 rad/s at the 4.7 Hz boom mode) that the baseline had and "
        "every controller removed. Behind closed valves the baseline's boom mode is lightly "
        "damped and the pressure loop adds damping, as a pump-controlled ride control should. "
        "Linear, one 40 mm board at 9 km/h (`loader_model.experiments.cause_analysis`; "
        "sensitivities, not model values):",
        "",
        (markdown_table(tables["cause_linear"]) + "\n") if "cause_linear" in tables else "",
        "5. **Table 3's gains act weakly on this model.** The velocities are semi-integrals of "
        "accelerations normalised by 2 g (section 3.3), so a gain of 5 asks for about 1 bar per "
        "m/s² at 3 Hz against pressure swings of tens of bar. Skyhook against the virtual "
        "accumulator (same pressure loop, K_fb = 0), linear, 9 km/h empty:",
        "",
        (markdown_table(tables["cause_gains"]) + "\n") if "cause_gains" in tables else "",
        "   Table 3 runs with k_φ = +0.22 (errata 12); the printed −0.22 leaves a real pole at "
        "about +0.05 rad/s and runs as the reported row skyhook-printed (Beyond the paper).",
        f"6. **Lift-offs**: the tyres leave the ground {lifts:.0f} times per trial on average "
        "(both axles, 5 boards, this run). A 40 mm board is four times the tyres' 7-11 mm "
        "static deflection, so even the tandem cams ride almost fully onto it; the cams change "
        "the shape of the input (the slope starts from zero), not its height. On 5 mm boards, "
        "where no tyre lifts off (nominal trial each):",
        "",
        markdown_table(tables["diagnostics"]) + "\n",
        "7. **Not modelled**: roll and the left/right board timing (planar model), the driver's "
        "steering and speed control, the tyres' nonlinear stiffness and rolling radius, the "
        "bucket load's shape (its centre of gravity and inertia are estimates), the occupant's "
        "reaction on the chassis. The simulator integrates 4 ROS2 steps per 1 ms period "
        "(within 0.3 % of the CVODES reference's a_total on the paper course).",
        "8. **Trial-to-trial variation** is speed (σ 2 %), board position (σ 50 mm) and "
        "assumed sensor noise (0.033 m/s², 0.05°, 0.4 bar per 1 kHz sample, in the compiled "
        "loop; the paper gives no sensor data). The p-values reflect this assumed spread, not "
        "the paper's.",
        "9. **Table 4** comes from the friction test with the chassis sensors (speeds "
        "log-uniform over 0.01-0.25 m/s, 5 µm position sensor): the paper's value lies "
        f"in the identified 95 % interval for {_covered(tables['table4'])} coefficients "
        f"(f_s: {tables['table4'][1][2]} kN in {tables['table4'][1][3]}, paper "
        f"{tables['table4'][1][4]} kN). Table 5: "
        f"{_covered(tables['table5'])} paper values inside the identified intervals.",
        "10. **Table 6's row labels** are garbled in the extracted text; they were read as "
        "Speed/Load = Low/Low, Low/High, High/Low, High/High, which the text confirms for the "
        "second block (low speed, high load: 'more or less the same with or without').\n",
    ]
    return "\n".join(lines)
