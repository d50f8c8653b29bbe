"""Cut the 2D medial branches into segments on which the 3D sheets are single patches.

A segment is a stretch of one branch where each side's footpoint stays on one boundary
element (an edge or a reflex vertex) and, when a level ``h`` is given, where the radius
stays on one side of ``h``. Its two ends are exact: a node of the graph (with the node's
own point, radius and footpoints), the point where a footpoint passes from one element
to the next (the foot is the joint, the centre on the joint's normal line), a point
where ``r = h`` (solved on the branch's spline), or the middle of a closed branch.

Pure numpy/scipy: no OCC.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any, TypeVar

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq, minimize_scalar

from medialcad.mat2d.boundary import Boundary, EdgePiece, Element
from medialcad.mat2d.graph import Branch, MedialGraph, Node, NodeKind
from medialcad.mat2d.pocket import POCKET_LENGTH, golden_minima, pocket_rows
from medialcad.mat2d.pocket import closed_period as _closed_period

__all__ = ["End", "Segment", "distinct_rows", "foot_normals", "split_branches"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
LevelFn = Callable[[FloatArray, FloatArray], FloatArray]
TouchFn = Callable[[FloatArray, float, FloatArray, FloatArray], bool]


@dataclass(frozen=True)
class End:
    """One end of a segment.

    ``kind`` is ``"node"`` (``node`` gives the graph node), ``"pass"`` (a curvature-centre
    node more branches end at: it ends none of the medial surface), ``"transition"`` (a
    footpoint changes element), ``"level"`` (``r = h``) or ``"split"`` (cut of a closed
    branch).
    """

    kind: str
    node: int | None = None
    node_kind: NodeKind | None = None


@dataclass(frozen=True)
class Segment:
    """A piece of a branch, sampled at increasing parameters ``w`` in ``[0, 1]``.

    ``centre``, ``radius``, ``foot_a``, ``foot_b`` are exact samples (2D, face frame);
    ``element_a``/``element_b`` are the boundary elements of the two sides.
    """

    branch: int
    w: FloatArray
    centre: FloatArray
    radius: FloatArray
    foot_a: FloatArray
    foot_b: FloatArray
    element_a: int
    element_b: int
    start: End
    end: End
    single: bool = False  # one-sided: an isolated node (a disk's centre) and its whole loop


def _chord(pts: FloatArray) -> FloatArray:
    d = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    u = np.concatenate([[0.0], np.cumsum(d)])
    return u / u[-1] if u[-1] > 0 else np.linspace(0.0, 1.0, len(pts))


def _foot_on(boundary: Boundary, element: int, c: FloatArray, guess: float) -> FloatArray:
    """The nearest point to ``c`` on an element (Newton from ``guess``, clamped)."""
    return _foot_param(boundary, element, c, guess)[0]


def _foot_param(
    boundary: Boundary, element: int, c: FloatArray, guess: float
) -> tuple[FloatArray, float]:
    """Nearest point to ``c`` on an element and its parameter (a vertex: the angle)."""
    e = boundary.elements[element]
    if e.piece is None:
        assert e.vertex is not None
        d = c - e.vertex
        return np.asarray(e.vertex, dtype=float), float(np.arctan2(d[1], d[0]))
    lo, hi = sorted((e.piece.t0, e.piece.t1))
    keep = _keeper(e, lo, hi)
    t = float(keep(np.array([guess]))[0])
    for _ in range(8):
        p, d1, d2 = (a[0] for a in e.piece.curve.derivs(np.array([t])))
        g = float((p - c) @ d1)
        h = float(d1 @ d1 + (p - c) @ d2)
        if h <= 0:
            break
        step = g / h
        t = float(keep(np.array([t - step]))[0])
        if abs(step) < 1e-15 * max(1.0, abs(t)):
            break
    return np.asarray(e.piece.curve.point(np.array([t]))[0], dtype=float), t


def _keeper(e: Element, lo: float, hi: float) -> Callable[[FloatArray], FloatArray]:
    """Keeps Newton's parameters on an element: clamped to ``[lo, hi]``, or wrapped when
    the element wraps round (:func:`_wrap_span`; a closed B-spline is one element: clamping
    at its seam left the feet there stuck while the centres moved on)."""
    if _wrap_span(e) is not None:
        return lambda t: lo + np.mod(np.asarray(t, dtype=float) - lo, hi - lo)
    return lambda t: np.clip(t, lo, hi)


_Cached = TypeVar("_Cached")
_WRAP: dict[int, tuple[EdgePiece, float | None]] = {}


def _per_piece(
    cache: dict[int, tuple[EdgePiece, _Cached]],
    piece: EdgePiece,
    build: Callable[[EdgePiece], _Cached],
) -> _Cached:
    """``build(piece)``, remembered per curve piece (keyed by identity; at most 512)."""
    got = cache.get(id(piece))
    if got is None or got[0] is not piece:
        if len(cache) > 512:
            cache.clear()
        got = (piece, build(piece))
        cache[id(piece)] = got
    return got[1]


def _closed_span(piece: EdgePiece) -> float | None:
    """The parameter span of a piece closed on itself (its ends within 1e-7 of its
    size), else ``None``."""
    lo, hi = sorted((piece.t0, piece.t1))
    pts = piece.curve.point(np.linspace(lo, hi, 9))
    size = float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0)))
    closed = size > 0 and float(np.linalg.norm(pts[0] - pts[-1])) <= 1e-7 * size
    return hi - lo if closed else None


def _wrap_span(e: Element) -> float | None:
    """The parameter span over which an edge element wraps round: a whole periodic curve's
    period, or the whole span of an edge closed on itself (its ends within 1e-7 of its
    size). Other systems write a closed curve clamped, its seam a corner of ~1e-6 rad (an
    offset curve approximated by OCC: 1.09e-6), which is not read as periodic; a side's
    feet pass over that seam as over a periodic curve's. Taken the long way round, rows
    solved from the feet either side of it came out 150 tol off."""
    assert e.piece is not None
    period = _closed_period(e)
    if period is not None:
        return period
    return _per_piece(_WRAP, e.piece, _closed_span)


def _joint(
    boundary: Boundary, e_from: int, e_to: int, near: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Point and inward normal where the boundary passes between two adjacent elements;
    ``near``: a point next to the joint (the feet either side of it). A loop of two
    elements (a circle written as two arcs) joins them at both ends: the one beside the
    feet is meant (the other put the rows' feet across the circle)."""
    a, b = boundary.elements[e_from], boundary.elements[e_to]
    edge = a if a.piece is not None else b
    vert = b if edge is a else a
    if vert.vertex is not None:
        p = np.asarray(vert.vertex, dtype=float)
    else:  # two edges meeting tangentially: the end of ``a`` next to ``b``
        assert a.piece is not None and b.piece is not None
        pts = a.piece.curve.point(np.array([a.piece.t0, a.piece.t1]))
        q = b.piece.curve.point(np.array([b.piece.t0, b.piece.t1]))
        dist = np.linalg.norm(pts[:, None, :] - q[None, :, :], axis=2).min(axis=1)
        shared = dist <= dist.min() + 1e-9 * boundary.diag
        score = np.where(shared, np.linalg.norm(pts - near, axis=1), np.inf)
        p = pts[int(np.argmin(score))]
    assert edge.piece is not None
    ends = np.array([edge.piece.t0, edge.piece.t1])
    pe = edge.piece.curve.point(ends)
    gap = np.linalg.norm(pe - p, axis=1)
    # (an edge closed on a vertex meets it at both ends: the end whose inside is nearer)
    inner = edge.piece.curve.point(ends + np.array([1e-3, -1e-3]) * (ends[1] - ends[0]))
    shared = gap <= gap.min() + 1e-9 * boundary.diag
    t_end = ends[int(np.argmin(np.where(shared, np.linalg.norm(inner - near, axis=1), np.inf)))]
    _, n, _ = boundary.frame_at(edge, np.array([t_end]))
    return p, n[0]


def _degree(graph: MedialGraph, node: int) -> int:
    """How many branch ends lie at ``node``."""
    return sum((b.start == node) + (b.end == node) for b in graph.branches)


def _node_end(graph: MedialGraph, node: int | None) -> End:
    """The end of a branch at ``node`` (a closed branch's: its split). A curvature centre
    that more branches end at is a node they pass through (``"pass"``): no skeletal edge
    there, their sheets join as at a transition."""
    if node is None:
        return End("split")
    kind = _end_kind(graph, node)
    if kind is NodeKind.CURVATURE_CENTRE and _degree(graph, node) > 1:
        return End("pass", node, kind)
    return End("node", node, kind)


def _end_kind(graph: MedialGraph, node: int) -> NodeKind:
    """The node's kind as an end of a branch: a "branch point" that ends a single branch
    (a flat arc the 2D engine saw as many footpoints) is an end point, a curvature centre;
    one that two branches end at is a node they pass through, like a curvature centre
    (the third branch, shorter than the tolerance, was not traced: a seam there bounded
    their two sheets only; FreeCAD fuzz seeds 29, 106 and 112)."""
    nd = graph.nodes[node]
    if nd.kind is NodeKind.BRANCH_POINT and _degree(graph, node) <= 2:
        return NodeKind.CURVATURE_CENTRE
    return nd.kind


def split_branches(
    graph: MedialGraph,
    boundary: Boundary,
    level: float | LevelFn | None = None,
    touch: TouchFn | None = None,
) -> list[Segment]:
    """Segments of every branch of ``graph`` (see the module docstring).

    ``level`` is a radius ``h`` (cut where ``r = h``) or a function ``g(centres (n, 2),
    radii (n,)) -> (n,)`` (cut where ``g = 0``). ``touch(centre, radius, foot_a, foot_b)``
    says whether the level, at the row where it lies farthest from the branch between two
    of its crossings (``|g|`` peaks), is within the tolerance there: the branch touches
    the level at that one row (a double root split by rounding), one cut, not a sliver
    segment between two.
    """
    out: list[Segment] = []
    for b in graph.branches:
        out.extend(_split(graph, boundary, b, level, touch))
    used = {n for b in graph.branches for n in (b.start, b.end) if n is not None}
    for nd in graph.nodes:
        if nd.index not in used and nd.kind is NodeKind.CURVATURE_CENTRE:
            out.extend(_fan(graph, boundary, nd.index, None))
        elif nd.kind is NodeKind.CURVATURE_CENTRE and _degree(graph, nd.index) > 1:
            out.extend(_contact_fans(graph, boundary, nd.index))
    for nd in graph.nodes:  # (after the branches: their segments' own feet at the node)
        if nd.kind is NodeKind.BRANCH_POINT and _degree(graph, nd.index) == 2:
            out.extend(_gap_fans(graph, boundary, nd.index, out))
    return [_unswing(_dedupe(s), graph.tol) for s in out]


def _unswing(s: Segment, tol: float) -> Segment:
    """Drop the interior rows the interpolating cubic through the rows swings at.

    Every row is exact, but next to a curvature-centre end of a noisy profile (an
    approximated circle: its centre's cluster of tiny branches) rows 6e-9 apart in ``w``
    can differ by 6e-5 in centre: a kink in the parametrisation, not in the branch, and
    the cubic through them swung 1,000 units off between its neighbours (a revolved sheet
    reaching 12 diag out of the solid). A step whose interpolated midpoint lies farther
    from its chord's midpoint than both a quarter of ``tol`` and the chord itself (a
    smooth branch bends ``h^2 k / 8``, far less) is a swing; of the rows beside it, the
    one closest in ``w`` to a neighbour goes, until no step swings."""
    from scipy.interpolate import make_interp_spline

    w, vals = s.w, np.column_stack([s.centre, s.radius, s.foot_a, s.foot_b])
    groups = (slice(0, 3), slice(3, 5), slice(5, 7))
    keep = np.arange(len(w))
    for _ in range(len(w)):
        if len(keep) < 5:
            break
        ww, vv = w[keep], vals[keep]
        mid = make_interp_spline(ww, vv, k=3)(0.5 * (ww[1:] + ww[:-1]))
        chord_mid = 0.5 * (vv[1:] + vv[:-1])
        dev = np.max([np.linalg.norm(mid[:, g] - chord_mid[:, g], axis=1) for g in groups], 0)
        step = np.max([np.linalg.norm(np.diff(vv[:, g], axis=0), axis=1) for g in groups], 0)
        bad = np.nonzero((dev > 0.25 * tol) & (dev > step))[0]
        if len(bad) == 0:
            break
        j = int(bad[np.argmax(dev[bad])])
        dw = np.diff(ww)
        near = np.minimum(np.r_[np.inf, dw], np.r_[dw, np.inf])  # each row's closest gap
        lo, hi = max(j - 2, 1), min(j + 3, len(ww) - 2)  # rows beside the step, not ends
        if hi < lo:
            break
        drop = lo + int(np.argmin(near[lo : hi + 1]))
        keep = np.delete(keep, drop)
    return s if len(keep) == len(w) else _rows(s, keep)


def _dedupe(s: Segment, gap: float = 1e-9) -> Segment:
    """Drop samples closer than ``gap`` in ``w`` to their predecessor (OCC merges knots
    closer than its parametric resolution); the end samples always stay."""
    w = s.w
    keep = np.concatenate([[True], np.diff(w) > gap])
    if len(w) > 1 and not keep[-1]:
        keep[-1] = True
        j = int(np.nonzero(keep[:-1])[0][-1])
        if w[-1] - w[j] <= gap and j > 0:
            keep[j] = False
    return s if np.all(keep) else _rows(s, keep)


def _rows(s: Segment, keep: NDArray[Any]) -> Segment:
    """``s`` with only the rows ``keep`` (indices or a mask)."""
    return replace(
        s,
        w=s.w[keep],
        centre=s.centre[keep],
        radius=s.radius[keep],
        foot_a=s.foot_a[keep],
        foot_b=s.foot_b[keep],
    )


def _project(boundary: Boundary, element: int, c: FloatArray) -> tuple[FloatArray, float]:
    """Nearest point to ``c`` on an element: coarse search, then Newton."""
    e = boundary.elements[element]
    if e.piece is None:
        return _foot_param(boundary, element, c, 0.0)
    t = np.linspace(e.piece.t0, e.piece.t1, 65)
    d = np.linalg.norm(e.piece.curve.point(t) - c, axis=1)
    return _foot_param(boundary, element, c, float(t[int(np.argmin(d))]))


def _project_many(
    boundary: Boundary, element: int, cs: FloatArray, near: FloatArray | None = None
) -> FloatArray:
    """Nearest points on an element to many centres (vectorised coarse search + Newton).

    With ``near`` (points close to the wanted feet), Newton starts at the curve point
    nearest to ``near`` instead: the foot on *this* side, where a centre has two nearest
    points on one curve (an ellipse's axis, both sides of a branch on one edge)."""
    e = boundary.elements[element]
    cs = np.asarray(cs, dtype=float)
    if e.piece is None:
        return np.broadcast_to(np.asarray(e.vertex, dtype=float), cs.shape).copy()
    return np.asarray(e.piece.curve.point(_project_params(boundary, element, cs, near)))


def _project_params(
    boundary: Boundary, element: int, cs: FloatArray, near: FloatArray | None = None
) -> FloatArray:
    """The curve parameters of :func:`_project_many`'s points (an edge element); of points
    lying on the element, their own parameters."""
    e = boundary.elements[element]
    assert e.piece is not None
    cs = np.asarray(cs, dtype=float)
    lo, hi = sorted((e.piece.t0, e.piece.t1))
    keep = _keeper(e, lo, hi)
    if near is None:
        grid = np.linspace(lo, hi, 65)
        pg = e.piece.curve.point(grid)
        t = grid[np.argmin(np.linalg.norm(cs[:, None, :] - pg[None, :, :], axis=2), axis=1)]
    else:  # the curve point nearest to ``near``, on a dense grid, then a finer one
        ref = np.asarray(near, dtype=float)
        grid, tree = _dense_samples(e)
        t = grid[tree.query(ref)[1]]
        dt = (hi - lo) / (len(grid) - 1)
        fine = keep(t[:, None] + np.linspace(-dt, dt, 33)[None, :])
        pf = e.piece.curve.point(fine.ravel()).reshape(len(t), 33, 2)
        t = fine[np.arange(len(t)), np.argmin(np.linalg.norm(pf - ref[:, None, :], axis=2), axis=1)]
    for _ in range(10):
        p, d1, d2 = e.piece.curve.derivs(t)
        g = np.einsum("ij,ij->i", p - cs, d1)
        h = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", p - cs, d2)
        step = np.where(h > 0, g / np.where(h > 0, h, 1.0), 0.0)
        t = keep(t - step)
        if np.all(np.abs(step) < 1e-15 * np.maximum(1.0, np.abs(t))):
            break
    return np.asarray(t)


_DENSE: dict[int, tuple[EdgePiece, tuple[FloatArray, Any]]] = {}


def _dense_samples(e: Element) -> tuple[FloatArray, Any]:
    """Parameters of 4,097 points along an element's curve and a KD-tree of the points
    (cached per curve piece). A start for Newton taken from 65 points missed a thin
    spike of a B-spline: the sides 0.02 apart, a foot near one side started on the other
    and stayed there (a local nearest point), and that side's rim crossed over."""
    from scipy.spatial import cKDTree

    def build(piece: EdgePiece) -> tuple[FloatArray, Any]:
        lo, hi = sorted((piece.t0, piece.t1))
        grid = np.linspace(lo, hi, 4097)
        return grid, cKDTree(piece.curve.point(grid))

    assert e.piece is not None
    return _per_piece(_DENSE, e.piece, build)


def foot_normals(boundary: Boundary, element: int, feet: FloatArray) -> FloatArray | None:
    """The boundary's inward unit normals at ``feet`` (points on the edge ``element``),
    NaN at a foot that is not on it (a segment's end foot on a neighbouring element);
    ``None`` for a reflex vertex (its normals are the directions to the centres) and for
    a fan's stretch over several elements (``element < 0``)."""
    if element < 0:
        return None
    e = boundary.elements[element]
    if e.piece is None:
        return None
    t = _project_params(boundary, element, feet)
    p, n, _ = boundary.frame_at(e, t)
    n = np.array(n, dtype=float)
    scale = max(1.0, float(np.abs(feet).max(initial=0.0)))
    n[np.linalg.norm(p - feet, axis=1) > 1e-9 * scale] = np.nan
    return n


def _loop_points(boundary: Boundary, loop: int, s0: float, s1: float, step: float) -> FloatArray:
    """Boundary points on loop coordinates ``s0 -> s1`` (increasing, may pass the seam)."""
    length = boundary.loop_lengths[loop]
    marks = [s0, s1]
    for e in boundary.elements:
        if e.loop != loop:
            continue
        for k in (-1, 0, 1):
            x = e.s0 + k * length
            if s0 < x < s1:
                marks.append(x)
    marks = sorted(set(marks))
    out = []
    for a, b in itertools.pairwise(marks):
        n = max(2, int(np.ceil((b - a) / step)))
        out.append(np.linspace(a, b, n + 1)[:-1])
    ss = np.concatenate([*out, np.array([s1])])
    pts = []
    for x in ss:
        xm = x % length
        if x > s0 and abs(xm) < 1e-12 * length:
            xm = length
        e = _element_at(boundary, loop, xm, prefer_end=x > s0)
        if e.piece is None:
            pts.append(np.asarray(e.vertex, dtype=float))
        else:
            pts.append(e.piece.curve.point(np.atleast_1d(boundary.param_of(e, np.array([xm]))))[0])
    return np.array(pts)


def _element_at(boundary: Boundary, loop: int, s: float, prefer_end: bool):  # type: ignore[no-untyped-def]
    cands = [
        e
        for e in boundary.elements
        if e.loop == loop and e.s0 - 1e-12 <= s <= e.s0 + e.length + 1e-12
    ]
    cands = [e for e in cands if e.piece is not None] or cands
    return cands[-1] if not prefer_end else cands[0]


def _fan(
    graph: MedialGraph,
    boundary: Boundary,
    node: int,
    ends: tuple[tuple[int, float], tuple[int, float]] | None,
) -> list[Segment]:
    """The boundary stretch seen by a curvature-centre node as one-sided segments.

    ``ends`` are the (element, parameter) of the feet of the branch ending at the node;
    ``None`` for an isolated node (a disk): the whole loop.
    """
    nd = graph.nodes[node]
    r = nd.radius
    if ends is None:
        loop = graph.elements[nd.footpoints[0].element].loop if nd.footpoints else 0
        length = boundary.loop_lengths[loop]
        pieces = [(0.0, 0.5 * length), (0.5 * length, length)]
    else:
        (ea, pa), (eb, pb) = ends
        loop = boundary.elements[ea].loop
        length = boundary.loop_lengths[loop]
        sa = float(boundary.s_of(boundary.elements[ea], np.array([pa]))[0])
        sb = float(boundary.s_of(boundary.elements[eb], np.array([pb]))[0])
        # the fan is the stretch between the feet whose points all lie on the node's
        # circle: test the middle of both stretches (the node's own foot may be off when
        # a flat curvature maximum was located only within the tolerance)
        best: tuple[float, float, float] | None = None
        for a, z in ((sa, sb), (sb, sa)):
            span = (z - a) % length
            if span < 1e-9 * length:
                continue
            mid = _loop_points(
                boundary, loop, a + 0.5 * span - 1e-9 * length, a + 0.5 * span, length
            )
            gap = abs(float(np.linalg.norm(mid[-1] - nd.point_2d)) - r)
            if best is None or gap < best[0]:
                best = (gap, a, span)
        if best is None or best[0] > max(10.0 * graph.tol, 1e-6 * boundary.diag):
            return []
        lo, span = best[1], best[2]
        pieces = [(lo, lo + span)]
    return _fan_segments(graph, boundary, node, loop, pieces)


def distinct_rows(rows: FloatArray, gap: float) -> IntArray:
    """Indices of ``rows`` without those within ``gap`` of the previous one kept: the
    first and last rows stay (the last in place of the one before it, which must not sit
    on it either). Rows that repeat give interpolation repeated parameters: a fan's
    stretch starting 4e-12 from an element's end gave three rows 4e-12 apart, and its
    rim, interpolated on their chord length, swung 0.016 off the node's circle (a
    FreeCAD fuzz prism); a side whose feet stand still for many rows looped."""
    n = len(rows)
    keep = [0]
    for i in range(1, n):
        if float(np.linalg.norm(rows[i] - rows[keep[-1]])) > gap:
            keep.append(i)
    if keep[-1] != n - 1:  # the end row (its node or level) stays, in place of the last
        if len(keep) > 1:
            keep[-1] = n - 1
        else:
            keep.append(n - 1)
        while len(keep) > 2 and float(np.linalg.norm(rows[keep[-1]] - rows[keep[-2]])) <= gap:
            del keep[-2]
    return np.array(keep, dtype=np.int64)


def _fan_segments(
    graph: MedialGraph,
    boundary: Boundary,
    node: int,
    loop: int,
    pieces: Sequence[tuple[float, float]],
) -> list[Segment]:
    """One-sided segments of a curvature-centre node over the stretches ``pieces`` (loop
    coordinates ``s0 -> s1``) of ``loop``: the node's centre and radius on every row, the
    stretch's points as feet."""
    nd = graph.nodes[node]
    r = nd.radius
    step = r * min(0.25, (2.0 * graph.tol / max(r, 1e-300)) ** 0.25)
    end = End("node", node, _end_kind(graph, node))
    segs = []
    for s0, s1 in pieces:
        part = _loop_points(boundary, loop, s0, s1, step)
        part = part[distinct_rows(part, 1e-3 * step)]
        if (
            len(part) < 2
            or float(np.linalg.norm(part[-1] - part[0])) + float(np.ptp(part, axis=0).max())
            <= 1e-9 * boundary.diag
        ):
            continue
        w = _chord(part)
        m = len(part)
        centre = np.broadcast_to(nd.point_2d, (m, 2)).copy()
        segs.append(
            Segment(-1, w, centre, np.full(m, r), part, part.copy(), -1, -1, end, end, True)
        )
    return segs


def _on_circle(
    graph: MedialGraph, boundary: Boundary, nd: Node, e: Element, strict: bool = False
) -> bool:
    """Whether the whole edge element ``e`` lies on the disk's circle of node ``nd``:
    within ten tolerances; ``strict``: within the tolerance, and longer than a hundred
    tolerances (an element a few tolerances long lies that near any circle tangent to
    it: a fillet piece 0.018 long at a branch point's foot, FreeCAD fuzz seed 30)."""
    if e.piece is None or e.length <= 0:
        return False
    eps = max(10.0 * graph.tol, 1e-6 * boundary.diag)
    if strict and e.length <= 10.0 * eps:
        return False
    pts = e.piece.curve.point(np.linspace(e.piece.t0, e.piece.t1, 9))
    gap = np.abs(np.linalg.norm(pts - nd.point_2d, axis=1) - nd.radius).max()
    return bool(gap <= (graph.tol if strict else eps))


def _passed(graph: MedialGraph, node: int) -> bool:
    """Whether branches pass through ``node``: a curvature centre or a branch point (see
    :func:`_end_kind`) that two or more branches end at."""
    return _end_kind(graph, node) is NodeKind.CURVATURE_CENTRE and _degree(graph, node) > 1


def _gap_fans(
    graph: MedialGraph, boundary: Boundary, node: int, segments: Sequence[Segment]
) -> list[Segment]:
    """The fans of a branch point two branches pass through (:func:`_end_kind`) over the
    boundary between their segments' feet there where they differ: the node's disk
    touches that stretch whole (FreeCAD fuzz seed 106: feet 0.016 apart on either side
    of two pieces of a rounding, 1e-3 and 1e-2 long; without a fan between them the caps
    of the two branches had a crack there). Only a stretch within the tolerance of the
    disk's circle; none where the feet agree."""
    nd = graph.nodes[node]
    ends = []  # each segment's two feet at the node: (element, point)
    for sg in segments:
        if sg.single:
            continue
        for row, end in ((0, sg.start), (-1, sg.end)):
            if end.node == node and end.kind in ("node", "pass"):
                ends.append(((sg.element_a, sg.foot_a[row]), (sg.element_b, sg.foot_b[row])))
    if len(ends) != 2:
        return []
    (a1, b1), (a2, b2) = ends
    straight = np.linalg.norm(a1[1] - a2[1]) + np.linalg.norm(b1[1] - b2[1])
    crossed = np.linalg.norm(a1[1] - b2[1]) + np.linalg.norm(b1[1] - a2[1])
    pairs = [(a1, a2), (b1, b2)] if straight <= crossed else [(a1, b2), (b1, a2)]
    eps = max(10.0 * graph.tol, 1e-6 * boundary.diag)
    out: list[Segment] = []
    for (e1, p1), (e2, p2) in pairs:
        el1, el2 = boundary.elements[e1], boundary.elements[e2]
        if float(np.linalg.norm(p1 - p2)) <= 1e-9 * boundary.diag or el1.loop != el2.loop:
            continue
        loop, length = el1.loop, boundary.loop_lengths[el1.loop]
        s1 = float(boundary.s_of(el1, np.array([_project(boundary, e1, p1)[1]]))[0])
        s2 = float(boundary.s_of(el2, np.array([_project(boundary, e2, p2)[1]]))[0])
        lo, span = min((s1, (s2 - s1) % length), (s2, (s1 - s2) % length), key=lambda x: x[1])
        pts = _loop_points(boundary, loop, lo, lo + span, max(span / 16.0, 1e-300))
        if np.abs(np.linalg.norm(pts - nd.point_2d, axis=1) - nd.radius).max() > eps:
            continue
        out.extend(_fan_segments(graph, boundary, node, loop, [(lo, lo + span)]))
    return out


def _contact_fans(graph: MedialGraph, boundary: Boundary, node: int) -> list[Segment]:
    """The fans of a curvature-centre node over every stretch of the boundary its disk touches: runs of edge
    elements lying on its circle (within the tolerance), merged where they join, less
    what the node's branches sweep (:func:`_uncovered`). The disk of a node two branches
    pass through touches the boundary along stretches apart from each other (the end arc
    of a slot cut in two by the part it sticks out of: the branch from the part reaches
    the arc's centre between two fillets, the slot's own branch goes on), which no
    single branch's feet bound."""
    nd = graph.nodes[node]
    eps = max(10.0 * graph.tol, 1e-6 * boundary.diag)
    out: list[Segment] = []
    for loop, length in enumerate(boundary.loop_lengths):
        els = sorted((e for e in boundary.elements if e.loop == loop), key=lambda e: e.s0)
        on = [_on_circle(graph, boundary, nd, e) for e in els]
        if not any(on):
            continue
        if all(on):
            runs = [(0.0, 0.5 * length), (0.5 * length, length)]
        else:
            # start after an element off the circle, so that no run is cut at the seam
            k0 = on.index(False)
            runs = []
            cur: list[float] | None = None
            for i in range(1, len(els) + 1):
                j = (k0 + i) % len(els)
                e = els[j]
                s0 = e.s0 if j > k0 else e.s0 + length
                if on[j]:
                    if cur is not None and abs(s0 - cur[1]) <= 1e-9 * length:
                        cur[1] = s0 + e.length
                    else:
                        if cur is not None:
                            runs.append((cur[0], cur[1]))
                        cur = [s0, s0 + e.length]
                elif cur is not None:
                    runs.append((cur[0], cur[1]))
                    cur = None
            if cur is not None:
                runs.append((cur[0], cur[1]))
        runs = _uncovered(runs, _branch_sweeps(graph, boundary, node, loop), length, eps)
        out.extend(_fan_segments(graph, boundary, node, loop, runs))
    return out


def _branch_sweeps(
    graph: MedialGraph, boundary: Boundary, node: int, loop: int
) -> list[tuple[float, float, float]]:
    """Where the feet of the branches at ``node`` start on ``loop`` and how far they move
    along their first element: ``(s at the node, least s, greatest s)`` in loop
    coordinates. The node's foot is the one :func:`_split` gives the branch's end."""
    nd = graph.nodes[node]
    out = []
    for b in graph.branches:
        n = len(b.points_2d)
        for where, step, at in ((0, 1, b.start), (n - 1, -1, b.end)):
            if at != node:
                continue
            for els, pars in (
                (b.foot_a_element, b.foot_a_param),
                (b.foot_b_element, b.foot_b_param),
            ):
                el = int(els[where])
                e = boundary.elements[el]
                if e.piece is None or e.loop != loop:
                    continue
                feet = b.foot_a_point if els is b.foot_a_element else b.foot_b_point
                k = _settled(graph, boundary, b, where, els)
                t0 = (
                    float(pars[k])
                    if k is not None
                    else _node_foot(graph, boundary, nd, el, feet[where], float(pars[where]))[1]
                )
                run = [where if k is None else k]  # (the rows round the node: one foot)
                while 0 <= run[-1] + step < n and int(els[run[-1] + step]) == el:
                    run.append(run[-1] + step)
                s = boundary.s_of(e, np.r_[t0, pars[run[1:]]])
                out.append((float(s[0]), float(s.min()), float(s.max())))
    return out


def _uncovered(
    runs: Sequence[tuple[float, float]],
    sweeps: Sequence[tuple[float, float, float]],
    length: float,
    eps: float,
) -> list[tuple[float, float]]:
    """The contact runs cut at the branches' feet at the node, without the parts their
    feet sweep on from there. The disk of a node whose circle a branch's feet leave on
    (a branch between the node's arc and an element its disk touches at one point, the
    disk within the tolerance of crossing it: FreeCAD fuzz seeds 29 and 106) sees that
    stretch once, through the branch; a fan over it as well gave two sheets over one
    stretch, each with edges free of the other."""
    out = []
    for s0, s1 in runs:
        cuts, drop = [s0, s1], []
        for at, lo, hi in sweeps:
            shift = length * np.round((s0 - at) / length) if not s0 <= at <= s1 else 0.0
            at, lo, hi = at + shift, lo + shift, hi + shift
            if not s0 - eps <= at <= s1 + eps:
                continue
            if s0 + eps < at < s1 - eps:
                cuts.append(at)
            else:  # at an end of the run: the run is cut there already
                at = s0 if at - s0 < s1 - at else s1
            if max(hi - at, at - lo) > eps:  # the way they go (past the node's own
                # element too: a fillet shorter than eps on the circle is in the run)
                drop.append(0.5 * (at + (s1 if hi - at >= at - lo else s0)))
        cuts = sorted(cuts)
        for a, z in itertools.pairwise(cuts):
            if z - a > 1e-12 * length and not any(a < x < z for x in drop):
                out.append((a, z))
    return out


def _settled(
    graph: MedialGraph, boundary: Boundary, b: Branch, where: int, els: NDArray[np.int64]
) -> int | None:
    """For a branch whose foot on one side, at its end ``where`` at a node, is on an
    element lying whole on the node's circle: the first row (from that end) whose centre
    is more than the tolerance from the node, with its foot on that element still.

    Such a branch leaves a curvature centre within the tolerance of being a branch point
    (FreeCAD fuzz seed 29: the disk crossed another element by 6e-6) and winds round the
    node at 1e-5 while its feet sweep half the arc; the node's fan takes that sweep, the
    branch starts from the foot of that row. ``None`` for other branches."""
    node = b.start if where == 0 else b.end
    if node is None:
        return None
    nd = graph.nodes[node]
    el = int(els[where])
    if not _passed(graph, node) or not _on_circle(
        graph, boundary, nd, boundary.elements[el], strict=True
    ):
        return None
    step = 1 if where == 0 else -1
    k = where
    n = len(b.points_2d)
    while 0 <= k + step < n and int(els[k + step]) == el:
        k += step
        if float(np.linalg.norm(b.points_2d[k] - nd.point_2d)) > graph.tol:
            return k
    return None


def _node_foot(
    graph: MedialGraph, boundary: Boundary, nd: Node, element: int, foot: FloatArray, param: float
) -> tuple[FloatArray, float]:
    """A branch's foot (point, parameter) on ``element`` at its end at node ``nd``, from
    the branch's own foot there (``foot``, ``param``): at a branch point the node's
    footpoint on that element nearest to it, else the limit of the branch's feet, the
    node's nearest point on the element; a reflex vertex's own point, exactly.

    On an element lying whole on the circle of a node branches pass through
    (:func:`_passed`) every point is a foot of the node and the one the tracer gives is
    arbitrary (a branch leaving a curvature centre
    within the tolerance of being a branch point, FreeCAD fuzz seed 29, started 0.4 of
    its arc from either end, or 3e-4 from the end where the node's other foot is): the
    branch's feet sweep the element from one end, the nearer one, taken exactly."""
    el = boundary.elements[element]
    if el.vertex is not None:
        return np.asarray(el.vertex, dtype=float), param
    assert el.piece is not None
    same = [f for f in nd.footpoints if f.element == element]
    if nd.kind is NodeKind.BRANCH_POINT and same:
        best = min(same, key=lambda f: float(np.linalg.norm(f.point_2d - foot)))
        point = np.asarray(best.point_2d, dtype=float)
        t = _foot_param(boundary, element, point, param)[1]
    else:
        point, t = _foot_param(boundary, element, nd.point_2d, param)
    if _passed(graph, nd.index) and _on_circle(graph, boundary, nd, el, strict=True):
        ends = np.array([el.piece.t0, el.piece.t1])
        pe = el.piece.curve.point(ends)
        k = int(np.argmin(np.linalg.norm(pe - point, axis=1)))
        return np.asarray(pe[k], dtype=float), float(ends[k])
    return point, t


def _split(
    graph: MedialGraph,
    boundary: Boundary,
    b: Branch,
    level: float | LevelFn | None,
    touch: TouchFn | None = None,
) -> list[Segment]:
    pocket = _pocket(graph, boundary, b, level)
    if pocket is not None:
        return [pocket]
    pts = b.points_2d
    u = _chord(pts)
    sp = b.spline
    n = len(u)
    fa, fb = b.foot_a_point.copy(), b.foot_b_point.copy()
    ea, eb = b.foot_a_element, b.foot_b_element
    ca, rad = pts.copy(), b.radius.copy()

    # exact ends at nodes
    for where, node in ((0, b.start), (n - 1, b.end)):
        if node is None:
            continue
        nd = graph.nodes[node]
        ca[where], rad[where] = nd.point_2d, nd.radius
        if nd.kind is NodeKind.CONVEX_VERTEX:
            fa[where] = fb[where] = nd.point_2d
            continue
        for feet, els, pars in ((fa, ea, b.foot_a_param), (fb, eb, b.foot_b_param)):
            k = _settled(graph, boundary, b, where, els)
            if k is not None:  # the rows round the node take the first foot past them
                feet[slice(0, k) if where == 0 else slice(k + 1, n)] = feet[k]
                continue
            feet[where] = _node_foot(
                graph, boundary, nd, int(els[where]), feet[where], float(pars[where])
            )[0]

    # curvature-centre ends: the boundary stretch the node sees as a whole (an arc's fan),
    # or, at a curvature maximum, one common foot for both sides (no crack between them)
    fans: list[Segment] = []
    for where, node in ((0, b.start), (n - 1, b.end)):
        if node is None or _end_kind(graph, node) is not NodeKind.CURVATURE_CENTRE:
            continue
        if _degree(graph, node) > 1:
            continue  # a node branches pass through: its fans are the node's own, once
        nd = graph.nodes[node]
        fan: list[Segment] = []
        if float(np.linalg.norm(fa[where] - fb[where])) > 1e-3 * graph.tol:
            # the fan runs between this branch's own end feet (the centre's projection
            # onto a nearly circular stretch may land anywhere on it: a fan from there
            # left a gap to the branch's caps, and their sheets fell apart)
            pa = _project(boundary, int(ea[where]), fa[where])[1]
            pb = _project(boundary, int(eb[where]), fb[where])[1]
            fan = _fan(graph, boundary, node, ((int(ea[where]), pa), (int(eb[where]), pb)))
        if fan:
            fans.extend(fan)
        elif float(np.linalg.norm(fa[where] - fb[where])) > graph.tol and (
            fan := _contact_fans(graph, boundary, node)
        ):
            # feet far apart, the stretch between them not on the node's circle: the disk
            # touches stretches apart from each other, each its own fan; the feet stay
            fans.extend(fan)
        else:
            own = [f.point_2d for f in nd.footpoints]
            mid = 0.5 * (fa[where] + fb[where])
            common = min(own, key=lambda q: float(np.linalg.norm(q - mid))) if own else mid
            fa[where] = fb[where] = np.asarray(common, dtype=float)

    # cut points: (u, kind, centre, radius, foot_a, foot_b, sides changing element there)
    cuts: list[tuple[float, str, FloatArray, float, FloatArray, FloatArray, set[int]]] = []

    # where each side changes element, first: a cut's feet are solved on the element each
    # side has at the cut (the nearest sample's may be past the other side's transition)
    transitions: list[tuple[float, int, int, FloatArray]] = []  # (u, side, interval, joint)
    for i in range(n - 1):
        for els, side in ((ea, 0), (eb, 1)):
            if els[i] == els[i + 1]:
                continue
            feet = fa if side == 0 else fb
            p, nrm = _joint(boundary, int(els[i]), int(els[i + 1]), 0.5 * (feet[i] + feet[i + 1]))

            def g(uu: float, p: FloatArray = p, nrm: FloatArray = nrm) -> float:
                c = sp(np.array([uu]))[0][:2]
                return float((c[0] - p[0]) * nrm[1] - (c[1] - p[1]) * nrm[0])

            lo, hi = float(u[i]), float(u[i + 1])
            glo, ghi = g(lo), g(hi)
            if glo * ghi < 0:
                us = float(brentq(g, lo, hi, xtol=1e-14))
            else:
                us = lo + (hi - lo) * abs(glo) / max(abs(glo) + abs(ghi), 1e-300)
            transitions.append((us, side, i, p))

    def element_at(side: int, uu: float, i: int) -> int:
        els = ea if side == 0 else eb
        if els[i] == els[i + 1]:
            return int(els[i])
        t = [x[0] for x in transitions if x[1] == side and x[2] == i]
        return int(els[i] if not t or uu < t[0] else els[i + 1])

    def at(uu: float, i: int) -> tuple[FloatArray, float, FloatArray, FloatArray]:
        v = sp(np.array([uu]))[0]
        c, r = v[:2], float(v[2])
        w = (uu - u[i]) / max(u[i + 1] - u[i], 1e-300)
        feet = []
        for side, els, pars in ((0, ea, b.foot_a_param), (1, eb, b.foot_b_param)):
            el = element_at(side, uu, i)
            # the parameter guess from the nearer sample on the same element
            j = i if (w < 0.5 and els[i] == el) or els[i + 1] != el else i + 1
            feet.append(_foot_on(boundary, el, c, float(pars[j])))
        return c, r, feet[0], feet[1]

    for us, side, i, p in transitions:
        c, r, ga, gb = at(us, i)
        if side == 0:
            ga = p
        else:
            gb = p
        cuts.append((us, "transition", c, r, ga, gb, {side}))
    if level is not None:
        if callable(level):
            gfun = level
        else:
            h = float(level)

            def gfun(c: FloatArray, r: FloatArray) -> FloatArray:
                return np.asarray(r - h)

        def g1(x: float) -> float:
            v = sp(np.array([x]))
            return float(gfun(v[:, :2], v[:, 2])[0])

        dense = np.unique(np.concatenate([u, 0.5 * (u[1:] + u[:-1])]))
        vals = sp(dense)
        vals[0, :2], vals[0, 2] = ca[0], rad[0]
        vals[-1, :2], vals[-1, 2] = ca[-1], rad[-1]
        rv = gfun(vals[:, :2], vals[:, 2])
        roots: list[float] = []
        for j in range(len(dense) - 1):
            if rv[j] == 0 and j > 0 and rv[j - 1] * rv[j + 1] < 0:
                us = float(dense[j])  # a sample exactly on the level
            elif rv[j] * rv[j + 1] < 0:
                us = float(brentq(g1, dense[j], dense[j + 1], xtol=1e-14))
            else:
                continue
            roots.append(us)
        for us in _touches(roots, g1, touch, lambda x: at(x, _interval(u, x))):
            c, r, ga, gb = at(us, _interval(u, us))
            cuts.append((us, "level", c, r, ga, gb, set()))
    if b.start is None:  # closed: cut in two at the middle sample
        i = n // 2
        cuts.append((float(u[i]), "split", ca[i], float(rad[i]), fa[i], fb[i], set()))
    cuts.sort(key=lambda x: x[0])
    # merge cuts closer than a sliver; the two sides changing element within 1e-2 tol of
    # each other (symmetric profiles) change at one cut: a sliver segment between them would
    # be thinner than the complex's vertex merging
    merged: list[tuple[float, str, FloatArray, float, FloatArray, FloatArray, set[int]]] = []
    for cut in cuts:
        if cut[0] < 1e-9 or cut[0] > 1 - 1e-9:
            continue
        if cut[1] == "level" and (
            min(float(np.linalg.norm(cut[2] - ca[0])), float(np.linalg.norm(cut[2] - ca[-1])))
            < 1e-2 * graph.tol
        ):
            continue  # the level passes through the end node itself (a threshold angle)
        prev = merged[-1] if merged else None
        # a cut at the previous one's parameter is that cut (the sides changing element
        # there join it: both sides of a symmetric profile change at the same parameter, and
        # the second side's transition, dropped, left its next segment on the old element)
        if prev is not None and (
            cut[0] - prev[0] < 1e-9
            or (
                cut[1] == prev[1] == "transition"
                and not (cut[6] & prev[6])
                and float(np.linalg.norm(cut[2] - prev[2])) < 1e-2 * graph.tol
            )
        ):
            new = cut[6] - prev[6]
            ga = cut[4] if 0 in new else prev[4]
            gb = cut[5] if 1 in new else prev[5]
            # (a level at a transition stays a level: the sheet ends there)
            lead = cut if prev[1] == "transition" and cut[1] != "transition" else prev
            merged[-1] = (prev[0], lead[1], lead[2], lead[3], ga, gb, prev[6] | cut[6])
            continue
        merged.append(cut)
    # where each side changes element
    side_cuts = ([m[0] for m in merged if 0 in m[6]], [m[0] for m in merged if 1 in m[6]])

    start_end = _node_end(graph, b.start)
    stop_end = _node_end(graph, b.end)
    bounds = [(0.0, start_end, ca[0], float(rad[0]), fa[0], fb[0])]
    bounds += [(m[0], End(m[1]), m[2], m[3], m[4], m[5]) for m in merged]
    bounds += [(1.0, stop_end, ca[-1], float(rad[-1]), fa[-1], fb[-1])]

    segs: list[Segment] = []
    for (u0, e0, c0, r0, a0, b0), (u1, e1, c1, r1, a1, b1) in itertools.pairwise(bounds):
        span = u1 - u0
        inner = (u > u0 + 1e-9 * 1) & (u < u1 - 1e-9)
        inner &= (u - u0 > 1e-6 * span) & (u1 - u > 1e-6 * span)
        idx = np.nonzero(inner)[0]
        w = np.concatenate([[0.0], (u[idx] - u0) / span, [1.0]])
        centre = np.vstack([c0[None], ca[idx], c1[None]])
        radius = np.concatenate([[r0], rad[idx], [r1]])
        foot_a = np.vstack([a0[None], fa[idx], a1[None]])
        foot_b = np.vstack([b0[None], fb[idx], b1[None]])
        um = 0.5 * (u0 + u1)
        k = _interval(u, um)
        # element of each side on this segment: the one at the segment's middle
        el_a = int(
            ea[k] if _side_before(side_cuts[0], um, u[k], u[k + 1], ea[k], ea[k + 1]) else ea[k + 1]
        )
        el_b = int(
            eb[k] if _side_before(side_cuts[1], um, u[k], u[k + 1], eb[k], eb[k + 1]) else eb[k + 1]
        )
        arrays = _refine(
            boundary, sp, u0, span, el_a, el_b, w, centre, radius, foot_a, foot_b, graph.tol
        )
        segs.append(Segment(b.index, *arrays, el_a, el_b, e0, e1))
    segs.extend(fans)
    return segs


def _interval(u: FloatArray, x: float) -> int:
    """The sample interval ``[u[i], u[i + 1]]`` holding ``x``."""
    return int(np.clip(np.searchsorted(u, x) - 1, 0, len(u) - 2))


def _touches(
    roots: list[float],
    g: Callable[[float], float],
    touch: TouchFn | None,
    row: Callable[[float], tuple[FloatArray, float, FloatArray, FloatArray]],
) -> list[float]:
    """The level cuts at ``roots`` (sorted), where two neighbouring roots whose level is
    within the tolerance between them (``touch`` at the row where ``|g|`` peaks) become
    one cut at that peak. At a revolution's critical angle ``r = x sin(Theta/2)`` touches
    a branch: rounding put two roots 1e-3 apart, and the lift built caps that met the mid
    plane on a sliver and a revolved sheet of area 9e-16 (unorientable, refused)."""
    if touch is None or len(roots) < 2:
        return roots
    out: list[float] = []
    k = 0
    while k < len(roots):
        if k + 1 < len(roots):
            lo, hi = roots[k], roots[k + 1]
            xs = np.linspace(lo, hi, 17)[1:-1]
            size = np.array([abs(g(float(x))) for x in xs])
            j = int(np.argmax(size))
            a, b = (lo if j == 0 else xs[j - 1]), (hi if j == len(xs) - 1 else xs[j + 1])
            best = minimize_scalar(
                lambda x: -abs(g(float(x))),
                bounds=(a, b),
                method="bounded",
                options={"xatol": 1e-13},
            )
            peak = float(best.x) if -best.fun >= size[j] else float(xs[j])
            if touch(*row(peak)):
                out.append(peak)
                k += 2
                continue
        out.append(roots[k])
        k += 1
    return out


def _refine(
    boundary: Boundary,
    sp: object,
    u0: float,
    span: float,
    el_a: int,
    el_b: int,
    w: FloatArray,
    centre: FloatArray,
    radius: FloatArray,
    foot_a: FloatArray,
    foot_b: FloatArray,
    tol: float,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Insert exact samples until the interpolated rows are within a fraction of ``tol``.

    Feet (which become the rims on the solid's boundary) must be much closer than the
    tolerance (0.02 tol); centres follow the branch's spline within 0.1 tol; no step is
    more than 3 times a neighbouring one. A new sample is the branch spline's point, its
    feet projected from it; next to a centre of curvature (``r k > 1/2`` at a foot) the
    projection is ill-conditioned (every boundary point near the foot is nearly as near):
    there the sample is solved from its foot instead (:func:`_from_foot`).
    """
    from scipy.interpolate import make_interp_spline

    cap = max(4 * len(w), 200)  # near a curvature-centre end the feet move like a square
    # root of the branch length: interpolation converges slowly there, stop refining
    pieces = boundary.elements[el_a].piece is not None and boundary.elements[el_b].piece is not None
    if pieces:  # the rows' feet's own parameters (kept through the insertions below)
        pa = _project_params(boundary, el_a, foot_a, foot_a)
        pb = _project_params(boundary, el_b, foot_b, foot_b)
    for _ in range(16):
        if len(w) < 2 or len(w) >= cap:
            break
        k = min(3, len(w) - 1)
        wm = 0.5 * (w[1:] + w[:-1])
        ex = sp(u0 + wm * span)  # type: ignore[operator]
        near_a, near_b = 0.5 * (foot_a[1:] + foot_a[:-1]), 0.5 * (foot_b[1:] + foot_b[:-1])
        if pieces:
            ea, eb = boundary.elements[el_a], boundary.elements[el_b]
            ta = _project_params(boundary, el_a, ex[:, :2], near_a)
            tb = _project_params(boundary, el_b, ex[:, :2], near_b)
            (ex_a, _, ka), (ex_b, _, kb) = boundary.frame_at(ea, ta), boundary.frame_at(eb, tb)
            # a foot projected outside its rows' feet leapt to another nearest point of
            # its curve (both feet of a branch into a tight turn of one B-spline: the
            # centre from the branch spline, a little off, is nearer to the other side)
            astray = _astray(boundary, el_a, ta, pa) | _astray(boundary, el_b, tb, pb)
            ill = np.nonzero((ex[:, 2] * ka > 0.5) | (ex[:, 2] * kb > 0.5) | astray)[0]
            solved = []
            if len(ill):
                got = _from_foot(boundary, el_a, el_b, foot_a, foot_b, ill)
                for j, (c, r, fa, fb) in zip(ill.tolist(), got, strict=True):
                    # its chord position between the two rows it splits
                    d0 = float(np.linalg.norm(c - centre[j]))
                    d1 = float(np.linalg.norm(centre[j + 1] - c))
                    step = float(np.linalg.norm(centre[j + 1] - centre[j]))
                    if not np.isfinite(r) or max(d0, d1) > 2.0 * step + tol:
                        continue  # not between its rows: keep the projected sample
                    astray[j] = False
                    f = d0 / (d0 + d1) if d0 + d1 > 0 else 0.5
                    wm[j] = w[j] + min(max(f, 0.05), 0.95) * (w[j + 1] - w[j])
                    ex[j, :2], ex[j, 2], ex_a[j], ex_b[j] = c, r, fa, fb
                    solved.append(j)
            if solved:  # feet solved, not projected: their own parameters
                sj = np.array(solved)
                ta[sj] = _project_params(boundary, el_a, ex_a[sj], ex_a[sj])
                tb[sj] = _project_params(boundary, el_b, ex_b[sj], ex_b[sj])
        else:
            ex_a = _project_many(boundary, el_a, ex[:, :2], near_a)
            ex_b = _project_many(boundary, el_b, ex[:, :2], near_b)
        fit_c = make_interp_spline(w, np.column_stack([centre, radius]), k=k)(wm)
        fit_a = make_interp_spline(w, foot_a, k=k)(wm)
        fit_b = make_interp_spline(w, foot_b, k=k)(wm)
        bad = np.linalg.norm(fit_c - ex, axis=1) > 0.1 * tol
        bad |= np.linalg.norm(fit_a - ex_a, axis=1) > 0.02 * tol
        bad |= np.linalg.norm(fit_b - ex_b, axis=1) > 0.02 * tol
        # and graded rows: a step more than 3 times its neighbour's is split too (the rows
        # are also interpolated into curves no check sees here, such as a revolution's
        # level curve on the mid sheet)
        dw = np.diff(w)
        beside = np.minimum(np.r_[np.inf, dw[:-1]], np.r_[dw[1:], np.inf])
        bad |= dw > 3.0 * beside
        # rows closer than 1e-5 in w are split only where the feet still sweep (more
        # than 10 tol per row: the disks nearly osculate the boundary and the centre
        # hardly moves); next to a curvature-centre end, that far down, the feet are
        # noise and would step back
        sweep = np.maximum(
            np.linalg.norm(np.diff(foot_a, axis=0), axis=1),
            np.linalg.norm(np.diff(foot_b, axis=0), axis=1),
        )
        bad &= (dw > 1e-5) | ((dw > 1e-7) & (sweep > 10.0 * tol))
        if pieces:
            bad &= ~astray  # no exact row there: better none than one on the wrong side
        if not np.any(bad):
            break
        idx = np.nonzero(bad)[0]
        w = np.insert(w, idx + 1, wm[idx])
        centre = np.insert(centre, idx + 1, ex[idx, :2], axis=0)
        radius = np.insert(radius, idx + 1, ex[idx, 2])
        foot_a = np.insert(foot_a, idx + 1, ex_a[idx], axis=0)
        foot_b = np.insert(foot_b, idx + 1, ex_b[idx], axis=0)
        if pieces:
            pa, pb = np.insert(pa, idx + 1, ta[idx]), np.insert(pb, idx + 1, tb[idx])
    return w, centre, radius, foot_a, foot_b


def _astray(boundary: Boundary, element: int, t: FloatArray, own: FloatArray) -> NDArray[np.bool_]:
    """Whether each parameter ``t[j]`` on ``element`` lies outside the parameters ``own``
    of the feet of rows ``j`` and ``j + 1``, widened by a quarter of their span on either
    side (modulo the period of a closed curve)."""
    lo, span = own[:-1], np.diff(own)
    period = _wrap_span(boundary.elements[element])
    if period is not None:  # the short way round
        span = (span + 0.5 * period) % period - 0.5 * period
    mid = lo + 0.5 * span
    off = t - mid
    if period is not None:
        off = (off + 0.5 * period) % period - 0.5 * period
    return np.asarray(np.abs(off) > 0.75 * np.abs(span) + 1e-12 * np.maximum(1.0, np.abs(mid)))


def _pocket(
    graph: MedialGraph, boundary: Boundary, b: Branch, level: float | LevelFn | None
) -> Segment | None:
    """The segment of a short branch from a branch point into a flat curvature maximum
    between two of its feet (:mod:`medialcad.mat2d.pocket`: rows solved from the boundary
    stretch itself); ``None`` for other branches, and where a level crosses it."""
    if b.start is None or b.end is None:
        return None
    length = np.linalg.norm(np.diff(b.points_2d, axis=0), axis=1).sum()
    if length > POCKET_LENGTH * graph.tol:
        return None  # long: sampled, the general path (rows from its spline) is good
    kinds = {_end_kind(graph, b.start), _end_kind(graph, b.end)}
    if kinds != {NodeKind.BRANCH_POINT, NodeKind.CURVATURE_CENTRE}:
        return None
    el = int(b.foot_a_element[0])
    if not (np.all(b.foot_a_element == el) and np.all(b.foot_b_element == el)):
        return None
    flip = _end_kind(graph, b.start) is NodeKind.BRANCH_POINT
    bp, cc = (
        (graph.nodes[b.start], graph.nodes[b.end])
        if flip
        else (graph.nodes[b.end], graph.nodes[b.start])
    )
    rows = pocket_rows(boundary, bp, cc, graph.tol)
    if rows is None or rows.element != el:
        return None
    if level is not None:  # a level crossing: the general path cuts it there
        lv = level(rows.centre, rows.radius) if callable(level) else rows.radius - float(level)
        if np.any(np.sign(lv[1:]) != np.sign(lv[0])):
            return None
    w, centre, radius, foot_a, foot_b = rows.w, rows.centre, rows.radius, rows.foot_a, rows.foot_b
    start = End("node", cc.index, NodeKind.CURVATURE_CENTRE)
    end = End("node", bp.index, NodeKind.BRANCH_POINT)
    if not flip:
        return Segment(b.index, w, centre, radius, foot_a, foot_b, el, el, start, end)
    return Segment(
        b.index, 1.0 - w[::-1], centre[::-1], radius[::-1], foot_a[::-1], foot_b[::-1],
        el, el, end, start,
    )  # fmt: skip


def _from_foot(
    boundary: Boundary,
    el_a: int,
    el_b: int,
    foot_a: FloatArray,
    foot_b: FloatArray,
    rows: IntArray,
) -> list[tuple[FloatArray, float, FloatArray, FloatArray]]:
    """Exact medial points between rows ``j`` and ``j + 1`` (``j`` in ``rows``), solved from
    the foot midway between theirs on side a (side b where its feet are several times
    further apart than side a's): the radius
    is the least ``f(q) = |q - b|^2 / (2 (q - b).n)`` (the disk tangent at ``b`` through
    ``q``) over ``q`` on the other side's element between its two feet (a bounded Brent
    search). The radius, hence the centre ``b + r n``, is exact to rounding where a
    centre from the branch spline projects to feet that are off by ``delta / (1 - r k)``.
    Solving from the side that moves matters where one side's foot stands still (a
    branch into a flat curvature maximum between two feet of a branch point: 3 tol of
    branch while side a's foot moves 1e-9; solved from side a, rows piled up there)."""
    # (side a unless side b moves several times more: near a curvature-centre end
    # both move alike)
    from_b = np.linalg.norm(foot_b[rows + 1] - foot_b[rows], axis=1) > 4.0 * np.linalg.norm(
        foot_a[rows + 1] - foot_a[rows], axis=1
    )
    out: list[tuple[FloatArray, float, FloatArray, FloatArray]] = [
        (np.zeros(2), np.nan, np.zeros(2), np.zeros(2))
    ] * len(rows)
    for flip in (False, True):
        sel = np.nonzero(from_b == flip)[0]
        if not len(sel):
            continue
        if flip:
            got = _solve_from(boundary, el_b, el_a, foot_b, foot_a, rows[sel])
            got = [(c, r, fa, fb) for c, r, fb, fa in got]
        else:
            got = _solve_from(boundary, el_a, el_b, foot_a, foot_b, rows[sel])
        for i, g in zip(sel.tolist(), got, strict=True):
            out[i] = g
    return out


def _solve_from(
    boundary: Boundary,
    el_a: int,
    el_b: int,
    foot_a: FloatArray,
    foot_b: FloatArray,
    rows: IntArray,
) -> list[tuple[FloatArray, float, FloatArray, FloatArray]]:
    """:func:`_from_foot` from side a's foot (``(centre, r, foot a, foot b)`` a row)."""
    ea, eb = boundary.elements[el_a], boundary.elements[el_b]
    assert ea.piece is not None and eb.piece is not None
    # (the feet lie on their curves: each is its own start, from the dense samples; from
    # 65 points Newton could start across a narrow part of the curve and stay there)
    fa = np.vstack([foot_a[rows], foot_a[rows + 1]])
    fb = np.vstack([foot_b[rows], foot_b[rows + 1]])
    ta = _project_params(boundary, el_a, fa, fa)
    tb = _project_params(boundary, el_b, fb, fb)
    m = len(rows)
    ta0, ta1, tb0, tb1 = ta[:m], ta[m:], tb[:m], tb[m:]
    period = _wrap_span(ea)
    if period is not None:  # across the seam of a closed curve: the short way round
        ta1 = ta0 + (ta1 - ta0 + 0.5 * period) % period - 0.5 * period
    lo_a, hi_a = sorted((ea.piece.t0, ea.piece.t1))
    b, n, _ = boundary.frame_at(ea, _keeper(ea, lo_a, hi_a)(0.5 * (ta0 + ta1)))
    lo_b, hi_b = sorted((eb.piece.t0, eb.piece.t1))
    period_b = _wrap_span(eb)
    x0, x1 = np.minimum(tb0, tb1), np.maximum(tb0, tb1)
    if period_b is not None:  # across the seam: the short way round
        wrap = x1 - x0 > 0.5 * period_b
        x0, x1 = np.where(wrap, x1, x0), np.where(wrap, x0 + period_b, x1)
    pad = 0.5 * (x1 - x0) + 1e-12 * np.maximum(1.0, np.abs(x0))
    lo, hi = x0 - pad, x1 + pad
    if period_b is None:
        lo, hi = np.maximum(lo, lo_b), np.minimum(hi, hi_b)
    curve = eb.piece.curve
    keep = _keeper(eb, lo_b, hi_b)  # (beyond a clamped closed curve's seam: wrapped)

    def f(t: FloatArray) -> FloatArray:  # t (m, k)
        q = curve.point(keep(t.ravel())).reshape(*t.shape, 2) - b[:, None, :]
        bb = np.einsum("mkj,mj->mk", q, n)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(bb > 0, np.einsum("mkj,mkj->mk", q, q) / (2.0 * bb), np.inf)

    # all rows together (a scalar search a row took 85 % of a B-spline extrusion's time)
    t, r = golden_minima(f, lo, hi, 120, rtol=1e-15)
    q = np.asarray(curve.point(keep(t)), dtype=float)
    return [(b[i] + r[i] * n[i], float(r[i]), b[i].copy(), q[i]) for i in range(m)]


def _side_before(cuts: list[float], um: float, ulo: float, uhi: float, e0: int, e1: int) -> bool:
    """Whether the point ``um`` between two samples lies before that side's transition
    (``cuts``: where this side changes element)."""
    if e0 == e1:
        return True
    ts = [c for c in cuts if ulo <= c <= uhi]
    return not ts or um < min(ts)
