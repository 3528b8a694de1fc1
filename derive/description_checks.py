"""Read a machine description safely and check the type of every entry before it is built.

:func:`read_description` refuses a file that is not a small UTF-8 TOML document (binary, UTF-16,
too large, nested too deeply, a duplicate key) and :func:`check_entries` every entry of the wrong
type or value: names that are not Python identifiers (a body, point, coordinate, parameter or the
machine itself), numbers that are not finite, ranges that are reversed, ``coordinates`` given as a
string, a coordinate or parameter name used twice, a sensor axis other than ``x`` and ``y``, a
``[tyres]`` entry without its unit, description, range or source, a joint that does not exist, a
two-point mount without exactly two different mount points, ``end_stops`` other than true or
false. A key that a table does not take (a misspelt one) is named before anything is read from
the table, with the closest allowed key, the keys still missing and the keys allowed
(:mod:`derive.description_keys`). Each raises :class:`~derive.description.DescriptionError`
naming the entry, the value and what is allowed, so that nothing is derived from a description
that cannot be built. Standard library only.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import Any

from derive.description_keys import (
    CIRCUIT_KINDS,
    CIRCUIT_SUPPLIES,
    JOINTS,
    KEYS,
    REQUIRED,
    unknown_key,
)

__all__ = ["MAX_BYTES", "DescriptionError", "check_entries", "read_description", "shown"]

#: Largest description file read (the shipped ones are 6-8 kB).
MAX_BYTES = 1_000_000
_AXES = ("x", "y")
_KINDS = ("driven", "locked")


class DescriptionError(ValueError):
    """A machine description that cannot be built; the message names the entry."""

    def __init__(self, where: str, entry: str, message: str) -> None:
        super().__init__(f"{where}: {entry}: {message}")
        self.entry = entry


def shown(value: Any, limit: int = 60) -> str:
    """``repr(value)`` cut to ``limit`` characters, for error messages."""
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def read_description(path: Path) -> dict[str, Any]:
    """The parsed TOML of the description file ``path``.

    Raises
    ------
    DescriptionError
        For a file that cannot be read, is larger than :data:`MAX_BYTES`, is not UTF-8 text or
        not TOML (a duplicate key, a syntax error, nesting deeper than the parser reads).
    """
    where, entry = path.name, "(file)"
    try:
        data = path.read_bytes()
    except OSError as error:
        raise DescriptionError(where, entry, f"cannot be read ({error.strerror})") from None
    if len(data) > MAX_BYTES:
        raise DescriptionError(
            where, entry, f"{len(data)} bytes; a description has at most {MAX_BYTES} bytes"
        )
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise DescriptionError(
            where,
            entry,
            f"not UTF-8 text (byte {error.start} is {data[error.start : error.start + 1]!r}); "
            "save the description as UTF-8",
        ) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise DescriptionError(where, entry, f"not valid TOML: {error}") from None
    except RecursionError:
        raise DescriptionError(where, entry, "nested too deeply to be a description") from None


class _Checker:
    """Type checks of the raw entries of one description, raising on the first bad one."""

    def __init__(self, where: str) -> None:
        self.where = where

    def fail(self, entry: str, value: Any, allowed: str) -> None:
        raise DescriptionError(self.where, entry, f"{shown(value)} is not allowed; {allowed}")

    def keys(self, entry: str, table: Any, kind: str) -> None:
        """Refuse a key of ``table`` that a table of ``kind`` (:data:`KEYS`) does not take."""
        if not isinstance(table, dict):
            return  # the table check names it
        allowed, required = KEYS[kind], REQUIRED[kind]
        for key in table:
            if key not in allowed:
                missing = required - table.keys()
                raise DescriptionError(
                    self.where, entry or "(top level)", unknown_key(key, missing, allowed)
                )

    def body_keys(self, entry: str, table: Any) -> None:
        """:meth:`keys` of a body: those of its joint, or any body's while the joint is unknown."""
        if not isinstance(table, dict):
            return
        joint = table.get("joint")
        if joint in JOINTS:
            self.keys(entry, table, joint)
            return
        allowed = frozenset().union(*(KEYS[kind] for kind in JOINTS))
        for key in table:
            if key not in allowed:
                missing = {"joint"} - table.keys()
                raise DescriptionError(self.where, entry, unknown_key(key, missing, allowed))

    def name(self, entry: str, value: Any) -> str:
        if not (isinstance(value, str) and value.isascii() and value.isidentifier()):
            self.fail(
                entry, value, "give a name: letters, digits and underscores, not a digit first"
            )
        return value

    def text(self, entry: str, value: Any) -> None:
        if not isinstance(value, str):
            self.fail(entry, value, "give a text (a quoted string)")

    def table(self, entry: str, value: Any) -> dict[str, Any]:
        if not isinstance(value, dict):
            self.fail(entry, value, "give a table")
        for key in value:
            self.name(f"{entry}.{key}" if entry else key, key)
        return value

    def numbers(self, entry: str, value: Any, count: int) -> list[float]:
        ok = isinstance(value, list) and len(value) == count
        ok = ok and all(isinstance(v, int | float) and not isinstance(v, bool) for v in value)
        if not ok or not all(math.isfinite(v) for v in value):
            self.fail(entry, value, f"give {count} finite numbers, [{', '.join(['...'] * count)}]")
        return value

    def range(self, entry: str, value: Any) -> None:
        low, high = self.numbers(entry, value, 2)
        if not low < high:
            self.fail(entry, value, "give [low, high] with low < high")


def _check_mounts(check: _Checker, entry: str, body: dict[str, Any]) -> None:
    """The keys of sliding and two-point mounts: ``end_stops`` and ``mounts``."""
    if "end_stops" in body and not isinstance(body["end_stops"], bool):
        check.fail(f"{entry}.end_stops", body["end_stops"], "give true or false")
    if "mounts" in body:
        value = body["mounts"]
        if not isinstance(value, list) or len(value) != 2:
            check.fail(f"{entry}.mounts", value, 'give the 2 mount points ["front", "rear"]')
        for index, item in enumerate(value):
            check.name(f"{entry}.mounts[{index}]", item)
        if value[0] == value[1]:
            check.fail(f"{entry}.mounts", value, "give two different points")


def _check_body(check: _Checker, name: str, raw: Any, names: dict[str, str]) -> None:
    entry = f"bodies.{name}"
    check.body_keys(entry, raw)
    body = check.table(entry, raw)
    if "joint" in body and body["joint"] not in JOINTS:
        check.fail(f"{entry}.joint", body["joint"], f"allowed: {', '.join(JOINTS)}")
    mounted = body.get("joint") == "two_mounts"
    for key in ("parent", "at", "reference", "mass", "inertia", "centre_of_gravity"):
        if key in body:
            check.name(f"{entry}.{key}", body[key])
    if "label" in body:
        check.text(f"{entry}.label", body["label"])
    if "points" in body:
        for point, text in check.table(f"{entry}.points", body["points"]).items():
            check.text(f"{entry}.points.{point}", text)
    if "direction" in body:
        direction = check.numbers(f"{entry}.direction", body["direction"], 2)
        if direction[0] == direction[1] == 0:
            check.fail(f"{entry}.direction", direction, "give a direction that is not [0, 0]")
    coordinates: list[tuple[str, Any]] = []
    if "coordinates" in body:
        value = body["coordinates"]
        count, shape = (2, '["bounce", "pitch"]') if mounted else (3, '["x", "y", "angle"]')
        if not isinstance(value, list) or len(value) != count:
            check.fail(f"{entry}.coordinates", value, f"give a list of {count} names {shape}")
        coordinates += [(f"{entry}.coordinates[{i}]", item) for i, item in enumerate(value)]
    _check_mounts(check, entry, body)
    for key in ("coordinate", "joint_angle", "mass", "inertia", "extension"):
        if key in body:
            coordinates.append((f"{entry}.{key}", body[key]))
    for where, value in coordinates:
        check.name(where, value)
        if value in names:
            check.fail(where, value, f"a name used once only (also {names[value]})")
        names[value] = where


def check_entries(where: str, raw: dict[str, Any]) -> None:
    """Check the type and value of every entry of a parsed description (module notes).

    Keys and the structure between entries (parents, points on bodies, the parameter list) are
    checked by :func:`derive.description.load_machine` after this.

    Raises
    ------
    DescriptionError
        Naming the first bad entry, its value and what is allowed.
    """
    check = _Checker(where)
    check.keys("", raw, "")
    head = raw.get("machine")
    check.keys("machine", head, "machine")
    if isinstance(head, dict):
        if "name" in head:
            check.name("machine.name", head["name"])
        if "title" in head:
            check.text("machine.title", head["title"])
        if "point_range" in head:
            check.range("machine.point_range", head["point_range"])
    names: dict[str, str] = {}
    for name, body in check.table("bodies", raw.get("bodies", {})).items():
        _check_body(check, name, body, names)
    axles = raw.get("axles", [])
    if not isinstance(axles, list):
        check.fail("axles", axles, "give [[axles]] tables, one per axle")
    for index, axle in enumerate(axles):
        check.keys(f"axles[{index}]", axle, "axle")
        item = check.table(f"axles[{index}]", axle)
        check.name(f"axles[{index}].point", item.get("point"))
        if "label" in item:
            check.text(f"axles[{index}].label", item["label"])
    for name, item in check.table("actuators", raw.get("actuators", {})).items():
        check.keys(f"actuators.{name}", item, "actuator")
        item = check.table(f"actuators.{name}", item)
        if item.get("kind") not in _KINDS:
            check.fail(f"actuators.{name}.kind", item.get("kind"), f"allowed: {', '.join(_KINDS)}")
        for key in ("base", "rod"):
            check.name(f"actuators.{name}.{key}", item.get(key))
    for point, item in check.table("sensors", raw.get("sensors", {})).items():
        check.keys(f"sensors.{point}", item, "sensor")
        item = check.table(f"sensors.{point}", item)
        axes = item.get("axes")
        if not (
            isinstance(axes, list)
            and axes
            and all(isinstance(axis, str) and axis in _AXES for axis in axes)
            and len(set(axes)) == len(axes)
        ):
            check.fail(f"sensors.{point}.axes", axes, 'give one or both of "x", "y", once each')
        if "label" in item:
            check.text(f"sensors.{point}.label", item["label"])
    if "circuit" in raw:
        _check_circuit(check, raw["circuit"])
    for table, kind in (("parameters", "parameter"), ("tyres", "tyre")):
        for name, item in check.table(table, raw.get(table, {})).items():
            check.keys(f"{table}.{name}", item, kind)
            item = check.table(f"{table}.{name}", item)
            for key in sorted(REQUIRED[kind] - item.keys()) if kind == "tyre" else ():
                raise DescriptionError(where, f"{table}.{name}.{key}", "missing")
            for key in ("unit", "description", "source"):
                if key in item:
                    check.text(f"{table}.{name}.{key}", item[key])
            if "range" in item:
                check.range(f"{table}.{name}.range", item["range"])


def _check_circuit(check: _Checker, raw: Any) -> None:
    """``[circuit]``: ``kind`` one of :data:`CIRCUIT_KINDS`; ``supply`` (a valve's only) one of
    :data:`CIRCUIT_SUPPLIES`."""
    check.keys("circuit", raw, "circuit")
    item = check.table("circuit", raw)
    kind = item.get("kind")
    if kind not in CIRCUIT_KINDS:
        check.fail("circuit.kind", kind, f"allowed: {', '.join(map(repr, CIRCUIT_KINDS))}")
    if "supply" in item:
        if kind != "valve":
            check.fail("circuit.supply", item["supply"], "a supply is given for kind 'valve' only")
        if item["supply"] not in CIRCUIT_SUPPLIES:
            check.fail(
                "circuit.supply",
                item["supply"],
                f"allowed: {', '.join(map(repr, CIRCUIT_SUPPLIES))}",
            )


def table_entry(where: str, entry: str, value: Any, allowed: set[str]) -> dict[str, Any]:
    """``value`` as a table whose keys are all in ``allowed``, or DescriptionError naming ``entry``."""
    if not isinstance(value, dict):
        raise DescriptionError(where, entry, "expected a table")
    for key in value:
        if key not in allowed:
            raise DescriptionError(
                where, entry, f"unknown key {key!r} (allowed: {', '.join(sorted(allowed))})"
            )
    return value


def required_entry(where: str, entry: str, table: dict[str, Any], key: str) -> Any:
    """``table[key]``, or DescriptionError naming ``entry.key`` as missing."""
    if key not in table:
        raise DescriptionError(where, f"{entry}.{key}", "missing")
    return table[key]
