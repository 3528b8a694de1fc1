"""The simulator's result: a labelled time series with units, its events, CSV and NPZ output.

Columns, all sampled at the controller's instants t_k = k h (the state at the start of each
period, the command u_k held over it): every plant state (:data:`~loader_model.plant.plant.
STATE_NAMES`), every plant output not already a state of the same name, the controller's command
``V_p_ref`` and state ``z_0 ...``, and the exogenous input (road, road rate, disturbance).
Files: CSV with a header ``name [unit]`` per column, or NPZ with one array per column and the
units and events as JSON strings; both written atomically (:func:`loader_model.io.export.
write_atomically`).
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from loader_model.io.export import write_atomically

__all__ = [
    "COLUMN_UNITS",
    "COMMAND_COLUMNS",
    "RESULT_SUFFIXES",
    "Event",
    "SimulationResult",
    "column_unit",
    "command_column",
    "machine_units",
    "seat_signal_names",
]

#: The column of the controller's command: the pump's ``V_p_ref`` [m³/rev] or, for a machine with
#: a valve circuit, the spool command ``x_s_ref`` [m].
COMMAND_COLUMNS = ("V_p_ref", "x_s_ref")

#: Suffixes :meth:`SimulationResult.write` accepts.
RESULT_SUFFIXES = (".csv", ".npz")

#: Unit of each named column (states, outputs, command, exogenous inputs).
COLUMN_UNITS: Mapping[str, str] = MappingProxyType(
    {
        "time": "s",
        "x_H": "m",
        "y_H": "m",
        "theta_1": "rad",
        "theta_2": "rad",
        "xd_H": "m/s",
        "yd_H": "m/s",
        "thetad_1": "rad/s",
        "thetad_2": "rad/s",
        "xi_A": "m",
        "xi_B": "m",
        "p_A": "Pa",
        "p_B": "Pa",
        "V_p": "m^3/rev",
        "Vd_p": "m^3/(rev*s)",
        "x_s": "m",
        "xd_s": "m/s",
        "x_s_ref": "m",
        "Q_supply": "m^3/s",
        "V_acc": "m^3",
        **{name: "m" for name in ("u_Px", "u_Ox", "u_Py", "u_Oy")},
        **{name: "m/s" for name in ("ud_Px", "ud_Ox", "ud_Py", "ud_Oy")},
        "phi": "rad",
        "f_Hx": "m/s^2",
        "f_Hy": "m/s^2",
        "f_Ny": "m/s^2",
        "f_Sx": "m/s^2",
        "f_Sy": "m/s^2",
        "thetadd_1": "rad/s^2",
        "F_act": "N",
        "x_piston": "m",
        "Q_pump": "m^3/s",
        "F_Ay": "N",
        "F_By": "N",
        "p_acc": "Pa",
        "f_Px": "m/s^2",
        "f_Py": "m/s^2",
        "V_p_ref": "m^3/rev",
        "w_Ax": "m",
        "w_Ay": "m",
        "w_Bx": "m",
        "w_By": "m",
        "wd_Ax": "m/s",
        "wd_Ay": "m/s",
        "wd_Bx": "m/s",
        "wd_By": "m/s",
        "F_dx": "N",
        "F_dy": "N",
        "M_d": "N*m",
    }
)


_AXLE_UNITS = (  # the columns of any axle <X>: (pattern, unit)
    (re.compile(r"F_[A-Za-z0-9]+y"), "N"),
    (re.compile(r"xi_[A-Za-z0-9]+"), "m"),
    (re.compile(r"w_[A-Za-z0-9]+[xy]"), "m"),
    (re.compile(r"wd_[A-Za-z0-9]+[xy]"), "m/s"),
)


def _axle_unit(name: str) -> str:
    """Unit of an axle's column not in :data:`COLUMN_UNITS` (a third axle's), else ``"-"``."""
    return next((unit for pattern, unit in _AXLE_UNITS if pattern.fullmatch(name)), "-")


def command_column(columns: Mapping[str, object]) -> str:
    """The name of the command column of a run's ``columns`` (:data:`COMMAND_COLUMNS`).

    Raises
    ------
    KeyError
        If the columns hold no command.
    """
    found = [name for name in COMMAND_COLUMNS if name in columns]
    if not found:
        raise KeyError(f"no command column; expected one of {', '.join(COMMAND_COLUMNS)}")
    return found[0]


def column_unit(name: str) -> str:
    """Unit of a simulation column or plant signal ``name``: :data:`COLUMN_UNITS`, else any
    axle's tyre, anchor and road signals by their name pattern, else ``"-"``."""
    return COLUMN_UNITS.get(name) or _axle_unit(name)


def machine_units(info: Any) -> dict[str, str]:
    """Units of the columns a machine's description names (:class:`~loader_model.machines.
    MachineInfo`): each coordinate in m (its length coordinates) or rad (every other, an angle),
    its rate per second, and the joint angles' outputs in rad."""
    lengths = set(info.length_coordinates)
    units = {}
    for coordinate, rate in zip(info.coordinate_names, info.rate_names, strict=True):
        unit = "m" if coordinate in lengths else "rad"
        units |= {coordinate: unit, rate: f"{unit}/s"}
    return units | dict.fromkeys(info.joint_angles, "rad")


def seat_signal_names() -> dict[str, str]:
    """The seat's ISO 2631 axes and the plant outputs (:data:`~loader_model.plant.plant.
    OUTPUT_NAMES`) that carry them: x = f_Px, z = f_Py, the seat pad under the occupant
    (section 5.3; :mod:`loader_model.plant.occupant`, equal to the chassis's f_S with the
    occupant off; the plant's y, up, is ISO 2631's z), pitch = θ̈1 from the chassis (section
    3.3). The one place that says what "the seat" is: :meth:`SimulationResult.seat_record` and
    the optimal-control bound (:mod:`loader_model.bound`) both read it."""
    return {"x": "f_Px", "z": "f_Py", "pitch": "thetadd_1"}


@dataclass(frozen=True)
class Event:
    """An interval in which the run did something the model or the machine limits flag.

    Attributes
    ----------
    kind : str
        ``"cavitation"`` (absolute pressure below zero), ``"tyre_off_ground"``, ``"end_stop"``
        (piston outside [0, stroke]), ``"pump_saturation"`` (|V_p,ref| at V_p,max),
        ``"pump_rate_limit"`` (|V̇_p| at its limit), ``"persistent_oscillation"`` (the motion
        does not decay after the road, :mod:`~loader_model.simulation.settling`) or
        ``"validity"`` (where a stopped run left the model's range of validity,
        :mod:`~loader_model.simulation.validity`).
    signal : str
        The column that shows it.
    start_s, end_s : float
        First and last sample time of the interval in s.
    extreme : float
        The signal's most extreme value in the interval, in its column unit.
    """

    kind: str
    signal: str
    start_s: float
    end_s: float
    extreme: float

    def describe(self) -> str:
        """One line: kind, signal, interval and extreme value with unit."""
        unit = COLUMN_UNITS.get(self.signal, "")
        return (
            f"{self.kind}: {self.signal} from {self.start_s:.3f} s to {self.end_s:.3f} s "
            f"(extreme {self.extreme:.4g} {unit})"
        )


@dataclass(frozen=True)
class SimulationResult:
    """Labelled time series of one closed-loop run (module notes).

    Attributes
    ----------
    time_s : numpy.ndarray
        (N,) sample times in s.
    columns : mapping of str to numpy.ndarray
        Column name to (N,) values in :data:`COLUMN_UNITS` (``z_i``: the controller's unit).
    final_state : numpy.ndarray
        Plant state at the end of the last period.
    events : tuple of Event
        What :func:`~loader_model.simulation.events.find_events` found.
    metadata : mapping of str to object
        Controller, backend, period, substeps, wall time and the like (JSON-serialisable).
    """

    time_s: np.ndarray
    columns: Mapping[str, np.ndarray]
    final_state: np.ndarray
    events: tuple[Event, ...] = ()
    metadata: Mapping[str, object] = field(default_factory=dict)

    def __getitem__(self, name: str) -> np.ndarray:
        """The column ``name``; KeyError naming the columns if there is none."""
        try:
            return self.columns[name]
        except KeyError:
            raise KeyError(f"no column {name!r}; columns: {list(self.columns)}") from None

    @property
    def names(self) -> tuple[str, ...]:
        """Column names in order."""
        return tuple(self.columns)

    def unit(self, name: str) -> str:
        """Unit of column ``name`` (any axle's tyre and road columns by their pattern, another
        machine's coordinates and joint angles from its description (metadata ``units``),
        ``"-"`` for the controller's state and other columns of no listed unit)."""
        described = self.metadata.get("units", {})
        return described.get(name) or column_unit(name)  # type: ignore[union-attr]

    def seat_record(self) -> object:
        """The seat's accelerations as an ISO 2631 record: x = f_Px, z = f_Py, pitch = θ̈1.

        What section 5.3 measured: the seat pad between the occupant and the cushion
        (:mod:`loader_model.plant.occupant`; with the occupant switched off the pad reads the
        chassis at S), and the chassis pitch acceleration (section 3.3). Specific forces minus
        their value at t = 0 (the static 1 g), so that the record holds the vibration; the
        plant's y (up) is ISO 2631's z.
        """
        from loader_model.iso2631 import VibrationRecord

        axes = {axis: self[signal] for axis, signal in seat_signal_names().items()}
        return VibrationRecord(self.time_s, {k: v - v[0] for k, v in axes.items()})

    def seat_evaluation(self) -> object:
        """ISO 2631-1 evaluation of :meth:`seat_record` with the paper's k factors (Eq. 49, 50)."""
        from loader_model.iso2631 import PAPER_K_FACTORS, evaluate_record

        record = self.seat_record()
        k_factors = {axis: PAPER_K_FACTORS[axis] for axis in record.axis_names}
        return evaluate_record(record, k_factors=k_factors)

    def write(self, path: str | Path) -> Path:
        """Write the series as CSV or NPZ (by suffix), atomically; return the path."""
        suffix = Path(path).suffix.lower()

        def write_csv(temporary: Path) -> None:
            header = ",".join(f"{name} [{self.unit(name)}]" for name in ("time", *self.names))
            table = np.column_stack([self.time_s, *self.columns.values()])
            np.savetxt(temporary, table, delimiter=",", header=header, comments="", fmt="%.10g")

        def write_npz(temporary: Path) -> None:
            with open(temporary, "wb") as handle:
                np.savez(
                    handle,
                    time=self.time_s,
                    final_state=self.final_state,
                    units=json.dumps({n: self.unit(n) for n in ("time", *self.names)}),
                    events=json.dumps([e.__dict__ for e in self.events]),
                    metadata=json.dumps(dict(self.metadata)),
                    **self.columns,
                )

        writer = write_csv if suffix == ".csv" else write_npz
        return write_atomically(path, writer, RESULT_SUFFIXES, "simulation result")
