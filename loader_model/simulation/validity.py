r"""Where the model holds: its range of validity, checked during a run.

The plant is a planar rigid-body model on tyres that touch the ground only at the axles A and B,
with a lift cylinder between stiff end stops. Outside the bounds below it describes no loader,
and a run that crosses one stops there with
:class:`~loader_model.simulation.validity_check.ModelValidityError`, which carries the time series
up to the violation (the evidence) and names the time, the state and the bound. The simulator
checks after every chunk of periods, on the rows just integrated
(:class:`~loader_model.simulation.validity_check.ValidityMonitor`: a few vectorised comparisons
per 500 periods). The default bounds (:func:`validity_bounds`, from the plant's parameters) and
their reasons:

- **Pitch** θ1 (tip-over): the static stability angles of the machine about the front and the rear
  tyres' contact points, atan(horizontal distance from the combined centre of gravity to the contact
  point / its height above it), with the chassis mass at H and the boom, bucket and load at G at
  p = 0, the contact points each axle's free tyre radius below it (the radii of the road input
  the simulator runs on; :data:`~loader_model.simulation.travel.DEFAULT_TYRE_RADIUS_M` by
  default). Past that angle the machine's weight tips it further over the tyres still on the
  ground, and the model, whose tyres act at the axle points and which has no bucket or chassis
  that could touch the ground, no longer describes where it rests. Default loader: 35.9°
  nose-down and 39.1° nose-up with the full bucket, 41.7° and 30.8° empty.
- **Boom angle** φ = θ2 − θ1 relative to its operating value (p = 0): the range the cylinder stroke
  allows, piston position 0 to stroke (from the generated cylinder kinematics), widened by
  :data:`END_STOP_MARGIN_RAD` for the end stops' compliance and never past the linkage's dead points
  (dx_cyl/dφ = 0). The model's end stops are stiff springs (k_end = 1e8 N/m per cylinder); 0.05 rad
  beyond the retracted stop is 21 mm of piston travel into it, 4 MN on the default's two cylinders,
  more than any stop survives; at the extended end (φ = +1.73 rad for the default) the dead point
  is 0.10 rad further, where the cylinder loses its lever arm and the model's boom swings over the
  top (measured: ISO 8608 class H at 40 km/h reached φ = 3.8 rad). Default: −0.116 to +1.779 rad.
- **Airborne**: both vertical tyre loads zero (F_Ay = F_By = 0) for longer than
  :data:`DEFAULT_AIRBORNE_MAX_S` = 0.5 s. A ballistic flight of T = 0.5 s rises g T²/8 = 0.31 m and
  lands at g T/2 = 2.5 m/s, which the default's tyres (4.35 MN/m together, 4270 kg loaded) take with
  at most 0.08 m of deflection (undamped, v √(m/k)), under 40 % of a 12-16.5 tyre's 0.21 m section
  height; a 1 s flight lands at 4.9 m/s and needs up to 0.15 m, near where the rim meets the ground
  and the linear tyre law fails. The paper's
  course keeps flights below 0.15 s (measured, every controller, both loads, 9 and 18 km/h).
- **Seat acceleration**: |f_Sx|, |f_Sy| from their static values above
  :data:`DEFAULT_SEAT_ACCELERATION_M_S2` = 50 g. Shocks on a seat stay below 50 g (the limit the ISO
  2631 input checks cite); the paper's course peaks at 35 m/s². The run that reached it (class E at
  40 km/h, full bucket, seed 1, t = 13.287 s: ẋ_H jumped by 13 m/s in one 1 ms period) was a failed
  fixed-step integration step: with 2 ROS2 substeps per period it stays below 0.2 rad of pitch.
  Such periods are now integrated again finer where the substeps' error estimate flags them
  (:mod:`~loader_model.simulation.simulator`); the bound stays as the last guard.
- Non-finite numbers: :class:`~loader_model.simulation.validity_check.SimulationError` naming the
  time and the last finite state, as before.

Every bound can be given instead (:class:`ValidityBounds`, ``simulate(validity=...)``); the check
and its error are in :mod:`~loader_model.simulation.validity_check`.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import casadi as ca
import numpy as np

from loader_model.plant.layout import SKID_STEER, PlantLayout
from loader_model.simulation._checks import as_number
from loader_model.simulation.travel import DEFAULT_TYRE_RADIUS_M, tyre_radii

__all__ = [
    "DEFAULT_AIRBORNE_MAX_S",
    "DEFAULT_SEAT_ACCELERATION_M_S2",
    "END_STOP_MARGIN_RAD",
    "ValidityBounds",
    "resolve_bounds",
    "validity_bounds",
]

#: Boom angle allowed beyond each end stop of the stroke, rad (module notes).
END_STOP_MARGIN_RAD = 0.05
#: Longest time with both tyres off the ground, s (module notes).
DEFAULT_AIRBORNE_MAX_S = 0.5
#: Largest seat acceleration from its static value, m/s² (50 g; module notes).
DEFAULT_SEAT_ACCELERATION_M_S2 = 50.0 * 9.80665

_GRID_STEP_RAD = 1e-3


@dataclass(frozen=True)
class ValidityBounds:
    """Bounds of the model's range of validity (module notes); every field is checked.

    Attributes
    ----------
    pitch_down_rad, pitch_up_rad : float
        Largest nose-down (−θ1) and nose-up (θ1) chassis pitch in rad, (0, π].
    boom_down_rad, boom_up_rad : float
        Largest boom angle below and above its operating value, −(φ − φ0) and φ − φ0 in rad,
        (0, π].
    airborne_s : float
        Longest time with both tyres off the ground in s, (0, 3600].
    seat_acceleration_m_s2 : float
        Largest |f_Sx|, |f_Sy| from their static values in m/s², (0, 1e5].
    """

    pitch_down_rad: float
    pitch_up_rad: float
    boom_down_rad: float
    boom_up_rad: float
    airborne_s: float = DEFAULT_AIRBORNE_MAX_S
    seat_acceleration_m_s2: float = DEFAULT_SEAT_ACCELERATION_M_S2

    def __post_init__(self) -> None:
        limits = {"airborne_s": (3600.0, "s"), "seat_acceleration_m_s2": (1e5, "m/s^2")}
        for field in dataclasses.fields(self):
            maximum, unit = limits.get(field.name, (math.pi, "rad"))
            value, name = getattr(self, field.name), f"validity bound {field.name}"
            if not isinstance(value, int | float | np.integer | np.floating):  # not "1" either
                raise ValueError(
                    f"{name} must be a number in (0, {maximum:g}] {unit}; got {value!r}"
                )
            number = as_number(value, name, unit, minimum=0.0, maximum=maximum, strict_minimum=True)
            object.__setattr__(self, field.name, number)


def _parameter(params: np.ndarray, name: str, layout: PlantLayout = SKID_STEER) -> float:
    return float(params[layout.parameter_names.index(name)])


@functools.cache
def _bodies(layout: PlantLayout) -> tuple[tuple[str, str | None], ...]:
    """(mass parameter, centre-of-gravity point or None for the chassis at H) of every body."""
    import tomllib

    info = layout.machine
    raw = tomllib.loads(info.description_path.read_text(encoding="utf-8"))["bodies"]
    return tuple(
        (body["mass"], None if body["joint"] == "free" else body["centre_of_gravity"])
        for body in raw.values()
    )


def _stability_angles(
    params: np.ndarray, tyre_radius_m: tuple[float, ...], layout: PlantLayout = SKID_STEER
) -> tuple[float, float]:
    """Static stability angles (nose-down, nose-up) in rad about the front and rear contacts."""

    def value(name: str) -> float:
        return _parameter(params, name, layout)

    bodies = _bodies(layout)
    total = sum(value(mass) for mass, _ in bodies)
    moving = [(value(mass), point) for mass, point in bodies if point is not None]
    # H is the chassis's centre of gravity
    x_cg = sum(mass * value(f"{point}_x") for mass, point in moving) / total
    y_cg = sum(mass * value(f"{point}_y") for mass, point in moving) / total
    axles = sorted(
        (value(f"{a}_x"), value(f"{a}_y") - radius_m)
        for a, radius_m in zip(layout.machine.axles, tyre_radius_m, strict=True)
    )
    axles = [axles[0], axles[-1]]
    (rear_x, rear_y), (front_x, front_y) = axles
    reach = (front_x - x_cg, x_cg - rear_x)
    height = (y_cg - front_y, y_cg - rear_y)
    if min(reach) <= 0.0 or min(height) <= 0.0:
        raise ValueError(
            f"the combined centre of gravity ({x_cg:.4g}, {y_cg:.4g}) m must lie between and "
            f"above the tyres' contact points ({rear_x:.4g}, {rear_y:.4g}) and ({front_x:.4g}, "
            f"{front_y:.4g}) m for a pitch bound"
        )
    return math.atan2(reach[0], height[0]), math.atan2(reach[1], height[1])


@functools.cache
def _kinematics_grid(layout: PlantLayout = SKID_STEER) -> tuple[np.ndarray, ca.Function]:
    """The grid of φ over a turn and the cylinder kinematics mapped over it, built once."""
    phi = np.arange(-math.pi, math.pi + _GRID_STEP_RAD / 2, _GRID_STEP_RAD)
    info = layout.machine
    return phi, info.function("cylinder_kinematics").map(phi.size)


def _boom_range(params: np.ndarray, layout: PlantLayout = SKID_STEER) -> tuple[float, float]:
    """φ − φ0 (down, up magnitudes) in rad that the stroke allows, with the end-stop margin,
    within the linkage's dead points (module notes)."""
    mechanical = params[: layout.n_mechanical]
    completed, _ = layout.machine.function("complete_parameters")(mechanical)
    phi, kinematics = _kinematics_grid(layout)
    n = layout.n_coordinates
    # x_cyl depends on φ = θ2 − θ1 only (the lift cylinder between chassis and boom)
    p = np.vstack([np.zeros((3, phi.size)), phi, np.zeros((n - 4, phi.size))])
    length, _, slope, _ = kinematics(p, np.zeros((n, phi.size)), ca.repmat(completed, 1, phi.size))
    piston = np.asarray(length).ravel() - _parameter(params, "L_retracted", layout)
    stroke = _parameter(params, "stroke", layout)
    sign = np.sign(np.asarray(slope).ravel())
    zero = int(np.argmin(np.abs(phi)))
    ranges = []
    for rows in (np.arange(zero, -1, -1), np.arange(zero, phi.size)):
        turned = np.flatnonzero(sign[rows] != sign[zero])  # past the dead point
        branch = rows[: turned[0]] if turned.size else rows
        dead = abs(float(phi[branch[-1]]))
        outside = np.flatnonzero((piston[branch] < 0.0) | (piston[branch] > stroke))
        if not outside.size:
            ranges.append(dead)
            continue
        last = branch[outside[0]]
        if outside[0] == 0:
            ranges.append(min(END_STOP_MARGIN_RAD, dead))
            continue
        inner = branch[outside[0] - 1]
        edge = 0.0 if piston[last] < 0.0 else stroke
        fraction = (edge - piston[inner]) / (piston[last] - piston[inner])
        crossing = abs(float(phi[inner] + fraction * (phi[last] - phi[inner])))
        ranges.append(min(crossing + END_STOP_MARGIN_RAD, dead))
    return ranges[0], ranges[1]


@functools.lru_cache(maxsize=64)
def _bounds_cached(
    key: bytes, tyre_radius_m: tuple[float, ...], layout: PlantLayout
) -> ValidityBounds:
    params = np.frombuffer(key, dtype=float)
    down, up = _stability_angles(params, tyre_radius_m, layout)
    boom_down, boom_up = _boom_range(params, layout)
    return ValidityBounds(down, up, boom_down, boom_up)


def validity_bounds(
    params: np.ndarray,
    *,
    tyre_radius_m: float | Sequence[float] = DEFAULT_TYRE_RADIUS_M,
    layout: PlantLayout = SKID_STEER,
) -> ValidityBounds:
    """The default bounds of the plant ``params`` (module notes), cached per parameter vector.

    Parameters
    ----------
    params : numpy.ndarray
        Plant parameters (:data:`~loader_model.plant.plant_parameters.PLANT_PARAMETER_NAMES`).
    tyre_radius_m : float or sequence of float
        Free tyre radius in m, (0, 2], one for all axles or one per axle (front first): each
        contact point lies this far below its axle.
    layout : PlantLayout
        The machine of ``params`` (default the skid-steer): its bodies' masses and centres of
        gravity, its outermost axles and its lift cylinder's kinematics.

    Returns
    -------
    ValidityBounds
        Pitch from the static stability angles, boom angle from the stroke, the fixed airborne
        time and seat acceleration.

    Raises
    ------
    ValueError
        If the centre of gravity does not lie between and above the contact points.
    """
    size = len(layout.parameter_names)
    vector = np.ascontiguousarray(params, dtype=float).ravel()
    if vector.size != size:
        raise ValueError(f"params must have {size} values; got {vector.size}")
    radii = tyre_radii(tyre_radius_m, layout.machine.axles)
    return _bounds_cached(vector.tobytes(), radii, layout)


def resolve_bounds(
    validity: ValidityBounds | None,
    params: np.ndarray,
    *,
    layout: PlantLayout = SKID_STEER,
    tyre_radius_m: float | Sequence[float] = DEFAULT_TYRE_RADIUS_M,
) -> ValidityBounds:
    """``validity`` checked, or the defaults of ``params`` (of the machine ``layout``, on tyres
    of ``tyre_radius_m``) when None."""
    if validity is None:
        return validity_bounds(params, layout=layout, tyre_radius_m=tyre_radius_m)
    if not isinstance(validity, ValidityBounds):
        raise TypeError(f"validity must be a ValidityBounds or None; got {type(validity).__name__}")
    return validity
