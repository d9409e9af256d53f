"""Tapered roller bearing (paper A: Wu, Xu & Deng 2018).

===============  ==============================================================
module           responsibility
===============  ==============================================================
``quasistatic``  rigid-ring equilibrium of the cone and all rollers (sliced
                 cup/cone line contacts, flange/roller-end Hertz contact,
                 centrifugal and gyroscopic roller loads): ``solve``,
                 ``QuasiStaticResult``
``layout``       state layout, option codes, parameter and diagnostic indices
``groups``       frozen groups (operating, model, lubricant, cage, flange,
                 initial) that check their values and name the case key
``kernels``      the compiled right-hand side: cone translation with
                 prescribed spin, 6-DOF rollers and cage, sliced raceway
                 contacts in 3-D with traction, the flange with friction, the
                 pocket and guide land (contact only or film), eq. 11 damping;
                 ``rhs``, ``contact_forces``, ``loads_many``, ``forces_many``
``model``        ``TaperedBearing``: parameters of ``rhs``, the start state
                 from the quasi-static equilibrium at ideal speeds, and
                 ``diagnostics`` (slice loads, tilt, skew, slip, speeds)
===============  ==============================================================

The geometry, kinematics and the slice law are laws written once
(:mod:`lubedyn.lubrication.laws.tapered`, :mod:`lubedyn.lubrication.laws.slices`).
"""
from .quasistatic import QuasiStaticResult, solve

__all__ = ["QuasiStaticResult", "solve"]
