"""The traced graph checked against the boundary, independently of how it was traced.

Every point of a medial axis is the centre of a disk inside the face whose radius is its
distance to the boundary. Each branch's spline is evaluated between its samples (where
an interpolating spline swings when a sample is wrong) and its disk is measured against
the boundary: a disk reaching out of the face by several tolerances (or a centre outside
it), or falling short of the boundary by as much, means the graph was traced wrong, and
the engine raises instead of answering.

The distance found is the least over the nearest boundary samples, each refined by
Newton on its curve: never less than the true distance, so a disk found to reach out of
the face by ``error`` reaches out by at least that much. A disk found short of the
boundary is short by at most that much: the true nearest point may have been missed
(the three nearest samples, at most a two-thousandth of the diagonal apart on edges up
to ten diagonals long, are each refined by Newton, and the nearest sample's own
distance bounds the answer).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.spatial import cKDTree

from medialcad.mat2d.boundary import Boundary
from medialcad.mat2d.curves import LineCurve
from medialcad.mat2d.graph import Branch

__all__ = ["disk_error"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

_NEAREST = 3  # boundary samples refined per point


def _samples(boundary: Boundary) -> tuple[FloatArray, NDArray[np.int64], FloatArray]:
    """Points along every edge element (at most ``diag / 2000`` apart, at least 16 an
    edge), each with its element and curve parameter; a reflex vertex is its point."""
    h = boundary.diag / 2000.0
    pts, els, pars = [], [], []
    for e in boundary.elements:
        if e.piece is None:
            assert e.vertex is not None
            pts.append(np.asarray(e.vertex, dtype=float)[None, :])
            els.append(np.array([e.index]))
            pars.append(np.array([np.nan]))
            continue
        n = int(min(max(16, math.ceil(e.length / h)), 20000))
        t = np.linspace(e.piece.t0, e.piece.t1, n)
        pts.append(e.piece.curve.point(t))
        els.append(np.full(n, e.index))
        pars.append(t)
    return np.vstack(pts), np.concatenate(els), np.concatenate(pars)


def _nearest(boundary: Boundary, q: FloatArray) -> tuple[FloatArray, BoolArray]:
    """Each point's distance to the boundary (see the module docstring) and whether it
    lies inside the face: on the inner side of its nearest point's normal (the points
    nearest a reflex vertex all lie inside; outside a convex corner both its edges'
    normals point away)."""
    pts, els, pars = _samples(boundary)
    k = min(_NEAREST, len(pts))
    d, j = cKDTree(pts).query(q, k=k)
    d, j = d.reshape(len(q), k), j.reshape(len(q), k)
    best = np.full(len(q), np.inf)
    inside = np.ones(len(q), dtype=bool)
    vertex = np.nonzero(np.isnan(pars[j[:, 0]]))[0]  # the nearest sample: a reflex vertex
    best[vertex] = d[vertex, 0]
    # a foot at an edge's end beside a reflex corner: every point nearest to it lies
    # inside (the edge's own normal there reads a point in the corner's fan as outside)
    reflex = _ReflexEnds.of(boundary)
    rows = np.repeat(np.arange(len(q)), k)
    cand = j.ravel()
    el = els[cand]
    lines = np.array(
        [isinstance(e.piece.curve, LineCurve) if e.piece else False for e in boundary.elements]
    )
    # lines, all at once: the nearest point in closed form
    sel = np.nonzero(lines[el])[0]
    if len(sel):
        foot, n, t = _line_feet(boundary, el[sel], q[rows[sel]])
        _update(best, inside, rows[sel], q[rows[sel]], foot, n, reflex.at(el[sel], t))
    # other curves, element by element: Newton from the sample
    order = np.argsort(el, kind="stable")
    order = order[~lines[el[order]] & ~np.isnan(pars[cand[order]])]
    starts = np.r_[0, np.nonzero(np.diff(el[order]))[0] + 1, len(order)]
    for a, b in itertools.pairwise(starts):
        if a == b:
            continue
        idx = order[a:b]
        e = boundary.elements[int(el[idx[0]])]
        assert e.piece is not None
        lo, hi = sorted((e.piece.t0, e.piece.t1))
        t, c = pars[cand[idx]], q[rows[idx]]
        for _ in range(8):
            p, d1, d2 = e.piece.curve.derivs(t)
            g = np.einsum("ij,ij->i", p - c, d1)
            hh = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", p - c, d2)
            t = np.clip(t - np.where(hh > 0, g / np.where(hh > 0, hh, 1.0), 0.0), lo, hi)
        foot, n, _ = boundary.frame_at(e, t)
        _update(best, inside, rows[idx], c, foot, n, reflex.at(el[idx], t))
    # the nearest sample itself bounds the distance too (a Newton run that stalled or
    # was clamped must not make a disk read as short of the boundary)
    return np.minimum(best, d[:, 0]), inside


@dataclass(frozen=True)
class _ReflexEnds:
    """Which ends of the edge elements meet a reflex corner (a vertex element next to
    them in their loop), with the elements' end parameters."""

    ends: BoolArray  # (elements, 2): at t0, at t1
    t0: FloatArray
    t1: FloatArray

    @classmethod
    def of(cls, boundary: Boundary) -> _ReflexEnds:
        ends = np.zeros((len(boundary.elements), 2), dtype=bool)
        for loop in range(len(boundary.loop_lengths)):
            ring = [e for e in boundary.elements if e.loop == loop]
            for k, e in enumerate(ring):
                ends[e.index] = (ring[k - 1].is_vertex, ring[(k + 1) % len(ring)].is_vertex)
        t0 = np.array([e.piece.t0 if e.piece is not None else np.nan for e in boundary.elements])
        t1 = np.array([e.piece.t1 if e.piece is not None else np.nan for e in boundary.elements])
        return cls(ends, t0, t1)

    def at(self, el: NDArray[np.int64], t: FloatArray) -> BoolArray:
        """Whether each foot (parameter ``t`` on edge element ``el``) is an end of its
        edge that meets a reflex corner (Newton and the closed form clamp exactly onto
        it)."""
        return np.asarray(
            (self.ends[el, 0] & (t == self.t0[el])) | (self.ends[el, 1] & (t == self.t1[el]))
        )


def _line_feet(
    boundary: Boundary, el: NDArray[np.int64], c: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Nearest points of the line elements ``el`` to the points ``c``, the elements'
    inward normals there and the points' parameters."""
    m = len(boundary.elements)
    o, dvec, span, sense = np.zeros((m, 2)), np.ones((m, 2)), np.zeros((m, 2)), np.ones(m)
    for e in boundary.elements:
        if e.piece is not None and isinstance(e.piece.curve, LineCurve):
            o[e.index], dvec[e.index] = e.piece.curve.origin, e.piece.curve.direction
            span[e.index] = sorted((e.piece.t0, e.piece.t1))
            sense[e.index] = 1.0 if e.piece.t1 > e.piece.t0 else -1.0
    oo, dd = o[el], dvec[el]
    t = np.einsum("ij,ij->i", c - oo, dd) / np.einsum("ij,ij->i", dd, dd)
    t = np.clip(t, span[el, 0], span[el, 1])
    foot = oo + t[:, None] * dd
    tan = sense[el, None] * dd / np.linalg.norm(dd, axis=1)[:, None]
    return foot, np.column_stack([-tan[:, 1], tan[:, 0]]), t


def _update(
    best: FloatArray,
    inside: BoolArray,
    rows: NDArray[np.int64],
    c: FloatArray,
    foot: FloatArray,
    n: FloatArray,
    at_reflex: NDArray[np.bool_],
) -> None:
    """Keep, per point, the nearest of the feet found (rows may repeat)."""
    got = np.linalg.norm(foot - c, axis=1)
    side = (np.einsum("ij,ij->i", c - foot, n) >= 0) | at_reflex
    order = np.lexsort((got, rows))
    lead = order[np.r_[True, rows[order][1:] != rows[order][:-1]]]
    r_u, g_u = rows[lead], got[lead]
    better = g_u < best[r_u]
    best[r_u[better]] = g_u[better]
    inside[r_u[better]] = side[lead[better]]


def disk_error(boundary: Boundary, branches: Sequence[Branch]) -> tuple[float, FloatArray]:
    """How far the worst disk of the branches' splines, evaluated at the thirds
    between their knots, is off the boundary, and that disk's centre: ``|radius -
    distance|`` for a centre inside the face (a disk reaching out of it or short of
    it), radius plus distance for a centre outside it."""
    q, r = [], []
    for b in branches:
        knots = np.unique(b.spline.knots)
        if len(knots) < 3:  # one polynomial piece (a straight branch, a short one): no
            continue  # samples between its ends to swing at
        u = np.concatenate([knots[:-1] + f * np.diff(knots) for f in (1 / 3, 2 / 3)])
        v = b.spline(u)
        q.append(v[:, :2])
        r.append(v[:, 2])
    if not q:
        return 0.0, np.zeros(2)
    qq, rr = np.vstack(q), np.concatenate(r)
    ok = np.all(np.isfinite(qq), axis=1) & np.isfinite(rr)
    qq, rr = qq[ok], rr[ok]
    if not len(qq):
        return 0.0, np.zeros(2)
    d, inside = _nearest(boundary, qq)
    error = np.where(inside, np.abs(rr - d), rr + d)
    worst = int(np.argmax(error))
    return float(error[worst]), qq[worst]
