"""The linear model of a machine (Eq. 38-40) with named signals, and its export."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

import loader_model_generated as generated

__all__ = ["LinearModel"]


@dataclass(frozen=True)
class LinearModel:
    """ẋ = A x + B u + E w, y = C x + D_u u + D_w w (Eq. 38-40) with named signals.

    The names default to the skid-steer's; a machine's model (
    :class:`loader_model.vehicle.dynamics.LoaderDynamics`) passes its own from the generated
    metadata.
    """

    A: np.ndarray
    B: np.ndarray
    E: np.ndarray
    C: np.ndarray
    D_u: np.ndarray
    D_w: np.ndarray
    state_names: tuple[str, ...] = generated.STATE_NAMES
    input_names: tuple[str, ...] = ("F_act",)
    exogenous_names: tuple[str, ...] = generated.EXOGENOUS_NAMES
    output_names: tuple[str, ...] = generated.OUTPUT_NAMES

    def state_space(self, *, exogenous: bool = True, name: str = "loader") -> Any:
        """Return a python-control ``StateSpace`` with named states, inputs and outputs.

        Inputs are F_act [N] and, with ``exogenous``, the road and disturbance inputs w.
        """
        import control

        inputs = list(self.input_names)
        b_matrix, d_matrix = self.B, self.D_u
        if exogenous:
            inputs += list(self.exogenous_names)
            b_matrix = np.hstack([self.B, self.E])
            d_matrix = np.hstack([self.D_u, self.D_w])
        return control.ss(
            self.A,
            b_matrix,
            self.C,
            d_matrix,
            states=list(self.state_names),
            inputs=inputs,
            outputs=list(self.output_names),
            name=name,
        )

    def save(self, path: str | Path) -> Path:
        """Export A, B, E, C, D_u, D_w and the signal names to ``.npz`` or ``.mat`` (atomic)."""
        from loader_model.io.export import save_arrays

        return save_arrays(
            path,
            {
                "A": self.A,
                "B": self.B,
                "E": self.E,
                "C": self.C,
                "D_u": self.D_u,
                "D_w": self.D_w,
                "state_names": list(self.state_names),
                "input_names": list(self.input_names),
                "exogenous_names": list(self.exogenous_names),
                "output_names": list(self.output_names),
            },
        )
