"""Figures the guide computes from the shipped parameter files, recomputed at the page's rounding.

The tyres' static deflection and contact patch of the skid-steer (simulation page, errata 13),
the compact wheel loader's accumulator precharge and the skid-steer's pressure norms against its
static piston pressures (machines page). Each is rebuilt from the resolved plants, not from the
text, and must appear in the page as printed. Cheap: static equilibria only, no simulation.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from loader_model.plant.scenario import resolve_plant
from tests.docs.test_quoted_numbers import flat

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "guide"


def _page(name: str) -> str:
    return flat((GUIDE / name).read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def skid_steer() -> dict:
    return {load: resolve_plant(None, load) for load in ("empty", "full")}


def test_tyre_deflection_and_contact_patch(skid_steer) -> None:
    """δ = F_iy0 / k_iy per axle and load; the patch 2 sqrt(2 R δ − δ²) at R = 0.42 m."""
    deflections = [
        plant.output(f"F_{axle}y") / plant.parameter(f"k_{axle}y")
        for plant in skid_steer.values()
        for axle in ("A", "B")
    ]
    patches = [2.0 * math.sqrt(2.0 * 0.42 * d - d * d) for d in deflections]
    low, high = min(deflections) * 1e3, max(deflections) * 1e3
    shortest, longest = round(min(patches) * 1e3), round(max(patches) * 1e3)
    simulation = _page("simulation.md")
    assert f"deflect {low:.1f}-{high:.1f} mm statically" in simulation
    assert f"free radius: {shortest}-{longest} mm)" in simulation
    errata = _page("errata.md")
    assert f"({shortest}-{longest} mm at {low:.0f}-{high:.0f} mm static deflection)" in errata


def test_pressure_norms_and_the_wheel_loaders_precharge(skid_steer) -> None:
    """‖p_A‖∞ = 100 / 200 bar over the skid-steer's static piston pressures; the wheel loader's
    precharge 0.56 of its lowest static piston pressure."""
    from loader_model.machines import machine
    from loader_model.plant.machine_parameters import PRECHARGE_FRACTION, precharge_pressure

    ratios = [
        norm / (skid_steer[load].output("p_A") / 1e5)
        for load, norm in (("empty", 100.0), ("full", 200.0))
    ]
    precharge_bar = precharge_pressure(machine("compact_wheel_loader")) / 1e5
    machines = _page("machines.md")
    assert f"skid-steer's {PRECHARGE_FRACTION:.2f} of the lightest load's static" in machines
    assert f"({precharge_bar:.1f} bar for the wheel loader" in machines
    assert f"200 bar, {ratios[0]:.2f} and {ratios[1]:.2f} times its own)" in machines
