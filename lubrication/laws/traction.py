r"""Traction law of a rolling contact (closed form), written once for films and dynamics.

``mu = mu_lim tanh(|v_s| / max(s0 |u_e|, v_reg))``: a traction curve over the slide-to-roll ratio
SRR = |v_s|/u_e (initial slope mu_lim/s0, limiting value mu_lim, the shape of Newtonian-then-
limiting-shear EHL traction curves, e.g. Johnson & Tevaarwerk 1977, Proc. R. Soc. A 356, 215),
regularised at vanishing entrainment by the sliding speed v_reg (then a smoothed Coulomb law).
"""
from __future__ import annotations

import math

from numba import njit

from .jit import INLINE


@njit(**INLINE)  # small leaf of the bearing rhs (see dynamics.cageless)
def traction_coefficient(slip_speed, entrainment_speed, mu_lim, srr_ref, v_reg):
    """``mu_lim tanh(|v_s| / max(srr_ref |u_e|, v_reg))`` (>= 0)."""
    scale = srr_ref * abs(entrainment_speed)
    if scale < v_reg:
        scale = v_reg
    return mu_lim * math.tanh(abs(slip_speed) / scale)
