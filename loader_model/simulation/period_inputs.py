"""Per-period tables the simulator's periods read besides the road: the controller's sensor
errors (offset, noise, quantisation steps) and the disturbance forces, checked against the
run's number of periods. The simulator and the gain sensitivities share them."""

from __future__ import annotations

import numpy as np

from loader_model.control.sensors import SENSOR_NAMES, SensorModel
from loader_model.plant.plant import OUTPUT_NAMES

__all__ = ["disturbance_table", "sensor_error_table"]


def sensor_error_table(
    sensors: SensorModel | None, count: int, output_names: tuple[str, ...] = OUTPUT_NAMES
) -> tuple[np.ndarray, np.ndarray]:
    """Per-period additive errors (count + 1, outputs) and converter steps (outputs) of the
    controller's sensors; zero outside :data:`~loader_model.control.sensors.SENSOR_NAMES`."""
    errors = np.zeros((count + 1, len(output_names)))
    steps = np.zeros(len(output_names))
    if sensors is None:
        return errors, steps
    if not isinstance(sensors, SensorModel):
        raise TypeError(f"sensors must be a SensorModel or None; got {type(sensors).__name__}")
    columns = [output_names.index(name) for name in SENSOR_NAMES]
    errors[:, columns] = sensors.errors(count + 1)
    steps[columns] = sensors.quantisation
    return errors, steps


def disturbance_table(disturbance: np.ndarray, count: int) -> np.ndarray:
    """The (count, 3) disturbance at the controller's instants, its last row repeated for the
    period end."""
    table = np.asarray(disturbance, dtype=float)
    if table.ndim != 2 or table.shape[0] != count:
        raise ValueError(
            f"disturbance must be ({count}, 3) at the controller's instants; got {table.shape}"
        )
    return np.vstack([table, table[-1:]])
