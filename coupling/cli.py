"""``lubedyn``: run, validate and list case files; run studies over many cases; report versions.

::

    lubedyn run CASE.toml [--out DIR] [--set KEY=VALUE ...] [--dry-run] [--smoke]
    lubedyn validate CASE.toml [--set KEY=VALUE ...] [--smoke]
    lubedyn study STUDY.toml [--out DIR] [--smoke] [--workers N] [--scheduler ADDR]
    lubedyn cases
    lubedyn info

``CASE`` may also be the name of a bundled case (``lubedyn run journal_finite``).
``--smoke`` merges the case's ``[smoke]`` table (coarse mesh) before ``--set``.
``--dry-run`` validates and builds the mesh and film, prints the plan and the
resolved case, and writes nothing.  ``study`` runs a base case over axes of ``--set`` values
and ensemble members, each run a normal run folder under ``DIR/runs/``, and writes
``study.csv``, ``study.json``, ``study.nc`` and ``study.png`` (:mod:`lubedyn.scenes.study`; ``--out`` defaults
to ``runs/<study stem>``); a run that fails is recorded and the others go on, and the exit
code is then 1.

Exit codes: 0 success; 1 a solve that did not converge (a study: a run that
failed); 2 input error (bad
TOML, unknown key, wrong unit, value out of range, missing file, impossible
geometry, an empty ``--out``); 3 an output that cannot be written (read-only
folder, a file where a folder is needed, disk full); 130 interrupted (Ctrl-C);
141 standard output closed before everything was written (``| head``).
Errors are one line on stderr, prefixed ``lubedyn: error:``, with no
traceback; an interrupt prints ``lubedyn: interrupted``.

Nothing heavy is imported before :func:`main` has installed its SIGINT
handler, so that a Ctrl-C at any moment (while scipy, VTK or numba load)
ends with that one line.
"""
from __future__ import annotations

import argparse
import contextlib
import logging
import os
import signal
import sys
import threading
from pathlib import Path

from lubedyn.lubrication.errors import close_matches, did_you_mean

EXIT_OK, EXIT_FAILED, EXIT_INPUT, EXIT_OUTPUT, EXIT_INTERRUPTED, EXIT_PIPE = 0, 1, 2, 3, 130, 141
log = logging.getLogger("lubedyn")
_interrupt = threading.Event()  # set by the SIGINT handler of main()


class _StdoutClosed(Exception):
    """Standard output was closed by its reader (``lubedyn ... | head``)."""


def _say(*args) -> None:
    """``print`` to stdout; a closed pipe ends the command quietly (:class:`_StdoutClosed`)."""
    try:
        print(*args)
    except BrokenPipeError:
        raise _StdoutClosed from None


class _Parser(argparse.ArgumentParser):
    """argparse with the project's one-line error format (exit code 2)."""

    def error(self, message):
        self.exit(EXIT_INPUT, f"lubedyn: error: {message} (see '{self.prog} --help')\n")


def _load(args):
    from lubedyn.config import load_case_file

    return load_case_file(args.case, smoke=args.smoke, overrides=args.set or ())


def _out_dir(args, path: Path) -> Path:
    """The output folder: ``--out`` or ``runs/<case stem>``; refuses an empty ``--out`` (input error)
    and, before any work, a folder that cannot be made (:class:`lubedyn.outputs.OutputError`)."""
    from lubedyn.lubrication.errors import InputError

    from lubedyn.outputs import OutputError

    if args.out is not None and not args.out.strip():
        raise InputError(f"--out = {args.out!r}: an empty path; give a folder (default runs/{path.stem})")
    out = Path(args.out) if args.out is not None else Path("runs") / path.stem
    if out.exists() and not out.is_dir():
        raise OutputError(out, "it is a file, not a folder")
    parent = out
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if parent.exists() and not parent.is_dir():
        raise OutputError(out, f"{parent} is a file, not a folder")
    if parent.is_dir() and not os.access(parent, os.W_OK | os.X_OK):
        raise OutputError(out, f"permission denied on {parent}")
    return out


def cmd_run(args) -> int:
    from lubedyn import scenes
    from lubedyn.config import check_smoke, resolved_toml
    from lubedyn.lubrication.errors import InputError
    from lubedyn.scenes.runner import run_loaded

    path, raw, case = _load(args)
    scene = scenes.get(case.scene)
    out = _out_dir(args, path)
    if args.dry_run:
        try:
            built = scene.build(case)
        except InputError as exc:
            raise (check_smoke(raw, args.set or (), exc) if args.smoke else exc) from None
        _say(f"dry run: {scene.describe(case, built)}")
        _say(f"dry run: would write {out}/summary.json, case.resolved.toml"
             + "".join(f", {_field_file(case, f)}" for f, k in scene.FIELD_FILES if k in case.output.write)
             + ", manifest.json")
        _say(resolved_toml(case, f"dry run of {path}"))
        return EXIT_OK
    result = run_loaded(path, raw, case, out, smoke=args.smoke, overrides=args.set or ())
    for line in scene.headline(result.summary):
        _say(line)
    _say(f"wrote {out}/: " + ", ".join(p.name for p in result.files))
    return EXIT_OK


def _field_file(case, name: str) -> str:
    """A scene's field file as the case writes it: the time series' name by ``output.timeseries_format``."""
    fmt = getattr(case.output, "timeseries_format", None)
    if fmt is not None and name.startswith("timeseries."):
        from lubedyn.outputs import TIMESERIES_FILES

        return TIMESERIES_FILES[fmt]
    return name


def cmd_study(args) -> int:
    """``lubedyn study``: run a study (:mod:`lubedyn.scenes.study`) and write its tables; exit 1 when a run failed.
    Runs that finished with warnings are counted on the final line (each one is logged, and tabulated
    as ``ok-with-warnings``) but do not change the exit code: their results exist, flagged."""
    from lubedyn.lubrication.errors import InputError

    from lubedyn.scenes.study import read_study, run_study

    if args.workers is not None and args.workers < 0:
        raise InputError(f"--workers = {args.workers} must be >= 0 (0: every usable core)")
    if args.scheduler is not None and not args.scheduler.strip():
        raise InputError(f"--scheduler = {args.scheduler!r}: an empty address; give the Dask scheduler's, "
                         "e.g. tcp://host:8786")
    path = Path(args.study)
    study = read_study(path)
    out = _out_dir(args, path)
    progress = logging.getLogger("lubedyn.scenes.study")  # "run 3/16 done (...)" on stderr without -v
    saved = progress.level
    if progress.getEffectiveLevel() > logging.INFO:
        progress.setLevel(logging.INFO)
    try:
        result = run_study(study, path, out, smoke=args.smoke, workers=args.workers, scheduler=args.scheduler)
    finally:
        progress.setLevel(saved)
    _say(f"study: {result.total} runs ({result.reused} reused, {result.ran} run, {len(result.failed)} failed), "
         f"{len(result.warned)} with warnings, {result.backend}")
    _say(f"wrote {out}/: " + ", ".join(p.name for p in result.files) + f"; run folders in {out}/runs/")
    if result.failed:
        folder, message = result.failed[0]
        _error_line(f"lubedyn: error: {len(result.failed)} of {result.total} runs failed (listed in "
                    f"{out}/study.csv), e.g. {folder}: {message}")
        return EXIT_FAILED
    return EXIT_OK


def cmd_validate(args) -> int:
    from lubedyn import scenes
    from lubedyn.config import check_smoke, in_smoke, validate_raw
    from lubedyn.lubrication.errors import InputError

    path, raw, case = _load(args)
    scene = scenes.get(case.scene)
    try:
        built = scene.build(case)
    except InputError as exc:
        raise (check_smoke(raw, args.set or (), exc) if args.smoke else exc) from None
    if not args.smoke and isinstance(raw.get("smoke"), dict):  # the smoke variant must be valid too
        try:  # the base case is valid: an error here lives in [smoke]
            smoke_case = validate_raw(raw, smoke=True, overrides=args.set or ())
            scenes.get(smoke_case.scene).build(smoke_case)
        except InputError as exc:
            raise in_smoke(exc, raw) from None
    _say(f"OK {path}: {scene.describe(case, built)}")
    return EXIT_OK


def cmd_cases(args) -> int:
    import tomllib

    from lubedyn.config import bundled_cases

    paths = bundled_cases()
    width = max((len(p.stem) for p in paths), default=10)
    for path in paths:
        try:
            description = tomllib.loads(path.read_text(encoding="utf-8")).get("description", "")
        except (OSError, tomllib.TOMLDecodeError) as exc:
            description = f"(unreadable: {' '.join(str(exc).split())})"
        _say(f"{path.stem:<{width}}  {description}")
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
        _say(f"{key:<11} {value}")
    return EXIT_OK


def _parser() -> argparse.ArgumentParser:
    verbose = argparse.ArgumentParser(add_help=False)
    verbose.add_argument("-v", "--verbose", action="count", default=argparse.SUPPRESS,
                         help="more log output (-v info, -vv debug)")
    p = _Parser(prog="lubedyn", parents=[verbose], formatter_class=argparse.RawDescriptionHelpFormatter,
                description="Lubricant films by finite elements, film maps and rolling-bearing dynamics.\n\n"
                            "scenes: film (Reynolds films: sliders, pockets, journals, squeeze films),\n"
                            "        ehl (isothermal EHL point and line contacts),\n"
                            "        map (film maps swept over their axes, local processes or Dask),\n"
                            "        dynamics (the cage-less ball bearing in numba: drop, steady, free)",
                epilog="exit codes: 0 ok, 1 solve did not converge, 2 input error, 3 output cannot be written,\n"
                       "130 interrupted, 141 stdout closed early")
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
    st = sub.add_parser("study", parents=[verbose], help="run a case over axes of --set values and tabulate")
    st.add_argument("study", help="study file (TOML): base case, [axes], [study], [paper]")
    st.add_argument("--out", metavar="DIR", help="output folder (default runs/<study stem>)")
    st.add_argument("--smoke", action="store_true", help="every run with its case's [smoke] table")
    st.add_argument("--workers", type=int, metavar="N", help="local worker processes (0: every usable core; "
                    "default: the study file's)")
    st.add_argument("--scheduler", metavar="ADDR", help="run on this Dask scheduler instead")
    st.set_defaults(func=cmd_study)
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
    # "compiling kernels (first run only)" (lubedyn.compilation, and lubedyn.dynamics.specialise for the second
    # process's share, INFO) on a terminal even without -v
    compiling = [logging.getLogger(name) for name in ("lubedyn.compilation", "lubedyn.dynamics.specialise")]
    saved_compiling = [lg.level for lg in compiling]
    if sys.stderr.isatty():
        for lg in compiling:
            lg.setLevel(min(level, logging.INFO))
    try:
        yield
    finally:
        root.removeHandler(handler)
        root.setLevel(saved[0])
        for lg, lvl in zip(compiling, saved_compiling):
            lg.setLevel(lvl)
        for name, lg in quiet.items():
            lg.setLevel(saved[1][name])


def _interrupted(exc: BaseException) -> bool:
    """Whether ``exc`` comes from a Ctrl-C: the SIGINT handler ran, or a KeyboardInterrupt is in its
    chain (numba's ``SystemError: CPUDispatcher ... returned a result with an exception set``, VTK's
    ``ImportError: Failed to load vtkCommonMath`` when the interrupt lands inside their C code)."""
    if _interrupt.is_set():
        return True
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False


_program = False  # main() runs as the program (argv from sys.argv), not called by Python code
_main_pid = os.getpid()  # the process that prints "lubedyn: interrupted" (not a forked child)
_exiting = False


def _exit_interrupted() -> int:
    """The one line; as a program, end the process now (``os._exit(130)``) after removing the staging
    folders of the outputs being written.

    A KeyboardInterrupt raised into library code can leave it half-initialised (VTK's and llvmlite's
    imports and object caches catch it, print it and go on; a numba dispatcher returns a
    ``SystemError``) and the run then crashed or went on: in sweeps of SIGINT over a dynamics run,
    tracebacks, segfaults (SIGSEGV in 8 of 105 interrupts over three sweeps) and runs that finished
    regardless.
    Ending at once loses nothing: outputs are written atomically, a staging folder of a killed run is
    removed by the next run, map points are stored as they are solved, and map workers die with
    their parent."""
    global _exiting
    if _program and (_exiting or os.getpid() != _main_pid):
        # a second signal while exiting, or a forked child of a library that inherited the handler:
        # the line is the parent's to print, once
        os._exit(EXIT_INTERRUPTED)
    _exiting = True
    _error_line("lubedyn: interrupted")
    if _program:
        outputs = sys.modules.get("lubedyn.outputs")
        if outputs is not None:
            outputs.discard_staging()
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        os._exit(EXIT_INTERRUPTED)
    return EXIT_INTERRUPTED


def _on_sigint(signum, frame):
    _interrupt.set()
    if _program:
        _exit_interrupted()
    raise KeyboardInterrupt


@contextlib.contextmanager
def _sigint_flag():
    """While a command runs: SIGINT sets :data:`_interrupt`; as a program it ends the process
    (:func:`_exit_interrupted`), called from Python it raises KeyboardInterrupt.  Only in the main
    thread and where Python's default handler is installed (a handler of the caller is left alone).
    As a program, SIGINT is ignored once the command is done (an interrupt during the interpreter's
    exit gave status -2)."""
    _interrupt.clear()
    install = (threading.current_thread() is threading.main_thread()
               and signal.getsignal(signal.SIGINT) is signal.default_int_handler)
    if install:
        signal.signal(signal.SIGINT, _on_sigint)
    try:
        yield
    finally:
        if install:
            signal.signal(signal.SIGINT, signal.SIG_IGN if _program else signal.default_int_handler)


def _quiet_stdout() -> None:
    """After a closed pipe: point stdout at devnull so that the interpreter's final flush is silent."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):  # stdout is not a file (captured in a test)
        pass


def main(argv=None) -> int:
    """Entry point of the ``lubedyn`` console script; returns the exit code.

    With ``argv`` None (the program: the console script, ``python -m lubedyn.cli``) an interrupt
    ends the process at once (:func:`_exit_interrupted`); called with a list, it raises
    KeyboardInterrupt through the command and returns 130."""
    global _program, _main_pid, _exiting
    os.environ.setdefault("MPLBACKEND", "Agg")
    args = _parser().parse_args(argv)
    _program, _main_pid, _exiting = argv is None, os.getpid(), False
    with _sigint_flag():
        try:
            with _logging_to_stderr(getattr(args, "verbose", 0)):
                code = args.func(args)
            try:
                sys.stdout.flush()
            except BrokenPipeError:
                raise _StdoutClosed from None
            if _interrupt.is_set():  # a Ctrl-C that a callback dropped: the user asked to stop
                raise KeyboardInterrupt
            return code
        except _StdoutClosed:
            _quiet_stdout()
            return EXIT_PIPE
        except BaseException as exc:  # noqa: BLE001 - every exit path gives one line and an exit code
            if isinstance(exc, SystemExit):
                raise
            if _interrupted(exc):
                return _exit_interrupted()
            from lubedyn.lubrication.errors import ConvergenceError, InputError

            from lubedyn.outputs import OutputError

            if isinstance(exc, InputError):
                code = EXIT_INPUT
            elif isinstance(exc, ConvergenceError):
                code = EXIT_FAILED
            elif isinstance(exc, OutputError):
                code = EXIT_OUTPUT
            elif isinstance(exc, OSError):
                code = EXIT_FAILED
            else:
                raise
            _error_line(f"lubedyn: error: {_one_line(exc)}")
            return code


def _error_line(text: str) -> None:
    try:
        if text == "lubedyn: interrupted" and sys.stderr.isatty():
            text = "\r\x1b[K" + text  # over a progress bar that will not be closed
        print(text, file=sys.stderr)
    except (OSError, ValueError):  # stderr closed as well: nothing to tell
        pass


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
