"""Undamped modes of a described machine from the runtime against an independent NumPy computation
from the generated functions, and the skid-steer through the same generic route."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy.linalg import eigh

import loader_model_generated as skid
import loader_model_generated.compact_wheel_loader as wl
from loader_model.machines import machine
from loader_model.modal.modes import modal_analysis
from loader_model.modal.undamped import machine_undamped_matrices, undamped_matrices
from loader_model.parameters.sets import bucket_load, default_loader, model_parameter_values

DATA = Path(__file__).resolve().parents[2] / "loader_model" / "data" / "machines"
SHIPPED = tomllib.loads((DATA / "compact_wheel_loader.toml").read_text(encoding="utf-8"))


def _closed_oil_columns(length: float) -> float:
    """Eq. 28 with the rod side (errata 6), written out from the file's [cylinders] table."""
    cyl = {k: v["value"] for k, v in SHIPPED["cylinders"].items()}
    bulk = SHIPPED["hydraulics"]["bulk_modulus"]["value"]
    piston = math.pi / 4 * cyl["piston_diameter"] ** 2
    annulus = piston - math.pi / 4 * cyl["rod_diameter"] ** 2
    x_p = length - cyl["retracted_length"]
    v_a = piston * x_p + cyl["dead_volume_a"]
    v_b = annulus * (cyl["stroke"] - x_p) + cyl["dead_volume_b"]
    return cyl["count"] * bulk * piston**2 * (1 / v_a + (annulus / piston) ** 2 / v_b)


@pytest.mark.parametrize("load", ["empty", "full"])
def test_wheel_loader_modes_equal_an_independent_computation(load: str) -> None:
    values = {k: v["value"] for k, v in SHIPPED["model"].items()}
    values |= {k: v["value"] for k, v in SHIPPED["loads"][load].items()}
    raw = np.array([values.get(n, 0.0) for n in wl.PARAMETER_NAMES])
    params, f_act0 = wl.function("complete_parameters")(raw)
    zeros = np.zeros(5)
    dr_dp = np.asarray(
        wl.function("residual_jacobians")(
            zeros, zeros, zeros, f_act0, np.zeros(4), np.zeros(4), np.zeros(3), params
        )[1]
    )
    q_act = np.asarray(wl.function("actuator_map")(zeros, params)).ravel()
    length = float(wl.function("cylinder_kinematics")(zeros, zeros, params)[0])
    stiffness = dr_dp + _closed_oil_columns(length) * np.outer(q_act, q_act)
    mass = np.asarray(wl.function("mass_matrix")(zeros, params))
    expected = np.sort(np.sqrt(eigh(stiffness, mass, eigvals_only=True)) / (2 * np.pi))[::-1]

    matrices = machine_undamped_matrices(machine("compact_wheel_loader"), None, load)
    result = modal_analysis(matrices.mass, matrices.stiffness)
    np.testing.assert_allclose(result.frequencies_hz, expected, rtol=1e-10)
    assert matrices.hydraulic_stiffness_n_per_m == pytest.approx(_closed_oil_columns(length))
    assert matrices.coordinate_names == wl.COORDINATE_NAMES
    assert np.all(expected > 1.0)


def test_locked_tilt_spring_is_in_the_stiffness() -> None:
    """Without the tilt spring the bucket hangs free: its angle's diagonal stiffness drops."""
    with_spring = machine_undamped_matrices(machine("compact_wheel_loader"), None, "full")
    values = {k: v["value"] for k, v in SHIPPED["model"].items()}
    params, _ = wl.function("complete_parameters")([values.get(n, 0.0) for n in wl.PARAMETER_NAMES])
    k_e = wl.function("internal_forces")
    zeros = np.zeros(5)
    stiffness_e = np.vstack(
        [
            (
                np.asarray(k_e(dp, zeros, params)[0]).ravel()
                - np.asarray(k_e(-dp, zeros, params)[0]).ravel()
            )
            / 2e-7
            for dp in np.eye(5) * 1e-7
        ]
    )
    assert abs(stiffness_e[4, 4]) > 1e3
    assert with_spring.stiffness[4, 4] > 0.5 * abs(stiffness_e[4, 4])


def test_generic_route_gives_the_skid_steers_plant_modes() -> None:
    """The generated residual plus k_eq Q_act Q_actᵀ equals the plant's linearisation for the
    skid-steer (Eq. 28 with the chambers closed), so both machines go the same way."""
    loader, load = default_loader(), bucket_load("empty")
    plant = undamped_matrices(loader, load)
    values = model_parameter_values(loader, load)
    params, f_act0 = skid.function("complete_parameters")(
        [values.get(n, 0.0) for n in skid.PARAMETER_NAMES]
    )
    zeros = np.zeros(4)
    dr_dp = np.asarray(
        skid.function("residual_jacobians")(
            zeros, zeros, zeros, f_act0, np.zeros(4), np.zeros(4), np.zeros(3), params
        )[1]
    )
    q_act = np.asarray(skid.function("actuator_map")(zeros, params)).ravel()
    stiffness = dr_dp + plant.hydraulic_stiffness_n_per_m * np.outer(q_act, q_act)
    np.testing.assert_allclose(
        0.5 * (stiffness + stiffness.T),
        plant.stiffness,
        rtol=1e-6,
        atol=1e-6 * abs(plant.stiffness).max(),
    )
