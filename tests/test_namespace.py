"""One installed namespace: the library is ``lubedyn`` and nothing else, each module is imported
under one name, and a wheel installed away from the checkout runs the bundled cases as the checkout does.

The folders ``coupling/``, ``lubrication/`` and ``dynamics/`` of the checkout are importable by their own
names from the repository root by accident (a test run from there has the root on ``sys.path``), which
would give a second copy of every module (two ``FilmMap`` classes, two numba caches, isinstance checks
that fail).  So the checks run in fresh processes whose ``sys.path`` does hold the root, and scan what the
library imported."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import sysconfig
import textwrap
from pathlib import Path

import pytest

import lubedyn
from lubedyn.config import CASES_DIR

ROOT = Path(__file__).resolve().parents[1]
FOLDER_NAMES = ("coupling", "lubrication", "dynamics", "cases")

SCAN = """
import collections, json, os, sys
import lubedyn
twice = collections.defaultdict(list)
for name, module in list(sys.modules.items()):
    path = getattr(module, "__file__", None)
    if path and name != "__main__":  # the library's files (under the checkout, or the installed package)
        if name.split(".")[0] in ("lubedyn",) + %(folders)r or os.path.realpath(path).startswith(%(roots)r):
            twice[os.path.realpath(path)].append(name)
print(json.dumps({"folder names": sorted(n for n in sys.modules if n.split(".")[0] in %(folders)r),
                  "two names": {p: sorted(n) for p, n in twice.items() if len(n) > 1},
                  "lubedyn": lubedyn.__file__, "cases": str(lubedyn.CASES_DIR)}))
""" % {"folders": FOLDER_NAMES, "roots": tuple(str(ROOT / f) + os.sep for f in FOLDER_NAMES)}


def _scan(script: str, tmp_path: Path) -> dict:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg", "PYVISTA_OFF_SCREEN": "true",
           "LUBEDYN_BACKGROUND_COMPILE": "0"}
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(script) + SCAN], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_every_module_has_one_name_after_a_run(tmp_path):
    """From the repository root with the root on ``sys.path`` (so ``import coupling`` would succeed): import
    every module of lubedyn, run a film case through the CLI and a map-driven dynamics case's build through
    the Python API; then no module is named after a folder, and no source file is loaded under two names."""
    found = _scan(f"""
        import importlib, os, pkgutil
        import lubedyn
        from lubedyn import cli
        for package in ("lubedyn", "lubedyn.lubrication", "lubedyn.dynamics", "lubedyn.cases"):
            path = importlib.import_module(package).__path__
            for m in pkgutil.walk_packages(path, package + "."):
                importlib.import_module(m.name)
        assert cli.main(["run", "journal_finite", "--smoke", "--out", {str(tmp_path / "film")!r}]) == 0
        from lubedyn.scenes import dynamics as dynamics_scene
        case = lubedyn.load_case(lubedyn.CASES_DIR / "cageless_6206_10krpm_short.toml", smoke=True)
        dynamics_scene.build(case, str(lubedyn.CASES_DIR / "cageless_6206_10krpm_short.toml"))
    """, tmp_path)
    assert found["folder names"] == []
    assert found["two names"] == {}
    assert Path(found["lubedyn"]).resolve() == ROOT / "coupling" / "__init__.py"  # the editable install
    assert Path(found["cases"]).resolve() == ROOT / "cases"


def test_the_api_and_the_subpackages():
    """``import lubedyn`` imports nothing heavy; the main API and the sub-packages load on first use."""
    script = textwrap.dedent("""
        import sys, lubedyn
        heavy = sorted(m for m in ("numpy", "scipy", "skfem", "numba", "pydantic", "lubedyn.lubrication",
                                   "lubedyn.dynamics", "lubedyn.config", "importlib.metadata") if m in sys.modules)
        print(heavy)
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, check=True)
    assert done.stdout.strip() == "[]"
    from lubedyn import lubrication, maps

    assert lubedyn.Film is lubrication.Film and lubedyn.solve is lubrication.solve
    assert lubedyn.FilmMap is maps.FilmMap
    assert lubedyn.lubrication is lubrication and lubedyn.dynamics.__name__ == "lubedyn.dynamics"
    assert lubedyn.cases.__name__ == "lubedyn.cases"
    assert lubedyn.CASES_DIR == CASES_DIR and lubedyn.bundled_cases()
    assert lubedyn.run_film.__module__ == "lubedyn.scenes.film"
    assert {"load_case", "run", "run_dynamics", "Film", "solve", "FilmMap", "lubrication", "dynamics",
            "cases"} <= set(dir(lubedyn))
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        lubedyn.nope  # noqa: B018
    with pytest.raises(ImportError):
        from lubedyn import nope  # noqa: F401


def _site_packages(python: Path) -> Path:
    out = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                         capture_output=True, text=True, check=True).stdout.strip()
    return Path(out)


@pytest.mark.slow
def test_a_wheel_installed_away_from_the_checkout_runs_a_bundled_case(tmp_path):
    """Build the wheel (no build isolation: no download) from a copy of the checkout's sources, install it
    (no dependencies) into a new virtual environment outside the checkout that sees this environment's
    packages through a ``.pth`` file, and from a folder outside the checkout: ``import lubedyn`` finds the
    wheel's copy, ``lubedyn cases`` lists the bundled cases, ``lubedyn run journal_finite --smoke`` writes
    the summary of the checkout's run, number for number.  About 30-60 s."""
    pytest.importorskip("wheel")
    src = tmp_path / "src"
    src.mkdir()
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.nbi", "*.nbc")
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(ROOT / name, src / name)
    for folder in FOLDER_NAMES:
        shutil.copytree(ROOT / folder, src / folder, ignore=ignore)
    wheels = tmp_path / "wheels"
    build = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
                            "-w", str(wheels), str(src)], capture_output=True, text=True, timeout=600)
    assert build.returncode == 0, build.stderr[-3000:]
    wheel, = wheels.glob("lubedyn-*.whl")

    import zipfile

    names = zipfile.ZipFile(wheel).namelist()
    tops = {n.split("/")[0] for n in names if not n.split("/")[0].endswith((".dist-info", ".data"))}
    assert tops == {"lubedyn"}
    shipped = {p.relative_to(ROOT / "cases").as_posix() for p in (ROOT / "cases").rglob("*")
               if p.is_file() and "__pycache__" not in p.parts}
    assert {n.removeprefix("lubedyn/cases/") for n in names if n.startswith("lubedyn/cases/")} == shipped
    # PEP 561: type checkers read the installed packages' hints only with their py.typed marker
    assert {"lubedyn/py.typed", "lubedyn/lubrication/py.typed", "lubedyn/dynamics/py.typed"} <= set(names)

    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True, timeout=120)
    python = venv / "bin" / "python"
    # the dependencies: this environment's site-packages, after the new one's (its own .pth files, such as
    # the editable install of the checkout, are not read from a directory named in a .pth file)
    (_site_packages(python) / "test-environment.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    install = subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "--no-deps", "-q",
                              str(wheel)], capture_output=True, text=True, timeout=600)
    assert install.returncode == 0, install.stderr[-3000:]

    away = tmp_path / "elsewhere"
    away.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env.update(MPLBACKEND="Agg", PYVISTA_OFF_SCREEN="true", LUBEDYN_BACKGROUND_COMPILE="0")
    where = subprocess.run([str(python), "-c", "import importlib.util, json, lubedyn; print(json.dumps("
                            "[lubedyn.__file__, str(lubedyn.CASES_DIR), lubedyn.__version__, "
                            "[importlib.util.find_spec(n) is None for n in ('coupling', 'lubrication', 'dynamics')]]))"],
                           cwd=away, env=env, capture_output=True, text=True, timeout=120)
    assert where.returncode == 0, where.stderr[-3000:]
    file, cases, version, absent = json.loads(where.stdout)
    site = _site_packages(python).resolve()
    assert Path(file).resolve() == site / "lubedyn" / "__init__.py"
    assert Path(cases).resolve() == site / "lubedyn" / "cases"
    assert version == lubedyn.__version__ and absent == [True, True, True]

    exe = venv / "bin" / "lubedyn"
    listed = subprocess.run([str(exe), "cases"], cwd=away, env=env, capture_output=True, text=True, timeout=300)
    assert listed.returncode == 0, listed.stderr[-3000:]
    assert all(p.stem in listed.stdout for p in CASES_DIR.glob("*.toml"))

    run = subprocess.run([str(exe), "run", "journal_finite", "--smoke", "--out", "out"], cwd=away, env=env,
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    theirs = json.loads((away / "out" / "summary.json").read_text())

    from lubedyn import cli

    assert cli.main(["run", "journal_finite", "--smoke", "--out", str(tmp_path / "checkout")]) == 0
    ours = json.loads((tmp_path / "checkout" / "summary.json").read_text())
    loads = [k for k in ours if k.startswith("Load")]
    assert loads and {k: theirs[k] for k in loads} == {k: ours[k] for k in loads}
    timings = {k for k in ours if k.endswith("time [s]")}
    assert {k: v for k, v in theirs.items() if k not in timings} == {k: v for k, v in ours.items() if k not in timings}
