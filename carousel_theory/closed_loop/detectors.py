"""The loop's detectors and remedies, by the stable effect names of :mod:`carousel_theory.effects`.

======================  ==========================================================================
name                    detection statistic (null: the fitted model; Bonferroni over the scan)
======================  ==========================================================================
``warmup``              max over time constants τ_c of |z| of the GLS amplitude of e^{−t/τ_c},
                        the noise refitted jointly with a 1/f term
``temperature``         |z| of the GLS coefficient of the temperature column, the noise refitted
                        jointly with the regressor
``steps``               max over t₀ of |z| of the GLS estimate of a bias step after sample t₀
``spikes``              max robust |z| of the residual about its running median (trimmed scale)
``sinusoid``            max of the Hann periodogram / (model PSD × local median level), exact tail
``colored_noise``       log(median level 5–15 % f_s / median level 35–50 % f_s), exact median tails
``flicker``             Δχ²/dispersion of the Allan-variance fit when a 1/f (d = 1/2) term is added,
                        parametric-bootstrap tail
======================  ==========================================================================
"""

from __future__ import annotations

from carousel_theory.closed_loop.detection import Detector, Remedy
from carousel_theory.closed_loop.noise_detectors import (
    ColoredNoiseDetector,
    FlickerDetector,
    FlickerGoodnessOfFit,
)
from carousel_theory.closed_loop.signal_detectors import SinusoidDetector, SpikesDetector
from carousel_theory.closed_loop.trend_detectors import StepsDetector, TemperatureDetector, WarmupDetector

__all__ = ["DETECTORS", "REMEDIES", "TESTED_EFFECTS", "VERIFIERS"]

_ENTRIES = (
    SpikesDetector(),
    StepsDetector(),
    SinusoidDetector(),
    WarmupDetector(),
    TemperatureDetector(),
    ColoredNoiseDetector(),
    FlickerDetector(),
)

#: The effects the loop tests, in the order used to break exact ties.
TESTED_EFFECTS: tuple[str, ...] = tuple(entry.name for entry in _ENTRIES)
#: Detector of each tested effect.
DETECTORS: dict[str, Detector] = {entry.name: entry for entry in _ENTRIES}
#: How each detected effect is fitted into the model.
REMEDIES: dict[str, Remedy] = {entry.name: entry for entry in _ENTRIES}
#: The test that decides whether an added effect explains its own evidence: its detector rerun on the new
#: residual, except for 1/f noise, which once in the model is judged by the goodness of fit.
VERIFIERS: dict[str, Detector] = {**DETECTORS, "flicker": FlickerGoodnessOfFit()}
