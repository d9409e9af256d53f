"""Linearised film coefficients (perturbation equations) against finite differences.

K_ij = -dF_i/dq_j and C_ij = -dF_i/d(dq_j/dt), F_q = int (p - p_amb) dh/dq dA.
The finite differences re-solve the *nonlinear* film with the gap shifted along
a mode (``ShiftedGap``) or with a mode velocity; central differences with a
step of 1e-4 of the clearance have a truncation error ~1e-8 relative, far below
the tolerances used, which are set by the solver tolerance (rtol 1e-10).
"""
import numpy as np
import pytest

from lubedyn.lubrication import Barus, Cavitation, DowsonHigginson, Film, JournalBearing, Lubricant, SpherePlane
from lubedyn.lubrication import mesh
from lubedyn.lubrication.gaps import ShiftedGap


def _fd(film, names, step_q, step_v):
    K = np.zeros((len(names), len(names)))
    C = np.zeros_like(K)
    for j, nj in enumerate(names):
        plus = film.with_(gap=ShiftedGap(film.gap, nj, step_q)).solve().mode_forces
        minus = film.with_(gap=ShiftedGap(film.gap, nj, -step_q)).solve().mode_forces
        base_v = dict(film.mode_velocities)
        vp = dict(base_v, **{nj: base_v.get(nj, 0.0) + step_v})
        vm = dict(base_v, **{nj: base_v.get(nj, 0.0) - step_v})
        fp = film.with_(mode_velocities=vp).solve().mode_forces
        fm = film.with_(mode_velocities=vm).solve().mode_forces
        for i, ni in enumerate(names):
            K[i, j] = -(plus[ni] - minus[ni]) / (2 * step_q)
            C[i, j] = -(fp[ni] - fm[ni]) / (2 * step_v)
    return K, C


def _journal(model, element="P1", lub=None):
    R, c, L = 0.025, 50e-6, 0.025
    m = mesh.rectangle(np.linspace(0, 2 * np.pi * R, 49), np.linspace(-L / 2, L / 2, 9), "quad", periodic_x=True)
    gap = JournalBearing.from_ratio(R, c, 0.6, attitude_angle=0.3)
    return Film(
        m, gap, lub or Lubricant.newtonian(0.02), velocity_upper=(300.0 * R, 0.0), velocity_lower=(0.0, 0.0),
        dirichlet={"bottom": 1e5, "top": 1e5}, cavitation=Cavitation(model), element=element,
    ), c


@pytest.mark.parametrize("model", ["none", "jfo"])
def test_journal_coefficients_match_finite_differences(model):
    film, c = _journal(model)
    names, K, C = film.solve().coefficients()
    Kfd, Cfd = _fd(film, names, 1e-4 * c, 1e-4 * 300.0 * c)
    scale_k, scale_c = np.abs(K).max(), np.abs(C).max()
    # full film: the discrete problem is smooth, agreement to the FD truncation;
    # JFO: the active set is frozen in the perturbation solve; the FD step moves
    # no node across the cavitation boundary here, so it is equally tight.
    assert np.abs(K - Kfd).max() / scale_k < 1e-5
    assert np.abs(C - Cfd).max() / scale_c < 1e-5


def test_piezoviscous_compressible_squeeze_coefficients():
    """Nonlinear laws: the Jacobian carries d(eta)/dp and d(rho)/dp terms."""
    R, h0, a = 5e-3, 1e-6, 0.4e-3
    lub = Lubricant(Barus(0.05, 1.85e-8), DowsonHigginson(992.0))
    film = Film(mesh.disk(a, 3), SpherePlane(R, h0), lub, velocity_lower=(0.0, 0.0),
                mode_velocities={"h0": -2.5e-2}, element="P2")
    s = film.solve()
    assert s.p_max * 1.85e-8 > 0.3  # piezoviscous effect is material at this point
    names, K, C = s.coefficients()
    Kfd, Cfd = _fd(film, names, 1e-4 * h0, 1e-5)
    assert K[0, 0] == pytest.approx(Kfd[0, 0], rel=1e-5)
    assert C[0, 0] == pytest.approx(Cfd[0, 0], rel=1e-5)
    assert K[0, 0] > 0 and C[0, 0] > 0  # approaching film pushes back and damps
