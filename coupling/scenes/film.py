"""Film scene: validated case -> mesh and :class:`~lubedyn.lubrication.Film` -> solve -> outputs.

``build_film(case)`` turns a :class:`~lubedyn.config.FilmCase` (SI) into
lubrication objects; ``run(case, out_dir)`` solves and writes

- ``summary.json``: flat mapping, names carry units (``"Load [N]"``); 1-D
  films carry per-unit-width names (``"Load per unit width [N/m]"``, given by
  ``FilmSolution.summary``); flows through every boundary that is not sealed
  (outward positive); film K and C when ``output.film_coefficients``; solver
  information and timings;
- ``case.resolved.toml``: the case as run, in SI with every default;
- ``film.vtu`` (``FilmSolution.save``) and ``pressure.png``
  (``FilmSolution.plot_pressure``) as listed in ``output.write``.

The solve happens before anything is written; the files are made in a
staging folder and moved into place (one rename each) only when all of them
are complete: a failed run leaves an existing output folder as it was.

Meshes: slider steps and pocket edges are made mesh nodes (the nearest grid
line is moved onto them, or one is added), so a discontinuous gap never cuts
through an element.
"""
from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field

import numpy as np

import lubedyn.lubrication as lub
from lubedyn.lubrication import mesh as meshes
from lubedyn.lubrication.errors import InputError

from lubedyn import limits, outputs, validity
from lubedyn.config import CASES_DIR as CASES
from lubedyn.config import FilmCase, resolved_toml

log = logging.getLogger(__name__)

CaseModel = FilmCase  # the schema (lubedyn.config, where the other scenes' base models live)
FIELD_FILES = (("film.vtu", "vtu"), ("pressure.png", "png"))


# ---------------------------------------------------------------------------
# case -> lubrication objects


def build_gap(case: FilmCase) -> lub.Gap:
    g = case.gap
    if g.type == "inclined_slider":
        return lub.InclinedSlider(g.h_in, g.h_out, g.length)
    if g.type == "step_slider":
        return lub.StepSlider(g.h_in, g.h_out, g.x_step)
    if g.type == "pocketed_slider":
        return lub.PocketedSlider(g.h_in, g.h_out, g.length, g.pocket_start, g.pocket_end, g.depth)
    if g.type == "journal":
        if g.eccentricity_x is not None:
            return lub.JournalBearing(g.radius, g.clearance, g.eccentricity_x, g.eccentricity_y)
        return lub.JournalBearing.from_ratio(g.radius, g.clearance, g.eccentricity_ratio, g.attitude_angle)
    if g.type == "sphere_plane":
        return lub.SpherePlane(g.radius, g.h0, exact=g.exact)
    if g.type == "sphere_sphere":
        return lub.SphereSphere(g.radius1, g.radius2, g.h0, exact=g.exact)
    if g.type == "cylinder_plane":
        return lub.CylinderPlane(g.radius, g.h0)
    if g.type == "ellipsoid_plane":
        return lub.EllipsoidPlane(g.radius_x, g.radius_y, g.h0)
    raise InputError(f"gap.type = {g.type!r} has no builder")  # pragma: no cover - schema forbids it


def _breakpoints(case: FilmCase) -> list[float]:
    g = case.gap
    if g.type == "step_slider":
        return [g.x_step]
    if g.type == "pocketed_slider":
        return [g.pocket_start, g.pocket_end]
    return []


def grid_with_breakpoints(lo: float, hi: float, n: int, breakpoints) -> np.ndarray:
    """``n + 1`` uniform points on [lo, hi] with every breakpoint inside made a
    node: the nearest point is moved onto it, or (if that point is taken or an
    end) a point is added.

    >>> grid_with_breakpoints(0.0, 1.0, 4, [0.3]).tolist()
    [0.0, 0.3, 0.5, 0.75, 1.0]
    """
    xs = list(np.linspace(lo, hi, n + 1))
    fixed = {xs[0], xs[-1]}
    for bp in sorted(b for b in breakpoints if lo < b < hi):
        j = int(np.argmin(np.abs(np.asarray(xs) - bp)))
        if xs[j] in fixed:
            xs = sorted(xs + [bp])
        else:
            xs[j] = bp
        fixed.add(bp)
    xs = np.asarray(xs)
    return xs


def build_mesh(case: FilmCase):
    m, g = case.mesh, case.gap
    if m.domain == "interval":
        xs = grid_with_breakpoints(m.x[0], m.x[1], m.nx, _breakpoints(case))
        return meshes.interval(xs[0], xs[-1], len(xs) - 1, points=xs)
    if m.domain == "rectangle":
        xs = grid_with_breakpoints(m.x[0], m.x[1], m.nx, _breakpoints(case))
        ys = np.linspace(m.y[0], m.y[1], m.ny + 1)
        return meshes.rectangle(xs, ys, cell=m.cell)
    if m.domain == "journal":
        xs = np.linspace(0.0, 2.0 * math.pi * g.radius, m.nx + 1)
        ys = np.linspace(-0.5 * g.length, 0.5 * g.length, m.ny + 1)
        return meshes.rectangle(xs, ys, cell=m.cell, periodic_x=True)
    if m.domain == "disk":
        return meshes.disk(m.radius, m.refinements)
    raise InputError(f"mesh.domain = {m.domain!r} has no builder")  # pragma: no cover


def build_lubricant(case: FilmCase) -> lub.Lubricant:
    v, d = case.lubricant.viscosity, case.lubricant.density
    if v.law == "constant":
        viscosity = lub.ConstantViscosity(v.eta0)
    elif v.law == "barus":
        viscosity = lub.Barus(v.eta0, v.alpha)
    else:
        viscosity = lub.Roelands(v.eta0, z=v.z, alpha=v.alpha)
    if d.law == "incompressible":
        density = lub.Incompressible(d.rho0)
    else:
        density = lub.DowsonHigginson(d.rho0, d.a, d.b)
    hb = case.lubricant.herschel_bulkley
    flow = None if hb is None else lub.HerschelBulkleyFlow(hb.yield_stress, hb.exponent, hb.creep)
    return lub.Lubricant(viscosity, density, case.lubricant.eyring_stress, flow)


def _check_gap_positive(gap, mesh, case: FilmCase):
    h = np.asarray(gap(mesh.p), dtype=float)
    if not np.all(np.isfinite(h)) or np.min(h) <= 0.0:
        k = int(np.nanargmin(np.where(np.isfinite(h), h, -np.inf)))
        where = ", ".join(f"{c:.4g}" for c in mesh.p[:, k])
        raise InputError(
            f"gap ({case.gap.type}): film thickness h = {h[k]:.4g} m at x = ({where}) m on the mesh; "
            "it must be > 0 everywhere (the surfaces touch or overlap): check the [gap] values and the mesh extent"
        )


# Peak resident memory per degree of freedom of a film run (mesh, assembly, sparse LU, K and C),
# measured (ru_maxrss growth): 1-D 0.7-1.3 kB (2e4-2e5 cells, P1 and P2); 2-D journal 3.3-4.1 kB
# (256 x 64 to 512 x 128, P1 and P2, quad and tri; it grows slowly with the LU's fill).  About twice that:
BYTES_PER_DOF = {1: 2048, 2: 8192}


def film_dofs(case: FilmCase) -> int:
    """Degrees of freedom of a case's film, from its mesh keys alone (no mesh is built): exact for
    the meshes of :func:`build_mesh`, except that a slider's step or pocket edges count one node
    each (:func:`grid_with_breakpoints` usually moves a node there instead of adding one).

    >>> from lubedyn.config import load_case
    >>> film_dofs(load_case(CASES / "journal_finite.toml", smoke=True))  # 32 x 8 cells, P2, periodic in x
    1088
    """
    m = case.mesh
    k = 2 if m.element == "P2" else 1
    if m.domain == "disk":
        verts, edges, cells = 5, 8, 4  # scikit-fem's init_circle(0); each refinement splits every triangle in 4
        for _ in range(m.refinements):
            verts, edges, cells = verts + edges, 2 * edges + 3 * cells, 4 * cells
        return verts + (edges if k == 2 else 0)
    nx = m.nx + sum(1 for b in _breakpoints(case) if m.x is None or m.x[0] < b < m.x[1])
    if m.domain == "interval":
        return k * nx + 1
    if m.domain == "journal":
        return k * m.nx * (k * m.ny + 1)
    return (k * nx + 1) * (k * m.ny + 1)


def _mesh_keys(m, refine: int = 1) -> str:
    """The mesh's size keys as a case states them, every direction refined by ``refine`` (a disk by
    the whole refinements that give at least that factor)."""
    if m.domain == "disk":
        return f"mesh.refinements = {m.refinements + int(math.ceil(math.log2(refine)))}"
    if m.domain == "interval":
        return f"mesh.nx = {m.nx * refine}"
    return f"mesh.nx = {m.nx * refine} with mesh.ny = {m.ny * refine}"


def check_size(case: FilmCase) -> int:
    """Refuse a film whose estimated memory exceeds the limit (:mod:`lubedyn.limits`); its DOFs."""
    dofs = film_dofs(case)
    m = case.mesh
    subject = _mesh_keys(m)
    limits.check_memory(case, f"{subject}: {dofs:.3g} degrees of freedom ({m.element}, {case.dim}-D)",
                        dofs * BYTES_PER_DOF[case.dim], "use a coarser mesh")
    return dofs


def build_film(case: FilmCase) -> lub.Film:
    """The :class:`~lubedyn.lubrication.Film` of a validated case (no solve)."""
    check_size(case)  # before any array of the mesh's size exists
    gap = build_gap(case)
    mesh = build_mesh(case)
    _check_gap_positive(gap, mesh, case)
    mo, b = case.motion, case.boundary
    upper = mo.velocity_upper
    if mo.speed is not None:  # the journal (upper body) turns; the bearing stands still
        upper = [mo.speed * case.gap.radius, 0.0]
    names = sorted((mesh.boundaries or {}).keys())
    dirichlet = {name: b.pressures.get(name, b.ambient) for name in names if name not in b.sealed}
    return lub.Film(
        mesh=mesh,
        gap=gap,
        lubricant=build_lubricant(case),
        velocity_lower=tuple(mo.velocity_lower),
        velocity_upper=tuple(upper),
        squeeze=mo.squeeze,
        mode_velocities=dict(mo.mode_velocities),
        dirichlet=dirichlet,
        element=case.mesh.element,
        cavitation=lub.Cavitation(case.cavitation.model, case.cavitation.pressure),
        ambient_pressure=b.ambient,
        options=lub.SolverOptions(
            rtol=case.solver.rtol, max_iter=case.solver.max_iter,
            linear_solver=case.solver.linear_solver, amg_tol=case.solver.amg_tol,
        ),
    )


def describe(case: FilmCase, film: lub.Film) -> str:
    """One line: what would be solved."""
    m = case.mesh
    cells = film.mesh.t.shape[1]
    kind = {"interval": "1-D interval", "rectangle": f"{m.cell} rectangle", "journal": f"periodic {m.cell} journal",
            "disk": "triangular disk"}[m.domain]
    return (f"film scene: gap {case.gap.type}, {kind} mesh with {cells} cells, {m.element}, "
            f"cavitation {case.cavitation.model}, viscosity {case.lubricant.viscosity.law}, "
            f"density {case.lubricant.density.law}")


# ---------------------------------------------------------------------------
# solve and summarise


def summarise(case: FilmCase, solution, coefficients=None) -> dict:
    """Flat mapping of the scene's scalar results (names carry units; 1-D
    films per unit width, named by :meth:`~lubedyn.lubrication.FilmSolution.summary`)."""
    film = solution.film
    # a sealed boundary has no flow by its condition
    open_boundaries = [name for name in sorted((film.mesh.boundaries or {}).keys()) if name not in case.boundary.sealed]
    out = dict(solution.summary(boundaries=open_boundaries, coefficients=coefficients))
    if case.gap.type == "journal":
        g = case.gap
        e = np.array([film.gap.eccentricity_x, film.gap.eccentricity_y])
        force = solution.load_vector[:2]
        out["Eccentricity ratio [-]"] = float(np.linalg.norm(e) / g.clearance)
        if np.linalg.norm(e) > 0 and np.linalg.norm(force) > 0:
            # attitude angle: between the applied load (-film force) and the line of centres
            cosang = np.dot(e, -force) / (np.linalg.norm(e) * np.linalg.norm(force))
            out["Attitude angle [deg]"] = float(np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0))))
        if case.motion.speed and np.linalg.norm(force) > 0:
            n_rev = case.motion.speed / (2.0 * math.pi)
            pressure = np.linalg.norm(force) / (2.0 * g.radius * g.length)
            out["Sommerfeld number [-]"] = float((g.radius / g.clearance) ** 2 * case.lubricant.viscosity.eta0 * n_rev / pressure)
    info = solution.info
    out.update({
        "Element": case.mesh.element,
        "Cavitation model": case.cavitation.model,
        "Linear solver": str(info.get("linear_solver", "")),
        "Stop reason": str(info.get("stop reason", "")),
        "Mesh cells [-]": int(film.mesh.t.shape[1]),
    })
    return out


def surface_speeds(case: FilmCase) -> list[float]:
    """The speeds [m/s] of the film's surfaces: the lower surface's, and the upper's (a journal's
    ``speed`` times its radius, or ``velocity_upper``)."""
    mo = case.motion
    speeds = [float(np.linalg.norm(mo.velocity_lower))]
    if mo.speed is not None:
        speeds.append(abs(mo.speed) * case.gap.radius)
    elif mo.velocity_upper is not None:
        speeds.append(float(np.linalg.norm(mo.velocity_upper)))
    return speeds


def film_reynolds_number(case: FilmCase, solution) -> float:
    """rho0 U h_max / eta0: the fastest surface (or squeeze) speed U, the thickest film on the mesh,
    the lubricant's density and viscosity at ambient pressure (a conservative upper bound: the
    viscosity laws only rise with pressure)."""
    speeds = surface_speeds(case) + [abs(case.motion.squeeze)]
    h_max = float(np.max(solution.film_thickness))
    return case.lubricant.density.rho0 * max(speeds) * h_max / case.lubricant.viscosity.eta0


def resolution_warnings(case: FilmCase, solution) -> list[str]:
    """The film's minimum-gap resolution guard
    (:meth:`~lubedyn.lubrication.FilmSolution.resolution_warning`), naming the case's mesh keys that
    would resolve the zone (every direction refined by the factor, rounded up; a disk by
    whole refinements); [] when resolved."""
    text = solution.resolution_warning()
    if text is None:
        return []
    return [f"{text} ({_mesh_keys(case.mesh, solution.info['min_gap_refine'])}, or finer)"]


def bound_scales(case: FilmCase, film, solution) -> dict:
    """The scales the outputs' physical bounds refer to (:mod:`lubedyn.bounds`).

    ``viscous_pressure``: for an iso-viscous, Newtonian film, the largest boundary pressure plus
    6 eta0 U L / h_min^2 (wedge and step films: a slider's largest pressure is below 0.2 times it) plus
    12 eta0 |V| L^2 / h_min^3 (squeeze films: a sphere's is 3 eta0 V R / h_min^2), with U the fastest
    surface speed, V the squeeze speed, L the mesh's largest extent (a journal's unwrapped
    circumference) and h_min the thinnest gap; absent when the viscosity rises with pressure (the
    pressure then has no iso-viscous bound)."""
    out = {}
    lub = case.lubricant
    if lub.viscosity.law != "constant" or lub.eyring_stress is not None:
        return out
    mo = case.motion
    speeds = surface_speeds(case) + [abs(v) for v in mo.mode_velocities.values()]
    squeeze = abs(mo.squeeze or 0.0)
    p = np.asarray(film.mesh.p, dtype=float)
    extent = float(np.max(np.ptp(p, axis=1)))
    if case.mesh.domain == "journal":  # unwrapped: the circumference
        extent = max(extent, 2.0 * math.pi * case.gap.radius)
    h_min, eta = float(solution.h_min), float(lub.viscosity.eta0)
    boundary = max([abs(case.boundary.ambient)] + [abs(v) for v in case.boundary.pressures.values()])
    if h_min > 0.0:
        out["viscous_pressure"] = (boundary + 6.0 * eta * max(speeds) * extent / h_min ** 2
                                   + 12.0 * eta * squeeze * extent ** 2 / h_min ** 3)
    return out


@dataclass
class FilmRun:
    """What :func:`run` produced: the solution, the summary and the files written."""

    case: FilmCase
    film: lub.Film
    solution: object = None
    summary: dict = field(default_factory=dict)
    files: list = field(default_factory=list)


def run(case: FilmCase, out_dir=None, *, name: str = "film", source: str = "", smoke: bool = False) -> FilmRun:
    """Build, solve and (if ``out_dir``) write the outputs of a film case.

    Raises :class:`~lubedyn.lubrication.errors.InputError` for a case that cannot be
    built and :class:`~lubedyn.lubrication.errors.ConvergenceError` for a failed
    solve; in both cases nothing is written.
    """
    t0 = time.perf_counter()
    film = build_film(case)
    t_build = time.perf_counter() - t0
    log.info("%s", describe(case, film))
    solution = lub.solve(film)
    coefficients = solution.coefficients() if case.output.film_coefficients else None
    scene_summary = summarise(case, solution, coefficients)
    reynolds = film_reynolds_number(case, solution)
    scene_summary["Film Reynolds number [-]"] = reynolds
    validity.report(scene_summary, validity.warnings_for(
        case.validity, max_pressure=solution.p_max, min_film=solution.h_min, reynolds=reynolds,
        model="the rigid-surface Reynolds film") + resolution_warnings(case, solution))
    if solution.warnings:  # the solver's own check (JFO fluid fraction), logged by lub.solve already
        scene_summary["Warnings"] = scene_summary.get("Warnings", []) + solution.warnings
    summary = outputs.run_summary(case, name, smoke, scene_summary, t0, t_build,
                                  scales=bound_scales(case, film, solution))
    result = FilmRun(case=case, film=film, solution=solution, summary=summary)
    if out_dir is None:
        return result
    header = outputs.resolved_header(name, source, smoke)

    def figure():
        fig = solution.plot_pressure()
        fig.axes[0].set_title(f"{name}: film pressure")
        return fig

    result.files = outputs.write_run(out_dir, resolved_toml(case, header), summary, case.output.write,
                                     fields=("film.vtu", solution.save), figure=("pressure.png", figure))
    return result


build = build_film  # the scene protocol of lubedyn.cli


def headline(summary: dict) -> list[str]:
    """The lines ``lubedyn run`` prints (:func:`lubedyn.outputs.headline_lines`: loads, pressures, films,
    then the solve's iterations and time)."""
    return outputs.headline_lines(summary)
