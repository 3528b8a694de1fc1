"""Plot of a course: raw and effective profile over distance, slope, and each axle's input in time.

Matplotlib is imported inside :func:`plot_course` and drives the Agg canvas directly, so no global
backend is selected and importing this module stays cheap.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from loader_model.simulation.courses import Course
from loader_model.simulation.envelope import effective_road
from loader_model.simulation.tandem_cam import TandemCam, tandem_cam_road
from loader_model.simulation.travel import DEFAULT_TYRE_RADIUS_M

__all__ = ["plot_course"]


def plot_course(
    path: str | Path,
    course: Course,
    *,
    wheelbase_m: float,
    tyre_radius_m: float = DEFAULT_TYRE_RADIUS_M,
    distance_range_m: tuple[float, float] | None = None,
    cams: Sequence[TandemCam] | None = None,
) -> Path:
    """Write a three-panel figure of ``course`` to ``path`` (PNG, PDF or SVG).

    Panels: raw ground height and effective height h_eff (rigid wheel of radius R) over distance;
    effective slope tan β over distance; w_Ay and w_By over the time either axle spends in the
    distance range, the rear delayed by L / v.

    Parameters
    ----------
    path : str or pathlib.Path
        Output file ending in .png, .pdf or .svg; written atomically.
    course : Course
        The drive.
    wheelbase_m : float
        Wheelbase L in m.
    tyre_radius_m : float
        Wheel radius R in m.
    distance_range_m : (float, float), optional
        Distance axis limits of the first two panels in m; default the whole drive of the front axle.
    cams : sequence of two TandemCam, optional
        Tandem cams of axles A and B (:func:`~loader_model.simulation.simulator.course_input`
        builds them from the static deflections): the first two panels add axle A's effective
        height and slope beside the rigid disc's, and the third panel shows the cams' inputs.
        Default: rigid discs only.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    if path.suffix.lower() not in (".png", ".pdf", ".svg"):
        raise ValueError(f"plot path must end in .png, .pdf or .svg; got {str(path)!r}")
    if not path.parent.is_dir():
        raise ValueError(f"plot path folder does not exist: {str(path.parent)!r}")
    drive = course.road_input(wheelbase_m, tyre_radius_m=tyre_radius_m, cams=cams)
    if distance_range_m is None:
        low_m, high_m = course.start_m, float(drive.axle_distance(drive.duration_s)[0])
    else:
        low_m, high_m = (float(value) for value in distance_range_m)
        if not low_m < high_m:
            raise ValueError(
                f"distance_range_m must be (low, high) with low < high; got {distance_range_m!r}"
            )
    distance_m = np.linspace(low_m, high_m, 20_001)
    profile = course.profile
    inside = (profile.distance_m > low_m) & (profile.distance_m < high_m)
    raw_s = np.concatenate([[low_m], profile.distance_m[inside], [high_m]])
    raw_h = np.concatenate(
        [profile.height([low_m]), profile.height_m[inside], profile.height([high_m])]
    )
    effective = effective_road(profile, distance_m, tyre_radius_m)

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(9.0, 8.0), layout="constrained")
    FigureCanvasAgg(figure)
    top, middle, bottom = figure.subplots(3, 1)
    top.plot(raw_s, raw_h * 1e3, color="0.3", lw=0.8, zorder=3, label="raw ground h(s)")
    top.plot(
        distance_m,
        effective.height_m * 1e3,
        color="C0",
        lw=1.2,
        label=f"effective h_eff(s), rigid wheel R = {tyre_radius_m:g} m",
    )
    if drive.cams is not None:
        cam = drive.cams[0]
        road = tandem_cam_road(profile, distance_m, cam)
        label = f"effective w(s), tandem cam of axle A (l_s = {cam.spacing_m * 1e3:.0f} mm)"
        top.plot(distance_m, road.height_m * 1e3, color="C2", lw=1.2, label=label)
    top.set_xlabel("distance s (m)")
    top.set_ylabel("height (mm)")
    top.set_title(course.name)
    top.margins(y=0.35)
    top.legend(loc="upper right")
    middle.plot(distance_m, effective.slope, color="C1", lw=1.0, label="rigid wheel")
    if drive.cams is not None:
        middle.plot(distance_m, road.slope, color="C2", lw=1.0, label="tandem cam, axle A")
        middle.legend(loc="upper right")
    middle.set_xlabel("distance s (m)")
    middle.set_ylabel("effective slope tan β (-)")
    for axes in (top, middle):
        axes.set_xlim(low_m, high_m)
        axes.grid(True, alpha=0.3)
    bottom.plot(
        drive.time_s, drive.road_m[:, 1] * 1e3, color="C0", lw=1.2, label="front axle A: w_Ay"
    )
    bottom.plot(
        drive.time_s,
        drive.road_m[:, 3] * 1e3,
        color="C3",
        lw=1.2,
        ls="--",
        label=f"rear axle B: w_By (delay L/v = {wheelbase_m / course.speed_m_s:.3f} s)",
    )
    bottom.set_xlabel("time t (s)")
    bottom.set_ylabel("effective height (mm)")
    bottom.set_title(f"road input at {course.speed_m_s * 3.6:g} km/h, wheelbase {wheelbase_m:g} m")
    first_s = max(0.0, (low_m - course.start_m) / course.speed_m_s)
    last_s = min(drive.duration_s, (high_m + wheelbase_m - course.start_m) / course.speed_m_s)
    bottom.set_xlim(first_s, max(last_s, first_s + 1.0 / drive.sample_rate_hz))
    bottom.grid(True, alpha=0.3)
    bottom.margins(y=0.35)
    bottom.legend(loc="upper right")

    handle, temporary = tempfile.mkstemp(suffix=path.suffix, dir=path.parent, prefix=".tmp-")
    os.close(handle)
    try:
        figure.savefig(temporary, dpi=110)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return path
