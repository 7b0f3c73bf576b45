"""Bias predictors for a gyro with 1/f noise (SJ 2012 §IV) and their error metrics (§V).

Three predictors of the bias over the h samples after a calibration y_1 … y_n:

* ``"KF"`` — the Kalman filter of SJ 2012 §IV-A: one state per 1/f noise sample, propagated by the
  fractional-integration weights of eq. (5)–(6), plus a constant bias state, observed through white
  measurement noise. :func:`kalman_forecast` runs it literally (a growing state, O(n³));
  :func:`carousel_theory.fast_prediction.fast_kalman_forecast` gives the same numbers in
  O((n + h) log(n + h)) without white noise, and with it in O(n log² n + (n + h) log(n + h)) time and
  O(n + h) memory (the generalized Schur recursion of :mod:`carousel_theory.generalized_schur`).
* ``"MA"`` — the moving average of eq. (8)–(9): the k-th forecast is the mean of the last k
  calibration samples, and the mean of all of them once k ≥ n.
* ``"CM"`` — the calibration mean.

The bias state has one of two priors (``BiasModel.bias_prior``): ``"diffuse"`` (an unknown constant;
the forecast tends to its generalised-least-squares estimate) or ``"calibration-mean"`` (the bias
fixed at the calibration mean, the reading of "taking the sample mean as an additional state
variable", §IV-A). Both give forecasts that are linear in the data and do not depend on the bias.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from carousel_theory._validation import (
    check_finite_array,
    check_fractional_order,
    check_positive_integer,
    check_positive_real,
)
from carousel_theory.evaluation_cost import check_budget, growing_kalman_cost
from carousel_theory.fast_prediction import Forecast, _check_bias_prior, fast_kalman_forecast
from carousel_theory.long_memory import autoregressive_coefficients

__all__ = [
    "BIAS_PRIORS",
    "METHODS",
    "BiasModel",
    "Forecast",
    "MetricSummary",
    "batch_metrics",
    "calibration_mean_forecast",
    "error_moments",
    "forecast_batch",
    "integrated_error",
    "kalman_forecast",
    "moving_average_forecast",
    "population_metrics",
    "predict",
    "prediction_weights",
    "root_sum_squared_error",
    "sampling_standard_errors",
    "simulate_sections",
    "summarize_metrics",
]

#: The three predictors, in the column order of SJ 2012 Table I.
METHODS = ("KF", "MA", "CM")
BIAS_PRIORS = ("diffuse", "calibration-mean")


@dataclass(frozen=True)
class BiasModel:
    """The error model the Kalman predictor assumes (SJ 2012 §III–IV).

    y_t = b + f_t + v_t with f the fractional integral of TIM 2014 eq. (3) of order ``d`` driven by
    white noise of variance ``driving_variance`` (σ_w²), and v white of variance ``white_variance``
    (σ_v²). SJ 2012 Table I (simulated) uses d = ½ and σ_v² = 0. The default bias prior is the
    paper's ("calibration-mean"); "diffuse" gives the best linear unbiased predictor.
    """

    d: float = 0.5
    driving_variance: float = 1.0
    white_variance: float = 0.0
    bias_prior: str = "calibration-mean"

    def __post_init__(self) -> None:
        check_fractional_order("d", self.d)
        check_positive_real("driving_variance", self.driving_variance)
        check_positive_real("white_variance", self.white_variance, allow_zero=True)
        if self.bias_prior not in BIAS_PRIORS:
            raise ValueError(f"bias_prior={self.bias_prior!r}: must be one of {BIAS_PRIORS}")


def _check_calibration(calibration: np.ndarray) -> np.ndarray:
    data = np.asarray(calibration, dtype=np.float64)
    if data.ndim not in (1, 2):
        raise ValueError(f"calibration: must be a 1- or 2-dimensional array, got shape {data.shape}")
    check_finite_array("calibration", data.reshape(-1))
    if data.shape[-1] < 2:
        raise ValueError(f"calibration: must hold at least 2 samples, got {data.shape[-1]}")
    return data


def kalman_forecast(
    calibration: np.ndarray,
    horizon: int,
    *,
    d: float = 0.5,
    driving_variance: float = 1.0,
    white_variance: float = 0.0,
    bias_mean: float | None = None,
    bias_variance: float = math.inf,
    force: bool = False,
) -> Forecast:
    """The growing-state Kalman filter of SJ 2012 §IV-A, run literally on one calibration.

    State after sample j: (b, f_1, …, f_j). Time update, eq. (5)–(6):
    f_j = Σ_{i=1}^{j−1} [f_j]_i f_i + w_j with [f_j]_i = −Γ(j−i−d)/(Γ(j−i+1)Γ(−d)).
    Measurement y_j = b + f_j + v_j for j ≤ n; after n only the time update runs and the forecast
    is b + f_{n+k}. A diffuse bias prior (``bias_variance=inf``) uses the exact diffuse
    initialisation: after y_1 the bias has mean y_1, variance σ_w² + σ_v² and covariance −σ_w² with
    f_1. Cost O((n + h)³) time and O((n + h)²) memory: this is the reference that
    :func:`~carousel_theory.fast_prediction.fast_kalman_forecast` reproduces. Refused when its estimated
    cost exceeds :mod:`carousel_theory.evaluation_cost`'s budget (about n + h = 5000), unless ``force``.
    """
    data = _check_calibration(calibration)
    if data.ndim != 1:
        raise ValueError(f"calibration: must be one sequence (1-D), got shape {data.shape}")
    h = check_positive_integer("horizon", horizon)
    d = float(check_fractional_order("d", d))
    sigma2_w = float(check_positive_real("driving_variance", driving_variance))
    sigma2_v = float(check_positive_real("white_variance", white_variance, allow_zero=True))
    bias_mean, prior = _check_bias_prior(bias_mean, bias_variance)
    n = data.shape[0]
    total = n + h
    what = "growing-state Kalman filter (fast_kalman_forecast gives the same forecast without the state)"
    check_budget(growing_kalman_cost(what, total), force=force)
    weights = autoregressive_coefficients(d, total)  # π_1 … π_total; eq. (6) [f_j]_i = π_{j−i}
    mean = np.zeros(total + 1)  # index 0: b; index j: f_j
    covariance = np.zeros((total + 1, total + 1))
    forecast = np.empty(h)
    variance = np.empty(h)

    _first_sample(mean, covariance, data[0], sigma2_w, sigma2_v, bias_mean, prior)
    for j in range(2, total + 1):
        coefficients = weights[j - 2 :: -1]  # π_{j−1}, …, π_1 for f_1 … f_{j−1}
        row = covariance[:j, 1:j] @ coefficients  # Cov(state, f_j)
        covariance[j, :j] = row
        covariance[:j, j] = row
        covariance[j, j] = row[1:] @ coefficients + sigma2_w
        mean[j] = coefficients @ mean[1:j]
        if j <= n:
            _measurement_update(mean, covariance, j, data[j - 1], sigma2_v)
        else:
            k = j - n - 1
            forecast[k] = mean[0] + mean[j]
            variance[k] = covariance[0, 0] + 2.0 * covariance[0, j] + covariance[j, j]
    return Forecast(mean=forecast, bias_variance=variance, observation_variance=variance + sigma2_v)


def _first_sample(mean, covariance, observed, sigma2_w, sigma2_v, bias_mean, prior) -> None:
    """State after y_1 (f_1 = w_1): the exact diffuse initialisation, or a prior update."""
    if math.isinf(prior):
        mean[0] = observed
        covariance[0, 0] = sigma2_w + sigma2_v
        covariance[0, 1] = covariance[1, 0] = -sigma2_w
        covariance[1, 1] = sigma2_w
    else:
        mean[0] = bias_mean
        covariance[0, 0] = prior
        covariance[1, 1] = sigma2_w
        _measurement_update(mean, covariance, 1, observed, sigma2_v)


def _measurement_update(mean: np.ndarray, covariance: np.ndarray, j: int, observed: float, sigma2_v: float):
    """Kalman update of the state (b, f_1 … f_j) with y_j = b + f_j + v_j."""
    cross = covariance[: j + 1, 0] + covariance[: j + 1, j]  # P Hᵀ
    innovation_variance = cross[0] + cross[j] + sigma2_v
    gain = cross / innovation_variance
    mean[: j + 1] += gain * (observed - mean[0] - mean[j])
    covariance[: j + 1, : j + 1] -= np.outer(gain, cross)


def moving_average_forecast(calibration: np.ndarray, horizon: int) -> np.ndarray:
    """SJ 2012 eq. (8)–(9): ŷ_k = (1/k) Σ_{i=n−k+1}^{n} y_i for k < n, and the mean of all n
    calibration samples for k ≥ n. Accepts one calibration or one per row."""
    data = _check_calibration(calibration)
    h = check_positive_integer("horizon", horizon)
    n = data.shape[-1]
    tail_sums = np.cumsum(data[..., ::-1], axis=-1)  # sums of the last 1, 2, …, n samples
    k = np.arange(1, h + 1)
    used = np.minimum(k, n)
    return tail_sums[..., used - 1] / used


def calibration_mean_forecast(calibration: np.ndarray, horizon: int) -> np.ndarray:
    """The mean of the calibration samples, repeated ``horizon`` times (SJ 2012 "CM")."""
    data = _check_calibration(calibration)
    h = check_positive_integer("horizon", horizon)
    return np.repeat(data.mean(axis=-1, keepdims=True), h, axis=-1)


def predict(calibration: np.ndarray, horizon: int, method: str, model: BiasModel | None = None):
    """Forecast with one of :data:`METHODS`; the Kalman forecast uses the exact fast form.

    Returns a :class:`Forecast` for ``"KF"`` and an array of forecasts for ``"MA"`` and ``"CM"``
    (the paper gives them no variance).
    """
    if method not in METHODS:
        raise ValueError(f"method={method!r}: must be one of {METHODS}")
    data = _check_calibration(calibration)
    h = check_positive_integer("horizon", horizon)
    if method == "MA":
        return moving_average_forecast(data, h)
    if method == "CM":
        return calibration_mean_forecast(data, h)
    model = BiasModel() if model is None else model
    if not isinstance(model, BiasModel):
        raise TypeError(f"model={model!r}: must be a BiasModel")
    parameters = {
        "d": model.d,
        "driving_variance": model.driving_variance,
        "white_variance": model.white_variance,
    }
    if model.bias_prior == "diffuse":
        return fast_kalman_forecast(data, h, **parameters)
    centre = data.mean(axis=-1, keepdims=True)
    known = fast_kalman_forecast(data - centre, h, bias_mean=0.0, bias_variance=0.0, **parameters)
    return Forecast(known.mean + centre, known.bias_variance, known.observation_variance)


def _check_pair(data: np.ndarray, prediction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    actual = np.asarray(data, dtype=np.float64)
    predicted = np.asarray(prediction, dtype=np.float64)
    check_finite_array("data", actual.reshape(-1))
    check_finite_array("prediction", predicted.reshape(-1))
    if actual.shape != predicted.shape:
        raise ValueError(
            f"data and prediction: must have the same shape, got {actual.shape} and {predicted.shape}"
        )
    return actual, predicted


def integrated_error(data: np.ndarray, prediction: np.ndarray) -> np.ndarray | float:
    """IE = Σ_k (y_{n+k} − ŷ_{n+k}), SJ 2012 §V: the sum of the prediction errors (last axis)."""
    actual, predicted = _check_pair(data, prediction)
    return (actual - predicted).sum(axis=-1)


def root_sum_squared_error(data: np.ndarray, prediction: np.ndarray) -> np.ndarray | float:
    """RSSE = √(Σ_k (y_{n+k} − ŷ_{n+k})²), SJ 2012 §V (the text omits the root its name and
    Table I carry; see ``paper_check.md``)."""
    actual, predicted = _check_pair(data, prediction)
    return np.sqrt(((actual - predicted) ** 2).sum(axis=-1))


# --- The batch test of SJ 2012 §V-C (Table I) --------------------------------------------------


@dataclass(frozen=True)
class MetricSummary:
    """Mean and standard deviation of IE and RSSE over runs (the rows of SJ 2012 Table I).

    For a Monte Carlo batch these are sample statistics (standard deviations with ddof = 1); for
    :func:`population_metrics` they are the exact population values of the Gaussian model.
    """

    mean_ie: float
    std_ie: float
    mean_rsse: float
    std_rsse: float

    def as_dict(self) -> dict[str, float]:
        return {
            "mean_ie": self.mean_ie,
            "std_ie": self.std_ie,
            "mean_rsse": self.mean_rsse,
            "std_rsse": self.std_rsse,
        }


def forecast_batch(
    calibrations: np.ndarray, horizon: int, method: str, model: BiasModel | None = None
) -> np.ndarray:
    """Forecasts (runs, horizon) of one method for calibrations (runs, n)."""
    result = predict(calibrations, horizon, method, model)
    return result.mean if isinstance(result, Forecast) else result


def batch_metrics(
    sections: np.ndarray, calibration_length: int, method: str, model: BiasModel | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """IE and RSSE of one method on each row of ``sections`` (runs, n + h): the first
    ``calibration_length`` samples calibrate, the rest are predicted (SJ 2012 §V-C)."""
    data = np.asarray(sections, dtype=np.float64)
    if data.ndim != 2:
        raise ValueError(f"sections: must be a 2-dimensional array (runs, samples), got shape {data.shape}")
    n = check_positive_integer("calibration_length", calibration_length, minimum=2)
    if n >= data.shape[1]:
        raise ValueError(
            f"calibration_length={calibration_length!r}: must be below the section length {data.shape[1]}"
        )
    forecast = forecast_batch(data[:, :n], data.shape[1] - n, method, model)
    errors = data[:, n:] - forecast
    return errors.sum(axis=1), np.sqrt((errors**2).sum(axis=1))  # IE and RSSE, as the functions above


def summarize_metrics(ie: np.ndarray, rsse: np.ndarray) -> MetricSummary:
    """Sample means and standard deviations (ddof = 1) of IE and RSSE over runs."""
    ie = check_finite_array("ie", ie, min_length=2)
    rsse = check_finite_array("rsse", rsse, min_length=2)
    return MetricSummary(float(ie.mean()), float(ie.std(ddof=1)), float(rsse.mean()), float(rsse.std(ddof=1)))


def simulate_sections(
    runs: int,
    length: int,
    model: BiasModel,
    *,
    rng: np.random.Generator,
    bias: float = 0.0,
) -> np.ndarray:
    """``runs`` independent sections y_t = bias + f_t + v_t, t = 1 … length (SJ 2012 §V-B: white
    noise half-integrated by eq. (3), plus a constant bias; plus white noise if the model has it)."""
    from carousel_theory.long_memory import fractional_integral

    runs = check_positive_integer("runs", runs)
    length = check_positive_integer("length", length)
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng={rng!r}: must be a numpy.random.Generator")
    white = rng.standard_normal((runs, length)) * math.sqrt(model.driving_variance)
    sections = fractional_integral(white, model.d) + bias
    if model.white_variance > 0:
        sections += rng.standard_normal((runs, length)) * math.sqrt(model.white_variance)
    return sections


def prediction_weights(
    calibration_length: int, horizon: int, method: str, model: BiasModel | None = None
) -> np.ndarray:
    """The matrix M (horizon × n) with forecast = M y for one method; every row sums to 1, so the
    forecast error does not depend on the bias."""
    n = check_positive_integer("calibration_length", calibration_length, minimum=2)
    h = check_positive_integer("horizon", horizon)
    return forecast_batch(np.eye(n), h, method, model).T


def _expected_norm(eigenvalues: np.ndarray) -> float:
    """E √Q for Q = Σ λ_i χ²_1 (independent), from √Q = (1/(2√π)) ∫₀^∞ (1 − e^{−tQ}) t^{−3/2} dt:
    E √Q = (1/(2√π)) ∫ (1 − Π_i (1 + 2tλ_i)^{−½}) t^{−½} d(log t)."""
    from scipy.integrate import quad

    lam = eigenvalues[eigenvalues > 0]

    def integrand(log_t: float) -> float:
        t = math.exp(log_t)
        log_laplace = -0.5 * np.log1p(2.0 * t * lam).sum()
        return -math.expm1(log_laplace) / math.sqrt(t)

    centre = -math.log(float(lam.sum()))  # where t·Σλ ≈ 1
    total = 0.0
    for low, high in ((centre - 40, centre - 5), (centre - 5, centre + 5), (centre + 5, centre + 60)):
        value, _ = quad(integrand, low, high, limit=400, epsabs=0.0, epsrel=1e-12)
        total += value
    return total / (2.0 * math.sqrt(math.pi))


@functools.lru_cache(maxsize=32)
def _error_covariance(n: int, h: int, method: str, model: BiasModel) -> np.ndarray:
    """C_e = G Σ Gᵀ, the covariance of the forecast errors e = G x (read-only).

    Σ = σ_w² ΨΨᵀ + σ_v² I, so C_e = σ_w² (GΨ)(GΨ)ᵀ + σ_v² GGᵀ; GΨ is a causal filter run backwards
    along each row of G (Ψᵀ is upper-triangular Toeplitz), O(h (n + h) log(n + h)).
    """
    from carousel_theory.long_memory import fractional_integral

    weights = prediction_weights(n, h, method, model)
    operator = np.hstack([-weights, np.eye(h)])  # G: e = G x
    mixed = fractional_integral(operator[:, ::-1], model.d)[:, ::-1]  # GΨ
    covariance = model.driving_variance * (mixed @ mixed.T)
    if model.white_variance > 0:
        covariance += model.white_variance * (operator @ operator.T)
    covariance.setflags(write=False)
    return covariance


@functools.lru_cache(maxsize=32)
def _error_spectrum(n: int, h: int, method: str, model: BiasModel) -> tuple[np.ndarray, float]:
    """Eigenvalues of C_e and Var IE = 1ᵀ C_e 1."""
    covariance = _error_covariance(n, h, method, model)
    eigenvalues = np.linalg.eigvalsh(covariance)
    eigenvalues.setflags(write=False)
    return eigenvalues, float(covariance.sum())


def error_moments(
    calibration_length: int, horizon: int, method: str, model: BiasModel | None = None
) -> tuple[float, float, float]:
    """Exact (Var IE, E RSSE², Var RSSE²) = (1ᵀC_e1, tr C_e, 2 tr C_e²) of the Gaussian forecast errors;
    no eigenvalues needed."""
    n, h, model = _check_population_arguments(calibration_length, horizon, method, model)
    covariance = _error_covariance(n, h, method, model)
    return float(covariance.sum()), float(np.trace(covariance)), 2.0 * float((covariance**2).sum())


def _check_population_arguments(calibration_length, horizon, method, model):
    model = BiasModel() if model is None else model
    if not isinstance(model, BiasModel):
        raise TypeError(f"model={model!r}: must be a BiasModel")
    if method not in METHODS:
        raise ValueError(f"method={method!r}: must be one of {METHODS}")
    n = check_positive_integer("calibration_length", calibration_length, minimum=2)
    h = check_positive_integer("horizon", horizon)
    return n, h, model


def population_metrics(
    calibration_length: int, horizon: int, method: str, model: BiasModel | None = None
) -> tuple[MetricSummary, float]:
    """Exact population values of IE and RSSE for one method under the Gaussian model.

    The error e = y_fut − M y_cal = [−M, I] x is Gaussian with covariance C_e = G Σ Gᵀ,
    Σ = σ_w² Γ + σ_v² I (Γ of :func:`~carousel_theory.fast_prediction.fractional_covariance_rows`).
    Hence E IE = 0 and Var IE = 1ᵀ C_e 1 exactly, E RSSE² = tr C_e exactly, and E RSSE = E √Q with
    Q = Σ λ_i χ²_1 over the eigenvalues of C_e, a one-dimensional integral evaluated by adaptive
    quadrature (relative error ~1e-12); Var RSSE = tr C_e − (E RSSE)². Returns the summary and
    E RSSE².
    """
    n, h, model = _check_population_arguments(calibration_length, horizon, method, model)
    eigenvalues, variance_ie = _error_spectrum(n, h, method, model)
    mean_square = float(eigenvalues.sum())
    mean_rsse = _expected_norm(eigenvalues)
    std_rsse = math.sqrt(max(mean_square - mean_rsse**2, 0.0))
    return MetricSummary(0.0, math.sqrt(variance_ie), mean_rsse, std_rsse), mean_square


def _expected_norm_cubed(eigenvalues: np.ndarray) -> float:
    """E Q^{3/2} = (3/(4√π)) ∫₀^∞ (E e^{−tQ} − 1 + t E Q) t^{−5/2} dt (since ∫(e^{−u} − 1 + u)u^{−5/2} du
    = Γ(−3/2) = 4√π/3), written with series where the terms cancel."""
    from scipy.integrate import quad

    lam = eigenvalues[eigenvalues > 0]

    def log1p_minus_x(x: np.ndarray) -> np.ndarray:
        small = x < 1e-3
        out = np.empty_like(x)
        xs = x[small]
        out[small] = -(xs**2) / 2 + xs**3 / 3 - xs**4 / 4 + xs**5 / 5
        out[~small] = np.log1p(x[~small]) - x[~small]
        return out

    def integrand(log_t: float) -> float:
        t = math.exp(log_t)
        excess = -0.5 * float(log1p_minus_x(2.0 * t * lam).sum())  # log E e^{−tQ} + t E Q ≥ 0
        a = -0.5 * float(np.log1p(2.0 * t * lam).sum())  # log E e^{−tQ}
        expm1_minus = math.expm1(a) - a if abs(a) > 1e-2 else a * a / 2 + a**3 / 6 + a**4 / 24 + a**5 / 120
        return (expm1_minus + excess) * t**-1.5

    centre = -math.log(float(lam.sum()))
    total = 0.0
    for low, high in ((centre - 40, centre - 5), (centre - 5, centre + 5), (centre + 5, centre + 60)):
        value, _ = quad(integrand, low, high, limit=400, epsabs=0.0, epsrel=1e-12)
        total += value
    return 3.0 * total / (4.0 * math.sqrt(math.pi))


def sampling_standard_errors(
    calibration_length: int, horizon: int, method: str, model: BiasModel | None = None, runs: int = 1000
) -> MetricSummary:
    """Standard errors of the four Table I statistics computed from ``runs`` independent runs.

    Exact population moments enter: SE(mean IE) = σ_IE/√R; IE is Gaussian, so SE(std IE) =
    σ_IE/√(2(R − 1)) to first order; SE(mean RSSE) = σ_R/√R; SE(std RSSE) = √((μ₄ − σ_R⁴)/R)/(2σ_R)
    (delta method) with μ₄ = E Q² − 4μ E Q^{3/2} + 6μ² E Q − 3μ⁴ and E Q² = (tr C_e)² + 2 tr C_e².
    """
    n, h, model = _check_population_arguments(calibration_length, horizon, method, model)
    runs = check_positive_integer("runs", runs, minimum=2)
    summary, mean_square = population_metrics(n, h, method, model)
    eigenvalues, _ = _error_spectrum(n, h, method, model)
    mean = summary.mean_rsse
    fourth_raw = mean_square**2 + 2.0 * float((eigenvalues**2).sum())
    central_fourth = (
        fourth_raw - 4 * mean * _expected_norm_cubed(eigenvalues) + 6 * mean**2 * mean_square - 3 * mean**4
    )
    variance = summary.std_rsse**2
    return MetricSummary(
        summary.std_ie / math.sqrt(runs),
        summary.std_ie / math.sqrt(2.0 * (runs - 1)),
        summary.std_rsse / math.sqrt(runs),
        math.sqrt(max(central_fourth - variance**2, 0.0) / runs) / (2.0 * summary.std_rsse),
    )
