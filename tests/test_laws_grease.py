"""Grease laws (lubedyn.lubrication.laws.grease) against independent values: a hand-computed apparent-viscosity
table of Table 2's 30 C rows (recomputed here from the raw rows; docs/paper_a.md, "Estimates at paper A's
operating points"), the ranking reversal of the two readings of phi, Table 2
itself at its temperatures, the Herschel-Bulkley law's oddness and its Newtonian limit, and the film of a
Newtonian "grease" against the project's Dowson-Toyoda and Moes line films and the hand estimate's
5.4 um."""
import math

import pytest

from lubedyn.papers.wu2018.parameters import GREASE_TABLE
from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws import film as F
from lubedyn.lubrication.laws import grease as G

ALPHA = 4.662e-8  # Table 1, polyurea at 30 C
# hand-computed apparent viscosity [Pa s] of Table 2's 30 C rows, tau_y/D + phi D^(n-1), to 2 significant figures
HAND_TABLE = {1e4: {"polyurea": 0.67, "lithium": 0.16, "calcium": 0.74},
            1e6: {"polyurea": 0.18, "lithium": 0.0043, "calcium": 0.080},
            1e7: {"polyurea": 0.09, "lithium": 0.0008, "calcium": 0.027}}


def _printed_half_unit(value):
    """Half a unit in the last printed digit of a value printed with 2 significant figures (1 for 0.09)."""
    text = repr(value)
    decimals = len(text.split(".")[1]) if "." in text else 0
    return 0.5 * 10.0**-decimals


def _row(name, t):
    return next(r for r in GREASE_TABLE[name] if r[0] == t)


@pytest.mark.parametrize("rate", sorted(HAND_TABLE))
def test_apparent_viscosity_is_the_hand_table(rate):
    """tau_y/D + phi D^(n-1) from Table 2's raw 30 C rows (written out here) equals the law to 1e-13 and
    the hand table to half a unit in its last digit."""
    for name, printed in HAND_TABLE[rate].items():
        _, ty, ph, n = _row(name, 30)
        independent = ty / rate + ph * rate ** (n - 1)
        law = G.grease_at(GREASE_TABLE[name], 30.0, ALPHA, name).apparent_viscosity(rate)
        assert law == pytest.approx(independent, rel=1e-13)
        assert abs(law - printed) <= _printed_half_unit(printed) * (1 + 1e-9), (name, rate, law)


def test_the_two_readings_reverse_the_ranking():
    """Table 2's phi0 read as Pa s (paper A's eqs. 12, 25, 34-35) ranks calcium > lithium > polyurea; the apparent viscosity at the
    contacts' 1e6 1/s ranks polyurea > calcium > lithium (lithium falls from second to last)."""
    greases = {n: G.grease_at(GREASE_TABLE[n], 30.0, ALPHA, n) for n in GREASE_TABLE}
    paper = sorted(greases, key=lambda n: -greases[n].viscosity("paper"))
    apparent = sorted(greases, key=lambda n: -greases[n].viscosity("apparent", shear_rate=1e6))
    assert paper == ["calcium", "lithium", "polyurea"]
    assert apparent == ["polyurea", "calcium", "lithium"]
    # base oil: one viscosity for all three (the grease enters through traction only)
    assert {g.viscosity("base_oil", base_oil_viscosity=0.1) for g in greases.values()} == {0.1}


def test_yield_share_at_1e6():
    """Table 2's 30 C rows: at 1e6 1/s the yield stress is 0.2 % of the stress for polyurea, about 19 % for lithium."""
    for name, share in (("polyurea", 0.002), ("lithium", 0.19)):
        g = G.grease_at(GREASE_TABLE[name], 30.0, ALPHA, name)
        assert g.yield_stress / g.stress(1e6) == pytest.approx(share, abs=0.0005 if share < 0.01 else 0.005)


def test_table_2_at_its_temperatures_and_between():
    """The table's numbers at 15/30/50/70 C exactly; midway the geometric mean of tau_y and phi and the
    arithmetic mean of n (log-linear / linear interpolation)."""
    for name, rows in GREASE_TABLE.items():
        for t, ty, ph, n in rows:
            g = G.grease_at(rows, t, ALPHA, name)
            assert (g.yield_stress, g.consistency, g.exponent) == (ty, ph, n)
        for (t0, ty0, ph0, n0), (t1, ty1, ph1, n1) in zip(rows, rows[1:]):
            g = G.grease_at(rows, 0.5 * (t0 + t1), ALPHA, name)
            assert g.yield_stress == pytest.approx(math.sqrt(ty0 * ty1), rel=1e-14)
            assert g.consistency == pytest.approx(math.sqrt(ph0 * ph1), rel=1e-14)
            assert g.exponent == pytest.approx(0.5 * (n0 + n1), rel=1e-14)


@pytest.mark.parametrize("t", [14.9, 70.01, -40.0, float("nan")])
def test_temperature_outside_the_table_is_one_line(t):
    with pytest.raises(InputError, match=r"grease temperature \[C\] = .* allowed 15-70 C") as info:
        G.grease_at(GREASE_TABLE["lithium"], t, ALPHA, "lithium")
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("compiled", [True, False])
def test_herschel_bulkley_is_odd_and_newtonian_in_the_limit(compiled):
    """tau(-D) = -tau(D); tau_y = 0, n = 1 gives tau = phi D; Barus phi0 exp(alpha p); Papanastasiou's
    regularisation tends to the exact law for D >> D_r and is continuous (-> 0) at D = 0."""
    hb = G.hb_stress if compiled else G.hb_stress.py_func
    for D in (1e-3, 7.0, 3e5):
        assert hb(-D, 351.8, 8.44, 0.7196, 0.0) == -hb(D, 351.8, 8.44, 0.7196, 0.0)
        assert hb(D, 0.0, 0.1, 1.0, 0.0) == pytest.approx(0.1 * D, rel=1e-15)
    assert hb(1e3, 351.8, 8.44, 0.7196, 1.0) == pytest.approx(hb(1e3, 351.8, 8.44, 0.7196, 0.0), rel=1e-15)
    # tau_y (1 - exp(-D/D_r)) <= tau_y D/D_r: at D = 1e-9 the stress is phi D^n plus at most 3.5e-7 Pa
    assert 0 < hb(1e-9, 351.8, 8.44, 0.7196, 1.0) - 8.44 * 1e-9**0.7196 <= 351.8e-9
    assert hb(0.0, 351.8, 8.44, 0.7196, 0.0) == 0.0
    g = G.Grease(0.0, 2.0, 1.0, ALPHA)
    assert g.stress(10.0, 4e8) == pytest.approx(2.0 * math.exp(ALPHA * 4e8) * 10.0, rel=1e-14)


def _u_w_g(eta, u, w, R, Ep):
    return eta * u / (Ep * R), w / (Ep * R), ALPHA * Ep


def test_newtonian_grease_film_is_dowson_toyoda_and_moes():
    """tau_y = 0, n = 1, phi0 = 0.1 Pa s: every reading that uses the grease gives the Newtonian line film
    of lubedyn.lubrication.laws.film to round-off (Dowson-Toyoda and Moes); at paper A's most loaded cone contact
    (2.4 krpm: u_m 11.03 m/s, 115 kN/m, R' 9.41 mm, E' 225 GPa) Dowson-Toyoda gives the hand estimate's
    5.4 um (to 0.1 um) and Moes lies within 6 % of it (measured 5.3 %)."""
    u, w, R, Ep = 11.03, 115e3, 9.41e-3, 225e9
    newtonian = G.Grease(0.0, 0.1, 1.0, ALPHA)
    U, W, Gp = _u_w_g(0.1, u, w, R, Ep)
    dt = R * F.dowson_toyoda_central(U, Gp, W)
    moes = R * math.sqrt(2 * U) * F.moes_line_central(W / math.sqrt(2 * U), Gp * (2 * U) ** 0.25)
    for reading in ("apparent", "paper"):
        assert G.grease_line_film(newtonian, reading, u, w, R, Ep).central == pytest.approx(dt, rel=1e-12)
        assert G.grease_line_film(newtonian, reading, u, w, R, Ep, formula="moes").central == pytest.approx(
            moes, rel=1e-12)
    assert G.grease_line_film(newtonian, "base_oil", u, w, R, Ep, 0.1).central == pytest.approx(dt, rel=1e-15)
    assert dt == pytest.approx(5.4e-6, abs=0.05e-6)
    assert abs(moes / dt - 1) < 0.06


def test_polyurea_films_under_each_reading():
    """Notes 2.3: phi0 = 8.44 read as Pa s gives raceway films of 115-191 um (115 um at the cone contact);
    the apparent reading solves D = u_m/h_c self-consistently (checked here) and gives a film between the
    base oil's and the paper's."""
    u, w, R, Ep = 11.03, 115e3, 9.41e-3, 225e9
    pu = G.grease_at(GREASE_TABLE["polyurea"], 30.0, ALPHA, "polyurea")
    paper = G.grease_line_film(pu, "paper", u, w, R, Ep)
    assert paper.central == pytest.approx(115e-6, abs=0.5e-6)
    app = G.grease_line_film(pu, "apparent", u, w, R, Ep)
    assert app.shear_rate == pytest.approx(u / app.central, rel=1e-12)
    assert app.viscosity == pytest.approx(pu.apparent_viscosity(u / app.central), rel=1e-12)
    base = G.grease_line_film(pu, "base_oil", u, w, R, Ep, 0.1)
    assert base.central < app.central < paper.central
    given = G.grease_line_film(pu, "apparent", u, w, R, Ep, shear_rate=1e6)
    assert given.viscosity == pytest.approx(351.8 / 1e6 + 8.44 * 1e6 ** (0.7196 - 1), rel=1e-13)


@pytest.mark.parametrize("call, match", [
    (lambda g: g.viscosity("apparant"), "grease viscosity reading = 'apparant'.*did you mean 'apparent'"),
    (lambda g: g.viscosity("base_oil"), r"base_oil_viscosity \[Pa s\] = None"),
    (lambda g: g.viscosity("apparent"), r"shear_rate \[1/s\] = None"),
    (lambda g: G.Grease(-1.0, 8.44, 0.7), r"grease yield_stress \[Pa\] = -1.0"),
    (lambda g: G.Grease(1.0, 8.44, 0.0), r"grease exponent n = 0.0 must lie in \(0, 2\]"),
    (lambda g: G.grease_line_film(g, "paper", 1.0, 1e5, 0.01, 2e11, formula="moss"), "line film formula = 'moss'"),
])
def test_bad_input_is_one_line(call, match):
    g = G.Grease(351.8, 8.44, 0.7196, ALPHA)
    with pytest.raises(InputError, match=match) as info:
        call(g)
    assert "\n" not in str(info.value)
