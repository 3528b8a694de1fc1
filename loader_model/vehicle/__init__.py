"""The vehicle: the generated multibody model bound to a parameter set (paper section 2.1).

:mod:`~loader_model.vehicle.dynamics` (``LoaderDynamics``: forward dynamics and the linear model of
Eq. 38-40), :mod:`~loader_model.vehicle.cylinder` (lift-cylinder geometry, chamber volumes, Eq. 28,
30), :mod:`~loader_model.vehicle.statics` (the static equilibrium of a loader with a load, and the
checks that it stands), :mod:`~loader_model.vehicle.summary` (the model's text report). Imports
the parameters and the generated model only.
"""
