r"""Per-direction Lyapunov exponents from the model's own tangent space.

Paper B (Zhang et al., Symmetry 2024, 16, 741, sec. 3.3, eqs. 24-27, Table 3) gives a "maximum Lyapunov
exponent" for the X, Y and Z directions of the balls, computed by "the orthogonalization method"
(Gram-Schmidt re-orthonormalisation of tangent vectors, after Wolf et al.), lambda = (1/(s tau)) sum log2 p_i.
A tangent-space method has one largest exponent for the whole system; the closest reading of an exponent
"per direction" that such a method gives is the growth rate of the largest tangent vector *seen in that
direction*, which is what this module computes.

Definition
----------
Benettin's method (:class:`lubedyn.dynamics.lyapunov.BenettinRun`, the project's one integrator of the
variational equations: RK4 on state and tangent vectors, QR every ``t_orth``) carries the first tangent
vector v.  Gram-Schmidt never mixes the other vectors into the first one: after each QR it is only
rescaled to unit length, so between the start of the averaging (t_0, after the transient that aligns it)
and t_0 + T it is the linearised flow applied to its start, v(T) = D Phi(t_0 + T, t_0) v(t_0), up to a
positive factor that the log sums record.  With P_d the orthogonal projector onto direction d of the
state (for a ball: the component of its *position* perturbation along its radial unit vector e_r = (x, y,
0)/r, tangential e_t = e_z x e_r, or axial e_z, in the co-rotating frame that the ball's own position
gives at that instant), the per-direction exponent is

    lambda_d(T) = (1/T) sum_k log(|P_d v_{k+1}| / |P_d v_k|) = (1/T) log(|P_d v(T)| / |P_d v(t_0)|)   [1/s]

where v_{k+1} is the evolved, not yet normalised vector at the end of interval k and v_k the normalised
one at its start (each projector at its own instant, so the sum telescopes).  Writing q = v / |v| for the
unit first vector and p_d = |P_d q|, this is

    lambda_d(T) = lambda_1(T) + (1/T) [log p_d(t_0 + T) - log p_d(t_0)]                          (1)

with lambda_1(T) the first vector's own finite-time exponent (the whole system's largest one).  What follows
from (1), and what the tests check:

* **Coupled directions give lambda_1.**  Where the first Lyapunov vector keeps a share of direction d
  (p_d does not decay exponentially), lambda_d -> lambda_1 as T grows, with a boundary term of order
  1/T.  On Lorenz, x, y and z each give 0.906 1/s.  In an irreducible system every direction does,
  which is why the per-direction values of a tangent-space method cannot be different from each other in
  the limit: their differences at finite T are the boundary term, not physics.  What does tell the
  directions apart is the **share** of the first Lyapunov vector in each direction, the time mean of
  p_d^2 / p_S^2 over the record (S: all position directions of all balls; the shares of radial, tangential
  and axial sum to 1): where the instability lives.
* **Decoupled blocks give their own exponent.**  In a direct product (Lorenz in three coordinates, a linear
  system dx/dt = A x in two more) the first vector's block components evolve with the block's own
  linearised flow, so lambda_d is the largest exponent of the block: 0.906 1/s in Lorenz's block and
  A's rate (-0.5 1/s for a rotation decaying at 0.5 1/s) in the linear one, independently of this code.
* **Maximum.**  If the directions d = 1..D split the subspace S orthogonally, sum_d p_d^2 = p_S^2, so
  max_d p_d >= p_S / sqrt(D) and, with p_d <= 1,

      lambda_1(T) + (1/T) log(p_S(t_0 + T) / sqrt(D))  <=  max_d lambda_d(T)  <=  lambda_1(T) - (1/T) min_d log p_d(t_0)

  i.e. the largest per-direction exponent is the whole system's lambda_1 within (1/T) times the logs of the
  shares at the record's ends (:attr:`DirectionExponents.max_bound`).

Why this is the closest reading of paper B.  Its eqs. 24-27 are Wolf et al.'s: the log2 growth of the
principal axes of an evolved ellipsoid after Gram-Schmidt, per unit time; the first axis is v above.
Projecting that axis onto X, Y, Z (or the co-rotating radial, tangential, axial) is the only way the
orthogonalisation itself gives a number per direction; (1) then says what that number is.  Exponents are
in 1/s and in bits/s (divided by ln 2, paper B's log2).

Smoothed contact laws need no saltation matrices
------------------------------------------------
A saltation matrix corrects the variational equation where the state jumps (an impact law with
restitution) or the vector field jumps across a switching surface (Filippov systems; Leine & Nijmeijer,
*Dynamics and bifurcations of non-smooth mechanical systems*, 2004, ch. 3): then D Phi jumps by
S = I + (f+ - f-) n^T / (n^T f-).  The cage-less model has neither: its state is continuous, and its
forces are continuous functions of the state (:mod:`lubedyn.dynamics.contacts`): the Hertz force K
delta^1.5 and its Hunt-Crossley damping K delta^1.5 alpha d(delta)/dt vanish at first touch, the clip at
zero (no adhesion) leaves the force continuous with a kink, the ball-ball film force vanishes continuously
at its cut and during separation, the locked film is continuous in force across the lock, the Thornton
phases switch the force's derivative only, traction is a tanh, slot edges are smooth steps.  So
f+ = f- on every switching surface and S = I: a kink makes the Jacobian jump by a bounded amount, and the
variational equation integrates a bounded, piecewise continuous J without a correction.  The one state
whose *rate* jumps, the pairs' plastic memory (its rate switches from the approach rate to 0), is left
out of the tangent space (``frozen``, :func:`lubedyn.scenes.dynamics_lyapunov.memory_states`).

Measured (``tests/test_tangent_directions.py::test_tangent_follows_the_secant_across_contact_onsets``; the
project has no analytic jvp of the bearing, so the check is against the nonlinear flow itself, which is
what a saltation term would correct): from the 10,000 rpm drop's start with ball 0 sent at 0.3 m/s towards
ball 1 (20 um away), over 0.4 ms in which the pair's film contact starts and ends and inner-race contacts
start, the kernel's tangent vector (forward differences) and the secant (y(y0 + eps v0) - y(y0)) / eps of
two trajectories of the same RK4 differ by 0.102, 0.0137 and 0.0022 (relative) at eps = 1e-2, 1e-3, 1e-4
of the scale: first order in eps, as a linearisation without a missing jump must (a missing saltation term
leaves an O(1) difference that does not fall with eps).  At 1 m/s (100 um): 0.146, 0.028, 0.0042.

Where the frozen memory shows: sent at 2 m/s the pair goes through the elastic-plastic phase and recovery
(Thornton), and the difference stops falling with eps: 0.082, 0.079, 0.079 at eps = 1e-3, 1e-4, 1e-5.  It
stays at 0.0007 through the film phase and the elastic-plastic loading and grows from 0.002 to 0.08 from
the turn-around into the recovery on, where the reference's and the perturbed pair's plastic memories
(which the tangent space does not carry) differ.  So after a plastic collision the tangent dynamics are
those of the frozen-memory system, by 8 % per such collision here, not the secant's; the exponents are the
mechanical states' with the memory shared (as :func:`lubedyn.scenes.dynamics_lyapunov._benettin` says).

Convergence in T and run length
-------------------------------
Records are advanced in chunks (:meth:`TangentDirections.advance`) and can be saved and resumed
(:meth:`TangentDirections.save`, :meth:`TangentDirections.load`) bit for bit; ``lambda T`` is reported
with every exponent (a positive exponent means something only when lambda T is well above the O(1)
boundary term of (1)).  The spread of a finite-time exponent over independent members (different initial
states: members that differ only in their initial tangent vectors align onto the same Lyapunov vector
during the transient and their spread says nothing) is sigma^2(T) = a^2 / T^2 + c^2 / T: a boundary term
(the log of a tangent vector's norm differs from its trend by a bounded function of the state) and the
diffusion of a mixing system's time average, which wins at long T.  :func:`run_length` takes the rule
from the end of a record: all of sigma(T_end)^2 T_end counted as diffusive, the record one member needs for
a relative standard deviation r is T_r = sigma(T_end)^2 T_end / (r lambda)^2 (T_r / M for the mean of M
members), an upper bound under the model.  Measured on Lorenz (16 members from different points of the
attractor, ``tests/test_tangent_directions.py::test_run_length_rule_bounds_the_spread_further_on``): the
spread falls as T^-0.75 to T^-1 up to 3,000 s (the boundary term still counts); the rule's prediction
sigma(T_end) sqrt(T_end / T) from T_end = 300 s matches the spread at 2,000 s (0.0026 against 0.0027 1/s,
16 members), and from 400 s it overestimates it at 3,000 s by 1.4-1.8 (16 and 32 members); Lorenz needs
T_r = 7-16 s for r = 5 %.
On the 10,000 rpm drop: docs/atlas/lyapunov.md ("Per-direction exponents from the tangent space").
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

from .errors import DynamicsInputError
from .lyapunov import BenettinRun, batch_means_uncertainty

logger = logging.getLogger(__name__)

#: a ball's position directions in the frame its own position gives (radial, tangential = axial x radial, axial)
CO_ROTATING = ("radial", "tangential", "axial")
#: bits per e-fold (paper B's log2)
BITS = 1.0 / math.log(2.0)


def _norm(x, axis=None):
    """Euclidean norm that neither underflows nor overflows in the squares (a direction the first vector has
    left keeps components of 1e-200 and below): max |x| sqrt(sum (x / max |x|)^2)."""
    x = np.asarray(x, dtype=float)
    m = np.max(np.abs(x), axis=axis, keepdims=True)
    safe = np.where(m > 0, m, 1.0)
    out = np.squeeze(m * np.sqrt(np.sum((x / safe) ** 2, axis=axis, keepdims=True)), axis=axis)
    return out if out.ndim else float(out)


class BallDirections:
    """Projector of a tangent vector on every ball's co-rotating position directions, built from a model's
    ``state_layout()`` names ("Ball j x", "Ball j y", "Ball j z" of the 6-DOF balls; "Ball j radial position"
    and "Ball j orbital angle" of planar ones, which have no axial direction).

    ``self(y, v)`` returns the norms |P_d v| of the tangent vector ``v`` at the state ``y`` (``v`` in the
    coordinates z = y / ``scale`` of :class:`lubedyn.dynamics.lyapunov.BenettinRun`; a planar ball's angle
    perturbation is converted to the length scale of its radius, r dphi s_phi / s_r): per ball j its radial e_r . dp, tangential e_t . dp (e_r = (x, y, 0) / r from the ball's own
    position, e_t = e_z x e_r) and axial dp_z components, then for each direction the norm over all balls,
    named by :attr:`names` ("ball 0 radial", ..., "radial (all balls)", ...).  Planar: dr and r dphi.
    ``inertial``: also the inertial x and y components (paper B's X, Y; its Z is axial), "ball j x", ...,
    "x (all balls)", "y (all balls)" after those (not part of :attr:`complete`)."""

    def __init__(self, layout, scale=None, *, inertial=False):
        names = [name for name, _ in layout]
        scale = np.ones(len(names)) if scale is None else np.asarray(scale, dtype=float)
        self.balls = sorted({int(n.split()[1]) for n in names if n.startswith("Ball ")})
        if not self.balls:
            raise DynamicsInputError("the state layout has no 'Ball j ...' entries: no ball directions to project on")
        if f"Ball {self.balls[0]} x" in names:
            self.planar = False
            self.index = np.array([[names.index(f"Ball {j} {c}") for c in "xyz"] for j in self.balls])
            self.directions = CO_ROTATING
        else:
            self.planar = True
            self.index = np.array([[names.index(f"Ball {j} {c}") for c in ("radial position", "orbital angle")]
                                   for j in self.balls])
            self.directions = CO_ROTATING[:2]
            self.angle_factor = scale[self.index[:, 1]] / scale[self.index[:, 0]]
        self.check_scale(scale)
        self.inertial = bool(inertial) and not self.planar
        self.names = tuple(f"ball {j} {d}" for j in self.balls for d in self.directions) + tuple(
            f"{d} (all balls)" for d in self.directions)
        if self.inertial:  # paper B's X and Y (its Z is the axial direction)
            self.names += tuple(f"ball {j} {d}" for j in self.balls for d in "xy") + ("x (all balls)", "y (all balls)")

    def components(self, y, v) -> np.ndarray:
        """Signed components (balls, directions) of ``v``'s ball positions along the co-rotating directions."""
        if self.planar:
            r = y[self.index[:, 0]]
            return np.stack([v[self.index[:, 0]], r * self.angle_factor * v[self.index[:, 1]]], axis=1)
        p, dp = y[self.index], v[self.index]
        r = np.hypot(p[:, 0], p[:, 1])
        er = p[:, :2] / r[:, None]
        radial = er[:, 0] * dp[:, 0] + er[:, 1] * dp[:, 1]
        tangential = -er[:, 1] * dp[:, 0] + er[:, 0] * dp[:, 1]
        return np.stack([radial, tangential, dp[:, 2]], axis=1)

    def check_scale(self, scale) -> None:
        """Refuse a state scaling that differs between a ball's position entries (the co-rotating rotation
        of a scaled tangent vector would then not be the physical one)."""
        if self.planar:  # the angle factor was made with the projector's scale
            if not np.allclose(np.asarray(scale)[self.index[:, 1]] / np.asarray(scale)[self.index[:, 0]],
                               self.angle_factor, rtol=1e-12, atol=0.0):
                raise DynamicsInputError("scale: the run's scale of a planar ball's radius and angle differs "
                                         "from the projector's (give BallDirections the run's scale)")
            return
        s = np.asarray(scale)[self.index]
        if not np.all(s == s[:, :1]):
            raise DynamicsInputError("scale: a ball's position entries must share one scale to be projected "
                                     "on its co-rotating directions")

    def __call__(self, y, v) -> np.ndarray:
        c = self.components(y, v)
        out = [np.abs(c).ravel(), _norm(c, axis=0)]
        if self.inertial:
            dp = v[self.index[:, :2]]
            out += [np.abs(dp).ravel(), _norm(dp, axis=0)]
        return np.concatenate(out)

    @property
    def complete(self) -> np.ndarray:
        """Indices of the directions that split the balls' position subspace S orthogonally (per ball),
        for :attr:`DirectionExponents.max_bound` and the shares."""
        return np.arange(len(self.balls) * len(self.directions))


class CoordinateDirections:
    """Projector on single state entries (e.g. Lorenz x, y, z) and on groups of them (a block's norm):
    ``groups`` {name: indices}.  The groups listed in ``complete`` split S orthogonally."""

    def __init__(self, groups: dict, complete=None):
        self.names = tuple(groups)
        self.groups = [np.atleast_1d(np.asarray(g, dtype=np.int64)) for g in groups.values()]
        self.complete = np.arange(len(self.names)) if complete is None else np.asarray(complete, dtype=np.int64)

    def __call__(self, y, v) -> np.ndarray:
        return np.array([_norm(v[g]) for g in self.groups])


@dataclass(frozen=True)
class DirectionExponents:
    """Per-direction exponents of one record (see the module docstring for the definition).

    Attributes
    ----------
    names : tuple of str
        Directions.
    exponents : ndarray (D,)
        lambda_d [1/s] over the averaging time T.
    largest : float
        The first tangent vector's exponent lambda_1 [1/s] over the same record (the whole system's).
    times : ndarray (q,)
        Averaging times [s] after each interval.
    running : ndarray (q, D)
        Running lambda_d [1/s]; ``running_largest`` (q,) lambda_1's.
    share : ndarray (D,)
        Time mean over the intervals of p_d^2 / p_S^2: the first Lyapunov vector's share in each direction
        (per ball; an "all balls" direction: the sum over balls).
    log_p0, log_p : ndarray (D,)
        log p_d at the start and at the end of the averaging; ``log_pS`` (2,) log p_S at both.
    complete : ndarray
        Indices of the directions that split S (for :attr:`max_bound`).
    """

    names: tuple
    exponents: np.ndarray
    largest: float
    times: np.ndarray
    running: np.ndarray
    running_largest: np.ndarray
    share: np.ndarray
    log_p0: np.ndarray
    log_p: np.ndarray
    log_pS: np.ndarray
    complete: np.ndarray

    @property
    def averaging_time(self) -> float:
        """T [s]."""
        return float(self.times[-1]) if self.times.size else 0.0

    @property
    def exponents_bits(self) -> np.ndarray:
        """lambda_d [bits/s] (paper B's log2)."""
        return self.exponents * BITS

    @property
    def lambda_T(self) -> np.ndarray:
        """lambda_d T [-]: the e-folds the direction's share of the first vector grew over the record (a
        positive exponent is resolved only when it is well above the O(1) boundary term of (1))."""
        return self.exponents * self.averaging_time

    @property
    def uncertainty(self) -> np.ndarray:
        """Batch-means standard error [1/s] of each lambda_d along the record
        (:func:`lubedyn.dynamics.lyapunov.batch_means_uncertainty`); the member spread is :func:`run_length`'s."""
        return batch_means_uncertainty(self.times, self.running)

    @property
    def max_bound(self) -> tuple[float, float]:
        """``(low, high)`` [1/s] that max_d lambda_d over the complete directions must lie in: lambda_1 +
        (1/T) log(p_S(T)/sqrt(D)) and lambda_1 - (1/T) min_d log p_d(t_0) (module docstring, "Maximum")."""
        T = self.averaging_time
        D = self.complete.size
        low = self.largest + (self.log_pS[1] - 0.5 * math.log(D)) / T
        high = self.largest - float(np.min(self.log_p0[self.complete])) / T
        return low, high


class TangentDirections:
    """A Benettin run (:class:`lubedyn.dynamics.lyapunov.BenettinRun`) whose first tangent vector is projected
    on ``projector``'s directions after every re-orthonormalisation.  ``advance(t)`` runs the run's transient
    first (its stretching is discarded and the projections start after it), then ``t`` seconds more;
    :meth:`result` gives the exponents so far; :meth:`save` / :meth:`load` stop and resume it bit for bit."""

    def __init__(self, run: BenettinRun, projector):
        self.run = run
        self.projector = projector
        if hasattr(projector, "check_scale"):
            projector.check_scale(run.scale)  # the projector's scale must be the run's
        self.names = tuple(projector.names)
        self.log_p0 = None
        self.log_pS0 = None
        self._log_p: list = []
        self._share_sum = np.zeros(len(self.names))
        self._log_pS = np.nan

    def _project(self):
        """p_d and p_S of the unit first tangent vector, in the scaled coordinates the kernel normalises in
        (a ball's x, y, z share one scale, :meth:`BallDirections.check_scale`, so its rotation into the
        co-rotating frame is the same there): p_d <= 1 (an orthogonal projection; not for a planar ball's
        r dphi), and (1) holds with the kernel's own log sums."""
        run = self.run
        p = np.asarray(self.projector(run.y, run.V[0]), dtype=float)
        p_S = _norm(p[self.projector.complete])
        return p, p_S

    def _observe(self, run):
        if run.q < run.n_transient:
            return
        p, p_S = self._project()
        if self.log_p0 is None:  # the transient was empty: the start was observed before the first interval
            raise AssertionError("TangentDirections: start of the averaging not recorded")
        with np.errstate(divide="ignore"):
            self._log_p.append(np.log(p))
        self._share_sum += (p / p_S) ** 2 if p_S > 0 else np.nan
        self._log_pS = math.log(p_S) if p_S > 0 else -math.inf

    def advance(self, t_total=None, *, n_intervals=None, progress=None) -> "TangentDirections":
        """Run the remaining transient, then ``t_total`` seconds (whole intervals, at least one) or
        ``n_intervals`` intervals."""
        run = self.run
        if run.q < run.n_transient:
            run.advance(run.n_transient - run.q, n_chunks=max(1, (run.n_transient - run.q) // 100))
        if self.log_p0 is None:
            p, p_S = self._project()
            with np.errstate(divide="ignore"):
                self.log_p0, self.log_pS0 = np.log(p), math.log(p_S)
        if n_intervals is not None:
            n = int(n_intervals)
            if n < 1:
                raise DynamicsInputError(f"n_intervals = {n_intervals!r} must be >= 1")
        elif t_total is None or not (float(t_total) > 0 and math.isfinite(float(t_total))):
            raise DynamicsInputError(f"t_total = {t_total!r} must be a finite number > 0")
        else:
            n = max(1, int(math.ceil(float(t_total) / run.interval - 1e-9)))
        run.advance(n, progress=progress, observe=self._observe)
        return self

    def result(self) -> DirectionExponents:
        run = self.run
        q = len(self._log_p)
        if q == 0:
            raise DynamicsInputError("TangentDirections.result: no averaging interval run yet (call advance)")
        times = (np.arange(q) + 1) * run.interval
        lam1 = run.running[run.n_transient:run.q, 0]  # the first row, not sorted: the first vector's
        log_p = np.array(self._log_p)
        with np.errstate(invalid="ignore"):
            running = lam1[:, None] + (log_p - self.log_p0[None, :]) / times[:, None]
        return DirectionExponents(names=self.names, exponents=running[-1].copy(), largest=float(lam1[-1]),
                                  times=times, running=running, running_largest=lam1.copy(),
                                  share=self._share_sum / q, log_p0=self.log_p0.copy(), log_p=log_p[-1].copy(),
                                  log_pS=np.array([self.log_pS0, self._log_pS]),
                                  complete=np.asarray(self.projector.complete))

    def save(self, path) -> None:
        """The Benettin run's state (``<path>``) and the projections so far (``<path>.directions.npz``)."""
        path = str(path)
        self.run.save(path)
        np.savez(path + ".directions.npz", log_p=np.array(self._log_p).reshape(-1, len(self.names)),
                 log_p0=np.full(len(self.names), np.nan) if self.log_p0 is None else self.log_p0,
                 log_pS0=np.nan if self.log_pS0 is None else self.log_pS0, log_pS=self._log_pS,
                 share_sum=self._share_sum, started=self.log_p0 is not None)

    @classmethod
    def load(cls, path, rhs, args, projector, *, jvp=None) -> "TangentDirections":
        """Resume from :meth:`save`'s files with the same ``rhs``, ``args``, ``projector`` and ``jvp``."""
        path = str(path)
        self = cls(BenettinRun.load(path, rhs, args, jvp=jvp), projector)
        with np.load(path + ".directions.npz") as f:
            self._log_p = list(f["log_p"])
            if bool(f["started"]):
                self.log_p0, self.log_pS0 = f["log_p0"].copy(), float(f["log_pS0"])
            self._log_pS = float(f["log_pS"])
            self._share_sum = f["share_sum"].copy()
        return self


@dataclass(frozen=True)
class RunLength:
    """:func:`run_length`'s answer.  The members' spread is modelled as sigma^2(T) = a^2 / T^2 + c^2 / T:
    ``a`` [-] the boundary term (the log of a tangent vector's norm differs from its trend by a bounded
    function of the state, so a finite-time exponent carries an O(1/T) part), ``c`` [1/sqrt(s)] the
    diffusive part of a mixing system, which wins at long T.  ``slope`` [-]: d log sigma / d log T over the
    fitted part (-1 where the boundary term dominates, -0.5 where the diffusion does); ``mean`` [1/s] and
    ``spread`` [1/s] the members' mean and standard deviation at the end T_end.

    ``required`` [s]: the record one member needs for a standard deviation ``rel`` |mean|, taking all of the
    end's sigma^2 T as diffusive: sigma(T_end)^2 T_end / (rel mean)^2 (``required_mean``: for the mean of the
    ``members``, divided by their number).  ``note``: "" or why no run length follows: a spread that does
    not fall over the fitted part (``slope`` above ``NOT_FALLING``) is not the statistics of one stationary
    record, but members that drift apart (a non-stationary record, or members on different attractors), and
    no record length brings them together -- or, with few members and intermittent stretching, that the
    spread is itself too uncertain to fit (4 members: a standard deviation uncertain by 40 %).
    ``c_windows`` [1/sqrt(s)] and ``required_windows`` [s] (with ``window``): the same rule from the
    exponents of consecutive windows of every member (:func:`window_exponents`, the first window left out:
    the tangent vector's alignment), c^2 = window var(window exponents), pooled over members and windows (batch
    means; the windows must be longer than the stretching's correlation time).  Each window carries its own
    boundary term, so c_windows^2 = c^2 + 2 a^2 / window: an upper bound that falls with the window (Lorenz:
    0.39, 0.26, 0.21 1/sqrt(s) at 20, 50, 100 s windows against sigma sqrt(T) = 0.12 at 2,000 s).  Under the model it is an upper bound (sigma^2 T falls with T);
    measured on Lorenz its prediction sigma(T_end) sqrt(T_end / T) matches the spread 7 times further on or
    overestimates it by up to 1.8 (``tests/test_tangent_directions.py``).  ``required_fit`` [s] solves a^2 / T^2 + c^2 / T = (rel mean)^2
    with the fitted a and c (less safe: the fit of a and c from one record's members scatters by a factor 2)."""

    a: float
    c: float
    slope: float
    mean: float
    spread: float
    rel: float
    required: float
    required_mean: float
    required_fit: float
    members: int
    note: str = ""
    c_windows: float = math.nan
    required_windows: float = math.nan


#: a members' spread whose log-log slope over the fitted part is above this does not fall with T (a
#: stationary mixing record's falls at -0.5 to -1): :class:`RunLength`'s ``note`` says so
NOT_FALLING = -0.25


def _length_for(a2, c2, target2):
    """Smallest T with a2 / T^2 + c2 / T <= target2."""
    if target2 <= 0:
        return math.inf
    return (c2 + math.sqrt(c2 * c2 + 4.0 * target2 * a2)) / (2.0 * target2)


def window_exponents(times, running, window):
    """``(ends, exponents)``: exponents [1/s] over consecutive windows of ``window`` [s] of running estimates
    ``running`` (M, q) at ``times`` (q,), from the log stretching S = running T differenced at the windows'
    ends (the last, partial window included): the record's local rate, where a running mean hides
    intermittency and drift."""
    times = np.asarray(times, dtype=float)
    running = np.atleast_2d(np.asarray(running, dtype=float))
    window = float(window)
    if not (window > 0 and math.isfinite(window)):
        raise DynamicsInputError(f"window = {window!r} must be a finite time > 0")
    stops = np.flatnonzero(np.diff(np.floor(times / window)) > 0)
    if stops.size == 0 or stops[-1] != times.size - 1:
        stops = np.concatenate([stops, [times.size - 1]])
    S = running[:, stops] * times[stops][None, :]
    t_end = times[stops]
    dS = np.diff(np.concatenate([np.zeros((running.shape[0], 1)), S], axis=1), axis=1)
    dT = np.diff(np.concatenate([[0.0], t_end]))
    return t_end, dS / dT[None, :]


def run_length(times, running, rel=0.1, *, fit_from=0.5, window=None) -> RunLength:
    """Run-length rule from independent members' running estimates ``running`` (M, q) at ``times`` (q,):
    sigma(T) = std over members (ddof 1) after ``fit_from`` of the record (the start is dominated by the
    alignment of the tangent vectors); sigma^2 = a^2 / T^2 + c^2 / T fitted there by non-negative least
    squares in relative terms (``scipy.optimize.nnls``); the required record from the end's spread
    (:class:`RunLength`).  Needs M >= 2 and a spread that is not zero."""
    from scipy.optimize import nnls

    times = np.asarray(times, dtype=float)
    running = np.atleast_2d(np.asarray(running, dtype=float))
    M, q = running.shape
    if M < 2 or q != times.size or q < 2:
        raise DynamicsInputError(f"running (shape {running.shape}) must hold >= 2 members' estimates at the "
                                 f"{times.size} times")
    if not 0.0 < float(rel) < 1.0:
        raise DynamicsInputError(f"rel = {rel!r} must be between 0 and 1")
    sigma = np.std(running, axis=0, ddof=1)
    part = (times >= fit_from * times[-1]) & (sigma > 0) & np.isfinite(sigma)
    if part.sum() < 2:
        raise DynamicsInputError("run_length: the members do not spread (identical members are not independent)")
    T, s2 = times[part], sigma[part] ** 2
    A = np.stack([1.0 / T ** 2, 1.0 / T], axis=1) / s2[:, None]
    (a2, c2), _ = nnls(A, np.ones(T.size))
    slope = float(np.polyfit(np.log(T), np.log(sigma[part]), 1)[0]) if part.sum() > 2 else math.nan
    mean = float(np.mean(running[:, -1]))
    target2 = (rel * mean) ** 2
    required = float(sigma[-1] ** 2 * times[-1] / target2) if target2 > 0 else math.inf
    c_w = req_w = math.nan
    if window is not None:
        ends, local = window_exponents(times, running, window)
        full = np.diff(np.concatenate([[0.0], ends])) >= 0.999 * float(window)
        blocks = local[:, 1:][:, full[1:]]
        if blocks.size > 1:
            c_w = math.sqrt(float(window) * float(np.var(blocks, ddof=1)))
            req_w = c_w * c_w / target2 if target2 > 0 else math.inf
    note = ""
    if not slope <= NOT_FALLING:
        note = (f"the members' spread does not fall with T over {T[0]:.4g}-{T[-1]:.4g} s (log-log slope "
                f"{slope:.2f}): they drift apart (non-stationary record or different attractors); no run "
                "length follows from it, or too few members to fit their spread")
    return RunLength(a=math.sqrt(a2), c=math.sqrt(c2), slope=slope, mean=mean, spread=float(sigma[-1]),
                     rel=float(rel), required=required, required_mean=required / M,
                     required_fit=_length_for(a2, c2, target2), members=M, note=note, c_windows=c_w,
                     required_windows=req_w)
