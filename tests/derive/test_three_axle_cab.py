"""A third description that no shipped machine is (issue 23): three axles and a cab on a vertical
sliding mount with a spring-damper (a suspended cab), derived through ``derive/`` into a
temporary folder. Checked: the statically indeterminate static loads (the level-road
compatibility of :func:`derive.mechanics._static_loads`), the mass matrix against an independent
``sympy.physics.mechanics`` model at one configuration, energy conservation of the undamped
motion, and that the runtime refuses the description without its generated folder, with advice."""

from __future__ import annotations

import importlib
import sys
from pathlib import Path
from types import ModuleType

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from tests.derive.three_axle_cab import DESCRIPTION, POINTS, VALUES

#: Deriving the fixture takes about 10 s with SymPy; the shipped machines' checks stay fast.
pytestmark = pytest.mark.slow

PACKAGE = "three_axle_cab_fixture"
N = 5  # x_H, y_H, θ1, θ2, s_cab
AXLES = ("A", "B", "R")
K_EQ_N_PER_M = 2.0e7  # the lift cylinders held as a hydraulic spring (order of Eq. 28)


@pytest.fixture(scope="module")
def generated(tmp_path_factory: pytest.TempPathFactory) -> tuple[ModuleType, Path]:
    """The fixture's package, derived by ``derive.generate`` into a temporary folder."""
    from derive.generate import generate

    root = tmp_path_factory.mktemp("derived")
    description = root / "three_axle_cab.toml"
    description.write_text(DESCRIPTION, encoding="utf-8")
    names = generate(root / PACKAGE, str(description))
    assert "internal_forces.py" in names  # the cab mount is an internal spring-damper
    sys.path.insert(0, str(root))
    try:
        module = importlib.import_module(PACKAGE)
    finally:
        sys.path.remove(str(root))
    return module, description


def _params(gen: ModuleType, **changes: float) -> np.ndarray:
    values = VALUES | {f"{k}_{a}": v[i] for k, v in POINTS.items() for i, a in enumerate("xy")}
    raw = np.array([changes.get(name, values.get(name, 0.0)) for name in gen.PARAMETER_NAMES])
    completed, _ = gen.function("complete_parameters")(raw)
    return np.asarray(completed).ravel()


def test_structure_of_the_derived_machine(generated: tuple[ModuleType, Path]) -> None:
    import json
    import tomllib

    from derive.description import MACHINES_DIR

    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads((MACHINES_DIR.parent / "machine.schema.json").read_text(encoding="utf-8"))
    jsonschema.validate(tomllib.loads(DESCRIPTION), schema)
    gen, _ = generated
    assert gen.COORDINATE_NAMES == ("x_H", "y_H", "theta_1", "theta_2", "s_cab")
    assert gen.ANCHOR_NAMES == ("xi_A", "xi_B", "xi_R")
    assert len(gen.ROAD_NAMES) == 6
    assert {"F_Ry0", "k_cab", "c_cab", "F_cab0"} <= set(gen.PARAMETER_NAMES)


def test_static_loads_of_three_axles_hold_the_machine_on_a_level_road(
    generated: tuple[ModuleType, Path],
) -> None:
    gen, _ = generated
    params = _params(gen)
    named = dict(zip(gen.PARAMETER_NAMES, params, strict=True))
    loads = np.array([named[f"F_{a}y0"] for a in AXLES])
    weight = VALUES["g"] * sum(VALUES[m] for m in ("m_1", "m_2", "m_cab"))
    assert loads.sum() == pytest.approx(weight, rel=1e-12)
    assert np.all(loads > 0.0)
    # compatibility: the static deflections F/k lie on a line over the axles' x (rigid chassis)
    x = np.array([POINTS[a][0] for a in AXLES])
    deflection = loads / np.array([VALUES[f"k_{a}y"] for a in AXLES])
    line = np.polyval(np.polyfit(x, deflection, 1), x)
    assert np.max(np.abs(deflection - line)) < 1e-12 * np.max(np.abs(deflection))
    # the cab mount carries the cab
    assert named["F_cab0"] == pytest.approx(VALUES["g"] * VALUES["m_cab"], rel=1e-12)
    # p = 0 at rest with the static lift force is an equilibrium: p̈ = 0
    f_act0 = float(gen.function("complete_parameters")(params)[1])
    zeros = np.zeros(N)
    pdd, _ = gen.function("forward_dynamics")(
        zeros, zeros, np.zeros(3), f_act0, np.zeros(6), np.zeros(6), np.zeros(3), params
    )
    assert np.max(np.abs(np.asarray(pdd))) < 1e-9 * VALUES["g"]


def _independent_mass_matrix(q: np.ndarray) -> np.ndarray:
    """M(q) of chassis, boom (pin at D) and cab (slider along the chassis y axis at M) from
    ``sympy.physics.mechanics``: the Hessian of the kinetic energy in the rates."""
    import sympy as sp
    from sympy.physics import mechanics as me

    coordinates = me.dynamicsymbols("x y theta1 theta2 s")
    rates = [c.diff(me.dynamicsymbols._t) for c in coordinates]
    x, y, theta1, theta2, s = coordinates
    world = me.ReferenceFrame("N")
    chassis = world.orientnew("chassis", "Axis", [theta1, world.z])
    boom = world.orientnew("boom", "Axis", [theta2, world.z])
    origin = me.Point("O")
    origin.set_vel(world, 0)

    def at(base: me.Point, frame: me.ReferenceFrame, name: str, vector: tuple) -> me.Point:
        point = base.locatenew(name, vector[0] * frame.x + vector[1] * frame.y)
        return point

    def offset(a: str, b: str) -> tuple[float, float]:
        return (POINTS[a][0] - POINTS[b][0], POINTS[a][1] - POINTS[b][1])

    h = origin.locatenew("H", x * world.x + y * world.y)
    d = at(h, chassis, "D", POINTS["D"])
    g = at(d, boom, "G", offset("G", "D"))
    z = h.locatenew("Z", POINTS["Z"][0] * chassis.x + (POINTS["Z"][1] + s) * chassis.y)
    for point in (h, d, g, z):
        point.set_vel(world, point.pos_from(origin).dt(world))

    def body(name: str, centre: me.Point, frame: me.ReferenceFrame, mass: str, inertia: str):
        dyadic = VALUES[inertia] * me.outer(frame.z, frame.z)
        return me.RigidBody(name, centre, frame, VALUES[mass], (dyadic, centre))

    bodies = [
        body("chassis", h, chassis, "m_1", "J_1"),
        body("boom", g, boom, "m_2", "J_2"),
        body("cab", z, chassis, "m_cab", "J_cab"),  # the slider keeps the chassis' frame
    ]
    energy = sum(body.kinetic_energy(world) for body in bodies)
    hessian = sp.hessian(energy, rates)
    values = dict(zip(coordinates, q, strict=True))
    return np.array(hessian.subs(values).evalf(), dtype=float)


def test_mass_matrix_matches_sympy_physics_mechanics(generated: tuple[ModuleType, Path]) -> None:
    gen, _ = generated
    q = np.array([0.1, -0.05, 0.2, -0.4, 0.03])
    actual = np.asarray(gen.function("mass_matrix")(q, _params(gen)))
    expected = _independent_mass_matrix(q)
    assert np.abs(expected[4, 4] - VALUES["m_cab"]) < 1e-9 * VALUES["m_cab"]  # a real slider
    np.testing.assert_allclose(actual, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


def test_undamped_motion_conserves_energy(generated: tuple[ModuleType, Path]) -> None:
    gen, _ = generated
    undamped = {f"c_{a}{x}": 0.0 for a in AXLES for x in "xy"} | {"c_cab": 0.0}
    params = _params(gen, **undamped)
    f_act0 = float(gen.function("complete_parameters")(params)[1])
    cylinder = gen.function("cylinder_kinematics")
    x0 = float(cylinder(np.zeros(N), np.zeros(N), params)[0])
    state = ca.SX.sym("state", 2 * N + 3)
    p, pd, anchor = state[:N], state[N : 2 * N], state[2 * N :]
    force = f_act0 - K_EQ_N_PER_M * (cylinder(p, ca.DM.zeros(N), params)[0] - x0)
    pdd, anchor_rate = gen.function("forward_dynamics")(
        p, pd, anchor, force, ca.DM.zeros(6), ca.DM.zeros(6), ca.DM.zeros(3), params
    )
    rate = ca.Function("rate", [state], [ca.vertcat(pd, pdd, anchor_rate)])
    start = 0.2 * np.array([0.002, -0.004, 0.004, -0.006, 0.01, 0.03, 0.02, -0.05, 0.08, -0.1])
    solution = solve_ivp(
        lambda _, y: np.asarray(rate(y)).ravel(),
        (0.0, 2.0),
        np.concatenate([start, np.zeros(3)]),
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
        t_eval=np.linspace(0.0, 2.0, 201),
    )
    assert solution.success, solution.message
    trajectory = solution.y.T
    assert np.all(trajectory[:, 2 * N :] == 0.0)  # the tyres stuck: no anchor moved
    assert np.ptp(trajectory[:, N - 1]) > 1e-4  # the cab moves on its mount
    energy_fn = gen.function("mechanical_energy")

    def energy(row: np.ndarray) -> float:
        q, qd, xi = row[:N], row[N : 2 * N], row[2 * N :]
        out = energy_fn(q, qd, xi, np.zeros(6), np.zeros(6), params)
        kinetic, gravity, tyres, internal = (float(out[i]) for i in (0, 1, 2, 5))
        extension = float(cylinder(q, qd, params)[0]) - x0
        lift = K_EQ_N_PER_M * extension**2 / 2 - f_act0 * extension
        return kinetic + gravity + tyres + internal + lift

    values = np.array([energy(row) for row in trajectory])
    kinetic0 = float(
        energy_fn(start[:N], start[N:], np.zeros(3), np.zeros(6), np.zeros(6), params)[0]
    )
    assert kinetic0 > 1.0  # the start moves: a real test, not 0 == 0
    drift = np.ptp(values) / max(np.abs(values).max(), kinetic0)
    print(f"three-axle cab: energy {values[0]:.4f} J, relative drift {drift:.2e}")
    assert drift < 1e-9


def test_linearisation_matches_finite_differences(generated: tuple[ModuleType, Path]) -> None:
    """A and B of the generated linearisation (linear tyre law) against central differences of
    the forward dynamics (contact law, every tyre loaded) at a state off the equilibrium."""
    from tests.numerics import central_difference

    gen, _ = generated
    params = _params(gen)
    f_act0 = float(gen.function("complete_parameters")(params)[1])
    dynamics = gen.function("forward_dynamics")
    zeros6, zeros3 = np.zeros(6), np.zeros(3)

    def rate(x: np.ndarray, force: float = f_act0) -> np.ndarray:
        pdd, _ = dynamics(x[:N], x[N:], np.zeros(3), force, zeros6, zeros6, zeros3, params)
        return np.concatenate([x[N:], np.asarray(pdd).ravel()])

    x0 = 0.1 * np.array([0.002, -0.004, 0.004, -0.006, 0.01, 0.03, 0.02, -0.05, 0.08, -0.1])
    out = gen.function("linearisation")(x0[:N], x0[N:], f_act0, zeros6, zeros6, zeros3, params)
    a_mat, b_mat = np.asarray(out[0]), np.asarray(out[1])
    index = [gen.STATE_NAMES.index(n) for n in (*gen.COORDINATE_NAMES, *gen.RATE_NAMES)]
    reference = central_difference(rate, x0, np.full(2 * N, 1e-6))
    scale = max(np.abs(reference).max(), 1.0)
    np.testing.assert_allclose(a_mat[np.ix_(index, index)], reference, rtol=1e-6, atol=1e-6 * scale)
    step = 1.0  # N of a 13 kN force
    b_reference = (rate(x0, f_act0 + step) - rate(x0, f_act0 - step)) / (2 * step)
    np.testing.assert_allclose(b_mat[index, 0], b_reference, rtol=1e-6, atol=1e-9)


def test_runtime_refuses_a_description_without_its_generated_folder(
    generated: tuple[ModuleType, Path], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The runtime binds a description outside the package only through its generated package in
    the runtime's own cache (written by ``python -m derive <file>``); this fixture was derived
    into another folder only (an empty cache here), so it is refused with that command."""
    from loader_model.machines import machine

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "empty_cache"))
    _, description = generated
    with pytest.raises(
        ValueError,
        match=r"no generated package for this version of the file \(none in .*loader-model/"
        r"machines/[0-9a-f]{40}/\); derive it with `[^`]*-m derive .*three_axle_cab.toml`",
    ):
        machine(description)
