"""Names and sizes of the plant of one described machine.

The plant of :mod:`loader_model.plant.plant` is the same for every machine of
:mod:`loader_model.machines`: its generated multibody model, the lift cylinder group driven by
the pump's closed circuit, the seated occupant at the machine's seat point. Only the sizes and
names change with the machine; :func:`plant_layout` gives them, and for the default skid-steer
they are exactly those of the paper's plant (the module constants ``STATE_NAMES``, ... of
:mod:`loader_model.plant.plant`)::

    x = (p, ṗ, ξ, p_A, p_B, V_p, V̇_p, V_acc, occupant)
    y = (ẋ_H, ẏ_H, θ̇1, φ, <further joint angles>, f_<sensor><axis>..., θ̈1, p_A, p_B, F_act,
         x_piston, V_p, Q_pump, F_<axle>y..., p_acc, f_Px, f_Py)

φ is the boom's angle to the chassis (the first pinned body); a machine with further pinned
bodies (the wheel loader's bucket, ψ) adds their joint angles after it. The specific forces are
those of the description's sensor points, in its order and axes.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

from loader_model.machines import DEFAULT_MACHINE, MachineInfo, machine
from loader_model.plant.occupant import OCCUPANT_PARAMETERS, OCCUPANT_STATE_NAMES

__all__ = ["HYDRAULIC_STATE_NAMES", "PlantLayout", "plant_layout"]

#: Hydraulic states after the mechanical ones (chamber pressures, pump displacement, accumulator).
HYDRAULIC_STATE_NAMES: tuple[str, ...] = ("p_A", "p_B", "V_p", "Vd_p", "V_acc")
_DRIVE_OUTPUTS = ("thetadd_1", "p_A", "p_B", "F_act", "x_piston", "V_p", "Q_pump")


@dataclass(frozen=True)
class PlantLayout:
    """Sizes and names of the plant of one machine (module notes).

    Attributes
    ----------
    machine : MachineInfo
        The machine's registry entry.
    state_names, input_names, exogenous_names, output_names, parameter_names : tuple of str
        Orders of x, u, w, y and the parameter vector θ.
    sensor_outputs : tuple of (str, int, int)
        For every specific-force output: its name, the index of the generated
        ``specific_forces`` output and the axis (0: x, 1: y).
    """

    machine: MachineInfo
    state_names: tuple[str, ...]
    input_names: tuple[str, ...]
    exogenous_names: tuple[str, ...]
    output_names: tuple[str, ...]
    parameter_names: tuple[str, ...]
    sensor_outputs: tuple[tuple[str, int, int], ...]

    @property
    def n_coordinates(self) -> int:
        """Number of generalised coordinates p."""
        return self.machine.n_coordinates

    @property
    def n_anchors(self) -> int:
        """Number of tyre anchor states ξ (one per axle)."""
        return len(self.machine.anchor_names)

    @property
    def n_mechanical(self) -> int:
        """Number of generated model parameters at the start of θ."""
        return len(self.machine.parameter_names)

    @property
    def n_hydraulic_end(self) -> int:
        """Index of the first occupant state (the states before it: mechanics and hydraulics)."""
        return self.state_names.index(OCCUPANT_STATE_NAMES[0])

    @property
    def seat_sensor(self) -> int:
        """Index of the seat point's output of the generated ``specific_forces``."""
        return list(self.machine.sensor_points).index(self.machine.seat_point)

    def index(self, name: str) -> int:
        """Index of state ``name`` (ValueError naming the allowed states otherwise)."""
        if name not in self.state_names:
            raise ValueError(f"unknown plant state {name!r}; allowed: {list(self.state_names)}")
        return self.state_names.index(name)


def _joint_outputs(info: MachineInfo) -> tuple[str, ...]:
    angles = info.joint_angles or ("phi",)
    return angles if angles[0] == "phi" else ("phi", *angles[1:])


@functools.cache
def plant_layout(name: str = DEFAULT_MACHINE) -> PlantLayout:
    """The plant layout of machine ``name`` (:func:`loader_model.machines.machine`; cached).

    Raises
    ------
    ValueError
        For an unknown machine, or one without the sensor at its seat point.
    """
    from loader_model.plant.plant_parameters import HYDRAULIC_PARAMETERS

    info = machine(name)
    if info.seat_point not in info.sensor_points:
        raise ValueError(
            f"machine {info.name!r}: its seat point {info.seat_point!r} has no sensor; the "
            "occupant sits on a sensor point of the description ([sensors])"
        )
    sensors = tuple(
        (f"f_{point}{axis}", k, "xy".index(axis))
        for k, (point, axes) in enumerate(info.sensor_points.items())
        for axis in axes
    )
    states = (
        *info.coordinate_names,
        *info.rate_names,
        *info.anchor_names,
        *HYDRAULIC_STATE_NAMES,
        *OCCUPANT_STATE_NAMES,
    )
    outputs = (
        "xd_H",
        "yd_H",
        "thetad_1",
        *_joint_outputs(info),
        *(item[0] for item in sensors),
        *_DRIVE_OUTPUTS,
        *(f"F_{axle}y" for axle in info.axles),
        "p_acc",
        "f_Px",
        "f_Py",
    )
    parameters = info.parameter_names + tuple(
        item[0] for item in HYDRAULIC_PARAMETERS + OCCUPANT_PARAMETERS
    )
    return PlantLayout(
        machine=info,
        state_names=states,
        input_names=("V_p_ref",),
        exogenous_names=info.exogenous_names,
        output_names=outputs,
        parameter_names=parameters,
        sensor_outputs=sensors,
    )
