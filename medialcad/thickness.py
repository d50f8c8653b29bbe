"""Wall thickness of a solid read off its medial axis transform.

The ball of radius ``r`` centred at a medial point touches the boundary in two or more
points; ``2 r`` is the *thickness* there. Its largest value is the diameter of the
largest inscribed ball. Its smallest value is useless as it stands: near every convex
edge the balls shrink to nothing (``r = 0`` on the rims), so the "thinnest place" of a
plain box would be 0.

Definition used here: a medial point is a **wall point** when its ball is pinched
between surfaces that face each other, i.e. two of its touch points are more than
``min_angle`` apart seen from the centre (default 120 degrees: the two surfaces are
within 60 degrees of facing each other squarely). On a plate the balls of the mid sheet
touch both sides 180 degrees apart; the balls along an edge where two faces meet at an
angle ``a`` touch them ``180 - a`` degrees apart, so right-angle edges (90) never count,
nor do curved faces meeting at about a right angle (the inside of a bent tube's end, a
few degrees over 90); an edge sharper than 60 degrees is a knife edge and does count,
its wall tapering to (nearly) zero. Then:

- **minimum wall thickness** = min of ``2 r`` over the wall points;
- **maximum wall thickness** = max of ``2 r`` over the whole medial axis (the largest
  inscribed ball; its centre is a wall point).

So a plate of thickness ``t`` gives ``min = max = t``, a tube gives its wall, a box
``a x b x c`` (``c`` smallest) gives ``c``, a cylinder its diameter, an L-bracket the
thickness of its legs (its max, the ball wedged into the inner corner, is a little
more). Balls smaller than ``10 tol`` are not judged (their touch directions are below
the resolution of the fitted geometry), so a knife edge reads about ``20 tol`` thick.

How it is computed:

- on a sheet (two touch points) the touch directions are
  ``-grad r ± sqrt(1 - |grad r|^2) n`` (``grad r`` the surface gradient of the radius,
  ``n`` the sheet normal), so the angle between them is ``arccos(2 |grad r|^2 - 1)``:
  sheets are sampled on grids of their ``(u, v)`` parameters, closure included, and the
  best samples refined;
- on the curves and junctions of the complex (three or more touch points, or a whole
  circle or sphere of them at a curvature centre, e.g. the axis of a cylinder) the touch
  points are found on the solid: the nearest point of every face within ``r`` (+ 3 tol),
  plus, on skeletal edges and junctions, rays cast on the cone of possible touch
  directions.

Example::

    import cadquery as cq
    from medialcad.api import medial_axis
    from medialcad.thickness import thickness_at, wall_thickness

    mat = medial_axis(cq.Workplane().box(100, 60, 4))
    t = wall_thickness(mat)
    t.min, t.max                  # (4.0, 4.0): the plate's thickness
    t.min_location                # the centre of a thinnest ball, on the mid sheet
    thickness_at(mat, (0, 0, 0))  # 4.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["Thickness", "thickness_at", "wall_thickness"]

FloatArray = NDArray[np.float64]

_R_FLOOR = 10.0
"""Balls smaller than this many tolerances are not walls: their touch directions cannot be
resolved on the fitted geometry (knife edges read as about ``20 tol`` thick)."""
_GOLDEN_DIRS = 120  # directions probed around a junction
_CONE_DIRS = 36  # directions probed on the cone of a curve point


@dataclass(frozen=True)
class Thickness:
    """Minimum and maximum wall thickness (see :mod:`medialcad.thickness`).

    Attributes:
        min: smallest ``2 r`` over the wall points (``nan`` when the medial axis has no
            wall point at all, e.g. ``min_angle`` set to 180 on a box).
        max: largest ``2 r`` over the medial axis: the diameter of the largest inscribed
            ball.
        min_location, max_location: medial points (model space) where they occur; the
            centres of those balls.
        min_entity, max_entity: names of the entities they lie on (``"sheet-3"``,
            ``"seam-1"``, ``"junction-2"``, ...).
    """

    min: float
    max: float
    min_location: FloatArray
    max_location: FloatArray
    min_entity: str = ""
    max_entity: str = ""


def thickness_at(result: Any, point: ArrayLike) -> float:
    """``2 r`` at the medial point nearest to ``point``.

    ``point`` is meant to be a point of the medial axis (or close to it); the radius is
    that of the nearest point of the complex (:meth:`MedialAxis3D.radius_at`).

    Example::

        mat = medial_axis(cq.Workplane().circle(20).circle(15).extrude(50))
        thickness_at(mat, (17.5, 0, 25))  # 5.0: the tube's wall
    """
    return 2.0 * float(result.radius_at(point))


@dataclass
class _Best:
    value: float
    point: FloatArray
    entity: str
    key: tuple[Any, ...]  # what to refine: ("sheet", index, u, v, du, dv) or ("curve", ...)


def wall_thickness(
    result: Any, *, min_angle: float = 120.0, samples: int = 33, refine: bool = True
) -> Thickness:
    """Minimum and maximum wall thickness of the solid whose MAT is ``result``.

    Args:
        result: a :class:`medialcad.mat3d.result.MedialAxis3D`.
        min_angle: degrees; a medial point counts as a wall point when two of its touch
            points are more than ``min_angle`` apart seen from the ball's centre. Raise it
            (e.g. to 150) to count only walls whose faces are nearly parallel. At 90 or less
            the balls along right-angle edges (touches exactly 90 degrees apart) come
            into play and the minimum drops towards 0.
        samples: grid points per parameter direction of a sheet (more where the sheet's
            knots are dense) and per curve.
        refine: refine the best samples by zooming in on their neighbourhoods.

    The curves and junctions are judged on the solid (``result.recognition.solid``); a
    result without it is judged on its sheets alone.

    Returns:
        A :class:`Thickness`.

    Example::

        mat = medial_axis(cq.Workplane().box(40, 20, 10))
        wall_thickness(mat).min   # 10.0
    """
    if not 0.0 <= min_angle <= 180.0:
        raise ValueError(f"min_angle must be within [0, 180] degrees, got {min_angle!r}")
    cos_lim = math.cos(math.radians(min_angle))
    prober = _Prober.of(result)
    r_floor = _R_FLOOR * float(result.tol)
    lo_cands: list[_Best] = []
    hi_cands: list[_Best] = []

    for i, sheet in enumerate(result.sheets):
        s = _SheetSampler(sheet)
        n_u = int(np.clip(max(samples, 2 * len(np.unique(sheet.knots))), 3, 257))
        n_v = max(3, samples // 3)
        got = s.grid(s.u0, s.u1, s.v0, s.v1, n_u, n_v, cos_lim, r_floor)
        if got is None:
            continue
        pts, rad, wall, uu, vv = got
        du = (s.u1 - s.u0) / (n_u - 1)
        dv = (s.v1 - s.v0) / (n_v - 1)
        k = int(np.argmax(rad))
        hi_cands.append(
            _Best(float(rad[k]), pts[k], sheet.name, ("sheet", i, uu[k], vv[k], du, dv))
        )
        if wall.any():
            w = np.flatnonzero(wall)
            k = int(w[np.argmin(rad[w])])
            lo_cands.append(
                _Best(float(rad[k]), pts[k], sheet.name, ("sheet", i, uu[k], vv[k], du, dv))
            )

    # curves and junctions: probe the solid in order of increasing radius, only while
    # the radius is below the best wall found so far (the first wall found is the least)
    probes: list[
        tuple[float, FloatArray, str, tuple[Any, ...], FloatArray | None, float, bool]
    ] = []
    n_seams = len(result.seams)
    for i, curve in enumerate(result.seams + result.skeletal_edges):
        c = _CurveSampler(curve)
        ts = np.linspace(c.t0, c.t1, max(samples // 2, 5))
        pts, rad, tang, slope = c.eval(ts)
        k = int(np.argmax(rad))
        dt = float(ts[1] - ts[0])
        hi_cands.append(_Best(float(rad[k]), pts[k], curve.name, ("curve", i, ts[k], dt)))
        for j in range(len(ts)):
            key = ("curve", i, ts[j], dt)
            probes.append(
                (float(rad[j]), pts[j], curve.name, key, tang[j], float(slope[j]), i >= n_seams)
            )
    for jn in result.junctions:
        p = np.asarray(jn.point, dtype=float)
        hi_cands.append(_Best(float(jn.radius), p, jn.name, ("point",)))
        probes.append((float(jn.radius), p, jn.name, ("point",), None, 0.0, True))
    if prober is not None:
        bound = min((b.value for b in lo_cands), default=math.inf)
        for pr, pp, name, key, tangent, ps, rays in sorted(probes, key=lambda x: x[0]):
            if pr >= bound:
                break
            if pr > r_floor and prober.is_wall(pp, pr, cos_lim, tangent, ps, rays=rays):
                lo_cands.append(_Best(pr, pp, name, key))
                break

    if not hi_cands:
        raise ValueError("the medial axis has no sheet, curve or junction")
    hi_cands.sort(key=lambda b: -b.value)
    lo_cands.sort(key=lambda b: b.value)
    if refine:
        hi_cands[:3] = [
            _refine(result, prober, b, cos_lim, r_floor, maximum=True) for b in hi_cands[:3]
        ]
        lo_cands[:3] = [
            _refine(result, prober, b, cos_lim, r_floor, maximum=False) for b in lo_cands[:3]
        ]
    hi = max(hi_cands, key=lambda b: b.value)
    lo = min(lo_cands, key=lambda b: b.value) if lo_cands else None
    return Thickness(
        min=2.0 * lo.value if lo is not None else math.nan,
        max=2.0 * hi.value,
        min_location=lo.point if lo is not None else np.full(3, np.nan),
        max_location=hi.point,
        min_entity=lo.entity if lo is not None else "",
        max_entity=hi.entity,
    )


def _refine(
    result: Any,
    prober: _Prober | None,
    best: _Best,
    cos_lim: float,
    r_floor: float,
    *,
    maximum: bool,
) -> _Best:
    """Zoom in around a sample (three rounds of a 7 x 7 / 7-point grid)."""
    kind = best.key[0]
    sign = -1.0 if maximum else 1.0
    if kind == "sheet":
        _, i, u, v, du, dv = best.key
        sheet = result.sheets[i]
        s = _SheetSampler(sheet)
        for _ in range(3):
            got = s.grid(
                max(s.u0, u - du),
                min(s.u1, u + du),
                max(s.v0, v - dv),
                min(s.v1, v + dv),
                7,
                7,
                cos_lim,
                r_floor,
            )
            if got is None:
                break
            pts, rad, wall, uu, vv = got
            ok = np.ones(len(rad), bool) if maximum else wall
            if ok.any():
                w = np.flatnonzero(ok)
                k = int(w[np.argmin(sign * rad[w])])
                if sign * rad[k] < sign * best.value:
                    best = _Best(float(rad[k]), pts[k], best.entity, best.key)
                    u, v = float(uu[k]), float(vv[k])
            du, dv = du / 3.0, dv / 3.0
        return best
    if kind == "curve":
        _, i, t, dt = best.key
        c = _CurveSampler((result.seams + result.skeletal_edges)[i])
        skeletal = i >= len(result.seams)  # seams touch in points: faces' nearest points do
        for _ in range(3):
            ts = np.linspace(max(c.t0, t - dt), min(c.t1, t + dt), 7)
            pts, rad, tang, slope = c.eval(ts)
            for j in np.argsort(sign * rad):
                if sign * rad[j] >= sign * best.value:
                    break
                if maximum or (
                    prober is not None
                    and rad[j] > r_floor
                    and prober.is_wall(
                        pts[j], float(rad[j]), cos_lim, tang[j], float(slope[j]), rays=skeletal
                    )
                ):
                    best = _Best(float(rad[j]), pts[j], best.entity, best.key)
                    t = float(ts[j])
                    break
            dt /= 3.0
        return best
    return best


# -- sheets --------------------------------------------------------------------------
class _SheetSampler:
    """Points, radius and touch angle of a sheet on grids of its ``(u, v)`` parameters."""

    def __init__(self, sheet: Any) -> None:
        from OCP.BRepAdaptor import BRepAdaptor_Surface
        from OCP.BRepTools import BRepTools
        from OCP.BRepTopAdaptor import BRepTopAdaptor_FClass2d

        self.sheet = sheet
        self.surf = BRepAdaptor_Surface(sheet.face)
        self.u0, self.u1, self.v0, self.v1 = BRepTools.UVBounds_s(sheet.face)
        self.classifier = BRepTopAdaptor_FClass2d(sheet.face, 1e-9)
        span = max(self.u1 - self.u0, self.v1 - self.v0, 1e-300)
        self.eps = 1e-7 * span  # keep off degenerated sides, where the gradient is 0/0
        self.ruled = self._is_ruled()

    def _radius(self, u: FloatArray, v: FloatArray) -> FloatArray:
        """``sheet.radius(u, v)``, vectorised here for tensor sheets (revolutions)."""
        sheet = self.sheet
        grid = getattr(sheet, "radius_grid", None)
        v_knots = getattr(sheet, "v_knots", None)
        if grid is None or v_knots is None or sheet.role == "mid":
            return np.asarray(sheet.radius(u, v), dtype=float)
        from scipy.interpolate import BSpline

        uu = np.asarray(u, dtype=float)
        vv = np.asarray(v, dtype=float)
        cu = BSpline(sheet.knots, grid, sheet.degree, extrapolate=True)(uu)  # (n, nv)
        vk = np.asarray(v_knots, dtype=float)
        basis = BSpline.design_matrix(vv, vk, sheet.v_degree, extrapolate=True).toarray()
        return np.asarray(np.einsum("ij,ij->i", basis, cu), dtype=float)

    def _is_ruled(self) -> bool:
        """A B-spline sheet ruled in ``v`` whose face is its whole parameter rectangle
        (the sewn sheets of :mod:`medialcad.occ.complex`): rows give every point."""
        from OCP.GeomAbs import GeomAbs_BSplineSurface

        s = self.surf
        if s.GetType() != GeomAbs_BSplineSurface or s.VDegree() != 1 or s.NbVPoles() != 2:
            return False
        full = (s.FirstUParameter(), s.LastUParameter(), s.FirstVParameter(), s.LastVParameter())
        mine = (self.u0, self.u1, self.v0, self.v1)
        return all(abs(a - b) <= 1e-9 * (1.0 + abs(a)) for a, b in zip(full, mine, strict=True))

    def _points(
        self, uu: FloatArray, vv: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray, NDArray[np.bool_]]:
        """Points, ``dS/du``, ``dS/dv`` and the inside mask at the parameters."""
        from OCP.gp import gp_Pnt, gp_Pnt2d, gp_Vec
        from OCP.TopAbs import TopAbs_OUT

        n = len(uu)
        pts = np.zeros((n, 3))
        su = np.zeros((n, 3))
        sv = np.zeros((n, 3))
        inside = np.ones(n, bool)
        p, a, b = gp_Pnt(), gp_Vec(), gp_Vec()
        for k in range(n):
            u, v = float(uu[k]), float(vv[k])
            if not self.ruled and self.classifier.Perform(gp_Pnt2d(u, v)) == TopAbs_OUT:
                inside[k] = False
                continue
            self.surf.D1(u, v, p, a, b)
            pts[k] = (p.X(), p.Y(), p.Z())
            su[k] = (a.X(), a.Y(), a.Z())
            sv[k] = (b.X(), b.Y(), b.Z())
        return pts, su, sv, inside

    def grid(
        self,
        u0: float,
        u1: float,
        v0: float,
        v1: float,
        nu: int,
        nv: int,
        cos_lim: float,
        r_floor: float,
    ) -> tuple[FloatArray, FloatArray, NDArray[np.bool_], FloatArray, FloatArray] | None:
        """``(points, r, wall, u, v)`` of the grid points inside the face, or ``None``."""
        us = np.linspace(u0, u1, nu)
        vs = np.linspace(v0, v1, nv)
        us = np.clip(us, self.u0 + self.eps, self.u1 - self.eps)
        vs = np.clip(vs, self.v0 + self.eps, self.v1 - self.eps)
        uu, vv = (a.ravel() for a in np.meshgrid(us, vs, indexing="ij"))
        if self.ruled:
            # S(u, v) = B(u) + w (T(u) - B(u)), w = (v - v0) / (v1 - v0): two rows per u
            rows = np.full(nu, self.v0), np.full(nu, self.v1)
            pb, db, _, _ = self._points(us, rows[0])
            pt, dt, _, _ = self._points(us, rows[1])
            w = ((vs - self.v0) / (self.v1 - self.v0))[None, :, None]
            pts = (pb[:, None] + w * (pt - pb)[:, None]).reshape(-1, 3)
            su = (db[:, None] + w * (dt - db)[:, None]).reshape(-1, 3)
            sv = np.repeat((pt - pb) / (self.v1 - self.v0), nv, axis=0)
            inside = np.ones(len(uu), bool)
        else:
            pts, su, sv, inside = self._points(uu, vv)
        if not inside.any():
            return None
        pts, su, sv, uu, vv = pts[inside], su[inside], sv[inside], uu[inside], vv[inside]
        rad = self._radius(uu, vv)
        hu = 1e-6 * max(self.u1 - self.u0, 1e-300)
        hv = 1e-6 * max(self.v1 - self.v0, 1e-300)
        ru = (self._radius(uu + hu, vv) - self._radius(uu - hu, vv)) / (2 * hu)
        rv = (self._radius(uu, vv + hv) - self._radius(uu, vv - hv)) / (2 * hv)
        e = np.einsum("ij,ij->i", su, su)
        f = np.einsum("ij,ij->i", su, sv)
        g = np.einsum("ij,ij->i", sv, sv)
        det = e * g - f * f
        good = det > 1e-18 * np.maximum(e * g, 1e-300)
        with np.errstate(divide="ignore", invalid="ignore"):
            grad2 = (g * ru * ru - 2.0 * f * ru * rv + e * rv * rv) / det
        # cos of the angle between the two touch directions: 2 |grad r|^2 - 1
        cos_touch = 2.0 * np.where(good, grad2, np.inf) - 1.0
        wall = good & (cos_touch < cos_lim) & (rad > r_floor)
        return pts, rad, wall, uu, vv


# -- curves and junctions ------------------------------------------------------------
class _CurveSampler:
    def __init__(self, curve: Any) -> None:
        from OCP.BRepAdaptor import BRepAdaptor_Curve

        self.curve = curve
        self.adaptor = BRepAdaptor_Curve(curve.edge)
        self.t0 = float(self.adaptor.FirstParameter())
        self.t1 = float(self.adaptor.LastParameter())

    def eval(self, ts: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Points, radius, unit tangents and ``dr/ds`` (arc length) at ``ts``."""
        from OCP.gp import gp_Pnt, gp_Vec

        pts = np.empty((len(ts), 3))
        d1 = np.empty((len(ts), 3))
        p, v = gp_Pnt(), gp_Vec()
        for k, t in enumerate(ts):
            self.adaptor.D1(float(t), p, v)
            pts[k] = (p.X(), p.Y(), p.Z())
            d1[k] = (v.X(), v.Y(), v.Z())
        rad = np.asarray(self.curve.radius(ts), dtype=float)
        h = 1e-6 * max(self.t1 - self.t0, 1e-300)
        dr = (np.asarray(self.curve.radius(ts + h)) - np.asarray(self.curve.radius(ts - h))) / (
            2 * h
        )
        speed = np.linalg.norm(d1, axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            tang = d1 / speed[:, None]
            slope = np.clip(dr / speed, -1.0, 1.0)
        tang = np.where(np.isfinite(tang), tang, 0.0)
        slope = np.where(np.isfinite(slope), slope, 0.0)
        return pts, rad, tang, slope


class _Prober:
    """Touch directions of balls found on the solid itself."""

    def __init__(self, solid: Any, tol: float) -> None:
        from OCP.Bnd import Bnd_Box
        from OCP.BRepBndLib import BRepBndLib
        from OCP.IntCurvesFace import IntCurvesFace_ShapeIntersector
        from OCP.TopAbs import TopAbs_FACE
        from OCP.TopExp import TopExp_Explorer

        self.faces: list[Any] = []
        self.boxes: list[Any] = []
        ex = TopExp_Explorer(solid, TopAbs_FACE)
        while ex.More():
            f = ex.Current()
            box = Bnd_Box()
            BRepBndLib.Add_s(f, box)
            self.faces.append(f)
            self.boxes.append(box)
            ex.Next()
        self.rays = IntCurvesFace_ShapeIntersector()
        self.rays.Load(solid, max(tol * 1e-3, 1e-9))
        # a probe just below the radius where a seam becomes a wall passes for one when its
        # far touch is within the slack: the reported thickness is then up to the slack
        # thin (3 tol read a plate of 2 as 1.9975, tol 1.2e-3)
        self.slack = 1.5 * tol
        self._normals: dict[Any, Any] = {}
        i = np.arange(_GOLDEN_DIRS) + 0.5
        z = 1.0 - 2.0 * i / _GOLDEN_DIRS
        phi = math.pi * (1.0 + 5.0**0.5) * i
        rho = np.sqrt(1.0 - z * z)
        self.sphere = np.column_stack([rho * np.cos(phi), rho * np.sin(phi), z])

    @classmethod
    def of(cls, result: Any) -> _Prober | None:
        solid = getattr(getattr(result, "recognition", None), "solid", None)
        if solid is None:
            return None
        return cls(solid, float(result.tol))

    def touches(self, p: FloatArray, r: float, dirs: FloatArray) -> FloatArray:
        """Unit directions from ``p`` to the boundary points at distance ``r`` (+ slack)."""
        from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
        from OCP.BRepExtrema import BRepExtrema_DistShapeShape
        from OCP.BRepGProp import BRepGProp_Face
        from OCP.gp import gp_Dir, gp_Lin, gp_Pnt, gp_Vec

        reach = r + self.slack
        q = gp_Pnt(*map(float, p))
        out: list[FloatArray] = []
        vertex = BRepBuilderAPI_MakeVertex(q).Vertex()
        for f, box in zip(self.faces, self.boxes, strict=True):
            if box.Distance(_point_box(q)) > reach:
                continue
            dss = BRepExtrema_DistShapeShape(vertex, f)
            if not dss.IsDone() or dss.NbSolution() == 0 or dss.Value() > reach:
                continue
            for k in range(1, dss.NbSolution() + 1):
                s = dss.PointOnShape2(k)
                d = np.array([s.X(), s.Y(), s.Z()]) - p
                nd = float(np.linalg.norm(d))
                if nd > 1e-12:
                    out.append(d / nd)
        # rays find touch sets that are whole arcs or caps (a cylinder's axis, a sphere's
        # centre); the direction taken is the face's outward normal at the hit, which is
        # the exact touch direction even when the ray only grazes within the slack
        pn, nv = gp_Pnt(), gp_Vec()
        for d in dirs:
            self.rays.Perform(gp_Lin(q, gp_Dir(*map(float, d))), 0.0, reach)
            if not self.rays.IsDone():
                continue
            for k in range(1, self.rays.NbPnt() + 1):
                face = self.rays.Face(k)
                props = self._normals.get(face)
                if props is None:
                    props = self._normals.setdefault(face, BRepGProp_Face(face))
                props.Normal(self.rays.UParameter(k), self.rays.VParameter(k), pn, nv)
                n = np.array([nv.X(), nv.Y(), nv.Z()])
                nn = float(np.linalg.norm(n))
                if nn > 0:
                    out.append(n / nn)
        return np.array(out).reshape(-1, 3)

    def is_wall(
        self,
        p: FloatArray,
        r: float,
        cos_lim: float,
        tangent: FloatArray | None,
        slope: float,
        *,
        rays: bool = True,
    ) -> bool:
        """Whether two touch points of the ball ``(p, r)`` are more than the limit apart.

        ``tangent``/``slope`` (``dr/ds``) put the probing rays on the cone of possible
        touch directions of a curve point; ``None`` probes all around (a junction).
        """
        if r <= 0:
            return False
        if not rays:
            dirs = np.zeros((0, 3))
        elif tangent is None or not np.any(tangent):
            dirs = self.sphere
        else:
            t = np.asarray(tangent, dtype=float)
            a = np.eye(3)[int(np.argmin(np.abs(t)))]
            n1 = np.cross(t, a)
            n1 /= np.linalg.norm(n1)
            n2 = np.cross(t, n1)
            ang = np.linspace(0.0, 2 * math.pi, _CONE_DIRS, endpoint=False)
            c = math.sqrt(max(0.0, 1.0 - slope * slope))
            dirs = -slope * t + c * (np.outer(np.cos(ang), n1) + np.outer(np.sin(ang), n2))
        d = self.touches(p, r, dirs)
        if len(d) < 2:
            return False
        return bool((d @ d.T).min() < cos_lim)


def _point_box(q: Any) -> Any:
    from OCP.Bnd import Bnd_Box

    b = Bnd_Box()
    b.Add(q)
    return b
