"""ROSS's finite-difference journal-bearing solver, timed on a lubedyn bearing.

``ross.bearings.fluid_flow.FluidFlow`` (ross-rotordynamics; Mota et al.
2020) discretises the Reynolds equation of a cylindrical bearing with central
differences on an (nz x ntheta) grid (theta from the widest gap, both ends of
[0, 2 pi] kept and tied by a periodicity row), assembles the system as a
*dense* ntotal x ntotal array (ntotal = nz * ntheta) that it converts to CSC
for SuperLU, and clips negative pressures to zero afterwards: the
half-Sommerfeld (Guembel) condition.  Its coefficients come from the annular
(curved) Couette-Poiseuille profile, so at c/R = 1e-3 its continuum limit
differs from the thin-film equation by about 1e-3 relative.

Run in-process by ``benchmarks/reynolds.py``, or, with a Python that has ROSS
in another environment, as ``python _ross.py '<json spec>'`` printing JSON.
"""
from __future__ import annotations

import contextlib
import io
import json
import os
import sys
import time

import numpy as np


@contextlib.contextmanager
def _quiet_fds():
    """Silence file descriptors 1 and 2 (C libraries print there, not to sys.stdout)."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        os.dup2(devnull, 2)
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            yield
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in saved + [devnull]:
            os.close(fd)


def import_ross():
    """Import ROSS quietly (its CoolProp/REFPROP and pint dependencies print on import).

    Returns ``(FluidFlow, calculate_oil_film_force, version)``; raises ImportError.
    """
    with _quiet_fds():
        try:
            import ross
            from ross.bearings.fluid_flow import FluidFlow
            from ross.bearings.fluid_flow_coefficients import calculate_oil_film_force
        except Exception as exc:  # ROSS fails with ValueError under plotly>=7, not ImportError
            raise ImportError(f"{type(exc).__name__}: {str(exc).splitlines()[0]}") from exc
    return FluidFlow, calculate_oil_film_force, getattr(ross, "__version__", "unknown")


def dense_matrix_gib(nz: int, ntheta: int) -> float:
    """Memory of ROSS's dense system matrix [GiB]."""
    return 8.0 * (nz * ntheta) ** 2 / 2**30


def solve_grid(spec: dict, nz: int, ntheta: int, repeats: int = 3) -> dict:
    """One ROSS solve of the bearing in ``spec`` on an nz x ntheta grid.

    ``spec``: radius [m] (journal), clearance [m], length [m], viscosity
    [Pa s], omega [rad/s], eccentricity_ratio.  Returns the load magnitude
    [N], attitude angle [deg] and the wall time split by ROSS's own phases.
    """
    FluidFlow, film_force, _ = import_ross()
    R, c = spec["radius"], spec["clearance"]

    def run():
        t = [time.perf_counter()]
        ff = FluidFlow(
            nz, ntheta, spec["length"], spec["omega"], 0.0, 0.0, R, R + c,
            spec["viscosity"], 860.0, attitude_angle=0.0,
            eccentricity=spec["eccentricity_ratio"] * c,
            immediately_calculate_pressure_matrix_numerically=False,
        )
        t.append(time.perf_counter())
        c1, c2, c0w = ff.calculate_coefficients()
        t.append(time.perf_counter())
        M, f = ff.mounting_matrix(c1, c2, c0w)
        t.append(time.perf_counter())
        P = ff.resolves_matrix(M, f)
        del M
        ff.p_mat_numerical = np.clip(P.reshape((ff.ntheta, ff.nz)), a_min=0, a_max=None).T
        ff.numerical_pressure_matrix_available = True
        t.append(time.perf_counter())
        radial, tangential, _, _ = film_force(ff, force_type="numerical")
        t.append(time.perf_counter())
        return np.diff(t), radial, tangential, ff.bearing_type

    phases = []
    for i in range(max(1, repeats)):
        dt, radial, tangential, kind = run()
        phases.append(dt)
        if i == 0 and dt.sum() > 30.0:
            break
    phases = np.array(phases)
    totals = phases.sum(axis=1)
    k = int(np.argsort(totals)[len(totals) // 2])
    names = ("geometry", "coefficients", "dense assembly", "sparse conversion + SuperLU", "force integral")
    return {
        "nz": nz,
        "ntheta": ntheta,
        "nodes": nz * ntheta,
        "dense_matrix_GiB": dense_matrix_gib(nz, ntheta),
        "bearing_type": kind,
        "load [N]": float(np.hypot(radial, tangential)),
        "attitude [deg]": float(np.degrees(np.arctan2(abs(tangential), abs(radial)))),
        "radial force [N]": float(radial),
        "tangential force [N]": float(tangential),
        "time [s]": float(np.median(totals)),
        "times [s]": [float(x) for x in totals],
        "phases [s]": {n: float(v) for n, v in zip(names, phases[k])},
    }


def run_grids(spec: dict, grids, repeats: int = 3, memory_cap_gib: float = 2.5) -> dict:
    """Solve on each (nz, ntheta) grid that fits ``memory_cap_gib``; never raises."""
    try:
        _, _, version = import_ross()
    except ImportError as exc:
        return {"available": False, "reason": f"import ross failed: {exc}"}
    points, skipped = [], []
    for nz, ntheta in grids:
        need = dense_matrix_gib(nz, ntheta)
        if need > memory_cap_gib:
            skipped.append({"nz": nz, "ntheta": ntheta, "reason": f"dense matrix needs {need:.1f} GiB > cap {memory_cap_gib} GiB"})
            continue
        try:
            points.append(solve_grid(spec, nz, ntheta, repeats))
        except Exception as exc:  # record and go on: a benchmark never stops on the comparison code
            skipped.append({"nz": nz, "ntheta": ntheta, "reason": f"{type(exc).__name__}: {exc}"})
    return {"available": True, "version": version, "points": points, "skipped": skipped}


if __name__ == "__main__":
    args = json.loads(sys.argv[1])
    print(json.dumps(run_grids(args["spec"], args["grids"], args.get("repeats", 3), args.get("memory_cap_gib", 2.5))))
