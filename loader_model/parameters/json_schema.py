"""JSON Schema of the parameter files, generated from the parameter dataclasses.

Editors that read JSON Schema for TOML (Taplo / Even Better TOML, JetBrains) validate and
complete a parameter file with it: every section and key, the unit each value must carry, and
the plausible range of every value with its reason. The schemas ship as
``loader_model/data/loader.schema.json`` and ``load.schema.json``; regenerate them with
``python -m loader_model.parameters.json_schema`` after changing a field (a test compares the bytes).
Consistency checks that involve several fields are not expressible here and run on loading.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path
from typing import Any

from loader_model.parameters.fields import Range
from loader_model.parameters.schema import BucketLoad, LoaderParameters
from loader_model.parameters.toml_format import leaf_metadata, section_types

__all__ = ["SCHEMA_FILES", "parameter_schema", "schema_text", "write_schemas"]

#: Shipped schema file name per top-level parameter class.
SCHEMA_FILES: dict[type, str] = {
    LoaderParameters: "loader.schema.json",
    BucketLoad: "load.schema.json",
}
_DATA = Path(__file__).parents[1] / "data"


def _number(allowed: Range, integer: bool) -> dict[str, Any]:
    schema: dict[str, Any] = {"type": "integer" if integer else "number"}
    if math.isfinite(allowed.low):
        schema["exclusiveMinimum" if allowed.low_open else "minimum"] = allowed.low
    if math.isfinite(allowed.high):
        schema["exclusiveMaximum" if allowed.high_open else "maximum"] = allowed.high
    return schema


def _leaf(cls: type, name: str) -> dict[str, Any]:
    meta = leaf_metadata(cls, name)
    allowed: Range = meta["allowed"]
    number = _number(allowed, meta["integer"])
    shape = meta["shape"]
    value = (
        number
        if shape == 0
        else {"type": "array", "items": number, "minItems": shape, "maxItems": shape}
    )
    return {
        "type": "object",
        "description": f"in {meta['unit']}; allowed: {allowed.describe()}",
        "properties": {
            "value": value,
            "unit": {"const": meta["unit"], "description": "SI unit, checked on loading"},
            "source": {"type": "string", "minLength": 1, "description": "source or reason"},
        },
        "required": ["value", "unit", "source"],
        "additionalProperties": False,
    }


def _section(cls: type) -> dict[str, Any]:
    sections = section_types(cls)
    properties = {}
    for name, field in cls.__dataclass_fields__.items():
        if "sources" in field.metadata:
            continue
        properties[name] = _section(sections[name]) if name in sections else _leaf(cls, name)
    return {
        "type": "object",
        "properties": properties,
        "required": list(properties),
        "additionalProperties": False,
    }


def parameter_schema(cls: type) -> dict[str, Any]:
    """JSON Schema (draft 2020-12) of the TOML file of ``cls`` (LoaderParameters or BucketLoad)."""
    schema = {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": f"loader-model {cls.__name__} file",
        "description": (cls.__doc__ or "").strip().splitlines()[0],
    }
    return schema | _section(cls)


def schema_text(cls: type) -> str:
    """The shipped text of the schema of ``cls``: indented JSON with a final newline."""
    return json.dumps(parameter_schema(cls), indent=2, ensure_ascii=False) + "\n"


def write_schemas(folder: Path = _DATA) -> list[Path]:
    """Write both schemas into ``folder``; return their paths."""
    paths = []
    for cls, name in SCHEMA_FILES.items():
        path = folder / name
        path.write_text(schema_text(cls), encoding="utf-8", newline="\n")
        paths.append(path)
    return paths


if __name__ == "__main__":
    for written in write_schemas(Path(sys.argv[1]) if len(sys.argv) > 1 else _DATA):
        print(f"wrote {written}")
