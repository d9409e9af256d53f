"""Collision events from sampled pair forces (lubedyn.dynamics.analysis)."""
from __future__ import annotations

import numpy as np
import pytest

from lubedyn.dynamics.analysis import collision_events, collision_summary, slip_ratio


def _pulses(t, pulses, Z=3):
    """Half-sine force pulses (pair, start, duration, peak) built independently of the detector."""
    F = np.zeros((t.size, Z))
    for pair, start, width, peak in pulses:
        inside = (t >= start) & (t <= start + width)
        F[inside, pair] += peak * np.sin(np.pi * (t[inside] - start) / width)
    return F


def test_events_found_with_their_peaks_and_durations():
    t = np.linspace(0.0, 1e-3, 10001)  # 0.1 us samples
    pulses = [(0, 1e-4, 4e-5, 50.0), (2, 3e-4, 2e-5, 120.0), (0, 7e-4, 6e-5, 10.0)]
    F = _pulses(t, pulses)
    comps = np.stack([F * 0.6, F * 0.8, F * 0.0], axis=-1)
    pos = np.ones((t.size, 3, 3))
    events = collision_events(t, F, comps, pos, threshold=1.0)
    assert [e.pair for e in events] == [0, 2, 0]
    for e, (pair, start, width, peak) in zip(events, pulses):
        assert e.t_peak == pytest.approx(start + width / 2, abs=1e-7)
        assert e.peak_force == pytest.approx(peak, rel=1e-6)
        # above 1 N: the half-sine exceeds the threshold for width (1 - 2 asin(1/peak)/pi)
        expected = width * (1 - 2 * np.arcsin(1.0 / peak) / np.pi)
        assert e.duration == pytest.approx(expected, abs=2e-7)
        assert e.force == pytest.approx((0.6 * peak, 0.8 * peak, 0.0), rel=1e-6)
    s = collision_summary(events, 3)
    assert s["Ball-ball collisions [-]"] == 3 and s["Collisions per pair, most [-]"] == 2
    assert s["Largest collision force y [N]"] == pytest.approx(96.0, rel=1e-6)


def test_event_cut_by_the_end_of_the_record_counts_and_shape_is_checked():
    t = np.linspace(0.0, 1.0, 11)
    F = np.zeros((11, 2))
    F[8:, 1] = 5.0
    events = collision_events(t, F, np.zeros((11, 2, 3)), np.zeros((11, 2, 3)), 1.0)
    assert len(events) == 1 and events[0].t_start == pytest.approx(0.8) and events[0].t_end == pytest.approx(1.0)
    with pytest.raises(ValueError, match="expected"):
        collision_events(t[:5], F, None, None, 1.0)


def test_slip_ratio():
    assert slip_ratio([50.0, 100.0], [100.0, 100.0]) == pytest.approx([0.5, 0.0])
    assert np.isnan(slip_ratio(1.0, 0.0))
