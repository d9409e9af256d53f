"""The docstring examples of the library, run as doctests under the modules' installed names.

pytest's ``--doctest-modules`` names a module after its folder (``coupling/config.py`` would be imported a
second time as ``coupling.config``, beside ``lubedyn.config``), so the package folders are not collected
(``testpaths`` in pyproject.toml) and every module of ``lubedyn`` is imported here by its installed name
instead.  One test per docstring with examples, with pytest's default option flags (ELLIPSIS); warnings are
errors as everywhere in the suite."""
from __future__ import annotations

import doctest
import importlib
import pkgutil
from pathlib import Path

import pytest

import lubedyn

PACKAGES = ("lubedyn", "lubedyn.lubrication", "lubedyn.dynamics", "lubedyn.cases")


def _module_names() -> list[str]:
    names = []
    for package in PACKAGES:
        names.append(package)
        path = importlib.import_module(package).__path__
        # only the package's own folder: lubedyn's sub-packages lubrication, dynamics, cases live elsewhere
        names += [m.name for m in pkgutil.walk_packages(path, f"{package}.") if m.name not in PACKAGES]
    return sorted(names)


MODULES = _module_names()


def _doctests():
    finder = doctest.DocTestFinder()
    out = []
    for name in MODULES:
        module = importlib.import_module(name)
        for test in finder.find(module, name):
            if test.examples:
                out.append(pytest.param(test, id=test.name))
    return sorted(out, key=lambda p: p.id)


DOCTESTS = _doctests()


def test_every_source_file_is_a_module_found_here():
    """Every ``*.py`` of the package folders is among the modules searched for examples."""
    files = set()
    for package in PACKAGES:
        root = Path(importlib.import_module(package).__file__).parent
        files |= {p.resolve() for p in root.rglob("*.py")}
    found = {Path(importlib.import_module(name).__file__).resolve() for name in MODULES}
    assert found == files
    assert len(DOCTESTS) >= 30  # 30 when the package folders were collected by --doctest-modules


@pytest.mark.parametrize("test", DOCTESTS)
def test_docstring_example(test):
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS, verbose=False)
    lines = []
    runner.run(test, out=lines.append, clear_globs=True)
    assert runner.failures == 0, "".join(lines)
