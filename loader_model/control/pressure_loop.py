r"""The pressure loop of section 3.2 on the detailed plant, and its comparison with Eq. 43.

Control law (sections 3.2, 3.3; implemented once, as the virtual accumulator of
:mod:`loader_model.control.controllers`, here its continuous linear equivalent), on normalised
signals with the bucket load's pressure norm
‖p_A‖∞ (100 bar empty, 200 bar full) and the pump's maximum displacement:

.. math::

    \frac{V_{p,ref}}{V_{p,max}} = k_p \, \frac{p_{A,ref} - \mathrm{HP}(p_A)}{\lVert p_A \rVert_\infty},
    \qquad \mathrm{HP}(s) = \frac{s}{s + \omega_{hp}}

The high-pass removes the static pressure that holds the boom (section 3.3); the paper gives no
corner, ω_hp is an input (default 1 rad/s, a decade below the 2.9 Hz boom mode). The loop is
closed around the plant linearised at its static equilibrium with the loader attached (pump,
valves, leakage and friction acting), giving p_A / p_A,ref; :func:`compare_with_equation_43`
sets its poles, zeros and gain beside those of Eq. 43,

.. math:: \frac{p_A(s)}{p_{A,ref}(s)} = \frac{2810 s - 6361}{s^3 + 222.3 s^2 + 6328 s + 78910}

whose DC gain is −0.081 and whose zero is at +2.26 rad/s (errata 9).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = [
    "EQUATION_43",
    "PressureLoopComparison",
    "compare_with_equation_43",
    "pressure_loop",
]

#: Numerator and denominator of Eq. 43 (highest power first).
EQUATION_43 = ((2810.0, -6361.0), (1.0, 222.3, 6328.0, 78910.0))


def pressure_loop(
    plant: Any,
    pressure_norm_pa: float,
    max_displacement_m3_rev: float,
    *,
    k_p: float = 0.5,
    highpass_rad_s: float | None = 1.0,
) -> Any:
    """Closed pressure loop p_A,ref [Pa] -> p_A [Pa] around a linearised plant.

    Parameters
    ----------
    plant : control.StateSpace
        Linearised plant with the actuator's command as its first input (``V_p_ref`` [m³/rev],
        or a valve circuit's spool command ``x_s_ref`` [m]) and output ``p_A`` [Pa]
        (:meth:`loader_model.plant.linear.PlantLinearisation.state_space`).
    pressure_norm_pa, max_displacement_m3_rev : float
        ‖p_A‖∞ of the load case and V_p,max of the pump (a valve's spool stroke [m]).
    k_p : float
        Loop gain on normalised signals (Table 3: 0.5).
    highpass_rad_s : float or None
        Corner of the high-pass on the measured p_A; None feeds back p_A itself.
    """
    import control

    for name, value in (
        ("pressure_norm_pa", pressure_norm_pa),
        ("max_displacement_m3_rev", max_displacement_m3_rev),
        ("k_p", k_p),
    ):
        if not np.isfinite(value) or value <= 0:
            raise ValueError(f"{name} = {value!r}; allowed: a finite number > 0")
    if highpass_rad_s is not None and (not np.isfinite(highpass_rad_s) or highpass_rad_s <= 0):
        raise ValueError(f"highpass_rad_s = {highpass_rad_s!r}; allowed: None or a number > 0")
    command = plant.input_labels[0]  # V_p_ref, or a valve circuit's spool command x_s_ref
    drive = control.ss(plant[["p_A"], [command]], name="drive")
    drive.set_inputs([command]), drive.set_outputs(["p_A"])
    feedback = _pressure_feedback(pressure_norm_pa, max_displacement_m3_rev, k_p, highpass_rad_s)
    # V_p,ref = k_p V_max (p_A,ref − HP(p_A)) / norm: the reference gain is minus the
    # high-frequency gain on p_A (the high-pass passes p_A with gain 1 at high frequency)
    gain = -float(np.squeeze(feedback.D))
    reference = control.ss([], [], [], [[gain]], inputs=["p_A_ref"], outputs=["u_ref"], name="ref")
    summing = control.summing_junction(inputs=["u_ref", "u_fb"], output=command, name="sum")
    return control.interconnect(
        [drive, feedback, reference, summing],
        inputs=["p_A_ref"],
        outputs=["p_A"],
        name="pressure_loop",
    )


def _pressure_feedback(
    norm: float, max_displacement: float, k_p: float, corner: float | None
) -> Any:
    """p_A [Pa] -> u_fb [m³/rev]: the virtual accumulator's continuous linear equivalent
    (:mod:`loader_model.control.controllers`, p_A,ref = 0), so the law has one implementation;
    ``corner=None`` keeps only its feed-through (the high-pass's gain 1 on p_A)."""
    import dataclasses

    import control

    from loader_model.control import (
        SENSOR_NAMES,
        default_settings,
        linear_controller,
        settings_vector,
    )

    settings = dataclasses.replace(default_settings(), k_p=k_p, highpass_corner=corner or 1.0)
    vector = settings_vector(
        settings,
        pressure_norm=norm,
        max_displacement=max_displacement,
        hold_command=0.0,
        gravity=9.81,  # the next three do not enter the p_A path
        accelerometer_x=1.0,
    )
    equivalent = linear_controller(
        "virtual_accumulator", vector, np.zeros(len(SENSOR_NAMES))
    ).continuous
    column = SENSOR_NAMES.index("p_A")
    a, b, c, d = equivalent.A, equivalent.B[:, [column]], equivalent.C, equivalent.D[:, [column]]
    if corner is None:
        a, b, c = np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((1, 0))
    return control.ss(a, b, c, d, inputs=["p_A"], outputs=["u_fb"], name="pressure_feedback")


@dataclass(frozen=True)
class PressureLoopComparison:
    """Poles, zeros and gains of the detailed loop beside Eq. 43 (rad/s; gains in Pa/Pa)."""

    poles: np.ndarray
    zeros: np.ndarray
    dc_gain: float
    gain_at_1hz: complex
    reference_poles: np.ndarray
    reference_zeros: np.ndarray
    reference_dc_gain: float
    dominant_poles: np.ndarray
    """The poles of the detailed loop with |s| < 500 rad/s (Eq. 43's band), slowest first."""


def compare_with_equation_43(loop: Any) -> PressureLoopComparison:
    """Poles, zeros and DC gain of ``loop`` (SISO p_A,ref -> p_A) beside Eq. 43's."""
    import control

    reference = control.tf(*EQUATION_43)
    poles = np.sort_complex(control.poles(loop))
    zeros = np.sort_complex(control.zeros(loop))
    response = complex(np.squeeze(control.evalfr(loop, 2j * np.pi)))
    dominant = poles[np.abs(poles) < 500.0]
    return PressureLoopComparison(
        poles=poles,
        zeros=zeros,
        dc_gain=float(np.real(np.squeeze(control.dcgain(loop)))),
        gain_at_1hz=response,
        reference_poles=np.sort_complex(control.poles(reference)),
        reference_zeros=np.sort_complex(control.zeros(reference)),
        reference_dc_gain=float(np.squeeze(control.dcgain(reference))),
        dominant_poles=dominant[np.argsort(np.abs(dominant))],
    )
