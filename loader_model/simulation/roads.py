"""Road profiles: ground height over travelled distance, and board obstacles.

A :class:`RoadProfile` is a piecewise-linear ground height h(s) [m] over distance s [m] along the
vehicle's path (+x forward). Vertices are given by distance and height; two vertices may share a
distance, which makes a vertical edge (a step), so boards have exactly vertical sides. Beyond the
first and last vertex the ground continues flat at the end heights.

The raw profile is what the ground is; what a tyre feels is its enveloped (effective) profile,
:mod:`loader_model.simulation.envelope`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from loader_model.simulation._checks import as_finite_array, as_number, as_seed

__all__ = ["RoadProfile", "board_course", "flat_road", "single_board"]


@dataclass(frozen=True)
class RoadProfile:
    """Piecewise-linear ground height h(s) over distance s, flat beyond its ends.

    Parameters
    ----------
    distance_m : array_like
        Vertex distances in m, non-decreasing, at least 2. Two equal consecutive distances make a
        vertical edge; three equal distances are refused.
    height_m : array_like
        Ground height at each vertex in m (finite).
    name : str
        Label for plots and reports.

    Notes
    -----
    At a vertical edge, :meth:`height` returns the upper of the two heights (the edge belongs to
    the obstacle), which is what a rigid wheel rests on.
    """

    distance_m: np.ndarray
    height_m: np.ndarray
    name: str = "road"

    def __post_init__(self) -> None:
        distance_m = as_finite_array(self.distance_m, "distance_m", "m")
        height_m = as_finite_array(self.height_m, "height_m", "m")
        if distance_m.size < 2:
            raise ValueError(f"distance_m must have at least 2 vertices; got {distance_m.size}")
        if height_m.shape != distance_m.shape:
            raise ValueError(
                f"height_m must have one value per distance ({distance_m.size}); "
                f"got {height_m.size}"
            )
        step_m = np.diff(distance_m)
        if np.any(step_m < 0.0):
            index = int(np.flatnonzero(step_m < 0.0)[0]) + 1
            raise ValueError(
                f"distance_m must be non-decreasing; got {distance_m[index - 1]:.9g} m then "
                f"{distance_m[index]:.9g} m at index {index}"
            )
        if np.any((step_m[:-1] == 0.0) & (step_m[1:] == 0.0)):
            index = int(np.flatnonzero((step_m[:-1] == 0.0) & (step_m[1:] == 0.0))[0])
            raise ValueError(
                f"distance_m may repeat a value at most twice (one vertical edge); got "
                f"{distance_m[index]:.9g} m three times from index {index}"
            )
        for array in (distance_m, height_m):
            array.setflags(write=False)
        object.__setattr__(self, "distance_m", distance_m)
        object.__setattr__(self, "height_m", height_m)

    @property
    def start_m(self) -> float:
        """Distance of the first vertex in m."""
        return float(self.distance_m[0])

    @property
    def end_m(self) -> float:
        """Distance of the last vertex in m."""
        return float(self.distance_m[-1])

    def height(self, distance_m: object) -> np.ndarray:
        """Raw ground height h(s) in m at ``distance_m`` (upper height at a vertical edge).

        Parameters
        ----------
        distance_m : array_like
            Distances in m (any shape).

        Returns
        -------
        numpy.ndarray
            Heights in m, same shape as ``distance_m``.
        """
        s = np.asarray(distance_m, dtype=float)
        left = _interpolate(s, self.distance_m, self.height_m, "left")
        right = _interpolate(s, self.distance_m, self.height_m, "right")
        return np.maximum(left, right)


def _interpolate(s: np.ndarray, xp: np.ndarray, fp: np.ndarray, side: str) -> np.ndarray:
    """Linear interpolation on the segment found by ``searchsorted(side)``, flat outside."""
    index = np.clip(np.searchsorted(xp, s, side=side), 1, xp.size - 1)  # type: ignore[call-overload]
    x0, x1, f0, f1 = xp[index - 1], xp[index], fp[index - 1], fp[index]
    width = x1 - x0
    with np.errstate(invalid="ignore", divide="ignore"):
        fraction = np.where(width > 0.0, (s - x0) / np.where(width > 0.0, width, 1.0), 1.0)
    value = f0 + np.clip(fraction, 0.0, 1.0) * (f1 - f0)
    value = np.where(s < xp[0], fp[0], value)
    return np.where(s > xp[-1], fp[-1], value)


def flat_road(length_m: float = 10.0, *, height_m: float = 0.0) -> RoadProfile:
    """Flat ground at ``height_m`` from 0 to ``length_m`` (and beyond, by flat extension)."""
    length_m = as_number(length_m, "length_m", "m", minimum=0.0, strict_minimum=True)
    height_m = as_number(height_m, "height_m", "m")
    return RoadProfile(np.array([0.0, length_m]), np.full(2, height_m), name="flat road")


def board_course(
    count: int,
    *,
    height_m: float,
    width_m: float,
    spacing_m: float,
    first_board_m: float = 0.0,
    position_jitter_m: float = 0.0,
    seed: int = 0,
    name: str | None = None,
) -> RoadProfile:
    """Boards with rectangular cross-section on flat ground at height 0.

    Parameters
    ----------
    count : int
        Number of boards, 1 to 1000.
    height_m, width_m : float
        Board height (0, 0.5] m and width along the path (0, 5] m.
    spacing_m : float
        Distance from one board's leading edge to the next one's in m, > ``width_m``
        (ignored for one board).
    first_board_m : float
        Leading edge of the first board in m.
    position_jitter_m : float
        Standard deviation in m of a normal shift of each board (a board laid by hand), drawn from
        ``seed``; 0 for exact spacing. Boards must not overlap after the shift.
    seed : int
        Seed of the jitter (``numpy.random.default_rng``).
    name : str, optional
        Label; default describes the boards.

    Returns
    -------
    RoadProfile
        Vertices at each board's four corners, vertical sides.
    """
    if isinstance(count, bool) or not isinstance(count, int | np.integer) or not 1 <= count <= 1000:
        raise ValueError(f"count must be an integer in [1, 1000] boards; got {count!r}")
    height_m = as_number(height_m, "height_m", "m", minimum=0.0, maximum=0.5, strict_minimum=True)
    width_m = as_number(width_m, "width_m", "m", minimum=0.0, maximum=5.0, strict_minimum=True)
    first_board_m = as_number(first_board_m, "first_board_m", "m")
    jitter_m = as_number(position_jitter_m, "position_jitter_m", "m", minimum=0.0)
    seed = as_seed(seed)
    if count > 1:
        spacing_m = as_number(spacing_m, "spacing_m", "m", minimum=width_m, strict_minimum=True)
    else:
        spacing_m = 0.0
    leading_m = first_board_m + spacing_m * np.arange(count)
    if jitter_m > 0.0:
        leading_m = leading_m + np.random.default_rng(seed).normal(0.0, jitter_m, count)
        gaps_m = np.diff(leading_m) - width_m
        if np.any(gaps_m <= 0.0):
            index = int(np.flatnonzero(gaps_m <= 0.0)[0])
            raise ValueError(
                f"position_jitter_m = {jitter_m:g} m with seed {seed} makes board {index + 1} "
                f"overlap board {index + 2}; use a smaller jitter or another seed"
            )
    trailing_m = leading_m + width_m
    distance_m = np.column_stack([leading_m, leading_m, trailing_m, trailing_m]).ravel()
    height = np.tile([0.0, height_m, height_m, 0.0], count)
    label = name or (
        f"{count} board(s) {height_m * 1e3:g} mm x {width_m * 1e3:g} mm"
        + (f", spacing {spacing_m:g} m" if count > 1 else "")
    )
    return RoadProfile(distance_m, height, name=label)


def single_board(
    *, height_m: float, width_m: float, position_m: float = 0.0, name: str | None = None
) -> RoadProfile:
    """One board of ``height_m`` and ``width_m`` whose leading edge is at ``position_m``."""
    return board_course(
        1, height_m=height_m, width_m=width_m, spacing_m=0.0, first_board_m=position_m, name=name
    )
