r"""Morris screening for studies (``[study] combine = "morris"``): which of many uncertain inputs move an
output, from a few runs.

Morris's elementary-effects method (Morris 1991, Technometrics 33, 161; the mu* measure of Campolongo,
Cariboni & Saltelli 2007, Environ. Model. Softw. 22, 1509).  Each of the k factors is scaled to x in
[0, 1] (linearly between the axis's two values, or in log10 for the keys of ``log``) on a grid of p
levels {0, 1/(p-1), ..., 1}.  A trajectory starts at a random grid point whose coordinates leave room
for the step Delta = p / (2 (p - 1)) and moves one factor at a time by +Delta or -Delta (a random order
and random signs), so it has k + 1 points.  For trajectory t and factor i the elementary effect is::

    EE_i^t = (y(x + Delta_i e_i) - y(x)) / Delta_i        (Delta_i = +-Delta, x in the scaled units)

and over the r trajectories::

    mu_i = mean_t EE_i^t,   mu*_i = mean_t |EE_i^t|,   sigma_i = std_t EE_i^t (ddof = 1)

mu*_i ranks the factors by influence (in output units per full range of the factor), sigma_i says how
much the effect depends on the other factors (interaction or non-linearity).  r (k + 1) runs in all.
The points come from ``numpy.random.default_rng(seed)``: the same study file gives the same runs on any
machine.  Checked in tests/test_screening.py on functions whose effects are known in closed form
(a linear function: mu* = |coefficient| x range exactly, sigma = 0; a product: sigma > 0).
"""
from __future__ import annotations

import math
import re

import numpy as np

from lubedyn.lubrication.errors import InputError

_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


def split_value(key: str, value) -> tuple[float, str]:
    """(number, unit text) of an axis end: a number, or a string "number unit" ("0.3 GPa")."""
    if isinstance(value, bool):
        raise InputError(f"axes.{key!r} = {value!r}: a Morris factor needs two numbers (with units), not booleans")
    if isinstance(value, (int, float)):
        return float(value), ""
    if isinstance(value, str):
        m = _NUMBER.match(value)
        if m:
            return float(m.group(1)), m.group(2)
    raise InputError(f"axes.{key!r} = {value!r}: a Morris factor's ends must be numbers or \"number unit\" strings")


def factor_ends(key: str, values: list, log: bool) -> tuple[float, float, str]:
    """(low, high, unit) of an axis ``[low, high]`` (same unit text at both ends; > 0 for ``log``)."""
    if not isinstance(values, list) or len(values) != 2:
        raise InputError(f"axes.{key!r} = {values!r}: with combine = 'morris' each axis is a range [low, high]")
    (lo, u1), (hi, u2) = split_value(key, values[0]), split_value(key, values[1])
    if u1 != u2:
        raise InputError(f"axes.{key!r} = {values!r}: both ends must be written in one unit ({u1!r} and {u2!r})")
    if not lo < hi:
        raise InputError(f"axes.{key!r} = {values!r}: the range must be [low, high] with low < high")
    if log and lo <= 0.0:
        raise InputError(f"axes.{key!r} = {values!r}: a log-scaled factor (study.morris.log) needs low > 0")
    return lo, hi, u1


def trajectories(k: int, r: int, levels: int, seed: int) -> np.ndarray:
    """(r, k + 1, k) scaled points in [0, 1]: r Morris trajectories on a ``levels``-level grid."""
    if k < 1 or r < 2 or levels < 2 or levels % 2:
        raise InputError(f"study.morris: needs >= 1 factor, trajectories >= 2 and an even number of levels >= 2 "
                         f"(got {k} factors, trajectories = {r}, levels = {levels})")
    rng = np.random.default_rng(seed)
    step = levels / (2.0 * (levels - 1))
    grid = np.arange(levels) / (levels - 1)
    out = np.empty((r, k + 1, k))
    for t in range(r):
        # start points from the lower half of the grid, so that +Delta stays inside; then flip each factor
        # with probability 1/2 and move it by -Delta instead (Morris's D* signs)
        start = rng.choice(grid[grid <= 1.0 - step + 1e-12], size=k)
        signs = rng.choice((-1.0, 1.0), size=k)
        x = np.where(signs > 0, start, start + step)
        out[t, 0] = x
        for j, i in enumerate(rng.permutation(k)):
            x = x.copy()
            x[i] += signs[i] * step
            out[t, j + 1] = x
    return np.round(out, 12)


def scaled_to_value(x: float, lo: float, hi: float, unit: str, log: bool):
    """The axis value at scaled ``x`` in [0, 1]: a number, or "number unit" when the axis had a unit."""
    v = 10.0 ** (math.log10(lo) + x * (math.log10(hi) - math.log10(lo))) if log else lo + x * (hi - lo)
    v = float(f"{v:.12g}")  # 12 digits: the value the run gets is the design's to 1e-12
    return f"{v:.12g} {unit}" if unit else v


def design(axes: dict, r: int, levels: int, seed: int, log: tuple = ()) -> tuple[list[dict], np.ndarray]:
    """The Morris runs of ``axes`` {key: [low, high]}: (points as {key: value}, scaled (r (k+1), k))."""
    keys = list(axes)
    for key in log:
        if key not in axes:
            raise InputError(f"study.morris.log: {key!r} is not an axis ({', '.join(map(repr, keys))})")
    ends = [factor_ends(key, axes[key], key in log) for key in keys]
    X = trajectories(len(keys), r, levels, seed).reshape(-1, len(keys))
    pts = [{key: scaled_to_value(x[i], *ends[i], key in log) for i, key in enumerate(keys)} for x in X]
    return pts, X


def effects(X: np.ndarray, y, k: int) -> list[dict]:
    """Per factor: mu, mu*, sigma of the elementary effects, and how many trajectories gave one (a
    trajectory step whose two runs both have a finite output).  ``X`` (r (k+1), k) scaled points, ``y``
    their outputs in the same order (None or nan: a failed run)."""
    X = np.asarray(X, float).reshape(-1, k + 1, k)
    y = np.array([np.nan if v is None else float(v) for v in y]).reshape(-1, k + 1)
    ee = [[] for _ in range(k)]
    for t in range(X.shape[0]):
        for j in range(k):
            d = X[t, j + 1] - X[t, j]
            i = int(np.flatnonzero(d)[0])
            a, b = y[t, j], y[t, j + 1]
            if math.isfinite(a) and math.isfinite(b):
                ee[i].append((b - a) / d[i])
    out = []
    for i in range(k):
        e = np.array(ee[i])
        out.append({"mu": float(e.mean()) if e.size else None,
                    "mu*": float(np.abs(e).mean()) if e.size else None,
                    "sigma": float(e.std(ddof=1)) if e.size > 1 else None,
                    "effects": int(e.size)})
    return out
