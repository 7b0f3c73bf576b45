"""Fast structural checks of every property of TIM 2014 §IV for one order n, in O(2^n n) time.

No 2^n × 2^n matrix is ever formed: the columns of K are square waves (checked one at a time as
int8 arrays of 2K = ±1), bin averages at τ = 2^m come from repeated pairwise sums, K Kᵀ is
checked through its closed form −½ S[r XOR s] on a fixed set of columns, and the Gram matrix
Kᵀ K is accumulated over row blocks. ``check_up_to(N)`` runs every property for n = 2 … N and
reports, per property, the largest n up to which it held for every n and the time it took.

The proofs for all n are in ``proofs/proof_graycode_*.py``; these checks are a second, direct way.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property

import numpy as np

from carousel_theory._validation import check_integer
from carousel_theory.graycode import (
    MINIMUM_ORDER,
    _check_order,
    _twice_column,
    deterministic_sequence,
    gray_code,
    overlapping_allan_variance_exact,
    sequence_coefficients,
)
from carousel_theory.progress import progress

__all__ = ["PROPERTIES", "PropertyResult", "check_order", "check_up_to"]

#: Peak memory per row of the checks of one order (measured: about 1.7 GB at n = 24, ~100 bytes/row).
_BYTES_PER_ROW = 128


class _Workspace:
    """Arrays shared by the checks of one order n, computed on first use."""

    def __init__(self, n: int) -> None:
        self.n = n
        self.length = 2**n

    @cached_property
    def rows(self) -> np.ndarray:
        return np.arange(self.length, dtype=np.int32 if self.n <= 30 else np.int64)

    @cached_property
    def gray(self) -> np.ndarray:
        return gray_code(self.rows)

    @cached_property
    def ones_in_gray(self) -> np.ndarray:
        return np.bitwise_count(self.gray).astype(np.int32)

    @cached_property
    def twice_sequence(self) -> np.ndarray:
        """2 S_{2^n} from Algorithm 1 as exact integers."""
        twice = 2.0 * deterministic_sequence(self.n)
        integers = np.rint(twice).astype(np.int32)
        if not np.array_equal(integers, twice):
            raise AssertionError("2 S is not integer-valued")
        return integers

    @cached_property
    def columns(self) -> list[np.ndarray]:
        """2K column by column (int8, ±1), from the package's column construction."""
        return [_twice_column(self.n, i) for i in range(1, self.n + 1)]

    @cached_property
    def row_words(self) -> np.ndarray:
        """Row r of K + ½ read as an n-bit integer, column 1 most significant (built from the columns)."""
        words = np.zeros(self.length, dtype=self.rows.dtype)
        for column in self.columns:
            np.left_shift(words, 1, out=words)
            np.bitwise_or(words, column > 0, out=words)
        return words

    @cached_property
    def packed_columns(self) -> list[np.ndarray]:
        """Column i of K + ½ packed eight rows to a byte."""
        return [np.packbits(column > 0) for column in self.columns]

    @cached_property
    def selected_columns(self) -> list[int]:
        """Columns s of K Kᵀ checked at every n: all of them while 4^n ≤ 2^20, else first, last,
        the row of the maximum of S and three seeded random rows."""
        if self.n <= 10:
            return list(range(self.length))
        rng = np.random.default_rng(self.n)
        picks = {0, 1, self.length - 1, 2 ** (self.n + 1) // 3}
        picks.update(int(v) for v in rng.integers(0, self.length, size=3))
        return sorted(picks)


def _level_sums(values: np.ndarray, n: int, magnitude: int = 1) -> Iterator[tuple[int, np.ndarray]]:
    """Yield (m, bin sums at τ = 2^m) for m = 0 … n − 1, by pairwise summation of integers with
    |values| ≤ ``magnitude``: int16 while the sums fit (half the memory traffic), int32 after."""
    sums: np.ndarray = values.astype(np.int16 if 2 * magnitude < 2**15 else np.int32)
    for m in range(n):
        yield m, sums
        if sums.dtype == np.int16 and magnitude * 2 ** (m + 2) >= 2**15:
            sums = sums.astype(np.int32)
        sums = np.add(sums[0::2], sums[1::2])


def _period_four(work: _Workspace) -> bool:
    """a_k of eq. (22): the recurrence a_k = −a_{k−2} and a_{k+4} = a_k, minimal period 4."""
    a = sequence_coefficients(work.length)
    recurrence = a[0] == -0.5 and a[1] == 0.5 and np.array_equal(a[2:], -a[:-2])
    period = np.array_equal(a[4:], a[:-4]) and not np.array_equal(a[2:], a[:-2]) and a[1] != a[0]
    return bool(recurrence and period)


def _gray_matrix_convention(work: _Workspace) -> bool:
    """K + ½ is the Gray code matrix: column i holds bit n − i (weight 2^{n−i}) of g(r)."""
    if not all(np.all(np.abs(column) == 1) for column in work.columns):
        return False
    return bool(np.array_equal(work.row_words, work.gray))


def _ones_count(work: _Workspace) -> bool:
    """S + n/2 = popcount(g(r)), with S from Algorithm 1 (eq. (32))."""
    return bool(np.array_equal(work.twice_sequence + work.n, 2 * work.ones_in_gray))


def _rule_21(work: _Workspace) -> bool:
    """Eq. (21): |S̄(τ)_{j+1} − S̄(τ)_j| = 1 for τ = 1, 2, …, 2^{n−1}."""
    for m, sums in _level_sums(work.twice_sequence, work.n, work.n):
        # sums are of 2S over 2^m samples: a unit change of the mean is 2·2^m
        if not np.all(np.abs(np.diff(sums)) == 2 ** (m + 1)):
            return False
    return True


def _single_innovation(work: _Workspace) -> bool:
    """Corrected eq. (23): the j-th bin difference of R at τ = 2^m is ±x_i, exactly one i, namely
    i = n − m − ν₂(j); hence each difference has variance C² and E[2σ_A²(2^m)] = C² exactly."""
    n = work.n
    for i, column in enumerate(work.columns, start=1):
        for m, sums in _level_sums(column, n):
            differences = np.diff(sums)
            valuation = n - m - i  # the j with ν₂(j) = n − m − i are 2^k (2q + 1), k = valuation
            if valuation < 0:
                if np.count_nonzero(differences):
                    return False
                continue
            # 1-based j = 2^k (2q + 1) is 0-based index 2^k − 1 + q 2^{k+1}
            expected = differences[2**valuation - 1 :: 2 ** (valuation + 1)]
            if not np.all(np.abs(expected) == 2 ** (m + 1)):
                return False
            if np.count_nonzero(differences) != expected.size:
                return False
    # the sets {j : ν₂(j) = k}, k = 0 … n − m − 1, partition 1 … 2^{n−m} − 1, so every difference
    # involves exactly one innovation: Σ_i (ΔK)_{j,i}² = 1 and E[2σ_A²(2^m)] = C² (unit x)
    return True


def _allan_statistic_of_s(work: _Workspace) -> bool:
    """σ_A²(2^m) of the deterministic S is exactly ½ for every m (eq. (20), (21))."""
    for m, sums in _level_sums(work.twice_sequence, work.n, work.n):
        squares = int(np.sum(np.diff(sums).astype(np.int64) ** 2))
        differences = len(sums) - 1
        # σ_A² = Σ (Δ mean)² / (2(M − 1)) with Δ mean = Δ sums / 2^{m+1}
        if squares != differences * 4 ** (m + 1):
            return False
    return True


def _diagonal(work: _Workspace) -> bool:
    """diag(K Kᵀ) = n/4: Σ_i (2K)_{r,i}² = n for every row."""
    total = np.zeros(work.length, dtype=np.int16)
    for column in work.columns:
        total += column.astype(np.int16) ** 2
    return bool(np.all(total == work.n))


def _gram(work: _Workspace) -> bool:
    """Kᵀ K = 2^{n−2} I (so K⁺ = 2^{2−n} Kᵀ and K⁺K = I): accumulated over row blocks."""
    n = work.n
    gram = np.empty((n, n), dtype=np.int64)
    packed = work.packed_columns
    for i in range(n):
        for j in range(i, n):
            # (±1)(±1) is +1 where the bits agree and −1 where they differ
            disagreements = int(np.bitwise_count(packed[i] ^ packed[j]).sum(dtype=np.int64))
            gram[i, j] = gram[j, i] = work.length - 2 * disagreements
    # gram is of 2K: (2K)ᵀ(2K) = 4 · 2^{n−2} I = 2^n I
    return bool(np.array_equal(gram, work.length * np.eye(n, dtype=np.int64)))


def _covariance_columns(work: _Workspace) -> bool:
    """(K Kᵀ)[:, s] = −½ S[r XOR s] and its bin averages change by exactly ½ at every τ = 2^m
    (the rule of eq. (21) with 1 replaced by ½), for the columns ``selected_columns``."""
    n = work.n
    for s in work.selected_columns:
        # 4 (K Kᵀ)[r, s] = Σ_i (2K)_{r,i} (2K)_{s,i} = n − 2 · #(bits where rows r and s differ)
        four_column = n - 2 * np.bitwise_count(work.row_words ^ work.row_words[s]).astype(np.int32)
        if not np.array_equal(four_column, -work.twice_sequence[work.rows ^ s]):
            return False
        for m, sums in _level_sums(four_column, n, n):
            # a change of ½ in the mean of K Kᵀ is a change of 2 · 2^m in sums of 4 K Kᵀ
            if not np.all(np.abs(np.diff(sums)) == 2 ** (m + 1)):
                return False
    return True


def _not_stationary(work: _Workspace) -> bool:
    """n = 2: the covariance depends on the lag only (exhaustive); n ≥ 3: cov(R_0, R_3) −
    cov(R_1, R_4) = C² ≠ 0, so R is not stationary; it is stationary under dyadic (XOR) shifts."""
    rows = np.stack(work.columns, axis=1).astype(np.int64) if work.n == 2 else None
    if rows is not None:
        covariance = rows @ rows.T  # 4 K Kᵀ, 4 × 4
        return all(len({int(covariance[t, t + lag]) for t in range(4 - lag)}) == 1 for lag in range(4))

    def four_cov(r: int, s: int) -> int:
        return sum(int(c[r]) * int(c[s]) for c in work.columns)

    return four_cov(0, 3) - four_cov(1, 4) == 4


def _overlapping_not_constant(work: _Workspace) -> bool:
    """E of the overlapping Allan variance of R at τ = 2 differs from C²/2 for n ≥ 3 (equal for n = 2,
    where τ = 2 leaves a single difference)."""
    n = work.n
    windows = work.length - 3
    total = 0
    for column in work.columns:
        pair = column[:-1] + column[1:]  # int8: sum of a window of two samples of 2K
        change = pair[2:] - pair[:-2]
        total += int(np.sum(change * change, dtype=np.int64))
    # d_t of K = (pair difference)/4, so E σ² = total / (16 · 2L); the package's prefix-sum
    # computation must agree, and the value must differ from ½ exactly when n ≥ 3
    expectation = Fraction(total, 32 * windows)
    if expectation != overlapping_allan_variance_exact(n, 1):
        return False
    return expectation == Fraction(1, 2) if n == 2 else expectation != Fraction(1, 2)


def _mcilroy_bounds(work: _Workspace) -> bool:
    """−n/2 ≤ S ≤ n/2 with the minimum only at r = 0 and the maximum only at r = ⌊2^{n+1}/3⌋;
    G(N) = Σ_{r<N} popcount(g(r)) satisfies B(N) ≤ G(N) ≤ B(N) + 2N/5 (B: binary, McIlroy's
    sum, itself ≤ (N/2) log₂ N) for every N ≤ 2^n, with G(2^k) = k 2^{k−1}."""
    n = work.n
    s = work.twice_sequence
    minimum = np.flatnonzero(s == -n)
    maximum = np.flatnonzero(s == n)
    if not (s.min() == -n and s.max() == n and list(minimum) == [0] and list(maximum) == [2 ** (n + 1) // 3]):
        return False
    # G from the sequence itself: S_r + n/2 counts the ones of g(r) ("ones-count")
    gray_sums = np.cumsum((s + n) // 2, dtype=np.int64)
    binary_sums = np.cumsum(np.bitwise_count(work.rows), dtype=np.int64)
    counts = work.rows.astype(np.int64) + 1
    excess = gray_sums - binary_sums
    if not (np.all(excess >= 0) and np.all(5 * excess <= 2 * counts)):
        return False
    # McIlroy: B(N) <= (N/2) log2 N, with equality at powers of two (where log2 is exact in float64)
    if not np.all(2 * binary_sums <= counts * np.log2(counts) * (1 + 1e-12)):
        return False
    return all(int(gray_sums[2**k - 1]) == k * 2 ** (k - 1) for k in range(1, n + 1))


@dataclass(frozen=True)
class _Property:
    name: str
    statement: str
    check: Callable[[_Workspace], bool] = field(repr=False)


#: Every property of TIM 2014 §IV checked per order n, in report order.
PROPERTIES: tuple[_Property, ...] = (
    _Property("a-period-four", "a_k of eq. (22) has minimal period four", _period_four),
    _Property("gray-matrix", "K + 1/2 = Gray code matrix (row r = g(r), MSB first)", _gray_matrix_convention),
    _Property("ones-count", "S + n/2 = popcount(g(r)), S from Algorithm 1", _ones_count),
    _Property("eq21", "eq. (21): |ΔS̄(2^m)| = 1 for m = 0..n-1", _rule_21),
    _Property("eq23-corrected", "ΔR̄(2^m)_j = ±x_i, i = n-m-ν₂(j); E[2σ_A²] = C²", _single_innovation),
    _Property("allan-of-S", "σ_A²(2^m) of S is exactly 1/2", _allan_statistic_of_s),
    _Property("diagonal", "diag(K Kᵀ) = n/4", _diagonal),
    _Property("gram", "Kᵀ K = 2^(n-2) I, K⁺ = 2^(2-n) Kᵀ", _gram),
    _Property("covariance-columns", "(K Kᵀ)[:, s] = -S[r xor s]/2, |Δ mean| = 1/2", _covariance_columns),
    _Property("stationarity", "stationary only for n = 2 (cov(R0,R3) ≠ cov(R1,R4))", _not_stationary),
    _Property("overlapping", "overlapping AVAR at τ = 2 is not C²/2 for n ≥ 3", _overlapping_not_constant),
    _Property("mcilroy-bounds", "|S| ≤ n/2 (attained), B(N) ≤ G(N) ≤ B(N) + 2N/5", _mcilroy_bounds),
)


def check_order(n: int) -> dict[str, bool]:
    """Run every property for one order n; a dict from property name to whether it held."""
    n = _check_order(n, _BYTES_PER_ROW)
    work = _Workspace(n)
    return {prop.name: bool(prop.check(work)) for prop in PROPERTIES}


@dataclass(frozen=True)
class PropertyResult:
    """Outcome of one property over n = 2 … up_to: the largest n such that it held for every order
    up to it (``MINIMUM_ORDER − 1`` if it failed at once), the first failing n, and the seconds spent."""

    name: str
    statement: str
    largest_verified: int
    first_failure: int | None
    seconds: float


def check_up_to(up_to: int, *, show_progress: bool = True) -> list[PropertyResult]:
    """Check every property for n = 2 … ``up_to`` (the paper's "at least R₂ … R₃₂₇₆₈" is up_to = 15)."""
    up_to = check_integer("up_to", up_to)
    if up_to < MINIMUM_ORDER:
        raise ValueError(f"up_to={up_to!r}: must be an integer >= {MINIMUM_ORDER} (Algorithm 1 takes 1 < n)")
    _check_order(up_to, _BYTES_PER_ROW)
    seconds = {prop.name: 0.0 for prop in PROPERTIES}
    first_failure: dict[str, int | None] = {prop.name: None for prop in PROPERTIES}
    orders = range(MINIMUM_ORDER, up_to + 1)
    for n in progress(orders, total=len(orders), label="graycode properties") if show_progress else orders:
        work = _Workspace(n)
        for prop in PROPERTIES:
            start = time.perf_counter()
            held = prop.check(work)
            seconds[prop.name] += time.perf_counter() - start
            if not held and first_failure[prop.name] is None:
                first_failure[prop.name] = n
        del work
    results = []
    for prop in PROPERTIES:
        failure = first_failure[prop.name]
        largest = up_to if failure is None else failure - 1
        results.append(PropertyResult(prop.name, prop.statement, largest, failure, seconds[prop.name]))
    return results
