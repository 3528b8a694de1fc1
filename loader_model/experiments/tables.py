"""The report's tables other than Table 6, each a list of rows (header first).

- Table 1: undamped modes of the default loader (Eq. 27-29) beside the paper's, both loads.
- Eq. 43: poles, zeros and DC gain of the detailed pressure loop beside the reduced-order one.
- Tables 4 and 5: friction (from the friction test with the chassis sensors) and leakage (from
  the default lift test) identified from synthetic records (seed 0) of the hydraulic plant,
  whose true values are Tables 4 and 5 themselves.
- Gains: Table 3, output-feedback LQR and comfort-optimised
  (:mod:`~loader_model.experiments.designed_gains`), with their linear-model a_total.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["Rows", "gain_rows", "identification_rows", "pressure_loop_rows", "table1_rows"]

#: A table: header row then data rows, all strings.
Rows = list[list[str]]


def table1_rows() -> Rows:
    """Table 1 beside the model: frequency per mode and MAC of M·φ (errata 7), both loads."""
    from loader_model.modal.modes import compare_with_table_1, modal_analysis
    from loader_model.modal.undamped import undamped_matrices
    from loader_model.parameters.sets import LOAD_CASES, bucket_load, default_loader

    rows: Rows = [["load", "mode", "model f [Hz]", "paper f [Hz]", "error [%]", "MAC M·φ"]]
    loader = default_loader()
    for case in LOAD_CASES:
        matrices = undamped_matrices(loader, bucket_load(case))
        comparison = compare_with_table_1(modal_analysis(matrices.mass, matrices.stiffness))
        for k in range(comparison.frequencies_hz.size):
            rows.append(
                [
                    case,
                    str(k + 1),
                    f"{comparison.frequencies_hz[k]:.3f}",
                    f"{comparison.table_frequencies_hz[k]:.2f}",
                    f"{comparison.frequency_errors_percent[k]:+.2f}",
                    f"{comparison.mac[k]:.4f}",
                ]
            )
    return rows


def _complex(values) -> str:
    """Poles or zeros as text; a complex value with positive imaginary part as σ ± ωj."""
    return ", ".join(
        f"{v.real:.1f}" + (f" ± {abs(v.imag):.1f}j" if abs(v.imag) > 1e-9 else "") for v in values
    )


def pressure_loop_rows(figure: Path | None = None) -> tuple[Rows, Rows]:
    """The detailed pressure loop (empty bucket) beside Eq. 43; optionally its Bode figure.

    Returns a summary (per loop: DC gain, zeros, the three slowest poles, how many poles lie
    within 500 rad/s) and the poles themselves, one row per pole or complex pair (s = σ ± jω
    written once, with |s| and the damping ratio −σ/|s|), slowest first.
    """
    from loader_model.control.hydraulics_report import hydraulics_report, plot_pressure_loop
    from loader_model.parameters.sets import bucket_load, default_loader

    report = hydraulics_report(default_loader(), bucket_load("empty"))
    summary: Rows = [
        [
            "loop",
            "DC gain",
            "slowest zeros, abs(s) < 500 [rad/s]",
            "three slowest poles [rad/s]",
            "poles with abs(s) < 500",
        ]
    ]
    poles: Rows = [["loop", "pole [rad/s]", "abs(s) [rad/s]", "damping ratio"]]
    first = next(iter(report.comparisons.values()))
    loops = [
        ("Eq. 43 (paper)", first.reference_dc_gain, first.reference_zeros, first.reference_poles)
    ]
    for name, comparison in report.comparisons.items():
        loops.append(
            (f"model, {name}", comparison.dc_gain, comparison.zeros, comparison.dominant_poles)
        )
    for name, dc_gain, zeros, loop_poles in loops:
        near = _one_per_pair(loop_poles[np.abs(loop_poles) < 500])
        summary.append(
            [
                name,
                f"{dc_gain:.4f}",
                _first_three(_one_per_pair(zeros[np.abs(zeros) < 500])),
                _complex(near[:3]),
                str(int(np.sum(np.abs(loop_poles) < 500))),
            ]
        )
        for pole in near:
            poles.append(
                [name, _complex([pole]), f"{abs(pole):.1f}", f"{-pole.real / abs(pole):.3f}"]
            )
    if figure is not None:
        plot_pressure_loop(report, figure, "Pressure loop p_A,ref -> p_A: model and Eq. 43")
    return summary, poles


def _first_three(values: np.ndarray) -> str:
    if values.size == 0:
        return "none"
    more = f" (and {values.size - 3} more)" if values.size > 3 else ""
    return _complex(values[:3]) + more


def _one_per_pair(values: np.ndarray) -> np.ndarray:
    """Real values and one of each complex-conjugate pair (imaginary part > 0), by |s|."""
    values = np.asarray(values, dtype=complex)
    kept = values[values.imag >= -1e-9 * np.maximum(1.0, np.abs(values))]
    return kept[np.argsort(np.abs(kept), kind="stable")]


def identification_rows(seed: int = 0) -> tuple[Rows, Rows]:
    """Tables 4 and 5 recovered from a synthetic lift-test record (module notes)."""
    from loader_model.identification import (
        LiftProfile,
        SensorOptions,
        identify_friction,
        identify_leakage,
        prepare_signals,
        synthesize,
    )
    from loader_model.identification.report import TABLE4_ROWS, TABLE5_ROWS
    from loader_model.parameters.sets import default_loader

    speed = default_loader().pump.shaft_speed
    test = synthesize(SensorOptions.friction_test(seed), LiftProfile.friction_test())
    signals = prepare_signals(test.record, speed, cylinder=test.cylinder)
    friction = identify_friction(signals, test.cylinder).fit
    recording = synthesize(SensorOptions(seed=seed), LiftProfile())
    signals = prepare_signals(recording.record, speed, cylinder=recording.cylinder)
    leakage = identify_leakage(signals, recording.cylinder)
    header = ["coefficient", "unit", "identified", "95 % interval", "paper"]
    table4: Rows = [header]
    for (name, unit, factor, paper), value, low, high in zip(
        TABLE4_ROWS, friction.values, friction.low, friction.high, strict=True
    ):
        table4.append(
            [
                name,
                unit,
                f"{value * factor:.4g}",
                f"[{low * factor:.4g}, {high * factor:.4g}]",
                f"{paper:.4g}",
            ]
        )
    table5: Rows = [header]
    regression = leakage.regression
    for name, unit, factor, paper in TABLE5_ROWS:
        if name == "K_oil":
            value, (low, high) = leakage.bulk_modulus, leakage.bulk_modulus_interval
        else:
            index = regression.names.index(name)
            value, low, high = (
                regression.values[index],
                regression.low[index],
                regression.high[index],
            )
        table5.append(
            [
                name,
                unit,
                f"{value * factor:.4g}",
                f"[{low * factor:.4g}, {high * factor:.4g}]",
                f"{paper:.4g}",
            ]
        )
    return table4, table5


def gain_rows(gains: dict[str, Any]) -> Rows:
    """Skyhook gains on normalised (ẋ_H, ẏ_H, θ̇1, φ): Table 3, output-feedback LQR and the
    comfort optimisation (:func:`~loader_model.experiments.designed_gains.designed_gains`), with
    their linear-model a_total and stability margin per load."""
    rows: Rows = [
        [
            "gain set",
            "k_ẋ",
            "k_ẏ",
            "k_θ̇",
            "k_φ",
            "a_total empty [m/s²]",
            "a_total full [m/s²]",
            "margin empty / full [rad/s]",
            "source",
        ]
    ]
    for name, gain in gains.items():
        totals = [gain.a_total_m_s2[load] for load in ("empty", "full")]
        rows.append(
            [
                name,
                *(f"{k:.4g}" for k in gain.k_fb),
                *("unstable" if not np.isfinite(t) else f"{t:.3f}" for t in totals),
                " / ".join(f"{gain.margin_rad_s[load]:+.3f}" for load in ("empty", "full")),
                gain.source,
            ]
        )
    return rows
