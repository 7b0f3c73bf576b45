"""The studies of SJ 2012 §V as library functions: a forecast for one recording, the Monte Carlo
batch test of Table I, and the same batch test on measured recordings.

Each study returns a frozen dataclass; :meth:`as_dict` gives the JSON form the command line
prints, and :func:`table1_markdown` the generated report ``docs/sj2012_table1_adis16405.md``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory._validation import (
    check_fractional_order,
    check_positive_integer,
    check_positive_real,
)
from carousel_theory.fast_prediction import Forecast
from carousel_theory.long_memory import exact_local_whittle
from carousel_theory.prediction import (
    BIAS_PRIORS,
    METHODS,
    BiasModel,
    MetricSummary,
    batch_metrics,
    moving_average_forecast,
    population_metrics,
    predict,
    simulate_sections,
    summarize_metrics,
)
from carousel_theory.progress import progress
from carousel_theory.restricted_likelihood import VarianceEstimate, estimate_noise_variances
from carousel_theory.signal_checks import check_noise_signal

__all__ = [
    "PAPER_TABLE1_MEASURED",
    "PAPER_TABLE1_SIMULATED",
    "ROW_NAMES",
    "AxisTable1",
    "MeasuredTable1",
    "MethodColumn",
    "RecordingForecast",
    "SimulatedTable1",
    "forecast_recording",
    "measured_table1",
    "simulated_table1",
    "table1_markdown",
]

RADIANS_TO_DEGREES = 180.0 / math.pi
#: SJ 2012 Table I as printed, simulated columns: (mean IE, IE std, mean RSSE, RSSE std).
PAPER_TABLE1_SIMULATED = {
    "KF": MetricSummary(-119, 2120, 136, 23.3),
    "MA": MetricSummary(-142, 2210, 139, 25.4),
    "CM": MetricSummary(-115, 2280, 138, 24.9),
}
#: SJ 2012 Table I as printed, real-data columns (°/s·samples and °/s).
PAPER_TABLE1_MEASURED = {
    "KF": MetricSummary(-0.0214, 3.86, 0.390, 0.0326),
    "MA": MetricSummary(-0.0258, 3.92, 0.393, 0.0339),
    "CM": MetricSummary(-0.0728, 4.22, 0.394, 0.0350),
}
ROW_NAMES = {"mean_ie": "mean IE", "std_ie": "IE std", "mean_rsse": "mean RSSE", "std_rsse": "RSSE std"}
#: REML searches σ_v²/σ_w² in these bounds; at the upper one the 1/f part is not identified.
RATIO_BOUNDS = (1e-4, 1e4)


# --- one recording -------------------------------------------------------------------------------


@dataclass(frozen=True)
class RecordingForecast:
    """The three forecasts of SJ 2012 §IV after one calibration segment of a recording.

    ``model`` is the Kalman model used (its variances given or estimated, see
    ``variances_estimated``, and its order estimated too when ``estimated_d``); ``measured`` holds
    the recorded samples of the horizon (NaN past the end of the recording); ``at_bound`` names the
    REML estimates that ended at their search bound (not identified by the calibration segment).
    """

    start: int
    calibration_length: int
    model: BiasModel
    variances_estimated: bool
    kalman: Forecast
    moving_average: np.ndarray
    calibration_mean: float
    measured: np.ndarray
    estimated_d: bool = False
    at_bound: tuple[str, ...] = ()

    def errors(self) -> dict[str, tuple[float, float]] | None:
        """(IE, RSSE) of KF, MA and CM when the whole horizon was recorded, else None."""
        if not np.isfinite(self.measured).all():
            return None
        predictions = {"KF": self.kalman.mean, "MA": self.moving_average, "CM": self.calibration_mean}
        result = {}
        for method, prediction in predictions.items():
            error = self.measured - prediction
            result[method] = (float(error.sum()), math.sqrt(float((error**2).sum())))
        return result


def _recording_model(
    calibration: np.ndarray,
    d: float,
    driving: float | None,
    white: float | None,
    prior: str,
    estimate_d: bool,
) -> tuple[BiasModel, bool, tuple[str, ...]]:
    if driving is not None and white is not None and not estimate_d:
        model = BiasModel(d=d, driving_variance=driving, white_variance=white, bias_prior=prior)
        return model, False, ()
    check_noise_signal(calibration, "the calibration segment")
    # One calibration segment: REML at fixed d, or of d too (SJ 2012 estimated the variances by hand).
    estimate = estimate_noise_variances(calibration[None, :], d, RATIO_BOUNDS, estimate_d=estimate_d)
    model = BiasModel(
        d=estimate.d,
        driving_variance=estimate.driving_variance if driving is None or estimate_d else driving,
        white_variance=estimate.white_variance if white is None or estimate_d else white,
        bias_prior=prior,
    )
    return model, True, estimate.at_bound


def forecast_recording(
    rates: np.ndarray,
    *,
    start: int,
    calibration_length: int,
    horizon: int,
    d: float = 0.5,
    driving_variance: float | None = None,
    white_variance: float | None = None,
    bias_prior: str = "calibration-mean",
    estimate_d: bool = False,
) -> RecordingForecast:
    """Calibrate on ``rates[start : start + calibration_length]`` and forecast ``horizon`` samples
    with KF (SJ 2012 §IV-A), MA (eq. (8)–(9)) and CM. Variances not given are REML estimates from
    the calibration segment at the order d; with ``estimate_d`` the order and both variances are
    estimated jointly by REML (given variances are then not used)."""
    n = check_positive_integer("calibration_length", calibration_length, minimum=2)
    h = check_positive_integer("horizon", horizon)
    start = check_positive_integer("start", start, minimum=0)
    d = float(check_fractional_order("d", d))
    if driving_variance is not None:
        check_positive_real("driving_variance", driving_variance)
    if white_variance is not None:
        check_positive_real("white_variance", white_variance, allow_zero=True)
    if bias_prior not in BIAS_PRIORS:
        raise ValueError(f"bias_prior={bias_prior!r}: must be one of {BIAS_PRIORS}")
    if start + n > rates.shape[0]:
        raise ValueError(
            f"calibration_length={calibration_length!r}: the recording has only {rates.shape[0] - start} "
            f"samples after start={start}"
        )
    calibration = np.asarray(rates[start : start + n], dtype=np.float64)
    model, estimated, at_bound = _recording_model(
        calibration, d, driving_variance, white_variance, bias_prior, estimate_d
    )
    indices = np.arange(start + n, start + n + h)
    measured = np.full(h, np.nan)
    available = indices < rates.shape[0]
    measured[available] = rates[indices[available]]
    return RecordingForecast(
        start=start,
        calibration_length=n,
        model=model,
        variances_estimated=estimated,
        kalman=predict(calibration, h, "KF", model),
        moving_average=moving_average_forecast(calibration, h),
        calibration_mean=float(calibration.mean()),
        measured=measured,
        estimated_d=estimate_d,
        at_bound=at_bound,
    )


# --- Table I -------------------------------------------------------------------------------------


@dataclass(frozen=True)
class MethodColumn:
    """One predictor's Table I statistics: ours (``observed``), the exact population values of the
    Gaussian model (simulated study only) and the paper's."""

    method: str
    observed: MetricSummary
    paper: MetricSummary
    population: MetricSummary | None = None
    mean_square_rsse: float | None = None

    def as_dict(self) -> dict[str, Any]:
        entry: dict[str, Any] = {**self.observed.as_dict(), "paper": self.paper.as_dict()}
        if self.population is not None:
            entry["population"] = {**self.population.as_dict(), "mean_square_rsse": self.mean_square_rsse}
        return entry


@dataclass(frozen=True)
class SimulatedTable1:
    """The Monte Carlo batch test of SJ 2012 §V-C: ``runs`` sections of ``calibration`` +
    ``horizon`` samples of ``model`` drawn with ``seed``."""

    runs: int
    seed: int
    calibration: int
    horizon: int
    model: BiasModel
    columns: tuple[MethodColumn, ...]

    def as_dict(self) -> dict[str, Any]:
        settings = {
            "kind": "simulated",
            "runs": self.runs,
            "seed": self.seed,
            "calibration": self.calibration,
            "horizon": self.horizon,
            "d": self.model.d,
            "driving_variance": self.model.driving_variance,
            "white_variance": self.model.white_variance,
            "bias_prior": self.model.bias_prior,
        }
        return {"settings": settings, **{column.method: column.as_dict() for column in self.columns}}


def simulated_table1(
    runs: int, calibration: int, horizon: int, model: BiasModel, seed: int, *, chunk: int = 100
) -> SimulatedTable1:
    """IE and RSSE of KF, MA and CM over ``runs`` simulated sections (SJ 2012 §V-B/C), drawn in
    chunks of ``chunk`` runs from ``numpy.random.default_rng(seed)``, beside the exact population
    values (:func:`carousel_theory.prediction.population_metrics`) and the paper's Table I."""
    runs = check_positive_integer("runs", runs, minimum=2)
    n = check_positive_integer("calibration", calibration, minimum=2)
    h = check_positive_integer("horizon", horizon)
    seed = check_positive_integer("seed", seed, minimum=0)
    chunk = check_positive_integer("chunk", chunk)
    if not isinstance(model, BiasModel):
        raise TypeError(f"model={model!r}: must be a BiasModel")
    rng = np.random.default_rng(seed)
    errors: dict[str, list[tuple[np.ndarray, np.ndarray]]] = {method: [] for method in METHODS}
    starts = range(0, runs, chunk)
    for first in progress(starts, total=len(starts), label=f"Table I runs (×{chunk})"):
        sections = simulate_sections(min(chunk, runs - first), n + h, model, rng=rng)
        for method in METHODS:
            errors[method].append(batch_metrics(sections, n, method, model))
    columns = []
    for method in progress(METHODS, label="population values"):
        integrated = np.concatenate([pair[0] for pair in errors[method]])
        root_sum = np.concatenate([pair[1] for pair in errors[method]])
        population, mean_square = population_metrics(n, h, method, model)
        columns.append(
            MethodColumn(
                method=method,
                observed=summarize_metrics(integrated, root_sum),
                paper=PAPER_TABLE1_SIMULATED[method],
                population=population,
                mean_square_rsse=mean_square,
            )
        )
    return SimulatedTable1(runs, seed, n, h, model, tuple(columns))


@dataclass(frozen=True)
class AxisTable1:
    """The measured batch test on one gyro axis: ``sections`` disjoint sections, the exact local
    Whittle d of each file, the REML variances and whether their ratio sits at the search bound."""

    axis: str
    sections: int
    whittle_d_per_file: tuple[float, ...]
    variances: VarianceEstimate
    ratio_at_bound: bool
    columns: tuple[MethodColumn, ...]

    def as_dict(self) -> dict[str, Any]:
        driving, white = self.variances.driving_variance, self.variances.white_variance
        return {
            "sections": self.sections,
            "whittle_d_per_file": list(self.whittle_d_per_file),
            "driving_variance": driving,
            "white_variance": white,
            "driving_std_deg_per_h": math.sqrt(driving) * RADIANS_TO_DEGREES * 3600.0,
            "white_std_deg_per_h": math.sqrt(white) * RADIANS_TO_DEGREES * 3600.0,
            "estimation_sections": self.variances.sections,
            "ratio_at_bound": self.ratio_at_bound,
            **{column.method: column.as_dict() for column in self.columns},
        }


@dataclass(frozen=True)
class MeasuredTable1:
    """The batch test of SJ 2012 §V-C on measured recordings (``files``), one entry per axis."""

    files: tuple[str, ...]
    sample_rate_hz: float
    average: int
    calibration: int
    horizon: int
    d: float
    bias_prior: str
    axes: tuple[AxisTable1, ...]

    def as_dict(self) -> dict[str, Any]:
        settings = {
            "kind": "measured",
            "files": list(self.files),
            "sample_rate_hz": self.sample_rate_hz,
            "average": self.average,
            "calibration": self.calibration,
            "horizon": self.horizon,
            "d": self.d,
            "bias_prior": self.bias_prior,
            "units": "IE in (°/s)·samples, RSSE in °/s",
        }
        return {"settings": settings, "axes": {entry.axis: entry.as_dict() for entry in self.axes}}


def _block_means(values: np.ndarray, average: int) -> np.ndarray:
    return values[: values.shape[0] // average * average].reshape(-1, average).mean(axis=1)


def _sections_of(rates: np.ndarray, length: int) -> np.ndarray:
    count = rates.shape[0] // length
    return rates[: count * length].reshape(count, length)


def _axis_table1(axis: str, series: Sequence[np.ndarray], n: int, h: int, d: float, prior: str) -> AxisTable1:
    sections = np.vstack([_sections_of(values, n + h) for values in series])
    whittle = tuple(exact_local_whittle(values).d for values in progress(series, label=f"{axis}: Whittle d"))
    # REML at d on every 10th calibration half (independent sections, one bias each).
    estimate = estimate_noise_variances(sections[::10, :n], d, RATIO_BOUNDS)
    model = BiasModel(
        d=d,
        driving_variance=estimate.driving_variance,
        white_variance=estimate.white_variance,
        bias_prior=prior,
    )
    columns = []
    for method in progress(METHODS, label=f"{axis}: predictors"):
        integrated, root_sum = batch_metrics(sections, n, method, model)
        summary = summarize_metrics(integrated * RADIANS_TO_DEGREES, root_sum * RADIANS_TO_DEGREES)
        columns.append(MethodColumn(method=method, observed=summary, paper=PAPER_TABLE1_MEASURED[method]))
    ratio_at_bound = estimate.white_variance / estimate.driving_variance > 0.999 * RATIO_BOUNDS[1]
    return AxisTable1(axis, int(sections.shape[0]), whittle, estimate, bool(ratio_at_bound), tuple(columns))


def _recording_paths(directory: Path) -> list[Path]:
    if not directory.is_dir():
        raise ValueError(f"directory={str(directory)!r}: must be a directory of recordings")
    files = sorted(path for path in directory.iterdir() if path.suffix.lower() in (".npz", ".csv"))
    if not files:
        raise ValueError(f"directory={str(directory)!r}: holds no .npz or .csv recording")
    return files


def measured_table1(
    directory: Path,
    calibration: int,
    horizon: int,
    *,
    d: float = 0.5,
    bias_prior: str = "calibration-mean",
    average: int = 1,
) -> MeasuredTable1:
    """The batch test of SJ 2012 §V-C on every ``*.npz``/``*.csv`` recording in ``directory``:
    block means of ``average`` samples, consecutive disjoint sections of calibration + horizon
    samples, σ_w² and σ_v² by REML at ``d`` on every 10th calibration segment, the paper's d
    checked per file by the exact local Whittle estimator. Rates in rad/s; IE and RSSE reported in
    °/s (·samples)."""
    from carousel_theory.data import load_recording

    n = check_positive_integer("calibration", calibration, minimum=2)
    h = check_positive_integer("horizon", horizon)
    d = float(check_fractional_order("d", d))
    average = check_positive_integer("average", average)
    if bias_prior not in BIAS_PRIORS:
        raise ValueError(f"bias_prior={bias_prior!r}: must be one of {BIAS_PRIORS}")
    files = _recording_paths(Path(directory))
    recordings = [load_recording(path) for path in progress(files, label="reading")]
    axes = [axis for axis in recordings[0].rates if all(axis in r.rates for r in recordings)]
    entries = tuple(
        _axis_table1(axis, [_block_means(r.rates[axis], average) for r in recordings], n, h, d, bias_prior)
        for axis in axes
    )
    return MeasuredTable1(
        files=tuple(path.name for path in files),
        sample_rate_hz=recordings[0].sample_rate / average,
        average=average,
        calibration=n,
        horizon=h,
        d=d,
        bias_prior=bias_prior,
        axes=entries,
    )


# --- the Markdown report -------------------------------------------------------------------------


def _format(value: float) -> str:
    return f"{value:.3g}"


def _simulated_markdown(table: SimulatedTable1) -> list[str]:
    model = table.model
    lines = [
        f"Simulated: {table.runs} runs (seed {table.seed}) of {table.calibration} + {table.horizon} samples, "
        f"d = {model.d}, σ_w² = {model.driving_variance}, σ_v² = {model.white_variance}, KF bias prior "
        f"{model.bias_prior}.",
        "",
        "| row | KF (ours) | KF (population) | KF (paper) | MA (ours) | MA (population) | MA (paper) | "
        "CM (ours) | CM (population) | CM (paper) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for row, name in ROW_NAMES.items():
        cells = []
        for column in table.columns:
            population = column.population.as_dict()[row] if column.population is not None else math.nan
            cells += [
                _format(column.observed.as_dict()[row]),
                _format(population),
                _format(column.paper.as_dict()[row]),
            ]
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return lines


def _axis_markdown(entry: AxisTable1, d: float) -> list[str]:
    values = entry.as_dict()
    whittle = ", ".join(f"{value:.3f}" for value in entry.whittle_d_per_file)
    unidentified = (
        " The ratio σ_v²/σ_w² sits at the search bound 10⁴: at this d the 1/f component is not "
        "identified in these segments."
    )
    lines = [
        f"## {entry.axis}: {entry.sections} sections",
        "",
        f"Exact local Whittle d per file (m = n^0.65): {whittle}. REML at d = {d}: "
        f"σ_w = {values['driving_std_deg_per_h']:.4g} °/h, σ_v = {values['white_std_deg_per_h']:.4g} °/h "
        f"(paper: 14 °/h and 45 °/h for its gyro) from {entry.variances.sections} segments."
        + (unidentified if entry.ratio_at_bound else ""),
        "",
        "| row | KF (ours) | KF (paper) | MA (ours) | MA (paper) | CM (ours) | CM (paper) |",
        "|---|---|---|---|---|---|---|",
    ]
    for row, name in ROW_NAMES.items():
        cells = []
        for column in entry.columns:
            cells += [_format(column.observed.as_dict()[row]), _format(column.paper.as_dict()[row])]
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return [*lines, ""]


def _measured_markdown(table: MeasuredTable1) -> list[str]:
    averaged = f" averaged over blocks of {table.average} samples" if table.average > 1 else ""
    lines = [
        f"Measured: {', '.join(table.files)}{averaged} at {table.sample_rate_hz:g} Hz, consecutive "
        f"disjoint sections of {table.calibration + table.horizon} samples, the first {table.calibration} "
        f"calibrate. d = {table.d} (as in the paper); σ_w² and σ_v² by restricted maximum likelihood "
        "(REML) of the model y = b + f + v at that d on every 10th calibration segment (one unknown bias per "
        "segment); exact local Whittle d per file for comparison with the paper's 0.535. KF bias prior "
        f"{table.bias_prior}. IE in (°/s)·samples, RSSE in °/s.",
        "",
        "These data are from a MEMS IMU without temperature control (no temperature column); the paper's "
        "gyro was temperature-conditioned, so the two are not expected to agree in scale.",
        "",
    ]
    for entry in table.axes:
        lines += _axis_markdown(entry, table.d)
    return lines


def table1_markdown(table: SimulatedTable1 | MeasuredTable1, command: str) -> str:
    """The generated Markdown report of a Table I study, headed by the ``command`` that makes it."""
    lines = [
        "<!-- generated by `carousel-theory predict --table1` — do not edit -->",
        "",
        "# SJ 2012 Table I: our batch test beside the paper's",
        "",
        f"Command: `{command}`",
        "",
    ]
    if isinstance(table, SimulatedTable1):
        return "\n".join(lines + _simulated_markdown(table)) + "\n"
    return "\n".join(lines + _measured_markdown(table))
