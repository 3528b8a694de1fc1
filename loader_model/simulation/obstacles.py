"""Courses of the user's own: a list of obstacles on flat ground, in code or in a TOML file.

Format of a course file (lengths in m, as the key names say)::

    name = "my yard"            # optional label

    [[obstacles]]
    position_m = 0.0            # where the obstacle begins, along the path
    height_m = 0.04             # its height (a pit: its depth)
    length_m = 0.14             # its length along the path
    shape = "board"             # optional: "board" (default), "bump" or "pit"

    [[obstacles]]
    position_m = 6.0
    height_m = 0.08
    length_m = 0.6
    shape = "bump"

Shapes (:data:`SHAPES`): a ``board`` is a rectangle with vertical sides, as the boards of the
paper's course (section 5.3); a ``bump`` rises linearly to ``height_m`` at its middle and falls
back (a triangle: a speed bump or a kerb stone crossed square); a ``pit`` is a rectangular hole
``height_m`` deep. Obstacles may be listed in any order but must not touch or overlap. The drive
starts with the front axle :data:`~loader_model.simulation.courses.LEAD_IN_M` before the first
obstacle. Every mistake in a file raises :class:`CourseFileError` (a ValueError) naming the file
and every bad entry, e.g. ``obstacles[2].height_m: -0.04 is not allowed; give a number in
(0, 0.5] m``; entries count from 1, in the file's order.
"""

from __future__ import annotations

import itertools
import math
import tomllib
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from loader_model.simulation._checks import as_number, shown
from loader_model.simulation.courses import LEAD_IN_M, Course, kmh_to_m_s
from loader_model.simulation.roads import RoadProfile

__all__ = [
    "LIMITS",
    "SHAPES",
    "CourseFileError",
    "Obstacle",
    "load_course_file",
    "obstacle_course",
    "obstacle_profile",
]

#: Obstacle shapes (module notes).
SHAPES = ("board", "bump", "pit")
#: Allowed range (low, high, low included) in m of each number of an obstacle.
LIMITS = {
    "position_m": (-1000.0, 10000.0, True),
    "height_m": (0.0, 0.5, False),
    "length_m": (0.0, 20.0, False),
}
_MAX_OBSTACLES = 1000


class CourseFileError(ValueError):
    """A course file that cannot be used; the message names the file and every bad entry."""


def _allowed(key: str) -> str:
    low, high, closed = LIMITS[key]
    return f"{'[' if closed else '('}{low:g}, {high:g}] m"


@dataclass(frozen=True)
class Obstacle:
    """One obstacle on flat ground (module notes).

    Attributes
    ----------
    position_m : float
        Where it begins along the path in m, [-1000, 10000].
    height_m : float
        Its height (a pit: depth) in m, (0, 0.5].
    length_m : float
        Its length along the path in m, (0, 20].
    shape : str
        One of :data:`SHAPES`.
    """

    position_m: float
    height_m: float
    length_m: float
    shape: str = "board"

    def __post_init__(self) -> None:
        for key in LIMITS:
            low, high, closed = LIMITS[key]
            value = as_number(
                getattr(self, key), key, "m", minimum=low, maximum=high, strict_minimum=not closed
            )
            object.__setattr__(self, key, value)
        if self.shape not in SHAPES:
            raise ValueError(f"shape must be one of {SHAPES}; got {shown(self.shape)}")

    @property
    def end_m(self) -> float:
        """Where it ends along the path in m."""
        return self.position_m + self.length_m

    def vertices(self) -> tuple[list[float], list[float]]:
        """Distances and heights in m of its outline (vertical sides as repeated distances)."""
        start, end, h = self.position_m, self.end_m, self.height_m
        if self.shape == "bump":
            return [start, 0.5 * (start + end), end], [0.0, h, 0.0]
        top = -h if self.shape == "pit" else h
        return [start, start, end, end], [0.0, top, top, 0.0]


def _overlaps(obstacles: Sequence[Obstacle]) -> list[str]:
    """Messages for each obstacle that touches or overlaps the one before it along the path."""
    order = sorted(range(len(obstacles)), key=lambda k: obstacles[k].position_m)
    found = []
    for before, after in itertools.pairwise(order):
        if obstacles[after].position_m <= obstacles[before].end_m:
            found.append(
                f"obstacles[{after + 1}].position_m: {obstacles[after].position_m:g} is not "
                f"allowed; obstacles[{before + 1}] lies from {obstacles[before].position_m:g} "
                f"to {obstacles[before].end_m:g} m: give a position past its end (obstacles "
                "must not touch or overlap)"
            )
    return found


def obstacle_profile(obstacles: Sequence[Obstacle], *, name: str = "obstacles") -> RoadProfile:
    """The ground of ``obstacles`` (any order, none touching another) on flat ground at 0.

    Parameters
    ----------
    obstacles : sequence of Obstacle
        1 to 1000 obstacles.
    name : str
        Label of the profile.

    Returns
    -------
    RoadProfile
        The obstacles' outlines in order along the path, flat ground between and beyond.

    Raises
    ------
    ValueError
        For no obstacle, more than 1000, or obstacles that touch or overlap (naming them,
        counted from 1).
    """
    obstacles = list(obstacles)
    if not 1 <= len(obstacles) <= _MAX_OBSTACLES:
        raise ValueError(f"obstacles: give 1 to {_MAX_OBSTACLES} obstacles; got {len(obstacles)}")
    overlaps = _overlaps(obstacles)
    if overlaps:
        raise ValueError("; ".join(overlaps))
    distance: list[float] = []
    height: list[float] = []
    for obstacle in sorted(obstacles, key=lambda o: o.position_m):
        d, h = obstacle.vertices()
        distance += d
        height += h
    return RoadProfile(np.array(distance), np.array(height), name=name)


def obstacle_course(
    obstacles: Sequence[Obstacle],
    speed_kmh: float,
    *,
    settle_s: float = 3.0,
    name: str = "obstacles",
) -> Course:
    """``obstacles`` driven at constant speed, the front axle starting :data:`LEAD_IN_M` before
    the first.

    Parameters
    ----------
    obstacles : sequence of Obstacle
        1 to 1000 obstacles, none touching another (:func:`obstacle_profile`).
    speed_kmh : float
        Driven speed in km/h, (0, 100].
    settle_s : float
        Seconds driven after the rear axle has passed the last obstacle, [0, 60].
    name : str
        Label; the course's is ``"{name} at {speed_kmh} km/h"``.

    Returns
    -------
    Course
        The drive.

    Raises
    ------
    ValueError
        Naming the argument or the obstacles and what is allowed.
    """
    profile = obstacle_profile(obstacles, name=name)
    speed_m_s = kmh_to_m_s(
        as_number(speed_kmh, "speed_kmh", "km/h", minimum=0.0, maximum=100.0, strict_minimum=True)
    )
    settle_s = as_number(settle_s, "settle_s", "s", minimum=0.0, maximum=60.0)
    label = f"{name} at {as_number(speed_kmh, 'speed_kmh', 'km/h'):g} km/h"
    return Course(profile, speed_m_s, profile.start_m - LEAD_IN_M, settle_s, label)


def _entry(index: int, entry: object, problems: list[str]) -> Obstacle | None:
    """The obstacle of file entry ``index`` (from 1), or None with its problems appended."""
    where = f"obstacles[{index}]"
    if not isinstance(entry, dict):
        problems.append(f"{where}: {shown(entry)} is not allowed; give a table [[obstacles]]")
        return None
    allowed = (*LIMITS, "shape")
    found = len(problems)
    for key in sorted(set(entry) - set(allowed)):
        problems.append(f"{where}.{key}: unknown key; allowed: {', '.join(allowed)}")
    values: dict[str, object] = {}
    for key in LIMITS:
        if key not in entry:
            problems.append(f"{where}.{key}: missing; give a number in {_allowed(key)}")
            continue
        value, (low, high, closed) = entry[key], LIMITS[key]
        number = value if isinstance(value, int | float) and not isinstance(value, bool) else None
        if (
            number is None
            or not math.isfinite(number)
            or not (low <= number if closed else low < number)
            or number > high
        ):
            problems.append(
                f"{where}.{key}: {shown(value)} is not allowed; give a number in {_allowed(key)}"
            )
        values[key] = value
    shape = entry.get("shape", "board")
    if shape not in SHAPES:
        problems.append(
            f"{where}.shape: {shown(shape)} is not allowed; give one of {', '.join(SHAPES)}"
        )
    if len(problems) > found:
        return None
    return Obstacle(shape=shape, **values)  # type: ignore[arg-type]


def load_course_file(path: str | Path, speed_kmh: float, *, settle_s: float = 3.0) -> Course:
    """The course of the TOML file ``path`` (module notes) driven at ``speed_kmh``.

    Parameters
    ----------
    path : str or pathlib.Path
        Course file.
    speed_kmh : float
        Driven speed in km/h, (0, 100].
    settle_s : float
        Seconds driven after the rear axle has passed the last obstacle, [0, 60].

    Returns
    -------
    Course
        Labelled with the file's ``name`` (default: the file's name).

    Raises
    ------
    CourseFileError
        Naming the file and every bad entry: unreadable or not TOML, unknown keys, no obstacle,
        a number missing or outside its range, an unknown shape, obstacles that touch.
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise CourseFileError(f"course file {path}: {exc}") from None
    problems = [
        f"{key}: unknown key; allowed: name, [[obstacles]]"
        for key in sorted(set(data) - {"name", "obstacles"})
    ]
    name = data.get("name", path.stem)
    if not isinstance(name, str) or not name.strip():
        problems.append(f"name: {shown(name)} is not allowed; give a non-empty string")
    entries = data.get("obstacles")
    if not isinstance(entries, list) or not 1 <= len(entries) <= _MAX_OBSTACLES:
        got = "none" if entries is None else shown(entries)[:60]
        problems.append(f"obstacles: give 1 to {_MAX_OBSTACLES} [[obstacles]] tables; got {got}")
        entries = []
    obstacles = [_entry(k, entry, problems) for k, entry in enumerate(entries, start=1)]
    if not problems:
        problems += _overlaps(obstacles)  # type: ignore[arg-type]
    if problems:
        raise CourseFileError(f"course file {path}: " + "; ".join(problems))
    return obstacle_course(obstacles, speed_kmh, settle_s=settle_s, name=str(name))  # type: ignore[arg-type]
