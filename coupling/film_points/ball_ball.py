"""Kind ``ball_ball``: the oil film between two neighbouring balls (rigid Reynolds FEM squeeze film
with entrainment, polar axes).

Part of :mod:`lubedyn.film_points` (the package docstring gives the physics and sources)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lubedyn.lubrication.errors import ConvergenceError, InputError, unknown_choice

from lubedyn.film_points.base import BALL_RADIUS, OIL_ALPHA, OIL_ETA0, OIL_RHO0, AxisDef, _get, _lubricant

# ====================================================================== ball-ball film

BALL_BALL_RESOLUTIONS = {
    # name: (rings, sectors, element).  Measured (isoviscous squeeze, h_a/h0 = 1000,
    # force against the closed form; central pressure): smoke 16 x 16: -3.3e-3, +2.0e-3;
    # default 24 x 24: -6.9e-4, +5.7e-4; fine 48 x 32: -9.1e-5, +2.4e-5.
    "smoke": (16, 16, "P2"),
    "default": (24, 24, "P2"),
    "fine": (48, 32, "P2"),
}
RING_GRADING = 4.0  # b of r_k = r_d sinh(b k/n)/sinh(b); measured best of 2..7 for the squeeze film

PRESSURE_NUMBER = "Pressure number [-]"
SQUEEZE_ANGLE = "Squeeze angle [rad]"
_THETA_LO = math.radians(-80.0)
# Polar axes (module docstring).  The gap is a pure scale (exact power laws, which the two end nodes
# interpolate exactly in log-log; the accuracy points still solve at random gaps); rho: log nodes,
# denser towards the Barus pole near 1; theta: every 15 deg on the approach side, 5 deg on the
# separating side (partly cavitated: K and C curve more) and 2.5 deg next to the axis' end, where log F
# bends over towards the onset at -88.19 deg.  Measured with 16 angles (10 deg steps from -60 to -30,
# 5 deg below): max errors F 2.0 %, K 2.6 %, C 3.1 % (at -59 deg), p_max 2.5 % (at -79 deg).
BALL_BALL_AXES = (
    AxisDef("Central gap [m]", 5e-8, 5e-5, 2, "log"),
    AxisDef(PRESSURE_NUMBER, 1e-3, 0.9, 12, "log",
            (1e-3, 3e-3, 0.01, 0.03, 0.1, 0.2, 0.3, 0.45, 0.6, 0.7, 0.8, 0.9)),
    AxisDef(SQUEEZE_ANGLE, _THETA_LO, 0.5 * math.pi, 20, "linear",
            tuple(math.radians(d) for d in (-80, -77.5, -75, -72.5, -70, -65, -60, -55, -50, -45, -40, -30, -15, 0,
                                            15, 30, 45, 60, 75, 90))),
)
BALL_BALL_OUTPUTS = (
    "Force [N]", "Stiffness [N/m]", "Damping [N s/m]", "Minimum film thickness [m]", "Maximum pressure [Pa]",
    "Friction per sliding speed [N s/m]",
)


def ball_ball_default_params() -> dict:
    """Paper B's ball-ball film: balls of Table 2, oil of Table 1 (SI; keys in :func:`evaluate_ball_ball`)."""
    return {
        "ball_radius": BALL_RADIUS,
        "eta0": OIL_ETA0,
        "alpha": OIL_ALPHA,
        "rho0": OIL_RHO0,
        "viscosity_law": "barus",
        "density_law": "dowson_higginson",
        "cavitation_pressure": 0.0,
        "domain_gap_ratio": 1000.0,
        "resolution": "default",
    }


def effective_radius(params) -> float:
    """R_eff = R/2 [m] of two equal balls."""
    return 0.5 * float(_get(params, "ball_radius"))


def squeeze_number(h0: float, v: float, params) -> float:
    """Lambda = 3 alpha eta0 R_eff v/h0^2 [-]: alpha times the central pressure of the rigid isoviscous squeeze film."""
    return 3.0 * float(params["alpha"]) * float(params["eta0"]) * effective_radius(params) * v / (h0 * h0)


def approach_speed(h0: float, squeeze: float, params) -> float:
    """v [m/s] (> 0: approach) of squeeze number ``squeeze`` at gap ``h0`` (inverse of :func:`squeeze_number`)."""
    return squeeze * h0 * h0 / (3.0 * float(params["alpha"]) * float(params["eta0"]) * effective_radius(params))


def entrainment_number(h0: float, ue: float, params) -> float:
    """E = 3 alpha eta0 |u_e| sqrt(2 R_eff h0)/h0^2 [-]: alpha times the rolling-pressure scale.

    The entrainment counterpart of :func:`squeeze_number` (module docstring, "Polar axes"):
    the Reynolds source 12 eta (u_e dh/dx + dh/dt) = 12 eta (u_e x/R_eff - v) over the
    contact width sqrt(2 R_eff h0) gives the pressure scales 3 eta R_eff v/h0^2 (squeeze)
    and 3 eta u_e sqrt(2 R_eff h0)/h0^2 (rolling); their ratio is Lambda/E.  The film is
    symmetric in x, so the sign of u_e does not matter.
    """
    return 3.0 * float(params["alpha"]) * float(params["eta0"]) * abs(ue) * math.sqrt(
        2.0 * effective_radius(params) * h0) / (h0 * h0)


def polar_numbers(h0: float, v: float, ue: float, params) -> tuple:
    """``(rho, theta)`` of a ball_ball point: rho = sqrt(Lambda^2 + E^2) [-], theta = atan2(Lambda, E) [rad].

    theta = pi/2: pure approach (squeeze), 0: pure rolling, -pi/2: pure separation
    (:func:`squeeze_number`, :func:`entrainment_number`).
    """
    lam, e = squeeze_number(h0, v, params), entrainment_number(h0, ue, params)
    return math.hypot(lam, e), math.atan2(lam, e)


def polar_speeds(h0: float, rho: float, theta: float, params) -> tuple:
    """``(v, u_e)`` [m/s] of gap ``h0``, pressure number ``rho`` and squeeze angle ``theta`` (inverse of
    :func:`polar_numbers`; u_e >= 0, exactly 0 at theta = +-pi/2)."""
    lam, e = rho * math.sin(theta), rho * math.cos(theta)
    if abs(math.cos(theta)) < 1e-12:
        e = 0.0
    k = 3.0 * float(params["alpha"]) * float(params["eta0"])
    return approach_speed(h0, lam, params), e * h0 * h0 / (k * math.sqrt(2.0 * effective_radius(params) * h0))


def separation_onset_angle(params) -> float:
    """Squeeze angle [rad] below which a separating film carries no load: -atan(sqrt(h_a/h0 - 1)).

    The Reynolds source 12 eta (u_e x/R_eff - v) is >= 0 on the whole disk r <= r_d when the
    separation speed -v >= u_e r_d/R_eff; then p = 0 is the solution (a pressure >= 0 with a
    source >= 0 has its maximum on the boundary, where p = 0), i.e. |Lambda|/E >= r_d/sqrt(2
    R_eff h0) = sqrt(h_a/h0 - 1) (31.6 for the default domain_gap_ratio 1000: theta = -88.19 deg).
    The same holds for any viscosity and density law (the argument uses only the sign of the source).
    """
    return -math.atan(math.sqrt(float(_get(params, "domain_gap_ratio", 1000.0)) - 1.0))


def ball_ball_derived(params: dict, point: dict) -> dict:
    """Closed-form quantities of a ball_ball point: "Approach speed [m/s]", "Entrainment speed [m/s]",
    "Squeeze number [-]", "Entrainment number [-]" (not tabulated: exact functions of the axes)."""
    h0, v, ue = _point_speeds(params, point)
    return {"Approach speed [m/s]": v, "Entrainment speed [m/s]": ue,
            "Squeeze number [-]": squeeze_number(h0, v, params),
            "Entrainment number [-]": entrainment_number(h0, ue, params)}


def _point_speeds(params, point) -> tuple:
    """``(h0, v, u_e)`` of a ball_ball point given on the polar axes or by speeds (module docstring)."""
    h0 = float(point["Central gap [m]"])
    if not h0 > 0:
        raise InputError(f"ball_ball point: 'Central gap [m]' = {h0!r} must be > 0")
    if PRESSURE_NUMBER in point:
        rho, theta = float(point[PRESSURE_NUMBER]), float(point[SQUEEZE_ANGLE])
        if abs(theta) > 0.5 * math.pi and abs(theta) - 0.5 * math.pi < 1e-9:  # "90 deg" rounded
            theta = math.copysign(0.5 * math.pi, theta)
        if not rho >= 0 or not -0.5 * math.pi <= theta <= 0.5 * math.pi:
            raise InputError(f"ball_ball point: {PRESSURE_NUMBER!r} = {rho!r} must be >= 0 and {SQUEEZE_ANGLE!r} = "
                             f"{theta!r} in [-pi/2, pi/2]")
        v, ue = polar_speeds(h0, rho, theta, params)
        return h0, v, ue
    if "Approach speed [m/s]" in point:
        v = float(point["Approach speed [m/s]"])
    else:
        v = approach_speed(h0, float(point["Squeeze number [-]"]), params)
    return h0, v, float(point.get("Entrainment speed [m/s]", 0.0))


def squeeze_force_barus(h0: float, squeeze: float, alpha: float, radius_eff: float, gap_ratio: float = np.inf) -> float:
    """Rigid Barus squeeze-film force [N] of a parabolic gap (incompressible, no entrainment).

    F = (2 pi R_eff h0/alpha) int_{x_a}^1 -ln(1 - Lambda (x^2 - x_a^2)) dx/x^2,
    x_a = 1/``gap_ratio`` (module docstring); the closed form
    2 sqrt(L) artanh(sqrt(L)) + ln(1 - L) for an infinite film, else scipy
    quad.  ``squeeze`` = Lambda in (-inf, 1/(1 - x_a^2)]; Lambda -> 0 gives
    the isoviscous 6 pi eta v R_eff^2/h0 (1 - x_a)^2.
    """
    scale = 2.0 * math.pi * radius_eff * h0 / alpha
    L = float(squeeze)
    if not np.isfinite(gap_ratio):
        if L >= 1.0 or L <= 0.0:
            raise InputError(f"squeeze number = {L!r}: the infinite-film closed form needs 0 < Lambda < 1")
        s = math.sqrt(L)
        return scale * (2.0 * s * math.atanh(s) + math.log1p(-L))
    from scipy.integrate import quad

    xa = 1.0 / gap_ratio
    val, _ = quad(lambda x: -math.log1p(-L * (x * x - xa * xa)) / (x * x), xa, 1.0, epsabs=0.0, epsrel=1e-12, limit=200)
    return scale * val


def polar_disk(radius: float, rings: int, sectors: int, grading: float = RING_GRADING):
    """Triangular mesh of the disk r <= ``radius`` on ``rings`` graded rings of ``sectors`` nodes.

    Ring k (1..rings) at r_k = radius sinh(grading k/rings)/sinh(grading);
    alternate rings are turned by half a sector so that the triangles stay
    near-equilateral; a fan of triangles round the centre node.  Boundary
    ``edge``.
    """
    import skfem

    if rings < 2 or sectors < 6:
        raise InputError(f"polar disk rings = {rings}, sectors = {sectors}: need >= 2 and >= 6")
    k = np.arange(1, rings + 1)
    r = radius * np.sinh(grading * k / rings) / np.sinh(grading) if grading > 0 else radius * k / rings
    j = np.arange(sectors)
    th = 2.0 * np.pi * (j[None, :] + 0.5 * ((k[:, None] - 1) % 2)) / sectors  # ring index k - 1 odd: turned
    rings_xy = np.stack([(r[:, None] * np.cos(th)).ravel(), (r[:, None] * np.sin(th)).ravel()])
    pts = np.concatenate([np.zeros((2, 1)), rings_xy], 1)
    idx = lambda ring, jj: 1 + ring * sectors + (jj % sectors)  # noqa: E731
    tris = [[0, idx(0, jj), idx(0, jj + 1)] for jj in range(sectors)]
    for ring in range(rings - 1):
        for jj in range(sectors):
            a, b, c, d = idx(ring, jj), idx(ring, jj + 1), idx(ring + 1, jj), idx(ring + 1, jj + 1)
            # ring + 1 is turned by +half a sector when ring is even, by -half when odd
            tris += [[a, b, c], [b, d, c]] if ring % 2 == 0 else [[a, b, d], [a, d, c]]
    m = skfem.MeshTri(np.ascontiguousarray(pts), np.ascontiguousarray(np.array(tris, dtype=np.int64).T))
    return m.with_boundaries({"edge": m.boundary_facets()})


@dataclass(frozen=True)
class _Start:
    """Starting pressure for :func:`lubedyn.lubrication.reynolds.solve` (what it reads of ``initial``)."""

    pressure_dofs: np.ndarray
    fluid_fraction_dofs: np.ndarray


def _reduced_pressure_inverse(viscosity, q):
    """p(q) with q(p) = int_0^p eta0/eta(s) ds the reduced pressure (tabulated); NaN beyond the pole."""
    eta0 = viscosity.eta0
    if getattr(viscosity, "is_constant", False):
        return np.asarray(q, dtype=float)
    p = np.concatenate([[0.0], np.geomspace(1e2, 1e10, 1500)])
    ratio = eta0 / viscosity(p)
    qt = np.concatenate([[0.0], np.cumsum(0.5 * (ratio[1:] + ratio[:-1]) * np.diff(p))])
    out = np.interp(q, qt, p, right=np.nan)
    return np.where(np.asarray(q) < 0, 0.0, out)


def _ball_ball_setup(params, point):
    import lubedyn.lubrication as lub  # deferred: scikit-fem

    h0, v, ue = _point_speeds(params, point)
    res = _get(params, "resolution", "default")
    if res not in BALL_BALL_RESOLUTIONS:
        raise unknown_choice("resolution", res, list(BALL_BALL_RESOLUTIONS))
    rings, sectors, element = BALL_BALL_RESOLUTIONS[res]
    Reff = effective_radius(params)
    ratio = float(_get(params, "domain_gap_ratio", 1000.0))
    if not ratio > 1:
        raise InputError(f"domain_gap_ratio = {ratio!r} must be > 1")
    rd = math.sqrt(2.0 * Reff * h0 * (ratio - 1.0))
    mesh = polar_disk(rd, rings, sectors)
    lubricant = _lubricant(params)
    pcav = float(_get(params, "cavitation_pressure", 0.0))
    full = ue == 0.0 and v > 0.0 and pcav <= 0.0  # pressure >= 0 everywhere: no cavitation possible
    R = 2.0 * Reff
    film = lub.Film(
        mesh=mesh, gap=lub.SphereSphere(R, R, h0), lubricant=lubricant,
        velocity_lower=(ue, 0.0), velocity_upper=(ue, 0.0), squeeze=-v, element=element,
        cavitation=lub.Cavitation("none" if full else "reynolds", pcav),
        options=lub.SolverOptions(rtol=1e-10, max_iter=60, warm_start_levels=0),
    )
    # start: the closed-form squeeze pressure of the lubricant's reduced pressure
    from lubedyn.lubrication.reynolds import make_basis  # deferred: scikit-fem

    h = h0 + np.sum(make_basis(mesh, element).doflocs ** 2, axis=0) / (2.0 * Reff)
    ha = h0 * ratio
    q_iso = 3.0 * lubricant.viscosity.eta0 * max(v, 0.0) * Reff * (1.0 / h**2 - 1.0 / ha**2)
    p_start = _reduced_pressure_inverse(lubricant.viscosity, q_iso)
    return film, h0, v, ue, p_start


def _point_text(point) -> str:
    return ", ".join(f"{k} = {float(val):.6g}" for k, val in point.items())


def solve_ball_ball(params, point):
    """Solve the ball-ball film at ``point``; returns ``(solution, h0, v, ue)``.

    Raises :class:`ConvergenceError` naming the point if the Reynolds solve
    fails or the piezoviscous film has no solution (beyond the pole).
    """
    import lubedyn.lubrication as lub  # deferred: scikit-fem

    film, h0, v, ue, p_start = _ball_ball_setup(params, point)
    if np.any(np.isnan(p_start)):
        raise ConvergenceError(
            f"ball_ball point ({_point_text(point)}): the rigid piezoviscous film has no solution "
            f"(the isoviscous central pressure times the reduced-pressure limit of the {params.get('viscosity_law')} "
            "law is beyond its pole: the balls deform, an EHL squeeze regime not modelled here)"
        )
    start = _Start(p_start, np.ones_like(p_start))
    try:
        sol = lub.solve(film, initial=start)
    except ConvergenceError as exc:
        raise ConvergenceError(f"ball_ball point ({_point_text(point)}): {exc}") from exc
    return sol, h0, v, ue


def evaluate_ball_ball(params: dict, point: dict) -> dict:
    """One ball-ball film solve (module docstring).

    ``params`` (SI): ``ball_radius`` [m], ``eta0`` [Pa s], ``alpha`` [1/Pa],
    ``rho0`` [kg/m^3], ``viscosity_law`` ("barus", "roelands" with the same
    low-pressure slope alpha, "constant"), ``density_law``
    ("dowson_higginson", "incompressible"), ``cavitation_pressure`` [Pa,
    gauge], ``domain_gap_ratio`` (h at the disk edge over h0), ``resolution``
    ("smoke", "default", "fine").  ``point``: "Central gap [m]", and
    "Squeeze number [-]" or "Approach speed [m/s]" (> 0 approach),
    "Entrainment speed [m/s]" (default 0).

    Returns "Force [N]" (> 0 pushes the balls apart), "Stiffness [N/m]"
    K = -dF/dh0, "Damping [N s/m]" C = dF/dv, "Minimum film thickness [m]",
    "Maximum pressure [Pa]", "Approach speed [m/s]", "Friction per sliding
    speed [N s/m]" (int eta(p)/h dA over the full film).
    """
    from lubedyn.lubrication.reynolds import film_coefficients, interpolate  # deferred: scikit-fem

    sol, h0, v, ue = solve_ball_ball(params, point)
    _, K, C = film_coefficients(sol)
    prob = sol.problem
    pq = np.asarray(interpolate(sol.basis, sol.pressure_dofs)) - sol.film.ambient_pressure
    eta = sol.film.lubricant.viscosity(pq)
    full = np.asarray(interpolate(sol.basis, sol.full_film.astype(float)))
    friction = sol.integrate(np.clip(full, 0.0, 1.0) * eta / prob.h)
    return {
        "Force [N]": float(sol.mode_forces["h0"]),
        "Stiffness [N/m]": float(K[0, 0]),
        "Damping [N s/m]": float(C[0, 0]),
        "Minimum film thickness [m]": float(sol.h_min),
        "Maximum pressure [Pa]": float(sol.p_max),
        "Approach speed [m/s]": float(v),
        "Friction per sliding speed [N s/m]": float(friction),
    }


def field_ball_ball(params: dict, point: dict):
    """The film at ``point`` as a pyvista grid ("Pressure [Pa]", "Film thickness [m]", ...)."""
    sol, *_ = solve_ball_ball(params, point)
    return sol.to_pyvista()
