"""Safe output files: one atomic writer for every file the package writes.

:func:`write_atomic` writes text or bytes to a temporary file beside the
target, fsyncs it, gives it the usual mode (``0666`` less the process umask:
0644 under the default umask, not the 0600 of :func:`tempfile.mkstemp`) and
renames it over the target, so a reader sees the whole file or none. Before
writing it checks the target: an existing target that is not a regular file
(a device such as ``/dev/null``, a directory, a symlink to one), an empty
name, a folder that is missing or is a file are refused with a
:class:`~pounding.errors.ArgumentError` naming the argument (``path``; the
command line shows the option typed). An error of the system (a read-only folder, a full disk) is an
:class:`OSError` naming the target, never the temporary file; the temporary
file is removed on any error, KeyboardInterrupt included.

Temporary files are named ``.<name>.<pid>.<random>.tmp``: one left by a
killed run (its process gone) is removed by the next write of the same
target, or by :func:`remove_stale` on its folder.
"""

from __future__ import annotations

import errno
import os
import re
import stat
import tempfile
import time
from pathlib import Path

from pounding.errors import ArgumentError

__all__ = ["check_folder", "check_target", "describe_os_error", "release_stdout", "remove_stale", "write_atomic"]

_STEM = 100  # characters of the target's name kept in its temporary file's name (file names stop at 255)
# .<stem>.<pid>.<8 characters of mkstemp>.tmp, or without the pid as written before; the stem is matched
# lazily, so that a digits-only part before the random one is read as the pid.
_TEMPORARY = re.compile(r"^\.(?P<stem>.+?)\.(?:(?P<pid>\d{1,10})\.)?[a-z0-9_]{8}\.tmp$")
_AFTER_STEM = re.compile(r"^(?:(?P<pid>\d{1,10})\.)?[a-z0-9_]{8}\.tmp$")
_LEGACY_AGE = 60.0  # [s] a temporary file without a pid (written before pids were named) is stale after this


def file_kind(mode: int) -> str:
    """What a file of ``mode`` (``os.stat``'s ``st_mode``) is, in words: "a file", "a folder", "a device", "a pipe"..."""
    if stat.S_ISREG(mode):
        return "a file"
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISFIFO(mode):
        return "a pipe"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a special file"


def _named(error: OSError, path, doing: str = "cannot write it") -> OSError:
    """``error`` naming ``path`` (the target, not a temporary file) and what failed; same errno, so the same subclass."""
    if error.errno is None:
        return error
    return OSError(error.errno, f"{doing}: {error.strerror or error}", str(path))


def _flushes(stream) -> bool:
    try:
        if stream is not None:
            stream.flush()
    except (OSError, ValueError):
        return False
    return True


def release_stdout(force: bool = False) -> bool:
    """If standard output cannot take what is waiting for it (a full disk, a
    closed pipe), or if ``force``, point it at the null device so that nothing
    more is tried (no second error at exit). Returns True when it did."""
    import sys

    if _flushes(sys.stdout) and not force:
        return False
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, sys.stdout.fileno())
        os.close(null)
    except (OSError, ValueError, AttributeError):
        pass
    return True


# Errors of a write that names no file: every file of the package is written by write_atomic, which names
# it, so these come from standard output (`> /dev/full`, a full disk, a pipe whose reader went away).
_WRITE_ERRORS = {getattr(errno, name) for name in ("ENOSPC", "EDQUOT", "EFBIG", "EIO", "EPIPE") if hasattr(errno, name)}


def describe_os_error(error: OSError) -> str:
    """One line for an error of the system: what failed, on which file (standard output included)."""
    reason = error.strerror or str(error) or type(error).__name__
    if error.filename is not None:
        return f"{os.fsdecode(error.filename)!r}: {reason}"
    if release_stdout(force=error.errno in _WRITE_ERRORS):
        return f"cannot write the standard output: {reason}"
    return reason


def _stat(path: Path, field: str, shown: str):
    """``os.stat`` of ``path`` (symlinks followed), or None when nothing is there."""
    try:
        return os.stat(path)
    except FileNotFoundError:
        return None
    except NotADirectoryError:
        raise ArgumentError(field, f"{shown!r}: a part of its folder is a file, not a folder") from None
    except OSError as error:
        raise _named(error, shown, "cannot look at it") from None


def _real(path, field: str, wanted: str = "a file name") -> tuple[Path, str]:
    """The path to write (a symlink is written through) and the path as given."""
    shown = os.fspath(path)
    if isinstance(shown, bytes):
        shown = os.fsdecode(shown)
    if not shown or not shown.strip():
        raise ArgumentError(field, f"is empty; give {wanted}")
    given = Path(shown)
    real = Path(os.path.realpath(given)) if given.is_symlink() else given
    if real != given and not os.path.lexists(real) and os.path.exists(given):
        real = given  # a link the kernel resolves but no path names (/dev/stdout into a pipe: pipe:[...]): stat it as given
    return real, shown


def check_target(path, field: str = "path", make_parents: bool = False, probe: bool = False) -> Path:
    """Check that ``path`` can be written as a file; return the path to write.

    A symlink is followed (its target is written, the link kept). Refused
    with :class:`ArgumentError` naming ``field``: an empty name; an existing
    target that is not a regular file (a device, a folder, a pipe); a
    folder that does not exist (unless ``make_parents``) or is a file.
    With ``probe``, a temporary file is also made (and removed) in the
    folder: a folder that takes no file fails now, as an :class:`OSError`
    naming ``path``, not after the work whose result it was to hold.
    """
    real, shown = _real(path, field)
    status = _stat(real, field, shown)
    if status is not None and not stat.S_ISREG(status.st_mode):
        raise ArgumentError(field, f"{shown!r} is {file_kind(status.st_mode)}, not a regular file; give a file name")
    folder = real.parent
    status = _stat(folder, field, shown)
    if status is None and not make_parents:
        raise ArgumentError(field, f"the folder {str(folder)!r} does not exist; create it first")
    if status is not None and not stat.S_ISDIR(status.st_mode):
        raise ArgumentError(field, f"{str(folder)!r} is {file_kind(status.st_mode)}, not a folder")
    if probe and status is not None:
        descriptor, name = _temporary(real, shown)
        os.close(descriptor)
        os.unlink(name)
    return real


def _temporary(real: Path, shown: str) -> tuple[int, str]:
    """A new temporary file beside ``real``: its descriptor and name."""
    try:
        descriptor, name = tempfile.mkstemp(prefix=f".{real.name[:_STEM]}.{os.getpid()}.", suffix=".tmp", dir=real.parent)
    except OSError as error:
        raise _named(error, shown) from None
    return descriptor, name


def check_folder(path, field: str = "output_dir", create: bool = False) -> Path:
    """Check that ``path`` is a folder, or can be made one (made when ``create``); return it.

    Refused with :class:`ArgumentError` naming ``field``: an empty name, an
    existing path that is not a folder (a file, a device), a part of the path
    that is a file. Errors of the system (permissions, a read-only file
    system) are :class:`OSError` naming ``path``.
    """
    real, shown = _real(path, field, "a folder")
    status = _stat(real, field, shown)
    if status is not None and not stat.S_ISDIR(status.st_mode):
        raise ArgumentError(field, f"{shown!r} is {file_kind(status.st_mode)}, not a folder; give a folder")
    if status is None and create:
        try:
            real.mkdir(parents=True, exist_ok=True)
        except (NotADirectoryError, FileExistsError):
            raise ArgumentError(field, f"{shown!r}: a part of it is a file, not a folder") from None
        except OSError as error:
            raise _named(error, shown, "cannot make the folder") from None
    return real


def _umask() -> int:
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)  # no other way to read it: set it and put it back at once
    os.umask(mask)
    return mask


def _running(pid: int) -> bool:
    if pid == os.getpid():
        return True
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (OverflowError, ValueError):
        return False
    except OSError:  # e.g. another user's process
        return True
    return True


def remove_stale(folder, name: str | None = None) -> int:
    """Remove the temporary files in ``folder`` left by killed writes (of the
    target ``name`` only, or of any); returns how many were removed.

    A temporary file is stale when the process named in it is gone (or, for
    one that names no process, when it is older than a minute): those of a
    write in progress are kept. Errors are ignored.
    """
    removed = 0
    stem = None if name is None else name[:_STEM]
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return 0
    now = time.time()
    prefix = None if stem is None else f".{stem}."
    for entry in entries:
        if prefix is None:
            match = _TEMPORARY.match(entry.name)
        else:
            match = _AFTER_STEM.match(entry.name[len(prefix):]) if entry.name.startswith(prefix) else None
        if match is None:
            continue
        try:
            if not entry.is_file(follow_symlinks=False):
                continue
            if match["pid"] is not None:
                stale = not _running(int(match["pid"]))
            else:
                stale = now - entry.stat(follow_symlinks=False).st_mtime > _LEGACY_AGE
            if stale:
                os.unlink(entry.path)
                removed += 1
        except OSError:
            continue
    return removed


def _sync_folder(folder: Path) -> None:
    """Make the rename durable (best effort: not every system can fsync a folder)."""
    try:
        descriptor = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(descriptor)
    except OSError:
        pass
    finally:
        os.close(descriptor)


def write_atomic(path, data: str | bytes, field: str = "path", *, encoding: str = "utf-8", make_parents: bool = False) -> Path:
    """Write ``data`` (text, encoded with ``encoding``, or bytes) to ``path`` atomically.

    The target is checked first (:func:`check_target`; the folder is made
    when ``make_parents``); the data go to a temporary file beside it, which
    is fsynced, given the mode ``0666 & ~umask`` and renamed over the target.
    A stale temporary file of the same target (from a killed run) is removed.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    ArgumentError
        The target cannot be a file (see :func:`check_target`), naming ``field``.
    OSError
        The system refused (read-only folder, full disk, ...), naming ``path``.
        No temporary file is left, whatever the error.
    """
    payload = data.encode(encoding) if isinstance(data, str) else bytes(data)
    real = check_target(path, field, make_parents)
    shown = os.fspath(path)
    folder = real.parent
    if make_parents:
        check_folder(folder, field, create=True)
    remove_stale(folder, real.name)
    descriptor, temporary = _temporary(real, shown)
    try:
        try:
            os.fchmod(descriptor, 0o666 & ~_umask())
            with os.fdopen(descriptor, "wb") as stream:
                descriptor = None
                stream.write(payload)
                stream.flush()
                os.fsync(stream.fileno())
        except OSError as error:
            raise _named(error, shown) from None
        check_target(real, field, make_parents)  # nothing but a regular file replaced, even one that appeared meanwhile
        try:
            os.replace(temporary, real)
        except OSError as error:
            raise _named(error, shown) from None
    except BaseException:
        if descriptor is not None:
            os.close(descriptor)
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise
    _sync_folder(folder)
    return Path(path)
