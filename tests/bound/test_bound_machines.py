"""The bound on another described machine than the skid-steer: the compact wheel loader (its
generated model, pump circuit, three coordinates of the chassis and two pinned bodies), and
the refusal of a machine with the valve-controlled circuit."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.bound.linear import evaluate, linear_quadratic, solve_linear_bound
from loader_model.bound.problem import BoundProblem, bound_problem, require_pump_circuit
from loader_model.bound.weighting import seat_weighting
from loader_model.plant.layout import plant_layout
from loader_model.plant.scenario import PlantScenario, resolve_plant
from loader_model.simulation.courses import Course
from loader_model.simulation.roads import board_course
from loader_model.simulation.scenario import closed_loop
from loader_model.simulation.simulator import course_input, simulate

WHEEL_LOADER = "compact_wheel_loader"


@pytest.fixture(scope="module")
def wheel_loader() -> PlantScenario:
    return resolve_plant(None, "empty", machine=plant_layout(WHEEL_LOADER))


@pytest.fixture(scope="module")
def course() -> Course:
    """One 5 mm board (near the linearisation, as the skid-steer's bound tests), 3 s."""
    return Course(board_course(1, height_m=0.005, width_m=0.14, spacing_m=0.0), 2.5, -0.3, 2.0, "")


# slow: its first simulation of the wheel loader compiles the machine's period (seconds)
@pytest.mark.slow
def test_linear_bound_of_the_wheel_loader_is_below_its_baseline(wheel_loader, course) -> None:
    """On the wheel loader's own states and outputs: the LQ problem's free response (zero
    command deviation) reads the simulated baseline (the pump holding u0; measured 7.8e-5
    apart, held at 1e-3), and the linear bound lies far below both (measured 0.341 of the
    baseline, held at 0.5), with its end condition met (measured 3.6e-12 scaled, held at 1e-9).
    """
    road = course_input(course, wheel_loader)
    problem = bound_problem(wheel_loader, road, duration_s=3.0)
    assert problem.layout.name == WHEEL_LOADER
    lq = linear_quadratic(problem)
    free = evaluate(lq, np.zeros(problem.intervals), problem)[0]
    run = simulate(road, closed_loop(wheel_loader), duration_s=problem.duration_s)
    weighting = seat_weighting()
    seat = np.column_stack([run[s] - run[s][0] for s in weighting.signals])
    baseline = weighting.a_total(seat)
    assert baseline == pytest.approx(float(run.seat_evaluation().total_m_s2), rel=1e-3)
    assert free == pytest.approx(baseline, rel=1e-3)
    bound = solve_linear_bound(problem)
    assert bound.a_total_m_s2 < 0.5 * baseline
    assert bound.a_total_m_s2 < 0.5 * free
    assert np.max(np.abs(bound.end_residual)) < 1e-9


def test_a_valve_circuit_is_refused_in_one_line() -> None:
    """The wheel loader's mechanics with the valve-controlled circuit (no parameter file needed:
    the refusal comes before any value is read)."""
    valve = plant_layout(WHEEL_LOADER, circuit="valve")
    with pytest.raises(ValueError) as caught:
        require_pump_circuit(valve)
    message = str(caught.value)
    assert "\n" not in message
    assert f"machine {WHEEL_LOADER!r} has the valve circuit" in message
    assert "allowed: a machine with the pump circuit" in message
    require_pump_circuit(plant_layout(WHEEL_LOADER))  # its own, the pump circuit


@pytest.mark.parametrize("command", ["bound", "preview"])
def test_the_commands_refuse_a_valve_circuit(command, monkeypatch, tmp_path, capsys) -> None:
    """Exit code 2, one line naming --machine, the circuit and what is allowed; nothing
    written (the machine resolved with the valve circuit in place of its description's)."""
    from loader_model.cli import main
    from loader_model.plant import layout

    valve = plant_layout(WHEEL_LOADER, circuit="valve")
    monkeypatch.setattr(layout, "plant_layout", lambda source, circuit=None: valve)
    output = tmp_path / "out"
    assert main([command, "--machine", WHEEL_LOADER, "--output", str(output)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert f"--machine {WHEEL_LOADER!r}: machine {WHEEL_LOADER!r} has the valve circuit" in err
    assert "allowed: a machine with the pump circuit" in err
    assert not output.exists()


def test_bound_problem_reads_the_machine_layout(wheel_loader, course) -> None:
    """The end conditions and path rows are the wheel loader's (its state order has a third
    coordinate before the pump's states, so a skid-steer index would read another state)."""
    road = course_input(course, wheel_loader)
    problem: BoundProblem = bound_problem(wheel_loader, road, duration_s=3.0)
    layout = wheel_loader.layout
    targets = problem.end_targets
    assert list(targets) == ["x_piston", "V_p", "Vd_p"]
    assert targets["V_p"] == wheel_loader.x0[layout.index("V_p")]
    assert targets["Vd_p"] == wheel_loader.x0[layout.index("Vd_p")]
    assert problem.u_bounds[1] == pytest.approx(0.99 * wheel_loader.command_limit(), rel=1e-15)
    assert problem.rate_limit == pytest.approx(0.99 * wheel_loader.rate_limit(), rel=1e-15)


# slow: 1.0-1.4 s each (the rollout's period compiled or loaded per machine, 20 refined periods)
@pytest.mark.slow
@pytest.mark.parametrize("which", ["plant", "wheel_loader"])
def test_a_refined_period_of_the_rollout_is_the_machines(which, course, request, monkeypatch):
    """With every period's error estimate over the limit, each period of the rollout is
    integrated again finer on the machine's own plant (the rollout once passed the machine's
    name there and stopped): the same trajectory as the coarse one on the static command
    (measured 1.3e-19 and 2.5e-18 apart at most, absolute), held at 1e-9 of each
    state's largest value plus 1e-15."""
    from loader_model.bound.trajectory import rollout
    from loader_model.simulation import refinement

    plant = request.getfixturevalue(which)
    problem = bound_problem(plant, course_input(course, plant), duration_s=0.02)
    command = np.full(problem.intervals, plant.u0)
    coarse = rollout(problem, command)
    monkeypatch.setattr(refinement, "STEP_ERROR_LIMIT", -1.0)
    calls = []
    refine = refinement.refine_period
    monkeypatch.setattr(
        refinement, "refine_period", lambda *args: calls.append(args[2]) or refine(*args)
    )
    fine = rollout(problem, command)
    assert len(calls) == problem.periods and set(calls) == {plant.layout}
    scale = np.max(np.abs(coarse.states), axis=0)
    assert np.all(np.abs(fine.states - coarse.states) <= 1e-9 * scale + 1e-15)
