"""The keys of a machine description: which each table takes and needs, and a misspelt one named.

A key that a table does not take is reported as found, with the key it was probably meant to be
(the closest in spelling, :func:`closest`), the keys still missing and those allowed
(:func:`unknown_key`); a parameter name likewise, with every missing parameter and its unit and
the static loads the derivation lists itself (:func:`parameter_names_problem`). The functions
return the message; the callers raise it as a :class:`~derive.description_checks.
DescriptionError` naming the entry. Standard library only.
"""

from __future__ import annotations

import difflib
from collections.abc import Collection, Iterable, Mapping

__all__ = [
    "CIRCUIT_KINDS",
    "CIRCUIT_SUPPLIES",
    "JOINTS",
    "KEYS",
    "REQUIRED",
    "closest",
    "parameter_names_problem",
    "unknown_key",
]

#: The joints of a body.
JOINTS = ("free", "pin", "slider", "two_mounts")
#: The keys each table of a description takes: the top level, [machine], a body by its joint,
#: an axle, an actuator, a sensor and a parameter.
KEYS: dict[str, frozenset[str]] = {
    "": frozenset(
        {"machine", "bodies", "axles", "actuators", "sensors", "parameters", "tyres", "circuit"}
    ),
    "machine": frozenset({"name", "title", "point_range"}),
    "free": frozenset({"joint", "label", "reference", "coordinates", "mass", "inertia", "points"}),
    "pin": frozenset(
        {"joint", "label", "parent", "at", "coordinate", "joint_angle", "mass", "inertia"}
        | {"centre_of_gravity", "points"}
    ),
    # sliding and two-point mounts (end stops, a slider's extension): derive/elements.py
    "slider": frozenset(
        {"joint", "label", "parent", "at", "direction", "coordinate", "mass", "inertia"}
        | {"centre_of_gravity", "points", "end_stops", "extension"}
    ),
    "two_mounts": frozenset(
        {"joint", "label", "parent", "at", "direction", "coordinates", "mounts", "mass"}
        | {"inertia", "centre_of_gravity", "points", "end_stops"}
    ),
    "axle": frozenset({"point", "label"}),
    "actuator": frozenset({"kind", "base", "rod"}),
    "sensor": frozenset({"axes", "label"}),
    "parameter": frozenset({"unit", "description", "range", "source"}),
    "tyre": frozenset({"unit", "description", "range", "source"}),
}
#: The keys of :data:`KEYS` that each table must have (as derive/machine.schema.json).
REQUIRED: dict[str, frozenset[str]] = {
    "": frozenset({"machine", "bodies", "axles", "actuators", "parameters", "tyres"}),
    "machine": frozenset({"name", "title"}),
    "free": frozenset({"joint", "reference", "coordinates", "mass", "inertia", "points"}),
    "pin": frozenset(
        {"joint", "parent", "at", "coordinate", "mass", "inertia", "centre_of_gravity", "points"}
    ),
    "slider": frozenset(
        {"joint", "parent", "at", "direction", "coordinate", "mass", "inertia"}
        | {"centre_of_gravity", "points"}
    ),
    "two_mounts": frozenset(
        {"joint", "parent", "at", "direction", "coordinates", "mounts", "mass", "inertia"}
        | {"centre_of_gravity", "points"}
    ),
    "axle": frozenset({"point"}),
    "actuator": frozenset({"kind", "base", "rod"}),
    "sensor": frozenset({"axes"}),
    "parameter": frozenset({"unit", "description"}),
    "tyre": frozenset({"unit", "description", "range", "source"}),
}

# -- the lift circuit ([circuit], optional; absent: the pump of the paper) --
#: The kinds of lift circuit: the paper's closed-circuit displacement-controlled pump, or a
#: proportional directional valve in an open circuit.
CIRCUIT_KINDS = ("pump", "valve")
#: What feeds a valve circuit: a load-sensing pump or a constant-pressure source.
CIRCUIT_SUPPLIES = ("load_sensing", "constant_pressure")
KEYS["circuit"] = frozenset({"kind", "supply"})
REQUIRED["circuit"] = frozenset({"kind"})


def _shown(value: object, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def closest(word: str, choices: Iterable[str]) -> str | None:
    """The choice nearest to ``word`` in spelling (a misspelt key's intended one), or None."""
    found = difflib.get_close_matches(word, sorted(choices), n=1, cutoff=0.6)
    return found[0] if found else None


def unknown_key(key: str, missing: Iterable[str], allowed: Iterable[str]) -> str:
    """The message for a key ``key`` a table does not take: the key found, the closest of the
    ``missing`` keys (else of the ``allowed``), the keys still missing and those allowed."""
    missing, allowed = sorted(missing), sorted(allowed)
    guess = closest(key, missing) or closest(key, allowed)
    text = f"unknown key {_shown(key)}"
    if guess:
        text += f" (did you mean {guess!r}?)"
    if missing:
        text += f"; missing: {', '.join(missing)}"
    return text + f"; allowed: {', '.join(allowed)}"


def parameter_names_problem(
    declared: Collection[str],
    structure: Iterable[tuple[str, str]],
    points: Collection[str],
    loads: Mapping[str, str],
) -> str | None:
    """What is wrong with the names of ``[parameters]``, or None.

    Parameters
    ----------
    declared : collection of str
        The names the description's ``[parameters]`` declares.
    structure : iterable of (str, str)
        (name, unit) of the machine's parameter vector
        (:func:`derive.description.structural_parameters`).
    points : collection of str
        The names of ``structure`` that are point coordinates (described by their body).
    loads : mapping of str to str
        The static loads the derivation lists (:func:`derive.description.static_load_parameters`):
        they may be left out.

    Returns
    -------
    str or None
        The first unknown name (with the closest name not yet declared, the missing ones and
        the allowed ones), else every missing name with its unit, else None.
    """
    structure = list(structure)
    names = [name for name, _ in structure if name not in points]
    missing = [
        f"{name} [{unit}]"
        for name, unit in structure
        if name not in declared and name not in points and name not in loads
    ]
    computed = f"the static loads {', '.join(loads)} may be left out (computed at rest)"
    for name in declared:
        if name not in names and name not in points:
            left = [n for n in names if n not in declared]
            guess = closest(name, left) or closest(name, names)
            text = f"unknown parameter {_shown(name)}"
            if guess:
                text += f" (did you mean {guess!r}?)"
            if missing:
                text += f"; missing: {', '.join(missing)}"
            return text + (
                f"; allowed: {', '.join(names)}, and <point>_x, <point>_y of each point "
                f"(described by its body); {computed}"
            )
    if missing:
        return (
            f"missing {', '.join(missing)}: give each as {{ unit, description, range, source }}; "
            f"{computed}"
        )
    return None
