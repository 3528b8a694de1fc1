"""Bad descriptions and bad output folders are refused by ``python -m derive`` before deriving.

Every case exits with code 2 and one line naming the file, the entry, the value and what is
allowed; nothing is written. The output-folder cases are the two attacks on the derivation: an
output that is a symbolic link to a folder of the user's, or an existing folder with a user's file
in it: the user's files survive byte for byte.
"""

from __future__ import annotations

import os
import re
import time
from pathlib import Path

import pytest

from derive.__main__ import main as derive_main
from derive.description import MACHINES_DIR
from loader_model.machine_packages import derive_extra_command

WHEEL_LOADER = (MACHINES_DIR / "compact_wheel_loader.toml").read_text(encoding="utf-8")
CHASSIS = 'coordinates = ["x_H", "y_H", "theta_1"]'


def _edit(old: str, new: str) -> str:
    assert old in WHEEL_LOADER, old
    return WHEEL_LOADER.replace(old, new, 1)


def _range(value: str) -> str:
    return _edit("range = [1000.0, 20000.0]", f"range = {value}")


def _tyre(name: str, old: str, new: str) -> bytes:
    """The wheel loader with ``old`` replaced by ``new`` in the [tyres] entry ``name``."""
    line = next(row for row in WHEEL_LOADER.splitlines() if row.startswith(f"{name} = "))
    return _edit(line, line.replace(old, new, 1) if old else new).encode()


CASES = [
    ("binary", b"\x00\x01\x89PNG\r\n\x1a\n" + bytes(range(256)), r"\(file\): not UTF-8 text"),
    ("utf16", WHEEL_LOADER.encode("utf-16"), r"\(file\): not UTF-8 text \(byte 0 is b'\\xff'\)"),
    ("nested", ("a = " + "[" * 5000 + "]" * 5000 + "\n").encode(), r"\(file\): nested too deep"),
    ("duplicate", (WHEEL_LOADER + '\n[machine]\nname = "x"\n').encode(), r"not valid TOML"),
    (
        "float_name",
        _edit('mass = "m_1"', "mass = 250.0").encode(),
        r"bodies\.chassis\.mass: 250\.0 is not allowed; give a name",
    ),
    ("nan_range", _range("[nan, 10]").encode(), r"parameters\.m_1\.range: \[nan, 10\] is not"),
    (
        "reversed_range",
        _range("[10, -10]").encode(),
        r"parameters\.m_1\.range: \[10, -10\] is not allowed; give \[low, high\] with low < high",
    ),
    ("inf_range", _range("[1e3, inf]").encode(), r"parameters\.m_1\.range: \[1000\.0, inf\]"),
    ("text_range", _range('"big"').encode(), r"parameters\.m_1\.range: 'big' is not allowed"),
    (
        "point_range",
        _edit("point_range = [-10.0, 10.0]", "point_range = [nan, 10]").encode(),
        r"machine\.point_range: \[nan, 10\] is not allowed; give 2 finite numbers",
    ),
    (
        "coordinates_text",
        _edit(CHASSIS, 'coordinates = "x_H"').encode(),
        r"bodies\.chassis\.coordinates: 'x_H' is not allowed; give a list of 3 names",
    ),
    (
        "coordinate_twice",
        _edit('coordinate = "theta_3"', 'coordinate = "theta_2"').encode(),
        r"bodies\.bucket\.coordinate: 'theta_2' is not allowed; a name used once only "
        r"\(also bodies\.boom\.coordinate\)",
    ),
    (
        "sensor_axis",
        _edit('axes = ["y"]', 'axes = ["w"]').encode(),
        r"sensors\.N\.axes: \['w'\] is not allowed; give one or both of \"x\", \"y\"",
    ),
    (
        "sensor_axis_list",
        _edit('axes = ["y"]', "axes = [[]]").encode(),
        r"sensors\.N\.axes: \[\[\]\] is not allowed; give one or both of \"x\", \"y\"",
    ),
    (
        "path_name",
        _edit('name = "compact_wheel_loader"', 'name = "../../evil"').encode(),
        r"machine\.name: '\.\./\.\./evil' is not allowed; give a name: letters, digits",
    ),
    (
        "number_name",
        _edit('name = "compact_wheel_loader"', "name = 5").encode(),
        r"machine\.name: 5 is not allowed; give a name",
    ),
    (
        "actuator_kind",
        _edit('kind = "locked"', 'kind = "floating"').encode(),
        r"actuators\.tilt\.kind: 'floating' is not allowed; allowed: driven, locked",
    ),
    (
        "tyre_radius_range",
        _tyre("R_A", "range = [0.2, 1.0]", "range = [0.2, 3.0]"),
        r"tyres\.R_A\.range: \[0\.2, 3\] m is not allowed; give a range inside \(0, 2\] m",
    ),
    (
        "tyre_exponent_range",
        _tyre("ce_B", "range = [1.5, 2.0]", "range = [1.0, 2.0]"),
        r"tyres\.ce_B\.range: \[1, 2\] - is not allowed; give a range inside \(1, 10\] -",
    ),
    ("tyre_nan_range", _tyre("R_B", "[0.2, 1.0]", "[nan, 1.0]"), r"tyres\.R_B\.range: \[nan, 1"),
    ("tyre_missing", _tyre("R_B", "", ""), r"tyres: missing R_B \[m\]: give each axle's free"),
    ("tyre_no_source", _tyre("ae_A", ', source = "', ', sources = "'), r"tyres\.ae_A: unknown"),
    (
        "tyre_unknown",
        _tyre("ls_B", "ls_B", "lsB"),
        r"tyres: unknown tyre parameter 'lsB' \(did you mean 'ls_B'\?\); allowed: R_A, ae_A",
    ),
    ("tyre_unit", _tyre("R_A", 'unit = "m"', 'unit = "mm"'), r"tyres\.R_A\.unit: 'mm', expected"),
]


@pytest.mark.parametrize(("label", "data", "message"), CASES, ids=[case[0] for case in CASES])
def test_bad_description_exits_2_with_one_line_before_deriving(
    label: str, data: bytes, message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    description = tmp_path / f"{label}.toml"
    description.write_bytes(data)
    output = tmp_path / "out"
    start = time.perf_counter()
    assert derive_main([str(description), "--output", str(output)]) == 2
    elapsed = time.perf_counter() - start
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert err.startswith(f"python -m derive: {label}.toml: "), err
    assert re.search(message, err), err
    assert sorted(path.name for path in tmp_path.iterdir()) == [description.name]
    assert elapsed < 3.0  # refused before deriving (a derivation takes 4-16 s)


def _user_folder(root: Path) -> tuple[Path, dict[str, bytes]]:
    folder = root / "my_project"
    folder.mkdir()
    files = {"my_code.py": b"print('mine')\n", "notes.txt": b"keep\n"}
    for name, data in files.items():
        (folder / name).write_bytes(data)
    return folder, files


@pytest.mark.parametrize("kind", ["symlink", "existing_folder", "file"])
def test_derive_output_never_destroys_a_users_files(
    kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A symbolic link to a folder of the user's, a folder with the user's files, or a file as
    ``--output``: refused naming it before anything is derived; every user file survives."""
    folder, files = _user_folder(tmp_path)
    description = tmp_path / "carrier.toml"
    description.write_text(_edit("compact_wheel_loader", "carrier"), encoding="utf-8")
    output = {"symlink": tmp_path / "link", "existing_folder": folder}.get(
        kind, folder / "notes.txt"
    )
    if kind == "symlink":
        output.symlink_to(folder, target_is_directory=True)
    argv = [str(description), "--output", str(output)]
    start = time.perf_counter()
    assert derive_main(argv) == 2
    assert time.perf_counter() - start < 3.0  # before deriving
    err = capsys.readouterr().err
    expected = {
        "symlink": "is a symbolic link",
        "existing_folder": "holds 'my_code.py', which derive did not write",
        "file": "is a file, not a folder",
    }[kind]
    assert f"python -m derive: {output}: {expected}" in err and err.count("\n") == 1, err
    assert {path.name: path.read_bytes() for path in folder.iterdir()} == files
    assert not [path for path in tmp_path.iterdir() if ".staging-" in path.name]


def test_default_machine_output_is_checked_too(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The default machine shares its folder with the other machines' packages (generated/):
    a folder with a user's Python file in it is refused all the same."""
    folder, files = _user_folder(tmp_path)
    assert derive_main(["--output", str(folder), "--machine", "skid_steer"]) == 2
    err = capsys.readouterr().err
    assert f"{folder}: holds 'my_code.py', which derive did not write" in err
    assert {path.name: path.read_bytes() for path in folder.iterdir()} == files


@pytest.mark.parametrize(("label", "data"), [case[:2] for case in CASES], ids=[c[0] for c in CASES])
def test_runtime_refuses_the_same_files_with_one_line(
    label: str, data: bytes, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``--machine FILE`` of each bad file: exit 2, one line naming the file, nothing run."""
    from loader_model.cli import main

    description = tmp_path / f"{label}.toml"
    description.write_bytes(data)
    assert main(["modes", "--machine", str(description)]) == 2
    err = capsys.readouterr().err
    assert str(description) in err and err.count("\n") == 1 and "Traceback" not in err, err


def test_derive_without_sympy_names_the_extra(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import derive.__main__ as command

    real = command.importlib.util.find_spec
    monkeypatch.setattr(
        command.importlib.util, "find_spec", lambda name: None if name == "sympy" else real(name)
    )
    description = tmp_path / "carrier.toml"
    description.write_text(WHEEL_LOADER, encoding="utf-8")
    assert derive_main([str(description)]) == 2
    err = capsys.readouterr().err
    assert err == (
        f"python -m derive: needs SymPy; install the derive extra: {derive_extra_command()}\n"
    )


def test_install_replaces_its_own_package_whole_and_keeps_a_users_late_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """derive.install without SymPy: a folder derive wrote is replaced as a whole (a stale file
    goes); a failed finishing step leaves the old package; a user's file that appears during the
    derivation is kept in the old folder, named in the error."""
    from derive.install import GENERATED_MARK, OutputError, install

    folder = tmp_path / "package"
    old = {"__init__.py": f"{GENERATED_MARK} (x)\nA = 1\n", "stale.py": f"{GENERATED_MARK}\n"}
    install(folder, old)
    new = {"__init__.py": f"{GENERATED_MARK} (x)\nA = 2\n"}

    def fail(staging: Path) -> None:
        raise OSError("disk full")

    with pytest.raises(OSError, match="disk full"):
        install(folder, new, finish=fail)
    assert {p.name: p.read_text() for p in folder.iterdir()} == old
    install(folder, new)
    assert {p.name: p.read_text() for p in folder.iterdir()} == new

    def late_user_file(staging: Path) -> None:
        (folder / "mine.txt").write_text("keep", encoding="utf-8")

    with pytest.raises(OutputError, match=r"holds 'mine.txt', which derive did not write; nothing"):
        install(folder, old, finish=late_user_file)
    assert {p.name: p.read_text() for p in folder.iterdir()} == {**new, "mine.txt": "keep"}
    (folder / "mine.txt").unlink()
    rename = os.rename

    def rename_after_a_user_write(source: Path, target: Path) -> None:
        if Path(source) == folder:  # the last moment: the user writes, then derive moves it
            (folder / "late.txt").write_text("keep", encoding="utf-8")
        rename(source, target)

    monkeypatch.setattr("derive.install.os.rename", rename_after_a_user_write)
    with pytest.raises(OutputError, match=r"previous contents are kept in .*\.package\.old-"):
        install(folder, old)
    kept = [path for path in tmp_path.iterdir() if path.name.startswith(".package.old-")]
    assert len(kept) == 1 and (kept[0] / "late.txt").read_text() == "keep"
    assert {p.name: p.read_text() for p in folder.iterdir()} == old
    assert not [path for path in tmp_path.iterdir() if ".staging-" in path.name]
