"""cadquery front end: the 3D medial axis as a ``cq.Workplane``.

Importing this module imports cadquery (the core :mod:`medialcad` package never does)
and changes nothing in it; :func:`register` adds ``Workplane.medialAxis`` when asked.

Example::

    import cadquery as cq
    from medialcad.cadquery import medial_axis

    part = cq.Workplane().box(40, 20, 10)
    mat = medial_axis(part)                    # a Workplane holding one cq.Compound
    cq.exporters.export(mat, "box-mat.step")   # the sewn medial complex
    mat.faces(tag="sheets").size()             # the medial sheets
    mat.edges(tag="seams").vals()              # the seams (edges shared by the sheets)
    entities(mat)["sheet-1"].label             # "sheet-1": named, labelled shapes

Or, after opting in::

    import medialcad.cadquery
    medialcad.cadquery.register()
    cq.Workplane().circle(10).extrude(30).medialAxis().val()
"""

from __future__ import annotations

from typing import Any

import cadquery as cq

__all__ = ["GROUPS", "entities", "medial_axis", "register", "to_workplane", "unregister"]

GROUPS = ("sheets", "seams", "skeletal_edges", "rims", "junctions")
"""Tags of the returned workplane, one per kind of entity of the medial axis."""


def medial_axis(obj: cq.Workplane | cq.Shape | Any, tol: float | None = None) -> cq.Workplane:
    """The exact 3D medial axis transform of an extrusion or a revolution, for cadquery.

    Args:
        obj: a ``cq.Workplane`` holding one solid, a ``cq.Shape`` (``Solid``, ``Compound``
            of one solid) or a ``TopoDS_Shape``.
        tol: geometric tolerance; default ``1e-5`` times the solid's bounding-box
            diagonal.

    Returns:
        A ``cq.Workplane`` (on the input workplane's plane) whose one object is a
        ``cq.Compound`` labelled ``"medial axis"``: the sewn complex, sheets sharing their
        seams, so ``cq.exporters.export`` writes it as it is. Tags name its parts (see
        :data:`GROUPS`): ``mat.faces(tag="sheets")``, ``mat.edges(tag="seams")``,
        ``mat.edges(tag="skeletal_edges")``, ``mat.edges(tag="rims")``,
        ``mat.vertices(tag="junctions")``; :func:`entities` gives them by name.

    Raises:
        medialcad.MedialCadError subclasses: the solid cannot be handled (not an
        extrusion or revolution, no solid, several solids, ...).

    Example::

        mat = medial_axis(cq.Workplane().circle(20).circle(15).extrude(50))
        mat.faces(tag="sheets").size()   # 10
    """
    from medialcad.api import medial_axis as compute

    result = compute(obj, tol)
    plane = obj.plane if isinstance(obj, cq.Workplane) else None
    return to_workplane(result, plane)


def to_workplane(result: Any, plane: cq.Plane | None = None) -> cq.Workplane:
    """A :class:`~medialcad.mat3d.result.MedialAxis3D` as a tagged ``cq.Workplane``.

    The cadquery shapes wrap the result's own ``TopoDS`` objects (nothing is copied).
    """
    comp = cq.Compound(result.compound)
    comp.label = "medial axis"
    wp = cq.Workplane(plane if plane is not None else "XY").newObject([comp])
    groups: dict[str, list[Any]] = {
        "sheets": [_labelled(cq.Face(s.face), s.name) for s in result.sheets],
        "seams": [_labelled(cq.Edge(c.edge), c.name) for c in result.seams],
        "skeletal_edges": [_labelled(cq.Edge(c.edge), c.name) for c in result.skeletal_edges],
        "rims": [_labelled(cq.Edge(c.edge), c.name) for c in result.rims],
        "junctions": [_labelled(cq.Vertex(j.vertex), j.name) for j in result.junctions],
    }
    for tag in GROUPS:
        # children of ``wp`` share its context, so the tags are visible from ``wp``
        wp.newObject(groups[tag]).tag(tag)
    return wp


def entities(wp: cq.Workplane) -> dict[str, cq.Shape]:
    """The named entities of a workplane made by :func:`medial_axis`: ``{name: shape}``.

    Each shape is labelled with its name (``"sheet-1"``, ``"seam-3"``, ``"junction-2"``,
    ...), the names of :meth:`MedialAxis3D.names` and of the CLI's radius sidecar.
    """
    out: dict[str, cq.Shape] = {}
    for tag in GROUPS:
        tagged = wp.ctx.tags.get(tag)
        if tagged is None:
            raise ValueError(f"the workplane has no {tag!r} tag: not made by medial_axis()")
        for shape in tagged.vals():
            if isinstance(shape, cq.Shape):
                out[shape.label] = shape
    return out


def _labelled(shape: Any, name: str) -> Any:
    shape.label = name
    return shape


def _workplane_medial_axis(self: cq.Workplane, tol: float | None = None) -> cq.Workplane:
    """The medial axis of the solid on this workplane (:func:`medialcad.cadquery.medial_axis`)."""
    return medial_axis(self, tol)


def register() -> None:
    """Add ``cq.Workplane.medialAxis(tol=None)`` (idempotent; nothing is added on import).

    Example::

        import medialcad.cadquery
        medialcad.cadquery.register()
        mat = cq.Workplane().box(100, 60, 4).medialAxis()
    """
    cq.Workplane.medialAxis = _workplane_medial_axis  # type: ignore[attr-defined]


def unregister() -> None:
    """Remove what :func:`register` added (if it is still ours)."""
    if getattr(cq.Workplane, "medialAxis", None) is _workplane_medial_axis:
        del cq.Workplane.medialAxis  # type: ignore[attr-defined]
