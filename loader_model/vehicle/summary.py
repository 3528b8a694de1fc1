"""Plain-text reports of the model for the command line."""

from __future__ import annotations

import numpy as np

from loader_model.vehicle.dynamics import COORDINATE_NAMES, LoaderDynamics

__all__ = ["format_matrix", "model_summary"]


def format_matrix(matrix: np.ndarray, rows: tuple[str, ...], columns: tuple[str, ...]) -> str:
    """Format a labelled matrix with aligned columns (engineering notation)."""
    width = 11
    head = " " * 10 + "".join(f"{c:>{width}}" for c in columns)
    lines = [head]
    for label, row in zip(rows, np.atleast_2d(matrix), strict=True):
        lines.append(f"{label:<10}" + "".join(f"{value:>{width}.3e}" for value in row))
    return "\n".join(lines)


def model_summary(model: LoaderDynamics) -> str:
    """Static equilibrium, M and K at p = 0, and the damped modes of the linear model (Eq. 38)."""
    mass = model.mass_matrix(np.zeros(4))
    linear = model.linearise()
    accelerations, positions = [1, 3, 5, 7], [0, 2, 4, 6]
    stiffness = -mass @ linear.A[np.ix_(accelerations, positions)]
    cylinder = model.cylinder_kinematics(np.zeros(4))
    eigenvalues = np.linalg.eigvals(linear.A)
    oscillating = sorted((ev for ev in eigenvalues if ev.imag > 1e-9), key=lambda ev: -abs(ev))
    lines = [
        "Static equilibrium (p = 0)",
        f"  front tyre load F_Ay0   {model.parameter('F_Ay0'):12.1f} N",
        f"  rear tyre load  F_By0   {model.parameter('F_By0'):12.1f} N",
        f"  cylinder force  F_act0  {model.static_cylinder_force_N:12.1f} N",
        f"  cylinder length x_cyl   {cylinder['x_cyl']:12.4f} m",
        f"  lever dx_cyl/dphi       {cylinder['dx_cyl_dphi']:12.4f} m/rad  (Eq. 35)",
        "",
        "Mass matrix M (Eq. 32)",
        format_matrix(mass, COORDINATE_NAMES, COORDINATE_NAMES),
        "",
        "Stiffness K of the tyres and gravity, cylinder force held constant (Eq. 33-34)",
        format_matrix(stiffness, COORDINATE_NAMES, COORDINATE_NAMES),
        "",
        "Modes of the linear model with tyre damping, cylinder force held constant (Eq. 38)",
        "  frequency [Hz]   damping ratio [-]",
    ]
    for ev in oscillating:
        lines.append(f"  {abs(ev) / (2 * np.pi):14.2f}   {-ev.real / abs(ev):17.3f}")
    return "\n".join(lines)
