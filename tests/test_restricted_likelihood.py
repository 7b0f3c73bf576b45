"""REML of σ_w², σ_v² (and d) by the generalized Schur recursion against the dense restricted
likelihood."""

from __future__ import annotations

import numpy as np
import pytest

from carousel_theory.prediction import BiasModel, simulate_sections
from carousel_theory.processes import fractional_coefficients
from carousel_theory.restricted_likelihood import estimate_noise_variances, restricted_log_likelihood


def _dense_restricted_log_likelihood(sections, d, driving, white):
    """−½ Σ_k [log|C| + log(1ᵀC⁻¹1) + y_kᵀ P y_k], C = σ_w² ΨΨᵀ + σ_v² I, written with dense matrices."""
    n = sections.shape[1]
    psi = fractional_coefficients(d, n)
    index = np.arange(n)
    lag = index[:, None] - index[None, :]
    mixing = np.where(lag >= 0, psi[np.clip(lag, 0, None)], 0.0)
    covariance = driving * mixing @ mixing.T + white * np.eye(n)
    inverse = np.linalg.inv(covariance)
    ones = np.ones(n)
    total = ones @ inverse @ ones
    projector = inverse - np.outer(inverse @ ones, inverse @ ones) / total
    quadratic = np.einsum("ki,ij,kj->", sections, projector, sections)
    return -0.5 * (sections.shape[0] * (np.linalg.slogdet(covariance)[1] + np.log(total)) + quadratic)


@pytest.mark.parametrize(
    ("count", "n", "d", "driving", "white"), [(1, 300, 0.5, 1.0, 3.0), (25, 80, 0.3, 2.0, 0.1)]
)
def test_restricted_log_likelihood_equals_the_dense_one(count, n, d, driving, white):
    rng = np.random.default_rng(count * n)
    sections = simulate_sections(
        count, n, BiasModel(d=d, driving_variance=driving, white_variance=white), rng=rng, bias=4.0
    )
    expected = _dense_restricted_log_likelihood(sections, d, driving, white)
    assert restricted_log_likelihood(sections, d, driving, white) == pytest.approx(expected, rel=1e-10)


def test_reml_variances_maximise_the_dense_restricted_likelihood():
    rng = np.random.default_rng(8)
    model = BiasModel(d=0.5, driving_variance=2.0, white_variance=5.0)
    sections = simulate_sections(60, 120, model, rng=rng, bias=3.0)
    estimate = estimate_noise_variances(sections, 0.5)
    best = _dense_restricted_log_likelihood(sections, 0.5, estimate.driving_variance, estimate.white_variance)
    assert estimate.log_likelihood == pytest.approx(best, rel=1e-10)
    for factor_w, factor_v in [(1.02, 1.0), (0.98, 1.0), (1.0, 1.02), (1.0, 0.98), (1.02, 1.02)]:
        nearby = _dense_restricted_log_likelihood(
            sections, 0.5, estimate.driving_variance * factor_w, estimate.white_variance * factor_v
        )
        assert nearby < best


def test_reml_with_estimated_order_maximises_the_dense_likelihood_in_d_too():
    rng = np.random.default_rng(11)
    model = BiasModel(d=0.4, driving_variance=1.0, white_variance=2.0)
    sections = simulate_sections(40, 100, model, rng=rng, bias=-1.0)
    estimate = estimate_noise_variances(sections, 0.5, estimate_d=True)
    assert estimate.d_estimated
    best = _dense_restricted_log_likelihood(
        sections, estimate.d, estimate.driving_variance, estimate.white_variance
    )
    assert estimate.log_likelihood == pytest.approx(best, rel=1e-10)
    fixed = estimate_noise_variances(sections, estimate.d)
    assert fixed.log_likelihood == pytest.approx(estimate.log_likelihood, rel=1e-8)
    for step in (0.02, -0.02):
        moved = estimate_noise_variances(sections, estimate.d + step)
        assert moved.log_likelihood < estimate.log_likelihood


INVALID = [
    ("one_dimensional", lambda: estimate_noise_variances(np.ones(10)), ValueError),
    ("nan", lambda: estimate_noise_variances(np.array([[1.0, np.nan, 2.0]])), ValueError),
    ("too_short", lambda: estimate_noise_variances(np.ones((2, 2))), ValueError),
    ("d_one", lambda: estimate_noise_variances(np.ones((2, 5)), 1.0), ValueError),
    ("bounds_reversed", lambda: estimate_noise_variances(np.ones((2, 5)), 0.5, (2.0, 1.0)), ValueError),
    ("bounds_zero", lambda: estimate_noise_variances(np.ones((2, 5)), 0.5, (0.0, 1.0)), ValueError),
    (
        "d_bounds_outside",
        lambda: estimate_noise_variances(np.ones((2, 5)), 0.5, estimate_d=True, d_bounds=(0.0, 1.0)),
        ValueError,
    ),
    ("likelihood_white_zero", lambda: restricted_log_likelihood(np.ones((2, 5)), 0.5, 1.0, 0.0), ValueError),
]


@pytest.mark.parametrize(("call", "error"), [(c, e) for _, c, e in INVALID], ids=[i for i, _, _ in INVALID])
def test_invalid_arguments_are_refused(call, error):
    with pytest.raises(error):
        call()
