"""TIM 2014 §IV: sequences with constant Allan variance, built from Gray-code square waves."""

from __future__ import annotations

import sympy as sp

from carousel_theory.derivations import Document
from carousel_theory.graycode import (
    ALLAN_ESTIMATOR_VARIANCE,
    ALLAN_VARIANCE,
    GRAM_SCALE,
    MVUE_VARIANCE,
    PROCESS_VARIANCE,
    C_symbol,
    deterministic_sequence,
    gray_code,
    gray_matrix,
    innovation_index,
    m_symbol,
    n_symbol,
    overlapping_allan_variance_exact,
)

__all__ = ["DOCUMENT"]


def _matrix(values) -> sp.Matrix:
    return sp.Matrix(values.tolist()).applyfunc(sp.nsimplify)


def _display(expression) -> str:
    return f"$$\n{sp.latex(expression)}\n$$"


def _sequence_and_matrix() -> list[str]:
    S8 = _matrix(deterministic_sequence(3).reshape(1, -1))
    K2 = _matrix(gray_matrix(2))
    rows = ["| r | g(r) | K₁₆ₓ₄ + ½ | S₁₆[r] + 2 |", "|---|---|---|---|"]
    K4 = gray_matrix(4)
    S16 = deterministic_sequence(4)
    for r in range(16):
        bits = "".join(str(int(v + 0.5)) for v in K4[r])
        rows.append(f"| {r} | {gray_code(r):04b} | {bits} | {int(S16[r] + 2)} |")
    return [
        "## 1. Algorithm 1, the square waves and the Gray code",
        "Algorithm 1 starts from $S_2 = a_{1\\ldots2}$ and repeats $v \\leftarrow v \\otimes [1\\;1] + "
        "a_{1\\ldots2^i}$, "
        "with $a_k$ of eq. (22): $a_1 = -\\tfrac12$, $a_2 = \\tfrac12$, $a_k = -a_{k-2}$. Applying (22) "
        "twice gives "
        "$a_{k+4} = a_k$: one period is $(-\\tfrac12, \\tfrac12, \\tfrac12, -\\tfrac12)$. Unrolled, column "
        "$i$ of "
        "$K \\in \\mathbb{R}^{2^n \\times n}$ is $a_{1\\ldots2^i} \\otimes 1_{2^{n-i}}$, a square wave, and "
        "$S_{2^n} = K\\,1$ (eq. (32)). Table I (n = 3):",
        _display(sp.Eq(sp.Symbol("S_8"), S8, evaluate=False)),
        "and eq. (24) (n = 2):",
        _display(sp.Eq(sp.Symbol("K"), K2, evaluate=False)),
        "Rows $r = 0 \\ldots 2^n - 1$ (the paper's row $r + 1$): $K + \\tfrac12$ is the binary reflected "
        "Gray code "
        "$g(r) = r \\oplus \\lfloor r/2 \\rfloor$ written most significant bit first, so $S_{2^n}[r] + n/2$ "
        "is the "
        "number of ones of $g(r)$ (proof: proofs/proof_graycode_gray_code.py, induction on n). For n = 4:",
        "\n".join(rows),
        "The sample values are quantized at the $n + 1$ values $-n/2, \\ldots, n/2$ (12 values for "
        "$S_{2048}$, the sum of 11 square waves); the minimum is at $r = 0$ only and the maximum at "
        "$r = \\lfloor 2^{n+1}/3 \\rfloor$ only.",
    ]


def _allan_variance() -> list[str]:
    n = 3
    table = ["| τ = 2^m | j = 1 … 2^{n−m} − 1: index i of the innovation in ΔR̄_j |", "|---|---|"]
    for m in range(n):
        indices = ", ".join(str(innovation_index(n, m, j)) for j in range(1, 2 ** (n - m)))
        table.append(f"| {2**m} | {indices} |")
    p = sp.Symbol("p", integer=True, positive=True)
    i = sp.Symbol("i", integer=True, positive=True)
    count = sp.Sum(2 ** (i - 1), (i, 1, p))
    return [
        "## 2. Bin differences and the Allan variance",
        "Eq. (23) prints one variable $x_\\tau$ per averaging time. What holds (proof: "
        "proofs/proof_graycode_single_innovation.py): at $\\tau = 2^m$ the $j$-th difference of bin means of "
        "$R = C K x$ is $\\pm C x_i$ with $i = n - m - \\nu_2(j)$, $\\nu_2$ the exponent of 2 in $j$ — a "
        "different innovation for different $j$. For n = 3:",
        "\n".join(table),
        "Every difference is one $\\pm C x_i$, so each has variance $C^2$ and the non-overlapping Allan "
        "variance (20) has, for every $m = 0 \\ldots n-1$ and any zero-mean unit-variance $x$,",
        _display(sp.Eq(sp.Symbol(r"\mathrm{E}\,\sigma_A^2(2^m)"), ALLAN_VARIANCE, evaluate=False)),
        "so (20) without its factor ½ is unbiased for $C^2$ (the main rendering). The alternative "
        "rendering's "
        "“without the term 1/τ” would use bin sums and have expectation $\\tau^2 C^2/2$. The deterministic "
        "$S$ has $\\sigma_A^2(2^m) = \\tfrac12$ exactly. With $p = n - m$, $x_i$ enters $2^{i-1}$ of the "
        f"$2^p - 1$ differences (${sp.latex(count)} = {sp.latex(sp.simplify(count.doit()))}$), so for "
        f"Gaussian $x$",
        _display(
            sp.Eq(sp.Symbol(r"\mathrm{Var}\,2\sigma_A^2(2^m)"), ALLAN_ESTIMATOR_VARIANCE, evaluate=False)
        ),
    ]


def _covariance() -> list[str]:
    K3 = gray_matrix(3)
    lag_three = (sp.nsimplify(K3[0] @ K3[3]), sp.nsimplify(K3[1] @ K3[4]))
    return [
        "## 3. The covariance $K K^T$",
        "Entries of $K$ are $\\pm\\tfrac12$, and the Gray code is linear over GF(2), so (proof: "
        "proofs/proof_graycode_covariance.py)",
        "$$\n(K K^T)_{r,s} = \\frac{n}{4} - \\frac{\\operatorname{popcount} g(r \\oplus s)}{2} = "
        "-\\tfrac12\\, S_{2^n}[r \\oplus s].\n$$",
        "The diagonal is $n/4$: ",
        _display(sp.Eq(sp.Symbol(r"\mathrm{Var}\,R_t"), PROCESS_VARIANCE, evaluate=False)),
        "for every $t$ (variance-stationary; the variance grows with $\\log_2$ of the length). Each column "
        "is "
        "$-\\tfrac12 S$ with XOR-permuted indices, so its bin means change by exactly $\\tfrac12$ (not 1) at "
        "every $\\tau = 2^m$: the columns of $2KK^T$ follow (21). The covariance depends on $r \\oplus s$, "
        "not "
        f"on $r - s$: for n = 3, $\\operatorname{{cov}}(R_0, R_3) = {sp.latex(lag_three[0])} C^2$ but "
        f"$\\operatorname{{cov}}(R_1, R_4) = {sp.latex(lag_three[1])} C^2$, and the difference is $C^2$ for "
        f"every "
        "$n \\ge 3$ (proofs/proof_graycode_stationarity.py). The sequence is stationary only for n = 2.",
    ]


def _estimators() -> list[str]:
    ratio = sp.simplify(ALLAN_ESTIMATOR_VARIANCE / MVUE_VARIANCE)
    rows = ["| n | Var 2σ_A²(1) / C⁴ | Var Ĉ² / C⁴ | ratio |", "|---|---|---|---|"]
    for order in (2, 3, 4, 8, 11, 15, 24):
        allan = ALLAN_ESTIMATOR_VARIANCE.subs({n_symbol: order, m_symbol: 0, C_symbol: 1})
        mvue = MVUE_VARIANCE.subs({n_symbol: order, C_symbol: 1})
        rows.append(f"| {order} | {sp.nsimplify(allan)} | {mvue} | {sp.N(allan / mvue, 6)} |")
    return [
        "## 4. Pseudoinverse and the minimum-variance unbiased estimator",
        "By induction on the doubling recursion $K_n = [K_{n-1} \\otimes 1_2 \\mid a_{1\\ldots2^n}]$ "
        "(proofs/proof_graycode_gram.py):",
        f"$$\nK^T K = {sp.latex(GRAM_SCALE)}\\, I_n\n$$",
        "hence $K^+ = 2^{2-n} K^T$ for every n (eq. (31) is n = 2) and $K^+ R = C x$. With $x \\sim N(0, "
        "I_n)$ "
        "the mean of $x$ is known, so the MVUE of $C^2$ is the mean of squares $\\lVert K^+R \\rVert^2/n$ "
        "(not "
        "the sample variance about the sample mean, whose variance is $2C^4/(n-1)$):",
        _display(sp.Eq(sp.Symbol(r"\mathrm{Var}\,\hat C^2"), MVUE_VARIANCE, evaluate=False)),
        "The ratio of the Allan-based estimator's variance to it is",
        f"$$\n\\frac{{\\mathrm{{Var}}\\,2\\sigma_A^2(2^m)}}{{\\mathrm{{Var}}\\,\\hat C^2}} = "
        f"{sp.latex(ratio)}\n$$",
        "which exceeds 1 for every $n \\ge 2$ and $m$ (proofs/proof_graycode_estimators.py). At τ = 1:",
        "\n".join(rows),
    ]


def _overlapping() -> list[str]:
    rows = ["| n | E σ²_overlap(2^m) / C², m = 0 … n − 1 |", "|---|---|"]
    for order in range(2, 8):
        values = ", ".join(str(overlapping_allan_variance_exact(order, m)) for m in range(order))
        rows.append(f"| {order} | {values} |")
    return [
        "## 5. The overlapping Allan variance is not constant",
        "With every start position (windows $t = 0 \\ldots 2^n - 2\\tau$), the expected overlapping Allan "
        "variance of $R$, computed exactly from prefix sums of the square waves, is ½ only at τ = 1 (where "
        "it "
        "coincides with (20)) and at τ = 2^{n−1} (one window):",
        "\n".join(rows),
    ]


def _bounds() -> list[str]:
    return [
        "## 6. Bounds from the number of ones",
        "$G(N) = \\sum_{r<N} \\operatorname{popcount} g(r) = \\sum_{r<N} S_r + nN/2$ equals McIlroy's binary "
        "sum "
        "$B(N) = \\sum_{r<N} \\operatorname{popcount} r$ at powers of two ($G(2^k) = k 2^{k-1}$) and, "
        "checked "
        "exhaustively up to $2^{24}$ by `carousel-theory graycode`, $B(N) \\le G(N) \\le B(N) + 2N/5$. With "
        "McIlroy's $B(N) \\le \\tfrac N2 \\log_2 N$ this bounds the running sum: "
        "$\\sum_{r<N} S_r \\le \\tfrac N2(\\log_2 N - n) + \\tfrac{2N}{5}$.",
    ]


def build() -> str:
    parts = [
        "Source: TIM 2014 §IV, eq. (20)-(32), Tables I-II. Symbols: $n$ (length $2^n$), $m$ ($\\tau = 2^m$ "
        "samples), $C$ (scale of $R = C K x$, $x$ i.i.d. zero mean, unit variance). Every identity below is "
        "computed by `carousel_theory.graycode` and proved for all $n$ in `proofs/proof_graycode_*.py`.",
        *_sequence_and_matrix(),
        *_allan_variance(),
        *_covariance(),
        *_estimators(),
        *_overlapping(),
        *_bounds(),
    ]
    return "\n\n".join(parts)


DOCUMENT = Document(
    name="tim2014_constant_allan_variance",
    title="Constant Allan variance from Gray-code square waves (TIM 2014 §IV)",
    build=build,
)
