"""Compiled kernels of the structured Reynolds path (:mod:`lubedyn.lubrication.reynolds.tensor`): P1 on a tensor
grid, node (i, j) = dof i * ny1 + j, cell (i, j) = element i * (ny1 - 1) + j, corners a = 2 ax + ay at node
(i + ax, j + ay).  ``w`` (nqp,): quadrature weights on the unit square; ``phi``, ``ds``, ``dt`` (4, nqp): the
corners' bilinear basis and its derivatives along x and y on the unit square.  Each cell's integrals are its
unit-square ones scaled by h_x h_y and 1/h_x, 1/h_y.

One pass over the cells (16 local pairs, or 4 corners), adding into the nodes' 9-point stencils; the
stencils are then written as CSR rows in increasing column order.  Loops rather than numpy array
expressions: on the 1M-DOF benchmark the array version (a (cells, 4) x (4, 16) matrix product, 16 strided
slice additions, boolean compression) took 0.9 s single-threaded and 1.3 s with OpenBLAS threads on a
busy machine; these loops take a fraction of that (``benchmarks/reynolds.py``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from lubedyn.lubrication.laws.jit import JIT

_AX = (0, 0, 1, 1)
_AY = (0, 1, 0, 1)


@njit(**JIT)
def diffusion_csr(xs, ys, a, w, ds, dt, indptr, indices, data):
    """The matrix of int a grad u . grad v (``a``: (cells, nqp)) into CSR arrays (``indptr`` (N+1,), ``indices``
    and ``data`` of length :func:`stencil_nnz`)."""
    nx1, ny1 = xs.size, ys.size
    nq = w.size
    stencil = np.zeros((nx1 * ny1, 9))
    loc = np.empty(16)
    for i in range(nx1 - 1):
        hx = xs[i + 1] - xs[i]
        for j in range(ny1 - 1):
            hy = ys[j + 1] - ys[j]
            c = i * (ny1 - 1) + j
            rx, ry = hy / hx, hx / hy
            for p in range(16):
                loc[p] = 0.0
            for q in range(nq):
                aq = a[c, q] * w[q]
                for ca in range(4):
                    sa, ta = ds[ca, q] * aq, dt[ca, q] * aq
                    for cb in range(4):
                        loc[4 * ca + cb] += (sa * ds[cb, q]) * rx + (ta * dt[cb, q]) * ry
            for ca in range(4):
                node = (i + _AX[ca]) * ny1 + j + _AY[ca]
                for cb in range(4):
                    stencil[node, (_AX[cb] - _AX[ca] + 1) * 3 + (_AY[cb] - _AY[ca] + 1)] += loc[4 * ca + cb]
    k = 0
    indptr[0] = 0
    for i in range(nx1):
        for j in range(ny1):
            node = i * ny1 + j
            for di in range(-1, 2):
                if 0 <= i + di < nx1:
                    for dj in range(-1, 2):
                        if 0 <= j + dj < ny1:
                            indices[k] = node + di * ny1 + dj
                            data[k] = stencil[node, (di + 1) * 3 + dj + 1]
                            k += 1
            indptr[node + 1] = k


def stencil_nnz(nx1: int, ny1: int) -> int:
    """Entries of the 9-point matrix of an nx1 x ny1 node grid."""
    return (3 * nx1 - 2) * (3 * ny1 - 2)


@njit(**JIT)
def flux_load(xs, ys, f, w, ds, dt, out):
    """Add int f . grad v (``f``: (2, cells, nqp)) into ``out`` (N,)."""
    ny1 = ys.size
    for i in range(xs.size - 1):
        hx = xs[i + 1] - xs[i]
        for j in range(ny1 - 1):
            hy = ys[j + 1] - ys[j]
            c = i * (ny1 - 1) + j
            for ca in range(4):
                s = 0.0
                for q in range(w.size):
                    s += (f[0, c, q] * ds[ca, q] * hy + f[1, c, q] * dt[ca, q] * hx) * w[q]
                out[(i + _AX[ca]) * ny1 + j + _AY[ca]] += s


@njit(**JIT)
def source_load(xs, ys, g, w, phi, out):
    """Add int g v (``g``: (cells, nqp)) into ``out`` (N,)."""
    ny1 = ys.size
    for i in range(xs.size - 1):
        hx = xs[i + 1] - xs[i]
        for j in range(ny1 - 1):
            area = hx * (ys[j + 1] - ys[j])
            c = i * (ny1 - 1) + j
            for ca in range(4):
                s = 0.0
                for q in range(w.size):
                    s += g[c, q] * phi[ca, q] * w[q]
                out[(i + _AX[ca]) * ny1 + j + _AY[ca]] += s * area
