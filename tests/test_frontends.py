"""The cadquery and build123d front ends, used the way their users would."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from medialcad.errors import MedialCadError
from medialcad.occ.io import read_shapes
from medialcad.occ.shapes import faces

ROOT = Path(__file__).resolve().parent.parent


def _python(code: str) -> None:
    proc = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert proc.returncode == 0, proc.stderr


def _unique_edges(shape: Any) -> int:
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp
    from OCP.TopTools import TopTools_IndexedMapOfShape

    m = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, TopAbs_EDGE, m)
    return m.Extent()


# -- the core stays free of both ----------------------------------------------------
def test_core_does_not_import_cadquery_or_build123d() -> None:
    _python(
        "import sys, medialcad, medialcad.api, medialcad.thickness, medialcad.recognition\n"
        "assert 'cadquery' not in sys.modules, 'cadquery imported'\n"
        "assert 'build123d' not in sys.modules, 'build123d imported'\n"
    )


def test_cadquery_import_patches_nothing() -> None:
    _python(
        "import cadquery as cq\n"
        "before = set(vars(cq.Workplane)), set(vars(cq.Shape))\n"
        "import medialcad.cadquery\n"
        "assert (set(vars(cq.Workplane)), set(vars(cq.Shape))) == before\n"
        "assert not hasattr(cq.Workplane, 'medialAxis')\n"
    )


# -- cadquery -------------------------------------------------------------------------
@pytest.fixture(scope="module")
def cq_box() -> Any:
    import cadquery as cq

    from medialcad.api import medial_axis as core
    from medialcad.cadquery import medial_axis

    part = cq.Workplane("XZ").box(40, 20, 10)
    return part, medial_axis(part), core(part)


def test_cadquery_workplane_holds_the_complex(cq_box: Any) -> None:
    import cadquery as cq

    part, mat, result = cq_box
    assert isinstance(mat, cq.Workplane)
    assert mat.plane == part.plane  # stays on the input's workplane
    (comp,) = mat.vals()
    assert isinstance(comp, cq.Compound) and comp.label == "medial axis"
    assert len(comp.Faces()) == len(result.sheets)
    assert mat.faces(tag="sheets").size() == len(result.sheets)
    assert mat.edges(tag="seams").size() == len(result.seams)
    assert mat.edges(tag="rims").size() == len(result.rims)
    assert mat.vertices(tag="junctions").size() == len(result.junctions)
    assert mat.edges(tag="skeletal_edges").size() == len(result.skeletal_edges) == 0


def test_cadquery_entities_are_named_and_shared(cq_box: Any) -> None:
    from medialcad.cadquery import entities

    _, mat, result = cq_box
    named = entities(mat)
    assert set(named) == {name for _, name in result.names()}
    assert all(shape.label == name for name, shape in named.items())
    # the seams are edges of the sheets themselves, not copies
    assert _unique_edges(mat.val().wrapped) == _unique_edges(result.compound)
    seam_edges = [named[n].wrapped for n in named if n.startswith("seam-")]
    sheet_edges = [e.wrapped for f in mat.faces(tag="sheets").vals() for e in f.Edges()]
    assert all(any(s.IsSame(e) for e in sheet_edges) for s in seam_edges)


def test_cadquery_input_as_shape_and_exporters(tmp_path: Path) -> None:
    import cadquery as cq

    from medialcad.cadquery import medial_axis

    solid = cq.Workplane().circle(20).circle(15).extrude(50).val()  # a cq.Solid
    mat = medial_axis(solid)
    n_sheets = mat.faces(tag="sheets").size()
    assert n_sheets == 10
    cq.exporters.export(mat, str(tmp_path / "tube-mat.step"))
    cq.exporters.export(mat, str(tmp_path / "tube-mat.brep"))
    for name in ("tube-mat.step", "tube-mat.brep"):
        shapes = read_shapes(tmp_path / name)
        assert sum(len(faces(s)) for s in shapes) == n_sheets


def test_cadquery_register_is_opt_in() -> None:
    import cadquery as cq

    import medialcad.cadquery as mcq

    mcq.register()
    try:
        mcq.register()  # idempotent
        mat = cq.Workplane().box(100, 60, 4).medialAxis()  # type: ignore[attr-defined]
        assert mat.faces(tag="sheets").size() > 0
        assert mat.val().label == "medial axis"
    finally:
        mcq.unregister()
    assert not hasattr(cq.Workplane, "medialAxis")


def test_cadquery_not_an_extrusion() -> None:
    import cadquery as cq

    from medialcad.cadquery import medial_axis

    twisted = cq.Workplane().rect(10, 20).twistExtrude(30, 45)
    with pytest.raises(MedialCadError):
        medial_axis(twisted)


# -- build123d -------------------------------------------------------------------------
@pytest.fixture(scope="module")
def bd_box() -> Any:
    import build123d as bd

    from medialcad.api import medial_axis as core
    from medialcad.build123d import medial_axis

    part = bd.Box(40, 20, 10)
    return medial_axis(part), core(part)


def test_build123d_labelled_children(bd_box: Any) -> None:
    import build123d as bd

    mat, result = bd_box
    assert isinstance(mat, bd.Compound) and mat.label == "medial axis"
    groups = {c.label: c for c in mat.children}
    assert list(groups) == ["sheets", "seams", "skeletal_edges", "rims", "junctions"]
    assert all(isinstance(f, bd.Face) for f in groups["sheets"].children)
    assert all(isinstance(e, bd.Edge) for e in groups["seams"].children)
    assert all(isinstance(v, bd.Vertex) for v in groups["junctions"].children)
    assert [f.label for f in groups["sheets"].children] == [s.name for s in result.sheets]
    assert [e.label for e in groups["seams"].children] == [s.name for s in result.seams]
    assert [v.label for v in groups["junctions"].children] == [j.name for j in result.junctions]
    assert len(groups["skeletal_edges"].children) == 0
    assert len(mat.faces()) == len(result.sheets)


def test_build123d_sheets_share_their_edges(bd_box: Any) -> None:
    mat, result = bd_box
    # the seams/rims children add no edge: they are the sheets' own edges
    assert _unique_edges(mat.wrapped) == _unique_edges(result.compound)
    sheets, seams = mat.children[0], mat.children[1]
    sheet_edges = [e.wrapped for f in sheets.children for e in f.edges()]
    for seam in seams.children:
        assert sum(seam.wrapped.IsSame(e) for e in sheet_edges) >= 2  # 2+ sheets meet


def test_build123d_export_step(bd_box: Any, tmp_path: Path) -> None:
    import build123d as bd

    mat, result = bd_box
    out = tmp_path / "box-mat.step"
    assert bd.export_step(mat, str(out))
    text = out.read_text(errors="replace")
    assert "sheet-1" in text and "seams" in text
    assert sum(len(faces(s)) for s in read_shapes(out)) == len(result.sheets)


def test_build123d_cylinder_axis() -> None:
    import build123d as bd

    from medialcad.build123d import medial_axis

    mat = medial_axis(bd.Cylinder(10, 30))
    (axis,) = mat.children[2].children
    assert axis.label == "skeletal-1"
    assert axis.length == pytest.approx(10.0, abs=1e-6)  # 30 - 2 r
