r"""Seated occupant on the seat cushion at S, driven by the chassis (errata 13).

Section 5.3 of the paper measured the seat with an accelerometer pad between operator and seat;
the chassis point S of the multibody model is the seat's base. Per axis of the chassis frame
(fore-aft x, vertical y), small-angle and in coordinates relative to S measured from the static
deflection (so the static state is zero):

- a cushion spring-damper (k_c, c_c) between S and a pad node of mass m_p + m_0 (the pad and
  cushion top, ``pad_mass``, plus the occupant's part m_0 that moves with the seat);
- the occupant's mode: a mass m_1 on the pad node through k_1 = m_1 ω_n², c_1 = 2 ζ m_1 ω_n.

This is the single-degree-of-freedom apparent-mass model with a mass on the seat platform that
Fairley & Griffin (1989, J. Biomech. 22) fitted to the mean normalised vertical apparent mass of
60 subjects: ω_n = 31.4 rad/s (5 Hz), ζ = 0.475 (as reported in the *Biomedical Engineering and
Design Handbook*, vol. 1, ch. 11, Fig. 11.7). The split m_0 / (m_0 + m_1), the fore-aft mode and
the cushion are estimates with ranges (``[seat]`` of the parameter file); the cushion is set so
the occupied seat resonates near 4 Hz vertically (conventional cushion seats "have typically a
resonance frequency around 4 Hz, and thus are effective to reduce whole-body vibration exposure
above about 6 Hz", a study of suspension seats, th4.ilovetranslation.com/HQYPPMm2nTX=d).

With Δf = on · (f_S − f_S0) the chassis specific force at S in the chassis frame minus its
static value (0, g), u_p, u_o the pad's and the occupant's displacement relative to S:

.. math::

    (m_p + m_0)\,\ddot u_p &= -k_c u_p - c_c \dot u_p + k_1 (u_o - u_p) + c_1 (\dot u_o - \dot u_p)
                              - (m_p + m_0)\,\Delta f \\
    m_1\,\ddot u_o &= -k_1 (u_o - u_p) - c_1 (\dot u_o - \dot u_p) - m_1 \Delta f \\
    f_P &= f_S + \ddot u_p = f_{S0} + \frac{k_1 (u_o - u_p) + c_1 (\dot u_o - \dot u_p)
           - k_c u_p - c_c \dot u_p}{m_p + m_0} \quad (\mathrm{on} = 1)

f_P is what a seat pad between occupant and cushion reads (specific force, gravity included).
With ``occupant_on`` = 0 the states are not driven (they stay at zero from the static state) and
f_P = f_S exactly. Apparent mass on a rigid seat and pad/chassis transmissibility (closed forms):

.. math::

    M(\omega) = m_0 + m_1 \frac{k_1 + j\omega c_1}{k_1 - \omega^2 m_1 + j\omega c_1}, \qquad
    T(\omega) = \frac{k_c + j\omega c_c}{k_c + j\omega c_c - \omega^2 (m_p + M(\omega))}

The occupant's reaction on the chassis is neglected (a 55 kg seated mass on a 3.5 t machine):
the chassis drives the occupant, not the other way round, and the plant's energy balance
(:mod:`loader_model.plant.energy`) is that of the loader without the occupant.
"""

from __future__ import annotations

from typing import Any

import casadi as ca

__all__ = ["OCCUPANT_PARAMETERS", "OCCUPANT_STATE_NAMES", "occupant_dynamics"]

#: States appended to the plant's: per axis the pad's and the occupant's displacement relative
#: to S (from the static deflection, m) and their rates (m/s).
OCCUPANT_STATE_NAMES: tuple[str, ...] = (
    "u_Px",
    "ud_Px",
    "u_Ox",
    "ud_Ox",
    "u_Py",
    "ud_Py",
    "u_Oy",
    "ud_Oy",
)

#: (name, unit, description) of the occupant's plant parameters (``[seat]`` of the loader file).
OCCUPANT_PARAMETERS: tuple[tuple[str, str, str], ...] = (
    ("m_seated", "kg", "mass on the seat pan, m_0 + m_1 (seated occupant)"),
    ("m_pad", "kg", "moving mass of the cushion top and the seat pad"),
    ("r_occ_x", "-", "fore-aft share m_0 / (m_0 + m_1) moving with the pad"),
    ("f_occ_x", "Hz", "fore-aft natural frequency of the occupant on a rigid seat"),
    ("zeta_occ_x", "-", "fore-aft damping ratio of the occupant's mode"),
    ("k_cush_x", "N/m", "cushion shear stiffness"),
    ("c_cush_x", "N*s/m", "cushion shear damping"),
    ("r_occ_y", "-", "vertical share m_0 / (m_0 + m_1) moving with the pad"),
    ("f_occ_y", "Hz", "vertical natural frequency of the occupant (Fairley & Griffin 1989)"),
    ("zeta_occ_y", "-", "vertical damping ratio of the occupant (Fairley & Griffin 1989)"),
    ("k_cush_y", "N/m", "cushion compression stiffness"),
    ("c_cush_y", "N*s/m", "cushion compression damping"),
    ("occupant_on", "-", "1: the chassis drives the occupant on the cushion; 0: pad reads f_S"),
)


def _axis(state: Any, delta_f: Any, theta: dict[str, Any], axis: str) -> tuple[Any, Any]:
    """Rates of (u_p, u̇_p, u_o, u̇_o) of one axis and ü_p + Δf (the pad's specific force minus
    the static one: the cushion's and the occupant's forces on the pad node over its mass)."""
    u_p, ud_p, u_o, ud_o = state[0], state[1], state[2], state[3]
    share = theta[f"r_occ_{axis}"]
    mass = theta["m_seated"]
    rigid, moving = share * mass, (1 - share) * mass
    omega = 2 * ca.pi * theta[f"f_occ_{axis}"]
    k_1 = moving * omega**2
    c_1 = 2 * theta[f"zeta_occ_{axis}"] * moving * omega
    body = k_1 * (u_o - u_p) + c_1 * (ud_o - ud_p)
    cushion = theta[f"k_cush_{axis}"] * u_p + theta[f"c_cush_{axis}"] * ud_p
    on_pad = (body - cushion) / (theta["m_pad"] + rigid)
    udd_o = -body / moving - delta_f
    return ca.vertcat(ud_p, on_pad - delta_f, ud_o, udd_o), on_pad


def occupant_dynamics(state: Any, f_s: Any, theta: dict[str, Any]) -> tuple[Any, Any]:
    """State rates of :data:`OCCUPANT_STATE_NAMES` and the pad's specific forces (f_Px, f_Py).

    Parameters
    ----------
    state
        The occupant's states (8), order :data:`OCCUPANT_STATE_NAMES`.
    f_s
        Specific force at S in the chassis frame (f_Sx, f_Sy), m/s² (gravity included).
    theta
        Plant parameters by name (``g`` and :data:`OCCUPANT_PARAMETERS`).
    """
    on, g = theta["occupant_on"], theta["g"]
    rate_x, on_pad_x = _axis(state[0:4], on * f_s[0], theta, "x")
    rate_y, on_pad_y = _axis(state[4:8], on * (f_s[1] - g), theta, "y")
    # f_P = f_S + ü_p = f_S0 + (forces on the pad) / mass; written so that occupant_on = 0 gives
    # f_S bit for bit and = 1 has no f_S − f_S cancellation (no direct feedthrough from f_S)
    pad = ca.vertcat((1 - on) * f_s[0] + on * on_pad_x, (1 - on) * f_s[1] + on * (g + on_pad_y))
    return ca.vertcat(rate_x, rate_y), pad
