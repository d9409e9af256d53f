"""The cone's tilt as an option (``operating.cone_tilt = "free"``) against independent
values: the bearing's effective load centre (where the cup normals through the contact centres meet the
axis, from the geometry alone), the quasi-static solver's tilt stiffness (a finite difference of a separate
2-D implementation) against a damped dynamic run, the virtual work of the kernel's own contact energy, and
the locked model's trajectory recorded before the option existed (bit for bit)."""
from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from lubedyn.config import CASES_DIR
from lubedyn.papers.wu2018.parameters import tapered_geometry
from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.dynamics.integrators import integrate
from lubedyn.dynamics.tapered import groups as G
from lubedyn.dynamics.tapered import kernels as K
from lubedyn.dynamics.tapered.quasistatic import solve
from lubedyn.lubrication.errors import InputError

from test_trb_dynamics import bearing

RPM = math.pi / 30
DATA = Path(__file__).parent / "data"


def tilted(speed=0.0, slices=5, damping=0.32, contacts=True, **operating):
    """The test bearing of tests/test_trb_dynamics.py (no cage, no friction) with the cone's tilt free."""
    tb = bearing(speed=speed, slices=slices, contacts=contacts)
    op = dict(speed=speed, axial="locked", radial_load=20e3, cone_tilt="free") | operating
    return replace(tb, operating=G.Operating(**op), fidelity=replace(tb.fidelity, damping_alpha=damping))


def load_centre(g):
    """The effective load centre [m] from the cone's reference point: the cup's normal through the roller's
    mid-point (x = 0, r = R_p) meets the axis at x = -R_p n_x/n_r (the cup's normal (n_x, n_r))."""
    n = g.cup_normal
    return -g.pitch_radius * n[0] / n[1]


def test_with_the_load_at_the_effective_load_centre_the_cone_does_not_tilt():
    """Each roller's net force on the cone is, at rest, the cup's force on the roller (the roller is in
    balance), whose line of action runs along the cup's normal through the contact centre: every roller's
    line meets the axis at the same point, 17.6 mm towards the large end (computed here from the
    geometry), so a radial load there makes no moment.  With the tilt free and Fr 20 kN there, the 2-D
    solver's tilt is below 1 % of the tilt with the load at the rollers' mid-plane (measured 0.5 %,
    4.9e-6 against 9.5e-4 rad: the rollers' own tilt shifts the cup's pressure centre slightly), and a
    2 ms run from that start stays there (the tilt moves by less than 1e-2 of the mid-plane tilt)."""
    g = tapered_geometry()
    xc = load_centre(g)
    assert xc == pytest.approx(0.0176, abs=2e-4)
    mid = solve(g, radial_load=20e3, axial_displacement=0.0, n_slices=5, cone_tilt="free")
    centre = solve(g, radial_load=20e3, axial_displacement=0.0, n_slices=5, cone_tilt="free", load_offset=xc)
    ref = abs(mid.cone_tilt[1])
    assert ref > 5e-4
    assert np.max(np.abs(centre.cone_tilt)) < 1e-2 * ref
    tb = tilted(load_offset=xc)
    args, y0 = tb.args(), tb.start_state()
    res = integrate(K.rhs, y0, np.linspace(0.0, 2e-3, 5), args, method="dopri5", rtol=1e-7, atol=1e-12)
    k = tb.tilt_index
    assert np.max(np.abs(res.y[:, k:k + 2])) < 1e-2 * ref


def test_the_tilt_stiffness_of_the_quasi_static_solver_is_where_a_damped_run_settles():
    """Fa 15 kN (axial DOF free) and Fr 10 kN at rest, alpha_e 3.2 s/m (damped): the cone starts at the
    quasi-static equilibrium with the radial load at the rollers' mid-plane, then the load moves 10 mm
    towards the large end (a 100 N m step).  The quasi-static tilt stiffness, the finite difference
    K = Delta M/Delta theta_z of the 2-D solver at the two load points (7.91e5 N m/rad), against the
    run's settled tilt after 25 ms: within 1 % (measured 0.1 %); every loaded roller's cup, cone and
    flange load is back on the quasi-static values within 1 % (measured 0.2-0.5 %; the rollers, with no
    cage at rest, slowly drift around: the tilted cone pushes them across at second order, 7e-3 rad in
    40 ms, which moves the loads by 0.9 % by then)."""
    fr, xa, xb = 10e3, 0.0, 0.01
    ta = tilted(damping=3.2, axial="force", axial_load=15e3, radial_load=fr, load_offset=xa)
    tb = replace(ta, operating=replace(ta.operating, load_offset=xb))
    qa, qb = ta.quasi_static(), tb.quasi_static()
    k_qs = fr * (xb - xa) / (qb.cone_tilt[1] - qa.cone_tilt[1])
    assert k_qs == pytest.approx(7.91e5, rel=0.01)
    y0 = ta.start_state(qa)
    args = tb.args(qb)
    res = integrate(K.rhs, y0, np.linspace(0.0, 25e-3, 3), args, method="dopri5", rtol=1e-7, atol=1e-12)
    k = ta.tilt_index
    k_dyn = fr * (xb - xa) / (res.y[-1, k + 1] - y0[k + 1])
    assert k_dyn == pytest.approx(k_qs, rel=0.01)
    assert res.y[-1, k + 1] == pytest.approx(qb.cone_tilt[1], rel=0.01)
    L = K.loads_many(res.y, args)
    for i, ref in enumerate((qb.cup_loads, qb.cone_loads, qb.flange_loads)):
        m = ref > 0.05 * ref.max()
        assert np.max(np.abs(L[0, m, i] / ref[m] - 1)) > 3e-3       # it was perturbed
        assert np.max(np.abs(L[-1, m, i] / ref[m] - 1)) < 1e-2


def _contact_energy(tb, args, y):
    """The kernel's elastic contact energy [J] at y: sum k_w delta^(19/9) 9/19 over the slices and
    (2/5) Q delta over the ribs (delta from each load by the laws' inverses)."""
    P = args.P[0]
    D = tb.diagnostics(y[None, :], y, args)
    q = D["Slice loads [N]"][0]
    qf = D["Flange load [N]"][0]
    return (9.0 / 19.0) * np.sum(q * (q / P.kw) ** 0.9) + 0.4 * np.sum(qf * (qf / P.kf) ** (2.0 / 3.0))


def test_the_contact_moment_on_the_cone_balances_the_applied_moment_at_the_start():
    """Fr 20 kN, axial locked, the load 10 mm off the rollers' mid-plane (x_F F_r = 200 N m), at rest.
    (a) The 2-D solver's moment from its contact points (a posteriori) balances x_F F_r to 1e-9.  (b) At
    the start, the kernel's contact moment on the cone balances it to round-off (1e-10 relative; the start
    moves the cone from the 2-D solver's tilt onto the kernel's balance, :meth:`TaperedBearing._balance_cone`,
    by 1e-4 of the tilt: the 2-D solver sees the tilt in each roller's plane only, asserted 1e-3), so the
    cone starts without a tilt acceleration.  (c) The kernel's moment is the virtual work of its own contact
    energy: M_z = -dE/d(theta_z) by a central difference at 3e-9 rad (theta_y = 0, so theta_z is a rotation
    about z), to 1e-6 of x_F F_r, independent of how the kernel sums r x f.  Measured 3.1e-7: as h falls
    (1e-7, 1e-8, 3e-9, 1e-9 rad: 3.5e-5, 4.7e-7, 3.1e-7, 2.4e-7) the difference tends to about 5e-5 N m,
    1e-8 of the rollers' gross moments (some 400 N m each), the level of slice_contact_3d's approximation
    for a skewed roller (those near +-90 deg see the tilted cone as a 4e-4 rad skew); below 1e-9 rad the
    energy's round-off takes over."""
    x_f, fr = 0.01, 20e3
    tb = tilted(load_offset=x_f)
    qs = tb.quasi_static()
    assert qs.applied_moment[2] == pytest.approx(x_f * fr)
    assert np.abs(qs.cone_moment + qs.applied_moment).max() < 1e-9 * x_f * fr
    args = tb.args(qs)
    y0 = tb.start_state(qs)
    k = tb.tilt_index
    assert y0[k + 1] == pytest.approx(qs.cone_tilt[1], rel=1e-3)
    D = tb.diagnostics(y0[None, :], y0, args)
    M = D["Cone moment [N m]"][0]
    assert abs(M[2] + x_f * fr) < 1e-10 * x_f * fr and abs(M[1]) < 1e-10 * x_f * fr
    d = np.zeros_like(y0)
    K.rhs(0.0, y0, args, d)
    assert np.max(np.abs(d[k + 2:k + 4])) * args.P[0].iconet < 1e-10 * x_f * fr
    y1 = y0.copy()
    y1[k] = 0.0

    def slope(h):
        e = []
        for s in (1.0, -1.0):
            yh = y1.copy()
            yh[k + 1] += s * h
            e.append(_contact_energy(tb, args, yh))
        return (e[0] - e[1]) / (2 * h)

    M1 = tb.diagnostics(y1[None, :], y1, args)["Cone moment [N m]"][0]
    assert M1[2] == pytest.approx(-slope(3e-9), abs=1e-6 * x_f * fr)


def test_a_free_spinning_cone_precesses_at_the_gyroscopic_rate():
    """Contacts off, no load, the cone spinning at 2,400 rpm and given a tilt rate of 1e-3 rad/s about y:
    with no moment, Euler's equations of the axisymmetric cone (first order in the tilt) turn the tilt
    rate about the axis at I_x Omega/I_t (analytic: the transverse rate of a spinning symmetric top
    without torque), here 456 rad/s with the assumed ring's I_x/I_t = 1.82, and keep its size (to 1e-9 at
    DOPRI5 rtol 1e-11)."""
    w = 2400 * RPM
    tb = tilted(speed=w, contacts=False, radial_load=0.0)
    args = tb.args()
    y0 = tb.start_state()
    k = tb.tilt_index
    y0[k + 2] = 1e-3
    i_x, i_t = tb.cone_inertia()
    rate = i_x * w / i_t
    assert rate == pytest.approx(456.0, rel=0.01)
    t = np.linspace(0.0, 20e-3, 11)
    res = integrate(K.rhs, y0, t, args, method="dopri5", rtol=1e-11, atol=1e-16)
    wy, wz = res.y[:, k + 2], res.y[:, k + 3]
    assert np.allclose(wy, 1e-3 * np.cos(rate * t), atol=1e-9 * 1e-3 * 1e3)
    assert np.allclose(wz, 1e-3 * np.sin(rate * t), atol=1e-9 * 1e-3 * 1e3)
    assert np.allclose(np.hypot(wy, wz), 1e-3, rtol=1e-9)


@pytest.mark.parametrize("changes, key", [({"cone_tilt": "wobbly"}, "operating.cone_tilt"),
                                          ({"load_offset": math.nan}, "operating.load_offset"),
                                          ({"applied_moment": (1.0,)}, "operating.applied_moment")])
def test_bad_tilt_keys_name_the_case_key(changes, key):
    with pytest.raises(DynamicsInputError) as info:
        G.Operating(**{"axial": "locked", **changes})
    assert info.value.key == key and str(info.value).startswith(key) and "\n" not in str(info.value)


def test_a_bad_cone_tilt_in_a_case_file_is_a_one_line_error_naming_the_key():
    from lubedyn.config import load_case

    with pytest.raises(InputError) as info:
        load_case(CASES_DIR / "trb_fig5_tilt.toml", overrides=["operating.cone_tilt=wobbly"])
    msg = str(info.value)
    assert "operating.cone_tilt" in msg and "wobbly" in msg and "locked" in msg and "\n" not in msg.strip()
    with pytest.raises(InputError, match="cone_tilt"):
        solve(tapered_geometry(), radial_load=1e3, axial_displacement=0.0, cone_tilt="wobbly")


def test_the_locked_cone_reproduces_the_model_before_the_option():
    """cases/trb_fig5_2400rpm.toml at 5 slices, 1 ms of RK4 (the step "auto" gave then, 0.8 x 2.776 us:
    the estimate is 1.49 x longer since 28 Nov 2026, TaperedBearing.traction_rate), sampled every 100 us, with the
    raceway traction by quadrature (the evaluation of that time): the packed parameters (the first 84;
    the tilt's and the traction table's are 0), the right-hand side at the recorded start state and the
    whole trajectory from it equal those recorded at commit 1b36d80 before the tilt existed
    (tests/data/trb_locked_reference.npz).  Bit for bit on the machine that wrote it (IEEE arithmetic
    without fastmath); asserted to 1e-12 relative so that another machine's libm cannot fail it.  The
    quasi-static start itself is the recorded one to the solver's tolerance, not bit for bit: its trust-region
    steps changed (its iterates differ, its equilibrium does not): the start state within 1e-12 (measured
    3e-16), the cone within 1e-12 (2e-13), the rollers' tilts (about 3e-6 rad, set by a moment balance at
    the 1e-10 residual) within 1e-14 rad (2.4e-15); the right-hand side at that start is within 1e-9 of the
    recorded (2.8e-10: the contacts' forces differ by their balance's rounding, 7e-6 N of 2e4 N)."""
    from lubedyn.scenes import tapered as S
    from lubedyn.scenes.bearing_run import drive
    from lubedyn.config import load_case

    with np.load(DATA / "trb_locked_reference.npz") as npz:
        ref = dict(npz)
    case = load_case(CASES_DIR / "trb_fig5_2400rpm.toml",
                     overrides=["model.slices=5", "integrator.duration=1 ms", "integrator.sample_interval=100 us",
                                "output.write=[]", "model.traction_evaluation=quadrature",
                                "integrator.dt=2.2204974146810178e-06"])
    model = S.build(case)
    args = model.args()
    qs = model.quasi_static()
    y0 = model.start_state(qs)

    def same(a, b, rtol=1e-12):
        np.testing.assert_allclose(a, b, rtol=rtol, atol=rtol * float(np.max(np.abs(b))))

    # the record's fields in the packed vector's order of that commit: the raceway film viscosities added
    # since (etao, etai) are left out and equal the films' viscosity eta with raceway_film = "formula"
    names = list(args.P.dtype.names)
    since = ("etao", "etai")
    assert all(args.P[0][n] == args.P[0]["eta"] for n in since)
    values = np.array([v for n, v in zip(names, args.P[0].tolist()) if n not in since])
    # the rib's film parameter: its entrainment speed is the cage frame's since 28 Nov 2026 (the ground
    # frame's carried the contact's orbital speed), a Hamrock-Dowson film thinner by (u_new/u_old)^0.67;
    # the reference is reproduced with the film parameter of its time
    lam = names.index("lam") - len(since)
    assert 0.6 < values[lam] / ref["P"][lam] < 0.66
    old_film = ref["P"][lam] / values[lam]  # the rib film and its film parameter of the reference's time
    values[lam] = ref["P"][lam]
    args.P["lam"][0] = ref["P"][lam]
    args.P["hrib"][0] *= old_film
    same(values[:84], ref["P"])
    assert not np.any(values[84:])
    same(y0, ref["y0"])
    same(qs.cone_displacement, ref["cone"])
    np.testing.assert_allclose(qs.roller_tilts, ref["tilts"], rtol=0.0, atol=1e-14)
    d = np.zeros_like(y0)
    K.rhs(0.0, y0, args, d)
    same(d, ref["dydt0"], rtol=1e-9)
    K.rhs(0.0, ref["y0"].copy(), args, d)
    same(d, ref["dydt0"])

    class FromTheRecordedStart(S.TaperedRunModel):
        def build(self):
            super().build()
            self.y0 = ref["y0"].copy()
            self.args.P["lam"][0] = ref["P"][lam]  # the rib film of the reference's time (above)
            self.args.P["hrib"][0] *= old_film

    r = drive(FromTheRecordedStart(case), None, name="tapered")
    assert np.array_equal(r.t, ref["t"])
    same(r.y, ref["y"])
