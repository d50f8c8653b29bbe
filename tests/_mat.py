"""Shared helpers of the 2D medial-axis tests (closed forms as polylines, topology counts)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

import medialcad

FloatArray = NDArray[np.float64]


def compute(face: Any, tol: float | None = None) -> medialcad.MedialAxis2D:
    return medialcad.medial_axis_2d(face, tol=tol)


def sample(result: medialcad.MedialAxis2D, per_branch: int = 50) -> tuple[FloatArray, FloatArray]:
    return result.sample(per_branch)


def compound(result: medialcad.MedialAxis2D) -> Any:
    return result.to_compound()


@dataclass
class ClosedForm:
    """A closed-form medial axis in the local frame: polyline pieces with radii."""

    pieces: list[tuple[FloatArray, FloatArray]]  # (points (n, 2), radius (n,))
    #: exact radius at a point of the axis (local (N, 2) -> (N,)); default: interpolation
    radius_fn: Callable[[FloatArray], FloatArray] | None = None

    def project(self, pts: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Distance of each local point ``(N, 2)`` to the axis and the radius there."""
        best = np.full(len(pts), np.inf)
        rad = np.zeros(len(pts))
        foot = np.zeros_like(pts)
        for p, r in self.pieces:
            if len(p) == 1:
                d = np.linalg.norm(pts - p[0], axis=1)
                better = d < best
                best[better], rad[better], foot[better] = d[better], r[0], p[0]
                continue
            a, b = p[:-1], p[1:]
            ab = b - a
            L2 = np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
            for k0 in range(0, len(pts), 256):
                x = pts[k0 : k0 + 256, None, :]
                t = np.clip(np.einsum("nij,ij->ni", x - a, ab) / L2, 0.0, 1.0)
                proj = a + t[..., None] * ab
                d = np.linalg.norm(x - proj, axis=2)
                j = np.argmin(d, axis=1)
                dj = d[np.arange(len(j)), j]
                rj = r[j] + t[np.arange(len(j)), j] * (r[j + 1] - r[j])
                sl = slice(k0, k0 + len(j))
                better = dj < best[sl]
                best[sl] = np.where(better, dj, best[sl])
                rad[sl] = np.where(better, rj, rad[sl])
                pj = proj[np.arange(len(j)), j]
                foot[sl] = np.where(better[:, None], pj, foot[sl])
        if self.radius_fn is not None:
            rad = self.radius_fn(foot)
        return best, rad

    def points(self, n_per_piece: int = 40) -> FloatArray:
        out = []
        for p, _ in self.pieces:
            idx = np.linspace(0, len(p) - 1, min(n_per_piece, len(p))).round().astype(int)
            out.append(p[idx])
        return np.vstack(out)


def segment(a: Any, b: Any, ra: float, rb: float, n: int = 2) -> tuple[FloatArray, FloatArray]:
    t = np.linspace(0.0, 1.0, n)
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a + t[:, None] * (b - a), ra + t * (rb - ra)


def cycle_rank(result: medialcad.MedialAxis2D) -> tuple[int, int]:
    """``(connected components, independent cycles)`` of the medial graph; a closed branch
    is one cycle on its own, an isolated node one component."""
    n = len(result.nodes)
    parent = list(range(n))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    open_branches = [b for b in result.branches if not b.closed]
    closed = [b for b in result.branches if b.closed]
    for br in open_branches:
        assert br.start is not None and br.end is not None
        parent[find(br.start)] = find(br.end)
    components = len({find(i) for i in range(n)}) + len(closed)
    cycles = len(open_branches) - n + len({find(i) for i in range(n)}) + len(closed)
    return components, cycles
