"""EHL contacts against film-thickness formulas and their own grid convergence.

Dimensionless groups (Moes): U = eta0 u_m/(E' R_x), G = alpha E', M = W (2U)^-3/4
(point, W = w/(E' R_x^2)) or M = W (2U)^-1/2 (line, W = w/(E' R_x)), L = G (2U)^1/4,
H = h/R_x (2U)^-1/2.  u_m is the mean (entrainment) speed.

References (closed forms in :mod:`lubedyn.lubrication.laws.film`, independent of the solver):
- Moes (1992) line contact, quoted accuracy a few per cent.
- Nijenbanning, Venner & Moes (1994) circular contact (D = 1), within ~5 %.
- Hamrock & Dowson (1977) central film, quoted within ~20 % of their own solutions.
"""
import dataclasses
import numpy as np
import pytest

from lubedyn.lubrication import ConvergenceError
from lubedyn.lubrication.ehl import EHLContact, EHLGrid, EHLOptions, Traction, solve_ehl
from lubedyn.lubrication.laws.film import hamrock_dowson_central
from lubedyn.lubrication.laws.film import moes_line_central as moes_line
from lubedyn.lubrication.laws.film import nijenbanning_central as nvm_circular


def H(sol, c, value):
    return value / c.radius_x * (2 * c.U) ** -0.5


def test_line_contact_converges_at_second_order_to_moes():
    c = EHLContact.from_moes(10, 5, line=True)
    hc = np.array([H(s, c, s.central_film_thickness) for s in
                   (solve_ehl(c, EHLGrid(nx=n)) for n in (129, 257, 513))])
    d1, d2 = abs(hc[1] - hc[0]), abs(hc[2] - hc[1])
    order = np.log2(d1 / d2)
    assert order > 1.8  # measured 2.0
    extrap = hc[2] + (hc[2] - hc[1]) / (2**order - 1)
    # Moes' fit is quoted to a few per cent; measured 1.3 %
    assert extrap == pytest.approx(moes_line(10, 5), rel=0.03)


def test_heavily_loaded_line_contact():
    """M = 1000, L = 10: Hertzian pressure, outlet spike, Moes film within 2 %."""
    c = EHLContact.from_moes(1000, 10, line=True)
    s = solve_ehl(c, EHLGrid(nx=1025))
    assert H(s, c, s.central_film_thickness) == pytest.approx(moes_line(1000, 10), rel=0.02)  # measured 0.4 %
    assert s.load == pytest.approx(c.load, rel=1e-9)
    P = s.problem
    x = P.basis.doflocs[0]
    p_hertz = P.ph * np.sqrt(np.clip(1 - (x / P.bx) ** 2, 0, None))
    # outside the outlet spike the film pressure is the dry Hertz pressure
    away = np.abs(x / P.bx) < 0.8
    assert np.max(np.abs(s.pressure[away] - p_hertz[away])) / P.ph < 0.01
    assert 0.8 * P.bx < s.pressure_spike_position < 1.1 * P.bx
    assert s.minimum_film_thickness < s.central_film_thickness


def test_circular_point_contact_against_nvm_and_hamrock_dowson():
    c = EHLContact.from_moes(20, 10)
    s = solve_ehl(c, EHLGrid(nx=65))
    hc = H(s, c, s.central_film_thickness)
    assert hc == pytest.approx(nvm_circular(20, 10), rel=0.05)  # measured +1.7 %
    hd = hamrock_dowson_central(c.U, c.G, c.W, 1.0) * c.radius_x
    assert s.central_film_thickness == pytest.approx(hd, rel=0.2)
    assert s.info["scheme"] == "second order"
    assert s.load == pytest.approx(c.load, rel=1e-9)


def test_under_resolved_heavy_contact_fails_clearly():
    """Where it stops: M = 1000 on 129 nodes cannot resolve the outlet
    constriction (the film goes through zero at one node)."""
    c = EHLContact.from_moes(1000, 10, line=True)
    with pytest.raises(ConvergenceError, match="film-thickness floor"):
        solve_ehl(c, EHLGrid(nx=129))


def test_traction_laws():
    t_n, t_l, t_e = Traction("newtonian"), Traction("limiting_shear", 5e6, 0.05), Traction("eyring", eyring_stress=5e6)
    eta, h, p = np.array([1.0, 1e3]), 1e-7, np.array([1e9, 1e9])
    du = 1e-4
    # low stress: all laws are Newtonian (Eyring to second order in tau/tau0)
    assert t_e.stress(eta[:1], du, h, p[:1]) == pytest.approx(t_n.stress(eta[:1], du, h, p[:1]), rel=1e-6)
    # high stress: limiting shear caps at tau_L0 + gamma p, Eyring grows logarithmically
    big = t_l.stress(eta[1:], 10.0, h, p[1:])
    assert big == pytest.approx(5e6 + 0.05 * 1e9)
    assert t_e.stress(eta[1:], 10.0, h, p[1:]) == pytest.approx(5e6 * np.arcsinh(1e3 * 10 / 1e-7 / 5e6))
    with pytest.raises(Exception, match="did you mean"):
        Traction("eyrin")


def test_light_line_contact_on_1025_nodes_converges_through_the_fallback():
    """M = 20, L = 10 on 1025 nodes: the second-order iteration from the
    first-order solution of the same grid does not converge (the outlet-spike
    node oscillates: 80 active-set steps; Fischer-Burmeister: steps of
    +-3 p_Hertz there, merit stuck at 4e-5).  The solver then starts from the
    prolonged second-order 513-node solution and converges (measured 15
    steps, H_c 5.2668 against the 129/257/513 Richardson value 5.2673);
    before, this contact failed.  Moes within his few per cent (measured +3.3 %)."""
    c = EHLContact.from_moes(20, 10, line=True)
    s = solve_ehl(c, EHLGrid(nx=1025))
    assert "did not converge in 80 Newton iterations" in s.info["fallback"]["failed_start"]
    assert s.load == pytest.approx(c.load, rel=1e-9)
    assert H(s, c, s.central_film_thickness) == pytest.approx(moes_line(20, 10), rel=0.05)


def _complementarity(s):
    """Discrete complementarity of a returned solution in the scikit-fem reference
    assembly (``assemble_skfem``, independent of the solver's fast assembly):
    (max|R| at free nodes, min R at cavitated nodes, max|p R|) relative to
    max|R| of the state with p scaled by 1.001 (the size of a residual one
    per mille off), and the relative load error."""
    P = s.problem
    free = P.free0
    R = P.assemble_skfem(s.pressure, s.h00, jac=False)[0][free]
    ref = np.max(np.abs(P.assemble_skfem(1.001 * s.pressure, s.h00, jac=False)[0][free]))
    p = s.pressure[free] / P.ph
    cav = p <= 0.0
    return (np.max(np.abs(R[~cav])) / ref, (R[cav].min() / ref) if cav.any() else 0.0,
            np.max(np.abs(p * R)) / ref, abs(P.weights @ s.pressure - s.contact.load) / s.contact.load)


@pytest.mark.parametrize("M, L", [(20, 10), (10, 5)])
def test_line_solution_satisfies_discrete_complementarity(M, L):
    """The active-set Newton's converged state (257 nodes) checked in the
    reference assembly: Reynolds residual 0 at free nodes, >= 0 (a valid
    multiplier) at cavitated nodes, p R = 0, load balanced, to the solver's
    rtol (1e-7; measured |R| <= 1e-11 of a per-mille residual, load 1e-15)."""
    c = EHLContact.from_moes(M, L, line=True)
    s = solve_ehl(c, EHLGrid(nx=257))
    free_res, cav_min, pr, load = _complementarity(s)
    assert free_res < 1e-7 and pr < 1e-7 and cav_min > -1e-7 and load < 1e-6


def test_line_contact_from_two_starts_gives_one_solution():
    """M = 10, L = 5 (alpha p_H = 6.5, far from the Barus round-off limit of
    tests/test_maps.py KNOWN_MISSES): the default nested start and a start
    from the solution at 6 % more load (h_min 0.76 % apart) converge to the
    same state; the difference is set by the tolerance (rtol = 1e-7 p_H per
    step), so h_min and h00 agree to 1e-5 of the film scale (measured: equal)."""
    c = EHLContact.from_moes(10, 5, line=True)
    g = EHLGrid(nx=257)
    a = solve_ehl(c, g)
    other = solve_ehl(dataclasses.replace(c, load=1.06 * c.load), g)
    b = solve_ehl(c, g, initial=other)
    assert b.minimum_film_thickness == pytest.approx(a.minimum_film_thickness, rel=1e-5)
    assert abs(b.h00 - a.h00) < 1e-5 * a.central_film_thickness
