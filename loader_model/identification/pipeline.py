"""From a measurement record to the regressions of Eq. 44-48 (section 4.1).

Position and pressures pass through Savitzky-Golay filters of one window (:mod:`.derivatives`):
x̂, v = ẋ, a = ẍ, p̂_A, p̂_B, ṗ_A.

Eq. 44 is filtered with one kernel throughout: the low-pass h₂ contained in the second-derivative
filter (:func:`~.derivatives.acceleration_kernel`) is applied to p_A, p_B, F_L (with chassis
columns: the gravity part of :mod:`.chassis`, and the specific forces), so the measured
friction is h₂ ∗ F_f. The friction model of Eq. 46 is evaluated at the smoothed
velocity v̂ and the raw p_A and then filtered with h₂ too (``Signals.smooth``), so model and
measurement went through the same kernel. With the plain smoothing filter on p_A, p_B instead,
the noise-free record of the former stand-in cylinder model (10 Hz cutoff) left a 440 N
residual and biased f_s by −53 % and γ by +54 %; with h₂, 1.4 N and below 0.1 %.

Eq. 48 uses the smoothed values and first derivatives; the pump flow Q_A enters unfiltered: it
is not differentiated, and filtering would smear an isolated drop-out over a whole window, where
the robust fit could no longer single it out. Half a window is dropped at each end (the filter's
end effects).

Residuals of filtered signals are correlated, so the covariances add Bartlett-weighted lags
(:mod:`.regression`) up to :data:`COVARIANCE_LAGS_PER_WINDOW` windows (chosen on the stand-in
model's records: with one window the friction standard errors were 1.3-1.9 times the scatter
over 28 seeds, with four within about 20 %).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import maximum_filter1d, minimum_filter1d
from scipy.signal import oaconvolve

from loader_model.identification.chassis import (
    boom_forces,
    boom_turn,
    mechanical_parameter_columns,
)
from loader_model.identification.derivatives import (
    DEFAULT_CUTOFF_HZ,
    acceleration_kernel,
    savgol_derivative,
    savgol_window,
)
from loader_model.identification.equivalent import EquivalentCylinder
from loader_model.identification.friction import (
    fit_friction,
    friction_force,
    measured_friction,
)
from loader_model.identification.leakage import LeakageFit, fit_leakage
from loader_model.identification.measurement import MeasurementRecord
from loader_model.identification.regression import LinearFit

__all__ = [
    "COVARIANCE_LAGS_PER_WINDOW",
    "VALVE_MARGIN_PA",
    "FrictionResult",
    "Signals",
    "identify_friction",
    "identify_leakage",
    "prepare_signals",
    "valid_samples",
]

#: Bartlett lags of the covariances, in derivative-filter windows.
COVARIANCE_LAGS_PER_WINDOW = 4


@dataclass(frozen=True)
class Signals:
    """Filtered signals and derivatives of a record, ends trimmed (SI units).

    Attributes
    ----------
    time, x, v, a, p_a, p_b, dp_a, flow, load_mass : numpy.ndarray
        t, x̂, ẋ, ẍ, p̂_A, p̂_B, ṗ_A, Q_A (unfiltered), m_load.
    window : int
        Savitzky-Golay window in samples.
    cutoff_hz : float
        Its −3 dB cutoff request in Hz.
    x_full, v_full, p_a_raw, p_b_raw, load_mass_raw : numpy.ndarray
        Untrimmed x̂, v̂, raw p_A, p_B and load mass (for the friction equation, see
        :meth:`smooth`).
    keep : slice
        The samples kept after trimming the filter's ends.
    sample_rate_hz : float
        Sample rate in Hz.
    pitch_full, pitch_rate, specific_force : numpy.ndarray or None
        Records with chassis columns: untrimmed smoothed pitch θ̂1, pitch rate θ̇1 (rad/s) and
        the specific forces filtered with h₂ (n, 3), both trimmed (:mod:`.chassis`).
    """

    time: np.ndarray
    x: np.ndarray
    v: np.ndarray
    a: np.ndarray
    p_a: np.ndarray
    p_b: np.ndarray
    dp_a: np.ndarray
    flow: np.ndarray
    load_mass: np.ndarray
    window: int
    cutoff_hz: float
    x_full: np.ndarray
    v_full: np.ndarray
    p_a_raw: np.ndarray
    p_b_raw: np.ndarray
    load_mass_raw: np.ndarray
    keep: slice
    sample_rate_hz: float
    pitch_full: np.ndarray | None = None
    pitch_rate: np.ndarray | None = None
    specific_force: np.ndarray | None = None

    def smooth(self, columns: np.ndarray) -> np.ndarray:
        """Filter untrimmed columns (n, k) like the acceleration (kernel h₂), then trim."""
        kernel = acceleration_kernel(self.window, self.sample_rate_hz)  # symmetric
        return oaconvolve(columns, kernel[:, None], mode="same", axes=0)[self.keep]


def prepare_signals(
    record: MeasurementRecord,
    shaft_speed_rev_s: float,
    cutoff_hz: float = DEFAULT_CUTOFF_HZ,
    cylinder: EquivalentCylinder | None = None,
) -> Signals:
    """Filter and differentiate a record (see the module docstring).

    ``cylinder`` converts a boom-angle column to the piston position (kinematically, as the
    paper did); it is needed only for records with ``phi`` instead of ``x_cyl``.
    """
    if record.position_m is None and cylinder is None:
        raise ValueError("the record gives the boom angle phi: pass the cylinder to convert it")
    position = record.position(cylinder.position_from_boom_angle if cylinder else np.asarray)
    fs = record.sample_rate_hz
    window = savgol_window(fs, cutoff_hz)
    if record.time_s.size < 3 * window:
        raise ValueError(
            f"record of {record.time_s.size} samples is too short for the derivative window of "
            f"{window} samples at {fs:g} Hz and cutoff {cutoff_hz:g} Hz; need at least "
            f"{3 * window}"
        )

    def d(signal: np.ndarray, order: int) -> np.ndarray:
        return savgol_derivative(signal, fs, order, window)

    keep = slice(window // 2, record.time_s.size - window // 2)
    x_full, v_full = d(position, 0), d(position, 1)
    chassis: dict[str, np.ndarray] = {}
    if record.has_chassis:
        pitch = np.asarray(record.pitch_rad)
        kernel = acceleration_kernel(window, fs)
        filtered = oaconvolve(record.specific_force_m_s2, kernel[:, None], mode="same", axes=0)
        chassis = {
            "pitch_full": d(pitch, 0),
            "pitch_rate": d(pitch, 1)[keep],
            "specific_force": filtered[keep],
        }
    return Signals(
        time=record.time_s[keep],
        x=x_full[keep],
        v=v_full[keep],
        a=d(position, 2)[keep],
        p_a=d(record.p_a_pa, 0)[keep],
        p_b=d(record.p_b_pa, 0)[keep],
        dp_a=d(record.p_a_pa, 1)[keep],
        flow=record.flow(shaft_speed_rev_s)[keep],
        load_mass=record.load_mass_kg[keep],
        window=window,
        cutoff_hz=cutoff_hz,
        x_full=x_full,
        v_full=v_full,
        p_a_raw=record.p_a_pa,
        p_b_raw=record.p_b_pa,
        load_mass_raw=record.load_mass_kg,
        keep=keep,
        sample_rate_hz=fs,
        **chassis,
    )


@dataclass(frozen=True)
class FrictionResult:
    """Friction fit with the measured friction it was fitted to (for the fit plot).

    ``used`` marks the samples of the fit (:func:`valid_samples`).
    """

    fit: LinearFit
    measured: np.ndarray
    signals: Signals
    used: np.ndarray

    @property
    def modelled(self) -> np.ndarray:
        """The fitted Eq. 46 at every sample, filtered like the measured friction."""
        s = self.signals
        return s.smooth(friction_force(self.fit.values, s.v_full, s.p_a_raw)[:, None])[:, 0]


#: Margin in Pa inside the charge and relief pressures for the friction fit's samples.
VALVE_MARGIN_PA = 10e5


def valid_samples(signals: Signals, cylinder: EquivalentCylinder) -> np.ndarray:
    """Samples of the friction fit (trimmed): one load, valves shut, over two filter windows.

    Left out: samples whose derivative window sees a changing bucket-load mass (the filter
    would mix parameter sets), and, with a parameter file, samples within two windows of a
    measured p_A outside [p_charge + 10 bar, p_relief − 10 bar]: there the check or relief
    valve opens, and the sharp pressure transients do not commute with the filters. On the
    noise-free friction test of seed 7 that left 48.7 N r.m.s. (2.6 kN at most) between the
    filtered Eq. 44 and the filtered true friction; without those samples (5.4 %), 3.9 N (128 N).
    """
    wide = 2 * signals.window
    mass = signals.load_mass_raw
    keep = maximum_filter1d(mass, signals.window) == minimum_filter1d(mass, signals.window)
    if cylinder.parameters is not None:
        hydraulics = cylinder.parameters[0].hydraulics
        p_a = signals.p_a_raw
        keep &= maximum_filter1d(p_a, wide) < hydraulics.relief_pressure - VALVE_MARGIN_PA
        keep &= minimum_filter1d(p_a, wide) > hydraulics.charge_pressure + VALVE_MARGIN_PA
    return keep[signals.keep]


def identify_friction(
    signals: Signals, cylinder: EquivalentCylinder, level: float = 0.95
) -> FrictionResult:
    """Table 4 from filtered signals: F_f by Eq. 44 (corrected), fit of Eq. 46.

    With chassis signals (and a cylinder built by
    :meth:`~.equivalent.EquivalentCylinder.from_parameters`), the cylinder force that moves the
    boom comes from the boom's equation of motion on the moving chassis (:mod:`.chassis`): its
    gravity part, a function of positions, is filtered with h₂ like the pressures; its dynamic
    part is evaluated at the filtered derivatives. Without them, F_L and m_eq take the lever at
    each sample's boom angle (:mod:`.equivalent`) with the chassis at rest.
    """
    s = signals
    smoothed = s.smooth(np.column_stack((s.p_a_raw, s.p_b_raw)))
    if s.specific_force is not None and cylinder.parameters is not None:
        load_force, inertial_force = _chassis_forces(s, cylinder)
    else:
        load_force = s.smooth(cylinder.load_force(s.load_mass_raw, s.x_full)[:, None])[:, 0]
        inertial_force = cylinder.inertial_force(s.load_mass, s.x, s.v, s.a)
    area, alpha = cylinder.area_m2, cylinder.alpha
    p_a, p_b = smoothed.T
    measured = measured_friction(area, alpha, p_a, p_b, load_force, inertial_force)
    used = valid_samples(s, cylinder)
    fit = fit_friction(
        s.v_full,
        s.p_a_raw,
        measured[used],
        smooth=lambda columns: s.smooth(columns)[used],
        lags=COVARIANCE_LAGS_PER_WINDOW * s.window,
        level=level,
    )
    return FrictionResult(fit, measured, s, used)


def _chassis_forces(s: Signals, cylinder: EquivalentCylinder) -> tuple[np.ndarray, np.ndarray]:
    """(h₂-filtered gravity part, dynamic part) of the boom's cylinder force (:mod:`.chassis`)."""
    loader, load = cylinder.parameters
    params = mechanical_parameter_columns(loader, load, s.load_mass_raw)
    retracted = loader.cylinders.retracted_length
    psi = boom_turn(s.x_full, retracted, params, cylinder.boom_turn(s.x_full))
    zeros = np.zeros_like(psi)  # the gravity part depends on positions only
    gravity, _ = boom_forces(
        s.pitch_full, psi, zeros, zeros, zeros, np.zeros((psi.size, 3)), params
    )
    _, dynamic = boom_forces(
        s.pitch_full[s.keep],
        psi[s.keep],
        s.pitch_rate,
        s.v,
        s.a,
        s.specific_force,
        params[:, s.keep],
    )
    return s.smooth(gravity[:, None])[:, 0], dynamic


def identify_leakage(
    signals: Signals, cylinder: EquivalentCylinder, *, robust: bool = True, level: float = 0.95
) -> LeakageFit:
    """Table 5 from filtered signals: the robust regression of Eq. 48."""
    return fit_leakage(
        signals.flow,
        signals.v,
        cylinder.area_m2,
        cylinder.volume_a(signals.x),
        signals.dp_a,
        signals.p_a,
        signals.p_b,
        robust=robust,
        lags=COVARIANCE_LAGS_PER_WINDOW * signals.window,
        level=level,
    )
