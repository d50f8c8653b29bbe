"""Accepting cadquery, build123d and raw OCP inputs (medialcad.occ.shapes)."""

from __future__ import annotations

import build123d as bd
import cadquery as cq
import pytest
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
from OCP.gp import gp_Pln
from OCP.TopoDS import TopoDS_Face, TopoDS_Shape, TopoDS_Solid

from medialcad.errors import InputError, NonPlanarFaceError, NotAFaceError
from medialcad.occ.shapes import (
    as_topods,
    compound,
    edges,
    faces,
    is_planar,
    shape_kind,
    single_face,
    solids,
)


def _raw_face() -> TopoDS_Face:
    return BRepBuilderAPI_MakeFace(gp_Pln(), 0.0, 4.0, 0.0, 2.0).Face()


# --------------------------------------------------------------------------- as_topods


def test_raw_shape_is_returned_as_is() -> None:
    box = BRepPrimAPI_MakeBox(1, 2, 3).Shape()
    assert as_topods(box) is box


def test_cadquery_shape_and_workplane() -> None:
    wp = cq.Workplane("XY").rect(4, 2).extrude(1)
    assert as_topods(wp.val()).IsSame(wp.val().wrapped)
    assert as_topods(wp).IsSame(wp.val().wrapped)
    assert shape_kind(as_topods(wp)) == "solid"


def test_cadquery_workplane_with_several_objects_is_a_compound() -> None:
    wp = cq.Workplane("XY").box(1, 1, 1).faces()
    shape = as_topods(wp)
    assert shape_kind(shape) == "compound"
    assert len(faces(shape)) == 6


def test_build123d_shapes() -> None:
    box = bd.Box(1, 2, 3)
    assert as_topods(box).IsSame(box.wrapped)
    assert len(solids(as_topods(box))) == 1
    face = bd.Rectangle(4, 2).face()
    assert as_topods(face).IsSame(face.wrapped)


def test_build123d_shape_list_is_a_compound() -> None:
    shape = as_topods(bd.Box(1, 1, 1).faces())
    assert shape_kind(shape) == "compound"
    assert len(faces(shape)) == 6


@pytest.mark.parametrize(
    ("obj", "match"),
    [
        (None, "NoneType"),
        (42, "int"),
        ("box.step", "str"),
        ([], "empty list"),
        (cq.Workplane("XY"), "empty Workplane"),
        (TopoDS_Shape(), "null shape"),
        (cq.Location(), "Location"),
    ],
)
def test_rejects_non_shapes(obj: object, match: str) -> None:
    with pytest.raises(InputError, match=match):
        as_topods(obj)


# --------------------------------------------------------------------------- helpers


def test_faces_and_solids_are_downcast_and_distinct() -> None:
    box = BRepPrimAPI_MakeBox(1, 2, 3).Shape()
    fs = faces(box)
    assert len(fs) == 6
    assert all(type(f) is TopoDS_Face for f in fs)
    (solid,) = solids(box)
    assert type(solid) is TopoDS_Solid
    assert len(edges(box)) == 12
    # A compound listing the same solid twice still has 6 distinct faces.
    assert len(faces(compound([box, box]))) == 6


# --------------------------------------------------------------------------- single_face


@pytest.mark.parametrize(
    "make",
    [
        _raw_face,
        lambda: cq.Workplane("XY").rect(4, 2).extrude(1).faces(">Z"),
        lambda: cq.Workplane("XY").rect(4, 2).extrude(1).faces(">Z").val(),
        lambda: cq.Face.makeFromWires(
            cq.Wire.makePolygon([(0, 0, 0), (4, 0, 0), (0, 2, 0)], close=True)
        ),
        lambda: bd.Rectangle(4, 2),  # a build123d Sketch: a compound holding one face
        lambda: bd.Rectangle(4, 2).face(),
        lambda: compound([_raw_face()]),
    ],
)
def test_single_face_accepts(make: object) -> None:
    face = single_face(make(), planar=True)  # type: ignore[operator]
    assert type(face) is TopoDS_Face
    assert is_planar(face)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: BRepPrimAPI_MakeBox(1, 2, 3).Shape(), "got a solid with 6 faces"),
        (lambda: bd.Box(1, 2, 3), "got a solid with 6 faces"),
        (lambda: cq.Workplane("XY").box(1, 1, 1), "got a solid with 6 faces"),
        (lambda: cq.Workplane("XY").sphere(1), "got a solid with 1 face"),
        (lambda: cq.Workplane("XY").box(1, 1, 1).faces(), "got 6 faces"),
        (lambda: cq.Workplane("XY").rect(4, 2), r"got no face \(a wire with 4 edges\)"),
        (
            lambda: [bd.Box(1, 1, 1), bd.Pos(5, 0, 0) * bd.Box(1, 1, 1)],
            "got 2 solids with 12 faces",
        ),
    ],
)
def test_single_face_rejects(make: object, message: str) -> None:
    with pytest.raises(NotAFaceError, match=f"^expected one planar face, {message}$"):
        single_face(make())  # type: ignore[operator]


def test_single_face_planar_check() -> None:
    side = cq.Workplane("XY").cylinder(2, 1).faces("%CYLINDER")
    assert shape_kind(single_face(side)) == "face"
    with pytest.raises(NonPlanarFaceError, match="Cylinder"):
        single_face(side, planar=True)


def test_single_face_keeps_orientation() -> None:
    face = _raw_face()
    reversed_face = face.Reversed()
    assert single_face(reversed_face).Orientation() == reversed_face.Orientation()
