"""Derivation document: the exact Allan variance of each discrete noise process of TIM 2014 §II (white,
rate random walk, quantization, 1/f by fractional integration), the degrees of freedom of the white-noise
estimator, the continuous-time conventions they reduce to, and the covariance of the estimates across τ
in closed form (:mod:`carousel_theory.tau_covariance`)."""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from carousel_theory import allan, symbols, tau_covariance
from carousel_theory.derivations import Document

_m = symbols.cluster_size
_i = sp.Symbol("i", integer=True, positive=True)
_K = sp.Symbol("K", integer=True, positive=True)
_white = symbols.white_sample_variance
_rrw = symbols.rrw_increment_variance
_Q = symbols.quantization_step
_dt = symbols.sample_interval
_tau = sp.Symbol("tau", positive=True)
_N = sp.Symbol("N", positive=True)
_Kc = sp.Symbol("K", positive=True)  # continuous RRW density (not the count _K)


def _math(expression: sp.Basic) -> str:
    return f"$${sp.latex(expression)}$$"


def _section_white() -> list[str]:
    # D = ȳ_{j+1} − ȳ_j has weights −1/m on the first bin and +1/m on the second.
    variance = sp.summation((sp.Rational(1) / _m) ** 2, (_i, 1, 2 * _m)) * _white
    avar = sp.simplify(variance / 2)
    assert sp.simplify(avar - allan.WHITE_ALLAN_VARIANCE) == 0
    continuous = sp.simplify(avar.subs(_white, _N**2 / _dt).subs(_m, _tau / _dt))
    assert sp.simplify(continuous - _N**2 / _tau) == 0
    return [
        "## 1. White noise",
        "",
        "The difference of adjacent bin means of $m$ samples, $D_j = \\bar y_{j+1} - \\bar y_j$, has weights "
        "$-1/m$ on the first bin and $+1/m$ on the second, so for white noise of per-sample variance "
        "$\\sigma_{WN}^2$",
        "",
        f"$$\\operatorname{{Var}} D = {sp.latex(sp.simplify(variance))}$$",
        "",
        "and, with TIM 2014 eq. (20) the half mean square of $D$,",
        "",
        _math(sp.Eq(sp.Symbol("sigma_A^2"), avar)),
        "",
        "exactly, for every $m \\ge 1$ (this is `allan.WHITE_ALLAN_VARIANCE`). With $\\tau = m\\Delta t$ "
        "and the angle random walk $N^2 = \\sigma_{WN}^2 \\Delta t$ it is $N^2/\\tau$: the continuous "
        "form holds exactly at every whole number of samples.",
        "",
    ]


def _section_rrw() -> list[str]:
    # r_t = Σ_{k≤t} q_k: q_i enters the first bin mean with weight (m − i + 1)/m (i ≤ m) and the
    # second with weight 1 (i ≤ m) or (2m − i + 1)/m (m < i ≤ 2m); the start value r_0 cancels in D.
    first = sp.summation(((_i - 1) / _m) ** 2, (_i, 1, _m))
    second = sp.summation(((2 * _m - _i + 1) / _m) ** 2, (_i, _m + 1, 2 * _m))
    variance = sp.factor(sp.simplify(first + second))
    avar = sp.factor(sp.simplify(_rrw * variance / 2))
    assert sp.simplify(avar - allan.RRW_ALLAN_VARIANCE) == 0
    # Brute force: exact covariance min(s, t) of the walk for small m.
    for size in range(1, 7):
        weights = [Fraction(-1, size)] * size + [Fraction(1, size)] * size
        exact = sum(
            (weights[s] * weights[t] * (min(s, t) + 1) for s in range(2 * size) for t in range(2 * size)),
            Fraction(0),
        )
        assert sp.Rational(exact.numerator, exact.denominator) == variance.subs(_m, size)
    continuous = sp.expand(avar.subs(_rrw, _Kc**2 * _dt).subs(_m, _tau / _dt))
    assert sp.simplify(continuous - (_Kc**2 * _tau / 3 + _Kc**2 * _dt**2 / (6 * _tau))) == 0
    return [
        "## 2. Rate random walk (TIM 2014 eq. (2))",
        "",
        "With $r_t = \\sum_{k \\le t} q_k$, the increment $q_i$ enters $D_j$ (bins $1..m$ and $m+1..2m$) "
        "with weight $(i-1)/m$ for $i \\le m$ and $(2m-i+1)/m$ for $m < i \\le 2m$; the walk's value "
        "before the first bin cancels. Summing the squares:",
        "",
        f"$$\\operatorname{{Var}} D / \\sigma_q^2 = {sp.latex(variance)}$$",
        "",
        "(checked against the exact covariance $\\min(s,t)$ for $m = 1..6$ in rationals), hence",
        "",
        _math(sp.Eq(sp.Symbol("sigma_A^2"), avar)),
        "",
        "exactly (`allan.RRW_ALLAN_VARIANCE`). With $\\sigma_q^2 = K^2\\Delta t$ (TIM 2014 Table III's "
        "$\\sigma_q^2$ in (rad/s)²/s is $K^2$) and $\\tau = m\\Delta t$:",
        "",
        _math(sp.Eq(sp.Symbol("sigma_A^2"), continuous)),
        "",
        "the familiar $K^2\\tau/3$ plus a discrete correction $K^2\\Delta t^2/(6\\tau)$, a fraction "
        "$1/(2m^2)$ of the first term: below 1 % once $m \\ge 8$.",
        "",
    ]


def _section_quantization() -> list[str]:
    # Rate y_t = (e_t − e_{t−1})/Δt with white angle error e of variance Q²: a bin mean telescopes.
    variance = (1 + 4 + 1) * _Q**2 / (_m * _dt) ** 2
    avar = sp.simplify(variance / 2)
    assert sp.simplify(avar - allan.QUANTIZATION_ALLAN_VARIANCE) == 0
    return [
        "## 3. Quantization",
        "",
        "A white angle error $e_t$ of variance $Q^2$ differenced into the rate, "
        "$y_t = (e_t - e_{t-1})/\\Delta t$, makes each bin mean telescope to "
        "$(e_{\\text{end}} - e_{\\text{start}})/(m\\Delta t)$, so "
        "$D = (e_{2m} - 2e_m + e_0)/(m\\Delta t)$ and",
        "",
        _math(sp.Eq(sp.Symbol("sigma_A^2"), avar)),
        "",
        "which is IEEE Std 952's $3Q^2/\\tau^2$ exactly at $\\tau = m\\Delta t$.",
        "",
    ]


def _flicker_exact(d: Fraction, length: int, m: int) -> Fraction:
    """E σ̂_A² of eq. (3) noise (σ_w² = 1), non-overlapping, record of ``length``: dense exact sums."""
    psi = [Fraction(1)]
    for j in range(1, length):
        psi.append(psi[-1] * (j - 1 + d) / j)
    bins = length // m
    total = Fraction(0)
    for j in range(bins - 1):
        weights = [Fraction(0)] * length
        for t in range(j * m, (j + 1) * m):
            weights[t] -= Fraction(1, m)
        for t in range((j + 1) * m, (j + 2) * m):
            weights[t] += Fraction(1, m)
        # Coefficient of w_i: Σ_{t ≥ i} weights_t ψ_{t−i}.
        total += sum(
            (
                sum((weights[t] * psi[t - i] for t in range(i, length)), Fraction(0)) ** 2
                for i in range(length)
            ),
            Fraction(0),
        )
    return total / (2 * (bins - 1))


def _section_flicker() -> list[str]:
    d = Fraction(1, 2)
    length = 12
    rows = []
    for m in (1, 2, 4):
        exact = _flicker_exact(d, length, m)
        numeric = allan.flicker_allan_variance(float(d), [m], length)[0]
        assert abs(float(exact) - numeric) <= 1e-13 * float(exact)
        rows.append(
            f"| {m} | ${sp.latex(sp.Rational(exact.numerator, exact.denominator))}$ | {float(exact):.15g} |"
        )
    return [
        "## 4. 1/f noise by fractional integration (TIM 2014 eq. (3))",
        "",
        "$f_t = \\sum_{i=1}^{t} \\psi_{t-i} w_i$ starts at $t = 1$, so it is not stationary and its Allan "
        "variance depends on where the bins sit. With $\\Psi_u = \\sum_{k \\le u} \\psi_k$ ($\\Psi_u = 0$ "
        "for $u < 0$), the coefficient of $w_i$ in the difference of the sums of bins $j$ and $j+1$ is "
        "$G(u) = \\Psi_u - 2\\Psi_{u-m} + \\Psi_{u-2m}$ with $u = (j+1)m - i$, so",
        "",
        "$$\\operatorname{Var} D_j = \\frac{\\sigma_w^2}{m^2} \\sum_{u=0}^{(j+1)m-1} G(u)^2,$$",
        "",
        "and the expected estimate of eq. (20) is the mean of these over $j = 1 \\dots M-1$ (for the "
        "overlapping estimator, over every start). One cumulative sum of $G^2$ gives all $j$ at once: "
        "$O(n)$ per τ for any $0 < d < 1$ (`allan.flicker_allan_variance`). There is no closed form in $m$; "
        f"for $d = 1/2$ and a record of {length} samples the exact rational values (dense sums over the "
        "covariance, in fractions) agree with the $O(n)$ evaluation to $10^{-13}$:",
        "",
        "| m | exact $E\\,\\hat\\sigma_A^2 / \\sigma_w^2$ | decimal |",
        "|---|---|---|",
        *rows,
        "",
    ]


def _section_degrees_of_freedom() -> list[str]:
    # Non-overlapping white: Var D = 2σ²/m², adjacent D correlate −σ²/m², others 0.
    variance = 2 * _K * (2 / _m**2) ** 2 + 2 * 2 * (_K - 1) * (1 / _m**2) ** 2  # 2 Σ_{s,r} cov²
    mean = _K * 2 / _m**2
    degrees = sp.factor(sp.simplify(2 * mean**2 / variance))
    assert sp.simplify(degrees - 2 * _K**2 / (3 * _K - 1)) == 0
    return [
        "## 5. Degrees of freedom of the white-noise estimator",
        "",
        "The $K = M - 1$ differences of eq. (20) are Gaussian with $\\operatorname{Var} D = 2\\sigma^2/m$ "
        "(in bin means) and adjacent ones correlated $-1/2$. The quadratic form $\\sum D_j^2$ has mean "
        "$K\\operatorname{Var}D$ and variance $2\\sum_{s,r}\\operatorname{cov}(D_s,D_r)^2$, so its "
        "equivalent degrees of freedom $2E^2/\\operatorname{Var}$ are",
        "",
        _math(sp.Eq(sp.Symbol("nu"), degrees)),
        "",
        "about $2K/3$, not $K$: the χ² interval of a non-overlapping Allan variance with $K$ differences "
        "is wider than $K$ degrees of freedom suggest. `allan.equivalent_degrees_of_freedom` evaluates the "
        "same formula for any mix of white, rate random walk, quantization and 1/f noise, for both "
        "estimators.",
        "",
    ]


_delta = sp.Symbol("delta", integer=True, nonnegative=True)


def _exact_pair_sum(m_i: int, m_j: int, length: int) -> int:
    """Σ_s Σ_r cov(d_{i,s}, d_{j,r})² for unit white noise (overlapping), by brute force in integers."""
    total = 0
    for s in range(length - 2 * m_i + 1):
        first = [(s + k, -1 if k < m_i else 1) for k in range(2 * m_i)]
        for r in range(length - 2 * m_j + 1):
            weights = {r + k: (-1 if k < m_j else 1) for k in range(2 * m_j)}
            total += sum(w * weights.get(t, 0) for t, w in first) ** 2
    return total


def _section_tau_covariance() -> list[str]:
    # Overlapping estimator, white noise, one τ: c(δ) = 2m − 3δ (0 ≤ δ ≤ m), δ − 2m (m ≤ δ < 2m), and
    # K − δ pairs of starts at offset ±δ (K = n − 2m + 1 ≥ 2m).
    c_near, c_far = 2 * _m - 3 * _delta, _delta - 2 * _m
    pair_sum = _K * (2 * _m) ** 2 + 2 * (
        sp.summation((_K - _delta) * c_near**2, (_delta, 1, _m))
        + sp.summation((_K - _delta) * c_far**2, (_delta, _m + 1, 2 * _m - 1))
    )
    pair_sum = sp.expand(pair_sum)
    variance = sp.factor(2 * pair_sum / (4 * _m**4 * _K**2))
    assert sp.simplify(variance * _white**2 - tau_covariance.WHITE_OVERLAPPING_ESTIMATE_VARIANCE) == 0
    rows = []
    for m, length in ((1, 5), (2, 9), (3, 14), (5, 40), (8, 60)):
        K = length - 2 * m + 1
        engine = tau_covariance._finite_gram(m, m, K, K)[0]
        assert engine == int(pair_sum.subs({_m: m, _K: K})) == _exact_pair_sum(m, m, length)
        rows.append(f"| {m} | {length} | {engine} |")
    cross = []
    for m_i, m_j, length in ((1, 2, 12), (2, 4, 20), (1, 4, 17), (3, 5, 23)):
        K_i, K_j = length - 2 * m_i + 1, length - 2 * m_j + 1
        engine = tau_covariance._finite_gram(m_i, m_j, K_i, K_j)[0]
        assert engine == _exact_pair_sum(m_i, m_j, length)
        cross.append(f"| {m_i} | {m_j} | {length} | {engine} |")
    return [
        "## 6. Covariance of the estimates across τ, without sums over the record",
        "",
        "Each overlapping estimate is $\\hat\\sigma^2(m) = \\sum_{s<K} d_s^2/(2m^2K)$, $K = n - 2m + 1$, "
        "with $d_s$ the difference of adjacent window sums. For Gaussian noise "
        "$\\operatorname{Cov}(\\hat\\sigma^2_i, \\hat\\sigma^2_j) = \\sum_\\delta N_{ij}(\\delta)\\, "
        "c_{ij}(\\delta)^2 / (2m_i^2m_j^2K_iK_j)$, with $c_{ij}(\\delta)$ the covariance of differences "
        "$\\delta$ samples apart and $N_{ij}(\\delta)$ the number of such pairs. For one τ and white noise "
        "of unit variance, $c(\\delta) = 2m - 3\\delta$ for $0 \\le \\delta \\le m$, $\\delta - 2m$ for "
        "$m \\le \\delta < 2m$, 0 beyond, and $N = K - |\\delta|$; summed in SymPy,",
        "",
        _math(sp.Eq(sp.Symbol("Sigma"), sp.factor(pair_sum))),
        "",
        "so that, for $n \\ge 4m - 1$,",
        "",
        _math(sp.Eq(sp.Symbol("Var") * sp.Symbol("sigma_A^2"), variance * _white**2)),
        "",
        "(`tau_covariance.WHITE_OVERLAPPING_ESTIMATE_VARIANCE`), a polynomial in $m$ and $K$: its cost "
        "does not depend on the record length. For any pair of τ "
        "and any mix of white noise, rate random walk and quantization, "
        "`carousel_theory.tau_covariance` writes $c_{ij}$ as a sum of nine ramps of degree 1 (white), 3 "
        "(rate random walk) or spikes (quantization), from the generating function "
        "$x^{2-2m_i}(1-x^{m_i})^2(1-x^{m_j})^2/(1-x)^4$ of the triangle correlation, and sums "
        "$N_{ij}c_{ij}^2$ exactly, piece by piece, by the Newton series "
        "$\\sum_{t<L}P(t) = \\sum_k \\Delta^kP(0)\\binom{L}{k+1}$ in integers. The table checks it against "
        "the polynomial above and a brute-force double sum over all pairs of differences (exact integers):",
        "",
        "| m | n | Σ N c² (closed form = brute force) |",
        "|---|---|---|",
        *rows,
        "",
        "and across τ (white noise, brute force over all pairs of differences):",
        "",
        "| m_i | m_j | n | Σ N c² |",
        "|---|---|---|---|",
        *cross,
        "",
        "For 1/f and autoregressive noise $c_{ij}$ has no finite support; it is the finite sum "
        "$\\sum_u W_{ij}(u)\\gamma_z(\\delta + u)$ over the $2m_i + 2m_j - 3$ lags of the triangle "
        "correlation $W_{ij}$, with $\\gamma_z$ the autocovariance of the increments, summed over a window "
        "of δ; the 1/f tail beyond the window is bounded (module text of `tau_covariance`).",
        "",
    ]


def _build() -> str:
    lines = [
        "Exact Allan variances of the discrete processes of TIM 2014 §II, for $m$ samples per bin "
        "($\\tau = m\\Delta t$), as used by `carousel_theory.allan.model_allan_variance`; each SymPy result "
        "is asserted equal to the expression stored in `carousel_theory.allan`.",
        "",
    ]
    for section in (
        _section_white,
        _section_rrw,
        _section_quantization,
        _section_flicker,
        _section_degrees_of_freedom,
        _section_tau_covariance,
    ):
        lines += section()
    return "\n".join(lines)


DOCUMENT = Document(
    name="allan_variance_models",
    title="Exact Allan variance of the discrete noise models",
    build=_build,
)
