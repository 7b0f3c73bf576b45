"""Theorem (carousel_theory.ar_modes): for an AR(p) process at unit innovation variance whose
characteristic roots λ_i are distinct, non-zero and inside the unit circle, the fourth sum of its
increment autocovariance, H(x) = Σ_k γ_z(k) R₃(x − k) with R₃(y) = C(y + 3, 3) for y ≥ −3 and 0 below, is

    H(x) = −S max(x + 2, 0) + Σ_i C_i λ_i^{|x + 2|}   at every integer x,
    S = 1/(1 − Σ_j φ_j)²,   C_i = −A_i λ_i/(1 − λ_i)²,   γ(k) = Σ_i A_i λ_i^{|k|}.

It is what lets the lag quadrature cover an AR term with Gauss blocks (the modes are analytic on either
side of x = −2), so that the cost of the τ-covariance does not grow with the correlation time.

Steps: the two series behind the proof (SymPy, symbolic λ and φ); the first-order case in closed form;
the identity itself at 50 digits (H summed from its definition with the γ of the Yule–Walker recursion,
for real, negative, complex and mixed roots); the package's double-precision modes against the 50-digit
ones.
"""

from __future__ import annotations

import mpmath
import numpy as np
import sympy as sp

from carousel_theory.ar_modes import ar_modes

lam, phi = sp.symbols("lambda phi")
j = sp.Symbol("j", integer=True, nonnegative=True)
k = sp.Symbol("k", integer=True)

COEFFICIENTS = [(0.8,), (-0.5,), (0.6, -0.2), (0.5, 0.2), (0.3, 0.2, 0.1)]


def step_1_binomial_series():
    """Σ_{j≥0} C(j + 3, 3) λ^j = 1/(1 − λ)⁴ (|λ| < 1): the left branch H(x) = Σ_j γ_z(x − j) C(j + 3, 3)
    and the right branch's correction Σ_{j≥0} γ_z(x + 4 + j) C(j + 3, 3) are this series times one mode
    each."""
    series = sp.summation(sp.binomial(j + 3, 3) * lam**j, (j, 0, sp.oo))
    assert isinstance(series, sp.Piecewise)
    assert sp.simplify(series.args[0][0] - 1 / (1 - lam) ** 4) == 0
    # p(−4 − j) = −C(j + 3, 3): R₃ and the cubic p differ exactly where x − k ≤ −4.
    cubic = (-4 - j + 1) * (-4 - j + 2) * (-4 - j + 3) / sp.Integer(6)
    assert sp.expand(cubic + sp.expand_func(sp.binomial(j + 3, 3))) == 0


def step_2_moments():
    """The Taylor form of the right branch has M₀ = 0, M₁ = M₃ = 0 and M₂ = −2S: with
    γ_z(k) = 2γ(k) − γ(k − 1) − γ(k + 1), Σ_k k^r γ_z(k) = Σ_k γ(k)(2k^r − (k + 1)^r − (k − 1)^r), and the
    bracket is 0 for r = 0, −2 for r = 2 (and odd for r = 1, 3, where γ is even). For AR(1),
    S = Σ_k φ^{|k|}/(1 − φ²) = 1/(1 − φ)²."""
    brackets = [sp.expand(2 * k**r - (k + 1) ** r - (k - 1) ** r) for r in range(4)]
    assert brackets[0] == 0 and brackets[2] == -2
    assert brackets[1] == 0 and brackets[3] == -6 * k  # odd in k: Σ γ(k)·odd = 0 for an even γ
    geometric = sp.summation(phi**j, (j, 0, sp.oo))
    assert isinstance(geometric, sp.Piecewise)
    tail = phi * geometric.args[0][0]  # Σ_{k≥1} φ^k
    long_run = (1 + 2 * tail) / (1 - phi**2)
    assert sp.simplify(long_run - 1 / (1 - phi) ** 2) == 0


def step_3_first_order_weight():
    """AR(1): A = 1/(1 − φ²), b = A(2 − φ − 1/φ), C = bφ²/(1 − φ)⁴ = −Aφ/(1 − φ)² = −φ/((1 − φ)²(1 − φ²))."""
    amplitude = 1 / (1 - phi**2)
    increment = amplitude * (2 - phi - 1 / phi)
    weight = increment * phi**2 / (1 - phi) ** 4
    assert sp.simplify(weight + amplitude * phi / (1 - phi) ** 2) == 0
    assert sp.simplify(weight + phi / ((1 - phi) ** 2 * (1 - phi**2))) == 0


def _modes_at_50_digits(coefficients):
    """(roots, A_i, S, γ) at 50 digits: γ(0 … p) from the Yule–Walker system, A_i from γ(0 … p − 1)."""
    p = len(coefficients)
    values = [mpmath.mpf(repr(c)) for c in coefficients]
    system = mpmath.eye(p + 1)
    for row in range(p + 1):
        for lag in range(1, p + 1):
            system[row, abs(row - lag)] -= values[lag - 1]
    right = mpmath.matrix([1] + [0] * p)
    head = mpmath.lu_solve(system, right)
    roots = mpmath.polyroots([1] + [-v for v in values], maxsteps=200, extraprec=200)
    vandermonde = mpmath.matrix([[r**row for r in roots] for row in range(p)])
    amplitudes = mpmath.lu_solve(vandermonde, mpmath.matrix([head[row] for row in range(p)]))
    return roots, [amplitudes[i] for i in range(p)], 1 / (1 - mpmath.fsum(values)) ** 2, head, values


def _direct_fourth_sums(roots, amplitudes, points: range) -> list:
    """H(x) at ``points`` from its definition, Σ_k γ_z(k) C(x − k + 3, 3) over k ≤ x (R₃ vanishes at −1, −2,
    −3), the modal γ summed out to where every |λ|^|k| < 10⁻⁷⁰."""
    slowest = max(abs(r) for r in roots)
    depth = int(mpmath.ceil(70 * mpmath.log(10) / -mpmath.log(slowest))) + 8
    reach = depth + max(abs(points.start), abs(points.stop)) + 2
    gamma = [
        mpmath.re(mpmath.fsum(a * r**lag for r, a in zip(roots, amplitudes, strict=True)))
        for lag in range(reach + 1)
    ]

    def increment(lag: int):
        return 2 * gamma[abs(lag)] - gamma[abs(lag - 1)] - gamma[abs(lag + 1)]

    return [
        mpmath.fsum(
            increment(lag) * ((x - lag + 1) * (x - lag + 2) * (x - lag + 3) // 6)
            for lag in range(x - depth, x + 1)
        )
        for x in points
    ]


def step_4_identity_at_50_digits():
    """The theorem at every integer x from −25 to 25, 50 digits, for real (0.8), negative (−0.5), complex
    (0.6, −0.2), mixed (0.5, 0.2) and three roots (0.3, 0.2, 0.1); the modal γ is first held to the
    Yule–Walker recursion, so H is summed from the process's own autocovariance."""
    with mpmath.workdps(50):
        for coefficients in COEFFICIENTS:
            roots, amplitudes, long_run, head, values = _modes_at_50_digits(coefficients)
            p = len(values)
            modal = [
                mpmath.re(mpmath.fsum(a * r**lag for r, a in zip(roots, amplitudes, strict=True)))
                for lag in range(p + 40)
            ]
            assert all(abs(modal[lag] - head[lag]) < mpmath.mpf(10) ** -45 for lag in range(p + 1))
            for lag in range(p + 1, p + 40):
                recursion = mpmath.fsum(values[i] * modal[lag - 1 - i] for i in range(p))
                assert abs(modal[lag] - recursion) < mpmath.mpf(10) ** -45
            weights = [-a * r / (1 - r) ** 2 for r, a in zip(roots, amplitudes, strict=True)]
            points = range(-25, 26)
            for x, direct in zip(points, _direct_fourth_sums(roots, amplitudes, points), strict=True):
                closed = -long_run * max(x + 2, 0) + mpmath.re(
                    mpmath.fsum(w * r ** abs(x + 2) for r, w in zip(roots, weights, strict=True))
                )
                assert abs(closed - direct) < mpmath.mpf(10) ** -40 * (1 + abs(direct))


def step_5_package_modes():
    """The package's double-precision modes (:func:`carousel_theory.ar_modes.ar_modes`) against the 50-digit
    ones: the same roots, weights C_i and S to 1e-11 relative."""
    with mpmath.workdps(50):
        for coefficients in COEFFICIENTS:
            roots, amplitudes, long_run, _, _ = _modes_at_50_digits(coefficients)
            modes = ar_modes(coefficients)
            assert modes is not None
            assert abs(modes.long_run_variance - float(long_run)) <= 1e-12 * float(long_run)
            for r, a in zip(roots, amplitudes, strict=True):
                exact = complex(-a * r / (1 - r) ** 2)
                place = int(np.argmin(np.abs(modes.roots - complex(r))))
                assert abs(modes.roots[place] - complex(r)) <= 1e-13
                assert abs(modes.weights[place] - exact) <= 1e-11 * abs(exact)
