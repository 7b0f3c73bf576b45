"""Every registered derivation document renders deterministically, carries the generated notice, and
the committed ``derivations/<name>.md`` equals its render (what ``carousel-theory derive --check``
checks in CI).

The two §II and §V documents build in a few seconds and run by default; the others (some take longer
to build) are marked slow.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from carousel_theory.derivations import GENERATED_NOTICE, Document, all_documents

REPOSITORY = Path(__file__).resolve().parents[1]
FAST = {"tim2014_error_processes", "tim2014_experiments"}
DOCUMENTS = {document.name: document for document in all_documents()}


def _parameters() -> list:
    return [
        pytest.param(name, id=name, marks=() if name in FAST else pytest.mark.slow)
        for name in sorted(DOCUMENTS)
    ]


def test_the_section_documents_are_registered() -> None:
    assert set(DOCUMENTS) >= FAST
    assert all(isinstance(document, Document) for document in DOCUMENTS.values())


@pytest.mark.parametrize("name", _parameters())
def test_document_is_deterministic_and_committed(name: str) -> None:
    document = DOCUMENTS[name]
    first, second = document.render(), document.render()
    assert first == second
    assert first.startswith(GENERATED_NOTICE + "\n\n# " + document.title + "\n")
    committed = REPOSITORY / "derivations" / f"{name}.md"
    assert committed.is_file(), f"{committed} is missing: run carousel-theory derive --only {name}"
    assert committed.read_text(encoding="utf-8") == first, f"run carousel-theory derive --only {name}"
