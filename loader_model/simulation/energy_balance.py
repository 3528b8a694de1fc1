r"""Energy balance of a run with the pump holding its static command (baseline, passive).

.. math:: W_{road} + W_{pump} + W_{charge} + W_{dist} = \sum_j D_j + \Delta E

with the power flows of :mod:`loader_model.plant.energy`. Two ways to get the integrals:

- :func:`reference_energy_balance`: CVODES over each 1 ms controller period as in
  :mod:`~loader_model.simulation.reference` (road table linear inside the period), with the
  power integrals appended to the state, so the same error control covers them. Inside a period
  the road displacement moves at the constant rate (w_{k+1} − w_k)/h, its true derivative.
- :func:`simulated_energy_balance`: trapezoid over the 1 ms rows of a
  :func:`~loader_model.simulation.simulator.simulate` result (ROS2); the elastic tyre forces'
  work against the road's motion is ½ (F_e,k + F_e,k+1) · (w_{k+1} − w_k) per period.

The residual (inputs − losses − ΔE) measures the integration, not the model: the model's
balance is an identity (``tests/plant/test_plant_energy.py``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import casadi as ca
import numpy as np

from loader_model.plant.energy import ENERGY_NAMES, INPUT_POWER_NAMES, LOSS_NAMES, energy_function
from loader_model.plant.equilibrium import static_state
from loader_model.plant.plant import EXOGENOUS_NAMES, STATE_NAMES, plant_function
from loader_model.simulation.controllers import CONTROLLER_PERIOD_S
from loader_model.simulation.result import SimulationResult
from loader_model.simulation.simulator import SimulationError, exogenous_table
from loader_model.simulation.travel import RoadInput

__all__ = ["EnergyBalance", "reference_energy_balance", "simulated_energy_balance"]


@dataclass(frozen=True)
class EnergyBalance:
    """Integrals of a run's power flows in J (names of :mod:`loader_model.plant.energy`).

    Attributes
    ----------
    duration_s : float
        Integrated time.
    method : str
        How the integrals were taken.
    stored_change_J, input_work_J, dissipated_J : dict of str to float
        ΔE per store, work per input, energy per loss.
    """

    duration_s: float
    method: str
    stored_change_J: dict[str, float]
    input_work_J: dict[str, float]
    dissipated_J: dict[str, float]

    @property
    def residual_J(self) -> float:
        """Inputs − losses − ΔE in J (zero for exact integration)."""
        stored = sum(self.stored_change_J.values())
        return sum(self.input_work_J.values()) - sum(self.dissipated_J.values()) - stored

    @property
    def largest_term_J(self) -> float:
        """Largest magnitude among the works, the total dissipation and the total ΔE, in J."""
        terms = [*self.input_work_J.values(), sum(self.dissipated_J.values())]
        return max(abs(v) for v in [*terms, sum(self.stored_change_J.values())])

    @property
    def relative_residual(self) -> float:
        """|residual| over :attr:`largest_term_J`."""
        return abs(self.residual_J) / self.largest_term_J

    def table(self) -> str:
        """The balance as a Markdown table (J)."""
        rows = [f"| term | J ({self.method}, {self.duration_s:g} s) |", "| --- | ---: |"]
        rows += [f"| work: {k} | {v:.6g} |" for k, v in self.input_work_J.items()]
        rows += [f"| dissipated: {k} | {v:.6g} |" for k, v in self.dissipated_J.items()]
        rows += [f"| stored change: {k} | {v:.6g} |" for k, v in self.stored_change_J.items()]
        rows.append(f"| residual | {self.residual_J:.3g} ({self.relative_residual:.2e}) |")
        return "\n".join(rows)


def _balance(
    duration_s: float, method: str, start: np.ndarray, end: np.ndarray, integrals: np.ndarray
) -> EnergyBalance:
    n_in = len(INPUT_POWER_NAMES)
    return EnergyBalance(
        duration_s,
        method,
        dict(zip(ENERGY_NAMES, (end - start).tolist(), strict=True)),
        dict(zip(INPUT_POWER_NAMES, integrals[:n_in].tolist(), strict=True)),
        dict(zip(LOSS_NAMES, integrals[n_in:].tolist(), strict=True)),
    )


def _stored(x: np.ndarray, u: float, w: np.ndarray, params: np.ndarray) -> np.ndarray:
    return np.asarray(energy_function()(x, u, w, np.zeros(4), params)[1], dtype=float).ravel()


def _period_integrator(period_s: float, npar: int, rtol: float, atol: float) -> ca.Function:
    nw, nx = len(EXOGENOUS_NAMES), len(STATE_NAMES)
    state = ca.SX.sym("state", nx + len(INPUT_POWER_NAMES) + len(LOSS_NAMES))
    t = ca.SX.sym("t")
    p = ca.SX.sym("p", 1 + 2 * nw + npar)
    u, w0, w1, params = p[0], p[1 : 1 + nw], p[1 + nw : 1 + 2 * nw], p[1 + 2 * nw :]
    w = w0 + (w1 - w0) * (t / period_s)
    road_velocity = (w1[0:4] - w0[0:4]) / period_s
    x = state[:nx]
    _, _, inputs, losses, _ = energy_function()(x, u, w, road_velocity, params)
    ode = ca.vertcat(plant_function()(x, u, w, params)[0], inputs, losses)
    options = {"reltol": rtol, "abstol": atol, "max_num_steps": 100_000}
    dae = {"x": state, "t": t, "p": p, "ode": ode}
    return ca.integrator("energy_period", "cvodes", dae, 0.0, period_s, options)


def reference_energy_balance(
    road: RoadInput,
    params: Sequence[float] | np.ndarray,
    *,
    duration_s: float | None = None,
    period_s: float = CONTROLLER_PERIOD_S,
    rtol: float = 1e-10,
    atol: float = 1e-12,
) -> EnergyBalance:
    """Balance of the hold run over ``road`` by CVODES with the integrals as states.

    Parameters
    ----------
    road : RoadInput
        Road table (:func:`~loader_model.simulation.simulator.course_input`).
    params : array_like
        Plant parameters; the run starts at their static state with the static command held.
    duration_s : float, optional
        Simulated time (default: the road table's).
    period_s : float
        Period of the road's linear interpolation (the controller's), s.
    rtol, atol : float
        CVODES tolerances (as :func:`~loader_model.simulation.reference.reference_simulation`).

    Raises
    ------
    SimulationError
        If CVODES fails in a period.
    """
    params = np.asarray(params, dtype=float).ravel()
    x, u = static_state(params)
    total_s = road.duration_s if duration_s is None else float(duration_s)
    count = int(np.floor(total_s / period_s + 1e-9))
    exogenous = exogenous_table(road, np.arange(count + 1) * period_s)
    integrator = _period_integrator(period_s, params.size, rtol, atol)
    state = np.concatenate([x, np.zeros(len(INPUT_POWER_NAMES) + len(LOSS_NAMES))])
    for k in range(count):
        parameters = np.concatenate([[u], exogenous[k], exogenous[k + 1], params])
        try:
            state = np.asarray(integrator(x0=state, p=parameters)["xf"], dtype=float).ravel()
        except RuntimeError as error:
            raise SimulationError(
                f"CVODES failed in the period starting at t = {k * period_s:.4f} s ({error})"
            ) from None
    nx = len(STATE_NAMES)
    start = _stored(x, u, exogenous[0], params)
    end = _stored(state[:nx], u, exogenous[count], params)
    return _balance(count * period_s, f"CVODES rtol {rtol:g}", start, end, state[nx:])


def simulated_energy_balance(
    result: SimulationResult, road: RoadInput, params: Sequence[float] | np.ndarray
) -> EnergyBalance:
    """Balance of a :func:`~loader_model.simulation.simulator.simulate` run, trapezoid over its
    rows and the final state (module notes), with the disturbance the run recorded."""
    params = np.asarray(params, dtype=float).ravel()
    time_s = np.append(result.time_s, 2 * result.time_s[-1] - result.time_s[-2])
    states = np.column_stack([result[name] for name in STATE_NAMES])
    states = np.vstack([states, result.final_state])
    commands = np.append(result["V_p_ref"], result["V_p_ref"][-1])
    recorded = np.column_stack([result[name] for name in EXOGENOUS_NAMES[8:]])
    exogenous = exogenous_table(road, time_s, np.vstack([recorded, recorded[-1:]]))
    count = time_s.size
    mapped = energy_function().map(count)
    _, parts, inputs, losses, elastic = (
        np.asarray(v, dtype=float)
        for v in mapped(states.T, commands, exogenous.T, np.zeros((4, count)), params)
    )
    powers = np.vstack([inputs, losses])
    steps = np.diff(time_s)
    integrals = ((powers[:, 1:] + powers[:, :-1]) / 2 * steps).sum(axis=1)
    displacement = np.diff(exogenous[:, 0:4], axis=0).T
    integrals[0] += ((elastic[:, 1:] + elastic[:, :-1]) / 2 * displacement).sum()
    duration = float(time_s[-1] - time_s[0])
    return _balance(duration, "ROS2 rows, trapezoid", parts[:, 0], parts[:, -1], integrals)
