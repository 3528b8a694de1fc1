"""Plain-text reports of the model for the command line."""

from __future__ import annotations

import numpy as np

from loader_model.vehicle.dynamics import LoaderDynamics

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
    info = model.machine
    names, zeros = info.coordinate_names, np.zeros(info.n_coordinates)
    mass = model.mass_matrix(zeros)
    linear = model.linearise()
    accelerations = [info.state_names.index(n) for n in info.rate_names]
    positions = [info.state_names.index(n) for n in names]
    stiffness = -mass @ linear.A[np.ix_(accelerations, positions)]
    cylinder = model.cylinder_kinematics(zeros)
    eigenvalues = np.linalg.eigvals(linear.A)
    oscillating = sorted((ev for ev in eigenvalues if ev.imag > 1e-9), key=lambda ev: -abs(ev))
    lines = [
        "Static equilibrium (p = 0)",
        *_static_loads(model),
        f"  cylinder force  F_act0  {model.static_cylinder_force_N:12.1f} N",
        f"  cylinder length x_cyl   {cylinder['x_cyl']:12.4f} m",
        f"  lever dx_cyl/dphi       {cylinder['dx_cyl_dphi']:12.4f} m/rad  (Eq. 35)",
        "",
        "Mass matrix M (Eq. 32)",
        format_matrix(mass, names, names),
        "",
        "Stiffness K of the tyres and gravity, cylinder force held constant (Eq. 33-34)"
        + (", locked cylinders as springs" if info.locked_cylinders else ""),
        format_matrix(stiffness, names, names),
        "",
        "Modes of the linear model with tyre damping, cylinder force held constant (Eq. 38)",
        "  frequency [Hz]   damping ratio [-]",
    ]
    for ev in oscillating:
        lines.append(f"  {abs(ev) / (2 * np.pi):14.2f}   {-ev.real / abs(ev):17.3f}")
    return "\n".join(lines)


def _static_loads(model: LoaderDynamics) -> list[str]:
    """The static tyre loads (front, rear, ...) and locked-cylinder preloads of the model."""
    info = model.machine
    labels = {"F_Ay0": "front tyre load F_Ay0", "F_By0": "rear tyre load  F_By0"}
    lines = []
    for name in info.static_names:
        label = labels.get(name, f"static load {name}")
        lines.append(f"  {label:<24}{model.parameter(name):12.1f} N")
    return lines
