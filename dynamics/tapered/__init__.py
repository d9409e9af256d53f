"""Tapered roller bearing (paper A: Wu, Xu & Deng 2018).

==============  ==============================================================
module          responsibility
==============  ==============================================================
``quasistatic`` rigid-ring equilibrium of the cone and all rollers (sliced
                cup/cone line contacts, flange/roller-end Hertz contact,
                centrifugal and gyroscopic roller loads): ``solve``,
                ``QuasiStaticResult``
==============  ==============================================================

The geometry, kinematics and the slice law are laws written once
(:mod:`lubrication.laws.tapered`, :mod:`lubrication.laws.slices`).
"""
from .quasistatic import QuasiStaticResult, solve

__all__ = ["QuasiStaticResult", "solve"]
