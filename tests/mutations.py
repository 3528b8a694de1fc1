"""Mutated user files for the property tests and the fuzz run: one field or one cell at a time.

A parameter file is mutated by rewriting the ``value`` (or ``unit``) of one leaf line of a valid
file as TOML text, so any TOML value can be tried (strings, booleans, huge integers, nan, lists).
A CSV is mutated by replacing one cell. :func:`outcome` runs the user's path through the package
and classifies the result.
"""

from __future__ import annotations

import json
import math
import re
from importlib import resources
from pathlib import Path

import numpy as np

from loader_model.parameters.schema import BucketLoad, LoaderParameters
from loader_model.parameters.toml_format import iter_leaves

LOADER_TEXT = (
    resources.files("loader_model")
    .joinpath("data", "default_loader.toml")
    .read_text(encoding="utf-8")
)
LOAD_TEXT = (
    resources.files("loader_model").joinpath("data", "load_empty.toml").read_text(encoding="utf-8")
)
LOADER_PATHS = [path for path, _, _ in iter_leaves(LoaderParameters)]
LOAD_PATHS = [path for path, _, _ in iter_leaves(BucketLoad)]

#: Bad or extreme values tried for every field by the fuzz run (TOML literals).
BAD_VALUES = [
    "0",
    "-1.0",
    "1e-300",
    "1e30",
    "-1e30",
    "1e300",
    "1" + "0" * 400,
    "nan",
    "inf",
    "-inf",
    "true",
    '"12"',
    "[]",
    "[1.0, 2.0, 3.0]",
    "{}",
    "2.5",
]


def toml_literal(value: object) -> str:
    """TOML text of a Python value (floats by repr, so nan and inf are written as TOML has them)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return (
            "nan"
            if math.isnan(value)
            else ("inf" if value > 0 else "-inf")
            if math.isinf(value)
            else repr(value)
        )
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, list):
        return "[" + ", ".join(toml_literal(v) for v in value) + "]"
    raise TypeError(value)


def mutate_leaf(text: str, path: str, literal: str, key: str = "value") -> str:
    """Replace ``key`` (value or unit) of the leaf at dotted ``path`` with TOML ``literal``."""
    *sections, name = path.split(".")
    lines = text.splitlines()
    header = f"[{'.'.join(sections)}]" if sections else None
    inside = header is None
    for index, line in enumerate(lines):
        if line.startswith("["):
            inside = line.strip() == header
            continue
        if inside and line.startswith(f"{name} = {{"):
            value = r"\[[^\]]*\]|[^,]+" if key == "value" else r'"[^"]*"'
            lines[index] = re.sub(
                rf"\b{key} = ({value})", lambda _: f"{key} = {literal}", line, count=1
            )
            return "\n".join(lines) + "\n"
    raise KeyError(path)


def valid_csv_rows(rate_hz: float = 200.0, duration_s: float = 8.0) -> list[list[str]]:
    """Rows (header first) of a valid seat record: time, x, z."""
    rng = np.random.default_rng(7)
    time_s = np.arange(round(rate_hz * duration_s)) / rate_hz
    x = 0.3 * np.sin(2 * np.pi * 1.5 * time_s) + 0.05 * rng.standard_normal(time_s.size)
    z = 9.81 + 0.8 * np.sin(2 * np.pi * 4.0 * time_s)
    return [["time", "x", "z"]] + [
        [f"{t:.3f}", f"{a:.5f}", f"{b:.5f}"] for t, a, b in zip(time_s, x, z, strict=True)
    ]


def write_csv(path: Path, rows: list[list[str]]) -> Path:
    path.write_text("\n".join(",".join(row) for row in rows) + "\n", encoding="utf-8")
    return path
