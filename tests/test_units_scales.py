"""Units that cannot slip: a bare number for a dimensioned key is SI, and
every length is checked against the scales of its own scene.

Before, ``clearance = 50`` (meant um) was a 50 m clearance that validated and ran; ``--set
gap.h_out=10`` on a 20 mm slider too.  Now a film thicker than a tenth of the length it spreads over
(:data:`lubedyn.config.THIN_FILM`), a film domain beyond its body, an EHL contact as wide as its
radius (:data:`lubedyn.scenes.ehl_case.SMALL_CONTACT`) or a bearing whose lengths do not fit together is
one line (exit 2) naming the key, its value, what it was compared with and, for a bare number, the
unit it was probably meant in.  A case file with a UTF-8 byte-order mark loads; a unit written
without quotes gets a hint.  Validation only: nothing here solves.
"""
from __future__ import annotations

import logging
import typing

import pytest

from lubedyn import cli
from lubedyn.config import CASES_DIR, CaseError, FilmCase, GapModel, load_case, load_case_text, read_toml

from test_cli import EHL_DIRECT  # (the same steel ball on a flat as the CLI tests)


def validate(capsys, case, *sets):
    argv = ["validate", str(case)]
    for s in sets:
        argv += ["--set", s]
    code = cli.main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def one_line(err: str) -> str:
    assert err.startswith("lubedyn: error: ") and err.count("\n") == 1 and "Traceback" not in err, err
    return err


def test_bare_clearance_of_a_journal_is_refused_with_the_unit_it_meant(capsys):
    """The issue's journal: a bare 50 is 50 m against a 25 mm radius."""
    code, _, err = validate(capsys, "journal_finite", "gap.clearance=50")
    assert code == 2
    assert one_line(err) == (
        "lubedyn: error: gap.clearance = 50 (50 m) is out of scale: clearance/radius = 2000 with gap.radius = "
        "0.025 m must be <= 0.1 (Reynolds' equation is the thin-film limit of the flow equations: it needs "
        "h/L << 1); bare numbers are SI (m): write \"50 um\"\n")


def test_bare_outlet_film_of_a_slider_is_refused_with_the_unit_it_meant(capsys):
    code, _, err = validate(capsys, "inclined_slider", "gap.h_out=10")
    assert code == 2
    for fragment in ("gap.h_out = 10 (10 m)", "h_out/length = 500", "gap.length = 0.02 m", "<= 0.1",
                     'bare numbers are SI (m): write "10 um"'):
        assert fragment in one_line(err), err


@pytest.mark.parametrize("case, setting, fragments", [
    # a bare radius in mm leaves a 50 um clearance 2e-6 of it: below the thermal floor, the radius is blamed
    ("journal_finite", "gap.radius=25", ["gap.radius = 25 (25 m)", ">= 1e-05", 'write "25 mm"']),
    ("journal_finite", "gap.clearance=0.05", ["gap.clearance = 0.05 (0.05 m)", 'write "0.05 mm"']),
    ("journal_finite", "gap.length=50 um", ["gap.clearance", "clearance/length = 1", "gap.length = 5e-05 m"]),
    ("inclined_slider", "gap.h_in=20", ["gap.h_in = 20 (20 m)", 'write "20 um"']),
    ("fowell_pocket", "gap.depth=1", ["gap.depth = 1 (1 m)", "depth/(pocket width) = 333",
                                      "gap.pocket_end - gap.pocket_start = 0.003 m", 'write "1 um"']),
    ("fowell_pocket", "gap.pocket_start=2", ["gap.pocket_start = 2 must be < pocket_end = 0.005 m",
                                             'write "2 mm"']),
    ("rayleigh_step", "gap.x_step=7.1822", ["gap.x_step = 7.1822 must be < length = 0.01 m", 'write "7.1822 mm"']),
    ("ball_ball_squeeze", "gap.h0=1", ["gap.h0 = 1 (1 m)", "gap.radius1 = 0.0047625 m", 'write "1 um"']),
    ("sphere_plane_squeeze", "gap.h0=2", ["gap.h0 = 2 (2 m)", 'write "2 um"']),
    ("sphere_plane_squeeze", "mesh.radius=1", ["mesh.radius = 1 (1 m)", "mesh.radius/gap.radius = 200", "< 1",
                                               "surface ends", 'write "1 mm"']),
    ("inclined_slider", "mesh.x=[0, 20]", ["mesh.x = [0, 20] (20 m)", "write ['0 mm', '20 mm']"]),
    # EHL: a bare modulus is Pa, a contact as wide as the ball; the bearing's lengths against each other
    ("ehl_ball_inner_race", "materials.modulus1=207", ["materials.modulus1 = 207 (207 Pa)",
                                                       "Hertz semi-axis/radius of curvature", 'write "207 GPa"']),
    ("ehl_roller_slice", "materials.modulus1=205", ["materials.modulus1 = 205 (205 Pa)", 'write "205 GPa"']),
    ("ehl_ball_inner_race", "bearing.pitch_diameter=46.005", ["bearing.pitch_diameter = 46.005 (46.005 m)",
                                                              "fill Z D/(pi d_m)", 'write "46.005 mm"']),
    ("ehl_ball_inner_race", "bearing.element_diameter=9.525", ["bearing.element_diameter = 9.525 must be < "
                                                               "pitch_diameter", 'write "9.525 mm"']),
    ("ehl_ball_inner_race", "bearing.inner_groove_radius=4.905", ["bearing.inner_groove_radius = 4.905 (4.905 m)",
                                                                  'write "4.905 mm"']),
    ("ehl_ball_inner_race", "bearing.diametral_clearance=0.02", ["bearing.diametral_clearance = 0.02 must be < 2 B D",
                                                                 'write "0.02 mm"']),
    ("ehl_roller_slice", "bearing.effective_length=42.06", ["bearing.effective_length = 42.06 (42.06 m)",
                                                            'write "42.06 mm"']),
])
def test_bare_lengths_are_checked_against_their_scene(case, setting, fragments):
    with pytest.raises(CaseError) as info:
        load_case(CASES_DIR / f"{case}.toml", overrides=[setting])
    text = str(info.value)
    assert "\n" not in text
    for fragment in fragments:
        assert fragment in text, text


def test_a_value_with_units_is_taken_as_meant(capsys):
    """'50 mm' is out of scale too, but its unit was written: no "bare numbers" hint."""
    code, _, err = validate(capsys, "journal_finite", "gap.clearance=50 mm")
    assert code == 2
    assert "gap.clearance = '50 mm' (0.05 m) is out of scale: clearance/radius = 2 with gap.radius" in one_line(err)
    assert "bare numbers" not in err


@pytest.mark.parametrize("setting, fragments", [
    ("materials.modulus1=210", ["materials.modulus1 = 210 (210 Pa)", 'write "210 GPa"']),
    ("operating.load=2e7", ["operating.load = 2e+07 (2e+07 N)", "Hertz semi-axis/radius of curvature = 1.09",
                            "R_x = 0.01 m", "bare numbers are SI (N)"]),
])
def test_ehl_contact_must_leave_room_for_a_film(tmp_path, setting, fragments):
    path = tmp_path / "direct.toml"
    path.write_text(EHL_DIRECT)
    assert load_case(path).operating.load == 20.0
    with pytest.raises(CaseError) as info:
        load_case(path, overrides=[setting])
    for fragment in fragments:
        assert fragment in str(info.value), str(info.value)


def test_ehl_approach_is_a_thin_film(tmp_path):
    path = tmp_path / "approach.toml"
    path.write_text(EHL_DIRECT.replace('load = "20 N"', "approach = 1"))
    with pytest.raises(CaseError, match=r'operating.approach = 1 \(1 m\) .* write "1 mm"'):
        load_case(path)


def test_every_gap_type_has_its_thin_film_lengths_and_bundled_films_are_far_inside():
    """One table (FILM_LENGTHS) drives the thin-film check of every gap type; the bundled film cases
    sit at least ten times inside it (largest: 2e-3, the journal's c/R)."""
    from lubedyn.config import FILM_LENGTHS, THIN_FILM

    gaps = typing.get_args(typing.get_args(GapModel)[0])
    types = {typing.get_args(m.model_fields["type"].annotation)[0] for m in gaps}
    assert set(FILM_LENGTHS) == types
    films = [p for p in sorted(CASES_DIR.glob("*.toml")) if read_toml(p).get("scene") == "film"]
    assert len(films) >= 6
    for path in films:
        gap = load_case(path).gap
        worst = max(abs(getattr(gap, h)) / getattr(gap, length) for h, length in FILM_LENGTHS[gap.type])
        assert worst < 0.1 * THIN_FILM, (path.name, worst)


def test_the_check_needs_no_case_file():
    """Validated without the raw case (FilmCase.model_validate), every value counts as bare."""
    raw = read_toml(CASES_DIR / "journal_finite.toml")
    raw["gap"]["clearance"] = 50
    with pytest.raises(Exception, match='bare numbers are SI \\(m\\): write "50 um"'):
        FilmCase.model_validate(raw)


def test_case_file_with_a_byte_order_mark_loads(tmp_path, caplog):
    """Some editors start UTF-8 files with a BOM, which TOML forbids ("Invalid statement (at line 1,
    column 1)" before): it is skipped, at DEBUG."""
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + (CASES_DIR / "inclined_slider.toml").read_bytes())
    with caplog.at_level(logging.DEBUG, logger="lubedyn.config"):
        case = load_case(path)
    assert case.gap.h_out == 1e-5
    assert any("byte-order mark" in r.getMessage() for r in caplog.records)
    assert load_case_text("\ufeff" + (CASES_DIR / "inclined_slider.toml").read_text()).gap.length == 0.02


@pytest.mark.parametrize("line, hint", [
    ("clearance = 50 um", 'write "50 um"'),
    ("clearance = 50um", 'write "50 um"'),
    ("x = [-1 mm, 1 mm]", 'write "-1 mm"'),
])
def test_a_unit_without_quotes_gets_a_hint(tmp_path, capsys, line, hint):
    path = tmp_path / "case.toml"
    path.write_text(f'scene = "film"\n[gap]\n{line}\n')
    code, _, err = validate(capsys, path)
    assert code == 2
    assert "invalid TOML" in one_line(err) and f"quantities with units are TOML strings: {hint}" in err, err
    path.write_text('scene = "film"\n[gap\n')  # a syntax error elsewhere: no hint
    code, _, err = validate(capsys, path)
    assert code == 2 and "invalid TOML" in one_line(err) and "units" not in err
