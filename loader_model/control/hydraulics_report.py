"""Numbers and figure of ``loader-model hydraulics``: static pressures, k_eq, the coupled plant's
modes with the chambers closed, at the operating point and with the accumulator, and the pressure
loop beside Eq. 43."""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from loader_model.control.pressure_loop import (
    EQUATION_43,
    PressureLoopComparison,
    compare_with_equation_43,
    pressure_loop,
)
from loader_model.plant.linear import linearise_plant, undamped_matrices_from_plant
from loader_model.plant.plant import OUTPUT_NAMES, plant_function
from loader_model.plant.plant_parameters import PlantOptions, plant_parameter_vector

__all__ = ["HydraulicsReport", "hydraulics_report", "plot_pressure_loop"]

#: Circuit settings whose modes the report lists: the loader's own, without the seated occupant
#: (its modes on the seat cushion are not the hydraulics'; :mod:`loader_model.plant.occupant`).
SETTINGS = {
    "chambers closed (Eq. 28)": replace(PlantOptions.closed(), occupant=False),
    "pump through open load-holding valves (virtual accumulator, skyhook)": (
        PlantOptions.for_controller("skyhook", occupant=False)
    ),
    "closed load-holding valves, pump idle (baseline)": PlantOptions.for_controller(
        "baseline", occupant=False
    ),
    "accumulator behind closed valves (passive ride control)": (
        PlantOptions.for_controller("passive", occupant=False)
    ),
}


@dataclass(frozen=True)
class HydraulicsReport:
    """What the hydraulics command prints (SI units)."""

    static_outputs: dict[str, float]
    k_eq_n_per_m: float
    modes: dict[str, list[tuple[float, float]]]
    """Per setting: (frequency [Hz], damping ratio) of the oscillatory modes below 100 Hz."""
    loops: dict[str, Any]
    comparisons: dict[str, PressureLoopComparison]


def _modes(params: np.ndarray) -> list[tuple[float, float]]:
    poles = np.linalg.eigvals(linearise_plant(params).state_space().A)
    out = [
        (abs(s) / (2 * np.pi), -s.real / abs(s))
        for s in poles
        if s.imag > 1e-6 and abs(s) < 2 * np.pi * 100
    ]
    return sorted(out)


def hydraulics_report(loader: Any, load: Any, *, highpass_rad_s: float = 1.0) -> HydraulicsReport:
    """Static pressures, k_eq, modes per setting and the pressure loop of ``loader``."""
    from loader_model.plant.equilibrium import static_state
    from loader_model.vehicle.statics import resolve_machine

    loader, load = resolve_machine(loader, load)

    params = plant_parameter_vector(loader, load)
    state, command = static_state(params)
    outputs = np.asarray(plant_function()(state, command, np.zeros(11), params)[1]).ravel()
    static = dict(zip(OUTPUT_NAMES, outputs.tolist(), strict=True)) | {"V_p_hold": command}
    _, _, k_eq = undamped_matrices_from_plant(
        plant_parameter_vector(loader, load, PlantOptions.closed())
    )
    modes = {
        name: _modes(plant_parameter_vector(loader, load, options))
        for name, options in SETTINGS.items()
    }
    plant = linearise_plant(params).state_space()
    loops = {
        f"high-pass {highpass_rad_s:g} rad/s": pressure_loop(
            plant,
            load.pressure_normalisation,
            loader.pump.max_displacement,
            k_p=loader.controller.k_p,
            highpass_rad_s=highpass_rad_s,
        ),
        "direct p_A feedback": pressure_loop(
            plant,
            load.pressure_normalisation,
            loader.pump.max_displacement,
            k_p=loader.controller.k_p,
            highpass_rad_s=None,
        ),
    }
    comparisons = {name: compare_with_equation_43(loop) for name, loop in loops.items()}
    return HydraulicsReport(static, k_eq, modes, loops, comparisons)


def plot_pressure_loop(report: HydraulicsReport, path: Path, title: str) -> None:
    """Bode overlay of the detailed pressure loops and Eq. 43 (magnitude and phase vs Hz)."""
    import control
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    frequencies_hz = np.logspace(-2, 2, 600)
    omega = 2 * np.pi * frequencies_hz
    figure, (magnitude, phase) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    numerator, denominator = EQUATION_43
    curves = dict(report.loops) | {
        "Eq. 43 (paper)": control.tf(numerator, denominator),
        "Eq. 43 with + 6361 (sign misprint?)": control.tf(
            [numerator[0], -numerator[1]], denominator
        ),
    }
    styles = {"Eq. 43 (paper)": "k--", "Eq. 43 with + 6361 (sign misprint?)": "k:"}
    for name, system in curves.items():
        response = np.squeeze(control.frequency_response(system, omega).complex)
        style = styles.get(name, "-")
        magnitude.semilogx(frequencies_hz, 20 * np.log10(np.abs(response)), style, label=name)
        phase.semilogx(frequencies_hz, np.degrees(np.unwrap(np.angle(response))), style, label=name)
    magnitude.set_ylabel("|p_A / p_A,ref| [dB]")
    phase.set_ylabel("phase [deg]")
    phase.set_xlabel("frequency [Hz]")
    magnitude.set_title(title)
    for axis in (magnitude, phase):
        axis.grid(True, which="both", alpha=0.3)
    magnitude.legend(loc="lower left")
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
