"""TIM 2014 §II: the error process models — bias (1), white noise, rate random walk (2) and 1/f
noise as fractional integration (3) — and their covariances, derived step by step with SymPy.

Every covariance derived here is compared with the package's own entry functions in
:mod:`carousel_theory.processes`, which hold the closed forms; this document only derives them.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from carousel_theory.derivations import Document
from carousel_theory.processes import (
    bias_covariance,
    flicker_covariance,
    fractional_coefficients_exact,
    rate_random_walk_covariance,
    white_covariance,
)
from carousel_theory.symbols import d, sigma_q, sigma_w

__all__ = ["DOCUMENT"]

_j = sp.Symbol("j", integer=True, positive=True)
_i = sp.Symbol("i", integer=True, positive=True)
_s = sp.Symbol("s", integer=True, positive=True)
_t = sp.Symbol("t", integer=True, positive=True)
_lag = sp.Symbol("h", integer=True, nonnegative=True)
_z = sp.Symbol("z")
_b = sp.Symbol("sigma_b", positive=True)
_sigma = sp.Symbol("sigma", positive=True)
_HALF = sp.Rational(1, 2)
#: Sizes for the exhaustive finite checks (every pair s, t ≤ this).
_SMALL = 8
#: Orders j ≤ this for the exact check of ψ at d = 1/2.
_PSI_CHECK = 10
#: Series terms compared between (1 − z)^{−d} and ψ_j.
_SERIES_TERMS = 6


def _psi(index: sp.Expr, order: sp.Expr = d) -> sp.Expr:
    """ψ_index of TIM 2014 eq. (3) as the Gamma ratio printed in the paper (the symbolic form)."""
    return sp.gamma(index + order) / (sp.gamma(index + 1) * sp.gamma(order))


def _display(expression: sp.Basic) -> str:
    return f"$$\n{sp.latex(expression)}\n$$\n"


def _fraction_latex(value: Fraction) -> str:
    return sp.latex(sp.Rational(value.numerator, value.denominator))


def _bias_and_white() -> list[str]:
    out = ["## 1. Bias (1) and white noise\n"]
    out.append(
        "Eq. (1): $b_t = b_{t-1}$, so $b_t = b$ for every t, a random constant with variance "
        "$\\sigma_b^2$. Hence $\\operatorname{Cov}(b_s, b_t) = E[b^2] = \\sigma_b^2$ for all s, t ≥ 1: "
        "the covariance matrix is $\\sigma_b^2 \\mathbf{1}\\mathbf{1}^T$, of rank one.\n"
    )
    out.append(
        "White noise: $e_t$ independent with variance $\\sigma^2$, so "
        "$\\operatorname{Cov}(e_s, e_t) = \\sigma^2 \\delta_{st}$ and the matrix is $\\sigma^2 I$.\n"
    )
    for s in range(1, _SMALL + 1):
        for t in range(1, _SMALL + 1):
            assert bias_covariance(s, t, Fraction(3)) == 3
            assert white_covariance(s, t, Fraction(3)) == (3 if s == t else 0)
    out.append(
        f"**Check.** `processes.bias_covariance` and `processes.white_covariance` give exactly "
        f"$3$ and $3\\delta_{{st}}$ at variance 3 for every s, t ≤ {_SMALL}.\n"
    )
    return out


def _rate_random_walk() -> list[str]:
    out = ["## 2. Rate random walk (2)\n"]
    out.append(
        "Eq. (2): $r_t = r_{t-1} + q_t$ with $r_0 = 0$ and independent increments "
        "$\\operatorname{Var} q_i = \\sigma_q^2$. Unrolling, $r_t = \\sum_{i=1}^{t} q_i$. For s ≤ t, "
        "$\\operatorname{Cov}(r_s, r_t) = \\sum_{i=1}^{s}\\sum_{i'=1}^{t} \\operatorname{Cov}(q_i, q_{i'}) "
        "= \\sum_{i=1}^{s} \\sigma_q^2$ (only i = i' ≤ min(s, t) survive).\n"
    )
    covariance = sp.summation(sigma_q**2, (_i, 1, _s))
    assert sp.simplify(covariance - sigma_q**2 * _s) == 0
    out.append("**Step 2.1.** SymPy `summation` of the surviving diagonal terms, s ≤ t:\n")
    out.append(_display(sp.Eq(sp.Sum(sigma_q**2, (_i, 1, _s)), covariance)))
    out.append("so $\\operatorname{Cov}(r_s, r_t) = \\sigma_q^2 \\min(s, t)$ (by symmetry for s > t).\n")
    size = 5
    cumulative = sp.Matrix(size, size, lambda row, column: 1 if column <= row else 0)
    product = cumulative * cumulative.T
    minimum = sp.Matrix(size, size, lambda row, column: min(row, column) + 1)
    assert product == minimum
    out.append(
        "**Step 2.2 (matrix form).** With the lower-triangular matrix of ones R of eq. (10), "
        "$r = R q$ and $\\operatorname{Cov} r = \\sigma_q^2 R R^T$. For n = 5 SymPy gives\n"
    )
    out.append(_display(sp.Eq(sp.Symbol("R") * sp.Symbol("R^{T}"), product, evaluate=False)))
    out.append(
        "which is $[\\min(s, t)]_{s,t}$. In general $(R R^T)_{st} = \\sum_i [i \\le s][i \\le t] = "
        "\\#\\{i : i \\le \\min(s, t)\\} = \\min(s, t)$.\n"
    )
    for s in range(1, _SMALL + 1):
        for t in range(1, _SMALL + 1):
            assert rate_random_walk_covariance(s, t, Fraction(1)) == min(s, t)
    out.append(
        f"**Check.** `processes.rate_random_walk_covariance` equals min(s, t) exactly for every "
        f"s, t ≤ {_SMALL}.\n"
    )
    return out


def _coefficients() -> list[str]:
    out = ["## 3. 1/f noise (3): the coefficients ψ_j\n"]
    psi = _psi(_j)
    out.append(
        "Eq. (3): $f_t = \\sum_{i=1}^{t} \\psi_{t-i} w_i$, independent $w_i$ of variance "
        "$\\sigma_w^2$, 0 < d < 1, with\n"
    )
    out.append(_display(sp.Eq(sp.Symbol("psi_j"), psi)))
    ratio = sp.gammasimp(psi / _psi(_j - 1))
    assert sp.simplify(ratio - (_j - 1 + d) / _j) == 0
    psi_zero = sp.gammasimp(_psi(sp.Integer(0)))
    assert psi_zero == 1
    out.append("**Step 3.1 (recursion).** SymPy `gammasimp` of the ratio of consecutive coefficients:\n")
    out.append(_display(sp.Eq(sp.Symbol("psi_j") / sp.Symbol(r"\psi_{j-1}"), ratio)))
    out.append(
        f"and $\\psi_0 = {sp.latex(psi_zero)}$. So $\\psi_j = \\psi_{{j-1}}(j-1+d)/j$: the recursion "
        "`processes.fractional_coefficients` and `fractional_coefficients_exact` evaluate.\n"
    )
    half_ratio = sp.gammasimp(_psi(_j, _HALF) / (sp.binomial(2 * _j, _j) / 4**_j))
    half_ratio = sp.simplify(sp.gammasimp(sp.combsimp(half_ratio.rewrite(sp.gamma))))
    assert half_ratio == 1
    exact = fractional_coefficients_exact(Fraction(1, 2), _PSI_CHECK + 1)
    for index in range(_PSI_CHECK + 1):
        central = Fraction(int(sp.binomial(2 * index, index)), 4**index)
        assert exact[index] == central
        assert sp.Rational(central.numerator, central.denominator) == sp.gammasimp(_psi(index, _HALF))
    out.append(
        "**Step 3.2 (d = 1/2).** SymPy simplifies "
        f"$\\psi_j\\big|_{{d=1/2}} \\big/ \\left(\\binom{{2j}}{{j}}/4^j\\right)$ to "
        f"${sp.latex(half_ratio)}$ (Legendre's duplication formula), so at d = 1/2\n"
    )
    out.append(_display(sp.Eq(sp.Symbol("psi_j"), sp.binomial(2 * _j, _j) / 4**_j)))
    out.append(
        f"Exactly for j = 0 … {_PSI_CHECK}, `fractional_coefficients_exact(1/2, {_PSI_CHECK + 1})` "
        "equals both $\\binom{2j}{j}/4^j$ and the Gamma ratio: "
        + ", ".join(f"${_fraction_latex(value)}$" for value in exact[:6])
        + ", ….\n"
    )
    return out


def _flicker_covariance() -> list[str]:
    out = ["## 4. 1/f noise: covariance and variance growth\n"]
    m = sp.Symbol("m", integer=True, nonnegative=True)
    psi = sp.Function("psi")
    out.append(
        "Since $w_i$ enters $f_s$ with coefficient $\\psi_{s-i}$ and the $w_i$ are independent, "
        "only i ≤ min(s, t) contributes; with m = i − 1,\n"
    )
    covariance = sigma_w**2 * sp.Sum(psi(_s - 1 - m) * psi(_t - 1 - m), (m, 0, sp.Min(_s, _t) - 1))
    out.append(_display(sp.Eq(sp.Symbol(r"\operatorname{Cov}(f_s, f_t)"), covariance)))
    out.append(
        "and, with j = min(s, t) − 1 − m and h = |s − t|, "
        "$\\sigma_w^2 \\sum_{j=0}^{\\min(s,t)-1} \\psi_j \\psi_{j+h}$ — the form "
        "`processes.flicker_covariance` evaluates.\n"
    )
    half = Fraction(1, 2)
    coefficients = fractional_coefficients_exact(half, _SMALL)
    for s in range(1, _SMALL + 1):
        for t in range(1, _SMALL + 1):
            direct = sum(
                (coefficients[s - 1 - k] * coefficients[t - 1 - k] for k in range(min(s, t))), Fraction(0)
            )
            assert flicker_covariance(s, t, half, Fraction(1)) == direct
    out.append(
        f"**Check.** At d = 1/2 the sum over m, formed from the exact ψ, equals "
        f"`processes.flicker_covariance` exactly for every s, t ≤ {_SMALL}.\n"
    )
    out.append(
        "**Variance growth.** At s = t, $\\operatorname{Var} f_t = \\sigma_w^2 \\sum_{j=0}^{t-1} "
        "\\psi_j^2$: it grows without bound iff $\\sum_j \\psi_j^2 = \\infty$; by (19) "
        "$\\psi_j^2 \\sim j^{2d-2}/\\Gamma(d)^2$, so iff d ≥ 1/2. At d = 1/2 "
        "($\\psi_j^2 \\sim 1/(\\pi j)$) the growth is logarithmic, $\\log t/\\pi$. Exact values at "
        "d = 1/2 ($\\sigma_w^2 = 1$):\n"
    )
    rows = ["| t | ψ_{t−1} | Var f_t | decimal |", "|---|---|---|---|"]
    total = Fraction(0)
    for t, value in enumerate(coefficients, start=1):
        total += value * value
        assert flicker_covariance(t, t, half, Fraction(1)) == total
        rows.append(f"| {t} | ${_fraction_latex(value)}$ | ${_fraction_latex(total)}$ | {float(total):.6f} |")
    out.append("\n".join(rows) + "\n")
    return out


def _transfer_function() -> list[str]:
    out = ["## 5. Transfer function and spectrum\n"]
    transfer = (1 - _z) ** (-d)
    series = sp.series(transfer, _z, 0, _SERIES_TERMS).removeO()
    for index in range(_SERIES_TERMS):
        coefficient = series.coeff(_z, index)
        assert sp.simplify(sp.gammasimp(coefficient - _psi(sp.Integer(index)))) == 0
    out.append(
        "Eq. (3) is the convolution $f = \\psi * w$ (w = 0 before t = 1), so its transfer function is "
        "the generating function $\\sum_j \\psi_j z^j$. SymPy `series` of $(1 - z)^{-d}$ at z = 0:\n"
    )
    terms = " + ".join(
        f"{sp.latex(sp.factor(series.coeff(_z, index)))}\\, {sp.latex(_z**index)}" if index else "1"
        for index in range(_SERIES_TERMS)
    )
    out.append(f"$$\n{sp.latex(transfer)} = {terms} + O(z^{{{_SERIES_TERMS}}})\n$$\n")
    out.append(
        f"whose coefficients equal $\\psi_0 … \\psi_{{{_SERIES_TERMS - 1}}}$ (each difference "
        "`gammasimp`s to 0); in general this is the binomial series "
        "$(1-z)^{-d} = \\sum_j \\binom{-d}{j}(-z)^j$ with $(-1)^j\\binom{-d}{j} = (d)_j/j! = \\psi_j$.\n"
    )
    frequency = sp.Symbol("f", positive=True)
    on_circle = 1 - sp.exp(-2 * sp.pi * sp.I * frequency)
    modulus_squared = sp.simplify(sp.expand_complex(on_circle * sp.conjugate(on_circle)))
    target = 4 * sp.sin(sp.pi * frequency) ** 2
    assert sp.simplify(sp.expand_trig(modulus_squared - target).rewrite(sp.cos)) == 0
    out.append(
        "On the unit circle $z = e^{-2\\pi i f}$ (f in cycles per sample), SymPy gives "
        f"$|1 - z|^2 = {sp.latex(modulus_squared)}$, so the spectral density of f "
        "is\n"
    )
    spectrum = sigma_w**2 * sp.Abs(2 * sp.sin(sp.pi * frequency)) ** (-2 * d)
    out.append(f"$$\nS_f(f) = {sp.latex(spectrum)}\n$$\n")
    low = sp.limit(spectrum.subs(d, _HALF) * frequency, frequency, 0, "+")
    assert sp.simplify(low - sigma_w**2 / (2 * sp.pi)) == 0
    out.append(
        "For small f, $|2\\sin(\\pi f)| \\approx 2\\pi f$, so $S_f \\propto f^{-2d}$; at d = 1/2 "
        f"$\\lim_{{f \\to 0^+}} f\\, S_f(f) = {sp.latex(low)}$: the spectrum is 1/f, which is why the "
        "paper takes d = 1/2 for flicker noise. (The driving noise is switched on at t = 1, so f is "
        "nonstationary for d ≥ 1/2 and the spectrum is that of the filter, not of a stationary process.)\n"
    )
    return out


def _build() -> str:
    out: list[str] = [
        "The four error processes of TIM 2014 §II, each started at sample t = 1, with their "
        "covariances. The package evaluates them in `carousel_theory.processes`; each step below is "
        "computed by SymPy when this document is generated and compared with that module.\n"
    ]
    out += _bias_and_white()
    out += _rate_random_walk()
    out += _coefficients()
    out += _flicker_covariance()
    out += _transfer_function()
    return "\n".join(out)


DOCUMENT = Document("tim2014_error_processes", "TIM 2014 §II: error process models", _build)
