"""Lubricant laws (lubedyn.lubrication.laws.lubricant) against their published forms: Barus (1893), Roelands
(1966) with p0 = 1.96e8 Pa and its low-pressure slope alpha = z (ln eta0 + 9.67)/p0, Dowson &
Higginson's (1966) density with its 1 + a/b = 1.353 limit; each derivative against a difference."""
import math

import numpy as np
import pytest

from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws.lubricant import Barus, ConstantViscosity, DowsonHigginson, Roelands

ETA0, ALPHA = 0.050, 1.85e-8  # paper B's oil (Table 1)


def test_barus():
    law = Barus(ETA0, ALPHA)
    p = np.array([0.0, 1e8, 1e9])
    assert law(p) == pytest.approx(ETA0 * np.exp(ALPHA * p), rel=1e-15)
    assert law.pressure_viscosity == ALPHA


def test_roelands_from_alpha_has_the_barus_slope_at_ambient():
    """z = alpha p0/(ln eta0 + 9.67); d ln(eta)/dp at p = 0 equals alpha (central difference)."""
    law = Roelands(ETA0, alpha=ALPHA)
    assert law.z == pytest.approx(ALPHA * 1.96e8 / (math.log(ETA0) + 9.67), rel=1e-15)
    assert 0.5 < law.z < 0.7  # Roelands' z of mineral oils (about 0.6)
    dp = 1e3
    slope = (math.log(law(dp)) - math.log(law(0.0))) / dp
    assert slope == pytest.approx(ALPHA, rel=1e-4)
    assert law.pressure_viscosity == ALPHA
    given_z = Roelands(ETA0, z=law.z)
    assert given_z.pressure_viscosity == pytest.approx(ALPHA, rel=1e-14)
    # Roelands grows slower than Barus at GPa pressures (the reason it exists)
    assert law(1e9) < Barus(ETA0, ALPHA)(1e9)
    p = 4e8
    assert law.derivative(p) == pytest.approx((law(p + 1e2) - law(p - 1e2)) / 2e2, rel=1e-7)


def test_dowson_higginson_density():
    """rho/rho0 = 1 + 0.6e-9 p/(1 + 1.7e-9 p): 1.222 at 1 GPa, -> 1 + 0.6/1.7 = 1.353 as p -> inf."""
    law = DowsonHigginson(870.0)
    assert law(1e9) / 870.0 == pytest.approx(1 + 0.6 / 2.7, rel=1e-15)
    assert law(1e15) / 870.0 == pytest.approx(1.3529, abs=1e-4)
    assert law(-1e6) == 870.0  # gauge pressure below ambient is clipped
    p = 3e8
    assert law.derivative(p) == pytest.approx((law(p + 1e2) - law(p - 1e2)) / 2e2, rel=1e-7)


def test_bad_laws_are_one_line():
    for make, match in ((lambda: Barus(ETA0, -1e-9), "pressure-viscosity alpha"),
                        (lambda: Roelands(ETA0), "exactly one of 'z' or 'alpha'"),
                        (lambda: ConstantViscosity(0.0), r"viscosity eta0 \[Pa s\] = 0.0 must be > 0")):
        with pytest.raises(InputError, match=match) as info:
            make()
        assert "\n" not in str(info.value)
