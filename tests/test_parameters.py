"""Parameter sets (lubedyn.papers): each paper's values against the independent transcription of
its tables in tests/data/seed_parameters.toml (made apart from the parameter modules), every value cited, and the case-file
merge (the set fills, the file and --set overrides win, errors are one line)."""
import math
import tomllib
from pathlib import Path

import pytest

from lubedyn import papers as P
from lubedyn.config import CASES_DIR as CASES
from lubedyn.config import CaseError, load_case, load_case_text, resolved_toml

SEED = Path(__file__).resolve().parent / "data" / "seed_parameters.toml"  # the papers' tables, transcribed


@pytest.mark.parametrize("name", list(P.SETS))
def test_every_value_is_cited_and_converts(name):
    module = P.parameter_set(name)
    assert module.NAME == name and module.CITATION
    for key, p in module.VALUES.items():
        assert p.source, key
        if p.source == "assumed":
            assert p.note, f"{key}: an assumed value says why"
        p.si()  # converts (a unit of the declared dimension)
    for scene, mapping in module.SCENES.items():
        for case_key, pname in mapping.items():
            assert pname in module.VALUES, (scene, case_key)


def test_zhang2024_against_the_transcribed_tables():
    seed = tomllib.loads(SEED.read_text())["cageless_ball_bearing"]
    si = lambda n: P.si("Zhang2024", n)  # noqa: E731
    assert si("n_balls") == seed["n_balls"]
    for key, seed_key in (("ball_diameter", "ball_diameter_mm"), ("ball_radius", "ball_radius_mm"),
                          ("pitch_diameter", "pitch_diameter_mm"), ("inner_groove_radius", "inner_groove_radius_mm"),
                          ("outer_groove_radius", "outer_groove_radius_mm"), ("outer_diameter", "outside_diameter_mm"),
                          ("bore", "bore_mm")):
        assert si(key) == pytest.approx(seed[seed_key] * 1e-3, rel=1e-15), key
    assert si("ball_modulus") == pytest.approx(seed["ball_elastic_modulus_GPa"] * 1e9, rel=1e-15)
    assert si("ring_modulus") == pytest.approx(seed["ring_elastic_modulus_GPa"] * 1e9, rel=1e-15)
    assert (si("ball_poisson"), si("ring_poisson")) == (seed["ball_poisson"], seed["ring_poisson"])
    assert (si("radial_load"), si("axial_load")) == (seed["radial_load_N"], seed["axial_load_N"])
    assert P.printed("Zhang2024", "speed", "rpm") == seed["shaft_speed_rpm"][0]
    clearance = (seed["outer_groove_bottom_diameter_mm"] - seed["inner_groove_bottom_diameter_mm"]
                 - 2 * seed["ball_diameter_mm"]) * 1e-3
    assert si("diametral_clearance") == pytest.approx(clearance, abs=1e-12)
    slot, oil = seed["functional_slot"], seed["lubricant"]
    assert (si("slot_width"), si("slot_length"), si("slot_depth")) == pytest.approx(
        (slot["width_mm"] * 1e-3, slot["length_mm"] * 1e-3, slot["depth_mm"] * 1e-3), rel=1e-15)
    assert si("viscosity") == oil["viscosity_Pa_s"]
    assert si("pressure_viscosity") == oil["pressure_viscosity_coefficient_m2_per_N"]
    assert si("density") == oil["density_kg_per_m3"]


def test_wu2018_against_the_transcribed_tables():
    seed = tomllib.loads(SEED.read_text())["tapered_roller_bearing"]
    si = lambda n: P.si("Wu2018", n)  # noqa: E731
    assert si("n_rollers") == seed["n_rollers"]
    # Table 1 prints the end diameters with their labels swapped (docs/paper_a.md): the large end is the larger
    ends = sorted((seed["roller_large_end_diameter_mm"], seed["roller_small_end_diameter_mm"]))
    assert (si("roller_small_end_diameter"), si("roller_large_end_diameter")) == pytest.approx(
        (ends[0] * 1e-3, ends[1] * 1e-3), rel=1e-15)
    assert si("roller_mean_diameter") == pytest.approx(0.5 * sum(ends) * 1e-3, rel=1e-15)
    assert si("pitch_diameter") == pytest.approx(
        (seed["outer_raceway_radius_mm"] + seed["inner_raceway_radius_mm"]) * 1e-3, rel=1e-15)
    for key, seed_key in (("effective_length", "roller_effective_length_mm"),
                          ("roller_end_sphere_radius", "roller_end_sphere_radius_mm"),
                          ("guide_land_clearance", "guide_land_clearance_mm"), ("pocket_clearance", "pocket_clearance_mm"),
                          ("cage_outer_diameter", "cage_outer_diameter_mm"), ("cage_thickness", "cage_thickness_mm")):
        assert si(key) == pytest.approx(seed[seed_key] * 1e-3, rel=1e-15), key
    assert P.printed("Wu2018", "outer_contact_angle", "deg") == seed["outer_contact_angle_deg"]
    assert P.printed("Wu2018", "inner_contact_angle", "deg") == seed["inner_contact_angle_deg"]
    assert si("steel_modulus") == pytest.approx(seed["roller_race_elastic_modulus_GPa"] * 1e9, rel=1e-15)
    assert si("cage_modulus") == pytest.approx(seed["cage_elastic_modulus_GPa"] * 1e9, rel=1e-15)
    grease = seed["grease_30C"]
    assert si("grease_yield_stress") == grease["yield_stress_Pa"]
    assert si("grease_plastic_viscosity") == grease["plastic_viscosity_Pa_s_n"]
    assert si("pressure_viscosity") == grease["pressure_viscosity_coefficient_m2_per_N"]
    table = seed["grease_table"]
    for grease_name, rows in P.parameter_set("Wu2018").GREASE_TABLE.items():
        assert [list(r) for r in rows] == table[grease_name]


def test_a_case_takes_the_set_and_overrides_it():
    base = (CASES / "cageless_6206_10krpm_short.toml").read_text()
    case = load_case_text(base)
    assert case.bearing.ball_diameter == 9.525e-3 and case.lubricant.viscosity.eta0 == 0.05
    assert case.slots.azimuths == [pytest.approx(math.radians(270.0), rel=1e-14)]
    over = load_case_text(base, overrides=["bearing.ball_diameter=9 mm", "lubricant.viscosity.eta0=0.1 Pa s"])
    assert over.bearing.ball_diameter == 9e-3 and over.lubricant.viscosity.eta0 == 0.1
    assert over.lubricant.viscosity.alpha == 1.85e-8  # the rest of the oil from the set
    assert over.bearing.pitch_diameter == case.bearing.pitch_diameter  # the rest from the set
    # the resolved case names the set, lists every value and is valid without the set
    text = resolved_toml(case)
    assert "parameters = 'Zhang2024' (lubedyn.papers.zhang2024.parameters)" in text
    again = load_case_text(text)
    assert again.bearing == case.bearing and again.films == case.films and again.slots == case.slots
    assert again.lubricant == case.lubricant


@pytest.mark.parametrize("scene_cases, seed_oil", [
    (("cageless_6206_steady", "ehl_ball_inner_race", "ball_ball_squeeze"), ("cageless_ball_bearing", "lubricant")),
    (("trb_fig5_2400rpm", "ehl_roller_slice"), ("tapered_roller_bearing", "grease_30C")),
])
def test_every_scene_reads_one_oil_table(scene_cases, seed_oil):
    """One [lubricant] table, one spelling: the dynamics, tapered, EHL and film cases of one paper all
    read the oil as lubricant.viscosity (Barus, eta0, alpha), and the bearing models get the paper's
    alpha (tests/data/seed_parameters.toml, transcribed independently) from it."""
    from lubedyn.scenes import dynamics, tapered

    seed = tomllib.loads(SEED.read_text())[seed_oil[0]][seed_oil[1]]
    alpha = seed["pressure_viscosity_coefficient_m2_per_N"]
    oils = set()
    for name in scene_cases:
        case = load_case(CASES / f"{name}.toml", smoke=True)
        v = case.lubricant.viscosity
        assert (v.law, v.alpha) == ("barus", alpha), name
        oils.add((v.eta0, v.alpha))
        if case.scene == "dynamics":
            films = dynamics.build(case).model.films
            assert (films.viscosity, films.pressure_viscosity) == (v.eta0, alpha)
        if case.scene == "tapered":
            group = tapered.build(case).lubricant
            assert (group.base_oil_viscosity, group.pressure_viscosity) == (v.eta0, alpha)
    assert len(oils) == 1  # the same oil in every scene of the paper


def test_a_tapered_case_may_leave_the_base_oil_out_only_with_a_grease_reading():
    """The tapered scene's [lubricant] without [lubricant.viscosity]: refused with the base-oil reading
    (the films would have no viscosity), accepted with the paper's reading of the grease (alpha 0)."""
    from lubedyn.config import validate_raw

    raw = tomllib.loads(resolved_toml(load_case(CASES / "trb_fig5_2400rpm.toml", smoke=True)))
    del raw["lubricant"]["viscosity"]
    with pytest.raises(CaseError, match=r"^lubricant.viscosity is required with reading = 'base_oil'"):
        validate_raw(raw)
    raw["lubricant"]["reading"] = "paper"
    assert validate_raw(raw).lubricant.oil() == (None, 0.0)


def test_the_python_twin_of_a_case_is_the_same_bearing():
    """lubedyn.papers.zhang2024.parameters.cageless_bearing() and a case naming Zhang2024 build the same model."""
    from lubedyn.scenes.dynamics import build
    from lubedyn.papers.zhang2024.parameters import cageless_bearing

    case = load_case(CASES / "cageless_6206_steady.toml")
    from_case = build(case).model
    twin = cageless_bearing(operating=dict(scenario="steady", speed=from_case.operating.speed))
    # the case's [bearing], [slots] and [lubricant] oil are the set's values; the rest are the case's choices
    assert twin.bearing == from_case.bearing
    assert twin.slots == from_case.slots
    for group, name in (("operating", "radial_load"), ("operating", "axial_load"), ("films", "viscosity"),
                        ("films", "pressure_viscosity")):
        assert getattr(getattr(twin, group), name) == getattr(getattr(from_case, group), name), name


@pytest.mark.parametrize("text, match", [
    ('scene = "dynamics"\nparameters = "Zhang2025"\n', r"parameters = 'Zhang2025' is not allowed; choose one of 'Zhang2024', 'Wu2018'; did you mean 'Zhang2024'\?"),
    ('scene = "dynamics"\nparameters = 3\n', "parameters = 3 must be the name of a parameter set"),
    ('scene = "dynamics"\nparameters = "Wu2018"\n', r"parameters = 'Wu2018' does not describe scene = 'dynamics'; it gives values for scene = 'static', 'tapered', 'ehl'"),
    ('scene = "dynamics"\n[operating]\nspeed = "1000 rpm"\n', r"bearing is required.*; or name a paper's values: parameters = 'Zhang2024'"),
])
def test_bad_parameter_sets_are_one_line(text, match):
    with pytest.raises(CaseError, match=match) as info:
        load_case_text(text)
    assert "\n" not in str(info.value)


def test_assumed_values_are_those_the_case_keeps():
    """A case naming a set lists, under "Assumed values", exactly the keys the set marks assumed and the
    case does not change: paper A's base oil in the roller EHL case, gone when the case gives its own."""
    from lubedyn.papers import assumed_values

    case = load_case(CASES / "ehl_roller_slice.toml")
    wu = P.parameter_set("Wu2018")
    expected = {k for k, n in wu.SCENES["ehl"].items() if wu.VALUES[n].source == "assumed"}
    assert set(assumed_values(case)) == expected and "lubricant.viscosity.eta0" in expected
    mine = load_case(CASES / "ehl_roller_slice.toml", overrides=["lubricant.viscosity.eta0=0.2 Pa s"])
    assert set(assumed_values(mine)) == expected - {"lubricant.viscosity.eta0"}
    assert assumed_values(load_case(CASES / "inclined_slider.toml")) == {}
