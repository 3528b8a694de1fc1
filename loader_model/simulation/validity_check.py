"""The range-of-validity check during a run, and the simulator's errors.

:class:`ValidityMonitor` checks each chunk of rows against the
:class:`~loader_model.simulation.validity.ValidityBounds` (bounds and their reasons:
:mod:`~loader_model.simulation.validity`) and returns the first :class:`ValidityViolation`; the
simulator then stops and raises :class:`ModelValidityError` with the time series up to it.
:func:`raise_if_not_finite` raises :class:`SimulationError` when the integration leaves the finite
numbers. Both errors are ValueErrors (the command line's user-error path, exit code 2).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from loader_model.plant.layout import PlantLayout
from loader_model.plant.plant import OUTPUT_NAMES, STATE_NAMES
from loader_model.simulation.result import Event, SimulationResult
from loader_model.simulation.validity import ValidityBounds

__all__ = [
    "ModelValidityError",
    "SimulationError",
    "ValidityMonitor",
    "ValidityViolation",
    "raise_if_not_finite",
]


class SimulationError(ValueError):
    """The integration failed or left the finite numbers; the message names time and state."""


@dataclass(frozen=True)
class ValidityViolation:
    """Where a run first left the range of validity.

    Attributes
    ----------
    bound : str
        The field of :class:`ValidityBounds` crossed.
    signal : str
        The column that shows it: ``theta_1``, ``phi`` (θ2 − θ1), the axles' loads
        (``F_Ay, F_By``; more axles: each), ``f_Sx`` or ``f_Sy``.
    index : int
        Row of the time series (t = index · h).
    time_s, value, limit : float
        Its time in s, the signal's value and the bound it crossed, both in the signal's unit
        and signed (the nose-down and retracted bounds negative; for ``airborne_s``: the time in
        the air so far and the bound, s; for the seat: the acceleration from its static value).
    state : mapping of str to float
        The plant state at that row.
    """

    bound: str
    signal: str
    index: int
    time_s: float
    value: float
    limit: float
    state: Mapping[str, float]

    def describe(self) -> str:
        """One line: time, what crossed which bound, and the state."""
        what = {
            "pitch_down_rad": ("chassis pitch", "the nose-down (forward tip-over) bound"),
            "pitch_up_rad": ("chassis pitch", "the nose-up (backward tip-over) bound"),
            "boom_down_rad": ("boom angle from its operating value", "the retracted end stop's "
                              "bound"),
            "boom_up_rad": ("boom angle from its operating value", "the extended end stop's "
                            "bound"),
        }  # fmt: skip
        if self.bound in what:
            name, bound = what[self.bound]
            text = (
                f"{name} {self.signal} = {self.value:.4g} rad ({math.degrees(self.value):.1f}°) "
                f"beyond {bound} {self.limit:.4g} rad ({math.degrees(self.limit):.1f}°)"
            )
        elif self.bound == "airborne_s":
            tyres = self.signal.split(", ")
            which = "both tyres" if len(tyres) == 2 else f"all {len(tyres)} tyres"
            text = (
                f"{which} off the ground ({' = '.join(tyres)} = 0) for {self.value:.3f} s, "
                f"longer than the bound {self.limit:g} s"
            )
        else:
            text = (
                f"seat acceleration {self.signal} = {self.value:.4g} m/s² from its static value, "
                f"beyond the bound {self.limit:.4g} m/s² (a failed integration step or a "
                "crash, not a ride)"
            )
        state = ", ".join(f"{n}={v:.6g}" for n, v in self.state.items())
        return (
            f"the run left the model's range of validity at t = {self.time_s:.3f} s: {text}; "
            f"state: {state}"
        )


class ModelValidityError(SimulationError):
    """A run left the model's range of validity (a :class:`SimulationError`, so a ValueError).

    Attributes
    ----------
    violation : ValidityViolation
        Which bound, when and in what state.
    result : SimulationResult
        The time series up to and including the violating row, with a ``validity`` event.
    """

    def __init__(self, violation: ValidityViolation, result: SimulationResult) -> None:
        super().__init__(violation.describe())
        self.violation = violation
        self.result = result

    @classmethod
    def stopping(cls, violation: ValidityViolation, result: SimulationResult) -> ModelValidityError:
        """The error of a run stopped at ``violation``: ``result`` with a ``validity`` event
        (from the start of the flight for ``airborne_s``, else at the violating row)."""
        period_s = float(result.metadata["period_s"])  # type: ignore[arg-type]
        start_s = violation.time_s
        if violation.bound == "airborne_s":
            start_s = violation.time_s - violation.value + period_s
        event = Event("validity", violation.signal, start_s, violation.time_s, violation.value)
        events = tuple(sorted((*result.events, event), key=lambda e: (e.start_s, e.kind, e.signal)))
        return cls(violation, dataclasses.replace(result, events=events))

    def __reduce__(self) -> tuple[type, tuple[ValidityViolation, SimulationResult]]:
        return type(self), (self.violation, self.result)


class ValidityMonitor:
    """Checks the rows of a run chunk by chunk against :class:`ValidityBounds` (module notes).

    Parameters
    ----------
    bounds : ValidityBounds
        The bounds.
    period_s : float
        Row spacing h in s.
    layout : PlantLayout, optional
        The plant's names (default the skid-steer's): pitch θ1, boom θ2 − θ1, every axle's
        vertical load (airborne: all of them zero) and the seat point's specific forces.
    """

    def __init__(
        self, bounds: ValidityBounds, period_s: float, layout: PlantLayout | None = None
    ) -> None:
        states = STATE_NAMES if layout is None else layout.state_names
        outputs = OUTPUT_NAMES if layout is None else layout.output_names
        axles = ("A", "B") if layout is None else layout.machine.axles
        seat = "S" if layout is None else layout.machine.seat_point
        self._state_names = states
        self._theta = states.index("theta_1"), states.index("theta_2")
        self._tyres = [outputs.index(f"F_{axle}y") for axle in axles]
        self._tyre_signal = ", ".join(f"F_{axle}y" for axle in axles)
        self._seat = outputs.index(f"f_{seat}x"), outputs.index(f"f_{seat}y")
        self._seat_signals = f"f_{seat}x", f"f_{seat}y"
        self.bounds = bounds
        self._period_s = float(period_s)
        self._airborne_rows = 0  # consecutive airborne rows that end the rows checked so far
        self._seat_static: np.ndarray | None = None
        self._longest_s = 0.0  # longest flight within the rows of the last check, s

    def check(
        self, start: int, states: np.ndarray, outputs: np.ndarray
    ) -> ValidityViolation | None:
        """The first violation in rows ``start ..`` of the run, or None.

        Parameters
        ----------
        start : int
            Row index of the first row given (rows must come in order, without gaps).
        states : numpy.ndarray
            (n, ≥ len(STATE_NAMES)) rows starting with the plant state (the simulator's carry).
        outputs : numpy.ndarray
            (n, len(OUTPUT_NAMES)) plant outputs of the rows.
        """
        bounds = self.bounds
        seat_columns = list(self._seat)
        if self._seat_static is None:
            self._seat_static = outputs[0, seat_columns].copy()
        theta = states[:, self._theta[0]]
        phi = states[:, self._theta[1]] - theta
        seat = outputs[:, seat_columns] - self._seat_static
        airborne = self._airborne_time(np.all(outputs[:, self._tyres] <= 0.0, axis=1))
        seat_x, seat_y = self._seat_signals
        accel, flight = bounds.seat_acceleration_m_s2, bounds.airborne_s * (1 + 1e-9)
        within = (  # the common case in a few reductions (NaN is never within: checked below)
            -bounds.pitch_down_rad <= theta.min()
            and theta.max() <= bounds.pitch_up_rad
            and -bounds.boom_down_rad <= phi.min()
            and phi.max() <= bounds.boom_up_rad
            and np.abs(seat).max() <= accel
            and self._longest_s <= flight
        )
        if within:
            return None
        candidates = (  # (bound, signal, signed values, signed limit, rows beyond it)
            ("pitch_down_rad", "theta_1", theta, -bounds.pitch_down_rad, theta < -bounds.pitch_down_rad),
            ("pitch_up_rad", "theta_1", theta, bounds.pitch_up_rad, theta > bounds.pitch_up_rad),
            ("boom_down_rad", "phi", phi, -bounds.boom_down_rad, phi < -bounds.boom_down_rad),
            ("boom_up_rad", "phi", phi, bounds.boom_up_rad, phi > bounds.boom_up_rad),
            ("airborne_s", self._tyre_signal, airborne, bounds.airborne_s, airborne > flight),
            ("seat_acceleration_m_s2", seat_x, seat[:, 0], accel, np.abs(seat[:, 0]) > accel),
            ("seat_acceleration_m_s2", seat_y, seat[:, 1], accel, np.abs(seat[:, 1]) > accel),
        )  # fmt: skip
        first: tuple[int, str, str, float, float] | None = None
        for bound, signal, values, limit, beyond in candidates:
            if beyond.any():
                row = int(np.argmax(beyond))
                if first is None or row < first[0]:
                    first = (row, bound, signal, float(values[row]), float(limit))
        if first is None:
            return None
        row, bound, signal, value, limit = first
        return ValidityViolation(
            bound,
            signal,
            start + row,
            (start + row) * self._period_s,
            value,
            limit,
            dict(zip(self._state_names, (float(v) for v in states[row]), strict=False)),
        )

    def _airborne_time(self, off: np.ndarray) -> np.ndarray:
        """Time in s every tyre has been off the ground at each row (0 on the ground); sets
        ``_longest_s``, the longest of them in these rows."""
        if not off.any():
            self._airborne_rows, self._longest_s = 0, 0.0
            return np.zeros(off.size)
        rows = np.arange(off.size)
        last_ground = np.maximum.accumulate(np.where(off, -1, rows))
        count = rows - last_ground
        count[last_ground < 0] += self._airborne_rows
        self._airborne_rows = int(count[-1])
        self._longest_s = int(count.max()) * self._period_s
        return count * self._period_s


def raise_if_not_finite(
    carry: np.ndarray,
    outputs: np.ndarray,
    start: int,
    period_s: float,
    state_names: tuple[str, ...] = STATE_NAMES,
) -> None:
    """Raise :class:`SimulationError` naming the time and the last finite state if a chunk's
    carry (columns: periods) or outputs hold a non-finite number (``state_names``: the
    plant's, default the skid-steer's)."""
    bad = ~(np.all(np.isfinite(carry), axis=0) & np.all(np.isfinite(outputs), axis=0))
    if not bad.any():
        return
    index = int(np.flatnonzero(bad)[0])
    previous = carry[:, index - 1] if index > 0 else None
    state = (
        "the state at the chunk's start"
        if previous is None
        else ", ".join(
            f"{n}={v:.6g}" for n, v in zip(state_names, previous[: len(state_names)], strict=True)
        )
    )
    raise SimulationError(
        f"the integration left the finite numbers in the period starting at "
        f"t = {(start + index) * period_s:.4f} s; last finite state: {state}"
    )
