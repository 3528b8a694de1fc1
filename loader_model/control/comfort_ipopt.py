r"""The ride-comfort gain optimisation solved by IPOPT through CasADi, unknowns = the free gains.

Same problem as :func:`~loader_model.control.feasible_descent.minimise_certified`: minimise

.. math::

    \Phi(k) = \frac{J(K)}{J(K_0)} - \mu \sum_{i,j} \log\Big(1 - \frac{e_{rms,ij}^2}{\bar e_{ij}^2}\Big)
    \quad \text{over} \quad \mathcal{S}_\sigma = \{k : \max \operatorname{Re} \lambda(A_{c,i}) < -\sigma
    \ \forall i\},

J the summed H2 cost (a_total² of Eq. 50 per load with the ISO weightings in the loop), the log
barrier keeping the r.m.s. limits. Φ is a ``casadi.Callback`` of the free gains k (scipy
Lyapunov solutions inside); its exact gradient, from the adjoint Lyapunov equations
(:func:`~loader_model.control.feasible_descent.cost_and_gradient`), is the Callback's Jacobian
(``has_jacobian`` / ``get_jacobian``); value and gradient are computed together and cached per k.
IPOPT runs with ``hessian_approximation = limited-memory`` (L-BFGS, 20 pairs kept); the unknowns
are 4 numbers, not the 2 964 Gramian and certificate entries of the retired Gramian design
(:mod:`~loader_model.control.feasible_descent` says why it was retired).

Stability during the solve: outside :math:`\mathcal{S}_\sigma` (or outside an r.m.s. limit) the
Callback returns Φ = +inf. CasADi's NLP oracle reports a non-finite output as a failed
evaluation ("Inf detected for output f"), ``eval_f`` returns false to IPOPT, and IPOPT's
line search cuts the step back ("Cutting back alpha due to evaluation error") instead of
accepting the point — measured on a toy problem and on the loader plants. An IPOPT iterate is
a trial point whose Φ was finite, so every iterate, and hence the returned point, is σ-stable and
inside the limits: IPOPT cannot end at a stationary point outside :math:`\mathcal{S}_\sigma`
(nor does it need the gradient there). The start must be in the set (IPOPT stops at once if the
first evaluation fails). An ``iteration_callback`` records every IPOPT iterate; after the solve
the margin is recomputed with numpy eigenvalues at each of them and at the result.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Any

import casadi as ca
import numpy as np

from loader_model.control.design_plant import DesignPlant
from loader_model.control.feasible_descent import BarrierObjective, _margin

__all__ = ["comfort_phi", "minimise_ipopt"]


class _Phi(ca.Callback):
    """Φ(k) as a CasADi Function of the free gains; +inf outside the certified set."""

    def __init__(self, objective: BarrierObjective, gain0: np.ndarray, free: np.ndarray) -> None:
        ca.Callback.__init__(self)
        self.objective, self.gain0, self.free = objective, gain0, free
        self.cache: dict[bytes, tuple[float, np.ndarray] | None] = {}
        self.costs: dict[bytes, float] = {}  # J at every point evaluated inside the set
        self.evaluations = self.rejected = 0
        self.jacobian: ca.Callback | None = None
        self.construct("comfort_phi", {})

    def get_n_in(self) -> int:
        return 1

    def get_n_out(self) -> int:
        return 1

    def get_name_in(self, i: int) -> str:
        return "k"

    def get_name_out(self, i: int) -> str:
        return "phi"

    def get_sparsity_in(self, i: int) -> ca.Sparsity:
        return ca.Sparsity.dense(int(self.free.sum()), 1)

    def gain(self, k: np.ndarray) -> np.ndarray:
        """The full gain matrix with the free entries (row-major) set to ``k``."""
        flat = self.gain0.ravel().copy()
        flat[self.free] = k
        return flat.reshape(self.gain0.shape)

    def value(self, k: Any) -> tuple[float, np.ndarray] | None:
        """(Φ, ∂Φ/∂k) at k, or None outside the set; one evaluation per distinct k."""
        k = np.asarray(k, dtype=float).ravel()
        key = k.tobytes()
        if key not in self.cache:
            self.evaluations += 1
            result = self.objective(self.gain(k))
            self.rejected += result is None
            self.cache = {key: None if result is None else (result[0], result[1][self.free])}
            if result is not None:
                self.costs[key] = result[2]
        return self.cache[key]

    def eval(self, arg: list) -> list:
        result = self.value(arg[0])
        return [np.inf if result is None else result[0]]

    def has_jacobian(self) -> bool:
        return True

    def get_jacobian(self, name: str, inames: list, onames: list, opts: dict) -> ca.Callback:
        self.jacobian = _Gradient(name, self)
        return self.jacobian


class _Gradient(ca.Callback):
    """∂Φ/∂k (1 x n) from the cache of :class:`_Phi`; inputs k and the nominal Φ."""

    def __init__(self, name: str, phi: _Phi) -> None:
        ca.Callback.__init__(self)
        self.phi = phi
        self.construct(name, {})

    def get_n_in(self) -> int:
        return 2

    def get_n_out(self) -> int:
        return 1

    def get_sparsity_in(self, i: int) -> ca.Sparsity:
        return ca.Sparsity.dense(int(self.phi.free.sum()), 1) if i == 0 else ca.Sparsity.dense(1)

    def get_sparsity_out(self, i: int) -> ca.Sparsity:
        return ca.Sparsity.dense(1, int(self.phi.free.sum()))

    def eval(self, arg: list) -> list:
        result = self.phi.value(arg[0])
        n = int(self.phi.free.sum())
        return [np.full((1, n), np.nan) if result is None else result[1][None, :]]


class _Recorder(ca.Callback):
    """IPOPT iteration callback: keeps x and Φ of every iterate."""

    def __init__(self, n: int) -> None:
        ca.Callback.__init__(self)
        self.n, self.iterates, self.values = n, [], []
        self.construct("comfort_iterates", {})

    def get_n_in(self) -> int:
        return ca.nlpsol_n_out()

    def get_n_out(self) -> int:
        return 1

    def get_name_in(self, i: int) -> str:
        return ca.nlpsol_out(i)

    def get_sparsity_in(self, i: int) -> ca.Sparsity:
        name = ca.nlpsol_out(i)
        if name in ("x", "lam_x"):
            return ca.Sparsity.dense(self.n, 1)
        return ca.Sparsity.dense(1, 1) if name == "f" else ca.Sparsity(0, 1)

    def eval(self, arg: list) -> list:
        self.iterates.append(np.asarray(arg[0], dtype=float).ravel().copy())
        self.values.append(float(arg[ca.nlpsol_out().index("f")]))
        return [0]


def comfort_phi(
    plants: Sequence[DesignPlant],
    gain0: np.ndarray,
    *,
    mask: np.ndarray,
    effort: np.ndarray,
    margin: float,
    mu: float = 1e-4,
) -> ca.Callback:
    """Φ of the module docstring as a CasADi Function ``comfort_phi(k) -> phi`` of the free gains.

    J is normalised by J(``gain0``); the entries of ``gain0`` outside ``mask`` stay fixed.
    Differentiable in CasADi (``ca.jacobian`` or ``ca.gradient`` of a call) by the adjoint
    gradient; +inf outside the certified set. Keep the returned object alive while it is used.

    Raises
    ------
    ValueError
        If ``gain0`` misses the margin or an r.m.s. limit.
    """
    gain0 = np.atleast_2d(np.asarray(gain0, dtype=float))
    objective = BarrierObjective(plants, effort, margin, mu)
    first = objective(gain0)
    if first is None:
        raise ValueError("the start gain misses the stability margin or an r.m.s. limit")
    objective.scale = first[2]
    return _Phi(objective, gain0, np.asarray(mask, dtype=bool).ravel())


def minimise_ipopt(
    plants: Sequence[DesignPlant],
    gain0: np.ndarray,
    *,
    mask: np.ndarray,
    effort: np.ndarray,
    margin: float,
    mu: float = 1e-4,
    tol: float = 1e-7,
    max_iterations: int = 200,
    print_level: int = 0,
) -> dict[str, Any]:
    """Minimise Φ of the module docstring with IPOPT from ``gain0`` (in the certified set).

    Returns the keys of :func:`~loader_model.control.feasible_descent.minimise_certified`
    (``gain``, ``cost`` J, ``iterations``, ``history``, ``converged``, ``status``, ``time_s``)
    plus ``iterates`` (gain per IPOPT iterate, the start first), ``iterate_margins`` (min over
    plants of min −Re λ at each, numpy eigenvalues, computed after the solve),
    ``evaluations`` (points evaluated) and ``rejected`` (of those, outside the set: Φ = +inf).
    ``history`` is J at each iterate, from the values IPOPT saw, ``phi_history`` Φ. ``tol`` is IPOPT's ``tol``
    (its scaled dual infeasibility, here the largest |∂Φ/∂k|); 1e-7 matches the gradient
    tolerance of :func:`~loader_model.control.feasible_descent.minimise_certified`.

    Raises
    ------
    ValueError
        If ``gain0`` misses the margin or an r.m.s. limit.
    """
    started = time.perf_counter()
    phi = comfort_phi(plants, gain0, mask=mask, effort=effort, margin=margin, mu=mu)
    objective, free = phi.objective, phi.free
    recorder = _Recorder(int(free.sum()))
    k = ca.MX.sym("k", int(free.sum()))
    options = {
        "ipopt.hessian_approximation": "limited-memory",
        # 20 pairs instead of 6: class C at 18 km/h, 28 instead of 63 iterations (measured)
        "ipopt.limited_memory_max_history": 20,
        "ipopt.tol": tol,
        "ipopt.max_iter": max_iterations,
        "ipopt.print_level": print_level,
        "ipopt.sb": "yes",  # no banner
        "print_time": False,
        "show_eval_warnings": False,
        "iteration_callback": recorder,
    }
    solver = ca.nlpsol("comfort_ipopt", "ipopt", {"x": k, "f": phi(k)}, options)
    solution = solver(x0=phi.gain0.ravel()[free])
    stats = solver.stats()
    gain = phi.gain(np.asarray(solution["x"]).ravel())
    final = objective(gain)  # the check after the solve: margin and limits at the result
    elapsed = time.perf_counter() - started
    history = [phi.costs.get(x.tobytes(), np.inf) for x in recorder.iterates]
    return {
        "gain": gain,
        "cost": np.inf if final is None else final[2],
        "iterations": int(stats["iter_count"]),
        "history": tuple(history),
        "converged": bool(stats["success"]) and final is not None,
        "status": str(stats["return_status"]),
        "time_s": elapsed,
        "iterates": tuple(phi.gain(x) for x in recorder.iterates),
        "phi_history": tuple(recorder.values),
        "iterate_margins": np.array([_margin(plants, phi.gain(x)) for x in recorder.iterates]),
        "evaluations": phi.evaluations,
        "rejected": phi.rejected,
    }
