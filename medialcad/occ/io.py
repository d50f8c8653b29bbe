"""Reading and writing STEP/BREP files, and turning OCC failures into :class:`OCCError`.

Reading never returns a partial result: every problem becomes a :class:`ReadError` with a
one-line message naming the file. Writing is atomic: the file is written to a temporary
file in the target directory and moved into place with :func:`os.replace`, so a failed
write never leaves a half-written file behind and never clobbers an existing target.

OCP exception classes (``Standard_Failure``, ``StdFail_NotDone``, ...) are *not* a Python
class hierarchy: each derives directly from :class:`Exception`, so catching
``Standard_Failure`` does not catch ``StdFail_NotDone``. :func:`occ_guard` therefore
recognises them by the module they come from.
"""

from __future__ import annotations

import logging
import os
import re
import tempfile
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
from OCP.BRep import BRep_Builder
from OCP.BRepTools import BRepTools
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.Message import Message
from OCP.STEPCAFControl import STEPCAFControl_Controller, STEPCAFControl_Writer
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader
from OCP.StepGeom import StepGeom_Placement
from OCP.StepShape import StepShape_FaceSurface, StepShape_ShapeRepresentation
from OCP.TCollection import TCollection_ExtendedString, TCollection_HAsciiString
from OCP.TDataStd import TDataStd_Name
from OCP.TDocStd import TDocStd_Document
from OCP.TopoDS import TopoDS_Shape
from OCP.XCAFDoc import XCAFDoc_DocumentTool

from medialcad.errors import MedialCadError, OCCError, ReadError
from medialcad.occ.shapes import compound, faces

__all__ = [
    "BREP_SUFFIXES",
    "STEP_SUFFIXES",
    "is_occ_exception",
    "occ_guard",
    "quiet_messenger",
    "read_shapes",
    "write_brep",
    "write_step",
]

log = logging.getLogger(__name__)

STEP_SUFFIXES = frozenset({".step", ".stp"})
BREP_SUFFIXES = frozenset({".brep", ".brp"})

_STEP_MAGIC = b"ISO-10303-21"
_BREP_MAGICS = (b"DBRep_DrawableShape", b"CASCADE Topology")
_SNIFF_BYTES = 512


# --------------------------------------------------------------------------- OCC errors


def is_occ_exception(err: BaseException) -> bool:
    """Whether ``err`` was raised by OpenCascade.

    OCP maps every ``Standard_Failure`` subclass to its own Python class deriving directly
    from :class:`Exception` (module ``OCP.OCP.<Package>``); C++ exceptions that are not
    ``Standard_Failure`` surface through pybind11 as a plain :class:`RuntimeError`.

    Args:
        err: Any exception.

    Returns:
        True for OCP exception types and for exact :class:`RuntimeError` instances.
    """
    cls = type(err)
    module = cls.__module__ or ""
    return module == "OCP" or module.startswith("OCP.") or cls is RuntimeError


def _describe_occ(err: BaseException) -> str:
    message = str(err).strip()
    name = type(err).__name__
    if not message:
        return name
    if isinstance(err, RuntimeError) and type(err) is RuntimeError:
        return message
    return f"{name}: {message}"


@contextmanager
def occ_guard(context: str) -> Iterator[None]:
    """Turn OpenCascade failures raised inside the block into :class:`OCCError`.

    Example:
        >>> with occ_guard("making the profile edge"):  # doctest: +SKIP
        ...     edge = BRepBuilderAPI_MakeEdge(p, p).Edge()
        OCCError: making the profile edge: StdFail_NotDone: BRep_API: command not done

    Args:
        context: What was being done, used as the message prefix.

    Raises:
        OCCError: If an OCP exception (``Standard_Failure`` and every other OCCT exception
            class, or a bare pybind11 ``RuntimeError``) escapes the block. Other
            exceptions, including every :class:`MedialCadError`, pass through unchanged.
    """
    try:
        yield
    except MedialCadError:
        raise
    except Exception as err:
        if not is_occ_exception(err):
            raise
        raise OCCError(f"{context}: {_describe_occ(err)}") from err


@contextmanager
def quiet_messenger() -> Iterator[None]:
    """Silence OCCT's default messenger (the coloured STEP statistics) inside the block.

    The printers are detached from ``Message::DefaultMessenger()`` and re-attached on exit,
    so global OCCT state is left as it was found.
    """
    messenger = Message.DefaultMessenger_s()
    printers = messenger.Printers()
    saved = [printers.Value(i) for i in range(1, printers.Length() + 1)]
    for printer in saved:
        messenger.RemovePrinter(printer)
    try:
        yield
    finally:
        for printer in saved:
            messenger.AddPrinter(printer)


# --------------------------------------------------------------------------- reading


def read_shapes(path: str | os.PathLike[str]) -> list[TopoDS_Shape]:
    """Read every root shape of a STEP (``.step``/``.stp``) or BREP (``.brep``/``.brp``) file.

    Args:
        path: The file to read; the suffix (case-insensitive) selects the format.

    Returns:
        The transferred root shapes, in file order (never empty, never null shapes).

    Raises:
        ReadError: The file is missing, is a directory, is empty, has an unknown suffix,
            is not a STEP/BREP file, cannot be parsed (e.g. truncated), or yields no shape.
    """
    p = Path(path)
    if not p.exists():
        raise ReadError(f"{p}: no such file")
    if p.is_dir():
        raise ReadError(f"{p}: is a directory, not a file")
    try:
        with p.open("rb") as fh:
            head = fh.read(_SNIFF_BYTES)
    except OSError as err:
        raise ReadError(f"{p}: cannot be read ({err.strerror or err})") from err
    if not head.strip():
        raise ReadError(f"{p}: empty file")
    suffix = p.suffix.lower()
    if suffix in STEP_SUFFIXES:
        return _read_step(p, head)
    if suffix in BREP_SUFFIXES:
        return _read_brep(p, head)
    raise ReadError(
        f"{p}: unsupported file type {suffix or '(no suffix)'!r}; expected .step, .stp or .brep"
    )


def _strip_bom(head: bytes) -> bytes:
    return head.removeprefix(b"\xef\xbb\xbf").lstrip()


def _read_step(p: Path, head: bytes) -> list[TopoDS_Shape]:
    if not _strip_bom(head).startswith(_STEP_MAGIC):
        raise ReadError(f"{p}: not a STEP file (no ISO-10303-21 header)")
    reader = STEPControl_Reader()
    try:
        with quiet_messenger():
            status = reader.ReadFile(str(p))
            if status != IFSelect_RetDone:
                raise ReadError(f"{p}: STEP file could not be parsed (truncated or corrupt)")
            reader.TransferRoots()
            shapes = [reader.Shape(i) for i in range(1, reader.NbShapes() + 1)]
    except MedialCadError:
        raise
    except Exception as err:
        if not is_occ_exception(err):
            raise
        raise ReadError(f"{p}: STEP file could not be read ({_describe_occ(err)})") from err
    shapes = [s for s in shapes if not s.IsNull()]
    if not shapes:
        raise ReadError(f"{p}: no shape could be transferred from the STEP file")
    log.debug("read %d shape(s) from %s", len(shapes), p)
    return shapes


def _read_brep(p: Path, head: bytes) -> list[TopoDS_Shape]:
    if not _strip_bom(head).startswith(_BREP_MAGICS):
        raise ReadError(f"{p}: not a BREP file (no OpenCascade topology header)")
    # OCC's BREP reader can loop forever on a truncated file: a complete one ends with the
    # root shape's reference ("+1 1"), so anything else is refused before OCC sees it
    tail = p.read_bytes()[-256:].split(b"\n")
    last = next((ln.strip() for ln in reversed(tail) if ln.strip()), b"")
    if not re.fullmatch(rb"[+\-]\d+ \d+", last):
        raise ReadError(f"{p}: BREP file could not be parsed (truncated or corrupt)")
    shape = TopoDS_Shape()
    try:
        with quiet_messenger():
            ok = BRepTools.Read_s(shape, str(p), BRep_Builder())
    except Exception as err:
        if not is_occ_exception(err):
            raise
        raise ReadError(f"{p}: BREP file could not be read ({_describe_occ(err)})") from err
    if not ok:
        raise ReadError(f"{p}: BREP file could not be parsed (truncated or corrupt)")
    if shape.IsNull():
        raise ReadError(f"{p}: the BREP file holds no shape")
    log.debug("read 1 shape from %s", p)
    return [shape]


# --------------------------------------------------------------------------- writing


def write_step(
    shapes: TopoDS_Shape | Sequence[TopoDS_Shape],
    path: str | os.PathLike[str],
    names: Mapping[int, str] | None = None,
    *,
    timestamp: str | None = None,
) -> Path:
    """Write shapes to a STEP (AP214) file atomically, one top-level product per shape.

    Args:
        shapes: One shape, or a sequence of shapes; each becomes a free root product.
        path: Target file; written via a temporary file in the same directory.
        names: Optional product names keyed by the index of the shape in ``shapes``
            (``{0: "medial_axis"}``); unnamed shapes get OCC's default product name.
        timestamp: Fixed ``FILE_NAME`` time stamp (e.g. ``"2000-01-01T00:00:00"``) for
            byte-reproducible files; ``None`` keeps OCC's current time.

    Returns:
        The path written.

    Raises:
        ValueError: No shapes, a null shape, or a name key that is not a shape index.
        OCCError: OCC failed to transfer or to write the model.
        OSError: The temporary file could not be created or moved into place.
    """
    shape_list = _as_shape_list(shapes)
    names = dict(names or {})
    bad = sorted(k for k in names if not (isinstance(k, int) and 0 <= k < len(shape_list)))
    if bad:
        raise ValueError(f"names keys must be shape indices 0..{len(shape_list) - 1}, got {bad}")
    target = Path(path)
    with occ_guard(f"writing STEP file {target}"), quiet_messenger():
        writer, _doc = _step_writer(shape_list, names)  # _doc: keep the document alive
        _check_step_transfer(writer, shape_list, target)
        _set_step_header(writer, name=target.name, timestamp=timestamp)
        with _atomic_target(target) as tmp:
            status = writer.Write(str(tmp))
            if status != IFSelect_RetDone:
                raise OCCError(f"writing STEP file {target}: OCC returned {status.name}")
    log.debug("wrote %d shape(s) to %s", len(shape_list), target)
    return target


def write_brep(shape: TopoDS_Shape, path: str | os.PathLike[str]) -> Path:
    """Write one shape to an OCC BREP file atomically.

    Args:
        shape: The shape to write (compound several shapes first).
        path: Target file; written via a temporary file in the same directory.

    Returns:
        The path written.

    Raises:
        ValueError: The shape is null.
        OCCError: OCC failed to write the file.
        OSError: The temporary file could not be created or moved into place.
    """
    (shape,) = _as_shape_list(shape)
    target = Path(path)
    with (
        occ_guard(f"writing BREP file {target}"),
        quiet_messenger(),
        _atomic_target(target) as tmp,
    ):
        if not BRepTools.Write_s(shape, str(tmp)):
            raise OCCError(f"writing BREP file {target}: OCC reported failure")
    log.debug("wrote 1 shape to %s", target)
    return target


def _as_shape_list(shapes: TopoDS_Shape | Sequence[TopoDS_Shape]) -> list[TopoDS_Shape]:
    shape_list = [shapes] if isinstance(shapes, TopoDS_Shape) else list(shapes)
    if not shape_list:
        raise ValueError("nothing to write: no shapes given")
    for i, shape in enumerate(shape_list):
        if not isinstance(shape, TopoDS_Shape):
            raise ValueError(f"shape {i} is a {type(shape).__name__}, not a TopoDS_Shape")
        if shape.IsNull():
            raise ValueError(f"shape {i} is a null shape")
    return shape_list


def _step_writer(
    shapes: list[TopoDS_Shape], names: Mapping[int, str]
) -> tuple[STEPCAFControl_Writer, TDocStd_Document]:
    """Transfer the shapes into an XCAF document (to carry product names) and a writer."""
    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    shape_tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    for i, shape in enumerate(shapes):
        label = shape_tool.AddShape(shape, False)
        if i in names:
            TDataStd_Name.Set_s(label, TCollection_ExtendedString(names[i]))
    writer = STEPCAFControl_Writer()
    if not writer.Transfer(doc, STEPControl_AsIs):
        raise OCCError("STEP transfer failed")
    return writer, doc


def _check_step_transfer(
    writer: STEPCAFControl_Writer, shapes: list[TopoDS_Shape], target: Path
) -> None:
    """Fail if OCC silently dropped geometry during the transfer.

    OCCT's STEP writer reports success but leaves out faces it cannot translate (e.g. a
    face bounded by a ``Geom_OffsetCurve`` edge), so count what reached the model.
    """
    model = writer.ChangeWriter().Model()
    entities = [model.Value(i) for i in range(1, model.NbEntities() + 1)]
    # isinstance, not IsKind: IsKind costs milliseconds per entity through OCP
    faces_out = sum(1 for e in entities if isinstance(e, StepShape_FaceSurface))
    faces_in = len(faces(compound(shapes)))
    if faces_out < faces_in:
        raise OCCError(
            f"writing STEP file {target}: OCC dropped {faces_in - faces_out} of {faces_in} "
            "faces (unsupported geometry such as offset curves?)"
        )
    if faces_in == 0 and not any(_has_geometry(e) for e in entities):
        raise OCCError(f"writing STEP file {target}: OCC transferred no geometry")


def _has_geometry(entity: Any) -> bool:
    """Whether a STEP entity is a shape representation holding more than placements."""
    if not isinstance(entity, StepShape_ShapeRepresentation):
        return False
    items = entity.Items()
    return any(
        not isinstance(items.Value(j), StepGeom_Placement)
        for j in range(items.Lower(), items.Upper() + 1)
    )


def _set_step_header(writer: STEPCAFControl_Writer, *, name: str, timestamp: str | None) -> None:
    """Set FILE_NAME's name (the target's, not the temp file's) and optionally its time."""
    model = writer.ChangeWriter().Model()
    header = APIHeaderSection_MakeHeader(model)
    header.SetName(TCollection_HAsciiString(name))
    if timestamp is not None:
        header.SetTimeStamp(TCollection_HAsciiString(timestamp))
    header.Apply(model)


def _new_file_mode() -> int:
    """Permissions for a new file (``0o666`` less the umask), without touching the umask."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return 0o666 & ~int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    return 0o644


@contextmanager
def _atomic_target(target: Path) -> Iterator[Path]:
    """Yield a temporary path next to ``target``; move it onto ``target`` if the block succeeds.

    On any exception (or an empty result) the temporary file is removed and ``target`` is
    left untouched.
    """
    directory = target.parent if str(target.parent) else Path(".")
    fd, tmp_name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=directory)
    os.close(fd)
    tmp = Path(tmp_name)
    try:
        yield tmp
        if tmp.stat().st_size == 0:
            raise OCCError(f"writing {target}: OCC wrote an empty file")
        mode = target.stat().st_mode & 0o7777 if target.exists() else _new_file_mode()
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def write_step_named(
    shape: TopoDS_Shape,
    named: Sequence[tuple[TopoDS_Shape, str]],
    path: str | os.PathLike[str],
    *,
    name: str = "medial_axis",
    timestamp: str | None = None,
) -> Path:
    """Write one shape to STEP with names on its sub-shapes (XCAF sub-shape labels).

    A viewer that reads STEP names (FreeCAD, CAD Assistant) shows ``sheet-1``,
    ``seam-1``, ... on the faces, edges and vertices given in ``named``.
    """
    target = Path(path)
    with occ_guard(f"writing STEP file {target}"), quiet_messenger():
        doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
        shape_tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
        label = shape_tool.AddShape(shape, False)
        TDataStd_Name.Set_s(label, TCollection_ExtendedString(name))
        for sub, sub_name in named:
            sub_label = shape_tool.AddSubShape(label, sub)
            if not sub_label.IsNull():
                TDataStd_Name.Set_s(sub_label, TCollection_ExtendedString(sub_name))
        # sub-shape names are written only with this switch (after the controller's init)
        STEPCAFControl_Controller.Init_s()
        Interface_Static.SetIVal_s("write.stepcaf.subshapes.name", 1)
        writer = STEPCAFControl_Writer()
        writer.SetNameMode(True)
        if not writer.Transfer(doc, STEPControl_AsIs):
            raise OCCError("STEP transfer failed")
        _check_step_transfer(writer, [shape], target)
        _set_step_header(writer, name=target.name, timestamp=timestamp)
        with _atomic_target(target) as tmp:
            status = writer.Write(str(tmp))
            if status != IFSelect_RetDone:
                raise OCCError(f"writing STEP file {target}: OCC returned {status.name}")
    return target


def atomic_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write a text file atomically (nothing is left behind on failure)."""
    target = Path(path)
    with _atomic_target(target) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return target
