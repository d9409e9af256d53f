"""Journal-bearing stiffness and damping over speed, and the bridge to ROSS.

A rotordynamics model takes each fluid-film bearing as 2 x 2 stiffness and damping matrices that depend on
the rotor speed.  :func:`bearing_coefficients` computes them with the film solver
(:func:`lubedyn.lubrication.reynolds.film_coefficients`: one perturbation solve per mode and kind about the
solved film) at each speed of a list, and :func:`to_ross` hands them to ROSS (``ross-rotordynamics``) as a
speed-dependent ``ross.BearingElement``::

    coef = lubedyn.bearing_coefficients("journal_finite", ["1000 rpm", "3000 rpm"], load="2 kN")
    coef["Stiffness K[x,y] [N/m]"]      # one named array over coef.speed [rad/s]
    bearing = lubedyn.to_ross(coef, n=0)  # ross.BearingElement(n=0, kxx=..., frequency=coef.speed)

Two ways of holding the journal:

- ``load`` given (the usual rotordynamics question): at each speed the journal centre is moved to where the
  film carries the static load on the bearing (Newton's method on the film force F(q) + W = 0, whose
  Jacobian -K is what the perturbation solves give; each solve starts from the previous one); a scalar load
  points along -y (a weight), a pair is (W_x, W_y);
- ``load=None``: the journal centre stays where the case puts it (``gap.eccentricity_ratio`` and
  ``attitude_angle``, or ``eccentricity_x``/``_y``) at every speed.

Frame and signs, the solver's (:class:`lubedyn.lubrication.JournalBearing`): fixed x, y; the journal turns
from +x towards +y (a positive spin about +z, as ROSS's and Friswell et al.'s rotors turn); q = (x, y) the
journal centre's displacement from the bearing centre; ``K[i, j] = -dF_i/dq_j`` [N/m] and
``C[i, j] = -dF_i/d(dq_j/dt)`` [N s/m] with F the film force on the journal, so that the film acts on the
rotor as ``-K q - C dq/dt``, which is what ROSS's ``kxy`` (force along x from a displacement along y) and
``cxy`` mean.  With the load along -y this is the load frame (u, v) of Friswell et al. (2010, sec. 5.5) and
of :func:`lubedyn.lubrication.closed_form.short_journal_coefficients`: u = +x, v = +y.

ROSS is an optional extra (``pip install 'lubedyn[ross]'``), imported inside :func:`to_ross` only.
"""
from __future__ import annotations

import logging
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lubedyn.lubrication.errors import ConvergenceError, InputError, did_you_mean

log = logging.getLogger(__name__)

_ENTRIES = ("x,x", "x,y", "y,x", "y,y")


@dataclass(frozen=True)
class BearingCoefficients:
    """Journal-bearing stiffness and damping at a list of speeds (SI), from :func:`bearing_coefficients`.

    Attributes
    ----------
    speed : (n,) array
        Journal speeds [rad/s], in the order asked for.
    K : (n, 2, 2) array
        Stiffness [N/m], ``K[k, i, j] = -dF_i/dq_j`` at ``speed[k]``; i, j over (x, y).
    C : (n, 2, 2) array
        Damping [N s/m], ``C[k, i, j] = -dF_i/d(dq_j/dt)``.
    eccentricity : (n, 2) array
        The journal centre (x, y) [m] from the bearing centre where K and C were computed.
    force : (n, 2) array
        The film force on the journal there [N] (equal to -load to ``rtol`` when a load was held).
    clearance : float
        Radial clearance [m].
    load : (2,) array or None
        The static load (W_x, W_y) [N] on the journal that the film carries, or None (centre held fixed).
    iterations : (n,) int array
        Film solves made at each speed (the equilibrium's Newton steps; 1 without a load).
    warnings : tuple of str
        The film's own checks at each speed, one line each naming the speed (logged at WARNING): a
        minimum-gap zone the mesh does not resolve (:meth:`~lubedyn.lubrication.FilmSolution.resolution_warning`,
        as the film scene reports it) and the solver's warnings; empty when none.

    Named access as in a film run's ``summary.json``: ``coef["Stiffness K[x,y] [N/m]"]``,
    ``coef["Damping C[y,y] [N s/m]"]``, ``coef["Eccentricity ratio [-]"]`` ... (``coef.names`` lists them),
    each an array over ``speed``.
    """

    speed: np.ndarray
    K: np.ndarray
    C: np.ndarray
    eccentricity: np.ndarray
    force: np.ndarray
    clearance: float
    load: np.ndarray | None = None
    iterations: np.ndarray | None = None
    warnings: tuple = ()

    def _columns(self) -> dict:
        e = self.eccentricity
        out = {"Speed [rad/s]": self.speed}
        for k, entry in enumerate(_ENTRIES):
            out[f"Stiffness K[{entry}] [N/m]"] = self.K[:, k // 2, k % 2]
        for k, entry in enumerate(_ENTRIES):
            out[f"Damping C[{entry}] [N s/m]"] = self.C[:, k // 2, k % 2]
        out["Eccentricity x [m]"] = e[:, 0]
        out["Eccentricity y [m]"] = e[:, 1]
        out["Eccentricity ratio [-]"] = np.hypot(e[:, 0], e[:, 1]) / self.clearance
        # between the load the film carries (-F) and the line of centres, as the film scene's summary states it
        # (NaN for a centred journal or no film force)
        norms = np.linalg.norm(e, axis=1) * np.linalg.norm(self.force, axis=1)
        dots = np.einsum("ki,ki->k", e, -self.force)
        cosang = np.divide(dots, norms, out=np.full_like(dots, np.nan), where=norms > 0.0)
        out["Attitude angle [deg]"] = np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0)))
        out["Film force x [N]"] = self.force[:, 0]
        out["Film force y [N]"] = self.force[:, 1]
        return out

    @property
    def names(self) -> list[str]:
        """The names ``coef[name]`` accepts."""
        return list(self._columns())

    def __getitem__(self, name: str) -> np.ndarray:
        columns = self._columns()
        if name not in columns:
            raise KeyError(f"no bearing coefficient named {name!r} (.names lists them){did_you_mean(str(name), list(columns))}")
        return columns[name]

    def __len__(self) -> int:
        return int(self.speed.size)

    def to_ross(self, n: int, **kwargs):
        """``ross.BearingElement`` at node ``n``: see :func:`to_ross`."""
        return to_ross(self, n, **kwargs)


# ---------------------------------------------------------------------------
# inputs


def _film_of(source, *, smoke: bool = False):
    """The :class:`~lubedyn.lubrication.Film` of a journal-bearing film case (a case, a path or a bundled
    case's name) or the film itself; raises InputError for anything else."""
    from lubedyn import config
    from lubedyn.lubrication import Film, JournalBearing

    if isinstance(source, Film):
        film = source
        what = "the film"
    else:
        case = config.load_case(source, smoke=smoke) if isinstance(source, (str, Path)) else source
        scene, gap = getattr(case, "scene", None), getattr(getattr(case, "gap", None), "type", None)
        if scene != "film" or gap != "journal":
            raise InputError(f"bearing_coefficients: a case of scene {scene!r} with gap.type = {gap!r}; coefficients "
                             "over speed need a film case with gap.type = 'journal' (e.g. the bundled 'journal_finite') "
                             "or a lubedyn.lubrication.Film with a JournalBearing gap")
        from lubedyn.scenes.film import build_film

        film = build_film(case)
        what = f"case {getattr(case, 'description', '') or 'journal'!r}"
    if not isinstance(film.gap, JournalBearing):
        raise InputError(f"bearing_coefficients: the film's gap is a {type(film.gap).__name__}; coefficients over speed "
                         "need a JournalBearing gap")
    still = (np.allclose(np.asarray(film.velocity_lower, dtype=float), 0.0) if not callable(film.velocity_lower) else False)
    if not still or any(v != 0.0 for v in film.mode_velocities.values()) or callable(film.squeeze) or (film.squeeze or 0.0) != 0.0:
        raise InputError(f"bearing_coefficients: {what} moves the bearing surface (velocity_lower = "
                         f"{film.velocity_lower!r}) or the journal centre (mode_velocities = {dict(film.mode_velocities)!r}, "
                         f"squeeze = {film.squeeze!r}); the coefficients are about a static journal in a fixed bearing: "
                         "set them to 0")
    return film


def _speeds(speeds) -> np.ndarray:
    from lubedyn.units import UnitError, parse_quantity

    values = [speeds] if isinstance(speeds, (str, int, float, np.generic)) else list(np.asarray(speeds, dtype=object).ravel())
    out = []
    for k, v in enumerate(values):
        try:
            w = parse_quantity(v.item() if isinstance(v, np.generic) else v, "angular velocity")
        except UnitError as exc:
            raise InputError(f"speeds[{k}] = {v!r} {exc}") from None
        if not np.isfinite(w) or w <= 0.0:
            raise InputError(f"speeds[{k}] = {v!r}: a journal speed must be > 0 rad/s (finite)")
        out.append(w)
    if not out:
        raise InputError("speeds = []: give at least one journal speed (rad/s, or strings such as '3000 rpm')")
    return np.asarray(out)


def _load(load) -> np.ndarray | None:
    from lubedyn.units import UnitError, parse_quantity

    if load is None:
        return None
    scalar = isinstance(load, (str, int, float, np.generic))
    parts = [load] if scalar else list(load)
    if len(parts) not in (1, 2) or (not scalar and len(parts) != 2):
        raise InputError(f"load = {load!r}: give the static load on the journal as one magnitude [N] (along -y) "
                         "or a pair (W_x, W_y) [N]")
    try:
        values = [parse_quantity(v.item() if isinstance(v, np.generic) else v, "force") for v in parts]
    except UnitError as exc:
        raise InputError(f"load = {load!r} {exc}") from None
    W = np.array([0.0, -values[0]]) if scalar else np.asarray(values)
    if not np.all(np.isfinite(W)) or np.linalg.norm(W) == 0.0 or (scalar and values[0] <= 0.0):
        raise InputError(f"load = {load!r}: the static load must be finite and > 0 N (a scalar points along -y)")
    return W


# ---------------------------------------------------------------------------
# coefficients


def bearing_coefficients(source, speeds, *, load=None, smoke: bool = False, rtol: float = 1e-8,
                         max_iter: int = 50) -> BearingCoefficients:
    """Stiffness K (n, 2, 2) [N/m] and damping C (n, 2, 2) [N s/m] of a journal bearing at each speed.

    Parameters
    ----------
    source : case, str, Path or Film
        A film case with ``gap.type = "journal"`` (as :func:`lubedyn.load_case` returns it), its path or the
        name of a bundled case (``"journal_finite"``), or a :class:`~lubedyn.lubrication.Film` with a
        :class:`~lubedyn.lubrication.JournalBearing` gap.  Its mesh, element, lubricant, cavitation and ends
        are used as they are; its speed is replaced by each of ``speeds``.
    speeds : sequence
        Journal speeds, numbers in rad/s or strings with units (``"3000 rpm"``); each > 0.
    load : float, str, pair or None
        The static load on the journal [N] that the film carries: a magnitude along -y (``"2 kN"``, a
        weight) or (W_x, W_y).  At each speed the journal centre is moved to its equilibrium, F(q) + W = 0
        to ``rtol`` |W| (Newton steps q += K^-1 (F + W), each at most halfway to the bearing wall), and K
        and C are computed there.  ``None``: the centre stays where the case (or film) puts it.
    smoke : bool
        With a path or a case name: merge the case's ``[smoke]`` table (coarser mesh).
    rtol, max_iter
        Equilibrium tolerance (relative to |W|) and the largest number of film solves per speed.

    Returns
    -------
    BearingCoefficients
        ``speed`` [rad/s], ``K``, ``C``, the ``eccentricity`` and film ``force`` at each speed; named arrays by
        ``coef["Stiffness K[x,y] [N/m]"]``.

    Raises :class:`~lubedyn.lubrication.errors.InputError` for a source that is not a journal-bearing film or
    a bad speed or load, and :class:`~lubedyn.lubrication.errors.ConvergenceError` when no equilibrium is
    found (a load the film cannot carry at that speed drives the journal to the wall).

    Measured (tests/test_rotordynamics.py): a short bearing (L/D = 1/20, half-Sommerfeld) under a fixed load
    lands within 1 % of Ocvirk's eccentricity ratio and its K and C within a few per cent of Friswell et
    al.'s closed forms; the bundled ``journal_finite`` (L/D = 1) under the load of Raimondi and Boyd's
    S = 0.121 lands at their eccentricity 0.6 and attitude 50.6 deg.

    >>> import lubedyn
    >>> coef = lubedyn.bearing_coefficients("journal_finite", ["1500 rpm", "3000 rpm"], smoke=True)
    >>> coef.K.shape, coef.C.shape
    ((2, 2, 2), (2, 2, 2))
    >>> round(float(coef.K[1, 0, 0] / coef.K[0, 0, 0]), 9)   # centre held fixed: K grows like the speed
    2.0
    """
    from lubedyn.lubrication import JournalBearing

    film = _film_of(source, smoke=smoke)
    w = _speeds(speeds)
    W = _load(load)
    if not 0.0 < rtol < 1.0:
        raise InputError(f"rtol = {rtol!r} must be in (0, 1)")
    if int(max_iter) < 1:
        raise InputError(f"max_iter = {max_iter!r} must be >= 1")
    R, c = film.gap.radius, film.gap.clearance
    q = np.array([film.gap.eccentricity_x, film.gap.eccentricity_y], dtype=float)
    if W is not None:  # start displaced along the load at the case's eccentricity ratio (0.5 for a centred journal)
        eps0 = np.linalg.norm(q) / c or 0.5
        q = eps0 * c * W / np.linalg.norm(W)
    n = w.size
    K, C, E, F = np.zeros((n, 2, 2)), np.zeros((n, 2, 2)), np.zeros((n, 2)), np.zeros((n, 2))
    iterations = np.zeros(n, dtype=int)
    previous, found = None, []
    for k, speed in enumerate(w):
        for it in range(1, int(max_iter) + 1):
            at = film.with_(gap=JournalBearing(R, c, float(q[0]), float(q[1])), velocity_upper=(speed * R, 0.0))
            previous = at.solve(initial=previous)
            force = np.array([previous.mode_forces["x"], previous.mode_forces["y"]])
            names, Kk, Ck = previous.coefficients()
            residual = None if W is None else force + W
            if W is None or np.linalg.norm(residual) <= rtol * np.linalg.norm(W):
                break
            if it == int(max_iter):
                raise ConvergenceError(
                    f"bearing_coefficients: no equilibrium of the journal under load ({W[0]:.4g}, {W[1]:.4g}) N at "
                    f"{speed:.4g} rad/s in {max_iter} film solves (force residual {np.linalg.norm(residual) / np.linalg.norm(W):.3g} "
                    f"of the load at eccentricity ratio {np.linalg.norm(q) / c:.4g}); near 1 the film cannot carry "
                    "this load at this speed: raise the speed or lower the load")
            step = np.linalg.solve(Kk, residual)
            limit = 0.5 * (np.linalg.norm(q) + c)  # at most halfway to the wall
            while np.linalg.norm(q + step) > limit:
                step *= 0.5
            q = q + step
        K[k], C[k], E[k], F[k], iterations[k] = Kk, Ck, q, force, it
        for text in [previous.resolution_warning(), *previous.warnings]:
            if text:
                found.append(f"at {speed:.6g} rad/s: {text}")
                log.warning("%s", found[-1])
        log.info("bearing coefficients at %.6g rad/s: eccentricity ratio %.4g after %d film solve(s)",
                 speed, np.linalg.norm(q) / c, it)
    return BearingCoefficients(speed=w, K=K, C=C, eccentricity=E, force=F, clearance=float(c), load=W,
                               iterations=iterations, warnings=tuple(found))


# ---------------------------------------------------------------------------
# ROSS


def _import_ross():
    """``ross``, imported without its dependencies' REFPROP notice (ccp warns on import that the REFPROP
    library of gas properties is not configured: nothing a bearing element uses)."""
    try:
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", message=r"[\s\S]*REFPROP", category=UserWarning)
            import ross
    except ImportError:
        raise ImportError("to_ross needs ROSS: pip install 'lubedyn[ross]' (or pip install ross-rotordynamics)") from None
    except ValueError as exc:  # ROSS 2.3 fails with ValueError under plotly >= 7 (benchmarks/README.md)
        raise ImportError(f"import ross failed ({str(exc).splitlines()[0] if str(exc) else 'ValueError'}); "
                          "pip install 'lubedyn[ross]' pins plotly < 7, which ROSS 2.3 needs") from None
    return ross


def to_ross(coefficients: BearingCoefficients, n: int, **kwargs):
    """A ``ross.BearingElement`` at shaft node ``n`` with the coefficients of :func:`bearing_coefficients`.

    ``kxx, kxy, kyx, kyy`` = ``K[:, 0, 0], K[:, 0, 1], K[:, 1, 0], K[:, 1, 1]`` [N/m], ``cxx ... cyy`` likewise
    from ``C`` [N s/m], ``frequency`` = the speeds [rad/s] in increasing order.  ROSS evaluates a bearing at
    the rotor speed: between the given speeds it interpolates (linear or quadratic for two or three speeds;
    from four on scipy's UnivariateSpline with its default smoothing, which passes within about 1e-5 of the
    given values, measured 2.7e-6 in tests/test_rotordynamics.py) and outside them it extrapolates, so give
    speeds that cover the rotor's range.  ROSS works in SI, as lubedyn does.  The
    frames agree: ROSS's kxy is the force along x from a displacement along y, and its rotor turns from +x
    towards +y at positive speed, as the journal does here.  Other keywords (``tag``, ``n_link``, ``kzz``,
    ``scale_factor``, ...) go to ``ross.BearingElement`` as they are.

    Needs the optional extra ``ross`` (``pip install 'lubedyn[ross]'``).
    """
    if not isinstance(coefficients, BearingCoefficients):
        raise InputError(f"to_ross: coefficients is a {type(coefficients).__name__}; expected the BearingCoefficients "
                         "of lubedyn.bearing_coefficients")
    clash = sorted(set(kwargs) & {"kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy", "frequency"})
    if clash:
        raise InputError(f"to_ross: {', '.join(clash)} come from the coefficients; do not pass them as keywords")
    order = np.argsort(coefficients.speed, kind="stable")
    speed = coefficients.speed[order]
    if np.any(np.diff(speed) == 0.0):
        raise InputError(f"to_ross: the speeds {coefficients.speed.tolist()} rad/s repeat one; ROSS interpolates "
                         "over speed and needs each once")
    ross = _import_ross()
    K, C = coefficients.K[order], coefficients.C[order]
    entries = {f"k{a}{b}": K[:, i, j] for i, a in enumerate("xy") for j, b in enumerate("xy")}
    entries.update({f"c{a}{b}": C[:, i, j] for i, a in enumerate("xy") for j, b in enumerate("xy")})
    return ross.BearingElement(n=n, frequency=speed, **entries, **kwargs)
