"""The design check as text: a table per condition beside the baseline and the passive
accumulator, the loop's margins, and the verdict; as Markdown (renders in CommonMark) or CSV."""

from __future__ import annotations

import csv
import io
import math

from loader_model.experiments.design_check.runs import COMPARED, RunOutcome
from loader_model.experiments.design_check.verdict import ACTUATOR_NAMES, DesignCheck

__all__ = ["check_csv", "check_markdown", "check_text"]

_COLUMNS = (
    "condition",
    "a_total design [m/s²]",
    "baseline",
    "passive",
    "change [%]",
    "pitch [rad/s²]",
    "command at limit [%]",
    "rate at limit [%]",
    "lift-offs",
    "residual pitch design / baseline [rad/s²]",
    "verdict",
)


def _number(value: float, digits: int = 3) -> str:
    return "stopped" if not math.isfinite(value) else f"{value:.{digits}f}"


def _row(check) -> list[str]:
    design: RunOutcome = check.runs["design"]
    base: RunOutcome = check.runs["baseline"]
    verdict = "not judged" if not check.judged else ("FAIL" if check.failures else "pass")
    change = check.change
    return [
        check.condition.label,
        _number(design.a_total),
        _number(base.a_total),
        _number(check.runs["passive"].a_total),
        "—" if not math.isfinite(change) else f"{100 * change:+.1f}",
        _number(design.weighted_rms.get("pitch", math.nan)),
        _number(100 * design.command_duty, 1),
        _number(100 * design.rate_duty, 1),
        str(design.lift_offs),
        f"{_number(design.tail_rms)} / {_number(base.tail_rms)}",
        verdict,
    ]


def _margin_lines(check: DesignCheck) -> list[str]:
    lines = []
    for load, m in check.margins.items():
        sampled = (
            f"; {m.sampled_unstable} of {m.sampled} sampled plants unstable, worst margin "
            f"{m.worst_sampled_rad_s:.3f} rad/s"
            if m.sampled
            else "; no sampled plants"
        )
        lines.append(
            f"{load}: loop margin {m.margin_rad_s:.3f} rad/s (required "
            f"{check.envelope.margin_rad_s:g}), least damping ratio {m.min_damping:.3f}{sampled}"
        )
    return lines


def _rest_lines(check: DesignCheck) -> list[str]:
    from loader_model.simulation.settling import REST_NOISE_FACTOR

    if not check.rest_rms:
        return []
    levels = ", ".join(f"{load} {value:.3f}" for load, value in check.rest_rms.items())
    return [
        f"at rest on flat ground with the sensors' noise alone: pitch acceleration {levels} "
        f"rad/s² r.m.s. (motion after the road counts from {REST_NOISE_FACTOR:g} times this)"
    ]


def _verdict_lines(check: DesignCheck) -> list[str]:
    judged = sum(c.judged for c in check.conditions)
    head = (
        f"PASSED: {judged} conditions judged, none worse than the baseline by more than "
        f"{check.envelope.worse_than_baseline:.0%}, no persistent oscillation, "
        f"{ACTUATOR_NAMES[check.design.layout.machine.circuit]} limits within bounds"
        if check.passed
        else f"FAILED: {len(check.failures)} finding(s) over {judged} judged conditions"
    )
    lines = [head, *(f"  - {reason}" for reason in check.failures)]
    lines += [f"  not judged: {reason}" for reason in check.not_judged]
    return lines


def _gate_lines(check: DesignCheck) -> list[str]:
    gate_kmh = 3.6 * check.design.settings.ride_control_min_speed
    slower = [c.condition.label for c in check.conditions if c.condition.speed_kmh < gate_kmh]
    if gate_kmh <= 0.0:
        return []
    return [
        f"The ride control is off below {gate_kmh:g} km/h (the settings' "
        f"ride_control_min_speed): {len(slower)} of {len(check.conditions)} conditions drive "
        "as the baseline"
    ]


def check_text(check: DesignCheck) -> str:
    """The check as aligned plain text for a terminal."""
    rows = [list(_COLUMNS), *(_row(c) for c in check.conditions)]
    widths = [max(len(r[i]) for r in rows) for i in range(len(_COLUMNS))]
    lines = [
        f"Design check of {check.design.controller} on {check.design.machine} "
        f"({check.envelope.source}; runs: {', '.join(COMPARED)})"
    ]
    lines += ["  ".join(cell.ljust(w) for cell, w in zip(r, widths, strict=True)) for r in rows]
    lines += ["Linearised loop:", *(f"  {line}" for line in _margin_lines(check))]
    lines += [line[0].upper() + line[1:] for line in [*_rest_lines(check), *_gate_lines(check)]]
    return "\n".join([*lines, *_verdict_lines(check)])


def check_markdown(check: DesignCheck) -> str:
    """The check as Markdown: a pipe table (no pipes inside cells) and the verdict."""
    header = [c.replace("|", "/") for c in _COLUMNS]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_row(c)) + " |" for c in check.conditions]
    notes = [*_margin_lines(check), *_rest_lines(check), *_gate_lines(check)]
    lines += ["", *(f"- {line}" for line in notes), ""]
    lines += [_verdict_lines(check)[0], ""]
    lines += [f"- {reason}" for reason in check.failures]
    lines += [f"- not judged: {reason}" for reason in check.not_judged]
    return "\n".join(lines).rstrip() + "\n"


def check_csv(check: DesignCheck) -> str:
    """One row per condition and run (design, baseline, passive), every measure with its unit."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(
        [
            "load",
            "road",
            "speed [km/h]",
            "seed",
            "run",
            "a_total [m/s^2]",
            "x [m/s^2]",
            "y [m/s^2]",
            "pitch [rad/s^2]",
            "command at limit [-]",
            "rate at limit [-]",
            "lift-offs",
            "residual pitch [rad/s^2]",
            "decay ratio [-]",
            "persistent",
            "stopped",
            "failures",
        ]
    )
    for row in check.conditions:
        c = row.condition
        for which in COMPARED:
            r = row.runs[which]
            w = r.weighted_rms
            writer.writerow(
                [
                    c.load,
                    c.road,
                    f"{c.speed_kmh:g}",
                    c.seed,
                    which,
                    *(f"{v:.6g}" for v in (r.a_total, w.get("x", math.nan), w.get("y", math.nan))),
                    f"{w.get('pitch', math.nan):.6g}",
                    f"{r.command_duty:.6g}",
                    f"{r.rate_duty:.6g}",
                    r.lift_offs,
                    f"{r.tail_rms:.6g}",
                    f"{r.decay_ratio:.6g}",
                    int(r.persistent),
                    r.stopped,
                    "; ".join(row.failures) if which == "design" else "",
                ]
            )
    return out.getvalue()
