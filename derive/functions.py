"""The list of generated functions: which expressions of :mod:`derive.mechanics` each one emits."""

from __future__ import annotations

import sympy as sp

from derive.codegen import FunctionSpec, InputSpec
from derive.energy import mechanical_energy_spec
from derive.mechanics import LoaderMechanics
from derive.naming import Naming
from derive.symbols import MachineSymbols, machine_symbols, parameter_symbol

__all__ = ["OUTPUT_NAMES", "function_specs", "output_names"]


def _inputs(sym: MachineSymbols, nm: Naming) -> dict[str, InputSpec]:
    lift = sym.machine.driven
    return {
        "p": InputSpec(
            "p",
            tuple(sym.coordinates),
            f"generalised coordinates {nm.coordinates} {nm.units('m', 'rad')}",
        ),
        "pd": InputSpec("pd", tuple(sym.rates), f"rates of p {nm.units('m/s', 'rad/s')}"),
        "pdd": InputSpec("pdd", tuple(sym.accelerations), "accelerations of p [m/s², rad/s²]"),
        "anchor": InputSpec(
            "anchor",
            tuple(sym.anchors),
            f"horizontal anchors ({nm.per_axle('ξ_{axle}')}) of the tyre contact points [m]",
        ),
        "F_act": InputSpec(
            "F_act",
            (sym.force,),
            f"total lift-cylinder force along {lift.base} -> {lift.rod} [N] (Eq. 31)",
        ),
        "road": InputSpec(
            "road",
            tuple(sym.road),
            f"road displacement ({', '.join(s.name for s in sym.road)}) under "
            f"{', '.join(sym.machine.axles)} [m]",
        ),
        "road_rate": InputSpec("road_rate", tuple(sym.road_rates), "rate of the road displacement [m/s]"),
        "disturbance": InputSpec(
            "disturbance",
            tuple(sym.disturbances),
            f"F_dx, F_dy [N] and M_d [N·m] at {nm.reference} (Eq. 5-7)",
        ),
        "params": InputSpec(
            "params",
            tuple(parameter_symbol(item.name) for item in sym.parameters),
            "model parameters in the order of PARAMETER_NAMES",
        ),
    }  # fmt: skip


def output_names(sym: MachineSymbols) -> tuple[str, ...]:
    """Outputs of the linear model: Eq. 40 (chassis rates and joint angles), then accelerations at
    the sensor points (world frame, kinematic), the pitch acceleration of the chassis, and the
    specific forces that chassis-fixed accelerometers at the sensor points read (chassis frame,
    gravity included). For the skid-steer: H, N (vertical only) and the seat S."""
    nm = Naming(sym)
    rates = [symbol.name for symbol in sym.rates[:3]]
    joints = [nm.joint_angle(b.name)[0] if b.joint == "pin" else b.coordinates[0]
              for b in sym.machine.bodies[1:]]  # fmt: skip
    sensors = [(k, axis) for k, (_, axes) in sym.machine.sensors.items() for axis in axes]
    return (
        *rates,
        *joints,
        *(f"a_{k}{axis}" for k, axis in sensors),
        sym.accelerations[2].name,
        *(f"f_{k}{axis}" for k, axis in sensors),
    )


#: The default machine's (the skid-steer's) outputs.
OUTPUT_NAMES = output_names(machine_symbols())


def _outputs(mech: LoaderMechanics) -> sp.Matrix:
    sym = mech.symbols
    p, pd, pdd = sym.coordinates, sym.rates, sym.accelerations
    joints = []
    for body in sym.machine.bodies[1:]:
        own = p[sym.index(body.coordinates[0])]
        if body.joint == "pin":
            parent = sym.machine.body(body.parent)  # type: ignore[arg-type]
            angle = parent.coordinates[2 if parent.joint == "free" else 0]
            own = own - p[sym.index(angle)]
        joints.append(own)
    accelerations, forces = [], []
    for k, (_, axes) in sym.machine.sensors.items():
        for axis in axes:
            accelerations.append(mech.accelerations[k]["xy".index(axis)])
            forces.append(mech.specific_forces[k]["xy".index(axis)])
    kinematic = [pd[0], pd[1], pd[2], *joints, *accelerations, pdd[2]]
    return sp.Matrix([*kinematic, *forces])


def _completed(mech: LoaderMechanics) -> sp.Matrix:
    """The parameter vector with the static loads replaced by the static equilibrium's."""
    entries = []
    for item in mech.symbols.parameters:
        entries.append(mech.static_loads.get(item.name, parameter_symbol(item.name)))
    return sp.Matrix(entries)


def function_specs(mech: LoaderMechanics) -> list[FunctionSpec]:
    """Return the specification of every generated function."""
    from derive.function_texts import kinematic_specs, model_specs

    sym = mech.symbols
    nm = Naming(sym)
    inputs = _inputs(sym, nm)
    outputs = _outputs(mech)
    names = output_names(sym)
    specs = model_specs(mech, nm, inputs)
    specs += kinematic_specs(mech, nm, inputs, outputs, names, _completed(mech))
    io = inputs
    specs.append(
        mechanical_energy_spec(
            mech, (io["p"], io["pd"], io["anchor"], io["road"], io["road_rate"], io["params"])
        )
    )
    return specs
