r"""Ride-comfort gain design: K_fb minimising a_total² of Eq. 50 over both bucket loads.

Design plant per load (:mod:`~loader_model.control.comfort_plant`): the detailed linearised plant,
the skyhook's continuous structure with K_fb as the static gain, the ISO 2631-1 weightings on the
seat outputs and an ISO 8608 road (:mod:`~loader_model.control.road_filter`). The cost is

.. math:: J(K) = \sum_{load} a_{total}^2 = \sum_{load} \| T_{\nu \to (k_x W_d f_{Sx},\,
          k_y W_k f_{Sy},\, k_\theta W_e \ddot\theta_1)} \|_{H_2}^2,

the mean square of the weighted seat accelerations under the road (Eq. 49, 50), subject to every
closed-loop pole left of −σ and the r.m.s. limits 3 σ_Vp ≤ V_p,max and 3 σ_pA ≤ ‖p_A‖∞ (the
pressure norm of the load: 100 / 200 bar) for each load. Minimised by
:func:`~loader_model.control.feasible_descent.minimise_certified` (every iterate certified) or,
with ``solver="ipopt"``, by IPOPT through CasADi on the same barrier cost
(:mod:`~loader_model.control.comfort_ipopt`).
Compared with Table 3 and with the output-feedback LQR (Eq. 41, 42) on the same plant, with
Q = C_zᵀ C_z (the weighted seat outputs), R = ``lqr_effort`` and X0 = B_w B_wᵀ.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from loader_model.control._checks import finite_matrix, gain_mask, symmetric_matrix
from loader_model.control.comfort_plant import (
    FIXED_STATES,
    MEASURED,
    PERFORMANCE,
    comfort_case,
    comfort_system,
)
from loader_model.control.design_plant import DesignPlant
from loader_model.control.feasible_descent import (
    balanced_plant,
    minimise_certified,
    reach_margin,
)
from loader_model.control.h2_cost import closed_loop, h2_costs

if TYPE_CHECKING:
    from loader_model.plant.scenario import PlantScenario

__all__ = [
    "DEFAULT_MARGIN",
    "TABLE3_GAIN",
    "TABLE3_PRINTED_GAIN",
    "GainEvaluation",
    "comfort_plants",
    "evaluate_gain",
    "lqr_gain",
    "optimise_gain",
]

#: K_fb of Table 3 as printed: k_φ = −0.22 leaves a real pole at about +0.05 rad/s on the model
#: (errata 12), reported as an unstable variant.
TABLE3_PRINTED_GAIN = np.array([[2.75, 5.10, -4.0, -0.22]])
#: K_fb of Table 3 with k_φ's sign corrected (errata 12): the high-passed pressure loop makes the
#: φ term an integral position loop, stable only for k_φ > 0; the paper's own design route
#: (output-feedback LQR, Eq. 41-43) gives k_φ > 0 and Table 3's signs of the velocity gains.
TABLE3_GAIN = np.array([[2.75, 5.10, -4.0, 0.22]])
#: Required stability margin σ [rad/s]: below the road filter's fixed pole 2π n_1 v (0.17 rad/s
#: at 9 km/h) and the slow boom pole, a 10 s time constant.
DEFAULT_MARGIN = 0.1


@dataclass(frozen=True)
class GainEvaluation:
    """One gain on one load: a_total [m/s²] (inf if unstable), poles, margin, r.m.s. values.

    ``poles``: all closed-loop poles; ``loop_poles``: those of the plant and skyhook only (the
    road and weighting filters are in cascade, their poles do not move with K); ``margin`` is
    min(−Re) over all poles, ``loop_margin`` over the loop poles, ``min_damping`` over the loop.
    """

    load: str
    a_total: float
    poles: np.ndarray
    loop_poles: np.ndarray
    margin: float
    loop_margin: float
    min_damping: float
    v_p_rms: float
    p_a_rms: float
    within_limits: bool


def comfort_plants(
    loads: Sequence[str] = ("empty", "full"),
    road_class: str = "C",
    speed_kmh: float = 9.0,
    params: dict[str, np.ndarray | PlantScenario] | None = None,
) -> tuple[DesignPlant, ...]:
    """Balanced :class:`DesignPlant` per load with the V_p and p_A r.m.s. limits (3 σ rule);
    ``params``: plant parameter vector or resolved plant per load
    (:func:`~loader_model.control.comfort_plant.comfort_case`), default the shipped loader's."""
    plants = []
    for load in loads:
        case = comfort_case(load, None if params is None else params.get(load))
        system = comfort_system(case, road_class, speed_kmh / 3.6)
        names = case.layout.parameter_names
        v_max = float(case.params[names.index(case.layout.command_limit)])
        p_norm = case.pressure_norm
        plant = DesignPlant.from_statespace(
            system,
            control=["p_ref_n"],
            noise=[n for n in system.input_labels if n.startswith("nu_")],
            measured=list(MEASURED),
            performance=list(PERFORMANCE),
            rms_limits={"V_p": v_max / 3.0, "p_A": p_norm / 3.0},
            name=load,
        )
        plants.append(balanced_plant(plant))
    return tuple(plants)


def evaluate_gain(plants: Sequence[DesignPlant], gain: Any) -> tuple[GainEvaluation, ...]:
    """a_total, poles, margin min(−Re λ), smallest damping ratio and r.m.s. values per plant."""
    gain = np.atleast_2d(np.asarray(gain, dtype=float))
    check = h2_costs(plants, gain)
    rows = []
    for plant, cost, poles, e_rms in zip(
        plants, check["costs"], check["poles"], check["e_rms"], strict=True
    ):
        n_loop = plant.A.shape[0] - FIXED_STATES
        loop = np.linalg.eigvals(closed_loop(plant, gain)[0][:n_loop, :n_loop])
        damping = -loop.real / np.maximum(np.abs(loop), 1e-300)
        limits = np.asarray(plant.e_rms_limits)
        rows.append(
            GainEvaluation(
                load=plant.name,
                a_total=float(np.sqrt(cost / plant.weight)) if np.isfinite(cost) else np.inf,
                poles=poles,
                loop_poles=loop,
                margin=float(-np.max(poles.real)),
                loop_margin=float(-np.max(loop.real)),
                min_damping=float(np.min(damping)),
                v_p_rms=float(e_rms[0]),
                p_a_rms=float(e_rms[1]),
                within_limits=bool(np.all(e_rms <= limits * (1 + 1e-9))),
            )
        )
    return tuple(rows)


def lqr_gain(plant: DesignPlant, effort: float = 1e-2) -> Any:
    """Output-feedback LQR (Eq. 41, 42) on one design plant: Q = C_zᵀ C_z, R = ``effort``,
    X0 = B_w B_wᵀ (so J_LQR = ½ (a_total² + R σ_r²)); returns the OutputFeedbackResult."""
    from loader_model.control.output_feedback import output_feedback_lqr

    return output_feedback_lqr(
        (plant.A, plant.B_u, plant.C_y),
        plant.C_z.T @ plant.C_z,
        np.array([[effort]]),
        plant.B_w @ plant.B_w.T,
        gain0=TABLE3_GAIN,
    )


def optimise_gain(
    plants: Sequence[DesignPlant],
    gain0: Any = None,
    *,
    margin: float = DEFAULT_MARGIN,
    max_iterations: int = 200,
    solver: str = "bfgs",
    mask: Any = None,
    effort: Any = None,
) -> dict[str, Any]:
    """Minimise Σ w_i J_i (a_total² on the comfort plants) with margin σ and the r.m.s. limits.

    The one entry point of the gain design: the start is moved into the σ-stable set if it
    misses it, then the certified descent or IPOPT minimises the H2 cost of
    :mod:`~loader_model.control.h2_cost` from its adjoint gradient.

    Parameters
    ----------
    plants : sequence of DesignPlant
        Design plants sharing the gain shape (m, p), e.g. :func:`comfort_plants`.
    gain0 : array_like, optional
        Start gain (m x p); default Table 3 (1 x 4). First moved to margin 1.5 σ + 0.01 by
        :func:`~loader_model.control.feasible_descent.reach_margin` if it misses it.
    margin : float
        σ ≥ 0 in rad/s: every pole of every closed loop left of −σ at every iterate.
    max_iterations : int
        Iteration limit of the solver.
    solver : {"bfgs", "ipopt"}
        ``"bfgs"``: :func:`~loader_model.control.feasible_descent.minimise_certified` (the
        default); ``"ipopt"``: :func:`~loader_model.control.comfort_ipopt.minimise_ipopt`,
        IPOPT through CasADi on the same Φ.
    mask : array_like of bool, optional
        m x p, True where a gain entry is free (default all); fixed entries keep gain0's value.
    effort : array_like, optional
        Effort weight R (m x m, ⪰ 0) of tr(R K C_y P C_yᵀ Kᵀ) in J (default 0).

    Returns
    -------
    dict
        The solver's dict (``gain``, ``cost``, ``iterations``, ``history``, ``converged``,
        ``status``, ``time_s``, ...) plus ``start`` and ``solver``.

    Raises
    ------
    ValueError
        For an unknown solver, malformed gain, mask or effort, a negative margin, a start that
        cannot be moved to the margin, or a start outside an r.m.s. limit.
    """
    if solver not in ("bfgs", "ipopt"):
        raise ValueError(f"solver {solver!r}: allowed: 'bfgs' or 'ipopt'")
    if not (np.isfinite(margin) and margin >= 0.0):
        raise ValueError(f"margin must be finite and >= 0; got {margin}")
    shape = plants[0].gain_shape
    start = finite_matrix("gain0", TABLE3_GAIN if gain0 is None else gain0, shape)
    mask = gain_mask(mask, shape)
    r = (
        np.zeros((shape[0],) * 2)
        if effort is None
        else symmetric_matrix("effort", effort, shape[0], definite=False)
    )
    start, failure = reach_margin(plants, start, mask, 1.5 * margin + 0.01)
    if failure is not None:
        raise ValueError(
            f"no start gain meets the margin {margin} rad/s: {failure['return_status']}"
        )
    if solver == "ipopt":
        from loader_model.control.comfort_ipopt import minimise_ipopt

        minimise = minimise_ipopt
    else:
        minimise = minimise_certified
    result = minimise(
        plants, start, mask=mask, effort=r, margin=margin, max_iterations=max_iterations
    )
    return {**result, "start": start, "solver": solver}
