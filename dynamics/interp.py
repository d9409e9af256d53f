"""Interpolation of tabulated film maps inside numba kernels: 1, 2 and 3 axes,
multilinear or monotone cubic (PCHIP), in log space per axis and for the values.

The kernels take plain arrays and scalars so that any ``@njit`` function (the
bearing right-hand side) can call them; :meth:`lubedyn.maps.FilmMap.kernel_arrays`
prepares the arrays from a map.  Everything here is independent of
``lubrication`` and ``coupling``.

Interpolation space
-------------------
Each axis k has nodes x_k,0 < ... < x_k,n-1 (n >= 2) and a flag ``log_k``.  The
kernel works in t_k = log(x_k) when ``log_k`` is set, else t_k = x_k, and on
u = log(v) when ``logv`` is set, else u = v.  The arrays handed to a kernel are
**already transformed**: ``ax_k`` holds t_k at the nodes and ``values`` holds u
(use :func:`prepare_axis` / :func:`prepare_values`), so a query costs one
``log`` per log axis and one ``exp`` for log values, nothing per node.

Log of the values is only possible for outputs that are strictly positive on
the whole grid (film thickness, a stiffness, a force on a log approach-speed
axis).  A **signed** output -- the squeeze force over an approach-speed axis
that crosses zero, a traction coefficient over a slide-to-roll axis through 0 --
is interpolated as it is (``logv = 0``) on a linear axis; its sign changes are
then represented exactly where the data change sign, and PCHIP keeps it monotone
where the data are.  :class:`lubedyn.maps.FilmMap` picks ``logv`` per output
this way (log only when every value is > 0).

Methods (``method``)
--------------------
0. multilinear in (t, u): reproduces any function that is multilinear in t
   exactly; second order, f - I f = O(h^2).
1. monotone piecewise cubic Hermite along each axis in turn (tensor
   product applied dimension by dimension, as
   ``scipy.interpolate.RegularGridInterpolator(method="pchip")`` does).  Node
   slopes are Fritsch-Butland's weighted harmonic mean of the neighbouring
   secants (zero where the secants change sign or one is zero), and the end
   slopes are the shape-preserving three-point formula, both exactly as
   ``scipy.interpolate.PchipInterpolator``: monotone data give a monotone
   interpolant without overshoot.  Third order on smooth data (the harmonic-mean
   slopes are second-order accurate; a cubic Hermite with O(h^2) slopes errs by
   O(h^3)).  A two-node axis is linear.  Cost grows as 4^ndim 1-D evaluations
   with their slope formulas (21 in 3-D).
2. ``hermite``: tensor-product cubic Hermite on node values and PCHIP node
   derivatives precomputed by :func:`hermite_data` (``hermite1/2/3[_grad]``,
   which take that (2^ndim, n0, ...) array in place of ``values`` and no
   ``method``).  Identical to method 1 in 1-D and along every grid line, C1,
   third order, exact for multilinear functions; between grid lines it differs
   from method 1 by O(h^3).  No slope formulas at query time: in 3-D about 5x
   cheaper than method 1.  Monotone data stay monotone along grid lines; between
   them neither cubic method guarantees monotonicity in 2-D/3-D (the sequential
   method is nonlinear in the data, this one has cross-derivative terms).

Speed: the hermite kernels have a single exit (a NaN result is selected at the
end after a harmless evaluation at the clamped point), write the counter on
every query (adding 0 or 1) and call only ``inline="always"`` helpers, so that
numba keeps no atomic reference counting of the array arguments (an early
return, a conditional store, ``int()`` or a call to a non-inlined numba
function brings it back).  The tensor sums are contracted one axis at a time,
with ``fastmath={"contract"}`` (fused multiply-adds: one rounding fewer) and
``error_model="numpy"`` (no division-by-zero branches; no division here can be
by zero on valid axes).  The multilinear and pchip kernels call non-inlined
helpers and keep the reference counting.  Measured costs per query, and a
per-cell polynomial variant of method 2 kept as a benchmark, are in
``benchmarks/maps.py`` and ``benchmarks/interp_cells.py``.

Gradients (``*_grad``) are the exact derivatives of the interpolant, returned
with respect to the **physical** coordinates x_k (chain rule through the logs)
and for the physical value v = exp(u).  For the cubic method the derivative
along an earlier axis is carried through the later axes' slope formulas
(forward mode: the partial derivatives of a 1-D PCHIP value with respect to its
four data values), so ``grad`` equals the derivative of ``value`` everywhere
inside a cell.  dF/dx from a force map is a stiffness.

Queries outside the axes
------------------------
``mode = 0`` (clamp): each coordinate outside its axis is moved to the nearest
end and ``counter[0]`` (an int64 array of length >= 1 owned by the caller) is
incremented once per query that had any coordinate outside (the hermite kernels
read and write it on every query, adding 0 or 1: not for sharing between
threads); the run reports the count.  ``mode = 1``: the kernel returns NaN (gradients NaN) and the caller
raises.  Never extrapolation.  The gradient at a clamped point is the one-sided
derivative of the interpolant at the boundary (useful as a stiffness; it is not
the zero derivative of the clamped function).  A NaN coordinate gives NaN in
both modes; mode 0 counts it in ``counter[0]`` like a query outside (it has no
place on the axes), so a run that clamps reports it, and mode 1's caller
raises (:meth:`lubedyn.maps.FilmMap.__call__` names the NaN coordinate).

Signatures (``ax*``: float64 1-D, ``values``: float64 of ndim 1, 2, 3, C order,
shape (n0[, n1[, n2]]); ``log*``, ``logv``, ``method``, ``mode``: int;
``counter``: int64 1-D)::

    interp1(ax0, log0, values, logv, method, x0, mode, counter) -> v
    interp2(ax0, ax1, log0, log1, values, logv, method, x0, x1, mode, counter) -> v
    interp3(ax0, ax1, ax2, log0, log1, log2, values, logv, method, x0, x1, x2, mode, counter) -> v
    interp1_grad(...) -> (v, dv/dx0)
    interp2_grad(...) -> (v, dv/dx0, dv/dx1)
    interp3_grad(...) -> (v, dv/dx0, dv/dx1, dv/dx2)
    hermite1(ax0, log0, deriv, logv, x0, mode, counter)               (and hermite2, hermite3,
    hermite3(ax0, ax1, ax2, log0, log1, log2, deriv, logv, x0, x1, x2, mode, counter)   hermite*_grad)

>>> import numpy as np
>>> ax = prepare_axis(np.array([1.0, 2.0, 4.0]), True)
>>> u = prepare_values(np.array([1.0, 4.0, 16.0]), True)    # v = x^2, exact in log-log
>>> counter = np.zeros(1, dtype=np.int64)
>>> round(interp1(ax, 1, u, 1, 0, 3.0, 0, counter), 12)
9.0
>>> round(interp1(ax, 1, u, 1, 0, 8.0, 0, counter), 12), int(counter[0])   # clamped to x = 4
(16.0, 1)
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, types
from numba.extending import typeof_impl

from lubedyn.lubrication.laws.jit import JIT

_JIT = dict(JIT, nogil=True)  # lubedyn's options (lubedyn.lubrication.laws.jit), releasing the GIL for threaded map queries
_INLINE = dict(_JIT, inline="always")
_FMA = dict(_JIT, fastmath={"contract"})  # a*b + c -> one fused multiply-add (one rounding fewer)

LINEAR, PCHIP, HERMITE = 0, 1, 2
CLAMP, NAN = 0, 1
METHODS = {"linear": LINEAR, "pchip": PCHIP, "hermite": HERMITE}


class Fixed(int):
    """An int that numba types as its own value (``Literal[int](v)``), so a kernel receiving it is
    compiled for that value: a branch on it is decided at compile time.

    A map's options (the axis scales ``log0..2`` and ``logv``, the method, the mode, the kind of an
    axis) are fixed for the map's life: :func:`fixed_options` hands them to the kernels as a tuple of
    ``Fixed``, and ``opts[MO_LOG0]`` (a constant index) is then a compile-time constant in every kernel
    that reads it.  The kernels are the same source for a runtime int64 array of options (the tests'
    and the Python front end's) and for fixed ones: numba compiles one version per argument *types*
    (per combination of values here), cached on disk like any other signature, and the arithmetic is
    the same, so the results are the same bits (``tests/test_interp.py``).  Measured
    (``benchmarks/maps.py --fixed-options``, before/after interleaved; ``benchmarks/HISTORY.md``, issue 42):
    the 3-D hermite value + gradient query 0.83 of the runtime-option one, the README main job's
    integration 0.82-0.93, the cold compile of the cage-less right-hand side unchanged.

    A value numba cannot fingerprint: a Python-side call of a kernel with fixed options is typed by
    ``numba.typeof`` each time (tens of microseconds), which is nothing against a right-hand side called
    inside a compiled integrator, and is never mistaken for another combination of values."""

    __slots__ = ()

    def __repr__(self):
        return f"Fixed({int(self)})"

    def __reduce__(self):  # pickled (Dask workers, background compilation) as the same type
        return (Fixed, (int(self),))


@typeof_impl.register(Fixed)
def _typeof_fixed(value, context):
    return types.literal(int(value))


def fixed_options(opts) -> tuple:
    """``opts`` (a sequence of ints: a map's ``MO_*`` options) as a tuple of :class:`Fixed`: what the
    kernels read at compile time."""
    return tuple(Fixed(int(v)) for v in opts)


def prepare_axis(nodes, log) -> np.ndarray:
    """Node coordinates in interpolation space (log(x) for a log axis), float64, checked increasing."""
    x = np.ascontiguousarray(nodes, dtype=np.float64)
    if x.ndim != 1 or x.size < 2:
        raise ValueError(f"an axis needs >= 2 nodes in a 1-D array, got shape {x.shape}")
    if log:
        if not np.all(x > 0):
            raise ValueError(f"a log axis needs nodes > 0, got min {x.min():g}")
        x = np.log(x)
    if not np.all(np.diff(x) > 0):
        raise ValueError("axis nodes must be strictly increasing")
    return x


def prepare_values(values, logv) -> np.ndarray:
    """Values in interpolation space (log(v) when ``logv``), float64, C order."""
    v = np.ascontiguousarray(values, dtype=np.float64)
    if logv:
        if not np.all(v > 0):
            raise ValueError(f"log values need every value > 0, got min {np.nanmin(v):g}")
        v = np.log(v)
    return np.ascontiguousarray(v)


# ---------------------------------------------------------------------------
# building blocks


@njit(**_INLINE)
def _coord(x, log):
    """x -> t (log when ``log``; -inf for x <= 0 on a log axis, which then lies below the axis)."""
    if log:
        if x > 0.0:
            return math.log(x)
        if x != x:
            return x
        return -np.inf
    return x


@njit(**_INLINE)
def locate(ax, t):
    """(cell i with ax[i] <= t <= ax[i+1], t clamped to the axis, 1 if t was outside)."""
    n = ax.size
    if not t >= ax[0]:  # below the axis, or NaN (the callers return NaN for a NaN coordinate)
        return 0, ax[0], 1
    if t > ax[n - 1]:
        return n - 2, ax[n - 1], 1
    # first guess: the cell of a uniformly spaced axis (linspace, or geomspace in log space); t >= ax[0],
    # so truncation is floor (np.int64, not int(): int() stops numba pruning the array refcounts)
    g = np.int64((t - ax[0]) / (ax[n - 1] - ax[0]) * (n - 1))
    if g > n - 2:
        g = n - 2
    if ax[g] <= t <= ax[g + 1]:
        return g, t, 0
    lo, hi = 0, n - 1
    while hi - lo > 1:
        mid = (lo + hi) >> 1
        if ax[mid] <= t:
            lo = mid
        else:
            hi = mid
    return lo, t, 0


# The multilinear / pchip kernels call the coordinate helpers as ordinary numba functions (LLVM inlines
# them): they keep reference counting anyway (their pchip branches call non-inlined helpers), and the
# numba-level inlining measured ~10 % slower for them.
@njit(**_JIT)
def _coord_call(x, log):
    return _coord(x, log)


@njit(**_JIT)
def locate_call(ax, t):
    return locate(ax, t)


@njit(**_JIT)
def _finish_call(u, logv):
    return _finish(u, logv)


@njit(**_JIT)
def _dtdx_call(t, log):
    return _dtdx(t, log)


@njit(**_INLINE)
def _cell(ax, x, log):
    """(cell i, clamped t, 1 if x was outside the axis, True if x is NaN) of a physical coordinate x."""
    t = _coord(x, log)
    i, c, o = locate(ax, t)
    return i, c, o, t != t


@njit(**_INLINE)
def _refuse(nan, out, mode, counter):
    """True when the query returns NaN (a NaN coordinate, or outside the axes in mode 1); in mode 0 a
    query outside the axes (clamped) or with a NaN coordinate adds 1 to ``counter[0]``.  The counter is written on every
    query (adding 0 or 1): a conditional store, like an early return, stops numba from pruning the
    atomic reference counting of the array arguments, which would cost more than the rest of a query."""
    refuse = nan or (out != 0 and mode == 1)
    counter[0] += (1 if (nan or out != 0) else 0) if mode == 0 else 0
    return refuse


@njit(**_JIT)
def _interior(h_left, h_right, m_left, m_right):
    """Fritsch-Butland node slope (scipy PchipInterpolator) and its partials
    with respect to the left and right secants."""
    if m_left * m_right <= 0.0:
        return 0.0, 0.0, 0.0
    w1 = 2.0 * h_right + h_left
    w2 = h_right + 2.0 * h_left
    den = w1 * m_right + w2 * m_left
    d = (w1 + w2) * m_left * m_right / den
    return d, (w1 + w2) * w1 * m_right * m_right / (den * den), (w1 + w2) * w2 * m_left * m_left / (den * den)


@njit(**_JIT)
def _edge(h0, h1, m0, m1):
    """Shape-preserving three-point end slope (scipy ``_edge_case``) and its
    partials with respect to the end secant m0 and the next one m1."""
    a = (2.0 * h0 + h1) / (h0 + h1)
    b = -h0 / (h0 + h1)
    d = a * m0 + b * m1
    if np.sign(d) != np.sign(m0):
        return 0.0, 0.0, 0.0
    if np.sign(m0) != np.sign(m1) and abs(d) > 3.0 * abs(m0):
        return 3.0 * m0, 3.0, 0.0
    return d, a, b


@njit(**_JIT)
def _pchip_seg(ax, i, t, ym, y0, y1, y2):
    """1-D PCHIP on cell [ax[i], ax[i+1]] from the values at nodes i-1 .. i+2
    (``ym``, ``y2`` unused when that node does not exist).

    Returns (v, dv/dt, dv/dym, dv/dy0, dv/dy1, dv/dy2)."""
    n = ax.size
    h0 = ax[i + 1] - ax[i]
    m0 = (y1 - y0) / h0
    has_left = i > 0
    has_right = i + 2 < n
    hl = 1.0
    hr = 1.0
    ml = 0.0
    mr = 0.0
    if has_left:
        hl = ax[i] - ax[i - 1]
        ml = (y0 - ym) / hl
    if has_right:
        hr = ax[i + 2] - ax[i + 1]
        mr = (y2 - y1) / hr
    # slope d0 at node i and d(d0)/d(ym, y0, y1, y2)
    if has_left:
        d0, a_l, a_0 = _interior(hl, h0, ml, m0)
        e0m, e00, e01, e02 = -a_l / hl, a_l / hl - a_0 / h0, a_0 / h0, 0.0
    elif has_right:
        d0, b_0, b_r = _edge(h0, hr, m0, mr)
        e0m, e00, e01, e02 = 0.0, -b_0 / h0, b_0 / h0 - b_r / hr, b_r / hr
    else:
        d0 = m0
        e0m, e00, e01, e02 = 0.0, -1.0 / h0, 1.0 / h0, 0.0
    # slope d1 at node i+1
    if has_right:
        d1, c_0, c_r = _interior(h0, hr, m0, mr)
        e1m, e10, e11, e12 = 0.0, -c_0 / h0, c_0 / h0 - c_r / hr, c_r / hr
    elif has_left:
        d1, c_0, c_l = _edge(h0, hl, m0, ml)
        e1m, e10, e11, e12 = -c_l / hl, c_l / hl - c_0 / h0, c_0 / h0, 0.0
    else:
        d1 = m0
        e1m, e10, e11, e12 = 0.0, -1.0 / h0, 1.0 / h0, 0.0
    s = (t - ax[i]) / h0
    s2 = s * s
    s3 = s2 * s
    h00 = 2.0 * s3 - 3.0 * s2 + 1.0
    h10 = s3 - 2.0 * s2 + s
    h01 = -2.0 * s3 + 3.0 * s2
    h11 = s3 - s2
    v = h00 * y0 + h10 * h0 * d0 + h01 * y1 + h11 * h0 * d1
    dv = ((6.0 * s2 - 6.0 * s) * (y0 - y1)) / h0 + (3.0 * s2 - 4.0 * s + 1.0) * d0 + (3.0 * s2 - 2.0 * s) * d1
    g0 = h10 * h0
    g1 = h11 * h0
    return (v, dv, g0 * e0m + g1 * e1m, h00 + g0 * e00 + g1 * e10, h01 + g0 * e01 + g1 * e11,
            g0 * e02 + g1 * e12)


@njit(**_JIT)
def _slope_in(h_left, h_right, m_left, m_right):
    """Value-only :func:`_interior`."""
    if m_left * m_right <= 0.0:
        return 0.0
    w1 = 2.0 * h_right + h_left
    w2 = h_right + 2.0 * h_left
    return (w1 + w2) * m_left * m_right / (w1 * m_right + w2 * m_left)


@njit(**_JIT)
def _slope_end(h0, h1, m0, m1):
    """Value-only :func:`_edge`."""
    d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
    if np.sign(d) != np.sign(m0):
        return 0.0
    if np.sign(m0) != np.sign(m1) and abs(d) > 3.0 * abs(m0):
        return 3.0 * m0
    return d


@njit(**_JIT)
def _pchip_val(ax, i, t, ym, y0, y1, y2):
    """Value-only :func:`_pchip_seg`."""
    n = ax.size
    h0 = ax[i + 1] - ax[i]
    m0 = (y1 - y0) / h0
    if i > 0:
        hl = ax[i] - ax[i - 1]
        ml = (y0 - ym) / hl
        d0 = _slope_in(hl, h0, ml, m0)
    if i + 2 < n:
        hr = ax[i + 2] - ax[i + 1]
        mr = (y2 - y1) / hr
        d1 = _slope_in(h0, hr, m0, mr)
        if i == 0:
            d0 = _slope_end(h0, hr, m0, mr)
    elif i > 0:
        d1 = _slope_end(h0, hl, m0, ml)
    else:
        d0 = m0
        d1 = m0
    s = (t - ax[i]) / h0
    s2 = s * s
    s3 = s2 * s
    return ((2.0 * s3 - 3.0 * s2 + 1.0) * y0 + (s3 - 2.0 * s2 + s) * h0 * d0 + (3.0 * s2 - 2.0 * s3) * y1
            + (s3 - s2) * h0 * d1)


@njit(**_JIT)
def _stencil(i, n):
    """Indices of nodes i-1, i, i+1, i+2 clipped into [0, n-1] (clipped ones are unused)."""
    return max(i - 1, 0), i, i + 1, min(i + 2, n - 1)


@njit(**_INLINE)
def _finish(u, logv):
    """(v, dv/du) of the interpolated u."""
    if logv:
        v = math.exp(u)
        return v, v
    return u, 1.0


@njit(**_INLINE)
def _dtdx(t, log):
    """dt/dx at the (clamped) coordinate."""
    if log:
        return math.exp(-t)
    return 1.0


# ---------------------------------------------------------------------------
# one axis


@njit(**_JIT)
def _core1(ax0, values, method, i, t):
    if method == 0:
        h = ax0[i + 1] - ax0[i]
        w = (t - ax0[i]) / h
        return (1.0 - w) * values[i] + w * values[i + 1], (values[i + 1] - values[i]) / h
    a, b, c, d = _stencil(i, ax0.size)
    r = _pchip_seg(ax0, i, t, values[a], values[b], values[c], values[d])
    return r[0], r[1]


@njit(**_JIT)
def interp1_grad(ax0, log0, values, logv, method, x0, mode, counter):
    """(v, dv/dx0) at x0; see the module docstring."""
    t0 = _coord_call(x0, log0)
    if t0 != t0:
        if mode == 0:
            counter[0] += 1
        return np.nan, np.nan
    i, c0, o0 = locate_call(ax0, t0)
    if o0:
        if mode == 1:
            return np.nan, np.nan
        counter[0] += 1
    u, du0 = _core1(ax0, values, method, i, c0)
    v, dvdu = _finish(u, logv)
    return v, dvdu * du0 * _dtdx_call(c0, log0)


@njit(**_JIT)
def interp1(ax0, log0, values, logv, method, x0, mode, counter):
    """v at x0; see the module docstring."""
    t0 = _coord_call(x0, log0)
    if t0 != t0:
        if mode == 0:
            counter[0] += 1
        return np.nan
    i, c0, o0 = locate_call(ax0, t0)
    if o0:
        if mode == 1:
            return np.nan
        counter[0] += 1
    if method == 0:
        w = (c0 - ax0[i]) / (ax0[i + 1] - ax0[i])
        u = (1.0 - w) * values[i] + w * values[i + 1]
    else:
        a, b, c, d = _stencil(i, ax0.size)
        u = _pchip_val(ax0, i, c0, values[a], values[b], values[c], values[d])
    return math.exp(u) if logv else u


# ---------------------------------------------------------------------------
# two axes


@njit(**_JIT)
def _col2(ax0, values, i, t0, j):
    """PCHIP along axis 0 at column j: (g, dg/dt0)."""
    a, b, c, d = _stencil(i, ax0.size)
    r = _pchip_seg(ax0, i, t0, values[a, j], values[b, j], values[c, j], values[d, j])
    return r[0], r[1]


@njit(**_JIT)
def _core2(ax0, ax1, values, method, i, s0, j, s1):
    if method == 0:
        h0 = ax0[i + 1] - ax0[i]
        h1 = ax1[j + 1] - ax1[j]
        w0 = (s0 - ax0[i]) / h0
        w1 = (s1 - ax1[j]) / h1
        v00 = values[i, j]
        v10 = values[i + 1, j]
        v01 = values[i, j + 1]
        v11 = values[i + 1, j + 1]
        a = (1.0 - w0) * v00 + w0 * v10
        b = (1.0 - w0) * v01 + w0 * v11
        return ((1.0 - w1) * a + w1 * b, ((1.0 - w1) * (v10 - v00) + w1 * (v11 - v01)) / h0, (b - a) / h1)
    ja, jb, jc, jd = _stencil(j, ax1.size)
    ga, da = _col2(ax0, values, i, s0, ja)
    gb, db = _col2(ax0, values, i, s0, jb)
    gc, dc = _col2(ax0, values, i, s0, jc)
    gd, dd = _col2(ax0, values, i, s0, jd)
    r = _pchip_seg(ax1, j, s1, ga, gb, gc, gd)
    return r[0], r[2] * da + r[3] * db + r[4] * dc + r[5] * dd, r[1]


@njit(**_JIT)
def interp2_grad(ax0, ax1, log0, log1, values, logv, method, x0, x1, mode, counter):
    """(v, dv/dx0, dv/dx1) at (x0, x1); see the module docstring."""
    t0 = _coord_call(x0, log0)
    t1 = _coord_call(x1, log1)
    if t0 != t0 or t1 != t1:
        if mode == 0:
            counter[0] += 1
        return np.nan, np.nan, np.nan
    i, c0, o0 = locate_call(ax0, t0)
    j, c1, o1 = locate_call(ax1, t1)
    if o0 or o1:
        if mode == 1:
            return np.nan, np.nan, np.nan
        counter[0] += 1
    u, du0, du1 = _core2(ax0, ax1, values, method, i, c0, j, c1)
    v, dvdu = _finish(u, logv)
    return v, dvdu * du0 * _dtdx_call(c0, log0), dvdu * du1 * _dtdx_call(c1, log1)


@njit(**_JIT)
def _val2(ax0, values, i, s0, j):
    a, b, c, d = _stencil(i, ax0.size)
    return _pchip_val(ax0, i, s0, values[a, j], values[b, j], values[c, j], values[d, j])


@njit(**_JIT)
def interp2(ax0, ax1, log0, log1, values, logv, method, x0, x1, mode, counter):
    """v at (x0, x1); see the module docstring."""
    t0 = _coord_call(x0, log0)
    t1 = _coord_call(x1, log1)
    if t0 != t0 or t1 != t1:
        if mode == 0:
            counter[0] += 1
        return np.nan
    i, s0, o0 = locate_call(ax0, t0)
    j, s1, o1 = locate_call(ax1, t1)
    if o0 or o1:
        if mode == 1:
            return np.nan
        counter[0] += 1
    if method == 0:
        w0 = (s0 - ax0[i]) / (ax0[i + 1] - ax0[i])
        w1 = (s1 - ax1[j]) / (ax1[j + 1] - ax1[j])
        u = ((1.0 - w1) * ((1.0 - w0) * values[i, j] + w0 * values[i + 1, j])
             + w1 * ((1.0 - w0) * values[i, j + 1] + w0 * values[i + 1, j + 1]))
    else:
        ja, jb, jc, jd = _stencil(j, ax1.size)
        u = _pchip_val(ax1, j, s1, _val2(ax0, values, i, s0, ja), _val2(ax0, values, i, s0, jb),
                       _val2(ax0, values, i, s0, jc), _val2(ax0, values, i, s0, jd))
    return math.exp(u) if logv else u


# ---------------------------------------------------------------------------
# three axes


@njit(**_JIT)
def _col3(ax0, values, i, t0, j, k):
    a, b, c, d = _stencil(i, ax0.size)
    r = _pchip_seg(ax0, i, t0, values[a, j, k], values[b, j, k], values[c, j, k], values[d, j, k])
    return r[0], r[1]


@njit(**_JIT)
def _plane3(ax0, ax1, values, i, t0, j, t1, k):
    """PCHIP over axes 0 then 1 at layer k: (h, dh/dt0, dh/dt1)."""
    ja, jb, jc, jd = _stencil(j, ax1.size)
    ga, da = _col3(ax0, values, i, t0, ja, k)
    gb, db = _col3(ax0, values, i, t0, jb, k)
    gc, dc = _col3(ax0, values, i, t0, jc, k)
    gd, dd = _col3(ax0, values, i, t0, jd, k)
    r = _pchip_seg(ax1, j, t1, ga, gb, gc, gd)
    return r[0], r[2] * da + r[3] * db + r[4] * dc + r[5] * dd, r[1]


@njit(**_JIT)
def _core3(ax0, ax1, ax2, values, method, i, s0, j, s1, k, s2):
    if method == 0:
        h0 = ax0[i + 1] - ax0[i]
        h1 = ax1[j + 1] - ax1[j]
        h2 = ax2[k + 1] - ax2[k]
        w0 = (s0 - ax0[i]) / h0
        w1 = (s1 - ax1[j]) / h1
        w2 = (s2 - ax2[k]) / h2
        # bilinear in (0, 1) on both layers k, k+1
        a0 = (1.0 - w0) * values[i, j, k] + w0 * values[i + 1, j, k]
        b0 = (1.0 - w0) * values[i, j + 1, k] + w0 * values[i + 1, j + 1, k]
        a1 = (1.0 - w0) * values[i, j, k + 1] + w0 * values[i + 1, j, k + 1]
        b1 = (1.0 - w0) * values[i, j + 1, k + 1] + w0 * values[i + 1, j + 1, k + 1]
        d0a0 = values[i + 1, j, k] - values[i, j, k]
        d0b0 = values[i + 1, j + 1, k] - values[i, j + 1, k]
        d0a1 = values[i + 1, j, k + 1] - values[i, j, k + 1]
        d0b1 = values[i + 1, j + 1, k + 1] - values[i, j + 1, k + 1]
        f0 = (1.0 - w1) * a0 + w1 * b0
        f1 = (1.0 - w1) * a1 + w1 * b1
        g0 = ((1.0 - w2) * ((1.0 - w1) * d0a0 + w1 * d0b0) + w2 * ((1.0 - w1) * d0a1 + w1 * d0b1)) / h0
        g1 = ((1.0 - w2) * (b0 - a0) + w2 * (b1 - a1)) / h1
        return (1.0 - w2) * f0 + w2 * f1, g0, g1, (f1 - f0) / h2
    ka, kb, kc, kd = _stencil(k, ax2.size)
    ha, a0, a1 = _plane3(ax0, ax1, values, i, s0, j, s1, ka)
    hb, b0, b1 = _plane3(ax0, ax1, values, i, s0, j, s1, kb)
    hc, c0, c1 = _plane3(ax0, ax1, values, i, s0, j, s1, kc)
    hd, d0, d1 = _plane3(ax0, ax1, values, i, s0, j, s1, kd)
    r = _pchip_seg(ax2, k, s2, ha, hb, hc, hd)
    return (r[0], r[2] * a0 + r[3] * b0 + r[4] * c0 + r[5] * d0, r[2] * a1 + r[3] * b1 + r[4] * c1 + r[5] * d1,
            r[1])


@njit(**_JIT)
def interp3_grad(ax0, ax1, ax2, log0, log1, log2, values, logv, method, x0, x1, x2, mode, counter):
    """(v, dv/dx0, dv/dx1, dv/dx2) at (x0, x1, x2); see the module docstring."""
    t0 = _coord_call(x0, log0)
    t1 = _coord_call(x1, log1)
    t2 = _coord_call(x2, log2)
    if t0 != t0 or t1 != t1 or t2 != t2:
        if mode == 0:
            counter[0] += 1
        return np.nan, np.nan, np.nan, np.nan
    i, c0, o0 = locate_call(ax0, t0)
    j, c1, o1 = locate_call(ax1, t1)
    k, c2, o2 = locate_call(ax2, t2)
    if o0 or o1 or o2:
        if mode == 1:
            return np.nan, np.nan, np.nan, np.nan
        counter[0] += 1
    u, du0, du1, du2 = _core3(ax0, ax1, ax2, values, method, i, c0, j, c1, k, c2)
    v, dvdu = _finish(u, logv)
    return (v, dvdu * du0 * _dtdx_call(c0, log0), dvdu * du1 * _dtdx_call(c1, log1), dvdu * du2 * _dtdx_call(c2, log2))


@njit(**_JIT)
def _val3(ax0, values, i, s0, j, k):
    a, b, c, d = _stencil(i, ax0.size)
    return _pchip_val(ax0, i, s0, values[a, j, k], values[b, j, k], values[c, j, k], values[d, j, k])


@njit(**_JIT)
def _val3_plane(ax0, ax1, values, i, s0, j, s1, k):
    ja, jb, jc, jd = _stencil(j, ax1.size)
    return _pchip_val(ax1, j, s1, _val3(ax0, values, i, s0, ja, k), _val3(ax0, values, i, s0, jb, k),
                      _val3(ax0, values, i, s0, jc, k), _val3(ax0, values, i, s0, jd, k))


@njit(**_JIT)
def interp3(ax0, ax1, ax2, log0, log1, log2, values, logv, method, x0, x1, x2, mode, counter):
    """v at (x0, x1, x2); see the module docstring."""
    t0 = _coord_call(x0, log0)
    t1 = _coord_call(x1, log1)
    t2 = _coord_call(x2, log2)
    if t0 != t0 or t1 != t1 or t2 != t2:
        if mode == 0:
            counter[0] += 1
        return np.nan
    i, s0, o0 = locate_call(ax0, t0)
    j, s1, o1 = locate_call(ax1, t1)
    k, s2, o2 = locate_call(ax2, t2)
    if o0 or o1 or o2:
        if mode == 1:
            return np.nan
        counter[0] += 1
    if method == 0:
        w0 = (s0 - ax0[i]) / (ax0[i + 1] - ax0[i])
        w1 = (s1 - ax1[j]) / (ax1[j + 1] - ax1[j])
        w2 = (s2 - ax2[k]) / (ax2[k + 1] - ax2[k])
        a0 = (1.0 - w0) * values[i, j, k] + w0 * values[i + 1, j, k]
        b0 = (1.0 - w0) * values[i, j + 1, k] + w0 * values[i + 1, j + 1, k]
        a1 = (1.0 - w0) * values[i, j, k + 1] + w0 * values[i + 1, j, k + 1]
        b1 = (1.0 - w0) * values[i, j + 1, k + 1] + w0 * values[i + 1, j + 1, k + 1]
        u = (1.0 - w2) * ((1.0 - w1) * a0 + w1 * b0) + w2 * ((1.0 - w1) * a1 + w1 * b1)
    else:
        ka, kb, kc, kd = _stencil(k, ax2.size)
        u = _pchip_val(ax2, k, s2, _val3_plane(ax0, ax1, values, i, s0, j, s1, ka),
                       _val3_plane(ax0, ax1, values, i, s0, j, s1, kb),
                       _val3_plane(ax0, ax1, values, i, s0, j, s1, kc),
                       _val3_plane(ax0, ax1, values, i, s0, j, s1, kd))
    return math.exp(u) if logv else u


# ---------------------------------------------------------------------------
# many queries (Python-side evaluation of a map)


@njit(**_JIT)
def many1(ax0, log0, values, logv, method, points, mode, counter, out, grad):
    """Evaluate at ``points`` (m, 1) into ``out`` (m,) and ``grad`` (m, 1)."""
    for q in range(points.shape[0]):
        r = interp1_grad(ax0, log0, values, logv, method, points[q, 0], mode, counter)
        out[q] = r[0]
        grad[q, 0] = r[1]


@njit(**_JIT)
def many2(ax0, ax1, log0, log1, values, logv, method, points, mode, counter, out, grad):
    """Evaluate at ``points`` (m, 2) into ``out`` (m,) and ``grad`` (m, 2)."""
    for q in range(points.shape[0]):
        r = interp2_grad(ax0, ax1, log0, log1, values, logv, method, points[q, 0], points[q, 1], mode, counter)
        out[q] = r[0]
        grad[q, 0] = r[1]
        grad[q, 1] = r[2]


@njit(**_JIT)
def many3(ax0, ax1, ax2, log0, log1, log2, values, logv, method, points, mode, counter, out, grad):
    """Evaluate at ``points`` (m, 3) into ``out`` (m,) and ``grad`` (m, 3)."""
    for q in range(points.shape[0]):
        r = interp3_grad(ax0, ax1, ax2, log0, log1, log2, values, logv, method, points[q, 0], points[q, 1],
                         points[q, 2], mode, counter)
        out[q] = r[0]
        grad[q, 0] = r[1]
        grad[q, 1] = r[2]
        grad[q, 2] = r[3]


def evaluate(axes, logs, values, logv, method, points, mode=CLAMP, counter=None, grad=False):
    """Python front end: interpolate prepared arrays at ``points`` (m, ndim).

    Returns ``v`` (m,) or ``(v, dv/dx)`` with dv/dx of shape (m, ndim).
    ``counter`` (int64, length >= 1) counts clamped queries in mode 0.
    """
    points = np.ascontiguousarray(np.atleast_2d(points), dtype=np.float64)
    ndim = len(axes)
    if not 1 <= ndim <= 3:
        raise ValueError(f"1 to 3 axes are supported, got {ndim}")
    if points.shape[1] != ndim:
        raise ValueError(f"points must have {ndim} columns, got shape {points.shape}")
    counter = np.zeros(1, dtype=np.int64) if counter is None else counter
    out = np.empty(points.shape[0])
    g = np.empty((points.shape[0], ndim))
    logs = tuple(int(bool(x)) for x in logs)
    if method == HERMITE:  # ``values`` is the derivative array of :func:`hermite_data`
        if values.shape[0] != 2**ndim or values.ndim != ndim + 1:
            raise ValueError(f"hermite needs the array of hermite_data, shape (2**{ndim}, ...), got {values.shape}")
        args = (int(bool(logv)), points, int(mode), counter, out, g)
        (hmany1, hmany2, hmany3)[ndim - 1](*axes, *logs, values, *args)
        return (out, g) if grad else out
    args = (int(bool(logv)), int(method), points, int(mode), counter, out, g)
    if ndim == 1:
        many1(axes[0], logs[0], values, *args)
    elif ndim == 2:
        many2(axes[0], axes[1], logs[0], logs[1], values, *args)
    elif ndim == 3:
        many3(axes[0], axes[1], axes[2], logs[0], logs[1], logs[2], values, *args)
    else:
        raise ValueError(f"1 to 3 axes are supported, got {ndim}")
    return (out, g) if grad else out


# ---------------------------------------------------------------------------
# method 2: tensor-product cubic Hermite on precomputed PCHIP node derivatives
#
# ``deriv`` has shape (2**ndim, n0[, n1[, n2]]): entry s holds the node values
# (s = 0) and the node derivatives d/dt_k for every axis k whose bit is set in
# s (bit 0: axis 0, bit 1: axis 1, bit 2: axis 2), made by :func:`hermite_data`
# with the PCHIP slope formulas applied along those axes in turn.  Evaluation
# is local -- 2**ndim corners x 2**ndim derivative entries, no slope formulas
# and no divisions at query time -- so it is the fastest cubic; the result is
# C1 across cell faces, equals PCHIP in 1-D and along every grid line, and
# reproduces multilinear functions exactly (PCHIP slopes of linear data are
# exact).  Between grid lines it is not the sequential PCHIP of method 1 (the
# two differ by O(h^3)).


def hermite_data(axes_t, u) -> np.ndarray:
    """Node values and PCHIP node derivatives, shape (2**ndim,) + u.shape, for the ``hermite`` kernels.

    ``axes_t``: prepared axes (t space), ``u``: prepared values."""
    from scipy.interpolate import PchipInterpolator

    u = np.ascontiguousarray(u, dtype=np.float64)
    nd = u.ndim
    out = np.empty((2**nd,) + u.shape)
    for s in range(2**nd):
        d = u
        for k in range(nd):
            if s >> k & 1:
                d = PchipInterpolator(axes_t[k], d, axis=k).derivative()(axes_t[k])
        out[s] = d
    return np.ascontiguousarray(out)


@njit(**_INLINE)
def _hbasis(ax, i, t):
    """Cubic Hermite bases on cell i at t: values (b0, b1, g0, g1) for (f_i, f_i+1, f'_i, f'_i+1)
    and their t-derivatives."""
    h = ax[i + 1] - ax[i]
    s = (t - ax[i]) / h
    s2 = s * s
    s3 = s2 * s
    b0 = 2.0 * s3 - 3.0 * s2 + 1.0
    g0 = (s3 - 2.0 * s2 + s) * h
    g1 = (s3 - s2) * h
    db0 = (6.0 * s2 - 6.0 * s) / h
    return (b0, 1.0 - b0, g0, g1), (db0, -db0, 3.0 * s2 - 4.0 * s + 1.0, 3.0 * s2 - 2.0 * s)


@njit(**_INLINE)
def hermite_value(ax, i, t):
    """Value bases of :func:`_hbasis` only."""
    h = ax[i + 1] - ax[i]
    s = (t - ax[i]) / h
    s2 = s * s
    s3 = s2 * s
    b0 = 2.0 * s3 - 3.0 * s2 + 1.0
    return b0, 1.0 - b0, (s3 - 2.0 * s2 + s) * h, (s3 - s2) * h


@njit(**_INLINE)
def _dtdx_at(x, t, outside, log):
    """dt/dx at the query: 1/x inside a log axis (no exp), exp(-t) at the clamped end."""
    if log:
        if outside:
            return math.exp(-t)
        return 1.0 / x
    return 1.0


# The tensor sums are contracted one axis at a time, last axis first (its node pairs k, k+1 are
# adjacent in memory): in 3-D 16 + 4 + 1 four-term dot products (84 multiplications) instead of the
# 64 x 3 of the plain sum over corners and derivative sets; the gradient reuses the partial sums.
# Index s of ``deriv`` = s0 + 2 s1 + 4 s2 (bit k: derivative along axis k); weights w = (b0, b1, g0, g1).


@njit(**_INLINE)
def hermite_dot(f0, f1, w):
    """f0[0] w0 + f0[1] w1 + f1[0] w2 + f1[1] w3: corners a = 0, 1 of the value (f0) and derivative (f1) sets."""
    return f0[0] * w[0] + f0[1] * w[1] + f1[0] * w[2] + f1[1] * w[3]


@njit(**_INLINE)
def pair2(deriv, s, i, j, w):
    """2-D, contracted over axis 1 for derivative bit 0 = s: (E(a=0), E(a=1)) at nodes i, i+1."""
    return ((deriv[s, i, j] * w[0] + deriv[s, i, j + 1] * w[1])
            + (deriv[s + 2, i, j] * w[2] + deriv[s + 2, i, j + 1] * w[3]),
            (deriv[s, i + 1, j] * w[0] + deriv[s, i + 1, j + 1] * w[1])
            + (deriv[s + 2, i + 1, j] * w[2] + deriv[s + 2, i + 1, j + 1] * w[3]))


@njit(**_INLINE)
def _quad3(deriv, s, i, j, k, w):
    """3-D, contracted over axis 2 for derivative bits (0, 1) = s: E(a, b) at nodes (i+a, j+b),
    returned as (E00, E01, E10, E11)."""
    return ((deriv[s, i, j, k] * w[0] + deriv[s, i, j, k + 1] * w[1])
            + (deriv[s + 4, i, j, k] * w[2] + deriv[s + 4, i, j, k + 1] * w[3]),
            (deriv[s, i, j + 1, k] * w[0] + deriv[s, i, j + 1, k + 1] * w[1])
            + (deriv[s + 4, i, j + 1, k] * w[2] + deriv[s + 4, i, j + 1, k + 1] * w[3]),
            (deriv[s, i + 1, j, k] * w[0] + deriv[s, i + 1, j, k + 1] * w[1])
            + (deriv[s + 4, i + 1, j, k] * w[2] + deriv[s + 4, i + 1, j, k + 1] * w[3]),
            (deriv[s, i + 1, j + 1, k] * w[0] + deriv[s, i + 1, j + 1, k + 1] * w[1])
            + (deriv[s + 4, i + 1, j + 1, k] * w[2] + deriv[s + 4, i + 1, j + 1, k + 1] * w[3]))


@njit(**_INLINE)
def _e2(a, b, c, d, w):
    """a w0 + b w1 + c w2 + d w3 (value, value, derivative, derivative of the two nodes of a cell)."""
    return (a * w[0] + b * w[1]) + (c * w[2] + d * w[3])


@njit(**_INLINE)
def _de2(a, b, c, d, dw):
    """:func:`_e2` with derivative weights, whose first two are opposite (dw1 = -dw0)."""
    return (a - b) * dw[0] + (c * dw[2] + d * dw[3])


@njit(**_INLINE)
def _ede2(a, b, c, d, w, dw):
    """(:func:`_e2` with ``w``, with ``dw``) sharing a - b (w1 = 1 - w0, dw1 = -dw0)."""
    ab = a - b
    return b + ab * w[0] + c * w[2] + d * w[3], ab * dw[0] + c * dw[2] + d * dw[3]


@njit(**_INLINE)
def _quad3_grad(deriv, s, i, j, k, w, dw):
    """:func:`_quad3` with the weights ``w`` and ``dw`` from the same loads: ((E00, E01, E10, E11), (dE...))."""
    a0, a1, a2, a3 = deriv[s, i, j, k], deriv[s, i, j, k + 1], deriv[s + 4, i, j, k], deriv[s + 4, i, j, k + 1]
    b0, b1, b2, b3 = (deriv[s, i, j + 1, k], deriv[s, i, j + 1, k + 1], deriv[s + 4, i, j + 1, k],
                      deriv[s + 4, i, j + 1, k + 1])
    c0, c1, c2, c3 = (deriv[s, i + 1, j, k], deriv[s, i + 1, j, k + 1], deriv[s + 4, i + 1, j, k],
                      deriv[s + 4, i + 1, j, k + 1])
    d0, d1, d2, d3 = (deriv[s, i + 1, j + 1, k], deriv[s, i + 1, j + 1, k + 1], deriv[s + 4, i + 1, j + 1, k],
                      deriv[s + 4, i + 1, j + 1, k + 1])
    ea, da = _ede2(a0, a1, a2, a3, w, dw)
    eb, db = _ede2(b0, b1, b2, b3, w, dw)
    ec, dc = _ede2(c0, c1, c2, c3, w, dw)
    ed, dd = _ede2(d0, d1, d2, d3, w, dw)
    return (ea, eb, ec, ed), (da, db, dc, dd)


@njit(**_INLINE)
def _pair3(p, q, w):
    """Contract over axis 1: p = E of derivative bit 1 = 0, q = bit 1 = 1 -> (F(a=0), F(a=1))."""
    return ((p[0] * w[0] + p[1] * w[1]) + (q[0] * w[2] + q[1] * w[3]),
            (p[2] * w[0] + p[3] * w[1]) + (q[2] * w[2] + q[3] * w[3]))


# Kernels have a single exit (a NaN result is selected at the end, after a harmless evaluation at
# the clamped point) and call only ``inline="always"`` helpers: numba then prunes the atomic
# reference counting of the array arguments (10 locked instructions a query otherwise).


@njit(**_FMA)
def hermite1_grad(ax0, log0, deriv, logv, x0, mode, counter):
    """(v, dv/dx0); ``deriv`` of shape (2, n0) from :func:`hermite_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    refuse = _refuse(nan0, o0, mode, counter)
    b, db = _hbasis(ax0, i, c0)
    u = (b[0] * deriv[0, i] + b[1] * deriv[0, i + 1]) + (b[2] * deriv[1, i] + b[3] * deriv[1, i + 1])
    du = (db[0] * deriv[0, i] + db[1] * deriv[0, i + 1]) + (db[2] * deriv[1, i] + db[3] * deriv[1, i + 1])
    v, dvdu = _finish(u, logv)
    if refuse:
        return np.nan, np.nan
    return v, dvdu * du * _dtdx_at(x0, c0, o0, log0)


@njit(**_FMA)
def hermite1(ax0, log0, deriv, logv, x0, mode, counter):
    """v at x0; ``deriv`` of shape (2, n0) from :func:`hermite_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    refuse = _refuse(nan0, o0, mode, counter)
    b = hermite_value(ax0, i, c0)
    u = (b[0] * deriv[0, i] + b[1] * deriv[0, i + 1]) + (b[2] * deriv[1, i] + b[3] * deriv[1, i + 1])
    if logv:
        u = math.exp(u)
    return np.nan if refuse else u


@njit(**_FMA)
def hermite2_grad(ax0, ax1, log0, log1, deriv, logv, x0, x1, mode, counter):
    """(v, dv/dx0, dv/dx1); ``deriv`` of shape (4, n0, n1) from :func:`hermite_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    j, c1, o1, nan1 = _cell(ax1, x1, log1)
    refuse = _refuse(nan0 or nan1, o0 | o1, mode, counter)
    w0, dw0 = _hbasis(ax0, i, c0)
    w1, dw1 = _hbasis(ax1, j, c1)
    f0 = pair2(deriv, 0, i, j, w1)
    f1 = pair2(deriv, 1, i, j, w1)
    g0 = pair2(deriv, 0, i, j, dw1)
    g1 = pair2(deriv, 1, i, j, dw1)
    v, dvdu = _finish(hermite_dot(f0, f1, w0), logv)
    if refuse:
        return np.nan, np.nan, np.nan
    return (v, dvdu * hermite_dot(f0, f1, dw0) * _dtdx_at(x0, c0, o0, log0),
            dvdu * hermite_dot(g0, g1, w0) * _dtdx_at(x1, c1, o1, log1))


@njit(**_FMA)
def hermite2(ax0, ax1, log0, log1, deriv, logv, x0, x1, mode, counter):
    """v at (x0, x1); ``deriv`` of shape (4, n0, n1) from :func:`hermite_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    j, c1, o1, nan1 = _cell(ax1, x1, log1)
    refuse = _refuse(nan0 or nan1, o0 | o1, mode, counter)
    w1 = hermite_value(ax1, j, c1)
    u = hermite_dot(pair2(deriv, 0, i, j, w1), pair2(deriv, 1, i, j, w1), hermite_value(ax0, i, c0))
    if logv:
        u = math.exp(u)
    return np.nan if refuse else u


@njit(**_FMA)
def hermite3_grad(ax0, ax1, ax2, log0, log1, log2, deriv, logv, x0, x1, x2, mode, counter):
    """(v, dv/dx0, dv/dx1, dv/dx2); ``deriv`` of shape (8, n0, n1, n2) from :func:`hermite_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    j, c1, o1, nan1 = _cell(ax1, x1, log1)
    k, c2, o2, nan2 = _cell(ax2, x2, log2)
    refuse = _refuse(nan0 or nan1 or nan2, o0 | o1 | o2, mode, counter)
    w0, dw0 = _hbasis(ax0, i, c0)
    w1, dw1 = _hbasis(ax1, j, c1)
    w2, dw2 = _hbasis(ax2, k, c2)
    # derivative bit 0 = 0, then 1: the 16 node values of each half are loaded once and used for
    # both the axis-2 value and its axis-2 derivative
    p, dp = _quad3_grad(deriv, 0, i, j, k, w2, dw2)
    q, dq = _quad3_grad(deriv, 2, i, j, k, w2, dw2)
    f0 = _pair3(p, q, w1)
    g0 = _pair3(p, q, dw1)
    h0 = _pair3(dp, dq, w1)
    p, dp = _quad3_grad(deriv, 1, i, j, k, w2, dw2)
    q, dq = _quad3_grad(deriv, 3, i, j, k, w2, dw2)
    f1 = _pair3(p, q, w1)
    g1 = _pair3(p, q, dw1)
    h1 = _pair3(dp, dq, w1)
    u0 = hermite_dot(f0, f1, dw0)
    u1 = hermite_dot(g0, g1, w0)
    u2 = hermite_dot(h0, h1, w0)
    v, dvdu = _finish(hermite_dot(f0, f1, w0), logv)
    if refuse:
        return np.nan, np.nan, np.nan, np.nan
    return (v, dvdu * u0 * _dtdx_at(x0, c0, o0, log0), dvdu * u1 * _dtdx_at(x1, c1, o1, log1),
            dvdu * u2 * _dtdx_at(x2, c2, o2, log2))


@njit(**_FMA)
def hermite3(ax0, ax1, ax2, log0, log1, log2, deriv, logv, x0, x1, x2, mode, counter):
    """v at (x0, x1, x2); ``deriv`` of shape (8, n0, n1, n2) from :func:`hermite_data`."""
    i, c0, o0, nan0 = _cell(ax0, x0, log0)
    j, c1, o1, nan1 = _cell(ax1, x1, log1)
    k, c2, o2, nan2 = _cell(ax2, x2, log2)
    refuse = _refuse(nan0 or nan1 or nan2, o0 | o1 | o2, mode, counter)
    w1 = hermite_value(ax1, j, c1)
    w2 = hermite_value(ax2, k, c2)
    f0 = _pair3(_quad3(deriv, 0, i, j, k, w2), _quad3(deriv, 2, i, j, k, w2), w1)
    f1 = _pair3(_quad3(deriv, 1, i, j, k, w2), _quad3(deriv, 3, i, j, k, w2), w1)
    u = hermite_dot(f0, f1, hermite_value(ax0, i, c0))
    if logv:
        u = math.exp(u)
    return np.nan if refuse else u


@njit(**_JIT)
def hmany1(ax0, log0, deriv, logv, points, mode, counter, out, grad):
    for q in range(points.shape[0]):
        r = hermite1_grad(ax0, log0, deriv, logv, points[q, 0], mode, counter)
        out[q] = r[0]
        grad[q, 0] = r[1]


@njit(**_JIT)
def hmany2(ax0, ax1, log0, log1, deriv, logv, points, mode, counter, out, grad):
    for q in range(points.shape[0]):
        r = hermite2_grad(ax0, ax1, log0, log1, deriv, logv, points[q, 0], points[q, 1], mode, counter)
        out[q] = r[0]
        grad[q, 0] = r[1]
        grad[q, 1] = r[2]


@njit(**_JIT)
def hmany3(ax0, ax1, ax2, log0, log1, log2, deriv, logv, points, mode, counter, out, grad):
    for q in range(points.shape[0]):
        r = hermite3_grad(ax0, ax1, ax2, log0, log1, log2, deriv, logv, points[q, 0], points[q, 1], points[q, 2],
                          mode, counter)
        out[q] = r[0]
        grad[q, 0] = r[1]
        grad[q, 1] = r[2]
        grad[q, 2] = r[3]
