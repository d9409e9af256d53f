"""Linearised film stiffness K = -dF/dq and damping C = -dF/d(dq/dt).

- short journal bearing (Ocvirk, half-Sommerfeld): the eight coefficients of
  Friswell et al. (2010, sec. 5.5), the frame pinned by finite differences of
  an independent semi-analytic short-bearing force, then the finite-element
  coefficients against them at L/D = 1/10 and 1/20 (error ~ (L/D)^2);
- squeeze films: C from the perturbation solve equals F/(-v), K against the
  analytic derivative.

Frame mapping (solver): fixed x, y; theta from +x towards +y;
h = c - e_x cos(theta) - e_y sin(theta); the journal is the upper surface
with ``velocity_upper = (omega R, 0)`` (turning towards +theta, counter-
clockwise), the bearing fixed, so u_m = omega R / 2.  Mode forces F_x, F_y are
the film force on the journal.  Friswell's (u, v): v along the static film
force on the journal (opposite to the external load), u = v turned 90 deg
against the rotation, i.e. (u_x, u_y) = (v_y, -v_x); the journal turns from u
towards v.  With T = [u; v] (rows), K_uv = T K_xy T^T and likewise C.
"""
import numpy as np
import pytest

from lubedyn.lubrication import Cavitation, Film, FunctionGap, JournalBearing, Lubricant, SpherePlane
from lubedyn.lubrication import closed_form as cf
from lubedyn.lubrication import mesh as meshes

R, C, ETA, U = 0.05, 50e-6, 0.02, 10.0  # radius, clearance [m], viscosity [Pa s], omega R [m/s]
EPS = [0.2, 0.4, 0.6, 0.8]


def load_frame(F):
    """Rows u, v of Friswell's frame from the static film force F on the journal."""
    v = np.asarray(F, dtype=float) / np.linalg.norm(F)
    return np.array([[v[1], -v[0]], v])


@pytest.mark.parametrize("eps", EPS)
def test_short_bearing_closed_forms_match_semi_analytic_derivatives(eps):
    """Pin Friswell's frame and signs: central differences (step 1e-4 c and
    1e-4 c omega) of :func:`closed_form.short_journal_forces` (scipy quad of
    the short-bearing pressure p = 6 eta (U/2 dh/dx + dh/dt)(z^2 - L^2/4)/h^3
    over the half circle where it is positive, in the solver's fixed frame)
    give K and C; rotated into (u, v) they equal the closed forms.  Measured
    agreement 3e-8 ... 5e-7 of the matrix scale (the O(step^2) difference
    error); asserted 1e-5.  The static force matches W and the attitude angle
    to round-off.  The journal centre sits at an arbitrary angle (0.3 rad).
    """
    L = 0.01
    ex, ey = eps * C * np.cos(0.3), eps * C * np.sin(0.3)
    force = lambda dx=0.0, dy=0.0, vx=0.0, vy=0.0: cf.short_journal_forces(R, C, L, ETA, U, ex + dx, ey + dy, vx, vy)
    F0 = force()
    W, attitude, W_r, W_t = cf.short_journal_load(R, C, L, eps, ETA, U)
    d = np.array([np.cos(0.3), np.sin(0.3)])
    n = np.array([-d[1], d[0]])  # d turned +90 deg in the direction of rotation
    assert F0 @ d == pytest.approx(-W_r, rel=1e-10)
    assert F0 @ n == pytest.approx(W_t, rel=1e-10)
    assert np.arctan2(F0 @ n, -(F0 @ d)) == pytest.approx(attitude, abs=1e-12)
    step, vstep = 1e-4 * C, 1e-4 * C * U / R
    K = -np.column_stack([(force(dx=step) - force(dx=-step)) / (2 * step),
                          (force(dy=step) - force(dy=-step)) / (2 * step)])
    Cm = -np.column_stack([(force(vx=vstep) - force(vx=-vstep)) / (2 * vstep),
                           (force(vy=vstep) - force(vy=-vstep)) / (2 * vstep)])
    T = load_frame(F0)
    K_ref, C_ref = cf.short_journal_coefficients(R, C, L, eps, ETA, U)
    assert np.max(np.abs(T @ K @ T.T - K_ref)) < 1e-5 * np.max(np.abs(K_ref))
    assert np.max(np.abs(T @ Cm @ T.T - C_ref)) < 1e-5 * np.max(np.abs(C_ref))


def short_bearing_fem(eps, L_over_D, n=256, nz=4):
    """Finite bearing (z in [0, L], p = 0 at both ends), half-Sommerfeld, P2.

    The journal centre is displaced along alpha = dtheta/6 (dtheta = 2 pi/n):
    the rupture lines of the half-Sommerfeld film (theta = alpha and
    alpha + pi, by the antisymmetry of the full-Sommerfeld pressure about the
    line of centres) then sit a sixth of an element from a vertex.  Reason:
    ``film_coefficients`` masks dp/dq at the *dofs* where p > p_cav (the exact
    derivative of the discrete clipped force), an O(h) error in general
    position (measured at alpha = 0, eps = 0.8, L/D = 1/10: K_xy changes by
    4.7 % and C_xx by 0.8 % between 256 and 1024 elements, halving with each
    doubling of n).  A P2 vertex dof carries 1/6 of an
    element's integral, so with the boundary at 1/6 the masking is exact to
    leading order and the coefficients converge at second order (differences
    between 128 and 256 elements below 3e-4 of the matrix scale).  P2 with
    4 elements in z: the nearly parabolic axial profile is resolved to 1e-7.
    """
    D = 2.0 * R
    L = L_over_D * D
    m = meshes.rectangle(np.linspace(0.0, 2.0 * np.pi * R, n + 1), np.linspace(0.0, L, nz + 1),
                         cell="quad", periodic_x=True)
    alpha = 2.0 * np.pi / n / 6.0
    film = Film(m, JournalBearing.from_ratio(R, C, eps, alpha), Lubricant.newtonian(ETA),
                velocity_upper=(U, 0.0), dirichlet={"bottom": 0.0, "top": 0.0}, element="P2",
                cavitation=Cavitation("half_sommerfeld", 0.0))
    sol = film.solve()
    names, K, Cm = sol.coefficients()
    assert names == ["x", "y"]
    F = np.array([sol.mode_forces["x"], sol.mode_forces["y"]])
    return L, alpha, F, K, Cm


def short_bearing_errors(eps, L_over_D):
    """Errors against Ocvirk: load (relative), attitude [rad], K and C entries
    in (u, v) relative to the largest closed-form entry of their matrix."""
    L, alpha, F, K, Cm = short_bearing_fem(eps, L_over_D)
    W, attitude, W_r, W_t = cf.short_journal_load(R, C, L, eps, ETA, U)
    d = np.array([np.cos(alpha), np.sin(alpha)])
    n = np.array([-d[1], d[0]])
    T = load_frame(-W_r * d + W_t * n)  # the closed-form frame
    K_ref, C_ref = cf.short_journal_coefficients(R, C, L, eps, ETA, U)
    return np.concatenate([
        [np.linalg.norm(F) / W - 1.0, np.arctan2(F @ n, -(F @ d)) - attitude],
        ((T @ K @ T.T - K_ref) / np.max(np.abs(K_ref))).ravel(),
        ((T @ Cm @ T.T - C_ref) / np.max(np.abs(C_ref))).ravel(),
    ])


@pytest.mark.parametrize("eps", EPS)
def test_short_bearing_fem_against_ocvirk(eps):
    """Load, attitude angle and K_uu, K_uv, K_vu, K_vv, C_uu, C_uv, C_vu, C_vv
    of the finite-element bearing tend to the short-bearing closed forms like
    (L/D)^2.

    Measured errors at L/D = 1/10 (load, attitude [rad], then the eight
    coefficients / matrix scale), largest over eps = 0.2 ... 0.8:
    load 4.4e-2, attitude 9.5e-3, K up to 6.9e-2, C up to 3.1e-2 (eps =
    0.8); at L/D = 1/20 each is 3.6 ... 4.0 times smaller wherever the error
    is above 2e-3 (fitted exponent 1.86 ... 1.99), as the short-bearing
    theory's leading neglected term (d/dx of the circumferential flow,
    relative size ~ (L/D)^2) predicts.  Discretisation error (n = 256,
    measured by halving n) < 3e-4.

    Asserted for every quantity: |e(1/10)| < 0.08 and
    |e(1/20) - e(1/10)/4| < 0.1 |e(1/10)| + 5e-4 (the 10 % is the
    (L/D)^4 term seen at eps = 0.8, 5e-4 the discretisation); and the mean
    exponent log2(e(1/10)/e(1/20)) over the errors above 5e-3 in [1.8, 2.1].
    """
    e10 = short_bearing_errors(eps, 0.1)
    e20 = short_bearing_errors(eps, 0.05)
    assert np.all(np.abs(e10) < 0.08)
    assert np.all(np.abs(e20 - e10 / 4.0) < 0.1 * np.abs(e10) + 5e-4)
    big = np.abs(e10) > 5e-3
    assert np.any(big)
    exponent = np.mean(np.log2(e10[big] / e20[big]))
    assert 1.8 < exponent < 2.1


# --------------------------------------------------------------------------
# squeeze films: C = F/(-v) and K = -dF/dh0

ETA_SQ, V = 0.05, -1e-3


def test_parallel_disk_coefficients():
    """Constant gap h: the discrete pressure scales exactly like (-v)/h^3,
    so K = -dF/dh = 3 F/h and C = F/(-v) hold to round-off for the
    perturbation solves; C also against 3 pi eta R^4/(2 h^3) (polygonal
    disk: measured 3.3e-3 at refinement 4, P2)."""
    radius, h = 5e-3, 10e-6
    film = Film(meshes.disk(radius, 4), FunctionGap(lambda x: np.full(x.shape[1:], h)),
                Lubricant.newtonian(ETA_SQ), mode_velocities={"h0": V}, element="P2")
    sol = film.solve()
    F = sol.mode_forces["h0"]
    names, K, Cm = sol.coefficients()
    assert names == ["h0"]
    assert Cm[0, 0] == pytest.approx(F / -V, rel=1e-10)
    assert K[0, 0] == pytest.approx(3.0 * F / h, rel=1e-10)
    assert Cm[0, 0] == pytest.approx(cf.parallel_disk_squeeze_force(radius, h, ETA_SQ, -1.0), rel=5e-3)


def test_sphere_plane_coefficients():
    """Sphere (R = 5 mm, parabolic gap) approaching a plane at v, domain
    a = 3 sqrt(2 R h0).  C = F/(-v) to round-off (the film is linear in v);
    C against 6 pi eta R^2/h0 (1 - h0/h_a)^2 and K against its h0-derivative
    at fixed v, K = 6 pi eta (-v) R^2 s^2 (1/(h0^2 h_a^2) + 2/(h0 h_a^3)),
    s = a^2/(2R): P2 on mesh.disk(a, 4), measured 4.2e-4 (C) and 2.5e-4 (K).
    """
    R_s, h0 = 5e-3, 1e-6
    a = 3.0 * np.sqrt(2.0 * R_s * h0)
    film = Film(meshes.disk(a, 4), SpherePlane(R_s, h0), Lubricant.newtonian(ETA_SQ),
                mode_velocities={"h0": V}, element="P2")
    sol = film.solve()
    F = sol.mode_forces["h0"]
    _, K, Cm = sol.coefficients()
    assert Cm[0, 0] == pytest.approx(F / -V, rel=1e-10)
    assert Cm[0, 0] == pytest.approx(cf.sphere_plane_squeeze_force(R_s, h0, ETA_SQ, -1.0, a), rel=1e-3)
    s = a * a / (2.0 * R_s)
    h_a = h0 + s
    K_ref = 6.0 * np.pi * ETA_SQ * (-V) * R_s**2 * s**2 * (1.0 / (h0**2 * h_a**2) + 2.0 / (h0 * h_a**3))
    assert K[0, 0] == pytest.approx(K_ref, rel=1e-3)
