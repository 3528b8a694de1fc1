"""The tractor example's figures on its own tyres, rebuilt from the kept design-check outputs
(docs/measurements/tractor_check_*.txt) and checked against docs/examples/tractor_front_loader.md."""

from __future__ import annotations

import re
from pathlib import Path

from tests.docs.test_kept_outputs import HEADER
from tests.docs.test_quoted_numbers import flat

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "examples" / "tractor_front_loader.md"


def _rows(name: str) -> dict[str, list[str]]:
    """Each judged condition's columns after its name (design, baseline, passive, change [%],
    ...) in a kept design check, as printed."""
    text = (ROOT / "docs" / "measurements" / name).read_text(encoding="utf-8")
    assert HEADER.match(text), f"{name}: first line must say command, date and machine"
    rows = {}
    for line in text.splitlines():
        if line.startswith(("empty, ", "full, ")) and line.rstrip().endswith(("pass", "FAIL")):
            condition, rest = line[:25].strip(), line[25:].split()
            rows[condition] = rest
    return rows


def _changes(name: str) -> dict[str, str]:
    return {condition: row[3] for condition, row in _rows(name).items()}


def test_table3_and_zero_gain_changes_are_the_kept_checks() -> None:
    table3, zero = _changes("tractor_check_table3.txt"), _changes("tractor_check_zero_gains.txt")
    assert len(table3) == len(zero) == 26
    failing = [c for c, v in table3.items() if float(v) > 2.0]
    assert len(failing) == 5
    quotes = [
        "Table 3's gains fail 5 of the 26 conditions",
        "the empty bucket on the class B, C and D roads at 5 km/h ("
        + ", ".join(f"{table3[f'empty, ISO {c} 5 km/h']} %" for c in "BCD")
        + ")",
        f"the full bucket on the boards at 5 and 18 km/h ({table3['full, boards 5 km/h']} %, "
        f"{table3['full, boards 18 km/h']} %)",
        f"{zero['empty, ISO C 5 km/h']} % on the empty bucket's class C road at 5 km/h, "
        f"{zero['full, boards 5 km/h']} % and {zero['full, boards 18 km/h']} % on the full "
        "bucket's boards at 5 and 18 km/h",
    ]
    text = flat(PAGE.read_text(encoding="utf-8"))
    for quote in quotes:
        assert flat(quote) in text, f"the tractor page should quote {quote!r}"
    assert all(float(zero[c]) > 2.0 for c in failing)  # "fails the same five"
    # "on the empty bucket's roads at 5 km/h the passive accumulator ... loses as much": the
    # passive runs' change against the baseline, from the kept columns (+2.0, +2.4, +2.5 %)
    for road in "BCD":
        _, baseline, passive, *_ = _rows("tractor_check_zero_gains.txt")[
            f"empty, ISO {road} 5 km/h"
        ]
        assert 100.0 * (float(passive) / float(baseline) - 1.0) > 1.9


def test_the_shipped_designs_figures_are_its_checks() -> None:
    """Section 6's figures of the shipped tractor design, from its shipped check."""
    text = (ROOT / "loader_model" / "data" / "design_check_tractor_front_loader.md").read_text(
        encoding="utf-8"
    )
    changes = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 11 and cells[0].startswith(("empty, ", "full, ")):
            changes[cells[0]] = float(cells[4])
    assert len(changes) == 26
    slow = [c for c in changes if float(c.split()[-2]) < 9.5]
    assert len(slow) == 10 and all(changes[c] == 0.0 for c in slow)
    worse = sorted(c for c, v in changes.items() if v > 0.0)
    assert worse == sorted(
        [
            "empty, boards 13.5 km/h",
            "empty, ISO C 30 km/h",
            "empty, ISO D 30 km/h",
            "full, ISO D 30 km/h",
        ]
    )
    page = flat(PAGE.read_text(encoding="utf-8"))
    quotes = [
        f"the empty bucket's boards at 13.5 km/h {changes['empty, boards 13.5 km/h']:+.1f} %",
        f"the class C and D roads at 30 km/h {changes['empty, ISO C 30 km/h']:+.1f} % and "
        f"{changes['empty, ISO D 30 km/h']:+.1f} %",
        f"the full bucket's class D road at 30 km/h {changes['full, ISO D 30 km/h']:+.1f} %",
        f"{-changes['full, boards 13.5 km/h']:.1f} % better on the full bucket's boards at 13.5 km/h",
        f"{-max(changes[c] for c in ('full, ISO B 30 km/h', 'full, ISO C 30 km/h')):.1f}-"
        f"{-min(changes[c] for c in ('full, ISO B 30 km/h', 'full, ISO C 30 km/h')):.1f} % on the "
        "full bucket's class B and C roads at 30 km/h",
    ]
    fifteen = [v for c, v in changes.items() if "15 km/h" in c] + [changes["empty, boards 18 km/h"]]
    quotes.append(f"{-max(fifteen):.1f}-{-min(fifteen):.1f} % better than the baseline")
    sampled = re.findall(r"(\d+) of (\d+) sampled plants unstable, worst margin (\d\.\d+)", text)
    assert [unstable for unstable, _, _ in sampled] == ["0", "0"]
    quotes.append(f"none of the {sum(int(n) for _, n, _ in sampled)} is unstable")
    margins = re.findall(r"loop margin (\d\.\d+) rad/s", text)
    assert [worst for _, _, worst in sampled] == margins  # "the worst margins are the nominal"
    quotes.append(f"The loop's margin is {margins[0]} rad/s with the empty bucket")
    quotes.append(f"and {margins[1]} with the full one")
    for quote in quotes:
        assert flat(quote) in page, f"the tractor page should quote {quote!r}"
