"""The benchmark's SymPy/scipy baseline (tests/bench_baseline.py) is the same model as the plant.

Checks: the lambdified right-hand side, outputs and Jacobian equal the CasADi plant's at
perturbed states (to round-off; measured worst relative difference 7e-15), and the baseline's closed loop
from rest over the paper's first board agrees with the CVODES reference
(:mod:`loader_model.simulation.reference`, rtol 1e-10) in the seat trace norm of
``tests/simulation/test_simulator.py``: ‖s − s_ref‖_rms / ‖s_ref − s_ref(0)‖_rms per signal (f_Sx, f_Sy,
θ̈1). Measured on the development machine, LSODA at rtol 1e-6, atol 1e-9: 0.0036 %, 0.0040 %,
0.0040 % over the first 2.5 s (this test, limit 0.1 %), 0.0039 %, 0.0046 %, 0.0058 % over the
first 3 s (``make bench``); the fast simulator (ROS2, 1 ms) is at 0.9 %, 1.3 %, 2.2 % there.
About 100 s: marked slow.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from loader_model.plant.equilibrium import static_state
from loader_model.plant.plant import OUTPUT_NAMES, plant_function
from loader_model.plant.plant_parameters import PlantOptions, plant_parameter_vector
from loader_model.simulation import paper_course
from loader_model.simulation.reference import reference_simulation
from loader_model.simulation.simulator import course_input
from tests.bench_baseline import (
    LOADER_STATES,
    baseline_model,
    baseline_simulation,
    seat_agreement,
)

#: The baseline is the loader without the occupant (its 15 states); the pad then reads f_S.
NO_OCCUPANT = PlantOptions(occupant=False)

pytestmark = pytest.mark.slow

SEAT = ("f_Sx", "f_Sy", "thetadd_1")
#: From rest until the front axle is over the first board (1.93 s) and the rear one reaches it.
SPAN_S = 2.5


@pytest.fixture(scope="module")
def model():
    """The lambdified baseline model (built once: about 2 s)."""
    return baseline_model()


@pytest.mark.parametrize("modules", ["numpy", "math"])
def test_the_lambdified_plant_equals_the_casadi_plant(modules: str) -> None:
    """ẋ and y at perturbed states and inputs, to round-off."""
    model = baseline_model(modules)
    params = plant_parameter_vector(None, "empty", NO_OCCUPANT)
    mechanical = model.completed(params)
    x0, u0 = static_state(params)
    x0 = np.r_[x0[:LOADER_STATES], np.zeros(x0.size - LOADER_STATES)]
    scale = np.r_[np.full(8, 1e-2), 1e-3, 1e-3, 1e5, 1e5, 1e-7, 1e-5, 1e-6, np.zeros(8)]
    rng = np.random.default_rng(12)
    for _ in range(5):
        x = x0 + rng.normal(size=x0.size) * scale
        w = rng.normal(size=11) * np.r_[np.full(8, 1e-2), 100.0, 100.0, 100.0]
        u = u0 * (1 + rng.normal())
        xdot, y = (np.asarray(v, dtype=float).ravel() for v in plant_function()(x, u, w, params))
        xdot, loader = xdot[:LOADER_STATES], x[:LOADER_STATES]
        np.testing.assert_allclose(
            model.rhs(loader, u, w, params, mechanical),
            xdot,
            rtol=1e-9,
            atol=1e-9 * np.abs(xdot).max(),
        )
        np.testing.assert_allclose(
            model.plant_outputs(loader, u, w, params, mechanical), y, rtol=1e-9, atol=1e-6
        )


def test_the_lambdified_jacobian_equals_casadis() -> None:
    """∂ẋ/∂x of the baseline (SymPy forward differentiation + translated hydraulics) against the
    AD Jacobian of the CasADi plant, at perturbed states."""
    model = baseline_model("math", jacobian=True)
    params = plant_parameter_vector(None, "empty", NO_OCCUPANT)
    mechanical = model.completed(params)
    plant = plant_function()
    x, u, w, theta = (ca.SX.sym(plant.name_in(i), plant.size1_in(i)) for i in range(4))
    exact = ca.Function(
        "plant_jacobian", [x, u, w, theta], [ca.jacobian(plant(x, u, w, theta)[0], x)]
    )
    x0, u0 = static_state(params)
    scale = np.r_[np.full(8, 1e-2), 1e-3, 1e-3, 1e5, 1e5, 1e-7, 1e-5, 1e-6, np.zeros(8)]
    rng = np.random.default_rng(3)
    for _ in range(3):
        state = x0 + rng.normal(size=x0.size) * scale
        road = rng.normal(size=11) * np.r_[np.full(8, 1e-2), 100.0, 100.0, 100.0]
        command = u0 * (1 + rng.normal())
        want = np.asarray(exact(state, command, road, params), dtype=float)
        want = want[:LOADER_STATES, :LOADER_STATES]
        got = model.jacobian(state[:LOADER_STATES], command, road, params, mechanical)
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12 * np.abs(want).max())


def test_the_baseline_matches_the_cvodes_reference_over_the_first_board(model) -> None:
    """Empty bucket, hold controller, first 2.5 s of the paper's course at 9 km/h: seat trace
    within 0.1 % (the fast simulator's own limit is 6 %, tests/simulation/test_simulator.py)."""
    params = plant_parameter_vector(None, "empty", NO_OCCUPANT)
    road = course_input(paper_course(9.0, settle_s=10.0), params)
    baseline = baseline_simulation(road, params, duration_s=SPAN_S, model=model)
    reference = reference_simulation(road, params, duration_s=SPAN_S)
    columns = [OUTPUT_NAMES.index(name) for name in SEAT]
    agreement = seat_agreement(baseline["y"][:, columns], reference["y"][:, columns])
    assert np.all(agreement <= 1e-3), agreement
