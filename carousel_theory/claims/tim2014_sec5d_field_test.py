"""Claims of TIM 2014 §V-D (the field test on a car-mounted carousel); the data are not public."""

from __future__ import annotations

from fractions import Fraction

import mpmath

from carousel_theory.claim import Claim, Status, Verdict
from carousel_theory.claims._common import DIGITS, exact_mpf, not_checkable
from carousel_theory.claims._tim2014_static_model import TABLE_III, degrees

__all__ = ["CLAIMS"]

PAPER = "TIM2014"


FIELD_TEST_MINUTES = 12


FIELD_TEST_SPEED_KMH = (10, 12)


FIELD_TEST_CABIN_HEADING_DEG = 240


def _check_field_speed() -> Verdict:
    low, high = (Fraction(v * 1000, 3600) for v in FIELD_TEST_SPEED_KMH)  # m/s
    seconds = FIELD_TEST_MINUTES * 60
    # An illustrative passenger-car tyre of 1.9 m circumference (the paper gives no size).
    circumference = Fraction(19, 10)
    periods = (float(circumference / high), float(circumference / low))
    return Verdict(
        Status.NOT_CHECKABLE,
        f"The field data are not public. 10–12 km/h for 12 min is {float(low * seconds) / 1000:.1f}–"
        f"{float(high * seconds) / 1000:.1f} km; with a 1.9 m tyre circumference (not given in the paper) "
        "one wheel "
        f"revolution takes {periods[0]:.2f}–{periods[1]:.2f} s, far shorter than the static test's T = 2 s.",
    )


def _check_cabin_heading() -> Verdict:
    seconds = FIELD_TEST_MINUTES * 60
    with mpmath.workdps(DIGITS):
        bias = mpmath.mpf(FIELD_TEST_CABIN_HEADING_DEG) / seconds  # °/s
        rrw = exact_mpf(TABLE_III["x"]["rrw"])
        # Integrated RRW after t seconds: variance σ_q² t³/3 (continuous limit of Σ_a Σ_b rrw_average_cov).
        sigma = degrees(mpmath.sqrt(rrw * mpmath.mpf(seconds) ** 3 / 3))
        return Verdict(
            Status.NOT_CHECKABLE,
            f"The field data are not public. 240° in 12 min corresponds to an uncompensated mean bias of "
            f"{mpmath.nstr(bias, 3)} °/s; with the x-gyro's Table III σ_q² the integrated RRW alone would "
            "have "
            f"σ ≈ {mpmath.nstr(sigma, 3)}° after 12 min.",
        )


CLAIMS: list[Claim] = [
    Claim(
        "TIM2014-secVD-speed-duration",
        PAPER,
        "§V-D, ¶2",
        "The vehicle was driven at 10–12 km/h in a parking lot for 12 minutes; N varied from revolution to "
        "revolution "
        "(Fig. 12).",
        _check_field_speed,
    ),
    Claim(
        "TIM2014-secVD-reference-accuracy",
        PAPER,
        "§V-D, ¶1",
        "The dual-frequency GPS receiver and the ring-laser gyro unit give sub-degree heading accuracy for "
        "the test.",
        not_checkable(
            "A property of the reference equipment [39], [40] during a test whose data are not public."
        ),
    ),
    Claim(
        "TIM2014-secVD-intervals-mismatch",
        PAPER,
        "§V-D, ¶3, Fig. 13",
        "The intervals computed with the stationary error variances do not match the field-test errors; "
        "there is no "
        "drifting trend in Fig. 13a; the local peaks are due to a logging bug.",
        not_checkable("Fig. 13 and the field data are not public."),
    ),
    Claim(
        "TIM2014-secVD-cabin-heading-240deg",
        PAPER,
        "§V-D, ¶4",
        "Without the bias correction (from the first 30 s) the cabin gyro heading error increases to 240° "
        "during the "
        "test.",
        _check_cabin_heading,
    ),
    Claim(
        "TIM2014-secVD-carouselled-heading-better",
        PAPER,
        "§V-D, ¶4, Fig. 14",
        "Although no bias compensation was applied to the wheel gyro, the carouselled heading is more "
        "accurate than "
        "the cabin-fixed one because of the mitigation of rate random walk.",
        not_checkable(
            "Fig. 14 and the field data are not public; the heading (z) gyro has no Table III entry."
        ),
    ),
]
