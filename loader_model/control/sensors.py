r"""Sensors of the active damping controller (section 3.3) and a seeded numpy sensor model.

The controller reads five signals, all plant outputs (:data:`loader_model.plant.plant.OUTPUT_NAMES`):

- ``f_Hx``, ``f_Hy``: triaxial accelerometer at the chassis centre of gravity H (x and y used);
- ``f_Ny``: vertical accelerometer at N, a chassis point ahead of H;
- ``phi``: boom angle relative to the chassis, φ = θ2 − θ1;
- ``p_A``: piston-side pressure, gauge [Pa].

Accelerometers read specific force (acceleration minus gravity) in the chassis frame, so a loader
at rest pitched nose-up by θ1 reads f_Hx = g sin θ1 and f_Hy = f_Ny = g cos θ1 (checked on the
plant in ``tests/control/test_controllers_sensors.py``).
The pitch acceleration follows from the two vertical readings (rigid chassis):

.. math::

    f_{Ny} - f_{Hy} = \ddot\theta_1 (N_x - H_x) - \dot\theta_1^2 (N_y - H_y)
    \quad\Rightarrow\quad \hat{\ddot\theta}_1 = \frac{f_{Ny} - f_{Hy}}{N_x - H_x}

with H the origin, neglecting the centripetal term (second order in θ̇1).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from loader_model.plant.layout import PlantLayout

__all__ = ["SENSOR_NAMES", "SensorModel", "pitch_acceleration", "quantise", "sensor_signals"]

#: Order of the controller's ``y_sensor`` input; each is a plant output of the same name.
SENSOR_NAMES: tuple[str, ...] = ("f_Hx", "f_Hy", "f_Ny", "phi", "p_A")


def pitch_acceleration(f_hy: Any, f_ny: Any, accelerometer_x: Any) -> Any:
    """θ̈1 estimated from the vertical readings at H and N (section 3.3); numpy or CasADi."""
    return (f_ny - f_hy) / accelerometer_x


def quantise(value: Any, step: Any) -> Any:
    """``value`` rounded to the nearest multiple of ``step`` (halves up); unchanged where
    ``step`` is 0. NumPy arrays or CasADi expressions (the compiled loop uses the same law)."""
    import casadi as ca

    if isinstance(value, ca.SX | ca.MX) or isinstance(step, ca.SX | ca.MX):
        safe = ca.if_else(step > 0, step, 1.0)
        return ca.if_else(step > 0, safe * ca.floor(value / safe + 0.5), value)
    step = np.asarray(step, dtype=float)
    safe = np.where(step > 0, step, 1.0)
    return np.where(step > 0, safe * np.floor(np.asarray(value) / safe + 0.5), value)


def sensor_signals(y: np.ndarray, layout: PlantLayout | None = None) -> np.ndarray:
    """The ideal sensor readings (order :data:`SENSOR_NAMES`) from plant outputs ``y``.

    ``y`` has the plant outputs along its last axis (one sample or a time series), those of
    the machine ``layout``'s plant (default the skid-steer's).
    """
    from loader_model.plant.layout import SKID_STEER

    names = (layout or SKID_STEER).output_names
    y = np.asarray(y, dtype=float)
    if y.shape[-1] != len(names):
        raise ValueError(f"y has {y.shape[-1]} outputs on its last axis; expected {len(names)}")
    return y[..., [names.index(name) for name in SENSOR_NAMES]]


@dataclass(frozen=True)
class SensorModel:
    """Noise, offset and quantisation of the five sensors (order :data:`SENSOR_NAMES`), seeded.

    Attributes
    ----------
    noise_std : tuple of 5 float
        Standard deviation of white measurement noise per sample, in the signal's unit.
    offset : tuple of 5 float
        Constant bias added to each reading.
    quantisation : tuple of 5 float
        Step of the converter (0: none); readings are rounded to the nearest multiple.
    seed : int
        Seed of the noise generator (:meth:`measure` is deterministic for a given seed).
    """

    noise_std: tuple[float, ...] = (0.0,) * 5
    offset: tuple[float, ...] = (0.0,) * 5
    quantisation: tuple[float, ...] = (0.0,) * 5
    seed: int = 0

    def __post_init__(self) -> None:
        for name in ("noise_std", "offset", "quantisation"):
            value = np.asarray(getattr(self, name), dtype=float)
            if value.shape != (len(SENSOR_NAMES),) or not np.all(np.isfinite(value)):
                raise ValueError(f"{name} = {value!r}; allowed: {len(SENSOR_NAMES)} finite numbers")
            if name != "offset" and np.any(value < 0):
                raise ValueError(f"{name} = {value!r}; allowed: numbers >= 0")

    def errors(self, count: int) -> np.ndarray:
        """Offset plus white noise of ``count`` samples (count × 5), from :attr:`seed`."""
        rng = np.random.default_rng(self.seed)
        noise = rng.standard_normal((int(count), len(SENSOR_NAMES)))
        return np.asarray(self.offset) + noise * np.asarray(self.noise_std)

    def measure(self, readings: np.ndarray) -> np.ndarray:
        """Corrupt ideal ``readings`` (samples × 5, or one sample of 5) with offset, noise and
        rounding (:func:`quantise`); the simulator applies the same errors in its 1 kHz loop."""
        readings = np.asarray(readings, dtype=float)
        rows = readings.reshape(-1, len(SENSOR_NAMES))
        noisy = rows + self.errors(rows.shape[0])
        return quantise(noisy, np.asarray(self.quantisation)).reshape(readings.shape)
