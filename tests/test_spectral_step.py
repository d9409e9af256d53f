"""RK4's step from the right-hand side's own spectrum (lubedyn.dynamics.integrators.spectral_step), and the
tapered bearing's "auto" step that now takes it into account (the closed-form step alone was
not conservative under paper A's reading of phi; docs/paper_a.md).

References: the closed-form stability limits of RK4 on a linear oscillator and a linear decay
(lubedyn.dynamics.integrators.stability_limit, from the stability polynomial), and the integrator's own growth
guard on the run that failed (studies/trb_plastic_viscosity_paper_reading.toml, phi = 38.44)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from numba import njit

from lubedyn.dynamics.errors import IntegrationError
from lubedyn.dynamics.integrators import integrate, spectral_step, stability_limit


@njit(cache=True)
def _linear(t, y, args, dydt):
    """y' = A y with A = [[-c, -w^2], [1, 0]] on (v, x) plus a separate decay y2' = -d y2."""
    w, c, d = args
    dydt[0] = -c * y[0] - w * w * y[1]
    dydt[1] = y[0]
    dydt[2] = -d * y[2]


def test_oscillator_and_decay_against_the_stability_polynomial():
    """An undamped oscillator omega = 3e5 rad/s with a slower decay: 2 sqrt(2)/omega (the imaginary-axis
    limit); a decay of 1e6 1/s with a slower oscillator: 2.785/lambda (the real-axis limit); a growing
    mode only (negative damping, d < 0 on its own): no limit."""
    y0 = np.array([0.3, 1e-3, 1.0])
    h = spectral_step(_linear, y0, (3e5, 0.0, 1e4))
    assert h == pytest.approx(stability_limit("rk4", "imaginary") / 3e5, rel=1e-6)
    h = spectral_step(_linear, y0, (1e4, 0.0, 1e6))
    assert h == pytest.approx(stability_limit("rk4", "real") / 1e6, rel=1e-6)
    assert spectral_step(_linear, y0, (0.0, -1e3, -1e3)) == math.inf
    # an oscillator whose real part is a hair above 0 (a neutral mode seen through the differences) is
    # read on the imaginary axis: without that no step would be stable (the tilted cone's precession)
    h = spectral_step(_linear, y0, (3e5, -1e-3, 1e4))
    assert h == pytest.approx(stability_limit("rk4", "imaginary") / 3e5, rel=1e-6)


def test_paper_reading_auto_step_is_stable_where_the_closed_form_was_not():
    """Fig. 14's base (Fa 15 kN, 2,800 rpm) with phi read as a viscosity at 38.44 Pa s: the closed forms
    (contacts, traction) allow 18.8 us, the start's spectrum 8.25 us (a decay at 3.4e5 1/s that they do not
    model).  RK4 at the old "auto" step (0.8 x 18.8 us) stops within 10 ms (the growth guard, naming a
    stable step below 9 us, or the state turning non-finite first); at the new one (0.8 x 8.25 us) the same 10 ms complete with the guard's
    largest |h lambda| below the limit."""
    from lubedyn.scenes import tapered as ts
    from lubedyn.config import CASES_DIR, load_case
    from lubedyn.dynamics.tapered import kernels as K

    over = ["lubricant.reading=paper", "lubricant.yield_stress=351.8 Pa", "lubricant.consistency=38.44",
            "lubricant.exponent=0.7196", "lubricant.grease=custom"]
    m = ts.build(load_case(CASES_DIR / "trb_grease_fa15kN.toml", overrides=over))
    args = m.args()
    qs = m.quasi_static()
    y0 = m.start_state(qs)
    closed = m.stable_step(qs)
    spectral = m.spectral_step(y0, args)
    assert closed == pytest.approx(1.877e-5, rel=1e-3)
    assert spectral == pytest.approx(8.25e-6, rel=0.01)
    assert m.stable_step(qs, y0) == spectral
    t_out = np.linspace(0.0, 1e-2, 101)
    with pytest.raises(IntegrationError) as err:
        integrate(K.rhs, y0, t_out, args, method="rk4", dt=0.8 * closed)
    # the growth guard names a stable step, unless the blow-up turns the state non-finite within the 5
    # steps it waits (which of the two depends on round-off: both seen)
    msg = str(err.value)
    assert "a stable step is dt <= " in msg or "non-finite" in msg, msg
    if "a stable step is dt <= " in msg:
        assert float(msg.split("a stable step is dt <= ")[1].split(" ")[0]) < 9e-6
    res = integrate(K.rhs, y0, t_out, args, method="rk4", dt=0.8 * spectral)
    assert res.stats["Largest estimated h*|lambda| (RK4) [-]"] < stability_limit("rk4", "real")
