"""Parameter sets of the hydraulic drive and the controller (paper sections 2.3, 2.4, 3, 4.1).

Units follow the SI rule of :mod:`loader_model.parameters.schema`; the pump's per-revolution
quantities use m³/rev and rev/s as in Table 2 and the nomenclature.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from loader_model.parameters.accumulator import AccumulatorParameters
from loader_model.parameters.fields import Range, TypedLeaves, integer, si
from loader_model.parameters.valve import ValveParameters

_DEAD_VOLUME = Range(1e-6, 0.05, reason="hose, tube and port volume per cylinder of 1 ml to 50 l")

__all__ = [
    "AccumulatorParameters",
    "ControllerParameters",
    "CylinderParameters",
    "FrictionParameters",
    "HydraulicParameters",
    "LeakageParameters",
    "PumpParameters",
    "ValveParameters",
]


@dataclass(frozen=True)
class CylinderParameters(TypedLeaves):
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

    count: int = field(
        metadata=integer(Range(1, 4, reason="one to four lift cylinders in parallel"))
    )
    piston_diameter: float = field(
        metadata=si(
            "m", Range(0.02, 0.4, reason="bores of 20-400 mm; mobile lift cylinders are 40-250 mm")
        )
    )
    rod_diameter: float = field(metadata=si("m", Range(0.01, 0.3, reason="rods of 10-300 mm")))
    stroke: float = field(metadata=si("m", Range(0.05, 3.0, reason="strokes of 5 cm to 3 m")))
    retracted_length: float = field(
        metadata=si("m", Range(0.2, 5.0, reason="pin-to-pin lengths of 0.2-5 m"))
    )
    dead_volume_a: float = field(metadata=si("m^3", _DEAD_VOLUME))
    dead_volume_b: float = field(metadata=si("m^3", _DEAD_VOLUME))
    end_stop_stiffness: float = field(
        metadata=si("N/m", Range(1e6, 1e10, reason="end stops from rubber cushions to steel"))
    )
    end_stop_damping: float = field(
        metadata=si("N s/m", Range(0.0, 1e7, reason="undamped to heavily cushioned end stops"))
    )

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
class HydraulicParameters(TypedLeaves):
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

    bulk_modulus: float = field(
        metadata=si(
            "Pa",
            Range(
                100000000.0,
                3000000000.0,
                reason="effective bulk modulus of oil with hoses and air (0.1 GPa) to water glycol (3 GPa)",
            ),
        )
    )
    charge_pressure: float = field(
        metadata=si(
            "Pa",
            Range(500000.0, 5000000.0, reason="charge pumps of closed circuits deliver 5-50 bar"),
        )
    )
    oil_density: float = field(
        metadata=si("kg/m^3", Range(800.0, 1100.0, reason="mineral oils to water glycol"))
    )
    charge_conductance: float = field(
        metadata=si(
            "m^3/(s Pa)", Range(1e-11, 1e-6, reason="valves passing 0.06-6000 l/min per bar")
        )
    )
    check_valve_conductance: float = field(
        metadata=si(
            "m^3/(s Pa)", Range(1e-11, 1e-6, reason="valves passing 0.06-6000 l/min per bar")
        )
    )
    relief_pressure: float = field(
        metadata=si("Pa", Range(5e6, 5e7, reason="relief settings of mobile machines, 50-500 bar"))
    )
    relief_conductance: float = field(
        metadata=si(
            "m^3/(s Pa)", Range(1e-11, 1e-6, reason="valves passing 0.06-6000 l/min per bar")
        )
    )


@dataclass(frozen=True)
class LeakageParameters(TypedLeaves):
    """Leakage: Table 5's regression flow and the cylinders' own piston-seal leakage.

    Q_L = k_Lp (p_A − p_B) − k_Lv ẋ_act (Eq. 47, Table 5) is the pump-side flow of the
    regression of Eq. 48 while the pump holds the boom through open load-holding valves
    (errata 11; :mod:`loader_model.plant.circuit`); behind closed valves only the
    piston seal's cross-port leakage Q_seal = n k_seal (p_A − p_B) acts.

    Attributes
    ----------
    k_lp : float
        Pressure coefficient k_Lp in m³/(s·Pa).
    k_lv : float
        Velocity coefficient k_Lv in m²; identified negative (−5.0e-4 m²), so any finite value.
    k_seal : float
        Piston-seal cross-port leakage coefficient per cylinder in m³/(s·Pa).
    """

    k_lp: float = field(
        metadata=si(
            "m^3/(s Pa)",
            Range(0.0, 1e-10, reason="no leakage to 60 l/min at 100 bar, a seal that has failed"),
        )
    )
    k_lv: float = field(
        metadata=si(
            "m^2",
            Range(
                -0.02,
                0.02,
                reason="at most a sixth of the area of the largest bore (0.4 m: 0.126 m^2) either way",
            ),
        )
    )
    k_seal: float = field(
        metadata=si(
            "m^3/(s Pa)",
            Range(
                0.0,
                1e-12,
                reason="a leak-free elastomer seal (0) to a worn one: 50 mm/min drift of a "
                "63 mm bore at 150 bar is 2.6e-13",
            ),
        )
    )


@dataclass(frozen=True)
class FrictionParameters(TypedLeaves):
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

    f_s: float = field(
        metadata=si(
            "N", Range(0.0, 200000.0, reason="up to 200 kN, the seal friction of a 400 mm bore")
        )
    )
    tau_s: float = field(
        metadata=si("s/m", Range(0.0, 1000.0, reason="Stribeck velocities down to 1 mm/s"))
    )
    gamma: float = field(
        metadata=si(
            "s/m", Range(0.0, 10000.0, reason="tanh(gamma v) switching over 0.1 mm/s or more")
        )
    )
    f_c: float = field(
        metadata=si("N/Pa", Range(0.0, 0.001, reason="up to 100 N/bar (Table 4: 10.7 N/bar)"))
    )
    f_v: float = field(
        metadata=si("N s/m", Range(0.0, 1000000.0, reason="up to 1 MN s/m (Table 4: 8.13 kN s/m)"))
    )


@dataclass(frozen=True)
class PumpParameters(TypedLeaves):
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
        read as 1.24e-3 m³/(rev·s), a full stroke in about 37 ms (errata 8).
    """

    max_displacement: float = field(
        metadata=si(
            "m^3/rev", Range(5e-06, 0.001, reason="mobile axial piston pumps of 5 to 1000 cm^3/rev")
        )
    )
    shaft_speed: float = field(
        metadata=si("rev/s", Range(5.0, 60.0, reason="diesel or electric drive at 300-3600 rpm"))
    )
    natural_frequency: float = field(
        metadata=si(
            "Hz", Range(1.0, 200.0, reason="displacement loops of 1-200 Hz (Table 2: 22.3 Hz)")
        )
    )
    damping_ratio: float = field(
        metadata=si(
            "-",
            Range(0.05, 5.0, reason="a loop that settles: 0.05 to overdamped 5 (Table 2: 0.53)"),
        )
    )
    displacement_rate_limit: float = field(
        metadata=si(
            "m^3/(rev s)",
            Range(1e-05, 0.1, reason="a full stroke of 5-1000 cm^3/rev pumps in 10 ms to 100 s"),
        )
    )

    @property
    def natural_frequency_rad_s(self) -> float:
        """ω_p in rad/s (2π times :attr:`natural_frequency`)."""
        return 2.0 * math.pi * self.natural_frequency


@dataclass(frozen=True)
class ControllerParameters(TypedLeaves):
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

    k_fb: tuple[float, float, float, float] = field(
        metadata=si(
            "-",
            Range(
                -100.0, 100.0, reason="gains on signals normalised to 1; Table 3 gains are below 6"
            ),
            shape=4,
        )
    )
    tau: float = field(
        metadata=si(
            "rad/s",
            Range(
                0.01,
                1000.0,
                reason="semi-integrator corner below the 1 kHz sample rate (Table 3: 10 rad/s)",
            ),
        )
    )
    k_p: float = field(
        metadata=si(
            "-",
            Range(
                0.0,
                100.0,
                low_open=True,
                reason="a gain on normalised signals is positive (section 3.2: 0.5)",
            ),
        )
    )
    sample_rate: float = field(
        metadata=si(
            "Hz",
            Range(
                50.0,
                100000.0,
                reason="digital controllers of 50 Hz to 100 kHz (section 3.3: 1 kHz)",
            ),
        )
    )
    linear_acceleration_norm: float = field(
        metadata=si("m/s^2", Range(0.1, 1000.0, reason="0.01 g to 100 g (section 3.3: 2 g)"))
    )
    angular_acceleration_norm: float = field(
        metadata=si(
            "rad/s^2", Range(0.1, 1000.0, reason="0.1-1000 rad/s^2 (section 3.3: 20 rad/s^2)")
        )
    )
    angle_norm: float = field(
        metadata=si(
            "rad", Range(0.01, math.pi, reason="0.6 deg to half a turn (section 3.3: 33 deg)")
        )
    )
