"""Exact rows of a short branch from a branch point into a flat curvature maximum that
lies between two of its feet on one edge (a "pocket").

Such a branch (a blob's maximum 1e-3 wide between two feet of a branch point, the branch
~10 tol long) has few samples or none: the tracer's samples there osculate, and a
spline through its ends is off by several tol (the branch bends). Its rows are solved
here from the boundary stretch itself: each from a foot on either half of the stretch
(the least tangent-disk radius over the other half, a bounded Brent search), from the
half whose foot moves more; they are parametrized by how far their feet are from the
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

    def point(t: float) -> FloatArray:
        return np.asarray(curve.point(np.array([wrap(t)]))[0], dtype=float)

    memo: dict[tuple[float, bool], _PocketRow | None] = {}

    def solve(t: float, side_a: bool) -> _PocketRow | None:
        """The row whose foot on one half is ``t`` (its partner on the other half);
        remembered: a midpoint whose row was not taken is asked again next round."""
        key = (t, side_a)
        if key not in memo:
            memo[key] = _solve(t, side_a)
        return memo[key]

    def _solve(t: float, side_a: bool) -> _PocketRow | None:
        other = (t_cc, tb_end) if side_a else (ta_end, t_cc)
        x, r = _tangent_partner(boundary, e, wrap(t), point, other)
        if x is None or not cc.radius <= r <= bp.radius:
            # beyond the stretch, or larger than the branch point's disk (not maximal:
            # it reaches past the node's other feet)
            return None
        bq, nq, _ = boundary.frame_at(e, np.array([wrap(t)]))
        ta, tb = (t, x) if side_a else (x, t)
        fa_, fb_ = (bq[0], point(x)) if side_a else (point(x), bq[0])
        return _PocketRow((tb - ta) / span, ta, tb, bq[0] + r * nq[0], r, fa_, fb_)

    tip = np.asarray(cc.footpoints[0].point_2d, dtype=float)
    rows = [
        _PocketRow(0.0, t_cc, t_cc, np.asarray(cc.point_2d, float), cc.radius, tip, tip),
        _PocketRow(1.0, ta_end, tb_end, np.asarray(bp.point_2d, float), bp.radius,
                   np.asarray(fa.point_2d, float), np.asarray(fb.point_2d, float)),
    ]  # fmt: skip
    for g in np.arange(1, 8) / 8.0:
        for row in (
            solve(t_cc + (ta_end - t_cc) * g, True),
            solve(t_cc + (tb_end - t_cc) * g, False),
        ):
            if row is not None:
                rows.append(row)
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
        for j in range(len(rows) - 1):
            lo_row, hi_row = rows[j], rows[j + 1]
            if ds[j] < 1e-9:
                continue
            side_a = abs(hi_row.ta - lo_row.ta) >= abs(hi_row.tb - lo_row.tb)
            row = None
            for a in (side_a, not side_a):  # the other half where the partner is at its end
                row = solve(0.5 * ((lo_row.ta + hi_row.ta) if a else (lo_row.tb + hi_row.tb)), a)
                if row is not None:
                    break
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


def _tangent_partner(
    boundary: Boundary,
    e: Element,
    t: float,
    point: Callable[[float], FloatArray],
    other: tuple[float, float],
) -> tuple[float | None, float]:
    """The disk tangent to element ``e`` at parameter ``t`` (inside) that touches the curve
    again between parameters ``other``: the partner's parameter and the radius, the least
    ``|q - b|^2 / (2 (q - b).n)`` (a bounded Brent search over the offset from
    ``other[0]``, so that its tolerance is relative to the stretch); ``None`` when the
    least is at an end of the stretch (the partner is beyond it)."""
    from scipy.optimize import minimize_scalar

    bq, nq, _ = boundary.frame_at(e, np.array([t]))
    lo, hi = sorted(other)
    width = hi - lo

    def f(y: float) -> float:
        q = point(lo + y) - bq[0]
        h = float(q @ nq[0])
        return float(q @ q) / (2.0 * h) if h > 0 else np.inf

    res = minimize_scalar(f, bounds=(0.0, width), method="bounded", options={"xatol": 1e-15})
    y, r = float(res.x), float(res.fun)
    if not (np.isfinite(r) and 1e-7 * width < y < width * (1.0 - 1e-7)):
        return None, np.nan
    return lo + y, r
