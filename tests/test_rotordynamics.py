"""Journal-bearing K and C over speed (lubedyn.bearing_coefficients) and the bridge to ROSS (lubedyn.to_ross).

- a short bearing (L/D = 1/20, half-Sommerfeld) under a fixed load at two speeds against Ocvirk's
  short-bearing theory: the equilibrium eccentricity and attitude (closed_form.short_journal_load solved
  for the load by brentq) and the eight coefficients of Friswell et al. (2010, eqs. 5.77-5.78); with the
  load along -y the solver's (x, y) is their load frame (u, v);
- the bundled journal_finite (L/D = 1, Reynolds cavitation) under the load of Raimondi and Boyd's
  S = 0.121 lands at their eccentricity ratio 0.6;
- with the centre held fixed, K grows like the speed and C does not (the isoviscous, incompressible film
  is linear in the surface speed);
- a film the mesh does not resolve near the wall is reported (the film's own check), naming the speed;
- bad input: one line naming the value;
- with ROSS installed (the optional extra ``ross``; not in ``test``, so this part skips in CI): a rotor
  with the bridge's bearing elements and the same rotor with ``ross.BearingElement`` typed from the arrays
  have equal natural frequencies, log decrements and critical speeds; and the frame is ROSS's: the rotor's
  half-speed whirl modes (oil whirl of a lightly loaded plain journal, Newkirk and Taylor 1925) whirl
  forward, as they must (the transposed matrices, a rotation the other way, make them backward).
"""
from __future__ import annotations

import sys

import numpy as np
import pytest
from scipy.optimize import brentq

import lubedyn
from lubedyn.lubrication import Cavitation, Film, JournalBearing, Lubricant
from lubedyn.lubrication import closed_form as cf
from lubedyn.lubrication import mesh as meshes
from lubedyn.lubrication.errors import ConvergenceError, InputError

R, C, ETA = 0.05, 50e-6, 0.02  # radius, clearance [m], viscosity [Pa s]


def short_film(L_over_D=0.05, n=256, nz=4):
    """A centred short journal, P2 on n x nz quads, half-Sommerfeld, p = 0 at both ends (as
    tests/test_film_coefficients.py)."""
    L = L_over_D * 2.0 * R
    m = meshes.rectangle(np.linspace(0.0, 2.0 * np.pi * R, n + 1), np.linspace(0.0, L, nz + 1), cell="quad",
                         periodic_x=True)
    return L, Film(m, JournalBearing(R, C), Lubricant.newtonian(ETA), dirichlet={"bottom": 0.0, "top": 0.0},
                   element="P2", cavitation=Cavitation("half_sommerfeld", 0.0))


def test_short_bearing_under_load_against_ocvirk():
    """L/D = 1/20, W = Ocvirk's load at eps = 0.6 and U = 10 m/s, held at omega = 200 and 66.7 rad/s (the
    second lands at eps = 0.758).  Measured against the short-bearing theory: eccentricity ratio +8.1e-4
    and +1.1e-3, attitude +0.03 and +0.04 deg, K and C entries within 3.2e-3 of their matrix's largest
    closed-form entry (0.0123 on 128 elements: the half-Sommerfeld rupture line in general position costs
    O(h), tests/test_film_coefficients.py).  Tolerances: the theory's neglected (L/D)^2 term, measured
    there up to 6.9e-2 of the matrix scale at L/D = 1/10 and four times smaller at 1/20, bounds the
    coefficients by 0.02 and, at L/D = 1/10, moved eps by 3.2e-3 here (so 1e-3 expected at 1/20): asserted
    |d eps| < 2e-3, |d attitude| < 0.1 deg, coefficients 0.01 of the scale.  The film carries the load to
    the requested 1e-8."""
    L, film = short_film()
    U0 = 10.0
    W = cf.short_journal_load(R, C, L, 0.6, ETA, U0)[0]
    speeds = np.array([U0, U0 / 3.0]) / R
    coef = lubedyn.bearing_coefficients(film, speeds, load=W)
    assert coef.K.shape == (2, 2, 2) and coef.C.shape == (2, 2, 2)
    assert np.all(np.abs(coef.force - [0.0, W]) <= 1e-8 * W)            # the film carries the load (-y)
    assert coef.warnings == ()                                         # resolved, no solver warning
    for k, w in enumerate(speeds):
        eps = brentq(lambda e: cf.short_journal_load(R, C, L, e, ETA, w * R)[0] - W, 1e-6, 1.0 - 1e-9, xtol=1e-14)
        attitude = np.degrees(cf.short_journal_load(R, C, L, eps, ETA, w * R)[1])
        K_ref, C_ref = cf.short_journal_coefficients(R, C, L, eps, ETA, w * R)   # (u, v) = (x, y) here
        assert abs(coef["Eccentricity ratio [-]"][k] - eps) < 2e-3
        assert abs(coef["Attitude angle [deg]"][k] - attitude) < 0.1
        assert np.max(np.abs(coef.K[k] - K_ref)) < 1e-2 * np.max(np.abs(K_ref))
        assert np.max(np.abs(coef.C[k] - C_ref)) < 1e-2 * np.max(np.abs(C_ref))
        assert coef["Stiffness K[y,x] [N/m]"][k] == coef.K[k, 1, 0] and coef["Damping C[x,y] [N s/m]"][k] == coef.C[k, 0, 1]


def test_journal_finite_under_raimondi_boyd_load():
    """Raimondi and Boyd (1958), L/D = 1, eps = 0.6: S = (R/c)^2 eta N / P = 0.121, attitude 50.58 deg.  The
    bundled case's bearing (smoke mesh) under the load of that S at 3000 rpm, W = (R/c)^2 eta N / S * 2 R L
    = 5165 N, measured: eps = 0.6009, attitude 51.95 deg (tests/test_cases.py: S within 0.3 % of theirs and
    51.98 deg converged; their table is read to about 1.4 deg).  Asserted |eps - 0.6| < 0.01 and the
    attitude within 2 deg, as tests/test_cases.py."""
    r, c, length, eta, n_rev = 0.025, 50e-6, 0.05, 0.02, 50.0
    W = (r / c) ** 2 * eta * n_rev / 0.121 * 2.0 * r * length
    coef = lubedyn.bearing_coefficients("journal_finite", ["3000 rpm"], load=f"{W} N", smoke=True)
    assert coef.speed[0] == pytest.approx(100.0 * np.pi, rel=1e-12)
    assert abs(coef["Eccentricity ratio [-]"][0] - 0.6) < 0.01
    assert abs(coef["Attitude angle [deg]"][0] - 50.58) < 2.0
    assert coef.iterations[0] > 1


def test_fixed_centre_scales_with_speed():
    """Centre held where the case puts it (eps = 0.6 along +x): the isoviscous incompressible film is
    linear in the surface speed with the same cavitated zone, so K(2 omega) = 2 K(omega) and C is the same
    (measured to 1e-9; a Newton solve to rtol 1e-10 each); the journal does not move."""
    coef = lubedyn.bearing_coefficients("journal_finite", [100.0, 200.0], smoke=True)
    assert np.allclose(coef.K[1], 2.0 * coef.K[0], rtol=1e-8, atol=0.0)
    assert np.allclose(coef.C[1], coef.C[0], rtol=1e-8, atol=0.0)
    assert np.all(coef.iterations == 1) and coef.load is None
    assert np.allclose(coef.eccentricity, [[0.6 * 50e-6, 0.0]] * 2, rtol=1e-12)


@pytest.mark.parametrize("kwargs, match", [
    (dict(source="inclined_slider", speeds=[100.0]), "gap.type = 'journal'"),
    (dict(source="journal_finite", speeds=[-1.0]), r"speeds\[0\] = -1.0"),
    (dict(source="journal_finite", speeds=["3000 mm"]), r"speeds\[0\] = '3000 mm' has units of length"),
    (dict(source="journal_finite", speeds=[]), "at least one"),
    (dict(source="journal_finite", speeds=[100.0], load="5 m"), "has units of length, expected force"),
    (dict(source="journal_finite", speeds=[100.0], load=(1.0, 2.0, 3.0)), "pair"),
    (dict(source="journal_finite", speeds=[100.0], load=-5.0), "> 0 N"),
])
def test_bad_input_one_line(kwargs, match):
    with pytest.raises(InputError, match=match) as info:
        lubedyn.bearing_coefficients(smoke=True, **kwargs)
    assert "\n" not in str(info.value)


def test_moving_bearing_or_centre_refused():
    """The coefficients are about a static journal in a fixed bearing: a film whose bearing surface or
    centre moves is refused in one line naming what moves."""
    _, film = short_film(n=16, nz=2)
    for changes, name in ((dict(velocity_lower=(1.0, 0.0)), "velocity_lower"), (dict(mode_velocities={"x": 1e-3}), "mode_velocities")):
        with pytest.raises(InputError, match=name) as info:
            lubedyn.bearing_coefficients(film.with_(**changes), np.array([100.0]))
        assert "\n" not in str(info.value)


def test_unresolved_film_is_reported():
    """5165 N at 100 rpm on the smoke mesh (32 x 8 P2): the journal sits at eps = 0.975 and the minimum-gap
    zone has 1.5 elements across (the film's own check wants 2.2 for P2): one warning naming the speed;
    at 3000 rpm (eps 0.60) none."""
    coef = lubedyn.bearing_coefficients("journal_finite", ["3000 rpm", "100 rpm"], load=5165.0, smoke=True)
    assert coef["Eccentricity ratio [-]"][1] > 0.97
    assert len(coef.warnings) == 1 and coef.warnings[0].startswith("at 10.472 rad/s: Minimum-gap zone")


def test_load_the_film_cannot_carry():
    """1 MN on the smoke journal at 10 rad/s: the Newton steps creep towards the wall (each at most
    halfway) and stop with one line naming the load, the speed and the eccentricity."""
    with pytest.raises(ConvergenceError, match=r"no equilibrium .* 10 rad/s .*eccentricity ratio 0\.9") as info:
        lubedyn.bearing_coefficients("journal_finite", [10.0], load=1e6, smoke=True, max_iter=8)
    assert "\n" not in str(info.value)


def test_to_ross_without_ross_names_the_extra(monkeypatch):
    coef = lubedyn.bearing_coefficients("journal_finite", [100.0], smoke=True)
    monkeypatch.setitem(sys.modules, "ross", None)                        # import ross -> ImportError
    with pytest.raises(ImportError, match=r"pip install 'lubedyn\[ross\]'") as info:
        lubedyn.to_ross(coef, n=0)
    assert "\n" not in str(info.value)
    with pytest.raises(InputError, match="kxx come from the coefficients"):
        coef.to_ross(0, kxx=1.0)


# ---------------------------------------------------------------------------- with ROSS


@pytest.fixture(scope="module")
def ross():
    """ROSS as to_ross imports it (without ccp's REFPROP notice); skip when it is not installed or does not
    import (ROSS 2.3 under plotly >= 7)."""
    from lubedyn.rotordynamics import _import_ross

    try:
        return _import_ross()
    except ImportError as exc:
        pytest.skip(str(exc))


@pytest.mark.slow
def test_ross_rotor_with_bridge_equals_rotor_typed_by_hand(ross):
    """Steel shaft 0.8 m x 50 mm in 4 elements, a 32.6 kg disk in the middle, the bundled journal (smoke)
    at both ends carrying half the rotor's weight (220 N each) at 1000 ... 6000 rpm.  The same rotor with
    ``ross.BearingElement(kxx=K[:, 0, 0], kxy=K[:, 0, 1], ..., frequency=speeds)`` typed here: the
    bearings' K and C at and between the speeds, the natural frequencies and log decrements at a given
    and an interpolated speed, and the critical speeds are equal (to round-off).  ROSS does not interpolate
    exactly: from four speeds on it fits scipy's UnivariateSpline with its default smoothing, which misses
    the given values by up to 2.7e-6 of the matrix scale (measured); asserted 1e-5.

    The frame: a lightly loaded plain journal (eps 0.02-0.14 here) whirls at half the running speed, in
    the direction of rotation (oil whirl).  The rotor's two lowest modes at 3000 rpm sit at 0.50 omega
    (measured 157.1 and 157.3 rad/s at 314.2) and ROSS calls them forward; the transposed matrices (a
    journal turning the other way) make them backward."""
    import dataclasses

    speeds = np.array([1000.0, 2000.0, 3000.0, 4000.0, 6000.0]) * np.pi / 30.0
    coef = lubedyn.bearing_coefficients("journal_finite", speeds, smoke=True, load=220.0)
    steel = ross.Material(name="steel_lubedyn_test", rho=7810.0, E=211e9, G_s=81.2e9)

    def rotor(bearings):
        shaft = [ross.ShaftElement(0.2, 0.0, 0.05, material=steel) for _ in range(4)]
        disk = ross.DiskElement.from_geometry(n=2, material=steel, width=0.07, i_d=0.05, o_d=0.28)
        return ross.Rotor(shaft, [disk], bearings)

    def typed(n, K, Cm):
        return ross.BearingElement(n=n, kxx=K[:, 0, 0], kxy=K[:, 0, 1], kyx=K[:, 1, 0], kyy=K[:, 1, 1],
                                   cxx=Cm[:, 0, 0], cxy=Cm[:, 0, 1], cyx=Cm[:, 1, 0], cyy=Cm[:, 1, 1], frequency=speeds)

    bridge = [lubedyn.to_ross(coef, n=0), coef.to_ross(4)]
    by_hand = [typed(0, coef.K, coef.C), typed(4, coef.K, coef.C)]
    for w in [*speeds, 250.0]:
        assert np.array_equal(bridge[0].K(w), by_hand[0].K(w)) and np.array_equal(bridge[1].C(w), by_hand[1].C(w))
    for k, w in enumerate(speeds):  # ROSS's smoothing spline (UnivariateSpline, s = 5) passes near the points
        assert np.max(np.abs(bridge[0].K(w)[:2, :2] - coef.K[k])) < 1e-5 * np.max(np.abs(coef.K[k]))
        assert np.max(np.abs(bridge[0].C(w)[:2, :2] - coef.C[k])) < 1e-5 * np.max(np.abs(coef.C[k]))
    a, b = rotor(bridge), rotor(by_hand)
    assert a.m == pytest.approx(44.86, rel=1e-3)                                # 12.27 kg shaft + 32.59 kg disk
    for w in (speeds[2], 250.0):
        ma, mb = a.run_modal(w, num_modes=8), b.run_modal(w, num_modes=8)
        assert np.allclose(ma.wn, mb.wn, rtol=1e-12) and np.allclose(ma.wd, mb.wd, rtol=1e-12)
        assert np.allclose(ma.log_dec, mb.log_dec, rtol=1e-10)
    ca, cb = a.run_critical_speed(num_modes=8), b.run_critical_speed(num_modes=8)
    assert np.allclose(ca.wn(), cb.wn(), rtol=1e-12) and np.allclose(ca.wd(), cb.wd(), rtol=1e-12)

    modal = a.run_modal(speeds[2], num_modes=8)
    assert np.allclose(modal.wd[:2], speeds[2] / 2.0, rtol=0.01)
    assert list(modal.whirl_direction()[:2]) == ["Forward", "Forward"]
    flipped = dataclasses.replace(coef, K=coef.K.transpose(0, 2, 1), C=coef.C.transpose(0, 2, 1))
    modal = rotor([lubedyn.to_ross(flipped, n=0), lubedyn.to_ross(flipped, n=4)]).run_modal(speeds[2], num_modes=8)
    assert list(modal.whirl_direction()[:2]) == ["Backward", "Backward"]
