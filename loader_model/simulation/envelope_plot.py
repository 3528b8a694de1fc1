"""Figure of the enveloping models over a stretch of road: ground, rigid disc, tandem cams.

Matplotlib is imported inside :func:`plot_envelopes` and drives the Agg canvas directly (no global
backend), as in :mod:`~loader_model.simulation.road_plot`.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from loader_model.simulation.envelope import effective_road
from loader_model.simulation.roads import RoadProfile
from loader_model.simulation.tandem_cam import TandemCam, tandem_cam_road
from loader_model.simulation.travel import DEFAULT_TYRE_RADIUS_M

__all__ = ["plot_envelopes"]


def plot_envelopes(
    path: str | Path,
    profile: RoadProfile,
    cams: Mapping[str, TandemCam],
    *,
    distance_range_m: tuple[float, float],
    tyre_radius_m: float = DEFAULT_TYRE_RADIUS_M,
    title: str = "",
) -> Path:
    """Write a two-panel figure (PNG, PDF or SVG): effective height and slope tan β over distance.

    Parameters
    ----------
    path : str or pathlib.Path
        Output file ending in .png, .pdf or .svg; written atomically.
    profile : RoadProfile
        The ground.
    cams : mapping of str to TandemCam
        Label (e.g. ``"front, empty bucket"``) to tandem cam
        (:meth:`~loader_model.simulation.tandem_cam.TandemCam.from_deflection`).
    distance_range_m : (float, float)
        Distance axis limits in m, low < high.
    tyre_radius_m : float
        Radius R of the rigid disc drawn beside them.
    title : str
        Figure title.

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
    low_m, high_m = (float(value) for value in distance_range_m)
    if not low_m < high_m:
        raise ValueError(
            f"distance_range_m must be (low, high) with low < high; got {distance_range_m!r}"
        )
    s = np.linspace(low_m, high_m, 8001)
    inside = (profile.distance_m > low_m) & (profile.distance_m < high_m)
    ground_s = np.concatenate([[low_m], profile.distance_m[inside], [high_m]])
    ground_h = np.concatenate(
        [profile.height([low_m]), profile.height_m[inside], profile.height([high_m])]
    )
    rigid = effective_road(profile, s, tyre_radius_m)

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(9.0, 6.5), layout="constrained")
    FigureCanvasAgg(figure)
    top, bottom = figure.subplots(2, 1, sharex=True)
    top.plot(ground_s, ground_h * 1e3, color="0.2", lw=1.0, label="ground h(s)")
    top.plot(s, rigid.height_m * 1e3, color="0.55", lw=1.2, ls="--", label="rigid disc")
    bottom.plot(s, rigid.slope, color="0.55", lw=1.2, ls="--", label="rigid disc")
    for index, (label, cam) in enumerate(cams.items()):
        road = tandem_cam_road(profile, s, cam)
        text = f"tandem cam, {label} (l_s = {cam.spacing_m * 1e3:.0f} mm)"
        top.plot(s, road.height_m * 1e3, color=f"C{index}", lw=1.3, label=text)
        bottom.plot(s, road.slope, color=f"C{index}", lw=1.2, label=text)
    top.set_ylabel("effective height w (mm)")
    top.set_title(title or profile.name)
    top.margins(y=0.5)  # room for the legend above the curves
    top.legend(loc="upper left", fontsize="small")
    bottom.set_xlabel("axle position s (m)")
    bottom.set_ylabel("effective slope tan β (-)")
    bottom.legend(loc="lower left", fontsize="small")
    for axes in (top, bottom):
        axes.set_xlim(low_m, high_m)
        axes.grid(True, alpha=0.3)

    handle, temporary = tempfile.mkstemp(suffix=path.suffix, dir=path.parent, prefix=".tmp-")
    os.close(handle)
    try:
        figure.savefig(temporary, dpi=110)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return path
