r"""Unit quaternions for rigid-body attitude, as small ``@njit`` kernels.

Convention: scalar first, ``q = (w, x, y, z)`` with ``w = cos(phi/2)`` and
``(x, y, z) = sin(phi/2) u`` for a rotation by ``phi`` about the unit axis
``u``.  ``q`` maps body-frame vectors to the inertial frame,
``v_inertial = R(q) v_body`` (the active rotation), and composition follows
the Hamilton product: ``R(p * q) = R(p) R(q)`` (first ``q``, then ``p``).
SciPy's :class:`scipy.spatial.transform.Rotation` stores the *scalar last*
``(x, y, z, w)``; :func:`to_scipy` / :func:`from_scipy` convert.

Kinematics with the body-frame angular velocity ``omega_b``::

    dq/dt = 1/2 q * (0, omega_b)

which keeps ``|q|`` constant exactly; a numerical integrator drifts slowly, so
a right-hand side should use ``q/|q|`` for the attitude and add the
stabilising term ``-k (|q|^2 - 1) q`` (Baumgarte) if it integrates for long
(see :func:`quat_derivative`).  Euler's equations for a body with principal
inertia ``J = (J1, J2, J3)`` in the body frame (gyroscopic term included)::

    J domega_b/dt = T_b - omega_b x (J omega_b)

(:func:`euler_rate`); for a sphere ``J1 = J2 = J3`` and the gyroscopic term
vanishes identically.

All kernels write into caller-owned output arrays (no allocation inside a
right-hand side) and accept any float64 1-D views (e.g. ``y[k:k+4]``).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from lubedyn.lubrication.laws.jit import JIT as _JIT


@njit(**_JIT)
def quat_multiply(p, q, out):
    """Hamilton product ``out = p * q`` (``out`` may not alias ``p`` or ``q``)."""
    pw, px, py, pz = p[0], p[1], p[2], p[3]
    qw, qx, qy, qz = q[0], q[1], q[2], q[3]
    out[0] = pw * qw - px * qx - py * qy - pz * qz
    out[1] = pw * qx + px * qw + py * qz - pz * qy
    out[2] = pw * qy - px * qz + py * qw + pz * qx
    out[3] = pw * qz + px * qy - py * qx + pz * qw


@njit(**_JIT)
def quat_conjugate(q, out):
    """``out = q^*`` (the inverse of a unit quaternion)."""
    out[0] = q[0]
    out[1] = -q[1]
    out[2] = -q[2]
    out[3] = -q[3]


@njit(**_JIT)
def quat_norm(q):
    """Euclidean norm ``|q|``."""
    return math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])


@njit(**_JIT)
def quat_normalize(q):
    """Scale ``q`` to unit length in place; returns the norm it had."""
    n = quat_norm(q)
    if n > 0.0:
        inv = 1.0 / n
        for k in range(4):
            q[k] *= inv
    return n


@njit(**_JIT)
def quat_rotate(q, v, out):
    """``out = R(q) v`` for a unit ``q`` (body -> inertial).

    Uses ``v' = v + 2 w (r x v) + 2 r x (r x v)`` with ``r = (x, y, z)``."""
    _rotate(q[0], q[1], q[2], q[3], v, out)


@njit(**_JIT)
def _rotate(w, x, y, z, v, out):
    """Rotate ``v`` by the unit quaternion (w, x, y, z) into ``out``."""
    tx = 2.0 * (y * v[2] - z * v[1])
    ty = 2.0 * (z * v[0] - x * v[2])
    tz = 2.0 * (x * v[1] - y * v[0])
    out[0] = v[0] + w * tx + (y * tz - z * ty)
    out[1] = v[1] + w * ty + (z * tx - x * tz)
    out[2] = v[2] + w * tz + (x * ty - y * tx)


@njit(**_JIT)
def quat_rotate_inverse(q, v, out):
    """``out = R(q)^T v`` for a unit ``q`` (inertial -> body)."""
    _rotate(q[0], -q[1], -q[2], -q[3], v, out)


@njit(**_JIT)
def quat_to_matrix(q, out):
    """Rotation matrix ``out`` (3 x 3) of a unit ``q``."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    out[0, 0] = 1.0 - 2.0 * (y * y + z * z)
    out[0, 1] = 2.0 * (x * y - w * z)
    out[0, 2] = 2.0 * (x * z + w * y)
    out[1, 0] = 2.0 * (x * y + w * z)
    out[1, 1] = 1.0 - 2.0 * (x * x + z * z)
    out[1, 2] = 2.0 * (y * z - w * x)
    out[2, 0] = 2.0 * (x * z - w * y)
    out[2, 1] = 2.0 * (y * z + w * x)
    out[2, 2] = 1.0 - 2.0 * (x * x + y * y)


@njit(**_JIT)
def quat_from_rotvec(rv, out):
    """Unit quaternion of the rotation vector ``rv`` (axis * angle [rad]).

    Near zero angle the series ``sin(phi/2)/phi = 1/2 - phi^2/48`` avoids 0/0."""
    phi = math.sqrt(rv[0] * rv[0] + rv[1] * rv[1] + rv[2] * rv[2])
    if phi < 1e-6:
        s = 0.5 - phi * phi / 48.0
    else:
        s = math.sin(0.5 * phi) / phi
    out[0] = math.cos(0.5 * phi)
    out[1] = s * rv[0]
    out[2] = s * rv[1]
    out[3] = s * rv[2]


@njit(**_JIT)
def quat_to_rotvec(q, out):
    """Rotation vector (angle in [0, pi]) of a unit ``q``."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    if w < 0.0:
        w, x, y, z = -w, -x, -y, -z
    s = math.sqrt(x * x + y * y + z * z)
    phi = 2.0 * math.atan2(s, w)
    f = 2.0 + phi * phi / 12.0 if s < 1e-8 else phi / s
    out[0] = f * x
    out[1] = f * y
    out[2] = f * z


@njit(**_JIT)
def quat_derivative(q, omega_body, out, stabilise=0.0):
    """``out = dq/dt = 1/2 q * (0, omega_b) - stabilise (|q|^2 - 1) q``.

    ``stabilise`` [1/s] (Baumgarte) pulls ``|q|`` back to 1 without changing the
    attitude; 0 gives the exact kinematics."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    ox, oy, oz = omega_body[0], omega_body[1], omega_body[2]
    out[0] = 0.5 * (-x * ox - y * oy - z * oz)
    out[1] = 0.5 * (w * ox + y * oz - z * oy)
    out[2] = 0.5 * (w * oy - x * oz + z * ox)
    out[3] = 0.5 * (w * oz + x * oy - y * ox)
    if stabilise != 0.0:
        c = stabilise * (w * w + x * x + y * y + z * z - 1.0)
        for k in range(4):
            out[k] -= c * q[k]


@njit(**_JIT)
def euler_rate(inertia, omega_body, torque_body, out):
    """Euler's equations: ``out = J^-1 (T_b - omega_b x (J omega_b))``.

    ``inertia`` holds the principal moments (J1, J2, J3) [kg m^2]."""
    J1, J2, J3 = inertia[0], inertia[1], inertia[2]
    w1, w2, w3 = omega_body[0], omega_body[1], omega_body[2]
    out[0] = (torque_body[0] - (J3 - J2) * w2 * w3) / J1
    out[1] = (torque_body[1] - (J1 - J3) * w3 * w1) / J2
    out[2] = (torque_body[2] - (J2 - J1) * w1 * w2) / J3


def to_scipy(q) -> np.ndarray:
    """Scalar-first ``(w, x, y, z)`` -> SciPy's scalar-last ``(x, y, z, w)``."""
    q = np.asarray(q, dtype=float)
    return np.concatenate([q[..., 1:], q[..., :1]], axis=-1)


def from_scipy(q) -> np.ndarray:
    """SciPy's scalar-last ``(x, y, z, w)`` -> scalar-first ``(w, x, y, z)``."""
    q = np.asarray(q, dtype=float)
    return np.concatenate([q[..., 3:], q[..., :3]], axis=-1)
