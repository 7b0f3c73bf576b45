"""``carousel-theory predict``: bias prediction for a recording (SJ 2012 §IV), or the batch test of
SJ 2012 Table I (simulated, or on measured recordings with ``--data``).

The analysis lives in :mod:`carousel_theory.bias_prediction_study`; this module parses, calls and
prints."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from carousel_theory._validation import check_fractional_order, check_positive_integer, check_positive_real
from carousel_theory.cli._files import write_or_compare
from carousel_theory.cli._recording_options import add_reader_options
from carousel_theory.data import MAX_VALUES
from carousel_theory.output_files import atomic_output, plan_outputs, write_text_atomic


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
    parser.add_argument("data", nargs="?", type=Path, help="a recording (CSV or NPZ) to predict")
    parser.add_argument("--axis", default=None, help="gyro column (default: the first in the file)")
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
    parser.add_argument("--output", type=Path, help="write the forecast here (.csv or .json)")
    parser.add_argument("--table1", action="store_true", help="run the batch test of SJ 2012 Table I")
    parser.add_argument("--runs", type=int, default=1000, help="simulated runs for --table1 (default 1000)")
    parser.add_argument("--seed", type=int, default=2012, help="seed of the simulated runs (default 2012)")
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
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    if args.table1:
        if args.data is not None:
            raise ValueError(
                f"DATA={str(args.data)!r}: not used with --table1 (use --data DIR for measured data)"
            )
        if args.time_unit is not None or args.max_values != MAX_VALUES:
            raise ValueError("--time-unit, --max-values: apply to DATA, not to --table1")
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
    if args.output is not None and args.output.suffix.lower() not in (".csv", ".json"):
        raise ValueError(f"--output={str(args.output)!r}: must end in .csv or .json")
    return calibration_length, horizon


def _run_recording(args: argparse.Namespace) -> int:
    from carousel_theory.bias_prediction_study import forecast_recording
    from carousel_theory.data import load_recording

    calibration_length, horizon = _check_recording_options(args)
    plan_outputs([(args.output, "file")], inputs=[args.data])
    recording = load_recording(args.data, time_unit=args.time_unit, max_values=args.max_values)
    axis = args.axis or next(iter(recording.rates))
    if axis not in recording.rates:
        raise ValueError(f"--axis={axis!r}: not in the recording (have {sorted(recording.rates)})")
    rates = recording.rates[axis]
    if args.start + calibration_length > rates.shape[0]:
        raise ValueError(
            f"--calibration={calibration_length!r}: the recording has only {rates.shape[0] - args.start} "
            f"samples after --start={args.start}"
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
    rows = _forecast_columns(result, recording.time[args.start], 1.0 / recording.sample_rate)
    _print_forecast(result, rows, f"{recording.source} [{axis}]")
    if args.output is not None:
        _write_forecast(args.output, rows, result.model, axis, str(recording.source))
        print(f"wrote {args.output}")
    return 0


def _forecast_columns(result, start_time: float, sample_interval: float) -> dict[str, np.ndarray]:
    horizon = result.measured.shape[0]
    indices = np.arange(
        result.start + result.calibration_length, result.start + result.calibration_length + horizon
    )
    low, high = result.kalman.interval(2.0)
    return {
        "index": indices,
        "time_s": start_time + (indices - result.start) * sample_interval,
        "kf_prediction": result.kalman.mean,
        "kf_sigma": np.sqrt(result.kalman.observation_variance),
        "kf_lower_2sigma": low,
        "kf_upper_2sigma": high,
        "ma_prediction": result.moving_average,
        "cm_prediction": np.full(horizon, result.calibration_mean),
        "measured": result.measured,
    }


def _print_forecast(result, rows: dict[str, np.ndarray], name: str) -> None:
    model = result.model
    note = "REML estimate from the calibration segment" if result.variances_estimated else "given"
    if result.variances_estimated and result.estimated_d:
        note = "d, σ_w², σ_v² by REML from the calibration segment"
    last = result.start + result.calibration_length - 1
    print(
        f"{name}: calibration {result.start}..{last}, horizon {result.measured.shape[0]}; "
        f"d = {model.d}, σ_w² = {model.driving_variance:.4g}, σ_v² = {model.white_variance:.4g} ({note}); "
        f"bias prior {model.bias_prior}"
    )
    print(
        f"KF forecast {result.kalman.mean[0]:.6g} → {result.kalman.mean[-1]:.6g} "
        f"(±2σ at the end {2 * rows['kf_sigma'][-1]:.3g}); "
        f"calibration mean {result.calibration_mean:.6g}"
    )
    errors = result.errors()
    if errors is not None:
        for method, (integrated, root_sum) in errors.items():
            print(f"  {method}: IE {integrated:.6g}, RSSE {root_sum:.6g}")


#: Rows of forecast CSV formatted at a time.
_CSV_CHUNK = 65_536


def _column_values(values: np.ndarray) -> list:
    """The column as Python floats, None where it is not finite (one pass, no per-element NumPy)."""
    result = np.asarray(values, dtype=np.float64).tolist()
    for index in np.flatnonzero(~np.isfinite(values)).tolist():
        result[index] = None
    return result


def _column_text(key: str, values: np.ndarray) -> list[str]:
    """CSV cells: the index as an integer, floats by repr (exact round trip), empty when not finite."""
    as_text = (lambda value: str(int(value))) if key == "index" else repr
    return ["" if value is None else as_text(value) for value in _column_values(values)]


def _write_forecast(path: Path, rows: dict, model, axis: str, source: str) -> None:
    suffix = path.suffix.lower()
    if suffix == ".json":
        payload = {
            "source": source,
            "axis": axis,
            "model": {
                "d": model.d,
                "driving_variance": model.driving_variance,
                "white_variance": model.white_variance,
                "bias_prior": model.bias_prior,
            },
            "columns": {key: _column_values(values) for key, values in rows.items()},
        }
        write_text_atomic(path, json.dumps(payload, indent=1) + "\n")
    elif suffix == ".csv":
        length = len(next(iter(rows.values())))
        with atomic_output(path) as temporary, temporary.open("w", encoding="utf-8", newline="") as handle:
            handle.write(",".join(rows) + "\n")
            for start in range(0, length, _CSV_CHUNK):  # in chunks: the text of 10⁶ rows never all in memory
                columns = [
                    _column_text(key, values[start : start + _CSV_CHUNK]) for key, values in rows.items()
                ]
                handle.write("".join(",".join(cells) + "\n" for cells in zip(*columns, strict=True)))
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
    table = _table1(args)
    result = table.as_dict()
    if args.json:
        print(json.dumps(result, indent=1, sort_keys=True))
    else:
        _print_table(result)
    if args.markdown is not None:
        same = write_or_compare(args.markdown, table1_markdown(table, _table1_command(args)), args.check)
        if args.check:
            return 0 if same else 1
    return 0


def _print_table(result: dict) -> None:
    from carousel_theory.bias_prediction_study import ROW_NAMES

    blocks = [("", result)] if result["settings"]["kind"] == "simulated" else list(result["axes"].items())
    for name, entry in blocks:
        if name:
            print(
                f"[{name}] {entry['sections']} sections, σ_w² = {entry['driving_variance']:.4g}, "
                f"σ_v² = {entry['white_variance']:.4g}"
            )
        print(f"{'':10s} " + " ".join(f"{m + ' ours':>11s} {m + ' paper':>11s}" for m in ("KF", "MA", "CM")))
        for row, row_name in ROW_NAMES.items():
            cells = " ".join(
                f"{entry[m][row]:11.4g} {entry[m]['paper'][row]:11.4g}" for m in ("KF", "MA", "CM")
            )
            print(f"{row_name:10s} {cells}")
