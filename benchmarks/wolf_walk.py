"""Wolf et al.'s exponent: the compiled walk against the former one (a k-d tree's ball query and the
replacement rule in Python, per evolution step), in the same process, interleaved.

The former walk is read from an earlier commit (``--before``, default 4e7dd77, the last with it) by
``git show`` and run beside the current :func:`lubedyn.dynamics.lyapunov._wolf_walk` on the same
embeddings: Henon (dim 2, delay 1), Lorenz x (dim 3 and 6), a quasi-periodic sine and Gaussian noise.
For each: CPU seconds of both (medians of ``--rounds`` interleaved pairs, the compiled walk's first
call -- its compile or cache load -- timed apart), the ratio, whether the replacement kinds and the
per-step logs agree, and the exponents [bits per sample interval].  The former walk broke ties in
the angle (collinear separations whose |cos| rounds to 1 all give exactly 0) by the k-d tree's
return order; the compiled walk by distance, then index.  The table therefore also runs the former
walk with that tie-break ("before, same ties"), which must agree with the compiled walk to round-off.

    python benchmarks/wolf_walk.py [--rounds 3] [--before REV]

Writes ``results/wolf_walk.json`` and ``results/wolf_walk.png``.
"""
from __future__ import annotations

import argparse
import math
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import machine_info, save_figure, write_json  # noqa: E402

from lubedyn.dynamics import lyapunov as L  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def former_walk(rev: str, same_ties: bool):
    """The walk of commit ``rev`` (``_wolf_first``, ``_wolf_replacement`` and the loop of
    ``largest_lyapunov_wolf``), optionally with the compiled walk's tie-break."""
    from scipy.spatial import cKDTree

    src = subprocess.run(["git", "show", f"{rev}:dynamics/lyapunov.py"], cwd=ROOT, check=True,
                         capture_output=True, text=True).stdout
    replacement = re.search(r"def _wolf_replacement.*?(?=\ndef _wolf_first)", src, re.S).group(0)
    if same_ties:
        replacement = (replacement
                       .replace("best = int(np.argmin(th))", "best = int(np.lexsort((idx, d, th))[0])")
                       .replace("best = int(np.argmin(np.where(sel, th, np.inf)))",
                                "best = int(np.lexsort((idx, d, np.where(sel, th, np.inf)))[0])")
                       .replace("return int(idx[np.argmin(d)]), 2", "return int(idx[np.lexsort((idx, d))[0]]), 2"))
    ns = {"np": np, "math": math, "WOLF_WIDEN": L.WOLF_WIDEN}
    exec(replacement, ns)  # noqa: S102 - the project's own former source, for the comparison

    def walk(X, n_use, evolve, first, theiler, smin, smax, angle_max):
        tree = cKDTree(X[:n_use])
        ind, nb, logs, kinds = 0, first, [], []
        while nb >= 0 and ind < n_use:
            di = float(np.linalg.norm(X[ind] - X[nb]))
            sep = X[ind + evolve] - X[nb + evolve]
            df = float(np.linalg.norm(sep))
            if df <= 0.0 or di <= 0.0:
                break
            logs.append(math.log2(df / di))
            ind += evolve
            if ind >= n_use:
                break
            nb, kind = ns["_wolf_replacement"](tree, X, n_use, ind, nb + evolve, sep, df, theiler, smin, smax,
                                               angle_max)
            kinds.append(kind)
        return np.asarray(logs), np.asarray(kinds, dtype=np.int64)

    return walk


def series():
    """(name, x, dim, delay, evolve, theiler) of the compared records."""
    from scipy.integrate import solve_ivp

    x = np.empty(20000)
    a, b = 0.1, 0.1
    for i in range(20100):
        a, b = 1.0 - 1.4 * a * a + b, 0.3 * a
        if i >= 100:
            x[i - 100] = a
    lorenz = solve_ivp(lambda t, y: [16 * (y[1] - y[0]), y[0] * (45.92 - y[2]) - y[1], y[0] * y[1] - 4 * y[2]],
                       [0, 160], [1, 1, 20], t_eval=np.arange(10, 160, 0.01), rtol=1e-9, atol=1e-9).y[0]
    t = np.arange(24000) * 1e-3
    rng = np.random.default_rng(1)
    return [("Henon x", x, 2, 1, 1, 10), ("Lorenz x, dim 3", lorenz, 3, 10, 5, 10),
            ("Lorenz x, dim 6", lorenz, 6, 8, 10, 20),
            ("quasi-periodic sine", np.sin(2 * np.pi * 7 * t) + 0.3 * np.sin(2 * np.pi * 7 * np.sqrt(2) * t), 4, 30,
             10, 50), ("Gaussian noise", rng.standard_normal(8000), 4, 1, 3, 10)]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--before", default="4e7dd77")
    args = ap.parse_args(argv)
    before = former_walk(args.before, same_ties=False)
    before_ties = former_walk(args.before, same_ties=True)
    rows = []
    for name, x, dim, delay, evolve, theiler in series():
        X = L.delay_embedding(x, dim, delay)
        n_use = X.shape[0] - evolve
        extent = float(np.ptp(x))
        smax, smin = L.WOLF_SCALE_MAX * extent, L.WOLF_SCALE_MIN * extent
        first = L._wolf_first(X, n_use, theiler, smin)
        call = (X, n_use, evolve, first, theiler, smin, smax, L.WOLF_ANGLE_MAX)
        t0 = time.process_time()
        L._wolf_walk(*call, L.WOLF_WIDEN)
        first_call = time.process_time() - t0
        cpu_before, cpu_after = [], []
        for _ in range(args.rounds):
            t0 = time.process_time()
            logs_b, kinds_b = before(*call)
            t1 = time.process_time()
            logs_a, kinds_a = L._wolf_walk(*call, L.WOLF_WIDEN)
            t2 = time.process_time()
            cpu_before.append(t1 - t0)
            cpu_after.append(t2 - t1)
        logs_t, kinds_t = before_ties(*call)
        same = logs_t.shape == logs_a.shape and bool(np.array_equal(kinds_t, kinds_a))
        row = dict(series=name, samples=int(x.size), dim=dim, delay=delay, evolve=evolve, theiler=theiler,
                   steps=int(logs_a.size), cpu_before_s=float(np.median(cpu_before)),
                   cpu_after_s=float(np.median(cpu_after)), first_call_s=first_call,
                   ratio=float(np.median(cpu_after) / np.median(cpu_before)),
                   kinds_equal_same_ties=same,
                   max_log_difference_same_ties=float(np.max(np.abs(logs_t - logs_a))) if same else None,
                   kinds_equal_former_ties=logs_b.shape == logs_a.shape and bool(np.array_equal(kinds_b, kinds_a)),
                   replacements_before=int(np.count_nonzero(kinds_b > 0)),
                   replacements_after=int(np.count_nonzero(kinds_a > 0)),
                   exponent_before_bits_per_sample=float(np.sum(logs_b) / (logs_b.size * evolve)),
                   exponent_after_bits_per_sample=float(np.sum(logs_a) / (logs_a.size * evolve)))
        rows.append(row)
        print(f"{name:22s} steps {row['steps']:6d}  before {row['cpu_before_s']:.3f} s  after "
              f"{row['cpu_after_s']:.4f} s  ratio {row['ratio']:.3f}  same ties: kinds equal {same}, "
              f"max |d log2| {row['max_log_difference_same_ties']}  exponent {row['exponent_before_bits_per_sample']:.4f}"
              f" -> {row['exponent_after_bits_per_sample']:.4f} bits/sample")
    out = HERE / "results"
    write_json(out / "wolf_walk.json", dict(machine=machine_info(("numba",)), rounds=args.rounds,
                                            before=args.before, rows=rows))
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.0, 3.6), layout="constrained")
    names = [r["series"] for r in rows]
    pos = np.arange(len(rows))
    ax.barh(pos - 0.2, [r["cpu_before_s"] for r in rows], 0.4, label="before: k-d tree + Python loop")
    ax.barh(pos + 0.2, [r["cpu_after_s"] for r in rows], 0.4, label="after: compiled walk")
    ax.set_yticks(pos, names)
    ax.set_xscale("log")
    ax.set_xlabel("CPU time of one Wolf walk [s]")
    ax.legend(loc="lower right", fontsize=8)
    save_figure(fig, out / "wolf_walk.png")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
