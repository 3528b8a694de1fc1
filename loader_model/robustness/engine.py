"""Run a study: batches of samples on a local process pool or a Dask cluster, saved as they finish.

The samples (:func:`~loader_model.robustness.sampling.sample_specs`) and the gains
(:func:`~loader_model.robustness.gains.resolve_gains`) are planned once, here; each task runs a
batch of ``study.batch_size`` samples (:func:`~loader_model.robustness.runner.run_batch`) so that
scheduling costs little beside the simulations, and the rows of each finished batch are written at
once, atomically, as one Parquet part file in ``FOLDER/parts``; the resolved gains go to
``FOLDER/gains.json``. A rerun on the same folder skips
the samples already saved (resume after an interruption or a dead worker); a folder of another
study is refused. At the end the parts are combined, sorted by sample and controller, into
``results.parquet`` and ``results.csv``.

Engines: ``workers = 1`` runs in this process; ``workers > 1`` a local process pool (spawned
processes with one BLAS thread each, ended with this process whichever way it ends,
:func:`~loader_model.io.processes.worker_pool`; the controllers' periods compile once per process);
``scheduler``: a Dask ``distributed`` scheduler address (``tcp://host:8786``, e.g. from
dask-jobqueue) or a ``distributed.Client`` (a ``LocalCluster`` in the tests). Dask retries the
tasks of a worker that dies; the local pool stops with an error that says how to resume.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from loader_model.io.staging import remove_stale
from loader_model.robustness.gains import Gains, resolve_gains
from loader_model.robustness.sampling import SampleSpec, sample_specs
from loader_model.robustness.study import Study
from loader_model.robustness.table import combine_parts, read_parts, write_part

__all__ = ["fingerprint", "read_gains", "run_study"]

_SINGLE_THREAD = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


def fingerprint(study: Study) -> str:
    """SHA-256 of the study's validated content (its repr), which names its results folder."""
    return hashlib.sha256(repr(study).encode()).hexdigest()


def _prepare(folder: Path, study: Study) -> None:
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"results folder {str(folder)!r} exists and is not a folder")
    (folder / "parts").mkdir(parents=True, exist_ok=True)
    remove_stale(folder / "parts")  # part files a killed run was writing (write_part leaves them)
    stamp = folder / "study.sha256"
    expected = fingerprint(study)
    if stamp.exists():
        if stamp.read_text(encoding="utf-8").strip() != expected:
            raise ValueError(
                f"results folder {str(folder)!r} holds results of another study; choose another "
                "folder or delete it"
            )
    else:
        stamp.write_text(expected + "\n", encoding="utf-8")


def _batches(specs: list[SampleSpec], done: set[int], size: int) -> list[list[SampleSpec]]:
    todo = [spec for spec in specs if spec.index not in done]
    return [todo[i : i + size] for i in range(0, len(todo), size)]


@contextlib.contextmanager
def _single_thread_environment() -> Iterator[None]:
    """One BLAS thread per worker process (what Dask's nanny sets too): with 2 cores and several
    workers, threaded BLAS made the small linear algebra of a sample 6 times slower."""
    saved = {name: os.environ.get(name) for name in _SINGLE_THREAD}
    os.environ.update(_SINGLE_THREAD)
    try:
        yield
    finally:
        for name, value in saved.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value


def _local(study: Study, gains: Gains, batches: list, workers: int, save: Any) -> None:
    from loader_model.robustness.runner import run_batch

    if workers == 1:
        for batch in batches:
            save(batch, run_batch(study, gains, batch))
        return
    import multiprocessing
    from concurrent.futures.process import BrokenProcessPool

    from loader_model.io.processes import worker_pool

    context = multiprocessing.get_context("spawn")
    with _single_thread_environment(), worker_pool(workers, mp_context=context) as pool:
        futures = {pool.submit(run_batch, study, gains, batch): batch for batch in batches}
        try:
            for future in pool.completed(futures):
                save(futures[future], future.result())
        except BrokenProcessPool as error:
            raise ValueError(
                f"a worker process died ({error}); the finished batches are saved: run the same "
                "study on the same folder again to resume"
            ) from None


def _dask(study: Study, gains: Gains, batches: list, scheduler: Any, save: Any) -> None:
    from distributed import Client, as_completed

    from loader_model.robustness.runner import run_batch

    client = scheduler if isinstance(scheduler, Client) else Client(scheduler)
    try:
        futures = {client.submit(run_batch, study, gains, b, pure=False): b for b in batches}
        for future in as_completed(futures):
            save(futures[future], future.result())
            future.release()
    finally:
        if client is not scheduler:
            client.close()


def _write_gains(path: Path, gains: Gains) -> None:
    import json

    from loader_model.io.export import write_atomically

    text = json.dumps(gains, indent=1, sort_keys=True) + "\n"
    write_atomically(path, lambda t: t.write_text(text, encoding="utf-8"), (".json",), "gains")


def read_gains(folder: str | Path) -> Gains:
    """The K_fb per controller and load a study in ``folder`` ran with (``gains.json``; empty
    if the study has no gain-based controller or has not started)."""
    import json

    path = Path(folder) / "gains.json"
    return json.loads(path.read_text(encoding="utf-8")) if path.exists() else {}


def run_study(
    study: Study,
    folder: str | Path,
    *,
    workers: int = 1,
    scheduler: Any = None,
    progress: bool = True,
    gains: Gains | None = None,
) -> Any:
    """Run (or resume) ``study`` into ``folder`` and return the combined result table.

    Parameters
    ----------
    study : Study
        A validated study.
    folder : str or pathlib.Path
        Results folder (created; ``parts/``, ``results.parquet``, ``results.csv``).
    workers : int
        Local worker processes (1: this process); ignored with ``scheduler``.
    scheduler : str or distributed.Client, optional
        Dask scheduler address or client: run on that cluster instead.
    progress : bool
        Show a progress bar over the samples.
    gains : Gains, optional
        Resolved gains (default: :func:`~loader_model.robustness.gains.resolve_gains`).

    Returns
    -------
    pyarrow.Table
        One row per sample and controller, sorted by sample then controller.
    """
    from tqdm import tqdm

    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be an integer >= 1; got {workers!r}")
    folder = Path(folder)
    _prepare(folder, study)
    specs = sample_specs(study)
    done = read_parts(folder, study)
    batches = _batches(specs, done, study.batch_size)
    if batches:
        gains = resolve_gains(study) if gains is None else gains
        _write_gains(folder / "gains.json", gains)
    bar = tqdm(
        total=len(specs),
        initial=len(done),
        desc=study.name[:40],
        unit="sample",
        disable=not progress,
    )

    def save(batch: list[SampleSpec], rows: list[dict]) -> None:
        write_part(folder, study, batch[0].index, rows)
        bar.update(len(batch))

    try:
        if not batches:
            pass
        elif scheduler is not None:
            _dask(study, gains, batches, scheduler, save)
        else:
            _local(study, gains, batches, workers, save)
    finally:
        bar.close()
    return combine_parts(folder, study)
