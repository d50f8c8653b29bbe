"""Fresh random solids the way a build123d user sketches them, through the 3D oracles.

A sketch is a base shape (rectangle, regular polygon, circle, ellipse, slot, trapezoid or
a random polygon) with zero to two random circles, rectangles, slots or polygons cut out
of it or added to it, some of its vertices filleted, sometimes offset (arcs at its
corners); it is extruded (along its normal, or 5 to 60 degrees off it: an oblique prism;
seeds drawing one of these were right prisms before 2026-12-07), or revolved (5 to 359 degrees or a full turn) about an axis
beside it or through its leftmost point (a profile touching its axis: at a vertex, along
an edge, or tangent to it, a pinched solid), then turned and moved at random. Sketches
that build123d cannot build as one face are skipped.

    python scripts/fuzz_build123d.py [COUNT] [FIRST_SEED] [--out out/fuzz_b3d]

Every example (seed ``s`` regenerates it) is judged by ``tests/_mat3d.check`` (the
oracles of ``tests/oracles3d.py``) and logged as one JSON line: passed, refused (a
medialcad ``InputError``), error (another medialcad error: an internal failure), failed
(the oracles' findings) or crash (anything else); non-passing solids are kept as exact
binary BREP for replay. The table at the end counts them. Unlike ``scripts/fuzz.sh``
(the hypothesis strategies of ``tests/faces.py``) this draws from build123d's own
operations: booleans of simple shapes, fillets, offsets.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import json
import math
import random
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from build123d import (  # noqa: E402
    Axis,
    Circle,
    Ellipse,
    Kind,
    Location,
    Polygon,
    Rectangle,
    RegularPolygon,
    SlotOverall,
    Trapezoid,
    extrude,
    fillet,
    offset,
    revolve,
)
from OCP.BinTools import BinTools  # noqa: E402

from tests import _mat3d as M  # noqa: E402


def _base(r: random.Random) -> Any:
    k = r.randrange(7)
    w, h = r.uniform(2, 10), r.uniform(1, 8)
    if k == 0:
        return Rectangle(w, h)
    if k == 1:
        return RegularPolygon(r.uniform(2, 5), r.randrange(3, 13))
    if k == 2:
        return Circle(r.uniform(1, 5))
    if k == 3:
        return Ellipse(w / 2, h / 2) if abs(w - h) > 0.2 else Rectangle(w, h)
    if k == 4:
        return SlotOverall(w + h, h / 1.5)
    if k == 5:
        return Trapezoid(w, h, r.uniform(50, 85))
    angles = sorted(r.uniform(0, 2 * math.pi) for _ in range(r.randrange(3, 9)))
    return Polygon(
        *[(r.uniform(2, 5) * math.cos(a), r.uniform(2, 5) * math.sin(a)) for a in angles]
    )


def _tool(r: random.Random) -> Any:
    k = r.randrange(4)
    loc = Location((r.uniform(-4, 4), r.uniform(-4, 4)), r.uniform(0, 360))
    if k == 0:
        return loc * Circle(r.uniform(0.3, 2.5))
    if k == 1:
        return loc * Rectangle(r.uniform(0.5, 4), r.uniform(0.5, 4))
    if k == 2:
        return loc * SlotOverall(r.uniform(1, 5), r.uniform(0.3, 1.5))
    return loc * RegularPolygon(r.uniform(0.5, 2), r.randrange(3, 8))


def sketch(r: random.Random) -> Any | None:
    """A random one-face sketch, or None."""
    sk = _base(r)
    for _ in range(r.randrange(0, 3)):
        t = _tool(r)
        sk = sk - t if r.random() < 0.6 else sk + t
    if r.random() < 0.4:
        vs = list(sk.vertices())
        if vs:
            # (a fillet too large for its corners: the corners stay)
            with contextlib.suppress(Exception):
                sk = fillet(r.sample(vs, r.randrange(1, len(vs) + 1)), r.uniform(0.05, 0.8))
    if r.random() < 0.25:
        with contextlib.suppress(Exception):
            sk = offset(sk, r.uniform(-0.3, 0.6), kind=Kind.ARC)
    fs = sk.faces()
    return fs[0] if len(fs) == 1 else None


def solid(r: random.Random, face: Any) -> tuple[Any, str]:
    """The face extruded or revolved, turned and moved; and a label."""
    bb = face.bounding_box()
    d = bb.diagonal
    u = r.random()
    if u < 0.2:  # along a vector 5 to 60 degrees off the normal: an oblique prism
        tilt, turn = math.radians(r.uniform(5.0, 60.0)), r.uniform(0.0, 2.0 * math.pi)
        way = (math.sin(tilt) * math.cos(turn), math.sin(tilt) * math.sin(turn), math.cos(tilt))
        out = extrude(face, r.uniform(0.05, 2.0) * d / math.cos(tilt), dir=way)
        kind = f"oblique extrusion {math.degrees(tilt):.0f}"
    elif u < 0.5:
        out, kind = extrude(face, r.uniform(0.05, 2.0) * d), "extrusion"
    else:
        gap = 0.0 if r.random() < 0.3 else r.uniform(0.05, 1.0) * d
        angle = r.choice([360.0, r.uniform(5, 359)])
        out = revolve(face, Axis((bb.min.X - gap, 0, 0), (0, 1, 0)), angle)
        kind = f"revolution {angle:.0f}" + (" touching" if gap == 0 else "")
    out = out.solids()[0]
    axis = (r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1))
    out = out.rotate(Axis((0, 0, 0), axis), r.uniform(0, 360))
    return out.translate((r.uniform(-50, 50),) * 3), kind


def run(seed: int, keep: Path) -> dict[str, Any] | None:
    r = random.Random(seed)
    try:
        face = sketch(r)
        if face is None:
            return None
        shape, kind = solid(r, face)
    except Exception:  # noqa: BLE001 - build123d could not build it: not our input
        return None
    rec: dict[str, Any] = {"seed": seed, "kind": kind, **M.judge(shape.wrapped, seed)}
    if rec["status"] != "passed":
        keep.mkdir(parents=True, exist_ok=True)
        BinTools.Write_s(shape.wrapped, str(keep / f"seed{seed}.bbrep"))
    return rec


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("count", nargs="?", type=int, default=200)
    ap.add_argument("first_seed", nargs="?", type=int, default=0)
    ap.add_argument("--out", default=str(ROOT / "out" / "fuzz_b3d"))
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    stamp = time.strftime("%Y%m%dT%H%M%S", time.gmtime())
    log = out / f"{stamp}.jsonl"
    counts: collections.Counter[str] = collections.Counter()
    with log.open("a") as fh:
        for seed in range(args.first_seed, args.first_seed + args.count):
            rec = run(seed, out / stamp)
            if rec is None:
                continue
            fh.write(json.dumps(rec) + "\n")
            fh.flush()
            counts[rec["status"]] += 1
            if rec["status"] != "passed":
                print(f"seed {seed} ({rec['kind']}): {rec['status']}: {rec['why'][:200]}")
    total = sum(counts.values())
    print(f"{total} solids: " + ", ".join(f"{v} {k}" for k, v in counts.most_common()))
    print(f"log: {log}")
    sys.exit(1 if counts["failed"] + counts["error"] + counts["crash"] else 0)


if __name__ == "__main__":
    main()
