"""How time and peak memory grow with the size of the input.

- 2D engine on star-shaped polygons with 10, 100, 1,000, 10,000 boundary edges;
- 2D engine on the same star written as 10 to 200 three-point B-spline pieces (how other
  CAD systems often write one smooth curve);
- 3D (extrusion) on gear wheels with 10 to 200 teeth.

Each case runs in its own process (peak RSS from ``resource``), with a time budget per
case: sizes beyond the budget are reported as such, not silently dropped.

    python bench/bench_scaling.py [--budget 120] [--only 2d|2dspline|3d] [--out bench/results_scaling.md]

With ``--only``, the rows of the other kind are kept from the existing results file.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

WORKER = r"""
import json, math, resource, sys, time
sys.path.insert(0, {root!r})
import cadquery as cq
kind, n = sys.argv[1], int(sys.argv[2])
def star(a):
    r = 50 * (1 + 0.15 * math.sin(7 * a) + 0.05 * math.sin(23 * a))
    return cq.Vector(r * math.cos(a), r * math.sin(a), 0)
if kind in ("2d", "2dspline"):
    if kind == "2d":
        pts = [star(2 * math.pi * i / n) for i in range(n)]
        face = cq.Face.makeFromWires(cq.Workplane().polyline(pts).close().val())
    else:
        a = [2 * math.pi * i / n for i in range(n + 1)]
        edges = [
            cq.Edge.makeSpline([star(a[i]), star(0.5 * (a[i] + a[i + 1])), star(a[(i + 1) % n])])
            for i in range(n)
        ]
        face = cq.Face.makeFromWires(cq.Wire.assembleEdges(edges))
    from medialcad import medial_axis_2d
    t0 = time.perf_counter()
    m = medial_axis_2d(face)
    out = {{"time": time.perf_counter() - t0, "branches": len(m.branches)}}
else:
    teeth = n
    r_root, r_tip = 40.0, 46.0
    pts = []
    for i in range(teeth):
        a0 = 2 * math.pi * i / teeth
        da = 2 * math.pi / teeth
        for f, r in ((0.0, r_root), (0.25, r_tip), (0.5, r_tip), (0.75, r_root)):
            a = a0 + f * da
            pts.append((r * math.cos(a), r * math.sin(a)))
    wp = cq.Workplane().polyline(pts).close().extrude(20).faces(">Z").workplane().hole(20)
    from medialcad.api import medial_axis
    t0 = time.perf_counter()
    m = medial_axis(wp.val())
    out = {{"time": time.perf_counter() - t0, "junctions": len(m.junctions), "sheets": len(m.sheets), "timings": m.timings}}
out["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps(out))
"""


LABELS = {"2d": "2D polygon edges", "2dspline": "2D spline pieces", "3d": "3D gear teeth"}
SIZES = {"2d": (10, 100, 1000, 10000), "2dspline": (10, 30, 100, 200), "3d": (10, 25, 50, 100, 200)}


def run_case(kind: str, n: int, budget: float) -> dict:
    code = WORKER.format(root=str(ROOT))
    try:
        res = subprocess.run(
            [sys.executable, "-c", code, kind, str(n)],
            capture_output=True,
            text=True,
            timeout=budget,
        )
    except subprocess.TimeoutExpired:
        return {"kind": kind, "n": n, "status": f"over the {budget:.0f} s budget"}
    if res.returncode != 0:
        return {"kind": kind, "n": n, "status": "failed: " + res.stderr.strip().splitlines()[-1]}
    out = json.loads(res.stdout.strip().splitlines()[-1])
    out.update(kind=kind, n=n, status="ok")
    return out


def _previous_rows(path: Path, kind: str) -> list[dict]:
    """The rows of ``kind`` in an existing results table (kept by ``--only``)."""
    label = LABELS[kind]
    rows: list[dict] = []
    if not path.exists():
        return rows
    for line in path.read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 5 or cells[0] != label:
            continue
        row: dict = {"kind": kind, "n": int(cells[1]), "status": cells[2]}
        if cells[2] == "ok":
            row.update(time=float(cells[3]), peak_rss_mb=float(cells[4]))
        rows.append(row)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--budget", type=float, default=120.0, help="seconds per case")
    ap.add_argument("--out", default=str(ROOT / "bench" / "results_scaling.md"))
    ap.add_argument("--only", choices=tuple(LABELS), help="run one kind only")
    args = ap.parse_args()
    rows = []
    for kind, sizes in SIZES.items():
        if args.only is not None and kind != args.only:
            rows += _previous_rows(Path(args.out), kind)
            continue
        prev = None
        for n in sizes:
            if prev is not None and prev.get("status") != "ok":
                rows.append({"kind": kind, "n": n, "status": "skipped (smaller size over budget)"})
                continue
            r = run_case(kind, n, args.budget)
            rows.append(r)
            prev = r
            print(json.dumps(r), flush=True)
    rows.sort(key=lambda r: list(LABELS).index(r["kind"]))  # in LABELS' order, as without --only
    lines = [
        "| case | n | status | time s | peak RSS MB | growth exponent |",
        "|---|---|---|---|---|---|",
    ]
    last: dict[str, dict] = {}
    for r in rows:
        exp = ""
        p = last.get(r["kind"])
        if r.get("status") == "ok" and p is not None:
            exp = f"{math.log(r['time'] / p['time']) / math.log(r['n'] / p['n']):.2f}"
        if r.get("status") == "ok":
            last[r["kind"]] = r
        label = LABELS[r["kind"]]
        lines.append(
            f"| {label} | {r['n']} | {r['status']} | {r.get('time', float('nan')):.2f} | "
            f"{r.get('peak_rss_mb', float('nan')):.0f} | {exp} |"
        )
    md = "\n".join(lines)
    print(md)
    out = Path(args.out)
    notes = _notes_after_table(out.read_text()) if out.exists() else ""
    out.write_text(
        "# Scaling (bench/bench_scaling.py)\n\nTime of the MAT computation only; growth "
        "exponent = log(t2/t1)/log(n2/n1) between consecutive sizes.\n\n" + md + "\n" + notes
    )


def _notes_after_table(text: str) -> str:
    """The hand-written notes below the table of an earlier results file, kept on rewrite."""
    lines = text.splitlines(keepends=True)
    rows = [i for i, line in enumerate(lines) if line.startswith("|")]
    return "".join(lines[rows[-1] + 1 :]) if rows else ""


if __name__ == "__main__":
    main()
