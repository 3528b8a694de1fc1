"""Planar two-body mechanics of the loader, reduced to p = (x_H, y_H, θ1, θ2) (paper section 2.1).

Sketch (side view, p = 0; x forward towards the bucket, y up)::

                     D o-------------- boom (body 2) ---------- G ----[bucket]
                      / \\                              E
        seat S      /    \\_______ lift cylinder C -> E /
           []     C o                 (force F_act)
        +-----------------H-----------------N---+   chassis (body 1), centre of gravity H
        |   B (rear axle)                  A (front axle)
           (O)                                (O)       tyres: spring-dampers in x and y
    ~~~~~~~~~~~~~~~~~~~ road w_B ~~~~~~~~~~~~~~~~~~~ road w_A ~~~~~~~~~~~~~~~~~~~~~~

The boom is pinned to the chassis at D; its position follows from p (the pin constraint of Eq. 17-19
is built into the kinematics, so p holds only independent coordinates, Eq. 26). The equations are

.. math:: M(p)\\,\\ddot p + C(p, \\dot p) + K(p, w) + D(p, \\dot p, \\dot w)
          = Q_{act}(p)\\,F_{act} + Q_g(p) + Q_d

(Eq. 25 with gravity kept and the disturbances of Eq. 5-7 at H). The generalised forces of point
forces are J_P(p)ᵀ F_P with J_P = ∂r_P/∂p (virtual work; moments are r_x F_y − r_y F_x with signed
coordinates, DESIGN.md errata 2). The inertia terms follow Kane's form Σ m Jᵀ a, which for the
chassis (H is its centre of gravity) and the boom (G) gives M = Σ m JᵀJ + diag(0, 0, J1, J2) and
C = m2 J_Gᵀ (d/dt J_G) ṗ.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from derive.contact import (
    MINIMUM_FRICTION_LIMIT_N,
    contact_factor,
    sliding_fraction,
    unilateral,
)
from derive.symbols import (
    ANCHORS,
    COORDINATE_ACCELERATIONS,
    COORDINATE_RATES,
    COORDINATES,
    DISTURBANCES,
    FORCE,
    ROAD,
    ROAD_RATES,
    parameter_symbol,
)

__all__ = ["LoaderMechanics", "derive_mechanics", "rotation"]

P = parameter_symbol


def rotation(angle: sp.Expr) -> sp.Matrix:
    """Planar rotation matrix of a counter-clockwise ``angle``."""
    return sp.Matrix([[sp.cos(angle), -sp.sin(angle)], [sp.sin(angle), sp.cos(angle)]])


def _point(letter: str) -> sp.Matrix:
    return sp.Matrix([P(f"{letter}_x"), P(f"{letter}_y")])


@dataclass(frozen=True)
class LoaderMechanics:
    """Symbolic results of the derivation (every entry an expression in the symbols of
    :mod:`derive.symbols`)."""

    positions: dict[str, sp.Matrix]
    """World positions of the points A, B, C, D, E, G, H, N, S."""
    mass_matrix: sp.Matrix
    """M(p), Eq. 25 and 32."""
    coriolis_centrifugal: sp.Matrix
    """C(p, ṗ), Eq. 25."""
    gravity_forces: sp.Matrix
    """Q_g(p): generalised gravity forces (right-hand side)."""
    tyre_spring_forces: sp.Matrix
    """K(p, w): tyre spring forces incl. static load, Eq. 1-4 and 25 (left-hand side)."""
    tyre_damper_forces: sp.Matrix
    """D(p, ṗ, ẇ): tyre damper forces, Eq. 1-4 and 25 (left-hand side)."""
    contact_tyre_forces: sp.Matrix
    """Generalised tyre forces (right-hand side) of the contact law of :mod:`derive.contact`."""
    contact_definitions: tuple[tuple[sp.Symbol, sp.Expr], ...]
    """Ordered intermediates (F_y_A, F_x_A, sigma_A, ...) of the contact law, in terms of the
    inputs and earlier intermediates; the contact outputs are written in these symbols."""
    tyre_forces: sp.Matrix
    """(F_Ax, F_Ay, F_Bx, F_By): world-frame forces of the road on each axle, contact law."""
    anchor_rates: sp.Matrix
    """(ξ̇_A, ξ̇_B): sliding rates of the tyre anchors (:mod:`derive.contact`)."""
    tyre_deflections: dict[str, sp.Matrix]
    """Per axle: its displacement from its position at p = 0 minus the road displacement."""
    tyre_slips: dict[str, sp.Matrix]
    """Per axle: its velocity relative to the road rate input."""
    actuator_map: sp.Matrix
    """Q_act(p) = ∂x_cyl/∂p: generalised force of a unit cylinder force, Eq. 15, 16, 25."""
    disturbance_map: sp.Matrix
    """Q_d per (F_dx, F_dy, M_d) at H, Eq. 5-7."""
    cylinder_length: sp.Expr
    """x_cyl(p) = |E − C|."""
    cylinder_lever: sp.Expr
    """dx_cyl/dφ, Eq. 35."""
    cylinder_angle: sp.Expr
    """γ: angle of the line C -> E to the global x axis, Eq. 15-16."""
    accelerations: dict[str, sp.Matrix]
    """World accelerations of points as functions of (p, ṗ, p̈)."""
    specific_forces: dict[str, sp.Matrix]
    """Specific force Rᵀ(θ1)(a + g ŷ) in the chassis frame (what a chassis-fixed accelerometer
    reads) at H, N and S, as functions of (p, ṗ, p̈)."""
    residual: sp.Matrix
    """r = M p̈ + C + K + D − Q_act F_act − Q_g − Q_d with the linear tyre law (zero on motion)."""
    static_loads: dict[str, sp.Expr]
    """F_Ay0, F_By0 and F_act0 that make p = 0 a static equilibrium."""


def derive_mechanics() -> LoaderMechanics:
    """Derive the loader's equations of motion and kinematics (paper section 2.1)."""
    p, pd, pdd = COORDINATES, COORDINATE_RATES, COORDINATE_ACCELERATIONS
    x_h, y_h, theta_1, theta_2 = p
    r_h = sp.Matrix([x_h, y_h])
    chassis = rotation(theta_1)
    boom = rotation(theta_2)

    positions: dict[str, sp.Matrix] = {"H": r_h}
    for letter in "ABCDNS":
        positions[letter] = r_h + chassis * _point(letter)
    for letter in "EG":
        positions[letter] = positions["D"] + boom * (_point(letter) - _point("D"))

    def jacobian(letter: str) -> sp.Matrix:
        return positions[letter].jacobian(p)

    def velocity(letter: str) -> sp.Matrix:
        return jacobian(letter) * pd

    def acceleration(letter: str) -> sp.Matrix:
        return jacobian(letter) * pdd + velocity(letter).jacobian(p) * pd

    m_1, m_2, j_1, j_2, g = (P(name) for name in ("m_1", "m_2", "J_1", "J_2", "g"))
    # Columns of J_G = ∂r_G/∂p as (angle, body vector) pairs: the column is R(angle) @ vector.
    # With S = ẑ× (a quarter turn), ∂(R(θ) u)/∂θ = R(θ) S u, and (R(a) u)·(R(b) v) = uᵀ R(b − a) v,
    # so M and C come out in θ2 − θ1 without a simplification pass.
    quarter_turn = sp.Matrix([[0, -1], [1, 0]])
    d_vec = _point("D")
    g_vec = _point("G") - _point("D")
    columns_g = [
        (sp.S.Zero, sp.Matrix([1, 0])),
        (sp.S.Zero, sp.Matrix([0, 1])),
        (theta_1, quarter_turn * d_vec),
        (theta_2, quarter_turn * g_vec),
    ]
    mass_matrix = sp.zeros(4, 4)
    for i in range(4):
        for j in range(i, 4):
            entry = m_2 * _rotated_dot(columns_g[i], columns_g[j])
            mass_matrix[i, j] = mass_matrix[j, i] = entry
    mass_matrix[0, 0] += m_1
    mass_matrix[1, 1] += m_1
    mass_matrix[2, 2] += j_1
    mass_matrix[3, 3] += j_2
    # Convective acceleration of G: −θ̇1² R(θ1) D − θ̇2² R(θ2) (G − D).
    convective_g = [(theta_1, -(pd[2] ** 2) * d_vec), (theta_2, -(pd[3] ** 2) * g_vec)]
    coriolis = sp.Matrix(
        [m_2 * sum(_rotated_dot(column, term) for term in convective_g) for column in columns_g]
    )

    up = sp.Matrix([0, 1])
    gravity = -g * (m_1 * jacobian("H").T * up + m_2 * jacobian("G").T * up)

    springs = sp.zeros(4, 1)
    dampers = sp.zeros(4, 1)
    contact = sp.zeros(4, 1)
    tyre_forces: list[sp.Expr] = []
    anchor_rates: list[sp.Expr] = []
    definitions: list[tuple[sp.Symbol, sp.Expr]] = []
    deflections: dict[str, sp.Matrix] = {}
    slips: dict[str, sp.Matrix] = {}
    mu, width, tau = P("mu_road"), P("F_transition"), P("tau_slip")
    for index, (axle, offset) in enumerate((("A", 0), ("B", 2))):
        deflection = positions[axle] - _point(axle) - ROAD[offset : offset + 2, 0]
        slip = velocity(axle) - ROAD_RATES[offset : offset + 2, 0]
        deflections[axle], slips[axle] = deflection, slip
        k_x, k_y = P(f"k_{axle}x"), P(f"k_{axle}y")
        c_x, c_y = P(f"c_{axle}x"), P(f"c_{axle}y")
        spring = sp.Matrix([-k_x * deflection[0], P(f"F_{axle}y0") - k_y * deflection[1]])
        damper = sp.Matrix([-c_x * slip[0], -c_y * slip[1]])
        springs -= jacobian(axle).T * spring
        dampers -= jacobian(axle).T * damper
        # Contact law of derive.contact: unilateral vertical force; horizontal spring anchored
        # at ξ with a load-faded damper, the anchor sliding with the fraction σ of the friction
        # limit's use (and in the air). Each law's result is a named intermediate (emitted in
        # order by the code generator), so that no Piecewise is nested in another's condition.
        vertical, horizontal, sliding = (
            sp.Symbol(f"{name}_{axle}", real=True) for name in ("F_y", "F_x", "sigma")
        )
        stretch = deflection[0] - ANCHORS[index]
        definitions += [
            (vertical, unilateral(spring[1] + damper[1], width)),
            (horizontal, -k_x * stretch - contact_factor(vertical, width) * c_x * slip[0]),
            (
                sliding,
                sliding_fraction(sp.Abs(horizontal), mu * vertical + MINIMUM_FRICTION_LIMIT_N),
            ),
        ]
        contact += jacobian(axle).T * sp.Matrix([horizontal, vertical])
        tyre_forces += [horizontal, vertical]
        anchor_rates.append(sliding * (slip[0] + stretch / tau))

    # The cylinder vector C -> E in the chassis frame depends on φ = θ2 − θ1 only (Eq. 35).
    cylinder = _point("D") - _point("C") + rotation(theta_2 - theta_1) * (_point("E") - _point("D"))
    cylinder_length = sp.sqrt(cylinder[0] ** 2 + cylinder[1] ** 2)
    actuator_map = sp.Matrix([cylinder_length]).jacobian(p).T
    cylinder_lever = actuator_map[3, 0]
    cylinder_angle = theta_1 + sp.atan2(cylinder[1], cylinder[0])

    disturbance_map = sp.Matrix([[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, 0]])
    residual = (
        mass_matrix * pdd
        + coriolis
        + springs
        + dampers
        - actuator_map * FORCE
        - gravity
        - disturbance_map * DISTURBANCES
    )

    static_loads = _static_loads(springs, actuator_map, gravity)
    accelerations = {letter: acceleration(letter) for letter in ("H", "N", "S")}
    return LoaderMechanics(
        positions=positions,
        mass_matrix=mass_matrix,
        coriolis_centrifugal=coriolis,
        gravity_forces=gravity,
        tyre_spring_forces=springs,
        tyre_damper_forces=dampers,
        contact_tyre_forces=contact,
        contact_definitions=tuple(definitions),
        tyre_forces=sp.Matrix(tyre_forces),
        anchor_rates=sp.Matrix(anchor_rates),
        tyre_deflections=deflections,
        tyre_slips=slips,
        actuator_map=actuator_map,
        disturbance_map=disturbance_map,
        cylinder_length=cylinder_length,
        cylinder_lever=cylinder_lever,
        cylinder_angle=cylinder_angle,
        accelerations=accelerations,
        specific_forces={
            letter: chassis.T * (accelerations[letter] + g * up) for letter in accelerations
        },
        residual=residual,
        static_loads=static_loads,
    )


def _rotated_dot(first: tuple[sp.Expr, sp.Matrix], second: tuple[sp.Expr, sp.Matrix]) -> sp.Expr:
    """(R(a) u)·(R(b) v) = uᵀ R(b − a) v for ``first = (a, u)`` and ``second = (b, v)``."""
    (angle_a, u), (angle_b, v) = first, second
    return sp.expand((u.T * rotation(angle_b - angle_a) * v)[0, 0])


def _static_loads(
    springs: sp.Matrix, actuator_map: sp.Matrix, gravity: sp.Matrix
) -> dict[str, sp.Expr]:
    """Static tyre loads and cylinder force for which p = 0 is an equilibrium.

    At rest with no road input, K(0) = Q_act(0) F_act0 + Q_g(0). The x row holds identically (no
    horizontal preload); the y, θ1 and θ2 rows are linear in F_Ay0, F_By0 and F_act0.
    """
    at_rest = {symbol: 0 for symbol in (*COORDINATES, *ROAD)}
    f_act0 = sp.Symbol("F_act0", real=True)
    balance = (springs - actuator_map * f_act0 - gravity).subs(at_rest)
    unknowns = [P("F_Ay0"), P("F_By0"), f_act0]
    solution = sp.solve(list(balance[1:, 0]), unknowns, dict=True)[0]
    if sp.simplify(balance[0, 0]) != 0:
        raise RuntimeError("horizontal static balance does not hold identically")
    return {str(name): sp.simplify(solution[name]) for name in unknowns}
