"""Symbols of the loader model and the order the generated functions expect.

This module owns the model's structure: the generalised coordinates p (paper Eq. 26), the inputs
and the parameter vector. ``generated/`` exports these orders and ``loader_model.parameters.sets`` maps
named parameter sets onto them; a test proves the two agree.

Frames and signs (DESIGN.md, "The model"): global frame at the chassis centre of gravity H at static
equilibrium, x forward (towards the bucket), y up, angles counter-clockwise (nose-up pitch positive).
Every point is given as (x, y) in the chassis frame relative to H, with the boom at its operating
angle, i.e. in the configuration p = 0. Signed coordinates replace the paper's abs()-based distances
of Eq. 8 and 9 (DESIGN.md errata 2).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

__all__ = [
    "ANCHORS",
    "COORDINATES",
    "COORDINATE_ACCELERATIONS",
    "COORDINATE_RATES",
    "DISTURBANCES",
    "FORCE",
    "PARAMETERS",
    "ROAD",
    "ROAD_RATES",
    "Parameter",
    "parameter_symbol",
]


@dataclass(frozen=True)
class Parameter:
    """One entry of the generated functions' parameter vector."""

    name: str
    unit: str
    description: str


def _points(names: str, where: str) -> list[Parameter]:
    out: list[Parameter] = []
    for letter, meaning in (item.split(":") for item in names.split(",")):
        for axis in "xy":
            out.append(
                Parameter(f"{letter}_{axis}", "m", f"{axis} of {meaning} ({where}, relative to H)")
            )
    return out


#: Parameter vector, in the order the generated functions take it.
PARAMETERS: tuple[Parameter, ...] = (
    Parameter("m_1", "kg", "mass of the chassis (body 1)"),
    Parameter("J_1", "kg*m^2", "moment of inertia of the chassis about its centre of gravity H"),
    Parameter("m_2", "kg", "mass of boom, bucket and bucket load (body 2)"),
    Parameter("J_2", "kg*m^2", "moment of inertia of body 2 about its centre of gravity G"),
    Parameter("g", "m/s^2", "gravitational acceleration (0 drops gravity, as the paper does)"),
    *_points(
        "A:front axle,B:rear axle,C:lift-cylinder base,D:boom pivot,S:seat reference point,"
        "N:second accelerometer ahead of H",
        "chassis point",
    ),
    *_points("E:lift-cylinder rod end,G:centre of gravity of body 2", "boom point at p = 0"),
    Parameter("k_Ax", "N/m", "horizontal tyre stiffness at the front axle A (Eq. 2)"),
    Parameter("k_Ay", "N/m", "vertical tyre stiffness at the front axle A (Eq. 1)"),
    Parameter("c_Ax", "N*s/m", "horizontal tyre damping at the front axle A (Eq. 2)"),
    Parameter("c_Ay", "N*s/m", "vertical tyre damping at the front axle A (Eq. 1)"),
    Parameter("k_Bx", "N/m", "horizontal tyre stiffness at the rear axle B (Eq. 3)"),
    Parameter("k_By", "N/m", "vertical tyre stiffness at the rear axle B (Eq. 4)"),
    Parameter("c_Bx", "N*s/m", "horizontal tyre damping at the rear axle B (Eq. 3)"),
    Parameter("c_By", "N*s/m", "vertical tyre damping at the rear axle B (Eq. 4)"),
    Parameter("mu_road", "-", "tyre-road friction coefficient: |F_x| <= mu_road F_y at each axle"),
    Parameter(
        "F_transition", "N", "half-width of the smooth vertical contact transition around zero load"
    ),
    Parameter(
        "tau_slip", "s", "relaxation time of a tyre's horizontal anchor when sliding or airborne"
    ),
    Parameter("F_Ay0", "N", "static vertical tyre load at A (from the static equilibrium)"),
    Parameter("F_By0", "N", "static vertical tyre load at B (from the static equilibrium)"),
)

_SYMBOLS: dict[str, sp.Symbol] = {item.name: sp.Symbol(item.name, real=True) for item in PARAMETERS}


def parameter_symbol(name: str) -> sp.Symbol:
    """Return the SymPy symbol of the parameter called ``name``."""
    return _SYMBOLS[name]


#: Generalised coordinates p = (x_H, y_H, θ1, θ2) (Eq. 26), their rates and accelerations.
COORDINATES = sp.Matrix(sp.symbols("x_H y_H theta_1 theta_2", real=True))
COORDINATE_RATES = sp.Matrix(sp.symbols("xd_H yd_H thetad_1 thetad_2", real=True))
COORDINATE_ACCELERATIONS = sp.Matrix(sp.symbols("xdd_H ydd_H thetadd_1 thetadd_2", real=True))

#: Total lift-cylinder force along C -> E (both cylinders together), Eq. 15-16 and 31.
FORCE = sp.Symbol("F_act", real=True)

#: Road displacement under each axle (the tyre's contact point moves by it) and its rate.
ROAD = sp.Matrix(sp.symbols("w_Ax w_Ay w_Bx w_By", real=True))
ROAD_RATES = sp.Matrix(sp.symbols("wd_Ax wd_Ay wd_Bx wd_By", real=True))

#: Horizontal anchors (ξ_A, ξ_B) of the tyre contact points: how far each contact point has slid
#: along the road since p = 0 [m] (states of the tyre contact law, see derive.contact).
ANCHORS = sp.Matrix(sp.symbols("xi_A xi_B", real=True))

#: Disturbance forces and moment at H (Eq. 5-7): F_dx, F_dy, M_d.
DISTURBANCES = sp.Matrix(sp.symbols("F_dx F_dy M_d", real=True))
