"""Linear models export to .npz and .mat with their signal names; failures leave no file."""

from __future__ import annotations

import os
import re
import stat
import tempfile
from pathlib import Path

import numpy as np
import pytest
import scipy.io

from loader_model.cli import main
from loader_model.io.export import check_output_path, write_atomically
from loader_model.vehicle.dynamics import OUTPUT_NAMES, STATE_NAMES, LoaderDynamics


@pytest.fixture
def linear(paper_layout: dict[str, float]):
    return LoaderDynamics(paper_layout).linearise()


def test_npz_round_trip(tmp_path: Path, linear) -> None:
    path = linear.save(tmp_path / "loader.npz")
    with np.load(path) as data:
        np.testing.assert_array_equal(data["A"], linear.A)
        np.testing.assert_array_equal(data["D_w"], linear.D_w)
        assert data["state_names"].tolist() == list(STATE_NAMES)
        assert data["output_names"].tolist() == list(OUTPUT_NAMES)


def test_mat_round_trip(tmp_path: Path, linear) -> None:
    data = scipy.io.loadmat(linear.save(tmp_path / "loader.mat"))
    np.testing.assert_array_equal(data["A"], linear.A)
    np.testing.assert_array_equal(data["B"], linear.B)
    assert [str(item[0]) for item in data["state_names"].ravel()] == list(STATE_NAMES)


def test_bad_suffix_and_missing_folder(tmp_path: Path, linear) -> None:
    with pytest.raises(
        ValueError, match=r"export file .* has suffix '\.csv'; allowed: \['\.npz', '\.mat'\]"
    ):
        linear.save(tmp_path / "loader.csv")
    with pytest.raises(ValueError, match=r"output folder .* does not exist"):
        linear.save(tmp_path / "missing" / "loader.npz")
    assert list(tmp_path.iterdir()) == []


def test_failed_write_leaves_no_file(tmp_path: Path, linear, monkeypatch) -> None:
    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(np, "savez", broken)
    (tmp_path / "loader.npz").write_bytes(b"good")
    with pytest.raises(ValueError, match=r"loader\.npz' could not be written: disk full; nothing"):
        linear.save(tmp_path / "loader.npz")
    assert (tmp_path / "loader.npz").read_bytes() == b"good"
    (tmp_path / "loader.npz").unlink()
    assert list(tmp_path.iterdir()) == []


def test_model_command_exports(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["model", "--load", "full", "--export", str(tmp_path / "m.npz")]) == 0
    assert "Static equilibrium" in capsys.readouterr().out
    with np.load(tmp_path / "m.npz") as data:
        assert data["A"].shape == (8, 8) and data["E"].shape == (8, 11)


@pytest.mark.parametrize("umask", [0o022, 0o077, 0o002])
def test_new_files_get_the_umask_permissions(tmp_path: Path, linear, umask: int) -> None:
    old = os.umask(umask)
    try:
        path = linear.save(tmp_path / "m.npz")
    finally:
        os.umask(old)
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~umask


def test_overwriting_keeps_the_permissions(tmp_path: Path, linear) -> None:
    path = tmp_path / "m.npz"
    path.write_bytes(b"old")
    path.chmod(0o644)
    linear.save(path)
    assert stat.S_IMODE(path.stat().st_mode) == 0o644
    with np.load(path) as data:
        np.testing.assert_array_equal(data["A"], linear.A)


def test_check_output_path_refusals(tmp_path: Path) -> None:
    (tmp_path / "d.npz").mkdir()
    os.mkfifo(tmp_path / "p.npz")
    cases = [
        ("", r"out must be a non-empty path ending in one of \['\.npz'\]; got ''"),
        (str(tmp_path / "d.npz"), r"out '.*d\.npz' is a folder; give a file name"),
        (str(tmp_path / "p.npz"), r"out '.*p\.npz' exists and is not a regular file"),
        (str(tmp_path / "x" / "m.npz"), r"output folder '.*x' of out '.*m\.npz' does not exist"),
        (str(tmp_path / "m.npy"), r"out '.*m\.npy' has suffix '\.npy'; allowed: \['\.npz'\]"),
    ]
    for path, message in cases:
        with pytest.raises(ValueError, match=message):
            check_output_path(path, (".npz",), "out")


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes anywhere")
def test_unwritable_folder_is_refused(tmp_path: Path) -> None:
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    with pytest.raises(ValueError, match=r"cannot be written: no permission"):
        check_output_path(folder / "m.npz", (".npz",))


def test_unwritable_location_is_refused_by_the_writer(tmp_path: Path, monkeypatch) -> None:
    # as root, permission bits do not stop writes: simulate the refusal of the OS instead
    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tempfile, "mkstemp", refuse)
    with pytest.raises(ValueError, match=r"out '.*m\.npz' cannot be written: Permission denied"):
        write_atomically(tmp_path / "m.npz", lambda p: None, (".npz",), "out")
    assert list(tmp_path.iterdir()) == []


CLI_OUTPUTS = [
    (["model", "--export", ""], r"--export must be a non-empty path"),
    (["model", "--export", "{tmp}"], r"--export '.*' has suffix ''"),
    (["model", "--export", "{tmp}/sub.npz"], r"--export '.*sub\.npz' is a folder"),
    (
        ["calibrate", "--output", "{tmp}/c.npz"],
        r"--output '.*c\.npz' has suffix '\.npz'; allowed: \['\.toml'",
    ),
    (["calibrate", "--output", "{tmp}/sub.npz"], r"has suffix '\.npz'"),
    (
        ["iso2631", "--plot-weightings", "{tmp}/sub.npz"],
        r"--plot-weightings .* suffix '\.npz'; allowed: \['\.png'",
    ),
    (
        ["iso2631", "--plot-weightings", "{tmp}/dir.png"],
        r"--plot-weightings '.*dir\.png' is a folder",
    ),
]


@pytest.mark.parametrize(("argv", "message"), CLI_OUTPUTS)
def test_commands_refuse_bad_output_paths_and_write_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], argv: list[str], message: str
) -> None:
    (tmp_path / "sub.npz").mkdir()
    (tmp_path / "dir.png").mkdir()
    before = sorted(tmp_path.rglob("*"))
    assert main([a.replace("{tmp}", str(tmp_path)) for a in argv]) == 2
    captured = capsys.readouterr()
    assert re.search(message, captured.err), captured.err
    assert "Traceback" not in captured.err
    assert captured.out == ""
    assert sorted(tmp_path.rglob("*")) == before


def test_a_nul_byte_in_an_output_path_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"out '.*' cannot be written: embedded null byte"):
        check_output_path(str(tmp_path / "a\x00b.npz"), (".npz",), "out")
