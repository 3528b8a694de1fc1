"""An FMU's Model Exchange instance in continuous-time mode, for tests that read its states and
derivatives directly (the FMI 2.0 call sequence in one place)."""

from __future__ import annotations

import ctypes
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np


@contextmanager
def continuous_time_instance(target: Path, model: Any, name: str) -> Iterator[Any]:
    """The instantiated, initialised FMU ``target`` (read as ``model``) in continuous-time
    mode; terminated and freed on exit."""
    import fmpy.fmi2

    fmu = fmpy.fmi2.FMU2Model(
        guid=model.guid,
        unzipDirectory=fmpy.extract(str(target)),
        modelIdentifier=model.modelExchange.modelIdentifier,
        instanceName=name,
    )
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.enterContinuousTimeMode()
    try:
        yield fmu
    finally:
        fmu.terminate()
        fmu.freeInstance()


def pointer(values: np.ndarray) -> Any:
    """A C double pointer to the float64 array ``values`` (for get/setContinuousStates)."""
    return values.ctypes.data_as(ctypes.POINTER(ctypes.c_double))
