"""The closed loop: fit a declared noise model, predict, measure the residual, name the missing effect,
add it, refit, and report the error before and after — until nothing significant remains.

Rooms, from the lowest floor up:

- :mod:`~carousel_theory.closed_loop.residual_model` — the noise model of one axis and its fit, an adapter
  over :class:`~carousel_theory.noise_model.NoiseModel` and :mod:`carousel_theory.fitting` (the only room
  that reads either);
- :mod:`~carousel_theory.closed_loop.view` — the residual of every axis under one model, a plain data view;
- :mod:`~carousel_theory.closed_loop.linear_statistics` — GLS statistics, their variances, refits;
- :mod:`~carousel_theory.closed_loop.detection` — the detectors' contract (``Detector.detect``,
  ``Remedy.fit``, the typed :class:`~carousel_theory.closed_loop.detection.Detection`);
- ``trend_detectors``, ``signal_detectors``, ``noise_detectors`` and the registry
  :mod:`~carousel_theory.closed_loop.detectors`;
- :mod:`~carousel_theory.closed_loop.evaluation` — predictions (bins, Allan variance) and metrics;
- :mod:`~carousel_theory.closed_loop.calibration` — the split of α and the final misfit test's bootstrap;
- :mod:`~carousel_theory.closed_loop.control` — the loop itself, with typed results
  (:mod:`~carousel_theory.closed_loop.result`);
- :mod:`~carousel_theory.closed_loop.report` — Markdown and plots.
"""

from carousel_theory.closed_loop.calibration import DEFAULT_ALPHA
from carousel_theory.closed_loop.control import run_loop
from carousel_theory.closed_loop.evaluation import BAND_EXPECTED_EXCEEDANCE, HEADLINE_METRIC
from carousel_theory.closed_loop.report import render_summary, write_report
from carousel_theory.closed_loop.resample import uniform_resample
from carousel_theory.closed_loop.result import LoopResult, Step, Trial

__all__ = [
    "BAND_EXPECTED_EXCEEDANCE",
    "DEFAULT_ALPHA",
    "HEADLINE_METRIC",
    "LoopResult",
    "Step",
    "Trial",
    "render_summary",
    "run_loop",
    "uniform_resample",
    "write_report",
]
