"""Raceway traction "map" of the tapered bearing (a fidelity option): the
roller EHL maps (cases/maps/ehl_roller_cup.npz, ehl_roller_cone.npz) read by the compiled kernel at the
run's entrainment speed (lubedyn.dynamics.tapered.model.TaperedBearing.map_traction_tables,
lubedyn.dynamics.tapered.kernels.map_traction_coefficient).

Independent references: the maps' own Python reader (lubedyn.maps.FilmMap: a 3-D Hermite query and its
sheared coordinate, a different code path from the kernel's 2-D restriction), a direct EHL line-contact
solve (lubedyn.film_points.evaluate_ehl_line) at a point between the maps' nodes, and the maps' linear
low-slip branch."""
from __future__ import annotations

import numpy as np
import pytest

from lubedyn.scenes import tapered as ts
from lubedyn.config import CASES_DIR, load_case
from lubedyn.dynamics.tapered import kernels as K
from lubedyn.dynamics.tapered import layout as L
from lubedyn.lubrication.errors import InputError

CASE = CASES_DIR / "trb_fig5_traction_map.toml"
TRACTION = "Traction coefficient [-]"


@pytest.fixture(scope="module")
def model():
    return ts.build(load_case(CASE))


@pytest.fixture(scope="module")
def A(model):
    return model.args()


def test_kernel_reads_the_maps_own_interpolant(model, A):
    """At 300 random (line load, slide-to-roll) points inside the maps' axes, at the run's entrainment
    speed (11.03 m/s, between the speed nodes), the kernel's value equals the FilmMap's 3-D query to
    1e-12 relative (measured 1.2e-14): a tricubic Hermite restricted to a plane is the bicubic Hermite of
    the restricted node data, so any difference is a defect of the restriction, not an approximation."""
    ue = A.P[0].ue
    assert ue == pytest.approx(11.03, rel=1e-3)
    rng = np.random.default_rng(7)
    counter = np.zeros(1, dtype=np.int64)
    for race, fmap in enumerate(model.traction_maps):
        w_axis, _, s_axis = fmap.axes
        w = np.exp(rng.uniform(np.log(w_axis.lo), np.log(w_axis.hi), 300))
        s = np.exp(rng.uniform(np.log(s_axis.lo), np.log(s_axis.hi), 300))
        ref = fmap(TRACTION, w, ue, s)
        got = np.array([K.map_traction_coefficient(race, a, b, A.P[0], A.maps, counter) for a, b in zip(w, s)])
        assert np.all(ref > 0.0)
        np.testing.assert_allclose(got, ref, rtol=1e-12)
    assert counter[0] == 0


def test_linear_below_the_axis_and_held_above_it(model, A):
    """Below the slide-to-roll axis' first node (1e-5) the traction is linear in the slip through 0 (the
    maps' convention, the film's linear shear); above the last (0.1) it is held; a load beyond the axis
    is clamped and counted."""
    counter = np.zeros(1, dtype=np.int64)
    lo, hi = A.P[0].tmslo, A.P[0].tmshi
    assert (lo, hi) == (pytest.approx(1e-5), pytest.approx(0.1))
    for race in (0, 1):
        w = 5e4
        at_lo = K.map_traction_coefficient(race, w, lo, A.P[0], A.maps, counter)
        for s in (1e-9, 1e-7, 3e-6):
            assert K.map_traction_coefficient(race, w, s, A.P[0], A.maps, counter) == pytest.approx(at_lo * s / lo, rel=1e-12)
        assert K.map_traction_coefficient(race, w, 0.5, A.P[0], A.maps, counter) == K.map_traction_coefficient(race, w, hi, A.P[0], A.maps,
                                                                                                  counter)
        assert counter[0] == 0
        top = model.traction_maps[race].axes[0].hi
        assert K.map_traction_coefficient(race, 2 * top, 1e-3, A.P[0], A.maps, counter) == pytest.approx(
            K.map_traction_coefficient(race, top, 1e-3, A.P[0], A.maps, counter), rel=1e-12)
        assert counter[0] >= 1
        counter[:] = 0


@pytest.mark.parametrize("race, load", [(0, 1.0e5), (1, 1.5e5)])
def test_kernel_traction_against_a_direct_ehl_solve(model, A, race, load):
    """The kernel's traction coefficient at the run's entrainment speed (off the maps' speed nodes) and a
    slip between the SRR nodes, against the EHL line contact solved directly with the map's own
    parameters: within 3 %, the maps' accuracy target (their measured misses, up to 8.5 %, lie in the
    28-58 kN/m transition band, cases/maps/README.md; these loads are above it)."""
    from lubedyn.film_points import evaluate_ehl_line

    fmap = model.traction_maps[race]
    ue, s = float(A.P[0].ue), 3.3e-3
    direct = evaluate_ehl_line(fmap.provenance["params"], {"Line load [N/m]": load, "Entrainment speed [m/s]": ue,
                                                          "Slide-to-roll ratio [-]": s})[TRACTION]
    got = K.map_traction_coefficient(race, load, s, A.P[0], A.maps, np.zeros(1, dtype=np.int64))
    assert got == pytest.approx(direct, rel=0.03)


def test_stable_step_follows_the_maps_low_slip_slope(model):
    """RK4's step estimate of the "map" traction: the larger decay rate of a roller's rolling speed and
    spin (:func:`lubedyn.dynamics.tapered.model.sliding_decay_rate`) with k = (mu/s) Q/u_e from the maps' own
    reader at the axis' first slip node and the start's largest cup load; checked against the right-hand
    side's own spectrum at the start (finite-difference Jacobian, an independent estimate): measured 6.89
    against 7.00 us, asserted within 5 %.  The closed form's earlier trace, (k_cup + k_cone)(1/m +
    rho_m^2/I_x), was 1.5 times the eigenvalue (4.6 us).  The maps' slope lies below the strip law's
    elastic slope at this point (the "limited" step is shorter)."""
    from lubedyn.dynamics.tapered.model import sliding_decay_rate

    qs = model.quasi_static()
    g = model.geometry
    load = float(np.max(qs.cup_loads))
    ue = float(model.args().P[0].ue)
    k = [float(fmap(TRACTION, load / g.effective_length, ue, 1e-5)) / 1e-5 * load / ue for fmap in model.traction_maps]
    m, ix, _, _ = g.roller_mass_properties()
    assert model.traction_rate(qs) == pytest.approx(sliding_decay_rate(*k, m, ix, g.mean_roller_radius), rel=1e-10)
    assert sliding_decay_rate(*k, m, ix, g.mean_roller_radius) < sum(k) * (1 / m + g.mean_roller_radius**2 / ix)
    spectral = model.spectral_step(model.start_state(qs), model.args(qs))
    assert model.stable_step(qs) == pytest.approx(spectral, rel=0.05)
    limited = ts.build(load_case(CASE, overrides=["model.traction=limited"]))
    assert model.stable_step(qs) > 1.5 * limited.stable_step(qs)


def test_sliding_decay_rate_is_the_eigenvalue_of_the_roller_sliding_system():
    """The closed form against numpy's eigenvalues of the 2 x 2 matrix, for equal and unequal slopes and a
    solid roller (I_x = m rho^2 / 2: 4 k/m for equal slopes, 2/3 of the trace)."""
    from lubedyn.dynamics.tapered.model import sliding_decay_rate

    m, rho = 0.05, 0.01
    for k1, k2, ix in ((300.0, 300.0, 0.5 * m * rho**2), (100.0, 900.0, 0.4 * m * rho**2), (1e3, 1.0, 1e-6)):
        A = np.array([[(k1 + k2) / m, (k1 - k2) * rho / m], [(k1 - k2) * rho / ix, (k1 + k2) * rho**2 / ix]])
        assert sliding_decay_rate(k1, k2, m, ix, rho) == pytest.approx(max(np.linalg.eigvals(A).real), rel=1e-12)
    assert sliding_decay_rate(300.0, 300.0, m, 0.5 * m * rho**2, rho) == pytest.approx(4 * 300.0 / m, rel=1e-12)


def test_entrainment_speed_outside_the_maps_is_one_line():
    """6,500 rpm gives u_e = 29.9 m/s, above the maps' 28 m/s: one line naming operating.speed, the speed and
    what is allowed."""
    with pytest.raises(InputError) as err:
        ts.build(load_case(CASE, overrides=["operating.speed=6500 rpm"])).args()
    msg = str(err.value)
    assert "\n" not in msg and "operating.speed" in msg and "7-28 m/s" in msg and "'limited'" in msg
