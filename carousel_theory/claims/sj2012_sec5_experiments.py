"""Claims of SJ 2012 §V (experiments): the metrics, the example runs of §V-B, every number of Table I
and the comparisons of §V-C.

Simulated numbers are decided against the exact population values of the Gaussian model
(:func:`carousel_theory.prediction.population_metrics`) with standard errors for 1000 runs; the
real-data numbers cannot be checked (the data are not public) — our ADIS16405 columns are in
``docs/sj2012_table1_adis16405.md``.
"""

from __future__ import annotations

import functools
import math
from dataclasses import astuple

import numpy as np

from carousel_theory.bias_prediction_study import PAPER_TABLE1_MEASURED, PAPER_TABLE1_SIMULATED
from carousel_theory.claim import Claim, Status, Verdict
from carousel_theory.claims._common import figure_1_not_public
from carousel_theory.prediction import (
    METHODS,
    BiasModel,
    error_moments,
    population_metrics,
    prediction_weights,
    sampling_standard_errors,
)
from carousel_theory.processes import fractional_coefficients

__all__ = ["CLAIMS"]

RUNS = 1000


CALIBRATION = 1000


HORIZON = 1000


#: Bound on |paper − population| in standard errors (the suite's Monte Carlo z).
Z = 4.5


#: SJ 2012 Table I as printed: (mean IE, IE std, mean RSSE, RSSE std) per method (one copy, in the library).
TABLE1_SIMULATED = {method: astuple(row) for method, row in PAPER_TABLE1_SIMULATED.items()}
TABLE1_REAL = {method: astuple(row) for method, row in PAPER_TABLE1_MEASURED.items()}


#: Half a unit of the last printed digit of each Table I entry (the printing's rounding).
ROUNDING_SIMULATED = {"KF": (0.5, 5, 0.5, 0.05), "MA": (0.5, 5, 0.5, 0.05), "CM": (0.5, 5, 0.5, 0.05)}


ROWS = ("mean_ie", "std_ie", "mean_rsse", "std_rsse")


ROW_NAMES = {"mean_ie": "mean IE", "std_ie": "IE std", "mean_rsse": "mean RSSE", "std_rsse": "RSSE std"}


#: §V-B example runs (2400 samples, first half calibrates): (IE, RSSE) per method.
EXAMPLE_SIMULATED = {"KF": (-201, 123), "MA": (535, 127), "CM": (-2910, 146)}


EXAMPLE_REAL = {"KF": (2.46, 0.410), "MA": (3.13, 0.424), "CM": (3.55, 0.415)}


@functools.lru_cache(maxsize=4)
def _table1_analysis(
    bias_prior: str = "calibration-mean", calibration: int = CALIBRATION, horizon: int = HORIZON
):
    """Population values and standard errors at σ_w = 1, and the σ_w fitted to the nine scale-carrying
    simulated numbers by weighted least squares (every statistic scales with σ_w)."""
    model = BiasModel(d=0.5, driving_variance=1.0, white_variance=0.0, bias_prior=bias_prior)
    populations = {m: population_metrics(calibration, horizon, m, model)[0].as_dict() for m in METHODS}
    errors = {m: sampling_standard_errors(calibration, horizon, m, model, RUNS).as_dict() for m in METHODS}
    numerator = denominator = 0.0
    for method in METHODS:
        for row, printed in zip(ROWS[1:], TABLE1_SIMULATED[method][1:], strict=True):
            a, b = populations[method][row], errors[method][row]
            numerator += printed * a / b**2
            denominator += a * a / b**2
    scale = numerator / denominator
    chi_square = sum(
        ((printed - scale * populations[m][row]) / (scale * errors[m][row])) ** 2
        for m in METHODS
        for row, printed in zip(ROWS, TABLE1_SIMULATED[m], strict=True)
    )
    return populations, errors, scale, 1.0 / math.sqrt(denominator), chi_square


def _table1_number_check(method: str, row: str):
    def check() -> Verdict:
        populations, errors, scale, _, _ = _table1_analysis()
        index = ROWS.index(row)
        printed = TABLE1_SIMULATED[method][index]
        expected = scale * populations[method][row]
        bound = Z * scale * errors[method][row] + ROUNDING_SIMULATED[method][index]
        status = Status.CONSISTENT if abs(printed - expected) <= bound else Status.REFUTED
        return Verdict(
            status,
            f"Population value at d = 1/2, σ_w = {scale:.3f} (fitted): {expected:.4g}; |{printed} "
            f"− {expected:.4g}| "
            f"= {abs(printed - expected):.3g} vs bound {bound:.3g} (4.5 SE for 1000 runs + rounding). "
            f"At σ_w = 1: {populations[method][row]:.4g}.",
        )

    return check


def _check_unit_driving_noise() -> Verdict:
    populations, errors, scale, scale_error, chi_square = _table1_analysis()
    worst = max(
        abs(TABLE1_SIMULATED[m][i] - populations[m][row]) / (errors[m][row] + 1e-300)
        for m in METHODS
        for i, row in enumerate(ROWS)
        if row != "mean_ie"
    )
    if worst > Z:
        return Verdict(
            Status.REFUTED,
            "With unit driving variance the population values (KF: IE std "
            f"{populations['KF']['std_ie']:.4g}, mean "
            f"RSSE {populations['KF']['mean_rsse']:.4g}) are {worst:.0f} SE from the table. All "
            "twelve simulated "
            f"numbers fit d = 1/2 with σ_w = {scale:.3f} ± {scale_error:.3f} (χ² = "
            f"{chi_square:.2f} on 11 dof).",
            corrected="Table I (simulated) corresponds to d = 1/2 and a driving-noise standard "
            f"deviation σ_w ≈ {scale:.2f}",
        )
    return Verdict(Status.CONSISTENT, f"within {worst:.2f} SE at unit driving variance")


def _check_rsse_definition() -> Verdict:
    populations, _, scale, _, _ = _table1_analysis()
    mean_square = scale**2 * population_metrics(CALIBRATION, HORIZON, "KF", BiasModel())[1]
    printed = TABLE1_SIMULATED["KF"][2]
    root = scale * populations["KF"]["mean_rsse"]
    if abs(printed - root) < abs(printed - mean_square):
        return Verdict(
            Status.ERRATUM,
            "Text: 'RSSE: the sum of the squares of the prediction errors'. Table I's KF mean "
            f"RSSE {printed} matches "
            f"E √Σe² = {root:.4g}, not E Σe² = {mean_square:.4g} (same fitted σ_w = {scale:.3f}).",
            corrected="RSSE = √(Σ_k e_k²), the root of the sum of squared prediction errors",
        )
    return Verdict(Status.FAILED, "the table does not match the root either")


def _generalised_least_squares_weights(calibration: int, horizon: int, d: float) -> np.ndarray:
    """The best linear unbiased predictor of y_{n+1..n+h} from y_1..y_n for y = b + f, b an unknown
    constant and f the process (3) from the first sample (no white noise), by dense GLS:
    M = Γ_fc Γ_cc⁻¹ + (1 − Γ_fc Γ_cc⁻¹ 1)(1ᵀ Γ_cc⁻¹ 1)⁻¹ 1ᵀ Γ_cc⁻¹, with Γ = Ψ Ψᵀ."""
    length = calibration + horizon
    psi = fractional_coefficients(d, length)
    lower = np.zeros((length, length))
    for row in range(length):
        lower[row, : row + 1] = psi[row::-1]
    covariance = lower @ lower.T
    past, future = covariance[:calibration, :calibration], covariance[calibration:, :calibration]
    ones = np.ones(calibration)
    solved_ones = np.linalg.solve(past, ones)
    simple = np.linalg.solve(past, future.T).T  # Γ_fc Γ_cc⁻¹
    return simple + np.outer(1 - simple @ ones, solved_ones / (ones @ solved_ones))


def _filter_population(bias_prior: str) -> dict[str, float]:
    model = BiasModel(bias_prior=bias_prior)
    return {m: population_metrics(CALIBRATION, HORIZON, m, model)[1] for m in METHODS}


#: The diffuse KF's weights and the dense GLS predictor's agree to rounding (measured about 5e-16; the
#: figure itself depends on the platform's BLAS, so the evidence states this bound).
_WEIGHTS_AGREE = 1e-12


def _check_kf_optimal() -> Verdict:
    gls = _generalised_least_squares_weights(60, 20, 0.5)
    diffuse_weights = prediction_weights(60, 20, "KF", BiasModel(bias_prior="diffuse"))
    gap = float(np.max(np.abs(gls - diffuse_weights)))
    plug_in, diffuse = _filter_population("calibration-mean"), _filter_population("diffuse")
    lowest_of_three = plug_in["KF"] < min(plug_in["MA"], plug_in["CM"])
    if gap > _WEIGHTS_AGREE or not lowest_of_three or not diffuse["KF"] < plug_in["KF"]:
        return Verdict(Status.FAILED, f"GLS gap {gap:.3g}; E RSSE² plug-in {plug_in}, diffuse {diffuse}")
    return Verdict(
        Status.QUALIFIED,
        "Exact E RSSE² at d = 1/2, σ_w = 1, 1000 + 1000 samples: the paper's KF (sample mean as the bias "
        "state) "
        + ", ".join(f"{m} {plug_in[m]:.5g}" for m in METHODS)
        + f": lowest of the three. It is not the minimum among linear unbiased predictors: the KF with "
        f"the bias as an unknown (diffuse) state reaches {diffuse['KF']:.5g}; its weights equal the "
        f"generalised-least-squares predictor (dense GLS, 60 + 20 samples, to within "
        f"{_WEIGHTS_AGREE:.0e}). 'In theory "
        "minimises the error variance' holds for that filter, not for the one the paper ran.",
        corrected="the KF that treats the bias as an unknown state (diffuse prior) minimises E Σe² among "
        "linear unbiased predictors; the plug-in KF of Table I does not, though its E Σe² is still the "
        "lowest of KF, MA and CM",
    )


def _check_kf_filter_of_table() -> Verdict:
    plug_in = _table1_analysis("calibration-mean")
    diffuse = _table1_analysis("diffuse")
    printed = TABLE1_SIMULATED["KF"][1]
    parts = []
    for name, (populations, errors, scale, _, chi_square) in (("plug-in", plug_in), ("diffuse", diffuse)):
        expected = scale * populations["KF"]["std_ie"]
        z = (printed - expected) / (scale * errors["KF"]["std_ie"])
        parts.append(
            f"{name}: χ² = {chi_square:.2f} on 11 dof at σ_w = {scale:.3f}, KF IE std {expected:.4g} "
            f"({z:+.2f} SE from the printed {printed})"
        )
    worse = max(plug_in[4], diffuse[4])
    status = (
        Status.CONSISTENT if plug_in[4] < diffuse[4] and worse < 11 + Z * math.sqrt(22) else Status.FAILED
    )
    return Verdict(
        status,
        "The twelve simulated numbers of Table I against the exact population values of each filter — "
        + "; ".join(parts)
        + ". The plug-in filter (the sample mean as an additional state, §IV-A) fits better, as the text "
        "says; both are within the sampling error of 1000 runs, so the table alone does not exclude the "
        "diffuse filter.",
    )


def _sigma_multiple_check(
    column: dict, statement_multiple: float, pair: tuple[str, str], digits: float, label: str
):
    def check() -> Verdict:
        better, worse = pair
        difference = column[worse][2] - column[better][2]
        standard_error = column[worse][3] / math.sqrt(RUNS)
        low = max(difference - digits, 0.0) / standard_error
        high = (difference + digits) / standard_error
        nominal = difference / standard_error
        inside = low - 0.5 <= statement_multiple <= high + 0.5
        return Verdict(
            Status.VERIFIED if inside else Status.REFUTED,
            f"{label}: ({column[worse][2]} − {column[better][2]})/({column[worse][3]}/√1000) = "
            f"{nominal:.2f} σ "
            f"({low:.2f}–{high:.2f} within the printed rounding); stated ≈ {statement_multiple:g} σ.",
        )

    return check


def _check_ie_differences() -> Verdict:
    lines = []
    ok = True
    for name, column in (("simulated", TABLE1_SIMULATED), ("real", TABLE1_REAL)):
        spread = max(c[0] for c in column.values()) - min(c[0] for c in column.values())
        se = min(c[1] for c in column.values()) / math.sqrt(RUNS)
        ok = ok and spread < se
        lines.append(f"{name}: largest mean-IE difference {spread:.3g} < smallest std/√1000 = {se:.3g}")
    return Verdict(Status.VERIFIED if ok else Status.REFUTED, "; ".join(lines) + ".")


def _check_real_better_ie() -> Verdict:
    real = TABLE1_REAL
    simulated = TABLE1_SIMULATED
    ok = abs(real["KF"][0]) < abs(real["CM"][0]) and abs(real["MA"][0]) < abs(real["CM"][0])
    ok = ok and abs(simulated["CM"][0]) < min(abs(simulated["KF"][0]), abs(simulated["MA"][0]))
    return Verdict(
        Status.VERIFIED if ok else Status.REFUTED,
        "Printed |mean IE|: real KF 0.0214, MA 0.0258 < CM 0.0728; simulated CM 115 < KF 119 < MA 142.",
    )


def _example_check(method: str, which: int):
    def check() -> Verdict:
        _, _, scale, _, _ = _table1_analysis()
        model = BiasModel(d=0.5, driving_variance=scale**2)
        variance_ie, mean_square, variance_square = error_moments(1200, 1200, method, model)
        printed = EXAMPLE_SIMULATED[method][which]
        if which == 0:  # IE ~ N(0, Var IE)
            centre, spread, name, value = 0.0, math.sqrt(variance_ie), "IE", printed
        else:  # RSSE² has mean tr C_e and variance 2 tr C_e²
            centre, spread, name, value = mean_square, math.sqrt(variance_square), "RSSE²", printed**2
        z = abs(value - centre) / spread
        return Verdict(
            Status.CONSISTENT if z <= Z else Status.REFUTED,
            f"One run of 1200 + 1200 samples at d = 1/2, σ_w = {scale:.3f}: {name} has population mean "
            f"{centre:.4g}, std {spread:.4g}; the printed value gives {value:.4g}, {z:.2f} std away.",
        )

    return check


def _data_not_public(what: str):
    def check() -> Verdict:
        return Verdict(
            Status.NOT_CHECKABLE,
            f"{what}: the authors' gyro data are not public. Our ADIS16405 columns (same batch, "
            "same predictors): "
            "docs/sj2012_table1_adis16405.md.",
        )

    return check


def _table1_and_example_claims() -> list[Claim]:
    claims = []
    for method in METHODS:
        for index, row in enumerate(ROWS):
            claims.append(
                Claim(
                    f"SJ2012-table1-simulated-{method.lower()}-{row.replace('_', '-')}",
                    "SJ2012",
                    "Table I, simulated",
                    f"{method} {ROW_NAMES[row]} = {TABLE1_SIMULATED[method][index]} (1000 runs, d "
                    "= 1/2, no white noise).",
                    _table1_number_check(method, row),
                )
            )
            claims.append(
                Claim(
                    f"SJ2012-table1-real-{method.lower()}-{row.replace('_', '-')}",
                    "SJ2012",
                    "Table I, real data",
                    f"{method} {ROW_NAMES[row]} = {TABLE1_REAL[method][index]} (1000 sections of "
                    "2000 samples).",
                    _data_not_public(f"{method} {ROW_NAMES[row]} = {TABLE1_REAL[method][index]}"),
                )
            )
        for which, name in enumerate(("ie", "rsse")):
            claims.append(
                Claim(
                    f"SJ2012-sec5b-example-simulated-{method.lower()}-{name}",
                    "SJ2012",
                    "§V-B, Fig. 2",
                    f"Example run on simulated data: {method} {name.upper()} = "
                    f"{EXAMPLE_SIMULATED[method][which]}.",
                    _example_check(method, which),
                )
            )
            claims.append(
                Claim(
                    f"SJ2012-sec5b-example-real-{method.lower()}-{name}",
                    "SJ2012",
                    "§V-B, Fig. 3",
                    f"Example run on real data: {method} {name.upper()} = {EXAMPLE_REAL[method][which]}.",
                    _data_not_public(f"{method} {name.upper()} = {EXAMPLE_REAL[method][which]}"),
                )
            )
    return claims


CLAIMS: list[Claim] = [
    Claim(
        "SJ2012-sec5-rsse-definition",
        "SJ2012",
        "§V",
        "Root sum of squared errors (RSSE): the sum of the squares of the prediction errors.",
        _check_rsse_definition,
    ),
    Claim(
        "SJ2012-sec5-exact-local-whittle-d",
        "SJ2012",
        "§V",
        "The exact local Whittle estimate of d for the gyro data used is 0.535.",
        _data_not_public("d = 0.535"),
    ),
    Claim(
        "SJ2012-sec5b-real-noise-levels",
        "SJ2012",
        "§V-B",
        "White noise 45 °/h and 1/f driving noise 14 °/h were found appropriate for the real data.",
        _data_not_public("45 °/h and 14 °/h"),
    ),
    Claim(
        "SJ2012-table1-simulated-unit-driving-noise",
        "SJ2012",
        "Table I, simulated; §V-B",
        "The simulated data are half-integrated (d = 1/2) Gaussian white noise, 1000 runs of 1000 + 1000 "
        "samples. The driving-noise variance is not stated; this claim tests the natural reading, unit "
        "variance, against the simulated columns of Table I.",
        _check_unit_driving_noise,
    ),
    Claim(
        "SJ2012-sec5c-kf-lowest-rsse",
        "SJ2012",
        "§V, §V-C",
        "The KF should, in theory, minimise the error variance among linear estimators (lowest RSSE).",
        _check_kf_optimal,
    ),
    Claim(
        "SJ2012-table1-simulated-kf-filter",
        "SJ2012",
        "§IV-A; Table I, simulated",
        "The KF of Table I is the filter of §IV-A, which handles the bias, unknown before calibration, "
        "by 'taking the sample mean as an additional state variable'.",
        _check_kf_filter_of_table,
    ),
    Claim(
        "SJ2012-sec5c-ie-differences-insignificant",
        "SJ2012",
        "§V-C",
        "The differences in mean IE are smaller than the standard deviations divided by √1000.",
        _check_ie_differences,
    ),
    Claim(
        "SJ2012-sec5c-ie-ranking",
        "SJ2012",
        "§V-C",
        "Both proposed methods give a lower average IE than CM with authentic data; CM is "
        "best in simulations.",
        _check_real_better_ie,
    ),
    Claim(
        "SJ2012-sec5c-kf-two-sigma-simulated",
        "SJ2012",
        "§V-C",
        "The KF mean RSSE is smaller by two sigmas than the CM mean RSSE in the simulated runs.",
        _sigma_multiple_check(TABLE1_SIMULATED, 2, ("KF", "CM"), 1.0, "simulated"),
    ),
    Claim(
        "SJ2012-sec5c-kf-four-sigma-real",
        "SJ2012",
        "§V-C",
        "The KF mean RSSE is smaller by four sigmas than the CM mean RSSE with real data.",
        _sigma_multiple_check(TABLE1_REAL, 4, ("KF", "CM"), 0.001, "real"),
    ),
    Claim(
        "SJ2012-sec5c-ma-cm-one-sigma-simulated",
        "SJ2012",
        "§V-C",
        "Between MA and CM there is a one-sigma difference in favour of CM in the simulations.",
        _sigma_multiple_check(TABLE1_SIMULATED, 1, ("CM", "MA"), 1.0, "simulated"),
    ),
    Claim(
        "SJ2012-sec5c-ma-cm-one-sigma-real",
        "SJ2012",
        "§V-C",
        "Between MA and CM there is a one-sigma difference in favour of MA with authentic data.",
        _sigma_multiple_check(TABLE1_REAL, 1, ("MA", "CM"), 0.001, "real"),
    ),
    *_table1_and_example_claims(),
    Claim(
        "SJ2012-sec5a-fig1-no-rrw-below-1e5",
        "SJ2012",
        "§V-A, Fig. 1",
        "Temperature-controlled gyro: no RRW slope at averaging times below 10^5 s; Allan variance almost "
        "constant above 10^2 s.",
        figure_1_not_public("10^5 s and 10^2 s"),
    ),
    Claim(
        "SJ2012-sec5a-fig1-rrw-above-4e3",
        "SJ2012",
        "§V-A, Fig. 1",
        "The gyro without temperature conditioning: Allan variance increases above approx. 4·10^3 s because "
        "of RRW.",
        figure_1_not_public("4·10^3 s"),
    ),
]
