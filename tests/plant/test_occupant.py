"""The seated occupant on the seat cushion at S (issue 21, item 2) against closed forms.

- Apparent mass on a rigid seat, from the plant's own occupant equations: the single-degree-of-
  freedom model with a mass on the seat (Fairley & Griffin 1989: ω_n = 31.4 rad/s, ζ = 0.475),
  M(ω) = m0 + m1 (k1 + jωc1) / (k1 − ω²m1 + jωc1), to 1e-6; its peak at 4.32 Hz (the published
  model's: r = √(√(1 + 8ζ²) − 1) / (2ζ) = 0.865 of 5 Hz), within 1 %.
- Pad/chassis transmissibility 0.5-20 Hz from the linearised plant (python-control), against
  T(ω) = (k_c + jωc_c) / (k_c + jωc_c − ω²(m_p + M(ω))) written here, to 1e-6 (both axes); the
  vertical peak of the occupied cushion near 4 Hz (the assumption of the parameter file).
- Occupant off: the pad outputs are the chassis's f_S bit for bit, in the plant and a run.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from loader_model.plant.linear import linearise_plant
from loader_model.plant.occupant import OCCUPANT_STATE_NAMES, occupant_dynamics
from loader_model.plant.plant import EXOGENOUS_NAMES, OUTPUT_NAMES, STATE_NAMES, plant_function
from loader_model.plant.plant_parameters import (
    PLANT_PARAMETER_NAMES,
    PlantOptions,
    plant_parameter_vector,
)

FREQUENCY_HZ = np.geomspace(0.5, 20.0, 80)


def _theta(params: np.ndarray) -> dict[str, float]:
    return dict(zip(PLANT_PARAMETER_NAMES, params, strict=True))


def _body(theta: dict[str, float], axis: str) -> tuple[float, float, float, float]:
    """m0, m1, k1, c1 of one axis from the parameter values (closed form, module docstring)."""
    mass, share = theta["m_seated"], theta[f"r_occ_{axis}"]
    m0, m1 = share * mass, (1 - share) * mass
    omega = 2 * np.pi * theta[f"f_occ_{axis}"]
    return m0, m1, m1 * omega**2, 2 * theta[f"zeta_occ_{axis}"] * m1 * omega


def apparent_mass(theta: dict[str, float], axis: str, frequency_hz: np.ndarray) -> np.ndarray:
    m0, m1, k1, c1 = _body(theta, axis)
    jw = 2j * np.pi * frequency_hz
    return m0 + m1 * (k1 + jw * c1) / (k1 + jw**2 * m1 + jw * c1)


def transmissibility(theta: dict[str, float], axis: str, frequency_hz: np.ndarray) -> np.ndarray:
    jw = 2j * np.pi * frequency_hz
    cushion = theta[f"k_cush_{axis}"] + jw * theta[f"c_cush_{axis}"]
    load = theta["m_pad"] + apparent_mass(theta, axis, frequency_hz)
    return cushion / (cushion + jw**2 * load)


def _occupant_response(theta: dict[str, float], axis: str, frequency_hz: np.ndarray) -> np.ndarray:
    """ü_o / Δf of the plant's occupant equations (AD-linearised) for one axis."""
    state, f_s = ca.SX.sym("u", len(OCCUPANT_STATE_NAMES)), ca.SX.sym("f", 2)
    rates, _ = occupant_dynamics(state, f_s, theta)
    column = 0 if axis == "x" else 1
    row = OCCUPANT_STATE_NAMES.index(f"ud_O{axis}")
    jac = ca.Function("j", [state, f_s], [ca.jacobian(rates, state), ca.jacobian(rates, f_s)])
    a, b = (np.asarray(m) for m in jac(np.zeros(len(OCCUPANT_STATE_NAMES)), [0.0, theta["g"]]))
    n = a.shape[0]
    return np.array(
        [
            a[row] @ np.linalg.solve(2j * np.pi * f * np.eye(n) - a, b[:, column]) + b[row, column]
            for f in frequency_hz
        ]
    )


@pytest.mark.parametrize("axis", ["x", "y"])
def test_apparent_mass_on_a_rigid_seat_is_the_published_model(axis: str) -> None:
    params = plant_parameter_vector(None, "empty")
    theta = _theta(params)
    rigid = theta | {f"k_cush_{axis}": 1e13, f"c_cush_{axis}": 0.0}  # the pad follows S
    m0, m1, _, _ = _body(theta, axis)
    measured = m0 + m1 * (1.0 + _occupant_response(rigid, axis, FREQUENCY_HZ))
    expected = apparent_mass(theta, axis, FREQUENCY_HZ)
    np.testing.assert_allclose(measured, expected, rtol=1e-6)


def test_vertical_apparent_mass_peaks_where_the_published_model_does() -> None:
    theta = _theta(plant_parameter_vector(None, "empty"))
    assert (theta["f_occ_y"], theta["zeta_occ_y"]) == (5.0, 0.475)  # Fairley & Griffin 1989
    fine = np.linspace(2.0, 8.0, 6001)
    m0, m1, _, _ = _body(theta, "y")
    moving = (apparent_mass(theta, "y", fine) - m0) / m1  # the published model's moving part
    zeta = theta["zeta_occ_y"]
    ratio = np.sqrt(np.sqrt(1 + 8 * zeta**2) - 1) / (2 * zeta)
    peak = fine[np.argmax(np.abs(moving))]
    assert peak == pytest.approx(ratio * 5.0, rel=0.01) and 4.2 < peak < 4.4
    r2 = ratio**2
    top = np.sqrt((1 + (2 * zeta * ratio) ** 2) / ((1 - r2) ** 2 + (2 * zeta * ratio) ** 2))
    assert np.max(np.abs(moving)) == pytest.approx(top, rel=1e-4)  # 1.51
    whole = np.abs(apparent_mass(theta, "y", fine)) / theta["m_seated"]
    assert 1.3 < whole.max() < 1.6 and 4.0 < fine[np.argmax(whole)] < 4.6  # normalised: 1.43


@pytest.mark.parametrize(("axis", "force"), [("y", "F_dy"), ("x", "F_dx")])
def test_pad_over_chassis_is_the_cushion_transmissibility(axis: str, force: str) -> None:
    import control

    params = plant_parameter_vector(None, "empty", PlantOptions.for_controller("skyhook"))
    system = linearise_plant(params).state_space()
    assert set(OCCUPANT_STATE_NAMES) <= set(system.state_labels)
    response = control.frequency_response(system, 2 * np.pi * FREQUENCY_HZ).complex
    inputs, outputs = list(system.input_labels), list(system.output_labels)
    chassis = response[outputs.index(f"f_S{axis}"), inputs.index(force)]
    pad = response[outputs.index(f"f_P{axis}"), inputs.index(force)]
    usable = np.abs(chassis) > 1e-6 * np.abs(chassis).max()  # away from the chassis's zeros
    assert usable.sum() > 70
    expected = transmissibility(_theta(params), axis, FREQUENCY_HZ)
    np.testing.assert_allclose(pad[usable] / chassis[usable], expected[usable], rtol=1e-6)
    if axis == "y":  # the occupied cushion resonates near 4 Hz and isolates above about 6 Hz
        fine = np.linspace(1.0, 10.0, 9001)
        magnitude = np.abs(transmissibility(_theta(params), "y", fine))
        assert 3.6 < fine[np.argmax(magnitude)] < 4.4 and 1.4 < magnitude.max() < 2.0
        assert magnitude[fine >= 7.0].max() < 1.0


def test_occupant_off_pad_reads_the_chassis_exactly() -> None:
    from loader_model.simulation.courses import single_obstacle_course
    from loader_model.simulation.simulator import course_input, simulate

    params = plant_parameter_vector(None, "full", PlantOptions(occupant=False))
    plant = plant_function()
    rng = np.random.default_rng(3)
    index = {name: OUTPUT_NAMES.index(name) for name in ("f_Sx", "f_Sy", "f_Px", "f_Py")}
    for _ in range(5):  # any state, the occupant's too
        x = rng.normal(0.0, 0.01, len(STATE_NAMES))
        x[STATE_NAMES.index("p_A")], x[STATE_NAMES.index("p_B")] = 1.2e7, 2e6
        w = rng.normal(0.0, 0.01, len(EXOGENOUS_NAMES))
        y = np.asarray(plant(x, 0.0, w, params)[1]).ravel()
        assert y[index["f_Px"]] == y[index["f_Sx"]] and y[index["f_Py"]] == y[index["f_Sy"]]
    result = simulate(course_input(single_obstacle_course(9.0), params), params, duration_s=3.0)
    np.testing.assert_array_equal(result["f_Px"], result["f_Sx"])
    np.testing.assert_array_equal(result["f_Py"], result["f_Sy"])
    assert np.ptp(result["f_Sy"]) > 1.0  # the board did move the chassis
    for name in OCCUPANT_STATE_NAMES:
        assert not result[name].any()  # not driven: the states stay at their static zero
    linear = linearise_plant(params).state_space()
    assert not set(OCCUPANT_STATE_NAMES) & set(linear.state_labels)  # dropped as inert
    on = linearise_plant(plant_parameter_vector(None, "full")).state_space()
    np.testing.assert_array_equal(  # the loader's part is the same with the occupant on
        np.asarray(on.A)[: linear.nstates, : linear.nstates], np.asarray(linear.A)
    )
