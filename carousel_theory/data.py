"""Reading measured gyro recordings (CSV, NPZ, arrays, a pandas DataFrame) into one checked form.

A :class:`Recording` holds time (s), gyro rates (rad/s), the sample rate (Hz) and optional temperature
(°C) and carouseling angle (rad). Every reader checks, before returning, for an empty input, a file that
is not what its extension says, NaN/inf (naming the column and the row), non-monotonic or non-uniform
timestamps and gaps (naming the first index and time). Irregular timing is refused unless the caller
asks to keep it (``irregular="keep"``); the recording is then marked ``uniform=False`` and analyses that
need a uniform sample rate (the Allan variance) refuse it. Files are only ever opened for reading.

Long recordings (12 h at 1 kHz is 4.3·10⁷ rows)
    CSV is parsed by ``pyarrow.csv`` when pyarrow is installed (the ``data`` extra; the core needs only
    NumPy): its streaming reader parses blocks of 4 MB on all cores (larger blocks in flight cost memory)
    straight into float64 columns, without holding the text in memory, about ten times faster than
    ``numpy.loadtxt``; the columns are joined one at a time, so the peak is about one extra column;
    pandas' C engine is as fast on one core but names neither the row nor the column of a bad value.
    Without pyarrow, ``numpy.loadtxt`` is used. When the fast parser refuses a file, the file is scanned
    once more, line by line, to name the row (counted from 0, header excluded) and the column of the first
    bad field; that scan reads lines of at most ``MAX_LINE_BYTES``. The first ``BINARY_CHECK_BYTES`` (64
    KiB) are read to check the header and that the file is text (no NUL byte, valid UTF-8) before the rest
    is parsed.
    An NPZ written without compression (``numpy.savez``) is memory-mapped, read-only: its arrays are
    paged in as the analysis touches them. A compressed NPZ (``savez_compressed``) is decompressed into
    memory. The headers of all members are read first: a file whose headers declare more than
    ``max_values`` values (default ``MAX_VALUES``), or whose zip directory states an uncompressed size
    other than the header's shape implies, is refused before anything is expanded.

Timestamps
    A numeric time column is in s unless ``time_unit`` says ms, us or ns; ``datetime64`` and
    ``timedelta64`` columns are converted from their own unit. The first timestamp is subtracted
    before scaling (in integer arithmetic for integer and date columns), so epoch timestamps keep
    their steps exact; the recording's ``time`` counts from it and ``time_origin`` keeps it.
"""

from __future__ import annotations

import codecs
import csv
import math
import zipfile
from collections.abc import Mapping
from dataclasses import dataclass, field
from itertools import count
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory._validation import check_positive_integer, check_positive_real
from carousel_theory.units import rate_to_rad_per_s

__all__ = [
    "MAX_VALUES",
    "RESERVED_COLUMN_NAMES",
    "TIME_UNITS",
    "Recording",
    "load_recording",
    "recording_from_arrays",
]

#: Relative spread of the time steps tolerated as "uniform" (clock jitter of float timestamps).
UNIFORM_TOLERANCE = 1e-6
#: A time step longer than this many nominal steps is reported as a gap.
GAP_FACTOR = 1.5
#: Most values (all columns together) a reader expands into memory unless the caller raises the limit
#: (``max_values=``, ``--max-values``): 10⁹ values are 8 GB as float64, 12 h at 1 kHz of 23 columns.
MAX_VALUES = 10**9
#: Seconds per unit of a numeric time column (``time_unit=``, ``--time-unit``).
TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}
#: Bytes of a CSV file checked for binary content (NUL bytes, invalid UTF-8) before it is parsed; the
#: header row must end within them.
BINARY_CHECK_BYTES = 1 << 16
#: Longest line the scan that names a bad CSV field reads; a longer one is refused, not held in memory.
MAX_LINE_BYTES = 1 << 20

_TIME_NAMES = ("t", "time", "time_s", "timestamp")
_TEMPERATURE_NAMES = ("temp", "temperature")
_ANGLE_NAMES = ("phi", "angle")
_RATE_PREFIXES = ("w", "gyro", "omega")
_NON_RATE_NAMES = {"t_raw", "fs", "sample_rate"}
#: Column names (compared in lower case) the readers give a role other than a gyro axis.
RESERVED_COLUMN_NAMES = frozenset((*_TIME_NAMES, *_TEMPERATURE_NAMES, *_ANGLE_NAMES, *_NON_RATE_NAMES))


@dataclass(frozen=True)
class Recording:
    """A checked gyro recording.

    Attributes
    ----------
    time : ndarray
        Sample times in s, strictly increasing.
    rates : dict[str, ndarray]
        Gyro rates in rad/s, one entry per axis (e.g. ``{"wx": ..., "wy": ...}``).
    sample_rate : float
        Samples per second (the nominal rate when ``uniform`` is False).
    temperature : ndarray or None
        Temperature in °C, when recorded.
    angle : ndarray or None
        Carouseling angle φ in rad (the 'phi' column), when recorded.
    source : str
        Where the data came from (a path or "arrays").
    uniform : bool
        True when the timestamps are uniform within ``UNIFORM_TOLERANCE`` (or the resolution of the
        timestamps, when coarser) and have no gaps.
    time_origin : float
        The first timestamp of the file in s (since the epoch for an epoch or ``datetime64`` clock);
        ``time`` counts from it, so that ``time[0] == 0`` and its steps keep full precision.
    """

    time: np.ndarray
    rates: dict[str, np.ndarray]
    sample_rate: float
    temperature: np.ndarray | None = None
    angle: np.ndarray | None = None
    source: str = "arrays"
    uniform: bool = True
    notes: tuple[str, ...] = field(default=())
    time_origin: float = 0.0

    @property
    def duration(self) -> float:
        """Length of the recording in s: number of samples / sample rate."""
        return len(self.time) / self.sample_rate

    def __len__(self) -> int:
        return len(self.time)

    def require_duration(self, seconds: float, purpose: str) -> None:
        """Refuse (ValueError) when the recording is shorter than ``seconds`` for ``purpose``."""
        if self.duration < seconds:
            raise ValueError(
                f"{self.source}: the recording lasts {self.duration:.6g} s, too short for {purpose} "
                f"(needs {seconds:.6g} s)"
            )


def _check_column(name: str, values: Any, source: str, expected_length: int | None) -> np.ndarray:
    kind = (values.dtype if hasattr(values, "dtype") else np.asarray(values).dtype).kind
    if kind == "c":
        raise TypeError(
            f"{source}: column {name!r} holds complex numbers; it must hold real numbers (the imaginary "
            "part would be lost; pass np.real(...) or np.abs(...) explicitly if that is what is meant)"
        )
    if kind in "mM":
        raise TypeError(f"{source}: column {name!r} holds dates or durations; only a time column may")
    try:
        array = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise TypeError(f"{source}: column {name!r} must hold real numbers ({error})") from None
    if array.ndim != 1:
        raise ValueError(f"{source}: column {name!r} must be 1-dimensional, got shape {array.shape}")
    if expected_length is not None and len(array) != expected_length:
        raise ValueError(
            f"{source}: column {name!r} has {len(array)} samples but the others have {expected_length}"
        )
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        first = int(bad[0])
        raise ValueError(
            f"{source}: column {name!r} holds {float(array[first])!r} at row {first} (counted from 0, "
            f"header excluded; first of {bad.size} non-finite values); remove or interpolate them first"
        )
    return array


def _check_timing(
    time: np.ndarray, resolution: float, source: str, irregular: str
) -> tuple[float, bool, tuple[str, ...]]:
    """Return (sample rate, uniform, notes) or raise on non-monotonic / irregular timestamps.

    ``time`` counts from the first timestamp (computed exactly, see :func:`_time_offsets`); a step
    counts as uneven when it differs from the median step by more than ``UNIFORM_TOLERANCE`` relative
    plus ``resolution``, the uncertainty of one step that the timestamps' own precision allows.
    """
    steps = np.diff(time)
    bad = np.flatnonzero(steps <= 0)
    if bad.size:
        i = int(bad[0])
        raise ValueError(
            f"{source}: timestamps are not strictly increasing: t[{i}]={time[i]!r} then "
            f"t[{i + 1}]={time[i + 1]!r} s after the first ({bad.size} such steps)"
        )
    nominal = float(np.median(steps))
    tolerance = UNIFORM_TOLERANCE * nominal + resolution
    gaps = np.flatnonzero(steps > GAP_FACTOR * nominal + resolution)
    uneven = np.flatnonzero(np.abs(steps - nominal) > tolerance)
    notes: list[str] = []
    if gaps.size:
        i = int(gaps[0])
        notes.append(
            f"gap: {gaps.size} steps longer than {GAP_FACTOR} x the median step {nominal:.6g} s; the first "
            f"is between t[{i}]={time[i]:.6g} s and t[{i + 1}]={time[i + 1]:.6g} s"
        )
    elif uneven.size:
        i = int(uneven[0])
        notes.append(
            f"non-uniform timestamps: {uneven.size} steps differ from the median step {nominal:.6g} s by "
            f"more than {tolerance:.3g} s ({UNIFORM_TOLERANCE:g} relative + the timestamps' resolution "
            f"{resolution:.3g} s); the first is t[{i + 1}]-t[{i}]={steps[i]:.6g} s"
        )
    if notes and irregular == "refuse":
        raise ValueError(
            f"{source}: {notes[0]} (uniform sampling is required here; in Python, "
            "load_recording(..., irregular='keep') keeps the timestamps for analyses that resample them, "
            "and `carousel-theory loop` averages such recordings onto a uniform grid)"
        )
    if notes:
        # The nominal rate of irregular data is the mean rate, not the median: it keeps duration right.
        return (len(time) - 1) / float(time[-1] - time[0]), False, tuple(notes)
    # The mean rate over the whole record, rounded to 9 significant digits, or fewer when the
    # timestamps' resolution allows fewer (epoch seconds in float64: 2.4·10⁻⁷ s): float timestamps such
    # as i/100 carry rounding that would otherwise leak into every τ (0.00999999999999801 s).
    span = float(time[-1] - time[0])
    digits = 9 if resolution <= 0 else min(9, max(1, math.floor(-math.log10(resolution / span))))
    return float(f"{(len(time) - 1) / span:.{digits}g}"), True, ()


def recording_from_arrays(
    rates: Mapping[str, Any] | Any,
    *,
    time: Any = None,
    sample_rate: float | None = None,
    temperature: Any = None,
    angle: Any = None,
    units: str = "rad/s",
    source: str = "arrays",
    irregular: str = "refuse",
    time_unit: str | None = None,
) -> Recording:
    """Build a checked :class:`Recording` from arrays.

    Parameters
    ----------
    rates : mapping of name to 1-D array, or a pandas DataFrame
        The gyro columns, in ``units``. A DataFrame contributes every column (use ``time=`` etc. for the
        others, or pass ``df[["wx", "wy"]]``).
    time : 1-D array, optional
        Sample times in ``time_unit`` (numbers) or ``datetime64``/``timedelta64`` values. The
        recording's ``time`` counts from the first of them (kept as ``time_origin``). Without it,
        ``sample_rate`` is required and ``t = index / sample_rate``.
    sample_rate : float, optional
        Samples per second. With ``time`` as well, the two must agree to 1e-6 relative.
    temperature, angle : 1-D arrays, optional
        °C and rad.
    units : {"rad/s", "deg/s", "deg/h"}
        Units of ``rates``.
    irregular : {"refuse", "keep"}
        What to do with gaps or non-uniform timestamps.
    time_unit : {"s", "ms", "us", "ns"}, optional
        Unit of a numeric time column (default s), e.g. "ms" for epoch milliseconds. Not allowed with a
        ``datetime64``/``timedelta64`` column, which carries its own unit.
    """
    _check_reading_options(irregular, time_unit, source)
    rates = _rate_mapping(rates, source)
    if sample_rate is not None:
        sample_rate = float(check_positive_real("sample_rate", sample_rate))
    converted = _converted_rates(rates, units, source)
    length = len(next(iter(converted.values())))
    axis = _time_axis(time, sample_rate, length, source, irregular, time_unit)
    temperature_array = (
        None if temperature is None else _check_column("temperature", temperature, source, length)
    )
    angle_array = None if angle is None else _check_column("angle", angle, source, length)
    return Recording(
        time=axis.time,
        rates=converted,
        sample_rate=float(axis.sample_rate),
        temperature=temperature_array,
        angle=angle_array,
        source=source,
        uniform=axis.uniform,
        notes=axis.notes,
        time_origin=axis.origin,
    )


def _rate_mapping(rates: Any, source: str) -> Mapping[str, Any]:
    """``rates`` as a non-empty mapping of column name to values (a DataFrame's columns)."""
    if hasattr(rates, "columns") and hasattr(rates, "to_numpy"):  # a DataFrame, without importing pandas
        rates = {str(name): rates[name].to_numpy() for name in rates.columns}
    if not isinstance(rates, Mapping):
        raise TypeError(
            f"rates={type(rates).__name__}: must be a mapping of column name to array, or a DataFrame"
        )
    if len(rates) == 0:
        raise ValueError(f"{source}: no gyro columns (rates is empty)")
    return rates


def _check_reading_options(irregular: Any, time_unit: Any, source: Any) -> None:
    if irregular not in ("refuse", "keep"):
        raise ValueError(f"irregular={irregular!r}: must be 'refuse' or 'keep'")
    if time_unit is not None and time_unit not in TIME_UNITS:
        raise ValueError(f"time_unit={time_unit!r}: must be one of {', '.join(TIME_UNITS)}")
    if not isinstance(source, str):
        raise TypeError(f"source={source!r}: must be a string")


def _converted_rates(rates: Mapping[str, Any], units: str, source: str) -> dict[str, np.ndarray]:
    """Each gyro column checked and in rad/s."""
    length: int | None = None
    converted: dict[str, np.ndarray] = {}
    for name, values in rates.items():
        if not isinstance(name, str):
            raise TypeError(f"rates: column name {name!r} must be a string")
        array = _check_column(name, values, source, length)
        length = len(array)
        # A read-only array (a memory-mapped NPZ member) in rad/s is kept as it is: nothing can change it.
        keep = units == "rad/s" and not array.flags.writeable
        converted[name] = array if keep else rate_to_rad_per_s(array, units)
    if length is None or length < 2:
        raise ValueError(f"{source}: needs at least 2 samples, got {length}")
    return converted


@dataclass(frozen=True)
class _TimeAxis:
    """A time column counted from its first timestamp, in s, and what the timing check found."""

    time: np.ndarray
    sample_rate: float
    uniform: bool
    notes: tuple[str, ...]
    origin: float = 0.0


def _time_axis(
    time: Any, sample_rate: float | None, length: int, source: str, irregular: str, time_unit: str | None
) -> _TimeAxis:
    """The time axis from a time column or from the sample rate."""
    if time is None:
        if sample_rate is None:
            raise ValueError(f"{source}: no time column and no sample_rate; give one of them")
        if time_unit is not None:
            raise ValueError(f"time_unit={time_unit!r}: given, but {source} has no time column")
        return _TimeAxis(np.arange(length, dtype=np.float64) / sample_rate, sample_rate, True, ())
    offsets, origin, resolution = _time_offsets(time, time_unit, source, length)
    rate, uniform, notes = _check_timing(offsets, resolution, source, irregular)
    if sample_rate is not None and uniform and abs(rate - sample_rate) > 1e-6 * sample_rate:
        raise ValueError(
            f"{source}: sample_rate={sample_rate!r} disagrees with the time column ({rate:.9g} Hz)"
        )
    if sample_rate is not None and uniform:
        rate = sample_rate
    return _TimeAxis(offsets, rate, uniform, notes, origin)


def _time_offsets(
    time: Any, time_unit: str | None, source: str, length: int
) -> tuple[np.ndarray, float, float]:
    """(seconds after the first timestamp, the first timestamp in s, the resolution of a step in s).

    The first timestamp is subtracted before scaling to seconds, exactly: in integer arithmetic for
    integer and ``datetime64``/``timedelta64`` columns; for floats the differences of neighbouring
    floats are exact (Sterbenz), and the resolution is two float spacings at the largest timestamp, so
    epoch seconds at 100 Hz (1700000000.01, spacing 2.4·10⁻⁷ s) are not mistaken for jitter.
    """
    raw = time if hasattr(time, "dtype") else np.asarray(time)
    kind = raw.dtype.kind
    if kind in "mM":
        return _datetime_offsets(np.asarray(raw), time_unit, source, length)
    scale = TIME_UNITS["s" if time_unit is None else time_unit]
    if kind in "iu":
        _check_column("time", raw, source, length)  # the shape and the length
        integers = np.asarray(raw).astype(np.int64)
        first = int(raw[0])
        return (integers - integers[0]).astype(np.float64) * scale, first * scale, scale
    array = _check_column("time", raw, source, length)
    first_value = float(array[0])
    largest = float(np.max(np.abs(array[[0, -1]])))
    offsets = array - first_value if first_value else array
    if scale != 1.0:
        offsets = offsets * scale
    return offsets, first_value * scale, 2.0 * float(np.spacing(largest)) * scale


def _datetime_offsets(
    raw: np.ndarray, time_unit: str | None, source: str, length: int
) -> tuple[np.ndarray, float, float]:
    """:func:`_time_offsets` for ``datetime64``/``timedelta64``: their unit is their own."""
    if time_unit is not None:
        raise ValueError(
            f"time_unit={time_unit!r}: the time column of {source} is {raw.dtype}, which carries its own "
            "unit; leave time_unit unset"
        )
    unit, count = np.datetime_data(raw.dtype)
    if unit in ("Y", "M", "generic"):
        raise ValueError(f"{source}: time column of dtype {raw.dtype}: months and years have no fixed length")
    if raw.ndim != 1 or len(raw) != length:
        raise ValueError(f"{source}: column 'time' must be 1-dimensional with {length} samples")
    missing = np.flatnonzero(np.isnat(raw))
    if missing.size:
        raise ValueError(f"{source}: column 'time' holds NaT at row {int(missing[0])} (counted from 0)")
    tick = float(np.array(count, dtype=f"m8[{unit}]") / np.timedelta64(1, "s"))
    integers = raw.view(np.int64)
    return (integers - integers[0]).astype(np.float64) * tick, int(integers[0]) * tick, tick


def _is_rate_name(name: str) -> bool:
    lowered = name.lower()
    if lowered in _NON_RATE_NAMES or lowered in _TIME_NAMES or lowered in _TEMPERATURE_NAMES:
        return False
    if lowered in _ANGLE_NAMES:
        return False
    return lowered.startswith(_RATE_PREFIXES)


def _pick(names: list[str], candidates: tuple[str, ...]) -> str | None:
    for name in names:
        if name.lower() in candidates:
            return name
    return None


def _read_npz(path: Path, max_values: int) -> dict[str, np.ndarray]:
    with path.open("rb") as handle:
        magic = handle.read(4)
    if magic != b"PK\x03\x04":
        raise ValueError(f"{path}: not an NPZ file (an NPZ is a zip archive; the file starts with {magic!r})")
    try:
        with zipfile.ZipFile(path) as archive:
            members = [info for info in archive.infolist() if info.filename.endswith(".npy")]
            values = sum(_member_values(archive, info, path) for info in members)
            _check_values(values, max_values, path, "its arrays' headers declare")
            mapped = {info.filename[:-4]: _mapped_member(path, info) for info in members}
        if all(array is not None for array in mapped.values()):
            return {name: array for name, array in mapped.items() if array is not None}
        with np.load(path, allow_pickle=False) as loaded:
            return {name: np.asarray(loaded[name]) for name in loaded.files}
    except (ValueError, OSError, zipfile.BadZipFile) as error:
        message = str(error)
        if not message.startswith(str(path)):
            message = f"{path}: not a readable NPZ file ({error})"
        raise ValueError(message) from None


def _check_values(values: int, max_values: int, path: Path, what: str) -> None:
    """Refuse, before expanding them, more values than ``max_values``."""
    if values > max_values:
        raise ValueError(
            f"{path}: {what} {values} values ({values * 8 / 1e9:.3g} GB as float64), more than "
            f"max_values={max_values} (the default {MAX_VALUES} is 8 GB); raise max_values "
            "(--max-values) if the machine has the memory"
        )


def _npy_header(handle: Any) -> tuple[tuple[int, ...], bool, np.dtype]:
    """(shape, Fortran order, dtype) from the header of an .npy stream, leaving it at the data."""
    version = np.lib.format.read_magic(handle)
    read_header = (
        np.lib.format.read_array_header_1_0 if version == (1, 0) else np.lib.format.read_array_header_2_0
    )
    return read_header(handle)


def _member_values(archive: zipfile.ZipFile, info: zipfile.ZipInfo, path: Path) -> int:
    """The number of values an .npy member's header declares, checked against the zip directory.

    Only the header is read (decompressing a few hundred bytes): the shape it declares bounds what the
    member expands to, and the uncompressed size the zip directory states must match it exactly, so a
    deflate bomb or a header claiming 10¹² samples is refused before anything is expanded.
    """
    with archive.open(info) as member:
        shape, _, dtype = _npy_header(member)
        header_bytes = member.tell()
    if dtype.hasobject:
        raise ValueError(
            f"{path}: member {info.filename!r} holds Python objects ({dtype}); only numbers are read"
        )
    values = math.prod(int(n) for n in shape)
    expected = header_bytes + values * dtype.itemsize
    if info.file_size != expected:
        raise ValueError(
            f"{path}: member {info.filename!r} declares shape {shape} of {dtype} ({expected} bytes with its "
            f"header) but the zip directory says it holds {info.file_size} bytes; the file is corrupt"
        )
    return values


def _mapped_member(path: Path, info: zipfile.ZipInfo) -> np.ndarray | None:
    """A read-only memory map of an uncompressed .npy member (None when compressed or an object array)."""
    if info.compress_type != zipfile.ZIP_STORED:
        return None
    with path.open("rb") as handle:
        handle.seek(info.header_offset)
        local = handle.read(30)
        if local[:4] != b"PK\x03\x04":
            raise ValueError(f"member {info.filename!r}: bad local header")
        name_length, extra_length = (
            int.from_bytes(local[26:28], "little"),
            int.from_bytes(local[28:30], "little"),
        )
        handle.seek(info.header_offset + 30 + name_length + extra_length)
        shape, fortran_order, dtype = _npy_header(handle)
        offset = handle.tell()
    if dtype.hasobject:
        return None
    if int(np.prod(shape)) == 0:
        return np.zeros(shape, dtype=dtype)
    return np.memmap(
        path, dtype=dtype, mode="r", offset=offset, shape=shape, order="F" if fortran_order else "C"
    )


def _csv_header(path: Path) -> tuple[list[str], str]:
    """(column names, delimiter) from the first line; refuses binary or non-UTF-8 content.

    Only the first ``BINARY_CHECK_BYTES`` are read here: a binary file (NUL bytes, a zip archive, bytes
    that are not UTF-8) is refused before the rest of it is touched, and the header row must end in them.
    """
    with path.open("rb") as handle:
        head = handle.read(BINARY_CHECK_BYTES)
    whole = len(head) < BINARY_CHECK_BYTES
    if b"\x00" in head or head[:4] == b"PK\x03\x04":
        raise ValueError(f"{path}: not a CSV text file (binary content in the first {len(head)} bytes)")
    try:
        # An incremental decoder accepts a character cut by the block's end, and nothing else invalid.
        text = codecs.getincrementaldecoder("utf-8-sig")().decode(head, final=whole)
    except UnicodeDecodeError as error:
        raise ValueError(
            f"{path}: not a CSV text file (not UTF-8 at byte {error.start} of the first block)"
        ) from None
    if not whole and "\n" not in text and "\r" not in text:
        raise ValueError(
            f"{path}: not a CSV file (no line break in the first {BINARY_CHECK_BYTES} bytes: the header "
            "row is missing or the file is not line-oriented text)"
        )
    lines = text.splitlines()
    if not lines or not lines[0].strip():
        raise ValueError(f"{path}: empty CSV file (no header row)")
    header_line = lines[0]
    delimiter = ","
    for candidate in (",", ";", "\t"):
        if candidate in header_line:
            delimiter = candidate
            break
    header = [name.strip() for name in next(csv.reader([header_line], delimiter=delimiter))]
    if any(_looks_numeric(name) for name in header):
        raise ValueError(f"{path}: the first row {header_line!r} is not a header row (it holds numbers)")
    if len(set(header)) != len(header):
        raise ValueError(f"{path}: repeated column names in the header {header}")
    if len(lines) < 2 and whole:
        raise ValueError(f"{path}: the CSV file has a header but no data rows")
    return header, delimiter


def _read_csv(path: Path, max_values: int) -> dict[str, np.ndarray]:
    header, delimiter = _csv_header(path)
    try:
        import pyarrow as arrow
        import pyarrow.csv as arrow_csv
    except ImportError:
        return _read_csv_numpy(path, header, delimiter, max_values)
    chunks: dict[str, list[np.ndarray]] = {name: [] for name in header}
    rows = 0
    try:
        reader = arrow_csv.open_csv(
            path,
            read_options=arrow_csv.ReadOptions(skip_rows=1, column_names=header, block_size=1 << 22),
            parse_options=arrow_csv.ParseOptions(delimiter=delimiter),
            convert_options=arrow_csv.ConvertOptions(
                column_types=dict.fromkeys(header, arrow.float64()), null_values=[""]  # "nan" stays NaN
            ),
            memory_pool=arrow.system_memory_pool(),  # freed blocks go back to the system at once
        )
        offset = 0
        for batch in reader:  # batch by batch: the text is never held whole, and Arrow's buffers are freed
            rows += batch.num_rows
            _check_values(rows * len(header), max_values, path, f"its first {rows} rows already hold")
            for index, name in enumerate(header):
                _refuse_empty_fields(path, name, batch.column(index), offset)
                chunks[name].append(batch.column(index).to_numpy(zero_copy_only=False))
            offset += batch.num_rows
    except (arrow.ArrowInvalid, UnicodeDecodeError) as error:
        where = _locate_bad_field(path, header, delimiter, error)
        raise ValueError(f"{path}: unreadable CSV data ({where})") from None
    if not any(len(chunk) for chunk in chunks[header[0]]):
        raise ValueError(f"{path}: the CSV file has a header but no data rows")
    columns = {}
    for name in header:  # one column at a time: the chunks and one column, never two copies of everything
        columns[name] = np.concatenate(chunks.pop(name))
        columns[name].setflags(write=False)  # ours alone: read-only, so rad/s columns need no copy
    return columns


def _refuse_empty_fields(path: Path, name: str, column: Any, offset: int) -> None:
    """An empty field parses as null: name its row (a file cut in the middle of a row ends this way)."""
    if column.null_count:
        first = offset + int(np.flatnonzero(column.is_null().to_numpy(zero_copy_only=False))[0])
        raise ValueError(
            f"{path}: unreadable CSV data (row {first} (counted from 0, header excluded), column {name!r} "
            "is empty: a row with a missing value, or a file cut off in the middle of its last row)"
        )


def _locate_bad_field(path: Path, header: list[str], delimiter: str, error: Exception) -> str:
    """Scan the file line by line for the first row with a wrong field count or a non-number.

    Lines are read at most ``MAX_LINE_BYTES`` at a time: a file without line breaks is refused, not
    read whole into memory.
    """
    with path.open("r", encoding="utf-8-sig", errors="replace", newline="") as handle:
        handle.readline(MAX_LINE_BYTES)  # the header, checked already
        for row in count():
            line = handle.readline(MAX_LINE_BYTES)
            if not line:
                break
            where = f"row {row} (counted from 0, header excluded)"
            if len(line) >= MAX_LINE_BYTES and not line.endswith(("\n", "\r")):
                return f"{where} is longer than {MAX_LINE_BYTES} characters; not a CSV recording"
            if "\x00" in line:
                return f"{where} holds NUL bytes: binary content"
            fields = next(csv.reader([line], delimiter=delimiter), [])
            if len(fields) != len(header):
                return f"{where} has {len(fields)} fields, the header {len(header)}"
            for column, field_text in zip(header, fields, strict=True):
                if field_text.strip() and not _looks_numeric(field_text):
                    return f"{where}, column {column!r}: {field_text!r} is not a number"
    return str(error).splitlines()[0]


def _read_csv_numpy(path: Path, header: list[str], delimiter: str, max_values: int) -> dict[str, np.ndarray]:
    # Every value takes at least two bytes ("0,"): a file too short to exceed the limit needs no count.
    if path.stat().st_size // 2 > max_values:
        with path.open("rb") as handle:
            lines = sum(block.count(b"\n") for block in iter(lambda: handle.read(1 << 20), b""))
        _check_values(lines * len(header), max_values, path, "its rows hold")
    try:
        table = np.loadtxt(path, delimiter=delimiter, skiprows=1, dtype=np.float64, ndmin=2, comments=None)
    except ValueError as error:
        raise ValueError(
            f"{path}: unreadable CSV data ({_locate_bad_field(path, header, delimiter, error)})"
        ) from None
    if table.shape[0] == 0:
        raise ValueError(f"{path}: the CSV file has a header but no data rows")
    if table.shape[1] != len(header):
        raise ValueError(f"{path}: {table.shape[1]} data columns but {len(header)} header names")
    return {name: table[:, i] for i, name in enumerate(header)}


def _column_roles(
    table: Mapping[str, Any], columns: Mapping[str, str] | None, path: Path
) -> tuple[str | None, str | None, str | None, dict[str, str]]:
    """(time, temperature, angle, gyro columns ours → theirs) from ``columns`` or the default names."""
    names = list(table)
    if columns is None:
        rate_names = {name: name for name in names if _is_rate_name(name) and np.ndim(table[name]) == 1}
        if not rate_names:
            raise ValueError(
                f"{path}: no gyro columns found among {names}; name them with columns={{'wx': ...}}"
            )
        return (
            _pick(names, _TIME_NAMES),
            _pick(names, _TEMPERATURE_NAMES),
            _pick(names, _ANGLE_NAMES),
            rate_names,
        )
    if not isinstance(columns, Mapping):
        raise TypeError(f"columns={columns!r}: must be a mapping of our name to the file's column name")
    missing = [file_name for file_name in columns.values() if file_name not in table]
    if missing:
        raise ValueError(f"{path}: columns {missing} not found; the file has {names}")
    time_name = columns.get("time")
    if time_name is None and "time" not in columns:
        time_name = _pick(names, _TIME_NAMES)
    rate_names = {
        ours: theirs for ours, theirs in columns.items() if ours not in ("time", "temperature", "angle")
    }
    if not rate_names:
        raise ValueError(f"{path}: no gyro columns found among {names}; name them with columns={{'wx': ...}}")
    return time_name, columns.get("temperature"), columns.get("angle"), rate_names


def _looks_numeric(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _read_table(path: Path, max_values: int) -> dict[str, np.ndarray]:
    """The columns of a CSV or NPZ file, by its extension."""
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file")
    if path.is_dir():
        raise ValueError(f"{path}: is a directory, not a recording file")
    if path.stat().st_size == 0:
        raise ValueError(f"{path}: empty file")
    suffix = path.suffix.lower()
    if suffix == ".npz":
        return _read_npz(path, max_values)
    if suffix in (".csv", ".txt"):
        return _read_csv(path, max_values)
    raise ValueError(f"{path}: unknown extension {path.suffix!r}; must be .csv or .npz")


def load_recording(
    path: str | Path,
    *,
    columns: Mapping[str, str] | None = None,
    sample_rate: float | None = None,
    units: str = "rad/s",
    irregular: str = "refuse",
    time_unit: str | None = None,
    max_values: int = MAX_VALUES,
) -> Recording:
    """Read a CSV (with a header row) or NPZ recording; the file is opened read-only.

    Parameters
    ----------
    path : str or Path
        A ``.csv`` (comma, semicolon or tab separated) or ``.npz`` file.
    columns : mapping, optional
        Our name → the file's name. Keys ``"time"``, ``"temperature"`` and ``"angle"`` are special; every
        other key names a gyro column. Without it: the time is the column ``t``/``time``, temperature
        ``temp``/``temperature``, angle ``phi``/``angle``, and the gyros every column whose name starts
        with ``w``, ``gyro`` or ``omega``.
    sample_rate : float, optional
        Needed when there is no time column (an NPZ's ``fs`` entry is used when present).
    units : {"rad/s", "deg/s", "deg/h"}
        Units of the gyro columns in the file.
    irregular : {"refuse", "keep"}
        What to do with gaps or non-uniform timestamps.
    time_unit : {"s", "ms", "us", "ns"}, optional
        Unit of a numeric time column (default s); see :func:`recording_from_arrays`.
    max_values : int
        Most values (all columns together) read into memory; an NPZ is refused from its headers, a CSV
        as soon as its rows exceed it (default ``MAX_VALUES``, 10⁹ values, 8 GB as float64).
    """
    if not isinstance(path, (str, Path)):
        raise TypeError(f"path={path!r}: must be a str or pathlib.Path")
    table = _read_table(Path(path), check_positive_integer("max_values", max_values))
    path = Path(path)
    time_name, temperature_name, angle_name, rate_names = _column_roles(table, columns, path)
    if sample_rate is None and "fs" in table and np.size(table["fs"]) == 1:
        sample_rate = float(np.asarray(table["fs"]).reshape(()))
        if not (math.isfinite(sample_rate) and sample_rate > 0):
            raise ValueError(f"{path}: the 'fs' entry {sample_rate!r} is not a positive sample rate")
    return recording_from_arrays(
        {ours: table[theirs] for ours, theirs in rate_names.items()},
        time=None if time_name is None else table[time_name],
        sample_rate=sample_rate,
        temperature=None if temperature_name is None else table[temperature_name],
        angle=None if angle_name is None else table[angle_name],
        units=units,
        source=str(path),
        irregular=irregular,
        time_unit=time_unit,
    )
