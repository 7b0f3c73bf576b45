"""Allan variance: estimators, confidence intervals, and the exact Allan variance of discrete noise models.

Estimators
    non-overlapping, exactly TIM 2014 eq. (20): the data are cut into M disjoint bins of m samples
    (τ = m/f_s, a trailing partial bin is dropped) and
    σ_A²(τ) = 1/(2(M−1)) Σ_{j=1}^{M−1} (ȳ_{j+1} − ȳ_j)²;
    overlapping: the same difference taken at every start sample s = 0 … n−2m (n − 2m + 1 terms).
    Both equal allantools' ``adev``/``oadev`` (squared, ``data_type="freq"``) on the same input.

Confidence intervals
    Each estimate is a quadratic form Σ_s d_s² of Gaussian differences d_s. With c(k) the covariance of
    the differences at a lag of k samples, its mean is K·c(0) and its variance 2 Σ_{s,r} c(s−r)², so the
    equivalent degrees of freedom (Satterthwaite; Greenhall and Riley's EDF) are
    ν = K² c(0)² / (K c(0)² + 2 Σ_{l≥1} (K−l) c(l·p)²), p the stride (m or 1).
    For a named noise type c(k) comes from that process's exact filter (1/f: the fractional-integration
    filter truncated at the record length); for a :class:`carousel_theory.noise_model.NoiseModel` the
    variance of each estimate comes from :mod:`carousel_theory.tau_covariance` (closed form for white,
    rate random walk and quantization, finite lag sums for 1/f and AR) and ν = 2σ_A⁴/Var σ̂². The
    interval is
    ν σ̂²/χ²_ν((1+level)/2) … ν σ̂²/χ²_ν((1−level)/2) (scipy.stats.chi2).

Speed
    Octave overlapping sums: the window sums at m = 1, 2, 4, … ≤ 2048 are doubled level by level inside
    chunks of 16384 starts that stay in cache (one read of the record for all those levels); larger m
    double whole arrays in place. Squares are summed without BLAS (a threaded ddot costs more in
    synchronisation than it saves). The arithmetic is the same pairwise doubling as before, so the values
    equal allantools' to ~1e-12.

Model Allan variance
    The expected value of the estimator for each discrete process of TIM 2014 §II, exactly (not the
    asymptotic slopes): white σ²/m, rate random walk σ_q²(2m²+1)/(6m) (derived in
    ``derivations/allan_variance_models.md``), quantization 3Q²/τ², and 1/f noise by fractional
    integration (eq. (3)) for any 0 < d < 1, whose Allan variance depends on the position in the record
    and hence on the record length, evaluated with the cumulative coefficients Ψ_u = Σ_{j≤u} ψ_j.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp
from scipy import stats

from carousel_theory import symbols
from carousel_theory._validation import (
    check_finite_array,
    check_fractional_order,
    check_positive_integer,
    check_positive_real,
    check_probability,
)
from carousel_theory.binary_scaling import binary_exponent, scaled_by_power_of_two
from carousel_theory.data import RESERVED_COLUMN_NAMES, TIME_COLUMN_NAMES, Recording, recording_from_arrays
from carousel_theory.lag_plan import WEIGHTS_RULE
from carousel_theory.noise_model import (
    QUANTIZATION_ALLAN_VARIANCE,
    RRW_ALLAN_VARIANCE,
    WHITE_ALLAN_VARIANCE,
    NoiseModel,
    cluster_sizes,
    term_allan_variance,
)
from carousel_theory.processes import fractional_coefficients
from carousel_theory.tau_covariance import allan_estimate_variance

__all__ = [
    "ESTIMATORS",
    "NOISE_TYPES",
    "QUANTIZATION_ALLAN_VARIANCE",
    "RRW_ALLAN_VARIANCE",
    "WHITE_ALLAN_VARIANCE",
    "AllanResult",
    "AllanResultsByAxis",
    "allan_covariance",
    "allan_variance",
    "check_tau_range",
    "difference_covariance",
    "equivalent_degrees_of_freedom",
    "flicker_allan_variance",
    "graycode_allan_variance",
    "model_allan_variance",
    "octave_cluster_sizes",
    "with_model_intervals",
]

ESTIMATORS = ("overlapping", "non-overlapping")
NOISE_TYPES = ("white", "rrw", "flicker", "quantization")

# Symbols of the closed forms (carousel_theory.symbols): m samples per cluster, per-sample variances,
# sample interval. The closed forms themselves live in carousel_theory.noise_model.
_m = symbols.cluster_size
_white_variance = symbols.white_sample_variance
_rrw_variance = symbols.rrw_increment_variance
_quantization = symbols.quantization_step
_sample_interval = symbols.sample_interval

_white_numeric = sp.lambdify((_white_variance, _m), WHITE_ALLAN_VARIANCE, "numpy")
_rrw_numeric = sp.lambdify((_rrw_variance, _m), RRW_ALLAN_VARIANCE, "numpy")
_quantization_numeric = sp.lambdify(
    (_quantization, _m, _sample_interval), QUANTIZATION_ALLAN_VARIANCE, "numpy"
)


@dataclass(frozen=True)
class AllanResult:
    """Allan variance estimates at a set of averaging times.

    Attributes
    ----------
    tau : ndarray
        Averaging times τ = m / f_s in s.
    avar : ndarray
        Allan variance estimates ((rad/s)² for rates in rad/s).
    ci_low, ci_high : ndarray
        Confidence interval at level ``confidence`` (χ² with ``edf`` degrees of freedom).
    clusters : ndarray
        Number M of disjoint clusters (bins) of τ in the record, as in TIM 2014 eq. (20).
    estimator : str
        "overlapping" or "non-overlapping".
    samples_per_cluster : ndarray
        m = τ f_s.
    terms : ndarray
        Number of squared differences averaged (M − 1, or n − 2m + 1 when overlapping).
    edf : ndarray
        Equivalent degrees of freedom of each estimate under ``noise``.
    confidence : float
        Level of the intervals.
    noise : str
        The noise model that the degrees of freedom assume.
    """

    tau: np.ndarray
    avar: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    clusters: np.ndarray
    estimator: str
    samples_per_cluster: np.ndarray | None = None
    terms: np.ndarray | None = None
    edf: np.ndarray | None = None
    confidence: float = 0.95
    noise: str = "white"
    deviation: np.ndarray | None = None
    deviation_low: np.ndarray | None = None
    deviation_high: np.ndarray | None = None

    @property
    def adev(self) -> np.ndarray:
        """Allan deviation √σ_A².

        Computed at the data's own power-of-two scale, so that it is finite and non-zero whenever the
        true deviation is, even where σ_A² itself leaves float64's range (rates near 10³⁰⁰ or 10⁻³⁰⁰).
        """
        return np.sqrt(self.avar) if self.deviation is None else self.deviation

    @property
    def adev_interval(self) -> tuple[np.ndarray, np.ndarray]:
        """The confidence interval of :attr:`adev` (the square roots of ``ci_low`` and ``ci_high``)."""
        if self.deviation_low is None or self.deviation_high is None:
            return np.sqrt(self.ci_low), np.sqrt(self.ci_high)
        return self.deviation_low, self.deviation_high


def octave_cluster_sizes(length: int) -> np.ndarray:
    """m = 1, 2, 4, … with τ at most a third of the record (m ≤ n/3, so at least 3 clusters)."""
    length = check_positive_integer("length", length, minimum=3)
    count = int(np.floor(np.log2(length / 3))) + 1
    return 2 ** np.arange(count, dtype=np.int64)


def _check_estimator(estimator: Any) -> str:
    if estimator not in ESTIMATORS:
        raise ValueError(f"estimator={estimator!r}: must be one of {ESTIMATORS}")
    return str(estimator)


def _cluster_sizes(taus: Any, sample_rate: float, length: int) -> tuple[np.ndarray, bool]:
    """Samples per cluster for ``taus`` and whether they are the octave sequence."""
    if isinstance(taus, str):
        if taus != "octave":
            raise ValueError(f"taus={taus!r}: must be 'octave' or an array of averaging times in s")
        if length < 3:
            raise ValueError(f"y: needs at least 3 samples for an Allan variance, got {length}")
        return octave_cluster_sizes(length), True
    tau_array = check_finite_array("taus", np.atleast_1d(taus))
    sizes = tau_array * sample_rate
    rounded = np.rint(sizes)
    bad = np.flatnonzero((rounded < 1) | (np.abs(sizes - rounded) > 1e-9 * np.maximum(sizes, 1.0)))
    if bad.size:
        i = int(bad[0])
        raise ValueError(
            f"taus[{i}]={tau_array[i]!r}: must be a positive whole number of sample intervals "
            f"(1/{sample_rate:g} s)"
        )
    sizes = rounded.astype(np.int64)
    too_long = np.flatnonzero(3 * sizes > length)
    if too_long.size:
        i = int(too_long[0])
        raise ValueError(
            f"taus[{i}]={tau_array[i]!r}: longer than a third of the recording ({length} samples = "
            f"{length / sample_rate:.6g} s); at least 3 clusters are needed"
        )
    if np.any(np.diff(sizes) <= 0):
        raise ValueError(f"taus={tau_array!r}: must be strictly increasing")
    return sizes, False


def _non_overlapping_sums(centered: np.ndarray, sizes: np.ndarray, octave: bool) -> np.ndarray:
    """Σ of squared differences of adjacent disjoint-bin *sums*, per cluster size."""
    result = np.empty(len(sizes))
    if octave:
        # Bin sums at 2m are pairwise sums of those at m: O(n) in all, and pairwise summation is accurate.
        sums = centered
        for level in range(len(sizes)):
            if level:
                count = len(sums) // 2
                sums = sums[: 2 * count : 2] + sums[1 : 2 * count : 2]
            differences = np.diff(sums)
            result[level] = np.dot(differences, differences)
        return result
    for i, m in enumerate(sizes):
        count = len(centered) // m
        sums = centered[: count * m].reshape(count, m).sum(axis=1)
        differences = np.diff(sums)
        result[i] = np.dot(differences, differences)
    return result


#: Samples per chunk of the overlapping sums (8 × 2¹⁴ bytes: the chunk stays in the L2 cache).
_CHUNK = 1 << 14


def _squared_difference_sum(window: np.ndarray, m: int, terms: int, buffer: np.ndarray) -> float:
    """Σ_{s<terms} (window[s + m] − window[s])², chunk by chunk."""
    total = 0.0
    for start in range(0, terms, len(buffer)):
        stop = min(start + len(buffer), terms)
        chunk = buffer[: stop - start]
        np.subtract(window[m + start : m + stop], window[start:stop], out=chunk)
        # Square and add without BLAS: a threaded ddot costs more in synchronisation than it saves here.
        np.multiply(chunk, chunk, out=chunk)
        total += float(np.add.reduce(chunk))
    return total


#: Octave levels with m up to this many samples are computed together, chunk by chunk, in cache.
_FUSED_MAXIMUM = 2048


def _fused_small_levels(centered: np.ndarray, small: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Sums of squared differences for the small octave m, and the window sums at the largest of them.

    Each chunk of starts is read once; its window sums are doubled level by level in cache
    (w_{2m}[s] = w_m[s] + w_m[s + m], the same additions as a global doubling).
    """
    length, largest = len(centered), int(small[-1])
    totals = np.zeros(len(small))
    windows = np.empty(length - largest + 1)
    for first in range(0, length - 1, _CHUNK):
        window = centered[first : first + _CHUNK + 2 * largest]
        for level, m in enumerate(int(value) for value in small):
            if level:
                if len(window) <= m // 2:  # the record ends inside this chunk: no window of length m
                    break
                window = window[: len(window) - m // 2] + window[m // 2 :]
            valid = min(_CHUNK, length - 2 * m + 1 - first)
            if valid > 0:
                difference = window[m : m + valid] - window[:valid]
                np.multiply(difference, difference, out=difference)
                totals[level] += float(np.add.reduce(difference))
        count = min(_CHUNK, length - largest + 1 - first)
        if count > 0:
            windows[first : first + count] = window[:count]
    return totals, windows


def _overlapping_octave_sums(centered: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """Octave overlapping sums: small m fused in cache, larger m by in-place doubling between two buffers."""
    small = sizes[sizes <= _FUSED_MAXIMUM]
    totals, window = _fused_small_levels(centered, small)
    result = np.empty(len(sizes))
    result[: len(small)] = totals
    if len(small) == len(sizes):
        return result
    spare = centered[: len(window)]  # ``centered`` (our own array) is read no more: reuse its memory
    buffer = np.empty(min(_CHUNK, len(window)))
    count = len(window)  # number of windows of the current length
    for level in range(len(small), len(sizes)):
        m = int(sizes[level])
        count -= m // 2
        np.add(window[:count], window[m // 2 : m // 2 + count], out=spare[:count])
        window, spare = spare, window
        result[level] = _squared_difference_sum(window, m, count - m, buffer)
    return result


def _overlapping_sums(centered: np.ndarray, sizes: np.ndarray, octave: bool) -> np.ndarray:
    """Σ over every start sample of the squared difference of adjacent window sums, per cluster size.

    Overwrites ``centered`` on the octave path (callers pass an array of their own).
    """
    if octave:
        return _overlapping_octave_sums(centered, sizes)
    result = np.empty(len(sizes))
    cumulative = np.concatenate(([0.0], np.cumsum(centered)))
    for i, m in enumerate(sizes):
        window = cumulative[m:] - cumulative[:-m]
        differences = window[m:] - window[:-m]
        result[i] = np.dot(differences, differences)
    return result


def _component_filters(
    noise: Any, m: int, length: int, sample_rate: float
) -> list[tuple[float, np.ndarray | None]]:
    """(driving variance, filter) pairs whose filters map unit white noise to the cluster-sum difference."""
    if isinstance(noise, str):
        if noise not in NOISE_TYPES:
            raise ValueError(f"noise={noise!r}: must be one of {NOISE_TYPES} or a NoiseModel")
        parts = {noise: 1.0}
        d = 0.5 if noise == "flicker" else None
    else:
        parts = {
            "white": float(noise.white_variance),
            "rrw": float(noise.rrw_variance),
            "flicker": float(noise.flicker_variance),
            "quantization": float(noise.quantization) ** 2 * sample_rate**2,
        }
        d = noise.flicker_d
        parts = {name: value for name, value in parts.items() if value > 0}
        if not parts:
            raise ValueError(f"noise={noise!r}: the model has no noise component")
    filters = []
    for name, variance in parts.items():
        taps: np.ndarray | None
        if name == "white":
            taps = None  # see difference_covariance
        elif name == "rrw":
            taps = np.concatenate((np.arange(m, dtype=np.float64), np.arange(m, 0, -1, dtype=np.float64)))
        elif name == "quantization":
            taps = np.zeros(2 * m + 1)
            taps[[0, m, 2 * m]] = (1.0, -2.0, 1.0)
        else:
            taps = _second_difference_of_cumulative_psi(0.5 if d is None else float(d), m, length)
        filters.append((variance, taps))
    return filters


@functools.lru_cache(maxsize=2)  # arrays of the record length: keep few
def _cumulative_psi(d: float, length: int) -> np.ndarray:
    """Ψ_u = Σ_{k≤u} ψ_k, u = 0 … length−1 (cached: the fit evaluates it for many τ at one d)."""
    values = np.cumsum(fractional_coefficients(d, length))
    values.setflags(write=False)
    return values


def _second_difference_of_cumulative_psi(d: float, m: int, length: int) -> np.ndarray:
    """G(u) = Ψ_u − 2Ψ_{u−m} + Ψ_{u−2m}, u = 0 … length−1, with Ψ_u = Σ_{k≤u} ψ_k and Ψ = 0 below 0."""
    psi_sum = _cumulative_psi(d, length)
    G = psi_sum.copy()
    if m < length:
        G[m:] -= 2.0 * psi_sum[:-m]
    if 2 * m < length:
        G[2 * m :] += psi_sum[: -2 * m]
    return G


def _checked_difference(m: Any, length: Any) -> tuple[int, int]:
    """(m, length) after checking them: integers, m ≥ 1, and 2m ≤ length (a cluster-sum difference)."""
    length = check_positive_integer("length", length, minimum=2)
    m = check_positive_integer("m", m)
    if 2 * m > length:
        raise ValueError(
            f"m={m}: a difference of two cluster sums needs 2m samples; length={length} holds m <= "
            f"{length // 2}"
        )
    return m, length


def difference_covariance(
    noise: Any, m: int, lags: np.ndarray, length: int, sample_rate: float = 1.0
) -> np.ndarray:
    """Covariance of the cluster-sum differences d_s and d_{s+k} at the given lags k (samples).

    ``noise`` is a noise-type name (unit driving variance) or a NoiseModel. The 1/f filter is truncated
    at ``length`` samples, which is exact for the last difference of a record of that length.
    """
    m, length = _checked_difference(m, length)
    sample_rate = check_positive_real("sample_rate", sample_rate)
    given = np.atleast_1d(np.asarray(lags))
    if given.ndim != 1 or given.dtype.kind not in "iu":
        raise TypeError(f"lags={lags!r}: must be a 1-D array of integer lags (samples)")
    lags = np.abs(given.astype(np.int64))
    total = np.zeros(len(lags))
    for variance, taps in _component_filters(noise, m, length, sample_rate):
        if taps is None:  # white noise: the autocovariance of the ±1 taps in closed form
            k = lags.astype(np.float64)
            total += variance * np.where(lags <= m, 2 * m - 3 * k, np.where(lags < 2 * m, k - 2 * m, 0.0))
            continue
        size = 1 << int(np.ceil(np.log2(2 * len(taps))))
        spectrum = np.fft.rfft(taps, size)
        autocovariance = np.fft.irfft(spectrum * np.conj(spectrum), size)[: len(taps)]
        inside = lags < len(taps)
        total[inside] += variance * autocovariance[lags[inside]]
    return total


def _model_parts(model: Any) -> dict[str, float]:
    """Driving variance of each component of a NoiseModel (quantization as the variance of fs·e)."""
    parts = {
        "white": float(model.white_variance),
        "rrw": float(model.rrw_variance),
        "flicker": float(model.flicker_variance),
        "quantization": float(model.quantization) ** 2 * float(model.sample_rate) ** 2,
    }
    return {name: value for name, value in parts.items() if value > 0}


def _positioned_taps(name: str, m: int, length: int, d: float, reach: int) -> tuple[np.ndarray, int]:
    """Taps g and offset o such that the cluster-sum difference starting at sample a is
    Σ_k g[k] e_{a + o + k} for the component's unit white driving noise e."""
    if name == "white":
        return np.concatenate((-np.ones(m), np.ones(m))), 0
    if name == "rrw":
        return np.concatenate((np.arange(m, dtype=np.float64), np.arange(m, 0, -1, dtype=np.float64))), 0
    if name == "quantization":
        taps = np.zeros(2 * m + 1)
        taps[[0, m, 2 * m]] = (1.0, -2.0, 1.0)
        return taps, -1
    taps_length = min(length, reach)
    G = _second_difference_of_cumulative_psi(d, m, taps_length)
    return G[::-1].copy(), 2 * m - taps_length


#: The 1/f filter is cut at this many cluster lengths in :func:`allan_covariance` (its tail decays
#: as u^{d−2}).
FLICKER_REACH_IN_CLUSTERS = 8
#: ... and never shorter than this many samples (short clusters need the tail most).
FLICKER_MINIMUM_REACH = 1024


def _overlap(start_a: Any, end_a: Any, start_b: Any, end_b: Any) -> Any:
    """Length of the intersection of the integer ranges [start_a, end_a) and [start_b, end_b)."""
    return np.maximum(0, np.minimum(end_a, end_b) - np.maximum(start_a, start_b))


def _cross_correlation(
    name: str, m_i: int, m_j: int, g_i: np.ndarray, g_j: np.ndarray, spectra: dict | None = None
) -> np.ndarray:
    """X(l) = Σ_k g_i[k] g_j[k + l] for l = −(len g_i − 1) … len g_j − 1 (as np.correlate(g_j, g_i, "full")).

    White (two ±1 boxes): sums of interval overlaps, exact in integers. Rate random walk: its taps are
    the reversed cumulative sums of the white taps, so its correlation is minus the double cumulative
    sum of the white one, shifted by one lag. Quantization: nine spikes. 1/f: by FFT.
    """
    if name in ("white", "rrw"):
        lags = np.arange(-(2 * m_i - 1), 2 * m_j)
        X = (
            _overlap(0, m_i, -lags, m_j - lags)
            - _overlap(0, m_i, m_j - lags, 2 * m_j - lags)
            - _overlap(m_i, 2 * m_i, -lags, m_j - lags)
            + _overlap(m_i, 2 * m_i, m_j - lags, 2 * m_j - lags)
        ).astype(np.float64)
        if name == "white":
            return X
        double = -np.cumsum(np.cumsum(X))
        return np.concatenate(([0.0], double[:-1]))
    if name == "quantization":
        X = np.zeros(len(g_i) + len(g_j) - 1)
        for position_i, weight_i in ((0, 1.0), (m_i, -2.0), (2 * m_i, 1.0)):
            for position_j, weight_j in ((0, 1.0), (m_j, -2.0), (2 * m_j, 1.0)):
                X[position_j - position_i + len(g_i) - 1] += weight_i * weight_j
        return X
    size = 1 << int(np.ceil(np.log2(len(g_i) + len(g_j))))
    spectra = {} if spectra is None else spectra
    for key, taps in (((m_i, size), g_i), ((m_j, size), g_j)):
        if key not in spectra:  # each τ's filter is transformed once per FFT size
            spectra[key] = np.fft.rfft(taps, size)
    wrapped = np.fft.irfft(np.conj(spectra[(m_i, size)]) * spectra[(m_j, size)], size)
    lags = np.arange(-(len(g_i) - 1), len(g_j))
    return wrapped[lags % size]


def _offsets_and_pairs(
    estimator: str, sizes: np.ndarray, m_i: int, m_j: int, K_i: int, K_j: int, low: int, high: int
) -> tuple[np.ndarray, np.ndarray]:
    """Offsets δ between the starts of two differences and the number of pairs at each (dense reference)."""
    if estimator == "overlapping":
        delta = np.arange(low, high + 1)
        return delta, np.minimum(K_j, K_i - delta) - np.maximum(0, -delta)
    if m_j % m_i:
        raise ValueError(
            f"tau_samples={sizes!r}: for the non-overlapping estimator each cluster size must "
            "divide the larger ones (use octave τ)"
        )
    ratio = m_j // m_i
    k = np.arange(low // m_i - 1, -(-high // m_i) + 2)
    r_low = np.maximum(0, -(k // ratio))
    r_high = np.minimum(K_j - 1, (K_i - 1 - k) // ratio)
    return k * m_i, r_high - r_low + 1


def allan_covariance(
    model: NoiseModel, tau_samples: Any, length: int, *, estimator: str = "overlapping"
) -> np.ndarray:
    """Covariance matrix of the Allan variance estimates at ``tau_samples`` for Gaussian noise of ``model``.

    Cov(σ̂²_i, σ̂²_j) = 2 Σ_s Σ_r cov(d_{i,s}, d_{j,r})² / (4 m_i² m_j² K_i K_j), with d the cluster-sum
    differences and K their numbers. The covariances come from the exact filters of each component; the
    1/f filter is cut at ``FLICKER_REACH_IN_CLUSTERS`` cluster lengths (and at ``length``), which the
    stationary approximation of the nonstationary eq. (3) process needs anyway. For the non-overlapping
    estimator each larger cluster size must be a multiple of each smaller one (octave τ).
    """
    estimator = _check_estimator(estimator)
    length = check_positive_integer("length", length, minimum=3)
    sizes = _check_tau_samples(tau_samples, length)
    parts = _model_parts(model)
    if not parts:
        raise ValueError(f"model={model!r}: the model has no noise component")
    d = float(model.flicker_d)
    terms = length - 2 * sizes + 1 if estimator == "overlapping" else length // sizes - 1
    taps = [
        {
            name: _positioned_taps(
                name, int(m), length, d, max((FLICKER_REACH_IN_CLUSTERS + 2) * int(m), FLICKER_MINIMUM_REACH)
            )
            for name in parts
        }
        for m in sizes
    ]
    count = len(sizes)
    result = np.empty((count, count))
    spectra: dict = {}
    for i in range(count):
        for j in range(i, count):
            m_i, m_j, K_i, K_j = int(sizes[i]), int(sizes[j]), int(terms[i]), int(terms[j])
            low = min(-(len(taps[i][c][0]) - 1) - taps[i][c][1] + taps[j][c][1] for c in parts)
            high = max(len(taps[j][c][0]) - 1 - taps[i][c][1] + taps[j][c][1] for c in parts)
            delta, pairs = _offsets_and_pairs(estimator, sizes, m_i, m_j, K_i, K_j, low, high)
            pairs = np.maximum(pairs, 0)
            covariance = np.zeros(len(delta))
            for name, variance in parts.items():
                g_i, o_i = taps[i][name]
                g_j, o_j = taps[j][name]
                cross = _cross_correlation(name, m_i, m_j, g_i, g_j, spectra)
                index = delta + o_i - o_j + len(g_i) - 1  # lag l sits at l + len(g_i) − 1
                inside = (index >= 0) & (index < len(cross))
                covariance[inside] += variance * cross[index[inside]]
            total = float(np.dot(pairs, covariance**2))
            result[i, j] = result[j, i] = total / (2.0 * m_i**2 * m_j**2 * K_i * K_j)
    return result


def equivalent_degrees_of_freedom(
    noise: Any, m: int, terms: int, stride: int, length: int, sample_rate: float = 1.0
) -> float:
    """ν = K² c(0)² / (K c(0)² + 2 Σ_{l=1}^{K−1} (K − l) c(l p)²) for K terms at stride p (Gaussian noise)."""
    m, length = _checked_difference(m, length)
    terms = check_positive_integer("terms", terms)
    stride = check_positive_integer("stride", stride)
    if isinstance(noise, str) and noise == "white" and stride == 1:
        # c(l) = 2m − 3l (l ≤ m), l − 2m (m < l < 2m): the sum in exact integers by power sums, O(1).
        last = min(terms - 1, 2 * m - 1)
        total = _weighted_square_sum(terms, 2 * m, -3, 1, min(m, last))
        total += _weighted_square_sum(terms, -2 * m, 1, m + 1, last)
        return float(Fraction(terms**2 * 4 * m * m, terms * 4 * m * m + 2 * total))
    reach = 2 * m + 1 if not _has_flicker(noise) else length
    count = min(terms, reach // stride + 2)
    lags = np.arange(count, dtype=np.int64) * stride
    covariance = difference_covariance(noise, m, lags, length, sample_rate)
    weights = terms - np.arange(count, dtype=np.float64)
    denominator = terms * covariance[0] ** 2 + 2.0 * np.dot(weights[1:], covariance[1:] ** 2)
    return float(terms**2 * covariance[0] ** 2 / denominator)


def _power_sum(power: int, first: int, last: int) -> int:
    """Σ_{l=first}^{last} l^power for power 0 … 3 (0 when last < first), in exact integers."""
    if last < first:
        return 0

    def upto(n: int) -> int:
        return (n, n * (n + 1) // 2, n * (n + 1) * (2 * n + 1) // 6, (n * (n + 1) // 2) ** 2)[power]

    return upto(last) - upto(first - 1)


def _weighted_square_sum(K: int, a: int, b: int, first: int, last: int) -> int:
    """Σ_{l=first}^{last} (K − l)(a + b l)², expanded into power sums."""
    s0, s1, s2, s3 = (_power_sum(p, first, last) for p in range(4))
    return K * (a * a * s0 + 2 * a * b * s1 + b * b * s2) - (a * a * s1 + 2 * a * b * s2 + b * b * s3)


def _has_flicker(noise: Any) -> bool:
    if isinstance(noise, str):
        return noise == "flicker"
    return float(noise.flicker_variance) > 0


def _check_options(sample_rate: Any, estimator: Any, noise: Any, confidence: Any) -> tuple[float, str, float]:
    sample_rate = float(check_positive_real("sample_rate", sample_rate))
    estimator = _check_estimator(estimator)
    confidence = check_probability("confidence", confidence)
    if isinstance(noise, str) and noise not in NOISE_TYPES:
        raise ValueError(f"noise={noise!r}: must be one of {NOISE_TYPES} or a NoiseModel")
    return sample_rate, estimator, confidence


def allan_variance(
    y: Any,
    sample_rate: float | None = None,
    taus: Any = "octave",
    *,
    estimator: str = "overlapping",
    noise: Any = "white",
    confidence: float = 0.95,
    tau_range: tuple[float | None, float | None] | None = None,
) -> Any:
    """Allan variance of the rate samples ``y`` with χ² confidence intervals.

    Parameters
    ----------
    y : 1-D array, 2-D array, pandas DataFrame or Recording
        Rate samples (rad/s), uniformly sampled. A 1-D array gives an :class:`AllanResult`, the others an
        :class:`AllanResultsByAxis`: a 2-D array one axis per column (wx, wy, wz; w0, w1, … beyond
        three), a DataFrame one per column except its time column (t, time, time_s, timestamp: s or
        datetime64, checked for uniform steps) and those of ``data.RESERVED_COLUMN_NAMES``.
    sample_rate : float
        Samples per second (not for a Recording or a DataFrame with a time column).
    taus : "octave" or array of float
        "octave": τ = 2^k/f_s up to a third of the record; or τ in s, whole numbers of samples, ≤ n/3.
    tau_range : (low, high), optional
        Only τ in [low, high] s; either end may be None (open): ``(0.1, None)``.
    estimator : {"overlapping", "non-overlapping"}
        "non-overlapping" is TIM 2014 eq. (20).
    noise : str or NoiseModel
        Assumed for the degrees of freedom: "white", "rrw", "flicker" (d = 1/2), "quantization", or a model.
    confidence : float
        Level of the intervals, in (0, 1).
    """
    options = {"estimator": estimator, "noise": noise, "confidence": confidence, "tau_range": tau_range}
    if isinstance(y, Recording) or _is_data_frame(y) or np.ndim(y) == 2:
        return _allan_variance_by_axis(y, sample_rate, taus, options)
    sample_rate, estimator, confidence = _check_options(
        _required_rate(sample_rate), estimator, noise, confidence
    )
    check_tau_range(tau_range)
    samples = check_finite_array("y", y, min_length=3)
    length, clusters = len(samples), _cluster_sizes(taus, sample_rate, len(samples))
    sizes, scaled, terms, exponent = _estimates(samples, clusters, estimator, tau_range, sample_rate)
    edf = _degrees_of_freedom(noise, sizes, terms, length, sample_rate, estimator)
    (avar, ci_low, ci_high), deviations = _unscaled(
        (scaled, *_chi_square_interval(scaled, edf, confidence)), exponent
    )
    return AllanResult(
        tau=sizes / sample_rate,
        avar=avar,
        ci_low=ci_low,
        ci_high=ci_high,
        clusters=length // sizes,
        estimator=estimator,
        samples_per_cluster=sizes,
        terms=terms,
        edf=edf,
        confidence=confidence,
        noise=noise if isinstance(noise, str) else "model",
        **dict(zip(("deviation", "deviation_low", "deviation_high"), deviations, strict=True)),
    )


def _unscaled(variances: tuple[np.ndarray, ...], exponent: int) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """The Allan variances (and their deviations) of the unscaled samples from those of the samples scaled
    by 2⁻ᵉ (:func:`_scaled_centered`): σ_A² = 4ᵉ · the scaled variance, exactly in binary."""
    with np.errstate(over="ignore", under="ignore"):  # σ_A² may leave float64's range; σ_A does not
        return (
            [np.ldexp(values, 2 * exponent) for values in variances],
            [np.ldexp(np.sqrt(values), exponent) for values in variances],
        )


def _required_rate(sample_rate: Any) -> Any:
    if sample_rate is None:
        raise ValueError(
            "sample_rate=None: required for a 1-D array of rates (a DataFrame with a time column or a "
            "Recording carries its own)"
        )
    return sample_rate


def _estimates(
    samples: np.ndarray,
    cluster_sizes: tuple[np.ndarray, bool],
    estimator: str,
    tau_range: Any = None,
    sample_rate: float = 1.0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """(cluster sizes, Allan variance of the samples scaled by 2⁻ᵉ, number of squared differences averaged,
    e), TIM 2014 eq. (20); σ_A² = 4ᵉ · the returned variance (:func:`_scaled_centered`)."""
    sizes, octave = cluster_sizes
    length = len(samples)
    centered, exponent = _scaled_centered(samples)
    if estimator == "overlapping":
        sums = _overlapping_sums(centered, sizes, octave)
        terms = length - 2 * sizes + 1
    else:
        sums = _non_overlapping_sums(centered, sizes, octave)
        terms = length // sizes - 1
    scaled = sums / (2.0 * sizes.astype(np.float64) ** 2 * terms)
    if tau_range is None:
        return sizes, scaled, terms, exponent
    kept = _in_tau_range(sizes / sample_rate, tau_range)  # only the τ in [low, high] s
    return sizes[kept], scaled[kept], terms[kept], exponent


def _scaled_centered(samples: np.ndarray) -> tuple[np.ndarray, int]:
    """(samples − mean) · 2⁻ᵉ, a new array whose largest magnitude lies in [1/2, 1), and e.

    The Allan variance ignores a constant; removing the mean keeps running sums small and accurate.
    Scaling by a power of two is exact in binary, so rates near 10³⁰⁰ no longer overflow when squared
    and rates near 10⁻³⁰⁰ no longer underflow: σ_A² = 4ᵉ · (the variance of the scaled samples).
    """
    first = binary_exponent(samples)
    centered = scaled_by_power_of_two(samples, -first)
    centered -= centered.mean()
    second = binary_exponent(centered)
    if second:
        scaled_by_power_of_two(centered, -second, out=centered)
    return centered, first + second


def _chi_square_interval(
    avar: np.ndarray, edf: np.ndarray, confidence: float
) -> tuple[np.ndarray, np.ndarray]:
    """ν σ̂²/χ²_ν((1+level)/2) … ν σ̂²/χ²_ν((1−level)/2)."""
    upper_quantile = stats.chi2.ppf((1.0 + confidence) / 2.0, edf)
    lower_quantile = stats.chi2.ppf((1.0 - confidence) / 2.0, edf)
    return edf * avar / upper_quantile, edf * avar / lower_quantile


def _degrees_of_freedom(
    noise: Any, sizes: np.ndarray, terms: np.ndarray, length: int, sample_rate: float, estimator: str
) -> np.ndarray:
    """ν at each m: for a NoiseModel 2σ_A⁴/Var σ̂² from the exact τ-covariance engine
    (:mod:`carousel_theory.tau_covariance`; 1/f and AR by the lag quadrature's
    :data:`~carousel_theory.lag_plan.WEIGHTS_RULE`, whose values agree with the proved rule's far beyond
    the digits a χ² quantile uses), otherwise by :func:`equivalent_degrees_of_freedom`."""
    if isinstance(noise, NoiseModel):
        if not noise.terms():
            raise ValueError(f"noise={noise!r}: the model has no noise component")
        variance = allan_estimate_variance(noise, sizes, length, estimator=estimator, rule=WEIGHTS_RULE)
        return np.asarray(2.0 * noise.allan_variance(sizes) ** 2 / variance, dtype=np.float64)
    return np.array(
        [
            equivalent_degrees_of_freedom(
                noise, int(m), int(k), 1 if estimator == "overlapping" else int(m), length, sample_rate
            )
            for m, k in zip(sizes, terms, strict=True)
        ]
    )


def with_model_intervals(result: AllanResult, model: NoiseModel, length: int) -> AllanResult:
    """``result`` with degrees of freedom and χ² intervals from ``model`` (no new pass over the data)."""
    sizes = np.asarray(result.samples_per_cluster, dtype=np.int64)
    terms = np.asarray(result.terms, dtype=np.int64)
    edf = _degrees_of_freedom(model, sizes, terms, length, float(model.sample_rate), result.estimator)
    low, high = _chi_square_interval(result.avar, edf, result.confidence)
    return replace(result, edf=edf, ci_low=low, ci_high=high, noise="model")


def flicker_allan_variance(
    d: float, tau_samples: Any, length: int, estimator: str = "non-overlapping"
) -> np.ndarray:
    """Expected Allan variance of the 1/f process of TIM 2014 eq. (3) (σ_w² = 1) in a record of ``length``.

    The difference of bins j and j+1 has variance Σ_{u=0}^{(j+1)m−1} G(u)²/m² with
    G(u) = Ψ_u − 2Ψ_{u−m} + Ψ_{u−2m}, Ψ_u = Σ_{k≤u} ψ_k (Ψ = 0 for negative index); the process starts at
    t = 1, so this grows with j, and the expected estimate is its average over the differences used.
    """
    d = check_fractional_order("d", d)
    length = check_positive_integer("length", length, minimum=3)
    estimator = _check_estimator(estimator)
    sizes = _check_tau_samples(tau_samples, length)
    result = np.empty(len(sizes))
    # Not the cached _cumulative_psi: an array of the record's length should not outlive this call.
    psi_sum = np.cumsum(fractional_coefficients(float(d), length))
    for i, m in enumerate(sizes):
        if estimator == "non-overlapping":
            count = length // m
            last = np.arange(2, count + 1) * m - 1  # (j+1)m − 1 for j = 1 … M−1
        else:
            last = np.arange(0, length - 2 * m + 1) + 2 * m - 1
        result[i] = _cumulative_square_at(psi_sum, int(m), last).mean() / (2.0 * m * m)
    return result


#: Samples per block of :func:`_cumulative_square_at` (bounds its memory, does not change its values).
_SQUARE_BLOCK = 1 << 20


def _cumulative_square_at(psi_sum: np.ndarray, m: int, last: np.ndarray) -> np.ndarray:
    """C(u) = Σ_{v≤u} G(v)² at the increasing indices ``last``, G(v) = Ψ_v − 2Ψ_{v−m} + Ψ_{v−2m} as in
    :func:`_second_difference_of_cumulative_psi`, block by block: the same operations and the same
    sequential sums as one ``np.cumsum`` over the record, without the four record-length arrays that
    would need (345 MB each for a 12-hour recording at 1 kHz)."""
    values = np.empty(len(last))
    carry = 0.0
    end = int(last[-1]) + 1
    for start in range(0, end, _SQUARE_BLOCK):
        stop = min(start + _SQUARE_BLOCK, end)
        block = psi_sum[start:stop].copy()
        for shift, weight in ((m, -2.0), (2 * m, 1.0)):
            low = max(start, shift)
            if low < stop:
                block[low - start :] += weight * psi_sum[low - shift : stop - shift]
        squares = block**2
        squares[0] += carry  # the running sum carried into the block, added as np.cumsum would
        cumulative = np.cumsum(squares)
        carry = float(cumulative[-1])
        first, after = np.searchsorted(last, [start, stop])
        values[first:after] = cumulative[last[first:after] - start]
    return values


def _check_tau_samples(tau_samples: Any, length: int | None = None) -> np.ndarray:
    array = cluster_sizes(tau_samples, "tau_samples")
    if length is not None and np.any(3 * array > length):
        raise ValueError(f"tau_samples={tau_samples!r}: must be at most a third of length={length}")
    return array.astype(np.int64)


def model_allan_variance(
    model: NoiseModel, tau_samples: Any, *, length: int | None = None, estimator: str = "non-overlapping"
) -> np.ndarray:
    """Exact expected Allan variance of the discrete noise model at m = ``tau_samples`` samples.

    Sum of the independent components: white σ²/m, rate random walk σ_q²(2m²+1)/(6m), quantization 3Q²/τ²,
    the AR term (stationary: :func:`~carousel_theory.noise_model.term_allan_variance`) and 1/f
    (:func:`flicker_allan_variance`, which needs the record ``length``). The bias adds nothing.
    """
    if not isinstance(model, NoiseModel):
        raise TypeError(f"model={model!r}: must be a NoiseModel")
    sizes = _check_tau_samples(tau_samples, length)
    estimator = _check_estimator(estimator)
    m = sizes.astype(np.float64)
    total = _white_numeric(float(model.white_variance), m) + _rrw_numeric(float(model.rrw_variance), m)
    if model.ar_variance:
        total = total + float(model.ar_variance) * term_allan_variance(
            "ar", sizes, ar_coefficients=tuple(model.ar_coefficients)
        )
    if model.quantization:
        total = total + _quantization_numeric(float(model.quantization), m, 1.0 / float(model.sample_rate))
    if model.flicker_variance:
        if length is None:
            raise ValueError(
                "length=None: the Allan variance of the 1/f process of TIM 2014 eq. (3) depends on the "
                "record length; give length= (samples)"
            )
        total = total + float(model.flicker_variance) * flicker_allan_variance(
            model.flicker_d, sizes, length, estimator
        )
    return np.asarray(total, dtype=np.float64)


def graycode_allan_variance(n: int, m: int, C: float = 1.0) -> Any:
    """Exact non-overlapping Allan variance of the Gray-code sequence R_{2^n} at τ = 2^m (TIM 2014 §IV).

    Delegates to :func:`carousel_theory.graycode.allan_variance_exact`.
    """
    n = check_positive_integer("n", n, minimum=2)
    m = check_positive_integer("m", m, minimum=0)
    try:
        from carousel_theory.graycode import allan_variance_exact
    except ImportError as error:  # the Gray-code module is a separate part of the package
        raise ImportError(f"carousel_theory.graycode is not available ({error})") from None
    return allan_variance_exact(n, m, C)


# --- inputs: τ ranges, several axes at once ---------------------------------------------------------


def check_tau_range(tau_range: Any) -> tuple[float, float]:
    """``tau_range`` as (low, high) in s, an open end (None) as 0 or ∞; None means (0, ∞).

    Each given end must be a positive finite number of seconds and low must not exceed high.
    """
    if tau_range is None:
        return 0.0, math.inf
    if isinstance(tau_range, str) or not hasattr(tau_range, "__len__") or len(tau_range) != 2:
        raise ValueError(f"tau_range={tau_range!r}: must be (low, high) in seconds, either end None")
    low, high = (
        default if value is None else float(check_positive_real("tau_range", value))
        for value, default in zip(tau_range, (0.0, math.inf), strict=True)
    )
    if not low <= high:
        raise ValueError(f"tau_range={tau_range!r}: low must not exceed high")
    if not math.isfinite(low):
        raise ValueError(f"tau_range={tau_range!r}: low must be finite")
    return low, high


def _in_tau_range(tau: np.ndarray, tau_range: Any) -> np.ndarray:
    """The indices of ``tau`` within ``tau_range`` (to 1e-12 relative); refuses an empty selection."""
    low, high = check_tau_range(tau_range)
    kept = np.flatnonzero((tau >= low * (1 - 1e-12)) & (tau <= high * (1 + 1e-12)))
    if kept.size == 0:
        raise ValueError(
            f"tau_range={tau_range!r}: holds none of the τ from {tau[0]:.6g} s to {tau[-1]:.6g} s"
        )
    return kept


@dataclass(frozen=True)
class AllanResultsByAxis(Mapping[str, AllanResult]):
    """Allan variance results of several axes, read like a dict: ``results["wx"]``.

    Attributes
    ----------
    results : dict[str, AllanResult]
        One result per axis, in the order of the input's columns.
    sample_rate : float
        Samples per second of every axis.
    """

    results: dict[str, AllanResult]
    sample_rate: float

    def __getitem__(self, axis: str) -> AllanResult:
        return self.results[axis]

    def __iter__(self) -> Iterator[str]:
        return iter(self.results)

    def __len__(self) -> int:
        return len(self.results)


def _is_data_frame(y: Any) -> bool:
    return hasattr(y, "columns") and hasattr(y, "to_numpy")  # pandas, without importing it


def _axes_recording(y: Any, sample_rate: float | None) -> Recording:
    """A Recording, a 2-D array or a DataFrame as a checked Recording (rates taken as rad/s)."""
    if isinstance(y, Recording):
        if sample_rate is not None:
            raise ValueError(f"sample_rate={sample_rate!r}: a Recording carries its own; leave it unset")
        return y
    if not _is_data_frame(y):
        return recording_from_arrays(np.asarray(y), sample_rate=sample_rate, source="y")
    names = [str(name) for name in y.columns]
    time_name = next((name for name in names if name.lower() in TIME_COLUMN_NAMES), None)
    axes = [name for name in names if name.lower() not in RESERVED_COLUMN_NAMES]
    return recording_from_arrays(
        {name: y[name].to_numpy() for name in axes},
        time=None if time_name is None else y[time_name].to_numpy(),
        sample_rate=sample_rate,
        source="DataFrame",
    )


def _allan_variance_by_axis(
    y: Any, sample_rate: float | None, taus: Any, options: dict[str, Any]
) -> AllanResultsByAxis:
    """:func:`allan_variance` of each axis of a Recording, a 2-D array or a DataFrame."""
    recording = _axes_recording(y, sample_rate)
    if not recording.uniform:
        raise ValueError(f"{recording.source}: {recording.notes[0]} (uniform sampling is required here)")
    results = {
        name: allan_variance(values, recording.sample_rate, taus, **options)
        for name, values in recording.rates.items()
    }
    return AllanResultsByAxis(results, recording.sample_rate)
