"""Restricted maximum likelihood (REML) of the bias-prediction model y = b + f + v (SJ 2012 §III).

Each section y_k (n samples) has its own unknown constant bias b_k; f is the fractional integral
of TIM 2014 eq. (3) of order d driven by white noise of variance σ_w², and v is white of variance
σ_v². With Γ the covariance of f for σ_w² = 1, ρ = σ_v²/σ_w² and A = Γ + ρI, the restricted
log-likelihood of K sections is, up to a constant,

    ℓ = −½ [K(n − 1) log σ_w² + K log|A| + K log(1ᵀA⁻¹1) + Σ_k y_kᵀ P_A y_k / σ_w²],

P_A = A⁻¹ − A⁻¹11ᵀA⁻¹/(1ᵀA⁻¹1) (Harville, JASA 72, 1977). σ_w² is profiled out,
σ̂_w² = Σ_k y_kᵀP_A y_k / (K(n − 1)), leaving a function of log ρ (and of d when it is estimated).

Every evaluation needs log|A|, 1ᵀA⁻¹1, 1ᵀA⁻¹y_k and y_kᵀA⁻¹y_k, which the generalized Schur
recursion of :mod:`carousel_theory.generalized_schur` gives exactly in O(n log² n (K + 1)) time
and O(n(K + 1)) memory, without the n × n matrix a dense Cholesky factorisation needs (at n = 6000
that matrix alone is 288 MB, its factorisation O(n³)). The recursion is exact, so the estimate
equals the dense REML estimate to rounding; a Whittle likelihood would be faster but only
approximate for the non-stationary d ≥ ½ of SJ 2012.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Generator
from dataclasses import dataclass
from typing import cast

import numpy as np

from carousel_theory._validation import check_finite_array, check_fractional_order, check_real
from carousel_theory.generalized_schur import whiten
from carousel_theory.progress import progress

__all__ = ["VarianceEstimate", "estimate_noise_variances", "restricted_log_likelihood"]


@dataclass(frozen=True)
class VarianceEstimate:
    """Restricted maximum-likelihood variances of the model y = b + f + v (f of TIM 2014 eq. (3)):
    ``driving_variance`` σ_w², ``white_variance`` σ_v², from ``sections`` independent sections of
    ``length`` samples each, at the order ``d`` (given, or estimated when ``d_estimated``), with the
    maximised restricted log-likelihood ``log_likelihood`` (constant dropped)."""

    driving_variance: float
    white_variance: float
    d: float
    sections: int
    length: int
    log_likelihood: float
    d_estimated: bool = False


def _profile(data: np.ndarray, d: float, log_ratio: float) -> tuple[float, float]:
    """(ℓ at σ̂_w², σ̂_w²) for one ratio ρ = e^{log_ratio} (module docstring)."""
    count, n = data.shape
    right_hand_sides = np.empty((n, count + 1))
    right_hand_sides[:, 0] = 1.0
    right_hand_sides[:, 1:] = data.T
    system = whiten(right_hand_sides, d=d, driving_variance=1.0, white_variance=math.exp(log_ratio))
    whitened_ones = system.whitened[:, 0]
    whitened_data = system.whitened[:, 1:]
    total_ones = float(whitened_ones @ whitened_ones)
    cross = whitened_ones @ whitened_data
    quadratic = float((whitened_data**2).sum()) - float((cross**2).sum()) / total_ones
    scale = quadratic / (count * (n - 1))
    log_likelihood = -0.5 * (
        count * (n - 1) * (math.log(scale) + 1.0) + count * (system.log_determinant + math.log(total_ones))
    )
    return log_likelihood, scale


def restricted_log_likelihood(
    sections: np.ndarray, d: float, driving_variance: float, white_variance: float
) -> float:
    """ℓ of the module docstring at given (d, σ_w², σ_v²), constant dropped, for sections (K, n)."""
    data = _check_sections(sections)
    d = float(check_fractional_order("d", d))
    sigma2_w = float(check_real("driving_variance", driving_variance))
    sigma2_v = float(check_real("white_variance", white_variance))
    if not (sigma2_w > 0 and sigma2_v > 0):
        raise ValueError(
            f"driving_variance={driving_variance!r}, white_variance={white_variance!r}: must both be > 0"
        )
    count, n = data.shape
    right_hand_sides = np.hstack([np.ones((n, 1)), data.T])
    system = whiten(right_hand_sides, d=d, driving_variance=sigma2_w, white_variance=sigma2_v)
    ones, whitened = system.whitened[:, 0], system.whitened[:, 1:]
    total_ones = float(ones @ ones)
    quadratic = float((whitened**2).sum()) - float(((ones @ whitened) ** 2).sum()) / total_ones
    return -0.5 * (count * (system.log_determinant + math.log(total_ones)) + quadratic)


def _check_sections(sections: np.ndarray) -> np.ndarray:
    data = np.asarray(sections, dtype=np.float64)
    if data.ndim != 2:
        raise ValueError(
            f"sections: must be a 2-dimensional array (sections, samples), got shape {data.shape}"
        )
    check_finite_array("sections", data.reshape(-1))
    if data.shape[1] < 3:
        raise ValueError(f"sections: must hold at least 3 samples each, got {data.shape[1]}")
    return data


def _check_bounds(name: str, bounds: tuple[float, float], low_limit: float, high_limit: float):
    low, high = (float(check_real(name, value)) for value in bounds)
    if not low_limit <= low < high <= high_limit:
        raise ValueError(f"{name}={bounds!r}: must satisfy {low_limit} <= low < high <= {high_limit}")
    return low, high


#: (ℓ, σ̂_w²) of the profile at (d, log ρ); see :func:`_profile`.
Evaluate = Callable[[float, float], tuple[float, float]]


def _maximise_ratio(evaluate: Evaluate, d: float, log_bounds: tuple[float, float]) -> float:
    from scipy.optimize import minimize_scalar  # slow to import, needed only here

    result = minimize_scalar(
        lambda value: -evaluate(d, value)[0], bounds=log_bounds, method="bounded", options={"xatol": 1e-5}
    )
    return float(result.x)


def _maximise_order_and_ratio(
    evaluate: Evaluate, d_bounds: tuple[float, float], log_bounds: tuple[float, float]
) -> tuple[float, float]:
    """Nested search: for each d the ratio is maximised by Brent's method, then d by Brent's method
    on that profile (robust where a simplex search in (d, log ρ) stalls on the ridge)."""
    from scipy.optimize import minimize_scalar  # slow to import, needed only here

    ratios: dict[float, float] = {}

    def objective(order: float) -> float:
        ratios[order] = _maximise_ratio(evaluate, order, log_bounds)
        return -evaluate(order, ratios[order])[0]

    result = minimize_scalar(objective, bounds=d_bounds, method="bounded", options={"xatol": 1e-5})
    d = float(result.x)
    return d, ratios[d] if d in ratios else _maximise_ratio(evaluate, d, log_bounds)


def estimate_noise_variances(
    sections: np.ndarray,
    d: float = 0.5,
    ratio_bounds: tuple[float, float] = (1e-4, 1e4),
    *,
    estimate_d: bool = False,
    d_bounds: tuple[float, float] = (0.05, 0.95),
    show_progress: bool | None = None,
) -> VarianceEstimate:
    """REML estimates of σ_w² and σ_v² (and of d when ``estimate_d``) from independent sections
    (rows), each with its own unknown constant bias.

    ``d`` is the fixed order (not used when ``estimate_d``); log ρ is searched over
    ``ratio_bounds`` (a ratio at a bound means one component is not identified), d over
    ``d_bounds`` (Brent's method on the profile in d of the profile in log ρ). Progress, one tick
    per likelihood evaluation, is shown on a terminal (``show_progress=None``) or as asked.
    """
    data = _check_sections(sections)
    d = float(check_fractional_order("d", d))
    low, high = _check_bounds("ratio_bounds", ratio_bounds, 0.0, math.inf)
    if low <= 0:
        raise ValueError(f"ratio_bounds={ratio_bounds!r}: must satisfy 0 < low < high")
    log_bounds = (math.log(low), math.log(high))
    d_limits = _check_bounds("d_bounds", d_bounds, 0.0, 1.0) if estimate_d else (d, d)
    if estimate_d and not (d_limits[0] > 0.0 and d_limits[1] < 1.0):
        raise ValueError(f"d_bounds={d_bounds!r}: must lie strictly inside (0, 1)")
    ticks = cast(
        Generator[int, None, None],
        progress(itertools.count(), label="REML evaluations", enabled=show_progress),
    )
    evaluations: dict[tuple[float, float], tuple[float, float]] = {}

    def evaluate(order: float, log_ratio: float) -> tuple[float, float]:
        # Brent's method ends on a point it has evaluated: the final values come from this memo.
        if (order, log_ratio) not in evaluations:
            next(ticks)
            evaluations[order, log_ratio] = _profile(data, order, log_ratio)
        return evaluations[order, log_ratio]

    try:
        if estimate_d:
            d, log_ratio = _maximise_order_and_ratio(evaluate, d_limits, log_bounds)
        else:
            log_ratio = _maximise_ratio(evaluate, d, log_bounds)
        log_likelihood, scale = evaluate(d, log_ratio)
    finally:
        ticks.close()
    return VarianceEstimate(
        driving_variance=scale,
        white_variance=scale * math.exp(log_ratio),
        d=d,
        sections=data.shape[0],
        length=data.shape[1],
        log_likelihood=log_likelihood,
        d_estimated=estimate_d,
    )
