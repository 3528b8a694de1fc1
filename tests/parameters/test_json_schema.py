"""The shipped JSON Schemas of the parameter files: fresh, valid, and agreeing with the loaders."""

from __future__ import annotations

import copy
import json
import tomllib
from importlib import resources
from pathlib import Path

import jsonschema
import pytest

from loader_model.parameters.json_schema import SCHEMA_FILES, schema_text
from loader_model.parameters.schema import BucketLoad, LoaderParameters

DATA = resources.files("loader_model").joinpath("data")
SHIPPED = {
    LoaderParameters: ["default_loader.toml"],
    BucketLoad: ["load_empty.toml", "load_full.toml"],
}


@pytest.mark.parametrize("cls", list(SCHEMA_FILES), ids=lambda c: c.__name__)
def test_shipped_schema_is_the_generated_one(cls: type) -> None:
    shipped = DATA.joinpath(SCHEMA_FILES[cls]).read_text(encoding="utf-8")
    assert shipped == schema_text(cls), (
        "stale schema: run `python -m loader_model.parameters.json_schema`"
    )


@pytest.mark.parametrize("cls", list(SCHEMA_FILES), ids=lambda c: c.__name__)
def test_schema_is_valid_and_accepts_the_shipped_files(cls: type) -> None:
    schema = json.loads(DATA.joinpath(SCHEMA_FILES[cls]).read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator.check_schema(schema)
    for name in SHIPPED[cls]:
        data = tomllib.loads(DATA.joinpath(name).read_text(encoding="utf-8"))
        jsonschema.validate(data, schema, cls=jsonschema.Draft202012Validator)


def _loader_data() -> dict:
    return tomllib.loads(DATA.joinpath("default_loader.toml").read_text(encoding="utf-8"))


EDITS = [
    (("chassis", "mass", "value"), 1e-300, "less than the minimum of 250"),
    (("tyres", "front", "k_y", "value"), 1e30, "greater than the maximum of 30000000"),
    (("geometry", "A", "value"), [1.0], "is too short"),
    (("chassis", "mass", "unit"), "t", "'kg' was expected"),
    (("cylinders", "count", "value"), 2.5, "is not of type 'integer'"),
    (("accumulator", "discharge_coefficient", "value"), 0.0, "less than the minimum of 0.1"),
]


@pytest.mark.parametrize(("keys", "value", "message"), EDITS)
def test_schema_refuses_what_the_loader_refuses(
    tmp_path: Path, keys: tuple, value: object, message: str
) -> None:
    from loader_model.parameters.sets import load_loader

    schema = json.loads(DATA.joinpath("loader.schema.json").read_text(encoding="utf-8"))
    data = copy.deepcopy(_loader_data())
    node = data
    for key in keys[:-1]:
        node = node[key]
    node[keys[-1]] = value
    with pytest.raises(jsonschema.ValidationError, match=message):
        jsonschema.validate(data, schema, cls=jsonschema.Draft202012Validator)
    text = DATA.joinpath("default_loader.toml").read_text(encoding="utf-8")
    (tmp_path / "bad.toml").write_text(text, encoding="utf-8")
    # the loader refuses the same edit (the files and the schema share the ranges)
    raw = tomllib.loads(text)
    node = raw
    for key in keys[:-1]:
        node = node[key]
    node[keys[-1]] = value
    from loader_model.parameters.toml_format import dumps

    (tmp_path / "bad.toml").write_text(dumps(raw), encoding="utf-8")
    with pytest.raises(
        ValueError, match=r"bad\.toml: " + r"\.".join(k for k in keys if k not in ("value", "unit"))
    ):
        load_loader(tmp_path / "bad.toml")


def test_unknown_key_is_refused_by_the_schema() -> None:
    schema = json.loads(DATA.joinpath("loader.schema.json").read_text(encoding="utf-8"))
    data = _loader_data()
    data["chassis"]["mas"] = data["chassis"]["mass"]
    with pytest.raises(jsonschema.ValidationError, match=r"Additional properties .* \('mas' was"):
        jsonschema.validate(data, schema, cls=jsonschema.Draft202012Validator)
