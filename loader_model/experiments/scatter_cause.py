"""Why the model's Table 6 trials scatter at 9 km/h: a_total over the driven speed.

A trial differs from another by its driven speed (σ 2 %), its board positions and its sensor
noise (:mod:`~loader_model.experiments.trials`). :func:`speed_scan` holds the boards and the
noise of one trial and steps the speed only, through the Table 6 trials themselves
(:func:`~loader_model.experiments.table6.run_trials`), on the model as built or with other
parameter values (a :class:`~loader_model.experiments.variant.ModelVariant`). A smooth curve
means a trial's a_total follows its speed; a step means the trials fall into two regimes,
and their scatter measures which side of the step the speed draw lands on::

    python -m loader_model.experiments.scatter_cause --load empty
    python -m loader_model.experiments.scatter_cause --load empty --tyre-damping 20000
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from loader_model.experiments.trials import AS_BUILT, TrialSpec
from loader_model.experiments.variant import ModelVariant

__all__ = ["main", "speed_scan"]


def speed_scan(
    factors: np.ndarray,
    load: str = "empty",
    controller: str = "baseline",
    speed_kmh: float = 9.0,
    course_seed: int = 0,
    variant: ModelVariant = AS_BUILT,
    jobs: int = 2,
) -> list[tuple[float, float, int]]:
    """a_total and lift-offs of one trial's course driven at each speed factor.

    Parameters
    ----------
    factors : array_like
        Driven speed over the nominal speed, each in (0, 2].
    load, controller : str
        The Table 6 condition (:data:`~loader_model.experiments.trials.LOADS`,
        :data:`~loader_model.experiments.trials.CONTROLLERS`).
    speed_kmh : float
        Nominal speed, 9 or 18 km/h.
    course_seed : int
        Seed of the board positions and the sensor noise, held for every factor.
    variant : ModelVariant
        The model (default: as built).
    jobs : int
        Worker processes.

    Returns
    -------
    list of (factor, a_total in m/s², lift-offs)
    """
    from loader_model.experiments.table6 import run_trials

    values = np.asarray(factors, dtype=float).ravel()
    if values.size == 0 or not np.all((values > 0.0) & (values <= 2.0)):
        raise ValueError(f"factors must be speed factors in (0, 2]; got {values.tolist()}")
    specs = [
        TrialSpec(speed_kmh, load, controller, k, float(f), int(course_seed), variant=variant)
        for k, f in enumerate(values)
    ]
    return [
        (o.spec.speed_factor, o.a_total_m_s2, o.lift_offs)
        for o in run_trials(specs, jobs=jobs, progress=False)
    ]


def main(argv: list[str] | None = None) -> int:
    """Print the scan as a table; a bad argument exits 2 with a one-line message."""
    parser = argparse.ArgumentParser(
        prog="python -m loader_model.experiments.scatter_cause",
        description="a_total of one Table 6 trial over the driven speed (9 km/h, boards held)",
    )
    parser.add_argument("--load", choices=("empty", "full"), default="empty", help="bucket load")
    parser.add_argument(
        "--controller",
        choices=("baseline", "passive", "virtual-accumulator", "skyhook"),
        default="baseline",
        help="ride controller",
    )
    parser.add_argument(
        "--tyre-damping", type=float, default=None, metavar="N_S_PER_M",
        help="vertical damping of every tyre in N s/m (default: the parameter file's)",
    )  # fmt: skip
    parser.add_argument("--jobs", type=int, default=2, metavar="N", help="worker processes")
    args = parser.parse_args(argv)
    if args.tyre_damping is not None and not 0.0 < args.tyre_damping <= 1e6:
        parser.error(f"--tyre-damping {args.tyre_damping}: allowed: (0, 1e6] N s/m")
    if args.jobs < 1:
        parser.error(f"--jobs {args.jobs}: allowed: an integer >= 1")
    variant = AS_BUILT
    if args.tyre_damping is not None:
        damping = args.tyre_damping
        variant = AS_BUILT.with_values({"tyres.front.c_y": damping, "tyres.rear.c_y": damping})
    rows = speed_scan(
        np.linspace(0.96, 1.04, 33), args.load, args.controller, variant=variant, jobs=args.jobs
    )
    print("speed factor  a_total [m/s²]  lift-offs")
    for factor, total, lifts in rows:
        print(f"{factor:12.4f}  {total:14.3f}  {lifts:9d}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
