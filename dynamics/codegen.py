"""Generate the specialised kernels of the shipped bearing models into :mod:`dynamics.kernels`.

::

    python -m dynamics.codegen            # write the modules that changed, remove stale ones
    python -m dynamics.codegen --check    # exit 1 if a committed module is out of date

Code generation is an explicit step (as pydy treats it), run by a developer after editing a kernel,
a bearing model or a law it calls, and committed with the edit; nothing is generated at run time
unless ``LUBEDYN_KERNEL_CACHE`` names a folder (:func:`dynamics.integrators.specialise`).
"""
from __future__ import annotations

import argparse
import logging
import sys

from . import integrators, specialise

log = logging.getLogger(__name__)


def shipped() -> list[tuple]:
    """``(impl, callables)`` of every kernel the shipped scenes specialise: DOPRI5 and RK4 on the
    cage-less bearing's right-hand side, and the Benettin spectrum on it and on its scaled form;
    DOPRI5 and RK4 on the tapered roller bearing's right-hand side."""
    from . import cageless, lyapunov
    from .tapered import kernels as tapered

    return [
        (integrators._dopri5_impl, {"rhs": cageless.rhs}),
        (integrators._rk4_impl, {"rhs": cageless.rhs}),
        (lyapunov._benettin_impl, {"rhs": cageless.rhs, "jvp": lyapunov.no_jvp}),
        (lyapunov._benettin_impl, {"rhs": cageless.rhs_scaled, "jvp": lyapunov.no_jvp}),
        (integrators._dopri5_impl, {"rhs": tapered.rhs}),
        (integrators._rk4_impl, {"rhs": tapered.rhs}),
    ]


def generate(check: bool = False) -> list[str]:
    """Write (or with ``check``, only compare) the shipped kernel modules; return the names that
    differed from what is on disk (stale modules included)."""
    directory = specialise.KERNEL_DIR
    wanted, changed = {}, []
    for impl, callables in shipped():
        stem, _, text = specialise.generated_module(impl, callables)
        wanted[stem] = text
    for stem, text in wanted.items():
        path = directory / f"{stem}.py"
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            changed.append(path.name)
            if not check:
                path.write_text(text, encoding="utf-8")
    for path in sorted(directory.glob("k_*.py")):
        if path.stem not in wanted:
            changed.append(path.name)
            if not check:
                path.unlink()
    return changed


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m dynamics.codegen", description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="only report modules that are out of date (exit 1)")
    args = ap.parse_args(argv)
    changed = generate(check=args.check)
    for name in changed:
        sys.stderr.write(f"{'out of date' if args.check else 'written'}: dynamics/kernels/{name}\n")
    return 1 if (args.check and changed) else 0


if __name__ == "__main__":
    sys.exit(main())
