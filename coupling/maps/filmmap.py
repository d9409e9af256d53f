"""FilmMap: a tabulated film (axes, outputs, provenance) with its interpolation, files and plots.

Part of :mod:`lubedyn.maps` (the package docstring gives the overview)."""
from __future__ import annotations

from pathlib import Path
from typing import NamedTuple
import dataclasses
import io
import json
import logging
import math
import zipfile

import numpy as np

from lubedyn.dynamics import interp
from lubedyn.dynamics.cageless.layout import BallBallMap
from lubedyn.lubrication.errors import InputError, unknown_choice

from lubedyn import outputs
from lubedyn.maps.fit import PowerLawFit, fit_power_law, local_floor, relative_error
from lubedyn.maps.registry import ACCURACY_TOLERANCE, FORMAT, FORMAT_VERSION, METHODS, MapAxis, ZERO_FLOOR

log = logging.getLogger(__name__)

#: what a film map file is, for the message when a file given as one is not
EXPECTED_FILE = "expected a film map .npz written by `lubedyn run` of a map case (e.g. cases/map_ball_ball.toml)"

# ---------------------------------------------------------------------------
# the map


class KernelArrays(NamedTuple):
    """What :mod:`lubedyn.dynamics.interp` needs for one output (see its docstring).

    ``method`` 0 (linear) or 1 (pchip): ``interp3(*axes, *logs, values, logv, method, x0, x1, x2, mode,
    counter)``; ``method`` 2 (hermite): ``values`` is the node-derivative array of
    :func:`lubedyn.dynamics.interp.hermite_data`, shape (2**ndim, n0, ...): ``hermite3(*axes, *logs, values, logv,
    x0, x1, x2, mode, counter)`` (likewise 1 and 2 axes)."""

    axes: tuple      # prepared node coordinates (log applied on log axes), float64
    logs: tuple      # 0/1 per axis
    values: np.ndarray  # prepared values (log applied when logv), C order; hermite: node derivatives
    logv: int
    method: int      # interp.LINEAR, interp.PCHIP or interp.HERMITE


class FilmMap:
    """Outputs of a film kind tabulated on axes; see the module docstring.

    Parameters
    ----------
    axes : sequence of :class:`MapAxis` (1 to 3)
    values : {output name: array of shape (n0[, n1[, n2]])}
    method : "hermite" (cubic Hermite on PCHIP node slopes, default; the fastest cubic), "pchip"
        (sequential monotone cubic, as scipy's RegularGridInterpolator(method="pchip")) or "linear"
    log_values : {output: bool}; default: log where every value is > 0
    provenance, fits, accuracy : dicts (see :func:`build_map`)
    sheared : {output: spec}: outputs the map returns on a sheared coordinate (the point kind's
        ``sheared``).  ``spec``: ``"values"`` (a tabulated output G), ``"shift"`` (a tabulated output c > 0,
        independent of axis ``"axis"``), ``"axis"`` k (a log axis), ``"centre"``, ``"a"``, ``"b"``.  At
        coordinates (..., x_k, ...) the map returns ``G(..., T^-1(x_k / c(...)), ...)``, T the map
        ln T(x) = a sinh(b ln(x/centre)) (denser near x = centre, where T = 1): the
        kind tabulates G at a node (..., x_k, ...) as the output at x_k' = T(x_k) c(node), so that along
        axis k it is a function of the normalised coordinate x_k'/c, in which a front at x_k' ~ c stays put
        from node to node (the roller kinds' traction, :mod:`lubedyn.film_points`).  The output's own
        table (at x_k) is kept for plots but not interpolated (:meth:`kernel_arrays` refuses it).
    """

    def __init__(self, axes, values: dict, *, method: str = "hermite", log_values: dict | None = None,
                 provenance: dict | None = None, fits: dict | None = None, accuracy: dict | None = None,
                 sheared: dict | None = None):
        self.axes = tuple(axes)
        if not 1 <= len(self.axes) <= 3:
            raise InputError(f"a map has 1 to 3 axes, got {len(self.axes)}")
        if method not in METHODS:
            raise unknown_choice("method", method, METHODS)
        self.method = method
        shape = tuple(a.n for a in self.axes)
        self.values = {}
        for name, arr in values.items():
            arr = np.ascontiguousarray(arr, dtype=float)
            if arr.shape != shape:
                raise InputError(f"values of {name!r} have shape {arr.shape}; the axes need {shape}")
            self.values[name] = arr
        log_values = dict(log_values or {})
        self.log_values = {k: bool(log_values.get(k, bool(np.all(v > 0)))) for k, v in self.values.items()}
        self.provenance = dict(provenance or {})
        self.fits = dict(fits or {})
        self.accuracy = dict(accuracy or {})
        self.sheared = {}
        for name, spec in dict(sheared or {}).items():
            spec = dict(spec)
            missing = [o for o in (name, spec.get("values"), spec.get("shift")) if o not in self.values]
            k = int(spec.get("axis", -1))
            if missing or not 0 <= k < len(self.axes) or not self.axes[k].log:
                raise InputError(f"sheared output {name!r}: needs tabulated outputs {name!r}, {spec.get('values')!r}, "
                                 f"{spec.get('shift')!r} (missing {missing}) and a log axis {k}")
            self.sheared[name] = spec
        self._kernel: dict = {}

    # -- description
    @property
    def outputs(self) -> tuple:
        return tuple(self.values)

    @property
    def shape(self) -> tuple:
        return tuple(a.n for a in self.axes)

    @property
    def ndim(self) -> int:
        return len(self.axes)

    @property
    def kind(self) -> str:
        """Name of the point kind the map tabulates ("" when unknown)."""
        return str(self.provenance.get("kind", ""))

    @property
    def input_hash(self) -> str:
        """sha256 of every input of the build (kind, parameters, axes, method, code); "" when unknown."""
        return str(self.provenance.get("input sha256", {}).get("map", ""))

    def __repr__(self):
        axes = ", ".join(f"{a.name} {a.lo:.3g}..{a.hi:.3g} ({a.n}, {a.scale})" for a in self.axes)
        return f"FilmMap({self.provenance.get('kind', '?')}: {axes}; outputs {', '.join(self.outputs)})"

    def _output(self, output: str) -> str:
        if output not in self.values:
            raise unknown_choice("output", output, self.outputs)
        return output

    # -- kernel
    def kernel_arrays(self, output: str) -> KernelArrays:
        """Plain arrays of ``output`` for :mod:`lubedyn.dynamics.interp` (``interp2(*ka.axes, *ka.logs, ka.values,
        ka.logv, ka.method, x0, x1, mode, counter)``)."""
        output = self._output(output)
        if output in self.sheared:
            raise InputError(f"map {self.kind}: {output!r} is returned on a sheared coordinate (FilmMap.sheared): "
                             f"its own table is not what the map interpolates; call the map, or take the kernel "
                             f"arrays of {self.sheared[output]['values']!r} and {self.sheared[output]['shift']!r}")
        if output not in self._kernel:
            logv = self.log_values[output]
            axes = tuple(interp.prepare_axis(a.nodes, a.log) for a in self.axes)
            u = interp.prepare_values(self.values[output], logv)
            if self.method == "hermite":
                u = interp.hermite_data(axes, u)
            self._kernel[output] = KernelArrays(axes, tuple(int(a.log) for a in self.axes), u, int(logv),
                                                interp.METHODS[self.method])
        return self._kernel[output]

    def __call__(self, output: str, *coords, mode: str = "raise", counter=None, grad: bool = False):
        """Interpolate ``output`` at broadcast ``coords`` (one array per axis, SI).

        ``mode``: "raise" (InputError for a point outside the axes or with a
        NaN coordinate), "clamp" (move it to the nearest end; ``counter[0]``
        counts such points, and points with a NaN coordinate, which give
        NaN), or "nan" (NaN for both).  ``grad=True`` also returns d output/d coordinate, shape (..., ndim).
        """
        if len(coords) != self.ndim:
            raise InputError(f"{output}: give {self.ndim} coordinates ({', '.join(a.name for a in self.axes)}), "
                             f"got {len(coords)}")
        if mode not in ("raise", "clamp", "nan"):
            raise unknown_choice("mode", mode, ("raise", "clamp", "nan"))
        if output in self.sheared:
            if grad:
                raise InputError(f"map {self.kind}: no gradient of the sheared output {output!r}")
            return self._sheared(output, coords, mode, counter)
        ka = self.kernel_arrays(output)
        arrays = np.broadcast_arrays(*[np.asarray(c, dtype=float) for c in coords])
        shape = arrays[0].shape
        points = np.stack([a.ravel() for a in arrays], axis=1)
        counter = np.zeros(1, dtype=np.int64) if counter is None else counter
        kmode = interp.CLAMP if mode == "clamp" else interp.NAN
        v, g = interp.evaluate(ka.axes, ka.logs, ka.values, ka.logv, ka.method, points, kmode, counter, grad=True)
        if mode == "raise":
            nan_rows = np.isnan(points).any(axis=1)
            if nan_rows.any():
                first = int(np.flatnonzero(nan_rows)[0])
                names = [a.name for a, x in zip(self.axes, points[first]) if np.isnan(x)]
                raise InputError(f"map {self.provenance.get('kind', '')} {output}: {int(nan_rows.sum())} point(s) "
                                 f"with a NaN coordinate, first point {first} ({', '.join(names)} = nan); "
                                 f"every coordinate must be a number (mode='clamp' counts such points, "
                                 f"mode='nan' returns NaN)")
            bad = np.isnan(v)
            if bad.any():
                q = points[np.flatnonzero(bad)[0]]
                where = [f"{a.name} = {x:.6g} (axis {a.lo:.6g} .. {a.hi:.6g})" for a, x in zip(self.axes, q)
                         if not a.lo <= x <= a.hi]
                raise InputError(f"map {self.provenance.get('kind', '')} {output}: {int(bad.sum())} point(s) outside "
                                 f"the axes, first {', '.join(where)}; extend the axes or query with mode='clamp'")
        v = v.reshape(shape)
        return (v, g.reshape(shape + (self.ndim,))) if grad else v

    def _sheared(self, output, coords, mode, counter):
        """A sheared output at ``coords`` (see the class docstring, ``sheared``)."""
        spec = self.sheared[output]
        k = int(spec["axis"])
        shift = self(spec["shift"], *coords, mode=mode, counter=counter)  # checks the coordinates
        a, b, centre = float(spec["a"]), float(spec["b"]), float(spec["centre"])
        with np.errstate(invalid="ignore", divide="ignore"):
            sigma = np.asarray(coords[k], dtype=float) / shift
            x = centre * np.exp(np.arcsinh(np.log(sigma) / a) / b)
        moved = list(coords)
        moved[k] = x
        # x leaves the axis only where the interpolated shift overshoots its tabulated range: clamp
        return self(spec["values"], *moved, mode="nan" if mode == "nan" else "clamp",
                    counter=np.zeros(1, dtype=np.int64))

    # -- dynamics
    def is_polar(self) -> bool:
        """True for a ball_ball map on the polar axes (gap, pressure number, squeeze angle)."""
        return [a.name for a in self.axes][1:] == [POLAR_AXES[0], POLAR_AXES[1]]

    def dynamics_film_map(self, output: str = "Force [N]"):
        """Kernel arrays of ``output`` for :class:`lubedyn.dynamics.cageless.CagelessBearing` (``film = "map"``).

        A map on (gap, squeeze number or approach speed, entrainment speed): its kernel arrays.  A polar
        ball_ball map (:mod:`lubedyn.film_points`, "Polar axes"): its kernel arrays with the speed axis they
        are on, ``BallBallMap(kernel_arrays, "polar")`` (:class:`lubedyn.dynamics.cageless.layout.BallBallMap`)."""
        output = self._output(output)
        if not self.is_polar():
            return self.kernel_arrays(output)

        return BallBallMap(self.kernel_arrays(output), "polar")

    def grid_points(self) -> np.ndarray:
        """All nodes as (N, ndim) in C order of the value arrays."""
        grids = np.meshgrid(*[a.nodes for a in self.axes], indexing="ij")
        return np.stack([g.ravel() for g in grids], axis=1)

    # -- fit
    def fit_power_law(self, output: str, cross="auto") -> PowerLawFit | None:
        """Fit (and keep in ``self.fits``) a power law of ``output``; see :func:`fit_power_law`."""
        output = self._output(output)
        fit = fit_power_law(self.axes, self.values[output], output, cross)
        self.fits[output] = fit
        return fit

    # -- accuracy
    def accuracy_against(self, points: np.ndarray, direct: dict) -> dict:
        """Interpolation error at ``points`` (m, ndim) against ``direct`` {output: (m,) values}:
        per output ``{"median": .., "max": .., "points": m, "above 3 %": .., "worst point": [...]}``."""
        report = {}
        # the tabulated function of a sheared output (its "values") is judged through that output: its
        # table spans (axes, normalised coordinate) combinations the output never reads (the roller kinds:
        # a node whose transition slip saturates at 1e-7 reads sigma >= 100 only)
        internal = {spec["values"] for spec in self.sheared.values()}
        for name, exact in direct.items():
            if name not in self.values or name in internal:
                continue
            exact = np.asarray(exact, float)
            approx = self(name, *points.T, mode="nan")
            err = relative_error(approx, exact, local_floor(self, name, points))
            ok = np.isfinite(err)
            if not ok.any():
                continue
            worst = int(np.nanargmax(np.where(ok, err, -1)))
            report[name] = {"median": float(np.median(err[ok])), "max": float(err[ok].max()), "points": int(ok.sum()),
                            "above 3 %": int(np.sum(err[ok] > 0.03)),
                            "worst point": [float(x) for x in points[worst]]}
        return report

    @property
    def accuracy_tolerance(self) -> float:
        """The largest relative error the accuracy report may show without a warning: the build's
        (``accuracy["tolerance"]``), else :data:`~lubedyn.maps.ACCURACY_TOLERANCE` (maps built before the
        tolerance was stored)."""
        return float(self.accuracy.get("tolerance", ACCURACY_TOLERANCE))

    def accuracy_warning(self, source: str = "") -> str | None:
        """One line when an output of the accuracy report has a relative error above
        :attr:`accuracy_tolerance` (None otherwise, and for a map without a report): ``source`` (the map
        file; default ``"map <kind>"``), each such output with its worst error, its median and the axis
        values of its worst point, worst output first, and the tolerance."""
        tol = self.accuracy_tolerance
        misses = sorted(((rep["max"], name, rep) for name, rep in self.accuracy.items()
                         if isinstance(rep, dict) and rep.get("max", 0.0) > tol), key=lambda m: -m[0])
        if not misses:
            return None
        parts = []
        for worst, name, rep in misses:
            at = ", ".join(f"{a.name} = {x:.4g}" for a, x in zip(self.axes, rep.get("worst point", ())))
            parts.append(f"{name} up to {100 * worst:.3g} % at ({at}), median {100 * rep['median']:.2g} % of "
                         f"{rep.get('points', '?')} points")
        return (f"{source or 'map ' + (self.kind or '?')}: interpolation error above the map's accuracy tolerance "
                f"{100 * tol:.3g} %: " + "; ".join(parts) + "; errors relative to direct solves at random off-grid "
                "points (the map's accuracy report): values read from the map near there carry them (rebuild it "
                "with more nodes on the axes, or set build.accuracy_tolerance if they are acceptable)")

    # -- storage
    def _header(self) -> dict:
        return {
            "format": FORMAT, "format_version": FORMAT_VERSION, "method": self.method,
            "axes": [{"name": a.name, "scale": a.scale, "array": f"axis_{i}"} for i, a in enumerate(self.axes)],
            "outputs": [{"name": k, "log_values": self.log_values[k], "array": f"values_{i}"}
                        for i, k in enumerate(self.values)],
            "provenance": self.provenance,
            "fits": {k: (dataclasses.asdict(f) if f is not None else None) for k, f in self.fits.items()},
            "accuracy": self.accuracy,
            "sheared": self.sheared,
        }

    def save(self, path) -> Path:
        """Write one self-describing ``.npz`` (arrays + JSON header) atomically."""
        arrays = {f"axis_{i}": a.nodes for i, a in enumerate(self.axes)}
        arrays.update({f"values_{i}": v for i, v in enumerate(self.values.values())})
        arrays["header"] = np.array(json.dumps(self._header(), default=_json_default))
        buffer = io.BytesIO()
        np.savez_compressed(buffer, **arrays)
        return outputs.write_bytes(path, buffer.getvalue())

    @classmethod
    def load(cls, path, *, key: str = "", check: bool = True) -> "FilmMap":
        """Read a file written by :meth:`save`; checks the format name and version.

        ``key``: the case key that named the file (``"films.map"``), for the messages.  A file that is not
        a film map raises one-line :class:`~lubedyn.lubrication.errors.InputError` saying what it is and what is
        expected.  ``check``: log :meth:`accuracy_warning` (WARNING) when the map's accuracy report is
        above its tolerance."""
        path = Path(path)
        subject = f"{key} = {str(path)!r}" if key else f"map file {str(path)!r}"
        if not path.is_file():
            raise InputError(f"{subject} not found")
        with open(path, "rb") as f:
            head = f.read(512)
        if not head.startswith(b"PK"):  # an .npz is a zip archive
            raise InputError(f"{subject} {_what_file(head)}, not a film map: {EXPECTED_FILE}")
        try:
            with np.load(path, allow_pickle=False) as data:
                if "header" not in data.files:
                    raise InputError(f"{subject} is an .npz without the film map's header (arrays: "
                                     f"{', '.join(data.files[:6]) or 'none'}): {EXPECTED_FILE}")
                header = json.loads(str(data["header"]))
                arrays = {k: np.array(data[k]) for k in data.files if k != "header"}
        except InputError:
            raise
        except (KeyError, ValueError, OSError, EOFError, zipfile.BadZipFile) as exc:
            # numpy's own text for object arrays advises loading them "unsafely" with allow_pickle: never passed on
            why = ("it holds Python objects, which a film map never does" if "pickle" in str(exc)
                   else " ".join(str(exc).split()))
            raise InputError(f"{subject} is not a readable film map ({why}): {EXPECTED_FILE}") from None
        if not isinstance(header, dict) or header.get("format") != FORMAT:
            got = header.get("format") if isinstance(header, dict) else None
            raise InputError(f"{subject}: format {got!r}, expected {FORMAT!r} ({EXPECTED_FILE})")
        if header.get("format_version") != FORMAT_VERSION:
            raise InputError(f"{subject}: format_version = {header.get('format_version')!r}; this "
                             f"lubedyn reads version {FORMAT_VERSION} (rebuild the map)")
        axes = [MapAxis(a["name"], arrays[a["array"]], a["scale"]) for a in header["axes"]]
        values = {o["name"]: arrays[o["array"]] for o in header["outputs"]}
        fits = {k: (PowerLawFit(**{**f, "exponents": tuple(f["exponents"]), "cross": tuple(f["cross"]),
                                   "terms": tuple(f.get("terms", ())),
                                   "quadratic": tuple(tuple(q) for q in f.get("quadratic", ()))})
                    if f is not None else None) for k, f in header.get("fits", {}).items()}
        fmap = cls(axes, values, method=header["method"],
                   log_values={o["name"]: o["log_values"] for o in header["outputs"]},
                   provenance=header.get("provenance", {}), fits=fits, accuracy=header.get("accuracy", {}),
                   sheared=header.get("sheared", {}))
        if check:
            text = fmap.accuracy_warning(subject)
            if text:
                log.warning("%s", text)
        return fmap

    # -- plots
    def plot(self, outputs_=None, *, lines: int = 5):
        """One panel per output against axis 0, a line per node of axis 1 (up to ``lines``),
        the other axes at their middle node.  Returns the matplotlib figure."""
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        names = list(outputs_ or self.outputs)
        ncol = min(3, len(names))
        nrow = math.ceil(len(names) / ncol)
        fig, axs = plt.subplots(nrow, ncol, figsize=(4.6 * ncol, 3.6 * nrow), squeeze=False)
        a0 = self.axes[0]
        fine = np.geomspace(a0.lo, a0.hi, 200) if a0.log else np.linspace(a0.lo, a0.hi, 200)
        picks = [0] if self.ndim == 1 else sorted(set(np.linspace(0, self.axes[1].n - 1, min(lines, self.axes[1].n))
                                                      .round().astype(int)))
        mids = [a.nodes[a.n // 2] for a in self.axes[2:]]
        cmap = plt.get_cmap("viridis")
        for ax, name in zip(axs.ravel(), names):
            for c, j in enumerate(picks):
                coords = [fine] + ([np.full_like(fine, self.axes[1].nodes[j])] if self.ndim > 1 else []) + \
                         [np.full_like(fine, m) for m in mids]
                color = cmap(c / max(1, len(picks) - 1))
                label = f"{self.axes[1].name.split('[')[0].strip()} = {self.axes[1].nodes[j]:.3g}" if self.ndim > 1 else None
                ax.plot(fine, self(name, *coords, mode="clamp"), color=color, lw=1.2, label=label)
                index = (slice(None),) + ((j,) if self.ndim > 1 else ()) + tuple(a.n // 2 for a in self.axes[2:])
                ax.plot(a0.nodes, self.values[name][index], "o", color=color, ms=3)
            v = self.values[name]
            if a0.log:
                ax.set_xscale("log")
            pos = v[v > 0]
            if self.log_values[name] or (np.all(v >= 0) and pos.size and pos.max() > 1e3 * pos.min()):
                ax.set_yscale("log")  # zeros (a cavitated film's force) are left out of a log axis
            elif np.any(v < 0) and np.any(v > 0):
                ax.set_yscale("symlog", linthresh=ZERO_FLOOR * np.abs(v).max() * 10)
            ax.set_xlabel(a0.name)
            ax.set_ylabel(name)
            ax.grid(True, which="both", alpha=0.3)
        if self.ndim > 1:
            axs.ravel()[0].legend(fontsize=7)
        for ax in axs.ravel()[len(names):]:
            ax.set_visible(False)
        rest = ", ".join(f"{a.name} = {m:.3g}" for a, m in zip(self.axes[2:], mids))
        fig.suptitle(f"{self.provenance.get('kind', 'map')}: nodes (dots) and {self.method} interpolation (lines)"
                     + (f"; {rest}" if rest else ""), fontsize=9)
        fig.tight_layout()
        return fig


_json_default = outputs.json_default


def _what_file(head: bytes) -> str:
    """What a file that is not a zip archive is, from its first bytes."""
    if not head:
        return "is empty"
    if head.startswith(b"\x93NUMPY"):
        return "is a single NumPy array (.npy)"
    try:
        text = head.decode("utf-8")
    except UnicodeDecodeError as exc:
        if exc.start < len(head) - 3:  # not a character cut at the end of the bytes read
            return "is not an .npz (zip) archive"
        text = head[:exc.start].decode("utf-8")
    return "is a text file" if "\x00" not in text else "is not an .npz (zip) archive"


POLAR_AXES = ("Pressure number [-]", "Squeeze angle [rad]")
CARTESIAN_SQUEEZE = (0.0, 0.01, 0.03, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9)
CARTESIAN_ENTRAINMENT = (0.0, 0.025, 0.05)


def cartesian_resample(fmap: "FilmMap", output: str = "Force [N]", squeeze=CARTESIAN_SQUEEZE,
                       entrainment=CARTESIAN_ENTRAINMENT, gaps: int = 19) -> "FilmMap":
    """A polar ball_ball map's ``output`` on (gap, squeeze number, entrainment speed) nodes (approach side).

    Each node (h0, Lambda, u_e) is turned into (rho, theta) (:func:`lubedyn.film_points.polar_numbers`)
    and read from the polar map: rho above the axis is clamped, rho below its first node scales the
    output by rho/rho_lo (isoviscous limit: F, K ~ rho), rho = 0 gives 0."""
    from lubedyn import film_points as fp  # deferred: the point kinds import scikit-fem

    params = fmap.provenance.get("params") or fp.ball_ball_default_params()
    g = fmap.axes[0]
    h_nodes = np.geomspace(g.lo, g.hi, gaps)
    rho_lo, rho_hi = fmap.axes[1].lo, fmap.axes[1].hi
    vals = np.zeros((gaps, len(squeeze), len(entrainment)))
    for i, h0 in enumerate(h_nodes):
        for j, lam in enumerate(squeeze):
            for k, ue in enumerate(entrainment):
                rho, theta = fp.polar_numbers(h0, fp.approach_speed(h0, lam, params), ue, params)
                if rho <= 0.0:
                    continue
                rq = min(max(rho, rho_lo), rho_hi)
                vals[i, j, k] = float(fmap(output, h0, rq, theta, mode="clamp")) * (rho / rho_lo if rho < rho_lo else 1.0)
    axes = [MapAxis(g.name, h_nodes, "log"), MapAxis("Squeeze number [-]", np.array(squeeze, float), "linear"),
            MapAxis("Entrainment speed [m/s]", np.array(entrainment, float), "linear")]
    prov = {**fmap.provenance, "resampled from": "polar axes (gap, pressure number, squeeze angle)"}
    return FilmMap(axes, {output: vals}, method=fmap.method, provenance=prov)
