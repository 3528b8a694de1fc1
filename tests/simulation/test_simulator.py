"""The closed-loop simulator against a CVODES reference at rtol 1e-10, and its safety rails.

Accuracy (paper's course at 9 km/h, section 5.3): the ISO 2631-1 weighted r.m.s. of the seat per
axis (x = f_Sx, z = f_Sy, pitch = θ̈1; Eq. 49) and a_total (Eq. 50, k = 0.4 for pitch) within 1 %,
and the seat trace in the normalised r.m.s. norm ‖s − s_ref‖_rms / ‖s_ref − s_ref(0)‖_rms within
6 % per signal. Measured on the development machine (ROS2, one step per 1 ms period):

============  =====  =======  =======  =======  =======  =====================
run           axis x  axis z  pitch    a_total  trace (x, z, pitch)
============  =====  =======  =======  =======  =======  =====================
empty         -0.33 %  -0.03 %  -0.31 %  -0.11 %  2.4, 3.2, 4.3 %
full          -0.06 %  -0.20 %  -0.14 %  -0.16 %  0.7, 1.5, 1.9 %
empty passive  0.00 %  -0.37 %  -0.31 %  -0.32 %  1.9, 1.6, 2.2 %
full passive  -0.07 %  -0.29 %  -0.14 %  -0.22 %  1.3, 1.7, 1.7 %
empty VA      +0.01 %  -0.33 %  -0.42 %  -0.27 %  2.1, 2.6, 3.2 %
empty skyhook -0.16 %  -0.40 %  -0.32 %  -0.36 %  1.6, 2.0, 2.8 %
full VA       -0.21 %  +0.03 %  -0.16 %  -0.06 %  0.6, 1.0, 1.0 %
full skyhook  -0.19 %  -0.01 %  -0.17 %  -0.06 %  0.8, 1.2, 1.2 %
============  =====  =======  =======  =======  =======  =====================

(VA: virtual accumulator; skyhook with Table 3 gains, both with the 1 kHz controller.)

The reference runs about 8-13 s per course (CVODES restarted each period), so the default tests
run the empty bucket's baseline over the whole course and the other three cases over the first
6 s; the whole course for those is marked slow.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from loader_model.experiments.trials import controller_arguments
from loader_model.iso2631 import VibrationRecord, evaluate_record
from loader_model.plant.equilibrium import static_state
from loader_model.plant.plant import EXOGENOUS_NAMES, OUTPUT_NAMES, STATE_NAMES, plant_function
from loader_model.plant.plant_parameters import (
    PLANT_PARAMETER_NAMES,
    PlantOptions,
    plant_parameter_vector,
)
from loader_model.simulation.controllers import check_controller, hold_controller
from loader_model.simulation.courses import paper_course, single_obstacle_course
from loader_model.simulation.reference import reference_simulation
from loader_model.simulation.simulator import SimulationError, course_input, simulate

SEAT = ("f_Px", "f_Py", "thetadd_1")  # the seat pad under the occupant, the chassis pitch
K_FACTORS = {"x": 1.0, "z": 1.0, "pitch": 0.4}


def _parameters(load: str, passive: bool = False, controller: str | None = None) -> np.ndarray:
    """The plant on the circuit of ``controller`` (default: the baseline, or passive)."""
    circuit = controller or ("passive" if passive else "baseline")
    return plant_parameter_vector(None, load, PlantOptions.for_controller(circuit))


def _seat_evaluation(time_s: np.ndarray, seat: np.ndarray):
    seat = seat - seat[0]
    record = VibrationRecord(time_s, {"x": seat[:, 0], "z": seat[:, 1], "pitch": seat[:, 2]})
    return evaluate_record(record, k_factors=K_FACTORS)


def _compare(
    load: str,
    passive: bool,
    duration_s: float | None,
    controller: str | None = None,
    substeps: int = 1,
) -> None:
    params = _parameters(load, passive, controller)
    road = course_input(paper_course(9.0), params)
    control = {} if controller is None else controller_arguments(controller, load, params)
    fast = simulate(road, params, duration_s=duration_s, substeps=substeps, **control)
    reference = reference_simulation(road, params, duration_s=duration_s, rtol=1e-10, **control)
    np.testing.assert_allclose(fast.time_s, reference["time"], rtol=0, atol=1e-12)
    reference_seat = reference["y"][:, [OUTPUT_NAMES.index(name) for name in SEAT]]
    fast_seat = np.column_stack([fast[name] for name in SEAT])
    got = _seat_evaluation(fast.time_s, fast_seat)
    want = _seat_evaluation(reference["time"], reference_seat)
    for mine, theirs in zip(got.axes, want.axes, strict=True):
        assert mine.weighted_rms == pytest.approx(theirs.weighted_rms, rel=0.01), mine.axis
    assert got.total_m_s2 == pytest.approx(want.total_m_s2, rel=0.01)
    error = np.sqrt(np.mean((fast_seat - reference_seat) ** 2, axis=0))
    scale = np.sqrt(np.mean((reference_seat - reference_seat[0]) ** 2, axis=0))
    assert np.all(error <= 0.06 * scale), error / scale


#: ROS2 substeps per 1 ms period for the baseline (the simulator's default is 4,
#: :data:`~loader_model.simulation.simulator.DEFAULT_SUBSTEPS`). On closed load-holding valves the
#: sealed piston side swings between the make-up check (20 bar) and the relief (230 bar) over the
#: boards, and the linearly implicit steps across those switches part from the CVODES reference
#: (measured, empty bucket, whole course, tandem-cam tyres, seat pad: a_total −2.2 % with one
#: substep, −1.6 % with two, +0.24 % with four (r.m.s. error of the pitch signal 6.2 % of its
#: excursion), 0.00 % with eight (0.5 %); rigid discs −4.6 %, −5.3 %, 0.00 %, 0.00 %). This test
#: holds the signals to 6 % r.m.s., so it runs eight.
BASELINE_SUBSTEPS = 8


@pytest.mark.slow  # 22 s with 8 substeps and the rtol 1e-10 reference; the first boards stay fast
def test_baseline_matches_the_cvodes_reference_on_the_paper_course() -> None:
    """Baseline (hold) controller, empty bucket, whole course at 9 km/h: a_w within 1 %."""
    _compare("empty", passive=False, duration_s=None, substeps=BASELINE_SUBSTEPS)


@pytest.mark.parametrize(
    "load",
    ["empty", pytest.param("full", marks=pytest.mark.slow)],  # 5 s; the course is slow too
)
def test_passive_matches_the_cvodes_reference_over_the_first_boards(load: str) -> None:
    """Accumulator connected (passive ride control), first 6 s (three boards)."""
    _compare(load, passive=True, duration_s=6.0)


@pytest.mark.slow  # 6 s; the empty bucket's first boards stay fast
def test_full_bucket_matches_the_cvodes_reference_over_the_first_boards() -> None:
    """Baseline controller, full bucket, first 6 s (three boards); whole course: slow test."""
    _compare("full", passive=False, duration_s=6.0, substeps=BASELINE_SUBSTEPS)


@pytest.mark.slow
def test_full_bucket_matches_the_cvodes_reference_on_the_paper_course() -> None:
    """Baseline controller, full bucket, whole course at 9 km/h."""
    _compare("full", passive=False, duration_s=None, substeps=BASELINE_SUBSTEPS)


@pytest.mark.parametrize(
    "controller",
    [pytest.param("virtual-accumulator", marks=pytest.mark.slow), "skyhook"],  # 5 s
)
def test_active_controllers_match_the_cvodes_reference_over_the_first_boards(
    controller: str,
) -> None:
    """The 1 kHz virtual accumulator and skyhook (Table 3), empty bucket, first 6 s."""
    _compare("empty", passive=False, duration_s=6.0, controller=controller)


@pytest.mark.slow
@pytest.mark.parametrize("load", ["empty", "full"])
@pytest.mark.parametrize("controller", ["virtual-accumulator", "skyhook"])
def test_active_controllers_match_the_cvodes_reference_on_the_paper_course(
    load: str, controller: str
) -> None:
    """The active controllers, whole course at 9 km/h, both loads."""
    _compare(load, passive=False, duration_s=None, controller=controller)


@pytest.mark.slow
@pytest.mark.parametrize("load", ["empty", "full"])
def test_passive_matches_the_cvodes_reference_on_the_paper_course(load: str) -> None:
    """Accumulator connected, whole course at 9 km/h, both loads."""
    _compare(load, passive=True, duration_s=None)


def test_rest_stays_at_rest_and_the_result_is_labelled(tmp_path) -> None:
    """Flat road for 1 s from the static state: nothing moves; every column named with a unit.
    On open load-holding valves, where the pump's command holds an exact equilibrium (behind
    closed valves the seals let the boom drift: tests/plant/test_circuit.py)."""
    params = _parameters("full", controller="skyhook")
    road = course_input(paper_course(9.0), params)  # the lead-in is flat for the first 2 s
    result = simulate(road, params, duration_s=1.0)
    x0, u0 = static_state(params)
    assert result.time_s.size == 1000
    np.testing.assert_allclose(result.final_state[:10], 0.0, atol=1e-9)
    np.testing.assert_allclose(result.final_state[10:15], x0[10:15], rtol=1e-6)
    np.testing.assert_allclose(result.final_state[15:], 0.0, atol=1e-12)  # the occupant
    np.testing.assert_allclose(result["V_p_ref"], u0, rtol=0)
    assert set(STATE_NAMES) <= set(result.names) and set(EXOGENOUS_NAMES) <= set(result.names)
    assert set(OUTPUT_NAMES) <= set(result.names)
    assert all(result.unit(name) != "-" for name in result.names)
    assert result.events == ()
    csv = result.write(tmp_path / "run.csv")
    header = csv.read_text().splitlines()[0].split(",")
    assert header[0] == "time [s]" and "p_A [Pa]" in header and "f_Sy [m/s^2]" in header
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert table.shape == (1000, len(result.names) + 1)
    npz = np.load(result.write(tmp_path / "run.npz"))
    np.testing.assert_array_equal(npz["p_A"], result["p_A"])


def test_events_are_recorded_on_the_paper_course() -> None:
    """The 4 cm boards lift tyres off the ground (measured: about 40 intervals, empty bucket)."""
    params = _parameters("empty")
    result = simulate(course_input(paper_course(9.0), params), params, duration_s=4.0)
    kinds = {event.kind for event in result.events}
    assert "tyre_off_ground" in kinds
    for event in result.events:
        assert event.end_s >= event.start_s
        assert result[event.signal][result.time_s.searchsorted(event.start_s)] <= 0.0


def test_pump_saturation_is_an_event() -> None:
    """A controller that commands twice the pump's maximum displacement is flagged."""
    params = _parameters("empty")
    v_max = params[PLANT_PARAMETER_NAMES.index("V_p_max")]
    road = course_input(single_obstacle_course(), params)
    result = simulate(road, params, hold_controller(2.0 * v_max), duration_s=0.2)
    assert any(event.kind == "pump_saturation" for event in result.events)


def test_a_diverging_controller_raises_with_time_and_state() -> None:
    """A controller whose state blows up makes the run non-finite: SimulationError, no NaN."""
    z = ca.SX.sym("z")
    y = ca.SX.sym("y", len(OUTPUT_NAMES))
    settings = ca.SX.sym("settings", 0)
    exploding = ca.Function(
        "exploding", [z, y, settings], [z * 1e30, z * 1e30], ["z", "y", "settings"], ["z_next", "u"]
    )
    params = _parameters("empty")
    road = course_input(single_obstacle_course(), params)
    with pytest.raises(SimulationError, match=r"t = 0\.\d+ s; last finite state: x_H="):
        simulate(road, params, exploding, controller_state=[1.0], duration_s=1.0)


def test_output_does_not_depend_on_the_command() -> None:
    """The period evaluates y_k with the previous command: valid because y does not depend on u."""
    plant = plant_function()
    x, u = ca.SX.sym("x", len(STATE_NAMES)), ca.SX.sym("u")
    w, p = ca.SX.sym("w", len(EXOGENOUS_NAMES)), ca.SX.sym("p", plant.size1_in(3))
    assert not ca.depends_on(plant(x, u, w, p)[1], u)


def test_the_sx_fallback_gives_the_jit_result() -> None:
    """Without JIT (SX virtual machine) the run is the same to rounding."""
    params = _parameters("empty")
    road = course_input(single_obstacle_course(), params)
    compiled = simulate(road, params, duration_s=0.5)
    interpreted = simulate(road, params, duration_s=0.5, jit=False)
    assert interpreted.metadata["backend"] == "sx"
    np.testing.assert_allclose(interpreted["f_Sy"], compiled["f_Sy"], rtol=1e-9, atol=1e-9)


def test_controller_interface_is_checked() -> None:
    """Wrong shapes are refused with the reason."""
    with pytest.raises(ValueError, match=r"casadi\.Function"):
        check_controller(lambda z, y, s: (z, 0.0))
    bad = ca.Function("bad", [ca.SX.sym("z", 0), ca.SX.sym("y", 3), ca.SX.sym("s", 0)], [0, 0])
    with pytest.raises(ValueError, match="y of size 3"):
        check_controller(bad)
