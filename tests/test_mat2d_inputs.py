"""``medial_axis_2d`` takes a face as users hold it: OCP, cadquery, build123d, from files."""

from __future__ import annotations

from pathlib import Path

import build123d as bd
import cadquery as cq
import numpy as np
import pytest

import medialcad
from medialcad.occ.io import read_shapes
from medialcad.occ.shapes import faces

FACES = Path(__file__).resolve().parent.parent / "fixtures" / "step" / "faces"


def _summary(mat: medialcad.MedialAxis2D) -> tuple[int, int, float]:
    return len(mat.branches), len(mat.branch_points), round(mat.rmax, 6)


def test_cadquery_face_workplane_and_raw_agree() -> None:
    wp = cq.Workplane("XZ").rect(40, 20).extrude(1).faces("<Y")
    face = wp.val()
    expected = (5, 2, 10.0)
    assert _summary(medialcad.medial_axis_2d(face)) == expected
    assert _summary(medialcad.medial_axis_2d(wp)) == expected
    assert _summary(medialcad.medial_axis_2d(face.wrapped)) == expected


def test_build123d_face() -> None:
    face = bd.Face(bd.Wire.make_rect(40, 20))
    assert _summary(medialcad.medial_axis_2d(face)) == (5, 2, 10.0)
    sketch = bd.Rectangle(40, 20)  # a compound holding one face
    assert _summary(medialcad.medial_axis_2d(sketch)) == (5, 2, 10.0)


def test_exact_offset_curve_edge_from_brep() -> None:
    """The BREP fixture keeps the exact Geom_OffsetCurve edge (STEP drops it): same axis as
    the B-spline approximation in the STEP fixture."""
    (exact,) = faces(read_shapes(FACES / "offset_face.brep")[0])
    (approx,) = faces(read_shapes(FACES / "offset_face.step")[0])
    a, b = medialcad.medial_axis_2d(exact), medialcad.medial_axis_2d(approx)
    assert len(a.branches) == len(b.branches) and len(a.nodes) == len(b.nodes)
    pa = np.array(sorted(tuple(np.round(n.point, 3)) for n in a.nodes))
    pb = np.array(sorted(tuple(np.round(n.point, 3)) for n in b.nodes))
    assert np.abs(pa - pb).max() <= 1e-2
    assert a.rmax == pytest.approx(b.rmax, abs=a.tol)


def _offset_bases() -> list[tuple[str, object]]:
    from OCP.Geom2d import Geom2d_BezierCurve, Geom2d_Circle, Geom2d_Ellipse, Geom2d_TrimmedCurve
    from OCP.Geom2dConvert import Geom2dConvert
    from OCP.gp import gp_Ax2d, gp_Dir2d, gp_Pnt2d
    from OCP.TColgp import TColgp_Array1OfPnt2d

    ellipse = Geom2d_Ellipse(gp_Ax2d(gp_Pnt2d(1, 2), gp_Dir2d(0.6, 0.8)), 3.0, 1.2)
    arc = Geom2d_TrimmedCurve(Geom2d_Circle(gp_Ax2d(gp_Pnt2d(0, 0), gp_Dir2d(1, 0)), 2.0), 0.3, 2.5)
    poles = TColgp_Array1OfPnt2d(1, 5)
    for i, (x, y) in enumerate([(0, 0), (1, 2), (2, -1), (3, 1), (4, 0)]):
        poles.SetValue(i + 1, gp_Pnt2d(x, y))
    return [
        ("ellipse", ellipse),
        ("rational B-spline", Geom2dConvert.CurveToBSplineCurve_s(arc)),
        ("Bezier", Geom2d_BezierCurve(poles)),
    ]


@pytest.mark.parametrize("offset", [0.3, -0.4])
@pytest.mark.parametrize("name", ["ellipse", "rational B-spline", "Bezier"])
def test_offset_curves_are_evaluated_exactly_as_occ_does(name: str, offset: float) -> None:
    """An offset of an ellipse or a (rational) spline is evaluated from its basis's
    derivatives: point, first and second derivative as OCC's own to 1e-12."""
    from OCP.Geom2d import Geom2d_OffsetCurve
    from OCP.gp import gp_Pnt2d, gp_Vec2d

    from medialcad.mat2d.curves import OffsetCurve
    from medialcad.occ.face2d import _curve_to_numpy

    basis = dict(_offset_bases())[name]
    occ = Geom2d_OffsetCurve(basis, offset)
    t0, t1 = occ.FirstParameter(), occ.LastParameter()
    if not np.isfinite(t1 - t0) or t1 - t0 > 100:
        t0, t1 = 0.0, 2.0 * np.pi
    ours = _curve_to_numpy(occ, t0, t1, 1e-9)
    assert isinstance(ours, OffsetCurve)
    ts = np.linspace(t0, t1, 23)
    got = np.hstack(ours.derivs(ts))
    want = []
    for t in ts:
        p, v1, v2 = gp_Pnt2d(), gp_Vec2d(), gp_Vec2d()
        occ.D2(float(t), p, v1, v2)
        want.append([p.X(), p.Y(), v1.X(), v1.Y(), v2.X(), v2.Y()])
    assert np.abs(got - np.array(want)).max() <= 1e-12 * max(1.0, np.abs(want).max())


def test_a_planar_offset_edge_is_read_as_the_offset_of_its_basis() -> None:
    """build123d's offset of an ellipse is Geom_OffsetCurve edges (split at the vertices,
    one piece a few 1e-5 long): read as offsets of the ellipse, not through
    ``GeomAPI.To2d``'s degree-10 Bezier approximation (whose 1e-9 errors grew a spurious
    branch at the curvature maximum)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    from medialcad.mat2d.curves import OffsetCurve
    from medialcad.occ.face2d import planar_face

    sketch = bd.offset(bd.Ellipse(3.08, 2.96), -0.29, kind=bd.Kind.ARC)
    face = sketch.faces()[0].rotate(bd.Axis((0, 0, 0), (0.98, 0.39, -0.24)), 145.8)
    pf = planar_face(face.wrapped)
    pieces = [p for loop in pf.loops for p in loop]
    assert pieces and all(isinstance(p.curve, OffsetCurve) for p in pieces)
    for p in pieces:
        curve = BRepAdaptor_Curve(pf.edges[p.edge_index])
        ts = np.linspace(p.t0, p.t1, 7)
        occ = np.array([[(q := curve.Value(t)).X(), q.Y(), q.Z()] for t in ts])
        assert np.abs(pf.frame.to_3d(p.curve.point(ts)) - occ).max() <= 1e-12 * pf.diag
    mat = medialcad.medial_axis_2d(face)
    assert len(mat.branches) == 1 and len(mat.branch_points) == 0
