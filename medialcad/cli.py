"""Command line: ``medialcad INPUT -o OUTPUT [options]`` and ``medialcad batch IN_DIR -o OUT_DIR``.

Every solid of ``INPUT`` gets its 3D medial axis (extrusions and revolutions); a file of
planar faces without any solid gets the 2D medial axis of every face.

Exit codes: 0 success, 2 the input (or one of its solids) cannot be handled
(:class:`InputError`), 1 an internal failure, 130 interrupted. Errors are one line on
stderr (a traceback only with ``--debug``).

Outputs are all-or-nothing: the medial axis, its radius sidecar, the picture and the
report are written to a staging folder beside their targets and moved into place together
at the end, only when every solid succeeded. A failed run leaves no output behind and never
clobbers an existing file -- except the ``--report``, which is written on a refusal too
(it is the diagnostic: it says which solid failed and why).
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import os
import shutil
import sys
import tempfile
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from types import TracebackType
from typing import Any

from medialcad.errors import InputError, MedialCadError

__all__ = ["Conversion", "convert", "default_radius_path", "main", "solid_product_name"]

log = logging.getLogger(__name__)

_DESCRIPTION = """\
Exact medial axis transform (MAT) of CAD solids and faces: STEP/BREP in, STEP/BREP out.

Every solid in INPUT is processed (extrusions and revolutions); a file holding planar
faces and no solid gets the 2D medial axis of every face instead.

Output: one STEP product per solid, named solid-N-medial-axis (N = 1, 2, ... in file
order). With a single solid the sheets, seams, junctions, skeletal edges and rims are
named too (sheet-1, seam-1, ...; the names used by the radius sidecar).

All or nothing: if any solid cannot be handled, no medial axis and no sidecar is written
(an existing OUTPUT is left untouched); the --report is still written and lists every
solid with its status ("ok", "refused" or "failed") and the reason.

Run 'medialcad batch --help' for folders of STEP files."""

_EPILOG = """\
radius sidecar (solids only): the radius function of every named entity, as JSON; by
default OUTPUT with its suffix replaced by .radius.json (out/part.step ->
out/part.radius.json). With several solids it holds {"solids": [...]}, one entry per solid.

exit codes: 0 success; 2 the input or one of its solids cannot be handled (one line on
stderr naming the solid); 1 an internal failure; 130 interrupted."""


# --------------------------------------------------------------------------- arguments


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="medialcad",
        description=_DESCRIPTION,
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("input", metavar="INPUT", help="STEP (.step/.stp) or BREP (.brep) file")
    p.add_argument(
        "-o", "--output", metavar="OUTPUT", required=True, help="medial axis output file"
    )
    p.add_argument(
        "--tol",
        metavar="T",
        type=float,
        default=None,
        help="absolute fit tolerance (default 1e-5 x bounding-box diagonal)",
    )
    p.add_argument(
        "--format",
        choices=("step", "brep"),
        default=None,
        help="output format (default: by the suffix of OUTPUT; .brep/.brp is BREP)",
    )
    p.add_argument("--report", metavar="REPORT.json", default=None, help="write a JSON report here")
    radius = p.add_mutually_exclusive_group()
    radius.add_argument(
        "--radius",
        metavar="RADIUS.json",
        default=None,
        help="radius sidecar file (solids; default OUTPUT with suffix .radius.json)",
    )
    radius.add_argument("--no-radius", action="store_true", help="do not write a radius sidecar")
    p.add_argument(
        "--png",
        metavar="PICTURE.png",
        default=None,
        help="picture: the first solid and its 3D medial axis coloured by radius beside its profile's 2D axis (or the 2D axis of the first face)",
    )
    p.add_argument(
        "--html",
        metavar="VIEWER.html",
        default=None,
        help="self-contained interactive 3D viewer of the first solid and its medial axis (solids only)",
    )
    p.add_argument(
        "--no-thickness",
        action="store_true",
        help="skip the minimum/maximum wall thickness (about doubles the time otherwise spent on a solid)",
    )
    p.add_argument("--debug", action="store_true", help="show tracebacks")
    return p


def default_radius_path(output: str | os.PathLike[str]) -> Path:
    """Where the radius sidecar of ``output`` goes by default: ``out/part.step`` ->
    ``out/part.radius.json``."""
    return Path(output).with_suffix(".radius.json")


def solid_product_name(index: int) -> str:
    """STEP product name of the medial axis of solid ``index`` (1-based)."""
    return f"solid-{index}-medial-axis"


# --------------------------------------------------------------------------- staging


class _Staging:
    """Files written into hidden staging folders beside their targets, moved into place
    together by :meth:`commit`; whatever was not committed is removed on exit."""

    def __init__(self) -> None:
        self._dirs: dict[Path, Path] = {}
        self._pairs: list[tuple[Path, Path]] = []

    def __enter__(self) -> _Staging:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        for d in self._dirs.values():
            shutil.rmtree(d, ignore_errors=True)

    def path(self, target: Path) -> Path:
        """A temporary path with ``target``'s name (so STEP headers carry the right name)."""
        parent = target.parent.absolute()
        if parent not in self._dirs:
            parent.mkdir(parents=True, exist_ok=True)
            self._dirs[parent] = Path(tempfile.mkdtemp(prefix=".medialcad-stage-", dir=parent))
        tmp = self._dirs[parent] / target.name
        self._pairs.append((tmp, target))
        return tmp

    def commit(self) -> list[Path]:
        """Move every staged file onto its target (renames within one directory)."""
        for tmp, final in self._pairs:
            if not tmp.exists():
                raise MedialCadError(f"internal: {final} was staged but not written")
        for tmp, final in self._pairs:
            if final.exists():
                os.chmod(tmp, final.stat().st_mode & 0o7777)
            os.replace(tmp, final)
        done = [final for _, final in self._pairs]
        self._pairs = []
        return done


# --------------------------------------------------------------------------- conversion


@dataclass
class Conversion:
    """What :func:`convert` did.

    Attributes:
        code: exit code: 0 success, 2 a solid was refused, 1 a solid failed internally.
        report: the JSON report (also written to ``report_path`` if given).
        lines: one summary line per face/solid, for stdout.
        error: one-line error message when ``code != 0``.
        written: files moved into place.
    """

    code: int
    report: dict[str, Any]
    lines: list[str] = field(default_factory=list)
    error: str | None = None
    written: list[Path] = field(default_factory=list)


def _one_line(text: object) -> str:
    return " ".join(str(text).split())


def _check_tol(tol: float | None) -> None:
    if tol is not None and not (math.isfinite(tol) and tol > 0):
        raise InputError(f"--tol must be a positive number, got {tol!r}")


def convert(
    input: str | os.PathLike[str],
    output: str | os.PathLike[str],
    *,
    tol: float | None = None,
    fmt: str | None = None,
    report_path: str | os.PathLike[str] | None = None,
    radius_path: str | os.PathLike[str] | None = None,
    png: str | os.PathLike[str] | None = None,
    html: str | os.PathLike[str] | None = None,
    thickness: bool = True,
    debug: bool = False,
) -> Conversion:
    """Compute the medial axis of every solid (or, without solids, every planar face) of
    ``input`` and write it to ``output``; the engine behind the ``medialcad`` command.

    Args:
        input: STEP or BREP file.
        output: medial axis file (STEP, or BREP with ``fmt="brep"`` / a ``.brep`` suffix).
        tol: absolute fit tolerance (default ``1e-5`` x bounding-box diagonal).
        fmt: ``"step"`` or ``"brep"``; default by the suffix of ``output``.
        report_path: JSON report; written even when a solid is refused.
        radius_path: radius sidecar (solids only); ``None``: none.
        png: picture: the first solid with its 3D medial axis and its profile's 2D axis
            (or the 2D axis of the first face).
        html: interactive viewer of the first solid and its medial axis (solids only).
        thickness: add the minimum and maximum wall thickness of every solid, with their
            locations, to the report and the summary lines.
        debug: print the traceback of every failing solid to stderr.

    Returns:
        A :class:`Conversion`; ``code != 0`` when a solid was refused or failed (then
        nothing but the report was written).

    Raises:
        InputError: the file cannot be read, holds no solid and no face, a face cannot be
            handled, or the arguments are inconsistent.
        MedialCadError, OSError: an internal failure while computing or writing.
    """
    from medialcad.occ.io import read_shapes
    from medialcad.occ.shapes import solids_or_shells

    _check_tol(tol)
    src, out = Path(input), Path(output)
    extra = (report_path, radius_path, png, html)
    targets = [out] + [Path(p) for p in extra if p is not None]
    resolved = [t.resolve() for t in targets]
    if len(set(resolved)) != len(resolved):
        raise InputError("the output, report, radius, picture and viewer files must all differ")
    if src.resolve() in resolved:
        raise InputError(f"{src}: refusing to overwrite the input file")
    if fmt is None:
        fmt = "brep" if out.suffix.lower() in (".brep", ".brp") else "step"
    if fmt not in ("step", "brep"):
        raise InputError(f"unknown output format {fmt!r} (step or brep)")
    shapes = read_shapes(src)
    all_solids = []
    loose = 0
    for sh in shapes:
        try:
            found = solids_or_shells(sh)
        except InputError as err:
            raise type(err)(f"{src}: {err}") from err
        all_solids.extend(found)
        loose += not found
    if not all_solids:
        if html is not None:
            raise InputError(
                f"{src} holds faces and no solid: --html shows solids (use --png for faces)"
            )
        return _convert_faces(src, out, shapes, tol, fmt, report_path, png)
    if loose:
        log.warning("%s: %d root shape(s) without a solid are ignored", src, loose)
    pictures = _Pictures(png, html)
    return _convert_solids(
        src, out, all_solids, tol, fmt, report_path, radius_path, pictures, thickness, debug
    )


@dataclass(frozen=True)
class _Pictures:
    png: str | os.PathLike[str] | None = None
    html: str | os.PathLike[str] | None = None


# --------------------------------------------------------------------------- solids


def _recognition_fields(mat: Any) -> dict[str, Any]:
    rec = mat.recognition
    if mat.kind == "extrusion":
        out = {"direction": _floats(rec.direction), "length": float(rec.length)}
        if rec.cap_normal is not None:  # an oblique prism
            out.update(cap_normal=_floats(rec.cap_normal), height=float(rec.height))
        return out
    return {
        "axis_point": _floats(rec.axis_point),
        "axis_direction": _floats(rec.axis_direction),
        "angle": float(rec.angle),
        "touches_axis": bool(rec.touches_axis),
    }


def _floats(v: Any) -> list[float]:
    return [float(x) + 0.0 for x in v]  # + 0.0: no -0.0


def _thickness_fields(mat: Any) -> dict[str, Any]:
    from medialcad.thickness import wall_thickness

    t = wall_thickness(mat)

    def num(x: float) -> float | None:
        return float(x) if math.isfinite(x) else None

    return {
        "min": num(t.min),
        "max": num(t.max),
        "min_location": _floats(t.min_location) if math.isfinite(t.min) else None,
        "max_location": _floats(t.max_location),
        "min_entity": t.min_entity,
        "max_entity": t.max_entity,
    }


def _solve_solid(
    index: int, count: int, solid: Any, tol: float | None, thickness: bool, debug: bool
) -> tuple[dict[str, Any], Any]:
    """The report entry of one solid and its medial axis (``None`` if it failed)."""
    from medialcad.api import medial_axis

    t0 = time.perf_counter()
    try:
        mat = medial_axis(solid, tol=tol)
    except Exception as err:  # noqa: BLE001 -- reported per solid; the others go on
        if debug:
            traceback.print_exception(err, file=sys.stderr)
        refused = isinstance(err, InputError)
        message = _one_line(err) if isinstance(err, MedialCadError) else _describe(err)
        log.debug("solid %d of %d %s: %s", index, count, "refused" if refused else "failed", err)
        return {
            "index": index,
            "status": "refused" if refused else "failed",
            "error": message,
            "error_type": type(err).__name__,
            "seconds": round(time.perf_counter() - t0, 4),
        }, None
    seconds = time.perf_counter() - t0
    timings = {k: round(float(v), 4) for k, v in mat.timings.items()}
    timings["total"] = round(seconds, 4)
    entry: dict[str, Any] = {
        "index": index,
        "status": "ok",
        "kind": mat.kind,
        **_recognition_fields(mat),
        "counts": mat.counts(),
        "rmax": float(mat.rmax),
        "tol": float(mat.tol),
        "input_tolerance": float(mat.input_tolerance),
        "error_bound": float(mat.error_bound),
        "timings": timings,
        "seconds": round(seconds, 4),
        "product": solid_product_name(index),
    }
    if mat.input_tolerance > mat.tol:
        log.warning(
            "solid %d of %d: its B-rep is only accurate to %.3g, more than tol %.3g: the "
            "medial axis is exact to tol for the recognised profile, within %.3g of the "
            "solid's faces",
            index,
            count,
            mat.input_tolerance,
            mat.tol,
            mat.error_bound,
        )
    if thickness:
        t1 = time.perf_counter()
        try:
            entry["thickness"] = _thickness_fields(mat)
            entry["timings"]["thickness"] = round(time.perf_counter() - t1, 4)
        except Exception as err:  # noqa: BLE001 -- the medial axis stands without it
            if debug:
                traceback.print_exception(err, file=sys.stderr)
            log.warning("solid %d of %d: no wall thickness: %s", index, count, err)
            entry["thickness"] = {"error": _one_line(err)}
        entry["seconds"] = round(time.perf_counter() - t0, 4)
    return entry, mat


def _describe(err: BaseException) -> str:
    return _one_line(f"internal error: {type(err).__name__}: {err}")


def _solid_line(entry: dict[str, Any], count: int) -> str:
    head = f"solid {entry['index']} of {count}"
    c = entry["counts"]
    if entry["kind"] == "extrusion":
        d = ", ".join(f"{x:.4g}" for x in entry["direction"])
        what = f"extrusion along ({d}), length {entry['length']:.6g}"
        if "cap_normal" in entry:  # an oblique prism
            what += f" (oblique: caps {entry['height']:.6g} apart)"
    else:
        what = f"revolution through {math.degrees(entry['angle']):.6g} deg"
    wall = ""
    if "thickness" in entry and "error" not in entry["thickness"]:
        t = entry["thickness"]
        low = "n/a" if t["min"] is None else f"{t['min']:.6g}"
        wall = f", wall {low}..{t['max']:.6g}"
    return (
        f"{head}: {what}: {c['sheets']} sheets, {c['seams']} seams, {c['junctions']} junctions, "
        f"{c['skeletal_edges']} skeletal edges, rmax {entry['rmax']:.6g}{wall}, "
        f"{entry['seconds']:.3f} s"
    )


def _convert_solids(
    src: Path,
    out: Path,
    all_solids: list[Any],
    tol: float | None,
    fmt: str,
    report_path: str | os.PathLike[str] | None,
    radius_path: str | os.PathLike[str] | None,
    pictures: _Pictures,
    thickness: bool,
    debug: bool,
) -> Conversion:
    from medialcad.occ.io import write_brep, write_step, write_step_named
    from medialcad.occ.shapes import compound

    n = len(all_solids)
    entries: list[dict[str, Any]] = []
    mats: list[Any] = []
    for i, solid in enumerate(all_solids, start=1):
        entry, mat = _solve_solid(i, n, solid, tol, thickness, debug)
        entries.append(entry)
        mats.append(mat)
    report: dict[str, Any] = {
        "input": str(src),
        "output": str(out),
        "options": {"tol": tol, "format": fmt},
        "solids": entries,
    }
    lines = [_solid_line(e, n) for e in entries if e["status"] == "ok"]
    bad = [e for e in entries if e["status"] != "ok"]
    report["status"] = (
        "ok" if not bad else ("refused" if any(e["status"] == "refused" for e in bad) else "failed")
    )
    with _Staging() as staging:
        if bad:
            what = "; ".join(f"solid {e['index']} of {n} {e['status']}: {e['error']}" for e in bad)
            error = f"{what} -- nothing written to {out}"
            report["written"] = False
            written: list[Path] = []
            if report_path is not None:
                _write_json(staging.path(Path(report_path)), report)
                written = staging.commit()
                error += f" (report: {report_path})"
            code = 2 if report["status"] == "refused" else 1
            return Conversion(code, report, lines, error, written)
        report["written"] = True
        tmp_out = staging.path(out)
        if fmt == "brep":
            write_brep(mats[0].compound if n == 1 else compound(m.compound for m in mats), tmp_out)
        elif n == 1:
            write_step_named(mats[0].compound, mats[0].names(), tmp_out, name=solid_product_name(1))
        else:
            write_step(
                [m.compound for m in mats],
                tmp_out,
                {i: solid_product_name(i + 1) for i in range(n)},
            )
        if radius_path is not None:
            report["radius"] = str(radius_path)
            if n == 1:
                data = mats[0].radius_data()
            else:
                data = {
                    "format": "medialcad-radius-multi/1",
                    "solids": [
                        {"index": i, "product": solid_product_name(i), **m.radius_data()}
                        for i, m in enumerate(mats, start=1)
                    ],
                }
            _write_json(staging.path(Path(radius_path)), data, indent=1)
        if pictures.png is not None or pictures.html is not None:
            from medialcad.plot3d import PNG_MAX_TRIANGLES, render_png, tessellate
            from medialcad.viewer import HTML_MAX_TRIANGLES, write_html

            scene = None
            if pictures.html is not None:
                scene = tessellate(mats[0], max_triangles=HTML_MAX_TRIANGLES)
                write_html(mats[0], staging.path(Path(pictures.html)), scene=scene)
            if pictures.png is not None:
                # the viewer's mesh serves the picture too when it is within the picture's
                # budget (matplotlib slows with triangles); otherwise a coarser one is made
                small = scene is not None and scene.triangle_count() <= PNG_MAX_TRIANGLES
                render_png(
                    mats[0], staging.path(Path(pictures.png)), scene=scene if small else None
                )
        if report_path is not None:
            _write_json(staging.path(Path(report_path)), report)
        written = staging.commit()
    return Conversion(0, report, lines, None, written)


def _write_json(path: Path, data: dict[str, Any], indent: int = 2) -> None:
    path.write_text(json.dumps(data, indent=indent) + "\n", encoding="utf-8")


# --------------------------------------------------------------------------- faces


def _face_report(index: int, mat: Any, seconds: float) -> dict[str, Any]:
    kinds: dict[str, int] = {}
    for n in mat.nodes:
        kinds[n.kind.value] = kinds.get(n.kind.value, 0) + 1
    return {
        "index": index,
        "kind": "face",
        "branches": len(mat.branches),
        "nodes": len(mat.nodes),
        "branch_points": kinds.get("branch_point", 0),
        "convex_vertices": kinds.get("convex_vertex", 0),
        "curvature_centres": kinds.get("curvature_centre", 0),
        "rmax": mat.rmax,
        "tol": mat.tol,
        "seconds": round(seconds, 4),
    }


def _convert_faces(
    src: Path,
    out: Path,
    shapes: list[Any],
    tol: float | None,
    fmt: str,
    report_path: str | os.PathLike[str] | None,
    png: str | os.PathLike[str] | None,
) -> Conversion:
    """The 2D behaviour: every planar face; any bad face fails the whole file."""
    from medialcad.api import medial_axis_2d
    from medialcad.occ.io import write_brep, write_step
    from medialcad.occ.shapes import compound, faces

    all_faces = [f for sh in shapes for f in faces(sh)]
    if not all_faces:
        raise InputError(f"{src} holds no solid and no face")
    results = []
    report: dict[str, Any] = {
        "input": str(src),
        "output": str(out),
        "options": {"tol": tol, "format": fmt},
        "faces": [],
    }
    for i, face in enumerate(all_faces):
        t0 = time.perf_counter()
        try:
            mat = medial_axis_2d(face, tol=tol)
        except MedialCadError as err:
            raise type(err)(f"face {i}: {err}") from err
        results.append(mat)
        report["faces"].append(_face_report(i, mat, time.perf_counter() - t0))
    comps = [m.to_compound() for m in results]
    with _Staging() as staging:
        if png is not None:
            from medialcad.plot import plot_medial_axis_2d

            plot_medial_axis_2d(results[0], staging.path(Path(png)))
        if report_path is not None:
            _write_json(staging.path(Path(report_path)), report)
        tmp_out = staging.path(out)
        if fmt == "brep":
            write_brep(compound(comps), tmp_out)
        else:
            write_step(comps, tmp_out, {i: f"medial-axis-face-{i}" for i in range(len(comps))})
        written = staging.commit()
    lines = [
        f"face {r['index']}: {r['branches']} branches, {r['branch_points']} branch points, "
        f"rmax {r['rmax']:.6g}, {r['seconds']:.3f} s"
        for r in report["faces"]
    ]
    return Conversion(0, report, lines, None, written)


# --------------------------------------------------------------------------- main


def _run(args: argparse.Namespace) -> int:
    radius = None if args.no_radius else (args.radius or default_radius_path(args.output))
    result = convert(
        args.input,
        args.output,
        tol=args.tol,
        fmt=args.format,
        report_path=args.report,
        radius_path=radius,
        png=args.png,
        html=args.html,
        thickness=not args.no_thickness,
        debug=args.debug,
    )
    for line in result.lines:
        print(line)
    if result.code != 0:
        sys.stdout.flush()
        print(f"medialcad: error: {result.error}", file=sys.stderr)
        return result.code
    print(f"wrote {', '.join(str(p) for p in result.written)}")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``medialcad`` console script."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] == "batch":
        from medialcad.batch import main as batch_main

        return batch_main(argv[1:])
    args = _parser().parse_args(argv)
    logging.basicConfig(
        level=logging.DEBUG if args.debug else logging.WARNING,
        format=logging.BASIC_FORMAT if args.debug else "medialcad: %(levelname)s: %(message)s",
    )
    try:
        return _run(args)
    except KeyboardInterrupt:
        print("medialcad: interrupted", file=sys.stderr)
        return 130
    except InputError as err:
        if args.debug:
            raise
        print(f"medialcad: error: {_one_line(err)}", file=sys.stderr)
        return 2
    except (MedialCadError, OSError) as err:
        if args.debug:
            raise
        print(f"medialcad: failed: {_one_line(err)}", file=sys.stderr)
        return 1
    except Exception as err:
        if args.debug:
            raise
        print(f"medialcad: {_describe(err)}", file=sys.stderr)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
