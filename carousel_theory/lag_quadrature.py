"""Σ_δ N_ij(δ) c_ij(δ)² of the overlapping Allan-variance covariance without a sum over the record.

Setting: :mod:`carousel_theory.tau_covariance`. c_ij(δ) = Σ_q w_q H(q − δ) with H the fourth sum of the
model's increment autocovariance (:mod:`carousel_theory.increment_sums`): the finite terms (white, rate
random walk, quantization, AR) through one finite γ_z, the 1/f term in closed form. Each H is smooth away
from x = −2, so c is smooth away from the breakpoints b_q = q + 2; N_ij is linear between 0 and K_j − K_i.

Scheme
    Exact: every integer lag within ``EXACT_REACH`` (and the AR reach) of a breakpoint.
    Elsewhere: blocks of consecutive lags, each at most ``BLOCK_RATIO`` times its distance to the
    nearest breakpoint, summed by the p-point discrete Gauss rule of the uniform measure on the block's
    integers (nodes by Golub–Welsch from the discrete Chebyshev recurrence β_k = k²(L² − k²)/(4(4k² − 1))).
    On a block the finite terms are cubic polynomials, so N c² is a polynomial of degree ≤ 7 plus the 1/f
    part; the rule is exact for degree ≤ 2p − 1.

Error bound (proved; reported per entry as ``truncation_bound``)
    Let P interpolate c at the p nodes; N P² has degree ≤ 2p − 1 and agrees with N c² at the nodes, so
    the rule returns Σ N P² exactly and the error is Σ N (c² − P²) = Σ N e (2P + e), e = c − P =
    c^{(p)}(ξ) π_p/p! with π_p the monic orthogonal polynomial. With B ≥ sup|c^{(p)}|/p! on the block,
    Cauchy–Schwarz and Σ π_p² = h_p = β_0 β_1 ⋯ β_p, Σ P² = Q(c²):
        |error| ≤ B · max N · (2 √(h_p Q(c²)) + B h_p).
    B: c^{(p)} is the 1/f part only (p ≥ 4). On each branch H = K_d F(j), j = |x + 2|, F(j) =
    Γ(j + 1 + d)/Γ(j − d) = Γ(z + s)/Γ(z), z = j − d, s = 1 + 2d ∈ (1, 3). For p > s,
    F^{(p)}(z) = (−1)^p/Γ(−s) ∫_0^∞ t^p e^{−(z+s)t} (1 − e^{−t})^{−s−1} dt (the Beta integral, continued
    analytically in s), so F^{(p)} has one sign and |F^{(p)}| decreases; hence
    |F^{(p)}(j)| ≤ |Δ^p F(j − p)| = |(s)_p↓| Γ(j − p + 1 + d)/Γ(j − d) (mean value over a B-spline), and
    B ≤ |K_d| σ_w² Σ_q |w_q| |Δ^p F(j_q − p)|/p!, j_q the block's distance to b_q. In the far tail, where
    c(δ) = Σ_u W(u) γ_z(δ + u) with W ≥ 0, Σ W = m_i² m_j² and −γ_z completely monotone
    (Γ(x + d − 1)/Γ(x + 2 − d), the same Beta integral), also B ≤ m_i² m_j² |Δ^p γ_z(x₀ − p)|/p!.

Far tail (distance from the support ≥ ``FAR`` times its width)
    The nine-term difference of H loses (distance/width)⁴ of its digits there, so c is taken from the
    Newton series c(δ) = Σ_{r≤R} ν_r Δ^r γ_z(x₀), x₀ the nearest argument, ν_r = Σ_v W(v) C(v, r) (the
    coefficients of B_{m_i}(1 + t)² B_{m_j}(1 + t)²), with remainder ≤ ν_{R+1} |Δ^{R+1} γ_z(x₀ − R − 1)|
    (Newton's interpolation remainder and the monotone derivative above); that remainder is added to the
    bound through Σ w N e (2|c| + e). Pairs whose support is at most ``_DIRECT_WIDTH`` lags wide take c
    elsewhere from Σ_u W(u) γ_z(δ + u) directly (at integer lags, and outside the support at any lag).

Many pairs (:func:`counted_square_sums`, all the τ pairs of one covariance): the integer arguments q − δ
of H at the pairs' exact lags are merged into runs of consecutive integers and H is evaluated once on
them (octave pairs share about thirty in thirty-one of these arguments); each pair then looks them up. H
is evaluated element by element, so every sum and bound is bit for bit the one of the pair alone.

Rounding is not in the bound: where the support is wider, the nine-term sum of H loses about (m_j/m_i)²
ulps; the tests hold the whole to the bound plus 1e-11 relative.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from scipy import special

from carousel_theory.increment_sums import (
    finite_fourth_sum,
    flicker_fourth_sum,
    flicker_normalisation,
    rising_factorial,
)
from carousel_theory.noise_model import NoiseModel, increment_autocovariance

__all__ = [
    "BLOCK_RATIO",
    "EXACT_REACH",
    "FAR",
    "GAUSS_POINTS",
    "LagModel",
    "counted_square_sum",
    "counted_square_sums",
]

#: Nodes of the discrete Gauss rule on each block.
GAUSS_POINTS = 12
#: A block is at most this fraction of its distance to the nearest breakpoint.
BLOCK_RATIO = 0.5
#: Lags within this distance of a breakpoint (plus the AR reach) are summed one by one.
EXACT_REACH = 32
#: Beyond FAR support widths from the support, c comes from the Newton series of γ_z (the nine-term sum
#: of H would lose about FAR⁴ ulps there).
FAR = 4
_NEWTON_TERMS = 24
#: Pairs whose support is at most this wide take c at integer lags from Σ_u W(u) γ_z(δ + u) directly.
_DIRECT_WIDTH = 256


@dataclass(frozen=True)
class LagModel:
    """The model's fourth sums, prepared once per covariance: a table of the finite H near x = −2, the
    moments of the finite γ_z for the cubic beyond, and the 1/f parameters."""

    finite_gamma: np.ndarray
    finite_total: float
    table_low: int
    table: np.ndarray
    flicker_variance: float
    flicker_d: float
    reach: int
    #: H tabulated at runs of consecutive integers (first integers, last integers, index of each run's
    #: first value in the values, values), shared by many pairs (:func:`counted_square_sums`); H is
    #: evaluated element by element, so a looked-up value is the value a direct call returns.
    memo: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = field(
        default=None, compare=False, repr=False
    )

    @classmethod
    def of(cls, model: NoiseModel) -> LagModel:
        terms = model.terms()
        reach = max(3, _ar_lags(model)) if "ar" in terms else 3
        gamma = np.zeros(reach + 1)
        for name in ("white", "rrw", "quantization", "ar"):
            if name in terms:
                taps = increment_autocovariance(name, reach + 1, ar_coefficients=model.ar_coefficients)
                gamma += terms[name] * taps
        total = terms.get("rrw", 0.0)  # Σ γ_z: 1 for the rate random walk, exactly 0 for the others
        low = -reach - 8
        table = finite_fourth_sum(gamma, np.arange(low, reach + 8), total=total)
        flicker = terms.get("flicker", 0.0)
        return cls(gamma, total, low, table, flicker, float(model.flicker_d), reach)

    def fourth_sum(self, x: np.ndarray) -> np.ndarray:
        """Σ_t θ_t H_t(x) at (integer-valued near −2) points x (looked up where :attr:`memo` holds x)."""
        if self.memo is None:
            return self._evaluate(x)
        firsts, lasts, offsets, values = self.memo
        result = np.empty(x.shape)
        integral = x == np.rint(x)
        points = x[integral]
        run = np.maximum(np.searchsorted(firsts, points, side="right") - 1, 0)
        found = (points >= firsts[run]) & (points <= lasts[run])
        looked_up = np.empty(points.shape)
        looked_up[found] = values[(offsets[run] + (points - firsts[run]))[found].astype(np.int64)]
        if not np.all(found):
            looked_up[~found] = self._evaluate(points[~found])
        result[integral] = looked_up
        if not np.all(integral):
            result[~integral] = self._evaluate(x[~integral])
        return result

    def _evaluate(self, x: np.ndarray) -> np.ndarray:
        result = np.empty(x.shape)
        index = np.rint(x).astype(np.int64) - self.table_low
        near = (index >= 0) & (index < len(self.table)) & (np.abs(x + 2.0) <= self.reach + 6)
        result[near] = self.table[index[near]]
        far = ~near
        value = x[far]
        result[far] = np.where(value > 0, _cubic(self, value), 0.0)
        if self.flicker_variance:
            result += self.flicker_variance * flicker_fourth_sum(x, self.flicker_d)
        return result


def _ar_lags(model: NoiseModel) -> int:
    from carousel_theory.noise_model import _ar_lags as lags

    return lags(tuple(model.ar_coefficients))


def _cubic(lag_model: LagModel, x: np.ndarray) -> np.ndarray:
    """The finite H beyond its reach: M₀ p(x) + M₂ p''(x)/2, p(x) = (x + 1)(x + 2)(x + 3)/6."""
    gamma = lag_model.finite_gamma
    lags = np.arange(1, len(gamma), dtype=np.float64)
    second_moment = 2.0 * float(np.dot(gamma[1:], lags**2))
    return lag_model.finite_total * (x + 1) * (x + 2) * (x + 3) / 6 + second_moment * (x + 2) / 2


# --- the pair's geometry ------------------------------------------------------------------------------


def ramp_positions(m_i: int, m_j: int) -> list[tuple[int, int]]:
    """(q, w) with W_ij(−δ) = Σ w R₃(q − δ): q = −p_αβ, merged where positions coincide (module text of
    :mod:`carousel_theory.tau_covariance`)."""
    merged: dict[int, int] = {}
    for alpha, w_alpha in enumerate((1, -2, 1)):
        for beta, w_beta in enumerate((1, -2, 1)):
            q = -(2 - 2 * m_i + alpha * m_i + beta * m_j)
            merged[q] = merged.get(q, 0) + w_alpha * w_beta
    return [(q, w) for q, w in sorted(merged.items()) if w]


@dataclass(frozen=True)
class _Pair:
    positions: np.ndarray
    weights: np.ndarray
    m_i: int
    m_j: int
    K_i: int
    K_j: int

    def count(self, delta: np.ndarray) -> np.ndarray:
        """N_ij(δ), linear between the kinks 0 and K_j − K_i (also at non-integer δ inside a piece)."""
        return np.minimum(self.K_i - 1, self.K_j - 1 - delta) - np.maximum(0, -delta) + 1

    def cross_covariance(self, lag_model: LagModel, delta: np.ndarray) -> np.ndarray:
        """c_ij(δ) = Σ_q w_q H(q − δ)."""
        values = lag_model.fourth_sum(self.positions[None, :] - delta[:, None])
        return values @ self.weights


@functools.lru_cache(maxsize=64)
def _gauss_rule(length: int, points: int) -> tuple[np.ndarray, np.ndarray, float]:
    """(offsets in [0, L − 1], weights, log h_p) of the p-point Gauss rule of the uniform measure on
    {0, …, L − 1}: Golub–Welsch on the discrete Chebyshev recurrence (module text)."""
    k = np.arange(1, points + 1, dtype=np.float64)
    beta = k**2 * (float(length) ** 2 - k**2) / (4.0 * (4.0 * k**2 - 1.0))
    jacobi = np.diag(np.sqrt(beta[:-1]), 1)
    jacobi = jacobi + jacobi.T
    nodes, vectors = np.linalg.eigh(jacobi)
    weights = length * vectors[0] ** 2
    return nodes + (length - 1) / 2.0, weights, math.log(length) + float(np.sum(np.log(beta)))


def _grow(start: int, stop: int, breakpoint: int, direction: int) -> list[tuple[int, int]]:
    """Blocks (first, length) covering start … stop (direction +1 away from a breakpoint on the left,
    −1 away from one on the right): power-of-two lengths ≤ BLOCK_RATIO × distance."""
    blocks: list[tuple[int, int]] = []
    x, remaining = start, abs(stop - start) + 1
    while remaining > 0:
        distance = abs(x - breakpoint)
        length = min(1 << max(0, int(BLOCK_RATIO * distance).bit_length() - 1), remaining)
        length = 1 << (length.bit_length() - 1)
        blocks.append((x if direction > 0 else x - length + 1, length))
        x += direction * length
        remaining -= length
    return blocks


@functools.lru_cache(maxsize=1024)
def _plan(
    m_i: int, m_j: int, K_i: int, K_j: int, reach: int
) -> tuple[np.ndarray, tuple[tuple[int, int], ...]]:
    """(integer lags summed one by one, Gauss blocks (first, length)) covering −(K_i − 1) … K_j − 1
    (cached: the refits of one record plan the same pairs)."""
    low, high = -(K_i - 1), K_j - 1
    breakpoints = np.unique([q + 2 for q, _ in ramp_positions(m_i, m_j)])
    zone = max(EXACT_REACH, reach + 8, GAUSS_POINTS + 2)
    exact: list[np.ndarray] = []
    blocks: list[tuple[int, int]] = []
    cuts = sorted(
        {low, high + 1, 0, K_j - K_i} | {int(b) + s for b in breakpoints for s in (-zone, zone + 1)}
    )
    for start, stop in itertools.pairwise(cuts):
        first, last = max(start, low), min(stop - 1, high)
        if first > last:
            continue
        below, above = breakpoints[breakpoints < first], breakpoints[breakpoints > last]
        left = int(below[-1]) if len(below) else None
        right = int(above[0]) if len(above) else None
        inside = len(below) + len(above) < len(breakpoints)
        near = min(
            first - left if left is not None else math.inf, right - last if right is not None else math.inf
        )
        if inside or near <= zone or last - first < 2 * GAUSS_POINTS:
            exact.append(np.arange(first, last + 1))
            continue
        # Blocks grow away from the breakpoints on either side and meet half-way between them.
        middle = last if right is None else first - 1 if left is None else (left + right) // 2
        middle = min(max(middle, first - 1), last)
        if left is not None and middle >= first:
            blocks += _grow(first, middle, left, 1)
        if right is not None and middle < last:
            blocks += _grow(last, middle + 1, right, -1)
    small = [(f, n) for f, n in blocks if n <= 2 * GAUSS_POINTS]
    exact += [np.arange(f, f + n) for f, n in small]
    large = tuple((f, n) for f, n in blocks if n > 2 * GAUSS_POINTS)
    lags = np.concatenate(exact) if exact else np.zeros(0, dtype=np.int64)
    lags.setflags(write=False)
    return lags, large


# --- bounds and the far-tail series -----------------------------------------------------------------


def _falling(value: float, order: int, skip: int | None = None) -> float:
    return math.prod(value - k for k in range(order) if k != skip)


def _branch_bound(distance: np.ndarray, d: float) -> np.ndarray:
    """|d^p/dx^p H(x)|/p! at distance j = |x + 2| ≥ p + 1 from the branch point, unit σ_w² (module text):
    |K_d (s)_p↓| Γ(j − p + 1 + d)/Γ(j − d)/p!, the factor s − 2 = 2(d − ½) cancelling the pole of K_d."""
    p, s = GAUSS_POINTS, 1.0 + 2.0 * d
    scale = flicker_normalisation(d) / (16.0 * (d - 1.0) * d * (d + 0.5)) * 2.0 * _falling(s, p, skip=2)
    return abs(scale) / rising_factorial(distance - p + 1.0 + d, p - 1.0 - 2.0 * d) / math.factorial(p)


def _increment_difference(x: np.ndarray, d: float, order: int) -> np.ndarray:
    """Δ^r γ_z(x) of unit 1/f increments, r = order: C_d (2d − 3)_r↓ Γ(x + d − 1)/Γ(x + 2 − d + r)."""
    base = flicker_normalisation(d) * _falling(2.0 * d - 3.0, order)
    return base / rising_factorial(x + d - 1.0, 3.0 - 2.0 * d + order)


@functools.lru_cache(maxsize=4096)
def _factorial_moments(m_i: int, m_j: int, scale: float) -> np.ndarray:
    """ν_r / S^r, r = 0 … R + 1: the coefficients of B_{m_i}(1 + t)² B_{m_j}(1 + t)² in t = τ/S."""
    terms = _NEWTON_TERMS + 2
    powers = scale ** -np.arange(terms, dtype=np.float64)
    factors = [special.comb(m, np.arange(1, terms + 1), exact=False) * powers for m in (m_i, m_j)]
    result = np.array([1.0])
    for factor in (factors[0], factors[0], factors[1], factors[1]):
        result = np.convolve(result, factor)[:terms]
    return result


def _newton_series(pair: _Pair, lag_model: LagModel, nearest: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(c, bound on its error) from Σ_{r≤R} ν_r Δ^r γ_z(x₀) at the nearest arguments x₀ (far tail)."""
    d, scale = lag_model.flicker_d, float(max(2 * pair.m_i + 2 * pair.m_j - 4, 1))
    moments = _factorial_moments(pair.m_i, pair.m_j, scale)
    base = flicker_normalisation(d) / rising_factorial(nearest + d - 1.0, 3.0 - 2.0 * d)
    total, term = np.zeros_like(nearest), base.copy()
    for r in range(_NEWTON_TERMS + 1):
        total += moments[r] * term
        term = term * (2.0 * d - 3.0 - r) * scale / (nearest + 2.0 - d + r)
    order = _NEWTON_TERMS + 1
    remainder = moments[order] * np.abs(_increment_difference(nearest - order, d, order)) * scale**order
    return lag_model.flicker_variance * total, lag_model.flicker_variance * remainder


# --- the sum --------------------------------------------------------------------------------------


@functools.lru_cache(maxsize=1024)
def _block_nodes(
    blocks: tuple[tuple[int, int], ...],
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(node lags, node weights, block index of each node, log h_p of each block)."""
    firsts = np.array([first for first, _ in blocks], dtype=np.float64)
    rules = [_gauss_rule(length, GAUSS_POINTS) for _, length in blocks]
    offsets = np.stack([rule[0] for rule in rules])
    weights = np.stack([rule[1] for rule in rules])
    log_norms = np.array([rule[2] for rule in rules])
    owner = np.repeat(np.arange(len(blocks)), GAUSS_POINTS)
    return (firsts[:, None] + offsets).ravel(), weights.ravel(), owner, log_norms


def _far_arguments(pair: _Pair, lags: np.ndarray) -> np.ndarray:
    """x₀, the argument of γ_z nearest to zero over the support of W at each lag (≤ 0 inside it)."""
    return np.maximum(lags - 2 * pair.m_i + 2, -lags - 2 * pair.m_j + 2)


def _derivative_bounds(pair: _Pair, lag_model: LagModel, blocks: np.ndarray) -> np.ndarray:
    """B ≥ sup|c^{(p)}|/p! on each block (first, last): the branch bound, and in the far tail the
    bound through W ≥ 0 and the monotone derivative of γ_z, whichever is smaller (module text)."""
    if not lag_model.flicker_variance:
        return np.zeros(len(blocks))
    d, breakpoints = lag_model.flicker_d, pair.positions + 2.0
    distance = np.minimum(
        np.abs(blocks[:, :1] - breakpoints[None, :]), np.abs(blocks[:, 1:] - breakpoints[None, :])
    )
    bound = _branch_bound(distance, d) @ np.abs(pair.weights)
    nearest = np.minimum(_far_arguments(pair, blocks[:, 0]), _far_arguments(pair, blocks[:, 1]))
    tail = nearest > GAUSS_POINTS + 2
    if np.any(tail):
        mass = float(pair.m_i) ** 2 * float(pair.m_j) ** 2
        far = mass * np.abs(_increment_difference(nearest[tail] - GAUSS_POINTS, d, GAUSS_POINTS))
        bound[tail] = np.minimum(bound[tail], far / math.factorial(GAUSS_POINTS))
    return lag_model.flicker_variance * bound


def _partition(
    pair: _Pair, lag_model: LagModel, lags: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray]:
    """(x₀, far, direct or None, near): how c is taken at each lag (:func:`_values`)."""
    nearest = _far_arguments(pair, lags)
    width = max(2 * pair.m_i + 2 * pair.m_j - 4, 1)
    far = (nearest >= FAR * width) & (nearest >= max(lag_model.reach + 8, _NEWTON_TERMS + 4))
    far &= bool(lag_model.flicker_variance)
    near = ~far
    # Integer lags, or any lag outside the support (where every δ + u keeps one sign and γ_z is analytic).
    direct = near & ((lags == np.rint(lags)) | (nearest >= 1)) if width <= _DIRECT_WIDTH else None
    direct = direct if lag_model.flicker_variance else None
    if direct is not None:
        near &= ~direct
    return nearest, far, direct, near


def _values(pair: _Pair, lag_model: LagModel, lags: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(c, bound on its error) at ``lags``: the Newton series in the far tail; elsewhere the nine-term sum
    of H, or for narrow pairs the direct Σ_u W(u) γ_z(δ + u) (no cancellation)."""
    nearest, far, direct, near = _partition(pair, lag_model, lags)
    values, errors = np.empty(len(lags)), np.zeros(len(lags))
    if direct is not None and np.any(direct):
        values[direct] = _direct_flicker(pair, lag_model, lags[direct])
        finite = replace(lag_model, flicker_variance=0.0, memo=None)
        values[direct] += pair.cross_covariance(finite, lags[direct])
    values[near] = pair.cross_covariance(lag_model, lags[near])
    if np.any(far):
        values[far], errors[far] = _newton_series(pair, lag_model, nearest[far])
    return values, errors


@functools.lru_cache(maxsize=256)
def _window(m_i: int, m_j: int) -> np.ndarray:
    """W(u) = Σ_k g_i[k] g_j[k + u], u = −(2m_i − 2) … 2m_j − 2."""
    triangle_i = np.minimum(np.arange(1, 2 * m_i), np.arange(2 * m_i - 1, 0, -1)).astype(np.float64)
    triangle_j = np.minimum(np.arange(1, 2 * m_j), np.arange(2 * m_j - 1, 0, -1)).astype(np.float64)
    return np.convolve(triangle_i[::-1], triangle_j)


def _direct_flicker(pair: _Pair, lag_model: LagModel, lags: np.ndarray) -> np.ndarray:
    """σ_w² Σ_u W(u) γ_z(δ + u) at integer lags or outside the support, γ_z(x) = C_d/rising(|x| + d − 1,
    3 − 2d) (even on the integers, analytic on either side of the support)."""
    d, window = lag_model.flicker_d, _window(pair.m_i, pair.m_j)
    offsets = np.arange(-(2 * pair.m_i - 2), 2 * pair.m_j - 1, dtype=np.float64)
    arguments = np.abs(lags[:, None] + offsets[None, :])
    gamma = flicker_normalisation(d) / rising_factorial(arguments + d - 1.0, 3.0 - 2.0 * d)
    return lag_model.flicker_variance * (gamma @ window)


def _make_pair(m_i: int, m_j: int, K_i: int, K_j: int) -> _Pair:
    ramps = ramp_positions(m_i, m_j)
    positions = np.array([q for q, _ in ramps], dtype=np.float64)
    return _Pair(positions, np.array([w for _, w in ramps], dtype=np.float64), m_i, m_j, K_i, K_j)


def counted_square_sum(lag_model: LagModel, m_i: int, m_j: int, K_i: int, K_j: int) -> tuple[float, float]:
    """(Σ_δ N_ij(δ) c_ij(δ)², proved bound on its error) for the overlapping estimator (module text)."""
    pair = _make_pair(m_i, m_j, K_i, K_j)
    exact, blocks = _plan(m_i, m_j, K_i, K_j, lag_model.reach)
    lags = exact.astype(np.float64)
    values, errors = _values(pair, lag_model, lags)
    counts = pair.count(lags)
    total = float(np.dot(counts, values * values))
    bound = float(np.dot(counts, errors * (2.0 * np.abs(values) + errors)))
    if blocks:
        nodes, weights, owner, log_norms = _block_nodes(blocks)
        values, errors = _values(pair, lag_model, nodes)
        weighted = weights * pair.count(nodes)
        total += float(np.dot(weighted, values * values))
        bound += float(np.dot(weighted, errors * (2.0 * np.abs(values) + errors)))
        ends = np.array([(first, first + length - 1) for first, length in blocks], dtype=np.float64)
        derivative = _derivative_bounds(pair, lag_model, ends)
        square_sums = np.bincount(owner, weights * values * values, minlength=len(blocks))
        largest_count = np.maximum(pair.count(ends[:, 0]), pair.count(ends[:, 1]))
        norms = np.exp(log_norms)
        bound += float(
            np.sum(derivative * largest_count * (2.0 * np.sqrt(norms * square_sums) + derivative * norms))
        )
    return total, bound


def _argument_runs(lag_model: LagModel, pair: _Pair, lags: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(first, last) of the runs of consecutive integers q − δ at which :func:`_values` evaluates H
    through the nine-term sum at the integer ``lags``."""
    near = np.unique(lags[_partition(pair, lag_model, lags)[3]]).astype(np.int64)
    if not len(near):
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    breaks = np.flatnonzero(np.diff(near) != 1)
    starts, stops = near[np.concatenate(([0], breaks + 1))], near[np.concatenate((breaks, [len(near) - 1]))]
    positions = pair.positions.astype(np.int64)[:, None]
    return (positions - stops[None, :]).ravel(), (positions - starts[None, :]).ravel()


def _merged_runs(firsts: np.ndarray, lasts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The union of the integer intervals [first, last] as disjoint, sorted, non-adjacent intervals."""
    order = np.argsort(firsts, kind="stable")
    firsts, reach = firsts[order], np.maximum.accumulate(lasts[order])
    new = np.concatenate(([True], firsts[1:] > reach[:-1] + 1))
    starts = np.flatnonzero(new)
    return firsts[starts], reach[np.concatenate((starts[1:] - 1, [len(firsts) - 1]))]


def counted_square_sums(
    lag_model: LagModel, pairs: Sequence[tuple[int, int, int, int]]
) -> list[tuple[float, float]]:
    """:func:`counted_square_sum` of every (m_i, m_j, K_i, K_j) in ``pairs``, with H evaluated once on
    the union of the integer arguments that the pairs' exact lags need (octave pairs share most of
    them: about one in thirty is distinct), then looked up; each value is the one the pair alone gives."""
    firsts, lasts = [np.zeros(0, dtype=np.int64)], [np.zeros(0, dtype=np.int64)]
    for m_i, m_j, K_i, K_j in pairs:
        exact = _plan(m_i, m_j, K_i, K_j, lag_model.reach)[0]
        first, last = _argument_runs(lag_model, _make_pair(m_i, m_j, K_i, K_j), exact.astype(np.float64))
        firsts.append(first)
        lasts.append(last)
    first, last = np.concatenate(firsts), np.concatenate(lasts)
    if len(first):
        starts, ends = _merged_runs(first, last)
        lengths = ends - starts + 1
        offsets = np.concatenate(([0], np.cumsum(lengths)[:-1]))
        keys = np.repeat(starts - offsets, lengths) + np.arange(int(lengths.sum()))
        values = lag_model.fourth_sum(keys.astype(np.float64))
        memo = (starts.astype(np.float64), ends.astype(np.float64), offsets.astype(np.float64), values)
        lag_model = replace(lag_model, memo=memo)
    return [counted_square_sum(lag_model, *pair) for pair in pairs]
