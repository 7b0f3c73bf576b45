"""Helpers shared by the claim modules: the working precision, exact-to-mpmath conversion, the
registry's formulas, the cumulative-sum matrix of TIM 2014 eq. (10), the fractional coefficients of
TIM 2014 eq. (3) and SJ 2012 eq. (3), (6), and the verdict of a claim whose evidence is not public.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction

import mpmath
import sympy as sp

from carousel_theory.claim import Status, Verdict
from carousel_theory.processes import rate_random_walk_covariance

__all__ = [
    "DIGITS",
    "EXAMPLE_RECORD",
    "SIMULATION_N",
    "UndecidedIdentityError",
    "check_rrw_future_dependence",
    "conditional_rrw_covariance",
    "counterexample",
    "cumulative_sum_matrix",
    "exact_mpf",
    "exact_sequence",
    "figure_1_not_public",
    "not_checkable",
    "phi",
    "psi",
    "ratio_is",
    "real_d",
    "real_hurst",
    "real_m",
    "registry_formula",
    "simplifies_to_zero",
    "six_digits",
]

#: Real symbols of SJ 2012 eq. (3), (4), (6): the order d, the index m and the Hurst exponent H.
real_d, real_m, real_hurst = sp.symbols("d m H", real=True)


def phi(d, m):  # (1 − z)^d coefficient
    return sp.gamma(m - d) / (sp.gamma(m + 1) * sp.gamma(-d))


def psi(d, m):  # (1 − z)^{−d} coefficient, TIM 2014 eq. (3)
    return sp.gamma(m + d) / (sp.gamma(m + 1) * sp.gamma(d))


def ratio_is(expression, expected) -> bool:
    """a_{m+1}/a_m of a Gamma-ratio sequence equals ``expected`` identically in m and d."""
    ratio = sp.gammasimp(expression.subs(real_m, real_m + 1) / expression)
    return sp.simplify(ratio - expected) == 0


def exact_sequence(order: Fraction, length: int) -> list[Fraction]:
    out = [Fraction(1)]
    for j in range(1, length):
        out.append(out[-1] * (j - 1 - order) / j)
    return out


#: Small integer record for the exact Allan-variance and moving-average examples.
EXAMPLE_RECORD = (3, -1, 4, 1, -5, 9, 2, -6, 5, 3, -5, 8)


DIGITS = 50


def registry_formula(name: str):
    from carousel_theory.formulas import formula

    return formula(name)


def exact_mpf(value) -> mpmath.mpf:
    """An exact value (Fraction, int, SymPy number) as an mpmath number at the current precision."""
    if isinstance(value, Fraction):
        return mpmath.mpf(value.numerator) / value.denominator
    if isinstance(value, sp.Basic):
        return mpmath.mpf(sp.N(value, mpmath.mp.dps + 5))
    return mpmath.mpf(value)


def not_checkable(reason: str):
    def check() -> Verdict:
        return Verdict(Status.NOT_CHECKABLE, reason)

    return check


#: The simulations of §V-A/B: N = 200 samples per bin, d = 1/2, σ² = 1.
SIMULATION_N = 200


def six_digits(value: float) -> str:
    return f"{value:.6g}"


class UndecidedIdentityError(ArithmeticError):
    """SymPy's simplifier left a remainder, and no sample point shows the remainder to be nonzero:
    neither a proof nor a counterexample. A check that meets it reports FAILED."""


#: Values tried for each free symbol, by its assumptions: integers ≥ 2 for integer symbols, and
#: rationals for the others (positive ones where the symbol is positive).
_INTEGER_SAMPLES = (2, 3, 5, 7, 12)
_RATIONAL_SAMPLES = (sp.Rational(1, 3), sp.Rational(5, 2), sp.Rational(3, 7), sp.Rational(9, 4), 2)


def _sample_points(symbols: list[sp.Symbol]) -> list[dict[sp.Symbol, sp.Expr]]:
    points = []
    for index in range(len(_INTEGER_SAMPLES)):
        point = {}
        for offset, symbol in enumerate(symbols):
            pool = _INTEGER_SAMPLES if symbol.is_integer else _RATIONAL_SAMPLES
            value = sp.sympify(pool[(index + offset) % len(pool)])
            point[symbol] = value if symbol.is_nonnegative or symbol.is_positive else value * (-1) ** offset
        points.append(point)
    return points


def counterexample(expression: sp.Expr) -> str | None:
    """A point where ``expression`` is nonzero, shown exactly (a nonzero rational) or at 50 digits
    (|value| above 10⁻⁴⁰ at both 50 and 70 digits); ``None`` if no sample point shows one."""
    for point in _sample_points(sorted(expression.free_symbols, key=str)):
        value = sp.nsimplify(expression.subs(point)) if expression.free_symbols else expression
        where = ", ".join(f"{symbol} = {point[symbol]}" for symbol in sorted(point, key=str)) or "as printed"
        if value.is_Rational and value != 0:
            return f"{where}: {value} (exact)"
        low, high = sp.N(value, DIGITS), sp.N(value, DIGITS + 20)
        if low.is_number and abs(low) > sp.Float("1e-40") and abs(high - low) < abs(low) * sp.Float("1e-30"):
            return f"{where}: {sp.N(value, 12)} (at {DIGITS} digits)"
    return None


def simplifies_to_zero(expression: sp.Expr | sp.Matrix) -> bool:
    """True when SymPy simplifies ``expression`` (every entry of a matrix) to 0; False only with a
    counterexample (:func:`counterexample`); raises :class:`UndecidedIdentityError` when neither decides,
    so that a simplifier that stops short of zero never turns into a refutation."""
    entries = list(expression) if isinstance(expression, sp.MatrixBase) else [expression]
    for entry in entries:
        remainder = sp.simplify(entry)
        if remainder == 0:
            continue
        if counterexample(remainder) is None:
            raise UndecidedIdentityError(
                f"simplify left {sp.sstr(remainder)!r} and no sample point is nonzero"
            )
        return False
    return True


def cumulative_sum_matrix(size: int) -> sp.Matrix:
    """The lower-triangular matrix of ones of TIM 2014 eq. (10), built from its definition."""
    return sp.Matrix(size, size, lambda row, column: 1 if column <= row else 0)


def conditional_rrw_covariance(size: int, targets: tuple[int, int], given: tuple[int, ...]) -> sp.Expr:
    """Cov(r_p, r_q | r_given) of the Gaussian RRW with Cov(r_s, r_t) = min(s, t), exact (times 1-based)."""
    covariance = sp.Matrix(size, size, lambda s, t: rate_random_walk_covariance(s + 1, t + 1))
    first, second = (index - 1 for index in targets)
    conditioning = [index - 1 for index in given]
    cross = sp.Matrix([[covariance[first, c] for c in conditioning]])
    cross_second = sp.Matrix([[covariance[second, c] for c in conditioning]])
    block = covariance.extract(conditioning, conditioning)
    return sp.nsimplify(covariance[first, second] - (cross * block.inv() * cross_second.T)[0])


def check_rrw_future_dependence(t: int = 3, size: int = 6) -> Verdict:
    past = conditional_rrw_covariance(size, (t, t - 2), (t - 1,))
    future = conditional_rrw_covariance(size, (t, t + 1), (t - 1,))
    both_neighbours = [
        conditional_rrw_covariance(size, (t, u), (t - 1, t + 1))
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


def figure_1_not_public(what: str) -> Callable[[], Verdict]:
    def check() -> Verdict:
        return Verdict(
            Status.NOT_CHECKABLE,
            f"{what}: read from Fig. 1, whose curves are not in the text rendering and whose data "
            "(AIST-350, ADXRS150 recordings) are not public.",
        )

    return check
