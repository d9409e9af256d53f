"""Exceptions of the film layer.

``InputError`` marks a user mistake (bad geometry, bad option): the CLI turns it
into a one-line message and exit code 2.  ``ConvergenceError`` marks a solve
that failed: exit code 1.  Both derive from builtin classes so that callers who
do not know lubedyn can still catch them.
"""
from __future__ import annotations

import difflib


class LubedynError(Exception):
    """Base class of every error raised on purpose by lubedyn."""


class InputError(LubedynError, ValueError):
    """Bad input: names the key, the value and what is allowed."""


class ConvergenceError(LubedynError, RuntimeError):
    """A nonlinear or complementarity solve that did not converge."""


def unknown_choice(key: str, value: object, allowed) -> InputError:
    """An :class:`InputError` for ``value`` not in ``allowed``, with close matches."""
    allowed = list(allowed)
    close = difflib.get_close_matches(str(value), [str(a) for a in allowed], n=3)
    hint = f"; did you mean {' or '.join(repr(c) for c in close)}?" if close else ""
    return InputError(
        f"{key} = {value!r} is not allowed; choose one of {', '.join(map(repr, allowed))}{hint}"
    )


def require_positive(key: str, value: float) -> float:
    """Return ``float(value)`` or raise an :class:`InputError` if it is not > 0."""
    value = float(value)
    if not value > 0.0:
        raise InputError(f"{key} = {value!r} must be > 0")
    return value
