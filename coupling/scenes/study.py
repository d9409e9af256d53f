"""Studies: one base case run over axes of ``--set`` overrides and ensemble members, then tabulated.

A study file (TOML; ``lubedyn study STUDY.toml --out DIR``)::

    description = "load of the inclined slider against the runner speed"
    base = "inclined_slider"        # a case file relative to the study file, or a bundled case's name
    [axes]                          # any key `lubedyn run --set` accepts -> its values (units allowed)
    "motion.velocity_lower" = ["2 m/s", "5 m/s", "8 m/s"]
    [study]
    combine = "grid"                # every combination of the axes; "zip": the i-th values together;
                                    # "morris": each axis a range [low, high], a Morris screen (below)
    members = 1                     # ensemble members per point
    member_key = "initial.seed"     # the --set key given the member index 0 .. members-1 (members > 1)
    set = ["mesh.nx=20"]            # --set overrides of every run
    skip_outputs = false            # true: every run writes only case.resolved.toml and summary.json
    smoke = false                   # every run with --smoke (the CLI's --smoke sets it too)
    workers = 0                     # local processes; 0: every usable core
    scheduler = ""                  # a Dask scheduler address: the runs go there instead
    outputs = ["Load per unit width [N/m]"]   # summary.json keys to tabulate and plot
    tables = ["netcdf"]             # study.nc beside study.csv and study.json ([]: none)
    [paper]                         # published values drawn as markers on study.png
    "Load per unit width [N/m]" = { axis = "motion.velocity_lower", at = ["5 m/s"], values = [63550] }

Morris screening (``combine = "morris"``, :mod:`lubedyn.scenes.screening`): each axis is a range
``[low, high]`` (numbers or strings in one unit), ``[study.morris]`` gives ``trajectories`` r (>= 2),
``levels`` p (even), ``seed`` and ``log`` (the axes scaled in log10); the study runs r (k + 1) points of
Morris trajectories and study.json gains ``"Morris screening"``: per output and factor mu, mu* and sigma
of the elementary effects (output units per full range of the factor).

Every run of the study is a normal run folder, ``DIR/runs/<point>/m<member>/``, written by the scene's
``run`` exactly as ``lubedyn run BASE --set ... --out FOLDER`` writes it (:func:`lubedyn.config.load_case_file`
and :func:`lubedyn.scenes.runner.run_loaded`); the overrides of a run are, in order: ``output.write=[]``
(``skip_outputs``), ``set``, the point's axis values, the member index.  Before anything runs, every
run's case is validated (an error names the axis, set entry or member key and its value) and the first
one is built.  A run folder is reused when its ``summary.json`` and ``case.resolved.toml`` are those of
one finished run (the hidden ``.study-run.json`` holds their digests, written after the run) and the
resolved case equals the one the study would run now; a killed study therefore reruns only what is
missing, and a half-written folder is redone.  A run that fails is recorded with its message and the
study goes on; failed runs are tried again by the next study.  Reuse looks at the resolved case
only: after changing lubedyn itself, remove ``DIR/runs`` to recompute.

Runs go to local worker processes (those of :mod:`lubedyn.maps.sweep`: they ignore SIGINT, die with
the parent, one BLAS thread each) or, with ``scheduler``, to a Dask cluster, whose workers must see
``DIR`` at the same path.  Each run is one process's work with one BLAS thread, so the table is
bit-identical whatever the backend and worker count.

``DIR`` gets ``study.csv`` (one row per run: the axis values as given and in SI, the member, the
outputs, the run folder, the status, warnings and error), ``study.json`` (the study resolved, per
point the median, min, max, spread = max - min and standard deviation over its members of each
numeric output and how many members failed or warned, the failed and the warned runs, the machine
and timing) and ``study.png`` (per output a panel against the first axis: the median over members,
the min-max band, one line per combination of the other axes; ``[paper]`` values as markers; points
with a warned member circled in orange, points with a failed member crossed in red, points with no
finished member absent) and ``study.nc`` (the table as compressed netCDF, :func:`study_dataset`: each
output over the axes -- or the points of a zip or Morris study -- and the members, units in the
attributes; ``StudyResult.to_xarray()`` gives the same Dataset in Python), written together through a
staging folder (:func:`lubedyn.outputs.staged`).

Every run carries its health into the tables, because a study is where results are compared and a
warning left in one run folder's ``summary.json`` is a warning nobody reads: the ``status`` of a run
is ``ok``, ``ok-with-warnings`` (it finished and its summary.json lists ``"Warnings"``, e.g. a
validity range left or a resolution guard fired) or ``failed`` (its message in ``error``).  The
``warnings`` cell of study.csv is empty for a clean run, else the count and every warning's one-line
text: ``2: first text | second text`` (one cell that a spreadsheet filter and ``split(" | ")`` both
read; study.json lists them per run).  Warned runs stay in the statistics (their values are results,
flagged); each point says how many of its members warned.  Every warned run is logged (WARNING, one
line naming its folder, the count and the first warning) whether it ran now or is reused, so a
resumed study reports what a fresh one does.
"""
from __future__ import annotations

import concurrent.futures as cf
import contextlib
import csv
import hashlib
import io
import itertools
import json
import logging
import math
import os
import re
import statistics
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import Field, ValidationError, model_validator

from lubedyn.lubrication.errors import InputError, LubedynError, close_matches, did_you_mean

from lubedyn import outputs, scenes
from lubedyn.config import (CASES_DIR, CaseTable, PositiveInt, case_path, check_smoke, format_validation_error,
                            load_case_file, parse_override, read_toml, resolved_toml, rule)
from lubedyn.maps.sweep import default_workers, init_worker, run_on_dask, sigint_blocked, stop_pool
from lubedyn.scenes import screening
from lubedyn.scenes.runner import run_loaded

log = logging.getLogger(__name__)

MARKER = ".study-run.json"  # in a run folder: digests of the finished run's case and summary
MARKER_FORMAT = "lubedyn study run"
SLUG_MAX = 120  # longest folder name of a point before it is shortened with a digest
TICKS_MAX = 12  # first-axis values labelled on study.png by their given text


class StudyError(InputError):
    """A study file mistake: one line naming the key, the value and what is allowed."""


# ---------------------------------------------------------------------------
# the study file


class PaperSeries(CaseTable):
    """Published values of one output: ``values[i]`` at the value ``at[i]`` of the first axis."""

    axis: str
    at: Annotated[list[Any], Field(min_length=1)]
    values: Annotated[list[float], Field(min_length=1)]

    @model_validator(mode="after")
    def _same_length(self):
        if len(self.at) != len(self.values):
            raise rule("values", self.values, f"has {len(self.values)} entries and at has {len(self.at)}; "
                       "give one value per entry of at")
        return self


class MorrisTable(CaseTable):
    """``[study.morris]``: r trajectories on a grid of ``levels`` (even) levels from ``seed``; the axes
    of ``log`` scaled in log10 (:mod:`lubedyn.scenes.screening`)."""

    trajectories: Annotated[int, Field(strict=True, ge=2)] = 4
    levels: Annotated[int, Field(strict=True, ge=2)] = 4
    seed: Annotated[int, Field(strict=True, ge=0)] = 1
    log: list[str] = []

    @model_validator(mode="after")
    def _even(self):
        if self.levels % 2:
            raise rule("levels", self.levels, "must be even (Morris's step p/(2(p-1)) then lands on the grid)")
        return self


class StudyTable(CaseTable):
    """The ``[study]`` table: how the points combine and run, and what is tabulated."""

    combine: Literal["grid", "zip", "morris"] = "grid"
    morris: MorrisTable | None = None
    members: PositiveInt = 1
    member_key: str = "initial.seed"
    set: list[str] = []
    skip_outputs: bool = False
    smoke: bool = False
    workers: Annotated[int, Field(strict=True, ge=0)] = 0
    scheduler: str = ""
    outputs: Annotated[list[str], Field(min_length=1)]
    tables: list[Literal["netcdf"]] = ["netcdf"]  # besides study.csv and study.json: study.nc ([]: none)


class StudyFile(CaseTable):
    """A study file: the base case, the axes, the ``[study]`` table and optional ``[paper]`` values."""

    description: str = ""
    base: str
    axes: dict[str, list[Any]]
    study: StudyTable
    paper: dict[str, PaperSeries] = {}

    @model_validator(mode="after")
    def _check(self):
        if not self.base.strip():
            raise rule("base", self.base, "is empty; give a case file (relative to the study file) or a bundled case")
        if not self.axes:
            raise rule("axes", None, "needs at least one axis: a --set key and its values, "
                       "e.g. \"operating.speed\" = [\"10000 rpm\", \"15000 rpm\"]")
        if self.study.combine == "morris":
            if self.study.morris is None:
                self.study.morris = MorrisTable()
            morris = self.study.morris
            for key, values in self.axes.items():
                _check_dotted(f"axes.{key!r}", key)
            try:
                screening.design(self.axes, morris.trajectories, morris.levels, morris.seed, tuple(morris.log))
            except InputError as exc:
                raise rule("axes", None, str(exc)) from None
            if self.study.members > 1:
                raise rule("study.members", self.study.members, "must be 1 with combine = 'morris' (each "
                           "trajectory step compares two single runs)")
            self._check_paper()
            return self
        if self.study.morris is not None:
            raise rule("study.morris", None, f"is only read with combine = 'morris' (combine = {self.study.combine!r})")
        for key, values in self.axes.items():
            # a grid repeats each value of an axis with every value of the others: each must be distinct;
            # zipped axes may repeat values as long as the points (the i-th values together) differ
            _check_axis(key, values, distinct=self.study.combine == "grid")
        if self.study.combine == "zip":
            lengths = {key: len(values) for key, values in self.axes.items()}
            if len(set(lengths.values())) > 1:
                raise rule("study.combine", "zip", "needs axes of one length; they have "
                           + ", ".join(f"{k!r}: {n}" for k, n in lengths.items()) + " (or use combine = 'grid')")
            seen = {}
            for i, point in enumerate(zip(*self.axes.values())):
                text = tuple(toml_value(v) for v in point)
                if text in seen:
                    raise rule("axes", None, f"point {i + 1} repeats point {seen[text] + 1} ("
                               + ", ".join(f"{k} = {given(v)!r}" for k, v in zip(self.axes, point))
                               + "); zipped points must differ in at least one axis")
                seen[text] = i
        for i, text in enumerate(self.study.set):
            try:
                parse_override(text)
            except InputError:
                raise rule(f"study.set[{i}]", text, "must be KEY=VALUE, e.g. \"mesh.nx=40\"") from None
        if self.study.members > 1:
            _check_dotted("study.member_key", self.study.member_key)
            if self.study.member_key in self.axes:
                raise rule("study.member_key", self.study.member_key, "is also an axis; the member index "
                           "needs a key of its own")
        self._check_paper()
        return self

    def _check_paper(self):
        first = next(iter(self.axes))
        for key, series in self.paper.items():
            if key not in self.study.outputs:
                raise rule(f"paper.{key!r}", None, "is not one of study.outputs ("
                           + ", ".join(map(repr, self.study.outputs)) + ")" + did_you_mean(key, self.study.outputs))
            if series.axis != first:
                raise rule(f"paper.{key!r}.axis", series.axis, f"must be the first axis {first!r} "
                           "(study.png draws every output against it)")


def _check_dotted(label: str, key: str):
    if not key or "=" in key or not all(key.split(".")):
        raise rule(label, key, "must be a dotted case key as --set takes it, e.g. \"operating.speed\"")


def _check_axis(key: str, values: list, distinct: bool = True):
    _check_dotted(f"axes.{key!r}", key)
    if not values:
        raise rule(f"axes.{key!r}", values, "has no values; give a list of one or more")
    seen = {}
    for value in values:
        if isinstance(value, dict):
            raise rule(f"axes.{key!r}", values, "must list values (numbers, strings with units, "
                       "booleans, lists), not tables")
        text = toml_value(value)
        if distinct and text in seen:
            raise rule(f"axes.{key!r}", values, f"lists {given(value)!r} twice")
        seen[text] = value


def read_study(path) -> StudyFile:
    """Read and validate a study file; raise :class:`StudyError` (one line) on any mistake."""
    path = Path(path)
    if path.is_dir():
        raise StudyError(f"study file {str(path)!r} is a directory; expected a .toml study file")
    if not path.is_file():
        hint = ""
        if path.parent.is_dir():
            siblings = {p.name: p for p in path.parent.glob("*.toml")}
            close = close_matches(path.name, siblings)
            hint = f"; did you mean {' or '.join(repr(str(siblings[c])) for c in close)}?" if close else ""
        raise StudyError(f"study file {str(path)!r} not found{hint}")
    try:
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise StudyError(f"{path}: invalid TOML: {' '.join(str(exc).split())}") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise StudyError(f"study file {str(path)!r} cannot be read: {getattr(exc, 'strerror', None) or exc}") from None
    try:
        return StudyFile.model_validate(raw)
    except ValidationError as exc:
        raise StudyError(format_validation_error(exc, StudyFile)) from None


# ---------------------------------------------------------------------------
# values, points, folders


def toml_value(value) -> str:
    """``value`` (a TOML value of an axis) as one line of TOML, the value text of a ``--set``."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)  # a TOML basic string (JSON's escapes are TOML's)
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    return str(value)  # dates and times: TOML's own text


def given(value) -> str:
    """``value`` as the user wrote it: a string as is, anything else as TOML."""
    return value if isinstance(value, str) else toml_value(value)


def points(study: StudyFile) -> list[dict]:
    """The study's points, {axis key: value} in file order: every combination (grid, last axis
    fastest) or the i-th values of every axis together (zip)."""
    if study.study.combine == "morris":
        m = study.study.morris
        return screening.design(study.axes, m.trajectories, m.levels, m.seed, tuple(m.log))[0]
    keys = list(study.axes)
    lists = [study.axes[k] for k in keys]
    combos = itertools.product(*lists) if study.study.combine == "grid" else zip(*lists)
    return [dict(zip(keys, combo)) for combo in combos]


def morris_screening(study: StudyFile, stats: list) -> dict | None:
    """``"Morris screening"`` of study.json: per output, per factor (axis) mu, mu*, sigma and the number
    of elementary effects (:func:`lubedyn.scenes.screening.effects`); None unless combine = 'morris'."""
    if study.study.combine != "morris":
        return None
    m, keys = study.study.morris, list(study.axes)
    _, X = screening.design(study.axes, m.trajectories, m.levels, m.seed, tuple(m.log))
    out = {"method": "Morris 1991 elementary effects; mu* of Campolongo et al. 2007 (lubedyn.scenes.screening)",
           "trajectories": m.trajectories, "levels": m.levels, "seed": m.seed, "log-scaled axes": list(m.log),
           "units": "output units per full range of the factor (scaled 0-1)", "outputs": {}}
    for name in study.study.outputs:
        y = [entry["outputs"][name]["median"] for entry in stats]
        out["outputs"][name] = dict(zip(keys, screening.effects(X, y, len(keys))))
    return out


def point_label(values: dict) -> str:
    """``"operating.speed=15000 rpm, films.race=none"``."""
    return ", ".join(f"{k}={given(v)}" for k, v in values.items())


def slug(values: dict) -> str:
    """A point's folder name, filesystem-safe and stable: ``operating.speed=15000rpm`` (axes joined by
    ``,``; white space dropped, other characters outside ``A-Za-z0-9._+=-`` as ``_``; a name longer
    than :data:`SLUG_MAX` keeps its head and gains a digest of the whole)."""
    parts = []
    for key, value in values.items():
        text = re.sub(r"\s+", "", given(value))
        parts.append(re.sub(r"[^A-Za-z0-9._+=-]", "_", f"{key}={text}"))
    name = ",".join(parts)
    if len(name) > SLUG_MAX:
        name = name[:SLUG_MAX - 13] + "-" + hashlib.sha1(name.encode()).hexdigest()[:12]
    return name


def _si(case, key: str):
    """The value of dotted ``key`` in the validated ``case`` (SI), JSON-able; a one-item list as its item."""
    node = case
    for part in key.split("."):
        node = node.get(part) if isinstance(node, dict) else getattr(node, part, None)
    if hasattr(node, "model_dump"):
        node = node.model_dump()
    if isinstance(node, (list, tuple)):
        node = list(node)
        return node[0] if len(node) == 1 else node
    return node


def _body(resolved: str) -> str:
    """A ``case.resolved.toml`` without its comment lines (which name the source and version)."""
    return "\n".join(line for line in resolved.splitlines() if not line.startswith("#")).strip()


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


def _message(exc: BaseException) -> str:
    """A failed run's message: lubedyn's own errors as they are, others with their type."""
    text = _one_line(exc)
    return text if isinstance(exc, LubedynError) else f"{type(exc).__name__}: {text}"


def run_warnings(summary) -> list[str]:
    """The warnings a finished run's summary lists (its ``"Warnings"``; absent: none), one line each."""
    found = summary.get("Warnings") if isinstance(summary, dict) else None
    if not found:
        return []
    return [_one_line(str(w)) for w in (found if isinstance(found, list) else [found])]


def status(result) -> str:
    """A run's status in the tables from its ``(status, payload)``: ``"ok"``, ``"ok-with-warnings"``
    (finished, its summary lists warnings) or ``"failed"``."""
    state, payload = result
    if state != "ok":
        return "failed"
    return "ok-with-warnings" if run_warnings(payload) else "ok"


def warnings_cell(warnings: list[str]) -> str:
    """study.csv's ``warnings`` cell: empty, or ``"2: first | second"`` (the count, every text)."""
    return f"{len(warnings)}: " + " | ".join(warnings) if warnings else ""


def warned_line(folder: str, warnings: list[str]) -> str:
    """The log line of a warned run: ``runs/x/m0: 2 warnings, the first: ... (all in its summary.json)``."""
    count = f"{len(warnings)} warning" + ("s, the first" if len(warnings) > 1 else "")
    return f"{folder}: {count}: {warnings[0]}" + (" (all in its summary.json)" if len(warnings) > 1 else "")


# ---------------------------------------------------------------------------
# the plan: every run validated before anything runs


@dataclass
class Run:
    """One run of the study: a point, a member, its folder (relative to DIR) and overrides."""

    index: int
    point: int
    member: int
    label: str
    folder: str
    overrides: list
    body: str  # the resolved case it runs, without comments


@dataclass
class Plan:
    base: Path
    points: list  # [{axis key: value}]
    si: list  # [{axis key: SI value}]
    runs: list  # [Run]
    paper_x: dict = field(default_factory=dict)  # output -> [first-axis SI value of each paper entry]


def _base_path(study: StudyFile, study_dir: Path) -> Path:
    """The base case: a path relative to the study file, else a bundled case's name."""
    text = study.base
    local = study_dir / text
    try:
        if local.exists() or Path(text).suffix or len(Path(text).parts) > 1:
            return case_path(str(local)).resolve()
        if (CASES_DIR / f"{text}.toml").is_file():
            return CASES_DIR / f"{text}.toml"
        return case_path(text).resolve()
    except InputError as exc:
        raise StudyError(f"base = {text!r}: {_one_line(exc)}") from None


def _smoke_keys(base: Path) -> set:
    """The dotted keys the base case's ``[smoke]`` table sets (``"integrator.duration"``)."""
    def walk(node, prefix):
        for k, v in node.items():
            key = f"{prefix}{k}"
            if isinstance(v, dict):
                yield from walk(v, key + ".")
            else:
                yield key

    smoke = read_toml(base).get("smoke")
    return set(walk(smoke, "")) if isinstance(smoke, dict) else set()


def _common(study: StudyFile, base: Path | None = None, smoke: bool = False) -> list[str]:
    """The overrides of every run: ``output.write=[]`` (skip_outputs), then ``set``.  With ``smoke``, an
    entry of ``set`` that the base case's ``[smoke]`` table also sets is left out (logged): a smoke
    study checks the study at the case's smoke size, whatever length the full study asks for."""
    kept = list(study.study.set)
    if smoke and base is not None:
        keys = _smoke_keys(base)
        dropped = [o for o in kept if ".".join(parse_override(o)[0]) in keys]
        if dropped:
            log.info("--smoke: the case's [smoke] table sets %s; study.set entries left out: %s",
                     ", ".join(sorted(keys)), ", ".join(dropped))
        kept = [o for o in kept if o not in dropped]
    return (["output.write=[]"] if study.study.skip_outputs else []) + kept


def _check_common(study: StudyFile, base: Path, smoke: bool):
    """The base case with the overrides of every run validates; else say which part does not."""
    common = _common(study, base, smoke)
    try:
        load_case_file(str(base), smoke=smoke, overrides=common)
        return
    except InputError as exc:
        error = exc
    try:
        load_case_file(str(base), smoke=smoke)
    except InputError as exc:
        raise StudyError(f"base = {study.base!r}: {_one_line(exc)}") from None
    skip = common[:1] if study.study.skip_outputs else []
    if skip:
        try:
            load_case_file(str(base), smoke=smoke, overrides=skip)
        except InputError as exc:
            raise StudyError(f"study.skip_outputs = true: {_one_line(exc)}") from None
    for i, text in enumerate(study.study.set):
        try:
            load_case_file(str(base), smoke=smoke, overrides=skip + [text])
        except InputError as exc:
            raise StudyError(f"study.set[{i}] = {text!r}: {_one_line(exc)}") from None
    raise StudyError(f"study.set = {study.study.set!r}: {_one_line(error)}") from None


def _load_labelled(base: Path, smoke: bool, common: list, labelled: list):
    """(path, raw, case) of the base with ``common`` and the (label, override) pairs; an error names
    the override that alone causes it (else all of them)."""
    try:
        return load_case_file(str(base), smoke=smoke, overrides=common + [text for _, text in labelled])
    except InputError as exc:
        error = exc
    for label, text in labelled:
        try:
            load_case_file(str(base), smoke=smoke, overrides=common + [text])
        except InputError as exc:
            raise StudyError(f"{label}: {_one_line(exc)}") from None
    raise StudyError(f"{'; '.join(label for label, _ in labelled)}: {_one_line(error)}") from None


def _labelled(study: StudyFile, values: dict, member: int) -> list:
    pairs = [(f"axes.{k!r} = {given(v)!r}", f"{k}={toml_value(v)}") for k, v in values.items()]
    if study.study.members > 1:
        key = study.study.member_key
        pairs.append((f"study.member_key = {key!r} (member {member})", f"{key}={member}"))
    return pairs


def _build_first(loaded, overrides, smoke: bool, label: str):
    """Build (not run) the first run's case as ``lubedyn validate`` does: geometry and sizes checked."""
    import inspect

    path, raw, case = loaded
    build = scenes.get(case.scene).build
    try:
        if "source" in inspect.signature(build).parameters:
            build(case, source=str(path))
        else:
            build(case)
    except InputError as exc:
        if smoke:
            exc = check_smoke(raw, overrides, exc)
        raise StudyError(f"{label}: {_one_line(exc)}") from None


def plan_study(study: StudyFile, study_path, *, smoke: bool = False) -> Plan:
    """Validate every run of the study (and build the first) before anything runs; the runs in order
    (points in order, members within a point)."""
    base = _base_path(study, Path(study_path).resolve().parent)
    _check_common(study, base, smoke)
    common, pts = _common(study, base, smoke), points(study)
    folders: dict = {}
    plan = Plan(base=base, points=pts, si=[], runs=[])
    for p, values in enumerate(pts):
        name = slug(values)
        if study.study.combine == "morris":  # trajectories may share a point: one folder per step
            name = f"t{p // (len(study.axes) + 1)}.{p % (len(study.axes) + 1)}," + name
        if name in folders:
            raise StudyError(f"axes: the points ({point_label(folders[name])}) and ({point_label(values)}) "
                             f"share the folder name {name!r}; give values that differ in more than spaces and punctuation")
        folders[name] = values
        for m in range(study.study.members):
            labelled = _labelled(study, values, m)
            loaded = _load_labelled(base, smoke, common, labelled)
            overrides = common + [text for _, text in labelled]
            if not plan.runs:
                _build_first(loaded, overrides, smoke, "; ".join(label for label, _ in labelled))
            label = point_label(values) + (f", member {m}" if study.study.members > 1 else "")
            plan.runs.append(Run(len(plan.runs), p, m, label, f"runs/{name}/m{m}", overrides,
                                 _body(resolved_toml(loaded[2]))))
        plan.si.append({k: _si(loaded[2], k) for k in values})
    first = next(iter(study.axes))
    for key, series in study.paper.items():
        xs = []
        for i, at in enumerate(series.at):
            case = _load_labelled(base, smoke, common, [(f"paper.{key!r}.at[{i}] = {given(at)!r}",
                                                         f"{first}={toml_value(at)}")])[2]
            xs.append(_si(case, first))
        plan.paper_x[key] = xs
    return plan


# ---------------------------------------------------------------------------
# running


def _mark_complete(folder: Path, cpu: float) -> dict:
    """After a run: record the digests of its case and summary (:data:`MARKER`) and the CPU seconds it
    took (``cpu``: its process's, :func:`run_one`); its summary."""
    resolved, summary = (folder / "case.resolved.toml").read_bytes(), (folder / "summary.json").read_bytes()
    outputs.write_json(folder / MARKER, {"format": MARKER_FORMAT,
                                         "case.resolved.toml": hashlib.sha256(resolved).hexdigest(),
                                         "summary.json": hashlib.sha256(summary).hexdigest(),
                                         "CPU time [s]": cpu})
    return json.loads(summary)


def run_cpu(folder: Path) -> float | None:
    """The CPU seconds a finished run took, from its marker (None for a run marked before they were kept)."""
    try:
        value = json.loads((folder / MARKER).read_text(encoding="utf-8")).get("CPU time [s]")
    except (OSError, ValueError, AttributeError):
        return None
    return float(value) if isinstance(value, (int, float)) else None


def reusable(folder: Path, body: str) -> dict | None:
    """The summary of a finished run in ``folder`` whose resolved case is ``body``, else None."""
    try:
        marker = json.loads((folder / MARKER).read_text(encoding="utf-8"))
        resolved, summary = (folder / "case.resolved.toml").read_bytes(), (folder / "summary.json").read_bytes()
        if not (isinstance(marker, dict) and marker.get("format") == MARKER_FORMAT
                and marker.get("case.resolved.toml") == hashlib.sha256(resolved).hexdigest()
                and marker.get("summary.json") == hashlib.sha256(summary).hexdigest()
                and _body(resolved.decode("utf-8")) == body):
            return None
        data = json.loads(summary)
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) else None


def run_one(spec: dict) -> tuple[str, Any, float]:
    """Worker: run one study run into its folder as ``lubedyn run`` does, with one BLAS thread;
    ("ok", summary, seconds) or ("failed", message, seconds).  Never raises an Exception (one failed
    run must not stop the others)."""
    from threadpoolctl import threadpool_limits

    t0, cpu0 = time.perf_counter(), time.process_time()
    folder = Path(spec["folder"])
    try:
        with contextlib.suppress(FileNotFoundError):
            (folder / MARKER).unlink()  # the folder is not a finished run until this run says so
        with threadpool_limits(1):
            path, raw, case = load_case_file(spec["case"], smoke=spec["smoke"], overrides=spec["overrides"])
            run_loaded(path, raw, case, folder, smoke=spec["smoke"], overrides=spec["overrides"])
        return "ok", _mark_complete(folder, time.process_time() - cpu0), time.perf_counter() - t0
    except Exception as exc:  # noqa: BLE001 - recorded in the table, reported by the caller
        return "failed", _message(exc), time.perf_counter() - t0


def _execute(specs: list, todo: list, workers: int, scheduler, accept, scheduler_key="study.scheduler") -> str:
    """Run ``specs[i]`` for i in ``todo``: in this process (one worker), local processes or Dask;
    ``accept(i, status, payload, seconds)`` as each ends.  Returns the backend's description."""
    if not todo:
        return "none needed"
    if scheduler:
        return _execute_dask(specs, todo, scheduler, accept, scheduler_key)
    workers = min(workers or default_workers(), len(todo))
    if workers <= 1:
        for i in todo:
            accept(i, *run_one(specs[i]))
        return "serial (this process)"
    import multiprocessing

    ctx = multiprocessing.get_context("fork") if hasattr(os, "fork") else None
    pool = cf.ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=init_worker,
                                  initargs=(os.getpid(),))
    try:
        with sigint_blocked():
            futures = {pool.submit(run_one, specs[i]): i for i in todo}
        for fut in cf.as_completed(futures):
            accept(futures[fut], *fut.result())
    except BaseException:  # Ctrl-C or an error: cancel the pending runs, end the workers now
        stop_pool(pool)
        raise
    pool.shutdown(wait=True)
    return f"local processes ({workers})"


def _execute_dask(specs: list, todo: list, scheduler, accept, key: str) -> str:
    """Run on a Dask cluster (:func:`lubedyn.maps.sweep.run_on_dask`): ``scheduler`` is an address, a
    Client or a cluster (``key``: where it was given, for messages)."""
    return run_on_dask(scheduler, key, [(run_one, specs[i]) for i in todo],
                       lambda k, result: accept(todo[k], *result), error=StudyError)


def check_outputs(study: StudyFile, summary: dict, folder: str):
    """Every ``study.outputs`` key is a key of ``summary`` (a run's); else a one-line StudyError."""
    for key in study.study.outputs:
        if key not in summary:
            raise StudyError(f"study.outputs: {key!r} is not a key of the runs' summary.json"
                             + (did_you_mean(key, summary) or f" (its keys: {folder}/summary.json)"))


def _duration(seconds: float) -> str:
    return f"{seconds:.2g} s" if seconds < 10 else f"{seconds:.0f} s"


@dataclass
class StudyResult:
    """What :func:`run_study` did: runs in total, reused, run now, failed (folder, message), files;
    ``warned``: the runs that finished with warnings, (folder, [warning, ...]), reused or run now."""

    out: Path
    total: int
    reused: int
    ran: int
    failed: list
    backend: str
    files: list
    warned: list = field(default_factory=list)
    table: tuple | None = field(default=None, repr=False)  # (study, plan, results) of to_xarray

    def to_xarray(self):
        """The study's table as an ``xarray.Dataset`` (:func:`study_dataset`): every output over the axes
        (grid) or the points (zip, morris) and the members, units in the attributes; what ``study.nc`` holds."""
        if self.table is None:
            raise ValueError("this study result has no table (it was made without its runs' results)")
        return study_dataset(*self.table)


def run_study(study: StudyFile, study_path, out, *, smoke: bool | None = None, workers: int | None = None,
              scheduler=None) -> StudyResult:
    """Plan, run (reusing finished runs) and tabulate a study into the folder ``out``.

    ``smoke``, ``workers``, ``scheduler``: the command line's, over the study file's (``smoke``: either
    one).  Raises :class:`StudyError` for a mistake in the study (before anything runs, or after the
    first run for an unknown output); a run that fails is recorded and the study goes on."""
    t0, started = time.perf_counter(), time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    smoke = bool(smoke) or study.study.smoke
    workers = study.study.workers if workers is None else workers
    scheduler_key = "--scheduler" if scheduler else "study.scheduler"
    scheduler = scheduler or study.study.scheduler or None
    out = Path(out).absolute()
    plan = plan_study(study, study_path, smoke=smoke)
    results: list = [None] * len(plan.runs)
    for run in plan.runs:
        summary = reusable(out / run.folder, run.body)
        if summary is not None:
            results[run.index] = ("ok", summary)
    reused = [r for r in plan.runs if results[r.index] is not None]
    todo = [r.index for r in plan.runs if results[r.index] is None]
    checked = False
    if reused:
        check_outputs(study, results[reused[0].index][1], reused[0].folder)
        checked = True
    for run in reused:  # a resumed study says again what the run said when it ran
        found = run_warnings(results[run.index][1])
        if found:
            log.warning("reused run %s", warned_line(run.folder, found))
    log.info("%d runs: %d reused (finished in %s/runs), %d to run", len(plan.runs), len(reused), out, len(todo))
    specs = [{"case": str(plan.base), "smoke": smoke, "overrides": r.overrides, "folder": str(out / r.folder)}
             for r in plan.runs]
    done = 0

    def accept(i, state, payload, seconds):
        nonlocal done, checked
        done += 1
        run = plan.runs[i]
        results[i] = (state, payload)
        if state == "ok":
            if not checked:
                check_outputs(study, payload, out / run.folder)
                checked = True
            found = run_warnings(payload)
            if found:
                log.warning("run %d/%d done with warnings (%s), %s; %s", done, len(todo), run.label,
                            _duration(seconds), warned_line(run.folder, found))
            else:
                log.info("run %d/%d done (%s), %s", done, len(todo), run.label, _duration(seconds))
        else:
            log.warning("run %d/%d failed (%s): %s", done, len(todo), run.label, payload)

    backend = _execute(specs, todo, workers, scheduler, accept, scheduler_key)
    failed = [(plan.runs[i].folder, payload) for i, (state, payload) in enumerate(results) if state != "ok"]
    warned = [(plan.runs[i].folder, run_warnings(payload)) for i, (state, payload) in enumerate(results)
              if state == "ok" and run_warnings(payload)]
    info = {"backend": backend, "workers": workers, "scheduler": scheduler if isinstance(scheduler, str) else None,
            "smoke": smoke, "total": len(plan.runs), "reused": len(reused), "ran": len(todo),
            "failed": len(failed), "ok with warnings": len(warned), "started [UTC]": started,
            "wall time [s]": time.perf_counter() - t0}
    # the CPU the study's results cost, reused runs included (each run's own process, from its marker)
    cpu = [run_cpu(out / r.folder) for r in plan.runs if results[r.index][0] == "ok"]
    known = [c for c in cpu if c is not None]
    info["CPU time of the runs [s]"] = sum(known) if known else None
    info["CPU time of the runs, runs counted"] = f"{len(known)} of {len(cpu)} finished runs"
    if known:
        log.info("CPU time of the study's %d finished runs: %s (median %s per run)", len(known),
                 _duration(sum(known)), _duration(statistics.median(known)))
    files = write_tables(study, study_path, plan, results, out, info)
    return StudyResult(out, len(plan.runs), len(reused), len(todo), failed, backend, files, warned,
                       (study, plan, results))


# ---------------------------------------------------------------------------
# tables and figure


def _cell(value) -> str:
    """A csv cell: floats by ``repr`` (they read back bit for bit), None empty, lists as JSON."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float, str)):
        return repr(value) if isinstance(value, float) else str(value)
    return json.dumps(value)


def table(study: StudyFile, plan: Plan, results: list) -> str:
    """``study.csv``: one row per run: each axis's value as given and in SI, the member, the outputs,
    the run folder (relative to the study folder), the status (:func:`status`), the warnings
    (:func:`warnings_cell`) and the error."""
    keys, names = list(study.axes), study.study.outputs
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([c for k in keys for c in (k, f"{k} [SI]")] + ["member"] + names
                    + ["run folder", "status", "warnings", "error"])
    for run, result in zip(plan.runs, results):
        values, si = plan.points[run.point], plan.si[run.point]
        ok = result[0] == "ok"
        summary = result[1] if ok else {}
        writer.writerow([c for k in keys for c in (given(values[k]), _cell(si[k]))] + [run.member]
                        + [_cell(summary.get(n)) for n in names]
                        + [run.folder, status(result), warnings_cell(run_warnings(summary)), "" if ok else result[1]])
    return buffer.getvalue()


def _number(value) -> float | None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return float(value)


def aggregates(study: StudyFile, plan: Plan, results: list) -> list[dict]:
    """Per point: its axis values, run folders, how many members failed and how many finished with
    warnings (their values are in the statistics: a reader of a point's median must know that some of
    it is flagged), and per output the finished members' values with their median, min, max, spread
    (max - min) and population standard deviation (None when no member gave a finite number)."""
    out = []
    for p, values in enumerate(plan.points):
        runs = [r for r in plan.runs if r.point == p]
        ok = [results[r.index][1] for r in runs if results[r.index][0] == "ok"]
        entry = {"axes": {k: given(v) for k, v in values.items()}, "axes [SI]": plan.si[p],
                 "run folders": [r.folder for r in runs], "members": len(runs), "failed": len(runs) - len(ok),
                 "ok with warnings": sum(1 for s in ok if run_warnings(s)), "outputs": {}}
        for name in study.study.outputs:
            numbers = [x for x in (_number(s.get(name)) for s in ok) if x is not None and math.isfinite(x)]
            stats = {"values": [s.get(name) for s in ok], "median": None, "min": None, "max": None,
                     "spread": None, "std": None}
            if numbers:  # statistics: exact sums (equal members have a std of exactly 0)
                stats.update(median=statistics.median(numbers), min=min(numbers), max=max(numbers),
                             spread=max(numbers) - min(numbers), std=statistics.pstdev(numbers))
            entry["outputs"][name] = stats
        out.append(entry)
    return out


def _machine() -> dict:
    import platform

    from lubedyn import __version__  # deferred: importlib.metadata

    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return {"host": platform.node(), "platform": platform.platform(), "python": platform.python_version(),
            "cores": f"{usable} usable of {os.cpu_count()}", "lubedyn version": __version__}


def _first_axis_x(study: StudyFile, plan: Plan):
    """x of each point on study.png: the first axis's SI value when every one is a number, else the
    index of its given value; and the ticks (positions, labels) of the first axis's values."""
    first = next(iter(study.axes))
    si = [s[first] for s in plan.si]
    numeric = all(_number(x) is not None for x in si)
    labels = [given(v) for v in study.axes[first]]
    if numeric:
        xs = [float(x) for x in si]
        by_text = {given(plan.points[p][first]): xs[p] for p in range(len(xs))}
        ticks = [by_text[t] for t in labels if t in by_text]
        return xs, (ticks, [t for t in labels if t in by_text]), True
    xs = [labels.index(given(v[first])) for v in plan.points]
    return xs, (list(range(len(labels))), labels), False


_HEALTH_MARKS = {  # study.png: a point with a warned / failed member (labelled once per panel, see _panel)
    "ok with warnings": {"marker": "o", "ms": 11, "mfc": "none", "mec": "tab:orange", "mew": 1.8,
                         "label": "with warnings (study.csv)"},
    "failed": {"marker": "x", "ms": 9, "color": "tab:red", "mew": 1.8, "label": "a member failed (study.csv)"},
}


def _panel(ax, study: StudyFile, plan: Plan, stats: list, name: str, groups: dict, first_axis) -> None:
    """One output of study.png: a line (median) and band (min-max) per group of points, paper markers."""
    xs, ticks, numeric = first_axis
    medians = [stats[p]["outputs"][name]["median"] for p in range(len(plan.points))]
    if all(m is None for m in medians):
        ax.text(0.5, 0.5, "no numeric values (see study.csv)", transform=ax.transAxes, ha="center", va="center")
    else:
        for label, members in groups.items():
            members = sorted(members, key=lambda p: xs[p])
            x = [xs[p] for p in members]
            pick = [stats[p]["outputs"][name] for p in members]
            med = [math.nan if s["median"] is None else s["median"] for s in pick]
            line, = ax.plot(x, med, "o-", label=label or ("lubedyn" if name in study.paper else None))
            if study.study.members > 1:
                lo = [math.nan if s["min"] is None else s["min"] for s in pick]
                hi = [math.nan if s["max"] is None else s["max"] for s in pick]
                ax.fill_between(x, lo, hi, color=line.get_color(), alpha=0.2, lw=0)
            for key, style in _HEALTH_MARKS.items():  # the health of each point, over its median
                marked = [(xs[p], m) for p, m in zip(members, med) if stats[p][key] and not math.isnan(m)]
                if marked:
                    ax.plot(*zip(*marked), ls="none", **style)
        with contextlib.suppress(AttributeError):  # plain values on the y axis, not "1e-9 + 750.3"
            ax.ticklabel_format(axis="y", useOffset=False)
    if name in study.paper:
        series = study.paper[name]
        px = plan.paper_x[name] if numeric else [ticks[1].index(given(a)) if given(a) in ticks[1] else math.nan
                                                 for a in series.at]
        ax.plot(px, series.values, "k*", ms=10, ls="none", label="paper")
    if len(ticks[0]) <= TICKS_MAX:
        ax.set_xticks(ticks[0], ticks[1])
    ax.set_title(name, fontsize="medium")
    ax.grid(alpha=0.3)
    handles = {}  # one legend entry per label (the health markers repeat per group of points)
    for h in ax.get_lines():
        if h.get_label() and not h.get_label().startswith("_"):
            handles.setdefault(h.get_label(), h)
    if handles:
        ax.legend(handles.values(), handles.keys(), fontsize="small")


def figure(study: StudyFile, plan: Plan, stats: list):
    """``study.png``: per output, median and min-max band over members against the first axis, one line
    per combination of the other axes (grid) or one line (zip), ``[paper]`` values as markers."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    keys, names = list(study.axes), study.study.outputs
    groups: dict = {}
    for p, values in enumerate(plan.points):
        other = point_label({k: values[k] for k in keys[1:]}) if study.study.combine == "grid" else ""
        groups.setdefault(other, []).append(p)
    first_axis = _first_axis_x(study, plan)
    ncols = min(3, len(names))  # a grid of panels, filled row by row
    nrows = -(-len(names) // ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, 3.0 * nrows + 0.8), squeeze=False)
    for k, name in enumerate(names):
        _panel(axes[k // ncols, k % ncols], study, plan, stats, name, groups, first_axis)
    for k in range(len(names), nrows * ncols):
        axes[k // ncols, k % ncols].set_visible(False)
    label = keys[0] + ("" if study.study.combine == "grid" or len(keys) == 1
                       else " (zipped with " + ", ".join(keys[1:]) + ")")
    for k in range(len(names)):
        if k + ncols >= len(names):  # the lowest panel of each column
            axes[k // ncols, k % ncols].set_xlabel(label)
    title = study.description or f"study of {plan.base.stem}"
    fig.suptitle(title + (f" ({study.study.members} members per point: median, min-max band)"
                          if study.study.members > 1 else ""), fontsize="medium")
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 1.0 - 0.5 / (3.0 * nrows + 0.8)))  # room for the title
    return fig


def _axis_unit(values: list) -> str:
    """The SI unit of an axis whose values are written with units ("5 m/s" -> "m/s"), "" when they are bare
    numbers or not quantities (the units of lubedyn.units)."""
    from lubedyn.units import UnitError, dimension_name, parse_units, si_unit

    found = set()
    for value in values:
        match = re.match(r"^\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*(\S.*?)\s*$", value) \
            if isinstance(value, str) else None
        if match is None:
            return ""
        try:
            found.add(parse_units(match.group(1))[1])
        except UnitError:
            return ""
    if len(found) != 1:
        return ""
    name = dimension_name(found.pop())
    try:
        return si_unit(name)
    except KeyError:
        return name  # an unnamed dimension: its SI units ("m^2 s")


def _table_array(values: list):
    """A study output's values as an array: floats (NaN where a run failed or gave none) when every value
    is a number, else strings ("" where none)."""
    import numpy as np

    if all(v is None or _number(v) is not None for v in values):
        return np.array([math.nan if v is None else float(v) for v in values])
    return np.array(["" if v is None else (v if isinstance(v, str) else json.dumps(v)) for v in values], dtype=str)


def study_dataset(study: StudyFile, plan: Plan, results: list, attrs: dict | None = None):
    """The study's table as an ``xarray.Dataset``, the numbers of ``study.csv``.

    Dimensions: with ``combine = "grid"`` one per axis, named by its key, its coordinate the axis's SI
    values (numbers) or the values as given (anything else), and the units when the values carry them
    ("5 m/s": ``units`` "m/s"); with "zip" or "morris" one dimension "point" with each axis a coordinate
    along it; then "member" when the study has more than one.  Variables: each output, named without its
    unit (``units`` and ``long_name`` attributes, ``column`` the full name), NaN where a run failed or
    gave no number; "status" (``ok``, ``ok-with-warnings``, ``failed``), "warnings" (the count) and "run
    folder".  The study's identity (description, base case, combine, lubedyn version) is in the attributes."""
    import numpy as np

    from lubedyn.results import import_xarray, split_unit

    xr = import_xarray()
    keys, names = list(study.axes), study.study.outputs
    members = study.study.members
    grid = study.study.combine == "grid"

    def coordinate(key, values, si):
        numeric = all(_number(x) is not None for x in si)
        data = np.array([float(x) for x in si]) if numeric else np.array([given(v) for v in values], dtype=str)
        unit = _axis_unit(values) if numeric else ""
        return data, {"long_name": key, "given": json.dumps([given(v) for v in values]),
                      **({"units": unit} if unit else {})}

    if grid:
        dims = keys
        shape = [len(study.axes[k]) for k in keys]
        first_si = {k: {} for k in keys}
        for values, si in zip(plan.points, plan.si):
            for k in keys:
                first_si[k].setdefault(toml_value(values[k]), si[k])
        coords = {}
        for k in keys:
            data, cattrs = coordinate(k, study.axes[k], [first_si[k][toml_value(v)] for v in study.axes[k]])
            coords[k] = (k, data, cattrs)
        index = {k: {toml_value(v): i for i, v in enumerate(study.axes[k])} for k in keys}

        def position(p):
            return tuple(index[k][toml_value(plan.points[p][k])] for k in keys)
    else:
        dims, shape = ["point"], [len(plan.points)]
        coords = {"point": ("point", np.arange(len(plan.points)), {"long_name": "point of the study"})}
        for k in keys:
            data, cattrs = coordinate(k, [v[k] for v in plan.points], [s[k] for s in plan.si])
            coords[k] = ("point", data, cattrs)

        def position(p):
            return (p,)
    if members > 1:
        dims, shape = dims + ["member"], shape + [members]
        coords["member"] = ("member", np.arange(members), {"long_name": f"ensemble member ({study.study.member_key})"})
    cells = int(np.prod(shape))
    flat: dict = {}  # flat index of each run in the table
    for run in plan.runs:
        where = position(run.point) + ((run.member,) if members > 1 else ())
        flat[run.index] = int(np.ravel_multi_index(where, shape))

    def table(value_of):
        values = [None] * cells
        for run in plan.runs:
            values[flat[run.index]] = value_of(run, results[run.index])
        return values

    data = {}
    for name in names:
        label, unit = split_unit(name)
        values = _table_array(table(lambda run, r: r[1].get(name) if r[0] == "ok" else None))
        data[label] = (dims, values.reshape(shape), {"units": unit, "long_name": label, "column": name})
    data["status"] = (dims, np.array(table(lambda run, r: status(r)), dtype=str).reshape(shape),
                      {"long_name": "run status: ok, ok-with-warnings or failed"})
    data["warnings"] = (dims, np.array(table(lambda run, r: len(run_warnings(r[1])) if r[0] == "ok" else 0),
                                       dtype=np.int32).reshape(shape), {"long_name": "warnings of the run", "units": "1"})
    data["run folder"] = (dims, np.array(table(lambda run, r: run.folder), dtype=str).reshape(shape),
                          {"long_name": "run folder, relative to the study folder"})
    from lubedyn import __version__  # deferred: importlib.metadata

    identity = {"format": "lubedyn study", "version": 1, "description": study.description,
                "base case": str(plan.base), "combine": study.study.combine, "members": members,
                "lubedyn version": __version__}
    return xr.Dataset(data, coords=coords, attrs={**identity, **dict(attrs or {})})


def write_tables(study: StudyFile, study_path, plan: Plan, results: list, out: Path, info: dict) -> list[Path]:
    """Write study.csv, study.json, study.nc (compressed netCDF: :func:`study_dataset`, the study file and
    the run information in its attributes; with ``study.tables`` naming "netcdf") and study.png into
    ``out`` together (staged; ``runs/`` kept)."""
    import matplotlib.pyplot as plt

    stats = aggregates(study, plan, results)
    doc = {"format": "lubedyn study", "version": 1, "study file": str(Path(study_path).resolve()),
           "base case": str(plan.base), "study": study.model_dump(), "runs": info,
           "points": stats, "failed runs": [{"run folder": r.folder, "error": results[r.index][1]}
                                            for r in plan.runs if results[r.index][0] != "ok"],
           "warned runs": [{"run folder": r.folder, "warnings": run_warnings(results[r.index][1])}
                           for r in plan.runs if status(results[r.index]) == "ok-with-warnings"],
           "run list": [{"run folder": r.folder, "point": r.point, "member": r.member, "overrides": r.overrides,
                         "status": status(results[r.index]),
                         "warnings": run_warnings(results[r.index][1]) if results[r.index][0] == "ok" else []}
                        for r in plan.runs],
           "machine": _machine(), "finished [UTC]": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
    screen = morris_screening(study, stats)
    if screen is not None:
        doc["Morris screening"] = screen
    fig = figure(study, plan, stats)
    try:
        with outputs.staged(out, keep=("runs",)) as stage:
            outputs.write_text(stage / "study.csv", table(study, plan, results))
            outputs.write_json(stage / "study.json", doc)
            if "netcdf" in study.study.tables:
                attrs = {"study file": doc["study file"], "date_created": doc["finished [UTC]"],
                         "study (resolved)": json.dumps(doc["study"], default=outputs.json_default),
                         "runs": json.dumps(info, default=outputs.json_default)}
                outputs.write_netcdf(stage / "study.nc", study_dataset(study, plan, results, attrs))
            outputs.save_figure(stage / "study.png", fig)
    finally:
        plt.close(fig)
    written = ("study.csv", "study.json") + (("study.nc",) if "netcdf" in study.study.tables else ()) + ("study.png",)
    return [out / name for name in written]
