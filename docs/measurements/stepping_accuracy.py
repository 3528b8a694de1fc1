"""The simulator's steppings against CVODES at rtol 1e-10, per run: the seat-pad signals' errors.

Run from the repository's root::

    .venv/bin/python docs/measurements/stepping_accuracy.py > docs/measurements/stepping_accuracy.txt

The 18 runs of ``tests/simulation/test_adaptive_accuracy.py`` (every controller, both loads, the
paper's course at 9 and 18 km/h, an ISO 8608 class D road at 20 km/h): for each, the normalised
r.m.s. error ‖s − s_ref‖_rms / ‖s_ref − s_ref(0)‖_rms in percent of (f_Px, f_Py, θ̈1) with the
substeps chosen by their error, four fixed substeps (the default) and four fixed substeps that
share their period's Jacobian; then the ratios to the default, over all runs and signals.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "docs" / "measurements"))


def main() -> int:
    """Print one line per run and the ratios' summary after a header line."""
    import numpy as np
    from bench_quick import header

    from tests.simulation.test_adaptive_accuracy import SENSITIVE, STEPPINGS, _cases, _errors

    print(header("stepping_accuracy.py"))
    print("run: seat-pad errors (f_Px, f_Py, thetadd_1) in %, " + " | ".join(STEPPINGS))
    ratios: dict[str, list[float]] = {label: [] for label in STEPPINGS if label != "fixed"}
    for case in _cases():
        errors = _errors(*case)
        cells = " | ".join(
            ", ".join(f"{100 * e:.3f}" for e in errors[label]) for label in STEPPINGS
        )
        mark = " (sensitive run: in the median only)" if case in SENSITIVE else ""
        print(f"{' '.join(case)}: {cells}{mark}")
        for label in ratios:
            ratios[label].extend(errors[label] / errors["fixed"])
    for label, values in ratios.items():
        print(
            f"{label} / fixed: median {np.median(values):.2f}, "
            f"from {min(values):.2f} to {max(values):.2f} over {len(values)} signals"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
