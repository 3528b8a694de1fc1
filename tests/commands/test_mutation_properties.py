"""Property tests (issue 9, item 7): one mutated field or cell gives a valid result or a clear error.

Every field of a valid parameter file and every cell of a valid CSV is replaced by values drawn
by hypothesis (any float including nan, inf and subnormals, huge integers, booleans, strings,
lists); the outcome must be a result without NaN or a ValueError naming the field or column.
Any other exception is a traceback for the user and fails the test; a deadline catches a hang.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from loader_model.iso2631 import evaluate_record, read_vibration_csv
from loader_model.modal.modes import modal_analysis
from loader_model.modal.undamped import undamped_matrices
from loader_model.vehicle.dynamics import LoaderDynamics
from loader_model.vehicle.statics import resolve_machine
from tests.mutations import (
    LOAD_PATHS,
    LOAD_TEXT,
    LOADER_PATHS,
    LOADER_TEXT,
    mutate_leaf,
    toml_literal,
    valid_csv_rows,
    write_csv,
)

scalars = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-1e4, max_value=1e4),
    st.integers(min_value=-(10**420), max_value=10**420),
    st.booleans(),
    st.text(max_size=5),
)
values = st.one_of(scalars, st.lists(st.floats(allow_nan=True), max_size=5))
SETTINGS = settings(max_examples=150, deadline=5000, suppress_health_check=[HealthCheck.too_slow])


def _use(loader_path: Path, load_path: Path | str) -> None:
    """The user's path: validate, build the model, linearise, modal analysis; all finite."""
    loader, load = resolve_machine(loader_path, load_path)
    model = LoaderDynamics.from_parameters(loader, load)
    linear = model.linearise()
    assert all(np.all(np.isfinite(m)) for m in (linear.A, linear.B, linear.C))
    matrices = undamped_matrices(loader, load)
    result = modal_analysis(matrices.mass, matrices.stiffness)
    assert np.all(np.isfinite(result.frequencies_hz))


def _check(path: str, run) -> None:
    try:
        run()
    except ValueError as error:
        names = {path, path.rsplit(".", 1)[0] if path.count(".") > 1 else path}
        assert any(name in str(error) for name in names), f"{path}: {error}"


@SETTINGS
@given(path=st.sampled_from(LOADER_PATHS), value=values)
def test_any_value_in_any_loader_field(path: str, value: object) -> None:
    text = mutate_leaf(LOADER_TEXT, path, toml_literal(value))
    with tempfile.TemporaryDirectory() as folder:
        file = Path(folder) / "loader.toml"
        file.write_text(text, encoding="utf-8")
        _check(path, lambda: _use(file, "empty"))


@SETTINGS
@given(path=st.sampled_from(LOAD_PATHS), value=values)
def test_any_value_in_any_load_field(path: str, value: object) -> None:
    text = mutate_leaf(LOAD_TEXT, path, toml_literal(value))
    with tempfile.TemporaryDirectory() as folder:
        file = Path(folder) / "load.toml"
        file.write_text(text, encoding="utf-8")
        # a load field may be named as load.<field> in consistency messages
        try:
            _use(None, file)  # type: ignore[arg-type]
        except ValueError as error:
            assert path in str(error), f"{path}: {error}"


ROWS = valid_csv_rows()
cells = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.text(alphabet="0123456789.e+-naif ,x", max_size=8),
    st.just(""),
)


@settings(max_examples=100, deadline=10000, suppress_health_check=[HealthCheck.too_slow])
@given(row=st.integers(min_value=0, max_value=len(ROWS) - 1), column=st.integers(0, 2), cell=cells)
def test_any_cell_of_a_csv(row: int, column: int, cell: str) -> None:
    rows = [list(r) for r in ROWS]
    rows[row][column] = cell
    name = ROWS[0][column]
    with tempfile.TemporaryDirectory() as folder:
        path = write_csv(Path(folder) / "seat.csv", rows)
        try:
            evaluation = evaluate_record(read_vibration_csv(path))
        except ValueError as error:
            message = str(error)
            in_header = row == 0 and "header" in message  # the column's name was mutated
            by_line = f"line {row + 1} has" in message  # a cell with a comma: a column too many
            named = f"'{name}'" in message or f"{name}_s" in message or in_header or by_line
            assert named, f"row {row} column {name} cell {cell!r}: {message}"
            return
    for item in evaluation.axes:
        values = (item.weighted_rms, item.mtvv, item.vdv, item.estimated_vdv)
        assert all(math.isfinite(v) for v in values)
        # undefined (NaN) only for an axis without vibration
        assert math.isfinite(item.crest_factor) == item.has_vibration
    assert math.isfinite(evaluation.total_m_s2)
