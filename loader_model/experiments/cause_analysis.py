r"""What moves a_total between the controllers: the linear seat response to one board.

The Table 6 experiment (module :mod:`loader_model.experiments.table6`) is nonlinear (tyre lift-off,
valves, friction, pump limits). Its sign against the paper (section 5.3: the damping controllers
*lower* a_total by up to 34 %) is already set in the linear model, so its causes can be isolated
there, quickly and without randomness. With Table 5's flow read as a cylinder leak and the seat
read on the rigid chassis the controllers raised a_total; on the circuit states (closed
load-holding valves for baseline and passive, errata 11) and the seat pad under a seated
occupant (errata 13) they lower it (the variants below switch each back):

- the plant (:func:`loader_model.plant.linear.linearise_plant`) at the static equilibrium of the
  load case, on the circuit of each controller as in the trials
  (:meth:`~loader_model.plant.plant_parameters.PlantOptions.for_controller`: baseline and
  passive on closed load-holding valves, passive with the accumulator);
- the controllers' own linear equivalents, continuous
  (:func:`loader_model.control.linear_controller.linear_controller`), the loop closed by
  :func:`~loader_model.control.linear_controller.closed_loop`;
- the road: one board of height h and width b under a point contact, front axle then rear axle
  after the wheelbase delay L/v, with its rate (the plant's ``w_Ay``, ``wd_Ay``, ``w_By``, ``wd_By``):

  .. math::

      R(\omega) = h\,\frac{1 - e^{-j\omega b/v}}{j\omega}, \qquad
      H_o(\omega) = \big(G_{o,A}(\omega) + j\omega G_{o,\dot A}(\omega)\big)
                    + e^{-j\omega L/v}\big(G_{o,B}(\omega) + j\omega G_{o,\dot B}(\omega)\big)

- the seat as in the trials: k_o W_o H_o R for o = f_Px (Wd, k 1), f_Py (Wk, k 1) of the seat pad
  under the occupant, θ̈1 (We, k 0.4) of the chassis
  (Eq. 49, 50); the energy :math:`E = \sum_o \int |k_o W_o H_o R|^2 df` over 0.05-100 Hz.

For one transient of fixed duration, a_total ∝ √E, so the change against the baseline is
√(E_c / E_baseline) − 1, the linear counterpart of a Table 6 cell (one board instead of five, no
lift-off, no rigid-wheel envelope). Variants change named plant parameters (sensitivities, not
model values: the report says which are which).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from loader_model.experiments.tables import Rows

__all__ = [
    "GAIN_PROBES",
    "LINEAR_CONTROLLERS",
    "PARAMETER_VARIANTS",
    "board_changes",
    "cause_rows",
    "gain_rows_linear",
    "plant_modes",
]

#: Controllers of the linear comparison, Table 6's order (baseline first).
LINEAR_CONTROLLERS: tuple[str, ...] = ("baseline", "passive", "virtual_accumulator", "skyhook")

#: Parameter variants of the cause table: label -> {plant parameter: value or "x<factor>"}.
PARAMETER_VARIANTS: dict[str, dict[str, Any]] = {
    "model (parameter files)": {},
    "sensitivity: k_Lp = 0 (no Table 5 leakage slope)": {"k_Lp": 0.0},
    "sensitivity: load-holding valves open for every controller (Table 5 as a cylinder leak)": {
        "holding_open": 1.0
    },
    "sensitivity: occupant off (the seat read on the rigid chassis at S)": {"occupant_on": 0.0},
    "sensitivity: seal friction off (Table 4)": {"friction_on": 0.0},
    "sensitivity: tyre damping c_y x2": {"c_Ay": "x2", "c_By": "x2"},
}

#: Skyhook gain sets of the gain table: label -> K_fb (normalised, Table 3's order).
GAIN_PROBES: dict[str, tuple[float, float, float, float]] = {
    "Table 3 (2.75, 5.1, -4.0, -0.22)": (2.75, 5.1, -4.0, -0.22),
    "k_xd = +20 only": (20.0, 0.0, 0.0, 0.0),
    "k_xd = -20 only": (-20.0, 0.0, 0.0, 0.0),
    "k_yd = +20 only": (0.0, 20.0, 0.0, 0.0),
    "k_yd = -20 only": (0.0, -20.0, 0.0, 0.0),
    "k_thd = +20 only": (0.0, 0.0, 20.0, 0.0),
    "k_thd = -20 only": (0.0, 0.0, -20.0, 0.0),
    "k_phi = +0.22 only": (0.0, 0.0, 0.0, 0.22),
    "k_phi = -0.22 only": (0.0, 0.0, 0.0, -0.22),
}

_SEAT = (("f_Px", "Wd", 1.0), ("f_Py", "Wk", 1.0), ("thetadd_1", "We", 0.4))
_ROAD = ("w_Ay", "wd_Ay", "w_By", "wd_By")


def _parameters(load: str, controller: str, overrides: dict[str, Any]) -> np.ndarray:
    from loader_model.plant.plant_parameters import (
        PLANT_PARAMETER_NAMES,
        PlantOptions,
        plant_parameter_vector,
    )

    params = plant_parameter_vector(None, load, PlantOptions.for_controller(controller))
    for name, value in overrides.items():
        index = PLANT_PARAMETER_NAMES.index(name)
        if isinstance(value, str):  # "x<factor>": scale the file's value
            params[index] *= float(value[1:])
        else:
            params[index] = float(value)
    return params


def _closed_loops(
    load: str, overrides: dict[str, Any], gains: tuple[float, ...] | None = None
) -> dict[str, tuple[Any, np.ndarray]]:
    """Linear closed loops (inputs: the exogenous w) and their parameter vectors, per controller."""
    from loader_model.control.linear_controller import closed_loop, linear_controller
    from loader_model.control.sensors import sensor_signals
    from loader_model.control.settings import default_settings, settings_vector_for_plant
    from loader_model.parameters.sets import bucket_load
    from loader_model.plant.equilibrium import static_state
    from loader_model.plant.linear import linearise_plant
    from loader_model.plant.plant import plant_function
    from loader_model.plant.plant_parameters import PlantOptions

    settings = default_settings()
    if gains is not None:
        settings = dataclasses.replace(settings, k_fb=tuple(float(g) for g in gains))
    norm = bucket_load(load).pressure_normalisation
    plants: dict[Any, tuple[Any, np.ndarray, np.ndarray, float]] = {}
    loops = {}
    for name in LINEAR_CONTROLLERS:
        circuit = PlantOptions.for_controller(name)
        if circuit not in plants:  # one equilibrium per plant
            params = _parameters(load, name, overrides)
            x0, u0 = static_state(params)
            y0 = np.asarray(plant_function()(x0, u0, np.zeros(11), params)[1]).ravel()
            linear = linearise_plant(params, x0, u0).state_space()
            plants[circuit] = (linear, params, y0, u0)
        plant, params, y0, u0 = plants[circuit]
        if name in ("baseline", "passive"):  # the pump holds its static command
            loops[name] = (plant, params)
            continue
        vector = settings_vector_for_plant(settings, params, norm, hold_command=u0)
        controller = linear_controller(name, vector, sensor_signals(y0)).continuous
        loops[name] = (closed_loop(plant, controller), params)
    return loops


def _board_energy(
    system: Any,
    params: np.ndarray,
    speed_kmh: float,
    height_m: float,
    width_m: float,
    frequency_hz: np.ndarray,
) -> float:
    """E of the module notes for one closed loop."""
    import control

    from loader_model.iso2631.weightings import weighting_response
    from loader_model.plant.plant_parameters import PLANT_PARAMETER_NAMES

    named = dict(zip(PLANT_PARAMETER_NAMES, params, strict=True))
    speed = speed_kmh / 3.6
    delay = (named["A_x"] - named["B_x"]) / speed
    omega = 2 * np.pi * frequency_hz
    response = control.frequency_response(system, omega).complex
    inputs, outputs = list(system.input_labels), list(system.output_labels)
    column = {name: inputs.index(name) for name in _ROAD}
    road = height_m * (1 - np.exp(-1j * omega * width_m / speed)) / (1j * omega)
    energy = 0.0
    for output, weighting, k in _SEAT:
        g = response[outputs.index(output)]
        front = g[column["w_Ay"]] + 1j * omega * g[column["wd_Ay"]]
        rear = g[column["w_By"]] + 1j * omega * g[column["wd_By"]]
        seat = (front + np.exp(-1j * omega * delay) * rear) * road
        weighted = k * weighting_response(weighting, frequency_hz) * seat
        energy += float(np.trapezoid(np.abs(weighted) ** 2, frequency_hz))
    return energy


def board_changes(
    load: str = "empty",
    speed_kmh: float = 9.0,
    overrides: dict[str, Any] | None = None,
    gains: tuple[float, ...] | None = None,
    *,
    height_m: float = 0.04,
    width_m: float = 0.14,
) -> dict[str, float]:
    """Linear change of the seat's a_total against the baseline, per controller, in percent.

    Parameters
    ----------
    load : str
        ``"empty"`` or ``"full"``.
    speed_kmh : float
        Driving speed.
    overrides : dict, optional
        Plant parameters to replace: a number, or ``"x<factor>"`` to scale the file's value.
    gains : tuple of 4 float, optional
        Skyhook K_fb (default: Table 3 from the controller file).
    height_m, width_m : float
        The board (section 5.3: 4 cm; width as the course module assumes).

    Returns
    -------
    dict
        Controller -> change in percent (baseline 0.0), and ``"baseline a_total"``, the baseline's
        √E in m/s²·√s (for scale only).
    """
    frequency = np.linspace(0.05, 100.0, 4000)
    loops = _closed_loops(load, overrides or {}, gains)
    energy = {
        name: _board_energy(system, params, speed_kmh, height_m, width_m, frequency)
        for name, (system, params) in loops.items()
    }
    base = energy["baseline"]
    changes = {name: 100.0 * (np.sqrt(e / base) - 1.0) for name, e in energy.items()}
    changes["baseline a_total"] = float(np.sqrt(base))
    return changes


def plant_modes(
    load: str = "empty",
    overrides: dict[str, Any] | None = None,
    band_hz: tuple[float, float] = (1.0, 15.0),
) -> list[tuple[float, float]]:
    """(frequency [Hz], damping ratio) of the baseline plant's modes in ``band_hz``, slowest first."""
    system, _ = _closed_loops(load, overrides or {})["baseline"]
    poles = np.linalg.eigvals(np.asarray(system.A))
    poles = poles[np.imag(poles) > 0]
    modes = sorted((abs(p) / (2 * np.pi), -p.real / abs(p)) for p in poles)
    return [(f, z) for f, z in modes if band_hz[0] <= f <= band_hz[1]]


def _percent(value: float) -> str:
    return f"{value:+.1f}"


def cause_rows(load: str = "empty", speed_kmh: float = 9.0) -> Rows:
    """The cause table: baseline modes and linear changes per controller, per variant."""
    rows: Rows = [
        [
            "variant",
            "baseline modes 1-15 Hz [Hz/ζ]",
            "passive Δ [%]",
            "virtual-accumulator Δ [%]",
            "skyhook Δ [%]",
        ]
    ]
    for label, overrides in PARAMETER_VARIANTS.items():
        changes = board_changes(load, speed_kmh, overrides)
        modes = " ".join(f"{f:.2f}/{z:.2f}" for f, z in plant_modes(load, overrides))
        rows.append(
            [
                label,
                modes,
                *(_percent(changes[c]) for c in ("passive", "virtual_accumulator", "skyhook")),
            ]
        )
    return rows


def gain_rows_linear(load: str = "empty", speed_kmh: float = 9.0) -> Rows:
    """The skyhook with probe gains (:data:`GAIN_PROBES`): change against the virtual accumulator
    (the same pressure loop with K_fb = 0) and the slowest closed-loop pole's real part."""
    rows: Rows = [["skyhook K_fb", "Δ against virtual accumulator [%]", "max Re(pole) [rad/s]"]]
    reference = board_changes(load, speed_kmh)
    for label, gains in GAIN_PROBES.items():
        changes = board_changes(load, speed_kmh, gains=gains)
        system, _ = _closed_loops(load, {}, gains)["skyhook"]
        ratio = (1 + changes["skyhook"] / 100) / (1 + reference["virtual_accumulator"] / 100)
        worst = float(np.max(np.linalg.eigvals(np.asarray(system.A)).real))
        rows.append([label, _percent(100 * (ratio - 1)), f"{worst:+.2f}"])
    return rows
