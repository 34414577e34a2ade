"""The teaching notebooks as HTML pages with their figures: each executed top to bottom, then exported.

The Sphinx build (``docs/conf.py``) writes them into the site's ``notebooks/`` folder, linked from its index, so
the lessons can be read with their plots without running Jupyter; the repository keeps the notebooks without
outputs. By hand::

    python3 docs/notebook_pages.py build/notebooks                # all six
    python3 docs/notebook_pages.py build/notebooks 3_random_vibration   # one

Each notebook runs in a fresh ``python3`` kernel in ``notebooks/`` (two at a time) with ``PANEL_INLINE=1``, so that
``pn.extension()`` writes BokehJS and Panel's JS into the notebook and the page draws its plots offline (the
same as ``PANEL_INLINE=1 jupyter nbconvert --execute --to html``). The pages run no Python: a lesson's widgets
show, but moving one recomputes nothing. Only nbconvert's template asks the network for something: MathJax
(offline, the equations stay as TeX) and require.js (unused).
"""

from __future__ import annotations

import os
import sys
import time
import warnings
from pathlib import Path

NOTEBOOKS = Path(__file__).resolve().parent.parent / "notebooks"
TIMEOUT = 600
"""[s] The longest a cell may run."""


def execute(path: Path, timeout: int = TIMEOUT):
    """The notebook at ``path`` executed in a fresh kernel with ``PANEL_INLINE=1``; a failing cell raises."""
    import nbformat
    from nbclient import NotebookClient

    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(notebook, timeout=timeout, kernel_name="python3", resources={"metadata": {"path": str(path.parent)}})
    client.execute(env={**os.environ, "PANEL_INLINE": "1"})
    return notebook


def html_page(notebook) -> str:
    """An executed notebook as one HTML page (nbconvert's lab template, as Jupyter's "Export as HTML")."""
    from nbconvert import HTMLExporter

    with warnings.catch_warnings():  # Panel leaves an empty display_data beside each live output
        warnings.filterwarnings("ignore", "Your element with mimetype", UserWarning)
        html, _ = HTMLExporter().from_notebook_node(notebook)
    return html


def write_page(path: Path, folder: Path) -> float:
    """The notebook at ``path`` executed and written as ``folder/<name>.html``; the seconds it took."""
    start = time.perf_counter()
    (folder / f"{path.stem}.html").write_text(html_page(execute(path)), encoding="utf-8")
    return time.perf_counter() - start


def write_pages(folder: Path, names: list[str] | None = None, workers: int = 2) -> dict[str, float]:
    """Each notebook (all, or those whose file name starts with one of ``names``) as ``folder/<name>.html``,
    ``workers`` at a time (one kernel each); the seconds each took, by name."""
    from concurrent.futures import ProcessPoolExecutor

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    paths = [path for path in sorted(NOTEBOOKS.glob("*.ipynb")) if not names or any(path.stem.startswith(n) for n in names)]
    with ProcessPoolExecutor(max_workers=max(1, min(workers, len(paths)))) as pool:
        took = pool.map(write_page, paths, [folder] * len(paths))
        return {path.stem: seconds for path, seconds in zip(paths, took)}


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for name, seconds in write_pages(Path(sys.argv[1]), sys.argv[2:]).items():
        print(f"{name}: {seconds:.0f} s")
