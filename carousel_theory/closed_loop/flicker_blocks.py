"""Block sums of 1/f noise drawn without drawing its samples.

The loop's parametric bootstraps need the sums of ``block`` consecutive samples of the 1/f process of
TIM 2014 eq. (3), f_t = Σ_{i=1}^{t} ψ_{t−i} ε_i (started at t = 1, ε white of variance σ_f²), for
``count`` blocks. With P(m) = ψ_0 + … + ψ_m the partial sums of the ψ_j, the record's running sum is
F_T = Σ_{i≤T} P(T − i) ε_i, so the j-th block sum S_j = F_{jb} − F_{(j−1)b} is, with the innovations
grouped by block (ε_{lb+r}, r = 1 … b),

    S_j = Σ_{l<j} ⟨D_{j−l}, ε_l⟩,   D_1(r) = P(b − r),   D_k(r) = P(kb − r) − P((k−1)b − r) (k ≥ 2),

a convolution over blocks of the rows of the count × b matrix D with the blocks of innovations. D has
numerical rank of about 8 (its rows are smooth in r; measured: the 8th singular direction already
leaves a relative row energy below 10⁻¹⁴), so with D = A Vᵀ (A = U Σ over the leading R singular
directions, V orthonormal) each block enters only through η_l = Vᵀ ε_l ~ N(0, σ_f² I_R), exactly, and

    S_j = Σ_{l<j} Σ_ρ A_{j−l, ρ} η_{l, ρ},

R convolutions of length ``count``: O(count log count) per draw instead of O(count · b · log) for the
samples. A is found once per (d, b, count) by a randomized range finder (Halko, Martinsson & Tropp
2011, Alg. 4.1, a fixed seed: it is a numerical device, not a statistical draw) over column chunks of
D, and the energy of every row of D that A misses is checked (FLICKER_RANK_TOLERANCE).
"""

from __future__ import annotations

import functools

import numpy as np
from scipy import signal

from carousel_theory.processes import fractional_coefficients

__all__ = ["FLICKER_RANK", "FLICKER_RANK_TOLERANCE", "flicker_block_factor", "flicker_block_sums"]

#: Singular directions of D kept (the range finder's width).
FLICKER_RANK = 16
#: Largest relative energy of a row of D that the kept directions may miss.
FLICKER_RANK_TOLERANCE = 1e-10
#: Columns of D formed at once.
_CHUNK = 4096


def _difference_rows(partial: np.ndarray, block: int, count: int, columns: slice) -> np.ndarray:
    """D[:, columns] (module docstring), from the partial sums P of the ψ_j."""
    r = np.arange(1, block + 1)[columns][np.newaxis, :]
    k = np.arange(1, count + 1)[:, np.newaxis]
    rows = partial[k * block - r]
    rows[1:] -= partial[(k[1:] - 1) * block - r]
    return rows


@functools.lru_cache(maxsize=8)
def flicker_block_factor(d: float, block: int, count: int) -> np.ndarray:
    """A (count × R) with D ≈ A Vᵀ, V orthonormal (module docstring); each row of D is reproduced to a
    relative energy error of at most FLICKER_RANK_TOLERANCE, else RuntimeError."""
    partial = np.cumsum(fractional_coefficients(d, count * block))
    rank = min(FLICKER_RANK, block, count)
    chunks = [slice(start, min(start + _CHUNK, block)) for start in range(0, block, _CHUNK)]
    test = np.random.default_rng(0).standard_normal((block, rank))
    sample, energy = np.zeros((count, rank)), np.zeros(count)
    for columns in chunks:
        rows = _difference_rows(partial, block, count, columns)
        sample += rows @ test[columns]
        energy += np.einsum("ij,ij->i", rows, rows)
    basis, _ = np.linalg.qr(sample)
    projected = np.hstack([basis.T @ _difference_rows(partial, block, count, c) for c in chunks])
    left, values, _ = np.linalg.svd(projected, full_matrices=False)
    factor = basis @ (left * values)
    missed = 1.0 - np.einsum("ij,ij->i", factor, factor) / energy
    if float(np.max(missed)) > FLICKER_RANK_TOLERANCE:
        raise RuntimeError(
            f"1/f block sums: rank {rank} leaves a relative row energy of {float(np.max(missed)):.3g} "
            f"(d={d!r}, block={block!r}, count={count!r}); FLICKER_RANK must grow"
        )
    factor.setflags(write=False)
    return factor


def flicker_block_sums(
    variance: float, d: float, block: int, count: int, rng: np.random.Generator, replicates: int = 1
) -> np.ndarray:
    """Sums of ``block`` consecutive samples of 1/f noise of order ``d`` and driving variance
    ``variance`` (TIM 2014 eq. (3), started at t = 1), ``count`` blocks (module docstring); ``replicates``
    independent draws as the rows of a (replicates × count) array."""
    factor = flicker_block_factor(float(d), int(block), int(count))
    innovations = rng.standard_normal((replicates, *factor.shape))
    sums = signal.fftconvolve(factor[np.newaxis], innovations, axes=1)[:, :count].sum(axis=2)
    return np.sqrt(variance) * sums
