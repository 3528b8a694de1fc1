"""Output-feedback LQR (Eq. 41, 42) against python-control's LQR, scipy and finite differences."""

from __future__ import annotations

import control
import numpy as np
import pytest
from scipy.linalg import solve_continuous_lyapunov

from loader_model.control import NoStabilisingGainError, output_feedback_lqr


def _cost(a, b, c, q, r, x0, k):
    """½ tr(P X0) by scipy, independent of the package (inf when A − B K C is not Hurwitz)."""
    a_c = a - b @ k @ c
    if np.max(np.linalg.eigvals(a_c).real) >= 0:
        return np.inf
    p = solve_continuous_lyapunov(a_c.T, -(q + c.T @ k.T @ r @ k @ c))
    return 0.5 * np.trace(p @ x0)


def _sof_system(seed: int) -> tuple[np.ndarray, ...]:
    """A random system that a known static output feedback K* stabilises: A = A_H + B K* C."""
    rng = np.random.default_rng(seed)
    n, m, p = int(rng.integers(4, 11)), int(rng.integers(1, 3)), int(rng.integers(2, 5))
    a_h = rng.normal(size=(n, n))
    a_h -= (np.max(np.linalg.eigvals(a_h).real) + 0.5) * np.eye(n)
    b, c = rng.normal(size=(n, m)), rng.normal(size=(p, n))
    return a_h + b @ rng.normal(size=(m, p)) @ c, b, c


@pytest.mark.parametrize("seed", range(5))
def test_full_state_feedback_matches_control_lqr(seed: int) -> None:
    rng = np.random.default_rng(100 + seed)
    n, m = 3 + seed, 1 + seed % 2
    a, b = rng.normal(size=(n, n)), rng.normal(size=(n, m))
    q, r = np.diag(rng.uniform(0.5, 2.0, n)), np.diag(rng.uniform(0.5, 2.0, m))
    reference, _, _ = control.lqr(a, b, q, r)
    result = output_feedback_lqr((a, b, np.eye(n)), q, r)
    assert result.converged
    np.testing.assert_allclose(
        result.gain, reference, rtol=1e-9, atol=1e-9 * np.abs(reference).max()
    )


@pytest.mark.parametrize("seed", range(20))
def test_random_systems_satisfy_eq42_with_monotone_cost(seed: int) -> None:
    a, b, c = _sof_system(seed)
    n, m = b.shape
    q, r, x0 = np.eye(n), np.eye(m), np.eye(n)
    result = output_feedback_lqr((a, b, c), q, r, x0)
    assert result.converged
    assert max(result.residuals) <= 1e-12
    # Monotone up to the rounding allowance of the Newton polish (DECREMENT_RTOL |J|, 1e-11).
    assert np.all(np.diff(result.cost_history) <= 1e-11 * result.cost)
    assert np.max(result.poles.real) < 0.0
    # Independent check: scipy's P and cost, and P, S satisfy Eq. 42 as recomputed here.
    k = result.gain
    a_c = a - b @ k @ c
    p = solve_continuous_lyapunov(a_c.T, -(q + c.T @ k.T @ r @ k @ c))
    s = solve_continuous_lyapunov(a_c, -x0)
    np.testing.assert_allclose(result.P, p, rtol=1e-9, atol=1e-11 * np.abs(p).max())
    np.testing.assert_allclose(result.cost, 0.5 * np.trace(p @ x0), rtol=1e-12)
    stationarity = r @ k @ c @ s @ c.T - b.T @ p @ s @ c.T
    assert np.linalg.norm(stationarity) <= 1e-8 * np.linalg.norm(b.T @ p @ s @ c.T)


def test_some_random_systems_need_the_homotopy() -> None:
    sources = {
        output_feedback_lqr(
            _sof_system(s), np.eye(len(_sof_system(s)[0])), 1.0 * np.eye(_sof_system(s)[1].shape[1])
        ).initial_gain_source
        for s in range(6)
    }
    assert {"zero", "homotopy"} <= sources


def test_optimum_is_stationary_by_finite_differences() -> None:
    a, b, c = _sof_system(3)
    n, m = b.shape
    q, r = np.eye(n), np.eye(m)
    result = output_feedback_lqr((a, b, c), q, r)
    h = 1e-6
    for index in np.ndindex(result.gain.shape):
        e = np.zeros_like(result.gain)
        e[index] = h
        slope = (
            _cost(a, b, c, q, r, np.eye(n), result.gain + e)
            - _cost(a, b, c, q, r, np.eye(n), result.gain - e)
        ) / (2 * h)
        assert abs(slope) <= 1e-6 * result.cost


def test_mask_holds_fixed_entries() -> None:
    a, b, c = _sof_system(9)
    n, m = b.shape
    full = output_feedback_lqr((a, b, c), np.eye(n), np.eye(m))
    mask = np.ones_like(full.gain, dtype=bool)
    mask[0, 0] = False
    gain0 = full.gain.copy()
    gain0[0, 0] *= 1.3
    masked = output_feedback_lqr((a, b, c), np.eye(n), np.eye(m), gain0=gain0, mask=mask)
    assert masked.gain[0, 0] == gain0[0, 0]
    assert masked.converged and max(masked.residuals) <= 1e-9
    assert full.cost <= masked.cost


def test_double_integrator_with_position_output_is_not_sof_stabilisable() -> None:
    # ẍ = u, y = x: u = −k x gives s² + k = 0, poles ±sqrt(−k), never in the open left half plane.
    a, b, c = np.array([[0.0, 1.0], [0.0, 0.0]]), np.array([[0.0], [1.0]]), np.array([[1.0, 0.0]])
    with pytest.raises(
        NoStabilisingGainError, match="no stabilising static output feedback"
    ) as info:
        output_feedback_lqr((a, b, c), np.eye(2), np.eye(1))
    assert info.value.best_abscissa >= 0.0


def test_statespace_names_and_controller_interconnection() -> None:
    a, b, c = _sof_system(1)
    n, m = b.shape
    sys = control.ss(
        a,
        np.hstack([b, np.ones((n, 1))]),
        c,
        0,
        inputs=[*["u0", "u1"][:m], "w"],
        outputs=[f"y{i}" for i in range(c.shape[0])],
    )
    result = output_feedback_lqr(sys, np.eye(n), np.eye(m), inputs=sys.input_labels[:m])
    assert result.input_names == tuple(sys.input_labels[:m])
    assert result.output_names == tuple(sys.output_labels)
    loop = control.feedback(sys[:, :m], result.controller(), sign=1)
    np.testing.assert_allclose(
        np.sort_complex(loop.poles()), np.sort_complex(result.poles), rtol=1e-9
    )


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"Q": np.eye(3)}, r"Q must have shape \(2, 2\); got shape \(3, 3\)"),
        ({"R": -np.eye(1)}, "R must be positive definite"),
        ({"Q": [[1.0, 2.0], [0.0, 1.0]]}, "Q must be symmetric"),
        ({"X0": [[np.nan, 0.0], [0.0, 1.0]]}, "X0 must be finite"),
        ({"mask": np.ones((2, 2), dtype=bool)}, r"mask must have the gain's shape \(1, 1\)"),
        ({"gain0": np.ones((1, 2))}, r"gain0 must have shape \(1, 1\)"),
        ({"outputs": ["z"]}, r"output 'z' is not a signal of the system; allowed: \['y\[0\]'\]"),
    ],
)
def test_bad_arguments_are_rejected(kwargs: dict, message: str) -> None:
    a, b, c = np.array([[0.0, 1.0], [-1.0, -1.0]]), np.array([[0.0], [1.0]]), np.array([[1.0, 0.0]])
    arguments = {"Q": np.eye(2), "R": np.eye(1)} | kwargs
    with pytest.raises(ValueError, match=message):
        output_feedback_lqr((a, b, c), **arguments)
