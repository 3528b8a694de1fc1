"""Parameters: the validated loader and bucket-load sets, their TOML files and JSON Schemas.

The first step of the data flow (``parameters -> vehicle -> plant -> ...``): frozen dataclasses
with units, sources and ranges (:mod:`~loader_model.parameters.schema`,
:mod:`~loader_model.parameters.fields`, :mod:`~loader_model.parameters.hydraulics`), TOML in and
out (:mod:`~loader_model.parameters.toml_format`, :mod:`~loader_model.parameters.sets`), checks
of one set (:mod:`~loader_model.parameters.checks`, :mod:`~loader_model.parameters.model_checks`)
and the JSON Schemas (:mod:`~loader_model.parameters.json_schema`). It imports nothing of the
model: whether a loader and a load stand together at rest is checked one layer up
(:mod:`loader_model.vehicle.statics`).
"""

from loader_model.parameters.sets import (
    COINCIDENCE_TOLERANCE_M,
    LOAD_CASES,
    MODEL_PARAMETER_NAMES,
    PARAMETER_SUFFIXES,
    AccumulatorParameters,
    AxleTyre,
    BoomParameters,
    BucketLoad,
    ChassisParameters,
    ControllerParameters,
    CylinderParameters,
    EnvironmentParameters,
    FrictionParameters,
    Geometry,
    HydraulicParameters,
    LeakageParameters,
    LoaderParameters,
    PumpParameters,
    TyreParameters,
    bucket_load,
    combine_bodies,
    default_loader,
    load_bucket_load,
    load_loader,
    model_parameter_values,
    replace,
    resolve_loader_and_load,
    save,
    validate,
)

__all__ = [
    "COINCIDENCE_TOLERANCE_M",
    "LOAD_CASES",
    "MODEL_PARAMETER_NAMES",
    "PARAMETER_SUFFIXES",
    "AccumulatorParameters",
    "AxleTyre",
    "BoomParameters",
    "BucketLoad",
    "ChassisParameters",
    "ControllerParameters",
    "CylinderParameters",
    "EnvironmentParameters",
    "FrictionParameters",
    "Geometry",
    "HydraulicParameters",
    "LeakageParameters",
    "LoaderParameters",
    "PumpParameters",
    "TyreParameters",
    "bucket_load",
    "combine_bodies",
    "default_loader",
    "load_bucket_load",
    "load_loader",
    "model_parameter_values",
    "replace",
    "resolve_loader_and_load",
    "save",
    "validate",
]
