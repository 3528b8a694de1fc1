"""The tyres' road geometry per axle: free radius and tandem-cam shape, their names and limits.

Each axle's tyres envelop the road (the road input of the plant, not its parameter vector) as a
rigid disc of their free radius R or as Schmeitz's tandem elliptical cam (A. J. C. Schmeitz,
H. B. Pacejka, I. J. M. Besselink, Vehicle System Dynamics 41(5), 2004; H. B. Pacejka, Tire and
Vehicle Dynamics, 3rd ed., 2012, section 10.2), whose lengths are stated in units of R as MF-Swift
tyre property files state them (``ELLIPS_LENGTH``, ``ELLIPS_HEIGHT``, ``ELLIPS_ORDER``,
``ELLIPS_SHIFT``):

=============  ============  ====  =======================================================
per axle X     grouped       unit  meaning
=============  ============  ====  =======================================================
``R_X``        radius        m     free (unloaded) radius R
``ae_X``       cam_length    \\-    cam half-length a_e / R
``be_X``       cam_height    \\-    cam half-height b_e / R
``ce_X``       cam_exponent  \\-    super-ellipse exponent c_e
``ls_X``       cam_spacing   \\-    cam spacing l_s over the static contact length 2a
=============  ============  ====  =======================================================

The skid-steer's grouped parameter file gives them in ``[tyres.front]`` and ``[tyres.rear]``
(:class:`~loader_model.parameters.schema.AxleTyre`), every other machine's flat file in its
``[tyres]`` table by per-axle name (:mod:`~loader_model.parameters.machine_files`), each value
inside the limits below and its machine description's range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from loader_model.io.arrays import real_number
from loader_model.parameters.fields import Range
from loader_model.parameters.flat_entries import check_names, entry

__all__ = [
    "TYRE_FIELDS",
    "TYRE_LIMITS",
    "AxleEnvelope",
    "axle_envelopes",
    "tyre_parameter_names",
    "tyre_table",
]

#: (per-axle prefix, field of the grouped file, unit), in the order of the files.
TYRE_FIELDS: tuple[tuple[str, str, str], ...] = (
    ("R", "radius", "m"),
    ("ae", "cam_length", "-"),
    ("be", "cam_height", "-"),
    ("ce", "cam_exponent", "-"),
    ("ls", "cam_spacing", "-"),
)
#: The values any machine's tyres may take (a description's ranges lie inside them).
TYRE_LIMITS: dict[str, Range] = {
    "radius": Range(
        0.0, 2.0, low_open=True, reason="a free radius is positive; the largest loader tyres are "
        "about 4 m across"
    ),
    "cam_length": Range(
        0.5, 2.0, reason="a_e / R: MF-Swift property files give 1.0-1.3; longer than any patch"
    ),
    "cam_height": Range(0.5, 2.0, reason="b_e / R: MF-Swift property files give 1.0-1.05"),
    "cam_exponent": Range(
        1.0, 10.0, low_open=True, reason="a convex super-ellipse (c_e > 1); 10 is nearly a box"
    ),
    "cam_spacing": Range(
        0.0, 2.0, reason="l_s / 2a: the sources give 0.4-0.83; 0 puts both cams at the axle"
    ),
}  # fmt: skip


def tyre_parameter_names(axle: str) -> tuple[str, ...]:
    """The per-axle names of :data:`TYRE_FIELDS` for axle point ``axle`` (``R_A``, ``ae_A``, ...)."""
    return tuple(f"{prefix}_{axle}" for prefix, _, _ in TYRE_FIELDS)


@dataclass(frozen=True)
class AxleEnvelope:
    """The road geometry of one axle's tyres (module notes).

    Attributes
    ----------
    radius_m : float
        Free radius R in m.
    length_ratio, height_ratio : float
        a_e / R and b_e / R.
    exponent : float
        c_e.
    spacing_ratio : float
        l_s / (2a).
    """

    radius_m: float
    length_ratio: float
    height_ratio: float
    exponent: float
    spacing_ratio: float

    def __post_init__(self) -> None:
        for (_, name, unit), field in zip(TYRE_FIELDS, self.__dataclass_fields__, strict=True):
            value, allowed = getattr(self, field), TYRE_LIMITS[name]
            number = (
                value if isinstance(value, int | float) and not isinstance(value, bool) else None
            )
            if number is None or not (math.isfinite(number) and allowed.contains(number)):
                raise ValueError(
                    f"tyre {name} = {value!r} {unit} is not allowed; allowed: {allowed.describe()}"
                )
            object.__setattr__(self, field, float(number))


def axle_envelopes(parameters: Any, axles: tuple[str, ...]) -> tuple[AxleEnvelope, ...]:
    """The tyres of each axle of ``axles`` (front first) in a machine's parameter set.

    Parameters
    ----------
    parameters : LoaderParameters or MachineParameters
        The skid-steer's grouped set (its front and rear axle) or another machine's flat set
        (its ``tyres`` by per-axle name).
    axles : tuple of str
        The machine's axle points, front first.

    Raises
    ------
    ValueError
        For a set that states no tyres for an axle (naming the missing entries).
    """
    grouped = getattr(parameters, "tyres", None)
    if hasattr(grouped, "front") and hasattr(grouped, "rear"):  # LoaderParameters
        if len(axles) != 2:
            raise ValueError(f"a grouped loader file has two axles; the machine has {axles}")
        sides = (parameters.tyres.front, parameters.tyres.rear)
        return tuple(
            AxleEnvelope(*(getattr(side, name) for _, name, _ in TYRE_FIELDS)) for side in sides
        )
    values = getattr(parameters, "tyres", None) or {}
    out = []
    for axle in axles:
        names = tyre_parameter_names(axle)
        missing = [name for name in names if name not in values]
        if missing:
            origin = getattr(parameters, "origin", "") or "the parameter set"
            raise ValueError(f"{origin} [tyres]: missing {', '.join(missing)}")
        out.append(AxleEnvelope(*(values[name] for name in names)))
    return tuple(out)


def tyre_table(
    where: str,
    info: Any,
    table: dict[str, Any],
    sources: dict[str, str],
) -> dict[str, float]:
    """The ``[tyres]`` table of a flat machine file: every name the description of ``info``
    (a :class:`~loader_model.machines.MachineInfo`) declares, each value in its range there and
    in :data:`TYRE_LIMITS`, each entry ``{ value, unit, source }`` as in the file's other tables
    (:mod:`~loader_model.parameters.flat_entries`). Records each source in ``sources``.

    Raises
    ------
    ValueError
        Naming ``where``, the entry, the value and what is allowed.
    """
    declared = set(info.tyre_units)
    check_names(where, table, declared, declared)
    limits = {prefix: TYRE_LIMITS[name] for prefix, name, _ in TYRE_FIELDS}
    out = {}
    for name, unit in info.tyre_units.items():
        value, sources[f"tyres.{name}"] = entry(where, name, table[name], unit)
        value = real_number(f"{where}: {name}", value)
        low, high = info.tyre_ranges.get(name, (-math.inf, math.inf))
        allowed = limits.get(name.split("_", 1)[0])
        if not (math.isfinite(value) and low <= value <= high):
            raise ValueError(
                f"{where}: {name} = {value!r} {unit} is out of range; allowed: [{low:g}, "
                f"{high:g}] (the description of {info.name!r})"
            )
        if allowed is not None and not allowed.contains(value):
            raise ValueError(
                f"{where}: {name} = {value!r} {unit} is out of range; allowed: {allowed.describe()}"
            )
        out[name] = value
    return out
