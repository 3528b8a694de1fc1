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
from loader_model.machines import DEFAULT_MACHINE
from loader_model.plant.layout import SKID_STEER, PlantLayout
from loader_model.plant.linear import linearise_plant, undamped_matrices_from_plant
from loader_model.plant.plant_parameters import PlantOptions
from loader_model.plant.scenario import PlantScenario, resolve_plant

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
    machine: str = DEFAULT_MACHINE
    """The machine's name (:func:`loader_model.machines.list_machines`)."""
    cylinder_count: int = 2
    """Lift cylinders in parallel (``n_cyl``; the static force is theirs together)."""


def _modes(plant: PlantScenario) -> list[tuple[float, float]]:
    linear = linearise_plant(plant.params, plant.x0, plant.u0, machine=plant.layout)
    poles = np.linalg.eigvals(linear.state_space().A)
    out = [
        (abs(s) / (2 * np.pi), -s.real / abs(s))
        for s in poles
        if s.imag > 1e-6 and abs(s) < 2 * np.pi * 100
    ]
    return sorted(out)


def _loop_scales(plant: PlantScenario) -> tuple[float, float, float]:
    """‖p_A‖∞ [Pa], V_p,max [m³/rev] and k_p of the pressure loop of ``plant``: the skid-steer's
    from its load case and loader file, another machine's from
    :func:`~loader_model.plant.machine_parameters.pressure_norm` and the shipped controller
    settings (Table 3's k_p)."""
    if plant.is_default_machine:
        loader, load = plant.loader, plant.load
        return load.pressure_normalisation, loader.pump.max_displacement, loader.controller.k_p
    from loader_model.control.settings import default_settings
    from loader_model.plant.machine_parameters import pressure_norm

    norm = pressure_norm(plant.output("p_A"))
    return norm, plant.command_limit(), default_settings().k_p


def hydraulics_report(
    loader: Any,
    load: Any,
    *,
    highpass_rad_s: float = 1.0,
    machine: PlantLayout = SKID_STEER,
) -> HydraulicsReport:
    """Static pressures, k_eq, modes per setting and the pressure loop of ``loader``.

    Parameters
    ----------
    loader, load
        The loader (object, file or None for the shipped one) and its bucket load, as
        :func:`~loader_model.plant.scenario.resolve_plant` takes them; for another machine than
        the skid-steer its parameter file and a load case of it.
    highpass_rad_s : float
        Corner of the high-pass on the measured p_A in the pressure loop [rad/s].
    machine : PlantLayout
        The machine resolved (:func:`~loader_model.plant.layout.plant_layout`; default the
        skid-steer of the paper).
    """
    plant = resolve_plant(loader, load, PlantOptions(), machine=machine)
    static = dict(zip(plant.layout.output_names, plant.y0.tolist(), strict=True))
    static["V_p_hold"] = plant.u0
    closed = plant.with_options(PlantOptions.closed())
    _, _, k_eq = undamped_matrices_from_plant(closed.params, machine=plant.layout)
    modes = {name: _modes(plant.with_options(options)) for name, options in SETTINGS.items()}
    linear = linearise_plant(plant.params, plant.x0, plant.u0, machine=plant.layout)
    state_space = linear.state_space()
    norm, max_displacement, k_p = _loop_scales(plant)
    loops = {
        name: pressure_loop(state_space, norm, max_displacement, k_p=k_p, highpass_rad_s=corner)
        for name, corner in (
            (f"high-pass {highpass_rad_s:g} rad/s", highpass_rad_s),
            ("direct p_A feedback", None),
        )
    }
    comparisons = {name: compare_with_equation_43(loop) for name, loop in loops.items()}
    count = round(plant.parameter("n_cyl"))
    return HydraulicsReport(static, k_eq, modes, loops, comparisons, plant.layout.name, count)


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
