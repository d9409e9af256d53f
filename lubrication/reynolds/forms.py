"""Weak forms of the Reynolds equation on scikit-fem bases, and field interpolation (shared with EHL).

Part of :mod:`lubrication.reynolds` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import numpy as np
import skfem
from skfem import BilinearForm, LinearForm
from skfem.helpers import dot, grad

from .. import mesh as meshes
from ..errors import InputError

# --------------------------------------------------------------------------
# small generic forms (coefficients are arrays at quadrature points)


@BilinearForm
def _diffusion(u, v, w):
    return w["a"] * dot(grad(u), grad(v))


@BilinearForm
def _advection(u, v, w):
    return u * dot(w["b"], grad(v))


@BilinearForm
def _mass(u, v, w):
    return w["c"] * u * v


@BilinearForm
def _streamline(u, v, w):
    return w["s"] * dot(w["beta"], grad(u)) * dot(w["beta"], grad(v))


@LinearForm
def _flux_load(v, w):
    return dot(w["f"], grad(v))


@LinearForm
def _source_load(v, w):
    return w["g"] * v


_ELEMENTS = {
    ("line", "P1"): skfem.ElementLineP1,
    ("line", "P2"): skfem.ElementLineP2,
    ("tri", "P1"): skfem.ElementTriP1,
    ("tri", "P2"): skfem.ElementTriP2,
    ("quad", "P1"): skfem.ElementQuad1,
    ("quad", "P2"): skfem.ElementQuad2,
}


def _cell_kind(mesh) -> str:
    if isinstance(mesh, skfem.MeshLine1):
        return "line"
    if isinstance(mesh, skfem.MeshTri1):
        return "tri"
    if isinstance(mesh, skfem.MeshQuad1):
        return "quad"
    raise InputError(f"mesh type {type(mesh).__name__} is not supported; use line, triangle or quad meshes")


def make_basis(mesh, element: str = "P1") -> skfem.CellBasis:
    """The scalar Lagrange basis (``P1``/``P2``) of ``mesh``."""
    elem = _ELEMENTS[(_cell_kind(mesh), element)]()
    intorder = 4 if element == "P2" else 3
    return skfem.Basis(mesh, elem, intorder=intorder)


def unwrapped_dofs(basis) -> tuple[skfem.Mesh, np.ndarray]:
    """``(mesh, index)``: the unwrapped mesh of ``basis`` (:func:`lubrication.mesh.unwrapped`)
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


def _as_vector_field(value, x, dim, key):
    if callable(value):
        out = np.asarray(value(x), dtype=float)
    else:
        arr = np.atleast_1d(np.asarray(value, dtype=float))
        if arr.size == 1 and dim > 1 and float(arr[0]) == 0.0:
            arr = np.zeros(dim)
        if arr.shape != (dim,):
            raise InputError(f"{key} = {value!r} must have {dim} component(s) for a {dim}-D film")
        out = arr.reshape((dim,) + (1,) * (x.ndim - 1)) * np.ones(x.shape[1:])
    if out.shape != x.shape:
        raise InputError(f"{key} returned shape {out.shape}, expected {x.shape}")
    return out


def _as_scalar_field(value, x, key):
    if callable(value):
        out = np.asarray(value(x), dtype=float)
    else:
        out = float(value) * np.ones(x.shape[1:])
    if out.shape != x.shape[1:]:
        raise InputError(f"{key} returned shape {out.shape}, expected {x.shape[1:]}")
    return out
