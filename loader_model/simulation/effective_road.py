"""The effective road under each axle of a drive, computed once per profile, grid and tyres.

Each axle's tyre envelops the raw profile either as a rigid disc of its free radius
(:mod:`~loader_model.simulation.envelope`) or as a tandem elliptical cam
(:mod:`~loader_model.simulation.tandem_cam`); :mod:`~loader_model.simulation.travel` tabulates
the result as the plant's road input. A process keeps the most recent tables, read-only, for the
next drive of the same profile on the same time grid with the same tyres: the same numbers,
computed once.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict

import numpy as np

from loader_model.simulation.envelope import effective_road
from loader_model.simulation.roads import RoadProfile
from loader_model.simulation.tandem_cam import TandemCam, tandem_cam_axles

__all__ = ["EFFECTIVE_ROADS_KEPT", "effective_heights", "effective_table"]

#: Effective roads a process keeps (:func:`effective_table`, least recently used out): the
#: design check drives each condition with three controllers over one road, the design on the
#: machine and the course refinement drive the same roads with every candidate's gains, and a
#: tandem cam over an ISO 8608 road costs about 0.1 s.
EFFECTIVE_ROADS_KEPT = 8
_EFFECTIVE_ROADS: OrderedDict[tuple, tuple[np.ndarray, np.ndarray, np.ndarray]] = OrderedDict()


def effective_table(
    profile: RoadProfile,
    time_s: np.ndarray,
    start_m: float,
    speed_m_s: float,
    offsets: tuple[float, ...],
    radii_m: tuple[float, ...],
    cams: tuple[TandemCam, ...] | None,
    names: tuple[str, ...],
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`effective_heights` at the axles' distances s_i(t) = s_0 + v t − d_i, read-only, kept for
    the next drive of the same profile, grid and tyres (:data:`EFFECTIVE_ROADS_KEPT`): the
    same numbers, computed once.

    Raises
    ------
    ValueError
        Where a tyre meets a wall at its equator (a step at least one radius tall).
    """
    digest = hashlib.sha256(profile.distance_m.tobytes() + profile.height_m.tobytes()).digest()
    key = (digest, time_s.size, float(time_s[1]), start_m, speed_m_s, offsets, radii_m, cams)
    kept = _EFFECTIVE_ROADS.get(key)
    if kept is not None:
        _EFFECTIVE_ROADS.move_to_end(key)
        return kept
    distance_m = start_m + speed_m_s * time_s[:, None] - np.array(offsets)
    height_m, slope, height_rate = effective_heights(profile, distance_m, radii_m, cams)
    if not np.all(np.isfinite(slope)):
        row, axle = np.argwhere(~np.isfinite(slope))[0]
        wheel = f"rigid wheel of radius {radii_m[axle]:g} m" if cams is None else "tandem cam"
        raise ValueError(
            f"the {wheel} meets a wall at its equator at "
            f"{distance_m[row, axle]:.6g} m (axle {names[axle]}): the profile has a step at "
            "least one radius tall"
        )
    kept = (height_m, slope, height_rate)
    for array in kept:
        array.setflags(write=False)
    _EFFECTIVE_ROADS[key] = kept
    while len(_EFFECTIVE_ROADS) > EFFECTIVE_ROADS_KEPT:
        _EFFECTIVE_ROADS.popitem(last=False)
    return kept


def effective_heights(
    profile: RoadProfile,
    distance_m: np.ndarray,
    tyre_radius_m: float | tuple[float, ...],
    cams: tuple[TandemCam, ...] | None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Effective height, slope tan β and dh_eff/ds at axle distances (..., n): in one pass when
    every axle has the same tyre, else axle by axle."""
    radii = tyre_radius_m if isinstance(tyre_radius_m, tuple) else (tyre_radius_m,)
    if cams is None:
        if len(set(radii)) == 1:
            height_m, slope = effective_road(profile, distance_m, radii[0])
            return height_m, slope, slope
        roads = [effective_road(profile, distance_m[..., i], r) for i, r in enumerate(radii)]
        height_m = np.stack([road.height_m for road in roads], axis=-1)
        slope = np.stack([road.slope for road in roads], axis=-1)
        return height_m, slope, slope
    if len({(c.half_length_m, c.half_height_m, c.exponent) for c in cams}) == 1:
        road = tandem_cam_axles(profile, distance_m, cams)
        return road.height_m, road.slope, road.height_rate
    each = [tandem_cam_axles(profile, distance_m[..., i : i + 1], (c,)) for i, c in enumerate(cams)]
    return tuple(np.concatenate(field, axis=-1) for field in zip(*each, strict=True))  # type: ignore[return-value]
