r"""Hydraulic components as small functions of CasADi expressions (paper sections 2.3, 2.4, 4.1).

Each function takes and returns CasADi expressions (SX or MX; plain floats work too), so the plant
(:mod:`loader_model.plant.plant`) composes them with the generated multibody model into one graph
and every component is testable alone against a closed form. Pressures are gauge pressures in Pa
(what the transducers of section 4.1 read); the gas law converts to absolute pressure with
:data:`ATMOSPHERIC_PRESSURE_PA`. Flows are in m³/s, forces in N.

Non-smooth laws are replaced by C¹ approximations that are *exact* outside a stated band, so that
an equilibrium or a linearisation away from the band is not shifted by the smoothing:

.. math::

    \operatorname{ramp}_w(x) = \begin{cases} 0 & x \le 0 \\ x^2 / (2 w) & 0 < x < w \\
    x - w/2 & x \ge w \end{cases}
    \qquad
    \operatorname{sat}_L(x) = \begin{cases} x & |x| \le L - w \\ \text{C¹ blend} & \\
    \pm L & |x| \ge L + w \end{cases}

(the saturation is ``x − ramp_{2w}(x − (L − w)) + ramp_{2w}(−x − (L − w))``, which is exact below
L − w and at ±L above L + w).
"""

from __future__ import annotations

from typing import Any

import casadi as ca

__all__ = [
    "ATMOSPHERIC_PRESSURE_PA",
    "END_STOP_BAND_M",
    "accumulator_gas_energy",
    "accumulator_gas_pressure",
    "chamber_pressure_rate",
    "chamber_volumes",
    "compression_energy",
    "end_stop_energy",
    "end_stop_force",
    "end_stop_spring_force",
    "flow_power_pressure",
    "leakage_flow",
    "orifice_flow",
    "pump_displacement_acceleration",
    "ramp",
    "saturate",
    "seal_friction",
]

#: Atmospheric pressure [Pa]: absolute = gauge + this (gas law, cavitation check).
ATMOSPHERIC_PRESSURE_PA = 101_325.0
#: Penetration [m] over which the end stops' spring grows in quadratically (C¹ contact).
END_STOP_BAND_M = 5e-4

Expr = Any


def ramp(x: Expr, width: Expr) -> Expr:
    """C¹ ramp max(x, 0): exactly 0 for x ≤ 0 and x − w/2 for x ≥ w (module docstring)."""
    return ca.if_else(x <= 0, 0, ca.if_else(x >= width, x - width / 2, x * x / (2 * width)))


def saturate(x: Expr, limit: Expr, width: Expr) -> Expr:
    """C¹ saturation to ±``limit``: exact for |x| ≤ limit − width, ±limit beyond limit + width."""
    knee = limit - width
    return x - ramp(x - knee, 2 * width) + ramp(-x - knee, 2 * width)


def _ramp_integral(x: Expr, width: Expr) -> Expr:
    """∫₀ˣ ramp_w: 0, x³/(6w), then w²/6 + (x² − w²)/2 − w (x − w)/2 (C², potential of ramp)."""
    linear = width**2 / 6 + (x * x - width**2) / 2 - width * (x - width) / 2
    return ca.if_else(x <= 0, 0, ca.if_else(x >= width, linear, x**3 / (6 * width)))


def chamber_volumes(
    piston_position_m: Expr,
    piston_area_m2: Expr,
    annulus_area_m2: Expr,
    stroke_m: Expr,
    dead_volume_a_m3: Expr,
    dead_volume_b_m3: Expr,
) -> tuple[Expr, Expr]:
    r"""Chamber volumes of one cylinder (Eq. 36, 37 and Fig. 8).

    .. math:: V_A = A_p x_p + V_{A,0}, \qquad V_B = \alpha A_p (s - x_p) + V_{B,0}
    """
    v_a = piston_area_m2 * piston_position_m + dead_volume_a_m3
    v_b = annulus_area_m2 * (stroke_m - piston_position_m) + dead_volume_b_m3
    return v_a, v_b


def chamber_pressure_rate(bulk_modulus_pa: Expr, volume_m3: Expr, net_inflow_m3_s: Expr) -> Expr:
    r"""Pressure build-up of a chamber (Eq. 36, 37): :math:`\dot p = K_{oil} Q_{net} / V`."""
    return bulk_modulus_pa / volume_m3 * net_inflow_m3_s


def flow_power_pressure(bulk_modulus_pa: Expr, pressure_pa: Expr) -> Expr:
    r"""Pressure π(p) whose product with a chamber's volume flow is the power that flow carries.

    .. math:: \pi(p) = K_{oil} \left(e^{p / K_{oil}} - 1\right) = p + p^2 / (2 K_{oil}) + \dots

    The chamber law of Eq. 36, 37 (:func:`chamber_pressure_rate`, constant K_oil) is the mass
    balance of a fluid of density ρ = ρ0 e^(p/K_oil) with volume flows Q at the chamber's density.
    A mass flow ρ Q carries the free enthalpy g(p) = ∫₀ᵖ dp'/ρ = (K/ρ0)(1 − e^(−p/K)) per kg, so
    the power is ρ g Q = π(p) Q: the familiar p Q to first order in p / K_oil.
    """
    return bulk_modulus_pa * ca.expm1(pressure_pa / bulk_modulus_pa)


def compression_energy(bulk_modulus_pa: Expr, volume_m3: Expr, pressure_pa: Expr) -> Expr:
    r"""Energy stored by compressing the oil of a chamber of ``volume_m3`` to ``pressure_pa``.

    .. math:: \Psi(p, V) = V \left(\pi(p) - p\right) = V \frac{p^2}{2 K_{oil}} + \dots

    It is a state function with :math:`\dot\Psi = \pi(p) Q - p \dot V` along Eq. 36, 37
    (Q: the volume inflow, −p V̇ the work done on the piston), which p²V/(2K) is not when V
    varies: ∂Ψ/∂p = V (e^(p/K) − 1) and ∂Ψ/∂V = π − p make the ṗ = K (Q − V̇)/V terms cancel.
    """
    return volume_m3 * (flow_power_pressure(bulk_modulus_pa, pressure_pa) - pressure_pa)


def leakage_flow(k_lp: Expr, k_lv: Expr, p_a: Expr, p_b: Expr, velocity_m_s: Expr) -> Expr:
    r"""Internal leakage from chamber A to chamber B (Eq. 47, as identified by Eq. 48).

    .. math:: Q_L = k_{Lp} (p_A - p_B) + k_{Lv} \dot x_{act}

    Eq. 47 prints −k_Lv ẋ, but Eq. 48, the regression that identified Table 5's k_Lv, has
    +k_Lv ẋ once Eq. 47 is substituted into Eq. 36; the plant uses the sign Table 5's value was
    identified with (identification uses the same form).
    """
    return k_lp * (p_a - p_b) + k_lv * velocity_m_s


def seal_friction(
    f_s: Expr,
    tau_s: Expr,
    gamma: Expr,
    f_c: Expr,
    f_v: Expr,
    p_a_gauge: Expr,
    velocity_m_s: Expr,
) -> Expr:
    r"""Seal friction of the cylinders (Eq. 46 in the reading of errata 10).

    .. math::

        F_f = \left(f_s e^{-\tau_s |\dot x|} + f_C\, p_A\right) \tanh(\gamma \dot x) + f_v \dot x

    Eq. 46 as printed adds f_C p_A without a sign of the velocity: about 950 N at 89 bar pushing
    one way whatever the motion, a bias rather than friction. The text says the Coulomb part was
    made "dependent on both pressure and velocity" with tanh as a continuous sign(v), which this
    reading implements; p_A is the piston-side gauge pressure as the transducer measured it.
    The identification (Table 4) uses the same form. Positive F_f opposes extension (Eq. 31).
    """
    coulomb = f_s * ca.exp(-tau_s * ca.fabs(velocity_m_s)) + f_c * p_a_gauge
    return coulomb * ca.tanh(gamma * velocity_m_s) + f_v * velocity_m_s


def _penetrations(piston_position_m: Expr, stroke_m: Expr) -> tuple[Expr, Expr]:
    """C¹ penetrations ramp(δ) of the retracted and the extended end stop (positive inside)."""
    below = ramp(-piston_position_m, END_STOP_BAND_M)
    return below, ramp(piston_position_m - stroke_m, END_STOP_BAND_M)


def end_stop_spring_force(piston_position_m: Expr, stroke_m: Expr, stiffness: Expr) -> Expr:
    """Elastic part of :func:`end_stop_force` (positive: extending), −d/dx of
    :func:`end_stop_energy`."""
    below, above = _penetrations(piston_position_m, stroke_m)
    return stiffness * (below - above)


def end_stop_force(
    piston_position_m: Expr, velocity_m_s: Expr, stroke_m: Expr, stiffness: Expr, damping: Expr
) -> Expr:
    r"""Contact force of the stroke's end stops on the piston (positive: extending).

    A one-sided spring-damper beyond each end, C¹ in the penetration δ (quadratic over the first
    0.5 mm), its damping faded in with the same ramp so that it never pulls:

    .. math:: F = k\,\mathrm{ramp}(\delta) + c\,\dot\delta\,\mathrm{ramp}(\delta)/\delta_0
    """
    band = END_STOP_BAND_M
    below, above = _penetrations(piston_position_m, stroke_m)
    fade_below = ca.fmin(below / band, 1)
    fade_above = ca.fmin(above / band, 1)
    retract_stop = stiffness * below - damping * velocity_m_s * fade_below
    extend_stop = stiffness * above + damping * velocity_m_s * fade_above
    return ca.fmax(retract_stop, 0) - ca.fmax(extend_stop, 0)


def end_stop_energy(piston_position_m: Expr, stroke_m: Expr, stiffness: Expr) -> Expr:
    """Elastic energy of the end stops of :func:`end_stop_force`: k ∫ ramp(δ) dδ over each end.

    Its rate plus the power the stop delivers to the piston is minus the damping loss (≤ 0:
    the stop's clamp at zero force only takes energy out).
    """
    band = END_STOP_BAND_M
    below = _ramp_integral(-piston_position_m, band)
    above = _ramp_integral(piston_position_m - stroke_m, band)
    return stiffness * (below + above)


def orifice_flow(
    diameter_m: Expr,
    discharge_coefficient: Expr,
    density_kg_m3: Expr,
    pressure_drop_pa: Expr,
    transition_pa: Expr,
) -> Expr:
    r"""Flow through a sharp-edged orifice, turbulent with a laminar region near zero flow.

    .. math::

        Q = C_d A \sqrt{2/\rho}\; \frac{\Delta p}{(\Delta p^2 + \Delta p_t^2)^{1/4}}

    which tends to the turbulent law C_d A √(2|Δp|/ρ) sign(Δp) for |Δp| ≫ Δp_t and is linear
    (laminar, conductance C_d A √(2/ρ) / √Δp_t) for |Δp| ≪ Δp_t.
    """
    area = ca.pi / 4 * diameter_m**2
    shape = pressure_drop_pa / (pressure_drop_pa**2 + transition_pa**2) ** 0.25
    return discharge_coefficient * area * ca.sqrt(2 / density_kg_m3) * shape


def accumulator_gas_pressure(
    precharge_pa: Expr, gas_volume_m3: Expr, exponent: Expr, oil_volume_m3: Expr
) -> Expr:
    r"""Gauge pressure of a gas accumulator holding ``oil_volume_m3`` of oil (polytropic gas).

    .. math::

        p + p_{atm} = (p_0 + p_{atm}) \left(\frac{V_0}{V_0 - V_{oil}}\right)^n

    with p_0 the gauge precharge and V_0 the gas volume at precharge. For V_oil ≤ 0 (empty) the
    pressure continues linearly with the slope at V_oil = 0 (C¹), a stand-in for the closed
    poppet: the accumulator then cannot deliver oil it does not have.
    """
    absolute = precharge_pa + ATMOSPHERIC_PRESSURE_PA
    full = absolute * (gas_volume_m3 / (gas_volume_m3 - ca.fmax(oil_volume_m3, 0))) ** exponent
    slope = exponent * absolute / gas_volume_m3
    empty = absolute + slope * oil_volume_m3
    return ca.if_else(oil_volume_m3 >= 0, full, empty) - ATMOSPHERIC_PRESSURE_PA


def accumulator_gas_energy(
    precharge_pa: Expr, gas_volume_m3: Expr, exponent: Expr, oil_volume_m3: Expr
) -> Expr:
    r"""Energy stored in the accumulator: ∫ p dV_oil from empty (:func:`accumulator_gas_pressure`).

    .. math::

        E = \frac{(p_0 + p_{atm}) V_0}{n - 1}\left[\left(\frac{V_0}{V_0 - V_{oil}}\right)^{n-1}
            - 1\right] - p_{atm} V_{oil}

    (the polytropic gas's work, gauge like every pressure here; at n = 1 its limit, with
    V_0 ln(V_0/(V_0 − V_oil))), continued for V_oil < 0 by the integral of the linear law there,
    so that dE/dV_oil is the gauge pressure everywhere.
    """
    absolute = precharge_pa + ATMOSPHERIC_PRESSURE_PA
    log_ratio = ca.log(gas_volume_m3 / (gas_volume_m3 - ca.fmax(oil_volume_m3, 0)))
    excess = exponent - 1  # (r^m − 1)/m, and its limit ln r at the isothermal m = 0
    safe = ca.if_else(excess == 0, 1, excess)
    growth = ca.if_else(excess == 0, log_ratio, ca.expm1(excess * log_ratio) / safe)
    full = absolute * gas_volume_m3 * growth
    slope = exponent * absolute / gas_volume_m3
    empty = absolute * oil_volume_m3 + slope * oil_volume_m3**2 / 2
    gas = ca.if_else(oil_volume_m3 >= 0, full, empty)
    return gas - ATMOSPHERIC_PRESSURE_PA * oil_volume_m3


def pump_displacement_acceleration(
    displacement: Expr,
    displacement_rate: Expr,
    command: Expr,
    natural_frequency_rad_s: Expr,
    damping_ratio: Expr,
) -> Expr:
    r"""Closed-loop swash-plate dynamics of Fig. 9: a second-order system.

    .. math:: \ddot V_p = \omega_p^2 (V_{p,ref} - V_p) - 2 \zeta_p \omega_p \dot V_p

    The rate limit and the displacement saturation of Fig. 9 are applied by the plant to the
    command and to the rate (see :mod:`loader_model.plant.plant`).
    """
    return (
        natural_frequency_rad_s**2 * (command - displacement)
        - 2 * damping_ratio * natural_frequency_rad_s * displacement_rate
    )
