"""Benchmark the 2D MAT engine against OCCT's BRepMAT2d and a sampled Voronoi method.

Usage: ``python bench/bench_2d.py [--quick] [--faces NAME ...] [--oracle auto|tests|fallback]``

See ``bench/README.md`` for what each column means. Writes ``bench/results_2d.md``.
"""

from __future__ import annotations

import argparse
import contextlib
import datetime as _dt
import json
import math
import platform
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

BENCH = Path(__file__).resolve().parent
ROOT = BENCH.parent
for _p in (str(ROOT), str(BENCH)):
    if _p not in sys.path:
        sys.path.insert(0, _p)

from _faces import count_edges, load_faces  # noqa: E402
from _geom import bbox_diag, face_frame, face_polygon  # noqa: E402
from _oracle_fallback import FallbackOracle  # noqa: E402
from OCP.BRep import BRep_Builder  # noqa: E402
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakePolygon  # noqa: E402
from OCP.BRepTools import BRepTools  # noqa: E402
from OCP.gp import gp_Pnt  # noqa: E402
from OCP.TopoDS import TopoDS_Compound  # noqa: E402

WORKER = BENCH / "_occt_mat2d_worker.py"
PER_BRANCH = 50


@dataclass
class Result:
    face: str
    edges: int
    method: str
    status: str = "ok"
    time_s: float | None = None
    sound: float | None = None  # max soundness error / diag
    compl: float | None = None  # max completeness error / diag
    n_points: int = 0
    notes: list[str] = field(default_factory=list)


@dataclass
class Output:
    points: np.ndarray  # (N, 3) model space
    polylines: list[np.ndarray] = field(default_factory=list)
    compound: object | None = None


# --------------------------------------------------------------------------- methods


def run_medialcad(face, repeats: int) -> tuple[float, Output]:
    import medialcad

    best = math.inf
    mat = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        mat = medialcad.medial_axis_2d(face)
        best = min(best, time.perf_counter() - t0)
    pts = np.asarray(mat.sample(per_branch=PER_BRANCH)[0], dtype=float)
    compound = None
    with contextlib.suppress(NotImplementedError):
        compound = mat.to_compound()
    return best, Output(pts, compound=compound)


def run_occt(face, repeats: int, timeout: float) -> tuple[str, float | None, Output, dict]:
    """BRepMAT2d in a worker process: ``(status, compute_s, output, meta)``."""
    with tempfile.TemporaryDirectory() as tmp:
        src, out = Path(tmp) / "face.brep", Path(tmp) / "out.npz"
        BRepTools.Write_s(face, str(src))
        cmd = [sys.executable, str(WORKER), str(src), str(out), "--repeats", str(repeats)]
        cmd += ["--per-arc", str(PER_BRANCH)]
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return "timeout", None, Output(np.zeros((0, 3))), {}
        if proc.returncode != 0 or not out.exists():
            sig = -proc.returncode if proc.returncode < 0 else None
            if sig:
                return "crashed", None, Output(np.zeros((0, 3))), {"why": f"signal {sig}"}
            err = proc.stderr.strip().splitlines()[-1:] if proc.stderr else [""]
            why = f"worker rc {proc.returncode}: {err[0][:70]}"
            return "error", None, Output(np.zeros((0, 3))), {"why": why}
        data = np.load(out)
        meta = json.loads(str(data["meta"]))
        pts = data["points"]
        lengths = data["polyline_lengths"]
        polylines = np.split(pts, np.cumsum(lengths)[:-1]) if len(lengths) else []
        return "ok", meta["compute_s"], Output(pts, list(polylines)), meta


def trimesh_pipeline(face, frame, diag: float, resolution: float):
    """face -> polygon -> trimesh medial axis; returns (segments (E, 2, 2) in frame coords)."""
    from trimesh.path.polygons import medial_axis

    poly = face_polygon(face, frame, 1e-5 * diag)
    edges, verts = medial_axis(poly, resolution=resolution, clip=(8, 10**7))
    return verts[edges]


def run_trimesh(face, frame, diag, resolution, repeats) -> tuple[float, Output]:
    best = math.inf
    segs = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        segs = trimesh_pipeline(face, frame, diag, resolution)
        best = min(best, time.perf_counter() - t0)
    segs3 = [frame.to_3d(s) for s in segs]
    pts = np.concatenate(segs3) if segs3 else np.zeros((0, 3))
    pts = np.unique(np.round(pts, 12), axis=0) if len(pts) else pts
    return best, Output(pts, polylines=segs3)


def tune_resolution(face, frame, diag, target_s: float) -> float:
    """A resolution whose trimesh pipeline time is close to ``target_s``."""
    lo_r, hi_r = diag / 20000, diag / 20
    r = diag / 200
    for _ in range(4):
        t, _ = run_trimesh(face, frame, diag, r, 2)
        if abs(t - target_s) < 0.15 * target_s:
            break
        r = float(np.clip(r * t / target_s, lo_r, hi_r))
    return r


# --------------------------------------------------------------------------- oracles


def polyline_compound(polylines):
    b = BRep_Builder()
    comp = TopoDS_Compound()
    b.MakeCompound(comp)
    n = 0
    for pl in polylines:
        pl = pl[np.all(np.isfinite(pl), axis=1)]
        mk = BRepBuilderAPI_MakePolygon()
        last = None
        for p in pl:
            if last is not None and np.linalg.norm(p - last) < 1e-9:
                continue
            mk.Add(gp_Pnt(*map(float, p)))
            last = p
        if last is not None and mk.Added() and mk.IsDone():
            b.Add(comp, mk.Wire())
            n += 1
    return comp if n else None


class Scorer:
    """Max soundness / completeness errors over the bbox diagonal for one face."""

    def __init__(self, face, mode: str, quick: bool) -> None:
        self.face = face
        self.diag = bbox_diag(face)
        self.quick = quick
        self.fallback = FallbackOracle(face, 2000 if quick else 4000)
        self.tests = None
        if mode in ("auto", "tests"):
            try:
                from tests import oracles

                self.tests = oracles
                self.fb = oracles.FaceBoundary(face)
            except Exception as exc:
                if mode == "tests":
                    raise
                print(f"  [tests.oracles unavailable: {exc}; using the fallback]")
                self.tests = None
        self.name = "tests/oracles.py (+ fallback screening)" if self.tests else FallbackOracle.name

    def score(self, out: Output) -> tuple[float, float]:
        pts = out.points
        if len(pts) == 0:
            return math.inf, math.inf
        tol = 1e-5 * self.diag
        screen = self.fallback.soundness(pts)
        if self.tests is None:
            sound = float(np.max(screen))
            compl = float(np.max(self.fallback.completeness(pts, out.polylines)))
            return sound / self.diag, compl / self.diag
        # the exact oracle costs ~20 ms a point: run it on the worst points by the
        # fallback screen plus a random subset
        k = 40 if self.quick else 150
        order = np.argsort(-screen)
        rng = np.random.default_rng(0)
        rest = order[k:]
        pick = np.concatenate([order[:k], rng.choice(rest, min(len(rest), k), replace=False)])
        sound = float(np.max(self.tests.soundness_2d(self.fb, pts[pick], tol)))
        target = out.compound
        if target is None and out.polylines:
            target = polyline_compound(out.polylines)
        if target is None:
            target = pts
        ce = self.tests.completeness_2d(self.fb, target, 150 if self.quick else 400)
        compl = float(np.nanmax(ce)) if np.any(np.isfinite(ce)) else math.inf
        return sound / self.diag, compl / self.diag


# --------------------------------------------------------------------------- driver


def classify(res: Result, out: Output, diag: float, bbox_pts: np.ndarray) -> Output:
    """Structural garbage checks; returns the output restricted to sane points."""
    pts = out.points
    finite = np.all(np.isfinite(pts), axis=1)
    lo, hi = bbox_pts.min(axis=0) - 0.01 * diag, bbox_pts.max(axis=0) + 0.01 * diag
    inb = finite & np.all((pts >= lo) & (pts <= hi), axis=1)
    reasons = []
    if len(pts) == 0:
        reasons.append("no output")
    if (~inb).any():
        reasons.append(f"{int((~inb).sum())} pts outside bbox/non-finite")
    if reasons:
        res.status = "garbage"
        res.notes.extend(reasons)
    polylines = [p[np.all(np.isfinite(p), axis=1)] for p in out.polylines]
    polylines = [p[np.all((p >= lo) & (p <= hi), axis=1)] for p in polylines]
    polylines = [p for p in polylines if len(p) >= 2]
    return Output(pts[inb], polylines, out.compound)


def finalize(res: Result) -> None:
    if res.status == "ok" and res.sound is not None and res.sound > 0.05:
        res.status = "garbage"
        res.notes.append("unsound > 5% diag")
    if res.status == "ok" and res.compl is not None and res.compl > 0.05:
        res.status = "incomplete"


def bench_face(name, face, args, scorer_mode) -> list[Result]:
    repeats = 1 if args.quick else 3
    frame = face_frame(face)
    diag = bbox_diag(face)
    edges = count_edges(face)
    poly = face_polygon(face, frame, 1e-5 * diag)
    bx0, by0, bx1, by1 = poly.bounds
    bbox_pts = frame.to_3d(np.array([[bx0, by0], [bx1, by1], [bx0, by1], [bx1, by0]]))
    scorer = Scorer(face, scorer_mode, args.quick)
    results: list[Result] = []

    def scored(res: Result, out: Output) -> Result:
        clean = classify(res, out, diag, bbox_pts)
        res.n_points = len(out.points)
        if len(clean.points):
            res.sound, res.compl = scorer.score(clean)
        finalize(res)
        return res

    # (a) medialcad
    ref_time = None
    res = Result(name, edges, "medialcad")
    try:
        t, out = run_medialcad(face, repeats)
        res.time_s = ref_time = t
        results.append(scored(res, out))
    except NotImplementedError:
        res.status = "n/a"
        res.notes.append("NotImplementedError")
        results.append(res)
    except Exception as exc:  # noqa: BLE001
        res.status = "error"
        res.notes.append(f"{type(exc).__name__}: {exc}"[:80])
        results.append(res)

    # (b) OCCT BRepMAT2d in a worker process
    res = Result(name, edges, "occt_brepmat2d")
    status, t, out, meta = run_occt(face, repeats, args.timeout)
    res.status, res.time_s = status, t
    if status == "ok":
        if meta.get("n_infinite_nodes") or meta.get("n_unbounded_arcs"):
            res.notes.append(
                f"{meta.get('n_infinite_nodes')} infinite nodes, "
                f"{meta.get('n_unbounded_arcs')} unbounded arcs"
            )
            res.status = "garbage"
        if not meta.get("is_done", True):
            res.status = "garbage"
            res.notes.append("not IsDone")
        res.notes.append(
            f"{meta.get('n_arcs', 0)} arcs, {meta.get('n_separators_dropped', 0)} separator arcs trimmed"
        )
        results.append(scored(res, out))
    else:
        res.notes.append(str(meta.get("why", status)))
        results.append(res)
    occt_time = res.time_s if res.status == "ok" else None

    # (c) trimesh at a tuned and a finer resolution
    target, tuned_to = ref_time, "medialcad"
    if target is None:
        target, tuned_to = occt_time, "occt"
    if target is None:
        res_c, tuned_to = diag / 200, "default diag/200"
    else:
        res_c = tune_resolution(face, frame, diag, target)
    for label, r in (("trimesh_tuned", res_c), ("trimesh_fine", res_c / 4)):
        res = Result(name, edges, label)
        try:
            t, out = run_trimesh(face, frame, diag, r, repeats)
            res.time_s = t
            res.notes.append(
                f"res={r / diag:.2e}*diag" + (f" (~{tuned_to})" if label == "trimesh_tuned" else "")
            )
            results.append(scored(res, out))
        except Exception as exc:  # noqa: BLE001
            res.status = "error"
            res.notes.append(f"{type(exc).__name__}: {exc}"[:80])
            results.append(res)
    for r in results:
        r.notes.insert(0, f"oracle={'tests' if scorer.tests else 'fallback'}")
    return results


def fmt(x: float | None, spec: str) -> str:
    if x is None:
        return "n/a"
    if math.isinf(x):
        return "inf"
    return format(x, spec)


def table(results: list[Result]) -> str:
    mc = {r.face: r.time_s for r in results if r.method == "medialcad" and r.status == "ok"}
    head = "| face | edges | method | time ms | ratio vs medialcad | sound err/diag | compl err/diag | status | notes |"
    lines = [head, "|" + "---|" * 9]
    for r in results:
        ref = mc.get(r.face)
        ratio = r.time_s / ref if (ref and r.time_s is not None) else None
        ms = r.time_s * 1e3 if r.time_s is not None else None
        lines.append(
            f"| {r.face} | {r.edges} | {r.method} | {fmt(ms, '.3f')} | {fmt(ratio, '.2f')} | "
            f"{fmt(r.sound, '.2e')} | {fmt(r.compl, '.2e')} | {r.status} | "
            f"{'; '.join(n for n in r.notes if not n.startswith('oracle='))} |"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="1 repeat, lighter oracles")
    ap.add_argument("--faces", nargs="*", help="only these face names")
    ap.add_argument("--oracle", choices=["auto", "tests", "fallback"], default="auto")
    ap.add_argument("--no-fixtures", action="store_true", help="built-in faces only")
    ap.add_argument("--no-builtin", action="store_true", help="fixture faces only")
    ap.add_argument("--timeout", type=float, default=120.0, help="BRepMAT2d worker timeout, s")
    ap.add_argument("--out", type=Path, default=BENCH / "results_2d.md")
    args = ap.parse_args(argv)

    faces, warnings = load_faces(
        ROOT / "fixtures" / "step" / "faces", not args.no_fixtures, not args.no_builtin
    )
    for w in warnings:
        print(f"warning: {w}")
    if args.faces:
        faces = [f for f in faces if f[0] in set(args.faces)]
    results: list[Result] = []
    t_start = time.perf_counter()
    for name, source, face in faces:
        print(f"{name} ({source}) ...", flush=True)
        try:
            results.extend(bench_face(name, face, args, args.oracle))
        except Exception as exc:  # noqa: BLE001
            print(f"  failed: {type(exc).__name__}: {exc}")
            results.append(
                Result(name, count_edges(face), "-", status="error", notes=[str(exc)[:80]])
            )
    tab = table(results)
    print(tab)
    oracles_used = sorted(
        {n.split("=", 1)[1] for r in results for n in r.notes if n.startswith("oracle=")}
    )
    header = [
        "# 2D MAT benchmark",
        "",
        f"- date: {_dt.datetime.now().isoformat(timespec='seconds')}",
        f"- command: `python bench/bench_2d.py {' '.join(sys.argv[1:] if argv is None else argv)}`",
        f"- python {platform.python_version()} on {platform.machine()}, "
        f"{'quick (1 repeat)' if args.quick else 'best of 3 repeats'}",
        f"- oracle: {', '.join(oracles_used) or 'n/a'}; bench wall time "
        f"{time.perf_counter() - t_start:.0f} s",
        "- columns: see bench/README.md",
        "",
    ]
    args.out.write_text("\n".join(header) + "\n" + tab + "\n")
    print(f"\nwritten {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
