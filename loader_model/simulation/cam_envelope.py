r"""One rigid super-elliptical cam on a piecewise-linear profile: its height and slope, exact.

The cam of :mod:`~loader_model.simulation.tandem_cam` (half-length a_e, half-height b_e, exponent
c_e, contour g(u) = (1 − |u/a_e|^c_e)^(1/c_e)) rests at the lowest height where it does not
penetrate the ground; its bottom point is

.. math::

    z(x) = \max_{|u| \le a_e} \left[h(x + u) + b_e\, g(u)\right] - b_e .

Computation (exact, no grid in u): g is concave for c_e ≥ 1, so on each linear segment of slope
m the bracket is concave in u; its maximum is at a vertex, or at the tangent point u* where
m = −b_e g'(u*): with q = |m| a_e / b_e and r = q^{c_e/(c_e − 1)}, |u*| = a_e (r / (1 + r))^{1/c_e}
and g(u*) = (1 + r)^{−1/c_e}. The slope dz/dx is the active term's (envelope theorem).
Queries with no vertex within a_e rest on the one segment under them (closed form); the others
are vectorised over (query, vertex) pairs in chunks, O(N K) for N queries and K vertices in reach,
as :mod:`~loader_model.simulation.envelope` does for the rigid disc (c_e = 2, a_e = b_e = R).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from loader_model.simulation.roads import RoadProfile

if TYPE_CHECKING:
    from loader_model.simulation.tandem_cam import TandemCam

__all__ = ["cam_height"]

#: Largest number of (query, candidate) pairs held in memory at once.
_CHUNK_PAIRS = 2_000_000


def cam_height(
    profile: RoadProfile, distance_m: object, cam: TandemCam
) -> tuple[np.ndarray, np.ndarray]:
    """Bottom height of one cam and its slope (module notes: z(x) and dz/dx, exact).

    Parameters
    ----------
    profile : RoadProfile
        Raw ground profile.
    distance_m : array_like
        Cam centres x in m (any shape).
    cam : TandemCam
        Its shape a_e, b_e, c_e (the spacing is not used).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        z(x) in m and dz/dx, shaped like ``distance_m``; the slope is infinite where the cam
        touches a corner at its end (a step at least b_e tall).
    """
    if not isinstance(profile, RoadProfile):
        raise ValueError(f"profile must be a RoadProfile; got {type(profile).__name__}")
    x_query = np.asarray(distance_m, dtype=float)
    shape, x_flat = x_query.shape, x_query.ravel()
    if x_flat.size and not np.all(np.isfinite(x_flat)):
        raise ValueError("distance_m must be finite")
    if x_flat.size == 0:
        return np.empty(shape), np.empty(shape)
    a_e, b_e, c_e = cam.half_length_m, cam.half_height_m, cam.exponent
    margin_m = 2.0 * a_e + 1.0  # flat extension beyond the ends as two far vertices
    first_m = min(profile.start_m, float(x_flat.min())) - margin_m
    last_m = max(profile.end_m, float(x_flat.max())) + margin_m
    d = np.concatenate([[first_m], profile.distance_m, [last_m]])
    h = np.concatenate([[profile.height_m[0]], profile.height_m, [profile.height_m[-1]]])
    width = np.diff(d)
    sloped = width > 0.0
    m = np.where(sloped, np.diff(h) / np.where(sloped, width, 1.0), 0.0)
    with np.errstate(over="ignore"):
        r = (np.abs(m) * a_e / b_e) ** (c_e / (c_e - 1.0))
        tangent_offset = np.sign(m) * a_e * (r / (1.0 + r)) ** (1.0 / c_e)
        lift = m * tangent_offset + b_e * (1.0 + r) ** (-1.0 / c_e)
    lo = np.searchsorted(d, x_flat - a_e, side="left")
    hi = np.searchsorted(d, x_flat + a_e, side="right")
    count = hi - lo
    # No vertex within reach: the cam rests on the one segment under it (tangent point inside).
    clear = count == 0
    segment = lo[clear] - 1
    height = np.empty_like(x_flat)
    slope = np.empty_like(x_flat)
    height[clear] = h[segment] + m[segment] * (x_flat[clear] - d[segment]) + lift[segment]
    slope[clear] = m[segment]
    order = np.flatnonzero(~clear)
    if order.size == 0:
        return (height - b_e).reshape(shape), slope.reshape(shape)
    order = order[np.argsort(count[order], kind="stable")]
    chunk_queries = max(256, _CHUNK_PAIRS // (int(count.max()) + 2))
    for start in range(0, order.size, chunk_queries):
        chunk = order[start : start + chunk_queries]
        height[chunk], slope[chunk] = _cam_chunk(
            x_flat[chunk], lo[chunk], count[chunk], d, h, m, lift, tangent_offset, sloped, cam
        )
    return (height - b_e).reshape(shape), slope.reshape(shape)


def _cam_chunk(
    x: np.ndarray,
    lo: np.ndarray,
    count: np.ndarray,
    d: np.ndarray,
    h: np.ndarray,
    m: np.ndarray,
    lift: np.ndarray,
    tangent_offset: np.ndarray,
    sloped: np.ndarray,
    cam: TandemCam,
) -> tuple[np.ndarray, np.ndarray]:
    """Cam-centre height z + b_e and its slope for one chunk of queries (module notes)."""
    a_e, b_e, c_e = cam.half_length_m, cam.half_height_m, cam.exponent
    offsets = np.arange(max(int(count.max()), 1) + 1)
    column = x[:, None]
    # Corners: vertices within a_e of x.
    vertex = np.minimum(lo[:, None] + offsets[:-1], d.size - 1)
    on_vertex = offsets[:-1] < count[:, None]
    u = d[vertex] - column
    t = np.minimum(np.abs(u) / a_e, 1.0)
    t_c = t**c_e
    rest = np.maximum(1.0 - t_c, 0.0)
    vertex_value = np.where(on_vertex, h[vertex] + b_e * rest ** (1.0 / c_e), -np.inf)
    # Segments where the cam is tangent to the segment's interior.
    segment = np.clip(lo[:, None] - 1 + offsets, 0, m.size - 1)
    touch = column + tangent_offset[segment]
    on_segment = (
        (offsets <= count[:, None])
        & sloped[segment]
        & (touch >= d[segment])
        & (touch <= d[segment + 1])
    )
    segment_value = np.where(
        on_segment, h[segment] + m[segment] * (column - d[segment]) + lift[segment], -np.inf
    )
    rows = np.arange(x.size)
    best_vertex = np.argmax(vertex_value, axis=1)
    best_segment = np.argmax(segment_value, axis=1)
    top_vertex = vertex_value[rows, best_vertex]
    top_segment = segment_value[rows, best_segment]
    tv, uv = t[rows, best_vertex], u[rows, best_vertex]
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex_slope = (
            (b_e / a_e) * np.sign(uv) * tv ** (c_e - 1.0) * (1.0 - tv**c_e) ** (1.0 / c_e - 1.0)
        )
    vertex_slope = np.where(uv == 0.0, 0.0, vertex_slope)
    use_segment = top_segment >= top_vertex
    centre = np.where(use_segment, top_segment, top_vertex)
    slope = np.where(use_segment, m[segment[rows, best_segment]], vertex_slope)
    return centre, slope
