"""Correlation dimension of a sampled trajectory (Grassberger & Procaccia 1983): what "fractal" is measured as.

Paper B (Zhang et al., *Symmetry* 16 (2024) 741, Figs. 6-8) calls the balls' phase portraits (displacement
against velocity, per direction) "fractal" with "an infinite level of self-similarity" and compares their
"fractal" across speeds, without a number.  The number that says how a set fills space at small scales is
its correlation dimension: with C(r) the fraction of point pairs closer than r,

    C(r) ~ r^D2   over a range of r (the scaling range),

D2 = 1 for a closed curve (a limit cycle: periodic motion), the space's dimension for a set that fills it
(noise, or a high-dimensional motion projected into a plane), and a non-integer value in between for a
fractal set (the Henon attractor: 1.21, Grassberger & Procaccia 1983, Physica D 9, 189; the Lorenz
attractor: 2.05, same paper).  A phase portrait is a two-dimensional projection: it can show a fractal only
where the motion's own dimension is below 2; a chaotic motion of a many-ball bearing projects onto a set
that fills the plane, D2 -> 2, whatever its attractor's dimension is.

Method (:func:`correlation_dimension`): each coordinate scaled by its standard deviation; at most
``max_points`` points evenly spaced in time; pair counts at log-spaced radii by
``scipy.spatial.cKDTree.count_neighbors``, less the pairs closer in time than the Theiler window (counted
directly, lag by lag: at small r a smooth curve's neighbours in time would make every set look like a
curve, slope 1); local slopes d log C / d log r by central differences; the scaling range is the widest
run of radii (at least a factor ``min_span`` in r) whose local slopes stay within ``plateau`` (relative) of
their median; D2 is the least-squares slope of log C against log r over it.  No such run: no D2, and the
verdict says so.  Checked (tests/test_dimension.py; 4,000 points): Henon 1.198 (1.21), a circle 1.011,
uniform noise in the plane 1.964, points on a sphere 1.997, Lorenz in three dimensions 2.10 (2.05), an
AR(1) noise's (x, dx) portrait 2.01 ("fills the space").  The verdict's integer test (within 0.1) cannot
tell Lorenz's 2.05 from 2: a D2 within 0.1 of an integer is "integer", not "not fractal".
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: radii of the pair counts, log-spaced from 1e-3 to R_MAX of the scaled set's extent (its largest range):
#: above about a quarter of the extent the count saturates (every point has the whole set as neighbours)
RADII = 32
R_MAX = 0.25
#: the local slopes of a scaling range stay within this fraction of their median
PLATEAU = 0.12
#: a scaling range spans at least this factor in r
MIN_SPAN = 4.0
#: a radius counts only where this many pairs lie within it (fewer: the count's noise sets the slope)
MIN_PAIRS = 50


@dataclass(frozen=True)
class CorrelationDimension:
    """:func:`correlation_dimension`'s result: ``value`` (None without a scaling range), its scaling range
    ``r_range`` (in the scaled coordinates), the local slopes' spread over it, the points used, and a
    ``verdict``: "curve (periodic)", "fills the space (d = n)", "non-integer (fractal)", "integer",
    "no scaling range" (with why), or "no dimension" (a slope above the space's dimension d + 0.1, which no
    set in d dimensions has: value None)."""

    value: float | None
    r_range: tuple[float, float] | None
    spread: float | None
    points: int
    verdict: str


def pair_counts(points: np.ndarray, radii: np.ndarray, theiler: int) -> np.ndarray:
    """Unordered pairs (i < j, j - i > ``theiler``) of ``points`` (n, d) closer than each radius."""
    from scipy.spatial import cKDTree

    n = points.shape[0]
    tree = cKDTree(points)
    ordered = tree.count_neighbors(tree, radii).astype(np.int64)  # ordered pairs, self-pairs included
    counts = (ordered - n) // 2
    for lag in range(1, theiler + 1):  # the pairs closer in time than the Theiler window, counted directly
        d = np.sqrt(np.sum((points[lag:] - points[:-lag]) ** 2, axis=1))
        counts -= np.searchsorted(np.sort(d), radii, side="left")
    return counts


def correlation_dimension(points, *, max_points: int = 4000, theiler: int | None = None,
                          radii: int = RADII, plateau: float = PLATEAU, min_span: float = MIN_SPAN
                          ) -> CorrelationDimension:
    """Correlation dimension of the sampled set ``points`` ((n, d), rows in time order); see the module.

    ``theiler``: pairs at most this many (kept) samples apart are left out; default: the lag at which the
    first coordinate's autocorrelation first drops below 1/e (at least 1).  Returns
    :class:`CorrelationDimension`.

    >>> t = np.linspace(0.0, 200.0, 4000)
    >>> round(correlation_dimension(np.c_[np.cos(t), np.sin(t)]).value, 2)
    1.0
    """
    x = np.asarray(points, dtype=float)
    if x.ndim != 2 or x.shape[0] < 100:
        raise ValueError(f"points has shape {x.shape}: need (n >= 100, d)")
    if not np.all(np.isfinite(x)):
        raise ValueError("points holds non-finite values")
    scale = x.std(axis=0)
    if np.any(scale == 0.0):
        return CorrelationDimension(None, None, None, x.shape[0], "no scaling range: a coordinate does not move")
    stride = max(1, math.ceil(x.shape[0] / max_points))
    y = (x[::stride] - x.mean(axis=0)) / scale
    n, d = y.shape
    if theiler is None:
        a = y[:, 0] - y[:, 0].mean()
        ac = np.correlate(a, a, mode="full")[n - 1:] / (a @ a)
        below = np.flatnonzero(ac < 1.0 / math.e)
        theiler = int(below[0]) if below.size else n // 10
    theiler = max(1, min(int(theiler), n // 4))
    extent = float(np.max(np.ptp(y, axis=0)))
    r = np.geomspace(extent * 1e-3, extent * R_MAX, radii)
    counts = pair_counts(y, r, theiler)
    ok = counts >= MIN_PAIRS
    if ok.sum() < 4:
        return CorrelationDimension(None, None, None, n, "no scaling range: too few close pairs")
    lr, lc = np.log(r[ok]), np.log(counts[ok].astype(float))
    local = np.gradient(lc, lr)
    # the widest run of radii whose local slopes stay within `plateau` of the run's median
    best = None
    for i in range(lr.size):
        for j in range(lr.size - 1, i, -1):
            if best is not None and j - i <= best[1] - best[0]:
                break
            if lr[j] - lr[i] < math.log(min_span):
                continue
            s = local[i:j + 1]
            m = float(np.median(s))
            if m > 0 and np.all(np.abs(s - m) <= plateau * m):
                best = (i, j)
                break
    if best is None:
        return CorrelationDimension(None, None, None, n, f"no scaling range: the local slopes do not stay within "
                                                         f"{plateau:.0%} over a factor {min_span:g} in r")
    i, j = best
    value = float(np.polyfit(lr[i:j + 1], lc[i:j + 1], 1)[0])
    spread = float(np.ptp(local[i:j + 1]) / max(abs(value), 1e-300))
    if value > d + 0.1:  # impossible for a set in d dimensions: the count's slope is not a dimension here
        return CorrelationDimension(None, (float(math.exp(lr[i])), float(math.exp(lr[j]))), spread, n,
                                    f"no dimension: the slope {value:.3g} exceeds the space's dimension {d} "
                                    "(too few close pairs for the counts to scale, or a lattice-like sampling)")
    if abs(value - 1.0) < 0.1:
        verdict = "curve (periodic)"
    elif value > d - 0.1:
        verdict = f"fills the space (d = {d})"
    elif abs(value - round(value)) < 0.1:
        verdict = "integer"
    else:
        verdict = "non-integer (fractal)"
    return CorrelationDimension(value, (float(math.exp(lr[i])), float(math.exp(lr[j]))), spread, n, verdict)
