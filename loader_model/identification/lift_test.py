"""Options of the synthetic lift test: the paper's Tables 4 and 5, sensors, test profile.

Used by :mod:`.synthetic`; kept apart so that options are importable without CasADi.
:func:`reference_schedule` turns a profile into the reference of the position law.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["TABLE4", "TABLE5", "LiftProfile", "SensorOptions", "reference_schedule"]

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
        Logging rate in Hz (also the integration grid).
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
    chassis : bool
        Log the chassis channels (pitch θ1, specific forces f_Hx, f_Hy, f_Ny of section 3.3).
    pitch_noise_rad, acceleration_noise_m_s2, acceleration_step_m_s2 : float
        Their noise (pitch, each specific force) and the accelerometers' quantisation step:
        0.05° of an IMU's pitch, 0.05 m/s² (5 mg) and 0.001 m/s² by default.
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
    chassis: bool = True
    pitch_noise_rad: float = 8.7e-4
    acceleration_noise_m_s2: float = 0.05
    acceleration_step_m_s2: float = 1e-3
    seed: int = 0

    @classmethod
    def friction_test(cls, seed: int = 0) -> SensorOptions:
        """Sensors for the friction test: a 5 µm position sensor (1 µm steps, e.g. a
        magnetostrictive in-cylinder sensor) and 0.01 m/s² accelerometers; the rest default.

        The acceleration estimate ẍ from the position dominates the measured friction's noise:
        with the default 50 µm, the residual of Eq. 44 was 796-879 N r.m.s. (seeds 0-2),
        with 5 µm 100-110 N.
        """
        return cls(
            position_noise_m=5e-6,
            position_step_m=1e-6,
            acceleration_noise_m_s2=0.01,
            seed=seed,
        )


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
        Bottom and highest top of the strokes, piston position in m; each top is drawn in the
        upper half. The run starts at the plant's static position and moves to the bottom
        during the first hold.
    hold_s : float
        Hold between strokes in s (loads change during the hold at the bottom).
    load_masses_kg : tuple of float
        Bucket loads drawn per cycle, in kg (> 0; the paper: 340 kg and 770 kg).
    log_speeds : bool
        Draw the speeds log-uniformly over ``speed_range_m_s`` (as many slow strokes per
        decade as fast ones: the Stribeck region lies below 1/τ_s = 0.025 m/s).
    position_gain : float
        k_x of the position law in 1/s.
    integral_gain : float
        k_i of the position law in 1/s².
    """

    cycles: int = 12
    speed_range_m_s: tuple[float, float] = (0.02, 0.15)
    ramp_range_s: tuple[float, float] = (0.4, 1.0)
    position_range_m: tuple[float, float] = (0.03, 0.28)
    hold_s: float = 1.5
    load_masses_kg: tuple[float, ...] = (340.0, 555.0, 770.0)
    log_speeds: bool = False
    position_gain: float = 8.0
    integral_gain: float = 8.0

    @classmethod
    def friction_test(cls) -> LiftProfile:
        """The friction test: 12 cycles at speeds log-uniform over 0.01-0.25 m/s.

        Strokes below 1/τ_s = 0.025 m/s show the Stribeck part, strokes near the pump's limit
        (0.29 m/s at full displacement) the tanh(γ v) saturation that separates γ from f_s and
        f_C; with the default 0.02-0.15 m/s, f_s, γ and f_C were ±25-45 % (95 % intervals).
        """
        return cls(speed_range_m_s=(0.01, 0.25), log_speeds=True)


def _raised_cosine_ramp(t: np.ndarray, start: float, duration: float) -> np.ndarray:
    u = np.clip((t - start) / duration, 0.0, 1.0)
    return 0.5 - 0.5 * np.cos(np.pi * u)


def reference_schedule(
    profile: LiftProfile, rng: np.random.Generator, dt: float, x_start: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Reference of the lift test on the sample grid: time, v_ref, x_ref and load mass.

    Strokes from the bottom to random tops and back with raised-cosine speed ramps, a hold
    between strokes (loads change during the hold at the bottom), starting at ``x_start``.
    """
    low, high = profile.position_range_m
    pieces: list[tuple[float, float, float]] = []  # (speed, ramp, distance) per stroke
    loads = rng.choice(profile.load_masses_kg, size=profile.cycles)
    for _ in range(profile.cycles):
        top = rng.uniform(low + 0.5 * (high - low), high)
        for direction in (1.0, -1.0):
            speed = rng.uniform(*profile.speed_range_m_s)
            if profile.log_speeds:  # the same draw, spread evenly over the decades
                low_speed, high_speed = profile.speed_range_m_s
                fraction = (speed - low_speed) / (high_speed - low_speed)
                speed = low_speed * (high_speed / low_speed) ** fraction
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
    # from the static position to the bottom during the first hold
    approach = (x_start - low) * (1.0 - _raised_cosine_ramp(t, 0.0, 0.8 * profile.hold_s))
    v_approach = np.gradient(approach, dt)
    x_ref = low + np.concatenate(([0.0], np.cumsum(0.5 * (v_ref[1:] + v_ref[:-1]) * dt)))
    return t, v_ref + v_approach, x_ref + approach, mass
