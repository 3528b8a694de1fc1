"""The tyre contact law (derive/contact.py) as a stiff integrator meets it: obstacle courses,
lift-off and landing, the energy balance through contact transitions.

The road inputs here are closed-form rigid-wheel profiles (the wheel centre of a disc of radius R
rolling over a rectangular board climbs on a circular arc around the board's edge), written as
CasADi expressions of time so that CVODES integrates them without an input table. They are test
inputs, not the package's road model.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

import loader_model_generated as generated
from loader_model.vehicle.dynamics import LoaderDynamics

WHEEL_RADIUS_M = 0.42  # 12-16.5 skid-steer tyre
BOARD_WIDTH_M = 0.14  # a 2x6 plank laid flat: 38 mm x 140 mm (the paper's "4 cm tall" boards)
NAMES = list(generated.PARAMETER_NAMES)


def _edge(distance: ca.SX, height: float) -> ca.SX:
    """Wheel-centre rise (minus R) near an edge of height ``height`` at ``distance`` from it."""
    reach = np.sqrt(WHEEL_RADIUS_M**2 - (WHEEL_RADIUS_M - height) ** 2)
    arc = height - WHEEL_RADIUS_M + ca.sqrt(ca.fmax(WHEEL_RADIUS_M**2 - distance**2, 0.0))
    return ca.if_else(ca.fabs(distance) < reach, arc, 0.0)


def board(s: ca.SX, height: float = 0.04, width: float = BOARD_WIDTH_M) -> ca.SX:
    """Effective height under a rigid wheel whose centre is at ``s`` (board from 0 to width)."""
    on_top = ca.logic_and(s >= 0.0, s <= width)
    return ca.if_else(
        on_top, height, ca.if_else(s < 0.0, _edge(s, height), _edge(s - width, height))
    )


def bump(s: ca.SX, height: float = 0.04, length_m: float = 0.5) -> ca.SX:
    """A smooth (half-cosine) bump of ``height`` over ``length_m``."""
    inside = ca.logic_and(s > 0.0, s < length_m)
    return ca.if_else(inside, 0.5 * height * (1.0 - ca.cos(2.0 * np.pi * s / length_m)), 0.0)


def drop(s: ca.SX, depth: float = 0.1) -> ca.SX:
    """Driving off a ledge of ``depth`` at s = 0: the wheel rolls round the edge, then falls."""
    reach = np.sqrt(WHEEL_RADIUS_M**2 - (WHEEL_RADIUS_M - depth) ** 2)
    arc = ca.sqrt(ca.fmax(WHEEL_RADIUS_M**2 - s**2, 0.0)) - WHEEL_RADIUS_M
    return ca.if_else(s <= 0.0, 0.0, ca.if_else(s < reach, arc, -depth))


def _course_integrator(model, parameters, profile, speed_m_s, grid):
    """CVODES over (p, ṗ, ξ) with the cylinder force held at its static value."""
    named = dict(zip(NAMES, parameters, strict=True))
    wheelbase = named["A_x"] - named["B_x"]
    time, state = ca.SX.sym("t"), ca.SX.sym("x", 10)
    p, pd, anchor = state[:4], state[4:8], state[8:]
    road = ca.vertcat(0.0, profile(speed_m_s * time), 0.0, profile(speed_m_s * time - wheelbase))
    road_rate = ca.jtimes(road, time, ca.SX(1.0))
    force = model.static_cylinder_force_N
    pdd, anchor_rate = generated.function("forward_dynamics")(
        p, pd, anchor, force, road, road_rate, ca.DM.zeros(3), parameters
    )
    dae = {"x": state, "t": time, "ode": ca.vertcat(pd, pdd, anchor_rate)}
    options = {"reltol": 1e-6, "abstol": 1e-8, "max_step_size": 0.01, "max_num_steps": 100000}
    contact = generated.function("tyre_contact")(p, pd, anchor, road, road_rate, parameters)
    tyre_forces = ca.Function("tyre_forces", [time, state], [contact[0]])
    return ca.integrator("course", "cvodes", dae, 0.0, grid, options), tyre_forces


def _boards(height: float, spacing_m: float, count: int = 5, start_m: float = 2.0):
    return lambda s: sum(board(s - (start_m + k * spacing_m), height) for k in range(count))


def _bumps(spacing_m: float, count: int = 5, start_m: float = 2.0):
    return lambda s: sum(bump(s - (start_m + k * spacing_m)) for k in range(count))


COURSES = {
    "paper 9 km/h, 6 m": (_boards(0.04, 6.0), 2.5),
    "paper 18 km/h, 9 m": (_boards(0.04, 9.0), 5.0),
    "20 mm boards": (_boards(0.02, 6.0), 2.5),
    "smooth 40 mm bumps": (_bumps(6.0), 2.5),
}


@pytest.mark.parametrize("load", ["empty", "full"])
@pytest.mark.parametrize("course", list(COURSES))
def test_cvodes_passes_the_courses_in_few_steps(load: str, course: str) -> None:
    """12 s over five obstacles: fewer than 30 000 CVODES steps (rtol 1e-6), a finite result.

    Measured on the development machine: 11 600-15 300 steps, 0.3-0.6 s per run (SX, not
    compiled); with the if_else contact switch of the first release 20 mm boards took 920 000.
    """
    model = LoaderDynamics.from_parameters(None, load)
    profile, speed = COURSES[course]
    grid = np.linspace(0.0, 12.0, 2401)
    integrator, _ = _course_integrator(model, model.parameters, profile, speed, grid)
    states = np.asarray(integrator(x0=np.zeros(10))["xf"]).T
    assert np.all(np.isfinite(states))
    assert integrator.stats()["nsteps"] < 30_000
    assert np.abs(states[:, 1]).max() > 0.005  # the obstacles really shook the loader


def test_paper_course_lifts_a_tyre_off() -> None:
    """The 4 cm boards at 18 km/h make tyres leave the ground: the contact law is exercised."""
    model = LoaderDynamics.from_parameters(None, "empty")
    profile, speed = COURSES["paper 18 km/h, 9 m"]
    grid = np.linspace(0.0, 12.0, 4801)
    integrator, tyre_forces = _course_integrator(model, model.parameters, profile, speed, grid)
    states = np.asarray(integrator(x0=np.zeros(10))["xf"]).T
    forces = np.array(
        [np.asarray(tyre_forces(t, x)).ravel() for t, x in zip(grid, states, strict=True)]
    )
    assert forces[:, 1].min() == 0.0 or forces[:, 3].min() == 0.0
    assert forces[:, [1, 3]].min() >= 0.0  # never pulling
    # The horizontal force exceeds the friction limit only while a loaded spring relaxes at
    # lift-off (time constant tau_slip, derive/contact.py): measured over this run, an excess
    # impulse of 1.3 and 1.1 kN·s (axles A, B) against 59 and 61 kN·s of |F_x| impulse (2.2 and
    # 1.8 %); over all eight course runs of the test above at most 3.5 %.
    mu = model.parameter("mu_road")
    step = grid[1] - grid[0]
    for horizontal, vertical in ((0, 1), (2, 3)):
        excess = np.maximum(np.abs(forces[:, horizontal]) - (mu * forces[:, vertical] + 1.0), 0.0)
        assert excess.sum() * step <= 0.03 * np.abs(forces[:, horizontal]).sum() * step


def test_a_drop_lands_without_drift() -> None:
    """Driving off a 10 cm ledge at 9 km/h: both axles fly, land and settle where they land.

    The horizontal position settles at the mean slid distance of the two contact points (the
    anchors); the horizontal tyre springs end relaxed.
    """
    model = LoaderDynamics.from_parameters(None, "empty")
    grid = np.linspace(0.0, 5.0, 5001)
    integrator, tyre_forces = _course_integrator(
        model, model.parameters, lambda s: drop(s - 1.0), 2.5, grid
    )
    states = np.asarray(integrator(x0=np.zeros(10))["xf"]).T
    assert np.all(np.isfinite(states))
    forces = np.array(
        [np.asarray(tyre_forces(t, x)).ravel() for t, x in zip(grid, states, strict=True)]
    )
    assert forces[:, 1].min() == 0.0 and forces[:, 3].min() == 0.0  # both axles were airborne
    final = states[-1]
    assert final[1] == pytest.approx(-0.1, abs=0.003)  # the loader sits 10 cm lower
    # x_H settles between the two anchors; measured: x_H −16.2 mm, anchors −15.3 and −17.3 mm
    # (the tyres slid that far on landing and re-anchored there)
    assert min(final[8:]) - 1e-3 <= final[0] <= max(final[8:]) + 1e-3
    assert abs(final[0]) < 0.02
    assert np.abs(states[-500:, 0] - final[0]).max() < 1e-3  # and stays there


def _vertical_potential(force: np.ndarray, width: float, stiffness: float) -> np.ndarray:
    """Elastic energy of the unilateral vertical law at elastic force ``force`` (= F_y0 − k u):
    V = W(F)/k with W(F) = ∫ U(f) df from −∞, U the C¹ clamp of derive/contact.py."""
    low = np.where(force <= -width, 0.0, (force + width) ** 3 / (12.0 * width))
    high = 2.0 * width**2 / 3.0 + (force**2 - width**2) / 2.0
    return np.where(force >= width, high, low) / stiffness


def test_energy_balance_closes_through_contact_transitions() -> None:
    """Off a 10 cm ledge and over a board, damped tyres, cylinder force constant: the stored
    energy change plus the dissipation equals the road's work. The issue asks for 1 %.

    Dissipation and road work are integrated by CVODES as extra states from the contact law's
    power terms: vertical damping (U(F_s) − U(F_s + F_d)) v_y and horizontal χ c v_x² + k e ξ̇
    (derive/contact.py); road work F_y ẇ_y. Stored energy: kinetic (generated M), gravity,
    cylinder (constant force), tyres (½ k e² and the clamp's potential).
    """
    model = LoaderDynamics.from_parameters(None, "empty")
    par = model.parameters
    named = dict(zip(NAMES, par, strict=True))
    wheelbase = named["A_x"] - named["B_x"]
    speed = 2.5

    def profile(s):
        return drop(s - 1.0) + board(s - 4.0, 0.04)

    time, state = ca.SX.sym("t"), ca.SX.sym("x", 12)
    p, pd, anchor = state[:4], state[4:8], state[8:10]
    road = ca.vertcat(0.0, profile(speed * time), 0.0, profile(speed * time - wheelbase))
    road_rate = ca.jtimes(road, time, ca.SX(1.0))
    force = model.static_cylinder_force_N
    pdd, anchor_rate = generated.function("forward_dynamics")(
        p, pd, anchor, force, road, road_rate, ca.DM.zeros(3), par
    )
    positions = generated.function("point_positions")(p, par)
    velocities = generated.function("point_velocities")(p, pd, par)
    tyre_force = generated.function("tyre_contact")(p, pd, anchor, road, road_rate, par)[0]
    dissipation, road_work = 0.0, 0.0
    for index, axle in enumerate("AB"):
        r_axle, v_axle = positions["ABCDEGHNS".index(axle)], velocities["ABCDEGHNS".index(axle)]
        k_x, c_x = named[f"k_{axle}x"], named[f"c_{axle}x"]
        k_y = named[f"k_{axle}y"]
        w_x, w_y = road[2 * index], road[2 * index + 1]
        wd_y = road_rate[2 * index + 1]
        stretch = r_axle[0] - named[f"{axle}_x"] - w_x - anchor[index]
        relative_y = v_axle[1] - wd_y
        elastic_y = named[f"F_{axle}y0"] - k_y * (r_axle[1] - named[f"{axle}_y"] - w_y)
        width = named["F_transition"]
        clamp = ca.if_else(
            elastic_y >= width,
            elastic_y,
            ca.if_else(elastic_y <= -width, 0.0, (elastic_y + width) ** 2 / (4 * width)),
        )
        f_y = tyre_force[2 * index + 1]
        sliding = anchor_rate[index]  # = σ (v_x + e/τ)
        u = f_y / (2 * width)
        fade = ca.if_else(u >= 1, 1.0, 3 * u**2 - 2 * u**3)  # χ of derive/contact.py
        dissipation += (clamp - f_y) * relative_y
        dissipation += fade * c_x * v_axle[0] ** 2 + k_x * stretch * sliding
        road_work += f_y * wd_y
    ode = ca.vertcat(pd, pdd, anchor_rate, dissipation, road_work)
    grid = np.linspace(0.0, 4.0, 4001)
    options = {"reltol": 1e-9, "abstol": 1e-10, "max_step_size": 0.002, "max_num_steps": 200000}
    integrator = ca.integrator(
        "balance", "cvodes", {"x": state, "t": time, "ode": ode}, 0.0, grid, options
    )
    states = np.asarray(integrator(x0=np.zeros(12))["xf"]).T

    x_cyl = generated.function("cylinder_kinematics")
    x_cyl0 = float(x_cyl(np.zeros(4), np.zeros(4), par)[0])
    mass = generated.function("mass_matrix")
    wheels = ca.Function("wheels", [time], [road])

    def stored(t: float, row: np.ndarray) -> float:
        r = dict(
            zip(
                "ABCDEGHNS",
                (
                    np.asarray(v).ravel()
                    for v in generated.function("point_positions")(row[:4], par)
                ),
                strict=True,
            )
        )
        kinetic = 0.5 * row[4:8] @ np.asarray(mass(row[:4], par)) @ row[4:8]
        gravity = named["g"] * (
            named["m_1"] * r["H"][1] + named["m_2"] * (r["G"][1] - named["G_y"])
        )
        cylinder = -force * (float(x_cyl(row[:4], row[4:8], par)[0]) - x_cyl0)
        w = np.asarray(wheels(t)).ravel()
        tyres = 0.0
        for index, axle in enumerate("AB"):
            stretch = r[axle][0] - named[f"{axle}_x"] - w[2 * index] - row[8 + index]
            tyres += 0.5 * named[f"k_{axle}x"] * stretch**2
            elastic = named[f"F_{axle}y0"] - named[f"k_{axle}y"] * (
                r[axle][1] - named[f"{axle}_y"] - w[2 * index + 1]
            )
            tyres += float(
                _vertical_potential(np.array(elastic), named["F_transition"], named[f"k_{axle}y"])
            )
        return float(kinetic + gravity + cylinder + tyres)

    change = stored(grid[-1], states[-1]) - stored(0.0, states[0])
    dissipated, worked = states[-1, 10], states[-1, 11]
    residual = change + dissipated - worked
    assert dissipated > 1000.0  # joules: the transitions really dissipate
    assert abs(residual) <= 1e-6 * max(dissipated, abs(worked)), (change, dissipated, worked)
