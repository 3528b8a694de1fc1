"""Every public function and class of the runtime packages has a docstring, and a function that
takes arguments documents them in a numpydoc ``Parameters`` section (issue 24).

The packages checked are those with an ``__all__`` (vehicle, plant, modal, fmu, experiments,
commands and io have none yet). The Parameters rule does not hold everywhere today:
``MISSING_PARAMETERS`` lists the public functions that lack the section (46 when this test was
written), so that no new one is added without it; a name leaves the list when its docstring gets
the section (the test fails while a listed name already has it).
"""

from __future__ import annotations

import importlib
import inspect

import pytest

PACKAGES = (
    "parameters",
    "vehicle",
    "plant",
    "modal",
    "control",
    "simulation",
    "identification",
    "fmu",
    "experiments",
    "robustness",
    "commands",
    "iso2631",
    "io",
)
MISSING_PARAMETERS = {
    "parameters": {
        "combine_bodies",
        "load_bucket_load",
        "load_loader",
        "model_parameter_values",
        "resolve_loader_and_load",
        "save",
        "validate",
    },
    "control": {
        "controller_state_names",
        "h2_costs",
        "load_settings",
        "sensor_signals",
        "settings_vector_for_plant",
    },
    "simulation": {
        "classify_psd",
        "displacement_psd",
        "edge_contact_length",
        "estimate_psd",
        "flat_road",
        "iso8608_course",
        "kmh_to_m_s",
        "profile_variance",
        "single_board",
        "single_obstacle_course",
        "write_road_csv",
    },
    "identification": {
        "identify_friction",
        "identify_leakage",
        "prepare_signals",
        "read_measurement_csv",
        "write_measurement_csv",
    },
    "robustness": {"load_study"},
    "iso2631": {
        "assess_directive_2002_44",
        "axis_unit",
        "check_axis_name",
        "check_weighting_name",
        "crest_factor",
        "daily_vibration_dose_value",
        "directive_status",
        "estimated_vibration_dose_value",
        "format_evaluation",
        "health_assessment",
        "maximum_transient_vibration_value",
        "settling_time_s",
        "vibration_dose_value",
        "weighting_abcd",
        "weighting_num_den",
        "weighting_state_space",
        "weighting_transfer_function",
    },
}


def public_callables(package: str) -> dict[str, object]:
    """The functions and classes named in ``loader_model.<package>.__all__`` (none without it)."""
    module = importlib.import_module(f"loader_model.{package}")
    names = getattr(module, "__all__", ())
    objects = {name: getattr(module, name) for name in names}
    return {n: o for n, o in objects.items() if inspect.isfunction(o) or inspect.isclass(o)}


def has_parameters_section(function) -> bool:
    arguments = [p for p in inspect.signature(function).parameters if p not in ("self", "cls")]
    return not arguments or "Parameters\n----------" in (inspect.getdoc(function) or "")


def test_missing_parameters_names_are_public():
    for package, names in MISSING_PARAMETERS.items():
        assert names <= set(public_callables(package)), package


@pytest.mark.parametrize("package", PACKAGES)
def test_public_callables_have_docstrings(package):
    undocumented = [
        n for n, o in public_callables(package).items() if not (o.__doc__ or "").strip()
    ]
    assert not undocumented, f"loader_model.{package}: no docstring: {undocumented}"


@pytest.mark.parametrize("package", PACKAGES)
def test_public_functions_document_their_parameters(package):
    functions = {n: o for n, o in public_callables(package).items() if inspect.isfunction(o)}
    lacking = {n for n, f in functions.items() if not has_parameters_section(f)}
    allowed = MISSING_PARAMETERS.get(package, set())
    assert not lacking - allowed, (
        f"loader_model.{package}: no Parameters section: {lacking - allowed}"
    )
    assert not allowed - lacking, (
        f"loader_model.{package}: now documented, remove from MISSING_PARAMETERS: "
        f"{allowed - lacking}"
    )


def test_parameters_rule_detects_a_missing_section():
    def documented(x):
        """Do.

        Parameters
        ----------
        x : int
            A number.
        """

    def undocumented(x):
        """Do."""

    def no_arguments():
        """Do."""

    assert has_parameters_section(documented)
    assert not has_parameters_section(undocumented)
    assert has_parameters_section(no_arguments)
