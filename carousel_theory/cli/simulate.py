"""``carousel-theory simulate``: a seeded synthetic recording, declared model plus undeclared effects."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from carousel_theory.effects import CATALOGUE
from carousel_theory.simulate import OUTSIDE_CATALOGUE, parse_injection, simulate_recording, write_recording


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
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    if args.duration <= 0 or args.sample_rate <= 0:
        raise ValueError(f"--duration={args.duration!r}, --sample-rate={args.sample_rate!r}: must be > 0")
    samples = round(args.duration * args.sample_rate)
    axes = tuple(a.strip() for a in args.axes.split(",") if a.strip())
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
    )
    write_recording(recording, args.out)
    described = ", ".join(args.effect) or "none"
    print(f"wrote {args.out}: {samples} samples, axes {', '.join(axes)}, effects {described}")
    return 0
