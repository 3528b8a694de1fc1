"""Distributions of a study's uncertain parameters, bounded so that their support can be checked.

Every distribution has a finite support [low, high], and the study refuses it unless both ends lie
inside the parameter's validated range (the range and reason of the parameter file's field, see
:mod:`loader_model.parameters.fields`). Samples are drawn by the inverse CDF of a point of the
sampling design (Latin hypercube or Sobol, :mod:`~loader_model.robustness.sampling`):

- ``uniform``: ``low``, ``high``;
- ``loguniform``: ``low``, ``high`` (> 0), uniform in the logarithm;
- ``normal``: ``mean``, ``std``, truncated to ``low``, ``high``;
- ``triangular``: ``low``, ``mode``, ``high``.

Each may carry ``source``, a one-line reason for its support (a datasheet, a paper, "estimate").
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from loader_model.parameters.fields import Range

__all__ = ["DISTRIBUTIONS", "Distribution", "parse_distribution"]

#: Distribution name -> its parameters besides ``unit``.
DISTRIBUTIONS: dict[str, tuple[str, ...]] = {
    "uniform": ("low", "high"),
    "loguniform": ("low", "high"),
    "normal": ("mean", "std", "low", "high"),
    "triangular": ("low", "mode", "high"),
}


@dataclass(frozen=True)
class Distribution:
    """A bounded distribution of one parameter in its SI unit (module notes).

    Attributes
    ----------
    kind : str
        A key of :data:`DISTRIBUTIONS`.
    low, high : float
        Support.
    mean, std, mode : float
        The normal's mean and standard deviation, the triangular's mode (NaN when unused).
    unit : str
        SI unit, equal to the parameter file's.
    source : str
        Where the support comes from (empty if the study gives none).
    """

    kind: str
    low: float
    high: float
    unit: str
    mean: float = math.nan
    std: float = math.nan
    mode: float = math.nan
    source: str = ""

    def ppf(self, u: np.ndarray) -> np.ndarray:
        """Values at probabilities ``u`` in [0, 1) (inverse CDF)."""
        u = np.asarray(u, dtype=float)
        if self.kind == "uniform":
            return self.low + (self.high - self.low) * u
        if self.kind == "loguniform":
            return np.exp(np.log(self.low) + (np.log(self.high) - np.log(self.low)) * u)
        from scipy import stats

        if self.kind == "normal":
            a, b = (self.low - self.mean) / self.std, (self.high - self.mean) / self.std
            return stats.truncnorm.ppf(u, a, b, loc=self.mean, scale=self.std)
        width = self.high - self.low
        return stats.triang.ppf(u, (self.mode - self.low) / width, loc=self.low, scale=width)


def parse_distribution(spec: Any, key: str, unit: str, allowed: Range) -> Distribution:
    """Check ``spec`` (a TOML inline table) against a parameter's SI ``unit`` and ``allowed`` range.

    Raises
    ------
    ValueError
        Naming ``key``, the value and what is allowed: unknown distribution or key, missing or
        non-finite numbers, a unit other than the parameter file's, an empty support, or a support
        outside the field's validated range (with its reason).
    """
    if not isinstance(spec, dict):
        raise ValueError(
            f"{key} = {spec!r}: allowed: a table {{ distribution = ..., ..., unit = {unit!r} }}"
        )
    kind = spec.get("distribution")
    if kind not in DISTRIBUTIONS:
        raise ValueError(f"{key}.distribution = {kind!r}: allowed: {list(DISTRIBUTIONS)}")
    names = DISTRIBUTIONS[kind]
    for name in spec:
        if name not in (*names, "distribution", "unit", "source"):
            allowed_keys = [*names, "unit", "source"]
            raise ValueError(
                f"{key}.{name}: unknown key for a {kind} distribution; allowed: {allowed_keys}"
            )
    source = spec.get("source", "")
    if not isinstance(source, str):
        raise ValueError(f"{key}.source = {source!r}: allowed: a string")
    if spec.get("unit") != unit:
        raise ValueError(
            f"{key}.unit = {spec.get('unit')!r}: the parameter file's unit is {unit!r} "
            "(SI, no conversion)"
        )
    values = {}
    for name in names:
        value = spec.get(name)
        if (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not math.isfinite(value)
        ):
            raise ValueError(f"{key}.{name} = {value!r}: allowed: a finite number in {unit}")
        values[name] = float(value)
    low, high = values["low"], values["high"]
    if not low < high:
        raise ValueError(f"{key}: low = {low:g} must be below high = {high:g}")
    for name in ("low", "high"):
        if not allowed.contains(values[name]):
            raise ValueError(
                f"{key}.{name} = {values[name]:g} {unit} is outside the parameter's validated "
                f"range; allowed: {allowed.describe()}"
            )
    if kind == "loguniform" and low <= 0:
        raise ValueError(f"{key}.low = {low:g}: a loguniform distribution needs low > 0")
    if kind == "normal" and not values["std"] > 0:
        raise ValueError(f"{key}.std = {values['std']:g}: allowed: a number > 0")
    if kind == "normal" and not low <= values["mean"] <= high:
        raise ValueError(f"{key}.mean = {values['mean']:g}: allowed: from low to high")
    if kind == "triangular" and not low <= values["mode"] <= high:
        raise ValueError(f"{key}.mode = {values['mode']:g}: allowed: from low to high")
    return Distribution(
        kind,
        low,
        high,
        unit,
        mean=values.get("mean", math.nan),
        std=values.get("std", math.nan),
        mode=values.get("mode", math.nan),
        source=source,
    )
