"""Σ_δ N_ij(δ) c_ij(δ)² of the overlapping Allan-variance covariance without a sum over the record.

Setting: :mod:`carousel_theory.tau_covariance`. c_ij(δ) = Σ_q w_q H(q − δ) with H the fourth sum of the
model's increment autocovariance (:mod:`carousel_theory.increment_sums`): the finite terms (white, rate
random walk, quantization) through one finite γ_z, the 1/f term in closed form, and the AR term as white
noise of its long-run variance plus its geometric modes (:mod:`carousel_theory.ar_modes`; where the
modes are not accurate, through the finite γ_z truncated at its reach). Each H is smooth away from
x = −2, so c is smooth away from the breakpoints b_q = q + 2; N_ij is linear between 0 and K_j − K_i.

Scheme (the plan of each pair: :mod:`carousel_theory.lag_plan`)
    Exact: every integer lag within the rule's ``exact_reach`` of a breakpoint (or the finite terms'
    reach: AR modes that turn faster than they decay, a truncated AR γ_z; module text: AR modes).
    Elsewhere: blocks of consecutive lags, each at most ``block_ratio`` times its distance to the
    nearest breakpoint (lengths ⌊2^{k/4}⌋, the largest that fits, so that few rules serve every block),
    summed by the p-point discrete Gauss rule of the uniform measure on the block's
    integers (nodes by Golub–Welsch from the discrete Chebyshev recurrence β_k = k²(L² − k²)/(4(4k² − 1))).
    On a block the finite terms are cubic polynomials, so N c² is a polynomial of degree ≤ 7 plus the 1/f
    and AR-mode parts; the rule is exact for degree ≤ 2p − 1.

Error bound (proved; reported per entry as ``truncation_bound``)
    Let P interpolate c at the p nodes; N P² has degree ≤ 2p − 1 and agrees with N c² at the nodes, so
    the rule returns Σ N P² exactly and the error is Σ N (c² − P²) = Σ N e (2P + e), e = c − P =
    c^{(p)}(ξ) π_p/p! with π_p the monic orthogonal polynomial. With B ≥ sup|c^{(p)}|/p! on the block,
    Cauchy–Schwarz and Σ π_p² = h_p = β_0 β_1 ⋯ β_p, Σ P² = Q(c²):
        |error| ≤ B · max N · (2 √(h_p Q(c²)) + B h_p).
    B: c^{(p)} is the 1/f part and the AR modes' (p ≥ 4). The modes add
    Σ_q |w_q| θ Σ_i |C_i| |Log λ_i|^p |λ_i|^{j_q}/p! (:func:`carousel_theory.ar_modes.mode_derivative_bound`,
    j_q the block's distance to b_q). For the 1/f part, on each branch H = K_d F(j), j = |x + 2|, F(j) =
    Γ(j + 1 + d)/Γ(j − d) = Γ(z + s)/Γ(z), z = j − d, s = 1 + 2d ∈ (1, 3). For p > s,
    F^{(p)}(z) = (−1)^p/Γ(−s) ∫_0^∞ t^p e^{−(z+s)t} (1 − e^{−t})^{−s−1} dt (the Beta integral, continued
    analytically in s), so F^{(p)} has one sign and |F^{(p)}| decreases; hence
    |F^{(p)}(j)| ≤ |Δ^p F(j − p)| = |(s)_p↓| Γ(j − p + 1 + d)/Γ(j − d) (mean value over a B-spline), and
    B ≤ |K_d| σ_w² Σ_q |w_q| |Δ^p F(j_q − p)|/p!, j_q the block's distance to b_q. In the far tail, where
    c(δ) = Σ_u W(u) γ_z(δ + u) with W ≥ 0, Σ W = m_i² m_j² and −γ_z completely monotone
    (Γ(x + d − 1)/Γ(x + 2 − d), the same Beta integral), also B ≤ m_i² m_j² |Δ^p γ_z(x₀ − p)|/p!.

Far tail (distance from the support ≥ ``FAR`` times its width)
    The nine-term difference of H is ill-conditioned there (Σ_q |w_q H|/|c| grows like
    (distance/width)⁴ and measures 10⁶–10⁸ from 0.5 to 3 widths out at m_i = 8, m_j = 128, d from 0.3
    to 0.95), so c is taken from the
    Newton series c(δ) = Σ_{r≤R} ν_r Δ^r γ_z(x₀), x₀ the nearest argument, ν_r = Σ_v W(v) C(v, r) (the
    coefficients of B_{m_i}(1 + t)² B_{m_j}(1 + t)²), with remainder ≤ ν_{R+1} |Δ^{R+1} γ_z(x₀ − R − 1)|
    (Newton's interpolation remainder and the monotone derivative above); that remainder is added to the
    bound through Σ w N e (2|c| + e). Pairs whose support is at most ``_DIRECT_WIDTH`` lags wide take c
    elsewhere from Σ_u W(u) γ_z(δ + u) directly (at integer lags, by γ_z evaluated once on the integers
    the lags reach and correlated with W, and outside the support at any lag). The finite terms' c is
    exactly 0 in the far tail and their direct part is the nine-term sum, so the partition into exact /
    direct / far does not depend on whether the model has 1/f: one batch serves a fit's every step,
    whatever terms each holds at zero.

Many pairs (:func:`counted_square_sums`, all the τ pairs of one covariance) are evaluated together:
each pair is a row of :class:`_Pairs` (its ramp positions and weights, padded to nine with weight 0, and
m_i, m_j, K_i, K_j), every lag and Gauss node carries the index of its row, and each step above (the
partition into exact / direct / far, the nine-term sum, the Newton series, the derivative bounds) is one
array operation over all pairs (only the narrow pairs' direct sums and the Newton moments loop over
rows); the sums and bounds are reduced per row by ``np.bincount`` in the
order of the row's own lags. At the exact lags H is needed only at integers: runs of consecutive lags
give runs of arguments q − δ, merged across pairs (octave pairs share about thirty in thirty-one), H is
evaluated once on their union and gathered by the run's offset. Everything is element by element and
each row is reduced in its own order, so each pair's sum and bound are, bit for bit, those of the pair
alone (:func:`counted_square_sum` is the batch of one). A lag's nine products w_q H(q − δ) are added
in the ramps' order on every path (:func:`_ramp_sum`, and the sparse rows of the gathers below), so
that its c does not depend on how its H was gathered beyond the rounding of a fused multiply-add.

What does not depend on the model's variances or its d — the plans, the partition, the union of the
exact lags' integer arguments and, for each lag, its nine weights at the columns of its arguments (a
sparse matrix, so that c at every lag is one product with H at the distinct arguments) — is a
:class:`PairBatch`, kept (:func:`pair_batch`) for the next covariance of the same pairs, so that a fit's
iterations pay for it once. At the Gauss nodes H is likewise evaluated once per distinct argument: a
node δ = f + o of a block starting at f has the arguments (q − f) − o, and blocks grown from breakpoints
at equal distances share their rows (q − f, block length) — for octave pairs about one in nine is new.
At the narrow pairs' integer lags γ_z is evaluated once on the integers the lags of all of them reach.
:func:`term_values` (the values of one model, or of one term) and :func:`combined_sums` (Σ N c² and the
bound for c = Σ_a θ_a c_a) are the two halves of :func:`counted_square_sums`; a caller that needs the
sums alone (a fit's weights) skips the bound (``bounds=False``: no far-tail remainders, no derivative
bounds, the same sums).

Rounding is not in the bound. A nine-term value of c carries the rounding of Σ_q w_q H(q − δ), a few ulps
of Σ_q |w_q H(q − δ)|, which from half a width to FAR widths out is 10⁶–10⁸ times |c|; a direct value
(positive weights, γ_z of one sign outside the support) about len(W) ulps of |c|; the Newton series a few
ulps of |c|. :func:`rounding_allowances` turns that into an allowance on each pair's sum,
Σ N (2|c| ρ + ρ²) over the exact lags and the Gauss nodes (N times the node's weight), with
ρ = ROUNDING_ULPS · u · S, S = Σ_q |w_q H| at a nine-term value, len(W)·|c| at a direct one and |c| in the
far tail (u the unit roundoff). Measured: one nine-term value differs from the direct sum by up to about
25 ulps of Σ_q |w_q H| (d = 0.875, m_i = 50, m_j/m_i = 16: H itself carries several ulps), hence
ROUNDING_ULPS = 64; the quadrature's difference from the every-lag sum beyond the proved bound reaches
1.7 times the allowance taken at one ulp (about 2,500 random pairs, d from 0.02 to 0.98, m_j/m_i up to
16); the every-lag sum itself is within 1e-13 of one taking c outside the support from the direct sum.
A fixed 1e-11 relative allowance is not enough: at d ≈ 0.77, m_j/m_i = 16 the sum moves by 1.04e-11
relative when the plan changes which lags are exact, and at d ≈ 0.92, m_i = 50, m_j/m_i = 16 by
1.04e-11 with the plan unchanged.

Rules (:class:`~carousel_theory.lag_plan.QuadratureRule`). The bound above holds for any rule.
:data:`~carousel_theory.lag_plan.PROVED_RULE` (12 points, blocks at most half their distance to the
breakpoint, 32 exact lags) keeps it below 10⁻¹¹ of the sum for the models a gyro fit meets and is the
default of every sum here. :data:`~carousel_theory.lag_plan.WEIGHTS_RULE` (4 points, the fewest that
integrate the finite terms' N c², a polynomial of degree 7 on a block, exactly; blocks up to their whole
distance, 16 exact lags) has a quarter of the Gauss nodes and of the exact lags (octave τ of 10⁶
samples, white + RRW + 1/f + AR(1): 73,764 nodes and 42,045 lags against 291,912 and 149,676) and costs
a little over a quarter (0.013 s per covariance against 0.047 s; 0.043 s against 0.13 s for the first,
which builds the plan). Its values are within 2·10⁻⁷ of the every-lag sum beyond both sums' rounding
allowances for pairs with d from 0.02 to 0.98, with and without AR (measured up to 1.1·10⁻⁷, at d = 0.5
and m_j/m_i = 16, on a grid of d, m_i, m_j/m_i and lengths), and within 2·10⁻⁷ of √(C_ii C_jj) of
PROVED_RULE's covariance at octave τ of 10⁶ samples for a fit's models (measured up to 8·10⁻⁸, at
d = 0.02 beside a Gauss–Markov term of φ = 0.99; tests). A fit
weights its GLS with it: its C is evaluated at an estimate known to a few per cent, and a relative
error ε in C moves the estimate and the χ² by about ε of themselves (10⁻⁸ measured on the benchmark's
records), where an 8-point rule (10⁻¹¹) cost 1.5 times as much per covariance. The Allan variance's χ²
intervals take their degrees of freedom from it (a quantile needs far fewer digits).

AR modes. The modes' part of H, G(|x + 2|) = Re Σ_i C_i λ_i^{|x+2|}, is analytic on each side of x = −2
and continued between the integers, so Gauss blocks cover it like the 1/f part, with its derivative in B,
and the exact zone does not grow with the correlation time (a Gauss–Markov term of τ_c = 1000 samples
costs what one of 2 samples costs). In the far tail the Newton series carries the 1/f part and the
modes' nine-term sum is added (0 where every |λ_i|^j has underflowed); its rounding scale there is
|c| plus Σ_q |w_q θ G|. Modes that turn faster than they decay (a negative root, a complex pair of
high frequency) would make B useless while they are alive: the exact zone then grows to their reach
(:attr:`carousel_theory.ar_modes.ArModes.rough_reach`), as it does with the truncated γ_z when the
modes are not accurate. :meth:`LagModel.of` rounds such a reach up to a multiple of ``REACH_STEP`` lags
(a longer reach only adds exact lags), so that the records of one sensor, whose estimated AR
coefficients differ in the third digit, share one plan (:func:`pair_batch`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace

import numpy as np
from scipy import sparse, special

from carousel_theory.ar_modes import (
    ArModes,
    ar_modes,
    fourth_sum_of_modes,
    mode_derivative_bound,
    underflow_distance,
)
from carousel_theory.increment_sums import (
    finite_fourth_sum,
    flicker_fourth_sum_at_distance,
    flicker_increment_difference,
    flicker_normalisation,
    rising_factorial,
)
from carousel_theory.lag_plan import (
    PROVED_RULE,
    WEIGHTS_RULE,
    LagPlan,
    QuadratureRule,
    plan_pairs,
    ramp_positions,
)
from carousel_theory.noise_model import NoiseModel, ar_increment_reach, increment_autocovariance

__all__ = [
    "FAR",
    "PROVED_RULE",
    "WEIGHTS_RULE",
    "LagModel",
    "QuadratureRule",
    "counted_square_sum",
    "counted_square_sums",
    "rounding_allowances",
    "rounding_scales",
]

#: Beyond FAR support widths from the support, c comes from the Newton series of γ_z (the nine-term sum
#: of H is ill-conditioned there: Σ|w_q H|/|c| grows like (distance/width)⁴ and was already 10⁷–10⁸ at
#: 2.8 widths, measured for m_i = 8, m_j = 128).
FAR = 4
_NEWTON_TERMS = 24
#: Ulps of the scale S of each value of c allowed for its rounding (module text: Rounding).
ROUNDING_ULPS = 64
#: The finite terms' reach is rounded up to a multiple of this many lags (module text).
REACH_STEP = 32
#: Pairs whose support is at most this wide take c at integer lags from Σ_u W(u) γ_z(δ + u) directly.
_DIRECT_WIDTH = 256


@dataclass(frozen=True)
class LagModel:
    """The model's fourth sums, prepared once per covariance: a table of the finite H near x = −2, the
    moments of the finite γ_z for the cubic beyond, the AR term's modes (any argument, module text: AR
    modes) and the 1/f parameters. ``reach``: the lags from a breakpoint that are summed one by one
    because of the finite terms (3, or the reach of AR modes that turn faster than they decay)."""

    finite_gamma: np.ndarray
    finite_total: float
    table_low: int
    table: np.ndarray
    flicker_variance: float
    flicker_d: float
    reach: int
    modes: ArModes | None = None
    mode_variance: float = 0.0

    @classmethod
    def of(cls, model: NoiseModel) -> LagModel:
        terms = model.terms()
        modes = ar_modes(tuple(float(c) for c in model.ar_coefficients)) if "ar" in terms else None
        if modes is not None:
            reach = max(3, modes.rough_reach)
        else:
            reach = max(3, ar_increment_reach(tuple(model.ar_coefficients))) if "ar" in terms else 3
        reach = -(-reach // REACH_STEP) * REACH_STEP if reach > 3 else reach
        gamma = np.zeros(reach + 1)
        finite = ("white", "rrw", "quantization") + (("ar",) if modes is None else ())
        for name in (name for name in finite if name in terms):
            taps = increment_autocovariance(name, reach + 1, ar_coefficients=model.ar_coefficients)
            gamma += terms[name] * taps
        if modes is not None:  # the AR term: white noise of its long-run variance, and its modes
            gamma += terms["ar"] * modes.long_run_variance * increment_autocovariance("white", reach + 1)
        total = terms.get("rrw", 0.0)  # Σ γ_z: 1 for the rate random walk, exactly 0 for the others
        low = -reach - 8
        table = finite_fourth_sum(gamma, np.arange(low, reach + 8), total=total)
        flicker = terms.get("flicker", 0.0)
        variance = terms.get("ar", 0.0) if modes is not None else 0.0
        return cls(gamma, total, low, table, flicker, float(model.flicker_d), reach, modes, variance)

    def fourth_sum(self, x: np.ndarray) -> np.ndarray:
        """Σ_t θ_t H_t(x) at points x (integers within the finite terms' reach of −2; any real x beyond),
        element by element: the table within reach + 6 of −2 (it spans −reach − 8 … reach + 7), the cubic
        beyond, the AR modes and 1/f."""
        distance = np.abs(x + 2.0)
        near = distance <= self.reach + 6
        result = np.zeros(np.shape(x))
        beyond = (x > 0) & ~near  # the cubic where the table ends (H is 0 on the far left)
        result[beyond] = _cubic(self, x[beyond])
        if np.any(near):
            result[near] = self.table[np.rint(x[near]).astype(np.int64) - self.table_low]
        if self.modes is not None:
            result += self.mode_variance * fourth_sum_of_modes(self.modes, distance)
        if self.flicker_variance:
            result += self.flicker_variance * flicker_fourth_sum_at_distance(distance, self.flicker_d)
        return result


def _cubic(lag_model: LagModel, x: np.ndarray) -> np.ndarray:
    """The finite H beyond its reach: M₀ p(x) + M₂ p''(x)/2, p(x) = (x + 1)(x + 2)(x + 3)/6."""
    gamma = lag_model.finite_gamma
    lags = np.arange(1, len(gamma), dtype=np.float64)
    second_moment = 2.0 * float(np.dot(gamma[1:], lags**2))
    return lag_model.finite_total * (x + 1) * (x + 2) * (x + 3) / 6 + second_moment * (x + 2) / 2


# --- the pair's geometry ------------------------------------------------------------------------------


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


#: The Gauss rules computed so far, by (L, p): kept for the process (a few hundred lengths at most).
_GAUSS_RULES: dict[tuple[int, int], tuple[np.ndarray, np.ndarray, float]] = {}


def _gauss_rule(length: int, points: int) -> tuple[np.ndarray, np.ndarray, float]:
    """(offsets in [0, L − 1], weights, log h_p) of the p-point Gauss rule of the uniform measure on
    {0, …, L − 1}: Golub–Welsch on the discrete Chebyshev recurrence (module text)."""
    return _gauss_rules((length,), points)[0]


def _gauss_rules(lengths: Sequence[int], points: int) -> list[tuple[np.ndarray, np.ndarray, float]]:
    """:func:`_gauss_rule` of each length; those not yet known from one stacked ``eigh`` (LAPACK's
    routine on each matrix in turn: the same values as one call per length)."""
    missing = sorted({int(length) for length in lengths if (int(length), points) not in _GAUSS_RULES})
    if missing:
        k = np.arange(1, points + 1, dtype=np.float64)
        size = np.array(missing, dtype=np.float64)[:, None]
        beta = k**2 * (size**2 - k**2) / (4.0 * (4.0 * k**2 - 1.0))
        jacobi = np.zeros((len(missing), points, points))
        above = np.arange(points - 1)
        jacobi[:, above, above + 1] = np.sqrt(beta[:, :-1])
        nodes, vectors = np.linalg.eigh(jacobi + np.transpose(jacobi, (0, 2, 1)))
        for row, length in enumerate(missing):
            rule = (
                nodes[row] + (length - 1) / 2.0,
                length * vectors[row, 0] ** 2,
                math.log(length) + float(np.sum(np.log(beta[row]))),
            )
            _GAUSS_RULES[(length, points)] = rule
    return [_GAUSS_RULES[(int(length), points)] for length in lengths]


# --- bounds and the far-tail series -----------------------------------------------------------------


def _falling(value: float, order: int, skip: int | None = None) -> float:
    return math.prod(value - k for k in range(order) if k != skip)


def _branch_bound(distance: np.ndarray, d: float, p: int) -> np.ndarray:
    """|d^p/dx^p H(x)|/p! at distance j = |x + 2| ≥ p + 1 from the branch point, unit σ_w² (module text):
    |K_d (s)_p↓| Γ(j − p + 1 + d)/Γ(j − d)/p!, the factor s − 2 = 2(d − ½) cancelling the pole of K_d."""
    s = 1.0 + 2.0 * d
    scale = flicker_normalisation(d) / (16.0 * (d - 1.0) * d * (d + 0.5)) * 2.0 * _falling(s, p, skip=2)
    return abs(scale) / rising_factorial(distance - p + 1.0 + d, p - 1.0 - 2.0 * d) / math.factorial(p)


@functools.lru_cache(maxsize=256)
def _binomials(m: int) -> np.ndarray:
    """C(m, r), r = 1 … R + 2 (the coefficients of B_m(1 + t) = ((1 + t)^m − 1)/t, shifted)."""
    return special.comb(m, np.arange(1, _NEWTON_TERMS + 3), exact=False)


@functools.lru_cache(maxsize=4096)
def _factorial_moments(m_i: int, m_j: int, scale: float) -> np.ndarray:
    """ν_r / S^r, r = 0 … R + 1: the coefficients of B_{m_i}(1 + t)² B_{m_j}(1 + t)² in t = τ/S."""
    terms = _NEWTON_TERMS + 2
    powers = scale ** -np.arange(terms, dtype=np.float64)
    factors = [_binomials(m) * powers for m in (m_i, m_j)]
    result = np.array([1.0])
    for factor in (factors[0], factors[0], factors[1], factors[1]):
        result = np.convolve(result, factor)[:terms]
    return result


@dataclass(frozen=True)
class _Pairs:
    """Many pairs as rows (:func:`counted_square_sums`): ramp positions and weights (rows padded at the
    first position with weight 0), and m_i, m_j, K_i, K_j as floats. Every evaluation takes an ``owner``
    array (the row of each lag), so all the pairs of one covariance are evaluated by the same few array
    operations, element by element: a pair's values do not depend on the others in the batch."""

    positions: np.ndarray
    weights: np.ndarray
    m_i: np.ndarray
    m_j: np.ndarray
    K_i: np.ndarray
    K_j: np.ndarray

    @classmethod
    def of(cls, pairs: Sequence[_Pair]) -> _Pairs:
        columns = 9  # at most nine ramps; a fixed width keeps each row's sum in one order
        positions, weights = np.empty((len(pairs), columns)), np.zeros((len(pairs), columns))
        for row, pair in enumerate(pairs):
            used = len(pair.positions)
            positions[row, :used], positions[row, used:] = pair.positions, pair.positions[0]
            weights[row, :used] = pair.weights
        sizes = np.array([(p.m_i, p.m_j, p.K_i, p.K_j) for p in pairs], dtype=np.float64).reshape(-1, 4)
        return cls(positions, weights, *sizes.T)

    def count(self, owner: np.ndarray, delta: np.ndarray) -> np.ndarray:
        """N_ij(δ), linear between the kinks 0 and K_j − K_i (also at non-integer δ inside a piece)."""
        return np.minimum(self.K_i[owner] - 1, self.K_j[owner] - 1 - delta) - np.maximum(0, -delta) + 1

    def nearest(self, owner: np.ndarray, lags: np.ndarray) -> np.ndarray:
        """x₀, the argument of γ_z nearest to zero over the support of W at each lag (≤ 0 inside it)."""
        return np.maximum(lags - 2 * self.m_i[owner] + 2, -lags - 2 * self.m_j[owner] + 2)

    def width(self) -> np.ndarray:
        """The support's width 2m_i + 2m_j − 4 (at least 1), the scale of the far-tail series."""
        return np.maximum(2 * self.m_i + 2 * self.m_j - 4, 1)


@dataclass(frozen=True)
class _FarTail:
    """What the far-tail series needs at its lags that does not depend on the model: the lags' pairs
    (``owner``), their nearest arguments x₀, the series' scale S (the support's width) and ν_r / S^r,
    r = 0 … R + 1, of each lag's pair (one row per r), so that a batch forms them once for every model."""

    owner: np.ndarray
    nearest: np.ndarray
    scale: np.ndarray
    moments: np.ndarray

    @classmethod
    def of(cls, pairs: _Pairs, owner: np.ndarray, nearest: np.ndarray) -> _FarTail:
        width = pairs.width()
        table = np.zeros((_NEWTON_TERMS + 2, len(pairs.m_i)))  # ν_r / S^r of each row, a row per order
        for row in np.unique(owner).tolist():
            table[:, row] = _factorial_moments(int(pairs.m_i[row]), int(pairs.m_j[row]), float(width[row]))
        return cls(owner, nearest, width[owner], table[:, owner])


def _newton_series(
    lag_model: LagModel, tail: _FarTail, bounds: bool = True
) -> tuple[np.ndarray, np.ndarray | None]:
    """(c, bound on its error or None without ``bounds``) from Σ_{r≤R} ν_r Δ^r γ_z(x₀) at the far
    tail's nearest arguments x₀. Each step is formed in place in two buffers of the lags' length (the
    same operations, in the same order, as the plain expressions)."""
    d, nearest, scale, moments = lag_model.flicker_d, tail.nearest, tail.scale, tail.moments
    shifted = nearest + 2.0 - d  # x₀ + 2 − d; the ratio's denominator is shifted + r
    total, term = np.zeros_like(nearest), flicker_increment_difference(nearest, d)
    product, denominator = np.empty_like(nearest), np.empty_like(nearest)
    for r in range(_NEWTON_TERMS + 1):
        np.multiply(moments[r], term, out=product)
        total += product
        np.multiply(term, 2.0 * d - 3.0 - r, out=term)
        np.multiply(term, scale, out=term)
        np.divide(term, np.add(shifted, r, out=denominator), out=term)
    total *= lag_model.flicker_variance
    if not bounds:
        return total, None
    order = _NEWTON_TERMS + 1
    difference = np.abs(flicker_increment_difference(nearest - order, d, order))
    remainder = moments[order] * difference * scale**order
    return total, lag_model.flicker_variance * remainder


# --- the sum --------------------------------------------------------------------------------------


def _derivative_bounds(
    pairs: _Pairs, lag_model: LagModel, owner: np.ndarray, ends: np.ndarray, points: int
) -> np.ndarray:
    """B ≥ sup|c^{(p)}|/p!, p = ``points``, on each block (first, last) of the pair ``owner``: for 1/f the
    branch bound, and in the far tail the bound through W ≥ 0 and the monotone derivative of γ_z,
    whichever is smaller; plus the AR modes' (:func:`carousel_theory.ar_modes.mode_derivative_bound` at
    each ramp's distance)."""
    bound = np.zeros(len(ends))
    if not (lag_model.flicker_variance or lag_model.modes is not None):
        return bound
    breakpoints = pairs.positions[owner] + 2.0
    distance = np.minimum(np.abs(ends[:, :1] - breakpoints), np.abs(ends[:, 1:] - breakpoints))
    weights = np.abs(pairs.weights[owner])
    if lag_model.flicker_variance:
        flicker = _flicker_derivative_bound(pairs, lag_model, owner, ends, distance, weights, points)
        bound += lag_model.flicker_variance * flicker
    if lag_model.modes is not None:
        modal = mode_derivative_bound(lag_model.modes, distance, points)
        bound += lag_model.mode_variance * np.einsum("ij,ij->i", modal, weights)
    return bound


def _flicker_derivative_bound(
    pairs: _Pairs,
    lag_model: LagModel,
    owner: np.ndarray,
    ends: np.ndarray,
    distance: np.ndarray,
    weights: np.ndarray,
    p: int,
) -> np.ndarray:
    """The 1/f part of :func:`_derivative_bounds` at unit σ_w² (module text: Error bound), ``distance``
    from each block to each breakpoint, ``weights`` = |w_q| and p Gauss points."""
    d = lag_model.flicker_d
    bound = np.einsum("ij,ij->i", _branch_bound(distance, d, p), weights)
    nearest = np.minimum(pairs.nearest(owner, ends[:, 0]), pairs.nearest(owner, ends[:, 1]))
    tail = nearest > p + 2
    if np.any(tail):
        mass = pairs.m_i[owner[tail]] ** 2 * pairs.m_j[owner[tail]] ** 2
        far = mass * np.abs(flicker_increment_difference(nearest[tail] - p, d, p))
        bound[tail] = np.minimum(bound[tail], far / math.factorial(p))
    return bound


def _far(
    pairs: _Pairs, owner: np.ndarray, lags: np.ndarray, reach: int, nearest: np.ndarray | None = None
) -> np.ndarray:
    """Where c comes from the far-tail series: at least FAR support widths and the finite terms' reach
    (+ 8) from the support (there the finite terms' c is exactly 0: the series carries the 1/f part, and
    the AR modes' nine-term sum is added)."""
    nearest = pairs.nearest(owner, lags) if nearest is None else nearest
    return (nearest >= FAR * pairs.width()[owner]) & (nearest >= max(reach + 8, _NEWTON_TERMS + 4))


def _partition(
    pairs: _Pairs, lag_model: LagModel, owner: np.ndarray, lags: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(x₀, far, direct, near): how c is taken at each lag (:func:`_batch_values`)."""
    return _partition_for(pairs, owner, lags, lag_model.reach)


def _partition_for(
    pairs: _Pairs, owner: np.ndarray, lags: np.ndarray, reach: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`_partition` for finite terms reaching ``reach`` lags: the same for a model with or without
    1/f, so that one batch serves both (a fit whose 1/f term is at 0 in one step and not in the next)."""
    nearest, width = pairs.nearest(owner, lags), pairs.width()[owner]
    far = _far(pairs, owner, lags, reach, nearest)
    # Narrow pairs at integer lags, or at any lag outside the support (where every δ + u keeps one sign
    # and γ_z is analytic).
    direct = ~far & (width <= _DIRECT_WIDTH) & ((lags == np.rint(lags)) | (nearest >= 1))
    return nearest, far, direct, ~far & ~direct


def _nine_term_sum(pairs: _Pairs, lag_model: LagModel, owner: np.ndarray, lags: np.ndarray) -> np.ndarray:
    """c_ij(δ) = Σ_q w_q H(q − δ) at ``lags`` of the pairs ``owner``."""
    values = lag_model.fourth_sum(pairs.positions[owner] - lags[:, None])
    weights = pairs.weights[owner]
    return _ramp_sum((values[:, k], weights[:, k]) for k in range(values.shape[1]))


def _modal_values(
    pairs: _Pairs, lag_model: LagModel, owner: np.ndarray, lags: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(Σ_q w_q θ G(|q − δ + 2|), Σ_q |w_q θ G(|q − δ + 2|)|) of the AR modes at ``lags`` of the pairs
    ``owner`` (in the far tail, where the finite terms' other parts vanish and the 1/f part is the Newton
    series), the nine products added in the ramps' order. Outside the support the nearest breakpoint is
    x₀ − 2 away (:meth:`_Pairs.nearest`); where every mode has underflowed there, both are 0."""
    assert lag_model.modes is not None
    total, magnitude = np.zeros(len(lags)), np.zeros(len(lags))
    alive = np.flatnonzero(pairs.nearest(owner, lags) - 2.0 < underflow_distance(lag_model.modes))
    if not len(alive):
        return total, magnitude
    owner, lags = owner[alive], lags[alive]
    distance = np.abs(pairs.positions[owner] - lags[:, None] + 2.0)
    values = lag_model.mode_variance * fourth_sum_of_modes(lag_model.modes, distance)
    weights = pairs.weights[owner]
    columns = range(values.shape[1])
    total[alive] = _ramp_sum((values[:, k], weights[:, k]) for k in columns)
    magnitude[alive] = _ramp_sum((np.abs(values[:, k]), np.abs(weights[:, k])) for k in columns)
    return total, magnitude


def _ramp_sum(products: Iterator[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """Σ_q H_q w_q over a lag's ramps, added in the ramps' order (every path to c adds them in this one
    order, so that a lag's value does not depend on how its H was gathered)."""
    total: np.ndarray | None = None
    for values, weights in products:
        product = values * weights
        total = product if total is None else np.add(total, product, out=total)
    assert total is not None
    return total


@dataclass(frozen=True)
class _Gathered:
    """c = Σ_q w_q H(q − δ) at many lags as H at distinct ``arguments`` and a sparse ``matrix`` whose row of
    each lag holds the weights w_q of its nine ramps at the columns of their arguments q − δ (a
    structure of the pairs alone, kept by :class:`PairBatch`). :meth:`values` is the matrix times H at
    the arguments: each row summed in the ramps' order, as :func:`_ramp_sum` sums the direct nine-term
    products, so that each value is the direct nine-term sum of the same H (bit for bit where the
    platform's sparse product does not fuse its multiply-adds; to a rounding of Σ|w_q H| where it does)."""

    arguments: np.ndarray
    matrix: sparse.csr_array

    def values(self, lag_model: LagModel) -> np.ndarray:
        if not self.matrix.shape[0]:
            return np.zeros(0)
        return np.asarray(self.matrix @ lag_model.fourth_sum(self.arguments))

    @classmethod
    def of(cls, arguments: np.ndarray, index: np.ndarray, weights: np.ndarray) -> _Gathered:
        """From the arguments, each lag's nine indices into them (rows) and its pair's nine weights."""
        return cls(arguments, _ramp_matrix(index, weights, len(arguments)))


def _ramp_matrix(index: np.ndarray, weights: np.ndarray, columns: int) -> sparse.csr_array:
    """The sparse matrix whose row r holds ``weights[r]`` at the columns ``index[r]``, in the ramps' order
    (a row's products are added in the order of its entries)."""
    rows, ramps = index.shape
    pointers = np.arange(0, rows * ramps + 1, ramps, dtype=index.dtype)
    return sparse.csr_array((weights.ravel(), index.ravel(), pointers), shape=(rows, columns))


def _no_gather() -> _Gathered:
    return _Gathered.of(np.zeros(0), np.zeros((0, 9), dtype=np.int32), np.zeros((0, 9)))


def _tabulated_gather(pairs: _Pairs, owner: np.ndarray, lags: np.ndarray) -> _Gathered:
    """:class:`_Gathered` at integer ``lags`` sorted within each pair: runs of consecutive lags give runs
    of arguments q − δ, merged across pairs (octave pairs share most of them) into the distinct ones."""
    if not len(lags):
        return _no_gather()
    breaks = np.flatnonzero((np.diff(lags) != 1) | (np.diff(owner) != 0))
    starts, stops = np.concatenate(([0], breaks + 1)), np.concatenate((breaks, [len(lags) - 1]))
    positions = pairs.positions[owner[starts]]
    lowest = (positions - lags[stops][:, None]).ravel()
    first, last = _merged_runs(lowest, (positions - lags[starts][:, None]).ravel())
    lengths = (last - first + 1).astype(np.int64)
    offsets = np.concatenate(([0], np.cumsum(lengths)[:-1]))
    keys = np.repeat(first - offsets, lengths) + np.arange(int(lengths.sum()))
    run = np.searchsorted(first, lowest, side="right") - 1  # the merged run holding each argument run
    base = (offsets[run] - first[run] + positions.ravel()).reshape(positions.shape)  # q − δ ↦ base − δ
    # Indices into the keys (fewer than 2³¹: the distinct arguments of one covariance), each lag's nine
    # ramps in a row: its run's bases less the lag.
    runs = np.repeat(np.arange(len(starts)), stops - starts + 1)
    index = base.astype(np.int32)[runs]
    index -= lags.astype(np.int32)[:, None]
    return _Gathered.of(keys.astype(np.float64), index, pairs.weights[owner])


def _direct_values(pairs: _Pairs, lag_model: LagModel, owner: np.ndarray, lags: np.ndarray) -> np.ndarray:
    """c at lags of narrow pairs: the 1/f part by :func:`_direct_flicker`, the finite part by the nine-term
    sum."""
    finite = replace(lag_model, flicker_variance=0.0)
    if not lag_model.flicker_variance:
        return _nine_term_sum(pairs, finite, owner, lags)
    flicker = np.empty(len(lags))
    integral = lags == np.rint(lags)
    integers = None
    if np.any(integral):  # γ_z once on 0 … the largest |δ + u| an integer lag reaches
        reach = np.abs(lags[integral]) + 2.0 * np.maximum(pairs.m_i, pairs.m_j)[owner[integral]]
        integers = flicker_increment_difference(
            np.arange(int(reach.max()) + 1, dtype=np.float64), lag_model.flicker_d
        )
    # γ_z at the nearest argument x₀ of every lag outside the support, in one call for all the pairs.
    starts = np.zeros(len(lags))
    if not np.all(integral):
        starts[~integral] = flicker_increment_difference(
            pairs.nearest(owner, lags)[~integral], lag_model.flicker_d
        )
    for row in np.unique(owner).tolist():
        mine = owner == row
        m_i, m_j = int(pairs.m_i[row]), int(pairs.m_j[row])
        flicker[mine] = _direct_flicker(m_i, m_j, lag_model, lags[mine], integers, starts[mine])
    return flicker + _nine_term_sum(pairs, finite, owner, lags)


def _batch_values(
    pairs: _Pairs, lag_model: LagModel, owner: np.ndarray, lags: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(c, bound on its error) at any ``lags`` of the pairs ``owner``, without a :class:`PairBatch`: the
    Newton series in the far tail; elsewhere the nine-term sum of H, or for narrow pairs the direct
    Σ_u W(u) γ_z(δ + u)."""
    parts = _partition(pairs, lag_model, owner, lags)
    near = parts[3]
    if not np.any(near):
        return _parted_values(pairs, lag_model, owner, lags, parts, None)
    return _parted_values(
        pairs, lag_model, owner, lags, parts, _nine_term_sum(pairs, lag_model, owner[near], lags[near])
    )


def _parted_values(
    pairs: _Pairs,
    lag_model: LagModel,
    owner: np.ndarray,
    lags: np.ndarray,
    parts: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    near_values: np.ndarray | None,
    bounds: bool = True,
    tail: _FarTail | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """(c, bound on its error) by the partition ``parts`` of :func:`_partition`, the nine-term sums at its
    near lags given (and the far lags' :class:`_FarTail`, or it is formed here); without ``bounds`` the
    error is not formed (an empty array)."""
    nearest, far, direct, near = parts
    values, errors = np.empty(len(lags)), np.zeros(len(lags) if bounds else 0)
    if np.any(direct):
        values[direct] = _direct_values(pairs, lag_model, owner[direct], lags[direct])
    if near_values is not None:
        values[near] = near_values
    if np.any(far):
        values[far], far_errors = 0.0, None  # the finite terms' c is exactly 0 there
        if lag_model.flicker_variance:
            tail = _FarTail.of(pairs, owner[far], nearest[far]) if tail is None else tail
            values[far], far_errors = _newton_series(lag_model, tail, bounds)
        if lag_model.modes is not None:
            values[far] += _modal_values(pairs, lag_model, owner[far], lags[far])[0]
        if far_errors is not None:
            errors[far] = far_errors
    return values, errors


def _values(pair: _Pair, lag_model: LagModel, lags: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(c, bound on its error) of one pair at ``lags`` (:func:`_batch_values` with one row)."""
    return _batch_values(_Pairs.of([pair]), lag_model, np.zeros(len(lags), dtype=np.int64), lags)


@functools.lru_cache(maxsize=256)
def _window(m_i: int, m_j: int) -> np.ndarray:
    """W(u) = Σ_k g_i[k] g_j[k + u], u = −(2m_i − 2) … 2m_j − 2."""
    triangle_i = np.minimum(np.arange(1, 2 * m_i), np.arange(2 * m_i - 1, 0, -1)).astype(np.float64)
    triangle_j = np.minimum(np.arange(1, 2 * m_j), np.arange(2 * m_j - 1, 0, -1)).astype(np.float64)
    return np.convolve(triangle_i[::-1], triangle_j)


def _direct_flicker(
    m_i: int,
    m_j: int,
    lag_model: LagModel,
    lags: np.ndarray,
    integers: np.ndarray | None = None,
    starts: np.ndarray | None = None,
) -> np.ndarray:
    """σ_w² Σ_u W(u) γ_z(δ + u) at integer lags or outside the support, γ_z(x) = C_d/rising(|x| + d − 1,
    3 − 2d) (even on the integers, analytic on either side of the support). At integer lags γ_z is
    evaluated once on the integers the lags reach and correlated with W; ``integers``, when given, holds
    γ_z(0), γ_z(1), … out to every |x| these lags reach (the same values, shared by many pairs);
    ``starts``, when given, holds γ_z(x₀) at each lag (read at the lags outside the support)."""
    d, window = lag_model.flicker_d, _window(m_i, m_j)
    result = np.empty(len(lags))
    integral = lags == np.rint(lags)
    if np.any(integral):
        points = lags[integral]
        first, last = int(points.min()), int(points.max())
        reached = np.arange(first - 2 * m_i + 2, last + 2 * m_j - 1)
        if integers is None:
            gamma = flicker_increment_difference(np.abs(reached.astype(np.float64)), d)
        else:
            gamma = integers[np.abs(reached)]
        result[integral] = np.correlate(gamma, window, "valid")[(points - first).astype(np.int64)]
    if not np.all(integral):
        start = None if starts is None else starts[~integral]
        result[~integral] = _outside_flicker(lags[~integral], m_i, m_j, d, window, start)
    return lag_model.flicker_variance * result


def _outside_flicker(
    lags: np.ndarray, m_i: int, m_j: int, d: float, window: np.ndarray, start: np.ndarray | None = None
) -> np.ndarray:
    """Σ_u W(u) γ_z(δ + u) at lags δ outside the support (every δ + u of one sign, |δ + u| ≥ 1), unit σ_w²:
    γ_z at the run of arguments x₀, x₀ + 1, … (x₀ the nearest, :meth:`_Pairs.nearest`) from γ_z(x₀) and
    the ratio γ_z(x + 1)/γ_z(x) = (x + d − 1)/(x + 2 − d) (Γ(x + d − 1)/Γ(x + 2 − d) up one step), a
    cumulative product: the magnitudes fall along the run and each step adds a rounding, so the values
    carry at most about len(W) ulps; W ≥ 0, so the sum keeps that relative accuracy. ``start``, when
    given, is γ_z(x₀) (the caller's, formed for many pairs at once)."""
    above = lags > 0  # the support −(2m_j − 2) … 2m_i − 2 lies below δ: δ + u > 0 for every u
    nearest = np.where(above, lags - (2 * m_i - 2), -lags - (2 * m_j - 2))
    arguments = nearest[:, None] + np.arange(len(window) - 1, dtype=np.float64)
    gamma = np.empty((len(lags), len(window)))
    gamma[:, 0] = flicker_increment_difference(nearest, d) if start is None else start
    gamma[:, 1:] = np.cumprod((arguments + (d - 1.0)) / (arguments + (2.0 - d)), axis=1)
    gamma[:, 1:] *= gamma[:, :1]
    # Column k is γ_z(x₀ + k): u = −(2m_i − 2) + k above the support, u = 2m_j − 2 − k below it, where
    # the weight is the same: W is a correlation of two palindromes, itself a palindrome.
    return gamma @ window


def _make_pair(m_i: int, m_j: int, K_i: int, K_j: int) -> _Pair:
    ramps = ramp_positions(m_i, m_j)
    positions = np.array([q for q, _ in ramps], dtype=np.float64)
    return _Pair(positions, np.array([w for _, w in ramps], dtype=np.float64), m_i, m_j, K_i, K_j)


def counted_square_sum(
    lag_model: LagModel, m_i: int, m_j: int, K_i: int, K_j: int, rule: QuadratureRule = PROVED_RULE
) -> tuple[float, float]:
    """(Σ_δ N_ij(δ) c_ij(δ)², proved bound on its error) for the overlapping estimator (module text)."""
    return counted_square_sums(lag_model, [(m_i, m_j, K_i, K_j)], rule=rule)[0]


def _merged_runs(firsts: np.ndarray, lasts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The union of the integer intervals [first, last] as disjoint, sorted, non-adjacent intervals."""
    order = np.argsort(firsts, kind="stable")
    firsts, reach = firsts[order], np.maximum.accumulate(lasts[order])
    new = np.concatenate(([True], firsts[1:] > reach[:-1] + 1))
    starts = np.flatnonzero(new)
    return firsts[starts], reach[np.concatenate((starts[1:] - 1, [len(firsts) - 1]))]


def _block_layout(plan: LagPlan, points: int) -> tuple[np.ndarray, ...]:
    """(node lags, node weights, node's block, block's pair, block ends, log h_p) of every pair's Gauss
    blocks (one ``points``-point rule per distinct block length)."""
    blocks = plan.blocks
    if not len(blocks):
        return ()
    distinct, which = np.unique(blocks[:, 1], return_inverse=True)
    rules = _gauss_rules(distinct.tolist(), points)
    offsets = np.stack([rule[0] for rule in rules])[which]
    weights = np.stack([rule[1] for rule in rules])[which]
    log_norms = np.array([rule[2] for rule in rules])[which]
    firsts = blocks[:, 0].astype(np.float64)
    ends = np.column_stack((firsts, firsts + blocks[:, 1] - 1))
    nodes = (firsts[:, None] + offsets).ravel()
    block = np.repeat(np.arange(len(blocks)), points)
    return nodes, weights.ravel(), block, plan.block_owner, ends, log_norms


@dataclass(frozen=True)
class PairBatch:
    """The pairs of one covariance with all that does not depend on the model's variances or its 1/f
    order: the exact lags and the Gauss blocks of :func:`~carousel_theory.lag_plan.plan_pairs` (for the
    finite terms' ``reach``, by ``rule``), the counts N there, how c is taken at each (:func:`_partition`: the
    far-tail series where the finite terms' c is exactly 0, every argument of their γ_z beyond their
    reach) and the gathers of H."""

    pairs: _Pairs
    reach: int
    rule: QuadratureRule
    lag_owner: np.ndarray
    lags: np.ndarray
    lag_counts: np.ndarray
    nodes: np.ndarray
    node_weights: np.ndarray
    node_block: np.ndarray
    node_owner: np.ndarray
    node_counts: np.ndarray
    block_owner: np.ndarray
    block_ends: np.ndarray
    block_largest: np.ndarray
    block_norms: np.ndarray

    @functools.cached_property
    def lag_parts(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """:func:`_partition` of the exact lags."""
        return _partition_for(self.pairs, self.lag_owner, self.lags, self.reach)

    @functools.cached_property
    def lag_gather(self) -> _Gathered:
        """:func:`_tabulated_gather` at the exact lags taken by the nine-term sum."""
        near = self.lag_parts[3]
        return _tabulated_gather(self.pairs, self.lag_owner[near], self.lags[near])

    @functools.cached_property
    def lag_tail(self) -> _FarTail:
        """:class:`_FarTail` of the exact lags in the far tail."""
        nearest, far = self.lag_parts[:2]
        return _FarTail.of(self.pairs, self.lag_owner[far], nearest[far])

    @functools.cached_property
    def node_tail(self) -> _FarTail:
        """:class:`_FarTail` of the Gauss nodes in the far tail."""
        nearest, far = self.node_parts[:2]
        return _FarTail.of(self.pairs, self.node_owner[far], nearest[far])

    @functools.cached_property
    def node_parts(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """:func:`_partition` of the Gauss nodes."""
        return _partition_for(self.pairs, self.node_owner, self.nodes, self.reach)

    @functools.cached_property
    def node_gather(self) -> _Grid:
        """:func:`_gridded_gather` at the Gauss nodes taken by the nine-term sum."""
        return _gridded_gather(self, self.node_parts[3])

    @classmethod
    def of(
        cls, pairs: Sequence[tuple[int, int, int, int]], reach: int, rule: QuadratureRule = PROVED_RULE
    ) -> PairBatch:
        """The batch of (m_i, m_j, K_i, K_j) ``pairs`` for terms reaching ``reach`` lags, by ``rule``."""
        batch = _Pairs.of([_make_pair(*pair) for pair in pairs])
        plan = plan_pairs(pairs, reach, rule)
        lags, owner = plan.lags.astype(np.float64), plan.lag_owner
        layout = _block_layout(plan, rule.points)
        if not layout:
            empty, none = np.zeros(0), np.zeros(0, dtype=np.int64)
            layout = (empty, empty, none, none, np.zeros((0, 2)), empty)
        nodes, weights, block, block_owner, ends, log_norms = layout
        node_owner = block_owner[block]
        largest = np.maximum(batch.count(block_owner, ends[:, 0]), batch.count(block_owner, ends[:, 1]))
        return cls(
            batch, reach, rule, owner, lags, batch.count(owner, lags), nodes, weights, block,
            node_owner, weights * batch.count(node_owner, nodes), block_owner, ends, largest,
            np.exp(log_norms),
        )  # fmt: skip


@dataclass(frozen=True)
class TermValues:
    """c of one term at a batch's exact lags and Gauss nodes, the bounds on the far-tail series' error
    there, and the bound B on each block's derivative (both zero for a finite term; empty when the values
    were formed without bounds)."""

    lags: np.ndarray
    lag_errors: np.ndarray
    nodes: np.ndarray
    node_errors: np.ndarray
    derivative: np.ndarray


def term_values(batch: PairBatch, lag_model: LagModel, *, bounds: bool = True) -> TermValues:
    """:class:`TermValues` of ``lag_model`` (one term, or the whole model) on ``batch``: the values
    :func:`counted_square_sums` sums, element by element; without ``bounds`` the same values, no error
    bounds (empty arrays)."""
    pairs = batch.pairs
    if lag_model.reach != batch.reach:
        raise ValueError(f"lag_model.reach={lag_model.reach!r}: must be the batch's reach {batch.reach}")
    values, errors = _parted_values(
        pairs,
        lag_model,
        batch.lag_owner,
        batch.lags,
        batch.lag_parts,
        batch.lag_gather.values(lag_model),
        bounds,
        batch.lag_tail if lag_model.flicker_variance else None,
    )
    node_values, node_errors = _parted_values(
        pairs,
        lag_model,
        batch.node_owner,
        batch.nodes,
        batch.node_parts,
        batch.node_gather.values(lag_model),
        bounds,
        batch.node_tail if lag_model.flicker_variance else None,
    )
    derivative = (
        _derivative_bounds(pairs, lag_model, batch.block_owner, batch.block_ends, batch.rule.points)
        if bounds
        else np.zeros(0)
    )
    return TermValues(values, errors, node_values, node_errors, derivative)


@dataclass(frozen=True)
class _Grid:
    """c at chosen Gauss nodes from H at the distinct (q − f, block length) rows times the p offsets
    (``arguments``, row after row): a sparse ``matrix`` gives each block holding a chosen node its nine
    ramps' weights at the columns of their rows, so that matrix @ H (rows × p) is c at every node of those
    blocks (each node's nine products added in the ramps' order, as at every lag), and ``take`` is each
    chosen node's place among them."""

    arguments: np.ndarray
    matrix: sparse.csr_array
    take: np.ndarray
    points: int

    def values(self, lag_model: LagModel) -> np.ndarray:
        if not len(self.take):
            return np.zeros(0)
        table = lag_model.fourth_sum(self.arguments).reshape(-1, self.points)
        return np.asarray(self.matrix @ table).ravel()[self.take]


def _gridded_gather(batch: PairBatch, chosen: np.ndarray) -> _Grid:
    """:class:`_Grid` at the ``chosen`` Gauss nodes. A node δ = f + o (f the block's first lag, o the
    rule's offset) has the arguments q − δ = (q − f) − o; blocks of the same length share their offsets
    and, grown from breakpoints at the same distances, most of their q − f (octave pairs: about one
    (block, q) in nine is new), so H is needed only on the distinct (q − f, length) at the p offsets."""
    pairs, points = batch.pairs, batch.rule.points
    if not np.any(chosen):
        return _Grid(
            np.zeros(0),
            _ramp_matrix(np.zeros((0, 9), dtype=np.int32), np.zeros((0, 9)), 0),
            np.zeros(0, dtype=np.int64),
            points,
        )
    holds = np.bincount(batch.node_block[chosen], minlength=len(batch.block_owner)) > 0
    blocks = np.flatnonzero(holds)
    first = batch.block_ends[blocks, 0]
    length = (batch.block_ends[blocks, 1] - first + 1).astype(np.int64)
    shift = (pairs.positions[batch.block_owner[blocks]] - first[:, None]).astype(np.int64)
    # (q − f, length) as one integer, without collisions: both are below the record length, so the key
    # stays below (2n)·(n + 1), far inside int64 for any recording that fits in memory.
    least, radix = int(shift.min()), int(length.max()) + 1
    keys = (shift - least) * radix + length[:, None]
    distinct, inverse = np.unique(keys.ravel(), return_inverse=True)
    lengths, which = np.unique(distinct % radix, return_inverse=True)
    offsets = np.stack([rule[0] for rule in _gauss_rules(lengths.tolist(), points)])[which]
    arguments = (distinct // radix + least).astype(np.float64)[:, None] - offsets
    rows = inverse.reshape(keys.shape).astype(np.int32)  # each block's nine rows (q − f, length)
    matrix = _ramp_matrix(rows, pairs.weights[batch.block_owner[blocks]], len(distinct))
    where = (np.cumsum(holds) - 1)[batch.node_block[chosen]]  # each chosen node's block among ``blocks``
    return _Grid(arguments.ravel(), matrix, where * points + np.flatnonzero(chosen) % points, points)


def _combined(arrays: Sequence[np.ndarray], variances: Sequence[float]) -> np.ndarray:
    """Σ_a θ_a x_a over the terms whose arrays are not empty."""
    total = np.zeros(0)
    for array, variance in zip(arrays, variances, strict=True):
        if len(array):
            total = variance * array if not len(total) else total + variance * array
    return total


def combined_sums(
    batch: PairBatch, terms: Sequence[TermValues], variances: Sequence[float], *, bounds: bool = True
) -> list[tuple[float, float]]:
    """(Σ_δ N c², proved bound on its error) of each pair for c = Σ_a θ_a c_a, θ = ``variances`` of the
    ``terms`` (module text): the exact lags and the Gauss blocks of the combined values. Without
    ``bounds`` (terms whose values were formed without them) the bound is NaN: not computed."""
    size = len(batch.pairs.m_i)
    values = _combined([t.lags for t in terms], variances)
    total = np.bincount(batch.lag_owner, batch.lag_counts * (values * values), minlength=size)
    bound = _lag_bound(batch, terms, variances, values) if bounds else np.full(size, np.nan)
    block_total: np.ndarray = np.zeros(size)
    if len(batch.nodes):
        values = _combined([t.nodes for t in terms], variances)
        block_total = np.bincount(batch.node_owner, batch.node_counts * (values * values), minlength=size)
        if bounds:
            bound = bound + _block_bound(batch, terms, variances, values)
    return list(zip((total + block_total).tolist(), bound.tolist(), strict=True))


def _lag_bound(
    batch: PairBatch, terms: Sequence[TermValues], variances: Sequence[float], values: np.ndarray
) -> np.ndarray:
    """The far-tail series' bound Σ N e (2|c| + e) over each pair's exact lags."""
    errors = _combined([t.lag_errors for t in terms], variances)
    error_terms = batch.lag_counts * (errors * (2.0 * np.abs(values) + errors))
    return np.bincount(batch.lag_owner, error_terms, minlength=len(batch.pairs.m_i))


def _block_bound(
    batch: PairBatch, terms: Sequence[TermValues], variances: Sequence[float], values: np.ndarray
) -> np.ndarray:
    """The Gauss blocks' bound of each pair: the far-tail series' at the nodes and the rule's (module
    text)."""
    size = len(batch.pairs.m_i)
    errors = _combined([t.node_errors for t in terms], variances)
    error_terms = batch.node_counts * (errors * (2.0 * np.abs(values) + errors))
    block_bound = np.bincount(batch.node_owner, error_terms, minlength=size)
    derivative = _combined([t.derivative for t in terms], variances)
    if len(derivative):
        square_sums = np.bincount(
            batch.node_block, batch.node_weights * values * values, minlength=len(batch.block_owner)
        )
        norms, largest = batch.block_norms, batch.block_largest
        quadrature = derivative * largest * (2.0 * np.sqrt(norms * square_sums) + derivative * norms)
        block_bound = block_bound + np.bincount(batch.block_owner, quadrature, minlength=size)
    return block_bound


def counted_square_sums(
    lag_model: LagModel,
    pairs: Sequence[tuple[int, int, int, int]],
    *,
    bounds: bool = True,
    rule: QuadratureRule = PROVED_RULE,
) -> list[tuple[float, float]]:
    """:func:`counted_square_sum` of every (m_i, m_j, K_i, K_j) in ``pairs``, all evaluated together (rows of
    :class:`_Pairs`), with H tabulated once on the union of the integer arguments the exact lags need.
    Every operation is element by element and each pair's sum is reduced in its own order, so each
    value is, bit for bit, the one the pair alone gives. Without ``bounds`` the same sums, each bound
    NaN (not computed: the far-tail remainders and the blocks' derivative bounds are skipped). ``rule``:
    the plan's (module text: Rules)."""
    if not pairs:
        return []
    batch = pair_batch(tuple(tuple(pair) for pair in pairs), lag_model.reach, rule)
    return combined_sums(batch, [term_values(batch, lag_model, bounds=bounds)], [1.0], bounds=bounds)


@functools.lru_cache(maxsize=4)
def pair_batch(
    pairs: tuple[tuple[int, int, int, int], ...], reach: int, rule: QuadratureRule = PROVED_RULE
) -> PairBatch:
    """:meth:`PairBatch.of` with its gathers built, kept for the next covariance of the same pairs (a fit's
    iterations, whatever terms each step holds at zero, and the next record of the same length and AR
    reach; four kept: a fit uses one for its τ and one for the intervals at every τ)."""
    batch = PairBatch.of(pairs, reach, rule)
    _ = (batch.lag_gather, batch.node_gather)
    return batch


def rounding_scales(
    pairs: _Pairs,
    lag_model: LagModel,
    owner: np.ndarray,
    lags: np.ndarray,
    values: np.ndarray,
) -> np.ndarray:
    """S at each lag (module text: Rounding): Σ_q |w_q H(q − δ)| where c is the nine-term sum,
    len(W)·|c| where it is the direct sum, |c| in the far tail; plus, with AR modes, Σ_q |w_q θ G| where
    the direct sum or the far tail's series has the modes' nine-term sum beside it."""
    _, far, direct, near = _partition(pairs, lag_model, owner, lags)
    if not lag_model.flicker_variance:  # without 1/f a direct value is the nine-term sum alone
        near, direct = near | direct, np.zeros_like(direct)
    scales = np.abs(values)
    scales[direct] *= (2 * pairs.m_i + 2 * pairs.m_j - 3)[owner[direct]]
    if lag_model.modes is not None:  # the modes' nine-term sum beside the Newton series or the direct sum
        for where in (far, direct):
            if np.any(where):
                scales[where] += _modal_values(pairs, lag_model, owner[where], lags[where])[1]
    if np.any(near):
        terms = lag_model.fourth_sum(pairs.positions[owner[near]] - lags[near][:, None])
        scales[near] = np.sum(np.abs(terms * pairs.weights[owner[near]]), axis=1)
    return scales


def _rounding_terms(counts: np.ndarray, values: np.ndarray, scales: np.ndarray) -> np.ndarray:
    """N (2|c| ρ + ρ²), ρ = ROUNDING_ULPS · u · S."""
    rho = ROUNDING_ULPS * np.finfo(np.float64).eps / 2.0 * scales
    return counts * rho * (2.0 * np.abs(values) + rho)


def rounding_allowances(
    lag_model: LagModel, pairs: Sequence[tuple[int, int, int, int]], rule: QuadratureRule = PROVED_RULE
) -> list[float]:
    """The rounding allowance of each pair's :func:`counted_square_sums` value by ``rule`` (module text:
    Rounding)."""
    if not pairs:
        return []
    batch = pair_batch(tuple(tuple(pair) for pair in pairs), lag_model.reach, rule)
    rows = batch.pairs
    values = term_values(batch, lag_model, bounds=False)
    at_lags = rounding_scales(rows, lag_model, batch.lag_owner, batch.lags, values.lags)
    at_nodes = rounding_scales(rows, lag_model, batch.node_owner, batch.nodes, values.nodes)
    size = len(rows.m_i)
    total = np.bincount(
        batch.lag_owner, _rounding_terms(batch.lag_counts, values.lags, at_lags), minlength=size
    )
    total += np.bincount(
        batch.node_owner, _rounding_terms(batch.node_counts, values.nodes, at_nodes), minlength=size
    )
    return total.tolist()
