r"""Discrete first-order filters of the controllers, zero-order-hold equivalents as CasADi expressions.

Both filters of section 3.3 are one pole at −a (a > 0):

.. math::

    \text{semi-integrator:}\quad \frac{1}{s + \tau}, \qquad
    \text{high-pass:}\quad \frac{s}{s + \omega_{hp}} = 1 - \frac{\omega_{hp}}{s + \omega_{hp}}

written as ż = −a z + v with output z (semi-integrator) or v − a z (high-pass). Their
zero-order-hold (ZOH) equivalents at sample time T are exact for inputs held constant over a
sample, so the sampled step response equals the continuous one at every sample instant:

.. math::

    z_{k+1} = e^{-aT} z_k + \frac{1 - e^{-aT}}{a}\, v_k

The semi-integrator's output is z_k (no feed-through: one sample of delay, as ZOH gives for a
strictly proper filter); the high-pass output is v_k − a z_k (feed-through 1). The coefficients are
CasADi expressions of a and T, so a new setting needs no rebuild. ``expm1`` would be more accurate
for aT → 0; at aT = 10⁻² (τ = 10 rad/s, 1 kHz) the relative rounding error of 1 − e^{−aT} is about
10⁻¹⁴, far below anything measured.
"""

from __future__ import annotations

from typing import Any

import casadi as ca

__all__ = ["highpass_step", "semi_integrator_step", "zoh_pole"]


def zoh_pole(a: Any, sample_time: Any) -> tuple[Any, Any]:
    """ZOH coefficients ``(e^{−aT}, (1 − e^{−aT}) / a)`` of ż = −a z + v (a > 0)."""
    decay = ca.exp(-a * sample_time)
    return decay, (1 - decay) / a


def semi_integrator_step(z: Any, v: Any, tau: Any, sample_time: Any) -> tuple[Any, Any]:
    """One sample of 1/(s + τ): returns ``(z_next, output)`` with output z_k (section 3.3)."""
    decay, gain = zoh_pole(tau, sample_time)
    return decay * z + gain * v, z


def highpass_step(z: Any, v: Any, corner: Any, sample_time: Any) -> tuple[Any, Any]:
    """One sample of s/(s + ω): returns ``(z_next, output)`` with output v_k − ω z_k."""
    decay, gain = zoh_pole(corner, sample_time)
    return decay * z + gain * v, v - corner * z
