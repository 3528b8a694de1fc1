"""Undamped mass and stiffness matrices of Eq. 27 for the modal analysis (paper section 2.2).

M is the generated mass matrix at p = 0 (Eq. 32). K has two parts:

* the tyres (and, unless ``gravity_stiffness=False``, the small geometric stiffness of gravity and
  the static tyre and cylinder loads, which the paper drops): ``K = −M ∂p̈/∂p`` from the generated
  linearisation with the cylinder force held constant (Eq. 33-34 with DESIGN.md errata 5);
* the lift cylinders as a hydraulic spring (Eq. 28 with the area ratio, errata 6):
  ``k_eq (dx_cyl/dφ)²`` on ``[[1, −1], [−1, 1]]`` over (θ1, θ2) (errata 5), with ``dx_cyl/dφ``
  (Eq. 35) and the chamber volumes at the operating point from the generated kinematics.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from loader_model.cylinder import hydraulic_stiffness_n_per_m
from loader_model.dynamics import LoaderDynamics
from loader_model.parameters import BucketLoad, LoaderParameters, model_parameter_values

__all__ = ["UndampedMatrices", "undamped_matrices"]

_ACCELERATION_ROWS = [1, 3, 5, 7]
_POSITION_COLUMNS = [0, 2, 4, 6]


@dataclass(frozen=True)
class UndampedMatrices:
    """M and K of M p̈ + K p = 0 (Eq. 27) and what K is made of."""

    mass: np.ndarray
    stiffness: np.ndarray
    hydraulic_stiffness_n_per_m: float
    """k_eq of both cylinders together (Eq. 28, corrected for the area ratio)."""
    cylinder_lever_m_per_rad: float
    """dx_cyl/dφ at the operating point (Eq. 35)."""


def undamped_matrices(
    loader: LoaderParameters, load: BucketLoad, *, gravity_stiffness: bool = True
) -> UndampedMatrices:
    """M and K (Eq. 27) of ``loader`` with the bucket ``load`` at its static equilibrium.

    Parameters
    ----------
    loader, load
        Validated parameter sets (see :mod:`loader_model.parameters`).
    gravity_stiffness
        Keep the geometric stiffness of gravity and the static loads (physical); ``False`` drops
        it by setting g = 0, as the paper's Eq. 33-34 do.
    """
    values = model_parameter_values(loader, load)
    if not gravity_stiffness:
        values["g"] = 0.0
    model = LoaderDynamics(values)
    mass = model.mass_matrix(np.zeros(4))
    acceleration = model.linearise().A[np.ix_(_ACCELERATION_ROWS, _POSITION_COLUMNS)]
    stiffness = -mass @ acceleration
    cylinder = model.cylinder_kinematics(np.zeros(4))
    k_eq = hydraulic_stiffness_n_per_m(loader.cylinders, loader.hydraulics, cylinder["x_cyl"])
    lever = cylinder["dx_cyl_dphi"]
    stiffness[2:, 2:] += k_eq * lever**2 * np.array([[1.0, -1.0], [-1.0, 1.0]])
    # the linearised K is symmetric up to round-off (a conservative system at rest)
    stiffness = 0.5 * (stiffness + stiffness.T)
    return UndampedMatrices(mass, stiffness, float(k_eq), float(lever))
