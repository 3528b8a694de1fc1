"""An independent derivation with sympy.physics.mechanics (Kane's method, built from frames, points
and rigid bodies) agrees with the emitted mass matrix and forcing at random points."""

from __future__ import annotations

import numpy as np
import pytest

import loader_model_generated as generated

pytestmark = pytest.mark.slow


def _kane_model():
    import sympy as sp
    from sympy.physics import mechanics as me

    x, y, th1, th2 = me.dynamicsymbols("x y th1 th2")
    u = me.dynamicsymbols("u0:4")
    names = generated.PARAMETER_NAMES
    par = dict(zip(names, sp.symbols(names, real=True), strict=True))
    force_act = sp.Symbol("F_act", real=True)
    road = sp.symbols("wAx wAy wBx wBy", real=True)
    road_rate = sp.symbols("vAx vAy vBx vBy", real=True)
    f_dx, f_dy, m_d = sp.symbols("F_dx F_dy M_d", real=True)

    world = me.ReferenceFrame("N")
    chassis = world.orientnew("B1", "Axis", [th1, world.z])
    boom = world.orientnew("B2", "Axis", [th2, world.z])
    chassis.set_ang_vel(world, u[2] * world.z)
    boom.set_ang_vel(world, u[3] * world.z)
    origin = me.Point("O")
    origin.set_vel(world, 0)
    h = origin.locatenew("H", x * world.x + y * world.y)
    h.set_vel(world, u[0] * world.x + u[1] * world.y)

    def on_chassis(letter: str) -> me.Point:
        point = h.locatenew(letter, par[f"{letter}_x"] * chassis.x + par[f"{letter}_y"] * chassis.y)
        point.v2pt_theory(h, world, chassis)
        return point

    a, b, c, d = (on_chassis(k) for k in "ABCD")

    def on_boom(letter: str) -> me.Point:
        offset = (par[f"{letter}_x"] - par["D_x"]) * boom.x + (
            par[f"{letter}_y"] - par["D_y"]
        ) * boom.y
        point = d.locatenew(letter, offset)
        point.v2pt_theory(d, world, boom)
        return point

    e, g_point = on_boom("E"), on_boom("G")
    body_1 = me.RigidBody(
        "chassis", h, chassis, par["m_1"], (me.inertia(chassis, 0, 0, par["J_1"]), h)
    )
    body_2 = me.RigidBody(
        "boom", g_point, boom, par["m_2"], (me.inertia(boom, 0, 0, par["J_2"]), g_point)
    )

    loads = [
        (h, -par["g"] * par["m_1"] * world.y + f_dx * world.x + f_dy * world.y),
        (g_point, -par["g"] * par["m_2"] * world.y),
        (chassis, m_d * world.z),
    ]
    for point, letter, w, wd in (
        (a, "A", road[:2], road_rate[:2]),
        (b, "B", road[2:], road_rate[2:]),
    ):
        position = point.pos_from(origin).to_matrix(world)
        velocity = point.vel(world).to_matrix(world)
        dx = position[0] - par[f"{letter}_x"] - w[0]
        dy = position[1] - par[f"{letter}_y"] - w[1]
        fx = -par[f"k_{letter}x"] * dx - par[f"c_{letter}x"] * (velocity[0] - wd[0])
        fy = (
            par[f"F_{letter}y0"]
            - par[f"k_{letter}y"] * dy
            - par[f"c_{letter}y"] * (velocity[1] - wd[1])
        )
        loads.append((point, fx * world.x + fy * world.y))
    direction = e.pos_from(c)
    unit = direction / direction.magnitude()
    loads += [(e, force_act * unit), (c, -force_act * unit)]

    q = [x, y, th1, th2]
    kane = me.KanesMethod(
        world,
        q_ind=q,
        u_ind=u,
        kd_eqs=[
            qd - ud for qd, ud in zip(sp.diff(sp.Matrix(q), me.dynamicsymbols._t), u, strict=True)
        ],
    )
    kane.kanes_equations([body_1, body_2], loads)
    inputs = [*q, *u, force_act, *road, *road_rate, f_dx, f_dy, m_d, *par.values()]
    return sp.lambdify(inputs, [kane.mass_matrix, kane.forcing], "numpy")


def test_kane_mass_matrix_and_forcing_agree_with_generated() -> None:
    evaluate = _kane_model()
    residual = generated.function("residual_jacobians")
    rng = np.random.default_rng(20091)
    for _ in range(25):
        p, pd = rng.uniform(-1, 1, 4), rng.uniform(-2, 2, 4)
        force = rng.uniform(-5e4, 5e4)
        road, road_rate, disturbance = (
            rng.uniform(-0.05, 0.05, 4),
            rng.uniform(-1, 1, 4),
            rng.uniform(-500, 500, 3),
        )
        params = rng.uniform(-1.5, 1.5, len(generated.PARAMETER_NAMES))
        for k, name in enumerate(generated.PARAMETER_NAMES):
            if name in ("m_1", "m_2", "J_1", "J_2") or name.startswith(("k_", "c_")):
                params[k] = abs(params[k]) * 1e3 + 1.0
        mass_kane, forcing_kane = evaluate(*p, *pd, force, *road, *road_rate, *disturbance, *params)
        r, *_, mass = residual(p, pd, np.zeros(4), force, road, road_rate, disturbance, params)[:4]
        np.testing.assert_allclose(np.asarray(mass), mass_kane, rtol=1e-10, atol=1e-9)
        # M p̈ = forcing  <=>  r(p̈ = 0) = −forcing
        np.testing.assert_allclose(
            -np.asarray(r).ravel(),
            np.asarray(forcing_kane, dtype=float).ravel(),
            rtol=1e-9,
            atol=1e-6,
        )
