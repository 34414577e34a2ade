"""Files: JSON read and written (atomically, by :mod:`pounding.output`), and
the chunk store (the files of a sweep in its output folder)."""

from __future__ import annotations

import json
from pathlib import Path

from pounding.output import check_folder, remove_stale, write_atomic
from pounding.studies.sweeps.points import Point

FIELD = "output_dir"
"""The field the sweep's file errors name (the CLI shows it as ``--output``)."""


def write_json(path: Path, value) -> None:
    """``value`` as JSON in ``path``, atomically (:func:`pounding.output.write_atomic`), its folder made if missing."""
    write_atomic(path, json.dumps(value, indent=1) + "\n", FIELD, make_parents=True)


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

    def remove_stale(self) -> int:
        """Remove the temporary files left by a killed sweep in this folder (not those of a sweep running)."""
        removed = remove_stale(self.root)
        try:
            points = list((self.root / "points").iterdir())
        except OSError:
            return removed
        return removed + sum(remove_stale(folder) for folder in points)

    def write_manifest(self, manifest: dict) -> None:
        check_folder(self.root, FIELD, create=True)
        self.remove_stale()
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
        if not (isinstance(value, dict) and value.get("first") == first and value.get("records") == count
                and len(value.get("force_max_values", ())) == count):
            return None
        return value
