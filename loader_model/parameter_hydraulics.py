"""Parameter sets of the hydraulic drive and the controller (paper sections 2.3, 2.4, 3, 4.1).

Units follow the SI rule of :mod:`loader_model.parameter_schema`; the pump's per-revolution
quantities use m³/rev and rev/s as in Table 2 and the nomenclature.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from loader_model.parameter_fields import FINITE, NONNEGATIVE, POSITIVE, Range, integer, si

__all__ = [
    "AccumulatorParameters",
    "ControllerParameters",
    "CylinderParameters",
    "FrictionParameters",
    "HydraulicParameters",
    "LeakageParameters",
    "PumpParameters",
]


@dataclass(frozen=True)
class CylinderParameters:
    """Single-rod lift cylinders in parallel (section 2.3, Fig. 8).

    Attributes
    ----------
    count : int
        Number of identical cylinders acting in parallel.
    piston_diameter, rod_diameter : float
        Bore and rod diameter in m (A_p, A_r of Eq. 30).
    stroke : float
        Stroke in m.
    retracted_length : float
        Pin-to-pin length at the retracted end stop in m.
    dead_volume_a, dead_volume_b : float
        Dead (line) volume of the piston side and of the rod side, per cylinder, in m³.
    end_stop_stiffness, end_stop_damping : float
        Stiffness in N/m and damping in N·s/m of the stroke's end stops, per cylinder.
    """

    count: int = field(metadata=integer())
    piston_diameter: float = field(metadata=si("m", POSITIVE))
    rod_diameter: float = field(metadata=si("m", POSITIVE))
    stroke: float = field(metadata=si("m", POSITIVE))
    retracted_length: float = field(metadata=si("m", POSITIVE))
    dead_volume_a: float = field(metadata=si("m^3", POSITIVE))
    dead_volume_b: float = field(metadata=si("m^3", POSITIVE))
    end_stop_stiffness: float = field(metadata=si("N/m", POSITIVE))
    end_stop_damping: float = field(metadata=si("N s/m", NONNEGATIVE))

    @property
    def piston_area(self) -> float:
        """Piston area A_p in m² (Eq. 30)."""
        return math.pi / 4.0 * self.piston_diameter**2

    @property
    def rod_area(self) -> float:
        """Rod cross-section A_r in m² (Eq. 30)."""
        return math.pi / 4.0 * self.rod_diameter**2

    @property
    def annulus_area(self) -> float:
        """Rod-side annulus area A_p − A_r = α A_p in m²."""
        return self.piston_area - self.rod_area


@dataclass(frozen=True)
class HydraulicParameters:
    """Oil and charge circuit.

    Attributes
    ----------
    bulk_modulus : float
        Effective bulk modulus K_oil in Pa (Eq. 28, 36, 37; Table 5).
    charge_pressure : float
        Charge-line pressure in Pa (gauge) feeding the rod side (sections 2.4, 3.2).
    oil_density : float
        Oil density in kg/m³ (orifice law of the accumulator).
    charge_conductance : float
        Conductance in m³/(s·Pa) of the low-side valve that ties the rod side to the charge line.
    check_valve_conductance : float
        Conductance in m³/(s·Pa) of the piston side's anti-cavitation check valve (open when
        p_A falls below the charge pressure).
    relief_pressure : float
        Setting in Pa (gauge) of the piston side's pressure relief valve.
    relief_conductance : float
        Conductance in m³/(s·Pa) of the relief valve above its setting.
    """

    bulk_modulus: float = field(metadata=si("Pa", POSITIVE))
    charge_pressure: float = field(metadata=si("Pa", POSITIVE))
    oil_density: float = field(metadata=si("kg/m^3", POSITIVE))
    charge_conductance: float = field(metadata=si("m^3/(s Pa)", POSITIVE))
    check_valve_conductance: float = field(metadata=si("m^3/(s Pa)", POSITIVE))
    relief_pressure: float = field(metadata=si("Pa", POSITIVE))
    relief_conductance: float = field(metadata=si("m^3/(s Pa)", POSITIVE))


@dataclass(frozen=True)
class LeakageParameters:
    """Internal seal leakage Q_L = k_Lp (p_A − p_B) − k_Lv ẋ_act (Eq. 47, Table 5).

    Attributes
    ----------
    k_lp : float
        Pressure coefficient k_Lp in m³/(s·Pa).
    k_lv : float
        Velocity coefficient k_Lv in m²; identified negative (−5.0e-4 m²), so any finite value.
    """

    k_lp: float = field(metadata=si("m^3/(s Pa)", NONNEGATIVE))
    k_lv: float = field(metadata=si("m^2", FINITE))


@dataclass(frozen=True)
class FrictionParameters:
    """Cylinder friction F_f = f_s e^(−τ_s|v|) tanh(γ v) + f_C p_A + f_v v (Eq. 46, Table 4).

    Attributes
    ----------
    f_s : float
        Static (Stribeck) friction force in N.
    tau_s : float
        Stribeck decay τ_s in s/m.
    gamma : float
        Slope γ of the tanh approximation of sign(v) in s/m.
    f_c : float
        Pressure-dependent Coulomb coefficient f_C in N/Pa (Table 4: 10.7 N/bar).
    f_v : float
        Viscous coefficient in N·s/m.
    """

    f_s: float = field(metadata=si("N", NONNEGATIVE))
    tau_s: float = field(metadata=si("s/m", NONNEGATIVE))
    gamma: float = field(metadata=si("s/m", NONNEGATIVE))
    f_c: float = field(metadata=si("N/Pa", NONNEGATIVE))
    f_v: float = field(metadata=si("N s/m", NONNEGATIVE))


@dataclass(frozen=True)
class PumpParameters:
    """Variable displacement pump with a rate-limited second-order displacement loop (Fig. 9).

    Attributes
    ----------
    max_displacement : float
        Maximum displacement V_p,max in m³/rev (section 2.4: 46 cm³/rev).
    shaft_speed : float
        Pump shaft speed in rev/s; the flow is Q = V_p n.
    natural_frequency : float
        ω_p in Hz as printed in Table 2 (see :attr:`natural_frequency_rad_s`).
    damping_ratio : float
        ζ_p (Table 2).
    displacement_rate_limit : float
        |dV_p/dt| limit in m³/(rev·s). Table 2 prints "±1.24 m³/s", which cannot be literal;
        read as 1.24e-3 m³/(rev·s), a full stroke in about 37 ms (DESIGN.md errata 8).
    """

    max_displacement: float = field(metadata=si("m^3/rev", POSITIVE))
    shaft_speed: float = field(metadata=si("rev/s", POSITIVE))
    natural_frequency: float = field(metadata=si("Hz", POSITIVE))
    damping_ratio: float = field(metadata=si("-", POSITIVE))
    displacement_rate_limit: float = field(metadata=si("m^3/(rev s)", POSITIVE))

    @property
    def natural_frequency_rad_s(self) -> float:
        """ω_p in rad/s (2π times :attr:`natural_frequency`)."""
        return 2.0 * math.pi * self.natural_frequency


@dataclass(frozen=True)
class ControllerParameters:
    """Skyhook output feedback and pressure loop (sections 3.2, 3.3; Table 3).

    Attributes
    ----------
    k_fb : tuple of 4 float
        Gains on the normalised outputs (ẋ_H, ẏ_H, θ̇1, φ) of Eq. 40, dimensionless.
    tau : float
        Corner τ of the semi-integrator 1/(s + τ) in rad/s.
    k_p : float
        Pressure-loop gain of V_p,ref = k_p (p_A,ref − p_A) on normalised signals.
    sample_rate : float
        Controller sample rate in Hz (1 ms sampling time).
    linear_acceleration_norm, angular_acceleration_norm, angle_norm : float
        Infinity norms for normalising the feedback signals: 19.62 m/s² (2 g), 20 rad/s², 33° in
        rad. The pressure norm depends on the load case (:class:`BucketLoad`).
    """

    k_fb: tuple[float, float, float, float] = field(metadata=si("-", FINITE, shape=4))
    tau: float = field(metadata=si("rad/s", POSITIVE))
    k_p: float = field(metadata=si("-", POSITIVE))
    sample_rate: float = field(metadata=si("Hz", POSITIVE))
    linear_acceleration_norm: float = field(metadata=si("m/s^2", POSITIVE))
    angular_acceleration_norm: float = field(metadata=si("rad/s^2", POSITIVE))
    angle_norm: float = field(metadata=si("rad", POSITIVE))


@dataclass(frozen=True)
class AccumulatorParameters:
    """Passive ride control: gas accumulators on the piston side through an orifice.

    Attributes
    ----------
    count : int
        Number of identical accumulators.
    precharge_pressure : float
        Gas precharge pressure in Pa.
    gas_volume : float
        Gas volume at precharge, per accumulator, in m³.
    polytropic_exponent : float
        Exponent n of p V^n = const, in [1, 1.7] (isothermal to adiabatic).
    orifice_diameter : float
        Damping orifice diameter in m.
    discharge_coefficient : float
        Orifice discharge coefficient C_d in (0, 1].
    laminar_transition_pressure : float
        Pressure drop in Pa around which the orifice flow turns from laminar to turbulent.
    """

    count: int = field(metadata=integer())
    precharge_pressure: float = field(metadata=si("Pa", POSITIVE))
    gas_volume: float = field(metadata=si("m^3", POSITIVE))
    polytropic_exponent: float = field(metadata=si("-", Range(1.0, 1.7)))
    orifice_diameter: float = field(metadata=si("m", POSITIVE))
    discharge_coefficient: float = field(metadata=si("-", Range(0.0, 1.0, low_open=True)))
    laminar_transition_pressure: float = field(metadata=si("Pa", POSITIVE))
