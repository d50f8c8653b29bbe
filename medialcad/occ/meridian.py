"""The exact meridian section of a full revolution.

A full revolution has no cap to read the profile from: it is cut by a half-plane through
the axis (a Boolean common). OCC's plane/surface intersection approximates where a face
is a general surface of revolution (a B-spline profile revolved: the section is a
128-pole B-spline that closes with a tangent kink, which the 2D MAT then reads as a
corner). On such a face the section is known exactly: the surface's iso-curve at the
angle of the half-plane (the basis curve, rotated). :func:`exact_meridian` rebuilds the
Boolean section with those curves, edge by edge, and keeps the Boolean's own edges
elsewhere (lines and circles of analytic faces are exact already).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeVertex,
    BRepBuilderAPI_MakeWire,
)
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepTools import BRepTools, BRepTools_WireExplorer
from OCP.Geom import (
    Geom_BSplineSurface,
    Geom_ConicalSurface,
    Geom_CylindricalSurface,
    Geom_RectangularTrimmedSurface,
    Geom_SphericalSurface,
    Geom_SurfaceOfRevolution,
    Geom_ToroidalSurface,
)
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
from OCP.gp import gp_Pnt, gp_Vec
from OCP.GProp import GProp_GProps
from OCP.ShapeAnalysis import ShapeAnalysis_Surface
from OCP.TopAbs import TopAbs_FORWARD, TopAbs_REVERSED, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Vertex

from medialcad.frame import Frame
from medialcad.occ.io import is_occ_exception

__all__ = ["exact_meridian", "face_of_edges", "iso_section"]

FloatArray = NDArray[np.float64]
log = logging.getLogger(__name__)
_SWEPT = (
    Geom_SurfaceOfRevolution,
    Geom_CylindricalSurface,
    Geom_ConicalSurface,
    Geom_SphericalSurface,
    Geom_ToroidalSurface,
)


class _RebuildError(Exception):
    """The exact section could not be assembled (the Boolean's is kept)."""


@dataclass(frozen=True)
class _Piece:
    """One edge of a section wire, in wire order: its curve, the parameters at its start
    and end (in wire order; ``t0 > t1`` when the wire runs against the curve), the two
    points, and whether the curve is an exact iso-curve."""

    curve: Any
    t0: float
    t1: float
    start: FloatArray
    end: FloatArray
    exact: bool


def _xyz(p: Any) -> FloatArray:
    return np.array([p.X(), p.Y(), p.Z()], dtype=float)


def _value(curve: Any, t: float) -> FloatArray:
    return _xyz(curve.Value(float(t)))


def _revolution_surfaces(
    faces: list[TopoDS_Face], frame: Frame, tol: float
) -> list[tuple[Any, tuple[float, ...], bool]]:
    """The surfaces of ``faces`` whose iso-curves may be meridians: ``(surface, its face's
    uv bounds, swept)``. Swept: surfaces of revolution, cylinders, cones, spheres and tori
    on the solid's axis, whose first parameter is the angle about it. Not swept: B-spline
    surfaces (a revolution written as NURBS, whose rational form keeps its iso-curves of
    one direction exactly planar meridians; which direction, and whether at all, is
    checked on the curve found)."""
    out: list[tuple[Any, tuple[float, ...], bool]] = []
    for f in faces:
        s = BRep_Tool.Surface_s(f)
        if isinstance(s, Geom_RectangularTrimmedSurface):
            s = s.BasisSurface()
        if isinstance(s, Geom_BSplineSurface):
            out.append((s, tuple(BRepTools.UVBounds_s(f)), False))
            continue
        if not isinstance(s, _SWEPT) or not _coaxial(s, frame, tol):
            continue
        out.append((s, tuple(BRepTools.UVBounds_s(f)), True))
    return out


def _coaxial(s: Any, frame: Frame, tol: float) -> bool:
    """Whether the swept surface ``s`` turns about the frame's axis (``y``)."""
    ax = s.Axis()
    d = _xyz(ax.Direction())
    off = _xyz(ax.Location()) - frame.origin
    return bool(
        np.linalg.norm(np.cross(d, frame.ydir)) <= 1e-9
        and np.linalg.norm(off - (off @ frame.ydir) * frame.ydir) <= tol
    )


def _tangent(curve: Any, t: float) -> FloatArray:
    p, v = gp_Pnt(), gp_Vec()
    curve.D1(float(t), p, v)
    return np.array([v.X(), v.Y(), v.Z()], dtype=float)


def _project(curve: Any, p: FloatArray) -> tuple[float, float]:
    """Parameter and distance of the nearest point of ``curve`` to ``p``."""
    proj = GeomAPI_ProjectPointOnCurve(gp_Pnt(*p), curve)
    if proj.NbPoints() == 0:
        return math.nan, math.inf
    return float(proj.LowerDistanceParameter()), float(proj.LowerDistance())


def _angle(surface: Any, u: float, v: float, frame: Frame) -> float:
    """The angle of the surface point ``(u, v)`` about the axis, from the section plane
    (the frame: x radial, y along the axis, z normal to the section plane)."""
    q = _value(surface.UIso(u), v) - frame.origin
    return math.atan2(float(q @ frame.zdir), float(q @ frame.xdir))


def _swept_iso(s: Any, u: float, v: float, frame: Frame) -> Any:
    """The meridian of a swept surface in the section plane: its first parameter is the
    angle (the sense of u about the frame's axis read off the surface itself: a mirrored
    placement turns the other way)."""
    return s.UIso(_swept_angle_param(s, u, v, frame, steps=2))


def _planar_isos(
    s: Any, u: float, v: float, bounds: tuple[float, ...], frame: Frame, tol: float
) -> list[tuple[Any, tuple[float, float]]]:
    """The iso-curves of a B-spline surface through the section plane near ``(u, v)``
    that lie in that plane (within a thousandth of ``tol``), with their parameter range:
    the surface's meridians where it is a revolution in rational form. The iso's
    parameter is solved (secant steps) so that its point at ``(u, v)`` lies in the plane."""
    u0, u1, v0, v1 = bounds
    u_lo, u_hi, v_lo, v_hi = s.Bounds()
    out = []
    size = 1.0 + float(np.linalg.norm(frame.origin))
    for v_iso in (False, True):  # the u-iso (a curve in v), then the v-iso
        if v_iso:
            p, q, lo, hi, iso_of = v, u, u0, u1, s.VIso
        else:
            p, q, lo, hi, iso_of = u, v, v0, v1, s.UIso

        def off(x: float, v_iso: bool = v_iso, q: float = q) -> float:
            pt = s.Value(q, x) if v_iso else s.Value(x, q)
            return float((_xyz(pt) - frame.origin) @ frame.zdir)

        try:
            x = _secant_root(off, p, size)
            if x is None:
                continue
            k0, k1, periodic = (
                (u_lo, u_hi, s.IsUPeriodic()) if not v_iso else (v_lo, v_hi, s.IsVPeriodic())
            )
            if periodic:
                x = k0 + (x - k0) % (k1 - k0)
            elif not k0 <= x <= k1:
                continue  # off the surface: an extrapolated curve is no meridian
            iso = iso_of(float(x))
            pts = np.array([_value(iso, t) for t in np.linspace(lo, hi, 17)])
        except Exception as err:  # an OCC failure costs this iso-curve only
            if not is_occ_exception(err):
                raise
            continue
        if float(np.abs((pts - frame.origin) @ frame.zdir).max()) <= 1e-3 * tol:
            out.append((iso, (lo, hi)))
    return out


def _secant_root(f: Any, x: float, size: float) -> float | None:
    """A root of ``f`` near ``x`` by secant steps, or None where they do not converge
    (to ``1e-12`` of ``size``)."""
    x0, f0 = x, f(x)
    x1 = x + 1e-6 * (1.0 + abs(x))
    f1 = f(x1)
    for _ in range(30):
        if f1 == f0 or abs(f1) <= 1e-15 * size:
            break
        x0, x1, f0 = x1, x1 - f1 * (x1 - x0) / (f1 - f0), f1
        if not math.isfinite(x1):
            return None
        f1 = f(x1)
    return x1 if math.isfinite(f1) and abs(f1) <= 1e-12 * size else None


def _iso_piece(
    surfaces: list[tuple[Any, tuple[float, ...], bool]],
    old: _Piece,
    frame: Frame,
    tol: float,
) -> _Piece | None:
    """The exact iso-curve piece replacing ``old``, if ``old`` lies on one of ``surfaces``."""
    mid_t = 0.5 * (old.t0 + old.t1)
    mid = _value(old.curve, mid_t)
    for s, bounds, swept in surfaces:
        sas = ShapeAnalysis_Surface(s)
        uv = sas.ValueOfUV(gp_Pnt(*mid), tol)
        if sas.Gap() > tol:
            continue
        u, v = uv.X(), uv.Y()
        # the half-plane's angle exactly: the iso-curve turned into the section plane
        if swept:
            isos = [(_swept_iso(s, u, v, frame), (bounds[2], bounds[3]))]
        else:
            isos = _planar_isos(s, u, v, bounds, frame, tol)
        for iso, ends in isos:
            got = _along(iso, ends, old, mid_t, mid, frame, tol)
            if got is not None:
                return got
    return None


def _along(
    iso: Any,
    ends: tuple[float, float],
    old: _Piece,
    mid_t: float,
    mid: FloatArray,
    frame: Frame,
    tol: float,
) -> _Piece | None:
    """The piece of ``iso`` (parameter range ``ends`` on its face) running along ``old``."""
    v0, v1 = ends
    closed = bool(np.linalg.norm(old.start - old.end) <= tol)
    tm, dm = _project(iso, mid)
    if dm > tol:
        return None
    forward = (
        float(_tangent(iso, tm) @ _tangent(old.curve, mid_t)) * (1.0 if old.t1 > old.t0 else -1.0)
        > 0
    )
    if closed:
        a, b = (v0, v1) if forward else (v1, v0)
    else:
        a, da = _project(iso, old.start)
        b, db = _project(iso, old.end)
        if max(da, db) > tol:
            return None
        # a section vertex lies on a circle where faces meet, the end of the face's
        # v-range: there exactly (the Boolean's vertex is off by up to its tolerance)
        a, b = (_snap(iso, x, (v0, v1), tol) for x in (a, b))
        snapped = (a, b)
        a, b = (_to_axis(iso, x, (a, b), frame, tol) for x in (a, b))
        moved = (a != snapped[0], b != snapped[1])
        period = iso.Period() if iso.IsPeriodic() else None
        if period is None and np.linalg.norm(_value(iso, v0) - _value(iso, v1)) <= tol:
            # a closed meridian on a non-periodic curve (a whole circle revolved): a piece
            # ending at its seam ends at whichever end of the range follows on
            if forward and b <= a:
                b, a = (v1, a) if b == v0 else (b, v0 if a == v1 else a)
            elif not forward and a <= b:
                a, b = (v1, b) if a == v0 else (a, v0 if b == v1 else b)
        if (b <= a) if forward else (a <= b):
            if period is None:
                return None
            if forward:
                b += period
            else:
                a += period
    # the replacement must run along the old edge
    # (a point past the old edge's end has no normal projection on it: its end counts)
    # (and an end moved onto the axis is checked where the Boolean's edge ended)
    ts = np.linspace(a, b, 9)
    if not closed:
        ts[0], ts[-1] = (snapped[0] if moved[0] else a), (snapped[1] if moved[1] else b)
    for t in ts:
        q = _value(iso, t)
        near = min(np.linalg.norm(q - old.start), np.linalg.norm(q - old.end))
        if min(_project(old.curve, q)[1], float(near)) > tol:
            return None
    return _Piece(iso, a, b, _value(iso, a), _value(iso, b), True)


def _to_axis(curve: Any, t: float, piece: tuple[float, float], frame: Frame, tol: float) -> float:
    """``t``, or where the meridian ``curve`` touches the axis next to it: a profile
    touching its axis at one point (a circle tangent to it, revolved: the solid is
    pinched there) leaves the Boolean's section vertex at the pole up to the vertex's
    tolerance off it (1.2e-4 along a circle of radius 1.8), and the two meridian pieces
    either side of the pole, one circle, met there with a gap and a kink the 2D MAT read
    as a convex corner with a spoke (4.8e-2 diag unsound). The point of the curve nearest
    the axis within a thousandth of the piece's parameter range (the least signed
    distance, the slope of which changes sign exactly there: the distance itself is flat
    at a tangency, and an axis read 1e-11 off made two crossings of it), when it is on
    the axis (within ``tol``) and the point at ``t`` is within 1e-3 of the piece's size."""
    from scipy.optimize import brentq, minimize_scalar

    mid = _value(curve, 0.5 * (piece[0] + piece[1])) - frame.origin
    side = 1.0 if float(mid @ frame.xdir) >= 0 else -1.0

    def x(u: float) -> float:
        return side * float((_value(curve, u) - frame.origin) @ frame.xdir)

    span = abs(piece[1] - piece[0])
    pts = [_value(curve, u) for u in np.linspace(piece[0], piece[1], 9)]
    size = max(float(np.linalg.norm(p - pts[0])) for p in pts)
    here = x(t)
    if span <= 0 or abs(here) > 1e-3 * size or abs(float(mid @ frame.xdir)) <= tol:
        return t  # far from the axis, or a piece along it
    w = 1e-3 * span
    lo, hi = max(t - w, curve.FirstParameter()), min(t + w, curve.LastParameter())
    if not lo < hi:
        return t

    def slope(v: float) -> float:
        return side * float(_tangent(curve, v) @ frame.xdir)

    got = minimize_scalar(x, bounds=(lo, hi), method="bounded", options={"xatol": 1e-14 * span})
    u = float(got.x)
    if not abs(x(u)) <= tol:
        return t
    # a touching point is a minimum inside: the slope changes sign there (an edge
    # ending on the axis at an angle, its curve going on across it, has none)
    for k in range(1, 12):
        d = 1e-12 * span * 10.0**k
        a, b = max(u - d, lo), min(u + d, hi)
        if slope(a) < 0 < slope(b):
            return float(brentq(slope, a, b, xtol=1e-15 * span))
    return t


def _snap(curve: Any, t: float, ends: tuple[float, float], tol: float) -> float:
    here = _value(curve, t)
    for e in ends:
        if np.linalg.norm(_value(curve, e) - here) <= tol:
            return e
    return t


def _pieces(wire: Any, face: TopoDS_Face) -> list[_Piece]:
    out = []
    ex = BRepTools_WireExplorer(TopoDS.Wire_s(wire), face)
    while ex.More():
        e = ex.Current()
        c = BRep_Tool.Curve_s(e, 0.0, 0.0)
        f, l = BRep_Tool.Range_s(e)
        if e.Orientation() == TopAbs_REVERSED:
            f, l = l, f
        out.append(_Piece(c, f, l, _value(c, f), _value(c, l), False))
        ex.Next()
    return out


def _vertex(p: FloatArray, tol: float) -> TopoDS_Vertex:
    v = BRepBuilderAPI_MakeVertex(gp_Pnt(*p)).Vertex()
    BRep_Builder().UpdateVertex(v, tol)
    return v


def _wire(pieces: list[_Piece], tol: float) -> Any:
    n = len(pieces)
    verts = []
    for i in range(n):  # the vertex where piece i starts (and piece i - 1 ends)
        prev, cur = pieces[i - 1], pieces[i]
        p = cur.start if cur.exact or not prev.exact else prev.end
        gap = max(float(np.linalg.norm(cur.start - p)), float(np.linalg.norm(prev.end - p)))
        verts.append(_vertex(p, max(1.5 * gap, 1e-7)))
    mk = BRepBuilderAPI_MakeWire()
    for i, pc in enumerate(pieces):
        vs, ve = verts[i], verts[(i + 1) % n]
        if pc.t0 < pc.t1:
            e: TopoDS_Edge = BRepBuilderAPI_MakeEdge(pc.curve, vs, ve, pc.t0, pc.t1).Edge()
        else:
            e = TopoDS.Edge_s(
                BRepBuilderAPI_MakeEdge(pc.curve, ve, vs, pc.t1, pc.t0).Edge().Reversed()
            )
        mk.Add(e)
        if not mk.IsDone():
            raise _RebuildError("the rebuilt section wire does not connect")
    return mk.Wire()


def _area(face: TopoDS_Face) -> float:
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(face, props, 1e-9)
    return float(props.Mass())


def exact_meridian(
    section: TopoDS_Face, solid_faces: list[TopoDS_Face], frame: Frame, tol: float
) -> TopoDS_Face:
    """``section`` with every edge that lies on a surface of revolution replaced by that
    surface's exact iso-curve. ``section`` itself when none does, or when the rebuilt face
    fails OCC's check or differs in area (then the Boolean's curves are kept)."""
    try:
        surfaces = _revolution_surfaces(solid_faces, frame, tol)
        if not surfaces:
            return section
        # the wires as the plane sees them (a REVERSED face runs them the other way)
        fwd = TopoDS.Face_s(section.Oriented(TopAbs_FORWARD))
        wires, replaced = [], 0
        outer = BRepTools.OuterWire_s(fwd)
        holes: list[Any] = []
        ex = TopExp_Explorer(fwd, TopAbs_WIRE)
        while ex.More():
            if not ex.Current().IsSame(outer):
                holes.append(ex.Current())
            ex.Next()
        for w in [outer, *holes]:
            pieces = []
            for pc in _pieces(w, fwd):
                new = _iso_piece(surfaces, pc, frame, tol)
                replaced += new is not None
                pieces.append(new or pc)
            wires.append(_wire(pieces, tol))
        if not replaced:
            return section
        plane = BRep_Tool.Surface_s(fwd)
        mk = BRepBuilderAPI_MakeFace(plane, wires[0])
        for w in wires[1:]:
            mk.Add(w)
        if not mk.IsDone():
            raise _RebuildError("the rebuilt section face failed")
        face = TopoDS.Face_s(mk.Face().Oriented(section.Orientation()))
        a0, a1 = _area(section), _area(face)
        if not BRepCheck_Analyzer(face).IsValid() or abs(a1 - a0) > 1e-6 * abs(a0):
            log.debug("exact meridian rejected: area %.9g vs %.9g", a1, a0)
            return section
    except Exception as err:  # an OCC failure here only costs the exact curves
        if not (is_occ_exception(err) or isinstance(err, _RebuildError)):
            raise
        log.debug("exact meridian failed: %s", err)
        return section
    return face


def _swept_angle_param(s: Any, u: float, v: float, frame: Frame, steps: int = 3) -> float:
    """The first parameter of a swept surface at the angle of ``frame``'s half-plane (the
    sense of u about the frame's axis read off the surface itself: a mirrored placement
    turns the other way), ``steps`` Newton steps of unit slope from ``u``."""
    a0 = _angle(s, u, v, frame)
    turn = math.remainder(_angle(s, u + 1e-3, v, frame) - a0, 2 * math.pi)
    sign = 1.0 if turn > 0 else -1.0
    for _ in range(steps):
        u -= sign * _angle(s, u, v, frame)
    return u


def _within(u: float, u0: float, u1: float) -> bool:
    span = u1 - u0
    return span >= 2 * math.pi - 1e-9 or (u - u0) % (2 * math.pi) <= span + 1e-9


def _meridian_edges(f: TopoDS_Face, frame: Frame, tol: float) -> list[TopoDS_Edge] | None:
    """The face's meridians in the half-plane ``x >= 0`` of ``frame``, or None when the
    face is no surface swept about the axis nor a plane across it."""
    from OCP.Geom import Geom_Plane

    from medialcad.occ.shapes import edges, wires

    s = BRep_Tool.Surface_s(f)
    if isinstance(s, Geom_RectangularTrimmedSurface):
        s = s.BasisSurface()
    u0, u1, v0, v1 = BRepTools.UVBounds_s(f)
    if isinstance(s, Geom_Plane):
        n = _xyz(s.Axis().Direction())
        if np.linalg.norm(np.cross(n, frame.ydir)) > 1e-9:
            return None
        pts = []
        for e in edges(f):
            c = BRep_Tool.Curve_s(e, 0.0, 0.0)
            if c is not None:
                a, b = BRep_Tool.Range_s(e)
                pts += [_value(c, t) for t in np.linspace(a, b, 9)]
        if not pts:
            return None
        q = np.array(pts) - frame.origin
        y = float(np.median(q @ frame.ydir))
        r = np.linalg.norm(q - np.outer(q @ frame.ydir, frame.ydir), axis=1)
        r_out = float(r.max())
        r_in = float(r.min()) if len(wires(f)) > 1 else 0.0
        at = frame.origin + y * frame.ydir
        p0, p1 = at + (r_in if r_in > tol else 0.0) * frame.xdir, at + r_out * frame.xdir
        return [BRepBuilderAPI_MakeEdge(gp_Pnt(*p0), gp_Pnt(*p1)).Edge()]
    if not isinstance(s, _SWEPT) or not _coaxial(s, frame, tol):
        return None
    um = 0.5 * (u0 + u1)
    # the angle is read at the iso's point farthest from the axis (its middle may be on it)
    vs = np.linspace(v0, v1, 9)
    q = np.array([_value(s.UIso(um), v) for v in vs]) - frame.origin
    radial = q - np.outer(q @ frame.ydir, frame.ydir)
    v_far = float(vs[int(np.argmax(np.linalg.norm(radial, axis=1)))])
    u = _swept_angle_param(s, um, v_far, frame)
    if not _within(u, u0, u1):
        return []
    return [BRepBuilderAPI_MakeEdge(s.UIso(u), v0, v1).Edge()]


def face_of_edges(edge_seq: Any, pln: Any, tol: float) -> TopoDS_Face | None:
    """One valid face on the plane ``pln`` bounded by the edges ``edge_seq`` (joined within
    ``tol`` into an outer wire and its holes), or None when they do not close into one."""
    from OCP.ShapeAnalysis import ShapeAnalysis_FreeBounds
    from OCP.ShapeFix import ShapeFix_Face
    from OCP.TopTools import TopTools_HSequenceOfShape

    from medialcad.occ.shapes import faces, wires

    joined = TopTools_HSequenceOfShape()
    ShapeAnalysis_FreeBounds.ConnectEdgesToWires_s(edge_seq, tol, False, joined)
    loops = []
    for i in range(1, joined.Length() + 1):
        w = TopoDS.Wire_s(joined.Value(i))
        mk = BRepBuilderAPI_MakeFace(pln, w, True)
        if not BRep_Tool.IsClosed_s(w) or not mk.IsDone():
            return None
        loops.append((abs(_area(mk.Face())), w))
    if not loops:
        return None
    loops.sort(key=lambda a: -a[0])
    mk = BRepBuilderAPI_MakeFace(pln, loops[0][1], True)
    for _, w in loops[1:]:
        mk.Add(w)
    if not mk.IsDone():
        return None
    fix = ShapeFix_Face(mk.Face())
    fix.Perform()
    pieces = faces(fix.Result())
    if len(pieces) != 1:  # a "hole" outside the outer wire: two regions, not a profile
        return None
    face = pieces[0]
    if len(wires(face)) != len(loops):
        return None
    want = loops[0][0] - sum(a for a, _ in loops[1:])
    if not BRepCheck_Analyzer(face).IsValid() or abs(_area(face) - want) > 1e-9 * loops[0][0]:
        return None
    return face


def iso_section(solid_faces: list[TopoDS_Face], frame: Frame, tol: float) -> TopoDS_Face | None:
    """The meridian section of a full revolution in the half-plane ``x >= 0`` of
    ``frame``, built from its faces' own meridians there (iso-curves of the surfaces swept
    about the axis, radial segments of the planes across it), the chains that end on the
    axis closed along it (their ends there, in order along it, pair up). For when OCC's
    common of the solid and the half-plane comes out empty (a rounded rectangle revolved
    about its side: its poles are dimples of horn-torus faces). None when a face is of
    another kind or the meridians do not close into one face."""
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pln
    from OCP.TopTools import TopTools_HSequenceOfShape

    try:
        seq = TopTools_HSequenceOfShape()
        ends: list[FloatArray] = []
        for f in solid_faces:
            got = _meridian_edges(f, frame, tol)
            if got is None:
                return None
            for e in got:
                seq.Append(e)
                c = BRep_Tool.Curve_s(e, 0.0, 0.0)
                a, b = BRep_Tool.Range_s(e)
                ends += [_value(c, a), _value(c, b)]
        if seq.Length() == 0:
            return None
        # free ends on the axis (an end no other edge shares), in order along it
        pts = np.array(ends)
        free = []
        for i, p in enumerate(pts):
            near = np.linalg.norm(pts - p, axis=1) <= tol
            on_axis = abs(float((p - frame.origin) @ frame.xdir)) <= tol
            if near.sum() == 1 and on_axis:
                free.append((float((p - frame.origin) @ frame.ydir), i))
        if len(free) % 2:
            return None
        free.sort()
        for (_, i), (_, j) in zip(free[::2], free[1::2], strict=True):
            seq.Append(BRepBuilderAPI_MakeEdge(gp_Pnt(*pts[i]), gp_Pnt(*pts[j])).Edge())
        pln = gp_Pln(gp_Ax3(gp_Pnt(*frame.origin), gp_Dir(*frame.zdir), gp_Dir(*frame.xdir)))
        return face_of_edges(seq, pln, tol)
    except Exception as err:  # an OCC failure: no section from the meridians
        if not is_occ_exception(err):
            raise
        log.debug("iso section failed: %s", err)
        return None
