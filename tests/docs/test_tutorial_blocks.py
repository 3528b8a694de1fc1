"""Every output the tutorial shows is an excerpt of a kept output of its command.

``docs/guide/tutorial.md`` shows after each command block the output the command printed,
shortened with "…". The whole outputs are kept in ``docs/measurements/tutorial/`` (one file per
command, :data:`KEPT`); each shown line must be a line of that file, and a line shortened with
"…" must hold its pieces, in order, in one line of the file. ``test_tutorial_output.py`` (slow)
runs the quick commands again. Cheap: it reads files only.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import loader_model

ROOT = Path(__file__).resolve().parents[2]
TUTORIAL = ROOT / "docs" / "guide" / "tutorial.md"
KEPT_DIR = ROOT / "docs" / "measurements" / "tutorial"
#: The last command of each shell block with output, and the file that keeps its whole output.
KEPT = {
    "loader-model simulate --controller skyhook --output run.csv": "simulate.txt",
    "loader-model simulate --compare": "compare.txt",
    "loader-model design --output my_gains.toml --no-progress": "design.txt",
    "loader-model check-design refined.toml --output refined_check.csv --no-progress": (
        "check_refined.txt"
    ),
    "python -m derive my_loader.toml": "my_loader_derive.txt",
    "loader-model simulate --machine my_loader.toml --params my_loader_values.toml --load full "
    "--compare": "my_loader_compare.txt",
    "loader-model design --machine my_loader.toml --params my_loader_values.toml "
    "--output my_loader_gains.toml --no-progress": "my_loader_design.txt",
    "loader-model simulate --machine my_loader.toml --params my_loader_values.toml --load full "
    "--compare --controller my_loader_gains.toml": "my_loader_compare_designed.txt",
    "loader-model check-design my_loader_gains.toml --machine my_loader.toml --params "
    "my_loader_values.toml --conditions rough.toml --no-progress": "my_loader_check_rough.txt",
}


def shown_outputs(text: str) -> list[tuple[str, str]]:
    """(last command, shown output) of every ```sh block followed by a ```text block."""
    pairs = re.findall(r"```sh\n(.*?)```\n\n```text\n(.*?)```", text, flags=re.S)
    return [(commands.strip().splitlines()[-1].strip(), output) for commands, output in pairs]


def flat(line: str) -> str:
    return " ".join(line.split())


def is_excerpt(shown: str, kept: str) -> list[str]:
    """The shown lines that are not in ``kept`` (empty when ``shown`` is an excerpt of it)."""
    lines = [flat(line) for line in kept.splitlines()]
    missing = []
    for line in shown.splitlines():
        pieces = [flat(piece) for piece in line.split("…") if flat(piece)]
        if not pieces:
            continue
        if len(pieces) == 1 and "…" not in line:
            found = pieces[0] in lines
        else:
            pattern = ".*".join(re.escape(piece) for piece in pieces)
            found = any(re.search(pattern, kept_line) for kept_line in lines)
        if not found:
            missing.append(line)
    return missing


def test_excerpt_logic() -> None:
    kept = "a 1.0 2.0 x\nb  3.0   y\n"
    assert is_excerpt("a 1.0 2.0 x\n…\nb 3.0 … y", kept) == []
    assert is_excerpt("a 1.1 2.0 x", kept) == ["a 1.1 2.0 x"]


def test_every_output_has_a_kept_file() -> None:
    commands = [command for command, _ in shown_outputs(TUTORIAL.read_text(encoding="utf-8"))]
    assert "loader-model --version" in commands
    unknown = [c for c in commands if c != "loader-model --version" and c not in KEPT]
    assert not unknown, f"tutorial outputs without a kept file in {KEPT_DIR}: {unknown}"
    assert sorted(KEPT) == sorted(c for c in commands if c in KEPT)


@pytest.mark.parametrize("command", sorted(KEPT), ids=lambda c: KEPT[c])
def test_shown_output_is_an_excerpt_of_the_kept_one(command: str) -> None:
    shown = dict(shown_outputs(TUTORIAL.read_text(encoding="utf-8")))[command]
    kept = (KEPT_DIR / KEPT[command]).read_text(encoding="utf-8")
    missing = is_excerpt(shown, kept)
    assert not missing, f"tutorial lines not in {KEPT[command]}: {missing}"


def test_version_shown_is_the_package_version() -> None:
    shown = dict(shown_outputs(TUTORIAL.read_text(encoding="utf-8")))["loader-model --version"]
    assert shown.strip() == f"loader-model {loader_model.__version__}"
