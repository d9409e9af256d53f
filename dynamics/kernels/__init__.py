"""Integrator and Lyapunov kernels specialised to the bearing models lubedyn ships, generated ahead of
time by ``python -m dynamics.codegen`` (never at run time) and committed.  Each module binds one
right-hand side as a global so that numba caches the compiled kernel across processes; its second
line holds the digest of the sources it was generated from, and
:func:`dynamics.integrators.specialise` uses it only while the digest matches
(``tests/test_codegen.py`` fails when a committed module is out of date)."""
