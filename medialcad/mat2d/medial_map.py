"""The medial map: for a boundary point ``b`` with inward normal ``n``, the maximal disk
tangent at ``b`` and where else it touches the boundary (THEORY.md Sec. 0).

The disk centred at ``b + rho n`` with radius ``rho`` passes through a boundary point
``q`` when ``rho = f(q) = |q - b|^2 / (2 (q - b).n)``; the maximal disk has
``rho* = min_q f(q)`` over the whole boundary, together with the curvature bound
``1/k(b)`` (the limit of ``f`` as ``q -> b`` on the same curve). The minimum is solved
exactly on each candidate element: in closed form for a line, a circle or a reflex
vertex, by safeguarded Newton on ``df/dt = 0`` for any other curve (on its exact
parameterization, started from dense candidate points).

Only elements that can hold the minimum are solved: ``f(q) <= R`` exactly when ``q`` lies
in the closed disk of radius ``R`` centred at ``b + R n``. An upper bound ``R`` comes from
a shrinking-ball search on a point cloud of the boundary; the elements whose bounding
circles meet that disk are solved exactly, and a sample whose minimum exceeds ``R`` is
solved again with ``2 R``. The answer is the minimum over the whole boundary: every
element left out has ``f > R`` everywhere.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, fields, replace
from functools import cached_property

import numpy as np
from numpy.typing import NDArray
from scipy.spatial import cKDTree

from medialcad.mat2d.boundary import Boundary, Element
from medialcad.mat2d.curves import CircleCurve, LineCurve

__all__ = ["Candidates", "MapSamples", "build_candidates", "evaluate", "pair_minima"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

_CHUNK_CELLS = 3_000_000
_KNN = 16  # neighbours fetched per size class before falling back to a ball query
LINE, CIRCLE, VERTEX, GENERAL = 0, 1, 2, 3


@dataclass(frozen=True)
class Candidates:
    """What the global minimum of ``f`` is searched over.

    Lines, circles and reflex vertices are solved in closed form (their tables below);
    every other curve has dense candidate points (contiguous per element, in parameter
    order) and a Newton solve on its exact parameterization. Every element also has a
    bounding circle (indexed by KD-trees, one per size class) and points on a cloud that
    covers the boundary (for the shrinking-ball bound).
    """

    points: FloatArray  # (K, 2) candidates of general curves
    element: IntArray  # (K,)
    param: FloatArray  # (K,)
    starts: IntArray  # (G,) first candidate of each general element
    stops: IntArray  # (G,)
    general: IntArray  # (G,) element indices of general curves
    lines: IntArray  # element indices
    line_o: FloatArray
    line_d: FloatArray
    line_nu: FloatArray
    line_lo: FloatArray
    line_hi: FloatArray
    circles: IntArray
    circ_c: FloatArray
    circ_r: FloatArray
    circ_x: FloatArray
    circ_y: FloatArray
    circ_lo: FloatArray
    circ_hi: FloatArray
    vertices: IntArray
    vert_p: FloatArray
    elem_key: FloatArray  # sorted start keys of all elements (loop offset + s0)
    loop_offset: FloatArray
    spacing: float  # candidate spacing of general curves
    reflex_end: BoolArray  # (E, 2): the edge's low / high parameter end is a reflex vertex
    convex_end: BoolArray  # (E, 2): ... is a convex corner
    touch: IntArray  # (E, 2): the element met at the edge's low / high parameter end
    ring: IntArray  # (E, 4): the elements one and two before and after, along the loop
    kind: IntArray  # (E,) LINE, CIRCLE, VERTEX or GENERAL
    pos: IntArray  # (E,) row of the element in its kind's table
    el_loop: IntArray  # (E,)
    el_s0: FloatArray  # (E,)
    el_len: FloatArray  # (E,)
    el_a: FloatArray  # (E,) parameter (edge) or normal angle (vertex) at s0
    el_b: FloatArray  # (E,) ... at s0 + length
    el_start: FloatArray  # (E, 2) point at s0 (a vertex: the vertex)
    el_end: FloatArray  # (E, 2) point at s0 + length
    bound_c: FloatArray  # (E, 2) bounding circle of each element
    bound_h: FloatArray  # (E,)
    trees: tuple[tuple[cKDTree, IntArray, float], ...]  # (tree of centres, ids, largest h)
    cloud: cKDTree  # points on the boundary, for the shrinking-ball bound
    diag: float


@dataclass(frozen=True)
class MapSamples:
    """Struct of arrays: the medial map evaluated at boundary samples."""

    loop: IntArray
    s: FloatArray
    element: IntArray
    param: FloatArray
    foot: FloatArray  # (n, 2) boundary point b
    normal: FloatArray  # (n, 2)
    radius: FloatArray  # rho*
    partner_element: IntArray  # -1 when the disk is the osculating one (self)
    partner_param: FloatArray
    partner_point: FloatArray  # (n, 2)
    partner_loop: IntArray
    partner_s: FloatArray
    is_self: BoolArray  # rho* = 1/k(b): the centre of curvature is the medial point

    @cached_property
    def centre(self) -> FloatArray:
        return np.asarray(self.foot + self.radius[:, None] * self.normal)

    def __len__(self) -> int:
        return len(self.s)

    def take(self, idx: IntArray | BoolArray) -> MapSamples:
        return MapSamples(**{f.name: getattr(self, f.name)[idx] for f in fields(MapSamples)})

    @staticmethod
    def concat(parts: list[MapSamples]) -> MapSamples:
        return MapSamples(
            **{
                f.name: np.concatenate([getattr(p, f.name) for p in parts])
                for f in fields(MapSamples)
            }
        )


def _edge_params(e: Element, spacing: float) -> FloatArray:
    assert e.piece is not None
    p = e.piece
    probe = np.linspace(p.t0, p.t1, 65)
    _, d1, d2 = p.curve.derivs(probe)
    speed = np.linalg.norm(d1, axis=1)
    turn = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.maximum(speed**2, 1e-300)
    total_turn = float(np.mean(turn) * abs(p.t1 - p.t0))
    n = int(
        np.clip(max(np.ceil(e.length / spacing), np.ceil(total_turn / np.radians(4.0))), 8, 4000)
    )
    return np.linspace(p.t0, p.t1, n + 1)


def _bounding_circle(pts: FloatArray, gap: float) -> tuple[FloatArray, float]:
    """A circle holding the curve through ``pts`` whose consecutive points are joined by
    stretches no longer than ``2 gap`` (so every curve point is within ``gap`` of one)."""
    c = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
    return c, float(np.linalg.norm(pts - c, axis=1).max()) + gap


def _size_trees(
    centres: FloatArray, reach: FloatArray, diag: float
) -> tuple[tuple[cKDTree, IntArray, float], ...]:
    """KD-trees of the bounding-circle centres, one per size class (factor 4 apart), so
    that a query radius padded by the class's largest reach stays local."""
    cls = np.floor(np.log(np.maximum(reach, 1e-6 * diag) / diag) / np.log(4.0)).astype(np.int64)
    out = []
    for k in np.unique(cls):
        ids = np.nonzero(cls == k)[0].astype(np.int64)
        out.append((cKDTree(centres[ids]), ids, float(reach[ids].max())))
    return tuple(out)


def _cloud_points(e: Element, spacing: float) -> FloatArray:
    """Points on a curved element, at most ``spacing`` apart and every 10 degrees on
    arcs (line segments: :func:`_segment_cloud`)."""
    assert e.piece is not None
    c = e.piece.curve
    n = int(np.clip(np.ceil(e.length / spacing), 1, 100_000))
    if isinstance(c, CircleCurve):
        n = max(n, int(np.ceil(abs(e.piece.t1 - e.piece.t0) / np.radians(10.0))))
    return c.point(np.linspace(e.piece.t0, e.piece.t1, n + 1))


def _segment_cloud(a: FloatArray, b: FloatArray, spacing: float) -> FloatArray:
    """Points on segments ``a[i] -> b[i]``, at most ``spacing`` apart, ends included."""
    if len(a) == 0:
        return np.zeros((0, 2))
    n = np.ceil(np.linalg.norm(b - a, axis=1) / spacing).astype(np.int64).clip(1, 100_000) + 1
    seg = np.repeat(np.arange(len(a)), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    f = (np.arange(len(seg)) - first[seg]) / (n[seg] - 1)
    return np.asarray(a[seg] + f[:, None] * (b - a)[seg])


def build_candidates(boundary: Boundary, spacing: float) -> Candidates:
    """Closed-form tables for lines, circles and reflex vertices; dense candidate points
    for every other curve; bounding circles and the point cloud of every element."""
    pts: list[FloatArray] = []
    elem: list[IntArray] = []
    par: list[FloatArray] = []
    starts: list[int] = []
    stops: list[int] = []
    general: list[int] = []
    lines: list[tuple[int, FloatArray, FloatArray, FloatArray, float, float]] = []
    circles: list[tuple[int, FloatArray, float, FloatArray, FloatArray, float, float]] = []
    verts: list[tuple[int, FloatArray]] = []
    n_el = len(boundary.elements)
    kind = np.zeros(n_el, dtype=np.int64)
    pos = np.zeros(n_el, dtype=np.int64)
    el_a = np.zeros(n_el)
    el_b = np.zeros(n_el)
    bound_c = np.zeros((n_el, 2))
    bound_h = np.zeros(n_el)
    cloud: list[FloatArray] = []
    pad = 1e-9 * boundary.diag
    k = 0
    for e in boundary.elements:
        if e.piece is None:
            assert e.vertex is not None
            kind[e.index], pos[e.index] = VERTEX, len(verts)
            el_a[e.index], el_b[e.index] = e.theta0, e.theta1
            bound_c[e.index], bound_h[e.index] = e.vertex, pad
            verts.append((e.index, e.vertex))
            continue
        c = e.piece.curve
        el_a[e.index], el_b[e.index] = e.piece.t0, e.piece.t1
        lo, hi = sorted((e.piece.t0, e.piece.t1))
        sense = 1.0 if e.piece.t1 > e.piece.t0 else -1.0
        if isinstance(c, LineCurve):
            tan = sense * c.direction
            kind[e.index], pos[e.index] = LINE, len(lines)
            lines.append((e.index, c.origin, c.direction, np.array([-tan[1], tan[0]]), lo, hi))
            continue
        if isinstance(c, CircleCurve):
            kind[e.index], pos[e.index] = CIRCLE, len(circles)
            step = (hi - lo) / 36
            arc = c.point(np.linspace(lo, hi, 37))
            bound_c[e.index], bound_h[e.index] = _bounding_circle(arc, c.radius * step + pad)
            circles.append((e.index, c.center, c.radius, c.xaxis, c.yaxis, lo, hi))
            cloud.append(_cloud_points(e, spacing))
            continue
        t = _edge_params(e, spacing)
        kind[e.index], pos[e.index] = GENERAL, len(general)
        starts.append(k)
        k += len(t)
        stops.append(k)
        p = e.piece.curve.point(t)
        chord = float(np.linalg.norm(np.diff(p, axis=0), axis=1).max())
        bound_c[e.index], bound_h[e.index] = _bounding_circle(p, 2.0 * chord + pad)
        pts.append(p)
        cloud.append(p)
        elem.append(np.full(len(t), e.index))
        par.append(t)
        general.append(e.index)
    i64 = np.int64
    lengths = np.array(boundary.loop_lengths)
    offset = np.concatenate([[0.0], np.cumsum(lengths + 1.0)])[:-1]
    keys = np.array([offset[e.loop] + e.s0 for e in boundary.elements])

    def col(rows: list, i: int, width: int = 0) -> FloatArray:
        if not rows:
            return np.zeros((0, width)) if width else np.zeros(0)
        return np.array([r[i] for r in rows], dtype=float)

    touch = _touching(boundary)
    ends = _end_points(boundary)
    line_o, line_d = col(lines, 1, 2), col(lines, 2, 2)
    line_ids = np.array([r[0] for r in lines], dtype=i64)
    vert_p = col(verts, 1, 2)
    ends_lo = line_o + col(lines, 4)[:, None] * line_d
    ends_hi = line_o + col(lines, 5)[:, None] * line_d
    bound_c[line_ids] = 0.5 * (ends_lo + ends_hi)
    bound_h[line_ids] = 0.5 * np.linalg.norm(ends_hi - ends_lo, axis=1) + pad
    cloud += [vert_p, _segment_cloud(ends_lo, ends_hi, spacing)]
    return Candidates(
        points=np.vstack(pts) if pts else np.zeros((0, 2)),
        element=np.concatenate(elem).astype(i64) if elem else np.zeros(0, dtype=i64),
        param=np.concatenate(par) if par else np.zeros(0),
        starts=np.array(starts, dtype=i64),
        stops=np.array(stops, dtype=i64),
        general=np.array(general, dtype=i64),
        lines=line_ids,
        line_o=line_o,
        line_d=line_d,
        line_nu=col(lines, 3, 2),
        line_lo=col(lines, 4),
        line_hi=col(lines, 5),
        circles=np.array([r[0] for r in circles], dtype=i64),
        circ_c=col(circles, 1, 2),
        circ_r=col(circles, 2),
        circ_x=col(circles, 3, 2),
        circ_y=col(circles, 4, 2),
        circ_lo=col(circles, 5),
        circ_hi=col(circles, 6),
        vertices=np.array([r[0] for r in verts], dtype=i64),
        vert_p=vert_p,
        elem_key=keys,
        loop_offset=offset,
        spacing=spacing,
        reflex_end=_reflex_ends(boundary, touch),
        convex_end=_convex_ends(boundary),
        touch=touch,
        ring=_ring(boundary),
        kind=kind,
        pos=pos,
        el_loop=np.array([e.loop for e in boundary.elements], dtype=i64),
        el_s0=np.array([e.s0 for e in boundary.elements]),
        el_len=np.array([e.length for e in boundary.elements]),
        el_a=el_a,
        el_b=el_b,
        el_start=ends[:, 0],
        el_end=ends[:, 1],
        bound_c=bound_c,
        bound_h=bound_h,
        trees=_size_trees(bound_c, bound_h, boundary.diag),
        cloud=cKDTree(np.vstack(cloud)),
        diag=boundary.diag,
    )


def _end_points(boundary: Boundary) -> FloatArray:
    """For each element, its points at ``s0`` and ``s0 + length``, ``(E, 2, 2)``."""
    out = np.zeros((len(boundary.elements), 2, 2))
    for e in boundary.elements:
        if e.piece is None:
            assert e.vertex is not None
            out[e.index] = e.vertex
        else:
            out[e.index] = e.piece.curve.point(np.array([e.piece.t0, e.piece.t1]))
    return out


def _touching(boundary: Boundary) -> IntArray:
    """For each edge, the element it meets at its low / high parameter end."""
    els = boundary.elements
    out = np.full((len(els), 2), -1, dtype=np.int64)
    by_loop: dict[int, list[Element]] = {}
    for e in els:
        by_loop.setdefault(e.loop, []).append(e)
    for same in by_loop.values():
        for k, e in enumerate(same):
            if e.piece is None:
                continue
            before, after = same[k - 1].index, same[(k + 1) % len(same)].index
            forward = e.piece.t1 > e.piece.t0
            out[e.index] = (before, after) if forward else (after, before)
    return out


def _ring(boundary: Boundary) -> IntArray:
    """For each element, the elements one and two before and after it on its loop."""
    out = np.zeros((len(boundary.elements), 4), dtype=np.int64)
    by_loop: dict[int, list[int]] = {}
    for e in boundary.elements:
        by_loop.setdefault(e.loop, []).append(e.index)
    for ids in by_loop.values():
        a = np.array(ids, dtype=np.int64)
        out[a] = np.column_stack([np.roll(a, 1), np.roll(a, -1), np.roll(a, 2), np.roll(a, -2)])
    return out


def _reflex_ends(boundary: Boundary, touch: IntArray) -> BoolArray:
    """For each edge, whether its low / high parameter end is a reflex vertex (whose
    element owns that point: a minimum of ``f`` clamped there is the vertex's)."""
    is_vertex = np.array([e.is_vertex for e in boundary.elements] + [False])
    return np.asarray(is_vertex[touch] & (touch != np.arange(len(touch))[:, None]))


def _convex_ends(boundary: Boundary) -> BoolArray:
    """For each edge, whether its low / high parameter end is a convex corner (a joint
    turning by less than the boundary's angle tolerance is smooth: no corner there)."""
    out = np.zeros((len(boundary.elements), 2), dtype=bool)
    lengths = np.asarray(boundary.loop_lengths)
    by_loop: dict[int, FloatArray] = {}
    for lp in range(len(lengths)):
        by_loop[lp] = np.array(
            [c.s for c in boundary.corners if c.loop == lp and c.turn > 0], dtype=float
        )
    for e in boundary.elements:
        cs = by_loop[e.loop]
        if e.piece is None or len(cs) == 0:
            continue
        length = lengths[e.loop]
        for k, s in enumerate((e.s0, e.s0 + e.length)):
            d = np.remainder(cs - s + 0.5 * length, length) - 0.5 * length
            if np.any(np.abs(d) <= 1e-12 * length):
                # k = 0: the loop start of the element, its t0 end
                side = k if e.piece.t1 > e.piece.t0 else 1 - k
                out[e.index, side] = True
    return out


def _dot(a: FloatArray, b: FloatArray) -> FloatArray:
    return np.asarray(np.einsum("ij,ij->i", a, b))


def _f_values(q: FloatArray, b: FloatArray, n: FloatArray, tiny: float) -> FloatArray:
    """``f(q)`` for each pair (broadcast), ``inf`` where q is not ahead of b."""
    d = q - b
    a = np.einsum("...i,...i->...", d, d)
    bb = np.einsum("...i,...i->...", d, n)
    # q must be ahead of b by more than the coordinates' noise, or a vertex shared with
    # the neighbouring edge would pass for a partner when b is next to it
    ok = (bb > 1e-12 * np.sqrt(a)) & (bb > 10.0 * tiny) & (a > tiny * tiny)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(ok, a / (2.0 * np.where(ok, bb, 1.0)), np.inf)


def _refine_on_edge(
    e: Element, b: FloatArray, n: FloatArray, t: FloatArray, lo: FloatArray, hi: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Minimize ``f`` on the curve within ``[lo, hi]`` (safeguarded Newton on ``g = 0``,
    where ``sign(df/dt) = sign(g)``). Returns ``(t, f)``."""
    assert e.piece is not None
    curve = e.piece.curve
    t, lo, hi = t.copy(), lo.copy(), hi.copy()
    scale = abs(e.piece.t1 - e.piece.t0)
    active = np.ones(len(t), dtype=bool)
    for _ in range(60):
        idx = np.nonzero(active)[0]
        if len(idx) == 0:
            break
        p, d1, d2 = curve.derivs(t[idx])
        w = p - b[idx]
        nn = n[idx]
        wn = np.einsum("ij,ij->i", w, nn)
        wd = np.einsum("ij,ij->i", w, d1)
        ww = np.einsum("ij,ij->i", w, w)
        g = 2.0 * wd * wn - ww * np.einsum("ij,ij->i", d1, nn)
        gp = 2.0 * (np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", w, d2)) * wn - ww * (
            np.einsum("ij,ij->i", d2, nn)
        )
        hi[idx] = np.where(g > 0, t[idx], hi[idx])
        lo[idx] = np.where(g < 0, t[idx], lo[idx])
        with np.errstate(divide="ignore", invalid="ignore"):
            tn = t[idx] - g / gp
        bad = (
            ~np.isfinite(tn)
            | (gp <= 0)
            | (tn <= np.minimum(lo[idx], hi[idx]))
            | (tn >= np.maximum(lo[idx], hi[idx]))
        )
        tn = np.where(bad, 0.5 * (lo[idx] + hi[idx]), tn)
        done = (
            (np.abs(tn - t[idx]) <= 1e-15 * scale)
            | (g == 0)
            | (np.abs(hi[idx] - lo[idx]) <= 1e-15 * scale)
        )
        t[idx] = tn
        active[idx[done]] = False
    q = curve.point(t)
    return t, _f_values(q, b, n, 0.0)


_Best = tuple[FloatArray, IntArray, FloatArray]  # value, element, parameter per sample


@dataclass(frozen=True)
class _Rows:
    """The samples whose minimum is being solved (struct of arrays)."""

    b: FloatArray  # (m, 2) boundary point
    n: FloatArray  # (m, 2) inward normal
    own: IntArray  # own element
    own_param: FloatArray
    self_bound: FloatArray  # 1/k (inf where not convex)
    near: FloatArray  # partners on the own curve closer than this are self
    cut: FloatArray  # the partner solve skips this much of the own curve round b

    def take(self, idx: IntArray) -> _Rows:
        return _Rows(**{k: v[idx] for k, v in self.__dict__.items()})


def _end_values(
    f_lo: FloatArray, f_hi: FloatArray, el: IntArray, own: IntArray, C: Candidates, pen: float
) -> tuple[FloatArray, BoolArray]:
    """Value of an edge's best end, and whether it is the low end. An end at a reflex
    vertex belongs to the vertex; an end at the joint with the sample's own element is
    the sample's own curve (a gap there is no partner)."""
    f_lo = np.where(C.reflex_end[el, 0] | (C.touch[el, 0] == own), np.inf, f_lo)
    f_hi = np.where(C.reflex_end[el, 1] | (C.touch[el, 1] == own), np.inf, f_hi)
    return np.minimum(f_lo, f_hi) * (1 + 1e-12) + pen, f_lo <= f_hi


def _lines_pairs(
    C: Candidates, b: FloatArray, n: FloatArray, own: IntArray, j: IntArray, tiny: float, pen: float
) -> tuple[FloatArray, FloatArray]:
    """Closed form per (sample, line ``j``) pair: the disk tangent at ``b`` growing until
    it touches the line segment. Returns value and parameter."""
    o, d, nu = C.line_o[j], C.line_d[j], C.line_nu[j]
    h = _dot(b - o, nu)
    nn = _dot(n, nu)
    sig = np.sign(h)
    den = 1.0 - sig * nn
    with np.errstate(divide="ignore", invalid="ignore"):
        # b on the line itself (a neighbouring edge's vertex) is no tangency
        rho = np.where((den > 1e-14) & (sig * h > 10.0 * tiny), sig * h / den, np.inf)
    c = b + np.where(np.isfinite(rho), rho, 0.0)[:, None] * n
    tf = _dot(c - o, d)
    lo, hi = C.line_lo[j], C.line_hi[j]
    el = C.lines[j]
    rho, tf = _across_corner(C, b, n, own, j, el, rho, tf, tiny)
    inside = np.isfinite(rho) & (tf >= lo) & (tf <= hi)
    f_lo = _f_values(o + lo[:, None] * d, b, n, tiny)
    f_hi = _f_values(o + hi[:, None] * d, b, n, tiny)
    end_val, low = _end_values(f_lo, f_hi, el, own, C, pen)
    val = np.where(inside, rho, end_val)
    par = np.where(inside, tf, np.where(low, lo, hi))
    # a line ending at the sample's own reflex vertex lies behind every normal of it:
    # exactly no partner (the vertex can sit off the line by the joint's tolerance, and the
    # closed form then found disks of radius ~1e-8 there)
    beside = (C.kind[own] == VERTEX) & ((C.touch[el, 0] == own) | (C.touch[el, 1] == own))
    return np.where((own == el) | beside, np.inf, val), par


def _across_corner(
    C: Candidates,
    b: FloatArray,
    n: FloatArray,
    own: IntArray,
    j: IntArray,
    el: IntArray,
    rho: FloatArray,
    tf: FloatArray,
    tiny: float,
) -> tuple[FloatArray, FloatArray]:
    """The disk tangent at ``b`` and at the line across the convex corner that ends
    ``b``'s own line: by symmetry it touches the line as far from the vertex as ``b`` is,
    ``rho = |b - V| / tan(turn / 2)``. Next to a nearly flat corner the distance of ``b``
    to that line is below the noise that :func:`_lines_pairs` guards against, while the
    corner's spoke is fed by exactly those points."""
    at_lo, at_hi = C.touch[el, 0] == own, C.touch[el, 1] == own
    sel = np.nonzero((at_lo | at_hi) & (C.kind[own] == LINE))[0]
    if len(sel) == 0:
        return rho, tf
    k = j[sel]
    o, d, nu = C.line_o[k], C.line_d[k], C.line_nu[k]
    tv = np.where(at_lo[sel], C.line_lo[k], C.line_hi[k])
    dl = np.linalg.norm(d, axis=1)
    dist = np.linalg.norm(b[sel] - (o + tv[:, None] * d), axis=1)
    ns = n[sel]
    cross = np.abs(ns[:, 0] * nu[:, 1] - ns[:, 1] * nu[:, 0])
    cosv = _dot(ns, nu)
    # convex: the line lies ahead of b (its inward side holds b)
    ok = (cross > 0) & (cosv > -1.0) & (_dot(b[sel] - o, nu) > -10.0 * tiny) & (dist > 10 * tiny)
    with np.errstate(divide="ignore", invalid="ignore"):
        r_sym = dist * (1.0 + cosv) / cross
    rho, tf = rho.copy(), tf.copy()
    rho[sel] = np.where(ok, r_sym, np.inf)
    tf[sel] = np.where(ok, tv + np.where(at_lo[sel], 1.0, -1.0) * dist / dl, tf[sel])
    return rho, tf


def _circles_pairs(
    C: Candidates, b: FloatArray, n: FloatArray, own: IntArray, j: IntArray, tiny: float, pen: float
) -> tuple[FloatArray, FloatArray]:
    """Closed form per (sample, arc ``j``) pair: the disk tangent at ``b`` touching the
    circular arc. Returns value and parameter."""
    cc, r, xa, ya = C.circ_c[j], C.circ_r[j], C.circ_x[j], C.circ_y[j]
    w = b - cc
    ww = _dot(w, w)
    wn = _dot(w, n)
    inner = ww < r * r
    with np.errstate(divide="ignore", invalid="ignore"):
        rho = np.where(inner, (r * r - ww) / (2 * (wn + r)), (ww - r * r) / (2 * (r - wn)))
    on = np.abs(np.sqrt(ww) - r) <= 10.0 * tiny  # b on the same circle (another arc of it)
    rho = np.where(on, np.where(wn < 0, r, np.inf), rho)
    rho = np.where(np.isfinite(rho) & (rho > 0), rho, np.inf)
    c = b + np.where(np.isfinite(rho), rho, 0.0)[:, None] * n
    v = c - cc
    lo, hi = C.circ_lo[j], C.circ_hi[j]
    alpha = np.arctan2(_dot(v, ya), _dot(v, xa))
    a = lo + np.mod(alpha - lo, 2 * np.pi)
    inside = np.isfinite(rho) & (a <= hi)
    p_lo = cc + r[:, None] * (np.cos(lo)[:, None] * xa + np.sin(lo)[:, None] * ya)
    p_hi = cc + r[:, None] * (np.cos(hi)[:, None] * xa + np.sin(hi)[:, None] * ya)
    el = C.circles[j]
    end_val, low = _end_values(
        _f_values(p_lo, b, n, tiny), _f_values(p_hi, b, n, tiny), el, own, C, pen
    )
    val = np.where(inside, rho, end_val)
    par = np.where(inside, a, np.where(low, lo, hi))
    return np.where(own == el, np.inf, val), par


def _candidate_f(C: Candidates, g: int, b: FloatArray, n: FloatArray, tiny: float) -> FloatArray:
    """``f`` at the candidate points of general element ``g`` for each sample, ``(m, K)``."""
    q = C.points[C.starts[g] : C.stops[g]]
    return _f_values(q[None, :, :], b[:, None, :], n[:, None, :], tiny)


def _row_chunks(rows: IntArray, width: int) -> list[IntArray]:
    step = max(1, _CHUNK_CELLS // max(width, 1))
    return [rows[i : i + step] for i in range(0, len(rows), step)]


def _general_pairs(
    boundary: Boundary,
    C: Candidates,
    R: _Rows,
    rows: IntArray,
    g: IntArray,
    tiny: float,
    pen: float,
) -> _Best:
    """Free-form curves, per (sample, general element ``g``) pair: dense candidates, then
    safeguarded Newton per candidate element. Returns the best per sample."""
    m = len(R.b)
    best = np.full(m, np.inf)
    best_e = np.full(m, -1, dtype=np.int64)
    best_p = np.zeros(m)
    if len(rows) == 0:
        return best, best_e, best_p
    order = np.lexsort((rows, g))
    rows, g = rows[order], g[order]
    cut = np.flatnonzero(np.diff(g)) + 1
    groups = list(zip(np.split(rows, cut), g[np.concatenate([[0], cut])], strict=True))
    # discrete minimum per pair and per sample over all its general elements, and the
    # discrete local minima of every pair (row, candidate, value)
    fe = np.empty(len(rows))
    minima: list[tuple[IntArray, IntArray, FloatArray]] = []
    k = 0
    for rr, gi in groups:
        width = int(C.stops[gi] - C.starts[gi])
        found = []
        for part in _row_chunks(rr, width):
            fg = _candidate_f(C, int(gi), R.b[part], R.n[part], tiny)
            fe[k : k + len(part)] = fg.min(axis=1)
            found.append(_local_minima(C, int(gi), part, fg, tiny))
            k += len(part)
        minima.append(
            (
                np.concatenate([x[0] for x in found]),
                np.concatenate([x[1] for x in found]),
                np.concatenate([x[2] for x in found]),
            )
        )
    rmin = R.self_bound.copy()
    np.minimum.at(rmin, rows, fe)
    keep = (fe <= rmin[rows] * 1.25 + 1e-9 * boundary.diag) & np.isfinite(fe)
    thr = rmin * 1.25 + 1e-9 * boundary.diag
    kept = np.zeros(m, dtype=bool)
    k = 0
    for (rr, gi), (lr, lj, lf) in zip(groups, minima, strict=True):
        kept[:] = False
        kept[rr[keep[k : k + len(rr)]]] = True
        k += len(rr)
        # every discrete local minimum near the best: one curve can hold several partners
        # whose values differ by less than the sampling error (at a branch point)
        use = kept[lr] & (lf <= thr[lr])
        solves = []
        if np.any(use):
            solves.append(
                _refine_element(boundary, C, int(gi), lr[use], lj[use], lf[use], R, tiny, pen)
            )
        # and next to a joint with the sample's own element, whatever the candidates read
        sr, sj, st_ = _joint_seeds(boundary, C, int(gi), rr, R)
        if len(sr):
            solves.append(
                _refine_element(
                    boundary, C, int(gi), sr, sj, np.full(len(sr), np.inf), R, tiny, pen, st_
                )
            )
        for win, fv, t in solves:
            better = fv < best[win]
            best[win[better]] = fv[better]
            best_e[win[better]] = C.general[gi]
            best_p[win[better]] = t[better]
    return best, best_e, best_p


def _joint_seeds(
    boundary: Boundary, C: Candidates, g: int, rows: IntArray, R: _Rows
) -> tuple[IntArray, IntArray, FloatArray]:
    """Newton seeds on general element ``g`` for the samples ``rows`` whose own element
    meets it at a convex corner: ``(rows, end candidate, start parameter)``, the start as far
    from the joint along ``g`` as the sample is from it (where the spoke of a nearly
    flat convex corner finds its partner), within the candidate cell at that end.
    There the partner lies within a fraction of a cell of the joint, and the
    candidates can miss it: every one behind the sample's tangent (``f = inf``) where
    both curves bend away from it, or the first cell holding a larger maximum of ``f``
    beyond the minimum (a profile of short B-spline edges: a disk of 6.44 where the
    spoke's is 1.13, then 2.6 where it is 0.01)."""
    ei = int(C.general[g])
    piece = boundary.elements[ei].piece
    assert piece is not None
    first, last = int(C.starts[g]), int(C.stops[g]) - 1
    if last - first < 2:
        return rows[:0], rows[:0], np.zeros(0)
    increasing = piece.t1 > piece.t0
    o = R.own[rows]
    out_r, out_j, out_t = [], [], []
    # candidates run from t0 to t1; side 0 is the low parameter end
    for side, end in ((0, first if increasing else last), (1, last if increasing else first)):
        if not C.convex_end[ei, side]:
            continue  # (a smooth joint: its candidates see the partners there)
        at = np.nonzero((C.touch[ei, side] == o) & (o != ei))[0]
        if len(at) == 0:
            continue
        inner = end + 1 if end == first else end - 1
        t_end, t_in = C.param[end], C.param[inner]
        joint = piece.curve.point(np.array([t_end]))[0]
        speed = float(np.linalg.norm(piece.curve.derivs(np.array([t_end]))[1][0]))
        d = np.linalg.norm(R.b[rows[at]] - joint, axis=1) / max(speed, 1e-300)
        # (a sample farther than a cell from the joint has its partner resolved by them)
        near = d < abs(t_in - t_end)
        at, d = at[near], d[near]
        t = t_end + np.sign(t_in - t_end) * np.minimum(d, 0.5 * abs(t_in - t_end))
        out_r.append(rows[at])
        out_j.append(np.full(len(at), end - first, dtype=np.int64))
        out_t.append(t)
    if not out_r:
        return rows[:0], rows[:0], np.zeros(0)
    return np.concatenate(out_r), np.concatenate(out_j), np.concatenate(out_t)


def _local_minima(
    C: Candidates, g: int, rows: IntArray, fg: FloatArray, tiny: float
) -> tuple[IntArray, IntArray, FloatArray]:
    """Discrete local minima of ``f`` along general element ``g`` (``fg``: ``f`` at its
    candidates for samples ``rows``): row, candidate offset and value, in row order."""
    first, last = int(C.starts[g]), int(C.stops[g]) - 1
    closed = np.linalg.norm(C.points[first] - C.points[last]) <= tiny
    pad = fg[:, -2:-1] if closed else np.full((len(rows), 1), np.inf)
    left = np.concatenate([pad, fg[:, :-1]], axis=1)
    pad = fg[:, 1:2] if closed else np.full((len(rows), 1), np.inf)
    right = np.concatenate([fg[:, 1:], pad], axis=1)
    lm = (fg <= left) & (fg <= right) & np.isfinite(fg)
    if closed:
        lm[:, -1] = False  # the seam point is the first candidate too
    ri, jj = np.nonzero(lm)
    # one candidate per plateau: a run of grid values each tied with the one before it
    # to rounding, and all within rounding of each other (a stretch on the sample's
    # tangent circle, where every point is a partner: a full circle written as a NURBS
    # had ~430 "minima" per sample, each refined by Newton, 1.65 s against 0.014 s for
    # the circle)
    with np.errstate(invalid="ignore"):
        tie = np.abs(fg - left) <= _PLATEAU * np.abs(fg)
    tie[:, 0] = False
    if len(ri) == 0 or not tie.any():  # no run longer than one value: every minimum is its own
        return rows[ri], jj.astype(np.int64), fg[ri, jj]
    runs = np.cumsum(~tie, axis=1) + (fg.shape[1] + 1) * np.arange(len(fg))[:, None]
    finite = np.isfinite(fg)
    lo_run = np.full(runs.max() + 1, np.inf)
    hi_run = np.full(runs.max() + 1, -np.inf)
    np.minimum.at(lo_run, runs[finite], fg[finite])
    np.maximum.at(hi_run, runs[finite], fg[finite])
    run = runs[ri, jj]
    flat = hi_run[run] - lo_run[run] <= _PLATEAU * np.abs(lo_run[run])
    vals = fg[ri, jj]
    # a chain of ties that drifts (across a bump between two distinct minima) is no
    # plateau: each of its minima is its own candidate
    run = np.where(flat, run, -1 - np.arange(len(run)))
    order = np.lexsort((vals, run, ri))
    first = np.r_[True, (ri[order][1:] != ri[order][:-1]) | (run[order][1:] != run[order][:-1])]
    keep = np.sort(order[first])
    return rows[ri[keep]], jj[keep].astype(np.int64), vals[keep]


_PLATEAU = 1e-9
"""Relative difference below which two grid values of ``f`` tie (the values' own
rounding near the sample reaches 4e-11 on a unit circle)."""


def _refine_element(
    boundary: Boundary,
    C: Candidates,
    g: int,
    rr: IntArray,
    jj: IntArray,
    f0: FloatArray,
    R: _Rows,
    tiny: float,
    pen: float,
    start: FloatArray | None = None,
) -> tuple[IntArray, FloatArray, FloatArray]:
    """Newton on general element ``g`` from discrete local minima (sample ``rr``,
    candidate offset ``jj``, value ``f0``; by sample, then candidate), or from the
    parameters ``start`` within the cells beside those candidates. Returns the best
    per sample: rows, values, parameters."""
    b, n, own, own_param, own_cut = R.b, R.n, R.own, R.own_param, R.cut
    ei = int(C.general[g])
    e = boundary.elements[ei]
    assert e.piece is not None
    first, last = int(C.starts[g]), int(C.stops[g]) - 1
    closed = np.linalg.norm(C.points[first] - C.points[last]) <= tiny
    cj = first + jj
    lo = C.param[np.maximum(cj - 1, first)]
    hi = C.param[np.minimum(cj + 1, last)]
    t0 = C.param[cj] if start is None else start
    lo2, hi2 = np.minimum(lo, hi), np.maximum(lo, hi)
    is_own = own[rr] == ei
    span = abs(e.piece.t1 - e.piece.t0)  # a closed edge's period
    speed = np.zeros(len(rr))
    if np.any(is_own):
        speed = np.linalg.norm(e.piece.curve.derivs(own_param[rr])[1], axis=1)

    def solve(
        t0: FloatArray, lo2: FloatArray, hi2: FloatArray, sel: IntArray
    ) -> tuple[FloatArray, FloatArray]:
        """Refine rows ``sel`` from ``t0`` within ``[lo2, hi2]``, never onto the trivial
        root q = b on the own curve: a partner lies at least ``R.cut`` away
        (:func:`_own_cut`; on a closed edge, from the own point's copy nearest the
        bracket: across the seam). A bracket round b is solved on both of its sides
        (a candidate on one side of b says nothing of a partner close on the other)."""
        t0, lo2, hi2 = t0[sel], lo2[sel], hi2[sel]
        own_rows = is_own[sel]
        if not np.any(own_rows):
            return _refine_on_edge(e, b[rr[sel]], n[rr[sel]], t0, lo2, hi2)
        tb = own_param[rr[sel]]
        if closed:
            tb = tb + span * np.round((t0 - tb) / span)
        cut = np.minimum(own_cut[rr[sel]] / np.maximum(speed[sel], 1e-300), 0.5 * np.abs(t0 - tb))
        inside = own_rows & (lo2 < tb + cut) & (tb - cut < hi2)
        up, down = inside & (t0 > tb), inside & (t0 < tb)
        lo_a = np.where(up, np.maximum(lo2, tb + cut), lo2)
        hi_a = np.where(down, np.minimum(hi2, tb - cut), hi2)
        t, fv = _refine_on_edge(e, b[rr[sel]], n[rr[sel]], t0, lo_a, hi_a)
        # the other side of b, where the bracket reaches past the cut
        other = np.nonzero((up & (lo2 < tb - cut)) | (down & (hi2 > tb + cut)))[0]
        if len(other):
            # (the full cut: the clamp above only keeps t0 inside the first bracket)
            oc = own_cut[rr[sel[other]]] / np.maximum(speed[sel[other]], 1e-300)
            o_lo = np.where(up[other], lo2[other], tb[other] + oc)
            o_hi = np.where(up[other], tb[other] - oc, hi2[other])
            keep = o_lo < o_hi
            other, o_lo, o_hi = other[keep], o_lo[keep], o_hi[keep]
        if len(other):
            rows = rr[sel[other]]
            t_o, f_o = _refine_on_edge(e, b[rows], n[rows], 0.5 * (o_lo + o_hi), o_lo, o_hi)
            better = f_o < fv[other]
            t[other[better]], fv[other[better]] = t_o[better], f_o[better]
        return t, fv

    every = np.arange(len(rr))
    t, fv = solve(t0, lo2, hi2, every)
    if closed:
        # a closed edge: a minimum at its seam may lie on the other side of it
        at_seam = np.nonzero((cj == first) | (cj == last))[0]
        if len(at_seam):
            other = np.where(cj[at_seam] == first, last, first)
            olo = C.param[np.where(other == first, first, last - 1)]
            ohi = C.param[np.where(other == first, first + 1, last)]
            ot0 = np.zeros(len(rr))
            ot0[at_seam] = C.param[other]
            blo, bhi = np.array(lo2), np.array(hi2)
            blo[at_seam], bhi[at_seam] = np.minimum(olo, ohi), np.maximum(olo, ohi)
            t_b, f_b = solve(ot0, blo, bhi, at_seam)
            better = f_b < fv[at_seam]
            t[at_seam[better]] = t_b[better]
            fv[at_seam[better]] = f_b[better]
    worse = ~(fv <= f0)
    t = np.where(worse, t0, t)
    fv = np.where(worse, f0, fv)
    at_end = (np.abs(t - e.piece.t0) < 1e-12 * span) | (np.abs(t - e.piece.t1) < 1e-12 * span)
    fv = np.where(at_end, fv * (1 + 1e-12) + pen, fv)
    lo_t, hi_t = min(e.piece.t0, e.piece.t1), max(e.piece.t0, e.piece.t1)
    # a minimum clamped at the end joined to the sample's own element is that joint (the
    # own element's trivial root); a closed element's seam joins it to itself, a point
    # inside the curve like any other (a C1 seam's curvature jump: partners rest on it)
    end_lo = C.reflex_end[ei, 0] | ((C.touch[ei, 0] == own[rr]) & (own[rr] != ei))
    end_hi = C.reflex_end[ei, 1] | ((C.touch[ei, 1] == own[rr]) & (own[rr] != ei))
    at_reflex = (end_lo & (np.abs(t - lo_t) < 1e-12 * span)) | (
        end_hi & (np.abs(t - hi_t) < 1e-12 * span)
    )
    fv = np.where(at_reflex, np.inf, fv)
    if np.any(is_own):
        gap = np.abs(t - own_param[rr])
        if closed:
            gap = np.minimum(gap, np.abs(span - gap))
        fv = np.where(is_own & (gap < 1e-9 * span), np.inf, fv)
    order = np.lexsort((fv, rr))
    head = np.ones(len(order), dtype=bool)
    head[1:] = rr[order][1:] != rr[order][:-1]
    win = order[head]
    return rr[win], fv[win], t[win]


_Parts = list[tuple[IntArray, FloatArray, FloatArray, IntArray, IntArray]]


def _joint_shifts(
    C: Candidates, R: _Rows, rows: IntArray, els: IntArray
) -> tuple[IntArray, FloatArray]:
    """For each (sample, element) pair: which joint joins the sample's own element to the
    partner (0: none; 1, 2: the own element's end, start; 3, 4: the same across a reflex
    vertex between them) and the shift of ``b`` that closes that joint's gap.

    Joints are consistent only to their tolerance (~1e-8 in real files). Next to a joint
    ``f`` is ill-conditioned: a partner's end a gap ``g`` ahead of ``b`` at a distance
    ``d`` gives ``f ~ d^2 / 2g``, a spurious disk where the exact joint has none (a convex
    arc into a reflex vertex: disks of radius 1e-8..1e-3 instead of 0.7). Solving the pair
    with ``b`` moved by the gap is solving it against the partner moved onto the own
    element's end: the exact joint, with the geometry changed by no more than its gap."""
    own = R.own[rows]
    ring = C.ring[own]
    kind = C.kind
    end, start = C.el_end[own], C.el_start[own]
    b = R.b[rows]
    slot = np.zeros(len(rows), dtype=np.int64)
    shift = np.zeros((len(rows), 2))
    best = np.full(len(rows), np.inf)
    cases = (
        (ring[:, 1] == els, end, C.el_start[els]),
        (ring[:, 0] == els, start, C.el_end[els]),
        ((ring[:, 3] == els) & (kind[ring[:, 1]] == VERTEX), end, C.el_start[els]),
        ((ring[:, 2] == els) & (kind[ring[:, 0]] == VERTEX), start, C.el_end[els]),
    )
    for k, (hit, joint, other) in enumerate(cases, start=1):
        # the nearer joint where a short loop has two with the same partner
        dist = np.where(hit & (els != own), np.linalg.norm(b - joint, axis=1), np.inf)
        take = dist < best
        best = np.where(take, dist, best)
        slot[take] = k
        shift[take] = (other - joint)[take]
    return slot, shift


def _solve_pairs(
    boundary: Boundary, C: Candidates, R: _Rows, rows: IntArray, els: IntArray, tiny: float
) -> _Best:
    """The minimum of ``f`` per sample over the given (sample, element) pairs: value,
    element and parameter (ties go to lines, then arcs, vertices, general curves, and
    within a kind to the lower element index). A partner joined to the sample's own
    element is solved with that joint's gap closed (:func:`_joint_shifts`)."""
    m = len(R.b)
    pen = 1e-14 * boundary.diag  # a minimum at a segment's end loses ties
    slot, shift = _joint_shifts(C, R, rows, els)
    parts: _Parts = [(rows[:0], np.zeros(0), np.zeros(0), rows[:0], els[:0])]
    for k in np.unique(slot):
        sel = np.nonzero(slot == k)[0]
        Rk = R
        if k > 0 and np.any(shift[sel]):
            b = R.b.copy()
            b[rows[sel]] += shift[sel]  # a sample has one partner per slot
            Rk = replace(R, b=b)
        parts += _pair_values(boundary, C, Rk, rows[sel], els[sel], tiny, pen)
    r = np.concatenate([x[0] for x in parts])
    v = np.concatenate([x[1] for x in parts])
    p = np.concatenate([x[2] for x in parts])
    blk = np.concatenate([x[3] for x in parts])
    el = np.concatenate([x[4] for x in parts])
    best = np.full(m, np.inf)
    best_e = np.full(m, -1, dtype=np.int64)
    best_p = np.zeros(m)
    np.minimum.at(best, r, v)
    # among a sample's minima, the lowest (kind, element)
    tie = np.nonzero((v == best[r]) & np.isfinite(v))[0]
    rank = blk[tie] * (len(C.kind) + 1) + el[tie]
    first = np.full(m, np.iinfo(np.int64).max)
    np.minimum.at(first, r[tie], rank)
    win = tie[rank == first[r[tie]]]
    best_e[r[win]], best_p[r[win]] = el[win], p[win]
    return best, best_e, best_p


def _pair_values(
    boundary: Boundary,
    C: Candidates,
    R: _Rows,
    rows: IntArray,
    els: IntArray,
    tiny: float,
    pen: float,
) -> _Parts:
    """The minimum of ``f`` per pair by element kind: (rows, values, parameters, kind,
    elements) blocks (a general curve's: the best per sample over its pairs)."""
    kind, pos = C.kind[els], C.pos[els]
    parts: _Parts = []
    for k, fn in ((LINE, _lines_pairs), (CIRCLE, _circles_pairs)):
        sel = np.nonzero(kind == k)[0]
        if len(sel):
            r = rows[sel]
            v, p = fn(C, R.b[r], R.n[r], R.own[r], pos[sel], tiny, pen)
            parts.append((r, v, p, np.full(len(r), k), els[sel]))
    sel = np.nonzero(kind == VERTEX)[0]
    if len(sel):
        r = rows[sel]
        v = _f_values(C.vert_p[pos[sel]], R.b[r], R.n[r], tiny)
        # a reflex vertex ending the sample's own line lies on its tangent: no partner
        own, ev = R.own[r], els[sel]
        beside = (C.kind[own] == LINE) & ((C.ring[own, 0] == ev) | (C.ring[own, 1] == ev))
        v = np.where(beside, np.inf, v)
        parts.append((r, v, np.zeros(len(r)), np.full(len(r), VERTEX), els[sel]))
    sel = np.nonzero(kind == GENERAL)[0]
    gv, ge, gp = _general_pairs(boundary, C, R, rows[sel], pos[sel], tiny, pen)
    has = np.nonzero(np.isfinite(gv))[0]
    parts.append((has, gv[has], gp[has], np.full(len(has), GENERAL), ge[has]))
    return parts


def _near_elements(
    C: Candidates, centre: FloatArray, radius: FloatArray, own: IntArray
) -> tuple[IntArray, IntArray]:
    """Pairs ``(row, element)`` whose element's bounding circle meets the disk
    ``(centre[row], radius[row])``, sorted by row then element. The nearest few centres
    of each size class come from one vectorized k-NN query; the rare rows with more in
    reach are completed by a ball query."""
    rows, els = [], []
    m = len(centre)
    for tree, ids, reach in C.trees:
        k = min(_KNN, tree.n)
        d, j = tree.query(centre, k=k)
        d, j = d.reshape(m, k), j.reshape(m, k)
        within = d <= (radius + reach)[:, None]
        more = within[:, -1] if k < tree.n else np.zeros(m, dtype=bool)
        r, c = np.nonzero(within & ~more[:, None])
        rows.append(r)
        els.append(ids[j[r, c]])
        full = np.nonzero(more)[0]
        if len(full):
            hits = tree.query_ball_point(centre[full], (radius + reach)[full])
            count = np.fromiter(map(len, hits), dtype=np.int64, count=len(hits))
            flat = np.fromiter(itertools.chain.from_iterable(hits), np.int64, int(count.sum()))
            rows.append(np.repeat(full, count))
            els.append(ids[flat])
    r, j = np.concatenate(rows), np.concatenate(els)
    ok = np.linalg.norm(centre[r] - C.bound_c[j], axis=1) <= radius[r] + C.bound_h[j]
    r, j = r[ok], j[ok]
    # a line segment exactly: its points with f <= R are those in the disk. Next to the
    # tangency point (and the contact) a fine polygon hugs the disk from outside, its
    # bounding circles meet it all along (~sqrt(edges) pairs a sample, not a handful)
    line = np.nonzero(C.kind[j] == LINE)[0]
    if len(line):
        k = C.pos[j[line]]
        c = centre[r[line]]
        o, d = C.line_o[k], C.line_d[k]
        t = np.clip(_dot(c - o, d) / _dot(d, d), C.line_lo[k], C.line_hi[k])
        gap = np.linalg.norm(c - (o + t[:, None] * d), axis=1)
        rl = radius[r[line]]
        # (not a line across a corner from the sample's own element: its disk is solved by
        # symmetry about the corner, which does not see a joint's gap, and the segment
        # itself can sit off that disk by the gap)
        o_r, jl = own[r[line]], j[line]
        beside = (C.touch[jl, 0] == o_r) | (C.touch[jl, 1] == o_r)
        far = (gap > rl * (1 + 1e-9) + 1e-12 * C.diag) & ~beside
        keep = np.ones(len(r), dtype=bool)
        keep[line[far]] = False
        r, j = r[keep], j[keep]
    order = np.lexsort((j, r))
    return r[order], j[order]


def _shrinking_ball(C: Candidates, b: FloatArray, n: FloatArray, r: FloatArray) -> FloatArray:
    """An estimate of the maximal disk's radius from the boundary's point cloud: shrink
    the tangent disk at ``b`` onto the nearest cloud point inside it until none is."""
    r = r.copy()
    pts = C.cloud.data
    tiny = 1e-12 * C.diag
    active = np.arange(len(b))
    k = min(4, C.cloud.n)
    for _ in range(100):
        if len(active) == 0:
            break
        c = b[active] + r[active, None] * n[active]
        # the nearest few cloud points: the least f among those inside the disk shrinks
        # it furthest (fewer rounds than the nearest one alone)
        dist, j = C.cloud.query(c, k=k)
        dist, j = dist.reshape(len(c), k), j.reshape(len(c), k)
        ra = r[active]
        fk = _f_values(pts[j], b[active, None, :], n[active, None, :], tiny)
        fk = np.where((dist < ra[:, None] * (1 - 1e-9)) & np.isfinite(dist), fk, np.inf)
        fq = fk.min(axis=1)
        shrink = fq < ra
        r[active[shrink]] = fq[shrink]
        active = active[shrink]
    return r


def _global_min(
    boundary: Boundary, C: Candidates, R: _Rows, hint: FloatArray | None = None
) -> _Best:
    """The minimum of ``f`` over the whole boundary per sample (module docstring). A
    sample is settled once its minimum is at most ``R`` (every element that can hold a
    value ``<= R`` was solved) or ``R`` reaches the osculating radius (the disk is the
    osculating one: no partner). ``hint``: a guess of the radius (from neighbouring
    samples) where the search starts; any value is safe (a low one only costs another
    round with a doubled reach)."""
    m = len(R.b)
    tiny = 1e-12 * boundary.diag
    diag = boundary.diag
    best = np.full(m, np.inf)
    best_e = np.full(m, -1, dtype=np.int64)
    best_p = np.zeros(m)
    # an upper bound from the neighbouring elements (next to a convex corner the partner
    # is the next edge, far closer than the point cloud resolves), then the cloud's
    # (closed forms only: a general curve's solve costs as much as the main one)
    rows = np.repeat(np.arange(m), 4)
    ring = C.ring[R.own].ravel()
    cheap = C.kind[ring] != GENERAL
    local = _solve_pairs(boundary, C, R, rows[cheap], ring[cheap], tiny)[0]
    start = np.minimum(np.minimum(R.self_bound, local), 0.5 * diag) * (1 + 1e-3)
    if hint is not None:
        start = np.minimum(start, np.where(hint > 0, hint, np.inf))
    reach = _shrinking_ball(C, R.b, R.n, start) * (1 + 1e-6) + 1e-9 * diag
    active = np.arange(m)
    while len(active):
        sub = R.take(active)
        ra = reach[active]
        full = ra > 4.0 * diag  # no element ahead of b at all: solve against everything
        rows, els = _near_elements(C, sub.b + ra[:, None] * sub.n, ra, sub.own)
        if np.any(full):
            fr = np.nonzero(full)[0]
            keep = ~full[rows]
            n_el = len(C.kind)
            rows = np.concatenate([rows[keep], np.repeat(fr, n_el)])
            els = np.concatenate([els[keep], np.tile(np.arange(n_el), len(fr))])
        v, e, p = _solve_pairs(boundary, C, sub, rows, els, tiny)
        done = (v <= ra) | (ra >= sub.self_bound) | full
        idx = active[done]
        best[idx], best_e[idx], best_p[idx] = v[done], e[done], p[done]
        active = active[~done]
        reach[active] *= 2.0
    return best, best_e, best_p


def _frames(
    boundary: Boundary, C: Candidates, elem: IntArray, s: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Parameter, boundary point, inward normal and signed curvature at loop coordinate
    ``s`` on element ``elem`` (vectorized over lines, arcs and vertices)."""
    m = len(s)
    a, bb = C.el_a[elem], C.el_b[elem]
    param = a + (s - C.el_s0[elem]) / C.el_len[elem] * (bb - a)
    foot = np.empty((m, 2))
    normal = np.empty((m, 2))
    curv = np.empty(m)
    kind, pos = C.kind[elem], C.pos[elem]
    sense = np.where(bb > a, 1.0, -1.0)
    sel = np.nonzero(kind == LINE)[0]
    if len(sel):
        o, d, t = C.line_o[pos[sel]], C.line_d[pos[sel]], param[sel]
        foot[sel] = o + t[:, None] * d
        tan = sense[sel, None] * d / np.linalg.norm(d, axis=1)[:, None]
        normal[sel] = np.column_stack([-tan[:, 1], tan[:, 0]])
        curv[sel] = 0.0
    sel = np.nonzero(kind == CIRCLE)[0]
    if len(sel):
        j, t = pos[sel], param[sel][:, None]
        r, xa, ya = C.circ_r[j][:, None], C.circ_x[j], C.circ_y[j]
        c, si = np.cos(t), np.sin(t)
        foot[sel] = C.circ_c[j] + r * (c * xa + si * ya)
        d1 = r * (-si * xa + c * ya)
        d2 = -r * (c * xa + si * ya)
        speed = np.linalg.norm(d1, axis=1)
        tan = sense[sel, None] * d1 / speed[:, None]
        normal[sel] = np.column_stack([-tan[:, 1], tan[:, 0]])
        curv[sel] = sense[sel] * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / speed**3
    sel = np.nonzero(kind == VERTEX)[0]
    if len(sel):
        foot[sel] = C.vert_p[pos[sel]]
        normal[sel] = np.column_stack([np.cos(param[sel]), np.sin(param[sel])])
        curv[sel] = -np.inf  # reflex: never a curvature bound
    gen = kind == GENERAL
    for ei in np.unique(elem[gen]):
        sel = np.nonzero(elem == ei)[0]
        foot[sel], normal[sel], curv[sel] = boundary.frame_at(boundary.elements[ei], param[sel])
    return param, foot, normal, curv


def _partner_points(
    boundary: Boundary, C: Candidates, p_elem: IntArray, p_param: FloatArray, centre: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Partner parameter (a vertex's: the normal angle towards the centre), point and
    loop coordinate."""
    p_param = p_param.copy()
    point = np.empty((len(p_elem), 2))
    kind, pos = C.kind[p_elem], C.pos[p_elem]
    sel = np.nonzero(kind == VERTEX)[0]
    if len(sel):
        v = C.vert_p[pos[sel]]
        c = centre[sel] - v
        th = np.arctan2(c[:, 1], c[:, 0])
        a, bb = C.el_a[p_elem[sel]], C.el_b[p_elem[sel]]
        rel = np.mod(th - a + np.pi, 2 * np.pi) - np.pi
        p_param[sel] = a + np.clip(rel, bb - a, 0.0)
        point[sel] = v
    sel = np.nonzero(kind == LINE)[0]
    if len(sel):
        j = pos[sel]
        point[sel] = C.line_o[j] + p_param[sel][:, None] * C.line_d[j]
    sel = np.nonzero(kind == CIRCLE)[0]
    if len(sel):
        j, t = pos[sel], p_param[sel][:, None]
        point[sel] = C.circ_c[j] + C.circ_r[j][:, None] * (
            np.cos(t) * C.circ_x[j] + np.sin(t) * C.circ_y[j]
        )
    gen = kind == GENERAL
    for ei in np.unique(p_elem[gen]):
        sel = np.nonzero(p_elem == ei)[0]
        piece = boundary.elements[ei].piece
        assert piece is not None
        point[sel] = piece.curve.point(p_param[sel])
    a, bb = C.el_a[p_elem], C.el_b[p_elem]
    f = (p_param - a) / (bb - a)
    p_s = C.el_s0[p_elem] + np.clip(f, 0.0, 1.0) * C.el_len[p_elem]
    return p_param, point, p_s


def _rows_at(
    boundary: Boundary, cands: Candidates, loop: IntArray, s: FloatArray, tol: float
) -> _Rows:
    """Boundary point, normal and curvature bounds at ``(loop, s)``."""
    n_el = len(boundary.elements)
    key = cands.loop_offset[loop] + s
    elem = np.clip(np.searchsorted(cands.elem_key, key, side="right") - 1, 0, n_el - 1)
    param, foot, normal, curv = _frames(boundary, cands, elem, s)
    # the osculating disk bounds rho* (limit of f on the own curve)
    with np.errstate(divide="ignore"):
        self_bound = np.where(curv > 0, 1.0 / np.where(curv > 0, curv, 1.0), np.inf)
    rho = np.where(np.isfinite(self_bound), self_bound, 0.0)
    near = 0.5 * np.sqrt(tol * rho)
    return _Rows(
        foot,
        normal,
        elem,
        param,
        self_bound,
        near,
        _own_cut(boundary, cands, elem, s, tol, rho, near),
    )


def _own_cut(
    boundary: Boundary,
    C: Candidates,
    elem: IntArray,
    s: FloatArray,
    tol: float,
    rho: FloatArray,
    near: FloatArray,
) -> FloatArray:
    """How much of the own curve round ``b`` the partner solve skips (its trivial root
    ``q = b``). On the own curve ``f(q) ~ rho + rho' g / 3`` at arc length ``g``: no
    partner below ``rho - tol / 20`` lies closer than ``0.15 tol / |rho'|``, a third of
    that is skipped; at most ``near / 2``, at least where ``(q - b) . n`` is still a
    millionth exact (that floor rules next to the fastest maxima). ``rho'`` is the
    steeper of the one-sided slopes over ``near / 4`` either side: a maximum on a knot
    has ``rho'`` jump there, and a centred difference beside it reads ~0. Where the
    radius of curvature changes fast (a narrow curvature maximum) a fixed ``near / 2``
    skipped the partners that feed its branch."""
    cut = 0.5 * near
    gen = np.nonzero((C.kind[elem] == GENERAL) & (rho > 0))[0]
    if len(gen) == 0:
        return cut
    e = elem[gen]
    s0, length = C.el_s0[e], C.el_len[e]
    h = 0.25 * near[gen]
    lo = np.clip(s[gen] - h, s0, s0 + length)
    hi = np.clip(s[gen] + h, s0, s0 + length)
    k_lo = _frames(boundary, C, e, lo)[3]
    k_hi = _frames(boundary, C, e, hi)[3]
    r0 = rho[gen]
    with np.errstate(divide="ignore", invalid="ignore"):
        up = np.where(hi > s[gen], np.abs(1.0 / k_hi - r0) / (hi - s[gen]), 0.0)
        down = np.where(lo < s[gen], np.abs(r0 - 1.0 / k_lo) / (s[gen] - lo), 0.0)
        slope = np.where((k_lo > 0) & (k_hi > 0) & (hi > lo), np.maximum(up, down), np.inf)
        fast = 0.05 * tol / slope
    floor = np.sqrt(2e6 * np.finfo(float).eps * boundary.diag * rho[gen])
    cut[gen] = np.clip(fast, np.minimum(floor, cut[gen]), cut[gen])
    return cut


def _osculates(
    boundary: Boundary,
    C: Candidates,
    e: IntArray,
    s: FloatArray,
    p_s: FloatArray,
    p_param: FloatArray,
    centre: FloatArray,
    loop_len: FloatArray,
    tol: float,
) -> BoolArray:
    """Of samples on element ``e`` whose partner is close on the same element: whether
    the disk is the osculating one at the nearby curvature maximum, its centre within
    ``tol / 2`` of the centre of curvature at the foot, the partner or half-way (next to
    a narrow maximum the centre runs fast along the branch while the partner is still
    close). A partner resting on a closed curve's seam, a curvature jump, is taken as
    before: those disks pivot on the seam point along its normal, the branch is
    straight, and the seam's end penalty would bias their radius."""
    d = p_s - s
    d = np.where(d > 0.5 * loop_len, d - loop_len, np.where(d < -0.5 * loop_len, d + loop_len, d))
    s0, length = C.el_s0[e], C.el_len[e]
    mid = s0 + np.clip(np.mod(s + 0.5 * d - s0, loop_len), 0.0, length)
    p_in = s0 + np.clip(np.mod(p_s - s0, loop_len), 0.0, length)
    off = np.full(len(e), np.inf)
    for at in (s, mid, p_in):
        _, b_at, n_at, k_at = _frames(boundary, C, e, at)
        convex = k_at > 0
        rho = 1.0 / np.where(convex, k_at, 1.0)
        dist = np.linalg.norm(centre - (b_at + rho[:, None] * n_at), axis=1)
        off = np.minimum(off, np.where(convex, dist, np.inf))
    # (a partner at a curvature jump is a kink of f: the solve stops ~1e-7 short of it)
    a, bb = C.el_a[e], C.el_b[e]
    seam = np.minimum(np.abs(p_param - a), np.abs(p_param - bb)) <= 1e-6 * np.abs(bb - a)
    return (off <= 0.5 * tol) | seam


def evaluate(
    boundary: Boundary,
    cands: Candidates,
    loop: IntArray,
    s: FloatArray,
    tol: float,
    hint: FloatArray | None = None,
) -> MapSamples:
    """The medial map at boundary points given by ``(loop, s)``.

    A disk whose radius is within ``tol / 20`` of the osculating radius ``1/k(b)`` is
    taken to be the osculating disk (its centre is the centre of curvature). So is a disk
    whose partner is on the own curve closer than ``sqrt(tol / k) / 2`` and whose centre
    lies within ``tol / 2`` of the centre of curvature at its foot, its partner or
    half-way: the end point of the nearby curvature maximum, where its equations are
    ill-conditioned (next to a narrow maximum the centre runs fast along the branch while
    the partner is still that close: those samples feed the branch).
    Such samples are flagged ``is_self`` and only locate that end point. ``hint``: a
    guess of each radius that speeds up the search (:func:`_global_min`).
    """
    loop = np.asarray(loop, dtype=np.int64)
    s = np.asarray(s, dtype=float)
    rows = _rows_at(boundary, cands, loop, s, tol)
    foot, normal, elem, param = rows.b, rows.n, rows.own, rows.own_param
    self_bound, near = rows.self_bound, rows.near
    best, best_elem, best_param = _global_min(boundary, cands, rows, hint)

    is_self = ~(best < self_bound - 0.05 * tol)
    radius = np.where(is_self, self_bound, best)
    centre = foot + radius[:, None] * normal
    p_elem = np.where(is_self, elem, best_elem)
    p_param, p_point, p_s = _partner_points(
        boundary, cands, p_elem, np.where(is_self, param, best_param), centre
    )
    p_loop = cands.el_loop[p_elem]
    loop_len = np.asarray(boundary.loop_lengths)[loop]
    gap_s = np.abs(p_s - s)
    gap_s = np.minimum(gap_s, loop_len - gap_s)  # across the seam of a closed curve
    own_close = (p_elem == elem) & ~is_self & (gap_s < near) & np.isfinite(self_bound)
    close = np.nonzero(own_close)[0]
    if len(close):
        own_close[close] = _osculates(
            boundary, cands, elem[close], s[close], p_s[close], p_param[close],
            centre[close], loop_len[close], tol,
        )  # fmt: skip
    is_self = is_self | own_close
    return MapSamples(
        loop=loop,
        s=s,
        element=elem,
        param=param,
        foot=foot,
        normal=normal,
        radius=radius,
        partner_element=p_elem,
        partner_param=p_param,
        partner_point=p_point,
        partner_loop=p_loop,
        partner_s=p_s,
        is_self=is_self,
    )


def pair_minima(
    boundary: Boundary, cands: Candidates, loop: IntArray, s: FloatArray, elem: IntArray, tol: float
) -> FloatArray:
    """The minimum of ``f`` at each boundary point ``(loop, s)`` over one given element
    ``elem`` each: the radius of the largest disk tangent there that that element alone
    allows (``inf`` where it allows any). The same values :func:`evaluate` minimizes."""
    loop = np.asarray(loop, dtype=np.int64)
    s = np.asarray(s, dtype=float)
    rows = _rows_at(boundary, cands, loop, s, tol)
    tiny = 1e-12 * boundary.diag
    m = len(s)
    return _solve_pairs(boundary, cands, rows, np.arange(m), np.asarray(elem, np.int64), tiny)[0]
