r"""Force elements of a machine: tyres (contact law of :mod:`derive.contact`), cylinders, mounts.

- Tyres: per axle, the paper's linear spring-damper in x and y (Eq. 1-4) and the contact law.
- The driven lift cylinder: its length x_cyl, lever dx_cyl/dφ and angle γ (Eq. 15, 16, 35); its
  generalised force per newton is Q_act = ∂x_cyl/∂p (virtual work).
- Internal spring-dampers (K_e, D_e on the left-hand side): a hydraulically locked cylinder is a
  spring of its chamber stiffness k along its line, F = F_0 − k (x − x_0) − c ẋ with generalised
  force F ∂x/∂p; a sliding mount (suspended cab or seat) a spring-damper on its travel s,
  F = F_0 − k s − c ṡ. The preloads F_0 come from the static equilibrium.
- A two-point mount (a cab on a front and a rear mount): the body bounces by s along the unit
  direction d at its point ``at`` (a point of the parent, at p = 0 the body's reference) and
  pitches by its own absolute angle θ_b about that point; mount i at the body's point Q_i
  deflects along d by

  .. math:: e_i = s + d^T \left(R(\theta_b - \theta_a) - I\right)(Q_i - at)

  (θ_a the parent's angle), with F_i = F_i0 − k_i e_i − c_i ė_i and generalised force
  F_i ∂e_i/∂p. For small angles e_i ≈ s + x_i θ with x_i the mount's lever along the body
  (the rigid body on two springs of vehicle dynamics).
- End stops on a mount (``end_stops = true``): beyond the travel limits s_min < 0 < s_max
  (from the static position p = 0) a one-sided spring-damper k_stop, c_stop acts on the
  penetration δ, C¹ in δ like the runtime's cylinder end stops (quadratic over the first
  :data:`STOP_BAND_M`), its damping faded in by the same ramp and clamped so the stop never
  pulls:

  .. math:: F_{stop} = \max(k_{stop}\,\mathrm{ramp}(\delta) + c_{stop}\,\dot\delta\,
            \min(\mathrm{ramp}(\delta)/\delta_0, 1),\ 0)

  with ramp(δ) = 0 for δ ≤ 0, δ²/(2δ_0) below δ_0, δ − δ_0/2 beyond. The elastic part is in
  K_e, the damped remainder in D_e; inside the travel both are exactly 0, so the static loads
  and the linear models at p = 0 do not see the stops.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import sympy as sp

from derive.contact import (
    MINIMUM_FRICTION_LIMIT_N,
    contact_factor,
    sliding_fraction,
    unilateral,
)
from derive.description import Actuator, Body
from derive.kinematics import TreeKinematics, point, rotation, unit_direction
from derive.symbols import MachineSymbols, parameter_symbol

__all__ = [
    "STOP_BAND_M",
    "Cylinder",
    "ElementForces",
    "TyreForces",
    "element_forces",
    "stop_ramp",
    "stop_ramp_integral",
    "tyre_forces",
]

P = parameter_symbol
#: δ_0: penetration over which an end stop's spring grows in quadratically (C¹), as the
#: runtime's cylinder end stops [m].
STOP_BAND_M = sp.Rational(1, 2000)


def stop_ramp(penetration: sp.Expr) -> sp.Expr:
    """C¹ ramp max(δ, 0): 0 for δ ≤ 0, δ²/(2δ_0) up to δ_0, δ − δ_0/2 beyond."""
    band = STOP_BAND_M
    return sp.Piecewise(
        (0, penetration <= 0),
        (penetration - band / 2, penetration >= band),
        (penetration**2 / (2 * band), True),
    )


def stop_ramp_integral(penetration: sp.Expr) -> sp.Expr:
    """∫ ramp(δ) dδ from 0: the end stop's elastic energy per unit stiffness [m²]."""
    band = STOP_BAND_M
    return sp.Piecewise(
        (0, penetration <= 0),
        (band**2 / 6 + penetration * (penetration - band) / 2, penetration >= band),
        (penetration**3 / (6 * band), True),
    )


def _stop_fade(penetration: sp.Expr) -> sp.Expr:
    """min(ramp(δ)/δ_0, 1) written on δ (no Piecewise in another's condition)."""
    band = STOP_BAND_M
    return sp.Piecewise(
        (0, penetration <= 0),
        (1, penetration >= 3 * band / 2),
        (penetration**2 / (2 * band**2), penetration <= band),
        (penetration / band - sp.Rational(1, 2), True),
    )


@dataclass(frozen=True)
class TyreForces:
    """Generalised tyre forces of every axle, linear law and contact law."""

    springs: sp.Matrix
    dampers: sp.Matrix
    contact: sp.Matrix
    definitions: tuple[tuple[sp.Symbol, sp.Expr], ...]
    forces: sp.Matrix
    anchor_rates: sp.Matrix
    deflections: dict[str, sp.Matrix]
    slips: dict[str, sp.Matrix]


def tyre_forces(
    sym: MachineSymbols,
    positions: dict[str, sp.Matrix],
    jacobian: Callable[[str], sp.Matrix],
    velocity: Callable[[str], sp.Matrix],
) -> TyreForces:
    """Tyre forces at every axle of ``sym.machine`` (module docstring)."""
    n = len(sym.coordinates)
    springs, dampers, contact = sp.zeros(n, 1), sp.zeros(n, 1), sp.zeros(n, 1)
    forces: list[sp.Expr] = []
    anchor_rates: list[sp.Expr] = []
    definitions: list[tuple[sp.Symbol, sp.Expr]] = []
    deflections: dict[str, sp.Matrix] = {}
    slips: dict[str, sp.Matrix] = {}
    mu, width, tau = P("mu_road"), P("F_transition"), P("tau_slip")
    for index, axle in enumerate(sym.machine.axles):
        offset = 2 * index
        deflection = positions[axle] - point(axle) - sym.road[offset : offset + 2, 0]
        slip = velocity(axle) - sym.road_rates[offset : offset + 2, 0]
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
        stretch = deflection[0] - sym.anchors[index]
        definitions += [
            (vertical, unilateral(spring[1] + damper[1], width)),
            (horizontal, -k_x * stretch - contact_factor(vertical, width) * c_x * slip[0]),
            (
                sliding,
                sliding_fraction(sp.Abs(horizontal), mu * vertical + MINIMUM_FRICTION_LIMIT_N),
            ),
        ]
        contact += jacobian(axle).T * sp.Matrix([horizontal, vertical])
        forces += [horizontal, vertical]
        anchor_rates.append(sliding * (slip[0] + stretch / tau))
    return TyreForces(
        springs,
        dampers,
        contact,
        tuple(definitions),
        sp.Matrix(forces),
        sp.Matrix(anchor_rates),
        deflections,
        slips,
    )


@dataclass(frozen=True)
class Cylinder:
    """A cylinder across one pin joint (base on the parent, rod end on the pinned body)."""

    length: sp.Expr
    generalised: sp.Matrix
    """∂x/∂p: generalised force per newton of extension force."""
    lever: sp.Expr
    """dx/dφ with φ the joint angle (child angle − parent angle)."""
    angle: sp.Expr
    """Angle of the line base -> rod end to the global x axis."""
    rate: sp.Expr
    """ẋ = dx/dφ φ̇."""


@dataclass(frozen=True)
class ElementForces:
    """The lift cylinder and the internal spring-dampers (left-hand side K_e, D_e)."""

    lift: Cylinder
    springs: sp.Matrix
    dampers: sp.Matrix
    potential: sp.Expr
    """Stored energy of the internal springs, 0 at p = 0 [J] (with their preloads)."""
    dissipation: sp.Expr
    """Power dissipated in the internal dampers [W]."""
    smooth_springs: sp.Matrix
    """K_e without the end stops (exactly K_e inside the travel: the static equilibrium)."""


def _cylinder(sym: MachineSymbols, tree: TreeKinematics, actuator: Actuator) -> Cylinder:
    machine = sym.machine
    child = machine.body_of(actuator.rod)
    parent = machine.body(child.parent)  # type: ignore[arg-type]
    child_angle, parent_angle = tree.angles[child.name], tree.angles[parent.name]
    # The vector base -> rod end in the parent's frame depends on the joint angle only (Eq. 35).
    joint = point(child.at)  # type: ignore[arg-type]
    vector = (
        joint
        - point(actuator.base)
        + rotation(child_angle - parent_angle) * (point(actuator.rod) - joint)
    )
    length = sp.sqrt(vector[0] ** 2 + vector[1] ** 2)
    generalised = sp.Matrix([length]).jacobian(sym.coordinates).T
    i, j = sym.index(child_angle.name), sym.index(parent_angle.name)
    lever = generalised[i, 0]
    return Cylinder(
        length=length,
        generalised=generalised,
        lever=lever,
        angle=parent_angle + sp.atan2(vector[1], vector[0]),
        rate=lever * (sym.rates[i] - sym.rates[j]),
    )


def element_forces(sym: MachineSymbols, tree: TreeKinematics) -> ElementForces:
    """The lift cylinder and the internal spring-dampers of ``sym.machine``."""
    machine = sym.machine
    n = len(sym.coordinates)
    at_rest = {symbol: 0 for symbol in sym.coordinates}
    springs, dampers = sp.zeros(n, 1), sp.zeros(n, 1)
    potential, dissipation = sp.S.Zero, sp.S.Zero
    stop_springs, stop_dampers = sp.zeros(n, 1), sp.zeros(n, 1)
    mounts = {f"{b.name}_{q}": (b, q) for b in machine.bodies for q in b.mounts}
    for name in machine.elements:
        k, c, preload = P(f"k_{name}"), P(f"c_{name}"), P(f"F_{name}0")
        locked = next((a for a in machine.actuators if a.name == name), None)
        if locked is not None:
            cylinder = _cylinder(sym, tree, locked)
            extension, rate, lever = (
                cylinder.length - cylinder.length.subs(at_rest),
                cylinder.rate,
                cylinder.generalised,
            )
        elif name in mounts:
            extension = _mount_deflection(sym, tree, *mounts[name])
            lever = sp.Matrix([extension]).jacobian(sym.coordinates).T
            rate = (lever.T * sym.rates)[0, 0]
        else:
            index = sym.index(machine.body(name).coordinates[0])
            extension, rate = sym.coordinates[index], sym.rates[index]
            lever = sp.zeros(n, 1)
            lever[index, 0] = 1
        springs -= lever * (preload - k * extension)
        dampers += lever * (c * rate)
        potential += k * extension**2 / 2 - preload * extension
        dissipation += c * rate**2
        if name in machine.stops:
            elastic, damped, energy, loss = _end_stops(name, extension, rate)
            stop_springs += lever * elastic
            stop_dampers += lever * damped
            potential += energy
            dissipation += loss
    return ElementForces(
        _cylinder(sym, tree, machine.driven),
        springs + stop_springs,
        dampers + stop_dampers,
        potential,
        dissipation,
        springs,
    )


def _mount_deflection(sym: MachineSymbols, tree: TreeKinematics, body: Body, mount: str) -> sp.Expr:
    """e_i of the mount at ``mount`` of a two-point mounted ``body`` (module docstring)."""
    direction = unit_direction(body)
    parent = sym.machine.body(body.parent)  # type: ignore[arg-type]
    turn = tree.angles[body.name] - tree.angles[parent.name]
    lever = point(mount) - point(body.at)  # type: ignore[arg-type]
    bounce = sp.Symbol(body.coordinates[0], real=True)
    return bounce + (direction.T * (rotation(turn) - sp.eye(2)) * lever)[0, 0]


def _end_stops(
    name: str, extension: sp.Expr, rate: sp.Expr
) -> tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]:
    """(elastic, damped remainder) of the end stops' force along −e (left-hand side, like
    k e), their elastic energy and their dissipated power (module docstring)."""
    low, high = P(f"s_min_{name}"), P(f"s_max_{name}")
    k, c = P(f"k_stop_{name}"), P(f"c_stop_{name}")
    above, below = extension - high, low - extension
    # each stop pushes out of itself: the upper along −e, the lower along +e
    upper_elastic, lower_elastic = k * stop_ramp(above), k * stop_ramp(below)
    upper = sp.Max(upper_elastic + c * rate * _stop_fade(above), 0)
    lower = sp.Max(lower_elastic - c * rate * _stop_fade(below), 0)
    elastic = upper_elastic - lower_elastic
    damped = (upper - upper_elastic) - (lower - lower_elastic)
    energy = k * (stop_ramp_integral(above) + stop_ramp_integral(below))
    return elastic, damped, energy, damped * rate
