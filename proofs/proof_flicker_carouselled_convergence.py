"""Theorem (TIM 2014 §III-D: the carouselled 1/f variance does not grow; made exact): for N ≥ 2,
0 < d < 1 and σ_w² = 1 the variance Var_k of the k-th carouselled estimate (sine gyro + cosine gyro,
eq. (6), (13)) increases with k to a finite limit Var_∞, and for d = 1/2, k ≥ 2

    0 ≤ Var_∞ − Var_k ≤ B(N, k) = (N − 1)² / (8π N⁴ sin²(π/N) (k − 1)²)   (≈ 1/(8π³(k − 1)²) for large N).

Assumptions: Var_k = N⁻² Σ_{j<kN} |h_j|², h_j = Σ_{u=1}^{N} z^u ψ_{u−N+j}, z = e^{2πi/N}
(proof_flicker_bin_coefficients); for the explicit bound, ψ_m² < 1/(πm) at d = 1/2
(proof_flicker_averaged_log_growth, Steps 1–2).

Proof:
Step 1 (summation by parts). With Z_u = z + … + z^u (so Z_N = 0), for j ≥ N − 1:
        h_j = Σ_{u=1}^{N−1} Z_u (ψ_{j−N+u} − ψ_{j−N+u+1}).
Step 2. |Z_u| = |sin(πu/N)| / sin(π/N) ≤ 1/sin(π/N).
Step 3. ψ_m − ψ_{m+1} = (1 − d) ψ_m/(m + 1) > 0, so |h_j| ≤ (ψ_{j−N+1} − ψ_j)/sin(π/N)
        ≤ (N − 1)(1 − d) ψ_{j−N+1} / ((j − N + 2) sin(π/N)) = O(j^{d−2}); since 2(d − 2) < −1 the
        squares are summable: Var_k increases (a sum of squares) to a finite limit.
Step 4. At d = 1/2: the tail N⁻² Σ_{j≥kN} |h_j|² ≤ N⁻² sin⁻²(π/N) (N−1)²/4 Σ_{m>(k−1)N} 1/(π m³)
        ≤ B(N, k).
Step 5. B(N, k) bounds the computed tail Var_{8k} − Var_k at 50 digits for N ∈ {2, 3, 8, 200}, k ∈ {2, 5, 10}.
"""

import mpmath
import sympy as sp

from carousel_theory import symbols
from carousel_theory.flicker_asymptotics import (
    CAROUSELLED_TAIL_BOUND_HALF,
    fractional_coefficient,
)
from carousel_theory.propagation import flicker_bin_variances_high_precision
from carousel_theory.symbols import d


def step_1_summation_by_parts():
    """Polynomial identity in free ψ's and z modulo 1 + z + … + z^{N−1} (i.e. z^N = 1, z ≠ 1), for
    N ≤ 6 and N − 1 ≤ j < 3N."""
    z = sp.Symbol("z")
    for N in range(2, 7):
        psi = sp.symbols(f"psi0:{3 * N + 1}")
        cyclotomic_multiple = sp.Poly(sum(z**v for v in range(N)), z)

        def partial(u):
            return sum(z**v for v in range(1, u + 1))

        for j in range(N - 1, 3 * N):
            h = sum(z**u * psi[u - N + j] for u in range(1, N + 1))
            by_parts = sum(partial(u) * (psi[j - N + u] - psi[j - N + u + 1]) for u in range(1, N))
            assert sp.rem(sp.Poly(sp.expand(h - by_parts), z), cyclotomic_multiple).is_zero


def step_2_partial_sums_of_roots_of_unity():
    """|Z_u|² = sin²(πu/N)/sin²(π/N): checked at 40 digits for N ≤ 12, all u."""
    with mpmath.workdps(40):
        for N in range(2, 13):
            z = mpmath.expjpi(mpmath.mpf(2) / N)
            for u in range(1, N + 1):
                partial = mpmath.fsum(z**v for v in range(1, u + 1))
                expected = mpmath.sinpi(mpmath.mpf(u) / N) ** 2 / mpmath.sinpi(mpmath.mpf(1) / N) ** 2
                assert abs(abs(partial) ** 2 - expected) < mpmath.mpf(10) ** -35
                assert abs(partial) ** 2 <= 1 / mpmath.sinpi(mpmath.mpf(1) / N) ** 2 + mpmath.mpf(10) ** -35


def step_3_differences_of_the_coefficients():
    m = sp.Symbol("m", integer=True, nonnegative=True)
    difference = sp.gammasimp(fractional_coefficient(m) - fractional_coefficient(m + 1))
    assert sp.simplify(difference - (1 - d) * fractional_coefficient(m) / (m + 1)) == 0


def step_4_explicit_tail_bound():
    """N⁻² sin⁻²(π/N) ((N−1)/2)² · (1/π) ∫_{(k−1)N}^{∞} x⁻³ dx = B(N, k)."""
    x = sp.Symbol("x", positive=True)
    N, k = symbols.N, symbols.k
    start = sp.Symbol("L", positive=True)  # L = (k − 1)N > 0 for k ≥ 2
    integral = sp.integrate(x**-3, (x, start, sp.oo)).subs(start, (k - 1) * N)
    bound = (N - 1) ** 2 / (4 * N**2 * sp.sin(sp.pi / N) ** 2) * integral / sp.pi
    assert sp.simplify(bound - CAROUSELLED_TAIL_BOUND_HALF) == 0


def step_5_bound_holds_at_50_digits():
    bound = sp.lambdify((symbols.N, symbols.k), CAROUSELLED_TAIL_BOUND_HALF, "mpmath")
    with mpmath.workdps(50):
        for N in (2, 3, 8, 200):
            every = flicker_bin_variances_high_precision(sp.Rational(1, 2), N, 80, "carouselled", digits=50)
            for k in (2, 5, 10):
                tail = every[8 * k - 1] - every[k - 1]
                assert 0 <= tail <= bound(N, k)
