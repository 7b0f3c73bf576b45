"""Bias, white noise and rate random walk under averaging and carouseling (TIM 2014 §III-A…C):
every closed form of :mod:`carousel_theory.closed_forms` derived step by step with SymPy."""

from __future__ import annotations

import sympy as sp

from carousel_theory import closed_forms as cf
from carousel_theory.derivations import Document
from carousel_theory.symbols import N, a, alpha, b, i, k, m, p, theta, var_x, var_y, x

__all__ = ["DOCUMENT"]


def _l(expression: sp.Expr) -> str:
    return sp.latex(expression)


def _zero(expression: sp.Expr) -> str:
    """'0' when SymPy simplifies the expression to zero; the remainder otherwise (shown, never hidden)."""
    return _l(sp.simplify(expression))


def _section_bias() -> list[str]:
    omega = sp.Symbol("omega")
    geometric = omega * (omega**N - 1) / (omega - 1)
    unit_power = sp.exp(2 * sp.pi * sp.I / N) ** N  # SymPy evaluates e^{2πi} = 1 itself
    return [
        "## 1. Additive bias, eq. (8)",
        "",
        "With $\\omega = e^{2\\pi i/N}$, $\\sum_{i=1}^{N}\\omega^i = "
        + _l(geometric)
        + "$ (geometric series, "
        "valid for $\\omega \\ne 1$, i.e. N ≥ 2), and "
        f"$\\omega^N = e^{{2\\pi i}} = {_l(unit_power)}$: the sum of the N-th roots of unity is 0 "
        "for N ≥ 2, and both its imaginary part $\\sum \\sin(2\\pi i/N)$ and its real part "
        "$\\sum\\cos(2\\pi i/N)$ vanish.",
        "",
        "At N = 1 the single weight pair is $(\\sin 2\\pi, \\cos 2\\pi) = (0, 1)$: the sine residual is "
        f"${_l(cf.BIAS_SINE_RESIDUAL)}$ for every N, the cosine residual is ${_l(cf.BIAS_COSINE_RESIDUAL)}$. "
        "So a y-gyro bias survives carouseling with one sample per revolution — the paper's 'for all N > 1' "
        "is exactly the right condition.",
        "",
    ]


def _section_white() -> list[str]:
    white = cf.WHITE_CAROUSEL_VARIANCE.subs({var_x: sp.Symbol("sigma_x^2"), var_y: sp.Symbol("sigma_y^2")})
    return [
        "## 2. White noise, eq. (9)",
        "",
        "$\\sum_{i=1}^{N}\\sin^2(2\\pi i/N) = N/2 - \\tfrac12\\sum_i\\cos(4\\pi "
        "i/N)$ and the last sum is N when "
        "N divides 2, else 0 (roots of unity, §1 with ω²). Hence "
        f"$\\sum\\sin^2 = {_l(cf.SINE_SQUARES_SUM)}$ and $\\sum\\cos^2 = {_l(cf.COSINE_SQUARES_SUM)}$.",
        "",
        "For white noise of variances $\\sigma_x^2$ (x gyro) and $\\sigma_y^2$ (y gyro) the carouselled "
        "variance $(\\sigma_x^2\\sum\\sin^2 + \\sigma_y^2\\sum\\cos^2)/N^2$ is "
        f"$${_l(white)}$$",
        "With equal variances every branch is $\\sigma^2/N$ (as printed; the sum "
        "in (9) must cover both terms, "
        "$\\sin^2 + \\cos^2 = 1$), equal to direct averaging, "
        f"${_l(cf.WHITE_AVERAGE_VARIANCE)}$. With unequal variances the two differ unless N ≥ 3 and "
        "$\\sigma_x^2 = \\sigma_y^2$.",
        "",
    ]


def _section_averaging() -> list[str]:
    first = sp.summation(((N - i + 1) / N) ** 2, (i, 1, N))
    moment = sp.summation(i / N, (i, 1, N))
    lemma = cf.rrw_bin_covariance_from_weights(sp.Symbol("W"), sp.Symbol("M"), sp.Symbol("V"))
    moment, first = sp.factor(moment), sp.factor(first)
    averaged = cf.rrw_bin_covariance_from_weights(1, moment, first)
    step = sp.simplify(cf.RRW_AVERAGE_VARIANCE.subs(k, k + 1) - cf.RRW_AVERAGE_VARIANCE)
    return [
        "## 3. Rate random walk, direct averaging: eqs. (14)–(15) for every pair of bins",
        "",
        "$r_t = \\sum_{u \\le t} q_u$ (eq. (2), $r_0 = 0$), so $\\operatorname{Cov}(r_s, "
        "r_t) = \\sigma_q^2\\min(s,t)$ "
        "— the matrix $\\mathbf R\\mathbf R^T$ of eq. (10). Bin a with weights $w_1 … w_N$ is "
        "$X_a = \\sum_i w_i r_{(a-1)N+i} = W\\,r_{(a-1)N} + \\sum_i w_i L^{(a)}_i$, "
        "where $W = \\sum_i w_i$ and "
        "the local walk $L^{(a)}$ uses only the increments of bin a (independent "
        "of $r_{(a-1)N}$ and of other "
        "bins' local walks).",
        "",
        "**Step 3.1 (lemma).** For a < b, $r_{(b-1)N} = r_{(a-1)N} + L^{(a)}_N "
        "+ (\\text{later increments})$, so "
        "with $M = \\sum_i i\\,w_i$ and $V = \\sum_i(\\sum_{j\\ge i}w_j)^2 = "
        "\\mathbf w^T\\mathbf R\\mathbf R^T"
        f"\\mathbf w$: $$\\operatorname{{Cov}}(X_a, X_b)/\\sigma_q^2 = {_l(lemma)}$$",
        "",
        f"**Step 3.2 (averaging, $w_i = 1/N$).** W = 1, $M = {_l(moment)}$ (the "
        f"printed $\\frac{{1}}{{N^2}}\\sum iN$), "
        f"$V = \\sum_i ((N-i+1)/N)^2 = {_l(sp.factor(first))}$ (the printed "
        f"$\\frac{{1}}{{N^2}}\\sum i^2$). So "
        f"$$\\operatorname{{Cov}}(X_a, X_b)/\\sigma_q^2 = {_l(averaged)}$$ which "
        f"is eq. (15) for a, b ∈ {{1, 2}}: "
        f"${_l(sp.factor(averaged.subs({a: 1, b: 1})))}$, ${_l(averaged.subs({a: 1, b: 2}))}$, "
        f"${_l(sp.expand(averaged.subs({a: 2, b: 2})))}$.",
        "",
        "**Step 3.3 (every subsequent average: proof by induction).** Base k = "
        "1: $\\operatorname{Var}_1 = V$. "
        "Step: $X_{k+1} = r_{kN} + (\\text{local})$ with $\\operatorname{Var} r_{kN} = kN$, so "
        f"$\\operatorname{{Var}}_{{k+1}} - \\operatorname{{Var}}_k = {_l(step)}$ "
        "exactly, for every k ≥ 1 and N ≥ 1: "
        f"$\\operatorname{{Var}}_k = {_l(cf.RRW_AVERAGE_VARIANCE)}$. The paper's "
        "'higher by $\\sigma_q^2 N$' is "
        "exact, not approximate.",
        "",
        "**Step 3.4 (the coefficient 4/3).** $\\operatorname{Var}_k/N \\to k - 2/3$: "
        + ", ".join(
            f"bin {n}: ${_l(sp.limit(cf.RRW_AVERAGE_VARIANCE.subs(k, n) / N, N, sp.oo))}$" for n in (1, 2, 3)
        )
        + ". The 4/3 quoted after (18) is the second bin's; the first bin's is 1/3.",
        "",
    ]


def _section_carousel() -> list[str]:
    geometric = cf.geometric_partial_sum(m)
    sine_partial = cf.sine_partial_sum()
    cosine_partial = cf.cosine_partial_sum()
    sine_check = sp.simplify((sp.im(sp.expand_complex(geometric)) - sine_partial).rewrite(sp.exp))
    cosine_check = sp.simplify((sp.re(sp.expand_complex(geometric)) - cosine_partial).rewrite(sp.exp))
    induction_sine = sp.simplify(
        (cf.sine_partial_sum(m + 1) - sine_partial - sp.sin((m + 1) * theta)).rewrite(sp.exp)
    )
    induction_cosine = sp.simplify(
        (cf.cosine_partial_sum(m + 1) - cosine_partial - sp.cos((m + 1) * theta)).rewrite(sp.exp)
    )
    derived = cf.derive_rrw_carousel_quadratic_forms()
    half = sp.pi / N
    sine_tail = (sp.cos(half) - sp.cos(alpha)) / (2 * sp.sin(half))
    cosine_tail = (sp.sin(alpha) - sp.sin(half)) / (2 * sp.sin(half))
    ratio = sp.Symbol("z")  # z = e^{2πip/N}
    period = sp.exp(sp.I * p * sp.pi / N) * (ratio**N - 1) / (ratio - 1)
    full_turn = sp.exp(2 * sp.pi * sp.I * p)  # SymPy: 1 for an integer p
    lines = [
        "## 4. Rate random walk, carouselled: eqs. (16)–(18), exact for every N and every bin",
        "",
        "**Step 4.1 (uncorrelated bins, equal variances).** For the sine weights W = Σ s_i = 0 for every N "
        "(§1; N = 1 included), for the cosine weights for N ≥ 2. The lemma of Step 3.1 with W = 0 gives "
        f"$${_l(cf.rrw_bin_covariance_from_weights(0, sp.Symbol('M'), sp.Symbol('V')))}$$ "
        "— zero for a ≠ b and "
        "the same V in every bin, for every number of bins k (this is the omitted 'rigorous proof' for "
        "$R_3, …$). At N = 1 the cosine weight is 1, nothing is carouselled and "
        f"$\\operatorname{{Cov}}(X_a, X_b) = {_l(cf.RRW_CAROUSEL_COVARIANCE.subs(N, 1))}$.",
        "",
        "**Step 4.2 (partial sums from a geometric series).** With θ = 2π/N, "
        f"$\\sum_{{j=1}}^m e^{{ij\\theta}} = {_l(geometric)}$. Its imaginary and real parts are "
        f"$$S_m = {_l(sine_partial)},\\qquad C_m = {_l(cosine_partial)}$$ (SymPy: "
        "the differences simplify to "
        f"${_l(sine_check)}$ and ${_l(cosine_check)}$). Induction as a second way: $S_0 = C_0 = 0$, and "
        f"$S_{{m+1}} - S_m - \\sin((m+1)\\theta)$ → ${_l(induction_sine)}$, "
        f"$C_{{m+1}} - C_m - \\cos((m+1)\\theta)$ → ${_l(induction_cosine)}$.",
        "",
        "**Step 4.3 (tails).** $S_N = 0$ and, for N ≥ 2, $C_N = 0$ (§1), so "
        "$(\\mathbf R^T\\mathbf s)_i = \\frac1N\\sum_{j\\ge i}\\sin(j\\theta) = -S_{i-1}/N$ and "
        "$(\\mathbf R^T\\mathbf c)_i = -C_{i-1}/N$. With $\\alpha_m = (2m+1)\\pi/N$, "
        f"$S_m = {_l(sine_tail)}$ and $C_m = {_l(cosine_tail)}$.",
        "",
        "**Step 4.4 (sums over a period).** For an integer p and $z = e^{2\\pi ip/N}$, "
        f"$\\sum_{{m=0}}^{{N-1}} e^{{ip\\alpha_m}} = {_l(period)}$ with "
        f"$z^N = e^{{2\\pi ip}} = {_l(full_turn)}$; the denominator vanishes only when N divides p. "
        "So for a trigonometric polynomial of degree < N in α only the constant Fourier coefficient "
        "survives: the sum is N times it. "
        "$S_m^2$, $C_m^2$, $S_mC_m$ have degree 2, so this holds for N ≥ 3.",
        "",
        "**Step 4.5 (the quadratic forms, N ≥ 3).** $\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf s = "
        "\\frac{1}{N^2}\\sum_{m=0}^{N-1}S_m^2$ etc.; Step 4.4 gives",
        "",
        f"- $\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf s = {_l(derived['sine'])} = "
        f"{_l(cf.RRW_CAROUSEL_SINE_GENERIC)}$ (difference "
        f"${_zero(derived['sine'] - cf.RRW_CAROUSEL_SINE_GENERIC)}$)",
        f"- $\\mathbf c^T\\mathbf R\\mathbf R^T\\mathbf c = {_l(derived['cosine'])} = "
        f"{_l(cf.RRW_CAROUSEL_COSINE_GENERIC)}$ (difference "
        f"${_zero(derived['cosine'] - cf.RRW_CAROUSEL_COSINE_GENERIC)}$)",
        f"- sum: ${_l(cf.RRW_CAROUSEL_TOTAL_GENERIC)}$ (difference "
        f"${_zero(derived['sine'] + derived['cosine'] - cf.RRW_CAROUSEL_TOTAL_GENERIC)}$)",
        f"- cross term $\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf c = {_l(derived['cross'])} = "
        f"{_l(cf.RRW_CAROUSEL_CROSS_GENERIC)}$ (difference "
        f"${_zero(derived['cross'] - cf.RRW_CAROUSEL_CROSS_GENERIC)}$)",
        "",
        "For N ≤ 2 the sine weights vanish ($\\sin\\pi = \\sin 2\\pi = 0$) and "
        "$\\mathbf c = (1)$ or $(-\\tfrac12, \\tfrac12)$; all N together:",
        "",
        f"$$\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf s = {_l(cf.RRW_CAROUSEL_SINE_VARIANCE)}$$",
        f"$$\\mathbf c^T\\mathbf R\\mathbf R^T\\mathbf c = {_l(cf.RRW_CAROUSEL_COSINE_VARIANCE)}$$",
        f"$$\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf c = {_l(cf.RRW_CAROUSEL_CROSS)}$$",
        "",
        "**Step 4.6 (expansions in 1/N).** From $\\csc^2 x = x^{-2} + \\tfrac13 + \\tfrac{x^2}{15} + …$ and "
        "$\\cot x = x^{-1} - \\tfrac{x}{3} - …$:",
        "",
    ]
    for label, expression in (
        ("\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf s", cf.RRW_CAROUSEL_SINE_GENERIC),
        ("\\mathbf c^T\\mathbf R\\mathbf R^T\\mathbf c", cf.RRW_CAROUSEL_COSINE_GENERIC),
        ("\\text{sum}", cf.RRW_CAROUSEL_TOTAL_GENERIC),
        ("\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf c", cf.RRW_CAROUSEL_CROSS_GENERIC),
    ):
        expansion = cf.expansion_in_inverse_N(expression, order=6)
        lines.append(f"- ${label} = {_l(expansion)} + O(N^{{-6}})$")
    lines += [
        "",
        "The leading terms are the paper's $3N/8\\pi^2$, $N/8\\pi^2$ and $N/2\\pi^2$; the next ones are "
        "$-1/(8N)$, $+7/(24N)$, $+1/(6N)$. The cross term tends to $-1/(4\\pi)$.",
        "",
        "**Step 4.7 (correlated gyros).** If the two gyros' increments at equal times have correlation ρ, "
        "$\\operatorname{Var}(-\\mathbf s^T\\mathbf R\\mathbf q_x + \\mathbf c^T\\mathbf R\\mathbf q_y) = "
        "\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf s + \\mathbf c^T\\mathbf R\\mathbf R^T\\mathbf c - "
        "2\\rho\\,\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf c$:",
        f"$$\\operatorname{{Var}} = {_l(cf.RRW_CAROUSEL_VARIANCE_CORRELATED)}$$",
        "which is $N/(2\\pi^2) + \\rho/(2\\pi) + O(1/N)$: positive correlation raises the variance by at "
        "most $1/(2\\pi)\\,\\sigma_q^2$; the bins stay uncorrelated (Step 4.1 holds term by term).",
        "",
    ]
    return lines


def _section_integrals() -> list[str]:
    lines = ["## 5. The integrals behind eq. (18)", ""]
    lines.append(
        "$\\mathbf s^T\\mathbf R\\mathbf R^T\\mathbf s = \\sum_{i=1}^N\\big(\\frac1N\\sum_{j=i}^N "
        "\\sin\\frac{2\\pi j}{N}\\big)^2$ — the printed inner summand $\\sin\\frac{2\\pi k}{N}$ must read "
        "$\\sin\\frac{2\\pi j}{N}$ (erratum). The rectangle rule with x = i/N, y = j/N gives "
        "$N\\int_0^1(\\int_x^1 \\sin 2\\pi y\\,dy)^2dx$."
    )
    lines.append("")
    for weight in ("sine", "cosine"):
        lines.append(f"**{weight.capitalize()} weights.**")
        lines.append("")
        for label, expression in cf.rectangle_rule_steps(weight):
            lines.append(f"- {label}: ${_l(expression)}$")
        lines.append("")
    printed = sp.simplify(N / (2 * sp.pi) * sp.integrate((sp.cos(2 * sp.pi * x) - 1) ** 2, (x, 0, 1)))
    lines += [
        "The printed third line of (18), $\\frac{N}{2\\pi}\\int_0^1(\\cos 2\\pi x - 1)^2dx$, has the wrong "
        f"factor: it equals ${_l(printed)}$, not $3N/(8\\pi^2)$. The square of "
        "$(\\cos 2\\pi x - 1)/(2\\pi)$ brings $1/(4\\pi^2)$ (erratum); the printed "
        "final value $3N/(8\\pi^2)$ "
        "is right. The rectangle rule is only the leading term: §4 gives the exact value "
        f"${_l(cf.RRW_CAROUSEL_SINE_GENERIC)}$.",
        "",
    ]
    return lines


def _section_table() -> list[str]:
    lines = [
        "## 6. Values",
        "",
        "| N | sᵀRRᵀs | cᵀRRᵀc | sum (exact) | sum (20 digits) | N/(2π²) | sᵀRRᵀc |",
        "|---|---|---|---|---|---|---|",
    ]
    for n in (2, 3, 4, 6, 8, 12, 200):
        sine = sp.radsimp(sp.simplify(cf.RRW_CAROUSEL_SINE_VARIANCE.subs(N, n)))
        cosine = sp.radsimp(sp.simplify(cf.RRW_CAROUSEL_COSINE_VARIANCE.subs(N, n)))
        total = cf.RRW_CAROUSEL_VARIANCE.subs(N, n)
        total = sp.radsimp(sp.simplify(total)) if n <= 12 else total
        cross = cf.RRW_CAROUSEL_CROSS.subs(N, n)
        cells = [
            str(n),
            f"${_l(sine)}$" if n <= 12 else "—",
            f"${_l(cosine)}$" if n <= 12 else "—",
            f"${_l(total)}$",
            str(sp.N(total, 20)),
            str(sp.N(sp.Rational(n) / (2 * sp.pi**2), 20)),
            str(sp.N(cross, 20)),
        ]
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    return lines


def build() -> str:
    sections = [
        "Unit driving variances (σ_q² = σ_WN² = 1); bins of N samples numbered from 1; carouseling weights "
        "$s_i = \\sin(2\\pi i/N)/N$, $c_i = \\cos(2\\pi i/N)/N$ (eq. (13)); estimate "
        "$-\\sum s_i\\omega_x + \\sum c_i\\omega_y$ (eq. (6)). Every closed form below is the one in "
        "`carousel_theory.closed_forms` (registry: `carousel-theory formula --list`).",
        "",
        *_section_bias(),
        *_section_white(),
        *_section_averaging(),
        *_section_carousel(),
        *_section_integrals(),
        *_section_table(),
    ]
    return "\n".join(sections)


DOCUMENT = Document(
    "tim2014_averaging_and_carouseling",
    "Bias, white noise and rate random walk under averaging and carouseling (TIM 2014 §III-A–C)",
    build,
)
