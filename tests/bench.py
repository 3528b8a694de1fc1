"""``make bench``: wall times of regeneration, import and model evaluation (medians of runs).

Machines are noisy, so every figure is reported with a ratio to a baseline measured in the same
run: ``python -c pass`` for process-level timings, and a plain NumPy 4x4 solve for calls.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def _median_seconds(action: Callable[[], object], repeats: int) -> float:
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        action()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def _process(*args: str) -> Callable[[], object]:
    return lambda: subprocess.run(
        [sys.executable, *args], cwd=ROOT, check=True, capture_output=True
    )


def _report(label: str, seconds: float, baseline: float | None = None, unit: str = "ms") -> None:
    scale = {"s": 1.0, "ms": 1e3, "us": 1e6}[unit]
    ratio = f"  ({seconds / baseline:.2f} x baseline)" if baseline else ""
    print(f"{label:<42}{seconds * scale:9.2f} {unit}{ratio}")


def main() -> int:
    python_start = _median_seconds(_process("-c", "pass"), 7)
    _report("baseline: python -c pass", python_start)
    imports = _median_seconds(_process("-c", "import loader_model"), 7)
    _report("import loader_model (goal <= 0.5 s)", imports, python_start)
    build_all = "import loader_model_generated as g; [g.function(n) for n in g.FUNCTION_NAMES]"
    build = _median_seconds(_process("-c", build_all), 5)
    _report("import + build all CasADi functions", build, python_start)
    with tempfile.TemporaryDirectory() as scratch:
        output = str(Path(scratch) / "generated")
        regenerate = _median_seconds(_process("-m", "derive", "--output", output), 5)
    _report("make regenerate (goal <= 5 s)", regenerate, python_start, unit="s")

    from loader_model.dynamics import LoaderDynamics

    model = LoaderDynamics.from_parameters()
    p, pd = np.full(4, 1e-3), np.full(4, 1e-2)
    mass = model.mass_matrix(p)
    solve = _median_seconds(lambda: [np.linalg.solve(mass, pd) for _ in range(1000)], 7) / 1000
    _report("baseline: numpy 4x4 solve", solve, unit="us")
    calls = 1000
    forward = _median_seconds(lambda: [model.forward_dynamics(p, pd) for _ in range(calls)], 7)
    _report("forward_dynamics via wrapper", forward / calls, solve, unit="us")
    linearise = _median_seconds(lambda: [model.linearise() for _ in range(100)], 5) / 100
    _report("linearise (A, B, E, C, D)", linearise, solve, unit="us")
    return 0


if __name__ == "__main__":
    sys.exit(main())
