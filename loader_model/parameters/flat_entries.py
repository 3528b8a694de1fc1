"""The entries of a flat parameter table: ``name = { value = <SI number>, unit = ..., source = ... }``.

Shared by the machines' flat parameter files (:mod:`loader_model.parameters.machine_files`) and
the tables that carry a component's own values in them (:mod:`loader_model.parameters.valve`):
each entry states its value, its unit (the one expected) and its source; a table names exactly
the entries it must and may hold.
"""

from __future__ import annotations

import math
from typing import Any

from loader_model.io.arrays import real_integer, real_number

__all__ = ["check_names", "entry", "schema_value"]


def entry(where: str, name: str, raw: Any, unit: str) -> tuple[Any, str]:
    """(value, source) of entry ``name`` of a table at ``where``, its unit checked."""
    if not isinstance(raw, dict) or set(raw) != {"value", "unit", "source"}:
        raise ValueError(
            f'{where}: {name}: must be {{ value = <number>, unit = {unit!r}, source = "..." }}'
            f"; got {raw!r}"
        )
    if raw["unit"] != unit:
        raise ValueError(f"{where}: {name}: unit {raw['unit']!r}; expected {unit!r}")
    if not isinstance(raw["source"], str) or not raw["source"].strip():
        raise ValueError(f"{where}: {name}: needs a source (where the value comes from)")
    return raw["value"], raw["source"]


def schema_value(where: str, cls: type, name: str, raw: Any) -> tuple[Any, str]:
    """(value, source) of entry ``name`` for field ``name`` of the dataclass ``cls``: its unit,
    integer-ness and allowed range from the field's metadata."""
    meta = cls.__dataclass_fields__[name].metadata
    value, source = entry(where, name, raw, meta["unit"])
    label = f"{where}: {name}"
    value = real_integer(label, value) if meta["integer"] else real_number(label, value)
    if not (math.isfinite(value) and meta["allowed"].contains(value)):
        raise ValueError(
            f"{label} = {value!r} {meta['unit']} is out of range; allowed: "
            f"{meta['allowed'].describe()}"
        )
    return value, source


def check_names(where: str, table: dict[str, Any], required: set[str], allowed: set[str]) -> None:
    """Refuse a table at ``where`` that lacks a ``required`` entry or holds one not ``allowed``."""
    missing = sorted(required - set(table))
    if missing:
        raise ValueError(f"{where}: missing {', '.join(missing)}")
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise ValueError(
            f"{where}: unknown {', '.join(unknown)}; allowed: {', '.join(sorted(allowed))}"
        )
