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
