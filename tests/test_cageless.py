"""The cage-less 6206 ball bearing (lubedyn.dynamics.cageless) against paper B's bearing:
quasi-static load distribution from a damped settling run against Jones' rigid-ring
model (lubedyn.lubrication.laws.bearing) and Stribeck's 4.37 Fr/(Z cos a); Hertz deflection against
load (lubedyn.lubrication.laws.contact); ball-train speed against epicyclic kinematics in the
no-slip limit; energy and angular momentum in a frictionless undamped run; the
rotor-drop friction law; bad input."""
import math

import numpy as np
import pytest

from lubedyn.lubrication.laws import bearing as cb
from lubedyn.dynamics import cageless as cg
from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.dynamics.integrators import integrate
from lubedyn.lubrication.laws import contact as hertz
from lubedyn.papers.zhang2024.parameters import cageless_bearing as paper_b  # noqa: E402

FR = 2000.0


def _run(model, y0, T, dt, n_out=21):
    t_out = np.linspace(0.0, T, n_out)
    res = integrate(cg.rhs, y0, t_out, model.args(), method="rk4", dt=dt)
    diag, ring = cg.forces_many(res.t, res.y, model.args())
    return res, diag, ring


@pytest.fixture(scope="module")
def settled():
    """Planar bearing at rest, zero clearance, loaded suddenly by F_r from the unloaded
    geometry, settled by the Hunt-Crossley contact damping (alpha = 2 s/m; the
    ring's damping ratio is ~0.2) over 5 ms."""
    model = paper_b(model=dict(dof="planar", race_damping=2.0), slots=dict(azimuths=()), bearing=dict(ring_mass=0.5),
                    operating=dict(axial_load=0.0, radial_load=FR, gravity=0.0, speed=0.0))
    res, diag, _ = _run(model, model.initial_state(settle=False), 5e-3, 1e-6, n_out=51)
    return model, res, diag


def _jones(model):
    D = model.bearing.ball_diameter
    ri, ro = model.bearing.inner_groove_radius, model.bearing.outer_groove_radius
    Kn = cb.deflection_constant(D, model.bearing.pitch_diameter, ri, ro, 0.0, model.e_star_race)
    return cb.ball_load_distribution(FR, 0.0, model.n_balls, D, ri, ro, Kn)


def test_settled_load_distribution(settled):
    model, res, diag = settled
    Q = diag[-10:, :, cg.D_QI].mean(axis=0)  # last 0.9 ms (residual ring oscillation < 0.1 %)
    Qj, _, _, dr = _jones(model)
    # Jones' rigid-ring model linearises the ring shift (delta_r cos psi): agreement to ~1e-3
    np.testing.assert_allclose(Q, Qj, rtol=0, atol=2e-3 * Qj.max())
    # Stribeck: Q_max = 4.37 F_r/(Z cos a) for zero clearance (Harris & Kotzalas ch. 7), quoted to 3 digits
    assert Q.max() == pytest.approx(4.37 * FR / model.n_balls, rel=5e-3)
    assert -res.y[-10:, 1].mean() == pytest.approx(dr, rel=3e-3)
    # the quasi-static solver of the model (second method) gives the same loads
    y_qs = model.initial_state()
    Qqs = cg.forces(0.0, y_qs, model.args())[0][:, cg.D_QI]
    np.testing.assert_allclose(Q, Qqs, rtol=0, atol=2e-3 * Qj.max())
    assert Qqs.max() == pytest.approx(Qj.max(), rel=1e-3)


def test_hertz_deflection_against_load(settled):
    """Each loaded contact: the overlap measured from the ball and groove-centre
    positions is the Hertz approach of lubedyn.lubrication.laws.contact at that load (0.1 %)."""
    model, res, diag = settled
    y = res.y[-1]
    d = diag[-1]
    D, dm = model.bearing.ball_diameter, model.bearing.pitch_diameter
    R_oc = dm / 2 + D / 2 - model.bearing.outer_groove_radius
    R_ic = dm / 2 - D / 2 + model.bearing.inner_groove_radius
    checked = 0
    for j in range(model.n_balls):
        b = model.ball_offset(j)
        c = y[b + 1] * np.array([math.cos(y[b]), math.sin(y[b])])
        rel = c - y[0:2]
        delta_o = np.linalg.norm(c) - R_oc - (model.bearing.outer_groove_radius - D / 2)
        delta_i = (R_ic - np.linalg.norm(rel)) - (model.bearing.inner_groove_radius - D / 2)
        for delta, Q, race, r in ((delta_i, d[j, cg.D_QI], "inner", model.bearing.inner_groove_radius),
                                  (delta_o, d[j, cg.D_QO], "outer", model.bearing.outer_groove_radius)):
            if Q < 50.0:
                continue
            rx = 0.5 * D * (1 - D / dm) if race == "inner" else 0.5 * D * (1 + D / dm)
            ry = r * D / (2 * r - D)
            ref = hertz.point_contact(Q, rx, ry, model.e_star_race).approach
            assert delta == pytest.approx(ref, rel=1e-3)
            checked += 1
    assert checked >= 8


@pytest.mark.parametrize("dof", ["planar", "6dof"])
def test_ball_train_speed_epicyclic(dof):
    """Balls start at rest on a ring turning at 1000 rpm (preload 8 um, no radial
    load, no gravity): traction drives them to free rolling; with no cage and no drag
    the steady ball train runs at omega_i (1 - D/d_m)/2 and spins at -omega_c d_m/D."""
    model = paper_b(model=dict(dof=dof, traction_limit=0.3, ball_ball=False), slots=dict(azimuths=()),
                    operating=dict(axial_load=0.0, radial_load=0.0, gravity=0.0, speed=1000.0 * math.pi / 30.0),
                    bearing=dict(diametral_clearance=-8e-6))
    y0 = model.initial_state()
    for j in range(model.n_balls):
        b = model.ball_offset(j)
        if dof == "planar":
            y0[b + 3] = y0[b + 5] = 0.0
        else:
            y0[b + 7:b + 13] = 0.0
    res, diag, _ = _run(model, y0, 2e-3, 2e-6)
    wc = 0.5 * model.omega_inner * (1 - model.bearing.ball_diameter / model.bearing.pitch_diameter)
    assert diag[0, :, cg.D_PSIDOT].max() == 0.0  # started at rest
    np.testing.assert_allclose(diag[-5:, :, cg.D_PSIDOT], wc, rtol=2e-3)
    np.testing.assert_allclose(diag[-1, :, cg.D_SPIN], -wc * model.bearing.pitch_diameter / model.bearing.ball_diameter, rtol=2e-3)


@pytest.mark.parametrize("dof", ["planar", "6dof"])
def test_frictionless_undamped_run_conserves_energy_and_angular_momentum(dof):
    """Balls thrown around a preloaded free ring (alternating orbital speeds: the
    neighbours collide elastically, Hertz without film, plasticity, damping or
    friction).  The mechanical energy and the angular momentum about the axis
    are invariants (the outer ring is fixed, its forces pass through the axis)."""
    model = paper_b(model=dict(dof=dof, traction_limit=0.0, race_damping=0.0, yield_stress=None),
                    operating=dict(axial_load=0.0, radial_load=0.0, gravity=0.0, scenario="free"),
                    slots=dict(azimuths=()), bearing=dict(diametral_clearance=-8e-6),
                    films=dict(ball_ball="none", friction_boundary=0.0, friction_film=0.0))
    y0 = model.initial_state()
    rng = np.random.default_rng(3)
    y0[4:6] = 0.05, -0.03
    y0[7] = 50.0
    for j in range(model.n_balls):
        b = model.ball_offset(j)
        w = 43.0 * (1 if j % 2 else -1) + 5.0 * rng.normal()
        if dof == "planar":
            y0[b + 3], y0[b + 4], y0[b + 5] = w, 0.05 * rng.normal(), 100.0 * rng.normal()
        else:
            c = y0[b:b + 3]
            y0[b + 7:b + 10] = w * np.array([-c[1], c[0], 0.0]) + 0.05 * rng.normal(size=3)
            y0[b + 10:b + 13] = 100.0 * rng.normal(size=3)
    E0, L0 = cg.bearing_energy(model, y0), cg.angular_momentum_z(model, y0)
    errs = []
    for dt in (4e-7, 2e-7):
        res, diag, _ = _run(model, y0, 1e-3, dt, n_out=101)
        E = np.array([cg.bearing_energy(model, y) for y in res.y])
        L = np.array([cg.angular_momentum_z(model, y) for y in res.y])
        errs.append(np.abs(E / E0 - 1).max())
        assert np.abs(L / L0 - 1).max() < 1e-11
    assert (diag[:, :, cg.D_BBN] > 0).sum() >= 10  # collisions did happen
    # RK4 energy error: < 1e-6 and shrinking with the step (non-smooth contact onsets limit the order)
    assert errs[1] < 1e-6 and errs[1] < 0.5 * errs[0]


def test_rotor_drop_friction_law():
    """Rotor drop: while the rotor slips on the inner ring (tanh ~ 1) it decelerates
    at mu F_r r_c/J_rotor exactly, whatever the balls do."""
    model = paper_b(operating=dict(scenario="drop", speed=10000.0 * math.pi / 30.0))
    y0 = model.initial_state()
    assert y0[7] == 0.0 and y0[8] == pytest.approx(10000 * math.pi / 30)
    # dt = 1 us: at 2 us RK4 is beyond its real-axis limit for the race traction of the balls at rest
    # (rate ~1.5e6 1/s, h lambda ~ 3 > 2.785; integrators module docstring), the ball slips chatter for
    # the first steps and the growth guard stops the run; at 1 us its estimate stays <= 2.54
    res, diag, ring = _run(model, y0, 1e-3, 1e-6, n_out=11)
    decel = model.operating.rotor_friction * model.operating.radial_load * model.operating.rotor_contact_radius / model.bearing.rotor_inertia
    np.testing.assert_allclose(res.y[:, 8], y0[8] - decel * res.t, rtol=1e-9)
    np.testing.assert_allclose(ring[1:, 4], model.operating.rotor_friction * model.operating.radial_load * model.operating.rotor_contact_radius,
                               rtol=1e-9)
    assert 0.0 < res.y[-1, 7] < res.y[-1, 8]  # the inner ring is being spun up


def test_slot_takes_groove_support_away():
    """The bottom ball over the outer-ring slot loses its groove contact and rests on
    the slot edges, the radial load moves to its neighbours."""
    plain = paper_b(model=dict(dof="planar"), operating=dict(axial_load=0.0, scenario="drop"), slots=dict(azimuths=()))
    slot = plain.replace(slots=dict(azimuths=(math.radians(270.0),)))
    d0 = cg.forces(0.0, plain.initial_state(), plain.args())[0]
    d1 = cg.forces(0.0, slot.initial_state(), slot.args())[0]
    assert d1[0, cg.D_QO] < 1e-6 * d0[0, cg.D_QO] and d1[0, cg.D_QE] > 0.0
    assert d1[1, cg.D_QI] > d0[1, cg.D_QI] and d1[0, cg.D_QI] < d0[0, cg.D_QI]


@pytest.mark.parametrize("dof", ["planar", "6dof"])
def test_kernel_compiled_matches_python(dof):
    kw = dict(axial_load=0.0) if dof == "planar" else {}
    model = paper_b(model=dict(dof=dof), operating=dict(scenario="drop", **kw))
    y = model.initial_state()
    b = model.ball_offset(1)
    y[b + 3 if dof == "planar" else b + 8] += 5.0  # a ball moving towards its neighbour
    if dof == "planar":
        y[b] -= 0.0995
    else:
        y[b:b + 2] = y[b:b + 2] @ np.array([[math.cos(-0.0995), math.sin(-0.0995)],
                                            [-math.sin(-0.0995), math.cos(-0.0995)]])
    a = model.args()
    d1, d2 = np.empty_like(y), np.empty_like(y)
    cg.rhs(0.0, y, a, d1)
    cg._evaluate.py_func(0.0, y, a, d2, np.zeros((model.n_balls, cg.N_DIAG)), np.zeros(cg.N_RING_DIAG))
    np.testing.assert_allclose(d1, d2, rtol=1e-12, atol=1e-9)
    assert cg.forces(0.0, y, a)[0][0, cg.D_BBN] > 0.0


def _slot_weight_reference(psi, z, azimuths, R_race, P):
    """numpy reference of the slot weight (module docstring of lubedyn.dynamics.cageless): the largest
    w_s(s) w_z(z) over the slots, w(x) = (1 - tanh((|x| - half)/blend))/2, s = R_race wrap(psi - az),
    exactly 0 for |s| > L_s/2 + 10 blend (and the largest w_s alone)."""
    half_l, half_w, blend = 0.5 * P.sl, 0.5 * P.sw, P.sblend
    far = half_l + 10.0 * blend
    best = np.zeros_like(psi)
    best_s = np.zeros_like(psi)
    for az in azimuths:
        s = R_race * ((psi - az + np.pi) % (2.0 * np.pi) - np.pi)
        ws = np.where(np.abs(s) > far, 0.0, 0.5 * (1.0 - np.tanh((np.abs(s) - half_l) / blend)))
        wz = 0.5 * (1.0 - np.tanh((np.abs(z) - half_w) / blend))
        best = np.maximum(best, ws * wz)
        best_s = np.maximum(best_s, ws)
    return best, best_s


@pytest.mark.parametrize("compiled", [True, False])
@pytest.mark.parametrize("race", ["outer", "inner"])
def test_slot_weight_skip_keeps_every_slot_point(compiled, race):
    """The rhs skips points far from a slot with a dot product before its atan2 (a 2.6x faster rhs
    came partly from that); no point the arc-length test keeps may be lost: points at
    |s| = far (1 -+ 1e-6), inside the slot and all round the race, against a numpy reference."""
    model = paper_b(slots=dict(azimuths=(math.radians(270.0), math.radians(30.0)), race=race))
    a = model.args()
    P, slots = a.P[0], a.slots
    theta = 0.7 if race == "inner" else 0.0  # an inner-ring slot turns with the ring
    r = 0 if race == "outer" else 1
    R_race = P.ro + P.roc if r == 0 else P.ric - P.ri
    far = 0.5 * P.sl + 10.0 * P.sblend
    az = slots[:, 0] + theta * r
    ds = far / R_race * np.array([0.0, 0.2, 0.5, 0.9, 1.0 - 1e-6, 1.0 + 1e-6, 1.005, 1.02, 3.0])
    psi = np.concatenate([az[0] + ds, az[0] - ds, az[1] + ds, np.linspace(-np.pi, np.pi, 97)])
    z = np.tile([0.0, 1.0e-3, 1.75e-3, 3e-3], psi.size // 4 + 1)[:psi.size]
    sdir, cfar = np.empty((slots.shape[0], 2)), np.empty(2)
    sd = cg._slot_directions if compiled else cg._slot_directions.py_func
    sw = cg._slot_weight if compiled else cg._slot_weight.py_func
    sd(P, slots, theta, sdir, cfar)
    got = np.array([sw(R_race * math.cos(p), R_race * math.sin(p), zz, r, theta, slots, R_race, P, sdir, cfar[r])
                    for p, zz in zip(psi, z)])
    ref, ref_s = _slot_weight_reference(psi, z, az, R_race, P)
    np.testing.assert_allclose(got[:, 0], ref, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(got[:, 1], ref_s, rtol=1e-12, atol=1e-15)
    # the points just inside the reach carry their tiny weight (not skipped), those beyond carry none
    k_in, k_out = 4, 5
    assert 1e-10 < got[k_in, 1] < 1e-8 and got[k_out, 1] == 0.0


def test_bad_input():
    """Each error names the case key it is about, in its message and as ``key``."""
    cases = [
        (dict(bearing=dict(n_balls=16)), "bearing.n_balls", "do not fit the pitch circle"),
        (dict(model=dict(dof="planar")), "operating.axial_load", "needs model.dof = '6dof'"),
        (dict(model=dict(dof="6dfo")), "model.dof", "did you mean '6dof'"),
        (dict(films=dict(ball_ball="map")), "films.map", "is needed with films.ball_ball = 'map'"),
        (dict(operating=dict(radial_lod=1.0)), "operating.radial_lod", "is not a key of \\[operating\\]; did you "
                                                                       "mean 'radial_load'"),
        (dict(operating=dict(radial_load=-1.0)), "operating.radial_load", "must be a finite number >= 0"),
        (dict(slots=dict(width=0.02)), "slots.width", "must be < the groove diameter"),
        (dict(speeds=dict(x=1)), "speeds", "not a group of the bearing model"),
    ]
    for changes, key, words in cases:
        with pytest.raises(DynamicsInputError, match=words) as err:
            paper_b(**changes)
        assert err.value.key == key and str(err.value).startswith(key)
    with pytest.raises(DynamicsInputError, match="operating.axial_load = 1e[+]06 N") as err:
        paper_b(operating=dict(axial_load=1e6), slots=dict(azimuths=())).initial_state()
    assert err.value.key == "operating.axial_load"


def test_initial_arrangement_and_seeded_perturbations():
    """[initial]: explicit azimuths place the balls where given; a seeded jitter and ring kick give the same
    start for the same seed (bit for bit) and another start for another seed; the kick has the asked
    magnitude; jitter and kick of zero leave the default start untouched; impossible arrangements are
    one-line errors naming the key."""
    base = paper_b(operating=dict(scenario="drop"), slots=dict(azimuths=()))
    y0 = base.initial_state()
    assert np.array_equal(base.replace(initial=dict(seed=7)).initial_state(), y0)
    pert = base.replace(initial=dict(jitter=math.radians(1.0), kick=2e-3, seed=7))
    a, b = pert.initial_state(), pert.initial_state()
    c = pert.replace(initial=dict(seed=8)).initial_state()
    assert np.array_equal(a, b) and not np.array_equal(a, c)
    assert math.hypot(a[4], a[5] + base.operating.drop_speed) == pytest.approx(2e-3, rel=1e-12)
    centres = np.array([a[base.ball_offset(j):base.ball_offset(j) + 2] for j in range(base.n_balls)])
    even = base.initial.first_ball_azimuth + 2 * np.pi * np.arange(base.n_balls) / base.n_balls
    moved = np.angle(np.exp(1j * (np.arctan2(centres[:, 1], centres[:, 0]) - even)))
    assert 0 < np.abs(moved).max() <= math.radians(1.0) + 1e-9
    given = tuple(np.linspace(0.1, 0.1 + 2 * np.pi, base.n_balls, endpoint=False))
    y = base.replace(initial=dict(azimuths=given)).initial_state()
    b0 = base.ball_offset(0)
    assert math.atan2(y[b0 + 1], y[b0]) == pytest.approx(0.1, abs=1e-12)
    for bad, key in ((dict(azimuths=(0.0, 1.0)), "initial.azimuths"), (dict(jitter=0.3), "initial.jitter"),
                     (dict(seed=-1), "initial.seed"), (dict(kick=-1.0), "initial.kick")):
        with pytest.raises(DynamicsInputError) as err:
            base.replace(initial=bad).initial_state()
        assert err.value.key == key and str(err.value).startswith(key)
