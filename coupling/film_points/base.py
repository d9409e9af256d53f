"""The film-point registry (AxisDef, PointKind) and the papers' values the kinds start from.

Part of :mod:`lubedyn.film_points` (the package docstring gives the physics and sources)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field as _field
from typing import Callable

import numpy as np

from lubedyn.lubrication.errors import InputError, unknown_choice

from lubedyn.papers import printed, si
from lubedyn.lubrication.laws.contact import reduced_modulus

# ---------------------------------------------------------------- registry


@dataclass(frozen=True)
class AxisDef:
    """One map axis: ``name`` with unit, default range [lo, hi] (SI), ``n`` nodes, ``scale`` "log"/"linear".

    ``explicit``: optional default nodes (increasing, from ``lo`` to ``hi``, ``n`` of them) where the
    function needs them (e.g. denser towards a pole); empty: uniform in x (linear) or log x (log)."""

    name: str
    lo: float
    hi: float
    n: int
    scale: str
    explicit: tuple = ()

    def __post_init__(self):
        if self.scale not in ("log", "linear"):
            raise unknown_choice(f"axis {self.name!r} scale", self.scale, ("log", "linear"))
        if not self.hi > self.lo or self.n < 2:
            raise InputError(f"axis {self.name!r}: needs lo < hi and n >= 2 (got {self.lo}, {self.hi}, {self.n})")
        if self.scale == "log" and not self.lo > 0:
            raise InputError(f"axis {self.name!r}: a log axis needs lo > 0 (got {self.lo})")
        if self.explicit:
            x = np.asarray(self.explicit, dtype=float)
            if (x.size != self.n or x[0] != self.lo or x[-1] != self.hi or not np.all(np.diff(x) > 0)):
                raise InputError(f"axis {self.name!r}: explicit nodes must be n = {self.n} increasing values "
                                 f"from lo = {self.lo} to hi = {self.hi}")

    def nodes(self) -> np.ndarray:
        if self.explicit:
            return np.asarray(self.explicit, dtype=float)
        if self.scale == "log":
            return np.geomspace(self.lo, self.hi, self.n)
        return np.linspace(self.lo, self.hi, self.n)


@dataclass(frozen=True)
class PointKind:
    """A family of film solves tabulated by a map (see the module docstring)."""

    name: str
    description: str
    axes: tuple
    outputs: tuple
    evaluate: Callable
    default_params: Callable
    field: Callable | None = None
    # closed-form quantities of a point (not tabulated: exact functions of the axes), e.g. the
    # approach and entrainment speeds of a ball_ball point: derived(params, point) -> {name: float}
    derived: Callable | None = None
    # outputs that are signed in physics and stored without log even where the map's axes keep them > 0
    # (the traction coefficient, odd in the slide-to-roll ratio: the dynamics extend it by sign and
    # linearly below the axis and read it with logv = 0)
    signed: tuple = ()
    # outputs tabulated on a sheared coordinate ({output: spec}, see lubedyn.maps.FilmMap, "sheared"):
    # the map returns them from a tabulated shift and a tabulated function of the normalised coordinate
    sheared: dict = _field(default_factory=dict, hash=False, compare=False)


# ---------------------------------------------------------------- paper data
# The kinds' default parameters come from the papers' parameter sets (lubedyn.papers): paper B
# (Zhang2024: Tables 1, 2, 4) for the ball kinds, paper A (Wu2018: Table 1, figure 5) for the roller.
BALL_RADIUS = si("Zhang2024", "ball_radius")
BALL_DIAMETER = si("Zhang2024", "ball_diameter")
PITCH_DIAMETER_6206 = si("Zhang2024", "pitch_diameter")
INNER_GROOVE_RADIUS = si("Zhang2024", "inner_groove_radius")
OUTER_GROOVE_RADIUS = si("Zhang2024", "outer_groove_radius")
N_BALLS = si("Zhang2024", "n_balls")
BALL_MODULUS, BALL_POISSON = si("Zhang2024", "ball_modulus"), si("Zhang2024", "ball_poisson")
RING_MODULUS, RING_POISSON = si("Zhang2024", "ring_modulus"), si("Zhang2024", "ring_poisson")
OIL_ETA0 = si("Zhang2024", "viscosity")
OIL_ALPHA = si("Zhang2024", "pressure_viscosity")
OIL_RHO0 = si("Zhang2024", "density")
PAPER_B_AXIAL_LOAD = si("Zhang2024", "axial_load")
SHAFT_SPEED_B = printed("Zhang2024", "speed", "rpm") * 2 * math.pi / 60  # rad/s: the film-solution speed
ROLLER_MEAN_DIAMETER = si("Wu2018", "roller_mean_diameter")
ROLLER_PITCH_DIAMETER = si("Wu2018", "pitch_diameter")
ROLLER_INNER_CONTACT_ANGLE = math.radians(printed("Wu2018", "inner_contact_angle", "deg"))
ROLLER_EFFECTIVE_LENGTH = si("Wu2018", "effective_length")
ROLLER_MODULUS, ROLLER_POISSON = si("Wu2018", "steel_modulus"), si("Wu2018", "steel_poisson")
ROLLER_EYRING_STRESS = 5e6  # Pa, Reynolds-Eyring tau0 of the roller map (assumed; ehl_roller_race_default_params)
GREASE_ALPHA = si("Wu2018", "pressure_viscosity")
ROLLER_BASE_OIL_ETA0 = si("Wu2018", "base_oil_viscosity")  # assumed (paper A gives none)
ROLLER_BASE_OIL_RHO0 = si("Wu2018", "base_oil_density")  # assumed
ROLLER_FILM_SHEAR_MODULUS = si("Wu2018", "film_shear_modulus")  # assumed (Johnson & Tevaarwerk 1977: 0.3-3 GPa)
SHAFT_SPEED_A = printed("Wu2018", "inner_speed", "rpm") * 2 * math.pi / 60  # rad/s, figure 5


def _reduced_modulus(E1, nu1, E2, nu2):
    return reduced_modulus(E1, nu1, E2, nu2)


VISCOSITY_LAWS = ("barus", "roelands", "constant")
DENSITY_LAWS = ("dowson_higginson", "incompressible")
# Poiseuille flow of the roller kinds' film ("rheology"): Reynolds-Eyring (the base oil, tau0 = eyring_stress)
# or Herschel-Bulkley (a grease: consistency phi0 = hb_consistency [Pa s^n] with the Barus alpha, yield stress
# hb_yield_stress [Pa], exponent hb_exponent, creep hb_creep; lubedyn.lubrication.laws.lubricant.HerschelBulkleyFlow)
RHEOLOGIES = ("eyring", "herschel_bulkley")


def _get(params, key, default=None):
    if key in params:
        return params[key]
    if default is None:
        raise InputError(f"film point parameter {key!r} is missing "
                         "(give it, or start from the kind's default_params())")
    return default


def _lubricant(params):
    import lubedyn.lubrication as lub  # deferred: scikit-fem

    law = _get(params, "viscosity_law", "barus")
    eta0 = float(_get(params, "eta0"))
    if law == "barus":
        visc = lub.Barus(eta0, float(_get(params, "alpha")))
    elif law == "roelands":
        visc = lub.Roelands(eta0, alpha=float(_get(params, "alpha")))
    elif law == "constant":
        visc = lub.ConstantViscosity(eta0)
    else:
        raise unknown_choice("viscosity_law", law, VISCOSITY_LAWS)
    dlaw = _get(params, "density_law", "dowson_higginson")
    rho0 = float(_get(params, "rho0", OIL_RHO0))
    if dlaw == "dowson_higginson":
        dens = lub.DowsonHigginson(rho0)
    elif dlaw == "incompressible":
        dens = lub.Incompressible(rho0)
    else:
        raise unknown_choice("density_law", dlaw, DENSITY_LAWS)
    rheology = params.get("rheology", "eyring")  # absent (the ball kinds): eyring_stress decides
    if rheology not in RHEOLOGIES:
        raise unknown_choice("rheology", rheology, RHEOLOGIES)
    if rheology == "herschel_bulkley":
        phi0 = float(_get(params, "hb_consistency", 0.0))
        if not phi0 > 0.0 or not math.isfinite(phi0):
            raise InputError(f"params.hb_consistency = {params.get('hb_consistency')!r}: rheology = 'herschel_bulkley' "
                             "needs the grease's consistency phi0 > 0 [Pa s^n] (paper A Table 2: polyurea 8.44, "
                             "calcium 49.23 at 30 C)")
        if law != "barus":
            raise InputError(f"params.viscosity_law = {law!r}: rheology = 'herschel_bulkley' takes the consistency "
                             "phi = phi0 exp(alpha p) (Barus, paper A eq. 26); allowed: 'barus'")
        hb = lub.HerschelBulkleyFlow(float(_get(params, "hb_yield_stress", 0.0)),
                                     float(_get(params, "hb_exponent", 1.0)), float(_get(params, "hb_creep", 0.0)))
        return lub.Lubricant(lub.Barus(phi0, float(_get(params, "alpha"))), dens, herschel_bulkley=hb)
    tau0 = params.get("eyring_stress")  # absent or None: Newtonian
    return lub.Lubricant(visc, dens, None if tau0 is None else float(tau0))
