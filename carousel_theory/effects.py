"""The catalogue of effects that a declared gyro noise model (bias + white + rate random walk) lacks.

Each entry says, with a stable name, (1) how the effect is put into a synthetic recording, (2) how it is
detected in the residual of a fitted model — a test statistic whose null distribution is computed under
the *fitted* noise model, with a family-wise false-alarm rate ``alpha`` — (3) how it enters the model and
(4) how it is fitted or removed. The closed loop (:mod:`carousel_theory.closed_loop`) runs every detector,
tries the best-supported effect, and keeps it only when it explains its own evidence.

======================  ==========================================================================
name                    detection statistic (null: the fitted model; Bonferroni over the scan)
======================  ==========================================================================
``warmup``              max over time constants τ_c of |z| of the GLS amplitude of e^{−t/τ_c}
``temperature``         |z| of the GLS coefficient of the temperature column
``steps``               max over t₀ of |z| of the GLS estimate of a bias step after sample t₀
``spikes``              max robust |z| of the residual about its running median (trimmed scale)
``sinusoid``            max of the Hann periodogram / (model PSD × local median level), ~Exp(1)
``colored_noise``       z of log(median level 5–15 % f_s / median level 35–50 % f_s) vs. the model
``flicker``             F = Δχ²/dispersion of the Allan-variance fit when a 1/f (d = 1/2) term is added
``quantization``        lattice test: every sample an integer multiple of one step (an observation)
``none``                nothing significant
======================  ==========================================================================

The trend detectors (warm-up, temperature, steps) use generalised least squares under white noise + rate
random walk: on first differences (which remove the bias) the noise is a tridiagonal MA(1), so the GLS
weights cost one banded solve. The standard deviation ``sd`` of a linear statistic Σ w_t e_t
(Σ w_t = 0, so the bias drops out) is the exact propagation of the fitted processes:
σ_WN² Σ w_t² + σ_q² Σ_i (Σ_{t≥i} w_t)² + σ_f² Σ_i (Σ_{t≥i} w_t ψ_{t−i})²
(:func:`carousel_theory.propagation.weighted_sum_variance`, TIM 2014 eqs. (2)–(3)); the rate random walk
therefore cannot masquerade as a trend, a step or a warm-up at the stated false-alarm rate.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar, Protocol

import numpy as np
from scipy import ndimage, optimize, stats

from carousel_theory._validation import check_real

__all__ = [
    "CATALOGUE",
    "DEFAULT_ALPHA",
    "Detection",
    "Effect",
    "FittedEffect",
    "ResidualView",
    "check_effect_parameters",
    "detect_quantization",
    "hann_periodogram",
]

#: Family-wise false-alarm rate of each detector in one iteration of the loop.
DEFAULT_ALPHA = 0.01


class ResidualView(Protocol):
    """What a detector sees: the residual of each axis and the fitted noise model (see closed_loop)."""

    axes: tuple[str, ...]
    time: np.ndarray
    sample_rate: float
    temperature: np.ndarray | None
    residuals: dict[str, np.ndarray]

    def statistic_variance(
        self, axis: str, weights: np.ndarray, noise: Any = None, include_flicker: bool = True
    ) -> float: ...

    def refit(self, axis: str, signal: np.ndarray) -> Any: ...

    def bounded_noise(self, axis: str, noise: Any) -> Any: ...

    def statistic_variance_dof(
        self, axis: str, weights: np.ndarray, noise: Any = None
    ) -> tuple[float, float]: ...

    def gls_weights(self, axis: str, regressor: np.ndarray, noise: Any = None) -> np.ndarray: ...

    def gls_step_scan(self, axis: str) -> tuple[np.ndarray, np.ndarray, float]: ...

    def gls_difference_solve(self, axis: str, vector: np.ndarray) -> np.ndarray: ...

    @property
    def gls_block(self) -> int: ...

    def noise_psd(self, axis: str, frequencies: np.ndarray) -> np.ndarray: ...

    def allan_chi_square(self, axis: str, extra: tuple[str, ...] = ()) -> tuple[float, int]: ...

    def fitted_ar_coefficients(self, axis: str) -> tuple[float, ...]: ...

    def noise_parameters(self, axis: str) -> dict[str, float]: ...


@dataclass(frozen=True)
class Detection:
    """The outcome of one detector on one residual.

    ``log10_p`` is the base-10 logarithm of the family-wise p-value (Bonferroni over the scan and the
    axes); ``significant`` is ``p < alpha``. ``testable`` is False when the data cannot show the effect
    at all (no temperature column, a constant one, a record too short); ``note`` then says why.
    """

    effect: str
    statistic: float
    statistic_name: str
    threshold: float
    log10_p: float
    significant: bool
    axes: tuple[str, ...] = ()
    details: dict[str, Any] = field(default_factory=dict)
    testable: bool = True
    note: str = ""

    def as_dict(self) -> dict[str, Any]:
        return {
            "effect": self.effect,
            "statistic": _json_number(self.statistic),
            "statistic_name": self.statistic_name,
            "threshold": _json_number(self.threshold),
            "log10_p": _json_number(self.log10_p),
            "significant": self.significant,
            "axes": list(self.axes),
            "details": {k: _json_value(v) for k, v in self.details.items()},
            "testable": self.testable,
            "note": self.note,
        }


@dataclass(frozen=True)
class FittedEffect:
    """A fitted effect: deterministic signals to subtract per axis, samples to replace per axis (spikes),
    and/or a change to the stochastic model ("ar_order", "flicker")."""

    effect: str
    parameters: dict[str, Any]
    signals: dict[str, np.ndarray] = field(default_factory=dict)
    replaced: dict[str, np.ndarray] = field(default_factory=dict)
    noise_change: dict[str, Any] = field(default_factory=dict)


def _json_number(value: float) -> float | str:
    value = float(value)
    return value if math.isfinite(value) else str(value)


def _json_value(value: Any) -> Any:
    if isinstance(value, (float, np.floating)):
        return _json_number(float(value))
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_json_value(v) for v in value]
    if isinstance(value, dict):
        return {k: _json_value(v) for k, v in value.items()}
    return value


def _log10_two_sided(z: float, tests: int) -> float:
    """log10 of min(1, tests · 2 Φ̄(|z|)) computed in logs, so that z = 200 does not underflow."""
    log_p = math.log(2.0 * max(tests, 1)) + float(stats.norm.logsf(abs(z)))
    return min(0.0, log_p / math.log(10.0))


def _threshold_two_sided(alpha: float, tests: int) -> float:
    return float(stats.norm.isf(alpha / (2.0 * max(tests, 1))))


def hann_periodogram(values: np.ndarray, sample_rate: float) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies (Hz, 0 … f_s/2) and the Hann-windowed periodogram |Σ h_t x_t e^{−iωt}|² / Σ h_t².

    For a stationary process of discrete spectral density S(ω) (per-sample variance units, S = σ² for
    white noise) each ordinate has mean ≈ S and, away from 0 and f_s/2, is ≈ S × Exp(1) for Gaussian
    data. The window keeps the leakage of a rate random walk's 1/f² spectrum local.
    """
    x = values - values.mean()
    window = np.hanning(len(x))
    spectrum = np.fft.rfft(x * window)
    power = (spectrum.real**2 + spectrum.imag**2) / float(np.dot(window, window))
    frequencies = np.fft.rfftfreq(len(x), d=1.0 / sample_rate)
    return frequencies, power


def _block_median(values: np.ndarray, block: int) -> np.ndarray:
    """A running-median-like level: the median of each block of ``block`` values, linearly interpolated
    between block centres (O(n), unlike a true running median, and just as robust to isolated lines)."""
    count = max(1, len(values) // block)
    edges = np.linspace(0, len(values), count + 1).astype(int)
    centres = 0.5 * (edges[:-1] + edges[1:] - 1)
    medians = np.array([np.median(values[a:b]) for a, b in itertools.pairwise(edges)])
    return np.interp(np.arange(len(values)), centres, medians)


class Effect:
    """Base class of a catalogue entry; see the module table."""

    name = "none"
    kind = "none"  # "additive", "noise_filter", "output", or "none"
    stochastic = False
    summary = ""
    detection = ""
    enters_model = ""
    removal = ""
    defaults: ClassVar[dict[str, float]] = {}

    def inject(
        self,
        signal: np.ndarray,
        time: np.ndarray,
        temperature: np.ndarray | None,
        rng: np.random.Generator,
        parameters: Mapping[str, float],
    ) -> np.ndarray:
        """Return ``signal`` with the effect put in (additive effects receive zeros and return the signal)."""
        raise NotImplementedError(f"effect {self.name!r} cannot be simulated")

    def detect(self, view: ResidualView, alpha: float = DEFAULT_ALPHA) -> Detection:
        raise NotImplementedError(f"effect {self.name!r} has no detector")

    def fit(self, view: ResidualView, detection: Detection, alpha: float = DEFAULT_ALPHA) -> FittedEffect:
        raise NotImplementedError(f"effect {self.name!r} cannot be fitted")

    def verify(self, view: ResidualView, alpha: float = DEFAULT_ALPHA) -> Detection:
        """The test that decides whether the effect, once added, explains its own evidence."""
        return self.detect(view, alpha)

    def describe(self) -> dict[str, str]:
        return {
            "name": self.name,
            "summary": self.summary,
            "detection": self.detection,
            "enters_model": self.enters_model,
            "removal": self.removal,
        }


def _regressor_statistic(
    view: ResidualView, axis: str, regressor: np.ndarray, *, quick: bool = False, refit: bool = True
) -> tuple[float, float, float]:
    """(z, amplitude, degrees of freedom) of a regressor g in the residual by generalised least squares.

    The statistic is Σ w_t e_t with the GLS weights w of white noise + rate random walk (first differences,
    which also remove the bias); its variance is the exact propagation of the whole noise model, 1/f noise
    included (module docstring). The noise model is refitted on the residual *without* the fitted
    regressor (a Wald test under the alternative): fitted with the effect still in the data, the rate
    random walk would absorb it. z is referred to Student's t with the Satterthwaite degrees of freedom of
    the estimated variance. ``quick`` skips the refit and the 1/f term, to rank the points of a scan.
    """
    weights = view.gls_weights(axis, regressor)
    information = float(np.dot(weights, regressor))
    if information <= 0.0:
        return 0.0, 0.0, math.inf
    projection = float(np.dot(weights, view.residuals[axis]))
    amplitude = projection / information
    if quick:
        variance, dof = view.statistic_variance(axis, weights, include_flicker=False), math.inf
    elif not refit:
        variance, dof = view.statistic_variance_dof(axis, weights)
    else:
        refitted = view.refit(axis, amplitude * (regressor - regressor.mean()))
        # The refit may not go below the null fit's lower 2-standard-error limit: a regressor can absorb
        # a stretch of the random walk, and σ_q² → 0 would make the test anticonservative.
        refitted = view.bounded_noise(axis, refitted)
        weights = view.gls_weights(axis, regressor, refitted)
        projection = float(np.dot(weights, view.residuals[axis]))
        variance, dof = view.statistic_variance_dof(axis, weights, noise=refitted)
    return projection / math.sqrt(max(variance, 1e-300)), amplitude, dof


def _log10_two_sided_t(z: float, tests: int, dof: float) -> float:
    """log10 of min(1, tests · 2 P(|T_ν| > |z|)), Student's t with ν degrees of freedom (normal for ν = ∞)."""
    if not math.isfinite(dof):
        return _log10_two_sided(z, tests)
    log_p = math.log(2.0 * max(tests, 1)) + float(stats.t.logsf(abs(z), dof))
    return min(0.0, log_p / math.log(10.0))


def _threshold_two_sided_t(alpha: float, tests: int, dof: float) -> float:
    if not math.isfinite(dof):
        return _threshold_two_sided(alpha, tests)
    return float(stats.t.isf(alpha / (2.0 * max(tests, 1)), dof))


# --- deterministic effects ----------------------------------------------------------------------------


class Warmup(Effect):
    name = "warmup"
    kind = "additive"
    summary = "exponential turn-on transient of the bias, A e^{−t/τ}"
    detection = (
        "max over 8 time constants (log-spaced, T/500 … T/4) of |z| of the projection of the residual on "
        "the centred e^{−t/τ}; Bonferroni over the grid and the axes"
    )
    enters_model = "a deterministic term A e^{−t/τ} added to the bias of each axis"
    removal = (
        "nonlinear least squares for (A, τ) on 1-s bin means, started at the best grid point; subtracted"
    )
    defaults: ClassVar[dict[str, float]] = {"amplitude": 2e-3, "time_constant": 120.0}

    def inject(self, signal, time, temperature, rng, parameters):
        return signal + parameters["amplitude"] * np.exp(-(time - time[0]) / parameters["time_constant"])

    def _grid(self, view: ResidualView) -> np.ndarray:
        span = float(view.time[-1] - view.time[0])
        low = max(span / 500.0, 5.0 / view.sample_rate)
        return np.geomspace(low, span / 4.0, 8)

    def detect(self, view, alpha=DEFAULT_ALPHA):
        grid = self._grid(view)
        tests = len(grid) * len(view.axes)
        relative = view.time - view.time[0]
        best: dict[str, Any] = {"log10_p": 1.0}
        significant_axes = []
        for axis in view.axes:
            ranked = (0.0, float(grid[0]))
            for time_constant in grid:
                z, _, _ = _regressor_statistic(view, axis, np.exp(-relative / time_constant), quick=True)
                if abs(z) > abs(ranked[0]):
                    ranked = (z, float(time_constant))
            z, amplitude, dof = _regressor_statistic(view, axis, np.exp(-relative / ranked[1]))
            log10_p = _log10_two_sided_t(z, tests, dof)
            if log10_p < math.log10(alpha):
                significant_axes.append(axis)
            if log10_p < best["log10_p"]:
                best = {
                    "log10_p": log10_p,
                    "z": z,
                    "axis": axis,
                    "tau": ranked[1],
                    "amplitude": amplitude,
                    "dof": dof,
                }
        if "z" not in best:
            best = {
                "log10_p": 0.0,
                "z": 0.0,
                "axis": "",
                "tau": float(grid[0]),
                "amplitude": 0.0,
                "dof": math.inf,
            }
        return Detection(
            self.name,
            abs(best["z"]),
            "max abs z of an exponential transient (Student t)",
            _threshold_two_sided_t(alpha, tests, best["dof"]),
            best["log10_p"],
            bool(significant_axes),
            tuple(significant_axes),
            {
                "axis": best["axis"],
                "time_constant_s": best["tau"],
                "amplitude": best["amplitude"],
                "degrees_of_freedom": best["dof"],
            },
        )

    def fit(self, view, detection, alpha=DEFAULT_ALPHA):
        relative = view.time - view.time[0]
        grid = self._grid(view)
        centre = float(detection.details.get("time_constant_s") or grid[0])
        # The time constant maximising the GLS fit (the detector's own criterion) on a fine grid around
        # the detected one; the amplitude by GLS. Nonlinear least squares on the raw samples would ignore
        # the random walk and leave part of the transient behind.
        fine = np.geomspace(max(centre / 4.0, grid[0] / 2.0), min(centre * 4.0, grid[-1] * 2.0), 13)
        signals, fitted = {}, {}
        for axis in view.axes:
            best = (-1.0, centre, 0.0)
            for time_constant in fine:
                regressor = np.exp(-relative / time_constant)
                weights = view.gls_weights(axis, regressor)
                information = float(np.dot(weights, regressor))
                projection = float(np.dot(weights, view.residuals[axis]))
                if information > 0 and projection**2 / information > best[0]:
                    best = (projection**2 / information, float(time_constant), projection / information)
            _, time_constant, amplitude = best
            curve = amplitude * np.exp(-relative / time_constant)
            signals[axis] = curve - curve.mean()
            fitted[axis] = {"amplitude": amplitude, "time_constant_s": time_constant}
        return FittedEffect(self.name, fitted, signals=signals)


class Temperature(Effect):
    name = "temperature"
    kind = "additive"
    summary = "bias linear in the temperature column, k (T − T̄)"
    detection = (
        "|z| of the projection of the residual on the centred temperature column; Bonferroni over axes"
    )
    enters_model = "a term k_axis (T_t − T̄) added to the bias of each axis (k in rad/s per °C)"
    removal = "least squares for k on each axis; subtracted"
    defaults: ClassVar[dict[str, float]] = {"coefficient": 1.5e-3}

    def inject(self, signal, time, temperature, rng, parameters):
        if temperature is None:
            raise ValueError("effect 'temperature': the recording has no temperature column")
        return signal + parameters["coefficient"] * (temperature - temperature[0])

    def detect(self, view, alpha=DEFAULT_ALPHA):
        tests = len(view.axes)
        threshold = _threshold_two_sided(alpha, tests)
        if view.temperature is None:
            return Detection(
                self.name,
                0.0,
                "abs z of the temperature regression",
                threshold,
                0.0,
                False,
                testable=False,
                note="no temperature column: a temperature effect cannot be tested",
            )
        if float(np.ptp(view.temperature)) == 0.0:
            return Detection(
                self.name,
                0.0,
                "abs z of the temperature regression",
                threshold,
                0.0,
                False,
                testable=False,
                note="the temperature column is constant: no temperature effect can be tested",
            )
        best: dict[str, Any] = {"log10_p": 1.0}
        axes = []
        for axis in view.axes:
            # No refit under the alternative here: a smooth regressor absorbs part of the random walk,
            # and the refitted σ_q² would then make the test anticonservative (measured: 10 % false
            # alarms at α = 1 % on 600-s records).
            z, coefficient, dof = _regressor_statistic(view, axis, view.temperature, refit=False)
            log10_p = _log10_two_sided_t(z, tests, dof)
            if log10_p < math.log10(alpha):
                axes.append(axis)
            if log10_p < best["log10_p"]:
                best = {"log10_p": log10_p, "z": z, "axis": axis, "coefficient": coefficient, "dof": dof}
        return Detection(
            self.name,
            abs(best["z"]),
            "abs z of the temperature regression (Student t)",
            _threshold_two_sided_t(alpha, tests, best["dof"]),
            best["log10_p"],
            bool(axes),
            tuple(axes),
            {
                "axis": best["axis"],
                "coefficient_rad_s_per_degC": best["coefficient"],
                "temperature_range_degC": float(np.ptp(view.temperature)),
                "degrees_of_freedom": best["dof"],
            },
        )

    def fit(self, view, detection, alpha=DEFAULT_ALPHA):
        assert view.temperature is not None
        centred = view.temperature - view.temperature.mean()
        signals, fitted = {}, {}
        for axis in view.axes:
            coefficient = float(np.dot(centred, view.residuals[axis]) / np.dot(centred, centred))
            signals[axis] = coefficient * centred
            fitted[axis] = {"coefficient_rad_s_per_degC": coefficient}
        return FittedEffect(self.name, fitted, signals=signals)


class Steps(Effect):
    name = "steps"
    kind = "additive"
    summary = "abrupt bias jumps (a bias step at time t₀)"
    detection = (
        "max over t₀ of |z| of the generalised-least-squares estimate of a bias step between samples t₀ and "
        "t₀ + 1 under white noise + rate random walk (all t₀ from one tridiagonal solve), sd from the whole "
        "fitted model; Bonferroni over the n − 1 positions and the axes"
    )
    enters_model = "a term h · 1[t ≥ t₀] added to the bias, for up to 5 jumps"
    removal = "each jump at the maximum |z|, its height by generalised least squares; subtracted; repeated"
    defaults: ClassVar[dict[str, float]] = {"size": 2e-3, "time": 0.6}  # time as a fraction of the record
    maximum_steps = 5

    def inject(self, signal, time, temperature, rng, parameters):
        at = time[0] + parameters["time"] * (time[-1] - time[0])
        return signal + parameters["size"] * (time >= at)

    def _quick_scan(self, view: ResidualView, axis: str) -> tuple[np.ndarray, float, float, float]:
        """(z of a step after every block, sd of the statistic, information (Σ_Δ⁻¹)_tt, degrees of freedom)
        under the fit; the degrees of freedom (Satterthwaite) carry the uncertainty of the fitted σ_q²,
        which on short records is large and would otherwise turn random-walk excursions into "steps"."""
        u, middle_weights, information = view.gls_step_scan(axis)
        variance, dof = view.statistic_variance_dof(axis, middle_weights)
        sd = math.sqrt(max(variance, 1e-300))
        return u / sd, sd, information, dof

    def detect(self, view, alpha=DEFAULT_ALPHA):
        n = len(view.time)
        tests = (n // view.gls_block - 1) * len(view.axes)
        best, best_axis, best_at, best_height, axes = 0.0, "", 0, 0.0, []
        best_log10_p, best_dof = 1.0, math.inf
        for axis in view.axes:
            z_all, sd, information, dof = self._quick_scan(view, axis)
            index = int(np.argmax(np.abs(z_all)))
            at = (index + 1) * view.gls_block
            # Under the model fitted with the data as they are (no refit): a refit without the largest
            # increment of the random walk lowers σ_q² enough to make the scan's maximum anticonservative.
            z, height = float(z_all[index]), float(z_all[index] * sd / information)
            log10_p = _log10_two_sided_t(z, tests, dof)
            if log10_p < math.log10(alpha):
                axes.append(axis)
            if log10_p < best_log10_p:
                best, best_axis, best_at, best_height = z, axis, at, height
                best_log10_p, best_dof = log10_p, dof
        threshold = _threshold_two_sided_t(alpha, tests, best_dof)
        return Detection(
            self.name,
            abs(best),
            "max abs z of a bias step (GLS, Student t)",
            threshold,
            min(0.0, best_log10_p),
            bool(axes),
            tuple(axes),
            {"axis": best_axis, "time_s": float(view.time[min(best_at, n - 1)]), "height": best_height},
        )

    def fit(self, view, detection, alpha=DEFAULT_ALPHA):
        n = len(view.time)
        tests = (n // view.gls_block - 1) * len(view.axes)
        signals, fitted = {}, {}
        for axis in view.axes:
            z_all, sd, information, dof = self._quick_scan(view, axis)
            threshold = _threshold_two_sided_t(alpha, tests, dof)
            statistic = z_all * sd  # u_t
            total = np.zeros(n)
            jumps = []
            for _ in range(self.maximum_steps):
                index = int(np.argmax(np.abs(statistic)))
                if abs(statistic[index]) / sd <= threshold:
                    break
                height = float(statistic[index] / information)
                at = (index + 1) * view.gls_block
                # Remove this jump from the scan: u changes by height · Σ_Δ⁻¹ e_index.
                impulse = np.zeros(len(statistic))
                impulse[index] = 1.0
                statistic = statistic - height * view.gls_difference_solve(axis, impulse)
                step = height * (np.arange(n) >= at)
                total += step - step.mean()
                jumps.append({"time_s": float(view.time[at]), "height": height})
            signals[axis] = total
            fitted[axis] = {"jumps": jumps}
        return FittedEffect(self.name, fitted, signals=signals)


class Sinusoid(Effect):
    name = "sinusoid"
    kind = "additive"
    summary = "a periodic disturbance A sin(2π f t + θ) (vibration, a mains pick-up)"
    detection = (
        "max over frequencies of the Hann periodogram divided by the fitted model's spectrum and by the "
        "local median level (/ln 2): Exp(1) under the model; Bonferroni over the frequencies and the axes"
    )
    enters_model = "a deterministic term A sin(2π f t + θ) per axis, one frequency shared by the axes"
    removal = "frequency refined by maximising the exact periodogram near the peak; A, θ by least squares"
    defaults: ClassVar[dict[str, float]] = {"amplitude": 1e-3, "frequency": 0.37, "phase": 0.0}
    lowest_bin = 8
    level_block = 512

    def inject(self, signal, time, temperature, rng, parameters):
        return signal + parameters["amplitude"] * np.sin(
            2 * np.pi * parameters["frequency"] * time + parameters["phase"]
        )

    def _ratios(self, view: ResidualView, axis: str) -> tuple[np.ndarray, np.ndarray]:
        frequencies, power = hann_periodogram(view.residuals[axis], view.sample_rate)
        frequencies, power = frequencies[self.lowest_bin : -1], power[self.lowest_bin : -1]
        whitened = power / view.noise_psd(axis, frequencies)
        level = _block_median(whitened, self.level_block) / math.log(2.0)
        return frequencies, whitened / level

    def detect(self, view, alpha=DEFAULT_ALPHA):
        best, best_axis, best_frequency, axes = 0.0, "", 0.0, []
        count = 1
        for axis in view.axes:
            frequencies, ratio = self._ratios(view, axis)
            if len(ratio) == 0:
                continue
            count = len(ratio) * len(view.axes)
            index = int(np.argmax(ratio))
            if ratio[index] > math.log(count / alpha):
                axes.append(axis)
            if ratio[index] > best:
                best, best_axis, best_frequency = float(ratio[index]), axis, float(frequencies[index])
        threshold = math.log(count / alpha)
        # P(max of `count` Exp(1) > u) ≤ count e^{−u}
        log10_p = min(0.0, (math.log(count) - best) / math.log(10.0))
        return Detection(
            self.name,
            best,
            "max periodogram / (model spectrum × local level)",
            threshold,
            log10_p,
            bool(axes),
            tuple(axes),
            {"axis": best_axis, "frequency_hz": best_frequency},
        )

    def fit(self, view, detection, alpha=DEFAULT_ALPHA):
        axis = detection.details["axis"]
        x = view.residuals[axis] - view.residuals[axis].mean()
        t = view.time - view.time[0]
        resolution = view.sample_rate / len(t)
        start = float(detection.details["frequency_hz"])

        def negative_power(frequency: float) -> float:
            phase = 2 * np.pi * frequency * t
            return -(float(np.dot(x, np.cos(phase))) ** 2 + float(np.dot(x, np.sin(phase))) ** 2)

        result = optimize.minimize_scalar(
            negative_power,
            bounds=(max(start - resolution, resolution / 4), start + resolution),
            method="bounded",
            options={"xatol": resolution * 1e-4},
        )
        frequency = float(result.x)
        phase = 2 * np.pi * frequency * t
        design = np.column_stack((np.sin(phase), np.cos(phase), np.ones_like(t)))
        signals, fitted = {}, {}
        for name in view.axes:
            coefficients, *_ = np.linalg.lstsq(design, view.residuals[name], rcond=None)
            signals[name] = design[:, :2] @ coefficients[:2]
            fitted[name] = {
                "frequency_hz": frequency,
                "amplitude": float(math.hypot(*coefficients[:2])),
                "phase_rad": float(math.atan2(coefficients[1], coefficients[0])),
            }
        return FittedEffect(self.name, fitted, signals=signals)


class Spikes(Effect):
    name = "spikes"
    kind = "additive"
    summary = "isolated outliers (shocks, bit errors, bumps)"
    detection = (
        "max over samples of the robust |z| of the residual about its 15-sample running median, scale from "
        "the central 99 %; threshold Φ⁻¹(1 − α/(2n·axes))"
    )
    enters_model = (
        "flagged samples (and their direct neighbours) are excluded: replaced by the running median"
    )
    removal = "replacement by the running median; the count and the largest |z| are reported"
    defaults: ClassVar[dict[str, float]] = {"amplitude": 0.05, "rate": 2e-4}
    window = 15

    def inject(self, signal, time, temperature, rng, parameters):
        n = len(time)
        count = max(1, round(parameters["rate"] * n))
        where = rng.choice(n, size=count, replace=False)
        signs = rng.choice((-1.0, 1.0), size=count)
        result = signal.copy()
        result[where] += signs * parameters["amplitude"]
        return result

    def _robust_z(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        # The mean of the medians of the 7 samples before and the 7 after (the sample itself left out, so
        # that its deviation is Gaussian in the tails as well as in the centre). scipy's 1-D median filter
        # is fast; shifting the centred 7-sample median by ±4 gives the one-sided windows.
        half = self.window // 2
        centred = ndimage.median_filter(x, size=half, mode="nearest")
        shift = half // 2 + 1
        padded = np.pad(centred, shift, mode="edge")
        running = 0.5 * (padded[: len(x)] + padded[2 * shift :])
        deviation = x - running
        # Scale in two passes: the central 99 % (a variance, so a coarse quantization lattice does not bias
        # it the way it biases a median absolute deviation), then the standard deviation of everything within
        # 4.5 of those scales (the deviation from a median is not exactly Gaussian in the shoulders, so the
        # trimmed estimate alone is a few per cent low, which matters at the 5σ of a Bonferroni threshold).
        low, high = np.quantile(deviation, (0.005, 0.995))
        central = deviation[(deviation >= low) & (deviation <= high)]
        cut = float(stats.norm.isf(0.005))
        trimmed_factor = 1.0 - 2.0 * cut * float(stats.norm.pdf(cut)) / 0.99
        scale = math.sqrt(float(np.var(central)) / trimmed_factor) if len(central) > 1 else 0.0
        if scale > 0:
            inside = deviation[np.abs(deviation - np.median(deviation)) < 4.5 * scale]
            scale = float(np.std(inside))
        scale = scale or float(np.std(deviation)) or 1.0
        return deviation / scale, running

    def detect(self, view, alpha=DEFAULT_ALPHA):
        n = len(view.time)
        tests = n * len(view.axes)
        threshold = _threshold_two_sided(alpha, tests)
        best, best_axis, best_count, axes = 0.0, "", 0, []
        for axis in view.axes:
            z, _ = self._robust_z(view.residuals[axis])
            peak = float(np.max(np.abs(z)))
            count = int(np.sum(np.abs(z) > threshold))
            if peak > threshold:
                axes.append(axis)
            if peak > best:
                best, best_axis, best_count = peak, axis, count
        return Detection(
            self.name,
            best,
            "max robust abs z about the running median",
            threshold,
            _log10_two_sided(best, tests),
            bool(axes),
            tuple(axes),
            {"axis": best_axis, "samples_beyond_threshold": best_count},
        )

    def fit(self, view, detection, alpha=DEFAULT_ALPHA):
        n = len(view.time)
        threshold = _threshold_two_sided(alpha, n * len(view.axes))
        replaced, fitted = {}, {}
        for axis in view.axes:
            z, _ = self._robust_z(view.residuals[axis])
            flagged = np.abs(z) > threshold
            # A spike's neighbours carry part of it when the sensor filters internally.
            flagged = flagged | np.roll(flagged, 1) | np.roll(flagged, -1)
            replaced[axis] = flagged
            fitted[axis] = {"samples_replaced": int(flagged.sum())}
        return FittedEffect(self.name, fitted, replaced=replaced)


# --- stochastic effects -------------------------------------------------------------------------------


class ColoredNoise(Effect):
    name = "colored_noise"
    kind = "noise_filter"
    stochastic = True
    summary = "short-correlated noise: white noise through a low-order filter (a sensor's internal low-pass)"
    detection = (
        "z of log(median whitened periodogram in 5–15 % of f_s / median in 35–50 % of f_s), whitened by "
        "the fitted model's spectrum; every second ordinate (independent); se² = 2.08 (1/M₁ + 1/M₂)"
    )
    enters_model = (
        "the white noise becomes an autoregressive process of order p ≤ 4 (Yule–Walker), its long-run "
        "variance playing the white-noise level for bins and for the Allan variance at long τ"
    )
    removal = "the noise model is refitted on the prewhitened residual (innovations scaled by 1/(1 − Σa))"
    defaults: ClassVar[dict[str, float]] = {"coefficient": 0.5}
    maximum_order = 4

    def inject(self, signal, time, temperature, rng, parameters):
        from scipy.signal import lfilter

        a = float(parameters["coefficient"])
        if not -1 < a < 1:
            raise ValueError(f"colored_noise: coefficient={a!r}: must lie in (-1, 1)")
        return lfilter([1.0], [1.0, -a], signal)

    def _statistic(self, view: ResidualView, axis: str) -> tuple[float, int]:
        frequencies, power = hann_periodogram(view.residuals[axis], view.sample_rate)
        relative = frequencies / view.sample_rate
        whitened = (power / np.maximum(view.noise_psd(axis, frequencies), 1e-300))[::2]
        relative = relative[::2]
        low = whitened[(relative >= 0.05) & (relative < 0.15)]
        high = whitened[(relative >= 0.35) & (relative < 0.5)]
        if len(low) < 8 or len(high) < 8:
            return 0.0, 0
        # log of a median of M Exp(1) values has variance ≈ 1 / (4 M f(m)² m²) = 2.08 / M
        se = math.sqrt(2.08 / len(low) + 2.08 / len(high))
        return math.log(np.median(low) / np.median(high)) / se, len(low) + len(high)

    def detect(self, view, alpha=DEFAULT_ALPHA):
        tests = len(view.axes)
        threshold = _threshold_two_sided(alpha, tests)
        best, best_axis, axes = 0.0, "", []
        for axis in view.axes:
            z, ordinates = self._statistic(view, axis)
            if ordinates == 0:
                continue
            if abs(z) > threshold:
                axes.append(axis)
            if abs(z) >= abs(best):
                best, best_axis = z, axis
        return Detection(
            self.name,
            abs(best),
            "abs z of the spectral slope, 10 % vs 42 % of f_s",
            threshold,
            _log10_two_sided(best, tests),
            bool(axes),
            tuple(axes),
            {"axis": best_axis, "signed_z": best},
        )

    def fit(self, view, detection, alpha=DEFAULT_ALPHA):
        return FittedEffect(
            self.name, {"maximum_order": self.maximum_order}, noise_change={"ar_order": self.maximum_order}
        )


class Flicker(Effect):
    name = "flicker"
    kind = "additive"
    stochastic = True
    summary = "1/f noise (bias instability), fractional integration of order d = 1/2 (TIM 2014 eq. (3))"
    detection = (
        "F = Δχ² / max(1, χ²/ν) of the Allan-variance fit (octave τ, weights from the equivalent degrees of "
        "freedom) when a 1/f term is added to the fitted terms; F(1, ν); Bonferroni over axes"
    )
    enters_model = "a 1/f component σ_f² (d = 1/2) in the noise model of each axis, fitted with the others"
    removal = "refit of the noise model with the 1/f term; nothing is subtracted"
    defaults: ClassVar[dict[str, float]] = {"variance": 1e-8, "d": 0.5}

    def inject(self, signal, time, temperature, rng, parameters):
        from carousel_theory.processes import sample_flicker

        return signal + sample_flicker(len(time), rng=rng, d=parameters["d"], variance=parameters["variance"])

    def detect(self, view, alpha=DEFAULT_ALPHA):
        tests = len(view.axes)
        best: dict[str, Any] = {"log10_p": 1.0, "statistic": 0.0, "axis": "", "dof": 1}
        axes = []
        for axis in view.axes:
            without, _ = view.allan_chi_square(axis)
            with_flicker, dof = view.allan_chi_square(axis, ("flicker",))
            dof = max(dof, 1)
            # F test: the gain over the residual dispersion of the larger fit (at least 1), so that Allan
            # points correlated across τ or a model slightly off elsewhere do not pass for 1/f noise.
            dispersion = max(1.0, with_flicker / dof)
            statistic = max(0.0, without - with_flicker) / dispersion
            log10_p = min(0.0, math.log10(tests) + float(stats.f.logsf(statistic, 1, dof)) / math.log(10.0))
            if log10_p < math.log10(alpha):
                axes.append(axis)
            if log10_p < best["log10_p"]:
                best = {"log10_p": log10_p, "statistic": statistic, "axis": axis, "dof": dof}
        return Detection(
            self.name,
            best["statistic"],
            "F of the Allan-variance fit with a 1/f term",
            float(stats.f.isf(alpha / tests, 1, best["dof"])),
            min(0.0, best["log10_p"]),
            bool(axes),
            tuple(axes),
            {"axis": best["axis"], "residual_degrees_of_freedom": best["dof"]},
        )

    def fit(self, view, detection, alpha=DEFAULT_ALPHA):
        return FittedEffect(self.name, {"d": 0.5}, noise_change={"flicker": True})

    def verify(self, view, alpha=DEFAULT_ALPHA):
        """After adding 1/f noise: the χ² goodness of fit of the Allan variance on every axis."""
        tests = len(view.axes)
        worst, worst_axis, worst_log_p, axes = 0.0, "", 0.0, []
        for axis in view.axes:
            chi_square, dof = view.allan_chi_square(axis)
            log_p = float(stats.chi2.logsf(chi_square, max(dof, 1))) / math.log(10.0) + math.log10(tests)
            if log_p < math.log10(alpha):
                axes.append(axis)
            if log_p <= worst_log_p:
                worst, worst_axis, worst_log_p = chi_square, axis, log_p
        return Detection(
            self.name,
            worst,
            "χ² of the Allan-variance fit",
            float("nan"),
            min(0.0, worst_log_p),
            bool(axes),
            tuple(axes),
            {"axis": worst_axis},
        )


class NoEffect(Effect):
    name = "none"
    summary = "the declared model fits: nothing significant remains"


class Quantization(Effect):
    name = "quantization"
    kind = "output"
    summary = "the output is a multiple of one step q (an ADC or a digital interface), noise q²/12 when fine"
    detection = (
        "lattice test: the smallest spacing q of the distinct values divides every sample to 1e-6 q and "
        "there are fewer than n/4 distinct values; an observation, reported, not added to the model"
    )
    enters_model = (
        "nothing: for a step much smaller than the noise, rounding adds white noise of variance q²/12 that "
        "the white term already absorbs"
    )
    removal = "none"
    defaults: ClassVar[dict[str, float]] = {"step": 8.7e-4}

    def inject(self, signal, time, temperature, rng, parameters):
        step = float(parameters["step"])
        if step <= 0:
            raise ValueError(f"quantization: step={step!r}: must be > 0")
        return np.round(signal / step) * step


def detect_quantization(values: np.ndarray) -> dict[str, Any]:
    """The lattice test of ``quantization``: {"quantized": bool, "step": q, "levels": count}."""
    x = np.asarray(values, dtype=np.float64)
    levels = np.unique(x)
    if len(levels) < 2 or len(levels) > max(2, len(x) // 4):
        return {"quantized": False, "step": 0.0, "levels": len(levels)}
    spacing = np.diff(levels)
    step = float(spacing.min())
    # A step at the rounding level of float64 is no lattice (averaged or converted data).
    if step <= 1e-9 * float(levels[-1] - levels[0]):
        return {"quantized": False, "step": 0.0, "levels": len(levels)}
    multiples = (levels - levels[0]) / step
    on_lattice = bool(
        np.all(np.abs(multiples - np.round(multiples)) < 1e-6 * max(1.0, np.abs(multiples).max()))
    )
    return {"quantized": on_lattice, "step": step if on_lattice else 0.0, "levels": len(levels)}


#: The catalogue, by stable name.
CATALOGUE: dict[str, Effect] = {
    effect.name: effect
    for effect in (
        NoEffect(),
        Flicker(),
        Warmup(),
        Temperature(),
        Spikes(),
        Sinusoid(),
        ColoredNoise(),
        Steps(),
        Quantization(),
    )
}

#: The effects the loop tests, in the order used to break exact ties.
TESTED_EFFECTS = ("spikes", "steps", "sinusoid", "warmup", "temperature", "colored_noise", "flicker")


def check_effect_parameters(name: str, parameters: Mapping[str, Any]) -> dict[str, float]:
    """The effect's defaults overridden by ``parameters``, each a finite real; unknown keys refused."""
    if name not in CATALOGUE or name == "none":
        raise ValueError(f"effect={name!r}: unknown effect; known: {sorted(set(CATALOGUE) - {'none'})}")
    if not isinstance(parameters, Mapping):
        raise TypeError(f"parameters={parameters!r}: must be a mapping of parameter name to number")
    defaults = CATALOGUE[name].defaults
    unknown = sorted(set(parameters) - set(defaults))
    if unknown:
        raise ValueError(f"effect {name!r}: unknown parameters {unknown}; known: {sorted(defaults)}")
    merged = dict(defaults)
    for key, value in parameters.items():
        merged[key] = float(check_real(f"{name}.{key}", value))
    return merged
