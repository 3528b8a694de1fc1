r"""The clairvoyant bound of the machine: Gauss-Newton SQP in single shooting on the command table.

Each iterate's trajectory is the simulator's (:func:`~loader_model.bound.trajectory.rollout`:
the simulator's compiled period, substeps, road table and seat signals), so the optimiser's
a_total (Eq. 49, 50, the sampled weightings of :mod:`~loader_model.bound.weighting`) is the one
the optimal command gives when replayed open loop (:func:`~loader_model.bound.replay.replay`).
One iteration: linearise along the trajectory with the flow's sensitivities
(:func:`~loader_model.bound.trajectory.linearise`), build the Gauss-Newton QP in stage form
(:func:`~loader_model.bound.stage_model.stage_qp`: one stage per command interval, every path
sample a row of its stage), solve it with the command box, the end condition and all path
limits by the Riccati interior point (:func:`~loader_model.bound.riccati_qp.solve_riccati_qp`,
cost linear in the course's length), with Levenberg-Marquardt damping relative to the condensed
Hessian's mean diagonal if needed, then a backtracking line search on the merit
a_total² + ρ × (largest relative violation of the path limits and the end condition) of the
TRUE simulated trajectory. Stops when the relative
decrease of the merit is below ``rtol`` with the trajectory feasible to ``path_tolerance``.
Measured figures: ``docs/guide/bound.md`` and the tests of ``tests/bound/test_nonlinear.py``.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace

import numpy as np

from loader_model.bound.constrained import path_limits
from loader_model.bound.dense_qp import QPResult
from loader_model.bound.problem import BoundProblem
from loader_model.bound.riccati_qp import mean_condensed_curvature, solve_riccati_qp
from loader_model.bound.stage_model import stage_qp
from loader_model.bound.trajectory import Trajectory, linearise, rollout
from loader_model.bound.weighting import SeatWeighting, seat_weighting
from loader_model.simulation.result import SimulationResult

__all__ = ["NonlinearBound", "end_residual", "path_violation", "solve_nonlinear_bound"]

#: Most command values of one nonlinear bound (20 s of 10 ms commands): memory and time grow
#: linearly with N (the linearisation holds K_s (n_x + n_y) n_x doubles, about 0.2 GB at 20 s;
#: one SQP iteration took about 6 s at 12 s).
MAX_NONLINEAR_INTERVALS = 2000
#: Relative tolerance of each QP (:mod:`~loader_model.bound.dense_qp`'s residuals and gap).
QP_TOLERANCE = 1e-8
#: Levenberg-Marquardt damping tries per linearisation (1e-9, 1e-6, 1e-3 of the mean curvature).
DAMPING_TRIES = 3
#: Penalty weight of the merit's constraint violation, relative to the warm start's a_total².
PENALTY = 10.0
#: The penalty weight is raised to this multiple of the QP's multiplier sum when below it.
MULTIPLIER_MARGIN = 2.0


@dataclass(frozen=True)
class NonlinearBound:
    """The nonlinear bound (module notes).

    Attributes
    ----------
    command : numpy.ndarray
        (N,) optimal command deviation from u0, m³/rev (as the linear bounds report it).
    a_total_m_s2 : float
        a_total (Eq. 50) of the optimal simulated trajectory.
    seat : numpy.ndarray
        (K_s, axes) its seat samples (vibration about rest).
    path : numpy.ndarray
        (K_s, len(PATH_SIGNALS) + 1) its bounded signals and V̇_p.
    max_violation : float
        Largest path-limit violation on it relative to each limit (negative: inside).
    end_residual : numpy.ndarray
        Its end values minus the targets (:attr:`~loader_model.bound.problem.BoundProblem.
        end_targets`).
    iterations : int
        SQP iterations (linearisations).
    qp_iterations : int
        Interior-point iterations over all QPs.
    solve_s : float
        Wall time, s.
    converged : bool
        The relative-decrease test held, or no damped step decreased the merit further with
        the trajectory feasible to ``path_tolerance`` (``status`` says which).
    warm_a_total_m_s2 : float
        a_total of the warm start's command table.
    history : tuple of float
        a_total after each iteration.
    status : str
        Why it stopped.
    penalty_weight : float
        ρ of the merit at the end (raised from ``PENALTY`` a_warm² to ``MULTIPLIER_MARGIN``
        times the QP's multiplier sum when that was larger).
    timings_s : dict of str to float
        Wall time by part: ``linearise``, ``model`` (the sensitivity sweep), ``qp`` and
        ``rollout`` (the line search's simulations), s.
    restorations : int
        Accepted restoration steps (the nearest point meeting the linearised limits, tried when
        no damped step of the full QP lowered the merit on an infeasible trajectory).
    """

    command: np.ndarray
    a_total_m_s2: float
    seat: np.ndarray
    path: np.ndarray
    max_violation: float
    end_residual: np.ndarray
    iterations: int
    qp_iterations: int
    solve_s: float
    converged: bool
    warm_a_total_m_s2: float
    history: tuple[float, ...] = ()
    status: str = ""
    restorations: int = 0
    penalty_weight: float = 0.0
    timings_s: dict[str, float] = field(default_factory=dict)

    @property
    def time_per_iteration_s(self) -> float:
        """Wall time per SQP iteration, s."""
        return self.solve_s / max(self.iterations, 1)


@contextmanager
def _timed(timings: dict[str, float], part: str) -> Iterator[None]:
    start = time.perf_counter()
    try:
        yield
    finally:
        timings[part] = timings.get(part, 0.0) + time.perf_counter() - start


def path_violation(problem: BoundProblem, trajectory: Trajectory) -> float:
    """Largest violation of the path limits on ``trajectory`` relative to each limit."""
    static, lower, upper, scale = path_limits(problem)
    deviation = trajectory.path() - static
    return float(np.max(np.maximum(deviation - upper, lower - deviation) / scale))


def end_residual(problem: BoundProblem, trajectory: Trajectory) -> np.ndarray:
    """End values of ``trajectory`` minus the end targets (boom position, V_p, V̇_p)."""
    from loader_model.plant.plant import OUTPUT_NAMES, STATE_NAMES

    values = []
    for name, target in problem.end_targets.items():
        if name in STATE_NAMES:
            values.append(trajectory.states[-1, STATE_NAMES.index(name)] - target)
        else:
            values.append(trajectory.outputs[-1, OUTPUT_NAMES.index(name)] - target)
    return np.array(values)


def _end_scale(problem: BoundProblem) -> np.ndarray:
    stroke = problem.plant.parameter("stroke")
    return np.array([stroke, problem.u_bounds[1], problem.rate_limit])


def _multiplier_sum(result: QPResult, end_scale: np.ndarray) -> float:
    """Σ|λ| of the QP's path rows and end rows in units of the merit's relative violation (the
    path rows are scaled by their limits, the end rows are physical: times ``end_scale``): an
    ℓ∞ penalty weight above it makes the QP's step a descent direction of the merit."""
    rows = np.sum(np.abs(result.row_multipliers)) if result.row_multipliers is not None else 0.0
    ends = result.equality_multipliers
    return float(rows + (np.sum(np.abs(ends) * end_scale) if ends is not None else 0.0))


def _warm_command(problem: BoundProblem, warm: SimulationResult | np.ndarray) -> np.ndarray:
    if isinstance(warm, SimulationResult):
        if warm.time_s.size < problem.periods:
            raise ValueError(
                f"warm: the run has {warm.time_s.size} rows; the problem needs {problem.periods}"
            )
        table = warm["V_p_ref"][: problem.periods].reshape(problem.intervals, -1).mean(axis=1)
    else:
        table = np.asarray(warm, dtype=float).ravel()
        if table.size != problem.intervals:
            raise ValueError(f"warm: {table.size} commands; the problem has {problem.intervals}")
    return np.clip(table, *problem.u_bounds)


def solve_nonlinear_bound(
    problem: BoundProblem,
    warm: SimulationResult | np.ndarray,
    *,
    weighting: SeatWeighting | None = None,
    max_iterations: int = 30,
    rtol: float = 1e-4,
    path_tolerance: float = 1e-3,
    progress: bool = False,
) -> NonlinearBound:
    """The nonlinear bound of ``problem`` from ``warm`` (module notes).

    Parameters
    ----------
    problem : BoundProblem
        Grid, road and limits.
    warm : SimulationResult or numpy.ndarray
        A controller's run over the same road (its command averaged over each interval) or an
        absolute command table (N values, m³/rev); clipped to the command bounds.
    max_iterations : int
        Most SQP iterations, ≥ 1.
    rtol : float
        Stop when the merit decreases by less than this fraction in an iteration, in (0, 0.1].
    path_tolerance : float
        Violation of the path limits and end condition accepted at the end, relative to each
        limit, in (0, 0.1].
    """
    if (
        isinstance(max_iterations, bool)
        or not isinstance(max_iterations, int)
        or max_iterations < 1
    ):
        raise ValueError(f"max_iterations must be an integer >= 1; got {max_iterations!r}")
    if problem.intervals > MAX_NONLINEAR_INTERVALS:
        raise ValueError(
            f"problem: {problem.intervals} command values ({problem.duration_s:g} s); the "
            f"nonlinear bound takes at most {MAX_NONLINEAR_INTERVALS} (MAX_NONLINEAR_INTERVALS): "
            "shorten the course (duration_s) or lengthen hold_periods"
        )
    for name, value in (("rtol", rtol), ("path_tolerance", path_tolerance)):
        if not 0.0 < value <= 0.1:
            raise ValueError(f"{name} must be in (0, 0.1]; got {value!r}")
    from tqdm import tqdm

    start = time.perf_counter()
    weighting = weighting or seat_weighting(problem.period_s)
    u0, scale = problem.plant.u0, problem.u_bounds[1]
    limits = path_limits(problem)
    end_scale = _end_scale(problem)
    command = _warm_command(problem, warm)
    trajectory = rollout(problem, command)
    a_warm = weighting.a_total(trajectory.seat())
    rho = PENALTY * a_warm**2

    def infeasibility(run: Trajectory) -> float:
        ends = np.max(np.abs(end_residual(problem, run)) / end_scale)
        return max(path_violation(problem, run), 0.0, float(ends))

    def merit(run: Trajectory) -> tuple[float, float, float]:
        a_total = weighting.a_total(run.seat())
        violation = infeasibility(run)
        return a_total**2 + rho * violation, a_total, violation

    current, a_total, violation = merit(trajectory)
    history, qp_iterations, converged, iterations = [a_total], 0, False, 0
    restorations, timings = 0, {}
    status = "max_iterations reached"
    bar = tqdm(total=max_iterations, desc="nonlinear bound", unit="it", disable=not progress)
    with bar:
        for _ in range(max_iterations):
            iterations += 1
            with _timed(timings, "linearise"):
                linearisation = linearise(problem, trajectory)
            with np.errstate(over="ignore", invalid="ignore"), _timed(timings, "model"):
                model = stage_qp(problem, trajectory, linearisation, weighting, scale, limits)
                curvature = mean_condensed_curvature(model)
            if not all(
                np.all(np.isfinite(x)) for x in (model.hessian, model.rows, model.transition)
            ) or not np.isfinite(curvature):
                status = "sensitivities overflow (the linearised period is unstable along the run)"
                break
            accepted, damping = False, 1e-9
            for attempt in range(DAMPING_TRIES + 1):
                hessian = model.hessian.copy()
                hessian[:, -1, -1] += damping * curvature
                # the last attempt is the restoration step: the nearest point (in the damped
                # Hessian's metric) that meets the linearised limits and end condition
                restore = attempt == DAMPING_TRIES
                if restore and violation <= path_tolerance:
                    break
                damped = replace(
                    model,
                    hessian=hessian,
                    gradient=0.0 * model.gradient if restore else model.gradient,
                )
                try:
                    # a failed QP: damp more
                    with np.errstate(over="raise", invalid="raise"), _timed(timings, "qp"):
                        result, _ = solve_riccati_qp(damped, tolerance=QP_TOLERANCE)
                except (np.linalg.LinAlgError, FloatingPointError):
                    damping *= 1e3
                    continue
                qp_iterations += result.iterations
                if not restore:  # an exact penalty needs ρ above the QP's multipliers
                    needed = MULTIPLIER_MARGIN * _multiplier_sum(result, end_scale)
                    if needed > rho:
                        rho = needed
                        current = a_total**2 + rho * violation
                step = result.u * scale
                alpha = 1.0
                while alpha > 1e-2 and not accepted:
                    with _timed(timings, "rollout"):
                        candidate = rollout(problem, command + alpha * step)
                    value, a_new, v_new = merit(candidate)
                    accepted = value < current
                    alpha = alpha if accepted else 0.5 * alpha
                if accepted:
                    restorations += restore
                    break
                if not restore:
                    damping *= 1e3
            if not accepted:
                converged = violation <= path_tolerance
                status = "stalled: no merit decrease along the damped steps" + (
                    ", feasible to path_tolerance" if converged else ", infeasible"
                )
                break
            decrease = (current - value) / current
            command, trajectory = command + alpha * step, candidate
            current, a_total, violation = value, a_new, v_new
            history.append(a_total)
            bar.set_postfix_str(
                f"a_total {a_total:.5f}, violation {violation:.1e}, α {alpha:g}, ρ {rho:.3g}"
            )
            bar.update()
            if decrease < rtol and violation <= path_tolerance:
                converged, status = True, "converged"
                break
    return NonlinearBound(
        command=command - u0,
        a_total_m_s2=a_total,
        seat=trajectory.seat(),
        path=trajectory.path(),
        max_violation=path_violation(problem, trajectory),
        end_residual=end_residual(problem, trajectory),
        iterations=iterations,
        qp_iterations=qp_iterations,
        solve_s=time.perf_counter() - start,
        converged=converged,
        warm_a_total_m_s2=a_warm,
        history=tuple(history),
        status=status,
        restorations=restorations,
        penalty_weight=rho,
        timings_s=timings,
    )
