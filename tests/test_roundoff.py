"""Convergence decisions (EHL and film Newton) are robust to round-off: the same contact converges to the same
state whatever the last bits of the residual are.

Why: on one machine (another BLAS/CPU) paper A's roller with Eyring flow (15 kN, 8.84 m/s)
failed with "did not converge in 80 Newton iterations ... last |dp|/p_Hertz = 1.26e-15, load
error 0": the iteration was at the round-off floor, where the residual norm (active set) or the
merit (Fischer-Burmeister) is noise, so the backtracking line search halved omega at random and
the old test, which asked for an undamped step (omega == 1), was never met.  The convergence
test now looks at the full Newton step before any line search (and, for the active set, lets a
cavitated node whose multiplier is negative only within rtol stay cavitated).

How: the residual of every assembly gets a seeded perturbation of ``ulps`` units of round-off
of the size of its own terms (tests/roundoff.py), the round-off a different BLAS or CPU could
make.  Measured before the fix: 1 ulp made 3 of 6 roller
solves run out of iterations (|dp|/p_H 1e-15 .. 1e-14, omega 0.06 .. 0.5 at every step);
after it: every solve converges at 1 and 100 ulps, the solutions agreeing to 3e-12 at 100
ulps (the tests' tolerance is 1e-9: a margin of 300 on the result and of 100 on the noise).
"""
import numpy as np
import pytest

from lubedyn.lubrication.ehl import EHLContact, EHLGrid, solve_ehl

from roundoff import perturb_residuals
from test_ehl import _complementarity
from test_ehl_eyring import _roller, _roller_solves


@pytest.fixture
def roundoff(monkeypatch):
    """``roundoff(ulps, seed)``: perturb every residual of this test by ``ulps`` round-off units."""
    return lambda ulps, seed: perturb_residuals(monkeypatch.setattr, ulps, seed)


@pytest.mark.parametrize("ulps, seed", [(1, 1), (1, 2), (1, 3), (100, 1)])
def test_eyring_roller_converges_whatever_the_roundoff(roundoff, ulps, seed):
    """The failing case of the fresh-clone run (15 kN, 8.84 m/s; four starts, active set on 129
    and 257 nodes) under perturbed round-off: every start converges, to one state (1e-9)."""
    roundoff(ulps, seed)
    sols = _roller_solves(_roller(eyring=True), 15e3, 8.84, [0.8, 1.06, 1.25])
    ref = sols[0]
    for s in sols[1:]:
        assert s.minimum_film_thickness == pytest.approx(ref.minimum_film_thickness, rel=1e-9)
    free_res, cav_min, pr, load_err = _complementarity(ref)
    assert free_res < 1e-7 and pr < 1e-7 and cav_min > -1e-7 and load_err < 1e-6


def test_roundoff_noise_changes_the_last_bits_only(roundoff):
    """The perturbation is what it claims: the 10 kN roller solved with and without it agrees to
    1e-11 (so the test above checks convergence decisions, not a different problem)."""
    params = _roller(eyring=True)
    clean = _roller_solves(params, 10e3, 8.84, [])[0]
    roundoff(100, 7)
    noisy = _roller_solves(params, 10e3, 8.84, [])[0]
    assert noisy.minimum_film_thickness == pytest.approx(clean.minimum_film_thickness, rel=1e-11)
    assert noisy.minimum_film_thickness != clean.minimum_film_thickness


@pytest.mark.parametrize("ulps, seed", [(1, 1), (100, 2)])
def test_point_contact_fischer_burmeister_converges_whatever_the_roundoff(roundoff, ulps, seed):
    """Fischer-Burmeister Newton (point contacts), M = 100, L = 10 on 65 x 65, under perturbed
    round-off: converges, within rtol of the unperturbed state (h_c to 1e-9)."""
    c = EHLContact.from_moes(100, 10)
    clean = solve_ehl(c, EHLGrid(nx=65))
    roundoff(ulps, seed)
    s = solve_ehl(c, EHLGrid(nx=65))
    assert s.central_film_thickness == pytest.approx(clean.central_film_thickness, rel=1e-9)
    assert s.minimum_film_thickness == pytest.approx(clean.minimum_film_thickness, rel=1e-9)


def test_film_newton_converges_at_its_roundoff_floor(roundoff):
    """The Reynolds film solver on Martin's rolling cylinder (Reynolds cavitation, P2, 800 graded
    elements, 40 plain Newton iterations).  Its residual floor is 1.05e-11 |R_0| on this machine
    (the sparse LU's backward error), 100 times below the residual test's 10 rtol; with residuals
    perturbed by 30 round-off units it is 1.5e-9 |R_0| and the residual-only test ran out of
    iterations (measured before the fix: ConvergenceError after 60 iterations with a Newton step of
    5e-12 |p|).  Now the full Newton step (2e-11 |p| at 30 units, 7e-11 at 100: below rtol 1e-10)
    ends it, at the unperturbed solution to 1e-9."""
    import numpy as np
    from lubedyn.lubrication import Cavitation, CylinderPlane, Film, Lubricant, SolverOptions
    from lubedyn.lubrication import mesh as meshes

    R_cyl, h0, eta, u = 10e-3, 1e-6, 0.05, 2.0
    b = np.sqrt(2.0 * R_cyl * h0)
    pts = meshes.graded(-30.0 * b, 3.0 * b, 800, 0.0, ratio=8.0)
    film = Film(meshes.interval(0, 0, 0, points=pts), CylinderPlane(R_cyl, h0), Lubricant.newtonian(eta),
                velocity_lower=(u,), velocity_upper=(u,), element="P2", cavitation=Cavitation("reynolds", 0.0),
                options=SolverOptions(warm_start_levels=0))
    clean = film.solve()
    roundoff(30, 5)
    noisy = film.solve()
    assert np.max(np.abs(noisy.pressure - clean.pressure)) < 1e-9 * np.max(clean.pressure)
    np.testing.assert_array_equal(noisy.full_film, clean.full_film)


def test_fine_linear_film_converges_at_its_roundoff_floor():
    """A 1-D inclined slider (K = 1) on 1e5 P1 cells (AMG-CG linear solves): linear, so the first
    Newton step is exact up to the linear solver's tolerance, but its residual floor (0.2 eps of its terms, measured) is 1.8e-7 of |R_0| and its
    Newton update 5e-10 |p| (cond ~ N^2): before the round-off-floor test it ran out of 60
    iterations.  Now it stops in 2 and matches the closed-form pressure to 1e-7 p_max (measured
    3.3e-10; 5.7e-7 on 1e3 cells, whose h^2 scaling would give 6e-11 here: the rest is round-off
    and the linear solver)."""
    import numpy as np
    from lubedyn.lubrication import Film, InclinedSlider, Lubricant
    from lubedyn.lubrication import mesh
    from lubedyn.lubrication.closed_form import inclined_slider_pressure

    L, eta, U = 0.01, 0.01, 1.0
    film = Film(mesh.interval(0, L, 100_000), InclinedSlider(2e-6, 1e-6, L), Lubricant.newtonian(eta),
                velocity_lower=(U,))
    s = film.solve()
    x = s.basis.doflocs[0]
    ref = inclined_slider_pressure(x, 2e-6, 1e-6, L, eta, U / 2)
    assert s.info["iterations"] <= 3
    assert np.max(np.abs(s.pressure - ref)) < 1e-7 * np.max(ref)
