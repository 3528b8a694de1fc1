"""ISO 2631-1:1997 whole-body vibration evaluation (the paper's section 5.3, Eq. 49 and 50).

- :mod:`~loader_model.iso2631.weightings`: exact continuous weightings of Annex A
  (Wk, Wd, Wc, We, Wj, Wf) as polynomials, state space and python-control systems.
- :mod:`~loader_model.iso2631.filters`: causal discrete weighting filters for sampled signals.
- :mod:`~loader_model.iso2631.metrics`: weighted r.m.s. (Eq. 49), total value (Eq. 50), crest
  factor, running r.m.s., MTVV, VDV, eVDV.
- :mod:`~loader_model.iso2631.comfort`: Annex C.2.3's likely comfort reactions to a total value.
- :mod:`~loader_model.iso2631.exposure`: daily exposure A(8), Directive 2002/44/EC values.
- :mod:`~loader_model.iso2631.timeseries`: labelled multi-axis records.
- :mod:`~loader_model.iso2631.vibration_csv`: records from CSV files, streamed.
- :mod:`~loader_model.iso2631.evaluation`: a whole record, per axis and in total.
- :mod:`~loader_model.iso2631.plot`: plot of the weighting curves (matplotlib, lazily).
"""

from __future__ import annotations

from loader_model.iso2631.comfort import COMFORT_SCALE, comfort_reaction
from loader_model.iso2631.evaluation import (
    COMFORT_K_FACTORS,
    DEFAULT_AXIS_WEIGHTINGS,
    NO_VIBRATION_RATIO,
    PAPER_K_FACTORS,
    AxisEvaluation,
    RecordEvaluation,
    evaluate_record,
    format_evaluation,
    health_assessment,
)
from loader_model.iso2631.exposure import (
    A8_ACTION_VALUE_M_S2,
    A8_LIMIT_VALUE_M_S2,
    HEALTH_K_FACTORS,
    REFERENCE_DURATION_S,
    VDV_ACTION_VALUE_M_S175,
    VDV_LIMIT_VALUE_M_S175,
    DirectiveAssessment,
    assess_directive_2002_44,
    daily_exposure_a8,
    daily_vibration_dose_value,
    directive_status,
)
from loader_model.iso2631.filters import (
    INITIAL_STATES,
    MAGNITUDE_TOLERANCE_DB,
    MINIMUM_SAMPLE_RATE_HZ,
    PHASE_TOLERANCE_DEG,
    SAMPLE_RATE_TO_BAND_RATIO,
    DiscreteWeighting,
    design_weighting_filter,
    weight_acceleration,
)
from loader_model.iso2631.metrics import (
    RUNNING_RMS_METHODS,
    crest_factor,
    estimated_vibration_dose_value,
    maximum_transient_vibration_value,
    running_rms,
    vibration_dose_value,
    vibration_total_value,
    weighted_rms,
)
from loader_model.iso2631.plot import PLOT_SUFFIXES, plot_weightings
from loader_model.iso2631.timeseries import (
    AXES,
    ROTATIONAL_AXES,
    TIME_JITTER_TOLERANCE,
    VibrationRecord,
    axis_unit,
    check_axis_name,
)
from loader_model.iso2631.vibration_csv import read_vibration_csv
from loader_model.iso2631.weightings import (
    NOMINAL_BAND_HZ,
    WEIGHTING_NAMES,
    WEIGHTINGS,
    WeightingParameters,
    WeightingSection,
    check_weighting_name,
    settling_time_s,
    weighting_abcd,
    weighting_num_den,
    weighting_response,
    weighting_sections,
    weighting_state_space,
    weighting_transfer_function,
)

__all__ = [
    "A8_ACTION_VALUE_M_S2",
    "A8_LIMIT_VALUE_M_S2",
    "AXES",
    "COMFORT_K_FACTORS",
    "COMFORT_SCALE",
    "DEFAULT_AXIS_WEIGHTINGS",
    "HEALTH_K_FACTORS",
    "INITIAL_STATES",
    "MAGNITUDE_TOLERANCE_DB",
    "MINIMUM_SAMPLE_RATE_HZ",
    "NOMINAL_BAND_HZ",
    "NO_VIBRATION_RATIO",
    "PAPER_K_FACTORS",
    "PHASE_TOLERANCE_DEG",
    "PLOT_SUFFIXES",
    "REFERENCE_DURATION_S",
    "ROTATIONAL_AXES",
    "RUNNING_RMS_METHODS",
    "SAMPLE_RATE_TO_BAND_RATIO",
    "TIME_JITTER_TOLERANCE",
    "VDV_ACTION_VALUE_M_S175",
    "VDV_LIMIT_VALUE_M_S175",
    "WEIGHTINGS",
    "WEIGHTING_NAMES",
    "AxisEvaluation",
    "DirectiveAssessment",
    "DiscreteWeighting",
    "RecordEvaluation",
    "VibrationRecord",
    "WeightingParameters",
    "WeightingSection",
    "assess_directive_2002_44",
    "axis_unit",
    "check_axis_name",
    "check_weighting_name",
    "comfort_reaction",
    "crest_factor",
    "daily_exposure_a8",
    "daily_vibration_dose_value",
    "design_weighting_filter",
    "directive_status",
    "estimated_vibration_dose_value",
    "evaluate_record",
    "format_evaluation",
    "health_assessment",
    "maximum_transient_vibration_value",
    "plot_weightings",
    "read_vibration_csv",
    "running_rms",
    "settling_time_s",
    "vibration_dose_value",
    "vibration_total_value",
    "weight_acceleration",
    "weighted_rms",
    "weighting_abcd",
    "weighting_num_den",
    "weighting_response",
    "weighting_sections",
    "weighting_state_space",
    "weighting_transfer_function",
]
