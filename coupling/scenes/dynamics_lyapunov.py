"""Lyapunov analysis of a dynamics run: the end of the transient, co-rotating coordinates, Wolf's and
Rosenstein's largest exponents per direction of one ball, Benettin's spectrum of the whole bearing.

Part of the dynamics scene (:mod:`lubedyn.scenes.dynamics`, which calls :func:`_lyapunov_per_direction`
and :func:`_benettin` after a run and writes what they return into ``summary.json``)."""
from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass

import numpy as np
from lubedyn.dynamics.cageless import rhs
from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.dynamics.tangent_directions import BITS, BallDirections, TangentDirections
from lubedyn.dynamics.lyapunov import BenettinRun, WOLF_SCALE_MIN, assess_largest_lyapunov, autocorrelation_delay, false_nearest_neighbours, largest_lyapunov_rosenstein, mean_period, mutual_information_delay, lyapunov_spectrum, per_shaft_revolution, rosenstein_shortfall, wolf_shortfall

log = logging.getLogger("lubedyn.scenes.dynamics")


LYAPUNOV_SAMPLES = 8000  # Rosenstein's neighbour search and divergence average: decimate to at most this
WOLF_SAMPLES = 50_000  # Wolf's algorithm: one ball query per evolution step, so more samples are cheap
#: embedding dimension of the per-direction exponents (both methods)
LYAPUNOV_DIM = 6
#: surrogates of each per-direction Wolf exponent's noise test (lubedyn.dynamics.lyapunov.N_SURROGATES)
LYAPUNOV_SURROGATES = 19
#: spin-up ends when the inner ring speed is within this fraction of the rotor speed (and stays there)
SPIN_UP_TOLERANCE = 0.01
#: width [s] of the bins of the collision rate in :func:`transient_end`
COLLISION_BIN = 2e-3


def spin_up_end(t, ring_speed, rotor_speed=None, *, tolerance=SPIN_UP_TOLERANCE) -> tuple[float | None, str]:
    """End [s] of the spin-up after a drop, and the reason, as ``(t_spin, reason)``: the first time after
    which the inner ring speed stays within ``tolerance`` (1 %) of the rotor speed to the end of the record;
    the record's start with no rotor (``rotor_speed`` None: a steady or free scenario).  ``t_spin`` is None
    when the ring is not within the tolerance at the end of the record: the record ends inside the spin-up,
    and ``reason`` says so ("... still spinning up").  The rule of both Lyapunov analyses: the per-direction
    exponents are not computed then (:func:`transient_end`), the whole-system ones are "not converged"
    (:func:`whole_system_verdicts`)."""
    t = np.asarray(t, dtype=float)
    if rotor_speed is None:
        return float(t[0]), "no rotor to catch up with (inner ring driven or free)"
    off = np.abs(np.asarray(ring_speed) - np.asarray(rotor_speed)) > tolerance * np.abs(rotor_speed)
    if off[-1]:
        return None, (f"the inner ring is not within {tolerance:.0%} of the rotor speed at the end "
                      f"of the record ({t[-1]:.4g} s): still spinning up")
    last_off = np.flatnonzero(off)
    t_spin = float(t[last_off[-1] + 1]) if last_off.size else float(t[0])
    return t_spin, f"inner ring within {tolerance:.0%} of the rotor speed from {t_spin:.4g} s"


def transient_end(t, ring_speed, rotor_speed=None, collision_times=(), *, tolerance=SPIN_UP_TOLERANCE,
                  bin_width=COLLISION_BIN) -> tuple[float, str]:
    """Detected end [s] of the start-up transient of a run, and the reason, as ``(t_end, reason)``.

    (1) Spin-up (a drop, ``rotor_speed`` given): the first time after which the inner ring speed
    stays within ``tolerance`` (1 %) of the rotor speed to the end of the record; with no rotor
    (steady or free scenario) the record's start.  A ring never within the tolerance at the end
    gives the record's end (no steady part).  (2) Collisions: ``collision_times`` [s] counted in
    bins of ``bin_width`` (2 ms) from the spin-up end; the transient ends at the start of the first
    bin whose count is at most the median count of that bin and all later ones (the rate has dropped
    to its later median).  ``t_end`` is the later of (1) and (2)."""
    t = np.asarray(t, dtype=float)
    t_spin, why = spin_up_end(t, ring_speed, rotor_speed, tolerance=tolerance)  # (1), the shared rule
    if t_spin is None:
        return float(t[-1]), why
    times = np.asarray(collision_times, dtype=float)
    edges = np.arange(t_spin, t[-1] + 1e-12, bin_width)
    if edges.size < 3:
        return t_spin, f"{why}; record too short after it for {bin_width:g} s bins of the collision rate"
    counts = np.histogram(times, bins=edges)[0]
    later_median = np.array([np.median(counts[k:]) for k in range(counts.size)])
    k = int(np.argmax(counts <= later_median))
    t_coll = float(edges[k])
    return max(t_spin, t_coll), (f"{why}; collision rate down to the median of the later record "
                                 f"({later_median[k] / bin_width:.4g} 1/s, {bin_width:g} s bins) from {t_coll:.4g} s")


def co_rotating(t, xyz) -> tuple[np.ndarray, np.ndarray, str]:
    """A ball centre's track ``xyz`` (m, 3) [m] in co-rotating coordinates: ``(t_kept, coords, reason)``
    with coords (k, 3) = (radial r - mean r, tangential r_mean (psi - psi_mean), axial z) [m].

    r = sqrt(x^2 + y^2) and psi = unwrapped atan2(y, x) are the ball's distance from the bearing axis
    and its orbital angle; the mean train angle psi_mean is psi's centred moving average over one
    revolution of the ball about the axis (2 pi over its mean orbital speed over the record), so a
    ball orbiting at constant speed on a circle has zero co-rotating radial and tangential motion, and
    motion at the orbital frequency itself (an eccentric orbit) averages out of psi_mean.  Half a
    revolution at each end has no centred average and is dropped.  ``reason`` is "" or why no
    coordinates (a record shorter than two revolutions, or no orbital motion)."""
    t = np.asarray(t, dtype=float)
    x, y, z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    r = np.hypot(x, y)
    psi = np.unwrap(np.arctan2(y, x))
    span = float(t[-1] - t[0])
    rate = (psi[-1] - psi[0]) / span if span > 0 else 0.0
    if rate == 0.0:
        return t[:0], np.zeros((0, 3)), "the ball does not orbit"
    dt = float(t[1] - t[0])
    half = int(round(math.pi / abs(rate) / dt))
    if t.size < 2 * (2 * half + 1):
        return t[:0], np.zeros((0, 3)), (f"the record ({span:.4g} s) is shorter than two revolutions of the ball "
                                         f"about the axis ({2 * math.pi / abs(rate):.4g} s each)")
    w = 2 * half + 1
    c = np.concatenate([[0.0], np.cumsum(psi - psi[0])])
    psi_mean = (c[w:] - c[:-w]) / w + psi[0]
    keep = slice(half, t.size - half)
    r_mean = float(np.mean(r[keep]))
    coords = np.stack([r[keep] - r_mean, r_mean * (psi[keep] - psi_mean), z[keep]], axis=1)
    return t[keep], coords, ""


#: the co-rotating directions of :func:`co_rotating`
CO_ROTATING = ("radial", "tangential", "axial")


# ---------------------------------------------------------------------------- the record an exponent needs
#: the 10,000 rpm drop's largest Lyapunov exponent [1/s] and the shaft speed it was measured at [rad/s]:
#: lambda_1 = 54.1 +- 0.9 1/s over T = 4 s after the 20 ms transient, 4 members (docs/atlas/lyapunov.md,
#: benchmarks/results/paper_b/tangent_directions_10krpm.json); every direction's tangent-space exponent equals it
REFERENCE_EXPONENT, REFERENCE_SPEED = 54.1, 10_000 * 2 * math.pi / 60
#: boundary term a [-] of a finite-time exponent's spread sigma^2(T) = a^2 / T^2 + c^2 / T
#: (:func:`lubedyn.dynamics.tangent_directions.run_length`), the largest of the 7 directions' fits on the same
#: 4 members (5.7-7.6; the diffusive c fitted 0: the spread falls as T^-1.4 to T^-1.6 over 2-4 s)
BOUNDARY_TERM = 7.6


@dataclass(frozen=True)
class RecordNeed:
    """What a Lyapunov exponent needs of its record, and what the run has.

    A finite-time exponent over a record T differs from the exponent by the boundary term a / T (the log of a
    tangent vector's norm differs from its trend by a bounded function of the state), so a record resolves an
    exponent lambda -- can tell it positive beyond two uncertainties, the verdicts' rule -- only when
    a / T <= lambda / 2, i.e. lambda T >= 2 a: ``needed`` = 2 a / lambda [s].  lambda is the 10,000 rpm drop's
    measured lambda_1 (:data:`REFERENCE_EXPONENT`) scaled with the shaft speed (assumed: a constant exponent per
    revolution, 0.33 1/rev; measured at 10,000 rpm only), a the measured :data:`BOUNDARY_TERM`.  The README's
    main job (20 ms, window from 5 ms): lambda T = 0.8 against 15.2 needed (0.28 s at 10,000 rpm).
    The per-direction time-series estimates (Wolf, Rosenstein) estimate the same lambda_1 from less
    information than the tangent space, so they need at least the same record."""

    estimator: str  # what is estimated, e.g. "the whole-system spectrum"
    record: float  # [s] the record the estimator would average over
    start: float  # [s] where that record starts
    exponent: float  # [1/s] the exponent expected (measured, scaled with the speed)
    needed: float  # [s] the record it needs

    @property
    def resolves(self) -> bool:
        return self.record >= self.needed

    def note(self) -> str:
        """"not computed: the record of X resolves no exponent ...; needs Y" (the summary's ``, note``)."""
        lam = self.exponent
        return (f"not computed: the record of {self.estimator} ({self.record:.3g} s from {self.start:.4g} s: "
                f"lambda T = {lam * self.record:.2g} with lambda ~ {lam:.3g} 1/s) resolves no exponent; needs "
                f"{self.needed:.3g} s (lambda T >= {lam * self.needed:.3g}: the boundary term {BOUNDARY_TERM:g} / T "
                "at most half the exponent); run longer, or force it with analysis.force = true")

    def forced(self) -> str:
        """The note of an estimate computed on a record that does not resolve it (``analysis.force``)."""
        return ("forced (analysis.force = true): " + self.note().removeprefix("not computed: ")
                .split("; run longer")[0] + "; the values do not resolve an exponent")


def record_need(estimator: str, record: float, start: float, shaft_speed: float) -> RecordNeed:
    """:class:`RecordNeed` of ``estimator`` over ``record`` [s] from ``start`` [s] at ``shaft_speed`` [rad/s]."""
    lam = REFERENCE_EXPONENT * abs(float(shaft_speed)) / REFERENCE_SPEED
    needed = 2.0 * BOUNDARY_TERM / lam if lam > 0 else math.inf
    return RecordNeed(estimator, float(record), float(start), lam, needed)


def forced(case) -> bool:
    """Whether the case forces the estimators on records that do not resolve them (``analysis.force``)."""
    return bool(getattr(case.analysis, "force", False))


def _lyapunov_per_direction(case, t, centres, shaft_speed, *, ring_speed=None, rotor_speed=None,
                            collision_times=(), scale_min=0.0) -> dict:
    """Largest Lyapunov exponent per direction of ball ``analysis.ball``, from each coordinate's time
    series: inertial x, y, z and co-rotating radial, tangential, axial (:func:`co_rotating`).

    Paper B's Table 3 gives a "maximum Lyapunov exponent" for X, Y and Z, computed by "the
    orthogonalization method" after Wolf et al., with log2 (so bits per unit time) and no units;
    it does not say which coordinates or how an exponent per coordinate came out of a tangent-space
    method.  Here each coordinate's series gets:

    - Wolf et al.'s fixed-evolution-time exponent, "the paper's way" (log2, bits/s; also 1/s):
      ``"Wolf exponent, ball j <dir> [bits/s]"`` with ``[1/s]``, ``uncertainty [bits/s]`` (batch
      means over 10 blocks of evolution steps), ``convergence [-]`` (relative change of the running
      estimate over the last half), ``replacements [-]``, ``poor-angle fraction [-]`` and
      ``verdict``: the guarded verdict of :func:`lubedyn.dynamics.lyapunov.assess_largest_lyapunov`,
      "positive" or "not positive" only when the estimate is distinguishable from those of 19 IAAFT
      surrogates, agrees within 35 % over the settings grid (dim +-1, delay and evolve x 2/3, 3/2, and dim
      at least the false-neighbour minimum) and its 4 disjoint windows give a standard error of at most
      25 % of it; else the failed guard ("not distinguishable from its surrogates (linear noise): ...",
      "depends on the embedding settings (...)", "not converged (...)").  The guards' numbers:
      ``window uncertainty [bits/s]``, ``surrogates mean [bits/s]``, ``surrogate z [-]``, ``settings
      spread [-]``, ``false-neighbour dimension [-]``; ``verdict, record alone`` keeps the record's own
      verdict ("not resolved" when the batch-means uncertainty exceeds half the exponent or the running
      estimate changed by more than 20 % over the last half, :attr:`lubedyn.dynamics.lyapunov.WolfResult.resolved`,
      else "positive" / "not positive"), which does not tell noise from chaos.  Settings: delay at the
      first minimum of the mutual information (:func:`lubedyn.dynamics.lyapunov.mutual_information_delay`),
      embedding dimension the false-nearest-neighbour minimum (``LYAPUNOV_DIM`` where there is none up to
      10), evolution time = the delay,
      scale_max 0.1 of the coordinate's range, scale_min the larger of 1e-4 of the range and
      ``scale_min`` (the integration's resolution of a position), at most ``WOLF_SAMPLES`` samples.
      Measured on a synthetic ball whose axial motion is Lorenz x in time scaled by 100 (lambda_1 =
      90.6 1/s, 24,000 samples): 86.4 1/s, "positive"; its circular orbit's x "not positive"
      (``tests/test_dynamics_scene.py``).  The settings used before the guards (dim ``LYAPUNOV_DIM`` = 6,
      delay at the first zero of the autocorrelation, here 457 samples) gave 7.8 1/s (0.09 x), which the
      guards call "not distinguishable from its surrogates".
    - Rosenstein's exponent (1/s, the inertial directions only, as before):
      ``"Largest Lyapunov exponent, ball j <dir> [1/s]"`` etc.

    The record starts at the later of ``analysis.transient`` and the detected end of the transient
    (:func:`transient_end`, from ``ring_speed``, ``rotor_speed`` and ``collision_times`` when given);
    both are in the summary.  A record after the window start shorter than the one an exponent needs
    (:func:`record_need`: lambda T >= 2 a, 0.28 s at 10,000 rpm) computes none of them: every entry is None
    with the note "not computed: the record of ... resolves no exponent; needs ..." (also in
    ``"Lyapunov exponents per direction, note"``), unless ``analysis.force``.  A direction whose record is
    too short or that does not move (its range at
    most 1e-10 of the ball's distance from the axis, or ``scale_min``) gets ``None`` and a
    ``"..., note"`` saying why (an expected outcome of a short run, logged at INFO)."""
    j = case.analysis.ball
    given = float(case.analysis.transient)
    out = {"Lyapunov window start, given (analysis.transient) [s]": given}
    if ring_speed is not None:
        detected, reason = transient_end(t, ring_speed, rotor_speed, collision_times)
        out["Lyapunov window start, detected [s]"] = detected
        out["Lyapunov window start, detected, reason"] = reason
        given = max(given, detected)
    out["Lyapunov window start [s]"] = given
    keep = np.flatnonzero(t >= given)
    if keep.size < 3:
        note = (f"not computed: no record after the window start {given:.4g} s"
                + (f" ({out['Lyapunov window start, detected, reason']})" if ring_speed is not None else ""))
        out.update(_per_direction_not_computed(j, note))
        log.info("Lyapunov exponents of ball %d: %s", j, note)
        return out
    need = record_need(f"ball {j}'s per-direction exponents", float(t[-1] - given), given, shaft_speed)
    out["Lyapunov record needed, per direction [s]"] = need.needed
    if not need.resolves:
        if not forced(case):
            out.update(_per_direction_not_computed(j, need.note()))
            out["Lyapunov exponents per direction, note"] = need.note()
            log.info("Lyapunov exponents of ball %d: %s", j, need.note())
            return out
        out["Lyapunov exponents per direction, note"] = need.forced()
    out.update(_rosenstein_directions(j, t, keep, centres, shaft_speed))
    xyz = centres[keep, j, :]
    series = {axis: (t[keep], xyz[:, i]) for i, axis in enumerate("xyz")}
    t_co, co, why = co_rotating(t[keep], xyz) if keep.size > 2 else (t[:0], np.zeros((0, 3)), "no samples")
    for i, name in enumerate(CO_ROTATING):
        series[name] = (t_co, co[:, i]) if not why else why
    size = float(np.max(np.abs(xyz))) if xyz.size else 1.0
    for name, s in series.items():
        out.update(_wolf_direction(f"Wolf exponent, ball {j} {name}", s, size, scale_min, given))
    return out


def _per_direction_not_computed(j: int, note: str) -> dict:
    """Every Wolf and Rosenstein entry of ball ``j`` None (verdict "not computed") with ``note``."""
    out = {}
    for name in ("x", "y", "z") + CO_ROTATING:
        out[f"Wolf exponent, ball {j} {name} [bits/s]"] = None
        out[f"Wolf exponent, ball {j} {name} verdict"] = "not computed"
        out[f"Wolf exponent, ball {j} {name}, note"] = note
    for axis in "xyz":
        out[f"Largest Lyapunov exponent, ball {j} {axis} [1/s]"] = None
        out[f"Largest Lyapunov exponent, ball {j} {axis}, note"] = note
    return out


def _wolf_direction(key, series, size, scale_min, start) -> dict:
    """Summary entries of Wolf's exponent of one coordinate (see :func:`_lyapunov_per_direction`)."""
    out = {f"{key} [bits/s]": None, f"{key} verdict": "not computed"}  # the verdict key is always there
    if isinstance(series, str):
        out[f"{key}, note"] = f"not computed: {series}"
        return out
    tt, x = series
    if x.size < 3 or np.ptp(x) <= max(1e-10 * size, scale_min):  # round-off of r, psi; below resolution
        out[f"{key}, note"] = "not computed: the coordinate does not move"
        return out
    step = max(1, int(math.ceil(x.size / WOLF_SAMPLES)))
    x = x[::step]
    dt = float(tt[1] - tt[0]) * step
    # the guards' own choices: the first minimum of the mutual information, the false-neighbour dimension
    delay = mutual_information_delay(x)
    theiler = int(round(mean_period(x, dt) / dt))
    dim = false_nearest_neighbours(x, delay, theiler=theiler).minimum_dim or LYAPUNOV_DIM
    reason = wolf_shortfall(x, dt, dim=dim, delay=delay, evolve=delay)
    if reason:
        out[f"{key}, note"] = (f"not computed: the record after {start:.4g} s ({(x.size - 1) * dt:.4g} s) has "
                               f"{reason}; run longer")
        log.info("%s: %s", key, out[f"{key}, note"])
        return out
    try:
        a = assess_largest_lyapunov(x, dt, method="wolf", dim=dim, delay=delay, evolve=delay, theiler=theiler,
                                    n_surrogates=LYAPUNOV_SURROGATES, seed=0,
                                    scale_min=max(WOLF_SCALE_MIN * float(np.ptp(x)), scale_min))
    except DynamicsInputError as exc:
        out[f"{key}, note"] = f"not computed: {exc}"
        log.info("%s not computed: %s", key, exc)
        return out
    res = a.result
    bits = 1.0 / math.log(2.0)
    out[f"{key} [bits/s]"] = res.exponent_bits
    out[f"{key} [1/s]"] = res.exponent
    out[f"{key} uncertainty [bits/s]"] = res.uncertainty_bits
    out[f"{key} convergence [-]"] = res.convergence if np.isfinite(res.convergence) else None
    out[f"{key} replacements [-]"] = res.replacements
    out[f"{key} poor-angle fraction [-]"] = (res.poor_angle_fraction if np.isfinite(res.poor_angle_fraction)
                                             else None)
    out[f"{key} settings"] = (f"dim {dim}, delay = evolve = {delay} samples of {dt:.4g} s, "
                              f"{res.steps} steps, scales {res.settings['scale_min']:.3g}-"
                              f"{res.settings['scale_max']:.3g} m")
    # the guards (lubedyn.dynamics.lyapunov.assess_largest_lyapunov)
    out[f"{key} window uncertainty [bits/s]"] = a.uncertainty * bits if np.isfinite(a.uncertainty) else None
    good = a.surrogate_exponents[np.isfinite(a.surrogate_exponents)]
    out[f"{key} surrogates mean [bits/s]"] = float(np.mean(good)) * bits if good.size else None
    out[f"{key} surrogate z [-]"] = a.surrogate_z if np.isfinite(a.surrogate_z) else None
    out[f"{key} settings spread [-]"] = a.settings_spread if np.isfinite(a.settings_spread) else None
    out[f"{key} false-neighbour dimension [-]"] = a.false_neighbours.minimum_dim
    out[f"{key} verdict, record alone"] = res.verdict if res.resolved else "not resolved"
    out[f"{key} verdict"] = a.verdict
    return out


def _rosenstein_directions(j, t, keep, centres, shaft_speed) -> dict:
    """Rosenstein's largest exponent of ball ``j``'s inertial x, y, z after the window start."""
    out = {}
    # Rosenstein's neighbour search is O(n^2): decimate to at most LYAPUNOV_SAMPLES samples
    step = max(1, int(math.ceil(keep.size / LYAPUNOV_SAMPLES)))
    keep = keep[::step]
    dt = float(t[1] - t[0]) * step
    out["Lyapunov sample interval [s]"] = dt
    for i, axis in enumerate("xyz"):
        x = centres[keep, j, i]
        key = f"Largest Lyapunov exponent, ball {j} {axis}"
        out[f"{key} [1/s]"] = None
        if x.size < 3 or np.ptp(x) <= 1e-15 * max(1.0, float(np.max(np.abs(x)))):
            out[f"{key}, note"] = "not computed: the coordinate does not move"  # planar z
            continue
        delay = _delay(x)
        reason = rosenstein_shortfall(x, dt, dim=LYAPUNOV_DIM, delay=delay)
        if reason:
            out[f"{key}, note"] = (f"not computed: the record after the window start "
                                   f"({(x.size - 1) * dt:.4g} s) has {reason}; run longer")
            log.info("Lyapunov exponent of ball %d %s: %s", j, axis, out[f"{key}, note"])
            continue
        try:
            res = largest_lyapunov_rosenstein(x, dt, dim=LYAPUNOV_DIM, delay=delay)
        except DynamicsInputError as exc:  # no divergence rise to fit: say so in the summary, do not fail
            out[f"{key}, note"] = f"not computed: {exc}"
            log.warning("Lyapunov exponent of ball %d %s not computed: %s", j, axis, exc)
            continue
        out[f"{key} [1/s]"] = float(res.exponent)
        out[f"{key} [1/rev]"] = float(per_shaft_revolution(res.exponent, shaft_speed))
        # spread over neighbouring fit windows / level resolution (lubedyn.dynamics.lyapunov), and whether the
        # exponent is positive beyond it
        out[f"{key} uncertainty [1/s]"] = float(res.uncertainty)
        out[f"{key} verdict"] = res.verdict
    return out


def memory_states(model) -> np.ndarray:
    """Indices of the ball pairs' plastic-memory states in the state vector."""
    return np.array([i for i, (name, _) in enumerate(model.state_layout()) if name.endswith("plastic memory")],
                    dtype=np.int64)


def benettin_start(given: float, detected: float | None, t_end: float) -> float:
    """Where Benettin's window starts: the per-direction analysis' window start ``detected`` (the later
    of ``analysis.transient`` and the detected end of the transient), unless it is None or would leave
    less than half the record after ``given`` (a run that ends during the spin-up): then ``given``."""
    if detected is None or not (detected - given <= 0.5 * (t_end - given)):
        return given
    return max(detected, given)


def benettin_need(case, t, start, shaft_speed) -> RecordNeed:
    """:class:`RecordNeed` of the whole-system spectrum (and the tangent-space directions): its averaging
    time, 0.9 of the window from :func:`benettin_start` (the first tenth aligns the tangent vectors)."""
    t0 = float(t[int(np.searchsorted(t, benettin_start(float(case.analysis.transient), start, float(t[-1]))))])
    what = "the whole-system spectrum" + (" and its tangent-space directions" if case.analysis.tangent_directions
                                          else "")
    return record_need(what, 0.9 * (float(t[-1]) - t0), t0, shaft_speed)


def benettin_not_computed(case, need: RecordNeed) -> dict:
    """The summary entries of a whole-system spectrum whose record resolves no exponent: each of the
    ``analysis.lyapunov_exponents`` exponents None, verdict "not computed", and the note
    (:meth:`RecordNeed.note`) on the spectrum."""
    note = need.note()
    out = {"Lyapunov exponents, whole system, note": note}
    for i in range(case.analysis.lyapunov_exponents):
        key = f"Lyapunov exponent {i + 1}, whole system (Benettin)"
        out[f"{key} [1/s]"] = None
        out[f"{key} verdict"] = "not computed"
        out[f"{key}, note"] = note
    if case.analysis.tangent_directions:
        out["Tangent-space exponents, note"] = note
    log.info("whole-system Lyapunov exponents: %s", note)
    return out


def _benettin(case, model, t, Y, shaft_speed, start=None, progress=None) -> dict:
    """The k largest Lyapunov exponents of the whole bearing (Benettin, RK4 on
    state and tangent vectors with QR re-orthonormalisation every 50 steps,
    forward-difference tangent dynamics on the state scaled by
    :meth:`CagelessBearing.state_scales`), over the rest of the run from ``start`` (the
    per-direction analysis' window start: the later of ``analysis.transient`` and the detected end of
    the transient), or from ``analysis.transient`` when ``start`` is None or would leave less than half
    the record after it; the summary gives the start used.

    The ball pairs' plastic-memory states are left out of the tangent space
    (``frozen``): their rate switches from the approach rate to 0 when the
    pair leaves plastic loading, so a forward difference across that switch is
    of order 1/eps and stretches the tangent vectors by e^10-e^30 in single
    orthonormalisation intervals, depending on the step (measured on the
    10 krpm drop over 6 ms: 14,700 1/s at dt = 0.3/omega_max, 44,400 1/s at
    0.15/omega_max; with the memory frozen the step dependence goes, see
    tests/test_bearing_lyapunov.py).  The exponents are those of the mechanical
    states with the memory shared by the reference and perturbed
    trajectories.  Collisions stay non-smooth (contact onset, film rupture),
    so the finite-time exponents converge slowly; the summary gives the
    relative change of the largest one over the second half of the window as
    a convergence measure.  Each exponent's verdict is :func:`whole_system_verdicts`': "positive" only
    beyond two uncertainties and with its running estimate settled (moved at most 20 % over the second
    half, :data:`lubedyn.dynamics.lyapunov.SETTLED`), else "not converged (moved X % over the second half)"; and
    "not converged (... still spinning up)" for every exponent of a record that ends inside the spin-up
    (:func:`spin_up_end`, the rule by which the per-direction exponents are not computed).
    ``progress(fraction)`` is called as the spectrum advances (100 kernel
    calls, bit-identical to one: :func:`lubedyn.dynamics.lyapunov.lyapunov_spectrum`'s ``n_chunks``).

    With ``analysis.tangent_directions`` the same run's first tangent vector is projected on every ball's
    radial, tangential and axial position directions after each QR (:mod:`lubedyn.dynamics.tangent_directions`)
    and :func:`tangent_direction_entries` joins the summary (``lyapunov_exponents = 0`` then runs one vector
    and writes only those)."""
    k = case.analysis.lyapunov_exponents
    i0 = int(np.searchsorted(t, benettin_start(float(case.analysis.transient), start, float(t[-1]))))
    window = float(t[-1] - t[i0])
    scale = model.state_scales()
    omega = model.omega_max(Y[i0])
    dt = DT_FACTOR / omega
    t_c = time.perf_counter()
    # the first tenth of the window aligns the random initial tangent vectors (its stretching is discarded)
    directions = None
    if case.analysis.tangent_directions:
        # the same run, its first tangent vector projected on the balls' directions after every QR: the
        # whole-system exponents are the bits lyapunov_spectrum gives (chunking does not change them)
        run = BenettinRun(rhs, Y[i0], model.args(), scale=scale, dt=dt, t_transient=0.1 * window,
                          t_orth=ORTH_STEPS * dt, n_exponents=max(k, 1), omega_max=omega, t0=float(t[i0]),
                          frozen=memory_states(model))
        td = TangentDirections(run, BallDirections(model.state_layout(), scale, inertial=True))
        n_orth = max(1, int(math.ceil(0.9 * window / run.interval)))
        td.advance(n_intervals=n_orth, progress=progress)
        res, directions = run.spectrum(), td.result()
    else:
        res = lyapunov_spectrum(rhs, Y[i0], model.args(), scale=scale, dt=dt, t_total=0.9 * window,
                                t_transient=0.1 * window, t_orth=ORTH_STEPS * dt, n_exponents=k, omega_max=omega,
                                t0=float(t[i0]), frozen=memory_states(model), n_chunks=100, progress=progress)
    out = {"Benettin window start [s]": float(t[i0]), "Benettin window [s]": window, "Benettin averaging time [s]": 0.9 * window,
           "Benettin time [s]": time.perf_counter() - t_c}
    if directions is not None:
        out.update(tangent_direction_entries(directions, case.analysis.ball))
    if not k:
        return out
    verdicts = whole_system_verdicts(res, record_spin_up(case, model, t, Y))
    for i, (lam, u, verdict) in enumerate(zip(res.exponents, res.uncertainty, verdicts)):
        out[f"Lyapunov exponent {i + 1}, whole system (Benettin) [1/s]"] = float(lam)
        out[f"Lyapunov exponent {i + 1}, whole system (Benettin) [1/rev]"] = float(per_shaft_revolution(lam,
                                                                                                       shaft_speed))
        # batch means over 10 blocks of the averaging time (lubedyn.dynamics.lyapunov.batch_means_uncertainty)
        out[f"Lyapunov exponent {i + 1}, whole system (Benettin) uncertainty [1/s]"] = (
            float(u) if np.isfinite(u) else None)
        out[f"Lyapunov exponent {i + 1}, whole system (Benettin) verdict"] = verdict
    running = res.running[:, 0]
    half = running[len(running) // 2]
    out["Benettin largest exponent, change over the second half [-]"] = (
        float(abs(running[-1] - half) / abs(running[-1])) if running[-1] else None)
    return out


def record_spin_up(case, model, t, Y) -> str:
    """Why the record of a drop ends inside the spin-up (:func:`spin_up_end` on the inner ring and rotor
    speeds of the states ``Y``), or "" (it does not, or the scenario has no rotor)."""
    if case.operating.scenario != "drop":
        return ""
    names = [name for name, _ in model.state_layout()]
    t_spin, why = spin_up_end(t, Y[:, names.index("Inner ring speed")], Y[:, names.index("Rotor speed")])
    return why if t_spin is None else ""


def whole_system_verdicts(spectrum, spin_up: str = "") -> list[str]:
    """Verdicts of the whole-system exponents of ``spectrum`` (a :class:`lubedyn.dynamics.lyapunov.LyapunovSpectrum`):
    each exponent's own (:func:`lubedyn.dynamics.lyapunov.verdict`: "positive" beyond two uncertainties once its
    running estimate has settled, "not positive", or "not converged (moved X % over the second half)"),
    except that a record ending inside the spin-up (``spin_up``: the reason :func:`record_spin_up` gives)
    makes every one "not converged (<reason>)": finite-time exponents of the transient say nothing about
    the motion the bearing settles into, and the per-direction analysis is not computed there."""
    if spin_up:
        return [f"not converged ({spin_up})"] * len(spectrum.exponents)
    return list(spectrum.verdicts)


def _delay(x) -> int:
    """Embedding delay: first zero crossing of the autocorrelation (at least 1,
    :func:`lubedyn.dynamics.lyapunov.autocorrelation_delay`)."""
    return autocorrelation_delay(x)


#: Benettin's step and orthonormalisation interval on the bearing (both analyses): dt = DT_FACTOR / omega_max,
#: t_orth = ORTH_STEPS dt
DT_FACTOR = 0.3
ORTH_STEPS = 50


def bearing_tangent_directions(model, y0, t0=0.0, *, t_transient=0.0) -> TangentDirections:
    """Per-direction exponents of the cage-less bearing from ``y0`` at ``t0`` [s]
    (:class:`lubedyn.dynamics.tangent_directions.TangentDirections`): the first tangent vector of Benettin's
    method with :func:`_benettin`'s settings (forward differences on the scaled state, dt = 0.3 / omega_max,
    QR every 50 steps, the plastic memory frozen), projected after each QR on every ball's radial, tangential
    and axial position directions; ``t_transient`` [s] aligns it first.  Advance it with
    ``.advance(seconds)``; ``.save``/``.load`` resume it."""
    scale = model.state_scales()
    omega = model.omega_max(y0)
    dt = DT_FACTOR / omega
    run = BenettinRun(rhs, y0, model.args(), scale=scale, dt=dt, t_orth=ORTH_STEPS * dt, t_transient=t_transient,
                      n_exponents=1, omega_max=omega, t0=float(t0), frozen=memory_states(model))
    return TangentDirections(run, BallDirections(model.state_layout(), scale))


def tangent_direction_entries(res, ball: int) -> dict:
    """Summary entries of per-direction tangent-space exponents ``res``
    (:class:`lubedyn.dynamics.tangent_directions.DirectionExponents`) for ball ``ball`` and for all balls:
    ``"Tangent-space exponent, ball j radial [1/s]"`` and ``[bits/s]`` (radial, tangential, axial, and x, y
    when the projector gives them), ``lambda T [-]``, ``uncertainty
    [1/s]`` (batch means along the record), ``share [-]`` (the first Lyapunov vector's share in the
    direction); the first vector's own exponent (the whole system's lambda_1 over the same record) and the
    bound the largest per-direction value must lie in (module docstring of
    :mod:`lubedyn.dynamics.tangent_directions`)."""
    T = res.averaging_time
    out = {"Tangent-space averaging time [s]": T,
           "Tangent-space largest exponent, first vector [1/s]": res.largest,
           "Tangent-space largest exponent, first vector [bits/s]": res.largest * BITS}
    low, high = res.max_bound
    out["Tangent-space largest direction exponent, bound from the first vector [1/s]"] = [low, high]
    u = res.uncertainty
    for i, name in enumerate(res.names):
        if not (name.startswith(f"ball {ball} ") or name.endswith("(all balls)")):
            continue
        key = f"Tangent-space exponent, {name}"
        lam = float(res.exponents[i])
        finite = math.isfinite(lam)
        out[f"{key} [1/s]"] = lam if finite else None
        out[f"{key} [bits/s]"] = lam * BITS if finite else None
        out[f"{key} lambda T [-]"] = lam * T if finite else None
        out[f"{key} uncertainty [1/s]"] = float(u[i]) if np.isfinite(u[i]) else None
        out[f"{key} share [-]"] = float(res.share[i])
    return out
