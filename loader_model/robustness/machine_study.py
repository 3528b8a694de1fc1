"""A robustness study of another described machine: its parameters and its plant.

With ``[study] machine = "compact_wheel_loader"`` the uncertain parameters are named by the
machine's flat parameter file (:mod:`loader_model.parameters.machine_files`): ``model.<name>``
for a generated model parameter (unit and range of the description; the static loads the
equilibrium computes cannot vary), ``cylinders.<field>`` for a scalar real field of the lift
cylinder group, ``hydraulics.bulk_modulus`` and ``hydraulics.charge_pressure``, and the sensor
errors of :data:`~loader_model.robustness.sensors.SENSOR_ERROR_FIELDS`. A varied ``model``
value replaces it in [model] and in every load case that sets it, so the sampled value holds in
whichever load the sample draws. The plant is then
:func:`~loader_model.plant.scenario.resolve_plant` with ``machine=``.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from loader_model.machines import MachineInfo
    from loader_model.plant.layout import PlantLayout
    from loader_model.plant.scenario import PlantScenario
    from loader_model.robustness.sampling import SampleSpec

__all__ = [
    "machine_parameter_field",
    "machine_sample_parameters",
    "machine_sample_plant",
    "study_machine",
    "study_params",
]


def _scalar_fields(cls: type, names: tuple[str, ...] | None = None) -> dict[str, Any]:
    fields = {}
    for item in dataclasses.fields(cls):
        if names is not None and item.name not in names:
            continue
        meta = item.metadata
        if "unit" in meta and not meta.get("integer", False) and meta.get("shape", 0) == 0:
            fields[item.name] = meta
    return fields


def study_machine(value: Any) -> str:
    """The machine of ``[study] machine``: a generated machine's name, or the absolute path of
    a description file outside the package (so that every worker process resolves the same
    file; :mod:`loader_model.machine_packages`). ValueError naming the key and the allowed ones.
    """
    from pathlib import Path

    from loader_model.machines import list_machines, resolve_machine_name

    if not isinstance(value, str):
        raise ValueError(f"study.machine = {value!r}: allowed: one of {list(list_machines())}")
    try:
        name = resolve_machine_name(value)
    except ValueError as error:
        raise ValueError(f"study.machine = {value!r}: {error}") from None
    return name if name in list_machines() else str(Path(value).resolve())


def study_params(value: Any, machine: str) -> str | None:
    """The checked ``[study] params`` of ``machine`` (a flat parameter file's absolute path, or
    None for the shipped one); ValueError naming the key, the value and what is allowed."""
    from pathlib import Path

    from loader_model.machines import list_machines

    if value is None:
        if machine not in list_machines():
            raise ValueError(
                f"study.params: missing key; machine {machine!r} comes from a description file "
                "and ships no parameter file: give its flat parameter file (TOML)"
            )
        return None
    if machine == "skid_steer":
        raise ValueError(
            f"study.params = {value!r}: allowed only for another machine than the skid-steer "
            "(whose uncertain parameters are paths of its grouped files)"
        )
    if not isinstance(value, str) or not Path(value).is_file():
        raise ValueError(f"study.params = {value!r}: allowed: the path of an existing file")
    return str(Path(value).resolve())


def machine_parameter_field(path: str, info: MachineInfo) -> tuple[str, Any]:
    """The SI unit and allowed :class:`~loader_model.parameters.fields.Range` of study parameter
    ``path`` of the machine ``info`` (module notes).

    Raises
    ------
    ValueError
        Naming the path, with the closest valid path.
    """
    from loader_model.parameters.fields import Range
    from loader_model.robustness.sensors import SENSOR_ERROR_FIELDS

    if path in SENSOR_ERROR_FIELDS:
        return SENSOR_ERROR_FIELDS[path]
    model = [n for n in info.parameter_names if n not in info.static_names]
    from loader_model.parameters.hydraulics import CylinderParameters, HydraulicParameters
    from loader_model.parameters.machine_files import HYDRAULIC_NAMES

    cylinders = _scalar_fields(CylinderParameters)
    hydraulics = _scalar_fields(HydraulicParameters, HYDRAULIC_NAMES)
    section, _, name = path.partition(".")
    if section == "model" and name in model:
        low, high = info.parameter_ranges.get(name, (-math.inf, math.inf))
        reason = f"the range of the description of {info.name!r}"
        return info.parameter_units[name], Range(low, high, reason=reason)
    if section == "cylinders" and name in cylinders:
        return cylinders[name]["unit"], cylinders[name]["allowed"]
    if section == "hydraulics" and name in hydraulics:
        return hydraulics[name]["unit"], hydraulics[name]["allowed"]
    valid = [
        *(f"model.{n}" for n in model),
        *(f"cylinders.{n}" for n in cylinders),
        *(f"hydraulics.{n}" for n in hydraulics),
        *SENSOR_ERROR_FIELDS,
    ]
    close = difflib.get_close_matches(path, valid, n=1, cutoff=0.5)
    hint = f"; did you mean {close[0]!r}?" if close else ""
    raise ValueError(
        f"parameters.{path}: unknown parameter of machine {info.name!r}{hint} (names are its "
        "flat parameter file's paths: 'model.<name>', 'cylinders.<field>', "
        "'hydraulics.bulk_modulus', or 'sensors.<f_Hx|f_Hy|f_Ny|phi|p_A>.<gain|offset|noise_std>')"
    )


def machine_sample_parameters(
    spec: SampleSpec, info: MachineInfo, params_path: str | None = None
) -> Any:
    """The machine's :class:`~loader_model.parameters.machine_files.MachineParameters` (its
    flat file ``params_path``, default the shipped one) with the sample's values (module
    notes)."""
    from loader_model.parameters.machine_files import resolve_machine_parameters

    params = resolve_machine_parameters(info, params_path)
    values = [(p, v) for p, v in spec.values if not p.startswith("sensors.")]
    model = {p.removeprefix("model."): v for p, v in values if p.startswith("model.")}
    cylinders = {p.removeprefix("cylinders."): v for p, v in values if p.startswith("cylinders.")}
    hydraulics = {
        p.removeprefix("hydraulics."): v for p, v in values if p.startswith("hydraulics.")
    }
    loads = {
        case: entries | {n: v for n, v in model.items() if n in entries}
        for case, entries in params.loads.items()
    }
    return dataclasses.replace(
        params,
        model=params.model | model,
        cylinders=dataclasses.replace(params.cylinders, **cylinders),
        hydraulics=params.hydraulics | hydraulics,
        loads=loads,
    )


def machine_sample_plant(
    spec: SampleSpec, layout: PlantLayout, params_path: str | None = None
) -> PlantScenario:
    """The sample's plant of the machine ``layout`` (accumulator shut; its load case
    ``spec.load``).

    Raises
    ------
    ValueError
        From the machine's checks (a plant that does not stand at rest, ...).
    """
    from loader_model.plant.scenario import resolve_plant

    params = machine_sample_parameters(spec, layout.machine, params_path)
    return resolve_plant(params, spec.load, machine=layout)
