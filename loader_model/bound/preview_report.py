r"""The preview law in the 1 kHz simulation, its sweep over the preview length, CSV and figure.

The simulator gives a controller the plant's outputs y (named by the machine's
:class:`~loader_model.plant.layout.PlantLayout`), not its state, and the preview law
(:mod:`~loader_model.bound.preview`) feeds back the full lifted state. Like the bound's playback
(:mod:`~loader_model.bound.replay`) the controller holds the course table: per command interval j
its design command u*_j (feedforward and feedback of the design's own closed loop on the linear
plant) and the design's outputs y*_j at the node. It closes the loop on the deviation from that
design trajectory, which obeys the road-free lifted model δz_{j+1} = A δz_j + B δu_j, δy_j = C
δz_j: a steady-state Kalman filter (current estimator, gain L) reconstructs δz from δy = y − y*_j
and the law adds δu_j = −K δẑ_j. On the linear plant δz = 0 and the controller is the design; on
the machine it corrects what the linear model misses. The command is clipped to ±0.99 V_p,max (the
bound problem's limit) and held over the M periods of each interval (the design's grid).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from pathlib import Path

import casadi as ca
import numpy as np
import scipy.linalg

from loader_model.bound.preview import PreviewDesign, PreviewRun
from loader_model.bound.problem import BoundProblem
from loader_model.io.export import write_atomically
from loader_model.plant.layout import SKID_STEER, PlantLayout
from loader_model.plant.linear import linearise_plant
from loader_model.simulation.result import SimulationResult
from loader_model.simulation.scenario import Scenario, closed_loop
from loader_model.simulation.simulator import simulate
from loader_model.simulation.travel import RoadInput

__all__ = [
    "MEASURED",
    "PreviewSweep",
    "measured_outputs",
    "plot_sweep",
    "preview_controller",
    "preview_scenario",
    "simulate_preview",
    "write_csv",
]


def measured_outputs(layout: PlantLayout) -> tuple[str, ...]:
    """Plant outputs of ``layout`` the controller's estimator reads: velocities, boom angle,
    pressures, stroke, displacement, every axle's tyre force, the seat."""
    tyres = tuple(f"F_{axle}y" for axle in layout.machine.axles)
    return (
        "xd_H", "yd_H", "thetad_1", "phi", "p_A", "p_B", "x_piston", layout.actuator_state,
        *tyres, "f_Px", "f_Py", "thetadd_1",
    )  # fmt: skip


#: The skid-steer's :func:`measured_outputs`.
MEASURED: tuple[str, ...] = measured_outputs(SKID_STEER)


@cache
def preview_controller(count: int, states: int, layout: PlantLayout = SKID_STEER) -> ca.Function:
    """The controller ``(z, y, settings) -> (z_next, u)`` (module notes) for ``count`` command
    intervals and ``states`` lifted states; z = (k, u held, δẑ), settings = (M, u*_j with y*_j
    per interval, K, L, A, B (matrices column-major), output scales, command scale, command
    limit). The command is clipped to the pump's limit and the estimator is given the clipped
    deviation (so a saturating pump does not wind the estimate up). ``layout``: the machine,
    whose :func:`measured_outputs` the estimator reads."""
    names = measured_outputs(layout)
    ny, nz = len(names), states
    z = ca.SX.sym("z", 2 + nz)
    y = ca.SX.sym("y", len(layout.output_names))
    sizes = [1, count * (1 + ny), nz, nz * ny, nz * nz, nz, ny, 1, 1]
    settings = ca.SX.sym("settings", sum(sizes))
    parts = ca.vertsplit(settings, list(np.cumsum([0, *sizes])))
    hold, table, k_gain, l_gain, a, b, y_scale, u_scale, limit = parts
    rows = [table[i * (1 + ny) : (i + 1) * (1 + ny)] for i in range(count)]
    index = ca.floor((z[0] + 0.5) / hold)
    row = rows[-1]
    for j in range(count - 2, -1, -1):
        row = ca.if_else(index <= j, rows[j], row)
    measured = ca.vertcat(*(y[layout.output_names.index(name)] for name in names))
    innovation = (measured - row[1:]) / y_scale
    estimate = z[2:] + ca.reshape(l_gain, nz, ny) @ innovation
    command = ca.fmin(ca.fmax(row[0] - u_scale * ca.dot(k_gain, estimate), -limit), limit)
    applied = (command - row[0]) / u_scale  # the deviation the pump is given, clipped
    predicted = ca.reshape(a, nz, nz) @ estimate + b * applied
    node = ca.fmod(z[0] + 0.5, hold) < 1.0
    u = ca.if_else(node, command, z[1])
    z_next = ca.vertcat(z[0] + 1.0, u, ca.if_else(node, predicted, z[2:]))
    return ca.Function(
        f"preview_{count}_{nz}", [z, y, settings], [z_next, u], ["z", "y", "settings"],
        ["z_next", "u"],
    )  # fmt: skip


def _output_map(design: PreviewDesign, problem: BoundProblem) -> tuple[np.ndarray, np.ndarray]:
    """C (scaled lifted state) and D (exogenous) of :func:`measured_outputs`."""
    plant = problem.plant
    linearisation = linearise_plant(plant.params, plant.x0, plant.u0, machine=plant.layout)
    system = linearisation.state_space(exogenous=True)
    rows = [system.output_labels.index(name) for name in measured_outputs(plant.layout)]
    c, d = np.asarray(system.C)[rows], np.asarray(system.D)[rows, 1:]
    n = c.shape[1]
    lifted = np.zeros((len(rows), design.lq.a.shape[0]))
    lifted[:, :n] = c * design.state_scale[None, :n]
    return lifted, d


def preview_scenario(
    design: PreviewDesign,
    problem: BoundProblem,
    run: PreviewRun,
    *,
    model_error: float = 1e-3,
    sensor_error: float = 1.0,
) -> Scenario:
    """The closed loop of ``problem``'s plant with the preview controller of ``run`` (module
    notes); the Kalman filter assumes process noise ``model_error`` (scaled states) and sensor
    noise ``sensor_error`` (of each output's peak along the design trajectory)."""
    plant, lq = problem.plant, design.lq
    c, d = _output_map(design, problem)
    nodes = problem.exogenous[: problem.periods : problem.hold_periods]
    names = measured_outputs(plant.layout)
    y0 = np.array([plant.output(name) for name in names])
    y_star = y0 + run.states[:-1] @ c.T + nodes @ d.T
    scale = np.maximum(np.max(np.abs(y_star - y0), axis=0), 1e-9 * (1.0 + np.abs(y0)))
    c_n = c / scale[:, None]
    nz, ny = lq.a.shape[0], len(names)
    w, v = model_error**2 * np.eye(nz), sensor_error**2 * np.eye(ny)
    p = scipy.linalg.solve_discrete_are(lq.a.T, c_n.T, w, v)
    gain = p @ c_n.T @ np.linalg.inv(c_n @ p @ c_n.T + v)
    table = np.column_stack([plant.u0 + run.command, y_star])
    settings = np.concatenate(
        [[problem.hold_periods], table.ravel(), design.gain, gain.ravel("F"), lq.a.ravel("F"),
         lq.b, scale, [lq.u_scale, problem.u_bounds[1]]]
    )  # fmt: skip
    controller = preview_controller(run.command.size, nz, plant.layout)
    return closed_loop(plant, controller, settings, np.concatenate([[0.0, plant.u0], np.zeros(nz)]))


def simulate_preview(
    design: PreviewDesign, problem: BoundProblem, run: PreviewRun, road: RoadInput
) -> SimulationResult:
    """Simulate the preview controller of ``run`` over ``road`` for ``problem``'s horizon.

    Runs the period Function in CasADi's virtual machine (``jit=False``): the course table makes
    its graph long (about 14 nodes per command interval), so compiling it to C takes minutes
    (7 min for a 3 s course on the development machine) where interpreting it takes seconds.
    """
    scenario = preview_scenario(design, problem, run)
    return simulate(road, scenario, duration_s=problem.duration_s, jit=False)


@dataclass(frozen=True)
class PreviewSweep:
    """a_total against the preview length on one course.

    Attributes
    ----------
    title : str
        Course, speed, load.
    preview_m : numpy.ndarray
        L in m.
    linear : numpy.ndarray
        a_total of the preview law on the linear plant, m/s².
    simulated : numpy.ndarray
        a_total of the preview controller in the 1 kHz simulation (NaN: not simulated), m/s².
    peak_command : numpy.ndarray
        Peak |command deviation| of the design over the pump's limit.
    bound_m_s2 : float
        The non-causal LQ bound on the linear plant.
    lqr_m_s2 : float
        The plain LQR (no preview, not even the wheelbase's) on the linear plant.
    references : dict
        Controller name -> a_total in the simulation (baseline, best causal controller), m/s².
    """

    title: str
    preview_m: np.ndarray
    linear: np.ndarray
    simulated: np.ndarray
    peak_command: np.ndarray
    bound_m_s2: float
    lqr_m_s2: float
    references: dict[str, float]

    def format(self) -> str:
        """The table: L, a_total linear and simulated, peak command, beside the bound."""
        lines = [
            self.title,
            f"{'L [m]':>7}{'linear [m/s²]':>15}{'simulated':>11}{'peak/limit':>12}",
        ]
        for values in zip(
            self.preview_m, self.linear, self.simulated, self.peak_command, strict=True
        ):
            simulated = "not run" if np.isnan(values[2]) else f"{values[2]:.4f}"
            lines.append(f"{values[0]:>7.2f}{values[1]:>15.4f}{simulated:>11}{values[3]:>12.2f}")
        lines.append(f"{'non-causal LQ bound (linear plant)':<38}{self.bound_m_s2:.4f}")
        lines.append(f"{'plain LQR, no preview (linear plant)':<38}{self.lqr_m_s2:.4f}")
        lines.extend(
            f"{name + ' (simulated)':<38}{value:.4f}" for name, value in self.references.items()
        )
        return "\n".join(lines)


def write_csv(sweep: PreviewSweep, path: str | Path) -> Path:
    """The sweep as CSV (atomically): one row per preview length, the bound in every row."""

    def write(temporary: Path) -> None:
        table = np.column_stack(
            [sweep.preview_m, sweep.linear, sweep.simulated, sweep.peak_command,
             np.full(sweep.preview_m.size, sweep.bound_m_s2),
             np.full(sweep.preview_m.size, sweep.lqr_m_s2)]
        )  # fmt: skip
        header = (
            "preview [m],a_total linear [m/s^2],a_total simulated [m/s^2],"
            "peak command/limit,bound [m/s^2],plain LQR [m/s^2]"
        )
        np.savetxt(temporary, table, delimiter=",", header=header, comments="", fmt="%.9g")

    return write_atomically(path, write, (".csv",), "preview CSV")


def plot_sweep(sweep: PreviewSweep, path: str | Path) -> Path:
    """Figure: a_total against the preview length, the bound and the simulated references."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7.0, 4.5), layout="constrained")
    FigureCanvasAgg(figure)
    axes = figure.subplots()
    axes.plot(sweep.preview_m, sweep.linear, "o-", label="preview LQ, linear plant")
    if np.any(np.isfinite(sweep.simulated)):
        axes.plot(sweep.preview_m, sweep.simulated, "s--", label="preview LQ, 1 kHz simulation")
    axes.axhline(sweep.bound_m_s2, color="k", lw=1.0, label="non-causal LQ bound (linear plant)")
    axes.axhline(
        sweep.lqr_m_s2, color="C2", ls="-.", lw=1.0, label="plain LQR, no preview (linear plant)"
    )
    styles = iter(("--", ":", (0, (1, 3))))
    for name, value in sweep.references.items():
        axes.axhline(
            value, color="grey", ls=next(styles, "--"), lw=1.0, label=f"{name} (simulated)"
        )
    axes.set_xlabel("preview length L ahead of the front axle [m] (rear axle: L + wheelbase)")
    axes.set_ylabel("a_total [m/s²]")
    axes.set_title(sweep.title, fontsize=10)
    axes.legend(fontsize=8)
    axes.grid(alpha=0.3)

    def write(temporary: Path) -> None:
        figure.savefig(temporary, format="png", dpi=110)

    return write_atomically(path, write, (".png",), "preview figure")
