"""Theorem (TIM 2014 §IV, "K_{16×4} + 0.5 is the standard Gray code matrix"; "S + n/2 depicts the
number of ones in the Gray code"), for every n ≥ 2:

    K_n[r, i] + ½ = bit (n − i) of g(r),   g(r) = r XOR ⌊r/2⌋ (binary reflected Gray code),
    S_{2^n}[r] + n/2 = popcount(g(r)),

rows r = 0 … 2^n − 1 (the paper's row r + 1), columns i = 1 … n (column 1 = most significant bit).

Assumptions: K_n is defined column-wise by TIM 2014 §IV, column i = a_{1…2^i} ⊗ 1_{2^{n−i}}, with a_k
of eq. (22); S_{2^n} = K_n 1 (eq. (32)).

Proof: induction on n through the doubling recursion of Algorithm 1,
K_n = [K_{n−1} ⊗ 1_2 | a_{1…2^n}]. Base case n = 2; step n − 1 → n for n ≥ 3.
"""

import itertools

import sympy as sp

from carousel_theory.graycode import gray_matrix, sequence_coefficients


def gray(r: int) -> int:
    return r ^ (r >> 1)


def bit(value: int, position: int) -> int:
    return (value >> position) & 1


def step_1_base_case_n_equals_2():
    """K_2 + ½ = [[0, 0], [0, 1], [1, 1], [1, 0]] = the 2-bit Gray codes 00, 01, 11, 10."""
    K = gray_matrix(2)
    for r in range(4):
        for i in (1, 2):
            assert K[r, i - 1] + 0.5 == bit(gray(r), 2 - i)


def step_2_doubling_recursion_of_K():
    """Column i < n of K_n is column i of K_{n−1} with every entry repeated twice:
    a_{1…2^i} ⊗ 1_{2^{n−i}} = (a_{1…2^i} ⊗ 1_{2^{n−1−i}}) ⊗ 1_2, because 1_{2^{n−i}} = 1_{2^{n−1−i}} ⊗ 1_2
    (lengths 2^{n−1−i} · 2 = 2^{n−i}). Hence K_n[2q + b, i] = K_{n−1}[q, i] for b ∈ {0, 1}."""
    n, i = sp.symbols("n i", integer=True, positive=True)
    assert sp.simplify(2 ** (n - 1 - i) * 2 - 2 ** (n - i)) == 0


def step_3_gray_code_recursion():
    """g(2q + b) = 2 g(q) + (b XOR q_0) for b ∈ {0, 1}: bit 0 of (2q + b) XOR q is b XOR q_0, and bit
    k ≥ 1 is q_{k−1} XOR q_k, which is bit k − 1 of g(q). Both are local identities in the bits,
    checked on every combination of the bits involved (complete for all q)."""
    for b, q0 in itertools.product((0, 1), repeat=2):
        assert (b ^ q0) == bit((2 * q0 + b) ^ q0, 0)
    for q_previous, q_current in itertools.product((0, 1), repeat=2):
        # bit k of (2q + b) is q_{k−1}; bit k of q is q_k; bit k − 1 of g(q) = q_{k−1} XOR q_k
        assert q_previous ^ q_current == bit(gray(q_previous + 2 * q_current), 0)


def step_4_last_column_is_the_least_significant_gray_bit():
    """K_n[r, n] = a_{r+1} and a_{r+1} + ½ = b XOR q_0 for r = 2q + b. Both sides depend on r mod 4 only
    (a has period four, eq. (22)), so the four residues are every case."""
    a = sequence_coefficients(4)
    for r in range(4):
        q, b = divmod(r, 2)
        assert a[r] + 0.5 == (b ^ (q & 1))


def step_5_inductive_step():
    """Assume K_{n−1}[q, i] + ½ = bit (n − 1 − i) of g(q) for all q, i (hypothesis). For r = 2q + b:
    i < n: K_n[r, i] + ½ = K_{n−1}[q, i] + ½ (step 2) = bit (n − 1 − i) of g(q) = bit (n − i) of
    2 g(q) + c (shift, any c ∈ {0, 1}) = bit (n − i) of g(r) (step 3); i = n: step 4 and step 3.
    The shift identity ⌊(2x + c)/2^{k+1}⌋ = ⌊x/2^k⌋ holds for integers x ≥ 0, c ∈ {0, 1}:"""
    x, k = sp.symbols("x k", integer=True, nonnegative=True)
    for c in (0, 1):
        # (2x + c)/2^{k+1} = x/2^k + c/2^{k+1} with 0 ≤ c/2^{k+1} < 1/2^k ≤ (the gap to the next integer)
        assert sp.simplify((2 * x + c) / 2 ** (k + 1) - (x / 2**k + sp.Rational(c, 2) / 2**k)) == 0
    # the fractional part of x/2^k is a multiple of 1/2^k, at most 1 − 1/2^k; adding the largest
    # c/2^{k+1} gives 1 − 1/2^{k+1} < 1, so the floor does not change:
    assert sp.simplify((1 - 1 / 2**k) + sp.Rational(1, 2) / 2**k - 1 + sp.Rational(1, 2) / 2**k) == 0


def step_6_ones_count():
    """S_{2^n}[r] = Σ_i K_n[r, i] = Σ_i (β_i − ½) = popcount(g(r)) − n/2, β_i the bits of g(r)."""
    n, i = sp.symbols("n i", integer=True, positive=True)
    beta = sp.IndexedBase("beta")
    lhs = sp.Sum(beta[i] - sp.Rational(1, 2), (i, 1, n)).doit()
    rhs = sp.Sum(beta[i], (i, 1, n)).doit() - n / 2
    assert sp.simplify(lhs - rhs) == 0


def step_7_the_paper_16x4_instance():
    """n = 4 instance of the theorem, exhaustively (the case the paper states)."""
    K = gray_matrix(4)
    assert all(K[r, i - 1] + 0.5 == bit(gray(r), 4 - i) for r in range(16) for i in range(1, 5))
    assert all(K[r].sum() + 2 == gray(r).bit_count() for r in range(16))
