"""``lubedyn``: run, validate and list case files; report versions.

::

    lubedyn run CASE.toml [--out DIR] [--set KEY=VALUE ...] [--dry-run] [--smoke]
    lubedyn validate CASE.toml [--set KEY=VALUE ...] [--smoke]
    lubedyn cases
    lubedyn info

``CASE`` may also be the name of a bundled case (``lubedyn run journal_finite``).
``--smoke`` merges the case's ``[smoke]`` table (coarse mesh) before ``--set``.
``--dry-run`` validates and builds the mesh and film, prints the plan and the
resolved case, and writes nothing.

Exit codes: 0 success; 2 input error (bad TOML, unknown key, wrong unit,
value out of range, missing file, impossible geometry); 1 a solve that did not
converge or an output that could not be written.  Errors are one line on
stderr, prefixed ``lubedyn: error:``, with no traceback.
"""
from __future__ import annotations

import argparse
import contextlib
import logging
import os
import sys
from pathlib import Path

from lubrication.errors import ConvergenceError, InputError

EXIT_OK, EXIT_FAILED, EXIT_INPUT = 0, 1, 2
log = logging.getLogger("lubedyn")


class _Parser(argparse.ArgumentParser):
    """argparse with the project's one-line error format (exit code 2)."""

    def error(self, message):
        self.exit(EXIT_INPUT, f"lubedyn: error: {message} (see '{self.prog} --help')\n")


def _case_path(text: str) -> Path:
    from .config import CASES_DIR

    path = Path(text)
    if not path.exists() and path.suffix == "" and (CASES_DIR / f"{text}.toml").is_file():
        return CASES_DIR / f"{text}.toml"
    return path


def _load(args):
    from .config import load_case

    path = _case_path(args.case)
    return path, load_case(path, smoke=args.smoke, overrides=args.set or ())


def _scene(case):
    """(scene module, builder) of a validated case.

    A scene is a module ``coupling.<scene>_scene`` with ``build(case)`` (validates
    what the schema cannot: geometry, positive gaps ...; raises InputError),
    ``describe(case, built) -> str``, ``run(case, out_dir, *, name, source, smoke)``
    returning an object with ``summary`` (dict) and ``files`` (paths), and
    ``FIELD_FILES``: ((file name, ``output.write`` key), ...) for the dry-run plan.
    """
    import importlib

    module = importlib.import_module(f"coupling.{case.scene}_scene")
    return module, module.build


def cmd_run(args) -> int:
    from .config import resolved_toml

    path, case = _load(args)
    scene, build = _scene(case)
    out = Path(args.out) if args.out else Path("runs") / path.stem
    if args.dry_run:
        built = build(case)
        print(f"dry run: {scene.describe(case, built)}")
        print(f"dry run: would write {out}/summary.json, case.resolved.toml"
              + "".join(f", {f}" for f, k in scene.FIELD_FILES if k in case.output.write))
        print(resolved_toml(case, f"dry run of {path}"))
        return EXIT_OK
    result = scene.run(case, out, name=path.stem, source=str(path), smoke=args.smoke)
    s = result.summary
    if hasattr(scene, "headline"):  # the scene chooses what to show
        for line in scene.headline(s):
            print(line)
        print(f"wrote {out}/: " + ", ".join(p.name for p in result.files))
        return EXIT_OK
    shown = [k for k in s if k.startswith(("Load [", "Load per unit width [", "Load per length [", "Maximum pressure",
                                           "Hertz pressure", "Central film", "Minimum film", "Attitude angle",
                                           "Eccentricity ratio"))]
    for key in shown:
        if isinstance(s[key], (int, float)):
            print(f"{key:<36} {s[key]:.6g}")
    if "Newton iterations [-]" in s:
        print(f"{'Newton iterations [-]':<36} {s.get('Newton iterations [-]')}, "
              f"{s.get('Degrees of freedom [-]')} dofs, {s['Run time [s]']:.3g} s")
    else:
        print(f"{'Run time [s]':<36} {s['Run time [s]']:.3g}")
    print(f"wrote {out}/: " + ", ".join(p.name for p in result.files))
    return EXIT_OK


def cmd_validate(args) -> int:
    from .config import read_toml, validate_raw

    path = _case_path(args.case)
    raw = read_toml(path)
    case = validate_raw(raw, smoke=args.smoke, overrides=args.set or ())
    scene, build = _scene(case)
    built = build(case)
    if not args.smoke and isinstance(raw.get("smoke"), dict):  # the smoke variant must be valid too
        smoke_case = validate_raw(raw, smoke=True, overrides=args.set or ())
        _scene(smoke_case)[1](smoke_case)
    print(f"OK {path}: {scene.describe(case, built)}")
    return EXIT_OK


def cmd_cases(args) -> int:
    import tomllib

    from .config import bundled_cases

    paths = bundled_cases()
    width = max((len(p.stem) for p in paths), default=10)
    for path in paths:
        try:
            description = tomllib.loads(path.read_text(encoding="utf-8")).get("description", "")
        except (OSError, tomllib.TOMLDecodeError) as exc:
            description = f"(unreadable: {' '.join(str(exc).split())})"
        print(f"{path.stem:<{width}}  {description}")
    return EXIT_OK


def _versions() -> dict:
    import platform
    from importlib.metadata import PackageNotFoundError, version

    out = {}
    for dist in ("lubedyn", "numpy", "scipy", "scikit-fem", "numba", "pyvista", "meshio", "matplotlib",
                 "pydantic", "pyamg"):
        try:
            out[dist] = version(dist)
        except PackageNotFoundError:
            out[dist] = "not installed"
    out["python"] = platform.python_version()
    out["platform"] = platform.platform()
    cores = os.cpu_count() or 1
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else cores
    out["cores"] = f"{usable} usable of {cores}"
    return out


def cmd_info(args) -> int:
    for key, value in _versions().items():
        print(f"{key:<11} {value}")
    return EXIT_OK


def _parser() -> argparse.ArgumentParser:
    verbose = argparse.ArgumentParser(add_help=False)
    verbose.add_argument("-v", "--verbose", action="count", default=argparse.SUPPRESS,
                         help="more log output (-v info, -vv debug)")
    p = _Parser(prog="lubedyn", description="Lubricant films and EHL contacts by finite elements; bearing dynamics (planned).",
                parents=[verbose])
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)

    def with_case(sp):
        sp.add_argument("case", help="case file (TOML), or the name of a bundled case")
        sp.add_argument("--set", action="append", metavar="KEY=VALUE",
                        help="override a value, e.g. --set mesh.nx=40 --set 'gap.h0=2 um' (repeatable)")
        sp.add_argument("--smoke", action="store_true", help="merge the case's [smoke] table (coarse, fast)")

    r = sub.add_parser("run", parents=[verbose], help="solve a case and write its outputs")
    with_case(r)
    r.add_argument("--out", metavar="DIR", help="output folder (default runs/<case stem>)")
    r.add_argument("--dry-run", action="store_true", help="validate, build and print the plan; write nothing")
    r.set_defaults(func=cmd_run)
    v = sub.add_parser("validate", parents=[verbose], help="check a case file (exit 0 OK, 2 with the error)")
    with_case(v)
    v.set_defaults(func=cmd_validate)
    sub.add_parser("cases", parents=[verbose], help="list the bundled cases").set_defaults(func=cmd_cases)
    sub.add_parser("info", parents=[verbose], help="versions and machine").set_defaults(func=cmd_info)
    return p


@contextlib.contextmanager
def _logging_to_stderr(verbosity: int):
    """Log records to stderr for the duration of one command, then restore."""
    level = logging.WARNING if verbosity <= 0 else (logging.INFO if verbosity == 1 else logging.DEBUG)
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("lubedyn: %(levelname)s: %(name)s: %(message)s"))
    root = logging.getLogger()
    # third-party chatter (scikit-fem's "Transforming over 1000 vertices ...") only at -vv
    quiet = {name: logging.getLogger(name) for name in ("skfem", "matplotlib", "pyvista")}
    saved = (root.level, {name: lg.level for name, lg in quiet.items()})
    root.addHandler(handler)
    root.setLevel(level)
    for lg in quiet.values():
        lg.setLevel(logging.DEBUG if verbosity >= 2 else logging.ERROR)
    # "compiling kernels (first run only)" (coupling.compilation, INFO) on a terminal even without -v
    compiling = logging.getLogger("coupling.compilation")
    saved_compiling = compiling.level
    if sys.stderr.isatty():
        compiling.setLevel(min(level, logging.INFO))
    try:
        yield
    finally:
        root.removeHandler(handler)
        root.setLevel(saved[0])
        compiling.setLevel(saved_compiling)
        for name, lg in quiet.items():
            lg.setLevel(saved[1][name])


def main(argv=None) -> int:
    """Entry point of the ``lubedyn`` console script; returns the exit code."""
    os.environ.setdefault("MPLBACKEND", "Agg")
    args = _parser().parse_args(argv)
    try:
        with _logging_to_stderr(getattr(args, "verbose", 0)):
            return args.func(args)
    except InputError as exc:
        print(f"lubedyn: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_INPUT
    except ConvergenceError as exc:
        print(f"lubedyn: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_FAILED
    except OSError as exc:
        print(f"lubedyn: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt:
        print("lubedyn: error: interrupted", file=sys.stderr)
        return 130


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
