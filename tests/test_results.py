"""Results by name (lubedyn.results): a bearing run's time series read as ``res[name]`` with the names of
``timeseries.nc``, their units, the run's warnings, ``to_xarray()`` and ``plot(kind)``; each read is checked
against a value the case states or the physics fixes, each figure's data against the series by name, not
against the reader itself."""
import math

import numpy as np
import pytest

import lubedyn
from lubedyn.results import split_unit


@pytest.fixture(scope="module")
def tapered():
    case = lubedyn.load_case("trb_fig5_2400rpm", smoke=True)
    return case, lubedyn.run(case)


def test_a_tapered_run_reads_its_series_by_name(tapered):
    case, res = tapered
    t = res["Time [s]"]
    assert np.allclose(np.diff(t), case.integrator.sample_interval, rtol=1e-9)
    assert t[-1] == pytest.approx(case.integrator.duration, rel=1e-9)
    # the cage turns at its ideal (epicyclic) speed within the rollers' slip, 2,400 rpm on the cone
    ideal = res.summary["Ideal cage speed [rpm]"] * math.pi / 30.0
    cage = res["Cage speed [rad/s]"]
    assert cage.shape == t.shape and np.all(np.abs(cage / ideal - 1.0) < 0.03)
    assert res.units("Cage speed [rad/s]") == "rad/s" and "Cage speed [rad/s]" in res.names
    assert res.warnings == []
    with pytest.raises(KeyError, match=r"did you mean 'Cage speed \[rad/s\]'"):
        res["Cage sped [rad/s]"]


def test_to_xarray_names_units_and_identity(tapered):
    pytest.importorskip("xarray")
    _, res = tapered
    ds = res.to_xarray()
    assert ds.sizes["time"] == len(res.t)
    var = ds["Cage speed"]
    assert var.attrs == {"units": "rad/s", "long_name": "Cage speed", "column": "Cage speed [rad/s]"}
    assert np.array_equal(var.values, res["Cage speed [rad/s]"])
    # the rollers' columns along a dimension of their own: one variable per quantity, the case's 17 rollers
    tilt = ds["Roller tilt"]
    assert tilt.dims == ("time", "roller") and tilt.attrs["units"] == "rad"
    assert list(ds["roller"].values) == list(range(17))
    for j in (0, 5, 16):
        assert np.array_equal(tilt.values[:, j], res[f"Roller {j} tilt [rad]"])
    assert ds["time"].attrs["units"] == "s" and ds.attrs["Scene"] == "tapered"
    assert ds.attrs["lubedyn version"] == lubedyn.__version__


@pytest.fixture(scope="module")
def cageless():
    case = lubedyn.load_case("cageless_6206_10krpm_short", smoke=True)
    return case, lubedyn.run(case)


def test_a_cageless_run_starts_at_the_cases_rotor_speed(cageless):
    case, res = cageless
    # 10,000 rpm before the drop, as the case states
    assert res["Rotor speed [rad/s]"][0] == pytest.approx(10000 * math.pi / 30.0, rel=1e-9)
    assert res["Inner ring speed [rad/s]"].shape == res.t.shape


def test_split_unit():
    assert split_unit("Ball 0 Inner sliding speed [m/s]") == ("Ball 0 Inner sliding speed", "m/s")
    assert split_unit("Loaded zone [-]") == ("Loaded zone", "-")
    assert split_unit("Phase") == ("Phase", "")


def test_plot_draws_the_cli_figures_into_a_given_axes_or_figure(tapered):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from lubedyn.scenes.tapered import FIELD_FILES

    _, res = tapered
    assert res.kinds == [f.removesuffix(".png") for f, kind in FIELD_FILES if kind == "png"]
    ms = res.t * 1e3
    # one panel into the caller's Axes: roller 0's slip and the mean over the 17 rollers, in percent
    fig = Figure()
    ax = fig.subplots()
    assert res.plot("slip", ax=ax) is fig and fig.axes == [ax]
    slip = np.array([res[f"Roller {j} roller slip [-]"] for j in range(17)])
    roller0, mean = ax.lines[0], ax.lines[1]
    assert np.array_equal(roller0.get_xdata(), ms) and np.array_equal(roller0.get_ydata(), 100 * slip[0])
    assert np.allclose(mean.get_ydata(), 100 * slip.mean(axis=0), rtol=1e-12, atol=0)
    # two panels into the caller's figure: tilt and skew of roller 0
    fig = Figure()
    assert res.plot("roller_attitude", fig=fig) is fig and len(fig.axes) == 2
    assert np.array_equal(fig.axes[0].lines[0].get_ydata(), res["Roller 0 tilt [rad]"])
    assert np.array_equal(fig.axes[1].lines[0].get_ydata(), res["Roller 0 skew [rad]"])
    # no target: a new figure, as lubedyn run saves it
    assert len(res.plot("cone_orbit").axes) == 1


def test_plot_refuses_an_unknown_kind_and_an_axes_for_several_panels_in_one_line(tapered):
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    _, res = tapered
    with pytest.raises(ValueError) as err:
        res.plot("slp")
    text = str(err.value)
    assert "\n" not in text and "'slp'" in text and "'roller_attitude'" in text and "did you mean 'slip'" in text
    with pytest.raises(ValueError, match=r"2 panels .*give fig="):
        res.plot("roller_attitude", ax=Figure().subplots())


def test_plot_of_a_cageless_run_into_a_subfigure(cageless):
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    case, res = cageless
    assert {"trajectories", "phase_portraits", "spectrum", "poincare", "collision_map"} <= set(res.kinds)
    j = case.analysis.ball
    left, right = Figure(figsize=(12, 6)).subfigures(1, 2)
    assert res.plot("trajectories", fig=left) is left and len(left.axes) == 3 and not right.axes
    for i, axis in enumerate("xyz"):  # the ball's centre in mm, the state columns of its 6-dof model
        assert np.array_equal(left.axes[i].lines[0].get_ydata(), res[f"Ball {j} {axis} [m]"] * 1e3)
    res.plot("phase_portraits", fig=right)
    assert len(right.axes) == 6
