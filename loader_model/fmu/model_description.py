"""The FMI 2.0 ``modelDescription.xml`` of the plant FMU (Model Exchange only)."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Sequence

from loader_model.fmu.variables import FmuVariable

__all__ = ["MODEL_IDENTIFIER", "model_description_xml"]

#: Name of the shared library in ``binaries/<platform>/`` and prefix of nothing else.
MODEL_IDENTIFIER = "loader_plant"


def _number(value: float) -> str:
    return repr(float(value))


def _variable(parent: ET.Element, variable: FmuVariable, index: dict[str, int]) -> None:
    attributes = {
        "name": variable.name,
        "valueReference": str(variable.value_reference),
        "description": variable.description,
        "causality": variable.causality,
        "variability": variable.variability,
    }
    if variable.initial:
        attributes["initial"] = variable.initial
    element = ET.SubElement(parent, "ScalarVariable", attributes)
    real: dict[str, str] = {}
    if variable.unit:
        real["unit"] = variable.unit
    if variable.derivative_of is not None:
        real["derivative"] = str(index[variable.derivative_of])
    if variable.nominal is not None:
        real["nominal"] = _number(variable.nominal)
    if variable.start is not None:
        real["start"] = _number(variable.start)
    ET.SubElement(element, "Real", real)


def model_description_xml(
    variables: Sequence[FmuVariable],
    guid: str,
    description: str,
    generation_tool: str,
    *,
    model_identifier: str = MODEL_IDENTIFIER,
) -> bytes:
    """The modelDescription.xml (UTF-8 bytes) of a Model Exchange FMU with these Real variables.

    Parameters
    ----------
    variables : sequence of FmuVariable
        Every Real variable, value references 0, 1, ... in this order (:func:`~loader_model.fmu.variables.
        fmu_variables`); the Boolean ``start_at_equilibrium`` is appended after them.
    guid : str
        The GUID the wrapper checks in ``fmi2Instantiate``.
    description, generation_tool : str
        Free text for the root element.
    model_identifier : str
        Name of the shared library, and the model's name.
    """
    states = [v for v in variables if v.derivative_of is not None]
    index = {v.name: i + 1 for i, v in enumerate(variables)}  # 1-based, as ModelStructure counts
    root = ET.Element(
        "fmiModelDescription",
        {
            "fmiVersion": "2.0",
            "modelName": model_identifier,
            "guid": guid,
            "description": description,
            "generationTool": generation_tool,
            "variableNamingConvention": "structured",
            "numberOfEventIndicators": "0",
        },
    )
    ET.SubElement(
        root,
        "ModelExchange",
        {
            "modelIdentifier": model_identifier,
            "canNotUseMemoryManagementFunctions": "true",
            "canGetAndSetFMUstate": "false",
        },
    )
    units = ET.SubElement(root, "UnitDefinitions")
    for unit in sorted({v.unit for v in variables if v.unit}):
        ET.SubElement(units, "Unit", {"name": unit})
    ET.SubElement(
        root, "DefaultExperiment", {"startTime": "0", "stopTime": "1", "tolerance": "1e-06"}
    )
    model_variables = ET.SubElement(root, "ModelVariables")
    for variable in variables:
        _variable(model_variables, variable, index)
    flag = ET.SubElement(
        model_variables,
        "ScalarVariable",
        {
            "name": "start_at_equilibrium",
            "valueReference": "0",
            "description": (
                "true: the states start at the static equilibrium of the parameters as set "
                "(overriding the states' start values); false: at the states' start values"
            ),
            "causality": "parameter",
            "variability": "fixed",
            "initial": "exact",
        },
    )
    ET.SubElement(flag, "Boolean", {"start": "true"})
    structure = ET.SubElement(root, "ModelStructure")
    outputs = ET.SubElement(structure, "Outputs")
    for variable in variables:
        if variable.causality == "output":
            ET.SubElement(outputs, "Unknown", {"index": str(index[variable.name])})
    derivatives = ET.SubElement(structure, "Derivatives")
    for variable in states:
        ET.SubElement(derivatives, "Unknown", {"index": str(index[variable.name])})
    initial = ET.SubElement(structure, "InitialUnknowns")
    for variable in variables:
        # outputs, states (initial approx) and derivatives; not the controller's discrete states
        if variable.causality == "output" or (
            variable.causality == "local" and variable.variability == "continuous"
        ):
            ET.SubElement(initial, "Unknown", {"index": str(index[variable.name])})
    ET.indent(root)
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"
