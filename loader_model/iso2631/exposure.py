"""Daily exposure A(8) and the values of EU Directive 2002/44/EC (Article 3, Annex B).

The Directive assesses whole-body vibration per axis of the seated operator with ISO 2631-1
(health, clause 7): A(8) = max(1.4 a_wx, 1.4 a_wy, a_wz) scaled to 8 h, or alternatively the
vibration dose value with the same multiplying factors, extrapolated to the daily exposure time.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

__all__ = [
    "A8_ACTION_VALUE_M_S2",
    "A8_LIMIT_VALUE_M_S2",
    "HEALTH_K_FACTORS",
    "REFERENCE_DURATION_S",
    "VDV_ACTION_VALUE_M_S175",
    "VDV_LIMIT_VALUE_M_S175",
    "DirectiveAssessment",
    "assess_directive_2002_44",
    "daily_exposure_a8",
    "daily_vibration_dose_value",
    "directive_status",
]

#: Reference duration T0 of A(8): 8 h in s.
REFERENCE_DURATION_S = 8.0 * 3600.0
#: Directive 2002/44/EC Article 3(2)(a)/(b): daily exposure action and limit values, A(8).
A8_ACTION_VALUE_M_S2 = 0.5
A8_LIMIT_VALUE_M_S2 = 1.15
#: Directive 2002/44/EC Article 3(2): the alternative values as vibration dose value.
VDV_ACTION_VALUE_M_S175 = 9.1
VDV_LIMIT_VALUE_M_S175 = 21.0
#: Multiplying factors for health, seated (ISO 2631-1 7.2.3; Directive Annex B.1).
HEALTH_K_FACTORS: Mapping[str, float] = MappingProxyType({"x": 1.4, "y": 1.4, "z": 1.0})


def _non_negative_values(value: float | Sequence[float], name: str, unit: str) -> np.ndarray:
    try:
        array = np.atleast_1d(np.asarray(value, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numbers >= 0 in {unit}; got {value!r}") from None
    if array.ndim != 1 or array.size == 0:
        raise ValueError(f"{name} must be a number or a non-empty 1-D sequence; got {value!r}")
    if not np.all(np.isfinite(array)) or np.any(array < 0.0):
        raise ValueError(f"{name} must be finite and >= 0 {unit}; got {value!r}")
    return array


def daily_exposure_a8(
    weighted_rms_m_s2: float | Sequence[float], exposure_duration_s: float | Sequence[float]
) -> float:
    """Daily exposure A(8) = [Σ a_wi² T_i / T0]^(1/2), T0 = 8 h (Directive 2002/44/EC Annex B).

    Parameters
    ----------
    weighted_rms_m_s2 : float or sequence of float
        Weighted r.m.s. acceleration of each operation, already multiplied by its k factor.
    exposure_duration_s : float or sequence of float
        Daily exposure time of each operation in s (same length).

    Returns
    -------
    float
        A(8) in m/s².
    """
    rms = _non_negative_values(weighted_rms_m_s2, "weighted_rms_m_s2", "m/s²")
    duration = _non_negative_values(exposure_duration_s, "exposure_duration_s", "s")
    if rms.size != duration.size:
        raise ValueError(
            f"weighted_rms_m_s2 and exposure_duration_s must have the same length; "
            f"got {rms.size} and {duration.size}"
        )
    return math.sqrt(float(np.sum(rms**2 * duration)) / REFERENCE_DURATION_S)


def daily_vibration_dose_value(
    vdv_m_s175: float | Sequence[float],
    measurement_duration_s: float | Sequence[float],
    exposure_duration_s: float | Sequence[float],
) -> float:
    """Daily VDV: each measured VDV extrapolated by (T_exp / T_meas)^(1/4), combined by fourth powers.

    .. math:: VDV_{day} = \\left[\\sum_i VDV_i^4 \\, T_{exp,i} / T_{meas,i}\\right]^{1/4}

    (ISO 2631-1 6.3.2 and Annex B.3; Directive 2002/44/EC Annex B.1.)
    """
    vdv = _non_negative_values(vdv_m_s175, "vdv_m_s175", "m/s^1.75")
    measured = _non_negative_values(measurement_duration_s, "measurement_duration_s", "s")
    exposed = _non_negative_values(exposure_duration_s, "exposure_duration_s", "s")
    if not vdv.size == measured.size == exposed.size:
        raise ValueError(
            "vdv_m_s175, measurement_duration_s and exposure_duration_s must have the same "
            f"length; got {vdv.size}, {measured.size} and {exposed.size}"
        )
    if np.any(measured == 0.0):
        raise ValueError(f"measurement_duration_s must be > 0 s; got {measurement_duration_s!r}")
    return float(np.sum(vdv**4 * exposed / measured)) ** 0.25


def directive_status(value: float, action_value: float, limit_value: float) -> str:
    """``"below action value"``, ``"action value exceeded"`` or ``"limit value exceeded"``."""
    if value > limit_value:
        return "limit value exceeded"
    if value > action_value:
        return "action value exceeded"
    return "below action value"


@dataclass(frozen=True)
class DirectiveAssessment:
    """A(8) and daily VDV compared with the Directive 2002/44/EC values (``None``: not given)."""

    a8_m_s2: float | None
    a8_status: str | None
    vdv_m_s175: float | None
    vdv_status: str | None


def assess_directive_2002_44(
    a8_m_s2: float | None = None, vdv_m_s175: float | None = None
) -> DirectiveAssessment:
    """Compare a daily exposure A(8) and/or a daily VDV with the Directive's values.

    Action and limit values: A(8) 0.5 and 1.15 m/s²; VDV 9.1 and 21 m/s^1.75.
    """
    if a8_m_s2 is None and vdv_m_s175 is None:
        raise ValueError("give a8_m_s2 and/or vdv_m_s175; got neither")
    a8_status = vdv_status = None
    if a8_m_s2 is not None:
        a8_m_s2 = float(_non_negative_values(a8_m_s2, "a8_m_s2", "m/s²")[0])
        a8_status = directive_status(a8_m_s2, A8_ACTION_VALUE_M_S2, A8_LIMIT_VALUE_M_S2)
    if vdv_m_s175 is not None:
        vdv_m_s175 = float(_non_negative_values(vdv_m_s175, "vdv_m_s175", "m/s^1.75")[0])
        vdv_status = directive_status(vdv_m_s175, VDV_ACTION_VALUE_M_S175, VDV_LIMIT_VALUE_M_S175)
    return DirectiveAssessment(a8_m_s2, a8_status, vdv_m_s175, vdv_status)
