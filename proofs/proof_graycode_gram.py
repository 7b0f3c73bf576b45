"""Theorem (closed form of TIM 2014 eq. (31) for every n): for every n ≥ 2,

    Kᵀ K = 2^{n−2} I_n,   hence   K⁺ = (KᵀK)⁻¹ Kᵀ = 2^{2−n} Kᵀ   and   K⁺ K = I_n,

so K⁺ R = C x for R = C K x (the step before the MVUE in §IV), and rank K = n = log₂(2^n).

Assumptions: K_n column i = a_{1…2^i} ⊗ 1_{2^{n−i}}, a_k of eq. (22).

Proof: induction on n through K_n = [K_{n−1} ⊗ 1_2 | a_{1…2^n}]. Base case n = 2; step n − 1 → n.
"""

import sympy as sp

from carousel_theory.graycode import GRAM_SCALE, gray_matrix, n_symbol, sequence_coefficients

n = n_symbol


def step_1_base_case_n_equals_2():
    K = sp.Matrix(gray_matrix(2).tolist()).applyfunc(sp.nsimplify)
    assert GRAM_SCALE.subs(n, 2) * sp.eye(2) == K.T * K


def step_2_repeated_block():
    """(K_{n−1} ⊗ 1_2)ᵀ (K_{n−1} ⊗ 1_2) = 2 K_{n−1}ᵀ K_{n−1} = 2 · 2^{n−3} I = 2^{n−2} I."""
    assert sp.simplify(2 * GRAM_SCALE.subs(n, n - 1) - GRAM_SCALE) == 0


def step_3_new_column_is_orthogonal():
    """(K_{n−1} ⊗ 1_2)ᵀ a = Σ_q K_{n−1}[q, :] (a_{2q+1} + a_{2q+2}) = 0: every aligned pair of a cancels
    (depends on q mod 2 only; both cases)."""
    a = sequence_coefficients(4)
    assert a[0] + a[1] == 0 and a[2] + a[3] == 0


def step_4_new_column_norm():
    """aᵀa = 2^n · (½)² = 2^{n−2}."""
    assert sp.simplify(2**n * sp.Rational(1, 4) - GRAM_SCALE) == 0


def step_5_pseudoinverse():
    """With KᵀK = g I (g = 2^{n−2}), P = Kᵀ/g satisfies the four Penrose conditions:
    P K = I; K P K = K (P K) = K; P K P = (P K) P = P; (K P)ᵀ = K Kᵀ/g = K P. Written with the
    scalar g: P K = g/g = 1."""
    g = GRAM_SCALE
    assert sp.simplify(g / g - 1) == 0
    assert sp.simplify(1 / g - 2 ** (2 - n)) == 0


def step_6_conclusion_checked_far():
    """KᵀK = 2^{n−2} I exactly for n = 3 … 14 (float64 sums of ±¼ are exact)."""
    import numpy as np

    for order in range(3, 15):
        K = gray_matrix(order)
        assert np.array_equal(K.T @ K, 2.0 ** (order - 2) * np.eye(order))
