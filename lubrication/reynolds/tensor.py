"""The structured path of the Reynolds solve: P1 on a tensor-product quad mesh.

Part of :mod:`lubedyn.lubrication.reynolds` (the package docstring gives the equations and sources).

When a film's mesh is a plain (not periodic) quad mesh of :func:`lubedyn.lubrication.mesh.rectangle`
(``skfem.MeshQuad.init_tensor``'s vertex and element order, checked by :func:`tensor_grid`) and the
element is P1, the solver uses this module instead of scikit-fem's generic path for the parts that cost
time at a million unknowns (issue 42, decision 6; profiled in ``benchmarks/reynolds.py``):

* **Quadrature points** from the axes (x = x_i + X_1 h_x, y = y_j + X_0 h_y with scikit-fem's own
  2 x 2 Gauss rule of order 3, in its element and point order) instead of the isoparametric mapping of
  a scikit-fem basis; the basis itself is built only if something asks for it (outputs, nonlinear
  lubricants, cavitation's advection terms).
* **Assembly** of the diffusion matrix and the two load vectors in one compiled pass over the cells
  (:mod:`lubedyn.lubrication.reynolds._tensor_kernels`: the bilinear basis' gradients at the Gauss points
  are the same for every cell up to 1/h_x, 1/h_y), added into the nodes' 9-point stencils and written as
  CSR directly (no COO -> CSR conversion of 16 entries per cell).  The same integrals as scikit-fem's
  assembly, summed in another order: equal to rounding (``tests/test_reynolds_tensor.py``).
* **Geometric multigrid** (:meth:`TensorGrid.multigrid`, one V-cycle in float32 per CG iteration:
  :meth:`TensorGrid.preconditioner`) as the CG preconditioner of the symmetric systems above
  ``DIRECT_SOLVER_MAX_DOFS``: linear interpolation along each axis between every second
  grid line (by the coordinates, so graded axes are interpolated exactly for linear fields), Galerkin
  coarse operators P^T A P, symmetric Gauss-Seidel, all through pyamg's ``MultilevelSolver`` -- no
  strength-of-connection or C/F splitting to compute, which were most of the Ruge-Stuben setup.  Rows
  and columns of the reduced system (Dirichlet, cavitated nodes removed) are taken from the full
  grid's operators, so any fixed set is handled.

Anything else (periodic, triangles, P2, graded or not) takes the general scikit-fem path.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
import skfem

from ._tensor_kernels import diffusion_csr, stencil_nnz
from ._tensor_kernels import flux_load as flux_load_kernel
from ._tensor_kernels import source_load as source_load_kernel

MULTIGRID_MAX_COARSE = 2000  # unknowns of the coarsest multigrid level at most (SuperLU there)
_CORNERS = [(0, 0), (0, 1), (1, 0), (1, 1)]  # corner a = (ax, ay) of a cell: node (i + ax, j + ay)


def tensor_grid(mesh, element: str) -> "TensorGrid | None":
    """The :class:`TensorGrid` of ``mesh`` if it is a plain P1 quad mesh in ``MeshQuad.init_tensor``'s order
    on some axes (what :func:`lubedyn.lubrication.mesh.rectangle` builds without ``periodic_x``), else None.

    Checked exactly, in vectorised passes over the vertices and elements (tens of milliseconds at a
    million cells): the vertex coordinates are the tensor product of the axes in that order, and the
    elements are the cells in that order with scikit-fem's vertex order."""
    if element != "P1" or type(mesh) is not skfem.MeshQuad1:
        return None
    p, t = mesh.p, mesh.t
    if p.shape[0] != 2:
        return None
    ny1 = int(np.argmax(p[0] != p[0, 0]))  # the first column of vertices: x = x_0 (0 if every x is equal)
    if ny1 < 2 or p.shape[1] % ny1:
        return None
    ys = p[1, :ny1]
    nx1 = p.shape[1] // ny1
    xs = p[0, ::ny1]
    if nx1 < 2 or not (np.all(np.diff(xs) > 0) and np.all(np.diff(ys) > 0)):
        return None
    grid = p.reshape(2, nx1, ny1)
    if not (np.array_equal(grid[0], np.broadcast_to(xs[:, None], (nx1, ny1)))
            and np.array_equal(grid[1], np.broadcast_to(ys[None, :], (nx1, ny1)))):
        return None
    nx, ny = nx1 - 1, ny1 - 1
    if t.shape != (4, nx * ny):
        return None
    first = (np.arange(nx)[:, None] * ny1 + np.arange(ny)[None, :]).ravel()  # node (i, j) of cell (i, j)
    for row, shift in zip(t, (0, 1, ny1 + 1, ny1)):  # scikit-fem's order: (i,j), (i,j+1), (i+1,j+1), (i+1,j)
        if not np.array_equal(row, first + shift):
            return None
    return TensorGrid(np.ascontiguousarray(xs), np.ascontiguousarray(ys))


@dataclass(frozen=True, eq=False)
class TensorGrid:
    """A P1 tensor grid: node (i, j) at (xs[i], ys[j]) is dof ``i * len(ys) + j``; cell (i, j) is element
    ``i * (len(ys) - 1) + j``; quadrature: scikit-fem's rule of order 3 on the reference square."""

    xs: np.ndarray
    ys: np.ndarray

    @property
    def shape(self) -> tuple[int, int]:
        return self.xs.size, self.ys.size

    @property
    def N(self) -> int:
        return self.xs.size * self.ys.size

    @cached_property
    def _rule(self):
        """(X (2, nqp), W (nqp,), phi (4, nqp), d/ds (4, nqp), d/dt (4, nqp)) of the four corners."""
        X, W = skfem.quadrature.get_quadrature(skfem.refdom.RefQuad, 3)
        t, s = X  # init_tensor's vertex order maps the reference X_0 along y and X_1 along x
        lin = (1.0 - s, s), (1.0 - t, t)
        dlin = (-np.ones_like(s), np.ones_like(s)), (-np.ones_like(t), np.ones_like(t))
        phi = np.array([lin[0][ax] * lin[1][ay] for ax, ay in _CORNERS])
        ds = np.array([dlin[0][ax] * lin[1][ay] for ax, ay in _CORNERS])
        dt = np.array([lin[0][ax] * dlin[1][ay] for ax, ay in _CORNERS])
        return X, W, phi, ds, dt

    def quadrature_points(self) -> np.ndarray:
        """(2, nelems, nqp): the quadrature points in scikit-fem's element and point order."""
        X = self._rule[0]
        hx, hy = np.diff(self.xs), np.diff(self.ys)
        nx, ny, nq = hx.size, hy.size, X.shape[1]
        out = np.empty((2, nx, ny, nq))
        out[0] = self.xs[:-1, None, None] + X[1][None, None, :] * hx[:, None, None]
        out[1] = self.ys[None, :-1, None] + X[0][None, None, :] * hy[None, :, None]
        return out.reshape(2, nx * ny, nq)

    def boundary_dofs(self) -> np.ndarray:
        """Sorted dofs of the nodes on the rectangle's boundary."""
        nx1, ny1 = self.shape
        on = np.zeros((nx1, ny1), dtype=bool)
        on[[0, -1], :] = True
        on[:, [0, -1]] = True
        return np.flatnonzero(on)

    def _arrays(self):
        _, W, phi, ds, dt = self._rule
        return self.xs, self.ys, np.ascontiguousarray(W), np.ascontiguousarray(phi), np.ascontiguousarray(ds), \
            np.ascontiguousarray(dt)

    def diffusion(self, a) -> sp.csr_matrix:
        """The matrix of int a grad u . grad v for ``a`` (nelems, nqp) at the quadrature points."""
        xs, ys, W, _, ds, dt = self._arrays()
        nnz = stencil_nnz(xs.size, ys.size)
        index = np.int32 if nnz < np.iinfo(np.int32).max else np.int64
        indptr, indices, data = np.empty(self.N + 1, dtype=index), np.empty(nnz, dtype=index), np.empty(nnz)
        diffusion_csr(xs, ys, np.ascontiguousarray(a, dtype=float), W, ds, dt, indptr, indices, data)
        A = sp.csr_matrix((data, indices, indptr), shape=(self.N, self.N), copy=False)
        A.has_sorted_indices = True  # the kernel writes each row's columns in increasing order
        return A

    def flux_load(self, f) -> np.ndarray:
        """The vector of int f . grad v, ``f`` (2, nelems, nqp)."""
        xs, ys, W, _, ds, dt = self._arrays()
        out = np.zeros(self.N)
        flux_load_kernel(xs, ys, np.ascontiguousarray(f, dtype=float), W, ds, dt, out)
        return out

    def source_load(self, g) -> np.ndarray:
        """The vector of int g v, ``g`` (nelems, nqp)."""
        xs, ys, W, phi, _, _ = self._arrays()
        out = np.zeros(self.N)
        source_load_kernel(xs, ys, np.ascontiguousarray(g, dtype=float), W, phi, out)
        return out

    def _corners(self, u):
        """The values of the dof vector ``u`` at each cell's four corners, (4, nelems)."""
        nx1, ny1 = self.shape
        U = np.asarray(u, dtype=float).reshape(nx1, ny1)
        return np.stack([U[ax:ax + nx1 - 1, ay:ay + ny1 - 1].ravel() for ax, ay in _CORNERS])

    def interpolate(self, u) -> skfem.element.DiscreteField:
        """``u`` (dofs) and its gradient at the quadrature points: sum over the corners of u phi_a, as
        :func:`lubedyn.lubrication.reynolds.forms.interpolate` on the basis (equal to rounding)."""
        _, _, phi, ds, dt = self._rule
        hx, hy = np.diff(self.xs), np.diff(self.ys)
        c = self._corners(u)
        # sums over the 4 corners written out: a (cells, 4) x (4, nqp) BLAS product is slower than this on a
        # busy machine (threads for an inner dimension of 4)
        value = sum(c[a][:, None] * phi[a][None, :] for a in range(4))
        gs = sum(c[a][:, None] * ds[a][None, :] for a in range(4))
        gt = sum(c[a][:, None] * dt[a][None, :] for a in range(4))
        grad = np.stack([gs / np.repeat(hx, hy.size)[:, None], gt / np.tile(hy, hx.size)[:, None]])
        return skfem.element.DiscreteField(value, grad)

    def integrate(self, f) -> float:
        """Integral over the grid of ``f`` (nelems, nqp) at the quadrature points."""
        W = self._rule[1]
        area = np.outer(np.diff(self.xs), np.diff(self.ys)).ravel()
        f = np.asarray(f)
        return float(np.sum(sum(f[:, q] * W[q] for q in range(W.size)) * area))

    # ------------------------------------------------------------------ geometric multigrid
    def preconditioner(self, A, index):
        """One V-cycle of :meth:`multigrid` in single precision, as a float64 ``LinearOperator`` for CG on ``A``.

        The hierarchy is built for ``A`` scaled by 1/max|diag A| in float32 (the scaling keeps any film's
        coefficients inside float32's range; the operator scales back), and each residual is cast to
        float32 after dividing it by its norm (a linear operator still, to rounding).  CG itself runs in
        float64 on ``A``, so the solution meets ``amg_tol`` as before.  At 1M DOFs (the benchmark's slider) setup
        and CG took 2.40 s CPU against 2.71 s with the float64 hierarchy, the same 7 CG iterations and the
        same final residual (median of 4 interleaved, loaded machine; ``benchmarks/HISTORY.md``, issue 42)."""
        from scipy.sparse.linalg import LinearOperator

        A = A.tocsr()
        scale = 1.0 / np.max(np.abs(A.diagonal()))
        single = sp.csr_matrix(((A.data * scale).astype(np.float32), A.indices, A.indptr), shape=A.shape)
        cycle = self.multigrid(single, index).aspreconditioner()

        def apply(r):
            r = np.ravel(r)
            norm = np.linalg.norm(r)
            if norm == 0.0:
                return np.zeros_like(r)
            return (cycle @ (r / norm).astype(np.float32)).astype(np.float64) * (norm * scale)

        return LinearOperator(A.shape, matvec=apply, dtype=np.float64)

    def multigrid(self, A, index, max_coarse: int | None = None):
        """A pyamg ``MultilevelSolver`` for ``A``, the grid's matrix restricted to the dofs ``index`` (sorted).

        Levels: every second grid line of each axis with more than 2 cells (the last line always kept),
        linear interpolation between them by the coordinates (a tensor product of the two 1-D
        interpolations), restricted to the kept dofs of each level (a coarse node is kept where its fine
        node is); Galerkin coarse operators (in ``A``'s precision); symmetric Gauss-Seidel before and
        after; SuperLU on the coarsest level (at most ``max_coarse`` unknowns, default :data:`MULTIGRID_MAX_COARSE`, or where no axis can be
        coarsened)."""
        from pyamg.multilevel import MultilevelSolver
        from pyamg.relaxation.smoothing import change_smoothers

        max_coarse = MULTIGRID_MAX_COARSE if max_coarse is None else max_coarse
        axes = (self.xs, self.ys)
        keep = np.zeros(self.N, dtype=bool)
        keep[index] = True
        levels = [MultilevelSolver.Level()]
        levels[0].A = A.tocsr()
        dtype = levels[0].A.dtype
        while levels[-1].A.shape[0] > max_coarse:
            picks = [_coarse_lines(a.size) for a in axes]
            if all(p.size == a.size for p, a in zip(picks, axes)):
                break
            P_full = sp.kron(_interpolation(axes[0], picks[0]), _interpolation(axes[1], picks[1]), format="csr")
            coarse_keep = keep.reshape(axes[0].size, axes[1].size)[np.ix_(picks[0], picks[1])].ravel()
            if not np.any(coarse_keep):  # no kept dof on the coarse lines (a scattered active set): stop here
                break
            P = P_full[keep][:, coarse_keep].tocsr().astype(dtype)
            R = P.T.tocsr()
            levels[-1].P, levels[-1].R = P, R
            levels.append(MultilevelSolver.Level())
            levels[-1].A = (R @ (levels[-2].A @ P)).tocsr()
            axes = tuple(a[p] for a, p in zip(axes, picks))
            keep = coarse_keep
        ml = MultilevelSolver(levels, coarse_solver="splu")
        change_smoothers(ml, ("gauss_seidel", {"sweep": "symmetric"}), ("gauss_seidel", {"sweep": "symmetric"}))
        return ml


def _coarse_lines(n: int) -> np.ndarray:
    """Indices of every second of ``n`` grid lines, the last one always kept; all of them below 4 lines."""
    if n < 4:
        return np.arange(n)
    pick = np.arange(0, n, 2)
    return pick if pick[-1] == n - 1 else np.append(pick, n - 1)


def _interpolation(x, pick) -> sp.csr_matrix:
    """(len(x), len(pick)): linear interpolation in the coordinate ``x`` from the lines ``pick``."""
    n, m = x.size, pick.size
    if m == n:
        return sp.identity(n, format="csr")
    seg = np.clip(np.searchsorted(pick, np.arange(n), side="right") - 1, 0, m - 2)
    w = (x - x[pick[seg]]) / (x[pick[seg + 1]] - x[pick[seg]])
    rows = np.concatenate([np.arange(n), np.arange(n)])
    cols = np.concatenate([seg, seg + 1])
    vals = np.concatenate([1.0 - w, w])
    nz = vals != 0.0
    return sp.csr_matrix((vals[nz], (rows[nz], cols[nz])), shape=(n, m))
