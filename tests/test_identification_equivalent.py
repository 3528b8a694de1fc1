"""The equivalent cylinder against the generated multibody model (independent derivation)."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.dynamics import LoaderDynamics
from loader_model.identification import EquivalentCylinder
from loader_model.parameters import bucket_load, default_loader


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
