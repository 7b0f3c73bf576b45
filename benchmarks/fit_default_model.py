"""Which default ``fit`` model do real MEMS recordings not reject? χ²/dof of candidate models on the shared
recordings.

Usage: ``python benchmarks/fit_default_model.py [DATA_DIR] [--candidates NAME ...]``

Every candidate (components and a short-τ cut-off ``tau_min`` in s, none, every τ then τ ≥ 1 s for an
axis rejected there, or the fit command's default,
:func:`carousel_theory.fit_defaults.select_default_fit`) is fitted with
:func:`carousel_theory.fitting.fit_recording` to every gyro axis of every static recording under DATA_DIR
(default ``../shared/data``): the ADIS16405 runs (100 Hz, uniform) and the MPU6050 static run (bursty
timestamps, bin-averaged onto a uniform grid by :func:`carousel_theory.closed_loop.resample.uniform_resample`
as ``loop`` does). The hand-rotated MPU6050 recording is left out: it turns, so it is no noise recording.
Prints one row per candidate: χ²/dof per recording (the worst axis, with its p-value) and how many axes
reject the model at p < 0.01, and the number of terms held at zero.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from carousel_theory.closed_loop.resample import uniform_resample
from carousel_theory.data import Recording, load_recording
from carousel_theory.fit_defaults import select_default_fit
from carousel_theory.fitting import fit_recording

#: Name: (components, tau_min in s or None for every τ or -1 for the default range, fixed 1/f order d).
CANDIDATES: dict[str, tuple[tuple[str, ...], float | None, float | None]] = {
    "white,rrw": (("white", "rrw"), None, None),
    "white,rrw τ≥0.1": (("white", "rrw"), 0.1, None),
    "white,rrw τ≥1": (("white", "rrw"), 1.0, None),
    "white,rrw,flicker": (("white", "rrw", "flicker"), None, None),
    "white,rrw,flicker τ≥0.1": (("white", "rrw", "flicker"), 0.1, None),
    "white,rrw,flicker τ≥0.3": (("white", "rrw", "flicker"), 0.3, None),
    "white,rrw,flicker τ≥1": (("white", "rrw", "flicker"), 1.0, None),
    "white,rrw,flicker, every τ or τ≥1 if rejected": (("white", "rrw", "flicker"), -1.0, None),
    "default: first of the ladder not rejected": ((), -2.0, None),
    "ar,rrw,flicker": (("ar", "rrw", "flicker"), None, None),
    "ar,rrw": (("ar", "rrw"), None, None),
    "ar,rrw,flicker τ≥0.1": (("ar", "rrw", "flicker"), 0.1, None),
    "white,rrw,flicker,ar": (("white", "rrw", "flicker", "ar"), None, None),
    "white,rrw,flicker d=0.5": (("white", "rrw", "flicker"), None, 0.5),
    "white,rrw,flicker d=0.5 τ≥1": (("white", "rrw", "flicker"), 1.0, 0.5),
    "white,rrw,flicker d=0.5, every τ or τ≥1 if rejected": (("white", "rrw", "flicker"), -1.0, 0.5),
}


def recordings(directory: Path) -> list[Recording]:
    """The shared static recordings (uniform grids)."""
    found = [load_recording(path) for path in sorted(directory.glob("adis16405_static/*.npz"))]
    for path in sorted(directory.glob("mpu6050_static*/*.npz")):
        found.append(uniform_resample(load_recording(path, irregular="keep"))[0])
    return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data", nargs="?", type=Path, default=Path("../shared/data"))
    parser.add_argument("--candidates", nargs="*", default=list(CANDIDATES), choices=list(CANDIDATES))
    args = parser.parse_args()
    loaded = recordings(args.data)
    print(
        "| candidate | "
        + " | ".join(Path(r.source).stem for r in loaded)
        + " | axes rejected | at zero | s |"
    )
    print("|---|" + "---|" * (len(loaded) + 3))
    for name in args.candidates:
        components, tau_min, flicker_d = CANDIDATES[name]
        start, cells, rejected, at_zero, total = time.perf_counter(), [], 0, 0, 0
        for recording in loaded:
            try:
                if tau_min == -2.0:  # the default of the fit command
                    fits, _ = select_default_fit(recording, iterations=3)
                elif tau_min == -1.0:  # every τ, then τ ≥ 1 s for an axis rejected there
                    fits = fit_recording(recording, components, iterations=3, flicker_d=flicker_d)
                    rejected = [name for name, fit in fits.items() if fit.p_value < 0.01]
                    if rejected:
                        fits.update(
                            fit_recording(
                                recording,
                                components,
                                axes=rejected,
                                tau_min=1.0,
                                iterations=3,
                                flicker_d=flicker_d,
                            )
                        )
                else:
                    fits = fit_recording(
                        recording, components, tau_min=tau_min, iterations=3, flicker_d=flicker_d
                    )
            except ValueError as error:  # reported in the table, e.g. an AR order of 0
                cells.append(f"error: {str(error)[:60]}")
                continue
            worst = max(fits.values(), key=lambda fit: fit.chi_square / max(fit.degrees_of_freedom, 1))
            cells.append(
                " ".join(f"{f.chi_square / max(f.degrees_of_freedom, 1):.3g}" for f in fits.values())
                + f" (p≥{worst.p_value:.1g})"
            )
            rejected += sum(fit.p_value < 0.01 for fit in fits.values())
            at_zero += sum(len(fit.at_bound) for fit in fits.values())
            total += len(fits)
        seconds = time.perf_counter() - start
        print(
            f"| {name} | " + " | ".join(cells) + f" | {rejected}/{total} | {at_zero} | {seconds:.0f} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
