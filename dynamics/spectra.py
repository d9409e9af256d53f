"""Amplitude spectra and ball-bearing characteristic frequencies.

Amplitude spectrum (:func:`amplitude_spectrum`)
-----------------------------------------------
One-sided amplitude spectrum of a uniformly sampled real signal from
``scipy.signal.periodogram(..., scaling="spectrum")``, which applies the
window, detrends and scales by (sum w)^2 so that a tone of amplitude A on a
bin gives the power A^2 / 2 (doubled one-sided bins); the amplitude is
sqrt(2 P) (sqrt(P) at DC and at Nyquist).  Use ``window="flattop"`` when
amplitudes of tones between bins matter (scalloping loss < 0.01 dB) and
``"hann"`` for resolution.

Characteristic frequencies (:func:`bearing_frequencies`)
--------------------------------------------------------
Rolling without slip, rings turning at f_i (inner) and f_o (outer) [Hz],
gamma = (d / d_m) cos(alpha) with ball diameter d, pitch diameter d_m and
contact angle alpha (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed.,
ch. 7; Randall & Antoni, MSSP 25 (2011) 485, eqs. 1-4):

- ball train (cage, FTF): f_c = [f_i (1 - gamma) + f_o (1 + gamma)] / 2
- ball pass, outer race (BPFO): Z |f_c - f_o|
- ball pass, inner race (BPFI): Z |f_i - f_c|
- ball spin (about its own axis, relative to the cage):
  f_b = (d_m / (2 d)) (1 - gamma^2) |f_i - f_o|; a ball defect strikes both
  races once per spin revolution, hence the "ball defect" line 2 f_b that
  many tables (e.g. the CWRU bearing data centre) call BSF.

Extra lines (e.g. the ball-ball collision frequency of a cage-less bearing,
which no kinematic formula gives) are passed in by name.
"""
from __future__ import annotations

import math

import numpy as np

from .errors import DynamicsInputError

NAMES = ("Shaft [Hz]", "Ball train (cage) [Hz]", "Ball spin [Hz]", "Ball defect (2 x spin) [Hz]",
         "BPFO [Hz]", "BPFI [Hz]")


def amplitude_spectrum(x, fs, window="hann", detrend="constant", nfft=None):
    """One-sided amplitude spectrum of a uniformly sampled signal.

    Parameters
    ----------
    x : array_like (N,)
        Signal (any unit U).
    fs : float
        Sampling frequency [Hz].
    window : str or tuple
        Window for ``scipy.signal.get_window`` ("hann", "flattop", "boxcar" ...).
    detrend : {"constant", "linear", False}
        Removed before windowing.
    nfft : int, optional
        FFT length (zero padding); default N.

    Returns
    -------
    f : ndarray
        Frequencies [Hz].
    amplitude : ndarray
        Amplitude [U] of a sinusoid at each frequency.

    Examples
    --------
    >>> t = np.arange(1000) / 1000.0
    >>> f, a = amplitude_spectrum(3.0 * np.sin(2 * np.pi * 50.0 * t), 1000.0)
    >>> round(float(a[np.argmin(abs(f - 50.0))]), 6)
    3.0
    """
    from scipy.signal import periodogram

    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 4 or not np.all(np.isfinite(x)):
        raise DynamicsInputError(f"x (shape {x.shape}) must be a 1-D array of >= 4 finite samples")
    if not (float(fs) > 0.0 and math.isfinite(fs)):
        raise DynamicsInputError(f"fs = {fs!r} must be a sampling frequency > 0 [Hz]")
    f, p = periodogram(x, fs=fs, window=window, nfft=nfft, detrend=detrend, scaling="spectrum")
    amp = np.sqrt(2.0 * p)
    amp[0] = math.sqrt(p[0])
    n = x.size if nfft is None else int(nfft)
    if n % 2 == 0:
        amp[-1] = math.sqrt(p[-1])
    return f, amp


def bearing_frequencies(inner_frequency, ball_diameter, pitch_diameter, n_balls, contact_angle=0.0,
                        outer_frequency=0.0, extra=None):
    """Kinematic characteristic frequencies [Hz] of a ball bearing (no slip).

    Parameters
    ----------
    inner_frequency, outer_frequency : float
        Ring rotation frequencies [Hz] (rev/s; rpm / 60).
    ball_diameter, pitch_diameter : float
        [m] (any common length unit: only the ratio enters).
    n_balls : int
        Number of balls Z.
    contact_angle : float
        [rad].
    extra : dict, optional
        Further named lines [Hz], e.g. ``{"Collision [Hz]": 412.0}``; copied into the result.

    Returns
    -------
    dict
        ``NAMES`` -> frequency [Hz] (plus the extra lines).

    Examples
    --------
    >>> f = bearing_frequencies(1.0, 0.3126, 1.537, 9)  # CWRU SKF 6205, multiples of shaft speed
    >>> round(f["BPFO [Hz]"], 4), round(f["BPFI [Hz]"], 4)
    (3.5848, 5.4152)
    """
    d, dm, z = float(ball_diameter), float(pitch_diameter), int(n_balls)
    if not (d > 0 and dm > d):
        raise DynamicsInputError(
            f"ball_diameter = {ball_diameter!r} and pitch_diameter = {pitch_diameter!r}: need 0 < d < d_m")
    if z < 1:
        raise DynamicsInputError(f"n_balls = {n_balls!r} must be >= 1")
    fi, fo = float(inner_frequency), float(outer_frequency)
    gamma = d / dm * math.cos(contact_angle)
    fc = 0.5 * (fi * (1.0 - gamma) + fo * (1.0 + gamma))
    fb = dm / (2.0 * d) * (1.0 - gamma * gamma) * abs(fi - fo)
    out = {
        "Shaft [Hz]": abs(fi),
        "Ball train (cage) [Hz]": abs(fc),
        "Ball spin [Hz]": fb,
        "Ball defect (2 x spin) [Hz]": 2.0 * fb,
        "BPFO [Hz]": z * abs(fc - fo),
        "BPFI [Hz]": z * abs(fi - fc),
    }
    for name, value in (extra or {}).items():
        out[str(name)] = float(value)
    return out


def peaks_near(f, amplitude, marks, rel_width=0.03, min_bins=2):
    """The largest spectral line near each marked frequency.

    Parameters
    ----------
    f, amplitude : ndarray
        A spectrum (e.g. from :func:`amplitude_spectrum`).
    marks : dict
        Name -> marked frequency [Hz] (e.g. from :func:`bearing_frequencies`).
    rel_width : float
        Search half-width as a fraction of the marked frequency (slip moves
        lines by 1-2 %).
    min_bins : int
        Smallest search half-width in frequency bins.

    Returns
    -------
    list of dict
        Per mark: "Name", "Marked [Hz]", "Peak [Hz]" (refined by a parabola
        through the log amplitudes of the three top bins), "Amplitude" (of the
        top bin), "Deviation [-]" (peak / marked - 1).  Marks beyond the
        spectrum are skipped.
    """
    f = np.asarray(f, dtype=float)
    a = np.asarray(amplitude, dtype=float)
    if f.shape != a.shape or f.ndim != 1 or f.size < 3:
        raise DynamicsInputError("f and amplitude must be 1-D arrays of the same length >= 3")
    df = f[1] - f[0]
    out = []
    for name, f0 in marks.items():
        f0 = float(f0)
        if not (0.0 < f0 <= f[-1]):
            continue
        half = max(rel_width * f0, min_bins * df)
        idx = np.nonzero(np.abs(f - f0) <= half)[0]
        k = int(idx[np.argmax(a[idx])])
        fp = f[k]
        if 0 < k < f.size - 1 and np.all(a[k - 1:k + 2] > 0):
            l0, l1, l2 = np.log(a[k - 1:k + 2])
            den = l0 - 2.0 * l1 + l2
            if den < 0:
                fp = f[k] + 0.5 * (l0 - l2) / den * df
        out.append({"Name": name, "Marked [Hz]": f0, "Peak [Hz]": float(fp), "Amplitude": float(a[k]),
                    "Deviation [-]": float(fp / f0 - 1.0)})
    return out


def plot_spectrum(f, amplitude, marks=None, ax=None, unit="m/s^2", f_max=None, log=True):
    """Plot an amplitude spectrum with the marked frequencies as labelled vertical lines.

    Returns the matplotlib figure (Agg-safe; nothing is shown).  ``marks`` is a
    name -> frequency [Hz] mapping such as :func:`bearing_frequencies` returns.
    """
    import matplotlib

    if ax is None:
        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(8, 4))
    else:
        fig = ax.figure
    f = np.asarray(f)
    a = np.asarray(amplitude)
    sel = f <= (f_max if f_max is not None else f[-1])
    (ax.semilogy if log else ax.plot)(f[sel], a[sel], lw=0.8, color="k")
    for k, (name, f0) in enumerate((marks or {}).items()):
        if 0 < f0 <= f[sel][-1]:
            ax.axvline(f0, color=f"C{k % 10}", ls="--", lw=0.8, label=f"{name.replace(' [Hz]', '')} {f0:.4g} Hz")
    ax.set_xlabel("Frequency [Hz]")
    ax.set_ylabel(f"Amplitude [{unit}]")
    if marks:
        ax.legend(fontsize=7, loc="upper right")
    return fig
