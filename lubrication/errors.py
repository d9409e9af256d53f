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


def close_matches(value: object, allowed, n: int = 3) -> list[str]:
    """The entries of ``allowed`` (as strings) closest to ``value``: a case-insensitive equal first,
    else up to ``n`` matches of :func:`difflib.get_close_matches`."""
    allowed = [str(a) for a in allowed]
    same = [a for a in allowed if a.lower() == str(value).lower()]
    return same or difflib.get_close_matches(str(value), allowed, n=n)


def did_you_mean(value: object, allowed, n: int = 3) -> str:
    """``"; did you mean 'a' or 'b'?"`` for the entries of ``allowed`` close to ``value``, else ``""``.

    The one "did you mean" of lubedyn: every unknown key, choice, unit or case name uses it.
    """
    close = close_matches(value, allowed, n)
    return f"; did you mean {' or '.join(repr(c) for c in close)}?" if close else ""


def unknown_choice(key: str, value: object, allowed) -> InputError:
    """An :class:`InputError` for ``value`` not in ``allowed``, with close matches."""
    allowed = list(allowed)
    hint = did_you_mean(value, allowed)
    return InputError(
        f"{key} = {value!r} is not allowed; choose one of {', '.join(map(repr, allowed))}{hint}"
    )


def require_positive(key: str, value: float) -> float:
    """Return ``float(value)`` or raise an :class:`InputError` if it is not > 0."""
    value = float(value)
    if not value > 0.0:
        raise InputError(f"{key} = {value!r} must be > 0")
    return value
