"""Modal analysis and the Table 1 calibration (paper section 2.2, Eq. 27-29).

:mod:`~loader_model.modal.undamped` takes the undamped M and K from the plant (one model),
:mod:`~loader_model.modal.modes` solves and compares the modes with Table 1,
:mod:`~loader_model.modal.report` prints them, :mod:`~loader_model.modal.calibration` and
:mod:`~loader_model.modal.table1` fit the least-known parameters to Table 1.
"""
