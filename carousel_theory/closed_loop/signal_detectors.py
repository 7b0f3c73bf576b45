"""Detectors of isolated outliers (spikes) and of a periodic disturbance (sinusoid)."""

from __future__ import annotations

import itertools
import math

import numpy as np
from scipy import ndimage, optimize, stats

from carousel_theory.closed_loop.detection import Detection, log10_two_sided, threshold_two_sided, untestable
from carousel_theory.closed_loop.null_distributions import exponential_over_median_log_sf
from carousel_theory.closed_loop.residual_model import spectral_density
from carousel_theory.closed_loop.view import FittedEffect, ResidualView

__all__ = ["SinusoidDetector", "SpikesDetector", "hann_periodogram", "residual_periodogram", "robust_z"]


def hann_periodogram(values: np.ndarray, sample_rate: float) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies (Hz, 0 … f_s/2) and the Hann-windowed periodogram |Σ h_t x_t e^{−iωt}|² / Σ h_t².

    For a stationary process of discrete spectral density S(ω) (per-sample variance units, S = σ² for
    white noise) each ordinate has mean ≈ S and, away from 0 and f_s/2, is ≈ S × Exp(1) for Gaussian
    data. The window keeps the leakage of a rate random walk's 1/f² spectrum local.
    """
    return _periodogram_in_place(np.subtract(values, values.mean()), sample_rate)


def residual_periodogram(view: ResidualView, axis: str) -> tuple[np.ndarray, np.ndarray]:
    """:func:`hann_periodogram` of ``view.residuals[axis]``, bit for bit, formed in an array of its own
    (:meth:`~carousel_theory.closed_loop.view.Residuals.fresh`): a long record holds no second copy of
    the residual beside the FFT's."""
    residual = view.residuals.fresh(axis)
    residual -= residual.mean()
    return _periodogram_in_place(residual, view.sample_rate)


def _periodogram_in_place(x: np.ndarray, sample_rate: float) -> tuple[np.ndarray, np.ndarray]:
    """The periodogram of the centred values ``x``, which it overwrites: each record-length array is
    freed once used, so that beside ``x`` at most the window, or the FFT's output and scratch, are held."""
    window = np.hanning(len(x))
    norm = float(np.dot(window, window))
    x *= window
    del window
    spectrum = np.fft.rfft(x)
    length = len(x)
    del x
    power = spectrum.real**2
    power += spectrum.imag**2
    del spectrum
    power /= norm
    frequencies = np.fft.rfftfreq(length, d=1.0 / sample_rate)
    return frequencies, power


def _block_edges(length: int, block: int) -> np.ndarray:
    """Edges of the blocks of :func:`_block_median`: ⌊length / block⌋ blocks of ``block`` to 2 block − 1
    values."""
    return np.linspace(0, length, max(1, length // block) + 1).astype(int)


def _block_median(values: np.ndarray, block: int) -> np.ndarray:
    """A running-median-like level: the median of each block of ``block`` values, linearly interpolated
    between block centres (O(n), unlike a true running median, and just as robust to isolated lines)."""
    edges = _block_edges(len(values), block)
    centres = 0.5 * (edges[:-1] + edges[1:] - 1)
    medians = np.array([np.median(values[a:b]) for a, b in itertools.pairwise(edges)])
    return np.interp(np.arange(len(values)), centres, medians)


def robust_z(x: np.ndarray, window: int = 15) -> np.ndarray:
    """Deviation of each sample from the mean of the medians of the 7 samples before and the 7 after
    (the sample itself left out, so its deviation is Gaussian in the tails as well as in the centre),
    over a robust scale.

    Scale in two passes: the central 99 % (a variance, so a coarse quantization lattice does not bias it
    the way it biases a median absolute deviation), then the standard deviation of everything within 4.5
    of those scales (the trimmed estimate alone is a few per cent low, which matters at the 5σ of a
    Bonferroni threshold). Computed in float64 whatever the input's type."""
    # Record-length temporaries are formed in place and freed once used: beside ``x`` a long record
    # holds at most three at a time (the same arithmetic, in the same order, as the plain expressions).
    x = np.asarray(x, dtype=np.float64)
    half = window // 2
    shift = half // 2 + 1
    padded = np.pad(ndimage.median_filter(x, size=half, mode="nearest"), shift, mode="edge")
    deviation = np.add(padded[: len(x)], padded[2 * shift :])
    del padded
    deviation *= 0.5
    np.subtract(x, deviation, out=deviation)  # x − (left + right)/2
    cut = float(stats.norm.isf(0.005))
    trimmed_factor = 1.0 - 2.0 * cut * float(stats.norm.pdf(cut)) / 0.99
    central_variance = _central_variance(deviation)
    scale = 0.0 if central_variance is None else math.sqrt(central_variance / trimmed_factor)
    if scale > 0:
        distance = np.subtract(deviation, np.median(deviation))
        np.abs(distance, out=distance)
        inside = distance < 4.5 * scale
        del distance
        scale = float(np.std(deviation[inside]))
    deviation /= scale or float(np.std(deviation)) or 1.0
    return deviation


def _central_variance(deviation: np.ndarray) -> float | None:
    """The variance of the central 99 % of ``deviation`` (None when fewer than two values are central)."""
    low, high = np.quantile(deviation, (0.005, 0.995))
    central = deviation[(deviation >= low) & (deviation <= high)]
    return float(np.var(central)) if len(central) > 1 else None


class SpikesDetector:
    """max over samples of the robust |z| about the running median; threshold Φ⁻¹(1 − α/(2n·axes))."""

    name = "spikes"
    stochastic = False

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        tests = len(view.time) * len(view.axes)
        threshold = threshold_two_sided(alpha, tests)
        best, best_axis, best_count, axes = 0.0, "", 0, []
        for axis in view.axes:
            z = robust_z(view.residuals[axis])
            np.abs(z, out=z)
            peak = float(np.max(z))
            if peak > threshold:
                axes.append(axis)
            if peak > best:
                best, best_axis, best_count = peak, axis, int(np.sum(z > threshold))
        return Detection(
            self.name,
            best,
            "max robust abs z about the running median",
            threshold,
            log10_two_sided(best, tests),
            bool(axes),
            tuple(axes),
            {"axis": best_axis, "samples_beyond_threshold": best_count},
        )

    def fit(self, view: ResidualView, detection: Detection, alpha: float) -> FittedEffect:
        """Flagged samples and their direct neighbours (a spike's neighbours carry part of it when the
        sensor filters internally) are replaced by the local median."""
        threshold = threshold_two_sided(alpha, len(view.time) * len(view.axes))
        replaced, fitted = {}, {}
        for axis in view.axes:
            z = robust_z(view.residuals[axis])
            flagged = np.abs(z, out=z) > threshold
            del z
            flagged = flagged | np.roll(flagged, 1) | np.roll(flagged, -1)
            replaced[axis] = flagged
            fitted[axis] = {"samples_replaced": int(flagged.sum())}
        return FittedEffect(self.name, fitted, replaced=replaced)


class SinusoidDetector:
    """max of the Hann periodogram / (model spectrum × local median level), Bonferroni over ordinates.

    Under the fitted model each whitened ordinate X is Exp(1) and the level is the median M of a block of
    ``level_block`` to 2·``level_block`` − 1 whitened ordinates over ln 2 (interpolated between block
    centres). For a level λ M_a + (1 − λ) M_b of two blocks' medians, P(X > u · level) =
    E[e^{−u(λM_a + (1−λ)M_b)/ln 2}] is log-convex in λ and so at most its value at λ ∈ {0, 1}: the exact
    tail of one median, :func:`~carousel_theory.closed_loop.null_distributions.exponential_over_median_log_sf`
    at the smallest block (the ordinate's own membership of its block only lowers the ratio, so leaving
    it out is conservative). At u ≈ 17 (the threshold of a 1 h record) the asymptotic Exp(1) tail e^{−u}
    is 1.7 times too small for blocks of 512."""

    name = "sinusoid"
    stochastic = False
    statistic_name = "max periodogram / (model spectrum × local median level)"
    lowest_bin = 8
    level_block = 512

    def _ratios(self, view: ResidualView, axis: str) -> tuple[np.ndarray, np.ndarray]:
        frequencies, power = residual_periodogram(view, axis)
        frequencies, power = frequencies[self.lowest_bin : -1], power[self.lowest_bin : -1]
        whitened = power / spectral_density(view.fits[axis].noise, frequencies)
        level = _block_median(whitened, self.level_block) / math.log(2.0)
        return frequencies, whitened / level

    def _peak(self, view: ResidualView, axis: str) -> tuple[float, float, int] | None:
        """(largest ratio, its frequency, ordinates) of one axis, None when there are no ordinates; the
        record-length arrays are freed before the next axis is analysed."""
        frequencies, ratio = self._ratios(view, axis)
        if not len(ratio):
            return None
        index = int(np.argmax(ratio))
        return float(ratio[index]), float(frequencies[index]), len(ratio)

    def _log_sf(self, ratio: float, length: int) -> float:
        """log P(one ordinate's ratio > ``ratio``) under the model (class docstring), at the smallest median
        block of a periodogram of ``length`` ordinates (the heaviest tail)."""
        smallest = int(np.diff(_block_edges(length, self.level_block)).min())
        return exponential_over_median_log_sf(ratio, smallest)

    def _threshold(self, alpha: float, tests: int, length: int) -> float:
        """The ratio at which the Bonferroni p-value tests · P(ratio > u) equals ``alpha``."""
        target = math.log(alpha / tests)
        return float(optimize.brentq(lambda u: self._log_sf(u, length) - target, 0.0, 10.0 - 10.0 * target))

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        peaks, length = {}, 0
        for axis in view.axes:
            peak = self._peak(view, axis)
            if peak is not None:
                ratio, frequency, length = peak
                peaks[axis] = (ratio, frequency)
        if not peaks:
            note = "the record is too short for a periodogram"
            return untestable(self.name, self.statistic_name, math.inf, note)
        tests = length * len(view.axes)
        threshold = self._threshold(alpha, tests, length)
        best_axis = max(peaks, key=lambda axis: peaks[axis][0])
        best, best_frequency = peaks[best_axis]
        log_p = math.log(tests) + self._log_sf(best, length)
        return Detection(
            self.name,
            best,
            self.statistic_name,
            threshold,
            min(0.0, log_p / math.log(10.0)),
            best > threshold,
            tuple(axis for axis, (peak, _) in peaks.items() if peak > threshold),
            {"axis": best_axis, "frequency_hz": best_frequency},
        )

    def fit(self, view: ResidualView, detection: Detection, alpha: float) -> FittedEffect:
        """Frequency refined by maximising the exact periodogram near the peak; A, θ by least squares."""
        axis = detection.details["axis"]
        x = view.residuals[axis] - view.residuals[axis].mean()
        t = view.time - view.time[0]
        resolution = view.sample_rate / len(t)
        start = float(detection.details["frequency_hz"])

        def negative_power(frequency: float) -> float:
            phase = 2 * np.pi * frequency * t
            return -(float(np.dot(x, np.cos(phase))) ** 2 + float(np.dot(x, np.sin(phase))) ** 2)

        bounds = (max(start - resolution, resolution / 4), start + resolution)
        result = optimize.minimize_scalar(
            negative_power, bounds=bounds, method="bounded", options={"xatol": resolution * 1e-4}
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
