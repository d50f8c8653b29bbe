"""Fresh random solids written as STEP by FreeCAD, through the 3D oracles.

One file, two roles. The *generator* runs under FreeCAD's headless interpreter (Debian:
``apt-get install freecad-python3``) and imports only FreeCAD, ``Part`` and the standard
library; ``freecadcmd`` runs the file as a module not named ``__main__`` and treats extra
command-line words as files to open, so its options come from the environment::

    MEDIALCAD_FREECAD_FUZZ_OUT=/tmp/fzfc MEDIALCAD_FREECAD_FUZZ_COUNT=150 \\
    MEDIALCAD_FREECAD_FUZZ_SEED=0 freecadcmd scripts/fuzz_freecad.py

For each seed ``s`` (``random.Random(s)``) it draws a planar profile with ``Part``: a base
(rectangle, regular polygon, circle, ellipse, slot, star or convex polygon, periodic
interpolated B-spline blob, polygon with some sides bent into arcs), zero to two circles,
rectangles or polygons cut out of it (holes inside it, or notches) or fused to it,
sometimes its reflex and/or convex corners rounded (``makeOffset2D`` out then in, or in
then out, arc joins), sometimes an offset. The face is extruded along its normal (0.05 to
2 diagonals) or along an oblique vector, or revolved (5 to 359 degrees or a full turn)
about an in-plane axis beside it (gap 0.05 to 1 diagonal) or through its leftmost point
(touching its axis), then turned and moved (up to 50 along each axis). Shapes that are not
one valid solid are skipped. Each solid goes to ``OUT/seed<s>.step`` (``exportStep``,
FreeCAD's own STEP writer) and ``OUT/seed<s>.brep`` (the same shape as BREP, to tell STEP
problems from geometry), one line per seed (skipped ones too) to ``OUT/manifest.jsonl``.

The *checker* runs with the venv's python and never imports FreeCAD::

    python scripts/fuzz_freecad.py check OUT [--seeds 3 17 ...] [--ext step|brep]

Every file is read with ``medialcad.read_step``, its volume compared with the manifest's
(FreeCAD's ``Shape.Volume``: an export sanity check), and its MAT judged exactly as
``scripts/fuzz_build123d.py`` does: ``tests/_mat3d.check`` (the oracles of
``tests/oracles3d.py``), logged as one JSON line to ``OUT/check-<stamp>.jsonl``: passed,
refused (a medialcad ``InputError``), error (another medialcad error: an internal
failure), failed (the oracles' findings) or crash (anything else). The table at the end
counts them; the exit status is 1 if any example failed, errored or crashed.
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import os
import random
import re
import sys
import time
import traceback
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
ENV = "MEDIALCAD_FREECAD_FUZZ_"

# --------------------------------------------------------------------------- generator
# (FreeCAD's python: FreeCAD, Part and the standard library only)


def _v(x: float, y: float, z: float = 0.0) -> Any:
    from FreeCAD import Vector  # type: ignore[import-not-found,unused-ignore]

    return Vector(float(x), float(y), float(z))


def _polygon_face(pts: list[tuple[float, float]]) -> Any:
    import Part  # type: ignore[import-not-found,unused-ignore]

    return Part.Face(Part.makePolygon([_v(*p) for p in [*pts, pts[0]]]))


def _circle_face(r: float, cx: float = 0.0, cy: float = 0.0) -> Any:
    import Part  # type: ignore[import-not-found,unused-ignore]

    return Part.Face(Part.Wire(Part.makeCircle(r, _v(cx, cy), _v(0, 0, 1))))


def _regular(r: float, n: int, phase: float = 0.0) -> list[tuple[float, float]]:
    return [
        (r * math.cos(phase + 2 * math.pi * k / n), r * math.sin(phase + 2 * math.pi * k / n))
        for k in range(n)
    ]


def _slot(length: float, width: float) -> Any:
    """A stadium: two half disks of radius ``width / 2`` joined by a rectangle."""
    import Part  # type: ignore[import-not-found,unused-ignore]

    a, h = (length - width) / 2, width / 2
    edges = [
        Part.LineSegment(_v(-a, -h), _v(a, -h)).toShape(),
        Part.Arc(_v(a, -h), _v(a + h, 0), _v(a, h)).toShape(),
        Part.LineSegment(_v(a, h), _v(-a, h)).toShape(),
        Part.Arc(_v(-a, h), _v(-a - h, 0), _v(-a, -h)).toShape(),
    ]
    return Part.Face(Part.Wire(edges))


def _arc_polygon(r: random.Random) -> Any:
    """A convex polygon some of whose sides are bent into arcs (in or out)."""
    import Part  # type: ignore[import-not-found,unused-ignore]

    n = r.randrange(3, 8)
    angles = sorted(r.uniform(0, 2 * math.pi) for _ in range(n))
    rad = r.uniform(2, 5)
    pts = [(rad * math.cos(a), rad * math.sin(a)) for a in angles]
    edges = []
    for k in range(n):
        (x0, y0), (x1, y1) = pts[k], pts[(k + 1) % n]
        if r.random() < 0.5:
            edges.append(Part.LineSegment(_v(x0, y0), _v(x1, y1)).toShape())
            continue
        chord = math.hypot(x1 - x0, y1 - y0)
        # sagitta along the outward normal (the polygon turns counter-clockwise)
        s = r.choice([-1, 1]) * r.uniform(0.05, 0.3) * chord
        nx, ny = (y1 - y0) / chord, -(x1 - x0) / chord
        mid = ((x0 + x1) / 2 + s * nx, (y0 + y1) / 2 + s * ny)
        edges.append(Part.Arc(_v(x0, y0), _v(*mid), _v(x1, y1)).toShape())
    return Part.Face(Part.Wire(edges))


def _blob(r: random.Random) -> Any:
    """A closed periodic B-spline interpolating points around the origin."""
    import Part  # type: ignore[import-not-found,unused-ignore]

    n = r.randrange(5, 13)
    base = r.uniform(2, 5)
    pts = []
    for k in range(n):
        t = 2 * math.pi * (k + r.uniform(-0.3, 0.3)) / n
        rho = base * r.uniform(0.6, 1.0)
        pts.append(_v(rho * math.cos(t), rho * math.sin(t)))
    curve = Part.BSplineCurve()
    curve.interpolate(pts, PeriodicFlag=True)
    return Part.Face(Part.Wire([curve.toShape()]))


def _base(r: random.Random) -> tuple[Any, str]:
    import Part  # type: ignore[import-not-found,unused-ignore]

    k = r.randrange(9)
    w, h = r.uniform(2, 10), r.uniform(1, 8)
    if k == 0:
        return _polygon_face(
            [(-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2)]
        ), "rect"
    if k == 1:
        n = r.randrange(3, 13)
        return _polygon_face(_regular(r.uniform(2, 5), n, r.uniform(0, 1))), f"ngon{n}"
    if k == 2:
        return _circle_face(r.uniform(1, 5)), "circle"
    if k == 3:
        a, b = max(w, h) / 2, min(w, h) / 2
        if a - b < 0.2:
            a += 0.5
        return Part.Face(Part.Wire(Part.Ellipse(_v(0, 0), a, b).toShape())), "ellipse"
    if k == 4:
        return _slot(w + h, h / 1.5), "slot"
    if k == 5:
        n = r.randrange(3, 8)
        ro, ri = r.uniform(2.5, 5), r.uniform(0.8, 2.2)
        pts = _regular(1.0, 2 * n, r.uniform(0, 1))
        return _polygon_face(
            [
                (x * (ro if i % 2 == 0 else ri), y * (ro if i % 2 == 0 else ri))
                for i, (x, y) in enumerate(pts)
            ]
        ), f"star{n}"
    if k == 6:
        angles = sorted(r.uniform(0, 2 * math.pi) for _ in range(r.randrange(3, 9)))
        rad = r.uniform(2, 5)
        return _polygon_face([(rad * math.cos(a), rad * math.sin(a)) for a in angles]), "convex"
    if k == 7:
        return _blob(r), "blob"
    return _arc_polygon(r), "arcgon"


def _tool(r: random.Random, cx: float, cy: float, size: float) -> tuple[Any, str]:
    """A circle, rectangle or regular polygon about ``(cx, cy)``, at most ``size`` across."""
    k = r.randrange(3)
    if k == 0:
        return _circle_face(size * r.uniform(0.06, 0.5), cx, cy), "circle"
    phase = r.uniform(0, 2 * math.pi)
    if k == 1:
        a, b = size * r.uniform(0.05, 0.35), size * r.uniform(0.05, 0.35)
        c, s = math.cos(phase), math.sin(phase)
        pts = [
            (cx + x * c - y * s, cy + x * s + y * c)
            for x, y in [(-a, -b), (a, -b), (a, b), (-a, b)]
        ]
        return _polygon_face(pts), "rect"
    n = r.randrange(3, 8)
    return _polygon_face(
        [(cx + x, cy + y) for x, y in _regular(size * r.uniform(0.1, 0.4), n, phase)]
    ), f"ngon{n}"


def _one_face(shape: Any) -> Any | None:
    with_faces = shape.removeSplitter() if len(shape.Faces) > 1 else shape
    return with_faces.Faces[0] if len(with_faces.Faces) == 1 else None


def _is_inside(face: Any, tool: Any) -> bool:
    """``tool`` lies inside ``face`` and clear of its boundary."""
    common = face.common(tool)
    if abs(common.Area - tool.Area) > 1e-9 * tool.Area:
        return False
    return face.Wires[0].distToShape(tool)[0] > 0.05


def sketch(r: random.Random) -> tuple[Any | None, list[str]]:
    """A random one-face profile in the xy plane (or None) and what was done to it."""
    face, name = _base(r)
    ops = [name]
    for _ in range(r.randrange(0, 3)):
        u = r.random()
        if u < 0.4:  # a hole: a small tool near the centre of mass
            bb, c = face.BoundBox, face.CenterOfMass
            cx = c.x + r.uniform(-0.25, 0.25) * bb.XLength
            cy = c.y + r.uniform(-0.25, 0.25) * bb.YLength
            tool, tname = _tool(r, cx, cy, 0.6 * min(bb.XLength, bb.YLength))
            if not _is_inside(face, tool):
                continue
            new, op = face.cut(tool), f"hole {tname}"
        else:
            tool, tname = _tool(r, r.uniform(-4, 4), r.uniform(-4, 4), 5.0)
            if u < 0.7:
                new, op = face.cut(tool), f"cut {tname}"
            elif face.common(tool).Area < 1e-3 * tool.Area:
                continue  # disjoint: the union would be two faces
            else:
                new, op = face.fuse(tool), f"fuse {tname}"
        new = _one_face(new)
        if new is None:
            return None, [*ops, op + " (not one face)"]
        face = new
        ops.append(op)
    if r.random() < 0.4:
        d = r.uniform(0.05, 0.8)
        # out then in rounds the reflex corners, in then out the convex ones
        order = r.choice([(d, -d), (-d, d), (d, -2 * d, d)])
        try:
            new = face
            for step in order:
                new = new.makeOffset2D(step, 0)
            new = _one_face(new)
        except Exception:  # noqa: BLE001 - a rounding too large for the face: keep it
            new = None
        if new is not None:
            face = new
            ops.append("round " + "/".join(f"{s:+.2f}" for s in order))
    if r.random() < 0.25:
        d = r.uniform(-0.3, 0.6)
        try:
            new = _one_face(face.makeOffset2D(d, 0))
        except Exception:  # noqa: BLE001
            new = None
        if new is not None:
            face = new
            ops.append(f"offset {d:+.2f}")
    try:
        face.check(True)  # raises on a self-intersecting wire
    except Exception:  # noqa: BLE001
        return None, [*ops, "invalid face"]
    return face, ops


def _leftmost_x(face: Any) -> float:
    """The exact smallest x of ``face`` (bounding boxes are padded)."""
    import Part  # type: ignore[import-not-found,unused-ignore]

    bb = face.optimalBoundingBox()
    x0 = bb.XMin - 1.0
    far = 10 * (bb.DiagonalLength + 1)
    line = Part.LineSegment(_v(x0, bb.YMin - far), _v(x0, bb.YMax + far)).toShape()
    return x0 + face.distToShape(line)[0]


def solid(r: random.Random, face: Any) -> tuple[Any, dict[str, Any]]:
    """The face extruded or revolved, turned and moved; and what was done."""
    face.rotate(_v(0, 0, 0), _v(0, 0, 1), r.uniform(0, 360))
    d = face.BoundBox.DiagonalLength
    info: dict[str, Any] = {}
    if r.random() < 0.5:
        length = r.uniform(0.05, 2.0) * d
        if r.random() < 0.25:
            tilt, turn = math.radians(r.uniform(10, 60)), r.uniform(0, 2 * math.pi)
            vec = (math.sin(tilt) * math.cos(turn), math.sin(tilt) * math.sin(turn), math.cos(tilt))
            info.update(kind="oblique extrusion", tilt_deg=round(math.degrees(tilt), 3))
        else:
            vec = (0.0, 0.0, 1.0)
            info["kind"] = "extrusion"
        out = face.extrude(_v(*(length * c for c in vec)))
        info["length"] = round(length, 6)
    else:
        touching = r.random() < 0.3
        gap = 0.0 if touching else r.uniform(0.05, 1.0) * d
        angle = r.choice([360.0, r.uniform(5, 359)])
        info.update(
            kind="revolution" + (" touching" if touching else ""),
            angle=round(angle, 6),
            gap=round(gap, 6),
        )
        try:
            out = face.revolve(_v(_leftmost_x(face) - gap, 0, 0), _v(0, 1, 0), angle)
        except Exception as err:
            # (FreeCAD 0.20 fails on an ellipse or B-spline tangent to the axis)
            raise RuntimeError(f"{info['kind']} {angle:.0f}: {type(err).__name__}: {err}") from err
    axis = (r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1))
    out.rotate(_v(0, 0, 0), _v(*axis), r.uniform(0, 360))
    out.translate(_v(*(r.uniform(-50, 50) for _ in range(3))))
    return out, info


def generate(seed: int, out: Path) -> dict[str, Any]:
    """Build seed ``seed``, write its STEP and BREP; its manifest line."""
    r = random.Random(seed)
    rec: dict[str, Any] = {"seed": seed}
    try:
        face, ops = sketch(r)
        rec["profile"] = ops
        if face is None:
            return {**rec, "skipped": ops[-1]}
        shape, info = solid(r, face)
    except Exception as err:  # noqa: BLE001 - FreeCAD could not build it: not our input
        return {**rec, "skipped": f"{type(err).__name__}: {err}"[:200]}
    rec.update(info)
    if len(shape.Solids) != 1 or not shape.isValid():
        return {
            **rec,
            "skipped": f"{shape.ShapeType}, {len(shape.Solids)} solids, valid {shape.isValid()}",
        }
    sol = shape.Solids[0]
    rec.update(volume=sol.Volume, faces=len(sol.Faces), file=f"seed{seed}.step")
    sol.exportStep(str(out / f"seed{seed}.step"))
    sol.exportBrep(str(out / f"seed{seed}.brep"))
    return rec


def _isolated(seed: int, out: Path) -> dict[str, Any]:
    """``generate(seed, out)`` in a forked child: OCC's 2D offset sometimes segfaults."""
    rfd, wfd = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child
        os.close(rfd)
        try:
            rec = generate(seed, out)
        except BaseException as err:  # noqa: BLE001 - reported to the parent
            rec = {"seed": seed, "skipped": f"{type(err).__name__}: {err}"[:200]}
        with os.fdopen(wfd, "w") as fh:
            fh.write(json.dumps(rec))
        sys.stdout.flush()
        os._exit(0)
    os.close(wfd)
    with os.fdopen(rfd) as fh:
        text = fh.read()
    _, status = os.waitpid(pid, 0)
    if text:
        return json.loads(text)
    return {"seed": seed, "skipped": f"FreeCAD crashed (wait status {status})"}


def generator_main() -> int:
    out = Path(os.environ.get(ENV + "OUT", "/tmp/fzfc"))
    count = int(os.environ.get(ENV + "COUNT", "150"))
    first = int(os.environ.get(ENV + "SEED", "0"))
    out.mkdir(parents=True, exist_ok=True)
    written = skipped = 0
    with (out / "manifest.jsonl").open("a") as fh:
        for seed in range(first, first + count):
            rec = _isolated(seed, out)
            fh.write(json.dumps(rec) + "\n")
            fh.flush()
            if "skipped" in rec:
                skipped += 1
                print(f"seed {seed}: skipped: {rec['skipped']}")
            else:
                written += 1
    print(f"wrote {written} STEP files, skipped {skipped} seeds: {out}")
    return 0


# --------------------------------------------------------------------------- checker
# (the venv's python: medialcad, OCP and the tests' oracles; never FreeCAD)


def _volume(shape: Any) -> float:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return float(props.Mass())


def check(path: Path, manifest: dict[str, Any]) -> dict[str, Any]:
    """Read ``path`` and judge its MAT the way ``scripts/fuzz_build123d.py`` does
    (``tests._mat3d.judge``); a file that cannot be read is judged like a MAT."""
    import medialcad
    from medialcad.errors import InputError, MedialCadError
    from tests import _mat3d as M

    seed = int(re.sub(r"\D", "", path.stem))
    rec: dict[str, Any] = {"seed": seed, "file": str(path), "kind": manifest.get("kind", "?")}
    try:
        solids = medialcad.read_step(path)
        if len(solids) != 1:
            raise RuntimeError(f"{len(solids)} solids in the file")
    except InputError as err:
        return {**rec, "status": "refused", "why": str(err)}
    except MedialCadError as err:
        return {**rec, "status": "error", "why": f"{type(err).__name__}: {err}"}
    except Exception:  # noqa: BLE001 - logged, the run goes on
        return {**rec, "status": "crash", "why": traceback.format_exc()[-800:]}
    shape = solids[0]
    if "volume" in manifest:
        vol = _volume(shape)
        rec["volume_rel_err"] = float(f"{abs(vol - manifest['volume']) / manifest['volume']:.2e}")
    return {**rec, **M.judge(shape, seed)}


def _manifest(out: Path) -> dict[int, dict[str, Any]]:
    lines = (
        (out / "manifest.jsonl").read_text().splitlines()
        if (out / "manifest.jsonl").exists()
        else []
    )
    return {(rec := json.loads(line))["seed"]: rec for line in lines if line.strip()}


def checker_main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("role", choices=["check"])
    ap.add_argument("out", type=Path, help="the generator's output directory")
    ap.add_argument("--seeds", type=int, nargs="*", help="only these seeds")
    ap.add_argument("--ext", default="step", choices=["step", "brep"], help="which files to read")
    args = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT))  # this checkout's medialcad and tests
    man = _manifest(args.out)
    files = sorted(args.out.glob(f"seed*.{args.ext}"), key=lambda p: int(re.sub(r"\D", "", p.stem)))
    if args.seeds:
        files = [p for p in files if int(re.sub(r"\D", "", p.stem)) in set(args.seeds)]
    stamp = time.strftime("%Y%m%dT%H%M%S", time.gmtime())
    log = args.out / f"check-{stamp}.jsonl"
    counts: collections.Counter[str] = collections.Counter()
    with log.open("a") as fh:
        for path in files:
            seed = int(re.sub(r"\D", "", path.stem))
            rec = check(path, man.get(seed, {}))
            fh.write(json.dumps(rec) + "\n")
            fh.flush()
            counts[rec["status"]] += 1
            if rec["status"] != "passed":
                print(f"seed {seed} ({rec['kind']}): {rec['status']}: {rec['why'][:200]}")
            if rec.get("volume_rel_err", 0) > 1e-6:
                print(f"seed {seed}: STEP volume off the manifest's by {rec['volume_rel_err']:.1e}")
    skipped = sum(1 for rec in man.values() if "skipped" in rec)
    total = sum(counts.values())
    print(f"{total} solids: " + ", ".join(f"{v} {k}" for k, v in counts.most_common()))
    print(f"{skipped} of {len(man)} seeds skipped by the generator")
    print(f"log: {log}")
    return 1 if counts["failed"] + counts["error"] + counts["crash"] else 0


if __name__ == "__main__":
    sys.exit(checker_main(sys.argv[1:]))
elif "FreeCAD" in sys.modules:
    # freecadcmd runs this file as a module named ``fuzz_freecad``, not ``__main__``.
    try:
        status = generator_main()
    except ImportError as err:
        print(f"fuzz_freecad: {err}: run me with freecadcmd", file=sys.stderr)
        status = 2
    sys.stdout.flush()
    sys.stderr.flush()
    if status:
        os._exit(status)  # freecadcmd would swallow SystemExit and exit 0
