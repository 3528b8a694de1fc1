"""The ``[tyres]`` table of a machine description: each axle's tyre road geometry.

Each axle X states its tyres' free (unloaded) radius ``R_X`` [m] and the shape of Schmeitz's
tandem elliptical cam (A. J. C. Schmeitz, H. B. Pacejka, I. J. M. Besselink, Vehicle System
Dynamics 41(5), 2004; H. B. Pacejka, Tire and Vehicle Dynamics, 3rd ed., 2012, section 10.2) in
units of R, as MF-Swift tyre property files state it: ``ae_X`` = a_e / R (``ELLIPS_LENGTH``),
``be_X`` = b_e / R (``ELLIPS_HEIGHT``), ``ce_X`` = c_e (``ELLIPS_ORDER``) and ``ls_X``, the cam
spacing over the static contact length, l_s / 2a (``ELLIPS_SHIFT``), where
2a = 2 sqrt(2 R δ − δ²) at the static deflection δ = F_y0 / k_y. They enter the road input only
(the enveloping of the ground), not the generated functions, so they are declared apart from
``[parameters]``, each as ``{ unit, description, range, source }`` with its range inside
:data:`TYRE_LIMITS`. Standard library only.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Sequence
from typing import Any

from derive.description_checks import DescriptionError
from derive.description_keys import closest

__all__ = ["TYRE_LIMITS", "check_tyres", "tyre_names_problem", "tyre_parameters"]

#: Per-axle prefix -> (unit, low, high, low excluded): the limits any description's range lies
#: in (the runtime's ``loader_model.parameters.tyres.TYRE_LIMITS``; a test keeps them equal).
TYRE_LIMITS: dict[str, tuple[str, float, float, bool]] = {
    "R": ("m", 0.0, 2.0, True),  # free radius: positive, the largest loader tyres 4 m across
    "ae": ("-", 0.5, 2.0, False),  # a_e / R: MF-Swift property files give 1.0-1.3
    "be": ("-", 0.5, 2.0, False),  # b_e / R: 1.0-1.05
    "ce": ("-", 1.0, 10.0, True),  # c_e: a convex super-ellipse; 1.5-2.0 published
    "ls": ("-", 0.0, 2.0, False),  # l_s / 2a: 0.4-0.83 published
}


def tyre_parameters(axles: Iterable[str]) -> list[tuple[str, str]]:
    """(name, unit) of every axle's tyre road geometry, axle by axle in :data:`TYRE_LIMITS`'
    order (``R_A``, ``ae_A``, ``be_A``, ``ce_A``, ``ls_A``, ``R_B``, ...)."""
    return [(f"{prefix}_{axle}", limits[0]) for axle in axles
            for prefix, limits in TYRE_LIMITS.items()]  # fmt: skip


def tyre_names_problem(declared: Collection[str], axles: Iterable[str]) -> str | None:
    """What is wrong with the names of ``[tyres]``, or None: the first unknown name (with the
    closest one still missing), else every missing name with its unit."""
    names = dict(tyre_parameters(axles))
    for name in declared:
        if name not in names:
            guess = closest(name, [n for n in names if n not in declared]) or closest(name, names)
            hint = f" (did you mean {guess!r}?)" if guess else ""
            return f"unknown tyre parameter {name!r}{hint}; allowed: {', '.join(names)}"
    missing = [f"{name} [{unit}]" for name, unit in names.items() if name not in declared]
    if missing:
        return (
            f"missing {', '.join(missing)}: give each axle's free radius R and tandem cam "
            "(ae = a_e/R, be = b_e/R, ce = c_e, ls = l_s/2a) as { unit, description, range, "
            "source }"
        )
    return None


def check_tyres(
    where: str, raw: dict[str, Any], axles: Sequence[str]
) -> list[tuple[str, str, str, tuple[float, float], str]]:
    """The checked ``[tyres]`` of a parsed description (entries' types already checked by
    :func:`derive.description_checks.check_entries`): (name, unit, description, range,
    source) per :func:`tyre_parameters`.

    Raises
    ------
    DescriptionError
        For a missing table or name, an unknown name, a wrong unit or a range outside
        :data:`TYRE_LIMITS`.
    """
    table = raw.get("tyres")
    if table is None:
        table = {}
    problem = tyre_names_problem(table, axles)
    if problem is not None:
        raise DescriptionError(where, "tyres", problem)
    out = []
    for name, unit in tyre_parameters(axles):
        entry, item = f"tyres.{name}", table[name]
        _, low, high, low_open = TYRE_LIMITS[name.split("_", 1)[0]]
        if item["unit"] != unit:
            raise DescriptionError(where, f"{entry}.unit", f"{item['unit']!r}, expected {unit!r}")
        first, last = (float(v) for v in item["range"])
        if not ((first > low if low_open else first >= low) and last <= high):
            bracket = "(" if low_open else "["
            raise DescriptionError(
                where,
                f"{entry}.range",
                f"[{first:g}, {last:g}] {unit} is not allowed; give a range inside "
                f"{bracket}{low:g}, {high:g}] {unit}",
            )
        out.append((name, unit, item["description"], (first, last), item["source"]))
    return out
