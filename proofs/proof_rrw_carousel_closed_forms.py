"""Theorem (exact finite-N form of TIM 2014 eq. (18)): for N ≥ 3, with s_i = sin(2πi/N)/N,
c_i = cos(2πi/N)/N and R the lower-triangular ones matrix of eq. (10),

    sᵀRRᵀs = (3 csc²(π/N) − 2)/(8N),   cᵀRRᵀc = (csc²(π/N) + 2)/(8N),
    sᵀRRᵀs + cᵀRRᵀc = csc²(π/N)/(2N),  sᵀRRᵀc = −cot(π/N)/(4N);

for N ≤ 2: sᵀRRᵀs = sᵀRRᵀc = 0, cᵀRRᵀc = 1 (N = 1), 1/4 (N = 2). The paper gives only the leading
terms 3N/(8π²), N/(8π²), N/(2π²), by a rectangle rule.

Assumptions: none beyond the definitions (eqs. (10), (13)); N a positive integer.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from carousel_theory import closed_forms as cf
from carousel_theory.symbols import N, alpha, m, p, theta

z = sp.Symbol("z")


def step_1_partial_sums_from_the_geometric_series():
    """Im and Re of Σ_{j=1}^{m} e^{ijθ} = e^{iθ}(e^{imθ} − 1)/(e^{iθ} − 1) are S_m and C_m."""
    geometric = cf.geometric_partial_sum(m)
    real_theta = sp.Symbol("theta_real", real=True)
    geometric = geometric.subs(theta, real_theta)
    sine = cf.sine_partial_sum(m, real_theta)
    cosine = cf.cosine_partial_sum(m, real_theta)
    assert sp.simplify((sp.im(sp.expand_complex(geometric)) - sine).rewrite(sp.exp)) == 0
    assert sp.simplify((sp.re(sp.expand_complex(geometric)) - cosine).rewrite(sp.exp)) == 0


def step_2_partial_sums_by_induction():
    """Second way, by induction on m. Base case: S_0 = C_0 = 0.
    Step: S_{m+1} − S_m = sin((m + 1)θ) and C_{m+1} − C_m = cos((m + 1)θ)."""
    assert sp.simplify(cf.sine_partial_sum(0)) == 0
    assert sp.simplify(cf.cosine_partial_sum(0)) == 0
    step_sine = cf.sine_partial_sum(m + 1) - cf.sine_partial_sum(m) - sp.sin((m + 1) * theta)
    step_cosine = cf.cosine_partial_sum(m + 1) - cf.cosine_partial_sum(m) - sp.cos((m + 1) * theta)
    assert sp.simplify(step_sine.rewrite(sp.exp)) == 0
    assert sp.simplify(step_cosine.rewrite(sp.exp)) == 0


def step_3_full_period_sums_vanish():
    """S_N = 0 for θ = 2π/N (every N ≥ 1) and C_N = 0 (N ≥ 2), so the tails are
    (Rᵀs)_i = Σ_{j≥i} s_j = −S_{i−1}/N and (Rᵀc)_i = −C_{i−1}/N."""
    step = 2 * sp.pi / N
    assert sp.simplify(cf.sine_partial_sum(N, step)) == 0
    assert sp.simplify(cf.cosine_partial_sum(N, step)) == 0  # sin(π/N) ≠ 0 needs N ≥ 2


def step_4_tails_in_the_shifted_angle():
    """With θ = 2π/N, (2m + 1)θ/2 = α_m = (2m + 1)π/N: S_m and C_m are the trigonometric polynomials of
    degree 1 in α used by derive_rrw_carousel_quadratic_forms."""
    step = 2 * sp.pi / N
    shifted = (2 * m + 1) * sp.pi / N
    sine_in_alpha = (sp.cos(sp.pi / N) - sp.cos(alpha)) / (2 * sp.sin(sp.pi / N))
    cosine_in_alpha = (sp.sin(alpha) - sp.sin(sp.pi / N)) / (2 * sp.sin(sp.pi / N))
    assert sp.simplify(cf.sine_partial_sum(m, step) - sine_in_alpha.subs(alpha, shifted)) == 0
    assert sp.simplify(cf.cosine_partial_sum(m, step) - cosine_in_alpha.subs(alpha, shifted)) == 0


def step_5_sum_over_a_period():
    """Σ_{m=0}^{N−1} e^{ipα_m} = e^{ipπ/N} (z^N − 1)/(z − 1), z = e^{2πip/N}: zero unless N | p, since
    z^N = e^{2πip} = 1 (p integer). Exhaustive exact check in Q(ζ_{2N}), ζ = e^{iπ/N}, for N = 3..30 and
    0 < |p| ≤ 2 (the degrees that occur): Σ_m ζ^{p(2m+1)} ≡ 0 mod Φ_{2N}."""
    assert sp.exp(2 * sp.pi * sp.I * p) == 1
    for n in range(3, 31):
        modulus = sp.Poly(sp.cyclotomic_poly(2 * n, z), z)
        for frequency in (-2, -1, 1, 2):
            exponent_shift = 2 * n * 2  # keep exponents non-negative: ζ^{2N} = 1
            total = sum(z ** ((frequency * (2 * index + 1)) % (2 * n) + exponent_shift) for index in range(n))
            assert sp.Poly(total, z).rem(modulus).is_zero


def step_6_quadratic_forms_for_N_at_least_3():
    """Squaring the tails and summing over the period (step 5 keeps only the constant Fourier term)
    gives the closed forms; each difference simplifies to 0."""
    derived = cf.derive_rrw_carousel_quadratic_forms()
    assert sp.simplify(derived["sine"] - cf.RRW_CAROUSEL_SINE_GENERIC) == 0
    assert sp.simplify(derived["cosine"] - cf.RRW_CAROUSEL_COSINE_GENERIC) == 0
    assert sp.simplify(derived["cross"] - cf.RRW_CAROUSEL_CROSS_GENERIC) == 0
    assert sp.simplify(derived["sine"] + derived["cosine"] - cf.RRW_CAROUSEL_TOTAL_GENERIC) == 0


def step_7_small_N():
    """N = 1: s = (0), c = (1); N = 2: s = (0, 0), c = (−1/2, 1/2). Exact tail sums in Fractions."""
    for n, sine, cosine in [(1, [0], [1]), (2, [0, 0], [Fraction(-1, 2), Fraction(1, 2)])]:
        sine_tail = [sum(sine[start:], Fraction(0)) for start in range(n)]
        cosine_tail = [sum(cosine[start:], Fraction(0)) for start in range(n)]
        assert cf.RRW_CAROUSEL_SINE_VARIANCE.subs(N, n) == sum(x * x for x in sine_tail)
        assert cf.RRW_CAROUSEL_COSINE_VARIANCE.subs(N, n) == sum(x * x for x in cosine_tail)
        assert cf.RRW_CAROUSEL_CROSS.subs(N, n) == sum(
            x * y for x, y in zip(sine_tail, cosine_tail, strict=True)
        )


def step_8_exact_check_where_sines_are_radicals():
    """Independent exact check for N = 3, 4, 6, 8, 12 (sin and cos of multiples of 2π/N in radicals):
    the dense tail sums minus the closed forms simplify to 0."""
    for n in (3, 4, 6, 8, 12):
        sine = [sp.sin(2 * sp.pi * index / n) / n for index in range(1, n + 1)]
        cosine = [sp.cos(2 * sp.pi * index / n) / n for index in range(1, n + 1)]
        sine_tail = [sum(sine[start:]) for start in range(n)]
        cosine_tail = [sum(cosine[start:]) for start in range(n)]
        for brute, closed in [
            (sum(x * x for x in sine_tail), cf.RRW_CAROUSEL_SINE_VARIANCE),
            (sum(x * x for x in cosine_tail), cf.RRW_CAROUSEL_COSINE_VARIANCE),
            (sum(x * y for x, y in zip(sine_tail, cosine_tail, strict=True)), cf.RRW_CAROUSEL_CROSS),
        ]:
            assert sp.simplify(sp.radsimp(brute - closed.subs(N, n))) == 0


def step_9_leading_terms_are_the_papers():
    """lim sᵀRRᵀs / N = 3/(8π²), cᵀRRᵀc / N → 1/(8π²), sum / N → 1/(2π²): TIM 2014 eq. (18) and after."""
    assert cf.leading_coefficient(cf.RRW_CAROUSEL_SINE_GENERIC) == 3 / (8 * sp.pi**2)
    assert cf.leading_coefficient(cf.RRW_CAROUSEL_COSINE_GENERIC) == 1 / (8 * sp.pi**2)
    assert cf.leading_coefficient(cf.RRW_CAROUSEL_TOTAL_GENERIC) == 1 / (2 * sp.pi**2)
