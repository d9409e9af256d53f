"""Case files: TOML -> validated model in SI -> (scene builders).

A case is a TOML file with a ``scene`` kind and one table per concern.  This
module is the *only* place where raw user input is read: it merges the
``[smoke]`` table (``--smoke``) and ``--set key=value`` overrides into the raw
mapping, checks the scene kind, validates the result with pydantic (unknown
keys forbidden, with close matches), converts every quantity to SI once
(:mod:`lubedyn.units`) and turns any mistake into a one-line
:class:`CaseError` naming the dotted key, the value and what is allowed.  A bare number is SI,
and every length is checked against the lengths of its own scene (:func:`check_scale`: a film thin
against its length, :data:`THIN_FILM`), so that ``clearance = 50`` meant in um is refused with
``bare numbers are SI (m): write "50 um"`` rather than run as 50 m.

Film case layout (``scene = "film"``; every quantity: a number in SI or a
string with units)::

    scene = "film"
    description = "one line shown by `lubedyn cases`"
    [gap]        type = inclined_slider | step_slider | pocketed_slider | journal |
                        sphere_plane | sphere_sphere | cylinder_plane | ellipsoid_plane
                 + that gap's parameters (see the ``*Gap`` models below)
    [mesh]       domain = auto | interval | rectangle | disk | journal
                 x, y = [lo, hi], nx, ny, cell = quad | tri, radius, refinements,
                 element = P1 | P2
    [motion]     velocity_lower, velocity_upper (number = x component, or [ux, uy]),
                 speed (journal, e.g. "3000 rpm"), squeeze (dh/dt) or
                 approach_velocity (= -squeeze), mode_velocities = {x = .., y = ..}
    [lubricant.viscosity]  law = constant | barus | roelands, eta0, alpha, z
    [lubricant.density]    law = incompressible | dowson_higginson, rho0, a, b
    [lubricant]  eyring_stress (EHL scenes only: Reynolds-Eyring shear thinning, tau0)
    [cavitation] model = none | half_sommerfeld | reynolds | jfo, pressure
    [boundary]   ambient, pressures = {name = p}, sealed = [names]
    [solver]     rtol, max_iter, linear_solver = auto | direct | amg, amg_tol
    [output]     write = ["vtu", "png"], film_coefficients = false
    [validity]   max_pressure, min_film, max_reynolds: warn when a result leaves the model's range
    [limits]     memory = "40 GiB", map_points (every scene: :mod:`lubedyn.limits`)
    [smoke]      a partial case merged over this one by ``--smoke``

Boundary names: interval ``left right``; rectangle ``left right bottom top``;
journal (periodic in theta) ``bottom top``; disk ``edge``.  A boundary not
listed in ``pressures`` is held at ``ambient``; one listed in ``sealed`` has
no flow through it.

The EHL scene's layout is in :mod:`lubedyn.scenes.ehl_case`, the map and dynamics scenes' in
:mod:`lubedyn.scenes.map` and :mod:`lubedyn.scenes.dynamics`.

>>> case = load_case_text('scene = "film"\\n[gap]\\ntype = "sphere_plane"\\nradius = "5 mm"\\n'
...                       'h0 = "2 um"\\n[mesh]\\nradius = "1 mm"\\n[lubricant]\\nviscosity = "0.1 Pa s"')
>>> case.gap.h0, case.mesh.domain
(2e-06, 'disk')
"""
from __future__ import annotations

import copy
import importlib.resources
import logging
import math
import re
import tomllib
import types
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal, Union

from pydantic import (BaseModel, BeforeValidator, ConfigDict, Field, PrivateAttr, ValidationError, ValidationInfo,
                      model_validator)
from pydantic_core import PydanticCustomError

from lubedyn import scenes
from lubedyn.lubrication.errors import InputError, close_matches, did_you_mean
from lubedyn.lubrication.laws.lubricant import DowsonHigginson

from lubedyn.papers import SETS as PARAMETER_SETS
from lubedyn.papers import apply_parameter_set, parameter_set
from lubedyn.units import UnitError, parse_quantity, si_unit, unit_hint, written
from lubedyn.limits import parse_bytes

# the bundled cases and maps: package data of ``lubedyn.cases`` (the checkout's ``cases/`` in an editable
# install, ``site-packages/lubedyn/cases`` in a wheel's), a real folder either way
CASES_DIR = Path(importlib.resources.files("lubedyn.cases"))
log = logging.getLogger(__name__)


class CaseError(InputError):
    """A case file mistake: one line naming the key, the value and what is allowed."""


# ---------------------------------------------------------------------------
# quantities


def _bounds_text(unit, gt, ge, lt, le) -> str:
    unit = "" if unit == "-" else f" {unit}"
    lo = f"({gt:g}" if gt is not None else (f"[{ge:g}" if ge is not None else None)
    hi = f"{lt:g})" if lt is not None else (f"{le:g}]" if le is not None else None)
    if lo and hi:
        return f"must be in {lo}, {hi}{unit}"
    if lo:
        return f"must be {'>' if gt is not None else '>='} {lo[1:]}{unit}"
    return f"must be {'<' if lt is not None else '<='} {hi[:-1]}{unit}"


class Dimension(str):
    """Marker in a quantity's metadata: its dimension (for messages)."""


@dataclass(frozen=True)
class Bounds:
    """Marker in a quantity's metadata: its range in SI and why (for messages and the generated case
    reference of the documentation, ``docs/_ext/case_reference.py``)."""

    gt: float | None = None
    ge: float | None = None
    lt: float | None = None
    le: float | None = None
    why: str = ""

    def text(self, dimension: str) -> str:
        """``"must be > 0 m"``, or ``""`` without bounds."""
        if self.gt is None and self.ge is None and self.lt is None and self.le is None:
            return ""
        return _bounds_text(si_unit(dimension), self.gt, self.ge, self.lt, self.le)


def Q(dimension: str, *, gt=None, ge=None, lt=None, le=None, why: str = ""):
    """An annotated float: a quantity of ``dimension`` converted to SI, range-checked."""

    def convert(value):
        try:
            x = parse_quantity(value, dimension)
        except UnitError as exc:
            raise PydanticCustomError("quantity", "{text}", {"text": str(exc)}) from None
        if not math.isfinite(x):
            raise PydanticCustomError("quantity", "{text}", {"text": "must be finite"})
        bad = (gt is not None and not x > gt) or (ge is not None and not x >= ge) or (
            lt is not None and not x < lt) or (le is not None and not x <= le)
        if bad:
            text = _bounds_text(si_unit(dimension), gt, ge, lt, le) + (f" ({why})" if why else "")
            raise PydanticCustomError("quantity", "{text}", {"text": text})
        return x

    return Annotated[float, BeforeValidator(convert), Dimension(dimension), Bounds(gt, ge, lt, le, why)]


def _listify(value):
    return value if isinstance(value, list) else [value]


Length = Q("length")
PositiveLength = Q("length", gt=0)
Pressure = Q("pressure")
Velocity = Q("velocity")
VelocityVector = Annotated[list[Velocity], BeforeValidator(_listify)]
Extent = Annotated[list[Length], Field(min_length=2, max_length=2)]
PositiveInt = Annotated[int, Field(strict=True, ge=1)]


def rule(key: str, value, text: str) -> PydanticCustomError:
    """A cross-field error on ``key`` (relative to the model raising it)."""
    return PydanticCustomError("case_rule", "{text}", {"key": key, "value": value, "text": text})


class CaseTable(BaseModel):
    """The base of every case-file table and case model: unknown keys are errors, defaults validated.

    Built from Python, a table takes what its case-file table takes -- quantities as numbers in SI or
    strings with units, ``ValidityModel(min_film="0.1 um")`` -- and a mistake is the case file's one-line
    :class:`CaseError` naming the table, the key, the value and what is allowed (not pydantic's report)."""

    model_config = ConfigDict(extra="forbid", validate_default=True)
    _parameter_set: str | None = PrivateAttr(default=None)  # the set a case named (lubedyn.papers)

    def __init__(self, /, **data):
        try:
            super().__init__(**data)
        except ValidationError as exc:
            raise CaseError(f"{type(self).__name__}: {format_validation_error(exc, type(self))}") from None

    # only a call from Python comes here: marked as pydantic's own __init__ (as pydantic's RootModel marks
    # its own), validation of a nested table goes on in pydantic's core, with its context, not through it
    __init__.__pydantic_base_init__ = True  # type: ignore[attr-defined]


# ---------------------------------------------------------------------------
# scales: a quantity checked against the scales of its own scene
#
# A bare number for a dimensioned key is SI (``clearance = 50`` is 50 m).  The schema cannot tell a
# bare 50 that means um from a real 50 m, but the scene can: every length is compared with the
# lengths it lives among, and a failure names the key, its value, the scale it was compared with and
# the unit it was probably meant in (``bare numbers are SI (m): write "50 um"``).  The checks run in
# the models' validators, so that ``lubedyn validate``, ``run`` and ``--set`` share them;
# :func:`validate_raw` hands the validators the raw mapping (pydantic's validation context), from
# which a check tells a bare number from a string with units.

THIN_FILM = 0.1
"""The largest film thickness over the length it spreads over (h/L) a case may give.  Reynolds'
equation is the leading order of the Navier-Stokes equations in the film's aspect ratio: it drops
terms of relative order (h/L)^2 (and the reduced Reynolds number Re h/L, which ``validity.max_reynolds``
watches after the solve), so it needs h/L << 1; 0.1 is where "much less" ends (the dropped terms are
then about 1 %).  Bearing films are far below it (a journal's c/R is about 1e-3, a slider's h/L 1e-4 to
1e-3): a ratio above 0.1 is a slipped unit, not a film."""
THIN_FILM_WHY = "Reynolds' equation is the thin-film limit of the flow equations: it needs h/L << 1"


@dataclass(frozen=True)
class Scaled:
    """One quantity of a scale check: its dotted key from the case's root, its value in SI and its
    dimension.  A derived key (``"gap.pocket_end - gap.pocket_start"``) is shown, never blamed."""

    key: str
    value: float
    dimension: str = "length"
    given: bool = True  # False: derived from given keys (shown, never blamed)


def context_raw(info) -> dict | None:
    """The raw case mapping a validator was given (:func:`validate_raw` passes it), or None."""
    context = getattr(info, "context", None)
    return context.get("raw") if isinstance(context, dict) else None


def _raw_at(raw: dict | None, key: str):
    node = raw
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def _is_bare(value) -> bool:
    if isinstance(value, list):
        return bool(value) and all(_is_bare(v) for v in value)
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _hint(raw_value, dimension: str, passes) -> str | None:
    """The unit rewrite of ``raw_value`` (a number or a string with units, or a list of them) that
    makes ``passes(si)`` hold (:func:`lubedyn.units.unit_hint`); a list's largest entry decides."""
    if not isinstance(raw_value, list):
        return unit_hint(raw_value, dimension, passes)
    forms = [written(v, dimension) for v in raw_value]
    if not forms or any(f is None for f in forms) or len({f[1] for f in forms}) != 1:
        return None
    big = max(range(len(forms)), key=lambda i: abs(forms[i][0]))
    one = unit_hint(raw_value[big], dimension, lambda si: passes(abs(si)))
    if one is None:
        return None
    unit = one.split(" ", 1)[1]
    return "[" + ", ".join(f"'{f[0]:g} {unit}'" for f in forms) + "]"


def check_scale(raw: dict | None, name: str, ratio, quantities, *, limit: float, why: str,
                lower: bool = False, strict: bool = False, blame=None, also=()) -> tuple[str, str] | None:
    """None when ``ratio(values)`` (values: ``{key: SI value}`` of ``quantities``) is within ``limit``
    (``<=``, or ``<`` when ``strict``; ``>=`` when ``lower``), else ``(key, text)`` of a one-line error.

    The key blamed is the first of ``blame`` (default: the quantities' keys, in order) that was written
    as a bare number (``raw``: the case mapping; None when unknown: every value counts as bare) and
    becomes right in another common unit; that rewrite is the hint (``bare numbers are SI (m): write
    "50 um"``).  When none does, the first bare one (else the first) is blamed and no unit is
    suggested: a value written with units is taken as meant, and the message shows what it was
    compared with.  ``also``: predicates ``f(values) -> bool`` (the scene's other scale checks) that a
    suggested value must pass too.

    >>> check_scale({"gap": {"clearance": 50, "radius": "25 mm"}}, "clearance/radius",
    ...             lambda v: v["gap.clearance"] / v["gap.radius"],
    ...             [Scaled("gap.clearance", 50.0), Scaled("gap.radius", 0.025)], limit=0.1, why="thin")
    ... # doctest: +NORMALIZE_WHITESPACE
    ('gap.clearance', '= 50 (50 m) is out of scale: clearance/radius = 2000 with gap.radius = 0.025 m
      must be <= 0.1 (thin); bare numbers are SI (m): write "50 um"')
    """
    values = {q.key: q.value for q in quantities}

    def ok(r: float) -> bool:
        if not math.isfinite(r):
            return False
        if lower:
            return r > limit if strict else r >= limit
        return r < limit if strict else r <= limit

    r = ratio(values)
    if ok(r):
        return None
    by_key = {q.key: q for q in quantities}
    order = [k for k in (blame or [q.key for q in quantities]) if k in by_key and by_key[k].given]
    bare = [k for k in order if _is_bare(_raw_at(raw, k) if raw is not None else by_key[k].value)]
    blamed, suggestion = by_key[(bare or order)[0]] if order else quantities[0], None
    for key in order:  # a unit is suggested for a bare number only: one with units is taken as meant
        q = by_key[key]
        raw_value = _raw_at(raw, key) if raw is not None else q.value
        if not _is_bare(raw_value):
            continue

        def passes(si, key=key):
            trial = {**values, key: si}
            return ok(ratio(trial)) and all(check(trial) for check in also)

        found = _hint(raw_value, q.dimension, passes)
        if found is not None:
            blamed, suggestion = q, found
            break
    unit = si_unit(blamed.dimension)
    raw_value = _raw_at(raw, blamed.key) if raw is not None and blamed.given else None
    shown = f"{blamed.value:g} {unit}" if raw_value is None else f"{show_value(raw_value)} ({blamed.value:g} {unit})"
    others = ", ".join(f"{q.key} = {q.value:g} {si_unit(q.dimension)}" for q in quantities if q is not blamed)
    op = (">" if strict else ">=") if lower else ("<" if strict else "<=")
    text = (f"= {shown} is out of scale: {name} = {r:.4g}" + (f" with {others}" if others else "")
            + f" must be {op} {limit:g} ({why})")
    if blamed.given and (raw is None or _is_bare(raw_value)):
        text += _bare_text(blamed.dimension, suggestion)
    return blamed.key, text


def _bare_text(dimension: str, suggestion: str | None) -> str:
    if suggestion and not suggestion.startswith("["):
        suggestion = f'"{suggestion}"'
    return f"; bare numbers are SI ({si_unit(dimension)})" + (f": write {suggestion}" if suggestion else "")


def bare_hint(raw: dict | None, key: str, dimension: str, passes) -> str:
    """``'; bare numbers are SI (m): write "50 um"'`` for a rule on ``key`` (dotted from the case's root)
    that was written as a bare number, in the unit whose SI value satisfies ``passes(si)``
    (:func:`lubedyn.units.unit_hint`); ``""`` when it was written with units (or is unknown): the
    hint of the schema's older rules (a step on its pad ...), whose wording it keeps."""
    value = _raw_at(raw, key)
    if raw is None or not _is_bare(value):
        return ""
    return _bare_text(dimension, _hint(value, dimension, passes))


def thin_film(raw: dict | None, film: Scaled, length: Scaled, name: str | None = None, *,
              limit: float = THIN_FILM, why: str = THIN_FILM_WHY) -> tuple[str, str] | None:
    """:func:`check_scale` of a film thickness over the length it spreads over: |h|/L <= ``limit``
    (``name``: how the ratio is called, default ``"clearance/radius"`` from the keys)."""
    name = name or f"{film.key.rsplit('.', 1)[-1]}/{length.key.rsplit('.', 1)[-1]}"
    return check_scale(raw, name, lambda v: abs(v[film.key]) / v[length.key], [film, length], limit=limit, why=why)


def raise_scale(failed: tuple[str, str] | None) -> None:
    """Raise a failed scale check as a case rule on its (root-relative) key."""
    if failed is not None:
        raise root_rule(failed[0], None, failed[1])


# ---------------------------------------------------------------------------
# gaps


class InclinedSliderGap(CaseTable):
    """Plane inclined slider h_in -> h_out over [0, length] (1-D, or 2-D with mesh.y)."""

    type: Literal["inclined_slider"]
    h_in: PositiveLength
    h_out: PositiveLength
    length: PositiveLength


class StepSliderGap(CaseTable):
    """Rayleigh step: h_in on [0, x_step), h_out on [x_step, length]."""

    type: Literal["step_slider"]
    h_in: PositiveLength
    h_out: PositiveLength
    x_step: PositiveLength
    length: PositiveLength

    @model_validator(mode="after")
    def _step_inside(self, info: ValidationInfo):
        if not self.x_step < self.length:
            raise rule("x_step", self.x_step, f"must be < length = {self.length:g} m" + bare_hint(
                context_raw(info), "gap.x_step", "length", lambda si: si < self.length))
        return self


class PocketedSliderGap(CaseTable):
    """Linear slider with a pocket of ``depth`` on [pocket_start, pocket_end]."""

    type: Literal["pocketed_slider"]
    h_in: PositiveLength
    h_out: PositiveLength
    length: PositiveLength
    pocket_start: Q("length", ge=0)
    pocket_end: PositiveLength
    depth: Length

    @model_validator(mode="after")
    def _pocket_inside(self, info: ValidationInfo):
        raw = context_raw(info)
        if not self.pocket_start < self.pocket_end:
            start = bare_hint(raw, "gap.pocket_start", "length", lambda si: si < self.pocket_end)
            if start:  # a bare pocket_start is the likelier slip
                raise rule("pocket_start", self.pocket_start, f"must be < pocket_end = {self.pocket_end:g} m" + start)
            raise rule("pocket_end", self.pocket_end, f"must be > pocket_start = {self.pocket_start:g} m")
        if not self.pocket_end <= self.length:
            raise rule("pocket_end", self.pocket_end, f"must be <= length = {self.length:g} m" + bare_hint(
                raw, "gap.pocket_end", "length", lambda si: self.pocket_start < si <= self.length))
        return self


class JournalGap(CaseTable):
    """Plain journal bearing; eccentricity as ratio + attitude angle or as (x, y)."""

    type: Literal["journal"]
    radius: PositiveLength
    clearance: PositiveLength
    length: PositiveLength
    eccentricity_ratio: Q("dimensionless", ge=0, lt=1, why="the journal would touch the bearing") | None = None
    attitude_angle: Q("angle") | None = None
    eccentricity_x: Length | None = None
    eccentricity_y: Length | None = None

    @model_validator(mode="after")
    def _eccentricity(self, info: ValidationInfo):
        by_ratio = self.eccentricity_ratio is not None or self.attitude_angle is not None
        by_xy = self.eccentricity_x is not None or self.eccentricity_y is not None
        if by_ratio and by_xy:
            raise rule("eccentricity_x", self.eccentricity_x if self.eccentricity_x is not None else self.eccentricity_y,
                       "cannot be combined with eccentricity_ratio/attitude_angle; give one or the other")
        if by_xy:
            ex, ey = self.eccentricity_x or 0.0, self.eccentricity_y or 0.0
            self.eccentricity_x, self.eccentricity_y = ex, ey
            eps = math.hypot(ex, ey) / self.clearance
            if eps >= 1.0:
                raw, c = context_raw(info), self.clearance
                hint = (bare_hint(raw, "gap.eccentricity_x", "length", lambda si: math.hypot(si, ey) < c)
                        or bare_hint(raw, "gap.eccentricity_y", "length", lambda si: math.hypot(ex, si) < c))
                raise rule("eccentricity_x", ex, f"and eccentricity_y = {ey:g} give an eccentricity ratio "
                           f"{eps:.4g}; it must be < 1 (the journal would touch the bearing)" + hint)
        else:
            self.eccentricity_ratio = self.eccentricity_ratio or 0.0
            self.attitude_angle = self.attitude_angle or 0.0
        return self


class SpherePlaneGap(CaseTable):
    type: Literal["sphere_plane"]
    radius: PositiveLength
    h0: PositiveLength
    exact: bool = False


class SphereSphereGap(CaseTable):
    type: Literal["sphere_sphere"]
    radius1: PositiveLength
    radius2: PositiveLength | None = None
    h0: PositiveLength
    exact: bool = False

    @model_validator(mode="after")
    def _equal_balls(self):
        if self.radius2 is None:
            self.radius2 = self.radius1
        return self


class CylinderPlaneGap(CaseTable):
    type: Literal["cylinder_plane"]
    radius: PositiveLength
    h0: PositiveLength


class EllipsoidPlaneGap(CaseTable):
    type: Literal["ellipsoid_plane"]
    radius_x: PositiveLength
    radius_y: PositiveLength
    h0: PositiveLength


GapModel = Annotated[
    Union[InclinedSliderGap, StepSliderGap, PocketedSliderGap, JournalGap, SpherePlaneGap,
          SphereSphereGap, CylinderPlaneGap, EllipsoidPlaneGap],
    Field(discriminator="type"),
]
SLIDERS = ("inclined_slider", "step_slider", "pocketed_slider")
JOURNAL_MIN_NX = 3  # fewest cells around a periodic journal mesh (lubedyn.lubrication.mesh.PERIODIC_MIN_CELLS)
ROUND = ("sphere_plane", "sphere_sphere", "ellipsoid_plane")
# each gap's film thicknesses and the lengths they spread over (thin-film check, THIN_FILM)
FILM_LENGTHS = {
    "inclined_slider": (("h_in", "length"), ("h_out", "length")),
    "step_slider": (("h_in", "length"), ("h_out", "length")),
    "pocketed_slider": (("h_in", "length"), ("h_out", "length")),
    "journal": (("clearance", "radius"), ("clearance", "length")),
    "sphere_plane": (("h0", "radius"),),
    "sphere_sphere": (("h0", "radius1"), ("h0", "radius2")),
    "cylinder_plane": (("h0", "radius"),),
    "ellipsoid_plane": (("h0", "radius_x"), ("h0", "radius_y")),
}
# each curved gap's radius of curvature along x and along y (None: straight): the film domain ends
# inside the body (a sphere pair: the smaller ball, chosen when checked)
BODY_RADII = {"sphere_plane": ("radius", "radius"), "sphere_sphere": ("radius1", "radius1"),
              "cylinder_plane": ("radius", None), "ellipsoid_plane": ("radius_x", "radius_y")}
BODY_ENDS_WHY = "the film domain must lie on the body, whose surface ends at its radius"
JOURNAL_MIN_CLEARANCE = 1e-5
"""The smallest journal clearance ratio c/R a case may give: steel's thermal expansion, 1.2e-5 per K,
changes the radial clearance by about 1.2e-5 R per kelvin between journal and bearing, so a c/R below
1e-5 would be closed by a 1 K temperature difference; machined bearings run at c/R near 1e-3.  (Films
between balls or on sliders have no such floor: their thickness is set by the load, not machined.)"""

# ---------------------------------------------------------------------------
# the other tables


class MeshModel(CaseTable):
    """Domain and discretisation.  ``domain = "auto"``: sliders -> interval
    [0, length] (rectangle when ``y`` is given), journal -> journal (periodic
    in theta, [0, 2 pi R) x [-L/2, L/2]), spheres/ellipsoid -> disk of ``radius``,
    cylinder -> interval ``x``."""

    domain: Literal["auto", "interval", "rectangle", "disk", "journal"] = "auto"
    x: Extent | None = None
    y: Extent | None = None
    nx: PositiveInt = 100
    ny: PositiveInt = 20
    cell: Literal["quad", "tri"] = "quad"
    radius: PositiveLength | None = None
    refinements: Annotated[int, Field(strict=True, ge=0, le=8)] = 4
    element: Literal["P1", "P2"] = "P1"


class MotionModel(CaseTable):
    velocity_lower: VelocityVector = [0.0]
    velocity_upper: VelocityVector | None = None
    speed: Q("angular velocity") | None = None
    squeeze: Velocity | None = None
    approach_velocity: Velocity | None = None
    mode_velocities: dict[str, Velocity] = {}

    @model_validator(mode="after")
    def _exclusive(self):
        if self.approach_velocity is not None:
            if self.squeeze is not None:
                raise rule("approach_velocity", self.approach_velocity,
                           "cannot be combined with squeeze (squeeze = -approach_velocity); give one")
            self.squeeze, self.approach_velocity = -self.approach_velocity, None
        if self.squeeze is None:
            self.squeeze = 0.0
        if self.speed is not None and self.velocity_upper is not None:
            raise rule("speed", self.speed, "cannot be combined with velocity_upper (speed sets the journal surface velocity)")
        return self


class ViscosityModel(CaseTable):
    """constant: eta0; barus: eta0, alpha; roelands: eta0 and one of alpha, z."""

    law: Literal["constant", "barus", "roelands"] = "constant"
    eta0: Q("dynamic viscosity", gt=0)
    alpha: Q("inverse pressure", ge=0) | None = None
    z: Q("dimensionless", gt=0) | None = None

    @model_validator(mode="after")
    def _law_keys(self):
        if self.law == "constant":
            for key in ("alpha", "z"):
                if getattr(self, key) is not None:
                    raise rule(key, getattr(self, key), "is not used by law = 'constant'; use law = 'barus' or 'roelands'")
        elif self.law == "barus":
            if self.z is not None:
                raise rule("z", self.z, "is not used by law = 'barus' (give alpha)")
            if self.alpha is None:
                raise rule("alpha", None, "is required by law = 'barus' (pressure-viscosity coefficient, e.g. '1.85e-8 m^2/N')")
        elif (self.alpha is None) == (self.z is None):
            raise rule("alpha", self.alpha, "law = 'roelands' needs exactly one of alpha or z")
        return self


def _viscosity_shorthand(value):
    return value if isinstance(value, dict) else {"law": "constant", "eta0": value}


class DensityModel(CaseTable):
    """incompressible: rho0; dowson_higginson: rho0 (1 + a p / (1 + b p))."""

    law: Literal["incompressible", "dowson_higginson"] = "incompressible"
    rho0: Q("density", gt=0) = 1000.0
    a: Q("inverse pressure", ge=0) | None = None
    b: Q("inverse pressure", ge=0) | None = None

    @model_validator(mode="after")
    def _law_keys(self):
        if self.law == "incompressible":
            for key in ("a", "b"):
                if getattr(self, key) is not None:
                    raise rule(key, getattr(self, key), "is not used by law = 'incompressible'")
        else:
            self.a = DowsonHigginson.a if self.a is None else self.a  # the law's published constants
            self.b = DowsonHigginson.b if self.b is None else self.b
        return self


class HerschelBulkleyModel(CaseTable):
    """Herschel-Bulkley (grease) Poiseuille flow (EHL scenes only; :class:`lubedyn.lubrication.laws.lubricant.
    HerschelBulkleyFlow`): yield_stress tau_y, exponent n in (0, 2], creep eps in [0, 1) (0: the exact law).
    The [lubricant.viscosity] law is then the consistency phi(p): eta0 = phi0, its SI number in Pa s^n
    written as Pa s (paper A Table 2), alpha of phi = phi0 exp(alpha p)."""

    yield_stress: Q("pressure", ge=0)
    exponent: Q("dimensionless", gt=0, le=2)
    creep: Q("dimensionless", ge=0, lt=1) = 0.0


Viscosity = Annotated[ViscosityModel, BeforeValidator(_viscosity_shorthand)]
"""``[lubricant.viscosity]``: a table (law, eta0, alpha, z) or the shorthand ``viscosity = "0.1 Pa s"``
(law = "constant")."""


class LubricantModel(CaseTable):
    """The oil of every scene, one table with one spelling (film, EHL, map, dynamics, tapered scenes):
    viscosity, density; eyring_stress tau0 (EHL scenes only): Reynolds-Eyring shear thinning of the
    Poiseuille flow (:mod:`lubedyn.lubrication.laws.lubricant`), omitted = Newtonian; herschel_bulkley (EHL
    scenes only): [lubricant.herschel_bulkley] yield_stress, exponent, creep, Herschel-Bulkley (grease)
    Poiseuille flow with the viscosity law as the consistency phi(p); at most one of the two.  The
    bearing-dynamics scenes read :meth:`barus` of it (their films and traction take Barus' law); the
    tapered scene adds its grease's keys to the same table (:class:`lubedyn.scenes.tapered.LubricantTable`)."""

    viscosity: Viscosity
    density: DensityModel = Field(default_factory=DensityModel)
    eyring_stress: Q("pressure", gt=0) | None = None
    herschel_bulkley: HerschelBulkleyModel | None = None

    @model_validator(mode="after")
    def _one_flow(self):
        if self.eyring_stress is not None and self.herschel_bulkley is not None:
            raise rule("eyring_stress", self.eyring_stress, "and [lubricant.herschel_bulkley] are two non-Newtonian "
                       "flows; give one of them")
        return self

    def barus(self, scene: str, *, grease: str = "") -> tuple[float, float]:
        """``(eta0, alpha)`` of a scene whose films and traction take Barus' law eta0 exp(alpha p) and
        nothing else of the table but the density, which their films do not read (incompressible):
        law = "constant" is alpha = 0; law = "roelands" and the EHL scenes' non-Newtonian flows are
        refused as a case rule on their key (from the case's root), since the scene would not read them.  ``grease``: where the
        scene takes a grease instead of herschel_bulkley (for the message).  ``(None, 0.0)`` where a
        scene's table may leave the viscosity out (the tapered scene's grease readings)."""
        v = self.viscosity
        if v is not None and v.law == "roelands":
            raise root_rule("lubricant.viscosity.law", v.law, f"is not read by scene = {scene!r}: its films and "
                            "traction take Barus' law; use law = 'barus' (eta0, alpha) or 'constant'")
        if self.eyring_stress is not None:
            raise root_rule("lubricant.eyring_stress", self.eyring_stress, f"is for EHL scenes; scene = {scene!r} "
                            "does not read it, remove it")
        if self.herschel_bulkley is not None:
            raise root_rule("lubricant.herschel_bulkley", None, f"is for EHL scenes; scene = {scene!r} does "
                            "not read it" + (f" ({grease})" if grease else "") + ", remove it")
        if v is None:
            return None, 0.0
        return v.eta0, (v.alpha if v.law == "barus" else 0.0)


RENAMED = {
    "films.viscosity": "lubricant.viscosity.eta0",
    "films.pressure_viscosity": "lubricant.viscosity.alpha",
    "lubricant.base_oil_viscosity": "lubricant.viscosity.eta0",
    "lubricant.pressure_viscosity": "lubricant.viscosity.alpha",
}
"""The oil's old spellings (the dynamics scene's ``[films]``, the tapered scene's ``[lubricant]``) and the
one key of :class:`LubricantModel` that replaced each."""


def refuse_renamed(data, keys=tuple(RENAMED)):
    """A ``mode="before"`` check of a case mapping ``data``: the first of ``keys`` (old spellings of
    :data:`RENAMED`) it gives is a one-line case rule naming the new key with the value rewritten,
    ``films.viscosity was renamed: write lubricant.viscosity.eta0 = "0.05 Pa s" ...``.

    The message (through :func:`format_error`): ``films.viscosity was renamed: write
    lubricant.viscosity.eta0 = "0.05 Pa s" (every scene reads its oil from one [lubricant] table)``.
    """
    for old in keys:
        value = _raw_at(data, old) if isinstance(data, dict) else None
        if value is None:
            continue
        shown = f'"{value}"' if isinstance(value, str) else show_value(value)
        law = ' and lubricant.viscosity.law = "barus"' if RENAMED[old].endswith(".alpha") else ""
        raise root_rule(old, None, f"was renamed: write {RENAMED[old]} = {shown}{law} (every scene reads its oil "
                        "from one [lubricant] table)")
    return data


class CavitationModel(CaseTable):
    model: Literal["none", "half_sommerfeld", "reynolds", "jfo"] = "none"
    pressure: Pressure = 0.0


class BoundaryModel(CaseTable):
    ambient: Pressure = 0.0
    pressures: dict[str, Pressure] = {}
    sealed: list[str] = []


class SolverModel(CaseTable):
    rtol: Q("dimensionless", gt=0, lt=1) = 1e-10
    max_iter: PositiveInt = 60
    linear_solver: Literal["auto", "direct", "amg"] = "auto"
    amg_tol: Q("dimensionless", gt=0, lt=1) = 1e-10


class OutputModel(CaseTable):
    write: list[Literal["vtu", "png"]] = ["vtu", "png"]
    film_coefficients: bool = False


def _memory_size(value):
    if value is None:
        return None

    try:
        return parse_bytes(value)
    except ValueError as exc:
        raise PydanticCustomError("quantity", "{text}", {"text": str(exc)}) from None


FILM_MAX_PRESSURE = 3e9  # Pa: validity.max_pressure of film scenes (ValidityModel)
EHL_MAX_PRESSURE = 4e9  # Pa: validity.max_pressure of EHL scenes


class BoundsModel(CaseTable):
    """``[validity]`` of every scene: ``strict`` (default true): an output outside its physical bound
    (:data:`lubedyn.bounds.BOUNDS`: a traction coefficient above 1, a fraction outside [0, 1], a film
    thicker than a tenth of the radius ...) ends the run with a one-line error (exit 1) and writes
    nothing; ``strict = false`` writes it with a WARNING listed under "Warnings" in summary.json."""

    strict: bool = True


class ValidityModel(BoundsModel):
    """Where the scene's model holds; a result outside gets a warning (logged, and listed under
    "Warnings" in summary.json), never a refusal (``strict``: see :class:`BoundsModel`, which is
    about impossible outputs, not these ranges).

    ``max_pressure``: the largest pressure the model is trusted at (film scenes 3 GPa: beyond it the
    solids of a rigid-surface film would deform and the viscosity law is extrapolated; EHL scenes
    4 GPa: about the contact-pressure limit of hardened bearing steel, ISO 76's 4.2 GPa, past which
    the Barus/Roelands laws are extrapolated beyond their measured range).  ``min_film``: the
    composite surface roughness sigma [m]; a minimum film below it means asperity contact, outside a
    full-film model (default 0.1 um where no roughness is given).  ``max_reynolds``: the largest
    film Reynolds number rho U h / eta (rho0, eta0, the fastest surface speed U and the thickest film
    h, a conservative upper bound) for laminar, inertia-free flow (default 1000)."""

    max_pressure: Q("pressure", gt=0) | None = None  # None: the scene's default (3 GPa film, 4 GPa EHL)
    min_film: Q("length", ge=0) = 1e-7
    max_reynolds: Q("dimensionless", gt=0) = 1000.0


class TimeSeriesOutput(CaseTable):
    """``[output]`` of a time-domain scene (``dynamics``, ``tapered``), the part they share:
    ``timeseries_format`` is the file of the time series, ``"netcdf"`` (default: ``timeseries.nc``,
    compressed netCDF-4 with units and provenance in its attributes, :func:`lubedyn.outputs.write_timeseries_netcdf`)
    or ``"npz"`` (``timeseries.npz``, :func:`lubedyn.outputs.write_timeseries`).  The default was chosen by
    size on the README's main job (smoke, as ``lubedyn run`` writes it): 1.29 MB against 2.2 MB."""

    timeseries_format: Literal["netcdf", "npz"] = "netcdf"

    @model_validator(mode="after")
    def _netcdf_installed(self):
        import importlib.util

        if self.timeseries_format == "netcdf":
            missing = [m for m in ("xarray", "netCDF4") if importlib.util.find_spec(m) is None]
            if missing:
                raise rule("timeseries_format", "netcdf", f"needs {' and '.join(missing)} (pip install "
                           "'lubedyn[xarray]'); or write output.timeseries_format = 'npz'")
        return self


class LimitsModel(CaseTable):
    """Size limits checked before a run allocates anything (:mod:`lubedyn.limits`).

    ``memory``: the most memory a run may need by its estimate, e.g. ``"40 GiB"`` (omitted: the
    environment variable ``LUBEDYN_MEMORY_LIMIT``, else 80 % of the memory available);
    ``map_points``: the most grid points a map scene may solve."""

    memory: Annotated[int | None, BeforeValidator(_memory_size)] = None
    map_points: PositiveInt = 1_000_000


BOUNDARIES = {
    "interval": ("left", "right"),
    "rectangle": ("left", "right", "bottom", "top"),
    "journal": ("bottom", "top"),
    "disk": ("edge",),
}


class FilmCase(CaseTable):
    """A film scene; after validation every value is SI and every default filled in."""

    scene: Literal["film"]
    description: str = ""
    gap: GapModel
    mesh: MeshModel = Field(default_factory=MeshModel)
    motion: MotionModel = Field(default_factory=MotionModel)
    lubricant: LubricantModel
    cavitation: CavitationModel = Field(default_factory=CavitationModel)
    boundary: BoundaryModel = Field(default_factory=BoundaryModel)
    solver: SolverModel = Field(default_factory=SolverModel)
    output: OutputModel = Field(default_factory=OutputModel)
    validity: ValidityModel = Field(default_factory=ValidityModel)
    limits: LimitsModel = Field(default_factory=LimitsModel)
    smoke: dict[str, Any] | None = None

    @property
    def dim(self) -> int:
        return 1 if self.mesh.domain == "interval" else 2

    @model_validator(mode="after")
    def _resolve(self, info: ValidationInfo):
        raw = context_raw(info)
        self._check_gap_scales(raw)
        if self.lubricant.eyring_stress is not None:
            raise root_rule("lubricant.eyring_stress", self.lubricant.eyring_stress, "is for EHL scenes (scene = "
                             "'ehl'); the film solver is Newtonian, remove it")
        if self.lubricant.herschel_bulkley is not None:
            raise root_rule("lubricant.herschel_bulkley", self.lubricant.herschel_bulkley.model_dump(),
                             "is for EHL scenes (scene = 'ehl'); the film solver is Newtonian, remove it")
        self._resolve_domain()
        self._check_mesh_scales(raw)
        self._resolve_motion()
        self._check_boundaries()
        if self.validity.max_pressure is None:
            self.validity.max_pressure = FILM_MAX_PRESSURE
        return self

    def _check_gap_scales(self, raw):
        """Every film thickness of the gap thin against the lengths it spreads over (THIN_FILM), a
        pocket's depth against the pocket's width, and a journal's clearance above its thermal floor."""
        g = self.gap

        def q(key):
            return Scaled(f"gap.{key}", getattr(g, key))

        for film, length in FILM_LENGTHS[g.type]:
            raise_scale(thin_film(raw, q(film), q(length)))
        if g.type == "pocketed_slider":
            width = Scaled("gap.pocket_end - gap.pocket_start", g.pocket_end - g.pocket_start, given=False)
            raise_scale(thin_film(raw, q("depth"), width, "depth/(pocket width)"))
        if g.type == "journal":
            raise_scale(check_scale(raw, "clearance/radius", lambda v: v["gap.clearance"] / v["gap.radius"],
                                    [q("clearance"), q("radius")], limit=JOURNAL_MIN_CLEARANCE, lower=True,
                                    blame=["gap.radius", "gap.clearance"],
                                    why="1 K between journal and bearing would close it: steel expands "
                                        "1.2e-5 of the radius per kelvin"))

    def _check_mesh_scales(self, raw):
        """The film domain on its body: a slider's within the pad's length of the origin, a curved
        gap's inside the body's radius along each axis."""
        m, g = self.mesh, self.gap
        if g.type in SLIDERS and m.x is not None:
            raise_scale(check_scale(raw, "max |x|/length", lambda v: v["mesh.x"] / v["gap.length"],
                                    [Scaled("mesh.x", max(abs(m.x[0]), abs(m.x[1]))), Scaled("gap.length", g.length)],
                                    limit=1.0 + 1e-9, why="the film lies under the pad [0, length]"))
        if g.type not in BODY_RADII:
            return
        rx, ry = BODY_RADII[g.type]
        if g.type == "sphere_sphere" and g.radius2 < g.radius1:
            rx = ry = "radius2"
        checks = [("mesh.radius", m.radius, rx), ("mesh.radius", m.radius, ry)] if m.domain == "disk" else [
            ("mesh.x", m.x, rx), ("mesh.y", m.y, ry)]
        for key, extent, radius in checks:
            if extent is None or radius is None:
                continue
            size = max(abs(extent[0]), abs(extent[1])) if isinstance(extent, list) else extent
            body = Scaled(f"gap.{radius}", getattr(g, radius))
            raise_scale(check_scale(raw, f"{key}/{body.key}", lambda v, k=key: v[k] / v[body.key],
                                    [Scaled(key, size), body], limit=1.0, strict=True, why=BODY_ENDS_WHY))

    def _resolve_domain(self):
        m, g = self.mesh, self.gap
        if m.domain == "auto":
            if g.type == "journal":
                m.domain = "journal"
            elif g.type in SLIDERS:
                m.domain = "rectangle" if m.y is not None else "interval"
            elif g.type in ROUND:
                m.domain = "disk"
            else:
                m.domain = "rectangle" if m.y is not None else "interval"
        if (m.domain == "journal") != (g.type == "journal"):
            raise root_rule("mesh.domain", m.domain, f"and gap.type = {g.type!r} do not go together: the journal "
                             "domain (periodic in theta) is for gap.type = 'journal' only, and a journal needs it")
        if m.domain in ("interval", "rectangle") and m.x is None:
            if g.type in SLIDERS:
                m.x = [0.0, g.length]
            else:
                raise root_rule("mesh.x", None, f"is required for domain = {m.domain!r} with gap.type = {g.type!r} "
                                 "(e.g. x = ['-1 mm', '1 mm'])")
        if m.domain == "rectangle" and m.y is None:
            raise root_rule("mesh.y", None, "is required for domain = 'rectangle' (e.g. y = ['-5 mm', '5 mm'])")
        for key in ("x", "y"):
            ext = getattr(m, key)
            if ext is not None and not ext[1] > ext[0]:
                raise root_rule(f"mesh.{key}", ext, "must be [lo, hi] with hi > lo")
        if m.domain == "journal" and m.nx < JOURNAL_MIN_NX:
            # measured: nx = 1 -> scikit-fem "duplicate index" (an element is its own periodic neighbour),
            # nx = 2 -> the two cells share both seams and the boundaries are lost; nx = 3 solves
            raise root_rule("mesh.nx", m.nx, f"must be >= {JOURNAL_MIN_NX} for a journal (periodic in theta: with "
                             "fewer cells around the circumference an element meets itself across the seam)")
        if m.domain == "disk" and m.radius is None:
            raise root_rule("mesh.radius", None, "is required for domain = 'disk' (the film's outer radius, e.g. '0.3 mm')")
        unused = {"interval": ("y", "radius"), "rectangle": ("radius",), "journal": ("x", "y", "radius"),
                  "disk": ("x", "y")}[m.domain]
        for key in unused:
            if getattr(m, key) is not None:
                raise root_rule(f"mesh.{key}", getattr(m, key), f"is not used by domain = {m.domain!r}")

    def _resolve_motion(self):
        mo, dim = self.motion, self.dim
        if mo.speed is not None and self.gap.type != "journal":
            raise root_rule("motion.speed", mo.speed, "is for gap.type = 'journal' only; give velocity_lower/velocity_upper")
        for key in ("velocity_lower", "velocity_upper"):
            vec = getattr(mo, key)
            if vec is None:
                continue
            if len(vec) == 1 and dim == 2:
                vec = [vec[0], 0.0]
            if len(vec) != dim:
                raise root_rule(f"motion.{key}", vec, f"must have {dim} component(s) for a {dim}-D film "
                                 f"(domain = {self.mesh.domain!r})")
            setattr(mo, key, vec)
        if mo.velocity_upper is None and mo.speed is None:
            mo.velocity_upper = [0.0] * dim
        modes = ("x", "y") if self.gap.type == "journal" else ("h0",)
        for name in mo.mode_velocities:
            if name not in modes:
                raise root_rule(f"motion.mode_velocities.{name}", mo.mode_velocities[name],
                                 f"is not a mode of gap.type = {self.gap.type!r}; modes: {', '.join(modes)}"
                                 + did_you_mean(name, modes))

    def _check_boundaries(self):
        names = BOUNDARIES[self.mesh.domain]
        b = self.boundary
        for name, value in b.pressures.items():
            if name not in names:
                raise root_rule(f"boundary.pressures.{name}", value, f"names no boundary of domain = "
                                 f"{self.mesh.domain!r}; boundaries: {', '.join(names)}" + did_you_mean(name, names))
        for name in b.sealed:
            if name not in names:
                raise root_rule("boundary.sealed", name, f"names no boundary of domain = {self.mesh.domain!r}; "
                                 f"boundaries: {', '.join(names)}" + did_you_mean(name, names))
            if name in b.pressures:
                raise root_rule("boundary.sealed", name, "is also given a pressure in boundary.pressures")
        if set(b.sealed) >= set(names):
            raise root_rule("boundary.sealed", b.sealed, "seals every boundary: the pressure would be undetermined")


def root_rule(key, value, text):
    return PydanticCustomError("case_rule", "{text}", {"key": key, "value": value, "text": text, "root": True})


def case_model(scene: str):
    """The pydantic model of a scene's case (``CaseModel`` of its module in :data:`lubedyn.scenes.SCENES`,
    imported when needed)."""
    try:
        return scenes.get(scene).CaseModel
    except InputError as exc:
        raise CaseError(str(exc)) from None


# ---------------------------------------------------------------------------
# error messages


def _unwrap(annotation):
    """The model class(es) behind an annotation (through Annotated, Optional, list, dict)."""
    origin = typing.get_origin(annotation)
    if origin is Annotated:
        return _unwrap(typing.get_args(annotation)[0])
    if origin in (Union, types.UnionType):
        found = []
        for arg in typing.get_args(annotation):
            sub = _unwrap(arg)
            if isinstance(sub, tuple):
                found.extend(sub)
            elif sub is not None:
                found.append(sub)
        return tuple(found) if len(found) > 1 else (found[0] if found else None)
    if origin in (list, dict):
        return ("container", _unwrap(typing.get_args(annotation)[-1]))
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    return None


def _metadata(annotation) -> list:
    if typing.get_origin(annotation) is Annotated:
        return list(annotation.__metadata__)
    return []


def _locate(root, loc):
    """Walk ``loc`` from model ``root``: (model at the end or None, display path)."""
    current, path = root, []
    for part in loc:
        if isinstance(current, tuple) and current and current[0] == "container":
            path.append(f"[{part}]" if isinstance(part, int) else f".{part}")
            current = current[1]
            continue
        if isinstance(current, tuple):  # a tagged union: this part is the tag
            tagged = [m for m in current if part in typing.get_args(m.model_fields.get("type").annotation)]
            current = tagged[0] if tagged else None
            continue
        if isinstance(part, int):
            path.append(f"[{part}]")
            current = None
            continue
        path.append(f".{part}" if path else str(part))
        if isinstance(current, type) and issubclass(current, BaseModel) and part in current.model_fields:
            current = _unwrap(current.model_fields[part].annotation)
        else:
            current = None
    return current, "".join(path)


def show_value(value) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, dict):
        return "{table}"
    return repr(value)


def _expected_list(text: str) -> list[str]:
    return re.findall(r"'([^']*)'", text)


def format_error(error: dict, root=None) -> str:
    """One line for one pydantic error dict."""
    root = root or FilmCase
    kind, loc, value, ctx = error["type"], error["loc"], error.get("input"), error.get("ctx") or {}
    model, path = _locate(root, loc)
    if kind == "case_rule":
        key = ctx["key"] if ctx.get("root") or not path else f"{path}.{ctx['key']}"
        shown = "" if ctx.get("value") is None else f" = {show_value(ctx['value'])}"
        return f"{key}{shown} {ctx['text']}"
    if kind == "quantity":
        return f"{path} = {show_value(value)} {ctx['text']}"
    if kind == "extra_forbidden":
        parent, ppath = _locate(root, loc[:-1])
        allowed = list(parent.model_fields) if isinstance(parent, type) else []
        hint = did_you_mean(loc[-1], allowed)
        where = f" in [{ppath}]" if ppath else " at the top level"
        return f"{path}: unknown key{where}{hint}" + (f" (allowed: {', '.join(allowed)})" if allowed else "")
    if kind == "missing":
        parent, _ = _locate(root, loc[:-1])
        hint = ""
        if isinstance(parent, type) and loc[-1] in parent.model_fields:
            info = parent.model_fields[loc[-1]]
            dims = [m for m in _metadata(info.annotation) + list(info.metadata) if isinstance(m, Dimension)]
            if dims:
                hint = f" ({dims[0]}: a number in {si_unit(dims[0])} or a string with units)"
            elif typing.get_origin(info.annotation) is Literal:
                hint = f" (one of {', '.join(map(repr, typing.get_args(info.annotation)))})"
        return f"{path} is required{hint}"
    if kind == "literal_error":
        allowed = _expected_list(ctx.get("expected", ""))
        return f"{path} = {show_value(value)} is not allowed; choose one of {', '.join(map(repr, allowed))}" + did_you_mean(value, allowed)
    if kind == "union_tag_invalid":
        allowed = _expected_list(ctx.get("expected_tags", ""))
        return (f"{path}.type = {ctx.get('tag')!r} is not allowed; choose one of "
                f"{', '.join(map(repr, allowed))}" + did_you_mean(ctx.get("tag"), allowed))
    if kind == "union_tag_not_found":
        tags = [t for m in (model if isinstance(model, tuple) else ()) if isinstance(m, type)
                for t in typing.get_args(m.model_fields["type"].annotation)]
        return f"{path}.type is required; choose one of {', '.join(map(repr, tags))}"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        op = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<", "less_than_equal": "<="}[kind]
        bound = next(iter(ctx.values()))
        return f"{path} = {show_value(value)} must be {op} {bound}"
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        return f"{path} = {show_value(value)} must be a table"
    if kind in ("too_short", "too_long"):
        return f"{path} = {show_value(value)} must have {ctx.get('min_length', ctx.get('max_length'))} items"
    nice = {"int_type": "must be an integer", "int_from_float": "must be an integer", "int_parsing": "must be an integer",
            "bool_type": "must be true or false", "bool_parsing": "must be true or false",
            "string_type": "must be a string", "list_type": "must be a list", "float_type": "must be a number",
            "float_parsing": "must be a number"}
    return f"{path} = {show_value(value)} {nice.get(kind, error['msg'])}"


def format_validation_error(exc: ValidationError, root=None) -> str:
    # an unknown key first: it is usually the misspelling behind a "required" error
    errors = sorted(exc.errors(), key=lambda e: e["type"] != "extra_forbidden")
    line = format_error(errors[0], root)
    if len(errors) > 1:
        line += f" (and {len(errors) - 1} more error{'s' if len(errors) > 2 else ''})"
    return line


# ---------------------------------------------------------------------------
# loading


def deep_merge(base: dict, over: dict) -> dict:
    """``base`` updated recursively with ``over`` (a new dict)."""
    out = copy.deepcopy(base)
    for key, value in over.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = deep_merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def parse_override(text: str) -> tuple[list[str], Any]:
    """``"mesh.nx=40"`` -> (["mesh", "nx"], 40); values are TOML, else strings."""
    if "=" not in text:
        raise CaseError(f"--set {text!r} must be KEY=VALUE, e.g. --set mesh.nx=40")
    key, raw = (s.strip() for s in text.split("=", 1))
    parts = key.split(".")
    if not all(parts):
        raise CaseError(f"--set {text!r}: {key!r} is not a dotted key")
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw
    return parts, value


def apply_overrides(raw: dict, overrides) -> dict:
    out = copy.deepcopy(raw)
    for text in overrides:
        parts, value = parse_override(text)
        node = out
        for i, part in enumerate(parts[:-1]):
            nxt = node.setdefault(part, {})
            if not isinstance(nxt, dict):
                raise CaseError(f"--set {text!r}: {'.'.join(parts[: i + 1])} = {show_value(nxt)} is not a table")
            node = nxt
        node[parts[-1]] = value
    return out


_TOML_AT = re.compile(r"\(at line (\d+), column (\d+)\)")
_NUMBER_BEFORE = re.compile(r"(?:^|[=\[,{])\s*([-+]?(?:\d[\d_]*\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*$")
_UNIT_AFTER = re.compile(r"^([A-Za-z\u00b5\u03bc\u00b0%][^,\]}#\"']*?)\s*(?:[,\]}#]|$)")


def _toml_hint(text: str, message: str) -> str:
    """``; quantities with units are TOML strings: write "50 um"`` when the TOML error sits at a unit
    written after a bare number (``clearance = 50 um``), else ``""``.

    >>> _toml_hint("clearance = 50 um", "Expected newline ... (at line 1, column 16)")
    '; quantities with units are TOML strings: write "50 um"'
    """
    at = _TOML_AT.search(message)
    if not at:
        return ""
    lines = text.splitlines()
    row, col = int(at.group(1)) - 1, int(at.group(2)) - 1
    if not 0 <= row < len(lines):
        return ""
    line = lines[row]
    number, unit = _NUMBER_BEFORE.search(line[:col]), _UNIT_AFTER.match(line[col:])
    if not (number and unit):
        return ""
    return f'; quantities with units are TOML strings: write "{number.group(1)} {unit.group(1).strip()}"'


def parse_toml(text: str, source: str = "") -> dict:
    """The mapping of a case's TOML ``text`` (``source``: the file, for messages); a leading UTF-8
    byte-order mark, which TOML does not allow but some editors write, is skipped (logged at DEBUG);
    a syntax error is a :class:`CaseError` (``invalid TOML: ...``, with a hint when it sits at a unit
    written without quotes)."""
    if text.startswith("\ufeff"):
        log.debug("%s: skipped the UTF-8 byte-order mark at its start (TOML allows none)", source or "case text")
        text = text[1:]
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message = " ".join(str(exc).split())
        where = f"{source}: " if source else ""
        raise CaseError(f"{where}invalid TOML: {message}{_toml_hint(text, message)}") from None


def read_toml(path) -> dict:
    path = Path(path)
    if not path.is_file():
        hint = ""
        if (CASES_DIR / f"{path.stem}.toml").is_file() and path.suffix in ("", ".toml"):
            hint = f"; the bundled case is {CASES_DIR / (path.stem + '.toml')}"
        raise CaseError(f"case file {str(path)!r} not found{hint}")
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise CaseError(f"{path}: not a UTF-8 text file") from None
    return parse_toml(text, str(path))


def validate_raw(raw: dict, *, smoke: bool = False, overrides=()) -> CaseTable:
    """Merge the smoke table (if ``smoke``) and the overrides, fill in the values of the case's
    parameter set (``parameters = "Zhang2024"``: :func:`lubedyn.papers.apply_parameter_set`; the
    file and the overrides win), then validate.

    Overrides of the ``[smoke]`` table itself (``--set smoke.mesh.nx=8``) are applied to it before
    it is merged, so that they take part in the smoke variant (and its validation) as if the file
    said them; every other override is applied after the merge."""
    overrides = list(overrides)
    to_smoke = [o for o in overrides if parse_override(o)[0][0] == "smoke"]
    raw = apply_overrides(raw, to_smoke)
    if smoke and isinstance(raw.get("smoke"), dict):
        raw = deep_merge(raw, raw["smoke"])
    raw = apply_overrides(raw, [o for o in overrides if o not in to_smoke])
    scene = raw.get("scene")
    if scene is None:
        raise CaseError(f"scene is required; choose one of {', '.join(map(repr, scenes.SCENES))}")
    if scene not in scenes.SCENES:
        raise CaseError(f"scene = {show_value(scene)} is not allowed; choose one of {', '.join(map(repr, scenes.SCENES))}"
                        + did_you_mean(scene, list(scenes.SCENES)))
    set_name = raw.get("parameters")
    named_set = set_name is not None
    try:
        raw = apply_parameter_set(raw)
    except InputError as exc:
        raise CaseError(str(exc)) from None
    model = case_model(scene)
    try:
        case = model.model_validate(raw, context={"raw": raw})  # the raw values: bare numbers (check_scale)
    except ValidationError as exc:
        text = format_validation_error(exc, model)
        if " is required" in text and not named_set:
            sets = [n for n in PARAMETER_SETS if scene in parameter_set(n).SCENES]
            if sets:
                text += (f"; or name a paper's values: parameters = {sets[0]!r} (sets for scene = {scene!r}: "
                         f"{', '.join(map(repr, sets))}; lubedyn.papers)")
        raise CaseError(text) from None
    case._parameter_set = set_name
    return case


def load_case(path, *, smoke: bool = False, overrides=()) -> CaseTable:
    """Read, merge and validate a case file (a path, or the name of a bundled case: ``"journal_finite"``);
    raise :class:`CaseError` on any mistake."""
    return validate_raw(read_toml(case_path(str(path))), smoke=smoke, overrides=overrides)


def load_case_text(text: str, **kwargs) -> CaseTable:
    return validate_raw(parse_toml(text), **kwargs)


# ---------------------------------------------------------------------------
# case files by path or bundled name, as the command line and the study runner load them


def case_path(text: str) -> Path:
    """The case file of ``text``: a path, or the name of a bundled case (with "did you mean")."""
    path = Path(text)
    if path.is_dir():
        raise CaseError(f"case file {text!r} is a directory; expected a .toml case file")
    if not path.exists() and path.suffix == "" and (CASES_DIR / f"{text}.toml").is_file():
        return CASES_DIR / f"{text}.toml"
    if path.exists():
        return path
    if path.suffix in ("", ".toml") and len(path.parts) == 1:
        hint = did_you_mean(path.stem, [p.stem for p in bundled_cases()])
        if hint:
            raise CaseError(f"case file {text!r} not found, nor a bundled case of that name{hint} "
                            "('lubedyn cases' lists them)")
    if path.parent.is_dir():  # a typo in a path: the case files next to it
        siblings = {p.name: p for p in path.parent.glob("*.toml")}
        close = close_matches(path.name, siblings)
        if close:
            raise CaseError(f"case file {text!r} not found; did you mean "
                            f"{' or '.join(repr(str(siblings[c])) for c in close)}?")
    return path


def _smoke_keys(table: dict, prefix: str = "") -> list[str]:
    """Dotted keys of the values of a (nested) ``[smoke]`` table."""
    keys = []
    for key, value in table.items():
        if isinstance(value, dict):
            keys += _smoke_keys(value, prefix + key + ".")
        else:
            keys.append(prefix + key)
    return keys


def in_smoke(exc, raw: dict) -> Exception:
    """``exc`` (an error of the ``[smoke]`` variant only) re-worded to say so: ``smoke.KEY ...`` when it
    names a key that the ``[smoke]`` table sets, else ``in [smoke]: ...``."""
    text = " ".join(str(exc).split())
    keys = sorted(_smoke_keys(raw.get("smoke") or {}), key=len, reverse=True)
    for key in keys:
        if text.startswith(key) and text[len(key):len(key) + 1] in (" ", ":", ".", "[", ""):
            return CaseError(f"smoke.{text}")
    return CaseError(f"in [smoke]: {text}")


def check_smoke(raw: dict, overrides, exc) -> Exception:
    """``exc`` raised by the ``--smoke`` variant of a case: if the case without its ``[smoke]`` table
    validates and builds, the error lives in ``[smoke]`` and is re-worded to say so."""
    if not isinstance(raw.get("smoke"), dict):
        return exc
    try:
        base = validate_raw(raw, smoke=False, overrides=overrides)
        scenes.get(base.scene).build(base)
    except InputError:
        return exc  # the error is not the smoke table's alone
    return in_smoke(exc, raw)


def load_case_file(case: str, *, smoke: bool = False, overrides=()):
    """(path, raw TOML mapping, validated case) of ``case`` (a path or a bundled case's name) with the
    ``[smoke]`` table (``smoke``) and the ``--set`` ``overrides`` merged, as ``lubedyn run`` loads it;
    an error that only the ``[smoke]`` variant has is worded to say so.  Raises InputError."""
    overrides = list(overrides or ())
    path = case_path(case)
    try:
        raw = read_toml(path)
    except OSError as exc:  # e.g. no read permission: an input error, not a failed run
        raise CaseError(f"case file {str(path)!r} cannot be read: {exc.strerror or exc}") from None
    try:
        return path, raw, validate_raw(raw, smoke=smoke, overrides=overrides)
    except InputError as exc:
        if smoke:
            raise check_smoke(raw, overrides, exc) from None
        raise


def resolved_toml(case: CaseTable, header: str = "") -> str:
    """The case with every default filled in, every quantity in SI, as TOML."""
    import tomli_w

    data = case.model_dump(exclude_none=True, exclude={"smoke"})
    lines = [f"# {line}" if line else "#" for line in header.splitlines()]
    if case._parameter_set:
        lines.append(f"# Values not given by the case file come from parameters = {case._parameter_set!r} "
                     f"(lubedyn.papers.{case._parameter_set.lower()}.parameters).")
    lines.append("# Resolved case: every value in SI (m, s, kg, Pa, Pa s, m/s, rad/s, rad, 1/Pa, kg/m^3),")
    lines.append("# every default filled in. It is itself a valid case file.")
    return "\n".join(lines) + "\n\n" + tomli_w.dumps(data)


def bundled_cases() -> list[Path]:
    return sorted(CASES_DIR.glob("*.toml"))
