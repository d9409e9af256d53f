"""The examples gallery (examples/*.py) at smoke size: each runs, saves its plot, and its numbers agree
with the independent values it shows (closed forms, the short-bearing theory, Stribeck, the ideal
kinematics), the scikit-fem way of keeping examples working."""
from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.fixture
def example(monkeypatch, tmp_path):
    monkeypatch.setenv("LUBEDYN_SMOKE", "1")
    monkeypatch.setenv("LUBEDYN_EXAMPLE_OUT", str(tmp_path))

    def load(name):
        spec = importlib.util.spec_from_file_location(f"example_{name}", EXAMPLES / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        out = module.main()
        assert (tmp_path / f"{name}.png").is_file()
        return out

    return load


def test_examples_import_nothing_private():
    """A user copies an example out of the gallery: it imports lubedyn and public packages only, no
    module of examples/ and no ``_name``."""
    import ast

    for path in EXAMPLES.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] + [a.name for a in node.names] if isinstance(node, ast.ImportFrom) else [])
            assert not any(part.startswith("_") and part != "__future__" for n in names for part in n.split(".")), \
                (path.name, names)


def test_every_example_is_tested():
    scripts = {p.stem for p in EXAMPLES.glob("*.py") if not p.stem.startswith("_")}
    tested = {name[len("test_"):] for name in globals() if name.startswith("test_")} - {"every_example_is_tested", "examples_import_nothing_private"}
    assert scripts == tested


def test_slider_and_journal(example):
    r = example("slider_and_journal")
    assert r["slider load [N/m]"] == pytest.approx(r["slider exact [N/m]"], rel=1e-3)  # P2, 8 elements
    assert r["journal load [N]"] == pytest.approx(r["Ocvirk [N]"], rel=0.05)  # L/D = 0.1: a few per cent


def test_own_gap(example):
    r = example("own_gap")
    assert r["1-D load [N/m]"] == pytest.approx(r["Rayleigh [N/m]"], rel=1e-9)  # P1 is exact for the step
    assert 0.2 < r["square pad load per width [N/m]"] / r["1-D load [N/m]"] < 0.6  # side leakage


def test_journal_coefficients(example):
    rows = example("journal_coefficients")
    for eps, trK, trK_ref, trC, trC_ref, detK, detK_ref in rows:
        assert trK == pytest.approx(trK_ref, rel=0.05) and trC == pytest.approx(trC_ref, rel=0.05)


def test_ehl_point_contact(example):
    """65 x 65 nodes (smoke): both methods carry the load; the Newton film within 5 % of the formula
    (measured +2.1 %), the multigrid within 15 % (measured -11.6 %: it needs 129 nodes at M = 100)."""
    r = example("ehl_point_contact")
    assert r["load Newton [N]"] == pytest.approx(r["load given [N]"], rel=1e-6)
    assert r["load multigrid [N]"] == pytest.approx(r["load given [N]"], rel=1e-4)
    assert r["h_c Newton [m]"] == pytest.approx(r["h_c formula [m]"], rel=0.05)
    assert r["h_c multigrid [m]"] == pytest.approx(r["h_c formula [m]"], rel=0.15)


def test_film_map(example):
    """4 x 4 polar nodes (smoke): off-grid query within 3 % of a direct solve (measured -1.2 %), the
    accuracy report's median below 1 % (0.11 %), pure squeeze within 2 % of the rigid Barus closed form
    (0.70 %: Dowson-Higginson density and interpolation)."""
    r = example("film_map")
    assert r["map force [N]"] == pytest.approx(r["direct force [N]"], rel=0.03)
    assert r["accuracy, force median [-]"] < 0.01
    assert r["squeeze map/closed form, max deviation [-]"] < 0.02


def test_tapered_roller_static(example):
    r = example("tapered_roller_static")
    assert r["most loaded roller, cup [N]"] == pytest.approx(r["Stribeck [N]"], rel=0.06)
    gamma = 21.305e-3 * math.cos(math.radians(10.0)) / 178e-3  # D_m cos(alpha_r)/d_m of the geometry
    assert r["ideal cage speed [rpm]"] == pytest.approx(2400 * (1 - gamma) / 2, rel=1e-9)


@pytest.mark.slow  # with ROSS installed (~40 s: ROSS imports in ~11 s and compiles its kernels); ~3 s without
def test_ross_bearing(example):
    """Raimondi and Boyd's S = 0.121 at 3000 rpm (L/D = 1): eccentricity ratio 0.6 (smoke mesh: 0.6009, as
    tests/test_rotordynamics.py); with ROSS, the rotor's lowest mode whirls forward at half the running
    speed (measured 0.5000-0.5003 of it at 1500-6000 rpm; oil whirl of a lightly loaded plain journal)."""
    r = example("ross_bearing")
    assert r["load [N]"] == pytest.approx(5165.3, rel=1e-4)
    assert abs(r["eccentricity at 3000 rpm [-]"] - 0.6) < 0.01
    if r["ross"]:
        assert r["rotor weight [N]"] == pytest.approx(9.81 * 44.86, rel=1e-3)
        assert np.allclose(r["lowest frequency / speed [-]"], 0.5, rtol=0.01)
        assert r["lowest whirl"] == ["Forward"] * 5


def test_read_outputs(example):
    r = example("read_outputs")
    assert r["last sample time [s]"] == pytest.approx(r["Simulated time [s]"], rel=1e-12)
    assert r["frames"] >= 2 and r["samples"] > 100
    assert r["rotor speed, xarray = read_timeseries"] and r["rotor speed units (xarray)"] == "rad/s"


def test_tapered_roller_dynamics(example):
    """Fig. 5's point for 1 ms: the rib's friction is what skews the loaded rollers (10 times or more the
    skew without it; measured on 5 ms at 10 slices: 9.9e-4 against 9e-7 rad, benchmarks/trb.py), and the
    cage runs within 1 % of the ideal speed 2,400 (1 - gamma)/2 rpm of the geometry."""
    r = example("tapered_roller_dynamics")
    with_f = r["mean loaded-zone skew, flange friction (eqs. 22-23) [rad]"]
    without = r["mean loaded-zone skew, no flange friction [rad]"]
    assert abs(with_f) > 10 * abs(without)
    gamma = 21.305e-3 * math.cos(math.radians(10.0)) / 178e-3
    assert r["ideal cage speed [rpm]"] == pytest.approx(2400 * (1 - gamma) / 2, rel=1e-9)
    for k in ("cage speed, flange friction (eqs. 22-23) [rpm]", "cage speed, no flange friction [rpm]"):
        assert r[k] == pytest.approx(r["ideal cage speed [rpm]"], rel=0.01)


def test_cavitation_models(example):
    """The long journal at eccentricity 0.6 on 32 P2 elements (128 P1 for JFO): each model's load against its
    closed form (measured at smoke size: none -3e-5, half-Sommerfeld -3e-5, Swift-Stieber -8e-5, JFO -2e-4),
    full Sommerfeld perpendicular to the line of centres, and JFO fed at the largest gap carrying
    Swift-Stieber's load."""
    r = example("cavitation_models")
    for model in ("none", "half_sommerfeld", "reynolds", "jfo"):
        assert r[f"{model} load [N/m]"] == pytest.approx(r[f"{model} closed form [N/m]"], rel=1e-3)
    assert r["none attitude [deg]"] == pytest.approx(90.0, abs=1e-6)
    assert r["half_sommerfeld load [N/m]"] < r["reynolds load [N/m]"] < r["none load [N/m]"]


def test_cageless_rotor_drop(example):
    """5 ms of the 3,000 rpm drop: the rotor follows the friction law Omega_0 - mu F_r r_c t / J_rotor while it
    slips (measured 2e-14); the ring catches up after the rigid two-inertia estimate (the balls' drag holds it
    back: measured 1.83 ms against 1.51 ms); every collision event is counted in the summary; the whole-system
    exponents carry an uncertainty and a verdict."""
    r = example("cageless_rotor_drop")
    assert r["samples while slipping"] > 100
    assert r["rotor speed, largest deviation from the friction law [-]"] < 1e-9
    assert r["ring catch-up, rigid estimate [s]"] < r["ring catch-up, measured [s]"] < 1.3 * r["ring catch-up, rigid estimate [s]"]
    assert r["collisions"] == r["collisions (summary)"] > 0
    verdict = r["Lyapunov exponent 1, whole system (Benettin) verdict"]
    assert verdict in ("positive", "not positive") or verdict.startswith("not converged (")


def test_study_on_dask(example):
    """The slider's load is linear in the runner speed (an isoviscous Reynolds film): load / speed equal at the
    three points of a study run on a local Dask cluster; study.nc holds the Dataset to_xarray() returns."""
    r = example("study_on_dask")
    assert r["runs"] == 3 and r["failed"] == 0 and "dask" in r["backend"].lower()
    ratio = r["load / speed [N s/m^2]"]
    assert np.allclose(ratio, ratio[0], rtol=1e-9) and ratio[0] > 0
    assert r["study.nc = to_xarray()"]
