"""Validated loader parameters: TOML files, updates by dotted path, and the model's values.

The parameter sets are the frozen dataclasses of :mod:`loader_model.parameters.schema` (SI units,
chassis-frame points at the operating boom angle). A loader file (``default_loader.toml``) holds
everything but the bucket load, which has one file per load case (``load_empty.toml``,
``load_full.toml``; section 5.3 of the paper: 340 kg and 770 kg).

Examples
--------
>>> from loader_model.parameters.sets import bucket_load, default_loader, model_parameter_values
>>> values = model_parameter_values(default_loader(), bucket_load("empty"))
>>> round(values["m_2"] - default_loader().boom.mass, 6)
340.0
"""

from __future__ import annotations

import difflib
import functools
import math
import os
import tomllib
from collections.abc import Mapping, Sequence
from importlib import resources
from pathlib import Path
from typing import Any, TypeVar

from loader_model.io.files import read_text
from loader_model.parameters.checks import (
    COINCIDENCE_TOLERANCE_M,
    check_loader,
    check_ranges,
)
from loader_model.parameters.schema import (
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
    Point,
    PumpParameters,
    SeatParameters,
    TyreParameters,
)
from loader_model.parameters.toml_format import build, dumps, iter_leaves, leaf_metadata, to_raw

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
    "SeatParameters",
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

#: Names of the generated model's numeric parameters (the order belongs to ``derive``).
MODEL_PARAMETER_NAMES = frozenset(
    "m_1 J_1 m_2 J_2 g A_x A_y B_x B_y C_x C_y D_x D_y S_x S_y N_x N_y E_x E_y G_x G_y "
    "k_Ax k_Ay c_Ax c_Ay k_Bx k_By c_Bx c_By mu_road F_transition tau_slip".split()
)

#: Suffixes of parameter files.
PARAMETER_SUFFIXES = (".toml",)
_LOAD_CASES = {"empty": "load_empty.toml", "full": "load_full.toml"}
#: Names of the shipped bucket-load cases (paper section 5.3: 340 kg and 770 kg).
LOAD_CASES: tuple[str, ...] = tuple(_LOAD_CASES)
_HEADERS = {
    LoaderParameters: "Loader parameters (loader_model.parameters.schema.LoaderParameters).",
    BucketLoad: "Bucket load case (loader_model.parameters.schema.BucketLoad).",
}
_HEADER_FORMAT = (
    "\nEvery value: { value = <SI number>, unit = <its SI unit, checked on loading>, "
    'source = "<one-line source or reason>" }.\nPoints are (x, y) in the chassis frame: '
    "origin H (chassis centre of gravity), x forward, y up, boom at its operating angle."
)

P = TypeVar("P", LoaderParameters, BucketLoad)


def validate(params: P) -> P:
    """Check ranges and consistency of a parameter set; return it unchanged.

    Raises
    ------
    ValueError
        Naming the field by dotted path (``tyres.front.k_y``), the value, the allowed range and
        its reason: a value outside the plausible range of its field
        (:mod:`loader_model.parameters.fields`), or a loader that is inconsistent
        (:func:`loader_model.parameters.checks.check_loader`: rod too thick, barrel shorter than
        the stroke, coincident points, A not ahead of B, cylinder on or beyond an end stop).
        A loader with a bucket load is checked further by
        :func:`loader_model.vehicle.statics.check_combination`.
    """
    check_ranges(params)
    if isinstance(params, LoaderParameters):
        check_loader(params)
    return params


def _parse(cls: type[P], text: str, origin: str) -> P:
    try:
        return validate(build(cls, tomllib.loads(text)))
    except ValueError as exc:
        raise ValueError(f"{origin}: {exc}") from None


def load_loader(path: str | Path) -> LoaderParameters:
    """Read and validate a loader parameter file (see :func:`save` for the layout).

    The file must be a readable regular file of UTF-8 text, with or without a byte-order mark
    (:func:`loader_model.io.files.read_text`); every error names the file.
    """
    return _parse(LoaderParameters, read_text(path, "loader parameter file"), str(path))


def load_bucket_load(path: str | Path) -> BucketLoad:
    """Read and validate a bucket-load file (one load case); see :func:`load_loader`."""
    return _parse(BucketLoad, read_text(path, "bucket load file"), str(path))


def save(params: LoaderParameters | BucketLoad, path: str | Path) -> None:
    """Write a parameter set as TOML; :func:`load_loader` / :func:`load_bucket_load` read it
    back equal (floats are written with ``repr``).

    The path must end in ``.toml``; the file is written atomically with the user's umask
    permissions (:func:`loader_model.io.export.write_atomically`).
    """
    from loader_model.io.export import write_atomically

    text = dumps(to_raw(params), _HEADERS[type(params)] + _HEADER_FORMAT)
    write_atomically(
        path,
        lambda temporary: temporary.write_text(text, encoding="utf-8", newline="\n"),
        PARAMETER_SUFFIXES,
        "parameter file",
    )


def replace(params: P, updates: Mapping[str, Any], source: str | None = None) -> P:
    """Return a validated copy of ``params`` with values replaced by dotted path.

    Parameters
    ----------
    params : LoaderParameters or BucketLoad
    updates : mapping
        ``{"tyres.front.k_y": 1.2e6, "geometry.E": (-0.5, 0.7), ...}`` in the field's SI unit.
    source : str, optional
        New source/reason of the updated values (e.g. ``"calibrated to Table 1"``); the old
        source is kept when omitted.
    """
    raw = to_raw(params)
    leaves = {path: (cls, name) for path, cls, name in iter_leaves(type(params))}
    for path, value in updates.items():
        if path not in leaves:
            close = difflib.get_close_matches(path, list(leaves), n=1, cutoff=0.5)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise ValueError(f"{path}: unknown parameter{hint}")
        leaf = functools.reduce(lambda node, key: node[key], path.split("."), raw)
        if leaf_metadata(*leaves[path])["shape"]:  # a point: a tuple, list or 1-D array
            value = value.tolist() if getattr(value, "ndim", 0) == 1 else value
            value = list(value) if isinstance(value, tuple) else value
        leaf["value"] = value  # a number is checked as given: an array is not a number
        if source is not None:
            leaf["source"] = source
    return validate(build(type(params), raw))


def _read_data(name: str) -> str:
    return resources.files("loader_model").joinpath("data", name).read_text(encoding="utf-8")


@functools.cache
def default_loader() -> LoaderParameters:
    """The shipped default loader, a plausible 3.5 t skid-steer (``data/default_loader.toml``)."""
    return _parse(LoaderParameters, _read_data("default_loader.toml"), "default_loader.toml")


@functools.cache
def bucket_load(case: str) -> BucketLoad:
    """A shipped bucket-load case: ``"empty"`` (340 kg) or ``"full"`` (770 kg, section 5.3)."""
    if case not in _LOAD_CASES:
        raise ValueError(f"bucket load case {case!r} is unknown; allowed: {sorted(_LOAD_CASES)}")
    return _parse(BucketLoad, _read_data(_LOAD_CASES[case]), _LOAD_CASES[case])


def combine_bodies(
    masses: Sequence[float], cogs: Sequence[Point], inertias: Sequence[float]
) -> tuple[float, Point, float]:
    r"""Combine rigid bodies of one planar body into mass, centre of gravity and inertia.

    .. math::

        m = \sum m_i, \quad G = \frac{1}{m}\sum m_i G_i, \quad
        J_G = \sum \left(J_i + m_i \lVert G_i - G \rVert^2\right)

    (parallel-axis theorem; ``J_i`` about each body's own centre of gravity ``G_i``).
    """
    mass = math.fsum(masses)
    gx = math.fsum(m * g[0] for m, g in zip(masses, cogs, strict=True)) / mass
    gy = math.fsum(m * g[1] for m, g in zip(masses, cogs, strict=True)) / mass
    inertia = math.fsum(
        j + m * ((g[0] - gx) ** 2 + (g[1] - gy) ** 2)
        for m, g, j in zip(masses, cogs, inertias, strict=True)
    )
    return mass, (gx, gy), inertia


def model_parameter_values(loader: LoaderParameters, load: BucketLoad) -> dict[str, float]:
    """Numeric values of the generated model's parameters, keyed by name.

    Body 1 is the chassis (m_1, J_1 about H); body 2 is the boom with the bucket load (m_2, J_2
    about the combined centre of gravity G by :func:`combine_bodies`). Points are chassis-frame
    coordinates at the operating angle; ``k_A*``, ``c_A*`` / ``k_B*``, ``c_B*`` are the front /
    rear axle tyres (Eq. 1-4). The static tyre loads are computed elsewhere from the equilibrium.
    The order of the generated function's inputs belongs to ``derive``; use the names.

    Whether the two stand together at rest is not checked here (that needs the model's statics):
    :func:`loader_model.vehicle.statics.check_combination` does it.
    """
    boom, geo = loader.boom, loader.geometry
    m_2, cog, j_2 = combine_bodies(
        (boom.mass, load.mass), (boom.cog, load.cog), (boom.inertia, load.inertia)
    )
    points = {name: getattr(geo, name) for name in ("A", "B", "C", "D", "S", "N", "E")}
    values = {"m_1": loader.chassis.mass, "J_1": loader.chassis.inertia, "m_2": m_2, "J_2": j_2}
    values["g"] = loader.environment.gravity
    for name, (x, y) in (points | {"G": cog}).items():
        values[f"{name}_x"], values[f"{name}_y"] = x, y
    for axle, tyre in (("A", loader.tyres.front), ("B", loader.tyres.rear)):
        for kind in ("k_x", "k_y", "c_x", "c_y"):
            values[f"{kind[0]}_{axle}{kind[2]}"] = getattr(tyre, kind)
    values["mu_road"] = loader.tyres.friction_coefficient
    values["F_transition"] = loader.tyres.contact_transition
    values["tau_slip"] = loader.tyres.slip_relaxation_time
    return {name: float(value) for name, value in values.items()}


def resolve_loader_and_load(
    loader: LoaderParameters | str | Path | None = None, load: BucketLoad | str | Path = "empty"
) -> tuple[LoaderParameters, BucketLoad]:
    """Resolve a loader and a bucket load given as objects, TOML paths or defaults.

    ``loader`` None is the shipped default loader; ``load`` may name a shipped case
    (:data:`LOAD_CASES`: ``"empty"`` 340 kg, ``"full"`` 770 kg, section 5.3). Each set is
    valid alone; :func:`loader_model.vehicle.statics.resolve_machine` also checks that they
    stand together.
    """
    if loader is None:
        loader = default_loader()
    elif isinstance(loader, str | os.PathLike):
        loader = load_loader(loader)
    elif not isinstance(loader, LoaderParameters):
        raise ValueError(
            f"loader must be a LoaderParameters, a path to its TOML file or None; got {loader!r}"
        )
    if isinstance(load, str) and load in LOAD_CASES:
        load = bucket_load(load)
    elif isinstance(load, str | os.PathLike):
        if not os.path.lexists(load):
            raise ValueError(
                f"load {os.fspath(load)!r} is neither a load case {list(LOAD_CASES)} "
                "nor an existing TOML file"
            )
        load = load_bucket_load(load)
    elif not isinstance(load, BucketLoad):
        raise ValueError(
            f"load must be a BucketLoad, a path to its TOML file or one of {list(LOAD_CASES)}; "
            f"got {load!r}"
        )
    return loader, load
