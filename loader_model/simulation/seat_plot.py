"""Figure of a run's seat accelerations (the signals ISO 2631-1 weighs, paper Fig. 13).

Three panels over time: the seat pad's longitudinal and vertical specific force minus their
static values (m/s², :mod:`loader_model.plant.occupant`; the chassis at S in a thin line) and the
chassis pitch acceleration θ̈1 (rad/s²), with the intervals in which a tyre
was off the ground shaded. Matplotlib is imported inside :func:`plot_seat` (Agg canvas, no global
backend); the file is written atomically.
"""

from __future__ import annotations

from pathlib import Path

from loader_model.io.export import check_output_path, write_atomically
from loader_model.simulation.result import SimulationResult

__all__ = ["PLOT_SUFFIXES", "plot_seat"]

#: File types :func:`plot_seat` writes.
PLOT_SUFFIXES = (".png", ".pdf", ".svg")

_PANELS = (
    ("f_Px", "seat pad x\nf_Px − f_Px(0) (m/s²)"),
    ("f_Py", "seat pad vertical\nf_Py − g (m/s²)"),
    ("thetadd_1", "pitch\nθ̈1 (rad/s²)"),
)
#: The chassis signal drawn beside each pad signal (the seat's base S).
_CHASSIS = {"f_Px": "f_Sx", "f_Py": "f_Sy"}


def plot_seat(result: SimulationResult, path: str | Path, title: str = "") -> Path:
    """Write the seat-acceleration figure of ``result`` to ``path`` (PNG, PDF or SVG).

    Parameters
    ----------
    result : SimulationResult
        A run of :func:`~loader_model.simulation.simulator.simulate`.
    path : str or pathlib.Path
        Output file, suffix one of :data:`PLOT_SUFFIXES`.
    title : str
        Figure title.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = check_output_path(path, PLOT_SUFFIXES, "plot file")
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(9.0, 7.0), layout="constrained")
    FigureCanvasAgg(figure)
    axes = figure.subplots(len(_PANELS), 1, sharex=True)
    airborne = [event for event in result.events if event.kind == "tyre_off_ground"]
    for axis, (name, label) in zip(axes, _PANELS, strict=True):
        values = result[name]
        if name in _CHASSIS:
            base = result[_CHASSIS[name]]
            axis.plot(
                result.time_s, base - base[0], linewidth=0.5, color="0.6", label="chassis at S"
            )
        axis.plot(result.time_s, values - values[0], linewidth=0.8, label="seat pad")
        for index, event in enumerate(airborne):
            axis.axvspan(
                event.start_s,
                event.end_s + result.metadata.get("period_s", 0.0),
                color="tab:orange",
                alpha=0.2,
                linewidth=0,
                label="a tyre off the ground" if index == 0 else None,
            )
        axis.set_ylabel(label)
        axis.grid(True, linewidth=0.3)
    axes[0].legend(loc="upper right")
    axes[-1].set_xlabel("time (s)")
    axes[-1].set_xlim(result.time_s[0], result.time_s[-1])
    figure.suptitle(title or "seat accelerations")
    return write_atomically(
        path, lambda temporary: figure.savefig(temporary, dpi=120), PLOT_SUFFIXES, "plot file"
    )
