"""Gap geometries h(x, y) of the Reynolds film, with their rigid-body modes.

A gap is a frozen dataclass in SI units (its lengths also taken as strings with units, ``"50 um"``, through
the case files' parser :mod:`lubedyn.lubrication.laws.units`), callable on coordinates ``x`` of shape
``(dim, ...)`` (the film's own plane; for a journal bearing ``x[0] = R*theta``
is the unwrapped circumferential length and ``x[1]`` the axial coordinate).

Rigid-body modes
----------------
``modes()`` maps a generalised coordinate name q to dh/dq(x).  The film's
generalised force on that coordinate is ``F_q = integral (p - p_amb) dh/dq dA``
(virtual work: a positive F_q pushes q towards a larger gap), its stiffness is
``K_ij = -dF_i/dq_j`` and its damping ``C_ij = -dF_i/d(dq_j/dt)``, where a mode
velocity adds ``dh/dq_j * dq_j/dt`` to the squeeze term dh/dt.  Every gap here
is affine in its q, so dh/dq does not depend on q.

- planar gaps: one mode ``"h0"`` (separation of the two surfaces along the
  film normal, +z); F_h0 is the load carried by the film;
- :class:`JournalBearing`: modes ``"x"`` and ``"y"``, the journal centre's
  displacement in the fixed frame; theta is measured from +x towards +y, and
  h = c - e_x cos(theta) - e_y sin(theta).  F_x, F_y are then the film force on
  the journal in that frame.

``surface_points`` / ``surface_normal`` give 3-D positions (for VTK: journals
are wrapped onto the cylinder) and the unit normal along which the pressure
pushes the *upper* body (the journal for a journal bearing).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import InputError, require_positive
from .laws.units import quantity, si_fields


class Gap:
    """Base class: planar film in the (x, y) plane with one approach mode ``h0``."""

    periodic_length: float | None = None

    def __call__(self, x):  # pragma: no cover - abstract
        raise NotImplementedError

    def modes(self) -> dict:
        return {"h0": lambda x: np.ones_like(np.asarray(x[0], dtype=float))}

    def surface_points(self, x):
        x = np.asarray(x, dtype=float)
        pts = np.zeros((3,) + x.shape[1:])
        pts[: x.shape[0]] = x
        return pts

    def surface_normal(self, x):
        x = np.asarray(x, dtype=float)
        n = np.zeros((3,) + x.shape[1:])
        n[2] = 1.0
        return n


def _r2(x):
    x = np.asarray(x, dtype=float)
    return sum(x[i] ** 2 for i in range(x.shape[0]))


@dataclass(frozen=True)
class InclinedSlider(Gap):
    """Plane inclined slider: h = h_in + (h_out - h_in) x / length, x in [0, length]."""

    h_in: float
    h_out: float
    length: float

    def __post_init__(self):
        si_fields(self, h_in="length", h_out="length", length="length")
        for k in ("h_in", "h_out", "length"):
            require_positive(f"gap {k} [m]", getattr(self, k))

    def __call__(self, x):
        return self.h_in + (self.h_out - self.h_in) * np.asarray(x[0], dtype=float) / self.length


@dataclass(frozen=True)
class StepSlider(Gap):
    """Rayleigh step: h = h_in for x < x_step, h_out for x >= x_step."""

    h_in: float
    h_out: float
    x_step: float

    def __post_init__(self):
        si_fields(self, h_in="length", h_out="length", x_step="length")
        require_positive("gap h_in [m]", self.h_in)
        require_positive("gap h_out [m]", self.h_out)

    def __call__(self, x):
        return np.where(np.asarray(x[0]) < self.x_step, self.h_in, self.h_out).astype(float)


@dataclass(frozen=True)
class PocketedSlider(Gap):
    """Linear slider h_in -> h_out over ``length`` with a pocket of ``depth`` in
    [pocket_start, pocket_end] (Fowell, Olver, Gosman & Spikes 2007, Tribol. Int.)."""

    h_in: float
    h_out: float
    length: float
    pocket_start: float
    pocket_end: float
    depth: float

    def __post_init__(self):
        si_fields(self, h_in="length", h_out="length", length="length", pocket_start="length", pocket_end="length",
                  depth="length")
        for k in ("h_in", "h_out", "length"):
            require_positive(f"gap {k} [m]", getattr(self, k))
        if not 0 <= self.pocket_start < self.pocket_end <= self.length:
            raise InputError(
                f"pocket [{self.pocket_start}, {self.pocket_end}] m must lie inside [0, {self.length}] m"
            )

    def __call__(self, x):
        x0 = np.asarray(x[0], dtype=float)
        h = self.h_in + (self.h_out - self.h_in) * x0 / self.length
        inside = (x0 > self.pocket_start) & (x0 < self.pocket_end)
        return h + np.where(inside, self.depth, 0.0)


@dataclass(frozen=True)
class JournalBearing(Gap):
    """Plain journal bearing, unwrapped: x[0] = R theta in [0, 2 pi R), x[1] = z.

    h = c - e_x cos(theta) - e_y sin(theta); ``eccentricity_x``/``_y`` [m].
    """

    radius: float
    clearance: float
    eccentricity_x: float = 0.0
    eccentricity_y: float = 0.0

    def __post_init__(self):
        si_fields(self, radius="length", clearance="length", eccentricity_x="length", eccentricity_y="length")
        require_positive("journal radius [m]", self.radius)
        require_positive("radial clearance [m]", self.clearance)
        eps = np.hypot(self.eccentricity_x, self.eccentricity_y) / self.clearance
        if eps >= 1.0:
            raise InputError(
                f"eccentricity ratio = {eps:.4g} must be < 1 (the journal would touch the bearing)"
            )

    @classmethod
    def from_ratio(cls, radius, clearance, eccentricity_ratio, attitude_angle=0.0):
        """Journal centre at distance eps*c along angle ``attitude_angle`` [rad] from +x (numbers in SI, or
        strings with units: ``from_ratio("25 mm", "50 um", 0.6, "30 deg")``)."""
        clearance = quantity(clearance, "length", "JournalBearing.from_ratio clearance")
        eccentricity_ratio = quantity(eccentricity_ratio, "dimensionless", "JournalBearing.from_ratio eccentricity_ratio")
        attitude_angle = quantity(attitude_angle, "angle", "JournalBearing.from_ratio attitude_angle")
        e = eccentricity_ratio * clearance
        return cls(radius, clearance, e * np.cos(attitude_angle), e * np.sin(attitude_angle))

    @property
    def periodic_length(self):
        return 2.0 * np.pi * self.radius

    def theta(self, x):
        return np.asarray(x[0], dtype=float) / self.radius

    def __call__(self, x):
        t = self.theta(x)
        return self.clearance - self.eccentricity_x * np.cos(t) - self.eccentricity_y * np.sin(t)

    def modes(self):
        return {
            "x": lambda x: -np.cos(self.theta(x)),
            "y": lambda x: -np.sin(self.theta(x)),
        }

    def surface_points(self, x):
        t = self.theta(x)
        z = np.asarray(x[1], dtype=float) if np.asarray(x).shape[0] > 1 else np.zeros_like(t)
        return np.stack([self.radius * np.cos(t), self.radius * np.sin(t), z])

    def surface_normal(self, x):
        t = self.theta(x)
        return np.stack([-np.cos(t), -np.sin(t), np.zeros_like(t)])


@dataclass(frozen=True)
class SpherePlane(Gap):
    """Sphere of ``radius`` over a plane, closest gap ``h0`` at the origin.

    ``exact=False`` uses the parabolic gap h0 + r^2/(2R) (the one behind the
    classical squeeze-film formulas); ``exact=True`` the true sphere.
    """

    radius: float
    h0: float
    exact: bool = False

    def __post_init__(self):
        si_fields(self, radius="length", h0="length")
        require_positive("sphere radius [m]", self.radius)
        require_positive("central gap h0 [m]", self.h0)

    def __call__(self, x):
        r2 = _r2(x)
        R = self.radius
        if self.exact:
            if np.any(r2 >= R * R):
                raise InputError("film domain extends beyond the sphere radius")
            return self.h0 + R - np.sqrt(R * R - r2)
        return self.h0 + r2 / (2.0 * R)


@dataclass(frozen=True)
class SphereSphere(Gap):
    """Two spheres ``radius1``, ``radius2`` with centre-line gap ``h0``.

    Parabolic form h0 + r^2/(2 R_eff), 1/R_eff = 1/R1 + 1/R2 (for equal balls
    R_eff = R/2), or the exact sum of both spherical caps (``exact=True``).
    Paper B (Zhang et al. 2024): neighbouring balls of a cage-less bearing.
    """

    radius1: float
    radius2: float
    h0: float
    exact: bool = False

    def __post_init__(self):
        si_fields(self, radius1="length", radius2="length", h0="length")
        require_positive("sphere radius1 [m]", self.radius1)
        require_positive("sphere radius2 [m]", self.radius2)
        require_positive("central gap h0 [m]", self.h0)

    @property
    def effective_radius(self):
        return 1.0 / (1.0 / self.radius1 + 1.0 / self.radius2)

    def __call__(self, x):
        r2 = _r2(x)
        if self.exact:
            R1, R2 = self.radius1, self.radius2
            if np.any(r2 >= min(R1, R2) ** 2):
                raise InputError("film domain extends beyond the smaller sphere radius")
            return self.h0 + (R1 - np.sqrt(R1 * R1 - r2)) + (R2 - np.sqrt(R2 * R2 - r2))
        return self.h0 + r2 / (2.0 * self.effective_radius)


@dataclass(frozen=True)
class CylinderPlane(Gap):
    """Cylinder (axis along y) over a plane: h = h0 + x^2 / (2 R) (line contact)."""

    radius: float
    h0: float

    def __post_init__(self):
        si_fields(self, radius="length", h0="length")
        require_positive("cylinder radius [m]", self.radius)
        require_positive("central gap h0 [m]", self.h0)

    def __call__(self, x):
        return self.h0 + np.asarray(x[0], dtype=float) ** 2 / (2.0 * self.radius)


@dataclass(frozen=True)
class EllipsoidPlane(Gap):
    """Ellipsoid with principal radii ``radius_x``, ``radius_y`` over a plane
    (ball on a raceway, reduced radii): h = h0 + x^2/(2 Rx) + y^2/(2 Ry)."""

    radius_x: float
    radius_y: float
    h0: float

    def __post_init__(self):
        si_fields(self, radius_x="length", radius_y="length", h0="length")
        require_positive("radius_x [m]", self.radius_x)
        require_positive("radius_y [m]", self.radius_y)
        require_positive("central gap h0 [m]", self.h0)

    def __call__(self, x):
        x = np.asarray(x, dtype=float)
        h = self.h0 + x[0] ** 2 / (2.0 * self.radius_x)
        if x.shape[0] > 1:
            h = h + x[1] ** 2 / (2.0 * self.radius_y)
        return h


@dataclass(frozen=True)
class FunctionGap(Gap):
    """A user gap ``h = func(x)``; ``modes`` optional mapping name -> dh/dq(x)."""

    func: object
    mode_funcs: tuple = ()

    def __call__(self, x):
        return np.asarray(self.func(np.asarray(x, dtype=float)), dtype=float)

    def modes(self):
        return dict(self.mode_funcs) if self.mode_funcs else super().modes()


@dataclass(frozen=True)
class ShiftedGap(Gap):
    """``base`` displaced by ``amount`` along its mode ``mode`` (for finite differences)."""

    base: Gap
    mode: str
    amount: float

    @property
    def periodic_length(self):
        return self.base.periodic_length

    def __call__(self, x):
        return self.base(x) + self.amount * self.base.modes()[self.mode](x)

    def modes(self):
        return self.base.modes()

    def surface_points(self, x):
        return self.base.surface_points(x)

    def surface_normal(self, x):
        return self.base.surface_normal(x)
