"""The road classes of ISO 8608: the displacement PSD G_d(n) = G_d(n_0) (n / n_0)^(−w).

Data of the standard, used by the simulated roads (:mod:`loader_model.simulation.iso8608`) and
by the road filter of the comfort design (:mod:`loader_model.control.road_filter`).
"""

from __future__ import annotations

__all__ = [
    "CLASS_PSD_M3",
    "ISO8608_BAND_CYCLES_M",
    "REFERENCE_SPATIAL_FREQUENCY_CYCLES_M",
    "WAVINESS",
]

#: n_0 of ISO 8608 in cycles/m.
REFERENCE_SPATIAL_FREQUENCY_CYCLES_M = 0.1
#: Exponent w of the fitted PSD (ISO 8608 classification uses w = 2).
WAVINESS = 2.0
#: Spatial frequency band of ISO 8608 in cycles/m.
ISO8608_BAND_CYCLES_M = (0.011, 2.83)
#: Geometric mean of G_d(n_0) per class in m³ (ISO 8608, table of road classes).
CLASS_PSD_M3 = {letter: 16e-6 * 4.0**index for index, letter in enumerate("ABCDEFGH")}
