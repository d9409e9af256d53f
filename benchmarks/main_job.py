"""The README's main job, before and after issue 42 (decisions 1 and 2), cold and warm, interleaved; and how its
outputs are best written off the critical path (serially, by threads, by forked processes).

    python benchmarks/main_job.py --before /path/to/checkout --before-python /path/to/its/venv/bin/python
                                  [--rounds 2] [--write-repeats 2] [--skip-runs] [--skip-writers]

(1) Runs.  Each round runs ``lubedyn run <case> --out <tmp>`` in a fresh process for the "before" checkout
(its own interpreter, whose editable install points at it) and for this one (this interpreter), each first
with ``NUMBA_CACHE_DIR`` a new empty folder (cold: every kernel compiles) and then again with the same folder
(warm).  Recorded per run: wall time of the process, CPU seconds of the process and the children it waited
for (``resource.getrusage(RUSAGE_CHILDREN)``: the forked output workers count, the background compiler of a
cold start, which is not waited for, does not), the 1-minute load average before it, and the run's own
build, integration and output-write times.  Ratios after/before are taken within each round (the runs of a
round are seconds apart, so they share the machine's load) and their median reported.

(2) Writers.  One in-process integration of the case, then its outputs written ``--write-repeats`` times each
way, interleaved: ``serial`` (frames, figures, time series one after another), ``threads`` (frames and
figures each in a thread beside the time series) and ``workers`` (each in a forked process:
:class:`lubedyn.outputs.ForkedWriter`, what ``lubedyn run`` does).  Wall and CPU seconds (this process and
its reaped children); the ratios against ``serial`` of the same repeat.

(3) GIL (``--gil``): :func:`gil`, whether each output job (VTK frames, figures, the netCDF write) releases
the GIL, which decides between a thread and a process for it.

Writes ``results/main_job.json`` and ``results/main_job.png``.
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS, ROOT, machine_info, save_figure, write_json  # noqa: E402

CASE = "cases/cageless_6206_10krpm_short.toml"
SUMMARY_TIMES = ("Build time [s]", "Integration wall time [s]", "Run time [s]", "Output write time [s]",
                 "Benettin time [s]")


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _self_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def one_run(python: str, root: Path, case: str, cache: Path, out: Path) -> dict:
    """``lubedyn run`` of ``case`` in a fresh process of ``python`` from ``root`` with the numba cache ``cache``."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), MPLBACKEND="Agg")
    load = os.getloadavg()[0]
    cpu0, t0 = _children_cpu(), time.perf_counter()
    p = subprocess.run([python, "-m", "lubedyn.cli", "run", case, "--out", str(out)], cwd=root, env=env,
                       capture_output=True, text=True)
    r = {"wall [s]": time.perf_counter() - t0, "cpu [s]": _children_cpu() - cpu0, "load before [-]": load,
         "returncode": p.returncode}
    summary = out / "summary.json"
    if p.returncode == 0 and summary.is_file():
        s = json.loads(summary.read_text())
        r.update({k: s.get(k) for k in SUMMARY_TIMES if k in s})
        r["terminal"] = p.stdout.splitlines()[-4:]
    else:
        r["stderr"] = p.stderr[-1500:]
    return r


def runs(before: Path, before_python: str, rounds: int, case: str) -> dict:
    """(1): the main job cold and warm, before and after, interleaved."""
    sides = {"before": (before_python, before), "after": (sys.executable, ROOT)}
    out = {side: {"cold": [], "warm": []} for side in sides}
    with tempfile.TemporaryDirectory(prefix="lubedyn-main-job-") as tmp:
        for rnd in range(rounds):
            for side, (python, root) in sides.items():
                cache = Path(tmp) / f"numba-{side}-{rnd}"
                for kind in ("cold", "warm"):
                    r = one_run(python, root, case, cache, Path(tmp) / f"out-{side}-{rnd}-{kind}")
                    out[side][kind].append(r)
                    print(f"round {rnd + 1} {side:>6} {kind}: {r['wall [s]']:.1f} s wall, {r['cpu [s]']:.1f} s CPU, "
                          f"load {r['load before [-]']:.1f} (exit {r['returncode']})", flush=True)
    ratios = {}
    for kind in ("cold", "warm"):
        for what in ("wall [s]", "cpu [s]"):
            rs = [a[what] / b[what] for a, b in zip(out["after"][kind], out["before"][kind])]
            ratios[f"{kind} {what}"] = {"per round": rs, "median": float(np.median(rs))}
    return {"runs": out, "after / before": ratios}


class _Threaded:
    """``job()`` in a thread; :meth:`wait` joins it and re-raises its error (the ``threads`` way)."""

    def __init__(self, label, job, stage):
        self.exc = None

        def target():
            try:
                job()
            except BaseException as exc:  # noqa: BLE001
                self.exc = exc

        self.thread = threading.Thread(target=target, name=f"bench-{label}")
        self.thread.start()

    def wait(self):
        self.thread.join()
        if self.exc is not None:
            raise self.exc

    def stop(self):
        self.thread.join()


def writers(case_path: str, repeats: int) -> dict:
    """(2): the main job's outputs written serially, by threads and by forked workers."""
    from lubedyn import outputs
    from lubedyn.config import load_case, resolved_toml
    from lubedyn.scenes.bearing_run import Timing, drive
    from lubedyn.scenes.dynamics import CagelessRunModel

    case = load_case(ROOT / case_path)
    model = CagelessRunModel(case)
    t0 = time.perf_counter()
    res = drive(model, None, name="main job")
    integration = time.perf_counter() - t0
    resolved = resolved_toml(case, "benchmark")
    ways = ("serial", "threads", "workers")
    out = {way: [] for way in ways}
    real = outputs.ForkedWriter
    with tempfile.TemporaryDirectory(prefix="lubedyn-writers-") as tmp:
        # one untimed write first (the first draws and writes of a process load fonts, VTK's writers ...)
        outputs.write_bearing_run(Path(tmp) / "warm-up", resolved, dict(res.summary), case.output.write,
                                  model.files(dict(res.summary), Timing(t0=0.0)), case.output.timeseries_format,
                                  workers=False)
        for rep in range(repeats):
            for way in ways[rep % 3:] + ways[:rep % 3]:  # the order turns from repeat to repeat
                files = model.files(dict(res.summary), Timing(t0=0.0))
                if way == "threads":
                    outputs.ForkedWriter = _Threaded
                load = os.getloadavg()[0]
                c_self, c_children, t_w = _self_cpu(), _children_cpu(), time.perf_counter()
                try:
                    outputs.write_bearing_run(Path(tmp) / f"{way}-{rep}", resolved, dict(res.summary), case.output.write,
                                              files, case.output.timeseries_format, workers=(way != "serial"))
                finally:
                    outputs.ForkedWriter = real
                r = {"wall [s]": time.perf_counter() - t_w,
                     "cpu [s]": (_self_cpu() - c_self) + (_children_cpu() - c_children), "load before [-]": load}
                out[way].append(r)
                print(f"write {rep + 1} {way:>8}: {r['wall [s]']:.2f} s wall, {r['cpu [s]']:.2f} s CPU, load "
                      f"{load:.1f}", flush=True)
    ratios = {way: {"wall": float(np.median([a["wall [s]"] / b["wall [s]"] for a, b in zip(out[way], out["serial"])])),
                    "cpu": float(np.median([a["cpu [s]"] / b["cpu [s]"] for a, b in zip(out[way], out["serial"])]))}
              for way in ways}
    return {"in-process run before the writes [s]": integration, "writes": out, "against serial (median)": ratios}


def _count_while(job) -> tuple[float, float]:
    """(iterations of a pure-Python loop per CPU second of the loop's thread, wall [s]) while ``job()`` runs
    in a second thread: near the solo rate when ``job`` releases the GIL, lower when it holds it."""
    done = threading.Event()

    def target():
        try:
            job()
        finally:
            done.set()

    worker = threading.Thread(target=target)
    n, c0, t0 = 0, time.thread_time(), time.perf_counter()
    worker.start()
    while not done.is_set():
        for _ in range(1000):
            n += 1
    wall = time.perf_counter() - t0
    worker.join()
    return n / max(wall, 1e-9), wall


def gil(case_path: str, repeats: int) -> dict:
    """(3): whether each output job releases the GIL: a pure-Python loop's iterations per wall second while
    the job runs in another thread, against the same loop beside ``time.sleep`` (GIL free) and beside a
    pure-Python loop (GIL shared), interleaved.  ``share`` = (rate - shared) / (free - shared): 1 the job
    leaves the GIL free (a thread would run beside it), 0 it holds it like Python code does."""
    import io

    from lubedyn import outputs
    from lubedyn.config import load_case
    from lubedyn.results import dataset
    from lubedyn.scenes.bearing_run import Timing, drive
    from lubedyn.scenes.dynamics import CagelessRunModel

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    case = load_case(ROOT / case_path)
    model = CagelessRunModel(case)
    res = drive(model, None, name="main job")
    files = model.files(dict(res.summary), Timing(t0=0.0))
    columns = files.columns()
    tmp = Path(tempfile.mkdtemp(prefix="lubedyn-gil-"))
    frames = list(files.frames())[:40]

    def write_frames():
        for k, (_, mesh) in enumerate(frames):
            outputs.write_frame(tmp / f"f{k}.vtp", mesh)

    def draw_figures():
        for name, draw in list(model.drawings().items())[:3]:
            fig = draw()
            fig.savefig(io.BytesIO(), format="png", dpi=120)
            plt.close(fig)

    ds = dataset(files.t, columns)

    def write_netcdf():
        outputs.write_netcdf(tmp / "t.nc", ds)

    def python_loop(seconds=2.0):
        t_end = time.perf_counter() + seconds
        while time.perf_counter() < t_end:
            sum(range(200))

    jobs = {"sleep (GIL free)": lambda: time.sleep(2.0), "Python loop (GIL shared)": python_loop,
            "VTK frames (40)": write_frames, "figures (3)": draw_figures, "netCDF write": write_netcdf}
    out = {name: [] for name in jobs}
    for rep in range(repeats):
        for name, job in jobs.items():
            rate, wall = _count_while(job)
            out[name].append({"loop rate [1/s]": rate, "wall [s]": wall, "load [-]": os.getloadavg()[0]})
            print(f"gil {rep + 1} {name:>26}: loop {rate:.3g}/s over {wall:.2f} s", flush=True)
    free = np.median([r["loop rate [1/s]"] for r in out["sleep (GIL free)"]])
    shared = np.median([r["loop rate [1/s]"] for r in out["Python loop (GIL shared)"]])
    share = {name: float((np.median([r["loop rate [1/s]"] for r in rs]) - shared) / (free - shared))
             for name, rs in out.items()}
    return {"runs": out, "GIL left free (share)": share}


def figure(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), layout="constrained")
    if "runs" in data:
        ax = axes[0]
        rr = data["runs"]["runs"]
        for i, kind in enumerate(("cold", "warm")):
            for j, side in enumerate(("before", "after")):
                x = 3 * i + j
                walls = [r["wall [s]"] for r in rr[side][kind]]
                cpus = [r["cpu [s]"] for r in rr[side][kind]]
                ax.bar(x - 0.2, np.median(walls), 0.4, color=f"C{j}", label=f"{side}, wall" if i == 0 else None)
                ax.bar(x + 0.2, np.median(cpus), 0.4, color=f"C{j}", alpha=0.45,
                       label=f"{side}, CPU" if i == 0 else None)
                ax.plot([x - 0.2] * len(walls), walls, "k.", ms=4)
                ax.plot([x + 0.2] * len(cpus), cpus, "k.", ms=4)
        ratio = data["runs"]["after / before"]
        ax.set_xticks([0.5, 3.5], [f"cold (after/before wall {ratio['cold wall [s]']['median']:.2f})",
                                   f"warm (after/before wall {ratio['warm wall [s]']['median']:.2f})"])
        ax.set_ylabel("main job [s] (median, dots: rounds)")
        ax.legend(fontsize=7)
        ax.set_title("lubedyn run cageless_6206_10krpm_short: before and after issue 42", fontsize=9)
    if "writers" in data:
        ax = axes[1]
        w = data["writers"]["writes"]
        for j, way in enumerate(w):
            walls = [r["wall [s]"] for r in w[way]]
            cpus = [r["cpu [s]"] for r in w[way]]
            ax.bar(j - 0.2, np.median(walls), 0.4, color="C2", label="wall" if j == 0 else None)
            ax.bar(j + 0.2, np.median(cpus), 0.4, color="C3", label="CPU" if j == 0 else None)
            ax.plot([j - 0.2] * len(walls), walls, "k.", ms=4)
            ax.plot([j + 0.2] * len(cpus), cpus, "k.", ms=4)
        ax.set_xticks(range(len(w)), [f"{way}\n(wall x{data['writers']['against serial (median)'][way]['wall']:.2f})"
                                      for way in w])
        ax.set_ylabel("writing the outputs [s]")
        ax.legend(fontsize=7)
        ax.set_title("frames + figures beside the time series", fontsize=9)
    load = data["machine"].get("load_average_at_start")
    fig.suptitle(f"{data['machine']['cpu'].get('model name', '')}, {data['machine']['cpus_available_to_process']} "
                 f"cores, load at start {load[0]:.1f}" if load else "", fontsize=8)
    save_figure(fig, path)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", type=Path, help="root of the checkout to compare with")
    ap.add_argument("--before-python", default=None, help="its interpreter (default: this one)")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--write-repeats", type=int, default=2)
    ap.add_argument("--case", default=CASE)
    ap.add_argument("--skip-runs", action="store_true")
    ap.add_argument("--skip-writers", action="store_true")
    ap.add_argument("--gil", action="store_true", help="also (3), the GIL probe of each output job")
    args = ap.parse_args(argv)
    data = {"case": args.case, "how": __doc__.split("\n\n")[2].strip() + "\n\n" + __doc__.split("\n\n")[3].strip(),
            "machine": machine_info(("numba", "xarray", "netCDF4", "vtk", "pyvista"))}
    if not args.skip_runs:
        if args.before is None:
            ap.error("--before is required unless --skip-runs")
        data["before"] = str(args.before.resolve())
        data["runs"] = runs(args.before.resolve(), args.before_python or sys.executable, args.rounds, args.case)
    if not args.skip_writers:
        data["writers"] = writers(args.case, args.write_repeats)
    if args.gil:
        data["gil"] = gil(args.case, args.write_repeats)
    data["load average at end"] = list(os.getloadavg())
    write_json(RESULTS / "main_job.json", data)
    figure(data, RESULTS / "main_job.png")
    summary = {}
    if "runs" in data:
        summary["after / before"] = {k: round(v["median"], 3) for k, v in data["runs"]["after / before"].items()}
    if "writers" in data:
        summary["writers against serial"] = data["writers"]["against serial (median)"]
    if "gil" in data:
        summary["GIL left free"] = data["gil"]["GIL left free (share)"]
    print(json.dumps(summary, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
