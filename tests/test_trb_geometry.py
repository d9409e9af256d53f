"""Tapered roller bearing geometry (lubedyn.lubrication.laws.tapered) and slice law (lubedyn.lubrication.laws.slices)
against independent values: Table 1 of paper A, hand estimates from its tables (docs/paper_a.md,
"Estimates at paper A's operating points"), Palmgren's line law, ISO/TS 16281's constant and closed forms written here."""
import math

import numpy as np
import pytest

from lubedyn.papers.wu2018.parameters import tapered_geometry
from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws import slices as sl

L_E, D_L, D_S, R_P = 42.06e-3, 24.76e-3, 17.85e-3, 0.5 * (99.52e-3 + 78.48e-3)
RHO_M = 0.25 * (D_L + D_S)
RPM = math.pi / 30.0


@pytest.fixture(scope="module")
def apex():
    return tapered_geometry(reconciliation="common_apex", profile="straight")


@pytest.fixture(scope="module")
def literal():
    return tapered_geometry(reconciliation="literal", profile="straight")


# ----------------------------------------------------------------------------- geometry


def test_common_apex_taper_and_raceways(apex):
    """phi = atan(rho_m sin(alpha_r)/R_p) with the roller axis at (15 + 5)/2 deg (1.19 deg);
    both raceway lines and the roller axis pass through one point of the bearing axis."""
    alpha_r = math.radians(10.0)
    phi = math.atan(RHO_M * math.sin(alpha_r) / R_P)
    assert math.degrees(phi) == pytest.approx(1.19, abs=0.005)
    assert apex.half_taper == pytest.approx(phi, rel=1e-12)
    assert (apex.cup_angle, apex.cone_angle) == pytest.approx((alpha_r + phi, alpha_r - phi), rel=1e-12)
    x_apex = -R_P / math.tan(alpha_r)
    for which in ("cup", "cone"):
        p, _, angle = apex.race(which)
        assert p[1] + (x_apex - p[0]) * math.tan(angle) == pytest.approx(0.0, abs=1e-15)
    # a straight roller touches both raceways along its whole length without load
    u = np.linspace(-0.5 * L_E, 0.5 * L_E, 11)
    assert np.abs(apex.interference(u, "cup")).max() < 1e-15
    assert np.abs(apex.interference(u, "cone")).max() < 1e-15


def test_literal_taper_and_misfit(literal):
    """Half-taper atan(3.455/42.06) = 4.70 deg (the printed end diameters read with
    their labels swapped); the generatrices miss the 15/5 deg
    raceways by 5 - 4.70 = 0.30 deg: touching at the small end, the large end gap is l_e sin(0.30 deg)."""
    phi = math.atan(0.5 * (D_L - D_S) / L_E)
    assert math.degrees(phi) == pytest.approx(4.70, abs=0.005)
    assert literal.half_taper == pytest.approx(phi, rel=1e-12)
    assert (math.degrees(literal.cup_angle), math.degrees(literal.cone_angle)) == pytest.approx((15.0, 5.0))
    misfit = math.radians(5.0) - phi
    for which in ("cup", "cone"):
        gaps = literal.interference(np.array([-0.5 * L_E, 0.5 * L_E]), which)
        assert gaps[0] == pytest.approx(0.0, abs=1e-15)
        assert -gaps[1] == pytest.approx(L_E * math.sin(misfit), rel=0.02)


def test_literal_end_sliding_against_a_hand_estimate(literal):
    """The literal roller ends slide -14.2 / +13.6 % against the cone.  Independent
    estimate from Table 1: roller radius ratio 1 +- (l_e/2) tan(phi)/rho_m over race radius ratio
    1 +- (l_e/2) sin(5 deg)/78.48 mm (pure rolling at mid-length)."""
    phi = math.atan(0.5 * (D_L - D_S) / L_E)
    h = 0.5 * L_E
    expect = [(1 + s * h * math.tan(phi) / RHO_M) / (1 + s * h * math.sin(math.radians(5)) / 78.48e-3) - 1
              for s in (-1, 1)]
    assert expect == pytest.approx([-0.142, 0.136], abs=5e-4)
    cup, cone = literal.end_sliding([-h, h])
    assert cone == pytest.approx(expect, abs=1e-3)   # the model's raceway sits 0.24 mm lower: 1e-4 here
    # the cup ends slide less (the cup's radius grows with sin 15 deg along the roller)
    expect_cup = [(1 + s * h * math.tan(phi) / RHO_M) / (1 + s * h * math.sin(math.radians(15)) / 99.52e-3) - 1
                  for s in (-1, 1)]
    assert cup == pytest.approx(expect_cup, abs=2e-3)


def test_common_apex_has_no_end_sliding(apex):
    cup, cone = apex.end_sliding(np.linspace(-0.5 * L_E, 0.5 * L_E, 7))
    assert np.abs(cup).max() < 1e-13 and np.abs(cone).max() < 1e-13


def test_ideal_kinematics(apex):
    """Cage speed at 2,400 rpm, cup fixed: about 1,057 rpm (a hand estimate from Table 1;
    the usual conventions for gamma span 0.41 %).
    Independent: the roller's instantaneous axis is the cup line, so omega_c/omega_i =
    sin(alpha_i) sin(alpha_o - alpha_r) / (sin(alpha_o - alpha_i) sin(alpha_r)) for a common apex,
    equal to (1 - gamma)/2 with gamma = D_m cos(alpha_r)/d_m."""
    wi = 2400 * RPM
    k = apex.kinematics(wi)
    ai, ao, ar = apex.cone_angle, apex.cup_angle, apex.roller_axis_angle
    ratio = math.sin(ai) * math.sin(ao - ar) / (math.sin(ao - ai) * math.sin(ar))
    assert k["cage speed [rad/s]"] / wi == pytest.approx(ratio, rel=1e-12)
    gamma = 2 * RHO_M * math.cos(ar) / (2 * R_P)
    assert k["cage speed [rad/s]"] / wi == pytest.approx((1 - gamma) / 2, rel=1e-12)
    assert k["cage speed [rad/s]"] / RPM == pytest.approx(1057.0, rel=0.005)      # 1,058.6 rpm
    # roller spin 9,886 rpm and entrainment 11.03 m/s (hand estimates for pure rolling, rounded)
    assert k["roller spin relative to cage [rad/s]"] / RPM == pytest.approx(9886, rel=0.002)
    assert k["entrainment speed [m/s]"] == pytest.approx(11.03, rel=0.002)
    r_o, r_i = k["cup contact radius [m]"], k["cone contact radius [m]"]
    assert k["entrainment speed [m/s]"] == pytest.approx((wi - k["cage speed [rad/s]"]) * r_i, rel=1e-12)
    assert (r_o, r_i) == pytest.approx((R_P + RHO_M * math.cos(ar), R_P - RHO_M * math.cos(ar)), rel=1e-12)


def test_flange_contact_point(apex, literal):
    """The rib normal at 83 deg to the radial plane is 3 deg off the 10 deg roller axis, so the
    contact point lies r_s sin(3 deg) = 7.13 mm off the axis towards the cone, on the end sphere."""
    for g in (apex, literal):
        off = 136.2e-3 * math.sin(math.radians(83.0 - 80.0))
        assert g.flange_offset == pytest.approx(-off, rel=1e-9)
        centre = np.array([0.0, R_P]) + g.sphere_center_u * g.axis_direction
        assert np.linalg.norm(g.flange_point - centre) == pytest.approx(136.2e-3, rel=1e-12)
        assert 0.0 < g.flange_height < g.rib_height


def test_flange_hertz_constant(apex):
    """Q_f = K delta^1.5 against Hertz's circular approximation delta = (9 Q^2/(16 E*^2 R))^(1/3),
    R = sqrt(R_x R_y): sphere 136.2 mm against a rib concave (cos 83 deg / r_P) circumferentially."""
    e_star = 1.0 / (2 * (1 - 0.3**2) / 205e9)
    r_x = 136.2e-3
    r_y = 1.0 / (1 / 136.2e-3 - math.cos(math.radians(83)) / apex.flange_point[1])
    q = 592.0
    delta = (9 * q**2 / (16 * e_star**2 * math.sqrt(r_x * r_y))) ** (1 / 3)
    assert (q / apex.flange_hertz_constant()) ** (2 / 3) == pytest.approx(delta, rel=2e-3)


def test_cage_and_guide_land_placement(apex):
    """Beyond the large end (assumed: Table 1's cage overlaps the cup raceway); 0.5 mm read as
    diametral (eq. 43's Delta e = (r_y - r_d)/2)."""
    assert apex.land_radius == pytest.approx(0.5 * 196.10e-3 - 0.25e-3, rel=1e-12)
    large_end = np.array([0.0, R_P]) + 0.5 * L_E * apex.axis_direction
    assert apex.land_x - 0.5 * 4.93e-3 > large_end[0]


def test_roller_mass_properties(apex, literal):
    """Frustum closed forms: m = rho pi l (R1^2 + R1 R2 + R2^2)/3, I_x = 3 m (R1^5 - R2^5)/(10 (R1^3 -
    R2^3)); the literal roller weighs about 0.119 kg (a hand estimate of a steel
    frustum)."""
    for g in (apex, literal):
        r1, r2 = (float(g.roller_radius(s * 0.5 * L_E, crown=False)) for s in (1, -1))
        m = 7850 * math.pi * L_E * (r1**2 + r1 * r2 + r2**2) / 3
        ix = 3 * m * (r1**5 - r2**5) / (10 * (r1**3 - r2**3))
        mass, i_x, i_y, _ = g.roller_mass_properties()
        assert mass == pytest.approx(m, rel=1e-6) and i_x == pytest.approx(ix, rel=1e-6)
        assert i_y == pytest.approx(m * (RHO_M**2 / 4 + L_E**2 / 12), rel=0.05)  # mean cylinder
    assert literal.roller_mass_properties()[0] == pytest.approx(0.119, rel=0.01)


def test_crown_profile():
    """Logarithmic crown: zero at mid-length, symmetric, end drop (2 Q/(pi l E')) ln(1/(0.3033 b/a))."""
    g = tapered_geometry(profile="logarithmic", crown_load=5000.0)
    z = g.crown(np.array([-0.5 * L_E, 0.0, 0.5 * L_E]))
    e_prime = 205e9 / (1 - 0.3**2)
    b, a = g.cup_half_width_at_crown_load, 0.5 * L_E
    end = 2 * 5000.0 / (math.pi * L_E * e_prime) * math.log(1 / (0.3033 * b / a))
    assert z[1] == 0.0 and z[0] == z[2] == pytest.approx(end, rel=1e-12)
    assert 1e-6 < end < 5e-6


def test_slices_cover_the_length(apex):
    for n in (1, 7, 40):
        u, w = apex.slices(n)
        assert w.sum() == pytest.approx(L_E, rel=1e-14) and u[0] == pytest.approx(-0.5 * L_E + 0.5 * w[0])


@pytest.mark.parametrize("override, key", [
    (dict(guide_land_clearance=-1e-4), "guide_land_clearance"),
    (dict(pocket_clearance=-1e-4), "pocket_clearance"),
    (dict(rib_height=30e-3), "rib_height"),
    (dict(rib_height=2e-3), "rib_height"),
    (dict(reconciliation="comon_apex"), "reconciliation"),
    (dict(profile="crowned"), "profile"),
    (dict(effective_length=0.0), "effective_length"),
    (dict(large_end_diameter=15e-3), "large_end_diameter"),
])
def test_bad_geometry_is_one_line(override, key):
    with pytest.raises(InputError) as err:
        tapered_geometry(**override)
    msg = str(err.value)
    assert msg.startswith(key) and "\n" not in msg


def test_bad_slice_count(apex):
    for n in (0, -3, 2.5):
        with pytest.raises(InputError, match=r"^n_slices = "):
            apex.slices(n)
        with pytest.raises(InputError, match=r"^n_slices = "):
            sl.slice_constant(1e9, n)


# ----------------------------------------------------------------------------- slice law


def test_palmgren_line_law():
    """K_L reproduces Palmgren's delta = 3.84e-5 Q^0.9 / l^0.8 [mm, N]; paper A's 0.356 E' with
    E' = E/(1 - nu^2) = 225.3 GPa is 0.49 % softer; E' = 226.4 GPa reproduces it."""
    K = sl.palmgren_line_constant(L_E)
    for q in (100.0, 3409.0, 5000.0):
        delta_mm = 3.84e-5 * q**0.9 / (L_E * 1e3) ** 0.8
        assert sl.approach(q, K) == pytest.approx(delta_mm * 1e-3, rel=1e-12)
    assert sl.line_constant(L_E, sl.palmgren_modulus()) == pytest.approx(K, rel=1e-14)
    assert sl.palmgren_modulus() == pytest.approx(2.264e11, rel=1e-3)
    assert sl.line_constant(L_E, 205e9 / (1 - 0.09)) / K == pytest.approx(0.9951, abs=1e-4)


def test_iso_16281_differs_by_about_4_percent():
    """ISO/TS 16281: Q = 35,948 l^(8/9) delta_total^(10/9) [N, mm] for the two contacts of a roller;
    Palmgren's two equal contacts in series: K_L / 2^(10/9)."""
    l_mm = L_E * 1e3
    iso = 35948 * l_mm ** (8 / 9)
    palmgren = sl.palmgren_line_constant(1.0) * 1e-6 * l_mm ** (8 / 9) / 2 ** (10 / 9)   # N, mm
    assert palmgren / iso - 1 == pytest.approx(0.038, abs=0.003)


@pytest.mark.parametrize("n", [1, 2, 3, 7, 20, 64, 199])
def test_equal_slices_sum_to_the_whole_roller(n):
    K = sl.palmgren_line_constant(L_E)
    kw = sl.slice_constant(K, n)
    for delta in (1e-7, 4.1e-6, 2e-5):
        total = sum(sl.slice_force(delta, 0.0, kw, 0.0) for _ in range(n))
        assert total == pytest.approx(K * delta ** (10 / 9), rel=1e-13)


def test_slice_force_damping_and_sign():
    kw, a = 1e9, 0.16
    d = 3e-6
    assert sl.slice_force(-1e-9, 0.0, kw, a) == 0.0
    assert sl.slice_force(d, 0.1, kw, a) == pytest.approx(kw * d ** (10 / 9) * (1 + 1.5 * a * 0.1), rel=1e-14)
    assert sl.slice_force(d, -100.0, kw, a) == 0.0      # separating fast: no pull


def test_slice_interference_by_brute_force():
    """The disc's rim in the meridional plane is S +- rho e_perp: the interference is the deeper of
    the two end points below the line, for any attitude."""
    rng = np.random.default_rng(3)
    for _ in range(200):
        beta, gamma = rng.uniform(0.0, 0.4), rng.uniform(0.0, 0.4)
        e = np.array([math.cos(beta), math.sin(beta)])
        n = np.array([math.sin(gamma), -math.cos(gamma)])
        s, x, rho = rng.normal(size=2) * 1e-2, rng.normal(size=2) * 1e-2, rng.uniform(5e-3, 1.5e-2)
        perp = np.array([-e[1], e[0]])
        ends = [s + rho * perp, s - rho * perp]
        brute = -min(float(n @ (p - x)) for p in ends)
        assert sl.slice_interference(s[0], s[1], e[0], e[1], rho, x[0], x[1], n[0], n[1]) == pytest.approx(
            brute, abs=1e-16)


def test_slice_interference_derivatives():
    beta, rho, u, g = 0.2, 1e-2, -0.02, 0.26
    n = (math.sin(g), -math.cos(g))

    def f(b):
        return sl.slice_interference(0.1 + u * math.cos(b), 0.09 + u * math.sin(b), math.cos(b), math.sin(b),
                                     rho, 0.0, 0.1, *n)
    h = 1e-5
    grad = sl.slice_interference_gradient(math.cos(beta), math.sin(beta), rho, u, *n)
    assert grad[:2] == pytest.approx((-n[0], -n[1]), rel=1e-15)
    assert grad[2] == pytest.approx((f(beta + h) - f(beta - h)) / (2 * h), rel=1e-8)
    curv = sl.slice_interference_curvature(math.cos(beta), math.sin(beta), rho, u, *n)
    assert curv == pytest.approx((f(beta + h) - 2 * f(beta) + f(beta - h)) / h**2, rel=1e-4)


def test_slice_leaves_run_inside_a_compiled_kernel():
    """The part-2 kernels call the slice law from numba: the leaves inline into an @njit caller and
    give the Python values."""
    from numba import njit

    @njit
    def kernel(delta_dot):
        d = sl.slice_interference(0.0, 0.0, 1.0, 0.0, 0.01, 0.0, -0.00999, 0.0, 1.0)
        return sl.slice_force(d, delta_dot, 1e9, 0.16)

    d = sl.slice_interference.py_func(0.0, 0.0, 1.0, 0.0, 0.01, 0.0, -0.00999, 0.0, 1.0)
    assert d == pytest.approx(1e-5, rel=1e-9)
    assert kernel(0.1) == pytest.approx(1e9 * d ** (10 / 9) * (1 + 1.5 * 0.16 * 0.1), rel=1e-14)


@pytest.mark.parametrize("which", ["cup", "cone"])
def test_slice_contact_3d_against_the_exact_distance_over_the_rim(apex, which):
    """A skewed and tilted slice of paper A's roller at any azimuth against the conical raceway: the
    interference and the contact point against the exact signed distance of 20,000 rim points (each
    point's meridional distance, sqrt(y^2 + z^2) exact), refined by a bounded scalar minimisation.
    Measured (20 random poses per case): interference within 3e-17 m unskewed and 1.2e-12 m at a skew
    of 2e-3 rad; contact point within 5e-10 m and 5.4e-8 m."""
    from scipy.optimize import minimize_scalar

    g = apex
    x0, n2, _ = g.race(which)
    rng = np.random.default_rng(5)
    for psi_skew in (0.0, 2e-3):
        for _ in range(20):
            az = rng.uniform(0.0, 2 * np.pi)
            u = rng.uniform(-0.02, 0.02)
            tilt = rng.uniform(-1e-3, 1e-3)
            beta = g.roller_axis_angle + tilt
            c0 = np.array([0.0, g.pitch_radius]) + rng.normal(size=2) * 2e-6
            # meridional roller axis, then skew about the radial direction, then turn to the azimuth
            e_m = np.array([math.cos(beta), math.sin(beta), 0.0])
            radial = np.array([0.0, 1.0, 0.0])
            k = radial
            e_s = (e_m * math.cos(psi_skew) + np.cross(k, e_m) * math.sin(psi_skew)
                   + k * (k @ e_m) * (1 - math.cos(psi_skew)))
            rot = np.array([[1, 0, 0], [0, math.cos(az), -math.sin(az)], [0, math.sin(az), math.cos(az)]])
            e = rot @ e_s
            S = rot @ np.array([c0[0], c0[1], 0.0]) + u * e
            rho = float(g.roller_radius(u))
            got = sl.slice_contact_3d(*S, *e, rho, x0[0], x0[1], n2[0], n2[1])
            a = np.cross(e, [1.0, 0.0, 0.0])
            a /= np.linalg.norm(a)
            b = np.cross(e, a)

            def dist(t):
                P = S + rho * (math.cos(t) * a + math.sin(t) * b)
                return n2[0] * (P[0] - x0[0]) + n2[1] * (math.hypot(P[1], P[2]) - x0[1])

            ts = np.linspace(0, 2 * np.pi, 20000, endpoint=False)
            d = np.array([dist(t) for t in ts[::50]])
            t0 = ts[::50][np.argmin(d)]
            res = minimize_scalar(dist, bounds=(t0 - 0.05, t0 + 0.05), method="bounded",
                                  options=dict(xatol=1e-12))
            exact = -res.fun
            assert got[0] == pytest.approx(exact, abs=1e-15 if psi_skew == 0.0 else 1e-11)
            P = S + rho * (math.cos(res.x) * a + math.sin(res.x) * b)
            assert np.linalg.norm(np.array(got[1:4]) - P) < (1e-8 if psi_skew == 0.0 else 1e-6)
