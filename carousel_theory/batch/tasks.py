"""The task adapter: the one place where the fleet calls the analyses.

Each task is a function ``(path, options, axis) -> list[BatchRow]`` over today's public APIs:
:func:`carousel_theory.data.load_recording`, :func:`carousel_theory.allan.allan_variance`,
:func:`carousel_theory.fitting.fit_noise_model` and :func:`carousel_theory.closed_loop.run_loop` — the
same calls the single-file commands ``allan``, ``fit`` and ``loop`` make, with the same options. A change
of those APIs touches this module only. The analyses are imported with this module, so a worker imports
them once, when it first receives a task, outside the time a task is timed against ``--task-timeout``.

``design`` fits each axis as ``fit`` does and then asks :mod:`carousel_theory.design` which rotation scheme
gives the smallest heading error with that gyro's noise (the fitted models of the first two axes are the
two horizontal gyros), at the latitude and durations given.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from carousel_theory.allan import ESTIMATORS, allan_variance
from carousel_theory.batch.rows import BatchRow
from carousel_theory.closed_loop import run_loop
from carousel_theory.data import MAX_VALUES, load_recording
from carousel_theory.design import DesignSettings, default_schemes, evaluate_scheme, recommended
from carousel_theory.fitting import COMPONENTS, NoiseModel, fit_recording
from carousel_theory.heading import check_latitude
from carousel_theory.rotation_schemes import parse_scheme
from carousel_theory.units import bias_instability_from_allan_minimum, rad_per_s_to_deg_per_h

__all__ = ["PER_AXIS_TASKS", "TASKS", "TaskOptions", "check_options", "recording_axes"]


@dataclass(frozen=True)
class TaskOptions:
    """The options of the single-file commands that change a result.

    ``columns``, ``units`` and ``sample_rate`` are the recording options (``--column``, ``--units``,
    ``--sample-rate``); ``estimator`` serves ``allan`` and ``fit``; ``model``, ``flicker_d``, ``tau_min``,
    ``tau_max`` and ``iterations`` serve ``fit`` (and ``design``); ``samples_per_revolution``, ``alpha``
    and ``loop_axes`` serve ``loop``; ``latitude``, ``design_durations`` and ``schemes`` (empty: the
    built-in sweep) serve ``design``.
    """

    columns: tuple[tuple[str, str], ...] = ()
    units: str = "rad/s"
    sample_rate: float | None = None
    estimator: str = "overlapping"
    model: tuple[str, ...] = ("white", "rrw")
    flicker_d: float | None = None
    tau_min: float | None = None
    tau_max: float | None = None
    iterations: int = 3
    samples_per_revolution: int = 200
    alpha: float = 0.01
    loop_axes: tuple[str, ...] | None = None
    latitude: float | None = None
    design_durations: tuple[float, ...] = (3600.0,)
    schemes: tuple[str, ...] = ()
    time_unit: str | None = None
    max_values: int = MAX_VALUES

    def fingerprint(self) -> str:
        """A stable text of the options: rows computed with other options are not reused."""
        return json.dumps(asdict(self), sort_keys=True, separators=(",", ":"))


def _load(path: str, options: TaskOptions, irregular: str = "refuse") -> Any:
    return load_recording(
        path,
        columns=dict(options.columns) or None,
        sample_rate=options.sample_rate,
        units=options.units,
        irregular=irregular,
        time_unit=options.time_unit,
        max_values=options.max_values,
    )


def recording_axes(path: str, options: TaskOptions) -> tuple[str, ...]:
    """The gyro axes of a recording, for splitting a long record into one task per axis."""
    return tuple(_load(path, options).rates)


def _recording_fields(recording: Any) -> dict[str, Any]:
    return {
        "samples": len(recording),
        "sample_rate_hz": float(recording.sample_rate),
        "duration_s": float(recording.duration),
    }


def _selected(recording: Any, axis: str | None) -> dict[str, np.ndarray]:
    if axis is None:
        return dict(recording.rates)
    if axis not in recording.rates:
        raise ValueError(f"axis={axis!r}: not in the recording's axes {sorted(recording.rates)}")
    return {axis: recording.rates[axis]}


def allan_task(path: str, options: TaskOptions, axis: str | None = None) -> list[BatchRow]:
    """``carousel-theory allan``: the octave Allan variance of each axis. The row keeps its minimum, the
    τ of the minimum and the bias instability read from it (min σ_A / 0.664, IEEE Std 952); no model is
    fitted, so there are no standard errors."""
    recording = _load(path, options)
    rows = []
    for name, rates in _selected(recording, axis).items():
        result = allan_variance(rates, recording.sample_rate, "octave", estimator=options.estimator)
        best = int(np.argmin(result.avar))
        minimum = math.sqrt(float(result.avar[best]))
        rows.append(
            BatchRow(
                path=path,
                task="allan",
                axis=name,
                **_recording_fields(recording),
                bias_deg_per_h=float(rad_per_s_to_deg_per_h(float(np.mean(rates)))),
                minimum_allan_deviation_rad_s=minimum,
                tau_at_minimum_s=float(result.tau[best]),
                bias_instability_deg_per_h=float(
                    rad_per_s_to_deg_per_h(bias_instability_from_allan_minimum(minimum))
                ),
            )
        )
    return rows


def _fit_fields(fit: Any) -> dict[str, Any]:
    """The field-unit parameters of a FitResult with their standard errors, the data's Allan minimum and
    the fit's χ²."""
    values: dict[str, Any] = {}
    for key, (value, error) in fit.field_units().items():
        values[key] = float(value)
        values[f"{key}_se"] = float(error)
    best = int(np.argmin(fit.allan.avar))
    values["minimum_allan_deviation_rad_s"] = math.sqrt(float(fit.allan.avar[best]))
    values["tau_at_minimum_s"] = float(fit.allan.tau[best])
    values["fit_chi_square"] = float(fit.chi_square)
    values["fit_degrees_of_freedom"] = float(fit.degrees_of_freedom)
    return values


def _fitted_axes(path: str, options: TaskOptions, axis: str | None) -> tuple[Any, list[tuple[str, Any]]]:
    recording = _load(path, options)
    fits = fit_recording(
        recording,
        options.model,
        axes=None if axis is None else [axis],
        tau_min=options.tau_min,
        tau_max=options.tau_max,
        flicker_d=options.flicker_d,
        estimator=options.estimator,
        iterations=options.iterations,
    )
    return recording, list(fits.items())


def fit_task(path: str, options: TaskOptions, axis: str | None = None) -> list[BatchRow]:
    """``carousel-theory fit``: GLS on the octave Allan variance, one row per axis in field units."""
    recording, fits = _fitted_axes(path, options, axis)
    return [
        BatchRow(path=path, task="fit", axis=name, **_recording_fields(recording), **_fit_fields(fit))
        for name, fit in fits
    ]


def _design_fields(models: list[NoiseModel], sample_rate: float, options: TaskOptions) -> dict[str, Any]:
    """The recommended scheme and its heading error at the longest duration (``carousel-theory design``)."""
    schemes = (
        [parse_scheme(text, sample_rate) for text in options.schemes]
        if options.schemes
        else default_schemes(sample_rate)
    )
    settings = DesignSettings(noise=models, sample_rate=sample_rate, latitude=float(options.latitude or 0.0))
    results = [
        result for scheme in schemes for result in evaluate_scheme(scheme, options.design_durations, settings)
    ]
    best_label = recommended(results)
    longest = max(options.design_durations)
    best = next(r for r in results if r.scheme == best_label and r.duration == longest)
    return {
        "design_scheme": best.scheme,
        "design_duration_s": float(best.duration),
        "design_heading_sigma_deg": float(best.heading_sigma_deg),
        "design_heading_rms_deg": math.nan if best.heading_rms_deg is None else float(best.heading_rms_deg),
    }


def design_task(path: str, options: TaskOptions, axis: str | None = None) -> list[BatchRow]:
    """``carousel-theory design`` on a fitted recording: each axis's fit (as ``fit``) and, on every row,
    the scheme with the smallest heading error for the first two axes as the horizontal gyros."""
    if axis is not None:
        raise ValueError(f"axis={axis!r}: design needs the two horizontal gyros together, not one axis")
    recording, fits = _fitted_axes(path, options, None)
    if len(fits) < 2:
        raise ValueError(
            f"{path}: design needs two gyro axes (the horizontal pair); found {[n for n, _ in fits]}"
        )
    shared = _design_fields([fits[0][1].model, fits[1][1].model], recording.sample_rate, options)
    return [
        BatchRow(
            path=path, task="design", axis=name, **_recording_fields(recording), **_fit_fields(fit), **shared
        )
        for name, fit in fits
    ]


def _relative_root_error(variance: float, error: float) -> float:
    """Relative standard error of √v by the delta method: SE(√v)/√v = SE(v) / (2v)."""
    return error / (2.0 * variance) if variance > 0 else math.nan


def _loop_axis_fields(model: dict[str, Any], sample_rate: float, length: int) -> dict[str, Any]:
    """Field-unit parameters of one axis of the loop's model (long-run white variance, RRW, bias); the
    bias instability is that model's Allan minimum / 0.664, without a standard error."""
    errors = model.get("standard_errors", {})
    white = float(model["long_run_white_variance_rad2_s2"])
    rrw = float(model["rrw_variance_rad2_s2"])
    noise = NoiseModel(sample_rate, bias=float(model["bias_rad_s"]), white_variance=white, rrw_variance=rrw)
    arw = noise.angle_random_walk_deg_per_sqrt_hour()
    rrw_field = noise.rate_random_walk_deg_per_hour_per_sqrt_hour()
    return {
        "bias_deg_per_h": float(noise.bias_deg_per_hour()),
        "angle_random_walk_deg_per_sqrt_h": float(arw),
        "angle_random_walk_deg_per_sqrt_h_se": float(
            arw * _relative_root_error(white, float(errors.get("long_run_white_variance", math.nan)))
        ),
        "rate_random_walk_deg_per_h_per_sqrt_h": float(rrw_field),
        "rate_random_walk_deg_per_h_per_sqrt_h_se": float(
            rrw_field * _relative_root_error(rrw, float(errors.get("rrw_variance", math.nan)))
        ),
        "bias_instability_deg_per_h": float(rad_per_s_to_deg_per_h(noise.bias_instability(length))),
    }


def loop_task(path: str, options: TaskOptions, axis: str | None = None) -> list[BatchRow]:
    """``carousel-theory loop``: the closed loop on the whole recording (its carouselled bins need the
    axes together, so it is never split); one row per analysed axis with the extended model's
    parameters, the effects found and the misfit before/after (the same on every row of the recording)."""
    if axis is not None:
        raise ValueError(f"axis={axis!r}: the loop runs on a whole recording, not on one axis")
    recording = _load(path, options, irregular="keep")
    result = run_loop(
        recording,
        samples_per_revolution=options.samples_per_revolution,
        axes=options.loop_axes,
        alpha=options.alpha,
    )
    shared = {
        **_recording_fields(recording),
        "effects": ";".join(result.effects),
        "misfit_metric": str(result.metric),
        "misfit_before": float(result.error_before),
        "misfit_after": float(result.error_after),
    }
    return [
        BatchRow(
            path=path,
            task="loop",
            axis=name,
            **shared,
            **_loop_axis_fields(result.model_after[name], recording.sample_rate, len(recording)),
        )
        for name in result.axes
    ]


#: Task name → adapter.
TASKS: dict[str, Callable[[str, TaskOptions, str | None], list[BatchRow]]] = {
    "allan": allan_task,
    "fit": fit_task,
    "loop": loop_task,
    "design": design_task,
}
#: Tasks that may run as one task per axis (``--per-axis``) on long records.
PER_AXIS_TASKS = frozenset({"allan", "fit"})


def check_options(task: str, options: TaskOptions) -> None:
    """Refuse options the analyses would refuse on every file, once, before the fleet starts."""
    if task not in TASKS:
        raise ValueError(f"task={task!r}: must be one of {sorted(TASKS)}")
    if options.estimator not in ESTIMATORS:
        raise ValueError(f"estimator={options.estimator!r}: must be one of {ESTIMATORS}")
    unknown = [name for name in options.model if name not in COMPONENTS]
    if unknown or not options.model:
        raise ValueError(f"model={options.model!r}: must be names from {COMPONENTS}")
    if options.iterations < 1:
        raise ValueError(f"iterations={options.iterations!r}: must be >= 1")
    if not 0 < options.alpha < 0.5:
        raise ValueError(f"alpha={options.alpha!r}: must be in (0, 0.5)")
    if task == "design":
        _check_design_options(options)
    if options.samples_per_revolution < 3:
        raise ValueError(f"samples_per_revolution={options.samples_per_revolution!r}: must be >= 3")


def _check_design_options(options: TaskOptions) -> None:
    if options.latitude is None:
        raise ValueError("latitude=None: the design task needs --latitude DEG")
    check_latitude(options.latitude)
    if not options.design_durations or any(
        not (d > 0 and math.isfinite(d)) for d in options.design_durations
    ):
        raise ValueError(f"design_durations={options.design_durations!r}: must be positive, finite seconds")
    for text in options.schemes:
        parse_scheme(text, options.sample_rate or 100.0)
