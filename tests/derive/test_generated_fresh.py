"""generated/ is what derive/ produces: a fast hash check and a full byte-for-byte regeneration."""

from __future__ import annotations

import difflib
from pathlib import Path

import pytest

import loader_model_generated
from derive.description import available_machines
from derive.input_hash import input_hash

GENERATED_DIR = Path(loader_model_generated.__file__).resolve().parent
HINT = "generated/ is stale: run `make regenerate` and commit the result"
NUMERIC_MODELS = "default_linear_models.py"


def test_input_hash_matches_derive_sources() -> None:
    assert loader_model_generated.INPUT_HASH == input_hash(), HINT


def test_every_generated_file_carries_header_and_hash() -> None:
    files = sorted(GENERATED_DIR.glob("*.py"))
    # one file per function, the package index and the default loader's numeric linear models
    assert len(files) == len(loader_model_generated.FUNCTION_NAMES) + 2
    for path in files:
        if path.name == NUMERIC_MODELS:
            continue
        head = path.read_text(encoding="utf-8").splitlines()[:4]
        assert "Do NOT modify by hand" in head[0], path.name
        assert head[2] == f"# Input hash: {input_hash()}", f"{path.name}: {HINT}"
        assert head[3].startswith("# Total ops: "), path.name


def _machine_dir(machine: str) -> Path:
    return GENERATED_DIR if machine == "skid_steer" else GENERATED_DIR / machine


def test_every_described_machine_is_generated() -> None:
    """Each derive/machines/*.toml has its package (the default machine: the top folder)."""
    folders = {p.name for p in GENERATED_DIR.iterdir() if p.is_dir() and p.name != "__pycache__"}
    assert folders == set(available_machines()) - {"skid_steer"}, HINT


@pytest.mark.parametrize("machine", available_machines())
def test_input_hash_of_every_machine_is_current(machine: str) -> None:
    head = (_machine_dir(machine) / "__init__.py").read_text(encoding="utf-8").splitlines()[2]
    assert head == f"# Input hash: {input_hash(machine)}", f"{machine}: {HINT}"


@pytest.mark.parametrize("machine", available_machines())
def test_regeneration_reproduces_generated_bytes(tmp_path: Path, machine: str) -> None:
    """The SymForce pattern: regenerate into a temporary folder and compare files and bytes."""
    pytest.importorskip("sympy")
    from derive.generate import generate

    fresh = tmp_path / "generated"
    generate(fresh, machine)
    folder = _machine_dir(machine)
    checked_in = {p.name for p in folder.glob("*.py")} - {NUMERIC_MODELS}
    regenerated = {p.name for p in fresh.glob("*.py")}
    assert checked_in == regenerated, f"file lists differ; {HINT}"
    for name in sorted(regenerated):
        old = (folder / name).read_text(encoding="utf-8")
        new = (fresh / name).read_text(encoding="utf-8")
        if old != new:
            diff = "".join(
                difflib.unified_diff(
                    old.splitlines(keepends=True),
                    new.splitlines(keepends=True),
                    f"generated/{name}",
                    f"regenerated/{name}",
                )
            )
            pytest.fail(f"{HINT}\n{diff[:5000]}")


def test_unknown_function_name_is_rejected() -> None:
    with pytest.raises(ValueError, match="unknown generated function 'nope'; allowed: mass_matrix"):
        loader_model_generated.function("nope")


@pytest.mark.slow
def test_regeneration_is_deterministic_across_hash_seeds(tmp_path: Path) -> None:
    """Two runs in fresh interpreters with different PYTHONHASHSEED give identical bytes."""
    import os
    import subprocess
    import sys

    outputs = []
    for seed in ("0", "4242"):
        out = tmp_path / f"seed{seed}"
        env = {**os.environ, "PYTHONHASHSEED": seed}
        root = Path(__file__).resolve().parents[2]
        command = [sys.executable, "-m", "derive", "--output", str(out)]
        subprocess.run(command, cwd=root, env=env, check=True, capture_output=True)
        outputs.append({str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("*.py"))})
    assert outputs[0] == outputs[1]


def test_numeric_linear_models_of_default_loader_are_fresh() -> None:
    """The checked-in numeric models match the current parameter files and generated code
    (compared as numbers to 1e-10 relative: the file prints 12 significant digits)."""
    import numpy as np

    from derive.numeric_models import parameter_files_hash, render_numeric_models
    from loader_model_generated import default_linear_models as checked_in

    assert checked_in.PARAMETER_FILES_HASH == parameter_files_hash(), HINT
    assert checked_in.INPUT_HASH == input_hash(), HINT
    namespace: dict = {}
    exec(render_numeric_models(input_hash()), namespace)
    fresh = namespace["LINEAR_MODELS"]
    assert fresh.keys() == checked_in.LINEAR_MODELS.keys(), HINT
    for case, matrices in fresh.items():
        for name, value in matrices.items():
            old = checked_in.LINEAR_MODELS[case][name]
            if isinstance(value, dict):
                old, value = list(old.values()), list(value.values())
            scale = max(np.abs(np.asarray(value)).max(), 1.0)
            np.testing.assert_allclose(
                old, value, rtol=1e-10, atol=1e-10 * scale, err_msg=f"{case} {name}: {HINT}"
            )
