"""Record every bundled case's results and compare two recordings (bit-identical by default).

Made for refactors that must not change any number: record on the code before the
change, record again after it, compare.

::

    python benchmarks/case_summaries.py record OUT.json [--smoke|--full] [--only NAME ...]
                                             [--root CHECKOUT] [--python PYTHON] [--timeout S]
    python benchmarks/case_summaries.py compare A.json B.json [--rtol R] [--ignore TEXT ...]

``record`` runs each ``cases/*.toml`` of the checkout ``--root`` (default: the checkout holding
this script) with ``PYTHON -m lubedyn.cli run CASE [--smoke] --out TMP``, one subprocess per case,
each into a fresh temporary folder (so no map cache of an earlier run is reused), and checks first
that the code the runs import is the checkout's.  A checkout of the one-namespace layout
(``pyproject.toml`` maps ``lubedyn`` onto ``coupling/``) is importable only installed, so ``--python``
(default: this interpreter) must have it installed (``pip install -e CHECKOUT``); a checkout of the
earlier layout (top-level ``coupling``, ``lubrication``, ``dynamics``) runs as ``python -m coupling.cli``
with the checkout first on ``sys.path``, from any interpreter with the dependencies, so that a
recording of an older commit can be compared with one of the current code.  Per case it keeps:

- ``summary``: every value of ``summary.json`` except the excluded keys below;
- ``arrays``: for each array of the outputs, its dtype, shape, the sha256 of its bytes and a few
  statistics (min, max, mean, norm, first, last; NaN-aware) so that a difference can be sized:
  every array of ``*.npz`` (time series, film maps), the points, cells, point and cell data of
  every ``.vtu``/``.vtp`` field file (read with VTK), the numeric columns of ``*.csv``;
- ``metadata``: the JSON stored in the npz files (time-series ``__meta__`` with its copy of the
  summary, the map ``header``: axes, outputs, provenance parameters, fits, accuracy), minus the
  excluded keys (of both lists);
- ``files``: the manifest's list of written files (plots included, their pixels are not compared)
  and the ``.pvd`` indices (time step, file);
- ``exit code`` of the run.

Excluded, because they measure the machine or the moment, not the result (decided by reading
every bundled case's summary.json, map header and time-series metadata):

- timings: ``Solve time [s]``, ``Build time [s]``, ``Run time [s]``, ``Wall time [s]``,
  ``Integration wall time [s]``, ``Simulated time per wall second [s/s]``, ``Benettin time [s]``
  (the wall time of the Benettin run), ``Output write time [s]``, ``Map build time [s]``, and in
  the map header ``build time [s]`` and ``built`` (a date);
- the machine: ``Backend`` (``local processes (N)``, N = cores) and ``backend``; the map header's
  ``versions`` (Python and library versions);
- hashes of the source code: ``Map input sha256`` and the header's ``input sha256`` and ``code``
  (they hash ``lubrication/**/*.py`` and the kind's source file, so any edit changes them);
- paths: ``loaded from cache`` (a path); the resolved case (``case.resolved.toml``) is not kept:
  it is the input and carries the path of the case file.
  Physical times such as ``Simulated time [s]`` or ``Benettin averaging time [s]`` are kept.

``compare`` prints every difference (case, key, a, b, relative difference) and exits 0 when the
two recordings are identical (floats bit for bit), 1 otherwise.  ``--rtol R`` accepts floats with
``|a - b| <= R max(|a|, |b|)``; arrays whose bytes differ are then judged by their statistics
within R (their digest cannot be compared with a tolerance) and listed as "bits differ".
``--ignore TEXT`` skips keys containing TEXT (explicit, printed).  Cases recorded in only one
file are differences.

Run time (2 shared cores, load 1-2.6, 2026-11-24): ``--smoke`` 65-67 s for the 18 bundled cases
with a warm numba cache (dynamics cases about 2.8 s each, map builds 3-24 s, films and EHL about
1 s), 77 s with a cold one; ``--full`` about 16 minutes (934 s; the EHL ball maps 457 and
164 s, the ball-ball map 190 s; per case in ``benchmarks/README.md``, "Case summaries").
"""
from __future__ import annotations

import argparse
import hashlib
import json
import math
import re
import os
import platform
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

FORMAT = "lubedyn case summaries"
EXCLUDED_SUMMARY_KEYS = frozenset({
    "Solve time [s]", "Build time [s]", "Run time [s]", "Wall time [s]", "Integration wall time [s]",
    "Simulated time per wall second [s/s]", "Benettin time [s]", "Output write time [s]",
    "Map build time [s]", "Backend", "Map input sha256",
})
EXCLUDED_METADATA_KEYS = frozenset({
    "build time [s]", "built", "backend", "versions", "code", "input sha256", "loaded from cache",
})


# ---------------------------------------------------------------- recording
def _clean(value, excluded):
    """``value`` with the keys in ``excluded`` removed at every depth."""
    if isinstance(value, dict):
        return {k: _clean(v, excluded) for k, v in value.items() if k not in excluded}
    if isinstance(value, list):
        return [_clean(v, excluded) for v in value]
    return value


def _float(x) -> float | None:
    """A float for JSON (``None`` for NaN; infinities as strings would lose the sign, so keep them)."""
    x = float(x)
    return None if math.isnan(x) else x


def array_record(a) -> dict:
    """dtype, shape, sha256 of the bytes and NaN-aware statistics of one array."""
    a = np.asarray(a)
    out = {"dtype": str(a.dtype), "shape": list(a.shape),
           "sha256": hashlib.sha256(np.ascontiguousarray(a).tobytes()).hexdigest()}
    if a.dtype.kind in "fiub" and a.size:
        f = a.astype(float).ravel()
        finite = f[np.isfinite(f)]
        out["nan count"] = int(np.isnan(f).sum())
        if finite.size:
            out.update({"min": _float(finite.min()), "max": _float(finite.max()), "mean": _float(finite.mean()),
                        "norm": _float(np.linalg.norm(finite)), "first": _float(f[0]), "last": _float(f[-1])})
    return out


def _npz(path: Path, arrays: dict, metadata: dict, rel: str) -> None:
    with np.load(path, allow_pickle=False) as z:
        for name in z.files:
            a = z[name]
            if a.dtype.kind == "U" and a.ndim == 0:  # JSON metadata (time-series __meta__, map header)
                try:
                    metadata[f"{rel}:{name}"] = _clean(json.loads(str(a)),
                                                       EXCLUDED_METADATA_KEYS | EXCLUDED_SUMMARY_KEYS)
                    continue
                except json.JSONDecodeError:
                    pass
            arrays[f"{rel}:{name}"] = array_record(a)


def _mesh(path: Path, arrays: dict, rel: str) -> None:
    """Points, cells and point/cell/field data of a VTK XML file (``.vtu``, ``.vtp``), read with VTK."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader

    reader = vtkXMLPolyDataReader() if path.suffix == ".vtp" else vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    data = reader.GetOutput()
    if data.GetPoints() is not None:
        arrays[f"{rel}:points"] = array_record(vtk_to_numpy(data.GetPoints().GetData()))
    if path.suffix == ".vtu":
        blocks = {"cells": data.GetCells()}
        arrays[f"{rel}:cell types"] = array_record(vtk_to_numpy(data.GetCellTypes()))
    else:
        blocks = {kind.lower(): getattr(data, f"Get{kind}")() for kind in ("Verts", "Lines", "Polys", "Strips")}
    for kind, cells in blocks.items():
        if cells.GetNumberOfCells():
            arrays[f"{rel}:{kind} offsets"] = array_record(vtk_to_numpy(cells.GetOffsetsArray()))
            arrays[f"{rel}:{kind} connectivity"] = array_record(vtk_to_numpy(cells.GetConnectivityArray()))
    for label, fields in (("point data", data.GetPointData()), ("cell data", data.GetCellData()),
                          ("field data", data.GetFieldData())):
        for i in range(fields.GetNumberOfArrays()):
            a = fields.GetAbstractArray(i)
            if a.IsNumeric():
                arrays[f"{rel}:{label} {a.GetName()}"] = array_record(vtk_to_numpy(a))
            else:
                text = "\n".join(a.GetValue(j) for j in range(a.GetNumberOfValues()))
                arrays[f"{rel}:{label} {a.GetName()}"] = {"sha256": hashlib.sha256(text.encode()).hexdigest()}


def _csv(path: Path, arrays: dict, rel: str) -> None:
    lines = path.read_text(encoding="utf-8").splitlines()
    if not lines:
        return
    header = lines[0].split(",")
    rows = [line.split(",") for line in lines[1:] if line.strip()]
    for j, name in enumerate(header):
        column = [r[j] for r in rows if j < len(r)]
        try:
            arrays[f"{rel}:{name}"] = array_record(np.array([float(x) for x in column]))
        except ValueError:  # a text column
            arrays[f"{rel}:{name}"] = {"sha256": hashlib.sha256("\n".join(column).encode()).hexdigest()}


def _pvd(path: Path) -> list:
    root = ET.parse(path).getroot()
    return [[d.get("timestep"), d.get("file")] for d in root.iter("DataSet")]


def collect(out: Path) -> dict:
    """The recorded results of one run folder ``out`` (see the module docstring)."""
    rec: dict = {"summary": {}, "arrays": {}, "metadata": {}, "files": {}}
    summary = out / "summary.json"
    if summary.is_file():
        rec["summary"] = _clean(json.loads(summary.read_text(encoding="utf-8")), EXCLUDED_SUMMARY_KEYS)
    manifest = out / "manifest.json"
    if manifest.is_file():
        rec["files"]["manifest"] = json.loads(manifest.read_text(encoding="utf-8")).get("files")
    for path in sorted(p for p in out.rglob("*") if p.is_file()):
        rel = path.relative_to(out).as_posix()
        if rel.startswith("."):  # .map-cache: the point store, same numbers as the map
            continue
        if path.suffix == ".npz":
            _npz(path, rec["arrays"], rec["metadata"], rel)
        elif path.suffix in (".vtu", ".vtp"):
            _mesh(path, rec["arrays"], rel)
        elif path.suffix == ".csv":
            _csv(path, rec["arrays"], rel)
        elif path.suffix == ".pvd":
            rec["files"][rel] = _pvd(path)
    return rec


def bundled_cases(root: Path) -> list[Path]:
    return sorted((root / "cases").glob("*.toml"))


def namespace_layout(root: Path) -> bool:
    """Whether the checkout ``root`` installs one namespace, ``lubedyn``, rather than the top-level
    packages ``coupling``, ``lubrication`` and ``dynamics`` of the earlier layout."""
    import tomllib

    pyproject = Path(root) / "pyproject.toml"
    if not pyproject.is_file():
        return False
    setuptools = tomllib.loads(pyproject.read_text(encoding="utf-8")).get("tool", {}).get("setuptools", {})
    return "lubedyn" in setuptools.get("package-dir", {})


def packages(root: Path) -> tuple[str, ...]:
    """The CLI module, then the packages whose code the runs of ``root`` import."""
    if namespace_layout(root):
        return ("lubedyn.cli", "lubedyn", "lubedyn.lubrication", "lubedyn.dynamics")
    return ("coupling.cli", "coupling", "lubrication", "dynamics")


def _env(root: Path) -> dict:
    env = dict(os.environ)
    if not namespace_layout(root):  # the earlier layout: the checkout first on sys.path
        env["PYTHONPATH"] = str(root) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["MPLBACKEND"] = "Agg"
    return env


def _code_paths(root: Path, python: str) -> dict:
    """Where the packages imported by the runs live (must be under ``root``)."""
    names = packages(root)[1:]
    code = (f"import importlib, json; mods = [importlib.import_module(n) for n in {names!r}]; "
            "print(json.dumps({m.__name__: m.__file__ for m in mods}))")
    done = subprocess.run([python, "-c", code], cwd=root, env=_env(root), capture_output=True, text=True)
    if done.returncode != 0:
        last = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else f"exit {done.returncode}"
        raise SystemExit(f"case_summaries: error: {python} cannot import {', '.join(names)}: {last}"
                         + ("; install the checkout into it (pip install -e ROOT)" if namespace_layout(root) else ""))
    return json.loads(done.stdout)


def _git(root: Path) -> dict:
    def git(*args):
        try:
            return subprocess.run(["git", *args], cwd=root, capture_output=True, text=True,
                                  check=True).stdout.strip()
        except (OSError, subprocess.CalledProcessError):
            return None

    status = git("status", "--porcelain", "--", "coupling", "lubrication", "dynamics", "cases")
    return {"commit": git("rev-parse", "HEAD"), "library or cases changed since commit": bool(status)}


def run_case(case: Path, root: Path, *, smoke: bool, python: str, timeout: float) -> tuple[dict, float]:
    """Run one case in a subprocess into a temporary folder and :func:`collect` its results."""
    with tempfile.TemporaryDirectory(prefix=f"case-summaries-{case.stem}-") as tmp:
        out = Path(tmp) / "out"
        cmd = [python, "-m", packages(root)[0], "run", str(case), "--out", str(out)] + (["--smoke"] if smoke else [])
        t0 = time.perf_counter()
        try:
            done = subprocess.run(cmd, cwd=root, env=_env(root), capture_output=True, text=True, timeout=timeout)
            code, stderr = done.returncode, done.stderr
        except subprocess.TimeoutExpired:
            code, stderr = None, f"timed out after {timeout} s"
        seconds = time.perf_counter() - t0
        rec = collect(out) if out.is_dir() else {"summary": {}, "arrays": {}, "metadata": {}, "files": {}}
    rec["exit code"] = code
    if code != 0:
        rec["stderr"] = " ".join(stderr.replace(tmp, "<out>").split())[-2000:]
    return rec, seconds


def record(path: Path, *, smoke: bool, only=(), root: Path = ROOT, timeout: float = 3600.0,
           python: str = sys.executable) -> dict:
    """Run the bundled cases of ``root`` and write the recording to ``path`` (JSON)."""
    root = Path(root).resolve()
    cases = bundled_cases(root)
    if only:
        names = {c.stem for c in cases}
        unknown = [n for n in only if n not in names]
        if unknown:
            raise SystemExit(f"case_summaries: error: --only {' '.join(unknown)}: not a bundled case of {root}; "
                             f"bundled: {', '.join(sorted(names))}")
        cases = [c for c in cases if c.stem in set(only)]
    code_paths = _code_paths(root, python)
    outside = {m: p for m, p in code_paths.items() if not Path(p).resolve().is_relative_to(root)}
    if outside:
        raise SystemExit(f"case_summaries: error: the runs would import {outside}, not the code of {root}"
                         + ("; install the checkout into the interpreter (pip install -e ROOT), or name one that "
                            "has it (--python)" if namespace_layout(root) else ""))
    out = {"format": FORMAT, "version": 1, "resolution": "smoke" if smoke else "full",
           "excluded summary keys": sorted(EXCLUDED_SUMMARY_KEYS),
           "excluded metadata keys": sorted(EXCLUDED_METADATA_KEYS | EXCLUDED_SUMMARY_KEYS),
           "machine (not compared)": _machine(root, code_paths), "cases": {}, "seconds (not compared)": {}}
    t0 = time.perf_counter()
    for case in cases:
        rec, seconds = run_case(case, root, smoke=smoke, python=python, timeout=timeout)
        out["cases"][case.stem] = rec
        out["seconds (not compared)"][case.stem] = round(seconds, 2)
        print(f"{case.stem:<28} exit {rec['exit code']}  {seconds:7.1f} s  "
              f"{len(rec['summary'])} summary values, {len(rec['arrays'])} arrays", flush=True)
    out["seconds (not compared)"]["total"] = round(time.perf_counter() - t0, 2)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(out, indent=1, allow_nan=True) + "\n", encoding="utf-8")
    os.replace(tmp, path)
    return out


def _machine(root: Path, code_paths: dict) -> dict:
    try:
        cpu = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                    if line.startswith("model name")), platform.processor())
    except OSError:
        cpu = platform.processor()
    return {"recorded [UTC]": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "cpu": cpu,
            "logical cpus": os.cpu_count(), "os": platform.platform(), "python": platform.python_version(),
            "numpy": np.__version__, "root": str(root), "git": _git(root), "code imported from": code_paths,
            "load average at start": list(os.getloadavg()) if hasattr(os, "getloadavg") else None}


# ---------------------------------------------------------------- comparing
def _rel(a: float, b: float) -> float:
    scale = max(abs(a), abs(b))
    return 0.0 if a == b else (math.inf if scale == 0 else abs(a - b) / scale)


# the temporary folder a case ran in (``tempfile``'s prefix + 8 random characters), named in texts such as
# a warning about the map file a map case wrote: not a result, so compared as ``<run folder>``
_RUN_FOLDER = re.compile(r"[^\s'\"]*case-summaries-[\w.-]+?-[a-z0-9_]{8}")


def _same(a, b, rtol: float) -> tuple[bool, float | None]:
    """(equal, relative difference or None for non-numbers); floats bit for bit when ``rtol`` is 0; texts
    equal up to the temporary run folder they name."""
    if isinstance(a, str) and isinstance(b, str):
        return _RUN_FOLDER.sub("<run folder>", a) == _RUN_FOLDER.sub("<run folder>", b), None
    numbers = (int, float)
    if isinstance(a, numbers) and isinstance(b, numbers) and not isinstance(a, bool) and not isinstance(b, bool):
        a, b = float(a), float(b)
        if math.isnan(a) or math.isnan(b):
            return math.isnan(a) and math.isnan(b), None
        rel = _rel(a, b)
        if rtol == 0:
            return a == b and math.copysign(1, a) == math.copysign(1, b), rel
        return rel <= rtol, rel
    return a == b, None


def _walk(a, b, key: str, rtol: float, out: list) -> None:
    if isinstance(a, dict) and isinstance(b, dict):
        for k in list(a) + [k for k in b if k not in a]:
            sub = f"{key} / {k}" if key else str(k)
            if k not in b:
                out.append((sub, a[k], "(missing)", None))
            elif k not in a:
                out.append((sub, "(missing)", b[k], None))
            else:
                _walk(a[k], b[k], sub, rtol, out)
        return
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            _walk(x, y, f"{key}[{i}]", rtol, out)
        return
    same, rel = _same(a, b, rtol)
    if not same:
        out.append((key, a, b, rel))


def _compare_array(a: dict, b: dict, key: str, rtol: float, out: list, notes: list) -> None:
    if a.get("sha256") == b.get("sha256") and a.get("shape") == b.get("shape") and a.get("dtype") == b.get("dtype"):
        return
    if rtol == 0 or a.get("shape") != b.get("shape") or a.get("dtype") != b.get("dtype") or "min" not in a:
        found: list = []
        _walk({k: v for k, v in a.items()}, {k: v for k, v in b.items()}, key, 0.0, found)
        out.extend(found or [(f"{key} / sha256", a.get("sha256"), b.get("sha256"), None)])
        return
    found = []
    _walk({k: v for k, v in a.items() if k != "sha256"}, {k: v for k, v in b.items() if k != "sha256"},
          key, rtol, found)
    if found:
        out.extend(found)
    else:
        notes.append(f"{key}: bits differ, statistics within rtol {rtol:g}")


def differences(a: dict, b: dict, *, rtol: float = 0.0, ignore=()) -> tuple[list, list]:
    """``(differences, notes)`` between two recordings: differences are ``(key, a, b, relative
    difference or None)``; notes list arrays accepted by their statistics under ``rtol``."""
    out: list = []
    notes: list = []
    if a.get("resolution") != b.get("resolution"):
        out.append(("resolution", a.get("resolution"), b.get("resolution"), None))
    ca, cb = a.get("cases", {}), b.get("cases", {})
    for name in list(ca) + [n for n in cb if n not in ca]:
        if name not in cb or name not in ca:
            out.append((name, "(recorded)" if name in ca else "(missing)",
                        "(recorded)" if name in cb else "(missing)", None))
            continue
        ra, rb = ca[name], cb[name]
        for part in ("exit code", "summary", "metadata", "files"):
            _walk(ra.get(part), rb.get(part), f"{name} / {part}", rtol, out)
        arr_a, arr_b = ra.get("arrays", {}), rb.get("arrays", {})
        for k in list(arr_a) + [k for k in arr_b if k not in arr_a]:
            key = f"{name} / arrays / {k}"
            if k not in arr_b or k not in arr_a:
                out.append((key, "(recorded)" if k in arr_a else "(missing)",
                            "(recorded)" if k in arr_b else "(missing)", None))
            else:
                _compare_array(arr_a[k], arr_b[k], key, rtol, out, notes)
    if ignore:
        out = [d for d in out if not any(text in d[0] for text in ignore)]
        notes = [n for n in notes if not any(text in n for text in ignore)]
    return out, notes


def _show(v) -> str:
    text = repr(v)
    return text if len(text) <= 80 else text[:77] + "..."


def compare(path_a: Path, path_b: Path, *, rtol: float = 0.0, ignore=(), stream=None) -> int:
    """Print the differences of two recordings; 0 if identical (within ``rtol``), 1 otherwise."""
    stream = stream or sys.stdout
    a = json.loads(Path(path_a).read_text(encoding="utf-8"))
    b = json.loads(Path(path_b).read_text(encoding="utf-8"))
    for p, rec in ((path_a, a), (path_b, b)):
        if rec.get("format") != FORMAT:
            raise SystemExit(f"case_summaries: error: {p}: not a case-summaries recording")
    diffs, notes = differences(a, b, rtol=rtol, ignore=ignore)
    if ignore:
        print(f"ignoring keys containing: {', '.join(map(repr, ignore))}", file=stream)
    for note in notes:
        print(f"note: {note}", file=stream)
    for key, va, vb, rel in diffs:
        rel_text = "" if rel is None else f"  rel {rel:.3e}"
        print(f"{key}: {_show(va)} -> {_show(vb)}{rel_text}", file=stream)
    n_cases = len(set(a.get("cases", {})) | set(b.get("cases", {})))
    what = "identical" if rtol == 0 else f"equal within rtol {rtol:g}"
    if diffs:
        print(f"{len(diffs)} differences over {n_cases} cases", file=stream)
        return 1
    print(f"{what}: {n_cases} cases", file=stream)
    return 0


# ---------------------------------------------------------------- command line
def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="case_summaries", description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("record", help="run the bundled cases and record their results")
    r.add_argument("out", type=Path, help="recording to write (JSON)")
    res = r.add_mutually_exclusive_group()
    res.add_argument("--smoke", dest="smoke", action="store_true", default=True,
                     help="smoke resolution (default)")
    res.add_argument("--full", dest="smoke", action="store_false", help="the cases' full resolution")
    r.add_argument("--only", nargs="+", default=(), metavar="NAME", help="only these bundled cases")
    r.add_argument("--root", type=Path, default=ROOT, help="checkout whose code and cases run (default: %(default)s)")
    r.add_argument("--python", default=sys.executable,
                   help="interpreter that runs the cases (default: this one); for a checkout of the one-namespace "
                        "layout it must have the checkout installed")
    r.add_argument("--timeout", type=float, default=3600.0, help="seconds per case (default %(default)s)")
    c = sub.add_parser("compare", help="compare two recordings: exit 0 identical, 1 different")
    c.add_argument("a", type=Path)
    c.add_argument("b", type=Path)
    c.add_argument("--rtol", type=float, default=0.0, help="relative tolerance on floats (default 0: bit-identical)")
    c.add_argument("--ignore", nargs="+", default=(), metavar="TEXT", help="skip keys containing TEXT")
    args = p.parse_args(argv)
    if args.command == "record":
        rec = record(args.out, smoke=args.smoke, only=args.only, root=args.root, timeout=args.timeout,
                     python=args.python)
        failed = [n for n, c in rec["cases"].items() if c["exit code"] != 0]
        if failed:
            print(f"non-zero exit: {', '.join(failed)} (recorded with their stderr)")
        print(f"wrote {args.out} ({rec['seconds (not compared)']['total']:.0f} s)")
        return 0
    if args.rtol < 0 or not math.isfinite(args.rtol):
        p.error(f"--rtol = {args.rtol}: a finite number >= 0")
    return compare(args.a, args.b, rtol=args.rtol, ignore=args.ignore)


if __name__ == "__main__":
    sys.exit(main())
