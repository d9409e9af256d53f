"""Quaternion kernels of lubedyn.dynamics.rotations against scipy.spatial.transform.Rotation
(an independent implementation), and rigid-body invariants."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from lubedyn.dynamics import rotations as R

RNG = np.random.default_rng(7)
ROTS = Rotation.random(12, random_state=11)


def _k(kernel, compiled):
    return kernel if compiled else kernel.py_func


@pytest.mark.parametrize("compiled", [True, False])
def test_product_composes_like_scipy(compiled):
    mul, mat = _k(R.quat_multiply, compiled), _k(R.quat_to_matrix, compiled)
    out, M = np.empty(4), np.empty((3, 3))
    for a, b in zip(ROTS[:6], ROTS[6:]):
        p, q = R.from_scipy(a.as_quat()), R.from_scipy(b.as_quat())
        mul(p, q, out)
        ref = R.from_scipy((a * b).as_quat())  # scipy: a * b applies b first, then a
        assert min(np.abs(out - ref).max(), np.abs(out + ref).max()) < 1e-14
        mat(out, M)
        np.testing.assert_allclose(M, (a * b).as_matrix(), atol=1e-14)


@pytest.mark.parametrize("compiled", [True, False])
def test_rotate_and_inverse_like_scipy(compiled):
    rot, inv = _k(R.quat_rotate, compiled), _k(R.quat_rotate_inverse, compiled)
    out = np.empty(3)
    for a in ROTS:
        q = R.from_scipy(a.as_quat())
        v = RNG.normal(size=3)
        rot(q, v, out)
        np.testing.assert_allclose(out, a.apply(v), atol=1e-14)
        inv(q, v, out)
        np.testing.assert_allclose(out, a.inv().apply(v), atol=1e-14)


@pytest.mark.parametrize("compiled", [True, False])
@pytest.mark.parametrize("angle", [3e-9, 1e-4, 0.7, 3.1])
def test_rotvec_round_trip_like_scipy(compiled, angle):
    frv, trv = _k(R.quat_from_rotvec, compiled), _k(R.quat_to_rotvec, compiled)
    axis = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    rv = angle * axis
    q = np.empty(4)
    frv(rv, q)
    ref = R.from_scipy(Rotation.from_rotvec(rv).as_quat())
    assert min(np.abs(q - ref).max(), np.abs(q + ref).max()) < 1e-15
    back = np.empty(3)
    trv(q, back)
    np.testing.assert_allclose(back, rv, rtol=1e-12, atol=1e-20)


@pytest.mark.parametrize("compiled", [True, False])
def test_normalize(compiled):
    q = np.array([2.0, -1.0, 0.5, 3.0])
    n = _k(R.quat_normalize, compiled)(q)
    assert n == pytest.approx(np.sqrt(14.25), rel=1e-15)
    assert np.linalg.norm(q) == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("compiled", [True, False])
def test_constant_body_rate_gives_exponential(compiled):
    """dq/dt = q (0, w)/2 with constant body w: q(T) = q0 * exp(w T) (scipy composition)."""
    deriv = _k(R.quat_derivative, compiled)
    w = np.array([3.0, -2.0, 5.0])
    q0 = R.from_scipy(ROTS[0].as_quat())

    def f(t, q):
        out = np.empty(4)
        deriv(q, w, out, 0.0)
        return out

    T = 0.8
    sol = solve_ivp(f, (0.0, T), q0, rtol=1e-12, atol=1e-14, method="DOP853")
    ref = R.from_scipy((ROTS[0] * Rotation.from_rotvec(w * T)).as_quat())
    qT = sol.y[:, -1]
    assert min(np.abs(qT - ref).max(), np.abs(qT + ref).max()) < 1e-9


def test_baumgarte_term_restores_unit_norm_without_turning():
    q = np.array([1.1, 0.0, 0.0, 0.0])
    out = np.empty(4)
    R.quat_derivative(q, np.zeros(3), out, 10.0)
    # d|q|^2/dt = 2 q.dq = -2 k (|q|^2 - 1)|q|^2 ; direction unchanged
    assert 2.0 * q @ out == pytest.approx(-2.0 * 10.0 * (1.21 - 1.0) * 1.21, rel=1e-14)
    assert out[1:].tolist() == [0.0, 0.0, 0.0]


@pytest.mark.parametrize("compiled", [True, False])
def test_torque_free_top_conserves_momentum_and_energy(compiled):
    """Euler + quaternion kinematics of an asymmetric top: the inertial angular
    momentum R J w and the kinetic energy stay constant (gyroscopic term)."""
    deriv, euler, rot = (_k(k, compiled) for k in (R.quat_derivative, R.euler_rate, R.quat_rotate))
    J = np.array([1.0, 2.0, 3.5])

    def f(t, y):
        out = np.empty(7)
        deriv(y[:4], y[4:], out[:4], 0.0)
        euler(J, y[4:], np.zeros(3), out[4:])
        return out

    y0 = np.concatenate([[1.0, 0, 0, 0], [0.4, 2.0, -0.3]])  # near the unstable middle axis
    sol = solve_ivp(f, (0.0, 6.0), y0, rtol=1e-11, atol=1e-13, method="DOP853")
    L = []
    for y in sol.y.T:
        out = np.empty(3)
        q = y[:4] / np.linalg.norm(y[:4])
        rot(q, J * y[4:], out)
        L.append(out.copy())
    L = np.array(L)
    assert np.abs(sol.y[4:, -1] - y0[4:]).max() > 0.5  # it does tumble
    np.testing.assert_allclose(L, np.broadcast_to(L[0], L.shape), atol=1e-8)
    E = 0.5 * np.sum(J[:, None] * sol.y[4:] ** 2, axis=0)
    np.testing.assert_allclose(E, E[0], rtol=1e-9)


def test_sphere_has_no_gyroscopic_term():
    out = np.empty(3)
    R.euler_rate(np.full(3, 2.0), np.array([3.0, -1.0, 7.0]), np.array([0.2, 0.4, -0.6]), out)
    np.testing.assert_allclose(out, [0.1, 0.2, -0.3], rtol=1e-15)
