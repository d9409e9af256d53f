"""Film meshes with named boundaries, built on scikit-fem's own constructors.

Every mesh returned here carries named boundaries (``mesh.boundaries``):
``left``/``right`` in 1-D; ``left``/``right``/``bottom``/``top`` on rectangles
(``bottom``/``top`` only when periodic in x); ``edge`` on disks.
"""
from __future__ import annotations

import numpy as np
import skfem

from .errors import InputError


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
    if periodic_x:
        cls = skfem.MeshQuad1DG if cell == "quad" else skfem.MeshTri1DG
        m = cls.init_tensor(xs, ys, periodic=[0])
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


def disk(radius: float, refinements: int = 4, smoothed: bool = True) -> skfem.Mesh:
    """Triangular mesh of the disk r <= ``radius`` (scikit-fem ``init_circle``,
    boundary nodes on the circle), boundary ``edge``."""
    if refinements < 0:
        raise InputError(f"mesh refinements = {refinements!r} must be >= 0")
    m = skfem.MeshTri.init_circle(refinements, smoothed=smoothed).scaled(radius)
    return _tag(m, {"edge": lambda x, t: np.ones(x.shape[1], dtype=bool)})


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
