"""Recorded ground motions: reading and writing accelerograms.

Two formats are read, by the file's suffix (any case):

- PEER NGA ``.AT2``: four header lines (title; event and station; ``ACCELERATION
  TIME SERIES IN UNITS OF G``; ``NPTS=  3930, DT= .00500 SEC`` as in NGA-West2,
  or the older ``3930    0.00500    NPTS, DT``), then NPTS values in g, any
  number a line, separated by blanks or commas;
- ``.csv``, ``.txt``, ``.dat``: two columns, time [s] and acceleration [g],
  separated by commas, blanks or semicolons; leading lines that are not numbers
  (headers) and lines starting with ``#`` are skipped. The time step must be
  uniform; the time may start at any value (sample k is taken at k dt).

Values in g are converted to m/s^2 once, with G = 9.80665 m/s^2. Every bad
record raises :class:`~pounding.errors.CaseError` whose field is the file's
name (``"motions/a.AT2:4"`` when a line is at fault).
"""

from __future__ import annotations

import glob
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import numpy as np

from pounding import defaults
from pounding.errors import ArgumentError, CaseError, check_limit, described, finite_number, quote
from pounding.output import file_kind
from pounding.units import STANDARD_GRAVITY

__all__ = [
    "SUFFIXES",
    "TIME_STEP_RANGE",
    "Accelerogram",
    "G",
    "expand_records",
    "read_accelerogram",
    "read_records",
    "write_at2",
    "write_csv",
]

G = STANDARD_GRAVITY
"""Standard gravity [m/s^2]: the unit g of the files."""
SUFFIXES = (".at2", ".csv", ".txt", ".dat")
"""The file suffixes read (any case): PEER .AT2, or two-column text."""

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?"
_NGA_WEST2 = re.compile(rf"^\s*NPTS\s*=\s*(\d+)\s*[,;]?\s*DT\s*=\s*({_NUMBER})\s*(?:SEC\w*)?\s*[,;]?", re.IGNORECASE)
_OLD_LAYOUT = re.compile(rf"^\s*(\d+)\s*[,;]?\s+({_NUMBER})\s*[,;]?\s*NPTS\s*[,;]?\s*DT", re.IGNORECASE)
_GLUED = re.compile(_NUMBER)
_SEPARATORS = re.compile(r"[,;\s]+")
TIME_STEP_RANGE = (1e-5, 1.0)
"""The time steps [s] a record may have: recorded motions are sampled at 0.001 to 0.02 s, old ones at 0.1 s; a step of
1 s keeps nothing of a building's response, and 1e-300 s (a typo) once reached the closed form as a cutoff frequency
of 1e300 rad/s before it was refused, naming the wrong key."""
_LAYOUTS = "'NPTS= 3930, DT= .00500 SEC' (NGA-West2) or '3930  0.00500  NPTS, DT' (NGA)"


@dataclass(frozen=True, eq=False)
class Accelerogram:
    """A ground acceleration record sampled uniformly.

    Parameters
    ----------
    name : str
        The file's name as given or expanded (``"motions/RSN1.AT2"``).
    time_step : float
        Sampling interval dt [s], > 0.
    acceleration : array
        Ground acceleration [m/s^2] at t = k dt, k = 0 .. n - 1 (n >= 2, finite);
        stored as a read-only float64 copy.
    metadata : mapping, optional
        What the record's source says of it (event, year, station, magnitude,
        distance, component...), kept as given; empty for a file. Read only.
    """

    name: str
    time_step: float
    acceleration: np.ndarray
    metadata: dict = field(default_factory=dict)

    def __post_init__(self):
        if not isinstance(self.name, str):
            raise CaseError("name", f"must be a string, got {described(self.name)}")
        step = finite_number(self.name or "time_step", self.time_step)
        low, high = TIME_STEP_RANGE
        if not low <= step <= high:
            raise CaseError(self.name or "time_step", f"time step must lie in [{low:g}, {high:g}] s, got {quote(step)}")
        try:
            values = np.array(self.acceleration, dtype=np.float64)
        except (TypeError, ValueError):
            raise CaseError(self.name or "acceleration", f"acceleration must be an array of numbers, got {described(self.acceleration)}") from None
        if values.ndim != 1 or values.size < 2:
            raise CaseError(self.name or "acceleration", f"must have at least 2 samples in one dimension, got shape {values.shape}")
        if not np.all(np.isfinite(values)):
            raise CaseError(self.name or "acceleration", f"acceleration has a NaN or infinite value at sample {int(np.argmin(np.isfinite(values)))}")
        values.setflags(write=False)
        if not isinstance(self.metadata, (dict, MappingProxyType)):
            raise CaseError(self.name or "metadata", f"metadata must be a mapping, got {described(self.metadata)}")
        object.__setattr__(self, "metadata", MappingProxyType(dict(self.metadata)))
        object.__setattr__(self, "time_step", step)
        object.__setattr__(self, "acceleration", values)

    @property
    def duration(self) -> float:
        """Length (n - 1) dt [s]."""
        return (self.acceleration.size - 1) * self.time_step

    @property
    def peak(self) -> float:
        """Peak ground acceleration max ``|a|`` [m/s^2]."""
        return float(np.max(np.abs(self.acceleration)))

    def times(self) -> np.ndarray:
        """Sample times k dt [s]."""
        return np.arange(self.acceleration.size) * self.time_step

    def scaled(self, factor) -> "Accelerogram":
        """The record times ``factor`` (a finite number > 0)."""
        value = finite_number("factor", factor, error=ArgumentError)
        if not value > 0:
            raise ArgumentError("factor", f"must be a finite number > 0, got {quote(value)}")
        return Accelerogram(self.name, self.time_step, self.acceleration * value, dict(self.metadata))


# --- reading -----------------------------------------------------------------


def _what(path: Path) -> str:
    """What ``path`` is, following links ("a folder", "a pipe", "a device"...), or "a broken link"."""
    try:
        return file_kind(path.stat().st_mode)
    except OSError:
        return "a broken link"


def _text(path: Path, name: str) -> str:
    """The file's text: UTF-8 (a byte-order mark allowed), not binary, within the size limit."""
    try:
        is_file, exists = path.is_file(), path.exists()
    except (OSError, ValueError):  # a name too long, a NUL byte
        is_file = exists = False
    if not is_file:
        what = f"is {_what(path)}, not a file" if exists else "no such file"
        raise CaseError(name, f"{what}; give an accelerogram file ({', '.join(SUFFIXES)})")
    try:
        with path.open("rb") as stream:
            data = stream.read(defaults.MAX_RECORD_FILE_BYTES + 1 if defaults.limits_enabled() else -1)
    except OSError as error:
        raise CaseError(name, f"cannot read it: {error.strerror or error}") from None
    check_limit(name, len(data), defaults.MAX_RECORD_FILE_BYTES, "bytes or more in the accelerogram file", "split or resample the record")
    if b"\x00" in data:
        offset = data.index(b"\x00")
        raise CaseError(name, f"a binary file (NUL byte at offset {offset}); an accelerogram is a text file")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise CaseError(name, f"not a UTF-8 text file (byte 0x{data[error.start]:02x} at offset {error.start})") from None


_HEADER_BYTES = 65_536
"""Bytes read of an .AT2 file for its four header lines before the rest (a header line is under 200 bytes)."""
_BYTES_PER_VALUE = (1, 64)
"""Fewest and most bytes one value of an .AT2 file takes with its separator: ``0`` and a space, or a 17-digit
number written with spaces around it (NGA files write 15 characters)."""


def _check_size_against_header(path: Path, name: str) -> None:
    """Refuse an .AT2 file whose size cannot hold the NPTS values its header announces, from the header and the
    file's size alone (a 199 MB file with a wrong NPTS was read, parsed and refused after 18 s and 1.85 GB)."""
    try:
        size = path.stat().st_size
        if not path.is_file() or size <= _HEADER_BYTES:
            return  # small, or not a file: read whole, and named there
        with path.open("rb") as stream:
            head = stream.read(_HEADER_BYTES).decode("utf-8-sig", errors="replace").splitlines()
    except OSError:
        return  # named when the file is read
    if len(head) < 5:
        return
    header = _NGA_WEST2.match(head[3]) or _OLD_LAYOUT.match(head[3])
    if header is None:
        return  # named when the file is read
    count = int(header.group(1))
    body = size - sum(len(line.encode()) + 1 for line in head[:4])
    fewest, most = _BYTES_PER_VALUE
    if body > count * most + _HEADER_BYTES:
        raise CaseError(f"{name}:4", f"NPTS = {count}, but {body:,} bytes follow the header: more than {count:,} values "
                        f"can take; correct NPTS or the file")
    if body < count * fewest:
        raise CaseError(f"{name}:4", f"NPTS = {count}, but only {body:,} bytes follow the header: fewer than {count:,} "
                        f"values need; correct NPTS or the file")


def _float(token: str) -> float:
    return float(token.replace("D", "E").replace("d", "e"))


def _line_values(line: str, where: str) -> list[float]:
    """The numbers of one line of an .AT2 file; tolerates Fortran's glued ``-.1E-02-.2E-02``."""
    out = []
    for token in _SEPARATORS.split(line.strip()):
        if not token:
            continue
        try:
            value = _float(token)
        except ValueError:
            pieces = _GLUED.findall(token)
            if "".join(pieces) != token:
                raise CaseError(where, f"not a number: {quote(token, 30)}") from None
            out.extend(_float(piece) for piece in pieces)
            continue
        if not math.isfinite(value):
            raise CaseError(where, f"value {quote(token, 30)} is not finite")
        out.append(value)
    return out


def _step(name: str, line_no: int, value: float) -> float:
    low, high = TIME_STEP_RANGE
    if not (math.isfinite(value) and low <= value <= high):
        raise CaseError(f"{name}:{line_no}", f"time step DT must lie in [{low:g}, {high:g}] s, got {quote(value)}")
    return value


def _read_at2(text: str, name: str) -> tuple[float, np.ndarray]:
    lines = text.splitlines()
    if len(lines) < 4:
        raise CaseError(name, f"has {len(lines)} lines; an .AT2 file has 4 header lines, then the values")
    units = re.search(r"UNITS\s+OF\s+(\S+)", lines[2], re.IGNORECASE)
    if units and units.group(1).rstrip(".,;").upper() != "G":
        raise CaseError(f"{name}:3", f"values in {quote(units.group(1), 20)}; only accelerations in units of g are read")
    header = _NGA_WEST2.match(lines[3]) or _OLD_LAYOUT.match(lines[3])
    if header is None:
        raise CaseError(f"{name}:4", f"header {quote(lines[3].strip(), 40)} does not parse; accepted: {_LAYOUTS}")
    count = int(header.group(1))
    step = _step(name, 4, _float(header.group(2)))
    if count < 2:
        raise CaseError(f"{name}:4", f"NPTS = {count}: a record needs at least 2 samples")
    check_limit(f"{name}:4", count, defaults.MAX_SAMPLES_PER_RECORD, "samples per record (NPTS)", "shorten or resample the record")
    body = lines[4:]
    try:
        values = np.array(_SEPARATORS.split(" ".join(body).strip()) if any(s.strip() for s in body) else [], dtype=float)
        if not np.all(np.isfinite(values)):
            raise ValueError
    except ValueError:  # find the line at fault (or values glued together)
        values = np.array([v for k, line in enumerate(body, 5) for v in _line_values(line, f"{name}:{k}")], dtype=float)
    if values.size != count:
        raise CaseError(name, f"has {values.size} values, but its header says NPTS = {count}")
    return step, values * G


def _data_lines(text: str) -> tuple[list[int], list[str]]:
    """Line numbers and text of the data lines: '#' comments, blanks and leading non-numeric lines dropped."""
    numbers, lines, started = [], [], False
    for k, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        if not started:
            try:
                _float(_SEPARATORS.split(stripped)[0])
            except ValueError:
                continue  # a header line
            started = True
        numbers.append(k)
        lines.append(stripped)
    return numbers, lines


def _read_table(text: str, name: str) -> tuple[float, np.ndarray]:
    numbers, lines = _data_lines(text)
    if len(lines) < 2:
        raise CaseError(name, f"has {len(lines)} rows of numbers; a record needs at least 2 (time s, acceleration g)")
    check_limit(name, len(lines), defaults.MAX_SAMPLES_PER_RECORD, "samples per record (rows)", "shorten or resample the record")
    table = np.empty((len(lines), 2))
    for row, (k, line) in enumerate(zip(numbers, lines)):
        tokens = _SEPARATORS.split(line)
        if len(tokens) != 2:
            raise CaseError(f"{name}:{k}", f"has {len(tokens)} columns; expected 2: time [s], acceleration [g]")
        try:
            table[row] = _float(tokens[0]), _float(tokens[1])
        except ValueError:
            raise CaseError(f"{name}:{k}", f"not a number: {quote(line, 40)}") from None
        if not (math.isfinite(table[row, 0]) and math.isfinite(table[row, 1])):
            raise CaseError(f"{name}:{k}", f"value is not finite: {quote(line, 40)}")
    time = table[:, 0]
    steps = np.diff(time)
    if not np.all(steps > 0):
        k = numbers[int(np.argmin(steps > 0)) + 1]
        raise CaseError(f"{name}:{k}", "time does not increase; the time step must be > 0 and uniform")
    step = float(np.median(steps))
    off = np.abs(steps - step) > 1e-6 * step + 1e-9
    if np.any(off):
        k = numbers[int(np.argmax(off)) + 1]
        raise CaseError(f"{name}:{k}", f"time step {steps[np.argmax(off)]:.9g} s differs from {step:.9g} s; it must be uniform")
    step = _step(name, numbers[0], (time[-1] - time[0]) / (time.size - 1))
    return step, table[:, 1] * G


def read_accelerogram(path, name: str | None = None) -> Accelerogram:
    """The accelerogram in the file ``path`` (.AT2, or .csv/.txt/.dat two columns), in m/s^2.

    ``name`` (default: ``path`` as given) names the record and its errors.
    """
    path = Path(path)
    name = os.fspath(path) if name is None else name
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        raise CaseError(name, f"unknown suffix {quote(path.suffix, 20) if path.suffix else '(none)'}; allowed: {', '.join(SUFFIXES)} (any case)")
    if suffix == ".at2":
        _check_size_against_header(path, name)
    text = _text(path, name)
    step, values = (_read_at2 if suffix == ".at2" else _read_table)(text, name)
    return Accelerogram(name, step, values)


def _sibling(field: str, key: str) -> str:
    parent = field.rpartition(".")[0]
    return f"{parent}.{key}" if parent else key


def expand_records(patterns, base_directory, field: str = "excitation.records") -> list[Path]:
    """The files that ``patterns`` (paths or globs, ``**`` recursive; relative to
    ``base_directory`` unless absolute) name: de-duplicated, in the sorted order
    of the expanded file names (relative to ``base_directory``).

    A pattern matching no file raises :class:`CaseError` whose field is the
    pattern as written, under ``field``.
    """
    if isinstance(patterns, (str, bytes)) or not (
            isinstance(patterns, (list, tuple)) and patterns and all(isinstance(p, str) and p for p in patterns)):
        raise CaseError(field, f"must be a non-empty list of file names or globs, e.g. [\"motions/*.AT2\"], got {quote(patterns)}")
    base = Path(base_directory)
    found: dict[str, tuple[str, Path]] = {}
    for pattern in patterns:
        absolute = os.path.isabs(pattern)
        try:
            matches = glob.glob(pattern, recursive=True) if absolute else glob.glob(pattern, root_dir=base, recursive=True)
        except (OSError, ValueError):
            matches = []
        files = [m for m in matches if (Path(m) if absolute else base / m).is_file()]
        if not files:
            magic = glob.has_magic(pattern)
            message = (f"matches no file in {quote(str(base), 80)}" if magic and not absolute
                       else "matches no file" if magic else "no such file")
            if matches and not magic:  # there, but no regular file: say what it is
                message = f"is {_what(Path(matches[0]) if absolute else base / matches[0])}, not a file; give an accelerogram file"
            raise CaseError(pattern, message).under(field)
        for match in files:
            path = Path(match) if absolute else base / match
            shown = os.path.normpath(match) if not absolute else _relative(path, base)
            key = os.path.normcase(os.path.realpath(path))
            found.setdefault(key, (shown, path))
    check_limit(field, len(found), defaults.MAX_RECORDS, "records", "give fewer files")
    return [path for _, path in sorted(found.values(), key=lambda item: item[0])]


def _relative(path: Path, base: Path) -> str:
    """``path`` relative to ``base`` when it lies under it, else as it is."""
    try:
        return os.path.normpath(os.path.relpath(path, base)) if Path(os.path.abspath(path)).is_relative_to(os.path.abspath(base)) else os.fspath(path)
    except ValueError:
        return os.fspath(path)


def read_records(patterns, base_directory, scale=None, pga=None, field: str = "excitation.records") -> tuple[Accelerogram, ...]:
    """The accelerograms of :func:`expand_records`, in its order, each named by
    its path relative to ``base_directory``; times ``scale`` (> 0), or each
    scaled so that its peak ``|a|`` equals ``pga`` [m/s^2] (not both)."""
    if scale is not None and pga is not None:
        raise CaseError(_sibling(field, "pga"), "give scale or pga, not both")
    for key, value in (("scale", scale), ("pga", pga)):
        if value is not None:
            number = finite_number(_sibling(field, key), value)
            if not number > 0:
                raise CaseError(_sibling(field, key), f"must be a finite number > 0, got {quote(value)}")
    base = Path(base_directory)
    records = []
    for path in expand_records(patterns, base, field):
        record = read_accelerogram(path, _relative(path, base))
        if scale is not None:
            record = record.scaled(scale)
        elif pga is not None:
            if record.peak == 0:
                raise CaseError(record.name, "is zero throughout; it cannot be scaled to a pga")
            record = record.scaled(float(pga) / record.peak)
        records.append(record)
    return tuple(records)


# --- writing -----------------------------------------------------------------


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def write_at2(path, accelerogram: Accelerogram, title: str = "") -> Path:
    """Write ``accelerogram`` as a PEER NGA-West2 .AT2 file (values in g, 5 a
    line, ``%15.7E``: 8 significant digits), atomically."""
    from pounding.output import write_atomic

    values = accelerogram.acceleration / G
    n = values.size
    padded = np.zeros(-(-n // 5) * 5)
    padded[:n] = values
    rows = ["%15.7E%15.7E%15.7E%15.7E%15.7E" % tuple(row) for row in padded.reshape(-1, 5)]
    if n % 5:
        rows[-1] = rows[-1][: 15 * (n % 5)]
    header = [
        _one_line(title) or "pounding accelerogram",
        _one_line(accelerogram.name) or "record",
        "ACCELERATION TIME SERIES IN UNITS OF G",
        f"NPTS= {n:7d}, DT= {accelerogram.time_step!r} SEC",
    ]
    return write_atomic(path, "\n".join(header + rows) + "\n")


def write_csv(path, accelerogram: Accelerogram) -> Path:
    """Write ``accelerogram`` as two columns ``time_s,acceleration_g`` (time
    ``%.12g``, acceleration ``%.9g``), atomically."""
    from pounding.output import write_atomic

    times = accelerogram.times()
    values = accelerogram.acceleration / G
    rows = ["%.12g,%.9g" % pair for pair in zip(times.tolist(), values.tolist())]
    return write_atomic(path, "time_s,acceleration_g\n" + "\n".join(rows) + "\n")
