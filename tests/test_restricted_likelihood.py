"""REML of σ_w², σ_v² (and d) by the generalized Schur recursion against the dense restricted
likelihood."""

from __future__ import annotations

import numpy as np
import pytest

from carousel_theory.prediction import BiasModel, simulate_sections
from carousel_theory.processes import fractional_coefficients
from carousel_theory.restricted_likelihood import (
    RATIO_TOLERANCE,
    estimate_noise_variances,
    restricted_log_likelihood,
)


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


def test_estimates_at_their_search_bound_are_named():
    # This white-noise record (seed 0) leaves the driving variance nothing to explain: σ_v²/σ_w² runs to
    # its upper bound (another seed, 4, shows enough chance low-frequency power to end inside, at 67). A
    # record drawn with both terms (the test above) ends inside both bounds.
    white = np.random.default_rng(0).standard_normal((1, 400))
    estimate = estimate_noise_variances(white, 0.5, (1e-4, 1e4))
    assert estimate.at_bound == ("σ_v²/σ_w²",)
    assert estimate.white_variance / estimate.driving_variance == pytest.approx(1e4, rel=1e-2)
    model = BiasModel(d=0.4, driving_variance=1.0, white_variance=2.0)
    sections = simulate_sections(40, 100, model, rng=np.random.default_rng(11), bias=-1.0)
    assert estimate_noise_variances(sections, 0.5, estimate_d=True).at_bound == ()


_NOISY = np.random.default_rng(0).standard_normal((2, 5))

INVALID = [
    ("one_dimensional", lambda: estimate_noise_variances(np.ones(10)), ValueError, "2-dimensional"),
    ("nan", lambda: estimate_noise_variances(np.array([[1.0, np.nan, 2.0]])), ValueError, "nan"),
    ("too_short", lambda: estimate_noise_variances(_NOISY[:, :2]), ValueError, "at least 3 samples"),
    (
        "no_more_contrasts_than_parameters",
        lambda: estimate_noise_variances(_NOISY[:1, :3]),
        ValueError,
        "1 section\\(s\\) of 3 samples leave 2 contrasts after each section's bias; REML of 2 parameters",
    ),
    (
        "no_more_contrasts_than_parameters_with_d",
        lambda: estimate_noise_variances(_NOISY[:1, :4], estimate_d=True),
        ValueError,
        "leave 3 contrasts .* REML of 3 parameters needs more than 3",
    ),
    ("constant", lambda: estimate_noise_variances(np.ones((2, 5))), ValueError, r"sections\[0\]: constant"),
    ("huge", lambda: estimate_noise_variances(1e200 * _NOISY), ValueError, r"within ±1e\+60"),
    ("d_one", lambda: estimate_noise_variances(_NOISY, 1.0), ValueError, "d=1.0"),
    ("bounds_reversed", lambda: estimate_noise_variances(_NOISY, 0.5, (2.0, 1.0)), ValueError, "low < high"),
    ("bounds_zero", lambda: estimate_noise_variances(_NOISY, 0.5, (0.0, 1.0)), ValueError, "0 < low"),
    ("bounds_three", lambda: estimate_noise_variances(_NOISY, 0.5, (1, 2, 3)), ValueError, "a pair"),
    ("estimate_d_int", lambda: estimate_noise_variances(_NOISY, estimate_d=1), TypeError, "estimate_d=1"),
    ("progress_int", lambda: estimate_noise_variances(_NOISY, show_progress=1), TypeError, "show_progress=1"),
    (
        "d_bounds_outside",
        lambda: estimate_noise_variances(_NOISY, 0.5, estimate_d=True, d_bounds=(0.0, 1.0)),
        ValueError,
        "d_bounds=",
    ),
    (
        "likelihood_white_zero",
        lambda: restricted_log_likelihood(_NOISY, 0.5, 1.0, 0.0),
        ValueError,
        "white_variance=0.0",
    ),
]


@pytest.mark.parametrize(("call", "error", "message"), [c[1:] for c in INVALID], ids=[c[0] for c in INVALID])
def test_invalid_arguments_are_refused(call, error, message):
    with pytest.raises(error, match=message):
        call()


def _dense_profile(sections, d, log_ratio):
    """(ℓ at σ̂_w², σ̂_w²) with σ_w² profiled out, written with a dense Cholesky factor of A = ΨΨᵀ + ρI:
    Q = Σ_k y_kᵀ P_A y_k, σ̂_w² = Q/(K(n − 1)), ℓ = −½[K(n − 1)(log σ̂_w² + 1) + K log|A| + K log 1ᵀA⁻¹1]."""
    from scipy.linalg import cho_factor, cho_solve

    count, n = sections.shape
    psi = fractional_coefficients(d, n)
    index = np.arange(n)
    lag = index[:, None] - index[None, :]
    mixing = np.where(lag >= 0, psi[np.clip(lag, 0, None)], 0.0)
    factor = cho_factor(mixing @ mixing.T + np.exp(log_ratio) * np.eye(n), lower=True)
    log_determinant = 2.0 * np.log(np.diagonal(factor[0])).sum()
    ones = np.ones(n)
    inverse_ones = cho_solve(factor, ones)
    total = ones @ inverse_ones
    quadratic = (
        np.einsum("ki,ik->", sections, cho_solve(factor, sections.T))
        - ((sections @ inverse_ones) ** 2).sum() / total
    )
    scale = quadratic / (count * (n - 1))
    return -0.5 * (count * (n - 1) * (np.log(scale) + 1.0) + count * (log_determinant + np.log(total))), scale


def _dense_maximiser(sections, d, log_bounds):
    from scipy.optimize import minimize_scalar

    result = minimize_scalar(
        lambda value: -_dense_profile(sections, d, value)[0],
        bounds=log_bounds,
        method="bounded",
        options={"xatol": 1e-8},
    )
    return float(result.x)


def _search_tolerance(log_ratio):
    """Brent's stopping rule: the maximiser lies within 2(√ε |x| + RATIO_TOLERANCE/3) of x."""
    return 2.0 * (np.sqrt(np.finfo(np.float64).eps) * abs(log_ratio) + RATIO_TOLERANCE / 3.0)


@pytest.mark.parametrize(
    ("count", "n", "d", "driving", "white", "seed"),
    [
        (1, 400, 0.5, 1.0, 30.0, 1),  # one long section, white dominant: ρ far from the Whittle start
        (1, 300, 0.5, 1.0, 0.2, 2),
        (8, 120, 0.35, 2.0, 5.0, 3),
        (30, 60, 0.7, 1.0, 1.0, 4),
    ],
)
def test_the_bracketed_search_finds_the_dense_maximiser_within_its_tolerance(
    count, n, d, driving, white, seed
):
    rng = np.random.default_rng(seed)
    model = BiasModel(d=d, driving_variance=driving, white_variance=white)
    sections = simulate_sections(count, n, model, rng=rng, bias=2.0)
    bounds = (1e-4, 1e4)
    estimate = estimate_noise_variances(sections, d, bounds)
    got = np.log(estimate.white_variance / estimate.driving_variance)
    expected = _dense_maximiser(sections, d, (np.log(bounds[0]), np.log(bounds[1])))
    assert abs(got - expected) <= _search_tolerance(expected) + 1e-8
    _, scale = _dense_profile(sections, d, got)
    assert estimate.driving_variance == pytest.approx(scale, rel=1e-9)
    best = _dense_restricted_log_likelihood(sections, d, estimate.driving_variance, estimate.white_variance)
    assert estimate.log_likelihood == pytest.approx(best, rel=1e-10)


def test_a_maximum_at_the_bound_is_found_by_the_search_over_all_bounds():
    # White-dominated data with an upper bound below the maximiser: the profile rises up to the bound.
    rng = np.random.default_rng(21)
    model = BiasModel(d=0.5, driving_variance=1.0, white_variance=100.0)
    sections = simulate_sections(1, 300, model, rng=rng, bias=0.0)
    bounds = (1e-3, 3.0)
    estimate = estimate_noise_variances(sections, 0.5, bounds)
    got = np.log(estimate.white_variance / estimate.driving_variance)
    expected = _dense_maximiser(sections, 0.5, (np.log(bounds[0]), np.log(bounds[1])))
    assert expected > np.log(bounds[1]) - 1e-3
    assert abs(got - expected) <= _search_tolerance(expected) + 1e-8


def test_narrow_ratio_bounds_are_searched_whole():
    rng = np.random.default_rng(22)
    model = BiasModel(d=0.5, driving_variance=1.0, white_variance=3.0)
    sections = simulate_sections(1, 200, model, rng=rng, bias=0.0)
    bounds = (2.5, 3.5)  # narrower than the first bracket: the bounded search over the whole interval
    estimate = estimate_noise_variances(sections, 0.5, bounds)
    got = np.log(estimate.white_variance / estimate.driving_variance)
    expected = _dense_maximiser(sections, 0.5, (np.log(bounds[0]), np.log(bounds[1])))
    assert np.log(bounds[0]) <= got <= np.log(bounds[1])
    assert abs(got - expected) <= _search_tolerance(expected) + 1e-8


def test_the_cubic_step_reaches_the_local_minimum_of_a_cubic_exactly():
    # f(t) = 1000 (t³ − 3t) has its local minimum at t = 1; from x = 0.8 the step is 0.2.
    from carousel_theory.restricted_likelihood import _cubic_vertex

    points = [(t, 1000.0 * (t**3 - 3.0 * t)) for t in (0.8, 0.5, 1.3, 2.0)]
    assert _cubic_vertex(points, 0.8) == pytest.approx(0.2, rel=1e-12)
    # For −f the local minimum is at t = −1 (step −1.8); with three points there is no cubic.
    assert _cubic_vertex([(t, -value) for t, value in points], 0.8) == pytest.approx(-1.8, rel=1e-12)
    assert _cubic_vertex(points[:3], 0.8) is None


def test_the_cubic_is_not_used_where_the_values_differ_by_rounding_only():
    from carousel_theory.restricted_likelihood import _cubic_vertex

    flat = [(t, 13279.0 + 1e-10 * t**2) for t in (7.0, 7.1, 7.2, 7.3)]
    assert _cubic_vertex(flat, 7.1) is None


@pytest.mark.parametrize("cubic", [1e-9, 1e-14, 1e-15])
def test_the_cubic_step_keeps_its_digits_when_the_cubic_term_is_small(cubic):
    # f(t) = (t − 0.3)² + c t³: near a smooth maximiser the likelihood is nearly quadratic, and the
    # textbook root (−q + √D)/(3c) cancels; the step must still be the local minimum, here checked
    # against the root of f'(t) = 3c t² + 2t − 0.6 at 50 digits.
    import mpmath

    from carousel_theory.restricted_likelihood import _cubic_vertex

    points = [(t, (t - 0.3) ** 2 + cubic * t**3) for t in (0.0, 0.5, 1.0, -0.4)]
    with mpmath.workdps(50):
        c = mpmath.mpf(cubic)
        exact = float((-1 + mpmath.sqrt(1 + mpmath.mpf("1.8") * c)) / (3 * c))
    assert _cubic_vertex(points, 0.0) == pytest.approx(exact, rel=1e-9)


def test_the_cubic_is_not_used_on_points_too_close_to_x():
    from carousel_theory.restricted_likelihood import _cubic_vertex

    # Values far apart (so only the spread of the abscissae can refuse): offsets of 1e-9 around x = 1.
    close = [(1.0 + k * 1e-9, 1000.0 * k**2 + 50.0 * k**3) for k in (0, 1, -1, 2)]
    assert _cubic_vertex(close, 1.0) is None
    spread = [(1.0 + k * 1e-2, 1000.0 * k**2 + 50.0 * k**3) for k in (0, 1, -1, 2)]
    assert _cubic_vertex(spread, 1.0) is not None
