"""lubedyn.maps: FilmMap, power-law fits, accuracy reports, storage, and map builds (local processes,
Dask, cache, resume, failures) on analytic point kinds defined here.

Analytic kind ``test_squeeze``: rigid isoviscous sphere-sphere squeeze film on a disk of radius a
(ambient pressure at r = a), R_eff = R/2 for two equal balls, D = a^2/(2 R_eff)::

    F = 6 pi eta R_eff^2 v D^2 / (h (h + D)^2)            (= 6 pi eta R_eff^2 v/h (1 - h/h_a)^2)
    K = -dF/dh = 6 pi eta R_eff^2 v D^2 (3h + D) / (h^2 (h + D)^3)
    C = dF/dv = F/v
"""
from __future__ import annotations

import math
import os
import uuid
from pathlib import Path

import numpy as np
import pytest

from lubedyn import maps
from lubedyn.config import CASES_DIR
from lubedyn.maps import FilmMap, MapAxis, build_map
from lubedyn.lubrication.errors import ConvergenceError, InputError


class Axis:  # the AxisDef protocol of lubedyn.film_points (duck-typed by lubedyn.maps)
    def __init__(self, name, lo, hi, n, scale):
        self.name, self.lo, self.hi, self.n, self.scale = name, lo, hi, n, scale


class Kind:
    def __init__(self, name, axes, outputs, evaluate, default_params, field=None, description=""):
        self.name, self.axes, self.outputs, self.evaluate = name, axes, outputs, evaluate
        self.default_params, self.field, self.description = default_params, field, description


GAP, SPEED = "Central gap [m]", "Approach speed [m/s]"


def squeeze_params():
    return {"radius": 4.7625e-3, "viscosity": 0.05, "film_radius": 0.3e-3, "poison": "", "log_dir": "", "delay": 0.0}


def squeeze_exact(params, h, v):
    r_eff = params["radius"] / 2
    D = params["film_radius"] ** 2 / (2 * r_eff)
    c = 6 * math.pi * params["viscosity"] * r_eff**2 * D**2 / (h * (h + D) ** 2)
    k = 6 * math.pi * params["viscosity"] * r_eff**2 * v * D**2 * (3 * h + D) / (h**2 * (h + D) ** 3)
    return c * v, k, c


def squeeze_evaluate(params, point):
    """Module level (picklable): the closed form; optionally fails while a poison file exists and logs calls."""
    h, v = point[GAP], point[SPEED]
    if params["delay"]:
        import time

        time.sleep(params["delay"])
    if params["log_dir"]:
        Path(params["log_dir"], uuid.uuid4().hex).write_text(f"{h!r} {v!r}")
    if params["poison"] and os.path.exists(params["poison"]) and h > 2e-6:
        raise ConvergenceError(f"test_squeeze: no convergence at h0 = {h:g} m")
    F, K, C = squeeze_exact(params, h, v)
    return {"Force [N]": F, "Stiffness [N/m]": K, "Damping [N s/m]": C}


def squeeze_field(params, point):
    """The closed-form film on a polar grid of the disk: p(r) = 3 eta v R_eff (1/h^2 - 1/h_a^2)."""
    import pyvista as pv

    h0, v = point[GAP], point[SPEED]
    r_eff, a = params["radius"] / 2, params["film_radius"]
    r, th = np.meshgrid(np.linspace(0, a, 21), np.linspace(0, 2 * np.pi, 33), indexing="ij")
    grid = pv.StructuredGrid(r * np.cos(th), r * np.sin(th), np.zeros_like(r))
    h = h0 + r**2 / (2 * r_eff)
    ha = h0 + a**2 / (2 * r_eff)
    grid.point_data["Pressure [Pa]"] = (3 * params["viscosity"] * v * r_eff * (1 / h**2 - 1 / ha**2)).ravel(order="F")
    grid.point_data["Film thickness [m]"] = h.ravel(order="F")
    return grid


SQUEEZE = Kind("test_squeeze", (Axis(GAP, 1e-7, 1e-5, 9, "log"), Axis(SPEED, 1e-3, 1e-1, 5, "log")),
               ("Force [N]", "Stiffness [N/m]", "Damping [N s/m]"), squeeze_evaluate, squeeze_params,
               field=squeeze_field, description="rigid isoviscous sphere-sphere squeeze (closed form)")
maps.register_kind(SQUEEZE)


def smooth3_evaluate(params, point):
    x, y, z = point["X [m]"], point["Y [-]"], point["Z [m/s]"]
    return {"Value [N]": params["scale"] * x**-1.5 * (1.0 + 0.3 * y + 0.1 * y * y) * (2.0 + math.tanh(z))}


SMOOTH3 = Kind("test_smooth3", (Axis("X [m]", 1e-7, 1e-5, 7, "log"), Axis("Y [-]", -1.0, 1.0, 6, "linear"),
                                Axis("Z [m/s]", 0.0, 2.0, 5, "linear")),
               ("Value [N]",), smooth3_evaluate, lambda: {"scale": 1e-10})
maps.register_kind(SMOOTH3)


def _count(log_dir):
    return len(os.listdir(log_dir))


# ---------------------------------------------------------------------------
# FilmMap


def test_power_law_fit_recovers_exponents_of_the_thin_film_limit():
    """For h << D the squeeze force tends to 6 pi eta R_eff^2 v/h: the fit on a thin-film grid finds
    exponents -1 (gap) and +1 (speed); its measured error equals the closed form's deviation from the
    pure power law (1 + h/D)^-2, which is < 1.3 % at h/D = 1e-3..6e-3."""
    p = squeeze_params()
    axes = maps.resolve_axes(SQUEEZE, {"central_gap": {"lo": 2e-8, "hi": 1e-7, "n": 6}})
    h, v = np.meshgrid(axes[0].nodes, axes[1].nodes, indexing="ij")
    F = squeeze_exact(p, h, v)[0]
    fmap = FilmMap(axes, {"Force [N]": F})
    fit = fmap.fit_power_law("Force [N]", cross=False)
    assert fit.exponents[0] == pytest.approx(-1.0, abs=0.02)
    assert fit.exponents[1] == pytest.approx(1.0, abs=1e-10)
    r_eff = p["radius"] / 2
    D = p["film_radius"] ** 2 / (2 * r_eff)
    assert fit.max_error < 1.3e-2 and fit.max_error == pytest.approx(
        np.abs(fit(h, v) / F - 1).max(), rel=1e-9)
    assert (1 + h.max() / D) ** 2 - 1 < 1.3e-2


def test_interpolation_against_closed_form_and_gradient_is_stiffness():
    """Default axes (9 x 5, log-log): pchip interpolation of F at random off-grid points within 1 % of
    the closed form (measured max 0.19 %), and -dF/dh of the interpolant approximates K (within 3 %,
    measured max 0.74 %)."""
    p = squeeze_params()
    axes = maps.resolve_axes(SQUEEZE)
    h, v = np.meshgrid(axes[0].nodes, axes[1].nodes, indexing="ij")
    F, K, C = squeeze_exact(p, h, v)
    fmap = FilmMap(axes, {"Force [N]": F, "Stiffness [N/m]": K, "Damping [N s/m]": C})
    q = maps.random_points(axes, 200, seed=3)
    Fx, Kx, _ = squeeze_exact(p, q[:, 0], q[:, 1])
    val, grad = fmap("Force [N]", q[:, 0], q[:, 1], grad=True)
    assert np.abs(val / Fx - 1).max() < 1e-2
    assert np.abs(-grad[:, 0] / Kx - 1).max() < 3e-2
    lin = FilmMap(axes, {"Force [N]": F}, method="linear")
    # F is not a power law (the finite-domain factor): linear-in-log error is larger than pchip's
    assert np.abs(lin("Force [N]", q[:, 0], q[:, 1]) / Fx - 1).max() > np.abs(val / Fx - 1).max()


def test_signed_output_is_not_logged_and_out_of_axes_raises_or_clamps():
    """A force over an approach speed through zero changes sign: its values are interpolated as they are
    (F is linear in v, so it is reproduced exactly along v); a query outside raises InputError naming the
    axis, or is clamped and counted."""
    p = squeeze_params()
    axes = (MapAxis.uniform(GAP, 1e-7, 1e-5, 9, "log"), MapAxis.uniform(SPEED, -0.1, 0.1, 5, "linear"))
    h, v = np.meshgrid(axes[0].nodes, axes[1].nodes, indexing="ij")
    fmap = FilmMap(axes, {"Force [N]": squeeze_exact(p, h, v)[0]})
    assert fmap.log_values["Force [N]"] is False
    hq = axes[0].nodes[3]
    assert fmap("Force [N]", hq, -0.037) == pytest.approx(squeeze_exact(p, hq, -0.037)[0], rel=1e-12)
    with pytest.raises(InputError, match=r"Approach speed \[m/s\] = 0.5"):
        fmap("Force [N]", 1e-6, 0.5)
    counter = np.zeros(1, np.int64)
    out = fmap("Force [N]", [1e-6, 1e-6, 2e-5], [0.5, 0.05, 0.05], mode="clamp", counter=counter)
    assert counter[0] == 2
    assert out[0] == pytest.approx(fmap("Force [N]", 1e-6, 0.1), rel=1e-14)
    assert out[2] == pytest.approx(fmap("Force [N]", 1e-5, 0.05), rel=1e-14)


@pytest.mark.parametrize("method", ["hermite", "linear"])
def test_nan_coordinate_raises_in_raise_mode_and_is_counted_in_clamp_mode(method):
    """A NaN coordinate in the default "raise" mode used to return NaN (the check skipped
    NaN points); it now raises InputError naming the axis and the number of such points.  "clamp"
    returns NaN for it and counts it with the points outside (one count per point), "nan" returns NaN
    without a count; finite points in the same query keep their exact values (F linear in v)."""
    p = squeeze_params()
    axes = (MapAxis.uniform(GAP, 1e-7, 1e-5, 9, "log"), MapAxis.uniform(SPEED, -0.1, 0.1, 5, "linear"))
    h, v = np.meshgrid(axes[0].nodes, axes[1].nodes, indexing="ij")
    fmap = FilmMap(axes, {"Force [N]": squeeze_exact(p, h, v)[0]}, method=method)
    hq = axes[0].nodes[3]
    with pytest.raises(InputError, match=r"2 point\(s\) with a NaN coordinate, first point 1 "
                                         r"\(Approach speed \[m/s\] = nan\)"):
        fmap("Force [N]", [hq, hq, np.nan], [0.05, np.nan, 0.05])
    with pytest.raises(InputError, match=r"NaN coordinate, first point 0 \(Central gap \[m\] = nan\)"):
        fmap("Force [N]", np.nan, 0.05, grad=True)
    counter = np.zeros(1, np.int64)
    out = fmap("Force [N]", [hq, hq, np.nan, 2e-5], [0.05, np.nan, 0.05, 0.05], mode="clamp", counter=counter)
    assert counter[0] == 3  # two NaN points and one outside
    assert np.isnan(out[1]) and np.isnan(out[2])
    assert out[0] == pytest.approx(squeeze_exact(p, hq, 0.05)[0], rel=1e-12)
    counter[0] = 0
    out = fmap("Force [N]", [hq, hq], [0.05, np.nan], mode="nan", counter=counter)
    assert counter[0] == 0 and np.isnan(out[1]) and np.isfinite(out[0])


def test_save_load_round_trip_and_format_check(tmp_path):
    """Saved and loaded maps interpolate identically and keep provenance, fits and log flags; a file
    with another format version is refused with a message naming it."""
    fmap = build_map("test_squeeze", workers=1, progress=False)
    path = fmap.save(tmp_path / "m.npz")
    again = FilmMap.load(path)
    q = maps.random_points(fmap.axes, 20, seed=1)
    for name in fmap.outputs:
        assert np.array_equal(again(name, *q.T), fmap(name, *q.T))
        assert again.fits[name] == fmap.fits[name]
    assert again.provenance["input sha256"] == fmap.provenance["input sha256"]
    assert again.provenance["versions"]["numpy"] == np.__version__
    ka = again.kernel_arrays("Force [N]")
    assert ka.logs == (1, 1) and ka.logv == 1 and np.allclose(np.exp(ka.axes[0]), fmap.axes[0].nodes, rtol=1e-15)
    import json

    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files}
    header = json.loads(str(arrays["header"]))
    header["format_version"] = 99
    arrays["header"] = np.array(json.dumps(header))
    np.savez(tmp_path / "future.npz", **arrays)
    with pytest.raises(InputError, match="format_version = 99"):
        FilmMap.load(tmp_path / "future.npz")


def _front_map(sheared: bool):
    """A map of mu(w, s) = s/(1 + (s/s_t)^6)^(1/6) (Newtonian below s_t, limited above) with s_t = 0.1 w^-35, the
    steepness of the roller traction's Newtonian-to-limited front (lubedyn.film_points,
    ROLLER_TRACTION_SHEAR: the front crosses the slip axis), on 5 load nodes (ratio 1.07) x 37 slip nodes
    1e-5..0.1; with ``sheared``
    also the transition slip (saturated as the kinds do) and the traction at the normalised slip."""
    from lubedyn.film_points import ROLLER_TRACTION_SHEAR as spec, normalised_slip, saturated_transition

    w = np.geomspace(1.0, 1.3, 5)
    s = np.geomspace(1e-5, 0.1, 37)
    W, S = np.meshgrid(w, s, indexing="ij")
    s_t = 0.1 * W**-35.0
    mu = lambda s_, st: s_ / (1.0 + (s_ / st) ** 6) ** (1 / 6)
    values = {"Traction coefficient [-]": mu(S, s_t)}
    extra = {}
    if sheared:
        c = np.vectorize(saturated_transition)(s_t)
        values[spec["shift"]] = c
        values[spec["values"]] = mu(normalised_slip(S) * c, s_t)
        extra = {"sheared": {"Traction coefficient [-]": dict(spec, axis=1)}}
    axes = [MapAxis("Load [-]", w, "log"), MapAxis("Slide-to-roll ratio [-]", s, "log")]
    return FilmMap(axes, values, **extra), mu


def test_sheared_output_follows_a_moving_front(tmp_path):
    """A front that moves by 2.4 e-folds of slip per load cell (the roller traction's): on the plain
    (load, slip) table the interpolation misses by > 10 %; the map with the output tabulated on the
    normalised slip (FilmMap "sheared") returns it within 3 % (measured 1.2 %; median 2e-5) at 200 random
    points, survives save/load,
    and refuses the plain kernel arrays of the sheared output (they are not what it returns)."""
    plain, mu = _front_map(False)
    sheared, _ = _front_map(True)
    q = maps.random_points(plain.axes, 200, seed=3)
    exact = mu(q[:, 1], 0.1 * q[:, 0] ** -35.0)
    err_plain = np.abs(plain("Traction coefficient [-]", *q.T) / exact - 1)
    err_sheared = np.abs(sheared("Traction coefficient [-]", *q.T) / exact - 1)
    assert err_plain.max() > 0.1
    assert err_sheared.max() < 0.03 and np.median(err_sheared) < 0.001
    again = FilmMap.load(sheared.save(tmp_path / "front.npz"))
    assert np.array_equal(again("Traction coefficient [-]", *q.T), sheared("Traction coefficient [-]", *q.T))
    with pytest.raises(InputError, match="sheared"):
        sheared.kernel_arrays("Traction coefficient [-]")
    with pytest.raises(InputError, match="outside the axes"):
        sheared("Traction coefficient [-]", 0.9, 0.2)


# ---------------------------------------------------------------------------
# builds


def test_build_accuracy_report_against_closed_form():
    """The build's accuracy report (direct solves at random off-grid points) meets the issue's targets
    on the default axes (median < 1 %, max < 3 %; measured F: median 0.019 %, max 0.18 %), and its
    numbers equal an error computed here from the closed form."""
    fmap = build_map("test_squeeze", workers=1, progress=False, accuracy_points=40, seed=7)
    rep = fmap.accuracy["Force [N]"]
    assert rep["points"] == 40 and rep["median"] < 0.01 and rep["max"] < 0.03
    q = maps.random_points(fmap.axes, 40, seed=7)
    F = squeeze_exact(squeeze_params(), q[:, 0], q[:, 1])[0]
    err = np.abs(fmap("Force [N]", *q.T) / F - 1)
    assert rep["max"] == pytest.approx(err.max(), rel=1e-9)
    assert rep["median"] == pytest.approx(np.median(err), rel=1e-9)


def test_local_processes_and_dask_give_the_same_map(tmp_path):
    """Two local processes and a Dask LocalCluster (2 workers, threads) produce bit-identical values,
    equal to the closed form at the nodes."""
    from distributed import LocalCluster

    axes = {"central_gap": {"n": 5}, "approach_speed": {"n": 3}}
    local = build_map("test_squeeze", axes=axes, workers=2, progress=False)
    with LocalCluster(n_workers=2, processes=False, threads_per_worker=1, dashboard_address=None) as cluster:
        remote = build_map("test_squeeze", axes=axes, scheduler=cluster.scheduler_address, progress=False)
    assert local.provenance["backend"].startswith("local processes")
    assert remote.provenance["backend"].startswith("dask")
    for name in local.outputs:
        assert np.array_equal(local.values[name], remote.values[name])
    h, v = np.meshgrid(local.axes[0].nodes, local.axes[1].nodes, indexing="ij")
    assert np.allclose(local.values["Force [N]"], squeeze_exact(squeeze_params(), h, v)[0], rtol=1e-14)


def test_failed_points_are_named_then_resumed_and_unchanged_inputs_not_rebuilt(tmp_path):
    """A build whose solves fail at h0 > 2 um raises ConvergenceError naming a failed point; the points
    that succeeded are persisted, so the rebuild (failure gone) solves only the failed ones; a third
    build with unchanged inputs loads the map without solving; changing a parameter rebuilds."""
    logs, poison = tmp_path / "calls", tmp_path / "poison"
    logs.mkdir()
    poison.write_text("")
    params = {"log_dir": str(logs), "poison": str(poison)}
    axes = {"central_gap": {"n": 7}, "approach_speed": {"n": 2}}
    nodes = np.geomspace(1e-7, 1e-5, 7)
    n_bad = 2 * int(np.sum(nodes > 2e-6))
    with pytest.raises(ConvergenceError, match=r"test_squeeze: .*points failed: \(Central gap \[m\] = .*no convergence"):
        build_map("test_squeeze", params, axes, workers=2, cache_dir=tmp_path / "cache", progress=False)
    assert _count(logs) == 14
    poison.unlink()
    fmap = build_map("test_squeeze", params, axes, workers=2, cache_dir=tmp_path / "cache", progress=False)
    assert _count(logs) == 14 + n_bad
    assert fmap.provenance["points from cache"] == 14 - n_bad
    again = build_map("test_squeeze", params, axes, workers=2, cache_dir=tmp_path / "cache", progress=False)
    assert _count(logs) == 14 + n_bad and "loaded from cache" in again.provenance
    changed = build_map("test_squeeze", {**params, "viscosity": 0.1}, axes, workers=1,
                        cache_dir=tmp_path / "cache", progress=False)
    assert _count(logs) == 28 + n_bad
    assert np.allclose(changed.values["Force [N]"], 2 * fmap.values["Force [N]"], rtol=1e-14)


def test_fill_option_marks_failed_points(tmp_path):
    """on_failure='fill': failed nodes take their nearest solved neighbour's value and are listed."""
    poison = tmp_path / "poison"
    poison.write_text("")
    fmap = build_map("test_squeeze", {"poison": str(poison)}, {"central_gap": {"n": 5}, "approach_speed": {"n": 2}},
                     workers=1, progress=False, on_failure="fill")
    filled = fmap.provenance["filled points"]
    assert len(filled) == 4 and all(f["point"][GAP] > 2e-6 for f in filled)
    F = fmap.values["Force [N]"]
    assert np.array_equal(F[3:, :], np.repeat(F[2:3, :], 2, axis=0))
    # the map scene's summary says why the build ended, with the points' own errors
    from lubedyn.scenes.map import _build_stop_reason

    reason = _build_stop_reason(fmap.provenance)
    assert reason.startswith("4 of 10 points failed and were filled") and f"2 x {filled[0]['error']}" in reason


def test_killed_build_resumes(tmp_path):
    """A build killed (SIGKILL) in the middle leaves whole point files only (each is written to a
    temporary file and renamed); the next build solves just the rest."""
    import signal
    import subprocess
    import sys
    import time

    logs = tmp_path / "calls"
    logs.mkdir()
    params = {"log_dir": str(logs), "delay": 0.04}
    script = f"""
import sys
sys.path.insert(0, {str(Path(__file__).parent)!r})
import test_maps
from lubedyn import maps
maps.build_map("test_squeeze", {params!r}, workers=1, cache_dir={str(tmp_path / 'cache')!r}, progress=False)
"""
    proc = subprocess.Popen([sys.executable, "-c", script])
    store = tmp_path / "cache" / "points" / "test_squeeze"
    t0 = time.time()
    while time.time() - t0 < 60 and (not store.is_dir() or len(list(store.glob("*.json"))) < 10):
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    done = len(list(store.glob("*.json")))
    assert 10 <= done < 45
    import json

    for f in store.glob("*.json"):  # every point file is whole (a kill mid-write leaves only a .tmp file)
        assert set(json.loads(f.read_text())) == {"point", "outputs"}
    fmap = build_map("test_squeeze", params, workers=1, cache_dir=tmp_path / "cache", progress=False)
    assert fmap.provenance["points from cache"] == done
    assert fmap.provenance["points solved"] == 45 - done
    h, v = np.meshgrid(fmap.axes[0].nodes, fmap.axes[1].nodes, indexing="ij")
    assert np.allclose(fmap.values["Damping [N s/m]"], squeeze_exact(squeeze_params(), h, v)[2], rtol=1e-14)


def test_three_axes_build_and_unknown_keys():
    """A 3-axis map of a smooth kind: pchip error at random off-grid points below 1 % median / 3 % max
    (measured 0.057 % / 0.25 %); unknown parameter or axis keys give one-line errors with a suggestion."""
    fmap = build_map("test_smooth3", workers=1, progress=False, accuracy_points=30, seed=2)
    rep = fmap.accuracy["Value [N]"]
    assert rep["median"] < 0.01 and rep["max"] < 0.03
    assert fmap.fits["Value [N]"] is not None and fmap.fits["Value [N]"].exponents[0] == pytest.approx(-1.5, abs=1e-9)
    with pytest.raises(InputError, match="params.scal: .*did you mean 'scale'"):
        build_map("test_smooth3", {"scal": 1.0}, workers=1, progress=False)
    with pytest.raises(InputError, match="axes.xx: .*did you mean 'x'"):
        build_map("test_smooth3", axes={"xx": {"n": 3}}, workers=1, progress=False)


# ---------------------------------------------------------------------------
# shipped maps (cases/maps/*.npz)

SHIPPED = [pytest.param(p, id=p.stem, marks=[pytest.mark.slow] if p.stem.startswith("ehl_") else [])
           for p in sorted((CASES_DIR / "maps").glob("*.npz"))]


@pytest.mark.parametrize("path", SHIPPED)
def test_shipped_map_agrees_with_a_fresh_solve(path):
    """A shipped map against fresh solves of its kind with the parameters stored in it: at one grid node
    every output must match to 1e-6 (the solver is deterministic; a larger difference means the physics
    changed and the map is stale: rebuild it, see cases/maps/README.md); for kinds cheaper than 2 s per
    point also at the centre (in interpolation space) of a cell whose corner values of the first output
    are all significant and positive, where the interpolation must be within 3 % (the issue's target)
    for every output positive at all the cell's corners whose accuracy report meets the median target
    (< 1 %; an output that misses it is listed in the map's report and summary instead) and that is not
    a recorded miss (KNOWN_MISSES, strict xfails of the accuracy test below: the roller maps' traction and
    transition slip)."""
    fmap = FilmMap.load(path)
    kind = maps.get_kind(fmap.provenance["kind"])
    params = fmap.provenance["params"]
    first = fmap.outputs[0]
    v = fmap.values[first]
    sig = maps._significant(v).reshape(v.shape) & (v > 0)
    # node: the significant node at the 75th percentile of |first output|; for a film-thickness map the
    # thickest film (lightest load, fastest entrainment: the lowest Moes M, the cheapest EHL solve -- on
    # the inner-race ball map 8 CPU-s against 90 s at the 75th percentile, where the secant coefficients
    # stall and fall back)
    idx = np.argwhere(sig)
    order = np.argsort(np.abs(v[sig]))
    node = tuple(idx[order[-1 if "film thickness" in first else int(0.75 * (len(order) - 1))]])
    point = {a.name: float(a.nodes[i]) for a, i in zip(fmap.axes, node)}
    fresh = kind.evaluate(params, point)
    for name in fmap.outputs:
        scale = max(abs(fresh[name]), 1e-300)
        assert abs(fmap.values[name][node] - fresh[name]) <= 1e-6 * scale + 1e-12 * np.abs(fmap.values[name]).max(), name
    per_point = fmap.provenance.get("build time [s]", 1e9) * maps.default_workers() / max(1, fmap.provenance["points"])
    if per_point > 2.0:
        return
    # off-grid: the middle one (in C order) of the cells whose corners are all significant and positive
    cells = [c for c in np.ndindex(*(n - 1 for n in fmap.shape))
             if all(sig[tuple(ci + o for ci, o in zip(c, off))] for off in np.ndindex(*(2,) * fmap.ndim))]
    cell = cells[len(cells) // 2]
    centre = []
    for a, i in zip(fmap.axes, cell):
        lo, hi = a.nodes[i], a.nodes[i + 1]
        centre.append(math.sqrt(lo * hi) if a.log else 0.5 * (lo + hi))
    fresh = kind.evaluate(params, {a.name: x for a, x in zip(fmap.axes, centre)})
    checked = 0
    for name in fmap.outputs:
        corners = [fmap.values[name][tuple(ci + o for ci, o in zip(cell, off))] for off in np.ndindex(*(2,) * fmap.ndim)]
        if (min(corners) > 0 and fmap.accuracy.get(name, {}).get("median", 1.0) < 0.01
                and (path.stem, name) not in KNOWN_MISSES):
            assert fmap(name, *centre) == pytest.approx(fresh[name], rel=0.03), name
            checked += 1
    assert checked >= 1


def test_dask_worker_processes_give_the_same_real_map(tmp_path):
    """A Dask LocalCluster with worker *processes* (each imports lubedyn afresh) builds
    the real ball-ball kind at smoke resolution bit-identically to local processes."""
    from distributed import LocalCluster

    axes = {"central_gap": {"n": 2}, "pressure_number": {"n": 2}, "squeeze_angle": {"n": 2}}
    params = {"resolution": "smoke"}
    local = build_map("ball_ball", params, axes, workers=2, cache_dir=tmp_path / "a", progress=False, fit=False)
    with LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) as cluster:
        remote = build_map("ball_ball", params, axes, scheduler=cluster.scheduler_address, cache_dir=tmp_path / "b",
                           progress=False, fit=False)
    assert remote.provenance["backend"].startswith("dask")
    for name in local.outputs:
        assert np.array_equal(local.values[name], remote.values[name]), name
    assert np.all(local.values["Force [N]"] >= 0.0) and local.values["Force [N]"].max() > 0.0


# ---------------------------------------------------------------------------
# the shipped maps' accuracy (cases/maps/README.md) and the polar ball-ball map

SHIPPED_MAPS = CASES_DIR / "maps"


# (map, output) pairs that miss the target, with the measured cause (strict xfail).  None since 28 Nov 2026:
# the roller maps' traction and transition slip missed (max 8.5 / 13.5 %) while their 257-node solutions were
# uniform and incompressible (the traction's low-slip slope jumped +-10 % between loads with the one-node
# pressure spike); rebuilt with a Dowson-Higginson film on a graded grid, solved with the pseudo-transient
# Newton (cases/maps/README.md, "Rebuilt 28 Nov 2026"), every output meets the target.  Earlier fixes: K and C
# (25 Nov 2026, the knee), the cone's central film (interpolated at x = 0), the Newtonian roller map's several
# exact solutions per point (22 Nov 2026, Eyring flow; tests/test_ehl.py pins it).
_RIB_FEW = ("accuracy report on 2 off-grid points, not the target's 15: each direct lithium rib solve takes "
            "12-300 s (the Herschel-Bulkley homotopy start); both points within 0.31 % (h_c) / 0.63 % (h_min)")
KNOWN_MISSES: dict = {
    ("ehl_rib_lithium_30C", "Central film thickness [m]"): _RIB_FEW,
    ("ehl_rib_lithium_30C", "Minimum film thickness [m]"): _RIB_FEW,
}


def _accuracy_cases():
    out = []
    for path in sorted(SHIPPED_MAPS.glob("*.npz")):
        fmap = FilmMap.load(path)
        # the tabulated function of a sheared output is judged through that output (FilmMap.accuracy_against)
        internal = {spec["values"] for spec in fmap.sheared.values()}
        for name in fmap.outputs:
            if name in internal:
                continue
            why = KNOWN_MISSES.get((path.stem, name))
            marks = [pytest.mark.xfail(strict=True, reason=why)] if why else []
            out.append(pytest.param(path, name, id=f"{path.stem}-{name.split('[')[0].strip()}", marks=marks))
    return out




@pytest.mark.parametrize("path, name", _accuracy_cases())
def test_shipped_map_accuracy_report_meets_the_target(path, name):
    """Every output of every shipped map: interpolation error against direct solves at random off-grid
    points (lubedyn.maps.accuracy_report, stored in the map) median < 1 %, max < 3 % (the issue's target),
    on at least 15 points, none failed.  Strict xfail: the pairs of KNOWN_MISSES (EHL solution jitter)."""
    rep = FilmMap.load(path).accuracy
    assert not rep.get("failed points"), rep.get("failed points")
    assert rep[name]["points"] >= 15, name
    assert rep[name]["median"] < 0.01 and rep[name]["max"] < 0.03, (name, rep[name])


def _old_cone_points():
    # the worst points of the earlier (gap, squeeze number, entrainment speed) map: F 59 %, C 123 %
    # (separating, 0.29 um) and F 39 % (approaching, 2.1 um), next to zero approach speed
    return [(2.9416789483285e-07, -0.015427428788579082, 0.005409470763730636),
            (2.13093296e-06, 3.13753268e-03, 8.90244440e-03)]


def test_shipped_ball_ball_map_at_the_cone_of_the_cartesian_axes():
    """The points where the Cartesian map failed (the cone at v = u_e = 0), read from the shipped polar
    map through lubedyn.film_points.polar_numbers, against direct Reynolds solves with the map's own
    parameters: F, K, C within 3 %."""
    from lubedyn import film_points as fp

    fmap = FilmMap.load(SHIPPED_MAPS / "ball_ball.npz")
    params = fmap.provenance["params"]
    for h0, lam, ue in _old_cone_points():
        v = fp.approach_speed(h0, lam, params)
        rho, theta = fp.polar_numbers(h0, v, ue, params)
        direct = fp.evaluate_ball_ball(params, {"Central gap [m]": h0, "Approach speed [m/s]": v,
                                                "Entrainment speed [m/s]": ue})
        for name in ("Force [N]", "Stiffness [N/m]", "Damping [N s/m]"):
            assert float(fmap(name, h0, rho, theta)) == pytest.approx(direct[name], rel=0.03), (name, h0, lam, ue)


def test_cartesian_resample_for_the_bearing_kernel():
    """The polar ball-ball map resampled on (gap, squeeze number, entrainment speed) nodes (what the bearing
    kernel reads until it reads polar axes): at nodes with and without entrainment it matches direct solves
    within 3 %; at Lambda = u_e = 0 the force is 0 (no film load at rest)."""
    from lubedyn import film_points as fp

    fmap = FilmMap.load(SHIPPED_MAPS / "ball_ball.npz")
    params = fmap.provenance["params"]
    cart = maps.cartesian_resample(fmap, "Force [N]")
    assert [a.name for a in cart.axes] == ["Central gap [m]", "Squeeze number [-]", "Entrainment speed [m/s]"]
    g, lam, ue = (a.nodes for a in cart.axes)
    assert np.all(cart.values["Force [N]"][:, 0, 0] == 0.0)
    for i, j, k in ((9, 4, 1), (3, 8, 2), (15, 2, 0)):
        direct = fp.evaluate_ball_ball(params, {"Central gap [m]": g[i], "Squeeze number [-]": lam[j],
                                                "Entrainment speed [m/s]": ue[k]})
        assert cart.values["Force [N]"][i, j, k] == pytest.approx(direct["Force [N]"], rel=0.03), (i, j, k)
    arrays = fmap.dynamics_film_map()
    assert arrays.speed_axis == "polar" and arrays.arrays.axes[1].size == fmap.axes[1].nodes.size
