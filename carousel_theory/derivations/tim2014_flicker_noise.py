"""1/f noise under averaging and carouseling (TIM 2014 §III-D, §V-B): exact bin variances for every
k, the limit (19), and how the variances grow with the bin number k.

The asymptotic laws are SymPy expressions of :mod:`carousel_theory.flicker_asymptotics`, shown here
with their derivation.
"""

from __future__ import annotations

import sympy as sp

from carousel_theory.derivations import Document
from carousel_theory.flicker_asymptotics import (
    AVERAGED_GROWTH_ABOVE_HALF,
    AVERAGED_GROWTH_AT_HALF,
    AVERAGED_INCREMENT,
    AVERAGED_LOG_LOWER_BOUND,
    AVERAGED_LOG_UPPER_BOUND,
    AVERAGED_TAIL_BELOW_HALF,
    CAROUSELLED_TAIL,
    CAROUSELLED_TAIL_BOUND_HALF,
    STATIONARY_AUTOCOVARIANCE,
    STATIONARY_AUTOCOVARIANCE_TAIL,
    cumulative_coefficient,
    fractional_coefficient,
    limit_19_log_series,
    log_growth_envelopes,
    stationary_autocovariance_derivation,
)
from carousel_theory.propagation import flicker_bin_variances
from carousel_theory.symbols import N, d, k

__all__ = ["DOCUMENT"]


_j = sp.Symbol("j", integer=True, positive=True)
_M = sp.Symbol("M", integer=True, nonnegative=True)
_i = sp.Symbol("i", positive=True)
_x = sp.Symbol("x", positive=True)
_z = sp.Symbol("z", nonzero=True)
_u = sp.Symbol("u", integer=True, positive=True)


def _zero(expression: sp.Expr) -> bool:
    return sp.simplify(sp.gammasimp(expression)) == 0


def _latex(expression: sp.Expr) -> str:
    return f"$${sp.latex(expression)}$$"


def _float(value: float) -> str:
    return f"{value:.6g}"


def _build() -> str:
    out: list[str] = []
    psi = fractional_coefficient(_j)

    out.append("## 1. The coefficients of eq. (3) and their cumulative sums\n")
    out.append(
        "TIM 2014 eq. (3): $f_t = \\sum_{i=1}^{t} \\psi_{t-i} w_i$ with "
        + _latex(sp.Eq(sp.Symbol("psi_j"), psi))
    )
    ratio = sp.gammasimp(psi / fractional_coefficient(_j - 1))
    assert _zero(ratio - (_j - 1 + d) / _j)
    psi_zero = sp.gammasimp(fractional_coefficient(sp.Integer(0)))
    out.append(
        "**Step 1.1 (recursion).** SymPy `gammasimp` gives $\\psi_j/\\psi_{j-1}$ = "
        f"${sp.latex(ratio)}$, and $\\psi_0 = {sp.latex(psi_zero)}$. "
        "The package evaluates ψ by this recursion (no Gamma value is formed, so nothing overflows for "
        "j up to 10⁷). For 0 < d < 1 the factor lies in (0, 1): ψ_j is positive and strictly decreasing.\n"
    )
    Psi = cumulative_coefficient(_M)
    base = sp.gammasimp(cumulative_coefficient(sp.Integer(0)))
    step = cumulative_coefficient(_M + 1) - cumulative_coefficient(_M) - fractional_coefficient(_M + 1)
    assert base == 1 and _zero(step)
    out.append(
        "**Step 1.2 (cumulative sum, by induction).** Claim: "
        + _latex(sp.Eq(sp.Symbol("Psi_M"), Psi))
        + f"Base case M = 0: the right side is {sp.latex(base)} = ψ_0. Induction step: "
        "$\\Psi_{M+1} - \\Psi_M - \\psi_{M+1}$ simplifies (SymPy `gammasimp`) to 0. "
        "So Ψ is ψ of order d + 1: the entries of $F\\mathbf{1}$ (§III-D) are $\\Psi_{t-1}/N$.\n"
    )

    out.append("## 2. The limit (19)\n")
    lhs = sp.gamma(_i + d) / (sp.gamma(_i + 1) * sp.gamma(d)) / _i ** (d - 1)
    middle = sp.gamma(_i + d) / (_i**d * sp.gamma(_i) * sp.gamma(d))
    assert _zero(lhs - middle)
    log_series = limit_19_log_series()
    out.append(
        "**Step 2.1.** The two middle forms of (19) are equal: "
        f"$\\frac{{\\psi_i}}{{i^{{d-1}}}} - {sp.latex(middle)} = 0$ (SymPy).\n"
    )
    out.append(
        "**Step 2.2.** Stirling's series (SymPy `series` at i = ∞): "
        f"$\\log\\frac{{\\Gamma(i+d)}}{{i^d\\Gamma(i)}} = {sp.latex(log_series)} + O(i^{{-2}})$ → 0, so "
        "$\\Gamma(i+d)/(i^d\\Gamma(i)) \\to 1$ and the limit (19) is $1/\\Gamma(d) > 0$ for every d > 0, "
        "as printed. Hence $\\psi_j \\sim j^{d-1}/\\Gamma(d)$ and (order d + 1) "
        "$\\Psi_M \\sim M^d/\\Gamma(d+1) \\to \\infty$.\n"
    )
    out.append(
        "**Step 2.3 (the comparison series).** The paper compares with $\\sum_{i=0}^{\\infty} i^{d-1}$. "
        "Its first term $0^{d-1}$ is undefined (division by zero) for every d < 1, i.e. for every order "
        "the model allows; the series must start at i = 1. Then $\\sum_{i\\ge1} i^{d-1}$ is the p-series "
        "with p = 1 − d, divergent exactly when p ≤ 1, i.e. d ≥ 0: the conclusion ($F\\mathbf{1}$ → ∞) "
        "holds for every d > 0, and Step 1.2 gives the rate $M^d/\\Gamma(d+1)$ directly.\n"
    )

    out.append("## 3. Every bin from one sequence\n")
    out.append(
        "Bin k holds samples t = (k−1)N + 1 … kN and is reduced with weights $a_1 … a_N$ "
        "(averaging: $a_u = 1/N$, eq. (12); carouseling: $s_u$, $c_u$ of eq. (13)). Substituting (3), "
        "the driving sample $w_i$ enters bin k with the coefficient "
        "$\\sum_{u:\\,(k-1)N+u \\ge i} a_u \\psi_{(k-1)N+u-i}$. With j = kN − i this is "
        "$$g_j = \\sum_{u=1}^{N} a_u\\, \\psi_{u-N+j}\\qquad(\\psi_{<0} = 0),$$ "
        "independent of k, so $\\operatorname{Var}_k = \\sigma_w^2 \\sum_{j=0}^{kN-1} g_j^2$: all bins from "
        "one cumulative sum, no (kN)×(kN) matrix. Averaging: $g_j = (\\Psi_j - \\Psi_{j-N})/N$. "
        "Carouseling: with $z = e^{2\\pi i/N}$ and $h_j = \\sum_u z^u \\psi_{u-N+j}$, the sine and cosine "
        "gyros give $\\operatorname{Im} h_j/N$ and $\\operatorname{Re} h_j/N$, and "
        "$h_j = \\bar z h_{j-1} + \\psi_j - \\psi_{j-N}$ (because $z^N = 1$), so the carouselled variance "
        "of bin k is $N^{-2}\\sum_{j<kN} |h_j|^2$.\n"
    )
    geometric = sp.summation(_u * _z**_u, (_u, 1, N))
    general = geometric.args[-1][0] if isinstance(geometric, sp.Piecewise) else geometric  # the z ≠ 1 branch
    target = N * _z / (_z - 1)
    assert sp.simplify(sp.expand(general).subs(_z**N, 1) - target) == 0
    out.append(
        "**Step 3.1.** For $z^N = 1$, z ≠ 1 (N ≥ 2), SymPy sums "
        f"$\\sum_{{u=1}}^{{N}} u z^u = {sp.latex(general)} = {sp.latex(target)}$, "
        "of modulus $N/|z-1| = N/(2\\sin(\\pi/N))$; and "
        "$\\sum_u z^u = 0$ (bias cancellation, eq. (8)).\n"
    )

    out.append("## 4. Averaged bins: growth with k\n")
    increment_integral = sp.integrate(_x ** (2 * d - 2), (_x, (k - 1) * N, k * N))
    out.append(
        "For j ≫ N, $g_j = N^{-1}\\sum_{m=j-N+1}^{j}\\psi_m = \\psi_j(1 + O(N/j))$ and, by (19), "
        "$\\psi_j^2 \\sim j^{2d-2}/\\Gamma(d)^2$. So the increment of bin k is "
        "$\\operatorname{Var}_k - \\operatorname{Var}_{k-1} = \\sum_{j=(k-1)N}^{kN-1} g_j^2 \\sim "
        "\\Gamma(d)^{-2}\\int_{(k-1)N}^{kN} x^{2d-2}\\,dx$, whose leading term in k is "
        + _latex(AVERAGED_INCREMENT)
        + f"(SymPy: the integral is ${sp.latex(sp.simplify(increment_integral))}$). Summing over k:\n\n"
        f"- 1/2 < d < 1: $\\operatorname{{Var}}_k = {sp.latex(AVERAGED_GROWTH_ABOVE_HALF)} + C(N,d) + o(1)$, "
        "unbounded;\n"
        f"- d = 1/2: $\\operatorname{{Var}}_k = {sp.latex(AVERAGED_GROWTH_AT_HALF)} + C(N) + o(1)$ — "
        "logarithmic, as TIM 2014 §V-B suspected from Fig. 5 ($\\Gamma(1/2)^2 = \\pi$). Rigorously, for "
        "every N ≥ 1 and k ≥ 2, "
        f"${sp.latex(AVERAGED_LOG_LOWER_BOUND)} \\le \\operatorname{{Var}}_k - \\operatorname{{Var}}_2 \\le "
        f"{sp.latex(AVERAGED_LOG_UPPER_BOUND)}$: with $a_j = j\\psi_j^2$, $b_j = (j+\\tfrac12)\\psi_j^2$, "
        f"SymPy gives $a_j/a_{{j-1}} - 1 = {sp.latex(log_growth_envelopes()[0])}$ and "
        f"$b_j/b_{{j-1}} - 1 = {sp.latex(log_growth_envelopes()[1])}$, so $1/(\\pi(j+\\frac12)) < \\psi_j^2 "
        "< 1/(\\pi j)$; $\\psi_j \\le g_j \\le \\psi_{j-N+1}$ (window mean of a decreasing sequence), and "
        "integral comparison bounds each increment; the sums telescope "
        "(proofs/proof_flicker_averaged_log_growth.py);\n"
        "- 0 < d < 1/2: the variance **converges**; "
        "$\\operatorname{Var}_\\infty - \\operatorname{Var}_k \\sim "
        f"{sp.latex(AVERAGED_TAIL_BELOW_HALF)}$.\n\n"
        "So $F\\mathbf{1} \\to \\infty$ (§III-D) does not by itself make the averaged variance unbounded: "
        "that needs $\\sum_j \\psi_j^2 = \\infty$, i.e. d ≥ 1/2.\n"
    )
    out.append(_averaged_table())

    out.append("## 5. Carouselled bins: convergence and its rate\n")
    tail_integral = sp.integrate(_x ** (2 * d - 4), (_x, k * N, sp.oo), conds="none")
    out.append(
        "For j ≫ N, Taylor expansion of ψ around j and Step 3.1 give "
        "$h_j \\approx \\psi'(j)\\sum_u (u-N) z^u = \\psi'(j)\\, N z/(z-1)$ with "
        "$\\psi'(j) \\sim (d-1) j^{d-2}/\\Gamma(d)$ (the next term is smaller by O(N/j)). Hence "
        "$|g_j|$ is $O(j^{d-2})$, square-summable for every d < 1: the carouselled variance converges "
        "to a finite limit, with "
        + "$$\\operatorname{Var}_\\infty - \\operatorname{Var}_k \\sim "
        + sp.latex(CAROUSELLED_TAIL)
        + "$$ to leading order "
        + f"($\\int_{{kN}}^{{\\infty}} x^{{2d-4}}dx = {sp.latex(sp.simplify(tail_integral))}$). "
        "At d = 1/2, N ≫ 1 this is $\\approx 1/(32\\pi^3 k^2)$. Rigorously (summation by parts with the "
        "partial sums $Z_u$ of the roots of unity, $|Z_u| \\le 1/\\sin(\\pi/N)$, "
        "$\\psi_m - \\psi_{m+1} = (1-d)\\psi_m/(m+1)$, and $\\psi_m^2 < 1/(\\pi m)$ at d = 1/2): "
        f"$\\operatorname{{Var}}_\\infty - \\operatorname{{Var}}_k \\le "
        f"{sp.latex(CAROUSELLED_TAIL_BOUND_HALF)}$ "
        "for k ≥ 2 (proofs/proof_flicker_carouselled_convergence.py).\n"
    )
    out.append(_carouselled_table())

    out.append("## 6. The Leibniz argument of §III-D\n")
    out.append(
        "For the carouselled sum over many revolutions, the coefficient of one driving sample is "
        "$\\sum_{m\\ge0} \\psi_m a_{(i+m) \\bmod N}$. For even N, $a_{u+N/2} = -a_u$ "
        "($\\sin(x+\\pi) = -\\sin x$), so grouping the terms with the same |a_u| gives N/2 alternating "
        "series whose terms decrease in absolute value (Step 1.1) to 0 (Step 2.2): each converges by "
        "Leibniz's criterion, as the paper says. For odd N the same conclusion follows from Dirichlet's "
        "test (the partial sums of a periodic zero-sum sequence are bounded and ψ decreases to 0). "
        "Convergence of these coefficients is weaker than convergence of the per-bin variance, which "
        "needs $\\sum_j g_j^2 < \\infty$; Section 5 supplies it.\n"
    )
    out.append("## 7. Long memory of eq. (3) (§II-D)\n")
    steps = stationary_autocovariance_derivation()
    assert steps["term"] == 0 and steps["gauss"] == 0 and steps["tail"] == 0
    out.append(
        "cov(f_t, f_{t+h}) = $\\sum_{j=0}^{t-1}\\psi_j\\psi_{j+h}$. Since "
        "$\\psi_j\\psi_{j+h} = \\psi_h\\,(d)_j (h+d)_j/((h+1)_j\\, j!)$ (SymPy, rising factorials), the "
        "limit t → ∞ is $\\psi_h\\,{}_2F_1(d, h+d; h+1; 1)$; Gauss's theorem (SymPy `hyperexpand`, valid "
        f"for 1 − 2d > 0) gives ${sp.latex(steps['gauss_value'])}$, so for 0 < d < 1/2 "
        + _latex(sp.Eq(sp.Symbol("gamma_h"), STATIONARY_AUTOCOVARIANCE))
        + "and, because $\\log\\frac{\\Gamma(h+d)}{\\Gamma(h+1-d)h^{2d-1}} = O(h^{-2})$ (its 1/h term "
        "cancels), $\\gamma_h \\sim "
        + sp.latex(STATIONARY_AUTOCOVARIANCE_TAIL)
        + "$: hyperbolic decay, not summable — long memory, as §II-D states, unlike the Markov RRW. "
        "For 1/2 ≤ d < 1 there is no stationary limit: $\\operatorname{Var} f_t = \\sum_{j<t}\\psi_j^2$ "
        "grows like $\\log t/\\pi$ (d = 1/2) or $t^{2d-1}/((2d-1)\\Gamma(d)^2)$ (Section 4, with N = 1).\n"
    )
    return "\n".join(out)


def _averaged_table() -> str:
    rows = [
        "Averaged bins, N = 200, σ_w² = 1 (float64, `flicker_bin_variances`); the last column is "
        "(Var_2k − Var_k) divided by its leading-order prediction, → 1:\n",
        "| d | Var_1 | Var_10 | Var_100 | Var_1000 | ratio at k = 1000 |",
        "|---|---|---|---|---|---|",
    ]
    size = 200
    for order in (0.25, 0.5, 0.75):
        values = flicker_bin_variances(order, size, 2000, "averaged")
        predicted = _averaged_doubling_prediction(order, size, 1000)
        ratio = (values[1999] - values[999]) / predicted
        rows.append(
            f"| {order} | {_float(values[0])} | {_float(values[9])} | {_float(values[99])} | "
            f"{_float(values[999])} | {ratio:.5f} |"
        )
    return "\n".join(rows) + "\n"


def _averaged_doubling_prediction(order: float, size: int, bin_number: int) -> float:
    """Leading-order Var_2k − Var_k from the expressions above."""
    if order == 0.5:
        growth = sp.lambdify(k, AVERAGED_GROWTH_AT_HALF, "math")
        return growth(2 * bin_number) - growth(bin_number)
    if order > 0.5:
        growth = sp.lambdify((d, N, k), AVERAGED_GROWTH_ABOVE_HALF, "math")
        return growth(order, size, 2 * bin_number) - growth(order, size, bin_number)
    tail = sp.lambdify((d, N, k), AVERAGED_TAIL_BELOW_HALF, "math")
    return tail(order, size, bin_number) - tail(order, size, 2 * bin_number)


def _carouselled_table() -> str:
    rows = [
        "Carouselled bins (sine + cosine gyro), N = 200, σ_w² = 1; Var_∞ is Var_2000 plus the "
        "leading tail; the last column is (Var_200 − Var_100) over its leading-order prediction:\n",
        "| d | Var_1 | Var_2 | Var_10 | Var_∞ | (Var_∞ − Var_1)/Var_∞ | ratio at k = 100 |",
        "|---|---|---|---|---|---|---|",
    ]
    size = 200
    tail = sp.lambdify((d, N, k), CAROUSELLED_TAIL, "math")
    for order in (0.25, 0.5, 0.75):
        values = flicker_bin_variances(order, size, 2000, "carouselled")
        limit = values[-1] + tail(order, size, 2000)
        ratio = (values[199] - values[99]) / (tail(order, size, 100) - tail(order, size, 200))
        rows.append(
            f"| {order} | {_float(values[0])} | {_float(values[1])} | {_float(values[9])} | "
            f"{_float(limit)} | {_float((limit - values[0]) / limit)} | {ratio:.4f} |"
        )
    rows.append(
        '\nFor d = 3/4 the carouselled limit exceeds σ_w² = 1: "significantly smaller than the driving '
        'noise variance" (§V-B) is a statement about d = 1/2, not about 1/f noise in general.'
    )
    return "\n".join(rows) + "\n"


DOCUMENT = Document(
    name="tim2014_flicker_noise",
    title="1/f noise under averaging and carouseling (TIM 2014 §III-D, §V-B)",
    build=_build,
)
