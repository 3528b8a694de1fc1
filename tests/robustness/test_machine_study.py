"""A robustness study of another described machine: the compact wheel loader."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from loader_model.robustness.engine import run_study
from loader_model.robustness.study import parse_study

MACHINE = "compact_wheel_loader"

STUDY = """
[study]
name = "wheel loader"
machine = "compact_wheel_loader"
seed = 3
samples = 2
duration_s = 3.0
batch_size = 2
[conditions]
speeds_kmh = [9.0]
[controllers]
compare = ["skyhook"]
[parameters]
"hydraulics.bulk_modulus" = { distribution = "uniform", low = 0.8e9, high = 1.8e9, unit = "Pa" }
"model.m_1" = { distribution = "uniform", low = 4000.0, high = 5000.0, unit = "kg" }
"cylinders.piston_diameter" = { distribution = "uniform", low = 0.075, high = 0.085, unit = "m" }
"""


def test_study_file_names_the_machine_and_its_flat_paths() -> None:
    study = parse_study(STUDY)
    assert study.machine == "compact_wheel_loader"
    assert [path for path, _ in study.parameters][1:] == ["model.m_1", "cylinders.piston_diameter"]
    skid_steer = STUDY.replace('machine = "compact_wheel_loader"\n', "").split('"model.m_1"')[0]
    assert parse_study(skid_steer).machine == "skid_steer"
    with pytest.raises(ValueError, match="unknown parameter of machine"):
        parse_study(STUDY.replace('"model.m_1"', '"mass.chassis"'))
    designed = parse_study(STUDY.replace('compare = ["skyhook"]', 'gains = { designed = "lqr" }'))
    assert designed.controllers[0] == "baseline" and designed.controllers[-1] == "designed"
    with pytest.raises(ValueError, match=r"study\.machine"):
        parse_study(STUDY.replace('"compact_wheel_loader"', '"no_such_machine"'))


@pytest.mark.slow  # 12 s measured: a two-sample wheel-loader study (four runs)
def test_wheel_loader_study_of_two_samples_runs(tmp_path: Path) -> None:
    started = time.perf_counter()
    table = run_study(parse_study(STUDY), tmp_path / "wl", workers=1, progress=False)
    rows = table.to_pylist()
    assert len(rows) == 4  # 2 samples x (baseline, skyhook)
    assert not [r["reason"] for r in rows if r["failed"]]
    assert all(r["a_total"] > 0 for r in rows)
    assert len({r["model.m_1"] for r in rows}) == 2
    print(f"wheel-loader study: {time.perf_counter() - started:.1f} s")


DESIGNED = STUDY.replace("samples = 2", "samples = 1").replace(
    'compare = ["skyhook"]',
    'compare = ["skyhook"]\ngains = { lqr = "lqr", optimised = "optimised", fixed = [1.0, 2.0, 3.0, 0.5] }',
)


@pytest.mark.slow  # 4 s; the designed-gains study run stays fast
def test_wheel_loader_designed_gains_are_the_machines_design() -> None:
    """The study's designed gains are those of ``design --machine`` on the same comfort plants."""
    from loader_model.control.comfort_design import comfort_plants
    from loader_model.control.gain_design import design_gains
    from loader_model.plant.scenario import resolve_plant
    from loader_model.robustness.gains import resolve_gains

    study = parse_study(DESIGNED)
    gains = resolve_gains(study)
    assert list(gains) == ["skyhook", "lqr", "optimised", "fixed"]
    plants = comfort_plants(
        study.loads,
        study.road_class,
        study.speeds_kmh[0],
        {load: resolve_plant(None, load, machine=MACHINE) for load in study.loads},
    )
    optimised = np.asarray(design_gains(plants, "optimise").gain).ravel()
    lqr = design_gains(plants, "lqr").gains
    for load in study.loads:
        np.testing.assert_allclose(gains["optimised"][load], optimised, rtol=1e-9)
        np.testing.assert_allclose(gains["lqr"][load], np.ravel(lqr[load]), rtol=1e-9)
        assert gains["fixed"][load] == (1.0, 2.0, 3.0, 0.5)
    # the machine's own design, not the skid-steer's: its gains are far from Table 3's
    skid_steer = resolve_gains(
        parse_study(
            DESIGNED.replace('machine = "compact_wheel_loader"\n', "").split('"model.m_1"')[0]
        )
    )
    assert not np.allclose(gains["optimised"]["full"], skid_steer["optimised"]["full"], rtol=0.1)


# slow: 14 s (a robustness study of the wheel loader); run by `make test-slow`
@pytest.mark.slow
def test_wheel_loader_study_runs_designed_gains(tmp_path: Path) -> None:
    study = parse_study(DESIGNED.replace(", fixed = [1.0, 2.0, 3.0, 0.5]", ""))
    rows = run_study(study, tmp_path / "wl_designed", workers=1, progress=False).to_pylist()
    assert [r["controller"] for r in rows] == ["baseline", "skyhook", "lqr", "optimised"]
    assert not [r["reason"] for r in rows if r["failed"]]
    by_name = {r["controller"]: r for r in rows}
    # the optimised gains are stable on the sampled plant (the margin is computed on it)
    assert by_name["optimised"]["max_pole_real"] < 0.0
    assert by_name["optimised"]["a_total"] > 0.0
    print({n: (round(r["a_total"], 4), round(r["max_pole_real"], 3)) for n, r in by_name.items()})


@pytest.mark.slow  # 3 s
def test_wheel_loader_robust_gains_are_designed_on_its_sampled_plants() -> None:
    """``robust``: the optimisation over plants drawn from the wheel loader's distributions
    (its flat file's paths), stable on them; not its nominal design."""
    from loader_model.control.comfort_design import comfort_plants, evaluate_gain
    from loader_model.robustness.gains import resolve_gains, robust_gain
    from loader_model.robustness.machine_study import machine_sample_plant

    text = DESIGNED.replace(
        'gains = { lqr = "lqr", optimised = "optimised", fixed = [1.0, 2.0, 3.0, 0.5] }',
        'gains = { robust = "robust", optimised = "optimised" }\nrobust_plants = 2',
    )
    study = parse_study(text)
    gains = resolve_gains(study)
    gain, specs = robust_gain(study)
    assert gains["robust"]["full"] == gain
    assert not np.allclose(gain, gains["optimised"]["full"], rtol=1e-6)
    for spec in specs:
        plant = machine_sample_plant(spec, study.layout)
        speed = spec.speed_kmh * spec.speed_factor
        (design,) = comfort_plants((spec.load,), study.road_class, speed, {spec.load: plant})
        assert evaluate_gain([design], np.asarray(gain))[0].margin > 0.0
