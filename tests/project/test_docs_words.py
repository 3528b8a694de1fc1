"""The shipped text cites what a user can open: no tracker numbers, sessions or design notes.

Covers the files: the guide and examples (docs/), the README, the parameter files shipped with the
package, and the docstrings and comments of ``loader_model`` and ``derive``. The command line
(``loader_model/cli.py``, ``loader_model/commands/``: their module docstrings are the ``--help``
descriptions) is checked through its ``--help`` output by the command-line tests. A page cites
the paper (Eq., Table, Fig.), ISO standards, the guide's pages (the errata page for "errata N")
and the CHANGELOG.
"""

from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: Words that point to something a user cannot open. A public repository's issue
#: (``casadi/casadi#3009``) is allowed: it has an owner/name before the ``#``.
FORBIDDEN = re.compile(
    r"\bsessions?\b"
    r"|\bissues?\s+#?\d+"
    r"|(?<![\w/.-])#\d+\b"
    r"|DESIGN\.md"
    r"|\bdesign notes\b",
    re.IGNORECASE,
)


def forbidden_words(text: str) -> list[str]:
    """Each match of :data:`FORBIDDEN` in ``text`` with its line number, as ``"line: match"``."""
    hits = []
    for match in FORBIDDEN.finditer(text):
        line = text.count("\n", 0, match.start()) + 1
        hits.append(f"{line}: {match.group(0)!r}")
    return hits


def python_prose(source: str) -> str:
    """The comments and string literals of a Python source (docstrings included), one per line.

    Line numbers are kept: each token's text is placed on its own starting line, the rest blank.
    """
    lines = [""] * (source.count("\n") + 2)
    for token in tokenize.generate_tokens(io.StringIO(source).readline):
        if token.type in (tokenize.COMMENT, tokenize.STRING) or token.type == getattr(
            tokenize, "FSTRING_MIDDLE", -1
        ):
            row = token.start[0] - 1
            for k, part in enumerate(token.string.split("\n")):
                lines[row + k] += " " + part
    return "\n".join(lines)


def _files() -> list[Path]:
    docs = [
        p
        for p in (ROOT / "docs").rglob("*")
        if p.suffix in {".md", ".rst", ".py", ".txt"} and "_build" not in p.parts
    ]
    data = sorted((ROOT / "loader_model" / "data").rglob("*.toml"))
    code = sorted((ROOT / "loader_model").rglob("*.py")) + sorted((ROOT / "derive").rglob("*.py"))
    command_line = ROOT / "loader_model" / "commands"
    code = [p for p in code if command_line not in p.parents and p.name != "cli.py"]
    return [*sorted(docs), ROOT / "README.md", *data, *code]


def _id(path: Path) -> str:
    return str(path.relative_to(ROOT))


def test_pattern_catches_what_it_should():
    bad = [
        "as measured in session 7",
        "Sessions 3-4 measured",
        "the fidelity criterion of issue 13",
        "(issues 21)",
        "fixed in #21",
        "see DESIGN.md errata 11",
        "the team's design notes",
    ]
    good = [
        "errata 11 of the guide",
        "casadi/casadi#3009",
        "Eq. 43, Table 6, Fig. 14",
        "the issue with the pump limit",
        "a_total 4.286 m/s²",
        "rgb #fff",
    ]
    assert all(forbidden_words(text) for text in bad), [t for t in bad if not forbidden_words(t)]
    assert not any(forbidden_words(text) for text in good), [t for t in good if forbidden_words(t)]


def test_python_prose_keeps_strings_and_comments_only():
    source = 'session = 1  # see issue 4\nx = "session 5"\n\ndef f():\n    """Doc."""\n'
    prose = python_prose(source)
    assert "session = 1" not in prose
    assert forbidden_words(prose) == ["1: 'issue 4'", "2: 'session'"]


@pytest.mark.parametrize("path", _files(), ids=_id)
def test_no_tracker_or_session_words(path):
    text = path.read_text(encoding="utf-8")
    if path.suffix == ".py":
        text = python_prose(text)
    hits = forbidden_words(text)
    assert not hits, (
        f"{_id(path)} cites what a user cannot open (a session, a tracker issue or design notes); "
        f"cite the paper, the guide's pages (errata page) or the CHANGELOG instead: {hits}"
    )
