"""Benchmark faces: STEP fixtures plus built-in fallbacks built with plain OCP."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeWire,
    BRepBuilderAPI_NurbsConvert,
    BRepBuilderAPI_Transform,
)
from OCP.GC import GC_MakeArcOfCircle
from OCP.Geom import Geom_BSplineCurve, Geom_Plane
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.gp import gp_Ax1, gp_Ax2, gp_Circ, gp_Dir, gp_Elips, gp_Pnt, gp_Trsf, gp_Vec
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.TColgp import TColgp_HArray1OfPnt
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape

__all__ = ["BUILTIN_FACES", "count_edges", "load_faces", "read_step_faces"]


def _wire(edges: list) -> object:
    mk = BRepBuilderAPI_MakeWire()
    for e in edges:
        mk.Add(e)
    if not mk.IsDone():
        raise RuntimeError("wire construction failed")
    return mk.Wire()


def _polyline_edges(pts: list[tuple[float, float]]) -> list:
    n = len(pts)
    return [
        BRepBuilderAPI_MakeEdge(gp_Pnt(*pts[i], 0.0), gp_Pnt(*pts[(i + 1) % n], 0.0)).Edge()
        for i in range(n)
    ]


def _face(outer, holes=()) -> TopoDS_Face:
    mk = BRepBuilderAPI_MakeFace(outer, True)
    for h in holes:
        mk.Add(h)
    if not mk.IsDone():
        raise RuntimeError("face construction failed")
    return mk.Face()


def _transformed(face: TopoDS_Face, trsf: gp_Trsf) -> TopoDS_Face:
    return TopoDS.Face_s(BRepBuilderAPI_Transform(face, trsf, True).Shape())


def rectangle() -> TopoDS_Face:
    return _face(_wire(_polyline_edges([(0, 0), (100, 0), (100, 40), (0, 40)])))


def l_shape_tilted() -> TopoDS_Face:
    """An L-shaped polygon (one reflex corner) in a tilted, offset plane."""
    pts = [(0, 0), (60, 0), (60, 20), (20, 20), (20, 50), (0, 50)]
    face = _face(_wire(_polyline_edges(pts)))
    t = gp_Trsf()
    t.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 2, 0.5)), 0.7)
    t2 = gp_Trsf()
    t2.SetTranslation(gp_Vec(10, -5, 30))
    return _transformed(face, t2.Multiplied(t))


def circle() -> TopoDS_Face:
    c = gp_Circ(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 25.0)
    return _face(_wire([BRepBuilderAPI_MakeEdge(c).Edge()]))


def ellipse() -> TopoDS_Face:
    e = gp_Elips(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 50.0, 20.0)
    return _face(_wire([BRepBuilderAPI_MakeEdge(e).Edge()]))


def _interp(pts: np.ndarray, periodic: bool) -> Geom_BSplineCurve:
    arr = TColgp_HArray1OfPnt(1, len(pts))
    for i, (x, y) in enumerate(pts, start=1):
        arr.SetValue(i, gp_Pnt(float(x), float(y), 0.0))
    it = GeomAPI_Interpolate(arr, periodic, 1e-7)
    it.Perform()
    if not it.IsDone():
        raise RuntimeError("interpolation failed")
    return it.Curve()


def bspline_blob() -> TopoDS_Face:
    """One closed periodic B-spline edge through 12 points of a wobbly blob."""
    t = np.linspace(0, 2 * math.pi, 12, endpoint=False)
    r = 40 + 8 * np.sin(3 * t) + 4 * np.cos(5 * t)
    pts = np.stack([r * np.cos(t), 0.7 * r * np.sin(t)], axis=1)
    return _face(_wire([BRepBuilderAPI_MakeEdge(_interp(pts, True)).Edge()]))


def bspline_d() -> TopoDS_Face:
    """A 'D': an open B-spline arc closed by a straight segment (two G0 corners)."""
    t = np.linspace(0, math.pi, 9)
    r = 30 + 5 * np.sin(2 * t) ** 2
    pts = np.stack([r * np.cos(t), r * np.sin(t) * 1.2], axis=1)
    pts[0] = (30.0, 0.0)
    pts[-1] = (-30.0, 0.0)
    spl = BRepBuilderAPI_MakeEdge(_interp(pts, False)).Edge()
    seg = BRepBuilderAPI_MakeEdge(gp_Pnt(-30, 0, 0), gp_Pnt(30, 0, 0)).Edge()
    return _face(_wire([spl, seg]))


def gear_with_hole(teeth: int = 21) -> TopoDS_Face:
    """A gear-like profile: per tooth a root arc, two straight flanks and a tip arc
    (4 edges per tooth, 84 for 21 teeth), with a circular hole."""
    r_root, r_tip = 40.0, 48.0
    pitch = 2 * math.pi / teeth
    edges = []

    def pt(r: float, a: float) -> gp_Pnt:
        return gp_Pnt(r * math.cos(a), r * math.sin(a), 0.0)

    for k in range(teeth):
        a0 = k * pitch
        # root arc from a0 to a0 + 0.45 pitch, flank up, tip arc, flank down
        a1, a2, a3, a4 = a0 + 0.45 * pitch, a0 + 0.55 * pitch, a0 + 0.85 * pitch, a0 + pitch
        root = GC_MakeArcOfCircle(pt(r_root, a0), pt(r_root, (a0 + a1) / 2), pt(r_root, a1))
        edges.append(BRepBuilderAPI_MakeEdge(root.Value()).Edge())
        edges.append(BRepBuilderAPI_MakeEdge(pt(r_root, a1), pt(r_tip, a2)).Edge())
        tip = GC_MakeArcOfCircle(pt(r_tip, a2), pt(r_tip, (a2 + a3) / 2), pt(r_tip, a3))
        edges.append(BRepBuilderAPI_MakeEdge(tip.Value()).Edge())
        edges.append(BRepBuilderAPI_MakeEdge(pt(r_tip, a3), pt(r_root, a4)).Edge())
    outer = _wire(edges)
    hole_c = gp_Circ(gp_Ax2(gp_Pnt(3, 2, 0), gp_Dir(0, 0, 1)), 12.0)
    hole = _wire([BRepBuilderAPI_MakeEdge(hole_c).Edge()])
    hole.Reverse()
    plane = Geom_Plane(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))
    mk = BRepBuilderAPI_MakeFace(plane, outer, True)
    mk.Add(TopoDS.Wire_s(hole))
    if not mk.IsDone():
        raise RuntimeError("gear face construction failed")
    return mk.Face()


def _nurbs(face: TopoDS_Face) -> TopoDS_Face:
    """The face with every edge a (rational) B-spline, as NURBS-only writers give them,
    on its own plane (the bench's baselines read plane faces only)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepTools import BRepTools
    from OCP.TopAbs import TopAbs_WIRE

    def converted(wire: object) -> object:
        return TopoDS.Wire_s(BRepBuilderAPI_NurbsConvert(wire, True).Shape())

    outer = BRepTools.OuterWire_s(face)
    mk = BRepBuilderAPI_MakeFace(BRepAdaptor_Surface(face).Plane(), converted(outer), True)
    ex = TopExp_Explorer(face, TopAbs_WIRE)
    while ex.More():
        if not ex.Current().IsSame(outer):
            mk.Add(converted(ex.Current()))
        ex.Next()
    if not mk.IsDone():
        raise RuntimeError("NURBS face construction failed")
    return mk.Face()


def nurbs_circle() -> TopoDS_Face:
    """The circle's disk, its circle a rational B-spline."""
    return _nurbs(circle())


def nurbs_gear_with_hole() -> TopoDS_Face:
    """The gear with every arc a rational B-spline."""
    return _nurbs(gear_with_hole())


BUILTIN_FACES: dict[str, Callable[[], TopoDS_Face]] = {
    "gear_with_hole": gear_with_hole,
    "bspline_blob": bspline_blob,
    "bspline_d": bspline_d,
    "ellipse": ellipse,
    "circle": circle,
    "rectangle": rectangle,
    "l_shape_tilted": l_shape_tilted,
    "nurbs_circle": nurbs_circle,
    "nurbs_gear_with_hole": nurbs_gear_with_hole,
}


def count_edges(shape: TopoDS_Shape) -> int:
    n = 0
    exp = TopExp_Explorer(shape, TopAbs_EDGE)
    while exp.More():
        n += 1
        exp.Next()
    return n


def read_step_faces(path: Path) -> list[TopoDS_Face]:
    reader = STEPControl_Reader()
    if reader.ReadFile(str(path)) != IFSelect_RetDone:
        raise RuntimeError(f"cannot read {path}")
    reader.TransferRoots()
    shape = reader.OneShape()
    faces = []
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        faces.append(TopoDS.Face_s(exp.Current()))
        exp.Next()
    return faces


def load_faces(
    fixture_dir: Path, use_fixtures: bool = True, use_builtin: bool = True
) -> tuple[list[tuple[str, str, TopoDS_Face]], list[str]]:
    """``([(name, source, face)], warnings)``: every face of every STEP file in
    ``fixture_dir``, then the built-in faces whose name no fixture already uses."""
    out: list[tuple[str, str, TopoDS_Face]] = []
    warnings: list[str] = []
    if use_fixtures and fixture_dir.is_dir():
        for path in sorted(fixture_dir.iterdir()):
            if path.suffix.lower() not in (".step", ".stp"):
                continue
            try:
                faces = read_step_faces(path)
            except Exception as exc:  # noqa: BLE001 - report and go on
                warnings.append(f"{path.name}: {exc}")
                continue
            if not faces:
                warnings.append(f"{path.name}: no face")
            for i, f in enumerate(faces):
                name = path.stem if len(faces) == 1 else f"{path.stem}#{i}"
                out.append((name, "fixture", f))
    if use_builtin:
        have = {n for n, _, _ in out}
        for name, build in BUILTIN_FACES.items():
            if name not in have:
                out.append((name, "builtin", build()))
    return out, warnings
