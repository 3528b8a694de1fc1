"""Measurement files for identification: a CSV with units in the header (section 4.1).

Format (comma separated, UTF-8; blank lines and lines starting with ``#`` are skipped):

.. code-block:: text

    # any comment lines
    time [s],x_cyl [m],p_A [Pa],p_B [Pa],Q_A [m^3/s],m_load [kg]
    0.000,0.05012,6.512e6,2.01e6,1.2e-5,340
    ...

========== ================================ =====================================================
column     accepted units                   meaning
========== ================================ =====================================================
time       s                                sample time, strictly increasing, uniform within 1 %
x_cyl      m                                piston position from the retracted end stop, *or*
phi        rad, deg (× π/180, converted)    boom angle φ = θ2 − θ1 (x_cyl from the geometry)
p_A        Pa, bar (× 1e5, converted)       piston-side gauge pressure (both cylinders)
p_B        Pa, bar (× 1e5, converted)       rod-side gauge pressure
Q_A        m^3/s, L/min (÷ 60000)           pump flow to the piston sides (both cylinders), *or*
V_p        m^3/rev, cm^3/rev (× 1e-6)       pump displacement; Q_A = V_p n with the shaft speed
                                            n of the parameter file's ``[pump]``
m_load     kg                               bucket-load mass (known, as in the paper)
theta_1    rad, deg (× π/180)               optional: chassis pitch from level, nose up positive
f_Hx       m/s^2, g (× 9.80665)             optional: specific force at H along the chassis x
f_Hy       m/s^2, g                         optional: specific force at H along the chassis y
f_Ny       m/s^2, g                         optional: specific force at N along the chassis y
========== ================================ =====================================================

The four chassis columns (section 3.3: triaxial accelerometer at H, vertical one at N, pitch)
come together or not at all; an accelerometer reads f = Rᵀ(a + g ŷ), so a chassis at rest
pitched by θ1 reads f_Hx = g sin θ1, f_Hy = g cos θ1. With them, the friction identification
takes the chassis motion into account (:mod:`.chassis`); without them it takes the chassis at
rest, which leaves kilonewtons of error on a machine on tyres (README).

Each header cell is ``name [unit]``. Other columns are allowed and ignored. Every error names
the column, the file line and the value.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from loader_model.io.export import write_atomically

__all__ = [
    "CHASSIS_COLUMNS",
    "COLUMN_UNITS",
    "MIN_ROWS",
    "TIME_JITTER_TOLERANCE",
    "MeasurementRecord",
    "read_measurement_csv",
    "write_measurement_csv",
]

#: Standard gravity [m/s²], the unit ``g`` of the specific-force columns.
STANDARD_GRAVITY = 9.80665
#: Column name -> accepted unit -> factor to SI.
COLUMN_UNITS: dict[str, dict[str, float]] = {
    "time": {"s": 1.0},
    "x_cyl": {"m": 1.0},
    "phi": {"rad": 1.0, "deg": np.pi / 180.0},
    "p_A": {"Pa": 1.0, "bar": 1e5},
    "p_B": {"Pa": 1.0, "bar": 1e5},
    "Q_A": {"m^3/s": 1.0, "L/min": 1.0 / 60000.0},
    "V_p": {"m^3/rev": 1.0, "cm^3/rev": 1e-6},
    "m_load": {"kg": 1.0},
    "theta_1": {"rad": 1.0, "deg": np.pi / 180.0},
    "f_Hx": {"m/s^2": 1.0, "g": STANDARD_GRAVITY},
    "f_Hy": {"m/s^2": 1.0, "g": STANDARD_GRAVITY},
    "f_Ny": {"m/s^2": 1.0, "g": STANDARD_GRAVITY},
}
#: Optional chassis columns, all or none (pitch, then the specific forces).
CHASSIS_COLUMNS = ("theta_1", "f_Hx", "f_Hy", "f_Ny")
_REQUIRED = ("time", "p_A", "p_B", "m_load")
_EITHER = (("x_cyl", "phi"), ("Q_A", "V_p"))
#: Fewest data rows accepted (the derivative window needs more for a useful fit anyway).
MIN_ROWS = 50
#: Largest accepted deviation of a sampling interval from the mean interval, as a fraction.
TIME_JITTER_TOLERANCE = 0.01


@dataclass(frozen=True)
class MeasurementRecord:
    """A validated identification record, in SI units (see the module docstring).

    Exactly one of ``position_m`` and ``boom_angle_rad``, and one of ``flow_m3_s`` and
    ``displacement_m3_rev`` is given.
    """

    time_s: np.ndarray
    position_m: np.ndarray | None
    p_a_pa: np.ndarray
    p_b_pa: np.ndarray
    load_mass_kg: np.ndarray
    flow_m3_s: np.ndarray | None = None
    displacement_m3_rev: np.ndarray | None = None
    boom_angle_rad: np.ndarray | None = None
    pitch_rad: np.ndarray | None = None
    specific_force_m_s2: np.ndarray | None = None

    @property
    def has_chassis(self) -> bool:
        """True if the record has the chassis pitch and specific forces (shape (n, 3))."""
        return self.pitch_rad is not None and self.specific_force_m_s2 is not None

    @property
    def sample_rate_hz(self) -> float:
        """Mean sample rate (n − 1)/(t_last − t_first) in Hz."""
        return float((self.time_s.size - 1) / (self.time_s[-1] - self.time_s[0]))

    def flow(self, shaft_speed_rev_s: float) -> np.ndarray:
        """Pump flow Q_A in m³/s: the flow column, or V_p n from the displacement column."""
        if self.flow_m3_s is not None:
            return self.flow_m3_s
        return np.asarray(self.displacement_m3_rev) * shaft_speed_rev_s

    def position(self, from_boom_angle: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """Piston position in m: the x_cyl column, or ``from_boom_angle(phi)``."""
        if self.position_m is not None:
            return self.position_m
        return from_boom_angle(np.asarray(self.boom_angle_rad))

    def columns(self) -> dict[str, np.ndarray]:
        """Header label ``name [SI unit]`` -> samples, in file order (for writing)."""
        out: dict[str, np.ndarray] = {"time [s]": self.time_s}
        if self.position_m is not None:
            out["x_cyl [m]"] = self.position_m
        else:
            out["phi [rad]"] = np.asarray(self.boom_angle_rad)
        out |= {"p_A [Pa]": self.p_a_pa, "p_B [Pa]": self.p_b_pa}
        if self.flow_m3_s is not None:
            out["Q_A [m^3/s]"] = self.flow_m3_s
        else:
            out["V_p [m^3/rev]"] = np.asarray(self.displacement_m3_rev)
        out["m_load [kg]"] = self.load_mass_kg
        if self.has_chassis:
            out["theta_1 [rad]"] = np.asarray(self.pitch_rad)
            for k, name in enumerate(CHASSIS_COLUMNS[1:]):
                out[f"{name} [m/s^2]"] = np.asarray(self.specific_force_m_s2)[:, k]
        return out


def _parse_header(cells: list[str], origin: str) -> dict[str, tuple[int, float]]:
    found: dict[str, tuple[int, float]] = {}
    for index, cell in enumerate(cells):
        text = cell.strip()
        name, _, rest = text.partition("[")
        name = name.strip()
        if name not in COLUMN_UNITS:
            continue  # other channels of a log are allowed and ignored
        if name in found:
            raise ValueError(f"{origin}: column {name!r} appears twice in the header")
        units = COLUMN_UNITS[name]
        if not rest.endswith("]"):
            raise ValueError(
                f"{origin}: column {text!r} has no unit; write it as '{name} [unit]' with unit "
                f"one of {list(units)}"
            )
        unit = rest[:-1].strip()
        if unit not in units:
            raise ValueError(f"{origin}: column {name!r} has unit {unit!r}; allowed: {list(units)}")
        found[name] = (index, units[unit])
    missing = [name for name in _REQUIRED if name not in found]
    for first, second in _EITHER:
        if first not in found and second not in found:
            missing.append(f"{first} (or {second})")
        if first in found and second in found:
            raise ValueError(f"{origin}: give either column {first!r} or {second!r}, not both")
    given = [name for name in CHASSIS_COLUMNS if name in found]
    if given and len(given) < len(CHASSIS_COLUMNS):
        raise ValueError(
            f"{origin}: chassis columns {given} given without "
            f"{[n for n in CHASSIS_COLUMNS if n not in found]}; give all of "
            f"{list(CHASSIS_COLUMNS)} (pitch and the three specific forces) or none"
        )
    if missing:
        raise ValueError(
            f"{origin}: missing column(s) {missing}; the header has {[c.strip() for c in cells]}"
        )
    return found


def _column(
    rows: list[list[str]], lines: list[int], index: int, name: str, origin: str
) -> np.ndarray:
    values = np.empty(len(rows))
    for row, (cells, line) in enumerate(zip(rows, lines, strict=True)):
        text = cells[index].strip() if index < len(cells) else ""
        try:
            values[row] = float(text)
        except ValueError:
            raise ValueError(
                f"{origin}: column {name!r}, line {line}: {text!r} is not a number"
            ) from None
        if not np.isfinite(values[row]):
            raise ValueError(
                f"{origin}: column {name!r}, line {line}: {text!r} is not finite"
            ) from None
    return values


def _check_time(time: np.ndarray, lines: list[int], origin: str) -> None:
    interval = np.diff(time)
    bad = np.flatnonzero(interval <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise ValueError(
            f"{origin}: column 'time', line {lines[i]}: {float(time[i])!r} s is not after "
            f"{float(time[i - 1])!r} s (time must be strictly increasing)"
        )
    mean = (time[-1] - time[0]) / (time.size - 1)
    bad = np.flatnonzero(np.abs(interval - mean) > TIME_JITTER_TOLERANCE * mean)
    if bad.size:
        i = int(bad[0]) + 1
        raise ValueError(
            f"{origin}: column 'time', line {lines[i]}: {float(time[i])!r} s is "
            f"{float(interval[i - 1]):.6g} s after {float(time[i - 1])!r} s; the mean interval is "
            f"{mean:.6g} s and intervals may deviate by {TIME_JITTER_TOLERANCE:.0%} "
            "(non-uniform sampling)"
        )


#: Largest pressure magnitude read [Pa] (10 000 bar, ten times any mobile hydraulics).
MAX_PRESSURE_PA = 1e9


def _check_values(
    data: dict[str, np.ndarray], header: list[str], found: dict[str, tuple[int, float]],
    lines: list[int], origin: str,
) -> None:  # fmt: skip
    """Refuse a negative load mass and an implausible pressure (a wrong unit in the header)."""
    negative = np.flatnonzero(data["m_load"] < 0.0)
    if negative.size:
        i = int(negative[0])
        raise ValueError(
            f"{origin}: column 'm_load', line {lines[i]}: {data['m_load'][i]:g} kg; allowed: a "
            "mass >= 0 kg"
        )
    for name in ("p_A", "p_B"):
        high = np.flatnonzero(np.abs(data[name]) > MAX_PRESSURE_PA)
        if high.size:
            i = int(high[0])
            raise ValueError(
                f"{origin}: column {header[found[name][0]].strip()!r}, line {lines[i]}: "
                f"{data[name][i]:.4g} Pa; allowed: at most {MAX_PRESSURE_PA:g} Pa (10 000 bar) "
                "in magnitude (is the unit in the header right?)"
            )


def read_measurement_csv(path: str | Path) -> MeasurementRecord:
    """Read and validate an identification record (format in the module docstring).

    Raises
    ------
    ValueError
        Naming column, line and value: missing column, missing or unknown unit, a cell that is
        not a finite number, fewer than :data:`MIN_ROWS` rows, time not strictly increasing,
        sampling intervals off the mean by more than :data:`TIME_JITTER_TOLERANCE`, a negative
        load mass, a pressure above :data:`MAX_PRESSURE_PA` (a wrong unit in the header).
    """
    origin = str(path)
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"measurement file {origin!r} does not exist")
    numbered = [
        (number, line)
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1)
        if line.strip() and not line.lstrip().startswith("#")
    ]
    if not numbered:
        raise ValueError(f"{origin}: no header row; expected {_REQUIRED} and Q_A or V_p")
    header = next(csv.reader([numbered[0][1]]))
    found = _parse_header(header, origin)
    body = numbered[1:]
    if len(body) < MIN_ROWS:
        raise ValueError(f"{origin}: {len(body)} data rows; at least {MIN_ROWS} are needed")
    rows = list(csv.reader(io.StringIO("\n".join(line for _, line in body))))
    lines = [number for number, _ in body]
    data = {
        name: _column(rows, lines, index, name, origin) * factor
        for name, (index, factor) in found.items()
    }
    _check_time(data["time"], lines, origin)
    _check_values(data, header, found, lines, origin)
    return MeasurementRecord(
        time_s=data["time"],
        position_m=data.get("x_cyl"),
        p_a_pa=data["p_A"],
        p_b_pa=data["p_B"],
        load_mass_kg=data["m_load"],
        flow_m3_s=data.get("Q_A"),
        displacement_m3_rev=data.get("V_p"),
        boom_angle_rad=data.get("phi"),
        pitch_rad=data.get("theta_1"),
        specific_force_m_s2=(
            np.column_stack([data[n] for n in CHASSIS_COLUMNS[1:]]) if "f_Hx" in data else None
        ),
    )


def write_measurement_csv(
    path: str | Path, columns: Mapping[str, np.ndarray], comments: tuple[str, ...] = ()
) -> Path:
    """Write labelled columns (``{"time [s]": t, ...}``) as CSV, atomically.

    Floats are written with ``repr`` (shortest text that reads back as the same number).
    """
    labels = list(columns)
    data = np.column_stack([np.asarray(columns[label], dtype=float) for label in labels])

    def write(temporary: Path) -> None:
        with open(temporary, "w", encoding="utf-8", newline="\n") as stream:
            for comment in comments:
                stream.write(f"# {comment}\n")
            stream.write(",".join(labels) + "\n")
            stream.writelines(",".join(map(repr, row)) + "\n" for row in data.tolist())

    return write_atomically(path, write, (".csv",), "measurement file")
