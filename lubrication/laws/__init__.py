"""The laws written once: the ground floor that both :mod:`lubrication` and :mod:`dynamics` import.

=============  ========================================================
module         laws
=============  ========================================================
``contact``    reduced modulus, relative radii, Hertz point contact (exact
               elliptic integrals, Hamrock-Brewe fits), line contact, contact
               stiffness Q = K delta^1.5, springs in series, Hunt-Crossley alpha
``bearing``    rolling-bearing geometry and kinematics: race radii, pitch
               ratio, cage and entrainment speeds, free and thrust contact
               angles, Stribeck's most loaded element, Jones' load distribution
``lubricant``  viscosity (constant, Barus, Roelands) and density
               (incompressible, Dowson-Higginson) with d/dp, Eyring flow factor
``thermal``    viscosity against temperature: the Walther line of
               ASTM D341 through two points
``film``       closed-form EHL film thickness (Hamrock-Dowson, Nijenbanning,
               Dowson-Toyoda, Pan-Hamrock, Moes)
``grease``     Herschel-Bulkley grease (Barus phi, Papanastasiou option),
               Table 2 of paper A in temperature, viscosity readings
               (base_oil / apparent / paper), grease line film
``traction``   traction curve mu(SRR); paper A's raceway traction eqs.
               12-13 ("paper") and a limited Herschel-Bulkley law over the
               Hertz strip or ellipse (Bair-Winer limit, extension)
``flange``     roller-end sphere on a conical rib: relative radii, exact
               Hertz, rib film (Hamrock-Dowson or eq. 24 rebuilt), mixed
               friction eqs. 22-23
``slices``     roller slice law: Palmgren's line law, k_w = K_L/n_s, eq. 11's
               damped slice force and slice interference (numba leaves)
``cage``       paper A's cage (eqs. 30-46): pocket gap and film (Martin,
               squeeze; the paper's Herschel-Bulkley law), boundary state
               with the paper's or a continuous switch, side-beam squeeze,
               guide land (short bearing, eq. 44, FEM-map reader; Couette
               torque; boundary state; the guiding ring's reaction)
``units``      quantities with units, "50 um" -> 5e-05 m: the one parser of
               the case files (``lubedyn.units``) and of these dataclasses'
               and the films' Python constructors (``si_fields``)
``tapered``    tapered roller bearing geometry (common-apex or literal
               reading of paper A's Table 1), flange, crown, cage land,
               ideal kinematics, end sliding, roller mass
=============  ========================================================

Everything here is a pure function of floats (or a frozen SI dataclass) with
its published source in the docstring; nothing imports a solver.  Each law is
tested against its source (``tests/test_laws_*.py``), and
``benchmarks/code_size.py`` checks that no law constant has a second copy
outside this package.
"""
