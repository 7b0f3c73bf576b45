"""Strict, versioned JSON documents: what every ``--json`` output of carousel-theory is made of.

* **Strict**: the output is RFC 8259 JSON that any parser accepts. A float that is not finite (NaN,
  ±inf) becomes ``null``, and a sibling key ``<key>_null_reason`` says why (the caller's reason where it
  gave one, otherwise what the value was). NumPy scalars and arrays become plain numbers and lists.
* **Versioned**: every document starts with ``schema`` (its name, e.g. ``carousel-theory/fit``),
  ``schema_version`` (changed whenever the layout changes incompatibly) and ``carousel_theory_version``.
  The layout of each document is a JSON Schema under ``docs/schemas/<name>.schema.json``.
* **Units named**: an object whose members carry a physical unit has a member ``units`` mapping each such
  member's name to its unit (an ASCII name of :data:`carousel_theory.units.UNIT_NAMES`); a member holding
  ``{value, standard_error}`` or an array has one unit for all its numbers; a member not named in
  ``units`` is dimensionless.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Mapping
from pathlib import PurePath
from typing import Any

import numpy as np

from carousel_theory import __version__

__all__ = ["SCHEMA_VERSION", "json_document", "strict_json", "to_strict"]

#: Version of the layout of every JSON document (major.minor; a major change breaks readers).
SCHEMA_VERSION = "1.0"

_NULL_SUFFIX = "_null_reason"


def _default_reason(value: float) -> str:
    if math.isnan(value):
        return "not a number (undefined for this fit or data)"
    return "+infinity (unbounded)" if value > 0 else "-infinity (unbounded)"


def _is_nonfinite(value: Any) -> bool:
    return isinstance(value, float | np.floating) and not math.isfinite(float(value))


def _plain(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, PurePath):
        return str(value)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return dataclasses.asdict(value)
    return value


def _strict_mapping(mapping: Mapping[Any, Any], reasons: Mapping[str, str]) -> dict[str, Any]:
    result: dict[str, Any] = {}
    for raw_key, raw in mapping.items():
        key = str(raw_key)
        value = _plain(raw)
        if _is_nonfinite(value):
            result[key] = None
            result.setdefault(key + _NULL_SUFFIX, reasons.get(key, _default_reason(float(value))))
        else:
            result[key] = to_strict(value, reasons)
    return result


def to_strict(value: Any, reasons: Mapping[str, str] | None = None) -> Any:
    """``value`` with every non-finite float replaced by ``None`` (with a reason beside it in mappings),
    NumPy types made plain and tuples made lists; ``reasons`` maps a key to the reason for its null."""
    reasons = {} if reasons is None else reasons
    value = _plain(value)
    if isinstance(value, Mapping):
        return _strict_mapping(value, reasons)
    if isinstance(value, list | tuple):
        return [None if _is_nonfinite(_plain(item)) else to_strict(item, reasons) for item in value]
    if _is_nonfinite(value):
        return None
    return value


def json_document(
    name: str, body: Mapping[str, Any], reasons: Mapping[str, str] | None = None
) -> dict[str, Any]:
    """The document ``carousel-theory/<name>``: the version header, then ``body`` made strict."""
    header = {
        "schema": f"carousel-theory/{name}",
        "schema_version": SCHEMA_VERSION,
        "carousel_theory_version": __version__,
    }
    return {**header, **to_strict(body, reasons)}


def strict_json(document: Any, *, indent: int | None = 1) -> str:
    """Serialise ``document`` as strict JSON (``allow_nan=False``: a non-finite number is an error)."""
    return json.dumps(to_strict(document), indent=indent, allow_nan=False, ensure_ascii=False) + "\n"
