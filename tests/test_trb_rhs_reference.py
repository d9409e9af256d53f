"""The tapered right-hand side against the one recorded before its workspaces changed (issue 42, decision
4: no array allocated per roller, the traction's linearisation added beside it): bit for bit at fixed
states, where the arithmetic is the same.

``tests/data/trb_rhs_reference.npz`` was written by this file run as a script under the interpreter of a
checkout of main at 0e37a9b (``python tests/test_trb_rhs_reference.py --write``): per configuration the
packed parameter record, two states (the quasi-static start and a perturbed one) and dy/dt at each.
The test packs the same record (the quasi-static start sets the rib film through scipy, whose last bits a
BLAS may change) and compares dy/dt exactly (IEEE arithmetic without fastmath; another machine's libm
could differ in the last bit: the tolerance is then 1e-13 relative, asserted beside)."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

DATA = Path(__file__).resolve().parent / "data" / "trb_rhs_reference.npz"
CONFIGS = {"default": [], "tilt": ["operating.cone_tilt=free", "operating.load_offset=10 mm"],
           "paper": ["model.traction=paper", "model.pocket=contact", "model.guide_land=contact"]}


def _model(over):
    from lubedyn.config import CASES_DIR, load_case
    from lubedyn.scenes import tapered as S

    return S.build(load_case(CASES_DIR / "trb_fig5_2400rpm.toml",
                             overrides=["model.slices=5", "integrator.duration=1 ms", "output.write=[]", *over]))


def _write():
    from lubedyn.dynamics.tapered import kernels as K

    out = {}
    for name, over in CONFIGS.items():
        model = _model(over)
        qs = model.quasi_static()
        args, y0 = model.args(qs), model.start_state(qs)
        y1 = y0 + 1e-6 * np.random.default_rng(1).standard_normal(y0.size) * np.maximum(np.abs(y0), 1e-3)
        out[f"{name} P"] = np.array(args.P[0].tolist())
        for k, y in (("start", y0), ("perturbed", y1)):
            d = np.empty_like(y)
            K.rhs(0.0, y, args, d)
            out[f"{name} {k} y"], out[f"{name} {k} dydt"] = y, d
    np.savez_compressed(DATA, **out)


@pytest.mark.parametrize("name", list(CONFIGS))
def test_the_rhs_is_the_one_before_the_workspaces(name):
    """dy/dt at the recorded states equals the record bit for bit (default law; cone tilt free; eq. 12 with
    the contact-only cage), and rhs_w's dy/dt equals rhs's."""
    from lubedyn.dynamics.tapered import kernels as K
    from lubedyn.dynamics.tapered import layout as L

    with np.load(DATA) as npz:
        ref = dict(npz)
    model = _model(CONFIGS[name])
    args = model.args()
    for field, value in zip(args.P.dtype.names, ref[f"{name} P"]):
        args.P[field][0] = value
    for k in ("start", "perturbed"):
        y = ref[f"{name} {k} y"]
        d = np.empty_like(y)
        K.rhs(0.0, y, args, d)
        np.testing.assert_allclose(d, ref[f"{name} {k} dydt"], rtol=1e-13, atol=0.0)
        assert np.array_equal(d, ref[f"{name} {k} dydt"])
        dw = np.empty_like(y)
        Z = model.n_rollers
        K.rhs_w(0.0, y, args, dw, np.zeros((Z, L.W_BLOCK, L.W_BLOCK)), np.zeros((Z, L.W_BLOCK), dtype=np.int64))
        assert np.array_equal(dw, d)


if __name__ == "__main__" and "--write" in sys.argv:
    _write()
