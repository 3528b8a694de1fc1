r"""Lift-cylinder chamber volumes and hydraulic stiffness (paper section 2.3, Eq. 28, 30).

The cylinders are single-rod and double-acting (Fig. 8), ``count`` of them in parallel, all at
the same pin-to-pin length. The piston position is measured from the retracted end stop,

.. math::

    x_p = L - L_r, \qquad 0 \le x_p \le s,

with L the pin-to-pin length, L_r the retracted length and s the stroke. Volumes are per
cylinder and include the dead (line) volume of each chamber.
"""

from __future__ import annotations

import math
from typing import Any

from loader_model.parameters.schema import CylinderParameters, HydraulicParameters

__all__ = [
    "area_ratio",
    "chamber_volumes_m3",
    "hydraulic_stiffness_n_per_m",
    "oil_column_stiffness_n_per_m",
    "piston_position_m",
]


def static_piston_pressure(
    force_n: Any, count: Any, piston_diameter_m: Any, rod_diameter_m: Any, charge_pressure_pa: Any
) -> Any:
    r"""Piston-side pressure that holds the total cylinder force at rest, rod side at charge.

    .. math:: p_{A0} = \frac{F_{act0} + n \alpha A_p p_c}{n A_p}, \qquad
        A_p = \frac{\pi}{4} d_p^2, \quad \alpha A_p = A_p - \frac{\pi}{4} d_r^2

    (force balance of Eq. 15 over the n cylinders, friction and end stops zero at rest). Works on
    floats and on CasADi expressions: the plant's equilibrium and the parameter checks use it.

    Parameters
    ----------
    force_n
        Total static force of the cylinders, N (pushing positive).
    count, piston_diameter_m, rod_diameter_m, charge_pressure_pa
        Number of cylinders, bore and rod diameters in m, rod-side (charge) pressure in Pa.

    Returns
    -------
    float or casadi expression
        p_A0 in Pa (gauge).
    """
    piston = math.pi / 4 * piston_diameter_m**2
    annulus = piston - math.pi / 4 * rod_diameter_m**2
    return (force_n + count * annulus * charge_pressure_pa) / (count * piston)


def area_ratio(cylinders: CylinderParameters) -> float:
    r"""Piston area ratio α of Eq. 30.

    .. math:: \alpha = \frac{A_p - A_r}{A_p}

    Parameters
    ----------
    cylinders : CylinderParameters

    Returns
    -------
    float
        Ratio of the rod-side annulus area to the piston area, in (0, 1).
    """
    return cylinders.annulus_area / cylinders.piston_area


def piston_position_m(cylinders: CylinderParameters, cylinder_length_m: float) -> float:
    """Piston position x_p = L − L_r in m, measured from the retracted end stop.

    Raises
    ------
    ValueError
        If the pin-to-pin length lies outside [L_r, L_r + stroke].
    """
    position = float(cylinder_length_m) - cylinders.retracted_length
    if not 0.0 <= position <= cylinders.stroke:
        low = cylinders.retracted_length
        raise ValueError(
            f"cylinder length {cylinder_length_m!r} m is outside the stroke "
            f"[{low:g}, {low + cylinders.stroke:g}] m"
        )
    return position


def chamber_volumes_m3(
    cylinders: CylinderParameters, cylinder_length_m: float
) -> tuple[float, float]:
    r"""Piston-side and rod-side volumes of one cylinder at a pin-to-pin length (Eq. 36, 37).

    .. math::

        V_A = A_p x_p + V_{A,dead}, \qquad V_B = (A_p - A_r)(s - x_p) + V_{B,dead}

    Parameters
    ----------
    cylinders : CylinderParameters
    cylinder_length_m : float
        Pin-to-pin length L in m.

    Returns
    -------
    (float, float)
        ``(V_A, V_B)`` in m³ per cylinder.

    Raises
    ------
    ValueError
        If the length lies outside the stroke (see :func:`piston_position_m`).
    """
    x_p = piston_position_m(cylinders, cylinder_length_m)
    v_a = cylinders.piston_area * x_p + cylinders.dead_volume_a
    v_b = cylinders.annulus_area * (cylinders.stroke - x_p) + cylinders.dead_volume_b
    return v_a, v_b


def hydraulic_stiffness_n_per_m(
    cylinders: CylinderParameters, hydraulics: HydraulicParameters, cylinder_length_m: float
) -> float:
    r"""Equivalent linear stiffness k_eq of the oil columns of all cylinders, in N/m.

    .. math::

        k_{eq} = n_{cyl} K_{oil} A_p^2 \left(\frac{1}{V_A} + \frac{\alpha^2}{V_B}\right)

    Eq. 28 of the paper keeps only the piston side; a single-rod cylinder also compresses the
    rod side through the annulus α A_p (Eq. 30, 37), which adds the α² / V_B term
    (errata 6). Both chambers are taken as closed (pump and charge line blocked), and the
    ``n_cyl`` cylinders act in parallel.

    Parameters
    ----------
    cylinders : CylinderParameters
    hydraulics : HydraulicParameters
        Supplies the bulk modulus K_oil (Table 5).
    cylinder_length_m : float
        Pin-to-pin length in m.

    Returns
    -------
    float
        k_eq in N/m along the cylinder axis.
    """
    return oil_column_stiffness_n_per_m(cylinders, hydraulics.bulk_modulus, cylinder_length_m)


def oil_column_stiffness_n_per_m(
    cylinders: CylinderParameters, bulk_modulus_pa: float, cylinder_length_m: float
) -> float:
    """k_eq of :func:`hydraulic_stiffness_n_per_m` from the bulk modulus alone, in N/m (for a
    machine whose parameter file gives only the hydraulics the spring needs)."""
    v_a, v_b = chamber_volumes_m3(cylinders, cylinder_length_m)
    alpha = area_ratio(cylinders)
    return (
        cylinders.count * bulk_modulus_pa * cylinders.piston_area**2 * (1.0 / v_a + alpha**2 / v_b)
    )
