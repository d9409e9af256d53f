"""Graded line grids of the EHL solver (``EHLGrid(refine > 1)``): elastic matrix, assembly, nesting, and
what the grading buys and where it stops (the roller maps' knee, cases/maps/README.md).

Independent references: the Toeplitz/FFT kernel of a uniform grid (:class:`lubedyn.lubrication.elastic.ElasticKernel`),
the Hertz line contact's deflection (u + x^2/(2R) constant inside the contact, Johnson 1985, section 5.6),
scikit-fem's generic ``asm`` (:meth:`_Problem.assemble_skfem`), and the uniform solver on fine grids."""
import dataclasses

import numpy as np
import pytest

from lubedyn.lubrication.elastic import ElasticKernel, line_influence_matrix
from lubedyn.lubrication.ehl import EHLContact, EHLGrid, EHLOptions, solve_ehl
from lubedyn.lubrication.ehl.problem import _Problem
from lubedyn.lubrication.errors import InputError


def test_influence_matrix_on_uniform_nodes_is_the_toeplitz_kernel():
    x = np.linspace(-3e-4, 1e-4, 101)
    p = np.random.default_rng(0).random(101) * 1e8
    K = ElasticKernel((101,), (x[1] - x[0],), 1.1e11)
    ref = K.deflect(p)
    assert np.max(np.abs(line_influence_matrix(x, 1.1e11) @ p - ref)) <= 1e-12 * np.max(np.abs(ref))  # 1.1e-14


@pytest.mark.parametrize("nx", [257, 513])
def test_graded_deflection_of_the_hertz_pressure_is_a_parabola(nx):
    """Inside a Hertz line contact the deflection plus x^2/(2R) is constant; the spread over |x| < 0.9 b,
    relative to b^2/(2R).  Measured: graded (refine 4 on [-1.2, 1.2] b) 9.7e-5 (257) and 1.1e-4 (513) against
    uniform 2.8e-3 and 6.8e-4 on the same [-4, 2] b (the sqrt edge of the Hertz pressure limits the order)."""
    E, R, w = 1.1e11, 0.01, 1e5
    b = np.sqrt(4 * w * R / (np.pi * E))
    p0 = 2 * w / (np.pi * b)
    spread = {}
    for refine in (1.0, 4.0):
        x = EHLGrid(nx=nx, x_min=-4, x_max=2, refine=refine, refine_width=0.5).x_nodes() * b
        u = line_influence_matrix(x, E) @ (p0 * np.sqrt(np.clip(1 - (x / b) ** 2, 0, None)))
        f = u + x**2 / (2 * R)
        spread[refine] = np.ptp(f[np.abs(x) < 0.9 * b]) / (b**2 / (2 * R))
    assert spread[4.0] < 3e-4
    assert spread[4.0] < 0.3 * spread[1.0]


def test_graded_nodes_are_nested_smooth_and_finer_in_the_zone():
    g = EHLGrid(nx=257, x_min=-20, x_max=8, refine=6.0, refine_zone=(-3.0, 3.0), refine_width=0.5)
    x = g.x_nodes()
    assert x[0] == -20 and x[-1] == 8 and np.all(np.diff(x) > 0)
    assert np.array_equal(g.coarser().x_nodes(), x[::2])  # the nested level of solve_ehl's sequence
    d = np.diff(x)
    mid = 0.5 * (x[1:] + x[:-1])
    inside, outside = d[(mid > -1) & (mid < 1)], d[(mid < -6) | (mid > 6)]
    assert outside.min() / inside.max() == pytest.approx(6.0, rel=0.02)
    assert np.max(d[1:] / d[:-1]) < 1.25  # smooth grading (measured 1.21)
    assert np.array_equal(EHLGrid(nx=65).x_nodes(), np.linspace(-4.5, 1.5, 65))


def test_element_forms_match_scikit_fem_on_a_graded_grid():
    c = EHLContact.from_moes(20, 10, line=True)
    P = _Problem(c, EHLGrid(nx=129, refine=4.0, refine_width=0.5), EHLOptions())
    x = P.xs / P.bx
    p = P.ph * np.sqrt(np.clip(1 - x**2, 0, None)) * (1 + 0.3 * np.sin(5 * x))
    h00 = 0.5 * P.hscale
    R1, _, A1, D1, _ = P.assemble(p, h00)
    R2, _, A2, D2, _ = P.assemble_skfem(p, h00)
    assert np.max(np.abs(R1 - R2)) <= 1e-12 * np.max(np.abs(R2))
    assert abs(A1 - A2).max() <= 1e-12 * abs(A2).max()
    assert abs(D1 - D2).max() <= 1e-12 * abs(D2).max()
    assert P.uniform_weights() == pytest.approx(P.forms.vector([(np.ones((P.forms.E, 2)), P.forms.val)]), rel=1e-12)


def test_nearly_uniform_grading_reproduces_the_uniform_solution():
    c = EHLContact.from_moes(20, 10, line=True)
    a = solve_ehl(c, EHLGrid(nx=257))
    b = solve_ehl(c, EHLGrid(nx=257, refine=1.0001))
    assert b.central_film_thickness == pytest.approx(a.central_film_thickness, rel=1e-5)  # measured 4e-8
    assert b.minimum_film_thickness == pytest.approx(a.minimum_film_thickness, rel=1e-4)  # measured 6e-6


def test_graded_257_resolves_the_outlet_spike_like_uniform_1025():
    """Moes M = 20, L = 10 on [-4.5, 1.5] b.  The spike's discrete height is not grid-converged even on 2049
    uniform nodes (measured p_max/p_Hertz: 1.00, 1.52, 1.67, 2.96 on 257, 513, 1025, 2049), so the check is
    relative: refine 4 on [-1.2, 1.2] b (cells 0.013 b there) puts 257 nodes where uniform 1025 is
    (1.43 against 1.67 and 0.998 on uniform 257) at 0.07 s against 3.1 s.  h_c moves by 0.1 %: the inlet's
    cells are twice as long (measured h_c 3.3267 / 3.3271 / 3.3311 e-7 m graded 257 / uniform 257 / uniform
    2049) -- the grading is for what the spike carries, not for h_c."""
    c = EHLContact.from_moes(20, 10, line=True)
    g = solve_ehl(c, EHLGrid(nx=257, refine=4.0, refine_width=0.5))
    u = solve_ehl(c, EHLGrid(nx=257))
    ratio_g = np.max(g.pressure) / g.problem.ph
    ratio_u = np.max(u.pressure) / u.problem.ph
    assert ratio_u < 1.05 and 1.3 < ratio_g < 1.8
    assert g.central_film_thickness == pytest.approx(u.central_film_thickness, rel=3e-3)
    assert g.load == pytest.approx(c.load, rel=1e-9)


@pytest.mark.parametrize("kw, key", [(dict(refine=0.5), "refine"), (dict(refine=2.0, ny=33), "ny"),
                                     (dict(refine_zone=(1.0, -1.0)), "refine_zone"),
                                     (dict(refine_width=0.0), "refine_width")])
def test_bad_grading_is_one_clear_line(kw, key):
    with pytest.raises(InputError, match=key):
        EHLGrid(nx=129, **kw)


def test_graded_point_contact_is_refused():
    c = EHLContact.from_moes(20, 10)
    grid = dataclasses.replace(EHLGrid(nx=33), refine=1.0)
    object.__setattr__(grid, "refine", 2.0)  # past the dataclass check: the problem refuses too
    with pytest.raises(InputError, match="line contacts"):
        _Problem(c, grid, EHLOptions())


# ---------------------------------------------------------------- pseudo-transient continuation

def test_pseudo_transient_newton_converges_to_the_plain_newton_solution():
    """The transient term only changes the path (it vanishes at the state it linearises about): on a
    contact plain Newton solves, both reach the same film (measured: h_c to 1e-10, p to 5.7e-8 p_Hertz; both
    iterations stop at a full step below rtol = 1e-7 p_Hertz)."""
    c = EHLContact.from_moes(20, 10, line=True)
    a = solve_ehl(c, EHLGrid(nx=257))
    b = solve_ehl(c, EHLGrid(nx=257), EHLOptions(pseudo_transient=0.1))
    assert b.central_film_thickness == pytest.approx(a.central_film_thickness, rel=1e-9)
    assert np.max(np.abs(b.pressure - a.pressure)) <= 1e-6 * a.problem.ph


def test_bad_pseudo_transient_is_one_clear_line():
    with pytest.raises(InputError, match="pseudo_transient"):
        EHLOptions(pseudo_transient=-1.0)


@pytest.mark.parametrize("load", [53604.0, 87315.0])
def test_pseudo_transient_newton_converges_where_plain_newton_does_not(load):
    """Paper A's cone at 7 m/s with a Dowson-Higginson film on the kinds' graded 257-node grid (refine 6),
    above the hydrodynamic-to-EHL knee (M = 0.98 and 1.60, L = 53): plain Newton from the solver's own start
    fails (measured: iteration limit), the pseudo-transient one converges (25 and 47 iterations, 0.5 s), and
    what it reaches is a root of the plain residual: the plain second-order Newton iteration started there
    (its cavitated set rebuilt from empty, measured 22-28 iterations) comes back to the same film.""" 
    from lubedyn.lubrication import ConvergenceError
    from lubedyn.film_points import ehl

    par = dict(ehl._roller_params("cone"), density_law="dowson_higginson", grid_refine=6.0)
    contact, grid, options = ehl._ehl_setup(par, load, 7.0)
    assert grid.graded and options.pseudo_transient == 0.0
    with pytest.raises(ConvergenceError):
        solve_ehl(contact, grid, options)
    sol = solve_ehl(contact, grid, dataclasses.replace(options, pseudo_transient=0.1))
    assert sol.load == pytest.approx(load, rel=1e-9)
    from lubedyn.lubrication.ehl.newton import _active_set_newton

    P = sol.problem
    assert P.o.pseudo_transient == 0.1
    P.o = options  # the same discrete problem, plain Newton
    p, h00, history, _ = _active_set_newton(P, sol.pressure.copy(), sol.h00, load)
    # to 10 x the solver's own tolerance (rtol 1e-7 of p_Hertz and of b^2/R; measured 1.6e-14 and 2.8e-14 m)
    assert abs(h00 - sol.h00) <= 1e-6 * P.hscale
    assert np.max(np.abs(p - sol.pressure)) <= 1e-6 * P.ph
