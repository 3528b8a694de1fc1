"""The python code blocks of the user guide's pages run as shown, page by page, in order."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "guide"
#: Pages whose blocks take longer than a few seconds (closed-loop drives, a small study).
SLOW = {"controllers", "robustness"}
#: Task-first pages: each opens with code that does the task.
MUST_HAVE_CODE = {"model", "controllers", "robustness", "fmu", "iso2631", "hydraulics"}


def python_blocks(text: str) -> list[str]:
    """The bodies of the ```python fenced blocks of ``text``, in order."""
    return re.findall(r"^```python\n(.*?)^```$", text, flags=re.M | re.S)


def _pages() -> list:
    pages = sorted(p for p in GUIDE.glob("*.md") if python_blocks(p.read_text(encoding="utf-8")))
    return [
        pytest.param(p, id=p.stem, marks=[pytest.mark.slow] if p.stem in SLOW else [])
        for p in pages
    ]


def test_task_pages_have_code():
    with_code = {p.stem for p in GUIDE.glob("*.md") if python_blocks(p.read_text("utf-8"))}
    assert MUST_HAVE_CODE <= with_code, (
        f"pages without a python block: {MUST_HAVE_CODE - with_code}"
    )


@pytest.mark.parametrize("page", _pages())
def test_guide_blocks_run(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": f"__guide_{page.stem}__"}
    for number, block in enumerate(python_blocks(page.read_text(encoding="utf-8")), start=1):
        exec(compile(block, f"docs/guide/{page.name} python block {number}", "exec"), namespace)
