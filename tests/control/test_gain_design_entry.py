"""design_gains, the one entry point of the linear gain design: each method gives what its route
gives when called directly, and bad arguments are named."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.control import design_gains, output_feedback_lqr
from loader_model.control.comfort_design import comfort_plants, optimise_gain


@pytest.fixture(scope="module")
def plants():
    return comfort_plants(("empty", "full"), "C", 9.0)


def test_lqr_is_the_output_feedback_lqr_of_each_plant(plants) -> None:
    design = design_gains(plants, "lqr", lqr_effort=1e-2)
    assert design.method == "lqr" and design.converged and set(design.gains) == {"empty", "full"}
    for plant in plants:
        # Eq. 41, 42 solved here from the stated weights, from zero (the homotopy's start)
        direct = output_feedback_lqr(
            (plant.A, plant.B_u, plant.C_y),
            plant.C_z.T @ plant.C_z,
            np.array([[1e-2]]),
            plant.B_w @ plant.B_w.T,
        )
        assert direct.converged
        # Two starts (Table 3 with k_φ flipped, and zero) reach the same optimum: the costs
        # agreed to 2.3e-11 and the gains to 2.2e-8 (Haswell) and 1.9e-5 (SkylakeX kernel),
        # relative: on these 38-state plants J is flat to round-off well before the gain is.
        result = design.details[plant.name]
        np.testing.assert_allclose(result.cost, direct.cost, rtol=1e-9)
        gain = design.gains[plant.name]
        assert np.abs(gain - direct.gain).max() <= 1e-4 * np.abs(direct.gain).max()
    with pytest.raises(ValueError, match="has one gain per plant"):
        _ = design.gain


def test_optimise_is_the_comfort_optimisation(plants) -> None:
    design = design_gains(plants, "optimise", solver="ipopt")
    direct = optimise_gain(plants, solver="ipopt")
    assert design.converged and design.summary.startswith("ipopt: ")
    np.testing.assert_array_equal(design.gain, direct["gain"])
    assert all(np.array_equal(g, design.gain) for g in design.gains.values())


@pytest.mark.parametrize(
    ("args", "kwargs", "message"),
    [
        (("newton",), {}, r"method 'newton': allowed: 'lqr', 'optimise'"),
        (("optimise",), {"solver": "cg"}, r"solver 'cg': allowed: 'bfgs' or 'ipopt'"),
    ],
)
def test_bad_arguments_are_named(plants, args, kwargs, message) -> None:
    with pytest.raises(ValueError, match=message):
        design_gains(plants, *args, **kwargs)
    with pytest.raises(ValueError, match="at least one design plant"):
        design_gains([], "lqr")
