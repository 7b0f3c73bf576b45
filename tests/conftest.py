"""Shared test configuration: Hypothesis profiles, a guard against the global NumPy RNG, the
working precision of mpmath restored after every test, and the location of the measured data."""

from __future__ import annotations

import inspect
import os
import re
from pathlib import Path

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, settings

from carousel_theory.noise_model import NoiseModel

settings.register_profile("ci", max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("dev", max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("thorough", max_examples=500, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

#: Monte Carlo tests assert |mean − theory| ≤ Z_MONTE_CARLO · SE, one z for the whole suite.
Z_MONTE_CARLO = 4.5

SHARED_DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data"

#: A MEMS gyro axis at 100 Hz: white + RRW + 1/f (d = 0.5) + first-order Gauss–Markov, per-sample
#: variances in (rad/s)² (the model of benchmarks/bench_fit_vs_allantools.py and
#: benchmarks/bench_fit_calibration.py).
GYRO_VARIANCES = {
    "white_variance": 3.6e-5,
    "rrw_variance": 1e-14,
    "flicker_variance": 1e-9,
    "ar_variance": 4e-6,
}
GYRO_MODEL = NoiseModel(sample_rate=100.0, flicker_d=0.5, ar_coefficients=(0.8,), **GYRO_VARIANCES)


@pytest.fixture(autouse=True)
def _restore_mpmath_precision():
    dps = mpmath.mp.dps
    yield
    mpmath.mp.dps = dps


@pytest.fixture(autouse=True)
def _forbid_global_numpy_rng(monkeypatch):
    """Any use of the legacy global ``np.random`` state fails the test: pass a Generator instead."""

    def refuse(*args, **kwargs):
        raise AssertionError("the global numpy.random state was used; pass a numpy.random.Generator")

    # np.random.seed stays allowed: Hypothesis seeds the global state itself around every example.
    for name in ("rand", "randn", "random", "normal", "standard_normal", "uniform", "randint"):
        monkeypatch.setattr(np.random, name, refuse)


@pytest.fixture
def shared_data() -> Path:
    """The measured recordings in ../shared/data; the test is skipped, with the reason, when absent."""
    if not SHARED_DATA.is_dir():
        pytest.skip(f"measured data not found at {SHARED_DATA} (the shared/ folder beside the project)")
    return SHARED_DATA


def public_functions(module) -> set[str]:
    """The names of the functions a module defines itself and does not mark private."""
    return {
        name
        for name, value in inspect.getmembers(module, inspect.isfunction)
        if value.__module__ == module.__name__ and not name.startswith("_")
    }


def functions_called_in(invalid_calls) -> set[str]:
    """The names that appear in the source of the calls of an invalid-call table ``(id, call, ...)``."""
    return {word for case in invalid_calls for word in re.findall(r"\w+", inspect.getsource(case[1]))}
