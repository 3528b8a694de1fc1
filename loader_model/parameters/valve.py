"""Parameter set of a valve-controlled lift circuit (guide page "Hydraulics", "Valve circuit").

A machine whose description has ``[circuit] kind = "valve"`` gives these values in the ``[valve]``
table of its parameter file (:mod:`loader_model.parameters.machine_files`). Units follow the SI
rule of :mod:`loader_model.parameters.schema`; the spool is in m (its stroke is the command's
saturation, as the pump's maximum displacement is the pump's). Re-exported by
:mod:`loader_model.parameters.hydraulics` with the drive's other parameter sets.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from loader_model.parameters.fields import Range, TypedLeaves, integer, si
from loader_model.parameters.flat_entries import check_names, schema_value

if TYPE_CHECKING:
    from loader_model.machines import MachineInfo

__all__ = ["ValveParameters", "valve_table"]

_CONDUCTANCE = Range(0.0, 1e-11, reason="a leak-free spool (0) to 6 l/min per 100 bar")


@dataclass(frozen=True)
class ValveParameters(TypedLeaves):
    """Proportional directional valve, pressure compensator and supply (Merritt ch. 3, 5).

    Attributes
    ----------
    spool_stroke : float
        Spool stroke x_s,max in m: the saturation of the spool and of its command.
    area_gradient : float
        Area gradient w of each metering edge in m (area per unit opening, Merritt ch. 3).
    overlap : float
        Overlap x_0 of each metering edge in m (0: critically lapped).
    discharge_coefficient : float
        C_d of the metering edges (Merritt: 0.61 for a sharp edge).
    compensator_setting : float
        Pressure drop Δp_c in Pa that the individual compensator holds across a meter-in edge.
    compensated : int
        1: the meter-in edges are pressure compensated; 0: plain orifices.
    natural_frequency : float
        Natural frequency of the spool position loop in Hz.
    damping_ratio : float
        Damping ratio of the spool position loop.
    stroke_rate_limit : float
        Spool rate limit in m/s.
    leakage_conductance : float
        Leakage of each work port to the tank line across the spool, m³/(s·Pa).
    tank_pressure : float
        Tank line pressure in Pa (gauge).
    supply_max_pressure : float
        Maximum pressure of the supply in Pa (gauge): the load-sensing pump's limit, or the
        constant-pressure source's setting.
    load_sensing_margin : float
        Δp_LS in Pa: the load-sensing pump's outlet above the highest load pressure.
    supply_max_flow : float
        Flow limit of the supply in m³/s.
    """

    spool_stroke: float = field(
        metadata=si("m", Range(5e-4, 0.02, reason="spool strokes of 0.5-20 mm"))
    )
    area_gradient: float = field(
        metadata=si(
            "m", Range(1e-4, 0.2, reason="edges of 0.1 mm (notched) to a full 64 mm spool's 0.2 m")
        )
    )
    overlap: float = field(
        metadata=si("m", Range(0.0, 0.005, reason="critically lapped (0) to 5 mm of overlap"))
    )
    discharge_coefficient: float = field(
        metadata=si("-", Range(0.1, 1.0, reason="0.1 (long laminar passage) to 1 (ideal nozzle)"))
    )
    compensator_setting: float = field(
        metadata=si("Pa", Range(2e5, 5e6, reason="compensator springs of 2-50 bar"))
    )
    compensated: int = field(
        metadata=integer(Range(0, 1, reason="1: pressure compensated; 0: plain orifices"))
    )
    natural_frequency: float = field(
        metadata=si("Hz", Range(0.5, 500.0, reason="spool loops of 0.5 Hz to servo valves' 500 Hz"))
    )
    damping_ratio: float = field(
        metadata=si("-", Range(0.05, 5.0, reason="a loop that settles: 0.05 to overdamped 5"))
    )
    stroke_rate_limit: float = field(
        metadata=si("m/s", Range(1e-3, 10.0, reason="a full stroke in 1 ms to 20 s"))
    )
    leakage_conductance: float = field(metadata=si("m^3/(s Pa)", _CONDUCTANCE))
    tank_pressure: float = field(
        metadata=si("Pa", Range(0.0, 1e6, reason="tank line back pressures of 0-10 bar"))
    )
    supply_max_pressure: float = field(
        metadata=si("Pa", Range(5e6, 5e7, reason="pumps of mobile machines, 50-500 bar"))
    )
    load_sensing_margin: float = field(
        metadata=si("Pa", Range(5e5, 5e6, reason="load-sensing margins of 5-50 bar"))
    )
    supply_max_flow: float = field(metadata=si("m^3/s", Range(1e-5, 0.02, reason="0.6-1200 l/min")))

    @property
    def natural_frequency_rad_s(self) -> float:
        """Spool loop's natural frequency in rad/s (2π times :attr:`natural_frequency`)."""
        return 2.0 * math.pi * self.natural_frequency


def valve_table(
    origin: str, raw: dict[str, Any], info: MachineInfo, sources: dict[str, str]
) -> ValveParameters | None:
    """The checked ``[valve]`` table of a machine parameter file's parsed ``raw`` (module
    notes): required for a valve circuit, refused for a pump's; ``sources`` gains the sources.

    Raises
    ------
    ValueError
        Naming the file, the entry, the value and what is allowed.
    """

    if info.circuit != "valve":
        if "valve" in raw:
            raise ValueError(
                f"{origin}: [valve] is given, but machine {info.name!r} has the circuit kind "
                f"{info.circuit!r}; allowed: [valve] for a description with [circuit] kind = "
                '"valve" only'
            )
        return None
    where = f"{origin} [valve]"
    if not isinstance(raw.get("valve"), dict):
        raise ValueError(
            f"{origin}: missing table [valve] (machine {info.name!r} has [circuit] kind = "
            '"valve"; give the fields of ValveParameters, guide page "Machines")'
        )
    fields = [f.name for f in ValveParameters.__dataclass_fields__.values() if f.init]
    fields = [n for n in fields if n != "sources"]
    check_names(where, raw["valve"], set(fields), set(fields))
    values = {}
    for name in fields:
        values[name], sources[f"valve.{name}"] = schema_value(
            where, ValveParameters, name, raw["valve"][name]
        )
    return ValveParameters(**values)
