"""Physical bounds on a run's outputs: no impossible number leaves a run.

Every summary value that has a physical bound declares it here, once, in :data:`BOUNDS`: a pattern
on the summary key, the bound (a number, or a multiple of one of the scene's own scales) and where the
bound comes from.  :func:`lubedyn.outputs.run_summary`, the one place every scene's summary passes
through, calls :func:`enforce` before anything is written:

- inside every bound: nothing happens;
- outside one, with ``[validity] strict = true`` (the default): :class:`ImplausibleResult` (a
  :class:`~lubedyn.lubrication.errors.ConvergenceError`: ``lubedyn run`` prints one line and exits 1, and the
  previous run's folder is left as it was) naming the output, its value and the bound;
- with ``[validity] strict = false``: one WARNING line per output, listed under ``"Warnings"`` in
  summary.json (and so in a study's table), and the numbers are written.

A bound is a statement about physics, not about accuracy: it catches results that no lubricated
contact can give (a traction coefficient of 3.8e20, a fraction of 1.3, a film thicker than the body that
carries it), whatever their cause.  Accuracy has its own checks (the EHL solver's coarser-level and
closed-form comparisons, the film's resolution guard, a map's accuracy report).

Scales are given by the scene (``scales=`` of :func:`enforce`), in SI:

- ``hertz_pressure``: the Hertz pressure of the dry contact under the same load [Pa] (EHL scene);
- ``radius``: the reduced radius of curvature along the entrainment direction [m] (EHL scene);
- ``viscous_pressure``: 6 eta0 U L / h_min^2 + 12 eta0 |V| L^2 / h_min^3 + the largest boundary
  pressure, for an iso-viscous film (film scene; absent for a pressure-dependent viscosity);
- ``applied_load``: the load the case prescribes [N] (EHL point contact with a given load);
- ``applied_load_per_length``: the same per unit length [N/m] (EHL line contact).

>>> from lubedyn.bounds import violations
>>> violations({"Traction coefficient [-]": 3.8e20, "Load [N]": 5.0})[0].split(" (")[0]
'Traction coefficient [-] = 3.8e+20 is outside its bound |value| <= 1'
>>> violations({"Traction coefficient [-]": 0.05, "Cavitated area fraction [-]": 0.3})
[]
"""
from __future__ import annotations

import logging
import math
import re
from dataclasses import dataclass

from lubedyn.lubrication.errors import ConvergenceError

log = logging.getLogger(__name__)


class ImplausibleResult(ConvergenceError):
    """An output outside its physical bound (:data:`BOUNDS`) under ``[validity] strict = true``."""


@dataclass(frozen=True)
class Bound:
    """``pattern``: a regular expression matched (in full) against a summary key, or the path of a
    nested value (``"Skew [rad] / loaded zone / mean"``); ``low``/``high``: the bound (None: open),
    times the scene's scale ``scale`` when given (the bound is skipped when the scene has no such
    scale); ``absolute``: bound |value|; ``why``: where the bound comes from (shown in the message)."""

    pattern: str
    low: float | None
    high: float | None
    why: str
    scale: str | None = None
    absolute: bool = False

    def limits(self, scales: dict) -> tuple[float, float] | None:
        """(low, high) in SI, or None when the bound needs a scale the scene did not give."""
        factor = 1.0
        if self.scale is not None:
            factor = scales.get(self.scale)
            if factor is None or not math.isfinite(factor) or factor <= 0.0:
                return None
        lo = -math.inf if self.low is None else self.low * factor
        hi = math.inf if self.high is None else self.high * factor
        return lo, hi

    def describe(self, lo: float, hi: float) -> str:
        """The bound as text: ``|value| <= 1``, ``0 <= value <= 1``, ``value <= 20 x hertz_pressure = 1.3e+10``."""
        name = "|value|" if self.absolute else "value"
        parts = [f"{_g(lo)} <=" if math.isfinite(lo) else "", name]
        if math.isfinite(hi):
            parts.append(f"<= {_g(hi)}" if self.scale is None else f"<= {_g(self.high)} x {self.scale} = {_g(hi)}")
        if self.scale is not None and math.isfinite(lo) and not math.isfinite(hi):
            parts[0] = f"{_g(self.low)} x {self.scale} = {_g(lo)} <="
        return " ".join(p for p in parts if p)


def _g(x: float) -> str:
    return f"{x:.3g}"


# The bounds, with where each comes from.  A pattern matches the key in full (re.fullmatch).
_BALANCE = ("the load balance of the EHL solve: the film carries the load the case applies (the solver "
            "meets it to its tolerance, 1e-7 relative by default)")
_FILM = r"(?:(?:Largest|Smallest) value of )?(?:Minimum|Central) film thickness \[m\]"
BOUNDS: tuple[Bound, ...] = (
    # (not the roller maps' "Traction coefficient at normalised slip [-]": an auxiliary table whose slip
    # coordinate runs to 1e6 times the transition slip, far beyond any rolling contact's sliding)
    Bound(r"(?:(?:Largest|Smallest) value of )?(?:Traction|Friction) coefficient \[-\]", None, 1.0,
          "a lubricated contact transmits at most the limiting shear stress of its film, measured at "
          "0.03-0.1 of the pressure (Bair & Winer 1979, J. Lubr. Technol. 101, 258); even dry steel on steel "
          "stays below 1 (Bowden & Tabor)", absolute=True),
    Bound(r"(?i).*\bfraction\b.*\[-\]", 0.0, 1.0, "a fraction of an area, a volume or a time"),
    Bound(r"Eccentricity ratio \[-\]", 0.0, 1.0, "the journal touches its bearing at 1"),
    Bound(r"(?:Largest|Smallest) value of (?:Entrainment|Squeeze) number \[-\]", -1.0, 1.0,
          "alpha times the rigid iso-viscous film's pressure scale: a Barus film's reduced pressure "
          "(1 - exp(-alpha p))/alpha stays below 1/alpha, so its pressure is finite only below 1 (the pole)"),
    Bound(_FILM, 0.0, None, "a film thickness is a distance between two surfaces"),
    Bound(_FILM, None, 0.1, "Reynolds' equation is a thin-film law (film << radius of curvature); a film a "
          "tenth of the radius is far outside it", scale="radius"),
    Bound(r"Maximum pressure \[Pa\]", None, 20.0,
          "a load-carrying EHL film's pressure follows the Hertz pressure; its outlet spike reaches 2-3 "
          "times it (Venner & Lubrecht 2000)", scale="hertz_pressure"),
    Bound(r"Maximum pressure \[Pa\]", None, 1.0,
          "the pressure an iso-viscous film of this speed, size and thinnest gap can build: the inclined "
          "slider's is 0.042 times 6 eta U L / h^2, a sphere's squeeze film's 3 eta V R / h^2 is below "
          "12 eta V L^2 / h^3; the bundled film cases reach 0.0006-0.07 of the scale", scale="viscous_pressure"),
    Bound(r"(?:(?:Initial |Quasi-static )?[Ll]argest .*(?:load|normal force).*|(?:Cup|Cone|Flange) loads) \[N\]",
          0.0, None, "a contact pushes: its normal load is never negative"),
    Bound(r"Force balance error \[-\]", None, 1e-3,
          "the quasi-static equilibrium: the contact forces sum to the applied loads (the solver meets it to "
          "2e-12 to 2.3e-8 on the bundled static cases)"),
    # the tapered scene's "Raceway films (lubricant.raceway_film = ...)" block, per raceway
    Bound(r"Raceway films .* / (?:EHL central|EHL minimum|Formula) film[^/]*\[um\]", 0.0, None,
          "a film thickness is a distance between two surfaces"),
    Bound(r"Raceway films .* / (?:Factor h_EHL/h_formula \[-\]|(?:Reference|Effective) viscosity \[Pa s\])",
          0.0, None, "a viscosity, and the ratio of two films, is positive"),
    # the Lyapunov estimates' guards (lubedyn.dynamics.lyapunov.assess_largest_lyapunov)
    Bound(r".*(?:[Ee]xponent|Lyapunov).* (?:window )?uncertainty \[(?:bits/s|1/s|1/rev)\]", 0.0, None,
          "an uncertainty is a spread (a standard error), never negative"),
    Bound(r".* settings spread \[-\]", 0.0, None, "a relative spread of estimates, never negative"),
    Bound(r"Tangent-space exponent, .* share \[-\]", 0.0, 1.0,
          "the time mean of a unit tangent vector's squared share in a subspace (lubedyn.dynamics.tangent_directions)"),
    Bound(r".* false-neighbour dimension \[-\]", 1.0, None, "an embedding has at least one dimension"),
    Bound(r"RK4 step(?: bound)? \[s\]", 0.0, None, "a time step is positive"),
    Bound(r"Load \[N\]", 0.99, 1.01, _BALANCE, scale="applied_load"),
    Bound(r"Load per length \[N/m\]", 0.99, 1.01, _BALANCE, scale="applied_load_per_length"),
)


def _leaves(summary: dict, prefix: str = "", top: str | None = None):
    """(path, value, top-level key) of every numeric leaf of ``summary`` (nested mappings joined by
    " / ", list items by their index); booleans and strings are not numbers."""
    for key, value in summary.items():
        path, owner = f"{prefix}{key}", key if top is None else top
        if isinstance(value, dict):
            yield from _leaves(value, path + " / ", owner)
        elif isinstance(value, (list, tuple)):
            for i, item in enumerate(value):
                if isinstance(item, (int, float)) and not isinstance(item, bool):
                    yield f"{path} / {i}", float(item), owner
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            yield path, float(value), owner


def violations(summary: dict, scales: dict | None = None) -> list[str]:
    """One line per summary value outside a bound of :data:`BOUNDS` (none: []).

    A bound applies to a top-level key and to every value nested below it (statistics of a series:
    ``"Skew [rad] / loaded zone / mean"``), matched on the top-level key, and to a nested value whose
    whole path it matches (a film inside a block of films); NaN ("not computed") is not a violation."""
    scales = dict(scales or {})
    out = []
    compiled = [(re.compile(b.pattern), b) for b in BOUNDS]
    for path, value, key in _leaves(summary):
        if math.isnan(value):
            continue
        for rx, bound in compiled:
            if not (rx.fullmatch(key) or rx.fullmatch(path)):
                continue
            lims = bound.limits(scales)
            if lims is None:
                continue
            lo, hi = lims
            v = abs(value) if bound.absolute else value
            if not (lo <= v <= hi) or math.isinf(value):
                out.append(f"{path} = {_g(value)} is outside its bound {bound.describe(lo, hi)} ({bound.why})")
    return out


def enforce(summary: dict, scales: dict | None = None, *, strict: bool = True) -> dict:
    """Check ``summary`` against :data:`BOUNDS`: raise :class:`ImplausibleResult` (``strict``) naming the
    first output outside its bound (and how many more), or log each as a WARNING and list it under
    ``"Warnings"``.  Returns ``summary``."""
    found = violations(summary, scales)
    if not found:
        return summary
    if strict:
        more = f"; and {len(found) - 1} more" if len(found) > 1 else ""
        err = ImplausibleResult(f"{found[0]}{more}: not a physical answer, so nothing was written; "
                                "[validity] strict = false writes it with a warning")
        err.stop = dict(reason="output outside its physical bound", detail="; ".join(found))
        raise err
    for text in found:
        log.warning("%s", text)
    summary.setdefault("Warnings", [])
    summary["Warnings"] = list(summary["Warnings"]) + found
    return summary


def strict_of(case) -> bool:
    """``[validity] strict`` of ``case`` (True where the case has no such key)."""
    return bool(getattr(getattr(case, "validity", None), "strict", True))
