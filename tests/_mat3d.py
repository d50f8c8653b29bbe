"""Shared helpers of the 3D medial-axis tests: solids with closed-form MATs, sampling of the
output on its own faces (with the radius it carries), and one oracle report per case.

The solids are built with plain OCP/cadquery (extruding the faces of :mod:`tests.faces`); the
output is judged only through :mod:`tests.oracles3d`, through OCCT's own measurements (areas,
lengths, ``BRepCheck``) and through the closed forms of THEORY.md Sec. 4.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex, BRepBuilderAPI_Transform
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepExtrema import BRepExtrema_DistShapeShape, BRepExtrema_ExtPC, BRepExtrema_ExtPF
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakePrism
from OCP.BRepTools import BRepTools
from OCP.Extrema import Extrema_ExtAlgo, Extrema_ExtFlag
from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.GeomAbs import GeomAbs_Line
from OCP.gp import gp_Pnt, gp_Vec
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_SOLID
from OCP.TopExp import TopExp
from OCP.TopoDS import TopoDS, TopoDS_Shape, TopoDS_Solid
from OCP.TopTools import TopTools_IndexedDataMapOfShapeListOfShape, TopTools_IndexedMapOfShape
from scipy.spatial import cKDTree

from tests import faces as F
from tests import oracles3d as O

FloatArray = NDArray[np.float64]


# --------------------------------------------------------------------------- solids


def prism(face: Any, length: float, placement: F.Placement = F.IDENTITY) -> TopoDS_Solid:
    """``face`` (in the local xy-plane) extruded by ``length`` along +z, then placed."""
    shape = BRepPrimAPI_MakePrism(face, gp_Vec(0.0, 0.0, float(length))).Shape()
    if placement is not F.IDENTITY:
        shape = BRepBuilderAPI_Transform(shape, placement.trsf(), True).Shape()
    return single_solid(shape)


def single_solid(shape: TopoDS_Shape) -> TopoDS_Solid:
    m = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, TopAbs_SOLID, m)
    assert m.Extent() == 1, f"expected one solid, got {m.Extent()}"
    return TopoDS.Solid_s(m.FindKey(1))


def box(a: float, b: float, c: float) -> TopoDS_Solid:
    """The box ``[0, a] x [0, b] x [0, c]``."""
    return single_solid(BRepPrimAPI_MakeBox(a, b, c).Shape())


def cylinder(r: float, h: float) -> TopoDS_Solid:
    """The disk of radius ``r`` extruded by ``h`` along +z."""
    return prism(F.circle(r), h)


def elliptic_prism(a: float, b: float, length: float, seam: float | None = None) -> TopoDS_Solid:
    return prism(F.ellipse(a, b, seam), length)


def tube(ri: float, ro: float, h: float) -> TopoDS_Solid:
    return prism(F.annulus(ri, ro), h)


# --------------------------------------------------------------------------- the MAT


def extrusion_mat(solid: Any, tol: float | None = None) -> Any:
    """The MAT of ``solid`` read as an extrusion (a solid that is also a revolution, like a
    tube, is read as an extrusion here whichever reading the recogniser prefers)."""
    import medialcad.api as api
    from medialcad.mat3d.solid import medial_axis_of
    from medialcad.recognition import Extrusion, recognize

    reading = recognize(solid)
    if not isinstance(reading, Extrusion):
        assert isinstance(reading.alternative, Extrusion), "not an extrusion"
        reading = reading.alternative
        return medial_axis_of(reading, tol, {})
    return api.medial_axis(solid, tol=tol)


# --------------------------------------------------------------------------- measuring shapes


def _iter(shape: Any, kind: Any) -> list[Any]:
    m = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, kind, m)
    return [m.FindKey(i) for i in range(1, m.Extent() + 1)]


def faces_in(shape: Any) -> list[Any]:
    return _iter(shape, TopAbs_FACE)


def face_area(face: Any) -> float:
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(face, props)
    return float(props.Mass())


def edge_length(edge: Any) -> float:
    return float(GCPnts_AbscissaPoint.Length_s(BRepAdaptor_Curve(TopoDS.Edge_s(edge))))


def edge_points(edge: Any, n: int) -> tuple[FloatArray, FloatArray]:
    """``n`` points at parameter midpoints of ``edge`` and their parameters."""
    c = BRepAdaptor_Curve(TopoDS.Edge_s(edge))
    t0, t1 = c.FirstParameter(), c.LastParameter()
    t = t0 + (np.arange(n) + 0.5) / n * (t1 - t0)
    pts = np.array([[p.X(), p.Y(), p.Z()] for p in (c.Value(float(s)) for s in t)])
    return pts.reshape(-1, 3), t


def face_samples(
    face: Any, n: int, seed: int = 0, segs: FloatArray | None = None
) -> tuple[FloatArray, FloatArray]:
    """About ``n`` points inside ``face`` (one random point in each cell of a grid over its
    ``(u, v)`` bounds, kept inside its boundary's pcurves by the even-odd rule on a fine
    polygon) and their ``(u, v)``. Random, not cell centres: rows interpolate exact samples
    at dyadic parameters, where a grid of centres would land exactly. ``segs``: the face's
    :func:`_uv_segments` if known.

    ``BRepClass_FaceClassifier`` takes ~0.1 s a point on a plane bounded by B-spline edges
    of thousands of poles; the polygon test is vectorised."""
    face = TopoDS.Face_s(face)
    surf = BRepAdaptor_Surface(face)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    segs = _uv_segments(face) if segs is None else segs
    k = max(2, math.ceil(math.sqrt(n)))
    rng = np.random.default_rng(seed)
    uv = np.empty((0, 2))
    for _ in range(3):
        g = np.arange(k) / k
        uu, vv = np.meshgrid(u0 + g * (u1 - u0), v0 + g * (v1 - v0), indexing="ij")
        jitter = rng.random((k * k, 2)) / k * np.array([u1 - u0, v1 - v0])
        cand = np.column_stack([uu.ravel(), vv.ravel()]) + jitter
        uv = cand[_inside(cand, segs)]
        if len(uv) >= 0.7 * n:
            break
        k = math.ceil(k * min(3.0, math.sqrt(n / max(len(uv), 1))))
    pts = np.array([_xyz(surf.Value(float(u), float(v))) for u, v in uv]).reshape(-1, 3)
    return pts, uv


def _uv_segments(face: Any, per_edge: int = 2000) -> FloatArray:
    """The boundary of ``face`` in its ``(u, v)`` plane as segments ``(M, 2, 2)``."""
    segs = []
    for e in _iter(face, TopAbs_EDGE):
        c = BRepAdaptor_Curve2d(TopoDS.Edge_s(e), face)
        k = 2 if c.GetType() == GeomAbs_Line else per_edge
        t = np.linspace(c.FirstParameter(), c.LastParameter(), k)
        p = np.array([[q.X(), q.Y()] for q in (c.Value(float(x)) for x in t)])
        segs.append(np.stack([p[:-1], p[1:]], axis=1))
    return np.vstack(segs) if segs else np.empty((0, 2, 2))


def _inside(pts: FloatArray, segs: FloatArray) -> NDArray[np.bool_]:
    """Even-odd rule: crossings of the ray ``+u`` from each point with the segments."""
    a, b = segs[None, :, 0, :], segs[None, :, 1, :]
    p = pts[:, None, :]
    straddle = (a[..., 1] > p[..., 1]) != (b[..., 1] > p[..., 1])
    dy = np.where(straddle, b[..., 1] - a[..., 1], 1.0)
    x = a[..., 0] + (p[..., 1] - a[..., 1]) * (b[..., 0] - a[..., 0]) / dy
    return np.asarray(np.sum(straddle & (x > p[..., 0]), axis=1) % 2 == 1)


def _xyz(p: gp_Pnt) -> FloatArray:
    return np.array([p.X(), p.Y(), p.Z()])


def plane_of(points: FloatArray) -> tuple[FloatArray, float, float]:
    """Least-squares plane ``n.x = d`` through ``points``: ``(n, d, max residual)``, with
    the sign of ``n`` fixed (first non-zero component positive)."""
    c = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - c)
    n = vt[-1]
    j = int(np.argmax(np.abs(n) > 1e-6))
    if n[j] < 0:
        n = -n
    return n, float(n @ c), float(np.max(np.abs((points - c) @ n)))


def planes_and_areas(result: Any, eps: float) -> list[tuple[FloatArray, float, float]]:
    """The sheets of ``result`` grouped by the plane they lie in: ``(normal, offset, total
    area)`` per distinct plane (every sheet must be planar within ``eps``)."""
    groups: list[tuple[FloatArray, float, float]] = []
    for s in result.sheets:
        pts, _ = face_samples(s.face, 16)
        n, d, res = plane_of(pts)
        assert res <= eps, f"{s.name} is not planar (residual {res:.2e})"
        a = face_area(s.face)
        for i, (gn, gd, ga) in enumerate(groups):
            if np.linalg.norm(gn - n) <= 1e-6 and abs(gd - d) <= eps:
                groups[i] = (gn, gd, ga + a)
                break
        else:
            groups.append((n, d, a))
    return groups


def edge_faces(compound: Any) -> list[tuple[Any, int]]:
    """Every non-degenerated edge of ``compound`` with the number of sheet sides along it:
    the faces it bounds, a face counted twice where the edge is its seam (a closed sheet,
    e.g. of a loop of the 2D MAT from a branch point back to it, meets itself there)."""
    anc = TopTools_IndexedDataMapOfShapeListOfShape()
    TopExp.MapShapesAndAncestors_s(compound, TopAbs_EDGE, TopAbs_FACE, anc)
    out = []
    for i in range(1, anc.Extent() + 1):
        e = anc.FindKey(i)
        if BRep_Tool.Degenerated_s(TopoDS.Edge_s(e)):
            continue
        faces: list[Any] = []
        for f in anc.FindFromIndex(i):
            if not any(f.IsSame(g) for g in faces):
                faces.append(f)
        edge = TopoDS.Edge_s(e)
        out.append(
            (e, sum(2 if BRep_Tool.IsClosed_s(edge, TopoDS.Face_s(f)) else 1 for f in faces))
        )
    return out


def faces_of(compound: Any, edge: Any) -> int:
    for e, k in edge_faces(compound):
        if e.IsSame(edge):
            return k
    return 0


HEAVY = 20000
"""Shapes with more poles than this are not given to ``BRepExtrema`` (a ruled sheet of
10^5 poles takes gigabytes there)."""


def poles(shape: Any) -> int:
    """Number of poles of a B-spline face or edge (0 for other geometry)."""
    if shape.ShapeType() == TopAbs_FACE:
        srf = BRep_Tool.Surface_s(TopoDS.Face_s(shape))
        return int(srf.NbUPoles() * srf.NbVPoles()) if hasattr(srf, "NbUPoles") else 0
    crv = BRep_Tool.Curve_s(TopoDS.Edge_s(shape), 0.0, 1.0)
    return int(crv.NbPoles()) if hasattr(crv, "NbPoles") else 0


class ComplexDistance:
    """Distance from points to the output complex, exactly (``BRepExtrema_ExtPF`` per face,
    ``BRepExtrema_ExtPC`` per edge, initialised once, plus the vertices).

    ``BRepExtrema_DistShapeShape`` against the compound rebuilds the extrema of every
    B-spline face per call (~0.5 s a point on a tube); here a KD-tree of points on the
    complex gives an upper bound and only faces and edges whose bounding boxes are nearer
    than that are visited."""

    def __init__(self, compound: Any) -> None:
        flag, algo = Extrema_ExtFlag.Extrema_ExtFlag_MIN, Extrema_ExtAlgo.Extrema_ExtAlgo_Grad
        self.faces = [TopoDS.Face_s(f) for f in _iter(compound, TopAbs_FACE)]
        self.edges = [
            TopoDS.Edge_s(e)
            for e in _iter(compound, TopAbs_EDGE)
            if not BRep_Tool.Degenerated_s(TopoDS.Edge_s(e))
        ]
        self._flag, self._algo = flag, algo
        # extrema are initialised on first use (a gear wheel's MAT has ~400 sheets)
        self._ext_f: list[Any] = [None] * len(self.faces)
        self._ext_e: list[Any] = [None] * len(self.edges)
        self._fbox = np.array([_bbox(f) for f in self.faces]).reshape(-1, 2, 3)
        self._ebox = np.array([_bbox(e) for e in self.edges]).reshape(-1, 2, 3)
        self._surf = [BRepAdaptor_Surface(f) for f in self.faces]
        self._segs = [_uv_segments(f) for f in self.faces]
        self._uvb = [BRepTools.UVBounds_s(f) for f in self.faces]
        pts, fidx, uvs = [], [], []
        for i, f in enumerate(self.faces):
            p, uv = face_samples(f, 100, segs=self._segs[i])
            pts.append(p)
            uvs.append(uv)
            fidx.append(np.full(len(p), i))
        for e in self.edges:
            pts.append(edge_points(e, 20)[0])
            uvs.append(np.full((20, 2), np.nan))
            fidx.append(np.full(20, -1))
        self._pts, self._fidx, self._uv = np.vstack(pts), np.concatenate(fidx), np.vstack(uvs)
        self._tree = cKDTree(self._pts)

    def _local(self, x: FloatArray, k: int = 4) -> float:
        """Upper bound: the nearest tree points, each projected locally onto its face."""
        dd, jj = self._tree.query(x, k=k)
        best = float(dd[0])
        for j in np.atleast_1d(jj):
            i = int(self._fidx[j])
            if i < 0:
                continue
            uv = _project(self._surf[i], x, self._uv[j], self._uvb[i])[None]
            if not _inside(uv, self._segs[i])[0]:
                continue
            y = _xyz(self._surf[i].Value(float(uv[0, 0]), float(uv[0, 1])))
            best = min(best, float(np.linalg.norm(y - x)))
        return best

    def distance(self, x: FloatArray, enough: float = 0.0) -> float:
        """The distance from ``x`` to the complex; an upper bound of it when that is at most
        ``enough`` (the exact search is skipped)."""
        best = self._local(x)
        if best <= enough:
            return best
        vx = BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, x))).Vertex()
        for boxes, shapes, is_face in (
            (self._fbox, self.faces, True),
            (self._ebox, self.edges, False),
        ):
            lb = np.linalg.norm(
                np.maximum(0.0, np.maximum(boxes[:, 0] - x, x - boxes[:, 1])), axis=1
            )
            for i in np.argsort(lb):
                if lb[i] > best:
                    break
                ext = self._extrema(i, is_face)
                if ext is None:
                    # too heavy to keep BRepExtrema_ExtPF initialised: one full search (the
                    # local projection alone, from the nearest of a face's 100 samples,
                    # stopped 0.52 units off a 250-degree revolved sheet of an ellipse
                    # whose medial points lie on it to 1e-10)
                    dss = BRepExtrema_DistShapeShape(vx, shapes[i])
                    if dss.IsDone():
                        best = min(best, dss.Value())
                    continue
                if is_face:
                    ext.Perform(vx, shapes[i])
                else:
                    ext.Perform(vx)
                if ext.IsDone():
                    for k in range(1, ext.NbExt() + 1):
                        best = min(best, math.sqrt(ext.SquareDistance(k)))
                else:  # the extrema gave up (seen on planar mid sheets): the full search
                    dss = BRepExtrema_DistShapeShape(vx, shapes[i])
                    if dss.IsDone():
                        best = min(best, dss.Value())
        return best

    def _extrema(self, i: int, is_face: bool) -> Any:
        exts, shapes = (self._ext_f, self.faces) if is_face else (self._ext_e, self.edges)
        if exts[i] is None and poles(shapes[i]) <= HEAVY:
            if is_face:
                exts[i] = BRepExtrema_ExtPF()
                exts[i].Initialize(shapes[i], self._flag, self._algo)
            else:
                exts[i] = BRepExtrema_ExtPC()
                exts[i].Initialize(shapes[i])
        return exts[i]

    def distances(self, points: FloatArray, enough: float = 0.0) -> FloatArray:
        return np.array([self.distance(p, enough) for p in np.asarray(points, dtype=float)])


def _project(surf: Any, x: FloatArray, uv: FloatArray, bounds: Sequence[float]) -> FloatArray:
    """Local projection of ``x`` onto a surface (Gauss-Newton from ``uv``, clamped to
    ``bounds``). ``ShapeAnalysis_Surface`` would first box the whole surface: minutes on a
    sheet of 10^5 poles."""
    u0, u1, v0, v1 = bounds
    u, v = float(uv[0]), float(uv[1])
    p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
    for _ in range(30):
        surf.D1(u, v, p, du, dv)
        r = x - _xyz(p)
        j = np.column_stack([_xyz(du), _xyz(dv)])
        step, *_ = np.linalg.lstsq(j, r, rcond=None)
        un = min(max(u + float(step[0]), u0), u1)
        vn = min(max(v + float(step[1]), v0), v1)
        if abs(un - u) + abs(vn - v) <= 1e-15 * (1.0 + abs(u) + abs(v)):
            break
        u, v = un, vn
    return np.array([u, v])


def _bbox(shape: Any) -> FloatArray:
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, box, False, True)
    return np.array(box.Get()).reshape(2, 3)


def completeness(
    sb: O.SolidBoundary, compound: Any, n: int, seed: int = 0, enough: float = 0.0
) -> FloatArray:
    """:func:`tests.oracles3d.completeness` with the distance of :class:`ComplexDistance`
    (upper bounds where they are at most ``enough``)."""
    _, m, _ = O.medial_points(sb, n, seed)
    return ComplexDistance(compound).distances(m, enough)


# --------------------------------------------------------------------------- the report


@dataclass
class Report:
    """Oracle numbers of one case, absolute (model units) unless said otherwise."""

    label: str
    diag: float
    tol: float
    soundness: float  # max over finite samples (nan = rim samples ignored)
    outside: int  # samples outside the solid
    n_sound: int
    radius: float
    completeness: float
    components: int
    euler: int
    solid_euler: int | None  # None: a pinched solid (its boundary's formula does not apply)
    valid: bool
    free_off_boundary: float  # largest distance of a free (1-face) edge from the boundary
    free_unnamed: int  # free edges neither a rim nor a skeletal edge
    thin_seams: list[str]  # named seams bounding fewer than 3 faces
    counts: dict[str, int]
    max_poles: int  # of the heaviest sheet
    seconds: dict[str, float] = field(default_factory=dict)

    def rel(self, x: float) -> float:
        return x / self.diag

    def line(self) -> str:
        c = self.counts
        return (
            f"{self.label}: tol {self.rel(self.tol):.0e} | sound {self.rel(self.soundness):.1e}"
            f" ({self.n_sound}, out {self.outside}) | radius {self.rel(self.radius):.1e}"
            f" | complete {self.rel(self.completeness):.1e} | comp {self.components}"
            f" chi {self.euler}/{self.solid_euler} valid {self.valid}"
            f" | free-off {self.rel(self.free_off_boundary):.1e} unnamed {self.free_unnamed}"
            f" thin {len(self.thin_seams)} | sheets {c['sheets']} seams {c['seams']}"
            f" junctions {c['junctions']} skeletal {c['skeletal_edges']} poles {self.max_poles}"
            f" | mat {self.seconds.get('mat', 0):.1f}s oracle {self.seconds.get('oracle', 0):.1f}s"
        )

    def failures(self) -> list[str]:
        """What this report says is wrong (empty: the case passes)."""
        out = []
        rel = self.rel
        if self.outside:
            out.append(f"{self.outside} samples outside the solid")
        if not self.soundness <= self.tol:
            out.append(f"soundness {rel(self.soundness):.2e} diag > tol {rel(self.tol):.0e}")
        if not self.radius <= self.tol:
            out.append(f"radius error {rel(self.radius):.2e} diag > tol")
        if not self.completeness <= self.tol:
            out.append(f"completeness {rel(self.completeness):.2e} diag > tol")
        if self.components != 1:
            out.append(f"{self.components} connected components")
        if self.solid_euler is not None and self.euler != self.solid_euler:
            out.append(f"Euler characteristic {self.euler} != solid's {self.solid_euler}")
        if not self.valid:
            out.append("BRepCheck_Analyzer: compound not valid")
        if not self.free_off_boundary <= self.tol:
            out.append(f"a free edge is {rel(self.free_off_boundary):.2e} diag off the boundary")
        if self.free_unnamed:
            out.append(f"{self.free_unnamed} free edges are neither rims nor skeletal edges")
        if self.max_poles > HEAVY:
            out.append(f"a sheet has {self.max_poles} poles (> {HEAVY})")
        if self.thin_seams:
            out.append(f"seams bounding < 3 faces: {self.thin_seams[:5]}")
        return out


def _sample_sheets(
    result: Any, per_face: int, max_faces: int, rng: np.random.Generator
) -> tuple[FloatArray, FloatArray]:
    sheets = list(result.sheets)
    if len(sheets) > max_faces:
        sheets = [sheets[i] for i in sorted(rng.choice(len(sheets), max_faces, replace=False))]
    pts, rad = [np.empty((0, 3))], [np.empty(0)]
    for s in sheets:
        p, uv = face_samples(s.face, per_face)
        if len(p):
            pts.append(p)
            rad.append(np.asarray(s.radius(uv[:, 0], uv[:, 1]), dtype=float).reshape(-1))
    return np.vstack(pts), np.concatenate(rad)


def _sample_curves(
    result: Any, per_edge: int, max_edges: int, rng: np.random.Generator
) -> tuple[FloatArray, FloatArray]:
    curves = list(result.seams) + list(result.skeletal_edges)
    if len(curves) > max_edges:
        curves = [curves[i] for i in sorted(rng.choice(len(curves), max_edges, replace=False))]
    pts, rad = [np.empty((0, 3))], [np.empty(0)]
    for c in curves:
        p, t = edge_points(c.edge, per_edge)
        pts.append(p)
        rad.append(np.asarray(c.radius(t), dtype=float).reshape(-1))
    for j in result.junctions:
        pts.append(np.asarray(j.point, dtype=float).reshape(1, 3))
        rad.append(np.array([j.radius]))
    return np.vstack(pts), np.concatenate(rad)


def check(
    solid: Any,
    result: Any,
    label: str,
    *,
    boundary: O.SolidBoundary | None = None,
    per_face: int = 15,
    max_faces: int = 30,
    per_edge: int = 2,
    max_edges: int = 30,
    n_complete: int = 100,
    seed: int = 0,
) -> Report:
    """Run every oracle on ``result`` (the MAT of ``solid``) and collect the numbers."""
    t0 = time.perf_counter()
    sb = boundary if boundary is not None else O.SolidBoundary(solid)
    rng = np.random.default_rng(seed)
    tol = float(result.tol)
    sp, sr = _sample_sheets(result, per_face, max_faces, rng)
    cp, cr = _sample_curves(result, per_edge, max_edges, rng)
    pts, rad = np.vstack([sp, cp]), np.concatenate([sr, cr])
    snd = O.soundness(sb, pts, refine_above=tol)
    finite = snd[np.isfinite(snd)]
    radius = O.radius_error(sb, pts, rad)
    cmp_ = completeness(sb, result.compound, n_complete, seed, enough=0.01 * tol)
    comp = result.compound
    n_comp, chi = O.topology(comp)
    # free edges: on the boundary (rims) or skeletal edges; named seams bound >= 3 faces
    named_free = list(result.rims) + list(result.skeletal_edges)
    free_off, unnamed = 0.0, 0
    for e, k in edge_faces(comp):
        if k != 1:
            continue
        if any(e.IsSame(s.edge) for s in result.skeletal_edges):
            continue
        if not any(e.IsSame(s.edge) for s in named_free):
            unnamed += 1
        p, _ = edge_points(e, 3)
        free_off = max(free_off, float(sb.distances(p).max()))
    counts = edge_faces(comp)
    thin = [
        s.name
        for s in result.seams
        if next((k for e, k in counts if e.IsSame(s.edge)), 0) < 3 and edge_length(s.edge) > tol
    ]
    rep = Report(
        label=label,
        diag=sb.diag,
        tol=tol,
        soundness=float(finite.max()) if len(finite) else 0.0,
        outside=int(np.sum(np.isinf(snd))),
        n_sound=len(snd),
        radius=float(np.max(radius, initial=0.0)),
        completeness=float(np.max(cmp_, initial=0.0)),
        components=n_comp,
        euler=chi,
        solid_euler=_solid_euler(solid),
        valid=bool(BRepCheck_Analyzer(comp).IsValid()),
        free_off_boundary=free_off,
        free_unnamed=unnamed,
        thin_seams=thin,
        counts=result.counts(),
        max_poles=max((poles(s.face) for s in result.sheets), default=0),
    )
    rep.seconds["oracle"] = time.perf_counter() - t0
    return rep


def passes(solid: Any, label: str, n_complete: int = 100) -> Any:
    """The MAT of ``solid``, asserted to pass every oracle of :func:`check`."""
    import medialcad

    result = medialcad.medial_axis(solid)
    rep = check(solid, result, label, n_complete=n_complete)
    print(rep.line())
    assert not rep.failures(), f"{label}: " + "; ".join(rep.failures())
    return result


def _solid_euler(solid: Any) -> int | None:
    """The solid's Euler characteristic, or None where its boundary is pinched (a profile
    tangent to its axis at a point, revolved: the boundary's characteristic comes out odd,
    and the solid's is not half of it)."""
    try:
        return O.solid_euler(solid)
    except ValueError:
        return None


def total_area(shapes: Sequence[Any]) -> float:
    return float(sum(face_area(s) for s in shapes))


def judge(shape: Any, seed: int) -> dict[str, Any]:
    """A fuzz verdict on ``shape``'s MAT (``scripts/fuzz_*.py``): its ``status``
    (passed, refused: a medialcad ``InputError``, error: another medialcad error, failed:
    the oracles' findings, crash: anything else), the ``seconds`` of the MAT, the oracles'
    ``report`` line and ``why`` it did not pass."""
    import traceback

    import medialcad
    from medialcad.errors import InputError, MedialCadError

    rec: dict[str, Any] = {}
    t0 = time.perf_counter()
    try:
        res = medialcad.medial_axis(shape)
        rec["seconds"] = round(time.perf_counter() - t0, 3)
        rep = check(
            shape, res, f"seed {seed}", per_face=10, max_faces=16, max_edges=16,
            per_edge=2, n_complete=60, seed=seed,
        )  # fmt: skip
        failures = rep.failures()
        rec["status"] = "failed" if failures else "passed"
        rec["report"] = rep.line()
        if failures:
            rec["why"] = "; ".join(failures)
    except InputError as err:
        rec["status"], rec["why"] = "refused", str(err)
    except MedialCadError as err:
        rec["status"], rec["why"] = "error", f"{type(err).__name__}: {err}"
    except Exception:  # noqa: BLE001 - logged, the run goes on
        rec["status"], rec["why"] = "crash", traceback.format_exc()[-800:]
    return rec
