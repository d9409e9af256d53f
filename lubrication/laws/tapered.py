r"""Tapered roller bearing geometry and ideal kinematics (paper A: Wu, Xu & Deng 2018, Table 1).

Everything lives in the bearing's meridional plane through one roller: x along the bearing axis
(towards the roller's large end), r radial.  The roller's reference point C0 = (0, R_p) is the
mid-point of its axis (R_p the pitch radius); its axis has the unit direction
e = (cos alpha_r, sin alpha_r), alpha_r the roller axis angle; slices sit at u in [-l_e/2, l_e/2]
along e from C0, and the roller radius (normal to its axis) is rho(u) = rho_m + u tan(phi) - z(u)
with phi the half-taper and z the crown.  Raceways are straight lines (cup at alpha_o, cone at
alpha_i to the axis, i.e. their contact angles) with unit normals pointing into the roller::

    n_o = (sin alpha_o, -cos alpha_o),     n_i = (-sin alpha_i, cos alpha_i)

Reconciliation of Table 1 (Wu, Xu & Deng 2018).  Table 1 is not a
common-apex design: the roller's half-taper atan((24.76 - 17.85)/(2 x 42.06)) = 4.70 deg (end
diameters printed swapped) does not equal (15 - 5)/2 = 5 deg, and with 15/5 deg raceways through a
common apex the pitch radius 89 mm would need a 90 mm roller.  Pitch radius, mean roller diameter,
l_e, a common apex and both printed contact angles cannot all be kept; the two options:

``"common_apex"`` (default)
    keeps the pitch radius R_p = (99.52 + 78.48)/2 = 89 mm, the mean roller diameter
    D_m = 21.305 mm, l_e, and the roller axis angle alpha_r = (15 + 5)/2 = 10 deg (the mean of
    the printed contact angles); the cup, cone and roller axis meet at the apex A = (-R_p/tan
    alpha_r, 0) on the bearing axis, so the half-taper is phi = atan(rho_m/L), L = R_p/sin
    alpha_r = 512.5 mm: phi = 1.19 deg, and the raceway (contact) angles become alpha_r +- phi =
    11.19 / 8.81 deg.  Pure rolling along the whole line (no end sliding).
``"literal"``
    keeps the printed contact angles (15 / 5 deg), the roller (its 4.70 deg half-taper, D_m, l_e),
    the axis at 10 deg through (0, R_p).  The roller generatrices then miss the raceways by
    (alpha_o - alpha_i)/2 - phi = 0.30 deg each, so each raceway line is placed where it touches
    the unloaded roller at one end only (the small end; no overlap elsewhere: 0.11 mm gap at the
    large end).  The printed radii 99.52 / 78.48 cannot hold at mid-length (they leave a 20.64 mm
    normal gap for a 21.22 mm roller section); :attr:`raceway_radii_at_mid` gives the radii used.
    The roller ends slide against the races (:meth:`end_sliding`: +13.6 / -14.2 % on the cone),
    and under load the roller tilts to the edge of a slice (the literal geometry is edge-loaded).

Flange (rib, on the cone at the large end).  The flange contact angle beta_f (83 deg) is the angle
between the rib's contact normal and the radial plane, as for the raceways, so the rib pushes the
roller along n_f = (-sin beta_f, -cos beta_f).  The roller's large end is a sphere of radius r_s
whose vertex is the end face centre C0 + (l_e/2) e (assumed: l_e taken as the length between end
faces); its centre S_f = C0 + (l_e/2 - r_s) e; the contact point P_f = S_f - r_s n_f; the rib face
is the line through P_f normal to n_f, and the flange interference is r_s - n_f.(S_f - P_f)
(paper eq. 20).  The contact point lies (r_s sin(angle(e, -n_f))) off the roller axis towards the
cone; its height above the cone raceway must be below the rib height.  Hertz curvatures of the
flange contact: 1/r_s in both directions on the roller; the rib is straight in the meridional plane
and concave circumferentially (-cos beta_f / r_P, r_P the contact point's radius).

Cage and guide land (Table 1's cage, 196.1-205.8 mm, does not fit between the raceways): the cage ring
and its inner-ring guide land are placed beyond the large end, at
x = x(large end face) + land gap + width/2 (land gap assumed), land radius = cage bore/2 -
clearance/2 with the 0.5 mm guide land clearance read as diametral (eq. 43's (r_y - r_d)/2).

Crown z(u): ``"straight"`` (z = 0) or ``"logarithmic"``, Lundberg's profile with the Johns & Gohar
(1981) end correction::

    z(u) = (2 Q_d / (pi l_e E')) ln(1 / (1 - (1 - 0.3033 b/a) (2u/l_e)^2)),   a = l_e/2

(E' = E/(1 - nu^2) for two equal steel bodies, b the Hertz half-width of the cup contact at the
design load Q_d, which stays finite at the ends).

Ideal kinematics (cup fixed, cone at omega_i, pure rolling at the mid-slice contacts whose radii
are r_i, r_o; for a common apex this is pure rolling along the whole line)::

    omega_c = omega_i r_i / (r_i + r_o) = omega_i (1 - gamma)/2,   gamma = (r_o - r_i)/(r_o + r_i)
    roller spin relative to the cage  omega_R = omega_c r_o / rho_m
    entrainment speed                 u_e = omega_c r_o = (omega_i - omega_c) r_i

(the mid-slice contact points sit at R_p -+ rho_m cos(alpha_r) in both readings, so gamma =
D_m cos(alpha_r)/d_m exactly: 1,058.55 rpm at 2,400 rpm; the conventions D_m cos(alpha)/d_m with
alpha = 5, 10, 15 deg (the cone's, the roller axis' and the cup's angle) give 1,056.9 / 1,058.5 / 1,061.3 rpm.)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, unknown_choice
from . import contact as hertz
from .contact import positive

RECONCILIATIONS = ("common_apex", "literal")
PROFILES = ("straight", "logarithmic")
JOHNS_GOHAR = 0.3033  # Johns & Gohar (1981): 1 - 0.3033 b/a keeps the logarithmic crown finite


def _unit(angle):
    return np.array([math.cos(angle), math.sin(angle)])


def _touching_line(c0, e, rho_m, phi, length, n):
    """A point of the raceway line of unit normal n that touches the straight roller (axis e through
    c0, radius rho_m + u tan(phi)) without overlapping it anywhere: placed tangent to the mid slice
    (n.(c0 - X) = rho_m sqrt(1 - (n.e)^2)), then moved off along n by the largest end overlap (the
    interference is linear in u, so an end decides)."""
    s = math.sqrt(1.0 - float(n @ e) ** 2)
    p = c0 - n * rho_m * s
    ends = np.array([-0.5 * length, 0.5 * length])
    overlap = (rho_m + ends * math.tan(phi)) * s - n @ (c0[:, None] + e[:, None] * ends[None, :] - p[:, None])
    return p - float(overlap.max()) * n


@dataclass(frozen=True)
class TaperedRollerGeometry:
    """Tapered roller bearing (SI, angles in rad); derived fields are computed on construction.

    Inputs: Table 1 of paper A plus the assumed ``rib_height``, ``land_axial_gap``, ``density``,
    crown design load ``crown_load`` (``profile="logarithmic"``)."""

    n_rollers: int
    effective_length: float
    large_end_diameter: float
    small_end_diameter: float
    end_sphere_radius: float
    outer_contact_angle: float
    inner_contact_angle: float
    flange_contact_angle: float
    outer_raceway_radius: float
    inner_raceway_radius: float
    rib_height: float
    cage_outer_diameter: float
    cage_inner_diameter: float
    cage_thickness: float
    guide_land_clearance: float
    guide_land_width: float
    pocket_clearance: float
    modulus: float
    poisson: float
    density: float
    land_axial_gap: float
    reconciliation: str = "common_apex"
    profile: str = "straight"
    crown_load: float = 0.0

    # derived (meridional plane, see the module docstring)
    pitch_radius: float = field(init=False)
    mean_roller_radius: float = field(init=False)
    roller_axis_angle: float = field(init=False)
    half_taper: float = field(init=False)
    cup_angle: float = field(init=False)
    cone_angle: float = field(init=False)
    axis_direction: np.ndarray = field(init=False, repr=False)
    cup_point: np.ndarray = field(init=False, repr=False)
    cup_normal: np.ndarray = field(init=False, repr=False)
    cone_point: np.ndarray = field(init=False, repr=False)
    cone_normal: np.ndarray = field(init=False, repr=False)
    apex_x: float = field(init=False)
    raceway_radii_at_mid: tuple = field(init=False)
    contact_radii: tuple = field(init=False)
    sphere_center_u: float = field(init=False)
    flange_normal: np.ndarray = field(init=False, repr=False)
    flange_point: np.ndarray = field(init=False, repr=False)
    flange_height: float = field(init=False)
    flange_offset: float = field(init=False)
    e_prime: float = field(init=False)
    e_star: float = field(init=False)
    cup_half_width_at_crown_load: float = field(init=False)
    land_radius: float = field(init=False)
    land_x: float = field(init=False)
    cage_x: float = field(init=False)

    def __post_init__(self):
        s = lambda k, v: object.__setattr__(self, k, v)  # noqa: E731
        self._validate()
        ai, ao, bf = self.inner_contact_angle, self.outer_contact_angle, self.flange_contact_angle
        l = self.effective_length
        rp = 0.5 * (self.outer_raceway_radius + self.inner_raceway_radius)
        rho_m = 0.25 * (self.large_end_diameter + self.small_end_diameter)
        alpha_r = 0.5 * (ao + ai)
        c0 = np.array([0.0, rp])
        if self.reconciliation == "common_apex":
            L = rp / math.sin(alpha_r)
            phi = math.atan(rho_m / L)
            cup, cone = alpha_r + phi, alpha_r - phi
            apex = np.array([-L * math.cos(alpha_r), 0.0])
            n_o, n_i = np.array([math.sin(cup), -math.cos(cup)]), np.array([-math.sin(cone), math.cos(cone)])
            p_o, p_i = apex.copy(), apex.copy()
        else:
            phi = math.atan((self.large_end_diameter - self.small_end_diameter) / (2.0 * l))
            cup, cone = ao, ai
            n_o, n_i = np.array([math.sin(cup), -math.cos(cup)]), np.array([-math.sin(cone), math.cos(cone)])
            p_o = _touching_line(c0, _unit(alpha_r), rho_m, phi, l, n_o)
            p_i = _touching_line(c0, _unit(alpha_r), rho_m, phi, l, n_i)
            # the two lines meet where n_o.(X - p_o) = n_i.(X - p_i) = 0
            A = np.array([n_o, n_i])
            apex = np.linalg.solve(A, np.array([n_o @ p_o, n_i @ p_i]))
        e = _unit(alpha_r)
        for k, v in (("pitch_radius", rp), ("mean_roller_radius", rho_m), ("roller_axis_angle", alpha_r),
                     ("half_taper", phi), ("cup_angle", cup), ("cone_angle", cone), ("axis_direction", e),
                     ("cup_point", p_o), ("cup_normal", n_o), ("cone_point", p_i), ("cone_normal", n_i),
                     ("apex_x", float(apex[0]))):
            s(k, v)
        s("raceway_radii_at_mid", (self._line_radius(p_o, cup, 0.0), self._line_radius(p_i, cone, 0.0)))
        q_o, q_i = self.contact_point(0.0, "cup"), self.contact_point(0.0, "cone")
        s("contact_radii", (float(q_o[1]), float(q_i[1])))
        # flange
        rs = self.end_sphere_radius
        n_f = np.array([-math.sin(bf), -math.cos(bf)])
        u_s = 0.5 * l - rs
        centre = c0 + u_s * e
        p_f = centre - rs * n_f
        rel = p_f - c0
        offset = float(e[0] * rel[1] - e[1] * rel[0])   # signed distance of P_f from the axis (+ cup side)
        s("sphere_center_u", u_s)
        s("flange_normal", n_f)
        s("flange_point", p_f)
        s("flange_offset", offset)
        s("flange_height", float(n_i @ (p_f - p_i)))
        large_radius = self.roller_radius(0.5 * l, crown=False)
        if abs(offset) >= large_radius:
            raise InputError(f"flange_contact_angle = {math.degrees(bf):.4g} deg puts the flange contact "
                             f"{abs(offset) * 1e3:.4g} mm off the roller axis, outside the large end "
                             f"(radius {large_radius * 1e3:.4g} mm)")
        if not 0.0 < self.flange_height < self.rib_height:
            raise InputError(f"rib_height = {self.rib_height!r} m must exceed the flange contact point's "
                             f"height {self.flange_height:.4g} m above the cone raceway")
        e_star = hertz.reduced_modulus(self.modulus, self.poisson, self.modulus, self.poisson)
        s("e_star", e_star)
        s("e_prime", 2.0 * e_star)
        b = 0.0
        if self.crown_load > 0.0:
            b = hertz.line_contact(self.crown_load / l, self.reduced_radius("cup"), e_star).b
        s("cup_half_width_at_crown_load", b)
        # cage and guide land, beyond the large end (assumed placement)
        x_end = float((c0 + 0.5 * l * e)[0]) + large_radius * math.sin(alpha_r)
        s("land_x", x_end + self.land_axial_gap + 0.5 * self.guide_land_width)
        s("cage_x", self.land_x)
        s("land_radius", 0.5 * self.cage_inner_diameter - 0.5 * self.guide_land_clearance)

    def _validate(self):
        """One-line :class:`InputError` for bad inputs (before any derived value)."""
        if self.reconciliation not in RECONCILIATIONS:
            raise unknown_choice("reconciliation", self.reconciliation, RECONCILIATIONS)
        if self.profile not in PROFILES:
            raise unknown_choice("profile", self.profile, PROFILES)
        if int(self.n_rollers) != self.n_rollers or self.n_rollers < 3:
            raise InputError(f"n_rollers = {self.n_rollers!r} must be an integer >= 3")
        for key in ("effective_length", "large_end_diameter", "small_end_diameter", "end_sphere_radius",
                    "outer_raceway_radius", "inner_raceway_radius", "rib_height", "cage_outer_diameter",
                    "cage_inner_diameter", "cage_thickness", "guide_land_width", "modulus", "density"):
            positive(key, getattr(self, key))
        for key in ("guide_land_clearance", "pocket_clearance", "land_axial_gap", "crown_load"):
            v = float(getattr(self, key))
            if not (v >= 0.0 and math.isfinite(v)):
                raise InputError(f"{key} = {v!r} must be a finite number >= 0")
        if self.profile == "logarithmic":
            positive("crown_load", self.crown_load)
        if not self.large_end_diameter > self.small_end_diameter:
            raise InputError(f"large_end_diameter = {self.large_end_diameter!r} must exceed "
                             f"small_end_diameter = {self.small_end_diameter!r}")
        ai, ao, bf = self.inner_contact_angle, self.outer_contact_angle, self.flange_contact_angle
        if not 0.0 <= ai < ao < 0.5 * math.pi:
            raise InputError(f"inner_contact_angle = {ai!r} rad must lie in [0, outer_contact_angle = {ao!r})")
        if not ao < bf < 0.5 * math.pi:
            raise InputError(f"flange_contact_angle = {bf!r} rad must lie in (outer_contact_angle, pi/2)")
        if not self.outer_raceway_radius > self.inner_raceway_radius:
            raise InputError(f"outer_raceway_radius = {self.outer_raceway_radius!r} must exceed "
                             f"inner_raceway_radius = {self.inner_raceway_radius!r}")
        if self.rib_height >= self.large_end_diameter:
            raise InputError(f"rib_height = {self.rib_height!r} m must be below the roller's large-end "
                             f"diameter {self.large_end_diameter!r} m (a rib taller than the roller)")
        if self.cage_inner_diameter >= self.cage_outer_diameter:
            raise InputError(f"cage_inner_diameter = {self.cage_inner_diameter!r} must be below "
                             f"cage_outer_diameter = {self.cage_outer_diameter!r}")

    # ---------------------------------------------------------------- geometry
    @staticmethod
    def _line_radius(point, angle, x):
        return float(point[1] + (x - point[0]) * math.tan(angle))

    def crown(self, u):
        """Crown drop z(u) [m] (0 for ``"straight"``; module docstring for ``"logarithmic"``)."""
        u = np.asarray(u, dtype=float)
        if self.profile == "straight":
            return np.zeros_like(u)
        a = 0.5 * self.effective_length
        k = 1.0 - JOHNS_GOHAR * self.cup_half_width_at_crown_load / a
        amp = 2.0 * self.crown_load / (math.pi * self.effective_length * self.e_prime)
        return amp * np.log(1.0 / (1.0 - k * np.clip(u / a, -1.0, 1.0) ** 2))

    def roller_radius(self, u, crown: bool = True):
        """rho(u) = rho_m + u tan(phi) - z(u) [m] at axial position u from the roller's mid-point."""
        u = np.asarray(u, dtype=float)
        rho = self.mean_roller_radius + u * math.tan(self.half_taper)
        return rho - self.crown(u) if crown else rho

    def slices(self, n_slices: int):
        """(centres u_k [m] from the mid-point, widths [m]) of ``n_slices`` equal slices over l_e."""
        if int(n_slices) != n_slices or n_slices < 1:
            raise InputError(f"n_slices = {n_slices!r} must be an integer >= 1")
        n = int(n_slices)
        w = self.effective_length / n
        return -0.5 * self.effective_length + (np.arange(n) + 0.5) * w, np.full(n, w)

    def race(self, which: str):
        """(point X, unit normal n towards the roller, contact angle) of the ``"cup"`` or ``"cone"`` line."""
        if which == "cup":
            return self.cup_point, self.cup_normal, self.cup_angle
        if which == "cone":
            return self.cone_point, self.cone_normal, self.cone_angle
        raise unknown_choice("race", which, ("cup", "cone"))

    def contact_point(self, u: float, which: str):
        """The rim point of the (uncrowned) slice at u nearest the raceway ``which`` (meridional plane)."""
        _, n, _ = self.race(which)
        e = self.axis_direction
        n_perp = n - (n @ e) * e
        centre = np.array([0.0, self.pitch_radius]) + u * e
        return centre - float(self.roller_radius(u, crown=False)) * n_perp / np.linalg.norm(n_perp)

    def interference(self, u, which: str):
        """Unloaded slice interference [m] (0 along the line for a common apex and a straight roller)."""
        x, n, _ = self.race(which)
        e = self.axis_direction
        u = np.asarray(u, dtype=float)
        centres = np.array([0.0, self.pitch_radius])[:, None] + e[:, None] * u[None, :]
        return self.roller_radius(u) * math.sqrt(1.0 - float(n @ e) ** 2) - n @ (centres - x[:, None])

    def reduced_radius(self, which: str) -> float:
        """Reduced radius R_x [m] of the mid-slice line contact: roller rho_m / cos(phi), race
        r_c / cos(alpha) (the cones' curvatures normal to their generatrices), concave for the cup."""
        _, _, angle = self.race(which)
        rho = self.mean_roller_radius / math.cos(self.half_taper)
        r_race = self.contact_radii[0 if which == "cup" else 1] / math.cos(angle)
        return 1.0 / (1.0 / rho + (-1.0 if which == "cup" else 1.0) / r_race)

    def flange_hertz_constant(self) -> float:
        """K [N/m^1.5] of Q_f = K delta^1.5 at the rib: sphere r_s against a rib straight in the
        meridional plane and concave (-cos beta_f / r_P) circumferentially."""
        rs = self.end_sphere_radius
        r_x, r_y = hertz.relative_radii((1.0 / rs, 0.0),
                                        (1.0 / rs, -math.cos(self.flange_contact_angle) / self.flange_point[1]))
        return hertz.hertz_constant(max(r_x, r_y), min(r_x, r_y), self.e_star)

    # ---------------------------------------------------------------- mass
    def roller_mass_properties(self, n_quad: int = 4000):
        """(mass [kg], I_x about the roller axis, I_y about a transverse axis through the mass centre
        [kg m^2], mass centre u [m]) of the uncrowned frustum of steel density, by midpoint quadrature
        of discs (error O(n_quad^-2) ~ 1e-8 relative)."""
        u, w = self.slices(n_quad)
        r = self.roller_radius(u, crown=False)
        dm = self.density * math.pi * r**2 * w
        m = float(dm.sum())
        uc = float((dm * u).sum() / m)
        ix = float((0.5 * dm * r**2).sum())
        iy = float((dm * (0.25 * r**2 + (u - uc) ** 2)).sum())
        return m, ix, iy, uc

    # ---------------------------------------------------------------- kinematics
    def cage_ratio(self) -> float:
        """omega_c / omega_i = r_i / (r_i + r_o) (= (1 - gamma)/2), cup fixed, mid-slice pure rolling."""
        r_o, r_i = self.contact_radii
        return r_i / (r_i + r_o)

    def kinematics(self, omega_inner: float) -> dict:
        """Ideal kinematics at cone speed ``omega_inner`` [rad/s], cup fixed (module docstring)."""
        r_o, r_i = self.contact_radii
        wc = omega_inner * self.cage_ratio()
        return {"cage speed [rad/s]": wc, "gamma": (r_o - r_i) / (r_o + r_i),
                "roller spin relative to cage [rad/s]": wc * r_o / self.mean_roller_radius,
                "entrainment speed [m/s]": wc * r_o, "cup contact radius [m]": r_o,
                "cone contact radius [m]": r_i}

    def end_sliding(self, u):
        """Sliding (roller surface speed / race surface speed - 1) at slice positions u against the
        (cup, cone), both in the cage frame, with pure rolling at the mid slice (ideal kinematics).
        The roller's speed is taken at the slice's rim point (radius rho(u)), the race's at the foot of
        that point on the raceway line (they differ where the literal geometry leaves a gap)."""
        u = np.atleast_1d(np.asarray(u, dtype=float))
        rho = self.roller_radius(u, crown=False) / self.mean_roller_radius
        out = []
        for which in ("cup", "cone"):
            x, n, _ = self.race(which)
            feet = [p - (n @ (p - x)) * n for p in (self.contact_point(ui, which) for ui in u)]
            r_mid = self.contact_point(0.0, which)
            r_mid = (r_mid - (n @ (r_mid - x)) * n)[1]
            out.append(rho / (np.array([f[1] for f in feet]) / r_mid) - 1.0)
        return out[0], out[1]
