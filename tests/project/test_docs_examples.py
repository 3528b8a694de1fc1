"""The worked examples of docs/examples/ run as shown, each in a temporary folder, and each page
shows its script's code as it is (readable on GitHub; the docs build appends the output)."""

from __future__ import annotations

import re
import runpy
from pathlib import Path

import pytest

EXAMPLES_DIR = Path(__file__).resolve().parents[2] / "docs" / "examples"
EXAMPLES = sorted(EXAMPLES_DIR.glob("*.py"))
# Examples that take longer than a few seconds run with `make test-slow`.
SLOW = {"identify_leakage"}  # 7 s


def _param(script: Path):
    marks = [pytest.mark.slow] if script.stem in SLOW else []
    return pytest.param(script, id=script.stem, marks=marks)


def test_examples_exist():
    assert {p.stem for p in EXAMPLES} >= {"design_gains_other_load", "custom_road_csv"}


@pytest.mark.parametrize("script", [_param(p) for p in EXAMPLES])
def test_example_runs(script, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    runpy.run_path(str(script), run_name="__main__")
    assert capsys.readouterr().out.strip(), f"{script.name} printed nothing"


@pytest.mark.parametrize("script", [_param(p) for p in EXAMPLES])
def test_example_has_its_page(script):
    page = EXAMPLES_DIR / f"{script.stem}.md"
    assert page.is_file(), f"{script.name}: no docs page {page.name} that includes it"
    text = page.read_text(encoding="utf-8")
    assert f"{script.name}" in text
    assert "{literalinclude}" not in text, "GitHub shows a directive, not the code"
    blocks = re.findall(r"^```python\n(.*?)^```$", text, flags=re.M | re.S)
    assert blocks == [script.read_text(encoding="utf-8")], (
        f"{page.name} must show {script.name} as it is, in one python block"
    )
    index = (EXAMPLES_DIR / "index.md").read_text(encoding="utf-8")
    assert f"\n{script.stem}\n" in index, f"{script.stem} is missing from examples/index.md"
