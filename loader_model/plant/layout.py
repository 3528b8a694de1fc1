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

The lift circuit (the description's ``[circuit] kind``) names the actuator: the pump's
displacement V_p [m³/rev] and its rate, command ``V_p_ref``, limit ``V_p_max``; or a valve's
spool position x_s [m] and its rate, command ``x_s_ref``, limit the spool stroke ``x_s_max``
(:mod:`loader_model.plant.valve_circuit`), output ``Q_supply`` in place of ``Q_pump``. The
lengths and orders of x, u and y are the same for both.

φ is the boom's angle to the chassis (the first pinned body); a machine with further pinned
bodies (the wheel loader's bucket, ψ) adds their joint angles after it. The specific forces are
those of the description's sensor points, in its order and axes.

A :class:`PlantLayout` is the machine resolved once: its registry entry (description, generated
functions, tyre and parameter metadata: :class:`~loader_model.machines.MachineInfo`), its lift
circuit and the plant's names and sizes. The command line and the public entry points resolve a
machine name or description file once (:func:`plant_layout`, :func:`resolve_layout`); the
scenario (:class:`~loader_model.plant.scenario.PlantScenario`) carries the layout, and everything
below takes it (or its :attr:`PlantLayout.machine`) instead of a name. A layout pickles as its
machine's source and hash and its circuit, so a worker process resolves it again through the
verified machine registry.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any

from loader_model.machines import DEFAULT_MACHINE, MachineInfo, machine
from loader_model.plant.occupant import OCCUPANT_PARAMETERS, OCCUPANT_STATE_NAMES

__all__ = [
    "CIRCUITS",
    "HYDRAULIC_STATE_NAMES",
    "SKID_STEER",
    "MachineSource",
    "PlantLayout",
    "machine_layout",
    "plant_layout",
    "resolve_layout",
]

#: Hydraulic states after the mechanical ones (chamber pressures, pump displacement, accumulator).
HYDRAULIC_STATE_NAMES: tuple[str, ...] = ("p_A", "p_B", "V_p", "Vd_p", "V_acc")
#: Per circuit kind: (actuator state, its rate, command, command limit, rate limit, flow output).
CIRCUITS: dict[str, tuple[str, str, str, str, str, str]] = {
    "pump": ("V_p", "Vd_p", "V_p_ref", "V_p_max", "Vd_p_max", "Q_pump"),
    "valve": ("x_s", "xd_s", "x_s_ref", "x_s_max", "xd_s_max", "Q_supply"),
}


@dataclass(frozen=True, eq=False)
class PlantLayout:
    """Sizes and names of the plant of one machine: the machine resolved once (module notes).

    Two layouts are equal when their machines (name and description hash) and circuits are.

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
    circuit: str = "pump"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, PlantLayout):
            return NotImplemented
        return (self.machine, self.circuit) == (other.machine, other.circuit)

    def __hash__(self) -> int:
        return hash((self.machine, self.circuit))

    def __reduce__(self) -> tuple[Any, tuple[MachineInfo, str]]:
        return machine_layout, (self.machine, self.circuit)

    @property
    def name(self) -> str:
        """The machine's name (:attr:`MachineInfo.name`)."""
        return self.machine.name

    @property
    def is_default(self) -> bool:
        """True for the paper's skid-steer with its pump circuit."""
        return self.machine.is_default and self.circuit == "pump"

    @property
    def command_limit(self) -> str:
        """Name of the parameter that saturates the actuator and its command (``V_p_max`` of
        the pump, the spool stroke ``x_s_max`` of a valve)."""
        return CIRCUITS[self.circuit][3]

    @property
    def rate_limit(self) -> str:
        """Name of the parameter that limits the actuator's rate (``Vd_p_max``, ``xd_s_max``)."""
        return CIRCUITS[self.circuit][4]

    @property
    def actuator_state(self) -> str:
        """Name of the actuator's state (``V_p`` or ``x_s``), two after ``p_A``."""
        return CIRCUITS[self.circuit][0]

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


#: A machine as the public entry points take it: a resolved layout, a machine name
#: (:func:`loader_model.machines.list_machines`) or the path of a description file.
MachineSource = PlantLayout | str | os.PathLike[str]

_LAYOUTS: dict[tuple[MachineInfo, str], PlantLayout] = {}


def plant_layout(
    source: str | os.PathLike[str] = DEFAULT_MACHINE, circuit: str | None = None
) -> PlantLayout:
    """The machine ``source`` resolved once: its plant layout (module notes).

    The look-up by name for the command line and the public entry points; everything below
    them takes the layout. ``circuit`` as :func:`machine_layout`.

    Parameters
    ----------
    source : str or pathlib.Path
        A machine name or description file (:func:`loader_model.machines.machine`).
    circuit : str, optional
        ``"pump"`` or ``"valve"`` (default the description's ``[circuit] kind``).

    Raises
    ------
    ValueError
        For an unknown machine or circuit, or a machine without the sensor at its seat point.
    """
    return machine_layout(machine(source), circuit)


def resolve_layout(source: MachineSource = DEFAULT_MACHINE) -> PlantLayout:
    """``source`` itself if it is a :class:`PlantLayout`, else :func:`plant_layout` of it: the one
    conversion of a public entry point that takes a machine as a layout, name or file."""
    return source if isinstance(source, PlantLayout) else plant_layout(source)


def machine_layout(info: MachineInfo, circuit: str | None = None) -> PlantLayout:
    """The plant layout of the resolved machine ``info`` (built once per machine and circuit).

    ``circuit`` (``"pump"`` or ``"valve"``, default the description's ``[circuit] kind``)
    chooses the lift circuit; another one than the description's builds the same mechanics
    with that circuit (for studies and tests).

    Raises
    ------
    ValueError
        For an unknown circuit, or a machine without the sensor at its seat point.
    """
    key = (info, info.circuit if circuit is None else circuit)
    if key not in _LAYOUTS:
        _LAYOUTS[key] = _build_layout(info, circuit)
    return _LAYOUTS[key]


def _build_layout(info: MachineInfo, circuit: str | None) -> PlantLayout:
    from loader_model.plant.plant_parameters import HYDRAULIC_PARAMETERS
    from loader_model.plant.valve_circuit import VALVE_PARAMETERS

    circuit = info.circuit if circuit is None else circuit
    if circuit not in CIRCUITS:
        raise ValueError(f"circuit {circuit!r} is not allowed; allowed: {', '.join(CIRCUITS)}")
    state, rate, command, _, _, flow = CIRCUITS[circuit]
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
        "p_A",
        "p_B",
        state,
        rate,
        "V_acc",
        *OCCUPANT_STATE_NAMES,
    )
    outputs = (
        "xd_H",
        "yd_H",
        "thetad_1",
        *_joint_outputs(info),
        *(item[0] for item in sensors),
        *("thetadd_1", "p_A", "p_B", "F_act", "x_piston", state, flow),
        *(f"F_{axle}y" for axle in info.axles),
        "p_acc",
        "f_Px",
        "f_Py",
    )
    hydraulic = HYDRAULIC_PARAMETERS if circuit == "pump" else _valve_entries(VALVE_PARAMETERS)
    parameters = info.parameter_names + tuple(item[0] for item in hydraulic + OCCUPANT_PARAMETERS)
    return PlantLayout(
        machine=info,
        state_names=states,
        input_names=(command,),
        exogenous_names=info.exogenous_names,
        output_names=outputs,
        parameter_names=parameters,
        sensor_outputs=sensors,
        circuit=circuit,
    )


#: Entries of the pump circuit that a valve circuit does not have (charge line, Table 5's
#: pump-side regression flow, the pump and its displacement loop).
_PUMP_ONLY = frozenset(
    {"p_charge", "G_charge", "k_Lp", "k_Lv", "V_p_max", "n_pump", "omega_p", "zeta_p"}
    | {"Vd_p_max"}
)


def _valve_entries(
    valve: tuple[tuple[str, str, str], ...],
) -> tuple[tuple[str, str, str], ...]:
    """The valve circuit's parameters: the pump circuit's shared entries (cylinders, oil,
    check and relief valves, seals, friction, accumulator) with the valve's before the
    accumulator, the switches last."""
    from loader_model.plant.plant_parameters import HYDRAULIC_PARAMETERS

    shared = [item for item in HYDRAULIC_PARAMETERS if item[0] not in _PUMP_ONLY]
    at = [item[0] for item in shared].index("n_acc")
    return (*shared[:at], *valve, *shared[at:])


#: The paper's skid-steer resolved once: the default machine of the functions that take a
#: :class:`PlantLayout`.
SKID_STEER: PlantLayout = plant_layout(DEFAULT_MACHINE)
