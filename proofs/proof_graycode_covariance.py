"""Theorem (what holds of TIM 2014 §IV "the columns of K Kᵀ also follow the rule (21)" and
"all diagonal elements of K Kᵀ contain n/4"): for every n ≥ 2 and rows r, s = 0 … 2^n − 1,

    (K Kᵀ)[r, s] = n/4 − popcount(g(r) XOR g(s))/2 = −½ S_{2^n}[r XOR s],

so the diagonal is n/4 (Var R_t = C² n/4 for every t), and every column of K Kᵀ has bin means whose
consecutive differences are exactly ½ (not 1) in magnitude at every τ = 2^m, m = 0 … n − 1: the
columns of 2 K Kᵀ follow (21).

Assumptions: the Gray-code theorem (proofs/proof_graycode_gray_code.py): K[r, i] = β_i(r) − ½ with
β_i(r) = bit (n − i) of g(r), g(r) = r XOR ⌊r/2⌋, and S[r] = popcount(g(r)) − n/2; and eq. (21) for S
(proofs/proof_graycode_rule_21.py) in the form: bin means of S_{2^n} at 2^m are S_{2^{n−m}}.

Proof: direct, for all n at once; each step is a local (bitwise) identity checked on every case of
the bits involved, or a SymPy identity.
"""

import itertools

import numpy as np
import sympy as sp

from carousel_theory.graycode import deterministic_sequence, gray_matrix


def gray(r: int) -> int:
    return r ^ (r >> 1)


def step_1_product_of_two_entries():
    """(β − ½)(γ − ½) = ¼ − ½ (β XOR γ) for bits β, γ: all four cases."""
    for beta, gamma in itertools.product((0, 1), repeat=2):
        half = sp.Rational(1, 2)
        assert (beta - half) * (gamma - half) == half / 2 - half * (beta ^ gamma)


def step_2_sum_over_columns():
    """Σ_{i=1}^n (¼ − ½ δ_i) = n/4 − ½ popcount(δ), δ = g(r) XOR g(s)."""
    n, i = sp.symbols("n i", integer=True, positive=True)
    delta = sp.IndexedBase("delta")
    lhs = sp.Sum(sp.Rational(1, 4) - delta[i] / 2, (i, 1, n)).doit()
    rhs = n / 4 - sp.Sum(delta[i], (i, 1, n)).doit() / 2
    assert sp.simplify(lhs - rhs) == 0


def step_3_gray_code_is_linear():
    """g(r XOR s) = g(r) XOR g(s): bit k of g(x) is x_k XOR x_{k+1}; XOR is associative and commutative,
    checked on all 16 cases of (r_k, r_{k+1}, s_k, s_{k+1})."""
    for rk, rk1, sk, sk1 in itertools.product((0, 1), repeat=4):
        assert ((rk ^ sk) ^ (rk1 ^ sk1)) == ((rk ^ rk1) ^ (sk ^ sk1))


def step_4_in_terms_of_S():
    """n/4 − ½ popcount(g(t)) = −½ (popcount(g(t)) − n/2) = −½ S[t]; diagonal t = 0: n/4."""
    n, p = sp.symbols("n p", integer=True, nonnegative=True)
    assert sp.simplify((n / 4 - p / 2) - (-(p - n / 2) / 2)) == 0
    assert sp.simplify((n / 4 - p / 2).subs(p, 0) - n / 4) == 0  # g(0) = 0


def step_5_xor_maps_bins_to_bins():
    """Bin u of length 2^m is {u 2^m + w : 0 ≤ w < 2^m}; XOR with s maps it bijectively onto bin
    u XOR ⌊s/2^m⌋ (the low m bits are permuted by w ↦ w XOR (s mod 2^m), the high bits are XORed with
    ⌊s/2^m⌋). So the bin mean of column s at bin u is −½ S̄(2^m)[u XOR c], c = ⌊s/2^m⌋, where
    S̄_{2^n}(2^m) = S_{2^{n−m}} (the Gray-code and (21) theorems). XOR with a fixed value is its own
    inverse, bit by bit ((w_k XOR c_k) XOR c_k = w_k, all four cases), hence a bijection; it acts on the
    low m bits and the high bits separately because XOR has no carries."""
    for w_bit, c_bit in itertools.product((0, 1), repeat=2):
        assert (w_bit ^ c_bit) ^ c_bit == w_bit


def step_6_consecutive_bins_differ_in_one_gray_bit():
    """g(u XOR c) XOR g((u + 1) XOR c) = g(u) XOR g(u + 1) (linearity, step 3) = g(u XOR (u + 1)), and
    u XOR (u + 1) = 2^{k+1} − 1 with k = ν₂(u + 1), whose Gray code is 2^k: one bit. A single flipped bit
    changes popcount by exactly ±1 (the flipped bit is 0 → 1 or 1 → 0), so consecutive bin means of
    the column differ by ½ · 1 = ½."""
    for k in range(62):  # every k a 64-bit index can have
        assert gray(2 ** (k + 1) - 1) == 2**k
    for flipped in (0, 1):
        assert abs((1 - flipped) - flipped) == 1


def step_7_conclusion_checked_far():
    """The closed form and the ½-rule on every column, for n = 2 … 8 (dense, exact in float64)."""
    for n in range(2, 9):
        K = gray_matrix(n)
        covariance = K @ K.T
        S = deterministic_sequence(n)
        rows = np.arange(2**n)
        for s in range(2**n):
            assert np.array_equal(covariance[:, s], -S[rows ^ s] / 2)
            for m in range(n):
                means = covariance[:, s].reshape(-1, 2**m).mean(axis=1)
                assert (abs(np.diff(means)) == 0.5).all()
        assert (np.diag(covariance) == n / 4).all()
