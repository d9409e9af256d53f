"""The documentation (docs/): the site builds with every warning an error, and the case-file reference,
generated from the pydantic case models by docs/_ext/case_reference.py, lists every key.

The build runs Sphinx as ``lubedyn``'s CI installs it (the ``test`` extra carries the ``docs`` packages) with
``-W`` and without executing the examples gallery (``-D plot_gallery=0``: tests/test_examples.py runs every
example already), so a broken page, reference, link or docstring fails here.  Measured on the 2-core
machine: 37 s alone, 61 s inside a full run at load average 6-8 (importing every module for the API reference
is most of it); the case-reference checks 15 s (they validate every bundled case)."""
from __future__ import annotations

import importlib
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


@pytest.fixture(scope="module")
def case_reference():
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        pytest.importorskip("docutils")
        yield importlib.import_module("case_reference")
    finally:
        sys.path.remove(str(DOCS / "_ext"))


def test_docs_build_with_warnings_as_errors(tmp_path):
    pytest.importorskip("sphinx")
    pytest.importorskip("sphinx_gallery")
    pytest.importorskip("myst_parser")
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html", "-D", "plot_gallery=0",
           "-d", str(tmp_path / "doctrees"), str(DOCS), str(tmp_path / "html")]
    run = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=900,
                         env={**os.environ, "MPLBACKEND": "Agg"})
    assert run.returncode == 0, (run.stdout[-3000:] + run.stderr[-6000:])
    html = tmp_path / "html"
    for page in ("index", "readme", "case_reference", "api", "theory/reynolds", "theory/ehl", "theory/maps",
                 "theory/cageless", "theory/tapered", "atlas/index", "atlas/reynolds_fem", "atlas/cavitation",
                 "atlas/ehl", "atlas/maps", "atlas/integrators", "atlas/lyapunov", "auto_examples/index", "python", "study_dask",
                 "auto_examples/cavitation_models", "auto_examples/cageless_rotor_drop", "papers", "paper_a"):
        assert (html / f"{page}.html").is_file(), page
    # every benchmark chart an atlas page shows was found and copied
    for chart in ("reynolds", "ehl", "maps", "dynamics", "dynamics_equal_accuracy", "method_limits"):
        assert (html / "_images" / f"{chart}.png").is_file(), chart


def _rows_by_table(case_reference, scene):
    from lubedyn.config import case_model

    found: dict[str, dict] = {}
    for row in case_reference.rows(case_model(scene)):
        found.setdefault(row.table, {})[row.key] = row
    return found


def _check_keys(data: dict, table: str, tables: dict, where: str):
    """Every key of a resolved case table is a row of the reference's table; recurse into sub-tables."""
    assert table in tables, f"{where}: table [{table}] missing from the reference"
    for key, value in data.items():
        assert key in tables[table], f"{where}: key {table + '.' if table else ''}{key} missing from the reference"
        row = tables[table][key]
        sub = f"{table}.{key}" if table else key
        if row.kind == "table" and isinstance(value, dict):
            tagged = f"{sub} (type = {value['type']!r})" if "type" in value and sub not in tables else sub
            _check_keys(value, tagged, tables, where)
        elif row.kind == "table of tables" and isinstance(value, dict):
            for item in value.values():
                _check_keys(item, f"{sub}.<name>", tables, where)


def test_case_reference_lists_every_key_of_every_bundled_case(case_reference):
    """Independent of the reference's own walk: each bundled case, validated and dumped with every default
    filled in (what ``case.resolved.toml`` holds), has each of its keys in the reference of its scene."""
    from lubedyn.config import bundled_cases, load_case

    scenes = set()
    for path in bundled_cases():
        case = load_case(path)
        scene = case.scene
        scenes.add(scene)
        _check_keys(case.model_dump(exclude={"smoke"}), "", _rows_by_table(case_reference, scene), path.name)
    assert scenes == {"film", "ehl", "map", "dynamics", "static", "tapered"}


def test_case_reference_lists_every_field_of_every_case_model(case_reference):
    """Every field of every pydantic model class of the case schema (found as subclasses of the models'
    base class, not by the reference's walk) is a key of some table of the reference."""
    from lubedyn import config
    from lubedyn.config import case_model
    from lubedyn.scenes import SCENES

    for scene in SCENES:
        case_model(scene)  # imports the scene's module, so that its models exist
    keys = {(r.key) for scene in SCENES for r in case_reference.rows(case_model(scene))}
    study_models = {m for m in _subclasses(config.CaseTable) if m.__module__ == "lubedyn.scenes.study"}
    for model in _subclasses(config.CaseTable) - study_models:
        for name in model.model_fields:
            assert name in keys, f"{model.__module__}.{model.__name__}.{name} missing from the case reference"


def test_case_reference_lists_each_map_kind_axis_and_parameter(case_reference):
    from lubedyn import maps

    text = "\n".join(case_reference.map_kinds_rst())
    for name, kind in maps.kinds().items():
        assert f"``kind = {name!r}``" in text
        for axis in kind.axes:
            assert f"``{maps.axis_key(axis.name)}``" in text
        for key in kind.default_params():
            assert f"``{key}``" in text


def test_case_reference_shows_units_ranges_and_defaults(case_reference):
    """A few rows read against the models' source: a bounded quantity, an integer constraint, a choice."""
    from lubedyn.config import case_model

    rows = {(r.table, r.key): r for r in case_reference.rows(case_model("film"))}
    rtol = rows[("solver", "rtol")]
    assert (rtol.kind, rtol.range, rtol.default) == ("dimensionless [-]", "in (0, 1)", "1e-10")
    assert rows[("mesh", "refinements")].range == ">= 0, <= 8"
    assert rows[("cavitation", "model")].allowed == "'none', 'half_sommerfeld', 'reynolds', 'jfo'"
    clearance = rows[("gap (type = 'journal')", "clearance")]
    assert clearance.kind == "length [m]" and clearance.default == "required"


def _subclasses(cls) -> set:
    out = set()
    for sub in cls.__subclasses__():
        out |= {sub} | _subclasses(sub)
    return out
