"""Undamped, unforced motion conserves energy (kinetic + tyre springs + cylinder spring + gravity).

The energy is assembled here from the generated mass matrix, point positions and cylinder length;
the motion comes from the generated forward dynamics (forces through Jacobian transposes), so the
test checks that the two routes agree. Integrated with SciPy's DOP853 (8th order) at rtol 1e-13;
CVODES (BDF, at most 5th order) drifted by 6e-8 at 1e-13 tolerances: integrator error, not model
error.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
from scipy.integrate import solve_ivp

import loader_model_generated as generated
from loader_model.vehicle.dynamics import LoaderDynamics

K_EQ_N_PER_M = 2.0e7  # hydraulic spring of the lift cylinders (order of Eq. 28 for this loader)


def test_undamped_motion_conserves_energy(paper_layout: dict[str, float]) -> None:
    undamped = dict(paper_layout, c_Ax=0.0, c_Ay=0.0, c_Bx=0.0, c_By=0.0)
    model = LoaderDynamics(undamped)
    params = model.parameters
    named = dict(zip(generated.PARAMETER_NAMES, params, strict=True))
    f_act0 = model.static_cylinder_force_N
    x_cyl0 = model.cylinder_kinematics(np.zeros(4))["x_cyl"]

    # state (p, ṗ, ξ): the tyre anchors are integrated too; sticking tyres keep them at 0
    state = ca.SX.sym("state", 10)
    p, pd, anchor = state[:4], state[4:8], state[8:]
    x_cyl = generated.function("cylinder_kinematics")(p, pd, params)[0]
    force = f_act0 - K_EQ_N_PER_M * (x_cyl - x_cyl0)
    zeros4, zeros3 = ca.DM.zeros(4), ca.DM.zeros(3)
    pdd, anchor_rate = generated.function("forward_dynamics")(
        p, pd, anchor, force, zeros4, zeros4, zeros3, params
    )
    rate = ca.Function("rate", [state], [ca.vertcat(pd, pdd, anchor_rate)])
    start = np.array([0.002, -0.004, 0.004, -0.006, 0.03, 0.02, -0.05, 0.08, 0.0, 0.0])
    solution = solve_ivp(
        lambda _, y: np.asarray(rate(y)).ravel(),
        (0.0, 5.0),
        start,
        method="DOP853",
        rtol=1e-13,
        atol=1e-15,
        t_eval=np.linspace(0.0, 5.0, 501),
    )
    assert solution.success, solution.message
    trajectory = solution.y.T
    assert np.all(trajectory[:, 8:] == 0.0)  # the tyres stuck throughout: no anchor moved
    trajectory = trajectory[:, :8]

    mass_matrix = generated.function("mass_matrix")
    positions = generated.function("point_positions")
    cylinder = generated.function("cylinder_kinematics")

    def energy(row: np.ndarray) -> float:
        p_row, pd_row = row[:4], row[4:]
        kinetic = 0.5 * pd_row @ np.asarray(mass_matrix(p_row, params)) @ pd_row
        r = dict(
            zip("ABCDEGHNS", (np.asarray(v).ravel() for v in positions(p_row, params)), strict=True)
        )
        gravity = named["g"] * (
            named["m_1"] * r["H"][1] + named["m_2"] * (r["G"][1] - named["G_y"])
        )
        tyres = 0.0
        for axle in "AB":
            dx = r[axle][0] - named[f"{axle}_x"]
            dy = r[axle][1] - named[f"{axle}_y"]
            tyres += 0.5 * named[f"k_{axle}x"] * dx**2 + 0.5 * named[f"k_{axle}y"] * dy**2
            tyres -= named[f"F_{axle}y0"] * dy
        stretch = float(cylinder(p_row, pd_row, params)[0]) - x_cyl0
        spring = 0.5 * K_EQ_N_PER_M * stretch**2 - f_act0 * stretch
        return float(kinetic + gravity + tyres + spring)

    energies = np.array([energy(row) for row in trajectory])
    assert energies[0] > 1.0  # a real perturbation: joules, not round-off
    assert np.ptp(trajectory[:, 3]) > 0.004  # the loader really moves
    drift = np.abs(energies - energies[0]).max() / energies[0]
    assert drift < 1e-8, f"relative energy drift {drift:.2e}"
