"""Size limits: estimate memory and work before anything is allocated, refuse what cannot run.

Every scene's ``build`` (run, ``--dry-run`` and ``lubedyn validate``) estimates
what the case will need from its sizes alone (degrees of freedom, samples,
map points, grid nodes) and raises :class:`~lubedyn.lubrication.errors.InputError`
(exit 2) with one line naming the key, the estimate and the limit when it
cannot fit.  The estimates are simple and conservative within a factor of a
few; each is checked against a measured run in ``tests/test_limits.py``.

The memory limit is, in order of precedence:

1. ``[limits] memory = "40 GiB"`` in the case (or ``--set 'limits.memory=40 GiB'``);
2. the environment variable ``LUBEDYN_MEMORY_LIMIT`` (same syntax: ``"40 GiB"``,
   ``"500 MB"``, or a number of bytes);
3. ``SAFETY_FRACTION`` (80 %) of the memory available now (``MemAvailable`` of
   ``/proc/meminfo``, else ``os.sysconf``); no limit where neither is known.

>>> parse_bytes("40 GiB"), parse_bytes("1.5 kB"), parse_bytes(2048)
(42949672960, 1500, 2048)
>>> format_bytes(3.3e12)
'3 TiB'
"""
from __future__ import annotations

import math
import os
import re

from lubedyn.lubrication.errors import InputError

SAFETY_FRACTION = 0.8
ENV_MEMORY = "LUBEDYN_MEMORY_LIMIT"
UNITS = {"": 1, "b": 1, "kb": 10**3, "mb": 10**6, "gb": 10**9, "tb": 10**12, "kib": 2**10, "mib": 2**20,
         "gib": 2**30, "tib": 2**40}


def parse_bytes(value) -> int:
    """A memory size: a number of bytes, or a string ``"<number> <unit>"`` (B, kB, MB, GB, TB, KiB ... TiB)."""
    if isinstance(value, bool):
        raise ValueError("must be a size such as '40 GiB'")
    if isinstance(value, (int, float)):
        number, unit = float(value), ""
    else:
        match = re.fullmatch(r"\s*([0-9.eE+-]+)\s*([A-Za-z]*)\s*", str(value))
        if not match:
            raise ValueError("must be a size such as '40 GiB', '500 MB' or a number of bytes")
        try:
            number = float(match.group(1))
        except ValueError:
            raise ValueError("must be a size such as '40 GiB', '500 MB' or a number of bytes") from None
        unit = match.group(2).lower()
        if unit not in UNITS:
            raise ValueError(f"has unit {match.group(2)!r}; use B, kB, MB, GB, TB, KiB, MiB, GiB or TiB")
    if not (math.isfinite(number) and number > 0):
        raise ValueError("must be > 0")
    return int(round(number * UNITS[unit]))


def format_bytes(n: float) -> str:
    """``n`` bytes in the largest binary unit that keeps the number >= 1 (3 significant figures)."""
    for unit, size in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{n:.3g} B"


def available_memory() -> int | None:
    """Memory available to a new allocation now [bytes]: ``MemAvailable`` of /proc/meminfo, else
    ``os.sysconf`` (available physical pages), else None."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return int(os.sysconf("SC_AVPHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):
        return None


def memory_limit(case=None) -> tuple[float, str]:
    """(limit [bytes], where it comes from): ``[limits] memory``, ``LUBEDYN_MEMORY_LIMIT`` or
    ``SAFETY_FRACTION`` of the available memory (``inf`` when unknown)."""
    limits = getattr(case, "limits", None)
    if limits is not None and limits.memory is not None:
        return float(limits.memory), "limits.memory"
    env = os.environ.get(ENV_MEMORY, "").strip()
    if env:
        try:
            return float(parse_bytes(env)), ENV_MEMORY
        except ValueError as exc:
            raise InputError(f"{ENV_MEMORY} = {env!r} {exc}") from None
    avail = available_memory()
    if avail is None:
        return math.inf, "no limit: the available memory is unknown"
    return SAFETY_FRACTION * avail, f"{SAFETY_FRACTION:.0%} of the {format_bytes(avail)} available"


HOW_TO_RAISE = f"[limits] memory = '...' in the case or the environment variable {ENV_MEMORY}"


def check_memory(case, subject: str, estimate: float, advice: str) -> None:
    """Raise InputError when ``estimate`` [bytes] exceeds the memory limit.

    ``subject`` starts the message: ``"KEY = VALUE: what it makes"``; ``advice``: what to change."""
    limit, source = memory_limit(case)
    if estimate > limit:
        raise InputError(f"{subject} need about {format_bytes(estimate)} of memory, more than the limit of "
                         f"{format_bytes(limit)} ({source}); {advice}, or raise the limit with {HOW_TO_RAISE}")
