"""The course options of the commands that drive one: ``--course`` and the ``--board-*`` options.

``loader-model simulate`` drives the course it names; ``loader-model design --method refine``
refines the gains on it. The course is driven at the command's own ``--speed`` (and, for a random
road, its ``--duration`` and ``--seed`` where it has them). Courses: the paper's (section 5.3),
boards at any speed (:func:`~loader_model.simulation.courses.board_course_at`), one board, an
ISO 8608 road (:func:`~loader_model.simulation.courses.iso8608_course`) or a course file of your
own obstacles (:func:`~loader_model.simulation.obstacles.load_course_file`; the simulation page
of the user guide).
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from loader_model.simulation.courses import Course

__all__ = ["BOARD_OPTIONS", "add_course_arguments", "check_drive", "course_from_arguments"]

#: The ``--board-*`` options: attribute, option, keyword of :func:`board_course_at`.
BOARD_OPTIONS = (
    ("boards", "--boards", "count"),
    ("board_spacing", "--board-spacing", "spacing_m"),
    ("board_height", "--board-height", "height_m"),
    ("board_length", "--board-length", "length_m"),
)

_COURSE_HELP = (
    "'paper' (the paper's five 4 cm boards, 6 m apart at 9 km/h or 9 m apart at "
    "18 km/h), 'boards' (boards at any --speed, shaped by the --board-* options), 'single' "
    "(one board), 'iso8608:CLASS' (random road, class A-H) or a course file FILE.toml "
    "(your own list of obstacles; see the user guide's simulation page)"
)


def add_course_arguments(parser: argparse.ArgumentParser, used_by: str = "") -> None:
    """Add ``--course`` (default: paper) and the ``--board-*`` group to ``parser``.

    ``used_by`` ends the help of ``--course`` (for example "; --method refine only").
    """
    parser.add_argument(
        "--course",
        default=None,
        metavar="COURSE",
        help=f"{_COURSE_HELP}{used_by} (default: paper)",
    )
    boards = parser.add_argument_group("the board course (--course boards)")
    boards.add_argument(
        "--boards",
        type=int,
        default=None,
        metavar="N",
        help="number of boards, 1-1000 (default: 5, the paper's)",
    )
    boards.add_argument(
        "--board-spacing",
        type=float,
        default=None,
        metavar="M",
        help="leading edge to leading edge in m, above the board length and at most 1000 "
        "(default: the paper's rule, 3 m + speed / (3 km/h) m: 6 m at 9 km/h, 9 m at 18 km/h)",
    )
    boards.add_argument(
        "--board-height",
        type=float,
        default=None,
        metavar="M",
        help="board height in m, (0, 0.5] (default: 0.04, the paper's)",
    )
    boards.add_argument(
        "--board-length",
        type=float,
        default=None,
        metavar="M",
        help="board length along the path in m, (0, 5] (default: 0.14, a 2x6 plank laid flat)",
    )


def course_options_given(args: argparse.Namespace) -> list[str]:
    """The course options given on the command line (``--course`` and ``--board-*``)."""
    given = ["--course"] if getattr(args, "course", None) is not None else []
    return given + [option for name, option, _ in BOARD_OPTIONS if getattr(args, name) is not None]


def course_from_arguments(args: argparse.Namespace) -> Course:
    """The course ``--course`` names (default: paper) at ``--speed``, shaped by ``--board-*``.

    Raises
    ------
    ValueError
        Naming the option, its value and what is allowed.
    """
    from loader_model.simulation.courses import (
        PAPER_SPACING_M,
        board_course_at,
        iso8608_course,
        paper_course,
        single_obstacle_course,
    )

    text, speed_kmh = args.course or "paper", args.speed
    board = {
        keyword: (option, getattr(args, name))
        for name, option, keyword in BOARD_OPTIONS
        if getattr(args, name, None) is not None
    }
    if board and text != "boards":
        options = ", ".join(option for option, _ in board.values())
        raise ValueError(f"{options}: allowed only with --course boards; got --course {text}")
    if text == "boards":
        try:
            return board_course_at(speed_kmh, **{k: v for k, (_, v) in board.items()})
        except ValueError as error:  # name the option, not the library's argument
            for keyword, (option, _) in board.items():
                if str(error).startswith(keyword):
                    raise ValueError(option + str(error)[len(keyword) :]) from None
            raise
    if text == "paper":
        if speed_kmh not in PAPER_SPACING_M:
            raise ValueError(
                f"--speed {speed_kmh:g}: allowed with --course paper: "
                f"{' or '.join(f'{v:g}' for v in PAPER_SPACING_M)} km/h (the paper's courses; "
                "--course boards drives them at any speed)"
            )
        return paper_course(speed_kmh)
    if text == "single":
        return single_obstacle_course(speed_kmh)
    if text.endswith(".toml"):
        from loader_model.simulation.obstacles import load_course_file

        return load_course_file(text, speed_kmh)
    from loader_model.simulation.iso8608 import CLASS_PSD_M3

    name, _, road_class = text.partition(":")
    if name != "iso8608" or road_class.strip().upper() not in CLASS_PSD_M3:
        classes = f"iso8608:{min(CLASS_PSD_M3)} to iso8608:{max(CLASS_PSD_M3)}"
        raise ValueError(
            f"--course must be paper, boards, single, {classes} or a course file FILE.toml; "
            f"got {text!r}"
        )
    duration_s = getattr(args, "duration", None)
    length_m = 200.0 if duration_s is None else speed_kmh / 3.6 * duration_s + 20.0
    seed = getattr(args, "seed", 0)
    return iso8608_course(road_class.strip().upper(), speed_kmh, length_m=length_m, seed=seed)


def check_drive(course: Course, speed_kmh: float) -> None:
    """Refuse a course that takes more than an hour at ``--speed`` (without ``--duration``)."""
    drive_s = course.duration_s(0.0)  # at least this long, whatever the machine's wheelbase
    if drive_s > 3600.0:
        raise ValueError(
            f"--speed {speed_kmh:g} km/h: the course takes {drive_s:.3g} s at that speed; "
            "allowed: a drive of at most 3600 s (a higher --speed, or give --duration)"
        )
