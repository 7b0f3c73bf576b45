"""What the noise model TIM 2014 prints for its static test (Table III, white noise + RRW, with the
variance propagation of §III) predicts for each number of §V-C, §V-D and §VI.

The static recording and the field-test data of the paper are not public, so a measured number
cannot be recomputed; these helpers compute the model's prediction from the closed forms of
:mod:`carousel_theory.formulas`. They serve the claims of §V-C, §V-D and §VI and the derivation
document of §V.

Units. Table III gives σ_WN² "(τ = 1 s)" in (rad/s)², the variance of a 1-s average of white noise,
and σ_q² in (rad/s)²/s, the rate of growth of the RRW variance. At the sample rate f_s the discrete
model of §II has the per-sample white variance σ_WN²·f_s·(1 s) and the per-sample RRW increment
variance σ_q²/f_s (see :mod:`carousel_theory.units`).
"""

from __future__ import annotations

import functools
from fractions import Fraction

import mpmath
import sympy as sp

from carousel_theory.claims._common import DIGITS, exact_mpf, registry_formula

__all__ = [
    "DURATION",
    "REPORTED_AVERAGED_ANGLE_DEG",
    "REPORTED_CAROUSELLED_ANGLE_DEG",
    "REPORTED_EXCEEDANCE",
    "SAMPLES_PER_BIN",
    "SAMPLE_RATE",
    "TABLE_III",
    "allan_minimum_white_rrw",
    "angle_standard_deviations",
    "averaged_rrw_sum_of_covariances",
    "band_variances",
    "bin_duration",
    "binomial_interval",
    "binomial_probabilities",
    "binomial_tail_at_least",
    "degrees",
    "flicker_floor_factor",
    "number_of_bins",
    "per_sample",
    "standard_normal_two_sided_tail",
]

#: Table III of TIM 2014 (both renderings agree, see ``TIM2014-render-table3``):
#: σ_WN² at τ = 1 s ((rad/s)²), σ_q² ((rad/s)²/s), bias instability (rad/s).
TABLE_III = {
    "x": {"white": Fraction(3, 10**7), "rrw": Fraction(3, 10**10), "bias_instability": Fraction(1, 10**5)},
    "y": {"white": Fraction(1, 10**7), "rrw": Fraction(2, 10**10), "bias_instability": Fraction(6, 10**5)},
}


#: §V-C: one hour at 100 Hz, bins of N = 200 samples.
SAMPLE_RATE = 100  # Hz


SAMPLES_PER_BIN = 200


DURATION = 3600  # s


#: §V-C, §V-D: the reported numbers.
REPORTED_EXCEEDANCE = Fraction(65, 1000)


REPORTED_AVERAGED_ANGLE_DEG = 600


REPORTED_CAROUSELLED_ANGLE_DEG = Fraction(3, 2)


def degrees(radians: mpmath.mpf) -> mpmath.mpf:
    return radians * 180 / mpmath.pi


def per_sample(gyro: str) -> tuple[Fraction, Fraction]:
    """(white per-sample variance, RRW per-sample increment variance) of a Table III gyro at 100 Hz."""
    parameters = TABLE_III[gyro]
    # A 1-s average holds f_s samples, so its variance is the per-sample variance / f_s.
    white = parameters["white"] * SAMPLE_RATE
    # The RRW variance grows by σ_q² per second, i.e. by σ_q²/f_s per sample.
    rrw = parameters["rrw"] / SAMPLE_RATE
    return white, rrw


def bin_duration() -> Fraction:
    return Fraction(SAMPLES_PER_BIN, SAMPLE_RATE)


def number_of_bins() -> int:
    bins = Fraction(DURATION) / bin_duration()
    if bins.denominator != 1:
        raise ValueError(f"one hour is not a whole number of bins: {bins}")
    return int(bins)


def averaged_rrw_sum_of_covariances() -> sp.Expr:
    """Σ_{a,b=1}^{K} Cov(bin a, bin b) of averaged RRW (unit increments), as a closed form in N and K.

    From ``rrw_average_cov``: the diagonal a = b and the pairs b = a + j, j ≥ 1, summed exactly.
    """
    covariance = registry_formula("rrw_average_cov").expression
    a, b = sp.Symbol("a", integer=True, positive=True), sp.Symbol("b", integer=True, positive=True)
    # The registry's symbols carry assumptions; substitute by name so that they match.
    names = {str(s): s for s in covariance.free_symbols}
    a, b, N = names.get("a", a), names.get("b", b), names["N"]
    j = sp.Symbol("j_offset", integer=True, positive=True)
    bins = sp.Symbol("K", integer=True, positive=True)
    diagonal = covariance.subs(b, a)
    off_diagonal = covariance.subs(b, a + j)  # Min(a, a + j) = a and a ≠ a + j, decided by SymPy
    total = sp.summation(diagonal, (a, 1, bins)) + 2 * sp.summation(
        sp.summation(off_diagonal, (j, 1, bins - a)), (a, 1, bins - 1)
    )
    return sp.factor(sp.simplify(total)), N, bins


@functools.cache
def angle_standard_deviations() -> dict[str, dict[str, mpmath.mpf]]:
    """σ (rad) of the angle integrated over the whole test, per error component, Table III model.

    Angle = T Σ_k (bin estimate k). Averaged gyro: white bins are independent (``white_average_var``),
    RRW bins are correlated (Σ_{a,b} ``rrw_average_cov``). Carouselled estimate: every bin has the
    same variance and distinct bins are uncorrelated (TIM 2014 eq. (17)), so the K bin variances add;
    the x gyro carries the sine weights and the y gyro the cosine weights (eq. (5)).
    """
    T = bin_duration()
    K = number_of_bins()
    N = SAMPLES_PER_BIN
    total, N_symbol, K_symbol = averaged_rrw_sum_of_covariances()
    rrw_sum = total.subs({N_symbol: N, K_symbol: K})
    white_bin = registry_formula("white_average_var").exact(N=N)
    result = {}
    for gyro in ("x", "y"):
        white, rrw = per_sample(gyro)
        result[f"averaged {gyro}"] = {
            "white": mpmath.sqrt(exact_mpf(sp.Rational(T) ** 2 * K * white_bin * sp.Rational(white))),
            "rrw": mpmath.sqrt(exact_mpf(sp.Rational(T) ** 2 * rrw_sum * sp.Rational(rrw))),
        }
    (white_x, rrw_x), (white_y, rrw_y) = per_sample("x"), per_sample("y")
    white_carousel = registry_formula("white_carousel_var").exact(N=N, var_x=white_x, var_y=white_y)
    rrw_carousel = registry_formula("rrw_carousel_var_sin").evaluate(digits=DIGITS, N=N) * exact_mpf(
        rrw_x
    ) + registry_formula("rrw_carousel_var_cos").evaluate(digits=DIGITS, N=N) * exact_mpf(rrw_y)
    result["carouselled"] = {
        "white": mpmath.sqrt(exact_mpf(sp.Rational(T) ** 2 * K * white_carousel)),
        "rrw": mpmath.sqrt(exact_mpf(T) ** 2 * K * rrw_carousel),
    }
    for parts in result.values():
        parts["total"] = mpmath.sqrt(parts["white"] ** 2 + parts["rrw"] ** 2)
    return result


def standard_normal_two_sided_tail(z: mpmath.mpf) -> mpmath.mpf:
    return mpmath.erfc(z / mpmath.sqrt(2))


def band_variances() -> dict[str, tuple[mpmath.mpf, mpmath.mpf]]:
    """Variance ((rad/s)²) of the first and last bin estimate of Fig. 7: white + RRW, Table III."""
    N, K = SAMPLES_PER_BIN, number_of_bins()
    bands = {}
    for gyro in ("x", "y"):
        white, rrw = per_sample(gyro)
        first, last = (
            exact_mpf(
                registry_formula("white_average_var").exact(N=N) * sp.Rational(white)
                + registry_formula("rrw_average_var").exact(N=N, k=k) * sp.Rational(rrw)
            )
            for k in (1, K)
        )
        bands[f"averaged {gyro}"] = (first, last)
    (white_x, rrw_x), (white_y, rrw_y) = per_sample("x"), per_sample("y")
    carousel = exact_mpf(registry_formula("white_carousel_var").exact(N=N, var_x=white_x, var_y=white_y)) + (
        registry_formula("rrw_carousel_var_sin").evaluate(digits=DIGITS, N=N) * exact_mpf(rrw_x)
        + registry_formula("rrw_carousel_var_cos").evaluate(digits=DIGITS, N=N) * exact_mpf(rrw_y)
    )
    bands["carouselled"] = (carousel, carousel)
    return bands


def binomial_probabilities(trials: int, probability: mpmath.mpf) -> list[mpmath.mpf]:
    """P(X = x), x = 0 … trials, of Binomial(trials, probability), by the ratio of consecutive terms."""
    terms = [(1 - probability) ** trials]
    ratio = probability / (1 - probability)
    for x in range(trials):
        terms.append(terms[-1] * (trials - x) / (x + 1) * ratio)
    return terms


def binomial_tail_at_least(count: int, trials: int, probability: mpmath.mpf) -> mpmath.mpf:
    return mpmath.fsum(binomial_probabilities(trials, probability)[count:])


def binomial_interval(trials: int, probability: mpmath.mpf, level: mpmath.mpf) -> tuple[int, int]:
    """The central ``level`` interval of Binomial(trials, probability): (lowest, highest) count, each tail
    outside it holding at most (1 − level)/2."""
    terms = binomial_probabilities(trials, probability)
    tail = (1 - level) / 2
    cumulative, lowest = mpmath.mpf(0), 0
    for x, term in enumerate(terms):
        if cumulative + term > tail:
            lowest = x
            break
        cumulative += term
    cumulative, highest = mpmath.mpf(0), trials
    for x in range(trials, -1, -1):
        if cumulative + terms[x] > tail:
            highest = x
            break
        cumulative += terms[x]
    return lowest, highest


def allan_minimum_white_rrw(gyro: str) -> tuple[mpmath.mpf, mpmath.mpf]:
    """(τ*, min over τ of σ_WN²/τ + σ_q² τ/3): the lowest Allan variance white noise and RRW allow."""
    white, rrw = (exact_mpf(TABLE_III[gyro][key]) for key in ("white", "rrw"))
    return mpmath.sqrt(3 * white / rrw), 2 * mpmath.sqrt(white * rrw / 3)


def flicker_floor_factor() -> mpmath.mpf:
    # Allan deviation of 1/f noise with bias instability B is √(2 ln 2/π)·B (IEEE Std 952, Annex C);
    # carousel_theory.units.BIAS_INSTABILITY_FACTOR holds the same number in float64.
    return mpmath.sqrt(2 * mpmath.log(2) / mpmath.pi)
