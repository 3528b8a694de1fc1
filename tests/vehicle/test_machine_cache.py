"""The runtime imports a described machine's generated code only from its own verified cache.

A package is put into the cache as ``python -m derive <file>`` puts it (``derive.install`` with
the manifest of ``loader_model.machine_packages``), here with the wheel loader's generated files
under another machine name, so no derivation runs. Every payload below writes a marker file when
it is imported: the marker must never appear.
"""

from __future__ import annotations

import os
import re
import shutil
import stat
import uuid
from functools import partial
from pathlib import Path

import pytest

from derive.description import MACHINES_DIR
from derive.install import install
from loader_model.cli import main
from loader_model.machine_packages import (
    cache_root,
    derive_command,
    description_hash,
    generated_folder,
    prepare_cache,
    write_manifest,
)
from loader_model.machines import machine

GENERATED = Path(__file__).resolve().parents[2] / "generated" / "compact_wheel_loader"
PARAMS = Path(__file__).resolve().parents[2] / "loader_model" / "data" / "machines"


def _payload(marker: Path) -> str:
    return f"from pathlib import Path\nPath({str(marker)!r}).write_text('ran')\n"


def _description(root: Path) -> Path:
    """A copy of the wheel loader's description under a fresh name (one per test)."""
    name = f"carrier_{uuid.uuid4().hex[:10]}"
    text = (MACHINES_DIR / "compact_wheel_loader.toml").read_text(encoding="utf-8")
    path = root / f"{name}.toml"
    path.write_text(text.replace('name = "compact_wheel_loader"', f'name = "{name}"'), "utf-8")
    return path


def _cache(description: Path, edit: dict[str, str | None] | None = None) -> Path:
    """Put the wheel loader's package into the cache for ``description`` as derive does."""
    files = {path.name: path.read_text(encoding="utf-8") for path in GENERATED.glob("*.py")}
    for name, text in (edit or {}).items():
        if text is None:
            del files[name]
        else:
            files[name] = text
    data = description.read_bytes()
    prepare_cache()
    folder = generated_folder(data)
    install(folder, files, finish=partial(write_manifest, description=data), mode=0o700)
    return folder


def test_payload_beside_the_description_never_runs(tmp_path: Path) -> None:
    """The folder beside the file that earlier versions imported (with the description's hash in
    it) is ignored: refused without a cached package, and left alone with one."""
    description = _description(tmp_path)
    marker = tmp_path / "marker"
    beside = tmp_path / f"{description.stem}_generated"
    beside.mkdir()
    header = f'DESCRIPTION_HASH = "{description_hash(description)}"\n'  # what was once checked
    (beside / "__init__.py").write_text(header + _payload(marker), encoding="utf-8")
    with pytest.raises(ValueError, match="has no generated package for this version of the file"):
        machine(description)
    assert not marker.exists()
    folder = _cache(description)
    assert not folder.is_relative_to(tmp_path) and folder.is_relative_to(cache_root())
    info = machine(description)
    assert info.coordinate_names == ("x_H", "y_H", "theta_1", "theta_2", "theta_3")
    assert info.description_path == folder / "description.toml"
    assert not marker.exists()
    assert stat.S_IMODE(folder.stat().st_mode) == 0o700


def _tamper(kind: str, folder: Path, marker: Path, tmp_path: Path) -> None:
    if kind == "edited":
        with (folder / "__init__.py").open("a", encoding="utf-8") as handle:
            handle.write(_payload(marker))
    elif kind == "added":
        (folder / "payload.py").write_text(_payload(marker), encoding="utf-8")
    elif kind == "symlink":
        elsewhere = tmp_path / "elsewhere"
        shutil.copytree(folder, elsewhere)
        shutil.rmtree(folder)
        folder.symlink_to(elsewhere, target_is_directory=True)
    elif kind == "no_manifest":  # a foreign folder under the right name
        (folder / "MANIFEST.json").unlink()
    elif kind == "open_folder":
        folder.chmod(0o755)
    elif kind == "other_user":
        os.chown(folder, 54321, 54321)


@pytest.mark.parametrize(
    ("kind", "message"),
    [
        ("edited", r"__init__\.py: differs from the manifest"),
        ("added", r"payload\.py: not in the manifest"),
        ("symlink", r"is a symbolic link; the runtime does not follow it"),
        ("no_manifest", r"MANIFEST\.json: the manifest cannot be read \(No such file"),
        ("open_folder", r"others may enter the generated package's folder \(not 0o700\)"),
        ("other_user", r"belongs to another user \(uid 54321\)"),
    ],
)
def test_tampered_cache_is_refused_before_anything_runs(
    kind: str, message: str, tmp_path: Path
) -> None:
    if kind == "other_user" and (not hasattr(os, "geteuid") or os.geteuid() != 0):
        pytest.skip("giving a folder to another user needs root")
    description = _description(tmp_path)
    folder = _cache(description)
    marker = tmp_path / "marker"
    _tamper(kind, folder, marker, tmp_path)
    with pytest.raises(ValueError, match=message) as error:
        machine(description)
    assert f"derive it again with `{derive_command(description)}`" in str(error.value)
    assert not marker.exists()


def test_a_cache_writable_by_others_is_refused(tmp_path: Path) -> None:
    description = _description(tmp_path)
    _cache(description)
    mode = stat.S_IMODE(cache_root().stat().st_mode)
    cache_root().chmod(0o777)
    try:
        with pytest.raises(ValueError, match="writable by the group or others"):
            machine(description)
    finally:
        cache_root().chmod(mode)


INIT = (GENERATED / "__init__.py").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        ({"__init__.py": "raise SystemExit(0)\n"}, r"does not import \(SystemExit: 0\)"),
        ({"__init__.py": "raise RuntimeError('boom')\n"}, r"RuntimeError: boom"),
        (
            {"__init__.py": INIT.replace("COORDINATE_NAMES: tuple", "OTHER_NAMES: tuple")},
            r"AttributeError: .*COORDINATE_NAMES",
        ),
        ({"mass_matrix.py": None}, r"no module mass_matrix of its FUNCTION_NAMES"),
    ],
    ids=["system_exit", "raises", "no_coordinate_names", "missing_module"],
)
def test_broken_package_exits_2_naming_the_repair(
    edit: dict[str, str | None], message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    description = _description(tmp_path)
    _cache(description, edit)
    params = PARAMS / "compact_wheel_loader.toml"
    for command in ("modes", "simulate", "design"):
        argv = [command, "--machine", str(description), "--params", str(params)]
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "Traceback" not in err, err
        assert re.search(message, err), err
        assert derive_command(description) in err, err


def test_a_worker_process_verifies_and_imports_the_same_folder(tmp_path: Path) -> None:
    """A fresh process (as a robustness study's worker) resolves the file to the same cache
    folder, verifies it and imports it; once the folder is tampered with, it refuses it too."""
    import subprocess
    import sys

    description = _description(tmp_path)
    folder = _cache(description)
    code = (
        "import sys\nfrom loader_model.machines import machine\n"
        "try:\n    print(machine(sys.argv[1]).description_path.parent)\n"
        "except ValueError as error:\n    print(error)\n"
    )

    def worker() -> str:
        command = [sys.executable, "-c", code, str(description)]
        done = subprocess.run(command, capture_output=True, text=True, check=True, timeout=60)
        return done.stdout.strip()

    assert worker() == str(folder)
    marker = tmp_path / "marker"
    _tamper("added", folder, marker, tmp_path)
    assert "payload.py: not in the manifest" in worker()
    assert not marker.exists()
