"""Theorem (TIM 2014 eq. (21)): for every n ≥ 2 and τ = 2^m, m = 0 … n − 1,

    |S̄_{2^n}(τ)_{j+1} − S̄_{2^n}(τ)_j| = 1   for j = 1 … 2^{n−m} − 1,

and therefore the non-overlapping Allan variance (20) of S_{2^n} is exactly ½ at every such τ.

Assumptions: S_{2^n} from Algorithm 1: S_2 = [−½, ½], S_{2^i} = S_{2^{i−1}} ⊗ [1 1] + a_{1…2^i}, a_k of
eq. (22).

Proof: induction on n. Base case n = 2. Step n − 1 → n: for m ≥ 1 the bin means of S_{2^n} at 2^m
are the bin means of S_{2^{n−1}} at 2^{m−1}; for m = 0 the consecutive differences are a_{2k+2} − a_{2k+1}
= ±1 inside a pair and S_{2^{n−1}}[k + 1] − S_{2^{n−1}}[k] across pairs.
"""

import sympy as sp

from carousel_theory.graycode import deterministic_sequence, sequence_coefficients


def step_1_base_case_n_equals_2():
    S = deterministic_sequence(2)  # [−1, 0, 1, 0]
    assert [abs(S[j + 1] - S[j]) for j in range(3)] == [1, 1, 1]  # τ = 1
    assert abs(S[2:].mean() - S[:2].mean()) == 1  # τ = 2


def step_2_coarser_octaves():
    """m ≥ 1: the bin mean of v ⊗ [1 1] over 2^m samples equals that of v over 2^{m−1} samples
    ((1/2^m) · 2 Σ v = (1/2^{m−1}) Σ v), and a_{1…2^n} has mean 0 over each aligned pair
    (a_{2k−1} + a_{2k} = 0; k mod 2 covers every case, period four). So S̄_{2^n}(2^m) = S̄_{2^{n−1}}(2^{m−1})
    and the hypothesis gives |differences| = 1."""
    m = sp.Symbol("m", integer=True, positive=True)
    assert sp.simplify(2 / 2**m - 1 / 2 ** (m - 1)) == 0
    a = sequence_coefficients(4)
    assert a[0] + a[1] == 0 and a[2] + a[3] == 0


def step_3_within_a_pair():
    """m = 0, samples 2k and 2k + 1 (0-based): same value of S_{2^{n−1}}[k], so the difference is
    a_{2k+2} − a_{2k+1} (1-based a), which depends on k mod 2 only: ±1 in both cases."""
    a = sequence_coefficients(4)
    assert abs(a[1] - a[0]) == 1 and abs(a[3] - a[2]) == 1


def step_4_across_pairs():
    """m = 0, samples 2k + 1 and 2k + 2: the difference is S_{2^{n−1}}[k + 1] − S_{2^{n−1}}[k] plus
    a_{2k+3} − a_{2k+2}, which is 0 in both cases k mod 2 (period four); the hypothesis at τ = 1
    gives ±1."""
    a = sequence_coefficients(8)
    assert a[2] - a[1] == 0 and a[4] - a[3] == 0


def step_5_allan_variance_of_S():
    """σ_A²(τ) = Σ_{j=1}^{M−1} 1 / (2(M − 1)) = ½ exactly, for every M = 2^{n−m} ≥ 2."""
    M = sp.Symbol("M", integer=True, positive=True)
    j = sp.Symbol("j", integer=True, positive=True)
    assert sp.simplify(sp.Sum(1, (j, 1, M - 1)).doit() / (2 * (M - 1)) - sp.Rational(1, 2)) == 0


def step_6_conclusion_checked_far():
    """The theorem for n = 3 … 16, every m (a check of the conclusion, not part of the induction)."""
    for n in range(3, 17):
        S = deterministic_sequence(n)
        for m in range(n):
            means = S.reshape(-1, 2**m).mean(axis=1)
            assert (abs(means[1:] - means[:-1]) == 1).all()
