"""The 3D oracles themselves, validated on hand-built closed-form MATs (no medialcad involved).

Known complexes (THEORY.md Sec. 4) are built here with plain OCP, sharing vertices and edges the
way a sewn output would:

- the box ``[0,a]x[0,b]x[0,c]``, ``a > b > c``: 13 planar sheets (the mid sheet ``z = c/2``,
  4 + 4 cap trapezoids at 45 degrees, 4 vertical triangles at the vertical edges), 12 seams,
  4 junctions;
- the cylinder ``R, H > 2R``: the axis segment ``z in [R, H - R]`` and two cones to the rims.

The ellipsoid (a B-spline boundary) checks the oracle against its closed form without a built
complex: a planar elliptical sheet in ``z = 0``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_GTransform,
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeVertex,
    BRepBuilderAPI_MakeWire,
)
from OCP.BRepPrimAPI import (
    BRepPrimAPI_MakeBox,
    BRepPrimAPI_MakeCone,
    BRepPrimAPI_MakeCylinder,
    BRepPrimAPI_MakeSphere,
    BRepPrimAPI_MakeTorus,
)
from OCP.gp import gp_Ax2, gp_Dir, gp_GTrsf, gp_Mat, gp_Pnt
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Shape

from tests import oracles3d as O

A, B, C = 4.0, 3.0, 2.0  # the box, a > b > c
R, H = 10.0, 40.0  # the cylinder, H > 2R


def _compound(shapes: list[TopoDS_Shape]) -> TopoDS_Compound:
    comp = TopoDS_Compound()
    builder = BRep_Builder()
    builder.MakeCompound(comp)
    for s in shapes:
        builder.Add(comp, s)
    return comp


def _box_sheets(a: float, b: float, c: float) -> dict[str, TopoDS_Shape]:
    """The 13 sheets of the box's MAT as planar faces sharing edges and vertices."""
    h = c / 2
    pts = {f"C{i}{j}{k}": (i * a, j * b, k * c) for i in (0, 1) for j in (0, 1) for k in (0, 1)}
    pts |= {f"J{i}{j}": (h + i * (a - c), h + j * (b - c), h) for i in (0, 1) for j in (0, 1)}
    verts = {n: BRepBuilderAPI_MakeVertex(gp_Pnt(*p)).Vertex() for n, p in pts.items()}
    edges: dict[frozenset[str], TopoDS_Shape] = {}

    def face(*names: str) -> TopoDS_Shape:
        wire = BRepBuilderAPI_MakeWire()
        for p, q in zip(names, names[1:] + names[:1], strict=True):
            key = frozenset((p, q))
            if key not in edges:
                edges[key] = BRepBuilderAPI_MakeEdge(verts[p], verts[q]).Edge()
            wire.Add(TopoDS.Edge_s(edges[key]))
        return BRepBuilderAPI_MakeFace(wire.Wire(), True).Face()

    sheets = {"mid": face("J00", "J10", "J11", "J01")}
    for k, side in ((0, "bottom"), (1, "top")):
        sheets[f"{side}_y0"] = face(f"C00{k}", f"C10{k}", "J10", "J00")
        sheets[f"{side}_yb"] = face(f"C01{k}", f"C11{k}", "J11", "J01")
        sheets[f"{side}_x0"] = face(f"C00{k}", f"C01{k}", "J01", "J00")
        sheets[f"{side}_xa"] = face(f"C10{k}", f"C11{k}", "J11", "J10")
    for i in (0, 1):
        for j in (0, 1):
            sheets[f"vertical_{i}{j}"] = face(f"C{i}{j}0", f"C{i}{j}1", f"J{i}{j}")
    return sheets


def _cone_face(apex_z: float, up: bool) -> TopoDS_Shape:
    """The lateral face of the cone from the rim circle of radius ``R`` to an apex on the axis."""
    if up:  # rim at z = 0, apex above
        cone = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), R, 0.0, apex_z)
    else:  # apex at apex_z, rim R above it
        cone = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, apex_z), gp_Dir(0, 0, 1)), 0.0, R, R)
    ex = TopExp_Explorer(cone.Shape(), TopAbs_FACE)
    while ex.More():
        f = TopoDS.Face_s(ex.Current())
        e = TopExp_Explorer(f, TopAbs_EDGE)
        while e.More():
            if BRep_Tool.Degenerated_s(TopoDS.Edge_s(e.Current())):
                return f  # the lateral face carries the degenerated edge at the apex
            e.Next()
        ex.Next()
    raise AssertionError("no lateral face")


def _apex(face: TopoDS_Shape) -> TopoDS_Shape:
    """The vertex of the cone face's degenerated edge."""
    e = TopExp_Explorer(face, TopAbs_EDGE)
    while e.More():
        edge = TopoDS.Edge_s(e.Current())
        if BRep_Tool.Degenerated_s(edge):
            return TopExp.FirstVertex_s(edge)
        e.Next()
    raise AssertionError("no apex")


def _cylinder_parts() -> dict[str, TopoDS_Shape]:
    """The cylinder's MAT: two cones whose apexes are the ends of the axis segment."""
    lower, upper = _cone_face(R, up=True), _cone_face(H - R, up=False)
    axis = BRepBuilderAPI_MakeEdge(
        TopoDS.Vertex_s(_apex(lower)), TopoDS.Vertex_s(_apex(upper))
    ).Edge()
    return {"lower": lower, "upper": upper, "axis": axis}


@pytest.fixture(scope="module")
def box() -> O.SolidBoundary:
    return O.SolidBoundary(BRepPrimAPI_MakeBox(A, B, C).Solid())


@pytest.fixture(scope="module")
def cylinder() -> O.SolidBoundary:
    return O.SolidBoundary(BRepPrimAPI_MakeCylinder(R, H).Solid())


@pytest.fixture(scope="module")
def box_mat() -> dict[str, TopoDS_Shape]:
    return _box_sheets(A, B, C)


@pytest.fixture(scope="module")
def cylinder_mat() -> dict[str, TopoDS_Shape]:
    return _cylinder_parts()


@pytest.fixture(scope="module")
def ellipsoid() -> O.SolidBoundary:
    """The ellipsoid with semi-axes 3, 2, 1 (a sphere under an affine map: a B-spline face)."""
    g = gp_GTrsf()
    g.SetVectorialPart(gp_Mat(3, 0, 0, 0, 2, 0, 0, 0, 1))
    sphere = BRepPrimAPI_MakeSphere(1.0).Shape()
    return O.SolidBoundary(BRepBuilderAPI_GTransform(sphere, g, True).Shape())


def _box_distance(p: np.ndarray) -> np.ndarray:
    """Closed form of the distance to the box's boundary, for points inside."""
    x, y, z = p.T
    return np.min([x, A - x, y, B - y, z, C - z], axis=0)


# --------------------------------------------------------------------------- the boundary


def test_distances_and_inside_match_the_box(box: O.SolidBoundary) -> None:
    rng = np.random.default_rng(1)
    p = rng.uniform(0, 1, (50, 3)) * [A, B, C]
    assert np.abs(box.distances(p) - _box_distance(p)).max() < 1e-12 * box.diag
    # interior points are not at distance 0 (the boundary is the faces, not the solid)
    assert box.distances([[1.0, 1.0, 1.0]])[0] == pytest.approx(1.0)
    d, foot = box.nearest([3.5, 1.5, 1.0])
    assert d == pytest.approx(0.5) and foot == pytest.approx([4.0, 1.5, 1.0])
    # outside: the unsigned distance to the box
    assert box.distances([[5.0, 1.0, 1.0]])[0] == pytest.approx(1.0)
    inside = box.inside([[1, 1, 1], [4, 1, 1], [4 + 1e-3, 1, 1], [-1, -1, -1]])
    assert inside.tolist() == [True, True, False, False]  # the closed solid


def test_both_distance_methods_agree(
    box: O.SolidBoundary, cylinder: O.SolidBoundary, ellipsoid: O.SolidBoundary
) -> None:
    rng = np.random.default_rng(2)
    for sb in (box, cylinder, ellipsoid):
        dss = O.SolidBoundary(sb.solid, method="dss")
        b, _ = sb.boundary_samples(100)
        lo, hi = b.min(axis=0), b.max(axis=0)
        p = lo + rng.uniform(-0.1, 1.1, (15, 3)) * (hi - lo)
        assert np.abs(sb.distances(p) - dss.distances(p)).max() < 1e-12 * sb.diag
    with pytest.raises(ValueError, match="method"):
        O.SolidBoundary(box.solid, method="mesh")


def test_boundary_samples_lie_on_the_surface_with_inward_normals(
    box: O.SolidBoundary, cylinder: O.SolidBoundary
) -> None:
    for sb in (box, cylinder):
        b, n = sb.boundary_samples(300, seed=3)
        assert len(b) > 250
        assert sb.distances(b).max() < 1e-12 * sb.diag
        assert np.allclose(np.linalg.norm(n, axis=1), 1.0)
        delta = 1e-4 * sb.diag
        assert sb.inside(b + delta * n).all() and not sb.inside(b - delta * n).any()
    # exact normals on the cylinder's side: horizontal, towards the axis
    b, n = cylinder.boundary_samples(200)
    side = np.abs(np.hypot(b[:, 0], b[:, 1]) - R) < 1e-9
    assert np.allclose(n[side], -np.c_[b[side, :2] / R, 0 * b[side, 2]], atol=1e-12)
    # none near an edge (the normal is ill-defined there)
    z_gap = np.minimum(b[side, 2], H - b[side, 2])
    assert z_gap.min() > 0.5 * cylinder.edge_margin


def test_boundary_samples_are_uniform_by_area(box: O.SolidBoundary) -> None:
    b, _ = box.boundary_samples(6000, seed=5)
    # faces normal to x, y, z: two of each, areas B*C, A*C, A*B
    areas = np.array([B * C, A * C, A * B])
    for k, size in enumerate((A, B, C)):
        on = np.isclose(b[:, k], 0) | np.isclose(b[:, k], size)
        assert on.mean() == pytest.approx(areas[k] / areas.sum(), abs=0.02)


def test_convex_edges_and_euler_of_solids() -> None:
    import cadquery as cq

    assert len(O.SolidBoundary(BRepPrimAPI_MakeBox(A, B, C).Solid()).convex_edges) == 12
    # an L-shaped prism: one reflex vertical edge out of 18 edges
    l_prism = (
        cq.Workplane().polyline([(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]).close().extrude(1)
    )
    assert len(O.SolidBoundary(l_prism).convex_edges) == 17
    assert O.solid_euler(BRepPrimAPI_MakeBox(A, B, C).Solid()) == 1
    assert O.solid_euler(BRepPrimAPI_MakeCylinder(R, H).Solid()) == 1
    assert O.solid_euler(BRepPrimAPI_MakeTorus(5.0, 1.0).Solid()) == 0
    assert O.solid_euler(cq.Workplane().box(4, 4, 1).faces(">Z").workplane().hole(1)) == 0


# --------------------------------------------------------------------------- ray depth


@settings(max_examples=25, deadline=None)
@given(x=st.floats(0.01, A - 0.01), y=st.floats(0.01, B - 0.01), z=st.floats(0.01, C - 0.01))
def test_ray_depth_from_the_box_faces_is_the_closed_form(
    box: O.SolidBoundary, x: float, y: float, z: float
) -> None:
    tol = 1e-10 * box.diag
    # from the bottom face straight up: the ball grows until it meets the top or a side
    depth = O.ray_depth(box, [x, y, 0], [0, 0, 1])
    assert depth == pytest.approx(min(C / 2, x, A - x, y, B - y), abs=tol)
    # from the side x = 0 along +x
    depth = O.ray_depth(box, [0, y, z], [1, 0, 0])
    assert depth == pytest.approx(min(A / 2, y, B - y, z, C - z), abs=tol)


def test_ray_depth_special_rays(box: O.SolidBoundary, cylinder: O.SolidBoundary) -> None:
    # a ray leaving the solid does not enter it: depth 0
    assert O.ray_depth(box, [1.0, 1.0, 0.0], [0, 0, -1]) == 0.0
    # the cylinder's side: the lower cone, the axis, the upper cone
    for z in (3.0, 10.0, 20.0, 35.0):
        s = O.ray_depth(cylinder, [R, 0, z], [-1, 0, 0])
        assert s == pytest.approx(min(z, H - z, R), abs=1e-10 * cylinder.diag)
    # a ray that is not normal to a face: the ball crosses the face at once
    assert O.ray_depth(box, [1.0, 1.0, 0.0], [0, 0.6, 0.8]) < 1e-9 * box.diag


# --------------------------------------------------------------------------- soundness


def test_box_mat_is_sound(box: O.SolidBoundary, box_mat: dict[str, TopoDS_Shape]) -> None:
    pts = O.sample_compound(_compound(list(box_mat.values())), n_face=60, n_edge=8)
    err = O.soundness(box, pts)
    rims = np.isnan(err)
    assert np.nanmax(err) < 1e-9 * box.diag
    # the rim samples are the samples on the box's 12 edges and its 8 corners
    on_edge = (np.isclose(pts, 0, atol=1e-9) | np.isclose(pts, [A, B, C], atol=1e-9)).sum(
        axis=1
    ) >= 2
    assert rims.tolist() == on_edge.tolist() and rims.sum() == 12 * 8 + 8


def test_shifted_sheets_show_their_offset(
    box: O.SolidBoundary, box_mat: dict[str, TopoDS_Shape]
) -> None:
    delta = 0.01 * box.diag
    # the mid sheet lifted by delta: every ray from the top face overshoots by delta
    mid = O.sample_compound(box_mat["mid"], n_face=100, n_edge=0)
    err = O.soundness(box, mid + np.array([0.0, 0.0, delta]))
    assert err == pytest.approx(np.full(len(mid), delta), rel=1e-8)
    # a vertical triangle (plane x = y) moved by delta across itself: the ray from the face
    # y = 0 crosses the sheet at 45 degrees, the error is sqrt(2) delta
    tri = O.sample_compound(box_mat["vertical_00"], n_face=200, n_edge=0)
    off = tri + delta * np.array([1.0, -1.0, 0.0]) / math.sqrt(2)
    x, z = off[:, 0], off[:, 2]
    clear = (np.minimum(z, C - z) > x + 1e-9) & (off[:, 1] > 1e-3)
    assert clear.sum() > 20
    err = O.soundness(box, off[clear])
    assert err == pytest.approx(np.full(clear.sum(), math.sqrt(2) * delta), rel=1e-8)


def test_refined_soundness_is_the_distance_to_the_mat(
    box: O.SolidBoundary, box_mat: dict[str, TopoDS_Shape]
) -> None:
    # the two shifted sheets above, re-measured where the ray error exceeds a threshold:
    # the distance to the true medial points with feet near the sample's (the mid sheet's
    # delta again; delta, not sqrt(2) delta, across the tilted triangle)
    delta = 0.01 * box.diag
    mid = O.sample_compound(box_mat["mid"], n_face=30, n_edge=0)
    x, y = mid[:, 0], mid[:, 1]
    inner = (np.minimum(x, A - x) > C / 2 + 2 * delta) & (np.minimum(y, B - y) > C / 2 + 2 * delta)
    assert inner.sum() >= 5
    err = O.soundness(box, mid[inner][:5] + np.array([0.0, 0.0, delta]), refine_above=0.1 * delta)
    assert err == pytest.approx(np.full(5, delta), rel=1e-6)
    tri = O.sample_compound(box_mat["vertical_00"], n_face=200, n_edge=0)
    off = tri + delta * np.array([1.0, -1.0, 0.0]) / math.sqrt(2)
    x, z = off[:, 0], off[:, 2]
    clear = (np.minimum(z, C - z) > x + 4 * delta) & (off[:, 1] > 4 * delta) & (x > 4 * delta)
    assert clear.sum() >= 5
    raw = O.soundness(box, off[clear][:5])
    err = O.soundness(box, off[clear][:5], refine_above=0.1 * delta)
    assert raw == pytest.approx(np.full(5, math.sqrt(2) * delta), rel=1e-8)
    assert err == pytest.approx(np.full(5, delta), rel=1e-6)
    # and a sample on the MAT stays at zero
    assert O.soundness(box, mid[inner][:3], refine_above=0.0).max() <= 1e-9 * box.diag


def test_special_samples(box: O.SolidBoundary) -> None:
    pts = [
        [A + 0.1, 1.0, 1.0],  # outside: a failure
        [A, B, 0.5 * C],  # on a convex edge: a rim sample, skipped
        [A, B, C],  # a corner: a rim sample
        [2.0, 1.5, 0.0],  # in the middle of a face: not medial, 1.5 from the nearest edge
        [2.0, 1.5, 0.3],  # inside, off the MAT: s* = c/2 on the ray from the bottom
    ]
    err = O.soundness(box, pts)
    assert np.isinf(err[0]) and np.isnan(err[1]) and np.isnan(err[2])
    assert err[3] == pytest.approx(1.5)
    assert err[4] == pytest.approx(C / 2 - 0.3, abs=1e-10 * box.diag)


def test_cylinder_mat_is_sound(
    cylinder: O.SolidBoundary, cylinder_mat: dict[str, TopoDS_Shape]
) -> None:
    pts = O.sample_compound(_compound(list(cylinder_mat.values())), n_face=150, n_edge=30)
    err = O.soundness(cylinder, pts)
    assert np.nanmax(err) < 1e-9 * cylinder.diag
    rho = np.hypot(pts[:, 0], pts[:, 1])
    assert np.isnan(err).tolist() == (np.abs(rho - R) < 1e-9).tolist()  # the rim circles
    # an axis beyond the cone apex is not medial: there the ball is stopped by the disk
    z = np.array([2.0, 5.0, 8.0])
    err = O.soundness(cylinder, np.c_[0 * z, 0 * z, z])
    assert err == pytest.approx(R - z, abs=1e-9 * cylinder.diag)


def test_ellipsoid_sheet_closed_form(ellipsoid: O.SolidBoundary) -> None:
    """Semi-axes 3 > 2 > 1: the MAT is the region of z = 0 inside the ellipse with semi-axes
    (9 - 1)/3 and (4 - 1)/2; its edge is made of curvature centres (second-order contact)."""
    ax, ay = 8 / 3, 3 / 2
    tol = 1e-9 * ellipsoid.diag
    _, m, r = O.medial_points(ellipsoid, 40, seed=1)
    assert np.abs(m[:, 2]).max() < tol
    assert ((m[:, 0] / ax) ** 2 + (m[:, 1] / ay) ** 2).max() <= 1 + 1e-9
    assert O.radius_error(ellipsoid, m, r).max() < tol
    t = np.linspace(0, 2 * np.pi, 7, endpoint=False)
    sheet = np.vstack([np.c_[k * ax * np.cos(t), k * ay * np.sin(t), 0 * t] for k in (0.3, 0.99)])
    assert O.soundness(ellipsoid, sheet).max() < tol
    # beyond the sheet's edge on the axes: the ray from the vertex stops at the curvature
    # centre, 1/3 from (3, 0, 0) and 1/2 from (0, 2, 0)
    err = O.soundness(ellipsoid, [[2.8, 0, 0], [0, 1.6, 0], [8 / 3, 0, 0]])
    assert err == pytest.approx([1 / 3 - 0.2, 1 / 2 - 0.4, 0.0], abs=tol)


def test_radius_error(box: O.SolidBoundary) -> None:
    p = np.array([[2.0, 1.5, 1.0], [0.5, 0.5, 0.3]])
    assert O.radius_error(box, p, [1.0, 0.3]).max() < 1e-12
    assert O.radius_error(box, p, [1.1, 0.3]) == pytest.approx([0.1, 0.0], abs=1e-12)


# --------------------------------------------------------------------------- completeness


def test_box_mat_is_complete_and_a_missing_sheet_is_found(
    box: O.SolidBoundary, box_mat: dict[str, TopoDS_Shape]
) -> None:
    err = O.completeness(box, _compound(list(box_mat.values())), 150)
    assert len(err) > 120 and err.max() < 1e-9 * box.diag
    # without the mid sheet the rays from the top and bottom centres find nothing near
    partial = [s for name, s in box_mat.items() if name != "mid"]
    err = O.completeness(box, _compound(partial), 150)
    assert err.max() > 0.2
    # dense points of the output instead of the shapes: the sampling gap shows, no more
    dense = O.sample_compound(_compound(list(box_mat.values())), n_face=400, n_edge=40)
    assert O.completeness(box, dense, 150).max() < 0.2


def test_cylinder_mat_is_complete_and_a_missing_cone_is_found(
    cylinder: O.SolidBoundary, cylinder_mat: dict[str, TopoDS_Shape]
) -> None:
    b, m, r = O.medial_points(cylinder, 150)
    # closed form: the medial point of a side point at height z is at radius R - min(z, H-z, R)
    side = np.abs(np.hypot(b[:, 0], b[:, 1]) - R) < 1e-9
    expect = R - np.minimum(np.minimum(b[side, 2], H - b[side, 2]), R)
    assert np.hypot(m[side, 0], m[side, 1]) == pytest.approx(expect, abs=1e-9 * cylinder.diag)
    assert O.radius_error(cylinder, m, r).max() < 1e-9 * cylinder.diag

    err = O.completeness(cylinder, _compound(list(cylinder_mat.values())), 150)
    assert err.max() < 1e-9 * cylinder.diag
    partial = _compound([cylinder_mat["lower"], cylinder_mat["axis"]])
    err = O.completeness(cylinder, partial, 150)
    assert err.max() > 0.3 * R
    # the errors are where the upper cone was: medial points above z = H - R
    assert (err[m[:, 2] < H - R - 1e-6] < 1e-9 * cylinder.diag).all()


# --------------------------------------------------------------------------- topology


def test_topology_of_the_known_complexes(
    box_mat: dict[str, TopoDS_Shape], cylinder_mat: dict[str, TopoDS_Shape]
) -> None:
    # the MAT is homotopy-equivalent to the solid: connected, chi = 1 for box and cylinder
    assert O.topology(_compound(list(box_mat.values()))) == (1, 1)  # 12 - 24 + 13
    assert O.topology(_compound(list(cylinder_mat.values()))) == (1, 1)  # 4 - 5 + 2
    # without the axis segment the cones fall apart
    assert O.topology(_compound([cylinder_mat["lower"], cylinder_mat["upper"]])) == (2, 2)
    # without the mid sheet the box's MAT has a hole: chi = 12 - 24 + 12
    partial = [s for name, s in box_mat.items() if name != "mid"]
    assert O.topology(_compound(partial)) == (1, 0)
    # sheets that only look adjacent (equal points, distinct vertices) are not connected
    twins = _box_sheets(A, B, C)
    assert O.topology(_compound([box_mat["mid"], twins["bottom_y0"]]))[0] == 2
    # a lone vertex and a lone edge
    v = BRepBuilderAPI_MakeVertex(gp_Pnt(0, 0, 0)).Vertex()
    assert O.topology(_compound([v])) == (1, 1)
    e = BRepBuilderAPI_MakeEdge(gp_Pnt(1, 0, 0), gp_Pnt(2, 0, 0)).Edge()
    assert O.topology(_compound([v, e])) == (2, 2)


def test_sample_compound_stays_on_the_shapes(cylinder_mat: dict[str, TopoDS_Shape]) -> None:
    cone = O.sample_compound(cylinder_mat["lower"], n_face=100, n_edge=10)
    z, rho = cone[:, 2], np.hypot(cone[:, 0], cone[:, 1])
    assert len(cone) > 80
    assert np.abs(rho - (R - z)).max() < 1e-12 and z.min() >= 0 and z.max() <= R + 1e-12
    axis = O.sample_compound(cylinder_mat["axis"], n_face=0, n_edge=10)
    assert len(axis) == 12 and np.abs(axis[:, :2]).max() == 0
    assert sorted(axis[:, 2])[:3] == pytest.approx([R, R + 1.0, R + 3.0])


def test_wrappers() -> None:
    import build123d as bd
    import cadquery as cq

    for solid in (cq.Workplane().box(4, 3, 2), bd.Box(4, 3, 2)):
        sb = O.SolidBoundary(solid)
        assert sb.diag == pytest.approx(math.sqrt(29))
        assert sb.distances([[0.0, 0.0, 0.0]])[0] == pytest.approx(1.0)  # centred boxes
    with pytest.raises(ValueError, match="one solid"):
        O.SolidBoundary(cq.Workplane().box(1, 1, 1).faces(">Z").val())


def test_medial_depths_of_an_extruded_blob_are_its_profiles() -> None:
    """A prism of a B-spline blob with a sharp tip (r 0.015, kept exactly from a random
    run): a wall point's medial depth in 3D is the 2D one of the profile (the cap face,
    judged by the 2D oracle) wherever the caps are farther. BRepExtrema missed the tip's
    other flank, 0.0024 nearer than the first flank's foot, and the nearest nodes all
    projected back onto the first flank: the medial point came out 20 tol too deep, and
    a correct MAT read as incomplete. Projections from nodes a distance apart fix it."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane

    from tests import faces as F
    from tests import oracles as O2

    solid = F.read_exact("blob_extrusion_seed5663.bbrep")
    sb = O.SolidBoundary(solid)
    cap = next(f for f in sb.faces if BRepAdaptor_Surface(f).GetType() == GeomAbs_Plane)
    plane = BRepAdaptor_Surface(cap).Plane()
    origin = np.array(plane.Location().Coord())
    normal = np.array(plane.Axis().Direction().Coord())
    fb = O2.FaceBoundary(cap)
    _, m, s = O.medial_points(sb, 60, seed=5663)
    height = (m - origin) @ normal
    other_cap = float(np.abs((sb._mesh_nodes - origin) @ normal).max())
    away = np.minimum(np.abs(height), np.abs(other_cap - np.abs(height))) > 1.5 * s
    assert away.sum() >= 20
    for mi, hi, si in zip(m[away], height[away], s[away], strict=True):
        d2, _ = fb.nearest(mi - hi * normal)
        assert abs(si - d2) <= 1e-9 * sb.diag, (si, d2)


def test_the_complex_distance_finds_a_heavy_sheet_everywhere() -> None:
    """A sheet with over 20,000 poles (as a 250-degree slice of an ellipse had before
    revolved sheets became exact arcs) is too heavy to keep ``BRepExtrema_ExtPF``
    initialised, and the local projection from the nearest of its 100 samples stopped
    0.52 units (1e-2 diag) off the sheet for medial points lying on it to 1e-10: a false
    "incomplete". Points on such a sheet (here a torus-like patch interpolated by OCC on
    a 200 x 110 grid) are found on it within 1e-9 away from its boundary, and a point off
    it by a known amount is measured so."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.GeomAPI import GeomAPI_PointsToBSplineSurface
    from OCP.TColgp import TColgp_Array2OfPnt

    from tests import _mat3d as M

    big, a, b = 13.26, 2.0, 0.9

    def on(t: float, phi: float) -> np.ndarray:
        rho = big + a * math.cos(t)
        return np.array([rho * math.cos(phi), b * math.sin(t), -rho * math.sin(phi)])

    ts, phis = np.linspace(0.2, 2.9, 200), np.linspace(0.0, math.radians(250.0), 110)
    grid = TColgp_Array2OfPnt(1, len(ts), 1, len(phis))
    for i, t in enumerate(ts):
        for j, phi in enumerate(phis):
            grid.SetValue(i + 1, j + 1, gp_Pnt(*on(float(t), float(phi))))
    fit = GeomAPI_PointsToBSplineSurface()
    fit.Interpolate(grid)
    surf = fit.Surface()
    face = BRepBuilderAPI_MakeFace(surf, 1e-7).Face()
    assert M.poles(face) > M.HEAVY
    rng = np.random.default_rng(0)
    u0, u1, v0, v1 = surf.Bounds()
    points = []
    # (inside its parameter range by 5 %: next to its boundary the local projection stops
    # off the sheet and BRepExtrema_DistShapeShape reads up to 3e-4 for a point on it)
    du, dv = 0.05 * (u1 - u0), 0.05 * (v1 - v0)
    us, vs = rng.uniform(u0 + du, u1 - du, 60), rng.uniform(v0 + dv, v1 - dv, 60)
    for u, v in zip(us, vs, strict=True):
        p = gp_Pnt()
        surf.D0(float(u), float(v), p)
        points.append([p.X(), p.Y(), p.Z()])
    cd = M.ComplexDistance(face)
    d = cd.distances(np.array(points), 1e-9)
    assert float(d.max()) <= 1e-9
    # 0.3 above the patch's top (t = pi/2) in its middle meridian plane: 0.3 away
    p_top = on(math.pi / 2, math.radians(125.0))
    got = cd.distance(p_top + np.array([0.0, 0.3, 0.0]))
    assert got == pytest.approx(0.3, abs=1e-6)
