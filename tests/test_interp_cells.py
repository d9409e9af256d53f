"""The per-cell Hermite kernels kept as a benchmark (benchmarks/interp_cells.py): the interpolant of
lubedyn.dynamics.interp's method 2 in another basis, checked against scipy's PCHIP, exact multilinear
reproduction and method 2 itself, with the clamp/NaN conventions and no reference counting."""
import re
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from benchmarks import interp_cells as ic  # noqa: E402
from lubedyn.dynamics import interp  # noqa: E402
from lubedyn.dynamics.interp import prepare_axis, prepare_values  # noqa: E402

rng = np.random.default_rng(1234)


def _compiled_and_plain(name):
    f = getattr(ic, name)
    return [pytest.param(f, id="njit"), pytest.param(f.py_func, id="py_func")]


def _nodes(n, lo=0.0, hi=1.0):
    x = np.sort(rng.uniform(lo, hi, n))
    x[0], x[-1] = lo, hi
    return x


def _cells(ax, V, logv=0):
    u = prepare_values(V, logv)
    return ic.hermite_cells_data(tuple(ax), interp.hermite_data(tuple(ax), u))


@pytest.mark.parametrize("fn", _compiled_and_plain("hermite1_cells_grad"))
def test_hermite_cells_1d_is_pchip(fn):
    """1-D cells: value and slope equal scipy's PchipInterpolator on random non-uniform nodes (the
    expanded cubic is the same Hermite cubic)."""
    x = _nodes(8, 0.0, 5.0)
    y = rng.normal(size=8)
    C = _cells([x], y)
    ref = PchipInterpolator(x, y)
    for q in np.concatenate([rng.uniform(0, 5, 30), x]):
        v, d = fn(x, 0, C, 0, q, 0, np.zeros(1, np.int64))
        assert v == pytest.approx(float(ref(q)), abs=1e-13)
        assert d == pytest.approx(float(ref.derivative()(q)), abs=1e-12)


@pytest.mark.parametrize("plain", [False, True], ids=["njit", "py_func"])
def test_hermite_cells_reproduce_multilinear_functions_with_gradient(plain):
    """3-D cells reproduce a multilinear function (exact PCHIP slopes) and its exact gradient."""
    fn = ic.hermite3_cells_grad.py_func if plain else ic.hermite3_cells_grad
    val = ic.hermite3_cells.py_func if plain else ic.hermite3_cells
    ax = [_nodes(5, -1, 2), _nodes(4, 0, 3), _nodes(6, 1, 2)]
    c = rng.normal(size=8)

    def f(x, y, z):
        return c[0] + c[1] * x + c[2] * y + c[3] * z + c[4] * x * y + c[5] * x * z + c[6] * y * z + c[7] * x * y * z

    C = _cells(ax, f(*np.meshgrid(*ax, indexing="ij")))
    for _ in range(10):
        q = [rng.uniform(a[0], a[-1]) for a in ax]
        r = fn(ax[0], ax[1], ax[2], 0, 0, 0, C, 0, q[0], q[1], q[2], 0, np.zeros(1, np.int64))
        exact = (c[1] + c[4] * q[1] + c[5] * q[2] + c[7] * q[1] * q[2],
                 c[2] + c[4] * q[0] + c[6] * q[2] + c[7] * q[0] * q[2],
                 c[3] + c[5] * q[0] + c[6] * q[1] + c[7] * q[0] * q[1])
        assert r[0] == pytest.approx(f(*q), abs=1e-12)
        assert np.allclose(r[1:], exact, atol=1e-11)
        assert val(ax[0], ax[1], ax[2], 0, 0, 0, C, 0, q[0], q[1], q[2], 0, np.zeros(1, np.int64)) == pytest.approx(
            f(*q), abs=1e-12)


@pytest.mark.parametrize("ndim", [1, 2, 3])
def test_hermite_cells_equal_the_tensor_hermite_form(ndim):
    """Cells (monomials in t - t_i, nested Horner) against method 2 (Hermite basis weights, node data):
    the same interpolant in two bases, so equal to rounding: values and gradients within 1e-13 of their
    range, on log axes with log values and a non-uniform axis (bisection), queries inside and clamped."""
    nodes = [np.geomspace(1e-7, 1e-5, 7), np.sort(np.r_[0.1, 3.0, rng.uniform(0.1, 3.0, 4)]), np.linspace(-1, 1, 4)]
    logs = (1, 0, 0)[:ndim]
    ax = tuple(prepare_axis(x, l) for x, l in zip(nodes[:ndim], logs))
    V = np.exp(rng.normal(size=tuple(a.size for a in ax)))
    u = prepare_values(V, 1)
    D = interp.hermite_data(ax, u)
    C = ic.hermite_cells_data(ax, D)
    assert C.shape == tuple(a.size - 1 for a in ax) + (4**ndim,)
    lo = np.array([1e-7, 0.1, -1.0])[:ndim]
    hi = np.array([1e-5, 3.0, 1.0])[:ndim]
    q = lo + rng.uniform(-0.05, 1.05, (300, ndim)) * (hi - lo)
    q[:, 0] = np.exp(np.log(1e-7) + rng.uniform(-0.05, 1.05, 300) * np.log(100.0))
    c1, c2 = np.zeros(1, np.int64), np.zeros(1, np.int64)
    v2, g2 = interp.evaluate(ax, logs, D, 1, interp.HERMITE, q, 0, c1, grad=True)
    v3, g3 = ic.evaluate_cells(ax, logs, C, 1, q, 0, c2, grad=True)
    assert c1[0] == c2[0] > 0
    assert np.abs(v3 - v2).max() < 1e-13 * np.abs(v2).max()
    assert np.all(np.abs(g3 - g2).max(axis=0) < 1e-13 * np.abs(g2).max(axis=0))




def test_hermite_cells_data_rejects_a_wrong_array():
    """hermite_cells_data needs the (2**ndim, n0, ...) array of hermite_data, not the values."""
    ax = (np.linspace(0, 1, 4), np.linspace(0, 1, 3))
    with pytest.raises(ValueError, match="hermite_data"):
        ic.hermite_cells_data(ax, np.zeros((4, 3)))


@pytest.mark.parametrize("plain", [False, True], ids=["njit", "py_func"])
@pytest.mark.parametrize("name", ["hermite3_cells", "hermite3_cells_grad"])
def test_hermite3_cells_clamp_count_and_nan(name, plain):
    """As tests/test_interp.py::test_hermite3_clamp_count_and_nan for the cells kernels: a query outside
    is clamped to the end value of v = 1 + x + 2 y - z with one count; mode 1 gives NaN without a count;
    a NaN coordinate gives NaN in both modes, counted in mode 0 only; the gradient at a clamped point is
    the one-sided derivative (1, 2, -1)."""
    fn = getattr(ic, name)
    fn = fn.py_func if plain else fn
    ax = (np.linspace(0, 1, 4), np.linspace(0, 2, 3), np.linspace(-1, 1, 5))
    V = 1.0 + ax[0][:, None, None] + 2.0 * ax[1][None, :, None] - ax[2][None, None, :]
    data = ic.hermite_cells_data(ax, interp.hermite_data(ax, V))
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
    assert np.all(np.isnan(call(0.5, np.nan, 3.0, 0))) and counter[0] == 3


def test_hermite3_cells_grad_has_no_reference_counting():
    """The compiled cells kernel holds no NRT_incref/NRT_decref (counted in its own assembly)."""
    import numba
    from numba import njit

    kernel = ic.hermite3_cells_grad
    fn = njit(**{k: v for k, v in kernel.targetoptions.items() if k != "nopython"})(kernel.py_func)
    ax = [np.linspace(0, 1, 4)] * 3
    data = ic.hermite_cells_data(tuple(ax), interp.hermite_data(tuple(ax), np.zeros((4,) * 3)))
    # compiled once, for a model's argument types (a call would first type the integers as literals)
    sig = tuple(numba.typeof(a) for a in (*ax, *[np.int64(0)] * 3, data, np.int64(0), *[0.5] * 3, np.int64(0),
                                         np.zeros(1, np.int64)))
    fn.compile(sig)
    asm = fn.inspect_asm(sig)
    start = re.compile(r"^_ZN\S*?\d+hermite3_cells_gradB\S*:$", re.M).search(asm)
    assert start is not None
    body = asm[start.end():asm.index(".Lfunc_end", start.end())]
    assert body.count("NRT_incref") + body.count("NRT_decref") == 0
