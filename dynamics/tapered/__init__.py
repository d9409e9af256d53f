"""Tapered roller bearing (paper A: Wu, Xu & Deng 2018).

==============  ==============================================================
module          responsibility
==============  ==============================================================
``quasistatic`` rigid-ring equilibrium of the cone and all rollers (sliced
                cup/cone line contacts, flange/roller-end Hertz contact,
                centrifugal and gyroscopic roller loads): ``solve``,
                ``QuasiStaticResult``
``kernels``     the compiled right-hand side (issue 23, first step): cone
                translation with prescribed spin, 6-DOF rollers, sliced
                raceway contacts in 3-D and the flange, eq. 11 damping;
                ``rhs``, ``contact_forces``, ``loads_many``
``model``       ``TaperedBearing``: parameters of ``rhs`` and the start state
                from the quasi-static equilibrium at ideal speeds
==============  ==============================================================

The geometry, kinematics and the slice law are laws written once
(:mod:`lubrication.laws.tapered`, :mod:`lubrication.laws.slices`).
"""
from .quasistatic import QuasiStaticResult, solve

__all__ = ["QuasiStaticResult", "solve"]
