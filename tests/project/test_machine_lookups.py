"""Below the command line, a machine travels as its resolved object, never as a name.

The command line (``loader_model/commands/``, ``loader_model/cli.py``) and a short list of public
entry points resolve a machine name or description file once
(:func:`~loader_model.plant.layout.plant_layout`); everything else takes the resolved
:class:`~loader_model.plant.layout.PlantLayout` (or its
:class:`~loader_model.machines.MachineInfo`) or reads it from the scenario. This test scans the
source of ``loader_model/`` (its syntax tree, no import) and fails on

- a parameter named ``machine`` (or ``machine_name``) whose annotation admits a ``str``
  (``str``, ``str | None``, ``MachineSource``), and
- a call of a name look-up: ``plant_layout``, ``resolve_layout``, ``resolve_machine_name`` or
  the registry's ``machine`` (under whatever name it is imported, or through its module),

outside :data:`ALLOWED`, each of whose entries says why it may. An entry that no longer matches
anything fails too, so the list only shrinks.
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "loader_model"
#: Folders and modules of the command line, where a name becomes a machine.
COMMAND_LAYER = ("commands/", "cli.py")
#: The look-ups: (module they are imported from, name).
LOOKUPS = {
    ("loader_model.plant.layout", "plant_layout"),
    ("loader_model.plant.layout", "resolve_layout"),
    ("loader_model.machines", "resolve_machine_name"),
    ("loader_model.machines", "machine"),
}
#: Look-ups also caught when called through their module (``layout.plant_layout(...)``).
QUALIFIED = ("plant_layout", "resolve_layout", "resolve_machine_name")
#: Annotations that admit a machine name.
NAME_TYPES = ("str", "MachineSource")

#: (module path below loader_model/, function qualname or "<module>") -> why it may.
ALLOWED: dict[tuple[str, str], str] = {
    # the registry and the layout: where the look-ups are defined
    ("machines.py", "machine"): "the registry's look-up by name or file",
    ("plant/layout.py", "plant_layout"): "the look-up by name itself",
    ("plant/layout.py", "resolve_layout"): "the one conversion of the public entry points",
    ("plant/layout.py", "<module>"): "SKID_STEER, the default layout, resolved once at import",
    # documented public entry points (docs/guide) that take a layout, a name or a file
    ("plant/scenario.py", "resolve_plant"): "public entry point (guide: machines, simulation)",
    ("plant/scenario.py", "PlantScenario.from_vector"): "public entry point (guide: machines)",
    ("plant/plant.py", "plant_function"): "public entry point (guide: machines)",
    ("plant/equilibrium.py", "static_state"): "public entry point (guide: machines)",
    ("plant/linear.py", "linearise_plant"): "public entry point (guide: machines)",
    ("plant/linear.py", "undamped_matrices_from_plant"): "public entry point (guide: machines)",
    ("plant/energy.py", "energy_function"): "public entry point (guide: machines)",
    ("simulation/scenario.py", "resolve_scenario"): "public entry point (guide: simulation)",
    ("simulation/reference.py", "reference_simulation"): "public entry point (guide: machines)",
    ("simulation/energy_balance.py", "reference_energy_balance"): "public entry point (guide)",
    ("simulation/energy_balance.py", "simulated_energy_balance"): "public entry point (guide)",
    ("fmu/build.py", "export_plant_fmu"): "public entry point (guide: FMU export)",
    ("fmu/crosscheck.py", "cross_check"): "public entry point (guide: machines)",
    ("vehicle/dynamics.py", "LoaderDynamics.__init__"): "public model class (guide: machines)",
    ("vehicle/dynamics.py", "LoaderDynamics.from_parameters"): "public model class",
    ("vehicle/dynamics.py", "_machine"): "LoaderDynamics' conversion of a name or file",
    # files that name their machine: resolved once when the file is read
    ("robustness/machine_study.py", "study_machine"): "checks [study] machine of a study file",
    ("robustness/study.py", "_build"): "resolves a study file's machine once",
    ("robustness/study.py", "Study.__post_init__"): "a Study made without its layout",
    ("experiments/design_check/runs.py", "Design.__post_init__"): "a Design made by name",
    # reports and studies still driven by a name (a public function of each)
    ("experiments/machine_report.py", "machine_rows"): "report section: resolves once",
    ("experiments/machine_report.py", "machine_section"): "report section: the name as text",
    ("experiments/course_refinement.py", "course_cost"): "public entry point (guide: machines)",
    ("experiments/course_refinement.py", "refine_on_course"): "public entry point (guide)",
    ("robustness/machine_study.py", "study_params"): "checks [study] params against the name",
}


def _annotation_admits_name(annotation: ast.expr | None) -> bool:
    if annotation is None:
        return False
    names = {node.id for node in ast.walk(annotation) if isinstance(node, ast.Name)}
    text = ast.unparse(annotation)
    return bool(names & set(NAME_TYPES)) or any(t in text for t in NAME_TYPES)


def _lookup_names(tree: ast.AST) -> set[str]:
    """The local names of the look-ups imported anywhere in a module (aliases included)."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            for alias in node.names:
                if (node.module, alias.name) in LOOKUPS:
                    found.add(alias.asname or alias.name)
    return found


def scan(source: str) -> list[tuple[str, int, str]]:
    """(function qualname or "<module>", line, what) of every name parameter and look-up call."""
    tree = ast.parse(source)
    lookups = _lookup_names(tree)
    found: list[tuple[str, int, str]] = []

    def visit(node: ast.AST, scope: list[str]) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
                inner = [*scope, child.name]
                if not isinstance(child, ast.ClassDef):
                    arguments = child.args
                    every = [*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs]
                    for argument in every:
                        if argument.arg in ("machine", "machine_name") and (
                            _annotation_admits_name(argument.annotation)
                        ):
                            what = f"parameter {argument.arg}: {ast.unparse(argument.annotation)}"
                            found.append((".".join(inner), child.lineno, what))
                visit(child, inner)
                continue
            if isinstance(child, ast.Call):
                called = child.func
                name = called.id if isinstance(called, ast.Name) else None
                if isinstance(called, ast.Attribute) and called.attr in QUALIFIED:
                    name = ast.unparse(called)
                if name in lookups or (name is not None and name.endswith(QUALIFIED)):
                    where = ".".join(scope) or "<module>"
                    found.append((where, child.lineno, f"call {name}(...)"))
            visit(child, scope)

    visit(tree, [])
    return found


@functools.cache
def _violations() -> tuple[list[str], set[tuple[str, str]]]:
    problems, used = [], set()
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE).as_posix()
        if relative.startswith(COMMAND_LAYER):
            continue
        for where, line, what in scan(path.read_text(encoding="utf-8")):
            key = (relative, where)
            if key in ALLOWED:
                used.add(key)
            else:
                problems.append(f"loader_model/{relative}:{line} {where}: {what}")
    return problems, used


def test_no_machine_name_below_the_command_line() -> None:
    problems, _ = _violations()
    assert not problems, (
        "a machine name below the command line (take the PlantLayout, or read "
        "scenario.layout; a public entry point goes into ALLOWED with its reason):\n"
        + "\n".join(problems)
    )


def test_every_allowed_entry_is_still_needed() -> None:
    _, used = _violations()
    stale = sorted(set(ALLOWED) - used)
    assert not stale, f"ALLOWED entries that match nothing (remove them): {stale}"


def test_the_scan_finds_a_name_parameter_and_a_look_up() -> None:
    source = (
        "from loader_model.plant.layout import plant_layout as layout_of\n"
        "from loader_model.machines import machine\n"
        "def f(params, machine: str = 'skid_steer'):\n"
        "    return layout_of(machine).state_names\n"
        "class C:\n"
        "    def g(self, machine: 'str | None' = None):\n"
        "        return machine('skid_steer')\n"
        "def h(layout: PlantLayout):\n"
        "    return layout.machine.name\n"
        "def k():\n"
        "    import loader_model.plant.layout as where\n"
        "    return where.plant_layout('skid_steer')\n"
    )
    assert scan(source) == [
        ("f", 3, "parameter machine: str"),
        ("f", 4, "call layout_of(...)"),
        ("C.g", 6, "parameter machine: 'str | None'"),
        ("C.g", 7, "call machine(...)"),
        ("k", 12, "call where.plant_layout(...)"),
    ]
