"""Build a sewn, non-manifold B-spline complex with ``BRep_Builder``.

Sheets are built as faces on B-spline surfaces ruled in ``v`` (degree 1) between two
rows of poles that share one knot vector in ``u``, or on tensor B-spline surfaces
(rational ones for revolved sheets, whose ``u = const`` sides are exact arcs); every
boundary side of a face is a real shared edge or a degenerated edge:

- *curve edges* (seams, rims, offset seams) are created once per key and carry the row's
  B-spline with parameter ``u``; every face on that row gets the pcurve ``v = 0`` or
  ``v = 1`` in the same parameter;
- *line edges* between two vertices (the rulings at a face's ``u`` ends) are shared by
  vertex pair, parameter ``[0, 1]``;
- vertices are merged when they coincide within ``merge`` (they come from the same
  numbers, so this only absorbs rounding).

Planar faces (mid sheets) are bounded by existing curve edges, wired into loops and
nested by their 2D polygons.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import NDArray
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
from OCP.Geom2d import Geom2d_Line
from OCP.gp import gp_Ax3, gp_Dir, gp_Dir2d, gp_Pln, gp_Pnt, gp_Pnt2d
from OCP.TColgp import TColgp_Array1OfPnt, TColgp_Array2OfPnt
from OCP.TColStd import TColStd_Array1OfInteger, TColStd_Array1OfReal, TColStd_Array2OfReal
from OCP.TopAbs import TopAbs_FACE, TopAbs_FORWARD, TopAbs_REVERSED
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Compound, TopoDS_Edge, TopoDS_Face, TopoDS_Vertex, TopoDS_Wire

from medialcad.errors import ComputationError
from medialcad.occ.io import occ_guard

__all__ = ["ComplexBuilder", "Row"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Row:
    """A B-spline curve ``u in [0, 1]`` given by clamped ``knots``, ``poles (n, 3)``."""

    key: Hashable
    knots: FloatArray
    poles: FloatArray
    degree: int
    weights: FloatArray | None = None  # (n,): rational


def _knots_mults(t: FloatArray) -> tuple[TColStd_Array1OfReal, TColStd_Array1OfInteger]:
    """OCC knots and multiplicities of a flat knot vector (cached: the rows of a segment
    share theirs; OCC copies the arrays it is given)."""
    t = np.ascontiguousarray(t, dtype=float)
    return _knots_mults_cached(t.tobytes())


@lru_cache(maxsize=4096)
def _knots_mults_cached(raw: bytes) -> tuple[TColStd_Array1OfReal, TColStd_Array1OfInteger]:
    vals: list[float] = []
    mults: list[int] = []
    for x in np.frombuffer(raw, dtype=float).tolist():
        if vals and x - vals[-1] <= 1e-13:
            mults[-1] += 1
        else:
            vals.append(x)
            mults.append(1)
    k = TColStd_Array1OfReal(1, len(vals))
    m = TColStd_Array1OfInteger(1, len(vals))
    for i, (v, mm) in enumerate(zip(vals, mults, strict=True), start=1):
        k.SetValue(i, v)
        m.SetValue(i, mm)
    return k, m


def _pnt(p: FloatArray) -> gp_Pnt:
    return gp_Pnt(float(p[0]), float(p[1]), float(p[2]))


def bspline(
    knots: FloatArray, poles: FloatArray, degree: int, weights: FloatArray | None = None
) -> Geom_BSplineCurve:
    arr = TColgp_Array1OfPnt(1, len(poles))
    for i, p in enumerate(poles, start=1):
        arr.SetValue(i, _pnt(p))
    k, m = _knots_mults(knots)
    if weights is None or np.all(weights == 1.0):
        return Geom_BSplineCurve(arr, k, m, degree)
    wa = TColStd_Array1OfReal(1, len(weights))
    for i, x in enumerate(np.asarray(weights, dtype=float).tolist(), start=1):
        wa.SetValue(i, x)
    return Geom_BSplineCurve(arr, wa, k, m, degree)


@dataclass
class _Edge:
    edge: TopoDS_Edge
    v0: int
    v1: int


@dataclass
class ComplexBuilder:
    """Accumulates vertices, edges and faces of one complex (see the module docstring)."""

    merge: float
    tol: float
    builder: BRep_Builder = field(default_factory=BRep_Builder)
    points: list[FloatArray] = field(default_factory=list)
    vertices: list[TopoDS_Vertex] = field(default_factory=list)
    curve_edges: dict[Hashable, _Edge] = field(default_factory=dict)
    line_edges: dict[tuple[int, int], _Edge] = field(default_factory=dict)
    faces: list[TopoDS_Face] = field(default_factory=list)
    _grid: dict[tuple[int, int, int], list[int]] = field(default_factory=dict)
    _xyz: list[tuple[float, float, float]] = field(default_factory=list)
    _uses: dict[int, tuple[Geom2d_Line, bool]] = field(default_factory=dict)  # this face's edges

    # -- vertices ------------------------------------------------------------------
    def vertex(self, p: FloatArray) -> int:
        p = np.asarray(p, dtype=float)
        x, y, z = p.tolist()
        size = 4 * self.merge
        cell = (math.floor(x / size), math.floor(y / size), math.floor(z / size))
        grid, merge2 = self._grid, self.merge * self.merge
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for i in grid.get((cell[0] + dx, cell[1] + dy, cell[2] + dz), ()):
                        qx, qy, qz = self._xyz[i]
                        if (qx - x) ** 2 + (qy - y) ** 2 + (qz - z) ** 2 <= merge2:
                            return i
        v = TopoDS_Vertex()
        self.builder.MakeVertex(v, _pnt(p), self.tol)
        self.points.append(p)
        self._xyz.append((x, y, z))
        self.vertices.append(v)
        i = len(self.points) - 1
        self._grid.setdefault(cell, []).append(i)
        return i

    # -- edges ---------------------------------------------------------------------
    def _edge(self, curve: Any, v0: int, v1: int) -> TopoDS_Edge:
        e = TopoDS_Edge()
        self.builder.MakeEdge(e, curve, self.tol)
        self.builder.Add(e, self.vertices[v0].Oriented(TopAbs_FORWARD))
        self.builder.Add(e, self.vertices[v1].Oriented(TopAbs_REVERSED))
        self.builder.Range(e, 0.0, 1.0)
        return e

    def is_degenerate(self, row: Row) -> bool:
        return bool(np.ptp(row.poles, axis=0).max() <= self.merge)

    def curve_edge(self, row: Row) -> _Edge:
        got = self.curve_edges.get(row.key)
        if got is None:
            v0, v1 = self.vertex(row.poles[0]), self.vertex(row.poles[-1])
            curve = bspline(row.knots, row.poles, row.degree, row.weights)
            got = _Edge(self._edge(curve, v0, v1), v0, v1)
            self.curve_edges[row.key] = got
        return got

    def line_edge(self, v0: int, v1: int) -> _Edge:
        key = (min(v0, v1), max(v0, v1))
        got = self.line_edges.get(key)
        if got is None:
            a, b = self.points[v0], self.points[v1]
            curve = bspline(np.array([0.0, 0.0, 1.0, 1.0]), np.vstack([a, b]), 1)
            got = _Edge(self._edge(curve, v0, v1), v0, v1)
            self.line_edges[key] = got
        return got

    # -- faces ---------------------------------------------------------------------
    def ruled_face(self, bottom: Row, top: Row) -> TopoDS_Face:
        """A face ruled between two rows of equal knots (``v = 0`` bottom, ``v = 1`` top)."""
        if len(bottom.poles) != len(top.poles) or bottom.degree != top.degree:
            raise ComputationError("ruled face rows are not compatible")
        self._uses = {}
        with occ_guard("building a medial sheet"):
            n = len(bottom.poles)
            arr = TColgp_Array2OfPnt(1, n, 1, 2)
            for i in range(n):
                arr.SetValue(i + 1, 1, _pnt(bottom.poles[i]))
                arr.SetValue(i + 1, 2, _pnt(top.poles[i]))
            uk, um = _knots_mults(bottom.knots)
            vk, vm = _knots_mults(np.array([0.0, 0.0, 1.0, 1.0]))
            surf = Geom_BSplineSurface(arr, uk, vk, um, vm, bottom.degree, 1)
            face = TopoDS_Face()
            self.builder.MakeFace(face, surf, TopLoc_Location(), self.tol)
            wire = TopoDS_Wire()
            self.builder.MakeWire(wire)
            b00 = self.vertex(bottom.poles[0])
            b10 = self.vertex(bottom.poles[-1])
            t01 = self.vertex(top.poles[0])
            t11 = self.vertex(top.poles[-1])
            # bottom: v = 0, u 0 -> 1
            self._row_side(wire, face, bottom, 0.0, forward=True, v_from=b00)
            # right: u = 1, v 0 -> 1
            self._line_side(wire, face, 1.0, b10, t11)
            # top: v = 1, u 1 -> 0
            self._row_side(wire, face, top, 1.0, forward=False, v_from=t11)
            # left: u = 0, v 1 -> 0
            self._line_side(wire, face, 0.0, t01, b00)
            self.builder.Add(face, wire)
        self.faces.append(face)
        return face

    def grid_face(
        self,
        poles: FloatArray,
        u_knots: FloatArray,
        v_knots: FloatArray,
        du: int,
        dv: int,
        bottom_key: Hashable,
        top_key: Hashable,
        weights: FloatArray | None = None,
    ) -> TopoDS_Face:
        """A face on a tensor B-spline surface ``poles (nu, nv, 3)`` (rational with
        ``weights (nu, nv)``); ``v = 0``/``v = 1`` rows are the shared curve edges
        ``bottom_key``/``top_key`` (unit weights there), the ``u = 0``/``u = 1`` sides are
        shared by their geometry (end vertices and middle pole)."""
        nu, nv = poles.shape[:2]
        self._uses = {}
        with occ_guard("building a medial sheet"):
            arr = TColgp_Array2OfPnt(1, nu, 1, nv)
            for i in range(nu):
                for j in range(nv):
                    arr.SetValue(i + 1, j + 1, _pnt(poles[i, j]))
            uk, um = _knots_mults(u_knots)
            vk, vm = _knots_mults(v_knots)
            if weights is None:
                surf = Geom_BSplineSurface(arr, uk, vk, um, vm, du, dv)
            else:
                wa = TColStd_Array2OfReal(1, nu, 1, nv)
                for i, line in enumerate(np.asarray(weights, dtype=float).tolist(), start=1):
                    for j, x in enumerate(line, start=1):
                        wa.SetValue(i, j, x)
                surf = Geom_BSplineSurface(arr, wa, uk, vk, um, vm, du, dv)
            face = TopoDS_Face()
            self.builder.MakeFace(face, surf, TopLoc_Location(), self.tol)
            wire = TopoDS_Wire()
            self.builder.MakeWire(wire)
            bottom = Row(bottom_key, u_knots, poles[:, 0], du)
            top = Row(top_key, u_knots, poles[:, -1], du)
            b00 = self.vertex(poles[0, 0])
            t11 = self.vertex(poles[-1, -1])
            self._row_side(wire, face, bottom, 0.0, forward=True, v_from=b00)
            wl, wr = (None, None) if weights is None else (weights[0], weights[-1])
            self._col_side(wire, face, 1.0, Row(None, v_knots, poles[-1], dv, wr), up=True)
            self._row_side(wire, face, top, 1.0, forward=False, v_from=t11)
            self._col_side(wire, face, 0.0, Row(None, v_knots, poles[0], dv, wl), up=False)
            self.builder.Add(face, wire)
        self.faces.append(face)
        return face

    def side_key(self, poles: FloatArray) -> tuple[Any, ...]:
        """The key a ``u = const`` side is shared by: its end vertices and middle pole."""
        v0, v1 = self.vertex(poles[0]), self.vertex(poles[-1])
        mid = np.round(poles[len(poles) // 2] / (100 * self.merge)).astype(int)
        return ("side", min(v0, v1), max(v0, v1), tuple(mid))

    def _col_side(
        self, wire: TopoDS_Wire, face: TopoDS_Face, u: float, col: Row, *, up: bool
    ) -> None:
        """The side ``u = const`` (poles from ``v = 0`` to ``v = 1``), traversed up or down."""
        v0 = self.vertex(col.poles[0])
        if self.is_degenerate(col):
            pc = Geom2d_Line(gp_Pnt2d(u, 0.0 if up else 1.0), gp_Dir2d(0.0, 1.0 if up else -1.0))
            self._degenerate(wire, face, pc, v0)
            return
        key = self.side_key(col.poles)
        e = self.curve_edges.get(key)
        if e is None:
            e = self.curve_edge(Row(key, col.knots, col.poles, col.degree, col.weights))
        same = e.v0 == v0  # the edge runs v = 0 -> 1 on this face
        pc = Geom2d_Line(gp_Pnt2d(u, 0.0 if same else 1.0), gp_Dir2d(0.0, 1.0 if same else -1.0))
        self._attach(wire, face, e, pc, forward=same == up)

    def _row_side(
        self,
        wire: TopoDS_Wire,
        face: TopoDS_Face,
        row: Row,
        v: float,
        *,
        forward: bool,
        v_from: int,
    ) -> None:
        if self.is_degenerate(row):
            d = 1.0 if forward else -1.0
            start = 0.0 if forward else 1.0
            pc = Geom2d_Line(gp_Pnt2d(start, v), gp_Dir2d(d, 0.0))
            self._degenerate(wire, face, pc, v_from)
            return
        e = self.curve_edge(row)
        pc = Geom2d_Line(gp_Pnt2d(0.0, v), gp_Dir2d(1.0, 0.0))
        self._attach(wire, face, e, pc, forward=forward)

    def _line_side(self, wire: TopoDS_Wire, face: TopoDS_Face, u: float, va: int, vb: int) -> None:
        """The side ``u = const`` traversed from vertex ``va`` to ``vb``."""
        going_up = u == 1.0  # right side goes v 0 -> 1, left side goes v 1 -> 0
        if va == vb:
            d = 1.0 if going_up else -1.0
            pc = Geom2d_Line(gp_Pnt2d(u, 0.0 if going_up else 1.0), gp_Dir2d(0.0, d))
            self._degenerate(wire, face, pc, va)
            return
        e = self.line_edge(va, vb)
        # pcurve in the edge's own parameter (from e.v0 to e.v1)
        same = e.v0 == va
        v_start = (0.0 if going_up else 1.0) if same else (1.0 if going_up else 0.0)
        d = (1.0 if going_up else -1.0) * (1.0 if same else -1.0)
        pc = Geom2d_Line(gp_Pnt2d(u, v_start), gp_Dir2d(0.0, d))
        self._attach(wire, face, e, pc, forward=same)

    def _attach(
        self, wire: TopoDS_Wire, face: TopoDS_Face, e: _Edge, pc: Geom2d_Line, *, forward: bool
    ) -> None:
        """Add edge ``e`` to the face's ``wire`` with its pcurve ``pc``. An edge met twice
        on one face is its seam (a loop of the 2D MAT from a branch point back to it: the
        sheet's two ends are one ruling or arc): it gets both pcurves, the first for its
        forward use."""
        prev = self._uses.get(id(e))
        if prev is None:
            self.builder.UpdateEdge(e.edge, pc, face, self.tol)
            self._uses[id(e)] = (pc, forward)
        else:
            pc0, forward0 = prev
            if forward0 == forward:
                raise ComputationError("a sheet runs along one of its edges twice the same way")
            pf, pr = (pc0, pc) if forward0 else (pc, pc0)
            self.builder.UpdateEdge(e.edge, pf, pr, face, self.tol)
        self.builder.Range(e.edge, face, 0.0, 1.0)
        self.builder.Add(wire, e.edge.Oriented(TopAbs_FORWARD if forward else TopAbs_REVERSED))

    def _degenerate(self, wire: TopoDS_Wire, face: TopoDS_Face, pc: Geom2d_Line, v: int) -> None:
        e = TopoDS_Edge()
        self.builder.MakeEdge(e)
        self.builder.UpdateEdge(e, pc, face, self.tol)
        self.builder.Degenerated(e, True)
        self.builder.Add(e, self.vertices[v].Oriented(TopAbs_FORWARD))
        self.builder.Add(e, self.vertices[v].Oriented(TopAbs_REVERSED))
        self.builder.Range(e, face, 0.0, 1.0)
        self.builder.Add(wire, e.Oriented(TopAbs_FORWARD))

    def planar_faces(
        self, keys: Sequence[Hashable], origin: FloatArray, xdir: FloatArray, ydir: FloatArray
    ) -> list[TopoDS_Face]:
        """Planar faces bounded by the curve edges ``keys`` (loops found by their vertices;
        keys of rows that collapsed to a point are skipped).

        The plane is ``origin + x xdir + y ydir``; loops are nested by their 2D polygons.
        """
        # a row that collapsed to a point (an offset curve of zero length) has no edge and
        # adds nothing to a loop
        loops = _loops([(k, self.curve_edges[k]) for k in keys if k in self.curve_edges])
        if not loops:
            return []
        polys = []
        for loop in loops:
            pts = []
            for key, fwd in loop:
                poles = self.curve_edges[key]
                crv = bspline_points(poles.edge, 24)
                pts.append(crv if fwd else crv[::-1])
            p3 = np.vstack(pts)
            d = p3 - origin
            polys.append(np.column_stack([d @ xdir, d @ ydir]))
        areas = [
            0.5 * float(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]))
            for p in polys
        ]
        depth = [
            sum(_inside(polys[i][0], polys[j]) for j in range(len(polys)) if j != i)
            for i in range(len(polys))
        ]
        zdir = np.cross(xdir, ydir)
        pln = gp_Pln(gp_Ax3(_pnt(origin), gp_Dir(*map(float, zdir)), gp_Dir(*map(float, xdir))))
        out: list[TopoDS_Face] = []
        with occ_guard("building a planar medial sheet"):
            for i, loop in enumerate(loops):
                if depth[i] % 2:
                    continue
                wire = self._wire(loop, reverse=areas[i] < 0)
                mk = BRepBuilderAPI_MakeFace(pln, wire, True)
                for j, inner in enumerate(loops):
                    if depth[j] == depth[i] + 1 and _inside(polys[j][0], polys[i]):
                        mk.Add(self._wire(inner, reverse=areas[j] > 0))
                if not mk.IsDone():
                    raise ComputationError("a planar medial sheet could not be built")
                face = mk.Face()
                self.faces.append(face)
                out.append(face)
        return out

    def _wire(self, loop: list[tuple[Hashable, bool]], *, reverse: bool) -> TopoDS_Wire:
        wire = TopoDS_Wire()
        self.builder.MakeWire(wire)
        items = loop[::-1] if reverse else loop
        for key, fwd in items:
            f = fwd != reverse
            self.builder.Add(
                wire, self.curve_edges[key].edge.Oriented(TopAbs_FORWARD if f else TopAbs_REVERSED)
            )
        return wire

    def compound(self, extra: list[Any] = ()) -> TopoDS_Compound:  # type: ignore[assignment]
        comp = TopoDS_Compound()
        self.builder.MakeCompound(comp)
        for f in self.faces:
            self.builder.Add(comp, f)
        for s in extra:
            self.builder.Add(comp, s)
        return comp


def check_valid(comp: TopoDS_Compound) -> None:
    """Raise :class:`ComputationError` unless OCC's ``BRepCheck_Analyzer`` accepts the
    medial complex (2 to 10 % of the MAT's time on the fixtures): a complex traced wrong
    (sheets of a nearly flat convex corner's spoke narrower than the tolerance) is an
    error, not an answer."""
    with occ_guard("checking the medial complex"):
        check = BRepCheck_Analyzer(comp)
        if check.IsValid():
            return
        what = ""
        explorer = TopExp_Explorer(comp, TopAbs_FACE)
        while explorer.More() and not what:
            face = explorer.Current()
            if not check.IsValid(face):
                status = [str(s).rsplit("_", 1)[-1] for s in check.Result(face).Status()]
                what = f" (a sheet: {', '.join(status)})"
            explorer.Next()
    raise ComputationError(
        f"the medial complex fails OCC's own check (BRepCheck_Analyzer){what}: traced wrong"
    )


def bspline_points(edge: TopoDS_Edge, n: int) -> FloatArray:
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    c = BRepAdaptor_Curve(edge)
    ts = np.linspace(c.FirstParameter(), c.LastParameter(), n)
    out = []
    for t in ts:
        p = c.Value(float(t))
        out.append((p.X(), p.Y(), p.Z()))
    return np.array(out)


def _inside(p: FloatArray, poly: FloatArray) -> bool:
    x, y = p
    xs, ys = poly[:, 0], poly[:, 1]
    xs2, ys2 = np.roll(xs, -1), np.roll(ys, -1)
    cross = (ys > y) != (ys2 > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xint = xs + (y - ys) * (xs2 - xs) / (ys2 - ys)
    return bool(np.count_nonzero(cross & (x < xint)) % 2)


def _loops(items: list[tuple[Hashable, _Edge]]) -> list[list[tuple[Hashable, bool]]]:
    """Chain edges into closed loops through their vertices."""
    at: dict[int, list[int]] = {}
    for i, (_, e) in enumerate(items):
        at.setdefault(e.v0, []).append(i)
        at.setdefault(e.v1, []).append(i)
    used = [False] * len(items)
    loops = []
    for i0 in range(len(items)):
        if used[i0]:
            continue
        loop = []
        i, fwd = i0, True
        start = items[i0][1].v0
        while True:
            used[i] = True
            loop.append((items[i][0], fwd))
            e = items[i][1]
            end = e.v1 if fwd else e.v0
            if end == start:
                break
            nxt = [j for j in at.get(end, []) if not used[j]]
            if not nxt:
                raise ComputationError("the mid sheet's boundary does not close")
            i = nxt[0]
            fwd = items[i][1].v0 == end
        loops.append(loop)
    return loops
