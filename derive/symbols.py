"""Symbols of a machine model and the order the generated functions expect.

This module owns the model's structure: the generalised coordinates p (paper Eq. 26 for the
skid-steer), the inputs and the parameter vector, all read from a machine description
(:mod:`derive.description`). ``generated/`` exports these orders and ``loader_model.parameters.sets``
maps named parameter sets onto them; a test proves the two agree.

Frames and signs (guide page "Model"): global frame at the chassis centre of gravity H at static
equilibrium, x forward (towards the bucket), y up, angles counter-clockwise (nose-up pitch positive).
Every point is given as (x, y) in the chassis frame relative to H, with the boom at its operating
angle, i.e. in the configuration p = 0. Signed coordinates replace the paper's abs()-based distances
of Eq. 8 and 9 (errata 2). Angles are absolute; a joint angle is a difference of two.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from derive.description import Machine, load_machine

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
    "MachineSymbols",
    "Parameter",
    "machine_symbols",
    "parameter_symbol",
    "rate_name",
]

DEFAULT_MACHINE = "skid_steer"


@dataclass(frozen=True)
class Parameter:
    """One entry of the generated functions' parameter vector."""

    name: str
    unit: str
    description: str


def parameter_symbol(name: str) -> sp.Symbol:
    """Return the SymPy symbol of the parameter called ``name``."""
    return sp.Symbol(name, real=True)


def rate_name(name: str, dots: str = "d") -> str:
    """``x_H`` -> ``xd_H``: the name of a coordinate's rate (``dd``: acceleration)."""
    head, _, tail = name.partition("_")
    return f"{head}{dots}_{tail}"


@dataclass(frozen=True)
class MachineSymbols:
    """Coordinates, inputs and parameters of one machine."""

    machine: Machine
    coordinates: sp.Matrix
    rates: sp.Matrix
    accelerations: sp.Matrix
    force: sp.Symbol
    road: sp.Matrix
    road_rates: sp.Matrix
    anchors: sp.Matrix
    disturbances: sp.Matrix
    parameters: tuple[Parameter, ...]

    def index(self, coordinate: str) -> int:
        """Position of the coordinate called ``coordinate`` in p."""
        return [symbol.name for symbol in self.coordinates].index(coordinate)


def _real(names: list[str]) -> sp.Matrix:
    return sp.Matrix([sp.Symbol(name, real=True) for name in names])


@cache
def machine_symbols(machine: str = DEFAULT_MACHINE) -> MachineSymbols:
    """The symbols of the described machine ``machine`` (a name or a TOML path)."""
    described = load_machine(machine)
    names = [name for body in described.bodies for name in body.coordinates]
    road = [f"w_{axle}{axis}" for axle in described.axles for axis in "xy"]
    return MachineSymbols(
        machine=described,
        coordinates=_real(names),
        rates=_real([rate_name(name) for name in names]),
        accelerations=_real([rate_name(name, "dd") for name in names]),
        force=sp.Symbol("F_act", real=True),
        road=_real(road),
        road_rates=_real([rate_name(name) for name in road]),
        anchors=_real([f"xi_{axle}" for axle in described.axles]),
        disturbances=_real(["F_dx", "F_dy", "M_d"]),
        parameters=tuple(
            Parameter(item.name, item.unit, item.description) for item in described.parameters
        ),
    )


_DEFAULT = machine_symbols()
#: The default machine's (the skid-steer's) orders, as before machine descriptions existed.
PARAMETERS: tuple[Parameter, ...] = _DEFAULT.parameters
#: Generalised coordinates p = (x_H, y_H, θ1, θ2) (Eq. 26), their rates and accelerations.
COORDINATES = _DEFAULT.coordinates
COORDINATE_RATES = _DEFAULT.rates
COORDINATE_ACCELERATIONS = _DEFAULT.accelerations
#: Total lift-cylinder force along C -> E (both cylinders together), Eq. 15-16 and 31.
FORCE = _DEFAULT.force
#: Road displacement under each axle (the tyre's contact point moves by it) and its rate.
ROAD = _DEFAULT.road
ROAD_RATES = _DEFAULT.road_rates
#: Horizontal anchors (ξ_A, ξ_B) of the tyre contact points: how far each contact point has slid
#: along the road since p = 0 [m] (states of the tyre contact law, see derive.contact).
ANCHORS = _DEFAULT.anchors
#: Disturbance forces and moment at H (Eq. 5-7): F_dx, F_dy, M_d.
DISTURBANCES = _DEFAULT.disturbances
