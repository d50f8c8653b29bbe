"""Command line: ``medialcad INPUT -o OUTPUT [--tol T] [--png FILE] [--report R.json]``.

Exit codes: 0 success, 2 the input cannot be handled (:class:`InputError`), 1 an internal
failure. Errors are one line on stderr (a traceback only with ``--debug``). Outputs are
written atomically: a failed run leaves no output, sidecar or picture behind and never
clobbers an existing file.
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from medialcad.errors import InputError, MedialCadError

__all__ = ["main"]

log = logging.getLogger(__name__)


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="medialcad",
        description="Exact medial axis transform of CAD faces (STEP/BREP in, STEP/BREP out).",
    )
    p.add_argument("input", help="STEP (.step/.stp) or BREP (.brep) file")
    p.add_argument("-o", "--output", required=True, help="medial axis output file")
    p.add_argument(
        "--tol", type=float, default=None, help="absolute tolerance (default 1e-5 x bbox diagonal)"
    )
    p.add_argument(
        "--format",
        choices=("step", "brep"),
        default=None,
        help="output format (default: by suffix)",
    )
    p.add_argument("--report", default=None, help="write a JSON report here")
    p.add_argument("--png", default=None, help="write a picture of the medial axis here")
    p.add_argument("--debug", action="store_true", help="show tracebacks")
    return p


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


def _run(args: argparse.Namespace) -> int:
    from medialcad.api import medial_axis_2d
    from medialcad.occ.io import read_shapes, write_brep, write_step
    from medialcad.occ.shapes import compound, faces, solids

    shapes = read_shapes(args.input)
    all_solids = [s for sh in shapes for s in solids(sh)]
    if all_solids:
        raise InputError(
            f"{args.input} holds {len(all_solids)} solid(s): this release computes the medial "
            "axis of planar faces only (solids come with the extrusion/revolution work)"
        )
    all_faces = [f for sh in shapes for f in faces(sh)]
    if not all_faces:
        raise InputError(f"{args.input} holds no face")
    results = []
    report: dict[str, Any] = {"input": str(args.input), "faces": []}
    for i, face in enumerate(all_faces):
        t0 = time.perf_counter()
        try:
            mat = medial_axis_2d(face, tol=args.tol)
        except MedialCadError as err:
            raise type(err)(f"face {i}: {err}") from err
        results.append(mat)
        report["faces"].append(_face_report(i, mat, time.perf_counter() - t0))
    out = Path(args.output)
    fmt = args.format or ("brep" if out.suffix.lower() == ".brep" else "step")
    comps = [m.to_compound() for m in results]
    staged: list[tuple[Path, Path]] = []
    try:
        # stage every output beside its target, then move them all into place
        if args.png:
            from medialcad.plot import plot_medial_axis_2d

            png = Path(args.png)
            tmp_png = _stage(png)
            staged.append((tmp_png, png))
            plot_medial_axis_2d(results[0], tmp_png)
        if args.report:
            rep = Path(args.report)
            tmp_rep = _stage(rep)
            staged.append((tmp_rep, rep))
            tmp_rep.write_text(json.dumps(report, indent=2))
        tmp_out = _stage(out)
        staged.append((tmp_out, out))
        if fmt == "brep":
            write_brep(compound(comps), tmp_out)
        else:
            write_step(comps, tmp_out, {i: f"medial-axis-face-{i}" for i in range(len(comps))})
        # everything is written: move it all into place (same directories, so renames)
        umask = os.umask(0)
        os.umask(umask)
        for tmp, final in staged:
            os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600 files
            os.replace(tmp, final)
    except BaseException:
        for tmp, _ in staged:
            tmp.unlink(missing_ok=True)
        raise
    for r in report["faces"]:
        print(
            f"face {r['index']}: {r['branches']} branches, {r['branch_points']} branch points, "
            f"rmax {r['rmax']:.6g}, {r['seconds']:.3f} s"
        )
    print(f"wrote {out}")
    return 0


def _stage(target: Path) -> Path:
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix, dir=target.parent)
    os.close(fd)
    return Path(name)


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``medialcad`` console script."""
    args = _parser().parse_args(argv)
    logging.basicConfig(level=logging.DEBUG if args.debug else logging.WARNING)
    try:
        return _run(args)
    except KeyboardInterrupt:
        print("medialcad: interrupted", file=sys.stderr)
        return 130
    except InputError as err:
        if args.debug:
            raise
        print(f"medialcad: error: {err}", file=sys.stderr)
        return 2
    except (MedialCadError, OSError) as err:
        if args.debug:
            raise
        print(f"medialcad: failed: {err}", file=sys.stderr)
        return 1
    except Exception as err:
        if args.debug:
            raise
        print(f"medialcad: internal error: {type(err).__name__}: {err}", file=sys.stderr)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
