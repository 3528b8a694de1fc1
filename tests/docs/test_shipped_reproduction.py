"""The reproduction run the README and the guide quote is still what ``reproduce`` gives (slow).

``docs/measurements/table6.csv`` and ``designed.csv`` are the files of one ``loader-model reproduce``
run (``docs/measurements/reproduce.toml``); ``test_quoted_numbers.py`` compares every quoted cell with
them. This test runs the same command again and compares the files cell by cell.

Tolerance: 1.0 percentage point on each change and interval bound. The run is deterministic on one
machine (same seed, same numbers); across CPUs (an AMD EPYC without AVX-512 against an Intel Xeon
with it) the shipped fidelity budget's cells, the same 4-trial Table 6 matrix, moved by up to
0.88 pp. A stale file (a model change) moves cells by more: the tyre enveloping moved the 9 km/h
empty cells by 3.9 to 7.2 pp (the fidelity budget's steps).
"""

from __future__ import annotations

import csv
import re
import tomllib
from pathlib import Path

import pytest

from loader_model.cli import main

pytestmark = pytest.mark.slow

RESULTS = Path(__file__).resolve().parents[2] / "docs" / "measurements"
TOLERANCE_PP = 1.0
#: the second machine's a_total, modes and gains: relative, plus one unit of the printed rounding
#: (one nominal drive each; across CPUs the bound table's nominal baselines moved by 3.6e-3)
RTOL_MACHINE = 5e-3


def numbers(text: str) -> list[float]:
    """Every signed decimal number in a cell (``"-2.2 [-22.7, +18.4]"`` -> three numbers)."""
    return [float(v) for v in re.findall(r"[-+]?\d+(?:\.\d+)?", text)]


def rows(path: Path) -> list[dict[str, str]]:
    with path.open(encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def test_shipped_tables_are_current(tmp_path: Path) -> None:
    run = tomllib.loads((RESULTS / "reproduce.toml").read_text(encoding="utf-8"))
    target = tmp_path / "report"
    argv = ["reproduce", "--output", str(target), "--trials", str(run["trials"])]
    argv += ["--seed", str(run["seed"]), "--jobs", "2", "--no-progress"]
    assert main(argv) == 0
    for name, columns in (
        ("table6.csv", ("model Δ [%]", "95 % CI [%]")),
        ("designed.csv", None),
    ):
        shipped, fresh = rows(RESULTS / name), rows(target / name)
        assert len(shipped) == len(fresh), name
        for old, new in zip(shipped, fresh, strict=True):
            keys = columns or [k for k in old if k.endswith("[95 % CI]")]
            for key in keys:
                assert numbers(new[key]) == pytest.approx(numbers(old[key]), abs=TOLERANCE_PP), (
                    f"docs/measurements/{name} is stale at {old['speed']}, {old['load']}, {key}: "
                    f"shipped {old[key]!r}, now {new[key]!r}; run `{run['command']}` and copy "
                    "the file (and update the pages that quote it)"
                )
            if columns:  # the paper's side of Table 6 is the paper's
                for key in ("paper Δ [%]", "paper p"):
                    assert new[key] == old[key]
    stale = machine_stale(RESULTS, target)
    assert not stale, f"stale in docs/measurements (rerun `{run['command']}`): {stale}"


def machine_stale(shipped_dir: Path, fresh_dir: Path) -> list[str]:
    """The rows of the second machine's files (one nominal drive per controller and load, its
    modes and gains) that moved by more than :data:`RTOL_MACHINE` plus one printed unit."""
    stale = []
    for name in ("machine_comparison.csv", "machine_modes.csv", "machine_gains.csv"):
        shipped = (shipped_dir / name).read_text(encoding="utf-8").splitlines()
        fresh = (fresh_dir / name).read_text(encoding="utf-8").splitlines()
        if len(shipped) != len(fresh):
            stale.append(f"{name}: {len(fresh)} lines, kept {len(shipped)}")
            continue
        for old, new in zip(shipped[1:], fresh[1:], strict=True):
            # the gains lead their row; the other files lead with a label
            part = (
                (lambda line: line.split(",")[0])
                if name == "machine_gains.csv"
                else (lambda line: line.split(",", 1)[1])
            )
            old_text = re.findall(r"[-+]?\d+(?:\.\d+)?", part(old))
            new_values = numbers(part(new))
            if len(new_values) != len(old_text):
                stale.append(f"{name}: {new!r}, kept {old!r}")
                continue
            for text, value in zip(old_text, new_values, strict=True):
                unit = 10.0 ** -len(text.partition(".")[2])  # one unit of the printed rounding
                if abs(value - float(text)) > RTOL_MACHINE * abs(float(text)) + unit:
                    stale.append(f"{name}: {new!r}, kept {old!r}")
                    break
    return stale
