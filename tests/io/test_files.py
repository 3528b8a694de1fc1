"""The one way in for files: existence, kind, permission, UTF-8 with or without BOM, line endings."""

from __future__ import annotations

import os
import threading
from pathlib import Path

import numpy as np
import pytest

from loader_model.io.files import check_readable_file, iter_lines, read_text
from loader_model.iso2631 import read_vibration_csv
from loader_model.parameters.sets import (
    bucket_load,
    default_loader,
    load_bucket_load,
    load_loader,
    resolve_loader_and_load,
    save,
)

BOM = b"\xef\xbb\xbf"


def _saved_loader(tmp_path: Path) -> bytes:
    save(default_loader(), tmp_path / "plain.toml")
    return (tmp_path / "plain.toml").read_bytes()


@pytest.mark.parametrize("bom", [False, True])
@pytest.mark.parametrize("newline", [b"\n", b"\r\n"])
def test_parameter_files_with_bom_or_windows_line_endings_load(
    tmp_path: Path, bom: bool, newline: bytes
) -> None:
    data = _saved_loader(tmp_path).replace(b"\n", newline)
    path = tmp_path / "loader.toml"
    path.write_bytes((BOM if bom else b"") + data)
    assert load_loader(path) == default_loader()
    save(bucket_load("full"), tmp_path / "load.toml")
    load_data = (tmp_path / "load.toml").read_bytes().replace(b"\n", newline)
    (tmp_path / "load.toml").write_bytes((BOM if bom else b"") + load_data)
    assert load_bucket_load(tmp_path / "load.toml") == bucket_load("full")


@pytest.mark.parametrize("bom", [False, True])
@pytest.mark.parametrize("newline", ["\n", "\r\n"])
def test_csv_with_bom_or_windows_line_endings_loads(
    tmp_path: Path, bom: bool, newline: str
) -> None:
    time_s = np.arange(50) / 100.0
    rows = ["time,z", *(f"{t:.2f},{np.sin(t):.6f}" for t in time_s)]
    path = tmp_path / "seat.csv"
    path.write_bytes((BOM if bom else b"") + newline.join(rows).encode() + newline.encode())
    record = read_vibration_csv(path)
    np.testing.assert_allclose(record.time_s, time_s, rtol=0, atol=1e-12)
    np.testing.assert_allclose(record.axes["z"], np.round(np.sin(time_s), 6), rtol=0, atol=1e-12)


def test_streamed_lines_survive_block_boundaries(tmp_path: Path) -> None:
    # \r\n split across two read blocks, a BOM, a multi-byte character split across blocks
    text = "a\r\nbé\r\n\rc\nlast"
    path = tmp_path / "lines.txt"
    path.write_bytes(BOM + text.encode())
    for chunk in (1, 2, 3, 7, 1 << 20):
        assert list(iter_lines(path, chunk_bytes=chunk)) == ["a", "bé", "", "c", "last"]


def _fifo(tmp_path: Path) -> Path:
    path = tmp_path / "pipe.toml"
    os.mkfifo(path)
    return path


KINDS = [
    (lambda p: p, r"loader parameter file '.*' is a folder, not a file"),
    (lambda p: p / "missing.toml", r"loader parameter file '.*missing\.toml' does not exist"),
    (_fifo, r"loader parameter file '.*pipe\.toml' is not a regular file"),
]


@pytest.mark.parametrize(("make", "message"), KINDS)
def test_params_that_are_not_regular_files_get_the_right_message(
    tmp_path: Path, make, message: str
) -> None:
    path = make(tmp_path)
    # a named pipe must not block: run in a thread with a time limit
    outcome: list[BaseException] = []

    def target() -> None:
        try:
            load_loader(path)
        except BaseException as error:
            outcome.append(error)

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    thread.join(timeout=5.0)
    assert not thread.is_alive(), "load_loader blocked"
    assert len(outcome) == 1 and isinstance(outcome[0], ValueError)
    assert __import__("re").search(message, str(outcome[0])), str(outcome[0])
    with pytest.raises(ValueError, match=message.replace("loader parameter", "vibration CSV")):
        read_vibration_csv(path)


def test_non_utf8_files_are_named(tmp_path: Path) -> None:
    bad = tmp_path / "latin1.toml"
    bad.write_bytes(_saved_loader(tmp_path).replace(b"standard gravity", b"Schwerkraft \xe4"))
    with pytest.raises(ValueError, match=r"latin1\.toml' is not UTF-8 text: byte 0xe4 at offset"):
        load_loader(bad)
    csv = tmp_path / "latin1.csv"
    csv.write_bytes(b"time,z\n0,1\n0.01,2\n# \xe4\n")
    with pytest.raises(ValueError, match=r"latin1\.csv' is not UTF-8 text: byte 0xe4 at offset 20"):
        read_vibration_csv(csv)


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads files whatever their permissions")
def test_unreadable_file_is_named(tmp_path: Path) -> None:
    path = tmp_path / "secret.toml"
    path.write_bytes(_saved_loader(tmp_path))
    path.chmod(0)
    with pytest.raises(ValueError, match=r"secret\.toml' cannot be read: permission denied"):
        load_loader(path)


@pytest.mark.parametrize("value", ["", 5, None])
def test_check_readable_file_refuses_non_paths(value: object) -> None:
    with pytest.raises(ValueError, match=r"input file must be a (non-empty )?path; got"):
        check_readable_file(value)  # type: ignore[arg-type]


def test_read_text_drops_only_a_leading_bom(tmp_path: Path) -> None:
    path = tmp_path / "t.txt"
    path.write_bytes(BOM + "x\ufeffy".encode())
    assert read_text(path) == "x\ufeffy"


def test_resolve_refuses_wrong_types_naming_the_argument() -> None:
    with pytest.raises(ValueError, match=r"loader must be a LoaderParameters, a path .*; got 5"):
        resolve_loader_and_load(5)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"load must be a BucketLoad, a path .*; got 1\.5"):
        resolve_loader_and_load(None, 1.5)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"load 'heavy' is neither a load case"):
        resolve_loader_and_load(None, "heavy")
