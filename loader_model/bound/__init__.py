"""The clairvoyant optimal-control bound: the best any pump command could do on a known course.

- :mod:`~loader_model.bound.weighting`: the seat's ISO 2631 weightings (Eq. 49, 50) as sampled
  linear filters built from the Annex A transfer functions.
- :mod:`~loader_model.bound.problem`: grid, road samples, pump, pressure and stroke limits.
- :mod:`~loader_model.bound.linear`: the non-causal LQ bound on the linearised plant (Riccati
  sweep; a sparse KKT solve as reference).
- :mod:`~loader_model.bound.nonlinear`: multiple shooting on the simulator's own step, IPOPT.
- :mod:`~loader_model.bound.replay`: a controller that plays a command table back, and the
  replay through the simulator.
"""
