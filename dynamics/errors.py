"""Exceptions of the dynamics layer, in lubedyn's one error tree (:mod:`lubedyn.lubrication.errors`).

``DynamicsInputError`` (an :class:`~lubedyn.lubrication.errors.InputError`) marks bad
input to a dynamics routine (wrong shape, a non-positive tolerance, a fixed
step beyond the stability limit): one line that
names the key, the value and what is allowed.  ``IntegrationError`` marks an
integration that failed (step budget exhausted, step-size underflow, a
non-finite state); it carries the status code, the time reached and the last
good output sample so that a caller can save what was computed.  Both derive
from :class:`~lubedyn.lubrication.errors.LubedynError` and builtin classes
(``ValueError`` / ``RuntimeError``): the laws both layers share raise
``InputError``, and one ``except InputError`` catches a user mistake from either.
"""
from __future__ import annotations

from lubedyn.lubrication.errors import InputError, LubedynError


class DynamicsError(LubedynError):
    """Base class of every error raised on purpose by :mod:`dynamics`."""


class DynamicsInputError(DynamicsError, InputError):
    """Bad input: names the key, the value and what is allowed.

    ``key``: the case key the error is about (``"operating.radial_load"``), when there is one."""

    def __init__(self, message, key: str | None = None):
        super().__init__(message)
        self.key = key


class IntegrationError(DynamicsError, RuntimeError):
    """A time integration that stopped before the last requested time.

    Attributes
    ----------
    status : int
        Kernel status code (1 step budget, 2 step-size underflow, 3 non-finite state).
    t_reached : float
        Time [s] of the last accepted step.
    t : ndarray
        Output times [s] that were filled before the failure.
    y : ndarray
        The filled output samples, shape ``(len(t), n)``; ``y[-1]`` is the last good sample.
    """

    def __init__(self, message, status=0, t_reached=float("nan"), t=None, y=None):
        super().__init__(message)
        self.status = int(status)
        self.t_reached = float(t_reached)
        self.t = t
        self.y = y
