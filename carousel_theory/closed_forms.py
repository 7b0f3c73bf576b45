"""Exact closed forms of TIM 2014 §III-A…C, for every number of samples N and every bin.

Each closed form is a SymPy expression in the symbols of :mod:`carousel_theory.symbols`, defined
once, here; :mod:`carousel_theory.formulas` names them, and numbers come from them by substitution,
``evalf`` or ``lambdify``. Unit driving variance throughout (σ_q² = σ_WN² = 1; multiply by it).

Conventions (TIM 2014 eqs. (6), (10)–(13)): a bin (an averaging interval, or one carouseling
revolution) holds N samples; bins are numbered from 1; the RRW r_t = r_{t−1} + q_t starts at
r_0 = 0, so Cov(r_s, r_t) = min(s, t). The carouseling weights are s_i = sin(2πi/N)/N and
c_i = cos(2πi/N)/N, i = 1 … N, and the estimate (5)–(6) is −Σ s_i ω_x + Σ c_i ω_y.

Derivation helpers (:func:`sum_over_period`, :func:`geometric_partial_sum`, the partial sums of
sines and cosines, :func:`derive_rrw_carousel_quadratic_forms`, :func:`rectangle_rule_steps`)
produce the same forms from first principles; the proofs in ``proofs/`` assert that they agree.
"""

from __future__ import annotations

import math
from fractions import Fraction

import sympy as sp

from carousel_theory._validation import check_positive_integer
from carousel_theory.symbols import (
    N,
    a,
    alpha,
    b,
    beta,
    epsilon,
    g,
    h,
    k,
    k_x,
    k_y,
    m,
    n,
    omega_r,
    psi,
    rho,
    sigma_e,
    sigma_nu,
    theta,
    u,
    var_x,
    var_y,
    wobble,
    x,
    y,
)

__all__ = [
    "BIAS_CAROUSEL_RESIDUAL",
    "BIAS_COSINE_RESIDUAL",
    "BIAS_SINE_RESIDUAL",
    "COSINE_SQUARES_SUM",
    "HEADING_ANGLE_BIAS",
    "HEADING_ANGLE_WALK_VARIANCE",
    "HEADING_ENCODER_NOISE_VARIANCE",
    "HEADING_SCALE_MISMATCH",
    "INDEXING2_BIAS_VARIANCE",
    "INDEXING2_RRW_VARIANCE",
    "INDEXING2_WHITE_VARIANCE",
    "INDEXING4_BIAS_VARIANCE",
    "INDEXING4_RRW_VARIANCE",
    "INDEXING4_WHITE_VARIANCE",
    "RATE_ERROR_MISALIGNMENT_WOBBLE",
    "RRW_AVERAGE_COVARIANCE",
    "RRW_AVERAGE_FIRST_BIN_VARIANCE",
    "RRW_AVERAGE_VARIANCE",
    "RRW_CAROUSEL_COSINE_GENERIC",
    "RRW_CAROUSEL_COSINE_VARIANCE",
    "RRW_CAROUSEL_COVARIANCE",
    "RRW_CAROUSEL_CROSS",
    "RRW_CAROUSEL_CROSS_GENERIC",
    "RRW_CAROUSEL_SINE_GENERIC",
    "RRW_CAROUSEL_SINE_VARIANCE",
    "RRW_CAROUSEL_TOTAL_GENERIC",
    "RRW_CAROUSEL_VARIANCE",
    "RRW_CAROUSEL_VARIANCE_CORRELATED",
    "SINE_SQUARES_SUM",
    "WHITE_AVERAGE_VARIANCE",
    "WHITE_CAROUSEL_VARIANCE",
    "cosine_partial_sum",
    "derive_rrw_carousel_quadratic_forms",
    "expansion_in_inverse_N",
    "geometric_partial_sum",
    "leading_coefficient",
    "rectangle_rule_steps",
    "rrw_bin_covariance_from_weights",
    "sine_partial_sum",
    "sum_over_period",
]

_pi = sp.pi


def _as_expression(name: str, value: object) -> sp.Expr:
    """A SymPy expression or an exact/finite number; TypeError for anything else (strings, bools, None)."""
    if isinstance(value, sp.Basic):
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float, Fraction)):
        raise TypeError(f"{name}={value!r}: must be a SymPy expression or a number")
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError(f"{name}={value!r}: must be finite")
    return sp.nsimplify(value) if isinstance(value, Fraction) else sp.sympify(value)


# --------------------------------------------------------------------------------------------
# §III-A additive bias, TIM 2014 eq. (8): (1/N) Σ_{i=1}^{N} sin(2πi/N) and the cosine companion.
# Σ_{i=1}^{N} exp(2πi·i/N) is the sum of the N-th roots of unity: 0 for N ≥ 2, and 1 for N = 1.
# Its imaginary part is 0 for every N ≥ 1 (sin 2π = 0 when N = 1); its real part is 1 at N = 1.
# --------------------------------------------------------------------------------------------

#: (1/N) Σ_{i=1}^{N} sin(2πi/N): zero for every N ≥ 1 (TIM 2014 eq. (8)).
BIAS_SINE_RESIDUAL = sp.Integer(0)
#: (1/N) Σ_{i=1}^{N} cos(2πi/N): one at N = 1 (the single weight is cos 2π = 1), else zero.
BIAS_COSINE_RESIDUAL = sp.Piecewise((sp.Integer(1), sp.Eq(N, 1)), (sp.Integer(0), True))
#: Residual of unit biases b_x = b_y = 1 in the carouselled estimate (6): −(1/N)Σ sin + (1/N)Σ cos.
BIAS_CAROUSEL_RESIDUAL = -BIAS_SINE_RESIDUAL + BIAS_COSINE_RESIDUAL

# --------------------------------------------------------------------------------------------
# §III-B white noise, TIM 2014 eq. (9).  Σ sin²(2πi/N) = N/2 − (1/2) Σ cos(4πi/N), and the last
# sum is N when N divides 2 (N = 1, 2) and 0 otherwise; likewise for cos².
# --------------------------------------------------------------------------------------------

#: Σ_{i=1}^{N} sin²(2πi/N): 0 for N ≤ 2 (every sine weight vanishes), N/2 for N ≥ 3.
SINE_SQUARES_SUM = sp.Piecewise((sp.Integer(0), N <= 2), (N / 2, True))
#: Σ_{i=1}^{N} cos²(2πi/N): 1 at N = 1, 2 at N = 2, N/2 for N ≥ 3.
COSINE_SQUARES_SUM = sp.Piecewise((sp.Integer(1), sp.Eq(N, 1)), (sp.Integer(2), sp.Eq(N, 2)), (N / 2, True))
#: Variance of the mean of N white samples of unit variance.
WHITE_AVERAGE_VARIANCE = 1 / N
#: Variance of the carouselled estimate (6) for white noise of variances var_x, var_y on the two gyros:
#: (var_x Σ sin² + var_y Σ cos²)/N², TIM 2014 eq. (9) generalised to unequal variances.
WHITE_CAROUSEL_VARIANCE = sp.Piecewise(
    (var_y, sp.Eq(N, 1)),
    (var_y / 2, sp.Eq(N, 2)),
    ((var_x + var_y) / (2 * N), True),
)

# --------------------------------------------------------------------------------------------
# §III-C rate random walk, direct averaging: TIM 2014 eqs. (14)–(15), generalised to bins a, b.
# --------------------------------------------------------------------------------------------


def rrw_bin_covariance_from_weights(
    weight_sum: sp.Expr, first_moment: sp.Expr, local_variance: sp.Expr
) -> sp.Expr:
    """Cov(X_a, X_b) of two bins of RRW weighted by the same vector w, as a function of a and b.

    With X_a = Σ_i w_i r_{(a−1)N+i}, write r_{(a−1)N+i} = r_{(a−1)N} + L_i^{(a)} where the local
    walk L^{(a)} uses only the increments of bin a. Then, for unit increment variance,

    Cov(X_a, X_b) = W² (min(a, b) − 1) N + { V if a = b;  W M if a ≠ b },

    with W = Σ w_i (``weight_sum``), M = Σ i w_i (``first_moment``) and
    V = Σ_i (Σ_{j≥i} w_j)² = wᵀRRᵀw (``local_variance``, TIM 2014 eq. (17)'s sᵀRRᵀs).
    """
    weight_sum = _as_expression("weight_sum", weight_sum)
    first_moment = _as_expression("first_moment", first_moment)
    local_variance = _as_expression("local_variance", local_variance)
    return weight_sum**2 * (sp.Min(a, b) - 1) * N + sp.Piecewise(
        (local_variance, sp.Eq(a, b)), (weight_sum * first_moment, True)
    )


#: Variance of the first averaged bin, 1ᵀRRᵀ1 = (1/N²) Σ i² (TIM 2014 eq. (15), upper left).
RRW_AVERAGE_FIRST_BIN_VARIANCE = (N + 1) * (2 * N + 1) / (6 * N)
#: Cov of averaged bins a and b (TIM 2014 eq. (15) for every pair of bins):
#: (min(a, b) − 1) N + (N + 1)(2N + 1)/(6N) if a = b, + (N + 1)/2 otherwise.
RRW_AVERAGE_COVARIANCE = (sp.Min(a, b) - 1) * N + sp.Piecewise(
    (RRW_AVERAGE_FIRST_BIN_VARIANCE, sp.Eq(a, b)), ((N + 1) / 2, True)
)
#: Variance of the k-th averaged bin: (k − 1) N + (N + 1)(2N + 1)/(6N) — exactly N more per bin.
RRW_AVERAGE_VARIANCE = RRW_AVERAGE_COVARIANCE.subs({a: k, b: k})

# --------------------------------------------------------------------------------------------
# §III-C rate random walk, carouselled: TIM 2014 eqs. (16)–(18), exact for every N.
# With θ = 2π/N the tail sums are Σ_{j≥i} sin(jθ) = −S_{i−1}, Σ_{j≥i} cos(jθ) = −C_{i−1} (N ≥ 2),
# S_m, C_m the partial sums below; squaring and summing over m = 0 … N − 1 leaves only the
# constant Fourier term (see sum_over_period), which gives these forms for N ≥ 3.
# --------------------------------------------------------------------------------------------

#: sᵀRRᵀs for N ≥ 3: (3 csc²(π/N) − 2)/(8N)  (TIM 2014 eq. (18) gives only its leading term 3N/8π²).
RRW_CAROUSEL_SINE_GENERIC = (3 * sp.csc(_pi / N) ** 2 - 2) / (8 * N)
#: cᵀRRᵀc for N ≥ 3: (csc²(π/N) + 2)/(8N)  (leading term N/8π²).
RRW_CAROUSEL_COSINE_GENERIC = (sp.csc(_pi / N) ** 2 + 2) / (8 * N)
#: sᵀRRᵀs + cᵀRRᵀc for N ≥ 3: csc²(π/N)/(2N)  (leading term N/2π²).
RRW_CAROUSEL_TOTAL_GENERIC = sp.csc(_pi / N) ** 2 / (2 * N)
#: sᵀRRᵀc for N ≥ 3: −cot(π/N)/(4N), tending to −1/(4π).
RRW_CAROUSEL_CROSS_GENERIC = -sp.cot(_pi / N) / (4 * N)

#: sᵀRRᵀs for every N ≥ 1: the sine weights vanish identically for N ≤ 2.
RRW_CAROUSEL_SINE_VARIANCE = sp.Piecewise((sp.Integer(0), N <= 2), (RRW_CAROUSEL_SINE_GENERIC, True))
#: cᵀRRᵀc for every N ≥ 1: c = (1) at N = 1 and c = (−1/2, 1/2) at N = 2.
RRW_CAROUSEL_COSINE_VARIANCE = sp.Piecewise(
    (sp.Integer(1), sp.Eq(N, 1)), (sp.Rational(1, 4), sp.Eq(N, 2)), (RRW_CAROUSEL_COSINE_GENERIC, True)
)
#: Variance of one carouselled bin, independent gyros: sᵀRRᵀs + cᵀRRᵀc (TIM 2014 eqs. (16)–(18)).
RRW_CAROUSEL_VARIANCE = sp.Piecewise(
    (sp.Integer(1), sp.Eq(N, 1)), (sp.Rational(1, 4), sp.Eq(N, 2)), (RRW_CAROUSEL_TOTAL_GENERIC, True)
)
#: sᵀRRᵀc for every N ≥ 1 (zero where s vanishes, N ≤ 2).
RRW_CAROUSEL_CROSS = sp.Piecewise((sp.Integer(0), N <= 2), (RRW_CAROUSEL_CROSS_GENERIC, True))
#: Variance of one carouselled bin when the two gyros' increments have correlation ρ at equal times:
#: Var(−sᵀR q_x + cᵀR q_y) = sᵀRRᵀs + cᵀRRᵀc − 2ρ sᵀRRᵀc.
#: (At N ≤ 2 the cross term vanishes with s, so ρ drops out.)
RRW_CAROUSEL_VARIANCE_CORRELATED = sp.Piecewise(
    (sp.Integer(1), sp.Eq(N, 1)),
    (sp.Rational(1, 4), sp.Eq(N, 2)),
    (RRW_CAROUSEL_TOTAL_GENERIC - 2 * rho * RRW_CAROUSEL_CROSS_GENERIC, True),
)
#: Cov of carouselled bins a and b (independent gyros): zero for a ≠ b once N ≥ 2 (the weights sum
#: to zero, TIM 2014 eq. (17)); at N = 1 nothing is carouselled and the bins are samples of the RRW.
RRW_CAROUSEL_COVARIANCE = sp.Piecewise(
    (sp.Min(a, b), sp.Eq(N, 1)), (RRW_CAROUSEL_VARIANCE, sp.Eq(a, b)), (sp.Integer(0), True)
)

# --------------------------------------------------------------------------------------------
# Derivation helpers
# --------------------------------------------------------------------------------------------


def geometric_partial_sum(length: sp.Expr, angle: sp.Expr = theta) -> sp.Expr:
    """Σ_{j=1}^{length} exp(i j angle) = e^{i angle}(e^{i length·angle} − 1)/(e^{i angle} − 1)."""
    length, angle = _as_expression("length", length), _as_expression("angle", angle)
    z = sp.exp(sp.I * angle)
    return z * (z**length - 1) / (z - 1)


def sine_partial_sum(length: sp.Expr = m, angle: sp.Expr = theta) -> sp.Expr:
    """S_m = Σ_{j=1}^{m} sin(j θ) = (cos(θ/2) − cos((2m + 1)θ/2)) / (2 sin(θ/2)).

    The imaginary part of :func:`geometric_partial_sum` (equivalently, telescoping
    2 sin(θ/2) sin(jθ) = cos((j − ½)θ) − cos((j + ½)θ)).
    """
    length, angle = _as_expression("length", length), _as_expression("angle", angle)
    return (sp.cos(angle / 2) - sp.cos((2 * length + 1) * angle / 2)) / (2 * sp.sin(angle / 2))


def cosine_partial_sum(length: sp.Expr = m, angle: sp.Expr = theta) -> sp.Expr:
    """C_m = Σ_{j=1}^{m} cos(j θ) = (sin((2m + 1)θ/2) − sin(θ/2)) / (2 sin(θ/2)), the real part."""
    length, angle = _as_expression("length", length), _as_expression("angle", angle)
    return (sp.sin((2 * length + 1) * angle / 2) - sp.sin(angle / 2)) / (2 * sp.sin(angle / 2))


def sum_over_period(expression: sp.Expr, angle: sp.Symbol = alpha, count: sp.Expr = N) -> sp.Expr:
    """Σ_{m=0}^{count−1} expression(α_m) for α_m = φ + 2πm/count, any phase φ.

    ``expression`` is a trigonometric polynomial in cos(angle), sin(angle) whose coefficients do not
    depend on the angle. With u = e^{iα} it is a Laurent polynomial Σ_p c_p u^p, and
    Σ_m e^{ipα_m} = e^{ipφ} Σ_m (e^{2πi p/count})^m, a geometric series of roots of unity that is 0
    unless count divides p. So when the degree is below ``count`` only c_0 survives: the sum is
    count·c_0. The caller guarantees degree < count (degree 2, i.e. N ≥ 3, for the RRW forms).
    """
    expression = _as_expression("expression", expression)
    if not isinstance(angle, sp.Symbol):
        raise TypeError(f"angle={angle!r}: must be a SymPy Symbol")
    laurent = sp.expand(
        expression.subs({sp.cos(angle): (u + 1 / u) / 2, sp.sin(angle): (u - 1 / u) / (2 * sp.I)})
    )
    if laurent.has(angle):
        raise ValueError(f"expression={expression!r}: must be a polynomial in cos({angle}) and sin({angle})")
    numerator, denominator = sp.fraction(sp.together(laurent))
    shift = sp.degree(denominator, u) if denominator.has(u) else 0
    denominator_free = sp.simplify(denominator / u**shift)
    constant = sp.Poly(numerator, u).coeff_monomial(u**shift) / denominator_free
    return sp.simplify(count * constant)


def derive_rrw_carousel_quadratic_forms() -> dict[str, sp.Expr]:
    """sᵀRRᵀs, cᵀRRᵀc and sᵀRRᵀc for N ≥ 3, derived from the partial sums and root-of-unity sums.

    (Rᵀs)_i = Σ_{j≥i} s_j = −S_{i−1}/N because S_N = 0; likewise (Rᵀc)_i = −C_{i−1}/N (C_N = 0 for
    N ≥ 2). With θ = 2π/N, S_m and C_m depend on m only through α_m = (2m + 1)π/N, so the sum over
    i = 1 … N is a :func:`sum_over_period` over m = 0 … N − 1 of a degree-2 trigonometric polynomial.
    """
    half = _pi / N  # θ/2
    sine_tail = (sp.cos(half) - sp.cos(alpha)) / (2 * sp.sin(half))  # S_m with (2m + 1)θ/2 → α
    cosine_tail = (sp.sin(alpha) - sp.sin(half)) / (2 * sp.sin(half))  # C_m likewise
    return {
        "sine": sp.simplify(sum_over_period(sine_tail**2) / N**2),
        "cosine": sp.simplify(sum_over_period(cosine_tail**2) / N**2),
        "cross": sp.simplify(sum_over_period(sine_tail * cosine_tail) / N**2),
    }


def expansion_in_inverse_N(expression: sp.Expr, order: int = 6) -> sp.Expr:
    """The large-N expansion of ``expression`` (a generic-branch form) up to, excluding, N^{−order}."""
    order = check_positive_integer("order", order)
    expression = _as_expression("expression", expression)
    series = sp.series(expression.subs(N, 1 / h), h, 0, order).removeO()
    return sp.expand(series.subs(h, 1 / N))


def leading_coefficient(expression: sp.Expr) -> sp.Expr:
    """lim_{N→∞} expression / N: the paper's "asymptotic proportionality coefficient"."""
    expression = _as_expression("expression", expression)
    # limits in the bounded variable h = 1/N: SymPy's limit in N itself mishandles csc(π/N)
    return sp.limit(expression.subs(N, 1 / h) * h, h, 0, "+")


def rectangle_rule_steps(weight: str = "sine") -> list[tuple[str, sp.Expr]]:
    """The continuous-time steps of TIM 2014 eq. (18), each derived by SymPy.

    sᵀRRᵀs = Σ_i (1/N Σ_{j≥i} sin(2πj/N))² ≈ N ∫_0^1 (∫_x^1 sin 2πy dy)² dx. Returns, in order:
    the inner integral, its square, the factor in front of ∫(…)² dx once the 2π is pulled out, the
    remaining integral and the result (for ``weight="cosine"`` the same with cos 2πy).
    """
    if weight not in ("sine", "cosine"):
        raise ValueError(f"weight={weight!r}: must be 'sine' or 'cosine'")
    function = sp.sin if weight == "sine" else sp.cos
    inner = sp.simplify(sp.integrate(function(2 * _pi * y), (y, x, 1)))
    # inner = g(x)/(2π) with g = cos 2πx − 1 (sine) or −sin 2πx (cosine)
    core = sp.simplify(inner * 2 * _pi)
    factor = N / (2 * _pi) ** 2
    outer = sp.integrate(sp.expand(core**2), (x, 0, 1))
    result = sp.simplify(N * sp.integrate(sp.expand(inner**2), (x, 0, 1)))
    return [
        ("inner integral", inner),
        ("squared integrand", inner**2),
        ("numerator of the squared integrand", core**2),
        ("factor in front of the integral", factor),
        ("integral of the numerator", outer),
        ("result", result),
    ]


# --------------------------------------------------------------------------------------------
# Beyond TIM 2014: 2- and 4-position indexing (maytagging) of the two-gyro unit, k whole cycles,
# N samples per dwell, g transition samples after each dwell (dropped from the estimate).
# Ω̂ = (1/n_used) Σ R_z(φ_t) ω_t (carousel_theory.rotation_schemes); each horizontal component
# weights each dwell's samples with ±1/(P k N) or 0. The suffix sums of these weights are linear
# ramps inside a dwell and constant across a gap, so Σ_i (Σ_{t≥i} w_t)² has the closed form below
# (proofs/proof_indexing_variances.py). Both components have this variance; they are uncorrelated.
# --------------------------------------------------------------------------------------------

#: A unit random-constant bias (TIM 2014 eq. (1)) on each gyro leaves nothing: each cycle's weights sum to 0.
INDEXING2_BIAS_VARIANCE = sp.Integer(0)
#: White noise, unit variance: 2kN samples weighted ±1/(2kN) on one gyro.
INDEXING2_WHITE_VARIANCE = 1 / (2 * k * N)
#: Rate random walk, unit increment variance: (2N² + 3gN + 1)/(12kN).
INDEXING2_RRW_VARIANCE = (2 * N**2 + 3 * g * N + 1) / (12 * k * N)
#: 4 positions: the bias cancels as well.
INDEXING4_BIAS_VARIANCE = sp.Integer(0)
#: White noise, unit variance: each gyro weighted ±1/(4kN) on 2kN samples, both gyros.
INDEXING4_WHITE_VARIANCE = 1 / (4 * k * N)
#: Rate random walk, unit increment variance: (5N² + 6gN + 1)/(24kN).
INDEXING4_RRW_VARIANCE = (5 * N**2 + 6 * g * N + 1) / (24 * k * N)


# --------------------------------------------------------------------------------------------
# Beyond TIM 2014 (its §VI future work): leading-order heading errors of rotation-scheme
# imperfections, for the demodulated estimate of carousel_theory.rotation_schemes about the vertical.
# carousel_theory.imperfections computes the exact effects; tests compare the two.
# --------------------------------------------------------------------------------------------

#: Encoder offset β: the estimate is E rotated by β exactly, so the heading moves by −β (rad), any scheme.
HEADING_ANGLE_BIAS = -beta
#: White Gaussian encoder noise σ_e over n used samples: heading variance Var(sin e)/n (rad²), the exact
#: cross-track variance over |E|² (the along-track part, Var(cos e)/n, does not move the heading).
HEADING_ENCODER_NOISE_VARIANCE = (1 - sp.exp(-2 * sigma_e**2)) / (2 * n)
#: Unmeasured angle random walk (σ_ν per sample) over n samples: the heading error is the walk's mean,
#: whose variance is the RRW average variance of TIM 2014 eq. (15) with N = n (rad², leading order).
HEADING_ANGLE_WALK_VARIANCE = sigma_nu**2 * (n + 1) * (2 * n + 1) / (6 * n)
#: Unequal scale factors under static averaging or 2-position indexing (each component from one gyro):
#: heading error (k_y − k_x) sin(2ψ)/2 (rad, leading order); zero for carouseling and 4-position indexing.
HEADING_SCALE_MISMATCH = (k_y - k_x) * sp.sin(2 * psi) / 2
#: A gyro tilted by ε toward the rotation axis, a once-per-turn rate wobble of relative size a at rate
#: ω_r, demodulated at the nominal angle: the rate error |δ| = sin ε · a ω_r / 2 (rad/s); the heading
#: error is at most |δ|/(Ω cos L).
RATE_ERROR_MISALIGNMENT_WOBBLE = sp.sin(epsilon) * wobble * omega_r / 2
