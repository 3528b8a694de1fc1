r"""Rigid-wheel enveloping filter: the road a tyre of radius R feels, its height and slope.

A tyre does not follow a sharp edge: its wheel centre rises on an arc before the edge is under the
axle. For a rigid disc of radius R rolling on the ground h(s), the wheel-centre height is the lowest
height at which the disc does not penetrate the ground:

.. math::

    y_c(s) = \max_{|u| \le R} \left[ h(s + u) + \sqrt{R^2 - u^2} \right],
    \qquad h_\mathrm{eff}(s) = y_c(s) - R .

``h_eff`` is the *effective road height* under the axle (flat ground: h_eff = h).

Computation (exact, no grid in u)
---------------------------------
The profile is piecewise linear, and on each segment of slope m the bracket above is concave in u,
so its maximum over the segment is either at an end (a vertex k: the disc rests on a corner,
``h_k + sqrt(R² − (s_k − s)²)``) or at the interior tangent point ``u* = R m / sqrt(1 + m²)``
(the disc rests on the segment: ``h(s) + R sqrt(1 + m²)``). Taking the maximum over the vertices
within R and the segments whose tangent point lies on them gives y_c(s) exactly, to rounding, at
any s; vertical edges (two vertices at one distance) are covered by their corners. The work is
vectorised over the query distances: O(N K) for N queries and K vertices within 2R.

Effective slope and the horizontal road input
---------------------------------------------
By the envelope theorem, dy_c/ds is the derivative of the active term: ``u / sqrt(R² − u²)`` on a
corner at offset u, m on a segment. Geometrically the ground force on a rigid disc acts along the
line from the contact point to the wheel centre, which is normal to the centre path y_c(s); its
horizontal component is therefore

.. math::

    F_x = -F_y \tan\beta, \qquad \tan\beta = \frac{d h_\mathrm{eff}}{ds},

with F_y ≥ 0 the vertical tyre force (a wheel climbing an edge is pushed back). This is the
*effective road plane* of Schmeitz and Pacejka (effective height w and effective slope tan β_y;
Pacejka, Tire and Vehicle Dynamics, 3rd ed. 2012, section 10.2 on enveloping and effective road
inputs) in its rigid-wheel limit, where it is exact. The contact point lies at u = R sin β ahead of
the axle. The third effective input of Pacejka's model (the variation of the effective rolling
radius, which drives longitudinal slip) is left out.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from loader_model.simulation._checks import as_number
from loader_model.simulation.roads import RoadProfile

__all__ = [
    "MAXIMUM_TYRE_RADIUS_M",
    "EffectiveRoad",
    "edge_contact_length",
    "effective_road",
]

#: Largest accepted tyre radius in m.
MAXIMUM_TYRE_RADIUS_M = 2.0
#: Largest number of (query, candidate) pairs held in memory at once.
_CHUNK_PAIRS = 2_000_000


class EffectiveRoad(NamedTuple):
    """Enveloped road under an axle at the query distances."""

    height_m: np.ndarray
    """Effective road height h_eff = y_c − R in m."""
    slope: np.ndarray
    """Effective slope tan β = dh_eff/ds (dimensionless; one-sided at kinks)."""


def edge_contact_length(tyre_radius_m: float, step_height_m: float) -> float:
    """Horizontal distance sqrt(R² − (R − H)²) in m over which a rigid wheel rides on a step edge.

    The wheel touches the edge of a step of height H when its centre is this far before it.
    """
    radius_m = as_number(
        tyre_radius_m,
        "tyre_radius_m",
        "m",
        minimum=0.0,
        maximum=MAXIMUM_TYRE_RADIUS_M,
        strict_minimum=True,
    )
    step_m = as_number(step_height_m, "step_height_m", "m", minimum=0.0, maximum=radius_m)
    return float(np.sqrt(radius_m**2 - (radius_m - step_m) ** 2))


def effective_road(profile: RoadProfile, distance_m: object, tyre_radius_m: float) -> EffectiveRoad:
    """Effective height and slope of ``profile`` under a rigid wheel of radius ``tyre_radius_m``.

    Parameters
    ----------
    profile : RoadProfile
        Raw ground profile.
    distance_m : array_like
        Axle positions s in m (any shape, any order).
    tyre_radius_m : float
        Wheel radius R in m, (0, :data:`MAXIMUM_TYRE_RADIUS_M`].

    Returns
    -------
    EffectiveRoad
        ``height_m`` and ``slope``, each shaped like ``distance_m``. The slope is infinite where
        the wheel touches a wall at its equator (a step at least R tall, which a rigid wheel cannot
        climb).
    """
    if not isinstance(profile, RoadProfile):
        raise ValueError(f"profile must be a RoadProfile; got {type(profile).__name__}")
    radius_m = as_number(
        tyre_radius_m,
        "tyre_radius_m",
        "m",
        minimum=0.0,
        maximum=MAXIMUM_TYRE_RADIUS_M,
        strict_minimum=True,
    )
    s_query = np.asarray(distance_m, dtype=float)
    shape = s_query.shape
    s_flat = s_query.ravel()
    if s_flat.size and not np.all(np.isfinite(s_flat)):
        raise ValueError("distance_m must be finite")
    if s_flat.size == 0:
        return EffectiveRoad(np.empty(shape), np.empty(shape))

    # Flat extension beyond the ends as two far vertices, so every window has its segments.
    margin_m = 2.0 * radius_m + 1.0
    first_m = min(profile.start_m, float(s_flat.min())) - margin_m
    last_m = max(profile.end_m, float(s_flat.max())) + margin_m
    d = np.concatenate([[first_m], profile.distance_m, [last_m]])
    h = np.concatenate([[profile.height_m[0]], profile.height_m, [profile.height_m[-1]]])
    width = np.diff(d)
    sloped = width > 0.0
    m = np.where(sloped, np.diff(h) / np.where(sloped, width, 1.0), 0.0)
    secant = np.sqrt(1.0 + m * m)
    tangent_offset = radius_m * m / secant

    lo = np.searchsorted(d, s_flat - radius_m, side="left")
    hi = np.searchsorted(d, s_flat + radius_m, side="right")
    count = hi - lo
    height = np.empty_like(s_flat)
    slope = np.empty_like(s_flat)
    order = np.argsort(count, kind="stable")  # similar window sizes chunk together
    chunk_queries = max(256, _CHUNK_PAIRS // (int(count.max()) + 2))
    for start in range(0, order.size, chunk_queries):
        chunk = order[start : start + chunk_queries]
        height[chunk], slope[chunk] = _envelope_chunk(
            s_flat[chunk],
            lo[chunk],
            count[chunk],
            d,
            h,
            m,
            secant,
            tangent_offset,
            sloped,
            radius_m,
        )
    return EffectiveRoad((height - radius_m).reshape(shape), slope.reshape(shape))


def _envelope_chunk(
    s: np.ndarray,
    lo: np.ndarray,
    count: np.ndarray,
    d: np.ndarray,
    h: np.ndarray,
    m: np.ndarray,
    secant: np.ndarray,
    tangent_offset: np.ndarray,
    sloped: np.ndarray,
    radius_m: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Wheel-centre height y_c and its slope for one chunk of queries (see module notes)."""
    offsets = np.arange(max(int(count.max()), 1) + 1)  # a corner column even if none is in reach
    column = s[:, None]
    # Corners: vertices lo .. hi-1 (within R of s).
    vertex = np.minimum(lo[:, None] + offsets[:-1], d.size - 1)
    on_vertex = offsets[:-1] < count[:, None]
    u = d[vertex] - column
    root = np.sqrt(np.maximum(radius_m * radius_m - u * u, 0.0))
    vertex_value = np.where(on_vertex, h[vertex] + root, -np.inf)
    # Segments lo-1 .. hi-1, where the disc is tangent to the segment's interior.
    segment = np.clip(lo[:, None] - 1 + offsets, 0, m.size - 1)
    touch = column + tangent_offset[segment]
    on_segment = (
        (offsets <= count[:, None])
        & sloped[segment]
        & (touch >= d[segment])
        & (touch <= d[segment + 1])
    )
    segment_value = np.where(
        on_segment,
        h[segment] + m[segment] * (column - d[segment]) + radius_m * secant[segment],
        -np.inf,
    )
    best_vertex = np.argmax(vertex_value, axis=1)
    best_segment = np.argmax(segment_value, axis=1)
    rows = np.arange(s.size)
    top_vertex = vertex_value[rows, best_vertex]
    top_segment = segment_value[rows, best_segment]
    with np.errstate(divide="ignore"):
        vertex_slope = u[rows, best_vertex] / root[rows, best_vertex]
    use_segment = top_segment >= top_vertex
    centre = np.where(use_segment, top_segment, top_vertex)
    slope = np.where(use_segment, m[segment[rows, best_segment]], vertex_slope)
    return centre, slope
