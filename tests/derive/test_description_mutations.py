"""Property: a mutated description or values file gives a clear error or a valid machine.

Hypothesis mutates the shipped descriptions (``derive/machines/*.toml``) and the wheel loader's
values file line by line: a value (also inside an inline table) replaced by any TOML literal
(floats with nan and inf, integers, booleans, strings, paths, arrays, tables), a line deleted,
duplicated or swapped, raw bytes put in. Each mutant is checked without deriving: by
:func:`derive.description.load_machine` (then :func:`~derive.description.structural_parameters`),
the runtime's :func:`~loader_model.machines.resolve_machine_name`, and for values by
:func:`~derive.description_values.check_values` and the runtime's parameter reader. Allowed outcomes: a
``ValueError`` of one line that names the file, or a machine; never another exception, and no
file is written beside the mutant.
"""

from __future__ import annotations

import json
import math
import re
import tempfile
import tomllib
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from derive.description import (
    MACHINES_DIR,
    DescriptionError,
    available_machines,
    load_machine,
    structural_parameters,
)
from derive.description_values import check_values
from loader_model.machines import machine, resolve_machine_name
from loader_model.parameters.machine_files import load_machine_parameters

DESCRIPTIONS = [(MACHINES_DIR / f"{name}.toml").read_text("utf-8") for name in available_machines()]
VALUES = (MACHINES_DIR / "values" / "compact_wheel_loader.toml").read_text("utf-8")
_VALUE = re.compile(r'(\w+) = ("[^"]*"|\[[^\]]*\]|[^,}\s#]+)')


def _float(value: float) -> str:
    if math.isnan(value):
        return "nan"
    return ("inf" if value > 0 else "-inf") if math.isinf(value) else repr(value)


LITERALS = st.one_of(
    st.floats().map(_float),
    st.integers(min_value=-(10**30), max_value=10**30).map(str),
    st.sampled_from(["true", "false", "[]", "{}", "[nan, 10]", "[10, -10]", "[1e3, inf]"]),
    st.sampled_from(['"big"', '"x_H"', '"theta_2"', '"A"', '"w"', '["w"]', '["x", "x"]']),
    st.sampled_from(['"../../evil"', '"skid_steer"', '"m_1"', '"kg"', '"N/m"', "[1, 2, 3]"]),
    st.text(max_size=10).map(json.dumps),
    st.lists(st.sampled_from(["1.0", '"x"', '"y"', "nan", "[]"]), max_size=4).map(
        lambda items: "[" + ", ".join(items) + "]"
    ),
)


@st.composite
def mutants(draw: st.DrawFn, texts: list[str]) -> bytes:
    """One to three line mutations of one of ``texts``."""
    lines = draw(st.sampled_from(texts)).splitlines()
    for _ in range(draw(st.integers(1, 3))):
        index = draw(st.integers(0, len(lines) - 1))
        operation = draw(st.sampled_from(["value", "value", "value", "delete", "copy", "swap"]))
        line = lines[index]
        matches = list(_VALUE.finditer(line))
        if operation == "value" and matches:
            match = draw(st.sampled_from(matches))
            lines[index] = line[: match.start(2)] + draw(LITERALS) + line[match.end(2) :]
        elif operation == "delete":
            del lines[index]
        elif operation == "copy":
            lines.insert(draw(st.integers(0, len(lines))), line)
        elif operation == "swap":
            other = draw(st.integers(0, len(lines) - 1))
            lines[index], lines[other] = lines[other], lines[index]
    data = ("\n".join(lines) + "\n").encode()
    if draw(st.integers(0, 20)) == 0:
        cut = draw(st.integers(0, len(data)))
        data = data[:cut] + draw(st.binary(min_size=1, max_size=4)) + data[cut:]
    return data


def _one_line(error: Exception, name: str) -> None:
    text = str(error)
    assert "\n" not in text and name in text, text


def _written_alone(folder: Path, name: str) -> None:
    assert [path.name for path in folder.iterdir()] == [name]


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=mutants(DESCRIPTIONS))
def test_mutated_description_is_a_machine_or_a_clear_error(data: bytes) -> None:
    with tempfile.TemporaryDirectory() as scratch:
        path = Path(scratch) / "mutant.toml"
        path.write_bytes(data)
        try:
            machine = load_machine(path)
        except DescriptionError as error:
            _one_line(error, "mutant.toml")
        else:
            names = [name for name, _ in structural_parameters(machine)]
            assert len(set(names)) == len(names)
            assert all(math.isfinite(v) for item in machine.parameters for v in item.range or ())
        try:
            resolve_machine_name(path)
        except ValueError as error:
            _one_line(error, "mutant.toml")
        _written_alone(Path(scratch), "mutant.toml")


WHEEL_LOADER = load_machine("compact_wheel_loader")


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=mutants([VALUES]))
def test_mutated_values_are_checked_or_a_clear_error(data: bytes) -> None:
    with tempfile.TemporaryDirectory() as scratch:
        path = Path(scratch) / "values.toml"
        path.write_bytes(data)
        try:
            values = tomllib.loads(data.decode("utf-8"))
        except (UnicodeDecodeError, tomllib.TOMLDecodeError):
            values = None
        if values is not None:
            try:
                check_values(WHEEL_LOADER, values)
            except DescriptionError as error:
                _one_line(error, "values for compact_wheel_loader")
        try:
            load_machine_parameters(path, machine("compact_wheel_loader"))
        except ValueError as error:
            _one_line(error, "values.toml")
        _written_alone(Path(scratch), "values.toml")
