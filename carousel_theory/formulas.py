"""The registry of named closed forms: expression, assumptions, source equation and evaluators.

>>> from carousel_theory.formulas import formula
>>> formula("rrw_average_var").exact(N=2, k=2)
13/4

Every entry is a :class:`Formula`. Unit driving variance throughout (σ_q² = σ_WN² = σ_w² = 1:
multiply by it), bins numbered from 1. The SymPy expressions live in
:mod:`carousel_theory.closed_forms`; the two 1/f entries have no closed form (``expression`` is
None) and delegate to :mod:`carousel_theory.propagation`.
"""

from __future__ import annotations

import numbers
from collections.abc import Callable
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np
import sympy as sp

from carousel_theory import closed_forms as cf
from carousel_theory import symbols
from carousel_theory._validation import (
    check_boolean,
    check_correlation,
    check_fractional_order,
    check_positive_integer,
    check_positive_real,
    check_real,
)
from carousel_theory.evaluation_cost import (
    EvaluationCost,
    check_budget,
    closed_form_cost,
    exact_flicker_cost,
    float_flicker_cost,
    high_precision_flicker_cost,
)

__all__ = ["FORMULAS", "PARAMETER_HELP", "Formula", "formula", "restricted_to_samples"]

# --------------------------------------------------------------------------------------------
# Parameters: one rule per name, shared by every formula
# --------------------------------------------------------------------------------------------

_BIN_PARAMETERS = ("a", "b", "k")
#: What each parameter means (shown by ``carousel-theory formula --list``).
PARAMETER_HELP = {
    "N": "samples per bin (carouseling revolution), an integer",
    "a": "first bin number, an integer >= 1",
    "b": "second bin number, an integer >= 1",
    "k": "bin number, an integer >= 1",
    "rho": "correlation of the two gyros' RRW increments, in [-1, 1]",
    "var_x": "white-noise variance of the x gyro, >= 0",
    "var_y": "white-noise variance of the y gyro, >= 0",
    "d": "degree of fractional integration, 0 < d < 1",
    "g": "indexing: transition samples after each dwell, dropped from the estimate, an integer >= 0",
    "n": "samples used by the estimate, an integer >= 1",
    "beta": "encoder offset, rad",
    "sigma_e": "encoder white noise per sample, rad, >= 0",
    "sigma_nu": "angle random walk per sample (unmeasured angle), rad, >= 0",
    "k_x": "scale-factor error of the x gyro (relative)",
    "k_y": "scale-factor error of the y gyro (relative)",
    "psi": "true heading, rad",
    "epsilon": "tilt of a gyro's sensing axis toward the rotation axis, rad",
    "wobble": "relative amplitude of a once-per-turn rotation-rate wobble, >= 0",
    "omega_r": "rotation rate, rad/s, > 0",
}
#: Rules of the rotation-scheme imperfection parameters (beyond TIM 2014).
_REAL_PARAMETERS = ("beta", "k_x", "k_y", "psi", "epsilon")
_NONNEGATIVE_PARAMETERS = ("sigma_e", "sigma_nu", "wobble")


def _check_scalar(name: str, value: Any, minimum_samples: int) -> Any:
    if name == "N":
        return check_positive_integer("N", value, minimum=minimum_samples)
    if name in _BIN_PARAMETERS:
        return check_positive_integer(name, value)
    if name == "g":
        return check_positive_integer("g", value, minimum=0)
    if name == "n":
        return check_positive_integer("n", value)
    if name in _REAL_PARAMETERS:
        return check_real(name, value)
    if name in _NONNEGATIVE_PARAMETERS:
        return check_positive_real(name, value, allow_zero=True)
    if name == "omega_r":
        return check_positive_real("omega_r", value)
    if name == "rho":
        return check_correlation("rho", value)
    if name in ("var_x", "var_y"):
        return check_positive_real(name, value, allow_zero=True)
    if name == "d":
        return check_fractional_order("d", value)
    raise AssertionError(f"no rule for parameter {name!r}")  # pragma: no cover - registry is fixed


def _to_sympy_exact(name: str, value: Any) -> sp.Expr:
    """An exact SymPy number for an exact input; TypeError for a float (its value is not exact)."""
    if isinstance(value, sp.Rational):
        return value
    if isinstance(value, numbers.Integral):
        return sp.Integer(int(value))
    if isinstance(value, Fraction):
        return sp.Rational(value.numerator, value.denominator)
    raise TypeError(
        f"{name}={value!r}: must be exact (int, fractions.Fraction or sympy Rational) for exact(); "
        "use evaluate() or numeric() for floats"
    )


def _to_sympy_any(name: str, value: Any) -> sp.Expr:
    """Exact inputs stay exact; a float or mpf is taken at its exact binary value."""
    if isinstance(value, (sp.Rational, numbers.Integral, Fraction)):
        return _to_sympy_exact(name, value)
    if isinstance(value, mpmath.mpf):
        mantissa, exponent = value.man_exp
        return sp.Integer(int(mantissa)) * sp.Integer(2) ** int(exponent)
    if isinstance(value, sp.Basic):
        return sp.nsimplify(value, rational=True)
    return sp.Rational(float(value))


def _check_array(name: str, value: Any, minimum_samples: int) -> np.ndarray:
    """Array form of :func:`_check_scalar` for ``numeric``: integer dtypes for N and bins."""
    if np.ndim(value) == 0:
        if name == "N" or name in _BIN_PARAMETERS or name in ("g", "n"):
            return np.asarray(float(_check_scalar(name, value, minimum_samples)))
        return np.asarray(float(_check_scalar(name, value, minimum_samples)), dtype=np.float64)
    array = np.asarray(value)
    if name == "N" or name in _BIN_PARAMETERS or name in ("g", "n"):
        if array.dtype.kind not in "iu":
            raise TypeError(f"{name}={value!r}: must be an integer array (dtype {array.dtype} given)")
        minimum = minimum_samples if name == "N" else 0 if name == "g" else 1
        if array.size and array.min() < minimum:
            bad = array.flat[int(np.argmin(array))].item()
            raise ValueError(f"{name}={bad!r}: must be an integer >= {minimum}")
        return array.astype(np.float64)  # float64: (N + 1)(2N + 1) would overflow int64 for N > 2·10⁹
    if array.dtype.kind not in "iuf":
        raise TypeError(f"{name}={value!r}: must be an array of real numbers")
    floats = array.astype(np.float64)
    for element in floats.flat:  # NaN, range: the scalar rules, element by element
        check_real(name, float(element))
        _check_scalar(name, float(element), minimum_samples)
    return floats


#: The parameters of every entry without a closed form (the 1/f bin variances).
_DELEGATED_PARAMETERS = ("d", "N", "k")
#: Why the carouselled variances of every bin are undefined at N = 1.
_BELOW_MINIMUM_SAMPLES = (
    "at N = 1 nothing is carouselled and the bin variance depends on the bin: use rrw_carousel_cov"
)

# --------------------------------------------------------------------------------------------
# The Formula
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Formula:
    """A named closed form with its evaluators.

    ``expression`` is a SymPy expression in the symbols of :mod:`carousel_theory.symbols` (or None
    when there is no closed form; then ``delegate_bins`` computes bins 1 … k_max in float64,
    ``delegate_mp`` one bin at any precision and ``delegate_exact``, if given, an exact one; the
    delegated entries take the parameters (d, N, k)). ``minimum_samples`` is the smallest N the
    formula is defined for: the one N rule that ``exact``, ``evaluate``, ``numeric``, the expression
    (its branches below the minimum are dropped, see :func:`restricted_to_samples`) and every export
    (:mod:`carousel_theory.export`) follow.
    """

    name: str
    parameters: tuple[str, ...]
    expression: sp.Expr | None
    assumptions: str
    source: str
    description: str
    minimum_samples: int = 1
    latex_text: str | None = None
    delegate_bins: Callable[..., np.ndarray] | None = field(default=None, repr=False, compare=False)
    delegate_mp: Callable[..., Any] | None = field(default=None, repr=False, compare=False)
    delegate_exact: Callable[..., Any] | None = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.expression is None:
            assert self.parameters == _DELEGATED_PARAMETERS, self.name
        elif self.minimum_samples > 1:
            restricted = restricted_to_samples(self.expression, self.minimum_samples)
            object.__setattr__(self, "expression", restricted)

    # -- argument handling --------------------------------------------------------------------

    def sample_rule(self) -> str:
        """The rule on N as a message tail: ``must be an integer >= 2 for … (why)``."""
        if self.minimum_samples == 1:
            return "must be an integer >= 1"
        return f"must be an integer >= {self.minimum_samples} for {self.name} ({_BELOW_MINIMUM_SAMPLES})"

    def _checked(self, values: dict[str, Any]) -> dict[str, Any]:
        missing = [p for p in self.parameters if p not in values]
        unknown = sorted(set(values) - set(self.parameters))
        if unknown:
            raise TypeError(
                f"{self.name}: unknown parameter(s) {unknown}; parameters are {list(self.parameters)}"
            )
        if missing:
            raise TypeError(
                f"{self.name}: missing parameter(s) {missing}; parameters are {list(self.parameters)}"
            )
        if "N" in values:
            self._check_sample_count(check_positive_integer("N", values["N"]))
        return {p: _check_scalar(p, values[p], self.minimum_samples) for p in self.parameters}

    def _check_sample_count(self, value: Any) -> None:
        """ValueError with :meth:`sample_rule` for an integer N (or integer array) below the minimum."""
        array = np.asarray(value)
        if self.minimum_samples > 1 and array.dtype.kind in "iu" and array.size:
            smallest = array.flat[int(np.argmin(array))].item()
            if smallest < self.minimum_samples:
                raise ValueError(f"N={smallest!r}: {self.sample_rule()}")

    def _substitute(self, converted: dict[str, sp.Expr]) -> sp.Expr:
        assert self.expression is not None
        mapping = {getattr(symbols, p): converted[p] for p in self.parameters}
        return self.expression.subs(mapping)

    def _call_text(self, values: dict[str, Any]) -> str:
        return f"{self.name}({', '.join(f'{p}={values[p]}' for p in self.parameters)})"

    # -- evaluators -----------------------------------------------------------------------------

    def exact(self, *, force: bool = False, **values: Any) -> sp.Expr:
        """The exact SymPy value for exact inputs (int, Fraction, sympy Rational).

        Raises ValueError when no exact form exists, TypeError for a float input, and
        :class:`~carousel_theory.evaluation_cost.EvaluationBudgetError` (a ValueError) when the
        estimated cost exceeds the budget, unless ``force=True``.
        """
        force = check_boolean("force", force)
        checked = self._checked(values)
        converted = {p: _to_sympy_exact(p, v) for p, v in checked.items()}
        if self.expression is not None:
            return self._substitute(converted)
        if self.delegate_exact is None:
            raise ValueError(f"{self.name}: no exact form (use evaluate() at any precision)")
        order = converted["d"]
        steps = int(converted["N"]) * int(converted["k"])
        cost = exact_flicker_cost(f"{self._call_text(checked)} exactly", steps, int(sp.denom(order)))
        check_budget(cost, force=force)
        value = self.delegate_exact(**{p: _as_python(v) for p, v in converted.items()})
        return sp.Rational(value.numerator, value.denominator)

    def evaluation_cost(self, digits: int = 50, **values: Any) -> EvaluationCost:
        """The estimated cost of ``evaluate(digits, **values)`` (checked like ``evaluate``)."""
        digits = check_positive_integer("digits", digits)
        checked = self._checked(values)
        what = f"{self._call_text(checked)} at {digits} digits"
        if self.expression is None:
            return high_precision_flicker_cost(what, int(checked["N"]) * int(checked["k"]), digits)
        return closed_form_cost(what, digits)

    def evaluate(self, digits: int = 50, *, force: bool = False, **values: Any) -> mpmath.mpf:
        """The value as an ``mpmath.mpf`` correct to ``digits`` significant digits.

        Refused with :class:`~carousel_theory.evaluation_cost.EvaluationBudgetError` when the
        estimated cost (:meth:`evaluation_cost`) exceeds the budget, unless ``force=True``.
        """
        force = check_boolean("force", force)
        check_budget(self.evaluation_cost(digits, **values), force=force)
        checked = self._checked(values)
        if self.expression is None:
            assert self.delegate_mp is not None
            with mpmath.workdps(digits):
                return +self.delegate_mp(**checked, digits=digits)
        converted = {p: _to_sympy_any(p, v) for p, v in checked.items()}
        value = self._substitute(converted)
        decimal = sp.Float(value.evalf(digits + 10), digits + 10)  # evalf tracks its own error
        with mpmath.workdps(digits):
            # Binary to binary: no decimal string, so no limit on int-string conversion digits.
            return +mpmath.mpf(decimal._mpf_)

    def numeric(self, *, force: bool = False, **values: Any) -> Any:
        """float64 value; broadcasts over array arguments like a NumPy ufunc.

        The 1/f entries group the arguments by (d, N) and take all bins 1 … max k of a group from
        one FFT (:func:`carousel_theory.propagation.flicker_bin_variances`); refused when that
        FFT's estimated cost exceeds the budget, unless ``force=True``.
        """
        force = check_boolean("force", force)
        missing = [p for p in self.parameters if p not in values]
        unknown = sorted(set(values) - set(self.parameters))
        if unknown or missing:
            self._checked(values)  # raises the TypeError naming them
        if "N" in values and not isinstance(values["N"], bool):
            self._check_sample_count(values["N"])
        checked = [_check_array(p, values[p], self.minimum_samples) for p in self.parameters]
        arrays = np.broadcast_arrays(*checked)
        scalar = all(np.ndim(values[p]) == 0 for p in self.parameters)
        if self.expression is None:
            result = self._numeric_from_bins(*arrays, force=force)
        else:
            result = np.asarray(_lambdified(self.name, self)(*arrays), dtype=np.float64)
            result = np.broadcast_to(result, arrays[0].shape if arrays else ()).copy()
        return float(result) if scalar else result

    def _numeric_from_bins(self, d: np.ndarray, N: np.ndarray, k: np.ndarray, *, force: bool) -> np.ndarray:
        assert self.delegate_bins is not None
        groups = np.unique(np.stack([d.ravel(), N.ravel()]), axis=1).T if d.size else np.empty((0, 2))
        masks = [(d == order) & (samples == N) for order, samples in groups]
        last_bins = [int(k[mask].max()) for mask in masks]
        length = sum(int(samples) * bins for (_, samples), bins in zip(groups, last_bins, strict=True))
        check_budget(float_flicker_cost(f"{self.name} numeric", length), force=force)
        result = np.empty(d.shape, dtype=np.float64)
        for (order, samples), mask, bins in zip(groups, masks, last_bins, strict=True):
            variances = self.delegate_bins(float(order), int(samples), bins)
            result[mask] = variances[k[mask].astype(np.int64) - 1]
        return result

    def latex(self) -> str:
        """The formula in LaTeX (the defining expression when there is no closed form)."""
        if self.expression is None:
            assert self.latex_text is not None
            return self.latex_text
        return sp.latex(self.expression)


def restricted_to_samples(expression: sp.Expr, minimum_samples: int) -> sp.Expr:
    """``expression`` without its Piecewise branches for N = 1 … minimum_samples − 1.

    Below its minimum a formula has no value: the branch that gave one (e.g. rrw_carousel_var = 1
    at N = 1, the first bin's variance only) is removed, so that the expression is undefined there
    (csc²(π/N) at N = 1 is SymPy's complex infinity) like ``exact`` and ``numeric``, which refuse.
    """

    def below(condition: Any) -> bool:
        return (
            isinstance(condition, sp.Eq)
            and condition.lhs == symbols.N
            and condition.rhs.is_Integer
            and int(condition.rhs) < minimum_samples
        )

    def drop(piecewise: sp.Piecewise) -> sp.Expr:
        return sp.Piecewise(
            *[(term, condition) for term, condition in piecewise.args if not below(condition)]
        )

    return expression.replace(lambda node: isinstance(node, sp.Piecewise), drop)


def _as_python(value: sp.Expr) -> Any:
    """SymPy Integer → int, Rational → Fraction (what the numeric modules accept)."""
    if value.is_Integer:
        return int(value)
    return Fraction(int(value.p), int(value.q))


_LAMBDIFIED: dict[str, Callable[..., Any]] = {}


def _lambdified(name: str, entry: Formula) -> Callable[..., Any]:
    if name not in _LAMBDIFIED:
        arguments = [getattr(symbols, p) for p in entry.parameters]
        # No docstring: printing the expression for it costs more than the lambdification.
        _LAMBDIFIED[name] = sp.lambdify(arguments, entry.expression, "numpy", docstring_limit=0)
    return _LAMBDIFIED[name]


# --------------------------------------------------------------------------------------------
# 1/f noise: no closed form; delegate to carousel_theory.propagation (imported when first used)
# --------------------------------------------------------------------------------------------


def _flicker_averaged_bins(d: float, N: int, k_max: int) -> np.ndarray:
    from carousel_theory.propagation import flicker_bin_variances

    return flicker_bin_variances(d, N, k_max, "averaged")


def _flicker_averaged_mp(d: Any, N: int, k: int, digits: int) -> Any:
    from carousel_theory.propagation import flicker_averaged_bin_variance

    return flicker_averaged_bin_variance(d, N, k, digits=digits)


def _flicker_averaged_exact(d: Any, N: int, k: int) -> Fraction:
    from carousel_theory.propagation import flicker_averaged_bin_variance_exact

    return flicker_averaged_bin_variance_exact(Fraction(d), N, k)


def _flicker_carouselled_bins(d: float, N: int, k_max: int) -> np.ndarray:
    from carousel_theory.propagation import flicker_bin_variances

    return flicker_bin_variances(d, N, k_max, "carouselled")


def _flicker_carouselled_mp(d: Any, N: int, k: int, digits: int) -> Any:
    from carousel_theory.propagation import flicker_carouselled_bin_variance

    return flicker_carouselled_bin_variance(d, N, k, digits=digits)


# --------------------------------------------------------------------------------------------
# The registry
# --------------------------------------------------------------------------------------------

_RRW = "RRW r_t = r_{t-1} + q_t from r_0 = 0 (TIM 2014 eq. (2)), unit increment variance σ_q² = 1"
_CAROUSEL = (
    "uniform carouseling, N samples per revolution, weights sin(2πi/N)/N and cos(2πi/N)/N, "
    "i = 1..N (TIM 2014 eq. (13)); estimate −Σ s_i ω_x + Σ c_i ω_y (eq. (6))"
)
_INDEPENDENT = "the two gyros' increments independent and identically distributed (TIM 2014 §III-C)"
_N1 = (
    "N >= 2: at N = 1 the single cosine weight is cos 2π = 1, nothing is carouselled and the bin "
    "variance depends on the bin (see rrw_carousel_cov)"
)

_DEMODULATED = (
    "two horizontal gyros turned about the vertical, demodulated mean of carousel_theory.rotation_schemes"
)

_ENTRIES = [
    Formula(
        "bias_carousel_residual",
        ("N",),
        cf.BIAS_CAROUSEL_RESIDUAL,
        f"unit additive biases b_x = b_y = 1 (TIM 2014 eq. (1)); {_CAROUSEL}",
        "TIM 2014 eq. (8), both gyros, exact for every N",
        "What a unit bias on each gyro leaves in the carouselled estimate: 0 for N >= 2, 1 at N = 1.",
    ),
    Formula(
        "bias_carousel_residual_cos",
        ("N",),
        cf.BIAS_COSINE_RESIDUAL,
        f"unit additive bias; {_CAROUSEL}",
        "TIM 2014 eq. (8), cosine companion, exact for every N",
        "(1/N) Σ_{i=1}^{N} cos(2πi/N): the sum of the N-th roots of unity over N, 1 at N = 1, else 0.",
    ),
    Formula(
        "bias_carousel_residual_sin",
        ("N",),
        cf.BIAS_SINE_RESIDUAL,
        f"unit additive bias; {_CAROUSEL}",
        "TIM 2014 eq. (8), exact for every N",
        "(1/N) Σ_{i=1}^{N} sin(2πi/N): zero for every N >= 1 (N = 1 included, sin 2π = 0).",
    ),
    Formula(
        "flicker_average_var",
        ("d", "N", "k"),
        None,
        "1/f noise as fractional integration of unit-variance white noise from t = 1 (TIM 2014 eq. (3)), "
        "0 < d < 1",
        "TIM 2014 eq. (3) and §III-D, 1ᵀF_kF_kᵀ1 for the k-th bin",
        "Variance of the k-th N-sample mean of 1/f noise; exact (Rational) for rational d, no closed form.",
        latex_text=r"\frac{1}{N^2}\sum_{j=0}^{kN-1}\left(\Psi_j-\Psi_{j-N}\right)^2,\quad "
        r"\Psi_j=\sum_{l=0}^{j}\frac{\Gamma(l+d)}{\Gamma(l+1)\Gamma(d)}",
        delegate_bins=_flicker_averaged_bins,
        delegate_mp=_flicker_averaged_mp,
        delegate_exact=_flicker_averaged_exact,
    ),
    Formula(
        "flicker_carousel_var",
        ("d", "N", "k"),
        None,
        f"1/f noise of TIM 2014 eq. (3), unit σ_w², 0 < d < 1; {_CAROUSEL}; the gyros' noises independent",
        "TIM 2014 eq. (3), (16) and §III-D, sᵀF_kF_kᵀs + cᵀF_kF_kᵀc for the k-th bin",
        "Variance of the k-th carouselled estimate of 1/f noise; no closed form (evaluate at any precision).",
        latex_text=r"\sum_{j}\left(\sum_{u}s_u\psi_{u-N+j}\right)^2+\left(\sum_{u}c_u\psi_{u-N+j}\right)^2",
        delegate_bins=_flicker_carouselled_bins,
        delegate_mp=_flicker_carouselled_mp,
    ),
    Formula(
        "rrw_average_cov",
        ("N", "a", "b"),
        cf.RRW_AVERAGE_COVARIANCE,
        f"{_RRW}; plain N-sample means, bins a, b >= 1",
        "TIM 2014 eq. (15), generalised to any pair of bins, exact finite-N form",
        "Covariance of the a-th and b-th N-sample means of RRW.",
    ),
    Formula(
        "rrw_average_var",
        ("N", "k"),
        cf.RRW_AVERAGE_VARIANCE,
        f"{_RRW}; plain N-sample means, bin k >= 1",
        "TIM 2014 eq. (15) diagonal, every bin, exact finite-N form",
        "Variance of the k-th N-sample mean of RRW: exactly N more than that of bin k − 1.",
    ),
    Formula(
        "rrw_carousel_cov",
        ("N", "a", "b"),
        cf.RRW_CAROUSEL_COVARIANCE,
        f"{_RRW}; {_CAROUSEL}; {_INDEPENDENT}",
        "TIM 2014 eq. (16)-(17), generalised to any pair of bins, exact finite-N form",
        "Covariance of the a-th and b-th carouselled estimates: zero for a ≠ b when N >= 2.",
    ),
    Formula(
        "rrw_carousel_cross",
        ("N",),
        cf.RRW_CAROUSEL_CROSS,
        f"{_RRW}; {_CAROUSEL}",
        "TIM 2014 eq. (16)-(18), sᵀRRᵀc, exact finite-N form",
        "The sine–cosine cross term sᵀRRᵀc = −cot(π/N)/(4N) for N >= 3 (0 for N <= 2), tending to −1/(4π).",
    ),
    Formula(
        "rrw_carousel_var",
        ("N",),
        cf.RRW_CAROUSEL_VARIANCE,
        f"{_RRW}; {_CAROUSEL}; {_INDEPENDENT}; {_N1}",
        "TIM 2014 eq. (17)-(18), sᵀRRᵀs + cᵀRRᵀc, exact finite-N form",
        "Variance of every carouselled bin: csc²(π/N)/(2N) for N >= 3 (1/4 at N = 2) ~ N/(2π²).",
        minimum_samples=2,
    ),
    Formula(
        "rrw_carousel_var_correlated",
        ("N", "rho"),
        cf.RRW_CAROUSEL_VARIANCE_CORRELATED,
        f"{_RRW}; {_CAROUSEL}; the two gyros' increments at equal times correlated with coefficient rho, "
        f"independent at different times; {_N1}",
        "TIM 2014 eq. (16) without the independence assumption, exact finite-N form",
        "Variance of every carouselled bin with correlated increments: sᵀRRᵀs + cᵀRRᵀc − 2ρ sᵀRRᵀc.",
        minimum_samples=2,
    ),
    Formula(
        "rrw_carousel_var_cos",
        ("N",),
        cf.RRW_CAROUSEL_COSINE_VARIANCE,
        f"{_RRW}; {_CAROUSEL}",
        "TIM 2014 eq. (18) cosine term, cᵀRRᵀc, exact finite-N form",
        "cᵀRRᵀc = (csc²(π/N) + 2)/(8N) for N >= 3 (1/4 at N = 2; 1 at N = 1, where c = (1)) ~ N/(8π²).",
    ),
    Formula(
        "rrw_carousel_var_sin",
        ("N",),
        cf.RRW_CAROUSEL_SINE_VARIANCE,
        f"{_RRW}; {_CAROUSEL}",
        "TIM 2014 eq. (17)-(18), sᵀRRᵀs, exact finite-N form",
        "sᵀRRᵀs = (3 csc²(π/N) − 2)/(8N) for N >= 3 (0 for N <= 2) ~ 3N/(8π²).",
    ),
    Formula(
        "white_average_var",
        ("N",),
        cf.WHITE_AVERAGE_VARIANCE,
        "white noise of unit variance",
        "TIM 2014 §III-B (direct averaging)",
        "Variance of the mean of N white samples: 1/N.",
    ),
    Formula(
        "white_carousel_var",
        ("N", "var_x", "var_y"),
        cf.WHITE_CAROUSEL_VARIANCE,
        f"independent white noise of variances var_x (x gyro) and var_y (y gyro); {_CAROUSEL}",
        "TIM 2014 eq. (9), generalised to unequal variances, exact for every N",
        "Variance of the carouselled estimate: (var_x + var_y)/(2N) for N >= 3, var_y/2 at N = 2, "
        "var_y at N = 1.",
    ),
    # --- 2- and 4-position indexing (beyond TIM 2014; proofs/proof_indexing_variances.py) ----------
    *(
        Formula(
            f"indexing{positions}_{process}_var",
            parameters,
            expression,
            f"{positions}-position indexing of two horizontal gyros, k whole cycles of {positions} dwells of "
            f"N samples{gap}; demodulated mean (carousel_theory.rotation_schemes); {assumption}",
            "TIM 2014 §III propagation (eqs. (12)-(17)) extended to indexing, a case beyond the paper; "
            "exact for every k >= 1, N >= 1",
            f"Variance of each horizontal Earth-rate component (they are uncorrelated): {text}.",
        )
        for positions, process, parameters, expression, gap, assumption, text in (
            (
                2,
                "bias",
                ("N", "k"),
                cf.INDEXING2_BIAS_VARIANCE,
                "",
                "unit random-constant biases (eq. (1))",
                "0, the bias cancels in every cycle",
            ),
            (2, "white", ("N", "k"), cf.INDEXING2_WHITE_VARIANCE, "", "unit-variance white noise", "1/(2kN)"),
            (
                2,
                "rrw",
                ("N", "k", "g"),
                cf.INDEXING2_RRW_VARIANCE,
                ", each followed by g dropped transition samples",
                _RRW,
                "(2N² + 3gN + 1)/(12kN)",
            ),
            (
                4,
                "bias",
                ("N", "k"),
                cf.INDEXING4_BIAS_VARIANCE,
                "",
                "unit random-constant biases (eq. (1))",
                "0, the bias cancels in every cycle",
            ),
            (4, "white", ("N", "k"), cf.INDEXING4_WHITE_VARIANCE, "", "unit-variance white noise", "1/(4kN)"),
            (
                4,
                "rrw",
                ("N", "k", "g"),
                cf.INDEXING4_RRW_VARIANCE,
                ", each followed by g dropped transition samples",
                _RRW,
                "(5N² + 6gN + 1)/(24kN)",
            ),
        )
    ),
    # --- imperfections of rotation schemes, leading order (beyond TIM 2014, its §VI future work) --------
    Formula(
        "heading_angle_bias",
        ("beta",),
        cf.HEADING_ANGLE_BIAS,
        f"{_DEMODULATED}; the encoder reads φ + β",
        "TIM 2014 §VI future work (imperfect angle knowledge), exact for any scheme",
        "Heading error (rad) of an encoder offset β: the estimate is the Earth rate turned by β, so −β.",
    ),
    Formula(
        "heading_angle_walk_var",
        ("sigma_nu", "n"),
        cf.HEADING_ANGLE_WALK_VARIANCE,
        f"{_DEMODULATED} at the nominal angle; the true angle random-walks by σ_ν per sample",
        "TIM 2014 §VI future work (variable slewing rate), leading order in σ_ν; eq. (15) with N = n",
        "Heading variance (rad²) of an unmeasured angle random walk: the variance of its n-sample mean.",
    ),
    Formula(
        "heading_encoder_noise_var",
        ("sigma_e", "n"),
        cf.HEADING_ENCODER_NOISE_VARIANCE,
        f"{_DEMODULATED} at encoder angles with independent Gaussian errors of standard deviation σ_e",
        "TIM 2014 §VI future work (imperfect angle knowledge), exact cross-track variance over |E|²",
        "Heading variance (rad², linearised in the estimate) of encoder noise over n used samples: "
        "(1 − exp(−2σ_e²))/(2n) ≈ σ_e²/n.",
    ),
    Formula(
        "heading_scale_mismatch",
        ("k_x", "k_y", "psi"),
        cf.HEADING_SCALE_MISMATCH,
        f"{_DEMODULATED}; static averaging or 2-position indexing; scale factors 1 + k_x, 1 + k_y",
        "TIM 2014 §VI future work (scale factor errors), leading order in k_x, k_y",
        "Heading error (rad) of unequal scale factors at true heading ψ: (k_y − k_x) sin(2ψ)/2; zero for "
        "carouseling and 4-position indexing.",
    ),
    Formula(
        "rate_error_misalignment_wobble",
        ("epsilon", "wobble", "omega_r"),
        cf.RATE_ERROR_MISALIGNMENT_WOBBLE,
        f"{_DEMODULATED} at the nominal angle; one gyro tilted by ε toward the rotation axis; rate "
        "ω_r(1 + a cos(φ + ϕ)) with a = wobble",
        "TIM 2014 §VI future work (variable slewing rate), leading order in the wobble",
        "Size (rad/s) of the Earth-rate error that the rotation rate leaks through a tilted gyro: "
        "sin(ε) a ω_r/2, for every phase ϕ; the heading error is at most this over Ω cos L.",
    ),
]

#: Every formula, by name, sorted by name.
FORMULAS: dict[str, Formula] = {entry.name: entry for entry in sorted(_ENTRIES, key=lambda e: e.name)}


def formula(name: str) -> Formula:
    """The formula called ``name``; ValueError naming the unknown name and listing the known ones."""
    if not isinstance(name, str):
        raise TypeError(f"name={name!r}: must be a string")
    try:
        return FORMULAS[name]
    except KeyError:
        raise ValueError(f"name={name!r}: no such formula; known: {', '.join(FORMULAS)}") from None
