"""Results outside the range where a scene's model holds are warned about, never silently accepted.

Each warning is one logged line (WARNING, on stderr through the CLI) and an
entry of the list under "Warnings" in summary.json (absent when there is none); the thresholds are the
documented options of ``[validity]`` (lubedyn.config.ValidityModel).  The
bundled film and EHL cases at their smoke resolution give none.
"""
from __future__ import annotations

import json

import pytest

from lubedyn import cli

from lubedyn.scenes import ehl as ehl_scene

from lubedyn.scenes import film as film_scene
from lubedyn.config import CASES_DIR, load_case

PRESSURE = "is above validity.max_pressure"
FILM = "is below validity.min_film"
REYNOLDS = "is above validity.max_reynolds"


def run_cli(capsys, tmp_path, case, *sets):
    argv = ["run", case, "--smoke", "--out", str(tmp_path / "out")]
    for s in sets:
        argv += ["--set", s]
    code = cli.main(argv)
    _, err = capsys.readouterr()
    assert code == 0, err
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    return summary, [line for line in err.splitlines() if line.startswith("lubedyn: WARNING: lubedyn.validity: ")]


def test_journal_at_1e9_rpm_is_warned(capsys, tmp_path):
    """The issue's journal at 1e9 rpm (smoke mesh: 1.66e12 Pa, Re = 1020 x 2.6e6 ... = 1.05e7)."""
    summary, lines = run_cli(capsys, tmp_path, "journal_finite", "motion.speed=1e9 rpm")
    assert summary["Warnings"] == [
        "Maximum pressure 1.66e+12 Pa is above validity.max_pressure = 3e+09 Pa: the rigid-surface Reynolds film "
        "does not hold there (the solids deform, the viscosity law is extrapolated)",
        "Film Reynolds number rho U h / eta = 1.05e+07 is above validity.max_reynolds = 1e+03: the flow is no "
        "longer laminar and inertia-free, which the Reynolds equation assumes"]
    assert lines == [f"lubedyn: WARNING: lubedyn.validity: {w}" for w in summary["Warnings"]]
    # Re = rho0 U h_max / eta0 with U = omega R and h_max = c (1 + eps)
    omega = 1e9 * 2 * 3.141592653589793 / 60
    assert summary["Film Reynolds number [-]"] == pytest.approx(1000 * omega * 0.025 * 50e-6 * 1.6 / 0.02, rel=1e-3)


def test_jfo_pocket_at_1e6_m_per_s_is_warned(capsys, tmp_path):
    summary, lines = run_cli(capsys, tmp_path, "fowell_pocket", "motion.velocity_lower=1e6")
    assert [w.split(":")[0] for w in summary["Warnings"]] == [
        "Maximum pressure 9.43e+12 Pa is above validity.max_pressure = 3e+09 Pa",
        "Film Reynolds number rho U h / eta = 2.04e+05 is above validity.max_reynolds = 1e+03"]
    assert len(lines) == 2


def test_film_thinner_than_the_roughness_is_warned():
    """A sphere 50 nm from a plane (default roughness 0.1 um), and the same film with a stated roughness
    of 10 nm: no warning."""
    case = load_case(CASES_DIR / "sphere_plane_squeeze.toml", overrides=["gap.h0='50 nm'", "mesh.refinements=5"])
    s = film_scene.run(case).summary
    assert s["Warnings"] == ["Minimum film thickness 5e-08 m is below validity.min_film = 1e-07 m (the surface "
                             "roughness): asperities would touch, outside a full-film model"]
    case = load_case(CASES_DIR / "sphere_plane_squeeze.toml", overrides=["gap.h0='50 nm'", "mesh.refinements=5",
                                                                        "validity.min_film='10 nm'"])
    assert "Warnings" not in film_scene.run(case).summary


def test_ehl_thresholds_are_options(caplog):
    """The 6206 inner-race contact (smoke: p_max 1.9 GPa, h_min 0.87 um) is inside the defaults; a 1 GPa
    pressure limit and a 1 um roughness put it outside both."""
    case = load_case(CASES_DIR / "ehl_ball_inner_race.toml", smoke=True,
                     overrides=["validity.max_pressure='1 GPa'", "validity.min_film='1 um'"])
    with caplog.at_level("WARNING", logger="lubedyn.validity"):
        s = ehl_scene.run(case).summary
    assert [w.split(":")[0] for w in s["Warnings"]] == [
        "Maximum pressure 1.9e+09 Pa is above validity.max_pressure = 1e+09 Pa",
        "Minimum film thickness 8.65e-07 m is below validity.min_film = 1e-06 m (the surface roughness)"]
    assert [r.getMessage() for r in caplog.records] == s["Warnings"]
    assert case.validity.max_reynolds == 1000.0


FILM_AND_EHL = [p for p in sorted(CASES_DIR.glob("*.toml"))
                if load_case(p).scene in ("film", "ehl")]


@pytest.mark.parametrize("path", FILM_AND_EHL, ids=[p.stem for p in FILM_AND_EHL])
def test_bundled_cases_give_no_validity_warning(path, caplog):
    """Margins measured at smoke: largest Re 31 (journal), smallest film 0.87 um (EHL ball, 8.7 x 0.1 um),
    largest pressure 1.9 GPa (EHL ball, limit 4 GPa)."""
    case = load_case(path, smoke=True)
    scene = film_scene if case.scene == "film" else ehl_scene
    with caplog.at_level("WARNING", logger="lubedyn.validity"):
        s = scene.run(case).summary
    assert "Warnings" not in s and not caplog.records
    assert s["Film Reynolds number [-]"] < 0.1 * case.validity.max_reynolds
    assert s["Minimum film thickness [m]"] > 5 * case.validity.min_film
    assert s["Maximum pressure [Pa]"] < 0.5 * case.validity.max_pressure
