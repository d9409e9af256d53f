"""EHL scene: validated case -> :class:`~lubedyn.lubrication.ehl.EHLContact` -> solve -> outputs.

``build(case)`` turns an :class:`~lubedyn.scenes.ehl_case.EHLCase` (SI) into the
contact, grid and options of :func:`lubedyn.lubrication.ehl.solve_ehl`; the contact
comes from the reduced or body radii and the operating point, from a
bearing (:mod:`lubedyn.lubrication.laws.bearing`: the most loaded element's contact with one
race), or from Moes' M and L.  ``run(case, out_dir)`` solves and writes

- ``summary.json``: :meth:`~lubedyn.lubrication.ehl.EHLSolution.summary` (film
  thickness, pressure, load, friction, Moes M and L, Newton iterations) plus
  the inputs in SI (reduced radii and modulus, speeds, load), the Hertz
  contact (pressure, semi-axes), Hamrock-Dowson U, G, W and the closed-form
  film thickness of :mod:`lubedyn.lubrication.laws.film` for comparison
  (Hamrock-Dowson for points; Dowson-Toyoda, Pan-Hamrock and Moes for
  lines), the bearing data when there is a ``[bearing]``, solver information
  and timings, ``"Stop reason"`` (why the solver stopped, with its figures)
  and ``"Warnings"`` (the solver's a-posteriori checks,
  :func:`lubedyn.lubrication.ehl.check_solution`, and the validity ranges of
  :mod:`lubedyn.validity`; absent when there is none);
- ``case.resolved.toml``: the case as run, in SI with every default;
- ``ehl.vtu`` (``EHLSolution.save``: "Pressure [Pa]", "Film thickness [m]",
  "Elastic deflection [m]") and ``profiles.png`` (centre-line pressure and
  film) as listed in ``output.write``.

The solve happens before anything is written; the files are made in a
staging folder and moved into place only when all are complete
(:func:`lubedyn.outputs.staged`), so a failed run leaves an existing output
folder as it was.
"""
from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field

from lubedyn.lubrication.ehl import EHLContact, EHLGrid, EHLOptions, Traction, multigrid_grid, solve_ehl
from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws import bearing as bearings
from lubedyn.lubrication.laws import contact as hertz
from lubedyn.lubrication.laws import film as film_formulas

from lubedyn import limits, outputs, validity
from lubedyn.config import resolved_toml
from lubedyn.scenes.ehl_case import EHLCase, race_contact
from lubedyn.scenes.film import build_lubricant as film_lubricant

log = logging.getLogger(__name__)

CaseModel = EHLCase  # the schema (lubedyn.scenes.ehl_case)
FIELD_FILES = (("ehl.vtu", "vtu"), ("profiles.png", "png"))

DEFAULT_E_STAR = 1.0e11  # Pa, the modulus scale of a [dimensionless] case without [materials]

# Finest line-contact grid of the Newton methods: the largest measured to converge (ehl_roller_slice:
# 2049 nodes in 29 s, 4097 in 89 s; 8193 did not converge in 80 Newton iterations, 394 s).  Nested
# iteration solves every coarser grid first, so a finer request runs for hours before it fails.
MAX_LINE_GRID = 4097
# Peak resident memory per node of the multigrid point solver (measured, M = 100, L = 10: 513 x 513
# 300 MB, 1025 x 1025 1.2 GB above the 300 MB of a 129 x 129 run: 1.15 kB per node), about twice that:
MULTIGRID_BYTES_PER_NODE = 2048


@dataclass(frozen=True)
class EHLSetup:
    """What a case builds: the contact, grid and options, the element's
    bearing data (or None) and the effective length of a line contact (or None)."""

    contact: EHLContact
    grid: EHLGrid
    options: EHLOptions
    bearing: bearings.RaceContact | None = None
    length: float | None = None


def build_lubricant(case: EHLCase):
    return film_lubricant(case)


def build(case: EHLCase) -> EHLSetup:
    """The contact, grid and options of a validated case (no solve)."""
    t, op = case.traction, case.operating
    traction = Traction(t.model, t.limiting_shear_stress, t.limiting_shear_slope, t.eyring_stress)
    e_star = case.materials.e_star if case.materials is not None else DEFAULT_E_STAR
    race, length = None, case.contact.length
    if case.mode == "dimensionless":
        d, c = case.dimensionless, case.contact
        contact = EHLContact.from_moes(d.M, d.L, radius_x=c.radius_x, e_star=e_star, eta0=d.eta0,
                                       mean_speed=op.mean_speed, line=c.line,
                                       radius_y=None if c.line else c.radius_y,
                                       slide_to_roll=op.slide_to_roll, traction=traction)
    elif case.mode == "bearing":
        race = race_contact(case, e_star)
        length = race.length
        load = race.load_per_length if race.radius_y is None else race.load
        contact = EHLContact(race.radius_x, race.radius_y, e_star, build_lubricant(case), race.mean_speed,
                             load=load, slide_to_roll=op.slide_to_roll, traction=traction)
    else:
        rx, ry = case.contact.reduced_radii()
        um, srr = op.speeds()
        load = op.load_per_length if op.load_per_length is not None else op.load
        if case.is_line and op.load is not None:
            load = op.load / length
        contact = EHLContact(rx, ry, e_star, build_lubricant(case), um, load=load, approach=op.approach,
                             slide_to_roll=srr, traction=traction)
    g = case.grid
    grid = EHLGrid(nx=g.nx, ny=g.ny, x_min=g.x_min, x_max=g.x_max, y_max=g.y_max if g.y_max is not None else 3.0)
    options = EHLOptions(rtol=case.solver.rtol, max_iter=case.solver.max_iter, max_step=case.solver.max_step,
                         method=case.solver.method)
    limit = getattr(options, "max_point_grid", None)
    if options.method == "multigrid":
        # refuses line contacts and grids that do not coarsen to 16 cells (found by validate, not only by run)
        grid = multigrid_grid(contact, grid)
        nodes = grid.nx * grid.ny
        limits.check_memory(case, f"grid.nx = {g.nx}: {grid.nx} x {grid.ny} = {nodes:.3g} grid nodes (multigrid)",
                            nodes * MULTIGRID_BYTES_PER_NODE, "use a coarser grid")
    elif contact.is_line and g.nx > MAX_LINE_GRID:
        raise InputError(f"grid.nx = {g.nx} is too fine for a line contact: the Newton solver's work grows about "
                         f"as nx^2 (measured on the roller slice: 2049 nodes 29 s, 4097 nodes 89 s, 8193 nodes not "
                         f"converged in 80 iterations after 394 s) and every coarser grid is solved first; use "
                         f"nx <= {MAX_LINE_GRID}")
    elif not contact.is_line and limit is not None and g.nx > limit:  # found by validate, not only by run
        raise InputError(f"grid.nx = {g.nx} is too fine for a point contact: the EHL solver converges for point "
                         f"contacts up to {limit} nodes per side (lubedyn.lubrication.ehl.EHLOptions.max_point_grid); "
                         f"solver.method = 'multigrid' solves finer point-contact grids")
    return EHLSetup(contact, grid, options, race, length)


def describe(case: EHLCase, setup: EHLSetup) -> str:
    """One line: what would be solved."""
    c, g = setup.contact, setup.grid
    kind = "line" if c.is_line else "point"
    load = (f"load {c.load:.4g} N/m" if c.is_line else f"load {c.load:.4g} N") if c.load is not None \
        else f"approach {c.approach:.4g} m"
    if case.mode == "bearing":
        where = f"from a {case.bearing.type} bearing ({case.bearing.race} race)"
    else:
        where = "from Moes' M, L" if case.mode == "dimensionless" else "given directly"
    grid = f"{g.nx} nodes" if c.is_line else f"{g.nx} x {g.ny or 'auto'} nodes"
    moes = f"M = {c.moes_M:.4g}, " if c.load is not None else ""
    return (f"ehl scene: {kind} contact {where}, R_x = {c.radius_x:.4g} m, u_m = {c.mean_speed:.4g} m/s, {load}, "
            f"{moes}L = {c.moes_L:.4g}, grid {grid}, viscosity {type(c.lubricant.viscosity).__name__}")


# ---------------------------------------------------------------------------
# summary


def hertz_data(contact: EHLContact, load: float) -> dict:
    """Hertz contact under ``load`` [N, or N/m for lines]: pressure, semi-axes, ellipticity."""
    if contact.is_line:
        h = hertz.line_contact(load, contact.radius_x, contact.e_star)
        return {"Hertz pressure [Pa]": h.p0, "Hertz half-width along x [m]": h.b}
    h = hertz.point_contact(load, contact.radius_x, contact.radius_y, contact.e_star)
    along_x, across = (h.b, h.a) if contact.radius_y >= contact.radius_x else (h.a, h.b)
    return {"Hertz pressure [Pa]": h.p0, "Hertz semi-axis along x [m]": along_x, "Hertz semi-axis along y [m]": across,
            "Ellipticity k = a_y/b_x [-]": across / along_x, "Hertz approach [m]": h.approach}


def film_formula_values(contact: EHLContact, load: float, ellipticity: float | None) -> dict:
    """Hamrock-Dowson groups and closed-form film thickness [m] at ``load``."""
    U, G = contact.U, contact.G
    Rx, Ep = contact.radius_x, contact.e_prime
    W = load / (Ep * Rx ** (1 if contact.is_line else 2))
    out = {"Speed parameter U [-]": U, "Material parameter G [-]": G, "Load parameter W [-]": W}
    if not G > 0.0:  # isoviscous: the piezoviscous fits do not apply
        return out
    if contact.is_line:
        M, L = W * (2 * U) ** -0.5, G * (2 * U) ** 0.25
        out["Dowson-Toyoda central film thickness [m]"] = film_formulas.dowson_toyoda_central(U, G, W) * Rx
        out["Pan-Hamrock central film thickness [m]"] = film_formulas.pan_hamrock_central(U, G, W) * Rx
        out["Pan-Hamrock minimum film thickness [m]"] = film_formulas.pan_hamrock_minimum(U, G, W) * Rx
        out["Moes central film thickness [m]"] = film_formulas.moes_line_central(M, L) * Rx * math.sqrt(2 * U)
    else:
        out["Hamrock-Dowson central film thickness [m]"] = film_formulas.hamrock_dowson_central(U, G, W, ellipticity) * Rx
        out["Hamrock-Dowson minimum film thickness [m]"] = film_formulas.hamrock_dowson_minimum(U, G, W, ellipticity) * Rx
        if contact.radius_y == Rx:
            M, L = W * (2 * U) ** -0.75, G * (2 * U) ** 0.25
            out["Nijenbanning central film thickness [m]"] = (film_formulas.nijenbanning_central(M, L) * Rx
                                                             * math.sqrt(2 * U))
    return out


def bearing_data(race: bearings.RaceContact) -> dict:
    out = {
        "Race": race.race,
        "Contact angle [deg]": math.degrees(race.contact_angle),
        "Free contact angle [deg]": math.degrees(race.free_contact_angle),
        "Pitch ratio gamma [-]": race.gamma,
        "Cage speed [rad/s]": race.cage_speed,
        "Element load [N]": race.load,
        "Stribeck element load [N]": race.stribeck_load,
        "Stribeck constant [-]": race.stribeck_constant,
        "Load distribution": race.load_distribution,
    }
    if race.length is not None:
        out["Effective length [m]"] = race.length
    return out


def summarise(case: EHLCase, setup: EHLSetup, solution) -> dict:
    """Flat mapping of the scene's scalar results and inputs (names carry units)."""
    c = setup.contact
    load = c.load if c.load is not None else solution.load
    out = dict(solution.summary())
    if c.load is None:  # prescribed approach: M, L and the Hertz scales at the load found
        W = load / (c.e_prime * c.radius_x ** (1 if c.is_line else 2))
        out["Moes M [-]"] = W * (2 * c.U) ** (-0.5 if c.is_line else -0.75)
    if c.is_line and setup.length is not None:
        out["Load [N]"] = solution.load * setup.length
    hz = hertz_data(c, load)
    out.update(hz)
    out.update({
        "Reduced radius R_x [m]": c.radius_x,
        **({} if c.is_line else {"Reduced radius R_y [m]": c.radius_y}),
        "Reduced modulus E* [Pa]": c.e_star,
        "Mean speed [m/s]": c.mean_speed,
        "Slide-to-roll ratio [-]": c.slide_to_roll,
        "Viscosity eta0 [Pa s]": c.lubricant.viscosity.eta0,
    })
    hb = c.lubricant.herschel_bulkley
    if hb is None:
        out.update(film_formula_values(c, load, hz.get("Ellipticity k = a_y/b_x [-]")))
    else:  # the Newtonian film formulas would read phi0 as Pa s: left out; the start's apparent viscosity
        start = solution.info.get("hb_start") or {}
        out.update({"Herschel-Bulkley yield stress [Pa]": hb.yield_stress, "Herschel-Bulkley exponent [-]": hb.exponent,
                    "Herschel-Bulkley creep [-]": hb.creep,
                    "Apparent viscosity of the start [Pa s]": start.get("apparent_viscosity"),
                    "Newtonian start viscosity [Pa s]": start.get("start_viscosity"),
                    "Newtonian start central film [m]": start.get("central_film")})
    if setup.bearing is not None:
        out.update(bearing_data(setup.bearing))
    P = solution.problem
    out.update({
        "Contact": "line" if c.is_line else "point",
        "Degrees of freedom [-]": int(P.N),
        "Grid nodes x [-]": int(P.shape[0]),
        **({} if c.is_line else {"Grid nodes y [-]": int(P.shape[1])}),
        "Linear solver": str(solution.info.get("linear", "")),
        "Scheme": str(solution.info.get("scheme", "")),
    })
    if solution.info.get("stop_reason"):  # why the solver stopped, with its figures
        out["Stop reason"] = f"{solution.info['stop_reason']}: {solution.info.get('stop_detail', '')}".rstrip(": ")
    last = (solution.info.get("history") or [{}])[-1]
    if solution.info.get("method") == "multigrid" and "stop" in last:  # which stop rule ended the cycles, and why
        out["Multigrid stop"] = f"{last['stop']}: {last['stop_detail']}"
    return out


def film_reynolds_number(contact: EHLContact, solution) -> float:
    """rho0 U h_c / eta0 with the faster surface's speed U = u_m (1 + |SRR|/2) and the central film
    h_c, at the lubricant's ambient density and viscosity (an upper bound in the contact)."""
    lub = contact.lubricant
    rho0 = getattr(lub.density, "rho0", 1000.0)
    speed = contact.mean_speed * (1.0 + 0.5 * abs(contact.slide_to_roll or 0.0))
    return rho0 * speed * solution.central_film_thickness / lub.viscosity.eta0


def bound_scales(setup: EHLSetup, solution) -> dict:
    """The scales the outputs' physical bounds refer to (:mod:`lubedyn.bounds`): the dry contact's
    Hertz pressure under the load (given, or the film's with a prescribed approach), the reduced
    radius along x and the applied load (given loads only)."""
    c = setup.contact
    load = c.load if c.load is not None else float(solution.load)
    out = {"radius": c.radius_x}
    if load > 0.0:
        out["hertz_pressure"] = float(hertz_data(c, load).get("Hertz pressure [Pa]", math.nan))
    if c.load is not None:
        out["applied_load_per_length" if c.is_line else "applied_load"] = c.load
    return out


@dataclass
class EHLRun:
    """What :func:`run` produced: the setup, the solution, the summary and the files written."""

    case: EHLCase
    setup: EHLSetup
    solution: object = None
    summary: dict = field(default_factory=dict)
    files: list = field(default_factory=list)


def run(case: EHLCase, out_dir=None, *, name: str = "ehl", source: str = "", smoke: bool = False) -> EHLRun:
    """Build, solve and (if ``out_dir``) write the outputs of an EHL case.

    Raises :class:`~lubedyn.lubrication.errors.InputError` for a case that cannot be
    built and :class:`~lubedyn.lubrication.errors.ConvergenceError` for a failed
    solve; in both cases nothing is written.
    """
    t0 = time.perf_counter()
    setup = build(case)
    t_build = time.perf_counter() - t0
    log.info("%s", describe(case, setup))
    solution = solve_ehl(setup.contact, setup.grid, setup.options)
    scene_summary = summarise(case, setup, solution)
    reynolds = film_reynolds_number(setup.contact, solution)
    scene_summary["Film Reynolds number [-]"] = reynolds
    # the solver's a-posteriori checks (lubedyn.lubrication.ehl.check_solution: closed-form film, coarser
    # level) were logged by the solve; they join the validity warnings in summary.json
    checks = list(solution.info.get("warnings", []))
    found = validity.warnings_for(
        case.validity, max_pressure=solution.maximum_pressure, min_film=solution.minimum_film_thickness,
        reynolds=reynolds, model="the isothermal EHL model")
    validity.report(scene_summary, found)
    if checks:
        scene_summary["Warnings"] = checks + found
    summary = outputs.run_summary(case, name, smoke, scene_summary, t0, t_build, scales=bound_scales(setup, solution))
    result = EHLRun(case=case, setup=setup, solution=solution, summary=summary)
    if out_dir is None:
        return result
    header = outputs.resolved_header(name, source, smoke)

    def figure():
        fig = solution.plot_profiles()
        fig.axes[0].set_title(f"{name}: EHL centre line (M = {summary['Moes M [-]']:.3g}, L = {summary['Moes L [-]']:.3g})")
        return fig

    result.files = outputs.write_run(out_dir, resolved_toml(case, header), summary, case.output.write,
                                     fields=("ehl.vtu", solution.save), figure=("profiles.png", figure))
    return result


def headline(summary: dict) -> list[str]:
    """The lines ``lubedyn run`` prints (:func:`lubedyn.outputs.headline_lines`: loads, pressures, films,
    then the solve's iterations and time)."""
    return outputs.headline_lines(summary)
