"""Planar kinematics over a machine's body tree, in forms that keep the expressions small.

Every material point P is carried by one body; its world position is

.. math:: r_P = r_H + \\sum_k R(a_k)\\, v_k

with absolute body angles a_k (coordinates) and vectors v_k in the p = 0 frame (constant for pins,
linear in the mount coordinate for sliding mounts; a two-point mount adds its bounce along its
direction at its point ``at`` and turns about that point by its own absolute pitch angle).
Columns of J_P = ∂r_P/∂p and the convective acceleration are lists of such (angle, vector)
terms, and with S = ẑ× (a quarter turn), ∂(R(a) v)/∂a = R(a) S v and (R(a) u)·(R(b) v) =
uᵀ R(b − a) v, so inner products come out in angle differences without a simplification
pass.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from derive.description import Body
from derive.symbols import MachineSymbols, parameter_symbol

__all__ = [
    "Term",
    "TreeKinematics",
    "point",
    "rotated_dot",
    "rotation",
    "tree_kinematics",
    "unit_direction",
]

#: (angle, vector): the contribution R(angle) @ vector.
Term = tuple[sp.Expr, sp.Matrix]
QUARTER_TURN = sp.Matrix([[0, -1], [1, 0]])


def rotation(angle: sp.Expr) -> sp.Matrix:
    """Planar rotation matrix of a counter-clockwise ``angle``."""
    return sp.Matrix([[sp.cos(angle), -sp.sin(angle)], [sp.sin(angle), sp.cos(angle)]])


def point(name: str) -> sp.Matrix:
    """The p = 0 coordinates (name_x, name_y) of a point, relative to H in the chassis frame."""
    return sp.Matrix([parameter_symbol(f"{name}_x"), parameter_symbol(f"{name}_y")])


def unit_direction(body: Body) -> sp.Matrix:
    """The unit vector of a mount's ``direction`` (in its parent's frame)."""
    direction = sp.Matrix(body.direction)
    return direction / sp.sqrt(sum(v**2 for v in body.direction))  # type: ignore[union-attr]


def rotated_dot(first: Term, second: Term) -> sp.Expr:
    """(R(a) u)·(R(b) v) = uᵀ R(b − a) v for ``first = (a, u)`` and ``second = (b, v)``."""
    (angle_a, u), (angle_b, v) = first, second
    return sp.expand((u.T * rotation(angle_b - angle_a) * v)[0, 0])


@dataclass(frozen=True)
class TreeKinematics:
    """Positions of every point and their (angle, vector) term lists."""

    symbols: MachineSymbols
    positions: dict[str, sp.Matrix]
    terms: dict[str, list[Term]]
    angles: dict[str, sp.Symbol]
    """Absolute angle of each body (a mount shares its parent's)."""

    def columns(self, name: str) -> list[list[Term]]:
        """Columns of J_P = ∂r_P/∂p as term lists (empty: a zero column)."""
        p = self.symbols.coordinates
        out: list[list[Term]] = [[(sp.S.Zero, sp.Matrix([1, 0]))], [(sp.S.Zero, sp.Matrix([0, 1]))]]
        for coordinate in list(p)[2:]:
            column = [(a, QUARTER_TURN * v) for a, v in self.terms[name] if a == coordinate]
            column += [(a, v.diff(coordinate)) for a, v in self.terms[name] if v.has(coordinate)]
            out.append(column)
        return out

    def convective(self, name: str) -> list[Term]:
        """Terms of the convective acceleration (d/dt J_P) ṗ of point ``name``."""
        out: list[Term] = []
        for angle, vector in self.terms[name]:
            rate = self.symbols.rates[self.symbols.index(angle.name)]
            term = -(rate**2) * vector
            for mount in (c for c in self.symbols.coordinates if vector.has(c)):
                mount_rate = self.symbols.rates[self.symbols.index(mount.name)]
                term += 2 * rate * mount_rate * QUARTER_TURN * vector.diff(mount)
            out.append((angle, term))
        return out


def tree_kinematics(symbols: MachineSymbols) -> TreeKinematics:
    """Positions and term lists of the points of every body of ``symbols.machine``."""
    machine = symbols.machine
    p = symbols.coordinates
    root = machine.root
    r_h = sp.Matrix([p[0], p[1]])
    frame = rotation(p[2])
    positions: dict[str, sp.Matrix] = {root.centre_of_gravity: r_h}
    terms: dict[str, list[Term]] = {root.centre_of_gravity: []}
    angles: dict[str, sp.Symbol] = {root.name: p[2]}
    rotations: dict[str, sp.Matrix] = {root.name: frame}

    def carried(body: Body, vector: sp.Matrix) -> tuple[sp.Matrix, list[Term]]:
        if body.joint == "free":
            return r_h + frame * vector, [(p[2], vector)]
        if body.joint == "pin":
            local = vector - point(body.at)  # type: ignore[arg-type]
            position = positions[body.at] + rotations[body.name] * local  # type: ignore[index]
            return position, [*terms[body.at], (angles[body.name], local)]  # type: ignore[index]
        mount = sp.Symbol(body.coordinates[0], real=True)
        direction = unit_direction(body)
        parent = machine.body(body.parent)  # type: ignore[arg-type]
        if body.joint == "slider":
            travel = mount + (parameter_symbol(body.extension) if body.extension else 0)
            return carried(parent, vector + direction * travel)
        # two mounts: bounce along the direction at the point `at`, pitch about it
        local = vector - point(body.at)  # type: ignore[arg-type]
        base, base_terms = carried(parent, point(body.at) + direction * mount)  # type: ignore[arg-type]
        return base + rotations[body.name] * local, [*base_terms, (angles[body.name], local)]

    for body in machine.bodies:
        if body.joint in ("pin", "two_mounts"):
            angles[body.name] = sp.Symbol(body.angle, real=True)  # type: ignore[arg-type]
            rotations[body.name] = rotation(angles[body.name])
        elif body.joint == "slider":
            angles[body.name] = angles[body.parent]  # type: ignore[index]
        for name in body.points:
            positions[name], terms[name] = carried(body, point(name))
    return TreeKinematics(symbols, positions, terms, angles)
