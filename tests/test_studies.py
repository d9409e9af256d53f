"""Every shipped study (studies/*.toml) plans: its base case, set entries and every point's overrides
validate (lubedyn.scenes.study.plan_study builds each run's case), and paper A's studies run the tapered scene
with the outputs its summary gives.  Running them is benchmarks' and the README's business."""
from __future__ import annotations

from pathlib import Path

import pytest

from lubedyn.scenes.study import plan_study, read_study

STUDIES = sorted((Path(__file__).resolve().parents[1] / "studies").glob("*.toml"))


@pytest.mark.parametrize("path", STUDIES, ids=[p.stem for p in STUDIES])
def test_study_plans(path):
    study = read_study(path)
    plan = plan_study(study, path, smoke=True)
    assert len(plan.runs) >= 2


def test_paper_a_studies_tabulate_keys_the_tapered_summary_writes(tmp_path):
    """The outputs the trb_* studies ask for are keys of a tapered run's summary (a 1 ms smoke run of the
    Fig. 5 case), so no column of their tables is empty by a typo."""
    from lubedyn.scenes import tapered as S
    from lubedyn.config import CASES_DIR, load_case

    s = S.run(load_case(CASES_DIR / "trb_fig5_2400rpm.toml", smoke=True)).summary
    for path in STUDIES:
        if path.stem.startswith("trb_") and "static" not in path.stem:
            for key in read_study(path).study.outputs:
                assert key in s, (path.name, key)
