"""Text report of the modal analysis side by side with the paper's Table 1 (section 2.2)."""

from __future__ import annotations

from collections.abc import Sequence

from loader_model.modal.modes import TABLE_1, ModalResult, compare_with_table_1
from loader_model.modal.undamped import UndampedMatrices

__all__ = ["format_machine_modes", "format_modes"]

_COORDINATES = ("x_H [m]", "y_H [m]", "θ1 [rad]", "θ2 [rad]")


def _shape_rows(model_shapes, paper_shapes) -> list[str]:
    lines = [f"{'':10}" + "".join(f"{'model':>8}{'paper':>7}   " for _ in range(4))]
    for i, label in enumerate(_COORDINATES):
        cells = []
        for mode in range(4):
            paper = f"{paper_shapes[i, mode]:7.2f}" if paper_shapes is not None else f"{'':7}"
            cells.append(f"{model_shapes[i, mode]:8.2f}{paper}   ")
        lines.append(f"{label:<10}" + "".join(cells))
    return lines


def format_modes(title: str, matrices: UndampedMatrices, result: ModalResult) -> str:
    """Frequencies, momentum shapes M·φ, displacement shapes φ and MACs against Table 1."""
    momentum = compare_with_table_1(result, "momentum")
    displacement = compare_with_table_1(result, "displacement")
    mode_header = f"{'':10}" + "".join(f"{f'mode {k + 1}':^18}" for k in range(4))
    lines = [
        title,
        "Undamped modes (Eq. 27-29): tyres, gravity, and the lift cylinders as a hydraulic spring",
        f"k_eq = {matrices.hydraulic_stiffness_n_per_m:.3e} N/m (Eq. 28 with the area ratio), "
        f"dx_cyl/dφ = {matrices.cylinder_lever_m_per_rad:.4f} m/rad (Eq. 35).",
        "",
        mode_header,
        f"{'':10}" + "".join(f"{'model':>8}{'paper':>7}   " for _ in range(4)),
        f"{'f [Hz]':<10}"
        + "".join(
            f"{f:8.2f}{p:7.1f}   "
            for f, p in zip(result.frequencies_hz, TABLE_1.frequencies_hz, strict=True)
        ),
        f"{'error [%]':<10}"
        + "".join(f"{e:+8.2f}{'':7}   " for e in momentum.frequency_errors_percent),
        f"{'MAC M·φ':<10}" + "".join(f"{m:8.4f}{'':7}   " for m in momentum.mac),
        f"{'MAC φ':<10}" + "".join(f"{m:8.4f}{'':7}   " for m in displacement.mac),
        "",
        "Momentum shapes M·φ: the reading Table 1's columns support (errata 7)",
        mode_header,
        *_shape_rows(result.momentum_shapes, TABLE_1.shapes),
        "",
        "Displacement shapes φ (Table 1 read literally; compare MAC φ above)",
        mode_header,
        *_shape_rows(result.displacement_shapes, TABLE_1.shapes),
        "",
        f"Within 1 % and MAC >= 0.99 for every mode (M·φ reading): {momentum.meets(1.0, 0.99)}",
    ]
    return "\n".join(lines)


def format_machine_modes(
    title: str,
    matrices: UndampedMatrices,
    result: ModalResult,
    units: Sequence[str] | None = None,
) -> str:
    """Frequencies, momentum shapes M·φ and displacement shapes φ of a machine without a paper
    reference (the layout of :func:`format_modes` without the paper's columns).

    ``units`` gives each coordinate's unit (the machine's ``coordinate_unit``); without it a
    name starting with x or y is read as a length in m, any other as an angle in rad.
    """
    names = matrices.coordinate_names
    if units is None:
        units = ["m" if n[0] in "xy" else "rad" for n in names]
    if len(units) != len(names):
        raise ValueError(f"units: {len(units)} given for the {len(names)} coordinates {names}")
    labels = [f"{n} [{unit}]" for n, unit in zip(names, units, strict=True)]
    count = result.frequencies_hz.size
    header = f"{'':14}" + "".join(f"{f'mode {k + 1}':>10}" for k in range(count))

    def rows(shapes) -> list[str]:
        return [
            f"{label:<14}" + "".join(f"{shapes[i, k]:10.2f}" for k in range(count))
            for i, label in enumerate(labels)
        ]

    return "\n".join(
        [
            title,
            "Undamped modes (Eq. 27-29): tyres, gravity, locked cylinders as springs, and the lift "
            "cylinders as a hydraulic spring",
            f"k_eq = {matrices.hydraulic_stiffness_n_per_m:.3e} N/m (Eq. 28 with the area ratio), "
            f"dx_cyl/dφ = {matrices.cylinder_lever_m_per_rad:.4f} m/rad (Eq. 35).",
            "",
            header,
            f"{'f [Hz]':<14}" + "".join(f"{f:10.2f}" for f in result.frequencies_hz),
            "",
            "Momentum shapes M·φ (the reading of the paper's Table 1, errata 7)",
            header,
            *rows(result.momentum_shapes),
            "",
            "Displacement shapes φ",
            header,
            *rows(result.displacement_shapes),
            "",
            "No paper reference for this machine (Table 1 is the skid-steer's).",
        ]
    )
