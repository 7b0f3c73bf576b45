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

Each evaluation is one pass of that recursion (about 0.55 s at n = 10⁵), so the search in log ρ is
built to need few: the Whittle likelihood of the first differences (O(n log n), biased for the
started process, used only as a starting point) gives log ρ₀; three points around it, walking
downhill by parabolic extrapolation when needed, bracket the maximum; Brent's method then starts
from that bracket with parabolic steps (cubic ones once four points are known, while their values
differ by more than rounding), and stops by Brent's rule, the one of the former bounded
search over the whole of ``ratio_bounds`` (x within 2(√ε |x| + RATIO_TOLERANCE/3) of the
maximiser). When the walk reaches a bound of ρ still climbing, the bounded search finishes on the
strip between that bound and the walk's last interior point. On the ADIS16405 x axis at n = 10⁵ this
takes 7 passes instead of 13; where the likelihood is very flat (ρ ≳ 10³, the z axis) or the maximum
is at a bound it can take a few more than the former search (``benchmarks/bench_reml_search.py``).
No analytic gradient is used: tr(A⁻¹) and A⁻¹y are not by-products of the forward recursion, and
carrying derivatives through every rotation would at least double the work of a pass (an estimate
from its operation count, not a measurement), more than the two or three passes a gradient could
save in a one-dimensional search.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Generator
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from carousel_theory._validation import check_boolean, check_finite_array, check_fractional_order, check_real
from carousel_theory.generalized_schur import whiten
from carousel_theory.progress import progress
from carousel_theory.signal_checks import check_noise_signal

__all__ = ["VarianceEstimate", "estimate_noise_variances", "restricted_log_likelihood"]


@dataclass(frozen=True)
class VarianceEstimate:
    """Restricted maximum-likelihood variances of the model y = b + f + v (f of TIM 2014 eq. (3)):
    ``driving_variance`` σ_w², ``white_variance`` σ_v², from ``sections`` independent sections of
    ``length`` samples each, at the order ``d`` (given, or estimated when ``d_estimated``), with the
    maximised restricted log-likelihood ``log_likelihood`` (constant dropped). ``at_bound`` names the
    estimates that ended at their search bound ("d", "σ_v²/σ_w²"): the data do not identify them."""

    driving_variance: float
    white_variance: float
    d: float
    sections: int
    length: int
    log_likelihood: float
    d_estimated: bool = False
    at_bound: tuple[str, ...] = ()


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
    for index, section in enumerate(data):  # varies, and its variances fit in float64
        check_noise_signal(section, f"sections[{index}]")
    return data


def _check_bounds(name: str, bounds: tuple[float, float], low_limit: float, high_limit: float):
    if isinstance(bounds, (str, bytes)) or not hasattr(bounds, "__len__") or len(bounds) != 2:
        raise ValueError(f"{name}={bounds!r}: must be a pair (low, high)")
    return _ordered_bounds(name, bounds, low_limit, high_limit)


def _ordered_bounds(name: str, bounds: tuple[float, float], low_limit: float, high_limit: float):
    low, high = (float(check_real(name, value)) for value in bounds)
    if not low_limit <= low < high <= high_limit:
        raise ValueError(f"{name}={bounds!r}: must satisfy {low_limit} <= low < high <= {high_limit}")
    return low, high


#: (ℓ, σ̂_w²) of the profile at (d, log ρ); see :func:`_profile`.
Evaluate = Callable[[float, float], tuple[float, float]]

#: The search stops once log ρ is known to ± 2 (√ε |log ρ| + RATIO_TOLERANCE/3) (Brent's rule).
RATIO_TOLERANCE = 1e-5
#: Half-width in log ρ of the first three points around the Whittle start: 16/√(K(n − 1)) within
#: [0.02, 0.25], shrinking with the data as the spread of the estimate and the Whittle start's bias
#: do (on the ADIS16405 x axis the start is 0.6 off at n = 6000 and 0.015 off at n = 10⁵; a step of
#: 0.05 there saves one of nine passes).
_FIRST_STEP_SCALE = 16.0
_FIRST_STEP_LIMITS = (0.02, 0.25)
_GOLDEN_SECTION = 0.5 * (3.0 - math.sqrt(5.0))
_GOLDEN_RATIO = 0.5 * (1.0 + math.sqrt(5.0))
_SQUARE_ROOT_EPSILON = math.sqrt(np.finfo(np.float64).eps)
#: The cubic interpolation is used while the four points nearest x spread over more than this many
#: tolerances; closer, the differences of the likelihood are too near its rounding for a cubic.
_CUBIC_SPREAD = 100.0
#: ... and while their values spread over more than _CUBIC_SPREAD times this many roundings of the
#: likelihood (a sum of n logarithms, whose rounding error is some 10⁴ ε |ℓ| at n = 10⁵), so that a
#: flat likelihood (ρ ≳ 10³) is left to Brent's parabola.
_CUBIC_VALUE_DIGITS = 1e4


def _whittle_log_ratio(sections: np.ndarray, d: float, log_bounds: tuple[float, float]) -> float:
    """log ρ̂ = log(σ_v²/σ_w²) of the Whittle likelihood of the first differences (the starting point
    of the exact search, not an estimate that is reported).

    The differences z = Δy of y = b + f + v lose the bias; for the stationary version of f (TIM 2014
    eq. (3) with an infinite past) z has the spectral density σ_w² S_f(ω)|1 − e^{−iω}|² +
    σ_v² |1 − e^{−iω}|² (S_f of :func:`carousel_theory.noise_model.spectral_density`); the scale is
    profiled out in closed form and log ρ found on a 41-point grid refined by Brent's method
    (:func:`_grid_then_brent`), O(n log n). The started process
    of eq. (3) differs from the stationary one, so ρ̂ is biased on short sections (on the ADIS16405
    x axis log ρ̂ − log ρ_REML ≈ −0.6 at n = 6000 and −0.01 at n = 10⁵); the exact REML search
    corrects this.
    """
    from carousel_theory.noise_model import spectral_density

    differences = np.diff(sections, axis=1)
    periodogram = (np.abs(np.fft.rfft(differences, axis=1)[:, 1:]) ** 2).ravel()
    omega = 2.0 * np.pi * np.arange(1, periodogram.size // sections.shape[0] + 1) / differences.shape[1]
    difference = 4.0 * np.sin(omega / 2.0) ** 2  # |1 − e^{−iω}|²
    flicker = np.tile(spectral_density("flicker", omega, d) * difference, sections.shape[0])
    white = np.tile(spectral_density("white", omega) * difference, sections.shape[0])
    if not np.any(periodogram > 0.0):  # straight lines: no start is better than another
        return 0.5 * (log_bounds[0] + log_bounds[1])

    def negative_log_likelihood(log_ratio: float) -> float:
        spectrum = flicker + math.exp(log_ratio) * white
        return float(np.log(spectrum).sum()) + periodogram.size * math.log(
            float((periodogram / spectrum).mean())
        )

    return _grid_then_brent(negative_log_likelihood, log_bounds)


#: Points of the grid in log ρ on which the Whittle start's search begins.
_WHITTLE_GRID = 41


def _grid_then_brent(objective: Callable[[float], float], log_bounds: tuple[float, float]) -> float:
    """The minimiser of a cheap ``objective`` on ``log_bounds``: the best of an even grid, then Brent's
    method (:func:`_brent_minimum`) on the bracket of its two neighbours; a bound when the grid's best
    is there. (scipy.optimize would do it too, at a fifth of a second to import.)"""
    grid = np.linspace(log_bounds[0], log_bounds[1], _WHITTLE_GRID)
    values = [objective(float(point)) for point in grid]
    best = int(np.argmin(values))
    if best in (0, grid.size - 1):
        return float(grid[best])
    return _brent_minimum(objective, float(grid[best - 1]), float(grid[best]), float(grid[best + 1]))


def _vertex(a: float, fa: float, b: float, fb: float, c: float, fc: float) -> float | None:
    """Abscissa of the vertex of the parabola through three points, None unless it is a minimum."""
    numerator = (b - a) ** 2 * (fb - fc) - (b - c) ** 2 * (fb - fa)
    denominator = (b - a) * (fb - fc) - (b - c) * (fb - fa)
    return b - 0.5 * numerator / denominator if denominator < 0.0 else None


def _downhill(objective, near: float, far: float, bound: float, points: tuple[float, float, float]) -> float:
    """The next point beyond ``far`` (downhill from ``near``, step s = far − near), from the vertex of
    the parabola through ``points``: 1.5 times the way to it when it lies beyond ``far``, twice its
    distance behind ``far`` otherwise (the minimum is then close: a short step closes the bracket),
    between 0.1|s| and 10|s|; golden-ratio growth when the parabola has no minimum; within ``bound``."""
    vertex = _vertex(*(value for point in points for value in (point, objective(point))))
    step = far - near
    if vertex is None:
        distance = _GOLDEN_RATIO * abs(step)
    elif (vertex - far) * step > 0.0:
        distance = 1.5 * abs(vertex - far)
    else:
        distance = 2.0 * abs(vertex - far)
    distance = math.copysign(min(max(distance, 0.1 * abs(step)), 10.0 * abs(step)), step)
    return min(max(far + distance, min(bound, far)), max(bound, far))


def _bracket(objective: Callable[[float], float], start: float, low: float, high: float, first_step: float):
    """(left, middle, right) with objective(middle) ≤ both ends, walking downhill from ``start``
    (first points ± ``first_step``, then parabolic extrapolation, :func:`_downhill`); when the walk
    reaches ``low`` or ``high`` still going down, the strip (bound, last interior point) that holds the
    minimum instead."""
    middle = min(max(start, low + first_step), high - first_step)
    left, right = middle - first_step, middle + first_step
    while True:
        if objective(middle) <= min(objective(left), objective(right)):
            return left, middle, right
        points = (left, middle, right)
        if objective(left) < objective(right):
            if left == low:
                return low, middle
            left, middle, right = _downhill(objective, middle, left, low, points), left, middle
        else:
            if right == high:
                return middle, high
            left, middle, right = middle, right, _downhill(objective, middle, right, high, points)


def _cubic_vertex(points: list[tuple[float, float]], x: float) -> float | None:
    """The local minimum nearest x of the cubic through the four evaluated points nearest x (x one of
    them), as a step from x; None when fewer than four are known, when they lie within
    ``_CUBIC_SPREAD`` tolerances of x or their values within ``_CUBIC_SPREAD · _CUBIC_VALUE_DIGITS``
    roundings (the cubic would fit rounding errors), or when the cubic has no local minimum."""
    if len(points) < 4:
        return None
    nearest = sorted(points, key=lambda point: abs(point[0] - x))[:4]
    offsets = np.array([point[0] - x for point in nearest])
    if np.abs(offsets).max() < _CUBIC_SPREAD * (_SQUARE_ROOT_EPSILON * abs(x) + RATIO_TOLERANCE / 3.0):
        return None
    values = np.array([point[1] for point in nearest])  # values[0] is at x itself (offset 0)
    if np.ptp(values) < _CUBIC_SPREAD * _CUBIC_VALUE_DIGITS * np.finfo(np.float64).eps * abs(values[0]):
        return None
    try:
        cubic, quadratic, linear, _ = np.linalg.solve(np.vander(offsets, 4), values - values[0])
    except np.linalg.LinAlgError:  # two abscissae equal
        return None
    # Stationary points 3c t² + 2q t + l = 0; the minimum is the root where 6c t + 2q > 0,
    # (−q + √D)/(3c) = −l/(q + √D): the second form does not cancel when c is small beside q.
    discriminant = quadratic * quadratic - 3.0 * cubic * linear
    if discriminant < 0.0:
        return None
    denominator = quadratic + math.sqrt(discriminant)
    if denominator != 0.0:
        return -linear / denominator
    # q ≤ 0 and c·l = 0: with c ≠ 0 and q < 0 the minimum is the root other than t = 0.
    return -2.0 * quadratic / (3.0 * cubic) if cubic != 0.0 and quadratic < 0.0 else None


def _interpolated_step(x, fx, w, fw, v, fv, points):
    """The step of Brent's parabola through (x, w, v), or, once four points are known, to the local
    minimum of the cubic through the four nearest x (:func:`_cubic_vertex`): near the maximum of a
    smooth likelihood its error is of the order of the product of three distances to the maximiser
    instead of two, which saves a pass or two of the recursion. None where neither exists."""
    cubic = _cubic_vertex(points, x)
    if cubic is not None:
        return cubic
    r = (x - w) * (fx - fv)
    q = (x - v) * (fx - fw)
    p = (x - v) * q - (x - w) * r
    q = 2.0 * (q - r)
    return -p / q if q != 0.0 else None


def _accepted_step(step, x, left, right, last_step, tolerance):
    """``step`` where Brent's method accepts an interpolation step (strictly inside the bracket and
    shorter than half the step before last; moved to ± tol next to an end), else None."""
    if step is None or not (abs(step) < abs(0.5 * last_step) and left < x + step < right):
        return None
    if (x + step - left) < 2.0 * tolerance or (right - x - step) < 2.0 * tolerance:
        return tolerance if 0.5 * (left + right) >= x else -tolerance
    return step


def _brent_minimum(objective: Callable[[float], float], left: float, middle: float, right: float) -> float:
    """Brent's minimisation (Algorithms for Minimization without Derivatives, 1973, ch. 5; the rule of
    scipy's bounded search) started from a bracket instead of a golden-section point, so that its
    first steps are interpolations (:func:`_interpolated_step`). Ends when the bracket around x is at
    most 2·tol wide on either side, tol = √ε |x| + RATIO_TOLERANCE/3."""
    x, fx = middle, objective(middle)
    (fw, w), (fv, v) = sorted([(objective(left), left), (objective(right), right)])
    points = [(x, fx), (w, fw), (v, fv)]
    step = last_step = right - left
    while True:
        tolerance = _SQUARE_ROOT_EPSILON * abs(x) + RATIO_TOLERANCE / 3.0
        centre = 0.5 * (left + right)
        if abs(x - centre) <= 2.0 * tolerance - 0.5 * (right - left):
            return x
        interpolated = None
        if abs(last_step) > tolerance:
            proposed = _interpolated_step(x, fx, w, fw, v, fv, points)
            interpolated = _accepted_step(proposed, x, left, right, last_step, tolerance)
        if interpolated is None:
            last_step = (right - x) if x < centre else (left - x)
            step = _GOLDEN_SECTION * last_step
        else:
            last_step, step = step, interpolated
        u = x + (step if abs(step) >= tolerance else math.copysign(tolerance, step))
        fu = objective(u)
        points.append((u, fu))
        if fu <= fx:
            left, right = (x, right) if u >= x else (left, x)
            v, fv, w, fw, x, fx = w, fw, x, fx, u, fu
            continue
        left, right = (left, u) if u >= x else (u, right)
        if fu <= fw or w == x:
            v, fv, w, fw = w, fw, u, fu
        elif fu <= fv or v in (x, w):
            v, fv = u, fu


def _maximise_ratio(
    evaluate: Evaluate, d: float, log_bounds: tuple[float, float], start: float, first_step: float
) -> float:
    """log ρ maximising the profile at order d: Brent's method from a bracket found around ``start``;
    by scipy's bounded search on the strip next to a bound when the walk reached it, or on the whole of
    ``log_bounds`` when they are too narrow for a bracket."""

    def objective(log_ratio: float) -> float:
        return -evaluate(d, log_ratio)[0]

    low, high = log_bounds
    found = _bracket(objective, start, low, high, first_step) if high - low > 4.0 * first_step else None
    if found is not None and len(found) == 3:
        return _brent_minimum(objective, *found)
    from scipy.optimize import minimize_scalar  # slow to import, needed only here

    strip = log_bounds if found is None else found
    result = minimize_scalar(objective, bounds=strip, method="bounded", options={"xatol": RATIO_TOLERANCE})
    return float(result.x)


def _maximise_order_and_ratio(
    evaluate: Evaluate,
    starting_point: Callable[[float], float],
    d_bounds: tuple[float, float],
    log_bounds: tuple[float, float],
    first_step: float,
) -> tuple[float, float]:
    """Nested search: for each d the ratio is maximised by Brent's method from the Whittle start
    ``starting_point(d)``, then d by Brent's method on that profile (robust where a simplex search
    in (d, log ρ) stalls on the ridge)."""
    from scipy.optimize import minimize_scalar  # slow to import, needed only here

    ratios: dict[float, float] = {}

    def ratio_at(order: float) -> float:
        if order not in ratios:
            ratios[order] = _maximise_ratio(evaluate, order, log_bounds, starting_point(order), first_step)
        return ratios[order]

    result = minimize_scalar(
        lambda order: -evaluate(order, ratio_at(order))[0],
        bounds=d_bounds,
        method="bounded",
        options={"xatol": 1e-5},
    )
    d = float(result.x)
    return d, ratio_at(d)


def _check_ratio_bounds(ratio_bounds: tuple[float, float]) -> tuple[float, float]:
    """(log low, log high) of the ratio bounds, 0 < low < high."""
    low, high = _check_bounds("ratio_bounds", ratio_bounds, 0.0, math.inf)
    if low <= 0:
        raise ValueError(f"ratio_bounds={ratio_bounds!r}: must satisfy 0 < low < high")
    return math.log(low), math.log(high)


def _first_step(data: np.ndarray) -> float:
    """The first bracket's half-width in log ρ for K sections of n samples (``_FIRST_STEP_SCALE``)."""
    step = _FIRST_STEP_SCALE / math.sqrt(data.size - data.shape[0])
    return min(max(step, _FIRST_STEP_LIMITS[0]), _FIRST_STEP_LIMITS[1])


def _order_limits(d: float, d_bounds: tuple[float, float]) -> tuple[float, float]:
    """The d search range ``d_bounds``, checked: strictly inside (0, 1)."""
    limits = _check_bounds("d_bounds", d_bounds, 0.0, 1.0)
    if not (limits[0] > 0.0 and limits[1] < 1.0):
        raise ValueError(f"d_bounds={d_bounds!r}: must lie strictly inside (0, 1)")
    return limits


def _identifiable(data: np.ndarray, parameters: int) -> np.ndarray:
    """``data``, after refusing sections with no more contrasts than parameters: each section's unknown
    bias takes one sample's worth, and the sections × (length − 1) contrasts left must outnumber them."""
    count, length = data.shape
    contrasts = count * (length - 1)
    if contrasts <= parameters:
        raise ValueError(
            f"sections: {count} section(s) of {length} samples leave {contrasts} contrasts after each "
            f"section's bias; REML of {parameters} parameters needs more than {parameters}"
        )
    return data


#: An estimate this close to its search bound (d; log σ_v²/σ_w²) is reported as at the bound.
_AT_BOUND = {"d": 1e-4, "σ_v²/σ_w²": 1e-3}


def _at_bounds(
    log_ratio: float, log_bounds: tuple[float, float], d: float, d_limits: tuple[float, float] | None
) -> tuple[str, ...]:
    """The names of the estimates within _AT_BOUND of one of their bounds (d only when estimated,
    ``d_limits`` None otherwise)."""
    estimates = {"σ_v²/σ_w²": (log_ratio, log_bounds)}
    if d_limits is not None:
        estimates["d"] = (d, d_limits)
    return tuple(
        name
        for name, (value, (low, high)) in estimates.items()
        if min(abs(value - low), abs(value - high)) <= _AT_BOUND[name]
    )


def _check_flags(estimate_d: Any, show_progress: Any) -> None:
    """``estimate_d`` True or False; ``show_progress`` True, False or None (on a terminal)."""
    check_boolean("estimate_d", estimate_d)
    if show_progress is not None:
        check_boolean("show_progress", show_progress)


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

    ``d`` is the fixed order (not used when ``estimate_d``); log ρ is searched over ``ratio_bounds``
    (a ratio at a bound means one component is not identified) by Brent's method from a bracket
    around the Whittle start of :func:`_whittle_log_ratio`, to ± 2(√ε |log ρ| + RATIO_TOLERANCE/3);
    d over ``d_bounds`` (Brent's method on the profile in d of the profile in log ρ). Progress, one
    tick per likelihood evaluation, is shown on a terminal (``show_progress=None``) or as asked.
    """
    _check_flags(estimate_d, show_progress)
    data = _identifiable(_check_sections(sections), 3 if estimate_d else 2)
    d = float(check_fractional_order("d", d))
    log_bounds = _check_ratio_bounds(ratio_bounds)
    d_limits = _order_limits(d, d_bounds) if estimate_d else (d, d)
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

    def starting_point(order: float) -> float:
        return _whittle_log_ratio(data, order, log_bounds)

    first_step = _first_step(data)
    try:
        if estimate_d:
            d, log_ratio = _maximise_order_and_ratio(
                evaluate, starting_point, d_limits, log_bounds, first_step
            )
        else:
            log_ratio = _maximise_ratio(evaluate, d, log_bounds, starting_point(d), first_step)
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
        at_bound=_at_bounds(log_ratio, log_bounds, d, d_limits if estimate_d else None),
    )
