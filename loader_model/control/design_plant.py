"""Design plants of the H2 gain optimisation: named channels of an LTI model.

.. math::
    \\dot x = A x + B_u u + B_w w, \\quad y = C_y x, \\quad z = C_z x + D_{zu} u,
    \\quad e = C_e x + D_{eu} u, \\quad u = -K y,

with w unit-intensity white noise (any shaping filter already in A), y the fed-back outputs, z the
performance outputs and e outputs whose r.m.s. is bounded (e.g. an actuator pressure).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from loader_model.control._checks import finite_matrix, select_channels

__all__ = ["DesignPlant"]


@dataclass(frozen=True)
class DesignPlant:
    """One LTI design plant (see the module docstring); build it with :meth:`from_statespace`.

    ``e_rms_limits`` are the r.m.s. bounds of the outputs e in their units; ``weight`` the
    plant's weight in the summed cost.
    """

    A: np.ndarray
    B_u: np.ndarray
    B_w: np.ndarray
    C_y: np.ndarray
    C_z: np.ndarray
    D_zu: np.ndarray
    C_e: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    D_eu: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    e_rms_limits: tuple[float, ...] = ()
    weight: float = 1.0
    name: str = "plant"
    input_names: tuple[str, ...] = ()
    measured_names: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        a = finite_matrix(f"{self.name}: A", self.A, (None, None))
        n = a.shape[0]
        a = finite_matrix(f"{self.name}: A", a, (n, n))
        b_u = finite_matrix(f"{self.name}: B_u", self.B_u, (n, None))
        m = b_u.shape[1]
        c_y = finite_matrix(f"{self.name}: C_y", self.C_y, (None, n))
        c_z = finite_matrix(f"{self.name}: C_z", self.C_z, (None, n))
        c_e = np.zeros((0, n)) if np.size(self.C_e) == 0 else self.C_e
        d_eu = np.zeros((0, m)) if np.size(self.D_eu) == 0 else self.D_eu
        values = {
            "A": a,
            "B_u": b_u,
            "B_w": finite_matrix(f"{self.name}: B_w", self.B_w, (n, None)),
            "C_y": c_y,
            "C_z": c_z,
            "D_zu": finite_matrix(f"{self.name}: D_zu", self.D_zu, (c_z.shape[0], m)),
            "C_e": finite_matrix(f"{self.name}: C_e", c_e, (None, n)),
        }
        values["D_eu"] = finite_matrix(f"{self.name}: D_eu", d_eu, (values["C_e"].shape[0], m))
        limits = tuple(float(v) for v in self.e_rms_limits)
        if len(limits) != values["C_e"].shape[0] or not all(
            np.isfinite(v) and v > 0 for v in limits
        ):
            raise ValueError(
                f"{self.name}: e_rms_limits must be {values['C_e'].shape[0]} positive finite "
                f"numbers (one per row of C_e); got {self.e_rms_limits}"
            )
        if not (np.isfinite(self.weight) and self.weight > 0):
            raise ValueError(f"{self.name}: weight must be positive and finite; got {self.weight}")
        for key, value in values.items():
            object.__setattr__(self, key, value)
        object.__setattr__(self, "e_rms_limits", limits)
        if not self.input_names:
            object.__setattr__(self, "input_names", tuple(f"u[{i}]" for i in range(m)))
        if not self.measured_names:
            object.__setattr__(
                self, "measured_names", tuple(f"y[{i}]" for i in range(c_y.shape[0]))
            )

    @property
    def gain_shape(self) -> tuple[int, int]:
        """Shape (m, p) of the gain K in u = −K y."""
        return self.B_u.shape[1], self.C_y.shape[0]

    @classmethod
    def from_statespace(
        cls,
        system: Any,
        *,
        control: Sequence[str | int],
        noise: Sequence[str | int],
        measured: Sequence[str | int],
        performance: Sequence[str | int],
        rms_limits: Mapping[str, float] | None = None,
        weight: float = 1.0,
        name: str | None = None,
    ) -> DesignPlant:
        """Design plant from a python-control ``StateSpace`` with named signals.

        ``rms_limits`` maps output names to r.m.s. bounds (the outputs e). D must vanish from
        noise to every selected output (finite H2 norm) and from control to measured outputs
        (no algebraic loop); raises ValueError otherwise.
        """
        limits = dict(rms_limits or {})
        a, b_u, c_y, d_yu, u_names, y_names = select_channels(system, control, measured)
        _, b_w, _, d_w, _, _ = select_channels(system, noise, None)
        _, _, c_z, d_zu, _, _ = select_channels(system, control, performance)
        _, _, c_e, d_eu, _, _ = select_channels(system, control, list(limits))
        label = name or getattr(system, "name", "plant")
        if np.any(d_yu != 0):
            raise ValueError(
                f"{label}: D from control to measured outputs must be 0 (algebraic loop)"
            )
        outputs = list(system.output_labels)
        for kind, chosen in (
            ("measured", measured),
            ("performance", performance),
            ("rms_limits", list(limits)),
        ):
            index = [outputs.index(k) if isinstance(k, str) else int(k) for k in chosen]
            if np.any(d_w[index] != 0):
                raise ValueError(
                    f"{label}: D from noise to {kind} outputs must be 0 (finite H2 norm)"
                )
        return cls(
            A=a,
            B_u=b_u,
            B_w=b_w,
            C_y=c_y,
            C_z=c_z,
            D_zu=d_zu,
            C_e=c_e,
            D_eu=d_eu,
            e_rms_limits=tuple(limits.values()),
            weight=weight,
            name=label,
            input_names=tuple(u_names),
            measured_names=tuple(y_names),
        )
