r"""Fig. 12: pitch-disturbance frequency response with and without the skyhook feedback.

The paper's "pitch disturbance transfer function" is drawn here as the magnitude of the pitch
acceleration per disturbance moment at H, |θ̈1 / M_d| [(rad/s²)/(kN·m)], of the linearised plant
(:mod:`~loader_model.control.comfort_plant`): without feedback (baseline: the pump holds the
boom, V_p,ref constant), and with the skyhook loop r = −K_fb ŷ for the gains given.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from loader_model.control.comfort_plant import MEASURED, ComfortCase, comfort_system

__all__ = ["pitch_responses", "plot_pitch_responses"]


def _magnitude(a, b, c, d, omega: np.ndarray) -> np.ndarray:
    n = a.shape[0]
    return np.array(
        [abs((c @ np.linalg.solve(1j * w * np.eye(n) - a, b) + d).item()) for w in omega]
    )


def pitch_responses(
    case: ComfortCase, gains: Mapping[str, Any], frequency_hz: np.ndarray
) -> dict[str, np.ndarray]:
    """|θ̈1 / M_d| [rad/s² per N·m] at ``frequency_hz``: ``"baseline"`` then one entry per gain."""
    plant = case.plant
    i_in, i_out = plant.input_labels.index("M_d"), plant.output_labels.index("thetadd_1")
    omega = 2 * np.pi * np.asarray(frequency_hz, dtype=float)
    a = np.asarray(plant.A)
    out = {
        "baseline (no feedback)": _magnitude(
            a,
            np.asarray(plant.B)[:, [i_in]],
            np.asarray(plant.C)[[i_out]],
            np.asarray(plant.D)[[i_out]][:, [i_in]],
            omega,
        )
    }
    system = comfort_system(case)
    a, b, c, d = (np.asarray(m) for m in (system.A, system.B, system.C, system.D))
    u, m_d = system.input_labels.index("p_ref_n"), system.input_labels.index("M_d")
    y = [system.output_labels.index(n) for n in MEASURED]
    z = system.output_labels.index("thetadd_1")
    for name, gain in gains.items():
        k = np.atleast_2d(np.asarray(gain, dtype=float))
        a_cl = a - b[:, [u]] @ k @ c[y]
        if np.max(np.linalg.eigvals(a_cl).real) >= 0:
            raise ValueError(f"{name}: the closed loop is unstable; its response is not plotted")
        out[name] = _magnitude(a_cl, b[:, [m_d]], c[[z]], d[[z]][:, [m_d]], omega)
    return out


def plot_pitch_responses(
    path: str | os.PathLike[str],
    curves: Mapping[str, Mapping[str, np.ndarray]],
    frequency_hz: np.ndarray,
) -> Path:
    """Write the Fig. 12 PNG to ``path`` (no atomicity: callers use
    :func:`loader_model.io.export.write_atomically`); one panel per load, log-log axes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7.0, 3.6 * len(curves)), layout="constrained")
    FigureCanvasAgg(figure)
    panels = np.atleast_1d(figure.subplots(len(curves), 1))
    styles = ("k-", "C1--", "C0-", "C2-.", "C3:")
    for axes, (load, lines) in zip(panels, curves.items(), strict=True):
        for style, (name, magnitude) in zip(styles, lines.items(), strict=False):
            axes.loglog(frequency_hz, magnitude * 1e3, style, lw=1.3, label=name)
        axes.set_xlabel("frequency (Hz)")
        axes.set_ylabel("|θ̈₁ / M_d|  ((rad/s²) / (kN·m))")
        axes.set_title(f"pitch disturbance transfer function, {load} bucket (cf. paper Fig. 12)")
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(loc="lower right", fontsize=8)
    figure.savefig(os.fspath(path), dpi=110, format="png")
    return Path(os.fspath(path))
