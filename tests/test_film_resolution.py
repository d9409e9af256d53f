"""A film whose minimum-gap zone is resolved by too few elements converges in
the Newton iterations but not in the mesh.  The film scene warns (logging WARNING, summary.json
"Warnings"), naming the mesh that resolves the zone.

Measured on the bundled journal (cases/journal_finite.toml, L/D = 1, P2, Reynolds cavitation)
moved to eps 0.999, |load| on 32x8 / 64x16 / 128x32 / 256x64: 1.552e6 / 3.557e6 / 4.553e6 /
4.592e6 N: the bundled smoke mesh (32x8) is 66 % low and the bundled mesh (64x16) 22.5 % low
against 256x64.  At the bundled eps 0.6 the same meshes agree to 0.03 %: the "22 % low" of the
issue is eps 0.999 on the bundled mesh; the bundled case's mesh is adequate for its eccentricity.
"""
from __future__ import annotations

import logging

import numpy as np
import pytest

from lubedyn.scenes import film as film_scene
from lubedyn.config import CASES_DIR, load_case
from lubedyn.lubrication.reynolds.solution import MIN_GAP_ELEMENTS

JOURNAL = CASES_DIR / "journal_finite.toml"


def journal(eps, nx, ny):
    case = load_case(JOURNAL, overrides=[f"gap.eccentricity_ratio={eps}", f"mesh.nx={nx}", f"mesh.ny={ny}"])
    return film_scene.run(case)


def load(run):
    return float(np.hypot(*run.solution.load_vector[:2]))


def test_journal_at_eps_0999_warns_with_the_mesh_needed(caplog):
    """eps 0.999: the zone h < 2 h_min is 5.1 deg wide; 0.43 elements across it on 64x16 (load
    22 % below 128x32's), 1.66 on 128x32 (0.85 % below 256x64's: still warned, the threshold for
    P2 is 2.2).  The warning names the refinement and the mesh keys."""
    with caplog.at_level(logging.WARNING, logger="lubedyn.validity"):
        coarse, fine = journal(0.999, 64, 16), journal(0.999, 128, 32)
    assert load(coarse) == pytest.approx(3.557e6, rel=1e-3) and load(fine) == pytest.approx(4.553e6, rel=1e-3)
    assert load(coarse) / load(fine) < 0.85  # measured 0.78
    assert coarse.solution.min_gap_elements() == pytest.approx(0.43, abs=0.01)
    assert fine.solution.min_gap_elements() == pytest.approx(1.66, abs=0.01)
    (text,) = [w for w in coarse.summary["Warnings"] if w.startswith("Minimum-gap zone")]
    assert "resolved by 0.43 elements across, fewer than 2.2 for P2" in text
    assert text.endswith("refine the mesh about 6x across that zone (mesh.nx = 384 with mesh.ny = 96, or finer)")
    assert text in [r.getMessage() for r in caplog.records]
    assert any(w.startswith("Minimum-gap zone") for w in fine.summary["Warnings"])


def test_journal_resolved_zone_does_not_warn():
    """eps 0.99 on 128x32: 5.1 elements across, load within 0.4 % of 256x64's (measured 4.268e5
    against 4.250e5); the bundled eps 0.6 has 12 (smoke 32x8) and 25 (64x16) elements."""
    run = journal(0.99, 128, 32)
    assert run.solution.min_gap_elements() == pytest.approx(5.10, abs=0.01)
    assert "Warnings" not in run.summary and load(run) == pytest.approx(4.250e5, rel=0.01)
    for smoke, expected in ((True, 12.16), (False, 24.88)):
        run = film_scene.run(load_case(JOURNAL, smoke=smoke))
        assert run.solution.min_gap_elements() == pytest.approx(expected, abs=0.01)
        assert run.solution.resolution_warning() is None


def test_a_step_in_the_gap_is_not_a_minimum_gap_zone():
    """The Rayleigh step's gap is piecewise constant: no slope, no zone to resolve."""
    run = film_scene.run(load_case(CASES_DIR / "rayleigh_step.toml", smoke=True))
    assert run.solution.min_gap_elements() == np.inf and run.solution.resolution_warning() is None


def test_thresholds():
    assert MIN_GAP_ELEMENTS == {"P1": 12, "P2": 2.2}
