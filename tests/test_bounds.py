"""No impossible number leaves a run: every output with a physical bound is checked against it
(:mod:`lubedyn.bounds`), before anything is written.

The issue's case: paper A's roller/inner-race line contact at a slide-to-roll ratio of 0.05 wrote a
traction coefficient of 3.8e20 with exit 0 (a Newtonian shear at the Hertz zone's piezoviscous
viscosity, then the default).  Now the default is the limited law and the Newtonian answer is refused.
"""
from __future__ import annotations

import json
import math

import pytest

from lubedyn import bounds, cli

from lubedyn.scenes import film as film_scene
from lubedyn.config import CASES_DIR, load_case

BOUND_LINE = "is outside its bound"


def run(capsys, tmp_path, case, *sets, out="out"):
    argv = ["run", case, "--smoke", "--out", str(tmp_path / out)]
    for s in sets:
        argv += ["--set", s]
    code = cli.main(argv)
    _, err = capsys.readouterr()
    return code, err


def summary_of(tmp_path, out="out"):
    return json.loads((tmp_path / out / "summary.json").read_text())


def test_newtonian_traction_at_ehl_pressure_is_refused_in_one_line_and_writes_nothing(capsys, tmp_path):
    """The 3.8e20 of main: exit 1, one line naming the output, its value and the bound; a previous
    run's folder is left as it was."""
    code, _ = run(capsys, tmp_path, "ehl_roller_slice", "operating.slide_to_roll=0.05")
    assert code == 0
    before = (tmp_path / "out" / "summary.json").read_bytes()
    code, err = run(capsys, tmp_path, "ehl_roller_slice", "operating.slide_to_roll=0.05", "traction.model=newtonian")
    assert code == cli.EXIT_FAILED
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("lubedyn: error: Traction coefficient [-] = 3.8e+20 " + BOUND_LINE)
    assert "|value| <= 1" in lines[0] and "strict = false" in lines[0]
    assert (tmp_path / "out" / "summary.json").read_bytes() == before


def test_not_strict_writes_the_number_with_a_warning(capsys, tmp_path):
    code, err = run(capsys, tmp_path, "ehl_roller_slice", "operating.slide_to_roll=0.05", "traction.model=newtonian",
                    "validity.strict=false")
    assert code == 0, err
    s = summary_of(tmp_path)
    assert s["Traction coefficient [-]"] > 1e19
    assert [w for w in s["Warnings"] if w.startswith("Traction coefficient [-] = 3.8e+20 " + BOUND_LINE)]
    assert "lubedyn: WARNING: lubedyn.bounds: Traction coefficient [-]" in err


@pytest.mark.parametrize("case, srr", [("ehl_roller_slice", 0.05), ("ehl_roller_slice", 5.0),
                                       ("ehl_ball_inner_race", 0.01), ("ehl_ball_inner_race", 5.0)])
def test_default_traction_is_the_limited_law_within_its_closed_form_bound(capsys, tmp_path, case, srr):
    """The default law caps the shear at tau_L0 + gamma p, so the coefficient F / W can be no larger
    than gamma + tau_L0 A / W (A: the solved domain's area or length, an upper bound on where the film
    shears), and no smaller than 0."""
    code, err = run(capsys, tmp_path, case, f"operating.slide_to_roll={srr}")
    assert code == 0, err
    s = summary_of(tmp_path)
    mu = s["Traction coefficient [-]"]
    r = load_case(tmp_path / "out" / "case.resolved.toml")
    tau0, gamma = r.traction.limiting_shear_stress, r.traction.limiting_shear_slope
    assert r.traction.model == "limiting_shear"
    if "Load per length [N/m]" in s:  # line: the domain [x_min, x_max] Hertz half-widths
        area, load = (r.grid.x_max - r.grid.x_min) * s["Hertz half-width along x [m]"], s["Load per length [N/m]"]
    else:
        b, a = s["Hertz semi-axis along x [m]"], s["Hertz semi-axis along y [m]"]
        area, load = (r.grid.x_max - r.grid.x_min) * b * 2 * r.grid.y_max * a, s["Load [N]"]
    assert 0.0 < mu <= gamma + tau0 * area / load < 1.0


def test_limited_traction_rises_with_sliding(capsys, tmp_path):
    """The limited law's stress is monotone in the sliding speed: so is the coefficient."""
    mus = []
    for i, srr in enumerate((0.01, 0.1, 1.0)):
        code, err = run(capsys, tmp_path, "ehl_roller_slice", f"operating.slide_to_roll={srr}", out=f"o{i}")
        assert code == 0, err
        mus.append(summary_of(tmp_path, f"o{i}")["Traction coefficient [-]"])
    assert mus[0] < mus[1] < mus[2]


def test_violations_of_each_kind():
    v = bounds.violations
    assert v({"Cavitated area fraction [-]": 1.3})[0].startswith("Cavitated area fraction [-] = 1.3 " + BOUND_LINE
                                                                 + " 0 <= value <= 1")
    assert v({"Mean void fraction [-]": -0.01})
    assert v({"Eccentricity ratio [-]": 1.2})
    assert v({"Largest value of Traction coefficient [-]": -1.5})  # |value|
    assert v({"Minimum film thickness [m]": -1e-9})
    # scaled bounds: skipped without the scale, applied with it
    assert not v({"Central film thickness [m]": 1e-3})
    assert v({"Central film thickness [m]": 1e-3}, {"radius": 5e-3})[0].endswith(
        "(Reynolds' equation is a thin-film law (film << radius of curvature); a film a tenth of the radius is "
        "far outside it)")
    assert v({"Maximum pressure [Pa]": 2e10}, {"hertz_pressure": 6.6e8})
    assert not v({"Maximum pressure [Pa]": 1.5e9}, {"hertz_pressure": 6.6e8})
    assert v({"Largest cup load [N]": -3.0}) and v({"Cone loads [N]": [10.0, -1.0]})
    assert not v({"Load x [N]": -3.0, "Largest collision force x [N]": -2.0})  # components have a sign
    assert v({"Force balance error [-]": 0.02})
    assert v({"Load [N]": 500.0}, {"applied_load": 723.0})
    assert not v({"Load [N]": 723.0 * (1 + 1e-6)}, {"applied_load": 723.0})
    # statistics nested below a key are checked; NaN ("not computed"), booleans and text are not numbers
    assert v({"Cavitated area fraction [-]": {"mean": 0.2, "largest": 1.5}})[0].startswith(
        "Cavitated area fraction [-] / largest = 1.5")
    assert not v({"Cavitated area fraction [-]": math.nan, "Converged [-]": True, "Traction coefficient [-]": "n/a"})
    assert v({"Traction coefficient [-]": math.inf})
    # a nested value whose whole path a bound names: the tapered scene's raceway films
    block = "Raceway films (lubricant.raceway_film = 'grease_ehl')"
    films = {"cup": {"EHL central film [um]": 0.41, "Formula film [um]": 0.68, "Factor h_EHL/h_formula [-]": 0.60,
                     "Effective viscosity [Pa s]": 0.048, "Line load [N/m]": 1.5e5}}
    assert not v({block: films})
    films["cup"]["EHL minimum film [um]"] = -0.02
    films["cup"]["Effective viscosity [Pa s]"] = -1.0
    found = v({block: films})
    assert len(found) == 2 and found[0].startswith(f"{block} / cup / Effective viscosity [Pa s] = -1 " + BOUND_LINE)
    assert not v({"Line load [N/m]": -1.0})  # a path bound does not reach a top-level key of another name
    # the Lyapunov guards' figures and the RK4 step
    assert v({"Wolf exponent, ball 0 z window uncertainty [bits/s]": -3.0})
    assert v({"Lyapunov exponent 1, whole system (Benettin) uncertainty [1/s]": -1.0})
    assert v({"Wolf exponent, ball 0 x settings spread [-]": -0.1})
    assert v({"Wolf exponent, ball 0 x false-neighbour dimension [-]": 0})
    assert v({"RK4 step [s]": -1e-6}) and v({"RK4 step bound [s]": -1e-6})
    assert not v({"Wolf exponent, ball 0 z window uncertainty [bits/s]": 49.99, "Wolf exponent, ball 0 x settings "
                  "spread [-]": 0.75, "Wolf exponent, ball 0 x false-neighbour dimension [-]": 4,
                  "RK4 step [s]": 2.857e-6, "Wolf exponent, ball 0 z [bits/s]": -717.8})


def test_strict_raises_the_first_and_counts_the_rest():
    with pytest.raises(bounds.ImplausibleResult, match=r"^Traction coefficient \[-\] = 2 .*; and 1 more: not a"):
        bounds.enforce({"Traction coefficient [-]": 2.0, "Eccentricity ratio [-]": 3.0})
    s = bounds.enforce({"Traction coefficient [-]": 2.0, "Warnings": ["earlier"]}, strict=False)
    assert s["Warnings"][0] == "earlier" and s["Warnings"][1].startswith("Traction coefficient")


def test_viscous_pressure_scale_against_the_inclined_slider_closed_form():
    """The film scene's viscous scale 6 eta U L / h_min^2: the inclined slider's largest pressure is
    K / (4 (1 + K)(2 + K)) of it (Hamrock, Fundamentals of Fluid Film Lubrication, ch. 8: K = h_in/h_out - 1)."""
    case = load_case(CASES_DIR / "inclined_slider.toml")
    r = film_scene.run(case)
    scale = film_scene.bound_scales(case, r.film, r.solution)["viscous_pressure"]
    K = case.gap.h_in / case.gap.h_out - 1.0
    assert r.solution.p_max / scale == pytest.approx(K / (4 * (1 + K) * (2 + K)), rel=2e-3)
    assert not bounds.violations(r.summary, film_scene.bound_scales(case, r.film, r.solution))
