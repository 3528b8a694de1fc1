r"""Tyre-road contact law that a stiff integrator can pass through (extends Eq. 1-4 of the paper).

The paper's tyre (Eq. 1-4, Fig. 5) is a linear spring-damper in x and y at each axle, valid while
the tyre is loaded. A simulation over obstacles also needs lift-off, touchdown and sliding, and
must stay continuous in every state so that a variable-step BDF integrator is not forced to
locate switching points. Per axle (A front, B rear), with the axle's displacement from its
position at p = 0 in world coordinates (δx, δy), the road displacement under it (w_x, w_y), its
velocity relative to the road (v_x, v_y) and the anchor state ξ (how far the contact point has
slid along the road):

Vertical force, unilateral with a C¹ transition of half-width ε (``F_transition``):

.. math::

    F_{y,lin} = F_{y0} - k_y (\delta y - w_y) - c_y v_y, \qquad
    F_y = \begin{cases} F_{y,lin} & F_{y,lin} \ge \varepsilon \\
          (F_{y,lin} + \varepsilon)^2 / (4 \varepsilon) & |F_{y,lin}| < \varepsilon \\
          0 & F_{y,lin} \le -\varepsilon \end{cases}

so a loaded tyre follows the paper's linear law exactly and a tyre never pulls.

Horizontal force: a spring from an anchor ξ (the contact point, which may slide along the road)
in parallel with a damper on the axle's velocity relative to the road, the damper faded in with
the vertical load (χ: C¹ smoothstep from 0 at F_y = 0 to 1 at F_y ≥ 2ε). While the tyre sticks
and is loaded this is exactly the paper's law:

.. math::

    e = \delta x - w_x - \xi, \qquad F_x = -k_x e - \chi(F_y)\, c_x v_x, \qquad \dot\xi = r\, e

The anchor slides with a sliding fraction σ ∈ [0, 1] of the force's use of the friction limit
L = μ F_y + L_min, a C¹ smoothstep between the fraction β (:data:`STICK_FRACTION`) and 1:

.. math::

    z = \frac{|F_x|}{L}, \qquad
    \sigma = \begin{cases} 0 & z \le \beta \\ 3 u^2 - 2 u^3,\ u = \frac{z - \beta}{1 - \beta}
    & \beta < z < 1 \\ 1 & z \ge 1 \end{cases}, \qquad
    \dot\xi = \sigma \left(v_x + \frac{e}{\tau}\right), \qquad
    \dot e = (1 - \sigma)\, v_x - \sigma \frac{e}{\tau}

- Sticking (z ≤ β): σ = 0, ξ̇ = 0, the paper's linear law; an undamped motion conserves energy.
- Sliding at a steady relative velocity v: ė = 0 where σ = v / (v + e/τ) < 1, i.e. with z < 1:
  the force stays below the friction limit, which it reaches when v ≫ L / (k_x τ).
- Airborne (F_y = 0, L = L_min = 1 N, χ = 0): z ≫ 1, σ = 1, ė = −e/τ whatever the axle does:
  the spring relaxes within a few τ and the force fades, so the tyre lands on a relaxed spring at
  the point where it touches down.

Power: with the spring energy ½ k_x e², the element delivers −(χ c_x v_x² + σ k_x e (v_x + e/τ))
to the rest of the system minus what it stores. While sliding on the ground e and v_x have the
same sign and this is dissipation; it can be positive only for a spring that is unloading faster
than v_x while the tyre leaves the ground (a release of energy stored in it, bounded by ½ k_x e²).
The vertical law is passive (its clamp is monotone, so damping inside it only removes energy).
"""

from __future__ import annotations

import sympy as sp

__all__ = [
    "MINIMUM_FRICTION_LIMIT_N",
    "STICK_FRACTION",
    "contact_factor",
    "sliding_fraction",
    "unilateral",
    "unilateral_potential",
]

#: Fraction β of the friction limit below which the tyre sticks exactly (linear law).
STICK_FRACTION = sp.Rational(9, 10)
#: L_min: friction limit of an unloaded tyre [N], keeps z finite in the air.
MINIMUM_FRICTION_LIMIT_N = sp.Integer(1)


def unilateral(force: sp.Expr, width: sp.Expr) -> sp.Expr:
    """C¹ unilateral force: ``force`` above ``width``, 0 below ``-width``, a parabola between."""
    return sp.Piecewise(
        (force, force >= width),
        (0, force <= -width),
        ((force + width) ** 2 / (4 * width), True),
    )


def unilateral_potential(force: sp.Expr, width: sp.Expr) -> sp.Expr:
    """W(F) = ∫ U(f) df from −∞ to F, U = :func:`unilateral`: the vertical tyre's elastic energy
    times k_y at elastic force F = F_y0 − k_y u (so that d(W/k_y)/du = −U, a potential)."""
    return sp.Piecewise(
        (2 * width**2 / 3 + (force**2 - width**2) / 2, force >= width),
        (0, force <= -width),
        ((force + width) ** 3 / (12 * width), True),
    )


def contact_factor(vertical: sp.Expr, width: sp.Expr) -> sp.Expr:
    """χ: C¹ smoothstep of the vertical load, 0 at no load and 1 from ``2 width`` on."""
    u = vertical / (2 * width)
    return sp.Piecewise((1, u >= 1), (3 * u**2 - 2 * u**3, True))


def sliding_fraction(force_magnitude: sp.Expr, limit: sp.Expr) -> sp.Expr:
    """σ: C¹ smoothstep of z = |F_x| / L from 0 at z = β to 1 at z = 1 (module docstring)."""
    beta = STICK_FRACTION
    u = (force_magnitude / limit - beta) / (1 - beta)
    return sp.Piecewise((0, u <= 0), (1, u >= 1), (3 * u**2 - 2 * u**3, True), evaluate=False)
