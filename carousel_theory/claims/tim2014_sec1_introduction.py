"""Claims of TIM 2014 §I (introduction): rotating IMUs, gyrocompassing, wheel-mounted IMUs and the
name and synthesis of 1/f noise.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import sympy as sp

from carousel_theory.claim import Claim, Status, Verdict
from carousel_theory.claims._common import not_checkable
from carousel_theory.processes import (
    fractional_coefficients,
    fractionally_integrate,
)
from carousel_theory.symbols import d

__all__ = ["CLAIMS"]

PAPER = "TIM2014"


#: TIM 2014 reference [9] as printed in both renderings.
REFERENCE_9 = (
    'E. S. Geller, "Inertial system platform rotation," IEEE Transactions on Aerospace and Electronic '
    "Systems, vol. AES-4, no. 4, pp. 557–568, Jul. 1968."
)


def _check_rotating_since_1960s() -> Verdict:
    import re

    years = [int(y) for y in re.findall(r"\b(1[89]\d\d|20\d\d)\b", REFERENCE_9)]
    if years and 1960 <= years[-1] <= 1969:
        return Verdict(Status.VERIFIED, f"The cited reference [9] is from {years[-1]}, in the 1960s.")
    return Verdict(Status.REFUTED, f"reference [9] is dated {years}, not in the 1960s")


def _check_flicker_name(order: Fraction = Fraction(1, 2)) -> Verdict:
    f = sp.Symbol("f", positive=True)
    # |1 − e^{−2πif}|^{−2d} = (2 sin πf)^{−2d}: the spectral density of (3) per unit σ_w².
    density = (2 * sp.sin(sp.pi * f)) ** (-2 * d)
    transfer_check = sp.simplify(
        sp.expand_complex((1 - sp.exp(-2 * sp.pi * sp.I * f)) * (1 - sp.exp(2 * sp.pi * sp.I * f)))
        - 4 * sp.sin(sp.pi * f) ** 2
    )
    base_limit = sp.limit(f / (2 * sp.sin(sp.pi * f)), f, 0)
    if transfer_check != 0 or base_limit != 1 / (2 * sp.pi):
        return Verdict(Status.FAILED, f"|1 − e^(−iλ)|² check {transfer_check}, limit {base_limit}")
    exponent = 2 * order
    if exponent != 1:
        return Verdict(
            Status.REFUTED,
            f"At d = {order} the density behaves like f^(−{exponent}) near 0, not 1/f.",
        )
    return Verdict(
        Status.PROVED,
        f"The density of (3) is σ_w² (2 sin πf)^(−2d) = {sp.sstr(density)}·σ_w², and f^(2d)·S(f) → σ_w² "
        f"(2π)^(−2d) "
        "as f → 0: a 1/f^(2d) law, exactly 1/f at the d = 1/2 used in §V-B (1/f^(2d) for other 0 < d < 1).",
    )


def _check_flicker_synthesis(length: int = 256, seed: int = 2014) -> Verdict:
    # For the record: the model (3) itself is synthesized exactly by a convolution (FFT, O(n log n)).
    innovations = np.random.default_rng(seed).standard_normal(length)
    psi = fractional_coefficients(0.5, length)
    direct = np.array([np.dot(psi[: t + 1][::-1], innovations[: t + 1]) for t in range(length)])
    fast = fractionally_integrate(innovations, 0.5)
    error = float(np.max(np.abs(fast - direct)) / np.max(np.abs(direct)))
    if error > 1e-12:
        return Verdict(Status.FAILED, f"the FFT synthesis of (3) differs from the direct sum by {error:.1e}")
    return Verdict(
        Status.NOT_CHECKABLE,
        "'Nontrivial' is a judgement, not a checkable statement [16]–[21]. For the record, the model (3) is "
        "synthesized by one FFT convolution in O(n log n); it matches the direct O(n²) sum of (3) within "
        f"1e-12 relative (n = {length}, d = 1/2, seeded). What is hard is a stationary 1/f process: (3) "
        "starts at t = 1 and is not stationary.",
    )


CLAIMS: list[Claim] = [
    Claim(
        "TIM2014-secI-gyrocompassing",
        PAPER,
        "§I, ¶1",
        "MEMS gyros have been shown to perform high-precision tasks such as gyrocompassing [1]–[3].",
        not_checkable("A statement about the cited literature [1]–[3]; no number or formula to compute."),
    ),
    Claim(
        "TIM2014-secI-rotating-imus-since-1960s",
        PAPER,
        "§I, ¶3",
        "Rotating IMUs have been studied already since the 1960s [9].",
        _check_rotating_since_1960s,
    ),
    Claim(
        "TIM2014-secI-wheel-mounted-imu",
        PAPER,
        "§I, ¶3",
        "A dedicated rotating system is not always necessary, e.g., if the IMU is mounted at the wheel of a "
        "land "
        "vehicle [11].",
        not_checkable(
            "Rests on a patent application [11] and the field test of §V-D, whose data are not public."
        ),
    ),
    Claim(
        "TIM2014-secI-flicker-name-spectral",
        "TIM2014",
        "§I, ¶4 and §II-D",
        "1/f (flicker) noise is named after its power spectral density; it is modelled by the fractional "
        "integral (3).",
        _check_flicker_name,
    ),
    Claim(
        "TIM2014-secI-flicker-nontrivial-to-synthesize",
        "TIM2014",
        "§I, ¶4",
        "1/f noise is a long-memory process and is nontrivial to synthesize [16]–[21].",
        _check_flicker_synthesis,
    ),
]
