r"""The seat's ISO 2631-1 weightings as sampled linear filters, for the bound's cost (Eq. 49, 50).

Each axis a of the seat (:func:`~loader_model.simulation.result.seat_signal_names`: x, z, pitch)
is weighted by its Annex A filter (:data:`~loader_model.iso2631.DEFAULT_AXIS_WEIGHTINGS`: Wd,
Wk, We) with the paper's k factor (:data:`~loader_model.iso2631.PAPER_K_FACTORS`). The continuous
state space (A_w, B_w, C_w, D_w) comes from :func:`~loader_model.iso2631.weighting_abcd` (the
Annex A.2 factors in series, no coefficient copied here) and is discretised exactly at the
controller period h with the acceleration held over each period (zero-order hold):

.. math::

    \xi_{k+1} = e^{A_w h} \xi_k + \int_0^h e^{A_w s} ds\, B_w\, a_k, \qquad
    a_{w,k} = C_w \xi_k + D_w a_k,

so that with the three axes stacked (block diagonal) and the k factors in :math:`K`,

.. math:: a_{total}^2 = \sum_a k_a^2 a_{w,a}^2 = \frac{1}{K_s} \sum_{k<K_s} \|K a_{w,k}\|^2
    \quad \text{(Eq. 49, 50)}

over the K_s samples of a run, as :meth:`~loader_model.simulation.result.SimulationResult.
seat_evaluation` reads the simulator's rows. The hold adds half a period of delay and a droop
of 1 − (π f h)²/6 (7e-4 at 20 Hz); the digital filters of :mod:`loader_model.iso2631.filters`
agree with the exact continuous response to 3e-4 at 1 kHz, so both read the same a_w.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from loader_model.iso2631 import DEFAULT_AXIS_WEIGHTINGS, PAPER_K_FACTORS, weighting_abcd
from loader_model.simulation.result import seat_signal_names

__all__ = ["SeatWeighting", "seat_weighting"]


@dataclass(frozen=True)
class SeatWeighting:
    """The seat's weighting filters, stacked over its axes and sampled at ``period_s``.

    Attributes
    ----------
    axes : tuple of str
        ISO 2631 axes in order (x, z, pitch).
    signals : tuple of str
        The plant output of each axis (:data:`~loader_model.plant.plant.OUTPUT_NAMES`).
    k_factors : numpy.ndarray
        k of each axis (paper Eq. 50).
    phi, gamma, c, d : numpy.ndarray
        ξ_{k+1} = phi ξ_k + gamma a_k, a_w = c ξ_k + d a_k (module notes).
    period_s : float
        Sample period h in s.
    """

    axes: tuple[str, ...]
    signals: tuple[str, ...]
    k_factors: np.ndarray
    phi: np.ndarray
    gamma: np.ndarray
    c: np.ndarray
    d: np.ndarray
    period_s: float

    @property
    def order(self) -> int:
        """Number of filter states."""
        return self.phi.shape[0]

    def states(self, acceleration: np.ndarray) -> np.ndarray:
        """Filter states ξ_k (K_s + 1, order) from rest driven by (K_s, axes) seat samples."""
        samples = np.asarray(acceleration, dtype=float)
        out = np.zeros((samples.shape[0] + 1, self.order))
        for k, a in enumerate(samples):
            out[k + 1] = self.phi @ out[k] + self.gamma @ a
        return out

    def interval_maps(self, count: int) -> tuple[np.ndarray, ...]:
        """The filter over ``count`` samples as linear maps of its start state ξ and the samples
        a = (a_0, …, a_{count−1}) stacked: ξ_end = L_ξ ξ + L_a a and the weighted residuals
        (k_a a_w,a at each sample, stacked) r = R_ξ ξ + R_a a."""
        n, m = self.order, len(self.axes)
        l_xi, l_a = np.eye(n), np.zeros((n, m * count))
        r_xi, r_a = np.zeros((m * count, n)), np.zeros((m * count, m * count))
        scale = np.diag(self.k_factors)
        for i in range(count):
            rows = slice(m * i, m * (i + 1))
            r_xi[rows] = scale @ self.c @ l_xi
            r_a[rows] = scale @ self.c @ l_a
            r_a[rows, rows] += scale @ self.d
            l_xi = self.phi @ l_xi
            l_a = self.phi @ l_a
            l_a[:, rows] += self.gamma
        return l_xi, l_a, r_xi, r_a

    def weighted(self, acceleration: np.ndarray) -> np.ndarray:
        """Weighted accelerations k_a a_w,a (K_s, axes) of (K_s, axes) seat samples from rest."""
        samples = np.asarray(acceleration, dtype=float)
        state = np.zeros(self.order)
        out = np.empty_like(samples)
        for k, a in enumerate(samples):
            out[k] = self.c @ state + self.d @ a
            state = self.phi @ state + self.gamma @ a
        return out * self.k_factors

    def a_total(self, acceleration: np.ndarray) -> float:
        """a_total (Eq. 50) of (K_s, axes) seat samples (vibration about rest), m/s²."""
        weighted = self.weighted(acceleration)
        return float(np.sqrt(np.mean(np.sum(weighted**2, axis=1))))


def seat_weighting(period_s: float = 1e-3) -> SeatWeighting:
    """The seat's weighting filters sampled at ``period_s`` (module notes)."""
    names = seat_signal_names()
    blocks = [weighting_abcd(DEFAULT_AXIS_WEIGHTINGS[axis]) for axis in names]
    a = scipy.linalg.block_diag(*(block[0] for block in blocks))
    b = scipy.linalg.block_diag(*(block[1] for block in blocks))
    c = scipy.linalg.block_diag(*(block[2] for block in blocks))
    d = scipy.linalg.block_diag(*(block[3] for block in blocks))
    n, m = b.shape
    augmented = np.zeros((n + m, n + m))
    augmented[:n, :n] = a * period_s
    augmented[:n, n:] = b * period_s
    exponential = scipy.linalg.expm(augmented)
    return SeatWeighting(
        axes=tuple(names),
        signals=tuple(names.values()),
        k_factors=np.array([PAPER_K_FACTORS[axis] for axis in names]),
        phi=exponential[:n, :n],
        gamma=exponential[:n, n:],
        c=c,
        d=d,
        period_s=float(period_s),
    )
