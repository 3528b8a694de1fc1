"""The passive run's energy balance (issue 12): road work + pump work + charge-line work =
dissipation + change of stored energy, over the paper's course at 9 km/h with the accumulator
connected and the pump holding its static command (loader_model/simulation/energy_balance.py).

The issue asks for 1 % of the largest term. Measured on the development machine (whole course,
15.3 s; CVODES at rtol 1e-10, atol 1e-12; the fast simulator's ROS2 at 1 ms, trapezoid over its
rows): empty bucket 1.5e-3 J (3.4e-8) and 187 J (4.2e-3); full bucket 1.5e-3 J (2.2e-8) and
−264 J (3.7e-3). The fast simulator's residual is its own integration error: it shrinks with
substeps (−130, −55, −23 J at 2, 4, 8, full bucket), the trapezoid on CVODES's 1 ms rows leaves
−10 J, and it builds up at about −5 J per ms where the rear tyre's load climbs a board's edge.
On a 2-core AMD EPYC a failed step at the tyres' stick-slip switch put 461 J into one period
(full bucket, 4.705 s: 3.5e-2 of the road work; empty 1.4e-2); with such periods integrated
again (loader_model.simulation.refinement) the residual there is 13.6 J (8.0e-4, empty) and
−2.9 J (2.2e-4, full).
"""

from __future__ import annotations

import pytest

from loader_model.experiments.trials import plant_for
from loader_model.simulation.courses import paper_course
from loader_model.simulation.energy_balance import (
    EnergyBalance,
    reference_energy_balance,
    simulated_energy_balance,
)
from loader_model.simulation.simulator import course_input, simulate


def _check(balance: EnergyBalance, tolerance: float) -> None:
    assert balance.input_work_J["road"] > 1000.0  # joules: the boards really did work
    assert balance.dissipated_J["tyres"] > 50.0
    assert balance.input_work_J["disturbance"] == 0.0
    assert balance.relative_residual < tolerance, balance.table()


def _passive_run(load: str, duration_s: float | None) -> tuple[EnergyBalance, EnergyBalance]:
    params = plant_for("passive", load)
    road = course_input(paper_course(9.0), params)
    reference = reference_energy_balance(road, params, duration_s=duration_s)
    result = simulate(road, params, duration_s=duration_s)
    return reference, simulated_energy_balance(result, road, params)


def test_passive_run_balances_over_the_first_board() -> None:
    """First 2 s, front axle over the first board (empty bucket). Measured with the default tandem
    cam: CVODES 3.5e-6 J (1.2e-9 of the pump's 2783 J), fast simulator 2.0 J (6.9e-4); road work
    1054 J, tyres 59 J (rigid discs: 8.8e-6 J, 18.4 J (5.5e-3); road 1649 J, tyres 326 J)."""
    reference, fast = _passive_run("empty", 2.0)
    _check(reference, 1e-7)
    _check(fast, 1e-2)
    for name, joules in reference.input_work_J.items():  # both see the same run
        assert fast.input_work_J[name] == pytest.approx(joules, rel=2e-2, abs=1.0)


@pytest.mark.slow
@pytest.mark.parametrize("load", ["empty", "full"])
def test_passive_run_balances_over_the_paper_course(load: str) -> None:
    reference, fast = _passive_run(load, None)
    _check(reference, 1e-6)
    _check(fast, 1e-2)
