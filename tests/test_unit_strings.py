"""Unit strings from Python: the films' constructors (gaps, lubricant laws, Film) and the case tables take
"50 um" as the case files do, through the one parser (lubedyn.lubrication.laws.units, public as
lubedyn.units); each string equals its SI float by the unit's definition (1 mm = 1e-3 m, 1 deg = pi/180
rad, 1 mPa s = 1e-3 Pa s), and a wrong dimension is one line naming the field, the value and what is
expected."""
from __future__ import annotations

import math

import pytest

from lubedyn.config import CaseError, SolverModel, ValidityModel
from lubedyn.lubrication import Film, InclinedSlider, JournalBearing, Lubricant
from lubedyn.lubrication import closed_form as cf
from lubedyn.lubrication import mesh as meshes
from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws.lubricant import Barus, DowsonHigginson, Roelands


def test_gaps_take_lengths_and_angles_with_units():
    assert JournalBearing("25 mm", "50 um", "10 um") == JournalBearing(0.025, 5e-05, 1e-05, 0.0)
    # an angle is pi/180 per degree, kept to the parser's 15 significant digits
    turned = JournalBearing.from_ratio("25 mm", "50 um", 0.6, "90 deg")
    assert turned.eccentricity_y == pytest.approx(0.6 * 5e-05, rel=1e-14) and abs(turned.eccentricity_x) < 1e-18
    assert InclinedSlider("40 um", "20 um", "5 cm") == InclinedSlider(4e-05, 2e-05, 0.05)


def test_lubricant_laws_take_their_units():
    assert Lubricant.newtonian("50 mPa s") == Lubricant.newtonian(0.05)
    assert Lubricant.newtonian("0.5 P", "850 kg/m^3") == Lubricant.newtonian(0.05, 850.0)  # 1 poise = 0.1 Pa s
    assert Barus("0.05 Pa s", "2e-8 1/Pa") == Barus(0.05, 2e-8)
    assert Roelands("50 cP", alpha="20 1/GPa").alpha == pytest.approx(2e-8, rel=1e-15)
    assert DowsonHigginson("850 kg/m^3", "0.6 1/GPa") == DowsonHigginson(850.0, 0.6e-9)


def test_a_film_built_from_strings_solves_to_the_slider_closed_form():
    """The README slider (h_in = 2 h_out = 40 um, 50 mm, 0.05 Pa s, runner 5 m/s) written with units: the
    same film as in SI, whose load per unit width is the closed form's."""
    mesh = meshes.interval(0.0, 0.05, 8)
    text = Film(mesh, InclinedSlider("40 um", "20 um", "50 mm"), Lubricant.newtonian("50 mPa s"),
                velocity_lower=("5 m/s",), element="P2")
    si = Film(mesh, InclinedSlider(4e-05, 2e-05, 0.05), Lubricant.newtonian(0.05), velocity_lower=(5.0,),
              element="P2")
    assert text.velocity_lower == (5.0,) and text.gap == si.gap and text.lubricant == si.lubricant
    load = text.solve().load
    assert load == si.solve().load
    assert load == pytest.approx(cf.inclined_slider_load(4e-05, 2e-05, 0.05, 0.05, 2.5), rel=1e-3)


@pytest.mark.parametrize("make, fragment", [
    (lambda: JournalBearing("25 mm", "50 Pa"), "JournalBearing.clearance = '50 Pa' has units of pressure, "
                                               "expected length (m)"),
    (lambda: Lubricant.newtonian("50 mm"), "ConstantViscosity.eta0 = '50 mm' has units of length, "
                                           "expected dynamic viscosity (Pa s)"),
    (lambda: JournalBearing.from_ratio(0.025, 5e-05, 0.5, "3 m"), "JournalBearing.from_ratio attitude_angle = "
                                                                  "'3 m' has units of length, expected angle"),
    (lambda: InclinedSlider("40 um", "20 uj", 0.05), "InclinedSlider.h_out = '20 uj' has an unknown unit 'uj'"),
])
def test_a_wrong_unit_is_one_line_naming_the_field(make, fragment):
    with pytest.raises(InputError) as err:
        make()
    assert "\n" not in str(err.value) and fragment in str(err.value)


def test_case_tables_built_from_python_take_units_and_say_mistakes_in_one_line():
    assert ValidityModel(min_film="0.1 um", max_pressure="3 GPa").min_film == pytest.approx(1e-7, rel=1e-15)
    assert ValidityModel(max_pressure="3 GPa").max_pressure == 3e9
    with pytest.raises(CaseError) as err:
        ValidityModel(min_film="0.1 Pa")
    assert str(err.value) == "ValidityModel: min_film = '0.1 Pa' has units of pressure, expected length (m)"
    with pytest.raises(CaseError, match=r"^SolverModel: rtl: unknown key .*did you mean 'rtol'"):
        SolverModel(rtl=1e-8)
