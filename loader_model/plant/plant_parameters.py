"""The plant's parameter vector: the generated model's, the hydraulic drive's, the occupant's.

One parameter flow: :func:`plant_parameter_vector` fills the whole vector from the parameter files
(loader and bucket load) and the :class:`PlantOptions` switches; the plant Function takes it as
its input ``params`` and completes the static equilibrium inside its graph. Names, units and
descriptions are exported (:data:`PLANT_PARAMETER_NAMES`, ...); a test checks them against the
Function's input. Switches are parameters too (0 or 1), so one compiled plant serves every setting.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

import loader_model_generated as generated
from loader_model.plant.occupant import OCCUPANT_PARAMETERS

__all__ = [
    "HYDRAULIC_PARAMETERS",
    "IDLE_PUMP_CONTROLLERS",
    "OCCUPANT_PARAMETERS",
    "PLANT_PARAMETER_NAMES",
    "PLANT_PARAMETER_UNITS",
    "PlantOptions",
    "plant_parameter_vector",
]

#: (name, unit, description) of the hydraulic entries, after the generated model's parameters.
HYDRAULIC_PARAMETERS: tuple[tuple[str, str, str], ...] = (
    ("n_cyl", "-", "number of lift cylinders in parallel"),
    ("d_piston", "m", "piston diameter (A_p of Eq. 30, per cylinder)"),
    ("d_rod", "m", "rod diameter (per cylinder)"),
    ("stroke", "m", "cylinder stroke"),
    ("L_retracted", "m", "pin-to-pin length at the retracted end stop"),
    ("V_dead_A", "m^3", "dead volume of the piston side, per cylinder"),
    ("V_dead_B", "m^3", "dead volume of the rod side, per cylinder"),
    ("k_end", "N/m", "stiffness of the stroke's end stops"),
    ("c_end", "N*s/m", "damping of the stroke's end stops"),
    ("K_oil", "Pa", "effective bulk modulus (Eq. 36, 37; Table 5)"),
    ("rho_oil", "kg/m^3", "oil density (orifice law)"),
    ("p_charge", "Pa", "charge pressure, gauge (sections 2.4, 3.2)"),
    ("G_charge", "m^3/(s*Pa)", "conductance of the low-side valve tying the rod side to charge"),
    ("G_check", "m^3/(s*Pa)", "conductance of the piston side's anti-cavitation check valve"),
    ("p_relief", "Pa", "setting of the piston side's pressure relief valve, gauge"),
    ("G_relief", "m^3/(s*Pa)", "conductance of the relief valve above its setting"),
    ("k_Lp", "m^3/(s*Pa)", "pump-side regression flow, pressure coefficient (Eq. 47, Table 5)"),
    ("k_Lv", "m^2", "pump-side regression flow, velocity coefficient (Eq. 48 sign, Table 5)"),
    ("k_seal", "m^3/(s*Pa)", "piston-seal cross-port leakage per cylinder (valves closed)"),
    ("f_s", "N", "static friction (Eq. 46, Table 4)"),
    ("tau_s", "s/m", "Stribeck decay (Eq. 46)"),
    ("gamma_f", "s/m", "tanh slope (Eq. 46)"),
    ("f_C", "N/Pa", "pressure-dependent Coulomb friction (Eq. 46)"),
    ("f_v", "N*s/m", "viscous friction (Eq. 46)"),
    ("V_p_max", "m^3/rev", "maximum pump displacement (section 2.4)"),
    ("n_pump", "rev/s", "pump shaft speed"),
    ("omega_p", "rad/s", "natural frequency of the displacement loop (Fig. 9, Table 2)"),
    ("zeta_p", "-", "damping ratio of the displacement loop (Table 2)"),
    ("Vd_p_max", "m^3/(rev*s)", "displacement rate limit (Table 2, errata 8)"),
    ("n_acc", "-", "number of accumulators on the piston side"),
    ("p_0", "Pa", "accumulator precharge, gauge"),
    ("V_0", "m^3", "accumulator gas volume at precharge, per accumulator"),
    ("n_poly", "-", "polytropic exponent of the accumulator gas"),
    ("d_orifice", "m", "accumulator damping orifice diameter"),
    ("C_d", "-", "orifice discharge coefficient"),
    ("dp_laminar", "Pa", "pressure drop of the orifice's laminar-turbulent transition"),
    ("pump_on", "-", "1: pump flow acts; 0: pump at zero displacement (Eq. 28)"),
    ("valves_on", "-", "1: charge, check and relief valves act; 0: all shut (Eq. 28)"),
    ("leakage_on", "-", "1: leakage acts (Table 5's flow or the seal's); 0: none"),
    ("friction_on", "-", "1: seal friction acts; 0: none"),
    ("accumulator_on", "-", "1: accumulator connected (passive ride control); 0: shut off"),
    ("holding_open", "-", "1: load-holding valves open (pump circuit); 0: closed (sealed)"),
)

PLANT_PARAMETER_NAMES: tuple[str, ...] = generated.PARAMETER_NAMES + tuple(
    name for name, _, _ in HYDRAULIC_PARAMETERS + OCCUPANT_PARAMETERS
)
PLANT_PARAMETER_UNITS: dict[str, str] = dict(generated.PARAMETER_UNITS) | {
    name: unit for name, unit, _ in HYDRAULIC_PARAMETERS + OCCUPANT_PARAMETERS
}
#: Controllers that leave the pump idle: the boom sits on closed load-holding valves
#: (guide page "Controllers"; errata 11). Every other controller drives the pump through them.
IDLE_PUMP_CONTROLLERS: tuple[str, ...] = ("baseline", "passive")


@dataclass(frozen=True)
class PlantOptions:
    """Switches of the plant (paper Eq. 28 closes the chambers: all hydraulic parts off).

    Attributes
    ----------
    pump, valves, leakage, friction, accumulator : bool
        Whether each part acts. ``closed()`` gives the chambers-closed setting of Eq. 28.
    holding : bool
        Load-holding valves open (the pump's circuit reaches the cylinders, Table 5's flow
        acts) or closed (the cylinders and the accumulator sealed from the pump, only the
        piston seals leak): :mod:`loader_model.plant.circuit`.
    occupant : bool
        The seated occupant on the cushion at S (:mod:`loader_model.plant.occupant`); off: the
        pad outputs equal the chassis's f_S.
    """

    pump: bool = True
    valves: bool = True
    leakage: bool = True
    friction: bool = True
    accumulator: bool = False
    holding: bool = True
    occupant: bool = True

    @classmethod
    def closed(cls) -> PlantOptions:
        """Both chambers closed: pump at zero displacement, valves shut, no leakage or friction."""
        return cls(
            pump=False,
            valves=False,
            leakage=False,
            friction=False,
            accumulator=False,
            holding=False,
        )

    @classmethod
    def for_controller(cls, controller: str, *, occupant: bool = True) -> PlantOptions:
        """The circuit a ride controller runs on (guide page "Controllers"; errata 11).

        ``baseline`` and ``passive`` (:data:`IDLE_PUMP_CONTROLLERS`) leave the pump idle: the
        boom sits on closed load-holding valves, ``passive`` with the accumulator connected
        between valves and cylinder. Every other controller (``virtual-accumulator``,
        ``skyhook`` and the designed skyhook gains; ``_`` or ``-`` alike) drives the pump
        through open valves, accumulator shut.

        Raises
        ------
        ValueError
            If ``controller`` is not a non-empty string.
        """
        return cls(occupant=bool(occupant)).with_controller(controller)

    def with_controller(self, controller: str) -> PlantOptions:
        """These switches with the circuit of ``controller`` (:meth:`for_controller`): the
        load-holding valves and the accumulator set, every other switch kept."""
        if not isinstance(controller, str) or not controller:
            raise ValueError(f"controller must be a non-empty name; got {controller!r}")
        name = controller.replace("_", "-")
        idle = name in IDLE_PUMP_CONTROLLERS
        return replace(self, accumulator=name == "passive", holding=not idle)

    def switches(self) -> dict[str, float]:
        """The switch entries of the parameter vector (0.0 or 1.0), by parameter name."""
        return {
            "pump_on": float(self.pump),
            "valves_on": float(self.valves),
            "leakage_on": float(self.leakage),
            "friction_on": float(self.friction),
            "accumulator_on": float(self.accumulator),
            "holding_open": float(self.holding),
            "occupant_on": float(self.occupant),
        }


def plant_parameter_vector(
    loader: Any, load: Any, options: PlantOptions | None = None, *, check: bool = True
) -> np.ndarray:
    """The plant's parameter vector (order :data:`PLANT_PARAMETER_NAMES`) from parameter files.

    Parameters
    ----------
    loader, load
        A :class:`loader_model.parameters.sets.LoaderParameters` and
        :class:`loader_model.parameters.sets.BucketLoad` (or what
        :func:`loader_model.vehicle.statics.resolve_machine` accepts).
    options : PlantOptions, optional
        Switches; default: pump, valves, leakage and friction on, load-holding valves open,
        accumulator off, occupant on (:meth:`PlantOptions.for_controller` per controller).
    check : bool
        Check the loader and load together at the static equilibrium first
        (:func:`loader_model.vehicle.statics.check_combination`).
    """
    from loader_model import parameters
    from loader_model.vehicle import statics

    options = options or PlantOptions()
    given = isinstance(loader, parameters.LoaderParameters) and isinstance(
        load, parameters.BucketLoad
    )
    if not given:  # files or names: resolving them also checks the combination
        loader, load = statics.resolve_machine(loader, load)
    elif check:
        statics.check_combination(loader, load)
    mechanical = parameters.model_parameter_values(loader, load)
    cyl, hyd, leak, fric = loader.cylinders, loader.hydraulics, loader.leakage, loader.friction
    pump, acc, seat = loader.pump, loader.accumulator, loader.seat
    values = mechanical | {
        "F_Ay0": 0.0,
        "F_By0": 0.0,
        "n_cyl": cyl.count,
        "d_piston": cyl.piston_diameter,
        "d_rod": cyl.rod_diameter,
        "stroke": cyl.stroke,
        "L_retracted": cyl.retracted_length,
        "V_dead_A": cyl.dead_volume_a,
        "V_dead_B": cyl.dead_volume_b,
        "k_end": cyl.end_stop_stiffness,
        "c_end": cyl.end_stop_damping,
        "K_oil": hyd.bulk_modulus,
        "rho_oil": hyd.oil_density,
        "p_charge": hyd.charge_pressure,
        "G_charge": hyd.charge_conductance,
        "G_check": hyd.check_valve_conductance,
        "p_relief": hyd.relief_pressure,
        "G_relief": hyd.relief_conductance,
        "k_Lp": leak.k_lp,
        "k_Lv": leak.k_lv,
        "k_seal": leak.k_seal,
        "f_s": fric.f_s,
        "tau_s": fric.tau_s,
        "gamma_f": fric.gamma,
        "f_C": fric.f_c,
        "f_v": fric.f_v,
        "V_p_max": pump.max_displacement,
        "n_pump": pump.shaft_speed,
        "omega_p": pump.natural_frequency_rad_s,
        "zeta_p": pump.damping_ratio,
        "Vd_p_max": pump.displacement_rate_limit,
        "n_acc": acc.count,
        "p_0": acc.precharge_pressure,
        "V_0": acc.gas_volume,
        "n_poly": acc.polytropic_exponent,
        "d_orifice": acc.orifice_diameter,
        "C_d": acc.discharge_coefficient,
        "dp_laminar": acc.laminar_transition_pressure,
        "m_seated": seat.seated_mass,
        "m_pad": seat.pad_mass,
        "r_occ_x": seat.fore_aft_rigid_fraction,
        "f_occ_x": seat.fore_aft_frequency,
        "zeta_occ_x": seat.fore_aft_damping_ratio,
        "k_cush_x": seat.cushion_stiffness_x,
        "c_cush_x": seat.cushion_damping_x,
        "r_occ_y": seat.vertical_rigid_fraction,
        "f_occ_y": seat.vertical_frequency,
        "zeta_occ_y": seat.vertical_damping_ratio,
        "k_cush_y": seat.cushion_stiffness_y,
        "c_cush_y": seat.cushion_damping_y,
    }
    values |= options.switches()
    return np.array([float(values[name]) for name in PLANT_PARAMETER_NAMES])
