"""The digital filters of the weightings in NumPy: second-order sections, FIR, interpolation.

:mod:`scipy.signal` takes about 0.6 s to import (it loads scipy.stats, scipy.interpolate and
scipy.optimize), several times the rest of ``loader-model simulate``. The weightings need only
the frequency response and the filtering of a cascade of second-order sections, of a short FIR
and a polyphase interpolator, written here with NumPy; ``tests/iso2631/test_iso2631_digital.py``
compares each with its :mod:`scipy.signal` counterpart (``sosfreqz``, ``freqz``, ``sosfilt``,
``lfilter``, ``resample_poly``).

Second-order sections are rows ``(b0, b1, b2, 1, a1, a2)`` (scipy's layout, ``a0 = 1``). The
cascade is filtered as one linear state-space system (each section in transposed direct form II,
as :func:`scipy.signal.sosfilt` does) in blocks of :data:`BLOCK_SAMPLES`: within a block the
output is a lower-triangular Toeplitz matrix of the impulse response times the block's input
plus the response to the state at its start, so each block is two matrix products and the
Python loop runs once per block, not per sample. Both are exact rearrangements of the sample
recursion: sample ``n`` of the output depends on the input up to ``n`` only. The products use
:func:`numpy.einsum` and the FIR fit :func:`least_squares`, not BLAS or LAPACK, whose threads
stall on a busy machine.

Rounding: the signal is filtered less its first sample (see :func:`sos_filter`), so an offset such
as gravity adds none. Against an exact (long-double) recursion of the same sections, with a 1 g
offset from its steady state, the output is off by 1.1e-12 of its peak for Wk at 1 kHz and
1.8e-10 for Wj at 10 kHz, where :func:`scipy.signal.sosfilt` is off by 2.1e-10 and 6.2e-8
(``tests/iso2631/test_iso2631_digital.py``; rounding grows as the poles approach z = 1 with the rate).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

__all__ = [
    "BLOCK_SAMPLES",
    "SEGMENT_SAMPLES",
    "dc_gain",
    "fir_filter",
    "fir_response",
    "interpolate",
    "least_squares",
    "sos_filter",
    "sos_response",
    "sos_steady_state",
]

#: Samples per block of :func:`sos_filter`: about this many multiply-adds per sample, and one
#: Python step per block (64 filters an hour at 1 kHz in 0.25 s, 32 in 0.7 s, 128 in 0.34 s).
BLOCK_SAMPLES = 64
#: Samples filtered per pass of :func:`sos_filter` and :func:`fir_filter` (a whole number of
#: blocks): their temporaries stay at a few times 8 MB whatever the record's length, so a
#: long record costs its input and output arrays only (a 10-million-row CSV, for example).
SEGMENT_SAMPLES = BLOCK_SAMPLES * 16384


def _unit_circle(frequency_hz: np.ndarray, sample_rate_hz: float) -> np.ndarray:
    return np.exp(-2j * np.pi * np.asarray(frequency_hz, dtype=float) / sample_rate_hz)


def sos_response(sos: np.ndarray, frequency_hz: np.ndarray, sample_rate_hz: float) -> np.ndarray:
    """Complex response of the cascade ``sos`` at ``frequency_hz`` (Hz) for ``sample_rate_hz``."""
    z_inverse = _unit_circle(frequency_hz, sample_rate_hz)
    response = np.ones_like(z_inverse)
    for b0, b1, b2, a0, a1, a2 in np.asarray(sos, dtype=float):
        numerator = b0 + z_inverse * (b1 + z_inverse * b2)
        response = response * numerator / (a0 + z_inverse * (a1 + z_inverse * a2))
    return response


def fir_response(fir: np.ndarray, frequency_hz: np.ndarray, sample_rate_hz: float) -> np.ndarray:
    """Complex response of the FIR with taps ``fir`` at ``frequency_hz`` (Hz)."""
    z_inverse = _unit_circle(frequency_hz, sample_rate_hz)
    return np.polyval(np.asarray(fir, dtype=float)[::-1], z_inverse)


@dataclass(frozen=True)
class _Blocks:
    """State space (A, B, C, D) of a cascade and its block matrices for L = BLOCK_SAMPLES."""

    powers: np.ndarray  # A^k, k = 0 .. L
    observe: np.ndarray  # C A^k, k = 0 .. L - 1: output from the state at a block's start
    toeplitz: np.ndarray  # h[i - j] (h[0] = D, h[k] = C A^(k-1) B) below the diagonal
    inputs: np.ndarray  # column j: A^(L-1-j) B, the state at a block's end from input j


def _sections(sos: np.ndarray) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, float]]:
    """(A, B, C, D) of each section in transposed direct form II (scipy's sosfilt)."""
    out = []
    for b0, b1, b2, _, a1, a2 in sos:
        a = np.array([[-a1, 1.0], [-a2, 0.0]])
        out.append((a, np.array([b1 - a1 * b0, b2 - a2 * b0]), np.array([1.0, 0.0]), b0))
    return out


@functools.lru_cache(maxsize=64)
def _blocks(coefficients: bytes, count: int) -> _Blocks:
    sos = np.frombuffer(coefficients).reshape(count, 6)
    a, b, c, d = np.zeros((0, 0)), np.zeros(0), np.zeros(0), 1.0
    for a2, b2, c2, d2 in _sections(sos):  # cascade: this section's input is the last output
        n1 = a.shape[0]
        a = np.block([[a, np.zeros((n1, 2))], [np.outer(b2, c), a2]])
        b, c, d = np.concatenate([b, b2 * d]), np.concatenate([d2 * c, c2]), d2 * d
    length = BLOCK_SAMPLES
    powers = np.empty((length + 1, *a.shape))
    powers[0] = np.eye(a.shape[0])
    for k in range(length):
        powers[k + 1] = a @ powers[k]
    observe = c @ powers[:length]
    response = np.concatenate([[d], observe[:-1] @ b])
    lag = np.arange(length)[:, None] - np.arange(length)[None, :]
    toeplitz = np.where(lag >= 0, response[np.clip(lag, 0, None)], 0.0)
    inputs = (powers[length - 1 :: -1] @ b).T
    for array in (powers, observe, toeplitz, inputs):
        array.setflags(write=False)
    return _Blocks(powers=powers, observe=observe, toeplitz=toeplitz, inputs=inputs)


def _times_transposed(left: np.ndarray, right: np.ndarray) -> np.ndarray:
    """``left @ right.T`` by :func:`numpy.einsum`, which does not call BLAS: for these small
    matrices a multi-threaded BLAS gains nothing, and on a busy machine its threads wait for
    cores (on a busy 2-core machine the whole ``loader-model simulate`` took 0.9-3.5 s instead
    of 0.5-0.7 s)."""
    return np.einsum("ij,kj->ik", left, right)


def least_squares(matrix: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Solution x of min ||matrix x - target|| for a tall matrix of full column rank.

    Householder QR written with :func:`numpy.einsum` (see :func:`_times_transposed`): numpy's
    ``lstsq`` calls a multi-threaded LAPACK, and on a busy machine its 33 calls in the design of
    three weightings took 1.6 s instead of 0.015 s.
    """
    r = np.array(matrix, dtype=float)
    y = np.array(target, dtype=float)
    columns = r.shape[1]
    for k in range(columns):
        x = r[k:, k]
        norm = float(np.sqrt(np.einsum("i,i", x, x)))
        if norm == 0.0:
            continue
        v = x.copy()
        v[0] += np.copysign(norm, x[0])
        v /= np.sqrt(np.einsum("i,i", v, v))
        r[k:, k:] -= 2.0 * np.outer(v, np.einsum("i,ij->j", v, r[k:, k:]))
        y[k:] -= 2.0 * v * np.einsum("i,i", v, y[k:])
    solution = np.zeros(columns)
    for k in range(columns - 1, -1, -1):  # back substitution on the triangle
        if r[k, k] != 0.0:
            solution[k] = (y[k] - np.einsum("i,i", r[k, k + 1 :], solution[k + 1 :])) / r[k, k]
    return solution


def _normalised(sos: np.ndarray) -> np.ndarray:
    sos = np.ascontiguousarray(sos, dtype=float)
    return sos / sos[:, 3:4]


def dc_gain(sos: np.ndarray) -> float:
    """Gain of the cascade at z = 1: the product of sum(b) / sum(a), exactly 0 for a section with
    a zero at z = 1 (coefficients 1, -2, 1 times a gain sum to 0 exactly)."""
    return float(np.prod(np.sum(sos[:, :3], axis=1) / np.sum(sos[:, 3:], axis=1)))


def sos_steady_state(sos: np.ndarray, value: float) -> np.ndarray:
    """State of :func:`sos_filter` at rest under the constant input ``value``.

    Section by section as :func:`scipy.signal.sosfilt_zi`: each section's steady state for its
    input, which is the previous section's DC gain ``sum(b) / sum(a)`` times the one before, so a
    section with a zero at z = 1 (a high-pass) passes exactly 0 on.
    """
    sos = _normalised(sos)
    states = []
    level = float(value)
    for (a, b, _, _), row in zip(_sections(sos), sos, strict=True):
        states.append(np.linalg.solve(np.eye(2) - a, b * level))
        level *= float(np.sum(row[:3]) / np.sum(row[3:]))
    return np.concatenate(states)


def sos_filter(
    sos: np.ndarray, signal: np.ndarray, state: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Filter ``signal`` with the cascade ``sos`` from ``state`` (default: rest).

    Parameters
    ----------
    sos : numpy.ndarray
        Second-order sections, shape (n, 6).
    signal : numpy.ndarray
        1-D input.
    state : numpy.ndarray, optional
        State (2 per section) from :func:`sos_steady_state` or a previous call.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        The output, same length as ``signal``, and the state after its last sample.
    """
    sos = _normalised(sos)
    blocks = _blocks(sos.tobytes(), sos.shape[0])
    current = np.zeros(2 * sos.shape[0]) if state is None else np.array(state, dtype=float)
    signal = np.asarray(signal, dtype=float)
    # Filter the signal less its first sample c from the state less the steady state of c, and
    # add c's steady output (exactly 0 through a zero at z = 1): equal by linearity and causal,
    # and an offset (gravity) then adds no rounding error, which the slow poles would amplify.
    offset = float(signal[0]) if signal.size else 0.0
    steady = sos_steady_state(sos, offset)
    current -= steady
    out = np.empty(signal.size)
    for start in range(0, signal.size, SEGMENT_SAMPLES):
        stop = min(start + SEGMENT_SAMPLES, signal.size)
        current = _filter_segment(blocks, signal[start:stop] - offset, current, out[start:stop])
    out += offset * dc_gain(sos)
    return out, current + steady


def _filter_segment(
    blocks: _Blocks, signal: np.ndarray, current: np.ndarray, out: np.ndarray
) -> np.ndarray:
    """Write the cascade's output for ``signal`` from ``current`` into ``out``; return the state
    after its last sample (the block recursion of the module notes)."""
    length = BLOCK_SAMPLES
    count, rest = divmod(signal.size, length)
    if count:
        inputs = signal[: count * length].reshape(count, length)
        driven = _times_transposed(inputs, blocks.inputs)
        starts = np.empty((count, current.size))
        transition = blocks.powers[length]
        for index in range(count):
            starts[index] = current
            current = transition @ current + driven[index]
        outputs = out[: count * length].reshape(count, length)
        outputs[:] = _times_transposed(inputs, blocks.toeplitz)
        outputs += _times_transposed(starts, blocks.observe)
    if rest:
        tail = signal[count * length :]
        out[count * length :] = (
            blocks.toeplitz[:rest, :rest] @ tail + blocks.observe[:rest] @ current
        )
        current = blocks.powers[rest] @ current + blocks.inputs[:, length - rest :] @ tail
    return current


def fir_filter(
    fir: np.ndarray, signal: np.ndarray, history: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Filter ``signal`` with the FIR ``fir``; ``history`` holds the ``len(fir) - 1`` inputs
    before it (default: zeros). Returns the output and the history after the last sample."""
    fir = np.asarray(fir, dtype=float)
    history = np.zeros(fir.size - 1) if history is None else np.asarray(history, dtype=float)
    signal = np.asarray(signal, dtype=float)
    out = np.empty(signal.size)
    for start in range(0, signal.size, SEGMENT_SAMPLES):
        padded = np.concatenate([history, signal[start : start + SEGMENT_SAMPLES]])
        out[start : start + padded.size - history.size] = np.convolve(padded, fir, mode="valid")
        history = padded[padded.size - (fir.size - 1) :].copy()
    return out, history


def interpolate(signal: np.ndarray, factor: int, taps: np.ndarray) -> np.ndarray:
    """Upsample ``signal`` by ``factor`` through the odd-length, centred FIR ``taps`` x ``factor``.

    The output at ``factor x n + p`` is ``factor x sum_j taps[j] s[n + (p + half - j) / factor]``
    over the ``j`` that make the index whole (``half = (len(taps) - 1) / 2``; zeros beyond the
    ends), what :func:`scipy.signal.resample_poly` computes with ``window=taps``; evaluated as
    ``factor`` convolutions of the signal with one phase of the taps each.
    """
    signal = np.asarray(signal, dtype=float)
    half = (taps.size - 1) // 2
    out = np.empty(signal.size * factor)
    for phase in range(factor):
        first = (phase + half) % factor
        shift = (phase + half - first) // factor
        convolved = np.convolve(signal, factor * taps[first::factor])
        out[phase::factor] = convolved[shift : shift + signal.size]
    return out
