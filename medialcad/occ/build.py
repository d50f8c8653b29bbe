"""numpy -> OCC builders: B-spline edges and vertices in model space."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeVertex
from OCP.Geom import Geom_BSplineCurve
from OCP.gp import gp_Pnt
from OCP.TColgp import TColgp_Array1OfPnt
from OCP.TColStd import TColStd_Array1OfInteger, TColStd_Array1OfReal
from OCP.TopoDS import TopoDS_Vertex

from medialcad.errors import OCCError
from medialcad.occ.io import occ_guard

__all__ = ["bspline_curve", "edge_between", "vertex"]


def bspline_curve(knots: NDArray[np.float64], poles: NDArray[np.float64], degree: int) -> Any:
    """A ``Geom_BSplineCurve`` from a clamped flat knot vector and 3D poles."""
    uniq, mults = np.unique(knots, return_counts=True)
    # merge knots closer than the OCC parametric resolution
    keep = np.concatenate([[True], np.diff(uniq) > 1e-12 * max(1.0, abs(uniq[-1] - uniq[0]))])
    if not keep.all():
        raise OCCError("spline knots closer than the parametric resolution")
    cp = TColgp_Array1OfPnt(1, len(poles))
    for i, p in enumerate(poles, start=1):
        cp.SetValue(i, gp_Pnt(*map(float, p)))
    kn = TColStd_Array1OfReal(1, len(uniq))
    mu = TColStd_Array1OfInteger(1, len(uniq))
    for i, (k, m) in enumerate(zip(uniq, mults, strict=True), start=1):
        kn.SetValue(i, float(k))
        mu.SetValue(i, int(m))
    with occ_guard("building a B-spline curve"):
        return Geom_BSplineCurve(cp, kn, mu, degree)


def vertex(point: NDArray[np.float64]) -> TopoDS_Vertex:
    return BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, point))).Vertex()


def edge_between(curve: Any, v0: TopoDS_Vertex | None, v1: TopoDS_Vertex | None) -> Any:
    """An edge on ``curve`` over its whole range, sharing the given end vertices."""
    with occ_guard("building an edge"):
        if v0 is None or v1 is None:
            mk = BRepBuilderAPI_MakeEdge(curve)
        else:
            # explicit parameters: OCC refuses (curve, V, V) for a closed curve otherwise
            mk = BRepBuilderAPI_MakeEdge(
                curve, v0, v1, curve.FirstParameter(), curve.LastParameter()
            )
        if not mk.IsDone():
            raise OCCError(f"building an edge failed (error {mk.Error()})")
        return mk.Edge()
