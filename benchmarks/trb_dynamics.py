"""Cost of the tapered roller bearing's compiled dynamics: cold compile, warm wall time per
simulated millisecond for DOPRI5 (rtol 1e-7) and RK4 (at 0.8 x its measured largest stable step), and
that largest stable step by bisection, on the smoke case (2,400 rpm, Fa = 15 kN, 5 and 20 slices, eq. 12
traction, contact-only cage).  Writes ``results/trb_dynamics.json``.

Run in a fresh process for the cold numbers (the numba cache on disk is cleared first).  Speed is measured
here, never asserted in tests."""
from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

import importlib.util  # noqa: E402

_HERE = Path(__file__).resolve().parent
# benchmarks/dynamics.py would shadow the package: take this folder off the path, load _common by file
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != _HERE] + [str(_HERE.parent / "tests")]
_spec = importlib.util.spec_from_file_location("_common", _HERE / "_common.py")
_common = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_common)
RESULTS, ROOT, machine_info, timed, write_json = (_common.RESULTS, _common.ROOT, _common.machine_info, _common.timed,
                                                  _common.write_json)


def main() -> dict:
    for p in ROOT.glob("dynamics/**/*.nbi"):
        p.unlink()
    t0 = time.perf_counter()
    from lubedyn.dynamics.integrators import integrate
    from lubedyn.dynamics.tapered import kernels as K
    from test_trb_dynamics import RPM, _rk4_load_error, bearing
    t_import = time.perf_counter() - t0
    out = {"machine": machine_info(), "import [s]": t_import, "cases": []}
    for slices in (5, 20):
        tb = bearing(speed=2400 * RPM, traction="paper", pocket="contact", slices=slices)
        args, y0 = tb.args(), tb.start_state()
        T = 2e-3
        t = np.linspace(0.0, T, 5)
        c0 = time.perf_counter()
        integrate(K.rhs, y0, t[:2] * 1e-3, args, method="dopri5", rtol=1e-7, atol=1e-12)
        cold_d = time.perf_counter() - c0
        c0 = time.perf_counter()
        integrate(K.rhs, y0, t[:2] * 1e-3, args, method="rk4", dt=1e-6)
        cold_r = time.perf_counter() - c0
        ref = integrate(K.rhs, y0, t, args, method="dopri5", rtol=1e-9, atol=1e-14)
        lo, hi = 2e-6, 1e-4
        for _ in range(12):
            mid = math.sqrt(lo * hi)
            lo, hi = (mid, hi) if _rk4_load_error(tb, args, y0, t, ref, mid) < 0.05 else (lo, mid)
        wd, _, rd = timed(lambda: integrate(K.rhs, y0, t, args, method="dopri5", rtol=1e-7, atol=1e-12))
        dt = 0.8 * lo
        wr, _, _ = timed(lambda: integrate(K.rhs, y0, t, args, method="rk4", dt=dt))
        out["cases"].append({
            "Slices [-]": slices, "State size [-]": int(y0.size),
            "First call incl. compile, DOPRI5 [s]": cold_d, "First call incl. compile, RK4 [s]": cold_r,
            "Largest stable RK4 step [s]": lo, "2 sqrt(2)/omega_max [s]": 2 * math.sqrt(2) / tb.omega_max(),
            "DOPRI5 rtol 1e-7 wall per simulated ms [s]": wd / (T * 1e3),
            "DOPRI5 accepted steps per simulated ms [-]": rd.stats["Accepted steps [-]"] / (T * 1e3),
            "RK4 step [s]": dt, "RK4 wall per simulated ms [s]": wr / (T * 1e3),
            "RK4 load error vs DOPRI5 1e-9 [-]": _rk4_load_error(tb, args, y0, t, ref, dt),
        })
    write_json(RESULTS / "trb_dynamics.json", out)
    return out


if __name__ == "__main__":
    import json

    print(json.dumps(main()["cases"], indent=1))
