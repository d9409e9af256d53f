r"""Quasi-static equilibrium of a tapered roller bearing: rigid rings, cup fixed, sliced rollers.

Unknowns: the cone's translation d = (d_x, d_y, d_z) (its tilts locked by default: the shaft's other
support carries the moment) and, for each roller j at azimuth psi_j = 2 pi j/Z (psi = 0 along +y,
the radial load's direction), its displacement (a_j, r_j) and tilt theta_j in its meridional plane
(x axial towards the large end, r radial; skew and circumferential motion are the cage's and are
not modelled here).  The cone moves in roller j's plane by (d_x, d_y cos psi_j + d_z sin psi_j).

With ``cone_tilt = "free"`` the cone's tilt (theta_y, theta_z), a small rotation about its reference
point (the origin of the meridional coordinates), joins the unknowns: roller j sees it as the in-plane
rotation phi_j = theta . e_t(psi_j) = -theta_y sin psi_j + theta_z cos psi_j of the cone's raceway line
and rib about that point (e_t = (0, -sin psi, cos psi) the tangential axis).  Its out-of-plane part (a
rotation about the roller's radial axis, which moves the roller across the cone by theta x, and looks to
it like a skew) changes the interferences at second order only: at 4e-4 rad the compiled kernel's
exact 3-D evaluation of this equilibrium is off by about 1e-4 of the tilt and 1e-3 of x_F F_r in the
cone's moment (the dynamic start removes it, :meth:`lubedyn.dynamics.tapered.model.TaperedBearing.start_state`).
The external moment is that of the radial load at the axial position ``load_offset`` x_F, x_F F_r about
z (its point moves with the tilt by theta x x_F e_x: work M . theta), plus an applied (M_y, M_z); the
cone's moment balance is checked a posteriori from the contact points (as the force balance).

Contacts (laws in :mod:`lubedyn.lubrication.laws.slices` and :mod:`lubedyn.lubrication.laws.tapered`):

- cup and cone: n_s slices each, delta_k = rho_k sqrt(1 - (n.e)^2) - n.(S_k - X),
  q_k = k_w delta_k^(10/9), k_w = K_L/n_s with Palmgren's K_L (paper A eq. 11 without damping);
- flange (rib on the cone): delta_f = r_s - n_f.(S_f - P_f), Q_f = K_f delta_f^1.5 (Hertz, point).

Loads on roller j: centrifugal m omega_c^2 R_cm along r at the mass centre, R_cm its radius as the
roller is displaced (u_c along the axis from the mid-point, so with a moment about the mid-point;
omega_c the ideal cage speed at the given cone speed) and, optionally, the gyroscopic moment about the tangential axis
M = omega_c sin(beta) [I_x (omega_s + omega_c cos beta) - I_y omega_c cos beta], omega_s = -omega_c
r_o/rho_m the spin relative to the cage (a moment the contacts must supply).  Load on the cone: F_r
along +y and F_a along -x (pushing the cone into the cup: "closing"), or a prescribed axial
displacement d_x = -s (preload s > 0 closes; s = 0 locks the axial DOF, paper A's Figs. 5-9).

Method: the contact forces derive from the energy Pi = sum k_w delta^(19/9) 9/19 + sum K_f
delta_f^(5/2) 2/5 - (external work), whose gradient is the force residual.  Levenberg-Marquardt
Newton steps on the Hessian sum q'(delta) grad(delta) grad(delta)^T + q d^2(delta)/d(theta)^2 (delta is
linear in every other unknown), accepted when Pi falls, with a trust radius on the displacements (the
contacts start at zero load, where the Hessian vanishes, and a roller that loses every contact has a
singular block: its damped step is zero).  A step longer than the radius is tried two ways, damped until
it fits (the Levenberg-Marquardt trust region) and shortened along its own direction, and the one that
lowers Pi more is taken: shortened alone, a step dominated by one roller's soft mode froze every other
unknown.  Stop: every residual below ``tol`` x the largest contact force (rotations scaled by l_e/2),
checked a posteriori by the bearing's force balance; otherwise :class:`ConvergenceError`.  With the axial
DOF under a force, a force below :func:`axial_load_needed` (no equilibrium exists) is refused up front.

Geometry matters (see :mod:`lubedyn.lubrication.laws.tapered`).  With the default common-apex reading the
rollers carry line loads.  The literal reading of Table 1 is edge-loaded: each raceway touches the roller at
its small-end slice and the rib at its large end, three point contacts that do not hold it (the roller
tilts, into the 0.22 mm large-end gap, until a second slice takes part), and a roller held by its
centrifugal load alone lies on the cup, tilted by the 0.30 deg misfit of its generatrix.  Under an axial
load the rollers find equilibrium on one or two end slices (per-roller loads still follow the 15/5/83 deg
force triangle exactly); at Fig. 5's point (Fr 20 kN, axial locked, 2,400 rpm) the shortened steps stalled
at a relative residual 0.98 and the solve now converges in 18-28 iterations (3-20 slices), matching an
independent rigid-laminae equilibrium to 1e-6 (tests/test_trb_quasistatic.py).  Measured over a grid of
288 solves (both readings, crowned; Fr 5/20/40 kN axial locked, Fa 2/15/30 kN, Fr 20 + Fa 5 kN, preloads
10/40 um; 0/300/2,400/5,000 rpm; 3/5/10/20 slices): every solve with an equilibrium converges (common
apex in 7-26 iterations, literal 10-73) except 11 of the literal reading's 32 preloads, at 0-300 rpm, a
near-mechanism (the tilt absorbs tens of um of axial displacement) that stops at a relative residual
1e-9 .. 2e-7 (stagnation or the iteration limit); the 24 below the force bound are refused.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

import numpy as np

from lubedyn.lubrication.errors import ConvergenceError, InputError
from lubedyn.lubrication.laws import slices as sl
from lubedyn.lubrication.laws.tapered import TaperedRollerGeometry

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class QuasiStaticResult:
    """Per-roller loads [N] (cup, cone, flange), contact angles [rad] of each resultant (to the
    radial plane), approaches [m] (largest slice interference; flange interference), per-slice loads
    [N] (Z x n_s), roller displacements (a, r) [m] and tilts [rad], the cone's translation [m],
    the applied loads, ideal kinematics, and the solver's stop report."""

    azimuths: np.ndarray
    cup_loads: np.ndarray
    cone_loads: np.ndarray
    flange_loads: np.ndarray
    cup_angles: np.ndarray
    cone_angles: np.ndarray
    flange_angles: np.ndarray
    cup_approaches: np.ndarray
    cone_approaches: np.ndarray
    flange_approaches: np.ndarray
    cup_slice_loads: np.ndarray
    cone_slice_loads: np.ndarray
    roller_displacements: np.ndarray
    roller_tilts: np.ndarray
    cone_displacement: np.ndarray
    axial_load: float
    radial_load: float
    centrifugal_force: float
    gyroscopic_moment: float
    kinematics: dict
    stop_reason: str
    iterations: int
    residual: float
    force_balance_error: float
    cone_tilt: np.ndarray = field(default_factory=lambda: np.zeros(2))
    cone_moment: np.ndarray = field(default_factory=lambda: np.zeros(3))
    applied_moment: np.ndarray = field(default_factory=lambda: np.zeros(3))
    moment_balance_error: float = 0.0


class CaseTable:
    """Assembles the energy, residual and Gauss-Newton Hessian of the bearing (plain numpy)."""

    def __init__(self, g: TaperedRollerGeometry, n_slices, centrifugal, gyro_moment, tilt=False):
        self.g = g
        # the cone's unknowns: translation (3) and, with its tilt free, the tilt (theta_y, theta_z) scaled
        # to a length by the pitch radius (the contacts' lever arm)
        self.tilt = bool(tilt)
        self.nc = 5 if self.tilt else 3
        self.tilt_scale = g.pitch_radius
        self.Z = int(g.n_rollers)
        self.psi = 2.0 * math.pi * np.arange(self.Z) / self.Z
        self.u, _ = g.slices(n_slices)
        self.rho = g.roller_radius(self.u)
        self.k_w = sl.slice_constant(sl.palmgren_line_constant(g.effective_length), n_slices)
        self.K_f = g.flange_hertz_constant()
        self.scale = 0.5 * g.effective_length       # theta -> length
        self.fc, self.mg = centrifugal, gyro_moment
        self.near = False
        self.uc = g.roller_mass_properties()[3]
        # m omega_c^2 from the centrifugal force at the nominal mass-centre radius
        self.mw2 = centrifugal / (g.pitch_radius + self.uc * math.sin(g.roller_axis_angle))

    def unpack(self, q):
        return q[:3], q[self.nc:].reshape(self.Z, 3)

    def in_plane_tilt(self, q, j):
        """phi_j = theta . e_t(psi_j) [rad]: the cone's tilt seen in roller j's meridional plane (a rotation
        (x, r) -> (x cos phi - r sin phi, x sin phi + r cos phi) about the cone's reference point)."""
        return (-math.sin(self.psi[j]) * q[3] + math.cos(self.psi[j]) * q[4]) / self.tilt_scale

    def contacts(self, q):
        """For each roller: lists of (delta, grad over [a, r, theta~], grad over the cone's in-plane
        (dx, dr)) for the cup slices, the cone slices and the flange."""
        g = self.g
        d, rl = self.unpack(q)
        out = []
        for j in range(self.Z):
            a, r, th = rl[j]
            beta = g.roller_axis_angle + th / self.scale
            ex, er = math.cos(beta), math.sin(beta)
            cx, cr = a, g.pitch_radius + r
            dr = d[1] * math.cos(self.psi[j]) + d[2] * math.sin(self.psi[j])
            if self.tilt:
                out.append(self._tilted_contacts(q, j, d[0], dr, cx, cr, ex, er))
                continue
            rows = []
            for which, moves in (("cup", 0.0), ("cone", 1.0)):
                x, n, _ = g.race(which)
                px, pr = x[0] + moves * d[0], x[1] + moves * dr
                dl = np.empty(len(self.u))
                gr = np.empty((len(self.u), 3))
                cv = np.empty(len(self.u))
                for k, (u, rho) in enumerate(zip(self.u, self.rho)):
                    dl[k] = sl.slice_interference(cx + u * ex, cr + u * er, ex, er, rho, px, pr, n[0], n[1])
                    gx, gy, gb = sl.slice_interference_gradient(ex, er, rho, u, n[0], n[1])
                    gr[k] = gx, gy, gb / self.scale
                    cv[k] = sl.slice_interference_curvature(ex, er, rho, u, n[0], n[1]) / self.scale**2
                rows.append((dl, gr, moves * np.array([n[0], n[1]]), cv))
            nf, us = g.flange_normal, g.sphere_center_u
            sx, sr = cx + us * ex, cr + us * er
            pf = g.flange_point + np.array([d[0], dr])
            df = g.end_sphere_radius - (nf[0] * (sx - pf[0]) + nf[1] * (sr - pf[1]))
            dbeta = -us * (nf[0] * -er + nf[1] * ex)
            curv = us * (nf[0] * ex + nf[1] * er) / self.scale**2
            rows.append((np.array([df]), np.array([[-nf[0], -nf[1], dbeta / self.scale]]), nf.copy(),
                         np.array([curv])))
            out.append(rows)
        return out

    def _tilted_contacts(self, q, j, dx, dr, cx, cr, ex, er):
        """Roller j's rows of :meth:`contacts` with the cone's tilt free: the cone's raceway line and rib
        rotated by phi_j (:meth:`in_plane_tilt`) about its reference point, then moved by (dx, dr); each
        row's cone gradient is per slice over (dx, dr, phi):  d(delta)/d(dx, dr) = n', and
        d(delta)/d(phi) = -rho c (J n').e/sqrt(1 - c^2) - (J n').(S - d) (J the quarter turn (a, b) ->
        (-b, a), c = n'.e), which is rotating the roller by -phi about the cone's reference point."""
        g = self.g
        phi = self.in_plane_tilt(q, j)
        cp, sp = math.cos(phi), math.sin(phi)
        rows = []
        for which, moves in (("cup", False), ("cone", True)):
            x, n, _ = g.race(which)
            if moves:
                px, pr = cp * x[0] - sp * x[1] + dx, sp * x[0] + cp * x[1] + dr
                nx, nr = cp * n[0] - sp * n[1], sp * n[0] + cp * n[1]
            else:
                (px, pr), (nx, nr) = x, n
            dl = np.empty(len(self.u))
            gr = np.empty((len(self.u), 3))
            cv = np.empty(len(self.u))
            gc = np.zeros((len(self.u), 3))
            for k, (u, rho) in enumerate(zip(self.u, self.rho)):
                sx, sr = cx + u * ex, cr + u * er
                dl[k] = sl.slice_interference(sx, sr, ex, er, rho, px, pr, nx, nr)
                gx, gy, gb = sl.slice_interference_gradient(ex, er, rho, u, nx, nr)
                gr[k] = gx, gy, gb / self.scale
                cv[k] = sl.slice_interference_curvature(ex, er, rho, u, nx, nr) / self.scale**2
                if moves:
                    c = nx * ex + nr * er
                    jn_e = -nr * ex + nx * er
                    gc[k] = nx, nr, (-rho * c * jn_e / math.sqrt(max(1.0 - c * c, 1e-300))
                                     - (-nr * (sx - dx) + nx * (sr - dr)))
            rows.append((dl, gr, gc, cv))
        nf0, us = g.flange_normal, g.sphere_center_u
        nf = np.array([cp * nf0[0] - sp * nf0[1], sp * nf0[0] + cp * nf0[1]])
        pf = np.array([cp * g.flange_point[0] - sp * g.flange_point[1] + dx,
                       sp * g.flange_point[0] + cp * g.flange_point[1] + dr])
        sx, sr = cx + us * ex, cr + us * er
        df = g.end_sphere_radius - (nf[0] * (sx - pf[0]) + nf[1] * (sr - pf[1]))
        dbeta = -us * (nf[0] * -er + nf[1] * ex)
        curv = us * (nf[0] * ex + nf[1] * er) / self.scale**2
        gcf = np.array([[nf[0], nf[1], -(-nf[1] * (sx - dx) + nf[0] * (sr - dr))]])
        rows.append((np.array([df]), np.array([[-nf[0], -nf[1], dbeta / self.scale]]), gcf, np.array([curv])))
        return rows

    def _laws(self, delta, kind):
        dp = np.maximum(delta, 0.0)
        if kind < 2:
            k = self.k_w
            return (k * dp ** (19 / 9) * 9 / 19, k * dp ** (10 / 9), k * (10 / 9) * dp ** (1 / 9))
        K = self.K_f
        return K * dp**2.5 / 2.5, K * dp**1.5, 1.5 * K * np.sqrt(dp)

    def largest_load(self, cs):
        """The largest total contact load [N] of any roller contact at the contacts ``cs``."""
        return max(float(self._laws(row[0], kind)[1].sum()) for rows in cs for kind, row in enumerate(rows))

    def evaluate(self, q, f_cone, m_cone=None):
        """(energy, residual, Hessian, contacts) at q; f_cone the external force on the cone (x, y, z),
        m_cone the external moment (y, z) about its reference point (tilt free)."""
        Z, nc = self.Z, self.nc
        n = nc + 3 * Z
        grad = np.zeros(n)
        H = np.zeros((n, n))
        d, rl = self.unpack(q)
        energy = -float(f_cone @ d)
        grad[:3] -= f_cone
        if self.tilt:
            energy -= float(m_cone @ q[3:5]) / self.tilt_scale
            grad[3:5] -= m_cone / self.tilt_scale
        cs = self.contacts(q)
        for j, rows in enumerate(cs):
            c, s = math.cos(self.psi[j]), math.sin(self.psi[j])
            # map of the cone's in-plane (dx, dr) onto (d_x, d_y, d_z)
            P = np.array([[1.0, 0.0, 0.0], [0.0, c, s]])
            if self.tilt:   # (dx, dr, phi) onto (d_x, d_y, d_z, theta_y~, theta_z~)
                P = np.array([[1.0, 0.0, 0.0, 0.0, 0.0], [0.0, c, s, 0.0, 0.0],
                              [0.0, 0.0, 0.0, -s / self.tilt_scale, c / self.tilt_scale]])
            idx = np.r_[0:nc, nc + 3 * j: nc + 3 + 3 * j]
            # the gyroscopic moment the contacts supply, at the nominal axis angle (constant): its change
            # with the roller's tilt (1.6e-5 of it at 3e-6 rad) is a negative tilt stiffness that stalls the
            # solver where the literal geometry is near a mechanism
            energy -= self.mg * rl[j, 2] / self.scale
            grad[nc + 3 * j + 2] -= self.mg / self.scale
            # centrifugal: the potential -m omega_c^2 rho^2/2 of the mass centre at radius rho = R_p + r +
            # u_c sin(beta) (u_c along the axis from the mid-point the unknowns place), so the force follows
            # the roller's displacement and has the moment m omega_c^2 rho u_c cos(beta) about the mid-point
            beta = self.g.roller_axis_angle + rl[j, 2] / self.scale
            cb, sb, ir, it = math.cos(beta), math.sin(beta), nc + 3 * j + 1, nc + 3 * j + 2
            rho = self.g.pitch_radius + rl[j, 1] + self.uc * sb
            drho = self.uc * cb / self.scale
            # -m omega_c^2 (rho^2 - rho_0^2)/2 with rho - rho_0 formed without cancellation
            b0 = self.g.roller_axis_angle
            d_rho = rl[j, 1] + self.uc * 2.0 * math.cos(0.5 * (beta + b0)) * math.sin(0.5 * (beta - b0))
            energy -= self.mw2 * d_rho * (rho - 0.5 * d_rho)
            grad[ir] -= self.mw2 * rho
            grad[it] -= self.mw2 * rho * drho
            # its derivatives over (r, tilt), added below where the contacts keep the block positive
            h_c = -self.mw2 * np.array([[1.0, drho], [drho, drho * drho - rho * self.uc * sb / self.scale**2]])

            for kind, (dl, gr, gc, cv) in enumerate(rows):
                e, f, kp = self._laws(dl, kind)
                energy += float(e.sum())
                if self.tilt:
                    J = np.hstack([gc @ P, gr])
                else:
                    J = np.hstack([np.outer(np.ones(len(dl)), gc @ P), gr])   # d delta / d [d, roller]
                grad[idx] += f @ J
                H[np.ix_(idx, idx)] += J.T @ (kp[:, None] * J)
                H[idx[-1], idx[-1]] += float(f @ cv)
            # the centrifugal load's own (r, tilt) derivatives, once near the solution (``near``: the
            # contacts are established; from the start they stall the steps) and where the roller's contacts
            # keep the block positive.  They matter where the literal geometry is near a mechanism.
            blk = np.ix_([ir, it], [ir, it])
            if self.near and np.all(np.linalg.eigvalsh(H[blk] + h_c) > 0.0):
                H[blk] += h_c
        return energy, grad, H, cs


def axial_load_needed(g: TaperedRollerGeometry, radial_load: float, centrifugal: float) -> float:
    """The least axial force [N] under which the cone has an equilibrium (a necessary condition, from force
    balance alone).  Roller j's force on the cone is -(Q_i n_i + Q_f n_f) = Q_o,j n_o + F_c e_r (its own
    balance), so the cone's balance is F_a = sin(a_o) sum Q_o,j and F_r = cos(a_o) sum Q_o,j cos(psi_j)
    (the F_c terms cancel over equally spaced rollers).  Eliminating the rib from a roller's balance gives
    Q_o = [F_c sin(b_f) + Q_i sin(b_f + a_i)] / sin(b_f + a_o) >= Q_c = F_c sin(b_f)/sin(b_f + a_o), and
    sum Q_o,j >= Z Q_c + sum (Q_o,j - Q_c) cos(psi_j) = Z Q_c + F_r/cos(a_o), so

        F_a >= F_r tan(a_o) + Z F_c sin(a_o) sin(b_f)/sin(b_f + a_o)

    (a_o the cup angle, b_f the flange angle, F_c the centrifugal load per roller; the gyroscopic moment
    is a moment).  Below it the radial and centrifugal loads push the cone out of the cup: measured, every
    solve of a grid of 288 below it ended at the iteration limit (Fr 20 kN + Fa 5 kN at 5,000 rpm common
    apex, 5.8 kN needed; Fa 2 kN at 5,000 rpm literal, 2.5 kN; Fr 20 kN + Fa 5 kN at rest literal, 5.36 kN)."""
    ao, bf = g.cup_angle, g.flange_contact_angle
    return (radial_load * math.tan(ao)
            + g.n_rollers * centrifugal * math.sin(ao) * math.sin(bf) / math.sin(bf + ao))


def solve(geometry: TaperedRollerGeometry, *, radial_load: float = 0.0, axial_load: float | None = None,
          axial_displacement: float | None = None, inner_speed: float = 0.0, n_slices: int = 20,
          gyroscopic: bool = True, tol: float = 1e-10, max_iterations: int = 400, cone_tilt: str = "locked",
          load_offset: float = 0.0, applied_moment=(0.0, 0.0)) -> QuasiStaticResult:
    """Quasi-static equilibrium (module docstring).  Give ``axial_load`` [N] (F_a > 0 closes) or
    ``axial_displacement`` [m] (s > 0 closes; 0 locks the axial DOF), not both; ``radial_load`` [N]
    along +y; ``inner_speed`` [rad/s] of the cone for the centrifugal and gyroscopic loads.
    ``cone_tilt`` "locked" (tilts held at 0) or "free": then the cone's tilt (theta_y, theta_z) is
    solved for too, under the moment of the radial load acting at ``load_offset`` [m] from the cone's
    reference point (load_offset F_r about z) plus ``applied_moment`` (M_y, M_z) [N m]."""
    g = geometry
    if cone_tilt not in ("locked", "free"):
        raise InputError(f"cone_tilt = {cone_tilt!r} is not allowed; choose 'locked' or 'free'")
    tilt = cone_tilt == "free"
    if not math.isfinite(float(load_offset)):
        raise InputError(f"load_offset = {load_offset!r} must be a finite length [m]")
    if len(applied_moment) != 2 or not all(math.isfinite(float(v)) for v in applied_moment):
        raise InputError(f"applied_moment = {applied_moment!r} must be two finite numbers (M_y, M_z) [N m]")
    if (axial_load is None) == (axial_displacement is None):
        raise InputError(f"axial_load = {axial_load!r}, axial_displacement = {axial_displacement!r}: "
                         "give exactly one of them")
    for key, v in (("radial_load", radial_load), ("inner_speed", inner_speed)):
        if not (math.isfinite(float(v)) and float(v) >= 0.0):
            raise InputError(f"{key} = {v!r} must be a finite number >= 0")
    if axial_load is not None and not (math.isfinite(float(axial_load)) and axial_load >= 0.0):
        raise InputError(f"axial_load = {axial_load!r} must be a finite number >= 0 (F_a > 0 closes)")
    if axial_displacement is not None and not math.isfinite(float(axial_displacement)):
        raise InputError(f"axial_displacement = {axial_displacement!r} must be finite")
    if axial_load is not None and axial_load == 0.0 and radial_load > 0.0:
        raise InputError("axial_load = 0.0 with radial_load > 0: a single tapered roller bearing has no "
                         "equilibrium with a free axial DOF (docs/paper_a.md); lock it with axial_displacement = 0")
    kin = g.kinematics(inner_speed)
    wc = kin["cage speed [rad/s]"]
    m, ix, iy, uc = g.roller_mass_properties()
    r_cm = g.pitch_radius + uc * math.sin(g.roller_axis_angle)
    fc = m * wc**2 * r_cm
    if axial_load is not None:
        need = axial_load_needed(g, float(radial_load), fc)
        if axial_load < 0.99 * need:
            raise InputError(
                f"axial_load = {axial_load:g} N cannot hold the cone: the rollers' force balance needs F_a >= "
                f"F_r tan(a_o) + Z F_c sin(a_o) sin(b_f)/sin(b_f + a_o) = {need:.5g} N (radial_load = "
                f"{radial_load:g} N, cup angle a_o = {math.degrees(g.cup_angle):.4g} deg, centrifugal load F_c = "
                f"{fc:.4g} N per roller at inner_speed = {inner_speed:.4g} rad/s); raise axial_load above it or "
                f"lock the axial DOF (axial_displacement = 0)")
    mg = 0.0
    if gyroscopic:
        beta = g.roller_axis_angle
        ws = -kin["roller spin relative to cage [rad/s]"]
        mg = wc * math.sin(beta) * (ix * (ws + wc * math.cos(beta)) - iy * wc * math.cos(beta))
    model = CaseTable(g, n_slices, fc, -mg, tilt)
    n = model.nc + 3 * model.Z
    free = np.ones(n, bool)
    q = np.zeros(n)
    f_cone = np.array([0.0, float(radial_load), 0.0])
    # the external moment (y, z) on the cone about its reference point: F_r e_y at x_F e_x, plus M
    m_cone = np.array([float(applied_moment[0]), float(applied_moment[1]) + float(load_offset) * float(radial_load)])
    if axial_displacement is not None:
        free[0] = False
        q[0] = -float(axial_displacement)
    else:
        f_cone[0] = -float(axial_load)
    # reference stiffness (one line contact at 1 um) for the damping floor and the trust radius
    k_ref = (10 / 9) * model.k_w * len(model.u) * 1e-6 ** (1 / 9)
    trust = 5e-6
    mu = 1e-3
    energy, grad, H, cs = model.evaluate(q, f_cone, m_cone)
    stop, it, res = "iteration limit", 0, math.inf
    for it in range(1, max_iterations + 1):
        f_scale = max(float(np.abs(f_cone).max()), model.fc, abs(model.mg) / model.scale, 1.0,
                      model.largest_load(cs))
        if tilt:
            f_scale = max(f_scale, float(np.abs(m_cone).max()) / model.tilt_scale)
        res = float(np.abs(grad[free]).max()) / f_scale
        log.debug("iteration %d: residual %.3g, mu %.3g, trust %.3g m", it, res, mu, trust)
        if res < tol:
            stop = "tolerance met"
            break
        if res < 1e-4 and not model.near:
            model.near = True
            energy, grad, H, cs = model.evaluate(q, f_cone, m_cone)
        Hf = H[np.ix_(free, free)]
        D = np.maximum(np.diag(Hf), 1e-6 * k_ref)
        accepted = False
        for _ in range(80):
            step = np.linalg.solve(Hf + mu * np.diag(D), -grad[free])
            big = float(np.abs(step).max())
            capped = big > trust
            trials = [step]
            if capped:
                # a step longer than the trust radius is tried two ways, and the one that lowers the energy more
                # is taken: damped until it fits (the Levenberg-Marquardt trust region; the fitting damping is
                # this step's only) and shortened along its own direction.  Shortened alone, a direction
                # dominated by one soft mode (a roller held by two point contacts, as where the literal geometry
                # is edge-loaded) froze every other unknown (measured: Fig. 5's point read literally stalled
                # at a relative residual 0.98 for 400 iterations); damped alone, the steps near a solution,
                # where the energy's change is below its rounding and a falling residual decides, turned
                # towards the gradient, which need not reduce the residual (measured: the literal straight
                # roller under a 40 um preload at 2,500 rpm stagnated at 4e-8).
                mu_fit, fit = mu, step
                while float(np.abs(fit).max()) > trust and mu_fit < 1e300:
                    mu_fit *= 2.0
                    fit = np.linalg.solve(Hf + mu_fit * np.diag(D), -grad[free])
                trials = [fit, step * (trust / big)]
            best = None
            for trial in trials:
                qt = q.copy()
                qt[free] += trial
                e_t, g_t, H_t, cs_t = model.evaluate(qt, f_cone, m_cone)
                # energy descent; near the solution the energy change falls below its rounding, where a
                # falling residual decides
                if e_t < energy or (e_t <= energy + 1e-10 * abs(energy)
                                    and np.linalg.norm(g_t[free]) < np.linalg.norm(grad[free])):
                    if best is None or e_t < best[1]:
                        best = (qt, e_t, g_t, H_t, cs_t)
            if best is not None:
                accepted = True
                q, energy, grad, H, cs = best
                mu = max(mu / 4.0, 1e-12)
                if capped:
                    trust = min(2.0 * trust, 1e-3)
                break
            if capped:
                trust *= 0.5
                # a capped step that is not a descent direction (an indefinite Hessian: a roller barely held
                # in the unloaded zone at low speed) stays one however short: damp it towards the gradient
                # (measured: Fig. 5's point at 1,000-1,400 rpm with 5 slices stagnated at a residual 0.05-0.4)
                if float(np.dot(step, grad[free])) >= 0.0:
                    mu *= 4.0
            else:
                mu *= 4.0
        if not accepted:
            stop = "stagnation"
            break
    if stop != "tolerance met":
        raise ConvergenceError(f"tapered quasi-static solve: {stop} after {it} iterations, relative force "
                               f"residual {res:.3g} (tolerance {tol:g})")
    return _result(model, q, cs, f_cone, fc, mg, kin, stop, it, res, m_cone)


def _result(model, q, cs, f_cone, fc, mg, kin, stop, it, res, m_cone):
    g, Z = model.g, model.Z
    d, rl = model.unpack(q)
    cup_sl, cone_sl = np.zeros((Z, len(model.u))), np.zeros((Z, len(model.u)))
    out = {k: np.zeros(Z) for k in ("cup", "cone", "flange", "cup_a", "cone_a", "flange_a",
                                    "cup_d", "cone_d", "flange_d")}
    normals = (g.cup_normal, g.cone_normal, g.flange_normal)
    cone_force = np.zeros(3)
    cone_moment = np.zeros(3)
    for j, rows in enumerate(cs):
        if model.tilt:
            phi = model.in_plane_tilt(q, j)
            rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
            normals = (g.cup_normal, rot @ g.cone_normal, rot @ g.flange_normal)
            cone_moment += _cone_moment(model, q, j, rows, normals, d)
        for kind, (name, (dl, _, _, _)) in enumerate(zip(("cup", "cone", "flange"), rows)):
            f = model._laws(dl, kind)[1]
            if kind == 0:
                cup_sl[j] = f
            elif kind == 1:
                cone_sl[j] = f
            total = float(f.sum())
            out[name][j] = total
            nrm = normals[kind]
            out[name + "_a"][j] = math.atan2(abs(nrm[0]), abs(nrm[1]))
            out[name + "_d"][j] = float(dl.max())
            if kind > 0:   # force of the roller on the cone: -total n (n points into the roller)
                fx, fr = -total * nrm[0], -total * nrm[1]
                cone_force += np.array([fx, fr * math.cos(model.psi[j]), fr * math.sin(model.psi[j])])
    # a posteriori: the cone's balance (roller forces + external load)
    balance = float(np.abs((cone_force + f_cone)[1:]).max())
    if f_cone[0] != 0.0:
        balance = max(balance, abs(cone_force[0] + f_cone[0]))
    scale = max(float(np.abs(f_cone).max()), out["cup"].max(), 1.0)
    if balance > 1e-6 * scale:
        log.warning("tapered quasi-static: cone force balance error %.3g N", balance)
    applied = np.array([0.0, m_cone[0], m_cone[1]])
    moment_error = 0.0
    if model.tilt:
        moment_error = float(np.abs(cone_moment + applied)[1:].max())
        if moment_error > 1e-6 * max(scale * model.tilt_scale, float(np.abs(applied).max())):
            log.warning("tapered quasi-static: cone moment balance error %.3g N m", moment_error)
    return QuasiStaticResult(
        azimuths=model.psi.copy(), cup_loads=out["cup"], cone_loads=out["cone"], flange_loads=out["flange"],
        cup_angles=out["cup_a"], cone_angles=out["cone_a"], flange_angles=out["flange_a"],
        cup_approaches=out["cup_d"], cone_approaches=out["cone_d"], flange_approaches=out["flange_d"],
        cup_slice_loads=cup_sl, cone_slice_loads=cone_sl, roller_displacements=rl[:, :2].copy(),
        roller_tilts=rl[:, 2] / model.scale, cone_displacement=d.copy(),
        axial_load=float(cone_force[0]) if f_cone[0] == 0.0 else float(-f_cone[0]),
        radial_load=float(f_cone[1]), centrifugal_force=fc, gyroscopic_moment=mg, kinematics=kin,
        stop_reason=stop, iterations=it, residual=res, force_balance_error=balance,
        cone_tilt=q[3:5] / model.tilt_scale if model.tilt else np.zeros(2), cone_moment=cone_moment,
        applied_moment=applied, moment_balance_error=moment_error)


def _cone_moment(model, q, j, rows, normals, d):
    """The moment (x, y, z) [N m] about the cone's reference point of roller j's forces on the cone, from
    the contact points (a posteriori, independent of the residual): each cone slice's load -q n' at its
    rim point S - rho (n' - c e)/|n' - c e| and the rib's at S_f - r_s n_f', in the roller's plane
    M_t = (x - d_x) f_r - (r - d_r) f_x about the tangential axis e_t = (0, -sin psi, cos psi)."""
    g = model.g
    _, rl = model.unpack(q)
    a, r, th = rl[j]
    beta = g.roller_axis_angle + th / model.scale
    ex, er = math.cos(beta), math.sin(beta)
    cx, cr = a, g.pitch_radius + r
    c_psi, s_psi = math.cos(model.psi[j]), math.sin(model.psi[j])
    dr = d[1] * c_psi + d[2] * s_psi
    mt = 0.0
    n = normals[1]
    for k, (u, rho) in enumerate(zip(model.u, model.rho)):
        f = float(model._laws(rows[1][0][k:k + 1], 1)[1][0])
        if f <= 0.0:
            continue
        c = n[0] * ex + n[1] * er
        m = np.array([n[0] - c * ex, n[1] - c * er])
        px, pr = np.array([cx + u * ex, cr + u * er]) - rho * m / np.linalg.norm(m)
        mt += (px - d[0]) * (-f * n[1]) - (pr - dr) * (-f * n[0])
    qf = float(model._laws(rows[2][0], 2)[1][0])
    if qf > 0.0:
        nf, us = normals[2], g.sphere_center_u
        px, pr = cx + us * ex - g.end_sphere_radius * nf[0], cr + us * er - g.end_sphere_radius * nf[1]
        mt += (px - d[0]) * (-qf * nf[1]) - (pr - dr) * (-qf * nf[0])
    return mt * np.array([0.0, -s_psi, c_psi])
