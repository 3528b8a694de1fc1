"""Plot of the ISO 2631-1 Annex A weighting curves (magnitude in dB over frequency).

Matplotlib is imported inside :func:`plot_weightings` and drives the Agg canvas directly, so no
global backend is selected and importing this module stays cheap.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from loader_model.io.export import check_output_path, write_atomically
from loader_model.iso2631.weightings import (
    NOMINAL_BAND_HZ,
    WEIGHTING_NAMES,
    check_weighting_name,
    weighting_response,
)

__all__ = ["PLOT_SUFFIXES", "plot_weightings"]

#: File types :func:`plot_weightings` writes.
PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def plot_weightings(
    path: str | Path,
    weightings: Sequence[str] = WEIGHTING_NAMES,
    *,
    frequency_range_hz: tuple[float, float] = (0.01, 1000.0),
) -> Path:
    """Write the magnitude of the exact weightings W(j 2π f) (Annex A.2) in dB to ``path``.

    Parameters
    ----------
    path : str or pathlib.Path
        Output file, suffix one of :data:`PLOT_SUFFIXES`; written atomically by
        :func:`loader_model.io.export.write_atomically`, so a failure leaves no partial file.
    weightings : sequence of str
        Names from :data:`~loader_model.iso2631.weightings.WEIGHTING_NAMES`.
    frequency_range_hz : (float, float)
        Frequency axis limits in Hz, 0 < low < high.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = check_output_path(path, PLOT_SUFFIXES, "plot file")
    names = list(weightings)
    for name in names:
        check_weighting_name(name)
    if not names:
        raise ValueError(f"weightings must name at least one of {WEIGHTING_NAMES}; got none")
    low_hz, high_hz = (float(value) for value in frequency_range_hz)
    if not 0.0 < low_hz < high_hz < np.inf:
        raise ValueError(
            f"frequency_range_hz must satisfy 0 < low < high < inf; got {frequency_range_hz!r}"
        )

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    frequency_hz = np.geomspace(low_hz, high_hz, 800)
    figure = Figure(figsize=(8.0, 5.0), layout="constrained")
    FigureCanvasAgg(figure)
    axes = figure.add_subplot()
    for name in names:
        magnitude_db = 20.0 * np.log10(np.abs(weighting_response(name, frequency_hz)))
        band_low_hz, band_high_hz = NOMINAL_BAND_HZ[name]
        axes.semilogx(
            frequency_hz, magnitude_db, label=f"{name} ({band_low_hz:g}-{band_high_hz:g} Hz)"
        )
    axes.set_xlim(low_hz, high_hz)
    axes.set_ylim(-60.0, 10.0)
    axes.set_xlabel("frequency (Hz)")
    axes.set_ylabel("|W(j2πf)| (dB)")
    axes.set_title("ISO 2631-1:1997 Annex A frequency weightings")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()

    return write_atomically(
        path, lambda temporary: figure.savefig(temporary, dpi=120), PLOT_SUFFIXES, "plot file"
    )
