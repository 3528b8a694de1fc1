"""The reproduction report: a folder with ``report.md``, PNG figures and one CSV per table.

:func:`write_report` builds everything in a staging folder beside the destination and renames
it into place only when complete, so a failure (or an interrupt) leaves either the previous report
or none, never a half-written one. The staging folder is named after its process
(:mod:`loader_model.io.staging`): the next run removes one that a killed run left behind, never one of
a run still going. The report folder gets the permissions of the user's umask.
"""

from __future__ import annotations

import csv
import secrets
import shutil
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from loader_model.experiments.table6 import LOAD_LABELS, SPEED_LABELS, Table6Cell
from loader_model.experiments.tables import Rows
from loader_model.io import staging
from loader_model.io.interrupts import check_interrupt

__all__ = [
    "FIDELITY_POINTS",
    "ReportOptions",
    "designed_rows",
    "table6_rows",
    "write_report",
    "write_tables",
]

#: Table 6 fidelity criterion: |model − paper| within this many percentage points.
FIDELITY_POINTS = 10.0


@dataclass(frozen=True)
class ReportOptions:
    """What the report runs: trials per cell, base seed, worker processes, progress bar, the
    tyres' envelope, and ``appendix``: Markdown sections from the layers above (the bound of
    :mod:`loader_model.bound`, which the experiments do not import), placed before the timings;
    a section may be a callable of the Table 6 cells (:class:`~loader_model.experiments.table6.
    Table6Cell`) that returns the Markdown, to set the trials' results beside its own."""

    trials: int = 4
    seed: int = 0
    jobs: int = 2
    progress: bool = True
    duration_s: float | None = None
    envelope: str = "tandem-cam"
    appendix: tuple[str | Callable[[Sequence[Table6Cell]], str], ...] = ()


def table6_rows(cells: list[Table6Cell]) -> Rows:
    """Table 6 side by side: model change [95 % CI] and Welch p beside the paper's."""
    rows: Rows = [
        [
            "speed",
            "load",
            "controller",
            "model Δ [%]",
            "95 % CI [%]",
            "model p",
            "paper Δ [%]",
            "paper p",
            "|Δ−Δ_paper| [pp]",
        ]
    ]
    for c in cells:
        rows.append(
            [
                f"{SPEED_LABELS.get(c.speed_kmh, '?')} ({c.speed_kmh:g} km/h)",
                f"{LOAD_LABELS.get(c.load, '?')} ({c.load})",
                c.controller,
                f"{c.model.change_percent:+.1f}",
                f"[{c.model.low_percent:+.1f}, {c.model.high_percent:+.1f}]",
                f"{c.model.p_value:.4f}",
                f"{c.paper_change_percent:+.1f}",
                f"{c.paper_p_value:.4f}",
                f"{c.within:.1f}",
            ]
        )
    return rows


def designed_rows(cells: list[Table6Cell]) -> Rows:
    """Per condition: the skyhook's change of a_total with Table 3 (k_φ = +0.22), Table 3 as
    printed (k_φ = −0.22, unstable), LQR, optimised and course-refined gains."""
    names = ("skyhook", "skyhook-printed", "skyhook-lqr", "skyhook-optimised", "skyhook-refined")
    rows: Rows = [["speed", "load", *(f"{n} Δ [%] [95 % CI]" for n in names), "best"]]
    conditions = sorted({(c.speed_kmh, c.load) for c in cells})
    for speed, load in conditions:
        found = {c.controller: c for c in cells if (c.speed_kmh, c.load) == (speed, load)}
        row = [f"{speed:g} km/h", load]
        for name in names:
            cell = found.get(name)
            row.append(
                "-"
                if cell is None
                else f"{cell.model.change_percent:+.1f} "
                f"[{cell.model.low_percent:+.1f}, {cell.model.high_percent:+.1f}]"
            )
        present = [n for n in names if n in found]
        row.append(min(present, key=lambda n: found[n].model.change_percent) if present else "-")
        rows.append(row)
    return rows


def markdown_table(rows: Rows) -> str:
    """``rows`` (header first) as a GitHub / CommonMark table: pipes in any cell are escaped,
    line breaks become spaces, and every row has the header's number of cells."""
    width = len(rows[0])
    for number, row in enumerate(rows[1:], start=1):
        if len(row) != width:
            raise ValueError(f"row {number} has {len(row)} cells, the header {width}: {row!r}")

    def line(row: Sequence[str]) -> str:
        cells = (str(c).replace("|", "\\|").replace("\n", " ") for c in row)
        return "| " + " | ".join(cells) + " |"

    return "\n".join([line(rows[0]), "|" + "---|" * width, *(line(row) for row in rows[1:])])


def write_tables(folder: Path, tables: dict[str, Rows]) -> None:
    """One CSV per table, named ``<key>.csv``."""
    for name, rows in tables.items():
        with open(folder / f"{name}.csv", "w", newline="", encoding="utf-8") as handle:
            csv.writer(handle).writerows(rows)


def _replace_folder(built: Path, destination: Path) -> None:
    """Move ``built`` to ``destination``; an existing report is swapped out, then removed."""
    old = None
    if destination.exists():
        token = secrets.token_hex(4)
        old = destination.with_name(f"{staging.staging_prefix(destination.name, 'old')}{token}")
        destination.rename(old)
    try:
        built.rename(destination)
    except BaseException:
        if old is not None:
            old.rename(destination)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def write_report(destination: str | Path, build: Callable[[Path], None]) -> Path:
    """Run ``build(folder)`` in a staging folder beside ``destination`` and rename it into place.

    Parameters
    ----------
    destination : str or pathlib.Path
        The report folder; its parent is created if missing. An existing folder is replaced
        only once the new one is complete. The staging folders of ``destination`` that killed
        runs left are removed first (:func:`loader_model.io.staging.remove_stale`).
    build : callable
        Writes the report's files into the folder it is given.

    Returns
    -------
    pathlib.Path
        ``destination``.
    """
    destination = Path(destination)
    if destination.exists() and not destination.is_dir():
        raise ValueError(f"--output {str(destination)!r} exists and is not a folder")
    destination.parent.mkdir(parents=True, exist_ok=True)
    staging.remove_stale(destination.parent, destination.name)
    temporary = staging.make_staging_folder(destination)
    try:
        build(temporary)
        check_interrupt()  # an interrupt that code in build caught: not a report to keep
        _replace_folder(temporary, destination)
    except BaseException:
        shutil.rmtree(temporary, ignore_errors=True)
        raise
    return destination
