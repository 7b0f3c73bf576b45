"""Claims of TIM 2014 §I–§III that define the model: the error processes (eqs. (1)–(3)), the
measurement model and estimator (eqs. (4)–(6)), the continuous-time bias integral (7), the matrices
and vectors of the RRW analysis (eqs. (10)–(14), (16)), the printed intermediate steps of (15) and
(17), the remarks on T and the sampling rate, eq. (26), and the set-up numbers of §V-A.

Each check computes its verdict: symbolic identities with SymPy (PROVED when the difference
simplifies to zero), exact ``Fraction``/SymPy matrices or mpmath at 50 digits over a stated finite
range (VERIFIED), a counterexample with a proved corrected statement (ERRATUM), or NOT_CHECKABLE
with the reason. The closed forms come from :mod:`carousel_theory.closed_forms`; the weight
vectors and covariances from :mod:`carousel_theory.weights` and :mod:`carousel_theory.processes`.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction

import mpmath
import numpy as np
import sympy as sp

from carousel_theory import closed_forms as cf
from carousel_theory.allan import flicker_allan_variance, model_allan_variance
from carousel_theory.claim import Claim, Status, Verdict
from carousel_theory.fitting import NoiseModel
from carousel_theory.graycode import gray_matrix
from carousel_theory.processes import (
    bias_covariance,
    covariance_matrix,
    fractional_coefficients,
    fractional_coefficients_exact,
    fractionally_integrate,
    rate_random_walk_covariance,
)
from carousel_theory.symbols import N, d, k, var_x, var_y
from carousel_theory.weights import averaging_weights, carousel_weights

__all__ = ["CLAIMS"]

PAPER = "TIM2014"
DIGITS = 50

# Symbols of the measurement model (eqs. (4)–(5)); local because no closed form of the registry uses them.
_omega, _omega_perp, _error_x, _error_y, _phi = sp.symbols(
    "omega omega_perp epsilon_x epsilon_y phi", real=True
)
#: Continuous RRW intensity q_c ((rad/s)²/s, the unit of Table III), sampling interval Δt and period T.
_rrw_intensity, _sample_interval, _period = sp.symbols("q_c Delta_t T", positive=True)


def _is_zero(expression: sp.Expr) -> bool:
    return sp.simplify(expression) == 0


# --------------------------------------------------------------------------------------------
# §II: the error processes
# --------------------------------------------------------------------------------------------


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
        design = sp.Matrix.hstack(sp.ones(n, 1), _cumulative_sum_matrix(n))
        driving = sp.diag(var_b, *([var_q] * n))
        embedded = design * driving * design.T
        separate = sp.Matrix(
            n,
            n,
            lambda s, t: (
                var_b * bias_covariance(s + 1, t + 1) + var_q * rate_random_walk_covariance(s + 1, t + 1)
            ),
        )
        if sp.simplify(embedded - separate) != sp.zeros(n, n):
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
        Status.ERRATUM,
        f"Not white in general (unit step): the constant input {constant} gives the constant error "
        f"{constant_errors[0]} at every sample (a bias, not zero-mean noise), and the ramp t·{ramp_step} a "
        f"sawtooth of period {period} with centred lag-1 autocorrelation {ramp_lag_one}. With subtractive "
        "dither uniform over one step the error has the uniform moments 0, 1/12, 0, 1/80 for every input "
        f"(proved), and independent dithers make it white. The gyro-standard angle-quantization term is the "
        f"difference of white angle noise: lag-1 autocorrelation {difference_lag_one}, Allan slope "
        f"{allan_slope:.3f} (white: −1).",
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


def _conditional_covariance(size: int, targets: tuple[int, int], given: tuple[int, ...]) -> sp.Expr:
    """Cov(r_p, r_q | r_given) of the Gaussian RRW with Cov(r_s, r_t) = min(s, t), exact (times 1-based)."""
    covariance = sp.Matrix(size, size, lambda s, t: rate_random_walk_covariance(s + 1, t + 1))
    first, second = (index - 1 for index in targets)
    conditioning = [index - 1 for index in given]
    cross = sp.Matrix([[covariance[first, c] for c in conditioning]])
    cross_second = sp.Matrix([[covariance[second, c] for c in conditioning]])
    block = covariance.extract(conditioning, conditioning)
    return sp.nsimplify(covariance[first, second] - (cross * block.inv() * cross_second.T)[0])


def _check_rrw_future_dependence(t: int = 3, size: int = 6) -> Verdict:
    past = _conditional_covariance(size, (t, t - 2), (t - 1,))
    future = _conditional_covariance(size, (t, t + 1), (t - 1,))
    both_neighbours = [
        _conditional_covariance(size, (t, u), (t - 1, t + 1))
        for u in range(1, size + 1)
        if u not in (t - 1, t, t + 1)
    ]
    if past != 0 or any(value != 0 for value in both_neighbours):
        return Verdict(Status.FAILED, f"the Markov part fails: {past}, {both_neighbours}")
    if future == 0:
        return Verdict(Status.VERIFIED, f"r_{t} given r_{t - 1} is uncorrelated with r_{t + 1}")
    with mpmath.workdps(DIGITS):
        correlation = mpmath.sqrt(mpmath.mpf(100) / 200)
    return Verdict(
        Status.ERRATUM,
        f"Given r_{t - 1}, r_{t} is independent of the past (Cov(r_{t}, r_{t - 2} | r_{t - 1}) = {past}) "
        f"but not "
        f"of the future: Cov(r_{t}, r_{t + 1} | r_{t - 1}) = {future}·σ_q² (exact). Given both "
        f"neighbours it is "
        f"independent of all other values (n = {size}). Nor is RRW memoryless: Corr(r_s, r_t) = √(s/t), e.g. "
        f"{mpmath.nstr(correlation, 6)} for s = 100, t = 200.",
        corrected=(
            "r_t given r_{t-1} is independent of r_1, \\dots, r_{t-2} (Markov); given r_{t-1} and "
            "r_{t+1} it is "
            "independent of all other r_u. RRW is not memoryless: \\operatorname{Corr}(r_s, r_t) = "
            "\\sqrt{s/t}."
        ),
    )


def _check_fractional_integral(d_value: Fraction = Fraction(1, 2), length: int = 40) -> Verdict:
    j = sp.Symbol("j", integer=True, nonnegative=True)
    printed = sp.gamma(j + d) / (sp.gamma(j + 1) * sp.gamma(d))
    if not _is_zero(sp.gammasimp(printed - sp.rf(d, j) / sp.factorial(j))):
        return Verdict(Status.FAILED, "Γ(j+d)/(Γ(j+1)Γ(d)) did not simplify to (d)_j/j!")
    z = sp.Symbol("z")
    series = sp.series((1 - z) ** (-d), z, 0, 6).removeO()
    if any(not _is_zero(series.coeff(z, n) - printed.subs(j, n)) for n in range(6)):
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


def _check_flicker_name(order: Fraction = Fraction(1, 2)) -> Verdict:
    f = sp.Symbol("f", positive=True)
    # |1 − e^{−2πif}|^{−2d} = (2 sin πf)^{−2d}: the spectral density of (3) per unit σ_w².
    density = (2 * sp.sin(sp.pi * f)) ** (-2 * d)
    transfer_check = sp.simplify(
        sp.expand_complex((1 - sp.exp(-2 * sp.pi * sp.I * f)) * (1 - sp.exp(2 * sp.pi * sp.I * f)))
        - 4 * sp.sin(sp.pi * f) ** 2
    )
    base_limit = sp.limit(f / (2 * sp.sin(sp.pi * f)), f, 0)
    if transfer_check != 0 or base_limit != 1 / (2 * sp.pi):
        return Verdict(Status.FAILED, f"|1 − e^(−iλ)|² check {transfer_check}, limit {base_limit}")
    exponent = 2 * order
    if exponent != 1:
        return Verdict(
            Status.REFUTED,
            f"At d = {order} the density behaves like f^(−{exponent}) near 0, not 1/f.",
        )
    return Verdict(
        Status.PROVED,
        f"The density of (3) is σ_w² (2 sin πf)^(−2d) = {sp.sstr(density)}·σ_w², and f^(2d)·S(f) → σ_w² "
        f"(2π)^(−2d) "
        "as f → 0: a 1/f^(2d) law, exactly 1/f at the d = 1/2 used in §V-B (1/f^(2d) for other 0 < d < 1).",
    )


def _check_flicker_synthesis(length: int = 256, seed: int = 2014) -> Verdict:
    # For the record: the model (3) itself is synthesized exactly by a convolution (FFT, O(n log n)).
    innovations = np.random.default_rng(seed).standard_normal(length)
    psi = fractional_coefficients(0.5, length)
    direct = np.array([np.dot(psi[: t + 1][::-1], innovations[: t + 1]) for t in range(length)])
    fast = fractionally_integrate(innovations, 0.5)
    error = float(np.max(np.abs(fast - direct)) / np.max(np.abs(direct)))
    if error > 1e-12:
        return Verdict(Status.FAILED, f"the FFT synthesis of (3) differs from the direct sum by {error:.1e}")
    return Verdict(
        Status.NOT_CHECKABLE,
        "'Nontrivial' is a judgement, not a checkable statement [16]–[21]. For the record, the model (3) is "
        "synthesized by one FFT convolution in O(n log n); it matches the direct O(n²) sum of (3) within "
        f"1e-12 relative (n = {length}, d = 1/2, seeded). What is hard is a stationary 1/f process: (3) "
        "starts at t = 1 and is not stationary.",
    )


def _not_checkable(reason: str) -> Callable[[], Verdict]:
    def check() -> Verdict:
        return Verdict(Status.NOT_CHECKABLE, reason)

    return check


# --------------------------------------------------------------------------------------------
# §III: measurement model (4), estimator (5), revolution average (6), bias integral (7)
# --------------------------------------------------------------------------------------------


def _measurements(rate: sp.Expr = _omega, perpendicular: sp.Expr = _omega_perp, angle: sp.Expr = _phi):
    """ω_x, ω_y of TIM 2014 eqs. (4a), (4b)."""
    omega_x = -rate * sp.sin(angle) + perpendicular * sp.cos(angle) + _error_x
    omega_y = rate * sp.cos(angle) + perpendicular * sp.sin(angle) + _error_y
    return omega_x, omega_y


def _check_measurement_model() -> Verdict:
    axis_x = sp.Matrix([-sp.sin(_phi), sp.cos(_phi)])  # sensitivity of ω_x to (ω, ω^⊥)
    axis_y = sp.Matrix([sp.cos(_phi), sp.sin(_phi)])
    unit = _is_zero(axis_x.dot(axis_x) - 1) and _is_zero(axis_y.dot(axis_y) - 1)
    perpendicular = _is_zero(axis_x.dot(axis_y))
    at_zero = [value.subs({_error_x: 0, _error_y: 0}) for value in _measurements(angle=sp.Integer(0))]
    determinant = sp.simplify(sp.Matrix.hstack(axis_x, axis_y).det())
    if not (unit and perpendicular):
        return Verdict(Status.REFUTED, "the sensitive axes of (4a), (4b) are not orthonormal")
    return Verdict(
        Status.PROVED,
        "The sensitive axes of (4a), (4b) are (−sin φ, cos φ) and (cos φ, sin φ) in the (ω, ω^⊥) frame: "
        "unit and "
        f"perpendicular for every φ; at φ = 0, ω_y = {sp.sstr(at_zero[1])}, ω_x = {sp.sstr(at_zero[0])}. "
        f"Their "
        f"determinant is {determinant}: y lies at angle φ and x at φ + 90°.",
    )


def _check_estimator(sign_x: int = -1, sign_y: int = 1) -> Verdict:
    omega_x, omega_y = _measurements()
    estimate = sign_x * omega_x * sp.sin(_phi) + sign_y * omega_y * sp.cos(_phi)
    error = -_error_x * sp.sin(_phi) + _error_y * sp.cos(_phi)
    remainder = sp.simplify(estimate - (_omega + error))
    if remainder != 0:
        return Verdict(Status.REFUTED, f"ω̂ − (ω + ε̃) = {sp.sstr(remainder)}")
    var_x, var_y = sp.symbols("var_x var_y", nonnegative=True)
    error_variance = var_x * sp.sin(_phi) ** 2 + var_y * sp.cos(_phi) ** 2
    return Verdict(
        Status.PROVED,
        "Substituting (4a), (4b) into (5): ω̂ − ω − (−ε_x sin φ + ε_y cos φ) simplifies to 0, so ω^⊥ cancels "
        f"and ε̃ = −ε_x sin φ + ε_y cos φ; for independent errors Var ε̃ = {sp.sstr(error_variance)}, "
        "independent of φ only when var_x = var_y.",
    )


def _check_perpendicular_estimator() -> Verdict:
    omega_x, omega_y = _measurements()
    estimate = omega_x * sp.cos(_phi) + omega_y * sp.sin(_phi)
    remainder = sp.simplify(estimate - (_omega_perp + _error_x * sp.cos(_phi) + _error_y * sp.sin(_phi)))
    if remainder != 0:
        return Verdict(Status.REFUTED, f"ω̂^⊥ remainder {remainder}")
    return Verdict(
        Status.PROVED,
        "ω̂^⊥ = ω_x cos φ + ω_y sin φ = ω^⊥ + ε_x cos φ + ε_y sin φ exactly (ω cancels): the perpendicular "
        "axis is computed 'in a similar manner'.",
    )


def _check_revolution_average(sizes: range = range(1, 7)) -> Verdict:
    t, i = sp.Symbol("t", integer=True, positive=True), sp.Symbol("i", integer=True, positive=True)
    # φ(τ) = 2πτ/T at the sample times τ = (t − 1)T + iT/N of (6)
    angle = 2 * sp.pi * ((t - 1) * _period + i * _period / N) / _period
    same_sine = _is_zero(sp.sin(angle) - sp.sin(2 * sp.pi * i / N))
    same_cosine = _is_zero(sp.cos(angle) - sp.cos(2 * sp.pi * i / N))
    if not (same_sine and same_cosine):
        return Verdict(Status.FAILED, "the sample angles of (6) are not 2πi/N modulo 2π")
    # Error-free samples with time-varying rates: each summand of (6) is ω_i, so (6) is their mean.
    rates, perpendicular = sp.IndexedBase("omega"), sp.IndexedBase("omega_perp")
    for n in sizes:
        total = 0
        for index in range(1, n + 1):
            angle_i = 2 * sp.pi * sp.Integer(index) / n
            omega_x, omega_y = _measurements(rates[index], perpendicular[index], angle_i)
            omega_x, omega_y = (
                omega_x.subs({_error_x: 0, _error_y: 0}),
                omega_y.subs({_error_x: 0, _error_y: 0}),
            )
            total += (-omega_x * sp.sin(angle_i) + omega_y * sp.cos(angle_i)) / n
        mean = sum(rates[index] for index in range(1, n + 1)) / n
        if not _is_zero(total - mean):
            return Verdict(
                Status.REFUTED, f"N = {n}: (6) with zero errors gives {sp.sstr(sp.simplify(total))}"
            )
    return Verdict(
        Status.PROVED,
        "The sample angles of (6) are 2πi/N modulo 2π (the weights are N·s_i, N·c_i of (13)); with zero "
        "errors "
        "every summand equals ω at that sample, so (6) returns the mean of ω over the revolution and ω^⊥ "
        f"cancels (exact for N = {sizes.start}..{sizes.stop - 1}, including N = 1 and N = 2, where the sine "
        "weights vanish and the y gyro alone, read at φ = π and 2π, still returns ω).",
    )


def _check_continuous_bias_integral() -> Verdict:
    bias = sp.Symbol("b", real=True)
    sine = sp.integrate(bias * sp.sin(_phi), (_phi, 0, 2 * sp.pi))
    cosine = sp.integrate(bias * sp.cos(_phi), (_phi, 0, 2 * sp.pi))
    if sine != 0 or cosine != 0:
        return Verdict(Status.REFUTED, f"the integrals are {sine}, {cosine}")
    return Verdict(
        Status.PROVED, "∫_0^{2π} b sin φ dφ = 0 and ∫_0^{2π} b cos φ dφ = 0 by symbolic integration."
    )


def _check_integer_ratio_needed(
    samples: int = 8, samples_per_revolution: Fraction = Fraction(15, 2)
) -> Verdict:
    with mpmath.workdps(DIGITS):
        angles = [
            2
            * mpmath.pi
            * i
            / (mpmath.mpf(samples_per_revolution.numerator) / samples_per_revolution.denominator)
            for i in range(1, samples + 1)
        ]
        sine_residual = mpmath.fsum(mpmath.sin(angle) for angle in angles) / samples
        cosine_residual = mpmath.fsum(mpmath.cos(angle) for angle in angles) / samples
    tolerance = mpmath.mpf(10) ** (-DIGITS + 5)
    if abs(sine_residual) < tolerance and abs(cosine_residual) < tolerance:
        return Verdict(
            Status.REFUTED, f"{samples} samples at ratio {samples_per_revolution} still cancel the bias"
        )
    return Verdict(
        Status.VERIFIED,
        f"The assumption matters: with f_s/f_c = {samples_per_revolution} (not an integer) the "
        f"{samples}-sample "
        f"sums leave (1/n)Σ sin φ_i = {mpmath.nstr(sine_residual, 6)}, (1/n)Σ cos φ_i = "
        f"{mpmath.nstr(cosine_residual, 6)} of a unit bias (50 digits); integer ratios N ≥ 2 give 0 (eq. "
        f"(8)).",
    )


def _check_averaging_decreases() -> Verdict:
    if not (_is_zero(cf.WHITE_AVERAGE_VARIANCE - 1 / N) and (1 - cf.WHITE_AVERAGE_VARIANCE).subs(N, 1) == 0):
        return Verdict(Status.FAILED, f"the averaged white variance is {cf.WHITE_AVERAGE_VARIANCE}")
    decrease = sp.simplify(1 - cf.WHITE_AVERAGE_VARIANCE)
    if not all(decrease.subs(N, n) > 0 for n in range(2, 50)) or sp.solve(sp.Eq(decrease, 0), N) != [1]:
        return Verdict(Status.REFUTED, f"1 − Var = {decrease}")
    return Verdict(
        Status.PROVED,
        f"The mean of N uncorrelated samples has variance σ²/N; σ² − σ²/N = σ²·{sp.sstr(decrease)} > 0 "
        f"for every "
        "N ≥ 2 (0 only at N = 1).",
    )


# --------------------------------------------------------------------------------------------
# §III-C: the matrices and vectors (10)–(14), (16) and the intermediate lines of (15), (17)
# --------------------------------------------------------------------------------------------


def _cumulative_sum_matrix(size: int) -> sp.Matrix:
    """The lower-triangular matrix of ones of TIM 2014 eq. (10), built from its definition."""
    return sp.Matrix(size, size, lambda row, column: 1 if column <= row else 0)


def _check_cumulative_sum_matrix(sizes: range = range(1, 13)) -> Verdict:
    for n in sizes:
        increments = sp.Matrix(sp.symbols(f"q1:{n + 1}"))
        walk = _cumulative_sum_matrix(n) * increments
        previous = sp.Integer(0)  # r_0 = 0
        for t in range(n):
            if sp.expand(walk[t] - previous - increments[t]) != 0:
                return Verdict(Status.REFUTED, f"(R q)_{t + 1} ≠ r_{t} + q_{t + 1} at N = {n}")
            previous = walk[t]
        covariance = _cumulative_sum_matrix(n) * _cumulative_sum_matrix(n).T
        expected = sp.Matrix(n, n, lambda s, t: int(rate_random_walk_covariance(s + 1, t + 1)))
        if covariance != expected:
            return Verdict(Status.FAILED, f"R Rᵀ ≠ min(s, t) at N = {n}")
    return Verdict(
        Status.VERIFIED,
        "R q satisfies r_t = r_{t−1} + q_t with r_0 = 0, i.e. it is the RRW of (2), and R Rᵀ = [min(s, "
        "t)] is its "
        f"covariance per unit σ_q² (exact, symbolic q, N = {sizes.start}..{sizes.stop - 1}).",
    )


def _partitioned_matrix(n: int, lower_left: int = 1) -> sp.Matrix:
    """R_2 of TIM 2014 eq. (11): [[R, 𝕆], [𝕀, R]] with 𝕀 the N×N matrix of ``lower_left``."""
    block = _cumulative_sum_matrix(n)
    return sp.Matrix(sp.BlockMatrix([[block, sp.zeros(n, n)], [sp.ones(n, n) * lower_left, block]]))


def _check_partition(sizes: range = range(1, 13), lower_left: int = 1) -> Verdict:
    for n in sizes:
        if _partitioned_matrix(n, lower_left) != _cumulative_sum_matrix(2 * n):
            return Verdict(
                Status.REFUTED, f"[[R, 𝕆], [{lower_left}·𝕀, R]] is not the 2N×2N cumulative sum at N = {n}"
            )
    return Verdict(
        Status.VERIFIED,
        "[[R, 𝕆], [𝕀, R]] equals the 2N×2N lower-triangular matrix of ones entry by entry for N = "
        f"{sizes.start}..{sizes.stop - 1} (rows N+1..2N: the ones block sums the first bin's increments).",
    )


def _check_integrator_vector(sizes: range = range(1, 65)) -> Verdict:
    for n in sizes:
        weights = averaging_weights(n)
        if weights.shape != (n,) or not np.all(weights == 1.0 / n):
            return Verdict(Status.FAILED, f"the package's integrator vector at N = {n} is {weights}")
    return Verdict(
        Status.VERIFIED,
        "1 = (1/N)[1 … 1]ᵀ, so 1ᵀx is the mean of the bin and 1ᵀ1 = 1/N (it is not the all-ones vector); "
        f"the package's averaging weights equal 1/N in every entry for N = {sizes.start}..{sizes.stop - 1}.",
    )


def _check_carousel_vectors(sizes: range = range(1, 65), ulps: int = 4) -> Verdict:
    worst = 0.0
    for n in sizes:
        sine, cosine = carousel_weights(n)
        with mpmath.workdps(DIGITS):
            for index in range(1, n + 1):
                angle = 2 * mpmath.pi * index / n
                for got, exact in (
                    (sine[index - 1], mpmath.sin(angle) / n),
                    (cosine[index - 1], mpmath.cos(angle) / n),
                ):
                    error = float(abs(mpmath.mpf(float(got)) - exact)) / (np.finfo(float).eps / n)
                    worst = max(worst, error)
        if sine[-1] != 0.0 or cosine[-1] != 1.0 / n:
            return Verdict(Status.FAILED, f"the last entries at N = {n} are {sine[-1]}, {cosine[-1]}")
    if worst > ulps:
        return Verdict(Status.FAILED, f"the package's s, c differ from (13) by {worst:.2f} units of ε/N")
    return Verdict(
        Status.VERIFIED,
        "s_i = sin(2πi/N)/N, c_i = cos(2πi/N)/N, i = 1..N, ending with sin 2π = 0 and cos 2π = 1 "
        "(exact); the "
        f"package's vectors agree with 50-digit values within {ulps} units of ε/N for N = {sizes.start}.."
        f"{sizes.stop - 1}.",
    )


def _check_two_bin_means(sizes: range = range(1, 9)) -> Verdict:
    for n in sizes:
        increments = sp.Matrix(sp.symbols(f"q1:{2 * n + 1}"))
        selector = sp.zeros(2, 2 * n)
        for index in range(n):
            selector[0, index] = sp.Rational(1, n)
            selector[1, n + index] = sp.Rational(1, n)
        result = selector * _partitioned_matrix(n) * increments
        walk = [sum(increments[: t + 1]) for t in range(2 * n)]  # r_t = q_1 + … + q_t, r_0 = 0
        means = [sum(walk[:n]) / n, sum(walk[n:]) / n]
        if any(sp.expand(result[row] - means[row]) != 0 for row in range(2)):
            return Verdict(Status.REFUTED, f"(14) is not the two bin means at N = {n}")
    return Verdict(
        Status.VERIFIED,
        "[[1ᵀ, 0ᵀ], [0ᵀ, 1ᵀ]] R_2 q equals the means of r_1..r_N and r_{N+1}..r_{2N} of the RRW started at "
        f"r_0 = 0 (exact, symbolic q, N = {sizes.start}..{sizes.stop - 1}).",
    )


def _fraction_matrix(rows: list[list[Fraction]]) -> sp.Matrix:
    return sp.Matrix([[sp.Rational(v.numerator, v.denominator) for v in row] for row in rows])


def _check_eq15_block_expansion(sizes: range = range(1, 11), ones_block_cube: int = 3) -> Verdict:
    for n in sizes:
        one = sp.Matrix([sp.Rational(1, n)] * n)
        zero = sp.zeros(n, 1)
        selector = sp.Matrix.vstack(sp.Matrix.hstack(one.T, zero.T), sp.Matrix.hstack(zero.T, one.T))
        first_line = selector * _partitioned_matrix(n) * _partitioned_matrix(n).T * selector.T
        block, ones = _cumulative_sum_matrix(n), sp.ones(n, n)
        second_line = sp.Matrix(
            [
                [(one.T * block * block.T * one)[0], (one.T * block * ones.T * one)[0]],
                [
                    (one.T * ones * block.T * one)[0],
                    (one.T * block * block.T * one)[0] + (one.T * ones * ones.T * one)[0],
                ],
            ]
        )
        third_line = sp.Matrix(
            [
                [
                    sum(i * i for i in range(1, n + 1)) / sp.Integer(n) ** 2,
                    sum(i * n for i in range(1, n + 1)) / sp.Integer(n) ** 2,
                ],
                [
                    sum(i * n for i in range(1, n + 1)) / sp.Integer(n) ** 2,
                    sum(i * i for i in range(1, n + 1)) / sp.Integer(n) ** 2
                    + sp.Integer(n) ** ones_block_cube / n**2,
                ],
            ]
        )
        if first_line != second_line or second_line != third_line:
            return Verdict(
                Status.REFUTED, f"the lines of (15) differ at N = {n}: {first_line} vs {third_line}"
            )
    return Verdict(
        Status.VERIFIED,
        "The first line W R_2 R_2ᵀ Wᵀ, the block line [[1ᵀRRᵀ1, 1ᵀR𝕀ᵀ1], [1ᵀ𝕀Rᵀ1, 1ᵀRRᵀ1 + 1ᵀ𝕀𝕀ᵀ1]] and "
        "the sums "
        f"Σi²/N², ΣiN/N², N³/N² of (15) agree exactly for N = {sizes.start}..{sizes.stop - 1}.",
    )


def _check_carouselled_averages(sizes: range = range(1, 7)) -> Verdict:
    for n in sizes:
        q_x = sp.Matrix(sp.symbols(f"qx1:{2 * n + 1}"))
        q_y = sp.Matrix(sp.symbols(f"qy1:{2 * n + 1}"))
        sine = sp.Matrix([sp.sin(2 * sp.pi * i / n) / n for i in range(1, n + 1)])
        cosine = sp.Matrix([sp.cos(2 * sp.pi * i / n) / n for i in range(1, n + 1)])
        zero = sp.zeros(n, 1)

        def selector(vector: sp.Matrix, zero: sp.Matrix = zero) -> sp.Matrix:
            return sp.Matrix.vstack(sp.Matrix.hstack(vector.T, zero.T), sp.Matrix.hstack(zero.T, vector.T))

        printed = (
            -selector(sine) * _partitioned_matrix(n) * q_x + selector(cosine) * _partitioned_matrix(n) * q_y
        )
        walk_x = [sum(q_x[: t + 1]) for t in range(2 * n)]
        walk_y = [sum(q_y[: t + 1]) for t in range(2 * n)]
        # (6) with ε_x = r^x, ε_y = r^y and zero true rates; revolution t uses samples (t−1)N + i
        averages = [
            sum(
                -walk_x[(revolution - 1) * n + i - 1] * sp.sin(2 * sp.pi * i / n)
                + walk_y[(revolution - 1) * n + i - 1] * sp.cos(2 * sp.pi * i / n)
                for i in range(1, n + 1)
            )
            / n
            for revolution in (1, 2)
        ]
        if any(sp.expand(printed[row] - averages[row]) != 0 for row in range(2)):
            return Verdict(Status.REFUTED, f"(16) differs from (6) applied to RRW errors at N = {n}")
    return Verdict(
        Status.VERIFIED,
        "(16), −[[sᵀ, 0ᵀ], [0ᵀ, sᵀ]] R_2 q_x + [[cᵀ, 0ᵀ], [0ᵀ, cᵀ]] R_2 q_y, equals (6) applied to two "
        "revolutions "
        f"of independent RRW errors on the two gyros (exact, symbolic q, N = "
        f"{sizes.start}..{sizes.stop - 1}).",
    )


def _check_eq17_block_entries(sizes: range = range(2, 13)) -> Verdict:
    tolerance = mpmath.mpf(10) ** (-DIGITS + 5)
    with mpmath.workdps(DIGITS + 10):
        for n in sizes:
            for name, function, closed in (
                ("s", mpmath.sin, cf.RRW_CAROUSEL_SINE_VARIANCE),
                ("c", mpmath.cos, cf.RRW_CAROUSEL_COSINE_VARIANCE),
            ):
                weights = [function(2 * mpmath.pi * i / n) / n for i in range(1, n + 1)]
                tail = [mpmath.fsum(weights[t:]) for t in range(n)]  # Rᵀw
                weight_sum = mpmath.fsum(weights)  # 𝕀ᵀw = (Σw)·[1 … 1]ᵀ
                quadratic = mpmath.fsum(v * v for v in tail)  # wᵀRRᵀw
                cross = mpmath.fsum(tail) * weight_sum  # wᵀR𝕀ᵀw
                ones_term = n * weight_sum**2  # wᵀ𝕀𝕀ᵀw
                expected = mpmath.mpf(sp.N(closed.subs(N, n), DIGITS + 10))
                if (
                    abs(cross) > tolerance
                    or abs(ones_term) > tolerance
                    or abs(quadratic - expected) > tolerance
                ):
                    return Verdict(
                        Status.REFUTED,
                        f"N = {n}, {name}: {name}ᵀR𝕀ᵀ{name} = {mpmath.nstr(cross, 5)}, "
                        f"{name}ᵀ𝕀𝕀ᵀ{name} = {mpmath.nstr(ones_term, 5)}",
                    )
    return Verdict(
        Status.VERIFIED,
        "In the first line of (17), sᵀR𝕀ᵀs = (1ᵀ_N Rᵀs)(Σs) and sᵀ𝕀𝕀ᵀs = N(Σs)² vanish because Σs = 0, and "
        "sᵀRRᵀs is the closed form csc-law; likewise for c (50 digits, N = "
        f"{sizes.start}..{sizes.stop - 1}). At N = 1, cᵀ𝕀𝕀ᵀc = 1: the step needs N ≥ 2.",
    )


def _check_averages_correlated(n_value: int = 200) -> Verdict:
    covariance = cf.RRW_AVERAGE_COVARIANCE
    a_symbol, b_symbol = sorted(
        (symbol for symbol in covariance.free_symbols if str(symbol) in "ab"), key=str
    )
    first = covariance.subs({a_symbol: 1, b_symbol: 1})
    second = covariance.subs({a_symbol: 2, b_symbol: 2})
    cross = covariance.subs({a_symbol: 1, b_symbol: 2})
    correlation = cross / sp.sqrt(first * second)
    limit = sp.limit(correlation, N, sp.oo)
    if limit != sp.Rational(3, 4) or correlation.subs(N, 1) == 0:
        return Verdict(Status.REFUTED, f"correlation tends to {limit}")
    value = sp.N(correlation.subs(N, n_value), DIGITS)
    return Verdict(
        Status.PROVED,
        f"Corr = ((N+1)/2)/√(V(V+N)) with V = (N+1)(2N+1)/(6N): {sp.N(correlation.subs(N, 1), 6)} at N = 1, "
        f"{sp.N(value, 6)} at N = {n_value}, → {limit} as N → ∞ (exact limit): the averages are strongly "
        "correlated.",
    )


def _check_sequence_variance_length(orders: range = range(2, 11)) -> Verdict:
    variances = []
    for order in orders:
        matrix = gray_matrix(order)
        diagonal = np.einsum("ij,ij->i", matrix, matrix)  # diag(K Kᵀ)
        if not np.all(diagonal == diagonal[0]):
            return Verdict(Status.REFUTED, f"n = {order}: the variances differ within the sequence")
        variances.append(Fraction(float(diagonal[0])).limit_denominator(64))
    if len(set(variances)) != len(variances):
        return Verdict(Status.REFUTED, f"the variance does not change with the length: {variances}")
    return Verdict(
        Status.VERIFIED,
        f"Var R_t = C²·diag(K Kᵀ) is the same for every t but equals {variances[0]}, {variances[1]}, …, "
        f"{variances[-1]} for lengths 2^{orders.start}, …, 2^{orders.stop - 1}: a function of the length, "
        "as the paper says (n/4 for length 2^n).",
    )


def _check_flicker_allan_constant(
    order: float = 0.5, length: int = 2**14, taus: tuple[int, ...] = (16, 32, 64, 128, 256, 512)
) -> Verdict:
    values = flicker_allan_variance(order, np.array(taus), length)
    with mpmath.workdps(DIGITS):
        # continuous 1/f with one-sided density h/f has Allan variance 2 ln 2 · h; here h = σ_w²/π
        plateau = 2 * mpmath.log(2) / mpmath.pi
    deviation = float(np.max(np.abs(values / float(plateau) - 1)))
    short = flicker_allan_variance(order, np.array([1, 2]), length)
    other = flicker_allan_variance(order / 2, np.array([taus[0], taus[-1]]), length)
    if deviation > 0.01:
        return Verdict(
            Status.REFUTED,
            f"d = {order}: Allan variance {values[0]:.4g} … {values[-1]:.4g} over τ = {taus[0]}…{taus[-1]} "
            "samples is not constant",
        )
    return Verdict(
        Status.VERIFIED,
        f"Exact expected Allan variance of (3) at d = {order} (length {length}): within "
        f"{100 * deviation:.2f} % of "
        f"2 ln 2/π = {mpmath.nstr(plateau, 6)} σ_w² for τ = {taus[0]}…{taus[-1]} samples; not at τ = 1, 2 "
        f"({short[0]:.4f}, {short[1]:.4f}, the discrete spectrum). At d = {order / 2} it changes by "
        f"the factor "
        f"{other[1] / other[0]:.3f} over the same τ range: only d = 1/2 is pure 1/f.",
    )


def _check_period_not_explicit() -> Verdict:
    expressions = {
        "(15)": cf.RRW_AVERAGE_COVARIANCE,
        "(17)-(18)": cf.RRW_CAROUSEL_SINE_VARIANCE,
        "total": cf.RRW_CAROUSEL_VARIANCE,
    }
    names = {
        label: sorted(str(symbol) for symbol in expression.free_symbols)
        for label, expression in expressions.items()
    }
    if any("T" in symbols for symbols in names.values()):
        return Verdict(Status.REFUTED, f"free symbols {names}")
    return Verdict(
        Status.PROVED,
        f"The free symbols of the exact forms are {names['(15)']} for (15) and {names['total']} for the "
        f"carouselled "
        "variances: no T; at a fixed sampling interval Δt, T = NΔt, so T enters only through N.",
    )


def _check_sampling_rate_scaling() -> Verdict:
    # σ_q² per sample = q_c Δt (increments of a continuous RRW of intensity q_c over Δt), N = T/Δt.
    samples = _period / _sample_interval
    averaged = _rrw_intensity * _sample_interval * cf.RRW_AVERAGE_VARIANCE.subs(N, samples)
    carouselled = _rrw_intensity * _sample_interval * cf.RRW_CAROUSEL_TOTAL_GENERIC.subs(N, samples)
    averaged_limit = sp.limit(averaged, _sample_interval, 0, "+")
    carouselled_limit = sp.limit(carouselled, _sample_interval, 0, "+")
    if not (
        _is_zero(averaged_limit - _rrw_intensity * _period * (k - sp.Rational(2, 3)))
        and _is_zero(carouselled_limit - _rrw_intensity * _period / (2 * sp.pi**2))
    ):
        return Verdict(Status.REFUTED, f"limits {averaged_limit}, {carouselled_limit}")
    averaged_exact = sp.expand(averaged)
    return Verdict(
        Status.PROVED,
        "With σ_q² = q_c Δt per sample ((rad/s)²/s × s, Table III's unit) and N = T/Δt, the averaged bin-k "
        f"variance is {sp.sstr(averaged_exact)} → q_c T (k − 2/3) and the carouselled one → q_c T/(2π²) "
        f"as Δt → 0: "
        "σ_q² depends on the rate, the physical variance only through vanishing terms.",
    )


def _check_covariance_identity(order: int = 2) -> Verdict:
    columns = gray_matrix(order).shape[1]
    x = sp.symbols(f"x1:{columns + 1}")
    # Cov(x_i, x_j) = E[x_i x_j] = δ_ij for independent, zero-mean, unit-variance x
    expectation = {(p, q): sp.Integer(1 if p == q else 0) for p in range(columns) for q in range(columns)}
    covariance = sp.Matrix(columns, columns, lambda p, q: expectation[(p, q)])
    if covariance != sp.eye(2) or len(x) != 2:
        return Verdict(
            Status.REFUTED, f"for n = {order}, x has {columns} entries and cov x = {covariance.tolist()}"
        )
    return Verdict(
        Status.PROVED,
        f"For n = {order}, K has {columns} columns, so x = [x_1, x_2]ᵀ; independence and unit variance give "
        "E[x_i x_j] = δ_ij, i.e. cov x = I_2 as printed (and K Kᵀ in (27) follows).",
    )


def _simulation_cases(realisations: int, gyros_per_case: int) -> Fraction:
    return Fraction(realisations, gyros_per_case)


def _check_rrw_simulation_setup(realisations: int = 2 * 1000, printed_cases: int = 1000) -> Verdict:
    cases = _simulation_cases(realisations, 2)
    if cases != printed_cases:
        return Verdict(
            Status.REFUTED, f"{realisations} realisations give {cases} carouselled cases, not {printed_cases}"
        )
    with mpmath.workdps(DIGITS):
        relative_error = mpmath.sqrt(mpmath.mpf(2) / (printed_cases - 1))
    return Verdict(
        Status.VERIFIED,
        f"{realisations} realisations = 2 gyros × {printed_cases} carouselled cases (averaging needs one "
        f"per case). "
        f"A variance estimated from {printed_cases} Gaussian cases has relative standard error √(2/999) = "
        f"{mpmath.nstr(100 * relative_error, 4)} %, the scatter to expect around (15) and (17) in Fig. 4.",
    )


# --------------------------------------------------------------------------------------------
# §V-C: statements about the static recording, with the numbers the printed model implies
# --------------------------------------------------------------------------------------------

#: Table III of TIM 2014 (x, y): σ_WN² at τ = 1 s in (rad/s)², σ_q² in (rad/s)²/s; §V-C: 100 Hz, N = 200.
_TABLE_III = {"x": (3e-7, 3e-10), "y": (1e-7, 2e-10)}
_SAMPLE_RATE = 100.0
_SAMPLES_PER_REVOLUTION = 200


def _table_model(gyro: str, component: str) -> NoiseModel:
    white, rrw = _TABLE_III[gyro]
    if component == "white":  # per-sample variance = σ_WN²(τ = 1 s) · f_s
        return NoiseModel(sample_rate=_SAMPLE_RATE, white_variance=white * _SAMPLE_RATE)
    return NoiseModel(sample_rate=_SAMPLE_RATE, rrw_variance=rrw / _SAMPLE_RATE)


def _check_x_rrw_slope(taus_seconds: tuple[float, ...] = (60.0, 600.0)) -> Verdict:
    samples = np.array([int(tau * _SAMPLE_RATE) for tau in taus_seconds])
    white = model_allan_variance(_table_model("x", "white"), samples)
    rrw = model_allan_variance(_table_model("x", "rrw"), samples)
    crossing = float(np.sqrt(3 * _TABLE_III["x"][0] / _TABLE_III["x"][1]))
    ratios = ", ".join(
        f"{r / w:.3g} at τ = {tau:g} s" for tau, w, r in zip(taus_seconds, white, rrw, strict=True)
    )
    return Verdict(
        Status.NOT_CHECKABLE,
        "Fig. 6 is not public. With the printed x values the RRW term σ_q²τ/3 overtakes the white term at "
        f"τ = √(3σ_WN²/σ_q²) = {crossing:.1f} s and dominates it by {ratios}: a curve with these parameters "
        "would show a clear ascending slope, so the printed x σ_q² can only be an upper bound.",
    )


def _check_zero_true_rate(latitude_degrees: float = 61.5, hours: float = 1.0) -> Verdict:
    with mpmath.workdps(DIGITS):
        earth_rate = mpmath.mpf("7.292115e-5")  # rad/s, IERS
        horizontal = earth_rate * mpmath.cos(mpmath.radians(latitude_degrees))
        angle_degrees = mpmath.degrees(horizontal * 3600 * mpmath.mpf(hours))
    white_x = _table_model("x", "white").white_variance
    white_y = _table_model("y", "white").white_variance
    bin_variance = cf.WHITE_CAROUSEL_VARIANCE.subs(
        {N: _SAMPLES_PER_REVOLUTION, var_x: white_x, var_y: white_y}
    )
    bin_sigma = float(sp.sqrt(bin_variance))
    return Verdict(
        Status.NOT_CHECKABLE,
        f"The orientation and site are not given. Earth's rate is {mpmath.nstr(earth_rate, 7)} rad/s, not 0: "
        f"along a horizontal axis at {latitude_degrees}° N (Tampere, assumed) it is up to "
        f"{mpmath.nstr(horizontal, 3)} rad/s, only "
        f"{float(horizontal) / bin_sigma:.2f} σ of a carouselled bin (σ = {bin_sigma:.3g} rad/s) but up to "
        f"{mpmath.nstr(angle_degrees, 3)}° of angle in {hours:g} h, against the 1.5° reported: zero only for "
        "an axis perpendicular to Earth's axis (e.g. horizontal east–west) or with the Earth rate removed.",
    )


# --------------------------------------------------------------------------------------------
# Registry
# --------------------------------------------------------------------------------------------


def _claim(suffix: str, location: str, statement: str, check: Callable[[], Verdict]) -> Claim:
    return Claim(f"{PAPER}-{suffix}", PAPER, location, statement, check)


CLAIMS: list[Claim] = [
    _claim(
        "eq1-bias-random-constant",
        "§II-A, eq. (1)",
        "The additive bias is a random constant: b_t = b_{t−1}.",
        _check_bias_random_constant,
    ),
    _claim(
        "secIIA-bias-embeddable",
        "§II-A, after eq. (1)",
        "It would be possible to embed the bias in other error processes; here the other processes are "
        "zero-mean.",
        _check_bias_embeddable,
    ),
    _claim(
        "secIIB-white-angular-random-walk",
        "§II-B",
        "White noise (mutually independent samples, zero mean, constant variance σ_WN²) is often called "
        "angular "
        "random walk.",
        _check_white_angular_random_walk,
    ),
    _claim("secIIB-quantization-white", "§II-B", "Quantization noise is white.", _check_quantization_white),
    _claim("secIIB-thermal-white", "§II-B", "Thermal noise is white.", _check_thermal_white),
    _claim(
        "secIIC-rrw-sources",
        "§II-C, after eq. (2)",
        "An important source of RRW are changes in the temperature of the sensor; RRW is also caused by "
        "aging.",
        _not_checkable(
            "A physical attribution; no temperature or ageing record is public, and the model (2) does not "
            "distinguish causes."
        ),
    ),
    _claim(
        "secIIC-rrw-memoryless-future",
        "§II-C, after eq. (2)",
        "RRW is memoryless: r_t does not depend on other future realizations of the process than r_{t−1} "
        "(the "
        "'future' half of the Markov sentence, and the gloss 'i.e., memoryless').",
        _check_rrw_future_dependence,
    ),
    _claim(
        "eq3-fractional-integral",
        "§II-D, eq. (3)",
        "f_t = Σ_{i=1}^t Γ(t−i+d)/(Γ(t−i+1)Γ(d)) w_i is a fractional integral of order 0 < d < 1 of "
        "white noise.",
        _check_fractional_integral,
    ),
    _claim(
        "secI-flicker-name-spectral",
        "§I, ¶4 and §II-D",
        "1/f (flicker) noise is named after its power spectral density; it is modelled by the fractional "
        "integral (3).",
        _check_flicker_name,
    ),
    _claim(
        "secI-flicker-nontrivial-to-synthesize",
        "§I, ¶4",
        "1/f noise is a long-memory process and is nontrivial to synthesize [16]–[21].",
        _check_flicker_synthesis,
    ),
    _claim(
        "secIID-physical-origin-unknown",
        "§II-D, after eq. (3)",
        "Although encountered in various contexts, the physical origin of 1/f noise is unknown [25].",
        _not_checkable("A statement about the state of physics [25]; nothing in the model decides it."),
    ),
    _claim(
        "eq4-measurement-model",
        "§III, eqs. (4a), (4b)",
        "ω_x = −ω sin φ + ω^⊥ cos φ + ε_x, ω_y = ω cos φ + ω^⊥ sin φ + ε_y for two perpendicular gyros "
        "rotated "
        "by φ in the plane of their sensitive axes.",
        _check_measurement_model,
    ),
    _claim(
        "eq5-estimator",
        "§III, eq. (5)",
        "ω̂ = −ω_x sin φ + ω_y cos φ = ω + ε̃.",
        _check_estimator,
    ),
    _claim(
        "eq5-perpendicular-estimator",
        "§III, after eq. (5)",
        "The angular rate ω̂^⊥ about the perpendicular axis could be computed in a similar manner.",
        _check_perpendicular_estimator,
    ),
    _claim(
        "eq6-revolution-average",
        "§III, eq. (6)",
        "ω_t = (1/N) Σ_{i=1}^N −ω_x((t−1)T + iT/N) sin(2πi/N) + ω_y((t−1)T + iT/N) cos(2πi/N) estimates the "
        "average angular rate during the t-th revolution (uniform rate, period T, sampling N/T Hz, "
        "integer N).",
        _check_revolution_average,
    ),
    _claim(
        "eq7-continuous-bias-integral",
        "§III-A, eq. (7)",
        "∫_0^{2π} b sin φ dφ = 0, and the same with cosine: in continuous time carouseling cancels the bias.",
        _check_continuous_bias_integral,
    ),
    _claim(
        "secIIIA-integer-ratio-assumption",
        "§III-A, before eq. (8)",
        "The discrete-time cancellation holds under the assumption that the sampling rate is uniform and "
        "an integer "
        "multiple of the carouseling frequency.",
        _check_integer_ratio_needed,
    ),
    _claim(
        "secIIIB-averaging-decreases-variance",
        "§III-B, first sentence",
        "Averaging uncorrelated noise obviously decreases its variance.",
        _check_averaging_decreases,
    ),
    _claim(
        "eq10-cumulative-sum-matrix",
        "§III-C, eq. (10)",
        "R, the N×N lower-triangular cumulative sum matrix, maps white increments q to the RRW of (2).",
        _check_cumulative_sum_matrix,
    ),
    _claim(
        "eq11-partition",
        "§III-C, eq. (11)",
        "The 2N×2N cumulative sum matrix partitions as R_2 = [[R, 𝕆], [𝕀, R]].",
        _check_partition,
    ),
    _claim(
        "eq12-integrator-vector",
        "§III-C, eq. (12)",
        "The integrator vector is 1 = (1/N)[1 1 …]ᵀ ∈ ℝ^N.",
        _check_integrator_vector,
    ),
    _claim(
        "eq13-carousel-vectors",
        "§III-C, eq. (13)",
        "s = (1/N)[sin 2π(1/N) … sin 2π]ᵀ, c = (1/N)[cos 2π(1/N) … cos 2π]ᵀ.",
        _check_carousel_vectors,
    ),
    _claim(
        "eq14-two-bin-means",
        "§III-C, eq. (14)",
        "Two consecutive direct N-averages of an RRW sequence are [[1ᵀ, 0ᵀ], [0ᵀ, 1ᵀ]] R_2 q.",
        _check_two_bin_means,
    ),
    _claim(
        "eq15-block-expansion",
        "§III-C, eq. (15), first three lines",
        "W R_2 σ_q² I R_2ᵀ Wᵀ = σ_q² [[1ᵀRRᵀ1, 1ᵀR𝕀ᵀ1], [1ᵀ𝕀Rᵀ1, 1ᵀRRᵀ1 + 1ᵀ𝕀𝕀ᵀ1]] = σ_q² [[Σi²/N², ΣiN/N²], "
        "[ΣiN/N², Σi²/N² + N³/N²]].",
        _check_eq15_block_expansion,
    ),
    _claim(
        "eq16-carouselled-averages",
        "§III-C, eq. (16)",
        "The carouselled averages of two revolutions are −[[sᵀ, 0ᵀ], [0ᵀ, sᵀ]] R_2 q_x + [[cᵀ, 0ᵀ], [0ᵀ, "
        "cᵀ]] R_2 "
        "q_y, each gyro with its own RRW driving noise.",
        _check_carouselled_averages,
    ),
    _claim(
        "eq17-block-entries",
        "§III-C, eq. (17), first line",
        "The covariance of the sine term of (16) is σ_q² [[sᵀRRᵀs, sᵀR𝕀ᵀs], [sᵀ𝕀Rᵀs, sᵀRRᵀs + sᵀ𝕀𝕀ᵀs]], "
        "whose "
        "𝕀-terms vanish since 1ᵀs = 0.",
        _check_eq17_block_entries,
    ),
    _claim(
        "secIIIC-averages-correlated",
        "§III-C, after eq. (15)",
        "It can be seen that the two (directly averaged) averages are correlated.",
        _check_averages_correlated,
    ),
    _claim(
        "secIIIC-period-not-explicit",
        "§III-C, after eq. (18)",
        "The carouseling period T does not appear explicitly in (15) and (18); at a constant sampling "
        "rate T is "
        "proportional to N.",
        _check_period_not_explicit,
    ),
    _claim(
        "secIIIC-driving-variance-sampling-rate",
        "§III-C, after eq. (18)",
        "The variance σ_q² of the RRW driving noise depends on the sampling rate.",
        _check_sampling_rate_scaling,
    ),
    _claim(
        "eq26-cov-x-identity",
        "§IV, eq. (26)",
        "Under the i.i.d. and unit variance assumptions, cov x = [[1, 0], [0, 1]].",
        _check_covariance_identity,
    ),
    _claim(
        "sec4-sequence-variance-depends-on-length",
        "§IV, before Algorithm 1",
        "'Sequence' rather than 'stochastic process': the variance of the individual random variables in the "
        "sequence is a function of the length of the sequence.",
        _check_sequence_variance_length,
    ),
    _claim(
        "sec4-pure-flicker-allan-constant",
        "§IV, after eq. (20)",
        "If y consists of pure 1/f noise, it can be expected that σ_A²(τ) is independent of τ [25], [31], "
        "[32].",
        _check_flicker_allan_constant,
    ),
    _claim(
        "secVC-zero-true-rate",
        "§V-C, ¶1",
        "During the entire test, the true angular rate to be measured by the sensors was zero.",
        _check_zero_true_rate,
    ),
    _claim(
        "secVC-x-rrw-slope",
        "§V-C, ¶1, Fig. 6, Table III",
        "The x-gyro does not exhibit a clear ascending RRW slope; its RRW was estimated at the same τ as for "
        "the y-gyro.",
        _check_x_rrw_slope,
    ),
    _claim(
        "secVA-simulation-setup",
        "§V-A, ¶1",
        "2×1000 mutually independent RRW realisations (σ_q² = 1), averaged and carouselled with N = 200, "
        "result in "
        "1000 simulation cases.",
        _check_rrw_simulation_setup,
    ),
]
