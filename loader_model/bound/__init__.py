"""The clairvoyant optimal-control bound: the best any pump command could do on a known course.

- :mod:`~loader_model.bound.weighting`: the seat's ISO 2631 weightings (Eq. 49, 50) as sampled
  linear filters built from the Annex A transfer functions.
- :mod:`~loader_model.bound.problem`: grid, road samples, pump, pressure and stroke limits.
- :mod:`~loader_model.bound.linear`: the non-causal LQ bound on the linearised plant (Riccati
  sweep; a sparse KKT solve as reference).
- :mod:`~loader_model.bound.condensed`: the LQ problem condensed onto the command values.
- :mod:`~loader_model.bound.dense_qp`: a dense primal-dual interior point for convex QPs.
- :mod:`~loader_model.bound.constrained`: the LQ bound with the pump's, pressure and stroke
  limits (constraint generation over every path sample).
- :mod:`~loader_model.bound.pump_sizing`: the constrained bound and a controller against pump
  size.
- :mod:`~loader_model.bound.preview`: LQ control with road preview on the linear bound's plant
  and cost; :mod:`~loader_model.bound.preview_report` runs it at 1 kHz and sweeps the preview.
- :mod:`~loader_model.bound.nonlinear`: the machine's bound, Gauss-Newton SQP in single shooting
  on the simulator's own period (:mod:`~loader_model.bound.trajectory`: rollout and exact
  linearisation; :mod:`~loader_model.bound.stage_model`: the Gauss-Newton QP in stage form;
  :mod:`~loader_model.bound.stage_form`: that QP's data and sweeps;
  :mod:`~loader_model.bound.riccati_qp`: its Riccati interior point).
- :mod:`~loader_model.bound.replay`: a controller that plays a command table back, and the
  replay through the simulator.
"""
