"""Specialised kernels without code written at run time (issue 13): the shipped modules of
dynamics/kernels are what the generator produces now, a stale one is not used, and without
LUBEDYN_KERNEL_CACHE a user's right-hand side gets a working kernel and no file is written."""
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np

from dynamics import codegen
from dynamics import integrators as I
from dynamics import specialise as S

ROOT = Path(__file__).resolve().parents[1]


def test_shipped_kernels_are_up_to_date():
    """`python -m dynamics.codegen --check` finds nothing to regenerate: a kernel, bearing model or law
    edited without regenerating fails here (and would otherwise be refused at run time)."""
    assert codegen.generate(check=True) == []


def test_shipped_kernel_is_used_for_the_bearing(caplog):
    from dynamics import cageless

    kernel = I.specialise(I._dopri5_impl, rhs=cageless.rhs)
    assert kernel.py_func.__module__ == "dynamics.kernels.k_dopri5_impl__dynamics_cageless_kernels_rhs"


def test_a_stale_shipped_kernel_is_refused(tmp_path, monkeypatch, caplog):
    """A committed module whose digest does not match the sources gives the generic kernel and a
    warning naming the file (numba's cache would otherwise keep the old callee code)."""
    from dynamics import cageless

    stem, digest, text = S.generated_module(I._rk4_impl, {"rhs": cageless.rhs})
    (tmp_path / f"{stem}.py").write_text(text.replace(digest, "0" * 16))
    monkeypatch.setattr(S, "KERNEL_DIR", tmp_path)
    monkeypatch.delenv("LUBEDYN_KERNEL_CACHE", raising=False)
    monkeypatch.setattr(S, "_SPECIALISED", {})
    with caplog.at_level("WARNING", logger="dynamics.specialise"):
        kernel = I.specialise(I._rk4_impl, rhs=cageless.rhs)
    assert "out of date" in caplog.text and stem in caplog.text
    assert not kernel.py_func.__module__.startswith("dynamics.kernels")


def test_no_file_is_written_without_the_opt_in(tmp_path):
    """A user's rhs in a fresh process with HOME and XDG_CACHE_HOME in tmp_path and no
    LUBEDYN_KERNEL_CACHE: DOPRI5 integrates y' = -y to exp(-1) and nothing appears under tmp_path."""
    script = tmp_path / "user_rhs.py"
    script.write_text(textwrap.dedent("""
        import math, sys
        import numpy as np
        from numba import njit
        from dynamics.integrators import integrate

        @njit(cache=False)
        def decay(t, y, args, dydt):
            dydt[0] = -y[0]

        res = integrate(decay, np.array([1.0]), np.array([0.0, 1.0]), (), rtol=1e-10, atol=1e-12)
        sys.stdout.write(repr(float(res.y[-1, 0])))
    """))
    env = {k: v for k, v in os.environ.items() if k != "LUBEDYN_KERNEL_CACHE"}
    env.update(HOME=str(tmp_path / "home"), XDG_CACHE_HOME=str(tmp_path / "xdg"), PYTHONPATH=str(ROOT))
    out = subprocess.run([sys.executable, str(script)], env=env, cwd=tmp_path, capture_output=True, text=True,
                         check=True).stdout
    assert abs(float(out) - np.exp(-1.0)) < 1e-8
    written = [p for p in tmp_path.rglob("*") if p.is_file() and p != script]
    assert written == []
