"""FMU export of the nonlinear plant: FMI 2.0 Model Exchange, built from CasADi-generated C.

:func:`~loader_model.fmu.build.export_plant_fmu` writes the FMU;
:mod:`~loader_model.fmu.variables` names its variables; :mod:`~loader_model.fmu.model_description`
writes its ``modelDescription.xml``.
"""
