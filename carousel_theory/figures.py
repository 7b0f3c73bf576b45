"""The simulation figures of the two papers, regenerated with the exact theory drawn over a seeded
Monte Carlo.

=========================  ==================================================================
file                       what it shows
=========================  ==================================================================
``tim2014_fig2.png``       TIM 2014 Fig. 2: the entries of Fᵀ1, Fᵀs and Fᵀc (1/f noise, d = ½,
                           N = 300): the averaging coefficients grow, the carouselling ones stay
                           bounded (§III-D).
``tim2014_fig3.png``       TIM 2014 Fig. 3: the sequence S_2048 of Algorithm 1 (§IV).
``tim2014_fig4.png``       TIM 2014 Fig. 4: variance of averaged and carouselled bins of rate
                           random walk, N = 200 (σ_q² = 1): Monte Carlo over the exact eq. (15)
                           and (17)–(18) forms.
``tim2014_fig5.png``       TIM 2014 Fig. 5: the same for 1/f noise, d = ½, σ_w² = 1.
``sj2012_fig2.png``        SJ 2012 Fig. 2: bias prediction on simulated ARFIMA(0, ½, 0) data plus a
                           constant bias — (a) Kalman filter with its ±2σ interval, (b) moving
                           average, each with the calibration mean.
=========================  ==================================================================

Randomness comes only from ``numpy.random.default_rng(seed)``; matplotlib (the ``plots`` extra) is
imported when a figure is drawn, with the non-interactive Agg backend.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory._validation import check_boolean, check_integer, check_positive_integer
from carousel_theory.evaluation_cost import check_budget, monte_carlo_cost
from carousel_theory.output_files import atomic_output
from carousel_theory.progress import progress

__all__ = [
    "DEFAULT_REALISATIONS",
    "DEFAULT_SEED",
    "FIGURES",
    "Figure",
    "flicker_coefficient_vectors",
    "monte_carlo_bin_variances",
    "write_figures",
]

#: TIM 2014 §V-A: "2 × 1000 mutually independent RRW realizations" — 1000 simulation cases.
DEFAULT_REALISATIONS = 1000
DEFAULT_SEED = 2014
#: Samples per bin of the simulations of TIM 2014 §V-A, §V-B.
SIMULATION_SAMPLES_PER_BIN = 200
#: Bins drawn in Figs. 4 and 5 (the papers do not state the count).
SIMULATION_BINS = 50
#: Realisations simulated at once (bounds the memory: 2 × 100 × 10⁴ float64 = 16 MB).
_CHUNK = 100
#: SJ 2012 §V: sections of 2400 samples, the first half calibrates; an arbitrary constant bias.
SJ2012_SECTION = 2400
SJ2012_BIAS = 3.0

_DPI = 120
#: Measured seconds per Monte Carlo realisation (2 × 200 × 50 samples) of the figures that simulate;
#: ``write_figures`` refuses a run whose estimate exceeds the evaluation budget unless forced.
_SECONDS_PER_REALISATION = {"tim2014_fig4": 2.5e-3, "tim2014_fig5": 1.8e-3}


@dataclass(frozen=True)
class Figure:
    """One regenerated figure: its file name, what it reproduces, and the function that draws it."""

    file_name: str
    source: str
    draw: Callable[..., Any]


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


# --- computations (no plotting) -----------------------------------------------------------------


def flicker_coefficient_vectors(d: float, N: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Fᵀ1, Fᵀs and Fᵀc of TIM 2014 §III-D for the N × N 1/f matrix F of eq. (3).

    F is unit lower triangular Toeplitz with F[t, i] = ψ_{t−i}; entry i of Fᵀw is Σ_{t≥i} w_t ψ_{t−i},
    the weight with which driving sample w_i enters the bin statistic wᵀf.
    """
    from carousel_theory.processes import fractional_coefficients
    from carousel_theory.weights import averaging_weights, carousel_weights

    N = check_positive_integer("N", N)
    psi = fractional_coefficients(d, N)
    F = np.zeros((N, N))
    for lag in range(N):
        F[np.arange(lag, N), np.arange(0, N - lag)] = psi[lag]
    s, c = carousel_weights(N)
    return F.T @ averaging_weights(N), F.T @ s, F.T @ c


def monte_carlo_bin_variances(
    process: str,
    realisations: int,
    *,
    rng: np.random.Generator,
    N: int = SIMULATION_SAMPLES_PER_BIN,
    bins: int = SIMULATION_BINS,
    d: float = 0.5,
    show_progress: bool | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Sample variances over ``realisations`` of the averaged (x gyro) and carouselled (x and y gyros)
    bin estimates, bins 1 … ``bins``, for ``process`` "rrw" (σ_q² = 1) or "flicker" (σ_w² = 1, order d).

    The processes have mean zero, so the variance estimate is the mean of squares (unbiased).
    """
    from carousel_theory.processes import sample_flicker, sample_rate_random_walk
    from carousel_theory.weights import carousel_weights

    if process not in ("rrw", "flicker"):
        raise ValueError(f"process={process!r}: must be 'rrw' or 'flicker'")
    realisations = check_positive_integer("realisations", realisations)
    N = check_positive_integer("N", N, minimum=3)
    bins = check_positive_integer("bins", bins)
    if not isinstance(rng, np.random.Generator):
        raise TypeError(
            f"rng={rng!r}: must be a numpy.random.Generator (e.g. numpy.random.default_rng(seed))"
        )
    s, c = carousel_weights(N)
    length = N * bins
    squares_averaged = np.zeros(bins)
    squares_carouselled = np.zeros(bins)
    sizes = [min(_CHUNK, realisations - start) for start in range(0, realisations, _CHUNK)]
    for size in progress(sizes, label=f"Monte Carlo ({process})", enabled=show_progress):
        if process == "rrw":
            x = sample_rate_random_walk(length, rng=rng, realisations=size)
            y = sample_rate_random_walk(length, rng=rng, realisations=size)
        else:
            x = sample_flicker(length, rng=rng, d=d, realisations=size)
            y = sample_flicker(length, rng=rng, d=d, realisations=size)
        x_bins, y_bins = x.reshape(size, bins, N), y.reshape(size, bins, N)
        averaged = x_bins.mean(axis=-1)
        carouselled = -(x_bins @ s) + y_bins @ c  # TIM 2014 eq. (6)
        squares_averaged += (averaged**2).sum(axis=0)
        squares_carouselled += (carouselled**2).sum(axis=0)
    return squares_averaged / realisations, squares_carouselled / realisations


# --- figures ------------------------------------------------------------------------------------


def _draw_tim2014_fig2(plt, **_: Any):
    averaged, sine, cosine = flicker_coefficient_vectors(0.5, 300)
    index = np.arange(1, 301)
    figure, axes = plt.subplots(figsize=(6.4, 4.0))
    axes.plot(index, averaged, color="black", label=r"$F^T\mathbf{1}$ (averaging)")
    axes.plot(index, sine, color="tab:blue", label=r"$F^T\mathbf{s}$ (carouseling, sine)")
    axes.plot(index, cosine, color="tab:orange", label=r"$F^T\mathbf{c}$ (carouseling, cosine)")
    axes.axhline(0, color="gray", linewidth=0.5)
    axes.set_xlabel("entry $i$ (driving-noise sample of the bin)")
    axes.set_ylabel("coefficient")
    axes.set_title("TIM 2014 Fig. 2: 1/f noise, $d = 1/2$, $N = 300$ (exact)")
    axes.legend()
    return figure


def _draw_tim2014_fig3(plt, **_: Any):
    from carousel_theory.graycode import deterministic_sequence

    sequence = deterministic_sequence(11)
    figure, axes = plt.subplots(figsize=(6.4, 4.0))
    axes.step(np.arange(1, sequence.size + 1), sequence, where="mid", color="black", linewidth=0.6)
    axes.set_xlim(1, sequence.size)
    axes.set_xlabel("sample")
    axes.set_ylabel("value")
    axes.set_title(r"TIM 2014 Fig. 3: the sequence $S_{2048}$ of Algorithm 1 (exact)")
    return figure


def _draw_simulation(plt, process: str, realisations: int, rng: np.random.Generator, show_progress):
    from carousel_theory.formulas import formula
    from carousel_theory.propagation import flicker_bin_variances

    N, bins = SIMULATION_SAMPLES_PER_BIN, SIMULATION_BINS
    k = np.arange(1, bins + 1)
    averaged, carouselled = monte_carlo_bin_variances(
        process, realisations, rng=rng, N=N, bins=bins, show_progress=show_progress
    )
    if process == "rrw":
        theory_averaged = formula("rrw_average_var").numeric(N=N, k=k)
        theory_carouselled = np.full(bins, formula("rrw_carousel_var").numeric(N=N))
        title = f"TIM 2014 Fig. 4: rate random walk, $N = {N}$, $\\sigma_q^2 = 1$"
        labels = ("exact (15)", "exact (17)–(18)")
    else:
        theory_averaged = flicker_bin_variances(0.5, N, bins, method="averaged")
        theory_carouselled = flicker_bin_variances(0.5, N, bins, method="carouselled")
        title = f"TIM 2014 Fig. 5: 1/f noise, $d = 1/2$, $N = {N}$, $\\sigma_w^2 = 1$"
        labels = ("exact", "exact")
    figure, axes = plt.subplots(figsize=(6.4, 4.0))
    # A mean of R squares of a zero-mean Gaussian of variance V has standard error V·√(2/R).
    relative_error = 2 * np.sqrt(2.0 / realisations)
    for theory, colour in ((theory_averaged, "0.85"), (theory_carouselled, "lightblue")):
        axes.fill_between(
            k, theory * (1 - relative_error), theory * (1 + relative_error), color=colour, linewidth=0
        )
    axes.plot(k, averaged, "o", markersize=3, color="0.55", label=f"averaged, Monte Carlo ({realisations})")
    axes.plot(k, theory_averaged, "-", color="black", label=f"averaged, {labels[0]}")
    axes.plot(
        k,
        carouselled,
        "s",
        markersize=3,
        color="tab:cyan",
        label=f"carouselled, Monte Carlo ({realisations})",
    )
    axes.plot(k, theory_carouselled, "-", color="tab:blue", label=f"carouselled, {labels[1]}")
    if process == "rrw":
        axes.set_yscale("log")
    else:
        axes.set_ylim(bottom=0)
    axes.set_xlabel("data bin $k$ (shaded: exact ± 2 standard errors of the Monte Carlo estimate)")
    axes.set_ylabel("variance of the bin estimate")
    axes.set_title(title)
    axes.legend(fontsize="small")
    return figure


def _draw_tim2014_fig4(plt, *, realisations: int, rng: np.random.Generator, show_progress=None, **_: Any):
    return _draw_simulation(plt, "rrw", realisations, rng, show_progress)


def _draw_tim2014_fig5(plt, *, realisations: int, rng: np.random.Generator, show_progress=None, **_: Any):
    return _draw_simulation(plt, "flicker", realisations, rng, show_progress)


def _draw_sj2012_fig2(plt, *, rng: np.random.Generator, **_: Any):
    from carousel_theory.prediction import (
        BiasModel,
        integrated_error,
        predict,
        root_sum_squared_error,
        simulate_sections,
    )

    model = BiasModel()  # d = 1/2, σ_w² = 1, no white noise (SJ 2012 §V-B)
    section = simulate_sections(1, SJ2012_SECTION, model, rng=rng, bias=SJ2012_BIAS)[0]
    n = SJ2012_SECTION // 2
    calibration, future = section[:n], section[n:]
    j = np.arange(-n + 1, SJ2012_SECTION - n + 1)  # j = 0: the last calibration sample (eq. (8))
    kalman = predict(calibration, n, "KF", model)
    moving = predict(calibration, n, "MA")
    mean = predict(calibration, n, "CM")
    low, high = kalman.interval(2.0)
    figure, panels = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True)
    for axes, forecast, name in (
        (panels[0], kalman.mean, "Kalman filter"),
        (panels[1], moving, "moving average"),
    ):
        axes.plot(j, section, color="0.6", linewidth=0.6, label="data")
        axes.plot(j[n:], forecast, color="black", label=f"predicted 1/f ({name})")
        axes.plot(j[n:], mean, "--", color="tab:blue", label="mean of calibration data")
        ie, rsse = integrated_error(future, forecast), root_sum_squared_error(future, forecast)
        axes.set_title(
            f"({'a' if axes is panels[0] else 'b'}) {name}: IE = {ie:.0f}, RSSE = {rsse:.0f}", fontsize=10
        )
        axes.set_ylabel("$y_j$ [unitless]")
    panels[0].plot(j[n:], low, ":", color="black", label=r"$\pm 2\sigma$")
    panels[0].plot(j[n:], high, ":", color="black")
    panels[1].set_xlabel("$j$")
    for axes in panels:
        axes.axvline(0.5, color="gray", linewidth=0.5)
        axes.legend(fontsize="x-small", loc="upper left")
    figure.suptitle(
        "SJ 2012 Fig. 2: simulated ARFIMA(0, 1/2, 0) data plus a constant bias\n"
        f"(first half calibrates; calibration-mean prediction: IE = {integrated_error(future, mean):.0f}, "
        f"RSSE = {root_sum_squared_error(future, mean):.0f})",
        fontsize=10,
    )
    figure.tight_layout()
    return figure


FIGURES: dict[str, Figure] = {
    "tim2014_fig2": Figure("tim2014_fig2.png", "TIM 2014 Fig. 2 (§III-D)", _draw_tim2014_fig2),
    "tim2014_fig3": Figure("tim2014_fig3.png", "TIM 2014 Fig. 3 (§IV, Algorithm 1)", _draw_tim2014_fig3),
    "tim2014_fig4": Figure("tim2014_fig4.png", "TIM 2014 Fig. 4 (§V-A)", _draw_tim2014_fig4),
    "tim2014_fig5": Figure("tim2014_fig5.png", "TIM 2014 Fig. 5 (§V-B)", _draw_tim2014_fig5),
    "sj2012_fig2": Figure("sj2012_fig2.png", "SJ 2012 Fig. 2 (§V-B)", _draw_sj2012_fig2),
}


def write_figures(
    out: Path | str,
    *,
    realisations: int = DEFAULT_REALISATIONS,
    seed: int = DEFAULT_SEED,
    only: list[str] | None = None,
    show_progress: bool | None = None,
    force: bool = False,
) -> list[Path]:
    """Draw the figures and write them as PNG into ``out`` (created if needed); return the paths.

    Each figure gets its own generator ``default_rng([seed, index])`` (index = position in
    :data:`FIGURES`), so that a figure does not change when another is left out. A Monte Carlo whose
    estimated time exceeds the budget of :mod:`carousel_theory.evaluation_cost` is refused before
    anything is drawn, unless ``force=True``.
    """
    realisations = check_positive_integer("realisations", realisations)
    force = check_boolean("force", force)
    seed = check_integer("seed", seed)
    if seed < 0:
        raise ValueError(f"seed={seed!r}: must be an integer >= 0")
    names = list(FIGURES) if only is None else list(only)
    unknown = [name for name in names if name not in FIGURES]
    if unknown:
        raise ValueError(f"only={unknown!r}: unknown figure(s); known: {', '.join(FIGURES)}")
    per_realisation = sum(_SECONDS_PER_REALISATION.get(name, 0.0) for name in names)
    if per_realisation:
        what = f"figures {', '.join(n for n in names if n in _SECONDS_PER_REALISATION)}"
        check_budget(monte_carlo_cost(what, realisations, per_realisation), force=force)
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise ValueError(f"out={str(out)!r}: must be a directory (a file of that name exists)")
    out.mkdir(parents=True, exist_ok=True)
    plt = _pyplot()
    written = []
    for name in progress(names, label="figures", enabled=show_progress):
        entry = FIGURES[name]
        rng = np.random.default_rng([seed, list(FIGURES).index(name)])
        figure = entry.draw(plt, realisations=realisations, rng=rng, show_progress=show_progress)
        path = out / entry.file_name
        try:  # No software/date metadata, so that the PNG bytes depend only on the drawing.
            with atomic_output(path) as temporary:
                figure.savefig(temporary, dpi=_DPI, format="png", metadata={"Software": None})
        finally:
            plt.close(figure)
        written.append(path)
    return written
