"""``carousel-theory predict``: bias prediction for a recording (SJ 2012 §IV), or the batch test of
SJ 2012 Table I (simulated, or on measured recordings with ``--data``).

The analysis lives in :mod:`carousel_theory.bias_prediction_study`; this module parses, calls and
prints."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory._validation import check_fractional_order, check_positive_integer, check_positive_real
from carousel_theory.cli._arguments import seed
from carousel_theory.cli._files import write_or_compare
from carousel_theory.cli._output_units import OutputUnits, add_output_units_option, output_units
from carousel_theory.cli._recording_options import add_reader_options, reader_keywords, reader_options_given
from carousel_theory.json_output import json_document, strict_json
from carousel_theory.output_files import atomic_output, plan_outputs, write_text_atomic
from carousel_theory.signal_checks import check_noise_signal


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "predict",
        help="predict the gyro bias after a calibration (Kalman filter for 1/f noise, moving average, "
        "calibration mean), or run the batch test of SJ 2012 Table I",
        description="With DATA: calibrate on --calibration samples from --start and forecast the bias over "
        "--horizon samples (SJ 2012 §IV), writing prediction and ±2σ interval to --output (CSV or JSON). "
        "With --table1: the batch test of SJ 2012 Table I on simulated data (or on the recordings "
        "in --data, one column block per gyro axis).",
    )
    parser.add_argument(
        "data",
        nargs="?",
        type=Path,
        help="a recording to predict: text (.csv .txt .tsv), .npz, HDF5 (.h5) or MATLAB (.mat)",
    )
    parser.add_argument("--axis", default=None, help="gyro column (default: the first in the file)")
    parser.add_argument(
        "--sample-rate", type=float, help="samples per second when the file has no time column"
    )
    add_reader_options(parser)
    parser.add_argument(
        "--start", type=int, default=0, help="index of the first calibration sample (default 0)"
    )
    parser.add_argument("--calibration", type=int, default=1000, help="calibration samples (default 1000)")
    parser.add_argument(
        "--horizon", type=int, default=None, help="forecast samples (default: = --calibration)"
    )
    parser.add_argument(
        "--d", type=float, default=0.5, help="fractional order of the 1/f model (default 0.5)"
    )
    parser.add_argument(
        "--fit-d",
        action="store_true",
        help="estimate d together with σ_w² and σ_v² by REML on the calibration segment",
    )
    parser.add_argument("--driving-variance", type=float, default=None, help="σ_w² ((rad/s)² for data)")
    parser.add_argument("--white-variance", type=float, default=None, help="σ_v² ((rad/s)² for data)")
    parser.add_argument(
        "--prior",
        choices=("calibration-mean", "diffuse"),
        default="calibration-mean",
        help="bias state of the Kalman filter: fixed at the calibration mean (the paper's) or diffuse (GLS)",
    )
    parser.add_argument(
        "--output", type=Path, help="write the forecast here (.csv or .json; rates in --output-units)"
    )
    add_output_units_option(parser)
    _add_table1_options(parser)
    parser.set_defaults(handler=run)


def _add_table1_options(parser: argparse.ArgumentParser) -> None:
    """The options of ``--table1``, the batch test of SJ 2012 Table I."""
    parser.add_argument("--table1", action="store_true", help="run the batch test of SJ 2012 Table I")
    parser.add_argument("--runs", type=int, default=1000, help="simulated runs for --table1 (default 1000)")
    parser.add_argument("--seed", type=seed, default=2012, help="seed of the simulated runs (default 2012)")
    parser.add_argument("--json", action="store_true", help="print the --table1 result as JSON")
    parser.add_argument(
        "--data", dest="data_dir", type=Path, help="--table1 on the *.npz/*.csv recordings here"
    )
    parser.add_argument(
        "--average",
        type=int,
        default=1,
        help="--table1 --data: average blocks of this many samples first (default 1: the raw samples)",
    )
    parser.add_argument("--markdown", type=Path, help="--table1: also write a markdown report here")
    parser.add_argument(
        "--check", action="store_true", help="with --markdown: write nothing, fail on difference"
    )


def run(args: argparse.Namespace) -> int:
    if args.table1:
        if args.data is not None:
            raise ValueError(
                f"DATA={str(args.data)!r}: not used with --table1 (use --data DIR for measured data)"
            )
        given = reader_options_given(args) + (["--sample-rate"] if args.sample_rate is not None else [])
        if given:
            raise ValueError(f"{', '.join(given)}: apply to DATA, not to --table1")
        if args.output_units != "rad/s":
            raise ValueError(
                f"--output-units={args.output_units!r}: applies to a DATA forecast; Table I reports the "
                "simulated data without unit (as SJ 2012) and recordings in rad/s"
            )
        return _run_table1(args)
    if args.data is None:
        raise ValueError("DATA: a recording is required (or use --table1)")
    return _run_recording(args)


# --- one recording -------------------------------------------------------------------------------


def _check_recording_options(args: argparse.Namespace) -> tuple[int, int]:
    """Every option is checked before the file is read."""
    calibration_length = check_positive_integer("--calibration", args.calibration, minimum=2)
    horizon = check_positive_integer(
        "--horizon", args.horizon if args.horizon is not None else calibration_length
    )
    if not isinstance(args.start, int) or args.start < 0:
        raise ValueError(f"--start={args.start!r}: must be an integer >= 0")
    check_fractional_order("--d", args.d)
    if args.driving_variance is not None:
        check_positive_real("--driving-variance", args.driving_variance)
    if args.white_variance is not None:
        check_positive_real("--white-variance", args.white_variance, allow_zero=True)
    for option, given in (("--markdown", args.markdown is not None), ("--check", args.check)):
        if given:
            raise ValueError(f"{option}: only with --table1 (a single recording writes --output)")
    if args.output is not None and args.output.suffix.lower() not in (".csv", ".json"):
        raise ValueError(f"--output={str(args.output)!r}: must end in .csv or .json")
    return calibration_length, horizon


def _run_recording(args: argparse.Namespace) -> int:
    from carousel_theory.bias_prediction_study import forecast_recording
    from carousel_theory.data import load_recording

    calibration_length, horizon = _check_recording_options(args)
    plan_outputs([(args.output, "file")], inputs=[args.data])
    recording = load_recording(args.data, sample_rate=args.sample_rate, **reader_keywords(args))
    for note in recording.notes:  # what --resample did, on stderr: stdout may be JSON
        print(f"note: {note}", file=sys.stderr)
    axis = args.axis or next(iter(recording.rates))
    if axis not in recording.rates:
        raise ValueError(f"--axis={axis!r}: not in the recording (have {sorted(recording.rates)})")
    rates = recording.rates[axis]
    if args.start + calibration_length > rates.shape[0]:
        raise ValueError(
            f"--calibration={calibration_length!r}: the recording has only {rates.shape[0] - args.start} "
            f"samples after --start={args.start}"
        )
    segment = f"samples {args.start}…{args.start + calibration_length - 1}"
    check_noise_signal(
        rates[args.start : args.start + calibration_length], f"{args.data}: column {axis!r}, {segment}"
    )
    result = forecast_recording(
        rates,
        start=args.start,
        calibration_length=calibration_length,
        horizon=horizon,
        d=args.d,
        driving_variance=args.driving_variance,
        white_variance=args.white_variance,
        bias_prior=args.prior,
        estimate_d=args.fit_d,
    )
    output = output_units(args)
    rows = _forecast_columns(result, recording.time[args.start], 1.0 / recording.sample_rate, output)
    _print_forecast(result, rows, f"{recording.source} [{axis}]", output, 1.0 / recording.sample_rate)
    if args.output is not None:
        _write_forecast(args.output, rows, result, axis, str(recording.source), output)
        print(f"wrote {args.output} (rates in {output.rate_label})")
    return 0


#: Columns of the forecast that are rates (the others: index, a count, and time_s in s).
_RATE_COLUMNS = (
    "kf_prediction",
    "kf_sigma",
    "kf_lower_2sigma",
    "kf_upper_2sigma",
    "ma_prediction",
    "cm_prediction",
    "measured",
)


def _forecast_columns(
    result, start_time: float, sample_interval: float, output: OutputUnits
) -> dict[str, np.ndarray]:
    """The forecast table, rates converted to ``output``."""
    horizon = result.measured.shape[0]
    indices = np.arange(
        result.start + result.calibration_length, result.start + result.calibration_length + horizon
    )
    low, high = result.kalman.interval(2.0)
    rates = {
        "kf_prediction": result.kalman.mean,
        "kf_sigma": np.sqrt(result.kalman.observation_variance),
        "kf_lower_2sigma": low,
        "kf_upper_2sigma": high,
        "ma_prediction": result.moving_average,
        "cm_prediction": np.full(horizon, result.calibration_mean),
        "measured": result.measured,
    }
    return {
        "index": indices,
        "time_s": start_time + (indices - result.start) * sample_interval,
        **{key: np.asarray(output.rates(values)) for key, values in rates.items()},
    }


def _print_forecast(
    result, rows: dict[str, np.ndarray], name: str, output: OutputUnits, sample_interval: float
) -> None:
    """The model, the forecast and (when the horizon was recorded) IE and RSSE, every figure with its unit:
    IE = Σ e_t over the horizon (rate × samples; × Δt it is the accumulated angle), RSSE = √Σ e_t²."""
    model = result.model
    note = "REML estimate from the calibration segment" if result.variances_estimated else "given"
    if result.variances_estimated and result.estimated_d:
        note = "d, σ_w², σ_v² by REML from the calibration segment"
    last = result.start + result.calibration_length - 1
    variance = output.variance_label
    print(
        f"{name}: calibration {result.start}..{last}, horizon {result.measured.shape[0]}; d = {model.d}, "
        f"σ_w² = {output.variances(model.driving_variance):.4g} {variance}, "
        f"σ_v² = {output.variances(model.white_variance):.4g} {variance} ({note}); "
        f"bias prior {model.bias_prior}"
    )
    if result.at_bound:
        print(
            f"notice: REML ended at the search bound of {', '.join(result.at_bound)}: the calibration "
            f"segment ({result.calibration_length} samples) does not identify "
            f"{'it' if len(result.at_bound) == 1 else 'them'}; give --d, --driving-variance and "
            "--white-variance, or a longer --calibration"
        )
    rate = output.rate_label
    print(
        f"KF forecast {rows['kf_prediction'][0]:.6g} → {rows['kf_prediction'][-1]:.6g} {rate} "
        f"(±2σ at the end {2 * rows['kf_sigma'][-1]:.3g} {rate}); "
        f"calibration mean {output.rates(result.calibration_mean):.6g} {rate}"
    )
    errors = result.errors()
    if errors is not None:
        angle_unit = "rad" if output.rate == "rad/s" else "°"
        for method, (integrated, root_sum) in errors.items():
            angle = _angle(integrated, sample_interval, angle_unit)
            print(
                f"  {method}: IE {output.rates(integrated):.6g} {rate}·sample ({angle:.6g} {angle_unit} of "
                f"angle), RSSE {output.rates(root_sum):.6g} {rate}"
            )


def _angle(integrated_rad_per_s: float, sample_interval: float, unit: str) -> float:
    """The accumulated angle IE·Δt (rad) in ``unit`` ("rad" or "°")."""
    angle = integrated_rad_per_s * sample_interval
    return angle if unit == "rad" else angle * 180.0 / np.pi


#: Why ``measured`` holds nulls in the forecast JSON.
_NOT_RECORDED = "null where the horizon runs past the end of the recording: not measured"

#: Rows of forecast CSV formatted at a time by the text writer.
_CSV_CHUNK = 65_536


def _column_values(values: np.ndarray) -> list:
    """The column as Python floats, None where it is not finite (one pass, no per-element NumPy)."""
    result = np.asarray(values, dtype=np.float64).tolist()
    for index in np.flatnonzero(~np.isfinite(values)).tolist():
        result[index] = None
    return result


def _column_text(key: str, values: np.ndarray) -> list[str]:
    """CSV cells: the index as an integer, floats by repr (shortest exact round trip), empty when not
    finite; ``map`` over the C ``repr`` (no Python call per cell)."""
    if key == "index":
        return list(map(str, np.asarray(values, dtype=np.int64).tolist()))
    cells = list(map(repr, np.asarray(values, dtype=np.float64).tolist()))
    for index in np.flatnonzero(~np.isfinite(values)).tolist():
        cells[index] = ""
    return cells


def _write_csv_text(handle, rows: dict[str, np.ndarray]) -> None:
    """The forecast table as CSV text, in chunks (the text of 10⁶ rows is never all in memory)."""
    length = len(next(iter(rows.values())))
    for start in range(0, length, _CSV_CHUNK):
        columns = [_column_text(key, values[start : start + _CSV_CHUNK]) for key, values in rows.items()]
        handle.write("".join(map("{}\n".format, map(",".join, zip(*columns, strict=True)))))


def _arrow_column(arrow, key: str, values: np.ndarray):
    """One column as a pyarrow array built on the NumPy buffer, with a validity bitmap where a value is
    not finite (``pyarrow.array`` would import pandas, a third of a second, to look for its types)."""
    if key == "index":
        integers = np.ascontiguousarray(values, dtype=np.int64)
        return arrow.Array.from_buffers(arrow.int64(), integers.size, [None, arrow.py_buffer(integers)])
    floats = np.ascontiguousarray(values, dtype=np.float64)
    finite = np.isfinite(floats)
    if finite.all():
        return arrow.Array.from_buffers(
            arrow.float64(), floats.size, [None, arrow.py_buffer(floats)], null_count=0
        )
    validity = arrow.py_buffer(np.packbits(finite, bitorder="little"))
    return arrow.Array.from_buffers(
        arrow.float64(),
        floats.size,
        [validity, arrow.py_buffer(floats)],
        null_count=int(floats.size - finite.sum()),
    )


def _write_csv_arrow(handle, rows: dict[str, np.ndarray]) -> bool:
    """The forecast table through pyarrow's C++ CSV writer (the ``data`` extra), about 6× faster than
    :func:`_write_csv_text` at 10⁶ rows; False when pyarrow is not installed.

    Floats are written in their shortest exact round-trip form: the significant digits of ``repr``,
    though the exponent and integer spelling may differ (``0.00001`` for ``1e-05``, ``30`` for ``30.0``);
    the index as integers; a value that is not finite as an empty cell."""
    try:
        import pyarrow as arrow
        import pyarrow.csv as arrow_csv
    except ImportError:
        return False
    columns = {key: _arrow_column(arrow, key, values) for key, values in rows.items()}
    handle.flush()
    arrow_csv.write_csv(
        arrow.table(columns), handle.buffer, write_options=arrow_csv.WriteOptions(include_header=False)
    )
    return True


#: The JSON names of the REML estimates that can end at a search bound.
_BOUND_NAMES = {"d": "d", "σ_v²/σ_w²": "white_to_driving_variance_ratio"}


def _write_forecast(path: Path, rows: dict, result, axis: str, source: str, output: OutputUnits) -> None:
    model = result.model
    suffix = path.suffix.lower()
    if suffix == ".json":
        payload: dict[str, Any] = {
            "source": source,
            "axis": axis,
            "output_units": output.rate,
            "model": {
                "d": model.d,
                "driving_variance": model.driving_variance,
                "white_variance": model.white_variance,
                "bias_prior": model.bias_prior,
                "at_bound": [_BOUND_NAMES[name] for name in result.at_bound],
                "units": {"driving_variance": "(rad/s)^2", "white_variance": "(rad/s)^2"},
            },
            "columns": {
                **{key: _column_values(values) for key, values in rows.items()},
                "index": np.asarray(rows["index"], dtype=np.int64).tolist(),
                "units": {"time_s": "s", **dict.fromkeys(_RATE_COLUMNS, output.rate)},
            },
        }
        if not np.isfinite(rows["measured"]).all():
            payload["columns"]["measured_null_reason"] = _NOT_RECORDED
        write_text_atomic(path, strict_json(json_document("predict", payload)))
    elif suffix == ".csv":
        with atomic_output(path) as temporary, temporary.open("w", encoding="utf-8", newline="") as handle:
            handle.write(",".join(rows) + "\n")
            if not _write_csv_arrow(handle, rows):
                _write_csv_text(handle, rows)
    else:
        raise ValueError(f"--output={str(path)!r}: must end in .csv or .json")


# --- Table I -------------------------------------------------------------------------------------


def _table1(args: argparse.Namespace):
    from carousel_theory.bias_prediction_study import measured_table1, simulated_table1
    from carousel_theory.prediction import BiasModel

    n = check_positive_integer("--calibration", args.calibration, minimum=2)
    h = check_positive_integer("--horizon", args.horizon if args.horizon is not None else n)
    d = float(check_fractional_order("--d", args.d))
    if args.data_dir is not None:
        if not args.data_dir.is_dir():
            raise ValueError(f"--data={str(args.data_dir)!r}: must be a directory of recordings")
        average = check_positive_integer("--average", args.average)
        return measured_table1(args.data_dir, n, h, d=d, bias_prior=args.prior, average=average)
    runs = check_positive_integer("--runs", args.runs, minimum=2)
    seed = check_positive_integer("--seed", args.seed, minimum=0)
    driving = 1.0 if args.driving_variance is None else args.driving_variance
    white = 0.0 if args.white_variance is None else args.white_variance
    model = BiasModel(d=d, driving_variance=driving, white_variance=white, bias_prior=args.prior)
    return simulated_table1(runs, n, h, model, seed)


def _table1_command(args: argparse.Namespace) -> str:
    command = "carousel-theory predict --table1" + (
        f" --data {args.data_dir}" if args.data_dir is not None else f" --runs {args.runs} --seed {args.seed}"
    )
    if args.data_dir is not None and args.average != 1:
        command += f" --average {args.average}"
    if args.data_dir is None and args.driving_variance is not None:
        command += f" --driving-variance {args.driving_variance}"
    return command + f" --markdown {args.markdown}"


def _run_table1(args: argparse.Namespace) -> int:
    from carousel_theory.bias_prediction_study import table1_markdown

    if args.output is not None:
        raise ValueError("--output: not used with --table1 (use --json or --markdown)")
    if args.fit_d:
        raise ValueError("--fit-d: not used with --table1 (Table I is run at the given --d)")
    if args.check and args.markdown is None:
        raise ValueError("--check: needs --markdown FILE, the Table I report to compare with")
    if not args.check:
        plan_outputs([(args.markdown, "file")])
    table = _table1(args)
    result = table.as_dict()
    if args.json:
        sys.stdout.write(strict_json(json_document("predict-table1", _with_units(result))))
    else:
        _print_table(result)
    if args.markdown is not None:
        same = write_or_compare(args.markdown, table1_markdown(table, _table1_command(args)), args.check)
        if args.check:
            return 0 if same else 1
    return 0


#: Units of the measured Table I's own figures (the paper's columns are as SJ 2012 printed them).
_TABLE1_UNITS = {
    "mean_ie": "rad/s*sample",
    "std_ie": "rad/s*sample",
    "mean_rsse": "rad/s",
    "std_rsse": "rad/s",
}


def _with_units(result: dict) -> dict:
    """Table I with ``units`` maps on the measured recordings' figures; the simulated data have none (as in
    SJ 2012: "no units assumed for the simulated data")."""
    if result["settings"]["kind"] == "simulated":
        return result
    axes = {}
    for name, entry in result["axes"].items():
        methods = {
            method: {
                **entry[method],
                "units": {key: _TABLE1_UNITS[key] for key in entry[method] if key in _TABLE1_UNITS},
            }
            for method in ("KF", "MA", "CM")
        }
        units = {"driving_variance": "(rad/s)^2", "white_variance": "(rad/s)^2"}
        axes[name] = {**entry, **methods, "units": units}
    return {**result, "axes": axes}


def _print_table(result: dict) -> None:
    from carousel_theory.bias_prediction_study import ROW_NAMES

    simulated = result["settings"]["kind"] == "simulated"
    blocks = [("", result)] if simulated else list(result["axes"].items())
    print(
        "IE and RSSE of simulated data have no unit (as in SJ 2012)"
        if simulated
        else "ours: IE in rad/s·sample (× Δt: the angle in rad), RSSE in rad/s; "
        "paper: as SJ 2012 Table I prints them"
    )
    for name, entry in blocks:
        if name:
            print(
                f"[{name}] {entry['sections']} sections, σ_w² = {entry['driving_variance']:.4g} (rad/s)², "
                f"σ_v² = {entry['white_variance']:.4g} (rad/s)²"
            )
        print(f"{'':10s} " + " ".join(f"{m + ' ours':>11s} {m + ' paper':>11s}" for m in ("KF", "MA", "CM")))
        for row, row_name in ROW_NAMES.items():
            cells = " ".join(
                f"{entry[m][row]:11.4g} {entry[m]['paper'][row]:11.4g}" for m in ("KF", "MA", "CM")
            )
            print(f"{row_name:10s} {cells}")
