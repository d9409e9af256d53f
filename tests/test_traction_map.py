"""Race traction from the EHL maps inside the bearing kernel.

(1) The packed kernel arrays read back the same traction coefficient as the
maps' own Python interpolation (lubedyn.maps.FilmMap), race by race: this
pins the packing and the race order.  (2) A steady run with map traction
keeps the balls at the epicyclic ball-train speed (no-slip kinematics, an
independent formula) and reports the queries clamped outside the map."""
from __future__ import annotations

import json

import numpy as np
import pytest

from lubedyn import cli
from lubedyn.config import CASES_DIR
from lubedyn.maps import FilmMap
from lubedyn.dynamics import cageless
from lubedyn.dynamics.cageless import _traction_arrays, _traction_from_map

MAPS = [FilmMap.load(CASES_DIR / "maps" / f"ehl_ball_{race}_race.npz") for race in ("inner", "outer")]
OUT = "Traction coefficient [-]"


@pytest.mark.parametrize("race", [0, 1])
@pytest.mark.parametrize("kernel", ["compiled", "py_func"])
def test_packed_arrays_read_the_maps(race, kernel):
    tmap = _traction_arrays(tuple(m.kernel_arrays(OUT) for m in MAPS))
    f = _traction_from_map if kernel == "compiled" else _traction_from_map.py_func
    rng = np.random.default_rng(race)
    for _ in range(5):  # slide-to-roll ratios above the maps' first node (1e-3): no linear regularisation
        q, ue, srr = rng.uniform(80.0, 1000.0), rng.uniform(7.0, 25.0), 10.0 ** rng.uniform(-2.9, -1.1)
        counter = np.zeros(1, dtype=np.int64)
        got = f(tmap, race, q, ue, srr * ue, counter)  # sliding speed srr * ue
        assert got == pytest.approx(float(MAPS[race](OUT, q, ue, srr)), rel=1e-9, abs=1e-12)
        assert counter[0] == 0


@pytest.mark.skipif(getattr(cageless, "TRACTION_MAP_BELOW_AXIS", None) != "linear",
                    reason="the maps' slide-to-roll axis starts at 1e-3; a kernel that clamps below it makes the "
                           "traction a step at zero slip (the run crawls): needs the linear regularisation of "
                           "dynamics/cageless.py (TRACTION_MAP_BELOW_AXIS)")
def test_steady_run_with_map_traction(tmp_path, capsys):
    code = cli.main(["run", str(CASES_DIR / "cageless_6206_steady.toml"), "--smoke", "--set", "model.traction=map",
                     "--set", "analysis.lyapunov_exponents=0", "--set", "output.write=[]", "--out", str(tmp_path)])
    capsys.readouterr()
    assert code == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    assert abs(s["Ball-train slip at end [-]"]) < 0.005
    # the unloaded balls (Q < 50 N, the map's first load node) are clamped and counted
    assert s["Film map queries outside axes [-]"] > 0
    assert s["Traction map, inner race"].endswith("ehl_ball_inner_race.npz")
