"""The 3D MAT of a revolution (THEORY.md Sec. 2), as tensor B-spline patches.

Canonical coordinates: a profile point is ``q = (x, y)`` (``x`` the distance from the
axis, ``y`` along it) and ``X(q, phi) = O + y D + x (cos(phi) A + sin(phi) B)`` with the
reading's frame (``A = xdir``, ``D = ydir`` = axis, ``B = D x A``).

Per segment of the 2D MAT (``sigma = sin(Theta/2)``, ``Theta`` the angle):

- low (``r < x sigma`` or ``Theta > pi``): the revolved sheet ``X(c, phi)``,
  ``asin(r/x) <= phi <= Theta - asin(r/x)``; on each side a start cap sheet
  ``X(q, asin(d(q)/x))`` over the ruling ``q = f + t (c - f)`` (``d = t r``; sampled
  at equal steps of the angle) and the mirrored end cap sheet;
- high (small angles): the caps stop on the level curve ``d(q) = x sigma`` at
  ``phi = Theta/2``, which bounds the planar mid sheet;
- full revolutions: the revolved sheets only (in four quarter turns), no caps; a profile
  on the axis is first mirrored across it and the MAT of the whole meridian section is
  revolved (its parts on the axis stay curves);
- pie slices (a profile on the axis, ``Theta < 2 pi``; ``docs/pie_slices.md``): the
  mirrored section's MAT, cut also where it crosses the axis; its parts on the mirror's
  side and on the axis are no sheets (the axis is an edge of the solid), the caps stand
  on the profile's own feet, and the mid sheet reaches the axis, closed there by the
  profile's edges on it (rims). The distance is ``min(d(q), x sin(phi), x sin(Theta -
  phi))`` as for any partial revolution, ``d`` to the section's boundary (a mirrored edge
  is never nearer). At ``Theta = pi`` the caps are one plane: no mid sheet (its balls
  touch it at one point). Beyond ``pi`` the axis is a reflex edge: the cut is at ``r =
  x``, the caps end at 90 degrees on the level curve ``d(q) = x``, and that curve revolves
  on to ``Theta`` - 90 degrees (the balls touching the profile and the axis).

Every patch interpolates exact rows (one per 2D MAT sample ``w``): a cap's row is a grid
of points, a revolved sheet's row is its exact arc (``mat3d.arcs``: rational quadratic
pieces, interpolated across rows in homogeneous coordinates), so revolved sheets and their
rims lie on circles exactly. Patches that meet share the rows or arcs of their common
side, hence one edge.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import make_interp_spline

from medialcad.errors import UnsupportedSolidError
from medialcad.mat2d.graph import NodeKind
from medialcad.mat3d.arcs import arc_knots, arc_net, arc_pieces, arc_points, homogeneous
from medialcad.mat3d.segments import End, Segment, TouchFn, split_branches
from medialcad.recognition import Revolution

__all__ = ["revolution_parts"]

FloatArray = NDArray[np.float64]
_LINEAR = np.array([0.0, 0.0, 1.0, 1.0])


@dataclass(frozen=True)
class GridPatch:
    role: str
    w: FloatArray  # (nu,)
    v: FloatArray  # (nv,); of a rational patch: its arcs' knots (degree 2)
    points: FloatArray  # (nu, nv, 3); of a rational patch: each row's arc poles
    radius: FloatArray  # (nu, nv)
    bottom_key: tuple
    top_key: tuple
    left: tuple[str | None, float]  # (role of the u = 0 side, its radius)
    right: tuple[str | None, float]
    weights: FloatArray | None = None  # (nu, nv): rows are exact arcs (mat3d.arcs)


class _Canon:
    """Face-frame 2D <-> canonical (x, y) and canonical (x, y, phi) -> model space."""

    def __init__(self, reading: Revolution, frame2d: Any) -> None:
        f = reading.frame
        self.O, self.A, self.D = f.origin, f.xdir, f.ydir
        self.B = np.cross(self.D, self.A)
        o2 = frame2d.origin - self.O
        self.M = np.array(
            [
                [frame2d.xdir @ self.A, frame2d.ydir @ self.A],
                [frame2d.xdir @ self.D, frame2d.ydir @ self.D],
            ]
        )
        self.t = np.array([o2 @ self.A, o2 @ self.D])

    def xy(self, p: FloatArray) -> FloatArray:
        return np.asarray(np.asarray(p) @ self.M.T + self.t)

    def model(self, q: FloatArray, phi: FloatArray) -> FloatArray:
        q = np.asarray(q, dtype=float)
        phi = np.asarray(phi, dtype=float)
        x, y = q[..., 0:1], q[..., 1:2]
        c, s = np.cos(phi)[..., None], np.sin(phi)[..., None]
        return np.asarray(self.O + y * self.D + x * (c * self.A + s * self.B))


def _nv(span: float, x: float, tol: float) -> int:
    """Samples across an angular span so that cubic interpolation of a circle of radius
    ``x`` stays within ``tol`` (error about ``x step^4 / 384``)."""
    if span <= 0 or x <= 0:
        return 4
    step = (384.0 * tol / max(x, 1e-300)) ** 0.25
    return int(np.clip(math.ceil(span / max(step, 1e-3)), 3, 200)) + 1


def revolution_parts(reading: Revolution, mat2d: Any, diag: float, tol: float) -> tuple:
    """Sheets, seams, skeletal edges, rims, junctions and the compound of a revolution."""
    full = reading.full
    pie = reading.touches_axis and not full
    if reading.touches_axis:
        from medialcad.api import medial_axis_2d
        from medialcad.occ.recognize import mirrored_section

        mat2d = medial_axis_2d(mirrored_section(reading), tol=tol)
    cn = _Canon(reading, mat2d.frame)
    if reading.touches_axis and not full:
        _refuse_cusped_slice(mat2d, cn, diag)
    # a half turn read 1e-13 past 180 degrees is a half turn (its caps are one plane)
    theta = math.pi if abs(reading.angle - math.pi) <= 1e-9 else reading.angle
    # a pie slice wider than a half turn: its axis is a reflex edge, the caps stop on the
    # level curve d(q) = x at 90 degrees and that curve revolves on to Theta - 90 degrees
    wide = pie and theta > math.pi
    sigma = 1.0 if wide else math.sin(theta / 2.0)
    mid = not full and theta <= math.pi
    graph, boundary = mat2d.graph, mat2d.boundary

    def g_level(c: FloatArray, r: FloatArray) -> FloatArray:
        x = cn.xy(c)[:, 0]
        return np.asarray(r - x * sigma)

    def g_axis(c: FloatArray, r: FloatArray) -> FloatArray:
        x = cn.xy(c)[:, 0]
        return np.asarray(np.where(np.abs(x) < 1e-9 * diag, 0.0, x))

    def g_pie(c: FloatArray, r: FloatArray) -> FloatArray:
        return np.asarray(g_level(c, r) * g_axis(c, r))

    def cap_spec(s: Segment) -> _CapSpec | None:
        return _cap_spec(s, cn, sigma, mid or wide, pie, reading.touches_axis, tol)

    level = g_level if mid and mat2d.rmax > 0 else (g_axis if reading.touches_axis else None)
    if pie:
        level = g_pie
    # (a touch only of the mid sheet's own level: a pie slice's cuts are its product with
    # x, and the axis's own cuts are no level of the radius)
    touch = _touch(cn, theta, sigma, tol) if level is g_level else None
    segments = split_branches(graph, boundary, level, touch)
    if pie:
        segments = [_axis_ends(s, cn, tol) for s in segments]
    k_rev = arc_pieces(theta)  # a partial turn's revolved rows: arcs in k_rev pieces
    if not full:
        segments = [_angular_rows(s, cn, theta, k_rev, tol, cap_spec(s)) for s in segments]
    # one angular sampling for all patches, so that shared sides get identical samples
    xs = [np.abs(cn.xy(s.centre)[:, 0]).max() for s in segments] + [1e-300]
    xf = [np.abs(cn.xy(np.vstack([s.foot_a, s.foot_b]))[:, 0]).max() for s in segments] + [1e-300]
    xmax = float(max(max(xs), max(xf)))
    # circles of isolated curvature centres: far inside the solid's own tolerance; caps
    # only need a fraction of tol (revolved sheets are exact arcs across)
    nv_rev = _nv(math.pi / 2 if full else theta, xmax, 1e-3 * tol)
    nv_cap = max(_nv(math.pi / 2 if theta > math.pi else theta / 2, xmax, 0.05 * tol), 5)
    if not full:
        jobs = []
        for seg in segments:
            spec = cap_spec(seg)
            if spec is None:
                continue
            c = spec.centres(cn.xy(seg.centre))
            for k in spec.feet:
                foot = cn.xy((seg.foot_a, seg.foot_b)[k])
                jobs.append((seg, c, foot, seg.radius, theta, sigma, spec.high))
        nv_cap = _cap_nv(cn, jobs, nv_cap, 0.05 * tol)
    grids: list[GridPatch] = []
    offsets: list[tuple] = []
    junctions: list[tuple[FloatArray, float]] = []
    axis_lines: list[tuple[FloatArray, FloatArray, FloatArray]] = []
    for si, s in enumerate(segments):
        c = cn.xy(s.centre)
        r = s.radius
        if reading.touches_axis:
            if float(np.abs(c[:, 0]).max()) <= 10 * tol and not pie:
                # on the axis: a curve of the MAT (of a pie slice: its edge, where the mid
                # sheet ends; the caps of the foot on the profile's side still stand on it)
                if not s.single:
                    axis_lines.append((cn.model(c, np.zeros(len(c))), r, s.w))
                continue
            if _mirror_side(c, tol):
                continue
            c[:, 0] = np.maximum(c[:, 0], 0.0)
        fa, fb = cn.xy(s.foot_a), cn.xy(s.foot_b)
        if full:
            if not s.single:
                _full_sheets(grids, cn, si, s, c, r)
            continue
        spec = cap_spec(s)
        assert spec is not None  # segments on the mirror's side were skipped above
        if not spec.high and not s.single:
            _revolved_sheet(grids, junctions, cn, si, s, c, r, theta, k_rev, wide)
        for k in spec.feet:
            side, f = (("a", fa), ("b", fb))[k]
            top = _cap_sheets(
                grids, offsets, cn, si, side, s, c, f, r, theta, sigma, spec.high, nv_cap
            )
            if wide and spec.high:
                _level_sheet(grids, cn, (si, side), s.w, top, theta, k_rev)
    used = {n for b in graph.branches for n in (b.start, b.end) if n is not None}
    for nd in graph.nodes:
        if nd.index in used or nd.kind is not NodeKind.CURVATURE_CENTRE:
            continue
        cc = cn.xy(nd.point_2d[None, :])[0]
        rr = float(nd.radius)
        if abs(cc[0]) <= 10 * tol:  # a ball centred on the axis (a sphere): one point
            if pie:
                continue  # of a pie slice: a point of its edge
            junctions.append((cn.model(np.array([0.0, cc[1]]), np.array(0.0)), rr))
            continue
        if cc[0] < 0:
            continue
        if full:
            lo, hi = 0.0, 2 * math.pi
        elif not (mid or wide) or rr < cc[0] * sigma:
            phi0 = math.asin(min(rr / cc[0], 1.0))
            lo, hi = phi0, theta - phi0
        else:
            continue
        pieces = max(1, math.ceil((hi - lo) / (math.pi / 2)))
        for k in range(pieces):
            a = lo + (hi - lo) * k / pieces
            b = lo + (hi - lo) * (k + 1) / pieces
            w = np.linspace(0.0, 1.0, nv_rev)
            pts = cn.model(np.broadcast_to(cc, (nv_rev, 2)), a + w * (b - a))
            axis_lines.append((pts, np.full(nv_rev, rr), w))
    from medialcad.mat3d.assemble import build_grid_complex

    mid_plane = None
    mid_rims: list[tuple[FloatArray, FloatArray]] = []
    # a pie slice of 180 degrees has its caps in one plane: the balls at Theta/2 beyond the
    # level curve touch it at one point (on the axis), no mid sheet; its caps meet there
    flat = pie and abs(theta - math.pi) <= 1e-9
    if mid and offsets and not flat:
        a_mid = math.cos(theta / 2) * cn.A + math.sin(theta / 2) * cn.B
        mid_plane = (cn.O, a_mid, cn.D)
    if pie and mid and offsets and not flat:
        # the mid sheet of a pie slice reaches the axis along the profile's edges there
        from medialcad.occ.recognize import axis_intervals

        for y0, y1 in axis_intervals(reading, 10 * tol):
            ends = cn.model(np.array([[0.0, y0], [0.0, y1]]), np.zeros(2))
            mid_rims.append((ends[0], ends[1]))
    return build_grid_complex(
        grids,
        offsets,
        junctions,
        axis_lines,
        diag=diag,
        mid_plane=mid_plane,
        seam_roles=_flat_roles if flat or wide else _roles,
        mid_slope=sigma,
        mid_rims=mid_rims,
    )


def _refuse_cusped_slice(mat2d: Any, cn: _Canon, diag: float) -> None:
    """A partial revolution whose mirrored section has a reflex cusp on the axis (a
    profile edge along the axis left tangentially by its neighbours: a rounded rectangle
    revolved about one of its sides) is refused: the caps' level curve runs into the
    cusp, and such slices came out up to 1.2 tol unsound at 160 degrees and with free
    edges 0.05 to 0.12 diag off the boundary beyond 180. Its full turn is answered."""
    for c in mat2d.boundary.corners:
        on_axis = abs(float(cn.xy(c.point[None, :])[0, 0])) <= 1e-7 * diag
        if c.turn <= -math.pi + 1e-9 and on_axis:
            p = mat2d.frame.to_3d(c.point[None, :])[0]
            raise UnsupportedSolidError(
                "a partial revolution whose profile leaves its axis tangentially (at "
                f"({p[0]:.6g}, {p[1]:.6g}, {p[2]:.6g})) is not supported; its full turn is"
            )


def _touch(cn: _Canon, theta: float, sigma: float, tol: float) -> TouchFn:
    """Whether the level ``g = r - x sin(Theta/2)`` passes within the tolerance of a
    row (centre, radius and feet in the face frame) that it touches: lifted as a
    touch, one cut there, the row's caps end on ``Theta/2`` at its centre, not on the
    level curve, ``r g / (f_x sin(Theta/2))`` off (the ruling's length past the level
    curve), or for a dip below the level, a revolved sheet ``2 g / cos(Theta/2)`` wide
    is left out (its points ``g / cos(Theta/2)`` off). Within a tenth of ``tol`` it is a
    touch."""
    cos = math.cos(min(theta, math.pi) / 2.0)

    def touch(c: FloatArray, r: float, fa: FloatArray, fb: FloatArray) -> bool:
        x, xa, xb = cn.xy(np.vstack([c, fa, fb]))[:, 0]
        g = abs(r - x * sigma)
        foot = min(xa, xb) * sigma
        if foot <= 0 or cos <= 0 or x <= 10 * tol:  # (on the axis: a pie slice's axis cut)
            return False
        return g * max(r / foot, 1.0 / cos) <= 0.1 * tol

    return touch


def _roles(key: tuple) -> str | None:
    return {"SB": "seam", "ST": "seam", "OFF": "seam", "F0": "rim", "FL": "rim", "AXR": "rim"}.get(
        key[0]
    )


def _flat_roles(key: tuple) -> str | None:
    """A pie slice's caps of 180 degrees or more meet smoothly on the level curve (the
    ``OFF`` rows at 180, ``OFS``/``OFE`` rows beyond: each cap meets the level curve's
    revolved sheet there): no seam."""
    return None if key[0] in ("OFF", "OFS", "OFE") else _roles(key)


def _end_role(s: Segment, which: int, wide: bool = False) -> str | None:
    """The role of a revolved sheet's end side: by its node, and at a level end of a pie
    slice wider than 180 degrees (``wide``) the seam arc shared with two level sheets."""
    end = s.start if which == 0 else s.end
    if end.kind == "level" and wide:
        return "seam"
    if end.kind != "node":
        return None
    return (
        {
            NodeKind.BRANCH_POINT: "seam",
            NodeKind.CURVATURE_CENTRE: "skeletal",
            NodeKind.CONVEX_VERTEX: "rim",
        }[end.node_kind]
        if end.node_kind is not None
        else None
    )


def _mirror_side(c: FloatArray, tol: float) -> bool:
    """Centres (canonical) of a segment on the mirror's side of the axis (one on the axis
    is on the profile's side)."""
    return float(np.abs(c[:, 0]).max()) > 10 * tol and float(np.median(c[:, 0])) < 0


def _profile_side(feet: FloatArray, tol: float) -> bool:
    """Feet (canonical) of a pie slice's cap on the profile's side of the axis. Feet on the
    mirror's side belong to the mirror; feet all on the axis (a vertex of the profile
    there) have ``d >= x`` everywhere, beyond every cap's level curve: their cap is empty."""
    return float(np.max(feet[:, 0])) > 10 * tol


def _axis_ends(s: Segment, cn: _Canon, tol: float) -> Segment:
    """A pie slice's segment with its level ends on the axis (cuts where ``x = 0``, not
    ``r = x sin(Theta/2)``) marked ``"axis"``: the caps' rulings there stop on the level
    curve like anywhere else, they do not reach the centre."""
    ends = []
    for i, end in ((0, s.start), (-1, s.end)):
        on_axis = abs(float(cn.xy(s.centre[i : i + 1 if i == 0 else None])[0, 0])) <= tol
        ends.append(End("axis") if end.kind == "level" and on_axis else end)
    return replace(s, start=ends[0], end=ends[1])


def _angular_rows(
    s: Segment,
    cn: _Canon,
    theta: float,
    k: int,
    tol: float,
    caps: _CapSpec | None = None,
) -> Segment:
    """The segment with rows added (from its own interpolant, within 0.1 tol of exact)
    where the revolved sheet's points (its rows exact arcs in ``k`` pieces, interpolated
    in homogeneous coordinates), or the start cap's (``caps``), cubic across rows, leave
    their exact surfaces by more than 0.05 tol.

    A row of a partial revolution's sheet spans the angles ``asin(r/x)`` to ``theta -
    asin(r/x)``, which change fast next to a level end (the span is 0 there): across 4
    rows of a straight branch from a level end to a convex corner, the interpolated
    points cut inside their circles by 1.0 tol (a 28-degree revolution at a critical
    angle). A cap's points change fast where the disks nearly osculate the profile (the
    feet sweep along it while the centre hardly moves): between two rows 8e-6 apart in
    ``w`` a pie slice's cap read 2.5 tol off. The caps and the sheet share the rows, so
    their sides stay sewn (the end caps mirror the start caps across ``Theta/2``)."""
    if s.single or len(s.w) < 2:
        return s
    v = np.array([0.0, 0.25, 0.5, 0.75, 1.0])
    t = np.linspace(0.0, 1.0, 4 * k + 1)  # the arcs' ends, quarters and middles
    inner = replace(s, start=End("inner"), end=End("inner"))  # rows between the ends

    def arcs(rows: FloatArray) -> FloatArray:
        xy, r = cn.xy(rows[:, :2]), rows[:, 2]
        phi0 = _start_angle(r, xy[:, 0], theta)
        return homogeneous(*arc_net(cn.model, xy, phi0, np.maximum(theta - 2 * phi0, 0.0), k))

    def cap_points(rows: FloatArray, seg: Segment) -> FloatArray:
        assert caps is not None
        xy, r = cn.xy(rows[:, :2]), rows[:, 2]
        c = caps.centres(xy)
        out = []
        for j in caps.feet:
            f = cn.xy(rows[:, 3 + 2 * j : 5 + 2 * j])
            q, ph, _ = _cap_grid(seg, c, f, r, theta, caps.sigma, caps.high, v)
            out.append(cn.model(q, ph))
        return np.concatenate(out, axis=1)

    w, rows = s.w, np.column_stack([s.centre, s.radius, s.foot_a, s.foot_b])
    for _ in range(12):
        ku = min(3, len(w) - 1)
        wm = 0.5 * (w[1:] + w[:-1])
        mid = make_interp_spline(w, rows, k=ku)(wm)
        fit = arc_points(make_interp_spline(w, arcs(rows), k=ku, axis=0)(wm), t)
        err = np.linalg.norm(fit - arc_points(arcs(mid), t), axis=2).max(axis=1)
        if caps is not None and caps.feet:
            fit = make_interp_spline(w, cap_points(rows, s), k=ku, axis=0)(wm)
            cap_err = np.linalg.norm(fit - cap_points(mid, inner), axis=2).max(axis=1)
            err = np.maximum(err, cap_err)
        bad = (err > 0.05 * tol) & (np.diff(w) > 1e-8)
        if not np.any(bad) or len(w) > 800:
            break
        idx = np.nonzero(bad)[0]
        w = np.insert(w, idx + 1, wm[idx])
        rows = np.insert(rows, idx + 1, mid[idx], axis=0)
    if len(w) == len(s.w):
        return s
    return replace(
        s, w=w, centre=rows[:, :2], radius=rows[:, 2], foot_a=rows[:, 3:5], foot_b=rows[:, 5:7]
    )


@dataclass(frozen=True)
class _CapSpec:
    """How a segment's caps are built: ``sin(Theta/2)``, whether they stop on the level
    curve (``high``), which feet (0: ``a``, 1: ``b``) have caps, and whether the centres
    are clamped to ``x >= 0`` (a profile on the axis)."""

    sigma: float
    high: bool
    feet: tuple[int, ...]
    clamp: bool

    def centres(self, c: FloatArray) -> FloatArray:
        """The caps' centres: ``c`` (canonical ``(x, y)``), clamped if need be."""
        out = np.array(c, dtype=float)
        if self.clamp:
            out[:, 0] = np.maximum(out[:, 0], 0.0)
        return out


def _cap_spec(
    s: Segment,
    cn: _Canon,
    sigma: float,
    mid: bool,
    pie: bool,
    touches_axis: bool,
    tol: float,
) -> _CapSpec | None:
    """The caps of a partial revolution's segment ``s`` (``None``: none, a segment on
    the mirrored section's side). A cap stops on the level curve ``r = x sin(Theta/2)``
    when the segment lies beyond it (``high``, only with a mid sheet: ``Theta <= 180``);
    a one-sided segment has the cap of its foot ``a`` only, and a pie slice's caps stand
    only on feet on the profile's own side."""
    c = cn.xy(s.centre)
    if touches_axis and _mirror_side(c, tol):
        return None
    x = np.maximum(c[:, 0], 0.0) if touches_axis else c[:, 0]
    g = s.radius - x * sigma
    # by the rows off the level: a short segment between two level ends (one row between
    # them, g = [0, 2.1e-5, 0]) had median 0 and came out low, a revolved sheet of area
    # 1.4e-14 where the caps meet the mid sheet
    inner = np.ones(len(g), dtype=bool)
    inner[[0, -1]] = [s.start.kind != "level", s.end.kind != "level"]
    high = mid and float(np.median(g[inner] if np.any(inner) else g)) > 0
    feet = tuple(
        k
        for k, f in enumerate((s.foot_a, s.foot_b)[: 1 if s.single else 2])
        if not pie or _profile_side(cn.xy(f), tol)
    )
    return _CapSpec(sigma, high, feet, touches_axis)


def _revolved_sheet(
    grids: list[GridPatch],
    junctions: list[tuple[FloatArray, float]],
    cn: _Canon,
    si: int,
    s: Segment,
    c: FloatArray,
    r: FloatArray,
    theta: float,
    k: int,
    wide: bool = False,
) -> None:
    """A segment's revolved sheet; ``wide``: a pie slice wider than 180 degrees, where a
    level end is an arc (from 90 degrees to ``Theta`` - 90), a seam with the level
    curve's revolved sheets on either side, not a point."""
    phi0 = _start_angle(r, c[:, 0], theta)
    _level_rows_at_half_angle(phi0, s, theta)
    span = np.maximum(theta - 2 * phi0, 0.0)
    pts, wts = arc_net(cn.model, c, phi0, span, k)
    rad = np.broadcast_to(r[:, None], wts.shape).copy()
    grids.append(
        GridPatch(
            "revolved",
            s.w,
            arc_knots(k),
            pts,
            rad,
            ("SB", si),
            ("ST", si),
            (_end_role(s, 0, wide), float(r[0])),
            (_end_role(s, 1, wide), float(r[-1])),
            wts,
        )
    )
    for i, end in ((0, s.start), (-1, s.end)):
        if (end.kind == "node" and end.node_kind is NodeKind.BRANCH_POINT) or (
            wide and end.kind == "level"
        ):
            junctions.append((pts[i, 0], float(r[i])))
            junctions.append((pts[i, -1], float(r[i])))
        elif end.kind == "level":
            junctions.append((pts[i, 0], float(r[i])))


def _level_sheet(
    grids: list[GridPatch],
    cn: _Canon,
    key: tuple,
    w: FloatArray,
    level: tuple,
    theta: float,
    k: int,
) -> None:
    """The level curve ``d(q) = x`` (``level``: its points ``q`` and distances ``d``, one a
    row ``w``) where a high segment's cap ends, revolved from 90 degrees to ``Theta`` - 90
    (a pie slice wider than 180 degrees): the balls there touch the profile and the axis,
    the solid's reflex edge; radius ``x``. ``key``: the cap's ``(segment, side)``."""
    q, d = level
    n = len(q)
    pts, wts = arc_net(cn.model, q, np.full(n, 0.5 * math.pi), np.full(n, theta - math.pi), k)
    rad = np.broadcast_to(d[:, None], wts.shape).copy()
    bottom, top = ("OFS", *key), ("OFE", *key)
    grids.append(
        GridPatch("revolved", w, arc_knots(k), pts, rad, bottom, top, (None, 0.0), (None, 0.0), wts)
    )


def _full_sheets(
    grids: list[GridPatch], cn: _Canon, si: int, s: Segment, c: FloatArray, r: FloatArray
) -> None:
    """A full turn's revolved sheet of segment ``s``, in four quarter turns (one exact
    rational arc a row)."""
    n = len(c)
    for k in range(4):
        pts, wts = arc_net(cn.model, c, np.full(n, 0.5 * math.pi * k), np.full(n, 0.5 * math.pi), 1)
        if k == 3:  # the last quarter ends on the first one's row exactly
            pts[:, -1] = cn.model(c, np.zeros(n))
        rad = np.broadcast_to(r[:, None], wts.shape).copy()
        grids.append(
            GridPatch(
                "revolved",
                s.w,
                arc_knots(1),
                pts,
                rad,
                ("ROW", si, k),
                ("ROW", si, (k + 1) % 4),
                (_end_role(s, 0), float(r[0])),
                (_end_role(s, 1), float(r[-1])),
                wts,
            )
        )


def _cap_grid(
    s: Segment,
    c: FloatArray,
    f: FloatArray,
    r: FloatArray,
    theta: float,
    sigma: float,
    high: bool,
    v: FloatArray,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Profile points ``q``, angles ``phi`` and distances ``d`` of a start cap grid.

    Each row is the ruling ``q = f + t (c - f)`` (``d = t r``) from its foot to its centre
    (to the level curve ``d = x sigma`` when ``high``), sampled at equal steps of the cap's
    angle ``phi = asin(d/x)``: ``v`` is the fraction of the row's end angle, and ``t``
    solves ``sin(phi) = t r / (f_x + t (c_x - f_x))``. Equal steps in ``t`` crowded the
    angle into a layer at the foot (``dphi/dt = r / f_x``) and, where a cap meets its level
    curve at 90 degrees (``asin`` steep next to 1), into a square root there: 513 samples
    across every cap of a 270-degree pin (a 60 MB STEP); in the angle the cap is smooth."""
    n = len(c)
    fx, cx = f[:, 0], c[:, 0]
    if high:
        # t* where the ruling meets the level curve d = x sigma
        den = r - (cx - fx) * sigma
        tstar = np.clip(fx * sigma / np.where(np.abs(den) > 1e-300, den, 1e-300), 0.0, 1.0)
        end_phi = np.full(n, min(theta, math.pi) / 2.0)  # asin(sigma)
        for i, end in ((0, s.start), (-1, s.end)):
            if end.kind == "level":
                tstar[i] = 1.0
    else:
        tstar = np.ones(n)
        end_phi = _start_angle(r, cx, theta)
        _level_rows_at_half_angle(end_phi, s, theta)
    phi = v[None, :] * end_phi[:, None]
    sn = np.sin(phi)
    den = r[:, None] - (cx - fx)[:, None] * sn
    ok = (den > 1e-12 * np.maximum(r, 1e-300)[:, None]) & (r[:, None] > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(ok, fx[:, None] * sn / np.where(ok, den, 1.0), v[None, :] * tstar[:, None])
    t = np.clip(t, 0.0, tstar[:, None])
    ends = v[-1] == 1.0  # the last column is the seam or the level curve: exact values
    if ends:
        t[:, -1] = tstar
    q = f[:, None, :] + t[..., None] * (c - f)[:, None, :]
    if ends:
        last = tstar == 1.0  # the ruling reaches the centre (a low row, a level end)
        q[last, -1, :] = c[last]
    d = t * r[:, None]
    return q, phi, d


def _start_angle(r: FloatArray, x: FloatArray, theta: float) -> FloatArray:
    """``asin(r/x)``, where a revolved sheet's rows start (its caps' rows end), at most
    ``Theta/2``: a row beyond the level by a rounding or at a touch (:func:`_touch`)
    has no revolved sheet, its start and end caps meet at ``Theta/2``, not past it."""
    phi = np.arcsin(np.clip(r / np.maximum(x, 1e-300), 0.0, 1.0))
    return np.asarray(np.minimum(phi, 0.5 * theta))


def _level_rows_at_half_angle(phi: FloatArray, s: Segment, theta: float) -> None:
    """Set ``phi`` (one value a row) to ``Theta/2`` at the segment's level ends, where
    ``r = x sin(Theta/2)`` holds exactly: ``asin(r/x)`` of the solved rows is off by
    ``~sqrt(eps)`` there at 180 degrees (``asin`` is steep next to 1), which left a
    sliver of a revolved sheet between its seams and an offset row that did not meet."""
    for i, end in ((0, s.start), (-1, s.end)):
        if end.kind == "level":
            phi[i] = min(theta, math.pi) / 2.0


def _cap_nv(cn: _Canon, jobs: list[tuple], base: int, tol: float) -> int:
    """Fewest samples across the caps (one count for all: shared sides) for which cubic
    interpolation across every cap stays within ``tol`` at the midpoints."""
    nv = base
    while nv < 400:
        v = np.linspace(0.0, 1.0, nv)
        vm = 0.5 * (v[1:] + v[:-1])
        worst = 0.0
        for seg, c, f, r, th, sg, hi in jobs:
            q, phi, _ = _cap_grid(seg, c, f, r, th, sg, hi, v)
            qm, phim, _ = _cap_grid(seg, c, f, r, th, sg, hi, vm)
            pts, exact = cn.model(q, phi), cn.model(qm, phim)
            fit = make_interp_spline(v, pts, k=min(3, nv - 1), axis=1)(vm)
            worst = max(worst, float(np.linalg.norm(fit - exact, axis=-1).max()))
        if worst <= tol:
            return nv
        nv = 2 * nv - 1
    return nv


def _cap_sheets(
    grids: list[GridPatch],
    offsets: list[tuple],
    cn: _Canon,
    si: int,
    side: str,
    s: Segment,
    c: FloatArray,
    f: FloatArray,
    r: FloatArray,
    theta: float,
    sigma: float,
    high: bool,
    nv: int,
) -> tuple[FloatArray, FloatArray]:
    """The start and end caps on foot ``f``; returns their top row's profile points and
    distances (of a high cap: the level curve where it ends)."""
    v = np.linspace(0.0, 1.0, nv)
    q, phi, d = _cap_grid(s, c, f, r, theta, sigma, high, v)
    wide = theta > math.pi  # (high caps of a pie slice): each meets its own level sheet
    start_top = ("OFS" if wide else "OFF", si, side)
    end_top = ("OFE" if wide else "OFF", si, side)
    for cap, ph, rim_key, top_key in (
        ("start", phi, ("F0", si, side), ("SB", si) if not high else start_top),
        ("end", theta - phi, ("FL", si, side), ("ST", si) if not high else end_top),
    ):
        pts = cn.model(q, ph)
        grids.append(GridPatch("cap", s.w, v, pts, d, rim_key, top_key, (None, 0.0), (None, 0.0)))
        del cap
    if high and not wide:
        offsets.append(("OFF", si, side))
    return q[:, -1], d[:, -1]


def interp_grid(
    w: FloatArray, v: FloatArray, values: FloatArray
) -> tuple[FloatArray, FloatArray, int, int, FloatArray]:
    """Tensor interpolation: knots in u and v, degrees, poles."""
    ku = int(min(3, len(w) - 1))
    kv = int(min(3, len(v) - 1))
    su = make_interp_spline(w, values, k=ku, axis=0)
    sv = make_interp_spline(v, su.c, k=kv, axis=1)  # its coefficients come axis-first
    return np.asarray(su.t), np.asarray(sv.t), ku, kv, np.moveaxis(np.asarray(sv.c), 0, 1)
