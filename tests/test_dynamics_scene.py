"""The dynamics scene through the CLI: bad input is one line with exit code 2, a
film map queried outside its axes is counted and reported, and a failed
integration is exit code 1 without overwriting earlier outputs."""
from __future__ import annotations

import json

import pytest

from lubedyn import cli
from lubedyn.config import CASES_DIR, load_case
from lubedyn.lubrication.errors import InputError

SHORT = CASES_DIR / "cageless_6206_10krpm_short.toml"


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def one_line(err, *fragments):
    assert err.startswith("lubedyn: error: ") and err.count("\n") == 1 and "Traceback" not in err, err
    for fragment in fragments:
        assert fragment in err, (fragment, err)


@pytest.mark.parametrize("overrides, fragments", [
    (["bearing.n_balls=16"], ["bearing.n_balls = 16", "do not fit the pitch circle"]),
    (["films.map=maps/ehl_ball_inner_race.npz"], ["films.map = 'maps/ehl_ball_inner_race.npz' is a map of kind",
                                                  "ball_ball is needed"]),
    (["films.ball_ball=map", "films.map=maps/nope.npz"], ["films.map = 'maps/nope.npz' not found"]),
    (["integrator.method=rk4"], ["integrator.dt", "required with method = 'rk4'"]),
    (["integrator.method=rk4", "integrator.dt='20 us'"], ["beyond the RK4 stability limit"]),
    (["operating.axial_load='200 kN'"], ["operating.axial_load = 200000 N", "beyond the groove shoulders"]),
    (["model.dof=planar"], ["operating.axial_load", "needs model.dof = '6dof'"]),
    (["analysis.ball=14"], ["analysis.ball = 14", "must be < bearing.n_balls = 14"]),
    (["operating.speed='100 m'"], ["operating.speed", "expected angular velocity"]),
])
def test_bad_input_is_one_line_exit_2(capsys, tmp_path, overrides, fragments):
    argv = ["run", SHORT, "--smoke", "--out", tmp_path / "out"]
    for o in overrides:
        argv += ["--set", o]
    code, _, err = run(capsys, *argv)
    assert code == 2
    one_line(err, *fragments)
    assert not (tmp_path / "out" / "summary.json").exists()


def test_the_main_job_runs_the_film_map_and_stays_inside_its_axes(capsys, tmp_path, caplog):
    """The shipped ball-ball map stops at pressure number 0.9 (a rigid Barus film has no solution at 1)
    and at a 50 um gap; a smoke drop with collisions (force above 100 N) queries it only inside its
    axes: thinner films are locked (the solids carry the load), thicker ones scaled self-similarly.
    Before the lock the same run clamped about 24,000 queries."""
    code, _, _ = run(capsys, "run", SHORT, "--smoke", "--set", "analysis.lyapunov_exponents=0",
                     "--set", "output.write=[]", "--out", tmp_path)
    assert code == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["Ball-ball film"] == "map" and s["Largest collision normal force [N]"] > 100.0
    assert s["Film map queries outside axes [-]"] == 0
    assert not any("queried outside their axes" in r.getMessage() for r in caplog.records)


def test_main_job_smoke_states_why_a_lyapunov_exponent_is_missing_without_a_warning(capsys, tmp_path, caplog):
    """The main job's [smoke] run (1 ms, 501 samples) ends while the inner ring is still spinning up
    (detected transient end = the record's end), so no direction has a record: every Wolf and
    Rosenstein entry is None with a note saying so and why, and nothing is logged at WARNING."""
    caplog.set_level("INFO")
    code, _, err = run(capsys, "run", SHORT, "--smoke", "--set", "output.write=[]", "--out", tmp_path)
    assert code == 0, err
    assert "WARNING" not in err and not [r for r in caplog.records if r.levelname == "WARNING"]
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["Lyapunov window start, given (analysis.transient) [s]"] == 0.0
    assert s["Lyapunov window start, detected [s]"] == pytest.approx(0.001)
    assert "not within 1% of the rotor speed at the end" in s["Lyapunov window start, detected, reason"]
    for name in ("x", "y", "z", "radial", "tangential", "axial"):
        assert s[f"Wolf exponent, ball 0 {name} [bits/s]"] is None
        note = s[f"Wolf exponent, ball 0 {name}, note"]
        assert note.startswith("not computed: no record after the window start 0.001 s (the inner ring"), note
    for axis in "xyz":
        assert s[f"Largest Lyapunov exponent, ball 0 {axis} [1/s]"] is None
        assert s[f"Largest Lyapunov exponent, ball 0 {axis}, note"].startswith("not computed: no record after")
    assert s["Lyapunov exponent 1, whole system (Benettin) [1/s]"] > 0.0  # the whole-system exponents still come


def test_co_rotating_coordinates_of_a_circular_orbit_are_zero():
    """A ball on a circle at constant orbital speed has no co-rotating radial or tangential motion (to
    round-off); a radial oscillation and an along-orbit oscillation show up as themselves; z passes
    through; half a revolution is dropped at each end; a record under two revolutions is refused."""
    import numpy as np

    from lubedyn.scenes.dynamics_lyapunov import co_rotating

    t = np.arange(20001) * 5e-6  # 0.1 s, 411 rad/s: about 6.5 revolutions
    rate, R = 411.0, 0.023
    psi = 0.3 + rate * t
    xyz = np.stack([R * np.cos(psi), R * np.sin(psi), 1e-6 * np.sin(2 * np.pi * 900 * t)], axis=1)
    tk, co, why = co_rotating(t, xyz)
    half = int(round(np.pi / rate / 5e-6))
    assert why == "" and tk.size == t.size - 2 * half and tk[0] == t[half]
    assert np.max(np.abs(co[:, :2])) < 1e-12
    assert np.array_equal(co[:, 2], xyz[half:t.size - half, 2])
    # 2 um radial and 5 urad tangential oscillations at 1.3 kHz (not a multiple of the orbital frequency)
    dr = 2e-6 * np.sin(2 * np.pi * 1300 * t)
    dpsi = 5e-6 * np.cos(2 * np.pi * 1300 * t)
    wobbly = np.stack([(R + dr) * np.cos(psi + dpsi), (R + dr) * np.sin(psi + dpsi), xyz[:, 2]], axis=1)
    _, co, _ = co_rotating(t, wobbly)
    assert co[:, 0] == pytest.approx(dr[half:-half] - np.mean(dr[half:-half]), abs=2e-8)
    assert co[:, 1] == pytest.approx(R * dpsi[half:-half], abs=0.05 * R * 5e-6)
    _, _, why = co_rotating(t[:3000], xyz[:3000])
    assert why.startswith("the record (0.015 s) is shorter than two revolutions")


def test_transient_end_is_spin_up_then_collision_rate():
    """The ring reaches the rotor speed (within 1 %) at 10 ms and stays; collisions come every 0.1 ms
    until 16 ms, then every 0.5 ms: the transient ends at the first 2 ms bin from 10 ms whose count is
    at most the later median, 16 ms.  Without a rotor only the collisions count; a ring still
    spinning up at the end gives the record's end."""
    import numpy as np

    from lubedyn.scenes.dynamics_lyapunov import transient_end

    t = np.linspace(0.0, 0.1, 20001)
    rotor = np.full(t.size, 1000.0)
    ring = 1000.0 * np.minimum(1.0, t / 0.0101)
    hits = np.concatenate([np.arange(0.0, 0.016, 1e-4), np.arange(0.016, 0.1, 5e-4)])
    end, reason = transient_end(t, ring, rotor, hits)
    assert end == pytest.approx(0.016) and "from 0.01 s" in reason and "from 0.016 s" in reason
    end, reason = transient_end(t, ring, None, hits)
    assert end == pytest.approx(0.016) and reason.startswith("no rotor")
    end, reason = transient_end(t, 0.5 * ring, rotor, hits)
    assert end == t[-1] and "still spinning up" in reason


def test_per_direction_summary_on_a_synthetic_ball():
    """Ball 0 orbits at constant speed on a circle with Lorenz x (scaled to 5 um) as its axial motion:
    inertial and co-rotating axial exponents are computed (Wolf: bits/s, 1/s, uncertainty,
    convergence, replacements, verdict), the co-rotating radial and tangential directions do not
    move, and Rosenstein's inertial entries stay."""
    import numpy as np

    from types import SimpleNamespace

    from lubedyn.scenes.dynamics_lyapunov import _lyapunov_per_direction
    from lubedyn.dynamics import integrators as I
    from test_lyapunov import LORENZ, LORENZ_L1, lorenz  # tests/ is on sys.path (rootdir conftest, prepend import mode)

    n, dt = 24000, 5e-5  # 1.2 s, 411 rad/s: 78 revolutions
    t = np.arange(n) * dt
    y0 = I.integrate(lorenz, [1.0, 1.0, 20.0], [0.0, 20.0], LORENZ, rtol=1e-10, atol=1e-10).y[-1]
    # Lorenz time scaled by 100 (its 0.01 s sample -> 1e-4 s): lambda = 0.906 x 100 1/s
    z = I.integrate(lorenz, y0, t * 100.0, LORENZ, rtol=1e-10, atol=1e-10).y[:, 0] * 5e-7
    psi = 411.0 * t
    centres = np.zeros((n, 2, 3))
    centres[:, 0, :] = np.stack([0.023 * np.cos(psi), 0.023 * np.sin(psi), z], axis=1)
    case = SimpleNamespace(analysis=SimpleNamespace(transient=0.0, ball=0))
    out = _lyapunov_per_direction(case, t, centres, 1047.0, ring_speed=np.full(n, 1000.0),
                                  rotor_speed=np.full(n, 1000.0), collision_times=[])
    assert out["Lyapunov window start [s]"] == 0.0
    # 1.2 s at 1047 rad/s resolves an exponent (needs 0.281 s: test_record_rule_is_the_measured_...): not gated
    assert out["Lyapunov record needed, per direction [s]"] < 1.2 and "Lyapunov exponents per direction, note" not in out
    for name in ("z", "axial"):
        key = f"Wolf exponent, ball 0 {name}"
        assert out[f"{key} [bits/s]"] > 0.0
        assert out[f"{key} [1/s]"] == pytest.approx(out[f"{key} [bits/s]"] * np.log(2.0))
        assert out[f"{key} uncertainty [bits/s]"] > 0.0 and out[f"{key} replacements [-]"] >= 0
        assert out[f"{key} verdict, record alone"] in ("positive", "not positive", "not resolved")
        assert out[f"{key} surrogate z [-]"] is not None and out[f"{key} settings spread [-]"] is not None
        assert out[f"{key} verdict"] == "positive" or out[f"{key} verdict"].startswith(
            ("not positive", "not distinguishable", "depends on the embedding", "not converged"))
    for name in ("radial", "tangential"):
        assert out[f"Wolf exponent, ball 0 {name} [bits/s]"] is None
        assert out[f"Wolf exponent, ball 0 {name}, note"] == "not computed: the coordinate does not move"
    assert "Largest Lyapunov exponent, ball 0 z [1/s]" in out
    # the guarded verdicts against the known answers: z is Lorenz x in time scaled by 100 (lambda_1 = 90.6
    # 1/s): measured 86.4 1/s (-4.6 %; surrogates z -25, settings spread 0.13), "positive"; with the
    # settings the scene used before the guards (dim 6, delay at the autocorrelation's zero, 457 samples)
    # it was 7.8 1/s, which the guards call "not distinguishable".  x is the circular orbit (lambda = 0):
    # "not positive" (surrogates z -12, spread 0.05).  The co-rotating axial series (z less half a
    # revolution at each end) measured "not converged" (its running estimate moved over 20 %).
    assert out["Wolf exponent, ball 0 z verdict"] == "positive"
    assert out["Wolf exponent, ball 0 z [1/s]"] == pytest.approx(100.0 * LORENZ_L1, rel=0.20)
    assert out["Wolf exponent, ball 0 x verdict"] == "not positive"


def test_rosenstein_shortfall_agrees_with_the_estimator():
    """The reason the scene writes is the estimator's own check: a record it accepts gives '', one it
    refuses gives the refusal's text."""
    import numpy as np

    from lubedyn.dynamics.errors import DynamicsInputError
    from lubedyn.dynamics.lyapunov import largest_lyapunov_rosenstein, rosenstein_shortfall

    t = np.arange(4000) * 1e-3
    x = np.sin(2 * np.pi * 7.0 * t) + 0.3 * np.sin(2 * np.pi * 7.0 * np.sqrt(2.0) * t)
    assert rosenstein_shortfall(x, 1e-3, dim=4, delay=10) == ""
    short = x[:300]
    reason = rosenstein_shortfall(short, 1e-3, dim=4, delay=30)
    assert reason.startswith("300 samples: too short for dim = 4, delay = 30")
    with pytest.raises(DynamicsInputError, match="too short") as info:
        largest_lyapunov_rosenstein(short, 1e-3, dim=4, delay=30)
    assert str(info.value) == f"x has {reason}"


def test_case_tables_are_the_model_groups_one_to_one():
    """Every table of a dynamics case is one frozen group of the model with the same field names (the
    group may hold more: numerical settings the case leaves at their defaults), every required field of a
    group is a key of its table -- but the films group's oil, which is the case's [lubricant] table, the
    one oil table of every scene --, and a model error from a case names the case key without translation."""
    import dataclasses

    from lubedyn.scenes import dynamics as ds
    from lubedyn.dynamics.cageless import CagelessBearing

    for table, attr in CagelessBearing.GROUPS.items():
        cls = CagelessBearing.GROUP_CLASSES[attr]
        assert cls.TABLE == table
        assert {f.name: f for f in dataclasses.fields(CagelessBearing)}[attr].type == cls.__name__
        keys = set(ds.DynamicsCase.model_fields[table].annotation.model_fields)
        names = {f.name: f for f in dataclasses.fields(cls)}
        assert keys <= set(names), (table, keys - set(names))
        required = {n for n, f in names.items() if f.default is dataclasses.MISSING}
        oil = {"viscosity", "pressure_viscosity"} if table == "films" else set()
        assert required <= keys | oil, (table, required - keys)
        assert not keys & oil
    case = load_case(CASES_DIR / "cageless_6206_steady.toml")
    model = ds.build(case).model
    v = case.lubricant.viscosity
    assert (model.films.viscosity, model.films.pressure_viscosity) == (v.eta0, v.alpha) == (0.05, 1.85e-8)
    assert model.slots.width == case.slots.width and model.fidelity.dof == case.model.dof
    assert model.films.ball_ball == case.films.ball_ball == "map" and model.films.map is not None
    with pytest.raises(InputError, match=r"^slots.width = 0.01 m must be < the groove diameter"):
        ds.build(case.model_copy(update={"slots": case.slots.model_copy(update={"width": 0.01})}))


def test_benettin_window_starts_after_the_detected_transient_when_the_record_allows():
    """The whole-system exponents average over the same window as the per-direction ones, unless the
    detected transient takes more than half the record (the 20 ms main job: spin-up and collisions end
    near 15 ms), or nothing was detected."""
    from lubedyn.scenes.dynamics_lyapunov import benettin_start

    assert benettin_start(0.02, 0.03, 0.4) == 0.03          # a 0.4 s drop: after the detected 30 ms
    assert benettin_start(0.005, 0.01496, 0.02) == 0.005    # the main job: 10 ms of 15 left -> given
    assert benettin_start(0.02, None, 0.4) == 0.02          # nothing detected (steady runs)
    assert benettin_start(0.05, 0.03, 0.4) == 0.05          # the given start is later
    assert benettin_start(0.0, 0.2, 0.4) == 0.2             # exactly half: still allowed


def test_record_rule_is_the_measured_exponent_and_boundary_term():
    """The record an exponent needs (issue 42, decision 1) from the 10,000 rpm drop's measurement
    (benchmarks/results/paper_b/tangent_directions_10krpm.json, 4 members over 4 s): lambda_1 the first
    tangent vector's mean, a the largest boundary term fitted over the directions; lambda T >= 2 a, i.e.
    2 x 7.6 / 54.1 = 0.281 s at 10,000 rpm, half that at 20,000 rpm; the README's main job (15 ms after
    its 5 ms transient) has lambda T = 0.81, below 1."""
    import math
    from pathlib import Path

    from lubedyn.scenes import dynamics_lyapunov as L

    measured = json.loads((Path(__file__).resolve().parents[1] / "benchmarks" / "results" / "paper_b"
                           / "tangent_directions_10krpm.json").read_text())["directions"]
    assert L.REFERENCE_EXPONENT == pytest.approx(measured["lambda_1 (first vector)"]["mean [1/s]"], abs=0.05)
    assert L.BOUNDARY_TERM == pytest.approx(max(d["a [-]"] for d in measured.values()), abs=0.05)
    rpm = 2 * math.pi / 60
    need = L.record_need("x", 0.015, 0.005, 10_000 * rpm)
    assert need.needed == pytest.approx(2 * 7.6 / 54.1, rel=1e-3) and need.exponent * 0.015 < 1.0
    assert not need.resolves and "resolves no exponent; needs 0.281 s" in need.note()
    assert L.record_need("x", 0.2, 0.0, 20_000 * rpm).needed == pytest.approx(0.5 * need.needed)
    assert L.record_need("x", 0.29, 0.0, 10_000 * rpm).resolves


def _synthetic_ball(n, dt=5e-5):
    """Ball 0 on a circle at 411 rad/s with Lorenz x (time scaled by 100: lambda_1 = 90.6 1/s) as its axial
    motion, as in :func:`test_per_direction_summary_on_a_synthetic_ball`."""
    import numpy as np

    from lubedyn.dynamics import integrators as I
    from test_lyapunov import LORENZ, lorenz

    t = np.arange(n) * dt
    y0 = I.integrate(lorenz, [1.0, 1.0, 20.0], [0.0, 20.0], LORENZ, rtol=1e-10, atol=1e-10).y[-1]
    z = I.integrate(lorenz, y0, t * 100.0, LORENZ, rtol=1e-10, atol=1e-10).y[:, 0] * 5e-7
    centres = np.zeros((n, 2, 3))
    centres[:, 0, :] = np.stack([0.023 * np.cos(411.0 * t), 0.023 * np.sin(411.0 * t), z], axis=1)
    return t, centres


@pytest.mark.parametrize("force", [False, True])
def test_a_short_record_says_what_it_needs_unless_forced(force):
    """A 0.1 s record at 10,000 rpm (lambda T = 5.4 against 15.2 needed): every per-direction entry None
    with "not computed: the record of ... resolves no exponent; needs 0.281 s"; with analysis.force the
    estimators run (the Lorenz axial direction gets a Wolf exponent) and the summary says the run was
    forced.  The 1.2 s record of test_per_direction_summary_on_a_synthetic_ball computes unforced."""
    import math
    from types import SimpleNamespace

    import numpy as np

    from lubedyn.scenes.dynamics_lyapunov import _lyapunov_per_direction

    t, centres = _synthetic_ball(2000)
    case = SimpleNamespace(analysis=SimpleNamespace(transient=0.0, ball=0, force=force))
    out = _lyapunov_per_direction(case, t, centres, 10_000 * 2 * math.pi / 60, ring_speed=np.full(t.size, 1000.0),
                                  rotor_speed=np.full(t.size, 1000.0), collision_times=[])
    assert out["Lyapunov record needed, per direction [s]"] == pytest.approx(0.281, abs=1e-3)
    note = out["Lyapunov exponents per direction, note"]
    if not force:
        assert note.startswith("not computed: the record of ball 0's per-direction exponents (0.1 s")
        assert "resolves no exponent; needs 0.281 s" in note
        for name in ("x", "y", "z", "radial", "tangential", "axial"):
            assert out[f"Wolf exponent, ball 0 {name} [bits/s]"] is None
            assert out[f"Wolf exponent, ball 0 {name}, note"] == note
        for axis in "xyz":
            assert out[f"Largest Lyapunov exponent, ball 0 {axis} [1/s]"] is None
    else:
        assert note.startswith("forced (analysis.force = true): the record of ball 0's")
        assert out["Wolf exponent, ball 0 z [bits/s]"] is not None
        assert out["Wolf exponent, ball 0 z verdict"] != "not computed"


def test_main_job_smoke_unforced_writes_why_the_spectrum_is_not_computed(capsys, tmp_path):
    """The main job's smoke run (1 ms) with analysis.force = false: the whole-system spectrum is not
    computed (its 0.9 ms window resolves no exponent; needs 0.281 s), in summary.json and on the terminal;
    the smoke default (force = true) computes it (test_main_job_smoke_states_why_...)."""
    code, out, err = run(capsys, "run", SHORT, "--smoke", "--set", "analysis.force=false", "--set",
                         "output.write=[]", "--out", tmp_path)
    assert code == 0, err
    s = json.loads((tmp_path / "summary.json").read_text())
    for i in (1, 2):
        assert s[f"Lyapunov exponent {i}, whole system (Benettin) [1/s]"] is None
        assert s[f"Lyapunov exponent {i}, whole system (Benettin) verdict"] == "not computed"
    note = s["Lyapunov exponents, whole system, note"]
    assert note.startswith("not computed: the record of the whole-system spectrum") and "needs 0.281 s" in note
    assert "Benettin time [s]" not in s
    assert f"Lyapunov exponents, whole system: {note}" in out
