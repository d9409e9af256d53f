"""The dominant frequency of a sampled signal in a band and the bearing line nearest to it, and the
spectrum axis set by the bearing lines (the names of :func:`lubedyn.dynamics.spectra.bearing_frequencies`).

Zhang et al., *Symmetry* 16 (2024) 741, Fig. 11 reads the inner ring's acceleration spectrum of the
cage-less bearing: its dominant line lies at 950-1,000 Hz at 3,000 rpm (:func:`vibration_entries`).
"""
from __future__ import annotations

import numpy as np
from lubedyn.dynamics.spectra import amplitude_spectrum

#: the bearing lines that set the spectrum's axis (their first harmonics 2 f included)
SPECTRUM_LINES = ("Shaft [Hz]", "Ball train (cage) [Hz]", "Ball spin [Hz]", "Ball defect (2 x spin) [Hz]",
                  "BPFO [Hz]", "BPFI [Hz]")
MAX_HARMONIC = 5


def spectrum_limit(freqs: dict, factor: float = 1.5) -> float | None:
    """Upper limit [Hz] of the spectrum axis: ``factor`` times the highest first harmonic (2 f) of
    the bearing lines :data:`SPECTRUM_LINES` (not the collision rate); None without lines."""
    lines = [2.0 * freqs[k] for k in SPECTRUM_LINES if freqs.get(k, 0) > 0]
    return factor * max(lines) if lines else None


def ring_acceleration(t, series):
    """The inner ring's vertical acceleration [m/s^2] (derivative of its vy), whose spectrum the
    dynamics scene plots."""
    return np.gradient(np.asarray(series["Inner ring vy [m/s]"], dtype=float), np.asarray(t, dtype=float))


def dominant_frequency(t, signal, band):
    """(frequency [Hz], amplitude) of the largest line of the Hann-windowed amplitude spectrum
    (:func:`lubedyn.dynamics.spectra.amplitude_spectrum`) within ``band`` = (low, high) [Hz]; (None, None)
    when the band holds no bin."""
    t = np.asarray(t, dtype=float)
    f, amp = amplitude_spectrum(signal, 1.0 / float(t[1] - t[0]))
    inside = np.flatnonzero((f >= band[0]) & (f <= band[1]))
    if inside.size == 0:
        return None, None
    k = int(inside[np.argmax(amp[inside])])
    return float(f[k]), float(amp[k])


def nearest_line(frequency: float, freqs: dict) -> str:
    """The bearing line harmonic n x f (n <= ``MAX_HARMONIC``: a high harmonic of the cage frequency
    lies near anything) nearest to ``frequency``, e.g. "3 x BPFO (+1.2 %)"."""
    best = None
    for name in SPECTRUM_LINES:
        f0 = freqs.get(name, 0.0)
        if f0 > 0:
            n = min(MAX_HARMONIC, max(1, round(frequency / f0)))
            dev = frequency / (n * f0) - 1.0
            if best is None or abs(dev) < abs(best[2]):
                best = (n, name, dev)
    return "" if best is None else f"{best[0]} x {best[1].replace(' [Hz]', '')} ({100 * best[2]:+.1f} %)"


def vibration_entries(t, series, freqs, band, transient: float = 0.0) -> dict:
    """Dominant inner-ring acceleration frequency within ``band`` after ``transient`` (paper B,
    Fig. 11: 950-1,000 Hz at 3,000 rpm), with the nearest bearing line."""
    t = np.asarray(t, dtype=float)
    keep = t >= transient
    lo, hi = band
    key = f"Dominant inner ring acceleration frequency, {lo:g}-{hi:g} Hz"
    if keep.sum() < 16:
        return {f"{key} [Hz]": None, f"{key}, note": "not computed: fewer than 16 samples after the transient"}
    f, amp = dominant_frequency(t[keep], ring_acceleration(t, series)[keep], band)
    if f is None:
        return {f"{key} [Hz]": None, f"{key}, note": "not computed: the band lies beyond the Nyquist frequency "
                f"or is narrower than the resolution 1/T = {1 / (t[keep][-1] - t[keep][0]):.3g} Hz"}
    return {f"{key} [Hz]": f, f"{key} amplitude [m/s^2]": amp, f"{key}, nearest bearing line": nearest_line(f, freqs),
            f"{key}, resolution [Hz]": 1.0 / float(t[keep][-1] - t[keep][0])}
