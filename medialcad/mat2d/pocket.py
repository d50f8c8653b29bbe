"""Exact rows of a short branch from a branch point into a flat curvature maximum that
lies between two of its feet on one edge (a "pocket").

Such a branch (a blob's maximum 1e-3 wide between two feet of a branch point, the branch
~10 tol long) has few samples or none: the tracer's samples there osculate, and a
spline through its ends is off by several tol (the branch bends). Its rows are solved
here from the boundary stretch itself: each from a foot on either half of the stretch
(the least tangent-disk radius over the other half: a grid, then golden sections on
the bracket around its least sample, all rows of a round at once), from the half whose
foot moves more; they are parametrized by how far their feet are from the
maximum (both move away from it monotonically) and refined until the interpolated rows
are within 0.1 tol (centres and radii) and 0.02 tol (feet) of exact ones. Both the 2D
graph (its branch) and the 3D segments (their rows) take them.

Pure numpy/scipy: no OCC.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from medialcad.mat2d.boundary import Boundary, Element
from medialcad.mat2d.curves import CircleCurve, EllipseCurve
from medialcad.mat2d.graph import Node, NodeKind

__all__ = ["PocketRows", "closed_period", "pocket_rows"]

FloatArray = NDArray[np.float64]

POCKET_LENGTH = 64.0  # longest pocket branch solved here, in tol (longer: sampled well)


@dataclass(frozen=True)
class PocketRows:
    """Rows from the centre of curvature (``w = 0``) to the branch point (``w = 1``):
    ``w`` increasing, centres ``(n, 2)``, radii, feet ``(n, 2)`` and their parameters on
    ``element`` (side a: the half before the maximum in the curve's parameter)."""

    element: int
    w: FloatArray
    centre: FloatArray
    radius: FloatArray
    foot_a: FloatArray
    foot_b: FloatArray
    param_a: FloatArray
    param_b: FloatArray


def closed_period(e: Element) -> float | None:
    """The parameter period of an element that is a whole closed curve (a periodic
    B-spline, a full ellipse or circle), else None."""
    assert e.piece is not None
    span = abs(e.piece.t1 - e.piece.t0)
    period = getattr(e.piece.curve, "period", None)
    if period is None and isinstance(e.piece.curve, (CircleCurve, EllipseCurve)):
        period = 2.0 * np.pi
    return float(period) if period is not None and span >= period * (1.0 - 1e-12) else None


def pocket_rows(boundary: Boundary, bp: Node, cc: Node, tol: float) -> PocketRows | None:
    """The rows of the branch from branch point ``bp`` to curvature centre ``cc`` when
    ``cc``'s foot lies on an edge between two of ``bp``'s feet on it; ``None`` otherwise
    (or when fewer than 4 rows could be solved)."""
    from scipy.interpolate import make_interp_spline

    if bp.kind is not NodeKind.BRANCH_POINT or cc.kind is not NodeKind.CURVATURE_CENTRE:
        return None
    if len(cc.footpoints) != 1:
        return None
    el = cc.footpoints[0].element
    e = boundary.elements[el]
    if e.piece is None:
        return None
    period = closed_period(e)
    t0 = min(e.piece.t0, e.piece.t1)
    t_cc = float(cc.footpoints[0].param)

    def near(t: float) -> float:  # a closed curve's parameter, the short way from t_cc
        if period is None:
            return t
        return t_cc + (t - t_cc + 0.5 * period) % period - 0.5 * period

    def wrap(t: float) -> float:
        return t if period is None else t0 + (t - t0) % period

    # the branch point's two feet on this element nearest the maximum, one either side
    feet = [(near(f.param), f) for f in bp.footpoints if f.element == el]
    below = [x for x in feet if x[0] < t_cc]
    above = [x for x in feet if x[0] > t_cc]
    if not below or not above:
        return None
    ta_end, fa = max(below, key=lambda x: x[0])
    tb_end, fb = min(above, key=lambda x: x[0])
    span = (t_cc - ta_end) + (tb_end - t_cc)
    curve = e.piece.curve

    def points(t: FloatArray) -> FloatArray:
        t = np.asarray(t, dtype=float)
        return np.asarray(curve.point(t if period is None else t0 + (t - t0) % period))

    def integral(a: FloatArray, b: FloatArray) -> FloatArray:
        half = 0.5 * (b - a)
        s = (a + half)[..., None] + half[..., None] * _GAUSS_X
        flat = s.ravel()
        d1 = np.asarray(curve.derivs(flat if period is None else t0 + (flat - t0) % period)[1])
        d1 = d1.reshape(*s.shape, 2)
        return np.asarray(np.einsum("mkgj,g->mkj", d1, _GAUSS_W) * half[..., None])

    def chords(t: FloatArray, u: FloatArray) -> FloatArray:
        """``C(u) - C(t)`` for ``t (m,)`` and ``u (m, k)``: the integral of ``C'``
        (Gauss-Legendre), exact to rounding relative to the chord itself (the difference
        of two points is exact only relative to the coordinates); split at a closed
        curve's seam, where the speed may jump."""
        a = np.broadcast_to(t[:, None], u.shape)
        if period is None:
            return integral(a, u)
        lo_, hi_ = np.minimum(a, u), np.maximum(a, u)
        seam = t0 + period * np.ceil((lo_ - t0) / period)
        cut = np.where((lo_ < seam) & (seam < hi_), seam, u)
        return integral(a, cut) + integral(cut, u)

    memo: dict[tuple[float, bool], _PocketRow | None] = {}

    def solve(queries: list[tuple[float, bool]]) -> list[_PocketRow | None]:
        """The rows whose foot on one half (side a when the flag is set) is at each
        query's parameter (their partners on the other half), solved together per half;
        remembered: a midpoint whose row was not taken is asked again next round."""
        for side_a in (True, False):
            ts = np.array(sorted({t for t, a in queries if a == side_a and (t, a) not in memo}))
            if len(ts) == 0:
                continue
            bq, nq, _ = boundary.frame_at(e, np.array([wrap(t) for t in ts]))
            xs, rs = _tangent_partners(bq, nq, ts, chords, t_cc, tb_end if side_a else ta_end)
            fx = points(np.where(np.isfinite(xs), xs, t_cc))
            for i, t in enumerate(ts):
                x, r = xs[i], rs[i]
                if not np.isfinite(x) or not cc.radius <= r <= bp.radius:
                    # beyond the stretch, or larger than the branch point's disk (not
                    # maximal: it reaches past the node's other feet)
                    memo[(t, side_a)] = None
                    continue
                ta, tb = (t, x) if side_a else (x, t)
                fa_, fb_ = (bq[i], fx[i]) if side_a else (fx[i], bq[i])
                memo[(t, side_a)] = _PocketRow(
                    (tb - ta) / span, ta, tb, bq[i] + r * nq[i], r, fa_, fb_
                )
        return [memo[q] for q in queries]

    tip = np.asarray(cc.footpoints[0].point_2d, dtype=float)
    rows = [
        _PocketRow(0.0, t_cc, t_cc, np.asarray(cc.point_2d, float), cc.radius, tip, tip),
        _PocketRow(1.0, ta_end, tb_end, np.asarray(bp.point_2d, float), bp.radius,
                   np.asarray(fa.point_2d, float), np.asarray(fb.point_2d, float)),
    ]  # fmt: skip
    grid = np.arange(1, 8) / 8.0
    first = [(float(t_cc + (ta_end - t_cc) * g), True) for g in grid]
    first += [(float(t_cc + (tb_end - t_cc) * g), False) for g in grid]
    rows += [row for row in solve(first) if row is not None]
    rows = _monotone(rows, span)
    for _ in range(24):
        if len(rows) >= 400:
            break
        s = _pocket_params(rows)
        k = min(3, len(rows) - 1)
        fit = make_interp_spline(s, np.array([x.values() for x in rows]), k=k)
        ds = np.diff(s)
        beside = np.minimum(np.r_[np.inf, ds[:-1]], np.r_[ds[1:], np.inf])
        new: list[_PocketRow] = []
        spans = [j for j in range(len(rows) - 1) if ds[j] >= 1e-9]
        asks: list[list[tuple[float, bool]]] = []
        for j in spans:
            lo_row, hi_row = rows[j], rows[j + 1]
            side_a = bool(abs(hi_row.ta - lo_row.ta) >= abs(hi_row.tb - lo_row.tb))
            # the other half where the partner is at its end
            asks.append(
                [
                    (0.5 * ((lo_row.ta + hi_row.ta) if a else (lo_row.tb + hi_row.tb)), a)
                    for a in (side_a, not side_a)
                ]
            )
        got_rows = solve([q[0] for q in asks])
        again = [k for k, row in enumerate(got_rows) if row is None]
        for k, row in zip(again, solve([asks[k][1] for k in again]), strict=True):
            got_rows[k] = row
        for j, row in zip(spans, got_rows, strict=True):
            lo_row, hi_row = rows[j], rows[j + 1]
            if row is None or not lo_row.s < row.s < hi_row.s or row.s >= s[j + 1]:
                continue
            got = fit(row.s)
            v = row.values()
            bad = np.linalg.norm(got[:3] - v[:3]) > 0.1 * tol
            feet_off = max(np.linalg.norm(got[3:5] - v[3:5]), np.linalg.norm(got[5:] - v[5:]))
            bad |= feet_off > 0.02 * tol
            if bad or ds[j] > 3.0 * beside[j]:
                new.append(row)
        if not new:
            break
        rows = _monotone(rows + new, span)
    rows = _thinned(rows, _THIN * tol)
    if len(rows) < 4:
        return None
    rows_w = _pocket_params(rows)
    return PocketRows(
        el,
        rows_w / rows_w[-1],
        np.array([x.centre for x in rows]),
        np.array([x.r for x in rows]),
        np.array([x.foot_a for x in rows]),
        np.array([x.foot_b for x in rows]),
        np.array([wrap(x.ta) for x in rows]),
        np.array([wrap(x.tb) for x in rows]),
    )


@dataclass(frozen=True)
class _PocketRow:
    """A row of :func:`pocket_rows`: ``s`` how far its feet are from the maximum (0 at the
    centre of curvature, 1 at the branch point), ``ta``/``tb`` their parameters."""

    s: float
    ta: float
    tb: float
    centre: FloatArray
    r: float
    foot_a: FloatArray
    foot_b: FloatArray

    def values(self) -> FloatArray:
        return np.r_[self.centre, self.r, self.foot_a, self.foot_b]


def _pocket_params(rows: list[_PocketRow]) -> FloatArray:
    """The rows' ``s``, the branch point's placed where the rows' radius reaches its own.

    Its feet are only known to about the tolerance along the stretch (the stretch is
    nearly a circle about it: the radius is stationary in them), so its ``s`` (1) can be
    far beyond the last exact row while the centre moves on as before: the end row then
    sits where the radius, linear in ``s`` over the last two rows, reaches the node's."""
    s = np.array([x.s for x in rows])
    if len(rows) >= 4:
        (s0, r0), (s1, r1), rn = (rows[-3].s, rows[-3].r), (rows[-2].s, rows[-2].r), rows[-1].r
        if r1 > r0 and rn > r1:
            s[-1] = min(1.0, max(s1 + (rn - r1) * (s1 - s0) / (r1 - r0), s1 + 0.25 * (s1 - s0)))
    return s


_THIN = 1e-2  # rows closer than this many tol (centre and radius) to the one before: dropped


def _thinned(rows: list[_PocketRow], gap: float) -> list[_PocketRow]:
    """The rows without those within ``gap`` (centre and radius) of the row kept before
    them; the first and the last row always kept.

    Where the rows' radius does not reach the branch point's as their feet reach its
    feet (those feet are only known to about the tolerance), the refinement bisects
    towards the branch point round after round: rows 1e-10 apart, their difference
    rounding, and an interpolating spline through them swings off by thousands of tol
    (a blob's weak maximum by a branch point, 2026-12-06)."""
    out = [rows[0]]
    for x in rows[1:-1]:
        if np.linalg.norm(x.values()[:3] - out[-1].values()[:3]) >= gap:
            out.append(x)
    if len(out) > 1 and np.linalg.norm(rows[-1].values()[:3] - out[-1].values()[:3]) < gap:
        out.pop()
    return [*out, rows[-1]]


def _monotone(rows: list[_PocketRow], span: float) -> list[_PocketRow]:
    """The rows by ``s``, keeping only those whose feet both move away from the maximum.

    A partner's parameter is only good to about ``1e-7 span`` where it barely moves (the
    radius is stationary in it): a step back within ``1e-6 span`` (far below the
    tolerance on the curve) is rounding; a row stepping back further is dropped."""
    eps = 1e-6 * span
    rows = sorted(rows, key=lambda x: x.s)
    out = [rows[0]]
    for x in rows[1:-1]:
        last = out[-1]
        if x.ta <= last.ta + eps and x.tb >= last.tb - eps and last.s + 1e-12 < x.s < 1.0:
            out.append(x)
    last = rows[-1]
    while len(out) > 1 and not (out[-1].ta >= last.ta - eps and out[-1].tb <= last.tb + eps):
        out.pop()
    return [*out, last]


_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(8)  # the chords' quadrature
_GRID = 32  # bracketing samples of the stretch per partner search
_GOLDEN_STEPS = 44  # golden-section steps from a bracket of 2/_GRID: below 1e-10 of it


def _tangent_partners(
    bq: FloatArray,
    nq: FloatArray,
    tq: FloatArray,
    chords: Callable[[FloatArray, FloatArray], FloatArray],
    near: float,
    far: float,
) -> tuple[FloatArray, FloatArray]:
    """The disks tangent to the curve at points ``bq`` (inward normals ``nq``) that touch
    it again between parameters ``near`` (the maximum) and ``far`` (the branch point's
    foot): the partners' parameters and the radii, the least ``|q - b|^2 / (2 (q - b).n)``
    over the stretch (all searched together: the least of a grid, then golden sections
    on the bracket around it, so that the tolerance is relative to the stretch).

    NaN where no point of the stretch is on the inner side, or where the least is at
    ``near`` (the partner is on the foot's own half). A least at ``far`` is taken there:
    the branch point's feet are only known to about the tolerance along the stretch
    (the radius is stationary in them), so the rows next to it touch the curve at its
    foot or just past it, with a radius between the maximum's and the node's (checked
    by the caller)."""
    lo, hi = sorted((near, far))
    width = hi - lo
    m = len(bq)

    def f(y: FloatArray) -> FloatArray:  # y (m, k) offsets from lo
        q = chords(tq, lo + y)
        h = np.einsum("mkj,mj->mk", q, nq)
        qq = np.einsum("mkj,mkj->mk", q, q)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(h > 0.0, qq / (2.0 * h), np.inf)

    grid = np.linspace(0.0, width, _GRID + 1)
    fg = f(np.broadcast_to(grid, (m, _GRID + 1)))
    k = np.argmin(fg, axis=1)
    a = grid[np.maximum(k - 1, 0)]
    b = grid[np.minimum(k + 1, _GRID)]
    y, r = golden_minima(f, a, b, _GOLDEN_STEPS)
    off = y if near == lo else width - y  # from the maximum
    ok = np.isfinite(r) & (off > 1e-7 * width)
    return np.where(ok, lo + y, np.nan), np.where(ok, r, np.nan)


def golden_minima(
    f: Callable[[FloatArray], FloatArray],
    a: FloatArray,
    b: FloatArray,
    steps: int,
    rtol: float = 0.0,
) -> tuple[FloatArray, FloatArray]:
    """Golden-section minima of ``f`` on the brackets ``[a, b]`` of ``m`` rows, all rows
    searched together: ``f`` maps ``(m, k)`` abscissae to ``(m, k)`` values, one call a
    step. At most ``steps`` steps, fewer once every bracket is within ``rtol`` (relative,
    at least absolute). Returns the abscissae and the least values."""
    g = 0.5 * (np.sqrt(5.0) - 1.0)
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    c, d = b - g * (b - a), a + g * (b - a)
    fcd = f(np.column_stack([c, d]))
    fc, fd = fcd[:, 0], fcd[:, 1]
    for _ in range(steps):
        left = fc <= fd  # the least is in [a, d]
        b = np.where(left, d, b)
        a = np.where(left, a, c)
        c_new = np.where(left, b - g * (b - a), d)
        d_new = np.where(left, c, a + g * (b - a))
        fn = f(np.where(left, c_new, d_new)[:, None])[:, 0]
        fc, fd = np.where(left, fn, fd), np.where(left, fc, fn)
        c, d = c_new, d_new
        if rtol and np.all(b - a <= rtol * np.maximum(1.0, np.abs(a))):
            break
    return np.where(fc <= fd, c, d), np.minimum(fc, fd)
