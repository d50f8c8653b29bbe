"""Turn patch rows into the sewn OCC complex and the named result."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from medialcad.mat3d.extrusion import EndLine, PatchRows
from medialcad.mat3d.result import Junction, Seam, Sheet

__all__ = ["build_complex"]

FloatArray = NDArray[np.float64]

_LINEAR = np.array([0.0, 0.0, 1.0, 1.0])


def build_complex(
    patches: list[PatchRows],
    offsets: list[tuple],
    lines: list[EndLine],
    junctions: list[tuple[FloatArray, float]],
    *,
    diag: float,
    mid_plane: tuple[FloatArray, FloatArray, FloatArray] | None,
    mid_radius: float = 0.0,
    seam_roles: Callable[[Any], str | None],
) -> tuple[
    tuple[Sheet, ...],
    tuple[Seam, ...],
    tuple[Seam, ...],
    tuple[Seam, ...],
    tuple[Junction, ...],
    Any,
]:
    """Build faces/edges/vertices; return sheets, seams, skeletal edges, rims, junctions
    and the compound.

    ``seam_roles(key)`` names the role of a row's curve edge (``"seam"``, ``"rim"`` or
    ``None`` for an unnamed inner curve).
    """
    from medialcad.occ.complex import ComplexBuilder, Row

    cb = ComplexBuilder(merge=1e-8 * diag, tol=max(1e-7 * diag, 1e-9))
    sheets: list[Sheet] = []
    row_radius: dict[Any, tuple[FloatArray, int, FloatArray]] = {}
    for p in patches:
        bottom = Row(p.bottom.key, p.knots, p.bottom.poles, p.degree)
        top = Row(p.top.key, p.knots, p.top.poles, p.degree)
        face = cb.ruled_face(bottom, top)
        sheets.append(
            Sheet(
                f"sheet-{len(sheets) + 1}",
                face,
                p.role,
                p.knots,
                p.degree,
                p.bottom.radius,
                p.top.radius,
            )
        )
        for r in (p.bottom, p.top):
            row_radius.setdefault(r.key, (p.knots, p.degree, r.radius))
    if mid_plane is not None and offsets:
        for face in cb.planar_faces(offsets, *mid_plane):
            sheets.append(
                Sheet(
                    f"sheet-{len(sheets) + 1}",
                    face,
                    "mid",
                    _LINEAR,
                    1,
                    np.array([mid_radius] * 2),
                    np.array([mid_radius] * 2),
                )
            )
    seams, rims = _row_curves(cb, row_radius, seam_roles)
    skeletal: list[Seam] = []
    named = _ShapeSet(s.edge for s in seams + rims)
    for ln in lines:
        v0, v1 = cb.vertex(ln.p0), cb.vertex(ln.p1)
        if v0 == v1:
            continue
        key = (min(v0, v1), max(v0, v1))
        e = cb.line_edges.get(key) or cb.line_edge(v0, v1)
        if e.edge in named:
            continue
        named.add(e.edge)
        target = {"seam": seams, "skeletal": skeletal, "rim": rims}[ln.role]
        target.append(Seam("", e.edge, ln.role, _LINEAR, 1, np.array([ln.radius, ln.radius])))
    seams, skeletal, rims = (
        _numbered(seams, "seam"),
        _numbered(skeletal, "skeletal"),
        _numbered(rims, "rim"),
    )
    juncs = _junctions(cb, junctions)
    line_edges = _ShapeSet(e.edge for e in cb.line_edges.values())
    in_faces = _face_edges(cb)
    # line edges made only for naming bound no face: they go into the compound loose
    extra = [s.edge for s in skeletal if not (s.edge in line_edges and s.edge in in_faces)]
    comp = cb.compound(extra)
    return tuple(sheets), tuple(seams), tuple(skeletal), tuple(rims), tuple(juncs), comp


def _row_curves(
    cb: Any,
    row_radius: dict[Any, tuple[FloatArray, int, FloatArray]],
    roles: Callable[[Any], str | None],
) -> tuple[list[Seam], list[Seam]]:
    """Seams and rims among the row curve edges (``roles`` names them; ``u = const``
    sides are named by the patches that own them)."""
    seams: list[Seam] = []
    rims: list[Seam] = []
    for key, e in cb.curve_edges.items():
        role = None if key[0] == "side" else roles(key)
        if role is None:
            continue
        knots, degree, rad = row_radius[key]
        (seams if role == "seam" else rims).append(Seam("", e.edge, role, knots, degree, rad))
    return seams, rims


def _numbered(items: list[Seam], prefix: str) -> list[Seam]:
    """The curves named ``prefix-1``, ``prefix-2``, ... in order."""
    return [replace(c, name=f"{prefix}-{i + 1}") for i, c in enumerate(items)]


def _junctions(cb: Any, junctions: list[tuple[FloatArray, float]]) -> list[Junction]:
    """One named junction per distinct vertex of the complex, in order."""
    out: list[Junction] = []
    seen: set[int] = set()
    for p, r in junctions:
        vi = cb.vertex(p)
        if vi not in seen:
            seen.add(vi)
            out.append(
                Junction(f"junction-{len(out) + 1}", cb.vertices[vi], cb.points[vi], float(r))
            )
    return out


class _ShapeSet:
    """Shapes up to orientation (``IsSame``), hashed: ``in`` is O(1)."""

    def __init__(self, shapes: Any = ()) -> None:
        from OCP.TopTools import TopTools_MapOfShape

        self._map = TopTools_MapOfShape()
        for sh in shapes:
            self._map.Add(sh)

    def add(self, shape: Any) -> None:
        self._map.Add(shape)

    def __contains__(self, shape: Any) -> bool:
        return bool(self._map.Contains(shape))


def _face_edges(cb: Any) -> _ShapeSet:
    """Every edge that bounds a face of the complex."""
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer

    out = _ShapeSet()
    for f in cb.faces:
        ex = TopExp_Explorer(f, TopAbs_EDGE)
        while ex.More():
            out.add(ex.Current())
            ex.Next()
    return out


def build_grid_complex(
    grids: list[Any],
    offsets: list[tuple],
    junctions: list[tuple[FloatArray, float]],
    axis_lines: list[tuple[FloatArray, FloatArray, FloatArray]],
    *,
    diag: float,
    mid_plane: tuple[FloatArray, FloatArray, FloatArray] | None,
    seam_roles: Callable[[Any], str | None],
    mid_slope: float = 0.0,
    mid_rims: Sequence[tuple[FloatArray, FloatArray]] = (),
) -> tuple:
    """Like :func:`build_complex` for tensor patches (revolutions).

    ``mid_rims`` are straight edges (end points) that bound the mid sheet besides the
    offset rows (a pie slice's axis), keyed ``("AXR", k)``: ``seam_roles`` names them."""
    from scipy.interpolate import make_interp_spline

    from medialcad.mat3d.arcs import interp_rational
    from medialcad.mat3d.revolution import interp_grid
    from medialcad.occ.complex import ComplexBuilder, Row

    cb = ComplexBuilder(merge=1e-8 * diag, tol=max(1e-7 * diag, 1e-9))
    sheets: list[Sheet] = []
    row_radius: dict[Any, tuple[FloatArray, int, FloatArray]] = {}
    named_sides: list[tuple[Any, str, float]] = []
    for g in grids:
        if g.weights is None:
            tu, tv, ku, kv, poles = interp_grid(g.w, g.v, g.points)
            _, _, _, _, rpoles = interp_grid(g.w, g.v, g.radius)
            weights = None
        else:  # rows of exact arcs; the radius is constant along them
            tu, ku, poles, weights = interp_rational(g.w, g.points, g.weights)
            tv, kv = g.v, 2
            rpoles = np.asarray(make_interp_spline(g.w, g.radius, k=ku, axis=0).c)
        face = cb.grid_face(poles, tu, tv, ku, kv, g.bottom_key, g.top_key, weights)
        sheets.append(
            Sheet(
                f"sheet-{len(sheets) + 1}",
                face,
                g.role,
                tu,
                ku,
                rpoles[:, 0],
                rpoles[:, -1],
                tv,
                kv,
                rpoles,
            )
        )
        row_radius.setdefault(g.bottom_key, (tu, ku, rpoles[:, 0]))
        row_radius.setdefault(g.top_key, (tu, ku, rpoles[:, -1]))
        for (role, rad), col in ((g.left, poles[0]), (g.right, poles[-1])):
            if role is None:
                continue
            e = cb.curve_edges.get(cb.side_key(col))
            if e is not None:
                named_sides.append((e.edge, role, rad))
    offsets = list(offsets)
    for k, (p0, p1) in enumerate(mid_rims):
        key = ("AXR", k)
        cb.curve_edge(Row(key, _LINEAR, np.vstack([p0, p1]), 1))
        row_radius[key] = (_LINEAR, 1, np.zeros(2))
        offsets.append(key)
    if mid_plane is not None and offsets:
        # the mid sheet of a small-angle revolution lies in the half-plane at Theta/2: its
        # radius is x sin(Theta/2), x the distance from the axis = the plane's u
        for face in cb.planar_faces(offsets, *mid_plane):
            sheets.append(
                Sheet(
                    f"sheet-{len(sheets) + 1}",
                    face,
                    "mid",
                    _LINEAR,
                    1,
                    np.zeros(2),
                    np.zeros(2),
                    slope=mid_slope,
                )
            )
    seams, rims = _row_curves(cb, row_radius, seam_roles)
    skeletal: list[Seam] = []
    seen = _ShapeSet()
    for edge, role, rad in named_sides:
        if edge in seen:
            continue
        seen.add(edge)
        target = {"seam": seams, "skeletal": skeletal, "rim": rims}[role]
        target.append(Seam("", edge, role, _LINEAR, 1, np.array([rad, rad])))
    extra: list[Any] = []
    for pts, rad, w in axis_lines:
        from scipy.interpolate import make_interp_spline

        k = int(min(3, len(w) - 1))
        sp = make_interp_spline(w, pts, k=k)
        sr = make_interp_spline(w, rad, k=k)
        row = Row(("AXIS", len(extra)), np.asarray(sp.t), np.asarray(sp.c), k)
        e = cb.curve_edge(row)
        extra.append(e.edge)
        skeletal.append(Seam("", e.edge, "skeletal", np.asarray(sr.t), k, np.asarray(sr.c)))
    seams, skeletal, rims = (
        _numbered(seams, "seam"),
        _numbered(skeletal, "skeletal"),
        _numbered(rims, "rim"),
    )
    juncs = _junctions(cb, junctions)
    in_faces = _face_edges(cb)
    loose = [e for e in extra if e not in in_faces]
    if not cb.faces and not loose:
        loose = [j.vertex for j in juncs]
    comp = cb.compound(loose)
    return tuple(sheets), tuple(seams), tuple(skeletal), tuple(rims), tuple(juncs), comp
