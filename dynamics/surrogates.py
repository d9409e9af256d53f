"""Surrogate series for tests of nonlinearity: phase-randomised and iterative amplitude-adjusted Fourier
transform (IAAFT) surrogates.

A surrogate keeps what a linear Gaussian process would share with the series and destroys the rest:

- :func:`phase_randomised` (Theiler, Eubank, Longtin, Galdrikian & Farmer, "Testing for nonlinearity in
  time series: the method of surrogate data", Physica D 58 (1992) 77): the amplitudes |X_k| of the
  discrete Fourier transform are kept, the phases replaced by independent uniform ones on [0, 2 pi)
  (the zero-frequency term and, for an even length, the Nyquist term keep their phase so that the
  surrogate is real with the same mean).  The power spectrum, hence the (circular) autocorrelation, is
  that of the series to round-off; the amplitude distribution becomes Gaussian.
- :func:`iaaft` (Schreiber & Schmitz, "Improved surrogate data for nonlinearity tests", Phys. Rev.
  Lett. 77 (1996) 635): starting from a random shuffle, alternately impose the series' Fourier
  amplitudes (keeping the current phases) and its amplitude distribution (rank-ordering the sorted
  series onto the current values), until the ranks stop changing or ``max_iter``; the result has
  exactly the series' values (a permutation of them) and nearly its power spectrum.

Each function draws from ``numpy.random.default_rng(seed)``: the same series and seed give the same
surrogates, bit for bit.  A null hypothesis of "linear Gaussian noise, possibly observed through a
monotone static function" is rejected when a statistic of the series lies outside the distribution of
the same statistic over the surrogates (:func:`lubedyn.dynamics.lyapunov.assess_largest_lyapunov` uses
the largest Lyapunov exponent).

Measured (tests/test_lyapunov_guards.py): phase-randomised surrogates of an AR(1) series (phi 0.95,
4,096 samples) keep its Fourier amplitudes to 2e-16 of the largest and its mean to 1e-16; IAAFT
surrogates keep its values exactly (a permutation) and its amplitude spectrum to 0.09 % (relative L2
distance); 5 of them take 0.3 s, one of 24,000 samples 0.5 s.
"""
from __future__ import annotations

import logging

import numpy as np

from .errors import DynamicsInputError

logger = logging.getLogger(__name__)

#: default iteration cap of :func:`iaaft` ...
IAAFT_MAX_ITER = 200
#: ... and its spectral tolerance: the surrogate's Fourier amplitudes within 1 % (relative L2) of the series'
IAAFT_TOLERANCE = 0.01


#: the largest prime factor a surrogate's length may have: numpy's FFT takes Bluestein's algorithm for a
#: length with a large prime factor (76,001 samples, a prime: 19-24 ms per real FFT against 1.4 ms for
#: 76,000 = 2^5 5^3 19 and 2.4-2.7 ms for lengths near it whose factors are at most 31, measured)
FAST_PRIME = 31


def _largest_prime_factor(m: int) -> int:
    big, p = 1, 2
    while p * p <= m:
        while m % p == 0:
            m //= p
            big = p
        p += 1
    return max(big, m) if m > 1 else big


def fast_length(n: int) -> int:
    """The largest length <= ``n`` without a prime factor above ``FAST_PRIME`` (31): the surrogates of a
    record are made of its first ``fast_length(N)`` samples, which keeps every FFT of the IAAFT
    iteration off Bluestein's slow path (10-15 x).  It drops at most 0.6 % of the samples from 2,000
    samples up (2,339 -> 2,325; at most 207 samples, 0.1 %, from 60,000 to 200,000), 2.3 % at worst
    below (215 -> 210); lengths whose factors are small are kept (76,001 -> 76,000, 24,000 -> 24,000).
    Not ``scipy.fft.prev_fast_len``: its lengths are 5-smooth for real transforms, which drops up to 6 %
    of a record (measured over 2,000-100,000 samples), where numpy's FFT is fast up to factors of 31."""
    n = int(n)
    if n < 1:
        raise DynamicsInputError(f"n = {n}: must be >= 1")
    m = n
    while _largest_prime_factor(m) > FAST_PRIME:
        m -= 1
    return m


def _series(x):
    x = np.asarray(x, dtype=np.float64)
    if x.ndim != 1 or x.size < 4 or not np.all(np.isfinite(x)):
        raise DynamicsInputError(f"x (shape {x.shape}) must be a 1-D array of at least 4 finite numbers")
    return x


def _count(n):
    n = int(n)
    if n < 1:
        raise DynamicsInputError(f"n = {n} surrogates: must be >= 1")
    return n


def phase_randomised(x, n=1, seed=0) -> np.ndarray:
    """``n`` phase-randomised surrogates of ``x`` (Theiler et al. 1992), shape (n, N): the Fourier
    amplitudes of ``x`` with independent uniform phases; the mean and the power spectrum are those of
    ``x`` to round-off."""
    x = _series(x)
    n = _count(n)
    rng = np.random.default_rng(seed)
    X = np.fft.rfft(x)
    amp = np.abs(X)
    out = np.empty((n, x.size))
    for i in range(n):
        phase = rng.uniform(0.0, 2.0 * np.pi, X.size)
        phase[0] = 0.0
        Y = amp * np.exp(1j * phase)
        Y[0] = X[0]
        if x.size % 2 == 0:
            Y[-1] = X[-1]
        out[i] = np.fft.irfft(Y, x.size)
    return out


def iaaft(x, n=1, seed=0, *, max_iter=IAAFT_MAX_ITER, tol=IAAFT_TOLERANCE) -> np.ndarray:
    """``n`` iterative amplitude-adjusted Fourier-transform surrogates of ``x`` (Schreiber & Schmitz
    1996), shape (n, N): each a permutation of ``x``'s values whose power spectrum approaches that of
    ``x``; the iteration stops when the amplitude spectrum of the current surrogate is within ``tol``
    (relative L2 distance) of the series', when an amplitude adjustment leaves the ranks unchanged
    (Schreiber & Schmitz's rule), or after ``max_iter`` rounds.  A pure sine converges slowly (24,000
    samples: 0.079 after 10 rounds, 0.0093 after 100), a broad spectrum fast (Lorenz x: 0.0016 after 10)."""
    x = _series(x)
    n = _count(n)
    if int(max_iter) < 1 or not tol >= 0.0:
        raise DynamicsInputError(f"max_iter = {max_iter!r} must be >= 1 and tol = {tol!r} >= 0")
    rng = np.random.default_rng(seed)
    amp = np.abs(np.fft.rfft(x))
    tol2 = float(tol) ** 2 * float(np.sum(amp * amp))
    sorted_x = np.sort(x)
    out = np.empty((n, x.size))
    for i in range(n):
        s = rng.permutation(x)
        order = np.argsort(s)
        for _ in range(int(max_iter)):
            S = np.fft.rfft(s)
            d = np.abs(S) - amp
            if np.sum(d * d) <= tol2:  # np.sum, not a BLAS norm (a BLAS dot took 13 ms here under load)
                break
            y = np.fft.irfft(amp * (S / np.maximum(np.abs(S), 1e-300)), x.size)
            new_order = np.argsort(y)
            s[new_order] = sorted_x  # rank-order the series' values onto y
            if np.array_equal(new_order, order):
                break
            order = new_order
        out[i] = s
    return out


#: the surrogate kinds by name (``assess_largest_lyapunov``'s ``surrogate`` argument)
KINDS = {"iaaft": iaaft, "phase": phase_randomised}


def surrogates(x, n, seed=0, kind="iaaft") -> np.ndarray:
    """``n`` surrogates of ``x`` of ``kind`` "iaaft" (:func:`iaaft`) or "phase" (:func:`phase_randomised`)."""
    if kind not in KINDS:
        raise DynamicsInputError(f"kind = {kind!r}: must be one of {sorted(KINDS)}")
    return KINDS[kind](x, n, seed)
