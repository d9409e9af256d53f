"""Kernels bound to their callables through numba function pointers (lubedyn.dynamics.specialise):
the same bits as the kernel with the right-hand side linked in, one compiled kernel for every
right-hand side of the same argument types, cached across processes without any file of ours, a
clear error for a callable of the wrong kind, and compilation in a second process."""
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from numba import njit

from lubedyn.config import CASES_DIR
from lubedyn.dynamics import integrators as I
from lubedyn.dynamics import lyapunov as L
from lubedyn.dynamics import specialise as S



@njit(cache=True)
def duffing(t, y, args, dydt):
    """Forced Duffing oscillator x'' + c x' + k x + b x^3 = F cos(w t); args = (coefficients, scale)."""
    p, s = args
    dydt[0] = y[1]
    dydt[1] = -p[0] * y[1] - p[1] * y[0] - p[2] * y[0] ** 3 + p[3] * np.cos(p[4] * t) * s[0]


@njit(cache=True)
def duffing_softer(t, y, args, dydt):
    p, s = args
    dydt[0] = y[1]
    dydt[1] = -p[0] * y[1] - 0.5 * p[1] * y[0] - p[2] * y[0] ** 3 + p[3] * np.cos(p[4] * t) * s[0]


ARGS = (np.array([0.3, -1.0, 1.0, 0.5, 1.2]), np.ones(1))


def test_bound_kernel_gives_the_linked_kernels_bits():
    """DOPRI5 and RK4 on a chaotic Duffing oscillator over 40 s: the pointer-bound kernel and the
    generic one (the rhs compiled into the kernel) agree to the last bit, and DOPRI5 at rtol 1e-10
    agrees with scipy's DOP853 at 1e-12 to 1e-6 (an independent integrator)."""
    from scipy.integrate import solve_ivp

    y0, t = np.array([1.0, 0.0]), np.linspace(0.0, 40.0, 401)
    bound = I.kernel_for("dopri5", duffing)(y0, t, ARGS, 1e-10, 1e-12, 0.0, 0.0, 10**7)[0]
    linked = I.dopri5(duffing, y0, t, ARGS, 1e-10, 1e-12, 0.0, 0.0, 10**7)[0]
    assert np.array_equal(bound, linked)
    ref = solve_ivp(lambda tt, y: [y[1], -0.3 * y[1] + y[0] - y[0] ** 3 + 0.5 * np.cos(1.2 * tt)], (0, 40), y0,
                    method="DOP853", t_eval=t, rtol=1e-12, atol=1e-14)
    assert np.abs(bound - ref.y.T).max() < 1e-6
    rk_bound = I.kernel_for("rk4", duffing)(y0, t, 0.01, ARGS)[0]
    assert np.array_equal(rk_bound, I.rk4(duffing, y0, t, 0.01, ARGS)[0])


def test_one_kernel_serves_every_rhs_of_the_same_types():
    """Two right-hand sides with the same argument types share one compiled kernel: binding the second
    compiles nothing more (the dispatcher keeps one signature) and still integrates its own equations."""
    y0, t = np.array([1.0, 0.0]), np.linspace(0.0, 1.0, 11)
    a = I.kernel_for("dopri5", duffing)(y0, t, ARGS, 1e-9, 1e-12, 0.0, 0.0, 10**6)[0]
    n_sigs = len(I.resumable_kernel("dopri5", duffing).dispatcher.signatures)
    b = I.kernel_for("dopri5", duffing_softer)(y0, t, ARGS, 1e-9, 1e-12, 0.0, 0.0, 10**6)[0]
    assert len(I.resumable_kernel("dopri5", duffing_softer).dispatcher.signatures) == n_sigs
    assert I.resumable_kernel("dopri5", duffing).dispatcher is I.resumable_kernel("dopri5", duffing_softer).dispatcher
    assert not np.array_equal(a, b)
    assert np.array_equal(b, I.dopri5(duffing_softer, y0, t, ARGS, 1e-9, 1e-12, 0.0, 0.0, 10**6)[0])


def test_a_callable_returning_a_value_is_refused_by_name():
    @njit
    def returns(t, y, args, dydt):
        dydt[0] = -y[0]
        return 1.0

    from lubedyn.dynamics.errors import DynamicsInputError

    with pytest.raises(DynamicsInputError, match=r"rhs = .*returns returns float64; the kernel _dopri5_impl needs none"):
        I.integrate(returns, [1.0], [0.0, 1.0], ())


def test_no_file_is_written_outside_numbas_cache(tmp_path):
    """A user's rhs (cache=False) in a fresh process with HOME, XDG_CACHE_HOME and the working directory
    in tmp_path: DOPRI5 integrates y' = -y to exp(-1) and no file appears under tmp_path except numba's
    cache folder, given by NUMBA_CACHE_DIR (the kernel's own cache; nothing of the rhs is in it)."""
    script = tmp_path / "user_rhs.py"
    script.write_text(textwrap.dedent("""
        import sys
        import numpy as np
        from numba import njit
        from lubedyn.dynamics.integrators import integrate

        @njit(cache=False)
        def decay(t, y, args, dydt):
            dydt[0] = -y[0]

        res = integrate(decay, np.array([1.0]), np.array([0.0, 1.0]), (), rtol=1e-10, atol=1e-12)
        sys.stdout.write(repr(float(res.y[-1, 0])))
    """))
    env = dict(os.environ, HOME=str(tmp_path / "home"), XDG_CACHE_HOME=str(tmp_path / "xdg"),
               NUMBA_CACHE_DIR=str(tmp_path / "numba"))
    out = subprocess.run([sys.executable, str(script)], env=env, cwd=tmp_path, capture_output=True, text=True,
                         check=True).stdout
    assert abs(float(out) - np.exp(-1.0)) < 1e-8
    written = [p for p in tmp_path.rglob("*") if p.is_file() and p != script]
    assert written and all((tmp_path / "numba") in p.parents for p in written)
    assert not any("user_rhs" in p.name or "decay" in p.name for p in written)


def test_background_compilation_fills_the_cache_the_caller_then_loads(tmp_path):
    """In a process with an empty numba cache: compile_in_background starts one child for the RK4 and
    Benettin kernels of a Duffing oscillator; the caller's kernels then load from the cache (hits, no
    misses), give the numbers of a plain run, and a second request starts nothing."""
    script = textwrap.dedent("""
        import sys
        import numpy as np
        sys.path.insert(0, sys.argv[1])
        from test_specialise import duffing, ARGS
        from lubedyn.dynamics import integrators as I, lyapunov as L, specialise as S
        y0, t = np.array([1.0, 0.0]), np.linspace(0.0, 2.0, 21)
        rk = I.resumable_kernel("rk4", duffing)
        Y, work = I.new_run(y0, t)
        params = I.make_params(dt=0.01, guard=True)
        ben = S.specialise(L._benettin_impl, rhs=duffing, jvp=L.no_jvp)
        ben_args = (y0.copy(), np.eye(2), np.ones(2), np.ones(2), ARGS, 0.0, 0.01, 10, 0, 20, 2, True, np.zeros(2),
                    np.zeros(1), np.zeros((20, 2)))
        S._usable_cores = lambda: 2  # the mechanism, also on a one-core machine (where runs skip it)
        started = S.compile_in_background([(rk, (t, ARGS, params, Y, work, 1)), (ben, ben_args)])
        rk(t, ARGS, params, Y, work, len(t))
        ben(*ben_args)
        ls = ben_args[12]  # log_sum, filled in place
        again = S.compile_in_background([(rk, (t, ARGS, params, Y, work, 1)), (ben, ben_args)])
        print(started, again, len(rk.stats.cache_hits), len(rk.stats.cache_misses), len(ben.stats.cache_hits),
              len(ben.stats.cache_misses), repr(float(Y[-1, 0])), repr(float(ls[0])))
    """)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path), LUBEDYN_BACKGROUND_COMPILE="1")
    out = subprocess.run([sys.executable, "-c", script, str(Path(__file__).parent)], env=env, capture_output=True,
                         text=True, check=True).stdout.split()
    assert out[:6] == ["2", "0", "1", "0", "1", "0"]
    Y = I.kernel_for("rk4", duffing)(np.array([1.0, 0.0]), np.linspace(0.0, 2.0, 21), 0.01, ARGS)[0]
    assert float(out[6]) == Y[-1, 0]
    log_sum = np.zeros(2)
    S.specialise(L._benettin_impl, rhs=duffing, jvp=L.no_jvp)(
        np.array([1.0, 0.0]), np.eye(2), np.ones(2), np.ones(2), ARGS, 0.0, 0.01, 10, 0, 20, 2, True, log_sum,
        np.zeros(1), np.zeros((20, 2)))
    assert float(out[7]) == log_sum[0]


def test_forces_many_equals_forces_row_by_row():
    """The cage-less bearing's forces_many (the model's body through a function pointer) gives the
    bits of forces() at each state, and forces' state derivative is the bits of rhs, which calls the
    body directly (compiled into it, not through a pointer)."""
    from lubedyn.config import load_case_file
    from lubedyn.scenes.dynamics import build
    from lubedyn.dynamics.cageless import forces, forces_many, rhs

    path, _, case = load_case_file(str(CASES_DIR / "cageless_6206_10krpm_short.toml"),
                                   smoke=True)
    setup = build(case, str(path))
    y0 = setup.y0
    rng = np.random.default_rng(1)
    Y = y0 + 1e-7 * rng.standard_normal((4, y0.size)) * np.abs(y0).clip(1e-6)
    t = np.array([0.0, 1e-4, 2e-4, 3e-4])
    D, R = forces_many(t, Y, setup.model.args())
    for i in range(4):
        d, r, dydt = forces(t[i], Y[i], setup.model.args())
        assert np.array_equal(D[i], d) and np.array_equal(R[i], r)
        direct = np.empty_like(dydt)
        rhs(t[i], np.ascontiguousarray(Y[i]), setup.model.args(), direct)
        assert np.array_equal(dydt, direct)


def test_the_dynamics_scenes_background_jobs_are_the_kernels_its_run_compiles():
    """The kernels a cage-less run has compiled in a second process on a cold cache are the ones its
    run calls: after a smoke run of the main job, every job's signature is among the compiled ones
    (a mismatch would compile them twice on a first run, silently)."""
    from lubedyn.scenes import dynamics as ds
    from lubedyn.config import load_case_file

    path, _, case = load_case_file(str(CASES_DIR / "cageless_6206_10krpm_short.toml"), smoke=True)
    assert case.analysis.lyapunov_exponents
    run = ds.run(case, None, source=str(path), smoke=True)
    assert run.summary["Lyapunov exponent 1, whole system (Benettin) [1/s]"] is not None
    jobs = ds.kernel_jobs(case, ds.build(case, str(path)).model)
    assert len(jobs) == 4
    for bound, example in jobs:
        assert bound.signature(*example) in bound.dispatcher.overloads, bound.impl.__name__


def test_the_tapered_scenes_background_job_is_the_kernel_its_run_compiles():
    """As for the cage-less scene: after a smoke run of the Fig. 5 tapered case, the integrator kernel
    the run compiled in a second process on a cold cache has the signature its run calls."""
    from lubedyn.scenes import tapered as ts
    from lubedyn.config import load_case_file

    path, _, case = load_case_file(str(CASES_DIR / "trb_fig5_2400rpm.toml"), smoke=True)
    run = ts.run(case, None, source=str(path), smoke=True)
    assert run.summary["Accepted steps [-]"] > 0
    jobs = ts.kernel_jobs(case)
    assert len(jobs) == 2
    for bound, example in jobs:
        assert bound.signature(*example) in bound.dispatcher.overloads, bound.impl.__name__


def test_tapered_forces_many_equals_contact_forces_row_by_row():
    """The tapered bearing's forces_many (contact_forces through a function pointer) gives the bits of
    contact_forces at each sampled state of a smoke run."""
    from lubedyn.scenes import tapered as ts
    from lubedyn.config import load_case_file
    from lubedyn.dynamics.tapered import kernels as K

    path, _, case = load_case_file(str(CASES_DIR / "trb_fig5_2400rpm.toml"), smoke=True)
    run = ts.run(case, None, source=str(path), smoke=True)
    model = ts.build(case)
    args = model.args(model.quasi_static())
    P = args.P[0]
    Y = run.y[::max(1, len(run.y) // 4)]
    loads, SL, FR, CG, FC = K.forces_many(Y, args)
    Z, ns = int(P.z), int(P.ns)
    for i in range(len(Y)):
        F, T, Fc, Tc, ld = np.empty((Z, 3)), np.empty((Z, 3)), np.empty(3), np.empty(3), np.empty((Z, 4))
        sl, fr, cg = np.empty((Z, 2, ns)), np.empty((Z, K.N_FRICTION)), np.empty(K.N_CAGE_DIAG)
        K.contact_forces(np.ascontiguousarray(Y[i]), args, F, T, Fc, Tc, ld, np.empty(3), np.empty(3), sl, fr, cg)
        assert np.array_equal(loads[i], ld) and np.array_equal(SL[i], sl) and np.array_equal(FR[i], fr)
        assert np.array_equal(CG[i], cg) and np.array_equal(FC[i], np.concatenate([Fc, Tc]))


def test_background_compilation_can_be_switched_off(monkeypatch):
    """LUBEDYN_BACKGROUND_COMPILE=0 (the pool workers of studies and map sweeps set it) starts nothing,
    and neither does a machine with one usable core."""
    bound = I.resumable_kernel("rk4", duffing_softer)
    Y, work = I.new_run(np.zeros(2), np.zeros(2))
    job = (bound, (np.zeros(2), (np.zeros(2), np.ones(1)), I.make_params(), Y, work, 1))
    monkeypatch.setattr(S, "_is_cached", lambda dispatcher, sig: False)  # as on a cold cache
    started = []
    monkeypatch.setattr(S.subprocess, "Popen", lambda *a, **k: started.append(a) or (_ for _ in ()).throw(OSError("x")))
    monkeypatch.setenv("LUBEDYN_BACKGROUND_COMPILE", "0")
    assert S.compile_in_background([job]) == 0 and not started
    monkeypatch.setenv("LUBEDYN_BACKGROUND_COMPILE", "1")
    monkeypatch.setattr(S, "_usable_cores", lambda: 1)
    assert S.compile_in_background([job]) == 0 and not started
    monkeypatch.setattr(S, "_usable_cores", lambda: 2)
    assert S.compile_in_background([job]) == 0 and len(started) == 1  # tried; its OSError is reported, not raised


def test_a_job_whose_signature_cannot_be_built_is_skipped_not_raised(monkeypatch):
    """The background compilation is an optimisation: a job it cannot type is left to the run itself."""
    bound = I.resumable_kernel("rk4", duffing_softer)
    monkeypatch.setattr(S, "_usable_cores", lambda: 2)
    monkeypatch.setenv("LUBEDYN_BACKGROUND_COMPILE", "1")
    assert S.compile_in_background([(bound, (object(),))]) == 0


def test_the_call_cache_tells_argument_types_apart():
    """Bound calls find their compiled entry by numba's type fingerprints of the arguments: the same types
    reuse one entry (one signature compiled), other types (a float32 coefficient array) get their own
    and their own numbers; the result is the same as the first call's for the same arguments."""
    y0, t = np.array([1.0, 0.0]), np.linspace(0.0, 1.0, 11)
    k = I.kernel_for("rk4", duffing_softer)
    a = k(y0, t, 0.01, ARGS)[0]
    n_sigs = len(k.kernel.dispatcher.signatures)
    assert np.array_equal(a, k(y0, t, 0.01, ARGS)[0]) and len(k.kernel.dispatcher.signatures) == n_sigs
    args32 = (ARGS[0].astype(np.float32), ARGS[1])
    b = k(y0, t, 0.01, args32)[0]
    assert len(k.kernel.dispatcher.signatures) == n_sigs + 1
    assert np.abs(b - a).max() < 1e-6 and not np.array_equal(a, b)  # float32 coefficients: rounded, same ODE


@njit(cache=True)
def duffing_switch(t, y, args, dydt):
    """:func:`duffing` with its forcing switched by ``args[2]`` (an int, or a compile-time constant)."""
    p, s, forced = args
    dydt[0] = y[1]
    dydt[1] = -p[0] * y[1] - p[1] * y[0] - p[2] * y[0] ** 3
    if forced == 1:
        dydt[1] += p[3] * np.cos(p[4] * t) * s[0]


def test_arguments_with_fixed_options_are_told_apart_and_typed_once(monkeypatch):
    """Arguments holding lubedyn.dynamics.interp.Fixed (map options fixed at compile time) cannot be
    fingerprinted by numba: the bound kernel keys them by identity, types them once per argument object
    (counted), compiles one entry per fixed value, and gives the bits of the same switch as a runtime int
    (three compiled RK4 kernels: Fixed(1), Fixed(0), int64)."""
    from lubedyn.dynamics.interp import Fixed

    y0, t = np.array([1.0, 0.0]), np.linspace(0.0, 1.0, 11)
    k = I.kernel_for("rk4", duffing_switch)
    on, off = (ARGS[0], ARGS[1], Fixed(1)), (ARGS[0], ARGS[1], Fixed(0))
    calls = []
    real_typeof = S.numba.typeof
    monkeypatch.setattr(S.numba, "typeof", lambda v, *a: calls.append(1) or real_typeof(v, *a))
    a = k(y0, t, 0.01, on)[0]
    typed = len(calls)
    assert np.array_equal(a, k(y0, t, 0.01, on)[0]) and len(calls) == typed  # same object: no typing
    b = k(y0, t, 0.01, off)[0]
    assert np.array_equal(a, k(y0, t, 0.01, (ARGS[0], ARGS[1], 1))[0])
    assert np.array_equal(b, k(y0, t, 0.01, (ARGS[0], ARGS[1], 0))[0])
    assert not np.array_equal(a, b)
    assert sum("Literal[int]" in str(sig) for sig in k.kernel.dispatcher.signatures) >= 2
