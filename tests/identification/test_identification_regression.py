"""Regression statistics: least squares against numpy, robust fits, sandwich covariance."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.identification.regression import (
    bisquare_psi,
    huber_psi,
    mad_scale,
    robust_linear_fit,
)


def _line(n: int, seed: int, noise: float = 0.1) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    x = np.column_stack((np.ones(n), rng.uniform(-1, 1, n)))
    return x, x @ np.array([2.0, -3.0]) + noise * rng.standard_normal(n)


def test_least_squares_matches_the_classical_formulas() -> None:
    n = 5000
    x, y = _line(n, 0)
    fit = robust_linear_fit(x, y, ("a", "b"), robust=False)
    beta, *_ = np.linalg.lstsq(x, y, rcond=None)
    np.testing.assert_allclose(fit.values, beta, rtol=1e-12)
    r = y - x @ beta
    s2 = r @ r / (n - 2)
    np.testing.assert_allclose(fit.s, np.sqrt(s2), rtol=1e-12)
    # Sandwich with ψ(u) = u, no lags: White's estimator; close to s²(XᵀX)⁻¹ (homoscedastic).
    classical = s2 * np.linalg.inv(x.T @ x)
    np.testing.assert_allclose(fit.standard_errors, np.sqrt(np.diag(classical)), rtol=0.05)
    np.testing.assert_allclose(fit.r_squared, 1 - (r @ r) / np.sum((y - y.mean()) ** 2), rtol=1e-12)


def test_psi_functions() -> None:
    u = np.array([-10.0, -1.0, 0.0, 0.5, 10.0])
    psi, dpsi = huber_psi(u)
    np.testing.assert_array_equal(psi, [-1.345, -1.0, 0.0, 0.5, 1.345])
    np.testing.assert_array_equal(dpsi, [0.0, 1.0, 1.0, 1.0, 0.0])
    psi, dpsi = bisquare_psi(u)
    assert psi[0] == psi[-1] == 0.0  # redescending: gross outliers get no weight
    h = 1e-6
    numeric = (bisquare_psi(u + h)[0] - bisquare_psi(u - h)[0]) / (2 * h)
    np.testing.assert_allclose(dpsi, numeric, atol=1e-8)


def test_mad_scale_of_gaussian_noise() -> None:
    noise = np.random.default_rng(3).standard_normal(200_000) * 2.5
    assert mad_scale(noise) == pytest.approx(2.5, rel=0.01)


def test_robust_fit_ignores_one_sided_outliers_that_bias_least_squares() -> None:
    x, y = _line(2000, 1, noise=0.1)
    y[::20] += 5.0  # 5 % gross outliers, one sided
    ls = robust_linear_fit(x, y, ("a", "b"), robust=False)
    robust = robust_linear_fit(x, y, ("a", "b"))
    assert abs(ls.value("a") - 2.0) > 0.2  # biased by about 5 % · 5
    assert abs(robust.value("a") - 2.0) < 0.01
    assert abs(robust.value("b") + 3.0) < 0.02
    assert np.all(robust.weights[::20] == 0.0)
    assert np.all(robust.low <= [2.0, -3.0]) and np.all(robust.high >= [2.0, -3.0])


def test_exact_data_give_exact_coefficients() -> None:
    x, y = _line(100, 2, noise=0.0)
    for robust in (True, False):
        fit = robust_linear_fit(x, y, ("a", "b"), robust=robust)
        np.testing.assert_allclose(fit.values, [2.0, -3.0], rtol=1e-13)


def test_zero_regressor_is_named() -> None:
    x, y = _line(50, 0)
    x[:, 1] = 0.0
    with pytest.raises(ValueError, match=r"identically zero.*b"):
        robust_linear_fit(x, y, ("a", "b"))
