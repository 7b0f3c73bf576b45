"""The lag quadrature of the τ-covariance: each part held to its proved bound.

- the Gauss-block sum against the same c summed over every lag (isolates the quadrature; the proved
  bound plus both sums' rounding allowances, which the bound does not cover: a nine-term value of c
  carries a few ulps of Σ|w_q H|, 10⁶–10⁸ times |c| from half a width to FAR widths out; the allowance is
  held below 1e-8 of the sum so that it cannot hide a quadrature error);
- c itself, including the Newton series of the far tail, against 30-digit mpmath sums Σ_u W(u) γ_z(δ + u);
- the rounding model of the allowance: a nine-term c outside the support within ROUNDING_ULPS ulps of
  Σ_q |w_q H| (plus len(W) ulps of |c|) of the direct sum, for m_j/m_i = 16 and 32;
- the lemma behind the derivative bound: F^{(p)} of F(z) = Γ(z + s)/Γ(z) keeps one sign, |F^{(p)}| falls,
  and |F^{(p)}(j)| ≤ |Δ^p F(j − p)| (mpmath derivatives at 30 digits);
- the discrete Gauss rule integrates polynomials of degree ≤ 2p − 1 over the block's integers exactly;
- the batched sum over many pairs (H tabulated once on the union of their integer arguments) returns,
  value for value and bound for bound, what each pair gives alone;
- c at the Gauss nodes from H on the distinct (q − f, block length) arguments equals the nine-term sum at
  each node to the rounding of the sum (64 ulps of Σ|w_q H|), and a pair batch reused for a second model
  gives what a fresh one gives;
- the sums without their bounds are the sums with them, and the narrow pairs' γ_z shared on the integers
  is each pair's own.
"""

from __future__ import annotations

from dataclasses import replace
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from carousel_theory import lag_quadrature
from carousel_theory.increment_sums import flicker_increment_difference
from carousel_theory.lag_quadrature import (
    PROVED_RULE,
    ROUNDING_ULPS,
    WEIGHTS_RULE,
    LagModel,
    PairBatch,
    _direct_flicker,
    _gauss_rule,
    _gauss_rules,
    _make_pair,
    _nine_term_sum,
    _Pairs,
    _rounding_terms,
    _values,
    combined_sums,
    counted_square_sum,
    counted_square_sums,
    rounding_allowances,
    rounding_scales,
    term_values,
)
from carousel_theory.noise_model import NoiseModel


def _every_lag(model: NoiseModel, m_i: int, m_j: int, length: int) -> tuple[float, float]:
    """(Σ N c² over every lag, its rounding allowance)."""
    K_i, K_j = length - 2 * m_i + 1, length - 2 * m_j + 1
    pair = _make_pair(m_i, m_j, K_i, K_j)
    lags = np.arange(-(K_i - 1), K_j, dtype=np.float64)
    lag_model = LagModel.of(model)
    values, errors = _values(pair, lag_model, lags)
    assert np.all(errors <= 1e-14 * np.max(np.abs(values)))
    owner = np.zeros(len(lags), dtype=np.int64)
    scales = rounding_scales(_Pairs.of([pair]), lag_model, owner, lags, values)
    allowance = float(np.sum(_rounding_terms(pair.count(lags), values, scales)))
    return float(np.dot(pair.count(lags), values * values)), allowance


def _flicker_model(d: float, with_ar: bool) -> NoiseModel:
    """White + RRW + 1/f of order d, with AR(1) short noise or not."""
    return NoiseModel(
        sample_rate=1.0,
        white_variance=0.5,
        rrw_variance=1e-6,
        flicker_variance=1.0,
        flicker_d=d,
        ar_variance=0.3 if with_ar else 0.0,
        ar_coefficients=(0.7,) if with_ar else (),
    )


@pytest.mark.parametrize("rule", [PROVED_RULE, WEIGHTS_RULE])
@given(
    d=st.floats(min_value=0.02, max_value=0.98),
    m_i=st.sampled_from([1, 2, 3, 8, 50, 256]),
    ratio=st.sampled_from([1, 2, 4, 16]),
    length=st.integers(min_value=5_000, max_value=60_000),
    with_ar=st.booleans(),
)
def test_gauss_blocks_equal_every_lag_summed_within_the_bound(rule, d, m_i, ratio, length, with_ar):
    """Both rules within their proved bound plus both sums' rounding allowances (the bound is for exact
    arithmetic: module text, Rounding). PROVED_RULE's bound is below 10⁻¹¹ of the sum, and its values
    are within the rounding allowances plus 10⁻¹¹ of the sum. WEIGHTS_RULE's (4 points, blocks up to
    their distance from the breakpoint, 16 exact lags) bound is loose, and its values are within the
    allowances plus 2·10⁻⁷ of the sum, its stated accuracy (measured up to 1.1·10⁻⁷ at d = 0.5,
    m_j/m_i = 16; an 8-point rule of the same blocks stays within 10⁻¹¹, a 6-point one within 5·10⁻¹¹)."""
    model = _flicker_model(d, with_ar)
    m_j = m_i * ratio
    assume(3 * m_j <= length)  # at least three clusters, as the fit requires
    pair = (m_i, m_j, length - 2 * m_i + 1, length - 2 * m_j + 1)
    lag_model = LagModel.of(model)
    total, bound = counted_square_sum(lag_model, *pair, rule=rule)
    (rounding,) = rounding_allowances(lag_model, [pair], rule)
    reference, reference_rounding = _every_lag(model, m_i, m_j, length)
    assert abs(total - reference) <= bound + rounding + reference_rounding
    accuracy = 1e-11 if rule == PROVED_RULE else 2e-7
    assert abs(total - reference) <= rounding + reference_rounding + accuracy * reference
    assert rounding + reference_rounding <= 1e-8 * reference
    if rule == PROVED_RULE:
        assert bound <= 1e-11 * reference


@pytest.mark.parametrize("d", ["0.3", "0.5", "0.9"])
@pytest.mark.parametrize(("m_i", "m_j"), [(1, 1), (3, 12), (64, 64)])
def test_cross_covariance_against_mpmath(d, m_i, m_j):
    # c(δ) = Σ_u W(u) γ_z(δ + u) at 30 digits, W = g_i ⋆ g_j; the lags reach the Newton-series tail.
    model = NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=float(d))
    span = 2 * m_i + 2 * m_j - 4
    lags = np.array([0, 1, -m_j, 2 * m_i + 40, 17 * max(span, 1) + 2 * m_i + 5, -30 * max(span, 1) - 2 * m_j])
    pair = _make_pair(m_i, m_j, 10**6, 10**6)
    values, errors = _values(pair, LagModel.of(model), lags.astype(np.float64))
    triangle_i = [min(k + 1, 2 * m_i - 1 - k) for k in range(2 * m_i - 1)]
    triangle_j = [min(k + 1, 2 * m_j - 1 - k) for k in range(2 * m_j - 1)]
    with mpmath.workdps(30):
        order = mpmath.mpf(d)
        start = mpmath.gamma(3 - 2 * order) / mpmath.gamma(2 - order) ** 2

        def gamma(k: int) -> mpmath.mpf:
            return start * mpmath.rf(2 - order, abs(k)) ** -1 * mpmath.rf(order - 1, abs(k))

        for lag, value, error in zip(lags.tolist(), values, errors, strict=True):
            exact = mpmath.fsum(
                a * b * gamma(lag + (k_j - k_i) + 2 * m_j - 2 - (2 * m_j - 2))
                for k_i, a in enumerate(triangle_i)
                for k_j, b in enumerate(triangle_j)
            )
            assert abs(value - float(exact)) <= error + 1e-12 * abs(float(exact))


@pytest.mark.parametrize("d", ["0.3", "0.5", "0.9"])
@pytest.mark.parametrize(("m_i", "m_j"), [(1, 1), (3, 12), (20, 80), (64, 64)])
def test_direct_sum_outside_the_support_against_mpmath(d, m_i, m_j):
    # c(δ) = Σ_u W(u) γ_z(δ + u) at non-integer δ on either side of the support (the narrow pairs' Gauss
    # nodes), γ_z(x) = C_d Γ(x + d − 1)/Γ(x + 2 − d) at 30 digits; the package runs the Gamma ratio up the
    # arguments by its one-step ratio, which may cost about len(W) ulps.
    lag_model = LagModel.of(NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=float(d)))
    above = 2 * m_i - 2 + np.array([1.37, 6.87, 301.62])
    below = -(2 * m_j - 2) - np.array([1.61, 9.11, 250.5])
    lags = np.concatenate((above, below))
    values = _direct_flicker(m_i, m_j, lag_model, lags)
    window = np.convolve(
        [min(k + 1, 2 * m_i - 1 - k) for k in range(2 * m_i - 1)][::-1],
        [min(k + 1, 2 * m_j - 1 - k) for k in range(2 * m_j - 1)],
    )
    with mpmath.workdps(30):
        order = mpmath.mpf(d)
        scale = mpmath.gamma(3 - 2 * order) / (mpmath.gamma(2 - order) * mpmath.gamma(order - 1))
        for lag, value in zip(lags.tolist(), values, strict=True):
            exact = mpmath.fsum(
                int(w) * scale * mpmath.gamma(x + order - 1) / mpmath.gamma(x + 2 - order)
                for u, w in enumerate(window.tolist(), start=-(2 * m_i - 2))
                for x in [abs(mpmath.mpf(lag) + u)]
            )
            assert abs(value - float(exact)) <= 1e-13 * abs(float(exact))


@pytest.mark.parametrize("d", ["0.1", "0.45", "0.55", "0.95"])
@pytest.mark.parametrize("j", [15, 40, 1000])
def test_derivative_lemma(d, j):
    # F(z) = Γ(z + s)/Γ(z), s = 1 + 2d, z = j − d: F^{(p)} one-signed and falling in magnitude for p > s,
    # and bounded by the p-th forward difference taken p steps back (the bound the quadrature uses).
    p = WEIGHTS_RULE.points if d in ("0.1", "0.95") else PROVED_RULE.points
    with mpmath.workdps(30):
        s = 1 + 2 * mpmath.mpf(d)

        def F(y):
            return mpmath.gamma(y - mpmath.mpf(d) + s) / mpmath.gamma(y - mpmath.mpf(d))

        values = [mpmath.diff(F, j + t, p) for t in (0, 1, 3)]
        assert all(mpmath.sign(v) == mpmath.sign(values[0]) for v in values)
        assert abs(values[0]) > abs(values[1]) > abs(values[2])
        difference = mpmath.fsum((-1) ** (p - k) * mpmath.binomial(p, k) * F(j - p + k) for k in range(p + 1))
        assert abs(values[0]) <= abs(difference)


@pytest.mark.parametrize("points", [PROVED_RULE.points, WEIGHTS_RULE.points])
def test_gauss_rules_of_many_lengths_at_once_are_each_length_alone(points, monkeypatch):
    """One stacked eigh gives, bit for bit, the rule of each length computed alone."""
    lengths = [points + 1, 25, 64, 97, 1000, 4097, 65_535, 2**20]
    known: dict = {}
    monkeypatch.setattr(lag_quadrature, "_GAUSS_RULES", known)
    alone = []
    for length in lengths:
        known.clear()
        alone.append(_gauss_rule(length, points))
    known.clear()
    together = _gauss_rules(lengths[::-1], points)[::-1]
    for one, other in zip(alone, together, strict=True):
        assert np.array_equal(one[0], other[0]) and np.array_equal(one[1], other[1]) and one[2] == other[2]


@pytest.mark.parametrize("points", [PROVED_RULE.points, WEIGHTS_RULE.points])
@pytest.mark.parametrize("length", [25, 64, 1000, 2**20])
def test_discrete_gauss_rule_is_exact_to_degree_2p_minus_1(length, points):
    offsets, weights, log_norm = _gauss_rule(length, points)
    for degree in (0, 1, 7, 2 * points - 1):
        scaled = offsets / (length - 1)
        exact = sum(Fraction(t, length - 1) ** degree for t in range(length)) if length < 5000 else None
        got = float(np.dot(weights, scaled**degree))
        if exact is not None:
            assert got == pytest.approx(float(exact), rel=1e-12)
    assert np.isfinite(log_norm)
    assert np.all(weights > 0)


@given(
    d=st.floats(min_value=0.02, max_value=0.98),
    sizes=st.lists(st.integers(min_value=1, max_value=400), min_size=1, max_size=5, unique=True),
    length=st.integers(min_value=2_000, max_value=300_000),
    with_ar=st.booleans(),
    with_flicker=st.booleans(),
)
def test_batched_pairs_equal_each_pair_alone(d, sizes, length, with_ar, with_flicker):
    model = NoiseModel(
        sample_rate=1.0,
        white_variance=0.5,
        rrw_variance=1e-6,
        flicker_variance=1.0 if with_flicker else 0.0,
        flicker_d=d,
        ar_variance=0.3 if with_ar else 0.0,
        ar_coefficients=(0.7,) if with_ar else (),
    )
    sizes = sorted(sizes)
    assume(3 * sizes[-1] <= length)
    terms = [length - 2 * m + 1 for m in sizes]
    pairs = [(sizes[i], sizes[j], terms[i], terms[j]) for j in range(len(sizes)) for i in range(j + 1)]
    lag_model = LagModel.of(model)
    batched = counted_square_sums(lag_model, pairs)
    alone = [counted_square_sum(lag_model, *pair) for pair in pairs]
    # Each row is reduced in its own order: a batch gives every pair what it gives alone (both sides use
    # the tabulated H; the table against direct evaluation is test_fourth_sum_table_is_direct_evaluation).
    assert batched == alone


@given(
    d=st.floats(min_value=0.02, max_value=0.98),
    length=st.integers(min_value=40_000, max_value=400_000),
    with_ar=st.booleans(),
)
def test_sums_without_bounds_are_the_sums_with_them(d, length, with_ar):
    # bounds=False skips the far-tail remainders, the derivative bounds and their sums, nothing else.
    sizes = [2**k for k in range(14) if 3 * 2**k <= length]
    terms = [length - 2 * m + 1 for m in sizes]
    pairs = [(sizes[i], sizes[j], terms[i], terms[j]) for j in range(len(sizes)) for i in range(j + 1)]
    lag_model = LagModel.of(_flicker_model(d, with_ar))
    with_bounds = counted_square_sums(lag_model, pairs)
    without = counted_square_sums(lag_model, pairs, bounds=False)
    assert [total for total, _ in without] == [total for total, _ in with_bounds]
    assert all(np.isnan(bound) for _, bound in without)
    assert all(bound > 0 for _, bound in with_bounds)


@given(
    d=st.floats(min_value=0.02, max_value=0.98),
    m_i=st.integers(min_value=1, max_value=64),
    ratio=st.sampled_from([1, 2, 4]),
    first=st.integers(min_value=-2000, max_value=2000),
    count=st.integers(min_value=1, max_value=300),
)
def test_direct_flicker_from_shared_integers_is_the_pairs_own(d, m_i, ratio, first, count):
    # γ_z tabulated once on 0 … the largest |δ + u| (shared by the narrow pairs of a batch) gives, bit for
    # bit, what the pair's own evaluation on the integers its lags reach gives; non-integer lags outside
    # the support take their own path either way.
    m_j = m_i * ratio
    lag_model = LagModel.of(_flicker_model(d, False))
    outside = 2.0 * m_j + 10.5 + np.arange(3)  # beyond the support, not integers
    lags = np.concatenate((np.arange(first, first + count, dtype=np.float64), outside))
    reach = int(np.max(np.abs(lags))) + 2 * m_j
    integers = flicker_increment_difference(np.arange(reach + 1, dtype=np.float64), d)
    shared = _direct_flicker(m_i, m_j, lag_model, lags, integers)
    np.testing.assert_array_equal(shared, _direct_flicker(m_i, m_j, lag_model, lags))


@pytest.mark.parametrize("with_ar", [False, True])
def test_fourth_sum_table_is_direct_evaluation(with_ar):
    """At the exact lags of many pairs, c from H tabulated on the merged argument runs (the pair batch's
    gather, which the covariance uses) is the nine-term sum of H evaluated at each lag, to the rounding of
    a fused multiply-add where the platform's sparse product uses one (exactly equal otherwise)."""
    model = NoiseModel(
        sample_rate=1.0,
        white_variance=0.5,
        rrw_variance=1e-6,
        flicker_variance=1.0,
        flicker_d=0.3,
        ar_variance=0.3 if with_ar else 0.0,
        ar_coefficients=(0.7,) if with_ar else (),
    )
    length, sizes = 200_000, [1, 2, 4, 16, 128, 1024]
    terms = [length - 2 * m + 1 for m in sizes]
    pairs = [(sizes[i], sizes[j], terms[i], terms[j]) for j in range(len(sizes)) for i in range(j + 1)]
    lag_model = LagModel.of(model)
    batch = PairBatch.of(pairs, lag_model.reach)
    near = batch.lag_parts[3]
    assert np.count_nonzero(near) > 1000
    got = batch.lag_gather.values(lag_model)
    _assert_gathered_are_nine_term_sums(batch, lag_model, batch.lag_owner[near], batch.lags[near], got, 16)


def _assert_node_values_are_nine_term_sums(batch, lag_model, near):
    """The gathered values at the ``near`` Gauss nodes against the direct nine-term sum, to 64 ulps of the
    sum's magnitude (the node arguments (q − f) − o round the offset)."""
    owner, nodes = batch.node_owner[near], batch.nodes[near]
    got = batch.node_gather.values(lag_model)
    _assert_gathered_are_nine_term_sums(batch, lag_model, owner, nodes, got, 64)


def _assert_gathered_are_nine_term_sums(batch, lag_model, owner, lags, got, ulps):
    """``got`` against the direct nine-term sum at ``lags`` of the pairs ``owner``, to ``ulps`` of Σ|wH|."""
    direct = _nine_term_sum(batch.pairs, lag_model, owner, lags)
    arguments = batch.pairs.positions[owner] - lags[:, None]
    magnitude = np.einsum(
        "ij,ij->i",
        np.abs(lag_model.fourth_sum(arguments.ravel()).reshape(arguments.shape)),
        np.abs(batch.pairs.weights[owner]),
    )
    assert np.all(np.abs(got - direct) <= ulps * np.finfo(float).eps * magnitude)


@given(
    d=st.floats(min_value=0.02, max_value=0.98),
    length=st.integers(min_value=40_000, max_value=400_000),
    with_ar=st.booleans(),
)
def test_gridded_node_values_equal_the_nine_term_sum(d, length, with_ar):
    model = _flicker_model(d, with_ar)
    sizes = [2**k for k in range(14) if 3 * 2**k <= length]
    terms = [length - 2 * m + 1 for m in sizes]
    pairs = [(sizes[i], sizes[j], terms[i], terms[j]) for j in range(len(sizes)) for i in range(j + 1)]
    lag_model = LagModel.of(model)
    batch = PairBatch.of(pairs, lag_model.reach)
    near = batch.node_parts[3]
    assert np.any(near)
    _assert_node_values_are_nine_term_sums(batch, lag_model, near)
    # The batch holds only the pairs' structure: reused for another model it gives a fresh batch's sums.
    other = LagModel.of(replace(model, flicker_d=1.0 - d, white_variance=2.0))
    reused = combined_sums(batch, [term_values(batch, other)], [1.0])
    fresh_batch = PairBatch.of(pairs, other.reach)
    assert reused == combined_sums(fresh_batch, [term_values(fresh_batch, other)], [1.0])


@pytest.mark.parametrize("length", [20_000_000, 43_200_000])
def test_gridded_node_values_hold_for_blocks_longer_than_four_million_lags(length):
    # Gauss blocks grow with the distance from the support; at these lengths some exceed 2²² lags, and the
    # node arguments must still be the nine-term sum's (not another block's, nor a singular rule).
    model = _flicker_model(0.3, True)
    sizes = [2**k for k in (0, 4, 12, 20, 22) if 3 * 2**k <= length]
    terms = [length - 2 * m + 1 for m in sizes]
    pairs = [(sizes[i], sizes[j], terms[i], terms[j]) for j in range(len(sizes)) for i in range(j + 1)]
    lag_model = LagModel.of(model)
    batch = PairBatch.of(pairs, lag_model.reach)
    near = batch.node_parts[3]
    blocks = batch.block_ends[:, 1] - batch.block_ends[:, 0] + 1
    assert blocks.max() > 2**22
    _assert_node_values_are_nine_term_sums(batch, lag_model, near)


@given(
    d=st.floats(min_value=0.02, max_value=0.98),
    m_i=st.sampled_from([1, 3, 8, 50]),
    ratio=st.sampled_from([16, 32]),
    widths=st.floats(min_value=0.05, max_value=4.0),
)
def test_nine_term_value_rounding_is_within_its_allowance(d, m_i, ratio, widths):
    # The rounding model behind rounding_allowances: a nine-term c outside the support against the direct
    # sum Σ_u W(u) γ_z(δ + u) (positive weights, γ_z of one sign there: accurate to about len(W) ulps).
    m_j = m_i * ratio
    lag_model = LagModel.of(NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=d))
    pairs = _Pairs.of([_make_pair(m_i, m_j, 10**6, 10**6)])
    width = float(pairs.width()[0])
    offset = 2 * m_i - 2 + np.ceil(widths * width + np.arange(5.0))  # x₀ = δ − (2m_i − 2) ≥ 1 above
    lags = np.concatenate((offset, -offset - (2 * m_j - 2) + (2 * m_i - 2)))
    owner = np.zeros(len(lags), dtype=np.int64)
    nine_term = _nine_term_sum(pairs, lag_model, owner, lags)
    direct = _direct_flicker(m_i, m_j, lag_model, lags)
    terms = lag_model.fourth_sum(pairs.positions[owner] - lags[:, None]) * pairs.weights[owner]
    scale = np.sum(np.abs(terms), axis=1) + (2 * m_i + 2 * m_j - 3) * np.abs(direct)
    unit = np.finfo(np.float64).eps / 2
    assert np.all(np.abs(nine_term - direct) <= ROUNDING_ULPS * unit * scale)
