"""Shared fixtures: a loader in the paper's sign layout (DESIGN.md errata 2)."""

from __future__ import annotations

import os
from collections.abc import Iterator

import pytest


@pytest.fixture(scope="session", autouse=True)
def machine_cache(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """The runtime's machine cache ($XDG_CACHE_HOME) in a temporary folder, not the user's.

    The compiled periods' cache (``loader_model.simulation.compiled``, which also follows
    $XDG_CACHE_HOME) stays where it was: the workers share the periods that
    :func:`pytest_configure` compiled before they started, and a later run reuses them.
    """
    from loader_model.simulation.compiled import cache_directory

    names = ("XDG_CACHE_HOME", "LOADER_MODEL_CACHE_DIR")
    before = {name: os.environ.get(name) for name in names}
    compiled = cache_directory()
    os.environ["LOADER_MODEL_CACHE_DIR"] = "off" if compiled is None else str(compiled)
    os.environ["XDG_CACHE_HOME"] = str(tmp_path_factory.mktemp("cache"))
    yield
    for name, value in before.items():
        if value is None:
            os.environ.pop(name, None)
        else:
            os.environ[name] = value


#: A plausible 3.5 t skid-steer whose points follow the layout the paper's signs assume:
#: A ahead of and below H, B behind and below H, C and D behind and above H, G ahead of and
#: below D, E behind and above G. Not the calibrated default loader; a fixed test case.
PAPER_LAYOUT = {
    "m_1": 2700.0,
    "J_1": 1800.0,
    "m_2": 800.0,
    "J_2": 450.0,
    "g": 9.81,
    "A_x": 0.55,
    "A_y": -0.30,
    "B_x": -0.62,
    "B_y": -0.28,
    "C_x": -0.70,
    "C_y": 0.20,
    "D_x": -0.85,
    "D_y": 0.95,
    "S_x": -0.35,
    "S_y": 0.55,
    "N_x": 0.80,
    "N_y": 0.10,
    "E_x": 0.20,
    "E_y": 0.75,
    "G_x": 0.90,
    "G_y": 0.35,
    "k_Ax": 3.0e5,
    "k_Ay": 6.0e5,
    "c_Ax": 2.0e3,
    "c_Ay": 3.0e3,
    "k_Bx": 3.2e5,
    "k_By": 6.5e5,
    "c_Bx": 2.1e3,
    "c_By": 3.2e3,
    "mu_road": 0.8,
    "F_transition": 200.0,
    "tau_slip": 0.01,
}


@pytest.fixture
def paper_layout() -> dict[str, float]:
    """Parameter values of a loader in the paper's sign layout (static loads left out)."""
    return dict(PAPER_LAYOUT)


def pytest_configure(config: pytest.Config) -> None:
    """Before the xdist workers start: compile the periods most tests share into the machine's
    cache, two at a time, so that the workers load them instead of each compiling the same
    ones (``loader_model.simulation.compiled``). Nothing to do when the cache holds them or is
    off, or inside a worker."""
    if hasattr(config, "workerinput") or config.getoption("numprocesses", None) in (None, 0):
        return
    from concurrent.futures import ThreadPoolExecutor

    from loader_model.simulation.compiled import cache_directory

    if cache_directory() is None:
        return
    with ThreadPoolExecutor(2) as pool:
        list(pool.map(_compile_shared_period, range(4)))


def _compile_shared_period(index: int) -> None:
    """The default periods (4 substeps) of the hold, virtual-accumulator and skyhook
    controllers and the hold's error-controlled one (compile_period caches them)."""
    from loader_model.experiments.trials import controller_arguments, plant_for
    from loader_model.simulation.controllers import hold_command_controller
    from loader_model.simulation.simulator import DEFAULT_SUBSTEPS
    from loader_model.simulation.stepper import compile_period

    if index == 0:
        compile_period(hold_command_controller(), substeps=None)
    elif index == 1:
        compile_period(hold_command_controller(), substeps=DEFAULT_SUBSTEPS)
    else:
        name = ("virtual-accumulator", "skyhook")[index - 2]
        controller = controller_arguments(name, "empty", plant_for(name, "empty"))["controller"]
        compile_period(controller, substeps=DEFAULT_SUBSTEPS)
