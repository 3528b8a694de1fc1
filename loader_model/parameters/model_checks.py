"""Plausibility of the generated model's parameter values, with the ranges of the parameter files.

:class:`loader_model.vehicle.dynamics.LoaderDynamics` takes a flat mapping of the generated model's
parameters (``m_1``, ``A_x``, ``k_Ay``, ...). Each name is checked against the range of the
parameter-file field it comes from (:mod:`loader_model.parameters.schema`), so the runtime API
refuses what the files refuse, with the same range and reason.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from loader_model.parameters.checks import check_distinct, shown
from loader_model.parameters.fields import COORDINATE, Range
from loader_model.parameters.schema import (
    AxleTyre,
    BoomParameters,
    BucketLoad,
    ChassisParameters,
    EnvironmentParameters,
    TyreParameters,
)

__all__ = ["MODEL_PARAMETER_RANGES", "check_model_parameters"]


def _allowed(cls: type, name: str) -> Range:
    return cls.__dataclass_fields__[name].metadata["allowed"]


def _body_2() -> tuple[Range, Range]:
    boom_m, load_m = _allowed(BoomParameters, "mass"), _allowed(BucketLoad, "mass")
    boom_j, load_j = _allowed(BoomParameters, "inertia"), _allowed(BucketLoad, "inertia")
    mass = Range(
        boom_m.low, boom_m.high + load_m.high, reason="boom (30-15 000 kg) plus bucket load"
    )
    # parallel-axis terms: both masses at most 2 x 10 m apart (the coordinate range)
    high = boom_j.high + load_j.high + boom_m.high * load_m.high / mass.high * 20.0**2
    inertia = Range(boom_j.low, high, reason="boom and load inertias with their offsets")
    return mass, inertia


_MASS_2, _INERTIA_2 = _body_2()
_MAX_WEIGHT_N = 2.0 * (45_000.0 + _MASS_2.high) * 9.84
_STATIC_LOAD = Range(
    0.0,
    _MAX_WEIGHT_N,
    low_open=True,
    reason="an axle in contact carries a compressive load, at most twice the heaviest machine",
)

#: Allowed range of each generated model parameter (a static load only when given).
MODEL_PARAMETER_RANGES: Mapping[str, Range] = {
    "m_1": _allowed(ChassisParameters, "mass"),
    "J_1": _allowed(ChassisParameters, "inertia"),
    "m_2": _MASS_2,
    "J_2": _INERTIA_2,
    "g": _allowed(EnvironmentParameters, "gravity"),
    **{f"{p}_{axis}": COORDINATE for p in "ABCDSNEG" for axis in "xy"},
    **{f"k_{a}{d}": _allowed(AxleTyre, f"k_{d}") for a in "AB" for d in "xy"},
    **{f"c_{a}{d}": _allowed(AxleTyre, f"c_{d}") for a in "AB" for d in "xy"},
    "mu_road": _allowed(TyreParameters, "friction_coefficient"),
    "F_transition": _allowed(TyreParameters, "contact_transition"),
    "tau_slip": _allowed(TyreParameters, "slip_relaxation_time"),
    "F_Ay0": _STATIC_LOAD,
    "F_By0": _STATIC_LOAD,
}


def check_model_parameters(values: Mapping[str, float]) -> None:
    """Raise ValueError for a value outside its range or a degenerate layout.

    Parameters
    ----------
    values : mapping of str to float
        Finite values by generated parameter name; names without a range are not checked.

    Raises
    ------
    ValueError
        Naming the parameter, the value, the range and its reason (``g = 0`` is allowed too: the
        paper's analysis without gravity, Eq. 33-34); or two coincident points
        among A, B, C, D, E, G; or the front axle A not ahead of B.
    """
    for name, value in values.items():
        if name == "g" and value == 0.0:
            continue  # the paper's analysis without gravity (Eq. 33-34; modes --no-gravity)
        allowed = MODEL_PARAMETER_RANGES.get(name)
        if allowed is not None and not allowed.contains(value):
            raise ValueError(
                f"model parameter {name} = {shown(value)} is out of range; allowed: "
                f"{allowed.describe()}"
            )
    points = {
        name: (values[f"{name}_x"], values[f"{name}_y"])
        for name in "ABCDEG"
        if f"{name}_x" in values and f"{name}_y" in values
    }
    check_distinct(points)
    if "A" in points and "B" in points and not points["A"][0] > points["B"][0]:
        raise ValueError(
            f"model parameters A_x = {points['A'][0]!r} and B_x = {points['B'][0]!r}: the front "
            "axle A must be ahead of the rear axle B (A_x > B_x)"
        )
    if not all(math.isfinite(v) for v in values.values()):
        raise ValueError("model parameters must be finite")
