"""Chamber volumes and hydraulic stiffness of the lift cylinders (Eq. 28, 30, errata 6)."""

from __future__ import annotations

import math
from dataclasses import replace as dc_replace

import pytest

from loader_model.parameters.schema import CylinderParameters, HydraulicParameters
from loader_model.parameters.sets import default_loader
from loader_model.vehicle.cylinder import (
    area_ratio,
    chamber_volumes_m3,
    hydraulic_stiffness_n_per_m,
    piston_position_m,
)


@pytest.fixture
def cyl2() -> CylinderParameters:
    """Two cylinders, bore 100 mm, rod 50 mm (alpha = 0.75 exactly), stroke 0.5 m."""
    return CylinderParameters(
        count=2,
        piston_diameter=0.1,
        rod_diameter=0.05,
        stroke=0.5,
        retracted_length=1.0,
        dead_volume_a=1e-3,
        dead_volume_b=2e-3,
        end_stop_stiffness=1e8,
        end_stop_damping=1e5,
    )


@pytest.fixture
def oil() -> HydraulicParameters:
    return HydraulicParameters(
        bulk_modulus=1.6e9,
        charge_pressure=2e6,
        oil_density=870.0,
        charge_conductance=5e-9,
        check_valve_conductance=5e-9,
        relief_pressure=2.3e7,
        relief_conductance=1.8e-9,
    )


def test_area_ratio_of_half_diameter_rod_is_three_quarters(cyl2: CylinderParameters) -> None:
    # alpha = 1 - (d_r / d_p)^2 = 1 - 0.25
    assert area_ratio(cyl2) == pytest.approx(0.75, rel=1e-14)


def test_chamber_volumes_hand_calculation(cyl2: CylinderParameters) -> None:
    # x_p = 1.2 - 1.0 = 0.2 m; A_p = pi/4 * 0.01 = 7.853981634e-3 m^2
    # V_A = 7.853981634e-3 * 0.2 + 1e-3 = 2.570796327e-3 m^3
    # V_B = 0.75 * 7.853981634e-3 * (0.5 - 0.2) + 2e-3 = 3.767145868e-3 m^3
    v_a, v_b = chamber_volumes_m3(cyl2, 1.2)
    assert v_a == pytest.approx(2.570796327e-3, rel=1e-9)
    assert v_b == pytest.approx(3.767145868e-3, rel=1e-9)


def test_chamber_volumes_at_the_end_stops(cyl2: CylinderParameters) -> None:
    v_a, v_b = chamber_volumes_m3(cyl2, 1.0)
    assert v_a == pytest.approx(1e-3, rel=1e-12)
    assert v_b == pytest.approx(0.75 * math.pi / 4 * 0.01 * 0.5 + 2e-3, rel=1e-12)
    v_a, v_b = chamber_volumes_m3(cyl2, 1.5)
    assert v_a == pytest.approx(math.pi / 4 * 0.01 * 0.5 + 1e-3, rel=1e-12)
    assert v_b == pytest.approx(2e-3, rel=1e-12)


@pytest.mark.parametrize("length", [0.999, 1.501, -1.0])
def test_length_outside_the_stroke_is_rejected(cyl2: CylinderParameters, length: float) -> None:
    with pytest.raises(ValueError, match=r"outside the stroke \[1, 1.5\] m"):
        chamber_volumes_m3(cyl2, length)


def test_piston_position(cyl2: CylinderParameters) -> None:
    assert piston_position_m(cyl2, 1.3) == pytest.approx(0.3, rel=1e-12)


def test_hydraulic_stiffness_hand_calculation(
    cyl2: CylinderParameters, oil: HydraulicParameters
) -> None:
    # n K A_p^2 = 2 * 1.6e9 * (7.853981634e-3)^2 = 197392.088 N m
    # 1/V_A = 388.98453 1/m^3, alpha^2 / V_B = 0.5625 / 3.767145868e-3 = 149.31729 1/m^3
    # k_eq = 197392.088 * 538.30182 = 1.0625652e8 N/m
    assert hydraulic_stiffness_n_per_m(cyl2, oil, 1.2) == pytest.approx(1.0625652e8, rel=1e-7)


def test_stiffness_tends_to_eq_28_for_a_huge_rod_side_volume(
    cyl2: CylinderParameters, oil: HydraulicParameters
) -> None:
    # Eq. 28 (piston side only) is the limit V_B -> infinity.
    soft_b = dc_replace(cyl2, dead_volume_b=1e6)
    v_a, _ = chamber_volumes_m3(soft_b, 1.2)
    eq28 = 2 * 1.6e9 * (math.pi / 4 * 0.01) ** 2 / v_a
    assert hydraulic_stiffness_n_per_m(soft_b, oil, 1.2) == pytest.approx(eq28, rel=1e-8)


def test_stiffness_scales_with_cylinder_count(
    cyl2: CylinderParameters, oil: HydraulicParameters
) -> None:
    single = dc_replace(cyl2, count=1)
    ratio = hydraulic_stiffness_n_per_m(cyl2, oil, 1.3) / hydraulic_stiffness_n_per_m(
        single, oil, 1.3
    )
    assert ratio == pytest.approx(2.0, rel=1e-14)


def test_default_loader_operating_point_is_inside_the_stroke() -> None:
    loader = default_loader()
    (cx, cy), (ex, ey) = loader.geometry.C, loader.geometry.E
    length = math.hypot(ex - cx, ey - cy)
    k_eq = hydraulic_stiffness_n_per_m(loader.cylinders, loader.hydraulics, length)
    # 65 mm bore, about 56 mm out of a 0.45 m stroke: of the order of 1e8 N/m
    assert 5e7 < k_eq < 2e8
