"""Robustness study: the study file's checks, the seeded samples, failures, resume."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from loader_model.cli import main
from loader_model.robustness.distributions import Distribution
from loader_model.robustness.sampling import SampleSpec, sample_specs
from loader_model.robustness.study import load_study, parse_study

TINY = """
[study]
name = "tiny"
seed = 7
samples = 5
duration_s = 3.0
batch_size = 2
[conditions]
speeds_kmh = [18.0]
[controllers]
compare = ["virtual-accumulator"]
[parameters]
"hydraulics.bulk_modulus" = { distribution = "uniform", low = 0.8e9, high = 1.8e9, unit = "Pa" }
"load.mass" = { distribution = "normal", mean = 500.0, std = 100.0, low = 200.0, high = 800.0, unit = "kg" }
"""


def test_example_study_is_valid_and_names_every_controller() -> None:
    example = Path(__file__).parents[2] / "loader_model" / "data" / "robustness_example.toml"
    study = load_study(example)
    assert study.controllers == (
        "baseline",
        "passive",
        "virtual-accumulator",
        "skyhook",
        "lqr",
        "optimised",
        "robust",
    )
    assert study.parameters[0][0] == "hydraulics.bulk_modulus"


@pytest.mark.parametrize(
    "change, message",
    [
        (('"hydraulics.bulk_modulus"', '"hydraulics.bulk_modulos"'), "did you mean 'hydraulics"),
        (("low = 0.8e9", "low = 1e6"), r"bulk_modulus.low = 1e\+06 Pa is outside .*allowed: \["),
        (("samples = 5", "samples = -3"), "study.samples = -3: allowed: an integer from 1"),
        (('unit = "Pa"', 'unit = "bar"'), "the parameter file's unit is 'Pa'"),
        (("low = 200.0", "low = 0.0"), r"load.mass.low = 0 kg is outside .*\(0, 15000\]"),
        (('"load.mass"', '"geometry.A"'), "only scalar real parameters"),
        (
            (
                '"load.mass" = { distribution = "normal", mean = 500.0, std = 100.0, low = 200.0, '
                'high = 800.0, unit = "kg" }',
                '"sensors.phi.offset" = { distribution = "uniform", '
                'low = -1.0, high = 0.0, unit = "rad" }',
            ),
            r"phi.offset.low = -1 rad .*33 deg",
        ),
        (("speeds_kmh = [18.0]", "speeds_kmh = [12.0]"), r"12.0 is not allowed; allowed: \[9.0"),
        (('compare = ["virtual', 'compare = ["semi'), "'semi-accumulator' is not allowed"),
        (("[conditions]", "[conditions]\nspeed = 3"), "conditions.speed: unknown key"),
        (('"uniform"', '"gamma"'), r"distribution = 'gamma': allowed: \['uniform'"),
        (("std = 100.0", "std = -1.0"), r"std = -1: allowed: a number > 0"),
        (("duration_s = 3.0", "duration_s = 1.0"), "study.duration_s = 1.0: allowed"),
        (('"load.mass"', '"sensors.p_A.gain"'), "sensors.p_A.gain.unit = 'kg': .* unit is '-'"),
        (('"load.mass"', '"sensors.p_A.offst"'), "did you mean 'sensors.p_A.offset'"),
        (('unit = "Pa"', 'unit = "Pa", source = 3'), r"bulk_modulus.source = 3: allowed: a string"),
        (('unit = "Pa"', 'unit = "Pa", why = "x"'), r"bulk_modulus.why: unknown key .*'source'"),
    ],
)
def test_bad_study_files_name_key_value_and_what_is_allowed(change, message) -> None:
    with pytest.raises(ValueError, match=message):
        parse_study(TINY.replace(*change), "study file")


def test_bad_study_file_on_the_command_line_writes_nothing(tmp_path: Path, capsys) -> None:
    study = tmp_path / "bad.toml"
    study.write_text(TINY.replace("samples = 5", "samples = -1"), encoding="utf-8")
    output = tmp_path / "out"
    assert main(["robustness", str(study), "--output", str(output)]) == 2
    error = capsys.readouterr().err
    assert "study.samples = -1" in error and "Traceback" not in error
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_samples_are_seeded_bounded_and_reproducible() -> None:
    study = parse_study(TINY)
    first, again = sample_specs(study), sample_specs(study)
    assert first == again
    assert [s.index for s in first] == list(range(5))
    values = np.array([[v for _, v in s.values] for s in first])
    assert np.all((values[:, 0] >= 0.8e9) & (values[:, 0] <= 1.8e9))
    assert np.all((values[:, 1] >= 200.0) & (values[:, 1] <= 800.0))
    # Latin hypercube: one sample in each fifth of the bulk modulus range
    strata = np.floor((values[:, 0] - 0.8e9) / 0.2e9).astype(int)
    assert sorted(strata) == [0, 1, 2, 3, 4]
    other = parse_study(TINY.replace("seed = 7", "seed = 8"))
    assert sample_specs(other) != first
    sobol = parse_study(TINY.replace("[study]", '[study]\nsampling = "sobol"'))
    assert sample_specs(sobol) != first


@pytest.mark.parametrize(
    "distribution",
    [
        Distribution("uniform", 1.0, 3.0, "-"),
        Distribution("loguniform", 1.0, 100.0, "-"),
        Distribution("normal", 1.0, 3.0, "-", mean=2.5, std=1.0),
        Distribution("triangular", 1.0, 3.0, "-", mode=1.5),
    ],
)
def test_distributions_stay_in_their_support(distribution) -> None:
    u = np.linspace(0.0, 1.0, 101)[:-1]
    values = distribution.ppf(u)
    assert np.all(np.diff(values) > 0)
    assert values[0] == pytest.approx(1.0, rel=1e-12) and values[-1] < distribution.high


def test_failed_samples_are_recorded_with_their_reason(monkeypatch) -> None:
    from loader_model.robustness import runner
    from loader_model.simulation.simulator import SimulationError

    study = parse_study(TINY)
    bad = SampleSpec(0, 18.0, 1.0, "full", (("hydraulics.bulk_modulus", 1.0),), 3)
    rows = runner.run_sample(study, {}, bad)
    assert [r["controller"] for r in rows] == ["baseline", "virtual-accumulator"]
    assert all(r["failed"] for r in rows) and "bulk_modulus" in rows[0]["reason"]
    assert all(math.isnan(r["a_total"]) for r in rows)

    def fake(study, gains, name, params, load, road, errors, sensors):
        if name == "virtual-accumulator":
            raise SimulationError("the integration left the finite numbers at t = 1.2 s")
        return {"a_total": 2.0}

    monkeypatch.setattr(runner, "_run", fake)
    monkeypatch.setattr(runner, "course_input", lambda course, params: None)
    rows = runner.run_sample(study, {}, sample_specs(study)[0])
    assert not rows[0]["failed"] and rows[0]["change_percent"] == 0.0
    assert rows[1]["failed"] and rows[1]["reason"].startswith("SimulationError: the integration")


def _fake_sample(study, gains, spec):
    return [
        {"sample": spec.index, "controller": c, "speed_kmh": spec.speed_kmh, "load": spec.load}
        | {"a_total": 1.0 + spec.index + i, "failed": False, "reason": ""}
        | dict(spec.values)
        for i, c in enumerate(study.controllers)
    ]


def test_an_interrupted_study_resumes_to_the_same_table(tmp_path: Path, monkeypatch) -> None:
    from loader_model.robustness import engine, runner

    study = parse_study(TINY)
    monkeypatch.setattr(runner, "run_sample", _fake_sample)
    whole = engine.run_study(study, tmp_path / "whole", progress=False, gains={})
    assert whole.column("sample").to_pylist() == [0, 0, 1, 1, 2, 2, 3, 3, 4, 4]
    calls = []
    monkeypatch.setattr(runner, "run_sample", lambda *a: calls.append(a[2].index) or 1 / 0)
    folder = tmp_path / "resumed"
    with pytest.raises(ZeroDivisionError):
        engine.run_study(study, folder, progress=False, gains={})
    assert not (folder / "results.csv").exists()
    monkeypatch.setattr(runner, "run_sample", _fake_sample)
    (folder / "parts").mkdir(exist_ok=True)
    engine.run_study(study, tmp_path / "part", progress=False, gains={})
    for part in sorted((tmp_path / "part" / "parts").iterdir())[:2]:  # batches 0-1 and 2-3
        part.rename(folder / "parts" / part.name)
    monkeypatch.setattr(
        runner, "run_sample", lambda *a: calls.append(a[2].index) or _fake_sample(*a)
    )
    resumed = engine.run_study(study, folder, progress=False, gains={})
    assert calls == [0, 4]  # the first attempt died at sample 0; the rerun ran only sample 4
    assert resumed.equals(whole)
    assert (folder / "results.csv").read_bytes() == (
        tmp_path / "whole" / "results.csv"
    ).read_bytes()
    other = parse_study(TINY.replace("seed = 7", "seed = 9"))
    with pytest.raises(ValueError, match="holds results of another study"):
        engine.run_study(other, folder, progress=False, gains={})


def test_wilson_interval_closed_forms() -> None:
    from loader_model.robustness.report import wilson_interval

    z2 = 1.959964**2
    # 0 of n: (0, z²/(n + z²)); n of n mirrors it; k of 2k is symmetric about 1/2
    assert wilson_interval(0, 10) == pytest.approx((0.0, z2 / (10 + z2)), rel=1e-12)
    assert wilson_interval(10, 10) == pytest.approx((10 / (10 + z2), 1.0), rel=1e-12)
    low, high = wilson_interval(5, 10)
    assert low + high == pytest.approx(1.0, rel=1e-12) and low == pytest.approx(0.2366, abs=1e-4)


def test_report_counts_worse_runs_and_ranks_the_parameter_that_drives_them() -> None:
    import pyarrow as pa

    from loader_model.robustness.report import controller_summary, report_text
    from loader_model.robustness.table import result_schema

    study = parse_study(TINY)
    rows = []
    for i in range(10):
        base = {"sample": i, "speed_kmh": 18.0, "speed_factor": 1.0, "load": "full"}
        base |= {"hydraulics.bulk_modulus": 1e9 + 1e7 * i, "load.mass": 500.0 - 9.0 * (i % 3)}
        for name, change in (("baseline", 0.0), ("virtual-accumulator", i - 4.5)):
            rows.append(
                base
                | {"controller": name, "a_total": 1.0 + change / 100, "change_percent": change}
                | {"max_pole_real": math.nan, "failed": False, "reason": "", "road_seed": 1}
            )
    rows[-1] |= {"failed": True, "reason": "SimulationError: left the finite numbers"}
    table = pa.Table.from_pylist(rows, schema=result_schema(study))
    summary = controller_summary(study, table, "virtual-accumulator")
    assert summary["evaluated"] == 9 and summary["failed"] == 1
    assert summary["counts"]["diverged"] == 1 and summary["failures"] == 1
    assert summary["p_worse"] == pytest.approx(4 / 9, rel=1e-12)
    assert summary["p_worse_all"] == pytest.approx(5 / 10, rel=1e-12)  # the failure is worse
    assert next(iter(summary["sensitivity"])) == "hydraulics.bulk_modulus"
    assert summary["sensitivity"]["hydraulics.bulk_modulus"] == pytest.approx(1.0, rel=1e-12)
    assert [r["sample"] for r in summary["worst"]] == [8, 7, 6]
    text = report_text(study, table, {"virtual-accumulator": {}})
    assert "probability of worse comfort: 0.500 over all 10 samples" in text
    assert "0.444 among the 9 evaluated" in text and "1 × SimulationError" in text
    assert "samples: 10: 9 evaluated, 0 unstable on the linearised plant, 1 diverged" in text


def test_a_distribution_carries_its_source() -> None:
    text = TINY.replace('unit = "Pa"', 'unit = "Pa", source = "Table 5 and air entrainment"', 1)
    distribution = dict(parse_study(text).parameters)["hydraulics.bulk_modulus"]
    assert distribution.source == "Table 5 and air entrainment"
    assert dict(parse_study(TINY).parameters)["hydraulics.bulk_modulus"].source == ""
