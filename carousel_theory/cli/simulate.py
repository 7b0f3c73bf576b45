"""``carousel-theory simulate``: a seeded synthetic recording, declared model plus undeclared effects."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from carousel_theory.cli._arguments import seed
from carousel_theory.effects import CATALOGUE
from carousel_theory.output_files import atomic_output, plan_outputs
from carousel_theory.simulate import (
    MAX_SIMULATED_SAMPLES,
    OUTSIDE_CATALOGUE,
    Datasheet,
    parse_injection,
    samples_for_duration,
    simulate_recording,
    write_recording,
)


def register(subparsers: argparse._SubParsersAction) -> None:
    names = sorted(set(CATALOGUE) - {"none"}) + sorted(OUTSIDE_CATALOGUE)
    parser = subparsers.add_parser(
        "simulate",
        help="write a seeded synthetic recording: bias + white + rate random walk (+ 1/f) + effects",
        description=(
            "Write a recording (CSV or NPZ by the extension of OUT; columns t, the axes, temp, and phi with "
            "--samples-per-revolution) from a declared noise model plus any set of undeclared effects. "
            f"Effects: {', '.join(names)}; give them as NAME or NAME:key=value,key=value."
        ),
    )
    parser.add_argument("out", type=Path, metavar="OUT", help="output file (.csv or .npz)")
    parser.add_argument("--seed", type=seed, required=True, help="seed of numpy.random.default_rng")
    parser.add_argument("--duration", type=float, default=600.0, help="seconds (default 600)")
    parser.add_argument("--sample-rate", type=float, default=100.0, help="Hz (default 100)")
    parser.add_argument("--bias", type=float, default=0.0, help="constant bias, rad/s")
    parser.add_argument(
        "--white-variance", type=float, help="per-sample white variance, (rad/s)² (default 3.6e-5)"
    )
    parser.add_argument(
        "--rrw-variance", type=float, help="per-sample RRW increment variance, (rad/s)² (default 1e-11)"
    )
    parser.add_argument(
        "--flicker-variance",
        type=float,
        help="1/f driving variance, (rad/s)² (TIM eq. (3), d = 1/2; default 0)",
    )
    _add_datasheet_options(parser)
    parser.add_argument("--axes", default="wx,wy", help="comma-separated axis names (default wx,wy)")
    parser.add_argument("--effect", action="append", default=[], metavar="NAME[:k=v,...]", help="repeatable")
    parser.add_argument("--no-temperature", action="store_true", help="no temperature column")
    parser.add_argument("--samples-per-revolution", type=int, help="add a phi column of a uniform rotation")
    parser.add_argument(
        "--max-samples",
        type=int,
        default=MAX_SIMULATED_SAMPLES,
        help=f"refuse a recording of more samples per axis (default {MAX_SIMULATED_SAMPLES:.0e})",
    )
    parser.set_defaults(handler=run)


#: Datasheet option → (the per-sample option it replaces, its default when no datasheet figure is given).
_DATASHEET_REPLACES = {
    "arw": ("white_variance", 3.6e-5),
    "rrw": ("rrw_variance", 1e-11),
    "bias_instability": ("flicker_variance", 0.0),
}


def _add_datasheet_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group(
        "datasheet figures (IEEE Std 952 units; converted to per-sample variances at --sample-rate; when "
        "any is given, a term given neither way is absent)"
    )
    group.add_argument(
        "--arw", type=float, metavar="°/√h", help="angle random walk (replaces --white-variance)"
    )
    group.add_argument(
        "--bias-instability",
        type=float,
        metavar="°/h",
        help="bias instability, 1/f (replaces --flicker-variance)",
    )
    group.add_argument(
        "--rrw", type=float, metavar="°/h/√h", help="rate random walk (replaces --rrw-variance)"
    )
    group.add_argument(
        "--quantization", type=float, default=0.0, metavar="Q", help="angle quantization (default 0)"
    )
    group.add_argument(
        "--quantization-unit",
        choices=("urad", "arcsec"),
        default="urad",
        help="unit of --quantization (µrad)",
    )


def _noise_variances(args: argparse.Namespace) -> dict[str, float]:
    """Per-sample variances and Q (rad) from the per-sample options or the datasheet figures (not both)."""
    datasheet_given = any(getattr(args, key) is not None for key in _DATASHEET_REPLACES)
    for key, (replaced, _) in _DATASHEET_REPLACES.items():
        if getattr(args, key) is not None and getattr(args, replaced) is not None:
            raise ValueError(
                f"--{key.replace('_', '-')}={getattr(args, key)!r}: give it or "
                f"--{replaced.replace('_', '-')}={getattr(args, replaced)!r}, not both"
            )
    model = Datasheet(
        angle_random_walk=args.arw or 0.0,
        bias_instability=args.bias_instability or 0.0,
        rate_random_walk=args.rrw or 0.0,
        quantization=args.quantization,
        quantization_unit=args.quantization_unit,
    ).noise_model(args.sample_rate)
    variances = {}
    for replaced, default in _DATASHEET_REPLACES.values():
        given = getattr(args, replaced)
        if given is not None:
            variances[replaced] = given
        else:
            variances[replaced] = getattr(model, replaced) if datasheet_given else default
    return {**variances, "quantization": model.quantization}


#: The extensions a recording is written in (``write_recording`` chooses the format by them).
RECORDING_SUFFIXES = (".csv", ".npz")


def run(args: argparse.Namespace) -> int:
    if args.out.suffix.lower() not in RECORDING_SUFFIXES:
        raise ValueError(f"OUT={str(args.out)!r}: must end in .csv or .npz (the format is chosen by it)")
    plan_outputs([(args.out, "file")])
    axes = tuple(a.strip() for a in args.axes.split(",") if a.strip())
    if not axes:
        raise ValueError(f"--axes={args.axes!r}: must name at least one axis, e.g. wx,wy")
    samples = samples_for_duration(
        args.duration, args.sample_rate, columns=len(axes) + 2, max_samples=args.max_samples
    )
    effects = [parse_injection(text) for text in args.effect]
    variances = _noise_variances(args)
    recording = simulate_recording(
        samples,
        args.sample_rate,
        rng=np.random.default_rng(args.seed),
        bias=args.bias,
        **variances,
        axes=axes,
        effects=effects,
        temperature=None if args.no_temperature else "auto",
        samples_per_revolution=args.samples_per_revolution,
        max_samples=args.max_samples,
    )
    with atomic_output(args.out) as temporary:  # whole or not at all: an old file survives a failure
        write_recording(recording, temporary)
    described = ", ".join(args.effect) or "none"
    print(f"wrote {args.out}: {samples} samples, axes {', '.join(axes)}, effects {described}")
    print(
        "per-sample model: "
        + ", ".join(
            f"{key} {value:.6g} {'rad' if key == 'quantization' else '(rad/s)²'}"
            for key, value in variances.items()
        )
    )
    return 0
