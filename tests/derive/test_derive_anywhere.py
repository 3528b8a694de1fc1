"""The derivation runs from any folder, and the command an error names runs where the user is."""

from __future__ import annotations

import os
import shlex
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from loader_model.machine_packages import derive_command, derive_extra_command

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(sys.executable).absolute().parent


def _run(command: list[str], cwd: Path, path: str) -> subprocess.CompletedProcess[str]:
    """Run ``command`` in ``cwd`` as a user outside the checkout with ``PATH`` = ``path``."""
    environment = {k: v for k, v in os.environ.items() if k not in {"PYTHONPATH", "VIRTUAL_ENV"}}
    environment["PATH"] = path
    return subprocess.run(
        command, cwd=cwd, env=environment, capture_output=True, text=True, timeout=120
    )


@pytest.mark.parametrize("activated", [True, False])
def test_the_named_derive_command_runs_from_another_folder(
    activated: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With this environment on the PATH (activated) the command is ``python -m derive`` or
    the console script; without it, this interpreter's full path. Either runs in a folder
    outside the checkout (its help here: deriving takes seconds and is tested elsewhere)."""
    path = os.pathsep.join([str(BIN), "/usr/bin", "/bin"]) if activated else "/usr/bin:/bin"
    monkeypatch.setenv("PATH", path)
    command = shlex.split(derive_command("my machine.toml"))
    assert command[-1] == "my machine.toml"  # as given, one word for the shell
    if activated:
        assert command[0] in ("python", "loader-model-derive")
    else:
        assert command[:3] == [str(Path(sys.executable).absolute()), "-m", "derive"]
    result = _run([*command[:-1], "--help"], tmp_path, path)
    assert result.returncode == 0, result.stderr
    assert "usage: " in result.stdout and "--machine" in result.stdout


def test_the_console_script_is_the_derivation(tmp_path: Path) -> None:
    """``loader-model-derive`` (pyproject.toml) calls ``derive.__main__.main`` and, installed
    beside this interpreter, runs outside the checkout under its own name."""
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))["project"]["scripts"]
    assert scripts["loader-model-derive"] == "derive.__main__:main"
    result = _run([str(BIN / "loader-model-derive"), "--help"], tmp_path, "/usr/bin:/bin")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("usage: loader-model-derive ")


def test_the_derive_extra_is_installed_into_this_environment() -> None:
    """This checkout is an editable install: the extra comes from its own folder, by path."""
    command = shlex.split(derive_extra_command())
    assert command[1:4] == ["-m", "pip", "install"]
    assert command[-2:] == ["-e", f"{ROOT}[derive]"]


def test_a_missing_package_names_the_extra_only_where_sympy_is_missing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from loader_model import machine_packages

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    description = tmp_path / "carrier.toml"
    description.write_text('[machine]\nname = "carrier"\n', encoding="utf-8")
    with pytest.raises(ValueError, match="has no generated package") as with_sympy:
        machine_packages.register_external(description, "carrier")
    assert str(with_sympy.value).endswith(f"derive it with `{derive_command(description)}`")
    real = machine_packages.importlib.util.find_spec
    monkeypatch.setattr(
        machine_packages.importlib.util,
        "find_spec",
        lambda name, *args: None if name == "sympy" else real(name, *args),
    )
    with pytest.raises(ValueError) as without:
        machine_packages.register_external(description, "carrier")
    assert str(without.value).endswith(
        f"`{derive_command(description)}` (needs the derive extra: `{derive_extra_command()}`)"
    )
