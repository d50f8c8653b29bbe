"""Accepting shapes from any front end, and small topology helpers.

Inputs are recognised by duck typing, so neither cadquery nor build123d is imported:

- a raw ``OCP.TopoDS.TopoDS_Shape`` (or subclass) is used as is;
- a cadquery ``Shape`` or build123d ``Shape`` carries its OCC shape in ``.wrapped``;
- a cadquery ``Workplane`` has ``.vals()``: one object is used as is, several are
  combined into a compound;
- a list/tuple (e.g. a build123d ``ShapeList``) is combined into a compound.

Note that build123d wraps ``Part`` and ``Sketch`` objects (``Box``, ``Rectangle``, ...)
in a ``TopoDS_Compound`` even when they hold a single solid or face.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.GeomAbs import GeomAbs_Plane
from OCP.GeomLib import GeomLib_IsPlanarSurface
from OCP.TopAbs import (
    TopAbs_EDGE,
    TopAbs_FACE,
    TopAbs_ShapeEnum,
    TopAbs_SHELL,
    TopAbs_SOLID,
    TopAbs_WIRE,
)
from OCP.TopExp import TopExp
from OCP.TopoDS import (
    TopoDS,
    TopoDS_Compound,
    TopoDS_Edge,
    TopoDS_Face,
    TopoDS_Shape,
    TopoDS_Shell,
    TopoDS_Solid,
    TopoDS_Wire,
)
from OCP.TopTools import TopTools_IndexedDataMapOfShapeListOfShape, TopTools_IndexedMapOfShape

from medialcad.errors import InputError, NonPlanarFaceError, NotAFaceError, OpenShellError

__all__ = [
    "as_topods",
    "compound",
    "edges",
    "faces",
    "is_planar",
    "shape_kind",
    "single_face",
    "solids",
    "solids_or_shells",
    "wires",
]

_KIND_NAMES = {
    "TopAbs_COMPOUND": "compound",
    "TopAbs_COMPSOLID": "compsolid",
    "TopAbs_SOLID": "solid",
    "TopAbs_SHELL": "shell",
    "TopAbs_FACE": "face",
    "TopAbs_WIRE": "wire",
    "TopAbs_EDGE": "edge",
    "TopAbs_VERTEX": "vertex",
    "TopAbs_SHAPE": "shape",
}

DEFAULT_PLANAR_TOLERANCE = 1e-7
"""Tolerance handed to ``GeomLib_IsPlanarSurface`` by :func:`single_face`."""


def as_topods(obj: Any) -> TopoDS_Shape:
    """Return the OpenCascade shape behind a raw, cadquery or build123d object.

    Args:
        obj: A ``TopoDS_Shape``; anything with a ``.wrapped`` ``TopoDS_Shape`` (cadquery or
            build123d shapes); a cadquery ``Workplane`` (``.vals()``); or a list/tuple of
            any of these.

    Returns:
        The shape itself (not a copy); several objects are combined into a compound.

    Raises:
        InputError: The object holds no shape, a null shape, or is of an unknown type.
    """
    shape = _as_topods(obj)
    if shape.IsNull():
        raise InputError("expected a shape, got a null shape")
    return shape


def _as_topods(obj: Any) -> TopoDS_Shape:
    if isinstance(obj, TopoDS_Shape):
        return obj
    wrapped = getattr(obj, "wrapped", None)
    if isinstance(wrapped, TopoDS_Shape):
        return wrapped
    vals = getattr(obj, "vals", None)
    if callable(vals) and not isinstance(obj, list | tuple):
        items = list(vals())
        if not items:
            raise InputError(f"expected a shape, got an empty {type(obj).__name__}")
        return _combine(items)
    if isinstance(obj, list | tuple):
        if not obj:
            raise InputError("expected a shape, got an empty list")
        return _combine(obj)
    raise InputError(f"expected a shape, got a {type(obj).__module__}.{type(obj).__name__}")


def _combine(items: Iterable[Any]) -> TopoDS_Shape:
    shapes = [as_topods(item) for item in items]
    return shapes[0] if len(shapes) == 1 else compound(shapes)


def compound(shapes: Iterable[TopoDS_Shape]) -> TopoDS_Compound:
    """Combine shapes into a new ``TopoDS_Compound`` (shapes are shared, not copied)."""
    builder = BRep_Builder()
    result = TopoDS_Compound()
    builder.MakeCompound(result)
    for shape in shapes:
        builder.Add(result, shape)
    return result


def _unique(shape: TopoDS_Shape, kind: TopAbs_ShapeEnum) -> list[TopoDS_Shape]:
    """Distinct sub-shapes of one kind, in exploration order (``IsSame`` identity)."""
    found = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, kind, found)
    return [found.FindKey(i) for i in range(1, found.Extent() + 1)]


def faces(shape: TopoDS_Shape) -> list[TopoDS_Face]:
    """Distinct faces of ``shape`` (the shape itself if it is a face), in exploration order."""
    return [TopoDS.Face_s(s) for s in _unique(shape, TopAbs_FACE)]


def solids(shape: TopoDS_Shape) -> list[TopoDS_Solid]:
    """Distinct solids of ``shape`` (the shape itself if it is a solid), in exploration order."""
    return [TopoDS.Solid_s(s) for s in _unique(shape, TopAbs_SOLID)]


def _free_shells(shape: TopoDS_Shape) -> list[TopoDS_Shell]:
    """Shells of ``shape`` that belong to no solid of it."""
    inside = TopTools_IndexedMapOfShape()
    for s in _unique(shape, TopAbs_SOLID):
        TopExp.MapShapes_s(s, TopAbs_SHELL, inside)
    return [TopoDS.Shell_s(s) for s in _unique(shape, TopAbs_SHELL) if not inside.Contains(s)]


def _free_edge_count(shell: TopoDS_Shell) -> int:
    """Edges used by exactly one face of ``shell`` (seam edges count twice: closed)."""
    owners = TopTools_IndexedDataMapOfShapeListOfShape()
    TopExp.MapShapesAndAncestors_s(shell, TopAbs_EDGE, TopAbs_FACE, owners)
    free = 0
    for i in range(1, owners.Extent() + 1):
        edge = TopoDS.Edge_s(owners.FindKey(i))
        if BRep_Tool.Degenerated_s(edge):
            continue
        users = owners.FindFromIndex(i)
        if users.Size() == 1 and not BRep_Tool.IsClosed_s(edge, TopoDS.Face_s(users.First())):
            free += 1
    return free


def _shell_solid(shell: TopoDS_Shell) -> TopoDS_Solid:
    """The solid bounded by a closed shell, oriented so that its faces point outwards."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeSolid
    from OCP.ShapeFix import ShapeFix_Solid

    from medialcad.occ.io import occ_guard

    with occ_guard("making a solid from a closed shell"):
        made = BRepBuilderAPI_MakeSolid(shell)
        if not made.IsDone():
            raise OpenShellError("a closed shell could not be made into a solid")
        fix = ShapeFix_Solid(made.Solid())
        fix.Perform()
        return TopoDS.Solid_s(solids(fix.Shape())[0])


def _one_plane(shell: TopoDS_Shell) -> bool:
    """Whether every face of ``shell`` lies in one plane (a sheet of planar regions)."""
    planes = []
    for face in faces(shell):
        surface = BRep_Tool.Surface_s(face)
        found = GeomLib_IsPlanarSurface(surface, DEFAULT_PLANAR_TOLERANCE)
        if not found.IsPlanar():
            return False
        planes.append(found.Plan())
    p0 = planes[0]
    for p in planes[1:]:
        if not p.Axis().IsParallel(p0.Axis(), 1e-9):
            return False
        if p0.Distance(p.Location()) > 1e-7 * max(1.0, p0.Location().Distance(p.Location())):
            return False
    return True


def solids_or_shells(shape: TopoDS_Shape) -> list[TopoDS_Solid]:
    """The solids of ``shape`` and, as solids, its closed shells that belong to no solid
    (files from surface modellers often hold a closed ``SHELL`` and no ``SOLID``).

    Open shells of planar faces in one plane (how STEP files of loose faces arrive) are
    left alone: they are faces, not solids.

    Raises:
        OpenShellError: a shell outside every solid does not close and is not flat: a
            surface model (e.g. a solid with a face missing), not a solid.
    """
    found = solids(shape)
    for i, shell in enumerate(_free_shells(shape), start=1):
        free = _free_edge_count(shell)
        if not free:
            found.append(_shell_solid(shell))
        elif not _one_plane(shell):
            raise OpenShellError(
                f"shell {i} (with {_plural(len(faces(shell)), 'face')}) is open: {free} free "
                "edge(s) bound no volume, so it is not a solid"
            )
    return found


def edges(shape: TopoDS_Shape) -> list[TopoDS_Edge]:
    """Distinct edges of ``shape``, in exploration order."""
    return [TopoDS.Edge_s(s) for s in _unique(shape, TopAbs_EDGE)]


def wires(shape: TopoDS_Shape) -> list[TopoDS_Wire]:
    """Distinct wires of ``shape``, in exploration order."""
    return [TopoDS.Wire_s(s) for s in _unique(shape, TopAbs_WIRE)]


def shape_kind(shape: TopoDS_Shape) -> str:
    """Lower-case name of the shape type: ``"solid"``, ``"face"``, ``"compound"``, ..."""
    return _KIND_NAMES.get(shape.ShapeType().name, "shape")


def _plural(n: int, word: str) -> str:
    return f"{n} {word}" if n == 1 else f"{n} {word}s"


def _describe(shape: TopoDS_Shape) -> str:
    """Describe a non-face input for an error message: 'a solid with 6 faces'."""
    n_solids = len(solids(shape))
    n_faces = len(faces(shape))
    if n_solids == 1:
        return f"a solid with {_plural(n_faces, 'face')}"
    if n_solids > 1:
        return f"{n_solids} solids with {_plural(n_faces, 'face')}"
    if n_faces > 1:
        return f"{n_faces} faces"
    return f"no face (a {shape_kind(shape)} with {_plural(len(edges(shape)), 'edge')})"


def single_face(obj: Any, *, planar: bool = False) -> TopoDS_Face:
    """Return the one face held by ``obj``.

    A face, or a shell/compound holding exactly one face and no solid, is accepted.

    Args:
        obj: Anything :func:`as_topods` accepts.
        planar: Also require the face to lie on a plane.

    Returns:
        The face, with the orientation it has in ``obj``.

    Raises:
        InputError: ``obj`` holds no shape (see :func:`as_topods`).
        NotAFaceError: ``obj`` holds a solid, several faces, or no face, e.g.
            ``"expected one planar face, got a solid with 6 faces"``.
        NonPlanarFaceError: ``planar`` is set and the face is not planar.
    """
    shape = as_topods(obj)
    found = faces(shape)
    if len(found) != 1 or solids(shape):
        raise NotAFaceError(f"expected one planar face, got {_describe(shape)}")
    face = found[0]
    if planar and not is_planar(face):
        surface = BRepAdaptor_Surface(face).GetType().name.removeprefix("GeomAbs_")
        raise NonPlanarFaceError(f"expected one planar face, got a face on a {surface} surface")
    return face


def is_planar(face: TopoDS_Face, tolerance: float = DEFAULT_PLANAR_TOLERANCE) -> bool:
    """Whether the face's surface is a plane, or a surface planar within ``tolerance``."""
    if BRepAdaptor_Surface(face).GetType() == GeomAbs_Plane:
        return True
    surface = BRep_Tool.Surface_s(face)
    return bool(GeomLib_IsPlanarSurface(surface, tolerance).IsPlanar())
