"""The medial map: for a boundary point ``b`` with inward normal ``n``, the maximal disk
tangent at ``b`` and where else it touches the boundary (THEORY.md Sec. 0).

The disk centred at ``b + rho n`` with radius ``rho`` passes through a boundary point
``q`` when ``rho = f(q) = |q - b|^2 / (2 (q - b).n)``; the maximal disk has
``rho* = min_q f(q)`` over the whole boundary, together with the curvature bound
``1/k(b)`` (the limit of ``f`` as ``q -> b`` on the same curve). The minimum is found on
dense candidate points, then solved exactly on each candidate element: in closed form for
a reflex vertex, by safeguarded Newton on ``df/dt = 0`` for a curve (for every curve type,
on its exact parameterization).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from medialcad.mat2d.boundary import Boundary, Element
from medialcad.mat2d.curves import CircleCurve, LineCurve

__all__ = ["Candidates", "MapSamples", "build_candidates", "evaluate"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

_CHUNK_CELLS = 3_000_000


@dataclass(frozen=True)
class Candidates:
    """What the global minimum of ``f`` is searched over.

    Lines, circles and reflex vertices are solved in closed form (their tables below);
    every other curve has dense candidate points (contiguous per element, in parameter
    order) and a Newton solve on its exact parameterization.
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
    touch: IntArray  # (E, 2): the element met at the edge's low / high parameter end


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

    @property
    def centre(self) -> FloatArray:
        return np.asarray(self.foot + self.radius[:, None] * self.normal)

    def __len__(self) -> int:
        return len(self.s)

    def take(self, idx: IntArray | BoolArray) -> MapSamples:
        return MapSamples(**{k: v[idx] for k, v in self.__dict__.items()})

    @staticmethod
    def concat(parts: list[MapSamples]) -> MapSamples:
        keys = parts[0].__dict__.keys()
        return MapSamples(**{k: np.concatenate([p.__dict__[k] for p in parts]) for k in keys})


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


def build_candidates(boundary: Boundary, spacing: float) -> Candidates:
    """Closed-form tables for lines, circles and reflex vertices; dense candidate points
    for every other curve."""
    pts, elem, par, starts, stops, general = [], [], [], [], [], []
    lines: list[tuple[int, FloatArray, FloatArray, FloatArray, float, float]] = []
    circles: list[tuple[int, FloatArray, float, FloatArray, FloatArray, float, float]] = []
    verts: list[tuple[int, FloatArray]] = []
    k = 0
    for e in boundary.elements:
        if e.piece is None:
            assert e.vertex is not None
            verts.append((e.index, e.vertex))
            continue
        c = e.piece.curve
        lo, hi = sorted((e.piece.t0, e.piece.t1))
        sense = 1.0 if e.piece.t1 > e.piece.t0 else -1.0
        if isinstance(c, LineCurve):
            tan = sense * c.direction
            lines.append((e.index, c.origin, c.direction, np.array([-tan[1], tan[0]]), lo, hi))
            continue
        if isinstance(c, CircleCurve):
            circles.append((e.index, c.center, c.radius, c.xaxis, c.yaxis, lo, hi))
            continue
        t = _edge_params(e, spacing)
        starts.append(k)
        k += len(t)
        stops.append(k)
        pts.append(e.piece.curve.point(t))
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
    return Candidates(
        points=np.vstack(pts) if pts else np.zeros((0, 2)),
        element=np.concatenate(elem).astype(i64) if elem else np.zeros(0, dtype=i64),
        param=np.concatenate(par) if par else np.zeros(0),
        starts=np.array(starts, dtype=i64),
        stops=np.array(stops, dtype=i64),
        general=np.array(general, dtype=i64),
        lines=np.array([r[0] for r in lines], dtype=i64),
        line_o=col(lines, 1, 2),
        line_d=col(lines, 2, 2),
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
        vert_p=col(verts, 1, 2),
        elem_key=keys,
        loop_offset=offset,
        spacing=spacing,
        reflex_end=_reflex_ends(boundary, touch),
        touch=touch,
    )


def _touching(boundary: Boundary) -> IntArray:
    """For each edge, the element it meets at its low / high parameter end."""
    els = boundary.elements
    out = np.full((len(els), 2), -1, dtype=np.int64)
    for e in els:
        if e.piece is None:
            continue
        same = [x for x in els if x.loop == e.loop]
        k = same.index(e)
        before, after = same[k - 1].index, same[(k + 1) % len(same)].index
        forward = e.piece.t1 > e.piece.t0
        out[e.index] = (before, after) if forward else (after, before)
    return out


def _reflex_ends(boundary: Boundary, touch: IntArray) -> BoolArray:
    """For each edge, whether its low / high parameter end is a reflex vertex (whose
    element owns that point: a minimum of ``f`` clamped there is the vertex's)."""
    is_vertex = np.array([e.is_vertex for e in boundary.elements] + [False])
    return np.asarray(is_vertex[touch] & (touch != np.arange(len(touch))[:, None]))


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


def _pick(vals: FloatArray, params: FloatArray, ids: IntArray) -> _Best:
    """Per-row minimum of an ``(m, E)`` block: value, element id and parameter."""
    if vals.shape[1] == 0:
        m = vals.shape[0]
        return np.full(m, np.inf), np.full(m, -1, dtype=np.int64), np.zeros(m)
    j = np.argmin(vals, axis=1)
    r = np.arange(len(j))
    return vals[r, j], ids[j], params[r, j]


def _endpoints_f(
    o: FloatArray, pts_lo: FloatArray, pts_hi: FloatArray, b: FloatArray, n: FloatArray, tiny: float
) -> tuple[FloatArray, FloatArray]:
    f_lo = _f_values(pts_lo[None, :, :], b[:, None, :], n[:, None, :], tiny)
    f_hi = _f_values(pts_hi[None, :, :], b[:, None, :], n[:, None, :], tiny)
    return f_lo, f_hi


def _lines_block(
    C: Candidates, b: FloatArray, n: FloatArray, own: IntArray, tiny: float, pen: float
) -> _Best:
    """Closed form: the disk tangent at ``b`` growing until it touches each line segment."""
    o, d, nu = C.line_o[None], C.line_d[None], C.line_nu[None]
    rel = b[:, None, :] - o
    h = np.einsum("mek,mek->me", rel, np.broadcast_to(nu, rel.shape))
    nn = n @ C.line_nu.T
    sig = np.sign(h)
    den = 1.0 - sig * nn
    with np.errstate(divide="ignore", invalid="ignore"):
        # b on the line itself (a neighbouring edge's vertex) is no tangency
        rho = np.where((den > 1e-14) & (sig * h > 10.0 * tiny), sig * h / den, np.inf)
    c = b[:, None, :] + np.where(np.isfinite(rho), rho, 0.0)[..., None] * n[:, None, :]
    tf = np.einsum("mek,mek->me", c - o, np.broadcast_to(d, c.shape))
    inside = np.isfinite(rho) & (tf >= C.line_lo) & (tf <= C.line_hi)
    p_lo = C.line_o + C.line_lo[:, None] * C.line_d
    p_hi = C.line_o + C.line_hi[:, None] * C.line_d
    f_lo, f_hi = _endpoints_f(o, p_lo, p_hi, b, n, tiny)
    # an end at a reflex vertex belongs to the vertex; an end at the joint with the
    # sample's own element is the sample's own curve (a gap there is no partner)
    f_lo = np.where(C.reflex_end[C.lines, 0] | (C.touch[C.lines, 0] == own[:, None]), np.inf, f_lo)
    f_hi = np.where(C.reflex_end[C.lines, 1] | (C.touch[C.lines, 1] == own[:, None]), np.inf, f_hi)
    end_val = np.minimum(f_lo, f_hi) * (1 + 1e-12) + pen
    end_par = np.where(f_lo <= f_hi, C.line_lo, C.line_hi)
    val = np.where(inside, rho, end_val)
    par = np.where(inside, tf, end_par)
    val = np.where(own[:, None] == C.lines[None, :], np.inf, val)
    return _pick(val, par, C.lines)


def _circles_block(
    C: Candidates, b: FloatArray, n: FloatArray, own: IntArray, tiny: float, pen: float
) -> _Best:
    """Closed form: the disk tangent at ``b`` touching each circular arc."""
    w = b[:, None, :] - C.circ_c[None]
    ww = np.einsum("mek,mek->me", w, w)
    wn = np.einsum("mek,mk->me", w, n)
    r = C.circ_r[None, :]
    inner = ww < r * r
    with np.errstate(divide="ignore", invalid="ignore"):
        rho = np.where(inner, (r * r - ww) / (2 * (wn + r)), (ww - r * r) / (2 * (r - wn)))
    on = np.abs(np.sqrt(ww) - r) <= 10.0 * tiny  # b on the same circle (another arc of it)
    rho = np.where(on, np.where(wn < 0, r, np.inf), rho)
    rho = np.where(np.isfinite(rho) & (rho > 0), rho, np.inf)
    c = b[:, None, :] + np.where(np.isfinite(rho), rho, 0.0)[..., None] * n[:, None, :]
    v = c - C.circ_c[None]
    alpha = np.arctan2(np.einsum("mek,ek->me", v, C.circ_y), np.einsum("mek,ek->me", v, C.circ_x))
    a = C.circ_lo + np.mod(alpha - C.circ_lo, 2 * np.pi)
    inside = np.isfinite(rho) & (a <= C.circ_hi)
    ang_lo, ang_hi = C.circ_lo[:, None], C.circ_hi[:, None]
    p_lo = C.circ_c + C.circ_r[:, None] * (np.cos(ang_lo) * C.circ_x + np.sin(ang_lo) * C.circ_y)
    p_hi = C.circ_c + C.circ_r[:, None] * (np.cos(ang_hi) * C.circ_x + np.sin(ang_hi) * C.circ_y)
    f_lo, f_hi = _endpoints_f(C.circ_c, p_lo, p_hi, b, n, tiny)
    f_lo = np.where(
        C.reflex_end[C.circles, 0] | (C.touch[C.circles, 0] == own[:, None]), np.inf, f_lo
    )
    f_hi = np.where(
        C.reflex_end[C.circles, 1] | (C.touch[C.circles, 1] == own[:, None]), np.inf, f_hi
    )
    end_val = np.minimum(f_lo, f_hi) * (1 + 1e-12) + pen
    end_par = np.where(f_lo <= f_hi, C.circ_lo, C.circ_hi)
    val = np.where(inside, rho, end_val)
    par = np.where(inside, a, end_par)
    val = np.where(own[:, None] == C.circles[None, :], np.inf, val)
    return _pick(val, par, C.circles)


def _vertices_block(C: Candidates, b: FloatArray, n: FloatArray, tiny: float) -> _Best:
    f = _f_values(C.vert_p[None, :, :], b[:, None, :], n[:, None, :], tiny)
    return _pick(f, np.zeros_like(f), C.vertices)


def _general_block(
    boundary: Boundary,
    C: Candidates,
    b: FloatArray,
    n: FloatArray,
    own: IntArray,
    own_param: FloatArray,
    self_bound: FloatArray,
    near: FloatArray,
    tiny: float,
    pen: float,
) -> _Best:
    """Free-form curves: dense candidates, then safeguarded Newton per candidate element."""
    m = len(b)
    if len(C.general) == 0:
        return np.full(m, np.inf), np.full(m, -1, dtype=np.int64), np.zeros(m)
    f = _f_values(C.points[None, :, :], b[:, None, :], n[:, None, :], tiny)
    fe = np.minimum.reduceat(f, C.starts, axis=1)
    rmin = np.minimum(fe.min(axis=1), self_bound)
    keep = (fe <= rmin[:, None] * 1.25 + 1e-9 * boundary.diag) & np.isfinite(fe)
    best = np.full(m, np.inf)
    best_e = np.full(m, -1, dtype=np.int64)
    best_p = np.zeros(m)
    for g in np.nonzero(keep.any(axis=0))[0]:
        rr = np.nonzero(keep[:, g])[0]
        ei = int(C.general[g])
        e = boundary.elements[ei]
        assert e.piece is not None
        first, last = int(C.starts[g]), int(C.stops[g]) - 1
        # every discrete local minimum near the best: one curve can hold several partners
        # whose values differ by less than the sampling error (at a branch point)
        fg = f[rr, first : last + 1]
        closed = np.linalg.norm(C.points[first] - C.points[last]) <= tiny
        pad = fg[:, -2:-1] if closed else np.full((len(rr), 1), np.inf)
        left = np.concatenate([pad, fg[:, :-1]], axis=1)
        pad = fg[:, 1:2] if closed else np.full((len(rr), 1), np.inf)
        right = np.concatenate([fg[:, 1:], pad], axis=1)
        thr = rmin[rr] * 1.25 + 1e-9 * boundary.diag
        lm = (fg <= left) & (fg <= right) & (fg <= thr[:, None]) & np.isfinite(fg)
        if closed:
            lm[:, -1] = False  # the seam point is the first candidate too
        ri, jj = np.nonzero(lm)
        rr, cj = rr[ri], first + jj
        lo = C.param[np.maximum(cj - 1, first)]
        hi = C.param[np.minimum(cj + 1, last)]
        t0 = C.param[cj]
        lo2, hi2 = np.minimum(lo, hi), np.maximum(lo, hi)
        is_own = own[rr] == ei
        if np.any(is_own):
            # never let the solve fall onto the trivial root q = b on the own curve: the
            # partner of a sample that is not near-self lies at least ``near`` away
            tb = own_param[rr]
            speed = np.linalg.norm(e.piece.curve.derivs(tb)[1], axis=1)
            cut = np.minimum(0.5 * near[rr] / np.maximum(speed, 1e-300), 0.5 * np.abs(t0 - tb))
            inside = is_own & (lo2 < tb + cut) & (tb - cut < hi2)
            lo2 = np.where(inside & (t0 > tb), np.maximum(lo2, tb + cut), lo2)
            hi2 = np.where(inside & (t0 < tb), np.minimum(hi2, tb - cut), hi2)
        t, fv = _refine_on_edge(e, b[rr], n[rr], t0, lo2, hi2)
        if closed:
            # a closed edge: a minimum at its seam may lie on the other side of it
            at_seam = np.nonzero((cj == first) | (cj == last))[0]
            if len(at_seam):
                other = np.where(cj[at_seam] == first, last, first)
                olo = C.param[np.where(other == first, first, last - 1)]
                ohi = C.param[np.where(other == first, first + 1, last)]
                t_b, f_b = _refine_on_edge(
                    e,
                    b[rr[at_seam]],
                    n[rr[at_seam]],
                    C.param[other],
                    np.minimum(olo, ohi),
                    np.maximum(olo, ohi),
                )
                better = f_b < fv[at_seam]
                t[at_seam[better]] = t_b[better]
                fv[at_seam[better]] = f_b[better]
        f0 = f[rr, cj]
        worse = ~(fv <= f0)
        t = np.where(worse, t0, t)
        fv = np.where(worse, f0, fv)
        span = abs(e.piece.t1 - e.piece.t0)
        at_end = (np.abs(t - e.piece.t0) < 1e-12 * span) | (np.abs(t - e.piece.t1) < 1e-12 * span)
        fv = np.where(at_end, fv * (1 + 1e-12) + pen, fv)
        lo_t, hi_t = min(e.piece.t0, e.piece.t1), max(e.piece.t0, e.piece.t1)
        end_lo = C.reflex_end[ei, 0] | (C.touch[ei, 0] == own[rr])
        end_hi = C.reflex_end[ei, 1] | (C.touch[ei, 1] == own[rr])
        at_reflex = (end_lo & (np.abs(t - lo_t) < 1e-12 * span)) | (
            end_hi & (np.abs(t - hi_t) < 1e-12 * span)
        )
        fv = np.where(at_reflex, np.inf, fv)
        if np.any(is_own):
            fv = np.where(is_own & (np.abs(t - own_param[rr]) < 1e-9 * span), np.inf, fv)
        order = np.lexsort((fv, rr))
        head = np.ones(len(order), dtype=bool)
        head[1:] = rr[order][1:] != rr[order][:-1]
        win = order[head]
        better = fv[win] < best[rr[win]]
        best[rr[win][better]] = fv[win][better]
        best_e[rr[win][better]] = ei
        best_p[rr[win][better]] = t[win][better]
    return best, best_e, best_p


def evaluate(
    boundary: Boundary, cands: Candidates, loop: IntArray, s: FloatArray, tol: float
) -> MapSamples:
    """The medial map at boundary points given by ``(loop, s)``.

    A disk whose radius is within ``tol / 20`` of the osculating radius ``1/k(b)`` is
    taken to be the osculating disk (its centre is the centre of curvature). So is a disk
    whose partner is on the own curve closer than ``sqrt(tol / k) / 2``: there the medial point is within ``tol`` of the centre of
    curvature of the nearby curvature maximum, and its equations are ill-conditioned.
    Such samples are flagged ``is_self`` and only locate that end point.
    """
    loop = np.asarray(loop, dtype=np.int64)
    s = np.asarray(s, dtype=float)
    m = len(s)
    elements = boundary.elements
    key = cands.loop_offset[loop] + s
    elem = np.clip(np.searchsorted(cands.elem_key, key, side="right") - 1, 0, len(elements) - 1)
    param = np.empty(m)
    foot = np.empty((m, 2))
    normal = np.empty((m, 2))
    curv = np.empty(m)
    for ei in np.unique(elem):
        sel = np.nonzero(elem == ei)[0]
        e = elements[ei]
        param[sel] = boundary.param_of(e, s[sel])
        foot[sel], normal[sel], curv[sel] = boundary.frame_at(e, param[sel])

    tiny = 1e-12 * boundary.diag
    pen = 1e-14 * boundary.diag  # a minimum at a segment's end loses ties
    # the osculating disk bounds rho* (limit of f on the own curve)
    with np.errstate(divide="ignore"):
        self_bound = np.where(curv > 0, 1.0 / np.where(curv > 0, curv, 1.0), np.inf)
    near = 0.5 * np.sqrt(tol * np.where(np.isfinite(self_bound), self_bound, 0.0))
    best = np.full(m, np.inf)
    best_elem = np.full(m, -1, dtype=np.int64)
    best_param = np.zeros(m)
    width = len(cands.lines) + len(cands.circles) + len(cands.vertices) + len(cands.points)
    chunk = max(1, _CHUNK_CELLS // max(width, 1))
    for c0 in range(0, m, chunk):
        sl = slice(c0, min(m, c0 + chunk))
        b, n, own = foot[sl], normal[sl], elem[sl]
        blocks = [
            _lines_block(cands, b, n, own, tiny, pen),
            _circles_block(cands, b, n, own, tiny, pen),
            _vertices_block(cands, b, n, tiny),
            _general_block(
                boundary, cands, b, n, own, param[sl], self_bound[sl], near[sl], tiny, pen
            ),
        ]
        vals = np.stack([blk[0] for blk in blocks])
        j = np.argmin(vals, axis=0)
        r = np.arange(vals.shape[1])
        best[sl] = vals[j, r]
        best_elem[sl] = np.stack([blk[1] for blk in blocks])[j, r]
        best_param[sl] = np.stack([blk[2] for blk in blocks])[j, r]

    is_self = ~(best < self_bound - 0.05 * tol)
    radius = np.where(is_self, self_bound, best)
    centre = foot + radius[:, None] * normal
    p_elem = np.where(is_self, elem, best_elem)
    p_param = np.where(is_self, param, best_param)
    p_point = np.empty((m, 2))
    p_loop = np.empty(m, dtype=np.int64)
    p_s = np.empty(m)
    for ei in np.unique(p_elem):
        sel = np.nonzero(p_elem == ei)[0]
        e = elements[ei]
        p_loop[sel] = e.loop
        if e.piece is None:
            assert e.vertex is not None
            c = centre[sel] - e.vertex
            th = np.arctan2(c[:, 1], c[:, 0])
            rel = np.mod(th - e.theta0 + np.pi, 2 * np.pi) - np.pi
            rel = np.clip(rel, e.theta1 - e.theta0, 0.0)
            p_param[sel] = e.theta0 + rel
            p_point[sel] = e.vertex
        else:
            p_point[sel] = e.piece.curve.point(p_param[sel])
        p_s[sel] = boundary.s_of(e, p_param[sel])
    loop_len = np.asarray(boundary.loop_lengths)[loop]
    gap_s = np.abs(p_s - s)
    gap_s = np.minimum(gap_s, loop_len - gap_s)  # across the seam of a closed curve
    own_close = (p_elem == elem) & ~is_self & (gap_s < near) & np.isfinite(self_bound)
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
