r"""The clairvoyant bound of the machine: Gauss-Newton SQP in single shooting on the command table.

Each iterate's trajectory is the simulator's (:func:`~loader_model.bound.trajectory.rollout`:
the simulator's compiled period, substeps, road table and seat signals), so the optimiser's
a_total (Eq. 49, 50, the sampled weightings of :mod:`~loader_model.bound.weighting`) is the one
the optimal command gives when replayed open loop (:func:`~loader_model.bound.replay.replay`).
One iteration: linearise along the trajectory with the flow's sensitivities
(:func:`~loader_model.bound.trajectory.linearise`), build the Gauss-Newton QP in stage form
(:func:`~loader_model.bound.stage_model.stage_qp`: a stage per few command intervals, every path
sample a row of its stage), solve it with the command box, the end condition and all path
limits by the Riccati interior point (:func:`~loader_model.bound.riccati_qp.solve_riccati_qp`,
cost linear in the course's length; about 4 command intervals per stage,
:func:`~loader_model.bound.stage_model.stage_block`), with Levenberg-Marquardt damping
relative to the condensed Hessian's mean diagonal if needed, then a backtracking line search on
the merit a_total² + ρ × (largest relative violation of the path limits and the end condition) of the
TRUE simulated trajectory. When the full step raises the simulated violation, the QP is
solved once more with its rows shifted by the linearisation's error at that step (the
second-order correction, :func:`~loader_model.bound.stage_model.corrected_qp`) and that step
is tried; on the 6 s paper course this took the solve from 1.3040 m/s², infeasible by 2.0e-3
of a limit, to 1.2691, feasible, in the same 30 iterations. Stops when the relative
decrease of the merit is below ``rtol`` with the trajectory feasible to ``path_tolerance``;
otherwise it measures the merit's noise floor at the end
(:func:`~loader_model.bound.feasibility.merit_noise_floor`).
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
from loader_model.bound.feasibility import (
    end_residual,
    end_scale,
    merit_noise_floor,
    path_violation,
)
from loader_model.bound.problem import BoundProblem
from loader_model.bound.riccati_qp import solve_riccati_qp
from loader_model.bound.stage_form import StageQP, mean_condensed_curvature
from loader_model.bound.stage_model import corrected_qp, stage_block, stage_qp
from loader_model.bound.trajectory import DivergedRollout, Trajectory, linearise, rollout
from loader_model.bound.weighting import SeatWeighting, seat_weighting
from loader_model.simulation.result import SimulationResult

__all__ = ["NonlinearBound", "solve_nonlinear_bound"]

#: Most command values of one nonlinear bound (20 s of 10 ms commands): memory and time grow
#: linearly with N (the linearisation holds K_s (n_x + n_y) n_x doubles, about 0.2 GB at 20 s;
#: one SQP iteration took about 6 s at 12 s).
MAX_NONLINEAR_INTERVALS = 2000
#: Relative tolerance of each QP (:mod:`~loader_model.bound.dense_qp`'s residuals and gap).
#: Every step is judged by the simulated merit, whose noise floor on 12 s is 5e-5 of a_total
#: (:func:`~loader_model.bound.feasibility.merit_noise_floor`), so the QP's objective needs no
#: more than 1e-6; at 1e-8 the dual residual met its round-off floor (4e-8 ... 0.5 once the
#: barrier terms reached 1e16) and QPs ran to their iteration limit (measured on the 11.55 s
#: paper course at 18 km/h: 8 of 57 QPs, 100 of the solve's 324 s).
QP_TOLERANCE = 1e-6
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
        ``rollout`` (the line search's simulations) and, when it did not converge, ``noise``
        (:func:`~loader_model.bound.feasibility.merit_noise_floor`), s.
    restorations : int
        Accepted restoration steps (the nearest point meeting the linearised limits, tried when
        no damped step of the full QP lowered the merit on an infeasible trajectory).
    corrections : int
        Accepted second-order corrections (module notes).
    noise_floor : tuple of float or None
        When it did not converge: how far the simulated a_total (relative) and the largest
        violation (in units of the limits) spread over round-off-sized perturbations of the
        final command (:func:`~loader_model.bound.feasibility.merit_noise_floor`); a decrease
        below it cannot be confirmed by simulation.
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
    corrections: int = 0
    noise_floor: tuple[float, float] | None = None

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


def _multiplier_sum(result: QPResult, end_units: np.ndarray) -> float:
    """Σ|λ| of the QP's path rows and end rows in units of the merit's relative violation (the
    path rows are scaled by their limits, the end rows are physical: times ``end_units``): an
    ℓ∞ penalty weight above it makes the QP's step a descent direction of the merit."""
    rows = np.sum(np.abs(result.row_multipliers)) if result.row_multipliers is not None else 0.0
    ends = result.equality_multipliers
    return float(rows + (np.sum(np.abs(ends) * end_units) if ends is not None else 0.0))


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
    end_units = end_scale(problem)
    command = _warm_command(problem, warm)
    block = stage_block(problem.intervals)
    trajectory = rollout(problem, command)
    a_warm = weighting.a_total(trajectory.seat())
    rho = PENALTY * a_warm**2

    def infeasibility(run: Trajectory) -> float:
        ends = np.max(np.abs(end_residual(problem, run)) / end_units)
        return max(path_violation(problem, run), 0.0, float(ends))

    def merit(run: Trajectory) -> tuple[float, float, float]:
        a_total = weighting.a_total(run.seat())
        violation = infeasibility(run)
        return a_total**2 + rho * violation, a_total, violation

    current, a_total, violation = merit(trajectory)

    def _trial(table: np.ndarray) -> Trajectory | None:
        """The simulated run of a trial table, None where it diverged (a rejected step)."""
        with _timed(timings, "rollout"):
            try:
                return rollout(problem, table)
            except DivergedRollout:
                return None

    def _second_order_step(
        qp: StageQP, w: np.ndarray, candidate: Trajectory
    ) -> tuple[np.ndarray | None, int]:
        """The corrected QP's step (module notes) and its interior-point iterations."""
        corrected = corrected_qp(qp, w, problem, trajectory, candidate, limits)
        try:
            with np.errstate(over="raise", invalid="raise"), _timed(timings, "qp"):
                result, _ = solve_riccati_qp(corrected, tolerance=QP_TOLERANCE)
        except (np.linalg.LinAlgError, FloatingPointError):
            return None, 0
        # an infeasible corrected QP (its rows shifted past what the command can meet) gives
        # no step worth a simulation
        return (result.u if result.converged else None), result.iterations

    history, qp_iterations, converged, iterations = [a_total], 0, False, 0
    restorations, corrections, timings = 0, 0, {}
    status = "max_iterations reached"
    bar = tqdm(total=max_iterations, desc="nonlinear bound", unit="it", disable=not progress)
    with bar:
        for _ in range(max_iterations):
            iterations += 1
            with _timed(timings, "linearise"):
                linearisation = linearise(problem, trajectory, compile_missing=True)
            with np.errstate(over="ignore", invalid="ignore"), _timed(timings, "model"):
                model = stage_qp(
                    problem, trajectory, linearisation, weighting, scale, limits, block
                )
                inputs = np.arange(model.states, model.states + block)
                curvature = mean_condensed_curvature(model)
            if not all(
                np.all(np.isfinite(x)) for x in (model.hessian, model.rows, model.transition)
            ) or not np.isfinite(curvature):
                status = "sensitivities overflow (the linearised period is unstable along the run)"
                break
            accepted, damping = False, 1e-9
            for attempt in range(DAMPING_TRIES + 1):
                hessian = model.hessian.copy()
                hessian[:, inputs, inputs] += damping * curvature
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
                        result, w = solve_riccati_qp(damped, tolerance=QP_TOLERANCE)
                except (np.linalg.LinAlgError, FloatingPointError):
                    damping *= 1e3
                    continue
                qp_iterations += result.iterations
                if not restore:  # an exact penalty needs ρ above the QP's multipliers
                    needed = MULTIPLIER_MARGIN * _multiplier_sum(result, end_units)
                    if needed > rho:
                        rho = needed
                        current = a_total**2 + rho * violation
                step = result.u * scale
                alpha = 1.0
                while alpha > 1e-2 and not accepted:
                    candidate = _trial(command + alpha * step)
                    if candidate is None:  # the step's run diverged: shorten it
                        alpha *= 0.5
                        continue
                    value, a_new, v_new = merit(candidate)
                    accepted = value < current
                    # the full step raised the simulated violation: correct the rows by the
                    # linearisation's error there and try once more (module notes)
                    if not accepted and alpha == 1.0 and v_new > max(violation, 0.0):
                        corrected, used = _second_order_step(damped, w, candidate)
                        qp_iterations += used
                        soc_run = None if corrected is None else _trial(command + corrected * scale)
                        if soc_run is not None:
                            soc_value, soc_a, soc_v = merit(soc_run)
                            if soc_value < current:
                                accepted, corrections = True, corrections + 1
                                step, candidate = corrected * scale, soc_run
                                value, a_new, v_new = soc_value, soc_a, soc_v
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
    noise = None
    if not converged:
        with _timed(timings, "noise"):
            noise = merit_noise_floor(problem, command, weighting)
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
        corrections=corrections,
        noise_floor=noise,
    )
