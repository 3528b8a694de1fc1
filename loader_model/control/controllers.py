r"""The four controllers of the Table 6 comparison as discrete CasADi Functions (section 3, 1 kHz).

Every controller is one Function with named inputs and outputs,

.. math:: (z_{k+1}, u_k) = \mathrm{controller}(z_k, y_k, \theta_c)

with z the filter states (:func:`controller_state_names`), y the sensor readings
(:data:`~loader_model.control.sensors.SENSOR_NAMES`), θ_c the settings vector
(:data:`~loader_model.control.settings.SETTINGS_NAMES`) and u = V_p,ref [m³/rev]. Filters are
ZOH equivalents (:mod:`loader_model.control.filters`); the command is saturated at ±u_limit.

- ``baseline``: u = u_hold, the static command (no damping): 0 behind the closed load-holding
  valves the baseline runs on (:mod:`loader_model.plant.circuit`; the boom sits on them).
- ``passive``: the same law; the accumulator is a plant option
  (``PlantOptions.for_controller("passive")``: behind closed load-holding valves).
- ``virtual_accumulator``: the pressure loop of section 3.2 with p_A,ref = 0 on the high-passed p_A.
- ``skyhook``: output feedback (Eq. 40, Table 3) through the pressure loop (Fig. 11):

.. math::

    \hat y = \Big(\tfrac{1}{s+\tau}\tfrac{f_{Hx}}{\|a\|},\;
                  \tfrac{1}{s+\tau}\tfrac{f_{Hy} - g}{\|a\|},\;
                  \tfrac{1}{s+\tau}\tfrac{\hat{\ddot\theta}_1}{\|\ddot\theta\|},\;
                  \tfrac{\varphi - \varphi_0}{\|\varphi\|}\Big), \qquad
    \frac{p_{A,ref}}{\|p_A\|} = -K_{fb}\,\hat y

The pressure loop (sections 3.2, 3.3), shared by the last two, with the holding command added as
feed-forward (the high-pass removes the static pressure, so the loop alone would not hold the boom):

.. math::

    u = \mathrm{sat}\Big(u_{hold} + k_p V_{p,max}
        \frac{p_{A,ref} - \mathrm{HP}(p_A)}{\|p_A\|}\Big)

Gravity: the vertical accelerometer at H reads f_Hy = (chassis-frame ÿ_H) + g cos θ1; the constant g is
subtracted before the semi-integrator (g(1 − cos θ1) ≈ g θ1²/2 stays, second order). Whatever
constant remains (that term, a pitched f_Hx = g sin θ1, sensor offsets) gives a bounded velocity
estimate c/τ, not drift: the semi-integrator's pole is at −τ. The velocities are semi-integrals of
the *normalised* accelerations (unit s), so K_fb acts on the signals the paper normalised.
"""

from __future__ import annotations

from functools import cache

import casadi as ca

from loader_model.control.filters import highpass_step, semi_integrator_step
from loader_model.control.sensors import SENSOR_NAMES, pitch_acceleration
from loader_model.control.settings import SETTINGS_NAMES

__all__ = ["CONTROLLER_NAMES", "controller_function", "controller_state_names"]

CONTROLLER_NAMES: tuple[str, ...] = ("baseline", "passive", "virtual_accumulator", "skyhook")

_STATES: dict[str, tuple[str, ...]] = {
    "baseline": (),
    "passive": (),
    "virtual_accumulator": ("z_hp",),
    "skyhook": ("z_vx", "z_vy", "z_vtheta", "z_hp"),
}


def controller_state_names(name: str) -> tuple[str, ...]:
    """Names of the controller ``name``'s states z (order of its Function's ``z``)."""
    _check(name)
    return _STATES[name]


def _check(name: str) -> None:
    if name not in CONTROLLER_NAMES:
        raise ValueError(f"controller {name!r} is unknown; allowed: {list(CONTROLLER_NAMES)}")


def _pressure_loop(
    z_hp: ca.SX, p_a: ca.SX, p_ref_normalised: ca.SX, s: dict[str, ca.SX]
) -> tuple[ca.SX, ca.SX]:
    """High-pass on p_A and the proportional pressure law; returns (z_hp_next, unsaturated u)."""
    z_next, p_hp = highpass_step(z_hp, p_a, s["omega_hp"], s["T_s"])
    u = s["u_hold"] + s["k_p"] * s["V_p_max"] * (p_ref_normalised - p_hp / s["p_norm"])
    return z_next, u


def _law(name: str, z: ca.SX, y: dict[str, ca.SX], s: dict[str, ca.SX]) -> tuple[ca.SX, ca.SX]:
    if name in ("baseline", "passive"):
        return ca.SX(0, 1), s["u_hold"]
    if name == "virtual_accumulator":
        return _pressure_loop(z[0], y["p_A"], 0, s)
    accelerations = (
        y["f_Hx"] / s["a_norm"],
        (y["f_Hy"] - s["g"]) / s["a_norm"],
        pitch_acceleration(y["f_Hy"], y["f_Ny"], s["N_x"]) / s["alpha_norm"],
    )
    steps = [semi_integrator_step(z[i], a, s["tau"], s["T_s"]) for i, a in enumerate(accelerations)]
    feedback = ca.vertcat(*(out for _, out in steps), (y["phi"] - s["phi_0"]) / s["phi_norm"])
    gains = ca.vertcat(s["k_x"], s["k_y"], s["k_theta"], s["k_phi"])
    z_hp, u = _pressure_loop(z[3], y["p_A"], -ca.dot(gains, feedback), s)
    return ca.vertcat(*(nxt for nxt, _ in steps), z_hp), u


@cache
def controller_function(name: str) -> ca.Function:
    """The discrete controller ``name`` (:data:`CONTROLLER_NAMES`) as an SX Function.

    ``controller(z, y_sensor, settings) -> (z_next, u)``; see the module docstring for the laws.
    """
    _check(name)
    z = ca.SX.sym("z", len(_STATES[name]))
    y_sensor = ca.SX.sym("y_sensor", len(SENSOR_NAMES))
    settings = ca.SX.sym("settings", len(SETTINGS_NAMES))
    y = {n: y_sensor[i] for i, n in enumerate(SENSOR_NAMES)}
    s = {n: settings[i] for i, n in enumerate(SETTINGS_NAMES)}
    z_next, u = _law(name, z, y, s)
    u = ca.fmin(ca.fmax(u, -s["u_limit"]), s["u_limit"])
    return ca.Function(
        name, [z, y_sensor, settings], [z_next, u], ["z", "y_sensor", "settings"], ["z_next", "u"]
    )
