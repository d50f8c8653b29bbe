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

__all__ = ["Candidates", "MapSamples", "build_candidates", "evaluate"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

_CHUNK_CELLS = 3_000_000


@dataclass(frozen=True)
class Candidates:
    """Dense boundary points grouped by element (contiguous, in parameter order)."""

    points: FloatArray  # (K, 2)
    element: IntArray  # (K,)
    param: FloatArray  # (K,)
    starts: IntArray  # (E,) first candidate of each element
    stops: IntArray  # (E,)


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
    turn = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.maximum(speed, 1e-300) ** 2
    total_turn = float(np.mean(turn) * abs(p.t1 - p.t0))
    n = int(np.clip(max(np.ceil(e.length / spacing), np.ceil(total_turn / np.radians(4.0))), 8, 4000))
    return np.linspace(p.t0, p.t1, n + 1)


def build_candidates(boundary: Boundary, spacing: float) -> Candidates:
    """Candidate points for the global minimum of ``f``: every edge densely, every
    reflex vertex once."""
    pts, elem, par, starts, stops = [], [], [], [], []
    k = 0
    for e in boundary.elements:
        if e.piece is not None:
            t = _edge_params(e, spacing)
            xy = e.piece.curve.point(t)
        else:
            assert e.vertex is not None
            t = np.array([e.theta0])
            xy = e.vertex[None, :]
        starts.append(k)
        k += len(t)
        stops.append(k)
        pts.append(xy)
        elem.append(np.full(len(t), e.index))
        par.append(t)
    return Candidates(
        np.vstack(pts),
        np.concatenate(elem).astype(np.int64),
        np.concatenate(par),
        np.array(starts, dtype=np.int64),
        np.array(stops, dtype=np.int64),
    )


def _f_values(q: FloatArray, b: FloatArray, n: FloatArray, tiny: float) -> FloatArray:
    """``f(q)`` for each pair (broadcast), ``inf`` where q is not ahead of b."""
    d = q - b
    a = np.einsum("...i,...i->...", d, d)
    bb = np.einsum("...i,...i->...", d, n)
    ok = (bb > 1e-12 * np.sqrt(a)) & (a > tiny * tiny)
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
        bad = ~np.isfinite(tn) | (gp <= 0) | (tn <= np.minimum(lo[idx], hi[idx])) | (
            tn >= np.maximum(lo[idx], hi[idx])
        )
        tn = np.where(bad, 0.5 * (lo[idx] + hi[idx]), tn)
        done = (np.abs(tn - t[idx]) <= 1e-15 * scale) | (g == 0) | (
            np.abs(hi[idx] - lo[idx]) <= 1e-15 * scale
        )
        t[idx] = tn
        active[idx[done]] = False
    q = curve.point(t)
    return t, _f_values(q, b, n, 0.0)


def evaluate(
    boundary: Boundary, cands: Candidates, loop: IntArray, s: FloatArray, self_tol: float
) -> MapSamples:
    """The medial map at boundary points given by ``(loop, s)``.

    A disk whose radius is within ``self_tol`` of the osculating radius ``1/k(b)`` is
    taken to be the osculating disk (its centre is the centre of curvature).
    """
    loop = np.asarray(loop, dtype=np.int64)
    s = np.asarray(s, dtype=float)
    m = len(s)
    elements = boundary.elements
    elem = np.empty(m, dtype=np.int64)
    param = np.empty(m)
    foot = np.empty((m, 2))
    normal = np.empty((m, 2))
    curv = np.empty(m)
    for e in elements:
        sel = np.nonzero((loop == e.loop) & (s >= e.s0) & (s <= e.s0 + e.length))[0]
        if len(sel) == 0:
            continue
        elem[sel] = e.index
        param[sel] = boundary.param_of(e, s[sel])
        foot[sel], normal[sel], curv[sel] = boundary.frame_at(e, param[sel])

    tiny = 1e-12 * boundary.diag
    best = np.full(m, np.inf)
    best_elem = np.full(m, -1, dtype=np.int64)
    best_param = np.zeros(m)
    # the osculating disk bounds rho* (limit of f on the own curve)
    with np.errstate(divide="ignore"):
        self_bound = np.where(curv > 0, 1.0 / np.where(curv > 0, curv, 1.0), np.inf)

    n_cand = len(cands.points)
    chunk = max(1, _CHUNK_CELLS // max(n_cand, 1))
    pair_rows: list[IntArray] = []
    pair_elems: list[IntArray] = []
    pair_cidx: list[IntArray] = []
    for c0 in range(0, m, chunk):
        rows = np.arange(c0, min(m, c0 + chunk))
        f = _f_values(cands.points[None, :, :], foot[rows, None, :], normal[rows, None, :], tiny)
        fe = np.minimum.reduceat(f, cands.starts, axis=1)
        rmin = np.minimum(fe.min(axis=1), self_bound[rows])
        keep = fe <= rmin[:, None] * 1.25 + 1e-9 * boundary.diag
        r_i, e_i = np.nonzero(keep & np.isfinite(fe))
        for ei in np.unique(e_i):
            sel = e_i == ei
            rr = r_i[sel]
            sub = f[rr, cands.starts[ei] : cands.stops[ei]]
            pair_rows.append(rr + c0)
            pair_elems.append(np.full(len(rr), ei))
            pair_cidx.append(cands.starts[ei] + np.argmin(sub, axis=1))
    rows_all = np.concatenate(pair_rows) if pair_rows else np.zeros(0, dtype=np.int64)
    elems_all = np.concatenate(pair_elems) if pair_elems else np.zeros(0, dtype=np.int64)
    cidx_all = np.concatenate(pair_cidx) if pair_cidx else np.zeros(0, dtype=np.int64)

    val = np.full(len(rows_all), np.inf)
    par = np.zeros(len(rows_all))
    for ei in np.unique(elems_all):
        sel = np.nonzero(elems_all == ei)[0]
        e = elements[ei]
        rr, cj = rows_all[sel], cidx_all[sel]
        if e.piece is None:
            val[sel] = _f_values(cands.points[cj], foot[rr], normal[rr], tiny)
            par[sel] = e.theta0
            continue
        first, last = cands.starts[ei], cands.stops[ei] - 1
        lo = cands.param[np.maximum(cj - 1, first)]
        hi = cands.param[np.minimum(cj + 1, last)]
        t0 = cands.param[cj]
        own = elem[rr] == ei
        lo2, hi2 = np.minimum(lo, hi), np.maximum(lo, hi)
        if np.any(own):
            # never let the solve fall onto the trivial root q = b on the own curve
            tb = param[rr]
            inside = own & (lo2 < tb) & (tb < hi2)
            lo2 = np.where(inside & (t0 > tb), tb + 0.5 * (t0 - tb), lo2)
            hi2 = np.where(inside & (t0 < tb), tb + 0.5 * (t0 - tb), hi2)
        t, fv = _refine_on_edge(e, foot[rr], normal[rr], t0, lo2, hi2)
        if np.linalg.norm(cands.points[first] - cands.points[last]) <= tiny:
            # a closed edge: a minimum at its seam may lie on the other side of it
            at_seam = np.nonzero((cj == first) | (cj == last))[0]
            if len(at_seam):
                other = np.where(cj[at_seam] == first, last, first)
                olo = cands.param[np.where(other == first, first, last - 1)]
                ohi = cands.param[np.where(other == first, first + 1, last)]
                t_b, f_b = _refine_on_edge(
                    e,
                    foot[rr[at_seam]],
                    normal[rr[at_seam]],
                    cands.param[other],
                    np.minimum(olo, ohi),
                    np.maximum(olo, ohi),
                )
                better = f_b < fv[at_seam]
                t[at_seam[better]] = t_b[better]
                fv[at_seam[better]] = f_b[better]
        f0 = _f_values(cands.points[cj], foot[rr], normal[rr], tiny)
        worse = ~(fv <= f0)
        t = np.where(worse, t0, t)
        fv = np.where(worse, f0, fv)
        # a minimum at the end of an edge is a vertex: let interior solutions win ties
        pe = e.piece
        at_end = (np.abs(t - pe.t0) < 1e-12 * abs(pe.t1 - pe.t0)) | (
            np.abs(t - pe.t1) < 1e-12 * abs(pe.t1 - pe.t0)
        )
        fv = np.where(at_end, fv * (1 + 1e-12) + 1e-14 * boundary.diag, fv)
        if np.any(own):
            near = own & (np.abs(t - param[rr]) < 1e-9 * abs(pe.t1 - pe.t0))
            fv = np.where(near, np.inf, fv)
        val[sel], par[sel] = fv, t

    order = np.lexsort((val, rows_all))
    first_of_row = np.ones(len(order), dtype=bool)
    first_of_row[1:] = rows_all[order][1:] != rows_all[order][:-1]
    win = order[first_of_row]
    best[rows_all[win]] = val[win]
    best_elem[rows_all[win]] = elems_all[win]
    best_param[rows_all[win]] = par[win]

    is_self = ~(best < self_bound - self_tol)
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
