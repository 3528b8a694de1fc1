"""The whole reproduction report: every file present, images linked, Table 6 complete (slow)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from loader_model.cli import main
from loader_model.experiments.reproduction import FIGURES
from tests.experiments.test_report_markdown import assert_every_table_renders

pytestmark = pytest.mark.slow


def test_reproduce_writes_a_complete_report(tmp_path: Path, capsys) -> None:
    target = tmp_path / "report"
    assert main(["reproduce", "--output", str(target), "--trials", "2", "--jobs", "2"]) == 0
    text = (target / "report.md").read_text()
    links = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert sorted(links) == sorted(FIGURES)
    for name in links:
        assert (target / name).stat().st_size > 10_000
    for name in ("table1", "table4", "table5", "table6", "eq43", "gains", "designed", "trials"):
        assert (target / f"{name}.csv").is_file()
    assert len((target / "table6.csv").read_text().strip().splitlines()) == 13
    gains = (target / "gains.csv").read_text().strip().splitlines()
    assert [line.split(",")[0] for line in gains[1:]] == [
        "skyhook",
        "skyhook-printed",
        "skyhook-lqr",
        "skyhook-optimised",
        "skyhook-refined",
    ]
    designed = (target / "designed.csv").read_text().strip().splitlines()
    assert len(designed) == 5 and "Beyond the paper" in text
    trials = (target / "trials.csv").read_text().strip().splitlines()
    assert len(trials) == 1 + 2 * 2 * 8 * 2  # 4 controllers of the paper + printed + 3 designed
    for name in ("comfort", "fidelity_budget", "calibrated_values", "uncertainty", "scatter"):
        assert (target / f"{name}.csv").is_file(), name
    assert "## Scatter: the model's trial-to-trial spread beside the paper's" in text
    assert "A second machine: the compact wheel loader" in text
    assert "Fidelity budget: one modelling step at a time" in text
    assert "The bound: what the pump could do" in text
    assert "best simulated Δ [%] (model)" in text and "the linear plant's bound is not" in text
    assert "within 10 percentage points" in capsys.readouterr().out
    # a CommonMark (GitHub) renderer shows every table as a table; the summary comes first
    assert_every_table_renders(text)
    sections = re.findall(r"^## (.+)$", text, flags=re.M)
    assert sections[0] == "Summary" and sections[1].startswith("Table 6")
    assert re.search(r"\*\*\d+ of 12 cells of Table 6 lie within 10 percentage points", text)
    assert (target / "eq43_poles.csv").is_file()
