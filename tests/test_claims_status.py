"""Every claim's status is pinned here, by id: a verdict that changes (a verification that turns into
a refutation, or a refutation that turns into a verification) fails pytest with the claim's name, the
status it reached and its evidence. The table was reviewed claim by claim against the two papers;
change an entry only with a reason (the commit that changes it says why).

All checks run once per test session (about 30 s).
"""

from __future__ import annotations

import pytest

from carousel_theory.claim import NEEDS_CORRECTED_FORM, Status
from carousel_theory.claims import all_claims
from carousel_theory.report import run_checks

PROVED, VERIFIED, CONSISTENT = Status.PROVED, Status.VERIFIED, Status.CONSISTENT
QUALIFIED, ERRATUM, TYPOGRAPHIC = Status.QUALIFIED, Status.ERRATUM, Status.TYPOGRAPHIC
REFUTED, INCONSISTENT, NOT_CHECKABLE = Status.REFUTED, Status.INCONSISTENT, Status.NOT_CHECKABLE

#: The status each claim must reach.
PINNED = {
    "SJ2012-eq1-measurement-model": PROVED,
    "SJ2012-eq2-allan-variance": VERIFIED,
    "SJ2012-eq3-fractional-difference": ERRATUM,
    "SJ2012-eq4-hurst": PROVED,
    "SJ2012-eq6-autoregressive-weights": PROVED,
    "SJ2012-eq6-coefficients-below-one": PROVED,
    "SJ2012-eq6-validity-d-half": REFUTED,
    "SJ2012-eq7-constant-allan-and-independent-increments": REFUTED,
    "SJ2012-eq7-increments-not-independent": VERIFIED,
    "SJ2012-eq8-eq9-moving-average": VERIFIED,
    "SJ2012-sec1-bias-white-calibrated-by-long-record": VERIFIED,
    "SJ2012-sec1-constant-bias-linear-angle-error": PROVED,
    "SJ2012-sec1-fig1-temperature-trend": NOT_CHECKABLE,
    "SJ2012-sec1-flicker-allan-constant": QUALIFIED,
    "SJ2012-sec3a-fig1-1000-seconds": NOT_CHECKABLE,
    "SJ2012-sec3b-bias-instability-measures-flicker": VERIFIED,
    "SJ2012-sec3b-flicker-long-memory": VERIFIED,
    "SJ2012-sec3b-optimal-averaging-time": PROVED,
    "SJ2012-sec3b-rrw-markov-future": ERRATUM,
    "SJ2012-sec3b-rrw-positive-slope": PROVED,
    "SJ2012-sec3b-white-negative-slope": PROVED,
    "SJ2012-sec4a-kalman-computationally-demanding": QUALIFIED,
    "SJ2012-sec5-exact-local-whittle-d": NOT_CHECKABLE,
    "SJ2012-sec5-rsse-definition": ERRATUM,
    "SJ2012-sec5a-fig1-no-rrw-below-1e5": NOT_CHECKABLE,
    "SJ2012-sec5a-fig1-rrw-above-4e3": NOT_CHECKABLE,
    "SJ2012-sec5b-example-real-cm-ie": NOT_CHECKABLE,
    "SJ2012-sec5b-example-real-cm-rsse": NOT_CHECKABLE,
    "SJ2012-sec5b-example-real-kf-ie": NOT_CHECKABLE,
    "SJ2012-sec5b-example-real-kf-rsse": NOT_CHECKABLE,
    "SJ2012-sec5b-example-real-ma-ie": NOT_CHECKABLE,
    "SJ2012-sec5b-example-real-ma-rsse": NOT_CHECKABLE,
    "SJ2012-sec5b-example-simulated-cm-ie": CONSISTENT,
    "SJ2012-sec5b-example-simulated-cm-rsse": CONSISTENT,
    "SJ2012-sec5b-example-simulated-kf-ie": CONSISTENT,
    "SJ2012-sec5b-example-simulated-kf-rsse": CONSISTENT,
    "SJ2012-sec5b-example-simulated-ma-ie": CONSISTENT,
    "SJ2012-sec5b-example-simulated-ma-rsse": CONSISTENT,
    "SJ2012-sec5b-real-noise-levels": NOT_CHECKABLE,
    "SJ2012-sec5c-ie-differences-insignificant": VERIFIED,
    "SJ2012-sec5c-ie-ranking": VERIFIED,
    "SJ2012-sec5c-kf-four-sigma-real": VERIFIED,
    "SJ2012-sec5c-kf-lowest-rsse": QUALIFIED,
    "SJ2012-sec5c-kf-two-sigma-simulated": VERIFIED,
    "SJ2012-sec5c-ma-cm-one-sigma-real": VERIFIED,
    "SJ2012-sec5c-ma-cm-one-sigma-simulated": VERIFIED,
    "SJ2012-table1-real-cm-mean-ie": NOT_CHECKABLE,
    "SJ2012-table1-real-cm-mean-rsse": NOT_CHECKABLE,
    "SJ2012-table1-real-cm-std-ie": NOT_CHECKABLE,
    "SJ2012-table1-real-cm-std-rsse": NOT_CHECKABLE,
    "SJ2012-table1-real-kf-mean-ie": NOT_CHECKABLE,
    "SJ2012-table1-real-kf-mean-rsse": NOT_CHECKABLE,
    "SJ2012-table1-real-kf-std-ie": NOT_CHECKABLE,
    "SJ2012-table1-real-kf-std-rsse": NOT_CHECKABLE,
    "SJ2012-table1-real-ma-mean-ie": NOT_CHECKABLE,
    "SJ2012-table1-real-ma-mean-rsse": NOT_CHECKABLE,
    "SJ2012-table1-real-ma-std-ie": NOT_CHECKABLE,
    "SJ2012-table1-real-ma-std-rsse": NOT_CHECKABLE,
    "SJ2012-table1-simulated-cm-mean-ie": CONSISTENT,
    "SJ2012-table1-simulated-cm-mean-rsse": CONSISTENT,
    "SJ2012-table1-simulated-cm-std-ie": CONSISTENT,
    "SJ2012-table1-simulated-cm-std-rsse": CONSISTENT,
    "SJ2012-table1-simulated-kf-filter": CONSISTENT,
    "SJ2012-table1-simulated-kf-mean-ie": CONSISTENT,
    "SJ2012-table1-simulated-kf-mean-rsse": CONSISTENT,
    "SJ2012-table1-simulated-kf-std-ie": CONSISTENT,
    "SJ2012-table1-simulated-kf-std-rsse": CONSISTENT,
    "SJ2012-table1-simulated-ma-mean-ie": CONSISTENT,
    "SJ2012-table1-simulated-ma-mean-rsse": CONSISTENT,
    "SJ2012-table1-simulated-ma-std-ie": CONSISTENT,
    "SJ2012-table1-simulated-ma-std-rsse": CONSISTENT,
    "SJ2012-table1-simulated-unit-driving-noise": REFUTED,
    "TIM2014-abstract-carouseling-reduces-errors": VERIFIED,
    "TIM2014-alg1-table1": VERIFIED,
    "TIM2014-eq1-bias-random-constant": VERIFIED,
    "TIM2014-eq10-cumulative-sum-matrix": VERIFIED,
    "TIM2014-eq11-partition": VERIFIED,
    "TIM2014-eq12-integrator-vector": VERIFIED,
    "TIM2014-eq13-carousel-vectors": VERIFIED,
    "TIM2014-eq14-two-bin-means": VERIFIED,
    "TIM2014-eq15-block-expansion": VERIFIED,
    "TIM2014-eq15-covariance-matrix": PROVED,
    "TIM2014-eq15-second-variance-4N-3": PROVED,
    "TIM2014-eq16-carouselled-averages": VERIFIED,
    "TIM2014-eq17-block-entries": VERIFIED,
    "TIM2014-eq17-uncorrelated-equal-variances": PROVED,
    "TIM2014-eq18-integral-factor": ERRATUM,
    "TIM2014-eq18-sine-coefficient": PROVED,
    "TIM2014-eq18-summation-index": ERRATUM,
    "TIM2014-eq19-limit": PROVED,
    "TIM2014-eq2-rrw-markov": VERIFIED,
    "TIM2014-eq20-unbiased-without-half": VERIFIED,
    "TIM2014-eq20-unbiased-without-one-over-tau": REFUTED,
    "TIM2014-eq21-unit-differences": VERIFIED,
    "TIM2014-eq22-period-four": PROVED,
    "TIM2014-eq23-stochastic-differences": ERRATUM,
    "TIM2014-eq24-31-matrices": VERIFIED,
    "TIM2014-eq26-cov-x-identity": PROVED,
    "TIM2014-eq3-fractional-integral": PROVED,
    "TIM2014-eq30-constant-allan-variance": VERIFIED,
    "TIM2014-eq31-pseudoinverse-all-n": PROVED,
    "TIM2014-eq32-sequence-from-K": VERIFIED,
    "TIM2014-eq4-measurement-model": PROVED,
    "TIM2014-eq5-estimator": PROVED,
    "TIM2014-eq5-perpendicular-estimator": PROVED,
    "TIM2014-eq6-revolution-average": PROVED,
    "TIM2014-eq7-continuous-bias-integral": PROVED,
    "TIM2014-eq8-bias-cancellation": PROVED,
    "TIM2014-eq9-white-variance": PROVED,
    "TIM2014-fig2-growth": VERIFIED,
    "TIM2014-render-algorithm1-loop": TYPOGRAPHIC,
    "TIM2014-render-eq11-ones-block": ERRATUM,
    "TIM2014-render-eq17-ones-in-off-diagonal": ERRATUM,
    "TIM2014-render-eq17-scalar-zero": TYPOGRAPHIC,
    "TIM2014-render-eq28-difference-matrix": TYPOGRAPHIC,
    "TIM2014-render-table1": TYPOGRAPHIC,
    "TIM2014-render-table2": TYPOGRAPHIC,
    "TIM2014-render-table3": VERIFIED,
    "TIM2014-render-unbiased-factor": ERRATUM,
    "TIM2014-render-wording": NOT_CHECKABLE,
    "TIM2014-sec4-allan-not-mvue": PROVED,
    "TIM2014-sec4-gray-code-matrix": VERIFIED,
    "TIM2014-sec4-kkt-columns-rule21": ERRATUM,
    "TIM2014-sec4-kkt-diagonal": PROVED,
    "TIM2014-sec4-logarithmic-state": QUALIFIED,
    "TIM2014-sec4-mcilroy-bounds": VERIFIED,
    "TIM2014-sec4-mvue": ERRATUM,
    "TIM2014-sec4-ones-count": VERIFIED,
    "TIM2014-sec4-overlapping-not-constant": VERIFIED,
    "TIM2014-sec4-pure-flicker-allan-constant": QUALIFIED,
    "TIM2014-sec4-s2048-quantized": VERIFIED,
    "TIM2014-sec4-sequence-variance-depends-on-length": VERIFIED,
    "TIM2014-sec4-stationary": REFUTED,
    "TIM2014-sec4-x-dimension": ERRATUM,
    "TIM2014-secI-flicker-name-spectral": PROVED,
    "TIM2014-secI-flicker-nontrivial-to-synthesize": NOT_CHECKABLE,
    "TIM2014-secI-gyrocompassing": NOT_CHECKABLE,
    "TIM2014-secI-rotating-imus-since-1960s": VERIFIED,
    "TIM2014-secI-wheel-mounted-imu": NOT_CHECKABLE,
    "TIM2014-secIIA-bias-embeddable": VERIFIED,
    "TIM2014-secIIB-quantization-white": QUALIFIED,
    "TIM2014-secIIB-thermal-white": VERIFIED,
    "TIM2014-secIIB-white-angular-random-walk": VERIFIED,
    "TIM2014-secIIC-rrw-memoryless-future": ERRATUM,
    "TIM2014-secIIC-rrw-sources": NOT_CHECKABLE,
    "TIM2014-secIID-long-memory": PROVED,
    "TIM2014-secIID-physical-origin-unknown": NOT_CHECKABLE,
    "TIM2014-secIIIA-averaging-keeps-bias": PROVED,
    "TIM2014-secIIIA-integer-ratio-assumption": VERIFIED,
    "TIM2014-secIIIB-averaging-decreases-variance": PROVED,
    "TIM2014-secIIIC-96-percent": VERIFIED,
    "TIM2014-secIIIC-R3-carouselled-same-variance": PROVED,
    "TIM2014-secIIIC-averages-correlated": PROVED,
    "TIM2014-secIIIC-coefficient-4-3": PROVED,
    "TIM2014-secIIIC-cosine-coefficient": PROVED,
    "TIM2014-secIIIC-driving-variance-sampling-rate": PROVED,
    "TIM2014-secIIIC-independent-increments": PROVED,
    "TIM2014-secIIIC-period-not-explicit": PROVED,
    "TIM2014-secIIIC-total-variance": PROVED,
    "TIM2014-secIIIC-variance-increment-N": PROVED,
    "TIM2014-secIIID-F-toeplitz": PROVED,
    "TIM2014-secIIID-F1-cumulative-sum": VERIFIED,
    "TIM2014-secIIID-F1-diverges": PROVED,
    "TIM2014-secIIID-averaged-faster": VERIFIED,
    "TIM2014-secIIID-comparison-series": ERRATUM,
    "TIM2014-secIIID-leibniz": PROVED,
    "TIM2014-secIIID-opposite-pairs": PROVED,
    "TIM2014-secVA-lower-order-terms": VERIFIED,
    "TIM2014-secVA-simulation-matches": CONSISTENT,
    "TIM2014-secVA-simulation-setup": VERIFIED,
    "TIM2014-secVB-averaged-logarithmic": PROVED,
    "TIM2014-secVB-carouselled-below-averaged": VERIFIED,
    "TIM2014-secVB-carouselled-below-driving": PROVED,
    "TIM2014-secVB-carouselled-no-trend": VERIFIED,
    "TIM2014-secVB-simulation-matches": CONSISTENT,
    "TIM2014-secVC-averaged-angle-600deg": NOT_CHECKABLE,
    "TIM2014-secVC-averaged-angle-includes-warmup": VERIFIED,
    "TIM2014-secVC-carouselled-angle-1.5deg": CONSISTENT,
    "TIM2014-secVC-exceedance-6.5-percent": INCONSISTENT,
    "TIM2014-secVC-fig7-bands": NOT_CHECKABLE,
    "TIM2014-secVC-flicker-neglected": VERIFIED,
    "TIM2014-secVC-recording": NOT_CHECKABLE,
    "TIM2014-secVC-sampling-N200-T2s": VERIFIED,
    "TIM2014-secVC-table3-bias-instability": INCONSISTENT,
    "TIM2014-secVC-table3-units": VERIFIED,
    "TIM2014-secVC-transient-excluded": NOT_CHECKABLE,
    "TIM2014-secVC-two-sigma-95-percent": VERIFIED,
    "TIM2014-secVC-unequal-white-variances": ERRATUM,
    "TIM2014-secVC-warmup-not-visible-carouselled": VERIFIED,
    "TIM2014-secVC-x-larger-variations": VERIFIED,
    "TIM2014-secVC-x-rrw-slope": NOT_CHECKABLE,
    "TIM2014-secVC-zero-true-rate": NOT_CHECKABLE,
    "TIM2014-secVD-cabin-heading-240deg": NOT_CHECKABLE,
    "TIM2014-secVD-carouselled-heading-better": NOT_CHECKABLE,
    "TIM2014-secVD-intervals-mismatch": NOT_CHECKABLE,
    "TIM2014-secVD-reference-accuracy": NOT_CHECKABLE,
    "TIM2014-secVD-speed-duration": NOT_CHECKABLE,
    "TIM2014-secVI-assumptions": VERIFIED,
    "TIM2014-secVI-integration-improvement": NOT_CHECKABLE,
    "TIM2014-secVI-processes": VERIFIED,
    "TIM2014-secVI-variance-stationary": VERIFIED,
    "TIM2014-table2-R4": VERIFIED,
}

#: Statuses whose verdicts never carry a corrected form.
WITHOUT_CORRECTED_FORM = frozenset({PROVED, VERIFIED, CONSISTENT, NOT_CHECKABLE})


@pytest.fixture(scope="module")
def verdicts():
    return {item.claim.id: item.verdict for item in run_checks(all_claims(), show_progress=False)}


def test_every_claim_is_pinned_and_every_pin_is_a_claim():
    ids = {claim.id for claim in all_claims()}
    assert sorted(ids - set(PINNED)) == [], "claims without a pinned status"
    assert sorted(set(PINNED) - ids) == [], "pinned statuses of claims that do not exist"


@pytest.mark.parametrize("claim_id", sorted(PINNED))
def test_claim_reaches_its_pinned_status(claim_id, verdicts):
    verdict = verdicts[claim_id]
    assert verdict.status is PINNED[claim_id], (
        f"{claim_id}: pinned {PINNED[claim_id].value!r}, the check found {verdict.status.value!r}: "
        f"{verdict.evidence}"
    )
    assert verdict.evidence.strip(), f"{claim_id}: no evidence"
    if verdict.status in NEEDS_CORRECTED_FORM:
        assert verdict.corrected, f"{claim_id}: a {verdict.status.value} verdict needs its corrected form"
    if verdict.status in WITHOUT_CORRECTED_FORM:
        assert verdict.corrected is None, (
            f"{claim_id}: a {verdict.status.value} verdict has no corrected form"
        )


@pytest.mark.parametrize("claim_id", sorted(c for c, s in PINNED.items() if s is INCONSISTENT))
def test_an_inconsistency_says_what_cannot_be_decided(claim_id, verdicts):
    assert "cannot be decided" in verdicts[claim_id].evidence, claim_id


def test_a_second_run_gives_the_same_verdicts(verdicts):
    fast = [claim for claim in all_claims() if claim.id.startswith(("TIM2014-render", "TIM2014-secVC"))]
    assert [verdicts[claim.id] for claim in fast] == [claim.check() for claim in fast]
