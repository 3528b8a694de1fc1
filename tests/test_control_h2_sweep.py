"""Slow: the H2 design from many warm starts and margins either meets the margin or says so."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.control import DesignPlant, H2DesignError, design_h2_gain, output_feedback_lqr
from tests.control_plant import MEASURED, PERFORMANCE, TABLE3_GAIN, loader_design_plant

Y, Z = list(MEASURED), list(PERFORMANCE)


@pytest.mark.slow
def test_warm_start_sweep() -> None:
    systems = {load: loader_design_plant(load) for load in ("empty", "full")}
    plants = [
        DesignPlant.from_statespace(
            systems[load],
            control=["u"],
            noise=["nu_Fy", "nu_M"],
            measured=Y,
            performance=Y + Z,
            name=load,
        )
        for load in ("empty", "full")
    ]
    c, b_w = np.asarray(systems["empty"].C), np.asarray(systems["empty"].B)[:, 1:]
    lqr = output_feedback_lqr(
        systems["empty"], c.T @ c, np.eye(1), b_w @ b_w.T, inputs=["u"], outputs=Y
    )
    starts = [lqr.gain, -lqr.gain, TABLE3_GAIN, -TABLE3_GAIN, np.zeros((1, 4))]
    optimum = {0.0: 0.4237270747766, 0.01: 0.4237270747766, 0.1: 0.42407}
    solved = 0
    for margin, best in optimum.items():
        for start in starts:
            try:
                result = design_h2_gain(plants, start, effort_weight=np.eye(1), margin=margin)
            except H2DesignError as error:
                assert not error.result.success
                continue
            solved += 1
            assert result.margin >= margin and all(np.max(p.real) < -margin for p in result.poles)
            assert result.cost <= best * (1 + 1e-5)
    assert solved >= 13  # measured: 14 of 15 (lqr.gain with margin 0.1 fails and says so)
