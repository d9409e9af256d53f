"""Kernels specialised to a right-hand side, cached by numba across processes, with no code written
at run time unless asked (issue 13).

numba cannot cache across processes a kernel that receives the rhs *as an argument* (the argument
type carries the object identity), nor a closure or a wrapper over a global rhs.  What caches is a
kernel whose rhs is a *module global*: :func:`specialise` uses such a module, generated from the
kernel source (a plain function whose leading parameters are the callables) with the callables
turned into imported globals.  For the shipped bearing models these modules are generated ahead of
time (``python -m dynamics.codegen``) into :mod:`dynamics.kernels` and committed; for other
right-hand sides they are generated at run time only into a folder the caller names with
``LUBEDYN_KERNEL_CACHE``, and otherwise the generic kernel (``cache=False``, registered with
:func:`register_generic`) is compiled once per process.  Each generated module carries a digest of
every source its kernel may reach (numba's cache does not track callees) and is used only while the
digest matches.
"""
from __future__ import annotations

import ast
import hashlib
import importlib
import importlib.util
import inspect
import logging
import os
import sys
import textwrap
from pathlib import Path

import numba

logger = logging.getLogger(__name__)

_SPECIALISED = {}


#: kernels generated ahead of time for the bearing models lubedyn ships (``python -m dynamics.codegen``)
KERNEL_DIR = Path(__file__).resolve().parent / "kernels"
_DIGEST_LINE = "# source digest: "


def kernel_cache_dir() -> Path | None:
    """Directory where :func:`specialise` may generate kernel modules at run time: the environment
    variable ``LUBEDYN_KERNEL_CACHE`` (an explicit choice, e.g. the test suite's temporary folder), or
    None: nothing is written at run time, and a kernel not shipped in :data:`KERNEL_DIR` is compiled
    generically once per process."""
    env = os.environ.get("LUBEDYN_KERNEL_CACHE")
    return Path(env) if env else None


def _import_path(func):
    """``(module, name)`` under which the @njit ``func`` can be imported, or None."""
    py = getattr(func, "py_func", None)
    if py is None:
        return None
    mod, name = py.__module__, py.__qualname__
    if mod in (None, "__main__") or "." in name or "<" in name:
        return None
    module = sys.modules.get(mod)
    if module is None or getattr(module, name, None) is not func:
        return None
    return mod, name


def _source_digest(func, whole_package=True) -> bytes:
    """Hash of the source files the compiled ``func`` may depend on.

    numba's cache does not track callees, so for a callable (rhs, jvp ...) the
    digest covers every ``.py`` file of its top-level package (for a module
    outside a package: its file alone); for a kernel source
    (``whole_package=False``) its own module and this module (the helpers).
    """
    h = hashlib.sha256()
    py = getattr(func, "py_func", func)
    module = sys.modules[py.__module__]
    files = [Path(getattr(module, "__file__", "") or "")]
    if whole_package:
        top = sys.modules.get(module.__name__.split(".")[0])
        top_file = getattr(top, "__file__", None)
        if top is not None and top is not module and top_file:
            files = sorted(Path(top_file).parent.rglob("*.py"))
            if top.__name__ == "dynamics":  # its kernels call the laws written once in lubrication.laws
                lub = Path(top_file).parent.parent / "lubrication"
                files += sorted((lub / "laws").rglob("*.py")) + [lub / "errors.py"]
            files = [f for f in files if f.parent.name != "kernels"]  # the generated modules themselves
    else:
        files.append(Path(__file__))
    for f in files:
        try:
            h.update(f.read_bytes())
        except OSError:
            h.update(str(f).encode())
    return h.digest()


def _generate_source(impl, callables) -> str:
    """Kernel source with the callables turned from parameters into module globals."""
    tree = ast.parse(textwrap.dedent(inspect.getsource(impl)))
    fn = tree.body[0]
    # inspect reads the file as it is now, at the line numbers of the code object as it was imported: a
    # process that imported this module before an edit that shifted it would generate another function's
    # source under the new file's digest (seen: an rk4 body in a dopri5 kernel file).  Refuse instead.
    code = impl.__code__
    if (not isinstance(fn, ast.FunctionDef) or fn.name != impl.__name__
            or [a.arg for a in fn.args.args] != list(code.co_varnames[:code.co_argcount])):
        raise ImportError(f"source of {impl.__name__} changed since import; not generating a kernel from it")
    fn.args.args = [a for a in fn.args.args if a.arg not in callables]
    fn.name = "kernel"
    fn.decorator_list = []
    lines = [
        f"# {impl.__module__}.{impl.__name__} with {', '.join(callables)} bound as module globals",
        "from numba import njit",
        f"import {impl.__module__} as _impl_module",
        "globals().update({k: v for k, v in vars(_impl_module).items() if not k.startswith('__')})",
    ]
    for pname, func in callables.items():
        mod, name = _import_path(func)
        lines.append(f"from {mod} import {name} as {pname}")
    lines.append("")
    # nogil: the caller may run a kernel in a thread while Python writes outputs (the dynamics scene runs
    # the Benettin spectrum beside its figures and frames); the kernel touches no Python object
    lines.append("@njit(cache=True, nogil=True)")
    lines.append(ast.unparse(fn))
    return "\n".join(lines) + "\n"


def _kernel_stem(impl, paths) -> str:
    tag = "_".join(f"{m.replace('.', '_')}_{n}" for m, n in paths.values())
    return f"k_{impl.__name__.strip('_')}__{tag}"


def generated_module(impl, callables) -> tuple[str, str, str]:
    """``(stem, digest, text)`` of the kernel module of ``impl`` with ``callables`` bound as globals.

    ``digest`` hashes the generated source, the kernel's own module and this one, and every source
    file the callables may reach (their top-level package; for :mod:`dynamics` also
    :mod:`lubrication.laws`): numba's cache does not track callees, so a kernel whose digest no
    longer matches its sources must not be used."""
    paths = {k: _import_path(v) for k, v in callables.items()}
    if any(p is None for p in paths.values()):
        raise ImportError(f"{impl.__name__}: callables {paths} are not importable by module and name")
    source = _generate_source(impl, callables)
    h = hashlib.sha256(source.encode())
    h.update(_source_digest(impl, whole_package=False))
    for func in callables.values():
        h.update(_source_digest(func))
    digest = h.hexdigest()[:16]
    text = (f"# generated by `python -m dynamics.codegen` (dynamics.specialise.generated_module); do not edit\n"
            f"{_DIGEST_LINE}{digest}\n" + source)
    return _kernel_stem(impl, paths), digest, text


def _committed_kernel(stem, digest):
    """The shipped kernel ``stem`` of :data:`KERNEL_DIR` if its digest matches the sources, else None."""
    path = KERNEL_DIR / f"{stem}.py"
    if not path.is_file():
        return None
    with open(path, encoding="utf-8") as fh:
        head = [fh.readline(), fh.readline()]
    if head[1].strip() != f"{_DIGEST_LINE}{digest}":
        logger.warning("%s is out of date (a source it binds changed since `python -m dynamics.codegen`): "
                       "compiling the generic kernel instead (correct, once per process)", path)
        return None
    return importlib.import_module(f"dynamics.kernels.{stem}").kernel


def specialise(impl, **callables):
    """A compiled kernel of ``impl`` with the given callables bound as globals (numba-cached).

    ``impl`` is a plain kernel source function whose leading parameters are the callables (e.g.
    ``rhs``); the returned kernel takes the remaining parameters.  In order:

    1. the module shipped in :data:`KERNEL_DIR` for this pair (the bearing models of lubedyn;
       generated ahead of time by ``python -m dynamics.codegen``), if its digest matches the current
       sources (:func:`generated_module`);
    2. if ``LUBEDYN_KERNEL_CACHE`` names a folder (an explicit choice; nothing is written at run time
       otherwise): a module generated there, named by the digest and the numba version;
    3. the generic kernel bound to the callables (correct; compiled once per process, since numba
       cannot cache a kernel that takes functions as arguments).
    """
    key = (impl, tuple((k, id(v)) for k, v in callables.items()))
    if key in _SPECIALISED:
        return _SPECIALISED[key]
    kernel = None
    try:
        stem, digest, text = generated_module(impl, callables)
    except ImportError as exc:
        logger.info("%s: %s; compiling once per process", impl.__name__, exc)
        stem = None
    if stem is not None:
        kernel = _committed_kernel(stem, digest)
        directory = kernel_cache_dir()
        if kernel is None and directory is not None:
            try:
                kernel = _load_generated(directory, f"{stem}__{digest}{_numba_tag()}", stem, text)
            except (OSError, ImportError, SyntaxError) as exc:  # pragma: no cover - environment dependent
                logger.warning("kernel cache %s unavailable (%s); compiling %s once per process", directory, exc,
                               impl.__name__)
    if kernel is None:
        generic = _GENERIC[impl]
        bound = tuple(callables.values())

        def kernel(*a, _g=generic, _b=bound):
            return _g(*_b, *a)

        kernel.py_func = lambda *a, _p=impl, _b=bound: _p(*_b, *a)
    _SPECIALISED[key] = kernel
    return kernel


def _numba_tag() -> str:
    return "_nb" + numba.__version__.replace(".", "_").replace("+", "_").replace("-", "_")[:24]


def _load_generated(directory, name, stem, text):
    directory.mkdir(parents=True, exist_ok=True)
    path = directory / f"{name}.py"
    if not path.exists():
        for old in directory.glob(f"{stem}__*.py"):  # stale generations of the same kernel
            old.unlink(missing_ok=True)
            for cached in (directory / "__pycache__").glob(f"{old.stem}.*"):
                cached.unlink(missing_ok=True)
        tmp = path.with_suffix(f".tmp{os.getpid()}")
        tmp.write_text(text)
        os.replace(tmp, path)
    modname = f"_lubedyn_kernels.{name}"
    module = sys.modules.get(modname)
    if module is None:
        spec = importlib.util.spec_from_file_location(modname, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[modname] = module
        spec.loader.exec_module(module)
    return module.kernel


_GENERIC = {}  # kernel source -> generic jitted kernel (register_generic)


def register_generic(impl, jitted):
    """Register the generic (argument-taking) jitted version of a kernel source for :func:`specialise`."""
    _GENERIC[impl] = jitted
