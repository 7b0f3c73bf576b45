"""The gyro noise model: one frozen dataclass, each term with its exact autocovariance, spectrum and Allan
variance.

Terms (per-sample discrete terms of TIM 2014 §II, sample interval Δt = 1/f_s)
    bias            b, eq. (1): adds nothing to any variance below.
    white           y_t = e_t, Var e = σ_WN².
    rate random walk y_t = y_{t−1} + q_t, Var q = σ_q², eq. (2).
    1/f             y = (1 − B)^{−d} w, Var w = σ_w², eq. (3), any 0 < d < 1.
    quantization    y_t = (a_t − a_{t−1}) f_s with a white angle error of variance Q².
    autoregressive  x_t = Σ_{j=1}^{p} φ_j x_{t−j} + ε_t, Var ε = σ_AR² (first-order Gauss–Markov is p = 1):
                    the short correlated noise of a sensor's internal low-pass filter.

One representation serves every term: the autocovariance γ_z of the *increments* z_t = y_t − y_{t−1}.
Every term has stationary increments, also the rate random walk and the 1/f noise for d ≥ ½ (whose rate
is not stationary): white 2σ², −σ² at lag ±1; rate random walk σ_q² at lag 0; quantization f_s²Q²
(6, −4, 1); autoregressive 2γ(k) − γ(k−1) − γ(k+1) from the AR autocovariance γ; 1/f the
ARFIMA(0, d − 1, 0) autocovariance σ_w² Γ(3 − 2d)/Γ(2 − d)² · Π_{j=1}^{k} (j − 2 + d)/(j + 1 − d).
The increments of the 1/f process of eq. (3), which starts at t = 1, converge to this stationary
sequence; the Allan variance of :mod:`carousel_theory.allan_model` is the one of the stationary
differences (the eq. (3) value inside a record of given length stays in
:func:`carousel_theory.allan.flicker_allan_variance`).

Allan variance (m samples per cluster, τ = mΔt)
    The cluster-mean difference d = Σ_{k<m} (y_{s+m+k} − y_{s+k}) has Var d = Σ_{|j|<m} (m − |j|)
    [D(|m + j|) − D(|j|)], with D(h) = E(y_{t+h} − y_t)² = Σ_{|k|<h} (h − |k|) γ_z(k) the variogram; the
    Allan variance is Var d/(2m²). White, rate random walk and quantization have the closed forms
    σ_WN²/m, σ_q²(2m² + 1)/(6m), 3Q²/τ² (SymPy, derived in ``derivations/allan_variance_models.md`` and
    lambdified once); 1/f and AR come from a fourth sum H of γ_z (∇⁴H = γ_z), in closed form for 1/f
    (telescoping Gamma ratios) and finite for AR, O(1) per τ (:mod:`carousel_theory.increment_sums`);
    the finite variogram sum above, O(m) per τ, stays as :func:`allan_variance_from_increments`.

Public API
    :class:`NoiseModel` (the dataclass), :func:`increment_autocovariance`, :func:`spectral_density`,
    :func:`term_allan_variance`, :func:`ar_autocovariance`, :func:`unit_flicker_increment_autocovariance`,
    :data:`TERMS`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import sympy as sp
from scipy import linalg

from carousel_theory import symbols, units
from carousel_theory._validation import (
    check_fractional_order,
    check_positive_integer,
    check_positive_real,
    check_real,
)
from carousel_theory.increment_sums import (
    allan_variance_from_fourth_sum,
    finite_fourth_sum,
    flicker_allan_variance_closed,
)

__all__ = [
    "QUANTIZATION_ALLAN_VARIANCE",
    "RRW_ALLAN_VARIANCE",
    "TERMS",
    "WHITE_ALLAN_VARIANCE",
    "NoiseModel",
    "ar_autocovariance",
    "ar_decay_lags",
    "ar_increment_reach",
    "check_ar_coefficients",
    "increment_autocovariance",
    "spectral_density",
    "term_allan_variance",
    "unit_flicker_increment_autocovariance",
]

#: Noise terms, in a fixed order (the rows of a fit).
TERMS = ("white", "rrw", "flicker", "quantization", "ar")

_m = symbols.cluster_size
#: Exact Allan variance of discrete white noise of per-sample variance σ_WN², m samples per cluster.
WHITE_ALLAN_VARIANCE: sp.Expr = symbols.white_sample_variance / _m
#: Exact Allan variance of the rate random walk of TIM 2014 eq. (2), increment variance σ_q² per sample.
RRW_ALLAN_VARIANCE: sp.Expr = symbols.rrw_increment_variance * (2 * _m**2 + 1) / (6 * _m)
#: Exact Allan variance of a white angle error of variance Q² differenced into the rate (τ = mΔt).
QUANTIZATION_ALLAN_VARIANCE: sp.Expr = 3 * symbols.quantization_step**2 / (_m * symbols.sample_interval) ** 2

_white_numeric = sp.lambdify((symbols.white_sample_variance, _m), WHITE_ALLAN_VARIANCE, "numpy")
_rrw_numeric = sp.lambdify((symbols.rrw_increment_variance, _m), RRW_ALLAN_VARIANCE, "numpy")
_quantization_numeric = sp.lambdify(
    (symbols.quantization_step, _m, symbols.sample_interval), QUANTIZATION_ALLAN_VARIANCE, "numpy"
)

#: The AR autocovariance is computed out to the lag where the geometric envelope ρ^k of its slowest root
#: falls below this fraction (the neglected tail is bounded by it, relative to γ(0)).
AR_TRUNCATION = 1e-17


@dataclass(frozen=True)
class NoiseModel:
    """A gyro noise model in the per-sample discrete terms of TIM 2014 §II.

    Attributes
    ----------
    sample_rate : float
        Samples per second f_s (Δt = 1/f_s).
    bias : float
        Constant bias b (rad/s), eq. (1).
    white_variance : float
        Per-sample white-noise variance σ_WN² ((rad/s)²).
    rrw_variance : float
        Per-sample increment variance σ_q² of the rate random walk, eq. (2) ((rad/s)²).
    flicker_variance : float
        Driving variance σ_w² of the fractionally integrated 1/f noise, eq. (3) ((rad/s)²).
    flicker_d : float
        Order 0 < d < 1 of the fractional integration (ignored when ``flicker_variance`` is 0).
    quantization : float
        Angle quantization Q (rad): Allan variance 3Q²/τ².
    ar_variance : float
        Innovation variance σ_AR² of the autoregressive short noise ((rad/s)²).
    ar_coefficients : tuple of float
        φ_1 … φ_p of x_t = Σ φ_j x_{t−j} + ε_t (stationary: every root of 1 − Σ φ_j z^j outside the
        unit circle); empty for no autoregressive term.
    """

    sample_rate: float
    bias: float = 0.0
    white_variance: float = 0.0
    rrw_variance: float = 0.0
    flicker_variance: float = 0.0
    flicker_d: float = 0.5
    quantization: float = 0.0
    ar_variance: float = 0.0
    ar_coefficients: tuple[float, ...] = ()
    extra: dict[Any, Any] = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        check_positive_real("sample_rate", self.sample_rate)
        check_real("bias", self.bias)
        for name in ("white_variance", "rrw_variance", "flicker_variance", "quantization", "ar_variance"):
            check_positive_real(name, getattr(self, name), allow_zero=True)
        check_fractional_order("flicker_d", self.flicker_d)
        check_ar_coefficients(self.ar_coefficients)
        if self.ar_variance and not self.ar_coefficients:
            raise ValueError(
                f"ar_variance={self.ar_variance!r}: an AR term needs ar_coefficients (AR(0) is white noise: "
                "use white_variance)"
            )

    # --- the terms ----------------------------------------------------------------------------------
    def terms(self) -> dict[str, float]:
        """Driving variance of each term present (quantization as f_s²Q², the variance of its rate)."""
        values = {
            "white": float(self.white_variance),
            "rrw": float(self.rrw_variance),
            "flicker": float(self.flicker_variance),
            "quantization": float(self.quantization) ** 2 * float(self.sample_rate) ** 2,
            "ar": float(self.ar_variance),
        }
        return {name: value for name, value in values.items() if value > 0}

    def unit(self, term: str) -> NoiseModel:
        """The same model with ``term`` at unit driving variance and every other term at zero."""
        zero = replace(
            self,
            white_variance=0.0,
            rrw_variance=0.0,
            flicker_variance=0.0,
            quantization=0.0,
            ar_variance=0.0,
        )
        if term == "quantization":
            return replace(zero, quantization=1.0 / float(self.sample_rate))
        if term not in TERMS:
            raise ValueError(f"term={term!r}: must be one of {TERMS}")
        return replace(zero, **{_FIELD[term]: 1.0})  # type: ignore[arg-type]

    @property
    def long_run_ar_variance(self) -> float:
        """σ_AR²/(1 − Σ φ_j)²: the white-noise variance that long averages of the AR term see."""
        return ar_long_run_variance(self.ar_variance, tuple(self.ar_coefficients))

    def increment_autocovariance(self, lags: int) -> np.ndarray:
        """γ_z(k), k = 0 … lags − 1, of the increments of the whole model (see the module text)."""
        total = np.zeros(lags)
        for term, variance in self.terms().items():
            total += variance * increment_autocovariance(term, lags, self.flicker_d, self.ar_coefficients)
        return total

    def spectral_density(self, frequencies: Any) -> np.ndarray:
        """Two-sided discrete spectral density of the rate at ``frequencies`` (Hz)."""
        omega = 2.0 * np.pi * np.asarray(frequencies, dtype=np.float64) / float(self.sample_rate)
        total = np.zeros_like(omega)
        for term, variance in self.terms().items():
            total = total + variance * spectral_density(term, omega, self.flicker_d, self.ar_coefficients)
        return total

    def allan_variance(self, tau_samples: Any) -> np.ndarray:
        """Exact Allan variance (stationary differences) of the model at m = ``tau_samples`` samples."""
        sizes = cluster_sizes(tau_samples)
        total = np.zeros(len(sizes))
        for term, variance in self.terms().items():
            total += variance * term_allan_variance(term, sizes, self.flicker_d, self.ar_coefficients)
        return total

    # --- the field's units (IEEE Std 952) -------------------------------------------------------
    def angle_random_walk(self) -> float:
        """N = √(σ_WN²/f_s) in rad/√s."""
        return units.angle_random_walk_from_white_variance(self.white_variance, self.sample_rate)

    def angle_random_walk_deg_per_sqrt_hour(self) -> float:
        """Angle random walk in °/√h."""
        return units.to_deg_per_sqrt_hour(self.angle_random_walk())

    def rate_random_walk(self) -> float:
        """K = √(σ_q² f_s) in rad/s/√s."""
        return units.rate_random_walk_from_increment_variance(self.rrw_variance, self.sample_rate)

    def rate_random_walk_deg_per_hour_per_sqrt_hour(self) -> float:
        """Rate random walk in °/h/√h."""
        return units.to_deg_per_hour_per_sqrt_hour(self.rate_random_walk())

    def bias_deg_per_hour(self) -> float:
        """The bias in °/h."""
        return units.rad_per_s_to_deg_per_h(self.bias)

    # --- the paper's units (TIM 2014 Table III) -------------------------------------------------
    def white_variance_at_one_second(self) -> float:
        """σ_WN² (τ = 1 s) of TIM 2014 Table III: the variance of a 1-s average, σ_WN²/f_s ((rad/s)²)."""
        return self.white_variance / self.sample_rate

    def rrw_variance_per_second(self) -> float:
        """σ_q² of TIM 2014 Table III in (rad/s)²/s: the increment variance per second, σ_q² f_s."""
        return self.rrw_variance * self.sample_rate

    def minimum_allan_deviation(self, length: int) -> tuple[float, float]:
        """(min σ_A, τ at the minimum) of this model over τ up to a third of a record of ``length`` samples.

        Searched on a log grid of 8 points per octave of the stationary Allan variance.
        """
        key = (  # ``extra`` is shared by models made with dataclasses.replace: key on every parameter
            "minimum",
            int(length),
            self.white_variance,
            self.rrw_variance,
            self.flicker_variance,
            self.flicker_d,
            self.quantization,
            self.ar_variance,
            self.ar_coefficients,
            self.sample_rate,
        )
        if key not in self.extra:
            top = max(1, int(length) // 3)
            count = 8 * max(1, int(math.log2(top)) + 1)
            grid = np.unique(np.rint(np.geomspace(1, top, count)).astype(np.int64))
            values = self.allan_variance(grid)
            best = int(np.argmin(values))
            self.extra[key] = (math.sqrt(float(values[best])), float(grid[best] / self.sample_rate))
        return self.extra[key]

    def bias_instability(self, length: int) -> float:
        """Bias instability B = min σ_A / 0.664 (rad/s) of the model's Allan curve (IEEE Std 952)."""
        return units.bias_instability_from_allan_minimum(self.minimum_allan_deviation(length)[0])


_FIELD = {
    "white": "white_variance",
    "rrw": "rrw_variance",
    "flicker": "flicker_variance",
    "quantization": "quantization",
    "ar": "ar_variance",
}


def check_ar_coefficients(coefficients: Any) -> None:
    """Refuse AR coefficients that are not a tuple of finite reals describing a stationary process."""
    if not stationary_ar(coefficients):  # which refuses what is not a tuple of finite reals
        raise ValueError(
            f"ar_coefficients={coefficients!r}: must describe a stationary AR process (every root of "
            "1 − Σ φ_j z^j outside the unit circle)"
        )


def stationary_ar(coefficients: tuple[float, ...]) -> bool:
    """Every root of 1 − Σ φ_j z^j outside the unit circle (() is white noise: stationary)."""
    if not isinstance(coefficients, tuple):
        raise TypeError(f"ar_coefficients={coefficients!r}: must be a tuple of floats")
    for j, value in enumerate(coefficients):
        check_real(f"ar_coefficients[{j}]", value)  # a finite real number
    return not coefficients or _slowest_root(tuple(coefficients)) < 1.0


def ar_long_run_variance(variance: float, coefficients: tuple[float, ...]) -> float:
    """σ²/(1 − Σ φ_j)²: the long-run variance of the AR process of innovation variance σ² (the white-noise
    variance that long averages of it see)."""
    check_positive_real("variance", variance, allow_zero=True)
    check_ar_coefficients(coefficients)
    return float(variance) / (1.0 - sum(coefficients)) ** 2


@functools.lru_cache(maxsize=256)
def _slowest_root(coefficients: tuple[float, ...]) -> float:
    """ρ = the largest |λ| over the roots λ of z^p − Σ φ_j z^{p−j} (stationary when ρ < 1); kept per
    coefficients, which every model built during a fit checks again."""
    return float(np.max(np.abs(np.roots(np.concatenate(([1.0], -np.asarray(coefficients)))))))


@functools.lru_cache(maxsize=64)
def ar_autocovariance(coefficients: tuple[float, ...], lags: int) -> np.ndarray:
    """γ(k), k = 0 … lags − 1, of the AR(p) process at unit innovation variance (read-only array).

    γ(0 … p) solve the Yule–Walker equations γ(k) − Σ_j φ_j γ(|k − j|) = [k = 0]; beyond, the exact
    recursion γ(k) = Σ_j φ_j γ(k − j). Lags where ρ^k < ``AR_TRUNCATION`` are set to 0 (ρ the slowest
    root; the neglected values are below that bound times a constant of the roots).
    """
    phi = np.asarray(coefficients, dtype=np.float64)
    p = len(phi)
    gamma = np.zeros(max(lags, p + 1))
    if p == 0:
        gamma[0] = 1.0
        return _frozen(gamma[:lags])
    system = np.eye(p + 1)
    for k in range(p + 1):
        for j in range(1, p + 1):
            system[k, abs(k - j)] -= phi[j - 1]
    right = np.zeros(p + 1)
    right[0] = 1.0
    gamma[: p + 1] = linalg.solve(system, right)
    reach = min(lags, p + 2 + ar_decay_lags(coefficients)) if _slowest_root(coefficients) else lags
    if reach > p + 1:
        gamma[p + 1 : reach] = _ar_recursion(phi, gamma[: p + 1], reach - p - 1)
    return _frozen(gamma[:lags])


#: Beyond this many lags an AR(p ≥ 2) recursion runs in scipy.signal.lfilter (C) instead of a loop.
_LOOPED_LAGS = 2048


def _ar_recursion(phi: np.ndarray, head: np.ndarray, count: int) -> np.ndarray:
    """γ(k) = Σ_j φ_j γ(k − j) for the ``count`` lags after ``head`` = γ(0 … p). AR(1): the running product
    γ(k − 1)·φ, the recursion's own multiplications in its order (np.multiply.accumulate); AR(p): the loop,
    or, over many lags (a slow complex pair), the same recursion as an all-pole filter of zero input."""
    p = len(phi)
    if p == 1:
        return np.multiply.accumulate(np.concatenate(([head[-1]], np.full(count, phi[0]))))[1:]
    if count > _LOOPED_LAGS:
        from scipy.signal import lfilter, lfiltic  # loaded only for a long AR(p ≥ 2) recursion

        denominator = np.concatenate(([1.0], -phi))
        state = lfiltic([1.0], denominator, head[:0:-1])
        return np.asarray(lfilter([1.0], denominator, np.zeros(count), zi=state)[0])
    gamma = np.concatenate((head, np.zeros(count)))
    for k in range(p + 1, p + 1 + count):
        gamma[k] = float(np.dot(phi, gamma[k - p : k][::-1]))
    return gamma[p + 1 :]


@functools.lru_cache(maxsize=64)
def ar_increment_reach(coefficients: tuple[float, ...]) -> int:
    """The last lag at which γ_z of the AR term can be non-zero: :func:`ar_autocovariance` keeps γ(k) for
    k ≤ p + 1 + ⌊log AR_TRUNCATION / log ρ⌋ (zero beyond), and γ_z(k) = 2γ(k) − γ(k − 1) − γ(k + 1)
    reaches one lag further."""
    return len(coefficients) + 2 + ar_decay_lags(tuple(float(c) for c in coefficients))


def ar_decay_lags(coefficients: tuple[float, ...]) -> int:
    """⌊log AR_TRUNCATION / log ρ⌋: the lags after which ρ^k, the AR autocovariance's slowest decay, is
    below ``AR_TRUNCATION`` (0 when ρ = 0)."""
    check_ar_coefficients(coefficients)
    if not coefficients:
        raise ValueError("ar_coefficients=(): an AR term needs at least one coefficient")
    rho = _slowest_root(coefficients)
    return 0 if rho == 0 else int(math.log(AR_TRUNCATION) / math.log(rho))


def _frozen(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


#: Lags per block of the 1/f autocovariance's running product (bounds its temporaries, 4 × 8 MiB).
_FLICKER_BLOCK = 1 << 20


@functools.lru_cache(maxsize=8)
def _flicker_increment_autocovariance(d: float, lags: int) -> np.ndarray:
    """ARFIMA(0, d − 1, 0) autocovariance at unit σ_w²: γ(0) = Γ(3 − 2d)/Γ(2 − d)², ratio (k−2+d)/(k+1−d).

    γ(k) = γ(0) Π_{j ≤ k} r_j, the running product taken in blocks of ``_FLICKER_BLOCK`` lags whose
    first ratio is multiplied by the product so far: the same sequence of products as one cumulative
    product over all lags, without temporaries of the record's length.
    """
    gamma = np.empty(lags)
    gamma[0] = math.exp(math.lgamma(3.0 - 2.0 * d) - 2.0 * math.lgamma(2.0 - d))
    product = 1.0
    for start in range(1, lags, _FLICKER_BLOCK):
        stop = min(start + _FLICKER_BLOCK, lags)
        k = np.arange(start, stop, dtype=np.float64)
        ratio = k - 2.0 + d
        ratio /= k + 1.0 - d
        if start > 1:
            ratio[0] *= product
        np.cumprod(ratio, out=ratio)
        product = float(ratio[-1])
        np.multiply(gamma[0], ratio, out=gamma[start:stop])
    return _frozen(gamma)


def unit_flicker_increment_autocovariance(flicker_d: float, lags: int) -> np.ndarray:
    """γ_z(k), k = 0 … lags − 1, of the 1/f term at unit σ_w²: the read-only array shared by every caller
    with the same (d, lags), held once per process (a long record's fits reuse it)."""
    check_fractional_order("flicker_d", flicker_d)
    return _flicker_increment_autocovariance(float(flicker_d), check_positive_integer("lags", lags))


def increment_autocovariance(
    term: str, lags: int, flicker_d: float = 0.5, ar_coefficients: tuple[float, ...] = ()
) -> np.ndarray:
    """γ_z(k), k = 0 … lags − 1, of the increments z_t = y_t − y_{t−1} of one term at unit driving variance.

    (Quantization at unit variance of its rate f_s·a_t.) See the module text for each term.
    """
    lags = check_positive_integer("lags", lags)
    _check_term(term, flicker_d, ar_coefficients)
    gamma = np.zeros(lags)
    if term == "white":
        gamma[:2] = (2.0, -1.0)[: min(lags, 2)]
    elif term == "rrw":
        gamma[:1] = 1.0
    elif term == "quantization":
        gamma[:3] = (6.0, -4.0, 1.0)[: min(lags, 3)]
    elif term == "flicker":
        gamma[:] = _flicker_increment_autocovariance(float(flicker_d), lags)
    elif term == "ar":
        ar = ar_autocovariance(tuple(float(c) for c in ar_coefficients), lags + 1)
        previous = np.concatenate((ar[1:2], ar[: lags - 1]))  # γ(k − 1), with γ(−1) = γ(1)
        gamma[:] = 2.0 * ar[:lags] - previous - ar[1 : lags + 1]
    else:
        raise ValueError(f"term={term!r}: must be one of {TERMS}")
    return gamma


def spectral_density(
    term: str, omega: np.ndarray, flicker_d: float = 0.5, ar_coefficients: tuple[float, ...] = ()
) -> np.ndarray:
    """Spectral density of one term's rate at angular frequency ω (rad/sample), unit driving variance.

    white 1; rate random walk 1/|1 − e^{−iω}|² (eq. (2)); 1/f |1 − e^{−iω}|^{−2d} (eq. (3));
    quantization |1 − e^{−iω}|²; AR 1/|1 − Σ φ_j e^{−ijω}|².
    """
    _check_term(term, flicker_d, ar_coefficients)
    if not np.all(np.isfinite(np.asarray(omega, dtype=np.float64))):
        raise ValueError(f"omega={omega!r}: angular frequencies must be finite")
    difference = 4.0 * np.sin(np.asarray(omega) / 2.0) ** 2  # |1 − e^{−iω}|²
    with np.errstate(divide="ignore"):
        if term == "white":
            return np.ones_like(difference)
        if term == "rrw":
            return 1.0 / difference
        if term == "flicker":
            return difference ** (-float(flicker_d))
        if term == "quantization":
            return difference
    if term == "ar":
        j = np.arange(1, len(ar_coefficients) + 1)
        transfer = 1.0 - np.exp(-1j * np.outer(omega, j)) @ np.asarray(ar_coefficients, dtype=np.float64)
        return 1.0 / np.abs(transfer) ** 2
    raise ValueError(f"term={term!r}: must be one of {TERMS}")


def variogram(increment_covariance: np.ndarray) -> np.ndarray:
    """D(h) = Σ_{|k|<h} (h − |k|) γ_z(k), h = 0 … len(γ_z): each step adds γ_z(0) + 2 Σ_{0<k<h} γ_z(k)."""
    if not len(increment_covariance):
        raise ValueError("increment_covariance: must hold γ_z(0) at least (an empty array was given)")
    steps = increment_covariance[0] + 2.0 * np.concatenate(([0.0], np.cumsum(increment_covariance[1:])))
    return np.concatenate(([0.0], np.cumsum(steps)))


def allan_variance_from_increments(increment_covariance: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """σ_A²(m) = Σ_{|j|<m} (m − |j|) [D(|m + j|) − D(|j|)] / (2m²) from γ_z(0 … 2m − 1) (module text)."""
    sizes = cluster_sizes(sizes)
    if len(increment_covariance) < 2 * int(np.max(sizes)):
        raise ValueError(
            f"increment_covariance: holds {len(increment_covariance)} lags; m={int(np.max(sizes))} needs "
            f"γ_z(0 … 2m − 1), {2 * int(np.max(sizes))} lags"
        )
    D = variogram(increment_covariance[: 2 * int(np.max(sizes))])
    result = np.empty(len(sizes))
    for i, m in enumerate(int(value) for value in sizes):
        # m + j runs over 1 … 2m − 1 with weights 1 … m … 1; |j| over 0 … m − 1 with m, 2(m − 1), …, 2.
        # (einsum, not np.dot: a threaded BLAS dot stalls on a loaded machine for no gain at this size)
        rising = np.arange(1, m + 1, dtype=np.float64)
        shifted = np.einsum("i,i->", rising, D[1 : m + 1]) + np.einsum(
            "i,i->", rising[-2::-1], D[m + 1 : 2 * m]
        )
        centred = m * D[0] + 2.0 * np.einsum("i,i->", rising[-2::-1], D[1:m])
        result[i] = float(shifted - centred) / (2.0 * m * m)
    return result


def cluster_sizes(sizes: Any, name: str = "sizes") -> np.ndarray:
    """``sizes`` as a 1-D int64 array after checking them: integers (or integral floats), each ≥ 1;
    messages name them ``name``."""
    given = np.atleast_1d(np.asarray(sizes))
    if given.ndim != 1 or not len(given):
        raise ValueError(f"{name}={sizes!r}: must be a non-empty 1-D array of cluster sizes (samples)")
    if given.dtype.kind not in "iu" and not (
        given.dtype.kind == "f" and np.all(np.isfinite(given)) and np.all(given == np.rint(given))
    ):
        raise TypeError(f"{name}={sizes!r}: cluster sizes must be integers (samples per cluster)")
    if np.min(given) < 1:
        raise ValueError(f"{name}={sizes!r}: every cluster size must be >= 1 sample")
    return given.astype(np.int64)


def _check_term(term: str, flicker_d: Any, ar_coefficients: Any) -> None:
    """Refuse an unknown term, a 1/f order outside 0 < d < 1, and AR coefficients that are not a
    non-empty stationary tuple for the AR term."""
    if term not in TERMS:
        raise ValueError(f"term={term!r}: must be one of {TERMS}")
    if term == "flicker":
        check_fractional_order("flicker_d", flicker_d)
    if term == "ar":
        check_ar_coefficients(ar_coefficients)
        if not ar_coefficients:
            raise ValueError("ar_coefficients=(): the AR term needs at least one coefficient")


def term_allan_variance(
    term: str, sizes: Any, flicker_d: float = 0.5, ar_coefficients: tuple[float, ...] = ()
) -> np.ndarray:
    """Exact Allan variance of one term (unit driving variance; quantization with f_s Q = 1) at m = sizes.

    White, rate random walk and quantization from the SymPy closed forms; 1/f from the closed-form fourth
    sum of its increment autocovariance and AR from the fourth sum of its finite γ_z
    (:mod:`carousel_theory.increment_sums`), O(1) per τ.
    """
    m = cluster_sizes(sizes)
    _check_term(term, flicker_d, ar_coefficients)
    if term == "white":
        return np.asarray(_white_numeric(1.0, m.astype(np.float64)), dtype=np.float64)
    if term == "rrw":
        return np.asarray(_rrw_numeric(1.0, m.astype(np.float64)), dtype=np.float64)
    if term == "quantization":  # Q = Δt: f_s Q = 1
        return np.asarray(_quantization_numeric(1.0, m.astype(np.float64), 1.0), dtype=np.float64)
    if term == "flicker":  # O(1) per τ: the telescoped fourth sum of the Gamma ratio
        return np.array(flicker_allan_variance_closed(float(flicker_d), tuple(m.tolist())))
    if term == "ar":  # O(T) per τ, T the AR reach: the fourth sum of the finite γ_z
        lags = ar_increment_reach(tuple(ar_coefficients)) + 1
        gamma = increment_autocovariance(term, lags, flicker_d, ar_coefficients)
        # Σ_k γ_z(k) = 0 exactly for the increments of a stationary process
        return allan_variance_from_fourth_sum(lambda x: finite_fourth_sum(gamma, x, total=0.0), m)
    raise ValueError(f"term={term!r}: must be one of {TERMS}")
