"""Start-up of the command line (issue 19): whole-process wall times, medians of several runs.

``loader-model --help`` should take at most 0.2 s and ``loader-model simulate`` (the paper's
course with default options, its compiled closed-loop period in the cache) at most 1.0 s, as a
whole process. Machines are noisy, so each is also given as a ratio to ``python -c pass``
measured in the same run, interleaved with it (one run of each in turn), together with the
load average. Run alone with ``python -m tests.bench_startup``; ``make bench`` runs it too.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RUNS = 7


def _command_line() -> list[str]:
    """The installed ``loader-model`` script beside this Python, else ``python -m``."""
    script = Path(sys.executable).with_name("loader-model")
    return [str(script)] if script.exists() else [sys.executable, "-m", "loader_model.cli"]


def _wall_time(argv: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(argv, cwd=ROOT, check=True, capture_output=True)
    return time.perf_counter() - start


def measure(runs: int = RUNS) -> dict[str, float]:
    """Median wall time in s of each start-up case over ``runs`` interleaved runs."""
    cli = _command_line()
    cases = {
        "baseline: python -c pass": [sys.executable, "-c", "pass"],
        "python -c 'import loader_model.cli'": [sys.executable, "-c", "import loader_model.cli"],
        "loader-model --help (goal <= 0.2 s)": [*cli, "--help"],
        "loader-model simulate (goal <= 1.0 s)": [*cli, "simulate"],
    }
    _wall_time(cases["loader-model simulate (goal <= 1.0 s)"])  # fills the compiled cache
    samples: dict[str, list[float]] = {label: [] for label in cases}
    for _ in range(runs):
        for label, argv in cases.items():
            samples[label].append(_wall_time(argv))
    return {label: statistics.median(values) for label, values in samples.items()}


def main() -> int:
    """Print the start-up section of the benchmark."""
    load = os.getloadavg()
    medians = measure()
    baseline = medians["baseline: python -c pass"]
    print(f"start-up, whole process, median of {RUNS} (load average {load[0]:.2f}):")
    for label, seconds in medians.items():
        ratio = "" if label.startswith("baseline") else f"  ({seconds / baseline:.2f} x baseline)"
        print(f"  {label:<40}{seconds * 1e3:9.1f} ms{ratio}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
