"""``carousel-theory design``: heading accuracy of rotation schemes for a gyro noise model; the best one."""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import asdict, replace
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory._validation import check_positive_real
from carousel_theory.cli._arguments import seed
from carousel_theory.design import (
    DesignSettings,
    SchemeResult,
    default_schemes,
    evaluate_scheme,
    noise_models_from_fit_json,
    recommended,
    record_length,
)
from carousel_theory.fitting import NoiseModel
from carousel_theory.heading import heading_monte_carlo
from carousel_theory.imperfections import Imperfections
from carousel_theory.json_output import json_document, strict_json
from carousel_theory.output_files import plan_outputs
from carousel_theory.progress import progress
from carousel_theory.rotation_schemes import parse_scheme

#: Imperfection options: flag → (field of Imperfections, help).
_IMPERFECTIONS = {
    "--angle-noise": ("angle_noise", "encoder white noise, rad (standard deviation per sample)"),
    "--angle-bias": ("angle_bias", "encoder offset, rad"),
    "--angle-quantization": ("angle_quantization", "encoder step, rad"),
    "--rate-wobble": (
        "rate_wobble",
        "relative amplitude a of a periodic rate wobble φ̇ = ω(1 + a cos(hφ + ϕ))",
    ),
    "--wobble-harmonic": ("wobble_harmonic", "h, wobble cycles per turn (default 1)"),
    "--wobble-phase": ("wobble_phase", "ϕ, wobble phase, rad"),
    "--rate-noise": ("rate_noise", "random walk of an unmeasured angle, rad per sample (with --open-loop)"),
    "--timing-jitter": ("timing_jitter", "sampling-time jitter, s (with --open-loop)"),
    "--scale-factor-x": ("scale_factor_x", "scale-factor error of the x gyro (relative)"),
    "--scale-factor-y": ("scale_factor_y", "scale-factor error of the y gyro (relative)"),
    "--misalignment": ("misalignment_x", "tilt of the x gyro toward the rotation axis, rad"),
    "--misalignment-y": ("misalignment_y", "tilt of the y gyro toward the rotation axis, rad"),
}


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "design",
        help="heading accuracy of rotation schemes (static, carousel, indexing) for a gyro, and the best one",
        description=(
            "For a noise model (per-sample variances, or --noise FILE.json from `fit --json`), a latitude "
            "and record durations, report for each rotation scheme the exact variance of the Earth-rate "
            "estimate across the true Earth rate and the heading error (linearised σ and exact RMS), and "
            "recommend the "
            "scheme with the smallest error at the longest duration. Schemes: static, carousel:N=200 or "
            "carousel:period=2 (s a turn), indexing:positions=4,dwell=10,transition=1 (s), two-axis:N=200, "
            "profile:file=ANGLES.npy (measured angles, rad); "
            "none given: a built-in sweep of carousel periods and indexing dwells."
        ),
    )
    noise = parser.add_argument_group("noise model (per sample, (rad/s)²)")
    noise.add_argument(
        "--noise", type=Path, metavar="FILE.json", help="the JSON of `carousel-theory fit --json`"
    )
    noise.add_argument("--white", type=float, default=0.0, help="white-noise variance per sample")
    noise.add_argument(
        "--rrw", type=float, default=0.0, help="rate-random-walk increment variance per sample"
    )
    noise.add_argument(
        "--flicker", type=float, default=0.0, help="1/f driving variance σ_w² (TIM 2014 eq. (3))"
    )
    noise.add_argument("--flicker-d", type=float, default=0.5, help="1/f order 0 < d < 1 (default 0.5)")
    noise.add_argument(
        "--bias", type=float, default=0.0, help="turn-on bias standard deviation per gyro, rad/s"
    )
    noise.add_argument("--sample-rate", type=float, help="Hz (default: from --noise, else 100)")
    parser.add_argument("--latitude", type=float, required=True, metavar="DEG", help="site latitude, degrees")
    parser.add_argument("--heading", type=float, default=0.0, metavar="DEG", help="true heading, degrees")
    parser.add_argument(
        "--duration",
        type=float,
        action="append",
        required=True,
        metavar="S",
        help="record length, s (repeatable)",
    )
    parser.add_argument("--scheme", action="append", metavar="TEXT", help="a scheme to compare (repeatable)")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("--plot", type=Path, metavar="FILE.png", help="plot heading σ against duration")
    parser.add_argument("--monte-carlo", type=int, metavar="R", help="also R seeded atan2 draws per result")
    parser.add_argument("--seed", type=seed, default=0, help="seed of the Monte Carlo (default 0)")
    errors = parser.add_argument_group("imperfections")
    for flag, (_, text) in _IMPERFECTIONS.items():
        errors.add_argument(flag, type=int if flag == "--wobble-harmonic" else float, help=text)
    errors.add_argument(
        "--open-loop", action="store_true", help="demodulate at the nominal, not the measured, angle"
    )
    parser.set_defaults(handler=run)


def _check_variances(args: argparse.Namespace) -> None:
    """Refuse a negative or non-finite --white, --rrw or --flicker by name (0 leaves the term out)."""
    for option in ("white", "rrw", "flicker"):
        check_positive_real(f"--{option}", getattr(args, option), allow_zero=True)


def _settings(args: argparse.Namespace) -> DesignSettings:
    _check_variances(args)
    explicit = args.white > 0 or args.rrw > 0 or args.flicker > 0
    if args.noise is not None and explicit:
        raise ValueError("--noise: give either --noise FILE.json or --white/--rrw/--flicker, not both")
    if args.noise is not None:
        models, rate = noise_models_from_fit_json(args.noise)
        if args.sample_rate is not None and not math.isclose(args.sample_rate, rate):
            raise ValueError(
                f"--sample-rate={args.sample_rate!r}: differs from the {rate!r} Hz of {args.noise}"
            )
    elif explicit:
        rate = 100.0 if args.sample_rate is None else args.sample_rate
        flicker_d = args.flicker_d
        models = [
            NoiseModel(
                rate,
                white_variance=args.white,
                rrw_variance=args.rrw,
                flicker_variance=args.flicker,
                flicker_d=flicker_d,
            )
        ]
    else:
        raise ValueError(
            "noise model: give --noise FILE.json or at least one of --white, --rrw, --flicker (> 0)"
        )
    values = {name: getattr(args, flag[2:].replace("-", "_")) for flag, (name, _) in _IMPERFECTIONS.items()}
    imperfections = Imperfections(
        measured_angles=not args.open_loop,
        **{name: value for name, value in values.items() if value is not None},
    )
    return DesignSettings(models, rate, args.latitude, args.heading, args.bias, imperfections)


def _monte_carlo(
    result: SchemeResult, settings: DesignSettings, replicates: int, seed: int
) -> dict[str, float]:
    errors = heading_monte_carlo(
        result.rate_covariance,
        settings.latitude,
        rng=np.random.default_rng(seed),
        replicates=replicates,
        heading_deg=settings.heading,
        bias=result.rate_bias,
    )
    squares = errors**2
    rms = math.sqrt(float(squares.mean()))
    # standard error of the RMS by the delta method: SE(mean e²) / (2 RMS)
    standard_error = float(squares.std(ddof=1)) / math.sqrt(replicates) / (2 * rms)
    return {
        "monte_carlo_rms_deg": math.degrees(rms),
        "monte_carlo_rms_standard_error_deg": math.degrees(standard_error),
        "monte_carlo_replicates": replicates,
    }


def _print_table(results: list[SchemeResult], best: str) -> None:
    print(
        f"{'scheme':<48} {'T (s)':>8} {'rate var (rad/s)²':>18} {'σ_ψ lin (°)':>12} "
        f"{'RMS exact (°)':>13} {'bias (°)':>9}  dominant"
    )
    for result in results:
        exact = "—" if result.heading_rms_deg is None else f"{result.heading_rms_deg:.4g}"
        print(
            f"{result.scheme:<48} {result.duration:>8g} {result.rate_variance:>18.4g} "
            f"{result.heading_sigma_deg:>12.4g} {exact:>13} {result.heading_bias_deg:>9.3g}  "
            f"{result.dominant_process}"
        )
    print(f"recommended: {best}")


def _plot(path: Path, schemes: list[Any], durations: list[float], settings: DesignSettings) -> None:
    """Heading σ against record duration per scheme, one marker per scheme, the legend outside the axes.

    The heading error is an angle (°), so this plot has no rate unit to choose.
    """
    from carousel_theory.plots import MARKERS, OUTSIDE_RIGHT, pyplot, save_figure

    plt = pyplot()
    grid = (
        np.geomspace(min(durations), max(durations), 24)
        if len(durations) > 1
        else np.geomspace(durations[0] / 30, durations[0], 24)
    )
    figure, axes = plt.subplots(figsize=(9, 5), layout="constrained")
    quick = replace(settings, exact=False)
    for index, scheme in enumerate(schemes):
        points = []
        for duration in grid:
            try:
                points.append((duration, evaluate_scheme(scheme, [duration], quick)[0].heading_sigma_deg))
            except ValueError:
                continue  # shorter than one cycle of this scheme
        if points:
            x, y = zip(*points, strict=True)
            name = evaluate_scheme(scheme, [points[0][0]], quick)[0].scheme
            axes.loglog(x, y, marker=MARKERS[index % len(MARKERS)], ms=3.5, lw=1.1, label=name)
    axes.set_xlabel("record duration (s)")
    axes.set_ylabel("heading σ, linearised (°)")
    axes.set_title(f"Heading error of each rotation scheme at latitude {settings.latitude:g}°", fontsize=10)
    axes.grid(True, which="major", alpha=0.35)
    axes.grid(True, which="minor", alpha=0.12)
    axes.legend(fontsize=7, **OUTSIDE_RIGHT)
    save_figure(figure, path)


def _input_files(args: argparse.Namespace) -> list[Path]:
    """The files design reads: --noise and the angle files of profile schemes (``profile:file=…``)."""
    profiles = [text.split("file=", 1)[1].split(",")[0] for text in args.scheme or () if "file=" in text]
    return [Path(name) for name in profiles] + ([args.noise] if args.noise is not None else [])


def run(args: argparse.Namespace) -> int:
    plan_outputs([(args.plot, "file")], inputs=_input_files(args))
    settings = _settings(args)
    for duration in args.duration:
        if not duration > 0:
            raise ValueError(f"--duration={duration!r}: must be > 0 seconds")
    schemes = (
        [parse_scheme(text, settings.sample_rate) for text in args.scheme]
        if args.scheme
        else default_schemes(settings.sample_rate)
    )
    if args.monte_carlo is not None and args.monte_carlo < 1:
        raise ValueError(f"--monte-carlo={args.monte_carlo!r}: must be an integer >= 1")
    results: list[SchemeResult] = []
    records: list[dict[str, Any]] = []
    for scheme in progress(schemes, label="schemes"):
        usable = [d for d in args.duration if _fits(scheme, d, settings.sample_rate)]
        if not usable:
            if args.scheme:
                evaluate_scheme(scheme, args.duration, settings)  # raises the error naming the duration
            continue
        for result in evaluate_scheme(scheme, usable, settings):
            results.append(result)
            record = asdict(result)
            record["rate_variance_by_process"]["units"] = dict.fromkeys(
                record["rate_variance_by_process"], "(rad/s)^2"
            )
            if args.monte_carlo:
                record.update(_monte_carlo(result, settings, args.monte_carlo, args.seed))
            records.append(
                {**record, "units": {key: unit for key, unit in DESIGN_UNITS.items() if key in record}}
            )
    best = recommended(results)
    if args.json:
        body = {
            "schemes": records,
            "recommended": best,
            "latitude": settings.latitude,
            "units": {"latitude": "deg"},
        }
        sys.stdout.write(strict_json(json_document("design", body)))
    else:
        _print_table(results, best)
    if args.plot is not None:
        _plot(args.plot, schemes, args.duration, settings)
    return 0


#: Units of a scheme record's members in ``design --json`` (the JSON convention of the README).
DESIGN_UNITS = {
    "duration": "s",
    "rate_variance": "(rad/s)^2",
    "rate_covariance": "(rad/s)^2",
    "rate_bias": "rad/s",
    "heading_sigma_deg": "deg",
    "heading_bias_deg": "deg",
    "heading_rms_deg": "deg",
    "monte_carlo_rms_deg": "deg",
    "monte_carlo_rms_standard_error_deg": "deg",
}


def _fits(scheme: Any, duration: float, sample_rate: float) -> bool:
    try:
        record_length(scheme, duration, sample_rate)
    except ValueError:
        return False
    return True
