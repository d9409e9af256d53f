"""The numba options of lubedyn's compiled kernels, in one place.

``JIT``: cached on disk, IEEE arithmetic (no ``fastmath``: no reassociation, so a kernel gives the
bits its Python twin gives), and numpy's error model (a division by zero gives inf/NaN, which the
integrators' non-finite-state check reports, instead of raising inside a compiled loop).
``INLINE``: the same, inlined at numba-IR level into the caller (small leaves of the bearing
right-hand side: no call overhead and no reference counting of array arguments).
"""
JIT = dict(cache=True, fastmath=False, error_model="numpy")
INLINE = dict(JIT, inline="always")
