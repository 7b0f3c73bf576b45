"""Strict, versioned JSON: no bare NaN or Infinity, a reason beside every null, a header on every document."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass

import numpy as np
import pytest

from carousel_theory import __version__
from carousel_theory.json_output import SCHEMA_VERSION, json_document, strict_json, to_strict


def _strict_loads(text: str) -> object:
    def refuse(constant: str) -> object:
        raise AssertionError(f"non-standard JSON constant {constant}")

    return json.loads(text, parse_constant=refuse)


@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf, np.float64("nan"), np.float32("inf")])
def test_nonfinite_becomes_null_with_a_reason(value: float) -> None:
    document = _strict_loads(strict_json({"arw": value, "ok": 1.5}))
    assert document == {"arw": None, "arw_null_reason": document["arw_null_reason"], "ok": 1.5}  # type: ignore[index]
    assert isinstance(document["arw_null_reason"], str)  # type: ignore[index]


def test_caller_reason_is_used() -> None:
    got = to_strict({"se": math.nan}, {"se": "term held at zero: no standard error"})
    assert got == {"se": None, "se_null_reason": "term held at zero: no standard error"}


def test_nested_lists_arrays_and_numpy_scalars() -> None:
    body = {"tau": np.array([1.0, np.nan]), "n": np.int64(3), "rows": [{"x": np.inf}], "pair": (1, 2)}
    got = _strict_loads(strict_json(body))
    assert got == {
        "tau": [1.0, None],
        "n": 3,
        "rows": [{"x": None, "x_null_reason": "+infinity (unbounded)"}],
        "pair": [1, 2],
    }


def test_dataclasses_become_objects() -> None:
    @dataclass
    class Pair:
        a: float
        b: float

    got = to_strict({"p": Pair(1.0, math.nan)})
    assert got["p"]["a"] == 1.0 and got["p"]["b"] is None
    assert got["p"]["b_null_reason"].startswith("not a number")


def test_document_header() -> None:
    document = json_document("fit", {"axes": []})
    assert list(document)[:3] == ["schema", "schema_version", "carousel_theory_version"]
    assert document["schema"] == "carousel-theory/fit"
    assert document["schema_version"] == SCHEMA_VERSION
    assert document["carousel_theory_version"] == __version__


def test_plain_json_module_would_have_emitted_nan() -> None:
    """The failure this module exists for: the standard encoder writes the invalid token NaN."""
    assert "NaN" in json.dumps({"x": math.nan})
    assert "NaN" not in strict_json({"x": math.nan})
