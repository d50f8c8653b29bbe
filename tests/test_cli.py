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
from medialcad.occ.shapes import edges

FACES = Path(__file__).resolve().parent.parent / "fixtures" / "step" / "faces"


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


def test_solid_is_refused_and_existing_output_kept(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    import cadquery as cq

    from medialcad.occ.io import write_step

    src = tmp_path / "box.step"
    write_step(cq.Workplane().box(1, 2, 3).val().wrapped, src)
    out = tmp_path / "out.step"
    out.write_text("precious")
    assert main([str(src), "-o", str(out)]) == 2
    assert "solid" in capsys.readouterr().err
    assert out.read_text() == "precious"


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
