"""Shared helpers of the benchmark scripts: machine description, timing,
reference values, atomic output.

Nothing here is imported by the library or by the tests.  Timings are wall
clock (``time.perf_counter``) medians of a few repeats; a machine that other
jobs share gives noisy numbers, which is why every script also reports times
as ratios against a reference run made in the same process.
"""
from __future__ import annotations

import hashlib
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from importlib import metadata
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RESULTS = Path(__file__).resolve().parent / "results"


# ---------------------------------------------------------------- machine
def _cpuinfo() -> dict:
    out: dict = {}
    try:
        text = Path("/proc/cpuinfo").read_text()
    except OSError:
        return {"model name": platform.processor() or "unknown"}
    for line in text.splitlines():
        if ":" not in line:
            continue
        key, value = (s.strip() for s in line.split(":", 1))
        if key in ("model name", "cpu MHz", "cache size", "flags") and key not in out:
            out[key] = value
    flags = set(out.pop("flags", "").split())
    out["simd"] = sorted(f for f in ("sse4_2", "avx", "avx2", "fma", "avx512f") if f in flags)
    return out


def _meminfo_gib() -> float | None:
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemTotal:"):
                return round(int(line.split()[1]) / 2**20, 1)
    except OSError:
        pass
    return None


def _version(dist: str) -> str | None:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return None


def _blas() -> list:
    """BLAS/OpenMP pools as threadpoolctl sees them (after numpy/scipy are imported)."""
    try:
        import scipy.linalg  # noqa: F401  (loads scipy's BLAS)
        from threadpoolctl import threadpool_info
    except ImportError:
        return [{"note": "threadpoolctl not installed"}]
    keep = ("user_api", "internal_api", "version", "num_threads", "threading_layer", "architecture", "filepath")
    return [{k: v for k, v in pool.items() if k in keep} for pool in threadpool_info()]


def _git() -> dict:
    """Commit, dirty flag and a hash of the library sources actually measured."""
    info: dict = {}
    try:
        info["commit"] = subprocess.run(
            ["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True, check=True
        ).stdout.strip()
        status = subprocess.run(
            ["git", "status", "--porcelain", "--", "lubrication"], cwd=ROOT, capture_output=True, text=True, check=True
        ).stdout
        info["lubrication_dirty"] = bool(status.strip())
    except (OSError, subprocess.CalledProcessError):
        info["commit"] = None
    digest = hashlib.sha256()
    for path in sorted((ROOT / "lubrication").rglob("*.py")):  # the solvers' packages and the laws too
        digest.update(path.relative_to(ROOT).as_posix().encode())
        digest.update(path.read_bytes())
    info["lubrication_sources_sha256"] = digest.hexdigest()[:16]
    return info


def machine_info(extra_packages=()) -> dict:
    """What ran the benchmark: CPU, cores, memory, Python and library versions, BLAS."""
    packages = ("numpy", "scipy", "scikit-fem", "pyamg", "matplotlib", "threadpoolctl") + tuple(extra_packages)
    try:
        affinity = len(os.sched_getaffinity(0))
    except AttributeError:
        affinity = None
    return {
        "cpu": _cpuinfo(),
        "logical_cpus": os.cpu_count(),
        "cpus_available_to_process": affinity,
        "memory_GiB": _meminfo_gib(),
        "os": platform.platform(),
        "python": sys.version.split()[0],
        "python_implementation": platform.python_implementation(),
        "packages": {name: _version(name) for name in packages},
        "blas": _blas(),
        "git": _git(),
        "load_average_at_start": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
    }


# ---------------------------------------------------------------- timing
def timed(fn, repeats: int = 3, single_above: float = 30.0):
    """Run ``fn()`` ``repeats`` times (once if the first run exceeds
    ``single_above`` seconds); return ``(median seconds, all seconds, last result)``."""
    times, result = [], None
    for i in range(max(1, repeats)):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
        if i == 0 and times[0] > single_above:
            break
    return float(np.median(times)), [float(t) for t in times], result


# ---------------------------------------------------------------- references
def richardson(values, ratio: float = 2.0) -> dict:
    """Reference value from the last three of a sequence refined by ``ratio``.

    If the last two differences have the same sign and shrink, the observed
    order p = log(d1/d2)/log(ratio) is used to extrapolate; otherwise (a
    non-monotone sequence, as free-boundary problems give) the finest value is
    the reference and the last difference its uncertainty.
    """
    v = [float(x) for x in values]
    out = {"finest": v[-1]}
    if len(v) < 3:
        out.update(method="finest value (fewer than 3 levels)", value=v[-1],
                   uncertainty=abs(v[-1] - v[-2]) if len(v) > 1 else None, observed_order=None)
        return out
    d1, d2 = v[-2] - v[-3], v[-1] - v[-2]
    if d1 * d2 > 0 and abs(d2) < abs(d1):
        p = float(np.log(d1 / d2) / np.log(ratio))
        corr = d2 / (ratio**p - 1.0)
        out.update(method="Richardson extrapolation with the observed order", value=v[-1] + corr,
                   observed_order=p, uncertainty=abs(corr))
    else:
        out.update(method="finest value (sequence not monotone: no extrapolation)", value=v[-1],
                   observed_order=None, uncertainty=abs(d2))
    return out


def time_to_error(times, errors, targets=(1e-2, 1e-3, 1e-4)) -> dict:
    """Wall time to reach each target error, interpolated log-log along the
    (time-sorted) series; ``None`` when the series does not bracket it."""
    t = np.asarray(times, dtype=float)
    e = np.asarray(errors, dtype=float)
    order = np.argsort(t)
    t, e = t[order], e[order]
    out = {}
    for target in targets:
        key = f"{target:.0e}"
        hits = np.flatnonzero(e <= target)
        if hits.size == 0:
            out[key] = None
            continue
        j = int(hits[0])
        if j == 0:
            out[key] = float(t[0])  # reached at the cheapest point already: an upper bound
            continue
        e0, e1, t0, t1 = e[j - 1], e[j], t[j - 1], t[j]
        if e1 <= 0 or e0 <= e1:
            out[key] = float(t1)
            continue
        s = (np.log(target) - np.log(e0)) / (np.log(e1) - np.log(e0))
        out[key] = float(np.exp(np.log(t0) + s * (np.log(t1) - np.log(t0))))
    return out


def fitted_order(sizes, errors) -> float | None:
    """Slope of log(error) against log(1/sqrt(dofs)) (2-D films), by ``np.polyfit``."""
    n = np.asarray(sizes, dtype=float)
    e = np.asarray(errors, dtype=float)
    ok = e > 0
    if ok.sum() < 2:
        return None
    return float(np.polyfit(np.log(1.0 / np.sqrt(n[ok])), np.log(e[ok]), 1)[0])


# ---------------------------------------------------------------- output
def _default(obj):
    from lubedyn.outputs import json_default

    return json_default(obj)


def _publish(tmp: str, path: Path) -> None:
    """Move a finished temporary file into place with ordinary permissions
    (``mkstemp`` creates files readable by their owner only)."""
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)
    os.replace(tmp, path)


def write_json(path: Path, data) -> Path:
    """Write ``data`` as JSON atomically (a crash leaves the old file intact)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(suffix=".json", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as fh:
            json.dump(data, fh, indent=1, default=_default, allow_nan=True)
            fh.write("\n")
        _publish(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path


def save_figure(fig, path: Path) -> Path:
    """Save a matplotlib figure atomically."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=130)
        _publish(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path
