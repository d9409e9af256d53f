"""Round-off perturbation of the film and EHL residuals: what another BLAS or CPU could do.

Every residual the Reynolds (``lubedyn.lubrication.reynolds.problem._Problem.assemble``) and EHL
(``lubedyn.lubrication.ehl.problem._Problem.assemble``) solvers assemble gets a seeded perturbation of ``ulps``
units of round-off (machine epsilon) of the size of its own terms, |J| |p| + |R| of the last
Jacobian assembly of that problem (the sum that round-off is relative to; |R| alone shrinks to
nothing at convergence).  Used by tests/test_roundoff.py, and by the audit mode of
tests/conftest.py: ``LUBEDYN_ROUNDOFF_ULPS=30 python -m pytest tests/test_ehl.py ...`` runs any
tests with every residual perturbed, to show that convergence decisions and tolerances hold
with margin on machines whose last bits differ from this one's.
"""
import numpy as np

EPS = np.finfo(float).eps


def perturb_residuals(setattr_, ulps: float, seed: int) -> None:
    """Install the perturbation with ``setattr_(obj, name, value)`` (``monkeypatch.setattr`` for
    one test, ``setattr`` for a whole session)."""
    from lubedyn.lubrication.reynolds import problem as reynolds
    from lubedyn.lubrication.ehl import problem as ehl

    rng = np.random.default_rng(seed)

    def noise(self, R, J, p):
        if J is not None:
            self._roundoff_terms = abs(J) @ np.abs(p) + np.abs(R)
        terms = getattr(self, "_roundoff_terms", None)
        if terms is None or terms.shape != R.shape:
            terms = np.abs(R)
        return R + ulps * EPS * terms * rng.standard_normal(R.shape)

    ehl_assemble = ehl._Problem.assemble

    def ehl_noisy(self, p, h00, jac=True):
        out = ehl_assemble(self, p, h00, jac=jac)
        return (noise(self, out[0], out[2] if jac else None, p),) + tuple(out[1:])

    film_assemble = reynolds._Problem.assemble

    def film_noisy(self, p, r, with_void):
        R, Jp, Jr = film_assemble(self, p, r, with_void)
        return noise(self, R, Jp, p), Jp, Jr

    setattr_(ehl._Problem, "assemble", ehl_noisy)
    setattr_(reynolds._Problem, "assemble", film_noisy)
