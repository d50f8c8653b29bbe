"""The ``medialcad`` command: STEP in, STEP out, one-line errors, nothing half-written."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from medialcad.cli import main
from medialcad.occ.io import read_shapes
from medialcad.occ.shapes import edges, faces

FACES = Path(__file__).resolve().parent.parent / "fixtures" / "step" / "faces"
SOLIDS = FACES.parent / "solids"


def test_face_to_step_png_and_report(tmp_path: Path) -> None:
    out, png, rep = tmp_path / "mat.step", tmp_path / "mat.png", tmp_path / "r.json"
    rc = main(
        [str(FACES / "rectangle.step"), "-o", str(out), "--png", str(png), "--report", str(rep)]
    )
    assert rc == 0
    (shape,) = read_shapes(out)
    assert len(edges(shape)) == 5  # 4 diagonals + the middle segment
    report = json.loads(rep.read_text())
    (face,) = report["faces"]
    assert face["branch_points"] == 2 and face["convex_vertices"] == 4
    assert face["rmax"] == pytest.approx(10.0, abs=face["tol"])
    import matplotlib.image as mpimg

    img = mpimg.imread(png)
    assert img.shape[0] > 200 and img.shape[1] > 200
    assert np.std(img[..., :3]) > 0.05, "the picture is blank"
    assert oct(png.stat().st_mode & 0o777) != oct(0o600)


def test_brep_output(tmp_path: Path) -> None:
    out = tmp_path / "mat.brep"
    assert main([str(FACES / "ellipse.step"), "-o", str(out)]) == 0
    (shape,) = read_shapes(out)
    assert len(edges(shape)) == 1


@pytest.mark.parametrize(
    ("make_input", "needle"),
    [
        (lambda d: d / "missing.step", "no such file"),
        (lambda d: _write(d / "empty.step", ""), "empty"),
        (lambda d: _write(d / "text.step", "hello, not a STEP file\n"), "STEP"),
    ],
)
def test_bad_input_exit_2_one_line_nothing_written(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], make_input: object, needle: str
) -> None:
    src = make_input(tmp_path)  # type: ignore[operator]
    out = tmp_path / "out.step"
    assert main([str(src), "-o", str(out), "--png", str(tmp_path / "p.png")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and needle.lower() in err.lower(), err
    assert not out.exists() and not (tmp_path / "p.png").exists()
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


def test_console_script_runs_as_a_module(tmp_path: Path) -> None:
    out = tmp_path / "m.step"
    proc = subprocess.run(
        [sys.executable, "-m", "medialcad", str(FACES / "missing.step"), "-o", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and proc.stderr.count("\n") == 1


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


# --------------------------------------------------------------------------- solids


def _cli(*args: object) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "medialcad", *map(str, args)],
        capture_output=True,
        text=True,
        check=False,
    )


def _no_leftovers(folder: Path) -> None:
    hidden = [p.name for p in folder.iterdir() if p.name.startswith(".")]
    assert hidden == [], f"staging files left behind: {hidden}"


def test_an_oblique_prism_reports_its_caps_slant(tmp_path: Path) -> None:
    out, rep = tmp_path / "oblique.mat.step", tmp_path / "oblique.json"
    src = FACES.parent / "freecad" / "fc_oblique_extrusion.step"
    proc = _cli(src, "-o", out, "--report", rep)
    assert proc.returncode == 0, proc.stderr
    (solid,) = json.loads(rep.read_text())["solids"]
    assert solid["status"] == "ok" and solid["kind"] == "extrusion"
    d, m = np.array(solid["direction"]), np.array(solid["cap_normal"])
    assert 0.0 < float(d @ m) < 1.0 - 1e-6
    # FreeCAD's 40 x 25 rectangle swept along (10, 5, 40): 40,000 in volume, whichever
    # of its three edges the prism is read along
    caps = {1000.0, float(np.linalg.norm(np.cross([0, 25, 0], [10, 5, 40]))),
            float(np.linalg.norm(np.cross([40, 0, 0], [10, 5, 40])))}  # fmt: skip
    assert any(abs(a * solid["height"] - 40000.0) < 1e-6 * 40000.0 for a in caps)
    assert len(read_shapes(out)) == 1


def test_box_step_report_and_radius_sidecar(tmp_path: Path) -> None:
    out, rep = tmp_path / "out" / "box.mat.step", tmp_path / "box.json"
    proc = _cli(SOLIDS / "box.step", "-o", out, "--report", rep)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert "solid 1 of 1: extrusion" in proc.stdout
    (shape,) = read_shapes(out)
    assert "PRODUCT('solid-1-medial-axis'" in out.read_text()

    report = json.loads(rep.read_text())
    assert report["input"] == str(SOLIDS / "box.step") and report["status"] == "ok"
    (solid,) = report["solids"]
    assert solid["index"] == 1 and solid["status"] == "ok" and solid["kind"] == "extrusion"
    direction = np.array(solid["direction"])
    assert np.isclose(np.linalg.norm(direction), 1.0)
    # the box is 60 x 40 x 100: any axis is a valid extrusion direction
    axis = int(np.argmax(np.abs(direction)))
    assert solid["length"] == pytest.approx([60.0, 40.0, 100.0][axis])
    counts = solid["counts"]
    assert set(counts) == {
        "branches",
        "branch_points",
        "junctions",
        "seams",
        "sheets",
        "skeletal_edges",
    }
    assert counts["branch_points"] == 2 and counts["junctions"] == 4
    assert len(faces(shape)) == counts["sheets"]
    assert solid["rmax"] > 0 and solid["tol"] > 0
    # a clean B-rep: its own tolerance (1e-7) is far below tol, and is in the bound
    assert 0 < solid["input_tolerance"] < 1e-3 * solid["tol"]
    assert solid["error_bound"] == pytest.approx(solid["tol"] + solid["input_tolerance"])
    assert {"recognition", "total"} <= set(solid["timings"])

    radius = json.loads((out.parent / "box.mat.radius.json").read_text())  # the default
    assert radius["format"] == "medialcad-radius/1" and radius["kind"] == "extrusion"
    assert len(radius["sheets"]) == counts["sheets"]
    assert len(radius["junctions"]) == counts["junctions"]
    assert report["radius"] == str(out.parent / "box.mat.radius.json")
    _no_leftovers(out.parent)
    _no_leftovers(tmp_path)


def test_multi_solid_one_product_per_solid(tmp_path: Path) -> None:
    out, rep, rad = tmp_path / "m.step", tmp_path / "m.json", tmp_path / "radius" / "r.json"
    proc = _cli(SOLIDS / "multi_solid.step", "-o", out, "--report", rep, "--radius", rad)
    assert proc.returncode == 0, proc.stderr
    assert len(read_shapes(out)) == 2
    text = out.read_text()
    assert "PRODUCT('solid-1-medial-axis'" in text and "PRODUCT('solid-2-medial-axis'" in text
    report = json.loads(rep.read_text())
    assert [s["index"] for s in report["solids"]] == [1, 2]
    assert all(s["status"] == "ok" for s in report["solids"])
    # the box 30 x 20 x 20 and the cylinder r = 5 (its axis is a skeletal edge)
    assert report["solids"][1]["rmax"] == pytest.approx(5.0, abs=1e-6)
    assert report["solids"][1]["counts"]["skeletal_edges"] == 1
    radius = json.loads(rad.read_text())
    assert radius["format"] == "medialcad-radius-multi/1"
    assert [(s["index"], s["product"]) for s in radius["solids"]] == [
        (1, "solid-1-medial-axis"),
        (2, "solid-2-medial-axis"),
    ]
    assert not (tmp_path / "m.radius.json").exists()  # --radius replaces the default


def test_neither_solid_exit_2_nothing_written(tmp_path: Path) -> None:
    out, rep = tmp_path / "out.step", tmp_path / "r.json"
    out.write_text("precious")
    proc = _cli(SOLIDS / "loft.step", "-o", out, "--report", rep)
    assert proc.returncode == 2
    err = proc.stderr.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert "solid 1 of 1 refused" in err and "neither an extrusion nor a revolution" in err
    assert out.read_text() == "precious"
    assert not (tmp_path / "out.radius.json").exists()
    report = json.loads(rep.read_text())  # the report is the diagnostic: always written
    assert report["status"] == "refused" and report["written"] is False
    (solid,) = report["solids"]
    assert solid["index"] == 1 and solid["status"] == "refused"
    assert solid["error_type"] == "NotExtrusionOrRevolutionError"
    _no_leftovers(tmp_path)


def test_one_bad_solid_means_no_output_but_all_reported(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from medialcad.occ.io import write_step
    from medialcad.recognition import read_step

    src = tmp_path / "mixed.step"
    write_step(read_step(SOLIDS / "multi_solid.step")[1:] + read_step(SOLIDS / "loft.step"), src)
    out, rep = tmp_path / "mixed.mat.step", tmp_path / "r.json"
    assert main([str(src), "-o", str(out), "--report", str(rep)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "solid 2 of 2 refused" in err
    assert "solid 1" not in err
    assert not out.exists() and not out.with_suffix(".radius.json").exists()
    report = json.loads(rep.read_text())
    assert [(s["index"], s["status"]) for s in report["solids"]] == [(1, "ok"), (2, "refused")]
    assert report["solids"][0]["counts"]["skeletal_edges"] == 1


def test_debug_shows_the_traceback(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main([str(SOLIDS / "loft.step"), "-o", str(tmp_path / "o.step"), "--debug"]) == 2
    err = capsys.readouterr().err
    assert "Traceback" in err and "NotExtrusionOrRevolutionError" in err


def test_faces_only_file_keeps_the_2d_behaviour(tmp_path: Path) -> None:
    out, rep = tmp_path / "f.step", tmp_path / "f.json"
    assert main([str(SOLIDS / "faces_only.step"), "-o", str(out), "--report", str(rep)]) == 0
    assert len(json.loads(rep.read_text())["faces"]) == 2
    assert not (tmp_path / "f.radius.json").exists()  # no radius sidecar for faces


def test_solid_to_brep_without_radius(tmp_path: Path) -> None:
    out = tmp_path / "cyl.brep"
    proc = _cli(SOLIDS / "cylinder.step", "-o", out, "--format", "brep", "--no-radius")
    assert proc.returncode == 0, proc.stderr
    assert out.read_bytes().lstrip().startswith(b"DBRep_DrawableShape")
    (shape,) = read_shapes(out)
    assert len(faces(shape)) > 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cyl.brep"]


@pytest.mark.parametrize(
    ("make_input", "needle"),
    [
        (lambda d: d / "missing.step", "no such file"),
        (lambda d: _write(d / "empty.step", ""), "empty"),
        (lambda d: _write(d / "text.step", "hello, not a STEP file\n"), "STEP"),
        (lambda d: _write(d / "bad.step", "ISO-10303-21; garbage"), "could not be parsed"),
    ],
)
def test_bad_file_exit_2_one_line_existing_output_kept(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], make_input: object, needle: str
) -> None:
    src = make_input(tmp_path)  # type: ignore[operator]
    out = tmp_path / "out.step"
    out.write_text("precious")
    assert main([str(src), "-o", str(out), "--report", str(tmp_path / "r.json")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and needle.lower() in err.lower(), err
    assert out.read_text() == "precious" and not (tmp_path / "r.json").exists()
    _no_leftovers(tmp_path)


def test_bad_tol_and_clashing_paths_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    src = str(SOLIDS / "cube.step")
    assert main([src, "-o", str(tmp_path / "o.step"), "--tol", "-1"]) == 2
    assert "--tol must be a positive number" in capsys.readouterr().err
    o = str(tmp_path / "o.step")
    assert main([src, "-o", o, "--report", o]) == 2
    assert "must all differ" in capsys.readouterr().err
    assert main([src, "-o", src]) == 2
    assert "overwrite the input" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_help_documents_all_or_nothing(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        main(["--help"])
    assert exc.value.code == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "All or nothing" in text and ".radius.json" in text and "exit codes" in text
    assert "medialcad batch --help" in text


# --------------------------------------------------------------------------- thickness, viewer


def test_report_gives_the_plates_wall_thickness_and_where(tmp_path: Path) -> None:
    """A plate 2 thick (with a hole): min = max = 2, at balls centred on its mid-surface."""
    out, rep = tmp_path / "plate.step", tmp_path / "plate.json"
    proc = _cli(SOLIDS / "thin_plate.step", "-o", out, "--report", rep)
    assert proc.returncode == 0, proc.stderr
    (solid,) = json.loads(rep.read_text())["solids"]
    wall, tol = solid["thickness"], solid["tol"]
    assert wall["min"] == pytest.approx(2.0, abs=2 * tol)
    assert wall["max"] == pytest.approx(2.0, abs=2 * tol)
    for where in ("min_location", "max_location"):
        x, y, z = wall[where]
        assert 0 <= x <= 100 and 0 <= y <= 60 and z == pytest.approx(1.0, abs=tol)
        assert (x - 50) ** 2 + (y - 30) ** 2 >= 10**2 - tol
    assert wall["min_entity"] and wall["max_entity"]
    assert "thickness" in solid["timings"]
    assert "wall 2..2," in proc.stdout


def test_report_gives_the_tubes_wall_thickness(tmp_path: Path) -> None:
    """A tube with radii 20 and 15: its wall is 5; the largest inscribed ball too."""
    import cadquery as cq

    from medialcad.occ.io import write_step

    src = tmp_path / "tube.step"
    write_step([cq.Workplane().circle(20).circle(15).extrude(50).val().wrapped], src)
    rep = tmp_path / "t.json"
    assert main([str(src), "-o", str(tmp_path / "t.step"), "--report", str(rep)]) == 0
    (solid,) = json.loads(rep.read_text())["solids"]
    assert solid["thickness"]["min"] == pytest.approx(5.0, abs=2 * solid["tol"])
    assert solid["thickness"]["max"] == pytest.approx(5.0, abs=2 * solid["tol"])
    x, y, _ = solid["thickness"]["min_location"]
    assert np.hypot(x, y) == pytest.approx(17.5, abs=solid["tol"])


def test_no_thickness_skips_it(tmp_path: Path) -> None:
    rep = tmp_path / "c.json"
    args = [str(SOLIDS / "cube.step"), "-o", str(tmp_path / "c.step"), "--report", str(rep)]
    assert main([*args, "--no-thickness"]) == 0
    (solid,) = json.loads(rep.read_text())["solids"]
    assert "thickness" not in solid and "thickness" not in solid["timings"]


def test_html_viewer_of_a_solid(tmp_path: Path) -> None:
    from tests._browser import CHROMIUM, Attrs, console_errors, dump_dom

    out, page = tmp_path / "l.step", tmp_path / "view" / "l.html"
    proc = _cli(SOLIDS / "housing_bracket.step", "-o", out, "--html", page)
    assert proc.returncode == 0, proc.stderr
    assert str(page) in proc.stdout
    text = page.read_text()
    assert text.startswith("<!DOCTYPE html>") and "<script" in text
    assert "http://" not in text and "https://" not in text  # self-contained
    _no_leftovers(page.parent)
    if CHROMIUM is None:
        pytest.skip("chromium not installed: the page was written, not loaded")
    dom, log = dump_dom(page)
    attrs = Attrs()
    attrs.feed(dom)
    assert attrs.html.get("data-state") == "ok", attrs.html.get("data-error")
    assert not console_errors(log)
    assert int(attrs.html.get("data-pixels", "0")) > 20_000


def test_html_of_faces_is_refused_and_nothing_written(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out, page = tmp_path / "f.step", tmp_path / "f.html"
    assert main([str(SOLIDS / "faces_only.step"), "-o", str(out), "--html", str(page)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--html shows solids" in err
    assert list(tmp_path.iterdir()) == []


def test_a_refused_solid_writes_no_viewer(tmp_path: Path) -> None:
    page = tmp_path / "v.html"
    proc = _cli(
        SOLIDS / "loft.step", "-o", tmp_path / "o.step", "--html", page, "--png", tmp_path / "p.png"
    )
    assert proc.returncode == 2
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(("name", "meshes"), [("housing_bracket.step", 1), ("gear_wheel.step", 2)])
def test_png_and_html_share_one_mesh_when_it_fits_the_picture(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, name: str, meshes: int
) -> None:
    import medialcad.plot3d as plot3d

    budgets: list[int] = []
    real = plot3d.tessellate

    def counting(*args: object, max_triangles: int = 200_000, **kw: object) -> plot3d.Scene:
        budgets.append(max_triangles)
        return real(*args, max_triangles=max_triangles, **kw)  # type: ignore[arg-type]

    monkeypatch.setattr(plot3d, "tessellate", counting)
    png, page = tmp_path / "p.png", tmp_path / "v.html"
    args = [str(SOLIDS / name), "-o", str(tmp_path / "o.step"), "--png", str(png)]
    assert main([*args, "--html", str(page), "--no-thickness"]) == 0
    assert png.stat().st_size > 10_000 and page.stat().st_size > 10_000
    # the bracket's viewer mesh is small enough for the picture; the gear's is not
    assert len(budgets) == meshes
    assert budgets[-1] == (plot3d.PNG_MAX_TRIANGLES if meshes == 2 else budgets[0])


def test_a_brep_looser_than_tol_is_warned_about_and_bounded(tmp_path: Path) -> None:
    """A fuzzed 13-degree revolution whose revolved face stops 4e-5 short of its profile
    edge: OCC records vertex and edge tolerances up to 6.2e-5, twice tol. The medial axis
    is exact to tol for the recognised profile; the report's error bound adds the B-rep's
    own tolerance, and one warning line says so."""
    from OCP.BRepTools import BRepTools

    from tests import faces as F

    src = tmp_path / "critical.brep"
    assert BRepTools.Write_s(F.read_exact("revolution_critical_13deg_radius.bbrep"), str(src))
    out, rep = tmp_path / "critical.mat.step", tmp_path / "critical.json"
    proc = _cli(src, "-o", out, "--report", rep, "--no-thickness", "--no-radius")
    assert proc.returncode == 0, proc.stderr
    (line,) = proc.stderr.strip().splitlines()
    assert line.startswith("medialcad: WARNING: solid 1 of 1: its B-rep is only accurate to 6.2")
    (solid,) = json.loads(rep.read_text())["solids"]
    assert solid["input_tolerance"] == pytest.approx(6.2e-5, rel=0.02)
    assert solid["error_bound"] == pytest.approx(solid["tol"] + solid["input_tolerance"])
