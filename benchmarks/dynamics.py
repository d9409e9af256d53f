"""Bearing dynamics: speed against accuracy on the cage-less 6206 (paper B).

Writes ``benchmarks/results/dynamics.json`` and ``dynamics.png`` (``--quick``:
``dynamics_quick.*``, so a smoke run never replaces the full numbers)::

    python benchmarks/dynamics.py            # full run (about 10-15 minutes on a busy 2-core machine)
    python benchmarks/dynamics.py --quick    # short windows, a couple of minutes
        --repeats N    timed repeats per point (median; default 3, quick 1)
        --skip-cli     leave out the cold/warm CLI runs (section 6; --quick leaves them out too)

The scene is ``cases/cageless_6206_10krpm.toml`` (rotor drop at 10,000 rpm
onto the inner ring, Fr = 2000 N, Fa = 200 N, 14 balls, 6-DOF balls,
closed-form ball-ball film, one outer-ring slot), built exactly as the CLI
builds it (:func:`lubedyn.scenes.dynamics.build`), from its quasi-static
initial state.

Sections
--------
1. Work-precision over the first ``window`` of the drop (2 ms full, 1 ms
   quick: the balls are pushed into their first collisions, 4 N at 1.0 ms,
   about 200 N at 1.6 ms; a longer window has no pointwise reference, see
   1b): RK4 over fixed steps from near its
   stability limit down, DOPRI5 over rtol 1e-3 ... 1e-9 (atol = 1e-3 rtol
   [m, m/s, rad/s ...], the case file's ratio).  Reference: DOPRI5 at rtol
   1e-10 (quick: 1e-9).  Errors at the window's end:
     * ball position error: max over the 14 balls of |c_j - c_j,ref| (3-D
       centre), divided by the Hertz deflection delta_H of the most loaded
       inner-race contact of the initial state ((Q_max/K_i)^(2/3));
     * inner-ring speed error |omega - omega_ref| divided by the rotor's
       initial speed Omega_0.
   A setting is *converged* when the position error is <= 1 % of delta_H and
   the ring-speed error <= 1e-3 Omega_0; the cheapest converged one is named.
   The run at the next-looser tolerance than the reference bounds the
   reference's own error (points below it are flagged).
1b. Predictability: DOPRI5 at rtol 1e-7, 1e-8 (, 1e-9) over 5 ms (quick
   2 ms) against the tightest of them, the ball position difference at every
   0.1 ms and its fitted growth rate (a finite-time Lyapunov exponent of the
   collision phase): after the first collisions two accurate solutions part
   within a few ms, so pointwise errors over longer windows measure chaos,
   not the integrator.
2. Largest stable step against contact stiffness: ball and ring moduli
   multiplied by 0.1 ... 30 (Hertz constants and ball-ball stiffness scale
   with E*), the largest step of RK4 and of fixed-step DOPRI5 (rtol = atol =
   1e10, h0 = h_max = dt: the error control never rejects) that keeps a
   2 ms drop run finite and within 100 delta_H of a DOPRI5 rtol 1e-7 run
   (bounded: stable, not accurate; a 0.8 mm excursion is impossible for a
   ball between its races, so it marks a blown-up run that is still finite),
   found by bisection in log(dt) to 2 %; compared with
   ``stability_limit(method) / omega_max``; what the integrator says beyond
   it (with and without ``omega_max``) is quoted; and what adaptive DOPRI5
   does at a loose tolerance (mean step against the stable step, rejections).
3. Fidelity: planar against 6-DOF balls (steady inner ring, Fa = 0 for both,
   and 6-DOF with Fa = 200 N for comparison) and the ball-ball film none /
   closed form / map (``cases/maps/ball_ball.npz``) in the drop; wall time
   per simulated ms and the answers (collisions above 1 N, peak collision
   force, ball-train speed, inner-ring orbit, ring speed); a second closed-
   form run at rtol 1e-7 gives the integration noise of those answers.
4. scipy ``solve_ivp`` (RK45, DOP853) on the same numba rhs through a Python
   wrapper, same rtol/atol, over a shorter window, against lubedyn's DOPRI5
   on the same window: wall per simulated ms and the ratio; their errors
   against the reference; and the same on a 2-state rhs (one Hertz impact).
4b. Equal accuracy (``equal_accuracy``): every lubedyn method (DOPRI5, RK4,
   ROS2 with a finite-difference Jacobian) and every scipy method (RK45,
   DOP853, LSODA, BDF and Radau, the last two with the bearing's
   ``jac_sparsity``) over a range of tolerances on the same window, the
   ball-position error at its end against the reference, the wall time to
   reach 0.1 / 0.01 / 0.001 delta_H interpolated log-log, and the honest
   ratio: scipy's best method over lubedyn's best at equal error.  Also the
   bound for methods making the same rhs calls, 1 + o/c with c one rhs call
   from compiled code and o scipy's overhead per call (wall/nfev - c).
   Walls here are the fastest of the repeats.
5. Simulated ms per wall second at the cheapest converged setting, and a
   measured 0.1 s run of the drop (quick: 10 ms, extrapolated).
6. First-call compile time in fresh processes with empty caches (cold) and
   again (warm): ``NUMBA_CACHE_DIR`` (numba's on-disk cache of every
   ``cache=True`` function, the bound kernels of :mod:`lubedyn.dynamics.specialise`
   included) points into a new temporary directory; and ``lubedyn run
   cases/cageless_6206_10krpm_short.toml --smoke`` cold and warm the same way.

Times are wall-clock medians of ``--repeats`` runs and also ratios to a
reference run in the same process (DOPRI5 rtol 1e-6 over the first 1 ms of
the drop), because the machine is shared; the load average is recorded per
section.  Every kernel is called once before it is timed (compilation or
cache load is reported separately).  Nothing here asserts a time.
"""
from __future__ import annotations

import argparse
import json
import logging
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks.dynamics_tools

import _common  # noqa: E402

from lubedyn.config import CASES_DIR, load_case  # noqa: E402
from lubedyn.scenes.dynamics import ball_centres, build  # noqa: E402
from lubedyn.dynamics.analysis import collision_events  # noqa: E402
from lubedyn.dynamics.cageless import (  # noqa: E402
    D_BBN, D_BBX, D_BBY, D_BBZ, D_PSIDOT, D_QI, forces, forces_many, rhs)
from lubedyn.dynamics.errors import DynamicsInputError, IntegrationError  # noqa: E402
from lubedyn.dynamics.integrators import integrate, stability_limit  # noqa: E402

log = logging.getLogger("benchmarks.dynamics")
ROOT = Path(__file__).resolve().parents[1]
RESULTS = Path(__file__).resolve().parent / "results"
CASE = CASES_DIR / "cageless_6206_10krpm.toml"
SHORT_CASE = CASES_DIR / "cageless_6206_10krpm_short.toml"
MAP = CASES_DIR / "maps" / "ball_ball.npz"
ATOL_PER_RTOL = 1e-3  # atol = 1e-3 rtol, as the case file (rtol 1e-6, atol 1e-9)
POS_TOL = 1e-2  # converged: ball position error <= 1 % of the Hertz deflection
SPEED_TOL = 1e-3  # ... and inner-ring speed error <= 1e-3 of the rotor's initial speed
UNSTABLE_FACTOR = 100.0  # a run more than 100 delta_H (about 0.8 mm) off a tight run counts as unstable

SIZES = {
    "quick": dict(window=1e-3, ref_rtol=1e-9, samples=11, predict_window=2e-3, predict_rtol=[1e-7, 1e-8],
                  rk4_dt=[1.2e-5, 1e-5, 5e-6, 2.5e-6, 1.25e-6],
                  dopri_rtol=[1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8],
                  stiffness=[0.3, 1.0, 3.0], stab_window=1e-3, bisections=5,
                  fidelity_window=2e-3, scipy_window=1e-3, long=10e-3, repeats=1,
                  eq_rtols=[1e-4, 1e-5, 1e-6, 1e-7, 1e-8], eq_rk4_dt=[2.5e-6, 1.25e-6, 6.25e-7],
                  eq_ros2_rtols=[1e-2], eq_ros2_steps=20000, eq_implicit_rtols=[1e-2, 1e-3, 1e-4],
                  eq_lsoda_rtols=[1e-4, 1e-6]),
    "full": dict(window=2e-3, ref_rtol=1e-10, samples=21, predict_window=5e-3, predict_rtol=[1e-7, 1e-8, 1e-9],
                 rk4_dt=[1.2e-5, 1e-5, 7.5e-6, 5e-6, 2.5e-6, 1.25e-6, 6.25e-7, 3.125e-7, 1.5625e-7],
                 dopri_rtol=[1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9],
                 stiffness=[0.1, 0.3, 1.0, 3.0, 10.0, 30.0], stab_window=2e-3, bisections=7,
                 fidelity_window=20e-3, scipy_window=2e-3, long=0.1, repeats=3,
                 eq_rtols=[1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9], eq_rk4_dt=[2.5e-6, 1.25e-6, 6.25e-7, 3.125e-7],
                 eq_ros2_rtols=[1e-2], eq_ros2_steps=50000,
                 eq_implicit_rtols=[1e-2, 1e-3, 1e-4, 1e-5], eq_lsoda_rtols=[1e-4, 1e-6]),
}


def load() -> float:
    return float(os.getloadavg()[0]) if hasattr(os, "getloadavg") else float("nan")


# ------------------------------------------------------------------ scene
def drop_setup():
    case = load_case(CASE)
    return build(case, str(CASE))


def variant(model, changes: dict):
    """A changed copy of the bearing (``changes`` by case key, ``{"model.dof": "planar"}``) and its own
    quasi-static initial state."""
    m = model.replace(**changes)
    return m, m.initial_state()


def hertz_deflection(model, y0) -> tuple[float, float]:
    """(delta_H [m], Q_max [N]) of the most loaded inner-race contact."""
    diag, _, _ = forces(0.0, y0, model.args())
    Ki, _ = model.hertz_constants()
    q = float(diag[:, D_QI].max())
    return (q / Ki) ** (2.0 / 3.0), q


def centres(model, Y):
    return ball_centres(SimpleNamespace(model=model), Y)


def run(model, y0, t_out, method, value, **kw):
    """One integration; ``value`` is dt (rk4) or rtol (dopri5)."""
    if method == "rk4":
        return integrate(rhs, y0, t_out, model.args(), method="rk4", dt=value, **kw)
    return integrate(rhs, y0, t_out, model.args(), method="dopri5", rtol=value, atol=ATOL_PER_RTOL * value, **kw)


def errors(model, Y, Yref, dH, omega0) -> dict:
    c, cr = centres(model, Y), centres(model, Yref)
    pos = np.max(np.linalg.norm(c - cr, axis=2), axis=1) / dH
    spd = np.abs(Y[:, 7] - Yref[:, 7]) / omega0
    ring = np.hypot(Y[:, 0] - Yref[:, 0], Y[:, 1] - Yref[:, 1]) / dH
    return {"ball position error at end [delta_H]": float(pos[-1]),
            "ball position error, max over samples [delta_H]": float(np.max(pos)),
            "inner ring speed error at end [Omega_0]": float(spd[-1]),
            "inner ring speed error, max over samples [Omega_0]": float(np.max(spd)),
            "inner ring position error at end [delta_H]": float(ring[-1])}


class Clock:
    """Reference time unit: DOPRI5 rtol 1e-6 (atol 1e-9) over the first 1 ms of the drop."""

    def __init__(self, model, y0, repeats=5):
        t_out = np.linspace(0.0, 1e-3, 11)
        run(model, y0, t_out, "dopri5", 1e-6)  # compile / load
        self.seconds, self.all, res = _common.timed(lambda: run(model, y0, t_out, "dopri5", 1e-6), repeats=repeats)
        self.nfev = res.stats["RHS evaluations [-]"]
        dy = np.empty(y0.size)
        args = model.args()
        rhs(0.0, y0, args, dy)
        n = 2000
        times = []
        for _ in range(3):
            t0 = time.perf_counter()
            for _ in range(n):
                rhs(0.0, y0, args, dy)
            times.append((time.perf_counter() - t0) / n)
        self.rhs_call = float(np.median(times))

    def ratio(self, seconds):
        return seconds / self.seconds

    def describe(self) -> dict:
        return {"what": "DOPRI5 rtol 1e-6, atol 1e-9 over the first 1 ms of the drop (11 samples)",
                "median [s]": self.seconds, "all [s]": self.all, "RHS evaluations [-]": self.nfev,
                "one rhs call from Python, 14 balls 6-DOF, initial state [us]": self.rhs_call * 1e6}


# ------------------------------------------------------------------ 1. work-precision
def bench_work_precision(setup, cfg, clock, repeats):
    model, y0 = setup.model, setup.y0
    dH, qmax = hertz_deflection(model, y0)
    omega0 = float(y0[8])
    t_out = np.linspace(0.0, cfg["window"], cfg["samples"])
    log.info("reference: DOPRI5 rtol %g over %g s", cfg["ref_rtol"], cfg["window"])
    t0 = time.perf_counter()
    ref = run(model, y0, t_out, "dopri5", cfg["ref_rtol"])
    ref_wall = time.perf_counter() - t0
    out = {"window [s]": cfg["window"], "samples [-]": cfg["samples"],
           "Hertz deflection delta_H [m]": dH, "largest inner race load Q_max [N]": qmax,
           "rotor initial speed Omega_0 [rad/s]": omega0,
           "error definition": ("ball position error: max over balls of the 3-D centre error at the window's end "
                                "over delta_H; inner ring speed error: |omega - omega_ref| / Omega_0 at the end"),
           "converged means": f"ball position error <= {POS_TOL:g} delta_H and ring speed error <= {SPEED_TOL:g} "
                              "Omega_0",
           "reference": {"method": "dopri5", "rtol": cfg["ref_rtol"], "atol": ATOL_PER_RTOL * cfg["ref_rtol"],
                         "wall [s]": ref_wall, **ref.stats},
           "load average": load()}
    points = []
    for method, values in (("rk4", cfg["rk4_dt"]), ("dopri5", cfg["dopri_rtol"])):
        for v in values:
            p = {"method": method, ("dt [s]" if method == "rk4" else "rtol [-]"): v}
            if method == "rk4":
                p["dt * omega_max [-]"] = v * model.omega_max(y0)
            try:
                wall, allw, res = _common.timed(lambda: run(model, y0, t_out, method, v), repeats=repeats,
                                                single_above=10.0)
            except (IntegrationError, DynamicsInputError) as exc:
                p["failed"] = str(exc)
                points.append(p)
                log.info("%s %g: FAILED %s", method, v, exc)
                continue
            p.update({"wall [s]": wall, "wall, all repeats [s]": allw, "time / unit [-]": clock.ratio(wall),
                      **res.stats})
            p.update(errors(model, res.y, ref.y, dH, omega0))
            points.append(p)
            log.info("%s %g: %.3f s, pos %.3g dH, speed %.3g", method, v, wall,
                     p["ball position error at end [delta_H]"], p["inner ring speed error at end [Omega_0]"])
    # the loosest run next to the reference bounds the reference's own error
    nxt = [p for p in points if p["method"] == "dopri5" and "failed" not in p
           and math.isclose(p["rtol [-]"], cfg["ref_rtol"] * 10.0)]
    floor_pos = nxt[0]["ball position error at end [delta_H]"] if nxt else 0.0
    floor_spd = nxt[0]["inner ring speed error at end [Omega_0]"] if nxt else 0.0
    out["reference uncertainty (error of the rtol 10x looser run) [delta_H, Omega_0]"] = [floor_pos, floor_spd]
    for p in points:
        if "failed" in p:
            p["converged"] = False
            continue
        p["converged"] = bool(p["ball position error at end [delta_H]"] <= POS_TOL
                              and p["inner ring speed error at end [Omega_0]"] <= SPEED_TOL)
        p["below reference uncertainty"] = bool(p is not (nxt[0] if nxt else None)
                                                and p["ball position error at end [delta_H]"] <= floor_pos)
    conv = [p for p in points if p["converged"]]
    best = min(conv, key=lambda p: p["wall [s]"]) if conv else None
    out["points"] = points
    out["cheapest converged"] = ({k: best[k] for k in ("method", "dt [s]", "rtol [-]", "wall [s]",
                                                        "ball position error at end [delta_H]",
                                                        "inner ring speed error at end [Omega_0]") if k in best}
                                 if best else None)
    for method in ("rk4", "dopri5"):
        c = [p for p in conv if p["method"] == method]
        b = min(c, key=lambda p: p["wall [s]"]) if c else None
        out[f"cheapest converged {method}"] = ({k: b[k] for k in ("dt [s]", "rtol [-]", "wall [s]") if k in b}
                                               if b else None)
    pts = [p for p in points if "failed" not in p]
    for method in ("rk4", "dopri5"):
        s = [p for p in pts if p["method"] == method]
        out[f"time to position error {method} [s]"] = _common.time_to_error(
            [p["wall [s]"] for p in s], [p["ball position error at end [delta_H]"] for p in s],
            targets=(1e-1, 1e-2, 1e-3))
    return out, ref


def bench_predictability(setup, cfg):
    model, y0 = setup.model, setup.y0
    dH, _ = hertz_deflection(model, y0)
    W = cfg["predict_window"]
    t = np.linspace(0.0, W, int(round(W / 1e-4)) + 1)
    runs = {r: run(model, y0, t, "dopri5", r).y for r in cfg["predict_rtol"]}
    tight = min(runs)
    diag, _ = forces_many(t, runs[tight], model.args())
    out = {"window [s]": W, "t [s]": t, "reference": f"dopri5 rtol {tight:g}",
           "largest ball-ball normal force at the samples of the reference [N]": diag[:, :, D_BBN].max(axis=1),
           "load average": load(), "pairs": []}
    ct = centres(model, runs[tight])
    for r in sorted(runs, reverse=True):
        if r == tight:
            continue
        e = np.max(np.linalg.norm(centres(model, runs[r]) - ct, axis=2), axis=1) / dH
        grow = (e > 1e-4) & (e < 0.3)
        rate = float(np.polyfit(t[grow], np.log(e[grow]), 1)[0]) if grow.sum() >= 3 else None

        def first(level):
            k = np.flatnonzero(e >= level)
            return float(t[k[0]]) if k.size else None

        out["pairs"].append({"rtol [-]": r, "ball position difference [delta_H]": e,
                             "growth rate while 1e-4 < difference < 0.3 delta_H [1/s]": rate,
                             "first time difference >= 0.01 delta_H [s]": first(0.01),
                             "first time difference >= 1 delta_H [s]": first(1.0)})
        log.info("predictability rtol %g vs %g: rate %s 1/s, 0.01 dH at %s s", r, tight, rate, first(0.01))
    return out


# ------------------------------------------------------------------ 2. stability
def _trial(model, y0, t_out, method, dt, cref, dH, omega_max=None):
    """(stable?, note) of one fixed-step run."""
    kw = {} if omega_max is None else {"omega_max": omega_max}
    try:
        if method == "rk4":
            res = integrate(rhs, y0, t_out, model.args(), method="rk4", dt=dt, **kw)
        else:
            res = integrate(rhs, y0, t_out, model.args(), method="dopri5", rtol=1e10, atol=1e10, h0=dt, h_max=dt,
                            max_steps=10**8, **kw)
    except (IntegrationError, DynamicsInputError) as exc:
        return False, f"{type(exc).__name__}: {exc}"
    except ZeroDivisionError as exc:  # raised inside the numba rhs (Python error model) by a wild state
        return False, f"{type(exc).__name__} raised inside the compiled rhs: {exc}"
    Y = res.y
    if not np.all(np.isfinite(Y)):
        return False, "non-finite samples"
    err = float(np.max(np.linalg.norm(centres(model, Y) - cref, axis=2))) / dH
    if err > UNSTABLE_FACTOR:
        return False, f"finished, but balls {err:.3g} delta_H off the tight run"
    return True, f"finished, ball position error {err:.3g} delta_H"


def largest_stable(model, y0, t_out, method, cref, dH, guess, bisections):
    lo, hi = 0.3 * guess, 3.0 * guess
    trials = []
    ok, note = _trial(model, y0, t_out, method, lo, cref, dH)
    trials.append((lo, ok, note))
    while not ok and lo > 1e-3 * guess:
        hi = lo
        lo *= 0.5
        ok, note = _trial(model, y0, t_out, method, lo, cref, dH)
        trials.append((lo, ok, note))
    ok, note = _trial(model, y0, t_out, method, hi, cref, dH)
    trials.append((hi, ok, note))
    while ok and hi < 1e3 * guess:
        lo = hi
        hi *= 2.0
        ok, note = _trial(model, y0, t_out, method, hi, cref, dH)
        trials.append((hi, ok, note))
    for _ in range(bisections):
        mid = math.sqrt(lo * hi)
        ok, note = _trial(model, y0, t_out, method, mid, cref, dH)
        trials.append((mid, ok, note))
        if ok:
            lo = mid
        else:
            hi = mid
    return lo, hi, trials


def jacobian_spectrum(model, y) -> dict:
    """Eigenvalues of the central-difference Jacobian of the rhs at ``y`` and the largest step for which
    the linearised system is stable under each method (|R(h lambda)| <= 1 for every eigenvalue with
    Re lambda <= 0; eigenvalues with Re lambda > 0 are reported and left out)."""
    from lubedyn.dynamics.integrators import STABILITY_POLYNOMIALS

    args = model.args()
    n = y.size
    J = np.empty((n, n))
    fp, fm = np.empty(n), np.empty(n)
    for i in range(n):
        d = 1.5e-8 * max(abs(y[i]), 1e-3)
        yp, ym = y.copy(), y.copy()
        yp[i] += d
        ym[i] -= d
        rhs(0.0, yp, args, fp)
        rhs(0.0, ym, args, fm)
        J[:, i] = (fp - fm) / (2.0 * d)
    lam = np.linalg.eigvals(J)
    big = np.abs(lam).max()
    unstable = lam[lam.real > 1e-9 * big]
    keep = lam[(lam.real <= 1e-9 * big) & (np.abs(lam) > 1e-9 * big)]
    out = {"spectral radius [1/s]": float(big), "largest |Im lambda| [rad/s]": float(np.abs(lam.imag).max()),
           "most negative Re lambda [1/s]": float(lam.real.min()),
           "eigenvalues with Re > 0 [-]": int(unstable.size),
           "largest Re lambda [1/s]": float(lam.real.max()),
           "eigenvalue of largest modulus": [float(lam[np.argmax(np.abs(lam))].real),
                                             float(lam[np.argmax(np.abs(lam))].imag)]}
    hs = np.logspace(-9, -3, 2401)
    for method, coeffs in STABILITY_POLYNOMIALS.items():
        Z = np.outer(hs, keep)
        R = np.polynomial.polynomial.polyval(Z, np.asarray(coeffs))
        bad = np.flatnonzero(np.abs(R).max(axis=1) > 1.0 + 1e-9)
        out[f"linear stable step {method} [s]"] = float(hs[bad[0] - 1]) if bad.size and bad[0] > 0 else None
    return out


def bench_stability(setup, cfg, ref=None, ref_t=None):
    base = setup.model
    t_out = np.linspace(0.0, cfg["stab_window"], 11)
    out = {"window [s]": cfg["stab_window"], "stable means": (
        f"finite and within {UNSTABLE_FACTOR:g} delta_H (ball centres, every sample) of a DOPRI5 rtol 1e-7 run"),
        "DOPRI5 fixed step": "rtol = atol = 1e10, h0 = h_max = dt (the error test never rejects)",
        "stability_limit imaginary axis": {m: stability_limit(m) for m in ("rk4", "dopri5")},
        "stability_limit real axis": {m: stability_limit(m, "real") for m in ("rk4", "dopri5")},
        "load average": load(), "scales": []}
    for s in cfg["stiffness"]:
        row = {"modulus factor [-]": s}
        try:
            model, y0 = (setup.model, setup.y0) if s == 1.0 else variant(
                base, {"bearing.ball_modulus": base.bearing.ball_modulus * s,
                       "bearing.ring_modulus": base.bearing.ring_modulus * s})
        except DynamicsInputError as exc:
            row["failed"] = str(exc)
            out["scales"].append(row)
            continue
        dH, q = hertz_deflection(model, y0)
        om = model.omega_max(y0)
        Ki, Ko = model.hertz_constants()
        row.update({"K_i [N/m^1.5]": Ki, "K_o [N/m^1.5]": Ko, "delta_H [m]": dH, "Q_max [N]": q,
                    "contact stiffness 1.5 K_i^(2/3) Q^(1/3) [N/m]": 1.5 * Ki ** (2 / 3) * q ** (1 / 3),
                    "omega_max [rad/s]": om})
        tight = run(model, y0, t_out, "dopri5", 1e-7)
        cref = centres(model, tight.y)
        row["linearised at the initial state"] = jacobian_spectrum(model, y0)
        for method in ("rk4", "dopri5"):
            predicted = stability_limit(method) / om
            lo, hi, trials = largest_stable(model, y0, t_out, method, cref, dH, predicted, cfg["bisections"])
            r = {"largest stable dt [s]": lo, "smallest unstable dt [s]": hi,
                 "predicted stability_limit/omega_max [s]": predicted,
                 "measured / predicted [-]": lo / predicted, "largest stable dt * omega_max [-]": lo * om,
                 "trials (dt, stable, note)": trials}
            beyond = 1.5 * lo
            ok, note = _trial(model, y0, t_out, method, beyond, cref, dH)
            r["at 1.5 x largest stable, without omega_max"] = {"dt [s]": beyond, "stable": ok, "outcome": note}
            ok, note = _trial(model, y0, t_out, method, beyond, cref, dH, omega_max=om)
            r["at 1.5 x largest stable, with omega_max"] = {"dt [s]": beyond, "stable": ok, "outcome": note}
            ok, note = _trial(model, y0, t_out, method, 0.9 * lo, cref, dH, omega_max=om)
            r["at 0.9 x largest stable, with omega_max"] = {"dt [s]": 0.9 * lo, "stable": ok, "outcome": note}
            row[method] = r
            log.info("E x %g, %s: largest stable %.3g s (predicted %.3g s)", s, method, lo, predicted)
        # adaptive DOPRI5 at loose tolerances: does its step control find the stability limit?
        row["adaptive dopri5"] = []
        for rtol in (1e-2, 1e-3, 1e-4):
            res = run(model, y0, t_out, "dopri5", rtol)
            acc = res.stats["Accepted steps [-]"]
            mean_h = cfg["stab_window"] / max(acc, 1)
            row["adaptive dopri5"].append({"rtol [-]": rtol, **res.stats, "mean accepted step [s]": mean_h,
                                           "mean step / largest stable fixed step [-]":
                                               mean_h / row["dopri5"]["largest stable dt [s]"]})
        out["scales"].append(row)
    # which mode is the stiffest?  Spectrum and adaptive DOPRI5 cost with the traction law changed
    base_t = np.linspace(0.0, cfg["stab_window"], 11)
    modes = {}
    for label, kw in (("as the case", {}),
                      ("traction_slip_regularisation x10 (0.5 m/s)",
                       {"model.traction_slip_regularisation": 10.0 * base.fidelity.traction_slip_regularisation}),
                      ("no race traction (traction_limit = 0)", {"model.traction_limit": 0.0}),
                      ("race_damping x10", {"model.race_damping": 10.0 * base.fidelity.race_damping})):
        m, y0 = (base, setup.y0) if not kw else variant(base, kw)
        r = {"omega_max() [rad/s]": m.omega_max(y0), **jacobian_spectrum(m, y0)}
        for rtol in (1e-3, 1e-6):
            w, _, res = _common.timed(lambda: run(m, y0, base_t, "dopri5", rtol), repeats=3)
            r[f"dopri5 rtol {rtol:g}"] = {"wall [s]": w, **res.stats,
                                          "mean accepted step [s]": cfg["stab_window"] / res.stats["Accepted steps [-]"]}
        modes[label] = r
        log.info("stiffest mode, %s: spectral radius %.3g, dopri5 1e-6 %d steps", label,
                 r["spectral radius [1/s]"], r["dopri5 rtol 1e-06"]["Accepted steps [-]"])
    out["stiffest mode (spectrum at the initial state; adaptive DOPRI5 over the window)"] = modes
    if ref is not None:  # the scene's own model at the sample of the reference with the largest collision force
        diag, _ = forces_many(ref_t, ref, setup.model.args())
        k = int(np.argmax(diag[:, :, D_BBN].max(axis=1)))
        out["linearised at the strongest collision of the reference"] = {
            "t [s]": float(ref_t[k]), "ball-ball normal force [N]": float(diag[k, :, D_BBN].max()),
            **jacobian_spectrum(setup.model, ref[k])}
    return out


# ------------------------------------------------------------------ 3. fidelity
def answers(model, y0, window, rtol=1e-6, sample=2e-6, repeats=1):
    n = int(round(window / sample))
    t_out = np.linspace(0.0, n * sample, n + 1)
    run(model, y0, t_out[:3], "dopri5", rtol)  # compile/load for this model's args types
    wall, allw, res = _common.timed(lambda: run(model, y0, t_out, "dopri5", rtol), repeats=repeats,
                                    single_above=5.0)
    Y = res.y
    diag, _ = forces_many(t_out, Y, model.args())
    c = centres(model, Y)
    pos = 0.5 * (c + np.roll(c, -1, axis=1))
    ev = collision_events(t_out, diag[:, :, D_BBN], diag[:, :, [D_BBX, D_BBY, D_BBZ]], pos, 1.0)
    half = t_out >= 0.5 * t_out[-1]
    rx, ry = Y[half, 0], Y[half, 1]
    out = {"rtol [-]": rtol, "states [-]": int(Y.shape[1]), "wall [s]": wall, "wall, all repeats [s]": allw,
           "wall per simulated ms [s]": wall / (t_out[-1] * 1e3), **res.stats,
           "collisions above 1 N [-]": len(ev),
           "peak collision normal force [N]": float(max((e.peak_force for e in ev), default=0.0)),
           "ball-train speed, mean over balls, second half [rad/s]": float(np.mean(diag[half][:, :, D_PSIDOT])),
           "inner ring speed at end [rad/s]": float(Y[-1, 7]),
           "inner ring orbit rms about its mean, second half [um]": float(
               np.sqrt(np.mean((rx - rx.mean()) ** 2 + (ry - ry.mean()) ** 2)) * 1e6),
           "inner ring y mean, second half [um]": float(ry.mean() * 1e6),
           "inner ring x, y peak-to-peak, second half [um]": [float(np.ptp(rx) * 1e6), float(np.ptp(ry) * 1e6)],
           "largest inner race load [N]": float(diag[:, :, D_QI].max())}
    ctr = getattr(model, "map_counter", None)
    if ctr is not None and model.films.ball_ball == "map":
        out["film map queries outside axes [-]"] = int(ctr[0])
    return out


def bench_fidelity(setup, cfg, repeats):
    base, W = setup.model, cfg["fidelity_window"]
    out = {"window [s]": W, "sample interval [s]": 2e-6, "integrator": "dopri5, atol = 1e-3 rtol",
           "collision": "a maximal run of 2-us samples with a pair's normal force above 1 N (lubedyn.dynamics.analysis)",
           "load average": load()}
    steady = {}
    for label, kw in (("6dof, Fa = 0", {"model.dof": "6dof", "operating.axial_load": 0.0}),
                      ("planar, Fa = 0", {"model.dof": "planar", "operating.axial_load": 0.0}),
                      ("6dof, Fa = 200 N", {"model.dof": "6dof", "operating.axial_load": 200.0}),
                      ("6dof, Fa = 0, rtol 1e-7 (integration noise)", {"model.dof": "6dof",
                                                                       "operating.axial_load": 0.0})):
        m, y0 = variant(base, {"operating.scenario": "steady", **kw})
        steady[label] = answers(m, y0, W, rtol=1e-7 if "1e-7" in label else 1e-6, repeats=repeats)
        log.info("steady %s: %.3f s/ms, %d collisions", label, steady[label]["wall per simulated ms [s]"],
                 steady[label]["collisions above 1 N [-]"])
    out["steady 10,000 rpm"] = steady
    films = {}
    from lubedyn.maps import FilmMap

    fmap = FilmMap.load(MAP)
    arrays = fmap.dynamics_film_map() if hasattr(fmap, "dynamics_film_map") else fmap.kernel_arrays("Force [N]")
    for label, kw, rtol in (("closed_form", {}, 1e-6), ("map", {"films.ball_ball": "map", "films.map": arrays}, 1e-6),
                            ("none", {"films.ball_ball": "none"}, 1e-6), ("closed_form, rtol 1e-7 (integration noise)", {},
                                                                1e-7)):
        m, y0 = (base, setup.y0) if not kw else variant(base, kw)
        films[label] = answers(m, y0, W, rtol=rtol, repeats=repeats)
        log.info("drop film %s: %.3f s/ms, %d collisions", label, films[label]["wall per simulated ms [s]"],
                 films[label]["collisions above 1 N [-]"])
    out["drop, ball-ball film"] = films
    costs = {}
    for label, kw in (("drop, 6dof, closed_form film (the case)", {}),
                      ("drop, 6dof, map film", {"films.ball_ball": "map", "films.map": arrays}),
                      ("drop, 6dof, no film", {"films.ball_ball": "none"}),
                      ("drop, 6dof, no ball-ball contacts", {"model.ball_ball": False}),
                      ("drop, 6dof, no slot", {"slots.azimuths": ()}),
                      ("steady, planar, Fa = 0", {"operating.scenario": "steady", "model.dof": "planar",
                                                  "operating.axial_load": 0.0}),
                      ("steady, 6dof, Fa = 0", {"operating.scenario": "steady", "operating.axial_load": 0.0})):
        m, y0 = (base, setup.y0) if not kw else variant(base, kw)
        costs[label] = {"states [-]": int(y0.size), "one rhs call [us]": setup_rhs_cost(m, y0) * 1e6}
    out["rhs cost at the initial state (2000 calls from Python)"] = costs
    out["map"] = {"file": f"cases/{MAP.relative_to(CASES_DIR).as_posix()}",
                  "kind": getattr(fmap, "kind", None) or fmap.provenance.get("kind"),
                  "method": getattr(fmap, "method", None)}
    return out


# ------------------------------------------------------------------ 4. scipy
def bench_scipy(setup, cfg, ref, ref_t, repeats, rtol=1e-6):
    from scipy.integrate import solve_ivp

    model, y0 = setup.model, setup.y0
    args = model.args()
    W = cfg["scipy_window"]
    dH, _ = hertz_deflection(model, y0)
    omega0 = float(y0[8])
    t_out = np.array([0.0, W])
    j = int(np.argmin(np.abs(ref_t - W)))
    have_ref = abs(ref_t[j] - W) < 1e-12
    out = {"window [s]": W, "rtol [-]": rtol, "atol [-]": ATOL_PER_RTOL * rtol, "load average": load(),
           "wrapper": "def f(t, y): rhs(t, y, args, dy); return dy.copy()  (the numba rhs, called from Python)"}
    wall, allw, res = _common.timed(lambda: run(model, y0, t_out, "dopri5", rtol), repeats=repeats)
    lub = {"wall [s]": wall, "wall, all repeats [s]": allw, **res.stats}
    if have_ref:
        lub.update(errors(model, res.y[-1:], ref[j:j + 1], dH, omega0))
    out["lubedyn dopri5"] = lub
    f, calls = python_rhs(args, y0.size)

    for method in ("RK45", "DOP853"):
        def go():
            calls[0] = 0
            return solve_ivp(f, (0.0, W), y0, method=method, rtol=rtol, atol=ATOL_PER_RTOL * rtol, t_eval=[W])

        wall_s, allw_s, sol = _common.timed(go, repeats=max(1, repeats - 1), single_above=20.0)
        r = {"wall [s]": wall_s, "wall, all repeats [s]": allw_s, "status": int(sol.status), "message": sol.message,
             "RHS evaluations [-]": int(sol.nfev), "ratio scipy / lubedyn per simulated ms [-]": wall_s / wall,
             "Python overhead per rhs call [us]": (wall_s / max(sol.nfev, 1) - setup_rhs_cost(model, y0)) * 1e6}
        if have_ref and sol.success:
            r.update(errors(model, sol.y[:, -1:].T, ref[j:j + 1], dH, omega0))
        out[f"scipy {method}"] = r
        log.info("scipy %s: %.2f s against %.4f s (x%.0f)", method, wall_s, wall, wall_s / wall)
    out["lubedyn wall per RHS evaluation [us]"] = wall / max(lub["RHS evaluations [-]"], 1) * 1e6
    out["one rhs call from Python at the initial state [us]"] = setup_rhs_cost(model, y0) * 1e6
    out["cheap rhs for comparison"] = bench_scipy_cheap(repeats, rtol)
    return out


def jac_sparsity(model) -> "scipy.sparse.csr_matrix":
    """Structural sparsity of the bearing Jacobian: ring <-> every ball, ball j <-> itself and its
    neighbours j +- 1 (ball-ball contacts), pair memory j <-> balls j, j+1 and itself (for scipy's
    BDF/Radau ``jac_sparsity``: column grouping cuts the finite-difference Jacobian from n rhs calls)."""
    from scipy.sparse import lil_matrix

    Z, n = model.n_balls, model.n_states
    nb = model.n_per_ball
    S = lil_matrix((n, n), dtype=bool)
    ring = list(range(9))
    blocks = [list(range(model.ball_offset(j), model.ball_offset(j) + nb)) for j in range(Z)]
    mem = [9 + j for j in range(Z)]
    for i in ring:
        S[i, :] = True
    for j in range(Z):
        cols = ring + blocks[j] + blocks[(j - 1) % Z] + blocks[(j + 1) % Z] + [mem[j], mem[(j - 1) % Z]]
        for i in blocks[j]:
            S[i, cols] = True
        S[mem[j], ring + blocks[j] + blocks[(j + 1) % Z] + [mem[j]]] = True
    return S.tocsr()


def bench_equal_accuracy(setup, cfg, ref, ref_t, repeats):
    """lubedyn's integrators against every scipy ``solve_ivp`` method on the same numba rhs, each
    over a range of tolerances, errors at the window's end against the work-precision reference;
    the honest ratio is the wall time of scipy's best method over lubedyn's best at equal error
    (interpolated log-log, :func:`_common.time_to_error`)."""
    from scipy.integrate import solve_ivp

    from lubedyn.dynamics.integrators import kernel_for

    model, y0 = setup.model, setup.y0
    args = model.args()
    W = cfg["scipy_window"]
    j = int(np.argmin(np.abs(ref_t - W)))
    assert abs(ref_t[j] - W) < 1e-12, "the scipy window must be a sample of the reference"
    dH, _ = hertz_deflection(model, y0)
    omega0 = float(y0[8])
    t_out = np.array([0.0, W])
    rhs_cost = rhs_cost_in_numba(model, y0)
    out = {"window [s]": W, "atol": "1e-3 rtol (every method)", "load average": load(),
           "error": "ball position error at the window's end [delta_H] (as section 1)",
           "wall": "fastest of the repeats (the machine is shared; a busy core only slows a run down)",
           "one rhs call from compiled code at the initial state [us] (c)": rhs_cost * 1e6,
           "one rhs call from Python at the initial state [us]": setup_rhs_cost(model, y0) * 1e6, "methods": {}}
    f, calls = python_rhs(args, y0.size)

    sparsity = jac_sparsity(model)

    def point(label, go, value, key):
        try:
            _, allw, res = _common.timed(go, repeats=repeats, single_above=5.0)
        except (IntegrationError, DynamicsInputError) as exc:
            return {key: value, "failed": str(exc)}
        wall = min(allw)
        if hasattr(res, "stats"):  # lubedyn
            yend, nfev, ok = res.y[-1], res.stats["RHS evaluations [-]"], True
            extra = {"Accepted steps [-]": res.stats["Accepted steps [-]"],
                     "Rejected steps [-]": res.stats["Rejected steps [-]"]}
        else:
            ok = bool(res.success) and np.ndim(res.y) == 2 and np.shape(res.y)[1] > 0
            yend, nfev = (res.y[:, -1] if ok else None), int(res.nfev)
            extra = {"status": int(res.status), "Jacobian evaluations [-]": int(getattr(res, "njev", 0)),
                     "LU decompositions [-]": int(getattr(res, "nlu", 0))}
        r = {key: value, "wall [s]": wall, "wall, all repeats [s]": allw, "RHS evaluations [-]": int(nfev),
             "wall per RHS evaluation [us]": wall / max(nfev, 1) * 1e6,
             "overhead per RHS evaluation beyond the rhs call [us]": (wall / max(nfev, 1) - rhs_cost) * 1e6,
             **extra}
        if ok and np.all(np.isfinite(yend)):
            r.update(errors(model, yend[None, :], ref[j:j + 1], dH, omega0))
        else:
            r["failed"] = "did not finish: " + str(getattr(res, "message", ""))
        log.info("%s %s %g: %.3f s, %d rhs, err %s", label, key, value, wall, nfev,
                 r.get("ball position error at end [delta_H]"))
        return r

    lub_tols = cfg["eq_rtols"]
    rows = {}
    rows["lubedyn dopri5"] = [point("lubedyn dopri5", lambda r=r: run(model, y0, t_out, "dopri5", r), r, "rtol [-]")
                              for r in lub_tols]
    rows["lubedyn rk4"] = [point("lubedyn rk4", lambda d=d: run(model, y0, t_out, "rk4", d), d, "dt [s]")
                           for d in cfg["eq_rk4_dt"]]
    ros = kernel_for("ros2", rhs)
    ros(y0, np.array([0.0, 1e-7]), args, 1e-3, 1e-6, 0.0, 0.0, 10, True)  # compile / load
    rows["lubedyn ros2 (finite-difference Jacobian)"] = [
        point("lubedyn ros2", lambda r=r: integrate(rhs, y0, t_out, args, method="ros2", rtol=r,
                                                    atol=ATOL_PER_RTOL * r, max_steps=cfg["eq_ros2_steps"]),
              r, "rtol [-]") for r in cfg["eq_ros2_rtols"]]
    for method in ("RK45", "DOP853", "LSODA", "BDF", "Radau"):
        kw = {"jac_sparsity": sparsity} if method in ("BDF", "Radau") else {}
        tols = {"LSODA": cfg["eq_lsoda_rtols"], "BDF": cfg["eq_implicit_rtols"],
                "Radau": cfg["eq_implicit_rtols"]}.get(method, cfg["eq_rtols"])
        rows[f"scipy {method}"] = [
            point(f"scipy {method}", lambda r=r, method=method, kw=kw: solve_ivp(
                f, (0.0, W), y0, method=method, rtol=r, atol=ATOL_PER_RTOL * r, t_eval=[W], **kw), r, "rtol [-]")
            for r in tols]
    out["methods"] = rows
    targets = (1e-1, 1e-2, 1e-3)
    ttl = {}
    for name, pts in rows.items():
        good = [p for p in pts if "failed" not in p and "ball position error at end [delta_H]" in p]
        ttl[name] = _common.time_to_error([p["wall [s]"] for p in good],
                                          [p["ball position error at end [delta_H]"] for p in good], targets)
    out["wall to reach the error [s] (interpolated; None: not reached)"] = ttl
    ratios = {}
    for tk in (f"{t:.0e}" for t in targets):
        lub = {k: v[tk] for k, v in ttl.items() if k.startswith("lubedyn") and v[tk] is not None}
        sci = {k: v[tk] for k, v in ttl.items() if k.startswith("scipy") and v[tk] is not None}
        if lub and sci:
            bl, bs = min(lub, key=lub.get), min(sci, key=sci.get)
            ratios[tk] = {"lubedyn best": bl, "scipy best": bs, "ratio scipy best / lubedyn best [-]": sci[bs] / lub[bl],
                          "per scipy method [-]": {k: v / lub[bl] for k, v in sci.items()}}
    out["ratio at equal error"] = ratios
    # the bound for an explicit method making the same rhs calls: (rhs + scipy overhead) / (rhs + lubedyn overhead)
    rk = [p for p in rows["scipy RK45"] if "failed" not in p]
    lk = [p for p in rows["lubedyn dopri5"] if "failed" not in p]
    if rk and lk:
        o_s = float(np.median([p["overhead per RHS evaluation beyond the rhs call [us]"] for p in rk]))
        o_l = float(np.median([p["overhead per RHS evaluation beyond the rhs call [us]"] for p in lk]))
        c = rhs_cost * 1e6
        out["bound for equal rhs calls"] = {
            "rhs call from compiled code [us]": c, "rhs call from Python [us]": setup_rhs_cost(model, y0) * 1e6,
            "scipy RK45 overhead per call [us]": o_s, "lubedyn DOPRI5 overhead per call [us]": o_l,
            "ratio bound (c + o_scipy) / (c + o_lubedyn) [-]": (c + o_s) / (c + max(o_l, 0.0)),
            "ratio bound 1 + o_scipy / c [-]": 1.0 + o_s / c}
    return out


_RHS_COST = {}


def bench_scipy_cheap(repeats, rtol=1e-6):
    """The same comparison on a 2-state rhs (a ball hitting a Hertz half-space,
    ``benchmarks/dynamics_tools._contact_rhs``): what the ratio is when the rhs costs nothing."""
    from scipy.integrate import solve_ivp

    from benchmarks.dynamics_tools import _contact_rhs

    k, m, v = 1e9, 3.5e-3, 0.5
    d_max = math.sqrt(1.875 * m * v * v / k)
    args = (k / (1.5 * math.sqrt(d_max)), m)
    dur = 2.9432 * d_max / v
    y0 = np.array([0.5 * v * dur, -v])
    t_out = np.array([0.0, 2.0 * dur])
    integrate(_contact_rhs, y0, t_out, args, rtol=rtol, atol=1e-3 * rtol * d_max)
    wall, _, res = _common.timed(lambda: integrate(_contact_rhs, y0, t_out, args, rtol=rtol,
                                                   atol=1e-3 * rtol * d_max), repeats=max(repeats, 5))
    dy = np.empty(2)

    def f(t, y):
        _contact_rhs(t, y, args, dy)
        return dy.copy()

    out = {"what": "2-state Hertz impact (benchmarks/dynamics_tools._contact_rhs), one impact, same rtol/atol",
           "lubedyn dopri5 wall [s]": wall, **res.stats}
    for method in ("RK45", "DOP853"):
        w, _, sol = _common.timed(lambda: solve_ivp(f, (0.0, 2.0 * dur), y0, method=method, rtol=rtol,
                                                    atol=1e-3 * rtol * d_max), repeats=max(repeats, 3))
        out[f"scipy {method} wall [s]"] = w
        out[f"scipy {method} RHS evaluations [-]"] = int(sol.nfev)
        out[f"ratio scipy {method} / lubedyn [-]"] = w / wall
    return out


def python_rhs(args, n):
    """The bearing's numba rhs as scipy calls it, ``f(t, y) -> dy/dt`` (a fresh array), and its call counter."""
    calls = [0]
    dy = np.empty(n)

    def f(t, y):
        calls[0] += 1
        rhs(t, y, args, dy)
        return dy.copy()

    return f, calls


def setup_rhs_cost(model, y0):
    """One rhs call from Python [s]: the fastest of 40 batches of 200 calls (a shared machine only
    ever makes a batch slower, so the minimum is the machine's cost)."""
    key = id(model)
    if key not in _RHS_COST:
        dy = np.empty(y0.size)
        args = model.args()
        rhs(0.0, y0, args, dy)
        n, best = 200, math.inf
        for _ in range(40):
            t0 = time.perf_counter()
            for _ in range(n):
                rhs(0.0, y0, args, dy)
            best = min(best, (time.perf_counter() - t0) / n)
        _RHS_COST[key] = best
    return _RHS_COST[key]


_RHS_LOOP = {}


def rhs_cost_in_numba(model, y0):
    """One rhs call from compiled code [s] (what lubedyn's integrators pay): the fastest of 200
    batches of 100 calls in a jitted loop."""
    from numba import njit

    key = id(model)
    if key not in _RHS_LOOP:
        @njit
        def loop(y, args, dy, n):
            for _ in range(n):
                rhs(0.0, y, args, dy)

        dy = np.empty(y0.size)
        args = model.args()
        loop(y0, args, dy, 1)
        best = math.inf
        for _ in range(200):
            t0 = time.perf_counter()
            loop(y0, args, dy, 100)
            best = min(best, (time.perf_counter() - t0) / 100)
        _RHS_LOOP[key] = best
    return _RHS_LOOP[key]


# ------------------------------------------------------------------ 5. throughput
def bench_throughput(setup, cfg, best, clock):
    model, y0 = setup.model, setup.y0
    out = {"load average": load()}
    settings = []
    if best:
        settings.append(("cheapest converged", best["method"], best.get("dt [s]", best.get("rtol [-]"))))
    settings.append(("case default (dopri5 rtol 1e-6)", "dopri5", 1e-6))
    L = cfg["long"]
    for label, method, value in settings:
        n = int(round(L / 5e-6))
        t_out = np.linspace(0.0, L, n + 1)
        t0 = time.perf_counter()
        try:
            res = run(model, y0, t_out, method, value)
        except (IntegrationError, DynamicsInputError) as exc:
            out[label] = {"method": method, "value": value, "failed": str(exc)}
            continue
        wall = time.perf_counter() - t0
        r = {"method": method, ("dt [s]" if method == "rk4" else "rtol [-]"): value, "simulated [s]": L,
             "sample interval [s]": 5e-6, "wall [s]": wall, "time / unit [-]": clock.ratio(wall),
             "simulated ms per wall second [-]": L * 1e3 / wall,
             "0.1 s of the bearing [s]": wall * 0.1 / L, "measured or extrapolated": (
                 "measured" if L >= 0.1 - 1e-12 else f"extrapolated from {L * 1e3:g} ms"), **res.stats}
        out[label] = r
        log.info("%s: %g s simulated in %.2f s (%.1f ms per wall s)", label, L, wall, L * 1e3 / wall)
    return out


# ------------------------------------------------------------------ 6. compile times
_FIRST = r"""
import json, sys, time
t0 = time.perf_counter()
import numpy as np
from lubedyn.config import load_case
from lubedyn.scenes.dynamics import build
from lubedyn.dynamics.cageless import rhs
from lubedyn.dynamics.integrators import integrate
t1 = time.perf_counter()
case = load_case(sys.argv[1])
s = build(case, sys.argv[1])
t2 = time.perf_counter()
integrate(rhs, s.y0, np.array([0.0, 1e-5]), s.model.args(), rtol=1e-6, atol=1e-9)
t3 = time.perf_counter()
integrate(rhs, s.y0, np.array([0.0, 1e-5]), s.model.args(), method="rk4", dt=1e-6)
t4 = time.perf_counter()
print(json.dumps({"import [s]": t1 - t0, "case + model + quasi-static state (compiles rhs, forces) [s]": t2 - t1,
                  "first dopri5 call [s]": t3 - t2, "first rk4 call [s]": t4 - t3, "total [s]": t4 - t0}))
"""


def bench_compile(skip_cli):
    out = {"how": ("fresh subprocesses with NUMBA_CACHE_DIR=<tmp>/numba (empty at the cold run; the same "
                   "directory again for the warm run)"), "load average": load()}
    py = sys.executable
    with tempfile.TemporaryDirectory(prefix="lubedyn-bench-cache-") as tmp:
        env = dict(os.environ, NUMBA_CACHE_DIR=str(Path(tmp) / "numba"))
        for label in ("cold", "warm"):
            t0 = time.perf_counter()
            p = subprocess.run([py, "-c", _FIRST, str(CASE)], env=env, cwd=ROOT, capture_output=True, text=True)
            wall = time.perf_counter() - t0
            r = {"process wall [s]": wall, "returncode": p.returncode}
            if p.returncode == 0:
                r.update(json.loads(p.stdout.strip().splitlines()[-1]))
            else:
                r["stderr"] = p.stderr[-2000:]
            out[f"python -c, {label}"] = r
            log.info("first call %s: %.1f s", label, wall)
        out["cache files after the runs"] = {"numba": len(list((Path(tmp) / "numba").rglob("*.nbi")))}
        if not skip_cli:
            exe = Path(py).with_name("lubedyn")
            cmd = [str(exe) if exe.exists() else "lubedyn", "run", str(SHORT_CASE), "--smoke"]
            with tempfile.TemporaryDirectory(prefix="lubedyn-bench-cli-") as tmp2:
                env2 = dict(os.environ, NUMBA_CACHE_DIR=str(Path(tmp2) / "numba"))
                for label in ("cold", "warm"):
                    t0 = time.perf_counter()
                    p = subprocess.run(cmd + ["--out", str(Path(tmp2) / f"out_{label}")], env=env2, cwd=ROOT,
                                       capture_output=True, text=True)
                    wall = time.perf_counter() - t0
                    r = {"command": " ".join(cmd[1:]) + " --out <tmp>", "wall [s]": wall,
                         "returncode": p.returncode}
                    summ = Path(tmp2) / f"out_{label}" / "summary.json"
                    if summ.is_file():
                        s = json.loads(summ.read_text())
                        r["summary: integration wall time [s]"] = s.get("Integration wall time [s]")
                        r["summary: simulated time [s]"] = s.get("Simulated time [s]")
                    if p.returncode != 0:
                        r["stderr"] = p.stderr[-2000:]
                    out[f"CLI --smoke, {label}"] = r
                    log.info("CLI %s: %.1f s (rc %d)", label, wall, p.returncode)
    return out


# ------------------------------------------------------------------ plot
def plot_equal_accuracy(ax, eq):
    """Work-precision of every method of section 4b on one axis, with the equal-error ratios."""
    styles = {"lubedyn dopri5": ("s-", "C1"), "lubedyn rk4": ("o-", "C0"),
              "lubedyn ros2 (finite-difference Jacobian)": ("D-", "C3"), "scipy RK45": ("v--", "C7"),
              "scipy DOP853": ("^--", "k"), "scipy LSODA": ("<--", "C8"), "scipy BDF": (">--", "C9"),
              "scipy Radau": ("x--", "C5")}
    for name, pts in eq["methods"].items():
        good = [p for p in pts if "failed" not in p and "ball position error at end [delta_H]" in p]
        if not good:
            continue
        mk, col = styles.get(name, ("+-", "C6"))
        ax.loglog([p["wall [s]"] for p in good], [max(p["ball position error at end [delta_H]"], 1e-12) for p in good],
                  mk, color=col, ms=4, label=name.replace(" (finite-difference Jacobian)", " (FD Jacobian)"))
    ax.axhline(POS_TOL, color="k", ls=":", lw=0.8)
    lines = []
    for tk, r in eq.get("ratio at equal error", {}).items():
        lines.append(f"error {tk} dH: {r['scipy best'].replace('scipy ', '')} / "
                     f"{r['lubedyn best'].replace('lubedyn ', '')} = {r['ratio scipy best / lubedyn best [-]']:.1f} x")
    bnd = eq.get("bound for equal rhs calls")
    if bnd:
        c = bnd["rhs call from compiled code [us]"]
        lines.append(f"same rhs calls: (c + o_scipy) / (c + o_lubedyn) = ({c:.1f} + "
                     f"{bnd['scipy RK45 overhead per call [us]']:.1f}) / ({c:.1f} + "
                     f"{bnd['lubedyn DOPRI5 overhead per call [us]']:.1f}) us = "
                     f"{bnd['ratio bound (c + o_scipy) / (c + o_lubedyn) [-]']:.1f} x")
    ax.text(0.02, 0.02, "\n".join(lines), transform=ax.transAxes, fontsize=7, va="bottom")
    ax.set_xlabel("wall [s]")
    ax.set_ylabel("ball position error at end / delta_H")
    ax.set_title(f"4. same numba rhs, every method, drop 0-{eq['window [s]'] * 1e3:g} ms: ratio at equal error",
                 fontsize=9)
    ax.legend(fontsize=6, ncol=2)


def plot(data, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(2, 3, figsize=(17, 9.5), constrained_layout=True)
    wp = data["work_precision"]
    ax = axs[0, 0]
    for method, mk, col in (("rk4", "o", "C0"), ("dopri5", "s", "C1")):
        pts = [p for p in wp["points"] if p["method"] == method and "failed" not in p]
        x = [p["wall [s]"] for p in pts]
        y = [max(p["ball position error at end [delta_H]"], 1e-12) for p in pts]
        ax.loglog(x, y, mk + "-", color=col, mfc="none", label=f"{method} ball position (open: not converged)")
        ax.loglog(x, [max(p["inner ring speed error at end [Omega_0]"], 1e-14) for p in pts], mk + ":", color=col,
                  ms=3, alpha=0.6, label=f"{method} ring speed error / Omega_0")
        for p, xi, yi in zip(pts, x, y):
            if p["converged"]:
                ax.loglog([xi], [yi], mk, color=col)
            lab = f"{p['dt [s]'] * 1e6:g} us" if method == "rk4" else f"{p['rtol [-]']:.0e}"
            ax.annotate(lab, (xi, yi), fontsize=6, xytext=(3, 3), textcoords="offset points")
    best = wp["cheapest converged"]
    if best:
        ax.loglog([best["wall [s]"]], [max(best["ball position error at end [delta_H]"], 1e-12)], "*", ms=16,
                  color="k", mfc="none", label="cheapest converged")
    ax.axhline(POS_TOL, color="k", ls=":", lw=0.8, label=f"{POS_TOL:g} delta_H (and 1e-3 Omega_0)")
    ax.axhline(SPEED_TOL, color="grey", ls=":", lw=0.6)
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("error at end (ball position / delta_H; ring speed / Omega_0)")
    ax.set_title(f"1. work-precision, drop 0-{wp['window [s]'] * 1e3:g} ms\n"
                 f"(delta_H = {wp['Hertz deflection delta_H [m]'] * 1e6:.2f} um; ref. DOPRI5 rtol "
                 f"{wp['reference']['rtol']:g})", fontsize=9)
    ax.legend(fontsize=7)

    ax = axs[0, 1]
    pr = data["predictability"]
    tt = np.asarray(pr["t [s]"]) * 1e3
    for p in pr["pairs"]:
        e = np.maximum(np.asarray(p["ball position difference [delta_H]"]), 1e-12)
        rate = p["growth rate while 1e-4 < difference < 0.3 delta_H [1/s]"]
        ax.semilogy(tt, e, "o-", ms=3, label=f"rtol {p['rtol [-]']:g} vs {pr['reference']}"
                    + (f" (growth {rate:.0f} 1/s)" if rate else ""))
    ax.axhline(POS_TOL, color="k", ls=":", lw=0.8)
    ax.axvline(wp["window [s]"] * 1e3, color="grey", ls="--", lw=0.8, label="work-precision window")
    ax2 = ax.twinx()
    ax2.plot(tt, pr["largest ball-ball normal force at the samples of the reference [N]"], color="C7", lw=0.7)
    ax2.set_ylabel("largest ball-ball force at the samples [N]", fontsize=7, color="C7")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("ball position difference / delta_H")
    ax.set_title("1b. predictability: two accurate solutions part after the first collisions", fontsize=9)
    ax.legend(fontsize=7)

    ax = axs[0, 2]
    st = data["stability"]
    rows = [r for r in st["scales"] if "failed" not in r]
    if rows:
        k = [r["contact stiffness 1.5 K_i^(2/3) Q^(1/3) [N/m]"] for r in rows]
        for method, col in (("rk4", "C0"), ("dopri5", "C1")):
            ax.loglog(k, [r[method]["largest stable dt [s]"] for r in rows], "o-", color=col,
                      label=f"{method} measured")
            ax.loglog(k, [r[method]["predicted stability_limit/omega_max [s]"] for r in rows], "--", color=col,
                      label=f"{method} stability_limit/omega_max")
        ax.loglog(k, [r["linearised at the initial state"]["linear stable step rk4 [s]"] for r in rows], "x-.",
                  color="C3", label="rk4 limit from the rhs Jacobian's eigenvalues")
        ax.loglog(k, [r["adaptive dopri5"][1]["mean accepted step [s]"] for r in rows], "^:", color="C2",
                  label="adaptive dopri5 rtol 1e-3, mean step")
        for r, ki in zip(rows, k):
            ax.annotate(f"E x{r['modulus factor [-]']:g}", (ki, r["rk4"]["largest stable dt [s]"]), fontsize=6,
                        xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("race contact stiffness at Q_max [N/m]")
    ax.set_ylabel("step [s]")
    ax.set_title(f"2. largest stable step (drop 0-{st['window [s]'] * 1e3:g} ms)", fontsize=9)
    ax.legend(fontsize=7)

    ax = axs[1, 0]
    fid = data["fidelity"]
    labels, costs, notes = [], [], []
    for group in ("steady 10,000 rpm", "drop, ball-ball film"):
        for lab, r in fid[group].items():
            labels.append(("steady: " if group.startswith("steady") else "drop: ") + lab.replace(" (integration noise)",
                                                                                                 " (noise)"))
            costs.append(r["wall per simulated ms [s]"])
            notes.append(f"{r['collisions above 1 N [-]']} coll., {r['peak collision normal force [N]']:.0f} N, "
                         f"train {r['ball-train speed, mean over balls, second half [rad/s]']:.0f} rad/s, "
                         f"orbit {r['inner ring orbit rms about its mean, second half [um]']:.2f} um")
    yy = np.arange(len(labels))
    ax.barh(yy, costs, color="C4")
    ax.set_yticks(yy)
    ax.set_yticklabels(labels, fontsize=7)
    ax.invert_yaxis()
    for yi, c, n in zip(yy, costs, notes):
        ax.text(c, yi, " " + n, va="center", fontsize=6)
    ax.set_xlim(0, max(costs) * 2.6)
    ax.set_xlabel("wall per simulated ms [s]")
    ax.set_title(f"3. fidelity: cost and answers ({fid['window [s]'] * 1e3:g} ms, DOPRI5 rtol 1e-6)", fontsize=9)

    plot_equal_accuracy(axs[1, 1], data["equal_accuracy"])

    ax = axs[1, 2]
    cp = data.get("compile", {})
    bars, vals = [], []
    for key in ("python -c, cold", "python -c, warm", "CLI --smoke, cold", "CLI --smoke, warm"):
        if key in cp:
            bars.append(key.replace("python -c", "first call"))
            vals.append(cp[key].get("process wall [s]", cp[key].get("wall [s]")))
    tp = data["throughput"]
    for lab, r in tp.items():
        if isinstance(r, dict) and "0.1 s of the bearing [s]" in r:
            bars.append(f"0.1 s drop, {lab.split(' (')[0]}")
            vals.append(r["0.1 s of the bearing [s]"])
    ax.barh(np.arange(len(bars)), vals, color="C5")
    ax.set_yticks(np.arange(len(bars)))
    ax.set_yticklabels(bars, fontsize=7)
    ax.invert_yaxis()
    for i, v in enumerate(vals):
        ax.text(v, i, f" {v:.1f} s", va="center", fontsize=7)
    ax.axvline(20.0, color="k", ls=":", lw=0.8)
    ax.set_xlabel("wall [s]")
    ax.set_title("5./6. 0.1 s of the bearing (target 20 s) and compile cold/warm", fontsize=9)
    fig.suptitle(f"lubedyn dynamics benchmark ({'quick' if data['quick'] else 'full'}), load average "
                 f"{data['machine']['load_average_at_start'][0]:.1f} at start; time unit "
                 f"{data['reference run']['median [s]'] * 1e3:.1f} ms", fontsize=10)
    _common.save_figure(fig, path)


# ------------------------------------------------------------------ main
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeats", type=int, default=None)
    ap.add_argument("--skip-cli", action="store_true")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(message)s", datefmt="%H:%M:%S")
    cfg = SIZES["quick" if args.quick else "full"]
    repeats = args.repeats or cfg["repeats"]
    t_start = time.perf_counter()
    data = {"machine": _common.machine_info(extra_packages=("numba",)), "quick": args.quick, "repeats": repeats,
            "case": f"cases/{CASE.name}", "sizes": cfg}
    setup = drop_setup()
    model, y0 = setup.model, setup.y0
    # first calls (compile or load from cache), reported, never timed as work
    t0 = time.perf_counter()
    run(model, y0, np.array([0.0, 1e-6]), "dopri5", 1e-6)
    t1 = time.perf_counter()
    run(model, y0, np.array([0.0, 1e-6]), "rk4", 1e-7)
    t2 = time.perf_counter()
    data["first calls in this process [s]"] = {"dopri5": t1 - t0, "rk4": t2 - t1}
    clock = Clock(model, y0)
    data["reference run"] = clock.describe()
    data["model"] = {"states [-]": int(y0.size), "omega_max at the initial state [rad/s]": model.omega_max(y0),
                     "rk4 stability_limit/omega_max [s]": stability_limit("rk4") / model.omega_max(y0),
                     "dopri5 stability_limit/omega_max [s]": stability_limit("dopri5") / model.omega_max(y0)}
    log.info("time unit %.4f s, rhs call %.1f us", clock.seconds, clock.rhs_call * 1e6)

    wp, ref = bench_work_precision(setup, cfg, clock, repeats)
    data["work_precision"] = wp
    ref_t = np.linspace(0.0, cfg["window"], cfg["samples"])
    data["predictability"] = bench_predictability(setup, cfg)
    data["stability"] = bench_stability(setup, cfg, ref.y, ref_t)
    data["fidelity"] = bench_fidelity(setup, cfg, repeats)
    data["scipy"] = bench_scipy(setup, cfg, ref.y, ref_t, repeats)
    data["equal_accuracy"] = bench_equal_accuracy(setup, cfg, ref.y, ref_t, repeats)
    data["throughput"] = bench_throughput(setup, cfg, wp["cheapest converged"], clock)
    data["compile"] = bench_compile(skip_cli=args.skip_cli or args.quick)
    data["reference run, again at the end"] = Clock(model, y0).describe()
    data["load average at end"] = list(os.getloadavg())
    data["benchmark wall [s]"] = time.perf_counter() - t_start
    stem = "dynamics_quick" if args.quick else "dynamics"
    _common.write_json(RESULTS / f"{stem}.json", data)
    plot(data, RESULTS / f"{stem}.png")
    print(f"wrote {RESULTS / stem}.json/.png in {data['benchmark wall [s]']:.0f} s")


if __name__ == "__main__":
    main()
