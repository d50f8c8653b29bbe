"""3D MAT benchmark: medialcad vs a sampled Voronoi-pole MAT, side by side in one process.

For each solid (the paper's Table 1 objects and the revolution fixtures) it times
``medialcad.medial_axis`` end to end, and a sampled method: boundary samples (by area,
``--samples`` of them), ``scipy.spatial.Voronoi``, and the *poles* (Voronoi vertices
inside the solid, the classic sampled approximation of the MAT). Both are judged by the
same independent oracle (``tests/oracles3d.py``): soundness (how far output points are
from being medial) and completeness (how far true medial points are from the output),
relative to the bounding-box diagonal.

    python bench/bench_3d.py            # all objects, writes bench/results_3d.md
    python bench/bench_3d.py --quick    # fewer oracle samples
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from scipy.spatial import Voronoi

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from medialcad.api import medial_axis  # noqa: E402
from medialcad.recognition import read_step  # noqa: E402
from tests import oracles3d as O  # noqa: E402

OBJECTS = [
    ("freeform_extrusion_1", "Fig. 16, 12 junctions, 6 s (PIII)"),
    ("i_section", "Fig. 18, 12 junctions, 6 s (PIII)"),
    ("gear_wheel", "Fig. 19, 32 junctions, 11 s (PIII)"),
    ("machine_tool_bed", "Fig. 20"),
    ("spider_joint", "Fig. 22 (revolution)"),
    ("bearing_housing", "Fig. 23 (revolution)"),
    ("stepped_shaft", "full revolution on the axis"),
    ("small_angle_revolution", "10 degrees"),
    ("pin_pie_slice", "120-degree pie slice (profile on the axis)"),
    ("pin_wide_slice", "270-degree pie slice (the axis a reflex edge)"),
]


def voronoi_poles(boundary: O.SolidBoundary, n: int) -> tuple[np.ndarray, float]:
    """Poles of a Voronoi diagram of ``n`` boundary samples (inside the solid)."""
    t0 = time.perf_counter()
    pts, _ = boundary.boundary_samples(n, seed=1)
    vor = Voronoi(pts)
    verts = vor.vertices
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    keep = np.all((verts >= lo) & (verts <= hi), axis=1)
    verts = verts[keep]
    inside = boundary.inside(verts)
    poles = verts[inside]
    return poles, time.perf_counter() - t0


def run(quick: bool) -> list[dict]:
    rows = []
    n_check = 150 if quick else 400
    n_complete = 60 if quick else 150
    for name, note in OBJECTS:
        path = ROOT / "fixtures" / "step" / "solids" / f"{name}.step"
        solid = read_step(path)[0]
        t0 = time.perf_counter()
        mat = medial_axis(solid)
        t_mat = time.perf_counter() - t0
        sb = O.SolidBoundary(solid)
        rng = np.random.default_rng(0)
        pts = O.sample_compound(mat.compound, 12, 4)
        if len(pts) > n_check:
            pts = pts[rng.choice(len(pts), n_check, replace=False)]
        snd = O.soundness(sb, pts)
        cmp_ = O.completeness(sb, mat.compound, n_complete)
        poles, t_vor = voronoi_poles(sb, 4000 if quick else 20000)
        ppts = (
            poles
            if len(poles) <= n_check
            else poles[rng.choice(len(poles), n_check, replace=False)]
        )
        snd_v = O.soundness(sb, ppts)
        cmp_v = O.completeness(sb, poles, n_complete)
        d = sb.diag
        rows.append(
            {
                "name": name,
                "note": note,
                "kind": mat.kind,
                "junctions": len(mat.junctions),
                "sheets": len(mat.sheets),
                "time_s": t_mat,
                "timings": mat.timings,
                "sound": float(np.nanmax(snd) / d),
                "complete": float(np.max(cmp_) / d),
                "vor_time_s": t_vor,
                "vor_sound": float(np.nanmax(np.where(np.isinf(snd_v), np.nan, snd_v)) / d),
                "vor_complete": float(np.max(cmp_v) / d),
            }
        )
        r = rows[-1]
        print(
            f"{name:24s} {r['kind']:10s} J={r['junctions']:3d} t={r['time_s']:6.2f}s "
            f"sound={r['sound']:.1e} complete={r['complete']:.1e} | voronoi t={t_vor:6.2f}s "
            f"sound={r['vor_sound']:.1e} complete={r['vor_complete']:.1e}",
            flush=True,
        )
    return rows


def table(rows: list[dict]) -> str:
    out = [
        "| object | kind | junctions | medialcad s | soundness | completeness | "
        "Voronoi poles s | soundness | completeness | error ratio | time ratio |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        err = max(r["sound"], r["complete"], 1e-16)
        err_v = max(r["vor_sound"], r["vor_complete"])
        out.append(
            f"| {r['name']} ({r['note']}) | {r['kind']} | {r['junctions']} | {r['time_s']:.2f} | "
            f"{r['sound']:.1e} | {r['complete']:.1e} | {r['vor_time_s']:.2f} | "
            f"{r['vor_sound']:.1e} | {r['vor_complete']:.1e} | {err_v / err:.0f}x smaller | "
            f"{r['vor_time_s'] / r['time_s']:.2f} |"
        )
    return "\n".join(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default=str(ROOT / "bench" / "results_3d.md"))
    args = ap.parse_args()
    rows = run(args.quick)
    md = table(rows)
    print(md)
    Path(args.out).write_text(
        "# 3D benchmark (bench/bench_3d.py)\n\nErrors relative to the bounding-box diagonal; "
        "medialcad's default tolerance is 1e-5. Time ratio = Voronoi time / medialcad time.\n\n"
        + md
        + "\n\n```json\n"
        + json.dumps(rows, indent=1)
        + "\n```\n"
    )


if __name__ == "__main__":
    main()
