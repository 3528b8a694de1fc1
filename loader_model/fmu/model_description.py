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


def _variable(parent: ET.Element, variable: FmuVariable) -> None:
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
    if variable.derivative is not None:
        real["derivative"] = str(variable.derivative)
    if variable.nominal is not None:
        real["nominal"] = _number(variable.nominal)
    if variable.start is not None:
        real["start"] = _number(variable.start)
    ET.SubElement(element, "Real", real)


def model_description_xml(
    variables: Sequence[FmuVariable], guid: str, description: str, generation_tool: str
) -> bytes:
    """The modelDescription.xml (UTF-8 bytes) of a Model Exchange FMU with these Real variables.

    Parameters
    ----------
    variables : sequence of FmuVariable
        Every Real variable in value-reference order (:func:`~loader_model.fmu.variables.
        fmu_variables`); the Boolean ``start_at_equilibrium`` is appended after them.
    guid : str
        The GUID the wrapper checks in ``fmi2Instantiate``.
    description, generation_tool : str
        Free text for the root element.
    """
    states = [v for v in variables if v.derivative is not None]
    root = ET.Element(
        "fmiModelDescription",
        {
            "fmiVersion": "2.0",
            "modelName": "loader_plant",
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
            "modelIdentifier": MODEL_IDENTIFIER,
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
        _variable(model_variables, variable)
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
    index = {v.value_reference: i + 1 for i, v in enumerate(variables)}
    structure = ET.SubElement(root, "ModelStructure")
    outputs = ET.SubElement(structure, "Outputs")
    for variable in variables:
        if variable.causality == "output":
            ET.SubElement(outputs, "Unknown", {"index": str(index[variable.value_reference])})
    derivatives = ET.SubElement(structure, "Derivatives")
    for variable in states:
        ET.SubElement(derivatives, "Unknown", {"index": str(index[variable.value_reference])})
    initial = ET.SubElement(structure, "InitialUnknowns")
    for variable in variables:
        if variable.causality in ("output", "local"):  # states (approx), derivatives, outputs
            ET.SubElement(initial, "Unknown", {"index": str(index[variable.value_reference])})
    ET.indent(root)
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"
