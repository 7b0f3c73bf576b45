"""Claims of TIM 2014 §II (error process models): the random-constant bias (1), white noise, the
rate random walk (2) and its Markov property, and 1/f noise as the fractional integral (3).

Symbolic identities are decided with SymPy, exact ``Fraction``/SymPy matrices or mpmath at 50 digits
over a stated finite range; the covariances come from :mod:`carousel_theory.processes`.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import sympy as sp

from carousel_theory import symbols
from carousel_theory.allan import model_allan_variance
from carousel_theory.claim import Claim, Status, Verdict
from carousel_theory.claims._common import (
    DIGITS,
    check_rrw_future_dependence,
    cumulative_sum_matrix,
    not_checkable,
    simplifies_to_zero,
)
from carousel_theory.fitting import NoiseModel
from carousel_theory.flicker_asymptotics import (
    STATIONARY_AUTOCOVARIANCE,
    stationary_autocovariance_derivation,
)
from carousel_theory.processes import (
    bias_covariance,
    covariance_matrix,
    fractional_coefficients,
    fractional_coefficients_exact,
    rate_random_walk_covariance,
)
from carousel_theory.symbols import d

__all__ = ["CLAIMS"]

PAPER = "TIM2014"


def _check_long_memory() -> Verdict:
    steps = stationary_autocovariance_derivation()
    exact_steps = steps["term"] == 0 and steps["gauss"] == 0 and steps["tail"] == 0
    # independent numbers: partial sums Σ_{j<t} ψ_j ψ_{j+h} (float64, t = 10⁶) plus their leading
    # tail t^{2d−1}/((1−2d)Γ(d)²), against γ_h, at d = 1/4
    order, length = 0.25, 10**6
    psi = fractional_coefficients(order, length + 100)
    gamma_h = sp.lambdify(
        sp.Symbol("h", integer=True, nonnegative=True),
        STATIONARY_AUTOCOVARIANCE.subs(symbols.d, sp.Rational(1, 4)),
        "math",
    )
    tail = length ** (2 * order - 1) / ((1 - 2 * order) * math.gamma(order) ** 2)
    deviations = [
        abs(float(np.dot(psi[:length], psi[lag : length + lag])) + tail - gamma_h(lag)) / gamma_h(lag)
        for lag in (1, 10, 100)
    ]
    if exact_steps and max(deviations) < 1e-4:
        return Verdict(
            Status.PROVED,
            "For 0 < d < 1/2, lim_t cov(f_t, f_{t+h}) = Γ(1−2d)Γ(h+d)/(Γ(d)Γ(1−d)Γ(h+1−d)) (Gauss's ₂F₁ sum, "
            "SymPy) ~ Γ(1−2d)/(Γ(d)Γ(1−d)) h^{2d−1}: hyperbolic, not summable; for d ≥ 1/2 Var f_t → ∞. "
            "At d = 1/4 partial sums to t = 10⁶ plus tail agree with γ_1, γ_10, γ_100 to "
            f"{max(deviations):.0e}.",
        )
    return Verdict(Status.FAILED, f"steps {steps}, deviations {deviations}")


def _check_bias_random_constant(sizes: range = range(1, 13)) -> Verdict:
    # b_t = b_{t−1} for t = 1..n telescopes to b_t = b_0, so every pair of samples has covariance σ_b².
    for n in sizes:
        exact = {bias_covariance(s, t) for s in range(1, n + 1) for t in range(1, n + 1)}
        if exact != {1} or not np.array_equal(covariance_matrix("bias", n), np.ones((n, n))):
            return Verdict(Status.FAILED, f"the bias covariance of size {n} is not the all-ones matrix")
    return Verdict(
        Status.VERIFIED,
        "b_t − b_0 = Σ_{u=1}^{t} (b_u − b_{u−1}) = 0 for every t, so b is one random variable and "
        "Cov(b_s, b_t) "
        f"= σ_b² for all s, t (the package's bias covariance is the all-ones matrix for n = {sizes.start}.."
        f"{sizes.stop - 1}).",
    )


def _check_bias_embeddable(sizes: range = range(1, 9)) -> Verdict:
    # b as the initial value of the RRW: (b + r_1, …, b + r_n) = [𝟙 | R] [b; q] with b independent of q.
    var_b, var_q = sp.symbols("sigma_b2 sigma_q2", positive=True)
    for n in sizes:
        design = sp.Matrix.hstack(sp.ones(n, 1), cumulative_sum_matrix(n))
        driving = sp.diag(var_b, *([var_q] * n))
        embedded = design * driving * design.T
        separate = sp.Matrix(
            n,
            n,
            lambda s, t: (
                var_b * bias_covariance(s + 1, t + 1) + var_q * rate_random_walk_covariance(s + 1, t + 1)
            ),
        )
        if not simplifies_to_zero(embedded - separate):
            return Verdict(Status.REFUTED, f"embedding b in the RRW changes the covariance at n = {n}")
    return Verdict(
        Status.VERIFIED,
        "Starting the RRW at r_0 = b (b independent of the increments) gives Cov = σ_b² + σ_q² min(s, "
        "t), the sum "
        f"of the bias and zero-mean RRW covariances (exact, n = {sizes.start}..{sizes.stop - 1}): the "
        f"bias can "
        "be embedded, as stated.",
    )


def _check_white_angular_random_walk(sizes: range = range(1, 21)) -> Verdict:
    # Σ_{s,t ≤ n} δ_st σ² = n σ²: the integrated white noise (the angle) has a variance growing like n.
    for n in sizes:
        total = sum(
            covariance_matrix("white", n, variance=1).ravel()
        )  # Var(Σ e_t) = 1ᵀ Σ 1 with unit variance
        if total != n:
            return Verdict(Status.REFUTED, f"Var(Σ_{{t≤{n}}} e_t) = {total}, not {n}")
    return Verdict(
        Status.VERIFIED,
        f"The angle Σ_{{t≤n}} e_t Δt of white rate noise has variance n σ² Δt², linear in n like a random "
        f"walk (exact for n = {sizes.start}..{sizes.stop - 1}): hence 'angular random walk'.",
    )


def _round_to_step(value: Fraction) -> int:
    """Mid-tread quantizer with unit step: the nearest integer, halves rounded up."""
    return int((value + Fraction(1, 2)) // 1)


def _quantization_errors(inputs: list[Fraction]) -> list[Fraction]:
    return [_round_to_step(value) - value for value in inputs]


def _centred_autocorrelation(values: list[Fraction], lag: int) -> Fraction:
    """Circular autocorrelation of one period of a periodic sequence, centred, normalised at lag 0."""
    n = len(values)
    mean = sum(values, Fraction(0)) / n
    centred = [v - mean for v in values]
    power = sum(v * v for v in centred)
    if power == 0:  # a constant sequence: no fluctuation to correlate
        return Fraction(0)
    return sum(centred[t] * centred[(t + lag) % n] for t in range(n)) / power


def _dithered_error_moments() -> list[sp.Expr]:
    """E[e^p], p = 1..4, of e = Q(x + u) − (x + u) for u uniform on [−1/2, 1/2), as functions of x ∈ [0, 1).

    Below u = 1/2 − x the input x + u rounds to 0, above it to 1 (periodicity covers every other x).
    """
    x, u = sp.Symbol("x", real=True), sp.Symbol("u", real=True)
    half = sp.Rational(1, 2)
    return [
        sp.simplify(
            sp.integrate((-x - u) ** p, (u, -half, half - x))
            + sp.integrate((1 - x - u) ** p, (u, half - x, half))
        )
        for p in range(1, 5)
    ]


def _check_quantization_white(
    constant: Fraction = Fraction(1, 3), ramp_step: Fraction = Fraction(1, 10)
) -> Verdict:
    constant_errors = _quantization_errors([constant] * 8)
    ramp_errors = _quantization_errors([t * ramp_step for t in range(1, int(1 / ramp_step) + 1)])
    period = len(ramp_errors)
    ramp_lag_one = _centred_autocorrelation(ramp_errors, 1)
    # Corrected statement: with subtractive dither the error has the moments of the uniform law on a
    # step whatever the input x, and independent dithers make successive errors independent.
    moments = _dithered_error_moments()
    uniform = [sp.Integer(0), sp.Rational(1, 12), sp.Integer(0), sp.Rational(1, 80)]
    if moments != uniform:
        return Verdict(Status.FAILED, f"dithered error moments {moments}")
    # The gyro-standard quantization term (angle quantization Q, NoiseModel.quantization) is the first
    # difference of white angle noise: Cov(e_t, e_{t+1}) = −σ², Var e_t = 2σ², and Allan slope −2.
    difference = (np.eye(3, 4, k=1) - np.eye(3, 4)).astype(np.int64)  # rows: a_{t+1} − a_t
    difference_covariance = difference @ difference.T
    difference_lag_one = Fraction(int(difference_covariance[0, 1]), int(difference_covariance[0, 0]))
    slope = model_allan_variance(NoiseModel(sample_rate=1.0, quantization=1.0), np.array([4, 8]))
    allan_slope = float(np.log2(slope[1] / slope[0]))
    if constant_errors[0] == 0 and abs(ramp_lag_one) < Fraction(1, 10):
        return Verdict(Status.VERIFIED, "both inputs give zero-mean, uncorrelated quantization errors")
    return Verdict(
        Status.QUALIFIED,
        f"Not white in general (unit step): the constant input {constant} gives the constant error "
        f"{constant_errors[0]} at every sample (a bias, not zero-mean noise), and the ramp t·{ramp_step} a "
        f"sawtooth of period {period} with centred lag-1 autocorrelation {ramp_lag_one}. With subtractive "
        "dither uniform over one step the error has the uniform moments 0, 1/12, 0, 1/80 for every input "
        f"(proved), and independent dithers make it white. The gyro-standard angle-quantization term is the "
        f"difference of white angle noise: lag-1 autocorrelation {difference_lag_one}, Allan slope "
        f"{allan_slope:.3f} (white: −1). The statement holds under the condition below, which the paper "
        "does not state.",
        corrected=(
            "Quantization error is white, uniform on one step with variance \\Delta^2/12 and independent of "
            "the input, when the input is dithered (subtractive uniform dither) or, approximately, when "
            "the noise at the quantizer input spans several steps; for a slowly varying input it is not."
        ),
    )


def _check_thermal_white(temperature: float = 300.0, frequency: float = 50.0) -> Verdict:
    with mpmath.workdps(DIGITS):
        planck, boltzmann = mpmath.mpf("6.62607015e-34"), mpmath.mpf("1.380649e-23")  # exact SI values
        ratio = planck * mpmath.mpf(frequency) / (boltzmann * mpmath.mpf(temperature))
        # Planck-corrected Johnson–Nyquist density relative to its flat value 4kTR: x/(eˣ − 1)
        deviation = 1 - ratio / mpmath.expm1(ratio)
        corner = boltzmann * mpmath.mpf(temperature) / planck
    if deviation > mpmath.mpf("1e-9"):
        return Verdict(
            Status.REFUTED, f"the thermal density falls by {mpmath.nstr(deviation, 3)} at {frequency} Hz"
        )
    return Verdict(
        Status.VERIFIED,
        f"Johnson–Nyquist noise is flat up to kT/h = {mpmath.nstr(corner, 3)} Hz at {temperature:g} K; "
        f"at the "
        f"{frequency:g} Hz Nyquist frequency of §V-C its density is below flat by "
        f"{mpmath.nstr(deviation, 3)} "
        "(50 digits, exact SI constants).",
    )


def _check_fractional_integral(d_value: Fraction = Fraction(1, 2), length: int = 40) -> Verdict:
    j = sp.Symbol("j", integer=True, nonnegative=True)
    printed = sp.gamma(j + d) / (sp.gamma(j + 1) * sp.gamma(d))
    if not simplifies_to_zero(sp.gammasimp(printed - sp.rf(d, j) / sp.factorial(j))):
        return Verdict(Status.FAILED, "Γ(j+d)/(Γ(j+1)Γ(d)) did not simplify to (d)_j/j!")
    z = sp.Symbol("z")
    series = sp.series((1 - z) ** (-d), z, 0, 6).removeO()
    if any(not simplifies_to_zero(series.coeff(z, n) - printed.subs(j, n)) for n in range(6)):
        return Verdict(Status.REFUTED, "the printed weights are not the coefficients of (1 − z)^(−d)")
    package = fractional_coefficients_exact(d_value, length)
    exact = [
        sp.gammasimp(printed.subs({j: n, d: sp.Rational(d_value.numerator, d_value.denominator)}))
        for n in range(length)
    ]
    if any(sp.Rational(p.numerator, p.denominator) != e for p, e in zip(package, exact, strict=True)):
        return Verdict(Status.FAILED, f"the package's ψ_j differ from (3) at d = {d_value}")
    return Verdict(
        Status.PROVED,
        "Γ(t−i+d)/(Γ(t−i+1)Γ(d)) = (d)_{t−i}/(t−i)!, the coefficient of z^{t−i} in (1 − z)^{−d}: (3) is the "
        f"fractional integral (1 − B)^{{−d}} w of order d; the package's weights equal it exactly at d = "
        f"{d_value}, "
        f"j < {length}.",
    )


def _check_rrw_markov() -> Verdict:
    # Gaussian RRW with Cov(r_s, r_t) = σ_q² min(s, t): r_t is Markov iff, given r_{t−1}, it is uncorrelated
    # with every earlier value: Cov(r_t, r_s | r_{t−1}) = min(t, s) − min(t, t−1) min(t−1, s) / (t − 1) = 0.
    def covariance(s: int, t: int) -> sp.Integer:
        return sp.Integer(min(s, t))

    for t in range(3, 41):
        for s in range(1, t - 1):
            explained = covariance(t, t - 1) * covariance(t - 1, s) / covariance(t - 1, t - 1)
            conditional = covariance(t, s) - explained
            if conditional != 0:
                return Verdict(Status.REFUTED, f"Cov(r_{t}, r_{s} | r_{t - 1}) = {conditional} ≠ 0")
    return Verdict(
        Status.VERIFIED,
        "Cov(r_s, r_t) = σ_q² min(s, t), so Cov(r_t, r_s | r_{t−1}) = s − (t−1)s/(t−1) = 0 exactly for every "
        "s < t − 1 ≤ 39: given r_{t−1}, r_t is independent of all earlier values (Markov). The 'or future "
        "realizations' part does not hold and is decided in TIM2014-secIIC-rrw-memoryless-future.",
    )


CLAIMS: list[Claim] = [
    Claim(
        "TIM2014-secIID-long-memory",
        PAPER,
        "§II-D, after eq. (3)",
        "As opposed to RRW, 1/f noise (the fractional integral (3)) is a long-memory process.",
        _check_long_memory,
    ),
    Claim(
        "TIM2014-eq1-bias-random-constant",
        "TIM2014",
        "§II-A, eq. (1)",
        "The additive bias is a random constant: b_t = b_{t−1}.",
        _check_bias_random_constant,
    ),
    Claim(
        "TIM2014-secIIA-bias-embeddable",
        "TIM2014",
        "§II-A, after eq. (1)",
        "It would be possible to embed the bias in other error processes; here the other processes are "
        "zero-mean.",
        _check_bias_embeddable,
    ),
    Claim(
        "TIM2014-secIIB-white-angular-random-walk",
        "TIM2014",
        "§II-B",
        "White noise (mutually independent samples, zero mean, constant variance σ_WN²) is often called "
        "angular "
        "random walk.",
        _check_white_angular_random_walk,
    ),
    Claim(
        "TIM2014-secIIB-quantization-white",
        "TIM2014",
        "§II-B",
        "Quantization noise is white.",
        _check_quantization_white,
    ),
    Claim(
        "TIM2014-secIIB-thermal-white", "TIM2014", "§II-B", "Thermal noise is white.", _check_thermal_white
    ),
    Claim(
        "TIM2014-secIIC-rrw-sources",
        "TIM2014",
        "§II-C, after eq. (2)",
        "An important source of RRW are changes in the temperature of the sensor; RRW is also caused by "
        "aging.",
        not_checkable(
            "A physical attribution; no temperature or ageing record is public, and the model (2) does not "
            "distinguish causes."
        ),
    ),
    Claim(
        "TIM2014-secIIC-rrw-memoryless-future",
        "TIM2014",
        "§II-C, after eq. (2)",
        "RRW is memoryless: r_t does not depend on other future realizations of the process than r_{t−1} "
        "(the "
        "'future' half of the Markov sentence, and the gloss 'i.e., memoryless').",
        check_rrw_future_dependence,
    ),
    Claim(
        "TIM2014-eq3-fractional-integral",
        "TIM2014",
        "§II-D, eq. (3)",
        "f_t = Σ_{i=1}^t Γ(t−i+d)/(Γ(t−i+1)Γ(d)) w_i is a fractional integral of order 0 < d < 1 of "
        "white noise.",
        _check_fractional_integral,
    ),
    Claim(
        "TIM2014-secIID-physical-origin-unknown",
        "TIM2014",
        "§II-D, after eq. (3)",
        "Although encountered in various contexts, the physical origin of 1/f noise is unknown [25].",
        not_checkable("A statement about the state of physics [25]; nothing in the model decides it."),
    ),
    Claim(
        "TIM2014-eq2-rrw-markov",
        PAPER,
        "§II-C, after eq. (2)",
        "RRW is a Markov process: r_t does not depend on previous realizations other than r_{t−1} "
        "(the past half of the sentence; the future half is a separate claim).",
        _check_rrw_markov,
    ),
]
