"""The 3D MAT of an extrusion ``P x [0, L]`` (THEORY.md Sec. 1), as patch rows.

Per segment of the 2D medial axis (see :mod:`medialcad.mat3d.segments`), with
``h = L/2``:

- ``r <= h`` (low): the vertical sheet ruled between the bottom seam ``(c, r)`` and the
  top seam ``(c, L - r)``; on each side a bottom cap sheet ruled between the foot
  ``(f, 0)`` and the bottom seam, and a top cap sheet between ``(f, L)`` and the top seam.
- ``r >= h`` (high, only when ``L < 2 Rmax``): on each side the caps are ruled between
  the foot and the offset point ``(f + h n, h)``; those offset seams bound the planar mid
  sheet ``z = h``.

Every row is a cubic B-spline interpolating exact samples at the segment's parameters,
so all rows of a segment share one knot vector and the ruled sheets are exact between
exact rows. The radius travels with every row (bilinear on the sheets).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import make_interp_spline

from medialcad.mat2d.boundary import Boundary
from medialcad.mat2d.graph import NodeKind
from medialcad.mat3d.segments import Segment, distinct_rows, foot_normals

__all__ = ["PatchRows", "RowData", "extrusion_rows", "interp_rows"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class RowData:
    """One row: a key (for sharing), 3D poles in model space and radius poles."""

    key: tuple
    poles: FloatArray
    radius: FloatArray


@dataclass(frozen=True)
class PatchRows:
    """A ruled sheet between two rows on the knots ``knots`` (degree ``degree``)."""

    role: str  # vertical, cap, revolved, ...
    segment: int
    knots: FloatArray
    degree: int
    bottom: RowData
    top: RowData


@dataclass(frozen=True)
class EndLine:
    """A line at a segment end that is a named entity (vertical seam, skeletal edge, rim)."""

    role: str  # seam, skeletal, rim
    p0: FloatArray
    p1: FloatArray
    radius: float


def interp_rows(w: FloatArray, *values: FloatArray) -> tuple[FloatArray, int, list[FloatArray]]:
    """Interpolate several sample arrays at the same parameters: common knots, coeffs."""
    k = int(min(3, len(w) - 1))
    out = []
    t: FloatArray | None = None
    for v in values:
        sp = make_interp_spline(w, v, k=k)
        t = np.asarray(sp.t, dtype=float)
        out.append(np.asarray(sp.c, dtype=float))
    assert t is not None
    return t, k, out


def _side_parameter(rows: FloatArray, fallback: FloatArray) -> tuple[FloatArray, IntArray]:
    """One side's rows of a high segment (its foot and offset point, functions of the
    foot alone: the side's cap sheets and its stretch of the mid sheet's boundary)
    parametrized by their own chord length, and the rows kept (where they move).

    The branch's parameter follows the centres, and the two sides need not move alike:
    where the radius is steep in one foot (a branch into a flat curvature maximum between
    two feet of a branch point: 3 tol of branch for 1e-9 of foot), or next to a
    curvature-centre end, one side's feet stand still for many rows and then jump, and
    its offset seam interpolated on the branch's parameter looped."""
    step = np.linalg.norm(np.diff(rows, axis=0), axis=1)
    total = float(step.sum())
    n = len(rows)
    if n < 2 or not total > 0:
        return fallback, np.arange(n)
    idx = distinct_rows(rows, 1e-9 * total)
    w = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(rows[idx], axis=0), axis=1))])
    return w / w[-1], idx


def extrusion_rows(
    segments: list[Segment],
    to_model: Callable[[FloatArray], FloatArray],
    length: float,
    high_level: float | None,
    boundary: Boundary | None = None,
) -> tuple[list[PatchRows], list[tuple], list[EndLine], list[tuple[FloatArray, float]]]:
    """Patches, offset-seam keys (mid sheet boundary), end lines and junctions.

    ``to_model`` maps ``(n, 3)`` canonical points (profile coordinates, height) to model
    space. ``high_level`` is ``L/2`` when there is a mid sheet, else ``None``. With the
    ``boundary``, the offset seams are ``f + h n(f)`` with the boundary's own normal at
    each foot ``f`` (exact whatever the row's centre: next to a curvature-centre end the
    rows' feet stand still while their centres move, and ``(c - f) / r`` turned the seam
    into a loop).
    """
    L = length
    patches: list[PatchRows] = []
    offsets: list[tuple] = []
    lines: list[EndLine] = []
    junctions: list[tuple[FloatArray, float]] = []
    for si, s in enumerate(segments):
        r = s.radius
        high = high_level is not None and float(np.median(r)) > high_level
        if not high:
            # without a mid sheet (Rmax within the tolerance above L/2) a disk wider than
            # L/2 still touches both caps: its centre is at z = L/2 with radius L/2 (the
            # seams ``(c, r)``, ``(c, L - r)`` would cross, carrying r where the distance
            # is ``L - r``: 1.01 tol at a fresh random L = 2 r of a branch point)
            r = np.minimum(r, 0.5 * L)
            t, k, (cc, fa, fb) = interp_rows(
                s.w, np.column_stack([s.centre, r]), s.foot_a, s.foot_b
            )
            cr = cc[:, 2]
            zero = np.zeros(len(cr))
            sb = RowData(("SB", si), to_model(cc), cr)
            st = RowData(("ST", si), to_model(np.column_stack([cc[:, :2], L - cr])), cr)
            if not s.single:
                patches.append(PatchRows("vertical", si, t, k, sb, st))
            for side, f in (("a", fa), ("b", fb))[: 1 if s.single else 2]:
                bot = RowData(("F0", si, side), to_model(np.column_stack([f, zero])), zero)
                top = RowData(
                    ("FL", si, side), to_model(np.column_stack([f, np.full(len(cr), L)])), zero
                )
                patches.append(PatchRows("cap", si, t, k, bot, sb))
                patches.append(PatchRows("cap", si, t, k, top, st))
            for end, i in ((s.start, 0), (s.end, -1)):
                c, rr = s.centre[i], float(r[i])
                p0 = to_model(np.array([[c[0], c[1], rr]]))[0]
                p1 = to_model(np.array([[c[0], c[1], L - rr]]))[0]
                if end.kind == "node":
                    if end.node_kind is NodeKind.BRANCH_POINT:
                        lines.append(EndLine("seam", p0, p1, rr))
                        junctions.append((p0, rr))
                        junctions.append((p1, rr))
                    elif end.node_kind is NodeKind.CURVATURE_CENTRE:
                        lines.append(EndLine("skeletal", p0, p1, rr))
                    else:
                        lines.append(EndLine("rim", p0, p1, 0.0))
                elif end.kind == "level":
                    junctions.append((p0, rr))
        else:
            assert high_level is not None
            h = high_level
            nrm_a = (s.centre - s.foot_a) / np.maximum(r, 1e-300)[:, None]
            nrm_b = (s.centre - s.foot_b) / np.maximum(r, 1e-300)[:, None]
            if boundary is not None:
                for nrm, el, f in ((nrm_a, s.element_a, s.foot_a), (nrm_b, s.element_b, s.foot_b)):
                    exact = foot_normals(boundary, el, f)
                    if exact is not None:
                        # (not at the end rows: a neighbouring segment shares them, with
                        # its own foot's element: a transition to a reflex vertex)
                        on = np.isfinite(exact[:, 0])
                        on[[0, -1]] = False
                        nrm[on] = exact[on]
            oa = s.foot_a + h * nrm_a
            ob = s.foot_b + h * nrm_b
            # at a level end the offset point is the centre itself
            for i, end in ((0, s.start), (-1, s.end)):
                if end.kind == "level":
                    oa[i] = ob[i] = s.centre[i]
            for side, f_rows, o_rows in (("a", s.foot_a, oa), ("b", s.foot_b, ob))[
                : 1 if s.single else 2
            ]:
                w, keep = _side_parameter(np.hstack([f_rows, o_rows]), s.w)
                t, k, (f, o) = interp_rows(w, f_rows[keep], o_rows[keep])
                n = len(f)
                zero, hh = np.zeros(n), np.full(n, h)
                orow = RowData(("OFF", si, side), to_model(np.column_stack([o, hh])), hh)
                bot = RowData(("F0", si, side), to_model(np.column_stack([f, zero])), zero)
                top = RowData(("FL", si, side), to_model(np.column_stack([f, np.full(n, L)])), zero)
                patches.append(PatchRows("cap", si, t, k, bot, orow))
                patches.append(PatchRows("cap", si, t, k, top, orow))
                offsets.append(orow.key)
    return patches, offsets, lines, junctions
