"""The README's main job from a cold and a warm numba cache, this checkout against another one, interleaved.

    python benchmarks/cold_start.py --other /path/to/older/checkout [--rounds 2] [--case cases/X.toml]

Each round runs, for each checkout in turn, ``lubedyn run <case>`` in a fresh process with
``NUMBA_CACHE_DIR`` pointing to a new empty folder (cold: every kernel compiles), then again with the
same folder (warm).  The checkouts run with this interpreter, so both use the same installed packages: a
checkout of the earlier layout (top-level ``coupling``) with ``PYTHONPATH`` set to its root, one of the
one-namespace layout (``lubedyn``) as installed in this interpreter, which must therefore be
that checkout's editable install (``case_summaries.packages``).  Wall times of the whole process; the
run's own summary gives the integration and Benettin times.  Writes ``results/cold_start.json`` and ``results/cold_start.png``.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS, ROOT, machine_info, save_figure, write_json  # noqa: E402
from case_summaries import namespace_layout, packages  # noqa: E402

CASE = "cases/cageless_6206_10krpm_short.toml"


def one_run(root: Path, case: str, cache: Path, out: Path) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    if not namespace_layout(root):
        env["PYTHONPATH"] = str(root)
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", packages(root)[0], "run", case, "--out", str(out)], cwd=root, env=env,
                       capture_output=True, text=True)
    wall = time.perf_counter() - t0
    r = {"wall [s]": wall, "returncode": p.returncode}
    summary = out / "summary.json"
    if p.returncode == 0 and summary.is_file():
        s = json.loads(summary.read_text())
        for k in ("Build time [s]", "Integration wall time [s]", "Benettin time [s]", "Run time [s]"):
            r[k] = s.get(k)
    else:
        r["stderr"] = p.stderr[-1500:]
    return r


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--other", type=Path, required=True, help="root of the checkout to compare with")
    ap.add_argument("--other-label", default="before")
    ap.add_argument("--label", default="after")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--case", default=CASE)
    args = ap.parse_args(argv)
    roots = {args.other_label: args.other.resolve(), args.label: ROOT}
    runs = {label: {"cold": [], "warm": []} for label in roots}
    with tempfile.TemporaryDirectory(prefix="lubedyn-cold-") as tmp:
        for rnd in range(args.rounds):
            for label, root in roots.items():
                cache = Path(tmp) / f"numba-{label}-{rnd}"
                for kind in ("cold", "warm"):
                    r = one_run(root, args.case, cache, Path(tmp) / f"out-{label}-{rnd}-{kind}")
                    runs[label][kind].append(r)
                    print(f"round {rnd + 1} {label:>8} {kind}: {r['wall [s]']:.1f} s (exit {r['returncode']})",
                          flush=True)
    data = {"case": args.case, "how": __doc__.split("\n\n")[1].strip(), "machine": machine_info(),
            "checkouts": {k: str(v) for k, v in roots.items()}, "runs": runs,
            "summary [s]": {label: {kind: [round(r["wall [s]"], 2) for r in rs] for kind, rs in v.items()}
                            for label, v in runs.items()}}
    write_json(RESULTS / "cold_start.json", data)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 3.2))
    labels = list(roots)
    for i, kind in enumerate(("cold", "warm")):
        for j, label in enumerate(labels):
            walls = [r["wall [s]"] for r in runs[label][kind]]
            x = i * (len(labels) + 1) + j
            ax.bar(x, min(walls), color=f"C{j}", label=label if i == 0 else None)
            ax.plot([x] * len(walls), walls, "k.", ms=4)
    ax.set_xticks([(len(labels) - 1) / 2, len(labels) + 1 + (len(labels) - 1) / 2], ["cold cache", "warm cache"])
    ax.set_ylabel("wall time of the main job [s]")
    ax.set_title(f"{Path(args.case).name}: first run and later runs", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, RESULTS / "cold_start.png")
    print(json.dumps(data["summary [s]"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
