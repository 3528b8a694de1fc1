"""The shipped bound table of the four Table 6 conditions is current, and renders."""

from __future__ import annotations

import pytest

from loader_model.bound.table6 import CONDITIONS, compute_table, load_table, render_markdown


def test_shipped_table_renders_every_condition():
    text = render_markdown()
    assert text.count("km/h") >= len(CONDITIONS)
    assert "make bound" in text
    assert "best simulated" not in text


def test_reductions_stand_beside_their_own_condition():
    """Each condition's row carries its own measured and simulated reductions; a condition
    without them gets a dash, not another condition's numbers."""
    reductions = {
        "9 km/h empty": {"measured": ("skyhook", -33.6), "simulated": ("skyhook-refined", -38.4)},
        "18 km/h full": {"simulated": ("skyhook-optimised", -22.1)},
    }
    rows = {
        line.split("|")[1].strip(): [cell.strip() for cell in line.split("|")[2:-1]]
        for line in render_markdown(reductions=reductions).splitlines()
        if line.startswith("| ") and "km/h" in line.split("|")[1]
    }
    assert set(rows) == {f"{speed:g} km/h {load}" for speed, load in CONDITIONS}
    assert rows["9 km/h empty"][-2:] == ["-33.6 (skyhook)", "-38.4 (skyhook-refined)"]
    assert rows["18 km/h full"][-2:] == ["—", "-22.1 (skyhook-optimised)"]
    assert rows["9 km/h full"][-2:] == ["—", "—"]
    assert all(len(cells) == 8 for cells in rows.values())
    counts = {"measured": 0, "simulated": 0}
    for name, row in load_table().items():
        limit = 100 * (row["constrained_bound_a_total_m_s2"] / row["baseline_a_total_m_s2"] - 1)
        for key, (_, change) in reductions.get(name, {}).items():
            counts[key] += change < limit
    assert counts == {"measured": 1, "simulated": 2}  # the shipped bounds: -15.2 %, -6.5 %
    assert (
        f"linear bound in {counts['simulated']} of {len(CONDITIONS)} conditions, "
        f"the paper's measured best in {counts['measured']}:"
    ) in render_markdown(reductions=reductions)


#: Relative tolerance of the simulated baselines: the simulator is deterministic on one CPU, but
#: NumPy's SIMD kernels differ between CPUs and the tyres' lift-offs amplify the last digits:
#: the baseline at 9 km/h, empty, read 4.286061 on the machine that wrote the earlier table and
#: 4.286081 (4.5e-6) on an AMD EPYC without AVX-512 (the other three conditions 1.5e-9 to
#: 1.7e-6). The bounds themselves are linear algebra: 1e-15 apart there.
SIMULATED_RTOL = 1e-4


@pytest.mark.slow
def test_shipped_table_is_current():
    shipped, current = load_table(), compute_table()
    assert set(shipped) == set(current)
    for name, row in current.items():
        for key, value in row.items():
            if isinstance(value, float):
                rtol = SIMULATED_RTOL if key.startswith("baseline") else 1e-6
                assert shipped[name][key] == pytest.approx(value, rel=rtol), (name, key)
