r"""Road input of the plant for a drive at constant speed: w(t) and ẇ(t) per axle on a time table.

The vehicle drives in +x at speed v. The front axle A is at distance s_A(t) = s_0 + v t along the
profile, axle i a distance d_i behind it (``axle_offsets_m``; d_A = 0; for two axles the rear axle
B a wheelbase L behind it, s_B(t) = s_A(t) − L), so axle i sees the front axle's road delayed by
d_i / v. Any number of axles, front first, in the order of the machine's ``axles`` (the
generated plant's road inputs (w_ix, w_iy) per axle in that order). Each tyre envelops the
ground either as a rigid disc of its axle's radius R_i
(:mod:`~loader_model.simulation.envelope`, ``cams=None``) or as a tandem elliptical cam per axle
(:mod:`~loader_model.simulation.tandem_cam`, whose spacing follows that axle's static deflection);
axles of different radii or cam shapes are enveloped one by one, each by its own tyre.

The plant's road input (``derive/symbols.py``) is the displacement of each tyre's contact point,
w = (w_Ax, w_Ay, w_Bx, w_By) in m, and its rate ẇ in m/s:

.. math::

    w_{iy}(t) = h_\mathrm{eff}(s_i(t)), \qquad \dot w_{iy} = v\, dh_\mathrm{eff}/ds,
    \qquad w_{ix}(t) = -c_i \tan\beta_i, \qquad c_i = F_{iy0} / k_{ix},
    \qquad \dot w_{ix} = 0 .

The horizontal input follows the effective road plane: the ground force is normal to the wheel-
centre path, F_x = −F_y tan β (envelope module notes). The generated plant has a horizontal tyre
spring F_x = −k_x (x_i − w_ix), so the displacement w_ix = −(F_iy0 / k_ix) tan β applies that force
to first order (the static load F_iy0 in place of the momentary F_iy; the neglected term
(F_iy − F_iy0) tan β is second order). With ``slope_to_x_m = (0, 0)`` (the default) w_x = 0 and a
simulator that wants the exact law adds −F_iy tan β_i itself from :attr:`RoadInput.slope`. Loss of
contact is the plant's business: its contact law drops both tyre forces when F_y would pull.

For the rigid disc dh_eff/ds = tan β; for the tandem cam tan β is the slope of the plane through
the two cams and dh_eff/ds the mean of their slopes (:attr:`RoadInput.slope` holds tan β).

Which input the simulator should use: w_y = h_eff (never the raw profile), and for the horizontal
direction the effective slope. With the generated plant as it is, pass c_i = F_iy0 / k_ix (6.9 mm
front and 10.3 mm rear for the default loader) so that w_x carries the effective-plane force to first
order; a simulator that adds −F_iy tan β_i as a force keeps c = 0. The kinematic x-shift of the
contact point (R sin β, up to 0.18 m on a 4 cm board) is not a displacement input of the tyre's
x spring: through k_x it would give forces of hundreds of kN.

Table and interpolation: samples on a uniform time grid at ``sample_rate_hz``, exact at the nodes
(the envelope is computed at each node's axle position), linear in between. ẇ_y is the exact
v dh_eff/ds at the nodes. ẇ_x is 0: w_x is the static-load equivalent of the road-plane force, not a motion of
the ground, and its rate would add a spurious damper force c_x ẇ_x (an impulse at each first contact,
where tan β jumps).
Between nodes the error is largest where the slope jumps (first contact with an edge, jump Δ): at
most v Δ / (4 f_s). Measured on the paper's course with R = 0.42 m (Δ = 0.47) at 1 kHz: 0.26 mm at
9 and 18 km/h (bound 0.29 mm at 9 km/h), 0.52 mm at 17 km/h; at 5 kHz 0.027 mm at 18 km/h.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from loader_model.simulation._checks import as_number
from loader_model.simulation.effective_road import effective_heights, effective_table
from loader_model.simulation.envelope import MAXIMUM_TYRE_RADIUS_M
from loader_model.simulation.roads import RoadProfile
from loader_model.simulation.tandem_cam import TandemCam

__all__ = [
    "DEFAULT_SAMPLE_RATE_HZ",
    "DEFAULT_TYRE_RADIUS_M",
    "ROAD_NAMES",
    "RoadInput",
    "road_input",
    "tyre_radii",
]

#: Free radius of a 12-16.5 skid-steer tyre (overall diameter about 0.84 m) in m.
DEFAULT_TYRE_RADIUS_M = 0.42
#: Default table rate in Hz (the controllers' 1 kHz).
DEFAULT_SAMPLE_RATE_HZ = 1000.0
#: Order of the columns of :attr:`RoadInput.road_m` (the generated plant's ``road`` input).
ROAD_NAMES = ("w_Ax", "w_Ay", "w_Bx", "w_By")


@dataclass(frozen=True)
class RoadInput:
    """Road input of the plant per axle, sampled on a uniform time grid (see module notes).

    Attributes
    ----------
    time_s : numpy.ndarray
        (N,) sample times from 0 in s, interval 1 / ``sample_rate_hz``.
    road_m : numpy.ndarray
        (N, 2n) displacement w = (w_Ax, w_Ay, w_Bx, w_By, ...) in m, per axle (x, y), front first
        (:data:`ROAD_NAMES` for two axles).
    road_rate_m_s : numpy.ndarray
        (N, 2n) its rate ẇ in m/s (ẇ_x = 0, module notes).
    slope : numpy.ndarray
        (N, n) effective slope tan β under each axle.
    profile : RoadProfile
        The raw profile.
    speed_m_s, wheelbase_m, start_m, sample_rate_hz : float
        The drive: speed, distance from the front to the rearmost axle, front-axle distance at
        t = 0, table rate.
    tyre_radius_m : float or tuple of float
        Free tyre radius R in m: one for every axle, or one per axle (front first).
    slope_to_x_m : tuple of float
        c_i in w_ix = −c_i tan β_i, per axle.
    cams : tuple of TandemCam or None
        The tandem cam of each axle, or None for the rigid disc of each axle's radius.
    axle_offsets_m : tuple of float
        d_i, the distance of each axle behind the front axle in m (first 0; default (0, L)).
    axle_names : tuple of str
        The axles' names, front first (default ("A", "B")), for messages and columns.
    """

    time_s: np.ndarray
    road_m: np.ndarray
    road_rate_m_s: np.ndarray
    slope: np.ndarray
    profile: RoadProfile
    speed_m_s: float
    wheelbase_m: float
    start_m: float
    tyre_radius_m: float | tuple[float, ...]
    sample_rate_hz: float
    slope_to_x_m: tuple[float, ...]
    cams: tuple[TandemCam, ...] | None = None
    axle_offsets_m: tuple[float, ...] = ()
    axle_names: tuple[str, ...] = ("A", "B")

    def __post_init__(self) -> None:
        if not self.axle_offsets_m:
            object.__setattr__(self, "axle_offsets_m", (0.0, self.wheelbase_m))

    @property
    def envelope(self) -> str:
        """``"rigid"`` or ``"tandem-cam"``."""
        return "rigid" if self.cams is None else "tandem-cam"

    @property
    def tyre_radii_m(self) -> tuple[float, ...]:
        """The free tyre radius R_i of each axle in m, front first."""
        if isinstance(self.tyre_radius_m, tuple):
            return self.tyre_radius_m
        return (self.tyre_radius_m,) * self.n_axles

    @property
    def duration_s(self) -> float:
        """Time of the last sample in s."""
        return float(self.time_s[-1])

    @property
    def n_axles(self) -> int:
        """Number of axles n."""
        return len(self.axle_offsets_m)

    def axle_distance(self, time_s: object) -> np.ndarray:
        """Distances (s_A, s_B, ...) in m of the axles at ``time_s``; shape (..., n)."""
        t = np.asarray(time_s, dtype=float)[..., None]
        return self.start_m + self.speed_m_s * t - np.array(self.axle_offsets_m)

    def road(self, time_s: object) -> np.ndarray:
        """w at ``time_s`` by linear interpolation of the table; shape (..., 2n), held past the
        end."""
        return self._interpolate(self.road_m, time_s)

    def road_rate(self, time_s: object) -> np.ndarray:
        """ẇ at ``time_s`` by linear interpolation of the table; shape (..., 2n)."""
        return self._interpolate(self.road_rate_m_s, time_s)

    def exact_road(self, time_s: object) -> np.ndarray:
        """w at ``time_s`` from the envelope itself, no table (slow; for checks); shape (..., 2n)."""
        distance = self.axle_distance(time_s)
        height_m, slope, _ = effective_heights(
            self.profile, distance, self.tyre_radius_m, self.cams
        )
        horizontal_m = -np.asarray(self.slope_to_x_m) * slope
        return _interleave(horizontal_m, height_m)

    def _interpolate(self, table: np.ndarray, time_s: object) -> np.ndarray:
        if isinstance(time_s, float | int):  # fast path for a simulator's scalar calls
            position = max(float(time_s) * self.sample_rate_hz, 0.0)
            index = min(int(position), self.time_s.size - 2)
            fraction = min(position - index, 1.0)
            row = table[index]
            return row + fraction * (table[index + 1] - row)
        position = np.clip(np.asarray(time_s, dtype=float) * self.sample_rate_hz, 0.0, None)
        index = np.minimum(position.astype(np.int64), self.time_s.size - 2)
        fraction = np.minimum(position - index, 1.0)[..., None]
        return table[index] + fraction * (table[index + 1] - table[index])


def _interleave(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """(..., n) x and y parts -> (..., 2n) columns (x_0, y_0, x_1, y_1, ...)."""
    return np.stack([x, y], axis=-1).reshape(*x.shape[:-1], 2 * x.shape[-1])


def _axles(
    wheelbase_m: float | None,
    axle_offsets_m: Sequence[float] | None,
    axle_names: Sequence[str] | None,
) -> tuple[tuple[float, ...], tuple[str, ...]]:
    """The checked axle offsets d_i (first 0, non-decreasing, ≤ 10 m) and names."""
    if (wheelbase_m is None) == (axle_offsets_m is None):
        raise ValueError(
            "give either wheelbase_m (two axles) or axle_offsets_m (each axle's distance behind "
            f"the front axle); got wheelbase_m={wheelbase_m!r}, axle_offsets_m={axle_offsets_m!r}"
        )
    if axle_offsets_m is None:
        offsets = (0.0, as_number(wheelbase_m, "wheelbase_m", "m", minimum=0.0, maximum=10.0))
    else:
        offsets = tuple(
            as_number(d, f"axle_offsets_m[{i}]", "m", minimum=0.0, maximum=10.0)
            for i, d in enumerate(axle_offsets_m)
        )
        if len(offsets) < 2 or offsets[0] != 0.0 or any(np.diff(offsets) < 0.0):
            raise ValueError(
                "axle_offsets_m must give two or more distances behind the front axle in m, "
                f"the first 0, front to rear (non-decreasing); got {axle_offsets_m!r}"
            )
    names = tuple(axle_names) if axle_names is not None else None
    if names is None:
        names = ("A", "B") if len(offsets) == 2 else tuple(f"axle {i}" for i in range(len(offsets)))
    if len(names) != len(offsets):
        raise ValueError(
            f"axle_names must name the {len(offsets)} axles of axle_offsets_m; got {axle_names!r}"
        )
    return offsets, names


def road_input(
    profile: RoadProfile,
    *,
    speed_m_s: float,
    wheelbase_m: float | None = None,
    duration_s: float,
    start_m: float = 0.0,
    tyre_radius_m: float | Sequence[float] = DEFAULT_TYRE_RADIUS_M,
    sample_rate_hz: float = DEFAULT_SAMPLE_RATE_HZ,
    slope_to_x_m: Sequence[float] | None = None,
    cams: Sequence[TandemCam] | None = None,
    axle_offsets_m: Sequence[float] | None = None,
    axle_names: Sequence[str] | None = None,
) -> RoadInput:
    """Tabulate the road input w(t), ẇ(t) of a drive over ``profile`` at constant speed.

    Parameters
    ----------
    profile : RoadProfile
        Raw ground profile.
    speed_m_s : float
        Forward speed v in m/s, (0, 30].
    wheelbase_m : float, optional
        Two axles: distance L from the rear axle B to the front axle A in m, [0, 10].
    duration_s : float
        Length of the drive in s, (0, 3600]; the table ends at the last sample not after it.
    start_m : float
        Distance of the front axle A at t = 0 in m.
    tyre_radius_m : float or sequence of float
        Free tyre radius R in m, (0, 2]: one for every axle or one per axle, front first (the
        rigid disc's radius, and the distance the rearmost axle runs past the last vertex).
    sample_rate_hz : float
        Table rate in Hz, [10, 1e6].
    slope_to_x_m : sequence of float, optional
        c_i in m in w_ix = −c_i tan β_i, one per axle: the static vertical tyre load over the
        longitudinal tyre stiffness, F_iy0 / k_ix; default zeros (w_x = 0).
    cams : sequence of TandemCam, optional
        One tandem elliptical cam per axle (:meth:`~loader_model.simulation.tandem_cam.
        TandemCam.from_deflection`); default: rigid discs of radius ``tyre_radius_m``. Cams of
        different shapes (a_e, b_e, c_e) envelop their axles one by one.
    axle_offsets_m : sequence of float, optional
        Any number of axles (instead of ``wheelbase_m``): each axle's distance behind the front
        axle in m, front first, the first 0, each in [0, 10].
    axle_names : sequence of str, optional
        The axles' names for messages (default ``("A", "B")`` for two axles).

    Returns
    -------
    RoadInput
        The table and its interpolating evaluators.
    """
    speed_m_s = as_number(
        speed_m_s, "speed_m_s", "m/s", minimum=0.0, maximum=30.0, strict_minimum=True
    )
    offsets, names = _axles(wheelbase_m, axle_offsets_m, axle_names)
    n = len(offsets)
    radii_m = tyre_radii(tyre_radius_m, names)
    duration_s = as_number(
        duration_s, "duration_s", "s", minimum=0.0, maximum=3600.0, strict_minimum=True
    )
    start_m = as_number(start_m, "start_m", "m")
    rate_hz = as_number(sample_rate_hz, "sample_rate_hz", "Hz", minimum=10.0, maximum=1e6)
    gains = (0.0,) * n if slope_to_x_m is None else tuple(slope_to_x_m)
    if len(gains) != n:
        wanted = ", ".join(f"c_{name}" for name in names) if n == 2 else f"{n} values c_i"
        raise ValueError(f"slope_to_x_m must give ({wanted}) in m; got {slope_to_x_m!r}")
    gains_m = tuple(
        as_number(c, f"slope_to_x_m[{i}]", "m", minimum=0.0, maximum=1.0)
        for i, c in enumerate(gains)
    )
    if cams is not None:
        cams = tuple(cams)
        if len(cams) != n or not all(isinstance(cam, TandemCam) for cam in cams):
            raise ValueError(
                f"cams must be {'two' if n == 2 else n} TandemCam (axles {', '.join(names)}) "
                f"or None; got {cams!r}"
            )
    count = int(np.floor(duration_s * rate_hz + 1e-9)) + 1
    if count < 2 or count > 50_000_000:
        raise ValueError(
            f"duration_s * sample_rate_hz must give 2 to 5e7 samples; got {count} "
            f"({duration_s:g} s at {rate_hz:g} Hz)"
        )
    time_s = np.arange(count) / rate_hz
    height_m, slope, height_rate = effective_table(
        profile, time_s, start_m, speed_m_s, offsets, radii_m, cams, names
    )
    road_m = _interleave(-np.asarray(gains_m) * slope, height_m)
    rate_m_s = _interleave(np.zeros((count, n)), speed_m_s * height_rate)
    for array in (time_s, road_m, rate_m_s):
        array.setflags(write=False)
    return RoadInput(
        time_s=time_s,
        road_m=road_m,
        road_rate_m_s=rate_m_s,
        slope=slope,
        profile=profile,
        speed_m_s=speed_m_s,
        wheelbase_m=offsets[-1],
        start_m=start_m,
        tyre_radius_m=radii_m[0] if len(set(radii_m)) == 1 else radii_m,
        sample_rate_hz=rate_hz,
        slope_to_x_m=gains_m,
        cams=cams,
        axle_offsets_m=offsets,
        axle_names=names,
    )


def tyre_radii(tyre_radius_m: object, names: Sequence[str]) -> tuple[float, ...]:
    """The checked free radius R_i in m of each axle ``names`` (one number: every axle).

    Raises
    ------
    ValueError
        Naming ``tyre_radius_m`` (and the axle) for a radius that is not a finite number in
        (0, 2] m, or for a sequence that does not give one radius per axle.
    """
    limits = {"minimum": 0.0, "maximum": MAXIMUM_TYRE_RADIUS_M, "strict_minimum": True}
    if isinstance(tyre_radius_m, str) or not isinstance(tyre_radius_m, Sequence | np.ndarray):
        return (as_number(tyre_radius_m, "tyre_radius_m", "m", **limits),) * len(names)
    radii = tuple(tyre_radius_m)
    if len(radii) != len(names):
        raise ValueError(
            f"tyre_radius_m must give one radius in m per axle ({', '.join(names)}) or one for "
            f"all; got {tyre_radius_m!r}"
        )
    return tuple(
        as_number(r, f"tyre_radius_m[{i}] (axle {name})", "m", **limits)
        for i, (r, name) in enumerate(zip(radii, names, strict=True))
    )
