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

from loader_model.parameters import sets as _sets
from loader_model.parameters.sets import *  # noqa: F403  (the public names of sets.py)

__all__ = list(_sets.__all__)
