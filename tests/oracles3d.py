"""Independent oracles for the 3D medial axis transform of solids (THEORY.md Sec. 3).

These share no code with medialcad. Every distance to the solid's boundary comes from
OpenCascade's ``BRepExtrema`` between a vertex and the solid's faces, edges and vertices (never
the solid itself: against a solid, ``BRepExtrema_DistShapeShape`` answers 0 for interior
points); inside/outside is ``BRepClass3d_SolidClassifier`` (or the sign along the exact normal
when the nearest boundary point is inside a face); and the output of the algorithm is only ever
seen through the shapes it writes (:func:`sample_compound`, :func:`topology`). Shapes may be
given as ``TopoDS_*`` or as cadquery/build123d objects (``.wrapped``, ``Workplane.val()``).

The central primitive is the *ray depth* of a boundary point ``q`` along an inward direction
``u`` (:func:`ray_depth`): the largest ``s`` with ``dist(q + s u, dS) >= s - eps``. The predicate
is monotone in ``s`` (once a boundary point is closer than ``s`` it stays closer), so it is
bracketed and solved by a safeguarded Newton iteration from the right (``g(s) = dist - s`` has
slope ``u.w - 1``, ``w`` the unit vector from the nearest boundary point; exact in one step when
that boundary point is on a plane) with bisection as the fallback. ``q + s* u`` is the true
medial point on that ray.

Distances are exact up to ``BRepExtrema`` (per-face ``BRepExtrema_ExtPF`` and per-edge
``BRepExtrema_ExtPC`` initialised once, or ``BRepExtrema_DistShapeShape``; see
:class:`SolidBoundary`). A dense set of points lying exactly on the boundary (triangulation nodes
plus surface evaluations, in a KD-tree) only *brackets* them: its nearest point is an upper bound,
and a local projection seeded there is a second candidate, which catches ``BRepExtrema`` misses;
its points also bound the ray depth from above. Cost: ~0.2 ms per distance on planes and
cylinders, ~3 ms on a B-spline face; a soundness or completeness sample takes 2 to 6 distances
(about 1 s per 1000 samples on a box or a cylinder, 6 to 10 s on an ellipsoid).

All errors are absolute (model units); divide by ``SolidBoundary.diag`` to report them.
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
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Curve2d, BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.BRepClass3d import BRepClass3d_SolidClassifier
from OCP.BRepExtrema import (
    BRepExtrema_DistShapeShape,
    BRepExtrema_ExtPC,
    BRepExtrema_ExtPF,
    BRepExtrema_SupportType,
)
from OCP.BRepLProp import BRepLProp_SLProps
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.Extrema import Extrema_ExtAlgo, Extrema_ExtFlag
from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.GeomAbs import GeomAbs_Plane
from OCP.gp import gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.ShapeAnalysis import ShapeAnalysis_Surface
from OCP.TopAbs import (
    TopAbs_EDGE,
    TopAbs_FACE,
    TopAbs_IN,
    TopAbs_OUT,
    TopAbs_REVERSED,
    TopAbs_SOLID,
    TopAbs_VERTEX,
    TopAbs_WIRE,
)
from OCP.TopExp import TopExp
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Face, TopoDS_Shape, TopoDS_Solid
from OCP.TopTools import TopTools_IndexedDataMapOfShapeListOfShape, TopTools_IndexedMapOfShape
from scipy.optimize import minimize
from scipy.spatial import cKDTree

from tests.oracles import _pnt, _vertex, _xyz, as_occ, bbox_diagonal, equidistant_point

__all__ = [
    "ShapeDistance",
    "SolidBoundary",
    "as_occ",
    "bbox_diagonal",
    "completeness",
    "euler_characteristic",
    "medial_points",
    "radius_error",
    "ray_depth",
    "sample_compound",
    "solid_euler",
    "soundness",
    "topology",
]

FloatArray = NDArray[np.float64]

_IN_FACE = BRepExtrema_SupportType.BRepExtrema_IsInFace


# --------------------------------------------------------------------------- helpers


def _indexed(shape: TopoDS_Shape, kind: Any) -> TopTools_IndexedMapOfShape:
    """Unique sub-shapes (``IsSame``) of one kind; 1-based, orientation of the first found."""
    m = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, kind, m)
    return m


def _ancestors(
    shape: TopoDS_Shape, kind: Any, parent: Any
) -> TopTools_IndexedDataMapOfShapeListOfShape:
    m = TopTools_IndexedDataMapOfShapeListOfShape()
    TopExp.MapShapesAndAncestors_s(shape, kind, parent, m)
    return m


def _compound(shapes: Sequence[TopoDS_Shape]) -> TopoDS_Compound:
    comp = TopoDS_Compound()
    builder = BRep_Builder()
    builder.MakeCompound(comp)
    for s in shapes:
        builder.Add(comp, s)
    return comp


def _points(points: ArrayLike) -> FloatArray:
    return np.atleast_2d(np.asarray(points, dtype=float)).reshape(-1, 3)


class ShapeDistance:
    """Distance from points to a fixed shape (e.g. a MAT compound), one
    ``BRepExtrema_DistShapeShape`` loaded once and reused."""

    def __init__(self, shape: Any) -> None:
        self.shape = as_occ(shape)
        self._dss = BRepExtrema_DistShapeShape()
        self._dss.LoadS2(self.shape)
        #: 1-based index of the nearest solution of the last :meth:`nearest` call
        self.last = 1

    def nearest(self, p: ArrayLike) -> tuple[float, FloatArray]:
        """``(distance, nearest point on the shape)`` for one point ``p (3,)``."""
        dss, x = self._dss, np.asarray(p, dtype=float)
        dss.LoadS1(_vertex(x))
        if not dss.Perform() or not dss.IsDone() or dss.NbSolution() < 1:
            raise RuntimeError("BRepExtrema_DistShapeShape failed")
        # every extremum within Precision::Confusion of the minimum is a "solution", in no
        # particular order: pick the truly nearest one
        best, self.last, foot = math.inf, 1, x
        for i in range(1, dss.NbSolution() + 1):
            q = _xyz(dss.PointOnShape2(i))
            dq = float(np.linalg.norm(q - x))
            if dq < best:
                best, self.last, foot = dq, i, q
        return float(dss.Value()), foot

    def distances(self, points: ArrayLike) -> FloatArray:
        """Distances ``(N,)`` of ``points (N, 3)``."""
        return np.array([self.nearest(p)[0] for p in _points(points)])


def _raised_by_occ(err: BaseException) -> bool:
    """Whether OpenCascade raised ``err`` (OCP gives every ``Standard_Failure`` its own
    class straight under ``Exception``, in module ``OCP.OCP.<package>``)."""
    return (type(err).__module__ or "").startswith("OCP") or type(err) is RuntimeError


# --------------------------------------------------------------------------- the boundary


_SEED_NODES = 32  # nearest nodes of the bracketing KD-tree looked at per query
_NEW_SEED = 1.0
"""A node farther than this (times the nearest node's distance) from every seed already
projected from on its face seeds another projection there. On the prism of a blob with
a sharp tip it fixed the missed flank at 0.25, 0.5, 0.75 and 1.0; 1.0 costs the fewest
projections (+35 % over one seed per face, against +250 % at 0.25)."""


class SolidBoundary:
    """A solid's boundary as a distance oracle, with inside tests and boundary samples.

    The solid is copied (without its mesh) before it is triangulated, so the caller's shape is
    left untouched.

    Args:
        solid: a ``TopoDS_Solid`` (or a shape holding exactly one solid, any wrapper).
        eps: slack of the medial predicate ``dist(q + s u) >= s - eps`` and the resolution of
            :func:`ray_depth`; default ``1e-11`` of the diagonal.
        eta: how far the nearest boundary point of ``q + s u`` may drift from ``q`` while
            ``dist`` is within ``eps`` below ``s`` (see :meth:`probe`); default ``1e-8 diag``.
        deflection: linear deflection of the triangulation; default ``1e-3 diag``.
        n_dense: surface samples added to the triangulation nodes of the bracketing KD-tree.
        edge_margin: boundary samples closer than this to a face edge are dropped (the normal
            is ill-defined there); default ``1e-3 diag``.
        seed: seed of the dense samples.
        method: ``"extrema"`` (default): one ``BRepExtrema_ExtPF`` per face and one
            ``BRepExtrema_ExtPC`` per edge, initialised once (about 2x faster than
            ``BRepExtrema_DistShapeShape`` on B-spline faces, which rebuilds them per call),
            visited in the order of their bounding boxes' distance and skipped once a box is
            farther than the best distance so far; ``"dss"``: ``BRepExtrema_DistShapeShape``
            against the compound of the faces. Both run the same extrema algorithms with the
            same settings, and both are bracketed (:meth:`nearest_support`).

    Raises:
        ValueError: the shape holds no solid or more than one.
    """

    def __init__(
        self,
        solid: Any,
        *,
        eps: float | None = None,
        eta: float | None = None,
        deflection: float | None = None,
        n_dense: int = 4000,
        edge_margin: float | None = None,
        seed: int = 0,
        method: str = "extrema",
    ) -> None:
        if method not in ("extrema", "dss"):
            raise ValueError(f"oracle: unknown distance method {method!r}")
        self.method = method
        shape = as_occ(solid)
        solids = _indexed(shape, TopAbs_SOLID)
        if solids.Extent() != 1:
            raise ValueError(f"oracle: expected one solid, got {solids.Extent()}")
        self.solid: TopoDS_Solid = TopoDS.Solid_s(
            BRepBuilderAPI_Copy(solids.FindKey(1), True, False).Shape()
        )
        self.diag = bbox_diagonal(self.solid)
        self._face_map = _indexed(self.solid, TopAbs_FACE)
        self.faces: list[TopoDS_Face] = [
            TopoDS.Face_s(self._face_map.FindKey(i)) for i in range(1, self._face_map.Extent() + 1)
        ]
        self.shell = _compound(self.faces)  # vs a solid, DSS answers 0 inside
        self._surf = [BRepAdaptor_Surface(f) for f in self.faces]
        self._planar = [s.GetType() == GeomAbs_Plane for s in self._surf]
        self._sas = [ShapeAnalysis_Surface(BRep_Tool.Surface_s(f)) for f in self.faces]
        self._face_classifier = BRepClass_FaceClassifier()
        # surface normal (D1U x D1V) times this sign = inward normal; checked in _orient_faces
        self._inward = np.array(
            [1.0 if f.Orientation() == TopAbs_REVERSED else -1.0 for f in self.faces]
        )
        self.eps = eps if eps is not None else 1e-11 * self.diag
        self.eta = eta if eta is not None else 1e-8 * self.diag
        self.edge_margin = edge_margin if edge_margin is not None else 1e-3 * self.diag
        tols = [BRep_Tool.Tolerance_s(TopoDS.Vertex_s(v)) for v in _iter(self.solid, TopAbs_VERTEX)]
        self.class_tol = max([1e-9 * self.diag, *tols])
        #: the B-rep's own tolerance (its largest vertex or edge tolerance): where its
        #: faces and edges are only that close to each other, so is any answer about it
        edge_tols = [
            BRep_Tool.Tolerance_s(TopoDS.Edge_s(e)) for e in _iter(self.solid, TopAbs_EDGE)
        ]
        self.brep_tol = max([0.0, *tols, *edge_tols])
        self._dss = ShapeDistance(self.shell)
        self._build_extrema()
        self._classifier = BRepClass3d_SolidClassifier(self.solid)
        #: how often the KD-tree bracket caught a BRepExtrema miss (a diagnostic)
        self.extrema_misses = 0

        # angular deflection 0.05 rad: nodes every ~R/20 on tight curves (a sharp tip of a
        # B-spline profile), where a second contact near the first needs a node to be found
        BRepMesh_IncrementalMesh(
            self.solid,
            deflection if deflection is not None else 1e-3 * self.diag,
            False,
            0.05,
            True,
        )
        self._build_mesh()
        self._build_edge_tree()
        rng = np.random.default_rng(seed)
        pts, _, fidx, uv = self._sample_faces(n_dense, rng)
        self._orient_faces(rng)
        self._nodes = np.vstack([self._mesh_nodes, pts])
        self._node_face = np.concatenate([self._mesh_node_face, fidx])
        self._node_uv = np.vstack([self._mesh_node_uv, uv])
        self._tree = cKDTree(self._nodes)
        #: the convex edges of the solid (where the MAT's rims lie)
        self.convex_edges: list[TopoDS_Shape] = self._find_convex_edges()
        vertices = _iter(self.solid, TopAbs_VERTEX)
        self._rims = ShapeDistance(_compound([*self.convex_edges, *vertices]))

    # -- construction

    def _build_mesh(self) -> None:
        nodes, nface, nuv, tris, tface = [], [], [], [], []
        offset = 0
        for i, face in enumerate(self.faces):
            loc = TopLoc_Location()
            tri = BRep_Tool.Triangulation_s(face, loc)
            if tri is None or tri.NbNodes() == 0:
                continue
            trsf = loc.Transformation()
            k = tri.NbNodes()
            nodes.append(np.array([_xyz(tri.Node(j).Transformed(trsf)) for j in range(1, k + 1)]))
            has_uv = tri.HasUVNodes()
            nuv.append(
                np.array(
                    [
                        (tri.UVNode(j).X(), tri.UVNode(j).Y()) if has_uv else (np.nan, np.nan)
                        for j in range(1, k + 1)
                    ]
                )
            )
            nface.append(np.full(k, i))
            t = np.array([tri.Triangle(j).Get() for j in range(1, tri.NbTriangles() + 1)]) - 1
            tris.append(t + offset)
            tface.append(np.full(len(t), i))
            offset += k
        if not nodes:
            raise RuntimeError("oracle: the solid could not be triangulated")
        self._mesh_nodes = np.vstack(nodes)
        self._mesh_node_face = np.concatenate(nface)
        self._mesh_node_uv = np.vstack(nuv)
        self._tris = np.vstack(tris)
        self._tri_face = np.concatenate(tface)
        a, b, c = (self._mesh_nodes[self._tris[:, j]] for j in range(3))
        self._tri_area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)

    def _build_edge_tree(self) -> None:
        """Points along every edge, spaced ``edge_margin / 2``: the near-edge filter."""
        step = 0.5 * self.edge_margin
        pts = []
        for e in _iter(self.solid, TopAbs_EDGE):
            edge = TopoDS.Edge_s(e)
            if BRep_Tool.Degenerated_s(edge):
                continue
            c = BRepAdaptor_Curve(edge)
            k = max(2, math.ceil(GCPnts_AbscissaPoint.Length_s(c) / step) + 1)
            pts.extend(
                _xyz(c.Value(t)) for t in np.linspace(c.FirstParameter(), c.LastParameter(), k)
            )
        self._edge_tree = cKDTree(np.array(pts)) if pts else None

    def _find_convex_edges(self) -> list[TopoDS_Shape]:
        """Edges whose interior dihedral angle is below about 178 degrees, decided
        at the edge's parameter midpoint: a probe at distance ``h`` along the bisector of the
        two faces' inward normals is nearer than ``h`` to the boundary (``h sin(angle/2)``)
        only at a convex edge; at a reflex or tangent edge the edge itself is nearest."""
        h = 1e-5 * self.diag
        out = []
        anc = _ancestors(self.solid, TopAbs_EDGE, TopAbs_FACE)
        for i in range(1, anc.Extent() + 1):
            edge = TopoDS.Edge_s(anc.FindKey(i))
            faces = _unique(list(anc.FindFromIndex(i)))
            if BRep_Tool.Degenerated_s(edge) or len(faces) != 2:
                continue  # a seam (one face) or a non-manifold edge
            c = BRepAdaptor_Curve(edge)
            t = 0.5 * (c.FirstParameter() + c.LastParameter())
            bis = np.zeros(3)
            for f in faces:
                j = self._face_map.FindIndex(f) - 1
                uv = BRepAdaptor_Curve2d(edge, self.faces[j]).Value(t)
                props = BRepLProp_SLProps(self._surf[j], uv.X(), uv.Y(), 1, 1e-12)
                if not props.IsNormalDefined():  # a pole (a profile tangent to its axis)
                    bis[:] = np.nan
                    break
                bis += self._inward[j] * _xyz(props.Normal())
            if not np.all(np.isfinite(bis)):
                continue
            if np.linalg.norm(bis) < 1e-9:
                continue  # a knife edge: no bisector
            y = _xyz(c.Value(t)) + h * bis / np.linalg.norm(bis)
            if self.nearest(y)[0] < h * (1 - 1e-4):
                out.append(edge)
        return out

    def rim_distance(self, p: ArrayLike) -> float:
        """Distance from ``p`` to the convex edges and the vertices of the solid: the places
        where a MAT point may have radius 0."""
        return self._rims.nearest(p)[0]

    def _orient_faces(self, rng: np.random.Generator) -> None:
        """Flip a face's inward sign if probes off a few of its samples disagree with it."""
        pts, nrm, fidx, _ = self._sample_faces(12 * len(self.faces) + 24, rng)
        delta = 20 * self.class_tol + 1e-6 * self.diag
        for i in range(len(self.faces)):
            votes = 0
            for p, n in list(zip(pts[fidx == i], nrm[fidx == i], strict=True))[:3]:
                inner, outer = self.inside([p + delta * n, p - delta * n])
                votes += int(inner and not outer) - int(outer and not inner)
            if votes < 0:
                self._inward[i] = -self._inward[i]

    def _sample_faces(
        self, n: int, rng: np.random.Generator
    ) -> tuple[FloatArray, FloatArray, NDArray[np.int64], FloatArray]:
        """About ``n`` samples spread by area, evaluated exactly on the faces, away from the
        edges: ``(points, inward normals, face index, (u, v))``."""
        if n <= 0:
            return np.empty((0, 3)), np.empty((0, 3)), np.empty(0, dtype=np.int64), np.empty((0, 2))
        prob = self._tri_area / self._tri_area.sum()
        ti = rng.choice(len(self._tris), size=n, p=prob)
        r1, r2 = np.sqrt(rng.random(n)), rng.random(n)
        w = np.c_[1 - r1, r1 * (1 - r2), r1 * r2]
        uv = np.einsum("ij,ijk->ik", w, self._mesh_node_uv[self._tris[ti]])
        faces = self._tri_face[ti]
        pts, nrms, keep = np.empty((n, 3)), np.empty((n, 3)), np.zeros(n, dtype=bool)
        for k in range(n):
            if not np.isfinite(uv[k]).all():
                continue
            props = BRepLProp_SLProps(self._surf[faces[k]], uv[k, 0], uv[k, 1], 1, 1e-12)
            if not props.IsNormalDefined():
                continue
            pts[k] = _xyz(props.Value())
            nrms[k] = self._inward[faces[k]] * _xyz(props.Normal())
            keep[k] = True
        if self._edge_tree is not None and keep.any():
            keep[keep] = self._edge_tree.query(pts[keep])[0] >= self.edge_margin
        return pts[keep], nrms[keep], faces[keep], uv[keep]

    # -- primitives

    def nearest_support(
        self, p: ArrayLike, local: Any = None
    ) -> tuple[float, FloatArray, int | None, FloatArray | None]:
        """``(dist(p, dS), foot point, face index, (u, v))``; the last two are ``None`` unless
        the foot is inside a face.

        The ``BRepExtrema`` answer (see ``method``) is bracketed by the KD-tree of points lying
        exactly on ``dS``: the nearest of them is an upper bound, and a local projection
        (Newton) seeded at it is another candidate; the least distance wins. This catches
        minima that ``BRepExtrema`` misses: for a point within ``Precision::Confusion`` of a
        cylinder's axis it answers the distance to the seam edge (up to ``1e-7`` too far).
        ``local``: the :meth:`_local_nearest` of ``p`` if already known.
        """
        x = np.asarray(p, dtype=float)
        dl, fl, facel, uvl, _ = self._local_nearest(x) if local is None else local
        if self.method == "dss":
            d, foot, face, uv = self._nearest_dss(x)
        else:
            d, foot, face, uv = self._nearest_extrema(x, dl + 1e-9 * self.diag)
        if dl < d - 1e-15 * max(1.0, d):
            if dl < d - 1e-9 * self.diag:
                self.extrema_misses += 1
            d, foot, face, uv = dl, fl, facel, uvl
        return float(d), foot, face, uv

    def _local_nearest(
        self, x: FloatArray
    ) -> tuple[float, FloatArray, int | None, FloatArray | None, float]:
        """An upper bound of ``dist(x, dS)`` from the bracketing KD-tree: ``(distance, point,
        face, uv, distance of the nearest node)``, the best of the nearest node and local
        projections seeded at nodes among the nearest (see below)."""
        dk, jk = self._tree.query(x, k=min(_SEED_NODES, len(self._nodes)))
        dk, jk = np.atleast_1d(dk), np.atleast_1d(jk)
        dn, jn = float(dk[0]), int(jk[0])
        d, foot = dn, self._nodes[jn].copy()
        face, uv = int(self._node_face[jn]), self._node_uv[jn].copy()
        if not np.isfinite(uv).all():
            return d, foot, None, None, dn
        best_face, best_uv = face, uv
        # projected on the nearest node's face, and on each other face with a node
        # nearly as near (beside an edge the nearest node may be the other face's: the
        # cap's, where the wall's minimum is a third nearer and BRepExtrema misses it);
        # on one face again from a node far from the seeds used there (the other flank
        # of a sharp tip of an extruded B-spline, 0.0024 nearer than the first flank's
        # foot: BRepExtrema missed it, and so did the projection from the first seed).
        # Only nodes within 1.5 times the nearest node's distance seed. A second minimum
        # whose nodes all lie within that distance of a seed is still left to BRepExtrema.
        seeds: dict[int, list[FloatArray]] = {}
        for dj, j in zip(dk, jk, strict=True):
            f_j = int(self._node_face[j])
            used = seeds.get(f_j, [])
            node = self._nodes[j]
            if (
                dj > 1.5 * dn
                or any(np.linalg.norm(node - q) <= _NEW_SEED * dn for q in used)
                or not np.isfinite(self._node_uv[j]).all()
            ):
                continue
            seeds.setdefault(f_j, []).append(node)
            dp, qp, uvp = self._project(x, f_j, self._node_uv[j])
            if dp < d:
                d, foot, best_face, best_uv = dp, qp, f_j, uvp
        return d, foot, best_face, best_uv, dn

    def _build_extrema(self) -> None:
        # the defaults of BRepExtrema_DistShapeShape: the tree algorithm is ~2x faster but
        # misses the nearest of two nearly equal minima (by 1e-4 on an ellipsoid)
        flag, algo = Extrema_ExtFlag.Extrema_ExtFlag_MINMAX, Extrema_ExtAlgo.Extrema_ExtAlgo_Grad
        self._ext_f = []
        for f in self.faces:
            ext = BRepExtrema_ExtPF()
            ext.Initialize(f, flag, algo)
            self._ext_f.append(ext)
        self._edges = [
            TopoDS.Edge_s(e)
            for e in _iter(self.solid, TopAbs_EDGE)
            if not BRep_Tool.Degenerated_s(TopoDS.Edge_s(e))
        ]
        self._ext_e = []
        for e in self._edges:
            ext = BRepExtrema_ExtPC()
            ext.Initialize(e)
            self._ext_e.append(ext)
        self._verts = np.array(
            [_xyz(BRep_Tool.Pnt_s(TopoDS.Vertex_s(v))) for v in _iter(self.solid, TopAbs_VERTEX)]
        ).reshape(-1, 3)
        self._fbox = np.array([_bbox(f) for f in self.faces]).reshape(-1, 2, 3)
        self._ebox = np.array([_bbox(e) for e in self._edges]).reshape(-1, 2, 3)

    def _nearest_dss(
        self, x: FloatArray
    ) -> tuple[float, FloatArray, int | None, FloatArray | None]:
        d, foot = self._dss.nearest(x)
        face, uv = None, None
        dss, i = self._dss._dss, self._dss.last
        if dss.SupportTypeShape2(i) == _IN_FACE:
            j = self._face_map.FindIndex(dss.SupportOnShape2(i))
            if j > 0:
                face, uv = j - 1, np.array(dss.ParOnFaceS2(i))
        return d, foot, face, uv

    def _nearest_extrema(
        self, x: FloatArray, bound: float
    ) -> tuple[float, FloatArray, int | None, FloatArray | None]:
        """Least distance over the vertices, the faces' interior extrema and the edges'
        extrema; a face or edge whose box is farther than ``bound`` or than the best so far
        is skipped (``bound``: a known upper bound of the distance)."""
        best, foot, face, uv = math.inf, x, None, None
        if len(self._verts):
            dv = np.linalg.norm(self._verts - x, axis=1)
            j = int(np.argmin(dv))
            best, foot = float(dv[j]), self._verts[j].copy()
        vx = _vertex(x)
        for boxes, exts, shapes, is_face in (
            (self._fbox, self._ext_f, self.faces, True),
            (self._ebox, self._ext_e, self._edges, False),
        ):
            if not len(boxes):
                continue
            lb = np.linalg.norm(
                np.maximum(0.0, np.maximum(boxes[:, 0] - x, x - boxes[:, 1])), axis=1
            )
            for i in np.argsort(lb):
                if lb[i] > min(best, bound):
                    break
                ext = exts[i]
                try:
                    if is_face:
                        ext.Perform(vx, shapes[i])
                    else:
                        ext.Perform(vx)
                except Exception as err:
                    if not _raised_by_occ(err):
                        raise
                    # Extrema's own construction failed (a zero cross product near a
                    # revolved face's pole, FreeCAD fuzz seed 106): ask the other algorithm
                    got = self._distance_dss(vx, shapes[i], is_face)
                    if got is not None and got[0] < best:
                        best, foot, face, uv = got[0], got[1], (int(i) if is_face else None), got[2]
                    continue
                if is_face and (not ext.IsDone() or ext.NbExt() == 0):
                    # BRepExtrema_ExtPF answers nothing where its face classifier errs:
                    # seen at a point whose projection is inside a planar bottom face
                    # (classified OUT there, IN 1e-9 away): project and classify again
                    got = self._project_fallback(x, int(i), best)
                    if got is not None and got[0] < best:
                        best, foot, face, uv = got[0], got[1], int(i), got[2]
                    continue
                if not ext.IsDone():
                    continue
                for k in range(1, ext.NbExt() + 1):
                    dk = math.sqrt(ext.SquareDistance(k))
                    if dk < best:
                        best, foot = dk, _xyz(ext.Point(k))
                        face, uv = (int(i), np.array(ext.Parameter(k))) if is_face else (None, None)
        return best, foot, face, uv

    def _distance_dss(
        self, vx: Any, shape: TopoDS_Shape, is_face: bool
    ) -> tuple[float, FloatArray, FloatArray | None] | None:
        """Distance from the vertex ``vx`` to one face or edge by
        ``BRepExtrema_DistShapeShape`` (with the foot's face parameters when it is inside
        the face), or ``None`` if that fails too."""
        try:
            dss = BRepExtrema_DistShapeShape(vx, shape)
            if not dss.IsDone() or dss.NbSolution() < 1:
                return None
            uv = None
            if is_face and dss.SupportTypeShape2(1) == _IN_FACE:
                uv = np.array(dss.ParOnFaceS2(1))
            return float(dss.Value()), _xyz(dss.PointOnShape2(1)), uv
        except Exception as err:
            if not _raised_by_occ(err):
                raise
            return None

    def _project_fallback(
        self, x: FloatArray, face: int, best: float
    ) -> tuple[float, FloatArray, FloatArray] | None:
        """For a planar face, the orthogonal projection of ``x`` if it is nearer than
        ``best`` and inside the face: classified IN, or OUT but IN at the two points
        1e-4 of the face's parameter box either side of it in u (the classifier answered
        OUT on a 1e-5 blob in the middle of a planar face); else ``None``."""
        if not self._planar[face]:
            return None
        p2 = self._sas[face].ValueOfUV(_pnt(x), 1e-12 * self.diag)
        u0, v0 = p2.X(), p2.Y()
        q = _xyz(self._surf[face].Value(u0, v0))
        d = float(np.linalg.norm(q - x))
        if d >= best:
            return None
        umin, umax, vmin, vmax = BRepTools.UVBounds_s(self.faces[face])
        ring = 1e-4 * math.hypot(umax - umin, vmax - vmin)
        for du in (0.0, ring, -ring):
            self._face_classifier.Perform(self.faces[face], gp_Pnt2d(u0 + du, v0), 1e-9)
            inside = self._face_classifier.State() != TopAbs_OUT
            if du == 0.0 and inside:
                break
            if du != 0.0 and not inside:
                return None
        return d, q, np.array([u0, v0])

    def _project(
        self, x: FloatArray, face: int, uv: FloatArray
    ) -> tuple[float, FloatArray, FloatArray]:
        """Local projection of ``x`` on face ``face`` from ``uv``; ``inf`` if it leaves the face."""
        p2 = self._sas[face].NextValueOfUV(
            gp_Pnt2d(float(uv[0]), float(uv[1])), _pnt(x), 1e-12 * self.diag
        )
        self._face_classifier.Perform(self.faces[face], p2, 1e-9)
        if self._face_classifier.State() == TopAbs_OUT:
            return math.inf, x, uv
        q = _xyz(self._surf[face].Value(p2.X(), p2.Y()))
        return float(np.linalg.norm(q - x)), q, np.array([p2.X(), p2.Y()])

    def nearest(self, p: ArrayLike) -> tuple[float, FloatArray]:
        """``(dist(p, dS), nearest boundary point)`` for one point ``p (3,)``."""
        d, foot, _, _ = self.nearest_support(p)
        return d, foot

    def distances(self, points: ArrayLike) -> FloatArray:
        """Unsigned distances ``(N,)`` of ``points (N, 3)`` to the boundary."""
        return np.array([self.nearest(p)[0] for p in _points(points)])

    def inside(self, points: ArrayLike, tol: float | None = None) -> NDArray[np.bool_]:
        """Whether each point is in the closed solid (``ON`` within ``tol`` counts as in)."""
        tol = self.class_tol if tol is None else tol
        out = []
        for p in _points(points):
            self._classifier.Perform(_pnt(p), tol)
            state_in = self._classifier.State() != TopAbs_OUT
            if not state_in:
                # OCCT's classifier can answer OUT for points exactly on an axis of
                # symmetry (its ray runs along a seam or through an apex): ask again at
                # three points nudged by 1e-6 diag and take the majority
                votes = 0
                for k in range(3):
                    nudge = np.array([(k == 0) - 0.3, (k == 1) - 0.3, (k == 2) - 0.3])
                    self._classifier.Perform(_pnt(p + 1e-6 * self.diag * nudge), tol)
                    votes += self._classifier.State() != TopAbs_OUT
                state_in = votes >= 2
            out.append(state_in)
        return np.array(out, dtype=bool)

    def boundary_samples(self, n: int, seed: int = 0) -> tuple[FloatArray, FloatArray]:
        """About ``n`` boundary points, uniform by area, none within ``edge_margin`` of an edge:
        ``(points (N, 3), exact inward unit normals (N, 3))``.

        Triangles of the mesh are drawn by area and a barycentric point of the triangle's
        ``(u, v)`` nodes is evaluated on the exact surface (so points are on ``dS``; uniform up
        to the parametrisation's distortion across one triangle)."""
        pts, nrm, _, _ = self._sample_faces(n, np.random.default_rng(seed))
        return pts, nrm

    def inward_normal(self, face: int, uv: ArrayLike) -> FloatArray | None:
        """The exact inward unit normal of face ``face`` at ``uv`` (``None`` where undefined)."""
        props = BRepLProp_SLProps(self._surf[face], float(uv[0]), float(uv[1]), 1, 1e-12)
        if not props.IsNormalDefined():
            return None
        return self._inward[face] * _xyz(props.Normal())

    def side(self, p: ArrayLike, foot: FloatArray, face: int | None, uv: Any) -> bool:
        """Whether ``p`` is in the closed solid, given its nearest boundary point: when that is
        inside a face, ``p - foot`` along the inward normal there says inside (no solid
        classification, ~4 ms on a B-spline face); otherwise, and for an apparent outside,
        :meth:`inside` decides (a foot at a reflex cusp edge, where two faces meet with
        opposite normals, reads outside from one of them)."""
        x = np.asarray(p, dtype=float)
        if face is not None and uv is not None:
            n = self.inward_normal(face, uv)
            v = x - foot
            if n is not None and float(v @ n) > 0.9 * float(np.linalg.norm(v)):
                return True
        if self.inside([x])[0]:
            return True
        # OCCT's classifier can answer OUT for a point well inside a B-spline solid (its
        # ray grazes a face; 7 samples of a 240-degree pie slice, 0.088 from the boundary).
        # The ball of radius dist(p, dS) meets no boundary: all its points share p's
        # state, so ask at points halfway to its surface and take the majority.
        d = float(np.linalg.norm(x - np.asarray(foot, dtype=float)))
        if d <= 1e-6 * self.diag:
            return False
        dirs = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, -1, -1], [1, -1, 1]], dtype=float)
        dirs /= np.linalg.norm(dirs, axis=1)[:, None]
        return int(self.inside(x + 0.5 * d * dirs).sum()) >= 3

    def curvature_bound(self, face: int, uv: ArrayLike) -> float:
        """``1/k`` for the largest principal curvature ``k`` of face ``face`` at ``uv`` bending
        towards the interior (``inf`` if none does): no inscribed ball tangent there is larger."""
        return min(self._curvature_bound(face, w) for w in self._seam_sides(face, uv))

    def _seam_sides(self, face: int, uv: ArrayLike) -> list[tuple[float, float]]:
        """``uv`` and, on the seam of a face closed in a parameter, the same point from the
        other end of the range (a periodic B-spline can be only C1 at its seam: there its two
        sides' curvatures differ, and the larger bounds the ball)."""
        s = self._surf[face]
        u, v = float(uv[0]), float(uv[1])
        out = [(u, v)]
        ranges = (
            (s.FirstUParameter(), s.LastUParameter()),
            (s.FirstVParameter(), s.LastVParameter()),
        )
        for axis, (lo, hi) in enumerate(ranges):
            x, slack = out[0][axis], 1e-9 * (hi - lo)
            alt = hi if abs(x - lo) <= slack else lo if abs(x - hi) <= slack else None
            if alt is not None and self._closed(face, axis, v if axis == 0 else u):
                out.append((alt, v) if axis == 0 else (u, alt))
        return out

    def _closed(self, face: int, axis: int, other: float) -> bool:
        """Whether the face's two ends of parameter ``axis`` meet (at the other parameter
        ``other``)."""
        s = self._surf[face]
        if axis == 0:
            lo, hi = s.FirstUParameter(), s.LastUParameter()
            a, b = s.Value(lo, other), s.Value(hi, other)
        else:
            lo, hi = s.FirstVParameter(), s.LastVParameter()
            a, b = s.Value(other, lo), s.Value(other, hi)
        return bool(np.isfinite(hi - lo) and a.Distance(b) <= 1e-9 * self.diag)

    def _curvature_bound(self, face: int, uv: tuple[float, float]) -> float:
        props = BRepLProp_SLProps(self._surf[face], uv[0], uv[1], 2, 1e-12)
        if not props.IsCurvatureDefined():
            return math.inf
        # curvatures are signed towards D1U x D1V; the inward normal is that times the sign
        sign = self._inward[face]
        k = max(sign * props.MaxCurvature(), sign * props.MinCurvature())
        return 1.0 / k if k > 1e-12 / self.diag else math.inf

    def medial_point(self, face: int, uv: ArrayLike) -> FloatArray | None:
        """The true medial point ``b + s* n`` of the boundary point of face ``face`` at
        ``uv`` (None where its normal is undefined)."""
        n = self.inward_normal(face, uv)
        if n is None:
            return None
        b = _xyz(self._surf[face].Value(float(uv[0]), float(uv[1])))
        s = ray_depth(self, b, n, max_depth=self.curvature_bound(face, uv), check_inside=False)
        return np.asarray(b + s * n)

    def local_medial_distance(
        self, p: FloatArray, face: int, uv: ArrayLike, window: float
    ) -> float:
        """Distance from ``p`` to the true medial points whose footpoint on face ``face``
        lies within about ``window`` (arc length) of ``uv``: a Nelder-Mead search over the
        footpoint's parameter offset (the 3D analogue of the 2D oracle's refinement)."""
        u0, v0 = float(uv[0]), float(uv[1])
        props = BRepLProp_SLProps(self._surf[face], u0, v0, 1, 1e-12)
        su = max(float(np.linalg.norm(_xyz(props.D1U()))), 1e-300)
        sv = max(float(np.linalg.norm(_xyz(props.D1V()))), 1e-300)
        srf = self._surf[face]
        lo_u, hi_u = srf.FirstUParameter(), srf.LastUParameter()
        lo_v, hi_v = srf.FirstVParameter(), srf.LastVParameter()

        # a face closed in a parameter (the seam of a periodic profile): the search wraps
        # across its seam instead of stopping there (next to a curvature-centre end at a
        # C1 seam the well-conditioned feet are on the other side)
        wrap_u = self._closed(face, 0, v0)
        wrap_v = self._closed(face, 1, u0)

        def fold(x: float, lo: float, hi: float, wrap: bool) -> float:
            return lo + (x - lo) % (hi - lo) if wrap else min(max(x, lo), hi)

        def f(x: FloatArray) -> float:
            uu = fold(u0 + x[0], lo_u, hi_u, wrap_u)
            vv = fold(v0 + x[1], lo_v, hi_v, wrap_v)
            m = self.medial_point(face, (uu, vv))
            return math.inf if m is None else float(np.linalg.norm(p - m))

        hu, hv = 0.25 * window / su, 0.25 * window / sv
        return _local_min_2d(f, hu, hv, 1e-9 * max(hu, hv), 1e-3 * self.eps)

    def faces_through(self, q: FloatArray) -> list[tuple[int, FloatArray]]:
        """The faces a boundary point ``q`` (on an edge) lies on, with its parameters on
        each: its projection on the face's surface within ``1e-7 diag``, inside the face."""
        eps = 1e-7 * self.diag
        lb = np.linalg.norm(
            np.maximum(0.0, np.maximum(self._fbox[:, 0] - q, q - self._fbox[:, 1])), axis=1
        )
        out = []
        for f in np.flatnonzero(lb <= eps):
            p2 = self._sas[int(f)].ValueOfUV(_pnt(q), 1e-12 * self.diag)
            on = _xyz(self._surf[int(f)].Value(p2.X(), p2.Y()))
            if float(np.linalg.norm(on - q)) > eps:
                continue
            self._face_classifier.Perform(self.faces[int(f)], p2, 1e-9)
            if self._face_classifier.State() != TopAbs_OUT:
                out.append((int(f), np.array([p2.X(), p2.Y()])))
        return out

    def local_bisector_distance(self, p: FloatArray, face: int, uv: ArrayLike) -> float:
        """Distance from ``p`` to the true medial points touching two of the faces near it
        (``face``, its foot's, near ``uv``, among them): the point where the distances to the two surfaces agree,
        by Newton on their difference from ``p`` (projections on the untrimmed surfaces,
        feet checked inside their faces, ball checked empty). Where the two contacts' normals
        differ by a small angle ``a`` (the spoke of a nearly flat corner or of a tiny fillet
        rounding one, revolved or extruded) the ray depth cannot resolve the sheet: along
        the ray the distances to the two sides differ by ``(1 - cos a) s``, below rounding
        for ``a`` ~ 1e-4; their gradients differ by ``a``, so the root is resolved to
        rounding / ``a``. ``inf`` when no such medial point is found."""
        x0 = np.asarray(p, dtype=float)
        d0, _ = self.nearest(x0)
        # candidate second faces: a surface whose distance from p is within d0 / 2 of d0
        lb = np.linalg.norm(
            np.maximum(0.0, np.maximum(self._fbox[:, 0] - x0, x0 - self._fbox[:, 1])), axis=1
        )
        cands = [(face, gp_Pnt2d(float(uv[0]), float(uv[1])))]
        across = self._across_seam(face, uv)
        if across is not None:  # a corner at the face's own seam: feet either side of it
            cands.append((face, across))
        for j in np.nonzero(lb <= 1.5 * d0)[0]:
            j = int(j)
            if j == face:
                continue
            uvj = self._sas[j].ValueOfUV(_pnt(x0), 1e-12 * self.diag)
            dj0 = float(np.linalg.norm(_xyz(self._surf[j].Value(uvj.X(), uvj.Y())) - x0))
            if dj0 <= 1.5 * d0:
                cands.append((j, uvj))
        # every pair of the faces near p: its foot's own, or two others (a foot on a tiny
        # fillet rounding the corner: the sheet beyond its centre is the sides' bisector)
        best = math.inf
        for (i, uvi), (j, uvj) in itertools.combinations(cands, 2):
            got = self._bisector_point(x0, i, uvi, j, uvj)
            if got is not None:
                best = min(best, float(np.linalg.norm(x0 - got)))
        return best

    def _across_seam(self, face: int, uv: ArrayLike) -> Any:
        """The point across the seam of a face closed on itself (a surface swept from a
        closed curve written clamped: its seam may be a corner) from ``uv``, at the same
        distance from the seam on the other side, as a ``gp_Pnt2d``; ``None`` for a face
        not closed in u or v."""
        u0, u1, v0, v1 = BRepTools.UVBounds_s(self.faces[face])
        u, v = float(uv[0]), float(uv[1])
        surf = self._surf[face]
        for closed_u in (True, False):
            a, b = (
                (_xyz(surf.Value(u0, v)), _xyz(surf.Value(u1, v)))
                if closed_u
                else (
                    _xyz(surf.Value(u, v0)),
                    _xyz(surf.Value(u, v1)),
                )
            )
            if float(np.linalg.norm(a - b)) > self.eta:
                continue
            if closed_u:
                return gp_Pnt2d(u0 + u1 - u, v)
            return gp_Pnt2d(u, v0 + v1 - v)
        return None

    def _bisector_point(
        self, x0: FloatArray, i: int, uvi: Any, j: int, uvj: Any
    ) -> FloatArray | None:
        """The point equidistant from faces ``i`` and ``j`` reached from ``x0`` by Newton
        (``uvi``, ``uvj``: ``gp_Pnt2d`` starting feet), if it is a medial point (both feet
        inside their faces, the ball empty). ``i == j``: the two sides of a face's own
        seam (a foot near each end of its parameter range)."""
        uv = [uvi, uvj]
        face = [i, j]

        def foot(k: int, prev: Any, x: FloatArray) -> tuple[Any, FloatArray]:
            q2 = self._sas[face[k]].NextValueOfUV(prev, _pnt(x), 1e-12 * self.diag)
            return q2, _xyz(self._surf[face[k]].Value(q2.X(), q2.Y()))

        def warm(k: int) -> Callable[[FloatArray], FloatArray]:
            def near(x: FloatArray) -> FloatArray:
                uv[k], q = foot(k, uv[k], x)
                return q

            return near

        c, degenerate = equidistant_point(x0, warm(0), warm(1), self.eps, self.diag)
        if degenerate:
            return None
        pi, pj = uv
        pi, qi = foot(0, pi, c)
        pj, qj = foot(1, pj, c)
        di, dj = float(np.linalg.norm(c - qi)), float(np.linalg.norm(c - qj))
        if abs(di - dj) > self.eta:
            return None
        if i == j:  # one foot at each end of the seam's parameter range, a quarter of
            # the range from it at most: the two sides of the seam, not one foot twice
            u0, u1, v0, v1 = BRepTools.UVBounds_s(self.faces[i])
            closed_u = abs(uvi.X() - uvj.X()) > abs(uvi.Y() - uvj.Y())
            lo, hi = (u0, u1) if closed_u else (v0, v1)
            a, b = (pi.X(), pj.X()) if closed_u else (pi.Y(), pj.Y())
            quarter = 0.25 * (hi - lo)
            if not (min(a, b) < lo + quarter and max(a, b) > hi - quarter):
                return None
        for k, q2 in ((i, pi), (j, pj)):
            self._face_classifier.Perform(self.faces[k], q2, 1e-9)
            if self._face_classifier.State() != TopAbs_IN:
                return None
        if self.nearest(c)[0] < di - self.eta:
            return None
        return c

    def local_medial_distance_at_edge(
        self, p: FloatArray, q: FloatArray, window: float
    ) -> float | None:
        """Distance from ``p`` to the true medial points of the balls touching the edge
        through ``q`` (a reflex edge: a foot on no face) near ``q``: a Nelder-Mead search over
        the position ``t`` along the edge and the direction's angle ``theta`` about it (the
        centre lies in the edge's normal plane). None if no edge passes through ``q``."""
        vx, best = _vertex(q), (math.inf, -1, 0.0)
        for i, ext in enumerate(self._ext_e):
            lo, hi = self._ebox[i]
            if np.any(q < lo - 1e-6 * self.diag) or np.any(q > hi + 1e-6 * self.diag):
                continue
            ext.Perform(vx)
            if not ext.IsDone():
                continue
            for k in range(1, ext.NbExt() + 1):
                dk = math.sqrt(ext.SquareDistance(k))
                if dk < best[0]:
                    best = (dk, i, float(ext.Parameter(k)))
        if best[1] < 0 or best[0] > 1e-7 * self.diag:
            return None
        curve = BRepAdaptor_Curve(self._edges[best[1]])
        t0, t_lo, t_hi = best[2], curve.FirstParameter(), curve.LastParameter()
        d = float(np.linalg.norm(p - q))
        u0 = (p - q) / d

        def frame(t: float) -> tuple[FloatArray, FloatArray, FloatArray, float]:
            pt, v1 = gp_Pnt(), gp_Vec()
            curve.D1(t, pt, v1)
            tan = _xyz(v1)
            speed = max(float(np.linalg.norm(tan)), 1e-300)
            tan = tan / speed
            n1 = u0 - (u0 @ tan) * tan
            n1 = n1 / max(float(np.linalg.norm(n1)), 1e-300)
            return _xyz(pt), n1, np.cross(tan, n1), speed

        def f(x: FloatArray) -> float:
            t = min(max(t0 + x[0], t_lo), t_hi)
            e, n1, n2, _ = frame(t)
            w = math.cos(x[1]) * n1 + math.sin(x[1]) * n2
            s = ray_depth(self, e, w, check_inside=False)
            return float(np.linalg.norm(p - (e + s * w)))

        speed = frame(t0)[3]
        return _local_min_2d(f, 0.25 * window / speed, 0.25 * window / d, 1e-12, 1e-3 * self.eps)

    def sampled_depth_bound(self, q: FloatArray, u: FloatArray) -> float:
        """An upper bound of the ray depth: the least radius of the balls centred on
        ``q + s u`` through ``q`` that contain a known boundary point ``y``:
        ``|y - q|^2 / (2 u.(y - q))``."""
        v = self._nodes - q
        h = v @ u
        vv = np.einsum("ij,ij->i", v, v)
        ok = (h > 1e-9 * self.diag) & (vv > (1e-4 * self.diag) ** 2)
        if not ok.any():
            return math.inf
        return float(np.min(vv[ok] / (2 * h[ok])))

    def probe(self, q: FloatArray, u: FloatArray, s: float) -> tuple[bool, float, FloatArray]:
        """Is ``q + s u`` at or before the medial point on the ray? ``(ok, dist, w)`` with ``w``
        the unit vector from the nearest boundary point. Both ``dist >= s - eps`` and, when
        ``dist < s``, "the nearest boundary point is still ``q`` (within ``eta``)" must hold:
        ``dist`` alone resolves ``s*`` only to ``sqrt(eps r)`` at a curvature-centre end point.

        A boundary point from the KD-tree bracket nearer than ``s - eps`` settles a failure
        without the exact (global) distance."""
        x = q + s * u
        local = self._local_nearest(x)
        if 0 < local[0] < s - self.eps:
            d, b = local[0], local[1]
            return False, d, (x - b) / d
        d, b, _, _ = self.nearest_support(x, local)
        w = (x - b) / d if d > 0 else u
        # "the nearest point moved off q" only counts beyond rounding (1e-12 diag, or 4e-14
        # of the coordinates far from the origin): on a fillet's arc of contacts, points
        # 1e-5 from q are as near as q to that
        noise = max(1e-12 * self.diag, 4e-14 * float(np.abs(x).max()))
        ok = d >= s - self.eps and (d >= s - noise or float(np.linalg.norm(b - q)) <= self.eta)
        if ok:
            # a second contact near the first (next to a curvature-centre end) can be missed by
            # BRepExtrema and by the nearest node alone: project from nodes near the ball that
            # are not next to q
            other = self._second_contact(x, q, s)
            if other is not None and other[0] < s - self.eps:
                return False, other[0], (x - other[1]) / other[0]
        return ok, d, w

    def _second_contact(
        self, x: FloatArray, q: FloatArray, s: float
    ) -> tuple[float, FloatArray] | None:
        """The least exact distance from ``x`` to the boundary away from ``q``: local
        projections from the KD-tree nodes nearest ``x`` (up to 12, within ``s`` plus a
        margin) that are not next to ``q`` and do not project back to it; ``None`` if none."""
        margin = min(2e-3 * self.diag, 0.25 * s)
        sep = min(1e-3 * self.diag, 0.1 * s)
        idx = self._tree.query_ball_point(x, s + margin)
        if not idx:
            return None
        idx = np.asarray(idx)
        nodes = self._nodes[idx]
        far = np.linalg.norm(nodes - q, axis=1) > sep
        idx, nodes = idx[far], nodes[far]
        best: tuple[float, FloatArray] | None = None
        for j in np.argsort(np.linalg.norm(nodes - x, axis=1))[:12]:
            cand = float(np.linalg.norm(nodes[j] - x)), nodes[j].copy()
            face, uv = int(self._node_face[idx[j]]), self._node_uv[idx[j]]
            if np.isfinite(uv).all():
                dp, qp, _ = self._project(x, face, uv)
                if dp < cand[0]:
                    cand = dp, qp
            if float(np.linalg.norm(cand[1] - q)) <= sep:
                continue  # back in q's basin
            if best is None or cand[0] < best[0]:
                best = cand
        return best


def _local_min_2d(f: Any, h1: float, h2: float, xatol: float, fatol: float) -> float:
    """The least value of ``f`` over offsets ``(x1, x2)`` near 0: ``f(0)`` or a
    Nelder-Mead search from the simplex with steps ``h1``, ``h2`` (at most 150 values)."""
    simplex = np.array([[0.0, 0.0], [h1, 0.0], [0.0, h2]])
    options = {"initial_simplex": simplex, "xatol": xatol, "fatol": fatol, "maxfev": 150}
    res = minimize(f, np.zeros(2), method="Nelder-Mead", options=options)
    return float(min(f(np.zeros(2)), res.fun))


def _iter(shape: TopoDS_Shape, kind: Any) -> list[TopoDS_Shape]:
    m = _indexed(shape, kind)
    return [m.FindKey(i) for i in range(1, m.Extent() + 1)]


def _bbox(shape: TopoDS_Shape) -> FloatArray:
    """``[[xmin, ymin, zmin], [xmax, ymax, zmax]]`` of the exact geometry, tolerance included."""
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, box, False, True)
    return np.array(box.Get()).reshape(2, 3)


def _unique(shapes: Sequence[TopoDS_Shape]) -> list[TopoDS_Shape]:
    out: list[TopoDS_Shape] = []
    for s in shapes:
        if not any(s.IsSame(o) for o in out):
            out.append(s)
    return out


def _boundary(solid: Any) -> SolidBoundary:
    return solid if isinstance(solid, SolidBoundary) else SolidBoundary(solid)


# --------------------------------------------------------------------------- the oracles


def ray_depth(
    boundary: Any,
    q: ArrayLike,
    u: ArrayLike,
    guess: float | None = None,
    max_depth: float = math.inf,
    check_inside: bool = True,
) -> float:
    """Largest ``s`` with ``dist(q + s u, dS) >= s - eps`` for a boundary point ``q`` and a unit
    direction ``u`` (THEORY Sec. 3); ``q + s* u`` is the medial point on the ray.

    Args:
        boundary: a :class:`SolidBoundary` (or a solid).
        q: the boundary point (3,).
        u: the direction (normalised here).
        guess: an expected depth (e.g. ``|p - q|`` when checking an output point ``p``).
        max_depth: a known upper bound, e.g. :meth:`SolidBoundary.curvature_bound` when ``u``
            is the normal at ``q``.
        check_inside: require the ray to enter the solid: if ``q + s*/2 u`` is outside, 0 is
            returned (the ball of radius ``s*`` is empty of boundary points, so every point of
            the open segment is on the same side).
    """
    sb = _boundary(boundary)
    q = np.asarray(q, dtype=float)
    u = np.asarray(u, dtype=float)
    u = u / np.linalg.norm(u)
    xtol = sb.eps
    bound = min(sb.diag, sb.sampled_depth_bound(q, u) * (1 + 1e-6), max_depth)
    lo, hi = 0.0, bound + 10 * xtol  # hi is taken as failing without a probe
    s = guess if guess is not None and lo < guess < hi else hi - 5 * xtol
    expand, oks, fails = xtol, 0, 0
    for it in range(400):
        ok, d, w = sb.probe(q, u, s)
        if ok:
            lo, oks, fails = s, oks + 1, 0
        else:
            hi, oks, fails = s, 0, fails + 1
        if hi - lo <= xtol:
            break
        cand: float | None = None
        if ok:
            if oks == 1:  # a good guess is confirmed by one more probe just right of it
                cand = lo + xtol
            elif oks == 2:  # not medial: probe just left of the bound, Newton from there
                cand = hi - xtol
            else:  # growing steps
                expand = 8.0 * expand
                cand = lo + expand
        else:
            slope = float(u @ w) - 1.0
            if slope < -1e-15:
                newton = s - (d - s) / slope  # from the right: newton <= s
                # slow (second-order) convergence: overshoot on purpose to find an ok
                cand = newton if fails <= 2 else hi - 4.0 * (hi - newton)
                if hi - cand < 0.5 * xtol:
                    cand = hi - xtol
        # every fourth probe bisects: the predicate is monotone, so the bracket halves at
        # least that often (Newton from the far side of a ball touching a distant part can
        # land on the same ok point forever)
        if cand is None or not (lo < cand < hi) or it % 4 == 3:
            cand = 0.5 * (lo + hi)
        s = cand
    else:
        raise RuntimeError(f"ray depth did not converge: bracket [{lo}, {hi}]")
    s_star = 0.5 * (lo + hi)
    if check_inside and lo > 0 and not sb.inside([q + 0.5 * lo * u])[0]:
        return 0.0
    return s_star


def soundness(
    boundary: Any,
    points: ArrayLike,
    rim_tol: float | None = None,
    refine_above: float | None = None,
    max_refine: int = 40,
) -> FloatArray:
    """Soundness errors of output samples: how far each sample is from being medial.

    For a sample ``p``: ``q`` = nearest boundary point, ``u = (p - q)/|p - q|``, ``s*`` the ray
    depth of ``q`` along ``u``; the error is ``|s* - |p - q||`` (0 on the MAT; ``s* >= |p - q|``
    always). Special values:

    - ``nan``: a *rim* sample: ``|p - q| < rim_tol`` (default ``1e-6 diag``) and within
      ``rim_tol`` of a convex edge or a vertex of the solid, or where the boundary bends
      with a radius below ``rim_tol``, where a MAT point may have radius (nearly) 0 and
      the ray direction is undefined. Count them with ``np.isnan``.
    - a boundary sample (``|p - q| < rim_tol``) anywhere else: its distance to the nearest
      convex edge or vertex (radius 0 is impossible there).
    - ``inf``: the sample is outside the solid (a failure).

    The ray depth uses the curvature bound at ``q`` when ``q`` is inside a face.

    The ray error magnifies an offset ``delta`` of ``p`` across the MAT by about
    ``1 / (1 - cos a)`` where the two contacts are only ``a`` apart seen from ``p`` (a ball
    pinched between two nearly parallel stretches: ~40 at 2.5 degrees). With
    ``refine_above``, the samples whose ray error exceeds it are re-measured as their
    distance to the true medial points whose feet lie near ``q`` on its face
    (:meth:`SolidBoundary.local_medial_distance`), and the smaller value is returned; if
    more than ``max_refine`` samples exceed it, none is (each search costs ~100 ray depths;
    the 20 skeletal circles of a full revolution of a blob, at its curvature-centre ends,
    read 1.25 tol each along the ray and 0.00 refined: 23 samples).
    """
    sb = _boundary(boundary)
    tol = 1e-6 * sb.diag if rim_tol is None else rim_tol
    pts = _points(points)
    errs = np.empty(len(pts))
    where: list[tuple[int, FloatArray, Any, Any]] = []
    for k, p in enumerate(pts):
        d, q, face, uv = sb.nearest_support(p)
        if d < tol:
            dr = sb.rim_distance(p)
            # a tip of the boundary bent tighter than tol (the skeletal edge of a
            # B-spline's turn of radius 1e-7 diag) holds MAT points of radius < tol
            if (
                dr > tol
                and face is not None
                and uv is not None
                and sb.curvature_bound(int(face), uv) <= tol
            ):
                dr = 0.0
            errs[k] = np.nan if dr <= tol else dr
            continue
        if not sb.side(p, q, face, uv):
            errs[k] = np.inf
            continue
        kappa_r = sb.curvature_bound(face, uv) if face is not None and uv is not None else math.inf
        s = ray_depth(sb, q, (p - q) / d, guess=d, max_depth=max(kappa_r, d), check_inside=False)
        errs[k] = abs(s - d)
        where.append((k, q, face, uv))
    todo = [w for w in where if refine_above is not None and errs[w[0]] > refine_above]
    if len(todo) <= max_refine:  # (many more: a broken result, whose verdict stands)
        for k, q, face, uv in todo:
            e = float(errs[k])
            window = 4.0 * math.sqrt(e * sb.diag) + 4.0 * e
            if face is not None and uv is not None:
                errs[k] = min(e, sb.local_medial_distance(pts[k], int(face), uv, window))
                if errs[k] > refine_above:  # a feature narrower than the window's first
                    # step (a revolved flat curvature maximum 1e-3 wide between two feet of
                    # a branch point: 2 tol along the ray, 0.1 tol in the profile's plane)
                    narrow = 4.0 * float(errs[k]) + refine_above
                    errs[k] = min(errs[k], sb.local_medial_distance(pts[k], int(face), uv, narrow))
                if errs[k] > refine_above:  # a spoke between nearly parallel contacts
                    errs[k] = min(errs[k], sb.local_bisector_distance(pts[k], int(face), uv))
                for f, f_uv in sb.faces_through(q):  # a foot on the face's edge: see below
                    if f != face and errs[k] > refine_above:
                        errs[k] = min(errs[k], sb.local_medial_distance(pts[k], f, f_uv, window))
            else:  # a foot on an edge (a reflex edge)
                got = sb.local_medial_distance_at_edge(pts[k], q, window)
                if got is not None:
                    errs[k] = min(e, got)
                # or a smooth one: the medial points of feet on either face through it
                # (an oblique prism's fillet, an ellipse in its cross-section, joins a side
                # at a curvature-centre end: one contact, the ray error 70x the offset)
                for f, f_uv in sb.faces_through(q):
                    if errs[k] > refine_above:
                        errs[k] = min(errs[k], sb.local_medial_distance(pts[k], f, f_uv, window))
    return errs


def medial_points(
    boundary: Any, n: int, seed: int = 0
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """True medial points from boundary samples: ``(b (N, 3), m (N, 3), radius (N,))`` with
    ``m = b + s* n`` (``n`` the inward normal at ``b``, ``s*`` its ray depth, bounded by the
    curvature there; the normal ray enters the solid, no inside test is needed)."""
    sb = _boundary(boundary)
    b, nrm, fidx, uv = sb._sample_faces(n, np.random.default_rng(seed))
    s = np.array(
        [
            ray_depth(sb, bi, ni, max_depth=sb.curvature_bound(int(f), w), check_inside=False)
            for bi, ni, f, w in zip(b, nrm, fidx, uv, strict=True)
        ]
    )
    return b, b + s[:, None] * nrm, s


def completeness(boundary: Any, mat: Any, n: int = 200, seed: int = 0) -> FloatArray:
    """Completeness errors: distance from true medial points to the output.

    Boundary samples ``b`` (by area, away from edges) with inward normals ``n`` give true medial
    points ``m = b + s* n``; the error of each is the distance from ``m`` to ``mat``: a shape
    (the output compound; ``BRepExtrema_DistShapeShape``) or an ``(N, 3)`` array of points
    (nearest point, so the sampling gap is included).
    """
    sb = _boundary(boundary)
    _, m, _ = medial_points(sb, n, seed)
    if isinstance(mat, (np.ndarray, Sequence)):
        return cKDTree(_points(mat)).query(m)[0]
    return ShapeDistance(mat).distances(m)


def radius_error(boundary: Any, points: ArrayLike, radii: ArrayLike) -> FloatArray:
    """``|r - dist(p, dS)|`` for each sample ``p`` and the radius ``r`` it carries."""
    sb = _boundary(boundary)
    return np.abs(np.asarray(radii, dtype=float) - sb.distances(points))


# --------------------------------------------------------------------------- the output


def sample_compound(compound: Any, n_face: int = 100, n_edge: int = 20) -> FloatArray:
    """Points on the output shapes themselves ``(N, 3)``: about ``n_face`` per face (a grid of
    cell centres over the face's ``(u, v)`` bounds, kept where ``BRepClass_FaceClassifier``
    says IN), ``n_edge`` per non-degenerated edge (parameter midpoints) and every vertex."""
    shape = as_occ(compound)
    out: list[FloatArray] = []
    for f in _iter(shape, TopAbs_FACE) if n_face > 0 else []:
        face = TopoDS.Face_s(f)
        surf = BRepAdaptor_Surface(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        tol = 1e-9 * max(u1 - u0, v1 - v0)
        k, kept = max(2, math.ceil(math.sqrt(n_face))), []
        for _ in range(3):
            g = (np.arange(k) + 0.5) / k
            kept = [
                (u, v)
                for u in u0 + g * (u1 - u0)
                for v in v0 + g * (v1 - v0)
                if BRepClass_FaceClassifier(face, gp_Pnt2d(u, v), tol).State() == TopAbs_IN
            ]
            if len(kept) >= 0.7 * n_face:
                break
            k = math.ceil(k * min(3.0, math.sqrt(n_face / max(len(kept), 1))))
        out.extend(_xyz(surf.Value(u, v)) for u, v in kept)
    for e in _iter(shape, TopAbs_EDGE):
        edge = TopoDS.Edge_s(e)
        if BRep_Tool.Degenerated_s(edge):
            continue
        c = BRepAdaptor_Curve(edge)
        t0, t1 = c.FirstParameter(), c.LastParameter()
        out.extend(_xyz(c.Value(t0 + (j + 0.5) / n_edge * (t1 - t0))) for j in range(n_edge))
    out.extend(_xyz(BRep_Tool.Pnt_s(TopoDS.Vertex_s(v))) for v in _iter(shape, TopAbs_VERTEX))
    return np.array(out).reshape(-1, 3)


def euler_characteristic(shape: Any) -> int:
    """``V - E + sum over faces of (2 - number of wires)``, degenerated edges not counted.

    Assumes every face cut along its seam edges is a disk with ``wires - 1`` holes (true of
    OCCT faces: periodic faces carry a seam, poles are degenerated edges)."""
    s = as_occ(shape)
    n_v = _indexed(s, TopAbs_VERTEX).Extent()
    n_e = sum(not BRep_Tool.Degenerated_s(TopoDS.Edge_s(e)) for e in _iter(s, TopAbs_EDGE))
    faces = sum(2 - _indexed(f, TopAbs_WIRE).Extent() for f in _iter(s, TopAbs_FACE))
    return n_v - n_e + faces


def topology(compound: Any) -> tuple[int, int]:
    """``(connected components, Euler characteristic)`` of the output complex.

    Faces, edges and vertices are nodes of a union-find, joined through shared sub-shapes
    (``IsSame``: the same ``TShape`` and location, any orientation); the Euler characteristic is
    :func:`euler_characteristic`. Free edges and free vertices count as they are."""
    s = as_occ(compound)
    verts, edges, faces = (_indexed(s, k) for k in (TopAbs_VERTEX, TopAbs_EDGE, TopAbs_FACE))
    nv, ne = verts.Extent(), edges.Extent()
    parent = list(range(nv + ne + faces.Extent()))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    def union(i: int, j: int) -> None:
        parent[find(i)] = find(j)

    for kind, parent_kind, base, pmap, pbase in (
        (TopAbs_VERTEX, TopAbs_EDGE, 0, edges, nv),
        (TopAbs_EDGE, TopAbs_FACE, nv, faces, nv + ne),
    ):
        anc = _ancestors(s, kind, parent_kind)
        keys = verts if kind == TopAbs_VERTEX else edges
        for i in range(1, anc.Extent() + 1):
            child = keys.FindIndex(anc.FindKey(i)) - 1 + base
            for a in anc.FindFromIndex(i):
                union(child, pmap.FindIndex(a) - 1 + pbase)
    n_comp = len({find(i) for i in range(len(parent))})
    return n_comp, euler_characteristic(s)


def solid_euler(solid: Any) -> int:
    """Euler characteristic of a solid: half that of its boundary surface (the formula of
    :func:`euler_characteristic` on its faces).

    Raises:
        ValueError: the boundary's characteristic is odd (the face assumption failed)."""
    chi = euler_characteristic(as_occ(solid))
    if chi % 2:
        raise ValueError(f"oracle: odd boundary Euler characteristic {chi}")
    return chi // 2
