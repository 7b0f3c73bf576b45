"""Theorem (TIM 2014 §IV says the sequences "are stationary for a given length"): R_{2^n} = C K x with
x i.i.d. (zero mean, unit variance) is wide-sense stationary for n = 2 and NOT for any n ≥ 3:

    cov(R_0, R_3) − cov(R_1, R_4) = C² ≠ 0   (0-based samples; the same lag 3),

while it is variance-stationary (Var R_t = C² n/4) and stationary under dyadic shifts:
cov(R_{r XOR u}, R_{s XOR u}) = cov(R_r, R_s).

Assumptions: cov R = C² K Kᵀ and (K Kᵀ)[r, s] = −½ S[r XOR s] with S[t] = popcount(g(t)) − n/2
(proofs/proof_graycode_covariance.py, proofs/proof_graycode_gray_code.py).

Proof: direct for all n ≥ 3 (rows 0 … 4 exist since 2^n ≥ 8); n = 2 exhaustive.
"""

import itertools

import sympy as sp

from carousel_theory.graycode import gray_matrix


def gray(r: int) -> int:
    return r ^ (r >> 1)


def step_1_case_n_equals_2_is_stationary():
    """All 4 × 4 covariances, grouped by lag: each lag has one value."""
    K = gray_matrix(2)
    covariance = K @ K.T
    for lag in range(4):
        assert len({covariance[t, t + lag] for t in range(4 - lag)}) == 1


def step_2_the_two_pairs():
    """0 XOR 3 = 3, 1 XOR 4 = 5; g(3) = 2 (one 1), g(5) = 7 (three 1s), independent of n ≥ 3."""
    assert (0 ^ 3, 1 ^ 4) == (3, 5)
    assert (gray(3).bit_count(), gray(5).bit_count()) == (1, 3)


def step_3_difference_for_every_n():
    """cov(R_0, R_3) − cov(R_1, R_4) = −C²/2 (1 − n/2) + C²/2 (3 − n/2) = C², for symbolic n."""
    n, C = sp.symbols("n C", positive=True)
    difference = -(C**2) / 2 * (1 - n / 2) + C**2 / 2 * (3 - n / 2)
    assert sp.simplify(difference - C**2) == 0


def step_4_dyadic_shift_invariance():
    """(r XOR u) XOR (s XOR u) = r XOR s, bitwise on all 8 cases."""
    for r, s, u in itertools.product((0, 1), repeat=3):
        assert (r ^ u) ^ (s ^ u) == r ^ s


def step_5_conclusion_checked_far():
    """The lag-3 pair for n = 3 … 12 from the dense product."""
    for n in range(3, 13):
        K = gray_matrix(n)
        assert K[0] @ K[3] - K[1] @ K[4] == 1.0
