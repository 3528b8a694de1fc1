r"""The one entry point of the skyhook gain design on linear plants (paper section 3.2).

:func:`design_gains` takes design plants (:func:`~loader_model.control.comfort_design.comfort_plants`:
the linearised plant with the skyhook's filters, a road filter and the ISO 2631-1 weightings, one
per bucket load) and a method:

- ``"lqr"``: the output-feedback LQR of Eq. 41, 42 on each plant alone
  (:func:`~loader_model.control.comfort_design.lqr_gain`: Q = C_zᵀ C_z, R = ``lqr_effort``,
  X0 = B_w B_wᵀ), the paper's design route; one gain per plant.
- ``"optimise"``: one gain for all plants minimising Σ a_total² (Eq. 50) with every pole left of
  −σ and the r.m.s. limits (:func:`~loader_model.control.comfort_design.optimise_gain`), by the
  certified BFGS (``solver="bfgs"``) or IPOPT through CasADi (``solver="ipopt"``), both on the
  adjoint gradient.

A third route needs the nonlinear simulator and so sits above this layer:
:func:`loader_model.experiments.course_refinement.refine_on_course` refines the ``"optimise"``
result on the paper's course. The Gramian IPOPT design that carried the Lyapunov solution as
unknowns is retired (:mod:`~loader_model.control.feasible_descent` says why).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from loader_model.control.design_plant import DesignPlant

__all__ = ["DESIGN_METHODS", "GainDesign", "design_gains"]

#: The methods of :func:`design_gains`.
DESIGN_METHODS = ("lqr", "optimise")


@dataclass(frozen=True)
class GainDesign:
    """Result of :func:`design_gains`.

    ``gains`` maps each plant's name to its K_fb (1 x 4): the same gain for every plant with
    ``"optimise"``, each plant's own with ``"lqr"``. ``details`` is the solver's own record
    (the dict of ``optimise_gain``, or the ``OutputFeedbackResult`` per plant).
    """

    method: str
    gains: dict[str, np.ndarray]
    converged: bool
    summary: str
    details: Any = field(repr=False, default=None)

    @property
    def gain(self) -> np.ndarray:
        """The one gain of an ``"optimise"`` design, or of a single-plant ``"lqr"`` design."""
        distinct = {tuple(g.ravel()) for g in self.gains.values()}
        if len(distinct) != 1:
            raise ValueError(
                f"the {self.method!r} design has one gain per plant ({', '.join(self.gains)}); "
                "pick one from .gains"
            )
        return next(iter(self.gains.values()))


def design_gains(
    plants: Sequence[DesignPlant],
    method: str = "optimise",
    *,
    solver: str = "bfgs",
    gain0: Any = None,
    margin: float | None = None,
    max_iterations: int = 200,
    lqr_effort: float = 1e-2,
) -> GainDesign:
    """Design K_fb of the skyhook (u = −K y) on linear design plants.

    Parameters
    ----------
    plants : sequence of DesignPlant
        One per bucket load (their ``name`` keys the result).
    method : {"lqr", "optimise"}
        See the module notes.
    solver : {"bfgs", "ipopt"}
        Solver of ``"optimise"``.
    gain0 : array_like, optional
        Start of ``"optimise"`` (default Table 3, moved into the σ-stable set if it misses it).
    margin : float, optional
        σ in rad/s for ``"optimise"`` (default
        :data:`~loader_model.control.comfort_design.DEFAULT_MARGIN`).
    max_iterations : int
        Iteration limit of ``"optimise"``.
    lqr_effort : float
        R of ``"lqr"`` (normalised command).

    Returns
    -------
    GainDesign

    Raises
    ------
    ValueError
        For an unknown method or solver, no plants, or a design that cannot start (see
        :func:`~loader_model.control.comfort_design.optimise_gain`).
    """
    from loader_model.control.comfort_design import DEFAULT_MARGIN, lqr_gain, optimise_gain

    if method not in DESIGN_METHODS:
        raise ValueError(f"method {method!r}: allowed: {', '.join(map(repr, DESIGN_METHODS))}")
    plants = list(plants)
    if not plants:
        raise ValueError("plants: allowed: at least one design plant; got none")
    if method == "lqr":
        results = {p.name: lqr_gain(p, lqr_effort) for p in plants}
        return GainDesign(
            method=method,
            gains={name: np.asarray(r.gain, dtype=float) for name, r in results.items()},
            converged=all(r.converged for r in results.values()),
            summary=f"output-feedback LQR per plant, Q = C_zᵀC_z, R = {lqr_effort:g}, "
            "X0 = B_w B_wᵀ",
            details=results,
        )
    result = optimise_gain(
        plants,
        gain0,
        margin=DEFAULT_MARGIN if margin is None else margin,
        max_iterations=max_iterations,
        solver=solver,
    )
    gain = np.asarray(result["gain"], dtype=float)
    return GainDesign(
        method=method,
        gains={p.name: gain for p in plants},
        converged=bool(result["converged"]),
        summary=f"{solver}: {result['iterations']} iterations, {result['time_s']:.2f} s, "
        f"{result['status']}",
        details=result,
    )
