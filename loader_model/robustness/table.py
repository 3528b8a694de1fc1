"""The result table of a study: schema, part files per batch, and the combined Parquet and CSV.

One row per sample and controller. Columns: ``sample``, ``controller``, the sample's conditions
(``speed_kmh`` nominal, ``speed_factor``, ``load``, ``road_seed``), every uncertain parameter by
its parameter-file path (SI units), the seat's ISO 2631-1 weighted r.m.s. per axis ``a_w_x``,
``a_w_z``, ``a_w_pitch`` and ``a_total`` (Eq. 49, 50; m/s², rad/s² for pitch),
``change_percent`` (a_total against the same sample's baseline), peak pressures ``p_A_max_Pa``,
``p_A_min_Pa``, ``p_B_max_Pa`` (gauge), ``pump_saturation_s`` (time with |V_p,ref| at or beyond V_p,max),
``tyre_lift_offs``, ``max_pole_real`` (largest real part of the plant-and-skyhook poles of the
gain, rad/s; NaN for controllers without K_fb), ``settle_ratio`` and ``settle_tail_rms`` (the
r.m.s. of θ̈1 in the run's last second over that in the second before, and the last second's in
rad/s², after the road's excitation: :func:`~loader_model.robustness.outcomes.settle_columns`;
NaN if not assessed), ``failed``, ``reason`` and ``category`` (``"evaluated"`` or why the run is
not counted: :mod:`~loader_model.robustness.outcomes`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from loader_model.robustness.study import Study

__all__ = ["combine_parts", "read_parts", "result_schema", "write_part"]

_METRICS = (
    "a_w_x",
    "a_w_z",
    "a_w_pitch",
    "a_total",
    "change_percent",
    "p_A_max_Pa",
    "p_A_min_Pa",
    "p_B_max_Pa",
    "pump_saturation_s",
    "tyre_lift_offs",
    "max_pole_real",
    "settle_ratio",
    "settle_tail_rms",
)


def result_schema(study: Study) -> Any:
    """The pyarrow schema of the study's result table (module notes)."""
    import pyarrow as pa

    fields = [
        ("sample", pa.int64()),
        ("controller", pa.string()),
        ("speed_kmh", pa.float64()),
        ("speed_factor", pa.float64()),
        ("load", pa.string()),
        ("road_seed", pa.int64()),
        *((path, pa.float64()) for path, _ in study.parameters),
        *((name, pa.float64()) for name in _METRICS),
        ("failed", pa.bool_()),
        ("reason", pa.string()),
        ("category", pa.string()),
    ]
    return pa.schema(fields)


def write_part(folder: Path, study: Study, first: int, rows: list[dict[str, Any]]) -> Path:
    """Write one batch's rows atomically as ``parts/part-<first sample>.parquet``.

    The temporary files killed runs left in ``parts`` are not looked for here (that would list the
    folder once per part): :func:`~loader_model.robustness.engine.run_study` removes them once.
    Each row gets its ``category`` (:func:`~loader_model.robustness.outcomes.categorise`; a batch
    holds every controller of its samples).
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    from loader_model.io.export import write_atomically
    from loader_model.robustness.outcomes import categorise

    categories = categorise(rows, study.duration_s)
    rows = [row | {"category": c} for row, c in zip(rows, categories, strict=True)]
    table = pa.Table.from_pylist(rows, schema=result_schema(study))
    path = folder / "parts" / f"part-{first:08d}.parquet"
    return write_atomically(
        path,
        lambda temporary: pq.write_table(table, temporary),
        (".parquet",),
        "result part",
        remove_stale=False,
    )


def _part_files(folder: Path) -> list[Path]:
    return sorted(p for p in (folder / "parts").glob("part-*.parquet") if p.is_file())


def read_parts(folder: Path, study: Study) -> set[int]:
    """Sample indices already saved in ``folder`` (complete rows of every controller)."""
    import pyarrow.parquet as pq

    done: set[int] = set()
    for path in _part_files(folder):
        done.update(pq.read_table(path, columns=["sample"]).column("sample").to_pylist())
    return done


def combine_parts(folder: Path, study: Study) -> Any:
    """Combine the part files, sorted by sample then controller, into ``results.parquet`` and
    ``results.csv`` in ``folder``; return the table. Parts written before the ``category`` and
    ``settle_*`` columns existed are read with them empty, and their rows categorised here."""
    import pyarrow as pa
    import pyarrow.csv as csv
    import pyarrow.parquet as pq

    from loader_model.io.export import write_atomically
    from loader_model.robustness.outcomes import categorise

    schema = result_schema(study)
    parts = [pq.read_table(path, schema=schema) for path in _part_files(folder)]
    table = pa.concat_tables(parts) if parts else schema.empty_table()
    rank = {name: i for i, name in enumerate(study.controllers)}
    rows = table.to_pylist()
    rows.sort(key=lambda row: (row["sample"], rank.get(row["controller"], len(rank))))
    if any(row["category"] is None for row in rows):  # parts written before the column existed
        categories = categorise(rows, study.duration_s)
        rows = [row | {"category": c} for row, c in zip(rows, categories, strict=True)]
    table = pa.Table.from_pylist(rows, schema=schema)
    write_atomically(
        folder / "results.parquet",
        lambda temporary: pq.write_table(table, temporary),
        (".parquet",),
        "result table",
    )
    write_atomically(
        folder / "results.csv",
        lambda temporary: csv.write_csv(table, temporary),
        (".csv",),
        "result table",
    )
    return table
