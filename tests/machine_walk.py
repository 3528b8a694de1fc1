"""Walk one Table 6 trial from ``run_trial`` through the code: which modules run, and how the
machine travels (``python -m tests.machine_walk``; about 2 s).

Every module of ``loader_model`` is imported first, so import-time code is not part of the
walk; the trial (9 km/h, full bucket, skyhook, seed 1, the whole course) then runs in this fresh
process, with nothing resolved yet, under :func:`sys.setprofile`. Printed: the distinct
``loader_model`` modules whose functions run, the calls of the look-ups by name
(``machines.machine``, ``machines.resolve_machine_name``, ``plant.layout.plant_layout``) with
their callers, and the modules whose functions receive the machine as a name (a local
``machine``, ``name`` or ``source`` equal to ``"skid_steer"``).
"""

from __future__ import annotations

import collections
import importlib
import pkgutil
import sys
from types import FrameType
from typing import Any

import loader_model

LOOKUPS = {
    ("loader_model.machines", "machine"),
    ("loader_model.machines", "resolve_machine_name"),
    ("loader_model.plant.layout", "plant_layout"),
}
_INSIDE = ("loader_model.machines", "loader_model.plant.layout")


def walk() -> dict[str, Any]:
    """Run the trial under the profiler; return the counts (module notes)."""
    for item in pkgutil.walk_packages(loader_model.__path__, "loader_model."):
        if not item.name.startswith(("loader_model.cli", "loader_model.commands")):
            importlib.import_module(item.name)
    from loader_model.experiments import trials

    modules: collections.Counter[str] = collections.Counter()
    lookups: collections.Counter[str] = collections.Counter()
    callers: collections.Counter[str] = collections.Counter()
    carriers: collections.Counter[str] = collections.Counter()

    def profile(frame: FrameType, event: str, _: Any) -> None:
        module = frame.f_globals.get("__name__", "")
        if event != "call" or not module.startswith("loader_model"):
            return
        if frame.f_code.co_name == "<module>":
            return
        modules[module] += 1
        if any(frame.f_locals.get(v) == "skid_steer" for v in ("machine", "name", "source")):
            carriers[module] += 1
        if (module, frame.f_code.co_name) in LOOKUPS:
            lookups[f"{module}.{frame.f_code.co_name}"] += 1
            caller = frame.f_back
            while caller is not None and caller.f_globals.get("__name__") in _INSIDE:
                caller = caller.f_back
            if caller is not None:
                callers[f"{caller.f_globals.get('__name__')}.{caller.f_code.co_name}"] += 1

    spec = trials.trial_specs(1, 1, speeds_kmh=(9.0,), loads=("full",), controllers=("skyhook",))
    sys.setprofile(profile)
    try:
        outcome = trials.run_trial(spec[0])
    finally:
        sys.setprofile(None)
    return {
        "a_total_m_s2": outcome.a_total_m_s2,
        "modules": dict(sorted(modules.items())),
        "lookups": dict(lookups),
        "callers": dict(callers),
        "carriers": dict(carriers),
    }


def main() -> None:
    """Print the walk."""
    found = walk()
    print(f"a_total {found['a_total_m_s2']!r} m/s²")
    print(f"{len(found['modules'])} modules run:")
    for name, count in found["modules"].items():
        print(f"  {name} ({count} calls)")
    print(f"look-ups by name: {sum(found['lookups'].values())} {found['lookups']}")
    print(f"  from {found['callers']}")
    print(f"modules given the machine as a name: {len(found['carriers'])} {found['carriers']}")


if __name__ == "__main__":
    main()
