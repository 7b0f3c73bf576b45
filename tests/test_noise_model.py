"""The noise model: each term's Allan variance checked two ways (exact dense sums, mpmath spectral
integrals), the increment autocovariances, and the refusal of bad models."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy as sp

from carousel_theory import noise_model, symbols
from carousel_theory.noise_model import (
    QUANTIZATION_ALLAN_VARIANCE,
    RRW_ALLAN_VARIANCE,
    WHITE_ALLAN_VARIANCE,
    NoiseModel,
    ar_autocovariance,
    increment_autocovariance,
    spectral_density,
    term_allan_variance,
    unit_flicker_increment_autocovariance,
)

EXACT_INCREMENTS = {"white": {0: 2, 1: -1}, "rrw": {0: 1}, "quantization": {0: 6, 1: -4, 2: 1}}
CLOSED_FORMS = {
    "white": WHITE_ALLAN_VARIANCE.subs(symbols.white_sample_variance, 1),
    "rrw": RRW_ALLAN_VARIANCE.subs(symbols.rrw_increment_variance, 1),
    "quantization": QUANTIZATION_ALLAN_VARIANCE.subs(
        {symbols.quantization_step: 1, symbols.sample_interval: 1}
    ),
}


def _haar_on_increments(m: int) -> list[int]:
    """The cluster-mean difference as weights on the increments z: the triangle 1, 2, …, m, …, 1."""
    return [min(k + 1, 2 * m - 1 - k) for k in range(2 * m - 1)]


@pytest.mark.parametrize("term", sorted(EXACT_INCREMENTS))
@pytest.mark.parametrize("m", [1, 2, 3, 5, 8])
def test_finite_terms_exact_two_ways(term, m):
    # Var d = gᵀ Γ_z g with the exact integer increment autocovariance, in Fractions; against SymPy.
    taps = EXACT_INCREMENTS[term]
    g = _haar_on_increments(m)
    variance = sum(
        Fraction(g[a] * g[b] * taps.get(abs(a - b), 0)) for a in range(len(g)) for b in range(len(g))
    )
    exact = variance / (2 * m * m)
    assert sp.Rational(exact.numerator, exact.denominator) == CLOSED_FORMS[term].subs(symbols.cluster_size, m)
    numeric = term_allan_variance(term, [m])[0]
    assert numeric == pytest.approx(float(exact), rel=1e-15)
    gamma = increment_autocovariance(term, 4)
    assert [gamma[k] for k in range(3)] == [taps.get(k, 0) for k in range(3)]


def test_ar1_allan_variance_against_exact_dense_sum():
    phi = Fraction(1, 2)
    for m in (1, 2, 3, 6):
        haar = [-1] * m + [1] * m
        variance = sum(
            haar[a] * haar[b] * phi ** abs(a - b) / (1 - phi * phi)
            for a in range(2 * m)
            for b in range(2 * m)
        )
        expected = float(variance / (2 * m * m))
        assert term_allan_variance("ar", [m], ar_coefficients=(0.5,))[0] == pytest.approx(expected, rel=1e-13)


def test_ar2_autocovariance_solves_yule_walker_and_matches_spectrum():
    phi = (0.6, -0.3)
    gamma = ar_autocovariance(phi, 40)
    assert gamma[0] - phi[0] * gamma[1] - phi[1] * gamma[2] == pytest.approx(1.0, rel=1e-14)
    for k in range(1, 10):
        assert gamma[k] == pytest.approx(phi[0] * gamma[k - 1] + phi[1] * gamma[abs(k - 2)], abs=1e-15)
    omega = np.linspace(-np.pi, np.pi, 20001)
    density = spectral_density("ar", omega, ar_coefficients=phi)
    for k in (0, 1, 3):
        integral = np.trapezoid(density * np.cos(k * omega), omega) / (2 * np.pi)
        assert integral == pytest.approx(gamma[k], rel=1e-6, abs=1e-9)


@pytest.mark.parametrize(
    "phi", [(0.8,), (0.9997,), (-0.6,), (0.5, 0.2), (1.98, -0.9801), (0.6, 0.39), (0.5, 0.2, 0.1)]
)
def test_ar_autocovariance_follows_its_recursion_out_to_its_reach(phi):
    # Beyond γ(0 … p) every value is Σ_j φ_j γ(k − j) of the values before it (AR(1): the running product,
    # out to 1.5·10⁵ lags at φ = 0.9997; AR(p) beyond 2048 lags: the recursion as an all-pole filter),
    # to the rounding of one step; the values stop at the reach of ρ^k ≥ AR_TRUNCATION and are 0 after.
    reach = len(phi) + 2 + noise_model.ar_decay_lags(phi)
    gamma = np.asarray(ar_autocovariance(phi, reach + 10))
    p = len(phi)
    recursed = np.array([np.dot(phi, gamma[k - p : k][::-1]) for k in range(p + 1, reach)])
    magnitude = np.array([np.dot(np.abs(phi), np.abs(gamma[k - p : k])) for k in range(p + 1, reach)])
    assert np.all(np.abs(gamma[p + 1 : reach] - recursed) <= 4 * np.finfo(float).eps * magnitude)
    assert np.all(gamma[reach:] == 0.0)
    assert abs(gamma[reach - 1]) > 0.0


@pytest.mark.parametrize("dps", [30, 50])
@pytest.mark.parametrize("d", [0.3, 0.5, 0.8])
def test_flicker_allan_variance_against_spectral_integral(d, dps):
    # σ_A²(m) = (1/2m²) ∫ 4 sin⁴(mω/2)/sin²(ω/2) · (4 sin²(ω/2))^{−d} dω/2π: the stationary differences.
    with mpmath.workdps(dps):
        for m in (1, 2, 4):
            dd = mpmath.mpf(d)

            def integrand(omega, m=m, dd=dd):
                s = mpmath.sin(omega / 2)
                return 4 * mpmath.sin(m * omega / 2) ** 4 / s**2 * (4 * s**2) ** (-dd)

            nodes = [mpmath.pi * k / m for k in range(m + 1)]
            exact = 2 * mpmath.quad(integrand, nodes) / (2 * mpmath.pi) / (2 * m * m)
            assert term_allan_variance("flicker", [m], d)[0] == pytest.approx(float(exact), rel=1e-12)


def test_flicker_increments_sum_to_zero_and_are_negative():
    gamma = increment_autocovariance("flicker", 200_000, 0.6)
    assert np.all(gamma[1:] < 0)
    assert np.all(np.diff(np.abs(gamma[1:])) < 0)
    # Σ_k γ_z(k) over all lags is the increments' spectrum at 0, which is 0 for d < 1: the partial sum
    # tends to 0 as the tail, which is of order K^{2d−2}.
    partial = gamma[0] + 2 * gamma[1:].sum()
    assert abs(partial) < 5 * 200_000 ** (2 * 0.6 - 2)


def _one_block(d: float, lags: int, monkeypatch) -> np.ndarray:
    """γ_z of 1/f with every lag in one block: one running product, the form the blocks must reproduce."""
    monkeypatch.setattr(noise_model, "_FLICKER_BLOCK", 1 << 40)
    noise_model._flicker_increment_autocovariance.cache_clear()
    return noise_model._flicker_increment_autocovariance(d, lags)


@pytest.mark.parametrize(("block", "lags"), [(7, 1), (7, 2), (7, 8), (7, 9), (7, 50), (1 << 20, 2_500_000)])
def test_flicker_blocks_equal_one_cumulative_product_bit_for_bit(monkeypatch, block, lags):
    try:
        for d in (0.1, 0.5, 0.83):
            whole = _one_block(d, lags, monkeypatch)
            monkeypatch.setattr(noise_model, "_FLICKER_BLOCK", block)
            noise_model._flicker_increment_autocovariance.cache_clear()
            got = noise_model._flicker_increment_autocovariance(d, lags)
            assert np.array_equal(got, whole)
            assert not got.flags.writeable
    finally:
        noise_model._flicker_increment_autocovariance.cache_clear()


def test_flicker_increments_against_gamma_functions():
    # γ_z(k) = Γ(3 − 2d) Γ(k − 1 + d) / (Γ(2 − d) Γ(d − 1) Γ(k + 2 − d)), the ARFIMA(0, d − 1, 0) form.
    d = mpmath.mpf(6) / 10
    gamma = increment_autocovariance("flicker", 3_000_000, 0.6)
    with mpmath.workdps(40):  # k − 1 + d must not be rounded at k ≈ 3·10⁶
        for k in (0, 1, 5, 1 << 20, (1 << 20) + 1, 2_999_999):
            exact = (
                mpmath.gamma(3 - 2 * d)
                * mpmath.gamma(k - 1 + d)
                / (mpmath.gamma(2 - d) * mpmath.gamma(d - 1) * mpmath.gamma(k + 2 - d))
            )
            # Relative only: γ_z is ~1e-12 at these lags, below pytest.approx's default absolute slack.
            assert gamma[k] == pytest.approx(float(exact), rel=5e-10, abs=0.0)


def test_model_allan_variance_adds_terms():
    model = NoiseModel(
        sample_rate=100.0,
        white_variance=2.0,
        rrw_variance=0.5,
        quantization=0.01,
        flicker_variance=0.3,
        flicker_d=0.4,
        ar_variance=0.7,
        ar_coefficients=(0.9,),
    )
    sizes = np.array([1, 2, 8, 64])
    expected = (
        2.0 * term_allan_variance("white", sizes)
        + 0.5 * term_allan_variance("rrw", sizes)
        + (0.01 * 100.0) ** 2 * term_allan_variance("quantization", sizes)
        + 0.3 * term_allan_variance("flicker", sizes, 0.4)
        + 0.7 * term_allan_variance("ar", sizes, ar_coefficients=(0.9,))
    )
    np.testing.assert_allclose(model.allan_variance(sizes), expected, rtol=1e-14)
    assert model.long_run_ar_variance == pytest.approx(0.7 / 0.1**2)


def test_long_averages_of_ar_see_its_long_run_variance():
    values = term_allan_variance("ar", [4096], ar_coefficients=(0.8,))[0]
    assert values * 4096 == pytest.approx(1 / 0.2**2, rel=2e-3)


BAD_MODELS = [
    ("negative-white", {"white_variance": -1.0}, "white_variance=-1.0"),
    ("d-zero", {"flicker_d": 0.0}, "flicker_d=0.0"),
    ("d-one", {"flicker_d": 1.0}, "flicker_d=1.0"),
    ("ar-list", {"ar_coefficients": [0.5]}, "must be a tuple"),
    ("ar-unit-root", {"ar_coefficients": (1.0,)}, "stationary"),
    ("ar-explosive", {"ar_coefficients": (0.5, 0.6)}, "stationary"),
    ("ar-text", {"ar_coefficients": ("a",)}, "ar_coefficients"),
    ("negative-ar-variance", {"ar_variance": -2.0}, "ar_variance=-2.0"),
    ("ar-without-coefficients", {"ar_variance": 1.0}, r"ar_variance=1.0: an AR term needs ar_coefficients"),
    ("rate", {"sample_rate": 0.0}, "sample_rate=0.0"),
]


@pytest.mark.parametrize(("options", "message"), [b[1:] for b in BAD_MODELS], ids=[b[0] for b in BAD_MODELS])
def test_bad_models_are_refused(options, message):
    with pytest.raises((ValueError, TypeError), match=message):
        NoiseModel(**{"sample_rate": 1.0, **options})


BAD_TERM_CALLS = [
    ("size-zero", lambda: term_allan_variance("white", [0]), ValueError, ">= 1 sample"),
    ("size-negative", lambda: term_allan_variance("white", [-2]), ValueError, ">= 1 sample"),
    ("size-fraction", lambda: term_allan_variance("white", [2.5]), TypeError, "must be integers"),
    ("size-nan", lambda: term_allan_variance("white", [np.nan]), TypeError, "must be integers"),
    ("size-empty", lambda: term_allan_variance("white", []), ValueError, "non-empty 1-D"),
    ("model-size-zero", lambda: NoiseModel(1.0, white_variance=1.0).allan_variance([0]), ValueError, ">= 1"),
    ("d-above", lambda: term_allan_variance("flicker", [2], flicker_d=1.5), ValueError, "flicker_d=1.5"),
    ("d-nan", lambda: term_allan_variance("flicker", [2], flicker_d=np.nan), ValueError, "flicker_d=nan"),
    ("ar-none", lambda: term_allan_variance("ar", [2]), ValueError, "at least one coefficient"),
    (
        "ar-unit-root",
        lambda: increment_autocovariance("ar", 5, ar_coefficients=(1.5,)),
        ValueError,
        "stationary",
    ),
    (
        "increment-d",
        lambda: increment_autocovariance("flicker", 5, flicker_d=1.5),
        ValueError,
        "flicker_d=1.5",
    ),
    ("increment-lags", lambda: increment_autocovariance("white", 2.5), TypeError, "lags=2.5"),
    ("unit-flicker-lags", lambda: unit_flicker_increment_autocovariance(0.5, 0), ValueError, "lags=0"),
    ("unit-flicker-d", lambda: unit_flicker_increment_autocovariance(1.0, 5), ValueError, "flicker_d=1.0"),
    ("spectrum-d", lambda: spectral_density("flicker", np.array([0.1]), flicker_d=1.5), ValueError, "1.5"),
    ("spectrum-nan", lambda: spectral_density("white", np.array([np.nan])), ValueError, "must be finite"),
    ("decay-unit-root", lambda: noise_model.ar_decay_lags((1.0,)), ValueError, "stationary"),
    ("decay-empty", lambda: noise_model.ar_decay_lags(()), ValueError, "at least one coefficient"),
    (
        "long-run-negative",
        lambda: noise_model.ar_long_run_variance(-1.0, (0.5,)),
        ValueError,
        "variance=-1.0",
    ),
    (
        "long-run-explosive",
        lambda: noise_model.ar_long_run_variance(1.0, (0.6, 0.6)),
        ValueError,
        "stationary",
    ),
    ("stationary-nan", lambda: noise_model.stationary_ar((np.nan,)), ValueError, "ar_coefficients"),
    ("stationary-none", lambda: noise_model.stationary_ar(None), TypeError, "must be a tuple"),
    ("variogram-empty", lambda: noise_model.variogram(np.array([])), ValueError, "γ_z"),
]


@pytest.mark.parametrize(
    ("call", "error", "message"), [b[1:] for b in BAD_TERM_CALLS], ids=[b[0] for b in BAD_TERM_CALLS]
)
def test_bad_term_arguments_are_refused_by_name(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_unknown_term_is_refused():
    with pytest.raises(ValueError, match="term='pink'"):
        term_allan_variance("pink", [1])
    with pytest.raises(ValueError, match="term='pink'"):
        NoiseModel(sample_rate=1.0).unit("pink")


def test_reexported_from_fitting():
    from carousel_theory import fitting

    assert fitting.NoiseModel is NoiseModel


@pytest.mark.parametrize("coefficients", [(0.5,), (0.99,), (0.999,), (1.2, -0.5), (0.3, 0.2, 0.1)])
def test_ar_reach_is_where_the_slowest_root_falls_below_the_truncation(coefficients):
    # ρ from a 50-digit polynomial root finder: ρ^k ≥ AR_TRUNCATION at k = decay, below at decay + 1.
    with mpmath.workdps(50):
        roots = mpmath.polyroots([1] + [-mpmath.mpf(c) for c in coefficients], maxsteps=200, extraprec=200)
        rho = max(abs(r) for r in roots)
        decay = int(mpmath.floor(mpmath.log(mpmath.mpf(noise_model.AR_TRUNCATION)) / mpmath.log(rho)))
    assert noise_model.ar_decay_lags(coefficients) == decay
    reach = noise_model.ar_increment_reach(coefficients)
    assert reach == len(coefficients) + 2 + decay
    # γ_z(k) = 2γ(k) − γ(k − 1) − γ(k + 1) is non-zero at the reach and exactly zero beyond it.
    gamma = noise_model.ar_autocovariance(coefficients, reach + 4)
    increments = 2 * gamma[1:-1] - gamma[:-2] - gamma[2:]  # lags 1 … reach + 2
    assert increments[reach - 1] != 0.0
    assert not np.any(increments[reach:])
