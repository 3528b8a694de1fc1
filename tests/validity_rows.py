"""Rows of a time series outside the model's range of validity, computed from its columns alone
(independently of the simulator's :class:`~loader_model.simulation.validity_check.ValidityMonitor`),
for the tests of the validity stop."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from loader_model.simulation.events import intervals
from loader_model.simulation.validity import ValidityBounds

__all__ = ["beyond_bounds"]


def beyond_bounds(
    columns: Mapping[str, np.ndarray], bounds: ValidityBounds, period_s: float = 1e-3
) -> np.ndarray:
    """Boolean per row: outside ``bounds`` (pitch, boom angle, seat acceleration from row 0's,
    or both tyres off the ground for longer than ``bounds.airborne_s`` up to that row)."""
    theta, phi = columns["theta_1"], columns["theta_2"] - columns["theta_1"]
    seat = np.column_stack([columns[n] - columns[n][0] for n in ("f_Sx", "f_Sy")])
    rows = (theta < -bounds.pitch_down_rad) | (theta > bounds.pitch_up_rad)
    rows |= (phi < -bounds.boom_down_rad) | (phi > bounds.boom_up_rad)
    rows |= np.any(np.abs(seat) > bounds.seat_acceleration_m_s2, axis=1)
    for first, last in intervals((columns["F_Ay"] <= 0.0) & (columns["F_By"] <= 0.0)):
        flight_s = (np.arange(first, last + 1) - first + 1) * period_s
        rows[first : last + 1] |= flight_s > bounds.airborne_s * (1 + 1e-9)
    return rows
