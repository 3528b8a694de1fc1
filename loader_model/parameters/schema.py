"""Typed, immutable parameter sets of the loader (the schema of the TOML parameter files).

SI rule
-------
Every number is in SI base or derived units (m, kg, s, N, Pa, rad, Hz) with one exception taken
from the paper's Table 2 and nomenclature: the pump's per-revolution quantities (displacement in
m³/rev, shaft speed in rev/s, displacement rate in m³/(rev·s)), so that the flow is simply
``Q = V_p n``. The unit of every field is in its dataclass metadata (:func:`unit_of`) and in the
TOML file, where it is checked on loading (no conversion).

Frame convention
----------------
Points are ``(x, y)`` in metres in the chassis frame: origin at the chassis centre of gravity H,
x forward (towards the bucket), y up, with the boom at its operating angle φ0 (the configuration
p = 0 of Eq. 26). Points on the boom (E, centres of gravity) are given in the same frame at φ0,
with signs, not as the paper's abs()-based distances of Eq. 8, 9 (errata 2)::

            D o------- boom --------.
             /|  E                    `-.  G (boom + load)
            / |/                          `-[bucket]
           /  C         S    H +------ N
          '--------------------------------'
               B o                  o A          (x forward ->, y up)

The dataclasses check only the type of each value on construction
(:class:`~loader_model.parameters.fields.TypedLeaves`: a real number, not an array, boolean or
string); :func:`loader_model.parameters.sets.validate` checks ranges and consistency, and the TOML
loaders call it before returning.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from loader_model.parameters.fields import (
    COORDINATE,
    Range,
    Sourced,
    TypedLeaves,
    si,
    sources_field,
    unit_of,
)
from loader_model.parameters.hydraulics import (
    AccumulatorParameters,
    ControllerParameters,
    CylinderParameters,
    FrictionParameters,
    HydraulicParameters,
    LeakageParameters,
    PumpParameters,
)
from loader_model.parameters.seat import SeatParameters
from loader_model.parameters.tyres import TYRE_LIMITS

__all__ = [
    "AccumulatorParameters",
    "AxleTyre",
    "BoomParameters",
    "BucketLoad",
    "ChassisParameters",
    "ControllerParameters",
    "CylinderParameters",
    "EnvironmentParameters",
    "FrictionParameters",
    "Geometry",
    "HydraulicParameters",
    "LeakageParameters",
    "LoaderParameters",
    "Point",
    "PumpParameters",
    "SeatParameters",
    "TyreParameters",
    "unit_of",
]

#: A point ``(x, y)`` in metres in the chassis frame (see the module docstring).
Point = tuple[float, float]

_TYRE_STIFFNESS = Range(
    5e4, 3e7, reason="two tyres of one axle, from 25 kN/m (small, soft) to 15 MN/m (50 t loader)"
)
_TYRE_DAMPING = Range(
    0.0, 1e6, reason="undamped (0) to a loss factor of about 0.3 on the stiffest tyres at 1 Hz"
)


@dataclass(frozen=True)
class Geometry(TypedLeaves):
    """Points of the chassis and of the boom at the operating boom angle (all in m).

    Attributes
    ----------
    boom_angle : float
        φ0 = θ2 − θ1 at p = 0 in rad: inclination of the line from D to the bucket hinge pin,
        counter-clockwise from the chassis x axis. Documents the configuration of the points.
    A, B : Point
        Front and rear axle (tyre forces, Eq. 1-4).
    C : Point
        Lift-cylinder base on the chassis.
    D : Point
        Boom pivot.
    S : Point
        Seat reference point (ISO 2631-1 evaluation, section 5.3).
    N : Point
        Second accelerometer ahead of H for the pitch acceleration (section 3.3).
    E : Point
        Cylinder rod end on the boom (Eq. 15, 16).
    """

    boom_angle: float = field(
        metadata=si(
            "rad",
            Range(-math.pi / 2, math.pi / 2, reason="a boom between straight down and straight up"),
        )
    )
    A: Point = field(metadata=si("m", COORDINATE, shape=2))
    B: Point = field(metadata=si("m", COORDINATE, shape=2))
    C: Point = field(metadata=si("m", COORDINATE, shape=2))
    D: Point = field(metadata=si("m", COORDINATE, shape=2))
    S: Point = field(metadata=si("m", COORDINATE, shape=2))
    N: Point = field(metadata=si("m", COORDINATE, shape=2))
    E: Point = field(metadata=si("m", COORDINATE, shape=2))


@dataclass(frozen=True)
class ChassisParameters(TypedLeaves):
    """Chassis, body 1 of Eq. 6, 7.

    Attributes
    ----------
    mass : float
        m1 in kg.
    inertia : float
        J1 about H in kg·m².
    """

    mass: float = field(
        metadata=si("kg", Range(250.0, 45_000.0, reason="chassis of a 0.5 t to 50 t machine"))
    )
    inertia: float = field(
        metadata=si(
            "kg m^2",
            Range(
                20.0,
                500_000.0,
                reason="chassis mass 250-45 000 kg with a radius of gyration of 0.3-3.3 m",
            ),
        )
    )


@dataclass(frozen=True)
class BoomParameters(TypedLeaves):
    """Boom with the bucket attachment structure, without the bucket load (part of body 2).

    Attributes
    ----------
    mass : float
        Mass in kg.
    cog : Point
        Centre of gravity in m (chassis frame, operating angle).
    inertia : float
        Moment of inertia about ``cog`` in kg·m².
    """

    mass: float = field(
        metadata=si(
            "kg",
            Range(
                30.0,
                15_000.0,
                reason="boom, attachment and empty bucket of a 0.5 t to 50 t machine",
            ),
        )
    )
    cog: Point = field(metadata=si("m", COORDINATE, shape=2))
    inertia: float = field(
        metadata=si(
            "kg m^2",
            Range(
                1.0,
                100_000.0,
                reason="boom mass 30-15 000 kg with a radius of gyration of 0.2-2.6 m",
            ),
        )
    )


@dataclass(frozen=True)
class BucketLoad(Sourced):
    """One bucket load case (section 5.3: 340 kg empty bucket, 770 kg concrete-filled).

    Attributes
    ----------
    mass : float
        Mass in kg.
    cog : Point
        Centre of gravity in m (chassis frame, operating angle).
    inertia : float
        Moment of inertia about ``cog`` in kg·m².
    pressure_normalisation : float
        ‖p_A‖∞ of the pressure feedback loop in Pa (section 3.3: 100 bar empty, 200 bar full).
    sources : tuple of (str, str)
        Source or reason of each value by dotted path (see :meth:`source`).
    """

    mass: float = field(
        metadata=si(
            "kg",
            Range(
                0.0,
                15_000.0,
                low_open=True,
                reason="a mass is positive; a 50 t wheel loader carries about 6 m^3 of rock, 12 t",
            ),
        )
    )
    cog: Point = field(metadata=si("m", COORDINATE, shape=2))
    inertia: float = field(
        metadata=si(
            "kg m^2",
            Range(
                0.0,
                50_000.0,
                low_open=True,
                reason="an inertia is positive; 15 t spread over a 4 m bucket is below 50 000 kg m^2",
            ),
        )
    )
    pressure_normalisation: float = field(
        metadata=si(
            "Pa", Range(1e6, 5e7, reason="10-500 bar, working pressures of mobile hydraulics")
        )
    )
    sources: tuple[tuple[str, str], ...] = sources_field()


@dataclass(frozen=True)
class AxleTyre(TypedLeaves):
    """The tyres of one axle, left and right lumped: linear spring-damper (Eq. 1-4) and the
    geometry with which they envelop the road (the road input only, not the plant's parameters).

    Attributes
    ----------
    k_x, k_y : float
        Longitudinal and vertical stiffness in N/m.
    c_x, c_y : float
        Longitudinal and vertical damping in N·s/m.
    radius : float
        Free (unloaded) radius R in m: the rigid disc's radius, the scale of the tandem cam.
    cam_length, cam_height : float
        Half-length a_e / R and half-height b_e / R of the tandem elliptical cam (Schmeitz;
        :mod:`~loader_model.simulation.tandem_cam`).
    cam_exponent : float
        Its super-ellipse exponent c_e.
    cam_spacing : float
        Cam spacing over the static contact length, l_s / (2a), 2a = 2 sqrt(2 R δ − δ²) at the
        static deflection δ.
    """

    k_x: float = field(metadata=si("N/m", _TYRE_STIFFNESS))
    k_y: float = field(metadata=si("N/m", _TYRE_STIFFNESS))
    c_x: float = field(metadata=si("N s/m", _TYRE_DAMPING))
    c_y: float = field(metadata=si("N s/m", _TYRE_DAMPING))
    radius: float = field(metadata=si("m", TYRE_LIMITS["radius"]))
    cam_length: float = field(metadata=si("-", TYRE_LIMITS["cam_length"]))
    cam_height: float = field(metadata=si("-", TYRE_LIMITS["cam_height"]))
    cam_exponent: float = field(metadata=si("-", TYRE_LIMITS["cam_exponent"]))
    cam_spacing: float = field(metadata=si("-", TYRE_LIMITS["cam_spacing"]))


@dataclass(frozen=True)
class TyreParameters(TypedLeaves):
    """Tyres of the front axle (point A) and of the rear axle (point B), and their contact law.

    The contact law (``derive/contact.py``) is the paper's linear law (Eq. 1-4) while a tyre is
    loaded and sticks; it lets a tyre lift off (no pulling force, C¹ transition), limits the
    horizontal force to ``friction_coefficient`` times the vertical load, and lets the contact
    point slide (anchor state) with the excess force.

    Attributes
    ----------
    friction_coefficient : float
        Tyre-road friction coefficient μ (horizontal force limit μ F_y), dimensionless.
    contact_transition : float
        Half-width ε in N of the smooth transition of the vertical force around zero load.
    slip_relaxation_time : float
        Relaxation time τ in s of the horizontal anchor when sliding or airborne.
    """

    front: AxleTyre
    rear: AxleTyre
    friction_coefficient: float = field(
        metadata=si("-", Range(0.1, 1.5, reason="tyres on ice (0.1) to dry concrete (up to 1.5)"))
    )
    contact_transition: float = field(
        metadata=si("N", Range(1.0, 1e4, reason="1 N to 10 kN, well below the static axle loads"))
    )
    slip_relaxation_time: float = field(
        metadata=si("s", Range(1e-4, 0.1, reason="0.1-100 ms, faster than a drop's flight"))
    )


@dataclass(frozen=True)
class EnvironmentParameters(TypedLeaves):
    """Environment.

    Attributes
    ----------
    gravity : float
        Gravitational acceleration g in m/s².
    """

    gravity: float = field(
        metadata=si(
            "m/s^2",
            Range(
                9.76,
                9.84,
                reason="gravity on the Earth's surface: 9.78 at the equator, 9.83 at the poles",
            ),
        )
    )


@dataclass(frozen=True)
class LoaderParameters(Sourced):
    """The whole loader without its bucket load (see :class:`BucketLoad`).

    One attribute per TOML section; ``sources`` holds the source or reason of each value by
    dotted path (see :meth:`source`).
    """

    geometry: Geometry
    chassis: ChassisParameters
    boom: BoomParameters
    tyres: TyreParameters
    cylinders: CylinderParameters
    hydraulics: HydraulicParameters
    leakage: LeakageParameters
    friction: FrictionParameters
    pump: PumpParameters
    controller: ControllerParameters
    accumulator: AccumulatorParameters
    environment: EnvironmentParameters
    seat: SeatParameters
    sources: tuple[tuple[str, str], ...] = sources_field()
