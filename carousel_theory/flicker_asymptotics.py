"""Closed forms of 1/f noise under averaging and carouseling (TIM 2014 eq. (3), (19), §III-D, §V-B):
the fractional coefficients and their partial sums, the stationary autocovariance, and the
asymptotic laws of the averaged and carouselled bin variances in the bin number k.

Each law is a SymPy expression defined here, once; the derivation document
:mod:`carousel_theory.derivations.tim2014_flicker_noise`, the claims and the proofs evaluate them
from here.
"""

from __future__ import annotations

import sympy as sp

from carousel_theory.symbols import N, d, k

__all__ = [
    "AVERAGED_GROWTH_ABOVE_HALF",
    "AVERAGED_GROWTH_AT_HALF",
    "AVERAGED_INCREMENT",
    "AVERAGED_LOG_LOWER_BOUND",
    "AVERAGED_LOG_UPPER_BOUND",
    "AVERAGED_TAIL_BELOW_HALF",
    "CAROUSELLED_TAIL",
    "CAROUSELLED_TAIL_BOUND_HALF",
    "STATIONARY_AUTOCOVARIANCE",
    "STATIONARY_AUTOCOVARIANCE_TAIL",
    "cumulative_coefficient",
    "fractional_coefficient",
    "limit_19_log_series",
    "log_growth_envelopes",
    "stationary_autocovariance_derivation",
]

_j = sp.Symbol("j", integer=True, positive=True)
_i = sp.Symbol("i", positive=True)


def fractional_coefficient(index: sp.Expr) -> sp.Expr:
    """ψ_index = Γ(index + d) / (Γ(index + 1) Γ(d)), TIM 2014 eq. (3)."""
    return sp.gamma(index + d) / (sp.gamma(index + 1) * sp.gamma(d))


def cumulative_coefficient(index: sp.Expr) -> sp.Expr:
    """Ψ_index = ψ_0 + … + ψ_index = Γ(index + 1 + d) / (Γ(index + 1) Γ(d + 1)) (Step 1.2: induction)."""
    return sp.gamma(index + 1 + d) / (sp.gamma(index + 1) * sp.gamma(d + 1))


_lag = sp.Symbol("h", integer=True, nonnegative=True)

#: lim_{t→∞} cov(f_t, f_{t+h}) = Σ_{j≥0} ψ_j ψ_{j+h} for 0 < d < 1/2 (Gauss's summation, Section 7).
STATIONARY_AUTOCOVARIANCE = (
    sp.gamma(1 - 2 * d) * sp.gamma(_lag + d) / (sp.gamma(d) * sp.gamma(1 - d) * sp.gamma(_lag + 1 - d))
)
#: Leading term of the stationary autocovariance as h → ∞: C h^{2d−1}, not summable for d > 0.
STATIONARY_AUTOCOVARIANCE_TAIL = sp.gamma(1 - 2 * d) / (sp.gamma(d) * sp.gamma(1 - d)) * _lag ** (2 * d - 1)

#: Leading term of Var_k − Var_{k−1} of the averaged bins as k → ∞ (fixed N, 0 < d < 1).
AVERAGED_INCREMENT = N ** (2 * d - 1) * k ** (2 * d - 2) / sp.gamma(d) ** 2
#: Leading term of Var_k of the averaged bins for 1/2 < d < 1 (Var_k = this + C(N, d) + o(1)).
AVERAGED_GROWTH_ABOVE_HALF = N ** (2 * d - 1) * k ** (2 * d - 1) / ((2 * d - 1) * sp.gamma(d) ** 2)
#: Bounds on Var_k − Var_2 of the averaged bins at d = 1/2, valid for every N ≥ 1, k ≥ 2 (Section 4,
#: proofs/proof_flicker_averaged_log_growth.py).
AVERAGED_LOG_LOWER_BOUND = sp.log((k * N + sp.Rational(1, 2)) / (2 * N + sp.Rational(1, 2))) / sp.pi
AVERAGED_LOG_UPPER_BOUND = sp.log(k - 1) / sp.pi
#: Leading term of Var_k of the averaged bins at d = 1/2 (Var_k = log(k)/π + C(N) + o(1)).
AVERAGED_GROWTH_AT_HALF = sp.log(k) / sp.pi
#: Leading term of Var_∞ − Var_k of the averaged bins for 0 < d < 1/2 (the variance converges).
AVERAGED_TAIL_BELOW_HALF = N ** (2 * d - 1) * k ** (2 * d - 1) / ((1 - 2 * d) * sp.gamma(d) ** 2)
#: Rigorous bound on Var_∞ − Var_k of the carouselled bins at d = 1/2, N ≥ 2, k ≥ 2
#: (proofs/proof_flicker_carouselled_convergence.py).
CAROUSELLED_TAIL_BOUND_HALF = (N - 1) ** 2 / (8 * sp.pi * N**4 * sp.sin(sp.pi / N) ** 2 * (k - 1) ** 2)
#: Leading term of Var_∞ − Var_k of the carouselled bins (sine + cosine gyro), N ≥ 2, 0 < d < 1.
CAROUSELLED_TAIL = (
    (1 - d) ** 2 * (k * N) ** (2 * d - 3) / (4 * sp.sin(sp.pi / N) ** 2 * (3 - 2 * d) * sp.gamma(d) ** 2)
)


def limit_19_log_series() -> sp.Expr:
    """log(Γ(i + d) / (i^d Γ(i))) expanded at i = ∞ to O(i⁻²) (Stirling series, by SymPy)."""
    series = sp.series(sp.loggamma(_i + d) - sp.loggamma(_i) - d * sp.log(_i), _i, sp.oo, n=2)
    return sp.simplify(series.removeO())


def log_growth_envelopes() -> tuple[sp.Expr, sp.Expr]:
    """At d = 1/2: a_j/a_{j−1} − 1 and b_j/b_{j−1} − 1 for a_j = j ψ_j², b_j = (j + 1/2) ψ_j².

    SymPy reduces them to 1/(4j(j − 1)) > 0 and −1/(4j²) < 0: a increases and b decreases to 1/π,
    so 1/(π(j + 1/2)) < ψ_j² < 1/(πj) for j ≥ 1.
    """
    half = sp.Rational(1, 2)
    ratio = sp.gammasimp(fractional_coefficient(_j) / fractional_coefficient(_j - 1)).subs(d, half)
    increasing = sp.factor(sp.simplify(_j / (_j - 1) * ratio**2 - 1))
    decreasing = sp.factor(sp.simplify((_j + half) / (_j - half) * ratio**2 - 1))
    return increasing, decreasing


def stationary_autocovariance_derivation() -> dict[str, sp.Expr]:
    """The steps behind :data:`STATIONARY_AUTOCOVARIANCE`, each a SymPy expression that must vanish.

    ψ_j ψ_{j+h} = ψ_h · (d)_j (h+d)_j / ((h+1)_j j!) (term of ₂F₁(d, h+d; h+1; 1)); Gauss's theorem
    (SymPy ``hyperexpand``) sums the series for c − a − b = 1 − 2d > 0; and the log of
    Γ(h+d)/(Γ(h+1−d) h^{2d−1}) tends to 0 (Stirling series).
    """
    j = sp.Symbol("j", integer=True, nonnegative=True)
    term = fractional_coefficient(j) * fractional_coefficient(j + _lag) / fractional_coefficient(_lag)
    hypergeometric_term = sp.rf(d, j) * sp.rf(_lag + d, j) / (sp.rf(_lag + 1, j) * sp.factorial(j))
    gauss = sp.hyperexpand(sp.hyper([d, _lag + d], [_lag + 1], 1))
    tail = sp.series(
        sp.loggamma(_lag + d) - sp.loggamma(_lag + 1 - d) - (2 * d - 1) * sp.log(_lag), _lag, sp.oo, n=2
    ).removeO()
    return {
        "term": sp.simplify(sp.gammasimp((term - hypergeometric_term).rewrite(sp.gamma))),
        "gauss": sp.simplify(sp.gammasimp(fractional_coefficient(_lag) * gauss - STATIONARY_AUTOCOVARIANCE)),
        "tail": sp.simplify(tail),
        "gauss_value": gauss,
    }
