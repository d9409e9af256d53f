"""The command line under interrupts, kills, reruns, closed pipes and unwritable outputs: exit codes, one-line messages, an output folder that holds one run.

Real processes where a signal is involved (SIGINT to the process group as a terminal sends it,
SIGKILL of the parent of a map build's workers); ``lubedyn.cli.main`` in-process otherwise.
"""
from __future__ import annotations

import errno
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from lubedyn import cli, outputs
from lubedyn.config import CASES_DIR

SLIDER = CASES_DIR / "inclined_slider.toml"
POCKET = CASES_DIR / "fowell_pocket.toml"
DYNAMICS = CASES_DIR / "cageless_6206_10krpm_short.toml"
WORKTREE = Path(__file__).resolve().parents[1]
TESTS = Path(__file__).resolve().parent


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def one_line_error(err: str, *fragments: str):
    assert err.startswith("lubedyn: error: "), err
    assert err.count("\n") == 1, f"not one line: {err!r}"
    for fragment in fragments:
        assert fragment in err, f"{fragment!r} not in {err!r}"


def tree(folder: Path) -> dict:
    """{relative path: bytes} of every file below ``folder`` (hidden ones included)."""
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def dead_pid() -> int:
    """The id of a process that has ended (and been reaped)."""
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


posix_signals = pytest.mark.skipif(not hasattr(os, "killpg"), reason="POSIX process groups and signals")
proc_children = pytest.mark.skipif(not Path(f"/proc/self/task/{os.getpid()}/children").exists(),
                                   reason="needs Linux /proc/<pid>/task/<tid>/children")


_PROCESSES: list = []


def _tracked(proc):
    """Register a child so that the fixture below closes its pipes (and ends it) after the test."""
    _PROCESSES.append(proc)
    return proc


@pytest.fixture(autouse=True)
def _close_children():
    """Every child's pipes are closed and the child ended after its test: left open they are
    ResourceWarnings (errors under the suite's warning filter) and leaked descriptors."""
    yield
    while _PROCESSES:
        proc = _PROCESSES.pop()
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        for stream in (proc.stdin, proc.stdout, proc.stderr):
            if stream is not None:
                stream.close()


def _terminal_sigint():
    """In the child before it runs Python: SIGINT as a terminal's foreground program has it (default
    disposition, not blocked).  A test suite started in the background by a shell without job control
    (``pytest ... &``) has SIGINT ignored, and every process it starts inherits that: its runs could not
    be interrupted at all, whatever the CLI does."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def cli_process(*argv, **kwargs):
    """``python -m lubedyn.cli ARGV`` (the installed lubedyn: this checkout, installed editable), in its own
    process group, SIGINT as in a terminal."""
    return _tracked(subprocess.Popen([sys.executable, "-m", "lubedyn.cli", *map(str, argv)], cwd=WORKTREE,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                     start_new_session=True, preexec_fn=_terminal_sigint, **kwargs))


def alive(pid: int) -> bool:
    """A process that exists and is not a zombie."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] != "Z"
    except (FileNotFoundError, ProcessLookupError):
        return False


def children(pid: int) -> list[int]:
    out = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            out += [int(c) for c in (task / "children").read_text().split()]
        except OSError:
            pass
    return out


# ---------------------------------------------------------------------------
# item 5: messages for a directory, a bundled-name typo, an empty --out, errors of [smoke]


def test_directory_as_case_file_says_it_is_a_directory(tmp_path, capsys):
    code, _, err = run(capsys, "run", tmp_path)
    assert code == 2
    one_line_error(err, f"case file {str(tmp_path)!r} is a directory; expected a .toml case file")


@pytest.mark.parametrize("typo, meant", [
    ("journal_finit", "'journal_finite'"), ("rayleigh_stp.toml", "'rayleigh_step'"),
    (str(CASES_DIR / "inclined_sldier.toml"), repr(str(CASES_DIR / "inclined_slider.toml"))),
    ("inclined_slider.tom", None), ("nothing_like_a_case", None)])
def test_case_name_typo_gets_did_you_mean(tmp_path, monkeypatch, capsys, typo, meant):
    """A bare name close to a bundled case, or a path close to a case file next to it: 'did you mean'."""
    monkeypatch.chdir(tmp_path)
    code, _, err = run(capsys, "validate", typo)
    assert code == 2
    if meant:
        one_line_error(err, f"case file {typo!r} not found", f"did you mean {meant}")
    else:
        one_line_error(err, f"case file {typo!r} not found")
        assert "did you mean" not in err


def test_unreadable_case_file_is_an_input_error(tmp_path, capsys, monkeypatch):
    """A case file that cannot be read (no permission: simulated, the tests may run as root): exit 2
    naming the file and the cause (was exit 1 with the raw errno text)."""
    case = tmp_path / "locked.toml"
    case.write_text(SLIDER.read_text())
    real = Path.read_text

    def locked(self, *args, **kwargs):
        if self == case:
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(self))
        return real(self, *args, **kwargs)

    monkeypatch.setattr(Path, "read_text", locked)
    code, _, err = run(capsys, "validate", case)
    assert code == 2
    one_line_error(err, f"case file {str(case)!r} cannot be read: Permission denied")


def test_empty_out_is_refused_and_nothing_is_written(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = run(capsys, "run", SLIDER, "--smoke", "--out", "")
    assert code == 2
    one_line_error(err, "--out = '': an empty path")
    assert list(tmp_path.iterdir()) == []  # not runs/inclined_slider either


@pytest.mark.parametrize("command", [("validate",), ("validate", "--smoke"), ("run", "--smoke", "--dry-run")])
def test_error_of_the_smoke_table_names_it(tmp_path, capsys, command):
    """A value that only [smoke] sets is reported as smoke.KEY; a geometry error that only the smoke
    variant has (found when the scene is built) as 'in [smoke]: ...'.  (Before: the same message as
    for an error of the case, and 'validate' without --smoke did not say where the error was.)"""
    text = SLIDER.read_text().replace("[smoke]           # `--smoke` (tests): coarse mesh\n",
                                      "[smoke]\nmesh.element = \"P7\"\n")
    case = tmp_path / "bad_smoke.toml"
    case.write_text(text)
    code, _, err = run(capsys, command[0], case, *command[1:])
    assert code == 2
    one_line_error(err, "smoke.mesh.element = 'P7' is not allowed; choose one of 'P1', 'P2'")
    # a value the schema accepts that only the smoke variant's build refuses: the gap closes inside the pocket
    pocket = tmp_path / "bad_smoke_pocket.toml"
    pocket.write_text(POCKET.read_text() + 'gap.depth = "-1.04 um"\n')
    code, _, err = run(capsys, command[0], pocket, *command[1:])
    assert code == 2
    one_line_error(err, "in [smoke]: gap (pocketed_slider): film thickness h = ", "must be > 0 everywhere")
    # an error of the case itself is not blamed on [smoke]
    pocket.write_text(POCKET.read_text().replace('depth = "1 um"', 'depth = "-1.04 um"'))
    code, _, err = run(capsys, command[0], pocket, *command[1:])
    assert code == 2 and "smoke" not in err
    one_line_error(err, "gap (pocketed_slider)", "must be > 0 everywhere")


# ---------------------------------------------------------------------------
# item 5: outputs that cannot be written: exit 3, one line naming the path and the cause


def test_out_is_a_file(tmp_path, capsys):
    blocker = tmp_path / "results"
    blocker.write_text("mine")
    for out, fragment in ((blocker, f"cannot write {blocker}: it is a file, not a folder"),
                          (blocker / "run1", f"cannot write {blocker / 'run1'}: {blocker} is a file, not a folder")):
        code, stdout, err = run(capsys, "run", SLIDER, "--smoke", "--out", out)
        assert code == 3 and stdout == ""
        one_line_error(err, fragment)
    assert blocker.read_text() == "mine"


def test_disk_full_while_writing(tmp_path, capsys, monkeypatch):
    """ENOSPC in the middle of the write: one line with the file (as named in --out, not its staging
    copy) and the cause; the previous run's files stay whole, no staging folder is left."""
    out = tmp_path / "out"
    assert run(capsys, "run", SLIDER, "--smoke", "--out", out)[0] == 0
    before = tree(out)
    real_fsync = os.fsync
    calls = []

    def full(fd):
        calls.append(fd)
        if len(calls) == 2:  # case.resolved.toml went through, the next file does not
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return real_fsync(fd)

    monkeypatch.setattr(outputs.os, "fsync", full)
    code, _, err = run(capsys, "run", SLIDER, "--smoke", "--set", "motion.velocity_lower=9 m/s", "--out", out)
    assert code == 3
    one_line_error(err, f"cannot write {out}/", ": No space left on device")
    assert ".staging" not in err
    assert tree(out) == before


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root writes into read-only folders")
def test_read_only_folder(tmp_path, capsys):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        code, _, err = run(capsys, "run", SLIDER, "--smoke", "--out", ro / "run")
        assert code == 3
        one_line_error(err, f"cannot write {ro / 'run'}: permission denied on {ro}")
    finally:
        ro.chmod(0o755)


# ---------------------------------------------------------------------------
# item 4 (c), (d): stale staging folders, a run owns its folder


def test_stale_staging_folders_of_dead_runs_are_removed(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    dead = dead_pid()
    stale = [out / f".staging-{dead}-k1ll3d", out / f".old-{dead}-frames-x7"]
    live = out / f".staging-{os.getpid()}-writing"  # a process that exists: still writing, kept
    legacy_old, legacy_new = out / ".staging-abc123xy", out / ".staging-zz9_recent"  # no pid: by age
    for folder in (*stale, live, legacy_old, legacy_new):
        folder.mkdir()
        (folder / "timeseries.npz").write_bytes(b"\0" * 1000)
    os.utime(legacy_old, (time.time() - 3600, time.time() - 3600))
    assert run(capsys, "run", SLIDER, "--smoke", "--out", out)[0] == 0
    assert not any(p.exists() for p in (*stale, legacy_old))
    assert live.is_dir() and legacy_new.is_dir()
    assert (out / "summary.json").is_file()


@posix_signals
def test_run_killed_while_writing_leaves_nothing_after_the_next_run(tmp_path, capsys):
    """SIGKILL of a real run in the middle of its write (the fields and the plot staged, the summary
    not yet): the previous outputs stay whole, and the next run removes the staging folder (it used
    to stay for ever, one more with each kill)."""
    out = tmp_path / "out"
    assert run(capsys, "run", SLIDER, "--smoke", "--out", out)[0] == 0
    before = {k: v for k, v in tree(out).items()}
    script = textwrap.dedent(f"""
        import os, signal, sys
        from lubedyn import cli, outputs
        real = outputs.write_json
        def killed(path, mapping):
            if path.name == "summary.json" and path.parent.name.startswith(".staging-"):
                os.kill(os.getpid(), signal.SIGKILL)
            return real(path, mapping)
        outputs.write_json = killed
        cli.main(["run", {str(SLIDER)!r}, "--smoke", "--set", "motion.velocity_lower=50 m/s", "--out", {str(out)!r}])
    """)
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert proc.returncode == -signal.SIGKILL
    staging = list(out.glob(".staging-*"))
    assert len(staging) == 1 and {p.name for p in staging[0].iterdir()} == {"case.resolved.toml", "film.vtu",
                                                                            "pressure.png"}
    assert {k: v for k, v in tree(out).items() if not k.startswith(".staging-")} == before
    assert run(capsys, "run", SLIDER, "--smoke", "--out", out)[0] == 0
    assert not list(out.glob(".staging-*"))
    assert sorted(p.name for p in out.iterdir()) == ["case.resolved.toml", "film.vtu", "manifest.json",
                                                     "pressure.png", "summary.json"]


def test_rerun_with_fewer_outputs_replaces_the_previous_run(tmp_path, capsys):
    """The 5 m/s film.vtu must not survive next to a 50 m/s summary; a user's own file stays."""
    out = tmp_path / "out"
    assert run(capsys, "run", SLIDER, "--smoke", "--out", out)[0] == 0
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["files"] == ["case.resolved.toml", "film.vtu", "pressure.png", "summary.json"]
    assert manifest["case"] == "inclined_slider" and manifest["scene"] == "film"
    (out / "notes.txt").write_text("my notes")
    code, _, _ = run(capsys, "run", SLIDER, "--smoke", "--out", out,
                     "--set", "motion.velocity_lower=50 m/s", "--set", "output.write=[]")
    assert code == 0
    assert sorted(p.name for p in out.iterdir()) == ["case.resolved.toml", "manifest.json", "notes.txt",
                                                     "summary.json"]
    assert json.loads((out / "manifest.json").read_text())["files"] == ["case.resolved.toml", "summary.json"]
    assert (out / "notes.txt").read_text() == "my notes"


def test_manifest_replaces_folders_and_never_leaves_the_output_folder(tmp_path, caplog):
    """At the library level: a sub-folder of the previous run (frames/) goes when the new run has none;
    a manifest entry pointing outside the folder or at a hidden entry is ignored; a folder without a
    manifest keeps its files and says so."""
    out = tmp_path / "out"
    outside = tmp_path / "precious.txt"
    outside.write_text("keep")
    out.mkdir()
    (out / ".map-cache").mkdir()
    (out / ".map-cache" / "p.json").write_text("{}")
    (out / "old_result.csv").write_text("from a lubedyn without manifests")
    with caplog.at_level("WARNING", logger="lubedyn.outputs"):
        with outputs.staged(out) as stage:
            (stage / "frames").mkdir()
            for k in range(3):
                outputs.write_text(stage / "frames" / f"frame_{k}.vtp", str(k))
            outputs.write_json(stage / "summary.json", {"Case": "a", "Scene": "dynamics"})
    assert "had no manifest.json: kept 1 file(s) that this run did not write (old_result.csv)" in caplog.text
    assert json.loads((out / "manifest.json").read_text())["files"] == [
        "frames/frame_0.vtp", "frames/frame_1.vtp", "frames/frame_2.vtp", "summary.json"]
    manifest = json.loads((out / "manifest.json").read_text())
    manifest["files"] += ["../precious.txt", str(outside), ".map-cache/p.json"]
    (out / "manifest.json").write_text(json.dumps(manifest))
    with outputs.staged(out) as stage:
        outputs.write_json(stage / "summary.json", {"Case": "b", "Scene": "dynamics"})
    assert sorted(p.name for p in out.iterdir()) == [".map-cache", "manifest.json", "old_result.csv", "summary.json"]
    assert outside.read_text() == "keep" and (out / ".map-cache" / "p.json").is_file()
    assert json.loads((out / "manifest.json").read_text())["case"] == "b"


def test_kill_in_the_middle_of_a_commit_leaves_every_file_listed(tmp_path, monkeypatch):
    """A kill after the new files are in place but before the old ones are removed: the manifest on
    disk lists both, so the next run removes the leftovers."""
    out = tmp_path / "out"
    with outputs.staged(out) as stage:
        for name in ("a.vtu", "summary.json"):
            outputs.write_text(stage / name, "1")
    real_replace = outputs.os.replace
    moved = []

    def killed_after_moves(src, dst):
        real_replace(src, dst)
        moved.append(dst)
        if Path(dst) == out / "summary.json":
            raise KeyboardInterrupt  # the last file moved in, nothing else done

    monkeypatch.setattr(outputs.os, "replace", killed_after_moves)
    with pytest.raises(KeyboardInterrupt):
        with outputs.staged(out) as stage:
            outputs.write_text(stage / "b.png", "2")
            outputs.write_text(stage / "summary.json", "2")
    monkeypatch.setattr(outputs.os, "replace", real_replace)
    assert set(json.loads((out / "manifest.json").read_text())["files"]) >= {"a.vtu", "b.png", "summary.json"}
    with outputs.staged(out) as stage:
        outputs.write_text(stage / "summary.json", "3")
    assert sorted(p.name for p in out.iterdir()) == ["manifest.json", "summary.json"]


# ---------------------------------------------------------------------------
# item 4 (f): a closed stdout; item 6: --help


@posix_signals
@pytest.mark.parametrize("argv", [("run", SLIDER, "--dry-run"), ("cases",)])
def test_closed_stdout_exits_141_quietly(argv):
    """The reader of the pipe is gone before lubedyn writes (``lubedyn ... | head`` with head done):
    exit 141 (128 + SIGPIPE, as coreutils), nothing on stderr."""
    proc = cli_process(*argv)
    proc.stdout.close()  # the reader closes at once
    err = proc.stderr.read()
    assert proc.wait(timeout=60) == 141
    assert err == ""


def test_help_lists_what_exists(capsys):
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["--help"])
    assert exit_info.value.code == 0
    text = capsys.readouterr().out
    assert "planned" not in text
    for scene in ("film", "ehl", "map", "dynamics"):
        assert f"{scene} (" in text
    assert "3 output cannot be written" in text and "130 interrupted" in text


# ---------------------------------------------------------------------------
# item 4 (e): Ctrl-C anywhere gives one line and exit 130


def test_exceptions_caused_by_an_interrupt_are_interrupts(capsys, monkeypatch):
    """numba's SystemError and VTK's ImportError when the KeyboardInterrupt lands inside their C code:
    with the interrupt in the chain, or with none in the chain but the SIGINT handler having run."""
    def numba_like(args):
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt:
            raise SystemError("<CPUDispatcher(<function rhs>)> returned a result with an exception set")

    monkeypatch.setattr(cli, "cmd_info", numba_like)
    code, out, err = run(capsys, "info")
    assert (code, out, err) == (130, "", "lubedyn: interrupted\n")

    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        pytest.skip("SIGINT is handled by the test runner here")

    def vtk_like(args):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(5)
        except KeyboardInterrupt:
            pass
        raise ImportError("Failed to load vtkCommonMath: No module named vtkmodules.vtkCommonMath")

    monkeypatch.setattr(cli, "cmd_info", vtk_like)
    code, out, err = run(capsys, "info")
    assert (code, out, err) == (130, "", "lubedyn: interrupted\n")
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # restored

    def unrelated(args):
        raise ImportError("a real import error")

    monkeypatch.setattr(cli, "cmd_info", unrelated)
    with pytest.raises(ImportError, match="a real import error"):  # not an interrupt: a bug, with its traceback
        cli.main(["info"])


@posix_signals
def test_ctrl_c_at_any_moment_of_a_dynamics_run(tmp_path):
    """SIGINT at a sweep of moments of a dynamics run (while scipy, numba kernels, VTK load, during the
    integration): each ends with exit 130, the one line 'lubedyn: interrupted', no traceback and no
    staging folder.  (Before: tracebacks while importing, ImportError exit 1.)  The sweep starts at
    0.3 s: the interpreter's own start and the import of ``lubedyn.cli`` (measured 40 ms together,
    margin for a loaded machine) come before ``main`` can handle anything."""
    out = tmp_path / "out"
    seen = []
    for delay in (0.3, 0.45, 0.6, 0.8, 1.0, 1.3, 1.6, 2.0, 2.5):
        proc = cli_process("run", DYNAMICS, "--smoke", "--out", out)
        time.sleep(delay)
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGINT)
        stdout, err = proc.communicate(timeout=60)
        lines = [line for line in err.splitlines() if not line.startswith(("lubedyn: WARNING:", "lubedyn: INFO:"))]
        if proc.returncode == 0:  # finished before the signal (a fast machine)
            continue
        seen.append(delay)
        assert proc.returncode == 130 and lines == ["lubedyn: interrupted"], (delay, proc.returncode, err)
        assert not list(out.glob(".staging-*")) if out.exists() else True
    assert seen  # at least one interrupt landed


# ---------------------------------------------------------------------------
# item 4 (a), (b): a map build interrupted, or its parent killed

MAP_CASE = """
scene = "map"
description = "analytic squeeze map, slow points"
kind = "test_squeeze"
[axes.central_gap]
lo = "0.1 um"
hi = "10 um"
n = 9
[axes.approach_speed]
lo = "1 mm/s"
hi = "0.1 m/s"
n = 5
[params]
delay = {delay}
log_dir = "{log_dir}"
[build]
workers = 2
accuracy_points = 0
[output]
write = ["map"]
"""


def map_process(tmp_path, delay, program=True):
    """A map build of the analytic squeeze kind (45 points, ``delay`` s each, 2 workers) through the CLI:
    as the program (``main()`` reads ``sys.argv``, as the console script does) or called from Python
    (``main(argv)``: Ctrl-C raises KeyboardInterrupt through the build, as in a notebook)."""
    logs = tmp_path / "calls"
    logs.mkdir(exist_ok=True)
    case = tmp_path / "map.toml"
    case.write_text(MAP_CASE.format(delay=delay, log_dir=logs))
    script = textwrap.dedent(f"""
        import sys
        sys.path.insert(0, {str(TESTS)!r})
        import test_maps  # registers test_squeeze
        from lubedyn import cli
        argv = ["run", {str(case)!r}, "--out", {str(tmp_path / 'out')!r}]
        if {program!r}:
            sys.argv[1:] = argv
            sys.exit(cli.main())
        sys.exit(cli.main(argv))
    """)
    proc = _tracked(subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True, start_new_session=True, preexec_fn=_terminal_sigint))
    return proc, logs, tmp_path / "out" / ".map-cache" / "points" / "test_squeeze", script


def wait_for(condition, timeout=60.0):
    t0 = time.monotonic()
    while not condition():
        assert time.monotonic() - t0 < timeout, "timed out"
        time.sleep(0.02)


@posix_signals
@proc_children
@pytest.mark.parametrize("program", [True, False], ids=["program", "called-from-python"])
def test_ctrl_c_during_a_map_build_stops_at_once_and_keeps_the_points(tmp_path, program):
    """Ctrl-C (SIGINT to the process group, as a terminal sends it) while 2 workers solve 45 points of
    0.3 s (7 s of work): exit 130 within 3 s with one line, the workers gone; every point finished is
    in the cache (at most the 2 in flight are lost); the rerun solves only the rest.  The program
    ends at once (its workers die with it); called from Python, the KeyboardInterrupt cancels the
    pending points and stops the workers.  Before: the build ran every queued point to the end
    (4.8 s after the interrupt), and points came to the cache only per finished line of 5 (3-7 of
    35-39 solved were kept)."""
    proc, logs, store, script = map_process(tmp_path, 0.3, program)
    wait_for(lambda: store.is_dir() and len(list(store.glob("*.json"))) >= 3)
    workers = children(proc.pid)
    t0 = time.monotonic()
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=30)
    stopped = time.monotonic() - t0
    assert proc.returncode == 130 and err == "lubedyn: interrupted\n", err
    assert stopped < 3.0, stopped
    wait_for(lambda: not any(alive(pid) for pid in workers), timeout=5)
    cached = len(list(store.glob("*.json")))
    calls = len(list(logs.iterdir()))
    assert 3 <= cached < 45 and calls - cached <= 2, (cached, calls)
    assert not (tmp_path / "out" / "summary.json").exists()
    if not program:
        return
    # the rerun takes the points the workers stored and solves only the rest
    rerun = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert rerun.returncode == 0, rerun.stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["Points from cache [-]"] == cached and summary["Points solved [-]"] == 45 - cached
    assert len(list(logs.iterdir())) == calls + 45 - cached


@posix_signals
@proc_children
def test_workers_die_with_a_killed_parent(tmp_path):
    """SIGKILL of the CLI process during a map build: its pool workers end within 5 s (they used to
    live on as orphans holding the parent's pipes); the points they finished are in the cache."""
    proc, logs, store, _ = map_process(tmp_path, 0.3)
    wait_for(lambda: store.is_dir() and len(list(store.glob("*.json"))) >= 2)
    workers = children(proc.pid)
    assert len(workers) >= 2, workers
    proc.kill()
    proc.wait()
    wait_for(lambda: not any(alive(pid) for pid in workers), timeout=5)
    assert proc.stdout.read() == ""  # the pipes close: no worker holds them any more
    cached = len(list(store.glob("*.json")))
    assert cached >= 2 and len(list(logs.iterdir())) - cached <= 2


@posix_signals
@pytest.mark.parametrize("platform", ["linux", "darwin"])
def test_die_with_parent_on_linux_and_elsewhere(platform):
    """The means a map worker uses to end with its parent: Linux prctl(PR_SET_PDEATHSIG), elsewhere a
    thread polling getppid() (exercised here by posing as macOS).  The parent is SIGKILLed; the child
    must be gone within 3 s."""
    if platform == "linux" and not sys.platform.startswith("linux"):
        pytest.skip("prctl is Linux only")
    script = textwrap.dedent(f"""
        import multiprocessing, os, sys, time
        from lubedyn import maps

        def child(parent):
            sys.platform = {platform!r}
            os.write(1, f"means={{maps._die_with_parent(parent)}}\\n".encode())  # one write: no interleaving
            time.sleep(60)

        if __name__ == "__main__":
            p = multiprocessing.get_context("fork").Process(target=child, args=(os.getpid(),))
            p.start()
            os.write(1, f"pid={{p.pid}}\\n".encode())
            time.sleep(60)
    """)
    parent = _tracked(subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True))
    lines = dict(parent.stdout.readline().strip().split("=") for _ in range(2))
    child_pid, means = int(lines["pid"]), lines["means"]
    assert means == ("prctl" if platform == "linux" else "watchdog thread")
    assert alive(child_pid)
    parent.kill()
    parent.wait()
    wait_for(lambda: not alive(child_pid), timeout=3)
