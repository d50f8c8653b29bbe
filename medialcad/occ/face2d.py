"""A planar OCC face as exact 2D curves in its own frame (the only OCP code of the 2D engine).

The frame's origin is the centre of the face's bounding box projected on its plane, so
faces far from the model origin keep full precision. Each edge's 3D curve is mapped to
that frame exactly (``GeomAPI.To2d``) and converted to numpy data: lines, circles and
ellipses in closed form, B-splines/Béziers/conics with their poles, weights and knots;
offset and other curves are approximated by a B-spline far inside the tolerance.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepCheck import BRepCheck_Analyzer, BRepCheck_ListOfStatus
from OCP.BRepTools import BRepTools_WireExplorer
from OCP.Geom import Geom_Curve, Geom_Line, Geom_OffsetCurve, Geom_TrimmedCurve
from OCP.Geom2d import (
    Geom2d_BSplineCurve,
    Geom2d_Circle,
    Geom2d_Curve,
    Geom2d_Ellipse,
    Geom2d_Line,
    Geom2d_OffsetCurve,
    Geom2d_TrimmedCurve,
)
from OCP.Geom2dConvert import Geom2dConvert, Geom2dConvert_ApproxCurve
from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomAPI import GeomAPI
from OCP.GeomLib import GeomLib_IsPlanarSurface
from OCP.gp import gp_Ax3, gp_Dir, gp_Pln, gp_Pnt, gp_Pnt2d, gp_Vec2d
from OCP.TopAbs import TopAbs_EDGE, TopAbs_REVERSED, TopAbs_VERTEX, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape

from medialcad.errors import (
    DegenerateFaceError,
    InputError,
    NonPlanarFaceError,
    NotAFaceError,
    OpenWireError,
    SelfIntersectingBoundaryError,
    UnsupportedGeometryError,
)
from medialcad.frame import Frame, projection_along
from medialcad.mat2d.boundary import EdgePiece
from medialcad.mat2d.curves import (
    CircleCurve,
    Curve,
    EllipseCurve,
    LineCurve,
    NurbsCurve,
    OffsetCurve,
    linear_image,
)
from medialcad.occ.io import is_occ_exception, occ_guard
from medialcad.occ.shapes import single_face

__all__ = ["PlanarFace", "planar_face", "sheared_planar_face"]


@dataclass(frozen=True)
class PlanarFace:
    face: TopoDS_Face
    frame: Frame
    loops: list[list[EdgePiece]]
    edges: list[Any]  # TopoDS_Edge per edge_index
    diag: float
    gap_tol: float


def _bbox(shape: TopoDS_Shape) -> tuple[np.ndarray, np.ndarray]:
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box, False)
    if box.IsVoid():
        raise DegenerateFaceError("the face is empty")
    x0, y0, z0, x1, y1, z1 = box.Get()
    return np.array([x0, y0, z0]), np.array([x1, y1, z1])


def _vec(d: Any) -> np.ndarray:
    return np.array([d.X(), d.Y(), d.Z()])


BREPCHECK_MAX_EDGES = 300
"""OCC's face check is quadratic in the edges (20 s for 10,000): above this many, the
wires' connectivity is checked here and crossings by ``medialcad.api._check_simple``."""


def _count_edges(face: TopoDS_Face) -> int:
    exp = TopExp_Explorer(face, TopAbs_EDGE)
    n = 0
    while exp.More():
        n += 1
        exp.Next()
    return n


def _check_connected(face: TopoDS_Face) -> None:
    """Every edge of every wire is reached by walking the wire (a disconnected wire
    leaves some out)."""
    wexp = TopExp_Explorer(face, TopAbs_WIRE)
    while wexp.More():
        wire = TopoDS.Wire_s(wexp.Current())
        listed = _count_edges(wire)
        walked = 0
        it = BRepTools_WireExplorer(wire, face)
        while it.More():
            walked += 1
            it.Next()
        if walked != listed:
            raise OpenWireError("a boundary loop of the face is not connected")
        wexp.Next()


def _check_valid(face: TopoDS_Face) -> None:
    if _count_edges(face) > BREPCHECK_MAX_EDGES:
        _check_connected(face)
        return
    ana = BRepCheck_Analyzer(face, True)
    if ana.IsValid():
        return
    statuses: set[str] = set()
    for kind in (TopAbs_WIRE, TopAbs_EDGE):
        exp = TopExp_Explorer(face, kind)
        while exp.More():
            res = ana.Result(exp.Current())
            if res is not None:
                lst: BRepCheck_ListOfStatus = res.StatusOnShape(face)
                for st in lst:
                    statuses.add(str(st))
                lst2 = res.Status()
                for st in lst2:
                    statuses.add(str(st))
            exp.Next()
    text = " ".join(sorted(statuses))
    if "SelfIntersectingWire" in text or "IntersectingWires" in text:
        raise SelfIntersectingBoundaryError("the boundary of the face intersects itself")
    if "NotClosed" in text or "Disconnected" in text:
        raise OpenWireError("a boundary loop of the face is not closed")
    # other statuses are tolerated: the boundary is checked geometrically later


def _curve_to_numpy(c: Geom2d_Curve, first: float, last: float, approx_tol: float) -> Curve:
    if isinstance(c, Geom2d_TrimmedCurve):
        return _curve_to_numpy(c.BasisCurve(), first, last, approx_tol)
    if isinstance(c, Geom2d_Line):
        pos = c.Position()
        loc, d = pos.Location(), pos.Direction()
        return LineCurve(np.array([loc.X(), loc.Y()]), np.array([d.X(), d.Y()]))
    if isinstance(c, Geom2d_Circle):
        ax = c.Position()
        o, x, y = ax.Location(), ax.XDirection(), ax.YDirection()
        return CircleCurve(
            np.array([o.X(), o.Y()]), c.Radius(), np.array([x.X(), x.Y()]), np.array([y.X(), y.Y()])
        )
    if isinstance(c, Geom2d_Ellipse):
        ax = c.Position()
        o, x, y = ax.Location(), ax.XDirection(), ax.YDirection()
        return EllipseCurve(
            np.array([o.X(), o.Y()]),
            c.MajorRadius(),
            c.MinorRadius(),
            np.array([x.X(), x.Y()]),
            np.array([y.X(), y.Y()]),
        )
    if isinstance(c, Geom2d_OffsetCurve):
        basis = c.BasisCurve()
        while isinstance(basis, Geom2d_TrimmedCurve):
            basis = basis.BasisCurve()
        if isinstance(basis, (Geom2d_Line, Geom2d_Circle)):
            # exact: offsets of lines and circles are lines and circles
            base = _curve_to_numpy(basis, first, last, approx_tol)
            return _offset_exact(base, c.Offset())
        if not isinstance(basis, Geom2d_OffsetCurve):
            # evaluated exactly from the basis's derivatives (an approximation of a
            # piece a few 1e-6 long at an ellipse's vertex misplaced its curvature maximum);
            # where the basis stalls at an end (a repeated pole) the offset's normal is a
            # limit OCC takes and a formula cannot: approximated below
            inner = _curve_to_numpy(basis, first, last, approx_tol)
            speed = np.linalg.norm(inner.derivs([first, last])[1], axis=1)
            pts = inner.point(np.linspace(first, last, 9))
            size = float(np.ptp(pts, axis=0).max())
            if float(speed.min()) * abs(last - first) > 1e-9 * max(size, 1e-300):
                return OffsetCurve(inner, c.Offset())
    if isinstance(c, Geom2d_BSplineCurve):
        return _nurbs(c, trimmed=False, first=first, last=last)
    trimmed = Geom2d_TrimmedCurve(c, first, last)
    if not isinstance(c, Geom2d_OffsetCurve):  # Bezier, parabola, hyperbola: exact conversion
        try:
            return _nurbs(
                Geom2dConvert.CurveToBSplineCurve_s(trimmed), trimmed=True, first=first, last=last
            )
        except Exception as err:  # an OCC failure: fall back to approximation
            if not is_occ_exception(err):
                raise
    approx = Geom2dConvert_ApproxCurve(trimmed, approx_tol, GeomAbs_C2, 400, 9)
    if not approx.HasResult():
        raise UnsupportedGeometryError(f"cannot approximate a {type(c).__name__} edge")
    return _nurbs(approx.Curve(), trimmed=True, first=first, last=last)


def _to_2d(c3: Geom_Curve, local: gp_Pln, zdir: np.ndarray) -> Geom2d_Curve | None:
    """The edge's curve in the plane. A 3D offset curve offset along the plane's normal
    stays an offset curve of its basis's image (``GeomAPI.To2d`` approximates it by
    Bezier pieces, whose 1e-9 errors misplace a curvature maximum)."""
    basis = c3
    while isinstance(basis, Geom_TrimmedCurve):
        basis = basis.BasisCurve()
    if isinstance(basis, Geom_OffsetCurve):
        v = _vec(basis.Direction())
        if np.linalg.norm(np.cross(v, zdir)) < 1e-12:
            inner = _to_2d(basis.BasisCurve(), local, zdir)
            if inner is not None:
                # 3D: basis + d (T x V); 2D: basis + d (T x Z)
                try:
                    return Geom2d_OffsetCurve(inner, basis.Offset() * float(np.sign(v @ zdir)))
                except Exception as err:  # OCC refuses a C0 basis: approximated instead
                    if not is_occ_exception(err):
                        raise
    return GeomAPI.To2d_s(c3, local)


def _pieces(
    c: Geom2d_Curve, first: float, last: float, approx_tol: float, forward: bool
) -> list[tuple[Curve, float, float]]:
    """The edge's curve, split where a B-spline has an internal knot of multiplicity
    at least its degree (only C0 there: a polyline exported as one degree-1 B-spline, a
    kinked spline): each piece is a medial element of its own, so that a corner inside
    an edge is a corner. Pieces in the order the loop runs through them."""
    basis = c
    while isinstance(basis, Geom2d_TrimmedCurve):
        basis = basis.BasisCurve()
    cuts: list[float] = []
    if isinstance(basis, Geom2d_BSplineCurve) and not basis.IsPeriodic():
        deg, span = basis.Degree(), abs(last - first)
        for i in range(2, basis.NbKnots()):
            k = basis.Knot(i)
            if basis.Multiplicity(i) >= deg and first + 1e-9 * span < k < last - 1e-9 * span:
                cuts.append(k)
    if not cuts:
        return [(_curve_to_numpy(c, first, last, approx_tol), first, last)]
    bounds = [first, *cuts, last]
    out = []
    for a, b in itertools.pairwise(bounds):
        part = basis.Copy()
        part.Segment(a, b)
        out.append((_nurbs(part, trimmed=False, first=a, last=b), a, b))
    return out if forward else out[::-1]


def _offset_exact(base: Curve, offset: float) -> Curve:
    if isinstance(base, LineCurve):
        d = base.direction
        # Geom2d offset direction: d x Z = (dy, -dx)
        return LineCurve(base.origin + offset * np.array([d[1], -d[0]]), d)
    assert isinstance(base, CircleCurve)
    orient = np.sign(base.xaxis[0] * base.yaxis[1] - base.xaxis[1] * base.yaxis[0])
    radius = base.radius + offset * orient
    if radius <= 0:
        raise UnsupportedGeometryError("offset of a circle with non-positive radius")
    return CircleCurve(base.center, radius, base.xaxis, base.yaxis)


def _smoothly_closed(bs: Geom2d_BSplineCurve, first: float, last: float) -> bool:
    """Whether ``[first, last]`` is the whole of a closed B-spline whose ends meet (within
    1e-7 of its size) with one tangent direction (within ``1e-6`` rad, the joints'
    tolerance)."""
    k0, k1 = bs.FirstParameter(), bs.LastParameter()
    span = k1 - k0
    if span <= 0 or abs(first - k0) > 1e-12 * span or abs(last - k1) > 1e-12 * span:
        return False
    p0, p1, v0, v1 = gp_Pnt2d(), gp_Pnt2d(), gp_Vec2d(), gp_Vec2d()
    bs.D1(k0, p0, v0)
    bs.D1(k1, p1, v1)
    poles = [bs.Pole(i) for i in range(1, bs.NbPoles() + 1)]
    size = max(max(abs(q.X()), abs(q.Y())) for q in poles)
    if p0.Distance(p1) > 1e-7 * max(size, 1.0):
        return False
    n0, n1 = v0.Magnitude(), v1.Magnitude()
    return n0 > 0 and n1 > 0 and v0.Angle(v1) ** 2 < 1e-12


class _Reparam(Curve):
    """A curve whose parameter is an affine function of another's (for converted curves)."""

    def __init__(self, inner: Curve, a: float, b: float) -> None:
        self.inner, self.a, self.b = inner, a, b  # t_inner = a + b * t

    def derivs(self, t: Any) -> Any:
        p, d1, d2 = self.inner.derivs(self.a + self.b * np.asarray(t, dtype=float))
        return p, d1 * self.b, d2 * self.b**2

    def derivs3(self, t: Any) -> Any:
        p, d1, d2, d3 = self.inner.derivs3(self.a + self.b * np.asarray(t, dtype=float))
        return p, d1 * self.b, d2 * self.b**2, d3 * self.b**3


def _nurbs(bs: Geom2d_BSplineCurve, *, trimmed: bool, first: float, last: float) -> Curve:
    bs = bs.Copy()
    period = None
    if bs.IsPeriodic():
        period = bs.Period()
        bs.SetNotPeriodic()
    elif not trimmed and _smoothly_closed(bs, first, last):
        # a whole closed curve written clamped (a NURBS-converted periodic spline): one
        # period, so that feet and samples wrap across its seam as on a periodic one
        period = last - first
    n = bs.NbPoles()
    poles = np.array([[bs.Pole(i).X(), bs.Pole(i).Y()] for i in range(1, n + 1)])
    weights = np.array([bs.Weight(i) for i in range(1, n + 1)])
    knots = np.array([bs.Knot(i) for i in range(1, bs.NbKnots() + 1)])
    mults = [bs.Multiplicity(i) for i in range(1, bs.NbKnots() + 1)]
    flat = np.repeat(knots, mults)
    curve: Curve = NurbsCurve(flat, poles, weights, bs.Degree(), period)
    if trimmed:
        # the converted curve spans its own knot range; map the edge's [first, last] onto it
        k0, k1 = bs.FirstParameter(), bs.LastParameter()
        b = (k1 - k0) / (last - first)
        curve = _Reparam(curve, k0 - b * first, b)
    return curve


def planar_face(obj: Any, plane_tol: float | None = None) -> PlanarFace:
    """Read a planar face into exact 2D curves in its own frame.

    Raises:
        NotAFaceError, NonPlanarFaceError, OpenWireError, SelfIntersectingBoundaryError,
        DegenerateFaceError, UnsupportedGeometryError: the face cannot be handled.
    """
    try:
        face = single_face(obj)
    except NotAFaceError:
        raise
    except InputError as err:  # not a shape at all: still "not a face" to the caller
        raise NotAFaceError(f"expected a planar face: {err}") from err
    lo, hi = _bbox(face)
    diag = float(np.linalg.norm(hi - lo))
    if diag <= 0:
        raise DegenerateFaceError("the face has zero size")
    with occ_guard("reading the face"):
        surf = BRep_Tool.Surface_s(face)
        # STEP planes stored as B-spline surfaces are often flat only to the face tolerance
        flat_tol = plane_tol if plane_tol else max(1e-7 * diag, 2 * BRep_Tool.Tolerance_s(face))
        checker = GeomLib_IsPlanarSurface(surf, flat_tol)
        if not checker.IsPlanar():
            raise NonPlanarFaceError(
                f"the face is not planar (its surface is a {type(surf).__name__})"
            )
        pln = checker.Plan()
        _check_valid(face)
        pos = pln.Position()
        xdir, ydir = _vec(pos.XDirection()), _vec(pos.YDirection())
        zdir = np.cross(xdir, ydir)
        centre = 0.5 * (lo + hi)
        o = _vec(pos.Location())
        origin = centre - ((centre - o) @ zdir) * zdir
        frame = Frame(origin, xdir, ydir)
        local = gp_Pln(gp_Ax3(gp_Pnt(*origin), gp_Dir(*zdir), gp_Dir(*xdir)))
        loops: list[list[EdgePiece]] = []
        edges: list[Any] = []
        gap_tol = 0.0
        wexp = TopExp_Explorer(face, TopAbs_WIRE)
        while wexp.More():
            wire = TopoDS.Wire_s(wexp.Current())
            loop: list[EdgePiece] = []
            it = BRepTools_WireExplorer(wire, face)
            while it.More():
                edge = it.Current()
                if not BRep_Tool.Degenerated_s(edge):
                    gap_tol = max(gap_tol, BRep_Tool.Tolerance_s(edge))
                    ad = BRepAdaptor_Curve(edge)
                    first, last = ad.FirstParameter(), ad.LastParameter()
                    c3 = BRep_Tool.Curve_s(edge, 0.0, 0.0)
                    if c3 is None:
                        raise UnsupportedGeometryError("an edge has no 3D curve")
                    # (a line is in the plane when its two ends are)
                    n_probe = 2 if isinstance(c3, Geom_Line) else 9
                    probe = np.array(
                        [_vec(c3.Value(t)) for t in np.linspace(first, last, n_probe)],
                        dtype=float,
                    )
                    off = float(np.abs(frame.height(probe)).max())
                    if off > max(10 * flat_tol, 2 * BRep_Tool.Tolerance_s(edge)):
                        raise NonPlanarFaceError(
                            f"edge {len(edges)} leaves the face's plane by {off:.3g}"
                        )
                    c2 = _to_2d(c3, local, zdir)
                    if c2 is None:
                        raise UnsupportedGeometryError("an edge cannot be mapped to the plane")
                    forward = it.Orientation() != TopAbs_REVERSED
                    for curve, a, b in _pieces(c2, first, last, 1e-9 * diag, forward):
                        t0, t1 = (a, b) if forward else (b, a)
                        loop.append(EdgePiece(curve, t0, t1, len(edges)))
                    edges.append(edge)
                it.Next()
            if loop:
                loops.append(loop)
            wexp.Next()
    if not loops:
        raise DegenerateFaceError("the face has no boundary")
    # off-plane check of the boundary (a non-planar wire on a "planar" surface)
    # gaps between edges are covered by vertex tolerances (STEP imports: up to ~1e-4)
    vexp = TopExp_Explorer(face, TopAbs_VERTEX)
    while vexp.More():
        gap_tol = max(gap_tol, BRep_Tool.Tolerance_s(TopoDS.Vertex_s(vexp.Current())))
        vexp.Next()
    return PlanarFace(face, frame, loops, edges, diag, max(gap_tol * 4, 1e-7 * diag))


def sheared_planar_face(
    cap: Any, origin: np.ndarray, d: np.ndarray, m: np.ndarray, display: TopoDS_Face
) -> PlanarFace:
    """An oblique prism's cross-section across its direction ``d``, exact: the planar
    ``cap`` (normal ``m``, through ``origin``) projected along ``d`` onto the plane
    through ``origin`` across ``d``. The projection is linear on the cap's plane, so each
    of the cap's exact curves maps to an exact curve (:func:`linear_image`); ``display``
    is the same section as an OCC face (its curves converted, for drawing)."""
    pf = planar_face(cap)
    lin = projection_along(d, m)
    o_q = origin + lin @ (pf.frame.origin - origin)
    mx, my = lin @ pf.frame.xdir, lin @ pf.frame.ydir
    x_q = mx / np.linalg.norm(mx)
    y_q = np.cross(d, x_q)
    a = np.array([[x_q @ mx, x_q @ my], [y_q @ mx, y_q @ my]])
    if np.linalg.det(a) < 0:  # keep the loops' sense of turning
        y_q = -y_q
        a[1] = -a[1]
    loops = []
    for loop in pf.loops:
        out = []
        for piece in loop:
            curve, t0, t1 = linear_image(piece.curve, a, piece.t0, piece.t1)
            out.append(EdgePiece(curve, t0, t1, piece.edge_index))
        loops.append(out)
    lo, hi = _bbox(display)
    stretch = float(np.linalg.norm(a, 2))
    return PlanarFace(
        display,
        Frame(o_q, x_q, y_q),
        loops,
        pf.edges,
        float(np.linalg.norm(hi - lo)),
        pf.gap_tol * stretch,
    )
