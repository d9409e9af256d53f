"""The tapered bearing's raceway films from the grease's EHL solve (``lubricant.raceway_film``).

Checked against:
- the kernel's film at a slice against Dowson & Toyoda's (1979) closed form H_c = 3.06 U^0.69 G^0.56
  W^-0.10, written out here, with each raceway's own film viscosity (cup P.etao, cone P.etai);
- "formula" (the default): both film viscosities are the films' Newtonian viscosity P.eta, so every
  existing case runs as before (benchmarks/case_summaries.py measured the trb cases bit-identical);
- "grease_ehl" with Table 2's polyurea at 30 C: the kernel's film at the most loaded roller's line load
  against a direct solve_ehl of the same contact (Table 2's numbers written out, the grid the scene used);
- lithium (n = 0.31), which the EHL solver does not reach: a one-line error naming the key.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import lubedyn
from lubedyn.config import CaseError
from lubedyn.dynamics.tapered import kernels as K
from lubedyn.lubrication import InputError
from lubedyn.lubrication.ehl import EHLContact, EHLGrid, solve_ehl
from lubedyn.lubrication.laws.lubricant import Barus, HerschelBulkleyFlow, Incompressible, Lubricant
from lubedyn.lubrication.laws.traction import limited_strip_traction
from lubedyn.scenes import tapered as S

CASE = "trb_grease_fa15kN"   # Fa 15 kN, 2,800 rpm, polyurea at 30 C


def _case(*overrides):
    return lubedyn.load_case(CASE, smoke=True, overrides=list(overrides))


def _dowson_toyoda(eta, u, w, R, alpha, ep):
    """Dowson & Toyoda (1979), line contact: h_c = R 3.06 U^0.69 G^0.56 W^-0.10."""
    return R * 3.06 * (eta * u / (ep * R)) ** 0.69 * (alpha * ep) ** 0.56 * (w / (ep * R)) ** -0.10


@pytest.mark.parametrize("case", ["trb_grease_fa15kN", "trb_fig5_2400rpm"])
def test_formula_leaves_both_film_viscosities_at_the_films_viscosity(case):
    """The default ("formula"): P.etao = P.etai = P.eta (0.1 Pa s, paper A's base oil)."""
    c = lubedyn.load_case(case, smoke=True)
    assert c.lubricant.raceway_film == "formula"
    P = S.build(c).args().P[0]
    assert P.etao == P.eta and P.etai == P.eta and P.eta == 0.1


def test_the_kernel_film_reads_the_race_viscosity():
    """K.raceway_film (the kernel's strip_film) against the closed form with the race's own viscosity,
    and the limited strip traction on that film: the cup's film follows P.etao only, the cone's P.etai
    only (measured: equal to the closed form to 1.1e-16)."""
    P = S.build(_case()).args().P.copy()[0]
    P.etao, P.etai = 0.37, 0.042
    w, vs = 8.0e4, 0.3
    for race, radius, eta in ((0, P.rxo, 0.37), (1, P.rxi, 0.042)):
        h = _dowson_toyoda(eta, P.ue, w, radius, P.pvc, P.ep)
        assert K.raceway_film(w, race, P) == pytest.approx(h, rel=1e-13)
        _, b, p0, h0 = K._slice_film(w * P.width, race, P)
        assert h0 == pytest.approx(h, rel=1e-13)
        assert b == pytest.approx(math.sqrt(8 * w * radius / (math.pi * P.ep)), rel=1e-14)
        assert K.strip_viscous_traction(w, race, vs, P) == limited_strip_traction(vs, h0, b, p0, K._rheo(P))
    cone = K.raceway_film(w, 1, P)
    P.etao = 5.0
    assert K.raceway_film(w, 1, P) == cone


def test_grease_ehl_film_is_the_solvers_film():
    """Polyurea at 30 C (tau_y 351.8 Pa, phi0 8.44 Pa s^n, n 0.7196, alpha 4.662e-8, Table 1-2): the
    kernel's film with the effective viscosity, at the most loaded roller's quasi-static line load of each
    raceway and the run's ideal entrainment speed, equals a direct solve_ehl of that line contact on the
    grid the scene used (the film at x = 0), to the solver's tolerance.  Measured: the cone 10.365 um
    against Dowson-Toyoda's 6.059 um with the 0.1 Pa s base oil (factor 1.711, eta_eff 0.218 Pa s); a
    second call solves nothing (the per-process cache)."""
    case = _case("lubricant.raceway_film=grease_ehl")
    model = S.build(case)
    qs = model.quasi_static()
    films = S.raceway_films(case, model, qs)
    P = model.args(qs).P[0]
    assert (P.etao, P.etai) == tuple(films[r]["Effective viscosity [Pa s]"] for r in S.RACES)
    assert P.eta == 0.1
    g, ue = model.geometry, model.entrainment_speed
    lub = Lubricant(Barus(8.44, 4.662e-8), Incompressible(870.0), herschel_bulkley=HerschelBulkleyFlow(351.8, 0.7196))
    race, r = "cone", 1
    w = float(np.max(qs.cone_loads)) / g.effective_length
    nx, x_min, x_max = films[race]["EHL grid (nodes, x_min, x_max) [-, b, b]"]
    sol = solve_ehl(EHLContact(g.reduced_radius(race), None, 0.5 * g.e_prime, lub, ue, load=w),
                    EHLGrid(nx=nx, x_min=x_min, x_max=x_max))
    x = sol.problem.doflocs[0]
    order = np.argsort(x)
    direct = float(np.interp(0.0, x[order], sol.film_thickness[order]))
    assert K.raceway_film(w, r, P) == pytest.approx(direct, rel=1e-6)
    assert films[race]["Factor h_EHL/h_formula [-]"] == pytest.approx(1.711, rel=1e-3)
    assert K.raceway_film(w, r, P) / _dowson_toyoda(0.1, ue, w, g.reduced_radius(race), 4.662e-8, g.e_prime) == \
        pytest.approx(films[race]["Factor h_EHL/h_formula [-]"], rel=1e-12)
    again = S.grease_ehl_film(race, g.reduced_radius(race), g.e_prime, model.lubricant.grease(), 870.0, w, ue)
    assert again["cached"] and again["central"] == pytest.approx(direct, rel=1e-6)


def test_lithium_reaches_the_solver_on_the_finer_grid():
    """Table 2's lithium (n = 0.31), out of the solver's reach before its homotopy start
    (lubedyn.lubrication.ehl.newton): its 257-node films fail the resolution check (18 % estimated error),
    the 513-node ones are used, and they are 1.2-1.6 times the apparent-viscosity line film
    (lubedyn.lubrication.laws.grease.grease_line_film, "apparent": the viscosity at the rolling shear
    rate u/h_c) as polyurea's and calcium's are (1.28 / 1.45, tests/test_ehl_hbflow.py; measured here 1.37 cup,
    1.38 cone): 0.064 / 0.054 um, far below the roughness."""
    from lubedyn.lubrication.laws import grease as G
    from lubedyn.papers.wu2018.parameters import GREASE_TABLE

    case = _case("lubricant.grease=lithium", "lubricant.raceway_film=grease_ehl")
    model = S.build(case)
    films = S.raceway_films(case, model, model.quasi_static())
    lithium = G.grease_at(GREASE_TABLE["lithium"], 30.0, 4.662e-8, "lithium")
    for race in S.RACES:
        r = films[race]
        assert r["EHL resolutions tried"][-1].startswith("513 nodes")
        apparent = G.grease_line_film(lithium, "apparent", r["Entrainment speed [m/s]"], r["Line load [N/m]"],
                                      r["Reduced radius [m]"], model.geometry.e_prime).central
        assert 1.2 < r["EHL central film [um]"] / (1e6 * apparent) < 1.6
        assert r["EHL central film [um]"] < 0.1


@pytest.mark.parametrize("overrides, word", [
    (["lubricant.grease=none", "lubricant.raceway_film=grease_ehl"], "needs a grease"),
    (["model.traction=map", "lubricant.raceway_film=grease_ehl"], "reads none"),
])
def test_grease_ehl_without_a_grease_or_a_film_traction_is_refused(overrides, word):
    with pytest.raises(CaseError) as err:
        _case(*overrides)
    assert "raceway_film" in str(err.value) and word in str(err.value) and "\n" not in str(err.value)
