"""The machine resolved once (:class:`~loader_model.plant.layout.PlantLayout`): built once per
machine and circuit, carried by the scenario, pickled by its source and hash."""

from __future__ import annotations

import pickle

import pytest

from loader_model.machines import _unpickle, machine
from loader_model.plant.layout import SKID_STEER, machine_layout, plant_layout, resolve_layout
from loader_model.plant.scenario import resolve_plant

#: A pickled layout holds a machine name (or a file's path), a sha256 and the circuit: 199 and
#: 209 bytes measured for the skid-steer and the wheel loader; 1000 would already mean that the
#: description's tables travel with it.
PICKLE_LIMIT_BYTES = 1000


def test_one_layout_per_machine_and_circuit() -> None:
    wheel_loader = plant_layout("compact_wheel_loader")
    assert plant_layout("compact_wheel_loader") is wheel_loader
    assert resolve_layout(wheel_loader) is wheel_loader
    assert resolve_layout("skid_steer") is SKID_STEER
    assert machine_layout(machine("compact_wheel_loader"), "pump") is wheel_loader
    valve = plant_layout("compact_wheel_loader", "valve")
    assert valve != wheel_loader and valve.machine == wheel_loader.machine
    assert valve.input_names == ("x_s_ref",) and wheel_loader.input_names == ("V_p_ref",)


@pytest.mark.parametrize("name", ["skid_steer", "compact_wheel_loader"])
def test_layout_pickles_as_its_source(name: str) -> None:
    layout = plant_layout(name)
    data = pickle.dumps(layout)
    assert len(data) < PICKLE_LIMIT_BYTES
    assert b"parameter_ranges" not in data  # not the registry entry's fields
    assert pickle.loads(data) is layout


def test_unpickling_refuses_a_changed_description() -> None:
    with pytest.raises(ValueError, match=r"compact_wheel_loader.*description changed"):
        _unpickle("compact_wheel_loader", "sha256:" + "0" * 64)


def test_scenario_carries_the_layout() -> None:
    scenario = resolve_plant(None, "full", machine="compact_wheel_loader")
    assert scenario.layout is plant_layout("compact_wheel_loader")
    assert not scenario.is_default_machine
    copy = pickle.loads(pickle.dumps(scenario))
    assert copy.layout is scenario.layout
    with pytest.raises(TypeError, match="layout must be a PlantLayout"):
        type(scenario)(scenario.params, scenario.x0, scenario.u0, scenario.y0, layout="skid_steer")
