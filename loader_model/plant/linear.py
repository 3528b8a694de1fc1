r"""Linearisation of the plant by CasADi's automatic differentiation (Eq. 38-40, extended).

.. math::

    \dot{\delta x} = A\,\delta x + B\,\delta u + E\,\delta w, \qquad
    \delta y = C\,\delta x + D_u\,\delta u + D_w\,\delta w

at any operating point (default: the static equilibrium of
:mod:`loader_model.plant.equilibrium`), returned with named signals as a python-control
``StateSpace``. The tyre anchors ξ have ξ̇ = 0 while the tyres stick, so at rest they are pure
integrators that nothing drives and that drive the loader only through their initial value;
:meth:`PlantLinearisation.state_space` drops them by default (exact for ξ(0) = 0), together with
the accumulator's oil volume when the accumulator is switched off and the occupant's states when
the occupant is (:mod:`loader_model.plant.occupant`: the chassis drives the occupant and the
pad outputs f_Px, f_Py, never the other way round, so the loader's part of A is the same either
way).

:func:`undamped_matrices_from_plant` gives M and K of Eq. 27 from the same linearisation with the
chambers closed (Eq. 28): the closed chambers' pressures are integrals of the cylinder motion,
:math:`\delta p_{A,B} = S\,\delta p` with :math:`S = \partial \dot p_{A,B} / \partial \dot p`, so

.. math:: -M^{-1} K = A_{\ddot p, p} + A_{\ddot p, (p_A, p_B)}\, S
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from typing import Any

import casadi as ca
import numpy as np

from loader_model.plant.equilibrium import static_state
from loader_model.plant.layout import SKID_STEER, MachineSource, PlantLayout, resolve_layout
from loader_model.plant.occupant import OCCUPANT_STATE_NAMES
from loader_model.plant.plant import plant_function

__all__ = ["PlantLinearisation", "linearise_plant", "undamped_matrices_from_plant"]


@cache
def _jacobian_function(layout: PlantLayout) -> ca.Function:
    plant = plant_function(layout)
    x = ca.SX.sym("x", plant.size1_in(0))
    u = ca.SX.sym("u", plant.size1_in(1))
    w = ca.SX.sym("w", plant.size1_in(2))
    params = ca.SX.sym("params", plant.size1_in(3))
    xdot, y = plant(x, u, w, params)
    return ca.Function(
        "plant_jacobians",
        [x, u, w, params],
        [ca.jacobian(xdot, v) for v in (x, u, w)] + [ca.jacobian(y, v) for v in (x, u, w)],
        ["x", "u", "w", "params"],
        ["A", "B", "E", "C", "D_u", "D_w"],
    )


@dataclass(frozen=True)
class PlantLinearisation:
    """Jacobians of the plant at an operating point, with the state, input and output names."""

    A: np.ndarray
    B: np.ndarray
    E: np.ndarray
    C: np.ndarray
    D_u: np.ndarray
    D_w: np.ndarray
    operating_state: np.ndarray
    operating_input: float
    layout: PlantLayout = SKID_STEER

    def state_space(
        self, *, drop: tuple[str, ...] | None = None, exogenous: bool = True, name: str = "plant"
    ) -> Any:
        """python-control ``StateSpace`` with named states, inputs (V_p_ref, then w) and outputs.

        ``drop`` names states to remove (default: the tyre anchors, the accumulator's oil
        volume when its row and column are zero, i.e. the accumulator is off, and the
        occupant's states when nothing drives them and no output reads them, i.e. the occupant
        is off: they are then uncontrollable and unobservable).
        """
        import control

        layout = self.layout
        states = layout.state_names
        if drop is None:
            drop = layout.machine.anchor_names
            index = states.index("V_acc")
            if not self.A[index].any() and not self.A[:, index].any():
                drop = (*drop, "V_acc")
            occupant = [states.index(n) for n in OCCUPANT_STATE_NAMES]
            rest = [i for i in range(len(states)) if i not in occupant]
            inert = not (
                self.A[np.ix_(occupant, rest)].any()
                or self.B[occupant].any()
                or self.E[occupant].any()
                or self.C[:, occupant].any()
            )
            if inert:
                drop = (*drop, *OCCUPANT_STATE_NAMES)
        unknown = sorted(set(drop) - set(states))
        if unknown:
            raise ValueError(f"drop: unknown states {unknown}; allowed: {list(states)}")
        keep = [i for i, n in enumerate(states) if n not in drop]
        inputs = list(layout.input_names) + (list(layout.exogenous_names) if exogenous else [])
        b = np.hstack([self.B, self.E]) if exogenous else self.B
        d = np.hstack([self.D_u, self.D_w]) if exogenous else self.D_u
        return control.ss(
            self.A[np.ix_(keep, keep)],
            b[keep],
            self.C[:, keep],
            d,
            states=[states[i] for i in keep],
            inputs=inputs,
            outputs=list(layout.output_names),
            name=name,
        )


def linearise_plant(
    params: np.ndarray,
    x: np.ndarray | None = None,
    u: float | None = None,
    w: Any = None,
    *,
    machine: MachineSource = SKID_STEER,
) -> PlantLinearisation:
    """Linearise the plant of ``machine`` (its :class:`~loader_model.plant.layout.PlantLayout`,
    or a name or description file resolved once here; default the skid-steer) at ``(x, u, w)``;
    default: its static equilibrium, no road input."""
    layout = resolve_layout(machine)
    params = np.asarray(params, dtype=float)
    if x is None or u is None:
        x0, u0 = static_state(params, layout)
        x = x0 if x is None else x
        u = u0 if u is None else u
    size = len(layout.exogenous_names)
    w = np.zeros(size) if w is None else np.asarray(w, dtype=float)
    matrices = [np.asarray(m) for m in _jacobian_function(layout)(x, u, w, params)]
    return PlantLinearisation(
        *matrices, operating_state=np.asarray(x, float), operating_input=u, layout=layout
    )


def undamped_matrices_from_plant(
    params: np.ndarray, *, machine: MachineSource = SKID_STEER
) -> tuple[np.ndarray, np.ndarray, float]:
    """M, K of Eq. 27 with the chambers closed (Eq. 28), and k_eq of the cylinders [N/m].

    ``params`` should have the pump, valves, leakage and friction switched off
    (:meth:`~loader_model.plant.plant_parameters.PlantOptions.closed`). k_eq is the stiffness
    of the closed oil columns along the cylinder axis: −∂F_act/∂x_cyl through the pressures.
    ``machine``: as :func:`linearise_plant`.
    """
    layout = resolve_layout(machine)
    info, index = layout.machine, layout.index
    linear = linearise_plant(params, machine=layout)
    position = [index(n) for n in info.coordinate_names]
    rate = [index(n) for n in info.rate_names]
    pressure = [index("p_A"), index("p_B")]
    sensitivity = linear.A[np.ix_(pressure, rate)]
    stiffness_over_mass = (
        linear.A[np.ix_(rate, position)] + linear.A[np.ix_(rate, pressure)] @ sensitivity
    )
    completed, _ = info.function("complete_parameters")(params[: layout.n_mechanical])
    zeros = np.zeros(layout.n_coordinates)
    mass = np.asarray(info.function("mass_matrix")(zeros, completed))
    stiffness = -mass @ stiffness_over_mass
    force_row = linear.C[layout.output_names.index("F_act"), pressure]
    lever = float(info.function("cylinder_kinematics")(zeros, zeros, completed)[2])
    k_eq = -float(force_row @ sensitivity[:, 3]) / lever
    return mass, 0.5 * (stiffness + stiffness.T), k_eq
