"""Window statistics of a tapered roller bearing run (Wu et al. 2018, paper A, sec. 4): per zone
(loaded, unloaded, all) the mean, amplitude and largest magnitude of each roller's tilt, skew, slip and
radial displacement over a time window; the cage's speed, slip and whirl; a periodicity measure.

The diagnostics ``D`` are those of :meth:`lubedyn.dynamics.tapered.model.TaperedBearing.diagnostics` (arrays
(samples, rollers) by name) with "Radial displacement [m]" and "Loaded zone [-]" added by the scene.
"""
from __future__ import annotations

import math

import numpy as np


def window_stats(x) -> dict:
    """Mean, amplitude (half the range) and largest magnitude of the finite values of ``x`` (each None when
    it has none)."""
    x = np.asarray(x, dtype=float)
    x = x[np.isfinite(x)]
    if x.size == 0:
        return {"mean": None, "amplitude": None, "largest magnitude": None}
    return {"mean": float(np.mean(x)), "amplitude": float(0.5 * (np.max(x) - np.min(x))),
            "largest magnitude": float(np.max(np.abs(x)))}


def periodicity(t, x, lag):
    """Pearson correlation of roller j's signal ``x[:, j]`` at t + ``lag`` with roller j+1's at t, over
    all rollers and the samples of ``t`` where t + lag is recorded.  In a motion that is steady in the
    loaded zone's frame, roller j reaches roller j+1's azimuth one roller pass (``lag`` = 2 pi/(Z
    omega_c)) later and repeats its signal: 1 for a periodic motion, near 0 for an irregular one.  None
    when the window is shorter than the lag or the signal constant."""
    keep = t + lag <= t[-1]
    if keep.sum() < 3:
        return None
    later = np.stack([np.interp(t[keep] + lag, t, x[:, j]) for j in range(x.shape[1])], axis=1)
    nxt = np.roll(x[keep], -1, axis=1)
    a, b = later.ravel() - later.mean(), nxt.ravel() - nxt.mean()
    den = math.sqrt(float(a @ a) * float(b @ b))
    return float(a @ b / den) if den > 0 else None


def _mean(x):
    return float(np.mean(x)) if x.size else None


def window_summary(model, t, D, lo, hi) -> dict:
    """Means, amplitudes (half the range) and largest magnitudes of tilt, skew, roller slip and radial
    displacement per zone (loaded, unloaded, all) over lo <= t <= hi; the cage's speed and slip; the
    periodicity of skew and tilt (:func:`periodicity` at the measured roller-pass period); where ``D`` has
    them (the tapered bearing), the zone means of the terms of the rollers' tilt moment and of their sum."""
    w = (t >= lo) & (t <= hi)
    out = {"Window [s]": [float(t[w][0]), float(t[w][-1])], "Samples [-]": int(w.sum())}
    zone = D["Loaded zone [-]"][w]
    for name, key in (("Tilt [rad]", "Tilt [rad]"), ("Skew [rad]", "Skew [rad]"), ("Roller slip [-]", "Roller slip [-]"),
                      ("Spin slip [-]", "Spin slip [-]"), ("Radial displacement [m]", "Radial displacement [m]")):
        x = D[key][w]
        out[name] = {"loaded zone": window_stats(x[zone]), "unloaded zone": window_stats(x[~zone]), "all": window_stats(x)}
    for name in ("Tilt [rad]", "Skew [rad]"):
        m = out[name]["all"]["mean"]
        out[name.replace("[rad]", "mean [deg]")] = None if m is None else math.degrees(m)
    out["Rollers in the loaded zone, mean [-]"] = float(np.mean(zone.sum(axis=1)))
    terms = [k for k in D if k.startswith("Tilt moment, ")]
    if terms:   # the terms of the contacts' moment about the rollers' tilt axes, mean per zone, and their sum
        out["Tilt moment means [N m]"] = {
            z: {**{k[len("Tilt moment, "):-len(" [N m]")]: _mean(D[k][w][sel]) for k in terms},
                "sum": _mean(sum(D[k][w] for k in terms)[sel])}
            for z, sel in (("loaded zone", zone), ("unloaded zone", ~zone))}
    if "Cone tilt [rad]" in D:
        for k, ax in enumerate("yz"):
            out[f"Cone tilt {ax} [rad]"] = window_stats(D["Cone tilt [rad]"][w, k])
    orbital = float(np.mean(D["Orbital speed [rad/s]"][w]))
    if orbital > 0.0:
        lag = 2.0 * math.pi / (model.n_rollers * orbital)
        out["Roller pass period [s]"] = lag
        out["Skew periodicity [-]"] = periodicity(t[w], D["Skew [rad]"][w], lag)
        out["Tilt periodicity [-]"] = periodicity(t[w], D["Tilt [rad]"][w], lag)
    if "Cage speed [rad/s]" in D:
        out["Cage speed, mean [rpm]"] = float(np.mean(D["Cage speed [rad/s]"][w])) * 30 / math.pi
        out["Cage slip [-]"] = window_stats(D["Cage slip [-]"][w])
        r = np.hypot(*D["Cage centre [m]"][w].T)
        out["Cage centre from the cone's, mean [m]"] = float(np.mean(r))
        out["Cage centre from the cone's, largest [m]"] = float(np.max(r))
    return out
