"""Solids written the way other CAD systems write them, as specifications.

The same solid reaches us in several B-rep dialects:

* **NURBS only** (Rhino and many translators): every face a B-spline surface, every edge
  a B-spline curve, planes and circles included (``BRepBuilderAPI_NurbsConvert``). A flat
  B-spline face is still a plane to recognition, and a revolution's meridian is read
  exactly off its rational B-spline surfaces.
* **Periodic faces split** (``ShapeUpgrade_ShapeDivideClosed``, as systems that do not
  keep closed faces write cylinders, cones and tori in halves).
* **Every face split** in a 3 x 3 grid (``ShapeUpgrade_ShapeDivideArea``): split caps are
  merged into one profile face; its edges stay split (more, smaller sheets).
* The NURBS copy **through a STEP file**.

Each must be read as the same extrusion or revolution (same length, angle and volume) and
its MAT must pass the independent oracles of :mod:`tests.oracles3d` (soundness, radius,
completeness, topology, ``BRepCheck``).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import cadquery as cq
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_NurbsConvert
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.Geom import Geom_BSplineSurface
from OCP.GProp import GProp_GProps
from OCP.ShapeAnalysis import ShapeAnalysis_ShapeTolerance
from OCP.ShapeUpgrade import ShapeUpgrade_ShapeDivideArea, ShapeUpgrade_ShapeDivideClosed
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Shape

import medialcad
from medialcad.occ.shapes import faces
from medialcad.recognition import Extrusion, Revolution
from tests import _mat3d as M
from tests import faces as F
from tests import oracles as O
from tests.test_mat3d_extrusion import HYPO3
from tests.test_mat3d_revolution import revolve

SOLIDS = Path(__file__).resolve().parents[1] / "fixtures" / "step" / "solids"


def nurbs(shape: TopoDS_Shape) -> TopoDS_Shape:
    """Every face and edge as a B-spline."""
    conv = BRepBuilderAPI_NurbsConvert(shape, True)
    out = M.single_solid(conv.Shape())
    assert all(isinstance(BRep_Tool.Surface_s(f), Geom_BSplineSurface) for f in faces(out))
    return out


def split_closed(shape: TopoDS_Shape) -> TopoDS_Shape:
    """Every closed (periodic) face cut in two (a solid without one comes back as is)."""
    div = ShapeUpgrade_ShapeDivideClosed(shape)
    div.SetNbSplitPoints(1)
    div.Perform()
    return M.single_solid(div.Result())


def split_faces(shape: TopoDS_Shape) -> TopoDS_Shape:
    """Every face cut in a 3 x 3 grid of faces (caps and sides alike), edges too."""
    div = ShapeUpgrade_ShapeDivideArea(shape)
    div.SetSplittingByNumber(True)
    div.SetNumbersUVSplits(3, 3)
    div.Perform()
    return M.single_solid(div.Result())


def nurbs_through_step(shape: TopoDS_Shape, tmp: Path) -> TopoDS_Shape:
    path = tmp / "nurbs.step"
    cq.exporters.export(cq.Shape.cast(nurbs(shape)), str(path))
    (solid,) = medialcad.read_step(path)
    return solid


def _revolve(points: list[tuple[float, float]], angle: float, x_axis: float = 0.0) -> Any:
    wp = cq.Workplane("XZ").polyline(points).close()
    return wp.revolve(angle, (x_axis, 0, 0), (x_axis, 1, 0)).val().wrapped


def _blob_ring() -> Any:
    """A B-spline blob revolved a full turn about an axis clear of it."""

    blob = F.bspline_blob([0.6274, 0.7225, 0.7523, 0.7767, 0.9978, 0.8963, 0.8111, 0.9945])
    return revolve(F.place(blob, F.Placement(np.eye(3), np.array([1.5, 0.0, 0.0]))))


SHAPES: dict[str, Callable[[], TopoDS_Shape]] = {
    "box": lambda: cq.Workplane().box(10, 6, 3).val().wrapped,
    "slot": lambda: cq.Workplane().slot2D(10, 3).extrude(2).val().wrapped,
    "tube": lambda: cq.Workplane().circle(5).circle(3).extrude(4).val().wrapped,
    "spline_plate": lambda: (
        cq.Workplane()
        .spline([(0, 0), (4, 1), (5, 4), (1, 5), (-1, 2)], periodic=True)
        .close()
        .extrude(1.5)
        .val()
        .wrapped
    ),
    "cone": lambda: _revolve([(0, 0), (4, 0), (1, 5), (0, 5)], 360),
    "torus": lambda: cq.Solid.makeTorus(5, 1).wrapped,
    "trapezoid_ring": lambda: _revolve([(3, 0), (6, 0), (5, 2), (3.5, 3)], 360),
    "cone_pie_slice": lambda: _revolve([(0, 0), (4, 0), (1, 5), (0, 5)], 120),
    "blob_ring": lambda: _blob_ring(),
    "stepped_shaft": lambda: _revolve([(0, 0), (3, 0), (3, 2), (2, 2), (2, 5), (0, 5)], 360),
}
KIND = {
    "box": Extrusion,
    "slot": Extrusion,
    "tube": Extrusion,
    "spline_plate": Extrusion,
    "cone": Revolution,
    "torus": Revolution,
    "trapezoid_ring": Revolution,
    "cone_pie_slice": Revolution,
    "blob_ring": Revolution,
    "stepped_shaft": Revolution,
}
DIALECTS = {"nurbs": nurbs, "split_closed": split_closed, "split_faces": split_faces}


def _same_reading(a: Any, b: Any) -> None:
    assert type(a) is type(b)
    if isinstance(a, Extrusion):
        assert b.length == pytest.approx(a.length, rel=1e-7)
        assert abs(float(np.dot(a.direction, b.direction))) == pytest.approx(1.0, abs=1e-9)
    else:
        assert b.angle == pytest.approx(a.angle, abs=1e-7)
        assert abs(float(np.dot(a.axis_direction, b.axis_direction))) == pytest.approx(1.0)
        assert b.touches_axis == a.touches_axis
    assert _area(b.profile) == pytest.approx(_area(a.profile), rel=1e-6)


def _area(face: Any) -> float:
    props = GProp_GProps()  # (adaptive, to 1e-9: the default is 1e-3 off on B-spline faces)
    BRepGProp.SurfaceProperties_s(face, props, 1e-9)
    return float(props.Mass())


def _check(solid: TopoDS_Shape, label: str) -> Any:
    return M.passes(solid, label, n_complete=60)


@pytest.mark.parametrize("dialect", sorted(DIALECTS))
@pytest.mark.parametrize("name", sorted(SHAPES))
def test_a_solid_in_another_dialect_is_read_alike_and_its_mat_passes_the_oracles(
    name: str, dialect: str
) -> None:
    skip = {
        ("torus", "split_closed"): "the ray-depth oracle's nearest point fails on the focal "
        "circle of a split torus (BRepExtrema misses the face minimum; the edge's answer is "
        "1e-7 off); the MAT's distances are right to 4e-6 of the radius",
        ("blob_ring", "split_closed"): "ShapeUpgrade_ShapeDivideClosed breaks the surface of "
        "revolution of a periodic spline (B-rep tolerance 0.8)",
    }
    if (name, dialect) in skip:
        pytest.skip(skip[name, dialect])
    plain = SHAPES[name]()
    other = DIALECTS[dialect](plain)
    try:
        b = medialcad.recognize(other)
    except medialcad.InputError as err:
        # (ShapeDivideArea cuts the blob ring into faces of zero width in u, which OCC
        # throws on: refused, naming the solid's invalidity; since the volume is integrated
        # on the faces as they are when OCC cannot convert them to NURBS, the refusal is
        # the reading's own, "... (and it is not a valid solid: ...)")
        assert not BRepCheck_Analyzer(other).IsValid(), err
        assert re.search(r"not (a )?valid", str(err)), err
        return
    a = medialcad.recognize(plain)
    assert isinstance(a, KIND[name])
    _same_reading(a, b)
    _check(other, f"{name}/{dialect}")


def test_a_nurbs_torus_is_read_with_its_exact_meridian_circle() -> None:
    """The section of a NURBS torus by a half-plane, as OCC's Boolean approximates it,
    wobbles by ~1e-4: its 2D MAT was 22 tiny branches round the centre and a revolved
    sheet's rows swung 1,000 units out of the solid. The meridian is now the surface's own
    iso-curve (rational, exactly a circle): one node, the circle's centre, radius 1."""
    reading = medialcad.recognize(nurbs(SHAPES["torus"]()))
    assert isinstance(reading, Revolution)
    mat2d = medialcad.medial_axis_2d(reading.profile)
    assert len(mat2d.branches) == 0
    (node,) = mat2d.nodes
    assert node.radius == pytest.approx(1.0, abs=1e-9)
    result = medialcad.medial_axis(reading.solid)
    assert len(result.sheets) == 0
    p, _ = M.edge_points(result.skeletal_edges[0].edge, 5)
    rho = np.linalg.norm(p[:, :2], axis=1)
    assert np.abs(rho - 5.0).max() <= 1e-6 and np.abs(p[:, 2]).max() <= 1e-6


def test_a_nurbs_copy_through_step_is_read_as_the_original(tmp_path: Path) -> None:
    for name in ("slot", "cone_pie_slice"):
        plain = SHAPES[name]()
        other = nurbs_through_step(plain, tmp_path)
        _same_reading(medialcad.recognize(plain), medialcad.recognize(other))
        _check(other, f"{name}/nurbs-step")


@pytest.mark.parametrize("file", ["pin_pie_slice.step", "gear_wheel.step"])
def test_fixtures_converted_to_nurbs(file: str) -> None:
    (solid,) = medialcad.read_step(SOLIDS / file)
    other = nurbs(solid)
    _same_reading(medialcad.recognize(solid), medialcad.recognize(other))
    _check(other, f"{file}/nurbs")


def test_a_flat_bspline_face_is_a_plane_but_a_curved_one_is_not() -> None:
    """Recognition reads a B-spline face as a plane only if it is flat: the box with a
    spherical bump stays refused when every face is a B-spline."""
    assert isinstance(medialcad.recognize(nurbs(SHAPES["box"]())), Extrusion)
    (bumped,) = medialcad.read_step(SOLIDS / "box_with_spherical_bump.step")
    with pytest.raises(medialcad.NotExtrusionOrRevolutionError):
        medialcad.recognize(nurbs(bumped))


def test_a_full_revolution_clear_of_its_axis_is_cut_by_its_plane_section() -> None:
    """The meridian section of a full revolution whose profile keeps clear of the axis is
    built from the plane's section curves (OCC's Boolean common of the NURBS blob ring with
    a half-plane took 62 s, its plane section 0.2 s); a profile on the axis is left to the
    common, which cuts it there. Both give the profile's area."""
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt

    from medialcad.occ.recognize import _plane_section

    for name, clear in (("blob_ring", True), ("trapezoid_ring", True), ("cone", False)):
        solid = nurbs(SHAPES[name]())
        reading = medialcad.recognize(solid)
        f = reading.frame
        ax = gp_Ax3(gp_Pnt(*f.origin), gp_Dir(*f.zdir), gp_Dir(*f.xdir))
        face = _plane_section(solid, ax, f, 1e-7 * reading.diag)
        if not clear:
            assert face is None, name
            continue
        assert face is not None, name
        assert _area(face) == pytest.approx(_area(reading.profile), rel=1e-6)


def test_a_closed_clamped_spline_wraps_across_its_seam() -> None:
    """A periodic spline written clamped (one closed, non-periodic B-spline edge, as a NURBS
    conversion writes it) is read as periodic: feet and rows wrap across its seam. Read as
    an open curve, feet near the seam were clamped at its ends and the rows of a blob
    ring's branch through there were 4e-3 off their own radius (the sheets 5 tol)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.TopAbs import TopAbs_EDGE

    from medialcad.mat3d.segments import split_branches

    reading = medialcad.recognize(nurbs(_blob_ring()))
    ex = TopExp_Explorer(reading.profile, TopAbs_EDGE)
    assert not BRepAdaptor_Curve(TopoDS.Edge_s(ex.Current())).IsPeriodic()
    mat2d = medialcad.medial_axis_2d(reading.profile)
    for seg in split_branches(mat2d.graph, mat2d.boundary, None):
        for feet in (seg.foot_a, seg.foot_b):
            off = np.abs(np.linalg.norm(seg.centre - feet, axis=1) - seg.radius)
            assert off.max() <= 0.1 * mat2d.tol
    # and a plate cut out by such an edge, as an extrusion
    blob = F.bspline_blob([0.6274, 0.7225, 0.7523, 0.7767, 0.9978, 0.8963, 0.8111, 0.9945])
    plate = nurbs(M.prism(blob, 0.4, F.random_placement(5)))
    _check(plate, "clamped blob plate")


def test_a_sphere_in_halves_has_no_axis_through_two_equal_centres() -> None:
    """A sphere cut in halves is two spherical faces with one centre. The axis through two
    spheres' centres is asked only of distinct centres: the unit vector of a zero vector
    gave a NaN candidate and a RuntimeWarning (an error where warnings are errors). The
    ball in halves is still the ball; the bumped box in halves is still refused."""
    import warnings

    ball = cq.Workplane().sphere(3).val().wrapped
    (bumped,) = medialcad.read_step(SOLIDS / "box_with_spherical_bump.step")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        _same_reading(medialcad.recognize(ball), medialcad.recognize(split_closed(ball)))
        with pytest.raises(medialcad.NotExtrusionOrRevolutionError):
            medialcad.recognize(split_closed(bumped))


@pytest.mark.parametrize("kink", [3e-6, -3e-6, 1e-4, 1e-3, 0.1, -1e-4, -1e-3, -1e-2, -0.1])
def test_a_closed_spline_written_clamped_with_a_corner_at_its_seam(kink: float) -> None:
    """Other systems write a closed curve clamped, its seam a corner of ~1e-6 rad or more,
    which is not read as periodic. A branch's feet pass over that seam: the rows solved
    from the feet either side of it were solved the long way round the curve (150 tol
    off at -3e-6: 73 tol unsound; at 1e-4 the compound failed BRepCheck). The seam of a
    curve closed on itself is now crossed as a periodic curve's. A convex seam corner
    (``kink < 0``) not flat at the tolerance was refused (1e-3 rad and more) or wrong
    (1e-4); the profile's loop is now two elements meeting at it. The 3D oracles missed
    the sheet of its spoke (feet either side of the wall's own seam) and, once,
    the wall's nearest point (BRepExtrema and the nearest node's face both missed it):
    both mended in ``tests/oracles3d.py``."""
    _check(M.prism(F.clamped_closed_blob(kink), 0.4), f"clamped blob, seam corner {kink}")


@pytest.mark.parametrize("kink", [-3e-5, -1.5e-4])
def test_a_nearly_flat_convex_seam_corner_is_answered_within_tol_or_refused(kink: float) -> None:
    """Prisms of the clamped blob whose seam is a nearly flat convex corner (3e-5 and
    1.5e-4 rad): the 2D MAT is answered, with the corner's spoke; the sheets of that
    spoke near the caps are narrower than the tolerance and the complex failed OCC's
    BRepCheck, a wrong answer nothing refused (before, the 2D MAT was refused at 1.5e-4
    and the mid sheet did not close at 3e-5). The complex is now checked with
    BRepCheck before it is returned: answered and passing the oracles, or refused."""
    solid = M.prism(F.clamped_closed_blob(kink), 0.4)
    try:
        _check(solid, f"clamped blob, nearly flat convex seam {kink}")
    except medialcad.ComputationError as err:
        assert "BRepCheck" in str(err), err


def test_a_revolution_at_its_critical_angle_is_answered_within_tol() -> None:
    """A fresh random revolution at the critical angle ``2 asin(Rmax / x)`` (its end
    planes' bisector just touches the largest disk; hypothesis seed 24545, kept
    exactly). The level ``r = x sin(Theta/2)`` touches a branch (3.6e-7 above it, 0.013
    tol): rounding put two roots 1.2e-3 apart, and the sliver between them gave two
    unorientable cap sheets and a revolved sheet of area 9e-16 (returned, then refused
    by the BRepCheck). A touch within the tolerance is now one cut: answered, passing
    the oracles."""
    solid = F.read_exact("critical_revolution_seed24545.bbrep")
    _check(solid, "critical revolution, seed 24545")


def test_an_offset_surface_is_read_as_what_it_is_offset_from() -> None:
    """OCC's offset of a blob prism (0.05 outwards, sharp joins; kept exactly) writes its
    side as an offset surface of the prism's surface of linear extrusion, as systems
    write offset or shelled parts. Recognition reads it as that extrusion (before:
    refused, OCC integrated the offset face's volume 2 % off; it is now integrated on a
    NURBS copy). Its cap is a closed B-spline written clamped, a corner of 1.09e-6 rad at
    its seam: the prisms of the cap pass the oracles (before: rows 150 tol off, the MAT
    5e-4 diag unsound). They are judged as plain prisms of the same cap: BRepExtrema
    takes minutes on the offset surface itself."""
    solid = F.read_exact("offset_blob_prism.bbrep")
    reading = medialcad.recognize(solid)
    assert isinstance(reading, Extrusion)
    assert reading.length == pytest.approx(0.5, rel=1e-9)
    nurbs_volume = GProp_GProps()
    BRepGProp.VolumeProperties_s(
        BRepBuilderAPI_NurbsConvert(solid, True).Shape(), nurbs_volume, 1e-9, False
    )
    assert _area(reading.profile) * reading.length == pytest.approx(nurbs_volume.Mass(), rel=1e-5)
    for length in (0.5, 2.0):
        _check(M.prism(reading.profile, length), f"prism of the offset cap, length {length}")


@pytest.mark.parametrize("name", ["box", "tube", "cone_pie_slice"])
def test_an_inside_out_solid_is_read_as_the_solid(name: str) -> None:
    """A solid whose shell faces inward (negative volume; OCC's checker accepts it, some
    writers produce it) is the same solid. Read inside out, the box's caps faced into it
    (refused) and the tube was read as a revolution whose MAT lay outside the solid. The
    oracle measures the result against the solid the right way out."""
    plain = SHAPES[name]()
    inside_out = TopoDS.Solid_s(plain.Reversed())
    assert BRepCheck_Analyzer(inside_out).IsValid()
    _same_reading(medialcad.recognize(plain), medialcad.recognize(inside_out))
    result = medialcad.medial_axis(inside_out)
    rep = M.check(plain, result, f"{name}/inside out", n_complete=60)
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


# --------------------------------------------------------------------------- random solids

# derandomized unless MEDIALCAD_HYPOTHESIS_RANDOM; MEDIALCAD_HYPOTHESIS_EXAMPLES_3D each
_PROFILES = st.one_of(
    F.random_bspline_blob(),
    F.star_polygon_strategy(),
    F.polygon_with_holes_strategy(),
    F.line_arc_fillet_mix(),
)
_DIALECT = st.sampled_from(["nurbs", "split_closed", "split_faces"])


@HYPO3
@given(face=_PROFILES, factor=st.floats(0.05, 3.0), dialect=_DIALECT, seed=st.integers(0, 2**16))
def test_random_extrusion_in_another_dialect(
    face: Any, factor: float, dialect: str, seed: int
) -> None:
    solid = M.prism(face, factor * O.bbox_diagonal(face), F.random_placement(seed))
    _random_check(DIALECTS[dialect](solid), f"extrusion L={factor:.2f}d {dialect} seed{seed}")


@HYPO3
@given(
    face=_PROFILES,
    margin=st.floats(0.05, 3.0),
    angle=st.one_of(st.floats(math.radians(5), math.radians(355)), st.just(2 * math.pi)),
    dialect=_DIALECT,
    seed=st.integers(0, 2**16),
)
def test_random_revolution_in_another_dialect(
    face: Any, margin: float, angle: float, dialect: str, seed: int
) -> None:
    shift = F.Placement(np.eye(3), np.array([1.0 + margin, 0.0, 0.0]))
    solid = revolve(F.place(face, shift), angle, F.random_placement(seed))
    label = f"revolution {math.degrees(angle):.0f}deg {dialect} seed{seed}"
    _random_check(DIALECTS[dialect](solid), label)


def _random_check(solid: TopoDS_Shape, label: str) -> None:
    """The oracles, or a clear refusal of an input OCC's own rewriting broke (its checker
    rejects the solid, or the B-rep's tolerance grew past the solid's tolerance)."""
    broken = not BRepCheck_Analyzer(solid).IsValid() or ShapeAnalysis_ShapeTolerance().Tolerance(
        solid, 1
    ) > 1e-5 * O.bbox_diagonal(solid)
    with F.dump_on_failure(solid, label.replace(" ", "-")):
        try:
            result = medialcad.medial_axis(solid)
        except medialcad.InputError:
            if broken:
                return
            raise
        assume(not broken)
        rep = M.check(
            solid, result, label, per_face=10, max_faces=16, max_edges=16, n_complete=60
        )  # fmt: skip
        print(rep.line())
        assert not rep.failures(), f"{label}: " + "; ".join(rep.failures())


def test_nurbs_revolution_of_a_loop_of_spline_pieces() -> None:
    """A 269-degree NURBS revolution of a loop of 26 spline pieces (fresh fuzz, thirteenth
    session; an xfail until the seventeenth): it missed a revolved medial point by 2.8
    tol and had a sheet of 25,920 poles. Both came from a pocket branch's exact rows
    bisected towards its branch point until they were 1e-10 apart; thinned to 1e-2 tol
    apart, the sheet has 13,824 poles and the oracles pass (complete 1.1e-7 diag)."""
    solid = F.read_exact("nurbs_chain_revolution_269.bbrep")
    _check(solid, "NURBS revolution of a spline loop, 269 degrees")
