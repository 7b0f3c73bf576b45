"""Theorem (corrected TIM 2014 eq. (23)): for every n ≥ 2, m = 0 … n − 1 and j = 1 … 2^{n−m} − 1,

    D_{n,m}[j, i] := K̄_n(2^m)_{j+1, i} − K̄_n(2^m)_{j, i} = ±1 if i = n − m − ν₂(j), and 0 otherwise,

where K̄_n(τ)_{j, i} is the mean of column i of K_n over bin j (bins of τ = 2^m samples, numbered from
1) and ν₂(j) is the exponent of 2 in j. Hence R̄(2^m)_{j+1} − R̄(2^m)_j = ±C x_{n−m−ν₂(j)} for R = C K x:
one innovation per difference, not one x_τ per τ as (23) prints.

Assumptions: K_n column i = a_{1…2^i} ⊗ 1_{2^{n−i}}, a_k of eq. (22) (period four: −½, ½, ½, −½).

Proof: induction on n through K_n = [K_{n−1} ⊗ 1_2 | a_{1…2^n}] (Algorithm 1). Base case n = 2
(all m, j, exhaustive). Step n − 1 → n (n ≥ 3), separately for m ≥ 1 and m = 0.
"""

import numpy as np
import sympy as sp

from carousel_theory.graycode import gray_matrix, sequence_coefficients


def two_adic_valuation(j: int) -> int:
    return (j & -j).bit_length() - 1


def differences(n: int, m: int):
    K = gray_matrix(n)
    means = K.reshape(2 ** (n - m), 2**m, n).mean(axis=1)
    return means[1:] - means[:-1]


def step_1_base_case_n_equals_2():
    for m in range(2):
        D = differences(2, m)
        for j in range(1, 2 ** (2 - m)):
            for i in (1, 2):
                expected = 1 if i == 2 - m - two_adic_valuation(j) else 0
                assert abs(D[j - 1, i - 1]) == expected


def step_2_new_column_averages_to_zero_over_pairs():
    """a_{2k−1} + a_{2k} = 0 for every k: depends on k mod 2 only (period four), both cases checked.
    So for m ≥ 1 (bins of even length 2^m, aligned at even positions) the new column n has bin mean
    0, and D_{n,m}[j, n] = 0 = [n = n − m − ν₂(j)] since m ≥ 1."""
    a = sequence_coefficients(4)
    assert a[0] + a[1] == 0 and a[2] + a[3] == 0


def step_3_old_columns_coarsen_by_one_octave():
    """For i < n, column i of K_n is column i of K_{n−1} repeated twice, so its mean over bin j of
    length 2^m (m ≥ 1) is the mean of column i of K_{n−1} over bin j of length 2^{m−1}:
    (1/2^m) Σ_{u ∈ bin} 2 v_u = (1/2^{m−1}) Σ_{u ∈ bin} v_u. Hence D_{n,m}[j, i] = D_{n−1,m−1}[j, i], and
    by the hypothesis it is ±1 iff i = (n − 1) − (m − 1) − ν₂(j) = n − m − ν₂(j)."""
    m, n, nu = sp.symbols("m n nu", integer=True, positive=True)
    assert sp.simplify(2 / 2**m - 1 / 2 ** (m - 1)) == 0
    assert sp.simplify(((n - 1) - (m - 1) - nu) - (n - m - nu)) == 0


def step_4_tau_one_old_columns():
    """m = 0, i < n: K_n[r, i] = K_{n−1}[⌊r/2⌋, i]. Rows j − 1 and j (0-based) share ⌊·/2⌋ when j is odd,
    so D_{n,0}[j, i] = 0 (and ν₂(j) = 0 gives n − ν₂(j) = n ≠ i). For even j = 2j′, the rows map to
    j′ − 1 and j′, so D_{n,0}[j, i] = D_{n−1,0}[j′, i], ±1 iff i = n − 1 − ν₂(j′) = n − ν₂(j) because
    ν₂(2j′) = ν₂(j′) + 1."""
    n, nu, u = sp.symbols("n nu u", integer=True, positive=True)
    # j′ = 2^ν u with u odd gives 2j′ = 2^{ν+1} u with the same odd u: ν₂(2j′) = ν₂(j′) + 1
    assert sp.simplify(2 * (2**nu * u) - 2 ** (nu + 1) * u) == 0
    assert sp.simplify((n - 1 - nu) - (n - (nu + 1))) == 0
    q = sp.Symbol("q", integer=True, nonnegative=True)
    # odd j = 2q + 1: rows 2q and 2q + 1 have ⌊·/2⌋ = q; even j = 2j′: rows 2j′ − 1, 2j′ give j′ − 1, j′
    assert sp.floor((2 * q) / 2) == q and sp.floor((2 * q + 1) / 2) == q
    assert sp.floor((2 * u - 1) / 2) == u - 1 and sp.floor((2 * u) / 2) == u


def step_5_tau_one_new_column():
    """m = 0, i = n: D_{n,0}[j, n] = a_{j+1} − a_j (1-based a). It depends on j mod 4 only; it is ±1
    exactly for odd j, i.e. exactly when n − 0 − ν₂(j) = n."""
    a = sequence_coefficients(8)
    for j in range(1, 5):
        change = a[j] - a[j - 1]
        assert abs(change) == (1 if j % 2 == 1 else 0)


def step_6_conclusion_checked_far():
    """The theorem itself for n = 3 … 10, all m, j, i (a check of the induction's conclusion)."""
    for n in range(3, 11):
        for m in range(n):
            D = differences(n, m)
            nu = np.array([two_adic_valuation(j) for j in range(1, 2 ** (n - m))])
            for i in range(1, n + 1):
                assert (abs(D[:, i - 1]) == (i == n - m - nu)).all()
