"""Figures of the reproduction report: Fig. 10, 13 and 14 of the paper, from the simulator.

- Fig. 10: spectra (|FFT| of the free response) of the chassis accelerations f_Hx, f_Hy
  (accelerometer at H) and θ̈1 over one board at 17 km/h, empty bucket, baseline, with Table 1's
  frequencies marked.
- Fig. 13: seat vertical acceleration f_Py − g (the seat pad under the occupant, as section 5.3
  measured) over one board at 9 km/h, empty bucket, with and without the Table 3 skyhook.
- Fig. 14: mean a_total per condition and controller with 95 % Student-t intervals.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from loader_model.experiments.statistics import mean_interval
from loader_model.experiments.table6 import LOAD_LABELS, SPEED_LABELS
from loader_model.experiments.trials import CONTROLLERS, DESIGNED_CONTROLLERS, TrialOutcome

__all__ = ["plot_fig10", "plot_fig13", "plot_fig14", "single_obstacle_run"]


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def single_obstacle_run(controller: str, speed_kmh: float, load: str = "empty", settle_s=3.0):
    """Simulate one board at ``speed_kmh`` with ``controller`` (the experiment's plant)."""
    from loader_model.experiments.trials import trial_scenario
    from loader_model.simulation.courses import single_obstacle_course
    from loader_model.simulation.simulator import course_input, simulate

    scenario = trial_scenario(controller, load)
    course = single_obstacle_course(speed_kmh, settle_s=settle_s)
    return simulate(course_input(course, scenario), scenario)


def plot_fig13(path: Path) -> dict[str, float]:
    """Fig. 13: seat vertical acceleration over one board at 9 km/h, empty, ± skyhook.

    Returns the largest absolute seat acceleration (about its static value) of each run in
    m/s², by controller, for the caption.
    """
    plt = _pyplot()
    figure, axis = plt.subplots(figsize=(7.5, 3.8))
    peaks: dict[str, float] = {}
    for controller, style in (("baseline", "-"), ("skyhook", "--")):
        result = single_obstacle_run(controller, 9.0, settle_s=2.0)
        f_sy = result["f_Py"]
        peaks[controller] = float(np.max(np.abs(f_sy - f_sy[0])))
        axis.plot(result.time_s, f_sy - f_sy[0], style, lw=1.0, label=controller)
    moving = np.flatnonzero(np.abs(f_sy - f_sy[0]) > 1e-3)
    if moving.size:
        axis.set_xlim(result.time_s[moving[0]] - 0.3, result.time_s[-1])
    axis.set_xlabel("time t [s]")
    axis.set_ylabel("seat vertical acceleration [m/s²]")
    axis.set_title("Fig. 13 (model): one 4 cm board at 9 km/h, empty bucket")
    axis.grid(True, alpha=0.3)
    axis.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return peaks


def plot_fig10(path: Path, table1_hz: Sequence[float]) -> Path:
    """Fig. 10: spectra of the chassis accelerations over one board at 17 km/h, empty, baseline."""
    plt = _pyplot()
    result = single_obstacle_run("baseline", 17.0, settle_s=8.0)
    rate = 1.0 / result.metadata["period_s"]
    figure, axes = plt.subplots(3, 1, figsize=(7.5, 7.0), sharex=True)
    signals = (
        ("f_Hx", "x: f_Hx [m/s²]"),
        ("f_Hy", "y: f_Hy [m/s²]"),
        ("thetadd_1", "θ: θ̈1 [rad/s²]"),
    )
    for axis, (name, label) in zip(axes, signals, strict=True):
        values = result[name] - result[name][0]
        spectrum = np.abs(np.fft.rfft(values)) / values.size * 2.0
        frequency = np.fft.rfftfreq(values.size, 1.0 / rate)
        axis.plot(frequency, spectrum, lw=1.0)
        for index, f in enumerate(table1_hz):
            axis.axvline(
                f, color="C3", ls=":", lw=1.0, label="Table 1 modes" if index == 0 else None
            )
        axis.set_ylabel(f"|A(f)| of {label}")
        axis.grid(True, alpha=0.3)
    axes[0].legend(loc="upper right")
    axes[0].set_title("Fig. 10 (model): one 4 cm board at 17 km/h, empty bucket, baseline")
    axes[-1].set_xlabel("frequency f [Hz]")
    axes[-1].set_xlim(0.0, 15.0)
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def plot_fig14(path: Path, outcomes: Sequence[TrialOutcome]) -> Path:
    """Fig. 14: mean a_total with 95 % intervals per speed/load condition and controller (top),
    and the change against the baseline with its 95 % interval beside the paper's Table 6
    (bottom). The paper publishes its absolute levels only as a bar chart; Table 6's changes
    are its numbers."""
    from loader_model.experiments.table6 import table6_cells

    plt = _pyplot()
    conditions = sorted({(o.spec.speed_kmh, o.spec.load) for o in outcomes})
    figure, (axis, change_axis) = plt.subplots(
        2, 1, figsize=(8.0, 8.2), height_ratios=(1.0, 1.0), sharex=True
    )
    present = {o.spec.controller for o in outcomes}
    controllers = [c for c in (*CONTROLLERS, *DESIGNED_CONTROLLERS) if c in present]
    width = 0.8 / len(controllers)
    offsets = {c: (k - (len(controllers) - 1) / 2) * width for k, c in enumerate(controllers)}
    for k, controller in enumerate(controllers):
        means, errors = [], []
        for speed, load in conditions:
            sample = [
                o.a_total_m_s2
                for o in outcomes
                if (o.spec.speed_kmh, o.spec.load, o.spec.controller) == (speed, load, controller)
            ]
            if len(sample) >= 2:
                mean, _, high = mean_interval(sample)
            else:
                mean, _, high = (sample[0],) * 3 if sample else (np.nan,) * 3
            means.append(mean)
            errors.append(high - mean)
        positions = np.arange(len(conditions)) + offsets[controller]
        axis.bar(positions, means, width, yerr=errors, capsize=3, label=controller, color=f"C{k}")
    axis.set_ylabel("a_total (Eq. 50) [m/s²]")
    axis.set_title("Fig. 14 (model): mean a_total, error bars 95 % confidence intervals")
    axis.grid(True, axis="y", alpha=0.3)
    axis.legend(fontsize=8, ncol=4, loc="upper center", bbox_to_anchor=(0.5, -0.02))

    index = {c: k for k, c in enumerate(conditions)}
    paper_label = "paper, Table 6"
    for cell in table6_cells(outcomes):
        key = (cell.speed_kmh, cell.load)
        if key not in index or cell.controller not in offsets:
            continue
        x = index[key] + offsets[cell.controller]
        k = controllers.index(cell.controller)
        m = cell.model
        change_axis.bar(x, m.change_percent, width, color=f"C{k}")
        change_axis.errorbar(
            x,
            m.change_percent,
            yerr=[[m.change_percent - m.low_percent], [m.high_percent - m.change_percent]],
            color="k",
            capsize=3,
            lw=0.8,
        )
        if np.isfinite(cell.paper_change_percent):
            change_axis.plot(
                x, cell.paper_change_percent, "D", color="k", ms=6, mfc="w", label=paper_label
            )
            paper_label = None
    change_axis.axhline(0.0, color="k", lw=0.8)
    change_axis.set_ylabel("change of a_total against baseline [%]")
    change_axis.set_title("model (bars, 95 % intervals) and the paper's Table 6 (diamonds)")
    change_axis.grid(True, axis="y", alpha=0.3)
    if paper_label is None:
        change_axis.legend(fontsize=8, loc="best")
    change_axis.set_xticks(
        np.arange(len(conditions)),
        [
            f"{SPEED_LABELS.get(s, s)} speed ({s:g} km/h)\n{LOAD_LABELS.get(ld, ld)} load ({ld})"
            for s, ld in conditions
        ],
    )
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path
