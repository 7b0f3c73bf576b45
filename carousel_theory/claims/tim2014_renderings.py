"""Where the two text renderings of TIM 2014 disagree, and which one is mathematically right.

The project holds two renderings of the same paper: ``carouseling-tim2014.md`` (called *primary*
below) and ``carouseling-tim2014-alt-rendering.md`` (*alternative*). A word-by-word comparison of
the two finds the disagreements listed here; every other token (each number, equation and table
value) is the same in both. Each claim quotes the two readings and its check evaluates both,
exactly or at 50 digits, against the rest of the paper, which both renderings print identically.
These claims are about the text, not a section; the mathematics of each section is in its own module.
"""

from __future__ import annotations

import re
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np
import sympy as sp

from carousel_theory.claim import Claim, Status, Verdict
from carousel_theory.claims._common import DIGITS, cumulative_sum_matrix, simplifies_to_zero

__all__ = ["CLAIMS"]

PAPER = "TIM2014"


TOLERANCE = mpmath.mpf(10) ** (-(DIGITS - 5))


#: Exhaustive ranges of the exact checks: every N (samples per bin) in 1..EXACT_N_MAX and, at 50
#: digits, every N in 1..DECIMAL_N_MAX.
EXACT_N_MAX = 12


DECIMAL_N_MAX = 40


def _averaging_vector(N: int) -> sp.Matrix:
    """The integrator vector 1 = (1/N)[1 … 1]ᵀ of eq. (12)."""
    return sp.Matrix([sp.Rational(1, N)] * N)


def _carousel_vectors_mp(N: int) -> tuple[list, list]:
    """s and c of eq. (13) at the current mpmath precision."""
    s = [mpmath.sin(2 * mpmath.pi * i / N) / N for i in range(1, N + 1)]
    c = [mpmath.cos(2 * mpmath.pi * i / N) / N for i in range(1, N + 1)]
    return s, c


def _quadratic_form_mp(left: list, matrix: np.ndarray, right: list) -> mpmath.mpf:
    """leftᵀ · matrix · right for an integer matrix, at the current mpmath precision."""
    return mpmath.fsum(
        left[row] * int(matrix[row, column]) * right[column]
        for row in range(len(left))
        for column in range(len(right))
        if matrix[row, column] != 0
    )


def _check_ones_block() -> Verdict:
    # The printed right-hand side of (15), identical in both renderings.
    N = sp.Symbol("N", positive=True, integer=True)
    printed_cross = (N + 1) / 2
    printed_second = (2 * N**3 + 3 * N**2 + N) / (6 * N**2) + N
    counterexample = None
    for size in range(1, EXACT_N_MAX + 1):
        R = cumulative_sum_matrix(size)
        R2 = cumulative_sum_matrix(2 * size)
        ones = sp.ones(size, size)
        identity = sp.eye(size)
        # The partition (11) of the 2N × 2N cumulative-sum matrix: its lower-left block is all ones.
        if R2[size:, :size] != ones or R2[:size, size:] != sp.zeros(size, size) or R2[size:, size:] != R:
            return Verdict(Status.FAILED, f"the partition (11) of R₂ does not hold at N = {size}")
        one = _averaging_vector(size)
        with_ones = (
            (one.T * R * ones.T * one)[0],
            (one.T * R * R.T * one + one.T * ones * ones.T * one)[0],
        )
        with_identity = (
            (one.T * R * identity.T * one)[0],
            (one.T * R * R.T * one + one.T * identity * identity.T * one)[0],
        )
        printed = (printed_cross.subs(N, size), printed_second.subs(N, size))
        if with_ones != printed:
            return Verdict(
                Status.FAILED, f"(15) with the ones matrix disagrees with its printed value at N = {size}"
            )
        if counterexample is None and with_identity != printed:
            counterexample = (size, with_identity[0], printed[0])
    if counterexample is None:
        return Verdict(
            Status.FAILED, f"reading the block as the identity also gives (15) for N ≤ {EXACT_N_MAX}"
        )
    size, got, printed_value = counterexample
    return Verdict(
        Status.ERRATUM,
        f"The lower-left block of the 2N×2N cumulative-sum matrix is the ones matrix, and with it (15) holds "
        f"exactly for every N ≤ {EXACT_N_MAX}; read as the identity I of σ_q²I (alternative rendering), "
        f"1ᵀR Iᵀ1 = {got} ≠ (N+1)/2 = {printed_value} already at N = {size}. The primary rendering (𝕀 ≠ I) "
        "is right.",
        corrected="R₂ = [[R, 𝕆], [𝕀, R]] with 𝕆, 𝕀 the N×N matrices of zeros and ones, distinct from the "
        "identity I in cov q = σ_q² I (as in the primary rendering)",
    )


def _check_eq17_off_diagonal() -> Verdict:
    with mpmath.workdps(DIGITS):
        # From N = 3: for N ≤ 2 the vector s vanishes and Σc = 0 fails at N = 1 (the roots of unity
        # cancel only for N > 1, TIM 2014 §III-A).
        for size in range(3, DECIMAL_N_MAX + 1):
            R = np.tril(np.ones((size, size), dtype=np.int64))  # eq. (10)
            ones = np.ones((size, size), dtype=np.int64)
            identity = np.eye(size, dtype=np.int64)
            s, c = _carousel_vectors_mp(size)
            for vector, name in ((s, "s"), (c, "c")):
                with_ones = _quadratic_form_mp(vector, R @ ones.T, vector)
                if abs(with_ones) > TOLERANCE:
                    return Verdict(
                        Status.FAILED, f"{name}ᵀR𝕀ᵀ{name} = {mpmath.nstr(with_ones, 5)} ≠ 0 at N = {size}"
                    )
                with_identity = _quadratic_form_mp(vector, R @ identity.T, vector)
                # sᵀR s = ((Σs)² + Σs²)/2 = 1/(4N) for N ≥ 3 (Σs = 0, Σs² = 1/(2N)).
                expected = mpmath.mpf(1) / (4 * size)
                if abs(with_identity - expected) > TOLERANCE:
                    return Verdict(
                        Status.FAILED,
                        f"{name}ᵀR{name} = {mpmath.nstr(with_identity, 8)} ≠ 1/(4N) at N = {size}",
                    )
    return Verdict(
        Status.ERRATUM,
        f"At 50 digits for every N = 3 … {DECIMAL_N_MAX}: sᵀR𝕀ᵀs = cᵀR𝕀ᵀc = 0 (𝕀 = ones, because 𝕀ᵀs = 𝟙·Σs "
        "= 0), "
        "whereas with the identity sᵀR s = cᵀR c = 1/(4N) ≠ 0 for N ≥ 3 (e.g. 1/800 at N = 200). The "
        "upper-right 'I' of (17), printed in both renderings, must be the ones matrix 𝕀, as the primary "
        "rendering writes in the other three places.",
        corrected="σ_q² [[sᵀRRᵀs, sᵀR𝕀ᵀs], [sᵀ𝕀Rᵀs, sᵀRRᵀs + sᵀ𝕀𝕀ᵀs]] = σ_q² [[sᵀRRᵀs, 0], [0, sᵀRRᵀs]], 𝕀 "
        "= ones",
    )


def _check_eq17_scalar_zero() -> Verdict:
    # Exact at N = 4: s = (1/4)[1, 0, −1, 0]; the off-diagonal entry is a 1×1 quantity (a scalar).
    size = 4
    s = sp.Matrix([sp.sin(2 * sp.pi * i / size) / size for i in range(1, size + 1)])
    entry = s.T * cumulative_sum_matrix(size) * sp.ones(size, size).T * s
    if entry.shape != (1, 1) or not simplifies_to_zero(entry[0]):
        return Verdict(Status.FAILED, f"sᵀR𝕀ᵀs at N = 4 is {entry}, not the scalar 0")
    return Verdict(
        Status.TYPOGRAPHIC,
        "Each entry of the 2×2 matrix (17) is a 1×1 quadratic form (exactly sᵀR𝕀ᵀs = 0 at N = 4), so the "
        "zeros "
        "are the scalar 0 (alternative rendering), not the bold 0 that the text after (14) defines as an N×1 "
        "vector (primary rendering).",
        corrected="σ_q² [[sᵀRRᵀs, 0], [0, sᵀRRᵀs]] with scalar zeros",
    )


def _halves(values) -> list[Fraction]:
    """Exact values of a float array of half-integers (Algorithm 1 produces only these)."""
    result = [Fraction(float(v)).limit_denominator(2) for v in np.asarray(values).ravel()]
    if any(float(r) != float(v) for r, v in zip(result, np.asarray(values).ravel(), strict=True)):
        raise ValueError("values are not half-integers")
    return result


H = Fraction(1, 2)


#: Table I as printed in the alternative rendering: S₂, S₂⊗[1 1], a_{1…4}, S₄, S₄⊗[1 1], a_{1…8}, S₈.
TABLE_I_ALTERNATIVE: dict[str, list[Any]] = {
    "S_2": [-H, H],
    "S_2 ⊗ [1 1]": [-H, -H, H, H],
    "a_1…4": [-H, H, H, -H],
    "S_4": [-1, 0, 1, 0],
    "S_4 ⊗ [1 1]": [-1, -1, 0, 0, 1, 1, 0, 0],
    "a_1…8": [-H, H, H, -H, -H, H, H, -H],
    "S_8": [-3 * H, -H, H, -H, H, 3 * H, H, -H],
}


#: The entries the primary rendering's garbled Table I still shows unambiguously: its S₈ row and,
#: read as stacked pairs (upper over lower) in the merged rows, these columns.
TABLE_I_PRIMARY_READABLE: dict[str, list[Any]] = {
    "S_8": [-3 * H, -H, H, -H, H, 3 * H, H, -H],
    "S_4": [None, 0, 1, 0],  # "_ ·1 0 1 0": the sign of −1 is lost
    "S_4 ⊗ [1 1] over a_1…8": [(-1, -H), (-1, H), (0, H), (0, -H), (1, -H), (None, H), (0, H), (0, -H)],
}


def _check_table_one() -> Verdict:
    from carousel_theory.graycode import deterministic_sequence, gray_matrix

    K = gray_matrix(3)  # columns: a_{1…2}⊗1₄, a_{1…4}⊗1₂, a_{1…8}
    computed = {
        "S_2": _halves(K[::4, 0]),
        "S_2 ⊗ [1 1]": _halves(K[::2, 0]),
        "a_1…4": _halves(K[::2, 1]),
        "S_4": _halves(deterministic_sequence(2)),
        "S_4 ⊗ [1 1]": _halves(np.repeat(deterministic_sequence(2), 2)),
        "a_1…8": _halves(K[:, 2]),
        "S_8": _halves(deterministic_sequence(3)),
    }
    if computed["S_8"] != _halves(K.sum(axis=1)):
        return Verdict(Status.FAILED, "S_8 from Algorithm 1 differs from K·1 (eq. (32))")
    wrong = [
        row for row, values in TABLE_I_ALTERNATIVE.items() if [Fraction(v) for v in values] != computed[row]
    ]
    if wrong:
        return Verdict(
            Status.FAILED, f"the alternative rendering's Table I differs from Algorithm 1 in rows {wrong}"
        )
    stacked = list(zip(computed["S_4 ⊗ [1 1]"], computed["a_1…8"], strict=True))
    primary_ok = (
        TABLE_I_PRIMARY_READABLE["S_8"] == computed["S_8"]
        and all(
            p is None or p == q for p, q in zip(TABLE_I_PRIMARY_READABLE["S_4"], computed["S_4"], strict=True)
        )
        and all(
            (u is None or u == cu) and lo == cl
            for (u, lo), (cu, cl) in zip(
                TABLE_I_PRIMARY_READABLE["S_4 ⊗ [1 1] over a_1…8"], stacked, strict=True
            )
        )
    )
    if not primary_ok:
        return Verdict(
            Status.FAILED, "the readable entries of the primary rendering's Table I contradict Algorithm 1"
        )
    return Verdict(
        Status.TYPOGRAPHIC,
        "All seven rows of the alternative rendering's Table I equal Algorithm 1's trace (S_8 = [−3/2, "
        "−1/2, 1/2, "
        "−1/2, 1/2, 3/2, 1/2, −1/2] = K·1). The primary rendering's table merges the ⊗[1 1] and a rows into "
        "stacked fractions, writes a_{14} for a_{1…4} and loses two entries (the −1 of S_4, a 1 of S_4⊗[1 "
        "1]); "
        "its readable entries agree.",
        corrected="Table I as in the alternative rendering",
    )


def _check_table_two() -> Verdict:
    from carousel_theory.graycode import gray_matrix

    x1, x2 = sp.symbols("x_1 x_2")
    K = sp.Matrix([[sp.Rational(str(v)) for v in row] for row in gray_matrix(2)])
    half = sp.Rational(1, 2)
    R4 = K * sp.Matrix([x1, x2])
    rows_alternative = {
        "R_2 ⊗ [1 1]": [-half * x1, -half * x1, half * x1, half * x1],
        "a_1…4 x_2": [-half * x2, half * x2, half * x2, -half * x2],
        "R_4": [-half * x1 - half * x2, -half * x1 + half * x2, half * x1 + half * x2, half * x1 - half * x2],
    }
    computed = {
        "R_2 ⊗ [1 1]": list(K[:, 0] * x1),
        "a_1…4 x_2": list(K[:, 1] * x2),
        "R_4": list(R4),
    }
    for row, values in rows_alternative.items():
        if any(sp.expand(a - b) != 0 for a, b in zip(values, computed[row], strict=True)):
            return Verdict(Status.FAILED, f"the alternative rendering's Table II row {row} differs from K x")
    # The primary rendering prints the 3rd and 4th entries of the middle rows as the fractions
    # (x₁/2)/(x₂/2) and −(x₁/2)/(−x₂/2): read literally both equal ±x₁/x₂, not entries of K x.
    literal_third, literal_fourth = (half * x1) / (half * x2), -(half * x1) / (-half * x2)
    if any(simplifies_to_zero(v - literal_third) or simplifies_to_zero(v - literal_fourth) for v in R4):
        return Verdict(Status.FAILED, "the primary rendering's literal fractions match an entry of K x")
    return Verdict(
        Status.TYPOGRAPHIC,
        "The alternative rendering's Table II equals K x exactly (K of eq. (24) from Algorithm 1): R_4 = "
        "[−x₁/2 − x₂/2, −x₁/2 + x₂/2, x₁/2 + x₂/2, x₁/2 − x₂/2]. The primary rendering prints the middle "
        "rows "
        "as nested fractions (read literally (x₁/2)/(x₂/2) = x₁/x₂, which is no entry of K x) and splits −½ "
        "from x₁ in the R_2 row.",
        corrected="Table II as in the alternative rendering",
    )


def _check_algorithm_loop() -> Verdict:
    from carousel_theory.graycode import deterministic_sequence

    # "for i = 2, …, n" doubles the length of S_2 n − 1 times: length 2^n (Algorithm 1's output S_{2^n}).
    lengths = {n: len(deterministic_sequence(n)) for n in range(2, 13)}
    if any(length != 2**n for n, length in lengths.items()):
        return Verdict(Status.FAILED, f"Algorithm 1 lengths {lengths} are not 2^n")
    return Verdict(
        Status.TYPOGRAPHIC,
        "Looping i = 2, …, n (n − 1 doublings of S_2) gives the stated output length 2^n for every n = 2 … "
        "12; "
        "the primary rendering's 'i = 2,, n' has lost the ellipsis, the alternative is right.",
        corrected="for i = 2, …, n do",
    )


def _check_difference_matrix_symbol() -> Verdict:
    from carousel_theory.graycode import gray_matrix

    # (28) at τ = 1 on a sequence of length 4: rows [… −1/τ … 1/τ …] for j = 1, 2, 3.
    tau = 1
    rows = []
    for j in range(1, 4):
        row = [sp.Integer(0)] * 4
        for t in range((j - 1) * tau, j * tau):
            row[t] = sp.Rational(-1, tau)
        for t in range(j * tau, (j + 1) * tau):
            row[t] = sp.Rational(1, tau)
        rows.append(row)
    from_28 = sp.Matrix(rows)
    printed_29 = sp.Matrix([[-1, 1, 0, 0], [0, -1, 1, 0], [0, 0, -1, 1]])
    printed_30 = sp.Matrix([[1, 0, -1], [0, 1, 0], [-1, 0, 1]])
    K = sp.Matrix([[sp.Rational(str(v)) for v in row] for row in gray_matrix(2)])
    if from_28 != printed_29 or printed_29 * K * K.T * printed_29.T != printed_30:
        return Verdict(Status.FAILED, "(28) at τ = 1 does not give (29), or A K Kᵀ Aᵀ differs from (30)")
    return Verdict(
        Status.TYPOGRAPHIC,
        "(28) at τ = 1 on R_4 gives exactly the matrix A of (29), and A K Kᵀ Aᵀ = "
        "[[1,0,−1],[0,1,0],[−1,0,1]] = "
        "(30); the paper defines only A, so the primary rendering's 'A y' is right and the alternative's 'Ā "
        "y' "
        "names a symbol that is never defined.",
        corrected="express the bin average differences in (20) in the matrix–vector product form A y; cov A "
        "y = "
        "cov A K x = A K Kᵀ Aᵀ",
    )


def _check_unbiased_factor() -> Verdict:
    from carousel_theory.graycode import allan_variance_exact, gray_matrix

    results = []
    for n in range(2, 7):
        K = sp.Matrix([[sp.Rational(str(v)) for v in row] for row in gray_matrix(n)])
        covariance = K * K.T  # cov R for unit-variance x (C = 1)
        for m in range(n):
            tau = 2**m
            bins = 2**n // tau
            # E[σ_A²(τ)] of (20), and the same with bin sums instead of bin means ("without 1/τ").
            total_means = sp.Integer(0)
            for j in range(bins - 1):
                difference = sp.zeros(1, 2**n)
                for t in range(j * tau, (j + 1) * tau):
                    difference[t] = sp.Rational(-1, tau)
                for t in range((j + 1) * tau, (j + 2) * tau):
                    difference[t] = sp.Rational(1, tau)
                total_means += (difference * covariance * difference.T)[0]
            expected_allan = total_means / (2 * (bins - 1))
            without_half = 2 * expected_allan
            # Bin sums instead of bin means (the 1/τ of ȳ removed, the 1/2 kept): τ² E[σ_A²].
            without_tau = tau**2 * expected_allan
            results.append((n, m, expected_allan, without_half, without_tau))
    if any(e != sp.Rational(1, 2) or e != allan_variance_exact(n, m, 1) for n, m, e, _, _ in results):
        return Verdict(Status.FAILED, "E[σ_A²(2^m)] of R_{2^n} is not 1/2 for some n ≤ 6")
    if any(w != 1 for _, _, _, w, _ in results):
        return Verdict(Status.FAILED, "dropping the factor 1/2 does not give C² = 1")
    if any(t == 1 for _, _, _, _, t in results):
        return Verdict(Status.FAILED, "dropping the 1/τ of the bin means gives C² for some τ")
    at = {2**m: t for n, m, _, _, t in results if n == 2}
    return Verdict(
        Status.ERRATUM,
        "Exactly, for every n = 2 … 6 and τ = 2^m: E[σ_A²(τ)] = C²/2, so (20) without its factor 1/2 is "
        "unbiased for C² (primary rendering). (20) contains no 1/τ; with bin sums instead of bin means "
        f"(alternative rendering's reading) it has expectation τ²C²/2 ({at[1]} at τ = 1, {at[2]} at τ = 2), "
        "never C².",
        corrected="(20) without the term 1/2 yields an unbiased estimate of C², i.e. E[2σ_A²(τ)] = C²",
    )


#: Table III's value cells as each rendering prints them (LaTeX source), in the order
#: x-gyro (σ_WN², σ_q², bias instability), y-gyro (the same).
TABLE_III_PRIMARY = (
    r"$3 \cdot 10^{-7} \\ 3 \cdot 10^{-10} \\ 1 \cdot 10^{-5}$",
    r"$1 \cdot 10^{-7} \\ 2 \cdot 10^{-10} \\ 6 \cdot 10^{-5}$",
)


TABLE_III_ALTERNATIVE = (
    r"$3 \cdot 10^{-7}$ $3 \cdot 10^{-10}$ $1 \cdot 10^{-5}$",
    r"$1 \cdot 10^{-7}$ $2 \cdot 10^{-10}$ $6 \cdot 10^{-5}$",
)


TABLE_III_UNITS_PRIMARY = r"$(rad/s)^2$ $(rad/s)^2/s$ rad/s"


TABLE_III_UNITS_ALTERNATIVE = "(rad/s) <sup>2</sup> | (rad/s) <sup>2</sup> /s | rad/s"


def _parse_scientific(cell: str) -> list[Fraction]:
    return [
        Fraction(int(mantissa)) * Fraction(10) ** int(exponent)
        for mantissa, exponent in re.findall(r"(\d+)\s*\\cdot\s*10\^\{(-?\d+)\}", cell)
    ]


def _normalised_units(text: str) -> list[str]:
    text = re.sub(r"\s*<sup>\s*(\d)\s*</sup>\s*", r"^\1", text).replace("$", "").replace("|", " ")
    return [
        re.sub(r"\s+", "", unit) for unit in re.split(r"\s{1,}(?=\(|rad/s$)", text.strip()) if unit.strip()
    ]


def _check_table_three() -> Verdict:
    primary = [_parse_scientific(cell) for cell in TABLE_III_PRIMARY]
    alternative = [_parse_scientific(cell) for cell in TABLE_III_ALTERNATIVE]
    units = (_normalised_units(TABLE_III_UNITS_PRIMARY), _normalised_units(TABLE_III_UNITS_ALTERNATIVE))
    if primary != alternative or any(len(column) != 3 for column in primary):
        return Verdict(Status.REFUTED, f"the renderings' Table III values differ: {primary} vs {alternative}")
    if units[0] != units[1]:
        return Verdict(Status.REFUTED, f"the renderings' Table III units differ: {units[0]} vs {units[1]}")
    values = "; ".join(
        f"{gyro}: " + ", ".join(f"{float(v):.0e}" for v in column)
        for gyro, column in zip(("x", "y"), primary, strict=True)
    )
    return Verdict(
        Status.VERIFIED,
        f"Both renderings give the same six values ({values}) and units ({', '.join(units[0])}); they differ "
        "only in layout (the primary's header reads 'Va Value').",
    )


WORDING_DIFFERENCES = (
    ("§I", "'have been studies' / 'highquality'", "'have been studied' / 'high-quality'", "alternative"),
    ("§II-A", "'zeromean'", "'zero-mean'", "alternative"),
    ("§III, §V", "'carouseled'", "'carouselled'", "both (spelling variants)"),
    ("§III-C before (16)", "'would be computed'", "'would be computed as'", "alternative"),
    ("§V-B", "'1/fnoise', 'the carouseled 1/f noise'", "'1/f noise', 'the carouseling 1/f noise'", "mixed"),
    ("§V-D", "'the carouseled heading estimates'", "'the carouseling heading estimates'", "primary"),
    ("Fig. 8(b)", "'carouseled estimate'", "'carousel estimate'", "primary"),
    (
        "Figs. 9–10",
        "no caption for Fig. 10",
        "'Fig. 10. Test route' (and a stray 'Test vehicle.eps')",
        "alternative",
    ),
    ("ref. [5]", "'Noureldin'", "'Nouredin'", "primary (A. Noureldin)"),
    ("ref. [21]", "'selfsimilar'", "'self-similar'", "alternative"),
    ("biography", "'Kirkkonumni'", "'Kirkkonummi'", "alternative (the town is Kirkkonummi)"),
)


def _check_wording() -> Verdict:
    listed = "; ".join(f"{where}: {a} vs {b} ({right})" for where, a, b, right in WORDING_DIFFERENCES)
    return Verdict(
        Status.NOT_CHECKABLE,
        f"No mathematical content, so nothing to compute; for completeness ({len(WORDING_DIFFERENCES)} "
        "places, "
        f"primary vs alternative, which is right): {listed}.",
    )


CLAIMS: list[Claim] = [
    Claim(
        "TIM2014-render-eq11-ones-block",
        PAPER,
        "§III-C, eq. (11) and (15); renderings differ",
        "Primary: R₂ = [[R, 𝕆], [𝕀, R]] with 𝕆, 𝕀 the N×N zeros and ones, distinct from the identity I of "
        "σ_q² I. Alternative: [[R, 0], [I, R]] with bold I for the ones matrix and again for the identity.",
        _check_ones_block,
    ),
    Claim(
        "TIM2014-render-eq17-ones-in-off-diagonal",
        PAPER,
        "§III-C, eq. (17); both renderings",
        "Both renderings print the upper-right entry of (17) as sᵀR Iᵀ s (primary: 𝕀 in the other three "
        "places; alternative: I everywhere) and set it to 0.",
        _check_eq17_off_diagonal,
    ),
    Claim(
        "TIM2014-render-eq17-scalar-zero",
        PAPER,
        "§III-C, eq. (17), second line; renderings differ",
        "Primary: off-diagonal entries written as bold 0 (the N×1 zero vector of (14)); alternative: scalar "
        "0.",
        _check_eq17_scalar_zero,
    ),
    Claim(
        "TIM2014-render-table1",
        PAPER,
        "§IV, Table I; renderings differ",
        "Table I (generating S_8): the alternative rendering prints seven clean rows; the primary rendering "
        "merges rows into stacked fractions and writes a_{14}.",
        _check_table_one,
    ),
    Claim(
        "TIM2014-render-table2",
        PAPER,
        "§IV, Table II; renderings differ",
        "Table II (generating R_4): the alternative rendering prints separate rows R_2, ⊗[1 1], a x_2, R_4; "
        "the primary prints nested fractions such as (x₁/2)/(x₂/2).",
        _check_table_two,
    ),
    Claim(
        "TIM2014-render-algorithm1-loop",
        PAPER,
        "§IV, Algorithm 1, line 2; renderings differ",
        "Primary: 'for i = 2,, n do'; alternative: 'for i = 2, …, n do'.",
        _check_algorithm_loop,
    ),
    Claim(
        "TIM2014-render-eq28-difference-matrix",
        PAPER,
        "§IV, text before (28) and eq. (30); renderings differ",
        "Primary: the bin differences are written 'A y' and (30) reads cov A y; alternative: 'Ā y' and cov "
        "Ā y.",
        _check_difference_matrix_symbol,
    ),
    Claim(
        "TIM2014-render-unbiased-factor",
        PAPER,
        "§IV, after eq. (30); renderings differ",
        "Primary: '(20) without the term 1/2 yields an unbiased estimate of C²'; alternative: 'without the "
        "term 1/τ'.",
        _check_unbiased_factor,
    ),
    Claim(
        "TIM2014-render-table3",
        PAPER,
        "§V-C, Table III; layout differs",
        "Table III: the primary rendering's header is garbled ('Va Value') and its cells are stacked arrays; "
        "the alternative prints one row per parameter.",
        _check_table_three,
    ),
    Claim(
        "TIM2014-render-wording",
        PAPER,
        "whole paper; renderings differ",
        "Spelling and wording differences between the renderings that carry no mathematics.",
        _check_wording,
    ),
]
