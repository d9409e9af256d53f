"""Size and shape of the library code: no module too large to read ("no god
modules"), every law written once.

::

    python benchmarks/code_size.py [--json OUT.json] [--top N]

Reads every ``*.py`` file of the packages ``lubrication``, ``dynamics`` and ``coupling`` with
:mod:`ast` (nothing is imported) and reports

- the largest modules (lines) and functions (lines from ``def`` to the last line of the body,
  decorators excluded), the counts of modules above 1,000 lines and functions above 100 lines;
- functions with more than 10 parameters;
- function-local imports of in-tree modules (``import``/``from`` statements inside a function
  that name ``lubrication``, ``dynamics``, ``coupling`` or a relative module);
- where each published law constant appears as a numeric literal in code (docstrings and
  comments do not count): see :data:`LAW_CONSTANTS`.  Each should have one home, the ground floor
  ``lubrication/laws``; ``tests/test_layout.py`` asserts it.

Writes JSON (default ``benchmarks/results/code_size.json``) and prints a short table.
"""
from __future__ import annotations

import argparse
import ast
import json
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]
PACKAGES = ("lubrication", "dynamics", "coupling")

#: Published constants of the laws (value: which law, where it is published).  A literal equal to
#: one of these values outside ``lubrication/laws`` is a second copy of a law.
LAW_CONSTANTS = {
    1.0339: "Hamrock-Brewe ellipticity k = 1.0339 (R_a/R_b)^0.636 (Hamrock & Brewe 1983)",
    0.636: "Hamrock-Brewe ellipticity exponent (Hamrock & Brewe 1983)",
    0.5968: "Hamrock-Brewe elliptic integral E = 1.0003 + 0.5968 R_b/R_a",
    1.0003: "Hamrock-Brewe elliptic integral E = 1.0003 + 0.5968 R_b/R_a",
    1.5277: "Hamrock-Brewe elliptic integral F = 1.5277 + 0.6023 ln(R_a/R_b)",
    0.6023: "Hamrock-Brewe elliptic integral F = 1.5277 + 0.6023 ln(R_a/R_b)",
    4.37: "Stribeck constant, point contacts (Harris)",
    4.08: "Stribeck constant, line contacts (Harris)",
    2.69: "Hamrock-Dowson central film H_c = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 e^-0.73k)",
    3.63: "Hamrock-Dowson minimum film H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - e^-0.68k)",
    0.067: "Hamrock-Dowson central film load exponent",
    0.073: "Hamrock-Dowson minimum film load exponent",
    9.67: "Roelands: alpha = z (ln eta0 + 9.67) / p0",
    1.96e8: "Roelands reference pressure p0 = 1.96e8 Pa",
    5.1e-9: "Roelands z = alpha / (5.1e-9 (ln eta0 + 9.67))",
    1.7e-9: "Dowson-Higginson density 1 + 0.6e-9 p / (1 + 1.7e-9 p)",
    3.84e-5: "Palmgren line law delta = 3.84e-5 Q^0.9 / l^0.8 [mm, N] (Palmgren 1959)",
    0.356: "paper A's slice stiffness k_w = 0.356 E' l^(8/9) / n_s (Wu et al. 2018, eq. 11)",
    0.3033: "Johns-Gohar logarithmic crown, 1 - 0.3033 b/a (Johns & Gohar 1981)",
}


def _files():
    """Library sources."""
    for pkg in PACKAGES:
        yield from sorted((ROOT / pkg).rglob("*.py"))


def _rel(path):
    return path.relative_to(ROOT).as_posix()


def _docstring_nodes(tree):
    """ids of the Constant nodes that are docstrings (module, class, function)."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                out.add(id(body[0].value))
    return out


def _n_params(fn):
    a = fn.args
    n = len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs)
    if a.args and a.args[0].arg in ("self", "cls"):
        n -= 1
    return n


def _is_in_tree(node):
    if isinstance(node, ast.ImportFrom):
        return node.level > 0 or (node.module or "").split(".")[0] in PACKAGES
    return any(alias.name.split(".")[0] in PACKAGES for alias in node.names)


def scan():
    modules, functions, local_imports, constants = [], [], [], {v: [] for v in LAW_CONSTANTS}
    for path in _files():
        text = path.read_text()
        tree = ast.parse(text)
        rel = _rel(path)
        modules.append({"module": rel, "lines": len(text.splitlines())})
        docs = _docstring_nodes(tree)
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                functions.append({"function": f"{rel}:{node.name}", "line": node.lineno,
                                  "lines": node.end_lineno - node.lineno + 1, "parameters": _n_params(node)})
                for sub in ast.walk(node):
                    if isinstance(sub, (ast.Import, ast.ImportFrom)) and _is_in_tree(sub):
                        local_imports.append(f"{rel}:{sub.lineno}")
            elif isinstance(node, ast.Constant) and id(node) not in docs and isinstance(node.value, float):
                for value in LAW_CONSTANTS:
                    if node.value == value:
                        constants[value].append(f"{rel}:{node.lineno}")
    modules.sort(key=lambda m: -m["lines"])
    functions.sort(key=lambda f: -f["lines"])
    return {
        "modules": modules,
        "functions": functions,
        "modules over 1000 lines": sum(m["lines"] > 1000 for m in modules),
        "functions over 100 lines": sum(f["lines"] > 100 for f in functions),
        "functions over 10 parameters": sum(f["parameters"] > 10 for f in functions),
        "function-local in-tree imports": local_imports,
        "law constants": {f"{v!r} ({LAW_CONSTANTS[v]})": sites for v, sites in constants.items()},
    }


def law_constant_sites_outside_laws(report=None):
    """{constant description: [file:line, ...]} of law-constant literals outside ``lubrication/laws``."""
    report = report or scan()
    out = {}
    for key, sites in report["law constants"].items():
        outside = [s for s in sites if not s.startswith("lubrication/laws/")]
        if outside:
            out[key] = outside
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(prog="code_size", description=__doc__.splitlines()[0])
    ap.add_argument("--json", default=str(ROOT / "benchmarks" / "results" / "code_size.json"))
    ap.add_argument("--top", type=int, default=10)
    args = ap.parse_args(argv)
    report = scan()
    pathlib.Path(args.json).parent.mkdir(parents=True, exist_ok=True)
    pathlib.Path(args.json).write_text(json.dumps(report, indent=1) + "\n")
    print(f"largest modules (of {len(report['modules'])}):")
    for m in report["modules"][:args.top]:
        print(f"  {m['lines']:6d}  {m['module']}")
    print(f"largest functions (of {len(report['functions'])}):")
    for f in report["functions"][:args.top]:
        print(f"  {f['lines']:6d}  {f['function']} (line {f['line']}, {f['parameters']} parameters)")
    for key in ("modules over 1000 lines", "functions over 100 lines", "functions over 10 parameters"):
        print(f"{key}: {report[key]}")
    print(f"function-local in-tree imports: {len(report['function-local in-tree imports'])}")
    outside = law_constant_sites_outside_laws(report)
    print(f"law constants with a literal outside lubrication/laws: {len(outside)}")
    for key, sites in outside.items():
        print(f"  {key}: {', '.join(sites)}")
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
