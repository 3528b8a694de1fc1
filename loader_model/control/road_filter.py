r"""ISO 8608 road as a shaping filter driven by white noise, with the rear axle delayed (Padé).

Derivation. ISO 8608 gives the one-sided displacement PSD over spatial frequency n (cycles/m),
:math:`G_d(n) = G_d(n_0)(n/n_0)^{-2}` (:mod:`loader_model.simulation.iso8608`). Driving at speed
v, the time frequency is f = v n and the one-sided PSD in time is :math:`G(f) = G_d(f/v)/v
= G_d(n_0) n_0^2 v / f^2`; the road *velocity* ḣ has the flat one-sided PSD
:math:`(2\pi f)^2 G(f) = 4\pi^2 G_d(n_0) n_0^2 v`: white noise. A pure integrator has infinite
variance, so the filter puts a pole at the lower ISO band limit n_1 = 0.011 cycles/m:

.. math::

    \dot h_A = -a\,h_A + q\,\nu, \qquad a = 2\pi n_1 v, \qquad q = \pi n_0 \sqrt{2 G_d(n_0) v},

with ν white noise of unit intensity (E ν(t)ν(t') = δ(t − t'), one-sided PSD 2). Its spatial PSD is

.. math:: G_{d,filter}(n) = \frac{2 q^2 v}{(2\pi v n)^2 + a^2} = G_d(n_0)\,\frac{n_0^2}{n^2 + n_1^2},

the ISO closed form times n²/(n² + n_1²): 1 % low at n = 10 n_1 = 0.11 cycles/m, 0.05 % at
0.5 cycles/m (checked in ``tests/control/test_comfort_design.py``).

Rear axle. B runs a wheelbase L behind A on the same track, :math:`h_B(t) = h_A(t - L/v)`,
approximated by the Padé approximant of order N (numerator and denominator degree N, an all-pass:
magnitude exact, phase error below 1° for ωT < 0.9 N roughly). The rates follow from the filter
states (no differentiation of a signal): :math:`\dot h_B = C_p(A_p x_p + B_p h_A) + D_p \dot h_A`.
The delay acts only on the front/rear cross-spectrum, and the ISO-weighted seat response spans
0.5-80 Hz while L/v = 0.48 s at 9 km/h: ωL/v reaches several hundred, far beyond any usable
Padé order. Measured (empty bucket, class C, 9 km/h, K_fb = Table 3 with k_φ = +0.22), against
the exact delay by frequency-domain quadrature (a_total = 2.7395 m/s²): Padé orders 1, 2, 3, 4,
5, 6, 8 give 1.902, 3.523, 1.917, 2.492, 3.408, 2.775, 3.785 m/s² (−31 % to +38 %; order 10
failed numerically); two *independent* tracks (the exact delay's limit for ωL/v ≫ 1, where the
cross term averages out) give 2.7604 m/s², +0.76 %. So the design uses ``rear="independent"``;
``"pade"`` is kept for studies of the low-frequency correlation.

Horizontal road input: neglected (w_Ax = w_Bx = 0, ẇ_x = 0), the default of
:mod:`loader_model.simulation.travel` (``slope_to_x_m = (0, 0)``); only w_Ay, ẇ_Ay, w_By, ẇ_By
are driven.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from loader_model.parameters.road_classes import (
    CLASS_PSD_M3,
    ISO8608_BAND_CYCLES_M,
    REFERENCE_SPATIAL_FREQUENCY_CYCLES_M,
)

__all__ = ["ROAD_OUTPUTS", "road_filter_coefficients", "road_filter_psd", "road_shaping_filter"]

#: Outputs of :func:`road_shaping_filter` (plant exogenous inputs of the same names).
ROAD_OUTPUTS: tuple[str, ...] = ("w_Ay", "wd_Ay", "w_By", "wd_By")


def _check(road_class: str, speed_m_s: float) -> float:
    if not isinstance(road_class, str) or road_class.upper() not in CLASS_PSD_M3:
        raise ValueError(f"road class must be one of {tuple(CLASS_PSD_M3)}; got {road_class!r}")
    if not (math.isfinite(speed_m_s) and 0.1 <= speed_m_s <= 30.0):
        raise ValueError(f"speed = {speed_m_s!r} m/s; allowed: 0.1 to 30 m/s (0.36-108 km/h)")
    return CLASS_PSD_M3[road_class.upper()]


def road_filter_coefficients(road_class: str, speed_m_s: float) -> tuple[float, float]:
    """(a [1/s], q [m/s^0.5]) of the first-order filter ḣ = −a h + q ν (module docstring)."""
    level = _check(road_class, speed_m_s)
    n0, n1 = REFERENCE_SPATIAL_FREQUENCY_CYCLES_M, ISO8608_BAND_CYCLES_M[0]
    return 2 * math.pi * n1 * speed_m_s, math.pi * n0 * math.sqrt(2 * level * speed_m_s)


def road_filter_psd(spatial_frequency_cycles_m: Any, road_class: str, speed_m_s: float) -> Any:
    """One-sided spatial PSD [m³] of the filter output h_A, from its frequency response."""
    a, q = road_filter_coefficients(road_class, speed_m_s)
    omega = 2 * np.pi * speed_m_s * np.asarray(spatial_frequency_cycles_m, dtype=float)
    return 2.0 * q**2 * speed_m_s / (omega**2 + a**2)


def road_shaping_filter(
    road_class: str,
    speed_m_s: float,
    wheelbase_m: float,
    rear: str = "independent",
    pade_order: int = 4,
    axles: Sequence[str] = ("A", "B"),
) -> Any:
    """python-control ``StateSpace`` of the road under the axles, driven by unit white noise.

    Parameters
    ----------
    road_class, speed_m_s
        ISO 8608 class ``"A"``-``"H"`` and travel speed [m/s].
    wheelbase_m
        L = A_x − B_x [m] (front to rearmost axle); the rear delay is L / v.
    rear
        ``"pade"``: h_B is h_A through the Padé approximant of order ``pade_order`` (inputs
        ``nu_road``; two axles only); ``"independent"``: every axle behind the front one has
        its own independent filter of the same PSD (inputs ``nu_road``, ``nu_rear``, then
        ``nu_rear_<axle>`` for a third axle on), the limit of the exact delay where ωL/v ≫ 1.
    axles
        The machine's axle points, front first (two or more); the outputs are each axle's
        ``w_<axle>y`` and ``wd_<axle>y``.

    Returns
    -------
    control.StateSpace
        Outputs :data:`ROAD_OUTPUTS` for axles A and B (``w_<axle>y``, ``wd_<axle>y`` per
        axle in general); states ``h_<axle>`` per axle or ``h_A`` then the Padé states.
    """
    import control

    a, q = road_filter_coefficients(road_class, speed_m_s)
    if not (math.isfinite(wheelbase_m) and 0.1 <= wheelbase_m <= 10.0):
        raise ValueError(f"wheelbase = {wheelbase_m!r} m; allowed: 0.1 to 10 m")
    axles = tuple(axles)
    if (
        len(axles) < 2
        or len(set(axles)) != len(axles)
        or not all(isinstance(n, str) for n in axles)
    ):
        raise ValueError(f"axles = {axles!r}; allowed: two or more distinct axle names")
    outputs = [f"{kind}_{axle}y" for axle in axles for kind in ("w", "wd")]
    if rear == "independent":
        count = len(axles)
        c_matrix = np.zeros((2 * count, count))
        d_matrix = np.zeros((2 * count, count))
        for i in range(count):
            c_matrix[2 * i, i], c_matrix[2 * i + 1, i] = 1.0, -a
            d_matrix[2 * i + 1, i] = q
        noise = ["nu_road", "nu_rear", *(f"nu_rear_{axle}" for axle in axles[2:])]
        return control.ss(
            -a * np.eye(count),
            q * np.eye(count),
            c_matrix,
            d_matrix,
            inputs=noise,
            outputs=outputs,
            states=[f"h_{axle}" for axle in axles],
            name="road",
        )
    if rear != "pade":
        raise ValueError(f"rear = {rear!r}; allowed: 'independent', 'pade'")
    if len(axles) != 2:
        raise ValueError(
            f"rear = 'pade' delays one rear axle; the machine has {len(axles)} axles "
            f"({', '.join(axles)}): use rear = 'independent'"
        )
    if not isinstance(pade_order, int) or not 1 <= pade_order <= 8:
        raise ValueError(f"pade_order = {pade_order!r}; allowed: an integer 1 to 8")
    delay = control.ss(control.tf(*control.pade(wheelbase_m / speed_m_s, pade_order)))
    a_p, b_p, c_p, d_p = (
        np.atleast_2d(np.asarray(m, dtype=float)) for m in (delay.A, delay.B, delay.C, delay.D)
    )
    n = a_p.shape[0]
    a_all = np.block([[np.array([[-a]]), np.zeros((1, n))], [b_p, a_p]])
    b_all = np.vstack([[[q]], np.zeros((n, 1))])
    c_all = np.vstack(
        [
            np.hstack([[[1.0]], np.zeros((1, n))]),
            np.hstack([[[-a]], np.zeros((1, n))]),
            np.hstack([d_p, c_p]),
            np.hstack([c_p @ b_p - d_p * a, c_p @ a_p]),
        ]
    )
    d_all = np.array([[0.0], [q], [0.0], [float(d_p[0, 0]) * q]])
    return control.ss(
        a_all,
        b_all,
        c_all,
        d_all,
        inputs=["nu_road"],
        outputs=outputs,
        states=[f"h_{axles[0]}", *(f"pade_{i}" for i in range(n))],
        name="road",
    )
