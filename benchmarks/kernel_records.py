"""The bearings' right-hand sides with their parameters as named records, against the packed vectors
they replaced: cost of one right-hand side call and the cold compile of a smoke run.

The kernels read their parameters from numba structured records by name (``P.kw``,
:mod:`lubedyn.dynamics.tapered.layout`, :mod:`lubedyn.dynamics.cageless.layout`) and their tables from
arrays of their own; before, from float vectors through index constants, tables appended past the end.
"before" is another checkout of the library (``--before``: the root of a checkout whose virtual
environment, ``.venv``, has it installed; default /work/main), measured in a subprocess with its own
interpreter; "after" is this checkout, the same way.  The two alternate, ``--repeats`` times each.

1. right-hand side per call [us]: the start state of each case (smoke size), ``rhs`` called ``n`` times
   in a compiled loop (as an integrator calls it; the best of 5 loops), and from Python (the dispatch,
   as :func:`lubedyn.dynamics.specialise` kernels are called once per chunk); the derivative's bytes
   are hashed, so the two sides are shown to compute the same numbers;
2. cold compile: wall and CPU time of ``lubedyn run CASE --smoke`` with a fresh ``NUMBA_CACHE_DIR`` (numba
   compiles every kernel; the second core compiles the integrator meanwhile), and warm (the same cache
   again).

Writes ``results/kernel_records.json`` and ``results/kernel_records.png`` with the machine noted; ratios
are after/before of the medians.  Speed is measured here, never asserted in tests.
``python benchmarks/kernel_records.py --before CHECKOUT [--repeats 3] [--no-compile]``
"""
from __future__ import annotations

import argparse
import hashlib
import importlib.util
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

_HERE = Path(__file__).resolve().parent
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != _HERE]

TAPERED = ("trb_fig5_2400rpm", "trb_fig5_tilt", "trb_fig5_traction_map")
CAGELESS = ("cageless_6206_10krpm_short", "cageless_6206_steady")
COMPILE_CASES = ("trb_fig5_2400rpm", "cageless_6206_10krpm_short")


# ---------------------------------------------------------------- worker (runs under either library)
def _worker(cases, n):
    """JSON of {case: {"jit_us", "python_us", "hash"}} for the library this interpreter imports."""
    from numba import njit

    from lubedyn.config import load_case

    @njit
    def loop(rhs, y, args, d, n):
        for _ in range(n):
            rhs(0.0, y, args, d)

    out = {}
    for name in cases:
        case = load_case(name, smoke=True)
        if name.startswith("trb"):
            from lubedyn.dynamics.tapered.kernels import rhs
            from lubedyn.scenes import tapered as S

            model = S.build(case)
            qs = model.quasi_static()
            y, args = model.start_state(qs), model.args(qs)
        else:
            from lubedyn.dynamics.cageless import rhs
            from lubedyn.scenes import dynamics as S

            setup = S.build(case)
            y, args = setup.y0, setup.model.args()
        d = np.zeros_like(y)
        rhs(0.0, y, args, d)
        digest = hashlib.sha256(d.tobytes()).hexdigest()[:16]
        loop(rhs, y, args, d, 2)
        jit = []
        for _ in range(5):
            t0 = time.perf_counter()
            loop(rhs, y, args, d, n)
            jit.append((time.perf_counter() - t0) / n)
        py = []
        for _ in range(5):
            t0 = time.perf_counter()
            for _ in range(n // 10):
                rhs(0.0, y, args, d)
            py.append((time.perf_counter() - t0) / (n // 10))
        out[name] = {"jit_us": 1e6 * min(jit), "python_us": 1e6 * min(py), "hash": digest}
    print(json.dumps(out))


def _python(root: Path) -> str:
    return str(root / ".venv" / "bin" / "python")


def _rhs_times(root: Path, cases, n, cache_dir):
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    proc = subprocess.run([_python(root), __file__, "--worker", "--n", str(n), *cases], cwd=root, env=env,
                          capture_output=True, text=True, check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _run_time(root: Path, case: str, cache_dir: str) -> tuple[float, float]:
    """(wall, CPU) seconds of ``lubedyn run case --smoke``; the CPU time (user + system of the run and of
    the second process it compiles in) is far less sensitive than the wall time to other jobs on the machine."""
    import resource

    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    out = tempfile.mkdtemp(prefix="kr_out_")
    try:
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run([str(root / ".venv" / "bin" / "lubedyn"), "run", case, "--smoke", "--out", out],
                       cwd=root, env=env, capture_output=True, text=True, check=True)
        wall = time.perf_counter() - t0
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        return wall, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    finally:
        shutil.rmtree(out, ignore_errors=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", type=Path, help="root of the checkout to compare with (its .venv is used); "
                    "required unless --worker")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--n", type=int, default=2000)
    ap.add_argument("--no-compile", action="store_true")
    ap.add_argument("--compile-only", action="store_true", help="keep the JSON's rhs times, measure the compile")
    ap.add_argument("--worker", action="store_true")
    ap.add_argument("cases", nargs="*")
    args = ap.parse_args(argv)
    if args.worker:
        return _worker(args.cases, args.n)
    if args.before is None:
        ap.error("--before CHECKOUT is required: the checkout of the code before the change (its .venv is used)")

    spec = importlib.util.spec_from_file_location("_common", _HERE / "_common.py")
    common = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(common)
    sides = {"before": args.before.resolve(), "after": common.ROOT}
    caches = {side: tempfile.mkdtemp(prefix=f"kr_cache_{side}_") for side in sides}
    rhs = {side: [] for side in sides}
    for _ in range(0 if args.compile_only else args.repeats):
        for side, root in sides.items():
            rhs[side].append(_rhs_times(root, TAPERED + CAGELESS, args.n, caches[side]))
    result = {"machine": common.machine_info(extra_packages=("numba", "llvmlite")),
              "before": str(sides["before"]), "repeats": args.repeats, "calls": args.n, "rhs": {}}
    if args.compile_only:
        result["rhs"] = json.loads((common.RESULTS / "kernel_records.json").read_text())["rhs"]
    for case in () if args.compile_only else TAPERED + CAGELESS:
        row = {}
        for side in sides:
            row[side] = {k: float(np.median([r[case][k] for r in rhs[side]])) for k in ("jit_us", "python_us")}
            row[side]["hash"] = rhs[side][0][case]["hash"]
        row["ratio jit"] = row["after"]["jit_us"] / row["before"]["jit_us"]
        row["ratio python"] = row["after"]["python_us"] / row["before"]["python_us"]
        row["same derivative"] = row["after"]["hash"] == row["before"]["hash"]
        result["rhs"][case] = row
    if not args.no_compile:
        result["compile"] = {}
        for case in COMPILE_CASES:
            row = {side: {"cold_s": [], "warm_s": [], "cold_cpu_s": [], "warm_cpu_s": []} for side in sides}
            for _ in range(max(1, args.repeats - 1)):
                for side, root in sides.items():
                    cache = tempfile.mkdtemp(prefix="kr_cold_")
                    try:
                        for kind in ("cold", "warm"):
                            wall, cpu = _run_time(root, case, cache)
                            row[side][f"{kind}_s"].append(wall)
                            row[side][f"{kind}_cpu_s"].append(cpu)
                    finally:
                        shutil.rmtree(cache, ignore_errors=True)
            for side in sides:
                row[side] = {k: float(np.median(v)) for k, v in row[side].items()} | {"runs": row[side]}
            row["ratio cold"] = row["after"]["cold_s"] / row["before"]["cold_s"]
            row["ratio cold CPU"] = row["after"]["cold_cpu_s"] / row["before"]["cold_cpu_s"]
            result["compile"][case] = row
    for cache in caches.values():
        shutil.rmtree(cache, ignore_errors=True)
    path = common.write_json(common.RESULTS / "kernel_records.json", result)
    _plot(result, common.RESULTS / "kernel_records.png")
    print(json.dumps({k: v for k, v in result.items() if k != "machine"}, indent=1))
    print(f"wrote {path}")


def _plot(result, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = list(result["rhs"])
    fig, axes = plt.subplots(1, 2 if "compile" in result else 1, figsize=(11, 4), squeeze=False)
    ax = axes[0, 0]
    x = np.arange(len(cases))
    for k, side in enumerate(("before", "after")):
        ax.bar(x + (k - 0.5) * 0.38, [result["rhs"][c][side]["jit_us"] for c in cases], 0.38,
               label=f"{side} ({'packed vector' if side == 'before' else 'named record'})")
    ax.set_xticks(x, [c.replace("_", "\n", 1) for c in cases], fontsize=7)
    ax.set_ylabel("right-hand side [us per call]")
    ax.set_title("rhs from a compiled loop, start state, smoke size")
    ax.legend(fontsize=8)
    if "compile" in result:
        ax = axes[0, 1]
        comp = list(result["compile"])
        x = np.arange(len(comp))
        for k, side in enumerate(("before", "after")):
            ax.bar(x + (k - 0.5) * 0.38, [result["compile"][c][side]["cold_s"] for c in comp], 0.38, label=side)
        ax.set_xticks(x, comp, fontsize=8)
        ax.set_ylabel("lubedyn run --smoke, fresh numba cache [s]")
        ax.set_title("cold compile + run")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
