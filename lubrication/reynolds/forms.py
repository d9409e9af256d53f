"""Weak forms of the Reynolds equation on scikit-fem bases, and field interpolation (shared with EHL).

Part of :mod:`lubedyn.lubrication.reynolds` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import skfem
from skfem import BilinearForm, LinearForm
from skfem.helpers import dot, grad

from .. import mesh as meshes
from ..errors import InputError

# --------------------------------------------------------------------------
# small generic forms (coefficients are arrays at quadrature points)


@BilinearForm
def diffusion_form(u, v, w):
    """int a grad u . grad v (``a``: scalar at the quadrature points)."""
    return w["a"] * dot(grad(u), grad(v))


@BilinearForm
def advection_form(u, v, w):
    """int u b . grad v (``b``: vector at the quadrature points)."""
    return u * dot(w["b"], grad(v))


@BilinearForm
def mass_form(u, v, w):
    """int c u v (``c``: scalar at the quadrature points)."""
    return w["c"] * u * v


@BilinearForm
def streamline_form(u, v, w):
    """int s (beta . grad u)(beta . grad v): streamline diffusion along ``beta`` with weight ``s``."""
    return w["s"] * dot(w["beta"], grad(u)) * dot(w["beta"], grad(v))


@LinearForm
def flux_load_form(v, w):
    """int f . grad v (``f``: vector at the quadrature points)."""
    return dot(w["f"], grad(v))


@LinearForm
def source_load_form(v, w):
    """int g v (``g``: scalar at the quadrature points)."""
    return w["g"] * v


# --------------------------------------------------------------------------
# the hot forms of the Reynolds solve, assembled without scikit-fem's generic
# path: the same numbers (the same products and sums in the same order, so the
# same matrix and vectors bit for bit; tests/test_reynolds_fast_paths.py compares
# them with asm on line, triangle, quad, P2, curved and periodic meshes)


def _local_arrays(basis, i):
    phi = basis.basis[i][0]
    return np.asarray(phi), np.asarray(phi.grad)


def assemble_diffusion(basis, a) -> sp.csr_matrix:
    """``asm(diffusion_form, basis, a=a).tocsr()``: the matrix of int a grad u . grad v.

    ``a``: array (nelems, nqp) at the quadrature points.  Why not ``asm``: on the
    1M-DOF P1 benchmark (1000 x 1000 quads, benchmarks/reynolds.py, profiled there) the
    form kernel evaluated all 16 local pairs through ``DiscreteField`` arithmetic (ndarray
    subclass wrapping, a large share of the assembly), and ``eliminate_zeros`` copied the 16M COO entries even
    when none is zero.  Here the kernel is evaluated on plain arrays for i <= j only
    (a grad phi_j . grad phi_i is symmetric bit for bit: the products commute), zeros
    are removed only if there are any, and the COO triplets are laid out exactly as
    scikit-fem lays them out (block ``j * nbfun + i``: rows = dofs of i, columns =
    dofs of j), so scipy's COO -> CSR conversion sums the duplicates in the same order.
    """
    nb, nt = basis.Nbfun, basis.nelems
    a = np.asarray(a)
    dx = np.asarray(basis.dx)
    grads = [_local_arrays(basis, i)[1] for i in range(nb)]
    ed = np.asarray(basis.element_dofs)
    data = np.empty((nb, nb, nt))
    for j in range(nb):
        for i in range(j + 1):
            data[j, i] = np.sum(a * dot(grads[j], grads[i]) * dx, axis=1)
            if i != j:
                data[i, j] = data[j, i]
    index = np.int32 if basis.N < np.iinfo(np.int32).max else np.int64  # what scipy would pick
    rows = np.empty((nb, nb, nt), dtype=index)
    cols = np.empty((nb, nb, nt), dtype=index)
    rows[...] = ed[None, :, :]  # block (j, i): element_dofs[i]
    cols[...] = ed[:, None, :]  # block (j, i): element_dofs[j]
    rows, cols, data = rows.ravel(), cols.ravel(), data.ravel()
    nonzero = data != 0
    if not np.all(nonzero):  # what scikit-fem's eliminate_zeros does before the conversion
        data, rows, cols = data[nonzero], rows[nonzero], cols[nonzero]
    return sp.coo_matrix((data, (rows, cols)), shape=(basis.N, basis.N)).tocsr()


def _load_vector(basis, local) -> np.ndarray:
    """Sum the local load vectors ``local(i) -> (nelems,)`` into the global one in
    scikit-fem's COO order (block i: dofs of basis function i), as its ``toarray``
    does (one pass, in order: ``np.bincount`` adds its weights in input order)."""
    rows = np.asarray(basis.element_dofs).ravel()
    data = np.concatenate([local(i) for i in range(basis.Nbfun)])
    return np.bincount(rows, weights=data, minlength=basis.N)


def assemble_flux_load(basis, f) -> np.ndarray:
    """``asm(flux_load_form, basis, f=f)``: the vector of int f . grad v, ``f`` (dim, nelems,
    nqp).  Same numbers; without ``asm``'s ``DiscreteField`` wrapping (see
    :func:`assemble_diffusion`)."""
    f = np.asarray(f)
    dx = np.asarray(basis.dx)
    return _load_vector(basis, lambda i: np.sum(dot(f, _local_arrays(basis, i)[1]) * dx, axis=1))


def assemble_source_load(basis, g) -> np.ndarray:
    """``asm(source_load_form, basis, g=g)``: the vector of int g v, ``g`` (nelems, nqp)."""
    g = np.asarray(g)
    dx = np.asarray(basis.dx)
    return _load_vector(basis, lambda i: np.sum(g * _local_arrays(basis, i)[0] * dx, axis=1))


# (cell kind, element order) -> scikit-fem element class
ELEMENTS = {
    ("line", "P1"): skfem.ElementLineP1,
    ("line", "P2"): skfem.ElementLineP2,
    ("tri", "P1"): skfem.ElementTriP1,
    ("tri", "P2"): skfem.ElementTriP2,
    ("quad", "P1"): skfem.ElementQuad1,
    ("quad", "P2"): skfem.ElementQuad2,
}


def cell_kind(mesh) -> str:
    """``"line"``, ``"tri"`` or ``"quad"``: the key of :data:`ELEMENTS` for ``mesh``."""
    if isinstance(mesh, skfem.MeshLine1):
        return "line"
    if isinstance(mesh, skfem.MeshTri1):
        return "tri"
    if isinstance(mesh, skfem.MeshQuad1):
        return "quad"
    raise InputError(f"mesh type {type(mesh).__name__} is not supported; use line, triangle or quad meshes")


class _InverseJacobianOnce:
    """A scikit-fem mapping that computes ``invDF(X, tind)`` once for the same ``X`` and
    ``tind`` objects and delegates everything else.

    Why: scikit-fem's ``ElementH1.gbasis`` asks the mapping for ``invDF`` once per basis
    function, and the isoparametric (quad) mapping recomputes the inverse Jacobian every
    time: four times the same work on a quad mesh, a visible share of building the basis
    of the 1M-DOF benchmark (benchmarks/reynolds.py).  Used only while :func:`make_basis` builds the basis (which then
    gets the mesh's own mapping back), so the cached array does not outlive it.  The same
    numbers: the one computation is scikit-fem's own.
    """

    def __init__(self, mapping):
        self._mapping = mapping
        self._key = None
        self._value = None

    def __getattr__(self, name):
        return getattr(self._mapping, name)

    def invDF(self, X, tind=None):
        if self._key is None or self._key[0] is not X or self._key[1] is not tind:
            self._key, self._value = (X, tind), self._mapping.invDF(X, tind)
        return self._value


def make_basis(mesh, element: str = "P1") -> skfem.CellBasis:
    """The scalar Lagrange basis (``P1``/``P2``) of ``mesh``; the inverse Jacobians
    computed once for all basis functions (:class:`_InverseJacobianOnce`)."""
    elem = ELEMENTS[(cell_kind(mesh), element)]()
    intorder = 4 if element == "P2" else 3
    mapping = mesh.mapping()
    basis = skfem.Basis(mesh, elem, mapping=_InverseJacobianOnce(mapping), intorder=intorder)
    basis.mapping = mapping
    return basis


def unwrapped_dofs(basis) -> tuple[skfem.Mesh, np.ndarray]:
    """``(mesh, index)``: the unwrapped mesh of ``basis`` (:func:`lubedyn.lubrication.mesh.unwrapped`)
    and, for a field u of ``basis``, ``u[index]`` is the same field for
    ``basis.elem`` on that mesh.  On non-periodic meshes: the mesh itself and
    the identity."""
    mesh = meshes.unwrapped(basis.mesh)
    if mesh is basis.mesh:
        return mesh, np.arange(basis.N)
    dofs = skfem.Dofs(mesh, basis.elem)
    index = np.empty(dofs.N, dtype=np.int64)
    index[dofs.element_dofs] = basis.element_dofs  # same elements, same local order
    return mesh, index


def interpolate(basis, u, zero: bool = False) -> skfem.element.DiscreteField:
    """Scalar field ``u`` (values at the dofs of ``basis``) and its gradient at
    the quadrature points: sum_i u[element_dofs[i]] phi_i(x_q).

    The same numbers as ``basis.interpolate(u)`` (same sum in the same order),
    without the ``np.unique`` over all element dofs that scikit-fem spends on
    splitting a vector field.  ``zero=True``: ``u`` is known to be zero; return
    zero arrays without the sum.
    """
    ed = basis.element_dofs
    ref = basis.basis[0][0]
    if zero:
        return skfem.element.DiscreteField(np.zeros(ref.shape), np.zeros(ref.grad.shape))
    value = np.zeros(ref.shape)
    grad_ = np.zeros(ref.grad.shape)
    for i in range(ed.shape[0]):
        phi = basis.basis[i][0]
        ui = u[ed[i]][:, None]
        value += ui * np.asarray(phi)
        grad_ += ui * phi.grad
    return skfem.element.DiscreteField(value, grad_)


def as_vector_field(value, x, dim, key):
    """``value`` (a constant vector of ``dim`` components or ``f(x)``) evaluated at the points ``x``
    (shape ``(dim, ...)``); ``key`` names the input in the error message."""
    if callable(value):
        out = np.asarray(value(x), dtype=float)
    else:
        arr = np.atleast_1d(np.asarray(value, dtype=float))
        if arr.size == 1 and dim > 1 and float(arr[0]) == 0.0:
            arr = np.zeros(dim)
        if arr.shape != (dim,):
            raise InputError(f"{key} = {value!r} must have {dim} component(s) for a {dim}-D film")
        out = np.empty(x.shape)  # one pass (not arr * ones: two arrays and two passes, same values)
        out[...] = arr.reshape((dim,) + (1,) * (x.ndim - 1))
    if out.shape != x.shape:
        raise InputError(f"{key} returned shape {out.shape}, expected {x.shape}")
    return out


def as_scalar_field(value, x, key):
    """``value`` (a number or ``f(x)``) evaluated at the points ``x`` (shape ``(dim, ...)``, result
    ``x.shape[1:]``); ``key`` names the input in the error message."""
    if callable(value):
        out = np.asarray(value(x), dtype=float)
    else:
        out = np.full(x.shape[1:], float(value))
    if out.shape != x.shape[1:]:
        raise InputError(f"{key} returned shape {out.shape}, expected {x.shape[1:]}")
    return out
