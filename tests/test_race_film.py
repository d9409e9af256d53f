"""Closed-form EHL films on the ball-race contacts of the cage-less bearing
(``films.race = "closed_form"``).

(1) The film thickness is Hamrock-Dowson's, recomputed here through an
independent path (lubedyn.lubrication.laws.contact ellipse, lubedyn.lubrication.laws.film).
(2) A film of constant thickness on every contact is equivalent, for the
loads, to a negative clearance: the balls are free radially, so only the sum
of the inner and outer approaches matters and a film h_i + h_o acts as a
diametral clearance of -2 (h_i + h_o).  The quasi-static loads of the two
models agree.
"""
from __future__ import annotations

import numpy as np
import pytest

from lubedyn.dynamics.cageless import D_QI, D_QO, forces
from lubedyn.lubrication.laws import contact as hertz
from lubedyn.lubrication.laws.film import hamrock_dowson_central
from lubedyn.papers.zhang2024.parameters import cageless_bearing as paper_b  # noqa: E402


def test_film_thickness_is_hamrock_dowson():
    m = paper_b(films=dict(race="closed_form"), operating=dict(scenario="steady"))
    D, dm = m.bearing.ball_diameter, m.bearing.pitch_diameter
    ue = 0.25 * dm * (1 - (D / dm) ** 2) * m.omega_inner  # epicyclic entrainment speed, 11.53 m/s
    got = m.race_film_thickness(ue)
    e_star, Q = m.e_star_race, 4.37 * m.operating.radial_load / m.n_balls
    for h, race, groove in zip(got, ("inner", "outer"), (m.bearing.inner_groove_radius, m.bearing.outer_groove_radius)):
        rx = D / 2 * (1 - D / dm if race == "inner" else 1 + D / dm)
        ry = groove * D / (2 * groove - D)
        ell = hertz.point_contact(Q, rx, ry, e_star)
        k = max(ell.a, ell.b) / min(ell.a, ell.b)
        U, G, W = m.films.viscosity * ue / (2 * e_star * rx), m.films.pressure_viscosity * 2 * e_star, Q / (2 * e_star * rx**2)
        assert h == pytest.approx(hamrock_dowson_central(U, G, W, k) * rx, rel=1e-9)
    assert 0.5e-6 < got[0] < got[1] < 2e-6  # 1.07 um inner, 1.30 um outer


def test_a_film_acts_as_a_negative_clearance_on_the_loads():
    kw = dict(operating=dict(scenario="steady"), slots=dict(azimuths=()), model=dict(ball_ball=False))
    wet = paper_b(films=dict(race="closed_form"), **kw)
    D, dm = wet.bearing.ball_diameter, wet.bearing.pitch_diameter
    ue = 0.25 * dm * (1 - (D / dm) ** 2) * wet.omega_inner
    h_total = sum(wet.race_film_thickness(ue))
    dry = paper_b(films=dict(race="none"), bearing=dict(diametral_clearance=-2 * h_total), **kw)
    loads = []
    for model in (wet, dry):
        diag, _, _ = forces(0.0, model.initial_state(), model.args())
        loads.append((diag[:, D_QI], diag[:, D_QO]))
    (qi_w, qo_w), (qi_d, qo_d) = loads
    assert qi_w.max() == pytest.approx(qi_d.max(), rel=2e-3)
    assert np.allclose(qo_w, qo_d, rtol=0, atol=2e-3 * qo_d.max())
    # and the film does change the loads: the preload spreads them over more balls
    plain = paper_b(films=dict(race="none"), **kw)
    diag, _, _ = forces(0.0, plain.initial_state(), plain.args())
    assert (qi_w > 1.0).sum() > (diag[:, D_QI] > 1.0).sum() or qi_w.max() < 0.99 * diag[:, D_QI].max()
