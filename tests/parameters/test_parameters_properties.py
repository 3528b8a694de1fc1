"""Property tests: combining rigid bodies and the TOML round trip."""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from loader_model.parameters.sets import combine_bodies, default_loader, load_loader, replace, save

masses = st.floats(min_value=1e-3, max_value=1e5, allow_nan=False)
coords = st.floats(min_value=-10.0, max_value=10.0, allow_nan=False)
inertias = st.floats(min_value=1e-3, max_value=1e5, allow_nan=False)
bodies = st.lists(st.tuples(masses, st.tuples(coords, coords), inertias), min_size=1, max_size=5)


@settings(max_examples=200, deadline=None)
@given(bodies)
def test_combination_conserves_mass_and_adds_inertia(parts: list) -> None:
    m, g, j = zip(*parts, strict=True)
    mass, cog, inertia = combine_bodies(m, g, j)
    assert mass == pytest.approx(math.fsum(m), rel=1e-15)
    assert inertia >= math.fsum(j) * (1.0 - 1e-12)
    # the combined CoG lies in the bounding box of the parts
    for axis in (0, 1):
        low, high = min(p[axis] for p in g), max(p[axis] for p in g)
        assert low - 1e-9 <= cog[axis] <= high + 1e-9


@settings(max_examples=100, deadline=None)
@given(bodies)
def test_inertia_about_g_is_minimal(parts: list) -> None:
    # parallel-axis theorem: J about any other point exceeds J about the combined G
    m, g, j = zip(*parts, strict=True)
    mass, (gx, gy), inertia = combine_bodies(m, g, j)
    other = (gx + 0.5, gy - 0.25)
    about_other = math.fsum(
        ji + mi * ((p[0] - other[0]) ** 2 + (p[1] - other[1]) ** 2)
        for mi, p, ji in zip(m, g, j, strict=True)
    )
    assert about_other == pytest.approx(inertia + mass * 0.3125, rel=1e-9)


# arbitrary floats inside each field's plausible range (every bit pattern must round-trip)
stiffness = st.floats(min_value=5e4, max_value=3e7)
inertia_1 = st.floats(min_value=20.0, max_value=5e5)
gain = st.floats(min_value=-100.0, max_value=100.0)


@settings(max_examples=50, deadline=None)
@given(stiffness, inertia_1, st.tuples(gain, gain, gain, gain), st.text(min_size=1))
def test_round_trip_of_arbitrary_values(
    k_y: float, inertia: float, k_fb: tuple, source: str
) -> None:
    source = source if source.strip() else source + "x"
    changed = replace(
        default_loader(),
        {"tyres.rear.k_y": k_y, "chassis.inertia": inertia, "controller.k_fb": k_fb},
        source=source,
    )
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "loader.toml"
        save(changed, path)
        assert load_loader(path) == changed
