"""lubedyn.dynamics: compiled (numba) rigid-body dynamics of rolling bearings.

======================  ==============================================================
module                  responsibility
======================  ==============================================================
``integrators``         RK4, Dormand-Prince 5(4) with dense output, the whole time
                        loop in numba; ``integrate`` driver with progress and checks
``rotations``           unit quaternions, Euler's equations (numba)
``contacts``            kernels: Hertz force with Hunt-Crossley damping, traction
                        curve, ball-ball film + Hertz series law, Thornton collision
                        phases, film-rupture friction (set-up laws: lubedyn.lubrication.laws)
``cageless``            cage-less 6206 ball bearing of paper B: ``CagelessBearing``,
                        ``rhs``, ``forces``, ``forces_many``
``tapered``             tapered roller bearing of paper A: quasi-static rigid-ring
                        equilibrium of the cone and sliced rollers (``solve``)
``interp``              map interpolation kernels (multilinear, monotone cubic, log
                        axes; clamp-and-count or NaN outside the axes)
``lyapunov``            Lyapunov spectrum (Benettin), largest exponent of a time
                        series (Wolf et al. in bits/s, Rosenstein) and its guards
                        (surrogates, false neighbours, settings grid, windows)
``tangent_directions``  per-direction exponents from Benettin's first tangent
                        vector projected on the balls' directions; run-length rule
``surrogates``          phase-randomised and IAAFT surrogate series (seeded)
``spectra``             amplitude spectra, bearing characteristic frequencies
``analysis``            collision events and slip from sampled contact forces
``errors``              ``DynamicsInputError``, ``IntegrationError``
======================  ==============================================================

``dynamics`` imports from ``lubrication`` only the laws written once for both
layers (:mod:`lubedyn.lubrication.laws`) and the error tree (:mod:`lubedyn.lubrication.errors`),
never a film solver, and never the coupling layer (``lubedyn`` itself): it sees films only as plain
arrays (map axes and values) and closed forms.
"""
