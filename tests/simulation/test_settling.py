"""The settle measure, the limit duty and their events against closed forms on synthetic runs."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from loader_model.simulation.events import find_events
from loader_model.simulation.settling import (
    PERSISTENCE_RATIO,
    REST_FLOOR_RAD_S2,
    excitation_end_s,
    limit_duty,
    settle_measure,
)

PERIOD_S = 1e-3


def _run(pitch: np.ndarray, road_end_s: float) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """A run's columns: a road that rises until ``road_end_s`` and stays, and the pitch."""
    time_s = np.arange(pitch.size) * PERIOD_S
    road = np.minimum(time_s, road_end_s) * 0.01
    return time_s, {"thetadd_1": pitch, "w_Ay": road, "w_By": road}


def _free_response(frequency_hz: float, damping: float, road_end_s: float, total_s: float):
    time_s = np.arange(round(total_s / PERIOD_S)) * PERIOD_S
    after = np.clip(time_s - road_end_s, 0.0, None)
    omega = 2 * np.pi * frequency_hz
    pitch = 3.0 * np.exp(-damping * omega * after) * np.sin(omega * after)
    return _run(pitch, road_end_s)


def test_excitation_ends_where_the_road_stops_changing() -> None:
    time_s, columns = _run(np.zeros(5000), 2.5)
    assert excitation_end_s(time_s, columns) == pytest.approx(2.5, abs=PERIOD_S)
    columns["F_dy"] = np.where(time_s < 3.2, 1.0, 0.0)
    assert excitation_end_s(time_s, columns) == pytest.approx(3.2, abs=PERIOD_S)
    flat = {"thetadd_1": np.zeros(10), "w_Ay": np.zeros(10)}
    assert excitation_end_s(np.arange(10) * PERIOD_S, flat) == 0.0


@settings(max_examples=25, deadline=None)
@given(
    frequency_hz=st.floats(2.0, 6.0),
    damping=st.floats(0.02, 0.3),
)
def test_a_decaying_mode_decays_by_its_closed_form(frequency_hz: float, damping: float) -> None:
    """r.m.s. of e^(−ζωt) sin(ωt) over the last second against the one before: the closed form
    of ∫ e^(−2at) sin²(ωt) dt = −e^(−2at)/(4a) − Re[e^((2iω−2a)t) / (2(2iω−2a))], a = ζω. The 1 kHz sample
    mean over a window is a rectangle rule, off the integral by about a h relative (up to 1.1 % at
    ζ = 0.3, 6 Hz); measured over f 2-6 Hz, ζ 0.02-0.3 on a grid of 132 pairs: at most 0.99 %."""
    time_s, columns = _free_response(frequency_hz, damping, 1.0, 4.0)
    measure = settle_measure(time_s, columns)
    omega = 2 * math.pi * frequency_hz
    a = damping * omega
    s = complex(-2 * a, 2 * omega)

    def integral(t: float) -> float:
        return -math.exp(-2 * a * t) / (4 * a) - (np.exp(s * t) / (2 * s)).real

    previous, tail = integral(2.0) - integral(1.0), integral(3.0) - integral(2.0)
    assert measure.judged
    assert measure.excitation_end_s == pytest.approx(1.0, abs=PERIOD_S)
    assert measure.decay_ratio == pytest.approx(math.sqrt(tail / previous), rel=2e-2)
    assert measure.decay_ratio < 1.5 * math.exp(-a)  # about the envelope's decay per second
    assert not measure.persistent  # fζ ≥ 0.04 Hz decays faster than the persistence ratio


def test_a_limit_cycle_persists_and_a_quiet_one_is_at_rest() -> None:
    time_s = np.arange(6000) * PERIOD_S
    cycle = 3.0 * np.sin(2 * np.pi * 5.0 * time_s)
    measure = settle_measure(*_run(cycle, 2.0))
    assert measure.decay_ratio == pytest.approx(1.0, abs=1e-2)
    assert measure.persistent
    quiet = settle_measure(*_run(0.5 * REST_FLOOR_RAD_S2 * np.sin(2 * np.pi * 5 * time_s), 2.0))
    assert quiet.decay_ratio == pytest.approx(1.0, abs=1e-2)
    assert not quiet.persistent  # below the rest floor: sensor noise, not an oscillation
    assert PERSISTENCE_RATIO < 1.0


def test_a_short_settle_window_is_not_judged() -> None:
    time_s = np.arange(3000) * PERIOD_S
    measure = settle_measure(*_run(np.sin(2 * np.pi * 5 * time_s), 1.5))
    assert not measure.judged and not measure.persistent
    assert math.isnan(measure.decay_ratio)


def test_limit_duty_counts_a_command_at_its_limit() -> None:
    v_max, vd_max = 46e-6, 1.24e-3
    command = np.array([0.0, v_max, -v_max, 0.5 * v_max])  # clipped at exactly V_p,max
    rate = np.array([0.0, 0.995 * vd_max, 0.5 * vd_max, -vd_max])
    duty = limit_duty({"V_p_ref": command, "Vd_p": rate}, v_max, vd_max)
    assert duty.command == 0.5 and duty.rate == 0.5
    with pytest.raises(ValueError, match=r"vd_p_max = 0\.0"):
        limit_duty({"V_p_ref": command, "Vd_p": rate}, v_max, 0.0)


def test_events_name_the_limits_and_the_persistent_oscillation() -> None:
    time_s = np.arange(6000) * PERIOD_S
    v_max = 46e-6
    columns = _run(3.0 * np.sin(2 * np.pi * 5.0 * time_s), 2.0)[1]
    columns |= {
        "p_A": np.full(time_s.size, 1e7),
        "p_B": np.full(time_s.size, 2e6),
        "F_Ay": np.full(time_s.size, 1e4),
        "F_By": np.full(time_s.size, 1e4),
        "x_piston": np.full(time_s.size, 0.2),
        "V_p_ref": np.where(time_s < 0.1, v_max, 0.0),
        "Vd_p": np.where((time_s > 1) & (time_s < 1.05), 1.24e-3, 0.0),
    }
    events = find_events(time_s, columns, stroke_m=0.6, max_displacement=v_max, max_rate=1.24e-3)
    kinds = {event.kind: event for event in events}
    assert set(kinds) == {"pump_saturation", "pump_rate_limit", "persistent_oscillation"}
    assert kinds["pump_saturation"].end_s == pytest.approx(0.099)
    assert kinds["persistent_oscillation"].start_s == pytest.approx(2.0, abs=PERIOD_S)
    assert kinds["persistent_oscillation"].extreme == pytest.approx(3.0 / math.sqrt(2), rel=1e-3)


def test_boards_at_any_speed_follow_the_papers_spacing() -> None:
    """The paper's course (section 5.3: 6 m at 9 km/h, 9 m at 18 km/h) is the spacing rule's."""
    from loader_model.simulation.courses import board_spacing_m, boards_at_speed, paper_course

    for speed, spacing in ((9.0, 6.0), (18.0, 9.0)):
        assert board_spacing_m(speed) == spacing
        paper, rule = paper_course(speed), boards_at_speed(speed)
        np.testing.assert_array_equal(paper.profile.distance_m, rule.profile.distance_m)
        assert paper.speed_m_s == rule.speed_m_s
    leading = boards_at_speed(13.5).profile.distance_m[::4]
    np.testing.assert_allclose(np.diff(leading), 7.5, rtol=1e-12)
    with pytest.raises(ValueError, match="speed_kmh"):
        boards_at_speed(0.0)
