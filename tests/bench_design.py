"""``make bench``: the gains optimised on the machine with exact gradients against the
derivative-free Nelder-Mead refinement, on the same scenarios from the same start, in one run.

Both start from Table 3's gains (k_φ = +0.22; the linear comfort optimum ends in a persistent
oscillation on the 40 mm boards at 9 km/h with the empty bucket, so the machine design cannot
start there) and drive both loads over the paper's course at 9 km/h. Printed: each method's final
a_total per load, its cost on both measures (Σ a_total², what the refinement minimises, and the
mean of a_total² relative to the baseline, what the machine design minimises), the closed-loop
runs it took and its wall time, with the ratios of the machine design to the refinement.
"""

from __future__ import annotations

import time

import numpy as np

LOADS = ("empty", "full")
SPEED_KMH = 9.0


def main(evaluations: int = 150, iterations: int = 12) -> None:
    from loader_model.control.comfort_design import TABLE3_GAIN
    from loader_model.experiments.course_refinement import course_cost, refine_on_course
    from loader_model.experiments.design_check import Envelope
    from loader_model.experiments.machine_design import design_on_machine

    envelope = Envelope(loads=LOADS, board_speeds_kmh=(SPEED_KMH,), road_classes=(), seeds=(0,))
    start = time.perf_counter()
    machine = design_on_machine(TABLE3_GAIN, envelope=envelope, max_iterations=iterations)
    machine_s = time.perf_counter() - start
    start = time.perf_counter()
    refined = refine_on_course(
        TABLE3_GAIN, loads=LOADS, speed_kmh=SPEED_KMH, max_evaluations=evaluations
    )
    refine_s = time.perf_counter() - start
    baseline = list(machine.baseline.values())
    rows = {}
    for name, gain in (
        ("machine (exact gradients)", machine.gain),
        ("Nelder-Mead", refined["gain"]),
    ):
        totals = course_cost(gain.ravel(), LOADS, SPEED_KMH)
        values = np.array([totals[load] for load in LOADS])
        rows[name] = (
            values,
            float(np.sum(values**2)),
            float(np.mean((values / np.asarray(baseline)) ** 2)),
        )
    runs = {
        "machine (exact gradients)": machine.simulations,
        "Nelder-Mead": 2 * refined["evaluations"],
    }
    walls = {"machine (exact gradients)": machine_s, "Nelder-Mead": refine_s}
    print(f"gain design on the paper course at {SPEED_KMH:g} km/h, both loads, from Table 3:")
    for name, (values, total, relative) in rows.items():
        print(
            f"  {name:<26} a_total {values[0]:.3f} / {values[1]:.3f} m/s², Σa² {total:.3f}, "
            f"mean (a/a_base)² {relative:.4f}, {runs[name]} runs, {walls[name]:.1f} s"
        )
    a, b = rows["machine (exact gradients)"], rows["Nelder-Mead"]
    print(
        f"  ratio machine / Nelder-Mead: Σa² {a[1] / b[1]:.3f}, relative cost {a[2] / b[2]:.3f}, "
        f"runs {runs['machine (exact gradients)'] / runs['Nelder-Mead']:.3f}, wall "
        f"{machine_s / refine_s:.3f} (a run with sensitivities costs more than a plain one)"
    )


if __name__ == "__main__":
    main()
