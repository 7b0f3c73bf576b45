"""Theorem (bin variances of a fractionally integrated process, generalising TIM 2014 §III-D): let
f_t = Σ_{i=1}^{t} ψ_{t−i} w_i with white w of unit variance and any coefficients ψ_0, ψ_1, … (eq. (3)
is one choice). For any weights a_1 … a_N, the statistic of bin k, B_k = Σ_{u=1}^{N} a_u f_{(k−1)N+u},
has

    Var B_k = Σ_{j=0}^{kN−1} g_j²,   g_j = Σ_{u=1}^{N} a_u ψ_{u−N+j}   (ψ of negative index = 0),

the same sequence g for every k. For z with z^N = 1 and h_j = Σ_u z^u ψ_{u−N+j}:
h_j = z^{−1} h_{j−1} + ψ_j − ψ_{j−N} (h_{−1} = 0).

Assumptions: none on ψ or a (they are free symbols below).

Proof: substituting eq. (3), w_i enters B_k with coefficient Σ_{u: (k−1)N+u ≥ i} a_u ψ_{(k−1)N+u−i};
with j = kN − i this is g_j. Steps 1–2 check both identities exhaustively, as polynomial identities
in free symbols ψ_0 … ψ_{kN−1}, a_1 … a_N, z, for every N ≤ 5 and k ≤ 3.
"""

import sympy as sp


def psi_symbols(length):
    return sp.symbols(f"psi0:{length}")


def step_1_variance_equals_sum_of_squared_bin_coefficients():
    """e_kᵀ F Fᵀ e_k (F the Toeplitz matrix of ψ, e_k = a in bin k) equals Σ_{j<kN} g_j², N ≤ 5, k ≤ 3."""
    for N in range(1, 6):
        a = sp.symbols(f"a1:{N + 1}")
        for k in range(1, 4):
            size = k * N
            psi = psi_symbols(size)
            F = sp.Matrix(size, size, lambda t, i, psi=psi: psi[t - i] if i <= t else 0)
            e = sp.Matrix([0] * ((k - 1) * N) + list(a))
            dense = sp.expand((e.T * F * F.T * e)[0, 0])

            def coefficient(j, psi=psi, a=a, N=N):
                return sum(a[u - 1] * psi[u - N + j] for u in range(1, N + 1) if u - N + j >= 0)

            assert sp.expand(dense - sum(coefficient(j) ** 2 for j in range(size))) == 0


def step_2_one_step_recursion_modulo_z_to_the_N_minus_1():
    """z h_j − (h_{j−1} + z ψ_j − z ψ_{j−N}) ≡ 0 modulo z^N − 1, N ≤ 5, j < 3N."""
    z = sp.Symbol("z")
    for N in range(1, 6):
        psi = psi_symbols(3 * N)

        def value(j, psi=psi, N=N):
            return psi[j] if j >= 0 else 0

        def h(j, psi=psi, N=N):
            return sum(z**u * value(u - N + j) for u in range(1, N + 1))

        for j in range(3 * N):
            remainder = sp.expand(z * h(j) - (h(j - 1) + z * value(j) - z * value(j - N)))
            assert sp.rem(sp.Poly(remainder, z), sp.Poly(z**N - 1, z)).is_zero
