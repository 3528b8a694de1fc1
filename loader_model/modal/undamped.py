"""Undamped mass and stiffness matrices of Eq. 27 for the modal analysis (paper section 2.2).

Taken from the plant (one model): :func:`loader_model.plant.linear.undamped_matrices_from_plant`
linearises the plant Function with the chambers closed as Eq. 28 assumes (pump at zero
displacement, valves shut, no leakage or friction). M is the generated mass matrix at p = 0
(Eq. 32); K holds the tyres, the closed oil columns of the lift cylinders (Eq. 28 with the area
ratio, errata 6: k_eq (dx_cyl/dφ)² on [[1, −1], [−1, 1]] over (θ1, θ2), errata 5) and, unless
``gravity_stiffness=False``, the small geometric stiffness of gravity and the static loads, which
the paper drops. ``tests/test_plant_modes.py`` checks K against the closed form of Eq. 28.

Another described machine (:mod:`loader_model.machines`) has no plant yet:
:func:`machine_undamped_matrices` takes M and K = ∂r/∂p of its generated residual at rest (the
tyres, gravity, and every locked cylinder as the spring of the generated internal forces, with its
static preload) and adds the lift cylinders' hydraulic spring k_eq Q_act Q_actᵀ of Eq. 28
(errata 6) along the generated actuator map, which is k_eq (dx_cyl/dφ)² on [[1, −1], [−1, 1]]
over (θ1, θ2) for the skid-steer. For the skid-steer both routes agree (a test).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

import loader_model_generated as _generated
from loader_model.machines import MachineInfo
from loader_model.parameters.machine_files import MachineParameters, resolve_machine_parameters
from loader_model.parameters.sets import BucketLoad, LoaderParameters
from loader_model.vehicle.cylinder import (
    hydraulic_stiffness_n_per_m,
    oil_column_stiffness_n_per_m,
)
from loader_model.vehicle.statics import resolve_machine_values

__all__ = ["UndampedMatrices", "machine_undamped_matrices", "undamped_matrices"]

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
    coordinate_names: tuple[str, ...] = _generated.COORDINATE_NAMES
    """Names of the rows and columns (the machine's generalised coordinates)."""


def undamped_matrices(
    loader: LoaderParameters, load: BucketLoad, *, gravity_stiffness: bool = True
) -> UndampedMatrices:
    """M and K (Eq. 27) of ``loader`` with the bucket ``load`` at its static equilibrium.

    Parameters
    ----------
    loader, load
        Validated parameter sets (see :mod:`loader_model.parameters.sets`).
    gravity_stiffness
        Keep the geometric stiffness of gravity and the static loads (physical); ``False`` drops
        it by setting g = 0, as the paper's Eq. 33-34 do.
    """
    from loader_model.plant.linear import undamped_matrices_from_plant
    from loader_model.plant.plant_parameters import (
        PLANT_PARAMETER_NAMES,
        PlantOptions,
        plant_parameter_vector,
    )

    params = plant_parameter_vector(loader, load, PlantOptions.closed())
    mass, stiffness, k_eq = undamped_matrices_from_plant(params)
    if not gravity_stiffness:
        stiffness = stiffness - _gravity_stiffness(params[: len(PLANT_PARAMETER_NAMES)])
    lever = float(_lever(params))
    # the closed form of Eq. 28 (errata 6) at the same operating point, as a cross-check
    x_cyl = loader.cylinders.retracted_length + _piston_position(params)
    expected = hydraulic_stiffness_n_per_m(loader.cylinders, loader.hydraulics, x_cyl)
    if not np.isclose(k_eq, expected, rtol=1e-9):
        raise RuntimeError(f"plant k_eq {k_eq:.6g} N/m differs from Eq. 28: {expected:.6g} N/m")
    return UndampedMatrices(mass, stiffness, float(k_eq), lever)


def _gravity_stiffness(params: np.ndarray) -> np.ndarray:
    """Geometric stiffness of gravity and the static loads (which the paper drops): the change
    of −M ∂p̈/∂p of the generated linearisation (linear tyres, constant cylinder force) when g
    goes to 0. The plant itself cannot drop g: its tyres would lose their static load."""
    import loader_model_generated as generated
    from loader_model.vehicle.dynamics import LoaderDynamics

    names = generated.PARAMETER_NAMES
    values = dict(zip(names, params[: len(names)], strict=True))
    rows, columns = [1, 3, 5, 7], [0, 2, 4, 6]
    stiffness = []
    for gravity in (values["g"], 0.0):
        model = LoaderDynamics(values | {"g": gravity})
        mass = model.mass_matrix(np.zeros(4))
        stiffness.append(-mass @ model.linearise().A[np.ix_(rows, columns)])
    difference = stiffness[0] - stiffness[1]
    return 0.5 * (difference + difference.T)


def _lever(params: np.ndarray) -> float:
    import loader_model_generated as generated

    completed, _ = generated.function("complete_parameters")(
        params[: len(generated.PARAMETER_NAMES)]
    )
    return float(generated.function("cylinder_kinematics")(np.zeros(4), np.zeros(4), completed)[2])


def _piston_position(params: np.ndarray) -> float:
    from loader_model.plant.equilibrium import static_state
    from loader_model.plant.plant import OUTPUT_NAMES, plant_function

    state, command = static_state(params)
    _, outputs = plant_function()(state, command, np.zeros(11), params)
    return float(np.asarray(outputs).ravel()[OUTPUT_NAMES.index("x_piston")])


def machine_undamped_matrices(
    info: MachineInfo,
    params: MachineParameters | str | Path | None = None,
    load: str | None = None,
    *,
    gravity_stiffness: bool = True,
) -> UndampedMatrices:
    """M and K (Eq. 27) of a described machine at its static equilibrium, from its generated code.

    Parameters
    ----------
    info
        The machine resolved (:func:`loader_model.machines.machine`).
    params
        Its parameter set, a path to its flat parameter file, or None for the shipped values
        (:mod:`loader_model.parameters.machine_files`).
    load
        A load case of the parameter file (None: its ``[model]`` values).
    gravity_stiffness
        Keep the geometric stiffness of gravity and the static loads; ``False`` takes K at g = 0
        (no static loads or preloads), as the paper's Eq. 33-34 do.

    Raises
    ------
    ValueError
        If the parameters are invalid or the machine does not stand
        (:func:`loader_model.vehicle.statics.resolve_machine_values`).
    """
    params = resolve_machine_parameters(info, params)
    values = resolve_machine_values(info, params, load)
    if not gravity_stiffness:
        values = values | {"g": 0.0}
    completed, force = info.function("complete_parameters")(
        [values[n] for n in info.parameter_names]
    )
    zeros, road = np.zeros(info.n_coordinates), np.zeros(len(info.road_names))
    jacobians = info.function("residual_jacobians")(
        zeros, zeros, zeros, force, road, road, np.zeros(len(info.disturbance_names)), completed
    )
    actuator = np.asarray(info.function("actuator_map")(zeros, completed)).ravel()
    x_cyl, _, lever, _ = (
        float(v) for v in info.function("cylinder_kinematics")(zeros, zeros, completed)
    )
    k_eq = oil_column_stiffness_n_per_m(params.cylinders, params.hydraulics["bulk_modulus"], x_cyl)
    stiffness = np.asarray(jacobians[1]) + k_eq * np.outer(actuator, actuator)
    mass = np.asarray(info.function("mass_matrix")(zeros, completed))
    return UndampedMatrices(
        0.5 * (mass + mass.T),
        0.5 * (stiffness + stiffness.T),
        float(k_eq),
        lever,
        info.coordinate_names,
    )
