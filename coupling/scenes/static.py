"""Static scene: the quasi-static equilibrium of a tapered roller bearing (paper A's bearing).

A case (``scene = "static"``; usually ``parameters = "Wu2018"``, which fills ``[bearing]`` from paper
A's Table 1 and the parameter module's assumed values)::

    scene = "static"
    parameters = "Wu2018"
    [bearing]                  # any field of lubedyn.lubrication.laws.tapered.TaperedRollerGeometry
    reconciliation = "common_apex"   # or "literal" (Table 1 as printed: the roller ends slide ~14 %)
    profile = "straight"       # or "logarithmic" (crowned; crown_load sets the design load)
    [operating]
    radial_load = "20 kN"      # along +y
    axial_displacement = "0 um"  # or axial_load = "15 kN" (give one): 0 locks the axial DOF
    speed = "2400 rpm"         # cone speed: centrifugal and gyroscopic roller loads
    [model]
    slices = 20                # slices per roller and raceway
    gyroscopic = true
    [solver]
    tol = 1e-10
    max_iterations = 400

``build(case)`` makes the geometry (:class:`lubedyn.lubrication.laws.tapered.TaperedRollerGeometry`) and
``run`` solves :func:`lubedyn.dynamics.tapered.quasistatic.solve` and writes

- ``summary.json``: per-roller loads on cup, cone and flange (most loaded, least, and every roller),
  contact angles, approaches, the cone's displacement, ideal kinematics (cage speed, roller spin,
  entrainment speed) from the model's own geometry, the derived geometry (roller axis angle, half
  taper, pitch radius), the solver's stop reason, iterations and force-balance error, and (as every
  scene's summary) ``"Assumed values"``: every value of the case that paper A does not give (source
  ``assumed`` in :mod:`lubedyn.papers.wu2018.parameters`) with its reason;
- ``case.resolved.toml``; ``loads.png`` (per-roller cup, cone and flange loads against azimuth, and
  the slice loads of the most loaded roller) when ``output.write`` lists ``"png"``;
- ``bearing.vtu`` (``"vtu"``) for ParaView: the cup and cone raceway surfaces over the rollers' length
  and the 17 rollers (crowned frustums) at their equilibrium positions and tilts, in metres, bearing
  axis along x and the radial load along +y; cell data ``"Body [-]"`` (0 cup, 1 cone, 2 + j roller j),
  point data ``"Cup load [N]"``, ``"Cone load [N]"``, ``"Flange load [N]"`` (each roller's, 0 on the
  rings).  Colour by ``Cup load [N]`` to see the load zone; the displacements are to scale (um).

Nothing is written when the solve fails (a :class:`~lubedyn.lubrication.errors.ConvergenceError` names why).
"""
from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from pydantic import Field, model_validator

from lubedyn.lubrication.errors import InputError

from lubedyn import outputs
from lubedyn.config import BoundsModel, LimitsModel, PositiveInt, PositiveLength, Q, CaseTable, resolved_toml, rule
from lubedyn.lubrication.laws.tapered import TaperedRollerGeometry

log = logging.getLogger(__name__)

FIELD_FILES = (("bearing.vtu", "vtu"), ("loads.png", "png"))

Angle = Q("angle", gt=0, lt=math.pi / 2)
Length = Q("length", ge=0)
Force = Q("force", ge=0)


class BearingTable(CaseTable):
    """The tapered roller bearing (paper A, Table 1, with ``parameters = "Wu2018"``)."""

    type: Literal["tapered_roller"] = "tapered_roller"
    n_rollers: PositiveInt
    effective_length: PositiveLength
    large_end_diameter: PositiveLength
    small_end_diameter: PositiveLength
    end_sphere_radius: PositiveLength
    outer_contact_angle: Angle
    inner_contact_angle: Q("angle", ge=0, lt=math.pi / 2)
    flange_contact_angle: Angle
    outer_raceway_radius: PositiveLength
    inner_raceway_radius: PositiveLength
    rib_height: PositiveLength
    cage_outer_diameter: PositiveLength
    cage_inner_diameter: PositiveLength
    cage_thickness: PositiveLength
    guide_land_clearance: PositiveLength
    guide_land_width: PositiveLength
    pocket_clearance: PositiveLength
    land_axial_gap: Length
    modulus: Q("pressure", gt=0)
    poisson: Q("dimensionless", ge=0, lt=0.5)
    density: Q("density", gt=0)
    reconciliation: Literal["common_apex", "literal"] = "common_apex"
    profile: Literal["straight", "logarithmic"] = "straight"
    crown_load: Force = 0.0

    @model_validator(mode="after")
    def _ends(self):
        if self.small_end_diameter >= self.large_end_diameter:
            raise rule("small_end_diameter", self.small_end_diameter,
                       f"must be < large_end_diameter = {self.large_end_diameter:g} m (the large end carries the "
                       "flange)")
        return self


class OperatingTable(CaseTable):
    """Loads on the cone (cup fixed) and its speed."""

    radial_load: Force = 0.0
    axial_load: Force | None = None
    axial_displacement: Q("length") | None = None
    speed: Q("angular velocity", ge=0) = 0.0

    @model_validator(mode="after")
    def _one_axial(self):
        if (self.axial_load is None) == (self.axial_displacement is None):
            raise rule("axial_load", self.axial_load, "give exactly one of axial_load (a force; > 0 closes the "
                       "bearing) and axial_displacement (0 locks the axial DOF, > 0 is a preload)")
        return self


class ModelTable(CaseTable):
    slices: PositiveInt = 20
    gyroscopic: bool = True


class SolverTable(CaseTable):
    tol: Q("dimensionless", gt=0, lt=1e-2) = 1e-10
    max_iterations: PositiveInt = 400


class OutputTable(CaseTable):
    write: list[Literal["vtu", "png"]] = Field(default_factory=lambda: ["vtu", "png"])


class StaticCase(CaseTable):
    """A static scene; after validation every value is SI and every default filled in."""

    scene: Literal["static"]
    description: str = ""
    bearing: BearingTable
    operating: OperatingTable = Field(default_factory=OperatingTable)
    model: ModelTable = Field(default_factory=ModelTable)
    solver: SolverTable = Field(default_factory=SolverTable)
    output: OutputTable = Field(default_factory=OutputTable)
    limits: LimitsModel = Field(default_factory=LimitsModel)
    validity: BoundsModel = Field(default_factory=BoundsModel)  # strict: lubedyn.bounds
    smoke: dict[str, Any] | None = None


CaseModel = StaticCase


def build(case: StaticCase):
    """The geometry of the case's bearing; an impossible geometry is an InputError naming the key."""
    b = case.bearing
    fields = {k: getattr(b, k) for k in BearingTable.model_fields if k != "type"}
    try:
        return TaperedRollerGeometry(**fields)
    except InputError as exc:
        text = str(exc)
        raise InputError(text if text.startswith("bearing.") else f"bearing.{text}") from None


def describe(case: StaticCase, geometry) -> str:
    op = case.operating
    axial = (f"F_a {op.axial_load:g} N" if op.axial_load is not None
             else f"axial displacement {op.axial_displacement * 1e6:g} um")
    return (f"tapered roller bearing ({case.bearing.reconciliation}, {case.bearing.profile}), "
            f"{case.bearing.n_rollers} rollers x {case.model.slices} slices; F_r {op.radial_load:g} N, {axial}, "
            f"{op.speed * 30 / math.pi:g} rpm")


def summarise(case: StaticCase, geometry, res) -> dict:
    """The summary's scene entries (module docstring)."""
    j = int(np.argmax(res.cup_loads))
    kin = res.kinematics
    s = {
        "Rollers [-]": case.bearing.n_rollers,
        "Slices per roller [-]": case.model.slices,
        "Geometry reconciliation": case.bearing.reconciliation,
        "Roller profile": case.bearing.profile,
        "Radial load [N]": res.radial_load,
        "Axial load [N]": res.axial_load,
        "Cone speed [rpm]": case.operating.speed * 30 / math.pi,
        "Cone displacement x (axial) [m]": float(res.cone_displacement[0]),
        "Cone displacement y (radial load) [m]": float(res.cone_displacement[1]),
        "Cone displacement z [m]": float(res.cone_displacement[2]),
        "Most loaded roller [-]": j,
        "Most loaded roller azimuth [deg]": math.degrees(float(res.azimuths[j])),
        "Largest cup load [N]": float(res.cup_loads[j]),
        "Largest cone load [N]": float(np.max(res.cone_loads)),
        "Largest flange load [N]": float(np.max(res.flange_loads)),
        "Smallest cup load [N]": float(np.min(res.cup_loads)),
        "Loaded rollers (cup load > 0) [-]": int(np.sum(res.cup_loads > 0.0)),
        "Largest cup approach [m]": float(np.max(res.cup_approaches)),
        "Largest cone approach [m]": float(np.max(res.cone_approaches)),
        "Largest slice load, cup [N]": float(np.max(res.cup_slice_loads)),
        "Cup loads [N]": [float(x) for x in res.cup_loads],
        "Cone loads [N]": [float(x) for x in res.cone_loads],
        "Flange loads [N]": [float(x) for x in res.flange_loads],
        "Cup contact angles [deg]": [math.degrees(float(x)) for x in res.cup_angles],
        "Roller tilts [rad]": [float(x) for x in res.roller_tilts],
        "Centrifugal force per roller [N]": res.centrifugal_force,
        "Gyroscopic moment per roller [N m]": res.gyroscopic_moment,
        "Roller axis angle [deg]": math.degrees(geometry.roller_axis_angle),
        "Cup raceway angle [deg]": math.degrees(geometry.cup_angle),
        "Cone raceway angle [deg]": math.degrees(geometry.cone_angle),
        "Flange contact angle [deg]": math.degrees(case.bearing.flange_contact_angle),
        "Roller half taper [deg]": math.degrees(geometry.half_taper),
        "Pitch radius [m]": geometry.pitch_radius,
        "Stop reason": res.stop_reason,
        "Iterations [-]": res.iterations,
        "Residual [-]": res.residual,
        "Force balance error [-]": res.force_balance_error,
    }
    warnings = []
    if not np.any(res.cone_loads > 0.0) and (res.axial_load > 0.0 or res.radial_load > 0.0):
        warnings.append(
            f"no roller touches the cone raceway: the {res.axial_load:.4g} N axial load is carried by the flange "
            f"alone (with bearing.reconciliation = {case.bearing.reconciliation!r} the rollers tilt into their "
            "large-end gap): a near-mechanism of the rigid-ring model, not a bearing in service")
    for text in warnings:
        log.warning("%s", text)
    if warnings:
        s["Warnings"] = warnings
    for k, v in kin.items():
        if isinstance(v, (int, float)):
            s[f"Ideal {k}" if "[" in k else f"Ideal {k} [-]"] = float(v)
    if "cage speed [rad/s]" in kin:
        s["Ideal cage speed [rpm]"] = float(kin["cage speed [rad/s]"]) * 30 / math.pi
    return s


@dataclass
class StaticRun:
    case: StaticCase
    geometry: object
    result: object = None
    summary: dict = field(default_factory=dict)
    files: list = field(default_factory=list)


def headline(s: dict) -> list[str]:
    """What ``lubedyn run`` prints."""
    lines = [f"{k:<40} {s[k]:.6g}" for k in ("Largest cup load [N]", "Largest cone load [N]", "Largest flange load [N]",
                                             "Cone displacement x (axial) [m]", "Cone displacement y (radial load) [m]")]
    lines.append(f"{'Stop reason':<40} {s['Stop reason']} ({s['Iterations [-]']} iterations)")
    n = len(s.get("Assumed values", {}))
    if n:
        lines.append(f"{'Assumed values (summary.json)':<40} {n}")
    return lines


def run(case: StaticCase, out_dir=None, *, name: str = "static", source: str = "", smoke: bool = False) -> StaticRun:
    """Build, solve and (if ``out_dir``) write; nothing is written when the build or the solve fails."""
    from lubedyn.dynamics.tapered.quasistatic import solve  # deferred: numba (validation needs none)

    t0 = time.perf_counter()
    geometry = build(case)
    t_build = time.perf_counter() - t0
    log.info("%s", describe(case, geometry))
    op = case.operating
    res = solve(geometry, radial_load=op.radial_load, axial_load=op.axial_load,
                axial_displacement=op.axial_displacement, inner_speed=op.speed, n_slices=case.model.slices,
                gyroscopic=case.model.gyroscopic, tol=case.solver.tol, max_iterations=case.solver.max_iterations)
    summary = outputs.run_summary(case, name, smoke, summarise(case, geometry, res), t0, t_build)
    result = StaticRun(case=case, geometry=geometry, result=res, summary=summary)
    if out_dir is None:
        return result
    header = outputs.resolved_header(name, source, smoke)
    result.files = outputs.write_run(out_dir, resolved_toml(case, header), summary, case.output.write,
                                     fields=("bearing.vtu", lambda path: bearing_mesh(geometry, res).save(path)),
                                     figure=("loads.png", lambda: _figure(name, res)))
    return result


def _revolve(points_xr, psi, tangential):
    """3-D points of meridional-plane points (x, r) with an out-of-plane offset ``tangential``, turned
    to the azimuth ``psi`` about the bearing axis x (psi = 0: +y)."""
    x, r = points_xr
    c, s = np.cos(psi), np.sin(psi)
    return np.stack([x, r * c - tangential * s, r * s + tangential * c], axis=-1)


def body_grid(pts, body: int, values: dict):
    """One body of a ParaView bearing mesh: the structured surface ``pts`` (..., 3) as an
    UnstructuredGrid with cell data "Body [-]" = ``body`` and each of ``values`` as constant point data."""
    import pyvista as pv

    m = pv.StructuredGrid(pts[..., 0], pts[..., 1], pts[..., 2]).cast_to_unstructured_grid()
    m.cell_data["Body [-]"] = np.full(m.n_cells, body, dtype=np.int32)
    for key, value in values.items():
        m.point_data[key] = np.full(m.n_points, value)
    return m


def raceway_surface(geometry, which: str, u, n_psi: int, shift=(0.0, 0.0, 0.0)):
    """Points (n_along, n_psi, 3) of the ``which`` ("cup" or "cone") raceway over the rollers' length ``u``
    (from the contact points at its ends), revolved about the bearing axis and moved by ``shift``."""
    ends = np.array([geometry.contact_point(ui, which) for ui in (u[0], u[-1])])
    psi = np.linspace(0.0, 2.0 * np.pi, n_psi)
    X, P = np.meshgrid(np.linspace(ends[0, 0], ends[1, 0], len(u)), psi, indexing="ij")
    R, _ = np.meshgrid(np.linspace(ends[0, 1], ends[1, 1], len(u)), psi, indexing="ij")
    return _revolve((X, R), P, 0.0) + np.asarray(shift, dtype=float)


def bearing_mesh(geometry, res, n_around: int = 24, n_along: int = 9):
    """The cup, cone and rollers at equilibrium as one pyvista UnstructuredGrid (module docstring)."""
    import pyvista as pv

    g = geometry
    e0 = g.axis_direction
    l = g.effective_length
    u = np.linspace(-0.5 * l, 0.5 * l, n_along)
    t = np.linspace(0.0, 2.0 * np.pi, n_around + 1)
    blocks = []

    def grid(pts, body, loads):
        return body_grid(pts, body, dict(zip(("Cup load [N]", "Cone load [N]", "Flange load [N]"), loads)))

    # raceways: the lines over the rollers' length, revolved about the axis
    for body, which in ((0, "cup"), (1, "cone")):
        blocks.append(grid(raceway_surface(g, which, u, 4 * n_around + 1), body, (0.0, 0.0, 0.0)))
    # rollers: frustums about their axes, displaced (a, r) and tilted in their meridional planes
    for j, psi in enumerate(res.azimuths):
        a, r = res.roller_displacements[j]
        th = res.roller_tilts[j]
        ct, st = math.cos(th), math.sin(th)
        e = np.array([ct * e0[0] - st * e0[1], st * e0[0] + ct * e0[1]])
        n_perp = np.array([-e[1], e[0]])
        c0 = np.array([a, g.pitch_radius + r])
        rho = np.asarray(g.roller_radius(u), dtype=float)
        U, T = np.meshgrid(u, t, indexing="ij")
        RHO, _ = np.meshgrid(rho, t, indexing="ij")
        x = c0[0] + U * e[0] + RHO * np.cos(T) * n_perp[0]
        rr = c0[1] + U * e[1] + RHO * np.cos(T) * n_perp[1]
        pts = _revolve((x, rr), psi, RHO * np.sin(T))
        blocks.append(grid(pts, 2 + j, (res.cup_loads[j], res.cone_loads[j], res.flange_loads[j])))
    return pv.merge(blocks, merge_points=False)


def _figure(name: str, res):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 4))
    ax, ax2 = fig.subplots(1, 2)
    deg = np.degrees(res.azimuths)
    for loads, label in ((res.cup_loads, "cup"), (res.cone_loads, "cone"), (res.flange_loads, "flange")):
        ax.plot(deg, loads, "o-", label=label)
    ax.set_xlabel("Roller azimuth [deg] (0: the radial load's direction)")
    ax.set_ylabel("Contact load [N]")
    ax.set_title(f"{name}: roller loads")
    ax.legend()
    j = int(np.argmax(res.cup_loads))
    n = res.cup_slice_loads.shape[1]
    ax2.plot(np.arange(n), res.cup_slice_loads[j], "o-", label="cup")
    ax2.plot(np.arange(n), res.cone_slice_loads[j], "s-", label="cone")
    ax2.set_xlabel("Slice (0: small end)")
    ax2.set_ylabel("Slice load [N]")
    ax2.set_title(f"most loaded roller ({j})")
    ax2.legend()
    fig.tight_layout()
    return fig
