"""The map scene through the CLI (``lubedyn run`` on a map case), with the analytic squeeze kind of
tests/test_maps.py: files written, the map read back and checked against the closed form, the .pvd
series read back with pyvista and checked against the closed-form central pressure, the summary's
accuracy report, the cache (a second run solves nothing), and one-line input errors."""
from __future__ import annotations

import json
import tomllib

import numpy as np
import pytest

import test_maps  # noqa: F401  (registers the analytic kinds)
from lubedyn import cli
from lubedyn.maps import FilmMap, random_points
from test_maps import squeeze_exact, squeeze_params

CASE = """
scene = "map"
description = "analytic squeeze map"
kind = "test_squeeze"
[axes.central_gap]
lo = "0.1 um"
hi = "10 um"
n = 9
[axes.approach_speed]
lo = "1 mm/s"
hi = "0.1 m/s"
n = 4
[params]
viscosity = "50 mPa s"
[build]
workers = 1
accuracy_points = 25
[output]
field_frames = 3
field_at = {approach_speed = "20 mm/s"}
[smoke]
axes.central_gap.n = 5
build.accuracy_points = 5
"""


def _run(tmp_path, text=CASE, *extra):
    path = tmp_path / "case.toml"
    path.write_text(text)
    return cli.main(["run", str(path), "--out", str(tmp_path / "out"), *extra])


def test_map_case_writes_map_png_pvd_and_summary(tmp_path):
    assert _run(tmp_path) == 0
    out = tmp_path / "out"
    names = {p.name for p in out.iterdir()}
    assert {"test_squeeze.npz", "map.png", "fields.pvd", "field_000.vtu", "field_002.vtu", "summary.json",
            "case.resolved.toml"} <= names
    s = json.loads((out / "summary.json").read_text())
    params = {**squeeze_params(), "viscosity": 0.05}
    # the map read back against the closed form at random off-grid points (pchip, 9 x 4 log nodes)
    fmap = FilmMap.load(out / "test_squeeze.npz")
    q = random_points(fmap.axes, 50, seed=11)
    F = squeeze_exact(params, q[:, 0], q[:, 1])[0]
    assert np.abs(fmap("Force [N]", *q.T) / F - 1).max() < 0.01
    assert s["Interpolation max relative error [-] of Force [N]"] < 0.03
    assert s["Grid points [-]"] == 36 and s["Points solved [-]"] == 36 and s["Accuracy points [-]"] == 25
    # the .pvd series: 3 frames along the gap at v = 20 mm/s; central pressure = 3 eta v R_eff (1/h0^2 - 1/h_a^2)
    import pyvista as pv

    reader = pv.get_reader(str(out / "fields.pvd"))
    assert len(reader.time_values) == 3
    r_eff, a = params["radius"] / 2, params["film_radius"]
    for t in reader.time_values:
        reader.set_active_time_value(t)
        grid = reader.read()[0]
        expected = 3 * 0.05 * 0.02 * r_eff * (1 / t**2 - 1 / (t + a * a / (2 * r_eff)) ** 2)
        assert grid.point_data["Pressure [Pa]"].max() == pytest.approx(expected, rel=1e-12)
    assert reader.time_values[0] == pytest.approx(1e-7) and reader.time_values[-1] == pytest.approx(1e-5)
    # resolved case is itself a valid case; the second run into the same folder loads the cached map
    resolved = tomllib.loads((out / "case.resolved.toml").read_text())
    assert resolved["axes"]["central_gap"]["lo"] == pytest.approx(1e-7)
    assert _run(tmp_path) == 0
    s2 = json.loads((out / "summary.json").read_text())
    assert s2["Map loaded from cache"] is True and s2["Map input sha256"] == s["Map input sha256"]


def test_smoke_and_bad_input(tmp_path, capsys):
    assert _run(tmp_path, CASE, "--smoke") == 0
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert s["Grid points [-]"] == 20 and s["Smoke resolution"] is True
    bad = [
        (CASE.replace("[axes.central_gap]", "[axes.central_gapp]"), "axes.central_gapp is not an axis of kind "
         "'test_squeeze'; did you mean 'central_gap'?"),
        (CASE.replace('lo = "0.1 um"', 'lo = "0.1 Pa"'), "axes.central_gap.lo = '0.1 Pa' has units of pressure, "
         "expected length"),
        (CASE.replace('viscosity = "50 mPa s"', 'viscosty = 0.05'), "params.viscosty"),
        (CASE.replace('kind = "test_squeeze"', 'kind = "test_squeez"'), "kind = 'test_squeez' is not a map kind"),
        (CASE.replace('n = 9', 'n = 1'), "axes.central_gap.n = 1 must be >= 2"),
        (CASE.replace('lo = "0.1 um"', 'lo = "-0.1 um"'), "axes.central_gap"),
    ]
    for text, message in bad:
        capsys.readouterr()
        assert _run(tmp_path, text) == 2, message
        err = capsys.readouterr().err
        assert message in err and len(err.strip().splitlines()) == 1, err


def test_map_scenes_take_the_typed_lubricant_table():
    """[lubricant] (the film and EHL scenes' typed table, units checked) sets a kind's oil parameters exactly
    as the untyped params keys do; giving both, a z for Roelands or a wrong unit is a one-line error
    naming the key."""
    from lubedyn.config import CASES_DIR, CaseError, load_case_text

    base = (CASES_DIR / "map_ehl_ball_inner_race.toml").read_text()
    table = ('\n[lubricant]\nviscosity = { law = "barus", eta0 = "50 mPa s", alpha = "1.85e-8 m^2/N" }\n'
             'density = { law = "dowson_higginson", rho0 = "992 kg/m^3" }\n')
    typed = load_case_text(base + table, smoke=True)
    untyped = load_case_text(base.replace('resolution = "default"', 'resolution = "default"\neta0 = "0.05 Pa s"\n'
                                          'alpha = "1.85e-8 m^2/N"\nrho0 = "992 kg/m^3"'), smoke=True)
    assert typed.params == untyped.params and typed.params["eta0"] == 0.05
    cases = [
        (base.replace('resolution = "default"', 'resolution = "default"\neta0 = 0.1') + table, "params.eta0"),
        (base + table.replace('alpha = "1.85e-8 m^2/N"', 'z = 0.6').replace('"barus"', '"roelands"'),
         "lubricant.viscosity.z"),
        (base + table.replace('"50 mPa s"', '"50 mPa"'), "lubricant.viscosity.eta0"),
    ]
    for text, key in cases:
        with pytest.raises(CaseError, match=key.replace(".", r"\.")) as info:
            load_case_text(text, smoke=True)
        assert "\n" not in str(info.value)
