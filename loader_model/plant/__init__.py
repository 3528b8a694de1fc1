"""The plant: generated multibody model, hydraulic drive and pump as one CasADi Function.

:func:`~loader_model.plant.plant.plant_function` (dynamics and outputs),
:func:`~loader_model.plant.equilibrium.equilibrium_function` (static state),
:mod:`~loader_model.plant.linear` (AD linearisation as python-control ``StateSpace``).
"""
