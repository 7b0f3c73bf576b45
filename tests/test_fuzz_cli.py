"""Property-based fuzzing of the readers and of every command that reads or writes (issue 13).

Generated recordings (CSV text and NPZ archives with hostile headers, NaN/inf, magnitudes near the ends
of float64, short files, bursty or epoch timestamps, odd dtypes, plain garbage) and generated argument
combinations (outputs over the input, below a file, too long, in missing folders) are fed to the command
line in-process. Whatever the input, each run must

* end without a traceback and without an unforeseen error ("unexpected …"),
* exit with 0, 1 or 2,
* leave every input file byte for byte unchanged,
* write nothing outside the outputs it was given, and leave no temporary file behind.

The examples are derandomized (same inputs on every run) and bounded, so the file costs about a minute.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import os
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from carousel_theory.cli import main
from carousel_theory.data import load_recording

FUZZ = settings(
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=list(HealthCheck),
)

# --- generated recordings ---------------------------------------------------------------------------


def mostly(usual, hostile, share: int = 3):
    """``usual`` in ``share`` draws out of ``share + len(hostile)``: most examples get past the readers
    and do real work, the rest probe the refusals."""
    return st.sampled_from([usual] * share + list(hostile))


MAGNITUDES = [1e-300, 1e-60, 1.0, 1e60, 1e300, 1.7e308]
SPECIAL_VALUES = [float("nan"), float("inf"), -float("inf"), 0.0, -0.0, 5e-324, 1.7976931348623157e308]
HEADERS = [
    ["t", "wx", "wy"],
    ["t", "wx"],
    ["time", "gyro_x", "temperature"],
    ["t", "wx", "wy", "temp", "phi"],
    ["t", "wx", "wx"],
    ["", "wx"],
    ["t", ""],
    ["t", " wx ", "wy"],
    ["\ufefft", "wx"],
    ["t", "ωx"],
    ["t", "w" * 300],
    ["t", "allow_pickle"],
    ["t", "wx", "fs"],
    ["wx"],
    ["a", "b"],
]


@dataclass(frozen=True)
class Signal:
    """How the rate columns of a generated recording look."""

    kind: str
    magnitude: float
    seed: int
    specials: tuple[tuple[int, float], ...] = field(default=())

    def column(self, count: int, index: int) -> np.ndarray:
        rng = np.random.default_rng([self.seed, index])
        base = {
            "noise": rng.standard_normal(count),
            "walk": np.cumsum(rng.standard_normal(count)),
            "constant": np.full(count, 0.5),
            "zero": np.zeros(count),
            "spike": np.eye(1, count, count // 2).ravel() if count else np.zeros(0),
            "quantized": np.round(rng.standard_normal(count) * 2.0),
        }[self.kind]
        with np.errstate(over="ignore"):
            values = base * self.magnitude
        for position, value in self.specials:
            if count:
                values[position % count] = value
        return values


signals = st.builds(
    Signal,
    kind=mostly("noise", ["walk", "walk", "constant", "zero", "spike", "quantized"]),
    magnitude=mostly(1e-3, MAGNITUDES, share=6),
    seed=st.integers(0, 2**16),
    specials=st.one_of(
        st.just(()),
        st.just(()),
        st.lists(st.tuples(st.integers(0, 10**6), st.sampled_from(SPECIAL_VALUES)), max_size=2).map(tuple),
    ),
)

TIME_KINDS = [
    "uniform",
    "epoch-seconds",
    "epoch-milliseconds",
    "bursty",
    "repeated",
    "decreasing",
    "nan",
    "none",
]


def time_column(kind: str, count: int) -> np.ndarray | None:
    steps = np.arange(count, dtype=np.float64)
    if kind == "none":
        return None
    column = {
        "uniform": steps / 100.0,
        "epoch-seconds": 1_700_000_000.0 + steps / 100.0,
        "epoch-milliseconds": 1_700_000_000_000.0 + 10.0 * steps,
        "bursty": np.floor(steps / 4.0) + (steps % 4) * 1e-3,
        "repeated": np.zeros(count),
        "decreasing": -steps / 100.0,
        "nan": np.where(steps == count // 2, np.nan, steps / 100.0),
    }[kind]
    return column


@dataclass(frozen=True)
class Recording:
    """A generated file: its name and bytes."""

    name: str
    content: bytes


def _csv_text(header: list[str], columns: list[np.ndarray], style: str) -> str:
    separator = ";" if style == "semicolon" else ","
    ending = "\r\n" if style == "crlf" else "\n"
    lines = [] if style == "no-header" else [separator.join(header)]
    if style == "comment":
        lines.insert(0, "# a comment line")
    for row in zip(*columns, strict=False):
        cells = [repr(float(value)) for value in row]
        if style == "ragged" and len(lines) == 3:
            cells.append("7")
        if style == "text-cell" and len(lines) == 2:
            cells[-1] = "abc"
        lines.append(separator.join(cells) + ("," if style == "trailing-comma" else ""))
        if style == "blank-lines" and len(lines) % 5 == 0:
            lines.append("")
    return ending.join(lines) + ending


@st.composite
def csv_recordings(draw: st.DrawFn) -> Recording:
    header = draw(mostly(HEADERS[0], HEADERS[1:], share=8))
    count = draw(mostly(300, [0, 1, 2, 3, 5, 40, 40, 3000]))
    signal = draw(signals)
    time = time_column(draw(mostly("uniform", TIME_KINDS[1:], share=8)), count)
    rates = [signal.column(count, index) for index in range(len(header) - 1)]
    columns = ([] if time is None else [time]) + rates
    names = header if time is not None else header[1:] or header
    style = draw(
        mostly(
            "plain",
            [
                "crlf",
                "semicolon",
                "comment",
                "ragged",
                "text-cell",
                "trailing-comma",
                "blank-lines",
                "no-header",
            ],
            share=9,
        )
    )
    return Recording("run.csv", _csv_text(names, columns, style).encode("utf-8"))


def _npz_bytes(arrays: dict[str, np.ndarray]) -> bytes:
    buffer = io.BytesIO()
    np.savez(buffer, **arrays)  # type: ignore[arg-type]
    return buffer.getvalue()


@st.composite
def npz_recordings(draw: st.DrawFn) -> Recording:
    count = draw(mostly(300, [0, 2, 3, 40]))
    signal = draw(signals)
    dtype = draw(mostly("float64", ["float32", "int64", "complex128", "bool", "object", "two-d"], share=6))
    rates = signal.column(count, 0)
    with np.errstate(over="ignore", invalid="ignore"):
        if dtype == "two-d":
            column = np.stack([rates, rates])
        elif dtype == "object":
            column = np.array([None, *rates.tolist()], dtype=object)
        else:
            column = rates.astype(dtype) if dtype != "int64" else np.nan_to_num(rates).astype(np.int64)
    arrays: dict[str, np.ndarray] = {"wx": column}
    time_kind = draw(mostly("uniform", ["datetime64", "short", "none", "fs-only"]))
    if time_kind == "uniform":
        arrays["t"] = np.arange(count) / 100.0
    elif time_kind == "datetime64":
        arrays["t"] = np.datetime64("2024-01-01T00:00:00", "ms") + np.arange(count) * np.timedelta64(10, "ms")
    elif time_kind == "short":
        arrays["t"] = np.arange(max(count - 1, 0)) / 100.0
    elif time_kind == "fs-only":
        arrays["fs"] = np.float64(draw(st.sampled_from([100.0, 0.0, -1.0, float("nan")])))
    return Recording("run.npz", _npz_bytes(arrays))


garbage = st.builds(
    Recording,
    name=st.sampled_from(["run.csv", "run.npz", "run.txt"]),
    content=st.one_of(
        st.binary(max_size=300), st.just(b"PK\x03\x04" + bytes(60)), st.just(b"t,wx\n" + b"1," * 2000)
    ),
)

recordings = st.one_of(csv_recordings(), csv_recordings(), csv_recordings(), npz_recordings(), garbage)

# --- running the command line in a folder of its own -------------------------------------------------


@dataclass(frozen=True)
class Outcome:
    status: int
    out: str
    err: str


@contextlib.contextmanager
def _inside(folder: Path) -> Iterator[None]:
    previous = os.getcwd()
    os.chdir(folder)
    try:
        yield
    finally:
        os.chdir(previous)


def run_cli(arguments: list[str], folder: Path) -> Outcome:
    out, err = io.StringIO(), io.StringIO()
    with _inside(folder), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            status = main(arguments)
        except SystemExit as stop:  # argparse: --help (0) or a usage error (2)
            status = stop.code if isinstance(stop.code, int) else 2
    return Outcome(status, out.getvalue(), err.getvalue())


def _listing(folder: Path) -> set[str]:
    return {str(path.relative_to(folder)) for path in folder.rglob("*")}


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else "absent"


def _allowed(listing: set[str], outputs: list[str], folders: list[str]) -> set[str]:
    """The paths a run may have created: the outputs, their missing parents, anything inside an output
    folder, and a C header beside a C source."""
    allowed = set(outputs)
    for output in [*outputs, *folders]:
        allowed |= {str(parent) for parent in Path(output).parents if str(parent) != "."}
        if output.endswith(".c"):
            allowed.add(output[:-2] + ".h")
    return allowed | {
        name for name in listing if any(name == f or name.startswith(f + os.sep) for f in folders)
    }


def check_run(
    arguments: list[str], folder: Path, inputs: list[str], outputs: list[str], folders: list[str] = ()
) -> Outcome:
    """Run and assert the four properties; return the outcome for further checks."""
    before = _listing(folder)
    digests = {name: _digest(folder / name) for name in inputs}
    outcome = run_cli(arguments, folder)
    context = f"{arguments}\nstatus {outcome.status}\nstderr: {outcome.err[-2000:]}"
    assert "Traceback" not in outcome.err, context
    assert "unexpected" not in outcome.err, context
    assert outcome.status in (0, 1, 2), context
    assert {name: _digest(folder / name) for name in inputs} == digests, context
    created = _listing(folder) - before
    stray = created - _allowed(created, list(outputs), list(folders))
    assert not stray, f"{context}\nwritten outside the named outputs: {sorted(stray)}"
    temporary = [name for name in created if Path(name).name.startswith(".")]
    assert not temporary, f"{context}\ntemporary files left behind: {temporary}"
    return outcome


@contextlib.contextmanager
def workspace(recording: Recording | None = None) -> Iterator[Path]:
    with tempfile.TemporaryDirectory(prefix="fuzz-") as name:
        folder = Path(name)
        (folder / "existing").mkdir()
        (folder / "notes.txt").write_text("not a folder\n", encoding="utf-8")
        if recording is not None:
            (folder / recording.name).write_bytes(recording.content)
        yield folder


#: Output paths a command may be given, relative to the workspace; "{input}" is the recording itself.
OUTPUT_PLACES = ["out", "existing/out", "new/deeper/out", "{input}", "notes.txt/out", "existing", "x" * 300]


def _output(place: str, suffix: str, recording: Recording) -> str:
    if place == "{input}":
        return recording.name
    if place == "existing":
        return place
    return place + suffix


# --- the readers ------------------------------------------------------------------------------------


@settings(FUZZ, max_examples=200)
@given(
    recording=recordings,
    time_unit=st.sampled_from([None, "s", "ms", "ns"]),
    rate=st.sampled_from([None, 100.0]),
)
def test_readers_refuse_with_a_value_error_or_return_a_recording(recording, time_unit, rate):
    with workspace(recording) as folder:
        path = folder / recording.name
        before = _digest(path)
        try:
            loaded = load_recording(path, sample_rate=rate, time_unit=time_unit, max_values=10**6)
        except (ValueError, TypeError) as error:
            assert str(error) and "\n" not in str(error).strip()
        else:
            assert loaded.rates and all(np.all(np.isfinite(v)) for v in loaded.rates.values())
            assert np.isfinite(loaded.sample_rate) and loaded.sample_rate > 0
        assert _digest(path) == before


# --- the commands that read a recording ---------------------------------------------------------------

reader_options = st.lists(
    mostly(
        [],
        [
            ["--sample-rate", "100"],
            ["--sample-rate", "0"],
            ["--time-unit", "ms"],
            ["--units", "deg/s"],
            ["--column", "wx=gyro_x"],
            ["--column", "time=t"],
            ["--max-values", "50"],
        ],
        share=10,
    ),
    max_size=1,
)


@st.composite
def reading_commands(draw: st.DrawFn, recording: Recording) -> tuple[list[str], list[str]]:
    """(arguments, outputs) of allan, fit, predict or loop on ``recording``."""
    command = draw(st.sampled_from(["allan", "fit", "predict", "loop"]))
    arguments, outputs = [command, recording.name], []
    place = draw(mostly(None, ["out", "out", *OUTPUT_PLACES], share=5))
    if command == "allan":
        arguments += draw(
            st.sampled_from([[], ["--json"], ["--estimator", "non-overlapping"], ["--taus", "0.01,0.02"]])
        )
        option, suffix = ("--plot", ".png") if draw(st.integers(0, 4)) == 0 else (None, "")
    elif command == "fit":
        arguments += draw(
            st.sampled_from([[], ["--json"], ["--model", "white,rrw,flicker"], ["--tau-min", "0.02"]])
        )
        option, suffix = "--markdown", ".md"
    elif command == "predict":
        calibration = draw(mostly("100", ["2", "10", "20", "1000"]))
        arguments += ["--calibration", calibration, "--horizon", draw(mostly("50", ["1", "5", "1000"]))]
        arguments += draw(st.sampled_from([[], ["--start", "3"], ["--axis", "wy"], ["--sample-rate", "100"]]))
        option, suffix = "--output", draw(st.sampled_from([".csv", ".json", ".txt"]))
    else:
        arguments += ["--samples-per-revolution", draw(st.sampled_from(["3", "4"]))]
        arguments += draw(st.sampled_from([[], ["--axes", "wx"], ["--axes", "wx,wy"], ["--alpha", "0.6"]]))
        option, suffix = "--json", ".json"
    if command != "predict":
        arguments += [part for group in draw(reader_options) for part in group]
    if option is not None and place is not None:
        output = _output(place, suffix, recording)
        arguments += [option, output]
        outputs.append(output)
    return arguments, outputs


@settings(FUZZ, max_examples=400)
@given(data=st.data(), recording=recordings)
def test_commands_that_read_a_recording(data, recording):
    arguments, outputs = data.draw(reading_commands(recording))
    with workspace(recording) as folder:
        outcome = check_run(arguments, folder, [recording.name], outputs)
        if recording.name in outputs:  # refused: as the input, or earlier for another reason
            assert outcome.status == 2


# --- the commands that only write -----------------------------------------------------------------


@st.composite
def writing_commands(draw: st.DrawFn) -> tuple[list[str], list[str], list[str]]:
    """(arguments, file outputs, folder outputs) of simulate, export, derive, check or figures."""
    command = draw(
        st.sampled_from(["simulate", "simulate", "export", "export", "derive", "check", "figures"])
    )
    place = draw(mostly("out", OUTPUT_PLACES[1:3] + OUTPUT_PLACES[4:]))
    if command == "simulate":
        out = place + draw(mostly(".csv", [".npz", ".npz", ".txt", ""]))
        arguments = ["simulate", out, "--seed", draw(mostly("1", ["-1"]))]
        arguments += ["--duration", draw(mostly("1", ["0.02", "0", "nan", "inf", "1e12"]))]
        arguments += draw(
            mostly(
                [],
                [
                    ["--axes", "t,wx"],
                    ["--axes", "wx,wx"],
                    ["--axes", ","],
                    ["--sample-rate", "1e-3"],
                    ["--effect", "spikes:rate=-1"],
                    ["--effect", "nonsense"],
                    ["--samples-per-revolution", "4"],
                    ["--white-variance", "-1"],
                    ["--no-temperature"],
                    ["--effect", "spikes"],
                    ["--effect", "warmup"],
                    ["--flicker-variance", "1e-9"],
                ],
                share=6,
            )
        )
        return arguments, [out], []
    if command == "export":
        suffix = draw(st.sampled_from([".c", ".json", ".h", ".tex"]))
        out = place + suffix
        form = {".c": "c", ".json": "json", ".h": "c", ".tex": "latex"}[suffix]
        return (
            [
                "export",
                "--format",
                form,
                "-o",
                out,
                *draw(st.sampled_from([[], ["--check"], ["--fragment"]])),
            ],
            [out],
            [],
        )
    if command == "derive":
        return (
            ["derive", "--out", place, "--only", draw(st.sampled_from(["rotation_schemes", "nothing"]))],
            [],
            [place],
        )
    if command == "check":
        return (
            ["check", "--out", place, "--only", draw(st.sampled_from(["TIM2014-eq18", "", "zzz"]))],
            [],
            [place],
        )
    realisations = draw(st.sampled_from(["2", "0", "-3"]))
    return ["figures", "--out", place, "--only", "tim2014_fig2", "--realisations", realisations], [], [place]


@settings(FUZZ, max_examples=80)
@given(command=writing_commands())
def test_commands_that_write(command):
    arguments, outputs, folders = command
    with workspace() as folder:
        check_run(arguments, folder, ["notes.txt"], outputs, folders)


@pytest.mark.parametrize("command", ["simulate", "export"])
def test_a_written_file_reads_back_and_a_refused_one_is_not_written(command, tmp_path):
    """The fuzzer's properties can pass by refusing everything: one valid call of each must write."""
    with workspace() as folder:
        arguments = (
            ["simulate", "new/run.csv", "--seed", "3", "--duration", "1"]
            if command == "simulate"
            else ["export", "--format", "json", "-o", "new/run.json"]
        )
        outcome = check_run(
            arguments, folder, ["notes.txt"], [arguments[1] if command == "simulate" else arguments[4]]
        )
        assert outcome.status == 0
        written = folder / "new" / ("run.csv" if command == "simulate" else "run.json")
        assert written.stat().st_size > 0


# --- what the fuzzer found, pinned ------------------------------------------------------------------


def _open_figures() -> list[int]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return list(plt.get_fignums())


def test_found_allan_plot_of_a_constant_column_is_refused_and_leaves_no_figure_open(tmp_path):
    """A constant column has Allan deviation 0, which log axes cannot show: matplotlib warned, then
    the figure stayed open, and after 20 such runs in one process every plot failed."""
    recording = Recording(
        "run.csv", _csv_text(["t", "wx"], [np.arange(50) / 100.0, np.full(50, 0.5)], "plain").encode()
    )
    with workspace(recording) as folder:
        before = _open_figures()
        outcome = check_run(["allan", "run.csv", "--plot", "out.png"], folder, ["run.csv"], [])
        assert outcome.status == 2 and "every Allan deviation is 0" in outcome.err
        assert _open_figures() == before


def test_found_a_plot_that_fails_to_write_closes_its_figure(tmp_path, monkeypatch):
    def full_disk(*args, **kwargs):
        raise OSError(28, "No space left on device", "out.png")

    monkeypatch.setattr("carousel_theory.plots.atomic_output", full_disk)
    signal = Signal("noise", 1e-3, 5).column(300, 0)
    recording = Recording(
        "run.csv", _csv_text(["t", "wx"], [np.arange(300) / 100.0, signal], "plain").encode()
    )
    with workspace(recording) as folder:
        before = _open_figures()
        outcome = check_run(["allan", "run.csv", "--plot", "out.png"], folder, ["run.csv"], ["out.png"])
        assert outcome.status == 1 and "No space left" in outcome.err
        assert _open_figures() == before


def _two_axis_csv(wx: np.ndarray, wy: np.ndarray) -> Recording:
    columns = [np.arange(len(wx)) / 100.0, wx, wy]
    return Recording("run.csv", _csv_text(["t", "wx", "wy"], columns, "plain").encode())


@pytest.mark.parametrize("seed", [2, 3, 4, 5])
def test_found_loop_on_a_short_recording_with_one_sample_blocks_runs(seed):
    """The misfit bootstrap drew the random walk's (I, W) pair by Cholesky; with one-sample blocks that
    covariance is singular (I = W), and ordinary white noise ended in 'not positive definite'."""
    rng = np.random.default_rng(seed)
    recording = _two_axis_csv(1e-3 * rng.standard_normal(300), 1e-3 * rng.standard_normal(300))
    with workspace(recording) as folder:
        outcome = check_run(["loop", "run.csv", "--samples-per-revolution", "4"], folder, ["run.csv"], [])
        assert outcome.status == 0, outcome.err


@pytest.mark.parametrize(
    ("value", "fragment"),
    [(1e-3, "once its effects are removed: constant"), (1.7e308, "a sample of magnitude 1.7e+308")],
    ids=["spike-on-zero", "huge-spike-on-zero"],
)
def test_found_loop_on_a_lone_spike_names_the_column_and_rule(value, fragment):
    """A lone spike on zeros: the loop removed the spike and then solved with a zero noise model
    ('1th leading minor not positive definite'), or overflowed squaring the quantization step."""
    spike = np.zeros(300)
    spike[150] = value
    with workspace(_two_axis_csv(spike, spike)) as folder:
        outcome = check_run(["loop", "run.csv", "--samples-per-revolution", "3"], folder, ["run.csv"], [])
        assert outcome.status == 2 and fragment in outcome.err and "column 'wx'" in outcome.err
