"""The 3D medial axis transform of oblique prisms (a profile swept along a slanted vector:
sides along the direction ``d``, caps in two parallel planes with normal ``m``).

The distance to a side is the cross-section's (across ``d``) and to a cap the height above
its plane, so the MAT is the right prism's of the cross-section (height ``H``, the caps'
distance) carried by the shear that slants the caps; the radius is carried unchanged.

- Closed form: a rectangle ``a x b`` swept along ``(s, 0, H)``. Its cross-section is the
  rectangle ``a cos x b`` (``cos = H / |v|``); every sheet is planar, and when ``H`` is the
  smallest width the mid sheet is the plane ``z = H/2`` with area
  ``(a cos - H)(b - H) / cos`` and the largest radius is ``H/2``.
- Every profile kind (polygons with holes, B-splines, arcs, ellipses, offset curves), thin
  and tall, in random placements, passes the independent oracles of
  :mod:`tests.oracles3d` (:func:`tests._mat3d.check`).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
from OCP.gp import gp_Vec

import medialcad
from medialcad.mat2d.curves import (
    AffineCurve,
    CircleCurve,
    EllipseCurve,
    LineCurve,
    NurbsCurve,
    OffsetCurve,
    linear_image,
)
from tests import _mat3d as M
from tests import faces as F

DATA = Path(__file__).resolve().parent / "data"
FREECAD = Path(__file__).resolve().parent.parent / "fixtures" / "step" / "freecad"


def oblique_prism(face: Any, v: tuple[float, float, float], seed: int | None = None) -> Any:
    """``face`` (local xy-plane) swept along ``v``, then placed at random (``seed``)."""
    shape = BRepPrimAPI_MakePrism(face, gp_Vec(*map(float, v))).Shape()
    if seed is not None:
        shape = BRepBuilderAPI_Transform(shape, F.random_placement(seed).trsf(), True).Shape()
    return M.single_solid(shape)


def _passes(solid: Any, label: str) -> Any:
    result = medialcad.medial_axis(solid)
    rep = M.check(solid, result, label, n_complete=100)
    print(rep.line())
    assert not rep.failures(), f"{label}: " + "; ".join(rep.failures())
    return result


# --------------------------------------------------------------------------- recognition


def test_an_oblique_prism_is_read_with_its_slant() -> None:
    v = np.array([3.0, 1.0, 2.0])
    solid = oblique_prism(F.rounded_rectangle(4.0, 2.0, 0.5), tuple(v))
    rec = medialcad.recognize(solid)
    assert rec.kind == "extrusion"
    assert abs(abs(rec.direction @ v) / np.linalg.norm(v) - 1.0) < 1e-9
    assert rec.cap_normal is not None
    assert abs(abs(rec.cap_normal[2]) - 1.0) < 1e-9
    assert rec.cap_normal @ rec.direction > 0
    assert rec.length == pytest.approx(np.linalg.norm(v), rel=1e-9)
    assert rec.height == pytest.approx(2.0, rel=1e-9)
    # the profile is the cross-section across the direction: its plane's normal is d
    pf = medialcad.medial_axis_2d(rec.profile).frame
    assert abs(abs(pf.zdir @ rec.direction) - 1.0) < 1e-9


def test_a_right_prism_keeps_its_right_reading() -> None:
    rec = medialcad.recognize(M.prism(F.l_shape(), 1.5))
    assert rec.cap_normal is None and rec.cap is None
    assert rec.height == rec.length == pytest.approx(1.5)


def test_freecads_oblique_prism_is_read_and_passes_the_oracles() -> None:
    """A 40 x 25 rectangle swept along (10, 5, 40): a parallelepiped, an oblique prism
    along each of its three edge directions (any of them is a correct reading)."""
    (solid,) = medialcad.read_step(FREECAD / "fc_oblique_extrusion.step")
    rec = medialcad.recognize(solid)
    edges = [np.array(e) / np.linalg.norm(e) for e in ((10, 5, 40), (1, 0, 0), (0, 1, 0))]
    assert any(abs(abs(rec.direction @ e) - 1.0) < 1e-9 for e in edges)
    assert rec.cap_normal is not None
    _passes(solid, "fc_oblique_extrusion")


# --------------------------------------------------------------------------- closed form


@pytest.mark.parametrize("s", [1.0, 3.0, -2.5])
def test_thin_sheared_box_has_the_closed_form_mid_sheet(s: float) -> None:
    a, b, h = 10.0, 6.0, 1.0
    solid = oblique_prism(F.rectangle(0.5 * a, 0.5 * b), (s, 0.0, h))  # (half-widths)
    result = _passes(solid, f"sheared box s={s}")
    cos = h / math.hypot(s, h)
    eps = 1e-6 * 12.0
    groups = M.planes_and_areas(result, eps)  # every sheet is planar
    mid = [g for g in groups if abs(abs(g[0][2]) - 1.0) < 1e-6 and abs(abs(g[1]) - 0.5 * h) < eps]
    assert len(mid) == 1, groups
    expected = (a * cos - h) * (b - h) / cos
    assert mid[0][2] == pytest.approx(expected, rel=1e-6)
    assert result.rmax == pytest.approx(0.5 * h, rel=1e-9)


def test_tall_sheared_box_has_the_cross_sections_radius() -> None:
    a, b, s, h = 4.0, 3.0, 2.0, 8.0
    solid = oblique_prism(F.rectangle(0.5 * a, 0.5 * b), (s, 0.0, h))
    result = _passes(solid, "tall sheared box")
    cos = h / math.hypot(s, h)
    assert result.rmax == pytest.approx(0.5 * min(a * cos, b), rel=1e-7)


# --------------------------------------------------------------------------- oracles

PROFILES = {
    "polygon_with_holes": lambda: F.polygon_with_holes(
        [(0, 0), (6, 0), (6, 4), (3, 5), (0, 4)], [[(1, 1), (2, 1), (2, 2), (1, 2)]]
    ),
    "bspline_blob": lambda: F.bspline_blob([1.0, 1.4, 0.8, 1.2, 0.9, 1.3]),
    "ellipse_with_hole": lambda: F.ellipse_with_hole(),
    "rounded_rectangle": lambda: F.rounded_rectangle(),
    "star": lambda: F.star_polygon(),
    "annulus": lambda: F.annulus(1.0, 2.0),
}
SWEEPS = {"tall": (0.6, -0.3, 3.0), "thin": (0.5, 0.4, 0.35)}


@pytest.mark.parametrize("sweep", list(SWEEPS))
@pytest.mark.parametrize("profile", list(PROFILES))
def test_oblique_prism_passes_the_oracles(profile: str, sweep: str) -> None:
    seed = sorted(PROFILES).index(profile) * 2 + sorted(SWEEPS).index(sweep)
    solid = oblique_prism(PROFILES[profile](), SWEEPS[sweep], seed=seed)
    _passes(solid, f"{profile} swept {sweep}")


def test_an_oblique_prism_of_offset_curves_passes_the_oracles() -> None:
    """FreeCAD fuzz seed 125: an ellipse less a rectangle, rounded by ``makeOffset2D``
    (offset curves of an ellipse), swept 34.5 degrees off its normal. The sheared offset
    curves have no closed form: they are mapped exactly, not approximated (OCC's own
    B-spline conversion of them left the 2D MAT traced wrong)."""
    (solid,) = medialcad.read_step(DATA / "freecad_fuzz125_rounded_ellipse_oblique.step")
    rec = medialcad.recognize(solid)
    assert rec.cap_normal is not None
    _passes(solid, "freecad fuzz 125")


# --------------------------------------------------------------------------- curves


def _same_image(curve: Any, a: np.ndarray, t: np.ndarray) -> None:
    image, scale = linear_image(curve, a)
    p, d1, d2 = curve.derivs(t)
    q, e1, e2 = image.derivs(t * scale)
    np.testing.assert_allclose(q, p @ a.T, atol=1e-12)
    np.testing.assert_allclose(e1 * scale, d1 @ a.T, atol=1e-12)
    np.testing.assert_allclose(e2 * scale**2, d2 @ a.T, atol=1e-12)


SHEAR = np.array([[0.8, 0.3], [-0.1, 1.2]])
T = np.linspace(-1.0, 2.0, 7)


def test_a_line_maps_to_a_line_on_a_scaled_parameter() -> None:
    line = LineCurve(np.array([1.0, 2.0]), np.array([0.6, 0.8]))
    assert isinstance(linear_image(line, SHEAR)[0], LineCurve)
    _same_image(line, SHEAR, T)


def test_circles_and_ellipses_map_to_ellipses_on_their_parameter() -> None:
    circle = CircleCurve(np.array([1.0, -1.0]), 2.0, np.array([1.0, 0.0]), np.array([0.0, -1.0]))
    ellipse = EllipseCurve(
        np.array([0.0, 3.0]), 3.0, 1.0, np.array([0.6, 0.8]), np.array([-0.8, 0.6])
    )
    for c in (circle, ellipse):
        image, scale = linear_image(c, SHEAR)
        assert isinstance(image, EllipseCurve) and scale == 1.0
        _same_image(c, SHEAR, T)


def test_nurbs_map_their_poles_and_other_curves_are_wrapped() -> None:
    knots = np.array([0, 0, 0, 1, 2, 2, 2], dtype=float)
    poles = np.array([[0, 0], [1, 2], [3, 2], [4, 0]], dtype=float)
    nurbs = NurbsCurve(knots, poles, np.array([1.0, 0.7, 1.3, 1.0]), 2)
    assert isinstance(linear_image(nurbs, SHEAR)[0], NurbsCurve)
    _same_image(nurbs, SHEAR, np.linspace(0.0, 2.0, 9))
    offset = OffsetCurve(nurbs, 0.3)
    assert isinstance(linear_image(offset, SHEAR)[0], AffineCurve)
    _same_image(offset, SHEAR, np.linspace(0.1, 1.9, 9))
