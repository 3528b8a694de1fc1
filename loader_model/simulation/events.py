"""Events of a run, found in its time series and recorded in the result (never hidden).

- ``cavitation``: a chamber's absolute pressure below zero, p + 101 325 Pa < 0 (the plant's
  pressures are gauge; a model without cavitation goes there instead of boiling).
- ``tyre_off_ground``: a vertical tyre load F_Ay or F_By exactly 0 (the contact law's lift-off)
  for at least ``airborne_min_s``.
- ``end_stop``: the piston position outside [0, stroke].
- ``pump_saturation``: the command |V_p,ref| at or above the pump's V_p,max (the controller clips
  at exactly V_p,max, so "at" counts: :data:`~loader_model.simulation.settling.COMMAND_AT_LIMIT`).
- ``pump_rate_limit``: the displacement rate |V̇_p| within the plant's saturation band of the rate
  limit V̇_p,max (:data:`~loader_model.simulation.settling.RATE_AT_LIMIT`).
- ``persistent_oscillation``: the chassis pitch acceleration does not decay after the road and the
  disturbance stop changing (:func:`~loader_model.simulation.settling.settle_measure`); from the
  excitation's end to the run's end, its value the tail's r.m.s. [rad/s²].
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from loader_model.plant.components import ATMOSPHERIC_PRESSURE_PA
from loader_model.simulation.result import Event, command_column
from loader_model.simulation.settling import (
    COMMAND_AT_LIMIT,
    RATE_AT_LIMIT,
    SETTLE_SIGNAL,
    settle_measure,
)

__all__ = ["DEFAULT_AIRBORNE_MIN_S", "find_events", "intervals"]

#: Shortest tyre lift-off reported, in s (shorter ones are contact chatter at an edge).
DEFAULT_AIRBORNE_MIN_S = 0.005


def intervals(mask: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges (first, last), inclusive, of the runs of True in a boolean ``mask``."""
    padded = np.concatenate([[False], np.asarray(mask, dtype=bool), [False]])
    edges = np.flatnonzero(np.diff(padded.astype(np.int8)))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2], strict=True)]


def find_events(
    time_s: np.ndarray,
    columns: dict[str, np.ndarray],
    *,
    stroke_m: float,
    max_displacement: float,
    airborne_min_s: float = DEFAULT_AIRBORNE_MIN_S,
    axles: Sequence[str] = ("A", "B"),
    max_rate: float | None = None,
    rate_signal: str = "Vd_p",
) -> tuple[Event, ...]:
    """All events (module notes) in a run's columns, in order of their start.

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times in s.
    columns : dict of str to numpy.ndarray
        Needs ``p_A``, ``p_B`` [Pa], ``F_<axle>y`` [N] of every axle, ``x_piston`` [m],
        ``V_p_ref`` (a valve circuit's ``x_s_ref``); ``Vd_p`` for ``max_rate``;
        :data:`~loader_model.simulation.settling.SETTLE_SIGNAL` and the exogenous inputs for
        ``persistent_oscillation``.
    stroke_m, max_displacement : float
        Cylinder stroke in m and the pump's maximum displacement in m³/rev.
    airborne_min_s : float
        Shortest reported tyre lift-off in s.
    axles : sequence of str
        The machine's axles, front first (default the skid-steer's A, B): a lift-off event per
        axle.
    max_rate : float, optional
        The pump's displacement rate limit in m³/(rev·s): ``pump_rate_limit`` events (none if
        not given).
    rate_signal : str
        The column of the actuator's rate: ``Vd_p`` of the pump, ``xd_s`` of a valve's spool
        (``max_rate`` then in m/s, ``max_displacement`` the spool stroke in m).
    """
    found: list[Event] = []

    def add(kind: str, signal: str, mask: np.ndarray, pick: object, min_s: float = 0.0) -> None:
        values = columns[signal]
        for first, last in intervals(mask):
            if time_s[last] - time_s[first] + _period(time_s) < min_s:
                continue
            found.append(
                Event(
                    kind,
                    signal,
                    float(time_s[first]),
                    float(time_s[last]),
                    float(pick(values[first : last + 1])),
                )
            )

    for name in ("p_A", "p_B"):
        add("cavitation", name, columns[name] + ATMOSPHERIC_PRESSURE_PA < 0.0, np.min)
    for name in (f"F_{axle}y" for axle in axles):
        add("tyre_off_ground", name, columns[name] <= 0.0, np.min, airborne_min_s)
    piston = columns["x_piston"]
    add("end_stop", "x_piston", piston < 0.0, np.min)
    add("end_stop", "x_piston", piston > stroke_m, np.max)
    name = command_column(columns)
    command = columns[name]
    add(
        "pump_saturation",
        name,
        np.abs(command) >= COMMAND_AT_LIMIT * max_displacement,
        _extreme,
    )
    if max_rate is not None and rate_signal in columns:
        rate = columns[rate_signal]
        add("pump_rate_limit", rate_signal, np.abs(rate) >= RATE_AT_LIMIT * max_rate, _extreme)
    if SETTLE_SIGNAL in columns and time_s.size > 1:
        settle = settle_measure(time_s, columns)
        if settle.persistent:
            found.append(
                Event(
                    "persistent_oscillation",
                    SETTLE_SIGNAL,
                    settle.excitation_end_s,
                    float(time_s[-1]),
                    settle.tail_rms,
                )
            )
    return tuple(sorted(found, key=lambda event: (event.start_s, event.kind, event.signal)))


def _period(time_s: np.ndarray) -> float:
    return float(time_s[1] - time_s[0]) if time_s.size > 1 else 0.0


def _extreme(values: np.ndarray) -> float:
    return float(values[np.argmax(np.abs(values))])
