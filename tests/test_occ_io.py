"""STEP/BREP reading and atomic writing (medialcad.occ.io)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeWire,
)
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeSphere
from OCP.Geom import Geom_OffsetCurve
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.gp import gp_Dir, gp_Pnt
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetFail, IFSelect_ReturnStatus
from OCP.Standard import Standard_Failure
from OCP.StdFail import StdFail_NotDone
from OCP.TColgp import TColgp_HArray1OfPnt
from OCP.TopoDS import TopoDS_Shape

import medialcad.occ.io as occ_io
from medialcad.errors import InputError, MedialCadError, OCCError, ReadError
from medialcad.occ import occ_guard, read_shapes, write_brep, write_step
from medialcad.occ.shapes import faces, solids

FIXED_TIME = "2000-01-01T00:00:00"


def _box(dx: float = 10.0, dy: float = 20.0, dz: float = 30.0) -> TopoDS_Shape:
    return BRepPrimAPI_MakeBox(dx, dy, dz).Shape()


def _volume(shape: TopoDS_Shape) -> float:
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return float(props.Mass())


def _leftovers(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.iterdir() if p.name.endswith(".tmp"))


# --------------------------------------------------------------------------- reading errors


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(ReadError, match="no such file"):
        read_shapes(tmp_path / "nope.step")


def test_directory(tmp_path: Path) -> None:
    with pytest.raises(ReadError, match="directory"):
        read_shapes(tmp_path)


@pytest.mark.parametrize("name", ["empty.step", "empty.brep"])
def test_empty_file(tmp_path: Path, name: str) -> None:
    (tmp_path / name).write_bytes(b"")
    with pytest.raises(ReadError, match="empty file"):
        read_shapes(tmp_path / name)


@pytest.mark.parametrize("name", ["notes.step", "notes.stp", "notes.brep"])
def test_text_file_is_not_step_or_brep(tmp_path: Path, name: str) -> None:
    (tmp_path / name).write_text("hello, this is not CAD data\n")
    with pytest.raises(ReadError, match=r"not a (STEP|BREP) file"):
        read_shapes(tmp_path / name)


def test_unknown_suffix(tmp_path: Path) -> None:
    (tmp_path / "part.iges").write_text("whatever\n")
    with pytest.raises(ReadError, match="unsupported file type"):
        read_shapes(tmp_path / "part.iges")


def test_truncated_step(tmp_path: Path) -> None:
    good = write_step(_box(), tmp_path / "good.step")
    text = good.read_text()
    bad = tmp_path / "bad.step"
    bad.write_text(text[: len(text) // 2])
    with pytest.raises(ReadError, match="could not be parsed"):
        read_shapes(bad)


def test_truncated_brep(tmp_path: Path) -> None:
    good = write_brep(_box(), tmp_path / "good.brep")
    text = good.read_text()
    bad = tmp_path / "bad.brep"
    bad.write_text(text[: len(text) // 2])
    with pytest.raises(ReadError):
        read_shapes(bad)


def test_step_without_shapes(tmp_path: Path) -> None:
    empty_model = tmp_path / "nothing.step"
    empty_model.write_text(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('x'),'2;1');\n"
        "FILE_NAME('x','2000-01-01T00:00:00',(''),(''),'','','');\n"
        "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\n"
        "DATA;\nENDSEC;\nEND-ISO-10303-21;\n"
    )
    with pytest.raises(ReadError, match="no shape"):
        read_shapes(empty_model)


def test_read_errors_are_input_errors(tmp_path: Path) -> None:
    with pytest.raises(InputError):
        read_shapes(tmp_path / "nope.stp")


def test_read_error_messages_are_one_line(tmp_path: Path) -> None:
    (tmp_path / "a.step").write_text("garbage")
    with pytest.raises(ReadError) as info:
        read_shapes(tmp_path / "a.step")
    assert "\n" not in str(info.value)
    assert "a.step" in str(info.value)


# --------------------------------------------------------------------------- round trips


@pytest.mark.parametrize("suffix", [".step", ".stp", ".STEP", ".brep"])
def test_round_trip_solid(tmp_path: Path, suffix: str) -> None:
    path = tmp_path / f"box{suffix}"
    writer = write_brep if suffix == ".brep" else write_step
    assert writer(_box(), path) == path
    (shape,) = read_shapes(path)
    assert len(solids(shape)) == 1
    assert len(faces(shape)) == 6
    assert _volume(shape) == pytest.approx(6000.0, rel=1e-9)
    assert _leftovers(tmp_path) == []


def test_round_trip_several_named(tmp_path: Path) -> None:
    path = tmp_path / "two.step"
    shapes = [_box(), BRepPrimAPI_MakeSphere(5.0).Shape()]
    write_step(shapes, path, names={0: "the_box", 1: "the_sphere"})
    back = read_shapes(path)
    assert len(back) == 2
    assert sorted(len(faces(s)) for s in back) == [1, 6]
    products = re.findall(r"PRODUCT\('([^']*)'", path.read_text())
    assert sorted(products) == ["the_box", "the_sphere"]


def test_header_is_reproducible(tmp_path: Path) -> None:
    a = write_step(_box(), tmp_path / "box.step", timestamp=FIXED_TIME)
    first = a.read_bytes()
    write_step(_box(), a, timestamp=FIXED_TIME)
    assert a.read_bytes() == first
    assert b"FILE_NAME('box.step','2000-01-01T00:00:00'" in first


def test_write_rejects_bad_arguments(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="no shapes"):
        write_step([], tmp_path / "x.step")
    with pytest.raises(ValueError, match="null"):
        write_step(TopoDS_Shape(), tmp_path / "x.step")
    with pytest.raises(ValueError, match="indices"):
        write_step(_box(), tmp_path / "x.step", names={3: "nope"})
    with pytest.raises(ValueError, match="null"):
        write_brep(TopoDS_Shape(), tmp_path / "x.brep")
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------- atomicity


class _FailingStepWriter:
    """Stands in for ``STEPCAFControl_Writer``: writes half a file, then fails."""

    def __init__(self, how: str) -> None:
        self.how = how

    def Write(self, path: str) -> IFSelect_ReturnStatus:
        Path(path).write_text("ISO-10303-21;\nHEADER;\n")
        if self.how == "raise":
            raise StdFail_NotDone("simulated failure half-way through the write")
        return IFSelect_RetFail


class _FailingBRepTools:
    """Stands in for ``OCP.BRepTools.BRepTools``: writes half a file, then fails."""

    @staticmethod
    def Write_s(_shape: TopoDS_Shape, path: str) -> bool:
        Path(path).write_text("DBRep_DrawableShape\n half")
        return False


@pytest.mark.parametrize("how", ["raise", "status"])
def test_failed_step_write_leaves_no_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, how: str
) -> None:
    target = tmp_path / "out.step"
    monkeypatch.setattr(occ_io, "_step_writer", lambda *_: (_FailingStepWriter(how), None))
    monkeypatch.setattr(occ_io, "_set_step_header", lambda *_, **__: None)
    monkeypatch.setattr(occ_io, "_check_step_transfer", lambda *_: None)
    with pytest.raises(OCCError, match=r"simulated|IFSelect_RetFail"):
        write_step(_box(), target)
    assert list(tmp_path.iterdir()) == []


def test_failed_brep_write_leaves_no_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(occ_io, "BRepTools", _FailingBRepTools)
    with pytest.raises(OCCError, match="OCC reported failure"):
        write_brep(_box(), tmp_path / "out.brep")
    assert list(tmp_path.iterdir()) == []


def test_failed_write_does_not_clobber(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    target = tmp_path / "precious.brep"
    write_brep(_box(1, 2, 3), target)
    before = target.read_bytes()
    monkeypatch.setattr(occ_io, "BRepTools", _FailingBRepTools)
    with pytest.raises(OCCError, match="OCC reported failure"):
        write_brep(_box(), target)
    assert target.read_bytes() == before
    assert _leftovers(tmp_path) == []


def test_failed_step_write_does_not_clobber(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    target = tmp_path / "precious.step"
    target.write_text("old contents\n")

    def boom(*_args: object) -> None:
        raise OSError("disk on fire")

    monkeypatch.setattr(occ_io.os, "replace", boom)
    with pytest.raises(OSError, match="disk on fire"):
        write_step(_box(), target)
    assert target.read_text() == "old contents\n"
    assert _leftovers(tmp_path) == []


def test_write_into_missing_directory(tmp_path: Path) -> None:
    with pytest.raises(OSError):
        write_step(_box(), tmp_path / "no" / "such" / "dir.step")


def test_overwrite_keeps_permissions(tmp_path: Path) -> None:
    target = tmp_path / "perm.step"
    write_step(_box(), target)
    target.chmod(0o640)
    write_step(_box(), target)
    assert target.stat().st_mode & 0o777 == 0o640


# --------------------------------------------------------------------------- occ_guard


def test_occ_guard_converts_stdfail() -> None:
    p = gp_Pnt(0, 0, 0)
    with (
        pytest.raises(OCCError, match=r"^making an edge: StdFail_NotDone") as info,
        occ_guard("making an edge"),
    ):
        BRepBuilderAPI_MakeEdge(p, p).Edge()
    assert isinstance(info.value.__cause__, StdFail_NotDone)
    # OCP exception classes are flat: StdFail_NotDone is NOT a Standard_Failure in Python.
    assert not isinstance(info.value.__cause__, Standard_Failure)


def test_occ_guard_converts_standard_errors() -> None:
    with (
        pytest.raises(OCCError, match="making a direction: Standard_ConstructionError"),
        occ_guard("making a direction"),
    ):
        gp_Dir(0, 0, 0)


def test_occ_guard_converts_plain_runtime_error() -> None:
    with pytest.raises(OCCError, match="ctx: boom"), occ_guard("ctx"):
        raise RuntimeError("boom")


@pytest.mark.parametrize(
    "err", [ValueError("v"), KeyError("k"), ReadError("r"), NotImplementedError()]
)
def test_occ_guard_passes_other_errors(err: Exception) -> None:
    with pytest.raises(type(err)), occ_guard("ctx"):
        raise err


def test_occ_error_is_a_medialcad_error() -> None:
    with pytest.raises(MedialCadError), occ_guard("ctx"):
        raise Standard_Failure("x")


def _offset_curve_face() -> TopoDS_Shape:
    """A face bounded in part by a Geom_OffsetCurve edge (OCCT cannot write it to STEP)."""
    pts = TColgp_HArray1OfPnt(1, 3)
    for i, (x, y) in enumerate([(0, 0), (10, 3), (20, 0)], start=1):
        pts.SetValue(i, gp_Pnt(x, y, 0))
    interp = GeomAPI_Interpolate(pts, False, 1e-9)
    interp.Perform()
    basis = interp.Curve()
    offset = Geom_OffsetCurve(basis, 1.0, gp_Dir(0, 0, 1))
    b0, b1 = basis.Value(basis.FirstParameter()), basis.Value(basis.LastParameter())
    o0, o1 = offset.Value(offset.FirstParameter()), offset.Value(offset.LastParameter())
    wire = BRepBuilderAPI_MakeWire()
    for e in [
        BRepBuilderAPI_MakeEdge(basis).Edge(),
        BRepBuilderAPI_MakeEdge(b1, o1).Edge(),
        BRepBuilderAPI_MakeEdge(offset.Reversed()).Edge(),
        BRepBuilderAPI_MakeEdge(o0, b0).Edge(),
    ]:
        wire.Add(e)
    return BRepBuilderAPI_MakeFace(wire.Wire(), True).Face()


def test_step_writer_silent_drop_is_an_error(tmp_path: Path) -> None:
    """OCCT reports success but writes no face for offset-curve edges; we refuse."""
    target = tmp_path / "offset.step"
    with pytest.raises(OCCError, match="dropped 1 of 1 faces"):
        write_step(_offset_curve_face(), target)
    with pytest.raises(OCCError, match="dropped 1 of 7 faces"):
        write_step([_box(), _offset_curve_face()], target)
    assert list(tmp_path.iterdir()) == []


def test_brep_keeps_offset_curves(tmp_path: Path) -> None:
    (shape,) = read_shapes(write_brep(_offset_curve_face(), tmp_path / "offset.brep"))
    assert len(faces(shape)) == 1


def test_assembly_instances_are_read_at_their_placements(tmp_path: Path) -> None:
    """A STEP assembly (one part placed twice, a nested sub-assembly) gives one solid per
    instance where the assembly puts it, and each instance's MAT lies in that placed solid
    (the oracles against the placed solid built here, not the one read back)."""
    import cadquery as cq

    from medialcad import medial_axis
    from tests import _mat3d as M

    box = cq.Workplane().box(10, 4, 2)
    tube = cq.Workplane().circle(3).circle(1).extrude(5)
    places = {
        "box": (box, cq.Location((20, 0, 0), (1, 1, 0), 30)),
        "tube1": (tube, cq.Location((0, 10, 0))),
        "tube2": (tube, cq.Location((0, -10, 5), (1, 0, 0), 90)),
    }
    asm = cq.Assembly()
    for name, (part, loc) in places.items():
        asm.add(part, name=name, loc=loc)
    sub = cq.Assembly().add(box, name="inner", loc=cq.Location((0, 0, 30)))
    asm.add(sub, name="sub", loc=cq.Location((5, 5, 5)))
    path = tmp_path / "assembly.step"
    asm.export(str(path))
    expected = [part.val().moved(loc) for part, loc in places.values()]
    expected.append(box.val().moved(cq.Location((5, 5, 35))))
    read = [s for shape in read_shapes(path) for s in solids(shape)]
    assert len(read) == len(expected)
    for want in expected:
        c = want.Center()
        near = [s for s in read if (cq.Shape.cast(s).Center() - c).Length < 1e-6]
        assert len(near) == 1, f"no instance at {c}"
        assert _volume(near[0]) == pytest.approx(want.Volume(), rel=1e-9)
        result = medial_axis(near[0])
        rep = M.check(want.wrapped, result, f"instance at {c}", n_complete=40)
        assert not rep.failures(), "; ".join(rep.failures())
