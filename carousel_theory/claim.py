"""A claim of one of the two papers, and the verdict its check reaches.

Each claim carries a ``check`` that *computes* its status: the status printed in
``paper_check.md`` is what the check found this run, never a label typed beside the claim.
"""

from __future__ import annotations

import enum
from collections.abc import Callable
from dataclasses import dataclass, field

__all__ = ["PAPERS", "Claim", "Status", "Verdict"]

#: Paper keys used in claim ids and in ``paper_check.json``.
PAPERS = {
    "TIM2014": "J. Collin, M. Kirkko-Jaakkola, J. Takala, “Effect of Carouseling on Angular Rate Sensor "
    "Error Processes”, IEEE Trans. Instrum. Meas., 2014",
    "SJ2012": "M. Kirkko-Jaakkola, J. Collin, J. Takala, “Bias Prediction for MEMS Gyroscopes”, "
    "IEEE Sensors J. 12(6), 2012",
}


class Status(enum.StrEnum):
    """How a claim was decided. ``FAILED`` means the check did not confirm what it was written to
    confirm: a regression, which ``carousel-theory check --check`` refuses."""

    PROVED = "proved"  # exact symbolic identity, for all values of its parameters
    VERIFIED = "verified"  # checked at >= 50 significant digits, or exhaustively over a stated finite range
    CONSISTENT = "consistent"  # Monte Carlo agreement within a stated bound
    REFUTED = "refuted"  # a counterexample, evaluated exactly or at >= 50 digits
    ERRATUM = "erratum"  # the printed form is wrong; ``corrected`` holds the right one
    NOT_CHECKABLE = "not checkable"  # with the reason: data not public, figure lost, ...
    FAILED = "failed"


@dataclass(frozen=True)
class Verdict:
    """What a check found: its status, the evidence (deterministic text) and, for an erratum, the
    corrected form."""

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
