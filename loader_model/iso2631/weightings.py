"""Exact continuous frequency weightings of ISO 2631-1:1997, Annex A.

Each weighting is the product of four factors in the Laplace variable ``s`` (rad/s), Annex A.2:

.. math::

    W(s) = H_h(s)\\,H_l(s)\\,H_t(s)\\,H_s(s)

band limiting high-pass :math:`H_h = s^2 / (s^2 + s ω_1/Q_1 + ω_1^2)`, band limiting low-pass
:math:`H_l = ω_2^2 / (s^2 + s ω_2/Q_2 + ω_2^2)`, acceleration-velocity transition
:math:`H_t = (1 + s/ω_3) / (1 + s/(ω_4 Q_4) + s^2/ω_4^2)` and upward step
:math:`H_s = (1 + s/(ω_5 Q_5) + s^2/ω_5^2) / (1 + s/(ω_6 Q_6) + s^2/ω_6^2) \\cdot (ω_5/ω_6)^2`,
with :math:`ω_i = 2π f_i`. The upward step therefore has unit gain at high frequency and
:math:`(f_5/f_6)^2` at low frequency; it is written here in the equivalent monic form
:math:`(s^2 + s ω_5/Q_5 + ω_5^2)/(s^2 + s ω_6/Q_6 + ω_6^2)`. A corner frequency of ``inf`` removes
its term: :math:`f_3 = ∞` leaves the numerator of :math:`H_t` equal to 1, :math:`f_3 = f_4 = ∞`
makes :math:`H_t = 1` and :math:`f_5 = f_6 = ∞` makes :math:`H_s = 1`.

The weighted accelerations enter the r.m.s. of Eq. 49 and the total value of Eq. 50 of the paper.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import control

__all__ = [
    "NOMINAL_BAND_HZ",
    "WEIGHTINGS",
    "WEIGHTING_NAMES",
    "WeightingParameters",
    "WeightingSection",
    "check_weighting_name",
    "settling_time_s",
    "weighting_abcd",
    "weighting_num_den",
    "weighting_response",
    "weighting_sections",
    "weighting_state_space",
    "weighting_transfer_function",
]

_Q_BUTTERWORTH = 1.0 / math.sqrt(2.0)


@dataclass(frozen=True)
class WeightingParameters:
    """Corner frequencies (Hz) and quality factors of one weighting, ISO 2631-1 Table A.1.

    ``math.inf`` for a frequency removes the corresponding term (see the module docstring).
    """

    description: str
    f1_hz: float
    f2_hz: float
    f3_hz: float
    f4_hz: float
    q4: float
    f5_hz: float
    q5: float
    f6_hz: float
    q6: float
    q1: float = _Q_BUTTERWORTH
    q2: float = _Q_BUTTERWORTH


_INF = math.inf

#: The weightings of ISO 2631-1 Annex A (Table A.1; same values in ISO 8041 Table 3.1).
WEIGHTINGS: Mapping[str, WeightingParameters] = MappingProxyType(
    {
        "Wk": WeightingParameters(
            description="vertical (z) seat surface, feet; recumbent vertical",
            f1_hz=0.4, f2_hz=100.0, f3_hz=12.5, f4_hz=12.5, q4=0.63,
            f5_hz=2.37, q5=0.91, f6_hz=3.35, q6=0.91,
        ),
        "Wd": WeightingParameters(
            description="horizontal (x, y) seat surface, feet; recumbent horizontal",
            f1_hz=0.4, f2_hz=100.0, f3_hz=2.0, f4_hz=2.0, q4=0.63,
            f5_hz=_INF, q5=1.0, f6_hz=_INF, q6=1.0,
        ),
        "Wc": WeightingParameters(
            description="seat-back horizontal (x)",
            f1_hz=0.4, f2_hz=100.0, f3_hz=8.0, f4_hz=8.0, q4=0.63,
            f5_hz=_INF, q5=1.0, f6_hz=_INF, q6=1.0,
        ),
        "We": WeightingParameters(
            description="rotational (roll, pitch, yaw) seat surface",
            f1_hz=0.4, f2_hz=100.0, f3_hz=1.0, f4_hz=1.0, q4=0.63,
            f5_hz=_INF, q5=1.0, f6_hz=_INF, q6=1.0,
        ),
        "Wj": WeightingParameters(
            description="recumbent head vertical (x)",
            f1_hz=0.4, f2_hz=100.0, f3_hz=_INF, f4_hz=_INF, q4=1.0,
            f5_hz=3.75, q5=0.91, f6_hz=5.32, q6=0.91,
        ),
        "Wf": WeightingParameters(
            description="motion sickness vertical (z)",
            f1_hz=0.08, f2_hz=0.63, f3_hz=_INF, f4_hz=0.25, q4=0.86,
            f5_hz=0.0625, q5=0.80, f6_hz=0.10, q6=0.80,
        ),
    }
)  # fmt: skip

#: Names accepted wherever a weighting is asked for.
WEIGHTING_NAMES: tuple[str, ...] = tuple(WEIGHTINGS)

#: Frequency range (Hz) over which this package states and checks each weighting: the
#: one-third-octave bands 0.1 Hz to 80 Hz of ISO 2631-1 Tables 3 and 4 (Wf: 0.02 Hz to 4 Hz).
NOMINAL_BAND_HZ: Mapping[str, tuple[float, float]] = MappingProxyType(
    {name: ((0.02, 4.0) if name == "Wf" else (0.1, 80.0)) for name in WEIGHTINGS}
)


@dataclass(frozen=True)
class WeightingSection:
    """One factor of Annex A.2 as polynomials in ``s`` (highest power first)."""

    name: str
    numerator: tuple[float, ...]
    denominator: tuple[float, ...]


def check_weighting_name(weighting: str) -> WeightingParameters:
    """Return the parameters of ``weighting``; raise ValueError naming the allowed names."""
    parameters = WEIGHTINGS.get(weighting) if isinstance(weighting, str) else None
    if parameters is None:
        raise ValueError(f"weighting must be one of {WEIGHTING_NAMES}; got {weighting!r}")
    return parameters


def weighting_sections(weighting: str) -> tuple[WeightingSection, ...]:
    """Factors of ISO 2631-1 Annex A.2 for ``weighting``, omitting those that equal 1.

    Parameters
    ----------
    weighting : str
        One of :data:`WEIGHTING_NAMES`.

    Returns
    -------
    tuple of WeightingSection
        ``high_pass`` and ``low_pass`` (band limiting), ``acceleration_velocity`` (a-v
        transition) and ``upward_step``, each with real polynomial coefficients in s.
    """
    p = check_weighting_name(weighting)
    corners_hz = (p.f1_hz, p.f2_hz, p.f3_hz, p.f4_hz, p.f5_hz, p.f6_hz)
    w1, w2, w3, w4, w5, w6 = (2.0 * math.pi * f for f in corners_hz)
    sections = [
        WeightingSection("high_pass", (1.0, 0.0, 0.0), (1.0, w1 / p.q1, w1 * w1)),
        WeightingSection("low_pass", (w2 * w2,), (1.0, w2 / p.q2, w2 * w2)),
    ]
    if math.isfinite(w4):
        # (1 + s/w3) w4^2 / (s^2 + s w4/Q4 + w4^2); the numerator is w4^2 alone when f3 = inf.
        numerator = (w4 * w4 / w3, w4 * w4) if math.isfinite(w3) else (w4 * w4,)
        sections.append(
            WeightingSection("acceleration_velocity", numerator, (1.0, w4 / p.q4, w4 * w4))
        )
    if math.isfinite(w5) and math.isfinite(w6):
        sections.append(
            WeightingSection("upward_step", (1.0, w5 / p.q5, w5 * w5), (1.0, w6 / p.q6, w6 * w6))
        )
    return tuple(sections)


def weighting_num_den(weighting: str) -> tuple[np.ndarray, np.ndarray]:
    """Numerator and denominator of W(s) (Annex A.2), highest power of ``s`` first.

    The plain polynomial form lets a control design append the weighting to a plant model,
    e.g. ``scipy.signal.lti(num, den)``.
    """
    numerator = np.array([1.0])
    denominator = np.array([1.0])
    for section in weighting_sections(weighting):
        numerator = np.polymul(numerator, section.numerator)
        denominator = np.polymul(denominator, section.denominator)
    return numerator, denominator


def weighting_response(weighting: str, frequency_hz: np.ndarray | float) -> np.ndarray:
    """Complex frequency response W(j 2π f) of ISO 2631-1 Annex A.2 (exact, no discretization).

    Parameters
    ----------
    weighting : str
        One of :data:`WEIGHTING_NAMES`.
    frequency_hz : array_like
        Frequencies in Hz (finite, non-negative).

    Returns
    -------
    numpy.ndarray
        Complex response, same shape as ``frequency_hz``; ``abs`` gives the weighting factor of
        ISO 2631-1 Tables 3 and 4 (there multiplied by 1000).
    """
    frequency = np.asarray(frequency_hz, dtype=float)
    if not np.all(np.isfinite(frequency)) or np.any(frequency < 0.0):
        raise ValueError(f"frequency_hz must be finite and >= 0; got {frequency_hz!r}")
    s = 2j * np.pi * frequency
    response = np.ones_like(s)
    for section in weighting_sections(weighting):
        response = response * np.polyval(section.numerator, s) / np.polyval(section.denominator, s)
    return response


def settling_time_s(weighting: str) -> float:
    """Time for the slowest mode of ``weighting`` to decay to 1 %: ln(100) / min(-Re(pole))."""
    slowest = min(
        float(-np.max(np.roots(section.denominator).real))
        for section in weighting_sections(weighting)
    )
    return math.log(100.0) / slowest


def _section_abcd(section: WeightingSection) -> tuple[np.ndarray, ...]:
    """Controllable canonical realization of one proper section of order 2."""
    den = np.asarray(section.denominator, dtype=float)
    num = np.concatenate([np.zeros(len(den) - len(section.numerator)), section.numerator])
    a = np.array([[-den[1], -den[2]], [1.0, 0.0]])
    b = np.array([[1.0], [0.0]])
    c = np.array([[num[1] - den[1] * num[0], num[2] - den[2] * num[0]]])
    d = np.array([[num[0]]])
    return a, b, c, d


def weighting_abcd(weighting: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """State-space matrices (A, B, C, D) of W(s), the Annex A.2 factors in series.

    The states are those of the sections in the order of :func:`weighting_sections`, two per
    section; input is the unweighted, output the weighted acceleration (same unit).
    """
    a, b, c, d = _section_abcd(weighting_sections(weighting)[0])
    for section in weighting_sections(weighting)[1:]:
        a2, b2, c2, d2 = _section_abcd(section)
        n1, n2 = a.shape[0], a2.shape[0]
        a = np.block([[a, np.zeros((n1, n2))], [b2 @ c, a2]])
        b = np.vstack([b, b2 @ d])
        c = np.hstack([d2 @ c, c2])
        d = d2 @ d
    return a, b, c, d


def weighting_transfer_function(
    weighting: str, *, input_name: str = "a", output_name: str = "a_w"
) -> control.TransferFunction:
    """W(s) as a python-control ``TransferFunction`` with named signals (system name = weighting)."""
    import control

    numerator, denominator = weighting_num_den(weighting)
    return control.tf(
        numerator, denominator, inputs=[input_name], outputs=[output_name], name=weighting
    )


def weighting_state_space(
    weighting: str, *, input_name: str = "a", output_name: str = "a_w"
) -> control.StateSpace:
    """W(s) as a python-control ``StateSpace`` (see :func:`weighting_abcd`), named signals."""
    import control

    a, b, c, d = weighting_abcd(weighting)
    states = [
        f"{weighting}_{section.name}_{index}"
        for section in weighting_sections(weighting)
        for index in (1, 2)
    ]
    return control.ss(
        a, b, c, d, inputs=[input_name], outputs=[output_name], states=states, name=weighting
    )
