"""``--machine NAME|FILE`` on the modes and model commands."""

from __future__ import annotations

import pytest

from derive.description import MACHINES_DIR
from loader_model.cli import main


def test_modes_of_the_wheel_loader(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["modes", "--machine", "compact_wheel_loader", "--load", "full"]) == 0
    out = capsys.readouterr().out
    assert "compact wheel loader" in out and "theta_3 [rad]" in out
    assert "No paper reference" in out and "mode 5" in out


def test_modes_from_a_description_file(capsys: pytest.CaptureFixture[str]) -> None:
    path = str(MACHINES_DIR / "compact_wheel_loader.toml")
    assert main(["modes", "--machine", path]) == 0
    assert "theta_3" in capsys.readouterr().out


def test_the_skid_steer_report_is_the_default(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["modes"]) == 0
    default = capsys.readouterr().out
    assert main(["modes", "--machine", "skid_steer"]) == 0
    assert capsys.readouterr().out == default and "paper" in default


def test_model_summary_of_the_wheel_loader(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["model", "--machine", "compact_wheel_loader"]) == 0
    out = capsys.readouterr().out
    assert "static load F_tilt0" in out and "theta_3" in out


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["modes", "--machine", "tractor"], "unknown machine 'tractor'; allowed:"),
        (["model", "--machine", "nothing/here.toml"], "here.toml"),
        (["modes", "--machine", "compact_wheel_loader", "--load", "x"], "unknown load case 'x'"),
    ],
)
def test_bad_machine_is_one_line_exit_2(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
