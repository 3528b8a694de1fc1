r"""The nearest gains whose loop is stable on every plant it must hold on: the start of a design
on the machine.

A gain refined on one course, or optimised on the nominal linear plant, can be unstable on a
plant drawn from the robustness study's parameter distributions (on the skid-steer the gains
refined on the paper course, K_fb = (38.0, −99.7, −18.5, 0.68), are unstable on 1 of 16 such
plants: a pump mode at 20.6 Hz with the pump's damping ratio drawn at 0.40, margin −3.48 rad/s).
The design check fails such a gain, and the design on the machine rejects every step from it.
Before that design starts, the gain is moved the least, relative to each gain's size, that makes
the loop keep a margin σ on every nominal and every sampled plant:

.. math::

    \min_z \; \|z\|_2^2 \quad \text{s.t.} \quad
    \min_{P} \; \min_i \, (-\operatorname{Re} \lambda_i(P, K(z))) \ge \sigma, \qquad
    K(z) = K_0 + z \odot \max(|K_0|, 1),

over the plants P (the loop of plant and skyhook linearised at each plant's static equilibrium,
:func:`~loader_model.control.comfort_design.evaluate_gain`), solved by SLSQP (SciPy) with
finite-difference gradients of the constraint (the eigenvalues are cheap: 16 plants take about
0.05 s). On the skid-steer's refined gains with σ = 0.1 rad/s the result moves k_x by +20 %,
k_y by −61 %, k_θ by −33 % and k_φ by +0.2 % (measured; 10 s).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["START_MARGIN_FACTOR", "loop_margin", "nearest_stable_gain", "stable_start"]

#: A start short of the margin σ on a plant is moved to the nearest gain that keeps this many
#: times σ: a start on the constraint's edge leaves the descent no step that keeps it (measured
#: on the skid-steer from the course-refined gains: moved to keep σ = 0.1 rad/s, every step of
#: the first iteration was rejected; moved to keep 0.2 rad/s, three steps lowered J from 0.704
#: to 0.670).
START_MARGIN_FACTOR = 2.0


def loop_margin(plants: list[Any], gain: np.ndarray) -> float:
    """min over ``plants`` of the loop's margin min(−Re λ) [rad/s] with ``gain`` (1 × 4);
    +inf when no plant is given."""
    from loader_model.control.comfort_design import evaluate_gain

    if not plants:
        return float("inf")
    gain = np.asarray(gain, dtype=float).reshape(1, 4)
    return min(float(e.loop_margin) for e in evaluate_gain(plants, gain))


def nearest_stable_gain(gain: Any, plants: list[Any], margin_rad_s: float) -> np.ndarray:
    """The gain nearest ``gain`` whose loop keeps ``margin_rad_s`` on every plant (module notes).

    Parameters
    ----------
    gain : array_like
        K_fb (4 values) on the shipped norms.
    plants : list
        Linear comfort plants (:func:`~loader_model.control.comfort_design.comfort_plants`):
        the nominal ones and the sampled ones.
    margin_rad_s : float
        σ in rad/s, >= 0.

    Returns
    -------
    numpy.ndarray
        K_fb (1 × 4); ``gain`` itself when it already keeps the margin.

    Raises
    ------
    ValueError
        For a bad argument, or when no gain near ``gain`` keeps the margin (the solver's
        message and the margin it reached are named).
    """
    from scipy.optimize import minimize

    start = np.asarray(gain, dtype=float).ravel()
    if start.size != 4 or not np.all(np.isfinite(start)):
        raise ValueError(f"gain = {start.tolist()}; allowed: 4 finite gains")
    if not (np.isfinite(margin_rad_s) and margin_rad_s >= 0):
        raise ValueError(f"margin_rad_s = {margin_rad_s!r}; allowed: a number >= 0")
    if loop_margin(plants, start) >= margin_rad_s:
        return start.reshape(1, 4)
    scale = np.maximum(np.abs(start), 1.0)

    def gain_of(z: np.ndarray) -> np.ndarray:
        return start + z * scale

    result = minimize(
        lambda z: float(z @ z),
        np.zeros(4),
        jac=lambda z: 2.0 * z,
        method="SLSQP",
        constraints=[
            {"type": "ineq", "fun": lambda z: loop_margin(plants, gain_of(z)) - margin_rad_s}
        ],
        options={"ftol": 1e-10, "maxiter": 200},
    )
    found = gain_of(result.x)
    reached = loop_margin(plants, found)
    # SLSQP meets an inequality to its own feasibility tolerance (about 1e-10 here); the loop
    # margin is then σ to within that, so accept 1e-6 rad/s below σ and say so otherwise
    if reached < margin_rad_s - 1e-6:
        raise ValueError(
            f"no gain near {start.tolist()} keeps the loop margin {margin_rad_s:g} rad/s on all "
            f"{len(plants)} plants (reached {reached:.4f} rad/s; SLSQP: {result.message})"
        )
    return found.reshape(1, 4)


def stable_start(given: np.ndarray, plants: list[Any], margin: float) -> np.ndarray:
    """``given`` if its loop keeps ``margin`` on ``plants`` (as the check judges it: the linear
    design's optimum lies on the margin itself); else the nearest gain that keeps
    :data:`START_MARGIN_FACTOR` times it (or the margin itself where that is out of reach)."""
    from loader_model.experiments.design_check.verdict import MARGIN_RTOL

    if loop_margin(plants, given) >= margin * (1.0 - MARGIN_RTOL):  # the check's tolerance
        return given
    try:
        return nearest_stable_gain(given, plants, START_MARGIN_FACTOR * margin).ravel()
    except ValueError:
        return nearest_stable_gain(given, plants, margin).ravel()
