"""Validity warnings: a result that leaves the range where the scene's model holds is reported.

The film and EHL scenes call :func:`warnings_for` after the solve with the
result's largest pressure, smallest film and film Reynolds number; each
threshold comes from the case's ``[validity]`` table
(:class:`lubedyn.config.ValidityModel`, with its documented defaults).
Every warning is logged (WARNING) as one line and listed under
``"Warnings"`` in summary.json (the key is absent when there is none); the
run itself is not refused.

>>> from lubedyn.config import ValidityModel
>>> v = ValidityModel(max_pressure="3 GPa")
>>> found = warnings_for(v, max_pressure=9.4e12, min_film=1e-6, reynolds=10.0, model="the rigid film")
>>> [text.split(":")[0] for text in found]
['Maximum pressure 9.4e+12 Pa is above validity.max_pressure = 3e+09 Pa']
"""
from __future__ import annotations

import logging

log = logging.getLogger(__name__)


def warnings_for(validity, *, max_pressure: float, min_film: float, reynolds: float, model: str) -> list[str]:
    """One-line warnings for the thresholds of ``validity`` that a result crosses (none: [])."""
    out = []
    if validity.max_pressure is not None and max_pressure > validity.max_pressure:
        out.append(f"Maximum pressure {max_pressure:.3g} Pa is above validity.max_pressure = "
                   f"{validity.max_pressure:.3g} Pa: {model} does not hold there (the solids deform, the viscosity "
                   "law is extrapolated)")
    if min_film < validity.min_film:
        out.append(f"Minimum film thickness {min_film:.3g} m is below validity.min_film = {validity.min_film:.3g} m "
                   "(the surface roughness): asperities would touch, outside a full-film model")
    if reynolds > validity.max_reynolds:
        out.append(f"Film Reynolds number rho U h / eta = {reynolds:.3g} is above validity.max_reynolds = "
                   f"{validity.max_reynolds:.3g}: the flow is no longer laminar and inertia-free, which the "
                   "Reynolds equation assumes")
    return out


def report(summary: dict, warnings: list[str]) -> dict:
    """Log each warning and list them under ``"Warnings"`` in ``summary`` (only when there is one: a
    result inside every range keeps the summary's values scalar)."""
    for text in warnings:
        log.warning("%s", text)
    if warnings:
        summary["Warnings"] = list(warnings)
    return summary
