"""Public entry points: orchestration only."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from medialcad.errors import (
    BelowToleranceError,
    ComputationError,
    InputError,
    MedialCadError,
    SelfIntersectingBoundaryError,
)
from medialcad.frame import Frame
from medialcad.mat2d.boundary import Boundary, build_boundary
from medialcad.mat2d.graph import Branch, MedialGraph, Node, NodeKind

__all__ = ["ANGLE_TOL", "MedialAxis2D", "medial_axis_2d"]

ANGLE_TOL = 1e-6
"""Joints whose tangents turn by less than this (radians) are tangent-continuous."""


@dataclass(frozen=True)
class MedialAxis2D:
    """The medial axis transform of a planar face.

    Attributes:
        graph: the medial graph (nodes, branches, footpoints, splines).
        face: the input face as a ``TopoDS_Face``.
        boundary: the exact boundary model the graph's element indices refer to.
    """

    graph: MedialGraph
    face: Any
    boundary: Boundary | None = None

    def outline(self, per_piece: int = 120) -> list[np.ndarray]:
        """The boundary the MAT was traced on, as polylines in :attr:`frame` (an oblique
        prism's cross-section is not its display ``face`` re-read: that face's own
        frame is turned)."""
        if self.boundary is None:
            from medialcad.occ.face2d import planar_face

            pieces = [p for loop in planar_face(self.face).loops for p in loop]
        else:
            pieces = [e.piece for e in self.boundary.elements if e.piece is not None]
        return [p.curve.point(np.linspace(p.t0, p.t1, per_piece)) for p in pieces]

    @property
    def nodes(self) -> tuple[Node, ...]:
        return self.graph.nodes

    @property
    def branches(self) -> tuple[Branch, ...]:
        return self.graph.branches

    @property
    def frame(self) -> Frame:
        return self.graph.frame

    @property
    def tol(self) -> float:
        return self.graph.tol

    @property
    def rmax(self) -> float:
        return self.graph.rmax

    @property
    def branch_points(self) -> tuple[Node, ...]:
        return tuple(n for n in self.nodes if n.kind is NodeKind.BRANCH_POINT)

    @property
    def end_points(self) -> tuple[Node, ...]:
        return tuple(n for n in self.nodes if n.kind is not NodeKind.BRANCH_POINT)

    def sample(self, per_branch: int = 50) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Points of the fitted medial axis in model space and their radii.

        Returns ``(points (N, 3), radius (N,))``: ``per_branch`` points evaluated on each
        branch's spline plus every node.
        """
        pts, rad = [], []
        for b in self.branches:
            lo, hi = b.spline.domain
            v = b.spline(np.linspace(lo, hi, per_branch))
            pts.append(v[:, :2])
            rad.append(v[:, 2])
        for n in self.nodes:
            pts.append(n.point_2d[None, :])
            rad.append(np.array([n.radius]))
        if not pts:
            return np.zeros((0, 3)), np.zeros(0)
        return self.frame.to_3d(np.vstack(pts)), np.concatenate(rad)

    def to_compound(self) -> Any:
        """A ``TopoDS_Compound`` of B-spline edges (one per branch) and vertices (isolated
        nodes), in the face's plane in model space."""
        from medialcad.occ.build import bspline_curve, edge_between, vertex
        from medialcad.occ.shapes import compound

        verts = [vertex(n.point) for n in self.nodes]
        used: set[int] = set()
        shapes: list[Any] = []
        for b in self.branches:
            poles = self.frame.to_3d(b.spline.coeffs[:, :2])
            curve = bspline_curve(b.spline.knots, poles, b.spline.degree)
            v0 = verts[b.start] if b.start is not None else None
            v1 = verts[b.end] if b.end is not None else None
            if b.start is not None and b.end is not None:
                used.update((b.start, b.end))
            shapes.append(edge_between(curve, v0, v1))
        shapes += [v for i, v in enumerate(verts) if i not in used]
        return compound(shapes)


def medial_axis_2d(face: Any, tol: float | None = None) -> MedialAxis2D:
    """The exact 2D medial axis transform of a planar face.

    Args:
        face: a ``TopoDS_Face``, a cadquery ``Face``/``Workplane`` holding one face, or a
            build123d ``Face``, in any plane anywhere in space.
        tol: geometric tolerance of the fitted branches; default ``1e-5`` times the
            bounding-box diagonal of the face.

    Raises:
        NotAFaceError, NonPlanarFaceError, OpenWireError, SelfIntersectingBoundaryError,
        DegenerateFaceError: the input cannot be handled.
        ComputationError: an internal failure.
    """
    from medialcad.occ.face2d import planar_face

    try:
        tol_abs = None if tol is None else float(tol)
    except (TypeError, ValueError) as err:
        raise InputError(f"tol must be a positive number, got {tol!r}") from err
    if tol_abs is not None and (not np.isfinite(tol_abs) or tol_abs <= 0):
        raise InputError(f"tol must be a positive number, got {tol!r}")
    return medial_axis_of_planar(planar_face(face), tol_abs)


def medial_axis_of_planar(pf: Any, tol: float | None) -> MedialAxis2D:
    """:func:`medial_axis_2d` of a face already read into exact curves
    (a :class:`medialcad.occ.face2d.PlanarFace`)."""
    from medialcad.mat2d.trace import TraceSettings, trace_medial_graph

    tol_abs = 1e-5 * pf.diag if tol is None else tol
    try:
        boundary = build_boundary(pf.loops, gap_tol=pf.gap_tol, angle_tol=ANGLE_TOL, tol=tol_abs)
        _check_simple(boundary)
        _check_resolvable(boundary, tol_abs, pf.frame)
        settings = TraceSettings(tol=tol_abs, spacing=pf.diag / 200.0)
        graph = trace_medial_graph(boundary, pf.frame, settings)
    except MedialCadError:
        raise
    except MemoryError as err:
        raise ComputationError("medial axis computation ran out of memory") from err
    except (ArithmeticError, ValueError, IndexError, KeyError, TypeError, AssertionError) as err:
        raise ComputationError(
            f"medial axis computation failed: {type(err).__name__}: {err}"
        ) from err
    return MedialAxis2D(graph, pf.face, boundary)


FEATURE_TOLERANCES = 2.0
"""An edge between two corners must be at least this many tolerances long."""


def _check_resolvable(boundary: Boundary, tol: float, frame: Frame) -> None:
    """Refuse features the tolerance cannot resolve: an edge shorter than
    ``FEATURE_TOLERANCES * tol`` with a corner (not a tangent join) at an end.

    Its medial branches would be shorter than the error allowed on them (a notch of
    1e-4 on a part of 100 at the default tol 1e-3 gives branches placed no better than
    the notch itself); tangent-continuous short pieces of a smooth curve are fine.
    """
    corners = {
        (c.loop, round(c.s, 9))
        for c in boundary.corners
        if abs(c.turn) > 1e-3  # a real corner, not a G1 join split by the modeller
    }
    short = []
    for e in boundary.elements:
        if e.piece is None or e.length >= FEATURE_TOLERANCES * tol:
            continue
        s1 = (e.s0 + e.length) % boundary.loop_lengths[e.loop]
        if (e.loop, round(e.s0, 9)) in corners or (e.loop, round(s1, 9)) in corners:
            short.append(e)
    if short:
        e = min(short, key=lambda x: x.length)
        assert e.piece is not None
        mid = e.piece.curve.point(np.array([0.5 * (e.piece.t0 + e.piece.t1)]))[0]
        where = ", ".join(f"{x:.6g}" for x in frame.to_3d(mid[None])[0])
        raise BelowToleranceError(
            f"{len(short)} edge(s) between corners are shorter than {FEATURE_TOLERANCES:g} x "
            f"the tolerance {tol:.3g}; the shortest, {e.length:.3g} long at ({where}), is a "
            "feature too small to resolve: pass a smaller tol or remove the feature"
        )


def _check_simple(boundary: Boundary) -> None:
    """Refuse boundaries whose edges cross (OCC's checker misses some of these).

    Polylines of every edge are tested pairwise where their segments are close enough
    to meet (a KD-tree on segment midpoints), for proper crossings between different
    edges and between segments of one edge that do not follow each other.
    """
    from scipy.spatial import cKDTree

    from medialcad.mat2d.curves import LineCurve

    a_list, b_list, idx_list = [], [], []
    sagitta, chord = 1e-7 * boundary.diag, boundary.diag / 400
    for e in boundary.elements:
        if e.piece is None:
            continue
        # enough points that the chords stay within ``sagitta`` of the curve: thin walls
        # between arcs must not look like crossings
        if isinstance(e.piece.curve, LineCurve):
            kmax = 0.0
        else:
            _, _, k = boundary.frame_at(e, np.linspace(e.piece.t0, e.piece.t1, 65))
            kmax = float(np.abs(k).max())
        # ... and short enough that the KD-tree's search radius stays local
        n = int(
            np.clip(
                max(np.ceil(e.length * np.sqrt(kmax / (8 * sagitta))), np.ceil(e.length / chord)),
                2,
                20000,
            )
        )
        p = e.piece.curve.point(np.linspace(e.piece.t0, e.piece.t1, n + 1))
        a_list.append(p[:-1])
        b_list.append(p[1:])
        idx_list.append(np.full(len(p) - 1, e.index))
    a, b, idx = np.vstack(a_list), np.vstack(b_list), np.concatenate(idx_list)
    mid, d = 0.5 * (a + b), b - a
    half = 0.5 * float(np.linalg.norm(d, axis=1).max())
    pairs = cKDTree(mid).query_pairs(2.0 * half + 1e-12, output_type="ndarray")
    if len(pairs) == 0:
        return
    i, j = pairs[:, 0], pairs[:, 1]
    # segments of different edges, or of one edge that are not neighbours (a curve
    # crossing itself; the first and last segments of a closed edge are neighbours)
    first = np.searchsorted(idx, idx, side="left")
    last = np.searchsorted(idx, idx, side="right") - 1
    step = np.abs(i - j)
    wrap = (np.minimum(i, j) == first[i]) & (np.maximum(i, j) == last[i])
    closed = np.linalg.norm(a[first[i]] - b[last[i]], axis=1) <= 1e-9 * boundary.diag
    keep = (idx[i] != idx[j]) | ((step > 1) & ~(wrap & closed))
    i, j = i[keep], j[keep]
    u = a[j] - a[i]
    den = d[i, 0] * d[j, 1] - d[i, 1] * d[j, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        ti = (u[:, 0] * d[j, 1] - u[:, 1] * d[j, 0]) / den
        tj = (u[:, 0] * d[i, 1] - u[:, 1] * d[i, 0]) / den
    inner = (ti > 1e-6) & (ti < 1 - 1e-6) & (tj > 1e-6) & (tj < 1 - 1e-6)
    if np.any((np.abs(den) > 1e-14 * boundary.diag**2) & inner):
        raise SelfIntersectingBoundaryError("the boundary of the face intersects itself")


def medial_axis(solid: Any, tol: float | None = None) -> Any:
    """The exact 3D medial axis transform of an extrusion or a revolution.

    Args:
        solid: a ``TopoDS_Solid`` (or a shape holding one solid), a cadquery
            ``Workplane``/``Shape`` or a build123d shape.
        tol: geometric tolerance; default ``1e-5`` times the solid's bounding-box diagonal.

    Returns:
        A :class:`medialcad.mat3d.result.MedialAxis3D`.

    Raises:
        NoSolidError, NotExtrusionOrRevolutionError, UnsupportedSolidError, InputError:
            the solid cannot be handled.
        ComputationError: an internal failure.
    """
    import time

    from medialcad.mat3d.solid import medial_axis_of

    t0 = time.perf_counter()
    tol_abs = _check_tol(tol)
    from medialcad.recognition import recognize

    reading = recognize(solid)
    t1 = time.perf_counter()
    return medial_axis_of(reading, tol_abs, {"recognition": t1 - t0})


def _check_tol(tol: float | None) -> float | None:
    try:
        tol_abs = None if tol is None else float(tol)
    except (TypeError, ValueError) as err:
        raise InputError(f"tol must be a positive number, got {tol!r}") from err
    if tol_abs is not None and (not np.isfinite(tol_abs) or tol_abs <= 0):
        raise InputError(f"tol must be a positive number, got {tol!r}")
    return tol_abs
