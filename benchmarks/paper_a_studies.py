"""Tabulate paper A's studies (studies/trb_*.toml, issue 24) from their ``study.json`` as markdown: one
table per study, one row per point, the loaded-zone means the paper plots, beside paper A's numbers where
it prints them.  Run the studies first (``lubedyn study studies/trb_speed.toml --out runs/studies/trb_speed``
and so on), then ``python benchmarks/paper_a_studies.py [runs/studies]``; writes
``results/paper_a_studies.md``."""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
STUDIES = ("trb_speed", "trb_preload", "trb_plastic_viscosity", "trb_yield_stress", "trb_grease_temperature")
COLUMNS = (("Skew, loaded zone, mean [rad]", "skew, loaded [rad]", ".3e"),
           ("Skew, unloaded zone, mean [rad]", "skew, unloaded [rad]", ".3e"),
           ("Tilt, loaded zone, mean [rad]", "tilt, loaded [rad]", ".2e"),
           ("Roller slip, loaded zone, mean [-]", "slip, loaded", ".2e"),
           ("Roller slip, unloaded zone, mean [-]", "slip, unloaded", ".2e"),
           ("Cage slip, mean [-]", "cage slip", ".2e"),
           ("Skew periodicity [-]", "skew periodicity", ".4f"),
           ("Largest cup load [N]", "largest cup load [N]", ".0f"),
           ("Integration wall time [s]", "wall [s]", ".0f"))


def _cell(v, fmt):
    return "-" if v is None or (isinstance(v, float) and not math.isfinite(v)) else format(v, fmt)


def table(path: Path) -> str:
    r = json.loads(path.read_text())
    axes = list(r["points"][0]["axes"])
    head = "| " + " | ".join(axes + [c[1] for c in COLUMNS]) + " |"
    rows = [head, "|" + "---|" * (len(axes) + len(COLUMNS))]
    for p in r["points"]:
        o = p["outputs"]
        rows.append("| " + " | ".join([str(p["axes"][a]) for a in axes]
                                      + [_cell(o.get(k, {}).get("median"), f) for k, _, f in COLUMNS]) + " |")
    paper = r.get("study", {}).get("paper") or {}
    if paper:
        rows.append("")
        rows.append("Paper A: " + "; ".join(f"{k} at {v['at']}: {v['values']}" for k, v in paper.items()))
    return "\n".join(rows)


def main(argv=None) -> str:
    base = Path((argv or sys.argv[1:] or [ROOT / "runs" / "studies"])[0])
    parts = []
    for name in STUDIES:
        path = base / name / "study.json"
        if path.is_file():
            parts.append(f"### {name}\n\n{table(path)}\n")
        else:
            parts.append(f"### {name}\n\nnot run ({path} missing)\n")
    text = "\n".join(parts)
    out = ROOT / "benchmarks" / "results" / "paper_a_studies.md"
    out.write_text(text)
    return text


if __name__ == "__main__":
    print(main())
