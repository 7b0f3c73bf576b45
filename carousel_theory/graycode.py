"""Constant-Allan-variance sequences built from Gray-code square waves (TIM 2014 §IV).

Algorithm 1 of TIM 2014 builds the deterministic sequence S_{2^n} by repeating every element of
the previous sequence twice and adding the period-four sequence a_k of eq. (22). Column i of the
2^n × n matrix K (eq. (24)) is a_{1…2^i} ⊗ 1_{2^{n−i}}, a square wave; S = K 1 (eq. (32)) and the
stochastic sequence is R = C K x with x i.i.d., zero mean, unit variance.

Conventions (0-based row r = 0 … 2^n − 1, i.e. the paper's row r + 1): K + ½ is the matrix of the
binary reflected Gray code g(r) = r XOR ⌊r/2⌋, written most significant bit first, so column i
holds the bit of weight 2^{n−i}. Hence S_{2^n}[r] = popcount(g(r)) − n/2 and
(K Kᵀ)[r, s] = −½ S_{2^n}[r XOR s].

The closed forms of the section live here once, as SymPy expressions (``ALLAN_VARIANCE``,
``PROCESS_VARIANCE``, ``GRAM_SCALE``, ``MVUE_VARIANCE``, ``ALLAN_ESTIMATOR_VARIANCE``); numbers
come from them.
"""

from __future__ import annotations

import functools
import os
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from carousel_theory._validation import check_finite_array, check_integer, check_real

__all__ = [
    "ALLAN_ESTIMATOR_VARIANCE",
    "ALLAN_VARIANCE",
    "GRAM_SCALE",
    "MINIMUM_ORDER",
    "MVUE_VARIANCE",
    "PROCESS_VARIANCE",
    "allan_estimator_variance",
    "allan_variance_exact",
    "allan_variance_statistic",
    "covariance_entry",
    "deterministic_sequence",
    "gray_code",
    "gray_column",
    "gray_matrix",
    "innovation_index",
    "mvue_variance",
    "mvue_variance_estimate",
    "overlapping_allan_variance_exact",
    "pseudoinverse",
    "sequence",
    "sequence_coefficients",
    "sequence_from_innovations",
]

#: Algorithm 1 takes 1 < n ∈ ℕ.
MINIMUM_ORDER = 2

#: Symbols of this section: the order n (length 2^n), the octave m (τ = 2^m) and the scale C.
n_symbol = sp.Symbol("n", integer=True, positive=True)
m_symbol = sp.Symbol("m", integer=True, nonnegative=True)
C_symbol = sp.Symbol("C", positive=True)

#: E[σ_A²(2^m)] of R = C K x for every m = 0 … n − 1: TIM 2014 eq. (20), (23), (30).
ALLAN_VARIANCE = C_symbol**2 / 2
#: Var R_t = C² (K Kᵀ)[t, t] = C² n / 4 for every t ("variance-stationary", TIM 2014 §IV).
PROCESS_VARIANCE = C_symbol**2 * n_symbol / 4
#: Kᵀ K = 2^{n−2} I, so K⁺ = 2^{2−n} Kᵀ (TIM 2014 eq. (31) is the case n = 2).
GRAM_SCALE = 2 ** (n_symbol - 2)
#: Var of the MVUE ‖K⁺R‖²/n of C² for Gaussian x: 2C⁴/n.
MVUE_VARIANCE = 2 * C_symbol**4 / n_symbol
#: Var of the unbiased Allan estimator 2σ_A²(2^m) for Gaussian x. With p = n − m, the 2^p − 1 bin
#: differences involve x_1 … x_p, and x_i enters 2^{i−1} of them, so
#: Var = 2C⁴ Σ 4^{i−1} / (2^p − 1)² = 2C⁴ (2^p + 1) / (3 (2^p − 1)).
ALLAN_ESTIMATOR_VARIANCE = (
    2 * C_symbol**4 * (2 ** (n_symbol - m_symbol) + 1) / (3 * (2 ** (n_symbol - m_symbol) - 1))
)

# Share of the physical memory one call may plan to use.
_MEMORY_SHARE = 0.5


@functools.cache
def _physical_memory_bytes() -> int:
    try:
        return int(os.sysconf("SC_PHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):  # pragma: no cover - non-POSIX systems
        return 8 * 2**30


def _check_order(n: Any, bytes_per_row: int = 0) -> int:
    """Validate the order n of Algorithm 1 (an integer ≥ 2) and, before anything is allocated, that
    the work fits in half the physical memory: 2^n rows × ``bytes_per_row`` bytes at the peak
    (0 for closed forms, which allocate nothing of length 2^n)."""
    value = check_integer("n", n)
    if value < MINIMUM_ORDER:
        raise ValueError(f"n={n!r}: must be an integer >= {MINIMUM_ORDER} (TIM 2014 Algorithm 1 takes 1 < n)")
    if bytes_per_row:
        limit = int(_physical_memory_bytes() * _MEMORY_SHARE)
        needed = 2**value * bytes_per_row
        if needed > limit:
            raise ValueError(
                f"n={n!r}: needs about {needed:.3g} bytes of memory (2^{value} rows x {bytes_per_row} "
                f"bytes), more than half of this machine's memory ({limit:.3g} bytes); use a smaller n"
            )
    return value


#: Peak bytes per sample of Algorithm 1 (four float64 arrays of length 2^n at once).
_SEQUENCE_BYTES_PER_ROW = 32


def _check_octave(m: Any, n: int) -> int:
    value = check_integer("m", m)
    if not 0 <= value <= n - 1:
        raise ValueError(f"m={m!r}: must be an integer in 0..{n - 1} (τ = 2^m, TIM 2014 eq. (21))")
    return value


def _check_scale(C: Any) -> Any:
    value = check_real("C", C)
    if not value > 0:
        raise ValueError(f"C={C!r}: must be > 0")
    return value


def _is_exact(value: Any) -> bool:
    return isinstance(value, (int, Fraction, sp.Rational)) and not isinstance(value, bool)


def _evaluate(expression: sp.Expr, C: Any, **values: int) -> Any:
    """Exact SymPy value for exact C (int, Fraction, Rational), float otherwise."""
    substituted = expression.subs({n_symbol: values.get("n", n_symbol), m_symbol: values.get("m", m_symbol)})
    if _is_exact(C):
        exact_C = sp.Rational(C.numerator, C.denominator) if isinstance(C, (Fraction, int)) else C
        return sp.simplify(substituted.subs(C_symbol, exact_C))
    return float(substituted.subs(C_symbol, sp.Float(float(C), 30)))


def sequence_coefficients(length: int) -> np.ndarray:
    """a_1 … a_length of TIM 2014 eq. (22): a_1 = −½, a_2 = +½, a_k = −a_{k−2}; period four
    (−½, +½, +½, −½)."""
    length = check_integer("length", length)
    if length < 1:
        raise ValueError(f"length={length!r}: must be an integer >= 1")
    return _coefficients(length).copy()


# eq. (22) applied twice gives a_k = a_{k−4}, so one period determines the sequence.
_PERIOD = np.array([-0.5, 0.5, 0.5, -0.5])
_PERIOD.flags.writeable = False


def _coefficients(length: int) -> np.ndarray:
    """a_1 … a_length (length already checked)."""
    periods = -(-length // 4)
    return np.broadcast_to(_PERIOD, (periods, 4)).reshape(-1)[:length]


def gray_code(r: Any) -> Any:
    """The binary reflected Gray code g(r) = r XOR ⌊r/2⌋ (int or integer array)."""
    return r ^ (r >> 1)


def sequence_from_innovations(x: Any, C: Any = 1.0) -> np.ndarray:
    """R_{2^n} = C K x by Algorithm 1 with a_{1…2^i} x_i added at step i (TIM 2014 §IV, Table II).

    ``x`` holds x_1 … x_n (n ≥ 2); no 2^n × n matrix is formed: O(2^n) time and memory.
    """
    x = check_finite_array("x", x, ndim=1, min_length=MINIMUM_ORDER)
    C = _check_scale(C)
    n = _check_order(x.shape[0], _SEQUENCE_BYTES_PER_ROW)
    coefficients = _coefficients(2**n)  # a_{1…2^i} is the prefix of length 2^i
    values = coefficients[:2] * x[0]  # line 1 of Algorithm 1, scaled by x_1
    for i in range(2, n + 1):
        # line 3: v ⊗ [1 1] + a_{1…2^i} x_i
        values = np.repeat(values, 2) + coefficients[: 2**i] * x[i - 1]
    return float(C) * values


def deterministic_sequence(n: int) -> np.ndarray:
    """S_{2^n} of TIM 2014 Algorithm 1 (length 2^n, half-integer values, exact in float64)."""
    n = _check_order(n, _SEQUENCE_BYTES_PER_ROW)
    return sequence_from_innovations(np.ones(n))


def gray_matrix(n: int) -> np.ndarray:
    """K ∈ ℝ^{2^n × n} of TIM 2014 eq. (24): column i is a_{1…2^i} ⊗ 1_{2^{n−i}}.

    K + ½ is the binary reflected Gray code matrix (row r = g(r), most significant bit first).
    """
    n = _check_order(n)
    _check_order(n, 8 * (n + 1))  # the matrix and one column being built
    matrix = np.empty((2**n, n), dtype=np.float64)
    for i in range(1, n + 1):
        matrix[:, i - 1] = gray_column(n, i)
    return matrix


def gray_column(n: int, i: int) -> np.ndarray:
    """Column i (1 … n) of K: a_{1…2^i} ⊗ 1_{2^{n−i}}, a square wave of ±½ (TIM 2014 §IV)."""
    n = _check_order(n, 16)
    i = check_integer("i", i)
    if not 1 <= i <= n:
        raise ValueError(f"i={i!r}: must be a column number in 1..{n}")
    return 0.5 * _twice_column(n, i)


def _twice_column(n: int, i: int) -> np.ndarray:
    """2 × column i of K as int8 (±1): a_{1…2^i} ⊗ 1_{2^{n−i}} doubled; arguments already checked."""
    twice_coefficients = (2 * sequence_coefficients(2**i)).astype(np.int8)
    return np.repeat(twice_coefficients, 2 ** (n - i))


def sequence(n: int, C: Any = 1.0, *, rng: np.random.Generator) -> np.ndarray:
    """A random R_{2^n} = C K x with x ~ N(0, I_n): its non-overlapping Allan variance has
    expectation exactly C²/2 at every τ = 2^m, m = 0 … n − 1 (TIM 2014 eq. (23), (30))."""
    n = _check_order(n, _SEQUENCE_BYTES_PER_ROW)
    C = _check_scale(C)
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng={rng!r}: must be a numpy.random.Generator (numpy.random.default_rng(seed))")
    return sequence_from_innovations(rng.standard_normal(n), C)


def innovation_index(n: int, m: int, j: int) -> int:
    """Which x_i the j-th bin difference (j = 1 … 2^{n−m} − 1) of R at τ = 2^m equals, up to sign.

    R̄(τ)_{j+1} − R̄(τ)_j = ± C x_i with i = n − m − ν₂(j), ν₂ the 2-adic valuation: the Gray code
    of j − 1 and of j differ in the bit of weight 2^{ν₂(j)}. This corrects TIM 2014 eq. (23), which
    writes one x_τ for all j.
    """
    n = _check_order(n)
    m = _check_octave(m, n)
    j = check_integer("j", j)
    if not 1 <= j <= 2 ** (n - m) - 1:
        raise ValueError(f"j={j!r}: must be an integer in 1..{2 ** (n - m) - 1}")
    return n - m - ((j & -j).bit_length() - 1)


def allan_variance_statistic(y: Any, tau: int) -> float:
    """The non-overlapping Allan variance statistic of TIM 2014 eq. (20) at an integer τ (samples)."""
    y = check_finite_array("y", y)
    tau = check_integer("tau", tau)
    bins = y.shape[0] // tau if tau >= 1 else 0
    if bins < 2:
        raise ValueError(f"tau={tau!r}: must be an integer in 1..{y.shape[0] // 2} (at least two bins)")
    means = y[: bins * tau].reshape(bins, tau).mean(axis=1)
    return float(np.sum(np.diff(means) ** 2) / (2 * (bins - 1)))


def allan_variance_exact(n: int, m: int, C: Any = 1.0) -> Any:
    """E[σ_A²(τ)] of R_{2^n} = C K x at τ = 2^m, m = 0 … n − 1: exactly C²/2 (TIM 2014 eq. (30)).

    Exact (SymPy) for exact C (int, Fraction, Rational), float otherwise. The deterministic
    S_{2^n} has σ_A²(2^m) = ½ exactly (C = 1).
    """
    n = _check_order(n)
    m = _check_octave(m, n)
    C = _check_scale(C)
    return _evaluate(ALLAN_VARIANCE, C, n=n, m=m)


def overlapping_allan_variance_exact(n: int, m: int, C: Any = 1) -> Any:
    """E of the fully overlapping Allan variance of R_{2^n} = C K x at τ = 2^m, exactly.

    σ²_overlap(τ) = Σ_{t=0}^{L−1} (ȳ_{t+τ} − ȳ_t)² / (2L), ȳ_t the mean of y_t … y_{t+τ−1},
    L = 2^n − 2τ + 1. Not constant in τ (TIM 2014 §IV, last paragraph before (32)). By independence of
    the x_i, E = C² Σ_i Σ_t (window-mean difference of column i)² / (2L); the window sums of each
    square-wave column come from m doublings in narrow integer types, O(2^n n m) time, and the result
    is a SymPy Rational times C² (exact for exact C).
    """
    n = _check_order(n, 24)
    m = _check_octave(m, n)
    C = _check_scale(C)
    tau = 2**m
    windows = 2**n - 2 * tau + 1
    total = 0
    for i in range(1, n + 1):
        # sums of 2K over every window of length 2^{k+1}: w_{k+1}[t] = w_k[t] + w_k[t + 2^k], in the
        # narrowest integer type that holds the later difference of two windows (|change| ≤ 2τ)
        window = _twice_column(n, i).astype(_integer_type(2 * tau))
        for k in range(m):
            window = window[: -(2**k)] + window[2**k :]
        change = np.abs(window[tau:] - window[:-tau])
        # exact sum of squares for every n: count each value, square in Python integers
        counts = np.bincount(change)
        total += sum(int(count) * value * value for value, count in enumerate(counts.tolist()) if count)
    # a difference of means of K is change / (2τ)
    expectation_unit = sp.Rational(total, 4 * tau**2 * 2 * windows)
    return _evaluate(C_symbol**2 * expectation_unit, C)


def _integer_type(bound: int) -> type[np.signedinteger]:
    """The narrowest signed integer type holding every value of magnitude up to ``bound``."""
    for candidate in (np.int8, np.int16, np.int32):
        if bound <= np.iinfo(candidate).max:
            return candidate
    return np.int64


def allan_estimator_variance(n: int, m: int, C: Any = 1.0) -> Any:
    """Var[2σ_A²(2^m)] of R_{2^n} for Gaussian x: 2C⁴(2^p + 1)/(3(2^p − 1)), p = n − m."""
    n = _check_order(n)
    m = _check_octave(m, n)
    C = _check_scale(C)
    return _evaluate(ALLAN_ESTIMATOR_VARIANCE, C, n=n, m=m)


def mvue_variance(n: int, C: Any = 1.0) -> Any:
    """Var of the minimum-variance unbiased estimator ‖K⁺R‖²/n of C² for Gaussian x: 2C⁴/n."""
    n = _check_order(n)
    C = _check_scale(C)
    return _evaluate(MVUE_VARIANCE, C, n=n)


def covariance_entry(n: int, r: int, s: int) -> Fraction:
    """(K Kᵀ)[r, s] = (n − 2 popcount(g(r XOR s)))/4 = −½ S_{2^n}[r XOR s], rows from 0.

    Entries of K are ±½, so a product of two rows counts agreeing bits minus disagreeing bits over
    four; the disagreeing bits are g(r) XOR g(s) = g(r XOR s) because g is linear over GF(2).
    """
    n = _check_order(n)
    r = check_integer("r", r)
    s = check_integer("s", s)
    for name, value in (("r", r), ("s", s)):
        if not 0 <= value < 2**n:
            raise ValueError(f"{name}={value!r}: must be a row index in 0..{2**n - 1}")
    return Fraction(n - 2 * gray_code(r ^ s).bit_count(), 4)


def pseudoinverse(n: int) -> np.ndarray:
    """K⁺ = (KᵀK)⁻¹Kᵀ = 2^{2−n} Kᵀ (n × 2^n), since KᵀK = 2^{n−2} I (TIM 2014 eq. (31) for n = 2)."""
    n = _check_order(n)
    _check_order(n, 8 * (2 * n + 1))  # K, its scaled transpose and one column
    scale = float(1 / GRAM_SCALE.subs(n_symbol, n))
    return scale * gray_matrix(n).T


def mvue_variance_estimate(R: Any) -> float:
    """The minimum-variance unbiased estimate ‖K⁺R‖²/n of C² from one R_{2^n} (Gaussian x).

    K⁺R = C x (TIM 2014 §IV); x has known mean zero, so the MVUE is the mean of squares (divisor
    n). K⁺R is computed column by column, without forming K.
    """
    R = check_finite_array("R", R)
    length = R.shape[0]
    n = length.bit_length() - 1
    if length != 2**n:
        raise ValueError(f"R: length must be a power of two 2^n with n >= {MINIMUM_ORDER}, got {length}")
    n = _check_order(n)
    scale = float(1 / GRAM_SCALE.subs(n_symbol, n))
    total = 0.0
    for i in range(1, n + 1):
        # column i of K is a square wave: sum R over blocks of 2^{n−i}, weight by a_{1…2^i}
        block_sums = R.reshape(2**i, 2 ** (n - i)).sum(axis=1)
        total += (scale * float(sequence_coefficients(2**i) @ block_sums)) ** 2
    return total / n
