"""Kernels bound to their right-hand side through function pointers, cached by numba across processes,
and compiled in a second process while the first compiles the model.

A kernel source (an integrator, the Benettin spectrum, a map over samples) is a plain function whose
leading parameters are callables (``rhs``, ``jac``, ``jvp`` ...).  :func:`register_kernel` compiles it
with ``cache=True`` and registers, for each callable, how the kernel calls it: a numba signature built
from the types of the kernel's other arguments.  :func:`specialise` binds callables to it: the kernel is
compiled for numba ``FunctionType`` arguments (first-class function pointers), so

* its compiled code does not contain the callable, and numba caches it across processes like any
  ``cache=True`` function (a callable passed as a plain argument would be typed by its identity and
  never hit the cache);
* it is compiled once per argument types, for every right-hand side with those types, and never
  re-optimises the right-hand side's code: the cage-less bearing's DOPRI5 kernel linked its
  right-hand side and re-optimised it (6.7 s of a cold run, the Benettin kernel 12.6 s);
* it does not depend on the right-hand side's source, so there is nothing to regenerate or to check
  for staleness when a model changes, and no source is written anywhere;
* it can be compiled in another process before the right-hand side exists (:func:`compile_in_background`),
  which a cold run uses to compile the integrator and analysis kernels on the second core while the
  first compiles the bearing model.

The call through the pointer costs a few nanoseconds against microseconds of a bearing right-hand
side; the results are bit-identical to the kernel with the right-hand side linked in (IEEE arithmetic,
no fast-math: inlining cannot change a result), which ``tests/test_specialise.py`` checks.
"""
from __future__ import annotations

import logging
import os
import pickle
import subprocess
import sys
import time

import numba
from numba.core.types import FunctionType

from .errors import DynamicsInputError

logger = logging.getLogger(__name__)

_KERNELS = {}  # kernel source -> (cached dispatcher, {callable name: signature builder})
_BOUND = {}  # (kernel source, callables' ids) -> Bound
_PENDING = {}  # (kernel source, signature) -> background compiler process (subprocess.Popen)


def register_kernel(impl, **signatures):
    """Compile ``impl`` (``cache=True``, ``nogil=True``) for binding by :func:`specialise`; return the
    dispatcher.  ``signatures[name](types)`` is the numba signature with which ``impl`` calls its
    callable parameter ``name``, built from ``types`` (parameter name -> numba type of the argument
    the kernel receives); the callables are the leading parameters of ``impl``, in the order given."""
    names = impl.__code__.co_varnames[:len(signatures)]
    if tuple(signatures) != names:
        raise TypeError(f"{impl.__name__}: the callables {tuple(signatures)} must be its leading parameters {names}")
    # nogil: a caller may run a kernel in a thread while Python writes outputs (the dynamics scene
    # runs the Benettin spectrum beside its figures and frames); the kernel touches no Python object
    jitted = numba.njit(cache=True, nogil=True)(impl)
    _KERNELS[impl] = (jitted, signatures)
    return jitted


try:  # the C fingerprint numba's dispatchers key their own type cache on (equal fingerprints, equal types)
    from numba._dispatcher import compute_fingerprint as _fingerprint
except ImportError:  # pragma: no cover - numba internals moved: every call types its arguments
    def _fingerprint(value):
        raise NotImplementedError


class Bound:
    """A kernel source with its callables bound: call it with the kernel's other arguments.

    ``stats`` are the kernel dispatcher's (cache hits and misses); ``py_func`` runs the source in
    plain Python with the callables' ``py_func``; :meth:`signature` is the compiled signature for given
    arguments."""

    def __init__(self, impl, callables):
        if impl not in _KERNELS:
            raise KeyError(f"{impl.__name__} is not a registered kernel (lubedyn.dynamics.specialise.register_kernel)")
        self.impl = impl
        self.dispatcher, self._builders = _KERNELS[impl]
        self.callables = dict(callables)
        missing = set(self._builders) - set(self.callables)
        if missing or set(self.callables) - set(self._builders):
            raise TypeError(f"{impl.__name__} takes the callables {tuple(self._builders)}, got {tuple(self.callables)}")
        self._ordered = tuple(self.callables[k] for k in self._builders)
        code = impl.__code__
        self.params = code.co_varnames[len(self._builders):code.co_argcount]
        self._entries = {}  # argument types -> compiled entry point
        self._by_fingerprint = {}  # numba's type fingerprints of the arguments -> the same entry point
        self._pinned = {}  # fingerprint keys naming unfingerprintable arguments by identity -> those arguments

    @property
    def stats(self):
        return self.dispatcher.stats

    @property
    def py_func(self):
        impl, fs = self.impl, tuple(getattr(f, "py_func", f) for f in self._ordered)
        return lambda *a: impl(*fs, *a)

    def callable_signatures(self, types):
        """``{name: signature}`` of the callables for the kernel arguments' numba ``types``."""
        named = dict(zip(self.params, types))
        return {name: build(named) for name, build in self._builders.items()}

    def signature(self, *args):
        """The numba signature (argument types) the kernel is compiled with for ``args``."""
        types = tuple(numba.typeof(a) for a in args)
        return _kernel_signature(self.callable_signatures(types), types)

    def _compile(self, types):
        sigs = self.callable_signatures(types)
        for name, func in zip(self._builders, self._ordered):
            sig = sigs[name]
            if not hasattr(func, "compile"):
                raise DynamicsInputError(f"{name} = {func!r} must be an @njit function")
            func.compile(sig.args)
            got = func.overloads[tuple(sig.args)].signature.return_type
            if got != sig.return_type:
                raise DynamicsInputError(f"{name} = {func.py_func.__qualname__} returns {got}; the kernel "
                                f"{self.impl.__name__} needs {sig.return_type} ({name}{sig})")
        full = _kernel_signature(sigs, types)
        _wait_for_background(self.impl, full)
        return self.dispatcher.compile(full)

    def __call__(self, *args):
        # numba's own type fingerprints (0.3 us for a bearing's argument tuple) find the compiled entry; its
        # typeof, which builds the types, costs 80-100 us (milliseconds for a bearing's parameter records on a
        # busy machine), too much for a call per integration chunk.  An argument numba cannot fingerprint (a
        # model's arguments holding lubedyn.dynamics.interp.Fixed options) is keyed by its identity instead,
        # kept alive while its key is cached (the last few), so that an identity is never reused under a key
        key, held = [], []
        for a in args:
            try:
                key.append(_fingerprint(a))
            except Exception:  # noqa: BLE001 - a value numba cannot fingerprint: by identity
                key.append(("id", id(a)))
                held.append(a)
        key = tuple(key)
        entry = self._by_fingerprint.get(key)
        if entry is None:
            types = tuple(numba.typeof(a) for a in args)
            entry = self._entries.get(types)
            if entry is None:
                entry = self._entries[types] = self._compile(types)
            self._by_fingerprint[key] = entry
            if held:
                self._pinned[key] = held
                if len(self._pinned) > _PINNED:
                    oldest = next(iter(self._pinned))
                    del self._pinned[oldest]
                    del self._by_fingerprint[oldest]
        return entry(*self._ordered, *args)


_PINNED = 8  # argument tuples keyed by identity per bound kernel


def entry_point(dispatcher, *example):
    """The compiled entry of the numba ``dispatcher`` for the types of ``example`` (compiled or loaded from the
    cache if need be), to call in a Python loop with arguments of those types.

    Why: a dispatcher types every call's arguments; for arguments numba cannot fingerprint (a model's
    arguments with :class:`lubedyn.dynamics.interp.Fixed` map options) that is a full ``numba.typeof``,
    milliseconds for a bearing's parameter records, against a few microseconds for the call itself
    (measured: the cage-less ``rhs`` 10 ms a call through the dispatcher on a busy machine, 7 us through
    its entry point).  The entry point does no type dispatch: call it only with arguments of the
    example's types."""
    sig = tuple(numba.typeof(a) for a in example)
    dispatcher.compile(sig)
    return dispatcher.overloads[sig].entry_point


def kernel_label(name: str) -> str:
    """A kernel source's readable name: ``_dopri5_impl`` -> ``dopri5 kernel``; other names unchanged."""
    if name.startswith("_") and name.endswith("_impl"):
        return f"{name.strip('_').removesuffix('_impl')} kernel"
    return name


def _kernel_signature(callable_sigs, types):
    return tuple(FunctionType(s) for s in callable_sigs.values()) + tuple(types)


def specialise(impl, **callables) -> Bound:
    """The kernel source ``impl`` (registered with :func:`register_kernel`) with ``callables`` bound."""
    key = (impl, tuple((k, id(v)) for k, v in callables.items()))
    bound = _BOUND.get(key)
    if bound is None:
        bound = _BOUND[key] = Bound(impl, callables)
    return bound


# ------------------------------------------------------------------ compiling in a second process
def _is_cached(dispatcher, signature) -> bool:
    """Whether numba's on-disk cache of ``dispatcher`` holds ``signature`` for this machine (without
    loading it); True if that cannot be told (then nothing is started needlessly)."""
    if signature in dispatcher.overloads:
        return True
    try:
        cache = dispatcher._cache
        return cache._index_key(tuple(signature), dispatcher.targetctx.codegen()) in cache._cache_file._load_index()
    except Exception:  # noqa: BLE001 - numba internals: if in doubt, compile in this process as usual
        return True


def compile_in_background(jobs) -> int:
    """Compile ``jobs`` (``[(bound kernel, example arguments), ...]``) in one child process, for the
    numba cache, unless they are cached already; return how many were started.

    A cold run calls it before it compiles its model: the kernels do not depend on the model's code,
    so the second core compiles them meanwhile, and :class:`Bound` waits for the child before it would
    compile the same signature itself (then loading it from the cache).  If the child fails or the
    cache cannot be written, the kernel is compiled in this process as before: the result is the same.
    Nothing is started on a machine with one usable core, or with ``LUBEDYN_BACKGROUND_COMPILE=0`` (set
    in the worker processes of studies and map sweeps, which are parallel already)."""
    if os.environ.get("LUBEDYN_BACKGROUND_COMPILE", "1") == "0" or _usable_cores() < 2:
        return 0
    todo, keys = [], []
    for bound, example in jobs:
        try:
            sig = bound.signature(*example)
        except Exception as exc:  # noqa: BLE001 - an optimisation only: never fails the run
            logger.debug("no background compilation of %s: %s", bound.impl.__name__, exc)
            continue
        key = (bound.impl, sig)
        if key in _PENDING or key in keys or _is_cached(bound.dispatcher, sig):
            continue
        todo.append((bound.impl.__module__, bound.impl.__name__, sig))
        keys.append(key)
    if not todo:
        return 0
    try:
        payload = pickle.dumps(todo)
        proc = subprocess.Popen([sys.executable, "-m", "lubedyn.dynamics.specialise"], stdin=subprocess.PIPE,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        proc.stdin.write(payload)
        proc.stdin.close()
    except (OSError, pickle.PicklingError, ValueError) as exc:
        logger.info("background compilation not started (%s); compiling in this process", exc)
        return 0
    for key in keys:
        _PENDING[key] = proc
    logger.info("compiling kernels (first run only): %s in a second process",
                ", ".join(f"{kernel_label(name)} ({module})" for module, name, _ in todo))
    return len(todo)


def usable_cores() -> int:
    """Cores this process may run on (its CPU affinity; the machine's count where there is none)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


_usable_cores = usable_cores  # what compile_in_background asks (a test sets it to try a one-core machine)


def _wait_for_background(impl, signature):
    proc = _PENDING.pop((impl, signature), None)
    if proc is None:
        return
    if proc.poll() is None:
        logger.info("waiting for the second process to finish compiling the %s", kernel_label(impl.__name__))
    t0 = time.perf_counter()
    while proc.poll() is None:  # short waits: a Ctrl-C is taken at once
        time.sleep(0.02)
    logger.debug("waited %.2f s for the background compilation of %s (exit %s)", time.perf_counter() - t0,
                 impl.__name__, proc.returncode)


def _child_main() -> int:
    """``python -m lubedyn.dynamics.specialise``: compile the pickled ``[(module, kernel source, signature)]``."""
    import importlib

    from lubedyn.dynamics import specialise  # this file runs as __main__: the registry is the imported module's

    jobs = pickle.loads(sys.stdin.buffer.read())
    status = 0
    for module, name, sig in jobs:
        try:
            impl = getattr(importlib.import_module(module), name)
            specialise._KERNELS[impl][0].compile(sig)
        except Exception:  # noqa: BLE001 - the parent compiles what the child could not
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(_child_main())
