"""Covariance of Allan-variance estimates across τ, without sums over the record.

Setting. The overlapping estimate at m samples per cluster is σ̂²(m) = Σ_{s<K} d_s²/(2m²K), K = n − 2m + 1,
with d_s = Σ_{k<m} (y_{s+m+k} − y_{s+k}); the non-overlapping one keeps every m-th start (K = ⌊n/m⌋ − 1,
TIM 2014 eq. (20)). With z_t = y_t − y_{t−1}, d_s = Σ_k g_m[k] z_{s+1+k}, g_m the triangle 1, 2, …, m, …, 1
(the coefficients of B_m(x)², B_m(x) = 1 + x + … + x^{m−1}). For Gaussian noise

    Cov(σ̂²_i, σ̂²_j) = Σ_δ N_ij(δ) c_ij(δ)² / (2 m_i² m_j² K_i K_j),
    c_ij(δ) = Cov(d_{i,s}, d_{j,s+δ}) = Σ_u W_ij(u) γ_z(δ + u),  W_ij(u) = Σ_k g_i[k] g_j[k + u],

N_ij(δ) the number of pairs of starts at offset δ (for both estimators) and γ_z the increment
autocovariance of :mod:`carousel_theory.noise_model`. W_ij has the generating function
x^{2−2m_i}(1 − x^{m_i})²(1 − x^{m_j})²/(1 − x)⁴, so it is a sum of nine cubic ramps
W_ij(u) = Σ_{α,β∈{0,1,2}} w_α w_β R₃(u − p_αβ), w = (1, −2, 1), p_αβ = 2 − 2m_i + αm_i + βm_j,
R₃(x) = C(x + 3, 3) for x ≥ 0 and 0 below.

Exact closed form (white, rate random walk, quantization; overlapping estimator)
    γ_z has at most five taps, and the differences of R₃ give c_ij in closed form: rate random walk
    W_ij(−δ) (piecewise cubic), white −Σ w_αβ max(2 − p_αβ − δ, 0) (piecewise linear, since the central
    second difference of R₃(x) is max(x + 2, 0)), quantization Σ w_αβ [δ = 2 − p_αβ] (nine spikes, the
    fourth difference). N_ij is piecewise linear with breaks at −(K_i − 1), 0, K_j − K_i, K_j. So
    N_ij c_ij² is a polynomial of degree ≤ 7 on each of at most ~25 pieces between sorted breakpoints, and
    each piece is summed exactly by the Newton series Σ_{t<L} P(t) = Σ_{k≤7} Δ^k P(0) C(L, k + 1) in
    integers. The cost does not depend on n or m; the result is exact (Python integers), and for
    n ≥ 2(m_i + m_j) it is A_ij + B_ij n (cached per (m_i, m_j), so a loop that refits pays once).

1/f and AR, overlapping estimator
    Records of up to :data:`EVERY_LAG_LENGTH` samples: c_ij(δ) at every lag of the record by two moving
    sums (below) and Σ N c² exactly, with no truncation. Longer records:
    :mod:`carousel_theory.lag_quadrature`, whose cost does not grow with n — exact lags near the
    breakpoints of c_ij, discrete Gauss blocks with a proved error bound elsewhere (the 1/f part
    through the telescoped fourth sum of :mod:`carousel_theory.increment_sums`), the 1/f far tail by
    its Newton series; its bound is :attr:`TauCovariance.truncation_bound` (plus rounding, about 1e-11
    relative).

Non-overlapping estimator (1/f, AR)
    c_ij(δ) on a window of lags, O(m_i + m_j + T) time and one array of that length per pair, T the reach
    of γ_z: γ_z is correlated with the triangle g_j and then with g_i = B_{m_i}⋆B_{m_i}, each as two
    moving sums in place, and only every m_i-th offset enters the sum.
    T: for AR, the lag beyond which the geometric envelope is below
    :data:`carousel_theory.noise_model.AR_TRUNCATION`; for 1/f, T = ``FLICKER_REACH``·(m_i + m_j). The 1/f
    tail beyond the window is bounded: for k ≥ 1, γ_z(k) < 0 and |γ_z(k)| decreases, with
    |γ_z(k)| ≤ |γ_z(V)| ((V + 2 − d)/(k + 2 − d))^{3−2d}, so
    Σ_{k≥V} γ_z(k)² ≤ γ_z(V)² (1 + (V + 2 − d)/(5 − 4d));
    with W ≥ 0 and Σ W = m_i² m_j², the neglected part of Σ N c² is at most 2 K (m_i² m_j²)² Σ_{k≥V} γ_z(k)²,
    V the first lag outside the window; :attr:`TauCovariance.truncation_bound` reports it.

Equivalent degrees of freedom (Satterthwaite) come from the diagonal: ν_i = 2 E[σ̂²_i]² / Var σ̂²_i.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp

from carousel_theory import symbols
from carousel_theory._validation import check_positive_integer
from carousel_theory.increment_sums import flicker_increment_difference
from carousel_theory.lag_quadrature import (
    PROVED_RULE,
    LagModel,
    QuadratureRule,
    counted_square_sums,
    ramp_positions,
)
from carousel_theory.noise_model import (
    NoiseModel,
    ar_increment_reach,
    cluster_sizes,
    unit_flicker_increment_autocovariance,
)

__all__ = [
    "FLICKER_REACH",
    "WHITE_OVERLAPPING_ESTIMATE_VARIANCE",
    "TauCovariance",
    "allan_estimate_covariance",
    "allan_estimate_variance",
]

#: The 1/f cross-covariance is summed over this many (m_i + m_j) lags beyond the filters' support; the
#: rest is bounded (module text).
FLICKER_REACH = 4
_FINITE = ("white", "rrw", "quantization")

_m, _K = symbols.cluster_size, symbols.difference_count
#: Var σ̂²(m) of the overlapping estimator for white noise of variance σ_WN², K = n − 2m + 1 ≥ 2m
#: differences (derived by summation in ``derivations/allan_variance_models.md`` §6).
WHITE_OVERLAPPING_ESTIMATE_VARIANCE: sp.Expr = (
    symbols.white_sample_variance**2 * (4 * _K * _m**2 + 5 * _K - 2 * _m**3 - _m) / (3 * _K**2 * _m**3)
)
_WEIGHTS = (1, -2, 1)


@dataclass(frozen=True)
class TauCovariance:
    """Covariance of the Allan variance estimates at ``sizes`` for Gaussian noise of a model.

    Attributes
    ----------
    sizes : ndarray of int
        m at each τ.
    covariance : ndarray
        Cov(σ̂²_i, σ̂²_j).
    allan_variance : ndarray
        The model's (stationary) Allan variance at each m.
    edf : ndarray
        Equivalent degrees of freedom 2 σ_A⁴ / Var σ̂².
    truncation_bound : ndarray
        Bound on the part of each entry left out by a truncated 1/f sum (0 where exact; NaN where the lag
        quadrature's bound was not asked for, ``bound=False``).
    estimator : str
        "overlapping" or "non-overlapping".
    """

    sizes: np.ndarray
    covariance: np.ndarray
    allan_variance: np.ndarray
    edf: np.ndarray
    truncation_bound: np.ndarray
    estimator: str


# --- the exact integer engine ---------------------------------------------------------------------


def _cross_values(ramps: Sequence[tuple[int, int]], delta: int) -> tuple[int, int]:
    """(c_white, c_rrw) at δ for unit variances, exact integers."""
    white = rrw = 0
    for q, w in ramps:
        x = q - delta
        if x >= -1:
            white -= w * (x + 2)
            if x >= 0:
                rrw += w * ((x + 1) * (x + 2) * (x + 3) // 6)
    return white, rrw


def _pair_count(delta: int, K_i: int, K_j: int) -> int:
    """N_ij(δ): starts s < K_i, r < K_j with r − s = δ (overlapping)."""
    return max(0, min(K_i - 1, K_j - 1 - delta) - max(0, -delta) + 1)


def _piece_sums(ramps: Sequence[tuple[int, int]], start: int, stop: int, K_i: int, K_j: int) -> np.ndarray:
    """Σ_{δ=start}^{stop−1} N c_a c_b for (a, b) = (W, W), (W, R), (R, R), exactly (one polynomial piece)."""
    length = stop - start
    points = min(length, 8)
    values = [[0] * points for _ in range(3)]
    for t in range(points):
        white, rrw = _cross_values(ramps, start + t)
        count = _pair_count(start + t, K_i, K_j)
        values[0][t], values[1][t], values[2][t] = (
            count * white * white,
            count * white * rrw,
            count * rrw * rrw,
        )
    if length <= 8:
        return np.array([sum(row) for row in values], dtype=object)
    sums = []
    for row in values:  # Newton series: Σ_{t<L} P(t) = Σ_k Δ^k P(0) C(L, k + 1), P of degree ≤ 7
        total, differences = 0, list(row)
        for k in range(8):
            total += differences[0] * math.comb(length, k + 1)
            differences = [b - a for a, b in itertools.pairwise(differences)]
        sums.append(total)
    return np.array(sums, dtype=object)


@functools.lru_cache(maxsize=4096)
def _finite_gram(m_i: int, m_j: int, K_i: int, K_j: int) -> tuple[int, int, int, int, int, int]:
    """Exact Σ_δ N c_a c_b for the pairs WW, WR, RR, QQ, QW, QR of unit-variance finite terms."""
    ramps = ramp_positions(m_i, m_j)
    low = max(-(K_i - 1), -2 * m_j - 2)
    high = min(K_j - 1, max(q for q, _ in ramps) + 2)
    cuts = {low, high + 1, 0, K_j - K_i, -(K_i - 1), K_j}
    for q, _ in ramps:
        cuts.update((q + 1, q + 2))
    edges = sorted(c for c in cuts if low <= c <= high + 1)
    total = np.zeros(3, dtype=object)
    for start, stop in itertools.pairwise(edges):
        total = total + _piece_sums(ramps, start, stop, K_i, K_j)
    spikes: dict[int, int] = {}
    for q, w in ramps:  # quantization: c_Q(δ) = Σ w [δ = q + 2]
        spikes[q + 2] = spikes.get(q + 2, 0) + w
    quantization = [0, 0, 0]
    for delta, weight in spikes.items():
        count = _pair_count(delta, K_i, K_j)
        white, rrw = _cross_values(ramps, delta)
        quantization[0] += count * weight * weight
        quantization[1] += count * weight * white
        quantization[2] += count * weight * rrw
    return (int(total[0]), int(total[1]), int(total[2]), quantization[0], quantization[1], quantization[2])


def _finite_sum(model: NoiseModel, m_i: int, m_j: int, K_i: int, K_j: int) -> float:
    """Σ_δ N c² of the model's white, rate random walk and quantization terms (overlapping), exact sums."""
    terms = model.terms()
    white, rrw, quantization = (terms.get(name, 0.0) for name in _FINITE)
    if not (white or rrw or quantization):
        return 0.0
    ww, wr, rr, qq, qw, qr = _finite_gram(m_i, m_j, K_i, K_j)
    return float(
        white * white * ww
        + 2 * white * rrw * wr
        + rrw * rrw * rr
        + quantization * quantization * qq
        + 2 * quantization * white * qw
        + 2 * quantization * rrw * qr
    )


# --- the finite lag sums (1/f, AR, non-overlapping) ---------------------------------------------------


def _lag_window(model: NoiseModel, m_i: int, m_j: int) -> int:
    """How far beyond the filters' support c_ij is summed (module text)."""
    terms = model.terms()
    reach = 0
    if "flicker" in terms:
        reach = FLICKER_REACH * (m_i + m_j) + 64
    if "ar" in terms:
        reach = max(reach, ar_increment_reach(tuple(model.ar_coefficients)))
    return reach


def _flicker_tail_bound(memory: _LongMemory, m_i: int, m_j: int, inner: int, count: int) -> float:
    """Bound on Σ N c² outside the δ window: 2 K (m_i² m_j²)² Σ_{k≥V} γ_z(k)² (module text)."""
    model = memory.model
    if "flicker" not in model.terms():
        return 0.0
    d = float(model.flicker_d)
    V = max(1, inner)
    # γ_z(V) of the unit 1/f term, FLICKER_INCREMENT_AUTOCOVARIANCE = C_d / (V + d − 1)^(3 − 2d) (rising).
    unit_gamma = float(flicker_increment_difference(np.array([float(V)]), d)[0])
    gamma_V = abs(float(model.flicker_variance) * unit_gamma)
    tail = gamma_V**2 * (1.0 + (V + 2.0 - d) / (5.0 - 4.0 * d))
    return 2.0 * count * (float(m_i) ** 2 * float(m_j) ** 2) ** 2 * tail


def _lag_range(model: NoiseModel, m_i: int, m_j: int, K_i: int, K_j: int, estimator: str) -> tuple[int, int]:
    """The offsets δ = first … last whose c_ij a lag sum needs: every offset of the record for the
    overlapping estimator (short records), else the window of the finite lag sum (module text)."""
    if estimator == "overlapping":
        return -(K_i - 1), K_j - 1
    reach = _lag_window(model, m_i, m_j)
    return max(-(K_i - 1) * m_i, -2 * m_j - reach), min((K_j - 1) * m_j, 2 * m_i + reach)


def _place_lags(buffer: np.ndarray, gamma: np.ndarray, low: int, high: int) -> None:
    """Write γ(|x|) for x = low … high into buffer[1 + x − low] where the lag |x| < len(gamma)."""
    held = len(gamma)
    if low < 0:  # x = start … stop (negative), lags −start … −stop, in decreasing order
        start, stop = max(low, 1 - held), min(high, -1)
        if start <= stop:
            buffer[1 + start - low : 2 + stop - low] = gamma[-start : -stop - 1 : -1]
    start, stop = max(low, 0), min(high, held - 1)
    if start <= stop:
        buffer[1 + start - low : 2 + stop - low] = gamma[start : stop + 1]


class _LongMemory:
    """c_ij(δ) = Σ_u g_i[u] A_j(δ − 2m_i + 2 + u) with A_j(x) = Σ_u g_j[u] γ_z(x + u), g the triangle
    B_m⋆B_m: each triangle applied as two moving sums (cumulative sums) in one buffer holding γ_z over
    the lags the pair's offsets reach, so that a pair costs one array of O(last − first + m_i + m_j).

    γ_z is held once: up to its last non-zero lag for white, rate random walk, quantization and AR terms,
    and for 1/f up to the record length, which bounds every lag a pair of ``pairs`` (m_i, m_j, K_i, K_j)
    reaches (the same length for every fit of a record, so that the 1/f autocovariance is computed once).
    """

    def __init__(
        self, model: NoiseModel, pairs: list[tuple[int, int, int, int]], estimator: str, length: int
    ) -> None:
        self.model = model
        extent = 1
        for m_i, m_j, K_i, K_j in pairs:
            first, last = _lag_range(model, m_i, m_j, K_i, K_j, estimator)
            extent = max(extent, 2 * m_i - 2 - first + 1, last + 2 * m_j - 2 + 1)
        terms = model.terms()
        # The other terms' γ_z vanish beyond the AR envelope's reach (values below do not depend on lags).
        finite = 4 + (ar_increment_reach(tuple(model.ar_coefficients)) if "ar" in terms else 0)
        self.scale: float | None = None
        if "flicker" not in terms:
            self.gamma = model.increment_autocovariance(min(extent, finite))
            return
        # σ_f² γ_f, then the model's whole sum where the other terms reach: the same values as
        # model.increment_autocovariance, taken from the shared unit 1/f autocovariance as each window
        # is filled, so that no scaled copy of the record's length is held.
        lags = max(extent, length)
        self.gamma = unit_flicker_increment_autocovariance(model.flicker_d, lags)
        self.scale = float(terms["flicker"])
        self.head = model.increment_autocovariance(min(finite, lags))

    def _window(self, low: int, high: int) -> np.ndarray:
        """γ_z(|x|) for x = low … high behind one free slot (zero beyond the lags held)."""
        buffer = np.zeros(high - low + 2)
        _place_lags(buffer, self.gamma, low, high)
        if self.scale is not None:
            buffer *= self.scale
            _place_lags(buffer, self.head, low, high)
        return buffer

    def cross_covariance(self, m_i: int, m_j: int, first: int, last: int) -> np.ndarray:
        """c_ij(δ) for δ = first … last."""
        buffer = self._window(first - 2 * m_i + 2, last + 2 * m_j - 2)
        correlated = _twice_moving_sum(buffer, m_j)  # A_j at x = first − 2m_i + 2 … last, γ_z ⋆ g_j
        return _twice_moving_sum(correlated, m_i)[1:]  # c_ij at δ = first … last


#: Entries per block of the in-place moving difference (bounds the copy NumPy makes of an overlapping input).
_MOVING_BLOCK = 1 << 18


def _moving_sum_in_place(values: np.ndarray, m: int) -> np.ndarray:
    """Σ_{l=k}^{k+m−1} v[l] for k = 0 … len(v) − m, v = values[1:], written over ``values``; returns the
    sums behind one free slot (a view of ``values``). values[0] is a free slot: it becomes the 0 that
    starts the cumulative sum C, and each sum C[k+m] − C[k] is stored at k + m, from the top in blocks
    (an entry is overwritten only after every difference that reads it)."""
    values[0] = 0.0
    np.cumsum(values, out=values)
    top = len(values)
    while top > m:
        bottom = max(m, top - _MOVING_BLOCK)
        values[bottom:top] -= values[bottom - m : top - m]
        top = bottom
    return values[m - 1 :]


def _twice_moving_sum(values: np.ndarray, m: int) -> np.ndarray:
    """The triangle g_m = B_m ⋆ B_m applied to values[1:] as two moving sums of length m, in place
    (values[0] is a free slot, as the result's first entry is); g_1 = (1)."""
    if m == 1:
        return values
    return _moving_sum_in_place(_moving_sum_in_place(values, m), m)


def _lag_sum(memory: _LongMemory, m_i: int, m_j: int, K_i: int, K_j: int) -> tuple[float, float]:
    """(Σ N c², bound on the neglected tail) by the finite lag sum over a window of δ (non-overlapping):
    δ = m_j b − m_i a = m_i t (m_i divides m_j), summed in blocks of t. On the diagonal N c² is even in
    δ (stationary increments), so only δ ≥ 0 is computed, the terms at δ > 0 counted twice."""
    reach = _lag_window(memory.model, m_i, m_j)
    low, high = _lag_range(memory.model, m_i, m_j, K_i, K_j, "non-overlapping")
    ratio = m_j // m_i
    diagonal = m_i == m_j and K_i == K_j
    t_first, t_last = 0 if diagonal else -(-low // m_i), high // m_i
    c = memory.cross_covariance(m_i, m_j, t_first * m_i, t_last * m_i)[::m_i]
    total = 0.0
    for start in range(t_first, t_last + 1, _MOVING_BLOCK):
        t = np.arange(start, min(start + _MOVING_BLOCK, t_last + 1))
        first = np.maximum(0, -((-t) // ratio))
        last = np.minimum(K_j - 1, (K_i - 1 + t) // ratio)
        counts = np.maximum(last - first + 1, 0).astype(np.float64)
        if diagonal:
            counts[t > 0] *= 2.0
        part = c[start - t_first : start - t_first + len(t)]
        total += float(np.einsum("i,i,i->", counts, part, part))
    bound = _flicker_tail_bound(memory, m_i, m_j, reach + 3, min(K_i, K_j)) if reach else 0.0
    return total, bound


# --- public ---------------------------------------------------------------------------------------


def _checked_sizes(tau_samples: Any, length: Any) -> tuple[np.ndarray, int]:
    """(the cluster sizes m as int64, the record length n) after checking them: n an integer ≥ 2, each m
    an integer ≥ 1 with 2m ≤ n (two clusters of m samples at least)."""
    length = check_positive_integer("length", length, minimum=2)
    sizes = cluster_sizes(tau_samples, "tau_samples")
    if np.any(2 * sizes > length):
        wrong = int(sizes[2 * sizes > length][0])
        raise ValueError(
            f"tau_samples: m={wrong} is outside 1 … {length // 2}: a record of length={length} samples "
            "holds two clusters of at most n/2 samples"
        )
    return sizes, length


def _terms_count(sizes: np.ndarray, length: int, estimator: str) -> np.ndarray:
    return length - 2 * sizes + 1 if estimator == "overlapping" else length // sizes - 1


#: Records up to this length sum the overlapping lag sums over every lag (O(n) per pair, exact); longer
#: ones use :mod:`carousel_theory.lag_quadrature` (cost independent of n, proved bound).
EVERY_LAG_LENGTH = 1 << 15


def _every_lag_sum(memory: _LongMemory, m_i: int, m_j: int, K_i: int, K_j: int) -> float:
    """Σ_δ N c² over every lag −(K_i − 1) … K_j − 1 of a short record (no truncation, no bound)."""
    c = memory.cross_covariance(m_i, m_j, -(K_i - 1), K_j - 1)
    deltas = np.arange(-(K_i - 1), K_j)
    counts = np.minimum(K_i - 1, K_j - 1 - deltas) - np.maximum(0, -deltas) + 1
    return float(np.einsum("i,i,i->", counts.astype(np.float64), c, c))


def _pair_sum(
    model: NoiseModel,
    engine: _LongMemory | None,
    m_i: int,
    m_j: int,
    K_i: int,
    K_j: int,
    estimator: str,
) -> tuple[float, float]:
    """(Σ N c², bound on its error) of one pair by the exact integers or the lag sums (the lag quadrature
    takes its pairs all at once: :func:`_pair_sums`)."""
    if engine is None:
        return _finite_sum(model, m_i, m_j, K_i, K_j), 0.0
    if estimator == "overlapping":
        return _every_lag_sum(engine, m_i, m_j, K_i, K_j), 0.0
    return _lag_sum(engine, m_i, m_j, K_i, K_j)


def _engine(
    model: NoiseModel, arguments: list[tuple[int, int, int, int]], length: int, estimator: str
) -> LagModel | _LongMemory | None:
    """None (white, RRW, quantization: exact integers), every lag (short records), or the quadrature."""
    long_terms = any(name in model.terms() for name in ("flicker", "ar"))
    if estimator == "overlapping" and not long_terms:
        return None
    if estimator == "overlapping" and length > EVERY_LAG_LENGTH:
        return LagModel.of(model)
    return _LongMemory(model, arguments, estimator, length)


def _pair_sums(
    model: NoiseModel,
    sizes: np.ndarray,
    terms: np.ndarray,
    length: int,
    estimator: str,
    pairs: list,
    bound: bool = True,
    rule: QuadratureRule = PROVED_RULE,
) -> list[tuple[float, float]]:
    """(Σ N c², error bound) of each (i, j) in ``pairs``; the lag quadrature takes them all at once, by
    ``rule`` (its bound NaN without ``bound``)."""
    arguments = [(int(sizes[i]), int(sizes[j]), int(terms[i]), int(terms[j])) for i, j in pairs]
    engine = _engine(model, arguments, length, estimator)
    if isinstance(engine, LagModel):
        return counted_square_sums(engine, arguments, bounds=bound, rule=rule)
    return [_pair_sum(model, engine, *pair, estimator) for pair in arguments]


def _upper_pairs(count: int) -> list[tuple[int, int]]:
    return [(i, j) for j in range(count) for i in range(j + 1)]


def _assembled(
    sizes: np.ndarray, terms: np.ndarray, sums: Sequence[tuple[float, float]]
) -> tuple[np.ndarray, np.ndarray]:
    """(Σ N c² / scale, error bound / scale) as matrices from the sums of :func:`_upper_pairs`."""
    count = len(sizes)
    covariance, bound = np.empty((count, count)), np.zeros((count, count))
    for (i, j), (total, tail) in zip(_upper_pairs(count), sums, strict=True):
        scale = 2.0 * float(sizes[i]) ** 2 * float(sizes[j]) ** 2 * int(terms[i]) * int(terms[j])
        covariance[i, j] = covariance[j, i] = total / scale
        bound[i, j] = bound[j, i] = tail / scale
    return covariance, bound


def _covariance_matrix(
    model: NoiseModel, sizes: np.ndarray, length: int, estimator: str, bound: bool, rule: QuadratureRule
) -> tuple[np.ndarray, np.ndarray]:
    """(Σ N c² / scale, error bound / scale) for every pair of non-decreasing ``sizes``."""
    terms = _terms_count(sizes, length, estimator)
    pairs = _upper_pairs(len(sizes))
    return _assembled(sizes, terms, _pair_sums(model, sizes, terms, length, estimator, pairs, bound, rule))


def allan_estimate_covariance(
    model: NoiseModel,
    tau_samples: Any,
    length: int,
    *,
    estimator: str = "overlapping",
    bound: bool = True,
    rule: QuadratureRule = PROVED_RULE,
) -> TauCovariance:
    """Covariance of the Allan variance estimates at m = ``tau_samples`` in a record of ``length`` samples.

    Exact in closed form for white, rate random walk and quantization with the overlapping estimator; 1/f
    and AR summed over every lag of a short record, by the lag quadrature (proved bound) of a long one,
    and by a finite lag sum with the 1/f tail bounded for the non-overlapping estimator (module text).
    For the non-overlapping estimator every m must divide the larger ones. ``bound=False`` skips the lag
    quadrature's error bound (the same covariance; its ``truncation_bound`` entries are then NaN), for
    callers that use the covariance alone. ``rule`` is the lag quadrature's
    (:class:`~carousel_theory.lag_plan.QuadratureRule`): :data:`~carousel_theory.lag_plan.WEIGHTS_RULE`
    takes about a quarter of the time of the default where seven digits of the values suffice (a fit's
    weights; the two rules' values compared: :mod:`carousel_theory.lag_quadrature`, module text: Rules).
    """
    sizes, length = _checked_sizes(tau_samples, length)
    if estimator not in ("overlapping", "non-overlapping"):
        raise ValueError(f"estimator={estimator!r}: must be 'overlapping' or 'non-overlapping'")
    if not model.terms():
        raise ValueError(f"model={model!r}: the model has no noise component")
    if estimator == "non-overlapping" and any(int(b) % int(a) for a in sizes for b in sizes if b >= a):
        raise ValueError(
            f"tau_samples={sizes!r}: for the non-overlapping estimator each cluster size must divide the "
            "larger ones (use octave τ)"
        )
    order = np.argsort(sizes, kind="stable")  # summed in increasing τ (the window of A_j covers m_i ≤ m_j)
    covariance, bounds = _covariance_matrix(model, sizes[order], int(length), estimator, bound, rule)
    return _in_given_order(model, sizes, covariance, bounds, np.argsort(order), estimator)


def _in_given_order(
    model: NoiseModel,
    sizes: np.ndarray,
    covariance: np.ndarray,
    bound: np.ndarray,
    inverse: np.ndarray,
    estimator: str,
) -> TauCovariance:
    """The :class:`TauCovariance` of matrices in ascending τ, put back in the order of ``sizes``."""
    covariance, bound = covariance[np.ix_(inverse, inverse)], bound[np.ix_(inverse, inverse)]
    allan = model.allan_variance(sizes)
    edf = 2.0 * allan**2 / np.diag(covariance)
    return TauCovariance(sizes, covariance, allan, edf, bound, estimator)


def allan_estimate_variance(
    model: NoiseModel,
    tau_samples: Any,
    length: int,
    *,
    estimator: str = "overlapping",
    rule: QuadratureRule = PROVED_RULE,
) -> np.ndarray:
    """Var σ̂²(m) at each m (the diagonal of :func:`allan_estimate_covariance`, without the other pairs;
    ``rule`` as there)."""
    sizes, length = _checked_sizes(tau_samples, length)
    if estimator not in ("overlapping", "non-overlapping"):
        raise ValueError(f"estimator={estimator!r}: must be 'overlapping' or 'non-overlapping'")
    terms = _terms_count(sizes, length, estimator)
    order = np.argsort(sizes, kind="stable")
    diagonal = [(k, k) for k in range(len(sizes))]
    sums = _pair_sums(model, sizes[order], terms[order], int(length), estimator, diagonal, False, rule)
    result = np.empty(len(sizes))
    for i, (total, _) in zip(order.tolist(), sums, strict=True):
        m, K = int(sizes[i]), int(terms[i])
        result[i] = total / (2.0 * float(m) ** 4 * K * K)
    return result
