r"""ISO 8608:2016 random road profiles by class, generated from a seed, and their PSD check.

ISO 8608 describes a road by the one-sided displacement power spectral density over spatial
frequency n (cycles/m):

.. math::

    G_d(n) = G_d(n_0) \left( \frac{n}{n_0} \right)^{-w}, \qquad n_0 = 0.1\ \mathrm{cycles/m},
    \quad w = 2,

with the class's geometric-mean G_d(n_0) (:data:`CLASS_PSD_M3`: A 16e-6 m³ ... H 262144e-6 m³,
a factor 4 per class; class limits a factor 2 either side) over 0.011 <= n <= 2.83 cycles/m.

Generation (sinusoid superposition with random phases, summed by an inverse FFT): on a period P,
spatial frequencies n_k = k / P inside the band get amplitudes A_k = sqrt(2 G_d(n_k) Δn), Δn = 1 / P,
and phases uniform in [0, 2π) from the seed; h(s) = Σ A_k cos(2π n_k s + φ_k). The variance is
then Σ G_d(n_k) Δn, the Riemann sum of ∫ G_d dn = G_d(n_0) n_0² (1/n_1 − 1/n_2) for w = 2. P is the
road length, but at least 1 / n_1, so the longest wave of the band fits; a longer period is cut.
"""

from __future__ import annotations

import math

import numpy as np

from loader_model.parameters.road_classes import (
    CLASS_PSD_M3,
    ISO8608_BAND_CYCLES_M,
    REFERENCE_SPATIAL_FREQUENCY_CYCLES_M,
    WAVINESS,
)
from loader_model.simulation._checks import as_number, as_seed
from loader_model.simulation.roads import RoadProfile

__all__ = [
    "CLASS_PSD_M3",
    "ISO8608_BAND_CYCLES_M",
    "REFERENCE_SPATIAL_FREQUENCY_CYCLES_M",
    "WAVINESS",
    "classify_psd",
    "displacement_psd",
    "estimate_psd",
    "iso8608_profile",
    "profile_variance",
]


def _check_class(road_class: object) -> str:
    if not isinstance(road_class, str) or road_class.upper() not in CLASS_PSD_M3:
        raise ValueError(f"road_class must be one of {tuple(CLASS_PSD_M3)}; got {road_class!r}")
    return road_class.upper()


def _check_band(band_cycles_m: object) -> tuple[float, float]:
    try:
        low, high = (float(value) for value in band_cycles_m)  # type: ignore[attr-defined]
    except (TypeError, ValueError):
        raise ValueError(
            f"band_cycles_m must be (low, high) in cycles/m; got {band_cycles_m!r}"
        ) from None
    if not 0.0 < low < high < math.inf:
        raise ValueError(
            f"band_cycles_m must satisfy 0 < low < high < inf cycles/m; got {band_cycles_m!r}"
        )
    return low, high


def displacement_psd(spatial_frequency_cycles_m: object, road_class: str) -> np.ndarray:
    """G_d(n) in m³ of the class's geometric mean at n in cycles/m (n > 0)."""
    n = np.asarray(spatial_frequency_cycles_m, dtype=float)
    if np.any(~(n > 0.0)) or np.any(~np.isfinite(n)):
        raise ValueError("spatial_frequency_cycles_m must be finite and > 0 cycles/m")
    level_m3 = CLASS_PSD_M3[_check_class(road_class)]
    return level_m3 * (n / REFERENCE_SPATIAL_FREQUENCY_CYCLES_M) ** (-WAVINESS)


def profile_variance(
    road_class: str, band_cycles_m: tuple[float, float] = ISO8608_BAND_CYCLES_M
) -> float:
    """Closed-form variance ∫ G_d dn = G_d(n_0) n_0² (1/n_1 − 1/n_2) in m² over the band."""
    low, high = _check_band(band_cycles_m)
    n0 = REFERENCE_SPATIAL_FREQUENCY_CYCLES_M
    return CLASS_PSD_M3[_check_class(road_class)] * n0**2 * (1.0 / low - 1.0 / high)


def iso8608_profile(
    road_class: str,
    length_m: float,
    *,
    seed: int,
    spacing_m: float = 0.02,
    band_cycles_m: tuple[float, float] = ISO8608_BAND_CYCLES_M,
    start_m: float = 0.0,
) -> RoadProfile:
    """Random road of ISO 8608 ``road_class`` from ``seed`` (see module notes).

    Parameters
    ----------
    road_class : str
        ``"A"`` to ``"H"``.
    length_m : float
        Length in m, (0, 1e5].
    seed : int
        Seed of the phases (``numpy.random.default_rng``).
    spacing_m : float
        Vertex spacing in m, (0, 0.1], and at most a quarter of the shortest wavelength 1 / n_2.
    band_cycles_m : (float, float)
        Spatial frequency band (n_1, n_2) in cycles/m.
    start_m : float
        Distance of the first vertex; the profile starts at height 0 there (a constant is removed,
        which leaves the PSD unchanged) and is flat at 0 before it.

    Returns
    -------
    RoadProfile
        Vertices every ``spacing_m``, linear in between.
    """
    road_class = _check_class(road_class)
    length_m = as_number(length_m, "length_m", "m", minimum=0.0, maximum=1e5, strict_minimum=True)
    low, high = _check_band(band_cycles_m)
    spacing_m = as_number(
        spacing_m,
        "spacing_m",
        "m",
        minimum=0.0,
        maximum=min(0.1, 0.25 / high),
        strict_minimum=True,
    )
    start_m = as_number(start_m, "start_m", "m")
    seed = as_seed(seed)
    samples = math.ceil(length_m / spacing_m) + 1
    period_samples = max(samples, math.ceil(1.0 / (low * spacing_m)))
    period_samples += period_samples % 2
    n = np.fft.rfftfreq(period_samples, d=spacing_m)
    in_band = (n >= low) & (n <= high) & (np.arange(n.size) < n.size - 1)  # no Nyquist term
    amplitude_m = np.zeros(n.size)
    amplitude_m[in_band] = np.sqrt(
        2.0 * displacement_psd(n[in_band], road_class) / (period_samples * spacing_m)
    )
    phase = np.random.default_rng(seed).uniform(0.0, 2.0 * np.pi, n.size)
    spectrum = 0.5 * period_samples * amplitude_m * np.exp(1j * phase)
    height_m = np.fft.irfft(spectrum, n=period_samples)[:samples]
    distance_m = start_m + spacing_m * np.arange(samples)
    return RoadProfile(
        distance_m, height_m - height_m[0], name=f"ISO 8608 class {road_class}, seed {seed}"
    )


def estimate_psd(
    profile: RoadProfile,
    *,
    band_cycles_m: tuple[float, float] = (0.05, 2.0),
    segment_m: float = 102.4,
) -> tuple[float, float]:
    """Fit G_d(n_0) in m³ and the waviness w to the Welch PSD of a profile's vertices.

    The vertices must be uniformly spaced. Welch's method (Hann window, segments of ``segment_m``,
    half overlap) estimates the one-sided PSD; a least-squares line through log G_d against
    log(n / n_0) inside ``band_cycles_m`` gives the level at n_0 and the slope −w.

    Returns
    -------
    (float, float)
        G_d(n_0) in m³ and w.
    """
    low, high = _check_band(band_cycles_m)
    spacing = np.diff(profile.distance_m)
    if np.ptp(spacing) > 1e-9 * spacing.mean():
        raise ValueError("profile vertices must be uniformly spaced to estimate the PSD")
    per_segment = round(
        as_number(segment_m, "segment_m", "m", minimum=0.0, strict_minimum=True) / spacing.mean()
    )
    if per_segment > profile.height_m.size:
        raise ValueError(
            f"segment_m = {segment_m:g} m is longer than the profile "
            f"({profile.end_m - profile.start_m:g} m)"
        )
    from scipy import signal  # imported here: scipy.signal takes about a second to import

    n, psd_m3 = signal.welch(profile.height_m, fs=1.0 / spacing.mean(), nperseg=per_segment)
    keep = (n >= low) & (n <= high)
    if np.count_nonzero(keep) < 3:
        raise ValueError(f"band_cycles_m {band_cycles_m!r} holds fewer than 3 Welch frequencies")
    x = np.log(n[keep] / REFERENCE_SPATIAL_FREQUENCY_CYCLES_M)
    slope, intercept = np.polyfit(x, np.log(psd_m3[keep]), 1)
    return float(np.exp(intercept)), float(-slope)


def classify_psd(level_m3: float) -> str:
    """ISO 8608 class whose limits (geometric mean ÷ 2 to × 2) hold G_d(n_0) = ``level_m3``."""
    level_m3 = as_number(level_m3, "level_m3", "m³", minimum=0.0, strict_minimum=True)
    for letter, mean_m3 in CLASS_PSD_M3.items():
        if level_m3 < 2.0 * mean_m3:
            return letter
    return "H"
