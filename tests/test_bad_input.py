"""Bad and awkward input through the command line, as a user meets it: every case either
gives a medial axis that passes the oracles or a one-line error with exit code 2 and no
output left behind.

Cases: open and closed shells without a solid, a STEP of wires only, a truncated STEP, a
solid that is not valid (a profile crossing the revolution axis), features below the
tolerance (a sliver slot, a 1e-4 notch on a part of 100), coordinates around 1e5, a STEP
written in inches. (Missing/empty/non-STEP files, several solids, lofts and bumps:
``test_cli.py``; mutated files: ``test_robustness.py``.)
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import cadquery as cq
import numpy as np
import pytest
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing
from OCP.BRepPrimAPI import BRepPrimAPI_MakeRevol
from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt
from OCP.TopoDS import TopoDS_Shell, TopoDS_Solid

from medialcad.api import medial_axis
from medialcad.cli import main
from medialcad.errors import BelowToleranceError, OpenShellError
from medialcad.occ.io import write_brep, write_step
from medialcad.occ.shapes import faces
from medialcad.recognition import read_step, recognize
from tests.test_robustness import _check


def _run(src: Path, out: Path, *extra: str) -> tuple[int, str, str]:
    proc = subprocess.run(
        [sys.executable, "-m", "medialcad", str(src), "-o", str(out), *extra],
        capture_output=True,
        text=True,
        check=False,
    )
    return proc.returncode, proc.stdout, proc.stderr


def _refused(tmp_path: Path, src: Path, needle: str) -> str:
    """Exit 2, one line on stderr containing ``needle``, nothing but ``src`` in the folder."""
    code, _, err = _run(src, tmp_path / "out.step", "--report", str(tmp_path / "r.json"))
    assert code == 2, err
    line = err.strip()
    assert len(line.splitlines()) == 1 and "Traceback" not in line, line
    assert needle in line, line
    assert not (tmp_path / "out.step").exists() and not (tmp_path / "out.radius.json").exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]
    return line


def _sewn(shape_faces: list[Any]) -> Any:
    sew = BRepBuilderAPI_Sewing(1e-6)
    for f in shape_faces:
        sew.Add(f)
    sew.Perform()
    return sew.SewedShape()


BOX = cq.Workplane().box(10, 20, 30).val()


# --------------------------------------------------------------------------- shells, wires


def test_an_open_shell_is_not_a_solid(tmp_path: Path) -> None:
    src = tmp_path / "open.step"
    write_step([_sewn([f.wrapped for f in BOX.Faces()][:-1])], src)
    _refused(tmp_path, src, "is open: 4 free edge(s)")
    with pytest.raises(OpenShellError, match="is open"):
        read_step(src)


def test_a_closed_shell_without_a_solid_is_taken_as_the_solid_it_bounds(tmp_path: Path) -> None:
    src, out = tmp_path / "closed.step", tmp_path / "closed.mat.step"
    write_step([_sewn([f.wrapped for f in BOX.Faces()])], src)
    code, stdout, err = _run(src, out)
    assert code == 0, err
    assert "solid 1 of 1: extrusion" in stdout and "wall 10..10" in stdout
    (solid,) = read_step(src)
    mat = medial_axis(solid)
    snd, cmp_ = _check(solid, mat)
    assert max(snd, cmp_) <= mat.tol


def test_a_flat_sheet_of_faces_keeps_the_2d_behaviour(tmp_path: Path) -> None:
    """Coplanar faces sewn into one open shell: a file of faces, not a broken solid."""
    src = tmp_path / "flat.step"
    a = cq.Face.makeFromWires(cq.Wire.makePolygon([(0, 0, 0), (10, 0, 0), (10, 5, 0)], close=True))
    b = cq.Face.makeFromWires(cq.Wire.makePolygon([(0, 0, 0), (10, 5, 0), (0, 5, 0)], close=True))
    write_step([_sewn([a.wrapped, b.wrapped])], src)
    rep = tmp_path / "r.json"
    assert main([str(src), "-o", str(tmp_path / "f.step"), "--report", str(rep)]) == 0
    assert len(json.loads(rep.read_text())["faces"]) == 2


def test_a_file_of_wires_holds_nothing_to_do(tmp_path: Path) -> None:
    src = tmp_path / "wires.step"
    write_step([cq.Workplane().rect(10, 10).val().wrapped], src)
    _refused(tmp_path, src, "holds no solid and no face")


def test_a_truncated_step_file(tmp_path: Path) -> None:
    full = tmp_path / "full.step"
    write_step([BOX.wrapped], full)
    src = tmp_path / "cut.step"
    src.write_bytes(full.read_bytes()[: full.stat().st_size * 2 // 3])
    full.unlink()
    _refused(tmp_path, src, "cut.step")


# --------------------------------------------------------------------------- invalid solid


def _bow_tie() -> TopoDS_Solid:
    """A 'revolution' whose profile crosses the axis: x in [-5, 10] turned 90 degrees about
    y, built face by face (OCC's own revolve refuses it): two quarter cylinders meeting on
    the axis, not a valid solid."""
    axis = gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0))
    builder, shell, solid = BRep_Builder(), TopoDS_Shell(), TopoDS_Solid()
    builder.MakeShell(shell)
    for x0, x1 in ((0.0, 10.0), (-5.0, 0.0)):
        wire = cq.Wire.makePolygon([(x0, 0, 0), (x1, 0, 0), (x1, 20, 0), (x0, 20, 0)], close=True)
        piece = BRepPrimAPI_MakeRevol(cq.Face.makeFromWires(wire).wrapped, axis, math.pi / 2)
        for f in faces(piece.Shape()):
            builder.Add(shell, f)
    builder.MakeSolid(solid)
    builder.Add(solid, shell)
    return solid


def test_a_revolution_whose_profile_crosses_the_axis_is_refused(tmp_path: Path) -> None:
    src = tmp_path / "bow_tie.brep"  # BREP: the STEP reader would repair it into two solids
    write_brep(_bow_tie(), src)
    line = _refused(tmp_path, src, "neither an extrusion nor a revolution")
    assert "not a valid solid" in line


# --------------------------------------------------------------------------- tolerance


def _profile_solid(points: list[tuple[float, float]], tmp_path: Path, name: str) -> Path:
    src = tmp_path / f"{name}.step"
    write_step([cq.Workplane().polyline(points).close().extrude(10).val().wrapped], src)
    return src


SLOT = 1e-5  # a slot 30 deep and 1e-5 wide in a 100 x 50 block: thinner than tol (1.1e-3)
SLIVER = [
    (0.0, 0.0),
    (100.0, 0.0),
    (100.0, 50.0),
    (50 + SLOT / 2, 50.0),
    (50 + SLOT / 2, 20.0),
    (50 - SLOT / 2, 20.0),
    (50 - SLOT / 2, 50.0),
    (0.0, 50.0),
]


def _notch(depth: float) -> list[tuple[float, float]]:
    return [
        (0.0, 0.0),
        (100.0, 0.0),
        (100.0, 50.0),
        (50 + depth, 50.0),
        (50.0, 50.0 - depth),
        (50 - depth, 50.0),
        (0.0, 50.0),
    ]


def test_a_sliver_thinner_than_the_tolerance_is_refused(tmp_path: Path) -> None:
    src = _profile_solid(SLIVER, tmp_path, "sliver")
    line = _refused(tmp_path, src, "feature too small to resolve")
    assert "1e-05 long at (50, 20, 0)" in line


def test_a_feature_of_1e_6_of_the_part_is_refused_at_the_default_tolerance(
    tmp_path: Path,
) -> None:
    src = _profile_solid(_notch(1e-4), tmp_path, "notch")
    _refused(tmp_path, src, "smaller tol")
    with pytest.raises(BelowToleranceError, match="2 edge"):
        medial_axis(read_step(src)[0])


def test_a_small_feature_is_resolved_with_a_tolerance_below_it(tmp_path: Path) -> None:
    src = _profile_solid(_notch(1e-3), tmp_path, "notch")
    (solid,) = read_step(src)
    with pytest.raises(BelowToleranceError):
        medial_axis(solid)  # default tol 1.1e-3: the notch's edges are 1.4e-3
    mat = medial_axis(solid, tol=1e-4)
    snd, cmp_ = _check(solid, mat)
    assert max(snd, cmp_) <= mat.tol
    assert mat.counts()["branch_points"] == 4  # two more than the plain block: the notch's


# --------------------------------------------------------------------------- placement, units


@pytest.mark.parametrize("offset", [(1e5, -1e5, 1e5), (-2.5e5, 3e4, 0.0)])
def test_coordinates_around_1e5(offset: tuple[float, float, float]) -> None:
    solid = (
        cq.Workplane()
        .polyline([(0, 0), (30, 0), (30, 10), (10, 10), (10, 25), (0, 25)])
        .close()
        .extrude(6)
        .translate(offset)
        .val()
    )
    mat = medial_axis(solid)
    assert mat.tol == pytest.approx(1e-5 * mat.recognition.diag)
    snd, cmp_ = _check(solid, mat)
    assert max(snd, cmp_) <= mat.tol
    for j in mat.junctions:  # where they belong, not at the origin
        assert np.all(np.abs(j.point - np.array(offset) - (15, 12.5, 3)) <= (15, 12.5, 3))


INCH_WRITER = r"""
import sys, cadquery as cq
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Controller, STEPControl_Writer
STEPControl_Controller.Init_s()
assert Interface_Static.SetCVal_s("write.step.unit", "INCH")
w = STEPControl_Writer()
w.Transfer(cq.Workplane().box(1 * 25.4, 2 * 25.4, 6 * 25.4).val().wrapped, STEPControl_AsIs)
w.Write(sys.argv[1])
"""


def test_a_step_file_in_inches_is_read_in_millimetres(tmp_path: Path) -> None:
    """A 1 x 2 x 6 inch block: the report is in millimetres (what OCC reads), so the
    largest inscribed ball has radius 0.5 in = 12.7 mm and the wall is 25.4 mm."""
    src = tmp_path / "inch.step"
    subprocess.run([sys.executable, "-c", INCH_WRITER, str(src)], check=True)
    assert "CONVERSION_BASED_UNIT('INCH'" in src.read_text()
    rep = tmp_path / "r.json"
    assert main([str(src), "-o", str(tmp_path / "o.step"), "--report", str(rep)]) == 0
    (solid,) = json.loads(rep.read_text())["solids"]
    assert solid["rmax"] == pytest.approx(12.7, abs=solid["tol"])
    assert solid["thickness"]["min"] == pytest.approx(25.4, abs=2 * solid["tol"])
    assert recognize(read_step(src)[0]).diag == pytest.approx(25.4 * math.sqrt(41), rel=1e-6)
