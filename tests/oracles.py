"""Independent oracles for the 2D medial axis transform (THEORY.md Sec. 3).

These share no code with medialcad: every distance is an OpenCascade
``BRepExtrema_DistShapeShape`` between a vertex and the face's boundary edges (a compound built
once and loaded once), inside/outside is ``BRepClass_FaceClassifier``. Shapes may be given as
``TopoDS_*`` or as cadquery/build123d objects (``.wrapped``, ``Workplane.val()``).

The central primitive is the *medial depth* of a boundary point ``q`` along an inward
direction ``u``: the largest ``s`` with ``dist(q + s u, dF) >= s - eps``. The predicate is
monotone in ``s`` (triangle inequality: once a boundary point is closer than ``s`` it stays
closer), so it is bracketed and solved by a safeguarded Newton iteration from the right
(``g(s) = dist(q + s u) - s`` has slope ``u.w - 1`` where ``w`` points from the nearest
boundary point) with bisection as the fallback. ``q + s* u`` is the true medial point on that
ray.

All errors are absolute (model units); divide by :func:`bbox_diagonal` to report them.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.BRepExtrema import BRepExtrema_DistShapeShape, BRepExtrema_SupportType
from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.GeomAbs import GeomAbs_C1, GeomAbs_Circle, GeomAbs_Ellipse, GeomAbs_Line, GeomAbs_Plane
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
from OCP.gp import gp_Pnt, gp_Vec
from OCP.TColStd import TColStd_Array1OfReal
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_OUT, TopAbs_VERTEX
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Face, TopoDS_Shape
from OCP.TopTools import TopTools_IndexedMapOfShape
from scipy.optimize import minimize_scalar
from scipy.spatial import cKDTree

__all__ = [
    "FaceBoundary",
    "ShapeDistance",
    "as_occ",
    "bbox_diagonal",
    "completeness_2d",
    "medial_points_2d",
    "radius_error_2d",
    "soundness_2d",
]

FloatArray = NDArray[np.float64]


# --------------------------------------------------------------------------- helpers


def as_occ(shape: Any) -> TopoDS_Shape:
    """The ``TopoDS_Shape`` behind a raw OCP shape, a cadquery/build123d shape or Workplane."""
    if isinstance(shape, TopoDS_Shape):
        return shape
    if hasattr(shape, "val") and callable(shape.val):  # cadquery Workplane
        shape = shape.val()
    wrapped = getattr(shape, "wrapped", None)
    if isinstance(wrapped, TopoDS_Shape):
        return wrapped
    raise TypeError(f"not a shape: {type(shape).__name__}")


def bbox_diagonal(shape: Any) -> float:
    """Diagonal of the (optimal, geometry-only) bounding box of ``shape``."""
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(as_occ(shape), box, False, False)
    xmin, ymin, zmin, xmax, ymax, zmax = box.Get()
    return float(math.dist((xmin, ymin, zmin), (xmax, ymax, zmax)))


def _pnt(p: FloatArray) -> gp_Pnt:
    return gp_Pnt(float(p[0]), float(p[1]), float(p[2]))


def _xyz(p: gp_Pnt | gp_Vec) -> FloatArray:
    return np.array([p.X(), p.Y(), p.Z()])


def _vertex(p: FloatArray) -> TopoDS_Shape:
    return BRepBuilderAPI_MakeVertex(_pnt(p)).Vertex()


def _subshapes(shape: TopoDS_Shape, kind: Any) -> list[TopoDS_Shape]:
    """The distinct sub-shapes of ``kind``, in exploration order (a hashed map: the
    pairwise ``IsSame`` scan this replaced was quadratic, minutes on a sampled method's
    polyline of thousands of edges)."""
    m = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, kind, m)
    return [m.FindKey(i) for i in range(1, m.Extent() + 1)]


class _EdgeSamples:
    """Dense points on the edges of a shape without faces (a medial compound), for seeding
    point-to-curve projections."""

    PER_EDGE = 400

    def __init__(self, shape: TopoDS_Shape) -> None:
        self.curves: list[tuple[Any, Any, FloatArray]] = []
        self.last: tuple[Any, float] = (None, 0.0)
        if _subshapes(shape, TopAbs_FACE):
            self.tree = None
            return
        pts, ids = [], []
        edges = _subshapes(shape, TopAbs_EDGE)
        per_edge = int(np.clip(40_000 // max(len(edges), 1), 16, self.PER_EDGE))
        for e in edges:
            edge = TopoDS.Edge_s(e)
            if BRep_Tool.Degenerated_s(edge):
                continue
            c, t0, t1 = BRep_Tool.Curve_s(edge, 0.0, 0.0), *BRep_Tool.Range_s(edge)
            if c is None:
                continue
            ts = np.linspace(t0, t1, per_edge)
            pts.append(np.array([_xyz(c.Value(float(t))) for t in ts]))
            ids.append(np.column_stack([np.full(len(ts), len(self.curves)), np.arange(len(ts))]))
            self.curves.append((edge, c, ts))
        self.tree = cKDTree(np.vstack(pts)) if pts else None
        self.ids = np.vstack(ids) if ids else np.zeros((0, 2), dtype=int)

    def nearest(self, x: FloatArray, bound: float) -> tuple[float, FloatArray] | None:
        """The nearest curve point found by projecting ``x`` onto the parameter windows
        around the tessellation points nearer than ``bound`` plus a sample step."""
        if self.tree is None:
            return None
        best: tuple[float, FloatArray] | None = None
        _, near = self.tree.query(x, k=min(8, self.tree.n))
        for j in np.atleast_1d(near):
            ci, k = self.ids[j]
            edge, c, ts = self.curves[int(ci)]
            lo, hi = ts[max(k - 1, 0)], ts[min(k + 1, len(ts) - 1)]
            proj = GeomAPI_ProjectPointOnCurve(gp_Pnt(*x), c, float(lo), float(hi))
            for i in range(1, proj.NbPoints() + 1):
                q = _xyz(proj.Point(i))
                d = float(np.linalg.norm(q - x))
                if best is None or d < best[0]:
                    best = (d, q)
                    self.last = (edge, float(proj.Parameter(i)))
            # the window ends too (a projection is an interior extremum)
            for t in (lo, hi):
                q = _xyz(c.Value(float(t)))
                d = float(np.linalg.norm(q - x))
                if best is None or d < best[0]:
                    best = (d, q)
                    self.last = (edge, float(t))
        return best


class ShapeDistance:
    """Distance from points to a fixed shape, one ``BRepExtrema_DistShapeShape`` reused."""

    def __init__(self, shape: Any) -> None:
        self.shape = as_occ(shape)
        self._dss = BRepExtrema_DistShapeShape()
        self._dss.LoadS2(self.shape)
        self._last = 1
        self._edges = _EdgeSamples(self.shape)

    def nearest(self, p: ArrayLike) -> tuple[float, FloatArray]:
        """``(distance, nearest point on the shape)`` for one point ``p (3,)``."""
        dss = self._dss
        x = np.asarray(p, dtype=float)
        dss.LoadS1(_vertex(x))
        if not dss.Perform() or not dss.IsDone() or dss.NbSolution() < 1:
            raise RuntimeError("BRepExtrema_DistShapeShape failed")
        # Every extremum within the deflection (Precision::Confusion, 1e-7 absolute) of the
        # minimum is a "solution", in no particular order: pick the truly nearest one.
        best, best_i, best_q = math.inf, 1, x
        for i in range(1, dss.NbSolution() + 1):
            q = _xyz(dss.PointOnShape2(i))
            dq = float(np.linalg.norm(q - x))
            if dq < best:
                best, best_i, best_q = dq, i, q
        self._last = best_i
        value = float(dss.Value())
        # BRepExtrema can settle on a farther local minimum of a B-spline edge with many
        # poles (1.5e-4 for 2e-9 on a random blob's branch): seeded projections from a
        # dense tessellation of the edges catch it (a nearer point is a true curve point)
        near = self._edges.nearest(x, value)
        if near is not None and near[0] < value:
            self._last = -1
            return near
        return value, best_q

    def support(self) -> tuple[TopoDS_Shape, Any, float | None]:
        """Support of the first solution of the last :meth:`nearest` call:
        ``(shape, BRepExtrema_SupportType, edge parameter or None)``."""
        dss, i = self._dss, self._last
        if i < 0:  # found by the edge samples
            edge, t = self._edges.last
            return edge, BRepExtrema_SupportType.BRepExtrema_IsOnEdge, t
        kind = dss.SupportTypeShape2(i)
        par = dss.ParOnEdgeS2(i) if kind == BRepExtrema_SupportType.BRepExtrema_IsOnEdge else None
        if isinstance(par, tuple):
            par = par[0]
        return dss.SupportOnShape2(i), kind, par

    def distances(self, points: ArrayLike) -> FloatArray:
        pts = np.atleast_2d(np.asarray(points, dtype=float))
        return np.array([self.nearest(p)[0] for p in pts])


# --------------------------------------------------------------------------- the boundary


class FaceBoundary:
    """A planar face's boundary as a distance oracle, plus inside tests and boundary samples.

    Args:
        face: the planar face (any wrapper).
        eps: slack of the medial predicate ``dist(q + s u) >= s - eps`` and the resolution
            of the medial depth; default ``1e-12`` of the bounding-box diagonal (plus the
            rounding of the coordinates' magnitude).
        eta: how far the nearest boundary point of ``q + s u`` may drift from ``q`` before
            ``s`` counts as past the medial point when ``dist`` alone cannot tell (see
            :meth:`_probe`); default ``1e-8`` of the diagonal.
    """

    def __init__(self, face: Any, eps: float | None = None, eta: float | None = None) -> None:
        self.face: TopoDS_Face = TopoDS.Face_s(as_occ(face))
        surf = BRepAdaptor_Surface(self.face)
        if surf.GetType() != GeomAbs_Plane:
            raise ValueError("oracle: the face is not planar")
        self.normal = _xyz(surf.Plane().Axis().Direction())
        self.edges = [TopoDS.Edge_s(e) for e in _subshapes(self.face, TopAbs_EDGE)]
        self.vertices = [
            _xyz(BRep_Tool.Pnt_s(TopoDS.Vertex_s(v))) for v in _subshapes(self.face, TopAbs_VERTEX)
        ]
        comp = TopoDS_Compound()
        builder = BRep_Builder()
        builder.MakeCompound(comp)
        for e in self.edges:
            builder.Add(comp, e)
        self.compound = comp
        self.diag = bbox_diagonal(self.face)
        self._dist = ShapeDistance(comp)
        scale = max(1.0, float(np.abs(self.vertices).max()) if self.vertices else 1.0, self.diag)
        self.eps = eps if eps is not None else 1e-12 * self.diag + 1e-15 * scale
        self.eta = eta if eta is not None else 1e-8 * self.diag + 1e-14 * scale
        self.edge_tol = max(BRep_Tool.Tolerance_s(e) for e in self.edges)
        self.class_tol = max(1e-9 * self.diag, self.edge_tol)
        self.curves = [BRepAdaptor_Curve(e) for e in self.edges]
        self._closed_edges = [self._ends_meet(c) for c in self.curves]
        #: ``(edge index, parameter)`` of the foot found by the last :meth:`nearest` (None: a vertex)
        self.last_foot: tuple[int, float] | None = None
        self.last_vertex: Any = None
        self._build_samples()
        self._edge_sign = [self._inward_sign(i) for i in range(len(self.edges))]
        self.convex_corners = np.array(
            [v for v in self.vertices if self._is_convex_corner(v)] + self._convex_kinks()
        ).reshape(-1, 3)

    # -- primitives

    def _build_samples(self, total: int = 6000, per_edge: int = 64) -> None:
        """Dense boundary samples (a KD-tree) seeding local projections; see :meth:`nearest`."""
        lengths = np.array([float(GCPnts_AbscissaPoint.Length_s(c)) for c in self.curves])
        pts, edge, par = [], [], []
        for i, c in enumerate(self.curves):
            k = max(per_edge, int(total * lengths[i] / lengths.sum()))
            ts = np.linspace(c.FirstParameter(), c.LastParameter(), k + 1)
            pts.extend(_xyz(c.Value(float(t))) for t in ts)
            edge.extend([i] * len(ts))
            par.extend(ts)
        self._spts = np.array(pts)
        self._sedge = np.array(edge)
        self._spar = np.array(par)
        steps = np.linalg.norm(np.diff(self._spts, axis=0), axis=1)
        steps[np.diff(self._sedge) != 0] = 0.0
        self._sh = float(steps.max())
        # DSS is exact on lines, circles and ellipses; only other edges need checking
        exact = {GeomAbs_Line, GeomAbs_Circle, GeomAbs_Ellipse}
        check = np.array([self.curves[i].GetType() not in exact for i in self._sedge])
        self._check_idx = np.flatnonzero(check)
        self._tree = cKDTree(self._spts[check]) if check.any() else None
        self._all_tree = cKDTree(self._spts)

    def _project_local(
        self, x: FloatArray, i: int, t: float, a: float, b: float
    ) -> tuple[float, FloatArray, float]:
        """Local minimum of ``|C_i(t) - x|`` for ``t`` in ``[a, b]`` by Newton from ``t``."""
        c = self.curves[i]
        p, d1, d2 = gp_Pnt(), gp_Vec(), gp_Vec()
        for _ in range(30):
            c.D2(t, p, d1, d2)
            r = _xyz(p) - x
            v1, v2 = _xyz(d1), _xyz(d2)
            f, df = r @ v1, v1 @ v1 + r @ v2
            step = -f / df if df > 0 else -f / max(v1 @ v1, 1e-300)
            t_new = min(max(t + step, a), b)
            # quadratic convergence: after a step this small the error is ~(1e-8 h)^2 / radius
            if abs(t_new - t) * math.sqrt(v1 @ v1) <= 1e-8 * self._sh:
                t = t_new
                break
            t = t_new
        q = _xyz(c.Value(t))
        return float(np.linalg.norm(q - x)), q, t

    def nearest(self, p: ArrayLike) -> tuple[float, FloatArray]:
        """``(dist(p, dF), nearest boundary point)``.

        ``BRepExtrema_DistShapeShape`` alone is not trusted: on B-spline edges it can miss
        the global minimum (a second, nearer foot on the same edge, the distance then jumps as
        the query point moves). Every local minimum of the dense boundary samples within
        reach of the sampled minimum seeds a Newton projection; the least distance wins.
        """
        x = np.asarray(p, dtype=float)
        d, q = self._dist.nearest(x)
        support, kind, par = self._dist.support()
        ei = (
            self.edge_index(support)
            if kind == BRepExtrema_SupportType.BRepExtrema_IsOnEdge and par is not None
            else None
        )
        self.last_foot = (ei, float(par)) if ei is not None and par is not None else None
        self.last_vertex = (
            TopoDS.Vertex_s(support)
            if kind == BRepExtrema_SupportType.BRepExtrema_IsVertex
            else None
        )
        if self._tree is None:
            return d, q
        # a foot nearer than d has a sample within h/2 of it, hence within d + h/2 of x
        idx = self._check_idx[
            np.array(self._tree.query_ball_point(x, d + 0.5 * self._sh), dtype=int)
        ]
        at_vertex = self.last_vertex is not None
        if len(idx) and not at_vertex:  # samples next to DSS's foot would only find it again
            idx = idx[np.linalg.norm(self._spts[idx] - q, axis=1) > 2.0 * self._sh]
        if len(idx) == 0:
            return d, q
        idx.sort()
        ds = np.linalg.norm(self._spts[idx] - x, axis=1)
        n = len(self._spts)
        full = (
            np.linalg.norm(self._spts[np.clip(idx - 1, 0, n - 1)] - x, axis=1),
            np.linalg.norm(self._spts[np.clip(idx + 1, 0, n - 1)] - x, axis=1),
        )
        same_prev = self._sedge[np.clip(idx - 1, 0, n - 1)] == self._sedge[idx]
        same_next = self._sedge[np.clip(idx + 1, 0, n - 1)] == self._sedge[idx]
        is_min = (~same_prev | (ds <= full[0])) & (~same_next | (ds <= full[1]))
        cand = idx[is_min]
        cand = cand[np.argsort(np.linalg.norm(self._spts[cand] - x, axis=1))][:12]
        for j in cand:
            i = int(self._sedge[j])
            a = self._spar[j - 1] if j > 0 and self._sedge[j - 1] == i else self._spar[j]
            b = self._spar[j + 1] if j + 1 < n and self._sedge[j + 1] == i else self._spar[j]
            dj, qj, tj = self._project_local(x, i, float(self._spar[j]), float(a), float(b))
            # a vertex DSS settled on (within its 1e-7 deflection) yields to a foot inside
            # an edge as near: beside the smooth seam of a closed B-spline the feet either
            # side of it are the true ones (a foot at an edge's end is its vertex again)
            if dj < d - 1e-15 * max(1.0, d) or (at_vertex and dj <= d + self.eps):
                d, q, self.last_foot, self.last_vertex = dj, qj, (i, tj), None
        return d, q

    def distances(self, points: ArrayLike) -> FloatArray:
        return self._dist.distances(points)

    def inside(self, p: ArrayLike, tol: float | None = None, clearance: float = 0.0) -> bool:
        """Whether ``p`` is in the closed face (and within ``tol`` of its plane);
        ``clearance``: a distance from ``p`` known to be free of boundary (0: unknown)."""
        q = np.asarray(p, dtype=float)
        tol = self.class_tol if tol is None else tol
        if abs((q - self.vertices[0]) @ self.normal) > max(tol, 1e-9 * self.diag):
            return False
        # OCC's classifier casts a ray and can miscount where the ray passes exactly
        # through a vertex (seen on a random polygon with a triangular hole: a branch point
        # 0.36 deep inside came back OUT); a majority of three votes, at q and at q moved
        # half the clearance (or 1e-6 diag) along two directions in the plane, avoids
        # the degenerate ray.
        n = np.asarray(self.normal, dtype=float)
        e1 = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
        # the moved points must stay on q's side of the boundary: within half the
        # clearance (a 1e-6 diag step left a point 7e-5 inside a 1e-3 notch's corner)
        if clearance <= 0:
            # a lower bound from the dense boundary samples (every boundary point is within
            # a sample step of one); the exact distance only within a step of the boundary
            clearance = float(self._all_tree.query(q)[0]) - self._sh
        if clearance <= 0:
            saved = self.last_foot, self.last_vertex
            clearance = self.nearest(q)[0]
            self.last_foot, self.last_vertex = saved
        step = 0.5 * clearance
        votes = sum(
            BRepClass_FaceClassifier(self.face, _pnt(x), tol).State() != TopAbs_OUT
            for x in (q, q + step * e1, q + step * (0.6 * e1 + 0.8 * e2))
        )
        return bool(votes >= 2)

    def _probe(self, q: FloatArray, u: FloatArray, s: float) -> tuple[bool, float, FloatArray]:
        """Is ``q + s u`` at or before the medial point? Both ``dist >= s - eps`` and "its
        nearest boundary point is still ``q`` (within ``eta``)" must hold: the first alone
        resolves ``s*`` only to ``sqrt(eps * r)`` where the axis ends at a curvature centre
        (there ``dist - s`` vanishes to second order while the footpoint moves like
        ``sqrt(s - s*)``)."""
        x = q + s * u
        d, b = self.nearest(x)
        w = (x - b) / d if d > 0 else u
        ok = d >= s - self.eps and (d >= s or float(np.linalg.norm(b - q)) <= self.eta)
        return ok, d, w

    def _sampled_depth_bound(self, q: FloatArray, u: FloatArray) -> float:
        """An upper bound of the medial depth: the least radius of the disks tangent at ``q``
        (centre on ``q + s u``) through a boundary sample ``y``: ``|y - q|^2 / (2 u.(y - q))``."""
        v = self._spts - q
        h = v @ u
        ok = (h > 1e-9 * self.diag) & (np.einsum("ij,ij->i", v, v) > (1e-4 * self.diag) ** 2)
        if not ok.any():
            return math.inf
        return float(np.min(np.einsum("ij,ij->i", v[ok], v[ok]) / (2 * h[ok])))

    def end_vertex(self, i: int, t: float) -> Any:
        """The vertex of edge ``i`` at parameter ``t`` if ``t`` is one of its ends (within
        1e-12 of its range), else None."""
        c = self.curves[i]
        t0, t1 = c.FirstParameter(), c.LastParameter()
        slack = 1e-12 * max(abs(t1 - t0), 1.0)
        if abs(t - t0) <= slack:
            return TopExp.FirstVertex_s(self.edges[i])
        if abs(t - t1) <= slack:
            return TopExp.LastVertex_s(self.edges[i])
        return None

    def feet_at_vertex(self, vertex: Any, u: FloatArray) -> list[tuple[int, float]]:
        """``(edge, parameter)`` at ``vertex`` of the edges whose inward normal there is ``u``
        (both sides of a smooth joint, or of the seam of a closed edge); empty at a corner."""
        out = []
        for i, e in enumerate(self.edges):
            c = self.curves[i]
            # both ends of a closed edge (the seam of a periodic B-spline, perhaps only C1
            # there: the two sides' curvatures differ); the parameter of the vertex alone
            # names one of them
            for end, t in (
                (TopExp.FirstVertex_s(e), c.FirstParameter()),
                (TopExp.LastVertex_s(e), c.LastParameter()),
            ):
                if end.IsSame(vertex):
                    _, nrm = self.inward_normal(i, t)
                    if float(nrm @ u) > 1 - 1e-10:
                        out.append((i, float(t)))
        return out

    def curvature_radius(self, i: int, t: float) -> float:
        """``1/k`` for the curvature ``k`` of edge ``i`` at ``t``, signed positive where the
        boundary is convex (bends towards the interior); ``inf`` where it is not."""
        p, d1, d2 = gp_Pnt(), gp_Vec(), gp_Vec()
        self.curves[i].D2(t, p, d1, d2)
        v1 = _xyz(d1)
        if float(v1 @ v1) <= 1e-300:  # a stalled end (repeated pole): no curvature bound
            return math.inf
        _, nrm = self.inward_normal(i, t)
        k = float(_xyz(d2) @ nrm) / float(v1 @ v1)
        return 1.0 / k if k > 1e-12 / self.diag else math.inf

    def medial_depth(
        self,
        q: ArrayLike,
        u: ArrayLike,
        guess: float | None = None,
        max_depth: float = math.inf,
    ) -> float:
        """Largest ``s`` with ``dist(q + s u, dF) >= s - eps`` for a boundary point ``q`` and an
        inward unit direction ``u`` (the ray must enter the face).

        ``max_depth``: a known upper bound; pass the radius of curvature at ``q`` when ``u`` is
        the normal there (the curvature criterion, exact where distances alone resolve the
        depth only to second order: at curvature-centre end points)."""
        q = np.asarray(q, dtype=float)
        u = np.asarray(u, dtype=float)
        u = u / np.linalg.norm(u)
        xtol = self.eps
        bound = min(1.01 * self.diag, self._sampled_depth_bound(q, u), max_depth)
        lo, hi = 0.0, bound + 10 * self.eps
        s = guess if guess is not None and lo < guess < hi else hi - 5 * self.eps
        expand, oks, fails = xtol, 0, 0
        for it in range(400):
            ok, d, w = self._probe(q, u, s)
            if ok:
                lo, oks, fails = s, oks + 1, 0
            else:
                hi, oks, fails = s, 0, fails + 1
            if hi - lo <= xtol:
                break
            cand: float | None = None
            if ok:  # step right, growing: a good guess is confirmed in one more probe
                expand = xtol if oks == 1 else 8.0 * expand
                cand = lo + expand
            else:
                slope = float(u @ w) - 1.0
                if slope < -1e-15:
                    newton = s - (d - s) / slope  # from the right: newton <= s
                    # slow (second-order) convergence: overshoot on purpose to find an ok
                    cand = newton if fails <= 2 else hi - 4.0 * (hi - newton)
                    if hi - cand < 0.5 * xtol:
                        cand = hi - xtol
            # every fourth probe bisects: the predicate is monotone, so the bracket halves
            # at least that often (Newton from a far failure can keep landing on one ok point)
            if cand is None or not (lo < cand < hi) or it % 4 == 3:
                cand = 0.5 * (lo + hi)
            s = cand
        else:
            raise RuntimeError(f"ray depth did not converge: bracket [{lo}, {hi}]")
        return 0.5 * (lo + hi)

    # -- boundary geometry

    def _tangent(self, i: int, t: float) -> tuple[FloatArray, FloatArray]:
        p, v = gp_Pnt(), gp_Vec()
        self.curves[i].D1(t, p, v)
        return _xyz(p), _xyz(v)

    def _inward_sign(self, i: int) -> float:
        """+1 if ``normal x tangent`` points into the face along edge ``i``, else -1 (decided
        by classifying probes on both sides of a few points of the edge)."""
        c = self.curves[i]
        votes = 0.0
        for f in (0.5, 0.3, 0.7, 0.1, 0.9):  # stops after two agreeing votes
            t = c.FirstParameter() + f * (c.LastParameter() - c.FirstParameter())
            b, tan = self._tangent(i, t)
            nrm = np.cross(self.normal, tan)
            if np.linalg.norm(nrm) == 0:
                continue
            nrm /= np.linalg.norm(nrm)
            for delta in (1e-4 * self.diag, 1e-6 * self.diag, 100 * self.class_tol):
                plus = self.inside(b + delta * nrm, self.class_tol)
                minus = self.inside(b - delta * nrm, self.class_tol)
                if plus != minus:
                    votes += 1.0 if plus else -1.0
                    break
            if abs(votes) >= 2:
                break
        if votes == 0:
            raise RuntimeError(f"oracle: cannot orient edge {i}")
        return 1.0 if votes > 0 else -1.0

    def inward_normal(self, i: int, t: float) -> tuple[FloatArray, FloatArray]:
        """``(point, inward unit normal)`` of edge ``i`` at parameter ``t``."""
        b, tan = self._tangent(i, t)
        n = np.cross(self.normal, tan)
        return b, self._edge_sign[i] * n / np.linalg.norm(n)

    def _convex_kinks(self) -> list[FloatArray]:
        """Convex corners inside an edge: where OCC's adaptor says the curve is not C1 (a
        B-spline knot of multiplicity >= its degree) and the tangents either side differ."""
        out = []
        for i, c in enumerate(self.curves):
            n = c.NbIntervals(GeomAbs_C1)
            if n < 2:
                continue
            arr = TColStd_Array1OfReal(1, n + 1)
            c.Intervals(arr, GeomAbs_C1)
            h = 1e-9 * (c.LastParameter() - c.FirstParameter())
            for k in range(2, n + 1):
                t = arr.Value(k)
                p, before = self._tangent(i, t - h)
                _, after = self._tangent(i, t + h)
                d0, d1 = -before / np.linalg.norm(before), after / np.linalg.norm(after)
                bis = d0 + d1
                if np.linalg.norm(bis) < 1e-7 or abs(d0 @ d1 + 1.0) < 1e-12:
                    continue  # a smooth join
                if self.inside(p + min(1e-4 * self.diag, 1e-3) * bis / np.linalg.norm(bis)):
                    out.append(p)
        return out

    def _is_convex_corner(self, v: FloatArray) -> bool:
        """A vertex is a convex corner iff the probe on the bisector of the two edge directions
        leaving it lies in the face (an interior angle below 180 degrees); a G1 joint is not."""
        dirs = []
        for i, e in enumerate(self.edges):
            c = self.curves[i]
            ex = TopExp_Explorer(e, TopAbs_VERTEX)
            while ex.More():
                vx = TopoDS.Vertex_s(ex.Current())
                if np.linalg.norm(_xyz(BRep_Tool.Pnt_s(vx)) - v) <= 10 * self.edge_tol:
                    t = BRep_Tool.Parameter_s(vx, e)
                    first = abs(t - c.FirstParameter()) <= abs(t - c.LastParameter())
                    t0, t1 = c.FirstParameter(), c.LastParameter()
                    _, tan = self._tangent(i, t0 if first else t1)
                    if np.linalg.norm(tan) < 1e-12:  # zero end derivative: limit from inside
                        step = 1e-7 * (t1 - t0)
                        _, tan = self._tangent(i, t0 + step if first else t1 - step)
                    dirs.append((1.0 if first else -1.0) * tan / np.linalg.norm(tan))
                ex.Next()
        if len(dirs) != 2:
            raise RuntimeError(f"oracle: vertex with {len(dirs)} edge ends")
        bis = dirs[0] + dirs[1]
        if np.linalg.norm(bis) < 1e-7:  # tangent joint
            return False
        dmin = min(
            (float(np.linalg.norm(v - w)) for w in self.vertices if np.linalg.norm(v - w) > 0),
            default=self.diag,
        )
        delta = min(1e-4 * self.diag, 0.1 * dmin)
        return self.inside(v + delta * bis / np.linalg.norm(bis))

    def edge_length(self, i: int) -> float:
        return float(GCPnts_AbscissaPoint.Length_s(self.curves[i]))

    def boundary_samples(self, n: int) -> tuple[FloatArray, FloatArray, list[tuple[int, float]]]:
        """About ``n`` boundary points spread by length (parameter midpoints, never a vertex):
        ``(points (N, 3), inward normals (N, 3), [(edge, param)])``."""
        lengths = np.array([self.edge_length(i) for i in range(len(self.edges))])
        pts, nrms, where = [], [], []
        for i, length in enumerate(lengths):
            k = max(2, round(n * length / lengths.sum()))
            c = self.curves[i]
            t0, t1 = c.FirstParameter(), c.LastParameter()
            for j in range(k):
                t = t0 + (j + 0.5) / k * (t1 - t0)
                b, nrm = self.inward_normal(i, t)
                pts.append(b), nrms.append(nrm), where.append((i, t))
        return np.array(pts), np.array(nrms), where

    def sharp_tips(self, max_radius: float) -> FloatArray:
        """``(N, 3)`` centres of curvature of the convex curvature maxima whose radius is at
        most ``max_radius``: tips so sharp that their end point lies within that distance
        of the boundary (at the tolerance they are corners)."""
        out = [c for r, c in self._curvature_tips() if r <= max_radius]
        return np.array(out).reshape(-1, 3)

    def _curvature_tips(self) -> list[tuple[float, FloatArray]]:
        """``(radius, centre)`` of every convex curvature maximum (computed once): each is
        bracketed on the dense samples and refined by a bounded scalar search."""
        if not hasattr(self, "_tips"):
            tips: list[tuple[float, FloatArray]] = []
            for i, c in enumerate(self.curves):
                if c.GetType() == GeomAbs_Line:
                    continue
                ts = self._spar[self._sedge == i]
                if c.GetType() == GeomAbs_Circle:  # one centre (an arc: every point a maximum)
                    t = float(ts[len(ts) // 2])
                    rho_c = self.curvature_radius(i, t)
                    if np.isfinite(rho_c):
                        b, n = self.inward_normal(i, t)
                        tips.append((rho_c, b + rho_c * n))
                    continue
                rho = np.array([self.curvature_radius(i, float(t)) for t in ts])
                inner = np.flatnonzero((rho[1:-1] <= rho[:-2]) & (rho[1:-1] <= rho[2:])) + 1
                brackets = [(float(ts[j - 1]), float(ts[j + 1]), float(ts[j])) for j in inner]
                t0, t1 = float(ts[0]), float(ts[-1])
                # a smooth closed curve's seam is a point like any other (parameters past
                # its end wrap round to its start)
                u0, u1 = self._tangent(i, t0)[1], self._tangent(i, t1)[1]
                smooth = float(u0 @ u1) > (1 - 1e-12) * float(
                    np.linalg.norm(u0) * np.linalg.norm(u1)
                )
                if c.IsClosed() and smooth and rho[0] <= rho[1] and rho[-1] <= rho[-2]:
                    brackets.append((float(ts[-2]), t1 + float(ts[1]) - t0, t1))

                def radius(x: float, i: int = i, t0: float = t0, t1: float = t1) -> float:
                    return self.curvature_radius(i, x - (t1 - t0) if x > t1 else x)

                for lo, hi, mid in brackets:
                    opt = minimize_scalar(
                        radius,
                        bounds=(lo, hi),
                        method="bounded",
                        options={"xatol": 1e-14 * max(1.0, abs(mid))},
                    )
                    if np.isfinite(opt.fun):
                        x = float(opt.x)
                        b, n = self.inward_normal(i, x - (t1 - t0) if x > t1 else x)
                        tips.append((float(opt.fun), b + float(opt.fun) * n))
            self._tips = tips
        return self._tips

    def curvature_ends(self, slack: float) -> FloatArray:
        """``(N, 3)`` centres of the convex curvature maxima whose osculating disk is
        empty (no boundary point nearer its centre than its radius less ``slack``): every
        one is an end point of the medial axis (THEORY.md), however short its branch."""
        out = []
        for rho, c in self._curvature_tips():
            d, _ = self.nearest(c)
            if d >= rho - slack and self.inside(c, clearance=d):
                out.append(c)
        return np.array(out).reshape(-1, 3)

    def near_convex_corner(self, p: FloatArray, dist: float) -> bool:
        if len(self.convex_corners) == 0:
            return False
        return bool(np.linalg.norm(self.convex_corners - p, axis=1).min() <= dist)

    def edge_index(self, shape: TopoDS_Shape) -> int | None:
        if not hasattr(self, "_edge_hash"):
            self._edge_hash: dict[int, list[int]] = {}
            for i, e in enumerate(self.edges):
                self._edge_hash.setdefault(hash(e), []).append(i)
        for i in self._edge_hash.get(hash(shape), range(len(self.edges))):
            if self.edges[i].IsSame(shape):
                return i
        for i, e in enumerate(self.edges):  # hash of a differently oriented copy
            if e.IsSame(shape):
                return i
        return None

    # -- the medial axis near a point

    def medial_point(self, i: int, t: float) -> FloatArray:
        """The true medial point ``b + s* n`` of the boundary point of edge ``i`` at ``t``."""
        b, nrm = self.inward_normal(i, t)
        # (the osculating radius where the osculating disk is in the face: the ray
        # bisection is ill-conditioned there, and read 0.0044 for 0.01 next to an
        # ellipse's vertex far from the origin)
        return b + _depth(self, b, nrm, self.curvature_radius(i, t)) * nrm

    def local_medial_distance(self, p: FloatArray, i: int, t: float, window: float) -> float:
        """Distance from ``p`` to the true medial points whose footpoint on edge ``i`` lies
        within arc length ``window`` of parameter ``t`` (a local 1D minimisation)."""
        c = self.curves[i]
        t0, t1 = c.FirstParameter(), c.LastParameter()
        speed = max(float(np.linalg.norm(self._tangent(i, t)[1])), 1e-300)
        a, b = t - window / speed, t + window / speed
        # a closed edge (a periodic B-spline's loop) goes on across its seam
        closed = bool(c.IsClosed()) and b - a < t1 - t0
        if not closed:
            a, b = max(t0, a), min(t1, b)

        def f(tt: float) -> float:
            if closed:
                tt = t0 + (tt - t0) % (t1 - t0)
            return float(np.linalg.norm(p - self.medial_point(i, tt)))

        return _local_min(f, a, b)

    def local_bisector_distance(self, p: FloatArray, i: int, t: float) -> float:
        """Distance from ``p`` to the true medial points touching two of the edges near
        it (edge ``i``, its foot's, near ``t``, among them): the point where the distances
        to the two edges agree, by Newton on their difference from ``p``. At a nearly flat convex
        corner (turn ``a``) the ray depth cannot resolve the spoke: along it the distances
        to the two sides differ by ``(1 - cos a) s``, below rounding for ``a`` ~ 1e-5,
        while their gradients differ by ``a``: the difference's root is resolved to
        rounding / ``a``. ``inf`` when no such medial point exists near ``p``."""
        best = math.inf
        inf = math.inf
        # every pair of the edges near p: its foot's own, or two others (a foot on a tiny
        # fillet rounding the corner: the spoke beyond its centre is the sides' bisector),
        # and a second foot on the foot's own edge (a branch off a curvature maximum of a
        # nearly circular outline: its spokes nearly parallel to it, the ray depth
        # magnifies an offset across it ten times over)
        cands = [(i, t), *self._second_edges(p, i), *self._same_edge_feet(p, i, t)]
        for (i, t), (j, tj) in itertools.combinations(cands, 2):
            # the feet may leave the edges while Newton runs (``p`` off the spoke has
            # its foot beyond the corner on one side): project onto the curves' extensions
            params = [t, tj]

            def foot(x: FloatArray, k: int, e: int, params: list[float] = params) -> FloatArray:
                _, q, params[k] = self._project_local(x, e, params[k], -inf, inf)
                return q

            c, _ = equidistant_point(
                np.asarray(p, dtype=float),
                lambda x, i=i: foot(x, 0, i),
                lambda x, j=j: foot(x, 1, j),
                self.eps,
                self.diag,
            )
            di, qi, ti = self._project_local(c, i, params[0], -inf, inf)
            dj, qj, tj = self._project_local(c, j, params[1], -inf, inf)
            # a tangent contact inside each edge, and the disk empty
            if not (self._inside_range(i, ti) and self._inside_range(j, tj)):
                continue
            if abs(di - dj) > self.eta or self.nearest(c)[0] < di - self.eta:
                continue
            # two distinct feet (on one edge both projections may slide to the same one;
            # on either side of a closed edge's seam they are distinct however close)
            if i == j and float(np.linalg.norm(qi - qj)) < 100.0 * self.eta:
                c_i = self.curves[i]
                span = c_i.LastParameter() - c_i.FirstParameter()
                # (a smooth seam's other side lands on the extension, out of range)
                if not (self._closed(i) and abs(ti - tj) > 0.5 * span):
                    continue
            best = min(best, float(np.linalg.norm(np.asarray(p) - c)))
        return best

    def _same_edge_feet(self, p: FloatArray, i: int, t: float) -> list[tuple[int, float]]:
        """``(i, parameter)`` of the samples of edge ``i`` where the distance to ``p`` has a
        local minimum within 1.5 times ``p``'s distance to the boundary, other than the
        one nearest ``t`` (the foot's own)."""
        x = np.asarray(p, dtype=float)
        sel = np.flatnonzero(self._sedge == i)
        if len(sel) < 3:
            return []
        dist = np.linalg.norm(self._spts[sel] - x, axis=1)
        par = self._spar[sel]
        # both feet within a sample cell of each other (a short branch into a flat
        # curvature maximum between them): seeds a fraction of the cell to either side
        cell = float(np.median(np.abs(np.diff(par))))
        near = [(i, t + s * f * cell) for f in (0.5, 0.2, 0.05) for s in (-1.0, 1.0)]
        limit = 1.5 * float(dist.min()) + self._sh
        if self._closed(i) and dist[0] <= limit and dist[0] <= dist[1] and dist[-1] <= dist[-2]:
            # a closed edge's seam nearest p (a corner there: its spoke's feet lie on
            # either side of it): the other side's end seeds the second foot
            c = self.curves[i]
            t0, t1 = c.FirstParameter(), c.LastParameter()
            near.append((i, t0 + 0.05 * cell if t - t0 > t1 - t else t1 - 0.05 * cell))
        inner = (dist[1:-1] <= dist[:-2]) & (dist[1:-1] <= dist[2:])
        minima = np.flatnonzero(inner) + 1
        if len(minima) < 2:
            return near
        own = minima[int(np.argmin(np.abs(par[minima] - t)))]
        return near + [(i, float(par[k])) for k in minima if k != own and dist[k] <= limit]

    def _closed(self, i: int) -> bool:
        """Whether edge ``i`` is closed on itself (its seam a point of the loop)."""
        return self._closed_edges[i]

    def _ends_meet(self, c: Any) -> bool:
        a, b = _xyz(c.Value(c.FirstParameter())), _xyz(c.Value(c.LastParameter()))
        return float(np.linalg.norm(a - b)) <= self.eta

    def _inside_range(self, i: int, t: float) -> bool:
        c = self.curves[i]
        return c.FirstParameter() < t < c.LastParameter() and self.end_vertex(i, t) is None

    def _second_edges(self, p: FloatArray, i: int) -> list[tuple[int, float]]:
        """``(edge, parameter of its sample nearest p)`` of the edges other than ``i`` that
        come within 1.5 times ``p``'s distance to the boundary."""
        x = np.asarray(p, dtype=float)
        dist = np.linalg.norm(self._spts - x, axis=1)
        d = float(dist.min())
        out = []
        for j in range(len(self.edges)):
            if j == i:
                continue
            sel = np.flatnonzero(self._sedge == j)
            k = sel[int(np.argmin(dist[sel]))]
            if dist[k] <= 1.5 * d + self._sh:
                out.append((j, float(self._spar[k])))
        return out

    def local_medial_distance_at_vertex(
        self, p: FloatArray, v: FloatArray, u: FloatArray, window: float
    ) -> float:
        """Distance from ``p`` to the true medial points of the disks touching the vertex
        ``v`` in directions within angle ``window`` of ``u`` (the vertex analogue of
        :meth:`local_medial_distance`: next to a reflex vertex the disks touch the vertex
        and an edge nearly opposite it, where the ray depth magnifies an offset across
        the axis many times over)."""
        n = np.asarray(self.normal, dtype=float)
        e1 = np.asarray(u, dtype=float)
        e2 = np.cross(n, e1)

        def f(th: float) -> float:
            w = math.cos(th) * e1 + math.sin(th) * e2
            return float(np.linalg.norm(p - (v + self.medial_depth(v, w) * w)))

        return _local_min(f, -window, window)


def equidistant_point(
    x0: FloatArray,
    foot_a: Callable[[FloatArray], FloatArray],
    foot_b: Callable[[FloatArray], FloatArray],
    eps: float,
    diag: float,
) -> tuple[FloatArray, bool]:
    """The point where the distances to two curves or surfaces agree, by Newton on their
    difference from ``x0`` (the bisector refinement of both soundness oracles: along a
    spoke between nearly parallel contacts, turning by ``a``, the distances differ by
    ``(1 - cos a) s``, below rounding, while their gradients differ by ``a``: the root is
    resolved to rounding / ``a``). ``foot_a``, ``foot_b``: the nearest point of each
    (warm-started by the caller). Returns the point and whether Newton stopped on a
    degenerate step (a foot at the point, or parallel gradients) instead of converging;
    the caller checks that the point is medial."""
    c = np.asarray(x0, dtype=float).copy()
    for _ in range(60):
        qa, qb = foot_a(c), foot_b(c)
        da, db = float(np.linalg.norm(c - qa)), float(np.linalg.norm(c - qb))
        if da <= 0 or db <= 0:
            return c, True
        g = (c - qa) / da - (c - qb) / db
        gg = float(g @ g)
        if gg <= 1e-30:
            return c, True
        step = (da - db) * g / gg
        c = c - step
        # (the root is resolved to rounding / |g| only: steps of that size dither)
        if float(np.linalg.norm(step)) <= eps + 1e-12 * diag / math.sqrt(gg):
            break
    return c, False


def _local_min(f: Any, a: float, b: float) -> float:
    """The least value of ``f`` on ``[a, b]``: a 13-point grid, then a bounded Brent
    search around its best point, in an offset from it (Brent's resolution is
    ``sqrt(eps) |x|``: at an edge parameter of 50 it was 7.5e-7, which a medial point
    moving 100 times faster than its foot turns into 67 tol at 1e-8 diag)."""
    grid = np.linspace(a, b, 13)
    vals = [f(tt) for tt in grid]
    k = int(np.argmin(vals))
    x0 = float(grid[k])
    lo, hi = float(grid[max(k - 1, 0)]) - x0, float(grid[min(k + 1, len(grid) - 1)]) - x0
    if hi <= lo:
        return float(vals[k])
    res = minimize_scalar(
        lambda dx: f(x0 + dx),
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": (hi - lo) * 1e-9},
    )
    return float(min(vals[k], res.fun))


def _boundary(face: Any) -> FaceBoundary:
    return face if isinstance(face, FaceBoundary) else FaceBoundary(face)


# --------------------------------------------------------------------------- the oracles


def soundness_2d(face: Any, points3d: ArrayLike, tol: float, refine: bool = True) -> FloatArray:
    """Soundness errors of output samples: how far each sample is from being medial.

    For a sample ``p``: ``q`` = nearest boundary point, ``u = (p - q)/|p - q|``, ``s*`` the medial
    depth of ``q`` along ``u``; the error is ``|s* - |p - q||`` (0 on the medial axis). A sample
    outside the face (or off its plane by more than ``tol``) is ``inf``. A sample within ``tol``
    of the boundary is 0 if it is within ``tol`` of a convex corner (an ``r = 0`` end point)
    or of the centre of a tip sharper than ``2 tol`` (:meth:`FaceBoundary.sharp_tips`), else
    its distance to the nearest of them (or ``inf``).

    The ray error magnifies a sample's offset ``delta`` across the axis by ``1/sin(theta)``
    (``theta``: angle between the ray and the axis), which blows up near curvature-centre end
    points. With ``refine`` (default), samples whose ray error exceeds ``tol/2`` are
    re-measured as their distance to the true medial points whose footpoints lie near ``q``
    (a local minimisation over the footpoint parameter), and the smaller value is returned.

    Args:
        face: the planar face (or a :class:`FaceBoundary` to reuse).
        points3d: ``(N, 3)`` model-space samples.
        tol: the result's tolerance (absolute).
    """
    fb = _boundary(face)
    pts = np.atleast_2d(np.asarray(points3d, dtype=float))
    errs = np.empty(len(pts))
    for k, p in enumerate(pts):
        if abs((p - fb.vertices[0]) @ fb.normal) > max(tol, 1e-9 * fb.diag):
            errs[k] = np.inf
            continue
        d, q = fb.nearest(p)
        if d <= tol:
            # r = 0 end points, and the ends at tips sharper than the tolerance
            ends = np.vstack([fb.convex_corners, fb.sharp_tips(2.0 * tol)])
            if len(ends) == 0:
                errs[k] = np.inf
            else:
                dc = float(np.linalg.norm(ends - p, axis=1).min())
                errs[k] = 0.0 if dc <= tol else dc
            continue
        if not fb.inside(p, clearance=d):
            errs[k] = np.inf
            continue
        foot = fb.last_foot
        u = (p - q) / d
        feet = [foot] if foot is not None else []
        vertex = fb.last_vertex if foot is None else fb.end_vertex(*foot)
        if vertex is not None:
            # a foot at a vertex (BRepExtrema may report it on an edge's end): the edges
            # whose normal there is u, none at a corner (a reflex vertex's parabola is not
            # capped by the curvature of the edge that ends there)
            feet = fb.feet_at_vertex(vertex, u)
            foot = feet[0] if feet else None
        # the curvature criterion on every side of the foot (a G1 line-arc joint: the arc's)
        kappa_r = min((fb.curvature_radius(*f) for f in feet), default=math.inf)
        s_star = fb.medial_depth(q, u, guess=d, max_depth=kappa_r)
        e = abs(s_star - d)
        if refine and e > 0.5 * tol:
            window = 4.0 * math.sqrt(e * fb.diag) + 4.0 * e
            if foot is not None:
                e = min(e, fb.local_medial_distance(p, foot[0], foot[1], window))
                if e > 0.5 * tol:  # a feature narrower than the window's grid step (a
                    # flat curvature maximum 1e-3 wide between two feet of a branch point)
                    e = min(e, fb.local_medial_distance(p, foot[0], foot[1], 4 * e + tol))
                if e > 0.5 * tol:  # next to a nearly flat corner: the bisector
                    e = min(e, fb.local_bisector_distance(p, foot[0], foot[1]))
            elif vertex is not None:  # a reflex vertex
                e = min(e, fb.local_medial_distance_at_vertex(p, q, u, min(window / d, 0.5)))
        errs[k] = e
    return errs


def medial_points_2d(face: Any, n_samples: int) -> tuple[FloatArray, FloatArray, FloatArray]:
    """True medial points from boundary samples: ``(b (N, 3), m (N, 3), radius (N,))`` with
    ``m = b + s* n`` (``n`` the inward normal at ``b``, ``s*`` its medial depth)."""
    fb = _boundary(face)
    b, nrm, where = fb.boundary_samples(n_samples)
    s = np.array(
        [
            _depth(fb, bi, ni, fb.curvature_radius(i, t))
            for bi, ni, (i, t) in zip(b, nrm, where, strict=True)
        ]
    )
    return b, b + s[:, None] * nrm, s


def _depth(fb: FaceBoundary, b: FloatArray, n: FloatArray, rho: float) -> float:
    """Medial depth of ``b``: the osculating radius ``rho`` when the osculating disk lies
    in the face (its centre is at least ``rho`` from the boundary: exact, where the ray
    bisection is ill-conditioned, as every point of an arc is nearly as near as ``b``),
    else the ray-depth bisection."""
    if np.isfinite(rho) and rho > 0:
        d, _ = fb.nearest(b + rho * n)
        if d >= rho - fb.eps and fb.inside(b + rho * n, clearance=d):
            return float(rho)
    return fb.medial_depth(b, n, max_depth=rho)


def completeness_2d(
    face: Any,
    compound_or_points: Any,
    n_samples: int = 200,
    corner_skip: float | None = None,
) -> FloatArray:
    """Completeness errors: distance from true medial points to the output.

    Boundary samples ``b`` (spread by length, never at a vertex) with inward normals ``n`` give
    true medial points ``m = b + s* n``; the error of each is the distance from ``m`` to the
    output: a shape (``to_compound()``; ``BRepExtrema_DistShapeShape``) or an ``(N, 3)`` array of
    points (nearest point, so it includes the sampling gap). Samples within ``corner_skip``
    (default ``1e-6`` of the diagonal) of a convex corner are skipped (NaN).
    """
    fb = _boundary(face)
    b, m, _ = medial_points_2d(fb, n_samples)
    skip = 1e-6 * fb.diag if corner_skip is None else corner_skip
    keep = np.array([not fb.near_convex_corner(bi, skip) for bi in b])
    errs = np.full(len(b), np.nan)
    if isinstance(compound_or_points, (np.ndarray, Sequence)):
        out = np.atleast_2d(np.asarray(compound_or_points, dtype=float))
        errs[keep] = cKDTree(out).query(m[keep])[0]
    else:
        target = ShapeDistance(compound_or_points)
        errs[keep] = target.distances(m[keep])
    return errs


def radius_error_2d(face: Any, points3d: ArrayLike, radii: ArrayLike) -> FloatArray:
    """``|r - dist(p, dF)|`` for each sample ``p`` and the radius ``r`` it carries."""
    fb = _boundary(face)
    return np.abs(np.asarray(radii, dtype=float) - fb.distances(points3d))
