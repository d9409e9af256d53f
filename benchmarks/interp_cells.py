"""Interpolation kernels used only by the benchmarks: per-query cost loops and the per-cell variant.

``benchmarks/maps.py --query-only`` times the map kernels of :mod:`lubedyn.dynamics.interp` with the value
loops ``sum1/2/3`` (multilinear and pchip) and ``hsum1/2/3`` (hermite), and times against them a
variant of the hermite method kept here because the library does not use it:

**hermite-cells**: the tensor cubic Hermite interpolant of :mod:`lubedyn.dynamics.interp` method 2, stored
per cell as the 4**ndim coefficients of its polynomial in d_k = t_k - t_k,i
(:func:`hermite_cells_data`, kernels ``hermite1/2/3_cells[_grad]`` with the signatures of
``hermite*``).  Equal to method 2 to rounding (1e-14 of the value range); nested Horner, no
division, one contiguous 512-byte block a 3-D query; 8x the memory of method 2 in 3-D.
``tests/test_interp_cells.py`` checks it against scipy's PCHIP and against method 2.

Measured (``benchmarks/maps.py --query-only``; ns per query, 3 axes, one log axis, numba loop,
thread CPU time, 2026-11-22): linear 58 / 101 (value / value + gradient), hermite 57 / 91,
hermite-cells 46 / 71, pchip 392 / 646.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from lubedyn.dynamics.interp import (
    _FMA, _INLINE, _JIT, _cell, _dtdx_at, _finish, _refuse, hermite1, hermite2, hermite3, hermite3_grad, interp1,
    interp2, interp3, interp3_grad,
)

HERMITE_CELLS = 3


def evaluate_cells(axes, logs, cells, logv, points, mode=0, counter=None, grad=False):
    """:func:`lubedyn.dynamics.interp.evaluate` for the per-cell array of :func:`hermite_cells_data`."""
    points = np.ascontiguousarray(np.atleast_2d(points), dtype=np.float64)
    ndim = len(axes)
    if cells.shape != tuple(a.size - 1 for a in axes) + (4**ndim,):
        raise ValueError(f"hermite-cells needs the array of hermite_cells_data, shape (n0-1, ..., {4**ndim}), "
                         f"got {cells.shape}")
    counter = np.zeros(1, dtype=np.int64) if counter is None else counter
    out = np.empty(points.shape[0])
    g = np.empty((points.shape[0], ndim))
    logs = tuple(int(bool(x)) for x in logs)
    (cmany1, cmany2, cmany3)[ndim - 1](*axes, *logs, cells, int(bool(logv)), points, int(mode), counter, out, g)
    return (out, g) if grad else out


@njit(**_JIT)
def sum1(ax0, log0, values, logv, method, xs, mode, counter):
    """Sum of values at ``xs`` (value only): the per-query cost benchmark."""
    s = 0.0
    for q in range(xs.size):
        s += interp1(ax0, log0, values, logv, method, xs[q], mode, counter)
    return s


@njit(**_JIT)
def sum2(ax0, ax1, log0, log1, values, logv, method, points, mode, counter):
    s = 0.0
    for q in range(points.shape[0]):
        s += interp2(ax0, ax1, log0, log1, values, logv, method, points[q, 0], points[q, 1], mode, counter)
    return s


@njit(**_JIT)
def sum3(ax0, ax1, ax2, log0, log1, log2, values, logv, method, points, mode, counter):
    s = 0.0
    for q in range(points.shape[0]):
        s += interp3(ax0, ax1, ax2, log0, log1, log2, values, logv, method, points[q, 0], points[q, 1],
                     points[q, 2], mode, counter)
    return s



@njit(**_JIT)
def hsum1(ax0, log0, deriv, logv, xs, mode, counter):
    s = 0.0
    for q in range(xs.size):
        s += hermite1(ax0, log0, deriv, logv, xs[q], mode, counter)
    return s


@njit(**_JIT)
def hsum2(ax0, ax1, log0, log1, deriv, logv, points, mode, counter):
    s = 0.0
    for q in range(points.shape[0]):
        s += hermite2(ax0, ax1, log0, log1, deriv, logv, points[q, 0], points[q, 1], mode, counter)
    return s


@njit(**_JIT)
def hsum3(ax0, ax1, ax2, log0, log1, log2, deriv, logv, points, mode, counter):
    s = 0.0
    for q in range(points.shape[0]):
        s += hermite3(ax0, ax1, ax2, log0, log1, log2, deriv, logv, points[q, 0], points[q, 1], points[q, 2], mode,
                      counter)
    return s


# value + gradient consumed inside numba (as the dynamics kernels use a query: no output arrays), 3-D
@njit(**_JIT)
def hgsum3(ax0, ax1, ax2, log0, log1, log2, deriv, logv, points, mode, counter):
    s = 0.0
    for q in range(points.shape[0]):
        r = hermite3_grad(ax0, ax1, ax2, log0, log1, log2, deriv, logv, points[q, 0], points[q, 1], points[q, 2],
                          mode, counter)
        s += r[0] + r[1] + r[2] + r[3]
    return s


@njit(**_JIT)
def gsum3(ax0, ax1, ax2, log0, log1, log2, values, logv, method, points, mode, counter):
    s = 0.0
    for q in range(points.shape[0]):
        r = interp3_grad(ax0, ax1, ax2, log0, log1, log2, values, logv, method, points[q, 0], points[q, 1],
                         points[q, 2], mode, counter)
        s += r[0] + r[1] + r[2] + r[3]
    return s


# ---------------------------------------------------------------------------
# method 3: the same tensor cubic Hermite, stored per cell as polynomial coefficients
#
# ``cells`` has shape (n0-1[, n1-1[, n2-1]], 4**ndim): for cell (i, j, k) the 64 (3-D) coefficients
# c[16 p + 4 q + r] of  u = sum c_pqr d0^p d1^q d2^r  with d_k = t_k - ax_k[cell] (not scaled by the
# cell width), made by :func:`hermite_cells_data` from the node values and PCHIP node derivatives of
# :func:`hermite_data`.  It is the interpolant of method 2 written in another basis: equal to it to
# rounding (about 1e-14 of the value range; the node values come out exactly at the cell's first
# corner).  A query reads one contiguous block of 4**ndim numbers and evaluates it by nested Horner:
# 21 cubics (63 fused multiply-adds) for a 3-D value, 123 for value and gradient, against 84 / 192
# multiply-adds of method 2, and no division at all (d is a difference; d/dt needs no 1/h).  The
# price is memory: 4**ndim / 2**ndim times the node array of method 2 (8x in 3-D), 512 bytes a cell.


def hermite_cells_data(axes_t, deriv) -> np.ndarray:
    """Per-cell polynomial coefficients, shape ``(n0-1, ..., 4**ndim)``, for the ``hermite*_cells`` kernels.

    ``axes_t``: prepared axes (t space); ``deriv``: the array of :func:`hermite_data` for them (shape
    ``(2**ndim, n0, ...)``).  On a cell of width h with end values f0, f1 and end slopes g0, g1 the
    cubic in d = t - t0 is f0 + g0 d + ((3 (f1 - f0)/h - 2 g0 - g1)/h) d^2 + ((2 (f0 - f1)/h + g0 + g1)/h^2) d^3
    (the cubic Hermite form expanded); the tensor product applies this map along every axis.

    >>> ax = prepare_axis(np.array([0.0, 1.0, 3.0]), False)
    >>> c = hermite_cells_data((ax,), hermite_data((ax,), ax ** 2))
    >>> c.shape
    (2, 4)
    """
    deriv = np.asarray(deriv, dtype=np.float64)
    nd = len(axes_t)
    if deriv.ndim != nd + 1 or deriv.shape[0] != 2**nd:
        raise ValueError(f"hermite_cells_data needs the (2**{nd}, n0, ...) array of hermite_data, got {deriv.shape}")
    ncell = tuple(n - 1 for n in deriv.shape[1:])
    # local Hermite data H[cells..., a_0, ..., a_nd-1], a = 0: value at the cell's first node, 1: at its
    # second, 2: slope at the first, 3: slope at the second
    H = np.empty(ncell + (4,) * nd)
    for a in np.ndindex(*(4,) * nd):
        s = sum((ak >> 1) << k for k, ak in enumerate(a))
        sl = tuple(slice(ak & 1, (ak & 1) + n) for ak, n in zip(a, ncell))
        H[(Ellipsis,) + a] = deriv[(s,) + sl]
    for k in range(nd):
        h = np.diff(np.asarray(axes_t[k], dtype=np.float64))
        M = np.zeros((h.size, 4, 4))  # M[cell, power, a]
        M[:, 0, 0] = 1.0
        M[:, 1, 2] = 1.0
        M[:, 2, 0], M[:, 2, 1], M[:, 2, 2], M[:, 2, 3] = -3.0 / h**2, 3.0 / h**2, -2.0 / h, -1.0 / h
        M[:, 3, 0], M[:, 3, 1], M[:, 3, 2], M[:, 3, 3] = 2.0 / h**3, -2.0 / h**3, 1.0 / h**2, 1.0 / h**2
        cells, local = "ijk"[:nd], "abc"[:nd]
        out = local.replace(local[k], "p")
        H = np.einsum(f"{cells}{local},{cells[k]}p{local[k]}->{cells}{out}", H, M)
    return np.ascontiguousarray(H.reshape(ncell + (4**nd,)))


@njit(**_INLINE)
def _cubic(c0, c1, c2, c3, d):
    """c0 + c1 d + c2 d^2 + c3 d^3 (Horner)."""
    return ((c3 * d + c2) * d + c1) * d + c0


@njit(**_INLINE)
def _cubic_grad(c0, c1, c2, c3, d):
    """(value, d/dd) of the cubic by Horner with derivative."""
    v = c3 * d + c2
    g = c3
    g = g * d + v
    v = v * d + c1
    g = g * d + v
    v = v * d + c0
    return v, g


@njit(**_INLINE)
def _line(c, b, d):
    """Cubic of the 4 coefficients c[b .. b+3] at d."""
    return _cubic(c[b], c[b + 1], c[b + 2], c[b + 3], d)


@njit(**_INLINE)
def _line_grad(c, b, d):
    return _cubic_grad(c[b], c[b + 1], c[b + 2], c[b + 3], d)


@njit(**_INLINE)
def _plane_grad(c, b, d1, d2):
    """3-D, one power p of d0 (coefficients c[b .. b+15]): (F, dF/dd1, dF/dd2) of the bicubic in (d1, d2)."""
    e0, g0 = _line_grad(c, b, d2)
    e1, g1 = _line_grad(c, b + 4, d2)
    e2, g2 = _line_grad(c, b + 8, d2)
    e3, g3 = _line_grad(c, b + 12, d2)
    f, f1 = _cubic_grad(e0, e1, e2, e3, d1)
    return f, f1, _cubic(g0, g1, g2, g3, d1)


@njit(**_FMA)
def hermite1_cells_grad(ax0, log0, cells, logv, x0, mode, counter):
    """(v, dv/dx0); ``cells`` of shape (n0-1, 4) from :func:`hermite_cells_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    refuse = _refuse(nan0, o0, mode, counter)
    u, u0 = _line_grad(cells[i], 0, c0 - ax0[i])
    v, dvdu = _finish(u, logv)
    if refuse:
        return np.nan, np.nan
    return v, dvdu * u0 * _dtdx_at(x0, c0, o0, log0)


@njit(**_FMA)
def hermite1_cells(ax0, log0, cells, logv, x0, mode, counter):
    """v at x0; ``cells`` of shape (n0-1, 4) from :func:`hermite_cells_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    refuse = _refuse(nan0, o0, mode, counter)
    u = _line(cells[i], 0, c0 - ax0[i])
    if logv:
        u = math.exp(u)
    return np.nan if refuse else u


@njit(**_FMA)
def hermite2_cells_grad(ax0, ax1, log0, log1, cells, logv, x0, x1, mode, counter):
    """(v, dv/dx0, dv/dx1); ``cells`` of shape (n0-1, n1-1, 16) from :func:`hermite_cells_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    j, c1, o1, nan1 = _cell(ax1, x1, log1)
    refuse = _refuse(nan0 or nan1, o0 | o1, mode, counter)
    c = cells[i, j]
    d1 = c1 - ax1[j]
    e0, g0 = _line_grad(c, 0, d1)
    e1, g1 = _line_grad(c, 4, d1)
    e2, g2 = _line_grad(c, 8, d1)
    e3, g3 = _line_grad(c, 12, d1)
    d0 = c0 - ax0[i]
    u, u0 = _cubic_grad(e0, e1, e2, e3, d0)
    u1 = _cubic(g0, g1, g2, g3, d0)
    v, dvdu = _finish(u, logv)
    if refuse:
        return np.nan, np.nan, np.nan
    return v, dvdu * u0 * _dtdx_at(x0, c0, o0, log0), dvdu * u1 * _dtdx_at(x1, c1, o1, log1)


@njit(**_FMA)
def hermite2_cells(ax0, ax1, log0, log1, cells, logv, x0, x1, mode, counter):
    """v at (x0, x1); ``cells`` of shape (n0-1, n1-1, 16) from :func:`hermite_cells_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    j, c1, o1, nan1 = _cell(ax1, x1, log1)
    refuse = _refuse(nan0 or nan1, o0 | o1, mode, counter)
    c = cells[i, j]
    d1 = c1 - ax1[j]
    u = _cubic(_line(c, 0, d1), _line(c, 4, d1), _line(c, 8, d1), _line(c, 12, d1), c0 - ax0[i])
    if logv:
        u = math.exp(u)
    return np.nan if refuse else u


@njit(**_FMA)
def hermite3_cells_grad(ax0, ax1, ax2, log0, log1, log2, cells, logv, x0, x1, x2, mode, counter):
    """(v, dv/dx0, dv/dx1, dv/dx2); ``cells`` of shape (n0-1, n1-1, n2-1, 64) from :func:`hermite_cells_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    j, c1, o1, nan1 = _cell(ax1, x1, log1)
    k, c2, o2, nan2 = _cell(ax2, x2, log2)
    refuse = _refuse(nan0 or nan1 or nan2, o0 | o1 | o2, mode, counter)
    c = cells[i, j, k]
    d1 = c1 - ax1[j]
    d2 = c2 - ax2[k]
    a0, a1, a2 = _plane_grad(c, 0, d1, d2)
    b0, b1, b2 = _plane_grad(c, 16, d1, d2)
    e0, e1, e2 = _plane_grad(c, 32, d1, d2)
    f0, f1, f2 = _plane_grad(c, 48, d1, d2)
    d0 = c0 - ax0[i]
    u, u0 = _cubic_grad(a0, b0, e0, f0, d0)
    u1 = _cubic(a1, b1, e1, f1, d0)
    u2 = _cubic(a2, b2, e2, f2, d0)
    v, dvdu = _finish(u, logv)
    if refuse:
        return np.nan, np.nan, np.nan, np.nan
    return (v, dvdu * u0 * _dtdx_at(x0, c0, o0, log0), dvdu * u1 * _dtdx_at(x1, c1, o1, log1),
            dvdu * u2 * _dtdx_at(x2, c2, o2, log2))


@njit(**_FMA)
def hermite3_cells(ax0, ax1, ax2, log0, log1, log2, cells, logv, x0, x1, x2, mode, counter):
    """v at (x0, x1, x2); ``cells`` of shape (n0-1, n1-1, n2-1, 64) from :func:`hermite_cells_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    j, c1, o1, nan1 = _cell(ax1, x1, log1)
    k, c2, o2, nan2 = _cell(ax2, x2, log2)
    refuse = _refuse(nan0 or nan1 or nan2, o0 | o1 | o2, mode, counter)
    c = cells[i, j, k]
    d1 = c1 - ax1[j]
    d2 = c2 - ax2[k]
    f0 = _cubic(_line(c, 0, d2), _line(c, 4, d2), _line(c, 8, d2), _line(c, 12, d2), d1)
    f1 = _cubic(_line(c, 16, d2), _line(c, 20, d2), _line(c, 24, d2), _line(c, 28, d2), d1)
    f2 = _cubic(_line(c, 32, d2), _line(c, 36, d2), _line(c, 40, d2), _line(c, 44, d2), d1)
    f3 = _cubic(_line(c, 48, d2), _line(c, 52, d2), _line(c, 56, d2), _line(c, 60, d2), d1)
    u = _cubic(f0, f1, f2, f3, c0 - ax0[i])
    if logv:
        u = math.exp(u)
    return np.nan if refuse else u


@njit(**_JIT)
def cmany1(ax0, log0, cells, logv, points, mode, counter, out, grad):
    for q in range(points.shape[0]):
        r = hermite1_cells_grad(ax0, log0, cells, logv, points[q, 0], mode, counter)
        out[q] = r[0]
        grad[q, 0] = r[1]


@njit(**_JIT)
def cmany2(ax0, ax1, log0, log1, cells, logv, points, mode, counter, out, grad):
    for q in range(points.shape[0]):
        r = hermite2_cells_grad(ax0, ax1, log0, log1, cells, logv, points[q, 0], points[q, 1], mode, counter)
        out[q] = r[0]
        grad[q, 0] = r[1]
        grad[q, 1] = r[2]


@njit(**_JIT)
def cmany3(ax0, ax1, ax2, log0, log1, log2, cells, logv, points, mode, counter, out, grad):
    for q in range(points.shape[0]):
        r = hermite3_cells_grad(ax0, ax1, ax2, log0, log1, log2, cells, logv, points[q, 0], points[q, 1],
                                points[q, 2], mode, counter)
        out[q] = r[0]
        grad[q, 0] = r[1]
        grad[q, 1] = r[2]
        grad[q, 2] = r[3]


@njit(**_JIT)
def csum1(ax0, log0, cells, logv, xs, mode, counter):
    s = 0.0
    for q in range(xs.size):
        s += hermite1_cells(ax0, log0, cells, logv, xs[q], mode, counter)
    return s


@njit(**_JIT)
def csum2(ax0, ax1, log0, log1, cells, logv, points, mode, counter):
    s = 0.0
    for q in range(points.shape[0]):
        s += hermite2_cells(ax0, ax1, log0, log1, cells, logv, points[q, 0], points[q, 1], mode, counter)
    return s


@njit(**_JIT)
def csum3(ax0, ax1, ax2, log0, log1, log2, cells, logv, points, mode, counter):
    s = 0.0
    for q in range(points.shape[0]):
        s += hermite3_cells(ax0, ax1, ax2, log0, log1, log2, cells, logv, points[q, 0], points[q, 1], points[q, 2],
                            mode, counter)
    return s


@njit(**_JIT)
def cgsum3(ax0, ax1, ax2, log0, log1, log2, cells, logv, points, mode, counter):
    """:func:`hgsum3` for the per-cell variant."""
    s = 0.0
    for q in range(points.shape[0]):
        r = hermite3_cells_grad(ax0, ax1, ax2, log0, log1, log2, cells, logv, points[q, 0], points[q, 1],
                                points[q, 2], mode, counter)
        s += r[0] + r[1] + r[2] + r[3]
    return s
