"""ISO 2631-1:1997 Annex C.2.3 comfort reactions, against the standard's table."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from loader_model.iso2631.comfort import COMFORT_SCALE, comfort_reaction


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (0.0, "not uncomfortable"),
        (0.3149, "not uncomfortable"),
        (0.315, "a little uncomfortable"),
        (0.4, "a little uncomfortable"),
        (0.55, "a little uncomfortable to fairly uncomfortable"),
        (0.7, "fairly uncomfortable"),
        (0.9, "fairly uncomfortable to uncomfortable"),
        (1.1, "uncomfortable"),
        (1.4, "uncomfortable to very uncomfortable"),
        (1.8, "very uncomfortable"),
        (2.2, "very uncomfortable to extremely uncomfortable"),
        (2.5, "extremely uncomfortable"),
        (7.0, "extremely uncomfortable"),
    ],
)
def test_reactions_follow_annex_c(value: float, expected: str) -> None:
    assert comfort_reaction(value) == expected


@given(st.floats(min_value=0.0, max_value=1e3, allow_nan=False))
def test_every_value_has_one_or_two_neighbouring_reactions(value: float) -> None:
    names = [name for _, _, name in COMFORT_SCALE]
    found = comfort_reaction(value).split(" to ")
    assert 1 <= len(found) <= 2
    indices = [names.index(name) for name in found]
    assert indices == list(range(indices[0], indices[0] + len(found)))


@pytest.mark.parametrize("bad", [-0.1, math.nan, math.inf, "1.0", True, None])
def test_bad_values_are_named(bad: object) -> None:
    with pytest.raises(ValueError, match="total_m_s2"):
        comfort_reaction(bad)  # type: ignore[arg-type]
