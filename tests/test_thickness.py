"""Wall thickness from the 3D medial axis, on solids whose answer is known."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import cadquery as cq
import numpy as np
import pytest

from medialcad.api import medial_axis
from medialcad.recognition import read_step
from medialcad.thickness import Thickness, thickness_at, wall_thickness

SOLIDS = Path(__file__).resolve().parent.parent / "fixtures" / "step" / "solids"


@pytest.fixture(scope="module")
def plate() -> Any:
    return medial_axis(cq.Workplane().box(100, 60, 4))


@pytest.fixture(scope="module")
def tube() -> Any:
    return medial_axis(cq.Workplane().circle(20).circle(15).extrude(50))


@pytest.fixture(scope="module")
def l_bracket() -> Any:
    pts = [(0, 0), (60, 0), (60, 5), (5, 5), (5, 40), (0, 40)]
    return medial_axis(cq.Workplane().polyline(pts).close().extrude(30))


def _close(x: float, want: float, mat: Any) -> bool:
    return abs(x - want) <= 20 * mat.tol


def _is_wall_point(mat: Any, t: Thickness) -> None:
    """The reported places are on the medial axis, with the reported thickness."""
    assert _close(thickness_at(mat, t.min_location), t.min, mat)
    assert _close(thickness_at(mat, t.max_location), t.max, mat)


def test_plate_min_is_its_thickness(plate: Any) -> None:
    t = wall_thickness(plate)
    assert _close(t.min, 4.0, plate) and _close(t.max, 4.0, plate)
    assert abs(t.min_location[2]) <= 20 * plate.tol  # the mid plane
    _is_wall_point(plate, t)
    assert thickness_at(plate, (0, 0, 0)) == pytest.approx(4.0, abs=20 * plate.tol)


def test_box_is_as_thick_as_its_smallest_side() -> None:
    mat = medial_axis(cq.Workplane().box(40, 20, 10))
    t = wall_thickness(mat)
    assert _close(t.min, 10.0, mat) and _close(t.max, 10.0, mat)
    _is_wall_point(mat, t)


def test_cube_minimum_is_at_the_centre_ball() -> None:
    """No sheet of a cube has opposite touches: only the centre ball does (6 faces)."""
    mat = medial_axis(cq.Workplane().box(10, 10, 10))
    t = wall_thickness(mat)
    assert _close(t.min, 10.0, mat) and _close(t.max, 10.0, mat)
    np.testing.assert_allclose(t.min_location, 0.0, atol=20 * mat.tol)


def test_tube_wall(tube: Any) -> None:
    t = wall_thickness(tube)
    assert _close(t.min, 5.0, tube) and _close(t.max, 5.0, tube)
    assert math.hypot(t.min_location[0], t.min_location[1]) == pytest.approx(17.5, abs=1e-2)
    assert thickness_at(tube, (17.5, 0, 25)) == pytest.approx(5.0, abs=20 * tube.tol)


def test_l_bracket(l_bracket: Any) -> None:
    t = wall_thickness(l_bracket)
    assert _close(t.min, 5.0, l_bracket)
    # the largest ball sits in the inner corner, touching both outer faces and the
    # inner corner's vertex: r + r sqrt(2) = 5 sqrt(2)
    assert _close(t.max, 2 * 5 * math.sqrt(2) / (1 + math.sqrt(2)), l_bracket)
    _is_wall_point(l_bracket, t)


def test_cylinder_axis_counts() -> None:
    """The axis of a cylinder is a skeletal edge: its balls touch a whole circle."""
    mat = medial_axis(cq.Workplane().circle(10).extrude(30))
    t = wall_thickness(mat)
    assert _close(t.min, 20.0, mat) and _close(t.max, 20.0, mat)
    assert t.min_entity.startswith("skeletal")


def test_knife_edges_count_unless_min_angle_is_raised() -> None:
    """A triangle prism has 53 degree edges: walls tapering to nothing."""
    mat = medial_axis(cq.Workplane().polyline([(0, 0), (30, 0), (15, 20)]).close().extrude(10))
    assert wall_thickness(mat).min < 100 * mat.tol
    assert wall_thickness(mat, min_angle=150).min > 1.0


def test_thin_plate_fixture() -> None:
    (solid,) = read_step(SOLIDS / "thin_plate.step")
    mat = medial_axis(solid)
    t = wall_thickness(mat)
    assert _close(t.min, 2.0, mat) and _close(t.max, 2.0, mat)


def test_bad_angle(plate: Any) -> None:
    with pytest.raises(ValueError, match="min_angle"):
        wall_thickness(plate, min_angle=200)


def test_the_result_answers_the_everyday_question_itself(tube: Any) -> None:
    """``MedialAxis3D.thickness()`` / ``.thickness_at()`` are the module's functions."""
    t, want = tube.thickness(), wall_thickness(tube)
    assert (t.min, t.max, t.min_entity, t.max_entity) == (
        want.min,
        want.max,
        want.min_entity,
        want.max_entity,
    )
    np.testing.assert_array_equal(t.min_location, want.min_location)
    assert tube.thickness_at((17.5, 0.0, 25.0)) == thickness_at(tube, (17.5, 0.0, 25.0))


def test_the_result_writes_its_pictures(plate: Any, tmp_path: Path) -> None:
    plate.write_png(tmp_path / "p.png", dpi=40)
    plate.write_html(tmp_path / "p.html")
    assert (tmp_path / "p.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "medialViewer" in (tmp_path / "p.html").read_text()
