"""The oracles themselves, validated on closed-form medial axes (no medialcad involved)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
from OCP.gp import gp_Pnt
from OCP.TopoDS import TopoDS_Compound

from tests import faces as F
from tests import oracles as O

PLACEMENTS = [pytest.param(F.IDENTITY, id="xy"), pytest.param(F.TILTED_FAR, id="tilted_far")]


def _segments_compound(segments: list[tuple[np.ndarray, np.ndarray]]) -> TopoDS_Compound:
    comp = TopoDS_Compound()
    builder = BRep_Builder()
    builder.MakeCompound(comp)
    for a, b in segments:
        builder.Add(comp, BRepBuilderAPI_MakeEdge(gp_Pnt(*a), gp_Pnt(*b)).Edge())
    return comp


def _rectangle_axis(a: float, b: float, pl: F.Placement) -> list[tuple[np.ndarray, np.ndarray]]:
    bp = [np.array([a - b, 0.0]), np.array([-(a - b), 0.0])]
    segs = [(bp[0], bp[1])]
    for sx in (1, -1):
        for sy in (1, -1):
            segs.append((bp[0 if sx > 0 else 1], np.array([sx * a, sy * b])))
    return [(pl.to_model(p), pl.to_model(q)) for p, q in segs]


@pytest.mark.parametrize("pl", PLACEMENTS)
def test_rectangle_soundness_on_and_off_axis(pl: F.Placement) -> None:
    a, b = 2.0, 1.0
    fb = O.FaceBoundary(F.place(F.rectangle(a, b), pl))
    tol = 1e-5 * fb.diag
    xs = np.linspace(-(a - b), a - b, 41)
    t = np.linspace(0.05, 1.0, 20)
    on = np.vstack(
        [np.c_[xs, 0 * xs], np.c_[(a - b) + b * t, b * t], np.c_[-(a - b) - b * t, -b * t]]
    )
    err = O.soundness_2d(fb, pl.to_model(on), tol)
    assert err.max() < 1e-9 * fb.diag
    for delta in (1e-3, 3e-2):
        off = pl.to_model(np.c_[xs * 0.9, 0 * xs + delta])
        err = O.soundness_2d(fb, off, tol)
        assert np.all(err > 0.5 * delta) and np.all(err < 1.5 * delta)


@pytest.mark.parametrize("pl", PLACEMENTS)
@pytest.mark.parametrize("turn", [5.8e-6, 1e-3])
@pytest.mark.parametrize("rf", [0.0, 0.2])
def test_soundness_on_the_spoke_of_a_nearly_flat_corner(
    pl: F.Placement, turn: float, rf: float
) -> None:
    """The spoke of a convex corner turning by ``turn`` (sharp, or rounded by a tiny
    fillet of radius ``rf``: the spoke then starts at its centre) is the corner's
    bisector. Along it the distances to the two sides differ by ``(1 - cos turn) s``:
    below rounding far from the origin at 5.8e-6 (a fresh random star read 64 tol
    unsound on its exact spoke, a revolved tiny fillet 6.6 tol). On the spoke the error
    is below half the tolerance, a step of ``delta`` off it reads ``delta``."""
    v = np.array([0.0, 1.0])
    d0 = np.array([math.cos(turn / 2), -math.sin(turn / 2)])  # from v along the right side
    d1 = np.array([-math.cos(turn / 2), -math.sin(turn / 2)])
    outline = [v, v + 1.2 * d0, np.array([0.4, -1.0]), np.array([-0.5, -1.0]), v + 1.1 * d1]
    face = F.filleted_polygon(outline, [rf, 0, 0, 0, 0]) if rf else F.polygon(outline)
    fb = O.FaceBoundary(F.place(face, pl))
    tol = 1e-5 * fb.diag
    s = np.linspace(max(0.02, 1.1 * rf), 0.4, 15)  # the bisector points straight down from v
    on = np.c_[0 * s, 1.0 - s]
    assert O.soundness_2d(fb, pl.to_model(on), tol).max() < 0.5 * tol
    for delta in (3 * tol, 30 * tol):
        err = O.soundness_2d(fb, pl.to_model(on + np.array([delta, 0.0])), tol)
        assert np.all(err > 0.5 * delta) and np.all(err < 1.5 * delta)


@pytest.mark.parametrize("pl", PLACEMENTS)
def test_soundness_special_points(pl: F.Placement) -> None:
    fb = O.FaceBoundary(F.place(F.rectangle(2.0, 1.0), pl))
    tol = 1e-5 * fb.diag
    pts = pl.to_model(np.array([[2.0, 1.0], [-2.0, -1.0], [0.5, 1.0], [3.0, 0.0]]))
    above = pl.to_model(np.array([[0.0, 0.0, 0.01]]))
    err = O.soundness_2d(fb, np.vstack([pts, above]), tol)
    assert err[0] == 0 and err[1] == 0  # convex corners: r = 0 end points
    assert err[2] > 1.0  # mid-edge boundary point: far from any convex corner
    assert np.isinf(err[3]) and np.isinf(err[4])  # outside, off the plane


@pytest.mark.parametrize("pl", PLACEMENTS)
def test_ellipse_soundness_closed_form(pl: F.Placement) -> None:
    a, b = 3.0, 1.0
    c = (a * a - b * b) / a
    fb = O.FaceBoundary(F.place(F.ellipse(a, b), pl))
    tol = 1e-8 * fb.diag
    xs = np.concatenate([np.linspace(-c, c, 41), [c - 1e-6, c - 1e-3, -c + 1e-4]])
    err = O.soundness_2d(fb, pl.to_model(np.c_[xs, 0 * xs]), tol)
    assert err.max() < 0.5 * tol
    # beyond the curvature-centre end point on the axis: the error is the overshoot
    err = O.soundness_2d(fb, pl.to_model(np.array([[c + 0.01, 0.0]])), tol)
    assert err[0] == pytest.approx(0.01, rel=1e-3)
    # the curvature centre itself, from the vertex
    q, u = (
        pl.to_model(np.array([[a, 0.0]]))[0],
        pl.to_model(np.array([[-1.0, 0.0]]))[0] - pl.translation,
    )
    assert fb.medial_depth(q, u) == pytest.approx(b * b / a, abs=1e-8 * fb.diag)


@pytest.mark.parametrize("pl", PLACEMENTS)
def test_medial_points_closed_forms(pl: F.Placement) -> None:
    # annulus: the mid circle
    ri, ro = 1.0, 2.0
    fb = O.FaceBoundary(F.place(F.annulus(ri, ro), pl))
    _, m, r = O.medial_points_2d(fb, 100)
    loc = pl.to_local(m)
    assert np.abs(np.hypot(loc[:, 0], loc[:, 1]) - (ri + ro) / 2).max() < 1e-9
    assert np.abs(r - (ro - ri) / 2).max() < 1e-9 and np.abs(loc[:, 2]).max() < 1e-9
    # ellipse: the segment |x| <= c with r(x) = b sqrt(1 - x^2/(a^2 - b^2))
    a, b = 3.0, 1.0
    fb = O.FaceBoundary(F.place(F.ellipse(a, b), pl))
    _, m, r = O.medial_points_2d(fb, 200)
    loc = pl.to_local(m)
    assert np.abs(loc[:, 1]).max() < 1e-9 and np.abs(loc[:, 0]).max() <= (a * a - b * b) / a + 1e-9
    assert (
        np.abs(r - b * np.sqrt(np.clip(1 - loc[:, 0] ** 2 / (a * a - b * b), 0, None))).max() < 1e-8
    )
    # L-shape: medial points with x < 1, y < 1 beyond the corner diagonal are on the parabola
    # equidistant from the reflex vertex (1, 1) and the opposite edge (y = 0 or x = 0)
    fb = O.FaceBoundary(F.place(F.l_shape(2.0, 1.0), pl))
    _, m, r = O.medial_points_2d(fb, 400)
    loc = pl.to_local(m)
    sel = (
        (loc[:, 0] < 1) & (loc[:, 1] < 1) & (loc[:, 0] + loc[:, 1] > 2 * (2 - math.sqrt(2)) + 1e-6)
    )
    assert sel.sum() > 10
    p = loc[sel]
    to_vertex = np.hypot(p[:, 0] - 1, p[:, 1] - 1)
    to_edge = np.minimum(p[:, 0], p[:, 1])
    assert np.abs(to_vertex - to_edge).max() < 1e-9
    assert np.abs(r[sel] - to_edge).max() < 1e-9


@pytest.mark.parametrize("pl", PLACEMENTS)
def test_completeness_and_radius_rectangle(pl: F.Placement) -> None:
    a, b = 2.0, 1.0
    face = F.place(F.rectangle(a, b), pl)
    fb = O.FaceBoundary(face)
    segs = _rectangle_axis(a, b, pl)
    err = O.completeness_2d(fb, _segments_compound(segs), 200)
    assert np.nanmax(err) < 1e-9 * fb.diag
    assert np.isnan(err).sum() == 0  # parameter midpoints never sit on a corner
    # a missing diagonal is detected
    err = O.completeness_2d(fb, _segments_compound(segs[:-1]), 200)
    assert np.nanmax(err) > 0.1
    # points instead of a compound: the sampling gap shows
    dense = np.vstack([p + np.linspace(0, 1, 2001)[:, None] * (q - p) for p, q in segs])
    err = O.completeness_2d(fb, dense, 200)
    assert np.nanmax(err) < 2e-3
    # radius oracle
    t = np.linspace(0, 1, 11)
    pts = pl.to_model(np.c_[(a - b) + b * t, b * t])
    assert O.radius_error_2d(fb, pts, b * (1 - t)).max() < 1e-12 * 1e4
    assert O.radius_error_2d(fb, pts, b * (1 - t) + 0.1).min() == pytest.approx(0.1)


def test_wrappers_and_bbox() -> None:
    import build123d as bd
    import cadquery as cq

    wp = cq.Workplane().rect(4, 2).extrude(1).faces(">Z")
    assert O.bbox_diagonal(wp) == pytest.approx(math.hypot(4, 2))
    assert O.bbox_diagonal(bd.Rectangle(4, 2).face()) == pytest.approx(math.hypot(4, 2))
    fb = O.FaceBoundary(bd.Rectangle(4, 2).face())
    assert O.soundness_2d(fb, [[0.5, 0.0, 0.0]], 1e-5)[0] < 1e-9


def test_oracle_is_self_consistent_on_a_blob() -> None:
    face = F.place(F.bspline_blob([1.0, 0.6, 0.9, 0.5, 0.8, 0.7, 0.95]), F.TILTED_FAR)
    fb = O.FaceBoundary(face)
    _, m, r = O.medial_points_2d(fb, 300)
    err = O.soundness_2d(fb, m, 1e-5 * fb.diag)
    rad = O.radius_error_2d(fb, m, r)
    # the oracle agrees with itself: its own medial points are sound (no timing here:
    # speed is measured in bench/, never asserted in unit tests)
    assert err.max() < 1e-9 * fb.diag and rad.max() < 1e-9 * fb.diag


@pytest.mark.parametrize("seam", [0.9554, 4.27283, 1.2])
def test_curvature_ends_do_not_depend_on_where_a_closed_curve_has_its_seam(seam: float) -> None:
    """A closed B-spline's seam is a point like any other: with the seam moved onto a
    curvature maximum (4.27283, the weak one; 0.9554, just before one) or between them,
    the oracle lists the same empty osculating disks' centres as before (it looked only
    inside the parameter range, and a maximum on the seam went unchecked)."""
    from OCP.TopoDS import TopoDS

    face = TopoDS.Face_s(F.read_exact("blob_weak_curvature_maximum.bbrep"))
    before = O.FaceBoundary(face).curvature_ends(1e-8)
    after = O.FaceBoundary(F.with_seam_at(face, seam)).curvature_ends(1e-8)
    assert len(before) == len(after) == 6
    gap = np.linalg.norm(before[:, None, :] - after[None, :, :], axis=2)
    assert gap.min(axis=1).max() < 1e-6 and gap.min(axis=0).max() < 1e-6


def test_soundness_across_a_branch_of_a_nearly_circular_outline() -> None:
    """Near the centre of a nearly circular outline (20 spline pieces) the branches run
    nearly parallel to their spokes, and the ray depth magnifies an offset across them
    several times over (half a tolerance read 1.8 tol): the bisector of the two feet on
    the same edge resolves it. True medial points read below half the tolerance, a step
    of half a tolerance across the spoke reads about that."""
    fb = O.FaceBoundary(F.near_circle_pieces(20, 1e-4, 3))
    tol = 1e-5 * fb.diag
    b, m, _ = O.medial_points_2d(fb, 40)
    u = (b - m) / np.linalg.norm(b - m, axis=1)[:, None]
    across = np.c_[-u[:, 1], u[:, 0], 0 * u[:, 0]]
    assert O.soundness_2d(fb, m, tol).max() < 0.5 * tol
    delta = 0.5 * tol
    err = O.soundness_2d(fb, m + delta * across, tol)
    assert np.all(err > 0.5 * delta) and np.all(err < 1.5 * delta)


@pytest.mark.parametrize("pl", PLACEMENTS)
def test_soundness_across_the_axis_next_to_an_ellipses_curvature_centre(
    pl: F.Placement,
) -> None:
    """On a nearly circular ellipse the two feet of an axis point lie either side of the
    vertex, the disks nearly osculate round it and the spokes nearly parallel the axis.
    A step across the axis reads its true size (the distance to the axis), neither
    magnified by the ray depth nor hidden by the bisector refinement (which now pairs
    feet on one edge as close as ``100 eta``, seeded within a sample cell of the own)."""
    a, b = 1.01, 1.0  # nearly a circle: the disks nearly osculate round the vertex
    c = (a * a - b * b) / a
    fb = O.FaceBoundary(F.place(F.ellipse(a, b), pl))
    tol = 1e-5 * fb.diag
    xs = c * np.array([0.0, 0.5, 0.9, 0.99])
    for delta in (0.5 * tol, 3.0 * tol):
        err = O.soundness_2d(fb, pl.to_model(np.c_[xs, delta + 0 * xs]), tol)
        assert np.all(err > 0.7 * delta) and np.all(err < 1.3 * delta), err / delta
