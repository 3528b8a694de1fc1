"""ISO 2631-1:1997 Annex C (informative): likely reactions to a total vibration value in public
transport, the scale the reproduce report sets the simulated a_total beside.

Annex C.2.3 gives overlapping ranges of the overall vibration total value (Eq. 50 with the
comfort k factors; the paper uses k = 1, 1, 0.4, section 5.3) and says that the reactions at a
given magnitude depend on passengers' expectations of trip duration and activity:

==========================  ==============================
overall total value [m/s²]  likely reaction
==========================  ==============================
below 0.315                 not uncomfortable
0.315 to 0.63               a little uncomfortable
0.5 to 1                    fairly uncomfortable
0.8 to 1.6                  uncomfortable
1.25 to 2.5                 very uncomfortable
greater than 2              extremely uncomfortable
==========================  ==============================

A value inside an overlap gets both neighbouring reactions ("uncomfortable to very
uncomfortable"); the bounds belong to the range they open (0.315 is "a little uncomfortable").
"""

from __future__ import annotations

import math

__all__ = ["COMFORT_SCALE", "comfort_reaction"]

#: Annex C.2.3 ranges: (lower bound, upper bound, reaction), in m/s² (r.m.s., weighted).
COMFORT_SCALE: tuple[tuple[float, float, str], ...] = (
    (0.0, 0.315, "not uncomfortable"),
    (0.315, 0.63, "a little uncomfortable"),
    (0.5, 1.0, "fairly uncomfortable"),
    (0.8, 1.6, "uncomfortable"),
    (1.25, 2.5, "very uncomfortable"),
    (2.0, math.inf, "extremely uncomfortable"),
)


def comfort_reaction(total_m_s2: float) -> str:
    """The likely reaction of ISO 2631-1 Annex C.2.3 to an overall total value.

    Parameters
    ----------
    total_m_s2 : float
        Overall vibration total value a_v (Eq. 50) in m/s², finite and >= 0.

    Returns
    -------
    str
        One reaction, or the two of an overlap joined by "to" (module table).

    Raises
    ------
    ValueError
        If ``total_m_s2`` is not a finite number >= 0.
    """
    if isinstance(total_m_s2, bool) or not isinstance(total_m_s2, int | float):
        raise ValueError(f"total_m_s2 must be a number in m/s^2; got {total_m_s2!r}")
    value = float(total_m_s2)
    if not (math.isfinite(value) and value >= 0.0):
        raise ValueError(f"total_m_s2 must be finite and >= 0 m/s^2; got {value!r}")
    reactions = [name for low, high, name in COMFORT_SCALE if low <= value < high]
    return " to ".join(reactions)
