"""One resolve and one equilibrium per plant (issue 20, item 3): call counts on the run paths.

Before the scenario, one Table 6 trial computed the static equilibrium of its plant four times
(road input, the controller's settings vector and fixed point, the simulator's start) and
``loader-model simulate --controller skyhook`` from files resolved and checked the files twice.
Each test wraps the functions that resolve, check and solve in every loaded ``loader_model``
module that holds them (so module-level and lazy imports are both counted) and follows one run.
"""

from __future__ import annotations

import collections
import dataclasses
import functools
import importlib
import sys
from pathlib import Path

import pytest

import loader_model

DATA = Path(loader_model.__file__).parent / "data"
#: (module, function) pairs counted: the combination check, the vector, the equilibrium.
COUNTED = (
    ("loader_model.vehicle.statics", "resolve_machine"),
    ("loader_model.vehicle.statics", "check_combination"),
    ("loader_model.plant.plant_parameters", "plant_parameter_vector"),
    ("loader_model.plant.equilibrium", "static_state"),
)


@pytest.fixture
def calls(monkeypatch) -> collections.Counter:
    """A Counter of calls to :data:`COUNTED`, wrapped wherever a loaded module holds them."""
    for name in (
        "loader_model.experiments.trials",
        "loader_model.robustness.runner",
        "loader_model.simulation.scenario",
        "loader_model.simulation.simulator",
        "loader_model.control.comfort_plant",
        "loader_model.commands.simulate_command",
    ):
        importlib.import_module(name)
    counter: collections.Counter = collections.Counter()
    for module_name, function_name in COUNTED:
        original = getattr(importlib.import_module(module_name), function_name)

        def wrapper(*args, _original=original, _name=function_name, **kwargs):
            counter[_name] += 1
            return _original(*args, **kwargs)

        functools.update_wrapper(wrapper, original)
        for module in list(sys.modules.values()):
            if getattr(module, "__name__", "").startswith("loader_model") and (
                getattr(module, function_name, None) is original
            ):
                monkeypatch.setattr(module, function_name, wrapper)
    return counter


def _counts(counter: collections.Counter) -> dict[str, int]:
    return {name: counter[name] for _, name in COUNTED}


def _once(resolves: int, equilibria: int) -> dict[str, int]:
    return {
        "resolve_machine": resolves,
        "check_combination": resolves,
        "plant_parameter_vector": resolves,
        "static_state": equilibria,
    }


def test_one_trial_resolves_once_and_reuses_the_scenario(calls, monkeypatch) -> None:
    """A fresh process's first trial of a condition: one resolve, one equilibrium; the next trial
    of it, and a trial of another controller on the same plant: none (the cached scenario).
    The virtual accumulator runs on the skyhook's circuit; baseline and passive on closed
    load-holding valves (one plant each, passive with the accumulator)."""
    from loader_model.experiments import trials

    monkeypatch.setattr(trials, "_PLANTS", {})
    monkeypatch.setattr(trials, "_SCENARIOS", {})
    specs = trials.trial_specs(
        5, 2, speeds_kmh=(9.0,), loads=("full",), controllers=("skyhook",), duration_s=3.0
    )
    trials.run_trial(specs[0])
    assert _counts(calls) == _once(1, 1)
    calls.clear()
    trials.run_trial(specs[1])
    assert _counts(calls) == _once(0, 0)
    trials.run_trial(dataclasses.replace(specs[0], controller="virtual-accumulator"))
    assert _counts(calls) == _once(0, 0)  # open valves, accumulator shut: the same plant
    baseline = dataclasses.replace(specs[0], controller="baseline")
    trials.run_trial(baseline)  # closed load-holding valves: another plant
    assert _counts(calls) == _once(1, 1)
    calls.clear()
    trials.run_trial(dataclasses.replace(baseline, trial=1))
    assert _counts(calls) == _once(0, 0)
    trials.run_trial(dataclasses.replace(specs[0], controller="passive"))
    assert _counts(calls) == _once(1, 1)  # the accumulator connected: another plant


def test_simulate_from_files_resolves_once(calls) -> None:
    """A scenario from the TOML files: the files resolved and checked once, one equilibrium for
    the road input, the controller's settings and fixed point and the simulator's start."""
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.scenario import resolve_scenario
    from loader_model.simulation.simulator import course_input, simulate

    scenario = resolve_scenario(
        DATA / "default_loader.toml", DATA / "load_full.toml", controller="skyhook"
    )
    result = simulate(course_input(paper_course(9.0), scenario), scenario, duration_s=0.2)
    assert result.time_s.size == 200
    assert _counts(calls) == _once(1, 1)


@pytest.mark.parametrize("controller", ["baseline", "skyhook"])
def test_the_simulate_command_from_files_resolves_once(calls, capsys, controller: str) -> None:
    """``loader-model simulate --params FILE --load FILE``: one resolve, one equilibrium (it
    resolved the files twice and solved the equilibrium four times for the skyhook)."""
    from loader_model.cli import main

    code = main(
        ["simulate", "--params", str(DATA / "default_loader.toml"),
         "--load", str(DATA / "load_full.toml"), "--controller", controller, "--duration", "3"]
    )  # fmt: skip
    assert code == 0 and "a_total" in capsys.readouterr().out
    assert _counts(calls) == _once(1, 1)


@pytest.mark.slow  # 11.3 s measured: one robustness sample of every controller
def test_a_robustness_sample_solves_one_equilibrium_per_plant(calls) -> None:
    """One sample, every controller and the pole margin of the gains: one resolve, and one
    equilibrium per distinct plant: open load-holding valves for the active controllers, closed
    for the baseline, closed with the accumulator connected for passive."""
    from loader_model.robustness.gains import resolve_gains
    from loader_model.robustness.runner import run_sample
    from loader_model.robustness.sampling import sample_specs
    from loader_model.robustness.study import parse_study

    study = parse_study(
        """
[study]
name = "calls"
seed = 3
samples = 1
duration_s = 3.0
[conditions]
speeds_kmh = [18.0]
loads = ["empty"]
[controllers]
compare = ["passive", "virtual-accumulator", "skyhook"]
[parameters]
"hydraulics.bulk_modulus" = { distribution = "uniform", low = 0.8e9, high = 1.8e9, unit = "Pa" }
"sensors.f_Hy.offset" = { distribution = "uniform", low = -0.1, high = 0.1, unit = "m/s^2" }
"""
    )
    gains = resolve_gains(study)
    (spec,) = sample_specs(study)
    calls.clear()
    rows = run_sample(study, gains, spec)
    assert [row["failed"] for row in rows] == [False] * 4, [row["reason"] for row in rows]
    assert _counts(calls) == _once(1, 3)
