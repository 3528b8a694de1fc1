"""TOML form of the parameter sets: structure, unit and type checks, and a small exact writer.

Every value is an inline table with its SI unit and a one-line source or reason::

    [chassis]
    mass = { value = 2700.0, unit = "kg", source = "..." }

Sections are TOML tables named after the dataclass fields (``[tyres.front]``). Reading checks
unknown keys (suggesting the closest valid key), missing keys, the unit string (must equal the
field's SI unit, no conversion), the value type and finiteness. A leaf whose field has a default
(a setting added after files were written with it) may be left out and takes that default.
Range and consistency checks are done afterwards by
:func:`loader_model.parameters.sets.validate`. Floats are written with ``repr``, which
:mod:`tomllib` reads back bit for bit, so load -> save -> load is exact.

The writer is hand-written on purpose: tomli-w (the usual TOML writer) writes every mapping as a
``[table]`` section, so each one-line ``{ value, unit, source }`` leaf would become a four-line
table and the files would lose the layout that makes them readable.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
import json
import math
import typing
from collections.abc import Iterator, Mapping
from typing import Any

from loader_model.io.arrays import real_integer, real_number

__all__ = ["build", "dumps", "iter_leaves", "leaf_metadata", "section_types", "to_raw"]

_LEAF_KEYS = ("value", "unit", "source")
_NO_SOURCE = "no source given (object built in code)"


@functools.cache
def section_types(cls: type) -> dict[str, type]:
    """Map each field of dataclass ``cls`` that is itself a parameter dataclass to its type."""
    hints = typing.get_type_hints(cls)
    return {
        f.name: hints[f.name]
        for f in dataclasses.fields(cls)
        if "unit" not in f.metadata and "sources" not in f.metadata
    }


def leaf_metadata(cls: type, name: str) -> Mapping[str, Any]:
    """Metadata (unit, allowed range, shape, integer) of leaf field ``name`` of ``cls``."""
    return cls.__dataclass_fields__[name].metadata


def _schema_keys(cls: type) -> list[str]:
    return [f.name for f in dataclasses.fields(cls) if "sources" not in f.metadata]


def _optional_keys(cls: type) -> frozenset[str]:
    """Leaves with a default: a file written before they existed may leave them out."""
    return frozenset(
        f.name
        for f in dataclasses.fields(cls)
        if "unit" in f.metadata and f.default is not dataclasses.MISSING
    )


def iter_leaves(cls: type, prefix: str = "") -> Iterator[tuple[str, type, str]]:
    """Yield ``(dotted path, owning dataclass, field name)`` of every leaf in schema order."""
    sections = section_types(cls)
    for name in _schema_keys(cls):
        path = f"{prefix}{name}"
        if name in sections:
            yield from iter_leaves(sections[name], f"{path}.")
        else:
            yield path, cls, name


def _check_keys(
    data: Mapping[str, Any], allowed: list[str], where: str, optional: frozenset[str] = frozenset()
) -> None:
    """Reject unknown keys (with the closest valid key) and report missing ones.

    Keys in ``optional`` may be missing."""
    for key in data:
        if key not in allowed:
            close = difflib.get_close_matches(key, allowed, n=1, cutoff=0.5)
            hint = f"; did you mean {close[0]!r}?" if close else f"; valid keys: {allowed}"
            raise ValueError(f"{where}{key}: unknown key{hint}")
    for key in allowed:
        if key not in data and key not in optional:
            raise ValueError(f"{where}{key}: missing key")


def _number(raw: Any, path: str, integer: bool) -> float | int:
    """One number of a leaf: :func:`loader_model.io.arrays.real_integer` or a finite
    :func:`loader_model.io.arrays.real_number` (a TOML array, a boolean or a string is refused)."""
    if integer:
        return real_integer(path, raw)
    value = real_number(path, raw)
    if not math.isfinite(value):
        raise ValueError(f"{path}: value {value!r} is not finite; allowed: a finite number")
    return value


def _leaf(cls: type, name: str, raw: Any, path: str) -> tuple[Any, str]:
    """Check one ``{ value, unit, source }`` table; return the typed value and the source."""
    meta = leaf_metadata(cls, name)
    if not isinstance(raw, Mapping):
        raise ValueError(
            f"{path}: expected a table {{ value = ..., unit = {meta['unit']!r}, source = ... }}, "
            f"got {raw!r}"
        )
    _check_keys(raw, list(_LEAF_KEYS), f"{path}.")
    unit, source = raw["unit"], raw["source"]
    if unit != meta["unit"]:
        raise ValueError(
            f"{path}: unit {unit!r} is not allowed; the allowed unit is {meta['unit']!r} "
            "(values are SI, no conversion)"
        )
    if not isinstance(source, str) or not source.strip():
        raise ValueError(f"{path}.source: expected a non-empty string, got {source!r}")
    value = raw["value"]
    shape = meta["shape"]
    if shape == 0:
        return _number(value, path, meta["integer"]), source
    if not isinstance(value, list) or len(value) != shape:
        raise ValueError(f"{path}: value {value!r} is not a list of {shape} numbers")
    return tuple(_number(v, f"{path}[{i}]", False) for i, v in enumerate(value)), source


def _build(cls: type, data: Any, prefix: str, sources: list[tuple[str, str]]) -> Any:
    if not isinstance(data, Mapping):
        raise ValueError(f"{prefix.rstrip('.')}: expected a table, got {data!r}")
    sections = section_types(cls)
    _check_keys(data, _schema_keys(cls), prefix, _optional_keys(cls))
    kwargs: dict[str, Any] = {}
    for name in _schema_keys(cls):
        if name not in data:  # an optional leaf left out: its default, without a source
            continue
        if name in sections:
            kwargs[name] = _build(sections[name], data[name], f"{prefix}{name}.", sources)
        else:
            kwargs[name], source = _leaf(cls, name, data[name], f"{prefix}{name}")
            sources.append((f"{prefix}{name}", source))
    return kwargs


def build(cls: type, data: Mapping[str, Any]) -> Any:
    """Build the top-level parameter dataclass ``cls`` from parsed TOML ``data``.

    Nothing is mutated: keyword arguments are collected for the whole tree first, and the
    objects are constructed only when every leaf passed its checks.
    """
    sources: list[tuple[str, str]] = []
    kwargs = _build(cls, data, "", sources)
    return _construct(cls, kwargs, tuple(sources))


def _construct(cls: type, kwargs: dict[str, Any], sources: tuple[tuple[str, str], ...]) -> Any:
    sections = section_types(cls)
    args = {
        name: _construct(sections[name], value, ()) if name in sections else value
        for name, value in kwargs.items()
    }
    if any("sources" in f.metadata for f in dataclasses.fields(cls)):
        args["sources"] = sources
    return cls(**args)


def to_raw(obj: Any) -> dict[str, Any]:
    """Nested dict in the TOML form (``{value, unit, source}`` leaves) of a parameter object."""
    sources = dict(obj.sources)

    def walk(node: Any, prefix: str) -> dict[str, Any]:
        cls = type(node)
        sections = section_types(cls)
        out: dict[str, Any] = {}
        for name in _schema_keys(cls):
            value = getattr(node, name)
            path = f"{prefix}{name}"
            if name in sections:
                out[name] = walk(value, f"{path}.")
            else:
                unit = leaf_metadata(cls, name)["unit"]
                plain = list(value) if isinstance(value, tuple) else value
                out[name] = {"value": plain, "unit": unit, "source": sources.get(path, _NO_SOURCE)}
        return out

    return walk(obj, "")


def _format_value(value: Any) -> str:
    if isinstance(value, list):
        return "[" + ", ".join(_format_value(v) for v in value) + "]"
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise TypeError(f"cannot write {value!r} as a TOML number")
    return repr(value)


def _string(text: str) -> str:
    """TOML basic string: JSON escapes, plus DEL, which TOML (unlike JSON) forbids raw."""
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def _is_leaf(node: Any) -> bool:
    return isinstance(node, Mapping) and set(node) == set(_LEAF_KEYS)


def dumps(raw: Mapping[str, Any], header: str = "") -> str:
    """Write nested TOML-form data: leaves as one-line inline tables, sections as ``[a.b]``.

    Strings are written as JSON strings (whose escapes are all valid TOML escapes), with DEL escaped.
    """
    lines: list[str] = []

    def emit(node: Mapping[str, Any], table: str) -> None:
        leaves = [(k, v) for k, v in node.items() if _is_leaf(v)]
        if leaves and table:
            lines.extend(["", f"[{table}]"])
        for key, leaf in leaves:
            value = _format_value(leaf["value"])
            unit, source = _string(leaf["unit"]), _string(leaf["source"])
            lines.append(f"{key} = {{ value = {value}, unit = {unit}, source = {source} }}")
        for key, sub in node.items():
            if not _is_leaf(sub):
                emit(sub, f"{table}.{key}" if table else key)

    emit(raw, "")
    head = [f"# {line}".rstrip() for line in header.splitlines()]
    body = lines[1:] if lines and lines[0] == "" else lines
    return "\n".join([*head, "", *body] if head else body) + "\n"
