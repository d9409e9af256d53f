"""Film meshes with named boundaries, built on scikit-fem's own constructors.

Every mesh returned here carries named boundaries (``mesh.boundaries``):
``left``/``right`` in 1-D; ``left``/``right``/``bottom``/``top`` on rectangles
(``bottom``/``top`` only when periodic in x); ``edge`` on disks.

Periodic rectangles are scikit-fem "DG-point" meshes: ``mesh.t`` holds
*topological* vertex numbers (the two sides of the seam are one vertex) while
``mesh.p`` holds one copy of the vertices per element, so ``mesh.p[:, mesh.t]``
does not address the geometry.  Use :func:`element_vertices` for coordinates
and :func:`unwrapped` for an ordinary mesh of the same elements.
"""
from __future__ import annotations

import numpy as np
import skfem

from skfem.mesh.mesh_dg import MeshDG

from .errors import InputError

PERIODIC_MIN_CELLS = 3  # fewest cells across a periodic direction


def _tag(mesh, names):
    """Name boundary facets by tests on their midpoints.

    Midpoints come from the element mapping (a facet basis), not from
    ``mesh.p[:, mesh.facets]``: on scikit-fem's periodic (DG-point) meshes the
    facet indices do not address the geometric points.
    """
    tol = 1e-9 * max(np.ptp(mesh.p[i]) for i in range(mesh.p.shape[0]))
    facets = mesh.boundary_facets()
    if hasattr(mesh, "_ix") and hasattr(mesh, "_orig"):
        # periodic mesh: topological vertex k sits at _orig.p[:, j] for the j
        # with _ix[j] == k (identified vertices differ only in the periodic
        # coordinate, which the boundary tests here never read)
        topo = np.zeros((mesh.p.shape[0], int(mesh._ix.max()) + 1))
        topo[:, mesh._ix] = mesh._orig.p
        mid = topo[:, mesh.facets[:, facets]].mean(axis=1)
    else:
        mid = mesh.p[:, mesh.facets[:, facets]].mean(axis=1)
    return mesh.with_boundaries({k: facets[f(mid, tol)] for k, f in names.items()})


def interval(x0: float, x1: float, n: int, points=None) -> skfem.Mesh:
    """1-D mesh of ``n`` elements on [x0, x1] (or on the sorted ``points``)."""
    if points is None:
        if n < 1:
            raise InputError(f"mesh elements = {n!r} must be >= 1")
        points = np.linspace(x0, x1, n + 1)
    points = np.asarray(points, dtype=float)
    if np.any(np.diff(points) <= 0):
        raise InputError("mesh points must be strictly increasing")
    spacing = np.diff(points)
    if np.min(spacing) < 1e-12 * (points[-1] - points[0]):
        k = int(np.argmin(spacing))
        raise InputError(
            f"mesh points {k} and {k + 1} are {spacing[k]:.3g} m apart, closer than 1e-12 of the "
            f"domain length {points[-1] - points[0]:.6g} m"
        )
    m = skfem.MeshLine(points)
    a, b = points[0], points[-1]
    return _tag(m, {"left": lambda x, t: np.abs(x[0] - a) < t, "right": lambda x, t: np.abs(x[0] - b) < t})


def rectangle(xs, ys, cell: str = "quad", periodic_x: bool = False) -> skfem.Mesh:
    """Tensor-product mesh on the coordinate arrays ``xs`` and ``ys``.

    ``cell`` is ``"quad"`` or ``"tri"``.  ``periodic_x=True`` identifies the
    left and right edges (journal bearings unwrapped in theta): the mesh is a
    scikit-fem periodic mesh (``MeshQuad1DG``/``MeshTri1DG``), so that any
    continuous element on it is periodic with no extra constraint.
    """
    xs = np.asarray(xs, dtype=float)
    ys = np.asarray(ys, dtype=float)
    if cell not in ("quad", "tri"):
        raise InputError(f"mesh cell = {cell!r} is not allowed; choose 'quad' or 'tri'")
    if len(xs) < 2 or len(ys) < 2:
        raise InputError("a rectangle mesh needs at least 2 points in each direction")
    if periodic_x and len(xs) < PERIODIC_MIN_CELLS + 1:
        # 1 cell: scikit-fem's "duplicate index" (the element is its own periodic neighbour); 2 cells: the
        # two share both seams and the boundary facets are lost
        raise InputError(f"a periodic rectangle mesh needs at least {PERIODIC_MIN_CELLS} cells along x "
                         f"(got {len(xs) - 1})")
    if periodic_x:
        m = _periodic_x(skfem.MeshQuad1DG if cell == "quad" else skfem.MeshTri1DG, xs, ys)
    else:
        cls = skfem.MeshQuad if cell == "quad" else skfem.MeshTri
        m = cls.init_tensor(xs, ys)
    names = {
        "bottom": lambda x, t: np.abs(x[1] - ys[0]) < t,
        "top": lambda x, t: np.abs(x[1] - ys[-1]) < t,
    }
    if not periodic_x:
        names["left"] = lambda x, t: np.abs(x[0] - xs[0]) < t
        names["right"] = lambda x, t: np.abs(x[0] - xs[-1]) < t
    return _tag(m, names)


def _periodic_x(cls, xs, ys) -> skfem.Mesh:
    """``cls.init_tensor(xs, ys, periodic=[0])`` of scikit-fem (``MeshDG.init_tensor`` and
    ``MeshDG.periodic``, the same vertex order, elements and ``_orig`` / ``_ix``), built from
    C-contiguous arrays.

    Why not scikit-fem's own: ``MeshDG.periodic`` reorders the vertices with
    ``np.hstack((doflocs[:, oix], doflocs[:, ix]))``; a fancy index along the second axis gives a
    Fortran-ordered array, which the mesh then copies to C order, logging "Transforming over 1000
    vertices to C_CONTIGUOUS." (WARNING, logger ``skfem``) for every periodic film of more than
    1000 vertices built from Python (tests/test_film_health.py).
    """
    from dataclasses import replace

    mesh = cls.__bases__[-1].init_tensor(xs, ys)
    ix = mesh.nodes_satisfying(lambda x: x[0] == xs.min())  # eliminated (left side) ...
    ix0 = mesh.nodes_satisfying(lambda x: x[0] == xs.max())  # ... replaced by the right side
    ix, first = np.unique(ix, return_index=True)
    ix0 = ix0[first]
    if len(ix) != len(ix0):  # pragma: no cover - a tensor mesh has as many vertices on both sides
        raise InputError("periodic mesh: the two sides have different vertex counts")
    n = mesh.nvertices
    remap = np.empty(n, dtype=np.int32)
    remap[ix] = np.arange(n - len(ix), n, dtype=np.int32)
    oix = np.setdiff1d(np.arange(n, dtype=np.int32), ix)
    remap[oix] = np.arange(n - len(ix), dtype=np.int32)
    doflocs = np.ascontiguousarray(np.hstack((mesh.doflocs[:, oix], mesh.doflocs[:, ix])))
    t = np.ascontiguousarray(remap[mesh.t])
    reordered = replace(mesh, doflocs=doflocs, t=t, sort_t=False)
    reremap = np.arange(n, dtype=np.int32)
    reremap[remap[ix]] = remap[ix0]
    periodic = cls.from_mesh(reordered, np.ascontiguousarray(reremap[t]))
    periodic._orig = reordered
    periodic._ix = reremap
    return periodic


def disk(radius: float, refinements: int = 4, smoothed: bool = True, order: int = 1) -> skfem.Mesh:
    """Triangular mesh of the disk r <= ``radius`` (scikit-fem ``init_circle``,
    boundary nodes on the circle), boundary ``edge``.

    ``order=1``: straight-sided triangles (``MeshTri1``); the polygon lies
    O(h^2) inside the circle, which limits any element to second order.
    ``order=2``: quadratic (isoparametric) triangles (``MeshTri2``) whose edge
    midpoints on the boundary lie on the circle; use it with ``P2`` films
    (the squeeze-film load then converges at order 4, against 2 on ``order=1``).

    >>> m = disk(1e-3, refinements=2, order=2)
    >>> type(m).__name__, sorted(m.boundaries)
    ('MeshTri2', ['edge'])
    """
    if refinements < 0:
        raise InputError(f"mesh refinements = {refinements!r} must be >= 0")
    if order not in (1, 2):
        raise InputError(f"mesh order = {order!r} is not allowed; choose 1 or 2")
    cls = skfem.MeshTri if order == 1 else skfem.MeshTri2
    m = cls.init_circle(refinements, smoothed=smoothed).scaled(radius)
    return m.with_boundaries({"edge": m.boundary_facets()})


def boundary_vertices(mesh) -> np.ndarray | None:
    """Sorted indices (into the columns of ``mesh.t``'s vertex numbering) of
    the vertices on the boundary of a 1-D or 2-D mesh, without building the
    mesh's facets; ``None`` for other meshes (3-D: use scikit-fem's
    ``mesh.boundary_nodes()``).

    Why: ``mesh.boundary_facets()`` builds every facet of the mesh first
    (``np.unique`` over the sorted vertex pairs of all element sides, then
    the facet-to-element inverse), a sizeable share of the 1M-DOF solve of
    benchmarks/reynolds.py, while a P1 film only needs the boundary vertices.  A facet (a vertex in
    1-D, an edge in 2-D) is on the boundary iff exactly one element has it:
    the element sides are counted by a sparse COO -> CSR conversion (which
    sums duplicates in linear time), an order of magnitude faster.  The same
    vertices as ``np.unique(mesh.facets[:, mesh.boundary_facets()])`` on
    every mesh kind (``tests/test_reynolds_fast_paths.py``), periodic
    (DG-point) meshes included: there ``mesh.t`` holds topological numbers,
    so the two sides of the seam are one edge, seen twice, as in scikit-fem.
    """
    import scipy.sparse as sp

    sides = mesh.elem.refdom.facets
    if sides is None or len(sides[0]) > 2:
        return None
    t = mesh.t
    nv = int(t.max()) + 1
    if len(sides[0]) == 1:  # 1-D: the facets are the vertices themselves
        return np.flatnonzero(np.bincount(t.ravel(), minlength=nv) == 1)
    a = np.concatenate([t[s[0]] for s in sides])
    b = np.concatenate([t[s[1]] for s in sides])
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    del a, b
    count = sp.coo_matrix((np.ones(lo.size, dtype=np.int32), (lo, hi)), shape=(nv, nv)).tocsr()
    count.sum_duplicates()
    once = count.data == 1
    rows = np.repeat(np.arange(nv), np.diff(count.indptr))[once]
    return np.unique(np.concatenate([rows, count.indices[once]]))


def element_vertices(mesh) -> np.ndarray:
    """Coordinates (dim, nverts, nel) of every element's vertices, in the local
    order of ``mesh.t``, from the element mapping (correct on periodic
    DG-point meshes and on curved meshes)."""
    nv = mesh.t.shape[0]
    X = np.ascontiguousarray(np.asarray(mesh.elem.doflocs, dtype=float)[:nv].T)
    return np.asarray(mesh.mapping().F(X)).transpose(0, 2, 1)


def unwrapped(mesh) -> skfem.Mesh:
    """An ordinary mesh with the same elements as ``mesh`` (same order, same
    local vertex order) and any periodic seam cut open.

    A non-periodic mesh is returned as it is.  For scikit-fem's periodic
    meshes (``MeshQuad1DG``, ``MeshTri1DG``) the vertices on the seam get one
    copy per side, so that the result can be plotted, searched
    (``element_finder``) and used for facet integrals.  Named boundaries are
    carried over (facets matched through their element and local index).
    """
    if not isinstance(mesh, MeshDG):
        return mesh
    cached = getattr(mesh, "_unwrapped_cache", None)
    if cached is not None:
        return cached
    nv, nel = mesh.t.shape
    pts = element_vertices(mesh).reshape(mesh.p.shape[0], -1)  # vertex (i, e) in column i * nel + e
    key = mesh.t.ravel()
    tol = 1e-9 * max(np.ptp(mesh.p[i]) for i in range(mesh.p.shape[0]))
    new = np.full(key.size, -1, dtype=np.int64)
    points = []
    count = 0
    remaining = np.arange(key.size)
    while remaining.size:
        # the first copy of each topological vertex makes a point; the copies at
        # the same place join it, those across a seam wait for the next round
        k = key[remaining]
        uniq, first, which = np.unique(k, return_index=True, return_inverse=True)
        canon = remaining[first]
        same = np.linalg.norm(pts[:, remaining] - pts[:, canon[which]], axis=0) <= tol
        new[remaining[same]] = count + which[same]
        points.append(pts[:, canon])
        count += uniq.size
        remaining = remaining[~same]
    base = type(mesh).__bases__[-1]  # MeshQuad1 / MeshTri1
    # C order (pts[:, canon] is Fortran-ordered): scikit-fem would copy it and log a WARNING
    um = base(np.ascontiguousarray(np.concatenate(points, axis=1)), new.reshape(nv, nel).astype(np.int32),
              sort_t=False)
    if mesh.boundaries:
        def carry(facets):
            elements = mesh.f2t[0, facets]
            local = np.argmax(mesh.t2f[:, elements] == facets, axis=0)
            return um.t2f[local, elements]

        um = um.with_boundaries({name: carry(f) for name, f in mesh.boundaries.items()})
    mesh._unwrapped_cache = um
    return um


def graded(x0: float, x1: float, n: int, centre: float, ratio: float = 1.0) -> np.ndarray:
    """``n + 1`` points on [x0, x1] clustered about ``centre`` (sinh stretching;
    ``ratio`` = 1 is uniform, larger ratios cluster harder)."""
    s = np.linspace(0.0, 1.0, n + 1)
    if ratio <= 1.0:
        return x0 + (x1 - x0) * s
    c = (centre - x0) / (x1 - x0)
    b = np.log(ratio)
    # map s -> t with t(0)=0, t(1)=1 and dt/ds smallest at t=c
    a0 = np.arcsinh((0.0 - c) * np.sinh(b))
    a1 = np.arcsinh((1.0 - c) * np.sinh(b))
    t = c + np.sinh(a0 + (a1 - a0) * s) / np.sinh(b)
    t = (t - t[0]) / (t[-1] - t[0])
    return x0 + (x1 - x0) * t
