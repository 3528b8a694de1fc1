"""Sensor errors of a study: scale factor, offset and white noise per controller sensor.

The controllers read five plant outputs (:data:`~loader_model.control.sensors.SENSOR_NAMES`:
accelerometers ``f_Hx``, ``f_Hy``, ``f_Ny``, boom angle ``phi``, pressure ``p_A``). A study may vary
``sensors.<name>.gain``, ``sensors.<name>.offset`` (reading = gain × true value + offset) and
``sensors.<name>.noise_std`` in [parameters], like a parameter-file field, with the unit and the
validated range of :data:`SENSOR_ERROR_FIELDS`. All act inside the compiled 1 kHz period. Gain and
offset: :func:`sensor_controller` wraps the ride controller's Function, corrupting the readings it
sees, with the ten errors as extra settings (one compiled period serves every sample); the
controller starts at its fixed point for the corrupted static readings (it has run at the biased
readings before the course). Noise: the simulator's
:class:`~loader_model.control.sensors.SensorModel` (:func:`sensor_model`), seeded by the sample's
road seed, so every controller of a sample sees the same draw. The stability margin of the gains
is computed with ideal sensors.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from loader_model.parameters.fields import Range

if TYPE_CHECKING:
    from loader_model.plant.layout import PlantLayout
    from loader_model.plant.scenario import PlantScenario

__all__ = [
    "SENSOR_ERROR_FIELDS",
    "corrupted_fixed_point",
    "sensor_controller",
    "sensor_errors",
    "sensor_model",
]

_SENSORS = ("f_Hx", "f_Hy", "f_Ny", "phi", "p_A")
_GAIN = Range(0.5, 2.0, reason="a sensor within a factor 2 of its calibration")
_OFFSETS = {
    "f_Hx": ("m/s^2", Range(-19.62, 19.62, reason="within the 2 g full scale (section 3.3)")),
    "f_Hy": ("m/s^2", Range(-19.62, 19.62, reason="within the 2 g full scale (section 3.3)")),
    "f_Ny": ("m/s^2", Range(-19.62, 19.62, reason="within the 2 g full scale (section 3.3)")),
    "phi": ("rad", Range(-0.576, 0.576, reason="within the 33 deg angle norm (section 3.3)")),
    "p_A": ("Pa", Range(-5e6, 5e6, reason="within 50 bar, a quarter of the 200 bar norm")),
}
_NOISE = {
    "f_Hx": ("m/s^2", Range(0.0, 1.0, reason="up to 0.1 g r.m.s. per sample")),
    "f_Hy": ("m/s^2", Range(0.0, 1.0, reason="up to 0.1 g r.m.s. per sample")),
    "f_Ny": ("m/s^2", Range(0.0, 1.0, reason="up to 0.1 g r.m.s. per sample")),
    "phi": ("rad", Range(0.0, 0.0175, reason="up to 1 deg r.m.s. per sample")),
    "p_A": ("Pa", Range(0.0, 1e6, reason="up to 10 bar r.m.s. per sample")),
}
#: ``sensors.<name>.gain|offset|noise_std`` -> (SI unit, validated range).
SENSOR_ERROR_FIELDS: Mapping[str, tuple[str, Range]] = {
    **{f"sensors.{n}.gain": ("-", _GAIN) for n in _SENSORS},
    **{f"sensors.{n}.offset": _OFFSETS[n] for n in _SENSORS},
    **{f"sensors.{n}.noise_std": _NOISE[n] for n in _SENSORS},
}
_CONTROLLERS: dict[Any, Any] = {}


def sensor_errors(values: Mapping[str, float]) -> np.ndarray:
    """The ten error settings (five gains, then five offsets) from a sample's values by path."""
    gains = [values.get(f"sensors.{n}.gain", 1.0) for n in _SENSORS]
    offsets = [values.get(f"sensors.{n}.offset", 0.0) for n in _SENSORS]
    return np.array(gains + offsets, dtype=float)


def sensor_model(values: Mapping[str, float], seed: int) -> Any:
    """The simulator's :class:`~loader_model.control.sensors.SensorModel` with the sample's noise
    (None without noise)."""
    from loader_model.control.sensors import SensorModel

    noise = tuple(float(values.get(f"sensors.{n}.noise_std", 0.0)) for n in _SENSORS)
    return SensorModel(noise_std=noise, seed=int(seed)) if any(noise) else None


def sensor_controller(kind: str, layout: PlantLayout | None = None) -> Any:
    """``controller(z, y, [settings; errors]) -> (z_next, u)``: ride controller ``kind`` on
    corrupted readings (module notes), built once per process and machine ``layout`` (None or
    the skid-steer: the paper's plant; another: its plant layout's outputs)."""
    import casadi as ca

    from loader_model.control.sensors import SENSOR_NAMES
    from loader_model.plant.plant import OUTPUT_NAMES
    from loader_model.simulation.ride_control import plant_controller

    layout = None if layout is None or layout.machine.is_default else layout
    key = kind if layout is None else (kind, layout)
    if key not in _CONTROLLERS:
        inner = plant_controller(kind, layout)
        names = OUTPUT_NAMES if layout is None else layout.output_names
        z = ca.SX.sym("z", inner.size1_in(0))
        y = ca.SX.sym("y", inner.size1_in(1))
        settings = ca.SX.sym("settings", inner.size1_in(2) + 2 * len(SENSOR_NAMES))
        count = inner.size1_in(2)
        gains = settings[count : count + len(SENSOR_NAMES)]
        offsets = settings[count + len(SENSOR_NAMES) :]
        read = [y[i] for i in range(y.numel())]
        for j, name in enumerate(SENSOR_NAMES):
            index = names.index(name)
            read[index] = gains[j] * y[index] + offsets[j]
        z_next, u = inner(z, ca.vertcat(*read), settings[:count])
        _CONTROLLERS[key] = ca.Function(
            f"{inner.name()}_sensor_errors",
            [z, y, settings],
            [z_next, u],
            ["z", "y", "settings"],
            ["z_next", "u"],
        )
    return _CONTROLLERS[key]


def corrupted_fixed_point(
    kind: str, vector: np.ndarray, plant: PlantScenario, errors: np.ndarray
) -> np.ndarray:
    """The controller's fixed point at the corrupted static readings (its initial state), from
    the static outputs of ``plant`` (no second equilibrium)."""
    from loader_model.control.linear_controller import linear_controller
    from loader_model.control.sensors import sensor_signals
    from loader_model.simulation.ride_control import RIDE_CONTROLLERS

    readings = sensor_signals(plant.y0, plant.layout)
    readings = errors[:5] * readings + errors[5:]
    fixed = linear_controller(RIDE_CONTROLLERS[kind], vector, readings)
    return np.asarray(fixed.operating_state, dtype=float).ravel()
