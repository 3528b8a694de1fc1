r"""Synthetic identification records from a small stand-in cylinder model (section 4.1).

**Stand-in model until the plant lands.** The records come from one equivalent cylinder built
from the same equations the estimators fit, not from the full hydraulic plant
(``loader_model.plant``, to come); a later change can swap the source behind
:func:`synthesize` and keep its output type (:class:`~.measurement.MeasurementRecord`).

The test follows the paper: "the boom cylinders were repeatedly extended and retracted with
varying rates and loads". States x (piston position), v = ẋ, p_A, p_B:

.. math::

    m_{eq}(m) \dot v &= A_p (p_A - \alpha p_B) - F_f(v, p_A) - F_L(m) \\
    \dot p_A &= \frac{K_{oil}}{V_A(x)} \big(Q_A - A_p v - Q_L\big) \\
    \dot p_B &= \frac{K_{oil}}{V_B(x)} \big(-G_c (p_B - p_c) + \alpha A_p v + Q_L\big)

with F_f of Eq. 46 (errata 10 reading, :mod:`.friction`), Q_L = k_Lp (p_A − p_B) + k_Lv v
(Eq. 47 in the sign of Eq. 48, :mod:`.leakage`), the rod side fed from the charge line p_c
through a conductance G_c (Eq. 37), F_L and m_eq of :mod:`.equivalent`. The pump flow follows a
smooth trapezoidal velocity profile with position feedback,
Q_A = Q_max tanh((A_p v_ref + k_x A_p (x_ref − x)) / Q_max). Load masses change only while the
boom is held, over a smooth ramp. Integrated with ``scipy.integrate.solve_ivp`` (LSODA).

Sensors: Gaussian noise, quantisation step and offset per channel; drop-outs of the flow
estimate (reads 0) on a fraction of samples (outliers); the flow offset defaults to Table 5's C.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from loader_model.identification.equivalent import EquivalentCylinder
from loader_model.identification.friction import friction_force
from loader_model.identification.measurement import MeasurementRecord
from loader_model.parameters import bucket_load, default_loader

__all__ = [
    "TABLE4",
    "TABLE5",
    "LiftProfile",
    "SensorOptions",
    "SyntheticRecording",
    "synthesize",
]

#: Table 4 in SI units, errata 10 reading (f_C 10.7 N/bar = 1.07e-4 N/Pa).
TABLE4 = {"f_s": 17.0e3, "tau_s": 40.0, "gamma": 5.7, "f_c": 1.07e-4, "f_v": 8.13e3}
#: Table 5 in SI units: C [m³/s], K_oil [Pa], k_Lp [m³/(s·Pa)], k_Lv [m²].
TABLE5 = {"C": -3.2e-4, "K_oil": 1.64e9, "k_Lp": 2.87e-11, "k_Lv": -5.0e-4}


@dataclass(frozen=True)
class SensorOptions:
    """Sensor model of the synthetic record (each channel: true + offset + noise, quantised).

    Attributes
    ----------
    sample_rate_hz : float
        Logging rate in Hz.
    pressure_noise_pa, position_noise_m, flow_noise_m3_s : float
        Standard deviations of white Gaussian noise.
    pressure_step_pa, position_step_m, flow_step_m3_s : float
        Quantisation steps (0: none).
    pressure_offset_pa, position_offset_m : float
        Constant offsets of p_A and p_B, and of x_cyl.
    flow_offset_m3_s : float
        Offset of the pump-flow estimate; Table 5's C by default.
    outlier_fraction : float
        Fraction of flow samples that drop out to 0 (sensor drop-outs).
    seed : int
        Seed of ``numpy.random.default_rng`` (noise, outliers and the test profile).
    """

    sample_rate_hz: float = 500.0
    pressure_noise_pa: float = 0.5e5
    position_noise_m: float = 5e-5
    flow_noise_m3_s: float = 1.0e-4
    pressure_step_pa: float = 0.1e5
    position_step_m: float = 1e-5
    flow_step_m3_s: float = 1e-6
    pressure_offset_pa: float = 0.0
    position_offset_m: float = 0.0
    flow_offset_m3_s: float = TABLE5["C"]
    outlier_fraction: float = 0.0
    seed: int = 0


@dataclass(frozen=True)
class LiftProfile:
    """The lift test: cycles of extend, hold, retract, hold with random rates and loads.

    Attributes
    ----------
    cycles : int
        Number of extend-retract cycles.
    speed_range_m_s : (float, float)
        Range of the cylinder speeds, drawn per stroke, in m/s.
    ramp_range_s : (float, float)
        Range of the speed ramp durations (raised cosine) in s.
    position_range_m : (float, float)
        Lowest and highest piston position in m (strokes drawn inside).
    hold_s : float
        Hold between strokes in s (loads change during the hold at the bottom).
    load_masses_kg : tuple of float
        Bucket loads drawn per cycle (the paper: empty, 340 kg, 770 kg).
    """

    cycles: int = 12
    speed_range_m_s: tuple[float, float] = (0.02, 0.25)
    ramp_range_s: tuple[float, float] = (0.15, 0.8)
    position_range_m: tuple[float, float] = (0.03, 0.42)
    hold_s: float = 1.5
    load_masses_kg: tuple[float, ...] = (0.0, 340.0, 770.0)


@dataclass(frozen=True)
class SyntheticRecording:
    """A synthetic record and the true signals behind it.

    Attributes
    ----------
    record : MeasurementRecord
        What the sensors logged (write it with ``write_measurement_csv(path, record.columns())``).
    truth : dict of str to numpy.ndarray
        True ``x``, ``v``, ``a`` (ẍ), ``p_a``, ``p_b``, ``dp_a`` (ṗ_A), ``flow`` (Q_A) and
        ``load_mass`` at the sample times, derivatives from the model's right-hand side.
    cylinder : EquivalentCylinder
        The equivalent cylinder and load model used.
    parameters : dict of str to float
        The true friction (:data:`TABLE4` names) and leakage (:data:`TABLE5` names) values.
    """

    record: MeasurementRecord
    truth: dict[str, np.ndarray]
    cylinder: EquivalentCylinder
    parameters: dict[str, float] = field(default_factory=dict)


def _raised_cosine_ramp(t: np.ndarray, start: float, duration: float) -> np.ndarray:
    u = np.clip((t - start) / duration, 0.0, 1.0)
    return 0.5 - 0.5 * np.cos(np.pi * u)


def _schedule(profile: LiftProfile, rng: np.random.Generator, dt: float):
    """Reference velocity, position and load mass on a fine grid (fine time, v_ref, x_ref, m)."""
    low, high = profile.position_range_m
    x0 = low
    pieces: list[tuple[float, float, float]] = []  # (speed, ramp, distance) per stroke
    loads = rng.choice(profile.load_masses_kg, size=profile.cycles)
    for _ in range(profile.cycles):
        top = rng.uniform(low + 0.5 * (high - low), high)
        for direction in (1.0, -1.0):
            speed = rng.uniform(*profile.speed_range_m_s)
            ramp = rng.uniform(*profile.ramp_range_s)
            pieces.append((direction * speed, ramp, top - low))
    durations = [abs(d / s) + r for s, r, d in pieces]  # ramps: half the ramp lost each end
    total = profile.hold_s + sum(durations) + profile.hold_s * len(pieces)
    t = np.arange(0.0, total + dt, dt)
    v_ref = np.zeros_like(t)
    mass = np.full_like(t, loads[0])
    start = profile.hold_s
    for k, ((speed, ramp, _), duration) in enumerate(zip(pieces, durations, strict=True)):
        v_ref += speed * (
            _raised_cosine_ramp(t, start, ramp)
            - _raised_cosine_ramp(t, start + duration - ramp, ramp)
        )
        start += duration + profile.hold_s
        cycle = (k + 1) // 2
        if k % 2 == 1 and cycle < profile.cycles:  # at the bottom: change the load
            step = loads[cycle] - loads[cycle - 1]
            mass += step * _raised_cosine_ramp(t, start - profile.hold_s, 0.8 * profile.hold_s)
    x_ref = x0 + np.concatenate(([0.0], np.cumsum(0.5 * (v_ref[1:] + v_ref[:-1]) * dt)))
    return t, v_ref, x_ref, mass


def synthesize(
    sensors: SensorOptions | None = None,
    profile: LiftProfile | None = None,
    *,
    cylinder: EquivalentCylinder | None = None,
    friction: dict[str, float] | None = None,
    leakage: dict[str, float] | None = None,
    charge_pressure_pa: float = 20e5,
    charge_conductance: float = 2e-9,
    max_flow_m3_s: float = 46e-6 * 40.0,
    position_gain: float = 5.0,
) -> SyntheticRecording:
    """Simulate the lift test and log it with the sensor model (see the module docstring).

    Parameters
    ----------
    sensors : SensorOptions, optional
        Sample rate, noise, quantisation, offsets, outliers and seed.
    profile : LiftProfile, optional
        The extend/retract cycles.
    cylinder : EquivalentCylinder, optional
        Default: the shipped default loader with the full-load case's centre of gravity.
    friction, leakage : dict, optional
        True coefficients; default :data:`TABLE4` and :data:`TABLE5` (K_oil, k_Lp, k_Lv).
    charge_pressure_pa, charge_conductance : float
        Charge-line pressure p_c in Pa and the rod side's conductance G_c in m³/(s·Pa).
    max_flow_m3_s : float
        Pump flow limit Q_max (default 46 cm³/rev at 40 rev/s).
    position_gain : float
        k_x of the position feedback in 1/s.
    """
    sensors = sensors or SensorOptions()
    profile = profile or LiftProfile()
    cyl = cylinder or EquivalentCylinder.from_parameters(default_loader(), bucket_load("full"))
    fr = {**TABLE4, **(friction or {})}
    lk = {**TABLE5, **(leakage or {})}
    coefficients = np.array([fr[k] for k in ("f_s", "tau_s", "gamma", "f_c", "f_v")])
    if not sensors.sample_rate_hz > 0.0:
        raise ValueError(f"sample rate must be > 0 Hz; got {sensors.sample_rate_hz!r}")
    if not 0.0 <= sensors.outlier_fraction < 0.5:
        raise ValueError(f"outlier fraction must be in [0, 0.5); got {sensors.outlier_fraction!r}")
    rng = np.random.default_rng(sensors.seed)
    t_fine, v_ref, x_ref, mass = _schedule(profile, rng, 1e-3)
    a_p, alpha, k_oil = cyl.area_m2, cyl.alpha, lk["K_oil"]

    def rhs(t: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """State derivative, load mass and pump flow; t scalar or (n,), y (4,) or (4, n)."""
        x, v, p_a, p_b = y
        m = np.interp(t, t_fine, mass)
        q = a_p * (np.interp(t, t_fine, v_ref) + position_gain * (np.interp(t, t_fine, x_ref) - x))
        q_a = max_flow_m3_s * np.tanh(q / max_flow_m3_s)
        leak = lk["k_Lp"] * (p_a - p_b) + lk["k_Lv"] * v
        f_f = friction_force(coefficients, np.atleast_1d(v), np.atleast_1d(p_a)).reshape(
            np.shape(v)
        )
        acc = (a_p * (p_a - alpha * p_b) - f_f - cyl.load_force(m)) / cyl.inertia(m)
        dp_a = k_oil / cyl.volume_a(x) * (q_a - a_p * v - leak)
        dp_b = (
            k_oil
            / cyl.volume_b(x)
            * (-charge_conductance * (p_b - charge_pressure_pa) + alpha * a_p * v + leak)
        )
        return np.array([v, acc, dp_a, dp_b]), m, q_a

    # Start at rest in equilibrium: F_f(0) = 0, so A_p (p_A − α p_B) = F_L, p_B = p_c.
    p_a0 = cyl.load_force(mass[0]) / a_p + alpha * charge_pressure_pa
    y0 = np.array([x_ref[0], 0.0, float(p_a0), charge_pressure_pa])
    t_samples = np.arange(0.0, t_fine[-1], 1.0 / sensors.sample_rate_hz)
    solution = solve_ivp(
        lambda t, y: rhs(t, y)[0],
        (0.0, t_samples[-1]),
        y0,
        method="LSODA",
        t_eval=t_samples,
        rtol=1e-8,
        atol=np.array([1e-9, 1e-9, 1.0, 1.0]),
        max_step=0.01,
    )
    if not solution.success:  # pragma: no cover - the stand-in model is benign
        raise RuntimeError(f"synthetic lift test did not integrate: {solution.message}")
    states = solution.y
    derivative, masses, flows = rhs(t_samples, states)
    truth = {
        "x": states[0],
        "v": states[1],
        "a": derivative[1],
        "p_a": states[2],
        "p_b": states[3],
        "dp_a": derivative[2],
        "flow": flows,
        "load_mass": masses,
    }

    def sense(true: np.ndarray, noise: float, step: float, offset: float) -> np.ndarray:
        measured = true + offset + noise * rng.standard_normal(true.size)
        return np.round(measured / step) * step if step > 0.0 else measured

    o = sensors
    flow = sense(truth["flow"], o.flow_noise_m3_s, o.flow_step_m3_s, o.flow_offset_m3_s)
    outliers = rng.random(flow.size) < o.outlier_fraction
    flow[outliers] = 0.0
    pressure = (o.pressure_noise_pa, o.pressure_step_pa, o.pressure_offset_pa)
    record = MeasurementRecord(
        time_s=t_samples,
        position_m=sense(truth["x"], o.position_noise_m, o.position_step_m, o.position_offset_m),
        p_a_pa=sense(truth["p_a"], *pressure),
        p_b_pa=sense(truth["p_b"], *pressure),
        load_mass_kg=truth["load_mass"].copy(),
        flow_m3_s=flow,
    )
    truth["outliers"] = outliers.astype(float)
    return SyntheticRecording(record, truth, cyl, {**fr, **lk})
