"""A robustness study of another described machine (issue 23): the compact wheel loader."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from loader_model.robustness.engine import run_study
from loader_model.robustness.study import parse_study

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
    with pytest.raises(ValueError, match="skid-steer only"):
        parse_study(STUDY.replace('compare = ["skyhook"]', 'gains = { designed = "lqr" }'))
    with pytest.raises(ValueError, match=r"study\.machine"):
        parse_study(STUDY.replace('"compact_wheel_loader"', '"no_such_machine"'))


def test_wheel_loader_study_of_two_samples_runs(tmp_path: Path) -> None:
    started = time.perf_counter()
    table = run_study(parse_study(STUDY), tmp_path / "wl", workers=1, progress=False)
    rows = table.to_pylist()
    assert len(rows) == 4  # 2 samples x (baseline, skyhook)
    assert not [r["reason"] for r in rows if r["failed"]]
    assert all(r["a_total"] > 0 for r in rows)
    assert len({r["model.m_1"] for r in rows}) == 2
    print(f"wheel-loader study: {time.perf_counter() - started:.1f} s")
