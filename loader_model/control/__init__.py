"""Controller design (paper section 3): output-feedback LQR and CasADi H2 gain optimisation.

The algorithms are generic in the plant: they take numpy matrices or python-control systems.
"""

from loader_model.control.output_feedback import (
    NoStabilisingGainError,
    OutputFeedbackResult,
    output_feedback_lqr,
)

__all__ = ["NoStabilisingGainError", "OutputFeedbackResult", "output_feedback_lqr"]
