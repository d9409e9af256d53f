"""The base oil's viscosity against temperature (lubedyn.lubrication.laws.thermal, ASTM D341's Walther line)
and its route into paper A's tapered bearing (``lubricant.oil_temperature = "walther"``).

Checked against a worked example of the standard's two-point method published with its constants, the
line's exactness at its two points, and the route: the dynamics' viscosity at a case's temperature is the
law's, the films that read it scale with it by their own published exponent."""
from __future__ import annotations

import math

import pytest

import lubedyn
from lubedyn.config import CaseError
from lubedyn.lubrication import InputError
from lubedyn.lubrication.laws import thermal as T
from lubedyn.scenes import tapered

CST = 1e-6  # mm^2/s -> m^2/s


def test_walther_matches_the_published_worked_example():
    """ASTM D341's two-point line through (40 C, 32 mm^2/s) and (100 C, 5.4 mm^2/s), worked with T = t + 273:
    A = 9.5259, B = 3.7449 and 8.5 mm^2/s at 80 C (as printed, to its digits)."""
    t40, t100 = 40.0 + 273.0 - T.KELVIN, 100.0 + 273.0 - T.KELVIN   # the example's 273 instead of 273.15
    a, b = T.walther_constants(t40, 32 * CST, t100, 5.4 * CST)
    assert a == pytest.approx(9.5259, abs=5e-5) and b == pytest.approx(3.7449, abs=5e-5)
    nu80 = T.walther_kinematic(80.0 + 273.0 - T.KELVIN, t40, 32 * CST, t100, 5.4 * CST) / CST
    assert round(nu80, 1) == 8.5


def test_walther_line_is_exact_at_its_points_and_straight_in_its_chart():
    """The two points come back exactly; a third point lies on the straight line in the chart's coordinates
    log log(nu + 0.7) against log T (checked from the coordinates, not from the constants)."""
    nu = lambda t: T.walther_kinematic(t, 40.0, 68 * CST, 100.0, 8.6 * CST)  # noqa: E731
    assert nu(40.0) == 68 * CST and nu(100.0) == 8.6 * CST
    z = lambda v: math.log10(math.log10(v / CST + 0.7))  # noqa: E731
    x = lambda t: math.log10(t + 273.15)  # noqa: E731
    for t in (15.0, 30.0, 70.0, 120.0):
        slope_a = (z(nu(t)) - z(nu(40.0))) / (x(t) - x(40.0))
        slope_b = (z(nu(100.0)) - z(nu(40.0))) / (x(100.0) - x(40.0))
        assert slope_a == pytest.approx(slope_b, rel=1e-9)
    # falls with temperature, by about 15 times from 15 to 70 C for this oil
    assert nu(15.0) > nu(30.0) > nu(70.0)
    assert 10 < nu(15.0) / nu(70.0) < 20


def test_walther_dynamic_keeps_the_reference_exact():
    eta = T.walther_dynamic(30.0, 30.0, 0.1, 100.0, 8.6 * CST, 870.0)
    assert eta == 0.1
    # an ISO VG 68 oil (61.2-74.8 mm^2/s at 40 C, ISO 3448): this line's 40 C viscosity is inside the grade
    nu40 = T.walther_dynamic(40.0, 30.0, 0.1, 100.0, 8.6 * CST, 870.0) / 870.0 / CST
    assert 61.2 <= nu40 <= 74.8


@pytest.mark.parametrize("call, word", [
    (lambda: T.walther_constants(40.0, 68 * CST, 40.0, 8.6 * CST), "equal"),
    (lambda: T.walther_constants(40.0, -1.0, 100.0, 8.6 * CST), "nu1"),
    (lambda: T.walther_kinematic(500.0, 40.0, 68 * CST, 100.0, 8.6 * CST), "outside"),
])
def test_walther_refuses_bad_input_in_one_line(call, word):
    with pytest.raises(InputError) as err:
        call()
    assert word in str(err.value) and "\n" not in str(err.value)


def _lubricant(*overrides):
    case = lubedyn.load_case("trb_grease_fa15kN", smoke=True, overrides=list(overrides))
    return case, tapered.build(case).lubricant


def test_the_tapered_bearings_base_oil_follows_the_grease_temperature():
    """Paper A's parameter set: 0.1 Pa s at 30 C (exactly, so the 30 C runs are unchanged), the Walther line
    elsewhere; with oil_temperature = "none" eta0 at every temperature."""
    _, at30 = _lubricant("lubricant.temperature_c=30")
    assert at30.base_oil_viscosity == 0.1 and at30.viscosity() == 0.1
    for t in (15.0, 50.0, 70.0):
        case, lu = _lubricant(f"lubricant.temperature_c={t}")
        expected = 870.0 * T.walther_kinematic(t, 30.0, 0.1 / 870.0, 100.0, 8.6 * CST)
        assert lu.viscosity() == pytest.approx(expected, rel=1e-12)
    _, fixed = _lubricant("lubricant.temperature_c=70", "lubricant.oil_temperature='none'")
    assert fixed.viscosity() == 0.1


def test_the_dynamics_read_the_oil_at_its_temperature():
    """The route into the compiled dynamics: the kernel's viscosity is the law's at the case's temperature,
    and the raceway traction's decay rate (the film's elastic slope 2 G b^2/(u_e h) over the roller's
    inertia, with h from Dowson-Toyoda) scales as h^-1 ~ eta^-0.69 between 15 and 70 C (Dowson & Toyoda 1979: H_c = 3.06 U^0.69 G^0.56 W^-0.1, the film formula's
    published exponent of eta; load and speed are the same in both runs)."""
    etas, rates = {}, {}
    for t in (15.0, 70.0):
        case, lu = _lubricant(f"lubricant.temperature_c={t}")
        bearing = tapered.build(case)
        assert bearing.args().P.eta[0] == lu.viscosity()
        etas[t], rates[t] = lu.viscosity(), bearing.traction_rate()
    assert rates[70.0] / rates[15.0] == pytest.approx((etas[15.0] / etas[70.0]) ** 0.69, rel=1e-9)
    assert 5 < rates[70.0] / rates[15.0] < 8


@pytest.mark.parametrize("overrides, key", [
    (["lubricant.temperature_c=-40"], "temperature_c"),
    (["lubricant.oil_reference_c=100"], "oil_reference_c"),
])
def test_bad_oil_temperature_keys_are_one_line_errors(overrides, key):
    with pytest.raises(CaseError) as err:
        lubedyn.load_case("trb_grease_fa15kN", smoke=True, overrides=overrides)
    assert key in str(err.value) and "\n" not in str(err.value)
