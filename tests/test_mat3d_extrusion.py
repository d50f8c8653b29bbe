"""The 3D medial axis transform of extrusions, as specifications (THEORY.md Sec. 1, 3, 4).

- Closed forms (Sec. 4): the box (13 planar sheets, 12 seams, 4 junctions), the cube (12
  triangles meeting at the centre), the cylinder (axis segment and two cones, or a mid disk
  and two frusta), the extruded ellipse (skeletal edges at the curvature centres) and the
  tube (a cylindrical sheet, or a planar annulus). Our faces are pieces of the geometric
  sheets, so sheets are compared by the planes they lie in and by their areas, seams by
  their total length.
- Every closed form, every extrusion fixture of ``fixtures/step`` and random extrusions in
  random placements pass the independent oracles of :mod:`tests.oracles3d`: soundness,
  completeness and radius error within the result's tolerance, no output point outside the
  solid, one connected component with the solid's Euler characteristic, a valid sewn complex
  whose free edges are rims on the solid's boundary or skeletal edges and whose seams bound
  at least 3 sheets (:func:`tests._mat3d.check`).
- Paper Table 1 junction counts, STEP export with names, the radius sidecar.

Errors are asserted in model units against ``result.tol`` and printed relative to the
bounding-box diagonal (``pytest -s`` shows one line per case).
"""

from __future__ import annotations

import json
import math
import os
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from OCP.BRepCheck import BRepCheck_Analyzer
from scipy.integrate import quad

from tests import _mat3d as M
from tests import faces as F
from tests import oracles3d as O

ROOT = Path(__file__).resolve().parent.parent
MANIFESTS = (ROOT / "fixtures/step/solids", ROOT / "fixtures/step/freecad")

# --------------------------------------------------------------------------- the cases

A, B, C = 4.0, 3.0, 2.0  # box, a > b > c
THIN = (10.0, 6.0, 0.5)  # thin box: the mid sheet dominates
CUBE = 2.0
R_LONG, H_LONG = 1.0, 5.0  # cylinder, H > 2R
R_SHORT, H_SHORT = 2.0, 1.0  # cylinder, H < 2R
EA, EB, EL = 3.0, 1.0, 4.0  # extruded ellipse, semi-axes and length
TUBE_TALL = (2.0, 2.5, 3.0)  # ri, ro, h with t = ro - ri < h
TUBE_FLAT = (1.0, 3.0, 0.6)  # t > h

CLOSED_FORMS = {
    "box": lambda: M.box(A, B, C),
    "thin_box": lambda: M.box(*THIN),
    "cube": lambda: M.box(CUBE, CUBE, CUBE),
    "cylinder_long": lambda: M.cylinder(R_LONG, H_LONG),
    "cylinder_short": lambda: M.cylinder(R_SHORT, H_SHORT),
    "ellipse": lambda: M.elliptic_prism(EA, EB, EL),
    # its profile one closed edge with the seam at an end of the minor axis: the partner
    # of the other end is the seam point itself
    "ellipse_minor_seam": lambda: M.elliptic_prism(EA, EB, EL, 0.5 * math.pi),
    "tube_tall": lambda: M.tube(*TUBE_TALL),
    "tube_flat": lambda: M.tube(*TUBE_FLAT),
}


def _fixtures() -> dict[str, tuple[Path, dict[str, Any]]]:
    out = {}
    for folder in MANIFESTS:
        manifest = folder / "manifest.json"
        if not manifest.is_file():
            continue
        for entry in json.loads(manifest.read_text())["solids"]:
            if entry.get("kind") == "extrusion":
                out[entry["name"]] = (folder / entry["file"], entry)
    return out


FIXTURES = _fixtures()

# Known failures of the algorithm (not of the tests): non-strict xfails, so that a fix
# shows up as XPASS. The numbers are in each case's report line (pytest -s).
# (fc_bspline_periodic_extrusion was here at 1.5 tol until the 3D soundness oracle measured
# samples above tol as their distance to the MAT, 2026-12-01)
KNOWN_ORACLES: dict[str, str] = {}
KNOWN_JUNCTIONS: dict[str, str] = {}


def _params(names: list[str], known: dict[str, str]) -> list[Any]:
    return [
        pytest.param(n, marks=pytest.mark.xfail(strict=False, reason=known[n])) if n in known else n
        for n in names
    ]


@dataclass
class Case:
    solid: Any
    result: Any
    seconds: float
    boundary: O.SolidBoundary | None = None
    report: M.Report | None = None

    @property
    def sb(self) -> O.SolidBoundary:
        if self.boundary is None:
            self.boundary = O.SolidBoundary(self.solid)
        return self.boundary


class Cache:
    """Solids, results and oracle reports, computed once per module."""

    def __init__(self) -> None:
        self.cases: dict[str, Case] = {}

    def __call__(self, name: str, fixture: bool = False) -> Case:
        """A closed form of :data:`CLOSED_FORMS`, or (``fixture``) a STEP fixture."""
        key = f"step:{name}" if fixture else name
        if key not in self.cases:
            if fixture:
                from medialcad.recognition import read_step

                solid = read_step(FIXTURES[name][0])[0]
            else:
                solid = CLOSED_FORMS[name]()
            t0 = time.perf_counter()
            result = M.extrusion_mat(solid)
            self.cases[key] = Case(solid, result, time.perf_counter() - t0)
        return self.cases[key]

    def report(self, name: str, fixture: bool = False, **kw: Any) -> M.Report:
        case = self(name, fixture)
        if case.report is None:
            label = f"step:{name}" if fixture else name
            case.report = M.check(case.solid, case.result, label, boundary=case.sb, **kw)
            case.report.seconds["mat"] = case.seconds
            print(case.report.line())
        return case.report


@pytest.fixture(scope="module")
def mats() -> Cache:
    return Cache()


def _close(actual: float, expected: float, tol: float, what: str) -> None:
    assert abs(actual - expected) <= tol, f"{what}: {actual:.9g}, expected {expected:.9g}"


# --------------------------------------------------------------------------- closed forms


def _canon(n: Any, d: float) -> tuple[np.ndarray, float]:
    n = np.asarray(n, dtype=float)
    k = float(np.linalg.norm(n))
    n, d = n / k, d / k
    j = int(np.argmax(np.abs(n) > 1e-6))
    return (-n, -d) if n[j] < 0 else (n, d)


def box_sheets(a: float, b: float, c: float) -> list[tuple[np.ndarray, float, float]]:
    """The 13 sheets of ``[0,a] x [0,b] x [0,c]`` (``a > b > c``): ``(normal, offset,
    area)`` of the plane ``n.x = d`` each lies in. Points where two faces are the nearest:
    the mid sheet ``z = c/2``, the 8 sheets between a cap and a side at 45 degrees
    (trapezoids), the 4 sheets between two sides at the vertical edges (triangles)."""
    r2 = math.sqrt(2.0)
    cap_x = r2 * (b * c / 2 - c * c / 4)  # between a z-face and an x-face
    cap_y = r2 * (a * c / 2 - c * c / 4)
    corner = r2 * c * c / 4
    planes = [((0, 0, 1), c / 2, (a - c) * (b - c))]
    planes += [((1, 0, -1), 0.0, cap_x), ((1, 0, 1), a, cap_x)]
    planes += [((1, 0, 1), c, cap_x), ((1, 0, -1), a - c, cap_x)]
    planes += [((0, 1, -1), 0.0, cap_y), ((0, 1, 1), b, cap_y)]
    planes += [((0, 1, 1), c, cap_y), ((0, 1, -1), b - c, cap_y)]
    planes += [((1, -1, 0), 0.0, corner), ((1, 1, 0), a, corner)]
    planes += [((1, 1, 0), b, corner), ((1, -1, 0), a - b, corner)]
    return [(*_canon(n, d), area) for n, d, area in planes]


def _match_planes(
    groups: list[tuple[np.ndarray, float, float]],
    expected: list[tuple[np.ndarray, float, float]],
    eps: float,
    area_tol: float,
) -> None:
    assert len(groups) == len(expected), (
        f"{len(groups)} distinct planes, expected {len(expected)}: "
        + ", ".join(f"{np.round(n, 3)}.x={d:.4g} (area {a:.4g})" for n, d, a in groups)
    )
    for n, d, area in expected:
        hit = [g for g in groups if np.linalg.norm(g[0] - n) <= 1e-6 and abs(g[1] - d) <= eps]
        assert hit, f"no sheet in the plane {np.round(n, 3)}.x = {d:.4g}"
        _close(hit[0][2], area, area_tol, f"area in the plane {np.round(n, 3)}.x = {d:.4g}")


@pytest.mark.parametrize("name", ["box", "thin_box"])
def test_box_has_13_planar_sheets_12_seams_4_junctions(mats: Cache, name: str) -> None:
    a, b, c = (A, B, C) if name == "box" else THIN
    r = mats(name).result
    tol = r.tol
    groups = M.planes_and_areas(r, eps=tol)
    _match_planes(groups, box_sheets(a, b, c), eps=tol, area_tol=tol * (a + b))
    r2, r3 = math.sqrt(2.0), math.sqrt(3.0)
    total = (a - c) * (b - c) + r2 * (2 * b * c + 2 * a * c - c * c)
    _close(M.total_area([s.face for s in r.sheets]), total, tol * (a + b), "total sheet area")
    # 12 seams: the mid rectangle's 4 sides and 8 lines from the corners to the junctions
    seam_length = sum(M.edge_length(s.edge) for s in r.seams)
    _close(seam_length, 2 * (a + b - 2 * c) + 4 * r3 * c, 10 * tol, "total seam length")
    h = c / 2
    expected = [(x, y, h) for x in (h, a - h) for y in (h, b - h)]
    got = np.array([j.point for j in r.junctions]).reshape(-1, 3)
    assert len(got) == 4, f"{len(got)} junctions"
    for p in expected:
        assert np.min(np.linalg.norm(got - p, axis=1)) <= tol, f"no junction at {p}"
    for j in r.junctions:
        _close(j.radius, h, tol, "junction radius")
    assert not r.skeletal_edges


def test_cube_has_12_triangles_meeting_at_the_centre(mats: Cache) -> None:
    c = CUBE
    r = mats("cube").result
    tol = r.tol
    # the 12 triangles (an edge of the cube and the centre) lie in the 6 diagonal planes,
    # two in each: area 2 * sqrt(2) c^2 / 4 per plane
    tri = math.sqrt(2.0) * c * c / 4
    expected = [
        (*_canon(n, d), 2 * tri)
        for n, d in (
            ((1, -1, 0), 0.0),
            ((1, 1, 0), c),
            ((1, 0, -1), 0.0),
            ((1, 0, 1), c),
            ((0, 1, -1), 0.0),
            ((0, 1, 1), c),
        )
    ]
    _match_planes(M.planes_and_areas(r, eps=tol), expected, eps=tol, area_tol=tol * c)
    _close(M.total_area([s.face for s in r.sheets]), 12 * tri, tol * c, "total sheet area")
    centre = np.full(3, c / 2)
    for j in r.junctions:
        assert np.linalg.norm(j.point - centre) <= tol, f"{j.name} at {j.point}, not the centre"
        _close(j.radius, c / 2, tol, "junction radius")
    assert r.junctions, "no junction"


def test_cube_has_exactly_one_junction(mats: Cache) -> None:
    r = mats("cube").result
    assert len(r.junctions) == 1, [j.point.tolist() for j in r.junctions]


def test_cylinder_long_is_an_axis_segment_and_two_cones(mats: Cache) -> None:
    R, H = R_LONG, H_LONG
    r = mats("cylinder_long").result
    tol = r.tol
    assert len(r.skeletal_edges) == 1, f"{len(r.skeletal_edges)} skeletal edges"
    axis = r.skeletal_edges[0]
    _close(M.edge_length(axis.edge), H - 2 * R, tol, "axis segment length")
    pts, t = M.edge_points(axis.edge, 9)
    assert np.abs(pts[:, :2]).max() <= tol, "the skeletal edge is off the axis"
    assert pts[:, 2].min() >= R - tol and pts[:, 2].max() <= H - R + tol
    assert np.abs(axis.radius(t) - R).max() <= tol, "axis radius"
    assert not r.seams and not r.junctions
    assert {s.role for s in r.sheets} == {"cap"}
    cone = math.pi * R * R * math.sqrt(2.0)  # base R, height R
    _close(M.total_area([s.face for s in r.sheets]), 2 * cone, tol * R, "area of the two cones")


def test_cylinder_short_is_a_mid_disk_and_two_frusta(mats: Cache) -> None:
    R, H = R_SHORT, H_SHORT
    r = mats("cylinder_short").result
    tol = r.tol
    rho = R - H / 2
    mids = [s for s in r.sheets if s.role == "mid"]
    assert mids, "no mid sheet"
    _close(M.total_area([s.face for s in mids]), math.pi * rho * rho, tol * R, "mid disk area")
    for s in mids:
        p, _ = M.face_samples(s.face, 16)
        assert np.abs(p[:, 2] - H / 2).max() <= tol, "the mid sheet is not in z = H/2"
    frusta = 2 * math.pi * (R + rho) * (H / 2) * math.sqrt(2.0)
    _close(
        M.total_area([s.face for s in r.sheets]),
        math.pi * rho * rho + frusta,
        tol * R,
        "total sheet area",
    )
    # one circular seam of radius R - H/2 at z = H/2 (possibly in pieces)
    _close(sum(M.edge_length(s.edge) for s in r.seams), 2 * math.pi * rho, tol, "seam length")
    for s in r.seams:
        p, _ = M.edge_points(s.edge, 9)
        assert np.abs(np.hypot(p[:, 0], p[:, 1]) - rho).max() <= tol, "seam radius"
        assert np.abs(p[:, 2] - H / 2).max() <= tol, "seam height"
    assert not r.skeletal_edges and not r.junctions


@pytest.mark.parametrize("name", ["ellipse", "ellipse_minor_seam"])
def test_ellipse_has_skeletal_edges_at_the_curvature_centres(mats: Cache, name: str) -> None:
    a, b, L = EA, EB, EL
    r = mats(name).result
    tol = r.tol
    c, rho = (a * a - b * b) / a, b * b / a
    assert len(r.skeletal_edges) == 2, f"{len(r.skeletal_edges)} skeletal edges"
    xs = []
    for e in r.skeletal_edges:
        p, t = M.edge_points(e.edge, 5)
        xs.append(float(p[0, 0]))
        assert np.abs(np.abs(p[:, 0]) - c).max() <= tol and np.abs(p[:, 1]).max() <= tol
        _close(M.edge_length(e.edge), L - 2 * rho, tol, "skeletal edge length")
        assert np.abs(e.radius(t) - rho).max() <= tol, "skeletal edge radius"
    assert sorted(np.sign(xs)) == [-1.0, 1.0], "both curvature centres"
    # the vertical sheet {(x, 0, z): |x| <= c, r(x) <= z <= L - r(x)}
    e2 = a * a - b * b

    def radius(x: float) -> float:
        return b * math.sqrt(max(0.0, 1 - x * x / e2))

    vertical = 2 * c * L - 2 * quad(radius, -c, c)[0]
    walls = [s.face for s in r.sheets if s.role == "vertical"]
    _close(M.total_area(walls), vertical, tol * a, "vertical sheet area")

    # its seams (x, 0, r(x)) and (x, 0, L - r(x))
    def slope(x: float) -> float:  # r'(x) = -b^2 x / (e^2 r(x))
        return b * b * x / (e2 * radius(x))

    arc = quad(lambda x: math.sqrt(1 + slope(x) ** 2), -c, c)[0]
    _close(sum(M.edge_length(s.edge) for s in r.seams), 2 * arc, 10 * tol, "seam length")


def _frustum(r1: float, r2: float, slant: float) -> float:
    return math.pi * (r1 + r2) * slant


def test_tube_tall_is_a_cylindrical_sheet_and_four_frusta(mats: Cache) -> None:
    ri, ro, h = TUBE_TALL
    t, rm = ro - ri, (ri + ro) / 2
    r = mats("tube_tall").result
    tol = r.tol
    walls = [s for s in r.sheets if s.role == "vertical"]
    _close(M.total_area([s.face for s in walls]), 2 * math.pi * rm * (h - t), tol * ro, "wall")
    for s in walls:
        p, uv = M.face_samples(s.face, 16)
        assert np.abs(np.hypot(p[:, 0], p[:, 1]) - rm).max() <= tol, "wall radius"
        assert p[:, 2].min() >= t / 2 - tol and p[:, 2].max() <= h - t / 2 + tol
        assert np.abs(s.radius(uv[:, 0], uv[:, 1]) - t / 2).max() <= tol, "wall MAT radius"
    slant = t / 2 * math.sqrt(2.0)
    total = 2 * math.pi * rm * (h - t) + 2 * _frustum(ro, rm, slant) + 2 * _frustum(ri, rm, slant)
    _close(M.total_area([s.face for s in r.sheets]), total, tol * ro, "total sheet area")
    _close(sum(M.edge_length(s.edge) for s in r.seams), 4 * math.pi * rm, 10 * tol, "seams")
    assert not r.junctions and not r.skeletal_edges


def test_tube_flat_is_a_planar_annulus_and_four_frusta(mats: Cache) -> None:
    ri, ro, h = TUBE_FLAT
    r = mats("tube_flat").result
    tol = r.tol
    r1, r2 = ri + h / 2, ro - h / 2  # the annulus {d >= h/2} at z = h/2
    mids = [s for s in r.sheets if s.role == "mid"]
    _close(M.total_area([s.face for s in mids]), math.pi * (r2 * r2 - r1 * r1), tol * ro, "mid")
    slant = h / 2 * math.sqrt(2.0)
    total = (
        math.pi * (r2 * r2 - r1 * r1) + 2 * _frustum(ro, r2, slant) + 2 * _frustum(ri, r1, slant)
    )
    _close(M.total_area([s.face for s in r.sheets]), total, tol * ro, "total sheet area")
    _close(sum(M.edge_length(s.edge) for s in r.seams), 2 * math.pi * (r1 + r2), 10 * tol, "seams")
    for s in r.seams:
        p, _ = M.edge_points(s.edge, 9)
        rad = np.hypot(p[:, 0], p[:, 1])
        assert np.minimum(np.abs(rad - r1), np.abs(rad - r2)).max() <= tol, "seam radius"
        assert np.abs(p[:, 2] - h / 2).max() <= tol, "seam height"
    assert not r.junctions and not r.skeletal_edges


# --------------------------------------------------------------------------- oracles


@pytest.mark.parametrize("name", _params(list(CLOSED_FORMS), KNOWN_ORACLES))
def test_closed_form_passes_the_oracles(mats: Cache, name: str) -> None:
    rep = mats.report(name)
    assert not rep.failures(), f"{name}: " + "; ".join(rep.failures())


FIXTURE_NAMES = sorted(FIXTURES)


@pytest.mark.skipif(not FIXTURES, reason="no solid fixtures")
@pytest.mark.parametrize("name", _params(FIXTURE_NAMES, KNOWN_ORACLES))
def test_fixture_passes_the_oracles(mats: Cache, name: str) -> None:
    # sheets subsampled on the big models (the gear wheel has ~400 sheets)
    rep = mats.report(name, fixture=True, per_face=12, max_faces=24, max_edges=24)
    assert not rep.failures(), f"{name}: " + "; ".join(rep.failures())


JUNCTION_FACTS = sorted(n for n, (_, e) in FIXTURES.items() if "junction_points" in e["facts"])


@pytest.mark.parametrize("name", _params(JUNCTION_FACTS, KNOWN_JUNCTIONS))
def test_junction_count_of_the_paper(mats: Cache, name: str) -> None:
    """Paper Table 1 (gear wheel 32, I-section 12, free-form 12) and the manifest's counts."""
    facts = FIXTURES[name][1]["facts"]
    r = mats(name, fixture=True).result
    assert len(r.junctions) == facts["junction_points"]
    for want in facts.get("junction_points_at", []):
        gaps = [float(np.linalg.norm(j.point - want)) for j in r.junctions]
        assert min(gaps) <= r.tol, f"no junction at {want} (nearest {min(gaps):.3g} away)"
    if "paper_junction_points" in facts:
        assert len(r.junctions) == facts["paper_junction_points"]


DEGENERATE = sorted(
    n for n, (_, e) in FIXTURES.items() if "degenerate_junction_points" in e["facts"]
)


@pytest.mark.parametrize("name", DEGENERATE)
def test_degenerate_junctions_sit_at_the_expected_points(mats: Cache, name: str) -> None:
    """Junctions with more than 4 touch points (``L = 2 r`` at a branch point, or a branch
    point with 4 footpoints): every junction is within tol of one expected point and every
    expected point has one."""
    expected = np.array(FIXTURES[name][1]["facts"]["degenerate_junction_points"], dtype=float)
    r = mats(name, fixture=True).result
    got = np.array([j.point for j in r.junctions]).reshape(-1, 3)
    d = np.linalg.norm(got[:, None, :] - expected[None, :, :], axis=2)
    assert len(got) and d.min(axis=1).max() <= r.tol, "a junction away from the expected points"
    assert d.min(axis=0).max() <= r.tol, "an expected junction point is missing"


# --------------------------------------------------------------------------- export


def test_step_export_keeps_faces_and_names(mats: Cache, tmp_path: Path) -> None:
    from medialcad.occ.io import read_shapes

    r = mats("box").result
    path = tmp_path / "box_mat.step"
    r.write_step(path)
    text = path.read_text(errors="replace")
    assert "sheet-1" in text and "seam-1" in text and "junction-1" in text
    shapes = read_shapes(path)
    assert len(shapes) == 1
    assert BRepCheck_Analyzer(shapes[0]).IsValid()
    assert len(M.faces_in(shapes[0])) == len(r.sheets)


def test_radius_sidecar_and_radius_at(mats: Cache, tmp_path: Path) -> None:
    case = mats("box")
    r = case.result
    path = tmp_path / "box_mat.radius.json"
    r.write_radius(path)
    data = json.loads(path.read_text())
    assert data["format"] == "medialcad-radius/1" and data["kind"] == "extrusion"
    assert set(data["sheets"]) == {s.name for s in r.sheets}
    assert {c.name for c in r.seams} <= set(data["curves"])
    assert set(data["junctions"]) == {j.name for j in r.junctions}
    rng = np.random.default_rng(1)
    for s in [r.sheets[i] for i in rng.choice(len(r.sheets), 6, replace=False)]:
        pts, _ = M.face_samples(s.face, 4)
        want = case.sb.distances(pts)
        got = np.array([r.radius_at(p) for p in pts])
        assert np.abs(got - want).max() <= r.tol, f"{s.name}: radius_at vs distance"


@pytest.mark.parametrize("length", [0.3, 2.0])
@pytest.mark.parametrize("skew", [1e-7, 3e-6, 1e-4])
def test_nearly_degenerate_branch_points(length: float, skew: float) -> None:
    """A 6-pointed star with one reflex vertex moved by ``skew`` (its branch point splits
    into nearby ones), extruded thin (mid sheet) and thick: the oracles pass and the complex
    is contractible (chi was -3 at skew 1e-4: a cut's feet solved on the wrong element)."""
    solid = M.prism(F.nearly_symmetric_star(skew), length, F.random_placement(5))
    result = M.extrusion_mat(solid)
    rep = M.check(solid, result, f"star skew {skew:g} L={length}", n_complete=40)
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())
    assert rep.euler == rep.solid_euler == 1


def test_feet_across_the_seam_of_a_periodic_profile() -> None:
    """A closed B-spline profile is one boundary element: feet projected near its seam must
    wrap around, not stop there. Before, they were clamped at the seam while the centres
    moved on (side rows off by up to 130 tol, caps 24 tol unsound, 620 samples where 85
    do). Every sample of every segment is a maximal disk: ``|c - f| = r`` on both sides."""
    from medialcad.mat3d.segments import split_branches

    face = F.bspline_blob([0.6274, 0.7225, 0.7523, 0.7767, 0.9978, 0.8963, 0.8111, 0.9945])
    solid = M.prism(face, 0.685 * O.bbox_diagonal(face), F.random_placement(1))
    result = M.extrusion_mat(solid)
    mat2d = result.mat2d
    for seg in split_branches(mat2d.graph, mat2d.boundary, None):
        for feet in (seg.foot_a, seg.foot_b):
            off = np.abs(np.linalg.norm(seg.centre - feet, axis=1) - seg.radius)
            assert off.max() <= 0.1 * result.tol
    rep = M.check(solid, result, "blob across its seam", n_complete=60)
    print(rep.line())
    # (1.04 tol next to a curvature-centre end at the seam until the oracles read both
    # sides of a C1 seam and refined across it, 2026-12-01: now 0.75 tol)
    assert not rep.failures(), "; ".join(rep.failures())


# --------------------------------------------------------------------------- random solids

# 3D examples cost ~10x the 2D ones: MEDIALCAD_HYPOTHESIS_EXAMPLES_3D per profile strategy,
# by default a quarter of the 2D budget
_EXAMPLES = int(os.environ.get("MEDIALCAD_HYPOTHESIS_EXAMPLES", "6"))
_EXAMPLES_3D = int(os.environ.get("MEDIALCAD_HYPOTHESIS_EXAMPLES_3D", str(max(1, _EXAMPLES // 4))))
HYPO3 = settings(
    max_examples=_EXAMPLES_3D,
    phases=[Phase.explicit, Phase.reuse, Phase.generate]
    + ([Phase.shrink] if os.environ.get("MEDIALCAD_HYPOTHESIS_SHRINK") else []),
    derandomize=not os.environ.get("MEDIALCAD_HYPOTHESIS_RANDOM"),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)


def _random_extrusion(
    face: Any, factor: float, seed: int, label: str, length: float | None = None
) -> None:
    """``face`` extruded by ``factor`` times its diagonal (or by ``length``), placed
    randomly, judged by the oracles."""
    diag = O.bbox_diagonal(face)
    if length is not None:
        factor = length / diag
    solid = M.prism(face, factor * diag, F.random_placement(seed))
    with F.dump_on_failure(solid, f"{label}-extrusion-seed{seed}"):
        t0 = time.perf_counter()
        result = M.extrusion_mat(solid)
        seconds = time.perf_counter() - t0
        rep = M.check(
            solid, result, f"{label} L={factor:.2f}d", per_face=10, max_faces=16, max_edges=16,
            per_edge=2, n_complete=60, seed=seed,
        )  # fmt: skip
        rep.seconds["mat"] = seconds
        print(rep.line())
        assert not rep.failures(), f"{label}: " + "; ".join(rep.failures())


_LENGTH = st.floats(0.05, 3.0)
_SEED = st.integers(0, 2**16)


@HYPO3
@given(face=F.random_bspline_blob(), factor=_LENGTH, seed=_SEED)
def test_random_blob_extrusion(face: Any, factor: float, seed: int) -> None:
    _random_extrusion(face, factor, seed, "blob")


@HYPO3
@given(face=F.star_polygon_strategy(), factor=_LENGTH, seed=_SEED)
def test_random_star_extrusion(face: Any, factor: float, seed: int) -> None:
    _random_extrusion(face, factor, seed, "star")


@HYPO3
@given(face=F.polygon_with_holes_strategy(), factor=_LENGTH, seed=_SEED)
def test_random_polygon_with_holes_extrusion(face: Any, factor: float, seed: int) -> None:
    _random_extrusion(face, factor, seed, "holes")


@HYPO3
@given(face=F.line_arc_fillet_mix(), factor=_LENGTH, seed=_SEED)
def test_random_line_arc_extrusion(face: Any, factor: float, seed: int) -> None:
    _random_extrusion(face, factor, seed, "fillets")


@st.composite
def _at_a_critical_length(draw: st.DrawFn) -> tuple[Any, float]:
    """A random profile and a length on a degenerate boundary of the thin extrusion
    (THEORY Sec. 1: the mid sheet is where ``r > L / 2``): ``L = 2 Rmax`` (the mid sheet
    shrinks to the largest disks' centres) or ``L = 2 r`` of a branch point (its boundary
    runs through the branch point)."""
    from medialcad.api import medial_axis_2d

    face = draw(F.any_profile())
    mat = medial_axis_2d(face)  # only to choose the length: the oracles judge the result
    radii = [mat.rmax] + [n.radius for n in mat.branch_points]
    return face, 2.0 * draw(st.sampled_from(radii))


@HYPO3
@given(case=_at_a_critical_length(), seed=_SEED)
def test_random_extrusion_at_a_critical_length(case: tuple[Any, float], seed: int) -> None:
    face, length = case
    _random_extrusion(face, 0.0, seed, "critical", length=length)


def _dumbbell() -> Any:
    """Two unit disks at ``x = +-2.2`` joined by an ellipse of semi-axes 1.5 and 0.5: its
    one branch's radius is 1 in the disks, dips at the necks and peaks at 0.5 in the
    middle, a local maximum below Rmax."""
    import cadquery as cq

    def disk(x: float) -> Any:
        return cq.Face.makeFromWires(
            cq.Wire.makeCircle(1.0, cq.Vector(x, 0, 0), cq.Vector(0, 0, 1))
        )

    ellipse = cq.Edge.makeEllipse(
        1.5, 0.5, cq.Vector(0, 0, 0), cq.Vector(0, 0, 1), cq.Vector(1, 0, 0)
    )
    middle = cq.Face.makeFromWires(cq.Wire.assembleEdges([ellipse]))
    return disk(-2.2).fuse(middle).fuse(disk(2.2)).clean().Faces()[0].wrapped


@pytest.mark.parametrize("below", [1e-9, 1e-7, 1e-5])
def test_half_length_just_below_a_local_maximum_of_the_radius(below: float) -> None:
    """``L/2`` a hair below the largest sampled radius of the dumbbell's middle (its true
    peak, 0.5, is 3.6e-5 above that sample, 0.55 tol): the level ``r = L/2`` crosses the
    branch twice there, and the small mid sheet between the crossings is no sliver. Every
    sheet is BRepCheck-valid and the oracles hold, as on either side of it."""
    from medialcad.api import medial_axis_2d

    face = _dumbbell()
    (branch,) = medial_axis_2d(face).graph.branches
    middle = np.abs(branch.points_2d[:, 0]) < 0.5
    peak = float(branch.radius[middle].max())
    solid = M.prism(face, 2.0 * (peak - below), F.random_placement(2))
    result = M.extrusion_mat(solid)
    # the disks' mid sheets, and the middle's where it is wider than the complex's merging
    # (at 1e-9 below, 2 tol wide at most, it is not built: the oracles measure that)
    assert len([s for s in result.sheets if s.role == "mid"]) >= 2
    for s in result.sheets:
        assert BRepCheck_Analyzer(s.face).IsValid(), f"{s.name} ({s.role}) fails BRepCheck"
    rep = M.check(
        solid, result, f"dumbbell, L/2 {below:.0e} below the middle's peak", n_complete=60
    )
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


def test_rmax_within_the_tolerance_above_half_the_length() -> None:
    """A fresh random extrusion (2026-12-02, kept exactly as binary BREP) of length
    ``L = 2 r`` for a branch point of radius r, next to another branch point 1.6e-5
    (0.5 tol) larger: Rmax is within the tolerance above L/2, so there is no mid sheet,
    and the larger disk still touches both caps. Its seam ran from z = r down to
    z = L - r, carrying r where the distance is L - r (1.01 tol). Every sample carries its
    distance to the boundary, and no radius exceeds L/2."""

    shape = F.read_exact("extrusion_rmax_just_above_half_length.bbrep")
    result = M.extrusion_mat(shape)
    half = 0.5 * result.recognition.length
    assert 0 < result.mat2d.rmax - half < result.tol  # the case: no mid sheet
    assert not [s for s in result.sheets if s.role == "mid"]
    assert max(j.radius for j in result.junctions) <= half * (1 + 1e-12)
    rep = M.check(shape, result, "Rmax just above L/2", per_face=10, n_complete=60)
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


def test_prism_of_a_blob_with_a_sharp_tip_is_complete() -> None:
    """A random run's blob prism (2026-12-06, kept exactly): its MAT was read as 1.96e-4
    diag incomplete at the tip's flank with the random test's own oracle settings. The
    MAT was right; the 3D oracle's distance had missed the tip's other flank (see
    ``test_medial_depths_of_an_extruded_blob_are_its_profiles``)."""
    shape = F.read_exact("blob_extrusion_seed5663.bbrep")
    result = M.extrusion_mat(shape)
    rep = M.check(
        shape, result, "blob prism, sharp tip", per_face=10, max_faces=16, max_edges=16,
        per_edge=2, n_complete=60, seed=5663,
    )  # fmt: skip
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


@pytest.mark.parametrize("length", [0.2, 2.0])
def test_thin_blob_profile_moved_to_its_canonical_frame_and_extruded(length: float) -> None:
    """The same profile moved rigidly to its canonical frame (plane z = 0) and extruded,
    thin (L = 0.2 < 2 Rmax = 1.06) and long: the branch point beside the nearly circular
    stretch was found at five places there (five feet, the branch into the flat maximum
    twice: a cycle, refused), and then, kept from the samples tangent at a stray foot,
    that branch was 12 tol off and the thin extrusion's sheets 0.037 diag unsound. With
    one contact per stretch on the disk and the branch's rows solved from the stretch,
    every oracle passes."""
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Vec

    from medialcad.recognition import recognize

    reading = recognize(F.read_exact("blob_thin_extrusion.bbrep"))
    fr = reading.frame
    rot = np.column_stack([fr.xdir, fr.ydir, fr.zdir])
    face = F.place(reading.profile, F.Placement(rot.T, -rot.T @ fr.origin))
    shape = M.single_solid(BRepPrimAPI_MakePrism(face, gp_Vec(0.0, 0.0, length)).Shape())
    result = M.extrusion_mat(shape)
    rep = M.check(shape, result, f"canonical thin blob L={length}", per_face=10, n_complete=60)
    assert not rep.failures(), "; ".join(rep.failures())


def test_thin_blob_extrusion_of_a_fresh_fuzz_run() -> None:
    """A fresh random blob extrusion, L = 0.05 d (2026-12-02, kept exactly as binary BREP),
    was refused ('the mid sheet's boundary does not close', exit code 1): its profile's
    2D MAT lost the branch from a branch point into a flat curvature maximum between two
    of its feet 1.1e-3 apart, so the mid sheet's boundary had a gap there. With the branch
    found, its rows solved from the stretch itself and each side's offset seam on its own
    chord length (the seam had looped, BRepCheck), the complex passes every oracle."""

    shape = F.read_exact("blob_thin_extrusion.bbrep")
    result = M.extrusion_mat(shape)
    rep = M.check(shape, result, "thin blob", per_face=10, n_complete=60)
    assert not rep.failures(), "; ".join(rep.failures())


def _slot_sticking_out_of_a_bar() -> Any:
    """A bar with a slot sticking out of its top, the slot's end circle centred above the
    bar's edge by less than its radius, the two concave corners where the end arc meets
    the bar filleted. The bar's branch rises between the fillets to the end arc's centre,
    where the slot's own branch goes on: a curvature-centre node two branches pass
    through, its disk touching the end arc on both sides of the bar, two stretches apart
    from each other."""
    from build123d import Location, Rectangle, SlotOverall, fillet

    sketch = Rectangle(9.8, 2.2) + Location((3.30, 2.463), 71) * SlotOverall(3.3, 1.03)
    corners = [v for v in sketch.vertices() if abs(v.Y - 1.1) < 1e-6 and 2 < v.X < 4]
    assert len(corners) == 2
    return fillet(corners, 0.07).faces()[0].wrapped


@pytest.mark.parametrize("length", [0.6, 3.0])
def test_a_curvature_centre_two_branches_pass_through_fans_over_both_stretches(
    length: float,
) -> None:
    """Each stretch of the end arc its disk touches is a fan of cap sheets of its own (the
    stretch between the branch's feet runs along the slot's sides, off the circle: no fan
    was built and both sides' end feet were put on one point, 2.1e-2 diag unsound for
    the thin prism and 1.3e-2 for the long one)."""
    from medialcad.api import medial_axis_2d

    face = _slot_sticking_out_of_a_bar()
    graph = medial_axis_2d(face)
    degree = {n.index: 0 for n in graph.nodes}
    for b in graph.branches:
        for n in (b.start, b.end):
            if n is not None:
                degree[n] += 1
    assert any(n.kind.value == "curvature_centre" and degree[n.index] == 2 for n in graph.nodes)
    solid = M.prism(face, length)
    result = M.extrusion_mat(solid)
    rep = M.check(solid, result, f"slot out of a bar L={length}", n_complete=100)
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


@pytest.mark.parametrize(
    ("a", "b", "offset", "factor", "axis", "angle", "shift"),
    [
        (
            3.2822941811772344,
            3.6710037444806405,
            -0.2302830728071295,
            1.8405179225970703,
            (0.6519409863787777, 0.04144148339492548, 0.902655932505334),
            288.4870241209305,
            -4.327125506371331,
        ),
        (
            6.16016391169858,
            5.911299556748989,
            -0.29207493670163975,
            1.0517407565802175,
            (0.9789858207551021, 0.38702052286287625, -0.24314685775343814),
            145.81718471493218,
            19.13096284123793,
        ),
    ],
    ids=["fuzz-1041", "fuzz-44"],
)
def test_prism_of_an_offset_ellipse_placed_at_random(
    a: float,
    b: float,
    offset: float,
    factor: float,
    axis: tuple[float, float, float],
    angle: float,
    shift: float,
) -> None:
    """build123d's offset of an ellipse, extruded, turned and moved (two build123d fuzz
    draws): its edges are offset curves split at the ellipse's vertices, one piece a few
    1e-5 long. Read through ``GeomAPI.To2d``'s Bezier approximation, the 2D MAT grew a
    second branch at a curvature maximum: 4 free edges 8.75e-2 diag off the boundary, and
    3.6e-3 diag unsound."""
    import build123d as bd

    sketch = bd.offset(bd.Ellipse(a / 2, b / 2), offset, kind=bd.Kind.ARC)
    face = sketch.faces()[0]
    solid = bd.extrude(face, factor * face.bounding_box().diagonal).solids()[0]
    solid = solid.rotate(bd.Axis((0, 0, 0), axis), angle).translate((shift,) * 3)
    result = M.extrusion_mat(solid.wrapped)
    assert result.counts()["branches"] == 1
    rep = M.check(solid.wrapped, result, f"offset ellipse prism {a:.2f}x{b:.2f}", n_complete=100)
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


@pytest.mark.parametrize("length", [1.0, 10.0])
def test_prism_of_a_profile_with_a_reflex_cusp(length: float) -> None:
    """A rectangle notched by two disks touching at a point (a reflex cusp, once refused
    as "cusp (zero angle)"): the cusp's edge is a reflex edge whose normals sweep a half
    turn. (The oracle read the disks' axes, equidistant from the whole of each disk's
    arc, as outside: its nearest point, the cusp edge, had the other face's normal.)"""
    solid = M.prism(F.cusped_notch(), length)
    result = M.extrusion_mat(solid)
    rep = M.check(solid, result, f"cusped notch prism L={length}", n_complete=100)
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


@pytest.mark.parametrize("length", [0.5, 5.0])
@pytest.mark.parametrize("centre", [(1.5, 0.2), (-1.2, -0.3)])
def test_prism_of_an_ellipse_with_a_hole_near_its_end(
    centre: tuple[float, float], length: float
) -> None:
    """A loop of the 2D MAT from a branch point back to it (round a hole near an end of an
    ellipse; FreeCAD fuzz seeds 40, 68 and 138): its sheets close on themselves, a ruling
    bounding the same sheet on both sides. Each such ruling got one pcurve, and OCC found
    the sheet unorientable ("traced wrong"): now it is the sheet's seam, with two."""
    face = F.ellipse_with_hole(centre=centre)
    solid = M.prism(face, length, F.random_placement(3, distance=80.0))
    result = M.extrusion_mat(solid)
    graph = result.mat2d.graph
    assert any(b.start == b.end and b.start is not None for b in graph.branches)  # the loop
    rep = M.check(solid, result, f"ellipse with a hole at {centre} L={length}", n_complete=100)
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


def test_prism_whose_arc_fan_starts_at_an_element_end() -> None:
    """FreeCAD fuzz seed 136 (its STEP as FreeCAD wrote it): a convex polygon less a
    heptagon and a triangle, rounded by offsets -0.56/+0.56, extruded 18.9. A curvature
    centre's fan over its arc started 4e-12 from the arc's end vertex: three rim rows
    4e-12 apart, and the rim interpolated on their chord length swung 0.016 off the
    node's circle (radius 4.7 tol off, soundness 11 tol). The fan's rows are now
    distinct (:func:`medialcad.mat3d.segments.distinct_rows`)."""
    from medialcad.mat3d.segments import distinct_rows
    from medialcad.recognition import read_step

    pts = np.array([[0.0, 0.0], [4e-12, 0.0], [4.4e-12, 0.0], [0.1, 0.0], [0.2, 1e-13]])
    assert distinct_rows(pts, 1e-6).tolist() == [0, 3, 4]
    (solid,) = read_step(Path(__file__).parent / "data" / "freecad_fuzz136_fan_prism.step")
    result = M.extrusion_mat(solid)
    rep = M.check(solid, result, "FreeCAD fuzz 136", n_complete=100)
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


@pytest.mark.parametrize("length", [3.0, 10.0])
def test_prism_through_an_arc_centre_found_within_the_tolerance(length: float) -> None:
    """The profile of FreeCAD fuzz seed 29, extruded. Its 2D MAT has a node at the centre
    of an arc whose disk crosses the next arc by 6e-6: a curvature centre, or a branch
    point of two branches, depending on the profile's frame. Either way the arc is seen
    once, by the node's fan up to where a branch's feet leave it (before: 4 free edges
    at 5e-2 diag and a seam bounding two sheets; L = 3: a crack 8e-5 diag wide)."""
    from medialcad.recognition import read_step, recognize

    (revolved,) = read_step(Path(__file__).parent / "data" / "freecad_fuzz29_arc_centre_pass.step")
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Vec

    rec = recognize(revolved)
    prism = BRepPrimAPI_MakePrism(rec.profile, gp_Vec(*(length * rec.frame.zdir)))
    solid = M.single_solid(prism.Shape())
    result = M.extrusion_mat(solid)
    rep = M.check(solid, result, f"FreeCAD fuzz 29 profile, L = {length:g}", n_complete=100)
    print(rep.line())
    assert not rep.failures(), "; ".join(rep.failures())


def test_a_contact_run_is_cut_where_a_branch_leaves_it() -> None:
    """A node's contact run (loop coordinates 1 -> 3) loses the part a branch at the
    node sweeps: from the branch's foot at the node the way its feet go, up to the next
    cut (a fillet shorter than eps on the node's circle is part of the run: the feet
    end at its joint); a foot within eps of the run's end is at it; feet elsewhere
    leave the run whole."""
    from medialcad.mat3d.segments import _uncovered

    runs = [(1.0, 3.0)]
    assert _uncovered(runs, [(2.0, 1.9, 2.9)], 10.0, 1e-3) == [(1.0, 2.0)]
    assert _uncovered(runs, [(2.0, 1.2, 2.05)], 10.0, 1e-3) == [(2.0, 3.0)]
    assert _uncovered(runs, [(1.0005, 1.0, 2.5)], 10.0, 1e-3) == []
    assert _uncovered(runs, [(1.5, 1.4, 2.5), (2.5, 2.5, 2.7)], 10.0, 1e-3) == [(1.0, 1.5)]
    assert _uncovered(runs, [(5.0, 4.0, 6.0)], 10.0, 1e-3) == runs
    # a run past the loop's seam (length 10) and a foot given in [0, 10)
    assert _uncovered([(9.0, 11.0)], [(0.5, 0.5, 0.9)], 10.0, 1e-3) == [(9.0, 10.5)]
