"""Parameter files: shipped defaults, exact TOML round trip, updates, the model's values."""

from __future__ import annotations

import math
import tomllib
from importlib import resources
from pathlib import Path

import pytest

from loader_model.parameters.fields import Range, unit_of
from loader_model.parameters.schema import BucketLoad, ChassisParameters
from loader_model.parameters.sets import (
    MODEL_PARAMETER_NAMES,
    LoaderParameters,
    bucket_load,
    default_loader,
    load_bucket_load,
    load_loader,
    model_parameter_values,
    replace,
    save,
)

DATA = resources.files("loader_model").joinpath("data")


def test_shipped_files_load_and_match_the_paper() -> None:
    loader = default_loader()
    assert loader.hydraulics.bulk_modulus == 1.64e9  # Table 5
    assert loader.leakage.k_lp == 2.87e-11 and loader.leakage.k_lv == -5.0e-4  # Table 5
    assert loader.friction.f_c == pytest.approx(10.7 / 1e5, rel=1e-12)  # Table 4, N/bar -> N/Pa
    assert loader.friction.f_s == 17.0e3 and loader.friction.f_v == 8.13e3
    assert loader.pump.max_displacement == pytest.approx(46e-6, rel=1e-12)  # 46 cm^3/rev
    assert loader.pump.natural_frequency_rad_s == pytest.approx(2 * math.pi * 22.3, rel=1e-12)
    # errata 8: a full stroke in about 37 ms
    full_stroke_s = loader.pump.max_displacement / loader.pump.displacement_rate_limit
    assert full_stroke_s == pytest.approx(0.037, abs=1e-3)
    assert loader.controller.k_fb == (
        2.75,
        5.10,
        -4.0,
        0.22,
    )  # Table 3, k_φ sign corrected (errata 12)
    assert loader.controller.angle_norm == pytest.approx(math.radians(33.0), rel=1e-12)
    assert bucket_load("empty").mass == 340.0 and bucket_load("full").mass == 770.0
    assert bucket_load("empty").pressure_normalisation == 100e5
    assert bucket_load("full").pressure_normalisation == 200e5


def test_every_value_has_a_source_and_calibrated_ones_say_so() -> None:
    loader = default_loader()
    assert all(text.strip() for _, text in loader.sources)
    assert (
        len(loader.sources) == 90
    )  # 67, k_seal, the 12 of [seat], each axle's 5 tyre geometry values
    from loader_model.modal.table1 import FREE_PARAMETERS

    calibrated = {path for item in FREE_PARAMETERS.values() for path in item.paths}
    assert len(calibrated) == 7
    for path in calibrated:
        assert "calibrated to Table 1 by `loader-model calibrate`" in loader.source(path)
    assert not [path for path, text in loader.sources if "placeholder" in text]
    with pytest.raises(KeyError):
        loader.source("chassis.weight")


def test_resource_loading_equals_path_loading() -> None:
    with resources.as_file(DATA.joinpath("default_loader.toml")) as path:
        assert load_loader(path) == default_loader()
    with resources.as_file(DATA.joinpath("load_full.toml")) as path:
        assert load_bucket_load(path) == bucket_load("full")


def test_unknown_bucket_load_case() -> None:
    with pytest.raises(ValueError, match=r"'half' is unknown; allowed: \['empty', 'full'\]"):
        bucket_load("half")


@pytest.mark.parametrize("name", ["default_loader.toml", "load_empty.toml", "load_full.toml"])
def test_save_reproduces_the_shipped_bytes(tmp_path: Path, name: str) -> None:
    shipped = DATA.joinpath(name).read_bytes()
    source = tmp_path / "in.toml"
    source.write_bytes(shipped)
    loader_fn = load_loader if name == "default_loader.toml" else load_bucket_load
    save(loader_fn(source), tmp_path / "out.toml")
    assert (tmp_path / "out.toml").read_bytes() == shipped


def test_round_trip_is_exact_for_awkward_values(tmp_path: Path) -> None:
    updates = {
        "tyres.front.k_y": 0.1 + 0.2 + 1e6,  # not representable in a short decimal
        "chassis.inertia": 2000.0 / 3.0,
        "leakage.k_lp": 5e-324,  # smallest subnormal
        "geometry.S": (-1.0 / 3.0, 2.0 / 7.0),
        "controller.k_fb": (99.99999999999999, -0.0, 1.0 / 3.0, -2.5e-17),
    }
    text = 'quote " backslash \\ tab \t nul \x00 del \x7f unicode φ₀ 33°'
    changed = replace(default_loader(), updates, source=text)
    save(changed, tmp_path / "loader.toml")
    again = load_loader(tmp_path / "loader.toml")
    assert again == changed
    assert again.tyres.front.k_y == updates["tyres.front.k_y"]
    assert again.controller.k_fb == updates["controller.k_fb"]
    assert math.copysign(1.0, again.controller.k_fb[1]) == -1.0
    assert again.source("geometry.S") == text
    save(bucket_load("full"), tmp_path / "load.toml")
    assert load_bucket_load(tmp_path / "load.toml") == bucket_load("full")


def test_saved_file_is_plain_toml_with_units(tmp_path: Path) -> None:
    save(default_loader(), tmp_path / "loader.toml")
    data = tomllib.loads((tmp_path / "loader.toml").read_text(encoding="utf-8"))
    assert data["chassis"]["mass"]["unit"] == "kg"
    assert data["tyres"]["front"]["c_y"]["unit"] == "N s/m"
    assert data["cylinders"]["count"]["value"] == 2


def test_replace_updates_values_and_sources() -> None:
    loader = default_loader()
    new = replace(loader, {"tyres.front.k_y": 1.5e6, "geometry.E": [-0.5, 0.75]})
    assert new.tyres.front.k_y == 1.5e6 and new.geometry.E == (-0.5, 0.75)
    assert new.tyres.rear.k_y == loader.tyres.rear.k_y
    assert new.source("tyres.front.k_y") == loader.source("tyres.front.k_y")
    marked = replace(loader, {"chassis.mass": 2800}, source="calibrated to Table 1")
    assert marked.chassis.mass == 2800.0 and isinstance(marked.chassis.mass, float)
    assert marked.source("chassis.mass") == "calibrated to Table 1"
    assert loader.chassis.mass == default_loader().chassis.mass != 2800.0  # original untouched


def test_replace_rejects_unknown_paths_and_bad_values() -> None:
    loader = default_loader()
    with pytest.raises(ValueError, match=r"tyres\.front\.ky: unknown parameter; did you mean "):
        replace(loader, {"tyres.front.ky": 1.0})
    with pytest.raises(ValueError, match=r"tyres\.front\.k_y = -1\.0 N/m is out of range"):
        replace(loader, {"tyres.front.k_y": -1.0})
    with pytest.raises(ValueError, match=r"mass = 0\.0 kg is out of range; allowed: \(0, 15000\]"):
        replace(bucket_load("empty"), {"mass": 0.0})
    assert loader == default_loader()


def test_objects_built_in_code_can_be_saved(tmp_path: Path) -> None:
    load = BucketLoad(mass=100.0, cog=(1.0, 0.0), inertia=5.0, pressure_normalisation=1e7)
    save(load, tmp_path / "load.toml")
    again = load_bucket_load(tmp_path / "load.toml")
    assert (again.mass, again.cog, again.inertia) == (100.0, (1.0, 0.0), 5.0)
    assert "no source given" in again.source("mass")


def test_units_and_ranges_are_described() -> None:
    assert unit_of(ChassisParameters, "inertia") == "kg m^2"
    assert str(Range(0.0, 1.0, low_open=True)) == "(0, 1]"
    assert str(Range(0.0, low_open=True)) == "> 0"
    assert str(Range(high=2.0)) == "<= 2"
    assert str(Range()) == "any finite value"


def test_model_parameter_values_names_and_mapping() -> None:
    loader = replace(
        default_loader(),
        {
            "tyres.front.k_x": 1.1e6,
            "tyres.front.k_y": 1.2e6,
            "tyres.front.c_x": 1.3e3,
            "tyres.front.c_y": 1.4e3,
            "tyres.rear.k_x": 2.1e6,
            "tyres.rear.k_y": 2.2e6,
            "tyres.rear.c_x": 2.3e3,
            "tyres.rear.c_y": 2.4e3,
        },
    )
    values = model_parameter_values(loader, bucket_load("empty"))
    assert set(values) == MODEL_PARAMETER_NAMES and len(values) == 32
    assert all(isinstance(v, float) for v in values.values())
    expected_tyres = {"k_Ax": 1.1e6, "k_Ay": 1.2e6, "c_Ax": 1.3e3, "c_Ay": 1.4e3}
    expected_tyres |= {"k_Bx": 2.1e6, "k_By": 2.2e6, "c_Bx": 2.3e3, "c_By": 2.4e3}
    assert {k: values[k] for k in expected_tyres} == expected_tyres
    geo = loader.geometry
    for name in "ABCDSNE":
        assert (values[f"{name}_x"], values[f"{name}_y"]) == getattr(geo, name)
    assert values["m_1"] == loader.chassis.mass and values["J_1"] == loader.chassis.inertia
    assert values["m_2"] == pytest.approx(loader.boom.mass + 340.0, rel=1e-15)
    assert values["g"] == 9.81


def _point_cloud(mass: float, cog: tuple[float, float], inertia: float) -> list[tuple]:
    """Four point masses m/4 at distance r = sqrt(J/m) from the CoG: same m, CoG and J."""
    r = math.sqrt(inertia / mass)
    offsets = [(r, 0.0), (-r, 0.0), (0.0, r), (0.0, -r)]
    return [(mass / 4, cog[0] + dx, cog[1] + dy) for dx, dy in offsets]


@pytest.mark.parametrize("case", ["empty", "full"])
def test_combined_body_matches_point_masses(case: str) -> None:
    loader, load = default_loader(), bucket_load(case)
    cloud = _point_cloud(loader.boom.mass, loader.boom.cog, loader.boom.inertia)
    cloud += _point_cloud(load.mass, load.cog, load.inertia)
    mass = sum(m for m, _, _ in cloud)
    gx = sum(m * x for m, x, _ in cloud) / mass
    gy = sum(m * y for m, _, y in cloud) / mass
    inertia = sum(m * ((x - gx) ** 2 + (y - gy) ** 2) for m, x, y in cloud)
    values = model_parameter_values(loader, load)
    assert values["m_2"] == pytest.approx(mass, rel=1e-14)
    assert values["G_x"] == pytest.approx(gx, rel=1e-12)
    assert values["G_y"] == pytest.approx(gy, rel=1e-12, abs=1e-14)
    assert values["J_2"] == pytest.approx(inertia, rel=1e-12)


def test_loader_type_is_exported() -> None:
    assert isinstance(default_loader(), LoaderParameters)
