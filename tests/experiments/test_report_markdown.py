"""The report's Markdown: tables that a CommonMark (GitHub) renderer shows as tables, and a
summary computed from the Table 6 cells."""

from __future__ import annotations

import re

import pytest
from markdown_it import MarkdownIt

from loader_model.experiments.fidelity_report import action_minutes
from loader_model.experiments.report import markdown_table
from loader_model.experiments.statistics import Comparison
from loader_model.experiments.summary import summary_section
from loader_model.experiments.table6 import Table6Cell

#: CommonMark with GitHub's table extension, as GitHub renders a .md file.
RENDERER = MarkdownIt("commonmark").enable("table")


def rendered_tables(text: str) -> list[tuple[int, list[int]]]:
    """Each table the renderer finds: (header cells, cells of each body row)."""
    tables, header, rows, cells, in_head = [], 0, [], 0, False
    for token in RENDERER.parse(text):
        if token.type == "table_open":
            header, rows = 0, []
        elif token.type == "thead_open":
            in_head = True
        elif token.type == "thead_close":
            in_head = False
        elif token.type == "tr_open":
            cells = 0
        elif token.type in ("th_open", "td_open"):
            cells += 1
        elif token.type == "tr_close":
            if in_head:
                header = cells
            else:
                rows.append(cells)
        elif token.type == "table_close":
            tables.append((header, rows))
    return tables


def pipe_blocks(text: str) -> list[list[str]]:
    """Runs of consecutive lines that start with a pipe: what the writer meant as tables."""
    blocks, current = [], []
    for line in [*text.splitlines(), ""]:
        if line.startswith("|"):
            current.append(line)
        elif current:
            blocks.append(current)
            current = []
    return blocks


def assert_every_table_renders(text: str) -> None:
    """Every pipe block of ``text`` is a table with all its rows and the header's width."""
    blocks, tables = pipe_blocks(text), rendered_tables(text)
    assert len(tables) == len(blocks), (
        f"{len(blocks)} pipe blocks but {len(tables)} rendered tables; first lines: "
        f"{[b[0][:60] for b in blocks]}"
    )
    for block, (header, rows) in zip(blocks, tables, strict=True):
        width = len(re.findall(r"(?<!\\)\|", block[1])) - 1
        assert header == width, block[0]
        assert rows == [width] * (len(block) - 2), block[0]


def test_the_table_check_catches_an_unescaped_pipe():
    broken = "| a | |x| [pp] |\n|---|---|\n| 1 | 2 |\n"
    with pytest.raises(AssertionError):
        assert_every_table_renders(broken)


def test_pipes_in_header_and_cells_render_as_one_table():
    text = markdown_table([["Δ", "|Δ−Δ_paper| [pp]"], ["a|b", "1.0"], ["multi\nline", "2"]])
    assert_every_table_renders(text)
    assert rendered_tables(text) == [(2, [2, 2])]


def test_a_row_of_the_wrong_width_is_refused():
    with pytest.raises(ValueError, match="row 1 has 1 cells, the header 2"):
        markdown_table([["a", "b"], ["only one"]])


def _cell(controller, speed, load, change, p, paper, paper_p, half=5.0):
    return Table6Cell(
        speed,
        load,
        controller,
        Comparison(change, change - half, change + half, p),
        paper,
        paper_p,
    )


CELLS = [
    _cell("passive", 9.0, "empty", -20.0, 0.001, -26.4, 0.0001),  # within, same sign
    _cell("skyhook", 9.0, "empty", +8.0, 0.01, -33.6, 0.0000),  # 41.6 pp off, reversed
    _cell("virtual-accumulator", 9.0, "empty", +6.0, 0.02, -22.6, 0.0003),  # 28.6 pp off
    _cell("passive", 9.0, "full", -3.0, 0.4, -1.3, 0.2683),  # within, paper not significant
]


def test_summary_counts_and_names_the_cells():
    text = summary_section(CELLS, None, "Mean a_total from 1 to 2 m/s².")
    assert text.startswith("## Summary")
    assert "**2 of 4 cells of Table 6 lie within 10 percentage points" in text
    # significant in the paper: the three 9 km/h empty cells; same sign: passive only
    assert "the model has 1 with the same sign (1 of them significant too) and 2 " in text
    off = text[text.index("Not reproduced") :]
    assert off.index("skyhook, 9 km/h empty") < off.index("virtual-accumulator, 9 km/h empty")
    assert "model +8.0 % [+3.0, +13.0], paper -33.6 %" in text
    assert "at most 2.0 pp per condition, where the paper measured up to 11.0 pp" in text
    assert "not shipped" in text and text.rstrip().endswith("Mean a_total from 1 to 2 m/s².")
    assert_every_table_renders(text)


def test_summary_reads_the_budget():
    def step(label, within, in_sign, held=None):
        return {
            "label": label,
            "within": within,
            "count": 4,
            "significant_in_sign": in_sign,
            "significant_count": 3,
            "held_out_kmh": held,
            "held_out_within": 1,
            "held_out_count": 2,
        }

    budget = {
        "steps": [
            step("as it was", 1, 0),
            step("+ valves", 3, 2),
            step("+ seat", 3, 2),
            step("+ fit to 9", 4, 3, held=18.0),
        ],
        "uncertainty": {
            "samples": 10,
            "cells": {"9/empty/skyhook": {"share": 0.2}, "9/empty/passive": {"share": 0.9}},
        },
    }
    text = summary_section(CELLS, budget)
    assert "“valves” took the cells within 10 pp from 1 to 3 of 4" in text
    assert "from 0 to 2 of 3" in text
    assert "“fit to 9” brings 4 of 4 cells within 10 pp, the held-out 18 km/h cells 1 of 2" in text
    assert "in 1 of 2 cells fewer than half of 10 plausible machines" in text
    assert "(9/empty/skyhook)" in text


def test_summary_needs_cells():
    with pytest.raises(ValueError, match="Table 6 cells"):
        summary_section([], None)


def test_action_minutes_follow_the_directive():
    # A(8) = a sqrt(T / 8 h) = 0.5 m/s²: a = 1 m/s² reaches it after 2 h; x counts 1.4 times
    assert action_minutes(0.0, 1.0) == pytest.approx(120.0, rel=1e-12)
    assert action_minutes(1.0, 1.0) == pytest.approx(480.0 * (0.5 / 1.4) ** 2, rel=1e-12)
    assert action_minutes(0.0, 0.0) == float("inf")
