"""The boundary of a planar face as medial-axis elements on a loop coordinate.

Each loop is oriented with the face on its left (outer loop counter-clockwise, holes
clockwise), so the inward normal is the tangent turned left and the signed curvature is
positive where the boundary is convex. The elements are the edges and the reflex
vertices (with their cone of normals). Every element owns an interval of its loop's
coordinate ``s`` (edges: their length, mapped linearly to the curve parameter; reflex
vertices: their normal angle times a length scale), so a boundary point and its normal
are a function of ``(loop, s)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from medialcad.errors import DegenerateFaceError, OpenWireError
from medialcad.mat2d.curves import Curve, LineCurve

__all__ = ["Boundary", "EdgePiece", "build_boundary"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class EdgePiece:
    """An edge of a loop, traversed from parameter ``t0`` to ``t1`` (either order)."""

    curve: Curve
    t0: float
    t1: float
    edge_index: int


@dataclass(frozen=True)
class Element:
    """A medial element: an oriented edge (``piece``) or a reflex vertex (``vertex``)."""

    index: int
    loop: int
    s0: float
    length: float  # extent on the loop coordinate
    piece: EdgePiece | None = None
    vertex: FloatArray | None = None
    theta0: float = 0.0  # reflex vertex: normal angle at s0 (decreasing along s)
    theta1: float = 0.0

    @property
    def is_vertex(self) -> bool:
        return self.vertex is not None


@dataclass(frozen=True)
class Corner:
    """A vertex between two consecutive edges of a loop."""

    loop: int
    s: float
    point: FloatArray
    turn: float  # signed turning angle of the tangent (>0 convex, <0 reflex)


@dataclass(frozen=True)
class Boundary:
    elements: tuple[Element, ...]
    loop_lengths: tuple[float, ...]
    corners: tuple[Corner, ...]
    diag: float
    angle_scale: float  # length on s per radian of a reflex vertex

    # -- evaluation -------------------------------------------------------------
    def element_at(self, loop: int, s: float) -> Element:
        for e in self.elements:
            if e.loop == loop and e.s0 <= s <= e.s0 + e.length:
                return e
        raise ValueError("s outside loop")

    def param_of(self, e: Element, s: FloatArray) -> FloatArray:
        """Curve parameter (edge) or normal angle (vertex) at loop coordinate ``s``."""
        f = (np.asarray(s, dtype=float) - e.s0) / e.length
        if e.piece is not None:
            return e.piece.t0 + f * (e.piece.t1 - e.piece.t0)
        return e.theta0 + f * (e.theta1 - e.theta0)

    def s_of(self, e: Element, param: FloatArray) -> FloatArray:
        """Inverse of :meth:`param_of`."""
        p = np.asarray(param, dtype=float)
        if e.piece is not None:
            f = (p - e.piece.t0) / (e.piece.t1 - e.piece.t0)
        else:
            f = (p - e.theta0) / (e.theta1 - e.theta0)
        return e.s0 + np.clip(f, 0.0, 1.0) * e.length

    def frame_at(self, e: Element, param: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Boundary point, unit inward normal and signed curvature at ``param``."""
        p = np.atleast_1d(np.asarray(param, dtype=float))
        if e.piece is not None:
            pt, d1, d2 = e.piece.curve.derivs(p)
            sense = 1.0 if e.piece.t1 > e.piece.t0 else -1.0
            speed = np.linalg.norm(d1, axis=1)
            stalled = speed <= 1e-12 * max(float(speed.max(initial=0.0)), 1e-300)
            if np.any(stalled):
                # a degenerate end (repeated pole): take the limit from just inside
                lo, hi = sorted((e.piece.t0, e.piece.t1))
                nudge = 1e-7 * (hi - lo)
                q = np.clip(
                    p[stalled] + np.where(p[stalled] <= 0.5 * (lo + hi), nudge, -nudge), lo, hi
                )
                _, d1[stalled], d2[stalled] = e.piece.curve.derivs(q)
                speed = np.linalg.norm(d1, axis=1)
            tan = sense * d1 / speed[:, None]
            nrm = np.column_stack([-tan[:, 1], tan[:, 0]])
            k = sense * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / speed**3
            return pt, nrm, k
        assert e.vertex is not None
        pt = np.broadcast_to(e.vertex, (len(p), 2)).copy()
        nrm = np.column_stack([np.cos(p), np.sin(p)])
        return pt, nrm, np.full(len(p), -np.inf)  # reflex: never a curvature bound


def _signed_area(pts: FloatArray) -> float:
    x, y = pts[:, 0], pts[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _loop_polyline(loop: list[EdgePiece], n: int = 64) -> FloatArray:
    """Points around a loop: a line's start point, ``n`` points of a curve."""
    pts = [
        p.curve.point([p.t0])
        if isinstance(p.curve, LineCurve)
        else p.curve.point(np.linspace(p.t0, p.t1, n, endpoint=False))
        for p in loop
    ]
    return np.vstack(pts)


def _end_derivs(piece: EdgePiece, at_end: bool) -> tuple[FloatArray, FloatArray]:
    """First and second derivative of the piece's curve at one end; at a degenerate end
    (a repeated pole) the limit from just inside."""
    t = piece.t1 if at_end else piece.t0
    _, d1, d2 = piece.curve.derivs([t])
    if np.linalg.norm(d1[0]) <= 1e-12 * max(abs(piece.t1 - piece.t0), 1e-300):
        _, d1, d2 = piece.curve.derivs(
            [t + 1e-7 * (piece.t0 - piece.t1 if at_end else piece.t1 - piece.t0)]
        )
    return d1[0], d2[0]


def _tangent(piece: EdgePiece, at_end: bool) -> FloatArray:
    if isinstance(piece.curve, LineCurve):
        d = piece.curve.direction * (1.0 if piece.t1 > piece.t0 else -1.0)
        return np.asarray(d / math.hypot(d[0], d[1]))
    d1, _ = _end_derivs(piece, at_end)
    v = d1 * (1.0 if piece.t1 > piece.t0 else -1.0)
    return np.asarray(v / np.linalg.norm(v))


def _curvature(piece: EdgePiece, at_end: bool) -> float:
    """Signed curvature (> 0 turning left, along the loop) at an end of ``piece``."""
    if isinstance(piece.curve, LineCurve):
        return 0.0
    d1, d2 = _end_derivs(piece, at_end)
    sense = 1.0 if piece.t1 > piece.t0 else -1.0
    return sense * float(d1[0] * d2[1] - d1[1] * d2[0]) / float(np.linalg.norm(d1)) ** 3


def _cusp_turn(a: EdgePiece, b: EdgePiece, diag: float) -> float | None:
    """The turn at a cusp between ``a`` (arriving) and ``b`` (leaving): ``-pi`` when it
    is reflex (the face on both sides of the two curves leaving it in one direction:
    the meridian of a fillet revolved about the edge it rounds), None when it is
    convex (a wedge of zero angle) or undecided. Both curves leave the cusp along ``u``;
    at a distance ``x`` along ``u`` they lie ``-ka x^2 / 2`` and ``kb x^2 / 2`` to the
    left of it (``a`` reversed flips its curvature); the face is left of ``b`` and right
    of ``a``: a wedge between them when ``ka + kb < 0``, everything but it when > 0."""
    ka, kb = _curvature(a, True), _curvature(b, False)
    return -np.pi if (ka + kb) * diag > 1e-6 else None


def _turn(ta: FloatArray, tb: FloatArray) -> float:
    """The signed angle from unit tangent ``ta`` to ``tb`` (> 0 turning left)."""
    return float(np.arctan2(ta[0] * tb[1] - ta[1] * tb[0], ta @ tb))


def _reverse(loop: list[EdgePiece]) -> list[EdgePiece]:
    return [EdgePiece(p.curve, p.t1, p.t0, p.edge_index) for p in reversed(loop)]


def _piece_length(p: EdgePiece) -> float:
    if isinstance(p.curve, LineCurve):
        return float(abs(p.t1 - p.t0) * np.linalg.norm(p.curve.direction))
    t = np.linspace(p.t0, p.t1, 257)
    pts = p.curve.point(t)
    return float(np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1)))


def _split_seam_corner(loop: list[EdgePiece], min_turn: float) -> list[EdgePiece]:
    """A loop of one edge whose seam is a convex corner turning by more than ``min_turn``
    (a closed curve written clamped, ending at an angle to its start) as two pieces of
    that edge, halves of its parameter range: a corner joins two elements, as everywhere
    else (traced as one element, the corner's spoke was paired across its own seam: the
    medial axis refused or, at 1e-4 rad, wrong)."""
    if len(loop) != 1:
        return loop
    (p,) = loop
    if _turn(_tangent(p, True), _tangent(p, False)) <= min_turn:
        return loop
    tm = 0.5 * (p.t0 + p.t1)
    return [EdgePiece(p.curve, p.t0, tm, p.edge_index), EdgePiece(p.curve, tm, p.t1, p.edge_index)]


def build_boundary(
    loops: list[list[EdgePiece]], gap_tol: float, angle_tol: float, tol: float | None = None
) -> Boundary:
    """Orient the loops, classify the corners and lay out the elements.

    Args:
        loops: connected edge pieces of each loop (any orientation, any loop first).
        gap_tol: largest gap allowed between consecutive pieces.
        angle_tol: turning angles below this (radians) are tangent-continuous joins.
        tol: the medial axis's tolerance. With it, a one-edge loop whose seam is a convex
            corner is split there into two elements (:func:`_split_seam_corner`) unless
            the corner is flat at the tolerance: turning by ``a`` with ``a diag / 2 <=
            tol``, the feet of its spoke's disks (radius below ``diag / 2``) lie within
            ``tol`` of it, and the corner is crossed as a smooth point of the curve.

    Raises:
        OpenWireError: consecutive pieces do not meet.
        DegenerateFaceError: a loop with (near) zero area or zero length.
    """
    polys = [_loop_polyline(lp) for lp in loops]
    allpts = np.vstack(polys)
    diag = float(np.linalg.norm(allpts.max(axis=0) - allpts.min(axis=0)))
    if diag <= 0.0:
        raise DegenerateFaceError("the face has zero size")
    areas = [_signed_area(p) for p in polys]
    outer = int(np.argmax(np.abs(areas)))
    if abs(areas[outer]) <= (1e-9 * diag) ** 2 * 1e3:
        raise DegenerateFaceError("the face has (near) zero area")
    oriented: list[list[EdgePiece]] = []
    for i, lp in enumerate(loops):
        want_ccw = i == outer
        if abs(areas[i]) <= 1e-12 * diag**2:
            raise DegenerateFaceError(f"boundary loop {i} encloses no area")
        oriented.append(lp if (areas[i] > 0) == want_ccw else _reverse(lp))
    # keep the outer loop first: loop ids are stable and meaningful
    order = [outer] + [i for i in range(len(oriented)) if i != outer]
    oriented = [oriented[i] for i in order]

    if tol is not None:
        flat = max(angle_tol, 2.0 * tol / diag)
        oriented = [_split_seam_corner(lp, flat) for lp in oriented]
    angle_scale = 0.05 * diag
    elements: list[Element] = []
    corners: list[Corner] = []
    loop_lengths: list[float] = []
    for li, lp in enumerate(oriented):
        s = 0.0
        for j, piece in enumerate(lp):
            length = _piece_length(piece)
            if length <= 1e-12 * diag:
                raise DegenerateFaceError(f"edge {piece.edge_index} has zero length")
            elements.append(Element(len(elements), li, s, length, piece=piece))
            s += length
            nxt = lp[(j + 1) % len(lp)]
            end = piece.curve.point([piece.t1])[0]
            start = nxt.curve.point([nxt.t0])[0]
            if np.linalg.norm(end - start) > gap_tol:
                raise OpenWireError(
                    f"boundary loop {li} is open: gap of {np.linalg.norm(end - start):.3g} "
                    f"after edge {piece.edge_index}"
                )
            ta, tb = _tangent(piece, True), _tangent(nxt, False)
            turn = _turn(ta, tb)
            vtx = 0.5 * (end + start)
            if abs(turn) <= angle_tol:
                continue
            if abs(abs(turn) - np.pi) < 1e-9:
                cusp = _cusp_turn(piece, nxt, diag)
                if cusp is None:
                    raise DegenerateFaceError(f"cusp (zero angle) at {vtx} in loop {li}")
                turn = cusp
            corners.append(Corner(li, s, vtx, turn))
            if turn < 0:  # reflex: the normal sweeps clockwise from na to nb
                na = np.array([-ta[1], ta[0]])
                th0 = float(np.arctan2(na[1], na[0]))
                length_v = -turn * angle_scale
                elements.append(
                    Element(
                        len(elements), li, s, length_v, vertex=vtx, theta0=th0, theta1=th0 + turn
                    )
                )
                s += length_v
        loop_lengths.append(s)
    return Boundary(tuple(elements), tuple(loop_lengths), tuple(corners), diag, angle_scale)
