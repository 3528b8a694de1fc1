"""Slow: the gain design from many starts and margins meets the margin and says when it stalls."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.control import DesignPlant, output_feedback_lqr
from loader_model.control.comfort_design import optimise_gain
from tests.control.test_gain_design import GRAMIAN_OPTIMUM
from tests.control_plant import MEASURED, TABLE3_GAIN, loader_design_plant, loader_h2_plants

Y = list(MEASURED)


def _margin(plants: list[DesignPlant], gain: np.ndarray) -> float:
    return min(-np.max(np.linalg.eigvals(p.A - p.B_u @ gain @ p.C_y).real) for p in plants)


@pytest.mark.slow
def test_start_sweep() -> None:
    systems = {load: loader_design_plant(load) for load in ("empty", "full")}
    plants = loader_h2_plants(systems)
    c, b_w = np.asarray(systems["empty"].C), np.asarray(systems["empty"].B)[:, 1:]
    lqr = output_feedback_lqr(
        systems["empty"], c.T @ c, np.eye(1), b_w @ b_w.T, inputs=["u"], outputs=Y
    )
    starts = [lqr.gain, -lqr.gain, TABLE3_GAIN, -TABLE3_GAIN, np.zeros((1, 4))]
    reached = {"bfgs": 0, "ipopt": 0}
    for margin in (0.0, 0.01, 0.1):
        for start in starts:
            for solver in ("bfgs", "ipopt"):
                result = optimise_gain(
                    plants, start, effort=np.eye(1), margin=margin, solver=solver
                )
                assert _margin(plants, result["gain"]) > margin
                if margin < 0.1:  # inactive margin: the unconstrained optimum
                    if result["converged"]:
                        reached[solver] += 1
                        np.testing.assert_allclose(result["cost"], GRAMIAN_OPTIMUM[0.01], rtol=1e-8)
                    else:  # measured: BFGS from −K_LQR at σ = 0.01 stalls 2.5e-3 above it
                        assert result["cost"] <= GRAMIAN_OPTIMUM[0.01] * (1 + 5e-3)
                else:  # active margin: interior methods stall above it (measured ≤ 2.5e-3)
                    assert GRAMIAN_OPTIMUM[0.01] <= result["cost"]
                    assert result["cost"] <= GRAMIAN_OPTIMUM[0.1] * (1 + 5e-3)
    # measured: IPOPT 10 of 10, BFGS 9 of 10 at the inactive margins
    assert reached["ipopt"] == 10 and reached["bfgs"] >= 9
