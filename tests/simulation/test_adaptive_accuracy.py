"""The error-controlled substeps against CVODES at rtol 1e-10, beside four fixed substeps.

Every controller, both loads, the paper's course at 9 and 18 km/h, and an ISO 8608 class D road
(60 m, seed 1) at 20 km/h (empty baseline, full skyhook): the seat-pad signals (f_Px, f_Py, θ̈1)
in the normalised r.m.s. norm ‖s − s_ref‖_rms / ‖s_ref − s_ref(0)‖_rms, the substeps chosen by
their error (``substeps=None``, :mod:`loader_model.simulation.adaptive`) and the default four
fixed substeps on the same run. Measured on the shared 2-core machine (the simulation guide has
the figures): the chosen substeps' error is 0.21 to 1.19 times the four substeps' per signal
(median 0.96). Single events dominate both errors
(a tyre's stick-slip or lift-off resolved a little differently: at a looser tolerance 74 % of one
run's error energy fell in one 0.5 s window), and which events shift turns on the last digits of
the arithmetic, so the test allows 1.5 times per signal and a median of the ratios of 1.1.
At 18 km/h the baseline parts from the reference by 28-71 % with either stepping (the run is
that sensitive: it changes its course after a board), so those two runs enter the median only.

Four substeps sharing their period's Jacobian (``jacobian="period"``) are compared too (the
simulation guide's table): as accurate in the median, not on every run.

Energy (passive, whole 9 km/h course, trapezoid over the rows: ``simulation.energy_balance``):
the chosen substeps' residual measured 2.0e-4 / 1.8e-4 of the largest term (empty / full) against
8.0e-4 / 2.2e-4 with four substeps; the test asks that it be no worse than 1.5 times theirs.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from loader_model.experiments.trials import controller_arguments, plant_for
from loader_model.plant.plant import OUTPUT_NAMES
from loader_model.simulation.courses import iso8608_course, paper_course
from loader_model.simulation.energy_balance import simulated_energy_balance
from loader_model.simulation.reference import reference_simulation
from loader_model.simulation.simulator import course_input, simulate

SEAT = ("f_Px", "f_Py", "thetadd_1")
CONTROLLERS = ("baseline", "passive", "virtual-accumulator", "skyhook")
#: Runs whose trajectory the stepping's last digits change (module notes): in the median only.
SENSITIVE = {("paper 18", "empty", "baseline"), ("paper 18", "full", "baseline")}


def _cases() -> list[tuple[str, str, str]]:
    paper = [
        (f"paper {speed}", load, controller)
        for speed in (9, 18)
        for load in ("empty", "full")
        for controller in CONTROLLERS
    ]
    return [*paper, ("class D 20", "empty", "baseline"), ("class D 20", "full", "skyhook")]


def _course(name: str):
    if name.startswith("paper"):
        return paper_course(float(name.split()[1]))
    return iso8608_course("D", 20.0, length_m=60.0, seed=1)


#: The steppings compared (simulate's substeps, jacobian): the chosen substeps, the default four
#: fixed substeps and four fixed substeps sharing their period's Jacobian (Rosenbrock-W).
STEPPINGS = {"chosen": (None, "substep"), "fixed": (4, "substep"), "period": (4, "period")}


@functools.cache
def _errors(course: str, load: str, controller: str) -> dict[str, np.ndarray]:
    """The seat signals' normalised r.m.s. errors of each of :data:`STEPPINGS` (kept: two tests
    read them)."""
    params = plant_for(controller, load)
    road = course_input(_course(course), params)
    control = controller_arguments(controller, load, params)
    reference = reference_simulation(road, params, rtol=1e-10, **control)
    want = reference["y"][:, [OUTPUT_NAMES.index(name) for name in SEAT]]
    scale = np.sqrt(np.mean((want - want[0]) ** 2, axis=0))
    errors = {}
    for label, (substeps, jacobian) in STEPPINGS.items():
        run = simulate(road, params, substeps=substeps, jacobian=jacobian, **control)
        got = np.column_stack([run[name] for name in SEAT])
        errors[label] = np.sqrt(np.mean((got - want) ** 2, axis=0)) / scale
    return errors


def _one_jacobian_a_period_as_measured() -> None:
    """Four substeps sharing their period's Jacobian (``jacobian="period"``) against four
    fixed substeps: measured median ratio 1.04 over the 54 signals, but 8.3 times on the
    18 km/h empty skyhook run (20.5 % against 2.5 %: its trajectory parts at a lift-off) and
    2.1-2.4 times on the 9 km/h one, which is why it is not the default (the simulation guide)."""
    ratios = [
        ratio for case in _cases() for ratio in _errors(*case)["period"] / _errors(*case)["fixed"]
    ]
    assert np.median(ratios) <= 1.1, np.median(ratios)
    worst = _errors("paper 18", "empty", "skyhook")
    assert np.all(worst["period"] > 4.0 * worst["fixed"])  # the run that keeps it optional


@pytest.mark.slow  # 18 CVODES references at rtol 1e-10: about 10-25 s each on an idle core
def test_the_chosen_substeps_hold_the_accuracy_of_four_fixed_ones() -> None:
    """The chosen substeps against four fixed ones (module notes); then, on the same
    references (one test, so that parallel workers do not compute them twice), one Jacobian a
    period as measured."""
    ratios, lines = [], []
    for case in _cases():
        errors = _errors(*case)
        chosen, fixed = errors["chosen"], errors["fixed"]
        ratio = chosen / fixed
        ratios.extend(ratio)
        lines.append(f"{case}: {np.round(100 * chosen, 3)} % vs {np.round(100 * fixed, 3)} %")
        if case not in SENSITIVE:
            assert np.all(ratio <= 1.5), lines[-1]
    assert np.median(ratios) <= 1.1, "\n".join(lines)
    _one_jacobian_a_period_as_measured()


@pytest.mark.slow  # three whole-course runs each way
@pytest.mark.parametrize("load", ["empty", "full"])
def test_the_energy_residual_is_no_worse_than_four_fixed_substeps(load: str) -> None:
    params = plant_for("passive", load)
    road = course_input(paper_course(9.0), params)
    residual = {
        label: abs(
            simulated_energy_balance(
                simulate(road, params, substeps=substeps, jacobian=jacobian), road, params
            ).relative_residual
        )
        for label, (substeps, jacobian) in STEPPINGS.items()
    }
    assert residual["chosen"] <= 1.5 * residual["fixed"] + 1e-5, residual
    # one Jacobian a period: measured 5.4e-4 / 3.5e-4 (empty / full) against 8.0e-4 / 2.2e-4
    assert residual["period"] <= 2.0 * residual["fixed"] + 1e-5, residual
