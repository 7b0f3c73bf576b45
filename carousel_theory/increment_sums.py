"""Fourth sums of increment autocovariances: the Allan variance and the τ cross-covariances in O(1) per lag.

Setting (TIM 2014 §II; :mod:`carousel_theory.noise_model`). With the increments z_t = y_t − y_{t−1} and
their autocovariance γ_z, the cluster-mean difference at m samples is d_s = Σ_k g_m[k] z_{s+1+k}, g_m the
triangle 1, 2, …, m, …, 1, and the cross-covariance of two such differences at offset δ is

    c_ij(δ) = Σ_u W_ij(u) γ_z(δ + u) = Σ_q w_q H(q − δ),    H(x) = Σ_k γ_z(k) R₃(x − k),

where W_ij = Σ w_q R₃(q − ·) is a sum of nine cubic ramps R₃(x) = C(x + 3, 3) (x ≥ −3, else 0) with integer
weights w_q that annihilate every cubic polynomial (their generating function has a zero of order four at
x = 1). H is a fourth sum of γ_z: its backward fourth difference is γ_z, ∇⁴H = γ_z, and any other fourth
sum differs from it by a cubic, which the weights remove. For m_i = m_j = m the positions are
q + 2 ∈ {2m, m, 0, −m, −2m} with weights 1, −4, 6, −4, 1, so Var d = c_mm(0) and the Allan variance is

    σ_A²(m) = [6H(−2) − 4(H(m − 2) + H(−m − 2)) + H(2m − 2) + H(−2m − 2)] / (2m²).

1/f (fractionally integrated, any 0 < d < 1; TIM 2014 eq. (3))
    γ_z(k) = σ_w² C_d Γ(k + d − 1)/Γ(k + 2 − d), C_d = Γ(3 − 2d)/(Γ(2 − d)Γ(d − 1)), for every integer k
    (the Gamma ratio is even on the integers, by the reflection formula). The ratio telescopes:
    Γ(x + 1 + e)/Γ(x + 1 − e) − Γ(x + e)/Γ(x − e) = 2e Γ(x + e)/Γ(x + 1 − e), so each sum raises e by ½,
    and four sums give the closed form :data:`FLICKER_FOURTH_SUM`

        H(x) = C_d Γ(x + 3 + d)/Γ(x + 2 − d) / (16 (d − 1)(d − ½) d (d + ½)),

    even about x = −2. At d = ½ the numerator Γ(j + 3/2)/Γ(j − ½) = j² − ¼ (j = x + 2) is a quadratic,
    which the weights remove; near d = ½ the evaluator subtracts it and divides exactly (a removable
    singularity), so every d in (0, 1) is evaluated to about 1e-12 relative.

Evaluation at large arguments (j = |x + 2| ≥ 16; the Gauss nodes of the lag quadrature)
    With F(j) = Γ(j + 1 + d)/Γ(j − d) = Γ(j + (1 + s)/2)/Γ(j + (1 − s)/2), s = 1 + 2d, the Stirling series
    of the two log Γ (with Bernoulli polynomials, B_n(1 − a) = (−1)^n B_n(a)) keeps only even powers:

        log F(j) = s log j + Σ_k e_k(s) j^{−2k},   e_k(s) = −2 B_{2k+1}((1 + s)/2)/(2k(2k + 1))

    (:data:`LOG_RATIO_COEFFICIENTS`, polynomials in s, checked against SymPy's expansion of the log Γ
    difference). Eight terms below j = 256 and three above; the first omitted terms are
    |e_9| j^{−18} ≤ 0.98·16^{−18} ≈ 2e-22 and |e_4| j^{−8} ≤ ¼·256^{−8} ≈ 1.4e-20 (extrema of the
    polynomials on s ∈ [1, 3] found exactly in the tests), far below the rounding of log and exp
    (about 50 ulps at j = 10⁷). Near d = ½ the subtracted form is taken without cancellation:
    F − (j² − ¼) = (j² − ¼)·expm1((s − 2)Λ), Λ = log j + Σ_k (e_k(s) − e_k(2))/(s − 2) j^{−2k}
    (:data:`LOG_RATIO_SLOPES`, exact polynomial quotients), so [F − (j² − ¼)]/(d − ½) =
    (j² − ¼)·2Λ·exprel(2(d − ½)Λ), which is Λ-smooth through d = ½.

Σ_{j≤N} (Γ(j + d)/Γ(j))² in O(1) (:func:`squared_rising_factorial_sum`; the variance of a 1/f record mean)
    The same series with σ = d and w = j + (d − 1)/2 gives (Γ(j + d)/Γ(j))² = Σ_k a_k w^{2d − 2k} (the
    exponential of 2 Σ_k e_k(d) w^{−2k} as a power series, nine terms, first omitted below 1e-30 relative
    at w ≥ 127); terms j < 128 are summed one by one, and each Σ_j w_j^p beyond is a difference of
    Hurwitz ζ(−p, ·) values from their Euler–Maclaurin series (eight Bernoulli terms at arguments ≥ 127,
    the leading pair in exprel form so that p = −1, i.e. d = ½, needs no special case). Tested against
    40-digit sums over every j up to 2.5·10⁵ to 1e-13.

Finite γ_z (autoregressive terms, truncated where their envelope is below
:data:`carousel_theory.noise_model.AR_TRUNCATION`)
    H(x) = Σ_{|k|≤T} γ_z(k) R₃(x − k) directly for |x| ≤ T + 3, 0 for x < −T − 3, and, for x > T − 3, where
    R₃ is the cubic p(x) = (x + 1)(x + 2)(x + 3)/6 at every k, the exact Taylor form
    Σ_r (−1)^r M_r p^{(r)}(x)/r! with the moments M_r = Σ_k k^r γ_z(k) (no cancellation of large values).
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np
import sympy as sp
from scipy import special

from carousel_theory import symbols

__all__ = [
    "FLICKER_FOURTH_SUM",
    "FLICKER_INCREMENT_AUTOCOVARIANCE",
    "allan_variance_from_fourth_sum",
    "finite_fourth_sum",
    "flicker_allan_variance_closed",
    "flicker_fourth_sum",
    "flicker_fourth_sum_at_distance",
    "flicker_increment_difference",
    "flicker_normalisation",
    "log_ratio_coefficient",
    "rising_factorial",
    "squared_rising_factorial_sum",
]

_d = symbols.d
_lag = sp.Symbol("x", integer=True)
_normalisation = sp.gamma(3 - 2 * _d) / (sp.gamma(2 - _d) * sp.gamma(_d - 1))
#: γ_z(k) of the 1/f increments at unit σ_w², any integer k (ARFIMA(0, d − 1, 0); TIM 2014 eq. (3)).
FLICKER_INCREMENT_AUTOCOVARIANCE: sp.Expr = _normalisation / sp.rf(_lag + _d - 1, 3 - 2 * _d)
#: A fourth sum H of :data:`FLICKER_INCREMENT_AUTOCOVARIANCE`: ∇⁴H(x) = γ_z(x) for every integer x.
FLICKER_FOURTH_SUM: sp.Expr = (
    _normalisation
    * sp.rf(_lag + 2 - _d, 1 + 2 * _d)
    / (16 * (_d - 1) * (_d - sp.Rational(1, 2)) * _d * (_d + sp.Rational(1, 2)))
)

# Stirling series of log Γ: B_{2k}/(2k(2k − 1)) for k = 1 … 8 (enough below 1e-17 for arguments ≥ 16).
_STIRLING = tuple(float(sp.bernoulli(2 * k) / (2 * k * (2 * k - 1))) for k in range(1, 9))
_STIRLING_FROM = 16.0


def rising_factorial(a: Any, step: float) -> np.ndarray:
    """Γ(a + step)/Γ(a) to a few 1e-14 relative (the rounding of a logarithm of size step·log a).

    scipy's ``poch`` below a = 16; above it, for 1 ≤ step ≤ 3, the even series of the module text at
    w = a + (step − 1)/2 (one logarithm, a polynomial in w⁻², one exponential), and for other steps the
    Stirling difference (a − ½) log(1 + step/a) + step log(a + step) − step + Σ_k c_k [(a + step)^{1−2k} −
    a^{1−2k}]; in both no difference of two large log Γ values is formed (scipy's ``poch`` loses about
    1e-11 near a = 10⁴).
    """
    a = np.asarray(a, dtype=np.float64)
    result = np.empty(a.shape)
    large = a >= _STIRLING_FROM
    if not np.all(large):
        result[~large] = special.poch(a[~large], step)
    if 1.0 <= step <= 3.0:  # the even series of the module text, w = a + (step − 1)/2 ≥ 16
        result[large] = _even_ratio(a[large] + (step - 1.0) / 2.0, step)
        return result
    for low, high, count in ((_STIRLING_FROM, 1e3, len(_STIRLING)), (1e3, np.inf, 3)):
        # Above a = 1000 three terms leave less than 1e-24 (the fourth is B₈/56 · a⁻⁷).
        chosen = (a >= low) & (a < high)
        base = a[chosen]
        shifted = base + step
        logarithm = (base - 0.5) * np.log1p(step / base) + step * np.log(shifted) - step
        inverse_shifted, inverse_base = 1.0 / shifted, 1.0 / base
        square_shifted, square_base = inverse_shifted**2, inverse_base**2
        for coefficient in _STIRLING[:count]:  # c_k [(a + step)^{1−2k} − a^{1−2k}], powers by products
            logarithm += coefficient * (inverse_shifted - inverse_base)
            inverse_shifted, inverse_base = inverse_shifted * square_shifted, inverse_base * square_base
        result[chosen] = np.exp(logarithm)
    return result


# The numeric evaluator: the SymPy factors, lambdified once; the rising factorial is the one above.
_normalisation_numeric = sp.lambdify(_d, _normalisation, "scipy")
_rising_numeric = sp.lambdify(
    (_lag, _d), sp.rf(_lag + 2 - _d, 1 + 2 * _d), [{"RisingFactorial": rising_factorial}, "scipy"]
)
_denominator = 16 * (_d - 1) * (_d - sp.Rational(1, 2)) * _d * (_d + sp.Rational(1, 2))
_regular_denominator_numeric = sp.lambdify(_d, sp.cancel(_denominator / (_d - sp.Rational(1, 2))), "scipy")
#: Within this distance of d = ½ the d = ½ quadratic is subtracted and the ratio taken by series.
_NEAR_HALF = 0.1
_SERIES_TERMS = 26


def flicker_normalisation(d: float) -> float:
    """C_d = Γ(3 − 2d)/(Γ(2 − d)Γ(d − 1)) of :data:`FLICKER_INCREMENT_AUTOCOVARIANCE` (negative)."""
    return float(_normalisation_numeric(float(d)))


def flicker_increment_difference(x: Any, d: float, order: int = 0) -> np.ndarray:
    """Δ^r γ_z(x), r = ``order``, of :data:`FLICKER_INCREMENT_AUTOCOVARIANCE` at unit σ_w² (forward
    differences): C_d (2d − 3)_r↓ Γ(x + d − 1)/Γ(x + 2 − d + r), at real x ≥ 1 (γ_z itself at r = 0; the
    Gamma ratio is even on the integers, so γ_z(|x|) gives every integer lag)."""
    falling = math.prod(2.0 * d - 3.0 - k for k in range(order))
    base = flicker_normalisation(d) * falling
    return base / rising_factorial(np.asarray(x, dtype=np.float64) + d - 1.0, 3.0 - 2.0 * d + order)


@functools.lru_cache(maxsize=256)
def _polygamma_at_half_integers(a: tuple[float, ...]) -> np.ndarray:
    """ψ^{(r−1)}(a), r = 1 … R, at half-integers a < 16 (what integer lags give: the Allan variance's
    points give the same few for every d), kept for the next call."""
    rows = special.polygamma(np.arange(_SERIES_TERMS)[:, None], np.array(a))
    rows.setflags(write=False)
    return rows


def _polygamma_rows(a: np.ndarray) -> np.ndarray:
    """ψ^{(r−1)}(a), r = 1 … R, one row per r, in one call (the same values as one call per order or per
    a: a ufunc, element by element); at half-integers a kept per set of a."""
    if np.all(2.0 * a == np.rint(2.0 * a)):
        return _polygamma_at_half_integers(tuple(a.tolist()))
    return special.polygamma(np.arange(_SERIES_TERMS)[:, None], a)


def _log_gamma_slope(a: np.ndarray, step: float) -> np.ndarray:
    """(log|Γ(a + step)| − log|Γ(a)|)/step for a ≥ ½, |step| ≤ 0.1, and ψ(a) at step = 0.

    Below a = 16 the Taylor series Σ ψ^{(r−1)}(a) step^{r−1}/r! (terms fall at least like (2|step|)^r/r);
    above, the Stirling difference of :func:`rising_factorial` divided by the step term by term, each
    through log(1 + x)/x and (eˣ − 1)/x, x = step/a, so that no difference of large values is formed.
    Each series is formed as one array of its terms, one row per term, added row after row (a running
    sum down the rows: the additions of a loop over the terms, in its order).
    """
    a = np.asarray(a, dtype=np.float64)
    result = np.empty_like(a)
    small = a < _STIRLING_FROM
    if np.any(small):
        result[small] = _taylor_slope(a[small], step)
        if np.all(small):
            return result
    large = a[~small]
    ratio = step / large
    log_step = np.log1p(ratio)
    log_ratio = log_step / ratio if step else np.ones_like(large)
    slope = (large - 0.5) / large * log_ratio + np.log(large + step) - 1.0
    inverse, inverse_square = 1.0 / large, 1.0 / large**2
    # a^{e − 1}, e = 1 − 2k: a⁻² then a product by a⁻² per term
    powers = np.cumprod(np.vstack([inverse * inverse] + [inverse_square] * (len(_STIRLING) - 1)), axis=0)
    exponents = np.arange(1, len(_STIRLING) + 1)[:, None] * -2 + 1
    # [(a + step)^e − a^e]/step = a^{e−1} · e · exprel(e log(1 + x)) · log(1 + x)/x
    scaled = np.array([c * (1 - 2 * k) for k, c in enumerate(_STIRLING, start=1)])[:, None]
    terms = scaled * powers * special.exprel(exponents * log_step) * log_ratio
    result[~small] = np.cumsum(np.vstack([slope[None, :], terms]), axis=0)[-1]
    return result


def _taylor_slope(a: np.ndarray, step: float) -> np.ndarray:
    """Σ_{r=1}^{R} ψ^{(r−1)}(a) step^{r−1}/r! at a < 16 (:func:`_log_gamma_slope`)."""
    coefficients, factorial, power = [], 1.0, 1.0
    for r in range(1, _SERIES_TERMS + 1):
        factorial *= r
        coefficients.append(power / factorial)
        power *= step
    terms = _polygamma_rows(a) * np.array(coefficients)[:, None]
    return np.cumsum(terms, axis=0)[-1]


def _near_half_ratio(j: np.ndarray, d: float) -> np.ndarray:
    """[Γ(j + 1 + d)/Γ(j − d) − (j² − ¼)] / (d − ½) for integers j ≥ 0 and |d − ½| ≤ 0.1, without
    cancellation: (j² − ¼)(e^g − 1)/ε with ε = d − ½ and g = log of Γ(j+1+d)Γ(j−½)/(Γ(j+3/2)Γ(j−d))."""
    epsilon = d - 0.5
    # g/ε = [log Γ(j+1+d) − log Γ(j+3/2)]/ε − [log|Γ(j−d)| − log|Γ(j−½)|]/ε; at j = 0 the second bracket
    # is taken at ½ by Γ(a) = Γ(a + 1)/a, which adds −log(1 + 2ε).
    lower_argument = np.maximum(j - 0.5, 0.5)
    slope = _log_gamma_slope(j + 1.5, epsilon) + _log_gamma_slope(lower_argument, -epsilon)
    correction = 2.0 if epsilon == 0.0 else float(np.log1p(2.0 * epsilon) / epsilon)
    slope = np.where(j == 0, slope + correction, slope)
    return (j * j - 0.25) * special.exprel(epsilon * slope) * slope


_s = sp.Symbol("s", positive=True)


def log_ratio_coefficient(k: int) -> sp.Expr:
    """e_k(s) = −2 B_{2k+1}((1 + s)/2)/(2k(2k + 1)) of log Γ(j + (1 + s)/2)/Γ(j + (1 − s)/2) =
    s log j + Σ_k e_k(s) j^{−2k} (module text), a polynomial in the symbol s."""
    return sp.expand(-2 * sp.bernoulli(2 * k + 1, (1 + _s) / 2) / (2 * k * (2 * k + 1)))


#: e_1 … e_8 (:func:`log_ratio_coefficient`), the terms the evaluator uses.
LOG_RATIO_COEFFICIENTS: tuple[sp.Expr, ...] = tuple(log_ratio_coefficient(k) for k in range(1, 9))
#: (e_k(s) − e_k(2))/(s − 2), polynomials in s: the series of Λ in the module text.
LOG_RATIO_SLOPES: tuple[sp.Expr, ...] = tuple(
    sp.quo(sp.expand(e - e.subs(_s, 2)), _s - 2, _s) for e in LOG_RATIO_COEFFICIENTS
)
_log_ratio_coefficients = sp.lambdify(_s, list(LOG_RATIO_COEFFICIENTS), "math")
_log_ratio_slopes = sp.lambdify(_s, list(LOG_RATIO_SLOPES), "math")
#: From this j on, F(j) = Γ(j + 1 + d)/Γ(j − d) comes from its even asymptotic series (module text).
ASYMPTOTIC_FROM = 16.0


#: From this j on three terms of the even series suffice (first omitted term |e_4| j^{−8} ≤ 1.4e-20;
#: below it eight, first omitted |e_9| j^{−18} ≤ 2e-22 at j ≥ 16).
_FEW_TERMS_FROM = 256.0


def _horner(coefficients: list[float], inverse_square: np.ndarray) -> np.ndarray:
    total = np.full_like(inverse_square, coefficients[-1])
    for coefficient in reversed(coefficients[:-1]):
        total *= inverse_square
        total += coefficient
    total *= inverse_square
    return total


def _even_series(coefficients: list[float], j: np.ndarray) -> np.ndarray:
    """Σ_k c_k j^{−2k} by Horner's rule in j^{−2}: three terms from j = 256 on, eight below."""
    inverse_square = 1.0 / (j * j)
    few = j >= _FEW_TERMS_FROM
    if np.all(few):
        return _horner(coefficients[:3], inverse_square)
    if not np.any(few):
        return _horner(coefficients, inverse_square)
    total = np.empty_like(j)
    total[few] = _horner(coefficients[:3], inverse_square[few])
    total[~few] = _horner(coefficients, inverse_square[~few])
    return total


def _large_argument_ratio(j: np.ndarray, d: float, near_half: bool) -> np.ndarray:
    """F(j)/(d − ½), or [F(j) − (j² − ¼)]/(d − ½) when ``near_half``, for j ≥ ASYMPTOTIC_FROM (module
    text): exp(s log j + Σ e_k j^{−2k}), and (j² − ¼)·2Λ·exprel(2(d − ½)Λ) with
    Λ = log j + Σ (e_k(s) − e_k(2))/(s − 2) j^{−2k}."""
    s = 1.0 + 2.0 * d
    logarithm = np.log(j)
    if near_half:
        slope = logarithm + _even_series(_log_ratio_slopes(s), j)
        return (j * j - 0.25) * 2.0 * slope * special.exprel(2.0 * (d - 0.5) * slope)
    return _even_ratio(j, s, logarithm) / (d - 0.5)


def _even_ratio(middle: np.ndarray, step: float, logarithm: np.ndarray | None = None) -> np.ndarray:
    """Γ(w + (1 + step)/2)/Γ(w + (1 − step)/2) = exp(step log w + Σ_k e_k(step) w^{−2k}) at w = ``middle``
    ≥ 16, 1 ≤ step ≤ 3 (module text; :func:`rising_factorial` at a = w − (step − 1)/2 and F(j) at w = j);
    ``logarithm`` is log w when the caller has it."""
    logarithm = np.log(middle) if logarithm is None else logarithm
    return np.exp(step * logarithm + _even_series(_log_ratio_coefficients(step), middle))


def flicker_fourth_sum(x: Any, d: float) -> np.ndarray:
    """:data:`FLICKER_FOURTH_SUM` at integers ``x`` (unit σ_w²), up to a quadratic in x that the Allan and
    cross-covariance weights remove (the module text)."""
    return flicker_fourth_sum_at_distance(np.abs(np.asarray(x, dtype=np.float64) + 2.0), d)


def flicker_fourth_sum_at_distance(j: np.ndarray, d: float) -> np.ndarray:
    """:func:`flicker_fourth_sum` at x with |x + 2| = ``j`` (H is even about x = −2)."""
    d = float(d)
    near_half = abs(d - 0.5) <= _NEAR_HALF
    large = j >= ASYMPTOTIC_FROM
    if np.all(large):
        ratio = _large_argument_ratio(j, d, near_half)
    else:
        ratio = np.empty(j.shape)
        ratio[large] = _large_argument_ratio(j[large], d, near_half)
        small = j[~large]
        ratio[~large] = (
            _near_half_ratio(small, d) if near_half else _rising_numeric(small - 2.0, d) / (d - 0.5)
        )
    return (_normalisation_numeric(d) / _regular_denominator_numeric(d)) * ratio


def finite_fourth_sum(gamma: np.ndarray, x: Any, *, total: float | None = None) -> np.ndarray:
    """H(x) = Σ_{|k|<len(γ)} γ(|k|) R₃(x − k) for a finitely supported even γ (module text), at integers x.

    ``total`` = Σ_k γ(k) when it is known exactly (0 for the increments of a stationary process, whose
    computed sum is only rounding, which the cubic would multiply by x³/6).
    """
    points = np.asarray(x, dtype=np.int64)
    reach = len(gamma) - 1
    lags = np.arange(-reach, reach + 1)
    full = np.concatenate((gamma[:0:-1], gamma))
    # einsum, not np.dot: a slow AR term's γ reaches 10⁴–10⁵ lags, where OpenBLAS threads its dot and the
    # threads' spinning costs more CPU time than the sum (measured: a fit at φ = 0.99 took 1.6 times the CPU).
    powers = lags.astype(np.float64)
    moments = [float(np.einsum("i,i->", full, powers**r)) for r in range(4)]
    moments[1] = moments[3] = 0.0  # γ is even
    if total is not None:
        moments[0] = float(total)
    value = points.astype(np.float64)
    # Σ_r (−1)^r M_r p^{(r)}(x)/r!, p(x) = (x+1)(x+2)(x+3)/6: p' = (3x² + 12x + 11)/6, p'' = x + 2, p''' = 1.
    cubic = (
        moments[0] * (value + 1) * (value + 2) * (value + 3) / 6
        - moments[1] * (3 * value**2 + 12 * value + 11) / 6
        + moments[2] * (value + 2) / 2
        - moments[3] / 6
    )
    near = np.abs(points) <= reach + 3
    result = np.where(points > reach - 3, cubic, 0.0)
    if np.any(near):
        # H = the fourth cumulative sum of γ from k = −reach (∇⁴H = γ, H = 0 below −reach): no large
        # ramp values cancel.
        table = np.concatenate((full, np.zeros(8)))
        for _ in range(4):
            table = np.cumsum(table)
        index = points[near] + reach
        result[near] = np.where(index >= 0, table[np.maximum(index, 0)], 0.0)
    return result


def allan_variance_from_fourth_sum(fourth_sum: Any, sizes: np.ndarray) -> np.ndarray:
    """σ_A²(m) = [6H(−2) − 4(H(m−2) + H(−m−2)) + H(2m−2) + H(−2m−2)]/(2m²) (module text); ``fourth_sum``
    maps an integer array x to H(x)."""
    m = np.asarray(sizes, dtype=np.int64)
    points = np.concatenate((np.array([-2]), m - 2, -m - 2, 2 * m - 2, -2 * m - 2))
    values = np.asarray(fourth_sum(points), dtype=np.float64)
    count = len(m)
    centre, near, near_left = values[0], values[1 : 1 + count], values[1 + count : 1 + 2 * count]
    far, far_left = values[1 + 2 * count : 1 + 3 * count], values[1 + 3 * count :]
    variance = 6.0 * centre - 4.0 * (near + near_left) + far + far_left
    return variance / (2.0 * m.astype(np.float64) ** 2)


@functools.lru_cache(maxsize=256)
def flicker_allan_variance_closed(d: float, sizes: tuple[int, ...]) -> np.ndarray:
    """The 1/f Allan variance (stationary differences, unit σ_w²) at ``sizes`` from the closed form."""
    result = allan_variance_from_fourth_sum(lambda x: flicker_fourth_sum(x, d), np.asarray(sizes))
    result.setflags(write=False)
    return result


# --- Σ (Γ(j + d)/Γ(j))² without a pass over j ------------------------------------------------------------

#: Terms j < this are summed one by one; the rest by the power series (module text).
SQUARE_SUM_HEAD = 128
_BERNOULLI_OVER_FACTORIAL = tuple(float(sp.bernoulli(2 * k) / sp.factorial(2 * k)) for k in range(1, 9))


def _hurwitz_difference(power: float, first: float, count: int) -> float:
    """Σ_{n<count} (first + n)^power = ζ(−power, first) − ζ(−power, first + count), each Hurwitz ζ(s, a)
    from its Euler–Maclaurin series a^{1−s}/(s − 1) + a^{−s}/2 + Σ_k B_{2k}/(2k)! (s)_{2k−1} a^{−s−2k+1}
    (first ≥ 64; eight terms). The leading pair is (b^ε − a^ε)/ε = a^ε log(b/a) exprel(ε log(b/a)),
    ε = power + 1, so that d = ½ (ε = 0) needs no special case."""
    last = first + count
    logarithm = math.log(last / first)
    epsilon = power + 1.0
    total = first**epsilon * logarithm * float(special.exprel(epsilon * logarithm))
    total += 0.5 * (first**power - last**power)
    s, rising = -power, -power  # (s)_{2k−1}, rising factorial
    for k, coefficient in enumerate(_BERNOULLI_OVER_FACTORIAL, start=1):
        exponent = power - 2 * k + 1
        total += coefficient * rising * (first**exponent - last**exponent)
        rising *= (s + 2 * k - 1) * (s + 2 * k)
    return total


def _squared_ratio_coefficients(step: float) -> list[float]:
    """a_k with (Γ(x + step)/Γ(x))² = Σ_k a_k w^{2 step − 2k}, w = x + (step − 1)/2: the exponential of
    2 Σ_k e_k(step) u^k (:data:`LOG_RATIO_COEFFICIENTS`, u = w^{−2}) as a power series in u."""
    g = [0.0] + [2.0 * float(e) for e in _log_ratio_coefficients(step)]
    a = [1.0]
    for n in range(1, len(g)):
        a.append(sum(k * g[k] * a[n - k] for k in range(1, n + 1)) / n)
    return a


def squared_rising_factorial_sum(step: float, count: int) -> float:
    """Σ_{j=1}^{count} (Γ(j + step)/Γ(j))², 0 < step < 1, at a cost that does not grow with ``count``.

    Terms j < :data:`SQUARE_SUM_HEAD` one by one (:func:`rising_factorial`); beyond, with
    Γ(x + step)/Γ(x) = Γ(w + (1 + σ)/2)/Γ(w + (1 − σ)/2), σ = step, w = x + (step − 1)/2, the even series of
    the module text gives (Γ(x + step)/Γ(x))² = Σ_{k≤8} a_k w^{2 step − 2k} (first omitted term below 1e-30
    relative at w ≥ 127), and each Σ_j w_j^p is a difference of two Hurwitz ζ values
    (:func:`_hurwitz_difference`).
    """
    head = min(int(count), SQUARE_SUM_HEAD - 1)
    values = rising_factorial(np.arange(1, head + 1, dtype=np.float64), float(step))
    total = float(np.dot(values, values))
    if count <= head:
        return total
    first = head + 1 + (float(step) - 1.0) / 2.0
    coefficients = _squared_ratio_coefficients(float(step))
    tail = sum(
        a * _hurwitz_difference(2.0 * float(step) - 2.0 * k, first, int(count) - head)
        for k, a in enumerate(coefficients)
    )
    return total + tail
