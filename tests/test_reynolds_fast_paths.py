"""The Reynolds solver's fast paths against scikit-fem's generic ones (the 1M-DOF solve of benchmarks/reynolds.py).

Each replacement must give what scikit-fem gives: the boundary vertices without building the
facets (``lubedyn.lubrication.mesh.boundary_vertices``), the Dirichlet dofs of ``_Problem``, the basis
built with one inverse Jacobian (``make_basis``), and the diffusion matrix and load vectors
assembled without ``asm`` (``assemble_diffusion``, ``assemble_flux_load``,
``assemble_source_load``) -- the last three bit for bit, on line, triangle, quad, curved and
periodic meshes, P1 and P2.
"""
from __future__ import annotations

import numpy as np
import pytest
import skfem
from skfem import asm

from lubedyn.lubrication import InclinedSlider, Lubricant
from lubedyn.lubrication import mesh as lmesh
from lubedyn.lubrication.reynolds import Film, make_basis
from lubedyn.lubrication.reynolds.forms import (ELEMENTS, assemble_diffusion, assemble_flux_load, assemble_source_load,
                                                cell_kind, diffusion_form, flux_load_form, source_load_form)
from lubedyn.lubrication.reynolds.problem import _Problem


def _graded_quads():
    return lmesh.rectangle(lmesh.graded(0.0, 1.0, 9, 0.3, 1.2), np.linspace(0.0, 0.5, 6), "quad")


MESHES = {
    "interval": lambda: lmesh.interval(0.0, 1.0, 7),
    "interval graded": lambda: lmesh.interval(0.0, 1.0, 0, points=lmesh.graded(0.0, 1.0, 12, 0.4, 1.3)),
    "quads": lambda: lmesh.rectangle(np.linspace(0.0, 2.0, 7), np.linspace(0.0, 1.0, 5), "quad"),
    "quads graded": _graded_quads,
    "triangles": lambda: lmesh.rectangle(np.linspace(0.0, 2.0, 7), np.linspace(0.0, 1.0, 5), "tri"),
    "periodic quads": lambda: lmesh.rectangle(np.linspace(0.0, 2.0, 9), np.linspace(0.0, 1.0, 4), "quad",
                                              periodic_x=True),
    "periodic triangles": lambda: lmesh.rectangle(np.linspace(0.0, 2.0, 9), np.linspace(0.0, 1.0, 4), "tri",
                                                  periodic_x=True),
    "disk": lambda: lmesh.disk(1e-3, 3),
    "curved disk": lambda: lmesh.disk(1e-3, 2, order=2),
    "L-shape": lambda: skfem.MeshTri.init_lshaped().refined(2),
    "skewed quads": lambda: skfem.MeshQuad.init_tensor(np.linspace(0, 1, 6), np.linspace(0, 1, 5)).with_defaults(),
}


def _skewed(m):
    """Perturb interior vertices so that quads are not parallelograms (isoparametric mapping)."""
    if isinstance(m, skfem.MeshQuad1) and type(m) is skfem.MeshQuad1:
        rng = np.random.default_rng(3)
        p = m.p.copy()
        inner = np.setdiff1d(np.arange(p.shape[1]), m.boundary_nodes())
        p[:, inner] += 0.03 * rng.standard_normal((2, inner.size))
        return skfem.MeshQuad1(p, m.t)
    return m


@pytest.mark.parametrize("name", sorted(MESHES))
def test_boundary_vertices_match_scikit_fem(name):
    m = MESHES[name]()
    fast = lmesh.boundary_vertices(m)
    reference = np.unique(m.facets[:, m.boundary_facets()])
    assert fast is not None
    assert np.array_equal(fast, reference)


def test_boundary_vertices_decline_3d_meshes():
    assert lmesh.boundary_vertices(skfem.MeshTet()) is None


def _periodic(m):
    return isinstance(m, skfem.mesh.mesh_dg.MeshDG)


def _film(m, element):
    return Film(mesh=m, gap=InclinedSlider(2e-5, 1e-5, 1.0), lubricant=Lubricant.newtonian(0.01),
                velocity_lower=(1.0,) + (0.0,) * (m.p.shape[0] - 1), element=element,
                pressure_points=((m.p[:, 0], 0.0),) if _periodic(m) else ())


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("name", sorted(MESHES))
def test_dirichlet_dofs_match_scikit_fem(name, element):
    m = MESHES[name]()
    prob = _Problem(_film(m, element))
    reference = np.unique(prob.basis.get_dofs(m.boundary_facets()).all())
    assert np.array_equal(np.unique(prob._boundary_dofs()), reference)
    fixed = np.flatnonzero(prob.fixed)
    if _periodic(m):  # plus the pressure point, if it is not on a boundary already
        assert np.setdiff1d(fixed, reference).size <= 1
        fixed = np.intersect1d(fixed, reference)
    assert np.array_equal(fixed, reference)


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("name", sorted(MESHES))
def test_basis_matches_scikit_fem(name, element):
    m = _skewed(MESHES[name]())
    fast = make_basis(m, element)
    elem = ELEMENTS[(cell_kind(m), element)]()
    reference = skfem.Basis(m, elem, intorder=4 if element == "P2" else 3)
    assert fast.mapping is m.mapping()  # the caching proxy is gone after the build
    assert np.array_equal(fast.dx, reference.dx)
    assert fast.Nbfun == reference.Nbfun
    for (f,), (r,) in zip(fast.basis, reference.basis):
        assert np.array_equal(np.asarray(f), np.asarray(r))
        assert np.array_equal(f.grad, r.grad)


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("name", sorted(MESHES))
def test_assembly_matches_asm_bit_for_bit(name, element):
    m = _skewed(MESHES[name]())
    b = make_basis(m, element)
    rng = np.random.default_rng(7)
    shape = (b.nelems, b.X.shape[-1])
    dim = m.p.shape[0]
    a = rng.uniform(0.5, 2.0, shape)
    f = rng.standard_normal((dim,) + shape)
    g = rng.standard_normal(shape)
    K, K_ref = assemble_diffusion(b, a), asm(diffusion_form, b, a=a).tocsr()
    assert K.shape == K_ref.shape
    assert np.array_equal(K.indptr, K_ref.indptr) and np.array_equal(K.indices, K_ref.indices)
    assert np.array_equal(K.data, K_ref.data)
    assert np.array_equal(assemble_flux_load(b, f), asm(flux_load_form, b, f=f))
    assert np.array_equal(assemble_source_load(b, g), asm(source_load_form, b, g=g))


def test_diffusion_drops_zero_entries_like_scikit_fem():
    # right triangles with a constant coefficient: the hypotenuse couplings are exactly zero,
    # which scikit-fem removes before summing
    m = lmesh.rectangle(np.linspace(0.0, 1.0, 5), np.linspace(0.0, 1.0, 5), "tri")
    b = make_basis(m, "P1")
    a = np.ones((b.nelems, b.X.shape[-1]))
    K, K_ref = assemble_diffusion(b, a), asm(diffusion_form, b, a=a).tocsr()
    local = np.einsum("idq,jdq->ij", np.array([phi.grad[:, 0] for (phi,) in b.basis]),
                      np.array([phi.grad[:, 0] for (phi,) in b.basis]))
    assert np.any(local == 0.0)  # the case this test is about
    assert np.array_equal(K.indptr, K_ref.indptr) and np.array_equal(K.indices, K_ref.indices)
    assert np.array_equal(K.data, K_ref.data)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_constant_lubricant_coefficients_without_the_pressure_field(element):
    # a pressure-independent lubricant's laws do not read p: evaluating them at gauge 0
    # (pressure=False, the linear film's assembly) gives the same fields as at the interpolated p
    m = lmesh.rectangle(np.linspace(0.0, 1.0, 9), np.linspace(0.0, 0.5, 5), "quad")
    prob = _Problem(_film(m, element))
    assert prob.linear
    rng = np.random.default_rng(11)
    p, r = rng.uniform(0.0, 1e6, prob.N), np.zeros(prob.N)
    full, short = prob.coefficients(p, r), prob.coefficients(p, r, pressure=False)
    assert short["pq"] is None and short["gp"] is None
    for key in ("eta", "deta", "rho", "drho", "r", "gr"):
        assert np.array_equal(np.asarray(full[key]), np.asarray(short[key])), key
