"""Independent references for the geometry of impact sites: the contacts of a lattice listed cell
by cell and classified by their offset, and Monte Carlo draws of the pipes' own motions (every
coefficient of every pipe, in one or two dimensions) from which each site's gap amplitude is
formed directly, without the Rayleigh scales of the forcing layer."""

from __future__ import annotations

import math

import numpy as np


def lattice_contact_classes(m: int) -> dict[str, int]:
    """Contacts of an ``m x m`` grid with 8-neighbour contact, by kind: ``wall`` (one per side of
    a boundary cell facing a wall), ``orthogonal`` (offset (0, 1) or (1, 0)) and ``diagonal``
    (offset (1, 1) or (1, -1)), each unordered pair once."""
    out = {"wall": 0, "orthogonal": 0, "diagonal": 0}
    for i in range(m):
        for j in range(m):
            out["wall"] += (i == 0) + (i == m - 1) + (j == 0) + (j == m - 1)
            for di, dj in ((0, 1), (1, 0), (1, 1), (1, -1)):   # each pair from one end only
                if 0 <= i + di < m and 0 <= j + dj < m:
                    out["diagonal" if di and dj else "orthogonal"] += 1
    return out


def _component_scale(sigma: float, omega: float, Omega: float | None) -> list[tuple[float, float]]:
    """``(coefficient sd, amplitude factor)`` of the free and the forced oscillation of a pipe."""
    Om2 = 2.0 if Omega is None else Omega * Omega
    return [(sigma, 1.0), (sigma, 1.0 / abs(omega * omega - Om2))]


def row_closure_fractions(n: int, sigma: float, samples: int, *, gap: float = 1.0,
                          omega: float = 1.0, Omega: float | None = None,
                          seed: int = 0) -> dict[str, float]:
    """Fraction of wall and of pipe-pipe sites whose gap can close in free flight, in
    ``samples`` rows of ``n`` pipes: every pipe draws its free ``(A_j, B_j)`` and forced
    ``(alpha_j, beta_j)`` coefficients ``~ N(0, sigma**2)``; a site's gap moves by the
    difference of its two bodies' motions (a wall does not move), and closes when the sum over
    the frequency components of that motion's amplitudes reaches ``gap`` (eq. 22)."""
    rng = np.random.default_rng(seed)
    total = np.zeros((samples, n + 1))
    for sd, factor in _component_scale(sigma, omega, Omega):
        c = rng.normal(0.0, sd, size=(samples, n, 2)) * factor   # cos and sin coefficients
        pad = np.zeros((samples, 1, 2))
        full = np.concatenate([pad, c, pad], axis=1)               # walls: zero motion
        diff = full[:, 1:] - full[:, :-1]                          # gap motion of sites 0..n
        total += np.hypot(diff[..., 0], diff[..., 1])
    hit = total >= gap
    return {"wall": float(hit[:, [0, n]].mean()), "pipe-pipe": float(hit[:, 1:n].mean())}


def lattice_closure_fractions(m: int, sigma: float, samples: int, *, pitch: float,
                              diameter: float, wall_gap: float | None = None,
                              omega: float = 1.0, Omega: float | None = None,
                              seed: int = 0) -> dict[str, float]:
    """As :func:`row_closure_fractions` for an ``m x m`` lattice moving in the plane: every pipe
    draws 2-D coefficient *vectors* ``~ N(0, sigma**2 I)``; a contact's gap (``pitch -
    diameter`` orthogonally, ``sqrt(2) pitch - diameter`` diagonally, ``wall_gap`` at a wall)
    closes when the sum over the components of the amplitude of the motion projected on the
    line of centres (the wall's normal) reaches the gap (linearised contact)."""
    rng = np.random.default_rng(seed)
    wg = pitch - diameter if wall_gap is None else wall_gap
    coeff = [rng.normal(0.0, sd, size=(samples, m, m, 2, 2)) * factor   # (.., xy, cos/sin)
             for sd, factor in _component_scale(sigma, omega, Omega)]
    hits = {"wall": [], "orthogonal": [], "diagonal": []}

    def amplitude(vec: np.ndarray, e: tuple[float, float]) -> np.ndarray:
        proj = vec[..., 0, :] * e[0] + vec[..., 1, :] * e[1]         # (samples, cos/sin)
        return np.hypot(proj[..., 0], proj[..., 1])

    for i in range(m):
        for j in range(m):
            for side, e in (((i == 0), (-1.0, 0.0)), ((i == m - 1), (1.0, 0.0)),
                            ((j == 0), (0.0, -1.0)), ((j == m - 1), (0.0, 1.0))):
                if side:
                    amp = sum(amplitude(c[:, i, j], e) for c in coeff)
                    hits["wall"].append(amp >= wg)
            for di, dj in ((0, 1), (1, 0), (1, 1), (1, -1)):
                if 0 <= i + di < m and 0 <= j + dj < m:
                    norm = math.hypot(di, dj)
                    e = (di / norm, dj / norm)
                    amp = sum(amplitude(c[:, i + di, j + dj] - c[:, i, j], e) for c in coeff)
                    kind = "diagonal" if di and dj else "orthogonal"
                    hits[kind].append(amp >= norm * pitch - diameter)
    return {k: float(np.mean(v)) for k, v in hits.items() if v}


def binomial_tolerance(p: float, samples: int, z: float = 4.5) -> float:
    """``z`` standard errors of a class's closure fraction over ``samples`` independent rows or
    lattices: the fraction is the mean over the rows of the row's mean over its sites of that
    class, and the variance of such a mean (whatever the correlation between sites sharing a
    pipe) is at most ``p (1 - p)``, so ``p (1 - p)/samples`` bounds the variance."""
    return z * math.sqrt(max(p * (1 - p), 1e-12) / samples)
