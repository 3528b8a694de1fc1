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

Any described machine (:mod:`loader_model.machines`; default the skid-steer): its plant and
energy Functions (:func:`~loader_model.plant.energy.energy_function`), with the stores and losses
of :func:`~loader_model.plant.energy.energy_names` (a machine with locked cylinders adds
``internal``: their springs and dampers) and one road displacement per axle and axis.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import casadi as ca
import numpy as np

from loader_model.plant.energy import INPUT_POWER_NAMES, energy_function, energy_names
from loader_model.plant.equilibrium import static_state
from loader_model.plant.layout import SKID_STEER, MachineSource, PlantLayout, resolve_layout
from loader_model.plant.plant import plant_function
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
    duration_s: float,
    method: str,
    start: np.ndarray,
    end: np.ndarray,
    integrals: np.ndarray,
    layout: PlantLayout = SKID_STEER,
) -> EnergyBalance:
    n_in = len(INPUT_POWER_NAMES)
    stores, losses = energy_names(layout)
    return EnergyBalance(
        duration_s,
        method,
        dict(zip(stores, (end - start).tolist(), strict=True)),
        dict(zip(INPUT_POWER_NAMES, integrals[:n_in].tolist(), strict=True)),
        dict(zip(losses, integrals[n_in:].tolist(), strict=True)),
    )


def _n_road(layout: PlantLayout) -> int:
    """Number of road displacements (per axle, x and y) at the start of w."""
    return len(layout.machine.road_names)


def _stored(
    x: np.ndarray, u: float, w: np.ndarray, params: np.ndarray, layout: PlantLayout = SKID_STEER
) -> np.ndarray:
    still = np.zeros(_n_road(layout))
    return np.asarray(energy_function(layout)(x, u, w, still, params)[1], dtype=float).ravel()


def _machine_params(params: Sequence[float] | np.ndarray, layout: PlantLayout) -> np.ndarray:
    """``params`` as a vector of the size of the plant of the machine ``layout``."""
    size = len(layout.parameter_names)
    vector = np.asarray(params, dtype=float).ravel()
    if vector.size != size:
        raise ValueError(
            f"params must have the {size} plant parameters of machine {layout.name!r}; got "
            f"{vector.size}"
        )
    return vector


def _period_integrator(
    period_s: float, npar: int, rtol: float, atol: float, layout: PlantLayout = SKID_STEER
) -> ca.Function:
    nw, nx, n_road = len(layout.exogenous_names), len(layout.state_names), _n_road(layout)
    losses_named = energy_names(layout)[1]
    state = ca.SX.sym("state", nx + len(INPUT_POWER_NAMES) + len(losses_named))
    t = ca.SX.sym("t")
    p = ca.SX.sym("p", 1 + 2 * nw + npar)
    u, w0, w1, params = p[0], p[1 : 1 + nw], p[1 + nw : 1 + 2 * nw], p[1 + 2 * nw :]
    w = w0 + (w1 - w0) * (t / period_s)
    road_velocity = (w1[0:n_road] - w0[0:n_road]) / period_s
    x = state[:nx]
    _, _, inputs, losses, _ = energy_function(layout)(x, u, w, road_velocity, params)
    ode = ca.vertcat(plant_function(layout)(x, u, w, params)[0], inputs, losses)
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
    machine: MachineSource = SKID_STEER,
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
    machine : PlantLayout, str or pathlib.Path
        The machine resolved (:func:`~loader_model.plant.layout.plant_layout`), or a name or
        description file resolved once here (default the skid-steer); ``params`` is its plant's.

    Raises
    ------
    ValueError
        If ``params`` does not have the machine's number of parameters.
    SimulationError
        If CVODES fails in a period.
    """
    layout = resolve_layout(machine)
    params = _machine_params(params, layout)
    x, u = static_state(params, layout)
    total_s = road.duration_s if duration_s is None else float(duration_s)
    count = int(np.floor(total_s / period_s + 1e-9))
    exogenous = exogenous_table(road, np.arange(count + 1) * period_s)
    integrator = _period_integrator(period_s, params.size, rtol, atol, layout)
    n_losses = len(energy_names(layout)[1])
    state = np.concatenate([x, np.zeros(len(INPUT_POWER_NAMES) + n_losses)])
    for k in range(count):
        parameters = np.concatenate([[u], exogenous[k], exogenous[k + 1], params])
        try:
            state = np.asarray(integrator(x0=state, p=parameters)["xf"], dtype=float).ravel()
        except RuntimeError as error:
            raise SimulationError(
                f"CVODES failed in the period starting at t = {k * period_s:.4f} s ({error})"
            ) from None
    nx = len(layout.state_names)
    start = _stored(x, u, exogenous[0], params, layout)
    end = _stored(state[:nx], u, exogenous[count], params, layout)
    return _balance(count * period_s, f"CVODES rtol {rtol:g}", start, end, state[nx:], layout)


def simulated_energy_balance(
    result: SimulationResult,
    road: RoadInput,
    params: Sequence[float] | np.ndarray,
    *,
    machine: MachineSource = SKID_STEER,
) -> EnergyBalance:
    """Balance of a :func:`~loader_model.simulation.simulator.simulate` run, trapezoid over its
    rows and the final state (module notes), with the disturbance the run recorded.

    Parameters
    ----------
    result : SimulationResult
        The run (its states, command and recorded disturbance by name).
    road : RoadInput
        The road table it ran on.
    params : array_like
        Its plant parameter vector.
    machine : PlantLayout, str or pathlib.Path
        The machine resolved (:func:`~loader_model.plant.layout.plant_layout`), or a name or
        description file resolved once here (default the skid-steer).

    Raises
    ------
    ValueError
        If ``params`` does not have the machine's number of parameters.
    """
    layout = resolve_layout(machine)
    params = _machine_params(params, layout)
    n_road = _n_road(layout)
    time_s = np.append(result.time_s, 2 * result.time_s[-1] - result.time_s[-2])
    states = np.column_stack([result[state] for state in layout.state_names])
    states = np.vstack([states, result.final_state])
    commands = np.append(result["V_p_ref"], result["V_p_ref"][-1])
    forces = layout.exogenous_names[2 * n_road :]  # after the road and its rate
    recorded = np.column_stack([result[force] for force in forces])
    exogenous = exogenous_table(road, time_s, np.vstack([recorded, recorded[-1:]]))
    count = time_s.size
    mapped = energy_function(layout).map(count)
    _, parts, inputs, losses, elastic = (
        np.asarray(v, dtype=float)
        for v in mapped(states.T, commands, exogenous.T, np.zeros((n_road, count)), params)
    )
    powers = np.vstack([inputs, losses])
    steps = np.diff(time_s)
    integrals = ((powers[:, 1:] + powers[:, :-1]) / 2 * steps).sum(axis=1)
    displacement = np.diff(exogenous[:, 0:n_road], axis=0).T
    integrals[0] += ((elastic[:, 1:] + elastic[:, :-1]) / 2 * displacement).sum()
    duration = float(time_s[-1] - time_s[0])
    return _balance(duration, "ROS2 rows, trapezoid", parts[:, 0], parts[:, -1], integrals, layout)
