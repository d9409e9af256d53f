"""Run outputs written atomically: a temporary file in the same folder, then
``os.replace``.  A run that fails, or is killed while writing, leaves every
file that was already there whole (either the old one or the new one).
:func:`staged` goes one step further for a set of files: they are all made
in a hidden staging folder and moved into place only once every one of them
has been written.

>>> import tempfile, pathlib
>>> d = pathlib.Path(tempfile.mkdtemp())
>>> write_json(d / "summary.json", {"Load [N]": 1.5}).name
'summary.json'
"""
from __future__ import annotations

import contextlib
import json
import logging
import os
import shutil
import tempfile
from pathlib import Path

log = logging.getLogger(__name__)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_bytes(path, data: bytes) -> Path:
    """Write ``data`` to ``path`` through a temporary file and a rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp creates 0600; give the usual mode
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    log.debug("wrote %s", path)
    return path


def write_text(path, text: str) -> Path:
    return write_bytes(path, text.encode("utf-8"))


def write_json(path, mapping: dict) -> Path:
    """A flat mapping as indented JSON (numpy scalars become Python numbers)."""

    def plain(value):
        if hasattr(value, "item"):
            return value.item()
        raise TypeError(f"{type(value).__name__} is not JSON serialisable")

    return write_text(path, json.dumps(mapping, indent=2, default=plain) + "\n")


def save_figure(path, figure, dpi: int = 120) -> Path:
    """Save a matplotlib figure atomically (Agg canvas; never opens a window)."""
    import io

    buffer = io.BytesIO()
    suffix = Path(path).suffix.lstrip(".") or "png"
    figure.savefig(buffer, format=suffix, dpi=dpi)
    return write_bytes(path, buffer.getvalue())


@contextlib.contextmanager
def staged(out_dir):
    """Yield a staging folder inside ``out_dir``; on success move its files into
    ``out_dir`` (one rename each), on failure discard it.  Either way the
    staging folder is removed."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=".staging-", dir=out))
    try:
        yield stage
        for item in sorted(stage.iterdir()):
            os.replace(item, out / item.name)
            log.info("wrote %s", out / item.name)
    finally:
        shutil.rmtree(stage, ignore_errors=True)


def write_run(out_dir, resolved: str, summary: dict, write, fields=None, figure=None) -> list[Path]:
    """Write one run's outputs into ``out_dir`` through a staging folder.

    ``resolved`` is the text of ``case.resolved.toml``; ``write`` the case's
    ``output.write`` list ("vtu", "png"); ``fields`` = (file name, callable
    writing a ``.vtu`` to a path); ``figure`` = (file name, callable returning
    a matplotlib figure).  Returns the paths written.
    """
    out = Path(out_dir)
    with staged(out) as stage:
        write_text(stage / "case.resolved.toml", resolved)
        if fields is not None and "vtu" in write:
            fields[1](stage / fields[0])
        if figure is not None and "png" in write:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt

            fig = figure[1]()
            try:
                save_figure(stage / figure[0], fig)
            finally:
                plt.close(fig)
        write_json(stage / "summary.json", summary)
        names = sorted(p.name for p in stage.iterdir())
    return [out / n for n in names]


def run_summary(case, name: str, smoke: bool, scene_summary: dict, t0: float, t_build: float) -> dict:
    """The summary every scene writes: identity, the scene's own results, timing."""
    import time

    from . import __version__

    summary = {"Case": name, "Scene": case.scene, "Description": case.description}
    summary.update(scene_summary)
    summary["Smoke resolution"] = bool(smoke)
    summary["Build time [s]"] = t_build
    summary["Run time [s]"] = time.perf_counter() - t0
    summary["lubedyn version"] = __version__
    return summary


def resolved_header(name: str, source, smoke: bool) -> str:
    """First line of ``case.resolved.toml``."""
    from . import __version__

    return f"lubedyn {__version__}: resolved from {source or name}" + (" with --smoke" if smoke else "")
