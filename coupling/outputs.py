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


def json_default(obj):
    """``json.dumps(default=...)`` for numpy scalars and arrays and paths."""
    import numpy as np

    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, Path):
        return str(obj)
    raise TypeError(f"{type(obj).__name__} is not JSON serialisable")


def write_json(path, mapping: dict) -> Path:
    """A mapping as indented JSON (numpy scalars and arrays become Python numbers and lists)."""
    return write_text(path, json.dumps(mapping, indent=2, default=json_default) + "\n")


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
            target = out / item.name
            if item.is_dir() and target.is_dir():
                # a folder of fields (frames/): move the old one aside, put the new one in, drop the old
                old = Path(tempfile.mkdtemp(prefix=f".old-{item.name}-", dir=out))
                os.replace(target, old / item.name)
                os.replace(item, target)
                shutil.rmtree(old, ignore_errors=True)
            else:
                os.replace(item, target)
            log.info("wrote %s", target)
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


def write_pvd(path, entries) -> Path:
    """A ParaView collection (``.pvd``) of ``(time [s], file name)`` entries.

    The data files are referenced relative to the ``.pvd`` (keep them in the
    same folder).  ParaView opens the ``.pvd`` as one time series.  Neither
    pyvista nor meshio writes this collection format (pyvista only reads it),
    so its small XML is written here.
    """
    from xml.sax.saxutils import quoteattr

    lines = ['<?xml version="1.0"?>',
             '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
             "  <Collection>"]
    for time, name in entries:
        lines.append(f"    <DataSet timestep={quoteattr(repr(float(time)))} group=\"\" part=\"0\" "
                     f"file={quoteattr(str(name))}/>")
    lines += ["  </Collection>", "</VTKFile>", ""]
    return write_text(path, "\n".join(lines))


def write_timeseries(path, time, columns: dict, meta: dict | None = None) -> Path:
    """A self-describing time series: ``.npz`` with ``"Time [s]"`` and one array
    per column (names carry units, e.g. ``"Ball 1 x [m]"``) plus a JSON
    ``"__meta__"`` entry (case, units convention, anything in ``meta``).

    Read it back with :func:`read_timeseries` (or ``numpy.load``).
    """
    import io

    import numpy as np

    buffer = io.BytesIO()
    arrays = {"Time [s]": np.asarray(time, dtype=float)}
    for name, value in columns.items():
        value = np.asarray(value)
        if value.shape[:1] != arrays["Time [s]"].shape:
            raise ValueError(f"column {name!r} has {value.shape[:1]} samples, time has {len(arrays['Time [s]'])}")
        arrays[name] = value
    header = {"format": "lubedyn time series", "version": 1, "columns": list(arrays), **(meta or {})}
    np.savez_compressed(buffer, __meta__=np.array(json.dumps(header, default=str)), **arrays)
    return write_bytes(path, buffer.getvalue())


def read_timeseries(path) -> tuple[dict, dict]:
    """(columns, meta) of a file written by :func:`write_timeseries`."""
    import numpy as np

    with np.load(path, allow_pickle=False) as data:
        meta = json.loads(str(data["__meta__"]))
        if meta.get("format") != "lubedyn time series":
            raise ValueError(f"{path}: not a lubedyn time series file")
        return {name: data[name] for name in meta["columns"]}, meta
