"""Controller design (paper section 3): output-feedback LQR and CasADi H2 gain optimisation.

The algorithms are generic in the plant: they take numpy matrices or python-control systems.
"""

from loader_model.control.design_plant import DesignPlant
from loader_model.control.h2_cost import h2_cost_function, h2_costs
from loader_model.control.h2_design import H2DesignError, H2DesignResult, design_h2_gain
from loader_model.control.output_feedback import (
    NoStabilisingGainError,
    OutputFeedbackResult,
    output_feedback_lqr,
)

__all__ = [
    "DesignPlant",
    "H2DesignError",
    "H2DesignResult",
    "NoStabilisingGainError",
    "OutputFeedbackResult",
    "design_h2_gain",
    "h2_cost_function",
    "h2_costs",
    "output_feedback_lqr",
]
