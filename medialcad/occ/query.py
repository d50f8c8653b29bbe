"""Nearest entity of a complex to a point (for radius queries)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
from OCP.BRepExtrema import BRepExtrema_DistShapeShape, BRepExtrema_IsInFace, BRepExtrema_IsOnEdge
from OCP.gp import gp_Pnt

from medialcad.errors import ComputationError
from medialcad.occ.io import occ_guard

__all__ = ["nearest_entity"]


def nearest_entity(
    comp: Any, shapes: tuple[list[Any], list[Any], list[Any]], point: ArrayLike
) -> tuple[str, int, tuple[float, ...]]:
    """``("face" | "edge" | "vertex", index in its list, parameters)`` nearest to ``point``."""
    p = np.asarray(point, dtype=float)
    with occ_guard("finding the nearest medial entity"):
        v = BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, p))).Vertex()
        dss = BRepExtrema_DistShapeShape(v, comp)
        if not dss.IsDone() or dss.NbSolution() == 0:
            raise ComputationError("distance to the medial complex failed")
        support = dss.SupportOnShape2(1)
        kind = dss.SupportTypeShape2(1)
        faces_, edges_, verts = shapes
        if kind == BRepExtrema_IsInFace:
            u, w = dss.ParOnFaceS2(1)
            for i, f in enumerate(faces_):
                if f.IsSame(support):
                    return "face", i, (u, w)
        elif kind == BRepExtrema_IsOnEdge:
            t = dss.ParOnEdgeS2(1)
            t = t[0] if isinstance(t, tuple) else t  # OCP returns (t,)
            for i, e in enumerate(edges_):
                if e.IsSame(support):
                    return "edge", i, (t,)
        for i, vv in enumerate(verts):
            if vv.IsSame(support):
                return "vertex", i, ()
        # an unnamed edge or vertex: fall back to the nearest face by its parameters
        best = None
        for i, f in enumerate(faces_):
            d2 = BRepExtrema_DistShapeShape(v, f)
            if d2.IsDone() and d2.NbSolution() and (best is None or d2.Value() < best[0]):
                if d2.SupportTypeShape2(1) == BRepExtrema_IsInFace:
                    best = (d2.Value(), i, d2.ParOnFaceS2(1))
                else:
                    best = (d2.Value(), i, None)
        if best is None:
            raise ComputationError("no medial entity near the point")
        if best[2] is None:
            from OCP.BRep import BRep_Tool
            from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf

            surf = BRep_Tool.Surface_s(faces_[best[1]])
            proj = GeomAPI_ProjectPointOnSurf(gp_Pnt(*map(float, p)), surf)
            return "face", best[1], tuple(proj.LowerDistanceParameters())
        return "face", best[1], tuple(best[2])
