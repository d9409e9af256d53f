"""Kind ehl_ball_ball (two 6206 balls of paper B through an EHL film) against independent values, smoke grid.

At 5 N, u_e = 2.5 m/s, v = 1e-3 m/s (Moes M ~ 60, L ~ 16; the squeeze a perturbation) the film is the
steady EHL point contact: central film against Hamrock & Dowson's formula (Barus, k = 1), the lubricated
contact's stiffness against Hertz 1.5 Q/delta, and approach + central film against the Hertz approach.
Measured (33 x 33): h_c 0.3018 um (HD 0.3036 um, -0.6 %), K 9.50e6 N/m (Hertz 9.70e6, -2.0 %),
-h00 + h_c 0.786 um (Hertz 0.773 um, +1.7 %), 11 s; at 1 N, 1 m/s: h_c +4.5 %, K +1.7 %.
"""
import math

import pytest

from lubedyn.film_points import KINDS
from lubedyn.lubrication.laws import contact as hertz


def test_ehl_ball_ball_light_load_is_hamrock_dowson_and_hertz():
    kind = KINDS["ehl_ball_ball"]
    p = kind.default_params()
    p["resolution"] = "smoke"
    Q, v, ue = 5.0, 1e-3, 2.5
    out = kind.evaluate(p, {"Load [N]": Q, "Approach speed [m/s]": v, "Entrainment speed [m/s]": ue})
    assert set(kind.outputs) <= set(out)
    R = p["radius"] / 2
    Ep = 2 * p["e_star"]
    U, G, W = p["eta0"] * ue / (Ep * R), p["alpha"] * Ep, Q / (Ep * R * R)
    h_hd = 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1 - 0.61 * math.exp(-0.73)) * R
    hp = hertz.point_contact(Q, R, R, p["e_star"])
    assert out["Central film thickness [m]"] == pytest.approx(h_hd, rel=0.03)
    assert out["Film stiffness [N/m]"] == pytest.approx(1.5 * Q / hp.approach, rel=0.03)
    assert out["Approach [m]"] + out["Central film thickness [m]"] == pytest.approx(hp.approach, rel=0.03)
    assert out["Film damping [N s/m]"] > 0
