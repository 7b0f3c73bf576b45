"""``carousel-theory figures`` writes the PNGs (smoke test at a reduced realisation count), and the
Monte Carlo behind Figs. 4–5 agrees with the exact theory."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO

from carousel_theory.cli import main
from carousel_theory.figures import (
    FIGURES,
    flicker_coefficient_vectors,
    monte_carlo_bin_variances,
    write_figures,
)
from carousel_theory.formulas import formula

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

pytest.importorskip("matplotlib")


def test_command_writes_every_figure(tmp_path, capsys):
    assert main(["figures", "--out", str(tmp_path), "--realisations", "20"]) == 0
    written = sorted(path.name for path in tmp_path.iterdir())
    assert written == sorted(entry.file_name for entry in FIGURES.values())
    for name in written:
        data = (tmp_path / name).read_bytes()
        assert data.startswith(PNG_SIGNATURE) and len(data) > 10_000, name
    assert capsys.readouterr().out.count("wrote ") == len(FIGURES)


def test_same_seed_same_bytes_and_figures_are_independent(tmp_path):
    first = write_figures(tmp_path / "a", realisations=5, only=["tim2014_fig4", "sj2012_fig2"])
    second = write_figures(tmp_path / "b", realisations=5, only=["sj2012_fig2"])
    assert first[1].read_bytes() == second[0].read_bytes()  # leaving Fig. 4 out changes nothing
    again = write_figures(tmp_path / "c", realisations=5, only=["tim2014_fig4"])
    assert again[0].read_bytes() == first[0].read_bytes()


@pytest.mark.parametrize(
    "call, error, match",
    [
        pytest.param(
            lambda p: write_figures(p, realisations=0), ValueError, "realisations=0", id="no-realisations"
        ),
        pytest.param(
            lambda p: write_figures(p, realisations=2.5), TypeError, "realisations=2.5", id="float-count"
        ),
        pytest.param(lambda p: write_figures(p, seed=-1), ValueError, "seed=-1", id="negative-seed"),
        pytest.param(
            lambda p: write_figures(p, only=["fig9"]), ValueError, "unknown figure", id="unknown-figure"
        ),
        pytest.param(
            lambda p: write_figures(p / "file.png"), ValueError, "must be a directory", id="out-is-a-file"
        ),
        pytest.param(
            lambda p: monte_carlo_bin_variances("white", 5, rng=np.random.default_rng(0)),
            ValueError,
            "process='white'",
            id="unknown-process",
        ),
        pytest.param(
            lambda p: monte_carlo_bin_variances("rrw", 5, rng=0), TypeError, "rng=0", id="rng-not-a-generator"
        ),
        pytest.param(
            lambda p: monte_carlo_bin_variances("rrw", 5, rng=np.random.default_rng(0), N=2),
            ValueError,
            "N=2",
            id="too-few-samples",
        ),
        pytest.param(lambda p: flicker_coefficient_vectors(0.5, 0), ValueError, "N=0", id="empty-matrix"),
        pytest.param(
            lambda p: flicker_coefficient_vectors(1.5, 10), ValueError, "d=1.5", id="order-out-of-range"
        ),
    ],
)
def test_invalid_calls(tmp_path, call, error, match):
    (tmp_path / "file.png").write_bytes(b"")
    with pytest.raises(error, match=match):
        call(tmp_path)


def test_command_reports_a_bad_output_directory(tmp_path, capsys):
    (tmp_path / "taken").write_text("x")
    assert (
        main(["figures", "--out", str(tmp_path / "taken"), "--realisations", "2", "--only", "tim2014_fig3"])
        == 2
    )
    assert "exists and is not a folder" in capsys.readouterr().err


def test_flicker_coefficients_against_the_definition():
    """Entry i of Fᵀw is Σ_{t ≥ i} w_t ψ_{t−i}; Fᵀ1 holds the cumulative sums of ψ in reverse (§III-D)."""
    from carousel_theory.processes import fractional_coefficients

    averaged, sine, cosine = flicker_coefficient_vectors(0.5, 12)
    psi = fractional_coefficients(0.5, 12)
    assert np.allclose(averaged, np.cumsum(psi)[::-1] / 12, rtol=1e-14, atol=0)
    i = np.arange(1, 13)
    s = np.sin(2 * np.pi * i / 12) / 12
    expected = [sum(s[t] * psi[t - row] for t in range(row, 12)) for row in range(12)]
    assert np.allclose(sine, expected, rtol=0, atol=1e-15)
    assert cosine.shape == (12,)


def test_carouselled_rrw_monte_carlo_matches_the_exact_variance():
    """Carouselled RRW bins are independent with one variance (TIM 2014 eq. (17)): pooled over bins and
    realisations, the mean of squares must match rrw_carousel_var within Z·SE, and a 2 % error must not."""
    realisations, N, bins = 2100, 200, 50
    _, carouselled = monte_carlo_bin_variances(
        "rrw", realisations, rng=np.random.default_rng(20140), N=N, bins=bins, show_progress=False
    )
    theory = formula("rrw_carousel_var").numeric(N=N)
    pooled = carouselled.mean()
    # Each square of a Gaussian of variance V has variance 2V²; realisations × bins of them are independent.
    standard_error = np.sqrt(2.0) * theory / np.sqrt(realisations * bins)
    assert 0.02 * theory > Z_MONTE_CARLO * standard_error
    assert abs(pooled - theory) <= Z_MONTE_CARLO * standard_error
