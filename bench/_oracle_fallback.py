"""A self-contained MAT accuracy oracle, used when ``tests/oracles.py`` is unavailable.

Independent of every method benchmarked (no ``medialcad``, no ``BRepMAT2d``, no Voronoi):
it only needs the distance to a densely sampled boundary (a KD-tree).

* Reference MA: for every boundary sample ``f`` with inward normal ``n`` (plus fans of
  directions at vertices), the centre ``f + R n`` of the largest disc tangent at ``f``
  that stays inside the face (bisection on ``R``: the discs are nested, so
  "``B(f + t n, t)`` is inscribed" holds exactly on ``[0, R]``). Every MA point is such
  a centre, so this cloud samples the whole MA and only the MA.
* Soundness of a point ``p``: points outside the face score their distance to the
  boundary; inside, ``r = d(p)`` with footpoint ``f``, and the error is the smaller of
  (a) ``t*``, how far ``p`` can move away from ``f`` with the disc still inscribed
  (the distance, along the normal line through ``f``, to the MA point of ``f``) and
  (b) the distance to the reference cloud. Both are upper bounds of the distance to
  the true MA; they are 0 (up to the sampling error) on it.
* Accuracy floor: the distance to the boundary is the distance to the nearest sample,
  which overestimates by about ``h**2 / (8 r)`` for spacing ``h``; with the default
  samples the floor is ~1e-5 of the bbox diagonal (worst near convex corners).
* Completeness: the largest distance from a reference point to the method's output
  (its polylines when given, else its points).
"""

from __future__ import annotations

import numpy as np
import shapely
from _geom import bbox_diag, boundary_samples, face_frame, face_polygon
from scipy.spatial import cKDTree

__all__ = ["FallbackOracle"]


def _nested_disc_limit(tree, origins, dirs, r0, hi, eps, iters=36):
    """Largest ``t`` in ``[0, hi]`` with ``d(origin + t dir) >= r0 + t - eps``."""
    lo = np.zeros(len(origins))
    hi = np.full(len(origins), float(hi))
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        d, _ = tree.query(origins + mid[:, None] * dirs)
        ok = d >= r0 + mid - eps
        lo = np.where(ok, mid, lo)
        hi = np.where(ok, hi, mid)
    return lo


class FallbackOracle:
    name = "bench fallback (nested-disc KD-tree oracle)"

    def __init__(self, face, n_samples: int = 4000) -> None:
        self.face = face
        self.frame = face_frame(face)
        self.diag = bbox_diag(face)
        self.poly = face_polygon(face, self.frame, self.diag * 1e-6)
        step = self.poly.length / n_samples
        pts, nrm, origin, wire, _ = boundary_samples(face, self.frame, step)
        self.samples = pts
        self.tree = cKDTree(pts)
        self.eps = 1e-9 * self.diag
        # fix the inward side per wire by a majority vote of tiny inside probes
        probe = pts[origin] + nrm * (1e-4 * self.diag)
        inside = shapely.contains_xy(self.poly, probe[:, 0], probe[:, 1])
        for w in np.unique(wire):
            sel = wire == w
            if inside[sel].mean() < 0.5:
                nrm[sel] = -nrm[sel]
        f = pts[origin]
        r = _nested_disc_limit(self.tree, f, nrm, 0.0, self.diag, self.eps)
        ref = f + r[:, None] * nrm
        keep = shapely.contains_xy(self.poly, ref[:, 0], ref[:, 1]) | (r < 1e-6 * self.diag)
        self.reference = ref[keep]
        self.ref_tree = cKDTree(self.reference)

    def soundness(self, points3d: np.ndarray) -> np.ndarray:
        """Per-point upper bound of the distance to the true MA (absolute units)."""
        p3 = np.asarray(points3d, dtype=float).reshape(-1, 3)
        if len(p3) == 0:
            return np.zeros(0)
        p = self.frame.to_2d(p3)
        off_plane = np.abs(self.frame.height(p3))
        r, idx = self.tree.query(p)
        inside = shapely.contains_xy(self.poly, p[:, 0], p[:, 1])
        f = self.samples[idx]
        n = (p - f) / np.maximum(r, 1e-300)[:, None]
        t = _nested_disc_limit(self.tree, p, n, r, self.diag, self.eps)
        dref, _ = self.ref_tree.query(p)
        err = np.where(inside, np.minimum(t, dref), np.maximum(r, dref))
        return np.hypot(err, off_plane)

    def completeness(self, points3d: np.ndarray, polylines=None) -> np.ndarray:
        """Per reference point: distance to the output (absolute units)."""
        pts = [np.asarray(points3d, dtype=float).reshape(-1, 3)]
        spacing = 1e-4 * self.diag
        for pl in polylines or ():
            pl = np.asarray(pl, dtype=float)
            if len(pl) < 2:
                continue
            a, b = pl[:-1], pl[1:]
            k = np.minimum(np.linalg.norm(b - a, axis=1) / spacing, 10000).astype(int) + 1
            seg = np.repeat(np.arange(len(a)), k + 1)
            frac = np.concatenate([np.linspace(0, 1, m + 1) for m in k])
            pts.append(a[seg] + frac[:, None] * (b[seg] - a[seg]))
        allp = np.concatenate(pts)
        allp = allp[np.all(np.isfinite(allp), axis=1)]
        if len(allp) == 0:
            return np.full(len(self.reference), np.inf)
        d, _ = cKDTree(self.frame.to_2d(allp)).query(self.reference)
        return d
