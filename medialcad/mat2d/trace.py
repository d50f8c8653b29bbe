"""Trace the medial axis by marching the medial map along the boundary.

Every boundary point maps to the centre of its maximal tangent disk (:mod:`medial_map`).
Walking each loop, the partner footpoint moves continuously except at *events*:

- a **jump** of the partner: a branch point (located by bisection on the loop coordinate
  down to a fraction of the tolerance; its three footpoints are the point and the two
  partners on either side of the jump);
- a **convex corner**: an end point with ``r = 0``;
- a **self-partner point**: the partner meets the point itself at a curvature maximum
  (or over a whole circular arc): an end point at the centre of curvature, ``r = 1/k``.

Between consecutive events the centres trace one side of a branch; the other side is
traced from the partner's interval, so each branch is kept once. Nodes from all events
are merged by position (a degenerate branch point collects all of its footpoints).
Branches are fitted with splines of ``(x, y, r)`` and refined until exact midpoints lie
within half the tolerance.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.spatial import cKDTree

from medialcad.errors import ComputationError
from medialcad.frame import Frame
from medialcad.mat2d.boundary import Boundary
from medialcad.mat2d.curves import CircleCurve, LineCurve
from medialcad.mat2d.graph import (
    BoundaryElement,
    Branch,
    ElementKind,
    Footpoint,
    MedialGraph,
    Node,
    NodeKind,
)
from medialcad.mat2d.medial_map import (
    CIRCLE,
    LINE,
    MapSamples,
    build_candidates,
    evaluate,
    pair_minima,
)
from medialcad.mat2d.pocket import POCKET_LENGTH, pocket_rows
from medialcad.mat2d.selfcheck import disk_error
from medialcad.mat2d.spline import Spline, fit_spline

__all__ = ["TraceSettings", "trace_medial_graph"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]


@dataclass(frozen=True)
class TraceSettings:
    """Numerical settings of the tracer (all lengths absolute, in model units)."""

    tol: float
    spacing: float  # initial boundary sample spacing
    max_fit_rounds: int = 10
    max_bisection_rounds: int = 64
    max_samples: int = 400_000

    @property
    def eps_s(self) -> float:
        """Bisection resolution on the loop coordinate."""
        return 1e-3 * self.tol


@dataclass
class _Event:
    loop: int
    s_lo: float
    s_hi: float
    kind: NodeKind
    point: FloatArray
    radius: float
    feet: list[tuple[int, float, FloatArray]] = field(default_factory=list)
    node: int = -1
    spread: float = 0.0  # how far the events merged into this one's node lay from it


def _initial_samples(boundary: Boundary, spacing: float) -> tuple[IntArray, FloatArray]:
    loops, ss = [], []
    for e in boundary.elements:
        n = max(4, int(np.ceil(e.length / spacing)))
        if e.piece is not None and not isinstance(e.piece.curve, LineCurve):
            # curved edges: at least one sample per 4 degrees of turning
            t = np.linspace(e.piece.t0, e.piece.t1, 33)
            _, _, k = boundary.frame_at(e, t)
            turn = float(np.mean(np.abs(k))) * e.length
            n = max(n, int(np.ceil(turn / np.radians(4.0))))
        elif e.piece is None:
            n = max(n, int(np.ceil(e.length / boundary.angle_scale / np.radians(4.0))))
        f = (np.arange(n) + 0.5) / n
        # and samples hugging both ends, so corners are approached closely
        delta = min(1e-3, 0.1 / n)
        f = np.concatenate([[delta], f, [1 - delta]])
        ss.append(e.s0 + f * e.length)
        loops.append(np.full(len(f), e.loop))
    return np.concatenate(loops).astype(np.int64), np.concatenate(ss)


def _curvature_maxima(boundary: Boundary) -> tuple[IntArray, FloatArray, FloatArray]:
    """Every local maximum of the (convex) curvature inside the free-form edges:
    ``(loop, s, disk)``, ``disk`` the osculating disk's centre and radius. A grid of 257
    parameters per edge, a grid of 65 across the bracket of each of its maxima, then
    golden-section search between the neighbours of the best. (A curvature jump at a
    joint or a seam is an end the events find themselves.)"""
    loops: list[int] = []
    out: list[float] = []
    disks: list[FloatArray] = [np.zeros((0, 3))]
    for e in boundary.elements:
        if e.piece is None or e.piece.curve.constant_curvature is not None:
            continue
        t = np.linspace(e.piece.t0, e.piece.t1, 257)
        k = boundary.frame_at(e, t)[2]
        left = np.concatenate([[-np.inf], k[:-1]])
        right = np.concatenate([k[1:], [-np.inf]])
        j = np.nonzero((k > 0) & (k >= left) & (k >= right) & ((k > left) | (k > right)))[0]
        j = j[(j > 0) & (j < len(t) - 1)]
        if len(j) == 0:
            continue
        lo, hi = t[j - 1], t[j + 1]
        fine = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, 65)[None, :]
        kf = boundary.frame_at(e, fine.ravel())[2].reshape(fine.shape)
        rows = np.arange(len(j))
        m = np.argmax(kf, axis=1)
        # golden-section search in the fine bracket (a peaked maximum: a parabola
        # through the grid missed one by 4 tol of radius); one new point per step
        a_ = fine[rows, np.maximum(m - 1, 0)]
        b_ = fine[rows, np.minimum(m + 1, 64)]
        g = 0.5 * (np.sqrt(5.0) - 1.0)
        x1, x2 = b_ - g * (b_ - a_), a_ + g * (b_ - a_)
        k1, k2 = boundary.frame_at(e, x1)[2], boundary.frame_at(e, x2)[2]
        for _ in range(40):
            up = k1 < k2  # the maximum is in [x1, b], and x2 is its new x1
            a_, b_ = np.where(up, x1, a_), np.where(up, b_, x2)
            x1, x2 = np.where(up, x2, b_ - g * (b_ - a_)), np.where(up, a_ + g * (b_ - a_), x1)
            k_new = boundary.frame_at(e, np.where(up, x2, x1))[2]
            k1, k2 = np.where(up, k2, k_new), np.where(up, k_new, k1)
        best = 0.5 * (a_ + b_)
        out += boundary.s_of(e, best).tolist()
        loops += [e.loop] * len(best)
        p, n, k = boundary.frame_at(e, best)
        disks.append(np.column_stack([p + n / k[:, None], 1.0 / k]))
    return np.array(loops, dtype=np.int64), np.array(out), np.vstack(disks)


def _one_per_disk(loop: IntArray, disk: FloatArray, near: float) -> IntArray:
    """Indices of the first of each cluster of maxima with the same osculating disk (its
    ``(centre x, centre y, radius)`` within ``near``) on one loop, in order: an arc
    written as a NURBS curve has its constant curvature's rounding for maxima (the gear
    wheel's, 4,267 of them), every one the same disk; the medial map at one of them says
    whether that disk is empty."""
    keep: list[int] = []
    for lp in np.unique(loop):
        idx = np.nonzero(loop == lp)[0]
        tree = cKDTree(disk[idx])
        taken = np.zeros(len(idx), dtype=bool)
        for j in range(len(idx)):
            if not taken[j]:
                keep.append(int(idx[j]))
                taken[tree.query_ball_point(disk[idx[j]], near)] = True
    return np.array(sorted(keep), dtype=np.int64)


def _near_flat_corners(
    boundary: Boundary, cfg: TraceSettings, S: MapSamples
) -> tuple[IntArray, FloatArray]:
    """Samples closing in on every nearly flat convex corner whose spoke the first
    samples miss: the spoke is fed by a boundary stretch of only ``turn * r / 2`` on each
    side, far below the spacing. Where the samples hugging the corner already have their
    partners across it, they lie on that stretch and nothing is added."""
    add_l: list[IntArray] = []
    add_s: list[FloatArray] = []
    order = np.lexsort((S.s, S.loop))
    loops, ss = S.loop[order], S.s[order]
    line_end = _line_line_corners(boundary)
    # (loop, s, turn, is an arc): convex corners, and arcs shorter than the spacing that
    # turn as little (a tiny fillet rounding a nearly flat corner: its spoke, ending at the
    # arc's centre, is fed by the same short stretch around it, and the arc's own samples
    # all see the osculating disk)
    spots = [(c.loop, c.s, c.turn, False) for c in boundary.corners]
    for e in boundary.elements:
        if e.piece is not None and isinstance(e.piece.curve, CircleCurve):
            turn = e.length / e.piece.curve.radius
            convex = boundary.frame_at(e, np.array([0.5 * (e.piece.t0 + e.piece.t1)]))[2][0] > 0
            if convex and e.length < cfg.spacing:
                spots.append((e.loop, e.s0 + 0.5 * e.length, turn, True))
    for loop, s_c, turn, arc in spots:
        if not 0 < turn < np.pi / 6:
            continue
        # not closer than where the two sides are collinear within coordinate noise,
        # unless both are lines (their disks are solved by symmetry about the corner)
        if (loop, s_c) in line_end:
            lo = 1e-2 * cfg.eps_s
        else:
            lo = max(1e-10 * boundary.diag / turn, cfg.eps_s)
        if lo >= cfg.spacing:
            continue
        a, b = np.searchsorted(loops, [loop, loop + 1])
        if b - a >= 2 and not arc:
            k = a + int(np.searchsorted(ss[a:b], s_c))
            before, after = order[a + (k - a - 1) % (b - a)], order[a + (k - a) % (b - a)]
            if (
                S.partner_element[before] == S.element[after]
                and S.partner_element[after] == S.element[before]
            ):
                continue
        d = np.geomspace(cfg.spacing, lo, 24)
        add_s.append(np.concatenate([s_c - d, s_c + d]) % boundary.loop_lengths[loop])
        add_l.append(np.full(2 * len(d), loop, dtype=np.int64))
    if not add_s:
        return np.zeros(0, dtype=np.int64), np.zeros(0)
    return np.concatenate(add_l), np.concatenate(add_s)


def _line_line_corners(boundary: Boundary) -> set[tuple[int, float]]:
    """``(loop, s)`` of the joints between two consecutive lines."""
    by_loop: dict[int, list[Any]] = {}
    for e in boundary.elements:
        by_loop.setdefault(e.loop, []).append(e)
    out = set()
    for lp, els in by_loop.items():
        for a, b in zip(els, els[1:] + els[:1], strict=True):
            if all(e.piece is not None and isinstance(e.piece.curve, LineCurve) for e in (a, b)):
                out.add((lp, a.s0 + a.length))
    return out


def _cyc(d: FloatArray, length: FloatArray) -> FloatArray:
    """Wrap a loop-coordinate difference into ``(-L/2, L/2]``."""
    return np.asarray(d - length * np.round(d / length))


class _Tracer:
    def __init__(self, boundary: Boundary, settings: TraceSettings) -> None:
        self.b = boundary
        self.cfg = settings
        self.fit_ok: set[tuple[int, float, float, int]] = set()
        self.mid_cache: dict[tuple[int, float], tuple[FloatArray, float, bool]] = {}
        self.sp_cache: dict[
            tuple[int, float, float], tuple[FloatArray, float, FloatArray, int, float]
        ] = {}
        self.splines: dict[bytes, Spline] = {}
        self.root_tries: dict[tuple[int, int, int, int], int] = {}
        self.known: list[tuple[FloatArray, FloatArray]] = []
        #: ``(loop, s, centre)`` of the curvature maxima whose osculating disk is empty
        self.empty_maxima: tuple[IntArray, FloatArray, FloatArray] | None = None
        self.cands = build_candidates(boundary, settings.spacing / 2)
        self.L = np.array(boundary.loop_lengths)
        els = boundary.elements
        self.elem_loop = np.array([e.loop for e in els], dtype=np.int64)
        self.loop_first = np.array(
            [min(e.index for e in els if e.loop == lp) for lp in range(len(self.L))]
        )
        self.loop_count = np.bincount(self.elem_loop, minlength=len(self.L))
        self.elem_pos = np.array([e.index for e in els]) - self.loop_first[self.elem_loop]
        self.convex = [
            (c.loop, c.s % self.L[c.loop], c.point) for c in boundary.corners if c.turn > 0
        ]
        # the convex corners sorted by (loop, s), for _off_corners
        cl = np.array([c[0] for c in self.convex], dtype=np.int64)
        cs = np.array([c[1] for c in self.convex], dtype=float)
        self.corner_offset = np.concatenate([[0.0], np.cumsum(self.L + 1.0)])[:-1]
        order = np.argsort(self.corner_offset[cl] + cs) if len(cl) else np.zeros(0, np.int64)
        self.corner_loop, self.corner_s = cl[order], cs[order]
        self.corner_key = self.corner_offset[self.corner_loop] + self.corner_s
        # consecutive elements meeting smoothly (not at a convex corner), low index first
        at_corner = {(c.loop, c.s) for c in boundary.corners if c.turn > 0}
        self.smooth_pairs: set[tuple[int, int]] = set()
        for e in els:
            if (e.loop, e.s0 + e.length) not in at_corner:
                k = self.loop_first[e.loop] + (self.elem_pos[e.index] + 1) % self.loop_count[e.loop]
                if k != e.index:
                    self.smooth_pairs.add((min(e.index, int(k)), max(e.index, int(k))))

    def fit(self, values: FloatArray) -> Spline:
        """:func:`fit_spline` through ``values``, remembered (the fit check and the
        assembly fit the same branches)."""
        key = np.ascontiguousarray(values).tobytes()
        if key not in self.splines:
            self.splines[key] = fit_spline(values)
        return self.splines[key]

    # -- sampling ------------------------------------------------------------------
    def eval(self, loop: IntArray, s: FloatArray) -> MapSamples:
        s = self._off_corners(loop, np.mod(s, self.L[loop]))
        return evaluate(self.b, self.cands, loop, s, self.cfg.tol, self._hint(loop, s))

    def _off_corners(self, loop: IntArray, s: FloatArray) -> FloatArray:
        """``s`` moved off every convex corner it sits on (within a thousandth of the
        bisection resolution), to the side it was on: at the corner itself the medial
        map is its limit from neither side (the disk tangent to one edge there, not the
        corner's end point of radius 0). A fit check's midpoint between samples placed
        symmetrically about a nearly flat corner fell on it exactly, and the step
        from there to its neighbour, whose partner was the corner's spoke, was taken
        for a branch point of the average radius."""
        if len(self.corner_s) == 0 or len(s) == 0:
            return s
        out = np.asarray(s, dtype=float).copy()
        length = self.L[loop]
        key = self.corner_offset[loop] + out
        k = np.searchsorted(self.corner_key, key)
        delta = np.maximum(1e-3 * self.cfg.eps_s, 64.0 * np.spacing(length))
        # the corners either side, and the loop's first and last (across its seam)
        first = np.searchsorted(self.corner_key, self.corner_offset[loop])
        last = np.searchsorted(self.corner_key, self.corner_offset[loop] + length) - 1
        for j in (k - 1, k, first, last):
            j = np.clip(j, 0, len(self.corner_s) - 1)
            same = self.corner_loop[j] == loop
            d = np.remainder(out - self.corner_s[j] + 0.5 * length, length) - 0.5 * length
            on = same & (np.abs(d) < delta)
            out = np.where(
                on, np.mod(self.corner_s[j] + np.where(d > 0, delta, -delta), length), out
            )
        return out

    def remember(self, S: MapSamples) -> None:
        """Keep the radii of samples sorted by loop and coordinate (hints for new ones)."""
        order = np.lexsort((S.s, S.loop))
        lp, ss, rr = S.loop[order], S.s[order], S.radius[order]
        cut = np.searchsorted(lp, np.arange(len(self.L) + 1))
        self.known = [(ss[a:b], rr[a:b]) for a, b in itertools.pairwise(cut.tolist())]

    def _hint(self, loop: IntArray, s: FloatArray) -> FloatArray | None:
        """A radius guess per point: 1.25 times the larger radius of the remembered
        samples either side (the radius along the boundary is continuous)."""
        if not self.known:
            return None
        out = np.zeros(len(s))
        for lp in np.unique(loop):
            ks, kr = self.known[lp]
            if len(ks) == 0:
                continue
            sel = np.nonzero(loop == lp)[0]
            j = np.searchsorted(ks, s[sel])
            r = np.maximum(kr[(j - 1) % len(ks)], kr[j % len(ks)])
            out[sel] = np.where(np.isfinite(r), 1.25 * r, 0.0)
        return out

    def frame_s(self, loop: int, s: float) -> tuple[FloatArray, FloatArray, float, int, float]:
        s = float(s % self.L[loop])
        e = self.b.element_at(loop, s)
        t = self.b.param_of(e, np.array([s]))
        p, n, k = self.b.frame_at(e, t)
        return p[0], n[0], float(k[0]), e.index, float(t[0])

    def _partner_over_corner(
        self, S: MapSamples, idx: IntArray, nxt: IntArray, same_loop: NDArray[np.bool_]
    ) -> NDArray[np.bool_]:
        out = np.zeros(len(idx), dtype=bool)
        for plp in np.unique(S.partner_loop[idx]):
            sel = np.nonzero(same_loop & (S.partner_loop[idx] == plp))[0]
            if len(sel) == 0:
                continue
            p0, p1 = S.partner_s[idx[sel]], S.partner_s[nxt[sel]]
            d = _cyc(p1 - p0, self.L[plp])
            start = np.where(d < 0, p1, p0)
            out[sel] = self._crosses_corner(int(plp), start, np.abs(d))
        return out

    def _adjacent(self, a: IntArray, b: IntArray) -> NDArray[np.bool_]:
        """Whether elements ``a`` and ``b`` follow each other on their loop."""
        pos, count, loop = self.elem_pos, self.loop_count, self.elem_loop
        same = loop[a] == loop[b]
        d = np.abs(pos[a] - pos[b])
        return np.asarray(same & ((d == 1) | (d == count[loop[a]] - 1)))

    def eval_cached(
        self, loop: IntArray, s: FloatArray
    ) -> tuple[FloatArray, FloatArray, NDArray[np.bool_]]:
        """Centre, radius and self flag at ``(loop, s)``, remembering past answers
        (the fit check asks for the same midpoints again after a refit)."""
        cache = self.mid_cache
        keys = [(int(lp), float(x)) for lp, x in zip(loop, s, strict=True)]
        todo = [i for i, k in enumerate(keys) if k not in cache]
        if todo:
            M = self.eval(loop[todo], s[todo])
            cen = M.centre
            for j, i in enumerate(todo):
                cache[keys[i]] = (cen[j], float(M.radius[j]), bool(M.is_self[j]))
        vals = [cache[k] for k in keys]
        return (
            np.array([v[0] for v in vals]).reshape(-1, 2),
            np.array([v[1] for v in vals]),
            np.array([v[2] for v in vals], dtype=bool),
        )

    # -- events --------------------------------------------------------------------
    def _crosses_corner(self, loop: int, s0: FloatArray, ds: FloatArray) -> NDArray[np.bool_]:
        """Whether a convex corner lies strictly inside each step ``[s0, s0 + ds]``."""
        cs = np.sort([sv for lp, sv, _ in self.convex if lp == loop])
        if len(cs) == 0:
            return np.zeros(len(s0), dtype=bool)
        length = self.L[loop]
        ext = np.concatenate([cs - length, cs, cs + length])
        lo = np.searchsorted(ext, s0, side="right")
        hi = np.searchsorted(ext, s0 + ds, side="left")
        return np.asarray(hi > lo)

    def _sp_node(
        self, loop: int, s0: float, s1: float
    ) -> tuple[FloatArray, float, FloatArray, int, float]:
        """The centre of curvature at the curvature maximum in ``[s0, s1]`` (golden section;
        remembered, as every refinement round finds the same end points again)."""
        key = (loop, float(s0), float(s1))
        if key not in self.sp_cache:
            self.sp_cache[key] = self._sp_node_solve(loop, s0, s1)
        return self.sp_cache[key]

    def _sp_node_solve(
        self, loop: int, s0: float, s1: float, retry: bool = True
    ) -> tuple[FloatArray, float, FloatArray, int, float]:
        length = self.L[loop]
        a, b = s0, s0 + (s1 - s0) % length
        # the samples only bracket the maximum approximately: widen by half the bracket,
        # staying on the curve that holds it
        pad = 0.5 * (b - a) + 1e-3 * self.cfg.spacing
        e = self.b.element_at(loop, float((0.5 * (a + b)) % length))
        if e.piece is not None and e.length < length:
            oa = (a - e.s0) % length
            ob = oa + (b - a)
            lo, hi = a, b  # a bracket over a joint between elements: searched as it is
            if ob <= e.length:  # within one element: padded and extended on it only
                lo, hi = a - oa, a - oa + e.length
                a, b = max(a - pad, lo), min(b + pad, hi)
        else:
            a, b = a - pad, b + pad
            lo, hi = 0.5 * (a + b) - 0.5 * length, 0.5 * (a + b) + 0.5 * length
        if b <= a:
            b = a + 1e-12
        best = self._golden_max(loop, a, b)
        # the maximum can lie outside the samples' bracket: at a curvature jump (a C1
        # seam or knot, the high side's curvature falling away from it) the self samples
        # start only a little after it. When the maximum sits at an end of the bracket
        # that is not the end of the curve, march on beyond that end in doubling steps
        # while the curvature rises (a window searched by golden section alone can put
        # both first probes past a jump and lose it: a blob's end 7.5 tol short of its
        # seam), then close in on the highest probe
        # (not on a curve of constant curvature, an arc: there every point is a maximum)
        constant = e.piece is not None and e.piece.curve.constant_curvature is not None
        stop = 4e-3 * self.cfg.eps_s
        x = best[5]
        side = -1.0 if x - a < stop and a > lo else 1.0 if b - x < stop and b < hi else 0.0
        if side and not constant:
            best = self._march_max(loop, best, side, lo, hi, stop)
        p, n, k, ei, t, _ = best
        if k <= 0 and retry and e.piece is not None and e.length < length:
            # a bracket at a joint (a nearly smooth one whose tangents differ by the joint's
            # gap, a convex corner of 1e-6 rad between a line and a fillet) can take the
            # element on the wrong side: the maximum is on the one across the joint
            eps = 1e-9 * self.cfg.spacing
            if a <= e.s0 + eps:
                x = (e.s0 - eps) % length
                return self._sp_node_solve(loop, x, x, retry=False)
            if b >= e.s0 + e.length - eps:
                x = (e.s0 + e.length + eps) % length
                return self._sp_node_solve(loop, x, x, retry=False)
        if k <= 0:
            raise ComputationError("self-partner point on a non-convex boundary stretch")
        return p + n / k, 1.0 / k, p, ei, t

    def _march_max(
        self,
        loop: int,
        best: tuple[FloatArray, FloatArray, float, int, float, float],
        side: float,
        lo: float,
        hi: float,
        stop: float,
    ) -> tuple[FloatArray, FloatArray, float, int, float, float]:
        """The curvature maximum beyond ``best`` (a bracket end) on ``side``: steps of
        ``stop * 2^j`` while the curvature rises by more than rounding, then a golden
        section that keeps the highest probe inside its bracket (a maximum at a jump is
        approached from its high side). ``best`` itself when nothing beyond is higher."""

        def probe(x: float) -> tuple[FloatArray, FloatArray, float, int, float, float]:
            q = self.frame_s(loop, x)
            return (*q, x)

        x0 = best[5]
        prev, cur = best, best
        step = stop
        nxt = None
        for _ in range(80):
            x = min(hi, max(lo, x0 + side * step))
            cand = probe(x)
            if cand[2] - cur[2] <= 1e-14 * abs(cur[2]):
                nxt = cand
                break
            prev, cur = cur, cand
            if x in (lo, hi):
                break
            step *= 2.0
        if cur is best:
            return best
        if nxt is None:  # rising up to the end of the search: its end rules
            return cur
        # the triple prev < cur > nxt (along ``side``): golden section on it
        g = 0.5 * (3.0 - np.sqrt(5.0))
        a, b = sorted((prev[5], nxt[5]))
        for _ in range(200):
            if b - a < 1e-3 * self.cfg.eps_s:
                break
            xc = cur[5]
            u = xc + g * (b - xc) if b - xc > xc - a else xc - g * (xc - a)
            cand = probe(u)
            if cand[2] > cur[2]:
                if u > xc:
                    a = xc
                else:
                    b = xc
                cur = cand
            elif u > xc:
                b = u
            else:
                a = u
        return cur

    def _golden_max(
        self, loop: int, a: float, b: float
    ) -> tuple[FloatArray, FloatArray, float, int, float, float]:
        """The boundary frame at the curvature maximum in ``[a, b]`` (golden section), and
        its loop coordinate."""
        g = (np.sqrt(5) - 1) / 2
        x1, x2 = b - g * (b - a), a + g * (b - a)
        k1, k2 = self.frame_s(loop, x1)[2], self.frame_s(loop, x2)[2]
        for _ in range(80):
            if b - a < 1e-3 * self.cfg.eps_s:
                break
            if k1 > k2:
                b, x2, k2 = x2, x1, k1
                x1 = b - g * (b - a)
                k1 = self.frame_s(loop, x1)[2]
            else:
                a, x1, k1 = x1, x2, k2
                x2 = a + g * (b - a)
                k2 = self.frame_s(loop, x2)[2]
        x = 0.5 * (a + b)
        p, n, k, ei, t = self.frame_s(loop, x)
        # at a curvature jump (a periodic B-spline only C1 at its seam, a C1 knot) the
        # middle can land on the low side (a node 0.1 diag off): the last probes either
        # side of it rule there
        for xp in (x1, x2):
            q = self.frame_s(loop, xp)
            if q[2] > k:
                (p, n, k, ei, t), x = q, xp
        return p, n, k, ei, t, x

    def missing_centres(self, ends: list[FloatArray]) -> tuple[IntArray, FloatArray, FloatArray]:
        """``(loop, s, centre)`` of every curvature maximum inside a free-form edge whose
        osculating disk is empty (an end point of the axis) with no curvature-centre
        node among ``ends`` (one per centre: an arc stored as a NURBS curve has its
        constant curvature's rounding for maxima, 95 of them at one centre)."""
        near = max(self.cfg.tol, 10 * self.cfg.eps_s)
        if self.empty_maxima is None:
            loop, s, disk = _curvature_maxima(self.b)
            one = _one_per_disk(loop, disk, 1e-3 * near)
            loop, s = loop[one], s[one]
            centre = np.zeros((0, 2))
            if len(s):
                at_max = self.eval(loop, s)
                sel = at_max.is_self  # an empty osculating disk
                loop, s, centre = loop[sel], s[sel], at_max.centre[sel]
            self.empty_maxima = (loop, s, centre)
        loop, s, centre = self.empty_maxima
        miss = np.ones(len(s), dtype=bool)
        if len(ends):
            at = np.array(ends).reshape(-1, 2)
            gap = np.linalg.norm(centre[:, None, :] - at[None, :, :], axis=2).min(axis=1)
            miss = gap > near
        keep: list[int] = []
        for k in np.nonzero(miss)[0]:
            if all(np.linalg.norm(centre[k] - centre[i]) > near for i in keep):
                keep.append(int(k))
        return loop[keep], s[keep], centre[keep]

    def missing_ends(
        self,
        missing: tuple[IntArray, FloatArray, FloatArray],
        S: MapSamples,
        exact: bool = False,
    ) -> MapSamples | None:
        """Samples for the ``missing`` end points (:meth:`missing_centres`): the branch
        ending there is fed by a stretch narrower than the sample spacing, and no step of
        the samples saw it. Not inside the end's own stretch (self samples there hide the
        partner jumps of a branch point beside it): a geometric cluster, down to the
        tolerance, about the boundary point across the disk (from the samples ``S``)
        whose partner jumps over the stretch: the jump finds the branch point, and the
        branch follows. ``exact``: about the point across where the partner passes the
        maximum, bisected to the coordinate noise (:meth:`_across`), for a jump the
        cluster's steps read as continuous. ``None`` if there is nowhere to put them."""
        steps = self.cfg.spacing * 0.5 ** np.arange(1, 60)
        steps = steps[steps > self.cfg.tol]
        offsets = np.concatenate([[0.0], steps, -steps])
        seeds_l: list[int] = []
        seeds_s: list[float] = []
        for lp, s_m, c in zip(*missing, strict=True):
            p, _, _, _, _ = self.frame_s(int(lp), float(s_m))
            rho = float(np.linalg.norm(c - p))
            far = np.linalg.norm(S.foot - p, axis=1) > rho
            if not np.any(far):
                continue
            if exact:
                at = self._across(S, far, int(lp), float(s_m), c)
                if at is None:
                    continue
                seeds_l += [at[0]] * (len(offsets) + 2)
                seeds_s += (at[1] + offsets).tolist() + list(at[2])
                continue
            d = np.where(far, np.linalg.norm(S.foot - c, axis=1), np.inf)
            j = int(np.argmin(d))
            seeds_l += [int(S.loop[j])] * len(offsets)
            seeds_s += (S.s[j] + offsets).tolist()
        if not seeds_s:
            return None
        return self.eval(np.array(seeds_l, dtype=np.int64), np.array(seeds_s))

    def _across(
        self, S: MapSamples, far: NDArray[np.bool_], loop: int, s_m: float, centre: FloatArray
    ) -> tuple[int, float, tuple[float, float]] | None:
        """``(loop, s, (s_lo, s_hi))`` across an empty osculating disk (at ``(loop,
        s_m)``, centred at ``centre``) where the partner passes the maximum: of the
        consecutive ``far`` samples whose partners lie on either side of it, the pair
        nearest the centre, bisected down to the coordinate noise (``s_lo``, ``s_hi``:
        the last pair). Near a weak maximum the partner sweeps over the stretch feeding
        its branch so fast that a step crossing it reads as continuous; at the limit it
        is a jump. ``None`` if no pair."""
        order = np.lexsort((S.s, S.loop))
        a, b = order, np.roll(order, -1)
        half = 0.5 * self.L[loop]
        off = np.remainder(S.partner_s - s_m + half, 2 * half) - half
        mine = S.partner_loop == loop
        pair = (
            (S.loop[a] == S.loop[b])
            & far[a]
            & far[b]
            & mine[a]
            & mine[b]
            & (np.sign(off[a]) != np.sign(off[b]))
            & (np.abs(off[a] - off[b]) < half)
        )
        if not np.any(pair):
            return None
        gap = np.linalg.norm(S.foot - centre, axis=1)
        i = int(np.argmin(np.where(pair, np.minimum(gap[a], gap[b]), np.inf)))
        lp = int(S.loop[a[i]])
        lo, hi = float(S.s[a[i]]), float(S.s[b[i]])
        if hi < lo:  # the pair spans the loop's seam
            hi += self.L[lp]
        side = np.sign(off[a[i]])
        for _ in range(200):  # (a tolerance below the coordinates' rounding stops here)
            x = 0.5 * (lo + hi)
            if hi - lo <= 1e-3 * self.cfg.eps_s or x in (lo, hi):
                break
            M = self.eval(np.array([lp]), np.array([x]))
            o = math.remainder(float(M.partner_s[0]) - s_m, 2 * half)
            if int(M.partner_loop[0]) == loop and np.sign(o) == side:
                lo = x
            else:
                hi = x
        return lp, 0.5 * (lo + hi), (lo, hi)

    def resolve(self, S: MapSamples) -> tuple[MapSamples, list[_Event], bool]:
        """Refine the samples until every step is continuous or an event is isolated.
        Returns the samples, the events, and whether it converged."""
        cfg = self.cfg
        for _ in range(cfg.max_bisection_rounds):
            order = np.lexsort((S.s, S.loop))
            S = S.take(order)
            self.remember(S)
            events: list[_Event] = []
            new_loop: list[int] = []
            new_s: list[float] = []
            jumps: list[_Jump] = []
            for lp in range(len(self.L)):
                idx = np.nonzero(S.loop == lp)[0]
                if len(idx) == 0:
                    continue
                self._loop_events(S, idx, lp, events, new_loop, new_s, jumps)
            if jumps:
                jl, js = self._bracket_jumps(jumps)
                new_loop += jl
                new_s += js
            if not new_s:
                return S, events, True
            # the budget grows with the boundary: every element has its own samples
            limit = max(cfg.max_samples, 400 * len(self.b.elements))
            if len(S) + len(new_s) > limit:
                raise ComputationError(f"the medial axis needs more than {limit} boundary samples")
            S = MapSamples.concat([S, self.eval(np.array(new_loop), np.array(new_s))])
        return S, events, False

    def _bracket_jumps(self, jumps: list[_Jump]) -> tuple[list[int], list[float]]:
        """New samples for steps where the partner jumps from one element to another:
        a pair just either side of the point where both elements allow the same disk
        (the branch point, found on those two elements alone), or, where that fails,
        the step split in eight."""
        lp = np.array([j.loop for j in jumps], dtype=np.int64)
        a = np.array([j.s0 for j in jumps])
        w = np.array([j.ds for j in jumps])
        e0 = np.array([j.e0 for j in jumps], dtype=np.int64)
        e1 = np.array([j.e1 for j in jumps], dtype=np.int64)
        x = self._jump_roots(lp, a, w, e0, e1)
        # close around the tie: the centres either side differ by the centre's speed
        # times the gap (large next to a nearly flat corner), kept below 1e-3 tol
        eps = self.cfg.eps_s
        delta = np.full(len(jumps), 1e-3 * eps)
        has = np.nonzero(np.isfinite(x))[0]
        if len(has):
            loops = np.concatenate([lp[has], lp[has]])
            xs = np.concatenate([x[has] - delta[has], x[has] + delta[has]])
            v = pair_minima(
                self.b,
                self.cands,
                loops,
                np.mod(xs, self.L[loops]),
                np.concatenate([e0[has], e1[has]]),
                self.cfg.tol,
            )
            jump = np.abs(v[len(has) :] - v[: len(has)])
            with np.errstate(invalid="ignore", divide="ignore"):
                shrink = np.where(jump > 1e-3 * self.cfg.tol, 1e-3 * self.cfg.tol / jump, 1.0)
            floor = self._root_width(lp[has])
            delta[has] = np.maximum(delta[has] * np.nan_to_num(shrink, nan=1.0), floor)
        out_l: list[int] = []
        out_s: list[float] = []
        frac = np.arange(1, 8) / 8.0
        for i in range(len(jumps)):
            if np.isfinite(x[i]):
                # and a geometric cluster either side down to a tenth of the tolerance,
                # as bisection would leave: the branches ending there are sampled
                # densely next to their node, where feet and centres turn fastest
                # (not between lines: those branches are straight)
                steps = w[i] * 0.125 ** np.arange(1, 40)
                steps = steps[(steps > 0.1 * self.cfg.tol) & (not jumps[i].lines)]
                pts = np.concatenate(
                    [[x[i] - delta[i], x[i] + delta[i]], x[i] - steps, x[i] + steps]
                )
                pts = pts[(pts > a[i]) & (pts < a[i] + w[i])]
            else:
                pts = a[i] + w[i] * frac
            out_l += [int(lp[i])] * len(pts)
            out_s += [float(v) for v in pts]
        return out_l, out_s

    def _root_width(self, lp: IntArray) -> FloatArray:
        """How closely the ties are solved on each loop: 1e-6 of the bisection
        resolution, but no closer than 16 units in the last place of the coordinate."""
        return np.maximum(1e-6 * self.cfg.eps_s, 16.0 * np.spacing(2.0 * self.L[lp]))

    def _jump_roots(
        self, lp: IntArray, a: FloatArray, w: FloatArray, e0: IntArray, e1: IntArray
    ) -> FloatArray:
        """Where ``f`` minimized on element ``e0`` equals ``f`` minimized on ``e1``, in
        each step ``[a, a + w]`` (bracketed: ``e0`` wins at ``a``, ``e1`` at ``a + w``);
        Illinois false position with a bisection every fourth step and no step closer
        than half the width to an end, to :meth:`_root_width`. NaN where the bracket
        does not hold or it fails."""
        cfg = self.cfg
        m = len(a)

        def g(idx: IntArray, x: FloatArray) -> FloatArray:
            loops = np.concatenate([lp[idx], lp[idx]])
            xs = np.mod(np.concatenate([x, x]), self.L[loops])
            v = pair_minima(
                self.b, self.cands, loops, xs, np.concatenate([e0[idx], e1[idx]]), cfg.tol
            )
            with np.errstate(invalid="ignore"):
                return np.asarray(v[: len(idx)] - v[len(idx) :])

        lo, hi = a.copy(), a + w
        width = self._root_width(lp)
        every = np.arange(m)
        g_lo, g_hi = g(every, lo), g(every, hi)
        ok = np.isfinite(g_lo) & np.isfinite(g_hi) & (g_lo <= 0) & (g_hi >= 0)
        kept = np.zeros(m, dtype=np.int64)  # +1: hi moved last time, -1: lo moved
        for it in range(200):
            idx = np.nonzero(ok & (hi - lo > width))[0]
            if len(idx) == 0:
                break
            gl, gh, l0, h0 = g_lo[idx], g_hi[idx], lo[idx], hi[idx]
            with np.errstate(invalid="ignore", divide="ignore"):
                xf = (l0 * gh - h0 * gl) / (gh - gl)
            mid = 0.5 * (l0 + h0)
            bad = ~np.isfinite(xf) | (it % 4 == 3)
            # a step at least half the width from either end: once one end sits on the
            # root (to its last digits) false position lands on it (or, rounded, past
            # it) again and again and only bisections moved the other end (35 steps for
            # ~15 % of ties); the step just inside closes the bracket to the width
            half = 0.5 * width[idx]
            xn = np.where(bad, mid, np.clip(xf, l0 + half, h0 - half))
            gx = g(idx, xn)
            ok[idx[~np.isfinite(gx)]] = False
            up = gx >= 0
            zero = gx == 0
            # Illinois: an end kept twice in a row has its value halved
            g_lo[idx] = np.where(up & (kept[idx] == 1), 0.5 * gl, gl)
            g_hi[idx] = np.where(~up & (kept[idx] == -1), 0.5 * gh, gh)
            hi[idx] = np.where(up, xn, h0)
            g_hi[idx] = np.where(up, gx, g_hi[idx])
            lo[idx] = np.where(up & ~zero, l0, xn)
            g_lo[idx] = np.where(up & ~zero, g_lo[idx], gx)
            kept[idx] = np.where(up, 1, -1)
        good = ok & (hi - lo <= width)
        return np.where(good, 0.5 * (lo + hi), np.nan)

    def _loop_events(
        self,
        S: MapSamples,
        idx: IntArray,
        lp: int,
        events: list[_Event],
        new_loop: list[int],
        new_s: list[float],
        jumps: list[_Jump],
    ) -> None:
        cfg = self.cfg
        length = self.L[lp]
        nxt = np.roll(idx, -1)
        s0, s1 = S.s[idx], S.s[nxt]
        ds = (s1 - s0) % length
        if len(idx) == 1:
            ds = np.array([length])
        same_loop = S.partner_loop[idx] == S.partner_loop[nxt]
        plen = self.L[S.partner_loop[idx]]
        gap = np.where(same_loop, np.abs(_cyc(S.partner_s[nxt] - S.partner_s[idx], plen)), np.inf)
        d0 = np.where(S.partner_loop[idx] == lp, _cyc(S.partner_s[idx] - s0, length), np.inf)
        d1 = np.where(S.partner_loop[nxt] == lp, _cyc(S.partner_s[nxt] - s1, length), -np.inf)
        self_ = S.is_self
        # convex corners: one event each, at the vertex
        for lpc, sv, pt in self.convex:
            if lpc == lp:
                events.append(_Event(lp, sv, sv, NodeKind.CONVEX_VERTEX, pt, 0.0, [(-1, 0.0, pt)]))
        # runs of self samples: one curvature-centre event each
        n = len(idx)
        run = self_[idx]
        start_run = [int(j) for j in np.nonzero(run & ~np.roll(run, 1))[0]]
        if n and run.all():
            start_run = [0]
        for j0 in start_run:
            j1 = j0
            while self_[idx[(j1 + 1) % n]] and (j1 + 1) % n != j0:
                j1 += 1
            lo_s, hi_s = S.s[idx[j0]], S.s[idx[j1 % n]]
            if run.all():
                lo_s, hi_s = 0.0, length
            c, r, p, ei, t = self._sp_node(lp, lo_s, hi_s)
            events.append(_Event(lp, lo_s, hi_s, NodeKind.CURVATURE_CENTRE, c, r, [(ei, t, p)]))
        if n < 2:
            return
        crosses = self._crosses_corner(lp, s0, ds)
        # steps across a convex corner take part in jump detection too: a nearly flat
        # corner's spoke meets the main axis at a branch point right next to it
        cand = ~self_[idx] & ~self_[nxt]
        # a jump: the partner moves much faster over this step than over the steps
        # beside it, and keeps doing so as the step is halved, and its *point* moves by
        # more than tol (a partner turning about a reflex vertex sweeps the vertex's
        # element, angle x angle_scale, without moving: fast next to a small feature)
        moved = np.hypot(*(S.partner_point[nxt] - S.partner_point[idx]).T)
        pgap = np.where(same_loop, moved, np.inf)
        ratio = gap / np.maximum(ds, 1e-300)
        cont = np.where(cand & np.isfinite(ratio), ratio, np.inf)
        beside = np.minimum(np.roll(cont, 1), np.roll(cont, -1))
        beside = np.where(np.isfinite(beside), beside, 0.0)
        pe0, pe1 = S.partner_element[idx], S.partner_element[nxt]
        apart = (pe0 != pe1) & ~self._adjacent(pe0, pe1)
        # a partner never rests on a convex corner: stepping over one is a jump (the
        # corner's spoke meets the axis there), however small the step
        # (a step that itself crosses a convex corner has partners on both sides of it)
        apart |= self._partner_over_corner(S, idx, nxt, same_loop) & ~crosses
        jump = cand & (gap > cfg.tol) & (pgap > cfg.tol) & ((ratio > 3.0 * beside + 1.0) | apart)
        split = jump & (ds > cfg.eps_s)
        # a jump between two distinct elements: bracket the point where they tie (a few
        # times per pair at most: a step may hold more than one event)
        own = S.element[idx]
        js = np.nonzero(split & (pe0 != pe1) & (pe0 >= 0) & (pe1 >= 0))[0]
        if len(js):
            kind = self.cands.kind
            all_lines = (
                (kind[own[js]] == LINE)
                & (kind[S.element[nxt[js]]] == LINE)
                & (kind[pe0[js]] == LINE)
                & (kind[pe1[js]] == LINE)
            ).tolist()
            rows = zip(
                js.tolist(),
                own[js].tolist(),
                pe0[js].tolist(),
                pe1[js].tolist(),
                s0[js].tolist(),
                ds[js].tolist(),
                all_lines,
                strict=True,
            )
            for j, ej, a, b, sj, dj, lines in rows:
                key = (lp, ej, a, b)
                tries = self.root_tries.get(key, 0)
                if tries < 3:
                    self.root_tries[key] = tries + 1
                    jumps.append(_Jump(lp, sj, dj, a, b, lines))
                    split[j] = False
        # split other suspicious steps in eight: fewer rounds of (overhead-bound) evaluation
        frac = np.arange(1, 8) / 8.0
        pts = (s0[split, None] + ds[split, None] * frac[None, :]).ravel()
        new_loop += [lp] * len(pts)
        new_s += list(pts)
        split |= jump & (ds > cfg.eps_s)
        # an isolated jump: a branch point with the point and the partners either side
        # as its footpoints (built row-wise from whole columns: there are thousands)
        js = np.nonzero(jump & ~split)[0]
        if len(js):
            i0, i1 = idx[js], nxt[js]
            cs = 0.5 * (S.centre[i0] + S.centre[i1])
            rows = zip(
                s0[js].tolist(),
                (s0[js] + ds[js]).tolist(),
                cs,
                (0.5 * (S.radius[i0] + S.radius[i1])).tolist(),
                S.element[i0].tolist(),
                S.param[i0].tolist(),
                S.foot[i0],
                S.partner_element[i0].tolist(),
                S.partner_param[i0].tolist(),
                S.partner_point[i0],
                S.partner_element[i1].tolist(),
                S.partner_param[i1].tolist(),
                S.partner_point[i1],
                strict=True,
            )
            bp = NodeKind.BRANCH_POINT
            for lo_s, hi_s, c, r, ea, ta, fa, eb, tb, fb, ec, tc, fc in rows:
                feet = [(ea, ta, fa), (eb, tb, fb), (ec, tc, fc)]
                events.append(_Event(lp, lo_s, hi_s, bp, c, r, feet))
        # a self-partner point: the (continuous) partner passes the point itself, from
        # ahead to behind; d0 - d1 = ds - (p1 - p0) <= ds + gap unless d wrapped around
        # the loop (the bound was 3 ds: a partner moving 2.1 times faster than the point
        # crossed it unseen, and the two sides of a branch became one self-twin loop)
        sp = cand & ~crosses & ~jump & (d0 > 0) & (d1 < 0) & (d0 - d1 <= ds + gap + cfg.tol)
        for j in np.nonzero(sp)[0]:
            c, r, p, ei, t = self._sp_node(lp, s0[j], s0[j] + ds[j])
            events.append(
                _Event(lp, s0[j], s0[j] + ds[j], NodeKind.CURVATURE_CENTRE, c, r, [(ei, t, p)])
            )


@dataclass(frozen=True)
class _Jump:
    """A step ``[s0, s0 + ds]`` of a loop over which the partner jumps from element
    ``e0`` to element ``e1``."""

    loop: int
    s0: float
    ds: float
    e0: int
    e1: int
    lines: bool = False  # the own elements at both ends and e0, e1 are all lines


def _complete_feet(
    tr: _Tracer, S: MapSamples, events: list[_Event], width: float, radius: float
) -> list[_Event]:
    """A branch point found at one of its footpoints is an event at each of the others
    too. Where a partner crosses a nearly flat convex corner it moves by less than the
    tolerance, which the jump test does not see, while the corner's spoke is found from
    its two sides: the foot across from the corner gets its event here. A foot within
    ``width`` (on the loop coordinate) of an event of its loop at the same point (within
    ``radius``, the node merge radius) is covered; so is a foot
    next to a sample whose disk is the osculating one (where the branch point's disk
    osculates too, at a curvature-centre end point, the other events rule)."""
    C = tr.cands
    bps = [e for e in events if e.kind is NodeKind.BRANCH_POINT]
    feet = [(e, k) for e in bps for k, f in enumerate(e.feet) if f[0] >= 0]
    if not feet:
        return events
    el = np.array([e.feet[k][0] for e, k in feet], dtype=np.int64)
    par = np.array([e.feet[k][1] for e, k in feet])
    a, b = C.el_a[el], C.el_b[el]
    with np.errstate(divide="ignore", invalid="ignore"):
        f = np.clip(np.where(b != a, (par - a) / (b - a), 0.0), 0.0, 1.0)
    s_foot = C.el_s0[el] + f * C.el_len[el]
    loops = C.el_loop[el]
    covered = np.zeros(len(feet), dtype=bool)
    node_pt = np.array([e.point for e, _ in feet])
    for lp in np.unique(loops):
        length = tr.L[lp]
        evs = [e for e in events if e.loop == lp]
        q = np.nonzero(loops == lp)[0]
        if not evs:
            continue
        lo = np.array([e.s_lo for e in evs]) % length
        ext = np.array([e.s_hi - e.s_lo for e in evs]) % length
        ext = np.where([e.s_hi - e.s_lo >= length for e in evs], length, ext)
        pts = np.tile(np.array([e.point for e in evs]), (3, 1))
        lo = np.concatenate([lo - length, lo, lo + length])
        hi = lo + np.tile(ext, 3)
        sq = np.mod(s_foot[q], length)
        # events of this loop near the foot; covered by one of the same branch point
        # (another branch point's event can lie within tol on a dense polygon). Short
        # events are found by a window on their sorted starts; the few long ones (a
        # curvature centre's stretch of an arc) are asked by every foot, in chunks
        # (one long event in a window as wide as itself made every foot ask every event:
        # 4e8 pairs where a gap at a joint had scattered events)
        long = (hi - lo) > 4 * width
        hit: list[IntArray] = []
        order = np.argsort(lo[~long])
        slo, shi, spt = lo[~long][order], hi[~long][order], pts[~long][order]
        j0 = np.searchsorted(slo, sq - 5 * width, side="left")
        j1 = np.searchsorted(slo, sq + width, side="right")
        count = np.maximum(j1 - j0, 0)
        row = np.repeat(np.arange(len(q)), count)
        ev = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
        ev += np.repeat(j0, count)
        hit.append(_covering(sq, node_pt[q], row, ev, (slo, shi, spt), width, radius))
        n_long = int(long.sum())
        step = max(1, 1_000_000 // max(n_long, 1))
        for c in range(0, len(q) if n_long else 0, step):
            rows = np.arange(c, min(c + step, len(q)))
            row, ev = np.repeat(rows, n_long), np.tile(np.arange(n_long), len(rows))
            spans = (lo[long], hi[long], pts[long])
            hit.append(_covering(sq, node_pt[q], row, ev, spans, width, radius))
        covered[q[np.concatenate(hit)]] = True
        on = np.nonzero(S.loop == lp)[0]
        if len(on):
            on = on[np.argsort(S.s[on])]
            k = np.searchsorted(S.s[on], sq)
            # the curvature-centre event of each self sample's run (its node's point)
            runs = sorted(
                (e for e in evs if e.kind is NodeKind.CURVATURE_CENTRE and e.s_hi >= e.s_lo),
                key=lambda e: e.s_lo,
            )
            run_lo = np.array([e.s_lo for e in runs])
            run_hi = np.array([e.s_hi for e in runs])
            run_pt = np.array([e.point for e in runs]).reshape(-1, 2)
            for nb in (on[k % len(on)], on[(k - 1) % len(on)]):
                # only where that disk is the node's own: the centre of the self sample's
                # run, else its own centre (a curvature centre ~10 tol from the branch
                # point, at a flat maximum between two of its feet, swallowed both feet:
                # the branch between them was lost; at 4 tol, one self sample's centre
                # was within the merge radius of the node while its run's was not)
                centre = S.centre[nb].copy()
                if len(runs):
                    j = np.searchsorted(run_lo, S.s[nb], side="right") - 1
                    inside = (j >= 0) & (S.s[nb] <= run_hi[np.maximum(j, 0)])
                    centre[inside] = run_pt[j[inside]]
                near = np.linalg.norm(centre - node_pt[q], axis=1) <= radius
                covered[q] |= S.is_self[nb] & near
    # a foot on an arc whose centre is the node (within the merge radius) is any point of
    # the arc, and ill-conditioned: the arc's curvature-centre event at the node stands
    # for it (a foot placed by the last digits of a tie cut the spoke from that centre
    # to a nearly flat convex corner beside the arc; its fit never converged)
    centres = [g for g in events if g.kind is NodeKind.CURVATURE_CENTRE]
    arc = np.nonzero(~covered & (C.kind[el] == CIRCLE))[0]
    if len(arc) and centres:
        at = np.linalg.norm(C.circ_c[C.pos[el[arc]]] - node_pt[arc], axis=1) <= radius
        for i in arc[at]:
            covered[i] = any(
                g.loop == loops[i] and np.linalg.norm(g.point - node_pt[i]) <= radius
                for g in centres
            )
    added: list[_Event] = []
    for i in np.nonzero(~covered)[0]:
        e, k = feet[i]
        own = [e.feet[k]] + [g for j, g in enumerate(e.feet) if j != k]
        s_i = float(np.mod(s_foot[i], tr.L[loops[i]]))
        added.append(_Event(int(loops[i]), s_i, s_i, NodeKind.BRANCH_POINT, e.point, e.radius, own))
    # one event per uncovered foot even where several events of its branch point name it
    kept: list[_Event] = []
    for ev in sorted(added, key=lambda e: (e.loop, e.s_lo)):
        if not any(
            k.loop == ev.loop
            and abs(k.s_lo - ev.s_lo) <= width
            and np.linalg.norm(k.point - ev.point) <= radius
            for k in kept[-8:]
        ):
            kept.append(ev)
    return events + kept


def _covering(
    sq: FloatArray,
    node_pt: FloatArray,
    row: IntArray,
    ev: IntArray,
    spans: tuple[FloatArray, FloatArray, FloatArray],
    width: float,
    radius: float,
) -> IntArray:
    """The feet (``row``: foot at loop coordinate ``sq`` of a node at ``node_pt``) that
    event ``ev`` (``spans``: its start, end and point) covers."""
    lo, hi, pts = spans
    ok = (
        (lo[ev] <= sq[row] + width)
        & (hi[ev] >= sq[row] - width)
        & (np.linalg.norm(pts[ev] - node_pt[row], axis=1) <= radius)
    )
    return np.asarray(row[ok])


def _find(parent: list[int], i: int) -> int:
    """The root of ``i`` in a union-find forest (path halving)."""
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


def _merge_nodes(events: list[_Event], radius: float) -> int:
    """Number the events' nodes: events within ``radius`` of each other, or branch
    points touching the boundary at the same points (:func:`_same_feet`, up to 100
    ``radius`` apart), are one node, at their mean point and radius. Returns the count."""
    pts = np.array([e.point for e in events]) if events else np.zeros((0, 2))
    parent = list(range(len(events)))

    def find(i: int) -> int:
        return _find(parent, i)

    if len(events) > 1:
        tree = cKDTree(pts)
        for i, j in tree.query_pairs(radius):
            parent[find(i)] = find(j)
        # one disk found from two of its feet: next to a nearly flat convex corner (turn
        # a) the centre moves ~2/a times faster than the feet beside the corner, and the
        # branch point where the corner's spoke ends, solved from either side, landed
        # 6 tol apart along the spoke (1.5e-4 rad) with the same feet to 1e-7; at 5e-5
        # rad more than 10 tol apart (the node is their mean: an open accuracy point)
        near = tree.query_pairs(100.0 * radius, output_type="ndarray")
        for i, j in near[_same_feet(events, near, radius)]:
            parent[find(int(i))] = find(int(j))
    roots: dict[int, int] = {}
    for i, e in enumerate(events):
        e.node = roots.setdefault(find(i), len(roots))
    if not events:
        return 0
    # every event of a node carries the node's point and radius (branches end exactly
    # there): the mean of its events', or a convex vertex's own (r = 0)
    n = len(roots)
    lab = np.array([e.node for e in events], dtype=np.int64)
    count = np.bincount(lab, minlength=n)
    rad = np.array([e.radius for e in events])
    pt = np.zeros((n, 2))
    np.add.at(pt, lab, pts)
    pt /= count[:, None]
    r = np.bincount(lab, weights=rad, minlength=n) / count
    for i, e in enumerate(events):
        if e.kind is NodeKind.CONVEX_VERTEX and count[lab[i]] > 1:
            pt[lab[i]], r[lab[i]] = e.point, 0.0
            count[lab[i]] = -count[lab[i]]  # the first corner rules
    count = np.abs(count)
    dist = np.linalg.norm(pts - pt[lab], axis=1)
    spread = np.zeros(n)
    np.maximum.at(spread, lab, dist)
    for i in np.nonzero(count[lab] > 1)[0]:
        e, k = events[i], lab[i]
        e.point, e.radius = pt[k], float(r[k])
        e.spread = max(e.spread, float(spread[k]))
    return n


def _same_feet(events: list[_Event], pairs: IntArray, radius: float) -> BoolArray:
    """For each pair of events ``(i, j)``, whether both are branch points touching the
    boundary at the same points (each foot within ``radius`` of one of the other's,
    three feet or more each)."""
    out = np.zeros(len(pairs), dtype=bool)
    count = np.array(
        [len(e.feet) if e.kind is NodeKind.BRANCH_POINT else 0 for e in events], dtype=np.int64
    )
    if len(pairs) == 0:
        return out
    k = count[pairs[:, 0]]
    for n in np.unique(k[(k >= 3) & (k == count[pairs[:, 1]])]):
        sel = np.nonzero((k == n) & (count[pairs[:, 1]] == n))[0]
        ids = np.unique(pairs[sel])
        feet = np.array([[f[2] for f in events[i].feet] for i in ids])  # (m, n, 2)
        fa = feet[np.searchsorted(ids, pairs[sel, 0])]
        fb = feet[np.searchsorted(ids, pairs[sel, 1])]
        gap = np.linalg.norm(fa[:, :, None, :] - fb[:, None, :, :], axis=3)
        out[sel] = np.all(gap.min(axis=2) <= radius, axis=1) & np.all(
            gap.min(axis=1) <= radius, axis=1
        )
    return out


@dataclass
class _Interval:
    loop: int
    start: _Event | None
    end: _Event | None
    samples: IntArray  # indices into S, in loop order


def _span(a: _Event, b: _Event, length: float) -> tuple[float, float]:
    """Start and extent on the loop of the stretch from event ``a`` to event ``b``."""
    span = (b.s_lo - a.s_hi) % length
    if a is b and span == 0.0:
        span = length
    return a.s_hi, span


@dataclass
class _LoopTable:
    """Where each loop's intervals start on the loop coordinate (for lookups)."""

    first: int  # index of the loop's first interval in the interval list
    starts: FloatArray  # loop coordinate where each interval starts (sorted)
    spans: FloatArray  # extent of each interval
    closed: bool  # a loop without events: one closed interval


def _intervals(
    S: MapSamples, events: list[_Event], L: FloatArray
) -> tuple[list[_Interval], dict[int, _LoopTable]]:
    """Cut every loop at its events; the samples between two events form an interval."""
    out: list[_Interval] = []
    tables: dict[int, _LoopTable] = {}
    for lp in range(len(L)):
        idx = np.nonzero((S.loop == lp) & ~S.is_self)[0]
        evs = sorted((e for e in events if e.loop == lp), key=lambda e: e.s_lo)
        if not evs:
            if len(idx):
                tables[lp] = _LoopTable(len(out), np.zeros(1), np.array([L[lp]]), True)
                out.append(_Interval(lp, None, None, idx[np.argsort(S.s[idx])]))
            continue
        pairs = list(zip(evs, evs[1:] + evs[:1], strict=True))
        starts = np.array([a.s_hi for a, _ in pairs])
        spans = np.array([_span(a, b, L[lp])[1] for a, b in pairs])
        tables[lp] = _LoopTable(len(out), starts, spans, False)
        k, off = _locate(tables[lp], S.s[idx], L[lp])
        ok = k >= 0
        idx, k, off = idx[ok], k[ok], off[ok]
        order = np.lexsort((off, k))
        idx, k = idx[order], k[order]
        bounds = np.searchsorted(k, np.arange(len(pairs) + 1))
        for j, (a, b) in enumerate(pairs):
            out.append(_Interval(lp, a, b, idx[bounds[j] : bounds[j + 1]]))
    return out, tables


def _locate(table: _LoopTable, s: FloatArray, length: float) -> tuple[IntArray, FloatArray]:
    """Interval (index within the loop, or -1 inside an event) and offset of each ``s``."""
    if table.closed:
        return np.zeros(len(s), dtype=np.int64), np.mod(s, length)
    # an event spanning the loop's seam starts its interval at a small coordinate:
    # the starts are cyclically but not numerically ordered
    order = np.argsort(table.starts, kind="stable")
    k = np.searchsorted(table.starts[order], np.mod(s, length), side="right") - 1
    k = order[np.where(k < 0, len(order) - 1, k)]
    off = np.mod(s - table.starts[k], length)
    return np.where(off <= table.spans[k], k, -1), off


def trace_medial_graph(boundary: Boundary, frame: Frame, settings: TraceSettings) -> MedialGraph:
    """Compute the medial graph of the boundary (see module docstring)."""
    tr = _Tracer(boundary, settings)
    S = tr.eval(*_initial_samples(boundary, settings.spacing))
    loop, s = _near_flat_corners(boundary, settings, S)
    if len(s):
        S = MapSamples.concat([S, tr.eval(loop, s)])
    graph, S, used = _converge(tr, frame, S, settings.max_fit_rounds)
    # end points no step of the samples saw are looked for in the converged graph: with
    # a cluster across their disks, then (for those still missing) at the exact point
    # across; a graph is taken only if it has more of them, the last one kept if the
    # rounds after the samples run out or fail
    for exact in (False, True):
        missing = tr.missing_centres(_curvature_ends(graph))
        if len(missing[1]) == 0:
            break
        extra = tr.missing_ends(missing, S, exact)
        if extra is None:
            continue
        try:
            found, S_found, more = _converge(
                tr, frame, MapSamples.concat([S, extra]), settings.max_fit_rounds - used
            )
        except ComputationError:
            continue
        if len(tr.missing_centres(_curvature_ends(found))[1]) < len(missing[1]):
            graph, S, used = found, S_found, used + more
    return graph


def _curvature_ends(graph: MedialGraph) -> list[FloatArray]:
    return [n.point_2d for n in graph.nodes if n.kind is NodeKind.CURVATURE_CENTRE]


def _converge(
    tr: _Tracer, frame: Frame, S: MapSamples, rounds: int
) -> tuple[MedialGraph, MapSamples, int]:
    """Refine the samples, round by round, until the branches fit within the tolerance
    and no interval is left empty: ``(graph, samples, rounds used)``. Raises
    :class:`ComputationError` when ``rounds`` are not enough or a round fails."""
    settings = tr.cfg
    tol = settings.tol
    merge = max(tol, 10 * settings.eps_s)
    for used in range(1, rounds + 1):
        S, events = _resolved_events(tr, S)
        intervals, tables = _intervals(S, events, tr.L)
        twin = _twins(S, intervals, tables, tr.L)
        flat = _unresolved_corners(intervals, twin)
        if flat:
            events = [e for e in events if all(e is not f for f in flat)]
            intervals, tables = _intervals(S, events, tr.L)
            twin = _twins(S, intervals, tables, tr.L)
        n_nodes = _merge_nodes(events, merge)
        intervals = _retarget_corner_ends(S, intervals, events, merge)
        kept = _thin(S, _dedupe(S, intervals, twin, tol), _THIN_GAP * tol, _THIN_CAP * tol)
        added = _missing_fit(tr, S, kept, tol) + _fill_empty(tr, kept, intervals)
        if not added:
            graph = _assemble(tr, frame, tol, S, events, n_nodes, kept)
            _check_topology(graph, len(tr.L))
            _check_disks(tr.b, graph, tol)
            return graph, S, used
        S = MapSamples.concat([S, *added])
    raise ComputationError("the medial axis did not reach the tolerance")


def _resolved_events(tr: _Tracer, S: MapSamples) -> tuple[MapSamples, list[_Event]]:
    """Refine the samples until their events are isolated, and complete the events'
    footpoints."""
    S, events, ok = tr.resolve(S)
    if not ok:
        raise ComputationError("medial axis events did not converge")
    # a boundary element holds a few events (its branch points, corners, curvature
    # ends); thousands per element are noise (an ill-conditioned joint), and pairing
    # their feet would cost quadratic memory
    n_el = len(tr.b.elements)
    if len(events) > 50 * n_el + 500:
        raise ComputationError(
            f"the medial axis found {len(events)} events on {n_el} "
            "boundary elements: the boundary is ill-conditioned at the tolerance"
        )
    tol = tr.cfg.tol
    return S, _complete_feet(tr, S, events, tol, max(tol, 10 * tr.cfg.eps_s))


def _check_topology(graph: MedialGraph, loops: int) -> None:
    """The medial axis of a face is homotopy equivalent to it: connected, with one
    independent cycle per hole. A graph that is not was traced wrong somewhere (seen at
    nearly flat convex corners at both ends of a fillet, below the sample spacing): an
    error, not a wrong answer."""
    components, cycles = _rank(len(graph.nodes), graph.branches)
    if (components, cycles) != (1, loops - 1):
        raise ComputationError(
            f"the medial graph has {components} components and {cycles} cycles, not 1 and "
            f"{loops - 1}: it was traced wrong (nearly flat corners below the sample spacing?)"
        )


_DISK_ERROR = 3.0
"""Tolerances a branch's disk may reach out of the face, or fall short of its boundary,
before the graph is refused (the 45 fixture profiles' disks reach out by 0.85 tol at
most; over a test run's 413 graphs, out by 1.1 and short by 0.55 tol at most; the
oracles allow 2)."""


def _check_disks(boundary: Boundary, graph: MedialGraph, tol: float) -> None:
    """Every branch's disks lie in the face and touch its boundary
    (:mod:`medialcad.mat2d.selfcheck`). A branch fitted through a wrong sample swings
    between its samples: a spoke of a nearly flat convex corner at a closed spline's
    seam went 944 tol out of the face and passed the topology check; a branch beside a
    weak curvature maximum ran through disks 3,000 tol short of the boundary. An error,
    not a wrong answer."""
    error, at = disk_error(boundary, graph.branches)
    if error > _DISK_ERROR * tol:
        raise ComputationError(
            f"the medial axis fails its own check: a disk centred at ({at[0]:.6g}, "
            f"{at[1]:.6g}) of the face plane is {error / tol:.3g} tol off the face's "
            "boundary (traced wrong)"
        )


def _rank(n_nodes: int, branches: Sequence[Branch]) -> tuple[int, int]:
    """``(connected components, independent cycles)`` of the graph of ``n_nodes`` nodes
    and ``branches``; a closed branch is a component and a cycle of its own."""
    parent = list(range(n_nodes))
    components, cycles = n_nodes, 0
    for b in branches:
        if b.start is None or b.end is None:  # a closed loop of its own
            components += 1
            cycles += 1
            continue
        a, c = _find(parent, b.start), _find(parent, b.end)
        if a == c:
            cycles += 1
        else:
            parent[a] = c
            components -= 1
    return components, cycles


def _twins(
    S: MapSamples, intervals: list[_Interval], tables: dict[int, _LoopTable], L: FloatArray
) -> IntArray:
    """For each interval, the interval its middle sample's partner lies in (-1: none).
    Where that partner lies inside an event (a sample right next to a branch point has
    its partner at the branch point's other foot), the samples either side of the middle
    and then the end samples are asked in turn."""
    twin = np.full(len(intervals), -1, dtype=np.int64)
    count = np.array([len(iv.samples) for iv in intervals])
    for rank in range(4):
        pos = [count // 2, (count - 1) // 2, np.zeros_like(count), count - 1][rank]
        ask = np.nonzero((twin < 0) & (count > 0))[0]
        if rank and len(ask) == 0:
            break
        mids = np.array([intervals[i].samples[pos[i]] for i in ask], dtype=np.int64)
        if len(mids) == 0:
            break
        p_loop, p_s = S.partner_loop[mids], S.partner_s[mids]
        for lp, table in tables.items():
            sel = np.nonzero(p_loop == lp)[0]
            if len(sel):
                k, _ = _locate(table, p_s[sel], L[lp])
                twin[ask[sel]] = np.where(k >= 0, table.first + k, -1)
    return twin


def _unresolved_corners(intervals: list[_Interval], twin: IntArray) -> list[_Event]:
    """Convex corners whose two sides map into one partner interval: the corner is so
    flat that its spoke's branch point is below the tolerance; it is a smooth join."""
    out = []
    starting: dict[int, int] = {}
    for k, other in enumerate(intervals):
        if other.start is not None:
            starting.setdefault(id(other.start), k)
    for i, iv in enumerate(intervals):
        if iv.end is None or iv.end.kind is not NodeKind.CONVEX_VERTEX:
            continue
        j = starting.get(id(iv.end), -1)
        if j >= 0 and twin[i] >= 0 and twin[i] == twin[j]:
            out.append(iv.end)
    return out


def _retarget_corner_ends(
    S: MapSamples, intervals: list[_Interval], events: list[_Event], radius: float
) -> list[_Interval]:
    """An interval that ends at a convex corner while its end sample's disk is large and
    its centre sits on another node ends at that node. Next to a nearly flat convex
    corner (1e-5 rad, a fillet meeting a line off tangent) the spoke's feet lie closer to
    the corner than any sample, so the event where the branch meets the spoke is not
    found and the branch was drawn on to the corner, 0.5 diag through the face."""
    if not intervals or not events:
        return intervals
    node_of: dict[int, _Event] = {}
    for e in events:
        if e.kind is not NodeKind.CONVEX_VERTEX:
            node_of.setdefault(e.node, e)
    if not node_of:
        return intervals
    ids = list(node_of)
    tree = cKDTree(np.array([node_of[k].point for k in ids]))
    # every (interval, end) at a convex corner, asked at once
    asks: list[tuple[int, int, int]] = []  # (interval, 0 start / 1 end, sample)
    corners: list[FloatArray] = []
    for i, iv in enumerate(intervals):
        if len(iv.samples):
            for s, ev, j in ((0, iv.start, iv.samples[0]), (1, iv.end, iv.samples[-1])):
                if ev is not None and ev.kind is NodeKind.CONVEX_VERTEX:
                    asks.append((i, s, int(j)))
                    corners.append(ev.point)
    if not asks:
        return intervals
    which, side, smp = (np.array(col, dtype=np.int64) for col in zip(*asks, strict=True))
    corner = np.array(corners)
    c = S.centre[smp]
    far = (np.linalg.norm(c - corner, axis=1) > 10 * radius) & (S.radius[smp] > 10 * radius)
    out = list(intervals)
    if not np.any(far):
        return out
    d, k = tree.query(c[far])
    for i, s, dd, kk in zip(which[far], side[far], d, k, strict=True):
        if dd <= radius:
            iv = out[i]
            node = node_of[ids[int(kk)]]
            out[i] = dataclasses.replace(iv, **({"start": node} if s == 0 else {"end": node}))
    return out


def _dedupe(
    S: MapSamples, intervals: list[_Interval], twin: IntArray, tol: float
) -> list[_Interval]:
    """Keep one of the two sides of every branch (the interval with the lower index, or
    the side whose end events sit where its end samples' centres lead: see
    :func:`_end_miss`)."""
    by_nodes: dict[tuple[int, int], list[int]] = {}
    for k, other in enumerate(intervals):
        if other.start is not None and other.end is not None:
            by_nodes.setdefault((other.start.node, other.end.node), []).append(k)
    kept: list[_Interval] = []
    for i, iv in enumerate(intervals):
        if len(iv.samples) == 0:
            # no sample between two distinct nodes: only the lower side keeps it
            distinct = iv.start is not None and iv.end is not None and iv.start.node != iv.end.node
            if distinct and _lower_side(i, intervals, by_nodes):
                kept.append(iv)
            continue
        j = twin[i]
        if j < 0 or j == i:
            kept.append(iv)
            continue
        a, b = _nodes(iv)
        if (
            twin[j] != i
            and a is not None
            and b is not None
            and a != b
            and iv.start is not None
            and iv.end is not None
            and NodeKind.CURVATURE_CENTRE in (iv.start.kind, iv.end.kind)  # no parallel branch
            and set(_nodes(intervals[j])) != {a, b}
        ):
            # its twin is a side of another branch (the one sample between a branch
            # point and a curvature centre 3 tol away had its partner across the disk):
            # the first of the intervals with samples between its nodes is the branch
            between = by_nodes.get((a, b), []) + by_nodes.get((b, a), [])
            if i == min(k for k in between if len(intervals[k].samples)):
                kept.append(iv)
            continue
        lower = i < j
        if twin[j] == i and len(intervals[j].samples) and _nodes(iv) != _nodes(intervals[j])[::-1]:
            # the two sides disagree on the branch's nodes: one of them missed an event
            # (a nearly flat convex corner whose spoke's feet lie closer to it than the
            # samples: the side along the corner ended at the corner, 0.5 off its samples)
            mi, mj = _end_miss(S, iv), _end_miss(S, intervals[j])
            if max(mi, mj) > 10 * tol + 4 * min(mi, mj):
                lower = mi < mj
        if lower:
            kept.append(iv)
    return kept


def _nodes(iv: _Interval) -> tuple[int | None, int | None]:
    return (
        iv.start.node if iv.start is not None else None,
        iv.end.node if iv.end is not None else None,
    )


def _end_miss(S: MapSamples, iv: _Interval) -> float:
    """How far the interval's end events lie from the centres of its end samples."""
    c = S.centre
    miss = 0.0
    if iv.start is not None:
        miss = max(miss, float(np.linalg.norm(c[iv.samples[0]] - iv.start.point)))
    if iv.end is not None:
        miss = max(miss, float(np.linalg.norm(c[iv.samples[-1]] - iv.end.point)))
    return miss


def _lower_side(
    i: int, intervals: list[_Interval], by_nodes: dict[tuple[int, int], list[int]]
) -> bool:
    """Whether the empty interval ``i`` is the side of its branch that is kept: no
    interval runs back between its nodes, or only an empty one of higher index does."""
    iv = intervals[i]
    assert iv.start is not None and iv.end is not None
    back = [k for k in by_nodes.get((iv.end.node, iv.start.node), []) if k != i]
    if not back:
        return True
    return i < back[0] if len(intervals[back[0]].samples) == 0 else False


_THIN_GAP = 1e-2  # samples closer than this many tol to the one before them are dropped
_THIN_CAP = 0.5  # ... and those within 3 spreads of a merged node, at most this many tol


def _node_reach(ev: _Event | None, gap: float, cap: float) -> float:
    """How far round a branch's end node :func:`_thin` drops its samples."""
    if ev is None:
        return 0.0
    return max(gap, min(cap, 3.0 * ev.spread))


def _thin(S: MapSamples, ivs: list[_Interval], gap: float, cap: float) -> list[_Interval]:
    """Drop samples closer than ``gap`` to the point before them (the bisection that
    isolates an event leaves clusters of them next to its node; interpolating through
    near-coincident points would make the spline oscillate), and samples inside a node
    merged from several nearby events (within 3 times their spread, at most ``cap``): the
    tiny branches between nearly coincident branch points (a slightly perturbed regular
    polygon) would kink the spline there. All intervals at once."""
    counts = np.array([len(iv.samples) for iv in ivs], dtype=np.int64)
    if counts.sum() == 0:
        return list(ivs)
    smp = np.concatenate([iv.samples for iv in ivs]).astype(np.int64)
    group = np.repeat(np.arange(len(ivs)), counts)
    first = np.concatenate([[0], np.cumsum(counts)[:-1]])
    c = S.centre[smp]
    prev = np.empty_like(c)
    prev[1:] = c[:-1]
    far = np.zeros((len(ivs), 2))
    near = np.zeros((len(ivs), 2))  # (start, end) radius around each end node
    start_pt, end_pt = np.zeros((len(ivs), 2)), np.zeros((len(ivs), 2))
    closed = np.zeros(len(ivs), dtype=bool)
    for k, iv in enumerate(ivs):
        if counts[k] == 0:
            continue
        if iv.start is None:
            closed[k] = True
            far[k] = c[first[k] + counts[k] - 1]
        else:
            far[k] = iv.start.point
            start_pt[k] = iv.start.point
            if iv.start.spread > 0:
                near[k, 0] = _node_reach(iv.start, gap, cap)
        if iv.end is not None:
            end_pt[k] = iv.end.point
            near[k, 1] = _node_reach(iv.end, gap, cap)
    has = counts > 0
    prev[first[has]] = far[has]
    keep = np.linalg.norm(c - prev, axis=1) >= gap
    keep[first[has & closed]] = True
    keep &= np.linalg.norm(c - start_pt[group], axis=1) >= near[group, 0]
    keep &= np.linalg.norm(c - end_pt[group], axis=1) >= near[group, 1]
    out = []
    for k, iv in enumerate(ivs):
        sl = slice(first[k], first[k] + counts[k])
        out.append(_Interval(iv.loop, iv.start, iv.end, iv.samples[keep[sl]]))
    return out


def _branch_arrays(S: MapSamples, iv: _Interval) -> tuple[FloatArray, FloatArray]:
    pts = [S.centre[iv.samples]]
    rad = [S.radius[iv.samples]]
    if iv.start is not None:
        pts.insert(0, iv.start.point[None, :])
        rad.insert(0, np.array([iv.start.radius]))
    if iv.end is not None:
        pts.append(iv.end.point[None, :])
        rad.append(np.array([iv.end.radius]))
    if iv.start is None:  # closed loop
        pts.append(S.centre[iv.samples[:1]])
        rad.append(S.radius[iv.samples[:1]])
    return np.vstack(pts), np.concatenate(rad)


@dataclass(frozen=True)
class _FitCheck:
    """A fitted branch and the exact midpoints it must pass within the tolerance."""

    key: tuple[int, float, float, int]
    loop: int
    spline: Spline
    mids: FloatArray  # loop coordinates of the check points
    lo: FloatArray  # the step holding each check point: its start and width (loop
    width: FloatArray  # coordinate) and the spline parameters of its two samples
    ua: FloatArray
    ub: FloatArray
    # the merged end nodes and how far round them the fit is not checked
    ends: tuple[tuple[FloatArray, float], ...] = ()


def _fit_check(tr: _Tracer, S: MapSamples, iv: _Interval) -> _FitCheck | None:
    """The spline through the interval's samples and the midpoints to check it at
    (None when there is nothing to check)."""
    if len(iv.samples) == 0:
        return None
    key = (
        iv.loop,
        iv.start.s_hi if iv.start is not None else -1.0,
        iv.end.s_lo if iv.end is not None else -1.0,
        len(iv.samples),
    )
    if key in tr.fit_ok:
        return None
    if _straight(tr, S, iv.samples):
        tr.fit_ok.add(key)
        return None
    length = tr.L[iv.loop]
    s = S.s[iv.samples]
    if iv.start is None:
        s_ext = np.concatenate([s, [s[0] + length]])
    else:
        assert iv.end is not None
        s_ext = np.concatenate([[iv.start.s_hi], s, [iv.end.s_lo]])
    d = np.diff(s_ext) % length
    ok = d > 4 * tr.cfg.eps_s
    if not np.any(ok):
        tr.fit_ok.add(key)
        return None
    pts, rad = _branch_arrays(S, iv)
    spline = tr.fit(np.column_stack([pts, rad]))
    u = _knots_of(pts)
    # a step over which a footpoint passes to the next element holds a joint where the
    # branch is only C1 (its curvature jumps): the interpolating spline can pass its
    # midpoint and still swing out beside it, so it is checked at its quarters too
    own, other = S.element[iv.samples], S.partner_element[iv.samples]
    change = (own[1:] != own[:-1]) | (other[1:] != other[:-1])
    if iv.start is None:
        joint = np.concatenate([change, [own[-1] != own[0] or other[-1] != other[0]]])
    else:
        joint = np.concatenate([[False], change, [False]])
    lo, width, ua, ub = s_ext[:-1][ok], d[ok], u[:-1][ok], u[1:][ok]
    frac = np.where(joint[ok][:, None], _QUARTERS, 0.5)
    first = np.ones_like(frac, dtype=bool)
    first[:, 1:] = joint[ok][:, None]
    rows = np.nonzero(first)[0]
    mids = (lo[:, None] + width[:, None] * frac)[first]
    # round a node merged from several events (3 spreads, at most the merge radius) the
    # node's own displacement rules the fit, not the check points; a chain of events
    # merged one to the next can lie farther than the merge radius from the node's
    # point, and the branch's last step, bent from its own event (up to a spread away)
    # to that point, is not checked within two spreads either
    tol = tr.cfg.tol
    merge = max(tol, 10 * tr.cfg.eps_s)
    ends = tuple(
        (ev.point, max(_node_reach(ev, _THIN_GAP * tol, merge), 2.0 * ev.spread))
        for ev in (iv.start, iv.end)
        if ev is not None and ev.spread > 0
    )
    return _FitCheck(key, iv.loop, spline, mids, lo[rows], width[rows], ua[rows], ub[rows], ends)


def _straight(tr: _Tracer, S: MapSamples, smp: IntArray) -> bool:
    """Whether every sample of a branch is equidistant from the same two lines: its
    centres lie on their bisector and the radius is linear along it, which the
    interpolating spline reproduces exactly (nothing to check)."""
    own, other = S.element[smp], S.partner_element[smp]
    if np.any(own != own[0]) or np.any(other != other[0]) or np.any(S.is_self[smp]):
        return False
    kind = tr.cands.kind
    return bool(kind[own[0]] == LINE and other[0] >= 0 and kind[other[0]] == LINE)


def _spline_miss(c: _FitCheck, centre: FloatArray, radius: FloatArray, ok: float) -> FloatArray:
    """How far the spline misses each exact check point ``(centre, radius)``: the distance
    to its projection on the spline between the two samples around it (the nearest of 17
    points, refined by Newton steps within the grid cells beside it) and the radius error
    there. The projection alone would let a spline that strays between sparse samples pass
    wherever it comes back near the exact point (0.1 diag between sparse samples of a
    free-form profile); a spline is also failed, with the step's chord as its miss, where
    its point at the parameter the chord lengths predict for the exact point, or any of
    its 17 points, lies farther than an eighth of the chord from the exact polyline
    through the two samples and the check point. Check points whose nearest grid point is
    already within ``ok`` skip the Newton steps (the projection is no farther)."""
    n = len(c.mids)
    grid = np.linspace(0.0, 1.0, 17)
    uu = c.ua[:, None] + (c.ub - c.ua)[:, None] * grid[None, :]
    cur = c.spline(uu.ravel()).reshape(n, 17, -1)
    xy = cur[..., :2]
    dist = np.linalg.norm(xy - centre[:, None, :], axis=2)
    j = np.argmin(dist, axis=1)
    r = np.arange(n)
    miss = np.maximum(dist[r, j], np.abs(cur[r, j, 2] - radius))
    far = np.nonzero(miss > ok)[0]
    if len(far):
        jf, cf = j[far], centre[far]
        lo, hi = uu[far, np.maximum(jf - 1, 0)], uu[far, np.minimum(jf + 1, 16)]
        u = uu[far, jf]
        d1, d2 = c.spline.derivative(1), c.spline.derivative(2)
        assert d1 is not None  # fitted splines have degree >= 1
        for _ in range(3):
            e = c.spline(u)[:, :2] - cf
            v1 = d1(u)[:, :2]
            v2 = d2(u)[:, :2] if d2 is not None else np.zeros_like(v1)
            g = np.einsum("ij,ij->i", e, v1)
            h = np.einsum("ij,ij->i", v1, v1) + np.einsum("ij,ij->i", e, v2)
            with np.errstate(divide="ignore", invalid="ignore"):
                step = np.where(h > 0, -g / h, 0.0)
            u = np.clip(u + np.nan_to_num(step), lo, hi)
        p = c.spline(u)
        proj = np.maximum(np.linalg.norm(p[:, :2] - cf, axis=1), np.abs(p[:, 2] - radius[far]))
        miss[far] = np.minimum(miss[far], proj)
    # the drift and stray guards
    a, b = xy[:, 0], xy[:, -1]
    la = np.linalg.norm(centre - a, axis=1)
    lb = np.linalg.norm(b - centre, axis=1)
    chord = la + lb
    with np.errstate(divide="ignore", invalid="ignore"):
        ustar = c.ua + (c.ub - c.ua) * np.where(chord > 0, la / chord, 0.5)
    drift = np.linalg.norm(c.spline(ustar)[:, :2] - centre, axis=1)
    band = np.minimum(
        _to_segment(xy, a[:, None, :], centre[:, None, :]),
        _to_segment(xy, centre[:, None, :], b[:, None, :]),
    ).max(axis=1)
    stray = np.maximum(drift, band) > 0.125 * chord
    return np.where(stray, np.maximum(miss, chord), miss)


def _to_segment(p: FloatArray, a: FloatArray, b: FloatArray) -> FloatArray:
    """Distance from points ``p (..., 2)`` to the segments ``a``-``b`` (broadcast)."""
    ab = b - a
    ll = np.einsum("...j,...j->...", ab, ab)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(ll > 0, np.einsum("...j,...j->...", p - a, ab) / ll, 0.0)
    t = np.clip(t, 0.0, 1.0)
    return np.asarray(np.linalg.norm(p - (a + t[..., None] * ab), axis=-1))


def _missing_fit(tr: _Tracer, S: MapSamples, kept: list[_Interval], tol: float) -> list[MapSamples]:
    """Samples in the steps whose exact midpoints the fitted splines miss by more than
    tol/2 (all branches' midpoints are evaluated at once). A step is split in ``k``
    equal parts, ``k = (4 e / tol)^(1/2)`` (2 to 8) for a miss ``e``: the ``h^2`` error
    of an interpolating cubic next to a joint where the branch's curvature jumps (the
    ``h^4`` of a smooth stretch would ask fewer), so a wide miss takes one round of
    refitting, not several."""
    checks = [c for c in (_fit_check(tr, S, iv) for iv in kept) if c is not None]
    if not checks:
        return []
    loops = np.concatenate([np.full(len(c.mids), c.loop, dtype=np.int64) for c in checks])
    centre, radius, is_self = tr.eval_cached(loops, np.concatenate([c.mids for c in checks]))
    add_loop: list[IntArray] = []
    add_s: list[FloatArray] = []
    k = 0
    for c in checks:
        sl = slice(k, k + len(c.mids))
        k += len(c.mids)
        miss = _spline_miss(c, centre[sl], radius[sl], 0.5 * tol)
        bad = (miss > 0.5 * tol) & ~is_self[sl]
        # (next to a curvature-centre end point: the end point rules there; round a node
        # merged from several events its spread does: samples within 3 spreads of it are
        # thinned, and a check point there asked for the same samples round after round)
        for point, reach in c.ends:
            bad &= np.linalg.norm(centre[sl] - point, axis=1) >= reach
        if not np.any(bad):
            tr.fit_ok.add(c.key)
            continue
        parts = np.clip(np.ceil((4.0 * miss[bad] / tol) ** 0.5), 2, _MAX_PARTS).astype(np.int64)
        lo, width = c.lo[bad], c.width[bad]
        j = np.arange(1, _MAX_PARTS)
        frac = j[None, :] / parts[:, None]
        take = j[None, :] < parts[:, None]
        new_s = np.unique((lo[:, None] + width[:, None] * frac)[take])
        add_loop.append(np.full(len(new_s), c.loop, dtype=np.int64))
        add_s.append(new_s)
    if not add_s:  # (every added array is non-empty)
        return []
    return [tr.eval(np.concatenate(add_loop), np.concatenate(add_s))]


_QUARTERS = np.array([0.5, 0.25, 0.75])  # check points of a step over a joint
_MAX_PARTS = 8  # most parts a step missed by its spline is split into in one round


def _fill_empty(tr: _Tracer, kept: list[_Interval], intervals: list[_Interval]) -> list[MapSamples]:
    """Samples inside intervals that have none: a quarter, half and three quarters of the
    way, once per interval.

    - kept intervals between two distinct nodes: a short branch between nearby branch
      points, whose events are solved exactly and whose bracketing samples hug the nodes;
    - any interval from a branch point back to the same node (between two of its feet):
      the boundary stretch between them lies outside the node's disk and may hold a
      branch of its own (a flat curvature maximum 0.0012 wide beside a blob's branch
      point, between two samples: its branch, ~10 tol long to the centre of curvature,
      was missing, and a thin extrusion's mid sheet did not close); the samples there
      find its events, or are the node's own disk (an arc of it) and add nothing;
    - intervals between distinct nodes that were not kept: the two halves of such a
      stretch, from the branch point to the curvature centre and back, are each
      other's twins and empty (taking kept intervals only lost that branch again)."""
    loops: list[int] = []
    ss: list[float] = []
    for iv in (*kept, *intervals):
        if len(iv.samples) or iv.start is None or iv.end is None:
            continue
        if iv.start.node == iv.end.node and (
            iv.start is iv.end or iv.start.kind is not NodeKind.BRANCH_POINT
        ):
            continue
        a, span = _span(iv.start, iv.end, tr.L[iv.loop])
        key = (iv.loop, float(a), float(span), -1)
        if span <= 4 * tr.cfg.eps_s or key in tr.fit_ok:
            continue
        tr.fit_ok.add(key)
        loops += [iv.loop] * 3
        ss += [a + span * f for f in (0.25, 0.5, 0.75)]
    return [tr.eval(np.array(loops, dtype=np.int64), np.array(ss))] if ss else []


def _knots_of(pts: FloatArray) -> FloatArray:
    d = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    u = np.concatenate([[0.0], np.cumsum(d)])
    return u / u[-1] if u[-1] > 0 else np.linspace(0, 1, len(pts))


def _assemble(
    tr: _Tracer,
    frame: Frame,
    tol: float,
    S: MapSamples,
    events: list[_Event],
    n_nodes: int,
    kept: list[_Interval],
) -> MedialGraph:
    boundary = tr.b
    elements = tuple(
        BoundaryElement(
            e.index,
            ElementKind.REFLEX_VERTEX if e.is_vertex else ElementKind.EDGE,
            e.loop,
            e.piece.edge_index if e.piece is not None else _prev_edge(boundary, e.index),
            e.vertex,
        )
        for e in boundary.elements
    )
    groups: dict[int, list[_Event]] = {}
    for ev in events:
        groups.setdefault(ev.node, []).append(ev)
    nodes: list[Node] = []
    for ni in range(n_nodes):
        evs = groups[ni]
        kinds = {e.kind for e in evs}
        kind = (
            NodeKind.BRANCH_POINT
            if NodeKind.BRANCH_POINT in kinds
            else NodeKind.CONVEX_VERTEX
            if NodeKind.CONVEX_VERTEX in kinds
            else NodeKind.CURVATURE_CENTRE
        )
        pt = evs[0].point if len(evs) == 1 else np.mean([e.point for e in evs], axis=0)
        r = evs[0].radius if len(evs) == 1 else float(np.mean([e.radius for e in evs]))
        feet: list[Footpoint] = []
        xy: list[tuple[float, float]] = []
        for e in evs:
            for el, par, fp in e.feet:
                # one foot per element within tol (events of one node found it apart);
                # feet on distinct elements are distinct (a nearly flat corner's spoke
                # touches both its sides closer than tol), unless they coincide
                x, y = float(fp[0]), float(fp[1])
                if all(
                    math.hypot(x - q[0], y - q[1])
                    > (tol if _one_foot(tr, f.element, el) else 1e-6 * tol)
                    for f, q in zip(feet, xy, strict=True)
                ):
                    feet.append(Footpoint(el, par, np.asarray(fp, dtype=float)))
                    xy.append((x, y))
        nodes.append(Node(ni, kind, pt, frame.to_3d(pt), r, tuple(feet)))
    degree = np.zeros(n_nodes, dtype=np.int64)
    for iv in kept:
        for end in (iv.start, iv.end):
            if end is not None:
                degree[end.node] += 1
    nodes = _one_contact(boundary, nodes, events, degree, tol)
    branches: list[Branch] = []
    stray: list[float] = []  # how far each branch's end events' own feet are from the node's
    for iv in kept:
        pts, rad = _branch_arrays(S, iv)
        if iv.start is not None and iv.end is not None and iv.start.node == iv.end.node:
            node = nodes[iv.start.node]
            extent = np.linalg.norm(pts - node.point_2d, axis=1).max()
            # a degenerate stretch between events of one node; or a loop that cannot
            # enclose a hole (it would reach past the node's empty disk): a stretch of a
            # branch beside the node whose end event merged into it (next to a nearly
            # flat convex corner by a fillet, where the whole arc maps into 1e-9 of the line)
            if extent <= max(4 * tol, 0.5 * node.radius):
                continue
        values = np.column_stack([pts, rad])
        if len(iv.samples) and _straight(tr, S, iv.samples):
            # collinear, radius linear along the line, chord-length parameters
            # proportional to arc length: the cubic through all the points is the line
            coeffs = (1 - _THIRDS) * values[0] + _THIRDS * values[-1]
            spline = Spline(np.repeat([0.0, 1.0], 4), coeffs, 3)
        else:
            spline = tr.fit(values)
        smp = iv.samples
        a_el, a_par, a_pt = S.element[smp], S.param[smp], S.foot[smp]
        b_el, b_par, b_pt = S.partner_element[smp], S.partner_param[smp], S.partner_point[smp]
        cols: list[tuple] = [(a_el, a_par, a_pt, b_el, b_par, b_pt)]
        if iv.start is not None:
            cols.insert(0, _pad(0, S, smp, iv.start, nodes[iv.start.node].footpoints, iv.end))
        if iv.end is not None:
            cols.append(_pad(-1, S, smp, iv.end, nodes[iv.end.node].footpoints, iv.start))
        if iv.start is None:  # closed loop: back to the first sample
            cols.append(tuple(x[:1] for x in cols[0]))
        a_el, a_par, a_pt, b_el, b_par, b_pt = (
            np.concatenate([c[k] for c in cols]) for k in range(6)
        )
        stray.append(
            max(_stray(ev, nodes[ev.node]) for ev in (iv.start, iv.end) if ev is not None)
            if iv.start is not None
            else 0.0
        )
        branches.append(
            Branch(
                len(branches),
                iv.start.node if iv.start is not None else None,
                iv.end.node if iv.end is not None else None,
                pts,
                rad,
                a_el.astype(np.int64),
                a_par,
                a_pt,
                b_el.astype(np.int64),
                b_par,
                b_pt,
                spline,
            )
        )
    branches = _drop_parallel(len(nodes), branches, stray, len(tr.L), tol)
    nodes, branches = _drop_stray_ends(nodes, branches)
    branches = _exact_pockets(tr, nodes, branches, tol)
    return MedialGraph(frame, tol, tuple(nodes), tuple(branches), elements)


def _one_contact(
    boundary: Boundary, nodes: list[Node], events: list[_Event], degree: IntArray, tol: float
) -> list[Node]:
    """A branch point's feet next to each other on one edge, with the edge between them
    within tol of its disk and no other node's foot between them, are one contact (the
    disk of a branch point beside a nearly circular stretch, found by jumps at several
    places along it): the foot most of its events name is kept. Branches then end on
    the same feet (a second pair 7e-5 apart gave the pocket branch there twice, a cycle).
    A branch point that ends a single branch (``degree`` 1: a flat arc seen as many feet,
    whose fan the 3D sheets are built from) keeps all its feet."""
    by_el: dict[int, list[float]] = {}
    for nd in nodes:
        for f in nd.footpoints:
            by_el.setdefault(f.element, []).append(f.param)
    votes: dict[tuple[int, float], int] = {}
    for ev in events:
        for el, par, _ in ev.feet:
            votes[(int(el), float(par))] = votes.get((int(el), float(par)), 0) + 1
    out: list[Node] = []
    for nd in nodes:
        if nd.kind is not NodeKind.BRANCH_POINT or len(nd.footpoints) <= 3 or degree[nd.index] < 2:
            out.append(nd)
            continue
        drop: set[int] = set()
        order = sorted(
            range(len(nd.footpoints)),
            key=lambda k: (nd.footpoints[k].element, nd.footpoints[k].param),
        )
        for i, j in itertools.pairwise(order):
            f, g = nd.footpoints[i], nd.footpoints[j]
            e = boundary.elements[f.element]
            if g.element != f.element or e.piece is None:
                continue
            lo, hi = f.param, g.param
            if any(lo < t < hi for t in by_el[f.element] if t not in (lo, hi)):
                continue
            pts = e.piece.curve.point(np.linspace(lo, hi, 17))
            dev = np.abs(np.linalg.norm(pts - nd.point_2d, axis=1) - nd.radius)
            if dev.max() > tol:
                continue
            vf = votes.get((f.element, float(f.param)), 0)
            vg = votes.get((g.element, float(g.param)), 0)
            drop.add(j if vf >= vg else i)
        feet = tuple(f for k, f in enumerate(nd.footpoints) if k not in drop)
        out.append(dataclasses.replace(nd, footpoints=feet) if drop else nd)
    return out


def _exact_pockets(
    tr: _Tracer, nodes: list[Node], branches: list[Branch], tol: float
) -> list[Branch]:
    """Short branches from a branch point into a flat curvature maximum between two of
    its feet get exact rows solved from the boundary stretch
    (:func:`~medialcad.mat2d.pocket.pocket_rows`): their samples osculate, and the spline
    through the few there are was 3.8 tol off the bent branch."""
    degree = np.zeros(len(nodes), dtype=np.int64)
    for b in branches:
        for n in (b.start, b.end):
            if n is not None:
                degree[n] += 1
    out: list[Branch] = []
    for b in branches:
        rows = None
        if b.start is not None and b.end is not None and b.start != b.end:
            first, last = nodes[b.start], nodes[b.end]
            bp, cc = (first, last) if first.kind is NodeKind.BRANCH_POINT else (last, first)
            if (
                bp.kind is NodeKind.BRANCH_POINT
                and cc.kind is NodeKind.CURVATURE_CENTRE
                and degree[bp.index] >= 2
                and np.linalg.norm(np.diff(b.points_2d, axis=0), axis=1).sum()
                <= POCKET_LENGTH * tol
            ):
                rows = pocket_rows(tr.b, bp, cc, tol)
        if rows is None:
            out.append(b)
            continue
        order = slice(None, None, -1) if bp is first else slice(None)
        centre, radius = rows.centre[order], rows.radius[order]
        sides = [
            (rows.param_a[order], rows.foot_a[order]),
            (rows.param_b[order], rows.foot_b[order]),
        ]
        # side a keeps the branch's own side a (its foot at the branch point)
        k = -1 if bp is last else 0
        if abs(b.foot_a_param[k] - sides[1][0][k]) < abs(b.foot_a_param[k] - sides[0][0][k]):
            sides.reverse()
        el = np.full(len(centre), rows.element, dtype=np.int64)
        spline = tr.fit(np.column_stack([centre, radius]))
        (pa, fa), (pb, fb) = sides
        out.append(dataclasses.replace(
            b, points_2d=centre, radius=radius, foot_a_element=el, foot_a_param=pa,
            foot_a_point=fa, foot_b_element=el.copy(), foot_b_param=pb, foot_b_point=fb,
            spline=spline,
        ))  # fmt: skip
    return out


def _stray(ev: _Event, node: Node) -> float:
    """How far the event's own foot is from the nearest of its node's feet on its element
    (0 where the node has none there)."""
    el, _, fp = ev.feet[0]
    d = [
        float(np.linalg.norm(f.point_2d - np.asarray(fp)))
        for f in node.footpoints
        if f.element == el
    ]
    return min(d) if d else 0.0


def _drop_parallel(
    n_nodes: int, branches: list[Branch], stray: list[float], loops: int, tol: float
) -> list[Branch]:
    """Drop one of two branches joining the same two nodes along the same path, where the
    graph has more cycles than the face has holes.

    A cycle of the medial axis encloses a hole, whose boundary stays at least the radius
    away from every medial point on the cycle: two branches that never part by more than
    half their radius enclose none; they are one branch traced twice from two feet of a
    branch point that touches a nearly circular stretch (within tol of its disk along
    3e-3 of a blob's boundary: the disk found by jumps at four places on the stretch). The
    branch that ends at the node's own feet (``stray``: how far its end events' feet are
    from them; the other one's samples were tangent at a foot merged away, 12 tol
    unsound), then the one with more samples, is kept."""
    if _rank(n_nodes, branches)[1] <= loops - 1:
        return branches
    drop: set[int] = set()
    by_ends: dict[tuple[int, int], list[Branch]] = {}
    for b in branches:
        if b.start is not None and b.end is not None and b.start != b.end:
            by_ends.setdefault((min(b.start, b.end), max(b.start, b.end)), []).append(b)
    for group in by_ends.values():
        group = sorted(group, key=lambda b: (round(stray[b.index] / tol, 1), -len(b.points_2d)))
        for i, keep in enumerate(group):
            if keep.index in drop:
                continue
            for other in group[i + 1 :]:
                if other.index not in drop and _beside(other, keep):
                    drop.add(other.index)
    if not drop:
        return branches
    kept = [b for b in branches if b.index not in drop]
    return [dataclasses.replace(b, index=k) for k, b in enumerate(kept)]


def _beside(b: Branch, other: Branch) -> bool:
    """Whether every point of ``b`` is within half its radius of ``other``'s polyline
    (densified: at least 64 points)."""
    q = other.points_2d
    if len(q) < 64:
        t = np.linspace(0.0, len(q) - 1.0, 64)
        i = np.minimum(t.astype(np.int64), len(q) - 2)
        q = q[i] + (t - i)[:, None] * (q[i + 1] - q[i])
    d, _ = cKDTree(q).query(b.points_2d)
    spacing = float(np.linalg.norm(np.diff(q, axis=0), axis=1).max())
    return bool(np.all(d <= 0.5 * b.radius + spacing))


def _drop_stray_ends(nodes: list[Node], branches: list[Branch]) -> tuple[list[Node], list[Branch]]:
    """Drop curvature-centre nodes that no branch reaches, unless there is no branch at all
    (a disk: its MAT is that one point). The medial axis is connected, so such a node is a
    spurious self-partner event (seen once in thousands of random B-spline blobs: a node
    0.006 diag off the axis next to a branch point, the branches all sound)."""
    if not branches:
        return nodes, branches
    used = {n for b in branches for n in (b.start, b.end) if n is not None}
    keep = [n for n in nodes if n.index in used or n.kind is not NodeKind.CURVATURE_CENTRE]
    if len(keep) == len(nodes):
        return nodes, branches
    new = {n.index: k for k, n in enumerate(keep)}
    nodes = [dataclasses.replace(n, index=new[n.index]) for n in keep]
    branches = [
        dataclasses.replace(
            b,
            start=None if b.start is None else new[b.start],
            end=None if b.end is None else new[b.end],
        )
        for b in branches
    ]
    return nodes, branches


_THIRDS = np.array([[0.0], [1 / 3], [2 / 3], [1.0]])  # control points of a straight cubic


def _one_foot(tr: _Tracer, a: int, b: int) -> bool:
    """Whether feet on elements ``a`` and ``b`` within tol of each other are one foot:
    the same element, or two meeting smoothly. Feet on two sides of a convex corner are
    two (a nearly flat corner's spoke touches both closer than tol)."""
    a, b = int(a), int(b)
    if a == b:
        return True
    if a < 0 or b < 0:
        return False
    return ((a, b) if a < b else (b, a)) in tr.smooth_pairs


def _pad(
    where: int,
    S: MapSamples,
    smp: IntArray,
    ev: _Event,
    node_feet: tuple,
    other: _Event | None = None,
) -> tuple:
    """Footpoints at an end node (one row of the six foot columns): a branch point's own
    footpoints on the two sides, a convex vertex itself, otherwise the nearest sample's.
    A branch with no samples from a branch point to a curvature centre ``other`` (a flat
    maximum between two of the branch point's feet, its samples all osculating) has the
    event's own foot on one side and, on the other, the node's foot nearest the centre's
    foot: the stretch between those two feet is the branch's."""
    if (
        not len(smp)
        and ev.kind is NodeKind.BRANCH_POINT
        and other is not None
        and other.kind is NodeKind.CURVATURE_CENTRE
        and other.feet
        and len(node_feet) > 1
    ):
        el, par, fp = ev.feet[0]
        tip = np.asarray(other.feet[0][2])
        # the stretch holds the centre's foot: its other end lies farther from this foot
        # than that (never a near-copy of this foot, e.g. on the element across a corner)
        reach = float(np.linalg.norm(tip - np.asarray(fp)))
        rest = [f for f in node_feet if np.linalg.norm(f.point_2d - np.asarray(fp)) > reach]
        if rest:
            g = min(rest, key=lambda f: float(np.linalg.norm(f.point_2d - tip)))
            return (
                np.array([el]),
                np.array([par]),
                np.asarray(fp)[None, :],
                np.array([g.element]),
                np.array([g.param]),
                g.point_2d[None, :],
            )
    if len(smp):
        j = smp[0] if where == 0 else smp[-1]
        vals = (
            S.element[j : j + 1],
            S.param[j : j + 1],
            S.foot[j : j + 1],
            S.partner_element[j : j + 1],
            S.partner_param[j : j + 1],
            S.partner_point[j : j + 1],
        )
    else:
        el, par, fp = ev.feet[0]
        vals = (
            np.array([el]),
            np.array([par]),
            np.asarray(fp)[None, :],
            np.array([el]),
            np.array([par]),
            np.asarray(fp)[None, :],
        )
    if ev.kind is NodeKind.CONVEX_VERTEX:
        vals = (vals[0], vals[1], ev.point[None, :], vals[3], vals[4], ev.point[None, :])
    elif len(smp) and ev.kind is NodeKind.BRANCH_POINT:
        # the node's own footpoints (one list for all its branches, so that they end on
        # identical feet): on each side, the one on the sample's element nearest the
        # sample's foot (the nearest sample may be far from the node: the events are
        # solved exactly); the sample's own where the node has none on that element
        out_vals: list[NDArray[Any]] = list(vals)
        for k in (0, 3):
            el, pt = int(vals[k][0]), vals[k + 2][0]
            same = [f for f in node_feet if f.element == el]
            if same:
                f = min(same, key=lambda f: float(np.linalg.norm(f.point_2d - pt)))
                out_vals[k : k + 3] = [np.array([el]), np.array([f.param]), f.point_2d[None, :]]
        vals = tuple(out_vals)  # type: ignore[assignment]
    elif len(smp) and ev.kind is NodeKind.CURVATURE_CENTRE and ev.feet:
        # both sides' feet converge on the curvature maximum: the node's own foot (the
        # nearest sample's feet are apart: a revolution's level curve, ruled from them to
        # the node, hooked back at the end)
        el, par, fp = ev.feet[0]
        out_cc: list[NDArray[Any]] = list(vals)
        for k in (0, 3):
            if int(vals[k][0]) == el:
                out_cc[k : k + 3] = [np.array([el]), np.array([par]), np.asarray(fp)[None, :]]
        vals = tuple(out_cc)  # type: ignore[assignment]
    return vals


def _prev_edge(boundary: Boundary, index: int) -> int:
    for e in reversed(boundary.elements[:index]):
        if e.piece is not None:
            return e.piece.edge_index
    return -1
