"""The operating envelope a ride-control design is checked over, and the check's criteria.

The default envelope (:data:`DEFAULT_ENVELOPE`): both bucket loads; the paper's board course
(section 5.3: five 40 mm boards) at 5, 9, 13.5 and 18 km/h, the boards spaced by the paper's rule
extended to any speed (:func:`~loader_model.simulation.courses.board_spacing_m`: 6 m at 9 km/h,
9 m at 18 km/h, linear in the speed); ISO 8608 roads of classes B, C and D at 5, 15 and
30 km/h, :attr:`Envelope.road_seconds` of road each; after every road a settle window of
:attr:`Envelope.settle_s` on flat ground. Courses of the user's own (course files of
:mod:`loader_model.simulation.obstacles`) may be added with :attr:`Envelope.courses`, driven at
:attr:`Envelope.course_speeds_kmh`; the default envelope has none. The criteria a condition
must meet sit beside it (:class:`Envelope`). A TOML file overrides any of them (:func:`load_envelope`)::

    [envelope]
    loads = ["empty", "full"]
    board_speeds_kmh = [5.0, 9.0, 13.5, 18.0]
    road_classes = ["B", "C", "D"]
    road_speeds_kmh = [5.0, 15.0, 30.0]
    courses = []                 # course files, e.g. ["my_yard.toml"], relative to this file
    course_speeds_kmh = [5.0, 9.0, 13.5, 18.0]
    road_seconds = 8.0
    settle_s = 3.0
    seeds = [0]

    [criteria]
    worse_than_baseline = 0.02   # a_total may exceed the baseline's by at most 2 %
    command_duty = 0.05          # share of the run with |V_p,ref| at V_p,max
    rate_duty = 0.10             # share with |dV_p/dt| at its limit
    tail_factor = 2.0            # residual pitch at the end vs the baseline's
    margin_rad_s = 0.1           # stability margin of the linearised loop per load
    sampled_plants = 16          # plants drawn from the robustness study; the loop must be
                                 # stable on each (0: none)
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Any

__all__ = ["COURSE_PREFIX", "DEFAULT_ENVELOPE", "Condition", "Envelope", "load_envelope"]

_CLASSES = ("A", "B", "C", "D", "E", "F", "G", "H")
#: Prefix of a condition's road that is a course file: ``"course:"`` and the file's path.
COURSE_PREFIX = "course:"


@dataclass(frozen=True)
class Condition:
    """One road of the envelope on one load.

    Attributes
    ----------
    load : str
        The load case (``"empty"``, ``"full"``, or another machine's case).
    road : str
        ``"boards"`` (the paper's course at any speed), an ISO 8608 class ``"A"`` - ``"H"``, or
        ``"course:"`` and the path of a course file.
    speed_kmh : float
        Driven speed.
    seed : int
        Seed of the road (ISO 8608 profile, board placement) and the sensors' noise.
    """

    load: str
    road: str
    speed_kmh: float
    seed: int = 0

    @property
    def label(self) -> str:
        """A short name, e.g. ``full, boards 9 km/h`` or ``empty, ISO C 15 km/h (seed 1)``."""
        road = "boards" if self.road == "boards" else f"ISO {self.road}"
        if self.road.startswith(COURSE_PREFIX):
            road = Path(self.road[len(COURSE_PREFIX) :]).stem
        seed = f" (seed {self.seed})" if self.seed else ""
        return f"{self.load}, {road} {self.speed_kmh:g} km/h{seed}"


@dataclass(frozen=True)
class Envelope:
    """Conditions and criteria of a design check (module notes; units in the names)."""

    loads: tuple[str, ...] = ("empty", "full")
    board_speeds_kmh: tuple[float, ...] = (5.0, 9.0, 13.5, 18.0)
    road_classes: tuple[str, ...] = ("B", "C", "D")
    road_speeds_kmh: tuple[float, ...] = (5.0, 15.0, 30.0)
    courses: tuple[str, ...] = ()
    course_speeds_kmh: tuple[float, ...] = (5.0, 9.0, 13.5, 18.0)
    road_seconds: float = 8.0
    settle_s: float = 3.0
    seeds: tuple[int, ...] = (0,)
    worse_than_baseline: float = 0.02
    command_duty: float = 0.05
    rate_duty: float = 0.10
    tail_factor: float = 2.0
    margin_rad_s: float = 0.1
    sampled_plants: int = 16
    source: str = field(default="the default envelope", compare=False)

    def __post_init__(self) -> None:
        _check(self)

    def conditions(self) -> tuple[Condition, ...]:
        """Every (load, road, speed, seed): boards first, then the course files, then the
        ISO 8608 roads; the board course with seed 0 only when one seed is given (its boards
        lie where the paper put them)."""
        rows = []
        for load in self.loads:
            for seed in self.seeds:
                rows += [Condition(load, "boards", v, seed) for v in self.board_speeds_kmh]
                rows += [
                    Condition(load, COURSE_PREFIX + course, v, seed)
                    for course in self.courses
                    for v in self.course_speeds_kmh
                ]
                rows += [
                    Condition(load, c, v, seed)
                    for c in self.road_classes
                    for v in self.road_speeds_kmh
                ]
        return tuple(rows)


def _check(envelope: Envelope) -> None:
    where = envelope.source

    def fail(name: str, value: Any, allowed: str) -> None:
        raise ValueError(f"{where}: {name} = {value!r}; allowed: {allowed}")

    if not envelope.loads or not all(isinstance(x, str) and x for x in envelope.loads):
        fail("loads", envelope.loads, "a non-empty list of load-case names")
    for name in ("board_speeds_kmh", "road_speeds_kmh", "course_speeds_kmh"):
        for v in getattr(envelope, name):
            if isinstance(v, bool) or not isinstance(v, int | float) or not 1.0 <= v <= 60.0:
                fail(name, getattr(envelope, name), "speeds from 1 to 60 km/h")
    for c in envelope.road_classes:
        if c not in _CLASSES:
            fail("road_classes", envelope.road_classes, f"ISO 8608 classes among {_CLASSES}")
    if envelope.road_classes and not envelope.road_speeds_kmh:
        fail("road_speeds_kmh", envelope.road_speeds_kmh, "at least one speed for the roads")
    if envelope.courses and not envelope.course_speeds_kmh:
        fail("course_speeds_kmh", envelope.course_speeds_kmh, "at least one speed for the courses")
    if not envelope.board_speeds_kmh and not envelope.road_classes and not envelope.courses:
        fail("board_speeds_kmh", envelope.board_speeds_kmh, "at least one course or road")
    _check_courses(envelope, fail)
    if not envelope.seeds or not all(
        isinstance(s, int) and not isinstance(s, bool) and 0 <= s < 2**32 for s in envelope.seeds
    ):
        fail("seeds", envelope.seeds, "a non-empty list of integers from 0 to 2^32 - 1")
    count = envelope.sampled_plants
    if isinstance(count, bool) or not isinstance(count, int) or not 0 <= count <= 1000:
        fail("sampled_plants", count, "an integer from 0 to 1000")
    bounds = {
        "road_seconds": (1.0, 120.0),
        "settle_s": (2.0, 30.0),
        "worse_than_baseline": (0.0, 1.0),
        "command_duty": (0.0, 1.0),
        "rate_duty": (0.0, 1.0),
        "tail_factor": (1.0, 100.0),
        "margin_rad_s": (0.0, 10.0),
    }
    for name, (low, high) in bounds.items():
        value = getattr(envelope, name)
        if (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not math.isfinite(value)
            or not low <= value <= high
        ):
            fail(name, value, f"a number from {low:g} to {high:g}")


def _check_courses(envelope: Envelope, fail: Any) -> None:
    """Every course file of the envelope must be a readable, valid course file."""
    from loader_model.simulation.obstacles import load_course_file

    for course in envelope.courses:
        if not isinstance(course, str) or not course.endswith(".toml"):
            fail("courses", envelope.courses, "a list of course files FILE.toml")
        try:
            load_course_file(course, 9.0)
        except ValueError as error:
            fail("courses", course, f"a valid course file ({error})")


#: The default envelope (module notes).
DEFAULT_ENVELOPE = Envelope()

_SECTIONS = {
    "envelope": (
        "loads",
        "board_speeds_kmh",
        "road_classes",
        "road_speeds_kmh",
        "courses",
        "course_speeds_kmh",
        "road_seconds",
        "settle_s",
        "seeds",
    ),
    "criteria": (
        "worse_than_baseline",
        "command_duty",
        "rate_duty",
        "tail_factor",
        "margin_rad_s",
        "sampled_plants",
    ),
}


def load_envelope(path: str | Path) -> Envelope:
    """The envelope of a TOML file (module notes): the default with the file's entries.

    Raises
    ------
    ValueError
        Naming the file and the entry, for an unreadable file, an unknown section or key, or a
        value outside what is allowed.
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise ValueError(f"envelope file {path}: {exc}") from None
    unknown = sorted(set(data) - set(_SECTIONS))
    if unknown:
        raise ValueError(
            f"envelope file {path}: unknown section(s) {unknown}; allowed: {sorted(_SECTIONS)}"
        )
    values: dict[str, Any] = {}
    for section, keys in _SECTIONS.items():
        table = data.get(section, {})
        if not isinstance(table, dict):
            raise ValueError(f"envelope file {path}: [{section}] must be a table")
        extra = sorted(set(table) - set(keys))
        if extra:
            raise ValueError(
                f"envelope file {path}: [{section}] has unknown key(s) {extra}; allowed: "
                f"{list(keys)}"
            )
        values.update(table)
    if "courses" in values and isinstance(values["courses"], list):
        values["courses"] = [
            str(path.parent / course) if isinstance(course, str) else course
            for course in values["courses"]
        ]
    kinds = {f.name: f.default for f in fields(Envelope)}
    for name, value in list(values.items()):
        if isinstance(kinds[name], tuple):
            if not isinstance(value, list):
                raise ValueError(f"envelope file {path}: {name} = {value!r}; allowed: a list")
            values[name] = tuple(value)
    return replace(DEFAULT_ENVELOPE, source=f"envelope file {path}", **values)
