"""Film maps: speed against accuracy.

1. Cost of one interpolation query inside a numba loop (``lubedyn.dynamics.interp``):
   1, 2, 3 axes; multilinear, sequential monotone cubic (pchip), cubic
   Hermite on precomputed PCHIP node slopes (hermite) and the same interpolant
   stored as per-cell polynomial coefficients (hermite-cells); value only and value
   + gradient; random queries (cell search by a guess plus bisection, branch
   mispredictions) and a sweep of neighbouring queries (what an integrator
   does).  Wall-clock median, and minimum thread CPU time (robust on a shared
   machine), of repeats of 200,000 queries, ns per query.
   ``--query-only`` runs only this section (one core, about a minute).
   1b. ``--fixed-options``: the map options (axis scales, method, mode) as compile-time constants
   (issue 42, decision 7) against runtime ones, interleaved: the 3-D hermite value + gradient query,
   the bearing's polar film read on the bundled map, and the cold compile of the cage-less
   right-hand side in a child process, the README main job's integration (:func:`fixed_options_cost`).
2. Map resolution against interpolation error against build time:
   - the analytic rigid isoviscous sphere-sphere squeeze film
     F = 6 pi eta R_eff^2 v D^2/(h (h + D)^2) (exact reference, cheap), nodes
     per axis doubled;
   - the real ``ball_ball`` kind (``lubedyn.film_points``) at three grid
     resolutions, errors against direct solves at random off-grid points
     (median and maximum relative error), build time on the usable cores.
3. Build time of the default ball-to-ball map on 2 cores (and the time per
   point with 1 and 2 workers on the same points).

``python benchmarks/maps.py [--quick]`` -> ``results/maps{_quick}.json`` and ``.png``.
``--quick`` skips the real kind's builds beyond its smoke map (< 1 min).
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the benchmarks package
from benchmarks import _common, interp_cells  # noqa: E402
from lubedyn import maps  # noqa: E402
from lubedyn.dynamics import contacts, interp  # noqa: E402

GAP, SPEED = "Central gap [m]", "Approach speed [m/s]"
HERMITE_CELLS = interp_cells.HERMITE_CELLS


# ---------------------------------------------------------------- analytic kind
def squeeze_params():
    return {"radius": 4.7625e-3, "viscosity": 0.05, "film_radius": 0.3e-3}


def squeeze_exact(params, h, v):
    r_eff = params["radius"] / 2
    D = params["film_radius"] ** 2 / (2 * r_eff)
    return 6 * math.pi * params["viscosity"] * r_eff**2 * v * D**2 / (h * (h + D) ** 2)


def squeeze_evaluate(params, point):
    return {"Force [N]": squeeze_exact(params, point[GAP], point[SPEED])}


class _Axis:
    def __init__(self, name, lo, hi, n, scale):
        self.name, self.lo, self.hi, self.n, self.scale = name, lo, hi, n, scale


class _Kind:
    name = "bench_squeeze"
    description = "rigid isoviscous sphere-sphere squeeze (closed form)"
    axes = (_Axis(GAP, 1e-7, 1e-5, 9, "log"), _Axis(SPEED, 1e-3, 1e-1, 3, "log"))
    outputs = ("Force [N]",)
    evaluate = staticmethod(squeeze_evaluate)
    default_params = staticmethod(squeeze_params)
    field = None


# ---------------------------------------------------------------- 1. query cost
def _cpu_min(fn, repeats):
    """Minimum thread CPU time of ``fn()`` over ``repeats`` runs: time the thread spent descheduled
    (other jobs on a shared machine) is not counted, unlike the wall-clock median."""
    best = math.inf
    for _ in range(max(1, repeats)):
        t0 = time.thread_time()
        fn()
        best = min(best, time.thread_time() - t0)
    return best


def query_cost(repeats=5, n=200_000):
    rng = np.random.default_rng(0)
    nodes = [np.geomspace(5e-8, 5e-5, 19), np.linspace(-0.2, 0.9, 12), np.linspace(0.0, 0.05, 3)]
    logs = (1, 0, 0)
    axes = [interp.prepare_axis(x, l) for x, l in zip(nodes, logs)]
    V = rng.normal(size=(19, 12, 3)).cumsum(axis=0)
    counter = np.zeros(1, np.int64)
    rand = np.stack([np.exp(rng.uniform(np.log(5e-8), np.log(5e-5), n)), rng.uniform(-0.2, 0.9, n),
                     rng.uniform(0, 0.05, n)], axis=1)
    s = np.linspace(0, 1, n)
    sweep = np.stack([np.exp(np.log(5e-8) + s * (np.log(5e-5) - np.log(5e-8))), -0.2 + 1.1 * s, 0.05 * s], axis=1)
    out = []
    for nd in (1, 2, 3):
        vals = np.ascontiguousarray(V[(slice(None),) * nd + (0,) * (3 - nd)])
        deriv = interp.hermite_data(tuple(axes[:nd]), vals)
        methods = [(interp.LINEAR, "linear"), (interp.PCHIP, "pchip"), (interp.HERMITE, "hermite")]
        cells = interp_cells.hermite_cells_data(tuple(axes[:nd]), deriv)
        methods.append((HERMITE_CELLS, "hermite-cells"))
        for method, mname in methods:
            for qname, q in (("random", rand), ("sweep", sweep)):
                pts = np.ascontiguousarray(q[:, :nd])
                x0 = np.ascontiguousarray(pts[:, 0])

                def value():
                    if method == HERMITE_CELLS:
                        if nd == 1:
                            return interp_cells.csum1(axes[0], 1, cells, 0, x0, 0, counter)
                        if nd == 2:
                            return interp_cells.csum2(axes[0], axes[1], 1, 0, cells, 0, pts, 0, counter)
                        return interp_cells.csum3(axes[0], axes[1], axes[2], 1, 0, 0, cells, 0, pts, 0, counter)
                    if method == interp.HERMITE:
                        if nd == 1:
                            return interp_cells.hsum1(axes[0], 1, deriv, 0, x0, 0, counter)
                        if nd == 2:
                            return interp_cells.hsum2(axes[0], axes[1], 1, 0, deriv, 0, pts, 0, counter)
                        return interp_cells.hsum3(axes[0], axes[1], axes[2], 1, 0, 0, deriv, 0, pts, 0, counter)
                    if nd == 1:
                        return interp_cells.sum1(axes[0], 1, vals, 0, method, x0, 0, counter)
                    if nd == 2:
                        return interp_cells.sum2(axes[0], axes[1], 1, 0, vals, 0, method, pts, 0, counter)
                    return interp_cells.sum3(axes[0], axes[1], axes[2], 1, 0, 0, vals, 0, method, pts, 0, counter)

                def grad():
                    if method == HERMITE_CELLS:
                        interp_cells.evaluate_cells(tuple(axes[:nd]), logs[:nd], cells, 0, pts, 0, counter, grad=True)
                        return
                    data = deriv if method == interp.HERMITE else vals
                    interp.evaluate(tuple(axes[:nd]), logs[:nd], data, 0, method, pts, 0, counter, grad=True)

                def grad_inside():
                    """value and gradient consumed in a numba loop (3-D), as the dynamics kernels use a query"""
                    if method == HERMITE_CELLS:
                        return interp_cells.cgsum3(axes[0], axes[1], axes[2], 1, 0, 0, cells, 0, pts, 0, counter)
                    if method == interp.HERMITE:
                        return interp_cells.hgsum3(axes[0], axes[1], axes[2], 1, 0, 0, deriv, 0, pts, 0, counter)
                    return interp_cells.gsum3(axes[0], axes[1], axes[2], 1, 0, 0, vals, 0, method, pts, 0, counter)

                value()
                grad()  # compile
                t_val, all_val, _ = _common.timed(value, repeats)
                t_grad, all_grad, _ = _common.timed(grad, repeats)
                cpu_val, cpu_grad = _cpu_min(value, repeats), _cpu_min(grad, repeats)
                row = {"axes": nd, "method": mname, "queries": qname, "ns per value query": t_val / n * 1e9,
                       "ns per value+gradient query (with output stores)": t_grad / n * 1e9,
                       "min thread CPU ns per value query": cpu_val / n * 1e9,
                       "min thread CPU ns per value+gradient query": cpu_grad / n * 1e9}
                inside = ""
                if nd == 3:
                    grad_inside()  # compile
                    t_in, _, _ = _common.timed(grad_inside, repeats)
                    cpu_in = _cpu_min(grad_inside, repeats)
                    row["ns per value+gradient query inside numba"] = t_in / n * 1e9
                    row["min thread CPU ns per value+gradient query inside numba"] = cpu_in / n * 1e9
                    inside = f"; inside numba {t_in / n * 1e9:6.1f} wall median, {cpu_in / n * 1e9:6.1f} CPU min"
                out.append(row)
                print(f"query {nd}-D {mname:13s} {qname:6s}: value {t_val / n * 1e9:7.1f} ns wall median, "
                      f"{cpu_val / n * 1e9:6.1f} CPU min; value+grad {t_grad / n * 1e9:7.1f} wall median, "
                      f"{cpu_grad / n * 1e9:6.1f} CPU min{inside}", flush=True)
    return out


# ---------------------------------------------------------------- 1b. fixed map options (issue 42, decision 7)
@njit(cache=True)
def _polar_reads(h, v, ue, p, ax0, ax1, ax2, vals, opts, counter):
    """The bearing's film read (``lubedyn.dynamics.contacts._film_map``) at every point, summed."""
    s = 0.0
    for q in range(h.size):
        f, d = contacts._film_map(h[q], v[q], ue[q], p, ax0, ax1, ax2, vals, opts, counter)
        s += f + d
    return s


def _bundled_polar_model():
    """Paper B's bearing with the bundled polar ball-ball map, as ``tests/test_polar_film_map.py`` builds it."""
    from lubedyn import film_points as fp
    from lubedyn.config import CASES_DIR
    from lubedyn.papers.zhang2024.parameters import cageless_bearing

    fmap = maps.FilmMap.load(CASES_DIR / "maps" / "ball_ball.npz")
    params = fmap.provenance.get("params") or fp.ball_ball_default_params()
    return cageless_bearing(films=dict(ball_ball="map", map=fmap.dynamics_film_map(), viscosity=float(params["eta0"]),
                                       pressure_viscosity=float(params["alpha"])))


def compile_probe(variant):
    """Child process of :func:`fixed_options_cost`: compile the cage-less right-hand side with the bundled map
    (empty numba cache: what a first CLI run compiles), with the map options as a runtime int64 array
    (``"array"``, before) or fixed (``"fixed"``, after); print the compile record as JSON."""
    import json

    from lubedyn.compilation import report_compilation
    from lubedyn.dynamics.cageless import kernels

    model = _bundled_polar_model()
    args = model.args()
    if variant == "array":
        args = args._replace(film_map=args.film_map._replace(opts=np.array(args.film_map.opts, dtype=np.int64)))
    y0 = model.initial_state(settle=False)
    dydt = np.empty_like(y0)
    c0 = time.process_time()
    with report_compilation() as record:
        kernels.rhs(0.0, y0, args, dydt)
    record["process CPU [s]"] = time.process_time() - c0
    record["signature"] = str(kernels.rhs.signatures[-1])[:400]
    print(json.dumps(record))


def fixed_options_cost(alternations=60, n=200_000, compile_rounds=2):
    """Decision 7 of issue 42: the map options (axis scales ...) as compile-time constants.

    Before/after single timings alternating in one process, ``alternations`` pairs: (a) the 3-D hermite value + gradient
    query consumed in a numba loop (as section 1's "inside numba", runtime int flags against
    :class:`lubedyn.dynamics.interp.Fixed` flags); (b) the bearing's polar film read on the bundled map
    (``contacts._film_map``: conversion to (gap, rho, theta), the query, the chain rule) at 4,096 random
    states, options as the int64 array against the fixed tuple the model now passes.  Thread CPU ns per
    query: minimum, 10th percentile and median of each, and the median of the pairs' ratios after/before
    (this VM's timings are bimodal under load: the pairs see the same state).  (c) The cold
    compile of the cage-less right-hand side with that map in a child process with an empty numba cache
    (numba's compile events, :func:`lubedyn.compilation.report_compilation`), before and after,
    alternating, ``compile_rounds`` times.  (d) The README main job's integration with both kinds of options
    (:func:`integration_cost`).  Results equal bit for bit are checked on the way."""
    import json
    import os
    import subprocess
    import tempfile

    rng = np.random.default_rng(0)
    nodes = [np.geomspace(5e-8, 5e-5, 19), np.linspace(-0.2, 0.9, 12), np.linspace(0.0, 0.05, 3)]
    logs = (1, 0, 0)
    axes = [interp.prepare_axis(x, l) for x, l in zip(nodes, logs)]
    deriv = interp.hermite_data(tuple(axes), rng.normal(size=(19, 12, 3)).cumsum(axis=0))
    pts = np.stack([np.exp(rng.uniform(np.log(5e-8), np.log(5e-5), n)), rng.uniform(-0.2, 0.9, n),
                    rng.uniform(0, 0.05, n)], axis=1)
    counter = np.zeros(1, np.int64)
    flags = {"runtime": (1, 0, 0, 0), "fixed": interp.fixed_options((1, 0, 0, 0))}

    def query(kind):
        l0, l1, l2, lv = flags[kind]
        return lambda: interp_cells.hgsum3(axes[0], axes[1], axes[2], l0, l1, l2, deriv, lv, pts, 0, counter)

    model = _bundled_polar_model()
    args = model.args()
    ma, p = args.film_map, args.bbp[0]
    m = 4096
    h = np.exp(rng.uniform(np.log(math.exp(ma.ax0[0])), np.log(math.exp(ma.ax0[-1])), m))
    v = rng.uniform(-0.05, 1.0, m)
    ue = rng.uniform(0.0, 5.0, m)
    opts = {"runtime": np.array(ma.opts, dtype=np.int64), "fixed": ma.opts}

    def polar(kind):
        return lambda: _polar_reads(h, v, ue, p, ma.ax0, ma.ax1, ma.ax2, ma.values, opts[kind], counter)

    out = {"query points": n, "film-read states": m, "alternations": alternations}
    same_query = query("runtime")() == query("fixed")()  # (compiles both)
    same_polar = polar("runtime")() == polar("fixed")()
    out["bit-identical sums (query, film read)"] = [bool(same_query), bool(same_polar)]
    reps = 20  # the film reads are short: 20 passes per timing
    per = {"query": n, "film read": reps * m}
    runs = {(what, kind): [] for what in per for kind in ("runtime", "fixed")}
    for r in range(alternations):  # single timings alternating before/after: the pairs share the machine's state
        for kind in (("runtime", "fixed") if r % 2 == 0 else ("fixed", "runtime")):
            fq, fp = query(kind), polar(kind)
            t0 = time.thread_time()
            fq()
            t1 = time.thread_time()
            for _ in range(reps):
                fp()
            t2 = time.thread_time()
            runs[("query", kind)].append((t1 - t0) / n * 1e9)
            runs[("film read", kind)].append((t2 - t1) / per["film read"] * 1e9)
    for what in per:
        rt, fx = np.array(runs[(what, "runtime")]), np.array(runs[(what, "fixed")])
        row = {"thread CPU ns, runtime options (before)": {"min": rt.min(), "10th percentile": np.percentile(rt, 10),
                                                            "median": np.median(rt)},
               "thread CPU ns, fixed options (after)": {"min": fx.min(), "10th percentile": np.percentile(fx, 10),
                                                        "median": np.median(fx)},
               "after/before, median of the pairs": float(np.median(fx / rt)),
               "after/before, 10th-90th percentile of the pairs": [float(np.percentile(fx / rt, 10)),
                                                                    float(np.percentile(fx / rt, 90))],
               "runs [ns]": {"runtime": rt.tolist(), "fixed": fx.tolist()}}
        out[what] = row
        print(f"{what}: before min {rt.min():.1f} / median {np.median(rt):.1f} ns, after min {fx.min():.1f} / "
              f"median {np.median(fx):.1f} ns, paired ratio {np.median(fx / rt):.3f}", flush=True)
    out["main job integration"] = integration_cost()
    out["compile"] = []
    for r in range(compile_rounds):
        for variant in (("array", "fixed") if r % 2 == 0 else ("fixed", "array")):
            with tempfile.TemporaryDirectory() as cache:
                env = dict(os.environ, NUMBA_CACHE_DIR=cache, LUBEDYN_BACKGROUND_COMPILE="0")
                res = subprocess.run([sys.executable, __file__, "--compile-probe", variant], env=env,
                                     capture_output=True, text=True, check=True)
            rec = json.loads(res.stdout.strip().splitlines()[-1])
            rec["variant"] = variant
            out["compile"].append(rec)
            print(f"cold compile of rhs ({variant}): {rec['Compile time [s]']:.1f} s, "
                  f"{rec['process CPU [s]']:.1f} s CPU", flush=True)
    return out


def integration_cost(rounds=8):
    """The README main job's integration (``cases/cageless_6206_10krpm_short.toml``: 20 ms, DOPRI5 at its rtol,
    the bundled film map) by the pointer-bound DOPRI5 kernel, with the model's fixed map options and with the
    same options as an int64 array, alternating, process CPU; the two trajectories compared bit for bit."""
    from lubedyn.config import CASES_DIR, load_case
    from lubedyn.dynamics import integrators
    from lubedyn.dynamics.cageless.kernels import rhs
    from lubedyn.scenes.dynamics import build

    case = load_case(CASES_DIR / "cageless_6206_10krpm_short.toml")
    setup = build(case)
    ig = case.integrator
    a = setup.model.args()
    variants = {"fixed": a,
                "runtime": a._replace(film_map=a.film_map._replace(opts=np.array(a.film_map.opts, dtype=np.int64)))}
    kernel = integrators.kernel_for("dopri5", rhs)

    def run(name):
        return kernel(setup.y0, setup.t_out, variants[name], ig.rtol, ig.atol, 0.0, 0.0, 10**8)

    first = {name: run(name) for name in variants}  # (compiles the runtime-option model)
    out = {"bit-identical trajectories": bool(np.array_equal(first["fixed"][0], first["runtime"][0])),
           "steps": int(first["fixed"][1][0]) if np.ndim(first["fixed"][1]) else None,
           "process CPU [s]": {"runtime": [], "fixed": []}}
    for r in range(rounds):
        for name in (("runtime", "fixed") if r % 2 == 0 else ("fixed", "runtime")):
            c0 = time.process_time()
            run(name)
            out["process CPU [s]"][name].append(time.process_time() - c0)
    rt, fx = (np.array(out["process CPU [s]"][k]) for k in ("runtime", "fixed"))
    out["after/before, median of the pairs"] = float(np.median(fx / rt))
    print(f"main job integration: before {np.median(rt):.2f} s, after {np.median(fx):.2f} s CPU (median), paired "
          f"{np.median(fx / rt):.3f}; bit-identical {out['bit-identical trajectories']}", flush=True)
    return out


def chart_fixed(data, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = data["fixed options"]
    fig, axs = plt.subplots(1, 3, figsize=(13, 3.6))
    for ax, what in zip(axs, ("query", "film read")):
        runs = d[what]["runs [ns]"]
        ax.plot(runs["runtime"], "o", ms=3, label="options at run time (before)")
        ax.plot(runs["fixed"], "s", ms=3, label="options fixed at compile time (after)")
        if what == "query":
            ax.axhline(80, color="k", ls="--", lw=0.8, label="target 80 ns")
        ax.set_xlabel("alternation")
        ax.set_ylabel("thread CPU ns")
        ax.set_title({"query": "3-D hermite value + gradient", "film read": "polar ball-ball film read"}[what]
                     + f"\nafter/before {d[what]['after/before, median of the pairs']:.2f} (median of pairs)",
                     fontsize=9)
        ax.legend(fontsize=7)
    comp = d["compile"]
    for i, variant in enumerate(("array", "fixed")):
        vals = [c["process CPU [s]"] for c in comp if c["variant"] == variant]
        axs[2].plot([i] * len(vals), vals, "o")
    axs[2].set_xticks([0, 1], ["options at run time", "fixed"])
    axs[2].set_xlim(-0.5, 1.5)
    axs[2].set_ylabel("process CPU [s]")
    axs[2].set_title("cold compile of the cage-less rhs\n(empty numba cache, child process)", fontsize=9)
    fig.tight_layout()
    _common.save_figure(fig, path)
    plt.close(fig)


# ---------------------------------------------------------------- 2. resolution vs error (analytic)
def analytic_resolution():
    kind = _Kind()
    params = squeeze_params()
    rows = []
    for n in (5, 9, 17, 33, 65):
        axes = maps.resolve_axes(kind, {"central_gap": {"n": n}})
        for method in ("linear", "pchip", "hermite"):
            t0 = time.perf_counter()
            fmap = maps.build_map(kind, None, axes, method=method, workers=1, progress=False, fit=False)
            q = maps.random_points(axes, 2000, seed=1)
            err = np.abs(fmap("Force [N]", *q.T) / squeeze_exact(params, q[:, 0], q[:, 1]) - 1)
            rows.append({"nodes along the gap": n, "method": method, "median relative error": float(np.median(err)),
                         "max relative error": float(err.max()), "build time [s]": time.perf_counter() - t0})
            print(f"analytic n={n:3d} {method:6s}: median {np.median(err):.2e}, max {err.max():.2e}", flush=True)
    for method in ("linear", "pchip", "hermite"):
        sel = [r for r in rows if r["method"] == method]
        p = -np.polyfit(np.log([r["nodes along the gap"] - 1 for r in sel]), np.log([r["max relative error"] for r in sel]), 1)[0]
        rows.append({"method": method, "fitted order (max error vs cells)": float(p)})
    return rows


# ---------------------------------------------------------------- 2b/3. the real ball-ball kind
def real_kind_levels(quick: bool, accuracy_points: int):
    """ball_ball maps at three resolutions (nodes per axis x 0.5, 0.75, 1 of the defaults), built without
    a cache (timed), each compared with the same direct solves at random off-grid points of the default
    axes (solved once)."""
    try:
        kind = maps.get_kind("ball_ball")
    except Exception as exc:  # noqa: BLE001 - recorded
        return {"available": False, "reason": str(exc)}
    defaults = {maps.axis_key(a.name): a for a in kind.axes}
    levels = {"smoke": 0.5} if quick else {"coarse": 0.5, "medium": 0.75, "default": 1.0}
    resolution = "smoke" if quick else "default"
    params = {**kind.default_params(), "resolution": resolution}
    workers = maps.default_workers()
    out = {"available": True, "params resolution": resolution, "workers": workers, "levels": []}
    ref_axes = maps.resolve_axes(kind)
    pts = maps.random_points(ref_axes, accuracy_points, seed=5)
    plist = [{a.name: float(x) for a, x in zip(ref_axes, row)} for row in pts]
    t0 = time.perf_counter()
    direct, info = maps.solve_points(kind, params, plist, workers=workers, progress=False)
    out["direct solves"] = {"points": accuracy_points, "failed": len(info["failed"]), "time [s]": time.perf_counter() - t0}
    ok = [i for i, r in enumerate(direct) if r is not None]
    for name, scale in levels.items():
        over = {} if scale == 1.0 else {k: {"n": max(2, int(round((a.n - 1) * scale)) + 1)} for k, a in defaults.items()}
        axes = maps.resolve_axes(kind, over)
        t0 = time.perf_counter()
        try:
            fmap = maps.build_map(kind, params, axes, workers=workers, progress=False, on_failure="fill")
        except Exception as exc:  # noqa: BLE001
            out["levels"].append({"level": name, "failed": str(exc)})
            continue
        t = time.perf_counter() - t0
        acc = {}
        for method in ("hermite", "pchip", "linear"):
            m = maps.FilmMap(fmap.axes, fmap.values, method=method, provenance=fmap.provenance)
            acc[method] = m.accuracy_against(pts[ok], {k: np.array([direct[i][k] for i in ok]) for k in fmap.outputs})
        row = {"level": name, "shape": list(fmap.shape), "points": int(np.prod(fmap.shape)), "build time [s]": t,
               "seconds per point per worker": t * workers / int(np.prod(fmap.shape)),
               "filled points": len(fmap.provenance.get("filled points", [])), "accuracy": acc,
               "fits": {k: {"max": f.max_error, "median": f.median_error, "formula": f.formula()}
                        for k, f in fmap.fits.items() if f is not None}}
        out["levels"].append(row)
        print(f"ball_ball {name}: {fmap.shape} in {t:.1f} s; hermite " + ", ".join(
            f"{k}: {v['median']:.2e}/{v['max']:.2e}" for k, v in acc["hermite"].items()), flush=True)
    return out


def worker_scaling(n_points=24):
    """Seconds per point on the same ball-ball points with 1 and 2 local workers."""
    try:
        kind = maps.get_kind("ball_ball")
    except Exception as exc:  # noqa: BLE001
        return {"available": False, "reason": str(exc)}
    axes = maps.resolve_axes(kind)
    pts = maps.random_points(axes, n_points, seed=9)
    plist = [{a.name: float(x) for a, x in zip(axes, row)} for row in pts]
    params = kind.default_params()
    out = {}
    for workers in (1, 2):
        t0 = time.perf_counter()
        maps.solve_points(kind, params, plist, workers=workers, progress=False)
        out[f"{workers} worker(s): s per point"] = (time.perf_counter() - t0) / n_points
    out["speed-up"] = out["1 worker(s): s per point"] / out["2 worker(s): s per point"]
    print("worker scaling", out, flush=True)
    return out


# ---------------------------------------------------------------- chart
def chart(data, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(1, 3, figsize=(15, 4.2))
    q = data["query cost"]
    labels = [f"{r['axes']}D {r['method']}\n{r['queries']}" for r in q]
    x = np.arange(len(q))
    axs[0].bar(x - 0.2, [r["ns per value query"] for r in q], 0.4, label="value")
    axs[0].bar(x + 0.2, [r["ns per value+gradient query (with output stores)"] for r in q], 0.4, label="value + gradient")
    axs[0].axhline(100, color="k", ls="--", lw=0.8, label="target 100 ns")
    axs[0].set_xticks(x, labels, fontsize=6, rotation=90)
    axs[0].set_ylabel("ns per query (numba loop)")
    axs[0].set_yscale("log")
    axs[0].legend(fontsize=7)
    axs[0].set_title("interpolation query cost")
    for method, marker in (("linear", "s"), ("pchip", "o"), ("hermite", "^")):
        sel = [r for r in data["analytic resolution"] if r.get("method") == method and "nodes along the gap" in r]
        axs[1].loglog([r["nodes along the gap"] for r in sel], [r["max relative error"] for r in sel], marker + "-",
                      label=f"{method} max")
        axs[1].loglog([r["nodes along the gap"] for r in sel], [r["median relative error"] for r in sel], marker + ":",
                      label=f"{method} median")
    axs[1].axhline(0.03, color="r", lw=0.8, ls="--")
    axs[1].axhline(0.01, color="g", lw=0.8, ls="--")
    axs[1].set_xlabel("nodes along the gap axis (0.1-10 um, log)")
    axs[1].set_ylabel("relative error of F")
    axs[1].set_title("analytic squeeze film: resolution vs error")
    axs[1].legend(fontsize=7)
    real = data.get("ball_ball levels", {})
    if real.get("available"):
        for out_name, marker in (("Force [N]", "o"), ("Stiffness [N/m]", "s"), ("Damping [N s/m]", "^")):
            pts = [(r["build time [s]"], r["accuracy"]["hermite"][out_name]) for r in real["levels"]
                   if "accuracy" in r and out_name in r["accuracy"]["hermite"]]
            if pts:
                axs[2].loglog([p[0] for p in pts], [p[1]["max"] for p in pts], marker + "-", label=f"{out_name} max")
                axs[2].loglog([p[0] for p in pts], [p[1]["median"] for p in pts], marker + ":", label=f"{out_name} median")
        axs[2].axhline(0.03, color="r", lw=0.8, ls="--")
        axs[2].axhline(0.01, color="g", lw=0.8, ls="--")
        axs[2].set_xlabel("map build time [s] (2 cores)")
        axs[2].set_ylabel("relative error vs direct solves")
        axs[2].set_title("ball_ball map: build time vs error")
        axs[2].legend(fontsize=6)
    else:
        axs[2].text(0.5, 0.5, "ball_ball kind not available", ha="center")
    fig.tight_layout()
    _common.save_figure(fig, path)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--accuracy-points", type=int, default=40)
    ap.add_argument("--query-only", action="store_true",
                    help="only section 1 (query cost, ~1 min on one core) -> results/maps_query.json")
    ap.add_argument("--repeats", type=int, default=None,
                    help="repeats per query-cost timing (default 7 with --query-only, 5, 3 with --quick)")
    ap.add_argument("--fixed-options", action="store_true",
                    help="only section 1b (map options fixed at compile time, before/after, ~3 min) "
                         "-> results/maps_fixed_options.json, .png")
    ap.add_argument("--compile-probe", choices=("array", "fixed"), help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.compile_probe:
        compile_probe(args.compile_probe)
        return
    if args.fixed_options:
        data = {"machine": _common.machine_info(("numba",)),
                "started": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
        data["fixed options"] = fixed_options_cost()
        data["load_average_at_end"] = list(__import__("os").getloadavg())
        _common.write_json(_common.RESULTS / "maps_fixed_options.json", data)
        chart_fixed(data, _common.RESULTS / "maps_fixed_options.png")
        print("wrote results/maps_fixed_options.json, .png")
        return
    if args.query_only:
        data = {"machine": _common.machine_info(("numba",)),
                "started": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                "load_average_at_start": list(__import__("os").getloadavg())}
        data["query cost"] = query_cost(repeats=args.repeats or 7)
        data["load_average_at_end"] = list(__import__("os").getloadavg())
        _common.write_json(_common.RESULTS / "maps_query.json", data)
        print("wrote results/maps_query.json")
        return
    t0 = time.perf_counter()
    data = {"machine": _common.machine_info(("numba", "dask", "distributed", "pyvista")),
            "started": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
    data["query cost"] = query_cost(repeats=args.repeats or (3 if args.quick else 5))
    data["analytic resolution"] = analytic_resolution()
    data["ball_ball levels"] = real_kind_levels(args.quick, 10 if args.quick else args.accuracy_points)
    if not args.quick:
        data["worker scaling"] = worker_scaling()
    data["total time [s]"] = time.perf_counter() - t0
    data["load_average_at_end"] = list(__import__("os").getloadavg())
    stem = "maps_quick" if args.quick else "maps"
    _common.write_json(_common.RESULTS / f"{stem}.json", data)
    chart(data, _common.RESULTS / f"{stem}.png")
    print(f"wrote results/{stem}.json, .png in {data['total time [s]']:.0f} s")


if __name__ == "__main__":
    main()
