"""lubedyn.dynamics.interp: numba interpolation kernels of film maps.

Independent references: exact multilinear functions, scipy's
RegularGridInterpolator (linear and pchip) and PchipInterpolator, measured
convergence orders (np.polyfit), monotone data.  Every kernel runs compiled and
as ``.py_func`` (the plain-Python path of the same code).
"""
import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator, RegularGridInterpolator

from lubedyn.dynamics import interp
from lubedyn.dynamics.interp import prepare_axis, prepare_values

rng = np.random.default_rng(1234)


def _compiled_and_plain(name):
    f = getattr(interp, name)
    return [pytest.param(f, id="njit"), pytest.param(f.py_func, id="py_func")]


def _call(fn, axes, logs, values, logv, method, x, mode=0, counter=None):
    counter = np.zeros(1, np.int64) if counter is None else counter
    if len(axes) == 1:
        return fn(axes[0], logs[0], values, logv, method, x[0], mode, counter)
    if len(axes) == 2:
        return fn(axes[0], axes[1], logs[0], logs[1], values, logv, method, x[0], x[1], mode, counter)
    return fn(axes[0], axes[1], axes[2], logs[0], logs[1], logs[2], values, logv, method, x[0], x[1], x[2], mode,
              counter)


def _nodes(n, lo=0.0, hi=1.0):
    x = np.sort(rng.uniform(lo, hi, n))
    x[0], x[-1] = lo, hi
    return x


@pytest.mark.parametrize("name", ["interp3", "interp3_grad"])
@pytest.mark.parametrize("plain", [False, True], ids=["njit", "py_func"])
def test_multilinear_reproduces_multilinear_functions(name, plain):
    """f = a + b x + c y + d z + e xy + g xz + k yz + m xyz is reproduced to round-off by trilinear
    interpolation on any (non-uniform) grid, with its exact gradient."""
    fn = getattr(interp, name)
    fn = fn.py_func if plain else fn
    ax = [_nodes(5, -1, 2), _nodes(4, 0, 3), _nodes(6, 1, 2)]
    c = rng.normal(size=8)

    def f(x, y, z):
        return c[0] + c[1] * x + c[2] * y + c[3] * z + c[4] * x * y + c[5] * x * z + c[6] * y * z + c[7] * x * y * z

    def grad(x, y, z):
        return (c[1] + c[4] * y + c[5] * z + c[7] * y * z, c[2] + c[4] * x + c[6] * z + c[7] * x * z,
                c[3] + c[5] * x + c[6] * y + c[7] * x * y)

    V = f(*np.meshgrid(*ax, indexing="ij"))
    for _ in range(20):
        q = [rng.uniform(a[0], a[-1]) for a in ax]
        r = _call(fn, ax, (0, 0, 0), V, 0, interp.LINEAR, q)
        if name == "interp3":
            assert r == pytest.approx(f(*q), abs=1e-12)
        else:
            assert r[0] == pytest.approx(f(*q), abs=1e-12)
            assert np.allclose(r[1:], grad(*q), atol=1e-11)


def test_log_axes_and_log_values_reproduce_power_laws():
    """v = 3 x^-1 y^2.5 is linear in (log x, log y, log v): multilinear in log space is exact."""
    x, y = np.geomspace(1e-7, 1e-5, 6), np.geomspace(0.01, 10.0, 5)
    V = 3.0 * x[:, None] ** -1.0 * y[None, :] ** 2.5
    ax = (prepare_axis(x, True), prepare_axis(y, True))
    u = prepare_values(V, True)
    for _ in range(10):
        q = (np.exp(rng.uniform(np.log(1e-7), np.log(1e-5))), np.exp(rng.uniform(np.log(0.01), np.log(10.0))))
        v, dx, dy = interp.interp2_grad(*ax, 1, 1, u, 1, interp.LINEAR, q[0], q[1], 0, np.zeros(1, np.int64))
        exact = 3.0 * q[0] ** -1.0 * q[1] ** 2.5
        assert v == pytest.approx(exact, rel=1e-12)
        assert dx == pytest.approx(-exact / q[0], rel=1e-11)  # a stiffness from a force map
        assert dy == pytest.approx(2.5 * exact / q[1], rel=1e-11)


@pytest.mark.parametrize("fn", _compiled_and_plain("interp1_grad"))
def test_pchip_1d_matches_scipy(fn):
    """Values and derivatives equal scipy.interpolate.PchipInterpolator (same Fritsch-Butland slopes and
    three-point end slopes), on random non-uniform data including sign changes."""
    x = _nodes(9, 0.0, 10.0)
    y = rng.normal(size=9)
    ref = PchipInterpolator(x, y)
    xs = np.concatenate([rng.uniform(0, 10, 60), x])
    got = np.array([_call(fn, (x,), (0,), y, 0, interp.PCHIP, [q]) for q in xs])
    assert np.allclose(got[:, 0], ref(xs), atol=1e-13)
    assert np.allclose(got[:, 1], ref.derivative()(xs), atol=1e-12)
    # two nodes: PCHIP is the straight line, as in scipy
    two = [_call(fn, (x[:2],), (0,), y[:2], 0, interp.PCHIP, [q]) for q in (x[0], 0.3 * x[1])]
    assert two[1][0] == pytest.approx(PchipInterpolator(x[:2], y[:2])(0.3 * x[1]), abs=1e-14)


@pytest.mark.parametrize("ndim", [2, 3])
@pytest.mark.parametrize("method", ["linear", "pchip"])
def test_nd_matches_scipy_regular_grid_interpolator(ndim, method):
    """N-D against RegularGridInterpolator.  Ours goes through the axes 0, 1, 2 in turn; scipy's pchip
    goes from the last axis down, so scipy is given the grid with its axes reversed."""
    ax = [_nodes(n, 0, s) for n, s in zip((7, 5, 4)[:ndim], (3.0, 1.0, 2.0))]
    V = rng.normal(size=tuple(a.size for a in ax))
    q = np.stack([rng.uniform(a[0], a[-1], 200) for a in ax], axis=1)
    ref = RegularGridInterpolator(tuple(ax[::-1]), V.transpose(), method=method)(q[:, ::-1])
    got = interp.evaluate(tuple(ax), (0,) * ndim, V, 0, interp.METHODS[method], q)
    assert np.abs(got - ref).max() < 1e-12


@pytest.mark.parametrize("ndim", [2, 3])
def test_pchip_nd_gradient_is_the_derivative_of_the_interpolant(ndim):
    """Forward-mode gradient through the later axes' slope formulas against central differences of the
    interpolated values (step 1e-6 of the cell; differences agree to O(step^2))."""
    ax = [_nodes(n, 0, 1) for n in (6, 5, 4)[:ndim]]
    V = np.cumsum(np.abs(rng.normal(size=tuple(a.size for a in ax))), axis=0)  # monotone along axis 0
    q = np.stack([rng.uniform(a[1], a[-2], 30) for a in ax], axis=1)
    v, g = interp.evaluate(tuple(ax), (0,) * ndim, V, 0, interp.PCHIP, q, grad=True)
    step = 1e-6
    for k in range(ndim):
        dq = np.zeros(ndim)
        dq[k] = step
        fd = (interp.evaluate(tuple(ax), (0,) * ndim, V, 0, interp.PCHIP, q + dq)
              - interp.evaluate(tuple(ax), (0,) * ndim, V, 0, interp.PCHIP, q - dq)) / (2 * step)
        assert np.allclose(g[:, k], fd, rtol=1e-5, atol=1e-6 * np.abs(V).max())


def test_pchip_monotone_data_no_overshoot():
    """Monotone data with a jump (where a cubic spline overshoots): the interpolant is monotone and stays
    within the data range (pchip, hermite = pchip in 1-D, linear)."""
    x = np.linspace(0.0, 1.0, 11)
    y = np.where(x < 0.5, 0.0, 1.0) + 0.01 * x
    xs = np.linspace(0.0, 1.0, 2001)
    for method in (interp.PCHIP, interp.LINEAR, interp.HERMITE):
        data = interp.hermite_data((x,), y) if method == interp.HERMITE else y
        v = interp.evaluate((x,), (0,), data, 0, method, xs[:, None])
        assert np.all(np.diff(v) >= -1e-15)
        assert v.min() >= y.min() - 1e-15 and v.max() <= y.max() + 1e-15
    from scipy.interpolate import CubicSpline

    spline = CubicSpline(x, y)(xs)
    assert spline.max() > y.max() + 0.05  # the reference case does overshoot with a spline


def _order(method, f, n_list, log_axis=False):
    errs = []
    fine = np.linspace(0.05, 0.95, 4001)
    for n in n_list:
        x = np.linspace(0.0, 1.0, n)
        v = interp.evaluate((x,), (0,), f(x), 0, method, fine[:, None])
        errs.append(np.abs(v - f(fine)).max())
    return -np.polyfit(np.log(n_list), np.log(errs), 1)[0], errs


def test_convergence_orders():
    """Max error on a smooth monotone function under refinement: multilinear 2, monotone cubic 3
    (Fritsch-Butland slopes are second-order accurate; measured 2.06, 1-D cubic 3.68, 2-D cubic 3.00).  (At an
    interior extremum PCHIP flattens its slope and drops towards second order: on sin(3x) + x^2, which
    has one at x = 0.68, the order measured 2.2 -- a property of the method, not tested here.)"""
    f = lambda x: np.exp(2.0 * x) + np.sin(x)  # noqa: E731
    n_list = np.array([9, 17, 33, 65, 129])
    p_lin, _ = _order(interp.LINEAR, f, n_list)
    p_cub, errs = _order(interp.PCHIP, f, n_list)
    assert p_lin == pytest.approx(2.0, abs=0.15)
    assert 2.8 < p_cub < 4.2
    errs2 = []
    q = np.stack([rng.uniform(0.05, 0.95, 400), rng.uniform(0.05, 0.95, 400)], axis=1)
    g = lambda x, y: np.exp(x) * np.cos(2 * y)  # noqa: E731
    for n in n_list[:4]:
        x = np.linspace(0, 1, n)
        V = g(*np.meshgrid(x, x, indexing="ij"))
        errs2.append(np.abs(interp.evaluate((x, x), (0, 0), V, 0, interp.PCHIP, q) - g(q[:, 0], q[:, 1])).max())
    p2 = -np.polyfit(np.log(n_list[:4]), np.log(errs2), 1)[0]
    assert 2.8 < p2 < 4.2


@pytest.mark.parametrize("fn", _compiled_and_plain("interp2"))
def test_out_of_axes_clamp_counts_and_nan_mode(fn):
    """Clamp mode: the value at the nearest end (never extrapolated) and one count per query with any
    coordinate outside; NaN mode: NaN and no count; a NaN coordinate gives NaN in both modes and is
    counted in clamp mode (a run that clamps reports it)."""
    x, y = np.linspace(0, 1, 5), np.geomspace(1.0, 100.0, 4)
    ax = (prepare_axis(x, False), prepare_axis(y, True))
    V = x[:, None] + np.log(y)[None, :]
    counter = np.zeros(1, np.int64)
    args = (ax[0], ax[1], 0, 1, V, 0, interp.PCHIP)
    assert fn(*args, 2.0, 10.0, 0, counter) == pytest.approx(1.0 + np.log(10.0), abs=1e-12)
    assert fn(*args, -1.0, 1e4, 0, counter) == pytest.approx(np.log(100.0), abs=1e-12)
    assert fn(*args, 0.5, -3.0, 0, counter) == pytest.approx(0.5, abs=1e-12)  # x <= 0 on a log axis: below it
    assert fn(*args, 0.5, 10.0, 0, counter) == pytest.approx(0.5 + np.log(10.0), abs=1e-12)  # inside: no count
    assert counter[0] == 3
    assert np.isnan(fn(*args, 2.0, 10.0, 1, counter))
    assert np.isnan(fn(*args, np.nan, 10.0, 0, counter))
    assert counter[0] == 4
    assert np.isnan(fn(*args, 0.5, np.nan, 1, counter))
    assert counter[0] == 4
    assert np.isnan(fn(*args, 0.5, np.nan, 0, counter))
    assert counter[0] == 5


def test_kernels_callable_from_another_njit_function():
    """The contract: the kernels are plain-array functions usable inside any @njit code (here a loop
    that integrates v over a line, against the trapezoid rule of the exact multilinear function)."""
    from numba import njit

    x, y = np.linspace(0, 1, 5), np.linspace(0, 2, 3)
    V = 1.0 + 2.0 * x[:, None] + 3.0 * y[None, :]

    @njit
    def line_mean(ax0, ax1, values, counter):
        s = 0.0
        for k in range(101):
            s += interp.interp2(ax0, ax1, 0, 0, values, 0, 0, k / 100.0, 1.0, 0, counter)
        return s / 101

    assert line_mean(x, y, V, np.zeros(1, np.int64)) == pytest.approx(1.0 + 1.0 + 3.0, rel=1e-12)


# ---------------------------------------------------------------------------
# method 2: cubic Hermite on precomputed PCHIP node derivatives


def _hermite_eval(ax, V, q, grad=False):
    D = interp.hermite_data(tuple(ax), V)
    return interp.evaluate(tuple(ax), (0,) * len(ax), D, 0, interp.HERMITE, q, grad=grad)


@pytest.mark.parametrize("fn", _compiled_and_plain("hermite1_grad"))
def test_hermite_1d_is_pchip(fn):
    """In 1-D the precomputed-slope Hermite is PCHIP: equal to scipy's PchipInterpolator (value, slope)."""
    x = _nodes(8, 0.0, 5.0)
    y = rng.normal(size=8)
    D = interp.hermite_data((x,), y)
    ref = PchipInterpolator(x, y)
    for q in rng.uniform(0, 5, 30):
        v, d = fn(x, 0, D, 0, q, 0, np.zeros(1, np.int64))
        assert v == pytest.approx(float(ref(q)), abs=1e-13)
        assert d == pytest.approx(float(ref.derivative()(q)), abs=1e-12)


@pytest.mark.parametrize("plain", [False, True], ids=["njit", "py_func"])
def test_hermite_reproduces_multilinear_functions_with_gradient(plain):
    """PCHIP node slopes of multilinear data are exact, so the tensor Hermite reproduces them (3-D)."""
    fn = interp.hermite3_grad.py_func if plain else interp.hermite3_grad
    ax = [_nodes(5, -1, 2), _nodes(4, 0, 3), _nodes(6, 1, 2)]
    c = rng.normal(size=8)

    def f(x, y, z):
        return c[0] + c[1] * x + c[2] * y + c[3] * z + c[4] * x * y + c[5] * x * z + c[6] * y * z + c[7] * x * y * z

    D = interp.hermite_data(tuple(ax), f(*np.meshgrid(*ax, indexing="ij")))
    for _ in range(10):
        q = [rng.uniform(a[0], a[-1]) for a in ax]
        r = fn(ax[0], ax[1], ax[2], 0, 0, 0, D, 0, q[0], q[1], q[2], 0, np.zeros(1, np.int64))
        assert r[0] == pytest.approx(f(*q), abs=1e-12)
        assert r[1] == pytest.approx(c[1] + c[4] * q[1] + c[5] * q[2] + c[7] * q[1] * q[2], abs=1e-11)


def test_hermite_order_gradient_and_grid_lines():
    """2-D: third order on a smooth monotone function (measured 3.0); the gradient equals central
    differences of the values; on a grid line it equals the sequential PCHIP (method 1) exactly."""
    g = lambda x, y: np.exp(x) * np.cos(2 * y)  # noqa: E731
    q = np.stack([rng.uniform(0.05, 0.95, 400), rng.uniform(0.05, 0.95, 400)], axis=1)
    errs, ns = [], np.array([9, 17, 33, 65])
    for n in ns:
        x = np.linspace(0, 1, n)
        errs.append(np.abs(_hermite_eval((x, x), g(*np.meshgrid(x, x, indexing="ij")), q) - g(*q.T)).max())
    assert 2.8 < -np.polyfit(np.log(ns), np.log(errs), 1)[0] < 4.2
    ax = [_nodes(6, 0, 1), _nodes(5, 0, 1)]
    V = rng.normal(size=(6, 5))
    v, grad = _hermite_eval(ax, V, q, grad=True)
    for k in range(2):
        dq = np.zeros(2)
        dq[k] = 1e-6
        fd = (_hermite_eval(ax, V, q + dq) - _hermite_eval(ax, V, q - dq)) / 2e-6
        assert np.allclose(grad[:, k], fd, rtol=1e-5, atol=1e-5)
    line = np.stack([rng.uniform(0, 1, 50), np.full(50, ax[1][2])], axis=1)
    assert np.allclose(_hermite_eval(ax, V, line), interp.evaluate(tuple(ax), (0, 0), V, 0, interp.PCHIP, line),
                       atol=1e-13)


@pytest.mark.parametrize("fn", _compiled_and_plain("hermite2"))
def test_hermite_clamp_counts(fn):
    """Out of axes: clamped to the end value with a count, or NaN (mode 1)."""
    x, y = np.linspace(0, 1, 4), np.linspace(0, 2, 3)
    V = x[:, None] * 2.0 + y[None, :]
    D = interp.hermite_data((x, y), V)
    counter = np.zeros(1, np.int64)
    assert fn(x, y, 0, 0, D, 0, 1.5, 1.0, 0, counter) == pytest.approx(3.0, abs=1e-12)
    assert fn(x, y, 0, 0, D, 0, 0.5, 1.0, 0, counter) == pytest.approx(2.0, abs=1e-12)
    assert counter[0] == 1
    assert np.isnan(fn(x, y, 0, 0, D, 0, 0.5, -1.0, 1, counter)) and counter[0] == 1


@pytest.mark.parametrize("plain", [False, True], ids=["njit", "py_func"])
@pytest.mark.parametrize("name", ["hermite3", "hermite3_grad"])
def test_hermite3_clamp_count_and_nan(name, plain):
    """3-D hermite kernels (single-exit code): a query outside is clamped to the end value of
    v = 1 + x + 2 y - z (reproduced exactly) with one count; mode 1 gives NaN without a count; a NaN
    coordinate gives NaN in both modes, counted in mode 0 only; the gradient at a clamped
    point is the one-sided derivative (1, 2, -1)."""
    fn = getattr(interp, name)
    fn = fn.py_func if plain else fn
    ax = (np.linspace(0, 1, 4), np.linspace(0, 2, 3), np.linspace(-1, 1, 5))
    V = 1.0 + ax[0][:, None, None] + 2.0 * ax[1][None, :, None] - ax[2][None, None, :]
    D = interp.hermite_data(ax, V)
    data = D
    counter = np.zeros(1, np.int64)

    def call(x, y, z, mode):
        r = fn(ax[0], ax[1], ax[2], 0, 0, 0, data, 0, x, y, z, mode, counter)
        return np.atleast_1d(np.asarray(r, dtype=float))

    r = call(1.5, 1.0, 0.5, 0)
    assert r[0] == pytest.approx(1.0 + 1.0 + 2.0 - 0.5, abs=1e-12) and counter[0] == 1
    if r.size > 1:
        assert np.allclose(r[1:], (1.0, 2.0, -1.0), atol=1e-12)
    assert call(0.5, 1.0, 0.5, 0)[0] == pytest.approx(1.0 + 0.5 + 2.0 - 0.5, abs=1e-12) and counter[0] == 1
    assert np.all(np.isnan(call(0.5, 3.0, 0.5, 1))) and counter[0] == 1
    assert np.all(np.isnan(call(np.nan, 1.0, 0.5, 0))) and counter[0] == 2
    assert np.all(np.isnan(call(0.5, 1.0, np.nan, 1))) and counter[0] == 2
    assert np.all(np.isnan(call(0.5, np.nan, 3.0, 0))) and counter[0] == 3  # NaN and outside: one count


@pytest.mark.parametrize("name", ["hermite3", "hermite3_grad"])
def test_hermite_kernels_have_no_reference_counting(name):
    """The compiled hermite kernels contain no NRT_incref/NRT_decref (each a locked atomic instruction on
    the arrays' reference counts, ten a query, more than the rest of a 3-D query costs): counted in
    the kernel's own assembly, expected 0.  Early returns, conditional stores, int() and calls to
    non-inlined helpers bring them back (see the kernels' comments)."""
    import re

    import numba
    from numba import njit

    kernel = getattr(interp, name)  # a fresh uncached copy with the same options (cached code has no assembly)
    fn = njit(**{k: v for k, v in kernel.targetoptions.items() if k != "nopython"})(kernel.py_func)
    nd = int(re.search(r"\d", name).group())
    ax = [np.linspace(0, 1, 4)] * nd
    data = interp.hermite_data(tuple(ax), np.zeros((4,) * nd))
    logs = [np.int64(0)] * nd
    # compiled once, for the argument types a model's call has (a call would first type the integers as
    # literals and compile twice)
    sig = tuple(numba.typeof(a) for a in (*ax, *logs, data, np.int64(0), *[0.5] * nd, np.int64(0),
                                         np.zeros(1, np.int64)))
    fn.compile(sig)
    asm = fn.inspect_asm(sig)
    symbol = re.compile(r"^_ZN\S*?\d+" + name + r"B\S*:$", re.M)
    start = symbol.search(asm)
    assert start is not None
    body = asm[start.end():asm.index(".Lfunc_end", start.end())]
    assert body.count("NRT_incref") + body.count("NRT_decref") == 0


@pytest.mark.parametrize("name", ["hermite3", "hermite3_grad", "interp3_grad"])
def test_fixed_options_give_the_same_bits(name):
    """Options handed as :class:`lubedyn.dynamics.interp.Fixed` (compile-time constants, as the bearing models
    pass a map's options) give the bits of the same options at run time, inside and outside the axes and
    for NaN coordinates, with the same clamp counts; and the fixed version is really compiled for the
    values (its signature holds ``Literal[int]``).  Independent check on the way: v = x^2 y / z^0.5 is
    linear in log-log-log space, so the multilinear and hermite readers reproduce it exactly."""
    fn = getattr(interp, name)
    nodes = [np.geomspace(1.0, 8.0, 5), np.geomspace(0.5, 4.0, 4), np.geomspace(1.0, 9.0, 6)]
    ax = [prepare_axis(x, True) for x in nodes]
    u = prepare_values(nodes[0][:, None, None] ** 2 * nodes[1][None, :, None] / np.sqrt(nodes[2][None, None, :]),
                       True)
    hermite = name.startswith("hermite")
    data = interp.hermite_data(tuple(ax), u) if hermite else u
    runtime = (1, 1, 1, 1)
    fixed = interp.fixed_options(runtime)
    pts = np.stack([rng.uniform(0.5, 10.0, 300), rng.uniform(0.3, 5.0, 300), rng.uniform(0.5, 10.0, 300)], axis=1)
    pts[::37, 1] = np.nan
    out = []
    for flags in (runtime, fixed):
        counter = np.zeros(1, np.int64)
        method = () if hermite else (interp.LINEAR,)
        res = [fn(ax[0], ax[1], ax[2], *flags[:3], data, flags[3], *method, x, y, z, 0, counter) for x, y, z in pts]
        out.append((np.array(res, dtype=float), int(counter[0])))
    assert out[0][1] == out[1][1] > 0
    assert np.array_equal(out[0][0], out[1][0], equal_nan=True)
    assert any("Literal[int](1)" in str(s) for s in fn.signatures)
    value = out[1][0] if out[1][0].ndim == 1 else out[1][0][:, 0]
    inside = np.all((pts >= [1.0, 0.5, 1.0]) & (pts <= [8.0, 4.0, 9.0]), axis=1)
    x, y, z = pts[inside].T
    assert np.allclose(value[inside], x**2 * y / np.sqrt(z), rtol=1e-12)
