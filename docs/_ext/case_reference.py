"""Sphinx extension: the case-file reference, generated from the pydantic case models at build time.

``.. case-reference::`` (no argument: every scene of :data:`lubedyn.scenes.SCENES`; or one scene name)
walks the scene's case model (:func:`lubedyn.config.case_model`) and writes one table per TOML table:
every key with its type or SI unit (quantities accept a number in SI or a string with units), its range
(the :class:`lubedyn.config.Bounds` of a quantity, or pydantic's ``ge``/``le`` constraints), its default
and the values allowed.  A model's docstring and the comment on a field's line in the source are shown
beside it.  Tagged unions (``[gap] type = ...``) get one table per member; ``[axes]`` and ``[params]`` of
the map scene list each map kind's axes and parameters from the kind registry
(:func:`lubedyn.maps.kinds`).  Nothing is written by hand, so the reference cannot drift from the code;
``tests/test_docs.py`` checks that every key of every bundled case, resolved, is listed.

:func:`rows` is the walk itself (used by the directive and the test).
"""
from __future__ import annotations

import functools
import inspect
import re
import types
import typing
from dataclasses import dataclass
from typing import Annotated, Any, Literal, Union

from docutils import nodes
from docutils.parsers.rst import Directive
from docutils.statemachine import StringList
from pydantic import BaseModel
from pydantic_core import PydanticUndefined


@dataclass
class Row:
    """One key of a case table."""

    table: str   # dotted table path ("" for the top level), e.g. "lubricant.viscosity"
    key: str
    kind: str    # type or unit
    range: str
    default: str
    allowed: str
    note: str

    @property
    def path(self) -> str:
        return f"{self.table}.{self.key}" if self.table else self.key


@functools.lru_cache(maxsize=None)
def _comments(model) -> types.MappingProxyType:
    """The comment on each field's line in the class source (``name: T = x  # comment``), read-only.
    Cached per class: ``inspect.getsource`` of a class parses its whole module, and :func:`rows` asks
    for the same classes once per table of every scene (660 calls, 46 of the 53 s the reference's tests
    took, before the cache)."""
    try:
        source = inspect.getsource(model)
    except (OSError, TypeError):
        return types.MappingProxyType({})
    found = {}
    for line in source.splitlines():
        m = re.match(r"\s{4}(\w+)\s*:[^#]*#\s*(.+)$", line)
        if m and m.group(1) in model.model_fields:
            found[m.group(1)] = m.group(2).strip()
    return types.MappingProxyType(found)


def _split(annotation):
    """(base annotation, metadata list, optional?) through Annotated and ``X | None``."""
    meta, optional = [], False
    while True:
        origin = typing.get_origin(annotation)
        if origin is Annotated:
            meta.extend(annotation.__metadata__)
            annotation = typing.get_args(annotation)[0]
            continue
        if origin in (Union, types.UnionType):
            args = [a for a in typing.get_args(annotation) if a is not type(None)]
            if len(args) < len(typing.get_args(annotation)):
                optional = True
            if len(args) == 1:
                annotation = args[0]
                continue
        return annotation, meta, optional


def _models_in(annotation) -> list:
    """The BaseModel classes an annotation is (a single model, or the members of a union)."""
    base, _, _ = _split(annotation)
    if isinstance(base, type) and issubclass(base, BaseModel):
        return [base]
    if typing.get_origin(base) in (Union, types.UnionType):
        out = []
        for arg in typing.get_args(base):
            out.extend(_models_in(arg))
        return out
    return []


def _fmt(value) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, BaseModel):
        return "(table)"
    return repr(value)


def _describe(annotation, metadata) -> tuple[str, str, str]:
    """(type or unit, range, allowed values) of a leaf annotation."""
    from lubedyn.config import Bounds, Dimension
    from lubedyn.units import si_unit

    base, meta, _ = _split(annotation)
    meta = list(metadata) + meta
    meta += [c for m in meta for c in getattr(m, "metadata", ())]  # Field(...) inside Annotated
    dims = [m for m in meta if isinstance(m, Dimension)]
    if dims:
        bounds = next((m for m in meta if isinstance(m, Bounds)), None)
        unit = si_unit(dims[0])
        text = bounds.text(dims[0]) if bounds else ""
        return (f"{dims[0]} [{unit}]", text.replace("must be ", ""), "")
    constraints = []
    for m in meta:
        for name, op in (("ge", ">="), ("gt", ">"), ("le", "<="), ("lt", "<")):
            if hasattr(m, name) and getattr(m, name) is not None and type(m).__name__.lower() == name:
                constraints.append(f"{op} {getattr(m, name)}")
        if type(m).__name__ == "MinLen":
            constraints.append(f"length >= {m.min_length}")
        if type(m).__name__ == "MaxLen":
            constraints.append(f"length <= {m.max_length}")
    origin = typing.get_origin(base)
    if origin is Literal:
        return ("choice", ", ".join(constraints), ", ".join(map(repr, typing.get_args(base))))
    if origin in (list, dict):
        args = typing.get_args(base)
        inner = args[-1] if args else Any
        kind, rng, allowed = _describe(inner, [])
        name = "list" if origin is list else "table"
        return (f"{name} of {kind}", ", ".join(constraints + ([rng] if rng else [])), allowed)
    if origin in (Union, types.UnionType):
        parts = [_describe(a, [])[0] for a in typing.get_args(base)]
        return (" or ".join(parts), ", ".join(constraints), "")
    name = getattr(base, "__name__", str(base))
    return ({"Any": "any", "float": "number", "int": "integer", "str": "string", "bool": "boolean"}.get(name, name),
            ", ".join(constraints), "")


def _default(field) -> str:
    if field.default_factory is not None:
        if isinstance(field.default_factory, type) and issubclass(field.default_factory, BaseModel):
            return "(table defaults)"
        value = field.default_factory()
        return "(table defaults)" if isinstance(value, BaseModel) else _fmt(value)
    if field.default is PydanticUndefined:
        return "required"
    if field.default is None:
        return "omitted"
    return _fmt(field.default)


def rows(model, table: str = "") -> list[Row]:
    """Every key of ``model`` and of its sub-tables, depth first."""
    out = []
    notes = _comments(model)
    for name, field in model.model_fields.items():
        models = _models_in(field.annotation)
        base, meta, _ = _split(field.annotation)
        container = typing.get_origin(base) in (list, dict)
        if models and not container:
            sub = f"{table}.{name}" if table else name
            if len(models) == 1:
                out.append(Row(table, name, "table", "", _default(field), "", notes.get(name, "")))
                out.extend(rows(models[0], sub))
            else:  # a tagged union: one table per member, named by its tag
                tags = [typing.get_args(m.model_fields["type"].annotation)[0] for m in models]
                out.append(Row(table, name, "table", "", _default(field), ", ".join(map(repr, tags)),
                               notes.get(name, "") or "one table per type, below"))
                for m, tag in zip(models, tags):
                    out.extend(rows(m, f"{sub} (type = {tag!r})"))
            continue
        if container and _models_in(typing.get_args(base)[-1]):
            inner = _models_in(typing.get_args(base)[-1])[0]
            sub = f"{table}.{name}" if table else name
            kind = "list of tables" if typing.get_origin(base) is list else "table of tables"
            out.append(Row(table, name, kind, "", _default(field), "", notes.get(name, "")))
            out.extend(rows(inner, f"{sub}.<name>" if typing.get_origin(base) is dict else f"{sub}[]"))
            continue
        kind, rng, allowed = _describe(field.annotation, field.metadata)
        out.append(Row(table, name, kind, rng, _default(field), allowed, notes.get(name, "")))
    return out


def _doc(model) -> str:
    text = inspect.getdoc(model) or ""
    inherited = inspect.getdoc(BaseModel) or ""
    return "" if text == inherited or text.startswith("A base class") else " ".join(text.split())


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ") if text else ""


def _table_rst(title: str, model, items: list[Row]) -> list[str]:
    lines = [".. list-table:: " + (f"``[{title}]``" if title else "top level"), "   :header-rows: 1",
             "   :widths: 18 22 16 14 30", "",
             "   * - key", "     - type [SI unit]", "     - range", "     - default", "     - allowed / note"]
    for r in items:
        extra = "; ".join(x for x in (r.allowed, r.note) if x)
        lines += [f"   * - ``{r.key}``", f"     - {_cell(r.kind)}", f"     - {_cell(r.range)}",
                  f"     - {_cell(r.default)}", f"     - {_cell(extra)}"]
    return lines + [""]


def _literal(text: str) -> str:
    """A docstring or comment shown as plain text (no rst markup is interpreted)."""
    text = text.replace("\\", "\\\\").replace("*", "\\*").replace("`", "\\`").replace("|", "\\|") \
        .replace("_", "\\_")
    return ("\\" + text if text[:1] in "-+#=" else text) if text else ""


def scene_rst(scene: str) -> list[str]:
    """The reference of one scene as reStructuredText lines."""
    from lubedyn.config import case_model

    model = case_model(scene)
    all_rows = rows(model)
    by_table: dict[str, list[Row]] = {}
    for r in all_rows:
        by_table.setdefault(r.table, []).append(r)
    models = {"": model}

    def collect(m, table):
        for name, field in m.model_fields.items():
            found = _models_in(field.annotation)
            base, _, _ = _split(field.annotation)
            sub = f"{table}.{name}" if table else name
            if typing.get_origin(base) in (list, dict):
                inner = _models_in(typing.get_args(base)[-1])
                if inner:
                    key = f"{sub}.<name>" if typing.get_origin(base) is dict else f"{sub}[]"
                    models[key] = inner[0]
                    collect(inner[0], key)
                continue
            if len(found) == 1:
                models[sub] = found[0]
                collect(found[0], sub)
            for f in found if len(found) > 1 else ():
                key = f"{sub} (type = {typing.get_args(f.model_fields['type'].annotation)[0]!r})"
                models[key] = f
                collect(f, key)

    collect(model, "")
    title = f'``scene = "{scene}"``'
    lines = [title, "-" * len(title), ""]
    doc = _doc(model)
    if doc:
        lines += [_literal(doc), ""]
    for table, items in by_table.items():
        m = models.get(table)
        doc = _doc(m) if m is not None and table else ""
        if doc:
            lines += [_literal(doc), ""]
        lines += _table_rst(table, m, items)
    if scene == "map":
        lines += map_kinds_rst()
    return lines


def map_kinds_rst() -> list[str]:
    """Each map kind's axes (``[axes.<key>]``) and parameters (``[params]``) with their defaults."""
    from lubedyn import maps

    lines = ["Map kinds: their axes (``[axes.<key>]`` overrides ``lo``, ``hi``, ``n``, ``scale``, ``nodes``) "
             "and parameters (``[params]``), with the defaults of the registry.", ""]
    for name, kind in maps.kinds().items():
        lines += [f".. list-table:: ``kind = {name!r}``: axes", "   :header-rows: 1", "",
                  "   * - axis key", "     - quantity", "     - lo", "     - hi", "     - n", "     - scale"]
        for a in kind.axes:
            lines += [f"   * - ``{maps.axis_key(a.name)}``", f"     - {_cell(a.name)}", f"     - {a.lo:g}",
                      f"     - {a.hi:g}", f"     - {a.n}", f"     - {a.scale}"]
        lines += ["", f".. list-table:: ``kind = {name!r}``: parameters", "   :header-rows: 1", "",
                  "   * - ``[params]`` key", "     - default"]
        for key, value in kind.default_params().items():
            lines += [f"   * - ``{key}``", f"     - {_cell(_fmt(value))}"]
        lines += [""]
    return lines


class CaseReference(Directive):
    optional_arguments = 1

    def run(self):
        from lubedyn.scenes import SCENES

        scenes = [self.arguments[0]] if self.arguments else list(SCENES)
        lines = []
        for scene in scenes:
            lines += scene_rst(scene)
        container = nodes.section()
        container.document = self.state.document
        self.state.nested_parse(StringList(lines, source="case_reference"), self.content_offset, container,
                                match_titles=True)
        return container.children


def setup(app):
    app.add_directive("case-reference", CaseReference)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
