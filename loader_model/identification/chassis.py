r"""Cylinder force that moves the boom on the moving chassis (Eq. 44 with chassis sensors).

The fixed-base load model of :mod:`.equivalent` takes the chassis at rest. On its tyres the
chassis heaves and pitches under the moving boom, and the boom's inertial and gravity load
changes with it. The machine of section 3.3 carries the sensors to measure that: a triaxial
accelerometer at H (specific force f_Hx, f_Hy along the chassis axes), a vertical one at N
(f_Ny) and the chassis pitch θ1. With those, the boom's own equation of motion (row θ2 of the
generated model, Eq. 25) gives the total cylinder force, with no tyre force in it (the tyres act
on the chassis only):

.. math::

    F_{act}\, Q_{act,\theta_2} = M_{\theta_2,:}(p)\, \ddot p + C_{\theta_2}(p, \dot p)
    - Q_{g,\theta_2}(p)

with p = (x_H, y_H, θ1, θ1 + ψ), ψ the boom turn from the operating angle that puts the
piston at x, ψ̇ = ẋ/h, ψ̈ = (ẍ − h' ψ̇²)/h (h = dx_cyl/dφ, Eq. 35), and the chassis accelerations
(ẍ_H, ÿ_H, θ̈1) solved from the three specific forces, which are affine in p̈
(``specific_forces`` of the generated model). Everything is composed from the generated
functions (``mass_matrix``, ``coriolis_centrifugal``, ``gravity_forces``, ``actuator_map``,
``cylinder_kinematics``, ``specific_forces``); nothing of the model is written again here.
The plant's x_H, y_H, ẋ_H, ẏ_H do not enter the boom row (translation invariance; a test
checks it), so they are passed as 0.

:func:`boom_forces` returns the gravity part −Q_g/Q_act (a function of positions only) and the
dynamic part (M p̈ + C)/Q_act separately, so that :mod:`.pipeline` can filter each like the
signals it comes from.
"""

from __future__ import annotations

import dataclasses
from functools import cache

import casadi as ca
import numpy as np

import loader_model_generated as generated
from loader_model.parameters.schema import BucketLoad, LoaderParameters

__all__ = ["boom_forces", "boom_turn", "mechanical_parameter_columns"]

_N_MECH = len(generated.PARAMETER_NAMES)


@cache
def _functions() -> tuple[ca.Function, ca.Function]:
    """(kinematics: ψ -> x_cyl, h; forces: signals -> gravity part, dynamic part), SX."""
    f = generated.function
    params = ca.SX.sym("params", _N_MECH)
    theta, psi, thetad, v, a = (ca.SX.sym(n) for n in ("theta", "psi", "thetad", "v", "a"))
    specific = ca.SX.sym("f", 3)  # f_Hx, f_Hy, f_Ny
    p = ca.vertcat(0, 0, theta, theta + psi)
    x_cyl, _, lever, _ = f("cylinder_kinematics")(p, ca.SX.zeros(4), params)
    kinematics = ca.Function("boom_kinematics", [psi, params], [x_cyl, lever])
    slope = ca.jacobian(lever, psi)
    psid = v / lever
    psidd = (a - slope * psid**2) / lever
    pd = ca.vertcat(0, 0, thetad, thetad + psid)
    chassis = ca.SX.sym("chassis", 3)  # ẍ_H, ÿ_H, θ̈1
    pdd = ca.vertcat(chassis, chassis[2] + psidd)
    f_h, f_n, _ = f("specific_forces")(p, pd, pdd, params)
    read = ca.vertcat(f_h[0], f_h[1], f_n[1])
    jac = ca.jacobian(read, chassis)  # read is affine in the chassis accelerations
    offset = ca.substitute(read, chassis, ca.SX.zeros(3))
    solved = ca.solve(jac, specific - offset)
    pdd = ca.substitute(pdd, chassis, solved)
    mass = f("mass_matrix")(p, params)
    coriolis = f("coriolis_centrifugal")(p, pd, params)
    gravity = f("gravity_forces")(p, params)
    q_act = f("actuator_map")(p, params)[3]
    forces = ca.Function(
        "boom_forces",
        [theta, psi, thetad, v, a, specific, params],
        [-gravity[3] / q_act, (mass[3, :] @ pdd + coriolis[3]) / q_act],
        ["theta_1", "psi", "thetad_1", "v", "a", "f", "params"],
        ["F_gravity", "F_dynamic"],
    )
    return kinematics, forces


def mechanical_parameter_columns(
    loader: LoaderParameters, load: BucketLoad, masses: np.ndarray
) -> np.ndarray:
    """Model parameter vectors (``complete_parameters``), one column per load mass in kg.

    Each mass is a bucket load with the centre of gravity and the inertia per kg of ``load``,
    combined with the boom (:func:`loader_model.parameters.sets.model_parameter_values`); distinct
    masses are computed once.
    """
    from loader_model.parameters.sets import model_parameter_values

    unique, index = np.unique(np.asarray(masses, dtype=float), return_inverse=True)
    complete = generated.function("complete_parameters")
    columns = []
    for mass in unique:
        case = dataclasses.replace(load, mass=float(mass), inertia=load.inertia * mass / load.mass)
        values = model_parameter_values(loader, case) | {"F_Ay0": 0.0, "F_By0": 0.0}
        vector = np.array([float(values[n]) for n in generated.PARAMETER_NAMES])
        columns.append(np.asarray(complete(vector)[0], dtype=float).ravel())
    return np.column_stack(columns)[:, index]


def boom_turn(
    position_m: np.ndarray, retracted_m: float, params: np.ndarray, start: np.ndarray
) -> np.ndarray:
    """ψ in rad that puts the piston at ``position_m`` (Newton on the generated x_cyl(ψ)).

    ``start`` is a first guess per sample (:meth:`.equivalent.EquivalentCylinder` gives the
    closed form); four Newton steps take it to the generated model's geometry (measured:
    |x_cyl(ψ) − L_r − x| below 1e-15 m after two).
    """
    kinematics = _functions()[0].map(np.size(position_m))
    psi = np.asarray(start, dtype=float)
    for _ in range(4):
        length, lever = (np.asarray(o, dtype=float).ravel() for o in kinematics(psi, params))
        psi = psi - (length - retracted_m - position_m) / lever
    return psi


def boom_forces(
    theta_1: np.ndarray,
    psi: np.ndarray,
    thetad_1: np.ndarray,
    velocity: np.ndarray,
    acceleration: np.ndarray,
    specific_forces: np.ndarray,
    params: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Gravity and dynamic parts of the cylinder force that moves the boom, in N.

    Parameters
    ----------
    theta_1, psi : numpy.ndarray
        Chassis pitch θ1 and boom turn ψ (:func:`boom_turn`) in rad, shape (n,).
    thetad_1 : numpy.ndarray
        Pitch rate θ̇1 in rad/s.
    velocity, acceleration : numpy.ndarray
        Piston velocity ẋ in m/s and acceleration ẍ in m/s².
    specific_forces : numpy.ndarray
        (n, 3): f_Hx, f_Hy, f_Ny in m/s² along the chassis axes (at rest: g sin θ1, g cos θ1).
    params : numpy.ndarray
        (n_params, n) from :func:`mechanical_parameter_columns`.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        −Q_g/Q_act and (M p̈ + C)/Q_act at the θ2 row; their sum is F_act (module docstring).
    """
    n = np.size(psi)
    forces = _functions()[1].map(n)
    gravity, dynamic = forces(
        theta_1, psi, thetad_1, velocity, acceleration, np.asarray(specific_forces).T, params
    )
    return np.asarray(gravity, dtype=float).ravel(), np.asarray(dynamic, dtype=float).ravel()
