"""The architecture rules of DESIGN.md that a scan can check (issue 13): every law constant has one home
(lubrication/laws), and dynamics imports from lubrication only the laws and the error tree."""
import ast
import sys
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


def _imports(path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.module
        elif isinstance(node, ast.Import):
            yield from (a.name for a in node.names)


def test_dynamics_imports_only_the_laws_and_errors_of_lubrication():
    """dynamics never imports a film solver, nor coupling (DESIGN.md, Layout)."""
    bad = []
    for path in sorted((ROOT / "dynamics").rglob("*.py")):
        for module in _imports(path):
            top = module.split(".")[0]
            if top == "coupling" or (top == "lubrication" and not (
                    module.startswith("lubrication.laws") or module == "lubrication.errors")):
                bad.append(f"{path.relative_to(ROOT)}: {module}")
    assert bad == []


def test_the_laws_import_no_solver():
    """lubrication/laws is the ground floor: it imports nothing of lubedyn but itself and the errors."""
    bad = []
    for path in sorted((ROOT / "lubrication" / "laws").rglob("*.py")):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                if node.level == 1 or (node.level == 2 and node.module == "errors"):
                    continue
                if node.level == 0 and node.module and node.module.split(".")[0] in ("lubrication", "dynamics",
                                                                                       "coupling"):
                    if not (node.module.startswith("lubrication.laws") or node.module == "lubrication.errors"):
                        bad.append(f"{path.name}: {node.module}")
                elif node.level >= 2:
                    bad.append(f"{path.name}: {'.' * node.level}{node.module}")
    assert bad == []
