r"""Flange (rib) / roller-end contact of a tapered roller bearing: paper A (Wu, Xu & Deng 2018), eqs. 20-27.

Geometry.  The roller end is a sphere of radius r_s (136.2 mm, Table 1); the rib face is a cone about
the bearing axis whose contact normal makes 90 deg - beta_f with the bearing axis (beta_f: the flange
contact angle, 83 deg).  At the contact, a distance r_f from the bearing axis, the cone's principal
curvatures are 0 along its generator and -cos(beta_f)/r_f along the circumference (Meusnier: the
parallel circle's curvature 1/r_f projected on the normal; negative: the normal, which points from the
rib to the sphere centre, leans towards the bearing axis, so the face is concave as the roller sees it).
Relative radii (:func:`rib_radii`)::

    1/R_gen = 1/r_s,   1/R_circ = 1/r_s - cos(beta_f)/r_f                  (R_circ > R_gen)

With r_f = 85.6 mm (assumed, parameter module) R_circ = 169.0 mm, R_gen = 136.2 mm: a mildly elliptical
contact, as eq. 20's text says (r_e > r_s).  The normal load is the exact Hertz point law of
:func:`lubedyn.lubrication.laws.contact.point_contact` (eq. 21 is Harris' form of the same theory,
q = (2 2^(1/2)/3) E' delta^(3/2) / (n_delta^(3/2) (sum rho)^(1/2)), checked in the tests).  Entrainment
and sliding are circumferential, i.e. along R_circ (the *major* axis of the ellipse).

Friction (eqs. 22-23)::

    f_f = f_asp + f_grease,   f_asp = (s0/p0) q_f exp(-B lambda^C),   lambda = h_c / sigma

s0/p0 = 0.2 (given); B, C and the composite roughness sigma are not given (assumed in the parameter
module).  ``mixing="paper"`` adds the two as printed; ``mixing="load_share"`` (an extension) weights the
grease traction by the fluid share 1 - exp(-B lambda^C), so that lambda -> 0 gives the boundary
friction (s0/p0) q_f exactly and lambda >> 3 the grease traction only (:func:`flange_friction`).

Grease traction (eqs. 26-27): eq. 26's Herschel-Bulkley law over the Hertz ellipse, eq. 27 read as
f = int tau dA (the printed "x" is read as a typo: a product would not be a force), with the limiting shear stress of
:func:`lubedyn.lubrication.laws.traction.limited_ellipse_traction` (unbounded as printed: tau ~ 5e13 Pa at
p = 0.43 GPa, D = 5e5 1/s).

The rib film (eq. 24-25).  As printed, eq. 24 is a dimensionless number with no length scale::

    H = 1.8035e-2 M^-0.5066 L^-1.1869,   M = W U^-3/4,  L = G U^1/4
    W = q_f/(E' r_s^2),  U = phi0 u_f/(E' r_s),  G = alpha E',  u_f = (u_flange + u_end)/2

Rebuilt here (``"paper_eq24"``) as h_c = r_s H: the only scaling of the printed groups that gives a
film of the order of an EHL film (Moes' h = r_s U^(1/2) H would give nanometres).  Even so its exponents
are not those of an EHL film (h ~ eta^0.08, alpha^-1.19: nearly blind to viscosity and thinner with a
larger alpha).  The alternative (default, ``"hamrock_dowson"``) is the Hamrock-Dowson (1977) central film
of :mod:`.film` with R_x = R_circ (the entrainment direction) and k = (transverse semi-axis)/(rolling
semi-axis) of the exact Hertz ellipse (k = 0.87 here, below the fit's 3-8, as usual for rib contacts).

What the choice does to lambda = h_c/sigma at paper A's rib operating points (measured and asserted in
tests/test_laws_flange.py::test_rib_film_ratio_at_paper_a_operating_points; sigma = 0.2 um assumed,
alpha = 4.662e-8 1/Pa, E' = 225.3 GPa, r_f = 85.6 mm; corners of flange loads 200-989 N x entrainment
8.1-20.2 m/s; 30 C)::

    viscosity reading                  hamrock_dowson h_c [um]   paper_eq24 h_c [um]
    base oil 0.1 Pa s                  8.4 - 17.3                12.4 - 30.1
    phi0 = 8.44 as Pa s ("paper")      164 - 337                 17.9 - 43.5
    apparent, polyurea (D = u_f/h_c)   13.5 - 26.5               13.2 - 31.9
    apparent, calcium                  6.9 - 12.9                12.4 - 30.0
    apparent, lithium                  0.144 - 0.249              9.7 - 23.4

So lambda >= 34 (asperity share exp(-B lambda^C) < 1e-50) for every combination except the apparent
reading of lithium with Hamrock-Dowson (lambda 0.72-1.25, share 0.10-0.30): only there does eq. 23's
asperity friction act, as the paper's explanation of Fig. 14 needs.  Under ``"paper_eq24"`` the film
barely moves with phi (2.44 -> 38.44 Pa s^n: x1.26), under Hamrock-Dowson it grows 6.3-fold.

The EHL rib film (``"ehl"``, not a closed form: :meth:`lubedyn.dynamics.tapered.model.TaperedBearing.rib_film`
reads it from a film map of kind ``ehl_rib``, :mod:`lubedyn.film_points.rib`): the project's point-EHL solver
on this contact (R_x = R_circ, R_y = r_s, Herschel-Bulkley flow of the case's grease), tabulated over the
flange load and the entrainment speed.  Hamrock-Dowson's fit (k = 1-8) is extrapolated here to k = 0.87
(entrainment along the ellipse's major axis); against the solver (65 x 57 nodes, the Newtonian film of lithium's
apparent viscosity, 2.25e-4 Pa s, Moes M 150-570, L 6-7), see tests/test_rib_film.py.  The solver reaches the
rib's thin films only (lithium: h_c 0.24 um at 500 N, 11.3 m/s, by its homotopy in (n, tau_y)); the base oil's,
polyurea's and calcium's films (7-300 um, Moes M 1-10 at L 25-40 for the oil) are in a light-load, strongly
piezoviscous corner where its Newton iterations stall and the multigrid stagnates (measured in
:mod:`lubedyn.film_points.rib`): for them the lambda of this table stands (>= 34: no asperity share).
"""
from __future__ import annotations

import math

from numba import njit

from ..errors import unknown_choice
from . import film as F
from .contact import point_contact, positive, relative_radii
from .jit import INLINE

#: rib film models of the tapered model's ``flange.rib_film``: two closed forms (:func:`rib_film`) and "ehl", the
#: central film of the project's EHL solver at the rib read from a film map of kind ``ehl_rib``
#: (:meth:`lubedyn.dynamics.tapered.model.TaperedBearing.rib_film`)
RIB_FILMS = ("hamrock_dowson", "paper_eq24", "ehl")
CLOSED_FORM_RIB_FILMS = ("hamrock_dowson", "paper_eq24")
MIXINGS = ("paper", "load_share")


def rib_radii(sphere_radius: float, rib_contact_radius: float, flange_angle: float) -> tuple[float, float]:
    """(R_circ, R_gen) [m]: relative radii of the roller-end sphere on the conical rib along the
    circumference (entrainment) and along the cone's generator; ``flange_angle`` beta_f [rad]."""
    rs = positive("roller end sphere radius r_s [m]", sphere_radius)
    rf = positive("rib contact radius r_f [m]", rib_contact_radius)
    rx, ry = relative_radii([1.0 / rs, -math.cos(flange_angle) / rf], [1.0 / rs, 0.0])
    return rx, ry


def rib_hertz(load: float, sphere_radius: float, rib_contact_radius: float, flange_angle: float, e_star: float):
    """Exact Hertz point contact (:class:`lubedyn.lubrication.laws.contact.HertzPoint`) of the rib contact;
    ``a`` lies along the circumference (the larger relative radius)."""
    rx, ry = rib_radii(sphere_radius, rib_contact_radius, flange_angle)
    return point_contact(load, rx, ry, e_star)


def paper_eq24_film(load, speed, viscosity, alpha, e_prime, sphere_radius):
    """Eq. 24-25 rebuilt as h_c = r_s 1.8035e-2 M^-0.5066 L^-1.1869 [m] (module docstring)."""
    U = viscosity * speed / (e_prime * sphere_radius)
    W = load / (e_prime * sphere_radius**2)
    M, L = W * U**-0.75, alpha * e_prime * U**0.25
    return sphere_radius * 1.8035e-2 * M**-0.5066 * L**-1.1869


def rib_film(model, load, speed, viscosity, alpha, e_prime, sphere_radius, rib_contact_radius, flange_angle):
    """Central film h_c [m] at the rib: ``model`` "hamrock_dowson" (R_x = R_circ, k from the exact
    Hertz ellipse) or "paper_eq24"; ``speed`` u_f [m/s] the entrainment speed."""
    if model not in CLOSED_FORM_RIB_FILMS:
        raise unknown_choice("rib film model", model, CLOSED_FORM_RIB_FILMS)
    load, speed = positive("flange load [N]", load), positive("rib entrainment speed u_f [m/s]", speed)
    viscosity, e_prime = positive("viscosity [Pa s]", viscosity), positive("E' [Pa]", e_prime)
    if model == "paper_eq24":
        return paper_eq24_film(load, speed, viscosity, alpha, e_prime, sphere_radius)
    rx, _ = rib_radii(sphere_radius, rib_contact_radius, flange_angle)
    hp = rib_hertz(load, sphere_radius, rib_contact_radius, flange_angle, 0.5 * e_prime)
    U, W, G = viscosity * speed / (e_prime * rx), load / (e_prime * rx * rx), alpha * e_prime
    return rx * F.hamrock_dowson_central(U, G, W, hp.b / hp.a)


@njit(**INLINE)
def asperity_share(film_ratio, b_coef, c_exp):
    """exp(-B lambda^C) of eq. 23 (1 at lambda = 0)."""
    return math.exp(-b_coef * max(film_ratio, 0.0) ** c_exp)


@njit(**INLINE)
def flange_friction(slip_speed, load, film_ratio, grease_force, mu_a, b_coef, c_exp, load_share):
    """f_f [N] of eqs. 22-23 along the sliding direction (sign of ``slip_speed``, the rib's surface speed
    minus the roller end's, force on the roller): mu_a q exp(-B lambda^C) sign(v_s) + w f_grease with
    w = 1 (``load_share`` False, as printed) or w = 1 - exp(-B lambda^C) (the fluid load share)."""
    share = asperity_share(film_ratio, b_coef, c_exp)
    f_asp = mu_a * load * share
    if slip_speed < 0.0:
        f_asp = -f_asp
    elif slip_speed == 0.0:
        f_asp = 0.0
    weight = 1.0 - share if load_share else 1.0
    return f_asp + weight * grease_force
