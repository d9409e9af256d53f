"""Paper B's Figs. 6-8 from several dynamics runs: phase portraits x, y, z of ball ``analysis.ball``
(one row per direction, one column per run) with the ideal-state orbit, and a table of the settling
and spin-up times (:func:`lubedyn.papers.zhang2024.figures.compare_runs`).

::

    python benchmarks/paper_b_figures.py RUN_DIR [RUN_DIR ...] --out PNG

e.g. after ``lubedyn run cageless_6206_10krpm --out runs/10k`` and the 15, 20 and 25 krpm cases.
Each folder needs ``timeseries.nc`` (or ``.npz``) (``output.write`` with ``"timeseries"``), ``summary.json`` and
``case.resolved.toml``.  Exit code 0 on success, 2 when a folder is not a dynamics run.
"""
from __future__ import annotations

import argparse
import sys

from lubedyn.lubrication.errors import InputError
from lubedyn.papers.zhang2024.figures import compare_runs


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", metavar="RUN_DIR", help="dynamics run folders, in column order")
    p.add_argument("--out", required=True, metavar="PNG", help="figure to write")
    args = p.parse_args(argv)
    try:
        out = compare_runs(args.runs, args.out)
    except InputError as exc:
        print(f"paper_b_figures: {exc}", file=sys.stderr)
        return 2
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
