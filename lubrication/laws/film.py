r"""Closed-form EHL film thickness formulas (regression fits of numerical solutions).

They are what an EHL solve is compared with, and what a bearing model uses
when a full solve is not wanted.  Every formula returns a *dimensionless*
film thickness H = h/R_x; multiply by R_x for metres.  Groups (Hamrock &
Dowson; u_m the mean entrainment speed, E' = 2 E*, 1/E* = (1 - nu1^2)/E1 +
(1 - nu2^2)/E2, alpha the pressure-viscosity coefficient, w the load [N] or
load per length [N/m])::

    U = eta0 u_m / (E' R_x)    G = alpha E'
    W = w / (E' R_x^2)  (points)      W = w / (E' R_x)  (lines)

Moes' groups: M = W (2U)^(-3/4) (points) or W (2U)^(-1/2) (lines),
L = G (2U)^(1/4), H_M = H (2U)^(-1/2).

Point contacts (entrainment along x = the minor axis of the Hertz ellipse,
ellipticity k = a/b >= 1; R_y >= R_x):

- Hamrock & Dowson (1977), *J. Lubr. Technol.* 99, 264-276, fitted for
  3 <= k <= 8 (used beyond that by everyone)::

      H_c   = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k))
      H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k))

- Nijenbanning, Venner & Moes (1994), *Wear* 176, 217-229, circular contact
  (k = 1), central film in Moes' groups, within about 5 % of their solutions.

Line contacts:

- Dowson & Toyoda (1979), Proc. 5th Leeds-Lyon Symposium, 60-65 (central)::

      H_c = 3.06 U^0.69 G^0.56 W^-0.10

- Pan & Hamrock (1989), *J. Tribol.* 111, 246-251, fitted for G in about
  [2500, 5000] (steel, mineral oils)::

      H_c   = 2.922 W^-0.166 U^0.692 G^0.470
      H_min = 1.714 W^-0.128 U^0.694 G^0.568

- Moes (1992), Proc. JSLE Int. Tribol. Conf., central film in Moes' groups,
  all regimes (rigid/elastic, iso-/piezoviscous), a few per cent.

>>> round(float(hamrock_dowson_central(1e-11, 5000, 1e-6, 1.0)) * 1e5, 3)
1.867
"""
from __future__ import annotations

import math

import numpy as np


def _exp(x):
    """exp of a float with ``math`` (the scalar path the bearing models use), of an array with numpy."""
    return math.exp(x) if isinstance(x, (int, float)) else np.exp(x)

# ---------------------------------------------------------------- point contacts


def hamrock_dowson_central(U, G, W, k):
    """Hamrock-Dowson (1977) central film H_c = h_c/R_x of a point contact with ellipticity ``k`` = a/b."""
    return 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1.0 - 0.61 * _exp(-0.73 * k))


def hamrock_dowson_minimum(U, G, W, k):
    """Hamrock-Dowson (1977) minimum film H_min = h_min/R_x of a point contact with ellipticity ``k`` = a/b."""
    return 3.63 * U**0.68 * G**0.49 * W**-0.073 * (1.0 - _exp(-0.68 * k))


def nijenbanning_central(M, L):
    """Nijenbanning, Venner & Moes (1994) central film of a circular contact in
    Moes' scaling, H_M = (h_c/R_x) (2U)^(-1/2)."""
    HRI = 145 * 1.796 ** (-15 / 7) * M**-2
    HEI = 3.18 * 1.63 ** (-14 / 25) * M ** (-2 / 15)
    HRP = 1.29 * 1.691 ** (-2 / 3) * L ** (2 / 3)
    HEP = 1.48 * 1.63 ** (-7 / 20) * M ** (-1 / 12) * L**0.75
    s = 1.5 * (1 + np.exp(-1.2 * HEI / HRI))
    H00 = 1.8
    return ((HRI**1.5 + (HEI**-4 + H00**-4) ** (-3 / 8)) ** (2 * s / 3) + (HRP**-8 + HEP**-8) ** (-s / 8)) ** (1 / s)


# ---------------------------------------------------------------- line contacts


def dowson_toyoda_central(U, G, W):
    """Dowson-Toyoda (1979) central film H_c = h_c/R_x of a line contact."""
    return 3.06 * U**0.69 * G**0.56 * W**-0.10


def pan_hamrock_central(U, G, W):
    """Pan-Hamrock (1989) central film H_c = h_c/R_x of a line contact."""
    return 2.922 * W**-0.166 * U**0.692 * G**0.470


def pan_hamrock_minimum(U, G, W):
    """Pan-Hamrock (1989) minimum film H_min = h_min/R_x of a line contact."""
    return 1.714 * W**-0.128 * U**0.694 * G**0.568


def moes_line_central(M, L):
    """Moes (1992) central film of a line contact in Moes' scaling,
    H_M = (h_c/R_x) (2U)^(-1/2)::

        H_M = ((H_RI^(7/3) + H_EI^(7/3))^(3s/7) + (H_RP^(-7/2) + H_EP^(-7/2))^(-2s/7))^(1/s)
        H_RI = 3/M, H_EI = 2.621 M^(-1/5), H_RP = 1.287 L^(2/3), H_EP = 1.311 M^(-1/8) L^(3/4),
        s = (7 + 8 exp(-2 H_EI/H_RI))/5
    """
    HRI, HEI = 3 / M, 2.621 * M**-0.2
    HRP, HEP = 1.287 * L ** (2 / 3), 1.311 * M ** (-1 / 8) * L**0.75
    s = 0.2 * (7 + 8 * np.exp(-2 * HEI / HRI))
    return ((HRI ** (7 / 3) + HEI ** (7 / 3)) ** (3 * s / 7) + (HRP**-3.5 + HEP**-3.5) ** (-2 * s / 7)) ** (1 / s)
