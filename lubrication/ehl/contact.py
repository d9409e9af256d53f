"""The EHL contact: geometry, materials, lubricant, kinematics and load of a point or line contact, and the traction laws.

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, require_positive, unknown_choice
from ..laws import contact as hertz
from ..laws.contact import hamrock_brewe_radius_ratio
from ..laws.lubricant import HB_PHI_CAP, Lubricant, eyring_flow_factor
from ..laws.lubricant import Barus, Incompressible

TRACTION_MODELS = ("newtonian", "limiting_shear", "eyring")


def supg_parameter(um, dx, rho, h, k):
    """Streamline-upwind parameter of the Reynolds equation at the quadrature points.

    Peclet number Pe = u_m dx rho h / (2 k), k = rho h^3/(12 eta) (so Pe = 6 u_m dx eta/h^2,
    rho cancels), capped at 1e8; tau = dx/(2 u_m) (coth Pe - 1/Pe) (Pe/3 below 1e-3) and its
    exact derivative d tau/d Pe (0 at the cap).  Returns ``(Pe, tau, dtau_dPe)``."""
    if um == 0.0:  # pure squeeze: no transport term, no stabilisation (tau u_m = 0)
        z = np.zeros(np.broadcast(rho, h, k).shape)
        return z, z, z
    Pe_raw = um * dx * rho * h / (2 * np.maximum(k, 1e-300))
    Pe = np.minimum(Pe_raw, 1e8)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        xi = np.where(Pe > 1e-3, 1.0 / np.tanh(np.minimum(Pe, 700)) - 1.0 / Pe, Pe / 3.0)
        sh = np.sinh(np.minimum(Pe, 300.0))
        dxi = np.where(Pe > 1e-3, 1.0 / Pe**2 - np.where(Pe < 300.0, 1.0 / sh**2, 0.0), 1.0 / 3.0)
    dxi = np.where(Pe_raw < 1e8, dxi, 0.0)
    return Pe, dx / (2 * um) * xi, dx / (2 * um) * dxi


def _log_slope(eta, deta):
    """d ln(eta)/dp, 0 where a far-off Newton iterate overflowed eta (there k = 0 and tau is capped)."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        r = deta / eta
    return np.where(np.isfinite(r), r, 0.0)


def _ratio(a, b):
    """a/b, 0 where b = 0 (a flow factor that vanishes: plug flow, where the products it enters vanish)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        r = np.where(b > 0, a / np.where(b > 0, b, 1.0), 0.0)
    return np.where(np.isfinite(r), r, 0.0)


def _eyring_terms(lub, h, grad_p, eta=None):
    """Non-Newtonian flow factors at the quadrature points (None for a Newtonian lubricant):
    Reynolds-Eyring (``eyring_stress``) or Herschel-Bulkley (``herschel_bulkley``).

    ``phi`` = Phi; ``c2`` = (dPhi/d|grad p|)/|grad p|, so that d(Phi grad p)/d(grad p) = Phi I + c2
    grad p grad p^T; ``dphi_dh`` = dPhi/dh at fixed grad p; ``c2_rel`` = c2/Phi and ``dlnphi_dh`` =
    dPhi/dh / Phi (0 where Phi = 0); ``dlnphi_dlneta`` = d ln Phi/d ln eta at fixed h, grad p.
    Eyring: Phi(x), x = s |grad p|, s = h/(2 tau0) (:func:`lubedyn.lubrication.laws.lubricant.eyring_flow_factor`),
    c2 = (Phi'/x) s^2, dPhi/dh = (Phi'/x) x^2/h, d ln Phi/d ln eta = 0.
    Herschel-Bulkley: Phi_HB(T_w, eta), T_w = h |grad p|/2, eta the consistency phi(p)
    (:func:`lubedyn.lubrication.laws.lubricant.herschel_bulkley_flow_factor`) plus the creep eps,
    c2 = Phi_T h/(2 |grad p|), dPhi/dh = Phi_T T_w/h, d ln Phi/d ln eta = (1 - 1/n) Phi_HB/Phi."""
    g2 = sum(np.asarray(grad_p[d]) ** 2 for d in range(len(grad_p)))
    hb = lub.herschel_bulkley
    if hb is not None:
        g = np.sqrt(g2)
        T = 0.5 * h * g
        phi_hb, dphi_T = hb.flow_factor(T, eta)
        phi = phi_hb + hb.creep
        c2 = _ratio(dphi_T * 0.5 * h, g)
        dphi_dh = dphi_T * T / h
        rel = (1.0 - 1.0 / hb.exponent) * _ratio(phi_hb, phi)
        return {"phi": phi, "c2": c2, "dphi_dh": dphi_dh, "c2_rel": _ratio(c2, phi),
                "dlnphi_dh": _ratio(dphi_dh, phi),
                "dlnphi_dlneta": np.where(phi_hb < HB_PHI_CAP, rel, 0.0)}
    tau0 = lub.eyring_stress
    if tau0 is None:
        return None
    s = h / (2.0 * tau0)
    x = s * np.sqrt(g2)
    phi, dphi_x = eyring_flow_factor(x)
    c2, dphi_dh = dphi_x * s**2, dphi_x * x**2 / h
    return {"phi": phi, "c2": c2, "dphi_dh": dphi_dh, "c2_rel": c2 / phi, "dlnphi_dh": dphi_dh / phi,
            "dlnphi_dlneta": 0.0}


@dataclass(frozen=True)
class Traction:
    """Shear law for friction.  ``newtonian``: tau = eta du/h;
    ``limiting_shear``: |tau| <= tau_L0 + gamma p; ``eyring``:
    tau = tau0 asinh(eta du/(h tau0)).  Stresses in Pa.

    The default is ``limiting_shear`` with tau_L0 = 5 MPa and gamma = 0.08: in the Hertz zone of an
    EHL contact the piezoviscous viscosity (Barus at 0.66 GPa and alpha 4.7e-8 1/Pa: 1e13 times eta0)
    makes a Newtonian shear meaningless (a traction coefficient of 3.8e20 at a slide-to-roll ratio of
    0.05), while measured traction curves of EHL contacts level off at 0.03-0.1 of the pressure: the
    limiting shear stress proportional to pressure of Bair & Winer (1979, J. Lubr. Technol. 101, 258;
    gamma 0.04-0.1 for mineral oils), the plateau of Johnson & Tevaarwerk's (1977, Proc. R. Soc. A 356,
    215) traction curves.  The Newtonian law stays for iso-viscous, lightly loaded films."""

    model: str = "limiting_shear"
    limiting_shear_stress: float = 5e6
    limiting_shear_slope: float = 0.08
    eyring_stress: float = 5e6

    def __post_init__(self):
        if self.model not in TRACTION_MODELS:
            raise unknown_choice("traction.model", self.model, TRACTION_MODELS)

    def stress(self, eta, sliding, h, p):
        """Couette shear stress [Pa] for sliding speed ``sliding`` = u2 - u1 [m/s]."""
        newt = eta * sliding / h
        if self.model == "newtonian":
            return newt
        if self.model == "limiting_shear":
            lim = self.limiting_shear_stress + self.limiting_shear_slope * np.maximum(p, 0.0)
            return np.sign(newt) * np.minimum(np.abs(newt), lim)
        return self.eyring_stress * np.arcsinh(newt / self.eyring_stress)


@dataclass(frozen=True)
class EHLContact:
    """An EHL contact (SI).

    ``radius_y=None`` makes a line contact (``load`` then in N/m).  Give
    ``load`` (load balance finds h00) or ``approach`` = h00 [m] (prescribed:
    h00 is the rigid-body separation, -h00 the approach of the bodies).
    ``mean_speed`` = u_m >= 0; u_m = 0 is a pure squeeze film (no transport term; the film then
    needs ``squeeze_velocity`` < 0 to carry a load, and has no Moes numbers: M = inf, L = 0).
    ``slide_to_roll`` = (u2 - u1)/u_m; ``squeeze_velocity`` = dh00/dt [m/s]
    (negative: the bodies approach; the Reynolds equation gets the source
    rho dh00/dt).  ``scale_load`` [N or N/m]: with a prescribed approach, the
    load whose Hertz contact sets the grid's length scales (default 1 N or
    1 N/m); give the load of a steady state to solve on the same grid.
    """

    radius_x: float
    radius_y: float | None
    e_star: float
    lubricant: Lubricant
    mean_speed: float
    load: float | None = None
    approach: float | None = None
    slide_to_roll: float = 0.0
    squeeze_velocity: float = 0.0
    traction: Traction = Traction()
    scale_load: float | None = None

    def __post_init__(self):
        require_positive("radius_x [m]", self.radius_x)
        if self.radius_y is not None:
            require_positive("radius_y [m]", self.radius_y)
        require_positive("reduced modulus E* [Pa]", self.e_star)
        if not (self.mean_speed >= 0.0 and np.isfinite(self.mean_speed)):
            raise InputError(f"mean (entrainment) speed [m/s] = {self.mean_speed!r} must be >= 0 (0: pure squeeze)")
        if self.mean_speed == 0.0 and self.load is not None and not self.squeeze_velocity < 0.0:
            raise InputError(f"squeeze_velocity = {self.squeeze_velocity!r} m/s with mean_speed = 0 and a load: a pure "
                             "squeeze film carries a load only while the bodies approach (squeeze_velocity < 0)")
        if (self.load is None) == (self.approach is None):
            raise InputError("an EHL contact needs exactly one of 'load' or 'approach'")
        if self.load is not None:
            require_positive("load [N or N/m]", self.load)
        if self.scale_load is not None:
            require_positive("scale_load [N or N/m]", self.scale_load)

    @property
    def is_line(self) -> bool:
        return self.radius_y is None

    @property
    def e_prime(self) -> float:
        return 2.0 * self.e_star

    def hertz_load(self) -> float:
        """Load used for the Hertz scales (the given load, else ``scale_load``, else 1)."""
        if self.load is not None:
            return self.load
        return self.scale_load if self.scale_load is not None else 1.0

    # dimensionless groups ----------------------------------------------
    @property
    def U(self) -> float:
        """Hamrock-Dowson speed parameter eta0 u_m / (E' R_x)."""
        return self.lubricant.viscosity.eta0 * self.mean_speed / (self.e_prime * self.radius_x)

    @property
    def G(self) -> float:
        """Material parameter alpha E' (alpha: Barus, or Roelands' low-pressure slope)."""
        return self.lubricant.viscosity.pressure_viscosity * self.e_prime

    @property
    def W(self) -> float:
        """Load parameter w/(E' R_x^2) (point) or w/(E' R_x) (line)."""
        return self.hertz_load() / (self.e_prime * self.radius_x ** (1 if self.is_line else 2))

    @property
    def moes_M(self) -> float:
        if self.U == 0.0:
            return float("inf")
        return self.W * (2 * self.U) ** (-0.5 if self.is_line else -0.75)

    @property
    def moes_L(self) -> float:
        return self.G * (2 * self.U) ** 0.25

    @classmethod
    def from_moes(cls, M, L, *, radius_x=0.01, e_star=1.0e11, eta0=0.04, mean_speed=None,
                  radius_y=..., line=False, density=None, **kw):
        """A circular (or ``line``) contact with Moes parameters ``M`` and ``L``.

        Radius, modulus and viscosity are fixed; the speed follows from ``L``
        only if ``mean_speed`` is None (then alpha = L/((2U)^(1/4) E')), else
        alpha is chosen from L at that speed.  Returns a Barus lubricant.
        """
        Ep = 2 * e_star
        if mean_speed is None:
            mean_speed = 1.0
        U = eta0 * mean_speed / (Ep * radius_x)
        alpha = L / ((2 * U) ** 0.25 * Ep)
        if line:
            load = M * (2 * U) ** 0.5 * Ep * radius_x
            ry = None
        else:
            load = M * (2 * U) ** 0.75 * Ep * radius_x**2
            ry = radius_x if radius_y is ... else radius_y
        lub = Lubricant(Barus(eta0, alpha), density or Incompressible(850.0))
        return cls(radius_x, ry, e_star, lub, mean_speed, load=load, **kw)

    @classmethod
    def from_hamrock_dowson(cls, W, U, G, k=1.0, *, radius_x=0.01, e_star=1.0e11, eta0=0.04, line=False,
                            ellipticity="exact", density=None, **kw):
        """A contact with Hamrock-Dowson groups ``W``, ``U``, ``G`` and ellipticity ``k`` = a/b.

        W = w/(E' R_x^2) (point; w/(E' R_x) with ``line=True``), U = eta0 u_m/(E' R_x),
        G = alpha E' (E' = 2 E*).  Radius, modulus and eta0 are fixed, so
        u_m = U E' R_x/eta0, alpha = G/E', w = W E' R_x^2 (or W E' R_x).  The
        radius ratio R_y/R_x (entrainment along the minor axis, k >= 1) is
        the one whose Hertz ellipse has a/b = k: exactly (``ellipticity=
        "exact"``), inverting the elliptic-integral relation of
        :mod:`lubedyn.lubrication.laws.contact`, R_y/R_x = (E(m)/(1 - m) - K(m))/(K(m) - E(m)),
        m = 1 - 1/k^2; or by Hamrock & Brewe's fit k = 1.0339 (R_y/R_x)^0.636
        (``"hamrock_brewe"``).  Returns a Barus lubricant.

        >>> c = EHLContact.from_hamrock_dowson(1e-6, 1e-11, 5000, 3.0)
        >>> round(c.W / 1e-6, 12), round(c.U / 1e-11, 12), round(c.G / 5000, 12)
        (1.0, 1.0, 1.0)
        """
        for key, val in (("W", W), ("U", U)):
            require_positive(f"Hamrock-Dowson {key}", val)
        if G < 0:
            raise InputError(f"Hamrock-Dowson G = {G!r} must be >= 0")
        if ellipticity not in hertz.METHODS:
            raise unknown_choice("ellipticity", ellipticity, hertz.METHODS)
        Ep = 2 * e_star
        mean_speed = U * Ep * radius_x / eta0
        lub = Lubricant(Barus(eta0, G / Ep), density or Incompressible(850.0))
        if line:
            return cls(radius_x, None, e_star, lub, mean_speed, load=W * Ep * radius_x, **kw)
        if not k >= 1.0:
            raise InputError(f"ellipticity k = {k!r} must be >= 1 (entrainment along the minor axis)")
        if ellipticity == "hamrock_brewe":
            ratio = hamrock_brewe_radius_ratio(k)
        elif k == 1.0:
            ratio = 1.0
        else:
            ratio = hertz.ellipse_radius_ratio(1.0 - 1.0 / k**2)
        return cls(radius_x, ratio * radius_x, e_star, lub, mean_speed, load=W * Ep * radius_x**2, **kw)
