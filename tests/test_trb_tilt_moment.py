"""Paper A's tapered bearing: the terms of the rollers' tilt moment (kernels, "Tilt moment") checked
against closed forms and Euler's equations, and the raceway traction laws' curves at paper A's most loaded
roller checked against independent values (closed forms, quadrature, a direct EHL solve)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from lubedyn.config import load_case
from lubedyn.dynamics.tapered import kernels as K
from lubedyn.dynamics.tapered import layout as L
from lubedyn.dynamics.tapered.model import attitude
from lubedyn.lubrication.laws.film import dowson_toyoda_central
from lubedyn.scenes import tapered as S

CASE = "cases/trb_fig5_2400rpm.toml"


def _forces(y, args):
    Z, ns = int(args.P[0].z), int(args.P[0].ns)
    F, T, loads, FR = np.zeros((Z, 3)), np.zeros((Z, 3)), np.zeros((Z, 4)), np.zeros((Z, L.N_FRICTION))
    K.contact_forces(np.ascontiguousarray(y), args, F, T, np.zeros(3), np.zeros(3), loads, np.zeros(3), np.zeros(3),
                     np.zeros((Z, 2, ns)), FR, np.zeros(L.N_CAGE_DIAG))
    return T, loads, FR


def _tilt_axis(y, j):
    c = y[L.N_CONE + j * L.NB:L.N_CONE + j * L.NB + 3]
    return np.array([0.0, -c[2], c[1]]) / math.hypot(c[1], c[2])


def _skewed(y, j, psi):
    """The state with roller j turned by ``psi`` about the normal a = e x t to its axis e in its meridional
    plane, so that its axis gains the tangential component sin(psi) (a skew of psi)."""
    from lubedyn.dynamics.rotations import quat_from_rotvec

    y = y.copy()
    b = L.N_CONE + j * L.NB
    q = y[b + 3:b + 7] / np.linalg.norm(y[b + 3:b + 7])
    w, x, yy, z = q
    e = np.array([1 - 2 * (yy * yy + z * z), 2 * (x * yy + w * z), 2 * (x * z - w * yy)])   # R(q) e_x
    a = np.cross(e, _tilt_axis(y, j))
    r = np.empty(4)
    quat_from_rotvec(psi * a / np.linalg.norm(a), r)
    # r * q (scalar first): the rotation r after q
    r0, rv, q0, qv = r[0], r[1:], q[0], q[1:]
    y[b + 3:b + 7] = np.concatenate([[r0 * q0 - rv @ qv], r0 * qv + q0 * rv + np.cross(rv, qv)])
    return y


@pytest.fixture(scope="module")
def laws():
    """({law: (model, kernel arguments)} at Fig. 5's point, the most loaded roller's (cup, cone) line loads [N/m],
    the quasi-static start)."""
    out, qs = {}, None
    for law in ("limited", "paper", "map"):
        model = S.build(load_case(CASE, overrides=[f"model.traction={law}"]))
        qs = model.quasi_static() if qs is None else qs
        out[law] = (model, model.args(qs))
    j = int(np.argmax(qs.cone_loads))
    le = out["limited"][0].geometry.effective_length
    return out, (float(qs.cup_loads[j] / le), float(qs.cone_loads[j] / le)), qs


@pytest.mark.parametrize("psi", [5e-3, -5e-3])
def test_a_skewed_rollers_raceway_traction_is_a_couple_about_its_tilt_axis_of_the_skews_sign(laws, psi):
    """The derivation of the tilt's sign (kernels, "Tilt moment"): a roller skewed by psi slides axially on
    both raceways at psi u_e in opposite senses, and the two tractions, on opposite sides of its axis, are
    a couple about its tilt axis of magnitude rho_m [mu_cup(|psi|) Q_cup + mu_cone(|psi|) Q_cone] and the
    sign of psi.  The most loaded roller of Fig. 5's start state, turned by psi: the kernel's cup + cone
    traction moment against that closed form (mu from the law at slide-to-roll ratio |psi|, Q the kernel's
    raceway loads).  Limited law (saturated, F_k proportional to the slice loads): measured 0.996 of it
    (7.61 against 7.65 N m) for both signs.  Eq. 12 ("paper", linear in the sliding and nearly independent
    of the load, so the crowned end slices that carry no load carry no traction either, while the closed
    form counts them): 0.90; its couple (3.7e-5 N m) is 5e-6 of the limited law's, and the rib's normal
    moment (-3.1 N m: negative, paper A's tilt sense; the rib load rises from 232 to 513 N with this skew,
    the end sphere's far centre swinging round the rib closes it at second order in psi) exceeds it by 5
    decades."""
    models, _, qs = laws
    out = {}
    for law in ("limited", "paper"):
        model, args = models[law]
        j = int(np.argmax(qs.cone_loads))
        y = _skewed(model.start_state(qs), j, psi)
        e_t = attitude(y[None, :], model.n_rollers)[1][0, j]
        assert e_t == pytest.approx(psi, rel=1e-9)
        T, loads, FR = _forces(y, args)
        m = FR[j, L.F_TILT:]
        assert m.sum() == pytest.approx(T[j] @ _tilt_axis(y, j), rel=1e-12)
        le, rho = model.geometry.effective_length, model.geometry.mean_roller_radius
        closed = math.copysign(rho * sum(model.raceway_traction_coefficient(race, loads[j, k] / le, abs(psi), args)
                                         * loads[j, k] for k, race in enumerate(("cup", "cone"))), psi)
        out[law] = (m[2] + m[3], closed, m[4])
    traction, closed, rib = out["limited"]
    assert traction == pytest.approx(closed, rel=0.03)
    assert np.sign(traction) == np.sign(psi) and rib < 0.0
    traction_paper, closed_paper, rib_paper = out["paper"]
    assert traction_paper == pytest.approx(closed_paper, rel=0.15)
    assert abs(traction_paper) < 1e-4 * abs(traction) and abs(traction_paper) < 1e-4 * abs(rib_paper)
    assert rib_paper < 0.0


def test_tilt_moment_terms_sum_to_the_torque_and_balance_the_gyroscopic_moment():
    """Over 1 ms of Fig. 5's point (smoke size), the terms' sum is each roller's contact torque about its
    tilt axis (round-off, at the end state), and its loaded-zone mean over the second half is the moment
    steady orbiting needs, Omega sin(beta) [I_x (omega_s + Omega cos beta) - I_y Omega cos beta] from the
    sampled attitude and speeds (Euler's equations; the tilt's own acceleration averages out): measured
    -0.1640 against -0.1629 N m (0.7 %; 0.5 % over 2 ms, 0.1 % over 20-40 ms at 10 slices,
    benchmarks/results/trb_tilt_sign.json)."""
    case = load_case(CASE, smoke=True)
    run = S.run(case)
    model = S.build(case)
    args = model.args()
    T, _, FR = _forces(run.y[-1], args)
    for j in range(model.n_rollers):
        assert FR[j, L.F_TILT:].sum() == pytest.approx(T[j] @ _tilt_axis(run.y[-1], j), rel=1e-10, abs=1e-12)
    D, t = run.diagnostics, run.t
    w = t >= 0.5 * t[-1]
    zone = D["Loaded zone [-]"][w]
    total = sum(D[name][w] for name in L.TILT_MOMENT_NAMES)[zone]
    beta, _, orbital, spin = attitude(run.y[w], model.n_rollers)
    P = args.P[0]
    demand = (orbital * np.sin(beta) * (P.ix * (spin + orbital * np.cos(beta)) - P.iy * orbital * np.cos(beta)))[zone]
    assert np.mean(total) == pytest.approx(np.mean(demand), rel=0.03)
    summary = run.summary["Record's second half (shorter than a cage revolution)"]["Tilt moment means [N m]"]
    assert summary["loaded zone"]["sum"] == pytest.approx(np.mean(total), rel=1e-12)


def _strip(model, race, w):
    """(R', b, h) from the geometry and the film law, not from the kernel's record."""
    g, lu = model.geometry, model.lubricant
    r, ep, ue = g.reduced_radius(race), g.e_prime, model.entrainment_speed
    h = r * dowson_toyoda_central(lu.viscosity() * ue / (ep * r), lu.pressure_viscosity * ep, w / (ep * r))
    return r, math.sqrt(8.0 * w * r / (math.pi * ep)), h


@pytest.mark.parametrize("race", ["cup", "cone"])
def test_limited_law_at_its_two_closed_form_limits(laws, race):
    """At the most loaded roller (cup 121.7, cone 118.4 kN/m, p_H 0.61 / 0.67 GPa, u_e 11.03 m/s): at SRR 1e-6
    the film's elastic shear, mu = 2 G b^2 s/(h w) (measured 1 - 1.5e-7: the tanh's cubic term); at SRR 0.1
    the limiting shear over the whole Hertz strip, mu = gamma_L + 2 b tau_L0/w = 0.0721 / 0.0719, an upper
    bound the law approaches from below (measured 0.9975 / 0.9983 of it: the strip's edges, below about 60
    MPa, shear under the limit)."""
    models, wl, _ = laws
    model, args = models["limited"]
    w = wl[0] if race == "cup" else wl[1]
    r, b, h = _strip(model, race, w)
    lu = model.lubricant
    elastic = 2.0 * lu.shear_modulus * b * b * 1e-6 / (h * w)
    assert model.raceway_traction_coefficient(race, w, 1e-6, args) == pytest.approx(elastic, rel=1e-6)
    bound = lu.limiting_slope + 2.0 * b * lu.limiting_stress / w
    ratio = model.raceway_traction_coefficient(race, w, 0.1, args) / bound
    assert 0.995 < ratio < 1.0


@pytest.mark.parametrize("race", ["cup", "cone"])
def test_paper_law_against_the_couette_traction_of_its_gap(laws, race):
    """Eq. 12 (eps of eq. 13 in closed form) against adaptive quadrature of the Couette traction of its gap
    h = h0 + 2 x^2/R' over the Hertz strip, eta s u_e int 2 (h - h0)/h^2 dx/w, at SRR 1e-3: measured 1e-15."""
    models, wl, _ = laws
    model, args = models["paper"]
    w = wl[0] if race == "cup" else wl[1]
    r, b, h = _strip(model, race, w)
    val, _ = quad(lambda x: 2.0 * (2.0 * x * x / r) / (h + 2.0 * x * x / r) ** 2, -b, b, epsabs=0.0, epsrel=1e-12)
    couette = model.lubricant.viscosity() * 1e-3 * model.entrainment_speed * val / w
    assert model.raceway_traction_coefficient(race, w, 1e-3, args) == pytest.approx(couette, rel=1e-9)


@pytest.mark.parametrize("race, srr", [("cup", 0.1), ("cone", 1e-2)])
def test_map_law_against_a_direct_ehl_solve(laws, race, srr):
    """The map law at the most loaded roller's line load and the run's entrainment speed against the EHL
    line contact solved directly with the map's parameters: within the maps' 3 % target (measured 2.5e-4
    for the cup at SRR 0.1, 1.0e-3 for the cone at 1e-2)."""
    from lubedyn.film_points import evaluate_ehl_line

    models, wl, _ = laws
    model, args = models["map"]
    w = wl[0] if race == "cup" else wl[1]
    fmap = model.traction_maps[0 if race == "cup" else 1]
    direct = evaluate_ehl_line(fmap.provenance["params"], {"Line load [N/m]": w, "Entrainment speed [m/s]":
                                                           model.entrainment_speed, "Slide-to-roll ratio [-]": srr})
    assert model.raceway_traction_coefficient(race, w, srr, args) == pytest.approx(
        direct["Traction coefficient [-]"], rel=0.03)


def test_raceway_traction_names_a_bad_race(laws):
    from lubedyn.lubrication.errors import InputError

    model, args = laws[0]["limited"]
    with pytest.raises(InputError, match="race = 'inner' is not a raceway; choose 'cup' or 'cone'"):
        model.raceway_traction_coefficient("inner", 1e5, 1e-3, args)
