"""Specifications (expressions and docstrings) of the generated functions of one machine."""

from __future__ import annotations

import sympy as sp

from derive.codegen import FunctionSpec, InputSpec, OutputSpec
from derive.mechanics import LoaderMechanics
from derive.naming import Naming, listing

__all__ = ["kinematic_specs", "model_specs"]


def _pick(io: dict[str, InputSpec], names: str) -> tuple[InputSpec, ...]:
    return tuple(io[name] for name in names.split())


def _coriolis_details(mech: LoaderMechanics, nm: Naming) -> str:
    others = mech.symbols.machine.bodies[1:]
    if len(others) == 1:
        body = others[0]
        mass = body.mass.replace("_", "")
        cog = body.centre_of_gravity
        return (
            f"C = {mass} J_{cog}ᵀ (dJ_{cog}/dt) ṗ; {nm.reference} is the chassis centre of gravity, "
            f"so only the {body.label} adds terms."
        )
    labels = listing([body.label for body in others])
    return (
        f"C = Σ m J_Gᵀ (dJ_G/dt) ṗ over the {labels} (each at its centre of gravity G);\n"
        f"{nm.reference} is the chassis centre of gravity, so the chassis adds no terms."
    )


def model_specs(mech: LoaderMechanics, nm: Naming, io: dict[str, InputSpec]) -> list[FunctionSpec]:
    """mass_matrix ... tyre_contact (and internal_forces for machines with spring elements)."""
    sym = mech.symbols
    n = nm.n
    machine = sym.machine
    lift = machine.driven
    child = machine.body_of(lift.rod)
    parent = machine.body(child.parent)  # type: ignore[arg-type]
    joint_name, joint = nm.joint_angle(child.name)
    pattern = [0] * n
    pattern[sym.index(child.coordinates[0])] = 1
    carrier = parent  # the body whose angle the parent shares (a slider's is its parent's)
    while carrier.angle is None:
        carrier = machine.body(carrier.parent)  # type: ignore[arg-type]
    pattern[sym.index(carrier.angle)] = -1
    vector = "(" + ", ".join({0: "0", 1: "1", -1: "−1"}[v] for v in pattern) + ")"
    forces = f"({n},) generalised forces {nm.forces}"
    both = "both tyres" if len(machine.axles) == 2 else "every tyre"
    rhs = (
        mech.actuator_map * sym.force
        + mech.gravity_forces
        + mech.disturbance_map * sym.disturbances
        + mech.contact_tyre_forces
        - mech.coriolis_centrifugal
    )
    if machine.elements:
        rhs -= mech.elements.springs + mech.elements.dampers
    tyre_list = nm.per_axle("F_{axle}x, F_{axle}y")
    jacobians = " + ".join(f"J_{a}ᵀ F_{a}" for a in machine.axles)
    specs = [
        FunctionSpec(
            "mass_matrix",
            "Mass matrix M(p) of the reduced equations of motion (paper Eq. 25; linearised: Eq. 32).",
            "Symmetric and positive definite for positive masses and inertias.",
            (io["p"], io["params"]),
            (OutputSpec("M", mech.mass_matrix, f"({n}, {n}) mass matrix [kg, kg·m, kg·m²]"),),
        ),
        FunctionSpec(
            "coriolis_centrifugal",
            "Centrifugal and Coriolis forces C(p, ṗ) (paper Eq. 25), left-hand side.",
            _coriolis_details(mech, nm),
            (io["p"], io["pd"], io["params"]),
            (OutputSpec("C", mech.coriolis_centrifugal, forces),),
        ),
        FunctionSpec(
            "gravity_forces",
            "Generalised gravity forces Q_g(p), right-hand side.",
            "The paper drops gravity by measuring from static equilibrium; here it is kept (g = 0 drops it).",
            (io["p"], io["params"]),
            (OutputSpec("Q_g", mech.gravity_forces, forces),),
        ),
        FunctionSpec(
            "tyre_spring_forces",
            "Tyre spring forces K(p, w) with the static tyre loads (paper Eq. 1-4, 25), left-hand side.",
            f"Linear law of the paper: {both} in contact. Deflection is the axle's displacement\n"
            "from its position at p = 0 minus the road displacement under it.",
            (io["p"], io["road"], io["params"]),
            (OutputSpec("K", mech.tyre_spring_forces, forces),),
        ),
        FunctionSpec(
            "tyre_damper_forces",
            "Tyre damper forces D(p, ṗ, ẇ) (paper Eq. 1-4, 25), left-hand side.",
            "Linear law of the paper; the damper acts on the axle's velocity relative to the road.",
            (io["p"], io["pd"], io["road_rate"], io["params"]),
            (OutputSpec("D", mech.tyre_damper_forces, forces),),
        ),
    ]
    if machine.elements:
        specs.append(
            FunctionSpec(
                "internal_forces",
                "Forces of the internal spring-dampers K_e(p), D_e(p, ṗ), left-hand side.",
                f"Elements {', '.join(machine.elements)} (derive/elements.py): hydraulically locked\n"
                "cylinders as springs of their chamber stiffness, sliding mounts as spring-dampers,\n"
                "with the preloads of the static equilibrium."
                + (
                    f"\nEnd stops (C¹ one-sided spring-dampers beyond the travel limits) on "
                    f"{', '.join(machine.stops)}."
                    if machine.stops
                    else ""
                ),
                (io["p"], io["pd"], io["params"]),
                (
                    OutputSpec("K_e", mech.elements.springs, forces),
                    OutputSpec("D_e", mech.elements.dampers, forces),
                ),
            )
        )
    specs += [
        FunctionSpec(
            "actuator_map",
            "Generalised force of a unit lift-cylinder force, Q_act(p) = ∂x_cyl/∂p (Eq. 15, 16, 25).",
            f"The force acts along {lift.base} -> {lift.rod} on the {child.label} at {lift.rod} and "
            f"opposite on the {parent.label} at {lift.base}; by virtual\nwork its generalised force is "
            f"F_act ∂x_cyl/∂p = F_act dx_cyl/d{joint} {vector}.",
            (io["p"], io["params"]),
            (
                OutputSpec(
                    "Q_act", mech.actuator_map, f"({n},) generalised force per newton {nm.units('1', 'm')}"
                ),
            ),
        ),
        FunctionSpec(
            "forward_dynamics",
            "Forward dynamics p̈ = M⁻¹ (Q_act F_act + Q_g + Q_d + Q_tyre − C) and anchor rates ξ̇."
            if not machine.elements
            else "Forward dynamics p̈ = M⁻¹ (Q_act F_act + Q_g + Q_d + Q_tyre − C − K_e − D_e), ξ̇.",
            "Tyres follow the contact law of derive.contact: the paper's linear law (Eq. 1-4) while\n"
            "loaded and sticking, no pulling tyre, horizontal force limited by mu_road F_y, anchors ξ\n"
            "that slide with the excess force. M is solved numerically inside the CasADi graph.",
            _pick(io, "p pd anchor F_act road road_rate disturbance params"),
            (
                OutputSpec("M", mech.mass_matrix, f"({n}, {n}) mass matrix"),
                OutputSpec("rhs", rhs, f"({n},) right-hand side"),
                OutputSpec(
                    "anchor_rate", mech.anchor_rates, f"({len(machine.axles)},) anchor rates ξ̇ [m/s]"
                ),
            ),
            epilogue="    pdd = ca.solve(M, rhs)",
            extra_outputs=(("pdd", f"({n},) accelerations p̈ {nm.units('m/s²', 'rad/s²')}"),),
            return_names=("pdd", "anchor_rate"),
            definitions=mech.contact_definitions,
        ),
        FunctionSpec(
            "tyre_contact",
            "Road forces on the axles and anchor rates of the tyre contact law (derive.contact).",
            f"F_tyre = ({tyre_list}) in the world frame [N]; Q_tyre their generalised\n"
            f"forces {jacobians} (right-hand side); ξ̇ the anchor sliding rates.",
            (io["p"], io["pd"], io["anchor"], io["road"], io["road_rate"], io["params"]),
            (
                OutputSpec("F_tyre", mech.tyre_forces, f"({2 * len(machine.axles)},) {tyre_list} [N]"),
                OutputSpec("Q_tyre", mech.contact_tyre_forces, forces),
                OutputSpec(
                    "anchor_rate", mech.anchor_rates, f"({len(machine.axles)},) anchor rates ξ̇ [m/s]"
                ),
            ),
            definitions=mech.contact_definitions,
        ),
    ]  # fmt: skip
    del joint_name
    return specs


def _positions_texts(nm: Naming) -> tuple[str, str]:
    machine = nm.machine
    groups = []
    for body in machine.bodies:
        names = sorted([*body.points, *([nm.reference] if body.joint == "free" else [])])
        groups.append(f"the {body.label} points {', '.join(names)}")
    joints = []
    for body in machine.bodies[1:]:
        kind = {"pin": "pin constraint", "two_mounts": "two-point mount"}.get(
            body.joint, "sliding mount"
        )
        joints.append(f"{body.label.capitalize()} points follow the {kind} at {body.at}")
    return (
        f"World positions of {listing(groups)}.",
        "; ".join(joints) + " (Eq. 17).",
    )


def kinematic_specs(
    mech: LoaderMechanics,
    nm: Naming,
    io: dict[str, InputSpec],
    outputs: sp.Matrix,
    names: tuple[str, ...],
    completed: sp.Matrix,
) -> list[FunctionSpec]:
    """point_positions ... output_jacobians."""
    sym = mech.symbols
    machine = sym.machine
    n, n_w = nm.n, len(sym.road) + len(sym.road_rates) + len(sym.disturbances)
    p, pd, pdd = sym.coordinates, sym.rates, sym.accelerations
    points = sorted(mech.positions)
    sensors = list(machine.sensors)
    labels = [label for label, _ in machine.sensors.values()]
    lift = machine.driven
    child = machine.body_of(lift.rod)
    parent = machine.body(child.parent)  # type: ignore[arg-type]
    _, joint = nm.joint_angle(child.name)
    summary, details = _positions_texts(nm)
    pitch = nm.angle(machine.root.name)
    bodies = listing([body.label for body in machine.bodies])
    loads = [f"F_{axle}y0" for axle in machine.axles]
    preloads = [f"F_{element}0" for element in machine.elements]
    solved = listing([*loads, "F_act0", *preloads])
    replaced = listing(loads + preloads)
    elements = " + K_e(0)" if machine.elements else ""
    e_terms = " + K_e + D_e" if machine.elements else ""
    exogenous = sp.Matrix([*sym.road, *sym.road_rates, *sym.disturbances])
    residual = mech.residual
    return [
        FunctionSpec(
            "point_positions",
            summary,
            details,
            (io["p"], io["params"]),
            tuple(
                OutputSpec(f"r_{k}", mech.positions[k], f"(2,) world position of {k} [m]")
                for k in points
            ),
        ),
        FunctionSpec(
            "point_velocities",
            f"World velocities of the {bodies} points.",
            "v = J(p) ṗ with J = ∂r/∂p (time derivative of Eq. 17).",
            (io["p"], io["pd"], io["params"]),
            tuple(
                OutputSpec(
                    f"v_{k}", mech.positions[k].jacobian(p) * pd, f"(2,) world velocity of {k} [m/s]"
                )
                for k in points
            ),
        ),
        FunctionSpec(
            "point_accelerations",
            f"World accelerations at {listing([labels[0], *(f'at {k}' for k in labels[1:])])}.",
            "a = J(p) p̈ + (∂(J ṗ)/∂p) ṗ. Kinematic accelerations; an accelerometer also senses gravity.",
            (io["p"], io["pd"], io["pdd"], io["params"]),
            tuple(
                OutputSpec(f"a_{k}", mech.accelerations[k], f"(2,) acceleration of {k} [m/s²]")
                for k in sensors
            ),
        ),
        FunctionSpec(
            "specific_forces",
            f"Specific force read by chassis-fixed accelerometers at {listing(sensors)} (chassis frame).",
            f"f = R({pitch})ᵀ (a + g ŷ): the kinematic acceleration plus the reaction to gravity, "
            f"resolved\nalong the chassis axes (x forward, y up). A {machine.title.split()[-1]} at "
            f"rest pitched by {pitch} reads\n(g sin {pitch}, g cos {pitch}).",
            (io["p"], io["pd"], io["pdd"], io["params"]),
            tuple(
                OutputSpec(f"f_{k}", mech.specific_forces[k], f"(2,) specific force at {k} [m/s²]")
                for k in sensors
            ),
        ),
        FunctionSpec(
            "cylinder_kinematics",
            f"Lift-cylinder length x_cyl, its rate, dx_cyl/d{joint} (Eq. 35) and its angle γ (Eq. 15-16).",
            f"x_cyl depends on {joint} = {nm.angle(child.name)} − {nm.angle(parent.name)} only; "
            f"ẋ_cyl = dx_cyl/d{joint} {joint}\u0307 (Eq. 35).",
            (io["p"], io["pd"], io["params"]),
            (
                OutputSpec("x_cyl", sp.Matrix([mech.cylinder_length]), "pin-to-pin length [m]"),
                OutputSpec("xd_cyl", sp.Matrix([mech.elements.lift.rate]), "extension rate [m/s]"),
                OutputSpec(
                    "dx_cyl_dphi", sp.Matrix([mech.cylinder_lever]), f"lever dx_cyl/d{joint} [m/rad]"
                ),
                OutputSpec(
                    "gamma",
                    sp.Matrix([mech.cylinder_angle]),
                    f"angle of {lift.base} -> {lift.rod} to global x [rad]",
                ),
            ),
        ),
        FunctionSpec(
            "static_equilibrium",
            "Static tyre loads and cylinder force for which p = 0 is an equilibrium.",
            f"Solves K(0){elements} = Q_act(0) F_act0 + Q_g(0) for {solved} (no horizontal preload).\n"
            f"The entries {replaced} of ``params`` are not used.",
            (io["params"],),
            tuple(
                OutputSpec(name, sp.Matrix([mech.static_loads[name]]), "[N]")
                for name in (*loads, "F_act0", *preloads)
            ),
        ),
        FunctionSpec(
            "complete_parameters",
            "Parameter vector with the static tyre loads of the static equilibrium, and F_act0.",
            f"Replaces {replaced} of ``params`` by the loads that make p = 0 a static\n"
            "equilibrium (masses, geometry, gravity), so that a CasADi graph of the parameters stays\n"
            "at rest and differentiates through the equilibrium; F_act0 is the cylinder force that\n"
            f"holds the {child.label} there.",
            (io["params"],),
            (
                OutputSpec("params_static", completed, "(n_params,) completed parameters"),
                OutputSpec("F_act0", sp.Matrix([mech.static_loads["F_act0"]]), "[N]"),
            ),
        ),
        FunctionSpec(
            "residual_jacobians",
            f"Residual r = M p̈ + C + K + D{e_terms} − Q_act F_act − Q_g − Q_d and its Jacobians "
            "(linear tyres).",
            "w = (road, road_rate, disturbance). Used by the linearisation (Eq. 38).",
            _pick(io, "p pd pdd F_act road road_rate disturbance params"),
            (
                OutputSpec("r", residual, f"({n},) residual"),
                OutputSpec("dr_dp", residual.jacobian(p), f"({n}, {n})"),
                OutputSpec("dr_dpd", residual.jacobian(pd), f"({n}, {n})"),
                OutputSpec("dr_dpdd", residual.jacobian(pdd), f"({n}, {n}) equals M"),
                OutputSpec("dr_du", residual.jacobian(sp.Matrix([sym.force])), f"({n}, 1)"),
                OutputSpec("dr_dw", residual.jacobian(exogenous), f"({n}, {n_w})"),
            ),
        ),
        FunctionSpec(
            "output_jacobians",
            "Jacobians of the outputs y(p, ṗ, p̈) of the linear model (Eq. 40 plus accelerations).",
            "y = " + ", ".join(names) + ".",
            (io["p"], io["pd"], io["pdd"], io["params"]),
            (
                OutputSpec("y", outputs, f"({len(names)},) outputs"),
                OutputSpec("dy_dp", outputs.jacobian(p), f"({len(names)}, {n})"),
                OutputSpec("dy_dpd", outputs.jacobian(pd), f"({len(names)}, {n})"),
                OutputSpec("dy_dpdd", outputs.jacobian(pdd), f"({len(names)}, {n})"),
            ),
        ),
    ]  # fmt: skip
