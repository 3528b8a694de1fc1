"""Reports of the identification: tables beside Tables 4 and 5, fit plots, parameter updates."""

from __future__ import annotations

import datetime
from pathlib import Path
from typing import Any

import numpy as np

from loader_model.identification.leakage import LeakageFit
from loader_model.identification.pipeline import FrictionResult, Signals
from loader_model.identification.regression import LinearFit
from loader_model.io.export import write_atomically

__all__ = [
    "TABLE4_ROWS",
    "TABLE5_ROWS",
    "format_friction",
    "format_leakage",
    "friction_updates",
    "leakage_updates",
    "plot_friction_fit",
    "plot_leakage_fit",
    "update_source",
]

#: (name, unit shown, factor from SI to the unit shown, Table 4 value in that unit).
TABLE4_ROWS = (
    ("f_s", "kN", 1e-3, 17.0),
    ("tau_s", "s/m", 1.0, 40.0),
    ("gamma", "s/m", 1.0, 5.7),
    ("f_c", "N/bar", 1e5, 10.7),
    ("f_v", "kN·s/m", 1e-3, 8.13),
)
#: (name, unit shown, factor from SI, Table 5 value in that unit); K_oil is shown for 1/K_oil.
TABLE5_ROWS = (
    ("C", "m³/s", 1.0, -3.2e-4),
    ("K_oil", "Pa", 1.0, 1.64e9),
    ("k_Lp", "m³/(s·Pa)", 1.0, 2.87e-11),
    ("k_Lv", "m²", 1.0, -5.0e-4),
)


def _row(name: str, unit: str, value: float, low: float, high: float, paper: float) -> str:
    return f"  {name:<7} {unit:<10} {value:>11.4g}  [{low:>11.4g}, {high:>11.4g}]  {paper:>10.4g}"


def _header(level: float, table: str) -> list[str]:
    interval = f"{level:.0%} interval"
    return [
        f"  {'coef':<7} {'unit':<10} {'identified':>11}  {interval:^26}  {table:>10}",
        "  " + "-" * 70,
    ]


def format_friction(fit: LinearFit, n_samples: int | None = None) -> str:
    """Table 4 side by side with the identified friction coefficients, R² and s."""
    lines = ["Friction, Eq. 46 (errata 10 reading), fitted by " + fit.method]
    lines += _header(fit.level, "Table 4")
    for name, unit, factor, paper in TABLE4_ROWS:
        i = fit.names.index(name)
        lines.append(
            _row(
                name, unit, fit.values[i] * factor, fit.low[i] * factor, fit.high[i] * factor, paper
            )
        )
    lines.append(f"  {'R²':<7} {'-':<10} {fit.r_squared:>11.3f}  {'':26}  {0.831:>10.4g}")
    lines.append(f"  {'s':<7} {'kN':<10} {fit.s * 1e-3:>11.3f}  {'':26}  {0.767:>10.4g}")
    if n_samples is not None:
        lines.append(f"  ({n_samples} samples)")
    return "\n".join(lines)


def format_leakage(result: LeakageFit, n_samples: int | None = None) -> str:
    """Table 5 side by side with the identified leakage and compressibility, R² and s."""
    fit = result.regression
    lines = ["Leakage and compressibility, Eq. 48, fitted by " + fit.method]
    lines += _header(fit.level, "Table 5")
    for name, unit, factor, paper in TABLE5_ROWS:
        if name == "K_oil":
            low, high = result.bulk_modulus_interval
            lines.append(_row(name, unit, result.bulk_modulus, low, high, paper))
            i = fit.names.index("inv_K_oil")
            lines.append(
                _row("1/K_oil", "1/Pa", fit.values[i], fit.low[i], fit.high[i], 1.0 / paper)
            )
            continue
        i = fit.names.index(name)
        lines.append(
            _row(
                name, unit, fit.values[i] * factor, fit.low[i] * factor, fit.high[i] * factor, paper
            )
        )
    lines.append(f"  {'R²':<7} {'-':<10} {fit.r_squared:>11.3f}  {'':26}  {'-':>10}")
    lines.append(f"  {'s':<7} {'m³/s':<10} {fit.s:>11.3g}  {'':26}  {2.09e-4:>10.4g}")
    lines.append(
        f"  robust scale σ (MAD) {fit.scale:.3g} m³/s; weight 0: {np.sum(fit.weights == 0)}"
    )
    if n_samples is not None:
        lines.append(f"  ({n_samples} samples)")
    return "\n".join(lines)


def friction_updates(fit: LinearFit) -> dict[str, float]:
    """Parameter-file paths and values of the identified friction (``[friction]``)."""
    return {f"friction.{name}": float(fit.value(name)) for name in fit.names}


def leakage_updates(result: LeakageFit) -> dict[str, float]:
    """Parameter-file paths and values: k_Lp, k_Lv and K_oil (C is a sensor offset, not kept)."""
    fit = result.regression
    return {
        "leakage.k_lp": fit.value("k_Lp"),
        "leakage.k_lv": fit.value("k_Lv"),
        "hydraulics.bulk_modulus": result.bulk_modulus,
    }


def update_source(data: str | Path, command: str, today: datetime.date | None = None) -> str:
    """``"identified from DATA.csv on YYYY-MM-DD by loader-model identify ..."``."""
    day = (today or datetime.date.today()).isoformat()
    return f"identified from {Path(data).name} on {day} by loader-model identify {command}"


def _figure() -> tuple[Any, Any, Any]:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(9.0, 7.0), layout="constrained")
    FigureCanvasAgg(figure)
    top, bottom = figure.subplots(2, 1)
    for axes in (top, bottom):
        axes.grid(True, alpha=0.3)
    return figure, top, bottom


def _save(figure: Any, path: str | Path) -> Path:
    from loader_model.iso2631.plot import PLOT_SUFFIXES

    return write_atomically(
        path, lambda temporary: figure.savefig(temporary, dpi=110), PLOT_SUFFIXES, "plot file"
    )


def plot_friction_fit(result: FrictionResult, path: str | Path, title: str = "") -> Path:
    """Measured (Eq. 44) and modelled (Eq. 46) friction over time and against velocity."""
    s: Signals = result.signals
    fig, top, bottom = _figure()
    top.plot(s.time, result.measured * 1e-3, color="0.6", lw=0.6, label="measured, Eq. 44")
    top.plot(s.time, result.modelled * 1e-3, color="C0", lw=0.8, label="model, Eq. 46")
    top.set_xlabel("time t [s]")
    top.set_ylabel("friction force F_f [kN]")
    top.legend(loc="upper right")
    top.set_title(title or "Cylinder friction: measured and identified")
    bottom.plot(s.v, result.measured * 1e-3, ".", ms=1.0, color="0.6", label="measured")
    bottom.plot(s.v, result.modelled * 1e-3, ".", ms=1.0, color="C0", label="model")
    bottom.set_xlabel("cylinder velocity ẋ [m/s]")
    bottom.set_ylabel("friction force F_f [kN]")
    bottom.legend(loc="upper left", markerscale=8)
    return _save(fig, path)


def plot_leakage_fit(
    result: LeakageFit, signals: Signals, area_m2: float, path: str | Path, title: str = ""
) -> Path:
    """Measured and modelled left side of Eq. 48 over time, and robust weights."""
    fit = result.regression
    measured = signals.flow - area_m2 * signals.v
    modelled = measured - fit.residuals
    to_l_min = 60000.0
    fig, top, bottom = _figure()
    top.plot(signals.time, measured * to_l_min, color="0.6", lw=0.5, label="measured Q_A − A_p ẋ")
    top.plot(signals.time, modelled * to_l_min, color="C0", lw=0.8, label="model, Eq. 48")
    rejected = fit.weights == 0.0
    if np.any(rejected):
        top.plot(
            signals.time[rejected],
            measured[rejected] * to_l_min,
            "x",
            ms=3,
            color="C3",
            label="weight 0 (outlier)",
        )
    top.set_xlabel("time t [s]")
    top.set_ylabel("flow Q_A − A_p ẋ [L/min]")
    top.legend(loc="upper right")
    top.set_title(title or "Leakage and compressibility: measured and identified")
    bottom.plot(modelled * to_l_min, measured * to_l_min, ".", ms=1.0, color="0.5")
    line = np.array([modelled.min(), modelled.max()]) * to_l_min
    bottom.plot(line, line, color="C0", lw=1.0, label="measured = model")
    bottom.set_xlabel("model, Eq. 48 [L/min]")
    bottom.set_ylabel("measured Q_A − A_p ẋ [L/min]")
    bottom.legend(loc="upper left")
    return _save(fig, path)
