"""The scatter study's file, its report section and its command line (fast), and the shipped
file's currency (slow: it re-runs trials)."""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy import stats

from loader_model.experiments.scatter import paper_implied_scatter
from loader_model.experiments.scatter_report import scatter_rows_for_report, scatter_section
from loader_model.experiments.scatter_study import (
    COLUMNS,
    main,
    read_scatter,
    scatter_rows,
    shipped_scatter,
    write_scatter,
)


def _row(speed: float, load: str, controller: str, sd: float, change: float) -> dict:
    row = dict.fromkeys(COLUMNS, 0.0)
    row.update(
        speed_kmh=speed, load=load, controller=controller, trials=40, failed_controller=0,
        failed_baseline=1, baseline_mean_m_s2=4.0, sd_pct=sd, change_pct=change, se_pp=1.5,
        four_change_pct=change + 20.0, four_low_pct=change, four_high_pct=change + 40.0,
        four_p=0.3, four_sd_pct=sd,
    )  # fmt: skip
    return row


def test_the_file_round_trips(tmp_path) -> None:
    rows = [_row(9.0, "empty", "passive", 12.25, -3.5), _row(18.0, "full", "skyhook", 3.0, -4.0)]
    path = tmp_path / "scatter.csv"
    write_scatter(str(path), rows, ["command: made here --seed 3", "date: today"])
    header, back = read_scatter(path.read_text(encoding="utf-8"))
    assert header == {"command": "made here --seed 3", "date": "today"}
    assert [r["controller"] for r in back] == ["passive", "skyhook"]
    assert (
        back[0]["sd_pct"] == 12.25 and back[0]["trials"] == 40 and back[0]["failed_baseline"] == 1
    )


def test_the_section_counts_against_the_implied_scatter() -> None:
    implied = paper_implied_scatter()
    passive = implied[(9.0, "full", "passive")].sd_percent
    rows = [
        # twice the paper's scatter + 1 %: outside; its mean 0.2 pp from the paper's -1.3
        _row(9.0, "full", "passive", 2.01 * passive, -1.1),
        # 1.5 times: inside; 12 pp off
        _row(18.0, "empty", "passive", 1.5 * implied[(18.0, "empty", "passive")].sd_percent, 9.4),
        # the upper bound (p = 0.0000): 1.9 times the bound is a ratio >= 1.9, counted inside
        _row(9.0, "empty", "skyhook", 1.9 * implied[(9.0, "empty", "skyhook")].sd_percent, -30.0),
    ]
    table, counts = scatter_rows_for_report(rows)
    assert counts == {
        "cells": 3, "within": 2, "within_four": 0, "scatter_within": 2, "se_met": 3, "failed": 3,
    }  # fmt: skip
    assert table[1][6] == "2.0" and table[3][6] == "≥ 1.9" and table[3][4].startswith("≤ ")
    text, _ = scatter_section(
        ({"command": "x --seed 0"}, rows), {(9.0, "full", "passive"): -1.0}, 0
    )
    assert "2 of 3 cells lie within 10 pp" in text and "differ by at most 20 pp" in text
    assert "t₁₋ₚ/₂,₆" in text and "upper bound" in text
    other_seed, _ = scatter_section(
        ({"command": "x --seed 0"}, rows), {(9.0, "full", "passive"): -1.0}, 1
    )
    assert "differ by at most" not in other_seed


def test_the_shipped_section_renders() -> None:
    from tests.experiments.test_report_markdown import assert_every_table_renders

    text, table = scatter_section(shipped_scatter())
    assert table is not None and len(table) == 13
    assert_every_table_renders(text)


def test_without_a_study_the_section_says_how_to_make_it() -> None:
    text, table = scatter_section(None)
    assert table is None and "make scatter" in text


@pytest.mark.parametrize(
    ("argv", "match"),
    [
        (["--trials", "3", "--output", "x.csv"], "--trials 3: allowed: an integer >= 4"),
        (["--jobs", "0", "--output", "x.csv"], "--jobs 0"),
        (["--output", "x.json"], "--output"),
    ],
)
def test_bad_arguments_exit_2_with_one_line(argv, match, capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    assert re.search(re.escape(match), capsys.readouterr().err)


def test_unknown_cells_are_named() -> None:
    with pytest.raises(ValueError, match="not Table 6 cells"):
        scatter_rows(4, cells=[(12.0, "empty", "skyhook")])


#: Standard errors within which a recomputed cell's mean change must equal the shipped one. Its
#: first trials are a subset of the shipped ones (difference variance σ²(1/k − 1/N)); on a CPU
#: where the lift-offs turn differently they are fresh draws (σ²(1/k + 1/N)): 4.5 combined
#: standard errors bound both; a Student t of k − 1 = 23 degrees of freedom exceeds 4.5 with
#: probability 1.6e-4.
MEAN_SE = 4.5
#: Two-sided probability at which the pooled SD of k trials per group is compared with the
#: shipped one (chi-square of 2 (k − 1) degrees of freedom, normal trials).
SD_ALPHA = 1e-4
#: Relative uncertainty of the shipped SD itself, added to the chi-square bounds: the SD of
#: N = 150 trials per group has a relative standard error of 1 / √(2 (2N − 2)) = 4 %; 3 of those.
SHIPPED_SD_RTOL = 0.12
CHECKED_CELLS = [(9.0, "empty", "skyhook"), (18.0, "full", "passive")]
CHECKED_TRIALS = 24


@pytest.mark.slow
def test_the_shipped_scatter_is_current() -> None:
    """Two cells recomputed with 24 trials per group agree with the shipped study within the
    statistical tolerances above (``make scatter`` remakes it)."""
    study = shipped_scatter()
    assert study is not None, "run make scatter"
    header, rows = study
    seed = int(re.search(r"--seed (\d+)", header["command"]).group(1))
    shipped = {(r["speed_kmh"], r["load"], r["controller"]): r for r in rows}
    assert len(shipped) == 12
    dof = 2 * (CHECKED_TRIALS - 1)
    low = np.sqrt(stats.chi2.ppf(SD_ALPHA / 2, dof) / dof) * (1 - SHIPPED_SD_RTOL)
    high = np.sqrt(stats.chi2.isf(SD_ALPHA / 2, dof) / dof) * (1 + SHIPPED_SD_RTOL)
    for row in scatter_rows(CHECKED_TRIALS, seed, jobs=2, cells=CHECKED_CELLS):
        want = shipped[(row["speed_kmh"], row["load"], row["controller"])]
        tolerance = MEAN_SE * np.hypot(row["se_pp"], want["se_pp"])
        assert abs(row["change_pct"] - want["change_pct"]) <= tolerance, (row, want)
        assert low <= row["sd_pct"] / want["sd_pct"] <= high, (row, want)
        # the first four trials are the report's; here a subset of the same draws
        assert row["four_change_pct"] == pytest.approx(want["four_change_pct"], abs=tolerance)
