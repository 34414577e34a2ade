"""Files: atomic writes, JSON read and written, and the chunk store (the
files of a sweep in its output folder)."""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

from ..errors import CaseError
from .points import Point


def write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to a temporary file beside ``path``, then rename it over
    ``path``: a reader sees the whole file or none."""
    path.parent.mkdir(parents=True, exist_ok=True)
    descriptor, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(descriptor, "wb") as stream:
            stream.write(data)
            stream.flush()
            os.fsync(stream.fileno())
        os.chmod(temporary, 0o644)  # mkstemp makes it private
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise


def write_json(path: Path, value) -> None:
    write_atomic(path, (json.dumps(value, indent=1) + "\n").encode())


def _read_json(path: Path):
    """The JSON in ``path``, or None when it is missing or unreadable (it is then recomputed)."""
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


class Store:
    """The files of a sweep in ``root``."""

    def __init__(self, root: Path):
        self.root = root

    def point_dir(self, point: Point) -> Path:
        return self.root / "points" / point.key

    def estimate_path(self, point: Point) -> Path:
        return self.point_dir(point) / "estimate.json"

    def chunk_path(self, point: Point, first: int, count: int) -> Path:
        return self.point_dir(point) / f"chunk-{first:09d}-{count}.json"

    def write_manifest(self, manifest: dict) -> None:
        if self.root.exists() and not self.root.is_dir():
            raise CaseError("output", f"{str(self.root)!r} exists and is not a folder")
        write_json(self.root / "sweep.json", manifest)

    def write_point(self, point: Point, paths: list[str]) -> None:
        path = self.point_dir(point) / "point.json"
        if not path.exists():
            write_json(path, {"values": dict(zip(paths, point.values)), "case": point.data})

    def estimate(self, point: Point) -> dict | None:
        value = _read_json(self.estimate_path(point))
        return value if isinstance(value, dict) and "force" in value else None

    def chunk(self, point: Point, first: int, count: int) -> dict | None:
        value = _read_json(self.chunk_path(point, first, count))
        if not (isinstance(value, dict) and value.get("first") == first and value.get("records") == count):
            return None
        return value
