"""The architecture rules of DESIGN.md that a scan can check: every law constant has one home
(lubrication/laws), and dynamics imports from lubrication only the laws and the error tree; and the layout of
the one installed namespace: the folders lubrication/, dynamics/, coupling/ and cases/ are
lubedyn.lubrication, lubedyn.dynamics, lubedyn itself and lubedyn.cases, and nothing names them otherwise."""
import ast
import re
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from benchmarks import code_size  # noqa: E402


def test_every_law_constant_has_one_home():
    """A grep of the published constants (1.0339, 0.636, 4.37, 2.69, 9.67, 1.7e-9 ...) as numeric
    literals in code finds them in lubrication/laws only, and each in one module there."""
    report = code_size.scan()
    assert code_size.law_constant_sites_outside_laws(report) == {}
    for key, sites in report["law constants"].items():
        assert len({s.split(":")[0] for s in sites}) <= 1, (key, sites)


# the installed namespace (pyproject.toml, [tool.setuptools] package-dir): package -> folder of the checkout
PACKAGE_DIR = {"lubedyn": "coupling", "lubedyn.lubrication": "lubrication", "lubedyn.dynamics": "dynamics",
               "lubedyn.cases": "cases"}
OLD_NAMES = ("lubrication", "dynamics", "coupling")  # the folders' names, never installed nor imported


def _module_name(path: Path) -> str:
    """The installed name of a source file of the checkout (``dynamics/cageless/model.py`` ->
    ``lubedyn.dynamics.cageless.model``)."""
    rel = path.relative_to(ROOT).with_suffix("")
    for package, folder in sorted(PACKAGE_DIR.items(), key=lambda kv: -len(kv[1])):
        if rel.parts[0] == folder:
            parts = rel.parts[1:]
            if parts and parts[-1] == "__init__":
                parts = parts[:-1]
            return ".".join((package, *parts))
    raise ValueError(path)


def _module_files() -> dict:
    """installed module name -> source file, for every module of the namespace."""
    return {_module_name(p): p for folder in PACKAGE_DIR.values() for p in (ROOT / folder).rglob("*.py")
            if "__pycache__" not in p.parts}


MODULES = _module_files()


def _import_nodes(path):
    """(line, module, names) of every import of ``path`` (at any depth: function-local imports too), the
    module absolute (relative imports resolved against its installed name, so that ``from .. import x``
    in ``dynamics/`` counts as an import of the coupling layer)."""
    name = _module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level == 0:
                base = node.module
            else:
                parts = package.split(".")
                base = ".".join(parts[:len(parts) - node.level + 1] + ([node.module] if node.module else []))
            yield node.lineno, base, [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            for a in node.names:
                yield node.lineno, a.name, []


def _imports(path):
    """The absolute names of the modules ``path`` imports: ``from a.b import c`` imports ``a.b``, and
    ``a.b.c`` too when that is a module of the namespace (``from lubedyn import outputs``)."""
    for _, base, names in _import_nodes(path):
        yield base
        yield from (f"{base}.{n}" for n in names if f"{base}.{n}" in MODULES)


def _layer(module: str) -> str | None:
    """lubrication, dynamics, cases or coupling (the rest of ``lubedyn``); None outside lubedyn."""
    if module != "lubedyn" and not module.startswith("lubedyn."):
        return None
    for layer in ("lubrication", "dynamics", "cases"):
        if module == f"lubedyn.{layer}" or module.startswith(f"lubedyn.{layer}."):
            return layer
    return "coupling"


def _law_or_error(module: str) -> bool:
    return module == "lubedyn.lubrication.errors" or module == "lubedyn.lubrication.laws" or module.startswith(
        "lubedyn.lubrication.laws.")


def test_dynamics_imports_only_the_laws_and_errors_of_lubrication():
    """dynamics never imports a film solver, nor the coupling layer (DESIGN.md, Layout)."""
    bad = []
    for path in sorted((ROOT / "dynamics").rglob("*.py")):
        for module in _imports(path):
            layer = _layer(module)
            if layer == "coupling" or (layer == "lubrication" and not _law_or_error(module)):
                bad.append(f"{path.relative_to(ROOT)}: {module}")
    assert bad == []


def test_lubrication_imports_neither_dynamics_nor_coupling():
    bad = [f"{path.relative_to(ROOT)}: {module}" for path in sorted((ROOT / "lubrication").rglob("*.py"))
           for module in _imports(path) if _layer(module) in ("dynamics", "coupling", "cases")]
    assert bad == []


def test_the_laws_import_no_solver():
    """lubrication/laws is the ground floor: it imports nothing of lubedyn but itself and the errors."""
    bad = [f"{path.name}: {module}" for path in sorted((ROOT / "lubrication" / "laws").rglob("*.py"))
           for module in _imports(path) if _layer(module) is not None and not _law_or_error(module)]
    assert bad == []


def test_the_relative_import_resolver():
    """The resolver above on known lines: a relative import out of dynamics/ is one of the coupling layer."""
    assert _module_name(ROOT / "dynamics" / "cageless" / "model.py") == "lubedyn.dynamics.cageless.model"
    assert _module_name(ROOT / "coupling" / "__init__.py") == "lubedyn"
    assert "lubedyn.dynamics.errors" in set(_imports(ROOT / "dynamics" / "specialise.py"))
    assert "lubedyn.lubrication" in set(_imports(ROOT / "coupling" / "maps" / "provenance.py"))
    assert "lubedyn.outputs" in set(_imports(ROOT / "coupling" / "scenes" / "study.py"))  # from lubedyn import outputs


def _graph() -> dict:
    """module -> the modules of the namespace it imports (function-local imports included); an import of
    ``a.b.c`` counts as one of the deepest module it names (``a.b.c`` when that is a module, else ``a.b``)."""
    graph = {}
    for module, path in MODULES.items():
        edges = set()
        for found in _imports(path):
            while found and found not in MODULES:
                found = found.rpartition(".")[0]
            if found and found != module:
                edges.add(found)
        graph[module] = edges
    return graph


def _cycles(graph: dict) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan's algorithm, iterative)."""
    index, low, on, stack, found, counter = {}, {}, set(), [], [], [0]
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter[0]; counter[0] += 1; stack.append(root); on.add(root)
        while work:
            node, children = work[-1]
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter[0]; counter[0] += 1; stack.append(child); on.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                    break
                if child in on:
                    low[node] = min(low[node], index[child])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop(); on.discard(member); component.append(member)
                        if member == node:
                            break
                    if len(component) > 1:
                        found.append(sorted(component))
    return found


def test_no_import_circle():
    """No module of the namespace imports, directly or through others, a module that imports it back:
    function-local imports count (they hide a circle, they do not remove it).  A package's ``__init__``
    importing its own modules is part of the graph like any other import."""
    assert _cycles(_graph()) == []


def test_the_cycle_finder():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_no_private_name_is_imported_across_packages():
    """``from lubedyn.x import _name`` only inside x's own package: a private name is its package's
    business; what another package needs is public (named without the underscore, documented)."""
    bad = []
    for module, path in MODULES.items():
        home = module if path.name == "__init__.py" else module.rpartition(".")[0]
        for line, base, names in _import_nodes(path):
            if not base or not base.startswith("lubedyn"):
                continue
            source = base if base in MODULES else base.rpartition(".")[0]
            source_package = source if MODULES.get(source, Path()).name == "__init__.py" else source.rpartition(".")[0]
            for n in names:
                if n.startswith("_") and not n.startswith("__") and source_package != home:
                    bad.append(f"{path.relative_to(ROOT)}:{line}: {n} of {base}")
    assert bad == []


# ---------------------------------------------------------------------------
# one namespace


def test_pyproject_installs_one_namespace_with_every_package():
    """The installed packages are lubedyn and its sub-packages, each folder with an ``__init__.py`` listed
    under its installed name, and nothing under the folders' own names."""
    setuptools = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert setuptools["package-dir"] == PACKAGE_DIR
    folders = {_module_name(p) for folder in PACKAGE_DIR.values() for p in (ROOT / folder).rglob("__init__.py")}
    assert set(setuptools["packages"]) == folders
    assert not [p for p in setuptools["packages"] if p.split(".")[0] != "lubedyn"]
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts == {"lubedyn": "lubedyn.cli:main"}


def _sources():
    for folder in (*PACKAGE_DIR.values(), "tests", "benchmarks", "examples", "docs"):
        yield from sorted(p for p in (ROOT / folder).rglob("*.py") if "_build" not in p.parts)


# the before/after tool runs older commits too, whose CLI is ``python -m coupling.cli``
EARLIER_LAYOUT = {("benchmarks/case_summaries.py", "coupling.cli")}


def test_no_code_names_the_folders_as_modules():
    """No import of ``lubrication``, ``dynamics`` or ``coupling`` as top-level modules in the library, the
    tests, benchmarks, examples and docs, and no string that names a module under them (``"coupling.study"``
    as a logger, ``importlib.import_module("dynamics.x")``, ``python -m coupling.cli``)."""
    bad = []
    module_string = re.compile(rf"^(?:-m )?(?:{'|'.join(OLD_NAMES)})\.[a-z_]+(?:\.[a-z_]+)*$")
    for path in _sources():
        if path == Path(__file__).resolve():  # this file names them, to check them
            continue
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.ImportFrom) and node.level == 0:
                names = [node.module]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.Constant) and isinstance(node.value, str) and module_string.match(node.value):
                names = [node.value]
            bad += [f"{path.relative_to(ROOT)}:{node.lineno}: {n}" for n in names
                    if n.removeprefix("-m ").split(".")[0] in OLD_NAMES
                    and (path.relative_to(ROOT).as_posix(), n) not in EARLIER_LAYOUT]
    assert bad == []


# the papers whose systems the toolkit models, by the names the project gives them
PAPER_NAMES = ("paper", "wu2018", "zhang2024")


def test_no_library_module_is_named_after_a_paper_outside_the_papers_room():
    """Each paper's parameter set, claims and figures live in ``lubedyn.papers.<paper>``; the library's
    other modules are named for what they compute."""
    bad = [m for m in MODULES if not (m == "lubedyn.papers" or m.startswith("lubedyn.papers."))
           and any(n in part for part in m.split(".") for n in PAPER_NAMES)]
    assert bad == []
    assert {"lubedyn.papers.wu2018.parameters", "lubedyn.papers.zhang2024.parameters"} <= set(MODULES)
