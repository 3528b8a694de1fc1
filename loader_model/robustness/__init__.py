"""Robustness study: ride control over sampled plants, roads, speeds and bucket loads.

A study file (TOML, :mod:`~loader_model.robustness.study`) names the uncertain parameters by
their parameter-file paths with bounded distributions; :func:`run_study` runs every controller on
every sample on a local process pool or a Dask cluster, saving each finished batch
(:mod:`~loader_model.robustness.engine`); :func:`report_text` summarises the result table
(:mod:`~loader_model.robustness.report`). Command: ``loader-model robustness STUDY.toml``.
"""

from __future__ import annotations

from loader_model.robustness.engine import run_study
from loader_model.robustness.report import report_text
from loader_model.robustness.sampling import SampleSpec, sample_specs
from loader_model.robustness.study import Study, load_study, parse_study

__all__ = [
    "SampleSpec",
    "Study",
    "load_study",
    "parse_study",
    "report_text",
    "run_study",
    "sample_specs",
]
