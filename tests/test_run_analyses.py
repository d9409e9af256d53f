"""The paper-independent analyses of a cage-less bearing run (lubedyn.dynamics.analysis: settling and
spin-up times, steady residuals, the co-rotating frame and Poincare sections, angular displacement,
collisions by quadrant, the dominant frequency in a band) on synthetic data with known answers: the
settling time of an exponential decay and the spin-up time of an exponential approach against their
closed forms, a ball train on a perfect circle (no co-rotating radial motion, a Poincare section of one
point at the analytic crossing times, settled from the start), known rotations, a collision in a known
quadrant, a tone in a band."""
from __future__ import annotations

import math

import numpy as np
import pytest

from lubedyn.dynamics import analysis as an
from lubedyn.dynamics.analysis import Collision
from lubedyn.dynamics.spectra import bearing_frequencies

Z, R0, W = 14, 23.0e-3, 400.0  # balls, pitch radius [m], orbital speed [rad/s]


def circle_series(t, z=Z, radius=R0, w=W, spin=-2000.0, ring=1036.0, rotor=None):
    """A ball train on a perfect circle at constant speed, each ball spinning about the inertial z
    axis at ``spin`` (quaternion and body rates consistent), the ring turning at ``ring``."""
    s = {"Time [s]": t, "Inner ring speed [rad/s]": np.full_like(t, ring),
         "Rotor speed [rad/s]": np.full_like(t, ring if rotor is None else rotor)}
    for a in "xyz":
        s[f"Inner ring {a} [m]"] = np.zeros_like(t)
        s[f"Inner ring v{a} [m/s]"] = np.zeros_like(t)
    for j in range(z):
        psi = 1.5 * math.pi + 2 * math.pi * j / z + w * t
        b = f"Ball {j} "
        s[b + "x [m]"], s[b + "y [m]"], s[b + "z [m]"] = radius * np.cos(psi), radius * np.sin(psi), np.zeros_like(t)
        s[b + "vx [m/s]"], s[b + "vy [m/s]"] = -radius * w * np.sin(psi), radius * w * np.cos(psi)
        s[b + "vz [m/s]"] = np.zeros_like(t)
        s[b + "Orbital angle [rad]"] = np.angle(np.exp(1j * psi))  # wrapped like the model's diagnostic
        s[b + "Orbital speed [rad/s]"] = np.full_like(t, w)
        s[b + "q0 [-]"], s[b + "q1 [-]"], s[b + "q2 [-]"] = np.cos(0.5 * spin * t), 0 * t, 0 * t
        s[b + "q3 [-]"] = np.sin(0.5 * spin * t)
        s[b + "body wx [rad/s]"], s[b + "body wy [rad/s]"] = 0 * t, 0 * t
        s[b + "body wz [rad/s]"] = np.full_like(t, spin)
    return s


# ---------------------------------------------------------------------------- Fig. 3: settling
def test_settling_time_of_an_exponential_decay_matches_the_time_to_leave_the_band():
    """x = c + A exp(-t/tau): the final window (last 25 %) has mean c and no spread, the band is 5 % of
    the largest excursion A, so x leaves it for good at tau ln(20)."""
    tau, A = 1e-3, 3e-6
    t = np.linspace(0.0, 0.02, 20001)
    x = 23e-3 + A * np.exp(-t / tau)
    time_, half, note = an.settling_time(t, x, an.final_start(t))
    assert note == ""
    assert half == pytest.approx(0.05 * A, rel=1e-6)
    assert time_ == pytest.approx(tau * math.log(20.0), rel=1e-5)


def test_a_signal_still_moving_in_the_final_window_has_not_settled():
    t = np.linspace(0.0, 0.02, 2001)
    time_, _, note = an.settling_time(t, t**2, an.final_start(t))
    assert time_ is None and note.startswith("not settled: drifts")
    x = np.where(t == t[1200], 1.0, 0.01 * np.sin(3000 * t))  # a spike at 12 ms, then the stable stage
    time_, half, note = an.settling_time(t, x, an.final_start(t))
    assert half == pytest.approx(0.05, rel=2e-3) and time_ == pytest.approx(t[1200], abs=1e-5)


def test_a_decay_still_running_into_the_final_window_is_record_too_short():
    """x = A exp(-t/tau) up to the final window (from 15 ms of 20), then an oscillation about 0 with the
    decay's amplitude there, d = A exp(-15 ms/tau) = 0.106 A > 5 % of A: the band is the final window's own
    largest deviation d, so the rule's last exit falls on the final window's start -- the record's edge, not
    a settling time: "record too short".  The same decay with tau = 1 ms settles at tau ln 20."""
    tau, A = 6.7e-3, 3e-6
    t = np.linspace(0.0, 0.02, 20001)
    i = an.final_start(t)
    d = A * math.exp(-t[i] / tau)
    x = np.where(t < t[i], A * np.exp(-t / tau), d * np.cos(2 * math.pi * (t - t[i]) / 1e-4))
    time_, half, note = an.settling_time(t, x, i)
    assert half == pytest.approx(d, rel=1e-3)  # about the final window's sampled mean, 2e-4 off 0
    assert time_ is None and note.startswith("record too short")
    time_, _, note = an.settling_time(t, A * np.exp(-t / 1e-3), i)
    assert note == "" and time_ == pytest.approx(1e-3 * math.log(20.0), rel=1e-5)


def test_spinup_time_of_an_exponential_approach():
    """Ring speed Omega (1 - exp(-t/tau)): within 1 % of the rotor's from tau ln(100) on."""
    tau, rotor = 2e-3, 1047.0
    t = np.linspace(0.0, 0.02, 20001)
    time_, note = an.spinup_time(t, rotor * (1 - np.exp(-t / tau)), np.full_like(t, rotor))
    assert note == "" and time_ == pytest.approx(tau * math.log(100.0), rel=1e-5)
    time_, note = an.spinup_time(t[:3000], rotor * (1 - np.exp(-t[:3000] / tau)), np.full(3000, rotor))
    assert time_ is None and "not spun up" in note


def test_ball_train_on_a_perfect_circle_is_settled_from_the_start():
    t = np.linspace(0.0, 0.02, 4001)
    s = circle_series(t)
    out = an.settling_times(t, s, 0)
    for key in ("x", "y", "orbital speed"):
        assert out[f"Settling time, ball 0 {key} [s]"] == 0.0
    assert out["Settling time, ball 0 z [s]"] is None and "does not move" in out["Settling time, ball 0 z, note"]
    assert out["Inner ring spin-up time [s]"] == 0.0


def test_steady_residual_removes_an_azimuth_pattern():
    """Every ball's value is f(azimuth) (a load-zone pattern): the residual is zero up to the bin width."""
    t = np.linspace(0.0, 0.02, 4001)
    az = np.stack([1.5 * math.pi + 2 * math.pi * j / Z + W * t for j in range(Z)], axis=1)
    values = 1e-5 * np.where(np.sin(az) < 0, 1.0, 0.0)  # a step at 0 and 180 deg, on bin edges
    res = an.steady_residuals(az, values, an.final_start(t))
    assert np.max(np.abs(res)) == 0.0


# ---------------------------------------------------------------------------- co-rotating frame, Poincare
def test_circle_has_no_corotating_radial_motion_and_a_one_point_poincare_section():
    t = np.linspace(0.0, 0.05, 10001)
    s = circle_series(t)
    m = an.ball_motion(t, s, 0)
    assert np.max(np.abs(m.radius - R0)) < 1e-15
    assert np.max(np.abs(m.radial_velocity)) < 1e-12
    section = 0.5 * math.pi
    times, vals = an.poincare_section(t, m.azimuth, np.stack([m.radius, m.radial_velocity], axis=1), section)
    # ball 0 starts at 270 deg: it passes 90 deg after half a revolution, then every revolution
    expected = (math.pi + 2 * math.pi * np.arange(times.size)) / W
    assert times.size == int((0.05 * W - math.pi) // (2 * math.pi)) + 1 == 3
    assert times == pytest.approx(expected, abs=1e-12)
    assert np.ptp(vals[:, 0]) < 1e-15 and np.max(np.abs(vals[:, 1])) < 1e-12


def test_planar_columns_give_the_same_motion():
    t = np.linspace(0.0, 0.01, 1001)
    psi = 0.3 + W * t
    s = {"Ball 0 Orbital angle [rad]": psi, "Ball 0 Orbital speed [rad/s]": np.full_like(t, W),
         "Ball 0 radial position [m]": np.full_like(t, R0), "Ball 0 radial speed [m/s]": np.zeros_like(t)}
    m = an.ball_motion(t, s, 0)
    assert m.position[:, 0] == pytest.approx(R0 * np.cos(psi), abs=1e-15)
    assert m.velocity[:, 1] == pytest.approx(R0 * W * np.cos(psi), abs=1e-12)
    assert np.all(m.position[:, 2] == 0.0)


# ---------------------------------------------------------------------------- Fig. 4: angular displacement
def test_constant_rotation_about_a_fixed_axis():
    t = np.linspace(0.0, 0.01, 2001)
    u, rate = np.array([1.0, 2.0, 2.0]) / 3.0, 1500.0
    q = np.column_stack([np.cos(0.5 * rate * t)] + [np.sin(0.5 * rate * t) * c for c in u])
    ang = an.angular_displacement(t, q, np.tile(rate * u, (t.size, 1)))
    assert ang[-1] == pytest.approx(rate * t[-1] * u, rel=1e-12)  # 15 rad: no wrapping at pi


def test_spin_about_a_tilted_body_axis_turns_about_the_tilted_inertial_axis():
    """q(t) = q_tilt * rot_z(W t) (body z tilted by 30 deg about inertial x) with w_body = (0, 0, W): the
    inertial rate is W R(q_tilt) e_z = W (0, -sin 30, cos 30), so the angles grow along it.  A test
    of the convention: q maps body to inertial."""
    t = np.linspace(0.0, 0.004, 4001)
    tilt, rate = math.radians(30.0), 2000.0
    c, s = math.cos(0.5 * tilt), math.sin(0.5 * tilt)
    ch, sh = np.cos(0.5 * rate * t), np.sin(0.5 * rate * t)
    q = np.column_stack([c * ch, s * ch, -s * sh, c * sh])  # (c, s, 0, 0) * (ch, 0, 0, sh)
    ang = an.angular_displacement(t, q, np.tile([0.0, 0.0, rate], (t.size, 1)))
    assert ang[-1] == pytest.approx(rate * t[-1] * np.array([0.0, -math.sin(tilt), math.cos(tilt)]), abs=1e-9)


# ---------------------------------------------------------------------------- Fig. 5: collisions by position
def test_quadrants():
    angles = np.radians([45, 135, 225, 315, 0, 90])
    assert list(an.quadrant_of(np.cos(angles), np.sin(angles))) == [1, 2, 3, 4, 1, 2]


def test_a_collision_is_placed_relative_to_the_inner_ring_centre():
    """Contact at (1, -2) mm while the ring's centre is at (3, 0) mm: (-2, -2) mm from it, quadrant III,
    although the point itself lies in quadrant IV."""
    t = np.linspace(0.0, 1e-3, 11)
    s = {"Inner ring x [m]": np.full_like(t, 3e-3), "Inner ring y [m]": 0 * t, "Inner ring z [m]": 0 * t}
    event = Collision(pair=0, t_start=4e-4, t_end=6e-4, t_peak=5e-4, peak_force=100.0, force=(0.0, 100.0, 0.0),
                      position=(1e-3, -2e-3, 0.0))
    tp, pos, fn, comp = an.collision_table(t, s, [event])
    assert pos[0] == pytest.approx([-2e-3, -2e-3, 0.0])
    counts = an.collision_entries(t, s, [event], 4e-4)
    assert counts["Collisions in quadrant III (x < 0, y < 0) [-]"] == 1
    assert counts["Collisions after ring spin-up [-]"] == 1 and counts["Collisions during ring spin-up [-]"] == 0


# ---------------------------------------------------------------------------- spectrum, Fig. 11
def test_spectrum_limit_and_dominant_frequency_in_a_band():
    freqs = bearing_frequencies(50.0, 9.525e-3, 46.005e-3, 14, extra={"Collision rate [Hz]": 23000.0})
    assert an.spectrum_limit(freqs) == pytest.approx(1.5 * 2 * freqs["BPFI [Hz]"])
    t = np.arange(20000) / 200e3  # 0.1 s: 10 Hz bins
    signal = 10.0 * np.sin(2 * math.pi * 300.0 * t) + 2.0 * np.sin(2 * math.pi * 980.0 * t)
    f, amp = an.dominant_frequency(t, signal, (500.0, 1500.0))
    assert f == pytest.approx(980.0) and amp == pytest.approx(2.0, rel=1e-3)
    # the first harmonic of BPFI is named as such (no other line's harmonic falls on it at 50 Hz)
    name = an.nearest_line(2 * freqs["BPFI [Hz]"], freqs)
    assert name.startswith("2 x BPFI") and "(+0.0 %)" in name
