"""The FreeCAD macro, run headless under ``freecadcmd`` against the real medialcad CLI.

A driver script (run by ``freecadcmd`` as a module, parameters in the environment)
builds a document, loads ``freecad/MedialAxis.FCMacro`` from its path, calls
``run(doc, objects, cli=[this python, "-m", "medialcad"])`` and dumps what was created as
JSON for the assertions.
"""

from __future__ import annotations

import ast
import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
MACRO = ROOT / "freecad" / "MedialAxis.FCMacro"
FREECADCMD = shutil.which("freecadcmd") or shutil.which("FreeCADCmd")

METADATA = (
    "__Name__",
    "__Comment__",
    "__Author__",
    "__Version__",
    "__Date__",
    "__License__",
    "__Web__",
    "__Wiki__",
    "__Icon__",
    "__Help__",
    "__Status__",
    "__Requires__",
    "__Communication__",
    "__Files__",
)

DRIVER = textwrap.dedent(
    """
    import importlib.machinery, importlib.util, json, os, time
    import FreeCAD as App
    import Part

    loader = importlib.machinery.SourceFileLoader("medial_axis_macro", os.environ["MA_MACRO"])
    spec = importlib.util.spec_from_loader("medial_axis_macro", loader)
    macro = importlib.util.module_from_spec(spec)
    loader.exec_module(macro)

    cli = json.loads(os.environ["MA_CLI"])
    which = os.environ["MA_OBJECTS"].split(",")
    doc = App.newDocument("MedialAxisTest")
    made = {}
    if "box" in which:
        box = doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 50, 20, 10
        made["box"] = box
    if "bump" in which:  # neither an extrusion nor a revolution
        bump = doc.addObject("Part::Feature", "Bump")
        bump.Shape = Part.makeBox(10, 10, 10).fuse(Part.makeSphere(4, App.Vector(5, 5, 10)))
        made["bump"] = bump
    if "pair" in which:  # two solids in one object
        pair = doc.addObject("Part::Feature", "Pair")
        pair.Shape = Part.makeCompound(
            [Part.makeBox(30, 30, 4), Part.makeCylinder(5, 20, App.Vector(60, 0, 0))]
        )
        made["pair"] = pair
    doc.recompute()

    out = {}
    t0 = time.time()
    out["results"] = macro.run(doc, [made[k] for k in which], cli=cli)
    out["seconds"] = time.time() - t0
    if os.environ.get("MA_MISSING"):
        out["missing_cli"] = macro.run(doc, [made[which[0]]], cli=["/nonexistent/medialcad"])

    def feature(o):
        d = {"name": o.Name, "label": o.Label, "type": o.TypeId, "shape": o.Shape.ShapeType}
        if o.Shape.ShapeType in ("Face", "Edge"):
            d["center"] = list(o.Shape.CenterOfMass)
        for p in ("MedialName", "Role", "Thickness", "ThicknessMin", "ThicknessMax"):
            if hasattr(o, p):
                v = getattr(o, p)
                d[p] = float(v) if p.startswith("Thickness") else v
        return d

    out["groups"] = [
        {
            "name": o.Name,
            "label": o.Label,
            "source": o.Source.Name,
            "children": [
                {"label": g.Label, "type": g.TypeId, "features": [feature(f) for f in g.Group]}
                for g in o.Group
            ],
        }
        for o in doc.Objects
        if o.TypeId == "App::DocumentObjectGroup" and hasattr(o, "Source")
    ]
    with open(os.environ["MA_OUT"], "w") as fh:
        json.dump(out, fh)
    """
)

# A stand-in for a CLI whose sidecar locates its curves: runs the real CLI, then adds
# "points" (start, middle, end) to every curve of the sidecar from the same computation.
POINTS_CLI = textwrap.dedent(
    """
    import json, sys
    from medialcad.cli import main

    argv = sys.argv[1:]
    rc = main(argv)
    if rc == 0:
        from OCP.BRepAdaptor import BRepAdaptor_Curve
        from medialcad.api import medial_axis
        from medialcad.recognition import read_step

        radius = argv[argv.index("--radius") + 1]
        (solid,) = read_step(argv[0])
        mat = medial_axis(solid)
        data = json.load(open(radius))
        for c in mat.seams + mat.skeletal_edges + mat.rims:
            a = BRepAdaptor_Curve(c.edge)
            t0, t1 = a.FirstParameter(), a.LastParameter()
            data["curves"][c.name]["points"] = [
                list(a.Value(t).Coord()) for t in (t0, 0.5 * (t0 + t1), t1)
            ]
        json.dump(data, open(radius, "w"))
    sys.exit(rc)
    """
)

needs_freecad = pytest.mark.skipif(FREECADCMD is None, reason="freecadcmd is not installed")


def _run_macro(tmp_path: Path, cli: list[str], objects: str, missing: bool = False) -> Any:
    assert FREECADCMD is not None
    driver = tmp_path / "driver.py"
    driver.write_text(DRIVER)
    out = tmp_path / "out.json"
    env = dict(
        os.environ,
        MA_MACRO=str(MACRO),
        MA_CLI=json.dumps(cli),
        MA_OBJECTS=objects,
        MA_OUT=str(out),
        MA_MISSING="1" if missing else "",
    )
    proc = subprocess.run(
        [FREECADCMD, str(driver)],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert out.exists(), f"the driver did not finish:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    return json.loads(out.read_text()), proc.stdout + proc.stderr


def _mat(shape_kind: str) -> Any:
    import cadquery as cq

    from medialcad.api import medial_axis

    if shape_kind == "box":
        return medial_axis(cq.Workplane().box(50, 20, 10))
    raise ValueError(shape_kind)


def _children(group: dict[str, Any]) -> dict[str, list[dict[str, Any]]]:
    return {c["label"].split(" (")[0]: c["features"] for c in group["children"]}


def test_macro_metadata() -> None:
    """FreeCAD-macros conventions: single-line string metadata at the top level."""
    tree = ast.parse(MACRO.read_text())
    found = {}
    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1:
            target = node.targets[0]
            if isinstance(target, ast.Name) and target.id in METADATA:
                assert isinstance(node.value, ast.Constant), target.id
                assert isinstance(node.value.value, str), target.id
                found[target.id] = node.value.value
    assert set(found) == set(METADATA)
    assert found["__Name__"] == "Medial Axis"
    for line in MACRO.read_text().splitlines():
        if line.startswith(METADATA):
            assert line.count("=") >= 1 and line.rstrip().endswith("'"), line  # one line each
    assert "def run(doc, objects, cli=None" in MACRO.read_text()


@needs_freecad
def test_macro_on_a_box_with_the_real_cli(tmp_path: Path) -> None:
    out, log = _run_macro(
        tmp_path, [sys.executable, "-m", "medialcad"], "box,bump,pair", missing=True
    )
    box_res, bump_res, pair_res = out["results"]
    assert "error" not in box_res, log
    assert "error" not in pair_res, log
    # the refused solid is reported, not raised, and adds nothing
    assert "neither an extrusion nor a revolution" in bump_res["error"]
    assert "Medial Axis: Bump:" in log
    (missing,) = out["missing_cli"]
    assert "cannot run /nonexistent/medialcad" in missing["error"]

    groups = {g["source"]: g for g in out["groups"]}
    assert set(groups) == {"Box", "Pair"}
    box = groups["Box"]
    assert box["label"] == "Box medial axis"
    kids = _children(box)
    assert list(kids) == ["Sheets", "Seams", "Junctions", "Skeletal edges"]
    assert all(c["type"] == "App::DocumentObjectGroup" for c in box["children"])

    mat = _mat("box")
    sheets = kids["Sheets"]
    assert [f["MedialName"] for f in sheets] == [s.name for s in mat.sheets]
    assert all(f["type"] == "Part::Feature" and f["shape"] == "Face" for f in sheets)
    assert all(f["ThicknessMin"] <= f["ThicknessMax"] == f["Thickness"] for f in sheets)
    # the thickest place is the 10 mm height; the mid sheet is 10 thick all over
    assert max(f["ThicknessMax"] for f in sheets) == pytest.approx(10.0, abs=1e-3)
    (mid,) = [f for f in sheets if f["ThicknessMin"] == pytest.approx(10.0, abs=1e-3)]
    assert mid["MedialName"] == next(s.name for s in mat.sheets if s.role == "mid")
    assert mid["center"] == pytest.approx([25.0, 10.0, 5.0], abs=1e-6)  # the mid plane
    assert min(f["ThicknessMin"] for f in sheets) == pytest.approx(0.0, abs=1e-6)  # rims
    assert len(kids["Seams"]) == len(mat.seams)
    assert all(f["shape"] == "Edge" for f in kids["Seams"])
    assert [f["MedialName"] for f in kids["Junctions"]] == [j.name for j in mat.junctions]
    assert all(f["Thickness"] == pytest.approx(10.0, abs=1e-3) for f in kids["Junctions"])
    assert kids["Skeletal edges"] == []

    # two solids in one object: one set of groups per solid
    pair = groups["Pair"]
    labels = [c["label"] for c in pair["children"]]
    assert "Sheets (Pair, solid 1)" in labels and "Skeletal edges (Pair, solid 2)" in labels
    pair_kids = {c["label"]: c["features"] for c in pair["children"]}
    plate = pair_kids["Sheets (Pair, solid 1)"]
    assert max(f["ThicknessMax"] for f in plate) == pytest.approx(4.0, abs=1e-3)
    (axis,) = pair_kids["Skeletal edges (Pair, solid 2)"]  # the cylinder's axis
    assert axis["Thickness"] == pytest.approx(10.0, abs=1e-3)


@needs_freecad
def test_macro_names_curves_when_the_sidecar_locates_them(tmp_path: Path) -> None:
    cli_script = tmp_path / "points_cli.py"
    cli_script.write_text(POINTS_CLI)
    out, log = _run_macro(tmp_path, [sys.executable, str(cli_script)], "box")
    (res,) = out["results"]
    assert "error" not in res, log
    kids = _children(out["groups"][0])
    mat = _mat("box")
    assert sorted(f["MedialName"] for f in kids["Seams"]) == sorted(s.name for s in mat.seams)
    by_name = {f["MedialName"]: f for f in kids["Seams"]}
    for seam in mat.seams:
        r = seam.radius(np.linspace(seam.knots[0], seam.knots[-1], 65))
        assert by_name[seam.name]["ThicknessMax"] == pytest.approx(2 * r.max(), abs=1e-3)
        assert by_name[seam.name]["ThicknessMin"] == pytest.approx(2 * r.min(), abs=1e-3)
