"""What the dashboard takes from a browser and keeps on the server's disk: the limits of an upload (stated on the page,
checked in the browser before a file is read and again here), the names it accepts, and the temporary folders of
each session (uploaded records, exported reports), all under one folder of the server process.

That folder is removed when the process exits (``atexit``: also after the SIGTERM on which Bokeh's server stops
its loop); ``pounding dashboard`` names it to the server (:data:`pounding.cli.serve.TEMPORARY_FOLDER_VARIABLE`)
and removes it itself once the server has ended, however it ended. A session's own folders go when the session
closes (:func:`remove`).
"""

from __future__ import annotations

import atexit
import os
import re
import shutil
import tempfile
import threading
from pathlib import Path

from pounding.cli.serve import TEMPORARY_FOLDER_VARIABLE

__all__ = [
    "MAX_CASE_BYTES",
    "MAX_RECORD_BYTES",
    "MAX_RECORD_FILES",
    "UploadRefused",
    "checked_name",
    "checked_size",
    "new_folder",
    "remove",
    "size_text",
]

MAX_RECORD_BYTES = 5_000_000
"""Bytes of one uploaded record: a PEER .AT2 file of a 60 s record at 0.005 s is about 0.2 MB; 5 MB holds 25 times
that. Each file travels to the server as one websocket message (base64: 4/3 of its size), within the server's
limit (``pounding dashboard`` sets it, :data:`pounding.cli.serve.WEBSOCKET_MESSAGE_BYTES`)."""
MAX_RECORD_FILES = 100
"""Records uploaded at once (the command line reads whole suites)."""
MAX_CASE_BYTES = 1_000_000
"""Bytes of an uploaded case file (as ``pounding.defaults.MAX_CASE_FILE_BYTES`` on the command line)."""

_PLAIN_NAME = re.compile(r"^[^/\\\x00-\x1f]{1,200}$")


class UploadRefused(ValueError):
    """An uploaded file refused before anything of it is written: ``message`` says why and what to do."""

    def __init__(self, message: str):
        self.message = message
        super().__init__(message)


def size_text(size: int) -> str:
    """A size in bytes as the page says it: ``5 MB``, ``1 MB``, ``230 kB``."""
    if size >= 1_000_000:
        return f"{size / 1_000_000:.3g} MB"
    return f"{size / 1000:.3g} kB" if size >= 1000 else f"{size} bytes"


def checked_name(name: str) -> str:
    """``name`` if it is a plain file name (no folder, not ``.`` or ``..``, no control character); else
    :class:`UploadRefused` saying so."""
    text = str(name)
    if not _PLAIN_NAME.match(text) or text.strip(". ") == "" or Path(text).name != text:
        shown = text if len(text) <= 40 else text[:37] + "..."
        raise UploadRefused(f"The file name {shown!r} is not a plain file name: rename the file (for example record1.AT2) "
                            "and upload it again.")
    return text


def checked_size(name: str, size: int, limit: int) -> None:
    """:class:`UploadRefused` if ``size`` [bytes] is over ``limit``."""
    if size > limit:
        raise UploadRefused(f"{checked_name(name)} is {size_text(size)}, over the {size_text(limit)} an upload may be: "
                            "shorten or resample it, or use the command line.")


_lock = threading.Lock()
_root: Path | None = None


def _server_root() -> Path:
    """The folder of this server process's temporary files (made on first use)."""
    global _root
    with _lock:
        if _root is None or not _root.is_dir():
            given = os.environ.get(TEMPORARY_FOLDER_VARIABLE)
            if given and Path(given).is_dir():
                _root = Path(given)
            else:
                _root = Path(tempfile.mkdtemp(prefix="pounding-dashboard-"))
            atexit.register(shutil.rmtree, _root, ignore_errors=True)
        return _root


def new_folder(prefix: str) -> Path:
    """A new empty folder for one session's files (``pounding-records-``...), under the server's folder."""
    return Path(tempfile.mkdtemp(prefix=prefix, dir=_server_root()))


def remove(folder: Path | None) -> None:
    """Remove ``folder`` and what it holds, if it exists."""
    if folder is not None:
        shutil.rmtree(folder, ignore_errors=True)
