"""Power-law fits of map outputs and their relative errors.

Part of :mod:`lubedyn.maps` (the package docstring gives the overview)."""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from lubedyn.maps.registry import ZERO_FLOOR

# ---------------------------------------------------------------------------
# power-law fit


@dataclass(frozen=True)
class PowerLawFit:
    """Closed form fitted to an output: a power law along every axis of one sign,
    a log-quadratic along an axis through zero::

        log|F| = c + sum_{i in P} a_i log|x_i| + sum_{j in Q} (b_j x_j + d_j x_j^2)
                   [+ sum_{i<k in P} e_ik log|x_i| log|x_k|],       sign(F) fixed

    P: axes whose nodes all have one sign (``terms[i] == "power"``); Q: axes
    through zero (``"quadratic"``: squeeze number, slide-to-roll ratio), where a
    power law is undefined.  Fitted by least squares on the grid nodes where
    the output has its dominant sign and is significant (at least ``ZERO_FLOOR``
    x the largest |value| at the same first-axis node; ``domain``);
    ``max_error``/``median_error`` are the relative errors there.
    ``exponents[i]`` = a_i (NaN on Q axes), ``quadratic[j]`` = (b_j, d_j) ((0, 0)
    on P axes), ``cross`` the e_ik in the order of the pairs of P axes.
    """

    output: str
    constant: float
    exponents: tuple
    cross: tuple
    sign: float
    max_error: float
    median_error: float
    points: int
    domain: str
    terms: tuple = ()
    quadratic: tuple = ()

    def __call__(self, *coords):
        x = [np.asarray(c, dtype=float) for c in coords]
        terms = self.terms or ("power",) * len(x)
        z = self.constant
        logs = {}
        for i, (xi, kind) in enumerate(zip(x, terms)):
            if kind == "power":
                logs[i] = np.log(np.abs(xi))
                z = z + self.exponents[i] * logs[i]
            else:
                b, d = self.quadratic[i]
                z = z + b * xi + d * xi * xi
        if self.cross:
            pairs = [(i, k) for i in logs for k in logs if i < k]
            z = z + sum(e * logs[i] * logs[k] for e, (i, k) in zip(self.cross, pairs))
        return self.sign * np.exp(z)

    def formula(self) -> str:
        terms = self.terms or ("power",) * len(self.exponents)
        parts = []
        for i, kind in enumerate(terms):
            if kind == "power":
                parts.append(f"|x{i}|^{self.exponents[i]:.4g}")
            else:
                b, d = self.quadratic[i]
                parts.append(f"exp({b:.4g} x{i} + {d:.4g} x{i}^2)")
        s = f"{self.sign * math.exp(self.constant):.6g} " + " ".join(parts)
        return s + (" (with cross terms)" if self.cross else "")


def relative_error(approx, exact, floor):
    """|approx - exact| / max(|exact|, floor) (floor: scalar or per point)."""
    approx, exact = np.asarray(approx, float), np.asarray(exact, float)
    return np.abs(approx - exact) / np.maximum(np.abs(exact), floor)


def fit_power_law(axes, values, output: str = "", cross="auto") -> PowerLawFit | None:
    """Least-squares closed form of ``values`` on the grid of ``axes`` (see :class:`PowerLawFit`).

    ``cross``: False (no cross terms), True, or "auto" (cross terms between power-law axes kept when
    they at least halve the maximum error).  None when fewer points than terms + 2.
    """
    grids = np.meshgrid(*[a.nodes for a in axes], indexing="ij")
    x = np.stack([g.ravel() for g in grids], axis=1)
    v = np.asarray(values, float).ravel()
    sign = 1.0 if np.sum(v > 0) >= np.sum(v < 0) else -1.0
    terms = tuple("power" if (a.nodes > 0).all() or (a.nodes < 0).all() else "quadratic" for a in axes)
    ok = (v * sign > 0) & np.isfinite(v) & _significant(values)
    total = v.size
    nd = x.shape[1]
    xs = x[ok]
    lv = np.log(sign * v[ok])
    power = [i for i in range(nd) if terms[i] == "power"]
    pairs = [(i, k) for i in power for k in power if i < k]

    def solve(with_cross):
        cols = [np.ones(xs.shape[0])]
        for i in range(nd):
            if terms[i] == "power":
                cols.append(np.log(np.abs(xs[:, i])))
            else:
                cols += [xs[:, i], xs[:, i] ** 2]
        if with_cross:
            cols += [np.log(np.abs(xs[:, i])) * np.log(np.abs(xs[:, k])) for i, k in pairs]
        A = np.stack(cols, axis=1)
        if A.shape[0] < A.shape[1] + 2:
            return None
        coef = np.linalg.lstsq(A, lv, rcond=None)[0]
        err = np.abs(np.exp(A @ coef - lv) - 1.0)
        return coef, err

    plain = solve(False)
    if plain is None:
        return None
    best, with_cross = plain, False
    if cross and pairs:
        crossed = solve(True)
        if crossed is not None and (cross is True or crossed[1].max() <= 0.5 * plain[1].max()):
            best, with_cross = crossed, True
    coef, err = best
    exponents, quadratic, j = [], [], 1
    for i in range(nd):
        if terms[i] == "power":
            exponents.append(float(coef[j]))
            quadratic.append((0.0, 0.0))
            j += 1
        else:
            exponents.append(float("nan"))
            quadratic.append((float(coef[j]), float(coef[j + 1])))
            j += 2
    domain = "whole grid" if ok.all() else f"{int(ok.sum())} of {total} nodes (significant, sign {sign:+g})"
    return PowerLawFit(output, float(coef[0]), tuple(exponents),
                       tuple(float(c) for c in coef[j:]) if with_cross else (), sign,
                       float(err.max()), float(np.median(err)), int(ok.sum()), domain, terms, tuple(quadratic))


def local_floor(fmap, output: str, points: np.ndarray) -> np.ndarray:
    """Denominator floor of the relative error at each point (see the module docstring).

    0 for an output that is nonzero and of one sign on the whole grid (plain
    relative error).  Otherwise ``ZERO_FLOOR`` x the largest |value| on the
    nodes of the point's slab of the first axis (every node whose first index
    is that of the cell's two ends): the first axis carries the scale (gap,
    load, over decades), and an output that vanishes or changes sign along the
    others (the zero force of a separating, cavitated film; a traction
    coefficient through SRR = 0) is judged against its scale at that gap or
    load instead of against zero."""
    v = fmap.values[output]
    if np.all(v > 0) or np.all(v < 0):
        return np.zeros(points.shape[0])
    a = fmap.axes[0]
    cell = np.clip(np.searchsorted(a.nodes, points[:, 0], side="right") - 1, 0, a.n - 2)
    slab = np.abs(v).reshape(a.n, -1).max(axis=1)
    return ZERO_FLOOR * np.maximum(slab[cell], slab[cell + 1])


def _significant(values) -> np.ndarray:
    """Nodes whose |value| is at least ``ZERO_FLOOR`` x the largest |value| of their first-axis slab."""
    v = np.abs(np.asarray(values, float))
    slab = v.reshape(v.shape[0], -1).max(axis=1)
    return (v >= ZERO_FLOOR * slab.reshape((-1,) + (1,) * (v.ndim - 1))).ravel()
