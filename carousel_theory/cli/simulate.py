"""``carousel-theory simulate``: a seeded synthetic recording, declared model plus undeclared effects."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from carousel_theory.effects import CATALOGUE
from carousel_theory.simulate import (
    MAX_SIMULATED_SAMPLES,
    OUTSIDE_CATALOGUE,
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
    parser.add_argument("--seed", type=int, required=True, help="seed of numpy.random.default_rng")
    parser.add_argument("--duration", type=float, default=600.0, help="seconds (default 600)")
    parser.add_argument("--sample-rate", type=float, default=100.0, help="Hz (default 100)")
    parser.add_argument("--bias", type=float, default=0.0, help="constant bias, rad/s")
    parser.add_argument(
        "--white-variance", type=float, default=3.6e-5, help="per-sample white variance, (rad/s)²"
    )
    parser.add_argument("--rrw-variance", type=float, default=1e-11, help="per-sample RRW increment variance")
    parser.add_argument(
        "--flicker-variance", type=float, default=0.0, help="1/f driving variance (TIM eq. (3))"
    )
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


def run(args: argparse.Namespace) -> int:
    axes = tuple(a.strip() for a in args.axes.split(",") if a.strip())
    if not axes:
        raise ValueError(f"--axes={args.axes!r}: must name at least one axis, e.g. wx,wy")
    samples = samples_for_duration(
        args.duration, args.sample_rate, columns=len(axes) + 2, max_samples=args.max_samples
    )
    effects = [parse_injection(text) for text in args.effect]
    recording = simulate_recording(
        samples,
        args.sample_rate,
        rng=np.random.default_rng(args.seed),
        bias=args.bias,
        white_variance=args.white_variance,
        rrw_variance=args.rrw_variance,
        flicker_variance=args.flicker_variance,
        axes=axes,
        effects=effects,
        temperature=None if args.no_temperature else "auto",
        samples_per_revolution=args.samples_per_revolution,
        max_samples=args.max_samples,
    )
    write_recording(recording, args.out)
    described = ", ".join(args.effect) or "none"
    print(f"wrote {args.out}: {samples} samples, axes {', '.join(axes)}, effects {described}")
    return 0
