"""Calibrate a loader parameter set so that its modal analysis reproduces Table 1 (section 2.2).

The paper does not publish geometry or masses. The default loader's geometry and masses are the
values Table 1 implies (rounded; see the sources in ``data/default_loader.toml``); the calibration
fits the six least-known parameters below within physically plausible bounds, on the generated model
(:func:`loader_model.modal.undamped.undamped_matrices`), reading Table 1's columns as momentum shapes M·φ
(errata 7). ``loader-model calibrate`` runs it and writes the result as a TOML file.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import reduce

from loader_model.modal.calibration import CalibrationResult, calibrate
from loader_model.modal.undamped import undamped_matrices
from loader_model.parameters.sets import BucketLoad, LoaderParameters, replace

__all__ = ["FREE_PARAMETERS", "FreeParameter", "calibrate_to_table_1"]


@dataclass(frozen=True)
class FreeParameter:
    """A calibrated quantity: the parameter-file fields it sets, its bounds and why."""

    paths: tuple[str, ...]
    bounds: tuple[float, float]
    unit: str
    reason: str


#: The six free parameters of the Table 1 calibration (Jacobian singular values all well above 0).
FREE_PARAMETERS: dict[str, FreeParameter] = {
    "k_x": FreeParameter(
        ("tyres.front.k_x", "tyres.rear.k_x"),
        (0.5e6, 5.0e6),
        "N/m",
        "longitudinal stiffness of two 12-16.5 tyres with hub and drive; one value for both axles "
        "(with A_y = B_y only their sum enters K)",
    ),
    "k_Ay": FreeParameter(
        ("tyres.front.k_y",),
        (0.6e6, 5.0e6),
        "N/m",
        "two 12-16.5 tyres at 3-4.5 bar: 0.3-2.5 MN/m each",
    ),
    "k_By": FreeParameter(
        ("tyres.rear.k_y",),
        (0.6e6, 5.0e6),
        "N/m",
        "two 12-16.5 tyres at 3-4.5 bar: 0.3-2.5 MN/m each",
    ),
    "J_1": FreeParameter(
        ("chassis.inertia",),
        (800.0, 2600.0),
        "kg m^2",
        "2830 kg chassis about 2.7 m long and 2 m tall: radius of gyration 0.53-0.96 m",
    ),
    "J_b": FreeParameter(
        ("boom.inertia",),
        (150.0, 900.0),
        "kg m^2",
        "670 kg boom with bucket spread over about 2.6 m: radius of gyration 0.47-1.16 m",
    ),
    "V_A0": FreeParameter(
        ("cylinders.dead_volume_a",),
        (0.2e-3, 1.5e-3),
        "m^3",
        "piston-side hose, tube and port volume per cylinder; hose length and compliance unknown",
    ),
}


def _current_value(loader: LoaderParameters, path: str) -> float:
    return float(reduce(getattr, path.split("."), loader))


def calibrate_to_table_1(
    loader: LoaderParameters,
    load: BucketLoad,
    *,
    gravity_stiffness: bool = True,
    free: Mapping[str, FreeParameter] = FREE_PARAMETERS,
) -> tuple[CalibrationResult, LoaderParameters]:
    """Fit the free parameters of ``loader`` to Table 1 with the bucket ``load``.

    Starts from the loader's current values plus seeded random starts (reproducible), so running
    it on an already calibrated loader returns the same values.

    Returns
    -------
    result : CalibrationResult
        Fitted values, frequencies, errors and MACs (see :mod:`loader_model.modal.calibration`).
    calibrated : LoaderParameters
        ``loader`` with the fitted values written in, each with a source naming the calibration.
    """
    start = {name: _current_value(loader, item.paths[0]) for name, item in free.items()}
    bounds = {name: item.bounds for name, item in free.items()}

    def with_values(values: Mapping[str, float]) -> LoaderParameters:
        updates = {path: values[name] for name, item in free.items() for path in item.paths}
        return replace(loader, updates)

    def build(values: Mapping[str, float]):
        matrices = undamped_matrices(with_values(values), load, gravity_stiffness=gravity_stiffness)
        return matrices.mass, matrices.stiffness

    result = calibrate(build, start, bounds, reading="momentum")
    calibrated = with_values(result.parameters)
    for name, item in free.items():
        low, high = item.bounds
        source = (
            f"calibrated to Table 1 by `loader-model calibrate` (momentum reading, errata 7; "
            f"bounds {low:g}-{high:g} {item.unit}: {item.reason})"
        )
        updates = {path: result.parameters[name] for path in item.paths}
        calibrated = replace(calibrated, updates, source=source)
    return result, calibrated
