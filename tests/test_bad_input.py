"""Bad input and failing solves give clear errors, never NaN fields (library level).

The CLI-level messages and exit codes are pinned in test_cli.py.
"""
import numpy as np
import pytest

from lubedyn.lubrication import (
    Cavitation, ConvergenceError, Film, InclinedSlider, InputError, JournalBearing, Lubricant,
    SolverOptions, SpherePlane, FunctionGap, Barus, PocketedSlider,
)
from lubedyn.lubrication import mesh

LUB = Lubricant.newtonian(0.01)


def test_zero_gap_is_rejected_with_location():
    gap = FunctionGap(lambda x: 1e-6 * (x[0] - 0.005) / 0.005)  # h = 0 at x = 5 mm, < 0 before
    with pytest.raises(InputError, match=r"gap h = .* m at x = .*must be > 0"):
        Film(mesh.interval(0, 0.01, 20), gap, LUB, velocity_lower=(1.0,)).solve()


def test_negative_geometry_is_rejected():
    with pytest.raises(InputError, match="radial clearance"):
        JournalBearing(0.02, -1e-5)
    with pytest.raises(InputError, match="eccentricity ratio = 1 must be < 1"):
        JournalBearing.from_ratio(0.02, 1e-5, 1.0)
    with pytest.raises(InputError, match="h_in"):
        InclinedSlider(0.0, 1e-6, 0.01)


def test_mesh_points_closer_than_round_off_are_rejected():
    pts = np.array([0.0, 0.004, 0.004 + 1e-15, 0.01])
    with pytest.raises(InputError, match=r"mesh points 1 and 2 are 1e-15 m apart, closer than 1e-12 of the domain"):
        mesh.interval(0, 0, 0, points=pts)
    assert mesh.interval(0, 0, 0, points=[0.0, 0.004, 0.004 + 1e-13, 0.01]).t.shape[1] == 3  # 1e-11 of L: allowed


def test_disk_order_is_checked():
    with pytest.raises(InputError, match="mesh order = 3"):
        mesh.disk(1.0, 2, order=3)


def test_no_dirichlet_boundary_is_rejected():
    film = Film(mesh.interval(0, 0.01, 20), InclinedSlider(2e-6, 1e-6, 0.01), LUB,
                velocity_lower=(1.0,), dirichlet={})
    with pytest.raises(InputError, match="no Dirichlet boundary"):
        film.solve()


def test_unknown_options_suggest_close_matches():
    with pytest.raises(InputError, match="did you mean 'reynolds'"):
        Cavitation("reynold")
    with pytest.raises(InputError, match="film.element"):
        Film(mesh.interval(0, 1, 2), InclinedSlider(2e-6, 1e-6, 1), LUB, element="P3")
    with pytest.raises(InputError, match="boundary"):
        Film(mesh.interval(0, 1, 2), InclinedSlider(2e-6, 1e-6, 1), LUB, dirichlet={"lft": 0.0}).solve()


def test_too_few_iterations_raise_convergence_error():
    """The Fowell pocket needs 5 active-set iterations at U = 1 m/s; allow 2."""
    gap = PocketedSlider(1.05e-6, 1.0e-6, 0.01, 0.002, 0.005, 1e-6)
    film = Film(mesh.interval(0, 0.01, 100), gap, LUB, velocity_lower=(1.0,),
                dirichlet={"left": 1e5, "right": 1e5}, cavitation=Cavitation("jfo"),
                options=SolverOptions(max_iter=2))
    with pytest.raises(ConvergenceError, match="did not converge in 2 iterations"):
        film.solve()
    assert film.with_(options=SolverOptions()).solve().info["iterations"] <= 8


def test_jfo_without_supply_is_reported_not_silently_wrong():
    """Where JFO stops working: a periodic journal whose only boundaries sit at the
    cavitation pressure has starved solutions besides the flooded one (the
    cavitated fraction is only transported, never supplied).  The solver must
    stop with a ConvergenceError rather than return one of them; with a supply
    pressure above p_cav the same film converges (9 iterations measured)."""
    R, c, L = 0.025, 50e-6, 0.025
    m = mesh.rectangle(np.linspace(0, 2 * np.pi * R, 49), np.linspace(-L / 2, L / 2, 9), "quad", periodic_x=True)
    gap = JournalBearing.from_ratio(R, c, 0.6, attitude_angle=0.3)
    base = Film(m, gap, Lubricant.newtonian(0.02), velocity_upper=(300.0 * R, 0.0), velocity_lower=(0.0, 0.0),
                cavitation=Cavitation("jfo", 0.0), options=SolverOptions(max_iter=40))
    with pytest.raises(ConvergenceError):
        base.with_(dirichlet={"bottom": 0.0, "top": 0.0}).solve()
    s = base.with_(dirichlet={"bottom": 1e5, "top": 1e5}).solve()
    assert s.info["iterations"] <= 15
    assert np.all(s.pressure >= -1e-6) and 0.0 <= s.fluid_fraction.min() < 1.0
    # the flooded JFO film carries a load close to (and below) the Reynolds-condition film
    s_rey = base.with_(dirichlet={"bottom": 1e5, "top": 1e5}, cavitation=Cavitation("reynolds")).solve()
    ratio = np.hypot(*s.mode_forces.values()) / np.hypot(*s_rey.mode_forces.values())
    assert 0.9 < ratio < 1.1


def test_pressure_divergence_is_reported_for_barus_pole():
    film = Film(mesh.interval(0, 0.02, 40), InclinedSlider(2e-6, 1e-6, 0.02), Lubricant(Barus(0.01, 1e-6)),
                velocity_lower=(2.0,), options=SolverOptions(max_iter=30))
    with pytest.raises(ConvergenceError):
        film.solve()


# --------------------------------------------------------------------------- bearing and slot geometry
from lubedyn.config import CASES_DIR, CaseError, load_case  # noqa: E402

DROP = CASES_DIR / "cageless_6206_10krpm_short.toml"
EHL_BALL = CASES_DIR / "ehl_ball_inner_race.toml"


@pytest.mark.parametrize("case, override, message", [
    # an inner groove radius smaller than the ball gave "bearing.diametral_clearance = 0.0 m must lie in
    # (2.86e-05, -0.002288) m": the key that is wrong is the groove radius
    (DROP, "bearing.inner_groove_radius='4 mm'",
     "bearing.inner_groove_radius = 0.004 must be > ball_diameter/2 = 0.0047625 m"),
    (DROP, "bearing.outer_groove_radius='4.5 mm'",
     "bearing.outer_groove_radius = 0.0045 must be > ball_diameter/2 = 0.0047625 m"),
    (DROP, "bearing.diametral_clearance='2 mm'",
     "bearing.diametral_clearance = 0.002 must be in (-1.665e-05, 0.001332) m"),
    (DROP, "bearing.ball_diameter='50 mm'", "bearing.ball_diameter = 0.05 must be < pitch_diameter = 0.046005 m"),
    # 1 mm gave "gamma = D cos(alpha)/d_m = -0.1038; it must be < 1"
    (EHL_BALL, "bearing.inner_groove_radius='4 mm'", "bearing.inner_groove_radius = 0.004 m must be > D/2"),
    (EHL_BALL, "bearing.diametral_clearance='1 mm'",
     "bearing.diametral_clearance = 0.001 must be < 2 B D = 0.000666 m, where the free contact angle reaches 90 deg"),
    # slots: a slot deeper than the ring ran silently
    (DROP, "slots.depth='20 mm'",
     "slots.depth = 0.02 must be < 0.003235 m, the outer ring's wall under the groove"),
    (DROP, "slots.race='inner'", None),
    (DROP, "slots.length='200 mm'", "slots.length = 0.2 must be < 0.174453 m, the race's circumference"),
    (DROP, "slots.azimuths=['0 deg', '10 deg']",
     "slots.length = 0.0115 must be < 0.00484591 m, the arc between the closest two slots"),
    (DROP, "slots.width='10 mm'", "slots.width = 0.01 must be < 0.00981 m, the groove diameter"),
    (DROP, "slots.edge_radius='1 mm'", "slots.edge_radius = 0.001 must be < 0.001 m"),
    (DROP, "bearing.outer_diameter='55 mm'", "bearing.outer_diameter = 0.055 must be > pitch_diameter + "
                                             "ball_diameter = 0.05553 m"),
])
def test_bearing_geometry_names_the_wrong_key(case, override, message):
    if case == EHL_BALL and override.startswith("bearing.inner_groove"):
        from lubedyn.scenes import ehl as ehl_scene  # the bearing's contact names it (tests/test_cli.py, exit 2)

        with pytest.raises(InputError, match=r"bearing.inner_groove_radius = 0.004 m must be > D/2"):
            ehl_scene.build(load_case(case, overrides=[override]))
        return
    if message is None:  # the same slot in the inner ring fits its 3.24 mm wall
        assert load_case(case, overrides=[override]).slots.race == "inner"
        return
    with pytest.raises(CaseError) as info:
        load_case(case, overrides=[override])
    text = str(info.value)
    assert text.startswith(message), text
    assert "\n" not in text


def test_no_range_message_is_reversed():
    """Every "(lo, hi)" or "[lo, hi]" interval a bad bearing or slot value produces reads lo < hi."""
    import re

    overrides = [f"bearing.{k}='{v} mm'" for k in ("inner_groove_radius", "outer_groove_radius")
                 for v in (1, 4, 4.76)] + [f"bearing.diametral_clearance='{v} mm'" for v in (-1, 1, 2, 5)]
    from lubedyn.scenes import dynamics as dynamics_scene
    from lubedyn.scenes import ehl as ehl_scene

    checked = 0
    for case, scene in ((DROP, dynamics_scene), (EHL_BALL, ehl_scene)):
        for o in overrides:
            try:
                scene.build(load_case(case, overrides=[o]))  # the case, then the model built from it
            except InputError as exc:
                checked += 1
                for lo, hi in re.findall(r"[(\[](-?[0-9.e+-]+), (-?[0-9.e+-]+)[)\]]", str(exc)):
                    assert float(lo) < float(hi), str(exc)
    assert checked == 2 * len(overrides)  # every one is refused (1 mm of clearance: no equilibrium under the load)
