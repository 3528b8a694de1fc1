"""The quick part of ``make bench`` whose figures the performance page quotes.

Run from the repository's root::

    .venv/bin/python docs/measurements/bench_quick.py > docs/measurements/bench_quick.txt

It calls the measurements of ``tests/bench.py`` that take seconds (start-up, one plant call, the
closed loop over 20 s, the 64-run Table 6 matrix, the gain designs, the linear bound) and leaves
out the slow ones (the hand-written SciPy baselines, the constrained and nonlinear bounds, the
robustness engines, the machine design, the test suite), which ``make bench`` runs. Its first
line says when, where and under what load it ran: the figures are wall times on that machine.
"""

from __future__ import annotations

import datetime
import os
import platform
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))


def _cpu() -> str:
    """The processor's model name and the number of cores."""
    name = platform.processor() or platform.machine()
    cpuinfo = Path("/proc/cpuinfo")
    if cpuinfo.exists():
        for line in cpuinfo.read_text(encoding="utf-8").splitlines():
            if line.startswith("model name"):
                name = line.split(":", 1)[1].strip()
                break
    return f"{os.cpu_count()}-core {name}"


def header(script: str) -> str:
    """The first line of a kept measurement: the command, today's date, this machine and its
    load average now."""
    today = datetime.datetime.now(datetime.UTC).date().isoformat()
    return (
        f"# python docs/measurements/{script} | {today} | {_cpu()} "
        f"({platform.system()} {platform.machine()}), shared with other jobs, load average "
        f"{os.getloadavg()[0]:.1f} at the start"
    )


def main() -> int:
    """Print the quick benchmark, one figure a line, after a header line."""
    import numpy as np

    from tests import bench, bench_startup
    from tests.bench_matrix import matrix_seconds

    print(header("bench_quick.py"))
    python_start = bench._median_seconds(bench._process("-c", "pass"), 7)
    bench._report("baseline: python -c pass", python_start)
    imports = bench._median_seconds(bench._process("-c", "import loader_model"), 7)
    bench._report("import loader_model", imports, python_start)
    bench_startup.main()

    from loader_model.vehicle.dynamics import LoaderDynamics

    model = LoaderDynamics.from_parameters()
    p, pd = np.full(4, 1e-3), np.full(4, 1e-2)
    forward = bench._median_seconds(lambda: [model.forward_dynamics(p, pd) for _ in range(1000)], 7)
    bench._bench_plant(forward / 1000)
    _closed_loop()
    warm = min(matrix_seconds(2)[1] for _ in range(2))
    print(f"{'64-run Table 6 matrix, 2 jobs':<42}{warm:9.2f} s  (whole process, cache warm)")
    bench._control_design()
    bench._comfort_design()
    _linear_bound()
    print(f"# load average at the end {os.getloadavg()[0]:.1f}")
    return 0


def _closed_loop() -> None:
    """20 s of the paper's course at 9 km/h, empty bucket, the pump held, in a warm process."""
    from loader_model.plant.plant_parameters import plant_parameter_vector
    from loader_model.simulation import paper_course
    from loader_model.simulation.simulator import course_input, simulate
    from tests.bench import _median_seconds

    params = plant_parameter_vector(None, "empty")
    road = course_input(paper_course(9.0, settle_s=10.0), params)
    simulate(road, params, duration_s=20.0)
    seconds = _median_seconds(lambda: simulate(road, params, duration_s=20.0), 7)
    label = "simulate 20 s of the paper course"
    print(f"{label:<42}{seconds:9.3f} s  (real-time factor {20.0 / seconds:.0f})")


def _linear_bound() -> None:
    """The linear bound of the paper course at 9 km/h, empty (Riccati sweep and KKT solve)."""
    from loader_model.bound.linear import solve_linear_bound
    from loader_model.bound.problem import bound_problem
    from loader_model.plant.scenario import resolve_plant
    from loader_model.simulation import paper_course
    from loader_model.simulation.simulator import course_input
    from tests.bench import _median_seconds, _report

    plant = resolve_plant(None, "empty")
    problem = bound_problem(plant, course_input(paper_course(9.0), plant))
    solve_linear_bound(problem)
    for method in ("riccati", "kkt"):
        seconds = _median_seconds(lambda m=method: solve_linear_bound(problem, m), 3)
        _report(f"linear bound, {problem.duration_s:.1f} s course ({method})", seconds, unit="s")


if __name__ == "__main__":
    sys.exit(main())
