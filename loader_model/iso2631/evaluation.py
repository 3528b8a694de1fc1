"""Evaluation of a multi-axis record per ISO 2631-1 and the paper's section 5.3 (Eq. 49 and 50).

Each axis is weighted with its filter (``a_wi = W_i(a_i)``), reduced to the values of ISO 2631-1
clause 6 and combined into the vibration total value a_v of Eq. 50. The default weightings and k
factors are those of ISO 2631-1 for the seat surface of a seated person (comfort, 8.2.3), which
for x, y, z and pitch are the paper's k = 1, 1, 1 and 0.4.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from loader_model.iso2631._checks import as_positive
from loader_model.iso2631.exposure import (
    HEALTH_K_FACTORS,
    REFERENCE_DURATION_S,
    DirectiveAssessment,
    assess_directive_2002_44,
)
from loader_model.iso2631.filters import weight_acceleration
from loader_model.iso2631.metrics import (
    crest_factor,
    estimated_vibration_dose_value,
    maximum_transient_vibration_value,
    peak_magnitude,
    vibration_dose_value,
    vibration_total_value,
    weighted_rms,
)
from loader_model.iso2631.timeseries import VibrationRecord, axis_unit, check_axis_name
from loader_model.iso2631.weightings import check_weighting_name

__all__ = [
    "COMFORT_K_FACTORS",
    "DEFAULT_AXIS_WEIGHTINGS",
    "MAX_K_FACTOR",
    "NO_VIBRATION_RATIO",
    "PAPER_K_FACTORS",
    "AxisEvaluation",
    "RecordEvaluation",
    "evaluate_record",
    "format_evaluation",
    "health_assessment",
]

#: Largest accepted k factor (ISO 2631-1 k factors lie between 0.2 and 1.4).
MAX_K_FACTOR = 2.0
#: An axis whose weighted r.m.s. is at most this fraction of its largest |sample| carries no
#: vibration (an all-zero channel, or a constant one such as gravity alone, which the
#: band-limiting high-pass removes down to rounding, about 1e-15 of it): its values are 0 and its
#: crest factor is undefined. Vibration of 1e-9 of a 1 g offset (1e-8 m/s²) is far below the
#: noise of any accelerometer (about 1e-5 m/s²).
NO_VIBRATION_RATIO = 1e-9
#: Weighting per axis, seated person, seat surface (ISO 2631-1 Table 1 / 7.2.2, 8.2.2).
DEFAULT_AXIS_WEIGHTINGS: Mapping[str, str] = MappingProxyType(
    {"x": "Wd", "y": "Wd", "z": "Wk", "roll": "We", "pitch": "We", "yaw": "We"}
)
#: k factors for comfort, seat surface (ISO 2631-1 8.2.3); rotations in m/rad.
COMFORT_K_FACTORS: Mapping[str, float] = MappingProxyType(
    {"x": 1.0, "y": 1.0, "z": 1.0, "roll": 0.63, "pitch": 0.40, "yaw": 0.20}
)
#: k factors of the paper (section 5.3, Eq. 50): 1 for x, y, z and 0.4 for pitch.
PAPER_K_FACTORS: Mapping[str, float] = MappingProxyType(
    {"x": 1.0, "y": 1.0, "z": 1.0, "pitch": 0.4}
)


@dataclass(frozen=True)
class AxisEvaluation:
    """ISO 2631-1 values of one axis; accelerations in ``unit``, VDVs in ``unit`` x s^0.25.

    An axis without vibration (see :data:`NO_VIBRATION_RATIO`) has every value 0 and
    ``crest_factor`` NaN (undefined); :attr:`has_vibration` tells it apart.
    """

    axis: str
    weighting: str
    k_factor: float
    unit: str
    weighted_rms: float
    crest_factor: float
    mtvv: float
    vdv: float
    estimated_vdv: float

    @property
    def has_vibration(self) -> bool:
        """False for an axis without vibration (a_w = 0, crest factor undefined)."""
        return self.weighted_rms > 0.0


@dataclass(frozen=True)
class RecordEvaluation:
    """Per-axis values and the vibration total value ``total_m_s2`` (paper Eq. 50)."""

    axes: tuple[AxisEvaluation, ...]
    total_m_s2: float
    duration_s: float
    sample_rate_hz: float
    integration_time_s: float


def _merged(
    defaults: Mapping[str, object], overrides: Mapping[str, object] | None, what: str
) -> dict[str, object]:
    merged = dict(defaults)
    for axis, value in (overrides or {}).items():
        check_axis_name(axis, f"{what} axis")
        merged[axis] = value
    return merged


def evaluate_record(
    record: VibrationRecord,
    *,
    weightings: Mapping[str, str] | None = None,
    k_factors: Mapping[str, float] | None = None,
    integration_time_s: float = 1.0,
    running_rms_method: str = "linear",
) -> RecordEvaluation:
    """Weight every axis of ``record`` and compute the ISO 2631-1 values and Eq. 50.

    Parameters
    ----------
    record : VibrationRecord
        The measured accelerations.
    weightings : mapping of str to str, optional
        Weighting per axis, overriding :data:`DEFAULT_AXIS_WEIGHTINGS`.
    k_factors : mapping of str to float, optional
        k factor per axis, overriding :data:`COMFORT_K_FACTORS`.
    integration_time_s : float
        Integration time τ of the running r.m.s. for MTVV (ISO 2631-1 6.3.1), s.
    running_rms_method : {"linear", "exponential"}
        Running r.m.s. integration.

    Returns
    -------
    RecordEvaluation
        Values per axis, in the record's axis order, and a_v of Eq. 50. An axis without
        vibration (an all-zero or constant channel, :data:`NO_VIBRATION_RATIO`) is evaluated
        with a_w, MTVV, VDV and eVDV 0 and an undefined (NaN) crest factor.
    """
    for what, overrides in (("weightings", weightings), ("k_factors", k_factors)):
        for axis in overrides or {}:
            check_axis_name(axis, f"{what} axis")
            if axis not in record.axes:
                raise ValueError(
                    f"{what}[{axis!r}]: axis {axis!r} is not in the record; its axes are "
                    f"{list(record.axes)}"
                )
    axis_weightings = _merged(DEFAULT_AXIS_WEIGHTINGS, weightings, "weightings")
    axis_k_factors = _merged(COMFORT_K_FACTORS, k_factors, "k_factors")
    evaluations = []
    for axis, acceleration in record.axes.items():
        weighting = str(axis_weightings[axis])
        check_weighting_name(weighting)
        k_factor = axis_k_factors[axis]
        if (
            isinstance(k_factor, bool)
            or not isinstance(k_factor, int | float)
            or not 0.0 <= k_factor <= MAX_K_FACTOR
        ):
            raise ValueError(
                f"k_factors[{axis!r}] must be a number in [0, {MAX_K_FACTOR:g}] (ISO 2631-1 uses "
                f"0.2 to 1.4); got {k_factor!r}"
            )
        weighted = weight_acceleration(acceleration, record.sample_rate_hz, weighting)
        rms = weighted_rms(weighted)
        if not rms > NO_VIBRATION_RATIO * peak_magnitude(acceleration):
            weighted = np.zeros_like(weighted)  # zero up to rounding: no vibration
            rms = 0.0
        evaluations.append(
            AxisEvaluation(
                axis=axis,
                weighting=weighting,
                k_factor=float(k_factor),
                unit=axis_unit(axis),
                weighted_rms=rms,
                crest_factor=crest_factor(weighted),
                mtvv=maximum_transient_vibration_value(
                    weighted,
                    record.sample_rate_hz,
                    integration_time_s=integration_time_s,
                    method=running_rms_method,
                ),
                vdv=vibration_dose_value(weighted, record.sample_rate_hz),
                estimated_vdv=estimated_vibration_dose_value(rms, record.duration_s),
            )
        )
        del weighted  # a long record's next axis is weighted without this one in memory
    total = vibration_total_value(
        {item.axis: item.weighted_rms for item in evaluations},
        {item.axis: item.k_factor for item in evaluations},
    )
    return RecordEvaluation(
        axes=tuple(evaluations),
        total_m_s2=total,
        duration_s=record.duration_s,
        sample_rate_hz=record.sample_rate_hz,
        integration_time_s=float(integration_time_s),
    )


def health_assessment(
    evaluation: RecordEvaluation, exposure_duration_s: float = REFERENCE_DURATION_S
) -> DirectiveAssessment | None:
    """A(8) and daily VDV of the worst translational axis (Directive 2002/44/EC Annex B.1).

    A(8) = max_i k_i a_wi (T_exp / 8 h)^(1/2) and VDV = max_i k_i VDV_i (T_exp / T)^(1/4) with
    the health factors k = 1.4, 1.4, 1 for x, y, z (ISO 2631-1 7.2.3), T the record duration.
    Returns ``None`` when the record has none of x, y, z.
    """
    exposure_s = as_positive(exposure_duration_s, "exposure_duration_s", "s")
    health_axes = [item for item in evaluation.axes if item.axis in HEALTH_K_FACTORS]
    if not health_axes:
        return None
    a8 = max(
        HEALTH_K_FACTORS[item.axis]
        * item.weighted_rms
        * math.sqrt(exposure_s / REFERENCE_DURATION_S)
        for item in health_axes
    )
    vdv = max(
        HEALTH_K_FACTORS[item.axis] * item.vdv * (exposure_s / evaluation.duration_s) ** 0.25
        for item in health_axes
    )
    return assess_directive_2002_44(a8_m_s2=a8, vdv_m_s175=vdv)


def format_evaluation(
    evaluation: RecordEvaluation, assessment: DirectiveAssessment | None = None, title: str = ""
) -> str:
    """Readable plain-text table of an evaluation (and of a health assessment, if given)."""
    header = ("axis", "weighting", "k", "a_w", "crest", "MTVV", "VDV", "eVDV", "unit")
    rows = [
        (
            item.axis,
            item.weighting,
            f"{item.k_factor:.2f}",
            f"{item.weighted_rms:.4g}",
            f"{item.crest_factor:.3g}" if item.has_vibration else "—",
            f"{item.mtvv:.4g}",
            f"{item.vdv:.4g}",
            f"{item.estimated_vdv:.4g}",
            f"{item.unit} (VDV: {item.unit.replace('s²', 's^1.75')})",
        )
        for item in evaluation.axes
    ]
    widths = [max(len(str(row[i])) for row in [header, *rows]) for i in range(len(header))]
    lines = [title] if title else []
    lines.append(
        f"ISO 2631-1:1997 evaluation: T = {evaluation.duration_s:.4g} s at "
        f"{evaluation.sample_rate_hz:.6g} Hz, MTVV with τ = {evaluation.integration_time_s:g} s"
    )
    for row in [header, *rows]:
        lines.append(
            "  ".join(
                str(cell).ljust(width) for cell, width in zip(row, widths, strict=True)
            ).rstrip()
        )
    for item in evaluation.axes:
        if not item.has_vibration:
            lines.append(
                f"{item.axis}: no vibration (an all-zero or constant channel: a_w = 0); crest "
                "factor undefined (—)"
            )
    lines.append(f"vibration total value a_total (paper Eq. 50) = {evaluation.total_m_s2:.4g} m/s²")
    if assessment is not None:
        lines.append(
            f"daily exposure A(8) = {assessment.a8_m_s2:.4g} m/s² ({assessment.a8_status}; "
            f"Directive 2002/44/EC action 0.5, limit 1.15 m/s²)"
        )
        lines.append(
            f"daily VDV = {assessment.vdv_m_s175:.4g} m/s^1.75 ({assessment.vdv_status}; "
            f"action 9.1, limit 21 m/s^1.75)"
        )
    return "\n".join(lines)
