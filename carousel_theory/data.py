"""Reading measured gyro recordings (text, NPZ, HDF5, MATLAB, arrays, a DataFrame) into one checked form.

A :class:`Recording` holds time (s), gyro rates (rad/s), the sample rate (Hz) and optional temperature
(°C) and carouseling angle (rad). The files are read by :mod:`carousel_theory.readers` (comma,
semicolon, tab or whitespace separated text; NPZ; HDF5; MATLAB ``.mat``), which bound what they expand
(``max_values``) and name the row, column or member of a bad file. Every recording is then checked,
before it is returned, for NaN/inf (naming the column and the row), non-monotonic or non-uniform
timestamps and gaps (naming the first index and time). Irregular timing is refused unless the caller
resamples it (``resample=HZ``: bin means on a uniform grid, :mod:`carousel_theory.resampling`) or asks
to keep it (``irregular="keep"``); a kept recording is marked ``uniform=False`` and analyses that need a
uniform sample rate (the Allan variance) refuse it. Files are only ever opened for reading.

Timestamps
    A numeric time column is in s unless ``time_unit`` says ms, us or ns; ``datetime64`` and
    ``timedelta64`` columns are converted from their own unit. The first timestamp is subtracted
    before scaling (in integer arithmetic for integer and date columns), so epoch timestamps keep
    their steps exact; the recording's ``time`` counts from it and ``time_origin`` keeps it.
    Timestamps are uniform when every step is within ``UNIFORM_TOLERANCE`` (relative) of the median
    step, or when every timestamp lies within ``JITTER_TOLERANCE`` of a step from the uniform grid
    through the first and the last: evenly spaced samples whose clock stamps them with a little
    jitter (a host clock in nanoseconds), which does not accumulate.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory._validation import check_positive_integer, check_positive_real
from carousel_theory.readers import DELIMITERS, MAX_VALUES, read_table
from carousel_theory.readers.text import BINARY_CHECK_BYTES, MAX_LINE_BYTES
from carousel_theory.resampling import block_average, default_resample_rate
from carousel_theory.units import rate_to_rad_per_s

__all__ = [
    "BINARY_CHECK_BYTES",
    "DELIMITERS",
    "MAX_LINE_BYTES",
    "MAX_VALUES",
    "RESERVED_COLUMN_NAMES",
    "TIME_COLUMN_NAMES",
    "TIME_UNITS",
    "Recording",
    "load_recording",
    "recording_from_arrays",
    "resample_recording",
]

#: Relative spread of the time steps tolerated as "uniform" (clock jitter of float timestamps).
UNIFORM_TOLERANCE = 1e-6
#: Largest distance, in steps, of a timestamp from the uniform grid through the first and the last that
#: still counts as uniform sampling (jitter of the timestamps, not of the samples).
JITTER_TOLERANCE = 1e-3
#: A time step longer than this many nominal steps is reported as a gap.
GAP_FACTOR = 1.5
#: Seconds per unit of a numeric time column (``time_unit=``, ``--time-unit``).
TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}

_TIME_NAMES = ("t", "time", "time_s", "timestamp")
#: Column names (compared in lower case) read as the time column when no mapping says otherwise.
TIME_COLUMN_NAMES = _TIME_NAMES
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


def _grid_deviation(time: np.ndarray) -> float:
    """Largest distance, in s, of a timestamp from the uniform grid through the first and the last."""
    step = float(time[-1] - time[0]) / (len(time) - 1)
    distance = np.arange(len(time), dtype=np.float64)  # |t_k − k·step|, in one record-length array
    distance *= step
    np.subtract(time, distance, out=distance)
    return float(np.max(np.abs(distance, out=distance)))


def _timing_note(time: np.ndarray, steps: np.ndarray, resolution: float) -> tuple[str | None, float]:
    """(what is irregular about ``time``: a gap, uneven steps, or None; the timestamps' jitter in s).

    ``time`` is strictly increasing from 0 and ``steps`` is ``np.diff(time)``. The jitter is the largest
    distance from the uniform grid, computed only when some step is uneven (0 otherwise).
    """
    nominal = float(np.median(steps))
    tolerance = UNIFORM_TOLERANCE * nominal + resolution
    gaps = np.flatnonzero(steps > GAP_FACTOR * nominal + resolution)
    if gaps.size:
        i = int(gaps[0])
        return (
            f"gap: {gaps.size} steps longer than {GAP_FACTOR} x the median step {nominal:.6g} s; the first "
            f"is between t[{i}]={time[i]:.6g} s and t[{i + 1}]={time[i + 1]:.6g} s"
        ), 0.0
    distance = np.subtract(steps, nominal)  # |step − median step|, in one record-length array
    np.abs(distance, out=distance)
    uneven = np.flatnonzero(distance > tolerance)
    del distance
    if uneven.size == 0:
        return None, 0.0
    jitter = _grid_deviation(time)
    if jitter <= JITTER_TOLERANCE * float(time[-1]) / (len(time) - 1) + resolution:
        return None, jitter  # evenly spaced samples, jittery stamps
    i = int(uneven[0])
    return (
        f"non-uniform timestamps: {uneven.size} steps differ from the median step {nominal:.6g} s by "
        f"more than {tolerance:.3g} s ({UNIFORM_TOLERANCE:g} relative + the timestamps' resolution "
        f"{resolution:.3g} s), and the timestamps stray from a uniform grid by more than "
        f"{JITTER_TOLERANCE:g} of a step; the first is t[{i + 1}]-t[{i}]={steps[i]:.6g} s"
    ), jitter


def _resample_advice(time: np.ndarray) -> str:
    """How to read an irregular recording anyway, with the rate :func:`default_resample_rate` allows."""
    rate = default_resample_rate(time)
    suggestion = (
        f" ({rate:.6g} Hz is the highest f/2^k, f the mean rate, whose empty bins can be bridged)"
        if rate is not None
        else " (no rate down to 1/2048 of the mean rate bridges its gaps: analyse the parts separately)"
    )
    return (
        "uniform sampling is required here; resample onto a uniform grid by bin means with --resample HZ "
        f"on the command line or load_recording(..., resample=HZ) in Python{suggestion}"
    )


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
            f"{source}: timestamps are not strictly increasing: t[{i}]={float(time[i])!r} then "
            f"t[{i + 1}]={float(time[i + 1])!r} s after the first ({bad.size} such steps)"
            + ("; --resample HZ averages repeated timestamps" if steps[i] == 0 else "")
        )
    note, jitter = _timing_note(time, steps, resolution)
    del steps
    if note is not None and irregular == "refuse":
        raise ValueError(f"{source}: {note} ({_resample_advice(time)})")
    if note is not None:
        # The nominal rate of irregular data is the mean rate, not the median: it keeps duration right.
        return (len(time) - 1) / float(time[-1] - time[0]), False, (note,)
    # The mean rate over the whole record, rounded to 9 significant digits, or fewer when the
    # timestamps' resolution (or jitter) allows fewer (epoch seconds in float64: 2.4·10⁻⁷ s): float
    # timestamps such as i/100 carry rounding that would otherwise leak into every τ (0.00999999999999801 s).
    span = float(time[-1] - time[0])
    spread = max(resolution, jitter)
    digits = 9 if spread <= 0 else min(9, max(1, math.floor(-math.log10(spread / span))))
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
    resample: float | str | None = None,
) -> Recording:
    """Build a checked :class:`Recording` from arrays.

    Parameters
    ----------
    rates : mapping of name to 1-D array, a pandas DataFrame, or a 2-D array
        The gyro columns, in ``units``: every column of a DataFrame (pass ``df[["wx", "wy"]]``); one axis
        per column of a 2-D array, named wx, wy, wz (w0, w1, … beyond three).
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
    resample : float or "auto", optional
        Bin means on a uniform grid of this many Hz (:mod:`carousel_theory.resampling`); needs ``time``.
    """
    _check_reading_options(irregular, time_unit, source)
    rates = _rate_mapping(rates, source)
    if sample_rate is not None:
        sample_rate = float(check_positive_real("sample_rate", sample_rate))
    converted = _converted_rates(rates, units, source)
    length = len(next(iter(converted.values())))
    if resample is not None:
        return _resampled_from_arrays(
            converted, time, temperature, angle, resample, source, time_unit, sample_rate
        )
    axis = _time_axis(time, sample_rate, length, source, irregular, time_unit)
    return Recording(
        time=axis.time,
        rates=converted,
        sample_rate=float(axis.sample_rate),
        temperature=_optional_column("temperature", temperature, source, length),
        angle=_optional_column("angle", angle, source, length),
        source=source,
        uniform=axis.uniform,
        notes=axis.notes,
        time_origin=axis.origin,
    )


def _optional_column(name: str, values: Any, source: str, length: int) -> np.ndarray | None:
    return None if values is None else _check_column(name, values, source, length)


def _rate_mapping(rates: Any, source: str) -> Mapping[str, Any]:
    """``rates`` as a non-empty mapping of column name to values (a DataFrame's or a 2-D array's columns)."""
    if hasattr(rates, "columns") and hasattr(rates, "to_numpy"):  # a DataFrame, without importing pandas
        rates = {str(name): rates[name].to_numpy() for name in rates.columns}
    elif isinstance(rates, np.ndarray) and rates.ndim == 2:
        names = ("wx", "wy", "wz") if rates.shape[1] <= 3 else tuple(f"w{j}" for j in range(rates.shape[1]))
        rates = {name: rates[:, j] for j, name in enumerate(names[: rates.shape[1]])}
    if not isinstance(rates, Mapping):
        raise TypeError(
            f"rates={type(rates).__name__}: must be a mapping of column name to array, or a DataFrame"
        )
    if len(rates) == 0:
        raise ValueError(f"{source}: no gyro columns (rates is empty)")
    return rates


def _check_resample(resample: Any, sample_rate: float | None) -> float | None:
    """The rate of ``resample=`` in Hz, or None for "auto"."""
    if sample_rate is not None:
        raise ValueError(
            f"sample_rate={sample_rate!r} and resample={resample!r}: give one (resample sets the rate)"
        )
    if resample == "auto":
        return None
    if isinstance(resample, str):
        raise ValueError(f"resample={resample!r}: must be a rate in Hz or 'auto'")
    return float(check_positive_real("resample", resample))


def _averaged_recording(
    offsets: np.ndarray,
    resolution: float,
    rates: Mapping[str, np.ndarray],
    extras: dict[str, np.ndarray | None],
    rate: float | None,
    source: str,
    origin: float,
    notes: tuple[str, ...],
) -> Recording:
    """A uniform recording of the bin means of ``rates`` (rad/s) and of the temperature and angle."""
    columns = {f"rate:{name}": values for name, values in rates.items()}
    columns.update({f"extra:{name}": values for name, values in extras.items() if values is not None})
    averaged = block_average(offsets, columns, rate, source, resolution)
    recording = recording_from_arrays(
        {name: averaged.columns[f"rate:{name}"] for name in rates},
        sample_rate=averaged.sample_rate,
        temperature=averaged.columns.get("extra:temperature"),
        angle=averaged.columns.get("extra:angle"),
        source=source,
    )
    return replace(recording, time_origin=origin, notes=(*notes, averaged.note))


def _resampled_from_arrays(
    rates: dict[str, np.ndarray],
    time: Any,
    temperature: Any,
    angle: Any,
    resample: Any,
    source: str,
    time_unit: str | None,
    sample_rate: float | None,
) -> Recording:
    """:func:`recording_from_arrays` with ``resample=``: bin means on a uniform grid."""
    if time is None:
        raise ValueError(
            f"resample={resample!r}: {source} has no time column to resample from (without one, its "
            "samples are taken as uniform at sample_rate)"
        )
    rate = _check_resample(resample, sample_rate)
    length = len(next(iter(rates.values())))
    offsets, origin, resolution = _time_offsets(time, time_unit, source, length)
    extras = {
        "temperature": None
        if temperature is None
        else _check_column("temperature", temperature, source, length),
        # An angle is unwrapped first: the mean of 359° and 1° is 360°, not 180°.
        "angle": None if angle is None else np.unwrap(_check_column("angle", angle, source, length)),
    }
    return _averaged_recording(offsets, resolution, rates, extras, rate, source, origin, ())


def resample_recording(recording: Recording, sample_rate: float | str = "auto") -> Recording:
    """``recording`` averaged onto a uniform grid of ``sample_rate`` Hz (bin means; see
    :mod:`carousel_theory.resampling` for the method and what it refuses).

    ``"auto"``: the highest f̄/2^k (f̄ the mean rate) whose empty bins can be bridged. The result's notes
    end with one sentence saying what was done; its ``time_origin`` is the input's first timestamp.
    """
    if not isinstance(recording, Recording):
        raise TypeError(f"recording={recording!r}: must be a carousel_theory.data.Recording")
    rate = _check_resample(sample_rate, None)
    extras = {
        "temperature": recording.temperature,
        "angle": None if recording.angle is None else np.unwrap(recording.angle),
    }
    offsets = recording.time - recording.time[0]
    origin = recording.time_origin + float(recording.time[0])
    # The float timestamps the recording was read from were known to two spacings at their largest.
    resolution = 2.0 * float(np.spacing(abs(recording.time_origin) + float(recording.time[-1])))
    return _averaged_recording(
        offsets, resolution, recording.rates, extras, rate, recording.source, origin, recording.notes
    )


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
    if "[" in lowered:  # a column of a matrix (NAME[:,j]) is a gyro axis only when mapped explicitly
        return False
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


def _file_sample_rate(table: Mapping[str, Any], path: Path) -> float | None:
    """The file's own ``fs`` entry (one positive number), if it has one."""
    if "fs" not in table or np.size(table["fs"]) != 1:
        return None
    sample_rate = float(np.asarray(table["fs"]).reshape(()))
    if not (math.isfinite(sample_rate) and sample_rate > 0):
        raise ValueError(f"{path}: the 'fs' entry {sample_rate!r} is not a positive sample rate")
    return sample_rate


def load_recording(
    path: str | Path,
    *,
    columns: Mapping[str, str] | None = None,
    sample_rate: float | None = None,
    units: str = "rad/s",
    irregular: str = "refuse",
    time_unit: str | None = None,
    max_values: int = MAX_VALUES,
    delimiter: str = "auto",
    resample: float | str | None = None,
) -> Recording:
    """Read a recording file; the file is opened read-only and never changed.

    Parameters
    ----------
    path : str or Path
        Text with a header row (``.csv``/``.txt``/``.tsv``), ``.npz``, HDF5 (``.h5``/``.hdf5``/``.hdf``,
        the ``hdf5`` extra) or MATLAB ``.mat``; :mod:`carousel_theory.readers` names their columns.
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
    resample : float or "auto", optional
        Bin means on a uniform grid of this many Hz; see :func:`recording_from_arrays`.
    max_values : int
        Most values (all columns together) read into memory; an NPZ is refused from its headers, a CSV
        as soon as its rows exceed it (default ``MAX_VALUES``, 10⁹ values, 8 GB as float64).
    delimiter : {"auto", "comma", "semicolon", "tab", "whitespace"}
        The separator of a text file ("auto": read from the header row).
    """
    if not isinstance(path, (str, Path)):
        raise TypeError(f"path={path!r}: must be a str or pathlib.Path")
    _check_reading_options(irregular, time_unit, str(path))
    table = read_table(Path(path), check_positive_integer("max_values", max_values), delimiter)
    path = Path(path)
    time_name, temperature_name, angle_name, rate_names = _column_roles(table, columns, path)
    if sample_rate is None and resample is None:
        sample_rate = _file_sample_rate(table, path)
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
        resample=resample,
    )
