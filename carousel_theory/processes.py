"""Gyro error processes of TIM 2014 §II: bias (1), white noise, rate random walk (2) and 1/f noise
as fractional integration (3)."""

from __future__ import annotations

import numpy as np

from carousel_theory._validation import check_fractional_order, check_positive_integer

__all__ = ["fractional_coefficients"]


def fractional_coefficients(d: float, length: int) -> np.ndarray:
    """The weights ψ_j = Γ(j + d) / (Γ(j + 1) Γ(d)), j = 0 … length − 1, of TIM 2014 eq. (3).

    ``f_t = Σ_{i=1}^{t} ψ_{t−i} w_i``. Computed by the stable recursion ψ_0 = 1,
    ψ_j = ψ_{j−1} (j − 1 + d) / j, which never forms a Gamma value, so it neither overflows nor
    loses accuracy for j up to 10⁷ and beyond.
    """
    d = check_fractional_order("d", d)
    length = check_positive_integer("length", length)
    j = np.arange(1, length, dtype=np.float64)
    psi = np.empty(length, dtype=np.float64)
    psi[0] = 1.0
    psi[1:] = np.cumprod((j - 1.0 + float(d)) / j)
    return psi
