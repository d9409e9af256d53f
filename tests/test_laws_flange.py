"""Flange / roller-end contact (lubedyn.lubrication.laws.flange) against independent values: the relative radii of
a sphere on a cone (Meusnier), the exact Hertz solution against Harris' form of it (eq. 21 of paper A,
q = (2 2^(1/2)/3) E' delta^(3/2)/(n_delta^(3/2) (sum rho)^(1/2))) with the elliptic integrals by
quadrature here, friction limits and continuity of eqs. 22-23, and the rib film ratio lambda at paper
A's operating points for both film models (the table of the module docstring)."""
import math

import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from lubedyn import papers as P
from lubedyn.papers.wu2018.parameters import GREASE_TABLE
from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws import contact as C
from lubedyn.lubrication.laws import flange as FL
from lubedyn.lubrication.laws import grease as G

SI = lambda name: P.si("Wu2018", name)  # noqa: E731
RS, RF = SI("roller_end_sphere_radius"), SI("rib_contact_radius")
BETA = SI("flange_contact_angle")
E_STAR = C.reduced_modulus(SI("steel_modulus"), SI("steel_poisson"), SI("steel_modulus"), SI("steel_poisson"))
EP, ALPHA, SIGMA = 2 * E_STAR, SI("grease_pressure_viscosity_all"), SI("flange_roughness")
B, CC, MU_A = SI("flange_asperity_b"), SI("flange_asperity_c"), SI("flange_asperity_friction")


def test_rib_radii_are_a_sphere_on_a_concave_cone():
    """1/R_gen = 1/r_s; 1/R_circ = 1/r_s - cos(beta_f)/r_f: 136.2 and 169.0 mm."""
    rc, rg = FL.rib_radii(RS, RF, BETA)
    assert rg == pytest.approx(RS, rel=1e-15)
    assert 1 / rc == pytest.approx(1 / RS - math.cos(math.radians(83)) / 0.0856, rel=1e-14)
    assert rc == pytest.approx(0.1690, abs=5e-5)


def _elliptic(m):
    K = quad(lambda t: 1 / math.sqrt(1 - m * math.sin(t) ** 2), 0, math.pi / 2, epsabs=0, epsrel=1e-13)[0]
    E = quad(lambda t: math.sqrt(1 - m * math.sin(t) ** 2), 0, math.pi / 2, epsabs=0, epsrel=1e-13)[0]
    return K, E


def _harris(load, ra, rb):
    """Harris & Kotzalas' dimensionless Hertz solution: kappa = a/b from F(rho) = ((k^2 + 1) E - 2 K)/
    ((k^2 - 1) E), a* = (2 k^2 E/pi)^(1/3), b* = (2 E/(pi k))^(1/3), delta* = (2 K/pi)(pi/(2 k^2 E))^(1/3);
    a = a* (3 Q/(2 sum rho E*))^(1/3), delta = delta* (3 Q/(2 sum rho E*))^(2/3) sum rho/2."""
    srho = 1 / ra + 1 / rb
    frho = (1 / rb - 1 / ra) / srho

    def resid(k):
        K, E = _elliptic(1 - 1 / k**2)
        return ((k * k + 1) * E - 2 * K) / ((k * k - 1) * E) - frho

    k = brentq(resid, 1 + 1e-9, 50.0, xtol=1e-15, rtol=1e-15)
    K, E = _elliptic(1 - 1 / k**2)
    s = 3 * load / (2 * srho * E_STAR)
    a_s, b_s = (2 * k * k * E / math.pi) ** (1 / 3), (2 * E / (math.pi * k)) ** (1 / 3)
    d_s = 2 * K / math.pi * (math.pi / (2 * k * k * E)) ** (1 / 3)
    return a_s * s ** (1 / 3), b_s * s ** (1 / 3), d_s * s ** (2 / 3) * srho / 2, d_s, srho


@pytest.mark.parametrize("load", [200.0, 446.0, 592.0, 711.0, 989.0])
def test_rib_hertz_is_harris_and_eq21(load):
    """The exact point law at the rib against Harris' solution with elliptic integrals by quadrature
    (1e-9), and eq. 21 (Harris' load-approach form) gives back the load."""
    hp = FL.rib_hertz(load, RS, RF, BETA, E_STAR)
    a, b, delta, n_delta, srho = _harris(load, *FL.rib_radii(RS, RF, BETA))
    assert (hp.a, hp.b, hp.approach) == pytest.approx((a, b, delta), rel=1e-9)
    q21 = 2 * math.sqrt(2) / 3 * EP * hp.approach**1.5 / (n_delta**1.5 * math.sqrt(srho))
    assert q21 == pytest.approx(load, rel=1e-9)
    assert hp.b / hp.a == pytest.approx(0.8662, abs=1e-4)  # mildly elliptical (eq. 20's text)


@pytest.mark.parametrize("compiled", [True, False])
def test_friction_limits_and_continuity(compiled):
    """lambda = 0: the boundary friction (s0/p0) q (load_share) or that plus the grease (paper);
    lambda >> 3: the grease traction only (both); odd in slip; continuous in lambda: steps of 1e-4
    change f by at most max|d share/d lambda| mu_a q dlambda (+ the grease part's share)."""
    ff = FL.flange_friction if compiled else FL.flange_friction.py_func
    q, fg = 592.0, 12.5
    assert ff(1.0, q, 0.0, fg, MU_A, B, CC, True) == pytest.approx(0.2 * q, rel=1e-15)
    assert ff(1.0, q, 0.0, fg, MU_A, B, CC, False) == pytest.approx(0.2 * q + fg, rel=1e-15)
    for mix in (True, False):
        assert ff(1.0, q, 30.0, fg, MU_A, B, CC, mix) == pytest.approx(fg, rel=1e-15)
        assert ff(-1.0, q, 0.7, -fg, MU_A, B, CC, mix) == -ff(1.0, q, 0.7, fg, MU_A, B, CC, mix)
    # eq. 23's share: 0.165 at lambda 1, 1.2e-3 at lambda 3 (B 1.8, C 1.2)
    assert FL.asperity_share(1.0, B, CC) == pytest.approx(math.exp(-1.8), rel=1e-15)
    assert FL.asperity_share(3.0, B, CC) < 1.5e-3
    step = 1e-4
    slope = B * CC * max(x**(CC - 1) * math.exp(-B * x**CC) for x in [i * 1e-3 for i in range(1, 10000)])
    lams = [i * step for i in range(0, 50001)]
    for mix in (True, False):
        f = [ff(1.0, q, lam, fg, MU_A, B, CC, mix) for lam in lams]
        jump = max(abs(f1 - f0) for f0, f1 in zip(f, f[1:]))
        assert jump <= slope * (MU_A * q + fg) * step * 1.01


# paper A's rib operating points (hand estimates, docs/paper_a.md): flange loads 200-989 N, entrainment 8.1-20.2 m/s
CORNERS = [(q, u) for q in (200.0, 989.0) for u in (8.1, 20.2)]
#: (reading, grease, model) -> (min, max) h_c [um] over CORNERS: the flange module's docstring table
TABLE = {("base", None, "hamrock_dowson"): (8.4, 17.3), ("base", None, "paper_eq24"): (12.4, 30.1),
         ("paper", "polyurea", "hamrock_dowson"): (164, 337), ("paper", "polyurea", "paper_eq24"): (17.9, 43.5),
         ("apparent", "polyurea", "hamrock_dowson"): (13.5, 26.5), ("apparent", "polyurea", "paper_eq24"): (13.2, 31.9),
         ("apparent", "calcium", "hamrock_dowson"): (6.9, 12.9), ("apparent", "calcium", "paper_eq24"): (12.4, 30.0),
         ("apparent", "lithium", "hamrock_dowson"): (0.144, 0.249), ("apparent", "lithium", "paper_eq24"): (9.7, 23.4)}


def _film(reading, name, model, q, u):
    def of(eta):
        return FL.rib_film(model, q, u, eta, ALPHA, EP, RS, RF, BETA)
    if reading == "base":
        return of(SI("base_oil_viscosity"))
    g = G.grease_at(GREASE_TABLE[name], 30.0, ALPHA, name)
    if reading == "paper":
        return of(g.viscosity("paper"))
    return G.apparent_film(g, u, of).central


@pytest.mark.parametrize("key", list(TABLE))
def test_rib_film_ratio_at_paper_a_operating_points(key):
    """h_c at the four corners within the docstring's printed ranges (to the printed digits, 1 %); lambda
    = h_c/sigma >= 34 and the asperity share negligible except lithium's apparent film under
    Hamrock-Dowson (lambda 0.72-1.25, share 0.10-0.30): a Hamrock-Dowson hand estimate
    with a 0.1 Pa s oil, 9-10 um, lies in the base-oil range."""
    h = [_film(*key, q, u) for q, u in CORNERS]
    lo, hi = TABLE[key]
    assert min(h) * 1e6 == pytest.approx(lo, rel=0.01) and max(h) * 1e6 == pytest.approx(hi, rel=0.01)
    lam = [x / SIGMA for x in h]
    shares = [FL.asperity_share(x, B, CC) for x in lam]
    if key == ("apparent", "lithium", "hamrock_dowson"):
        assert 0.6 < min(lam) and max(lam) < 1.3 and 0.09 < min(shares) and max(shares) < 0.31
    else:
        assert min(lam) > 34 and max(shares) < 1e-50


def test_eq24_exponents_and_hamrock_dowson_viscosity_response():
    """Eq. 24 rebuilt: h ~ eta^(0.5066 x 3/4 - 1.1869/4) = eta^0.0832 and alpha^-1.1869 (log-derivatives);
    phi 2.44 -> 38.44 Pa s^n changes h by 15.75^0.0832 = 1.257 (eq. 24) and 15.75^0.67 (Hamrock-Dowson)."""
    q, u = 592.0, 11.3
    h = lambda eta, model, al=ALPHA: FL.rib_film(model, q, u, eta, al, EP, RS, RF, BETA)  # noqa: E731
    assert math.log(h(2.0, "paper_eq24") / h(1.0, "paper_eq24")) / math.log(2) == pytest.approx(
        0.5066 * 0.75 - 1.1869 / 4, rel=1e-12)
    assert math.log(h(1.0, "paper_eq24", 2 * ALPHA) / h(1.0, "paper_eq24")) / math.log(2) == pytest.approx(
        -1.1869, rel=1e-12)
    ratio = 38.44 / 2.44
    assert h(38.44, "paper_eq24") / h(2.44, "paper_eq24") == pytest.approx(ratio**0.0832, rel=1e-3)
    assert h(38.44, "hamrock_dowson") / h(2.44, "hamrock_dowson") == pytest.approx(ratio**0.67, rel=1e-12)


def test_bad_input_is_one_line():
    for call, match in ((lambda: FL.rib_film("moes", 1.0, 1.0, 0.1, ALPHA, EP, RS, RF, BETA), "rib film model = 'moes'"),
                        (lambda: FL.rib_hertz(-5.0, RS, RF, BETA, E_STAR), r"contact load \[N\] = -5.0"),
                        (lambda: FL.rib_radii(RS, 0.0, BETA), r"rib contact radius r_f \[m\] = 0.0")):
        with pytest.raises(InputError, match=match) as info:
            call()
        assert "\n" not in str(info.value)
