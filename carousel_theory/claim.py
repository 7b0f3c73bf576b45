"""A claim of one of the two papers, and the verdict its check reaches.

Each claim carries a ``check`` that *computes* its status: the status printed in
``paper_check.md`` is what the check found this run, never a label typed beside the claim.
"""

from __future__ import annotations

import enum
from collections.abc import Callable
from dataclasses import dataclass, field

__all__ = ["FINDINGS", "NEEDS_CORRECTED_FORM", "PAPERS", "STATUS_MEANINGS", "Claim", "Status", "Verdict"]

#: Paper keys used in claim ids and in ``paper_check.json``.
PAPERS = {
    "TIM2014": "J. Collin, M. Kirkko-Jaakkola, J. Takala, “Effect of Carouseling on Angular Rate Sensor "
    "Error Processes”, IEEE Trans. Instrum. Meas., 2014",
    "SJ2012": "M. Kirkko-Jaakkola, J. Collin, J. Takala, “Bias Prediction for MEMS Gyroscopes”, "
    "IEEE Sensors J. 12(6), 2012",
}


class Status(enum.StrEnum):
    """How a claim was decided. ``FAILED`` means the check did not confirm what it was written to
    confirm (or could not decide): a regression, which ``carousel-theory check --check`` refuses.

    Three kinds of "the paper is not right as printed" are kept apart: ``QUALIFIED`` (true under a
    condition the paper does not state), ``ERRATUM``/``REFUTED`` (false as stated) and ``TYPOGRAPHIC``
    (a difference of notation with no mathematical content). ``INCONSISTENT`` is narrower than
    ``REFUTED``: printed numbers contradict the paper's own printed model, while what unpublished
    data would show cannot be decided.
    """

    PROVED = "proved"  # exact symbolic identity, for all values of its parameters
    VERIFIED = "verified"  # checked at >= 50 significant digits, or exhaustively over a stated finite range
    CONSISTENT = "consistent"  # Monte Carlo agreement within a stated bound
    QUALIFIED = "qualified"  # true under a condition the paper leaves unstated; ``corrected`` states it
    ERRATUM = "erratum"  # the printed mathematics is wrong as stated; ``corrected`` holds the right form
    TYPOGRAPHIC = "erratum (typographic)"  # notation differs from the intended symbol; nothing mathematical
    REFUTED = "refuted"  # false as stated: a counterexample, evaluated exactly or at >= 50 digits
    INCONSISTENT = "inconsistent"  # printed numbers contradict the printed model; the data are not public
    NOT_CHECKABLE = "not checkable"  # with the reason: data not public, figure lost, ...
    FAILED = "failed"


#: What each status means, in the words ``paper_check.md`` prints at its top.
STATUS_MEANINGS = {
    Status.PROVED: "an exact symbolic identity, for all values of its parameters",
    Status.VERIFIED: "checked exactly or at ≥ 50 significant digits, or exhaustively over a stated "
    "finite range",
    Status.CONSISTENT: "Monte Carlo or a sampling distribution agrees within a stated bound (z = 4.5)",
    Status.QUALIFIED: "true under a condition the paper does not state; the corrected form states the "
    "condition, and the evidence shows that the statement fails without it",
    Status.ERRATUM: "the printed mathematics is wrong as stated (a counterexample); the corrected form is "
    "proved or verified",
    Status.TYPOGRAPHIC: "the printed symbol or layout differs from the intended one and nothing "
    "mathematical depends on it; the corrected form gives the intended notation",
    Status.REFUTED: "false as stated: a counterexample evaluated exactly or at ≥ 50 digits; where the "
    "statement has more than one reading the evidence names the reading refuted",
    Status.INCONSISTENT: "printed numbers contradict the paper's own printed model (decided exactly or at "
    "50 digits); what the unpublished recording shows cannot be decided, and the evidence says what "
    "change of model would reconcile them",
    Status.NOT_CHECKABLE: "cannot be decided from public material; the evidence gives the reason",
    Status.FAILED: "the check could not decide (or raised): a regression",
}

#: Statuses whose verdict must carry a corrected form (the condition, for QUALIFIED).
NEEDS_CORRECTED_FORM = frozenset({Status.QUALIFIED, Status.ERRATUM, Status.TYPOGRAPHIC})
#: Statuses that say the paper is not right as printed; listed together at the end of paper_check.md.
FINDINGS = (Status.ERRATUM, Status.REFUTED, Status.INCONSISTENT, Status.QUALIFIED, Status.TYPOGRAPHIC)


@dataclass(frozen=True)
class Verdict:
    """What a check found: its status, the evidence (deterministic text) and, for the statuses of
    :data:`NEEDS_CORRECTED_FORM`, the corrected form (for ``QUALIFIED``, the condition)."""

    status: Status
    evidence: str
    corrected: str | None = None


@dataclass(frozen=True)
class Claim:
    """One claim of a paper.

    ``id`` is stable (``TIM2014-eq15-variance``); ``location`` names the equation, section, table
    or page; ``statement`` quotes or paraphrases the paper; ``check`` decides it.
    """

    id: str
    paper: str
    location: str
    statement: str
    check: Callable[[], Verdict] = field(repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.paper not in PAPERS:
            raise ValueError(f"paper={self.paper!r}: must be one of {sorted(PAPERS)}")
        if not self.id.startswith(self.paper + "-"):
            raise ValueError(f"id={self.id!r}: must start with the paper key {self.paper!r} and a dash")
