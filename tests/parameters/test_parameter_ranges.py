"""Plausible ranges of every parameter field, and the consistency checks of loader with load."""

from __future__ import annotations

import math

import numpy as np
import pytest

from loader_model.parameters.schema import BucketLoad, LoaderParameters
from loader_model.parameters.sets import (
    LOAD_CASES,
    bucket_load,
    default_loader,
    model_parameter_values,
    replace,
)
from loader_model.parameters.toml_format import iter_leaves, leaf_metadata
from loader_model.vehicle.dynamics import LoaderDynamics
from loader_model.vehicle.statics import check_combination, resolve_machine, static_equilibrium

LEAVES = [*iter_leaves(LoaderParameters), *iter_leaves(BucketLoad)]


@pytest.mark.parametrize(("path", "cls", "name"), LEAVES, ids=[p for p, _, _ in LEAVES])
def test_every_field_has_a_finite_range_and_a_reason(path: str, cls: type, name: str) -> None:
    allowed = leaf_metadata(cls, name)["allowed"]
    assert math.isfinite(allowed.low) and math.isfinite(allowed.high), path
    assert allowed.low < allowed.high, path
    assert len(allowed.reason) >= 10, f"{path}: give the reason of the range"


def _values(params: object) -> list[tuple[str, float, object]]:
    out = []
    for path, cls, name in iter_leaves(type(params)):
        value = params
        for part in path.split("."):
            value = getattr(value, part)
        for item in value if isinstance(value, tuple) else (value,):
            out.append((path, item, leaf_metadata(cls, name)["allowed"]))
    return out


def test_shipped_files_lie_inside_the_ranges() -> None:
    shipped = [default_loader(), *(bucket_load(case) for case in LOAD_CASES)]
    for params in shipped:
        for path, value, allowed in _values(params):
            assert allowed.contains(value), f"{path} = {value} outside {allowed}"
    for case in LOAD_CASES:
        check_combination(default_loader(), bucket_load(case))


def _hand_statics(loader, load) -> dict[str, float]:
    """Independent reference: vertical force balance and moments about H for the whole machine
    give the axle loads; moments about the boom pivot D for body 2 give the cylinder force along
    C -> E; the piston pressure holds it with the rod side at the charge pressure."""
    geo, boom, cyl = loader.geometry, loader.boom, loader.cylinders
    g = loader.environment.gravity
    m_1, m_2 = loader.chassis.mass, boom.mass + load.mass
    g_x = (boom.mass * boom.cog[0] + load.mass * load.cog[0]) / m_2
    weight = (m_1 + m_2) * g
    f_a = (m_2 * g * g_x - weight * geo.B[0]) / (geo.A[0] - geo.B[0])
    length = math.hypot(geo.E[0] - geo.C[0], geo.E[1] - geo.C[1])
    u_x, u_y = (geo.E[0] - geo.C[0]) / length, (geo.E[1] - geo.C[1]) / length
    arm = (geo.E[0] - geo.D[0]) * u_y - (geo.E[1] - geo.D[1]) * u_x
    force = m_2 * g * (g_x - geo.D[0]) / arm
    pressure = (force / cyl.count + loader.hydraulics.charge_pressure * cyl.annulus_area) / (
        cyl.piston_area
    )
    return {"F_Ay0": f_a, "F_By0": weight - f_a, "F_act0": force, "p_A0": pressure}


@pytest.mark.parametrize("case", LOAD_CASES)
def test_plant_statics_match_hand_statics(case: str) -> None:
    loader, load = default_loader(), bucket_load(case)
    statics = static_equilibrium(loader, load)
    for name, value in _hand_statics(loader, load).items():
        assert statics[name] == pytest.approx(value, rel=1e-9), name


def test_static_piston_pressure_matches_the_defaults_documentation() -> None:
    # default_loader.toml documents about 89 bar with the 340 kg load and 130 bar with 770 kg
    # (cylinders.piston_diameter source); this includes the charge pressure on the annulus.
    empty = static_equilibrium(default_loader(), bucket_load("empty"))["p_A0"]
    full = static_equilibrium(default_loader(), bucket_load("full"))["p_A0"]
    assert 60e5 < empty < 100e5
    assert full > empty


def test_a_load_that_tips_the_machine_is_refused() -> None:
    heavy = replace(bucket_load("full"), {"mass": 14_000.0, "cog": (3.0, -0.4)})
    # refused on every way from files or objects to the model
    for build in (resolve_machine, LoaderDynamics.from_parameters):
        with pytest.raises(
            ValueError, match=r"static rear \(B\) axle load is -[0-9.e+]+ N; allowed: > 0"
        ):
            build(default_loader(), heavy)


def test_a_load_behind_the_pivot_needs_a_pulling_cylinder_and_is_refused() -> None:
    behind = replace(bucket_load("empty"), {"mass": 10.0, "cog": (-2.0, 0.5)})
    loader = replace(default_loader(), {"boom.cog": (-0.75, 0.9), "geometry.B": (-1.0, -0.47)})
    with pytest.raises(ValueError, match=r"static lift-cylinder force is -[0-9.e+]+ N"):
        check_combination(loader, behind)


def test_precharge_above_the_static_pressure_is_refused() -> None:
    loader = replace(default_loader(), {"accumulator.precharge_pressure": 1.2e7})
    with pytest.raises(ValueError, match=r"accumulator\.precharge_pressure = 12000000\.0 Pa must"):
        check_combination(loader, bucket_load("empty"))
    check_combination(loader, bucket_load("full"))  # 130 bar with 770 kg: holds oil


def test_the_model_command_and_the_modes_command_agree_on_a_heavy_load() -> None:
    heavy = replace(bucket_load("full"), {"mass": 1_500.0})
    values = model_parameter_values(default_loader(), heavy)
    model = LoaderDynamics(values)
    mass = model.mass_matrix(np.zeros(4))
    assert np.all(np.linalg.eigvalsh(mass) > 0.0)
