"""Robustness-study throughput (issue 14): 10 s runs per minute on the local pool and on Dask.

One study (paper course at 9 and 18 km/h, both loads, oil, tyre and pump parameters varied;
baseline, passive, virtual accumulator and skyhook per sample, plus the skyhook's stability
margin) run on a local pool of 2 processes and on a Dask ``LocalCluster`` of 2 worker processes
(started before the clock). Reports the wall time of the whole study (process start and period
compilation included) and the steady rate from the part files' modification times (first to
last finished batch), in 10 s runs per minute, and the Dask / local ratio of both.

Also the CPU time per run in one process (warm), which the machine's load does not change, and
the rate on 2 idle cores that it implies.

Run: ``.venv/bin/python -m tests.bench_robustness [SAMPLES]`` or as part of ``make bench``.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

STUDY = """
[study]
name = "bench"
seed = 1
samples = {samples}
duration_s = 10.0
batch_size = 8
[conditions]
speeds_kmh = [9.0, 18.0]
loads = ["empty", "full"]
[controllers]
compare = ["passive", "virtual-accumulator", "skyhook"]
[parameters]
"hydraulics.bulk_modulus" = {{ distribution = "uniform", low = 0.8e9, high = 1.8e9, unit = "Pa" }}
"tyres.front.k_y" = {{ distribution = "uniform", low = 1.6e6, high = 2.6e6, unit = "N/m" }}
"pump.natural_frequency" = {{ distribution = "uniform", low = 15.0, high = 30.0, unit = "Hz" }}
"""


def _rates(folder: Path, runs_per_sample: int, batch: int, wall_s: float, samples: int):
    times = sorted(p.stat().st_mtime for p in (folder / "parts").glob("part-*.parquet"))
    steady = (len(times) - 1) * batch * runs_per_sample / max(times[-1] - times[0], 1e-9)
    return samples * runs_per_sample / wall_s * 60.0, steady * 60.0


def main(samples: int = 128) -> int:
    """Run the benchmark study on both engines and print runs per minute and the ratio."""
    from distributed import Client, LocalCluster

    from loader_model.robustness.engine import run_study
    from loader_model.robustness.study import parse_study

    study = parse_study(STUDY.format(samples=samples))
    runs = len(study.controllers)
    results = {}
    with tempfile.TemporaryDirectory() as scratch:
        start = time.perf_counter()
        table = run_study(study, Path(scratch) / "local", workers=2, progress=False)
        wall = time.perf_counter() - start
        failed = sum(table.column("failed").to_pylist())
        results["local pool, 2 processes"] = (
            wall,
            *_rates(Path(scratch) / "local", runs, 8, wall, samples),
        )
        with (
            LocalCluster(
                processes=True, n_workers=2, threads_per_worker=1, dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            start = time.perf_counter()
            run_study(study, Path(scratch) / "dask", scheduler=client, progress=False)
            wall = time.perf_counter() - start
        results["Dask LocalCluster, 2 workers"] = (
            wall,
            *_rates(Path(scratch) / "dask", runs, 8, wall, samples),
        )
        same = (Path(scratch) / "local" / "results.csv").read_bytes() == (
            Path(scratch) / "dask" / "results.csv"
        ).read_bytes()
    print(
        f"robustness study: {samples} samples x {runs} controllers = {samples * runs} runs of "
        f"10 s (goal >= 2000 runs/min on 2 cores); failed runs: {failed}; same table: {same}"
    )
    for name, (wall, total, steady) in results.items():
        met = "goal met" if total >= 2000 else "GOAL MISSED"
        print(
            f"  {name:<30} {wall:7.1f} s wall  {total:7.0f} runs/min  steady {steady:7.0f}  "
            f"{met} (>= 2000)"
        )
    (local, _, steady_l), (dask, _, steady_d) = results.values()
    print(
        f"  Dask / local wall-time ratio {dask / local:.3f} (goal overhead < 20 %: < 1.2); "
        f"steady-rate ratio local / Dask {steady_l / steady_d:.3f}"
    )
    _in_fresh_process(samples)
    return 0


def _in_fresh_process(samples: int) -> None:
    """Run :func:`_cpu_per_run` in a new interpreter with one BLAS thread, as the workers have
    (this process may have loaded a threaded BLAS already)."""
    import os
    import subprocess

    environment = os.environ | dict.fromkeys(
        ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"), "1"
    )
    command = [sys.executable, "-m", "tests.bench_robustness", str(samples), "--cpu"]
    subprocess.run(command, env=environment, check=True)


def _cpu_per_run(study) -> None:
    """CPU time per run in this process after warm-up: what the machine's load does not change
    (the wall-clock rates above depend on what else the shared cores run)."""
    from loader_model.robustness.gains import resolve_gains
    from loader_model.robustness.runner import run_batch
    from loader_model.robustness.sampling import sample_specs

    gains, specs = resolve_gains(study), sample_specs(study)
    run_batch(study, gains, specs[:4])  # compile the periods, import everything
    measured = specs[4:20]
    cpu, wall = time.process_time(), time.perf_counter()
    run_batch(study, gains, measured)
    runs = len(measured) * len(study.controllers)
    cpu, wall = (time.process_time() - cpu) / runs, (time.perf_counter() - wall) / runs
    print(
        f"  in-process, warm: {cpu * 1e3:.1f} ms CPU per 10 s run ({wall * 1e3:.1f} ms wall), "
        f"i.e. {2 * 60 / cpu:.0f} runs/min on 2 idle cores"
    )


if __name__ == "__main__":
    if "--cpu" in sys.argv:
        from loader_model.robustness.study import parse_study

        _cpu_per_run(parse_study(STUDY.format(samples=int(sys.argv[1]))))
        sys.exit(0)
    sys.exit(main(*(int(a) for a in sys.argv[1:2])))
