"""Inputs medial_axis_2d must refuse, each with its own error class and a one-line message."""

from __future__ import annotations

from typing import Any

import cadquery as cq
import numpy as np
import pytest
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon
from OCP.gp import gp_Pln, gp_Pnt
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Wire

import medialcad
from medialcad import (
    DegenerateFaceError,
    InputError,
    MedialCadError,
    NonPlanarFaceError,
    NotAFaceError,
    OpenWireError,
    SelfIntersectingBoundaryError,
)


def _polyline(pts: list[tuple[float, float, float]], close: bool) -> TopoDS_Wire:
    poly = BRepBuilderAPI_MakePolygon()
    for p in pts:
        poly.Add(gp_Pnt(*p))
    if close:
        poly.Close()
    return poly.Wire()


def cylindrical_face() -> TopoDS_Face:
    solid = cq.Solid.makeCylinder(1.0, 2.0).wrapped
    ex = TopExp_Explorer(solid, TopAbs_FACE)
    while ex.More():
        f = TopoDS.Face_s(ex.Current())
        if cq.Face(f).geomType() == "CYLINDER":
            return f
        ex.Next()
    raise AssertionError("no cylindrical face")


def open_wire_face() -> TopoDS_Face:
    """A face on a plane bounded by an open wire (BRepBuilderAPI_MakeFace accepts it)."""
    wire = _polyline([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], close=False)
    return BRepBuilderAPI_MakeFace(gp_Pln(), wire, True).Face()


def bow_tie_face() -> TopoDS_Face:
    wire = _polyline([(0, 0, 0), (1, 1, 0), (1, 0, 0), (0, 1, 0)], close=True)
    return BRepBuilderAPI_MakeFace(wire, True).Face()


def zero_area_face() -> TopoDS_Face:
    wire = _polyline([(0, 0, 0), (1, 0, 0), (2, 0, 0)], close=True)
    return BRepBuilderAPI_MakeFace(gp_Pln(), wire, True).Face()


CASES: list[tuple[str, Any, tuple[type[Exception], ...]]] = [
    ("cylindrical_face", cylindrical_face, (NonPlanarFaceError,)),
    ("open_wire_face", open_wire_face, (OpenWireError,)),
    (
        "open_wire",
        lambda: _polyline([(0, 0, 0), (1, 0, 0), (1, 1, 0)], close=False),
        (NotAFaceError, OpenWireError),
    ),
    (
        "edge",
        lambda: cq.Edge.makeLine(cq.Vector(0, 0, 0), cq.Vector(1, 0, 0)).wrapped,
        (NotAFaceError,),
    ),
    (
        "closed_wire",
        lambda: _polyline([(0, 0, 0), (1, 0, 0), (1, 1, 0)], close=True),
        (NotAFaceError,),
    ),
    ("bow_tie", bow_tie_face, (SelfIntersectingBoundaryError,)),
    ("zero_area", zero_area_face, (DegenerateFaceError, SelfIntersectingBoundaryError)),
    ("solid", lambda: cq.Solid.makeBox(1, 1, 1).wrapped, (NotAFaceError,)),
    ("cq_box_workplane", lambda: cq.Workplane().box(1, 1, 1), (NotAFaceError,)),
    ("none", lambda: None, (NotAFaceError,)),
    ("string", lambda: "a face", (NotAFaceError,)),
]


@pytest.mark.parametrize(("make", "expected"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_input_raises(make: Any, expected: tuple[type[Exception], ...]) -> None:
    obj = make()
    with pytest.raises(MedialCadError) as info:
        medialcad.medial_axis_2d(obj)
    err = info.value
    assert isinstance(err, InputError), f"{type(err).__name__} is not an InputError"
    assert isinstance(err, expected), f"got {type(err).__name__}: {err}"
    msg = str(err)
    assert msg and "\n" not in msg.strip(), f"message should be one line: {msg!r}"


def test_error_hierarchy() -> None:
    for cls in (
        NotAFaceError,
        NonPlanarFaceError,
        OpenWireError,
        SelfIntersectingBoundaryError,
        DegenerateFaceError,
    ):
        assert issubclass(cls, InputError) and issubclass(InputError, MedialCadError)


def test_edge_off_the_plane_is_refused() -> None:
    """A face whose surface is a plane but one of whose edges leaves it (bad export)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon
    from OCP.gp import gp_Pln, gp_Pnt

    import medialcad

    poly = BRepBuilderAPI_MakePolygon(
        gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0), gp_Pnt(10, 5, 0.5), gp_Pnt(0, 5, 0), True
    )
    face = BRepBuilderAPI_MakeFace(gp_Pln(), poly.Wire(), True).Face()
    with pytest.raises((medialcad.NonPlanarFaceError, medialcad.InputError)) as info:
        medialcad.medial_axis_2d(face)
    assert "\n" not in str(info.value)


def test_self_crossing_boundary_with_many_edges_is_refused() -> None:
    """Above ``BREPCHECK_MAX_EDGES`` edges OCC's (quadratic) face check is skipped and the
    crossings are found by medialcad's own check: a pentagram traced by 395 short edges
    (nonzero area, every star point a crossing) is refused as before."""
    from medialcad.occ.face2d import BREPCHECK_MAX_EDGES

    ang = np.pi / 2 + 4 * np.pi * np.arange(5) / 5
    tips = list(10 * np.column_stack([np.cos(ang), np.sin(ang)]))
    pts = [
        tuple(a + t * (b - a))
        for a, b in zip(tips, tips[1:] + tips[:1], strict=True)
        for t in np.linspace(0.0, 1.0, 80)[:-1]
    ]
    assert len(pts) > BREPCHECK_MAX_EDGES
    face = cq.Face.makeFromWires(cq.Workplane().polyline(pts).close().val())
    with pytest.raises(SelfIntersectingBoundaryError):
        medialcad.medial_axis_2d(face)
