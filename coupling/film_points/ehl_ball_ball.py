r"""Kind ``ehl_ball_ball``: the elastohydrodynamic (EHL) film between two neighbouring balls of paper B's
cage-less 6206 (Zhang et al. 2024, Symmetry 16, 741, sec. 2.1, eqs. 5-7), quasi-steady, with squeeze.

Part of :mod:`lubedyn.film_points` (the package docstring gives the other kinds).

Film (paper B eqs. 5-7): Reynolds with the squeeze term (quasi-steady: the rigid-body separation h00
changes at a uniform rate dh00/dt = -v, v > 0 the approach speed) and the entrainment u_e of the pair,
Roelands viscosity matched to paper B's Barus alpha = 1.85e-8 m^2/N at p -> 0
(:class:`lubedyn.lubrication.laws.lubricant.Roelands` with ``alpha``: z = 0.544, p0 = 1.96e8 Pa),
Dowson-Higginson density, the elastic deflection of both balls (E* from two steel balls, 207 GPa,
nu 0.29: 113.0 GPa), R_x = R_y = R/2 = 2.381 mm; solved by :func:`lubedyn.lubrication.ehl.solve_ehl`
with the load given (load balance).  u_e = 0 (equal spins) is a pure squeeze film (the solver's
``mean_speed = 0``).  Outputs: central and minimum film, "Approach [m]" = -h00, "Film stiffness [N/m]"
K = -dF/dh00 and "Film damping [N s/m]" C = dF/dv (central secants of load balance solves: load
(1 +- s) Q, approach speed (1 +- s) v at the load; C = K dh00/dv at fixed load), traction coefficient
of the limiting-shear law (tau_L0 5 MPa, slope 0.08, as the race kinds) at ``sliding_speed``.

Measured (this module's author, first 6 ms of cases/cageless_6206_10krpm_short.toml with the locked
rigid film map, 2 us samples, 12,437 pair samples with a normal force > 1 N): the kernel's entrainment
u_e = |(w_j - w_k) x a|/2 is *not* near zero during the drop (the balls spin up unequally): median
0.42 m/s, 95th percentile 2.5 m/s, largest 2.64 m/s (over 200 N: median 0.38, largest 0.92 m/s); the
approach speed v = -dg/dt spans -2.1 ... +3.8 m/s (5th/95th percentiles -0.37 / +0.44 m/s; over 200 N
-0.95 / +1.6 m/s); the sliding speed 0.3 - 18.5 m/s (median 4.7 m/s); the largest force 657 N; the
rigid gap down to -31.9 um (Hertz solids); the locked film 0.04 - 16 um (median 0.74 um).

What the quasi-steady EHL film can and cannot describe there (measured with this kind's solver):

- at collision loads the steady EHL film is beyond the solver: Moes M = W (2U)^-3/4 ~ 4000-6000 at
  100-250 N with u_e 0.4-1 m/s (L ~ 12-15), while the Newton solvers converge up to M ~ 256 on 33 x 33
  and ~1000 on 129 x 129 nodes; 250 N at u_e = 1, 0.1, 0.01 m/s failed on 33 x 33 (line search stalls);
- with this kind on the smoke grid: 20 N, u_e 1 m/s, v 1e-3 m/s (M = 310) converges (h_c 0.232 um, K 1.53e7
  N/m, 40 s; the solver's own resolution check puts h_c 8-9 % above the 65 x 65 grid's), 100 N, u_e 0.4
  m/s, v 1e-2 m/s (M = 3083) does not (line-search stalls, 19 s);
- the quasi-steady pure squeeze film has no physical state at collision loads: with the whole film
  thinning at the approach speed, the flux out of the Hertz zone needs |dp/dr| = 6 eta(p) v r/h^3, and
  at 100 N (p ~ 3 GPa, Roelands eta ~ 1e9 Pa s) no film of micrometres carries v = 0.1 m/s; the solver
  returns (isoviscous -> Roelands continuation, 33 x 33) a trapped-oil state with p_max = 42 GPa and
  h_c = 72 um, an artefact of the quasi-steady assumption.  Physically the film in the Hertz zone then
  thins at ~ h^3 p/(6 eta a^2) ~ 1e-6 m/s (h 1 um, p 1 GPa, a 0.1 mm): it is frozen over a collision
  (tens of microseconds), the solids take the approach, and entrainment at u_e ~ 0.4 m/s renews it only
  over 2a/u_e ~ 0.75 ms.  That is the locked film of :mod:`lubedyn.dynamics.contacts` (film thickness
  set where the rigid piezoviscous film reaches the Barus pole, Grubin's inlet argument, the solids in
  series), not a missing elasticity: a frozen 1 um film compresses (Dowson-Higginson, 1.33 rho0 at
  GPa) by ~0.25 um against a 19 um Hertz approach;
- isoviscous, the pure squeeze film converges at collision loads (100 N, 0.1 m/s: -h00 + h_c = 5.787
  um against Hertz 5.698 um), and at light loads the piezoviscous film converges where the pressure
  stays low: Roelands, 33 x 33, converged at 0.1 N / 1e-3 m/s (p_max 0.25 GPa, h_c 0.090 um, rigid
  isoviscous 0.053 um), not at 0.1 N / 1e-2, 1 N / 1e-4 and 1e-3 m/s (line-search stalls) and with a
  spurious trapped state at 0.1 N / 1e-4 m/s (p_max 20 GPa); the same 0.1 N / 1e-3 m/s from the solver's
  own squeeze start converges to a trapped state too (19.5 GPa, 55 x Hertz; 1.65 / 2.1 x on 17 / 25
  nodes): the quasi-steady piezoviscous squeeze film is not unique and not grid-independent, and the
  solver's a-posteriori check now names such states (``SQUEEZE_PRESSURE_LIMIT`` of
  :mod:`lubedyn.lubrication.ehl.checks`).  With entrainment the film is the steady EHL
  film with the squeeze as a perturbation, and light loads converge (:data:`EHL_BALL_BALL_AXES`).
"""
from __future__ import annotations

import logging
import math

import numpy as np

from lubedyn.lubrication.errors import ConvergenceError, unknown_choice

from lubedyn.film_points.base import (AxisDef, BALL_MODULUS, BALL_POISSON, BALL_RADIUS, OIL_ALPHA, OIL_ETA0, OIL_RHO0,
                                      _get, _lubricant, _reduced_modulus)
from lubedyn.film_points.ehl import TRACTION

log = logging.getLogger(__name__)

# nodes per side of the square domain |x|, |y| <= x_max a (a: Hertz radius of the load)
EHL_BALL_BALL_RESOLUTIONS = {"smoke": 33, "default": 49, "fine": 65}
EHL_BALL_BALL_OUTPUTS = (
    "Central film thickness [m]", "Minimum film thickness [m]", "Film stiffness [N/m]", "Film damping [N s/m]",
    "Traction coefficient [-]", "Approach [m]",
)
# Default axes: where the film converges on the default grid (light loads with entrainment, the squeeze a
# perturbation: Moes M ~ 10-60, L ~ 12-16); collision states (100-650 N, 0.1-4 m/s, M ~ 4000-6000) are
# outside the solver's reach and the quasi-steady model's (module docstring)
EHL_BALL_BALL_AXES = (
    AxisDef("Load [N]", 0.5, 5.0, 3, "log"),
    AxisDef("Approach speed [m/s]", 1e-4, 1e-2, 3, "log"),
    AxisDef("Entrainment speed [m/s]", 0.5, 2.5, 3, "log"),
)


def ehl_ball_ball_default_params() -> dict:
    """Two 6206 balls of paper B (radius 4.7625 mm, E 207 GPa, nu 0.29 both), Table 1 oil (eta0 0.050 Pa s,
    alpha 1.85e-8 m^2/N, rho0 992 kg/m^3) with Roelands viscosity matched to alpha at p -> 0 and
    Dowson-Higginson density."""
    return {
        "radius": BALL_RADIUS,
        "e_star": _reduced_modulus(BALL_MODULUS, BALL_POISSON, BALL_MODULUS, BALL_POISSON),
        "eta0": OIL_ETA0, "alpha": OIL_ALPHA, "rho0": OIL_RHO0,
        "viscosity_law": "roelands", "density_law": "dowson_higginson",
        # domain half-width: the larger of hertz_lengths a and film_lengths sqrt(2 R_eff h_iso), h_iso the rigid
        # isoviscous squeeze film of the load (the pressure of a light, hydrodynamic film spans sqrt(2 R h))
        "hertz_lengths": 3.0, "film_lengths": 4.0,
        "traction_model": TRACTION["model"], "limiting_shear_stress": TRACTION["limiting_shear_stress"],
        "limiting_shear_slope": TRACTION["limiting_shear_slope"],
        "sliding_speed": 4.7,  # [m/s] median of the drops' collisions (module docstring)
        "secant_step": 0.1,
        "resolution": "default",
    }


def _setup(params, load, v, ue):
    from lubedyn.lubrication.ehl import EHLContact, EHLGrid, EHLOptions, Traction  # deferred: scikit-fem
    from lubedyn.lubrication.laws import contact as hertz

    res = _get(params, "resolution", "default")
    if res not in EHL_BALL_BALL_RESOLUTIONS:
        raise unknown_choice("resolution", res, list(EHL_BALL_BALL_RESOLUTIONS))
    r_eff = 0.5 * float(params["radius"])
    es = float(params["e_star"])
    lub = _lubricant(params)
    traction = Traction(_get(params, "traction_model", "limiting_shear"),
                        float(_get(params, "limiting_shear_stress", 5e6)), float(_get(params, "limiting_shear_slope", 0.08)))
    contact = EHLContact(r_eff, r_eff, es, lub, float(ue), load=float(load), squeeze_velocity=-float(v),
                         traction=traction)
    a = hertz.point_contact(float(load), r_eff, r_eff, es).a
    h_iso = 6 * math.pi * lub.viscosity.eta0 * r_eff**2 * float(v) / float(load)
    xm = max(float(params["hertz_lengths"]), float(params["film_lengths"]) * math.sqrt(2 * r_eff * h_iso) / a)
    n = EHL_BALL_BALL_RESOLUTIONS[res]
    return contact, EHLGrid(nx=n, ny=n, x_min=-xm, x_max=xm, y_max=xm), EHLOptions()


def _solve(contact, grid, options, initial=None):
    """solve_ehl with a viscosity continuation when the direct start fails: isoviscous, then the law with
    alpha x 0.5, 0.75, 1 (measured need: Roelands pure squeeze at 1 N, 0.1 m/s stalls from the Hertz start)."""
    import dataclasses

    import lubedyn.lubrication as lub
    from lubedyn.lubrication.ehl import solve_ehl  # deferred: scikit-fem

    try:
        return solve_ehl(contact, grid, options, initial=initial)
    except (ConvergenceError, np.linalg.LinAlgError) as exc:
        first = exc
    visc = contact.lubricant.viscosity
    sol = None
    try:
        for f in (0.0, 0.5, 0.75, 1.0):
            if f == 1.0:
                v = visc
            elif f == 0.0:
                v = lub.ConstantViscosity(visc.eta0)
            elif isinstance(visc, lub.Roelands):
                v = lub.Roelands(visc.eta0, alpha=visc.pressure_viscosity * f)
            else:
                v = lub.Barus(visc.eta0, visc.pressure_viscosity * f)
            c = dataclasses.replace(contact, lubricant=dataclasses.replace(contact.lubricant, viscosity=v))
            sol = solve_ehl(c, grid, options, initial=sol)
        return sol
    except (ConvergenceError, np.linalg.LinAlgError) as exc:
        raise ConvergenceError(f"{first}; viscosity continuation: {exc}") from exc


def evaluate_ehl_ball_ball(params: dict, point: dict) -> dict:
    """One quasi-steady EHL ball-ball film at "Load [N]", "Approach speed [m/s]" (> 0), "Entrainment speed
    [m/s]" (>= 0); see the module docstring.  Raises ConvergenceError naming the point."""
    import dataclasses

    Q = float(point["Load [N]"])
    v = float(point["Approach speed [m/s]"])
    ue = float(point.get("Entrainment speed [m/s]", 0.0))
    where = f"ehl_ball_ball at Q = {Q:g} N, v = {v:g} m/s, u_e = {ue:g} m/s"
    contact, grid, options = _setup(params, Q, v, ue)
    try:
        sol = _solve(contact, grid, options)
        s = float(params.get("secant_step", 0.1))

        def h00(**change):
            c = dataclasses.replace(contact, **change)
            return _solve(c, grid, options, initial=sol).h00

        K = -2 * s * Q / (h00(load=Q * (1 + s)) - h00(load=Q * (1 - s)))
        # F(h00, v): dF = -K dh00 + C dv = 0 at fixed load, so C = K dh00/dv
        C = K * (h00(squeeze_velocity=-v * (1 + s)) - h00(squeeze_velocity=-v * (1 - s))) / (2 * s * v)
    except (ConvergenceError, np.linalg.LinAlgError) as exc:
        raise ConvergenceError(f"{where}: {exc}") from exc
    return {
        "Central film thickness [m]": float(sol.central_film_thickness),
        "Minimum film thickness [m]": float(sol.minimum_film_thickness),
        "Film stiffness [N/m]": float(K), "Film damping [N s/m]": float(C),
        # limiting-shear traction at the collisions' sliding speed (the solution's own Couette integral)
        "Traction coefficient [-]": sol.friction(float(params.get("sliding_speed", 4.7))) / Q,
        "Approach [m]": float(-sol.h00),
        "Maximum pressure [Pa]": float(sol.maximum_pressure),
    }
