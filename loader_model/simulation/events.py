"""Events of a run, found in its time series and recorded in the result (never hidden).

- ``cavitation``: a chamber's absolute pressure below zero, p + 101 325 Pa < 0 (the plant's
  pressures are gauge; a model without cavitation goes there instead of boiling).
- ``tyre_off_ground``: a vertical tyre load F_Ay or F_By exactly 0 (the contact law's lift-off)
  for at least ``airborne_min_s``.
- ``end_stop``: the piston position outside [0, stroke].
- ``pump_saturation``: the command |V_p,ref| above the pump's V_p,max (the plant saturates it).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from loader_model.plant.components import ATMOSPHERIC_PRESSURE_PA
from loader_model.simulation.result import Event

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
) -> tuple[Event, ...]:
    """All events (module notes) in a run's columns, in order of their start.

    Parameters
    ----------
    time_s : numpy.ndarray
        Sample times in s.
    columns : dict of str to numpy.ndarray
        Needs ``p_A``, ``p_B`` [Pa], ``F_<axle>y`` [N] of every axle, ``x_piston`` [m],
        ``V_p_ref``.
    stroke_m, max_displacement : float
        Cylinder stroke in m and the pump's maximum displacement in m³/rev.
    airborne_min_s : float
        Shortest reported tyre lift-off in s.
    axles : sequence of str
        The machine's axles, front first (default the skid-steer's A, B): a lift-off event per
        axle.
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
    command = columns["V_p_ref"]
    add("pump_saturation", "V_p_ref", np.abs(command) > max_displacement, _extreme)
    return tuple(sorted(found, key=lambda event: (event.start_s, event.kind, event.signal)))


def _period(time_s: np.ndarray) -> float:
    return float(time_s[1] - time_s[0]) if time_s.size > 1 else 0.0


def _extreme(values: np.ndarray) -> float:
    return float(values[np.argmax(np.abs(values))])
