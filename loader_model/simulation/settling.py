"""How a run ends: the pump's time at its limits, and whether the motion decays after the road.

A ride controller can look good on one number and still be wrong on the machine: a loop that
rides the pump's displacement limit keeps the chassis pitching at the boom's frequency after the
last obstacle, and ISO 2631-1's rotational weighting W_e (Annex A) barely counts pitch at 5 Hz, so
a_total (Eq. 50) may even reward it. Two measures of a finished run make this visible:

- **Limit duty** (:func:`limit_duty`): the share of the controller's periods in which its command
  |V_p,ref| is at the pump's maximum displacement V_p,max (≥, within :data:`COMMAND_AT_LIMIT`:
  the controller clips at exactly V_p,max), and in which the displacement rate |V̇_p| is within
  the plant's saturation band of the rate limit V̇_p,max (the C¹ saturation of the plant is exact
  below :data:`RATE_AT_LIMIT` of the limit, Table 2 and Fig. 9).
- **Settling** (:func:`settle_measure`): the excitation ends at the last instant at which the
  road under any axle, or the disturbance, still changes (:func:`excitation_end_s`). Over the
  last two seconds of the window after it, the r.m.s. of the chassis pitch acceleration θ̈1 (the
  signal a 5 Hz pitch oscillation lives in) in the last :data:`TAIL_WINDOW_S` is compared with
  that in the :data:`TAIL_WINDOW_S` before. The motion *persists* when the tail is above the floor
  :data:`REST_FLOOR_RAD_S2` (the level a controlled machine comes to rest at despite sensor
  noise) and keeps more than :data:`PERSISTENCE_RATIO` of the second before: a mode of damping
  ratio ζ at frequency f keeps exp(−2π f ζ · 1 s) of its level from one second to the next, so
  only modes with f ζ < 0.036 Hz (ζ < 0.7 % at 5 Hz) persist by this rule; a limit cycle keeps
  its level.

Measured on the skid-steer, paper course (section 5.3) with a 5 s settle window, θ̈1 r.m.s. per
second of the window's last four seconds and the ratio of the last to the one before: the
baseline (boom behind closed load-holding valves, lightly damped on its hydraulic spring) keeps
0.61-0.65 per second (9 km/h empty: 1.10, 0.61, 0.38 rad/s²), the passive accumulator 0.37-0.40,
Table 3's skyhook 0.13-0.23 down to 0.005 rad/s²; the skyhook with the pitch gain's sign
reversed, k_θ = +80 (9 km/h, empty bucket), rides the pump's displacement limit and keeps
3.05, 3.19, 3.85 rad/s² (ratios 1.04, 1.21), while k_θ = +40 still decays (0.53-0.67).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from loader_model.simulation.result import command_column

__all__ = [
    "COMMAND_AT_LIMIT",
    "PERSISTENCE_RATIO",
    "RATE_AT_LIMIT",
    "REST_FLOOR_RAD_S2",
    "REST_NOISE_FACTOR",
    "SETTLE_SIGNAL",
    "TAIL_WINDOW_S",
    "LimitDuty",
    "SettleMeasure",
    "excitation_end_s",
    "limit_duty",
    "settle_measure",
]

#: A command counts as at the pump's limit from this fraction of V_p,max (the controller clips
#: at exactly V_p,max; the margin only absorbs the round-off of the clip).
COMMAND_AT_LIMIT = 1.0 - 1e-9
#: The displacement rate counts as at its limit from this fraction of V̇_p,max: the plant's C¹
#: saturation is exact below 99 % of a limit.
RATE_AT_LIMIT = 0.99
#: The signal judged for persistence: the chassis pitch acceleration θ̈1 [rad/s²].
SETTLE_SIGNAL = "thetadd_1"
#: Length in s of the settle window's last part (the tail), and of the part before it.
TAIL_WINDOW_S = 1.0
#: Tail r.m.s. of θ̈1 [rad/s²] below which the chassis counts as at rest (the skyhook of Table 3
#: comes to 0.005 rad/s² on the paper course, module notes).
REST_FLOOR_RAD_S2 = 0.05
#: Tail over the previous second's r.m.s. above which the motion counts as persistent (module
#: notes: the baseline keeps at most 0.65, a limit cycle about 1).
PERSISTENCE_RATIO = 0.8
#: Where the level a controlled machine keeps at rest on flat ground, driven by its sensors'
#: noise alone, is known (the design check measures it), a tail counts as persistent only above
#: this many times that level: measured on the compact wheel loader with gains designed on the
#: machine, K_fb = (2.49, −13.9, 69.7, 11.0), at rest 0.049 / 0.053 rad/s² (full / empty; 1e-4
#: without noise), after the ISO 8608 roads at 5 and 15 km/h 0.050-0.077 rad/s² with ratios
#: 0.80-1.11: the noise's stationary response, not a motion the road left.
REST_NOISE_FACTOR = 2.0


@dataclass(frozen=True)
class LimitDuty:
    """Share of a run's periods at the pump's limits (module notes).

    Attributes
    ----------
    command : float
        Share of periods with |V_p,ref| ≥ V_p,max, 0 to 1.
    rate : float
        Share of periods with |V̇_p| within the saturation band of V̇_p,max, 0 to 1.
    """

    command: float
    rate: float


@dataclass(frozen=True)
class SettleMeasure:
    """The free response after the excitation (module notes).

    Attributes
    ----------
    excitation_end_s : float
        Time in s at which the road and the disturbance stop changing.
    settle_s : float
        Length in s of the window after it (to the run's end).
    previous_rms : float
        r.m.s. of θ̈1 [rad/s²] over the :data:`TAIL_WINDOW_S` before the tail (nan if the window
        is shorter than two tails).
    tail_rms : float
        r.m.s. of θ̈1 [rad/s²] over the window's last :data:`TAIL_WINDOW_S` (nan likewise).
    """

    excitation_end_s: float
    settle_s: float
    previous_rms: float
    tail_rms: float

    @property
    def judged(self) -> bool:
        """True when the window is long enough to judge (two tails)."""
        return bool(np.isfinite(self.tail_rms))

    @property
    def decay_ratio(self) -> float:
        """Tail over the previous second's r.m.s. (nan when not judged; 0 when both are 0)."""
        if not self.judged:
            return float("nan")
        return float(self.tail_rms / self.previous_rms) if self.previous_rms > 0 else 0.0

    @property
    def persistent(self) -> bool:
        """True when the motion does not decay (module notes); False when not judged."""
        return self.persistent_above(0.0)

    def persistent_above(self, rest_rms: float) -> bool:
        """:attr:`persistent`, with the tail also above :data:`REST_NOISE_FACTOR` times
        ``rest_rms``, the level [rad/s²] the machine keeps at rest with its sensors' noise."""
        floor = max(REST_FLOOR_RAD_S2, REST_NOISE_FACTOR * rest_rms)
        return bool(self.judged and self.tail_rms > floor and self.decay_ratio > PERSISTENCE_RATIO)


def limit_duty(columns: Mapping[str, np.ndarray], v_p_max: float, vd_p_max: float) -> LimitDuty:
    """Share of periods at the pump's displacement and rate limits (module notes).

    Parameters
    ----------
    columns : mapping of str to numpy.ndarray
        A run's columns; needs ``V_p_ref`` [m³/rev] and ``Vd_p`` [m³/(rev·s)] (a valve
        circuit's run: the spool command ``x_s_ref`` [m] and its rate ``xd_s`` [m/s]).
    v_p_max, vd_p_max : float
        The pump's maximum displacement [m³/rev] and displacement rate [m³/(rev·s)], > 0
        (a valve's spool stroke [m] and rate limit [m/s]).
    """
    for name, value in (("v_p_max", v_p_max), ("vd_p_max", vd_p_max)):
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r}: allowed: a finite number > 0")
    command = np.abs(np.asarray(columns[command_column(columns)], dtype=float))
    rate = np.abs(np.asarray(columns["Vd_p" if "Vd_p" in columns else "xd_s"], dtype=float))
    return LimitDuty(
        command=float(np.mean(command >= COMMAND_AT_LIMIT * v_p_max)) if command.size else 0.0,
        rate=float(np.mean(rate >= RATE_AT_LIMIT * vd_p_max)) if rate.size else 0.0,
    )


def excitation_end_s(time_s: np.ndarray, columns: Mapping[str, np.ndarray]) -> float:
    """The first instant [s] from which the road under every axle (columns ``w_*``, ``wd_*``)
    and the disturbance (``F_dx``, ``F_dy``, ``M_d``) no longer change; the run's start when they
    never do."""
    names = [n for n in columns if n.startswith(("w_", "wd_")) or n in ("F_dx", "F_dy", "M_d")]
    if not names or len(time_s) < 2:
        return float(time_s[0]) if len(time_s) else 0.0
    table = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    changing = np.flatnonzero(np.any(np.diff(table, axis=0) != 0.0, axis=1))
    return float(time_s[changing[-1] + 1]) if changing.size else float(time_s[0])


def settle_measure(time_s: np.ndarray, columns: Mapping[str, np.ndarray]) -> SettleMeasure:
    """Tail and previous r.m.s. of θ̈1 after the excitation ends (module notes).

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times in s, equally spaced.
    columns : mapping of str to numpy.ndarray
        A run's columns; needs :data:`SETTLE_SIGNAL` and the exogenous inputs.
    """
    time_s = np.asarray(time_s, dtype=float)
    end_s = excitation_end_s(time_s, columns)
    period = float(time_s[1] - time_s[0]) if time_s.size > 1 else 0.0
    last_s = float(time_s[-1]) + period if time_s.size else 0.0
    settle_s = max(last_s - end_s, 0.0)
    signal = np.asarray(columns[SETTLE_SIGNAL], dtype=float)
    if settle_s < 2 * TAIL_WINDOW_S - 1e-9:
        return SettleMeasure(end_s, settle_s, float("nan"), float("nan"))
    split_s = last_s - TAIL_WINDOW_S - 1e-9
    tail = time_s >= split_s
    previous = (time_s >= split_s - TAIL_WINDOW_S) & ~tail
    return SettleMeasure(
        end_s,
        settle_s,
        float(np.sqrt(np.mean(signal[previous] ** 2))),
        float(np.sqrt(np.mean(signal[tail] ** 2))),
    )
