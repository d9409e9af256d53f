r"""Elastic deflection of two half-spaces under a pressure field.

Combined normal surface displacement of both bodies (positive = the gap opens)::

    u(x) = 1/(pi E*) int p(x') / |x - x'| dA'           (point contacts)
    u(x) = -2/(pi E*) int p(s) ln|x - s| ds + const      (line contacts)

with 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson, *Contact Mechanics*,
1985, eqs. 3.19 and 2.25; Hamrock's reduced modulus is E' = 2 E*).

Discretisation: the pressure is piecewise constant on the cells of a uniform
tensor grid (cell centres at the grid nodes).  The influence coefficient of a
cell is the exact integral of the kernel over it:

- rectangle 2a x 2b about the origin, seen from (x, y) (Love 1929)::

      K(x, y) = 1/(pi E*) [F(x+a, y+b) - F(x+a, y-b) - F(x-a, y+b) + F(x-a, y-b)]
      F(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)    (terms -> 0 where X or Y = 0)

- strip of width 2a about the origin, seen from x::

      K(x) = -2/(pi E*) [G(x + a) - G(x - a)],   G(X) = X ln|X| - X

The convolution u_i = sum_j K_{i-j} p_j is evaluated by FFT on a grid padded
to twice the size with the kernel in wrap-around order (the "DC-FFT" of Liu,
Wang & Liu 2000, Wear 243: exact linear convolution, no periodic images), in
O(N log N); :meth:`ElasticKernel.deflect_direct` is the dense O(N^2) sum used
to check it.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.fft

from .errors import InputError, require_positive


def _F(X, Y):
    X = np.asarray(X, dtype=float)
    Y = np.asarray(Y, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        ax, ay = np.abs(X), np.abs(Y)
        t1 = np.where(ax > 0, X * np.arcsinh(Y / np.where(ax > 0, ax, 1.0)), 0.0)
        t2 = np.where(ay > 0, Y * np.arcsinh(X / np.where(ay > 0, ay, 1.0)), 0.0)
    return t1 + t2


def _G(X):
    X = np.asarray(X, dtype=float)
    ax = np.abs(X)
    return np.where(ax > 0, X * np.log(np.where(ax > 0, ax, 1.0)) - X, 0.0)


def rectangle_influence(x, y, a, b, e_star):
    """Displacement at (x, y) [m] per unit pressure on [-a, a] x [-b, b]."""
    return (
        _F(x + a, y + b) - _F(x + a, y - b) - _F(x - a, y + b) + _F(x - a, y - b)
    ) / (np.pi * e_star)


def strip_influence(x, a, e_star):
    """Displacement at x [m] per unit pressure on the strip [-a, a] (line contact)."""
    return -2.0 / (np.pi * e_star) * (_G(x + a) - _G(x - a))


def line_influence_matrix(x, e_star: float) -> np.ndarray:
    """Dense influence matrix of a line contact on the (possibly non-uniform) nodes ``x`` [m]:
    ``M @ p`` is the deflection at the nodes [m] for node pressures ``p`` [Pa], each held constant on
    the node's own cell, from the midpoint with its left neighbour to the midpoint with its right one
    (the end nodes' cells symmetric about them), integrated exactly::

        M_ij = -2/(pi E*) [G(x_i - l_j) - G(x_i - r_j)],   G(X) = X ln|X| - X

    On a uniform grid this is the Toeplitz kernel of :class:`ElasticKernel` (strips of width dx centred
    on the nodes) to round-off; on a graded grid the cell is centred on its node to O(dx^2) (smooth
    grading), and the deflection keeps second order.  O(N^2) storage and matvec: line grids of a few
    hundred to two thousand nodes."""
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 2 or np.any(np.diff(x) <= 0):
        raise InputError("line_influence_matrix: x must be increasing nodes (at least 2)")
    require_positive("reduced modulus E* [Pa]", e_star)
    mid = 0.5 * (x[1:] + x[:-1])
    left = np.concatenate([[x[0] - (mid[0] - x[0])], mid])
    right = np.concatenate([mid, [x[-1] + (x[-1] - mid[-1])]])
    centre, half = 0.5 * (left + right), 0.5 * (right - left)
    return strip_influence(x[:, None] - centre[None, :], half[None, :], e_star)


@dataclass
class ElasticKernel:
    """Influence coefficients of a uniform grid and their padded FFT.

    Parameters
    ----------
    shape : tuple
        Grid size ``(nx,)`` (line contact) or ``(nx, ny)`` (point contact).
    spacing : tuple
        Cell sizes ``(dx,)`` or ``(dx, dy)`` [m].
    e_star : float
        Reduced modulus E* [Pa] (see :func:`lubedyn.lubrication.laws.contact.reduced_modulus`).
    """

    shape: tuple
    spacing: tuple
    e_star: float
    _spectrum: np.ndarray = field(init=False, repr=False)
    _kernel: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        self.shape = tuple(int(n) for n in self.shape)
        self.spacing = tuple(float(d) for d in self.spacing)
        if len(self.shape) not in (1, 2) or len(self.spacing) != len(self.shape):
            raise InputError(f"grid shape {self.shape} and spacing {self.spacing} must both be 1-D or 2-D")
        require_positive("reduced modulus E* [Pa]", self.e_star)
        offsets = [np.arange(-(n - 1), n) * d for n, d in zip(self.shape, self.spacing)]
        if len(self.shape) == 1:
            K = strip_influence(offsets[0], self.spacing[0] / 2, self.e_star)
        else:
            X, Y = np.meshgrid(offsets[0], offsets[1], indexing="ij")
            K = rectangle_influence(X, Y, self.spacing[0] / 2, self.spacing[1] / 2, self.e_star)
        self._kernel = K  # offsets -(n-1) .. (n-1) per axis
        self._spectrum = self.padded_spectrum(tuple(2 * n for n in self.shape))

    def padded_spectrum(self, shape: tuple) -> np.ndarray:
        """rfftn of the influence coefficients on a zero-padded grid of ``shape``
        (each length >= 2n - 1; offset k at index k mod length, the wrap-around
        order of the DC-FFT): ``irfftn(rfftn(p, s=shape) * this, s=shape)`` cut
        to the grid is the deflection.  :meth:`deflect` uses 2n; lengths from
        ``scipy.fft.next_fast_len`` avoid large prime factors (2n = 514 has 257)."""
        if any(q < 2 * n - 1 for q, n in zip(shape, self.shape)):
            raise InputError(f"padded FFT shape {shape} must be at least 2n - 1 = "
                             f"{tuple(2 * n - 1 for n in self.shape)} per axis")
        padded = np.zeros(shape)
        idx = [np.arange(-(n - 1), n) % q for n, q in zip(self.shape, shape)]
        padded[np.ix_(*idx)] = self._kernel
        return scipy.fft.rfftn(padded)

    def deflect(self, p: np.ndarray) -> np.ndarray:
        """Displacement u [m] on the grid for cell pressures ``p`` [Pa] (FFT)."""
        p = np.asarray(p, dtype=float)
        if p.shape != self.shape:
            raise InputError(f"pressure grid shape {p.shape} does not match the kernel's {self.shape}")
        full = tuple(2 * n for n in self.shape)
        u = scipy.fft.irfftn(scipy.fft.rfftn(p, s=full) * self._spectrum, s=full)
        return u[tuple(slice(0, n) for n in self.shape)]

    def deflect_direct(self, p: np.ndarray) -> np.ndarray:
        """Dense O(N^2) sum of the same influence coefficients (for checks)."""
        p = np.asarray(p, dtype=float)
        K = self._kernel
        if len(self.shape) == 1:
            n = self.shape[0]
            i = np.arange(n)
            return K[(i[:, None] - i[None, :]) + n - 1] @ p
        nx, ny = self.shape
        ix, iy = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
        ix, iy = ix.ravel(), iy.ravel()
        M = K[ix[:, None] - ix[None, :] + nx - 1, iy[:, None] - iy[None, :] + ny - 1]
        return (M @ p.ravel()).reshape(self.shape)
