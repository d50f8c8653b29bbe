"""Worker process: OCCT ``BRepMAT2d_BisectingLocus`` on one face, isolated from the bench.

Usage: ``python _occt_mat2d_worker.py FACE.brep OUT.npz [--repeats N] [--per-arc K]``

Reads a face from a BREP file, runs ``BRepMAT2d_Explorer`` + ``BRepMAT2d_BisectingLocus``
(``Compute(explorer, 1, MAT_Left, GeomAbs_Arc, False)``, as ``BRepFill_OffsetWire`` does)
``N`` times, and writes to ``OUT.npz``: the best ``Compute`` wall time, the sampled
bisector points mapped to model space with the face's surface, per-arc polylines and
diagnostic counters. Arcs separating two boundary elements that meet smoothly (an edge
and its own end vertex at a reflex corner, two G1-joined edges) are Voronoi-diagram edges
but not medial-axis branches (except beyond a centre of curvature): their non-medial
samples are dropped unless ``--keep-separators``. A segfault in OCCT kills only this process; the bench reports it.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time

import numpy as np

# Bisector curves whose parameter range reaches this are unbounded (OCCT uses 2e100).
_HUGE = 1e50


def _read_face(path: str):
    from OCP.BRep import BRep_Builder
    from OCP.BRepTools import BRepTools
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS, TopoDS_Shape

    shape = TopoDS_Shape()
    if not BRepTools.Read_s(shape, path, BRep_Builder()):
        raise RuntimeError(f"cannot read {path}")
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    if not exp.More():
        raise RuntimeError("no face in BREP")
    return TopoDS.Face_s(exp.Current())


def _element(geom):
    """``("point", p)`` or ``("curve", [(p, t, k), (p, t, k)])`` for a MAT basic element:
    position, unit tangent and curvature vector at both ends."""
    if geom.DynamicType().Name() == "Geom2d_CartesianPoint":
        return "point", np.array([geom.X(), geom.Y()])
    from OCP.gp import gp_Pnt2d, gp_Vec2d

    ends = []
    for u in (geom.FirstParameter(), geom.LastParameter()):
        p, v, acc = gp_Pnt2d(), gp_Vec2d(), gp_Vec2d()
        geom.D2(u, p, v, acc)
        vv = np.array([v.X(), v.Y()])
        aa = np.array([acc.X(), acc.Y()])
        n = float(np.linalg.norm(vv)) or 1.0
        t = vv / n
        kappa = (vv[0] * aa[1] - vv[1] * aa[0]) / n**3
        ends.append((np.array([p.X(), p.Y()]), t, kappa * np.array([-t[1], t[0]])))
    return "curve", ends


def _separator(e1, e2, tol: float):
    """For a Voronoi edge between two boundary elements that meet smoothly, the
    junction and the curvature vectors there; ``None`` otherwise.

    An edge and its own end vertex (reflex corner), or two G1-joined curves, are
    separated near the junction ``J`` by the normal line there, which is no part of the
    medial axis up to the nearest centre of curvature on its side (discs tangent at
    ``J`` grow until then); beyond it the arc is a genuine branch. A point ``p`` is kept
    when ``|p - J| >= min 1/|k|`` over the curvature vectors ``k`` at ``J`` with
    ``(p - J) . k > 0`` (none: dropped).
    """
    if e1[0] == "point" and e2[0] == "point":
        return None
    if e1[0] == "point" or e2[0] == "point":
        pt, cv = (e1[1], e2[1]) if e1[0] == "point" else (e2[1], e1[1])
        if min(np.linalg.norm(pt - cv[0][0]), np.linalg.norm(pt - cv[1][0])) < tol:
            return pt, []
        return None
    for pa, ta, ka in e1[1]:
        for pb, tb, kb in e2[1]:
            cross = abs(ta[0] * tb[1] - ta[1] * tb[0])
            if np.linalg.norm(pa - pb) < tol and cross < 1e-6 and ta @ tb > 0:
                return pa, [ka, kb]
    return None


def _medial_mask(pts2: np.ndarray, junction: np.ndarray, kvecs: list) -> np.ndarray:
    """Samples of a separator arc that are medial: beyond the nearest centre of
    curvature (among the curvature vectors pointing to their side)."""
    w = pts2 - junction
    dist = np.linalg.norm(w, axis=1)
    rho = np.full(len(pts2), np.inf)
    for k in kvecs:
        kn = float(np.linalg.norm(k))
        if kn > 0:
            rho = np.where(w @ k > 0, np.minimum(rho, 1.0 / kn), rho)
    return dist >= rho * (1.0 - 1e-9)


def run(face_path: str, repeats: int, per_arc: int, keep_separators: bool = False) -> dict:
    from OCP.BRep import BRep_Tool
    from OCP.BRepMAT2d import BRepMAT2d_BisectingLocus, BRepMAT2d_Explorer
    from OCP.GeomAbs import GeomAbs_Arc
    from OCP.MAT import MAT_Left
    from OCP.TopAbs import TopAbs_FORWARD
    from OCP.TopoDS import TopoDS

    face = TopoDS.Face_s(_read_face(face_path).Oriented(TopAbs_FORWARD))
    best = math.inf
    locus = None
    for _ in range(max(1, repeats)):
        explorer = BRepMAT2d_Explorer(face)
        locus = BRepMAT2d_BisectingLocus()
        t0 = time.perf_counter()
        locus.Compute(explorer, 1, MAT_Left, GeomAbs_Arc, False)
        best = min(best, time.perf_counter() - t0)
    assert locus is not None
    info: dict = {"compute_s": best, "is_done": bool(locus.IsDone())}
    if not locus.IsDone():
        return info | {"points": np.zeros((0, 3)), "polylines": []}

    graph = locus.Graph()
    info["n_arcs"] = graph.NumberOfArcs()
    info["n_nodes"] = graph.NumberOfNodes()
    info["n_infinite_nodes"] = graph.NumberOfInfiniteNodes()
    surf = BRep_Tool.Surface_s(face)
    polylines: list[np.ndarray] = []
    n_unbounded = 0
    n_failed = 0
    n_sep = 0
    elements = {}
    for i in range(1, graph.NumberOfArcs() + 1):
        arc = graph.Arc(i)
        if not keep_separators:
            try:
                pair = []
                for be in (arc.FirstElement(), arc.SecondElement()):
                    if be.Index() not in elements:
                        elements[be.Index()] = _element(locus.GeomElt(be))
                    pair.append(elements[be.Index()])
                sep = _separator(pair[0], pair[1], 1e-7)
            except Exception:  # noqa: BLE001 - keep the arc when unsure
                sep = None
        else:
            sep = None
        try:
            curve = locus.GeomBis(arc, False).Value()
            u0, u1 = curve.FirstParameter(), curve.LastParameter()
        except Exception:  # noqa: BLE001 - OCCT raised on this arc
            n_failed += 1
            continue
        if not (abs(u0) < _HUGE and abs(u1) < _HUGE):
            n_unbounded += 1
            u0, u1 = max(min(u0, _HUGE), -_HUGE), max(min(u1, _HUGE), -_HUGE)
        pts, uv = [], []
        for u in np.linspace(u0, u1, per_arc):
            try:
                p2 = curve.Value(float(u))
                p3 = surf.Value(p2.X(), p2.Y())
                pts.append((p3.X(), p3.Y(), p3.Z()))
                uv.append((p2.X(), p2.Y()))
            except Exception:  # noqa: BLE001
                n_failed += 1
        if sep is not None and pts:
            keep = _medial_mask(np.asarray(uv), sep[0], sep[1])
            if keep.any():
                # the branch starts exactly at the nearest centre of curvature
                w = np.asarray(uv)[keep][0] - sep[0]
                ks = [k for k in sep[1] if w @ k > 0]
                k = max(ks, key=lambda v: float(np.linalg.norm(v)))
                c = sep[0] + k / float(k @ k)
                p3 = surf.Value(float(c[0]), float(c[1]))
                pts = [(p3.X(), p3.Y(), p3.Z())] + [
                    p for p, kk in zip(pts, keep, strict=True) if kk
                ]
            else:
                pts = []
            n_sep += 1
        if pts:
            polylines.append(np.asarray(pts, dtype=float))
    info["n_separators_dropped"] = n_sep
    info["n_unbounded_arcs"] = n_unbounded
    info["n_failed_evals"] = n_failed
    points = np.concatenate(polylines) if polylines else np.zeros((0, 3))
    return info | {"points": points, "polylines": polylines}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("face")
    ap.add_argument("out")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--per-arc", type=int, default=50)
    ap.add_argument("--keep-separators", action="store_true")
    args = ap.parse_args(argv)
    res = run(args.face, args.repeats, args.per_arc, args.keep_separators)
    polylines = res.pop("polylines")
    points = res.pop("points")
    lengths = np.array([len(p) for p in polylines], dtype=np.int64)
    np.savez(
        args.out,
        points=points,
        polyline_lengths=lengths,
        meta=np.array(json.dumps(res)),
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
