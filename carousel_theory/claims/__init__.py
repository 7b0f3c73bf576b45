"""The claims of both papers, one module per section.

Each module in this package defines ``CLAIMS: list[Claim]``; :func:`all_claims` collects them
in a stable order (by id). Adding a section means adding a module; nothing else changes.
"""

from __future__ import annotations

import importlib
import pkgutil

from carousel_theory.claim import Claim

__all__ = ["all_claims"]


def all_claims() -> list[Claim]:
    """Every registered claim, sorted by id; refuses duplicate ids."""
    claims: list[Claim] = []
    for module_info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if module_info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{__name__}.{module_info.name}")
        claims.extend(module.CLAIMS)
    ids = [claim.id for claim in claims]
    duplicates = sorted({i for i in ids if ids.count(i) > 1})
    if duplicates:
        raise RuntimeError(f"duplicate claim ids: {duplicates}")
    return sorted(claims, key=lambda claim: claim.id)
