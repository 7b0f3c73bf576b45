"""The closed loop: fit a declared noise model, predict, measure the residual, name the missing effect,
add it, refit, and report the error before and after — until nothing significant remains.

One iteration
    1. **Fit** the declared model on each gyro axis (bias + white + rate random walk by default; a 1/f
       term and an autoregressive short-noise filter once the catalogue adds them): weighted least squares
       on the non-overlapping Allan variance (TIM 2014 eq. (20)) at octave τ, weights from the
       equivalent degrees of freedom of the fitted model
       (:func:`carousel_theory.allan.equivalent_degrees_of_freedom`).
    2. **Predict**, from the exact propagation of the fitted processes (TIM 2014 eqs. (9), (15), (17);
       :mod:`carousel_theory.propagation`): the variance of every directly averaged bin (relative to the
       recording mean) and of every carouselled bin — virtual carouseling of a static two-axis recording
       as in TIM 2014 §V-C with N samples per revolution (default 200), or the measured angles when the
       recording has a ``phi`` column — and the Allan variance at every τ.
    3. **Residual metrics**: the Allan-variance misfit (each τ as a z-value of its χ² distribution), the
       ±2σ exceedance rates of averaged and carouselled bins, the mean squared standardised carouselled bin
       (uncorrelated under the model, TIM 2014 eq. (17)), the tails of the sample-to-sample differences,
       and every catalogue detector's statistic (trends, steps, spectral lines, spectral slope).
       The headline error, ``standardized_misfit``, is the root mean square of the z-values of the
       Allan variance at each τ and axis, of the carouselled-bin variance ratio and of the tail
       (kurtosis) of each axis: about 1 when the model is right, large when it is not.
    4. **Test the catalogue** (:mod:`carousel_theory.effects`): every detector whose family-wise p-value
       is below ``alpha`` is a candidate; the three with the smallest p-values are tried, in that order.
    5. **Add** the candidate, refit, recompute every metric. It is kept only when the headline error
       drops, no noise variance has to grow by more than 2 standard errors to absorb what a deterministic
       effect leaves, and the effect explains its own evidence (its detector, rerun on the new residual, is no
       longer significant; for 1/f noise, the Allan variance then fits; for colored noise, whose real
       filters are not exactly AR(p ≤ 4), a 95 % drop of the evidence's −log p is kept as "most of it").
    6. **Repeat**; stop when no detector is significant (``none`` if nothing was added) or when every
       significant candidate is rejected (``unexplained``). ``unexplained`` is also appended when no
       detector fires but the Allan variance still misfits the model (largest |z| over τ and axes,
       Bonferroni, at ``alpha``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from scipy import optimize, stats
from scipy.interpolate import CubicSpline
from scipy.linalg import solve_toeplitz, solveh_banded

from carousel_theory._validation import check_positive_integer, check_positive_real
from carousel_theory.allan import (
    allan_variance,
    equivalent_degrees_of_freedom,
    flicker_allan_variance,
)
from carousel_theory.data import Recording, recording_from_arrays
from carousel_theory.effects import (
    CATALOGUE,
    DEFAULT_ALPHA,
    TESTED_EFFECTS,
    Detection,
    FittedEffect,
    detect_quantization,
)
from carousel_theory.fitting import NoiseModel
from carousel_theory.propagation import repeated_weights_bin_variances, weighted_sum_variance
from carousel_theory.weights import carousel_weights, carousel_weights_from_angles

__all__ = [
    "HEADLINE_METRIC",
    "AxisNoise",
    "LoopResult",
    "render_summary",
    "run_loop",
    "uniform_resample",
    "write_report",
]

#: Name of the headline error measure reported as ``error_before`` / ``error_after``.
HEADLINE_METRIC = "standardized_misfit"
#: Candidates tried per iteration, from the smallest p-value.
MAXIMUM_TRIALS = 3
#: Long records are reduced to at most this many block means to choose the GLS weights of trend tests.
GLS_BLOCKS = 50_000
#: Fewest clusters an Allan-variance point needs to enter the fit (τ ≤ T/8).
MINIMUM_CLUSTERS = 8
#: Fewest bins the virtual carouseling needs.
MINIMUM_BINS = 10
#: Two-sided 2σ band, as in TIM 2014 §V-C (95.45 % inside for a Gaussian).
BAND_SIGMA = 2.0
BAND_EXPECTED_EXCEEDANCE = float(2.0 * stats.norm.sf(BAND_SIGMA))
#: Autocovariance lags kept for the autoregressive short noise (its correlation dies out long before).
AR_LAGS = 256
#: Averaged-bin variances are computed exactly at this many bins and interpolated between them.
AVERAGED_BIN_GRID = 9


@dataclass(frozen=True)
class AxisNoise:
    """The fitted noise model of one axis in per-sample discrete terms (TIM 2014 §II).

    ``white_variance`` is the innovation variance of the short noise: white when ``ar_coefficients`` is
    empty, otherwise the autoregressive process x_t = Σ a_j x_{t−j} + e_t (the ``colored_noise``
    effect). Its long-run variance σ_e²/(1 − Σ a_j)² is what averaging over many samples sees.
    """

    sample_rate: float
    bias: float
    white_variance: float
    rrw_variance: float = 0.0
    flicker_variance: float = 0.0
    flicker_d: float = 0.5
    ar_coefficients: tuple[float, ...] = ()
    standard_errors: dict[str, float] = field(default_factory=dict)

    @property
    def long_run_variance(self) -> float:
        return self.white_variance / (1.0 - sum(self.ar_coefficients)) ** 2

    def short_autocovariance(self, lags: int = AR_LAGS) -> np.ndarray:
        """γ_h, h = 0 … lags − 1, of the short noise (white: σ² at lag 0 only)."""
        gamma = np.zeros(lags)
        if not self.ar_coefficients:
            gamma[0] = self.white_variance
            return gamma
        # Impulse response of 1/(1 − Σ a_j z^j), long enough for |roots| < 1 to have died out.
        from scipy.signal import lfilter

        length = lags + 4096
        impulse = np.zeros(length)
        impulse[0] = 1.0
        response = lfilter([1.0], np.concatenate(([1.0], -np.asarray(self.ar_coefficients))), impulse)
        spectrum = np.fft.rfft(response, 2 * length)
        autocorrelation = np.fft.irfft(spectrum * np.conj(spectrum), 2 * length)[:lags]
        return self.white_variance * autocorrelation

    def psd(self, frequencies: np.ndarray) -> np.ndarray:
        """Discrete spectral density (per-sample variance units: white σ² is flat at σ²)."""
        omega = 2.0 * np.pi * np.asarray(frequencies) / self.sample_rate
        short = np.full_like(omega, self.white_variance, dtype=np.float64)
        if self.ar_coefficients:
            j = np.arange(1, len(self.ar_coefficients) + 1)
            transfer = 1.0 - np.exp(-1j * np.outer(omega, j)) @ np.asarray(self.ar_coefficients)
            short = self.white_variance / np.abs(transfer) ** 2
        difference = np.maximum(4.0 * np.sin(omega / 2.0) ** 2, 1e-300)  # |1 − e^{−iω}|²
        total = short + self.rrw_variance / difference  # TIM 2014 eq. (2): r = q / (1 − B)
        if self.flicker_variance:
            total = total + self.flicker_variance / difference**self.flicker_d  # eq. (3): (1 − B)^{−d}
        return total

    def noise_model(self, *, short_as_white: bool = True) -> NoiseModel:
        """The :class:`~carousel_theory.fitting.NoiseModel` of the white/RRW/1/f parts (the short noise as
        white of its long-run variance, or left out with ``short_as_white=False``)."""
        return NoiseModel(
            sample_rate=self.sample_rate,
            bias=self.bias,
            white_variance=self.long_run_variance if short_as_white else 0.0,
            rrw_variance=self.rrw_variance,
            flicker_variance=self.flicker_variance,
            flicker_d=self.flicker_d,
        )

    def as_dict(self) -> dict[str, Any]:
        result: dict[str, Any] = {
            "bias_rad_s": self.bias,
            "white_variance_rad2_s2": self.white_variance,
            "long_run_white_variance_rad2_s2": self.long_run_variance,
            "rrw_variance_rad2_s2": self.rrw_variance,
            "flicker_variance_rad2_s2": self.flicker_variance,
            "flicker_d": self.flicker_d if self.flicker_variance else None,
            "ar_coefficients": list(self.ar_coefficients),
            "angle_random_walk_deg_per_sqrt_h": math.degrees(
                math.sqrt(self.long_run_variance / self.sample_rate)
            )
            * 60.0,
            "rate_random_walk_deg_per_h_per_sqrt_h": math.degrees(
                math.sqrt(self.rrw_variance * self.sample_rate)
            )
            * 3600.0
            * 60.0,
            "standard_errors": dict(self.standard_errors),
        }
        return result


# --- the Allan variance of the model and its fit -----------------------------------------------------


def _short_noise_allan(noise: AxisNoise, sizes: np.ndarray) -> np.ndarray:
    """Exact Allan variance of the stationary short noise from its autocovariance:
    σ_A²(m) = Var(x̄_m) − Cov(x̄_m⁽¹⁾, x̄_m⁽²⁾), both finite sums of γ_h (γ_h = 0 beyond AR_LAGS)."""
    if not noise.ar_coefficients:
        return noise.white_variance / sizes.astype(np.float64)
    gamma = noise.short_autocovariance()
    h = np.arange(len(gamma), dtype=np.float64)
    result = np.empty(len(sizes))
    for i, m in enumerate(sizes.astype(np.float64)):
        inside = h < m
        variance = (gamma[0] * m + 2.0 * np.sum((m - h[1:][inside[1:]]) * gamma[1:][inside[1:]])) / m**2
        near = (h >= 1) & (h < 2 * m)
        covariance = np.sum(np.minimum(h[near], 2 * m - h[near]) * gamma[near]) / m**2
        result[i] = variance - covariance
    return result


@dataclass
class _AxisFit:
    noise: AxisNoise
    allan_tau: np.ndarray
    allan_sizes: np.ndarray
    allan_observed: np.ndarray
    allan_model: np.ndarray
    allan_edf: np.ndarray
    chi_square: float
    dof: int


class _FlickerBasis:
    """The unit 1/f Allan-variance curve, cached per record length (it costs one pass per τ)."""

    def __init__(self) -> None:
        self._cache: dict[tuple[int, tuple[int, ...]], np.ndarray] = {}

    def __call__(self, sizes: np.ndarray, length: int) -> np.ndarray:
        key = (length, tuple(int(m) for m in sizes))
        if key not in self._cache:
            self._cache[key] = flicker_allan_variance(0.5, sizes, length, "non-overlapping")
        return self._cache[key]


def _yule_walker(x: np.ndarray, sample_rate: float, maximum_order: int) -> tuple[float, ...]:
    """AR coefficients by Yule–Walker on the residual with its slow part (rate random walk, 1/f, trends)
    removed by a centred 10-s moving average (a shorter one biases the lag covariances by about
    −(long-run variance)/window); the order is the largest p ≤ maximum_order whose partial
    autocorrelation exceeds 4/√n (Levinson–Durbin)."""
    from scipy.ndimage import uniform_filter1d

    window = max(1001, round(10 * sample_rate) | 1)
    fast = x - uniform_filter1d(x, window, mode="nearest")
    n = len(fast)
    spectrum = np.fft.rfft(fast, 2 * n)
    autocovariance = np.fft.irfft(spectrum * np.conj(spectrum), 2 * n)[: maximum_order + 1] / n
    order = 0
    for p in range(1, maximum_order + 1):
        coefficients = solve_toeplitz(autocovariance[:p], autocovariance[1 : p + 1])
        if abs(coefficients[-1]) > 4.0 / math.sqrt(n):  # the last coefficient is the partial autocorrelation
            order = p
    if order == 0:
        return ()
    coefficients = solve_toeplitz(autocovariance[:order], autocovariance[1 : order + 1])
    return tuple(float(c) for c in coefficients)


def _fit_axis(
    x: np.ndarray,
    sample_rate: float,
    *,
    ar_order: int,
    flicker: bool,
    flicker_basis: _FlickerBasis,
    allan_cache: dict[int, Any],
    edf_hint: np.ndarray | None = None,
) -> _AxisFit:
    """Fit bias + short noise + rate random walk (+ 1/f) to one axis.

    Gap being filled: :mod:`carousel_theory.fitting` provides the NoiseModel but no fit that knows the
    autoregressive short noise of ``colored_noise`` or returns the χ² of nested fits the ``flicker``
    detector compares; this private weighted least squares on the Allan variance does both. Weights:
    Var(σ̂_A²) = 2 σ_A⁴/ν with ν the equivalent degrees of freedom of the current fit (iterated).
    """
    n = len(x)
    ar = _yule_walker(x, sample_rate, ar_order) if ar_order else ()
    key = id(x)
    if key not in allan_cache:
        allan_cache[key] = allan_variance(
            x, sample_rate, "octave", estimator="non-overlapping", noise="white"
        )
    allan = allan_cache[key]
    # τ with at least MINIMUM_CLUSTERS clusters: beyond, an estimate rests on 2-6 squared differences and
    # a single one decides whether the fit "needs" a 1/f or a random-walk term.
    keep = allan.samples_per_cluster * MINIMUM_CLUSTERS <= n
    sizes = allan.samples_per_cluster[keep].astype(np.int64)
    observed = allan.avar[keep]
    tau = allan.tau[keep]
    # Columns: short noise of unit long-run variance, rate random walk, (1/f).
    unit_short = AxisNoise(sample_rate, 0.0, (1.0 - sum(ar)) ** 2, ar_coefficients=ar)
    columns = [_short_noise_allan(unit_short, sizes), (2.0 * sizes**2 + 1.0) / (6.0 * sizes)]
    names = ["short", "rrw"]
    if flicker:
        columns.append(flicker_basis(sizes, n))
        names.append("flicker")
    design = np.column_stack(columns)
    edf = allan.edf[keep].astype(np.float64) if edf_hint is None else edf_hint
    weights_base = observed
    theta = np.zeros(len(names))
    for iteration in range(3 if edf_hint is None else 2):
        sigma = np.maximum(weights_base, 1e-300) * np.sqrt(2.0 / edf)
        theta, _residual = optimize.nnls(design / sigma[:, None], observed / sigma)
        fitted_curve = design @ theta
        weights_base = np.maximum(fitted_curve, 1e-300)
        trial = AxisNoise(
            sample_rate, 0.0, theta[0] * (1.0 - sum(ar)) ** 2, float(theta[1]), ar_coefficients=ar
        )
        model = trial.noise_model()
        terms = n // sizes - 1  # non-overlapping, TIM 2014 eq. (20): M − 1 differences at stride m
        edf = (
            np.array(
                [
                    equivalent_degrees_of_freedom(model, int(m), int(k), int(m), n, sample_rate)
                    for m, k in zip(sizes, terms, strict=True)
                ]
            )
            if (model.white_variance + model.rrw_variance > 0 and edf_hint is None and iteration < 2)
            else edf
        )
    fitted_curve = design @ theta
    sigma = np.maximum(fitted_curve, 1e-300) * np.sqrt(2.0 / edf)
    chi_square = float(np.sum(((observed - fitted_curve) / sigma) ** 2))
    # Standard errors from the weighted normal equations (parameters at a bound get none).
    standard_errors: dict[str, float] = {}
    try:
        covariance = np.linalg.inv((design / sigma[:, None]).T @ (design / sigma[:, None]))
        for i, name in enumerate(names):
            standard_errors[name] = float(math.sqrt(max(covariance[i, i], 0.0)))
    except np.linalg.LinAlgError:
        pass
    noise = AxisNoise(
        sample_rate=sample_rate,
        bias=float(x.mean()),
        white_variance=float(theta[0]) * (1.0 - sum(ar)) ** 2,
        rrw_variance=float(theta[1]),
        flicker_variance=float(theta[2]) if flicker else 0.0,
        ar_coefficients=ar,
        standard_errors={
            "long_run_white_variance": standard_errors.get("short", float("nan")),
            "rrw_variance": standard_errors.get("rrw", float("nan")),
            **({"flicker_variance": standard_errors.get("flicker", float("nan"))} if flicker else {}),
        },
    )
    return _AxisFit(noise, tau, sizes, observed, fitted_curve, edf, chi_square, len(sizes) - len(names))


# --- the state of the loop and its evaluation ------------------------------------------------------------


@dataclass(frozen=True)
class _ModelSpec:
    ar_order: int = 0
    flicker: bool = False
    fitted: tuple[FittedEffect, ...] = ()


def _local_median_replacement(x: np.ndarray, mask: np.ndarray, half_width: int = 7) -> np.ndarray:
    """x with the masked samples replaced by the median of the unmasked samples within ±half_width."""
    if not mask.any():
        return x
    result = x.copy()
    padded = np.pad(np.where(mask, np.nan, x), half_width, mode="edge")
    windows = np.lib.stride_tricks.sliding_window_view(padded, 2 * half_width + 1)
    where = np.flatnonzero(mask)
    selected = windows[where]
    # Inside a long flagged run (a bump) a window holds no unmasked sample: interpolate linearly there.
    empty = np.all(np.isnan(selected), axis=1)
    local = np.empty(len(where))
    if (~empty).any():
        local[~empty] = np.nanmedian(selected[~empty], axis=1)
    kept = np.flatnonzero(~mask)
    if empty.any():
        local[empty] = np.interp(where[empty], kept, x[kept]) if len(kept) else 0.0
    result[where] = local
    return result


class _View:
    """The residual of every axis under one model specification, with the fitted noise models: what the
    detectors of :mod:`carousel_theory.effects` see (the ``ResidualView`` protocol)."""

    def __init__(
        self, recording: Recording, axes: tuple[str, ...], spec: _ModelSpec, flicker_basis: _FlickerBasis
    ) -> None:
        self.axes = axes
        self.time = recording.time
        self.sample_rate = recording.sample_rate
        self.temperature = recording.temperature
        self.spec = spec
        self._flicker_basis = flicker_basis
        self._allan_cache: dict[int, Any] = {}
        self._cache: dict[Any, Any] = {}
        self.cleaned: dict[str, np.ndarray] = {}
        for axis in axes:
            x = recording.rates[axis]
            mask = np.zeros(len(x), dtype=bool)
            for fitted in spec.fitted:
                if axis in fitted.replaced:
                    mask |= fitted.replaced[axis]
            for fitted in spec.fitted:
                if axis in fitted.signals:
                    x = x - fitted.signals[axis]
            self.cleaned[axis] = _local_median_replacement(x, mask)
        self.fits = {
            axis: _fit_axis(
                self.cleaned[axis],
                self.sample_rate,
                ar_order=spec.ar_order,
                flicker=spec.flicker,
                flicker_basis=flicker_basis,
                allan_cache=self._allan_cache,
            )
            for axis in axes
        }
        self.noise = {axis: self.fits[axis].noise for axis in axes}
        self.residuals = {axis: self.cleaned[axis] - self.noise[axis].bias for axis in axes}

    # ResidualView protocol
    def statistic_variance(
        self, axis: str, weights: np.ndarray, noise: AxisNoise | None = None, include_flicker: bool = True
    ) -> float:
        noise = self.noise[axis] if noise is None else noise
        # Short noise: its long-run variance times Σw² (exact for white; for the autoregressive noise exact
        # up to O(correlation length / scale of w), the weights used here varying slowly).
        total = noise.long_run_variance * float(np.dot(weights, weights))
        if noise.rrw_variance:
            total += noise.rrw_variance * weighted_sum_variance(weights, "rrw")
        if noise.flicker_variance and include_flicker:
            total += noise.flicker_variance * weighted_sum_variance(weights, "flicker", d=noise.flicker_d)
        return total

    @property
    def gls_block(self) -> int:
        """Samples per block of the GLS trend statistics: records longer than GLS_BLOCKS samples are
        reduced to block means for the *choice* of the weights (their variance stays exact, per sample)."""
        return max(1, math.ceil(len(self.time) / GLS_BLOCKS))

    def _block_means(self, values: np.ndarray) -> np.ndarray:
        block = self.gls_block
        count = len(values) // block
        return values[: count * block].reshape(count, block).mean(axis=1)

    def _expand(self, block_weights: np.ndarray) -> np.ndarray:
        block = self.gls_block
        expanded = np.repeat(block_weights / block, block)
        return np.concatenate((expanded, np.zeros(len(self.time) - len(expanded))))

    def _difference_covariance_bands(self, noise: AxisNoise) -> np.ndarray:
        # Differences Δx_t = q_t + w_t − w_{t−1} of white + rate random walk: MA(1) with γ₀ = σ_q² + 2σ²,
        # γ₁ = −σ²; a floor on σ_q² keeps the tridiagonal system well conditioned when no walk is fitted.
        # On block means of b samples: white σ²/b, walk increments ≈ σ_q² b.
        block = self.gls_block
        white = noise.long_run_variance / block
        walk = max(noise.rrw_variance * block, 1e-8 * white)
        size = len(self.time) // block - 1
        bands = np.empty((2, size))
        bands[0, :] = -white
        bands[0, 0] = 0.0
        bands[1, :] = walk + 2.0 * white
        return bands

    def gls_weights(self, axis: str, regressor: np.ndarray, noise: AxisNoise | None = None) -> np.ndarray:
        """Sample weights w of the generalised-least-squares projection on ``regressor`` under white noise +
        rate random walk: w = Dᵀ Σ_Δ⁻¹ D g, D the first difference (which also removes the bias), Σ_Δ the
        tridiagonal covariance of the differences (on block means for long records). Σ w_t y_t is the GLS
        statistic; its exact variance under the full model (1/f included) is :meth:`statistic_variance`."""
        noise = self.noise[axis] if noise is None else noise
        solved = solveh_banded(
            self._difference_covariance_bands(noise),
            np.diff(self._block_means(regressor)),
            check_finite=False,
        )
        return self._expand(np.concatenate(([0.0], solved)) - np.concatenate((solved, [0.0])))

    def gls_difference_solve(self, axis: str, vector: np.ndarray) -> np.ndarray:
        """Σ_Δ⁻¹ v for the tridiagonal covariance of the (block) differences under the fitted model."""
        return solveh_banded(self._difference_covariance_bands(self.noise[axis]), vector, check_finite=False)

    def gls_step_scan(self, axis: str) -> tuple[np.ndarray, np.ndarray, float]:
        """(u, sample weights of a step in the middle, its information (Σ_Δ⁻¹)_mm).

        u_j = (Σ_Δ⁻¹ Δx)_j is the GLS statistic of a bias step after block j (sample (j + 1)·gls_block),
        for every j at once."""
        key = ("scan", axis)
        if key not in self._cache:
            bands = self._difference_covariance_bands(self.noise[axis])
            u = solveh_banded(bands, np.diff(self._block_means(self.residuals[axis])), check_finite=False)
            impulse = np.zeros(len(u))
            impulse[len(u) // 2] = 1.0
            solved = solveh_banded(bands, impulse, check_finite=False)
            weights = self._expand(np.concatenate(([0.0], solved)) - np.concatenate((solved, [0.0])))
            self._cache[key] = (u, weights, float(solved[len(u) // 2]))
        return self._cache[key]

    def statistic_variance_dof(
        self, axis: str, weights: np.ndarray, noise: AxisNoise | None = None
    ) -> tuple[float, float]:
        """(variance, effective degrees of freedom): the variance of Σ w_t e_t as :meth:`statistic_variance`,
        and ν = 2 V² / Var(V̂) from the standard errors of the fitted variances (Satterthwaite), so that a
        z built on it is referred to Student's t with ν degrees of freedom: a rate random walk estimated from
        a few long-τ Allan points is uncertain, and a normal reference would then be anticonservative."""
        noise = self.noise[axis] if noise is None else noise
        parts = {"long_run_white_variance": (noise.long_run_variance, float(np.dot(weights, weights)))}
        # The walk's share counts even at a fitted σ_q² of 0: its standard error still says how large it
        # could be.
        parts["rrw_variance"] = (noise.rrw_variance, weighted_sum_variance(weights, "rrw"))
        if noise.flicker_variance or math.isfinite(
            noise.standard_errors.get("flicker_variance", float("nan"))
        ):
            parts["flicker_variance"] = (
                noise.flicker_variance,
                weighted_sum_variance(weights, "flicker", d=noise.flicker_d),
            )
        variance = sum(value * unit for value, unit in parts.values())
        spread = 0.0
        for name, (value, unit) in parts.items():
            error = noise.standard_errors.get(name, float("nan"))
            spread += (unit * (error if math.isfinite(error) else value)) ** 2
        dof = 2.0 * variance**2 / spread if spread > 0 else math.inf
        return variance, max(dof, 1.0)

    def bounded_noise(self, axis: str, noise: AxisNoise) -> AxisNoise:
        """``noise`` with each variance raised to at least the current fit's value minus 2 standard errors."""
        current = self.noise[axis]
        errors = current.standard_errors

        def floor(name: str, value: float, reference: float) -> float:
            error = errors.get(name, float("nan"))
            limit = reference - 2.0 * error if math.isfinite(error) else reference
            return max(value, limit, 0.0)

        return replace(
            noise,
            rrw_variance=floor("rrw_variance", noise.rrw_variance, current.rrw_variance),
            flicker_variance=floor("flicker_variance", noise.flicker_variance, current.flicker_variance)
            if noise.flicker_variance or current.flicker_variance
            else 0.0,
            standard_errors=dict(current.standard_errors)
            if noise.rrw_variance < current.rrw_variance
            else noise.standard_errors,
        )

    def refit(self, axis: str, signal: np.ndarray) -> AxisNoise:
        """The noise model of the axis refitted on its residual minus ``signal`` (same model family)."""
        fit = _fit_axis(
            self.cleaned[axis] - signal,
            self.sample_rate,
            ar_order=self.spec.ar_order,
            flicker=self.spec.flicker,
            flicker_basis=self._flicker_basis,
            allan_cache={},
            edf_hint=self.fits[axis].allan_edf,
        )
        return fit.noise

    def noise_psd(self, axis: str, frequencies: np.ndarray) -> np.ndarray:
        return self.noise[axis].psd(frequencies)

    def noise_parameters(self, axis: str) -> dict[str, float]:
        noise = self.noise[axis]
        return {
            "long_run_variance": noise.long_run_variance,
            "rrw_variance": noise.rrw_variance,
            "flicker_variance": noise.flicker_variance,
        }

    def allan_chi_square(self, axis: str, extra: tuple[str, ...] = ()) -> tuple[float, int]:
        if not extra or ("flicker" in extra and self.spec.flicker):
            fit = self.fits[axis]
            return fit.chi_square, fit.dof
        fit = _fit_axis(
            self.cleaned[axis],
            self.sample_rate,
            ar_order=self.spec.ar_order,
            flicker="flicker" in extra or self.spec.flicker,
            flicker_basis=self._flicker_basis,
            allan_cache=self._allan_cache,
            edf_hint=self.fits[axis].allan_edf,
        )
        return fit.chi_square, fit.dof

    def fitted_ar_coefficients(self, axis: str) -> tuple[float, ...]:
        return self.noise[axis].ar_coefficients


# --- predictions and metrics ------------------------------------------------------------------------------


def _z_from_chi_square(observed: np.ndarray, expected: np.ndarray, edf: np.ndarray) -> np.ndarray:
    """z-value of each Allan-variance estimate: ν σ̂²/σ² ~ χ²_ν under the model, mapped through its cdf."""
    statistic = edf * observed / np.maximum(expected, 1e-300)
    lower = stats.chi2.logcdf(statistic, edf)
    upper = stats.chi2.logsf(statistic, edf)
    z = np.where(lower < upper, stats.norm.ppf(np.exp(lower)), -stats.norm.ppf(np.exp(upper)))
    # exp(log p) underflows past z ≈ 38; beyond that the exact size no longer matters.
    z = np.where(np.isfinite(z), z, np.where(lower < upper, -38.0, 38.0))
    return np.clip(z, -38.0, 38.0)


def _carousel_bins(view: _View, N: int, angle: np.ndarray | None) -> dict[str, Any] | None:
    """Virtual carouseling (TIM 2014 eq. (6)) of the two axes, with predicted variances per bin."""
    if len(view.axes) < 2:
        return None
    x_axis, y_axis = view.axes[0], view.axes[1]
    x, y = view.residuals[x_axis], view.residuals[y_axis]
    noise_x, noise_y = view.noise[x_axis], view.noise[y_axis]
    if angle is None:
        count = len(x) // N
        s, c = carousel_weights(N)  # TIM 2014 eq. (13)
        values = -x[: count * N].reshape(count, N) @ s + y[: count * N].reshape(count, N) @ c  # eq. (6)
        variance = np.zeros(count)
        for noise, weights in ((noise_x, s), (noise_y, c)):
            gamma = noise.short_autocovariance(min(AR_LAGS, N))
            lagged = np.array([np.dot(weights[: N - h], weights[h:]) for h in range(len(gamma))])
            variance += gamma[0] * lagged[0] + 2.0 * np.dot(gamma[1:], lagged[1:])  # wᵀΓw, eq. (9) for white
            if noise.rrw_variance:  # eq. (17)-(18), exact for every bin
                variance += noise.rrw_variance * repeated_weights_bin_variances(weights, "rrw", count)
            if noise.flicker_variance:
                variance += noise.flicker_variance * repeated_weights_bin_variances(
                    weights, "flicker", count, d=noise.flicker_d
                )
        centres = (np.arange(count) + 0.5) * N / view.sample_rate
        return {"values": values, "variance": variance, "time": centres, "mode": f"virtual, N = {N}"}
    # Measured angles: one bin per complete revolution.
    turns = np.floor((np.unwrap(angle) - angle[0]) / (2.0 * np.pi)).astype(np.int64)
    turns = turns if turns[-1] >= 0 else -turns
    edges = np.flatnonzero(np.diff(turns)) + 1
    starts = np.concatenate(([0], edges))[:-1]
    stops = edges
    if len(starts) == 0:
        return {
            "values": np.array([]),
            "variance": np.array([]),
            "time": np.array([]),
            "mode": "measured angles (no complete revolution)",
        }
    bin_values: list[float] = []
    bin_variances: list[float] = []
    bin_centres: list[float] = []
    for start, stop in zip(starts, stops, strict=True):
        s, c = carousel_weights_from_angles(angle[start:stop])
        bin_values.append(-float(np.dot(s, x[start:stop])) + float(np.dot(c, y[start:stop])))
        total = 0.0
        for noise, weights in ((noise_x, s), (noise_y, c)):
            total += noise.long_run_variance * float(np.dot(weights, weights))
            # r at the bin start enters every sample of the bin: t₀ (Σw)² plus the walk within the bin.
            total += noise.rrw_variance * (
                start * float(weights.sum()) ** 2 + weighted_sum_variance(weights, "rrw")
            )
            if noise.flicker_variance:
                padded = np.concatenate((np.zeros(start), weights))
                total += noise.flicker_variance * weighted_sum_variance(padded, "flicker", d=noise.flicker_d)
        bin_variances.append(total)
        bin_centres.append(0.5 * float(view.time[start] + view.time[stop - 1]))
    return {
        "values": np.array(bin_values),
        "variance": np.array(bin_variances),
        "time": np.array(bin_centres),
        "mode": "measured angles, one bin per revolution",
    }


def _averaged_bins(view: _View, axis: str, N: int) -> dict[str, Any]:
    """Bin means of N samples minus the mean of the whole bins, with their exact predicted variances
    (TIM 2014 eq. (15) generalised: weights 1/N on the bin minus 1/(KN) everywhere), computed exactly at
    AVERAGED_BIN_GRID bins and joined by a cubic in k (exact for white noise and the rate random walk,
    whose contributions are polynomials of degree ≤ 2 in k; smooth for 1/f noise)."""
    x = view.residuals[axis]
    count = len(x) // N
    total = count * N
    bins = x[:total].reshape(count, N).mean(axis=1)
    values = bins - bins.mean()
    grid = np.unique(np.linspace(1, count, min(count, AVERAGED_BIN_GRID)).astype(int))
    grid_variance = np.empty(len(grid))
    for i, k in enumerate(grid):
        weights = np.full(total, -1.0 / total)
        weights[(k - 1) * N : k * N] += 1.0 / N
        grid_variance[i] = view.statistic_variance(axis, weights)
    # A cubic through the grid is exact for the white and random-walk parts (at most quadratic in k).
    if len(grid) >= 4:
        variance = CubicSpline(grid, grid_variance)(np.arange(1, count + 1))
    else:
        variance = np.interp(np.arange(1, count + 1), grid, grid_variance)
    variance = np.maximum(variance, grid_variance.min() * 0.5)
    centres = (np.arange(count) + 0.5) * N / view.sample_rate
    return {"values": values, "variance": variance, "time": centres}


def _tail_z(x: np.ndarray) -> tuple[float, float]:
    """(excess kurtosis, z) of the sample-to-sample differences: 0 ± √(24/n) for Gaussian noise; the
    difference removes the bias and the slow processes, spikes make it large."""
    differences = np.diff(x)
    kurtosis = float(stats.kurtosis(differences, fisher=True, bias=True))
    return kurtosis, kurtosis / math.sqrt(24.0 / len(differences))


@dataclass
class _Evaluation:
    view: _View
    metrics: dict[str, Any]
    headline: float
    averaged: dict[str, dict[str, Any]]
    carouselled: dict[str, Any] | None
    detections: dict[str, Detection]


def _z_from_log10_p(log10_p: float) -> float:
    """The two-sided normal z of a (family-wise) p-value given as log10 p, clipped at 38."""
    if log10_p >= 0:
        return 0.0
    log_half = log10_p * math.log(10.0) - math.log(2.0)
    return float(min(38.0, -stats.norm.ppf(math.exp(log_half)) if log_half > -700 else 38.0))


def _evaluate(view: _View, N: int, angle: np.ndarray | None, alpha: float) -> _Evaluation:
    z_values: list[float] = []
    allan_metrics = {}
    for axis in view.axes:
        fit = view.fits[axis]
        z = _z_from_chi_square(fit.allan_observed, fit.allan_model, fit.allan_edf)
        z_values.extend(z.tolist())
        allan_metrics[axis] = {
            "rms_z": float(np.sqrt(np.mean(z**2))),
            "max_abs_z": float(np.max(np.abs(z))),
            "fraction_outside_95": float(np.mean(np.abs(z) > 1.96)),
            "chi_square": fit.chi_square,
            "dof": fit.dof,
        }
    averaged = {axis: _averaged_bins(view, axis, N) for axis in view.axes}
    averaged_metrics = {}
    for axis, bins in averaged.items():
        standardized = bins["values"] / np.sqrt(bins["variance"])
        averaged_metrics[axis] = {
            "bins": len(standardized),
            "exceedance_2sigma": float(np.mean(np.abs(standardized) > BAND_SIGMA)),
            "mean_square_z": float(np.mean(standardized**2)),
        }
    carouselled = _carousel_bins(view, N, angle)
    carousel_metrics: dict[str, Any] | None = None
    if carouselled is not None and len(carouselled["values"]):
        standardized = carouselled["values"] / np.sqrt(carouselled["variance"])
        count = len(standardized)
        mean_square = float(np.mean(standardized**2))
        # Carouselled bins are uncorrelated under the model (TIM 2014 eq. (17)): mean z² is 1 ± √(2/K).
        ratio_z = (mean_square - 1.0) / math.sqrt(2.0 / count)
        z_values.append(float(np.clip(ratio_z, -38.0, 38.0)) if count >= MINIMUM_BINS else 0.0)
        carousel_metrics = {
            "bins": count,
            "mode": carouselled["mode"],
            "exceedance_2sigma": float(np.mean(np.abs(standardized) > BAND_SIGMA)),
            "mean_square_z": mean_square,
            "mean_square_z_score": ratio_z,
        }
    tails = {}
    for axis in view.axes:
        kurtosis, tail_z = _tail_z(view.residuals[axis])
        # Only heavy tails count against the model (light tails come from coarse quantization).
        z_values.append(min(max(tail_z, 0.0), 38.0))
        tails[axis] = {"excess_kurtosis_of_differences": kurtosis, "z": tail_z}
    # Trends, steps, spectral lines and spectral slope: every detector of an effect the model lacks
    # (1/f noise, once in the model, is judged by the Allan-variance z-values above).
    detections = {
        name: CATALOGUE[name].detect(view, alpha)
        for name in TESTED_EFFECTS
        if not (name == "flicker" and view.spec.flicker)
    }
    residual_tests = {}
    for name, detection in detections.items():
        if detection.testable:
            test_z = _z_from_log10_p(detection.log10_p)
            z_values.append(test_z)
            residual_tests[name] = {
                "statistic": detection.statistic,
                "log10_p": detection.log10_p,
                "z": test_z,
            }
    headline = float(np.sqrt(np.mean(np.square(z_values))))
    metrics = {
        "residual_tests": residual_tests,
        HEADLINE_METRIC: headline,
        "allan": allan_metrics,
        "averaged_bins": averaged_metrics,
        "carouselled_bins": carousel_metrics,
        "tails": tails,
        "expected_exceedance_2sigma": BAND_EXPECTED_EXCEEDANCE,
    }
    return _Evaluation(view, metrics, headline, averaged, carouselled, detections)


# --- the loop -----------------------------------------------------------------------------------------------


@dataclass
class LoopResult:
    """What the loop found; :meth:`as_dict` is the JSON of ``carousel-theory loop --json``."""

    effects: list[str]
    metric: str
    error_before: float
    error_after: float
    model_before: dict[str, Any]
    model_after: dict[str, Any]
    metrics_before: dict[str, Any]
    metrics_after: dict[str, Any]
    steps: list[dict[str, Any]]
    fitted_effects: list[dict[str, Any]]
    observations: list[str]
    samples_per_revolution: int
    source: str
    axes: list[str]
    evaluation_before: Any = field(default=None, repr=False)
    evaluation_after: Any = field(default=None, repr=False)

    def as_dict(self) -> dict[str, Any]:
        return _clean_json(
            {
                "source": self.source,
                "axes": self.axes,
                "samples_per_revolution": self.samples_per_revolution,
                "effects": self.effects,
                "metric": self.metric,
                "error_before": self.error_before,
                "error_after": self.error_after,
                "model_before": self.model_before,
                "model_after": self.model_after,
                "metrics_before": self.metrics_before,
                "metrics_after": self.metrics_after,
                "fitted_effects": self.fitted_effects,
                "steps": self.steps,
                "observations": self.observations,
            }
        )


def _clean_json(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): _clean_json(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean_json(v) for v in value]
    if isinstance(value, (np.floating, float)):
        number = float(value)
        return number if math.isfinite(number) else str(number)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.ndarray):
        return _clean_json(value.tolist())
    return value


def _noise_growth(before: _View, after: _View, z: float = 2.0) -> list[str]:
    """Noise variances that grew by more than ``z`` standard errors when a deterministic effect was
    removed. Removing a real effect can only leave less to explain; an effect that does not describe the
    data (a few steps fitted to a sawtooth) leaves structure that the rate random walk then absorbs."""
    grown = []
    for axis in before.axes:
        old, new = before.noise[axis], after.noise[axis]
        errors = old.standard_errors
        pairs = (
            ("long_run_white_variance", old.long_run_variance, new.long_run_variance),
            ("rrw_variance", old.rrw_variance, new.rrw_variance),
            ("flicker_variance", old.flicker_variance, new.flicker_variance),
        )
        for name, value_before, value_after in pairs:
            error = errors.get(name, float("nan"))
            if not math.isfinite(error) or error <= 0:
                error = 0.1 * value_before
            if value_after > value_before + z * error and value_after > 1.2 * value_before:
                grown.append(f"{axis} {name} {value_before:.3g} -> {value_after:.3g}")
    return grown


def uniform_resample(recording: Recording, sample_rate: float | None = None) -> tuple[Recording, str]:
    """Bin-average an irregularly sampled recording onto a uniform grid (empty bins linearly
    interpolated). Default rate: the highest of f̄/2^k (f̄ the mean rate) at which at most 1 % of the bins
    are empty. Returns the new recording and a sentence saying what was done."""
    time = recording.time
    mean_rate = (len(time) - 1) / float(time[-1] - time[0])
    if sample_rate is None:
        sample_rate = mean_rate
        for _ in range(12):
            edges = np.arange(time[0], time[-1] + 1.0 / sample_rate, 1.0 / sample_rate)
            counts = np.histogram(time, edges)[0]
            if np.mean(counts == 0) <= 0.01:
                break
            sample_rate /= 2.0
    sample_rate = float(check_positive_real("sample_rate", sample_rate))
    edges = np.arange(time[0], time[-1] + 1.0 / sample_rate, 1.0 / sample_rate)
    index = np.clip(np.searchsorted(edges, time, side="right") - 1, 0, len(edges) - 2)
    count = np.bincount(index, minlength=len(edges) - 1).astype(np.float64)
    centres = edges[:-1] + 0.5 / sample_rate
    filled = count > 0

    def average(values: np.ndarray) -> np.ndarray:
        sums = np.bincount(index, weights=values, minlength=len(edges) - 1)
        means = np.divide(sums, count, out=np.zeros_like(sums), where=filled)
        return np.interp(centres, centres[filled], means[filled])

    rates = {name: average(values) for name, values in recording.rates.items()}
    temperature = None if recording.temperature is None else average(recording.temperature)
    angle = None if recording.angle is None else average(np.unwrap(recording.angle))
    note = (
        f"irregular timestamps (mean rate {mean_rate:.4g} Hz): bin-averaged onto a uniform "
        f"{sample_rate:.4g} Hz grid, {int((~filled).sum())} of {len(filled)} bins empty and interpolated"
    )
    resampled = recording_from_arrays(
        rates, sample_rate=sample_rate, temperature=temperature, angle=angle, source=recording.source
    )
    return resampled, note


def run_loop(
    recording: Recording,
    *,
    samples_per_revolution: int = 200,
    axes: Sequence[str] | None = None,
    alpha: float = DEFAULT_ALPHA,
    maximum_iterations: int = 8,
    declared: Sequence[str] = ("white", "rrw"),
) -> LoopResult:
    """Run the closed loop on a static recording (see the module docstring).

    Parameters
    ----------
    recording
        A :class:`~carousel_theory.data.Recording`; irregular timestamps are bin-averaged onto a uniform
        grid first (said in ``observations``).
    samples_per_revolution
        N of the virtual carouseling (TIM 2014 §V-C uses 200); ignored for the carouselled bins when the
        recording has a ``phi`` column (one bin per measured revolution), still used for averaged bins.
    axes
        The gyro axes; default: ``wx`` and ``wy`` when present, else every axis (one axis: averaging only).
    alpha
        Family-wise false-alarm rate of each detector in each iteration.
    maximum_iterations
        Upper bound on the number of effects added.
    declared
        The declared model: "white" and "rrw" always, "flicker" optionally.
    """
    if not isinstance(recording, Recording):
        raise TypeError(f"recording={recording!r}: must be a carousel_theory.data.Recording")
    N = check_positive_integer("samples_per_revolution", samples_per_revolution, minimum=3)
    alpha = float(check_positive_real("alpha", alpha))
    if not alpha < 0.5:
        raise ValueError(f"alpha={alpha!r}: must be < 0.5")
    maximum_iterations = check_positive_integer("maximum_iterations", maximum_iterations)
    declared = tuple(declared)
    unknown = sorted(set(declared) - {"white", "rrw", "flicker"})
    if unknown or not {"white", "rrw"} <= set(declared):
        raise ValueError(f"declared={declared!r}: must hold 'white' and 'rrw', optionally 'flicker'")
    observations: list[str] = list(recording.notes)
    # The lattice test needs the samples as recorded (averaging onto a uniform grid would hide it).
    for axis in (a for a in (axes or ("wx", "wy")) if a in recording.rates):
        lattice = detect_quantization(recording.rates[axis])
        if lattice["quantized"]:
            observations.append(
                f"quantization on {axis}: step {lattice['step']:.4g} rad/s, {lattice['levels']} levels "
                f"(noise q²/12 = {lattice['step'] ** 2 / 12:.3g} (rad/s)² is inside the white term)"
            )
    if not recording.uniform:
        recording, note = uniform_resample(recording)
        observations.append(note)
    if axes is None:
        names = tuple(recording.rates)
        axes = ("wx", "wy") if {"wx", "wy"} <= set(names) else names
    axes = tuple(axes)
    missing = [a for a in axes if a not in recording.rates]
    if not axes or missing:
        raise ValueError(f"axes={axes!r}: not in the recording, which has {sorted(recording.rates)}")
    if len(axes) > 2:
        raise ValueError(f"axes={axes!r}: give one axis (averaging) or two (averaging and carouseling)")
    needed = MINIMUM_BINS * N
    if len(recording) < needed:
        raise ValueError(
            f"{recording.source}: {len(recording)} samples are too short for samples_per_revolution={N} "
            f"(needs at least {MINIMUM_BINS} bins, {needed} samples)"
        )
    if len(axes) == 1:
        observations.append(
            f"one gyro axis ({axes[0]}): averaging analysis only; carouseling needs two perpendicular axes"
        )
    angle = recording.angle
    if angle is not None and len(axes) == 2:
        observations.append(
            "phi column present: carouselled bins use the measured angles, one bin per revolution"
        )
    if recording.temperature is None:
        observations.append("no temperature column: the temperature effect cannot be tested")
    elif float(np.ptp(recording.temperature)) == 0.0:
        observations.append("the temperature column is constant: no temperature effect can be tested")

    flicker_basis = _FlickerBasis()
    spec = _ModelSpec(flicker="flicker" in declared)
    current = _evaluate(_View(recording, axes, spec, flicker_basis), N, angle, alpha)
    before = current
    effects: list[str] = []
    steps: list[dict[str, Any]] = []
    unexplained = False
    tried_and_kept: set[str] = set()
    for iteration in range(1, maximum_iterations + 1):
        candidates = [name for name in current.detections if name not in tried_and_kept]
        if current.view.spec.ar_order:
            candidates = [name for name in candidates if name != "colored_noise"]
        detections: list[Detection] = [current.detections[name] for name in candidates]
        significant = sorted(
            (d for d in detections if d.significant), key=lambda d: (d.log10_p, -d.statistic)
        )
        record: dict[str, Any] = {
            "iteration": iteration,
            "error": current.headline,
            "detections": [d.as_dict() for d in detections],
            "tried": [],
        }
        steps.append(record)
        if not significant:
            record["decision"] = "nothing significant remains"
            break
        kept = None
        # The three best-supported candidates are tried; weaker evidence is rarely the cause of stronger.
        for detection in significant[:MAXIMUM_TRIALS]:
            effect = CATALOGUE[detection.effect]
            fitted = effect.fit(current.view, detection, alpha)
            new_spec = replace(
                current.view.spec,
                fitted=(*current.view.spec.fitted, fitted),
                ar_order=max(current.view.spec.ar_order, int(fitted.noise_change.get("ar_order", 0))),
                flicker=current.view.spec.flicker or bool(fitted.noise_change.get("flicker", False)),
            )
            candidate = _evaluate(_View(recording, axes, new_spec, flicker_basis), N, angle, alpha)
            verification = candidate.detections.get(detection.effect) or effect.verify(candidate.view, alpha)
            improved = candidate.headline < current.headline
            explained = not verification.significant
            # A real sensor's filter is not exactly AR(p ≤ 4): on long records the slope test stays
            # significant after a fit that removes nearly all of it. Only for colored_noise, a reduction of
            # the evidence's −log p by ≥ 95 % counts (and "unexplained" is still appended at the end).
            partial = (
                detection.effect == "colored_noise"
                and verification.log10_p > 0.05 * detection.log10_p
                and detection.log10_p < 0
            )
            grown = [] if effect.stochastic else _noise_growth(current.view, candidate.view)
            accepted = improved and (explained or partial) and not grown
            if accepted:
                decision = (
                    "added: explains its evidence" if explained else "added: explains most of its evidence"
                )
            elif not improved:
                decision = "rejected: the error did not drop"
            elif grown:
                decision = (
                    "rejected: the noise model had to grow to absorb what it leaves ("
                    + ", ".join(grown)
                    + ")"
                )
            else:
                decision = "rejected: its own evidence remains (it does not explain the residual)"
            record["tried"].append(
                {
                    "effect": detection.effect,
                    "statistic": detection.statistic,
                    "statistic_name": detection.statistic_name,
                    "threshold": detection.threshold,
                    "log10_p": detection.log10_p,
                    "error_before": current.headline,
                    "error_after": candidate.headline,
                    "verification_statistic": verification.statistic,
                    "verification_log10_p": verification.log10_p,
                    "decision": decision,
                    "parameters": fitted.parameters,
                }
            )
            if accepted:
                kept = (detection, candidate, fitted)
                break
        if kept is None:
            record["decision"] = "unexplained: no candidate explains the significant evidence"
            unexplained = True
            break
        detection, candidate, fitted = kept
        record["decision"] = f"added {detection.effect}"
        record["effect"] = detection.effect
        record["statistic"] = detection.statistic
        effects.append(detection.effect)
        tried_and_kept.add(detection.effect)
        current = candidate
    else:
        # The iteration budget ran out: whatever is still significant is unexplained.
        if any(d.significant for n, d in current.detections.items() if n not in tried_and_kept):
            unexplained = True
    if not unexplained:
        # No detector fires, but the Allan variance may still disagree with the model beyond its intervals:
        # the largest |z| over τ and axes, Bonferroni over all of them (each z from χ²_ν with the EDF).
        fits = [current.view.fits[axis] for axis in axes]
        tests = sum(len(fit.allan_sizes) for fit in fits)
        worst_axis, worst_z = axes[0], 0.0
        for axis, fit in zip(axes, fits, strict=True):
            z = _z_from_chi_square(fit.allan_observed, fit.allan_model, fit.allan_edf)
            if len(z) and float(np.max(np.abs(z))) > abs(worst_z):
                worst_axis, worst_z = axis, float(z[np.argmax(np.abs(z))])
        log10_p = min(0.0, (math.log(2.0 * tests) + float(stats.norm.logsf(abs(worst_z)))) / math.log(10.0))
        if log10_p < math.log10(alpha):
            unexplained = True
            steps.append(
                {
                    "iteration": len(steps) + 1,
                    "error": current.headline,
                    "detections": [],
                    "tried": [],
                    "decision": (
                        f"unexplained: the Allan variance of {worst_axis} still misfits the model "
                        f"(largest z = {worst_z:.3g} over {tests} τ and axes, log10 p = {log10_p:.3g})"
                    ),
                }
            )
    if not unexplained:
        # A stochastic effect kept for "most of its evidence" leaves the rest unexplained.
        for name in effects:
            verification = current.detections.get(name) or CATALOGUE[name].verify(current.view, alpha)
            if verification.significant:
                unexplained = True
                steps.append(
                    {
                        "iteration": len(steps) + 1,
                        "error": current.headline,
                        "detections": [],
                        "tried": [],
                        "decision": f"unexplained: evidence of {name} remains after adding it",
                    }
                )
                break
    final_effects = effects if effects else ["none"]
    if unexplained:
        final_effects = [*effects, "unexplained"]
    fitted_effects = [{"effect": f.effect, "parameters": f.parameters} for f in current.view.spec.fitted]
    return LoopResult(
        effects=final_effects,
        metric=HEADLINE_METRIC,
        error_before=before.headline,
        error_after=current.headline,
        model_before={axis: before.view.noise[axis].as_dict() for axis in axes},
        model_after={axis: current.view.noise[axis].as_dict() for axis in axes},
        metrics_before=before.metrics,
        metrics_after=current.metrics,
        steps=steps,
        fitted_effects=fitted_effects,
        observations=observations,
        samples_per_revolution=N,
        source=recording.source,
        axes=list(axes),
        evaluation_before=before,
        evaluation_after=current,
    )


# --- the report ------------------------------------------------------------------------------------------


def _format_number(value: Any) -> str:
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.4g}"
    return str(value)


def render_summary(result: LoopResult, plots: Sequence[str] = ()) -> str:
    """The markdown summary of one run of the loop (deterministic for a given result)."""
    lines = [
        f"# Closed loop on `{result.source}`",
        "",
        f"- axes: {', '.join(result.axes)}; samples per revolution N = {result.samples_per_revolution}",
        f"- effects (in the order added): **{', '.join(result.effects)}**",
        f"- headline error `{result.metric}`: {result.error_before:.4g} before, "
        f"{result.error_after:.4g} after "
        "(root mean square of the z-values of every prediction; about 1 when the model is right)",
        "",
    ]
    if result.observations:
        lines += ["## Observations", ""] + [f"- {note}" for note in result.observations] + [""]
    lines += ["## Error before and after, in the same metrics", ""]
    lines += ["| metric | before | after |", "|---|---|---|"]
    lines.append(f"| {result.metric} | {result.error_before:.4g} | {result.error_after:.4g} |")
    for axis in result.axes:
        for key in ("rms_z", "max_abs_z", "fraction_outside_95"):
            lines.append(
                f"| Allan variance {axis}: {key} | {result.metrics_before['allan'][axis][key]:.4g} | "
                f"{result.metrics_after['allan'][axis][key]:.4g} |"
            )
        lines.append(
            f"| averaged bins {axis}: exceedance of ±2σ (expect {BAND_EXPECTED_EXCEEDANCE:.4f}) | "
            f"{result.metrics_before['averaged_bins'][axis]['exceedance_2sigma']:.4f} | "
            f"{result.metrics_after['averaged_bins'][axis]['exceedance_2sigma']:.4f} |"
        )
        lines.append(
            f"| tails {axis}: excess kurtosis of differences | "
            f"{result.metrics_before['tails'][axis]['excess_kurtosis_of_differences']:.4g} | "
            f"{result.metrics_after['tails'][axis]['excess_kurtosis_of_differences']:.4g} |"
        )
    if result.metrics_before["carouselled_bins"] and result.metrics_after["carouselled_bins"]:
        before, after = result.metrics_before["carouselled_bins"], result.metrics_after["carouselled_bins"]
        lines.append(
            f"| carouselled bins ({before['mode']}): exceedance of ±2σ | {before['exceedance_2sigma']:.4f} | "
            f"{after['exceedance_2sigma']:.4f} |"
        )
        lines.append(
            f"| carouselled bins: mean squared z (expect 1) | {before['mean_square_z']:.4g} | "
            f"{after['mean_square_z']:.4g} |"
        )
    for name in sorted(
        set(result.metrics_before["residual_tests"]) | set(result.metrics_after["residual_tests"])
    ):
        b = result.metrics_before["residual_tests"].get(name, {}).get("z")
        a = result.metrics_after["residual_tests"].get(name, {}).get("z")
        lines.append(
            f"| residual test {name}: z | {'—' if b is None else f'{b:.3g}'} | "
            f"{'—' if a is None else f'{a:.3g}'} |"
        )
    lines += ["", "## Fitted noise model (per axis)", ""]
    lines += ["| axis | model | bias (rad/s) | long-run white σ² | RRW σ_q² | 1/f σ_f² | AR coefficients |"]
    lines += ["|---|---|---|---|---|---|---|"]
    for label, model in (("before", result.model_before), ("after", result.model_after)):
        for axis in result.axes:
            m = model[axis]
            ar = ", ".join(f"{a:.3g}" for a in m["ar_coefficients"]) or "—"
            lines.append(
                f"| {axis} | {label} | {m['bias_rad_s']:.5g} | {m['long_run_white_variance_rad2_s2']:.4g} | "
                f"{m['rrw_variance_rad2_s2']:.4g} | {m['flicker_variance_rad2_s2']:.4g} | {ar} |"
            )
    lines += ["", "## Steps", ""]
    for step in result.steps:
        lines.append(f"**Iteration {step['iteration']}** (error {step['error']:.4g}): {step['decision']}")
        lines.append("")
        significant = [d for d in step["detections"] if d["significant"]]
        if significant:
            lines += ["| significant test | statistic | threshold | log10 p |", "|---|---|---|---|"]
            for d in significant:
                lines.append(
                    f"| {d['effect']} ({d['statistic_name']}) | {_format_number(d['statistic'])} | "
                    f"{_format_number(d['threshold'])} | {_format_number(d['log10_p'])} |"
                )
            lines.append("")
        for tried in step["tried"]:
            lines.append(
                f"- tried **{tried['effect']}**: error {tried['error_before']:.4g} → "
                f"{tried['error_after']:.4g}; "
                f"its evidence afterwards log10 p = {_format_number(tried['verification_log10_p'])}; "
                f"{tried['decision']}"
            )
        notes = [d["note"] for d in step["detections"] if d.get("note")]
        lines += [f"- note: {note}" for note in notes]
        lines.append("")
    if result.fitted_effects:
        lines += ["## Fitted effects", ""]
        for fitted in result.fitted_effects:
            lines.append(f"- **{fitted['effect']}**: `{_clean_json(fitted['parameters'])}`")
        lines.append("")
    if plots:
        lines += ["## Plots", ""] + [f"![{name}]({name})" for name in plots] + [""]
    return "\n".join(lines)


def write_report(result: LoopResult, directory: Any) -> list[str]:
    """Write ``summary.md`` and the plots (matplotlib, Agg backend, imported here) into ``directory``.

    Plots: the Allan deviation with its 95 % intervals and the model before/after for each axis; the
    averaged bins of each axis and the carouselled bins with the ±2σ bands of the model before and after
    (as TIM 2014 Fig. 7). Returns the file names written.
    """
    from pathlib import Path

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    directory = Path(directory)
    if directory.exists() and not directory.is_dir():
        raise ValueError(f"report directory {directory}: exists and is not a directory")
    directory.mkdir(parents=True, exist_ok=True)
    before, after = result.evaluation_before, result.evaluation_after
    written: list[str] = []

    figure, axes_list = plt.subplots(1, len(result.axes), figsize=(6 * len(result.axes), 4.5), squeeze=False)
    for plot, axis in zip(axes_list[0], result.axes, strict=True):
        for label, evaluation, style in (("before", before, "--"), ("after", after, "-")):
            fit = evaluation.view.fits[axis]
            if label == "after":
                low = fit.allan_observed * fit.allan_edf / stats.chi2.ppf(0.975, fit.allan_edf)
                high = fit.allan_observed * fit.allan_edf / stats.chi2.ppf(0.025, fit.allan_edf)
                plot.fill_between(
                    fit.allan_tau, np.sqrt(low), np.sqrt(high), color="0.85", label="95 % interval"
                )
                plot.loglog(
                    fit.allan_tau, np.sqrt(fit.allan_observed), "k.", label="measured (after removal)"
                )
            plot.loglog(fit.allan_tau, np.sqrt(fit.allan_model), style, label=f"model {label}")
        plot.loglog(
            before.view.fits[axis].allan_tau,
            np.sqrt(before.view.fits[axis].allan_observed),
            "x",
            color="0.5",
            label="measured (as recorded)",
        )
        plot.set_xlabel("τ (s)")
        plot.set_ylabel("Allan deviation (rad/s)")
        plot.set_title(axis)
        plot.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(directory / "allan_deviation.png", dpi=110)
    plt.close(figure)
    written.append("allan_deviation.png")

    rows = len(result.axes) + (1 if after.carouselled is not None and len(after.carouselled["values"]) else 0)
    figure, plots = plt.subplots(rows, 1, figsize=(9, 2.6 * rows), squeeze=False)
    for row, axis in enumerate(result.axes):
        plot = plots[row][0]
        bins_before, bins_after = before.averaged[axis], after.averaged[axis]
        plot.plot(bins_before["time"], bins_before["values"], color="0.6", lw=0.6, label="as recorded")
        plot.plot(bins_after["time"], bins_after["values"], color="k", lw=0.6, label="effects removed")
        for bins, style, label in ((bins_before, "--", "±2σ before"), (bins_after, "-", "±2σ after")):
            band = BAND_SIGMA * np.sqrt(bins["variance"])
            plot.plot(bins["time"], band, "b" + style, lw=0.8, label=label)
            plot.plot(bins["time"], -band, "b" + style, lw=0.8)
        plot.set_ylabel(f"averaged {axis} (rad/s)")
        plot.legend(fontsize=7, loc="upper right")
    if rows > len(result.axes):
        plot = plots[-1][0]
        plot.plot(
            before.carouselled["time"], before.carouselled["values"], color="0.6", lw=0.6, label="as recorded"
        )
        plot.plot(
            after.carouselled["time"], after.carouselled["values"], color="k", lw=0.6, label="effects removed"
        )
        for bins, style, label in (
            (before.carouselled, "--", "±2σ before"),
            (after.carouselled, "-", "±2σ after"),
        ):
            band = BAND_SIGMA * np.sqrt(bins["variance"])
            plot.plot(bins["time"], band, "r" + style, lw=0.8, label=label)
            plot.plot(bins["time"], -band, "r" + style, lw=0.8)
        plot.set_ylabel("carouselled (rad/s)")
        plot.legend(fontsize=7, loc="upper right")
    plots[-1][0].set_xlabel("time (s)")
    figure.tight_layout()
    figure.savefig(directory / "bins.png", dpi=110)
    plt.close(figure)
    written.append("bins.png")

    (directory / "summary.md").write_text(render_summary(result, written), encoding="utf-8")
    written.append("summary.md")
    return written
