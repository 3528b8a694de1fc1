"""The machine-wide cache of compiled Functions (loader_model.simulation.compiled)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from loader_model.simulation import compiled


def _function() -> ca.Function:
    x, y = ca.SX.sym("x", 3), ca.SX.sym("y")
    return ca.Function("cache_probe", [x, y], [ca.sin(x) * y, ca.sumsqr(x)], ["x", "y"], ["s", "q"])


def _libraries(folder: Path) -> list[Path]:
    return sorted(folder.glob("cache_probe-*.so"))


def test_compiled_function_matches_the_sx_graph_and_keeps_its_names(tmp_path, monkeypatch):
    monkeypatch.setenv("LOADER_MODEL_CACHE_DIR", str(tmp_path))
    function = _function()
    library = compiled.compiled_function(function)
    assert library.name_in() == ["x", "y"] and library.name_out() == ["s", "q"]
    x = np.array([0.3, -1.2, 2.5])
    for expected, got in zip(function(x, 1.7), library(x, 1.7), strict=True):
        np.testing.assert_allclose(np.asarray(got), np.asarray(expected), rtol=1e-15, atol=0)
    assert len(_libraries(tmp_path)) == 1
    assert not list(tmp_path.glob(".build-*")), "the build folder is removed"


def test_a_second_process_loads_the_library_without_compiling(tmp_path, monkeypatch):
    real = shutil.which("cc") or shutil.which("gcc")
    assert real, "the tests need a C compiler"
    wrapper = tmp_path / "cc"
    wrapper.write_text(f'#!/bin/sh\nexec {real} "$@"\n')
    wrapper.chmod(0o755)
    cache = tmp_path / "cache"
    monkeypatch.setenv("LOADER_MODEL_CACHE_DIR", str(cache))
    monkeypatch.setenv("CC", str(wrapper))
    compiled.compiled_function(_function())
    (library,) = _libraries(cache)
    stamp = library.stat().st_mtime_ns
    wrapper.write_text("#!/bin/sh\necho compiler called >&2\nexit 1\n")  # same path, now broken
    script = (
        "import casadi as ca, sys\n"
        "sys.path.insert(0, 'tests/simulation')\n"
        "from test_compiled import _function\n"
        "from loader_model.simulation.compiled import compiled_function\n"
        "f = compiled_function(_function())\n"
        "print(float(f(ca.DM([0, 0, 1]), 2.0)[1]))\n"
    )
    env = {**os.environ, "LOADER_MODEL_CACHE_DIR": str(cache), "CC": str(wrapper)}
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, env=env, check=False
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "1.0"
    assert library.stat().st_mtime_ns == stamp, "loaded, not compiled again"


def test_cached_function_never_compiles_and_loads_what_the_cache_holds(tmp_path, monkeypatch):
    monkeypatch.setenv("LOADER_MODEL_CACHE_DIR", str(tmp_path))
    assert compiled.cached_function(_function()) is None
    assert not _libraries(tmp_path)
    compiled.compiled_function(_function())
    library = compiled.cached_function(_function())
    assert library is not None and float(library(ca.DM([0, 3, 0]), 1.0)[1]) == 9.0
    assert len(_libraries(tmp_path)) == 1


def test_a_damaged_library_is_compiled_again(tmp_path, monkeypatch):
    monkeypatch.setenv("LOADER_MODEL_CACHE_DIR", str(tmp_path))
    compiled.compiled_function(_function())
    (library,) = _libraries(tmp_path)
    library.write_bytes(b"not a shared object")
    again = compiled.compiled_function(_function())
    assert float(again(ca.DM([0, 0, 2]), 1.0)[1]) == 4.0
    assert library.read_bytes()[:4] == b"\x7fELF"


def test_without_a_cache_the_library_lives_in_a_folder_of_the_process(tmp_path, monkeypatch):
    monkeypatch.setenv("LOADER_MODEL_CACHE_DIR", "off")
    assert compiled.cache_directory() is None
    library = compiled.compiled_function(_function())
    assert float(library(ca.DM([1, 0, 0]), 1.0)[1]) == 1.0
    assert not _libraries(tmp_path)


def test_without_a_compiler_it_raises_a_compilation_error(tmp_path, monkeypatch):
    monkeypatch.setenv("LOADER_MODEL_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("CC", str(tmp_path / "no-such-compiler"))
    with pytest.raises(compiled.CompilationError, match="no-such-compiler"):
        compiled.compiled_function(_function())
    assert not _libraries(tmp_path)


def test_the_cache_folder_follows_xdg_when_not_set(monkeypatch, tmp_path):
    monkeypatch.delenv("LOADER_MODEL_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert compiled.cache_directory() == tmp_path / "loader-model"


def test_the_simulator_falls_back_to_the_sx_graph_without_a_compiler(tmp_path, monkeypatch):
    from loader_model.simulation import stepper
    from loader_model.simulation.controllers import hold_controller

    monkeypatch.setenv("LOADER_MODEL_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("CC", str(tmp_path / "no-such-compiler"))
    monkeypatch.setattr(stepper, "_COMPILED", {})
    period, backend = stepper.compile_period(hold_controller(1e-5))
    assert backend == "sx" and period.name() == "closed_loop_period"


@pytest.mark.slow  # 5 s (compiles two periods)
def test_plants_with_different_static_commands_share_one_compiled_period(tmp_path, monkeypatch):
    """The default hold controller takes u0 as a setting: varied plants compile nothing new."""
    from loader_model.plant.plant_parameters import PLANT_PARAMETER_NAMES, plant_parameter_vector
    from loader_model.simulation import stepper
    from loader_model.simulation.courses import paper_course
    from loader_model.simulation.simulator import course_input, simulate

    monkeypatch.setenv("LOADER_MODEL_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(stepper, "_COMPILED", {})
    for mass in (1.0, 1.05):
        params = plant_parameter_vector(None, "empty")
        params[PLANT_PARAMETER_NAMES.index("m_2")] *= mass
        simulate(course_input(paper_course(9.0), params), params, duration_s=0.05)
    assert len(list(tmp_path.glob("closed_loop_period-*.so"))) == 1
