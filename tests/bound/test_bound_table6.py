"""The shipped bound table of the four Table 6 conditions is current, and renders."""

from __future__ import annotations

import pytest

from loader_model.bound.table6 import CONDITIONS, compute_table, load_table, render_markdown


def test_shipped_table_renders_every_condition():
    text = render_markdown()
    assert text.count("km/h") >= len(CONDITIONS)
    assert "make bound" in text


@pytest.mark.slow
def test_shipped_table_is_current():
    shipped, current = load_table(), compute_table()
    assert set(shipped) == set(current)
    for name, row in current.items():
        for key, value in row.items():
            if isinstance(value, float):
                assert shipped[name][key] == pytest.approx(value, rel=1e-6), (name, key)
