"""Hashes and versions that identify what a map was built from.

Part of :mod:`lubedyn.maps` (the package docstring gives the overview)."""
from __future__ import annotations

from pathlib import Path
import hashlib
import inspect
import json
import platform

import numpy as np

# ---------------------------------------------------------------------------
# hashing and versions


def _canonical(obj) -> str:
    """JSON with sorted keys and floats written exactly (hex), for hashing."""

    def plain(o):
        if isinstance(o, dict):
            return {str(k): plain(v) for k, v in sorted(o.items(), key=lambda kv: str(kv[0]))}
        if isinstance(o, (list, tuple)):
            return [plain(v) for v in o]
        if isinstance(o, np.ndarray):
            return [plain(v) for v in o.tolist()]
        if isinstance(o, (float, np.floating)):
            return float(o).hex()
        if isinstance(o, np.integer):
            return int(o)
        return o

    return json.dumps(plain(obj), sort_keys=True)


def sha256_text(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()


def code_fingerprint(kind) -> dict:
    """sha256 of the kind's source file and of ``lubedyn.lubrication``'s ``**/*.py`` (the solver and the laws), and the
    lubedyn version."""
    from lubedyn import __version__  # deferred: importlib.metadata, scikit-fem

    out = {"lubedyn": __version__}
    try:
        src = Path(inspect.getsourcefile(kind.evaluate))
        out[f"kind source {src.name}"] = hashlib.sha256(src.read_bytes()).hexdigest()
    except (TypeError, OSError):
        out["kind source"] = "unavailable"
    from lubedyn import lubrication  # deferred: importlib.metadata, scikit-fem

    digest = hashlib.sha256()
    root = Path(lubrication.__file__).parent
    for p in sorted(root.rglob("*.py")):
        digest.update(p.relative_to(root).as_posix().encode())
        digest.update(p.read_bytes())
    out["lubrication sources"] = digest.hexdigest()
    return out


def versions() -> dict:
    from importlib.metadata import PackageNotFoundError, version

    out = {"python": platform.python_version()}
    for dist in ("lubedyn", "numpy", "scipy", "scikit-fem", "numba", "dask", "distributed"):
        try:
            out[dist] = version(dist)
        except PackageNotFoundError:
            out[dist] = None
    return out


def point_hash(kind_name: str, params: dict, point: dict, code: dict) -> str:
    return sha256_text(_canonical({"kind": kind_name, "params": params, "point": point, "code": code}))
