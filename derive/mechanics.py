"""Planar multibody mechanics of a described machine, reduced to its coordinates p.

For the skid-steer of the paper (section 2.1; ``derive/machines/skid_steer.toml``)::

                     D o-------------- boom (body 2) ---------- G ----[bucket]
                      / \\                              E
        seat S      /    \\_______ lift cylinder C -> E /
           []     C o                 (force F_act)
        +-----------------H-----------------N---+   chassis (body 1), centre of gravity H
        |   B (rear axle)                  A (front axle)
           (O)                                (O)       tyres: spring-dampers in x and y
    ~~~~~~~~~~~~~~~~~~~ road w_B ~~~~~~~~~~~~~~~~~~~ road w_A ~~~~~~~~~~~~~~~~~~~~~~

with p = (x_H, y_H, θ1, θ2). In general the chassis is free in the plane, every other body sits on
a pin (its absolute angle a coordinate) or on a sliding mount of its parent (its travel a
coordinate); the joints are built into the kinematics (Eq. 17-19), so p holds only independent
coordinates (Eq. 26). The equations are

.. math:: M(p)\\,\\ddot p + C(p, \\dot p) + K(p, w) + D(p, \\dot p, \\dot w) + K_e(p) + D_e(p, \\dot p)
          = Q_{act}(p)\\,F_{act} + Q_g(p) + Q_d

(Eq. 25 with gravity kept and the disturbances of Eq. 5-7 at H; K_e, D_e of the internal
spring-dampers, :mod:`derive.elements`). The generalised forces of point forces are J_P(p)ᵀ F_P
with J_P = ∂r_P/∂p (virtual work; moments are r_x F_y − r_y F_x with signed coordinates,
errata 2). The inertia terms follow Kane's form Σ m Jᵀ a at each centre of gravity, which gives
M = Σ m J_Gᵀ J_G + Σ J e eᵀ (e picks a body's angle) and C = Σ m J_Gᵀ (d/dt J_G) ṗ.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from derive.elements import ElementForces, element_forces, tyre_forces
from derive.kinematics import rotated_dot, rotation, tree_kinematics
from derive.symbols import DEFAULT_MACHINE, MachineSymbols, machine_symbols, parameter_symbol

__all__ = ["LoaderMechanics", "derive_mechanics", "rotation"]

P = parameter_symbol


@dataclass(frozen=True)
class LoaderMechanics:
    """Symbolic results of the derivation (every entry an expression in the symbols of
    :mod:`derive.symbols`)."""

    symbols: MachineSymbols
    positions: dict[str, sp.Matrix]
    """World positions of every point (for the skid-steer A, B, C, D, E, G, H, N, S)."""
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
    """(F_Ax, F_Ay, F_Bx, F_By, ...): world-frame forces of the road on each axle, contact law."""
    anchor_rates: sp.Matrix
    """(ξ̇_A, ξ̇_B, ...): sliding rates of the tyre anchors (:mod:`derive.contact`)."""
    tyre_deflections: dict[str, sp.Matrix]
    """Per axle: its displacement from its position at p = 0 minus the road displacement."""
    tyre_slips: dict[str, sp.Matrix]
    """Per axle: its velocity relative to the road rate input."""
    elements: ElementForces
    """Internal spring-dampers: hydraulically locked cylinders and sliding mounts."""
    actuator_map: sp.Matrix
    """Q_act(p) = ∂x_cyl/∂p: generalised force of a unit cylinder force, Eq. 15, 16, 25."""
    disturbance_map: sp.Matrix
    """Q_d per (F_dx, F_dy, M_d) at H, Eq. 5-7."""
    cylinder_length: sp.Expr
    """x_cyl(p) = |E − C| of the lift cylinder."""
    cylinder_lever: sp.Expr
    """dx_cyl/dφ, Eq. 35 (φ: the angle of the lift cylinder's joint)."""
    cylinder_angle: sp.Expr
    """γ: angle of the line C -> E to the global x axis, Eq. 15-16."""
    accelerations: dict[str, sp.Matrix]
    """World accelerations of the sensor points as functions of (p, ṗ, p̈)."""
    specific_forces: dict[str, sp.Matrix]
    """Specific force Rᵀ(θ1)(a + g ŷ) in the chassis frame (what a chassis-fixed accelerometer
    reads) at the sensor points (H, N and S), as functions of (p, ṗ, p̈)."""
    residual: sp.Matrix
    """r = M p̈ + C + K + D + K_e + D_e − Q_act F_act − Q_g − Q_d with the linear tyre law."""
    static_loads: dict[str, sp.Expr]
    """F_Ay0, F_By0 (each axle), the element preloads and F_act0 that make p = 0 an equilibrium."""


def derive_mechanics(machine: str = DEFAULT_MACHINE) -> LoaderMechanics:
    """Derive the equations of motion and kinematics of the described ``machine``."""
    sym = machine_symbols(machine)
    described = sym.machine
    p, pd, pdd = sym.coordinates, sym.rates, sym.accelerations
    n = len(p)
    tree = tree_kinematics(sym)
    positions = tree.positions

    def jacobian(letter: str) -> sp.Matrix:
        return positions[letter].jacobian(p)

    def velocity(letter: str) -> sp.Matrix:
        return jacobian(letter) * pd

    def acceleration(letter: str) -> sp.Matrix:
        return jacobian(letter) * pdd + velocity(letter).jacobian(p) * pd

    g = P("g")
    mass_matrix = sp.zeros(n, n)
    coriolis_rows = [sp.S.Zero] * n
    for body in described.bodies:
        mass = P(body.mass)
        columns = tree.columns(body.centre_of_gravity)
        convective = tree.convective(body.centre_of_gravity)
        for i in range(n):
            for j in range(i, n):
                dots = sum(rotated_dot(a, b) for a in columns[i] for b in columns[j])
                mass_matrix[i, j] = mass_matrix[j, i] = mass_matrix[i, j] + mass * dots
            terms = sum(rotated_dot(a, b) for a in columns[i] for b in convective)
            coriolis_rows[i] += mass * terms
    for body in described.bodies:
        k = sym.index(tree.angles[body.name].name)
        mass_matrix[k, k] += P(body.inertia)
    coriolis = sp.Matrix(coriolis_rows)

    up = sp.Matrix([0, 1])
    weights = [P(b.mass) * jacobian(b.centre_of_gravity).T * up for b in described.bodies]
    total = weights[0]
    for weight in weights[1:]:
        total = total + weight
    gravity = -g * total

    tyres = tyre_forces(sym, positions, jacobian, velocity)
    elements = element_forces(sym, tree)
    lift = elements.lift
    disturbance_map = sp.zeros(n, 3)
    for index in range(3):
        disturbance_map[index, index] = 1
    residual = (
        mass_matrix * pdd
        + coriolis
        + tyres.springs
        + tyres.dampers
        - lift.generalised * sym.force
        - gravity
        - disturbance_map * sym.disturbances
    )
    if described.elements:
        residual += elements.springs + elements.dampers

    static_loads = _static_loads(
        sym, tyres.springs + elements.smooth_springs, lift.generalised, gravity
    )
    sensors = tuple(described.sensors)
    accelerations = {letter: acceleration(letter) for letter in sensors}
    return LoaderMechanics(
        symbols=sym,
        positions=positions,
        mass_matrix=mass_matrix,
        coriolis_centrifugal=coriolis,
        gravity_forces=gravity,
        tyre_spring_forces=tyres.springs,
        tyre_damper_forces=tyres.dampers,
        contact_tyre_forces=tyres.contact,
        contact_definitions=tyres.definitions,
        tyre_forces=tyres.forces,
        anchor_rates=tyres.anchor_rates,
        tyre_deflections=tyres.deflections,
        tyre_slips=tyres.slips,
        elements=elements,
        actuator_map=lift.generalised,
        disturbance_map=disturbance_map,
        cylinder_length=lift.length,
        cylinder_lever=lift.lever,
        cylinder_angle=lift.angle,
        accelerations=accelerations,
        specific_forces={
            letter: rotation(p[2]).T * (accelerations[letter] + g * up) for letter in accelerations
        },
        residual=residual,
        static_loads=static_loads,
    )


def _static_loads(
    sym: MachineSymbols, springs: sp.Matrix, actuator_map: sp.Matrix, gravity: sp.Matrix
) -> dict[str, sp.Expr]:
    """Static tyre loads, element preloads and cylinder force for which p = 0 is an equilibrium.

    At rest with no road input, K(0) + K_e(0) = Q_act(0) F_act0 + Q_g(0). The x row holds
    identically (no horizontal preload); the other rows are linear in the unknowns (two axles:
    statically determinate). Three or more axles are statically indeterminate; the compatibility
    condition is that of a rigid chassis set down on a level road with every tyre just touching
    it: the static tyre deflections F_iy0 / k_iy are linear in the axle's x, a + b x_i, so the
    unknowns are a and b instead of the loads.
    """
    machine = sym.machine
    at_rest = {symbol: 0 for symbol in (*sym.coordinates, *sym.road)}
    f_act0 = sp.Symbol("F_act0", real=True)
    balance = (springs - actuator_map * f_act0 - gravity).subs(at_rest)
    loads = [P(f"F_{axle}y0") for axle in machine.axles]
    preloads = [P(f"F_{element}0") for element in machine.elements]
    if len(machine.axles) == 2:
        unknowns = [*loads, f_act0, *preloads]
        solution = sp.solve(list(balance[1:, 0]), unknowns, dict=True)[0]
    else:
        level, slope = sp.symbols("delta_0 delta_slope", real=True)
        compatible = {
            load: P(f"k_{axle}y") * (level + slope * P(f"{axle}_x"))
            for load, axle in zip(loads, machine.axles, strict=True)
        }
        balance = balance.subs(compatible)
        found = sp.solve(list(balance[1:, 0]), [level, slope, f_act0, *preloads], dict=True)[0]
        solution = {load: compatible[load].subs(found) for load in loads} | found
        unknowns = [*loads, f_act0, *preloads]
    if sp.simplify(balance[0, 0]) != 0:
        raise RuntimeError("horizontal static balance does not hold identically")
    return {str(name): sp.simplify(solution[name]) for name in unknowns}
