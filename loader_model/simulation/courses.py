"""Courses: a road profile driven at a speed, with the paper's test course and single obstacle.

The paper's course (section 5.3): five wooden boards 4 cm tall on paved concrete, spaced 6 m at
9 km/h and 9 m at 18 km/h. Its model check (section 2.5, Fig. 10): the free response after a
single obstacle at 17 km/h.

Assumptions the paper leaves open:

- Board width 140 mm (:data:`BOARD_WIDTH_M`): "4 cm tall" wooden boards are most plausibly North
  American dimension lumber laid flat (the tests ran at Purdue), whose 2-by sizes are 38 mm thick;
  the commonest plank, a 2x6, is 140 mm wide (a 2x8 is 184 mm). The height is kept at the paper's
  40 mm. The width matters little: a rigid 0.42 m wheel rides on each edge for 0.179 m, so the
  enveloped bump is 0.50 m long with 140 mm and 0.54 m with 184 mm.
- Spacing is leading edge to leading edge.
- The single obstacle of Fig. 10 is one board of the course (the paper does not describe it).
- The front axle starts :data:`LEAD_IN_M` before the first board, and the drive goes on until the
  rear axle is past the last board and ``settle_s`` more seconds have passed.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from loader_model.simulation._checks import as_number
from loader_model.simulation.iso8608 import iso8608_profile
from loader_model.simulation.roads import RoadProfile, board_course
from loader_model.simulation.tandem_cam import TandemCam
from loader_model.simulation.travel import (
    DEFAULT_SAMPLE_RATE_HZ,
    DEFAULT_TYRE_RADIUS_M,
    RoadInput,
    road_input,
)

__all__ = [
    "BOARD_HEIGHT_M",
    "BOARD_WIDTH_M",
    "FIG10_SPEED_KMH",
    "LEAD_IN_M",
    "PAPER_BOARD_COUNT",
    "PAPER_SPACING_M",
    "Course",
    "board_course_at",
    "board_spacing_m",
    "boards_at_speed",
    "iso8608_course",
    "kmh_to_m_s",
    "paper_course",
    "single_obstacle_course",
]

#: Board height of the paper's course in m (section 5.3).
BOARD_HEIGHT_M = 0.04
#: Assumed board width in m: a 2x6 plank laid flat (module notes).
BOARD_WIDTH_M = 0.14
#: Number of boards of the paper's course.
PAPER_BOARD_COUNT = 5
#: Board spacing of the paper's course in m by speed in km/h.
PAPER_SPACING_M = {9.0: 6.0, 18.0: 9.0}
#: Speed of the single-obstacle drive of Fig. 10 in km/h.
FIG10_SPEED_KMH = 17.0
#: Distance in m from the front axle at t = 0 to the first obstacle.
LEAD_IN_M = 5.0


def kmh_to_m_s(speed_kmh: float) -> float:
    """Speed in m/s of ``speed_kmh`` km/h."""
    return as_number(speed_kmh, "speed_kmh", "km/h", minimum=0.0, strict_minimum=True) / 3.6


@dataclass(frozen=True)
class Course:
    """A profile driven at constant speed from ``start_m`` (front axle at t = 0).

    Attributes
    ----------
    profile : RoadProfile
        Raw ground profile.
    speed_m_s : float
        Forward speed in m/s.
    start_m : float
        Front-axle distance at t = 0 in m.
    settle_s : float
        Time in s the drive continues after the rear axle has passed the profile's last vertex.
    name : str
        Label.
    """

    profile: RoadProfile
    speed_m_s: float
    start_m: float
    settle_s: float
    name: str

    def duration_s(
        self, wheelbase_m: float, tyre_radius_m: float | Sequence[float] = DEFAULT_TYRE_RADIUS_M
    ) -> float:
        """Drive time in s until the rear axle (``wheelbase_m`` behind the front axle; for more
        axles the rearmost one's distance) is R past the last vertex plus ``settle_s`` (R: the
        largest of the axles' radii when one is given per axle)."""
        many = isinstance(tyre_radius_m, Sequence) and not isinstance(tyre_radius_m, str)
        radii = tyre_radius_m if many else (tyre_radius_m,)  # checked by road_input
        radius_m = max((float(r) for r in radii if isinstance(r, int | float) and r > 0), default=0)
        past_m = self.profile.end_m + wheelbase_m + radius_m - self.start_m
        return max(past_m, 0.0) / self.speed_m_s + self.settle_s

    def road_input(
        self,
        wheelbase_m: float | None = None,
        *,
        tyre_radius_m: float | Sequence[float] = DEFAULT_TYRE_RADIUS_M,
        sample_rate_hz: float = DEFAULT_SAMPLE_RATE_HZ,
        slope_to_x_m: Sequence[float] | None = None,
        cams: Sequence[TandemCam] | None = None,
        axle_offsets_m: Sequence[float] | None = None,
        axle_names: Sequence[str] | None = None,
    ) -> RoadInput:
        """The drive's road input table (:func:`~loader_model.simulation.travel.road_input`):
        two axles ``wheelbase_m`` apart, or any number at ``axle_offsets_m`` behind the front
        axle (``cams``: one tandem cam per axle, default rigid discs; ``tyre_radius_m``: one free
        radius for all axles or one per axle). The drive lasts until the rearmost axle is past
        the last vertex (:meth:`duration_s`)."""
        if axle_offsets_m is None:
            wheelbase_m = as_number(wheelbase_m, "wheelbase_m", "m", minimum=0.0, maximum=10.0)
            rear_m = wheelbase_m
        else:
            rear_m = max((float(d) for d in axle_offsets_m), default=0.0)
        return road_input(
            self.profile,
            speed_m_s=self.speed_m_s,
            wheelbase_m=wheelbase_m,
            duration_s=self.duration_s(rear_m, tyre_radius_m),
            start_m=self.start_m,
            tyre_radius_m=tyre_radius_m,
            sample_rate_hz=sample_rate_hz,
            slope_to_x_m=slope_to_x_m,
            cams=cams,
            axle_offsets_m=axle_offsets_m,
            axle_names=axle_names,
        )


def paper_course(
    speed_kmh: float,
    *,
    board_width_m: float = BOARD_WIDTH_M,
    position_jitter_m: float = 0.0,
    seed: int = 0,
    settle_s: float = 3.0,
) -> Course:
    """The paper's test course (section 5.3) at 9 or 18 km/h.

    Parameters
    ----------
    speed_kmh : float
        9 (boards 6 m apart) or 18 (9 m apart).
    board_width_m : float
        Board width in m (default: the assumed 2x6 plank, module notes).
    position_jitter_m, seed : float, int
        Standard deviation in m of a seeded normal shift of each board (boards laid by hand).
    settle_s : float
        Seconds driven after the rear axle has left the last board, [0, 60].
    """
    if speed_kmh not in PAPER_SPACING_M or isinstance(speed_kmh, bool):
        raise ValueError(
            f"speed_kmh must be one of the paper's speeds {tuple(PAPER_SPACING_M)} km/h; "
            f"got {speed_kmh!r}"
        )
    spacing_m = PAPER_SPACING_M[float(speed_kmh)]
    return boards_at_speed(
        speed_kmh,
        board_width_m=board_width_m,
        position_jitter_m=position_jitter_m,
        seed=seed,
        settle_s=settle_s,
        name=f"paper course, {speed_kmh:g} km/h: 5 boards 40 mm, {spacing_m:g} m apart",
    )


def board_spacing_m(speed_kmh: float) -> float:
    """The paper's board spacing rule extended to any speed: 6 m at 9 km/h and 9 m at 18 km/h
    (section 5.3), linear in the speed between and beyond, 3 m + speed / (3 km/h) m, so the
    boards pass the axles 2.4 s apart at 9 km/h and 1.8 s apart at 18 km/h."""
    speed_kmh = as_number(speed_kmh, "speed_kmh", "km/h", minimum=0.0, maximum=100.0)
    return 3.0 + speed_kmh / 3.0


def boards_at_speed(
    speed_kmh: float,
    *,
    board_width_m: float = BOARD_WIDTH_M,
    position_jitter_m: float = 0.0,
    seed: int = 0,
    settle_s: float = 3.0,
    name: str | None = None,
) -> Course:
    """The paper's five 40 mm boards (section 5.3) at any speed, spaced by
    :func:`board_spacing_m`; at 9 and 18 km/h the same course as :func:`paper_course`.

    Parameters
    ----------
    speed_kmh : float
        Driven speed in km/h, (0, 100].
    board_width_m : float
        Board width in m, its length along the path (default: the assumed 2x6 plank, module
        notes).
    position_jitter_m, seed : float, int
        Standard deviation in m of a seeded normal shift of each board (boards laid by hand).
    settle_s : float
        Seconds driven after the rear axle has left the last board, [0, 60].
    name : str, optional
        Label (default: the boards, their spacing and the speed).

    See Also
    --------
    board_course_at : any number, spacing, height and length of boards.
    """
    return board_course_at(
        speed_kmh,
        length_m=board_width_m,
        position_jitter_m=position_jitter_m,
        seed=seed,
        settle_s=settle_s,
        name=name,
    )


def board_course_at(
    speed_kmh: float,
    *,
    spacing_m: float | None = None,
    height_m: float = BOARD_HEIGHT_M,
    length_m: float = BOARD_WIDTH_M,
    count: int = PAPER_BOARD_COUNT,
    position_jitter_m: float = 0.0,
    seed: int = 0,
    settle_s: float = 3.0,
    name: str | None = None,
) -> Course:
    """A course of equal boards on flat ground driven at ``speed_kmh``: the paper's (section 5.3)
    with any speed, spacing, board height, board length and number of boards.

    With the defaults it is :func:`boards_at_speed`, and at 9 and 18 km/h :func:`paper_course`.

    Parameters
    ----------
    speed_kmh : float
        Driven speed in km/h, (0, 100].
    spacing_m : float, optional
        Leading edge to leading edge in m, (``length_m``, 1000] (default: the paper's rule,
        :func:`board_spacing_m`; ignored for one board).
    height_m : float
        Board height in m, (0, 0.5] (default: the paper's 40 mm).
    length_m : float
        Board length along the path in m, (0, 5] (default: the assumed 140 mm plank, module
        notes).
    count : int
        Number of boards, 1 to 1000 (default: the paper's five).
    position_jitter_m, seed : float, int
        Standard deviation in m of a seeded normal shift of each board (boards laid by hand).
    settle_s : float
        Seconds driven after the rear axle has left the last board, [0, 60].
    name : str, optional
        Label (default: the boards, their spacing and the speed).

    Raises
    ------
    ValueError
        Naming the argument, its value and the allowed range.
    """
    speed_kmh = as_number(
        speed_kmh, "speed_kmh", "km/h", minimum=0.0, maximum=100.0, strict_minimum=True
    )
    length_m = as_number(length_m, "length_m", "m", minimum=0.0, maximum=5.0, strict_minimum=True)
    height_m = as_number(height_m, "height_m", "m", minimum=0.0, maximum=0.5, strict_minimum=True)
    if spacing_m is None:
        spacing_m = board_spacing_m(speed_kmh)
    else:
        spacing_m = as_number(
            spacing_m, "spacing_m", "m", minimum=length_m, maximum=1000.0, strict_minimum=True
        )
    settle_s = as_number(settle_s, "settle_s", "s", minimum=0.0, maximum=60.0)
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= 1000:
        raise ValueError(f"count must be an integer in [1, 1000] boards; got {count!r}")
    if name is None:
        name = f"{count} boards {height_m * 1e3:g} mm"
        name += "" if length_m == BOARD_WIDTH_M else f" x {length_m * 1e3:g} mm"
        name += f", {spacing_m:g} m apart, at {speed_kmh:g} km/h" if count > 1 else ""
        name += "" if count > 1 else f" at {speed_kmh:g} km/h"
    profile = board_course(
        count,
        height_m=height_m,
        width_m=length_m,
        spacing_m=spacing_m,
        first_board_m=0.0,
        position_jitter_m=position_jitter_m,
        seed=seed,
        name=name,
    )
    return Course(profile, kmh_to_m_s(speed_kmh), -LEAD_IN_M, settle_s, profile.name)


def single_obstacle_course(
    speed_kmh: float = FIG10_SPEED_KMH,
    *,
    height_m: float = BOARD_HEIGHT_M,
    width_m: float = BOARD_WIDTH_M,
    settle_s: float = 8.0,
) -> Course:
    """One board driven at ``speed_kmh`` (Fig. 10: 17 km/h), long enough for a free response."""
    profile = board_course(
        1, height_m=height_m, width_m=width_m, spacing_m=0.0, name="single obstacle"
    )
    settle_s = as_number(settle_s, "settle_s", "s", minimum=0.0, maximum=600.0)
    speed_m_s = kmh_to_m_s(
        as_number(speed_kmh, "speed_kmh", "km/h", minimum=0.0, maximum=100.0, strict_minimum=True)
    )
    name = f"single obstacle {height_m * 1e3:g} mm at {speed_kmh:g} km/h"
    return Course(profile, speed_m_s, -LEAD_IN_M, settle_s, name)


def iso8608_course(
    road_class: str,
    speed_kmh: float,
    *,
    length_m: float = 200.0,
    seed: int = 0,
    settle_s: float = 0.0,
) -> Course:
    """An ISO 8608 random road of ``road_class`` and ``length_m`` driven at ``speed_kmh``."""
    profile = iso8608_profile(road_class, length_m, seed=seed)
    speed_m_s = kmh_to_m_s(
        as_number(speed_kmh, "speed_kmh", "km/h", minimum=0.0, maximum=100.0, strict_minimum=True)
    )
    settle_s = as_number(settle_s, "settle_s", "s", minimum=0.0, maximum=600.0)
    name = f"{profile.name} at {speed_kmh:g} km/h"
    return Course(profile, speed_m_s, -LEAD_IN_M, settle_s, name)
