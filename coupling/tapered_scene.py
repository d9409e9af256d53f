"""Tapered-roller dynamics scene (``scene = "tapered"``): paper A's bearing in time (issue 23, first step).

A case (usually ``parameters = "Wu2018"``: Table 1 and the parameter module's assumed values)::

    scene = "tapered"
    parameters = "Wu2018"
    [operating]
    speed = "2400 rpm"          # cone; cup fixed
    radial_load = "20 kN"       # along +y
    axial = "locked"            # "locked" (at axial_displacement) or "force" (free under axial_load)
    axial_displacement = "0 um"
    [model]
    slices = 20
    traction = "paper"          # eq. 12 of paper A; "none"
    cage = true                 # pockets and guide land (lubrication.laws.cage)
    damping_alpha = "0.16 s/m"  # eq. 11's alpha_e
    [integrator]
    duration = "20 ms"
    sample_interval = "20 us"

``run`` starts from the quasi-static equilibrium (:func:`dynamics.tapered.quasistatic.solve`) with the
cage and rollers at their ideal speeds, integrates :func:`dynamics.tapered.kernels.rhs` (DOPRI5) and
writes ``summary.json`` (per roller and for the cage: means and ranges of tilt, skew and slip over the
record's second half, paper A's definitions below; cage speed and slip; cone and cage centre excursions;
largest loads; the assumed values), ``timeseries.npz`` (every state, and per roller tilt, skew, orbital
speed, slip and the four loads) and ``roller_attitude.png``, ``slip.png``, ``cage_whirl.png``.

Definitions (paper A, sec. 4; notes 2.9): at each sample the roller axis e is split in the roller's own
radial frame (x axial, r radial through its centre, t tangential): tilt = atan2(e_r, e_x) - its initial
value (rotation in the meridional plane), skew = asin(e_t) (rotation out of it); slip (eq. 52) =
(omega_ideal - omega)/omega_ideal of the orbital speed of a roller's centre, and of the cage's spin,
with omega_ideal the geometry's own ideal cage speed omega_i (1 - gamma)/2.

Not yet (issue 23): flange friction, side-beam contacts, the tilting cone, RK4, the ParaView series,
the loaded-zone marker and the periodicity measure.
"""
from __future__ import annotations

import logging
import math
import sys
import time
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from pydantic import Field, model_validator

from lubrication.errors import ConvergenceError, InputError

from . import outputs
from .config import LimitsModel, PositiveInt, Q, _Model, resolved_toml, rule
from .static_scene import BearingTable

log = logging.getLogger(__name__)

FIELD_FILES = (("timeseries.npz", "timeseries"), ("roller_attitude.png", "png"), ("slip.png", "png"),
               ("cage_whirl.png", "png"))


class OperatingTable(_Model):
    speed: Q("angular velocity", ge=0) = 0.0
    radial_load: Q("force", ge=0) = 0.0
    axial: Literal["locked", "force"] = "locked"
    axial_load: Q("force", ge=0) = 0.0
    axial_displacement: Q("length") = 0.0

    @model_validator(mode="after")
    def _axial(self):
        if self.axial == "force" and self.axial_load == 0.0 and self.radial_load > 0.0:
            raise rule("axial_load", 0.0, "must be > 0 with axial = 'force' and a radial load: a single tapered "
                       "bearing under radial load alone has no equilibrium with a free axial DOF (paper_A_notes "
                       "2.7); or set axial = 'locked'")
        return self


class ModelTable(_Model):
    slices: PositiveInt = 20
    traction: Literal["none", "paper"] = "paper"
    cage: bool = True
    damping_alpha: Q("inverse velocity", ge=0) = 0.16
    cone_mass: Q("mass", gt=0) = 5.0  # assumed (not in paper A)
    pocket_switch: Literal["continuous", "paper"] = "continuous"


class LubricantTable(_Model):
    viscosity: Q("dynamic viscosity", gt=0)
    pressure_viscosity: Q("inverse pressure", ge=0)


class CageTable(_Model):
    mass: Q("mass", gt=0)
    pocket_critical_film: Q("length", gt=0)
    pocket_stiffness: Q("stiffness", gt=0)
    pocket_damping: Q("damping", ge=0)
    boundary_friction: Q("dimensionless", ge=0)
    land_critical_film: Q("length", gt=0)


class IntegratorTable(_Model):
    rtol: Q("dimensionless", gt=0, lt=1) = 1e-7
    atol: Q("dimensionless", gt=0) = 1e-12
    duration: Q("time", gt=0)
    sample_interval: Q("time", gt=0) = 20e-6
    max_steps: PositiveInt = 50_000_000

    @model_validator(mode="after")
    def _samples(self):
        n = self.duration / self.sample_interval
        if n < 2:
            raise rule("sample_interval", self.sample_interval, f"must be below integrator.duration = "
                       f"{self.duration:g} s (at least 2 samples)")
        if n > 2_000_000:
            raise rule("sample_interval", self.sample_interval, f"gives {n:.3g} samples; at most 2,000,000")
        return self


class OutputTable(_Model):
    write: list[Literal["timeseries", "png"]] = Field(default_factory=lambda: ["timeseries", "png"])


class TaperedCase(_Model):
    scene: Literal["tapered"]
    description: str = ""
    bearing: BearingTable
    operating: OperatingTable = Field(default_factory=OperatingTable)
    model: ModelTable = Field(default_factory=ModelTable)
    lubricant: LubricantTable
    cage: CageTable
    integrator: IntegratorTable
    output: OutputTable = Field(default_factory=OutputTable)
    limits: LimitsModel = Field(default_factory=LimitsModel)
    smoke: dict[str, Any] | None = None


CaseModel = TaperedCase


def build(case: TaperedCase):
    """The :class:`dynamics.tapered.model.TaperedBearing` of a case; a bad value is a one-line error
    naming the key."""
    from dynamics.errors import DynamicsInputError
    from dynamics.tapered import groups as G
    from dynamics.tapered.model import TaperedBearing

    from .static_scene import build as build_geometry

    g = build_geometry(case)
    op, m, c = case.operating, case.model, case.cage
    level = "film" if m.cage else "none"
    try:
        return TaperedBearing(
            geometry=g,
            operating=G.Operating(speed=op.speed, radial_load=op.radial_load, axial=op.axial,
                                  axial_load=op.axial_load, axial_displacement=op.axial_displacement),
            fidelity=G.Fidelity(slices=m.slices, traction=m.traction, pocket=level, guide_land=level,
                                damping_alpha=m.damping_alpha, cone_mass=m.cone_mass, pocket_switch=m.pocket_switch),
            lubricant=G.Lubricant(base_oil_viscosity=case.lubricant.viscosity,
                                  pressure_viscosity=case.lubricant.pressure_viscosity),
            cage=G.Cage(mass=c.mass, boundary_friction=c.boundary_friction,
                        pocket_critical_film=c.pocket_critical_film, pocket_stiffness=c.pocket_stiffness,
                        pocket_damping=c.pocket_damping, land_critical_film=c.land_critical_film))
    except DynamicsInputError as exc:
        raise InputError(str(exc)) from None


def describe(case: TaperedCase, model) -> str:
    op = case.operating
    return (f"tapered roller bearing, {model.n_rollers} rollers x {model.n_slices} slices, cage "
            f"{'on' if model.has_cage else 'off'}, traction {model.traction}; {op.speed * 30 / math.pi:g} rpm, "
            f"F_r {op.radial_load:g} N, axial {op.axial}; {case.integrator.duration * 1e3:g} ms")


def attitude(model, Y):
    """(tilt [rad], skew [rad], orbital speed [rad/s], radius [m]) per sample and roller (module docstring)."""
    from scipy.spatial.transform import Rotation

    from dynamics.rotations import to_scipy
    from dynamics.tapered import kernels as K

    n, Z = Y.shape[0], model.n_rollers
    tilt, skew, orbital = np.empty((n, Z)), np.empty((n, Z)), np.empty((n, Z))
    for j in range(Z):
        b = K.N_CONE + j * K.NB
        c, q, v = Y[:, b:b + 3], Y[:, b + 3:b + 7], Y[:, b + 7:b + 10]
        e = Rotation.from_quat(to_scipy(q)).apply([1.0, 0.0, 0.0])   # the roller axis R(q) e_x (normalises q)
        rr = np.hypot(c[:, 1], c[:, 2])
        er_ = (e[:, 1] * c[:, 1] + e[:, 2] * c[:, 2]) / rr
        et = (-e[:, 1] * c[:, 2] + e[:, 2] * c[:, 1]) / rr
        beta = np.arctan2(er_, e[:, 0])
        tilt[:, j] = beta - beta[0]
        skew[:, j] = np.arcsin(np.clip(et, -1.0, 1.0))
        orbital[:, j] = (c[:, 1] * v[:, 2] - c[:, 2] * v[:, 1]) / rr**2
    return tilt, skew, orbital


def summarise(case, model, t, Y, loads) -> dict:
    from dynamics.tapered import kernels as K

    g = model.geometry
    ideal = float(g.kinematics(model.speed)["cage speed [rad/s]"])
    tilt, skew, orbital = attitude(model, Y)
    half = t >= 0.5 * t[-1]
    s = {"Rollers [-]": model.n_rollers, "Slices per roller [-]": model.n_slices, "Traction": model.traction,
         "Cage": bool(model.has_cage), "Cone speed [rpm]": model.speed * 30 / math.pi,
         "Simulated time [s]": float(t[-1]), "Samples [-]": int(t.size),
         "Ideal cage speed [rad/s]": ideal, "Analysis window [s]": [float(t[half][0]), float(t[-1])]}
    for name, arr, unit in (("tilt", tilt, "rad"), ("skew", skew, "rad")):
        a = arr[half]
        s[f"Roller {name}, mean [{unit}]"] = float(np.mean(a))
        s[f"Roller {name}, mean [deg]"] = math.degrees(float(np.mean(a)))
        s[f"Roller {name}, largest magnitude [{unit}]"] = float(np.max(np.abs(a)))
    if ideal > 0.0:
        slip = (ideal - orbital[half]) / ideal
        s["Roller slip, mean [-]"] = float(np.mean(slip))
        s["Roller slip, largest magnitude [-]"] = float(np.max(np.abs(slip)))
    if model.has_cage:
        b = K.N_CONE + K.NB * model.n_rollers
        wc = Y[:, b + 10]
        s["Cage speed at end [rad/s]"] = float(wc[-1])
        if ideal > 0.0:
            s["Cage slip, mean [-]"] = float(np.mean((ideal - wc[half]) / ideal))
        whirl = np.hypot(Y[:, b + 1] - Y[:, 1], Y[:, b + 2] - Y[:, 2])
        s["Cage centre excursion from the cone, largest [m]"] = float(np.max(whirl))
        s["Largest pocket load [N]"] = float(np.max(loads[:, :, 3]))
    s["Cone centre excursion, largest [m]"] = float(np.max(np.hypot(Y[:, 1] - Y[0, 1], Y[:, 2] - Y[0, 2])))
    s["Largest cup load [N]"] = float(np.max(loads[:, :, 0]))
    s["Largest cone load [N]"] = float(np.max(loads[:, :, 1]))
    s["Largest flange load [N]"] = float(np.max(loads[:, :, 2]))
    return s


@dataclass
class TaperedRun:
    summary: dict = field(default_factory=dict)
    files: list = field(default_factory=list)
    t: Any = None
    y: Any = None


def headline(s: dict) -> list[str]:
    keys = ("Simulated time [s]", "Roller tilt, mean [rad]", "Roller skew, mean [rad]", "Roller slip, mean [-]",
            "Cage slip, mean [-]", "Largest cup load [N]", "Accepted steps [-]", "Integration wall time [s]")
    return [f"{k:<44} {s[k]:.6g}" if isinstance(s[k], float) else f"{k:<44} {s[k]}" for k in keys if k in s]


def run(case: TaperedCase, out_dir=None, *, name: str = "tapered", source: str = "", smoke: bool = False) -> TaperedRun:
    from dynamics.errors import IntegrationError
    from dynamics.integrators import integrate
    from dynamics.tapered import kernels as K

    t0 = time.perf_counter()
    model = build(case)
    args = model.args()
    y0 = model.start_state()
    t_build = time.perf_counter() - t0
    log.info("integrating %s", describe(case, model))
    ig = case.integrator
    t_out = np.arange(0.0, ig.duration * (1 + 1e-12), ig.sample_interval)
    try:
        res = integrate(K.rhs, y0, t_out, args, method="dopri5", rtol=ig.rtol, atol=ig.atol, max_steps=ig.max_steps,
                        progress=sys.stderr.isatty(), n_chunks=100)
    except IntegrationError as exc:
        raise ConvergenceError(f"{exc} (integrator.rtol = {ig.rtol:g})") from None
    t_int = time.perf_counter() - t0 - t_build
    loads = K.loads_many(res.y, args)
    scene = summarise(case, model, res.t, res.y, loads)
    scene.update(res.stats)
    scene["Integration wall time [s]"] = t_int
    summary = outputs.run_summary(case, name, smoke, scene, t0, t_build)
    result = TaperedRun(summary=summary, t=res.t, y=res.y)
    if out_dir is None:
        return result
    write = case.output.write
    tilt, skew, orbital = attitude(model, res.y)
    from pathlib import Path

    out = Path(out_dir)
    with outputs.staged(out) as stage:
        outputs.write_text(stage / "case.resolved.toml",
                           resolved_toml(case, outputs.resolved_header(name, source, smoke)))
        if "timeseries" in write:
            cols = {n: res.y[:, i] for i, n in enumerate(model.state_names())}
            for j in range(model.n_rollers):
                cols[f"Roller {j} tilt [rad]"] = tilt[:, j]
                cols[f"Roller {j} skew [rad]"] = skew[:, j]
                cols[f"Roller {j} orbital speed [rad/s]"] = orbital[:, j]
                for k, what in enumerate(("cup", "cone", "flange", "pocket")):
                    cols[f"Roller {j} {what} load [N]"] = loads[:, j, k]
            outputs.write_timeseries(stage / "timeseries.npz", res.t, cols, {"Case": name, "Scene": "tapered"})
        if "png" in write:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt

            for fname, fig in _figures(model, res.t, res.y, tilt, skew, orbital).items():
                try:
                    outputs.save_figure(stage / fname, fig)
                finally:
                    plt.close(fig)
        outputs.write_json(stage / "summary.json", summary)
        names = sorted(p.name for p in stage.iterdir())
    result.files = [out / n for n in names]
    return result


def _figures(model, t, Y, tilt, skew, orbital) -> dict:
    from matplotlib.figure import Figure

    from dynamics.tapered import kernels as K

    ms = t * 1e3
    ideal = float(model.geometry.kinematics(model.speed)["cage speed [rad/s]"])
    figs = {}
    fig = Figure(figsize=(10, 4))
    a, b = fig.subplots(1, 2)
    a.plot(ms, tilt[:, 0], label="roller 0")
    a.plot(ms, np.mean(tilt, axis=1), "k", lw=0.8, label="mean of all")
    a.set_xlabel("time [ms]")
    a.set_ylabel("tilt [rad]")
    a.legend()
    b.plot(ms, skew[:, 0], label="roller 0")
    b.plot(ms, np.mean(skew, axis=1), "k", lw=0.8, label="mean of all")
    b.set_xlabel("time [ms]")
    b.set_ylabel("skew [rad]")
    b.legend()
    fig.tight_layout()
    figs["roller_attitude.png"] = fig
    fig = Figure(figsize=(6.4, 4.2))
    ax = fig.subplots()
    if ideal > 0.0:
        ax.plot(ms, 100 * (ideal - orbital[:, 0]) / ideal, label="roller 0")
        if model.has_cage:
            bcg = K.N_CONE + K.NB * model.n_rollers
            ax.plot(ms, 100 * (ideal - Y[:, bcg + 10]) / ideal, label="cage")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("slip [%] (eq. 52, against the ideal cage speed)")
    ax.legend()
    fig.tight_layout()
    figs["slip.png"] = fig
    fig = Figure(figsize=(5, 5))
    ax = fig.subplots()
    if model.has_cage:
        bcg = K.N_CONE + K.NB * model.n_rollers
        ax.plot((Y[:, bcg + 1] - Y[:, 1]) * 1e6, (Y[:, bcg + 2] - Y[:, 2]) * 1e6, label="cage centre")
    ax.plot((Y[:, 1] - Y[0, 1]) * 1e6, (Y[:, 2] - Y[0, 2]) * 1e6, label="cone centre (from its start)")
    ax.set_xlabel("y [um]")
    ax.set_ylabel("z [um]")
    ax.set_aspect("equal", "datalim")
    ax.legend()
    fig.tight_layout()
    figs["cage_whirl.png"] = fig
    return figs
