"""Methods atlas: each method swept along its stress axis, with the outcome of every point.

Writes ``benchmarks/results/method_limits.json`` and ``method_limits.png``
(``--quick``: ``method_limits_quick.*``, so a smoke run never replaces the full
numbers)::

    python benchmarks/method_limits.py           # full run (71 s measured on 2 shared cores)
    python benchmarks/method_limits.py --quick   # smaller sweeps (15 s measured)

Every point is solved in this process inside ``try/except`` and classified:

``right``
    the method finished, said nothing, and its answer is within the stated
    tolerance of the reference;
``warned``
    the method finished and warned (a-posteriori check, resolution guard,
    ...); the warning text is stored;
``refused``
    the method stopped with an error (ConvergenceError, IntegrationError,
    DynamicsInputError); the message and the stop reason are stored;
``wrong (silent)``
    the method finished without a warning but its answer is beyond the
    tolerance: the case the library must never give.  None is expected; the atlas shows
    where one would be.

Sweeps (stress axis, reference, tolerance for "right")
-------------------------------------------------------
1. EHL line contact, FEM Newton (``solve_ehl``, default method): Moes M in
   (20, 100, 300, 1000), L = 10, 129 / 257 / 513 nodes; central film against
   Moes' formula, tolerance 10 % (``lubedyn.lubrication.ehl.FORMULA_TOLERANCE``).
2. EHL circular contact, FAS multigrid: M in (20, 100, 1000), L = 10,
   129^2 / 257^2; central film against Nijenbanning-Venner-Moes, 10 %.
3. Journal bearing (cases/journal_finite.toml: L/D = 1, P2, Reynolds
   cavitation) at eccentricity 0.6 / 0.9 / 0.99 / 0.999 on 32x8 ... 128x32
   (full run: and 256x64 as the reference; quick: 128x32 is the reference);
   |load| against the finest mesh, tolerance 5 %.  Outcome from the film's
   resolution guard (``FilmSolution.resolution_warning``); the scene's other
   validity warnings (pressure, film below the roughness) are stored but do
   not count: they are about the model, not the method.
4. Linear solve: sphere-plane squeeze film (full film: one linear system per
   solve), P2 quads graded geometrically away from the contact (cell ratios
   1.0, 1.05, 1.1), 60 x 60 cells (14,641 DOFs: "auto" is SuperLU below
   ``DIRECT_SOLVER_MAX_DOFS`` = 60,000) and 125 x 125 cells (63,001 DOFs:
   "auto" probes AMG-CG and falls back): wall time of ``auto``, ``direct``
   and ``amg``; error = max |p - p_direct| / max p, tolerance 1e-6.
5. RK4 on an undamped oscillator x'' = -omega^2 x (omega = 1e5 rad/s, one
   step per output, 20 periods), bare call (no ``omega_max``: the growth
   guard alone) at h omega in (2.0, 2.7, 2.8, 2.84, 3.0, 3.5): |x|/x0 at the
   end.  The stress axis of a fixed step is stability: a completed run is
   "right" when it has not grown (|x|/x0 <= 1.5; below the limit it equals
   RK4's own amplification |R(i h omega)|^N, damped to 1e-8 at h omega = 2
   after 20 periods: the accuracy of the step the user chose, stored as
   ``amplitude``), "wrong (silent)" when it grew.  |R|^N (what an unguarded
   run would give) is stored next to it.  The same runs with ``omega_max``
   given are refused at t0 beyond 2.828.
6. DOPRI5 and ROS2 on the same oscillator (omega = 1, 10 periods) against
   rtol 1e-3 ... 1e-9 (atol = 1e-3 rtol): error of (x, v) at the end against
   the exact solution, accepted + rejected steps; tolerance 100 rtol.

Times are wall-clock seconds of one solve on this machine (noted in the
JSON, with its load average); the machine is shared, so compare ratios and
outcomes, not seconds.  Nothing here asserts a time.
"""
from __future__ import annotations

import argparse
import logging
import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import _common  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
log = logging.getLogger("benchmarks.method_limits")

EHL_TOL = 0.10
JOURNAL_TOL = 0.05
LINEAR_TOL = 1e-6
RK4_TOL = 0.5
ODE_TOL_FACTOR = 100.0


# ---------------------------------------------------------------- helpers
class _Capture(logging.Handler):
    """Collects WARNING records of the library loggers during one solve."""

    def __init__(self):
        super().__init__(level=logging.WARNING)
        self.records = []

    def emit(self, record):
        self.records.append(record.getMessage())


def _run(fn):
    """``fn()`` with the library's warnings captured; returns (seconds, result or None,
    exception or None, warning lines)."""
    cap = _Capture()
    loggers = [logging.getLogger("lubedyn")]  # the library's loggers: lubedyn.*
    for lg in loggers:
        lg.addHandler(cap)
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings(record=True) as pyw:
            warnings.simplefilter("always")
            result, exc = fn(), None
    except Exception as e:  # recorded as the point's outcome: the message is the data
        result, exc, pyw = None, e, []
    finally:
        for lg in loggers:
            lg.removeHandler(cap)
    seconds = time.perf_counter() - t0
    lines = cap.records + [f"{w.category.__name__}: {w.message}" for w in pyw]
    return seconds, result, exc, lines


def _refused(exc) -> dict:
    stop = getattr(exc, "stop", None)
    reason = stop.get("reason") if isinstance(stop, dict) else getattr(exc, "stop_reason", None)
    if reason is None and hasattr(exc, "status"):  # IntegrationError: the kernel's status
        from lubedyn.dynamics.integrators import STATUS_MESSAGES

        reason = STATUS_MESSAGES.get(exc.status)
    if reason is None and type(exc).__name__.endswith("InputError"):
        reason = "refused at input"
    return dict(outcome="refused", exception=type(exc).__name__, message=str(exc), stop_reason=reason)


def _classify(error, tol, warned):
    if warned:
        return "warned"
    return "right" if (error is not None and abs(error) <= tol) else "wrong (silent)"


def _progress(tag, row):
    err = row.get("error")
    log.info("%-8s %-40s %-15s t %.3g s  error %s", tag, row.get("label", ""), row["outcome"], row.get("time_s", 0.0),
             "-" if err is None else f"{err:+.3g}")


# ---------------------------------------------------------------- 1, 2: EHL
def _H(c, h):
    return h / c.radius_x * (2 * c.U) ** -0.5


def ehl_line(Ms, grids):
    from lubedyn.lubrication.ehl import EHLContact, EHLGrid, solve_ehl
    from lubedyn.lubrication.laws.film import moes_line_central

    rows = []
    for M in Ms:
        c = EHLContact.from_moes(M, 10.0, line=True)
        ref = float(moes_line_central(M, 10.0))
        for nx in grids:
            t, s, exc, lines = _run(lambda: solve_ehl(c, EHLGrid(nx=nx)))
            row = dict(M=M, L=10.0, nx=nx, label=f"line M={M} nx={nx}", time_s=t, reference_Hc=ref)
            if exc is not None:
                row.update(_refused(exc), error=None)
            else:
                Hc = _H(c, s.central_film_thickness)
                row.update(Hc=Hc, error=Hc / ref - 1.0, stop_reason=s.info.get("stop_reason"),
                           stop_detail=s.info.get("stop_detail"), newton_iterations=s.info.get("iterations"),
                           work=s.info.get("work"), warnings=s.info.get("warnings", []), log=lines)
                row["outcome"] = _classify(row["error"], EHL_TOL, bool(row["warnings"]))
            _progress("ehl-line", row)
            rows.append(row)
    return dict(method="EHL line contact, FEM Newton (active set)", stress_axis="Moes M (L = 10) and nodes",
                reference="Moes (1992) line formula", tolerance=EHL_TOL, points=rows)


def ehl_point_multigrid(Ms, grids):
    from lubedyn.lubrication.ehl import EHLContact, EHLGrid, EHLOptions, solve_ehl
    from lubedyn.lubrication.laws.film import nijenbanning_central

    options = EHLOptions(method="multigrid")
    # compile (or load from the cache) the multigrid's numba kernels outside the timed points
    _run(lambda: solve_ehl(EHLContact.from_moes(100, 10.0), EHLGrid(nx=33), options))
    rows = []
    for M in Ms:
        c = EHLContact.from_moes(M, 10.0)
        ref = float(nijenbanning_central(M, 10.0))
        for nx in grids:
            t, s, exc, lines = _run(lambda: solve_ehl(c, EHLGrid(nx=nx), options))
            row = dict(M=M, L=10.0, nx=nx, label=f"point MG M={M} {nx}^2", time_s=t, reference_Hc=ref)
            if exc is not None:
                row.update(_refused(exc), error=None)
            else:
                Hc = _H(c, s.central_film_thickness)
                row.update(Hc=Hc, error=Hc / ref - 1.0, stop_reason=s.info.get("stop_reason"),
                           stop_detail=s.info.get("stop_detail"), cycles=s.info.get("cycles"),
                           work_units=s.info.get("work_units"), warnings=s.info.get("warnings", []), log=lines,
                           coarse_level=s.info.get("checks", {}).get("coarse_level"))
                row["outcome"] = _classify(row["error"], EHL_TOL, bool(row["warnings"]))
            _progress("ehl-mg", row)
            rows.append(row)
    return dict(method="EHL circular contact, FAS multigrid", stress_axis="Moes M (L = 10) and nodes",
                reference="Nijenbanning, Venner & Moes (1994)", tolerance=EHL_TOL, points=rows)


# ---------------------------------------------------------------- 3: journal
def journal(eccentricities, meshes, reference_mesh):
    from lubedyn.scenes import film as film_scene
    from lubedyn.config import CASES_DIR, load_case

    case_file = CASES_DIR / "journal_finite.toml"

    def solve(eps, nx, ny):
        case = load_case(case_file, overrides=[f"gap.eccentricity_ratio={eps}", f"mesh.nx={nx}", f"mesh.ny={ny}"])
        return film_scene.run(case)

    rows = []
    for eps in eccentricities:
        series = []
        for nx, ny in list(meshes) + ([reference_mesh] if reference_mesh not in meshes else []):
            t, run, exc, lines = _run(lambda: solve(eps, nx, ny))
            row = dict(eccentricity=eps, mesh=f"{nx}x{ny}", nx=nx, ny=ny, label=f"journal eps={eps} {nx}x{ny}",
                       time_s=t, is_reference=(nx, ny) == tuple(reference_mesh))
            if exc is not None:
                row.update(_refused(exc), error=None)
            else:
                sol = run.solution
                warn = [w for w in run.summary.get("Warnings", []) if w.startswith("Minimum-gap zone")]
                row.update(load=float(np.hypot(*sol.load_vector[:2])), min_gap_elements=sol.min_gap_elements(),
                           dofs=run.summary.get("Degrees of freedom [-]"), stop_reason=run.summary.get("Stop reason"),
                           warnings=warn, other_warnings=[w for w in run.summary.get("Warnings", []) if w not in warn])
            series.append(row)
        ref = next((r for r in series if r["is_reference"] and "load" in r), None)
        for row in series:
            if "load" in row:
                row["reference_load"] = ref["load"] if ref else None
                row["error"] = row["load"] / ref["load"] - 1.0 if ref else None
                row["outcome"] = _classify(row["error"], JOURNAL_TOL, bool(row["warnings"]))
            _progress("journal", row)
        rows += series
    return dict(method="Journal bearing, Reynolds FEM (P2, Reynolds cavitation)",
                stress_axis="eccentricity ratio and mesh", reference=f"finest mesh {reference_mesh[0]}x"
                f"{reference_mesh[1]} P2 at the same eccentricity", tolerance=JOURNAL_TOL, points=rows)


# ---------------------------------------------------------------- 4: linear solve
def _geometric_axis(half, n, ratio):
    """2 n cells on [-half, half], the smallest at 0, each ``ratio`` times the previous outwards."""
    w = ratio ** np.arange(n)
    x = np.concatenate([[0.0], np.cumsum(w)]) / np.sum(w) * half
    return np.concatenate([-x[::-1], x[1:]])


def linear_solve(ratios, half_cells):
    from lubedyn.lubrication import Lubricant, SpherePlane
    from lubedyn.lubrication import mesh as lmesh
    from lubedyn.lubrication.reynolds import DIRECT_SOLVER_MAX_DOFS, Film, SolverOptions

    rows = []
    for n in half_cells:
        for ratio in ratios:
            xs = _geometric_axis(1e-3, n, ratio)
            film = Film(lmesh.rectangle(xs, xs), SpherePlane(10e-3, 1e-6), Lubricant.newtonian(0.01), squeeze=-1e-3,
                        element="P2")
            direct = None
            for solver in ("direct", "auto", "amg"):
                f = film.with_(options=SolverOptions(linear_solver=solver))
                t, s, exc, lines = _run(f.solve)
                row = dict(ratio=ratio, cells=2 * n, solver=solver, label=f"linear {solver} ratio={ratio} {2 * n}^2",
                           time_s=t)
                if exc is not None:
                    row.update(_refused(exc), error=None)
                else:
                    if solver == "direct":
                        direct = s
                    row.update(dofs=int(s.basis.N), linear_solver=s.info.get("linear_solver"),
                               stop_reason=s.info.get("stop reason"), newton_iterations=s.info.get("iterations"),
                               load=float(s.load), log=lines)
                    row["error"] = (float(np.max(np.abs(s.pressure - direct.pressure)) / direct.p_max)
                                    if direct is not None else None)
                    # an AMG-CG that stops short of amg_tol logs a WARNING: that is its "warned"
                    row["warnings"] = [w for w in lines if "AMG-CG stopped" in w]
                    row["outcome"] = _classify(row["error"], LINEAR_TOL, bool(row["warnings"]))
                _progress("linear", row)
                rows.append(row)
    return dict(method="Reynolds linear solve (full film, one system)",
                stress_axis="mesh grading ratio and DOFs", reference="SuperLU (linear_solver = 'direct')",
                tolerance=LINEAR_TOL, direct_solver_max_dofs=DIRECT_SOLVER_MAX_DOFS, points=rows)


# ---------------------------------------------------------------- 5, 6: integrators
def _oscillator_rhs():
    from numba import njit

    @njit
    def oscillator(t, y, args, dydt):
        dydt[0] = y[1]
        dydt[1] = -args[0] * args[0] * y[0]

    return oscillator


def rk4_oscillator(h_omegas, periods=20):
    from lubedyn.dynamics.integrators import STABILITY_POLYNOMIALS, integrate, stability_limit

    rhs = _oscillator_rhs()
    omega = 1e5
    limit = stability_limit("rk4", "imaginary")
    _run(lambda: integrate(rhs, [1.0, 0.0], np.array([0.0, 1e-6]), (omega,), method="rk4", dt=1e-6))  # compile
    rows = []
    for ho in h_omegas:
        h = ho / omega
        n = int(round(periods * 2 * math.pi / ho))
        t_out = np.arange(n + 1) * h
        unguarded = float(abs(np.polynomial.Polynomial(STABILITY_POLYNOMIALS["rk4"])(1j * ho)) ** n)
        for mode, kw in (("bare call (growth guard)", {}), ("omega_max given", dict(omega_max=omega))):
            t, res, exc, lines = _run(lambda: integrate(rhs, [1.0, 0.0], t_out, (omega,), method="rk4",
                                                        dt=h * (1 + 1e-13), **kw))
            row = dict(h_omega=ho, mode=mode, steps=n, label=f"rk4 h*omega={ho} {mode}", time_s=t,
                       stability_limit=limit, unguarded_amplitude=unguarded)
            if exc is not None:
                row.update(_refused(exc), error=None, status=getattr(exc, "status", None))
                y = getattr(exc, "y", None)
                if y is not None and len(y):
                    row["amplitude_at_stop"] = float(np.max(np.hypot(y[:, 0], y[:, 1] / omega)))
                    row["t_reached"] = float(exc.t_reached)
            else:
                amp = float(np.hypot(res.y[-1, 0], res.y[-1, 1] / omega))
                row.update(amplitude=amp, error=amp - 1.0, stop_reason=res.stats.get("Integrator stop reason"),
                           largest_h_lambda=res.stats.get("Largest estimated h*|lambda| (RK4) [-]"),
                           discrete_amplitude_error=amp / unguarded - 1.0)
                # stable: the amplitude is RK4's own |R|^N (damped, the accuracy of the chosen step); a growth
                # the oscillator does not have is the silent wrong answer
                row["outcome"] = "right" if amp <= 1.0 + RK4_TOL else "wrong (silent)"
            _progress("rk4", row)
            rows.append(row)
    return dict(method="RK4, fixed step", stress_axis="h omega (undamped oscillator, 20 periods)",
                reference="exact amplitude 1", tolerance=RK4_TOL, points=rows)


def adaptive_oscillator(rtols, periods=10):
    from lubedyn.dynamics.integrators import integrate

    rhs = _oscillator_rhs()
    omega = 1.0
    T = periods * 2 * math.pi
    t_out = np.array([0.0, T])
    exact = np.array([math.cos(omega * T), -omega * math.sin(omega * T)])
    rows = []
    for method in ("dopri5", "ros2"):
        _run(lambda: integrate(rhs, [1.0, 0.0], t_out, (omega,), method=method, rtol=1e-3, atol=1e-6))  # compile
        for rtol in rtols:
            t, res, exc, lines = _run(lambda: integrate(rhs, [1.0, 0.0], t_out, (omega,), method=method, rtol=rtol,
                                                        atol=1e-3 * rtol))
            row = dict(method=method, rtol=rtol, label=f"{method} rtol={rtol:.0e}", time_s=t)
            if exc is not None:
                row.update(_refused(exc), error=None)
            else:
                err = float(np.max(np.abs(res.y[-1] - exact)))
                row.update(error=err, accepted=res.stats["Accepted steps [-]"], rejected=res.stats["Rejected steps [-]"],
                           rhs_evaluations=res.stats["RHS evaluations [-]"],
                           stop_reason=res.stats.get("Integrator stop reason"))
                row["outcome"] = "right" if err <= ODE_TOL_FACTOR * rtol else "wrong (silent)"
            _progress(method, row)
            rows.append(row)
    return dict(method="DOPRI5 and ROS2, adaptive", stress_axis="rtol (atol = 1e-3 rtol), oscillator omega = 1, "
                "10 periods", reference="exact solution", tolerance=f"{ODE_TOL_FACTOR:g} rtol", points=rows)


# ---------------------------------------------------------------- chart
MARKERS = {"right": ("o", "tab:green"), "warned": ("^", "tab:orange"), "refused": ("X", "tab:red"),
           "wrong (silent)": ("s", "black")}


def _panel(ax, title, groups, xkey, xlabel, ylabel, tol=None, xlog=False, ylog=True, error=abs, ykey="error",
           twin=True):
    """One method: error (markers by outcome, a line per group) and time (grey, right axis; with
    ``twin=False`` the time is the plotted value itself, ``ykey="time_s"``)."""
    tax = ax.twinx() if twin else None
    styles = ["-", "--", ":", "-."]
    for i, (name, pts, *look) in enumerate(groups):
        style, colour = look if look else (styles[i % 4], "tab:blue")
        pts = sorted(pts, key=lambda r: r[xkey])
        xs = [r[xkey] for r in pts]
        ys = [error(r[ykey]) if r.get(ykey) is not None and r["outcome"] != "refused" else np.nan for r in pts]
        ax.plot(xs, ys, style, color=colour, lw=0.9, label=name)
        for r, x, y in zip(pts, xs, ys):
            m, c = MARKERS[r["outcome"]]
            if not np.isfinite(y):  # refused: drawn at the panel's top edge
                ax.plot([x], [0.97], m, color=c, ms=8, transform=ax.get_xaxis_transform())
            else:
                ax.plot([x], [y], m, color=c, ms=7, mec="k", mew=0.4)
        if tax is not None:
            tax.plot(xs, [r["time_s"] for r in pts], style, color="0.6", lw=0.8, marker=".", ms=3)
    if tol is not None:
        ax.axhline(tol, color="tab:red", lw=0.6, ls=":")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(xlabel, fontsize=8)
    ax.set_ylabel(ylabel, fontsize=8)
    if tax is not None:
        tax.set_ylabel("wall time [s] (grey)", fontsize=7, color="0.4")
        tax.tick_params(which="both", labelsize=6, colors="0.4")
        tax.set_yscale("log")
    if xlog:
        ax.set_xscale("log")
    if ylog:
        ax.set_yscale("log")
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=6, loc="lower right" if ylog else "best")


def plot(data, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    fig, axes = plt.subplots(2, 3, figsize=(15, 8.5))
    s = data["sweeps"]

    def by(points, key, fmt):
        keys = sorted({p[key] for p in points}, key=lambda k: (str(type(k)), k))
        return [(fmt(k), [p for p in points if p[key] == k]) for k in keys]

    if "ehl_line" in s:
        _panel(axes[0, 0], "EHL line, FEM Newton, L = 10", by(s["ehl_line"]["points"], "nx", lambda k: f"{k} nodes"),
               "M", "Moes M", "|h_c / Moes - 1|", tol=EHL_TOL, xlog=True)
    if "ehl_point_multigrid" in s:
        _panel(axes[0, 1], "EHL circle, FAS multigrid, L = 10",
               by(s["ehl_point_multigrid"]["points"], "nx", lambda k: f"{k}^2"), "M", "Moes M", "|h_c / NVM - 1|",
               tol=EHL_TOL, xlog=True)
    if "journal" in s:
        pts = [p for p in s["journal"]["points"] if not p["is_reference"]]
        _panel(axes[0, 2], "Journal L/D = 1, P2 (ref.: finest mesh)",
               [(f"{r[0]['mesh']}", r) for _, r in by(pts, "nx", str)], "eccentricity",
               "eccentricity ratio", "|load / load_ref - 1|", tol=JOURNAL_TOL,
               error=lambda e: max(abs(e), 1e-6))
        axes[0, 2].set_xscale("function", functions=(lambda x: -np.log10(1.0 - np.minimum(x, 0.9999)),
                                                     lambda y: 1.0 - 10.0 ** (-y)))
        axes[0, 2].set_xticks([0.6, 0.9, 0.99, 0.999])
    if "linear_solve" in s:
        pts = s["linear_solve"]["points"]
        colours = {"direct": "tab:blue", "auto": "tab:purple", "amg": "tab:brown"}
        groups = [(f"{solver}, {pts_c[0]['dofs']} DOFs", [p for p in pts_c if p["solver"] == solver],
                   ("-", "--", ":")[k % 3], colours[solver])
                  for k, c in enumerate(sorted({p["cells"] for p in pts}))
                  for pts_c in [[p for p in pts if p["cells"] == c and "dofs" in p]]
                  for solver in ("direct", "auto", "amg")]
        _panel(axes[1, 0], "Linear solve, graded P2 sphere film (outcome vs SuperLU, 1e-6)", groups, "ratio",
               "cell grading ratio", "wall time of the solve [s]", error=lambda t: t, ykey="time_s", twin=False)
    if "rk4" in s:
        _panel(axes[1, 1], "RK4 fixed step, undamped oscillator, 20 periods",
               by(s["rk4"]["points"], "mode", str), "h_omega", "h omega", "|x|/x0 at the end (exact: 1)",
               tol=1.0 + RK4_TOL, error=lambda e: max(1.0 + e, 1e-16))
        axes[1, 1].axvline(s["rk4"]["points"][0]["stability_limit"], color="k", lw=0.6, ls="--")
    if "adaptive" in s:
        _panel(axes[1, 2], "DOPRI5 / ROS2, oscillator, 10 periods", by(s["adaptive"]["points"], "method", str),
               "rtol", "rtol", "error at the end", xlog=True)
        axes[1, 2].invert_xaxis()
    handles = [Line2D([], [], ls="", marker=m, color=c, mec="k", mew=0.4, label=k) for k, (m, c) in MARKERS.items()]
    handles.append(Line2D([], [], color="0.6", marker=".", label="wall time (right axis)"))
    fig.legend(handles=handles, loc="lower center", ncol=5, fontsize=8)
    m = data["machine"]
    fig.suptitle(f"Methods atlas: error and time along each method's stress axis; {m['cpu'].get('model name')}"
                 f", {m['cpus_available_to_process']} cores, load {m['load_average_at_start'][0]:.1f} at start"
                 + (" (quick)" if data.get("quick") else ""), fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.96))
    _common.save_figure(fig, path)
    plt.close(fig)
    return path


# ---------------------------------------------------------------- main
SIZES = {
    "quick": dict(line_M=(100, 1000), line_nx=(257, 513), mg_M=(100, 1000), mg_nx=(129,),
                  journal_eps=(0.6, 0.999), journal_meshes=((32, 8), (64, 16)), journal_ref=(128, 32),
                  lin_ratios=(1.0, 1.1), lin_half=(30,), rk4=(2.0, 2.8, 3.0, 3.5), rtols=(1e-3, 1e-6, 1e-9)),
    "full": dict(line_M=(20, 100, 300, 1000), line_nx=(129, 257, 513), mg_M=(20, 100, 1000), mg_nx=(129, 257),
                 journal_eps=(0.6, 0.9, 0.99, 0.999), journal_meshes=((32, 8), (64, 16), (128, 32)),
                 journal_ref=(256, 64), lin_ratios=(1.0, 1.05, 1.1), lin_half=(30, 63),
                 rk4=(2.0, 2.7, 2.8, 2.84, 3.0, 3.5), rtols=(1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)),
}


def summary_table(data) -> list:
    """One row per point: sweep, label, outcome, error, time (what README's table is drawn from)."""
    out = []
    for name, sweep in data["sweeps"].items():
        for p in sweep["points"]:
            out.append(dict(sweep=name, point=p["label"], outcome=p["outcome"], error=p.get("error"),
                            time_s=p["time_s"], stop_reason=p.get("stop_reason")))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller sweeps (about a minute)")
    ap.add_argument("--replot", action="store_true", help="redraw the PNG from the stored JSON (no solves)")
    ap.add_argument("--only", nargs="+", default=None,
                    choices=("ehl_line", "ehl_point_multigrid", "journal", "linear_solve", "rk4", "adaptive"),
                    help="run these sweeps only (the stored others are kept)")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.WARNING, format="%(message)s")
    log.setLevel(logging.INFO)
    logging.getLogger("lubedyn").propagate = False  # the library's warnings are captured per point, not printed
    stem = "method_limits_quick" if args.quick else "method_limits"
    if args.replot:
        import json

        return plot(json.loads((RESULTS / f"{stem}.json").read_text()), RESULTS / f"{stem}.png")
    z = SIZES["quick" if args.quick else "full"]
    data = dict(machine=_common.machine_info(extra_packages=("numba",)), quick=args.quick, sizes=z, sweeps={})
    if args.only:
        import json

        old = RESULTS / f"{stem}.json"
        if old.exists():
            prev = json.loads(old.read_text())
            data["sweeps"] = {k: v for k, v in prev.get("sweeps", {}).items() if k not in args.only}
            data["machine_previous_sweeps"] = prev.get("machine")
    jobs = {
        "ehl_line": lambda: ehl_line(z["line_M"], z["line_nx"]),
        "ehl_point_multigrid": lambda: ehl_point_multigrid(z["mg_M"], z["mg_nx"]),
        "journal": lambda: journal(z["journal_eps"], z["journal_meshes"], z["journal_ref"]),
        "linear_solve": lambda: linear_solve(z["lin_ratios"], z["lin_half"]),
        "rk4": lambda: rk4_oscillator(z["rk4"]),
        "adaptive": lambda: adaptive_oscillator(z["rtols"]),
    }
    t0 = time.perf_counter()
    for name, job in jobs.items():
        if args.only and name not in args.only:
            continue
        t = time.perf_counter()
        data["sweeps"][name] = job()
        data["sweeps"][name]["sweep_time_s"] = time.perf_counter() - t
        data["table"] = summary_table(data)
        _common.write_json(RESULTS / f"{stem}.json", data)  # after every sweep: a long run leaves partial results
    data["total_time_s"] = time.perf_counter() - t0
    data["load_average_at_end"] = list(__import__("os").getloadavg())
    data["table"] = summary_table(data)
    _common.write_json(RESULTS / f"{stem}.json", data)
    plot(data, RESULTS / f"{stem}.png")
    counts = {}
    for row in data["table"]:
        counts[row["outcome"]] = counts.get(row["outcome"], 0) + 1
    log.info("outcomes: %s; %.0f s in all; %s", counts, data["total_time_s"], RESULTS / f"{stem}.json")
    return data


if __name__ == "__main__":
    main()
