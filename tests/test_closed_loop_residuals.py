"""The loop's residuals made per axis when asked: the values, read-only, and nothing held once dropped."""

from __future__ import annotations

import gc
import weakref

import numpy as np
import pytest

from carousel_theory.closed_loop.view import Residuals


def _residuals() -> tuple[Residuals, dict[str, np.ndarray]]:
    rng = np.random.default_rng(11)
    cleaned = {"wx": rng.standard_normal(500), "wy": rng.standard_normal(500) + 3.0}
    return Residuals(cleaned, {"wx": 0.25, "wy": 3.0}), cleaned


def test_values_are_cleaned_minus_bias():
    residuals, cleaned = _residuals()
    assert list(residuals) == ["wx", "wy"] and len(residuals) == 2
    np.testing.assert_array_equal(residuals["wx"], cleaned["wx"] - 0.25)
    np.testing.assert_array_equal(residuals["wy"], cleaned["wy"] - 3.0)
    with pytest.raises(KeyError):
        residuals["wz"]


def test_read_only_and_shared_while_held():
    residuals, _ = _residuals()
    first = residuals["wx"]
    assert residuals["wx"] is first  # held by the caller: the same array again
    with pytest.raises(ValueError, match="read-only"):
        first[0] = 1.0


def test_nothing_held_once_dropped():
    residuals, _ = _residuals()
    reference = weakref.ref(residuals["wy"])
    gc.collect()
    assert reference() is None


def test_fresh_is_a_writable_array_of_its_own():
    residuals, cleaned = _residuals()
    held = residuals["wx"]
    fresh = residuals.fresh("wx")
    np.testing.assert_array_equal(fresh, held)
    assert fresh.flags.writeable and not np.shares_memory(fresh, held)
    fresh[0] += 1.0
    np.testing.assert_array_equal(residuals["wx"], cleaned["wx"] - 0.25)  # the shared one is unchanged
