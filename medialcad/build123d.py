"""build123d front end: the 3D medial axis as a labelled ``build123d.Compound``.

Importing this module imports build123d (the core :mod:`medialcad` package never does).

Example::

    from build123d import Box, export_step
    from medialcad.build123d import medial_axis

    mat = medial_axis(Box(40, 20, 10))
    [c.label for c in mat.children]
    # ['sheets', 'seams', 'skeletal_edges', 'rims', 'junctions']
    sheets = mat.children[0]
    sheets.children[0].label        # 'sheet-1' (a Face)
    len(mat.faces())                # the sheets, sewn: they share their seams
    export_step(mat, "box-mat.step")
"""

from __future__ import annotations

from typing import Any

from build123d import Compound, Edge, Face, Vertex

__all__ = ["GROUPS", "medial_axis", "to_compound"]

GROUPS = ("sheets", "seams", "skeletal_edges", "rims", "junctions")
"""Labels of the children of the returned compound, in order."""


def medial_axis(shape: Any, tol: float | None = None) -> Compound:
    """The exact 3D medial axis transform of an extrusion or a revolution, for build123d.

    Args:
        shape: a build123d ``Part``/``Solid``/``Compound`` holding one solid (or a
            ``TopoDS_Shape``).
        tol: geometric tolerance; default ``1e-5`` times the solid's bounding-box
            diagonal.

    Returns:
        A ``Compound`` labelled ``"medial axis"`` whose children are compounds labelled
        ``"sheets"`` (``Face`` objects), ``"seams"``, ``"skeletal_edges"``, ``"rims"``
        (``Edge`` objects) and ``"junctions"`` (``Vertex`` objects); every entity is
        labelled with its name (``"sheet-1"``, ``"seam-2"``, ...: the names of the CLI's
        radius sidecar). All of them wrap the result's own ``TopoDS`` objects, so the
        sheets share their seams and rims with each other and with the edges of the
        ``"seams"``/``"rims"`` children (an edge is the same object wherever it shows).

    Raises:
        medialcad.MedialCadError subclasses: the solid cannot be handled (not an
        extrusion or revolution, no solid, several solids, ...).

    Example::

        from build123d import Cylinder
        mat = medial_axis(Cylinder(10, 30))
        axis = mat.children[2].children[0]     # the skeletal edge (the axis)
        axis.label, axis.length                # ('skeletal-1', 10.0)
    """
    from medialcad.api import medial_axis as compute

    return to_compound(compute(shape, tol))


def to_compound(result: Any) -> Compound:
    """A :class:`~medialcad.mat3d.result.MedialAxis3D` as a labelled ``Compound``
    (see :func:`medial_axis`)."""
    items: dict[str, list[Any]] = {
        "sheets": [_labelled(Face(s.face), s.name) for s in result.sheets],
        "seams": [_labelled(Edge(c.edge), c.name) for c in result.seams],
        "skeletal_edges": [_labelled(Edge(c.edge), c.name) for c in result.skeletal_edges],
        "rims": [_labelled(Edge(c.edge), c.name) for c in result.rims],
        "junctions": [_labelled(Vertex(j.vertex), j.name) for j in result.junctions],
    }
    groups = [_group(tag, items[tag]) for tag in GROUPS]
    return Compound(label="medial axis", children=groups)


def _labelled(shape: Any, name: str) -> Any:
    shape.label = name
    return shape


def _group(label: str, shapes: list[Any]) -> Compound:
    if shapes:
        return Compound(label=label, children=shapes)
    from OCP.BRep import BRep_Builder
    from OCP.TopoDS import TopoDS_Compound

    empty = TopoDS_Compound()
    BRep_Builder().MakeCompound(empty)
    return Compound(empty, label=label)
