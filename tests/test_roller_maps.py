"""Paper A's roller EHL map kinds on a line-load axis (issue 22, section 4): geometry, the light-load
domain, the high-speed limit of the Newton iteration, and the convention of the traction axis.

Independent values: paper A's notes (reduced radii, 3.2), the rigid piezoviscous line contact solved
here by quadrature (Martin's isoviscous film with Barus' reduced pressure), a second solve of the same
discrete problem from another start."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from coupling import film_points as fp
from coupling.film_points import ehl as E
from lubrication.ehl import solve_ehl
from lubrication.errors import ConvergenceError, InputError


def test_reduced_radii_are_the_models_geometry_and_match_the_notes():
    """R_x of the cone and cup kinds is tapered_geometry().reduced_radius (the model's own); paper A's
    notes (3.2) give 9.41 / 11.93 mm, rounded: within 0.3 % (measured 0.16 % / 0.20 %)."""
    from coupling.parameters.wu2018 import tapered_geometry

    g = tapered_geometry()
    for race, notes in (("cone", 9.41e-3), ("cup", 11.93e-3)):
        params = fp.KINDS[f"ehl_roller_{race}"].default_params()
        assert params["radius_x"] == g.reduced_radius(race)
        assert params["radius_x"] == pytest.approx(notes, rel=3e-3)
    with pytest.raises(InputError, match="race"):
        fp.roller_race_radius("flange")


def _rigid_barus_film(w, u, R, eta0, alpha):
    """Central film [m] of a rigid cylinder (radius R) on a plane at line load w [N/m], entrainment speed
    u [m/s], Barus oil, Reynolds outlet: the reduced pressure q = (1 - exp(-alpha p))/alpha obeys the
    isoviscous equation, so with h = h0 (1 + t^2), x = sqrt(2 R h0) t (Martin 1916)::

        q(t) = 12 eta0 u sqrt(2 R h0)/h0^2  int_{-inf}^t (s^2 - t_c^2)/(1 + s^2)^3 ds,   q(t_c) = 0
        w = sqrt(2 R h0) int p dt,   p = -ln(1 - alpha q)/alpha

    (t_c = 0.4751; isoviscous limit w = 2.45 eta0 u R/h0 ... Martin's 4.9 eta0 U R/h0 with U = 2u)."""
    f = lambda s, tc: (s * s - tc * tc) / (1 + s * s) ** 3
    tc = brentq(lambda tc: quad(f, -np.inf, tc, args=(tc,))[0], 0.3, 0.6)

    def load(h0):
        scale = 12 * eta0 * u * math.sqrt(2 * R * h0) / h0**2
        q = lambda t: scale * quad(f, -np.inf, t, args=(tc,))[0]
        if alpha * q(-tc) >= 1.0:  # q is largest where q' = 0, at t = -t_c: beyond Barus' pole
            return math.inf
        p = lambda t: -math.log1p(-alpha * q(t)) / alpha
        return math.sqrt(2 * R * h0) * quad(p, -60.0, tc, limit=200)[0]

    return brentq(lambda h0: load(h0) - w, 1e-6, 1e-3, rtol=1e-10)


@pytest.mark.parametrize("race", ["cone", "cup"])
def test_light_load_film_against_the_rigid_piezoviscous_solution(race):
    """Centrifugal-only rollers (notes 3.2: 2.1 kN/m at 2 krpm) are hydrodynamic: at 0.7 kN/m, 8 m/s
    (M = 0.012) the kind's film on its film-scaled domain (smoke, 129 nodes) against the rigid Barus
    solution above: measured -2.8 % (cone and cup, also at 2.1 kN/m, 9.2 m/s: the inlet at -8 sqrt(2 R h);
    on 257 nodes -2.2 % against -16 sqrt(2 R h)), within 4 %.
    The fixed Hertz domain [-20, 3] b gave 0.085 of it (measured 1 kN/m, 8 m/s: 3.8 against 45 um).
    Moes' formula is not the reference here: its rigid-isoviscous asymptote 3/M is 22 % above Martin's
    2.45/M."""
    params = dict(fp.KINDS[f"ehl_roller_{race}"].default_params(), resolution="smoke")
    out = fp.evaluate_ehl_line(params, {"Line load [N/m]": 700.0, "Entrainment speed [m/s]": 8.0,
                                        "Slide-to-roll ratio [-]": 1e-3})
    ref = _rigid_barus_film(700.0, 8.0, params["radius_x"], params["eta0"], params["alpha"])
    assert out["Central film thickness [m]"] == pytest.approx(ref, rel=0.04)
    assert out["Central deflection [m]"] > 0


def test_high_speed_heavy_load_converges_and_is_unique():
    """Where the Newton iteration's own start fails (issue 22, 2): 100 kN/m, 25 m/s (M = 0.97, L = 73;
    smoke, 129 nodes) -- solve_ehl from its start raises ConvergenceError (a clear error, no answer);
    the kind's fallbacks (continuation, then other Newton strategies on the same discrete problem)
    converge, and a solve of the same problem started from the converged 28 m/s state reaches the same
    film to 1e-6 (a second solution would show here: the Newtonian oil had two)."""
    params = dict(fp.ehl_roller_cone_default_params(), resolution="smoke")
    c, g, o = E._ehl_setup(params, 1e5, 25.0)
    with pytest.raises(ConvergenceError):
        solve_ehl(c, g, o)
    E._EHL_CACHE.clear()
    sol = fp.ehl_load_response(params, 1e5, 25.0)["solution"]
    other = solve_ehl(dataclasses.replace(c, mean_speed=28.0), E._ehl_setup(params, 1e5, 28.0)[1], o)
    again = solve_ehl(c, g, dataclasses.replace(o, max_step=1.0, max_iter=150), initial=other)
    assert again.central_film_thickness == pytest.approx(sol.central_film_thickness, rel=1e-6)
    assert again.minimum_film_thickness == pytest.approx(sol.minimum_film_thickness, rel=1e-6)


def test_traction_axis_reaches_the_steady_slips_and_is_odd():
    """The SRR axis starts at 1e-5 (paper A's steady slips 0.005-0.02 % lie on it); traction is odd in
    the SRR and at the heaviest load limited already at 1e-5 (limiting shear: mu(1e-5) is more than half
    of mu(1e-3), where a linear extension from 1e-3 would give 1 %)."""
    axis = fp.EHL_ROLLER_LINE_AXES[2]
    assert axis.scale == "log" and axis.lo == 1e-5 and axis.hi == 0.1
    params = dict(fp.ehl_roller_cone_default_params(), resolution="smoke")
    pt = {"Line load [N/m]": 2e5, "Entrainment speed [m/s]": 11.0}
    mu = {s: fp.evaluate_ehl_line(params, dict(pt, **{"Slide-to-roll ratio [-]": s}))["Traction coefficient [-]"]
          for s in (1e-5, -1e-5, 1e-3)}
    assert mu[-1e-5] == -mu[1e-5]
    assert 0.5 * mu[1e-3] < mu[1e-5] < mu[1e-3]
