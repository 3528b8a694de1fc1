r"""The ride-comfort design plant: detailed linear plant + skyhook structure + road + ISO weightings.

One model, no stand-in: the plant is :func:`loader_model.plant.linear.linearise_plant` at the
static equilibrium of the load case, the controller is the linear equivalent of the 1 kHz skyhook
Function (:func:`loader_model.control.linear_controller.linear_controller`, continuous), opened
at its static gain. The skyhook law (module :mod:`loader_model.control.controllers`) is

.. math::

    V_{p,ref} = u_{hold} + k_p V_{p,max}\big(r - \mathrm{HP}(p_A)/\|p_A\|\big),
    \qquad r = p_{A,ref}/\|p_A\| = -K_{fb}\,\hat y,

bilinear in K_fb and the filtered signals ŷ = (semi-integrated normalised f_Hx, f_Hy − g, θ̈1
estimate; (φ − φ0)/‖φ‖). So the command's Jacobian at gain K is C(K) = C(0) − k_p V_p,max Σ_i K_i c_i
with c_i the row of ŷ_i, and ŷ_i is read off the same Function: c_i = (C(0) − C(e_i)) / (k_p V_p,max)
(exact: the law is linear in K). The design plant's control input is r (``p_ref_n``), entering
V_p,ref with gain k_p V_p,max; its measured outputs are ŷ (``yh_x``, ``yh_y``, ``yh_theta``,
``yh_phi``); then u = −K y of :func:`~loader_model.control.comfort_design.optimise_gain` is exactly
r = −K_fb ŷ and K is K_fb.

Performance outputs (Eq. 49, 50): the seat pad's specific force (the seated occupant on the
cushion at S, :mod:`loader_model.plant.occupant`, as section 5.3 measured) and the chassis pitch
acceleration through the ISO 2631-1 weightings, k_x W_d f_Px, k_y W_k f_Py, k_θ W_e θ̈1 with
k = (1, 1, 0.4); the sum of their mean squares is a_total². Road: :mod:`road_filter`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from loader_model.control.road_filter import road_shaping_filter
from loader_model.control.settings import (
    SETTINGS_NAMES,
    default_settings,
    settings_vector_for_plant,
)

if TYPE_CHECKING:
    from loader_model.plant.layout import PlantLayout
    from loader_model.plant.scenario import PlantScenario

__all__ = [
    "FIXED_STATES",
    "GAIN_NAMES",
    "MEASURED",
    "PERFORMANCE",
    "PERFORMANCE_K",
    "ComfortCase",
    "comfort_case",
    "comfort_system",
    "seat_weightings",
    "skyhook_structure",
]

#: Measured outputs ŷ of the design plant (order of K_fb, Eq. 40).
MEASURED: tuple[str, ...] = ("yh_x", "yh_y", "yh_theta", "yh_phi")
#: Weighted seat outputs: (name, plant output, ISO weighting, k of Eq. 50).
PERFORMANCE_K: tuple[tuple[str, str, str, float], ...] = (
    ("aw_x", "f_Px", "Wd", 1.0),
    ("aw_y", "f_Py", "Wk", 1.0),
    ("aw_theta", "thetadd_1", "We", 0.4),
)
PERFORMANCE: tuple[str, ...] = tuple(p[0] for p in PERFORMANCE_K)
GAIN_NAMES: tuple[str, ...] = ("k_x", "k_y", "k_theta", "k_phi")
#: States after the plant and skyhook in :func:`comfort_system` with the independent rear road:
#: road (2) + W_d (6) + W_k (8) + W_e (6), in cascade with the loop.
FIXED_STATES = 22


@dataclass(frozen=True)
class ComfortCase:
    """Linearised plant, settings vector and static sensor readings of one bucket load."""

    load: str
    params: np.ndarray
    plant: Any
    settings: np.ndarray
    sensors: np.ndarray
    layout: PlantLayout
    """The machine of the plant (its :attr:`~loader_model.plant.scenario.PlantScenario.layout`)."""
    pressure_norm: float = 0.0
    """‖p_A‖∞ of the controller's normalisation, Pa (the paper's norm of the bucket load for the
    skid-steer; :func:`~loader_model.plant.machine_parameters.pressure_norm` otherwise)."""


_CASES: dict[tuple[str, tuple[float, ...] | None, PlantLayout | None], ComfortCase] = {}


def _pressure_norm(load: str, plant: PlantScenario) -> float:
    if plant.is_default_machine:
        from loader_model.parameters.sets import bucket_load

        return bucket_load(load).pressure_normalisation
    from loader_model.plant.machine_parameters import pressure_norm

    return pressure_norm(plant.output("p_A"))


def _case(load: str, plant: PlantScenario) -> ComfortCase:
    """The case of ``plant``: its equilibrium, static readings and linearisation, computed once."""
    from loader_model.control.sensors import sensor_signals
    from loader_model.plant.linear import linearise_plant

    params = np.array(plant.params)
    norm = _pressure_norm(load, plant)
    settings = settings_vector_for_plant(
        default_settings(), params, norm, hold_command=plant.u0, layout=plant.layout
    )
    linear = linearise_plant(params, np.array(plant.x0), plant.u0, machine=plant.layout)
    system = linear.state_space(name=f"plant_{load}")
    sensors = sensor_signals(np.array(plant.y0), plant.layout)
    return ComfortCase(load, params, system, settings, sensors, plant.layout, norm)


def comfort_case(load: str, params: np.ndarray | PlantScenario | None = None) -> ComfortCase:
    """:class:`ComfortCase` of ``load`` (``"empty"`` or ``"full"``): default parameters,
    ``params`` (a vector) or a resolved plant (its equilibrium is not computed again; of any
    machine); cached per load, parameter vector and machine."""
    from loader_model.plant.scenario import PlantScenario, resolve_plant

    if load not in ("empty", "full"):
        raise ValueError(f"load must be 'empty' or 'full'; got {load!r}")
    plant = params if isinstance(params, PlantScenario) else None
    vector = None if params is None else np.asarray(params if plant is None else plant.params)
    machine = None if plant is None else plant.layout
    key = (load, None if vector is None else tuple(float(v) for v in vector.ravel()), machine)
    if key not in _CASES:
        if plant is None:
            plant = (
                resolve_plant(None, load) if vector is None else PlantScenario.from_vector(vector)
            )
        _CASES[key] = _case(load, plant)
    return _CASES[key]


def skyhook_structure(case: ComfortCase) -> Any:
    """The skyhook's linear equivalent at K_fb = 0 with input ``p_ref_n`` added and ŷ as outputs.

    Inputs: sensor names, then ``p_ref_n``; outputs the plant's command (``V_p_ref``, or a
    valve circuit's ``x_s_ref``) then :data:`MEASURED`.
    """
    import control

    from loader_model.control.linear_controller import linear_controller

    index = [SETTINGS_NAMES.index(n) for n in GAIN_NAMES]
    zero = case.settings.copy()
    zero[index] = 0.0
    base = linear_controller("skyhook", zero, case.sensors).continuous
    scale = zero[SETTINGS_NAMES.index("k_p")] * zero[SETTINGS_NAMES.index("V_p_max")]
    rows_c, rows_d = [], []
    for i in index:
        unit = zero.copy()
        unit[i] = 1.0
        probe = linear_controller("skyhook", unit, case.sensors).continuous
        rows_c.append((np.asarray(base.C) - np.asarray(probe.C)) / scale)
        rows_d.append((np.asarray(base.D) - np.asarray(probe.D)) / scale)
    a, b = np.asarray(base.A), np.asarray(base.B)
    c = np.vstack([np.asarray(base.C), *rows_c])
    d = np.vstack([np.asarray(base.D), *rows_d])
    b = np.hstack([b, np.zeros((a.shape[0], 1))])
    d = np.hstack([d, np.zeros((d.shape[0], 1))])
    d[0, -1] = scale
    return control.ss(
        a,
        b,
        c,
        d,
        inputs=[*base.input_labels, "p_ref_n"],
        outputs=[case.plant.input_labels[0], *MEASURED],
        states=list(base.state_labels),
        name="skyhook_structure",
    )


def seat_weightings() -> list[Any]:
    """k_i W_i of Eq. 50 as ``StateSpace`` blocks: input the plant output, output ``aw_*``."""
    import control

    from loader_model.iso2631.weightings import weighting_state_space

    blocks = []
    for out, signal, weighting, k in PERFORMANCE_K:
        w = weighting_state_space(weighting, input_name=signal, output_name=out)
        blocks.append(
            control.ss(
                w.A,
                w.B,
                k * w.C,
                k * w.D,
                inputs=[signal],
                outputs=[out],
                states=[f"{out}_{s}" for s in w.state_labels],
                name=out,
            )
        )
    return blocks


def comfort_system(
    case: ComfortCase,
    road_class: str = "C",
    speed_m_s: float = 2.5,
    rear: str = "independent",
    pade_order: int = 4,
) -> Any:
    """Interconnected ``StateSpace`` of the design (module docstring).

    Inputs: ``p_ref_n`` (control r), the road's unit white noise (``nu_road`` and, with
    ``rear="independent"``, ``nu_rear`` and ``nu_rear_<axle>`` for every further axle of the
    machine: :func:`~loader_model.control.road_filter.road_shaping_filter`), ``M_d`` [N·m]
    (Fig. 12).
    Outputs: :data:`MEASURED`, :data:`PERFORMANCE`, then ``V_p``, ``p_A``, ``thetad_1``,
    ``thetadd_1``, ``V_p_ref`` (unweighted, for limits and plots; ``V_p`` and ``V_p_ref`` are
    the actuator's position and command: a valve circuit's spool x_s and its command, in m).
    """
    import control

    layout = case.layout
    named = dict(zip(layout.parameter_names, case.params, strict=True))
    first, last = layout.machine.axles[0], layout.machine.axles[-1]
    wheelbase = float(named[f"{first}_x"] - named[f"{last}_x"])
    road = road_shaping_filter(
        road_class, speed_m_s, wheelbase, rear, pade_order, axles=layout.machine.axles
    )
    weights = seat_weightings()
    plant = case.plant.name
    noise = list(road.input_labels)
    actuator, command = layout.actuator_state, case.plant.input_labels[0]
    extra = [f"{plant}.{n}" for n in (actuator, "p_A", "thetad_1", "thetadd_1")]
    return control.interconnect(
        [case.plant, skyhook_structure(case), road, *weights],
        inplist=["skyhook_structure.p_ref_n", *(f"road.{n}" for n in noise), f"{plant}.M_d"],
        inputs=["p_ref_n", *noise, "M_d"],
        outlist=[*MEASURED, *PERFORMANCE, *extra, f"skyhook_structure.{command}"],
        outputs=[*MEASURED, *PERFORMANCE, "V_p", "p_A", "thetad_1", "thetadd_1", "V_p_ref"],
        name=f"comfort_{case.load}",
        check_unused=False,
    )
