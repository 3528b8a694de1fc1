"""The calibration's files: the calibrated loader parameter file and the fit's JSON summary.

:func:`~loader_model.experiments.calibration_table6.calibrate_table6` finds the values; here they
become a loader file whose every calibrated value names the cells it was fitted to, the date and
the plausible range it was bounded by (:func:`calibrated_loader`), and a summary for the report
and the currency test (:func:`write_summary`). ``make calibrate-table6`` ships both per fitted
speed (:data:`~loader_model.experiments.calibration_table6.CALIBRATED_FILES`).
"""

from __future__ import annotations

from importlib import resources
from typing import Any

__all__ = ["calibrated_loader", "calibrated_values", "shipped_calibration", "write_summary"]


def calibrated_loader(result: Any, date: str) -> Any:
    """The shipped loader with the calibrated values, each with a source that says to which cells
    and on what date it was calibrated, and what it was."""
    from loader_model import parameters
    from loader_model.experiments.calibration_table6 import ESTIMATES_FILE

    loader = parameters.default_loader()
    held_out = 18.0 if result.fit_speed_kmh == 9.0 else 9.0
    for path, value in result.values.items():
        low, high = result.bounds[path]
        bound = " (at a bound)" if path in result.at_bounds else ""
        source = (
            f"calibrated to Table 6's six {result.fit_speed_kmh:g} km/h cells on {date} "
            f"(make calibrate-table6; the {held_out:g} km/h cells held out){bound}; shipped "
            f"estimate {result.start[path]:.6g}, plausible range [{low:.6g}, {high:.6g}] "
            f"({ESTIMATES_FILE})"
        )
        loader = parameters.replace(loader, {path: value}, source=source)
    return loader


def calibrated_values(path: Any) -> dict[str, float]:
    """The estimated parameters' values in a calibrated loader file (:func:`calibrated_loader`)."""
    from functools import reduce

    from loader_model import parameters
    from loader_model.experiments.calibration_table6 import estimated_parameters
    from loader_model.parameters.toml_format import to_raw

    raw = to_raw(parameters.load_loader(path))
    return {
        p: float(reduce(lambda node, key: node[key], p.split("."), raw)["value"])
        for p, _ in estimated_parameters()
    }


def shipped_calibration(fit_speed_kmh: float) -> dict[str, float]:
    """The values of the shipped calibrated loader file of ``fit_speed_kmh`` (package data)."""
    from loader_model.experiments.calibration_table6 import CALIBRATED_FILES

    name = CALIBRATED_FILES[float(fit_speed_kmh)]
    with resources.as_file(resources.files("loader_model").joinpath("data", name)) as path:
        return calibrated_values(path)


def write_summary(
    path: Any,
    result: Any,
    date: str,
    command: str,
    check: dict[str, Any] | None = None,
) -> None:
    """The fit's summary as JSON (atomically), for the report and the currency test; ``check``
    (:func:`check_calibration`), if given, under ``"check"``."""
    import dataclasses
    import json

    from loader_model.io.export import write_atomically

    content = dataclasses.asdict(result) | {"date": date, "command": command}
    if check is not None:
        content["check"] = check
    content["bounds"] = {k: list(v) for k, v in result.bounds.items()}
    text = json.dumps(content, indent=1, sort_keys=True)
    write_atomically(
        path,
        lambda temporary: temporary.write_text(text + "\n", encoding="utf-8"),
        (".json",),
        "calibration summary",
    )
