"""The equivalent cylinder against the generated multibody model (independent derivation)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from loader_model.identification import EquivalentCylinder
from loader_model.parameters.sets import bucket_load, default_loader
from loader_model.vehicle.dynamics import LoaderDynamics


@pytest.mark.parametrize("case", ["empty", "full"])
def test_load_force_lever_and_inertia_match_the_generated_model(case: str) -> None:
    load = bucket_load(case)
    cylinder = EquivalentCylinder.from_parameters(default_loader(), load)
    model = LoaderDynamics.from_parameters(None, case)
    p0 = np.zeros(4)
    lever = model.cylinder_kinematics(p0)["dx_cyl_dphi"]
    assert cylinder.lever_m_per_rad == pytest.approx(lever, rel=1e-12)
    # F_L: the static cylinder force that holds boom and load at the operating point.
    assert float(cylinder.load_force(load.mass)) == pytest.approx(
        model.static_cylinder_force_N, rel=1e-9
    )
    # m_eq: the boom's inertia about the pivot D (M[θ2, θ2] of Eq. 32) over the lever squared.
    inertia_d = model.mass_matrix(p0)[3, 3]
    assert float(cylinder.inertia(load.mass)) == pytest.approx(inertia_d / lever**2, rel=1e-9)


def test_totals_of_both_cylinders() -> None:
    loader = default_loader()
    cylinder = EquivalentCylinder.from_parameters(loader, bucket_load("full"))
    cyl = loader.cylinders
    assert cylinder.area_m2 == pytest.approx(cyl.count * np.pi / 4 * cyl.piston_diameter**2)
    assert float(cylinder.volume_a(0.1)) == pytest.approx(
        cyl.count * (cyl.piston_area * 0.1 + cyl.dead_volume_a)
    )
    assert float(cylinder.volume_b(0.1)) == pytest.approx(
        cyl.count * (cyl.annulus_area * (cyl.stroke - 0.1) + cyl.dead_volume_b)
    )


def test_position_from_boom_angle_follows_the_lever() -> None:
    loader = default_loader()
    cylinder = EquivalentCylinder.from_parameters(loader, bucket_load("full"))
    phi0 = loader.geometry.boom_angle
    c, e = np.array(loader.geometry.C), np.array(loader.geometry.E)
    at_operating = float(cylinder.position_from_boom_angle(np.array([phi0]))[0])
    assert at_operating == pytest.approx(
        np.linalg.norm(e - c) - loader.cylinders.retracted_length, rel=1e-14
    )
    h = 1e-6
    slope = cylinder.position_from_boom_angle(np.array([phi0 + h, phi0 - h])) @ [1, -1] / (2 * h)
    assert slope == pytest.approx(cylinder.lever_m_per_rad, rel=1e-8)
    with pytest.raises(ValueError, match=r"\(sample 2\) puts .* outside the stroke"):
        cylinder.position_from_boom_angle(np.array([phi0 + 0.1, phi0 - 0.5]))


def test_boom_angle_record_gives_the_same_signals(tmp_path: Path) -> None:
    from loader_model.identification import (
        LiftProfile,
        SensorOptions,
        prepare_signals,
        read_measurement_csv,
        synthesize,
        write_measurement_csv,
    )

    recording = synthesize(SensorOptions(seed=5, sample_rate_hz=200.0), LiftProfile(cycles=2))
    cylinder = recording.cylinder
    phi0 = default_loader().geometry.boom_angle
    grid = np.linspace(phi0 - 0.06, phi0 + 1.2, 200_001)
    positions = cylinder.position_from_boom_angle(grid)  # increasing: the boom rises
    phi = np.interp(recording.record.position_m, positions, grid)
    columns = recording.record.columns()
    del columns["x_cyl [m]"]
    columns = {"phi [deg]": np.degrees(phi)} | columns
    path = write_measurement_csv(tmp_path / "phi.csv", columns)
    record = read_measurement_csv(path)
    assert record.position_m is None
    with pytest.raises(ValueError, match="boom angle phi"):
        prepare_signals(record, 40.0)
    from_angle = prepare_signals(record, 40.0, cylinder=cylinder)
    from_position = prepare_signals(recording.record, 40.0)
    # Interpolation on a 6 µrad grid: positions agree to about 0.1 µm.
    np.testing.assert_allclose(from_angle.x, from_position.x, rtol=0, atol=1e-6)
    np.testing.assert_allclose(from_angle.v, from_position.v, rtol=0, atol=1e-4)


@pytest.mark.parametrize("turn", [-0.05, 0.3, 0.7])
def test_lever_load_force_and_inertia_at_each_boom_angle_match_the_generated_model(
    turn: float,
) -> None:
    # The per-sample equivalent cylinder (F_L, m_eq and the lever at the boom angle of each
    # piston position) against the generated kinematics and mass matrix, chassis at rest.
    load = bucket_load("full")
    loader = default_loader()
    cylinder = EquivalentCylinder.from_parameters(loader, load)
    model = LoaderDynamics.from_parameters(None, "full")
    p = np.array([0.0, 0.0, 0.0, turn])
    kinematics = model.cylinder_kinematics(p)
    position = np.array([kinematics["x_cyl"] - loader.cylinders.retracted_length])
    angle, lever, slope = cylinder._lever(position)
    assert float(angle[0]) == pytest.approx(turn, abs=1e-12)
    assert float(lever[0]) == pytest.approx(kinematics["dx_cyl_dphi"], rel=1e-10)
    points = model.point_positions(p)
    moment = model.parameter("g") * model.parameter("m_2") * (points["G"][0] - points["D"][0])
    force = cylinder.load_force(np.array([load.mass]), position)
    assert float(force[0]) == pytest.approx(moment / kinematics["dx_cyl_dphi"], rel=1e-9)
    inertia = cylinder.inertia(np.array([load.mass]), position)
    assert float(inertia[0]) == pytest.approx(
        model.mass_matrix(p)[3, 3] / kinematics["dx_cyl_dphi"] ** 2, rel=1e-9
    )
    h = 1e-6
    ahead = model.cylinder_kinematics(p + np.array([0, 0, 0, h]))["dx_cyl_dphi"]
    behind = model.cylinder_kinematics(p - np.array([0, 0, 0, h]))["dx_cyl_dphi"]
    assert float(slope[0]) == pytest.approx((ahead - behind) / (2 * h), rel=1e-6)
