"""The plant parameter vector of a described machine other than the skid-steer.

A machine's flat parameter file (:mod:`loader_model.parameters.machine_files`) gives its
multibody model, its lift cylinder group and the oil's bulk modulus and charge pressure. The rest
of the plant (pump, valves, leakage, seal friction, accumulator, seated occupant) is not in it:
no manufacturer publishes those values for a compact machine, and the paper identified them on
its skid-steer only. They are taken from the skid-steer's shipped defaults
(``loader_model/data/default_loader.toml``) and are estimates for any other machine, with one
rule that keeps the accumulator working: its precharge is the skid-steer's fraction of the
static piston pressure (50 bar of 89 bar, 0.56) applied to the machine's lightest load case, so
the accumulator holds oil in every load case (a precharge above the static pressure holds none).

A machine with a valve circuit (``[circuit] kind = "valve"``) takes its valve, compensator and
supply from the ``[valve]`` table of its file (:func:`valve_plant_entries`) and has no pump,
charge line or Table 5 regression flow; the rest is as above.
"""

from __future__ import annotations

from functools import cache

import numpy as np

from loader_model.machines import MachineInfo
from loader_model.parameters.valve import ValveParameters
from loader_model.plant.layout import PlantLayout
from loader_model.plant.plant_parameters import PlantOptions, plant_parameter_vector

__all__ = [
    "PRECHARGE_FRACTION",
    "PRESSURE_NORM_FACTOR",
    "machine_plant_parameter_vector",
    "precharge_pressure",
    "pressure_norm",
    "valve_plant_entries",
]

#: Accumulator precharge / static piston pressure of the lightest load (the skid-steer's 50/89).
PRECHARGE_FRACTION = 0.56
#: ‖p_A‖∞ of the controllers' normalisation / the static piston pressure of the load, for a
#: machine without the paper's norms (the skid-steer: 100/89 = 1.12 empty, 200/130 = 1.54 full).
PRESSURE_NORM_FACTOR = 1.5


def pressure_norm(static_piston_pressure_pa: float) -> float:
    """‖p_A‖∞ [Pa] of a machine other than the skid-steer: :data:`PRESSURE_NORM_FACTOR` times
    its static piston pressure (the skid-steer's loads carry the paper's 100 and 200 bar)."""
    return PRESSURE_NORM_FACTOR * float(static_piston_pressure_pa)


@cache
def _skid_steer_defaults() -> dict[str, float]:
    from loader_model.plant.plant_parameters import PLANT_PARAMETER_NAMES

    vector = plant_parameter_vector(None, "empty", PlantOptions())
    return dict(zip(PLANT_PARAMETER_NAMES, vector.tolist(), strict=True))


def precharge_pressure(info: MachineInfo, params: object = None) -> float:
    """Accumulator precharge [Pa gauge] of machine ``info``: :data:`PRECHARGE_FRACTION` of the
    lowest static piston pressure over its load cases (and its [model] values)."""
    from loader_model.parameters.machine_files import resolve_machine_parameters
    from loader_model.vehicle.statics import machine_static_equilibrium

    values = resolve_machine_parameters(info, params)  # type: ignore[arg-type]
    cases = (None, *values.loads)
    lowest = min(machine_static_equilibrium(info, values, case)["p_A0"] for case in cases)
    return PRECHARGE_FRACTION * lowest


def valve_plant_entries(valve: ValveParameters, supply: str = "load_sensing") -> dict[str, float]:
    """The valve circuit's entries of the plant parameter vector
    (:data:`~loader_model.plant.valve_circuit.VALVE_PARAMETERS`) from a ``[valve]`` table and
    the description's ``[circuit] supply`` (``"load_sensing"`` or ``"constant_pressure"``)."""
    if supply not in ("load_sensing", "constant_pressure"):
        raise ValueError(
            f"supply {supply!r} is not allowed; allowed: 'load_sensing', 'constant_pressure'"
        )
    return {
        "x_s_max": valve.spool_stroke,
        "w_s": valve.area_gradient,
        "x_s_lap": valve.overlap,
        "C_d_s": valve.discharge_coefficient,
        "dp_comp": valve.compensator_setting,
        "compensated": float(valve.compensated),
        "omega_s": valve.natural_frequency_rad_s,
        "zeta_s": valve.damping_ratio,
        "xd_s_max": valve.stroke_rate_limit,
        "G_spool": valve.leakage_conductance,
        "p_tank": valve.tank_pressure,
        "p_supply_max": valve.supply_max_pressure,
        "dp_LS": valve.load_sensing_margin,
        "Q_supply_max": valve.supply_max_flow,
        "load_sensing": float(supply == "load_sensing"),
    }


def machine_plant_parameter_vector(
    layout: PlantLayout,
    params: object = None,
    load: str | None = None,
    options: PlantOptions | None = None,
) -> np.ndarray:
    """The plant parameter vector of a machine (order ``layout.parameter_names``).

    Parameters
    ----------
    layout : PlantLayout
        The machine other than the skid-steer and its circuit
        (:func:`~loader_model.plant.layout.plant_layout`).
    params : MachineParameters, str, pathlib.Path or None
        Its parameter file (None: the shipped one).
    load : str, optional
        A bucket load case of the file (None: [model] as given).
    options : PlantOptions, optional
        Circuit switches (default as :func:`plant_parameter_vector`).

    Raises
    ------
    ValueError
        For the skid-steer (use :func:`plant_parameter_vector`), an invalid file or load, or a
        machine that does not stand at rest (:func:`~loader_model.vehicle.statics.
        resolve_machine_values`).
    """
    from loader_model.parameters.machine_files import resolve_machine_parameters
    from loader_model.vehicle.statics import resolve_machine_values

    info = layout.machine
    if info.is_default:
        raise ValueError("the skid-steer's plant vector is plant_parameter_vector(loader, load)")
    values = resolve_machine_parameters(info, params)  # type: ignore[arg-type]
    model = resolve_machine_values(info, values, load)
    cyl = values.cylinders
    entries = _skid_steer_defaults() | {n: model[n] for n in info.parameter_names if n in model}
    entries |= {n: 0.0 for n in info.static_names}  # completed inside the plant's graph
    entries |= {
        "n_cyl": cyl.count,
        "d_piston": cyl.piston_diameter,
        "d_rod": cyl.rod_diameter,
        "stroke": cyl.stroke,
        "L_retracted": cyl.retracted_length,
        "V_dead_A": cyl.dead_volume_a,
        "V_dead_B": cyl.dead_volume_b,
        "k_end": cyl.end_stop_stiffness,
        "c_end": cyl.end_stop_damping,
        "K_oil": values.hydraulics["bulk_modulus"],
        "p_0": precharge_pressure(info, values),
    }
    if values.valve is not None:
        entries |= valve_plant_entries(values.valve, info.circuit_supply)
    else:
        entries["p_charge"] = values.hydraulics["charge_pressure"]
    entries |= (options or PlantOptions()).switches()
    names = layout.parameter_names
    missing = [n for n in names if n not in entries]
    if missing:
        raise ValueError(f"machine {info.name!r}: no value for plant parameters {missing}")
    return np.array([float(entries[n]) for n in names])
