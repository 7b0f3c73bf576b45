"""Every SymPy symbol of the closed forms, defined once, with its assumptions.

The registry (:mod:`carousel_theory.formulas`) and the closed forms
(:mod:`carousel_theory.closed_forms`) use these objects, so that an expression built in one module
substitutes cleanly in another (SymPy matches symbols by name *and* assumptions).
"""

from __future__ import annotations

import sympy as sp

__all__ = [
    "N",
    "a",
    "alpha",
    "b",
    "beta",
    "cluster_size",
    "d",
    "difference_count",
    "epsilon",
    "g",
    "h",
    "i",
    "j",
    "k",
    "k_x",
    "k_y",
    "m",
    "n",
    "omega_r",
    "p",
    "psi",
    "quantization_step",
    "rho",
    "rrw_increment_variance",
    "sample_interval",
    "sigma_e",
    "sigma_nu",
    "sigma_q",
    "sigma_w",
    "theta",
    "u",
    "var_x",
    "var_y",
    "white_sample_variance",
    "wobble",
    "x",
    "y",
]

#: Samples per carouseling revolution (= per averaging bin), TIM 2014 §III ("an integer N").
N = sp.Symbol("N", integer=True, positive=True)
#: Bin (revolution) numbers, counted from 1 as in TIM 2014 eq. (6) ("the t-th revolution").
a = sp.Symbol("a", integer=True, positive=True)
b = sp.Symbol("b", integer=True, positive=True)
k = sp.Symbol("k", integer=True, positive=True)
#: Summation indices: sample in a bin (i, j, from 1) and partial-sum length (m, from 0).
i = sp.Symbol("i", integer=True, positive=True)
j = sp.Symbol("j", integer=True, positive=True)
m = sp.Symbol("m", integer=True, nonnegative=True)
#: An integer frequency in the root-of-unity sums Σ_m exp(i p α_m).
p = sp.Symbol("p", integer=True)
#: Correlation coefficient of the two gyros' RRW increments (TIM 2014 §III-C assumes 0).
rho = sp.Symbol("rho", real=True)
#: White-noise variances of the x and y gyro (TIM 2014 eq. (9) takes them equal).
var_x = sp.Symbol("var_x", nonnegative=True)
var_y = sp.Symbol("var_y", nonnegative=True)
#: Degree of fractional integration of 1/f noise, TIM 2014 eq. (3): 0 < d < 1.
d = sp.Symbol("d", positive=True)
#: Standard deviations of the RRW increments q_t (eq. (2)) and of the 1/f driving noise w_t (eq. (3)).
sigma_q = sp.Symbol("sigma_q", positive=True)
sigma_w = sp.Symbol("sigma_w", positive=True)
#: Carouseling step angle θ = 2π/N, and the shifted angle α_m = (2m + 1)π/N of the partial sums.
theta = sp.Symbol("theta", positive=True)
alpha = sp.Symbol("alpha", real=True)
#: u = exp(i α): the unit-circle variable in which a trigonometric polynomial becomes a Laurent polynomial.
u = sp.Symbol("u", nonzero=True)
#: Continuous time in one revolution (TIM 2014 eq. (18)): x, y ∈ [0, 1].
x = sp.Symbol("x", real=True)
y = sp.Symbol("y", real=True)
#: h = 1/N, the expansion variable of the large-N series.
h = sp.Symbol("h", positive=True)
#: Allan variance models (:mod:`carousel_theory.allan`): m samples per cluster (τ = mΔt), the per-sample
#: white variance σ_WN², the per-sample RRW increment variance σ_q², the quantization step Q, the sample
#: interval Δt.
cluster_size = sp.Symbol("m", integer=True, positive=True)
white_sample_variance = sp.Symbol("sigma_WN^2", positive=True)
rrw_increment_variance = sp.Symbol("sigma_q^2", positive=True)
quantization_step = sp.Symbol("Q", positive=True)
sample_interval = sp.Symbol("Delta_t", positive=True)
#: Indexing (maytagging): samples spent turning between two dwell positions, dropped from the estimate.
g = sp.Symbol("g", integer=True, nonnegative=True)
#: Imperfections of a rotation scheme (carousel_theory.imperfections): encoder offset β (rad), encoder
#: noise σ_e (rad per sample), angle random walk σ_ν (rad per sample), n samples used, scale-factor
#: errors k_x, k_y, true heading ψ (rad), tilt ε of a gyro toward the rotation axis (rad), relative
#: once-per-turn rate wobble a ("wobble") and the rotation rate ω_r (rad/s).
beta = sp.Symbol("beta", real=True)
sigma_e = sp.Symbol("sigma_e", nonnegative=True)
sigma_nu = sp.Symbol("sigma_nu", nonnegative=True)
n = sp.Symbol("n", integer=True, positive=True)
k_x = sp.Symbol("k_x", real=True)
k_y = sp.Symbol("k_y", real=True)
psi = sp.Symbol("psi", real=True)
epsilon = sp.Symbol("epsilon", real=True)
wobble = sp.Symbol("wobble", nonnegative=True)
omega_r = sp.Symbol("omega_r", positive=True)
#: Number K of squared differences an Allan-variance estimate averages (n − 2m + 1 when overlapping).
difference_count = sp.Symbol("K", integer=True, positive=True)
