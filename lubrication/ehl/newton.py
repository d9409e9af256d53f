"""Newton solvers of the EHL complementarity problem: active set and Fischer-Burmeister, with line search.

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import logging
import warnings

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ConvergenceError
from .budget import _BUDGET, _spend
from .contact import EHLContact
from .problem import _Problem
from .solution import EHLSolution
from ..laws.film import dowson_toyoda_central, nijenbanning_central
from ..laws.lubricant import Barus

log = logging.getLogger(__name__)

def _hertz_guess(P: _Problem):
    loc = P.doflocs
    r2 = (loc[0] / P.bx) ** 2
    if not P.c.is_line:
        r2 = r2 + (loc[1] / P.by) ** 2
    return P.ph * np.sqrt(np.clip(1 - r2, 0, None))


def _film_guess(c: EHLContact) -> float:
    """Central film thickness start value [m].

    Line contacts: Dowson-Toyoda, floored by an order-of-magnitude rigid
    estimate 8 U/W.  Point contacts: Nijenbanning-Venner-Moes (all four
    regimes, circular), times Hamrock-Dowson's ellipticity factor
    (1 - 0.61 exp(-0.73 k)) / (1 - 0.61 exp(-0.73)) for k = (R_y/R_x)^(2/pi).
    (The former point-contact start, Hamrock-Dowson floored by 8 U/W, was
    3 to 17 times too thick for M = 20 ... 200, L = 10, and its Newton
    iteration did not recover: measured failures at M = 40, 50, 100 on 33 x 33.)
    """
    U, G, W = c.U, max(c.G, 1e-3), c.W
    if U == 0.0:
        return _squeeze_film_guess(c)
    if c.lubricant.herschel_bulkley is not None:
        return hb_apparent_start(c)[1]
    if c.is_line:
        H = dowson_toyoda_central(U, G, W)
        return max(H, 8 * U / W) * c.radius_x
    k = (c.radius_y / c.radius_x) ** (2 / np.pi)
    shape = (1 - 0.61 * np.exp(-0.73 * k)) / (1 - 0.61 * np.exp(-0.73))
    return float(nijenbanning_central(c.moes_M, max(c.moes_L, 1e-6)) * np.sqrt(2 * U) * shape) * c.radius_x


def _squeeze_film_guess(c: EHLContact) -> float:
    """Central film start of a pure squeeze contact (u_m = 0, approach speed v = -dh00/dt > 0) [m]: the
    thicker of the rigid isoviscous film that carries the load (sphere-plane squeeze, F = 6 pi eta0 R_x R_y
    v/h; line, per length: F = 3 sqrt(2) pi eta0 v (R/h)^1.5) and the film at
    which the rigid film's central pressure reaches 1/alpha (3 alpha eta0 R v/h^2 = 1, Grubin's reasoning
    for the inlet of an EHL film)."""
    visc = c.lubricant.viscosity
    eta0, alpha = visc.eta0, visc.pressure_viscosity
    v = max(-c.squeeze_velocity, 0.0)
    W = c.hertz_load()
    if c.is_line:
        R = c.radius_x
        h_iso = (3 * np.pi * np.sqrt(2.0) * eta0 * R**1.5 * v / W) ** (2 / 3)
    else:
        R = np.sqrt(c.radius_x * c.radius_y)
        h_iso = 6 * np.pi * eta0 * c.radius_x * c.radius_y * v / W
    h_pole = np.sqrt(3 * alpha * eta0 * R * v)
    floor = 1e-3 * hertz_film_scale(c)
    return float(max(h_iso, h_pole, floor))


def hertz_film_scale(c: EHLContact) -> float:
    """b^2/R_x [m] of the contact's Hertz zone (the EHL film scale)."""
    from ..laws import contact as hertz

    W = c.hertz_load()
    if c.is_line:
        b = hertz.line_contact(W, c.radius_x, c.e_star).b
    else:
        hp = hertz.point_contact(W, c.radius_x, c.radius_y, c.e_star)
        b = hp.b if c.radius_y >= c.radius_x else hp.a
    return b * b / c.radius_x


def hb_apparent_start(c: EHLContact):
    """``(eta_app, h_c)`` of a Herschel-Bulkley contact: the Newtonian (Barus, the grease's alpha) film
    guess :func:`_film_guess` with the apparent viscosity eta_app = tau_y/D + phi0 D^(n-1) at its own
    rolling shear rate D = u_m/h_c, i.e. the root of g(h) = ln(h_guess(eta_app(h))) - ln(h) (the fixed
    point of lubedyn.lubrication.laws.grease.apparent_film).

    The root taken is the thinnest: g is scanned upwards in ln h from 1e-6 of the Hertz film scale b^2/R_x
    (where g > 0 for every n in (0, 2]: the guess grows slower than h) over 12 decades, 8 points a decade,
    and the first sign change is bisected (brentq, xtol 1e-13 in ln h).  Why not the damped fixed-point
    iteration from eta = phi0 (the earlier method): on a point contact the guess's rigid-isoviscous branch
    (h ~ eta^2 at Moes' M << 1, which phi0 = 8-49 Pa s^n puts it in) and the yield stress's eta ~ h make a
    second, unstable fixed point at huge films, and the iteration ran off towards it (measured on paper A's
    rib, 500 N, 11.3 m/s: calcium's film 0.95 m, 1.9 m, ... 2e5 m after 8 steps, then a ZeroDivisionError).
    On paper A's cone line contacts both methods find the same root (measured over 1-300 kN/m, 7-28 m/s,
    the three greases at 30 C: eta_app equal to 1e-8, lithium at 1 kN/m, 7 m/s to 4e-5).  No sign change: :class:`ConvergenceError`."""
    import dataclasses

    from scipy.optimize import brentq

    hb = c.lubricant.herschel_bulkley
    phi0, alpha = c.lubricant.viscosity.eta0, c.lubricant.viscosity.pressure_viscosity

    def eta_at(h):
        D = c.mean_speed / h
        return hb.yield_stress / D + phi0 * D ** (hb.exponent - 1.0)

    def guess(h):
        return _film_guess(dataclasses.replace(c, lubricant=dataclasses.replace(
            c.lubricant, viscosity=Barus(eta_at(h), alpha), herschel_bulkley=None)))

    def g(lnh):
        return float(np.log(guess(np.exp(lnh)))) - lnh

    if c.is_line:
        from ..laws.contact import line_contact
        b = line_contact(c.hertz_load(), c.radius_x, c.e_star).b
    else:
        from ..laws.contact import point_contact
        hp = point_contact(c.hertz_load(), c.radius_x, c.radius_y, c.e_star)
        b = hp.b if c.radius_y >= c.radius_x else hp.a
    lo = float(np.log(1e-6 * b * b / c.radius_x))
    grid = lo + np.arange(12 * 8 + 1) * np.log(10.0) / 8
    prev = g(grid[0])
    for a, z in zip(grid[:-1], grid[1:]):
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            try:
                cur = g(z)
            except (ZeroDivisionError, OverflowError, FloatingPointError):
                cur = np.nan
        if not np.isfinite(cur):
            break
        if prev > 0.0 >= cur:
            lnh = brentq(g, a, z, xtol=1e-13, rtol=4 * np.finfo(float).eps)
            h = float(np.exp(lnh))
            return float(eta_at(h)), guess(h)
        prev = cur
    raise ConvergenceError(f"EHL Herschel-Bulkley start: no apparent-viscosity film h = h_guess(eta_app(h)) between "
                           f"{np.exp(grid[0]):.3g} m and {np.exp(z):.3g} m (lubricant {hb!r}, phi0 = {phi0:g} Pa s^n, "
                           f"u_m = {c.mean_speed:g} m/s, load {c.hertz_load():g})")


def _stopped(reason: str, message: str) -> ConvergenceError:
    """A :class:`ConvergenceError` carrying its stop reason (``.stop``: reason and detail)."""
    err = ConvergenceError(message)
    err.stop = dict(reason=reason, detail=message)
    return err


def _lu_factor(J, P: _Problem):
    """Dense LU of a Newton matrix; an exactly singular one (an iterate that has left the
    solution's basin, e.g. every node cavitated) raises ConvergenceError, which the start and
    fallback chain of :func:`solve_ehl` handles, instead of scipy's LinAlgWarning and a
    non-finite step."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", sla.LinAlgWarning)
        try:
            return sla.lu_factor(J, check_finite=False)
        except sla.LinAlgWarning as exc:
            raise _stopped("singular Jacobian", f"EHL Newton: singular Jacobian at M = {P.c.moes_M:.4g}, "
                                   f"L = {P.c.moes_L:.4g} ({_nodes(P)}; {exc}){_heavy(P, '; ')}") from None


class _Linear:
    """Dense LU or ILU-preconditioned GMRES for J = A + D K restricted to ``idx``."""

    def __init__(self, P: _Problem, A, D, idx):
        self.P, self.idx = P, idx
        n = idx.size
        self.dense = n <= (P.o.dense_max_line if P.c.is_line else P.o.dense_max)
        if self.dense:
            K = P.K_dense()
            J = A[idx][:, idx].toarray() + (D[idx] @ K[:, idx])
            self.lu = _lu_factor(J, P)
        else:
            self.A, self.D = A, D
            Pm = (A + D @ P.K_local())[idx][:, idx].tocsc()
            try:
                self.ilu = spla.spilu(Pm, drop_tol=1e-6, fill_factor=20)
            except RuntimeError as exc:  # SuperLU: "Factor is exactly singular", as the dense branch above
                raise _stopped("singular Jacobian", f"EHL Newton: singular preconditioner (ILU) at M = "
                               f"{P.c.moes_M:.4g}, L = {P.c.moes_L:.4g} ({_nodes(P)}; {exc})"
                               f"{_heavy(P, '; ')}") from None
            full = np.zeros(P.N)

            def mv(v):
                full[:] = 0.0
                full[idx] = v
                return (A @ full + D @ P.deflect(full))[idx]

            self.op = spla.LinearOperator((n, n), matvec=mv, dtype=float)
            self.M = spla.LinearOperator((n, n), matvec=self.ilu.solve, dtype=float)
            self.gmres_iters = 0

    def solve(self, rhs):
        if self.dense:
            return sla.lu_solve(self.lu, rhs, check_finite=False)
        count = [0]

        def cb(_):
            count[0] += 1

        x, info = spla.gmres(self.op, rhs, M=self.M, rtol=self.P.o.gmres_rtol, atol=0.0, restart=80, maxiter=20,
                             callback=cb, callback_type="pr_norm")
        self.gmres_iters += count[0]
        if info != 0:
            log.warning("EHL GMRES did not reach rtol %.1e (%d iterations)", self.P.o.gmres_rtol, count[0])
        return x


def _grid_values(P: _Problem, values):
    out = np.zeros(np.prod(P.shape))
    out[P.flat] = values
    return out.reshape(P.shape)


def _prolong(coarse: EHLSolution, P: _Problem) -> np.ndarray:
    """Coarse-grid pressure interpolated (multilinear) onto the dofs of ``P``."""
    from scipy.interpolate import RegularGridInterpolator

    Pc = coarse.problem
    axes = (Pc.xs,) if Pc.c.is_line else (Pc.xs, Pc.ys)
    f = RegularGridInterpolator(axes, _grid_values(Pc, coarse.pressure), bounds_error=False, fill_value=0.0)
    return f(P.doflocs.T)


def _pseudo_transient(P: _Problem, p, hn, R, A, D, state):
    """Pseudo-transient continuation of the Newton step (``EHLOptions.pseudo_transient``): the Jacobian gains
    the lumped transient term of d(rho h)/dt with a pseudo time step dtau, dR_i/dp_i += w_i rho'_i h_i/dtau
    and dR_i/dh_i += w_i rho_i/dtau (the residual, the converged state and the convergence test are
    unchanged: backward Euler in pseudo time linearised at the current state, where the transient term
    vanishes).  dtau grows as the residual falls (switched evolution relaxation, Mulder & van Leer 1985):
    dtau = dtau0 |R_0|/|R|, dtau0 = ``pseudo_transient`` transit times of the domain (its length over u_m);
    off once dtau exceeds 1e10 transit times (plain Newton, quadratic convergence kept).  Why: where the viscosity is
    eta0 exp(alpha p) with alpha p = 30-60 the Poiseuille flow vanishes, the film is held by its Couette
    balance d(rho h)/dx = 0 alone, whose Jacobian has a near-null mode (a pressure whose deflection is
    constant there); finer grids resolve it and the plain Newton step jumps by p_Hertz along it.  The
    transient term penalises that mode (measured: paper A's cone at 7 m/s, Dowson-Higginson film, graded
    257 nodes: 53.6-87.3 kN/m failed with every fallback and converge with dtau0 = 0.1 in 0.3-9 s as map points,
    in 25-47 iterations from the solver's own start; tests/test_ehl_graded.py).  The pseudo step is in transit
    times of the domain, not of the Hertz width: at light loads the film spans 10-160 b and a step of b/u_m
    stalled the iteration (0.7 kN/m failed; it converges in 0.3 s with the domain's transit time)."""
    r = float(np.linalg.norm(R[P.free0]))
    if "r0" not in state:
        state["r0"] = max(r, 1e-300)
    transit = (P.xs[-1] - P.xs[0]) / abs(P.c.mean_speed)
    dtau = P.o.pseudo_transient * transit * state["r0"] / max(r, 1e-300)
    if dtau >= 1e10 * transit:
        return A, D
    lub = P.c.lubricant
    pp = np.maximum(p, 0.0)
    w = P.weights / dtau
    A = (A + sp.diags(w * lub.density.derivative(pp) * hn)).tocsr()
    D = (D + sp.diags(w * lub.density(pp))).tocsr()
    return A, D


def _active_set_newton(P: _Problem, p, h00, W):
    """Bordered Newton with a projected active set (the module docstring's
    scheme; line contacts by default).  Returns ``(p, h00, history, gmres)``."""
    options, contact = P.o, P.c
    balance = W is not None
    cav = np.zeros(P.N, dtype=bool)
    history = []
    gm = 0
    rejected = None
    ptc = {} if options.pseudo_transient > 0 else None
    for it in range(1, options.max_iter + 1):
        _spend(P)
        R, hn, A, D, aux = P.assemble(p, h00)
        if ptc is not None:
            A, D = _pseudo_transient(P, p, hn, R, A, D, ptc)
        added_any = False
        for _inner in range(options.active_set_passes):
            # Newton step with the cavitated set fixed at p = 0; free nodes the
            # step would drive negative join the set and the step is recomputed
            free = P.free0 & ~cav
            idx = np.flatnonzero(free)
            lin = _Linear(P, A, D, idx)
            dpc = np.zeros(P.N)
            dpc[cav] = -p[cav]
            rhs = -R[idx] - ((A @ dpc + D @ P.deflect(dpc))[idx] if cav.any() else 0.0)
            z1 = lin.solve(rhs)
            dp = dpc.copy()
            dh = 0.0
            if balance:
                z2 = lin.solve(-(D @ np.ones(P.N))[idx])
                wv = P.weights[idx]
                load_err = P.weights @ (p + dp) - W
                denom = wv @ z2
                if not (np.isfinite(denom) and denom != 0.0):  # no free node responds to the approach
                    dh = 0.0
                    dp[idx] = z1
                else:
                    dh = -(wv @ z1 + load_err) / denom
                    dp[idx] = z1 + dh * z2
            else:
                dp[idx] = z1
            gm += getattr(lin, "gmres_iters", 0)
            neg = free & (p + dp < -1e-9 * P.ph)
            if not neg.any():
                break
            cav = cav | neg
            added_any = True
        # convergence on the full (undamped) Newton step, before any line search: at the round-off
        # floor the residual norm is noise, so a backtracking test there can halve omega at random
        # and an omega == 1 requirement never be met (tests/test_roundoff.py)
        # pressure scale: p_Hertz, or the largest pressure where that is smaller (nearly rigid,
        # hydrodynamic contacts), as in the Fischer-Burmeister scheme
        pmax = float(np.max(p))
        p_ref = P.ph if pmax <= 0 else min(P.ph, pmax)
        full = (np.max(np.abs(dp)) / p_ref, abs(dh) / P.hscale)
        if full[0] <= options.rtol and full[1] <= options.rtol:
            p_try, h_try = np.maximum(p + dp, 0.0), h00 + dh
            load_rel = abs(P.weights @ p_try - W) / W if balance else 0.0
            R_try = P.assemble(p_try, h_try, jac=False)[0]
            mult = _largest_negative_multiplier(P, A, D, R_try, cav, p_ref)
            load_tol = max(options.rtol, 1e-10) * 10
            if load_rel <= load_tol and mult <= options.rtol:
                p, h00 = p_try, h_try
                history.append((full[0], full[1], load_rel, int(cav.sum())))
                P.stop = dict(reason="tolerance met", detail=(
                    f"full Newton step max|dp|/p_ref {full[0]:.1e}, |dh00|/(b^2/R_x) {full[1]:.1e} <= rtol "
                    f"{options.rtol:.0e}, load error {load_rel:.1e} <= {load_tol:.0e}, cavitated multipliers >= "
                    f"-{options.rtol:.0e} p_ref ({int(cav.sum())} cavitated nodes) after {it} iterations"))
                log.debug("EHL %d: full step |dp|/ph = %.2e, dh00/hs = %.2e, load err %.2e: converged",
                          it, full[0], full[1], load_rel)
                break
            # the step met the tolerance, the state did not: remember which test refused it
            rejected = dict(iteration=it, load=(load_rel, load_tol), multiplier=(mult, options.rtol))
        # damping: cap the pressure change at max_step p_Hertz, then backtrack
        # on the free-node residual norm (at most 4 halvings); p + omega dp >= 0
        # on free nodes up to round-off because p >= 0 and p + dp >= 0 there
        omega = 1.0 / max(np.max(np.abs(dp)) / (options.max_step * P.ph), 1.0)
        # (a trial far outside the basin can overflow the norm: inf is "no decrease", no warning)
        with np.errstate(over="ignore"):
            r0 = np.linalg.norm(R[idx])
        for _ in range(4):
            trial = np.maximum(p + omega * dp, 0.0)
            Rt = P.assemble(trial, h00 + omega * dh, jac=False)[0]
            with np.errstate(over="ignore"):
                decreased = np.linalg.norm(Rt[idx]) <= r0
            if decreased or r0 == 0.0:
                break
            omega *= 0.5
        p_new = np.maximum(p + omega * dp, 0.0)
        h00 = h00 + omega * dh
        cav_new = cav.copy()
        if cav.any() and not added_any:
            # release cavitated nodes whose multiplier is negative, but only in
            # iterations that cavitated no new node (otherwise the set flips)
            Rn = Rt  # residual at (p_new, h00): the accepted line-search trial
            release = cav & (Rn < 0)
            cav_new &= ~release
        dmax = omega * np.max(np.abs(dp)) / P.ph
        p, cav = p_new, cav_new
        load_rel = abs(P.weights @ p - W) / W if balance else 0.0
        history.append((dmax, omega * abs(dh) / P.hscale, load_rel, int(cav.sum())))
        log.debug("EHL %d: |dp|/ph = %.2e, dh00/hs = %.2e, load err %.2e, omega %.2f, cav %d",
                  it, dmax, history[-1][1], load_rel, omega, cav.sum())
        if not np.all(np.isfinite(p)):
            raise _stopped("non-finite pressure",
                           f"EHL Newton iteration {it}: non-finite pressure (M = {contact.moes_M:.4g})")
    else:
        err = ConvergenceError(
            f"EHL solve did not converge in {options.max_iter} Newton iterations at M = {contact.moes_M:.4g}, "
            f"L = {contact.moes_L:.4g} ({_nodes(P)}): last |dp|/p_Hertz = {history[-1][0]:.2e}, load error "
            f"{history[-1][2]:.2e}; {_iteration_limit_hint(P, history, rejected, hn)} ([solver] max_iter, "
            "EHLOptions.max_iter)")
        err.stop = dict(reason="iteration limit", detail=str(err))
        raise err
    return p, h00, history, gm


# Moes M up to which a line contact's outlet constriction is resolved by nx nodes, from the sweep of
# tests/test_ehl_limits.py's docstring (benchmarks/method_limits.py, sweep 1, repeats it: Moes line
# M = 10 ... 1000, L = 5 ... 20, active set, against 1025 nodes): 129 nodes are within 3 % up to M = 100, 257 up to M = 300 (+19 % at
# M = 500, +86 % at M = 1000), 513 up to M = 1000; M_resolved = (nx - 1)^2/220 (74, 298, 1191).
def _resolved_line_M(nx):
    return (nx - 1) ** 2 / 220.0


def _iteration_limit_hint(P: _Problem, history, rejected, hn):
    """What stopped an active-set iteration at its limit, computed from the state: the test that
    refused a converged step (with its figures), active-set cycling (the cavitated counts), a film at
    the floor, and a finer grid only where the load parameter asks for one."""
    o, c = P.o, P.c
    parts = []
    if rejected is not None:
        (le, lt), (mu, mt) = rejected["load"], rejected["multiplier"]
        failed = []
        if le > lt:
            failed.append(f"the load error {le:.1e} > {lt:.0e}")
        if mu > mt:
            failed.append(f"a cavitated node's multiplier -{mu:.1e} p_ref below -{mt:.0e}")
        parts.append(f"the Newton step met rtol {o.rtol:.0e} (last at iteration {rejected['iteration']}) but "
                     + " and ".join(failed) + " refused the state")
    else:
        tail = [h[0] for h in history[-5:]]
        parts.append(f"the full step never met rtol {o.rtol:.0e} (last five max|dp|/p_Hertz "
                     + ", ".join(f"{v:.1e}" for v in tail) + ")")
    counts = [h[3] for h in history[-10:]]
    if len(counts) >= 6 and len(set(counts[-6:])) > 1 and max(counts[-6:]) - min(counts[-6:]) > 0 \
            and len(set(counts[-6:])) <= 3:
        parts.append(f"the cavitated set keeps changing ({min(counts[-6:])} ... {max(counts[-6:])} nodes over the "
                     "last six steps)")
    if np.min(hn) <= o.h_floor * P.hscale * 1.0001:
        parts.append("the film reached the floor")
    heavy = _heavy(P)
    if heavy:
        parts.append(heavy)
    return "; ".join(parts)


# Moes M up to which the Newton methods converge on a circular contact of nx x nx nodes (L = 10, the
# package docstring; benchmarks/method_limits.py, sweeps 1-2: M = 200 on 33 x 33, 500 on 65 x 65,
# 1000 on 129 x 129; M = 500 on 33 x 33, 1000 on 65 x 65 and 2000 on 129 x 129 fail).  The FAS multigrid converges at M = 1000 from 129 x 129 and M = 2000
# from 257 x 257, and on 513 x 513 is within 10 % of the closed form at M = 2000 (-4 %; 257 x 257:
# -8 % at M = 1000, -18 % at M = 2000; tests/test_ehl_limits.py)
def _converged_point_M(nx):
    return 8.0 * (nx - 1)


# elongated point contacts (R_y/R_x > 4): the largest M known to converge (paper B's ball / inner race,
# cases/ehl_ball_inner_race.toml, k = 11, M = 1001, L = 25: 33 x 17, 65 x 33, 129 x 33 converge)
ELONGATED_POINT_M = 1001.0


def _requested_nx():
    """grid.nx of the solve_ehl call being served (None outside one)."""
    budget = _BUDGET.get()
    return None if budget is None else budget.get("nx")


def _nodes(P: _Problem) -> str:
    """'N nodes' of the grid level P, naming the grid asked for when P is a coarser level of the nested
    start (an error there is not about the user's grid)."""
    text = f"{P.N} nodes" if P.c.is_line else f"{P.shape[0]} x {P.shape[1]} nodes"
    req = _requested_nx()
    if req is not None and P.shape[0] < req:
        text += f", a coarser level of the nested start for the grid.nx = {req} asked for"
    return text


def _heavy(P: _Problem, sep: str = "") -> str:
    """Where Moes' load parameter M is beyond what the grid level P resolves (lines) or what the Newton
    methods converge on (points), the sentence that says so and what to change (case-file keys, the
    EHLOptions field from Python); '' otherwise."""
    c = P.c
    if c.load is None:
        return ""
    nx = P.shape[0]
    M = c.moes_M
    req = _requested_nx()
    nested = req is not None and nx < req
    if c.is_line:
        if M <= _resolved_line_M(nx):
            return ""
        finer = nx
        while M > _resolved_line_M(finer):
            finer = 2 * (finer - 1) + 1
        text = (f"M = {M:.4g} is a very heavily loaded (or slow) contact, beyond what {nx} nodes resolve (about "
                f"M <= {_resolved_line_M(nx):.0f})")
        if nested:
            return sep + text + f" (a level the nested start passes through; grid.nx >= {finer} resolves M)"
        return sep + text + f": use grid.nx >= {finer} ([grid] nx, EHLGrid.nx)"
    if max(c.radius_y / c.radius_x, c.radius_x / c.radius_y) > 4.0:
        # elongated contacts: measured to converge up to paper B's ball (k = 11, M = 1001: 33 x 17 ... 129 x 33);
        # the multigrid's line relaxation assumes square cells (multigrid.py), so it is no way out
        if M <= ELONGATED_POINT_M:
            return ""
        return (sep + f"M = {M:.4g} is a very heavily loaded (or slow) contact, beyond what was measured to converge "
                f"for elongated contacts (M = {ELONGATED_POINT_M:.0f}; at M = 1e6, 1 rpm, paper B's ball fails on "
                "65 x 33 and 129 x 65 alike, and the multigrid does not take elongated cells): lower the load or raise "
                "the speed ([operating] or [bearing])")
    if M <= _converged_point_M(nx):
        return ""
    text = (f"M = {M:.4g} is a very heavily loaded (or slow) contact: the Newton methods converge up to about "
            f"M = {_converged_point_M(nx):.0f} on {nx} x {nx} nodes (measured, circular contacts)")
    if nested:
        return sep + text + " (a level the nested start passes through)"
    if M > 3000.0:
        return (sep + text + "; no grid was measured to converge beyond M = 3000 (the multigrid on 513 x 513): lower "
                "the load or raise the speed")
    mg = 513 if M >= 1000 else 257
    return (sep + text + f"; use [solver] method = 'multigrid' with [grid] nx >= {mg} (EHLOptions.method; "
            "measured: M = 2000 converges there, 4 % off the closed form on 513 x 513)")


class _FBLinear:
    """Linear solver of the Fischer-Burmeister Newton step on the free (interior) dofs ``idx``::

        J = diag(a') + diag(b' s) (A + D K)     (a' = dphi/da / p_ref, given scaled)

    dense LU up to ``dense_max`` unknowns; otherwise restarted GMRES with
    FFT products (K applied by :meth:`_Problem.deflect`), right-preconditioned
    by the sparse LU (``splu``) of the same matrix with K replaced by its
    local truncation ``K_local`` (offsets up to ``EHLOptions.stencil``),
    factorised once per Newton step.
    """

    def __init__(self, P: _Problem, A, D, da, dbs, idx, reuse=None, rtol=None):
        self.P, self.idx = P, idx
        self.rtol = P.o.gmres_rtol if rtol is None else rtol
        self.refactored = False
        n = idx.size
        self.dense = n <= (P.o.dense_max_line if P.c.is_line else P.o.dense_max)
        self.gmres_iters = 0
        if self.dense:
            K = P.K_dense()
            J = A[idx][:, idx].toarray() + (D[idx] @ K[:, idx])
            J *= dbs[:, None]
            J[np.arange(n), np.arange(n)] += da
            self.lu = _lu_factor(J, P)
            return
        self._parts = (A, D, da, dbs)
        if reuse is not None:
            self.lu = reuse
        else:
            self._factorise()
        full = np.zeros(P.N)

        def mv(v):
            full[:] = 0.0
            full[idx] = v
            return dbs * (A @ full + D @ P.deflect(full))[idx] + da * v

        self.op = spla.LinearOperator((n, n), matvec=mv, dtype=float)
        self.M = spla.LinearOperator((n, n), matvec=self.lu.solve, dtype=float)

    def solve(self, rhs):
        if self.dense:
            return sla.lu_solve(self.lu, rhs, check_finite=False)
        count = [0]

        def cb(_):
            count[0] += 1

        x, info = spla.gmres(self.op, rhs, M=self.M, rtol=self.rtol, atol=0.0, restart=60,
                             maxiter=10, callback=cb, callback_type="pr_norm")
        self.gmres_iters += count[0]
        self.last_iters = count[0]
        if info != 0:
            log.debug("EHL GMRES did not reach rtol %.1e (%d iterations)", self.rtol, count[0])
        return x

    def _factorise(self):
        A, D, da, dbs = self._parts
        Jl = (A + D @ self.P.K_local())[self.idx][:, self.idx]
        Pm = (sp.diags(dbs) @ Jl + sp.diags(da)).tocsc()
        # minimum degree on A^T + A: 3-4 times less fill and time than COLAMD here
        try:
            self.lu = spla.splu(Pm, permc_spec="MMD_AT_PLUS_A")
        except RuntimeError as exc:  # SuperLU: "Factor is exactly singular" (measured: a homotopy step of paper
            # A's rib with lithium grease, 65 x 57 nodes), a ConvergenceError as the ILU and dense branches
            raise _stopped("singular Jacobian", f"EHL Newton: singular preconditioner (sparse LU) at M = "
                           f"{self.P.c.moes_M:.4g}, L = {self.P.c.moes_L:.4g} ({_nodes(self.P)}; {exc})"
                           f"{_heavy(self.P, '; ')}") from None
        self.refactored = True

    def solve_bordered(self, rhs, col, row, rhs_row):
        """Solve [[J, col], [row^T, 0]] [x; t] = [rhs; rhs_row] (the load-balance
        border).  Dense: two LU solves and the Schur complement.  Iterative:
        one GMRES on the bordered system, right-preconditioned by the block
        factorisation with J replaced by its sparse LU (y = LU^-1 col once,
        then x = LU^-1 r - t y, t = (row . LU^-1 r - s)/(row . y)); half the
        GMRES work of solving for the two right-hand sides separately."""
        if self.dense:
            z1, z2 = self.solve(rhs), self.solve(col)
            t = (row @ z1 - rhs_row) / (row @ z2)
            return z1 - t * z2, t
        n = self.idx.size
        pre = {}

        def setup():
            pre["y"] = self.lu.solve(col)
            pre["ry"] = row @ pre["y"]

        def prec(v):
            z = self.lu.solve(v[:n])
            t = (row @ z - v[n]) / pre["ry"]
            out = np.empty(n + 1)
            out[:n] = z - t * pre["y"]
            out[n] = t
            return out

        def mv(v):
            out = np.empty(n + 1)
            out[:n] = self.op.matvec(v[:n]) + col * v[n]
            out[n] = row @ v[:n]
            return out

        op = spla.LinearOperator((n + 1, n + 1), matvec=mv, dtype=float)
        M = spla.LinearOperator((n + 1, n + 1), matvec=prec, dtype=float)
        count = [0]

        def cb(_):
            count[0] += 1

        b = np.concatenate([rhs, [rhs_row]])
        setup()
        x0 = None
        if not self.refactored:
            # a factorisation kept from an earlier step: if GMRES needs more
            # than precond_refresh iterations with it (the Jacobian has moved:
            # measured 299 iterations at 257 x 257), refactorise and go on
            x0, info = spla.gmres(op, b, M=M, rtol=self.rtol, atol=0.0, restart=self.P.o.precond_refresh,
                                  maxiter=1, callback=cb, callback_type="pr_norm")
            if info != 0:
                self._factorise()
                setup()
        if x0 is None or info != 0:
            x, info = spla.gmres(op, b, x0=x0, M=M, rtol=self.rtol, atol=0.0, restart=60, maxiter=10, callback=cb,
                                 callback_type="pr_norm")
        else:
            x = x0
        self.gmres_iters += count[0]
        self.last_iters = count[0]
        if info != 0:
            log.debug("EHL GMRES did not reach rtol %.1e (%d iterations)", self.rtol, count[0])
        return x[:n], x[n]


def _row_scale(P: _Problem, A, D, idx, p_ref=None):
    """s_i = 1/(p_ref max_j |J_ij|), J = A + D K_local: Reynolds residual rows in
    units of the pressure scale ``p_ref`` (default p_Hertz)."""
    Jl = (A + D @ P.K_local())[idx][:, idx]
    rowmax = np.asarray(abs(Jl).max(axis=1).todense()).ravel()
    rowmax = np.maximum(rowmax, 1e-12 * np.max(rowmax))
    return 1.0 / ((P.ph if p_ref is None else p_ref) * rowmax)


def _largest_negative_multiplier(P: _Problem, A, D, R, cav, p_ref):
    """Largest negative Reynolds multiplier of the cavitated nodes, in units of ``p_ref``:
    max_i (-s_i R_i) over cavitated i with R_i < 0 (0 if none), s_i = 1/(p_ref max_j |J_ij|) the
    row scale of :func:`_row_scale` taken over the whole row.  A cavitated node whose scaled
    multiplier is below -rtol would gain about that pressure if released; one within
    [-rtol, 0) is a degenerate node (p = R = 0 up to round-off) whose release changes
    nothing the tolerance can see, so it does not block convergence."""
    neg = np.flatnonzero(cav & (R < 0))
    if neg.size == 0:
        return 0.0
    rows = sp.csr_matrix(A)[neg] + sp.csr_matrix(D)[neg] @ P.K_local()  # only the rows asked for
    rowmax = np.asarray(abs(rows).max(axis=1).todense()).ravel()
    return float(np.max(-R[neg] / (p_ref * np.maximum(rowmax, 1e-300))))


def _fb(a, b):
    """Fischer-Burmeister function phi(a, b) = sqrt(a^2 + b^2) - a - b and its
    partial derivatives (phi = 0 <=> a >= 0, b >= 0, a b = 0).  At a = b = 0
    (where phi is not differentiable) the element (1/sqrt2 - 1, 1/sqrt2 - 1)
    of the generalised Jacobian is taken."""
    r = np.hypot(a, b)
    safe = np.where(r > 0, r, 1.0)
    da = np.where(r > 0, a / safe, 2**-0.5) - 1.0
    db = np.where(r > 0, b / safe, 2**-0.5) - 1.0
    return r - a - b, da, db


def _fb_newton(P: _Problem, p, h00, W, max_iter=None, rtol=None, max_damped=None):
    """Semismooth (Fischer-Burmeister) Newton on the coupled system, globalised by an Armijo line search.

    Unknowns: the interior pressures and, with a load, h00.  Equations::

        Phi_i = phi(p_i / p_H, s_i R_i(p, h00)) = 0        (every interior node)
        (int p dA - W) / W = 0                              (load balance)

    phi the Fischer-Burmeister function (:func:`_fb`): Phi_i = 0 is exactly the
    complementarity p_i >= 0, R_i >= 0, p_i R_i = 0, with no active set to
    guess.  s_i = 1/(p_H max_j |J_ij|) scales residual rows to pressures
    (J = A + D K_local, refreshed every step).  The step solves
    the bordered system as the active-set scheme does (two solves with one
    factorisation, :class:`_FBLinear`); it is capped so that no pressure
    moves by more than ``max_step`` p_H and then halved until the merit
    theta = |Phi|^2 + load error^2 decreases by the Armijo fraction 1e-4
    (at most ``line_search`` halvings; if none decreases, the best trial is
    taken and counted as a stall).

    Convergence test (as for the active-set scheme), on the full Newton step
    before the line search: max|dp| <= rtol p_ref, |dh00| <= rtol b^2/R_x and
    relative load error after the step <= 10 rtol; the step is then taken.  Returns ``(p, h00, history, gmres_iterations)``; p is
    clipped at 0 (it is >= -rtol p_H at convergence).
    """
    options, contact = P.o, P.c
    balance = W is not None
    idx = np.flatnonzero(P.free0)
    wv = P.weights[idx]
    history, gm = [], 0

    def merit(R, pp, hh, s):
        phi = _fb(pp[idx] / ps, s * R[idx])[0]
        le = (P.weights @ pp - W) / W if balance else 0.0
        return phi @ phi + le * le, phi, le

    stalls, nfact, keep, damped = 0, 0, None, 0
    max_iter = options.max_iter if max_iter is None else max_iter
    tol = options.rtol if rtol is None else rtol
    for it in range(1, max_iter + 1):
        _spend(P)
        R, hn, A, D, aux = P.assemble(p, h00)
        # pressure scale: p_Hertz, or the largest pressure where that is smaller
        # (hydrodynamic, nearly rigid contacts: p << p_Hertz of the nominal load)
        pmax = float(np.max(p))
        ps = P.ph if pmax <= 0 else min(P.ph, pmax)
        s = _row_scale(P, A, D, idx, ps)
        phi, da, db = _fb(p[idx] / ps, s * R[idx])
        le = (P.weights @ p - W) / W if balance else 0.0
        theta0 = phi @ phi + le * le
        # inexact Newton: GMRES to rtol min(1e-3, |Phi|) (floored at gmres_rtol);
        # the sparse LU preconditioner is kept from the previous step while
        # GMRES needs fewer than precond_refresh iterations per solve
        eta_k = max(options.gmres_rtol, min(options.gmres_forcing, np.sqrt(theta0)))
        lin = _FBLinear(P, A, D, da / ps, db * s, idx, reuse=keep, rtol=eta_k)
        dp = np.zeros(P.N)
        dh = 0.0
        if balance:
            # bordered step: J dp + c dh = -phi, w . dp / W = -le (h00 in units of b^2/R_x)
            col = (db * s) * (D @ np.ones(P.N))[idx] * P.hscale
            dp[idx], t = lin.solve_bordered(-phi, col, wv / W, -le)
            dh = t * P.hscale
        else:
            dp[idx] = lin.solve(-phi)
        gm += lin.gmres_iters
        if not lin.dense:
            nfact += lin.refactored
            # bordered solves refactorise by themselves when the kept LU has gone stale
            keep = lin.lu if (balance or lin.last_iters < options.precond_refresh) else None
        # convergence on the full (undamped) step, before the line search: at the round-off floor
        # the merit is noise and its Armijo test can halve omega at random, so an omega == 1
        # requirement is a coin toss between machines (tests/test_roundoff.py)
        full_dp = np.max(np.abs(dp)) / ps
        if full_dp <= tol and abs(dh) / P.hscale <= tol:
            p_try, h_try = p + dp, h00 + dh
            load_rel = abs(P.weights @ p_try - W) / W if balance else 0.0
            if load_rel <= max(tol, 1e-10) * 10 and np.all(np.isfinite(p_try)):
                p, h00 = p_try, h_try
                history.append((full_dp, abs(dh) / P.hscale, load_rel, int(np.sum(p[idx] < 1e-6 * ps))))
                P.stop = dict(reason="tolerance met", detail=(
                    f"full Newton step max|dp|/p_ref {full_dp:.1e}, |dh00|/(b^2/R_x) {abs(dh) / P.hscale:.1e} <= "
                    f"rtol {tol:.0e}, load error {load_rel:.1e} <= {max(tol, 1e-10) * 10:.0e} after {it} "
                    f"iterations ({stalls} line-search stalls)"))
                log.debug("EHL FB %d: full step |dp|/p_ref = %.2e, dh00/hs = %.2e, load err %.2e: converged",
                          it, full_dp, history[-1][1], load_rel)
                break
        omega = omega_cap = 1.0 / max(np.max(np.abs(dp)) / (options.max_step * ps), 1.0)
        if log.isEnabledFor(logging.DEBUG):
            i = int(np.argmax(np.abs(dp)))
            j = int(np.searchsorted(idx, i))
            loc = P.doflocs[:, i]
            log.debug("EHL FB %d: largest step %.2e p_ref at x/b = %.3f%s (p/p_ref %.3f, s R %.2e, h/hs %.3e)", it,
                      dp[i] / ps, loc[0] / P.bx, "" if contact.is_line else f", y/b = {loc[1] / P.by:.3f}",
                      p[i] / ps, (s * R[idx])[j] if j < idx.size and idx[j] == i else 0.0, hn[i] / P.hscale)
        best = None
        for _ in range(options.line_search + 1):
            trial_p, trial_h = p + omega * dp, h00 + omega * dh
            Rt = P.assemble(trial_p, trial_h, jac=False)[0]
            theta = merit(Rt, trial_p, trial_h, s)[0]
            if best is None or theta < best[0]:
                best = (theta, omega)
            if theta <= (1.0 - 2e-4 * omega) * theta0:
                break
            omega *= 0.5
        else:
            omega = best[1]
        # a stall: no Armijo decrease, or one only after 6 or more halvings
        if omega <= omega_cap / 64:
            stalls += 1
            if stalls >= options.max_stalls:
                err = ConvergenceError(
                    f"EHL Newton line search stalled {stalls} times at M = {contact.moes_M:.4g}, "
                    f"L = {contact.moes_L:.4g} ({_nodes(P)}; merit {theta0:.2e}; from Python the stall limit is "
                    f"EHLOptions.max_stalls); " + (_heavy(P) or "try [solver] method = 'active_set' "
                    "(EHLOptions.method; measured: paper B's inner contact at 178 N, 30 m/s, which stalls so, "
                    "converges with it)"))
                err.iterate = (np.maximum(p + omega * dp, 0.0), h00 + omega * dh)
                err.stop = dict(reason="line search stalled", detail=str(err))
                raise err
        damped += omega < 1.0
        if max_damped is not None and damped > max_damped:
            err = ConvergenceError(
                f"EHL Newton needed more than {max_damped} damped steps at M = {contact.moes_M:.4g}, "
                f"L = {contact.moes_L:.4g} ({_nodes(P)}; from Python the limit is EHLOptions.max_damped)"
                f"{_heavy(P, '; ')}")
            err.iterate = (np.maximum(p, 0.0), h00)
            err.stop = dict(reason="damped-step budget", detail=str(err))
            raise err
        p = p + omega * dp
        h00 = h00 + omega * dh
        pmax = float(np.max(p))
        dmax = omega * np.max(np.abs(dp)) / (P.ph if pmax <= 0 else min(P.ph, pmax))
        load_rel = abs(P.weights @ p - W) / W if balance else 0.0
        history.append((dmax, omega * abs(dh) / P.hscale, load_rel, int(np.sum(p[idx] < 1e-6 * ps))))
        log.debug("EHL FB %d: |dp|/ph = %.2e, dh00/hs = %.2e, load err %.2e, omega %.3g, merit %.2e, gmres %d, "
                  "h_min/hs %.2e, h00/hs %.3g",
                  it, dmax, history[-1][1], load_rel, omega, theta0, lin.gmres_iters, np.min(hn) / P.hscale,
                  h00 / P.hscale)
        if not np.all(np.isfinite(p)):
            raise _stopped("non-finite pressure",
                           f"EHL Newton iteration {it}: non-finite pressure (M = {contact.moes_M:.4g})")
    else:
        err = ConvergenceError(
            f"EHL solve did not converge in {max_iter} Newton iterations at M = {contact.moes_M:.4g}, "
            f"L = {contact.moes_L:.4g} ({_nodes(P)}): last |dp|/p_Hertz = {history[-1][0]:.2e}, load error "
            f"{history[-1][2]:.2e} ({stalls} line-search stalls; [solver] max_iter, EHLOptions.max_iter)"
            f"{_heavy(P, '; ')}"
        )
        err.iterate = (np.maximum(p, 0.0), h00)
        err.stop = dict(reason="iteration limit", detail=str(err))
        raise err
    P.factorisations = nfact
    return np.maximum(p, 0.0), h00, history, gm
