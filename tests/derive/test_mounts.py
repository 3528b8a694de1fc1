"""Two-point mounts, end stops and a telescope held by its cylinder, derived through ``derive/``
into a temporary folder (:mod:`tests.derive.mounted_cab`) and checked against closed forms.

- the cab on two mounts: bounce and pitch natural frequencies of a rigid body on two springs
  (the 2×2 eigenproblem written here, chassis and seat held);
- end stops: the static deflection past the seat's lower stop under a known load;
- the telescope: its extension moves its points and holds under an added load within the
  stiffness of its locked cylinder;
- the static loads hold the machine at rest; undamped motion with the stops hit conserves energy.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable
from types import ModuleType

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from tests.derive.mounted_cab import DESCRIPTION, POINTS, VALUES

#: Deriving the fixture takes about 35 s with SymPy; the six checks then take 20 s.
pytestmark = pytest.mark.slow

PACKAGE = "mounted_cab_fixture"
COORDINATES = ("x_H", "y_H", "theta_1", "theta_2", "s_tele", "s_cab", "theta_cab", "s_seat")
N = len(COORDINATES)
K_EQ_N_PER_M = 2.0e7  # the lift cylinder held as a hydraulic spring (order of Eq. 28)
BAND_M = 5e-4  # δ_0 of the end stops (derive.elements.STOP_BAND_M)
ZEROS4 = np.zeros(4)


@pytest.fixture(scope="module")
def gen(tmp_path_factory: pytest.TempPathFactory) -> ModuleType:
    """The fixture's package, derived by ``derive.generate`` into a temporary folder."""
    from derive.generate import generate

    root = tmp_path_factory.mktemp("derived")
    description = root / "mounted_cab.toml"
    description.write_text(DESCRIPTION, encoding="utf-8")
    generate(root / PACKAGE, str(description))
    sys.path.insert(0, str(root))
    try:
        return importlib.import_module(PACKAGE)
    finally:
        sys.path.remove(str(root))


def _params(gen: ModuleType, complete: bool = True, **changes: float) -> np.ndarray:
    values = VALUES | {f"{k}_{a}": v[i] for k, v in POINTS.items() for i, a in enumerate("xy")}
    raw = np.array([changes.get(name, values.get(name, 0.0)) for name in gen.PARAMETER_NAMES])
    if not complete:
        return raw
    completed, _ = gen.function("complete_parameters")(raw)
    return np.asarray(completed).ravel()


def _index(name: str) -> int:
    return COORDINATES.index(name)


def test_structure_and_static_loads(gen: ModuleType) -> None:
    import json
    import tomllib

    from derive.description import MACHINES_DIR

    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads((MACHINES_DIR.parent / "machine.schema.json").read_text(encoding="utf-8"))
    jsonschema.validate(tomllib.loads(DESCRIPTION), schema)
    assert gen.COORDINATE_NAMES == COORDINATES
    params = _params(gen)
    named = dict(zip(gen.PARAMETER_NAMES, params, strict=True))
    g = VALUES["g"]
    # the seat spring carries the seat; the two cab mounts carry cab and seat
    assert named["F_seat0"] == pytest.approx(g * VALUES["m_seat"], rel=1e-12)
    mounts = named["F_cab_F0"] + named["F_cab_R0"]
    assert mounts == pytest.approx(g * (VALUES["m_cab"] + VALUES["m_seat"]), rel=1e-12)
    # and their moment about M balances the weights' (lever arms along x)
    m_x = POINTS["M"][0]
    arms = {q: POINTS[q][0] - m_x for q in ("F", "R", "Z", "Y")}
    moment = named["F_cab_F0"] * arms["F"] + named["F_cab_R0"] * arms["R"]
    weights = g * (VALUES["m_cab"] * arms["Z"] + VALUES["m_seat"] * arms["Y"])
    assert moment == pytest.approx(weights, rel=1e-12)
    f_act0 = float(gen.function("complete_parameters")(params)[1])
    zeros = np.zeros(N)
    pdd, _ = gen.function("forward_dynamics")(
        zeros, zeros, np.zeros(2), f_act0, ZEROS4, ZEROS4, np.zeros(3), params
    )
    assert np.max(np.abs(np.asarray(pdd))) < 1e-9 * g


def _composite_about_m() -> tuple[float, float, float]:
    """Mass, first moment along x and inertia about M of cab and seat held on it."""
    mass = first = inertia = 0.0
    for m, j, centre in (("m_cab", "J_cab", "Z"), ("m_seat", "J_seat", "Y")):
        dx = POINTS[centre][0] - POINTS["M"][0]
        dy = POINTS[centre][1] - POINTS["M"][1]
        mass += VALUES[m]
        first += VALUES[m] * dx
        inertia += VALUES[j] + VALUES[m] * (dx**2 + dy**2)
    return mass, first, inertia


def test_cab_on_two_mounts_bounce_and_pitch_frequencies(gen: ModuleType) -> None:
    """Rigid body on two vertical springs at levers x_F, x_R from M (bounce s at M, pitch θ):

    T = ½ m ṡ² + S ṡ θ̇ + ½ J_M θ̇²,  V = ½ k_F (s + x_F θ)² + ½ k_R (s + x_R θ)²

    without gravity (no preloads, so no geometric stiffness): det(K − ω² M) = 0.
    """
    params = _params(gen, g=0.0)
    cab = [_index("s_cab"), _index("theta_cab")]
    mass_matrix = np.asarray(gen.function("mass_matrix")(np.zeros(N), params))[np.ix_(cab, cab)]
    p = ca.SX.sym("p", N)
    k_e = gen.function("internal_forces")(p, ca.DM.zeros(N), params)[0]
    stiffness = np.asarray(ca.Function("k", [p], [ca.jacobian(k_e, p)])(np.zeros(N)))
    stiffness = stiffness[np.ix_(cab, cab)]

    mass, first, inertia = _composite_about_m()
    x_f, x_r = (POINTS[q][0] - POINTS["M"][0] for q in ("F", "R"))
    k_f, k_r = VALUES["k_cab_F"], VALUES["k_cab_R"]
    m_closed = np.array([[mass, first], [first, inertia]])
    k_closed = np.array(
        [[k_f + k_r, k_f * x_f + k_r * x_r], [k_f * x_f + k_r * x_r, k_f * x_f**2 + k_r * x_r**2]]
    )
    np.testing.assert_allclose(mass_matrix, m_closed, rtol=1e-12, atol=1e-12 * inertia)
    np.testing.assert_allclose(stiffness, k_closed, rtol=1e-12, atol=1e-12 * k_f)
    # the closed form's eigenproblem: ω² from the quadratic det(K − ω² M) = 0
    a = np.linalg.det(m_closed)
    b = -(k_closed[0, 0] * m_closed[1, 1] + k_closed[1, 1] * m_closed[0, 0])
    b += 2 * k_closed[0, 1] * m_closed[0, 1]
    c = np.linalg.det(k_closed)
    closed = np.sqrt((-b + np.array([-1.0, 1.0]) * np.sqrt(b**2 - 4 * a * c)) / (2 * a))
    derived = np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(mass_matrix, stiffness)).real))
    print(f"two mounts: {closed / (2 * np.pi)} Hz (closed form), {derived / (2 * np.pi)} Hz")
    assert np.all(closed / (2 * np.pi) > 1.0)  # real cab modes, not zero
    np.testing.assert_allclose(derived, closed, rtol=1e-10)


def _row_balance(gen: ModuleType, params: np.ndarray, name: str) -> Callable[[float], float]:
    """The static balance K_e − Q_g of coordinate ``name``, every other coordinate held at 0."""
    internal, gravity = gen.function("internal_forces"), gen.function("gravity_forces")
    index = _index(name)

    def balance(value: float) -> float:
        p = np.zeros(N)
        p[index] = value
        k_e = np.asarray(internal(p, np.zeros(N), params)[0]).ravel()
        q_g = np.asarray(gravity(p, params)).ravel()
        return float(k_e[index] - q_g[index])

    return balance


def test_end_stop_deflection_under_a_known_load(gen: ModuleType) -> None:
    """The seat loaded by an extra 100 kg (its preload kept): the spring runs to s_min, the stop
    takes the rest F_stop = ΔF − k (|s_min| + δ), and on its linear part (beyond δ_0) the
    deflection past the stop is δ = F_stop / k_stop + δ_0/2 (the C¹ ramp's offset)."""
    params = _params(gen)
    named = dict(zip(gen.PARAMETER_NAMES, params, strict=True))
    extra = 100.0
    loaded = params.copy()
    loaded[gen.PARAMETER_NAMES.index("m_seat")] += extra
    balance = _row_balance(gen, loaded, "s_seat")
    s_min, k, k_stop = (named[n] for n in ("s_min_seat", "k_seat", "k_stop_seat"))
    found = brentq(balance, s_min - 0.1, 0.0, xtol=1e-14, rtol=1e-14)
    load = extra * VALUES["g"]
    past = s_min - found
    stop_load = load - k * (abs(s_min) + past)
    expected = stop_load / k_stop + BAND_M / 2
    print(f"seat stop: {past * 1e3:.4f} mm past the stop, F/k_stop + δ_0/2 {expected * 1e3:.4f} mm")
    assert past > BAND_M  # on the linear part of the stop
    assert stop_load > 0.3 * load  # the stop carries a good part of the load
    assert past == pytest.approx(expected, rel=1e-9)
    # without the stop the spring alone would sink 75 mm, beyond the 45 mm travel
    assert load / k > abs(s_min) + 0.02


def test_end_stop_damping_never_pulls(gen: ModuleType) -> None:
    """Leaving the upper stop fast: the damping would pull, the clamp gives zero stop force."""
    params = _params(gen)
    named = dict(zip(gen.PARAMETER_NAMES, params, strict=True))
    p, pd = np.zeros(N), np.zeros(N)
    index = _index("s_seat")
    p[index] = named["s_max_seat"] + 10 * BAND_M
    internal = gen.function("internal_forces")
    spring = named["F_seat0"] - named["k_seat"] * p[index]  # the seat spring alone (+: up)

    def stop_force(rate: float) -> float:
        pd[index] = rate
        k_e, d_e = (np.asarray(v).ravel()[index] for v in internal(p, pd, params))
        return -(k_e + d_e) - spring - (-named["c_seat"] * rate)

    elastic = named["k_stop_seat"] * (10 * BAND_M - BAND_M / 2)
    assert stop_force(0.0) == pytest.approx(-elastic, rel=1e-12)  # pushes down, out of it
    into = 0.5  # m/s upwards, into the stop
    assert stop_force(into) == pytest.approx(-elastic - named["c_stop_seat"] * into, rel=1e-12)
    # leaving at 10 m/s: c ẋ > k δ, clamped to zero (round-off of the spring terms only)
    assert abs(stop_force(-10.0)) < 1e-12 * elastic


def test_telescope_extension_and_holding(gen: ModuleType) -> None:
    """The extension l moves the telescope's points by l along its direction; an added 500 kg
    at its centre of gravity shortens it by Δm g d_y / k_tele (the locked cylinder's spring)."""
    params = _params(gen)
    named = dict(zip(gen.PARAMETER_NAMES, params, strict=True))
    direction = np.array([1.0, 0.1]) / np.hypot(1.0, 0.1)
    positions = gen.function("point_positions")(np.zeros(N), params)
    names = sorted({*POINTS, "H"})
    t_point = np.asarray(positions[names.index("T")]).ravel()
    expected = np.array(POINTS["T"]) + VALUES["l_tele"] * direction
    np.testing.assert_allclose(t_point, expected, rtol=1e-12, atol=1e-12)
    extra = 500.0
    loaded = params.copy()
    loaded[gen.PARAMETER_NAMES.index("m_tele")] += extra
    found = brentq(_row_balance(gen, loaded, "s_tele"), -0.01, 0.01, xtol=1e-16, rtol=1e-14)
    closed = -extra * VALUES["g"] * direction[1] / named["k_tele"]
    print(f"telescope: {found * 1e6:.4f} um under {extra:g} kg, closed form {closed * 1e6:.4f} um")
    assert found == pytest.approx(closed, rel=1e-9)
    # another extension needs no new derivation: the static loads follow it
    longer = _params(gen, l_tele=1.6)
    f_act0 = float(gen.function("complete_parameters")(longer)[1])
    zeros = np.zeros(N)
    pdd, _ = gen.function("forward_dynamics")(
        zeros, zeros, np.zeros(2), f_act0, ZEROS4, ZEROS4, np.zeros(3), longer
    )
    assert np.max(np.abs(np.asarray(pdd))) < 1e-9 * VALUES["g"]


def test_undamped_motion_with_the_stops_hit_conserves_energy(gen: ModuleType) -> None:
    dampers = [n for n in gen.PARAMETER_NAMES if n.startswith(("c_", "c_stop_"))]
    params = _params(gen, **dict.fromkeys(dampers, 0.0))
    f_act0 = float(gen.function("complete_parameters")(params)[1])
    cylinder = gen.function("cylinder_kinematics")
    x0 = float(cylinder(np.zeros(N), np.zeros(N), params)[0])
    state = ca.SX.sym("state", 2 * N + 2)
    p, pd, anchor = state[:N], state[N : 2 * N], state[2 * N :]
    force = f_act0 - K_EQ_N_PER_M * (cylinder(p, ca.DM.zeros(N), params)[0] - x0)
    pdd, anchor_rate = gen.function("forward_dynamics")(
        p, pd, anchor, force, ca.DM.zeros(4), ca.DM.zeros(4), ca.DM.zeros(3), params
    )
    rate = ca.Function("rate", [state], [ca.vertcat(pd, pdd, anchor_rate)])
    start = np.zeros(2 * N + 2)
    start[N + _index("s_seat")] = 0.8  # m/s up: the seat reaches its 45 mm upper stop
    start[N + _index("s_cab")] = 0.5  # m/s up: the cab reaches its mounts' 20 mm stops
    start[N + _index("theta_cab")] = 0.3  # rad/s
    start[N + _index("theta_2")] = -0.05
    solution = solve_ivp(
        lambda _, y: np.asarray(rate(y)).ravel(),
        (0.0, 1.0),
        start,
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
        t_eval=np.linspace(0.0, 1.0, 401),
    )
    assert solution.success, solution.message
    trajectory = solution.y.T
    named = dict(zip(gen.PARAMETER_NAMES, params, strict=True))
    seat = trajectory[:, _index("s_seat")]
    assert seat.max() > named["s_max_seat"] + BAND_M  # the stop was really hit
    assert seat.min() < named["s_min_seat"] - BAND_M
    energy_fn = gen.function("mechanical_energy")

    def energy(row: np.ndarray) -> float:
        q, qd, xi = row[:N], row[N : 2 * N], row[2 * N :]
        out = energy_fn(q, qd, xi, ZEROS4, ZEROS4, params)
        kinetic, gravity, tyres, internal = (float(out[i]) for i in (0, 1, 2, 5))
        extension = float(cylinder(q, qd, params)[0]) - x0
        lift = K_EQ_N_PER_M * extension**2 / 2 - f_act0 * extension
        return kinetic + gravity + tyres + internal + lift

    values = np.array([energy(row) for row in trajectory])
    assert values[0] > 10.0  # joules: a real motion
    drift = np.ptp(values) / values[0]
    print(f"mounts and stops: energy {values[0]:.4f} J, relative drift {drift:.2e}")
    # measured 2.7e-11 (DOP853, rtol 1e-12); the stops are C¹ only, which costs the integrator
    # order at their edges: a wide margin
    assert drift < 1e-7


def test_linearisation_through_an_engaged_stop_matches_finite_differences(gen: ModuleType) -> None:
    """A and B of the generated linearisation against central differences of the forward
    dynamics at a state with the seat 3 mm into its upper stop and moving into it (the stop's
    spring and damper on their linear parts): CasADi's derivatives go through the stops."""
    from tests.numerics import central_difference

    params = _params(gen)
    named = dict(zip(gen.PARAMETER_NAMES, params, strict=True))
    f_act0 = float(gen.function("complete_parameters")(params)[1])
    dynamics = gen.function("forward_dynamics")
    zeros3 = np.zeros(3)

    def rate(x: np.ndarray, force: float = f_act0) -> np.ndarray:
        pdd, _ = dynamics(x[:N], x[N:], np.zeros(2), force, ZEROS4, ZEROS4, zeros3, params)
        return np.concatenate([x[N:], np.asarray(pdd).ravel()])

    x0 = 1e-3 * np.array([1, -2, 2, -3, 0.01, 4, 3, 0, 10, -20, 8, 15, 0.1, 20, 30, 100.0])
    x0[_index("s_seat")] = named["s_max_seat"] + 6 * BAND_M
    out = gen.function("linearisation")(x0[:N], x0[N:], f_act0, ZEROS4, ZEROS4, zeros3, params)
    a_mat = np.asarray(out[0])
    index = [gen.STATE_NAMES.index(n) for n in (*gen.COORDINATE_NAMES, *gen.RATE_NAMES)]
    reference = central_difference(rate, x0, np.full(2 * N, 1e-7))
    seat = N + _index("s_seat")
    # the seat's acceleration per metre of its travel: spring and stop, k + k_stop over its mass
    stiff = (named["k_seat"] + named["k_stop_seat"]) / VALUES["m_seat"]
    assert -reference[seat, _index("s_seat")] > 0.9 * stiff  # the stop is in the derivative
    scale = np.abs(reference).max()
    np.testing.assert_allclose(a_mat[np.ix_(index, index)], reference, rtol=1e-5, atol=1e-6 * scale)
