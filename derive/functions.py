"""The list of generated functions: which expressions of :mod:`derive.mechanics` each one emits."""

from __future__ import annotations

import sympy as sp

from derive.codegen import FunctionSpec, InputSpec, OutputSpec
from derive.energy import mechanical_energy_spec
from derive.mechanics import LoaderMechanics
from derive.symbols import (
    ANCHORS,
    COORDINATE_ACCELERATIONS,
    COORDINATE_RATES,
    COORDINATES,
    DISTURBANCES,
    FORCE,
    PARAMETERS,
    ROAD,
    ROAD_RATES,
    parameter_symbol,
)

__all__ = ["OUTPUT_NAMES", "function_specs"]

_P = InputSpec(
    "p", tuple(COORDINATES), "generalised coordinates (x_H, y_H, θ1, θ2) [m, m, rad, rad]"
)
_PD = InputSpec("pd", tuple(COORDINATE_RATES), "rates of p [m/s, m/s, rad/s, rad/s]")
_PDD = InputSpec("pdd", tuple(COORDINATE_ACCELERATIONS), "accelerations of p [m/s², rad/s²]")
_XI = InputSpec(
    "anchor", tuple(ANCHORS), "horizontal anchors (ξ_A, ξ_B) of the tyre contact points [m]"
)
_F = InputSpec("F_act", (FORCE,), "total lift-cylinder force along C -> E [N] (Eq. 31)")
_W = InputSpec("road", tuple(ROAD), "road displacement (w_Ax, w_Ay, w_Bx, w_By) under A, B [m]")
_WD = InputSpec("road_rate", tuple(ROAD_RATES), "rate of the road displacement [m/s]")
_DIST = InputSpec("disturbance", tuple(DISTURBANCES), "F_dx, F_dy [N] and M_d [N·m] at H (Eq. 5-7)")
_PAR = InputSpec(
    "params",
    tuple(parameter_symbol(item.name) for item in PARAMETERS),
    "model parameters in the order of PARAMETER_NAMES",
)

#: Outputs of the linear model: Eq. 40, then accelerations at H, at N and at the seat S (world
#: frame, kinematic), the pitch acceleration of the chassis, and the specific forces that
#: chassis-fixed accelerometers at H, N and S read (chassis frame, gravity included).
OUTPUT_NAMES = (
    "xd_H",
    "yd_H",
    "thetad_1",
    "phi",
    "a_Hx",
    "a_Hy",
    "a_Ny",
    "a_Sx",
    "a_Sy",
    "thetadd_1",
    "f_Hx",
    "f_Hy",
    "f_Ny",
    "f_Sx",
    "f_Sy",
)


def _outputs(mech: LoaderMechanics) -> sp.Matrix:
    pd, pdd = COORDINATE_RATES, COORDINATE_ACCELERATIONS
    a_h, a_n, a_s = (mech.accelerations[k] for k in "HNS")
    f_h, f_n, f_s = (mech.specific_forces[k] for k in "HNS")
    phi = COORDINATES[3] - COORDINATES[2]
    kinematic = [pd[0], pd[1], pd[2], phi, a_h[0], a_h[1], a_n[1], a_s[0], a_s[1], pdd[2]]
    return sp.Matrix([*kinematic, f_h[0], f_h[1], f_n[1], f_s[0], f_s[1]])


def _completed(mech: LoaderMechanics) -> sp.Matrix:
    """The parameter vector with F_Ay0 and F_By0 replaced by the static equilibrium's loads."""
    entries = []
    for item in PARAMETERS:
        entries.append(mech.static_loads.get(item.name, parameter_symbol(item.name)))
    return sp.Matrix(entries)


def function_specs(mech: LoaderMechanics) -> list[FunctionSpec]:
    """Return the specification of every generated function."""
    p, pd, pdd = COORDINATES, COORDINATE_RATES, COORDINATE_ACCELERATIONS
    exogenous = sp.Matrix([*ROAD, *ROAD_RATES, *DISTURBANCES])
    rhs_contact = (
        mech.actuator_map * FORCE
        + mech.gravity_forces
        + mech.disturbance_map * DISTURBANCES
        + mech.contact_tyre_forces
        - mech.coriolis_centrifugal
    )
    residual = mech.residual
    outputs = _outputs(mech)
    positions = [
        OutputSpec(f"r_{k}", mech.positions[k], f"(2,) world position of {k} [m]")
        for k in "ABCDEGHNS"
    ]
    velocities = [
        OutputSpec(
            f"v_{k}", mech.positions[k].jacobian(p) * pd, f"(2,) world velocity of {k} [m/s]"
        )
        for k in "ABCDEGHNS"
    ]
    return [
        FunctionSpec(
            "mass_matrix",
            "Mass matrix M(p) of the reduced equations of motion (paper Eq. 25; linearised: Eq. 32).",
            "Symmetric and positive definite for positive masses and inertias.",
            (_P, _PAR),
            (OutputSpec("M", mech.mass_matrix, "(4, 4) mass matrix [kg, kg·m, kg·m²]"),),
        ),
        FunctionSpec(
            "coriolis_centrifugal",
            "Centrifugal and Coriolis forces C(p, ṗ) (paper Eq. 25), left-hand side.",
            "C = m2 J_Gᵀ (dJ_G/dt) ṗ; H is the chassis centre of gravity, so only the boom adds terms.",
            (_P, _PD, _PAR),
            (
                OutputSpec(
                    "C", mech.coriolis_centrifugal, "(4,) generalised forces [N, N, N·m, N·m]"
                ),
            ),
        ),
        FunctionSpec(
            "gravity_forces",
            "Generalised gravity forces Q_g(p), right-hand side.",
            "The paper drops gravity by measuring from static equilibrium; here it is kept (g = 0 drops it).",
            (_P, _PAR),
            (OutputSpec("Q_g", mech.gravity_forces, "(4,) generalised forces [N, N, N·m, N·m]"),),
        ),
        FunctionSpec(
            "tyre_spring_forces",
            "Tyre spring forces K(p, w) with the static tyre loads (paper Eq. 1-4, 25), left-hand side.",
            "Linear law of the paper: both tyres in contact. Deflection is the axle's displacement\n"
            "from its position at p = 0 minus the road displacement under it.",
            (_P, _W, _PAR),
            (OutputSpec("K", mech.tyre_spring_forces, "(4,) generalised forces [N, N, N·m, N·m]"),),
        ),
        FunctionSpec(
            "tyre_damper_forces",
            "Tyre damper forces D(p, ṗ, ẇ) (paper Eq. 1-4, 25), left-hand side.",
            "Linear law of the paper; the damper acts on the axle's velocity relative to the road.",
            (_P, _PD, _WD, _PAR),
            (OutputSpec("D", mech.tyre_damper_forces, "(4,) generalised forces [N, N, N·m, N·m]"),),
        ),
        FunctionSpec(
            "actuator_map",
            "Generalised force of a unit lift-cylinder force, Q_act(p) = ∂x_cyl/∂p (Eq. 15, 16, 25).",
            "The force acts along C -> E on the boom at E and opposite on the chassis at C; by virtual\n"
            "work its generalised force is F_act ∂x_cyl/∂p = F_act dx_cyl/dφ (0, 0, −1, 1).",
            (_P, _PAR),
            (
                OutputSpec(
                    "Q_act", mech.actuator_map, "(4,) generalised force per newton [1, 1, m, m]"
                ),
            ),
        ),
        FunctionSpec(
            "forward_dynamics",
            "Forward dynamics p̈ = M⁻¹ (Q_act F_act + Q_g + Q_d + Q_tyre − C) and anchor rates ξ̇.",
            "Tyres follow the contact law of derive.contact: the paper's linear law (Eq. 1-4) while\n"
            "loaded and sticking, no pulling tyre, horizontal force limited by mu_road F_y, anchors ξ\n"
            "that slide with the excess force. M is solved numerically inside the CasADi graph.",
            (_P, _PD, _XI, _F, _W, _WD, _DIST, _PAR),
            (
                OutputSpec("M", mech.mass_matrix, "(4, 4) mass matrix"),
                OutputSpec("rhs", rhs_contact, "(4,) right-hand side"),
                OutputSpec("anchor_rate", mech.anchor_rates, "(2,) anchor rates ξ̇ [m/s]"),
            ),
            epilogue="    pdd = ca.solve(M, rhs)",
            extra_outputs=(("pdd", "(4,) accelerations p̈ [m/s², m/s², rad/s², rad/s²]"),),
            return_names=("pdd", "anchor_rate"),
            definitions=mech.contact_definitions,
        ),
        FunctionSpec(
            "tyre_contact",
            "Road forces on the axles and anchor rates of the tyre contact law (derive.contact).",
            "F_tyre = (F_Ax, F_Ay, F_Bx, F_By) in the world frame [N]; Q_tyre their generalised\n"
            "forces J_Aᵀ F_A + J_Bᵀ F_B (right-hand side); ξ̇ the anchor sliding rates.",
            (_P, _PD, _XI, _W, _WD, _PAR),
            (
                OutputSpec("F_tyre", mech.tyre_forces, "(4,) F_Ax, F_Ay, F_Bx, F_By [N]"),
                OutputSpec(
                    "Q_tyre", mech.contact_tyre_forces, "(4,) generalised forces [N, N, N·m, N·m]"
                ),
                OutputSpec("anchor_rate", mech.anchor_rates, "(2,) anchor rates ξ̇ [m/s]"),
            ),
            definitions=mech.contact_definitions,
        ),
        FunctionSpec(
            "point_positions",
            "World positions of the chassis points A, B, C, D, H, N, S and the boom points E, G.",
            "Boom points follow the pin constraint at D (Eq. 17).",
            (_P, _PAR),
            tuple(positions),
        ),
        FunctionSpec(
            "point_velocities",
            "World velocities of the chassis and boom points.",
            "v = J(p) ṗ with J = ∂r/∂p (time derivative of Eq. 17).",
            (_P, _PD, _PAR),
            tuple(velocities),
        ),
        FunctionSpec(
            "point_accelerations",
            "World accelerations at H, at the second accelerometer N and at the seat S.",
            "a = J(p) p̈ + (∂(J ṗ)/∂p) ṗ. Kinematic accelerations; an accelerometer also senses gravity.",
            (_P, _PD, _PDD, _PAR),
            tuple(
                OutputSpec(f"a_{k}", mech.accelerations[k], f"(2,) acceleration of {k} [m/s²]")
                for k in "HNS"
            ),
        ),
        FunctionSpec(
            "specific_forces",
            "Specific force read by chassis-fixed accelerometers at H, N and S (chassis frame).",
            "f = R(θ1)ᵀ (a + g ŷ): the kinematic acceleration plus the reaction to gravity, resolved\n"
            "along the chassis axes (x forward, y up). A loader at rest pitched by θ1 reads\n"
            "(g sin θ1, g cos θ1).",
            (_P, _PD, _PDD, _PAR),
            tuple(
                OutputSpec(f"f_{k}", mech.specific_forces[k], f"(2,) specific force at {k} [m/s²]")
                for k in "HNS"
            ),
        ),
        FunctionSpec(
            "cylinder_kinematics",
            "Lift-cylinder length x_cyl, its rate, dx_cyl/dφ (Eq. 35) and its angle γ (Eq. 15-16).",
            "x_cyl depends on φ = θ2 − θ1 only; ẋ_cyl = dx_cyl/dφ φ̇ (Eq. 35).",
            (_P, _PD, _PAR),
            (
                OutputSpec("x_cyl", sp.Matrix([mech.cylinder_length]), "pin-to-pin length [m]"),
                OutputSpec(
                    "xd_cyl",
                    sp.Matrix([mech.cylinder_lever * (pd[3] - pd[2])]),
                    "extension rate [m/s]",
                ),
                OutputSpec(
                    "dx_cyl_dphi", sp.Matrix([mech.cylinder_lever]), "lever dx_cyl/dφ [m/rad]"
                ),
                OutputSpec(
                    "gamma", sp.Matrix([mech.cylinder_angle]), "angle of C -> E to global x [rad]"
                ),
            ),
        ),
        FunctionSpec(
            "static_equilibrium",
            "Static tyre loads and cylinder force for which p = 0 is an equilibrium.",
            "Solves K(0) = Q_act(0) F_act0 + Q_g(0) for F_Ay0, F_By0 and F_act0 (no horizontal preload).\n"
            "The entries F_Ay0 and F_By0 of ``params`` are not used.",
            (_PAR,),
            tuple(
                OutputSpec(name, sp.Matrix([mech.static_loads[name]]), "[N]")
                for name in ("F_Ay0", "F_By0", "F_act0")
            ),
        ),
        FunctionSpec(
            "complete_parameters",
            "Parameter vector with the static tyre loads of the static equilibrium, and F_act0.",
            "Replaces F_Ay0 and F_By0 of ``params`` by the loads that make p = 0 a static\n"
            "equilibrium (masses, geometry, gravity), so that a CasADi graph of the parameters stays\n"
            "at rest and differentiates through the equilibrium; F_act0 is the cylinder force that\n"
            "holds the boom there.",
            (_PAR,),
            (
                OutputSpec("params_static", _completed(mech), "(n_params,) completed parameters"),
                OutputSpec("F_act0", sp.Matrix([mech.static_loads["F_act0"]]), "[N]"),
            ),
        ),
        FunctionSpec(
            "residual_jacobians",
            "Residual r = M p̈ + C + K + D − Q_act F_act − Q_g − Q_d and its Jacobians (linear tyres).",
            "w = (road, road_rate, disturbance). Used by the linearisation (Eq. 38).",
            (_P, _PD, _PDD, _F, _W, _WD, _DIST, _PAR),
            (
                OutputSpec("r", residual, "(4,) residual"),
                OutputSpec("dr_dp", residual.jacobian(p), "(4, 4)"),
                OutputSpec("dr_dpd", residual.jacobian(pd), "(4, 4)"),
                OutputSpec("dr_dpdd", residual.jacobian(pdd), "(4, 4) equals M"),
                OutputSpec("dr_du", residual.jacobian(sp.Matrix([FORCE])), "(4, 1)"),
                OutputSpec("dr_dw", residual.jacobian(exogenous), "(4, 11)"),
            ),
        ),
        FunctionSpec(
            "output_jacobians",
            "Jacobians of the outputs y(p, ṗ, p̈) of the linear model (Eq. 40 plus accelerations).",
            "y = " + ", ".join(OUTPUT_NAMES) + ".",
            (_P, _PD, _PDD, _PAR),
            (
                OutputSpec("y", outputs, f"({len(OUTPUT_NAMES)},) outputs"),
                OutputSpec("dy_dp", outputs.jacobian(p), f"({len(OUTPUT_NAMES)}, 4)"),
                OutputSpec("dy_dpd", outputs.jacobian(pd), f"({len(OUTPUT_NAMES)}, 4)"),
                OutputSpec("dy_dpdd", outputs.jacobian(pdd), f"({len(OUTPUT_NAMES)}, 4)"),
            ),
        ),
        mechanical_energy_spec(mech, (_P, _PD, _XI, _W, _WD, _PAR)),
    ]
