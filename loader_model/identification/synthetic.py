r"""Synthetic identification records from the hydraulic plant (section 4.1).

The test follows the paper: "the boom cylinders were repeatedly extended and retracted with
varying rates and loads". The machine is the plant (:func:`loader_model.plant.plant.
plant_function`, one CasADi Function: multibody model on its tyres, both lift cylinders, pump,
charge and relief valves, leakage Eq. 47, friction Eq. 46), parked (w = 0), with the parameters
of a loader file (default: the shipped loader, whose friction and leakage are Table 4 and 5).

Pump command, composed as CasADi expressions around the plant (a PI position law on the piston
position x = ``x_piston`` of the plant's outputs):

.. math::

    V_{p,ref} = \frac{A_p}{n}\left(\dot x_{ref} + k_x (x_{ref} - x) + k_i z\right), \qquad
    \dot z = x_{ref} - x

with A_p the total piston area and n the shaft speed; z starts at the value that gives the
static command (the pump holding the boom against the leakage), so the run starts at rest in
the plant's static equilibrium (:func:`~loader_model.plant.equilibrium.static_state`).

The reference: a smooth trapezoidal velocity profile (raised-cosine ramps) of extend and retract
strokes (:func:`~.lift_test.reference_schedule`); the bucket load changes only while the boom
is held at the bottom. Each load mass m is its own plant parameter vector (bucket load of mass m with the
centre of gravity and the inertia per kg of a load case, combined with the boom by
:func:`~loader_model.parameters.sets.combine_bodies`), passed per sample interval.

Integration: CasADi ``cvodes`` on the sample grid, inputs piecewise constant. Recorded flow:
the plant's ``Q_pump`` (n V_p); p_A, p_B gauge. True ẋ and ẍ: the generated
``cylinder_kinematics`` and its directional derivative along the plant's ẋ.

Sensors: noise, quantisation and offset per channel, flow drop-outs (outliers); the flow
offset defaults to Table 5's C; chassis channels (pitch, specific forces) drawn last.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from functools import cache

import casadi as ca
import numpy as np

import loader_model_generated as generated
from loader_model.identification.equivalent import EquivalentCylinder
from loader_model.identification.lift_test import (
    TABLE4,
    TABLE5,
    LiftProfile,
    SensorOptions,
    reference_schedule,
)
from loader_model.identification.measurement import MeasurementRecord
from loader_model.parameters.schema import BucketLoad, LoaderParameters

__all__ = ["TABLE4", "TABLE5", "LiftProfile", "SensorOptions", "SyntheticRecording", "synthesize"]

_N_MECH = len(generated.PARAMETER_NAMES)


@dataclass(frozen=True)
class SyntheticRecording:
    """A synthetic record and the true signals behind it.

    Attributes
    ----------
    record : MeasurementRecord
        What the sensors logged (write it with ``write_measurement_csv(path, record.columns())``).
    truth : dict of str to numpy.ndarray
        True ``x``, ``v``, ``a`` (ẍ), ``p_a``, ``p_b``, ``dp_a`` (ṗ_A), ``flow`` (Q_pump),
        ``force`` (F_act), ``phi`` (boom angle from the static one), ``theta_1``,
        ``thetad_1``, ``thetadd_1`` (chassis pitch, its rate and acceleration), ``f_Hx``,
        ``f_Hy``, ``f_Ny`` (specific forces), ``command`` (V_p,ref) and ``load_mass`` at the
        sample times, from the plant's state and right-hand side; ``outliers`` (1: dropped).
    cylinder : EquivalentCylinder
        The equivalent cylinder of the loader and load case (what an estimator would use).
    parameters : dict of str to float
        The plant's true friction (:data:`TABLE4` names) and leakage (:data:`TABLE5` names,
        C the sensor's flow offset) values.
    """

    record: MeasurementRecord
    truth: dict[str, np.ndarray]
    cylinder: EquivalentCylinder
    parameters: dict[str, float] = field(default_factory=dict)


@cache
def _lift_functions() -> tuple[ca.Function, ca.Function]:
    """(closed-loop ODE, truth outputs) of the plant under the PI position law (SX)."""
    from loader_model.plant.plant import OUTPUT_NAMES, STATE_NAMES, plant_function
    from loader_model.plant.plant_parameters import PLANT_PARAMETER_NAMES

    plant = plant_function()
    names = {name: i for i, name in enumerate(PLANT_PARAMETER_NAMES)}
    out = {name: i for i, name in enumerate(OUTPUT_NAMES)}
    x = ca.SX.sym("x", len(STATE_NAMES))
    z = ca.SX.sym("z")
    # references and gains: x_ref, v_ref, k_x, k_i; then the plant parameters
    ref = ca.SX.sym("ref", 4)
    params = ca.SX.sym("params", len(PLANT_PARAMETER_NAMES))
    area = params[names["n_cyl"]] * ca.pi / 4 * params[names["d_piston"]] ** 2
    w = ca.SX.zeros(len(generated.EXOGENOUS_NAMES))
    _, y = plant(x, 0, w, params)
    error = ref[0] - y[out["x_piston"]]
    command = area / params[names["n_pump"]] * (ref[1] + ref[2] * error + ref[3] * z)
    xdot, y = plant(x, command, w, params)
    state = ca.vertcat(x, z)
    u = ca.vertcat(ref, params)
    rhs = ca.vertcat(xdot, error)
    ode = ca.Function("lift_ode", [state, u], [rhs], ["x", "u"], ["xdot"])
    completed, _ = generated.function("complete_parameters")(params[:_N_MECH])
    kinematics = generated.function("cylinder_kinematics")(x[0:4], x[4:8], completed)
    velocity = kinematics[1]
    acceleration = ca.jtimes(velocity, x, xdot)
    truth = ca.Function(
        "lift_truth",
        [state, u],
        [
            ca.vertcat(
                y[out["x_piston"]],
                velocity,
                acceleration,
                y[out["p_A"]],
                y[out["p_B"]],
                xdot[STATE_NAMES.index("p_A")],
                y[out["Q_pump"]],
                y[out["F_act"]],
                y[out["phi"]],
                x[STATE_NAMES.index("theta_1")],
                y[out["thetadd_1"]],
                command,
                y[out["thetad_1"]],
                y[out["f_Hx"]],
                y[out["f_Hy"]],
                y[out["f_Ny"]],
            )
        ],
        ["x", "u"],
        ["truth"],
    )
    return ode, truth


_TRUTH_NAMES = (
    "x",
    "v",
    "a",
    "p_a",
    "p_b",
    "dp_a",
    "flow",
    "force",
    "phi",
    "theta_1",
    "thetadd_1",
    "command",
    "thetad_1",
    "f_Hx",
    "f_Hy",
    "f_Ny",
)


def _load_case(load: BucketLoad, mass: float) -> BucketLoad:
    """The load case scaled to ``mass``: same centre of gravity, same inertia per kg."""
    return dataclasses.replace(load, mass=float(mass), inertia=load.inertia * mass / load.mass)


def _parameter_columns(
    loader: LoaderParameters, load: BucketLoad, masses: np.ndarray
) -> np.ndarray:
    """Plant parameter vectors, one column per sample (each distinct mass once)."""
    from loader_model.plant.plant_parameters import plant_parameter_vector

    unique, index = np.unique(masses, return_inverse=True)
    vectors = np.column_stack([plant_parameter_vector(loader, _load_case(load, m)) for m in unique])
    return vectors[:, index]


def synthesize(
    sensors: SensorOptions | None = None,
    profile: LiftProfile | None = None,
    *,
    loader: LoaderParameters | None = None,
    load: BucketLoad | str = "full",
) -> SyntheticRecording:
    """Run the lift test on the plant and log it with the sensor model (module docstring).

    Parameters
    ----------
    sensors : SensorOptions, optional
        Sample rate, noise, quantisation, offsets, outliers and seed.
    profile : LiftProfile, optional
        The extend/retract cycles, load masses and the position law's gains.
    loader : LoaderParameters, optional
        The machine (default: the shipped loader, Table 4 and 5 values).
    load : BucketLoad or str
        Load case whose centre of gravity and inertia per kg place every load mass
        (default ``"full"``).

    Raises
    ------
    ValueError
        For a non-positive sample rate or load mass, or an outlier fraction outside [0, 0.5).
    RuntimeError
        If the integrator fails.
    """
    from loader_model.plant.equilibrium import static_state
    from loader_model.vehicle.statics import resolve_machine

    sensors = sensors or SensorOptions()
    profile = profile or LiftProfile()
    loader, load = resolve_machine(loader, load)
    if not sensors.sample_rate_hz > 0.0:
        raise ValueError(f"sample rate must be > 0 Hz; got {sensors.sample_rate_hz!r}")
    if not 0.0 <= sensors.outlier_fraction < 0.5:
        raise ValueError(f"outlier fraction must be in [0, 0.5); got {sensors.outlier_fraction!r}")
    if min(profile.load_masses_kg) <= 0.0:
        raise ValueError(f"load masses must be > 0 kg; got {profile.load_masses_kg!r}")
    rng = np.random.default_rng(sensors.seed)
    dt = 1.0 / sensors.sample_rate_hz
    ode, truth_function = _lift_functions()
    cyl = EquivalentCylinder.from_parameters(loader, load)
    # p = 0 (the static state) is the operating boom angle whatever the load
    x_static = float(cyl.position_from_boom_angle(np.array([loader.geometry.boom_angle]))[0])
    t, v_ref, x_ref, mass = reference_schedule(profile, rng, dt, x_static)
    params = _parameter_columns(loader, load, mass)
    x0, u0 = static_state(params[:, 0])
    n_pump = loader.pump.shaft_speed
    z0 = u0 * n_pump / cyl.area_m2 / profile.integral_gain
    gains = np.tile([[profile.position_gain], [profile.integral_gain]], (1, t.size))
    controls = np.vstack((x_ref, v_ref, gains, params))
    integrator = ca.integrator(
        "lift",
        "cvodes",
        {
            "x": (state := ca.SX.sym("s", x0.size + 1)),
            "u": (u := ca.SX.sym("u", controls.shape[0])),
            "ode": ode(state, u),
        },
        0.0,
        t[1:],
        {"abstol": 1e-8, "reltol": 1e-7, "max_num_steps": 100_000},
    )
    start = np.append(x0, z0)
    try:
        states = np.asarray(integrator(x0=start, u=controls[:, :-1])["xf"], dtype=float)
    except RuntimeError as error:
        raise RuntimeError(f"synthetic lift test did not integrate: {error}") from error
    states = np.column_stack((start, states))
    values = np.asarray(truth_function.map(t.size)(states, controls), dtype=float)
    truth = dict(zip(_TRUTH_NAMES, values, strict=True)) | {"load_mass": mass}

    def sense(true: np.ndarray, noise: float, step: float, offset: float) -> np.ndarray:
        measured = true + offset + noise * rng.standard_normal(true.size)
        return np.round(measured / step) * step if step > 0.0 else measured

    o = sensors
    flow = sense(truth["flow"], o.flow_noise_m3_s, o.flow_step_m3_s, o.flow_offset_m3_s)
    outliers = rng.random(flow.size) < o.outlier_fraction
    flow[outliers] = 0.0
    pressure = (o.pressure_noise_pa, o.pressure_step_pa, o.pressure_offset_pa)
    record = MeasurementRecord(
        time_s=t,
        position_m=sense(truth["x"], o.position_noise_m, o.position_step_m, o.position_offset_m),
        p_a_pa=sense(truth["p_a"], *pressure),
        p_b_pa=sense(truth["p_b"], *pressure),
        load_mass_kg=mass.copy(),
        flow_m3_s=flow,
    )
    if o.chassis:  # drawn after the other channels: their noise does not change with them
        accel = (o.acceleration_noise_m_s2, o.acceleration_step_m_s2, 0.0)
        record = dataclasses.replace(
            record,
            pitch_rad=sense(truth["theta_1"], o.pitch_noise_rad, 0.0, 0.0),
            specific_force_m_s2=np.column_stack(
                [sense(truth[name], *accel) for name in ("f_Hx", "f_Hy", "f_Ny")]
            ),
        )
    truth["outliers"] = outliers.astype(float)
    fr, lk = loader.friction, loader.leakage
    parameters = {
        "f_s": fr.f_s,
        "tau_s": fr.tau_s,
        "gamma": fr.gamma,
        "f_c": fr.f_c,
        "f_v": fr.f_v,
        "C": o.flow_offset_m3_s,
        "K_oil": loader.hydraulics.bulk_modulus,
        "k_Lp": lk.k_lp,
        "k_Lv": lk.k_lv,
    }
    return SyntheticRecording(record, truth, cyl, parameters)
