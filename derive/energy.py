r"""Energy of the multibody model with the tyre contact law: what is stored, what is dissipated.

Stored (a function of the state and the road displacement w only):

.. math::

    T = \tfrac12 \dot p^\mathsf{T} M(p) \dot p, \qquad
    V_g = g \left(m_1 y_H + m_2 (y_G - G_y)\right), \qquad
    V_{tyre} = \sum_{i \in \{A, B\}} \tfrac12 k_{ix} e_i^2 + W(F_{iy,s}) / k_{iy}

with e the horizontal spring's stretch from its anchor, F_s = F_y0 − k_y δy the vertical spring's
linear force and W the integral of the C¹ clamp U (:func:`derive.contact.unilateral_potential`),
so that the elastic forces F_e = (−k_x e, U(F_s)) are exactly −∂V_tyre/∂(axle position).
The tyre element then balances as (derive/contact.py, power notes)

.. math::

    F \cdot \dot w + F_e \cdot (\dot w_{true} - \dot w)
    = F \cdot v_{axle} + \dot V_{tyre} + D_{tyre}, \qquad
    D_{tyre} = \sum_i (U(F_s) - F_y)\, s_y + \chi c_x s_x^2 + k_x e\, \dot\xi

with s the axle's velocity relative to the road rate input ẇ and ẇ_true the time derivative of
the road displacement input (the two differ when the input table says so: the horizontal input
w_x has ẇ_x = 0 by design, :mod:`loader_model.simulation.travel`). The left-hand side is the road's
power; F · v_axle enters the bodies, which with gravity and the generalised forces of Eq. 25 give
d(T + V_g)/dt = Q_act F_act ṗ + Q_d · ṗ + Σ F · v_axle.
"""

from __future__ import annotations

import sympy as sp

from derive.codegen import FunctionSpec, InputSpec, OutputSpec
from derive.contact import contact_factor, unilateral, unilateral_potential
from derive.mechanics import LoaderMechanics
from derive.symbols import parameter_symbol

__all__ = ["mechanical_energy_spec"]

P = parameter_symbol


def mechanical_energy_spec(mech: LoaderMechanics, inputs: tuple[InputSpec, ...]) -> FunctionSpec:
    """Specification of the generated ``mechanical_energy`` (module docstring).

    ``inputs`` are (p, ṗ, ξ, road, road_rate, params) in the order of ``tyre_contact``. Machines
    with internal spring-dampers (:mod:`derive.elements`) also get ``V_internal`` (their springs
    with preloads, 0 at p = 0) and ``D_internal`` (their dampers).
    """
    sym = mech.symbols
    machine = sym.machine
    pd = sp.Matrix(sym.rates)
    kinetic = (pd.T * mech.mass_matrix * pd)[0, 0] / 2
    root = machine.root
    heights = P(root.mass) * mech.positions[root.centre_of_gravity][1]
    for body in machine.bodies[1:]:
        cog = body.centre_of_gravity
        heights += P(body.mass) * (mech.positions[cog][1] - P(f"{cog}_y"))
    gravity = P("g") * heights
    width = P("F_transition")
    stored = sp.S.Zero
    dissipated = sp.S.Zero
    elastic: list[sp.Expr] = []
    definitions = list(mech.contact_definitions)
    for index, axle in enumerate(machine.axles):
        deflection, slip = mech.tyre_deflections[axle], mech.tyre_slips[axle]
        k_x, k_y, c_x = P(f"k_{axle}x"), P(f"k_{axle}y"), P(f"c_{axle}x")
        stretch = deflection[0] - sym.anchors[index]
        spring = P(f"F_{axle}y0") - k_y * deflection[1]
        clamped = sp.Symbol(f"F_e_{axle}", real=True)
        definitions.append((clamped, unilateral(spring, width)))
        vertical = sp.Symbol(f"F_y_{axle}", real=True)  # the contact law's F_y (definitions)
        stored += k_x * stretch**2 / 2 + unilateral_potential(spring, width) / k_y
        dissipated += (clamped - vertical) * slip[1]
        dissipated += contact_factor(vertical, width) * c_x * slip[0] ** 2
        dissipated += k_x * stretch * mech.anchor_rates[index]
        elastic += [-k_x * stretch, clamped]
    masses = [body.mass.replace("_", "") for body in machine.bodies]
    cogs = [body.centre_of_gravity for body in machine.bodies]
    v_g = f"{masses[0]} y_{cogs[0]}" + "".join(
        f" + {m} (y_{c} − {c}_y)" for m, c in zip(masses[1:], cogs[1:], strict=True)
    )
    tyre_list = ", ".join(f"F_{a}x, F_{a}y" for a in machine.axles)
    outputs = [
        OutputSpec("T", sp.Matrix([kinetic]), "kinetic energy [J]"),
        OutputSpec("V_gravity", sp.Matrix([gravity]), "gravity potential, 0 at p = 0 [J]"),
        OutputSpec("V_tyre", sp.Matrix([stored]), "elastic energy of the tyres [J]"),
        OutputSpec(
            "F_elastic",
            sp.Matrix(elastic),
            f"({2 * len(machine.axles)},) elastic parts of {tyre_list} [N]",
        ),
        OutputSpec("D_tyre", sp.Matrix([dissipated]), "power dissipated in the tyres [W]"),
    ]
    if machine.elements:
        outputs += [
            OutputSpec(
                "V_internal",
                sp.Matrix([mech.elements.potential]),
                "elastic energy of the internal springs with preloads, 0 at p = 0 [J]",
            ),
            OutputSpec(
                "D_internal",
                sp.Matrix([mech.elements.dissipation]),
                "power dissipated in the internal dampers [W]",
            ),
        ]
    return FunctionSpec(
        "mechanical_energy",
        "Stored energy and tyre dissipation of the multibody model (derive/energy.py).",
        f"T = ½ ṗᵀ M ṗ, V_g = g ({v_g}), V_tyre: tyre springs with the clamp's\n"
        "potential; F_elastic = −∂V_tyre/∂r_axle; D_tyre: dampers and sliding of the contact law.\n"
        "Road power F_tyre · ẇ + F_elastic · (ẇ_true − ẇ) = F_tyre · v_axle + dV_tyre/dt + D_tyre.",
        inputs,
        tuple(outputs),
        definitions=tuple(definitions),
    )
