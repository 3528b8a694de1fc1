"""Parameter files of described machines other than the skid-steer: flat, by model name.

The skid-steer keeps its grouped files (:mod:`loader_model.parameters.sets`). Every other machine
of :mod:`loader_model.machines` has one flat TOML file, ``loader_model/data/machines/<name>.toml``
for the shipped values::

    [model]       # every generated parameter by name (PARAMETER_NAMES): the multibody model
    m_1 = { value = 4200.0, unit = "kg", source = "estimate: ..." }
    [cylinders]   # the driven lift cylinder group (fields of CylinderParameters): Eq. 28, 30
    count = { value = 2, unit = "-", source = "..." }
    [hydraulics]  # bulk_modulus and charge_pressure (fields of HydraulicParameters)
    [tyres]       # each axle's free radius and tandem cam (loader_model.parameters.tyres)
    R_A = { value = 0.45, unit = "m", source = "..." }
    [valve]       # a valve circuit's (fields of ValveParameters; its [hydraulics]: bulk_modulus)
    [loads.empty] # a bucket load case: values of [model] it replaces (m_3, J_3, Q_x, ...)

``[valve]`` is required for a machine whose description has ``[circuit] kind = "valve"`` and
refused for any other (its rod side is at the tank pressure, so no charge pressure is given).

Every value is checked on loading: a missing or unknown name, a wrong unit (the generated
``PARAMETER_UNITS``; the schema's units for the cylinders), no source, or a value outside the
description's range (points: its ``point_range``; the cylinders: the schema's ranges; the tyres:
the description's ``[tyres]`` ranges inside :data:`~loader_model.parameters.tyres.TYRE_LIMITS`) raise a
ValueError naming the file and the entry. The static loads (``F_Ay0``, ``F_By0``, the locked
cylinders' ``F_<name>0``) are computed by the static equilibrium and may be left out.
"""

from __future__ import annotations

import math
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from loader_model.io.arrays import real_number
from loader_model.io.files import read_text
from loader_model.machines import MachineInfo
from loader_model.parameters.checks import MAX_ROD_TO_PISTON_RATIO
from loader_model.parameters.flat_entries import check_names, entry, schema_value
from loader_model.parameters.hydraulics import CylinderParameters, HydraulicParameters
from loader_model.parameters.tyres import tyre_table
from loader_model.parameters.valve import ValveParameters, valve_table

__all__ = [
    "HYDRAULIC_NAMES",
    "MachineParameters",
    "check_machine_model_values",
    "default_machine_parameters",
    "load_machine_parameters",
    "machine_model_values",
    "parse_machine_parameters",
    "resolve_machine_parameters",
]

#: The fields of :class:`HydraulicParameters` a machine file gives (the rest is the plant's).
HYDRAULIC_NAMES = ("bulk_modulus", "charge_pressure")
#: The fields of :class:`HydraulicParameters` a valve circuit's file gives.
VALVE_HYDRAULIC_NAMES = ("bulk_modulus",)
_SECTIONS = {"model", "cylinders", "hydraulics", "tyres", "valve", "loads"}


@dataclass(frozen=True)
class MachineParameters:
    """A checked parameter set of one described machine.

    Attributes
    ----------
    machine : str
        Name in :func:`loader_model.machines.list_machines`.
    model : dict
        Value of every generated model parameter (static loads 0 until the equilibrium).
    cylinders : CylinderParameters
        The driven lift cylinder group (count, bore, rod, stroke, lengths, dead volumes).
    hydraulics : dict
        ``bulk_modulus`` [Pa] and (pump circuit) ``charge_pressure`` [Pa].
    loads : dict
        Load case name -> the model values it replaces.
    sources : dict
        ``section.name`` -> source of every value.
    origin : str
        The file it was read from.
    tyres : dict
        Each axle's tyre road geometry by per-axle name (``R_A`` [m], ``ae_A``, ``be_A``,
        ``ce_A``, ``ls_A``; :mod:`loader_model.parameters.tyres`).
    valve : ValveParameters or None
        The valve circuit's values (``[valve]``); None for the pump circuit.
    """

    machine: str
    model: dict[str, float]
    cylinders: CylinderParameters
    hydraulics: dict[str, float]
    loads: dict[str, dict[str, float]]
    sources: dict[str, str] = field(repr=False, default_factory=dict)
    origin: str = ""
    tyres: dict[str, float] = field(default_factory=dict)
    valve: ValveParameters | None = None

    @property
    def rod_side_pressure(self) -> float:
        """Pressure [Pa gauge] of the rod side at rest: the charge pressure of the pump
        circuit, the tank pressure of a valve circuit."""
        if self.valve is not None:
            return self.valve.tank_pressure
        return self.hydraulics["charge_pressure"]


def _model_value(where: str, info: MachineInfo, name: str, raw: Any) -> tuple[float, str]:
    if name not in info.parameter_units:
        raise ValueError(
            f"{where}: {name}: not a parameter of machine {info.name!r}; allowed: "
            f"{', '.join(info.parameter_names)}"
        )
    value, source = entry(where, name, raw, info.parameter_units[name])
    value = real_number(f"{where}: {name}", value)
    low, high = info.parameter_ranges.get(name, (-math.inf, math.inf))
    if not (math.isfinite(value) and low <= value <= high) and name not in info.static_names:
        raise ValueError(
            f"{where}: {name} = {value!r} {info.parameter_units[name]} is out of range; "
            f"allowed: [{low:g}, {high:g}] (the description of {info.name!r})"
        )
    return value, source


def _section(where: str, raw: dict[str, Any], name: str) -> dict[str, Any]:
    table = raw.get(name)
    if not isinstance(table, dict):
        raise ValueError(f"{where}: missing table [{name}]")
    return table


def parse_machine_parameters(text: str, info: MachineInfo, origin: str) -> MachineParameters:
    """Check the text of a machine parameter file (see the module docstring) against ``info``."""
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{origin}: not valid TOML: {error}") from None
    unknown = sorted(set(raw) - _SECTIONS)
    if unknown:
        raise ValueError(f"{origin}: unknown tables {unknown}; allowed: {sorted(_SECTIONS)}")
    model_raw = _section(origin, raw, "model")
    names = set(info.parameter_names)
    check_names(f"{origin} [model]", model_raw, names - set(info.static_names), names)
    sources: dict[str, str] = {}
    model = {}
    for name in info.parameter_names:
        if name in model_raw:
            model[name], sources[f"model.{name}"] = _model_value(
                f"{origin} [model]", info, name, model_raw[name]
            )
        else:
            model[name] = 0.0
    cyl_raw = _section(origin, raw, "cylinders")
    fields = [f.name for f in CylinderParameters.__dataclass_fields__.values() if f.init]
    fields = [n for n in fields if n != "sources"]
    check_names(f"{origin} [cylinders]", cyl_raw, set(fields), set(fields))
    cyl = {}
    for name in fields:
        cyl[name], sources[f"cylinders.{name}"] = schema_value(
            f"{origin} [cylinders]", CylinderParameters, name, cyl_raw[name]
        )
    if cyl["rod_diameter"] >= MAX_ROD_TO_PISTON_RATIO * cyl["piston_diameter"]:
        raise ValueError(
            f"{origin} [cylinders]: rod_diameter {cyl['rod_diameter']!r} m must be below "
            f"{MAX_ROD_TO_PISTON_RATIO} x piston_diameter {cyl['piston_diameter']!r} m"
        )
    hyd_raw = _section(origin, raw, "hydraulics")
    valve = info.circuit == "valve"
    hyd_names = VALVE_HYDRAULIC_NAMES if valve else HYDRAULIC_NAMES
    check_names(f"{origin} [hydraulics]", hyd_raw, set(hyd_names), set(hyd_names))
    hydraulics = {}
    for name in hyd_names:
        hydraulics[name], sources[f"hydraulics.{name}"] = schema_value(
            f"{origin} [hydraulics]", HydraulicParameters, name, hyd_raw[name]
        )
    tyres = tyre_table(f"{origin} [tyres]", info, _section(origin, raw, "tyres"), sources)
    loads: dict[str, dict[str, float]] = {}
    for case, table in raw.get("loads", {}).items():
        where = f"{origin} [loads.{case}]"
        if not isinstance(table, dict):
            raise ValueError(f"{where}: must be a table of model values")
        check_names(where, table, set(), names - set(info.static_names))
        loads[case] = {}
        for name, item in table.items():
            loads[case][name], sources[f"loads.{case}.{name}"] = _model_value(
                where, info, name, item
            )
    _check_travel_limits(f"{origin} [model]", model)
    for case, table in loads.items():
        _check_travel_limits(f"{origin} [loads.{case}]", model | table)
    valve_values = valve_table(origin, raw, info, sources)
    return MachineParameters(
        info.name,
        model,
        CylinderParameters(**cyl),
        hydraulics,
        loads,
        sources,
        origin,
        tyres,
        valve_values,
    )


def load_machine_parameters(path: str | os.PathLike[str], info: MachineInfo) -> MachineParameters:
    """Read and check the parameter file ``path`` of machine ``info`` (every error names it)."""
    return parse_machine_parameters(read_text(path, "machine parameter file"), info, str(path))


def default_machine_parameters(info: MachineInfo) -> MachineParameters:
    """The shipped parameter set ``loader_model/data/machines/<name>.toml`` of a machine.

    Raises
    ------
    ValueError
        For the skid-steer (its parameters are the grouped files of
        :mod:`loader_model.parameters.sets`) or a machine without shipped values.
    """
    name = info.name
    if info.is_default:
        raise ValueError(
            f"machine {name!r} has grouped parameter files (loader_model.parameters.sets)"
        )
    path = resources.files("loader_model").joinpath("data", "machines", f"{name}.toml")
    if not path.is_file():
        raise ValueError(
            f"machine {name!r} has no shipped parameter file loader_model/data/machines/"
            f"{name}.toml; give one with --params"
        )
    return parse_machine_parameters(path.read_text(encoding="utf-8"), info, f"{name}.toml")


def resolve_machine_parameters(
    info: MachineInfo, params: MachineParameters | str | os.PathLike[str] | None
) -> MachineParameters:
    """A checked parameter set of machine ``info``: given, read from a path, or the shipped
    default."""
    if params is None:
        return default_machine_parameters(info)
    if isinstance(params, MachineParameters):
        if params.machine != info.name:
            raise ValueError(f"parameters of machine {params.machine!r} given for {info.name!r}")
        return params
    if isinstance(params, str | os.PathLike):
        return load_machine_parameters(Path(params), info)
    raise ValueError(f"params must be a MachineParameters, a path or None; got {params!r}")


def machine_model_values(params: MachineParameters, load: str | None = None) -> dict[str, float]:
    """The model values of ``params`` with the bucket load case ``load`` (None: as in [model]).

    Raises
    ------
    ValueError
        For a load case the file does not define (listing those it does).
    """
    values = dict(params.model)
    if load is not None:
        if load not in params.loads:
            raise ValueError(
                f"machine {params.machine!r}: unknown load case {load!r}; allowed: "
                f"{', '.join(params.loads) or 'none defined in ' + params.origin}"
            )
        values |= params.loads[load]
    return values


def check_machine_model_values(info: MachineInfo, values: Mapping[str, float]) -> None:
    """Raise ValueError for a model value of machine ``info`` outside its description's range.

    A static tyre load (``F_<axle>y0``), when given, must be compressive; the axles must be in
    the description's order, front first (the first axle ahead of the second); the travel limits
    of an end stop (``s_min_<element>``, ``s_max_<element>``) must hold p = 0 inside. Names without a
    range are not checked; ``g = 0`` is allowed (the analysis without gravity).
    """
    tyre_loads = {f"F_{axle}y0" for axle in info.axles}
    for name, value in values.items():
        if name in tyre_loads:
            if not value > 0.0:
                raise ValueError(
                    f"model parameter {name} = {value!r} is out of range; allowed: > 0 (an axle "
                    f"in contact carries a compressive load; machine {info.name!r} must stand on "
                    "every axle)"
                )
            continue
        if name in info.static_names or (name == "g" and value == 0.0):
            continue
        low, high = info.parameter_ranges.get(name, (-math.inf, math.inf))
        if not (math.isfinite(value) and low <= value <= high):
            raise ValueError(
                f"model parameter {name} = {value!r} is out of range; allowed: [{low:g}, "
                f"{high:g}] (the description of machine {info.name!r})"
            )
    front, rear = (f"{axle}_x" for axle in info.axles[:2])
    if front in values and rear in values and not values[front] > values[rear]:
        raise ValueError(
            f"model parameters {front} = {values[front]!r} and {rear} = {values[rear]!r}: the "
            f"front axle must be ahead of the rear axle ({front} > {rear})"
        )
    _check_travel_limits("model parameters", values)


def _check_travel_limits(where: str, values: Mapping[str, float]) -> None:
    """Refuse end stops (``s_min_<element>``, ``s_max_<element>``) that miss p = 0."""
    for low_name in (name for name in values if name.startswith("s_min_")):
        high_name = "s_max_" + low_name.removeprefix("s_min_")
        low, high = values[low_name], values.get(high_name, math.inf)
        if not low < 0.0 < high:
            raise ValueError(
                f"{where}: {low_name} = {low!r} m and {high_name} = {high!r} m: the end stops' "
                "travel limits must hold the static position inside (s_min < 0 < s_max, travel "
                "from p = 0)"
            )
