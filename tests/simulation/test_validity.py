"""The model's range of validity: the default bounds' geometry, their checks, and the stop.

The bounds are checked against what they mean (the centre of gravity above the tyre contact at
the pitch bound, the piston at its end stop at the boom bound less the margin), and the simulator's
stop against the rows computed from an unbounded run's columns (:mod:`tests.validity_rows`).
"""

from __future__ import annotations

import dataclasses
import math
import pickle

import numpy as np
import pytest

import loader_model_generated as generated
from loader_model.plant.plant import STATE_NAMES
from loader_model.plant.plant_parameters import PLANT_PARAMETER_NAMES, plant_parameter_vector
from loader_model.simulation.courses import paper_course
from loader_model.simulation.simulator import (
    ModelValidityError,
    SimulationError,
    course_input,
    simulate,
)
from loader_model.simulation.travel import DEFAULT_TYRE_RADIUS_M
from loader_model.simulation.validity import (
    END_STOP_MARGIN_RAD,
    ValidityBounds,
    validity_bounds,
)
from tests.validity_rows import beyond_bounds

#: Wide enough that no run of the paper's course reaches them.
UNBOUNDED = ValidityBounds(math.pi, math.pi, math.pi, math.pi, 3600.0, 1e5)


def _value(params: np.ndarray, name: str) -> float:
    return float(params[PLANT_PARAMETER_NAMES.index(name)])


def _completed(params: np.ndarray) -> object:
    return generated.function("complete_parameters")(params[: len(generated.PARAMETER_NAMES)])[0]


@pytest.mark.parametrize("load", ["empty", "full"])
def test_the_pitch_bounds_put_the_centre_of_gravity_over_the_tyre_contact(load: str) -> None:
    """Rotate the rigid machine about the front (rear) contact point by the nose-down (nose-up)
    bound: the combined centre of gravity (generated point positions) is right above it."""
    params = plant_parameter_vector(None, load)
    bounds = validity_bounds(params)
    completed = _completed(params)
    m1, m2 = _value(params, "m_1"), _value(params, "m_2")
    for axle, angle in (("A", -bounds.pitch_down_rad), ("B", bounds.pitch_up_rad)):
        contact = np.array([_value(params, f"{axle}_x"), _value(params, f"{axle}_y")])
        contact[1] -= DEFAULT_TYRE_RADIUS_M
        turn = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
        h = contact + turn @ (-contact)  # H (the origin at p = 0) turned about the contact
        positions = generated.function("point_positions")([h[0], h[1], angle, angle], completed)
        r_g, r_h = np.asarray(positions[5]).ravel(), np.asarray(positions[6]).ravel()
        centre = (m1 * r_h + m2 * r_g) / (m1 + m2)
        assert centre[0] == pytest.approx(contact[0], abs=1e-9), axle
        assert centre[1] > contact[1]
    assert 0.4 < min(bounds.pitch_down_rad, bounds.pitch_up_rad)  # over 23°: not a ride's pitch


def test_the_boom_bounds_are_the_stroke_plus_the_margin_short_of_the_dead_point() -> None:
    """x_piston = 0 at the lower bound less the margin, = stroke at the upper bound less the
    margin (the default's extended end is 0.10 rad from the dead point), and the cylinder keeps
    its lever arm (dx_cyl/dφ > 0) over the whole allowed range."""
    params = plant_parameter_vector(None, "full")
    bounds = validity_bounds(params)
    completed = _completed(params)
    kinematics = generated.function("cylinder_kinematics")

    def piston(phi: float) -> tuple[float, float]:
        length, _, slope, _ = kinematics([0.0, 0.0, 0.0, phi], [0.0] * 4, completed)
        return float(length) - _value(params, "L_retracted"), float(slope)

    retracted = piston(-(bounds.boom_down_rad - END_STOP_MARGIN_RAD))[0]
    extended = piston(bounds.boom_up_rad - END_STOP_MARGIN_RAD)[0]
    assert retracted == pytest.approx(0.0, abs=1e-6)
    assert extended == pytest.approx(_value(params, "stroke"), abs=1e-6)
    slopes = [piston(phi)[1] for phi in np.linspace(-bounds.boom_down_rad, bounds.boom_up_rad, 200)]
    assert min(slopes) > 0.0


@pytest.mark.parametrize("field", [f.name for f in dataclasses.fields(ValidityBounds)])
@pytest.mark.parametrize("value", [0.0, -0.1, math.nan, math.inf, 1e6, True, "1", None])
def test_bad_bounds_are_refused_naming_the_field(field: str, value: object) -> None:
    good = dataclasses.asdict(UNBOUNDED)
    with pytest.raises(ValueError, match=rf"validity bound {field} must be a .*number in \(0, "):
        ValidityBounds(**(good | {field: value}))


def test_bad_validity_arguments_are_refused() -> None:
    params = plant_parameter_vector(None, "empty")
    road = course_input(paper_course(9.0), params)
    with pytest.raises(TypeError, match="validity must be a ValidityBounds or None; got dict"):
        simulate(road, params, duration_s=0.1, validity={"airborne_s": 1.0})
    with pytest.raises(ValueError, match=r"tyre_radius_m must be a finite number in \(0, 2\] m"):
        validity_bounds(params, tyre_radius_m=0.0)
    with pytest.raises(ValueError, match="params must have"):
        validity_bounds(params[:-1])
    ahead = params.copy()
    ahead[PLANT_PARAMETER_NAMES.index("G_x")] = 10.0  # centre of gravity ahead of the front axle
    with pytest.raises(ValueError, match="must lie between and above the tyres' contact points"):
        validity_bounds(ahead)


# slow: 6 s (a whole course run twice)
@pytest.mark.slow
def test_a_valid_run_is_not_changed_by_the_check() -> None:
    """The default bounds and bounds no run reaches give the same numbers, bit for bit."""
    params = plant_parameter_vector(None, "empty")
    road = course_input(paper_course(18.0), params)
    checked = simulate(road, params, duration_s=4.0)
    unchecked = simulate(road, params, duration_s=4.0, validity=UNBOUNDED)
    assert checked.names == unchecked.names and checked.events == unchecked.events
    for name in checked.names:
        np.testing.assert_array_equal(checked[name], unchecked[name], err_msg=name)
    assert checked.metadata["validity"] == dataclasses.asdict(validity_bounds(params))


@pytest.mark.parametrize(
    ("change", "bound"),
    [
        ({"pitch_down_rad": 0.02}, "pitch_down_rad"),
        ({"pitch_up_rad": 0.02}, "pitch_up_rad"),
        ({"boom_up_rad": 0.01}, "boom_up_rad"),
        ({"boom_down_rad": 0.005}, "boom_down_rad"),
        ({"airborne_s": 0.02}, "airborne_s"),
        ({"seat_acceleration_m_s2": 5.0}, "seat_acceleration_m_s2"),
    ],
)
@pytest.mark.parametrize("chunk_periods", [500, 7])  # 7: flights span chunks
def test_the_run_stops_at_the_first_row_beyond_a_bound(
    change: dict, bound: str, chunk_periods: int
) -> None:
    """Tight bounds on the paper's course at 18 km/h (empty): the run stops at the first row
    that the unbounded run's columns put beyond them, whatever the chunk size; the error carries
    the rows up to it, their events and a ``validity`` event."""
    params = plant_parameter_vector(None, "empty")
    road = course_input(paper_course(18.0), params)
    bounds = dataclasses.replace(UNBOUNDED, **change)
    free = simulate(road, params, duration_s=5.0, validity=UNBOUNDED)
    first = int(np.argmax(beyond_bounds(free.columns, bounds)))
    assert first > 0
    with pytest.raises(ModelValidityError) as caught:
        simulate(road, params, duration_s=5.0, validity=bounds, chunk_periods=chunk_periods)
    error = caught.value
    assert isinstance(error, SimulationError) and isinstance(error, ValueError)
    assert error.violation.bound == bound and error.violation.index == first
    result = error.result
    assert result.time_s.size == first + 1
    assert result.time_s[-1] == pytest.approx(error.violation.time_s, abs=1e-12)
    for name in free.names:
        np.testing.assert_array_equal(result[name], free[name][: first + 1], err_msg=name)
    np.testing.assert_array_equal(result.final_state, [result[n][-1] for n in STATE_NAMES])
    stops = [event for event in result.events if event.kind == "validity"]
    assert len(stops) == 1 and stops[0].end_s == result.time_s[-1]
    assert f"at t = {result.time_s[-1]:.3f} s" in str(error) and "; state: x_H=" in str(error)
    again = pickle.loads(pickle.dumps(error))  # process pools return it to the parent
    assert str(again) == str(error) and again.result.time_s.size == first + 1
