"""Pictures of a 3D medial axis: a PNG (matplotlib, headless) and the tessellated scene the
HTML viewer (:mod:`medialcad.viewer`) shares.

The solid and the medial complex are meshed on copies (``BRepBuilderAPI_Copy``), so the
caller's shapes never get a triangulation attached (a BREP written later stays lean).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from medialcad.mat3d.result import MedialAxis3D, Seam

__all__ = ["Mesh", "Polylines", "Scene", "render_png", "tessellate"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

CURVE_KINDS = ("seam", "skeletal", "rim", "solid_edge")
"""Polyline groups of a :class:`Scene`, in drawing order."""

PNG_MAX_TRIANGLES = 30_000
"""Triangle budget of :func:`render_png` (matplotlib sorts and draws every one)."""


@dataclass(frozen=True)
class Mesh:
    """Triangles of several faces, one vertex range per face.

    Attributes:
        points: ``(N, 3)`` vertices; triangles: ``(M, 3)`` vertex indices.
        names: the entity each face comes from; starts: ``(len(names) + 1,)`` first vertex
            of each face (and the total at the end).
        radius: ``(N,)`` radius at each vertex (``nan`` for the solid).
        tri_radius: ``(M,)`` radius at each triangle's ``(u, v)`` centroid.
    """

    points: FloatArray
    triangles: IntArray
    names: tuple[str, ...]
    starts: IntArray
    radius: FloatArray
    tri_radius: FloatArray

    @staticmethod
    def empty() -> Mesh:
        return Mesh(
            np.zeros((0, 3)),
            np.zeros((0, 3), dtype=np.int64),
            (),
            np.zeros(1, dtype=np.int64),
            np.zeros(0),
            np.zeros(0),
        )


@dataclass(frozen=True)
class Polylines:
    """Named polylines: ``points[i]`` ``(k, 3)`` with ``radius[i]`` ``(k,)``."""

    names: tuple[str, ...] = ()
    points: tuple[FloatArray, ...] = ()
    radius: tuple[FloatArray, ...] = ()

    def segments(self) -> FloatArray:
        """``(S, 2, 3)`` consecutive point pairs of every polyline."""
        segs = [np.stack([p[:-1], p[1:]], axis=1) for p in self.points if len(p) > 1]
        return np.concatenate(segs) if segs else np.zeros((0, 2, 3))


@dataclass(frozen=True)
class Scene:
    """Everything a picture of a :class:`MedialAxis3D` draws, in model space."""

    kind: str
    solid: Mesh
    sheets: Mesh
    curves: dict[str, Polylines]
    junction_names: tuple[str, ...]
    junction_points: FloatArray
    junction_radius: FloatArray
    rmax: float
    diag: float
    decimated: bool = False
    counts: dict[str, int] = field(default_factory=dict)

    def triangle_count(self) -> int:
        """Triangles of the solid and the sheets (what the picture budgets count)."""
        return len(self.solid.triangles) + len(self.sheets.triangles)


# --------------------------------------------------------------------------- meshing
def _xyz(p: Any) -> tuple[float, float, float]:
    return (p.X(), p.Y(), p.Z())


def _face_mesh(face: Any) -> tuple[FloatArray, FloatArray | None, IntArray] | None:
    """Vertices (model space), ``(u, v)`` nodes and triangles of a meshed face."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_REVERSED
    from OCP.TopLoc import TopLoc_Location

    loc = TopLoc_Location()
    tri = BRep_Tool.Triangulation_s(face, loc)
    if tri is None or tri.NbTriangles() == 0:
        return None
    n, m = tri.NbNodes(), tri.NbTriangles()
    trsf = None if loc.IsIdentity() else loc.Transformation()
    pts = np.empty((n, 3))
    for i in range(n):
        p = tri.Node(i + 1)
        pts[i] = _xyz(p if trsf is None else p.Transformed(trsf))
    uv = None
    if tri.HasUVNodes():
        uv = np.empty((n, 2))
        for i in range(n):
            q = tri.UVNode(i + 1)
            uv[i] = (q.X(), q.Y())
    tris = np.empty((m, 3), dtype=np.int64)
    for i in range(m):
        tris[i] = tri.Triangle(i + 1).Get()
    tris -= 1
    if face.Orientation() == TopAbs_REVERSED:
        tris = tris[:, ::-1].copy()
    return pts, uv, tris


def _meshed_copy(shape: Any, deflection: float, angle: float) -> Any:
    """A meshed copy of ``shape`` (the copier, to map sub-shapes)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Copy
    from OCP.BRepMesh import BRepMesh_IncrementalMesh

    copier = BRepBuilderAPI_Copy(shape, False, False)
    BRepMesh_IncrementalMesh(copier.Shape(), deflection, False, angle, False)
    return copier


def _copied_face(copier: Any, face: Any) -> Any:
    from OCP.TopoDS import TopoDS

    try:
        return TopoDS.Face_s(copier.ModifiedShape(face))
    except Exception:  # noqa: BLE001 - a face outside the copied shape
        return None


def _assemble(parts: list[tuple[str, FloatArray, IntArray, FloatArray, FloatArray]]) -> Mesh:
    if not parts:
        return Mesh.empty()
    pts, tris, rad, trad, starts = [], [], [], [], [0]
    for _, p, t, r, tr in parts:
        tris.append(t + starts[-1])
        pts.append(p)
        rad.append(r)
        trad.append(tr)
        starts.append(starts[-1] + len(p))
    return Mesh(
        np.vstack(pts),
        np.vstack(tris),
        tuple(x[0] for x in parts),
        np.asarray(starts, dtype=np.int64),
        np.concatenate(rad),
        np.concatenate(trad),
    )


def _solid_mesh(solid: Any, deflection: float, angle: float) -> Mesh:
    from medialcad.occ.shapes import faces

    copier = _meshed_copy(solid, deflection, angle)
    parts = []
    for i, f in enumerate(faces(copier.Shape())):
        got = _face_mesh(f)
        if got is not None:
            p, _, t = got
            parts.append((f"face-{i + 1}", p, t, np.full(len(p), np.nan), np.full(len(t), np.nan)))
    return _assemble(parts)


def _refine(
    pts: FloatArray, uv: FloatArray, tris: IntArray, max_len: float, cap: int
) -> tuple[FloatArray, FloatArray, IntArray]:
    """Bisect the longest edge of triangles longer than ``max_len`` (longest first) while
    at most ``cap`` triangles result: a sliver across a radius gradient would otherwise
    show as one flat patch. New vertices get the mean of the ends' ``pts`` and ``uv``
    (the caller moves them onto the surface)."""
    while len(tris) < cap:
        e = pts[tris[:, [1, 2, 0]]] - pts[tris]
        lens = np.sqrt((e**2).sum(axis=2))
        longest = lens.max(axis=1)
        split = np.flatnonzero(longest > max_len)
        if len(split) == 0:
            break
        split = split[np.argsort(-longest[split], kind="stable")][: cap - len(tris)]
        # rotate each split triangle so that its longest edge is (0, 1)
        k = lens[split].argmax(axis=1)
        rows = np.arange(3)[None, :] + k[:, None]
        t = np.take_along_axis(tris[split], rows % 3, axis=1)
        mid = len(pts) + np.arange(len(split))
        pts = np.vstack([pts, 0.5 * (pts[t[:, 0]] + pts[t[:, 1]])])
        uv = np.vstack([uv, 0.5 * (uv[t[:, 0]] + uv[t[:, 1]])])
        new = np.concatenate(
            [np.stack([t[:, 0], mid, t[:, 2]], axis=1), np.stack([mid, t[:, 1], t[:, 2]], axis=1)]
        )
        tris = np.vstack([np.delete(tris, split, axis=0), new])
    return pts, uv, tris


@dataclass(frozen=True)
class _RawSheets:
    """Meshed sheets before refinement: ``uvf`` holds ``(u, v, face index)`` per vertex."""

    sheets: tuple[Any, ...]
    faces: tuple[Any, ...]
    points: FloatArray
    uvf: FloatArray
    triangles: IntArray


def _raw_sheets(result: MedialAxis3D, deflection: float, angle: float) -> _RawSheets:
    from medialcad.occ.shapes import compound

    copier = _meshed_copy(compound([s.face for s in result.sheets]), deflection, angle)
    kept: list[Any] = []
    kept_faces: list[Any] = []
    pts: list[FloatArray] = []
    uvf: list[FloatArray] = []
    tris: list[IntArray] = []
    n = 0
    for sheet in result.sheets:
        face = _copied_face(copier, sheet.face)
        got = None if face is None else _face_mesh(face)
        if got is None:
            continue
        p, uv, t = got
        if uv is None:  # no parameters: no radius
            uv = np.full((len(p), 2), np.nan)
        uvf.append(np.column_stack([uv, np.full(len(p), float(len(kept)))]))
        kept.append(sheet)
        kept_faces.append(face)
        pts.append(p)
        tris.append(t + n)
        n += len(p)
    if not kept:
        return _RawSheets((), (), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3), np.int64))
    return _RawSheets(
        tuple(kept), tuple(kept_faces), np.vstack(pts), np.vstack(uvf), np.vstack(tris)
    )


def _finish_sheets(raw: _RawSheets, max_len: float, cap: int) -> Mesh:
    """Refine (up to ``cap`` triangles in all), group by sheet, evaluate the radius."""
    if not raw.sheets:
        return Mesh.empty()
    from OCP.BRepAdaptor import BRepAdaptor_Surface

    pts, uvf, tris = _refine(raw.points, raw.uvf, raw.triangles, max_len, cap)
    fid = uvf[:, 2].round().astype(np.int64)
    # new vertices: on the surface at their (u, v), which need not be the chord's midpoint
    new = np.arange(len(raw.points), len(pts))
    new = new[np.isfinite(uvf[new, 0])]
    surfaces: dict[int, Any] = {}
    for i in new:
        k = int(fid[i])
        if k not in surfaces:
            surfaces[k] = BRepAdaptor_Surface(raw.faces[k])
        pts[i] = _xyz(surfaces[k].Value(float(uvf[i, 0]), float(uvf[i, 1])))
    order = np.argsort(fid, kind="stable")
    inv = np.empty_like(order)
    inv[order] = np.arange(len(order))
    pts, uvf, fid, tris = pts[order], uvf[order], fid[order], inv[tris]
    tfid = fid[tris[:, 0]]
    torder = np.argsort(tfid, kind="stable")
    tris, tfid = tris[torder], tfid[torder]
    nf = len(raw.sheets)
    starts = np.concatenate([[0], np.cumsum(np.bincount(fid, minlength=nf))])
    tstarts = np.concatenate([[0], np.cumsum(np.bincount(tfid, minlength=nf))])
    centroid = uvf[tris].mean(axis=1)
    radius = np.full(len(pts), np.nan)
    tri_radius = np.full(len(tris), np.nan)
    for k, sheet in enumerate(raw.sheets):
        a, b = starts[k], starts[k + 1]
        ta, tb = tstarts[k], tstarts[k + 1]
        if b == a or np.isnan(uvf[a, 0]):
            continue
        uv = np.vstack([uvf[a:b, :2], centroid[ta:tb, :2]])
        r = np.asarray(sheet.radius(uv[:, 0], uv[:, 1]), dtype=float)
        radius[a:b], tri_radius[ta:tb] = r[: b - a], r[b - a :]
    return Mesh(
        pts, tris, tuple(sh.name for sh in raw.sheets), starts.astype(np.int64), radius, tri_radius
    )


def _edge_polyline(edge: Any, angle: float, deflection: float) -> tuple[FloatArray, FloatArray]:
    """Points and parameters of an edge, refined by curvature (lines: two points)."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.GCPnts import GCPnts_TangentialDeflection
    from OCP.GeomAbs import GeomAbs_Line

    if BRep_Tool.Degenerated_s(edge):
        return np.zeros((0, 3)), np.zeros(0)
    ad = BRepAdaptor_Curve(edge)
    t0, t1 = ad.FirstParameter(), ad.LastParameter()
    if ad.GetType() == GeomAbs_Line:
        ts = np.array([t0, t1])
    else:
        td = GCPnts_TangentialDeflection(ad, angle, deflection, 3)
        ts = np.array([td.Parameter(i) for i in range(1, td.NbPoints() + 1)])
        if len(ts) < 2:
            ts = np.linspace(t0, t1, 8)
    pts = np.array([_xyz(ad.Value(float(t))) for t in ts])
    return pts, ts


def _curves(items: tuple[Seam, ...], angle: float, deflection: float) -> Polylines:
    names, pts, rad = [], [], []
    for c in items:
        p, t = _edge_polyline(c.edge, angle, deflection)
        if len(p) < 2:
            continue
        names.append(c.name)
        pts.append(p)
        rad.append(np.asarray(c.radius(t), dtype=float))
    return Polylines(tuple(names), tuple(pts), tuple(rad))


def _solid_edges(solid: Any, angle: float, deflection: float) -> Polylines:
    from medialcad.occ.shapes import edges

    names, pts, rad = [], [], []
    for i, e in enumerate(edges(solid)):
        p, _ = _edge_polyline(e, angle, deflection)
        if len(p) >= 2:
            names.append(f"edge-{i + 1}")
            pts.append(p)
            rad.append(np.full(len(p), np.nan))
    return Polylines(tuple(names), tuple(pts), tuple(rad))


def _bbox_diag(shape: Any) -> float:
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box, False)
    if box.IsVoid():
        return 1.0
    x0, y0, z0, x1, y1, z1 = box.Get()
    return float(np.linalg.norm([x1 - x0, y1 - y0, z1 - z0])) or 1.0


def _subsample(mesh: Mesh, keep: int) -> Mesh:
    """Every k-th triangle (a last resort: picture budgets)."""
    m = len(mesh.triangles)
    if m <= keep:
        return mesh
    idx = np.linspace(0, m - 1, keep).round().astype(np.int64)
    return Mesh(
        mesh.points, mesh.triangles[idx], mesh.names, mesh.starts, mesh.radius, mesh.tri_radius[idx]
    )


def tessellate(result: MedialAxis3D, *, solid: Any = None, max_triangles: int = 200_000) -> Scene:
    """Mesh the solid and the sheets, discretise the curves.

    Args:
        result: the medial axis.
        solid: the solid to draw (default: the recognised one, ``result.recognition.solid``);
            a ``TopoDS_Shape`` or a cadquery/build123d object.
        max_triangles: budget for solid + sheets: the mesh is redone coarser (up to twice)
            and, if still too large, every k-th triangle is kept (``Scene.decimated``).
    """
    from medialcad.occ.shapes import as_topods

    shape = as_topods(solid) if solid is not None else getattr(result.recognition, "solid", None)
    diag = _bbox_diag(shape) if shape is not None else _bbox_diag(result.compound)
    deflection, angle = 1e-2 * diag, 0.3
    decimated = False
    for attempt in range(3):
        solid_mesh = Mesh.empty() if shape is None else _solid_mesh(shape, deflection, angle)
        raw = _raw_sheets(result, deflection, angle)
        total = len(solid_mesh.triangles) + len(raw.triangles)
        if total <= max_triangles or attempt == 2:
            break
        decimated = True
        deflection *= 4.0 * total / max_triangles
        angle = min(2.0 * angle, 1.0)
    # what is left of the budget goes to splitting long sheet triangles
    cap = max(max_triangles - len(solid_mesh.triangles), len(raw.triangles))
    sheets = _finish_sheets(raw, diag / 40.0, cap)
    total = len(solid_mesh.triangles) + len(sheets.triangles)
    if total > max_triangles:
        share = max_triangles / total
        solid_mesh = _subsample(solid_mesh, int(share * len(solid_mesh.triangles)))
        sheets = _subsample(sheets, int(share * len(sheets.triangles)))
    curve_angle, curve_defl = 0.15, 1e-3 * diag
    curves = {
        "seam": _curves(result.seams, curve_angle, curve_defl),
        "skeletal": _curves(result.skeletal_edges, curve_angle, curve_defl),
        "rim": _curves(result.rims, curve_angle, curve_defl),
        "solid_edge": Polylines()
        if shape is None
        else _solid_edges(shape, curve_angle, curve_defl),
    }
    js = result.junctions
    return Scene(
        kind=result.kind,
        solid=solid_mesh,
        sheets=sheets,
        curves=curves,
        junction_names=tuple(j.name for j in js),
        junction_points=np.array([j.point for j in js], dtype=float).reshape(-1, 3),
        junction_radius=np.array([j.radius for j in js], dtype=float),
        rmax=float(result.rmax),
        diag=diag,
        decimated=decimated,
        counts=dict(result.counts()),
    )


# --------------------------------------------------------------------------- PNG
def draw_profile(ax: Any, mat: Any, *, norm: Any = None, disks: int = 8) -> Any:
    """Draw a 2D medial axis on ``ax`` (the face's own frame): the profile in black, the
    branches coloured by radius, the nodes and the ``disks`` largest maximal disks.
    Returns the branches' ``LineCollection`` (or ``None``)."""
    from matplotlib.collections import LineCollection
    from matplotlib.colors import Normalize
    from matplotlib.patches import Circle

    for xy in mat.outline(120):
        ax.plot(xy[:, 0], xy[:, 1], color="black", lw=1.0)
    segs: list[FloatArray] = []
    vals: list[FloatArray] = []
    for b in mat.branches:
        lo, hi = b.spline.domain
        v = b.spline(np.linspace(lo, hi, 120))
        segs.append(np.stack([v[:-1, :2], v[1:, :2]], axis=1))
        vals.append(0.5 * (v[:-1, 2] + v[1:, 2]))
    lc = None
    if segs:
        lc = LineCollection(list(np.concatenate(segs)), cmap="viridis", linewidths=2.0)
        lc.set_array(np.concatenate(vals))
        lc.set_norm(norm if norm is not None else Normalize(0.0, max(mat.rmax, 1e-300)))
        ax.add_collection(lc)
    markers = {"branch_point": "o", "convex_vertex": "s", "curvature_centre": "^"}
    for n in mat.nodes:
        ax.plot(*n.point_2d, markers.get(n.kind.value, "o"), color="crimson", ms=3.5)
    for n in sorted(mat.nodes, key=lambda n: -n.radius)[:disks]:
        if n.radius > 0:
            ax.add_patch(
                Circle(tuple(n.point_2d), n.radius, fill=False, color="tab:orange", lw=0.6)
            )
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_title(
        f"profile: {len(mat.branches)} branches, {len(mat.branch_points)} branch points",
        fontsize=10,
    )
    return lc


def _draw_3d(ax: Any, scene: Scene, norm: Any, cmap: Any) -> None:
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # type: ignore[import-untyped]

    polys, colours = [], []
    if len(scene.sheets.triangles):
        polys.append(scene.sheets.points[scene.sheets.triangles])
        r = np.nan_to_num(scene.sheets.tri_radius, nan=0.0)
        c = cmap(norm(r))
        c[:, 3] = 0.9
        colours.append(c)
    if len(scene.solid.triangles):
        polys.append(scene.solid.points[scene.solid.triangles])
        colours.append(np.tile([0.6, 0.6, 0.62, 0.12], (len(scene.solid.triangles), 1)))
    if polys:
        pc = Poly3DCollection(
            list(np.concatenate(polys)),
            facecolors=np.concatenate(colours),
            edgecolors="none",
            linewidths=0.0,
            antialiased=False,  # no hairlines between the triangles of a sheet
        )
        ax.add_collection3d(pc)
    styles = {
        "solid_edge": {"colors": "0.55", "linewidths": 0.6},
        "rim": {"colors": "0.35", "linewidths": 0.5, "linestyles": ":"},
        "seam": {"colors": "0.1", "linewidths": 1.3},
        "skeletal": {"colors": "#7a1010", "linewidths": 1.6},
    }
    for kind in CURVE_KINDS:
        segs = scene.curves[kind].segments()
        if len(segs):
            ax.add_collection3d(Line3DCollection(list(segs), **styles[kind]))
    if len(scene.junction_points):
        p = scene.junction_points
        ax.scatter(p[:, 0], p[:, 1], p[:, 2], color="crimson", s=14, depthshade=False)
    every = [scene.solid.points, scene.sheets.points, scene.junction_points]
    every += [np.vstack(c.points) for c in scene.curves.values() if c.points]
    allp = np.vstack([p for p in every if len(p)]) if any(len(p) for p in every) else None
    if allp is not None:
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        pad = 0.02 * max(float(np.max(hi - lo)), 1e-12)
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_zlim(lo[2] - pad, hi[2] + pad)
    ax.set_aspect("equal")
    from matplotlib.ticker import MaxNLocator

    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(nbins=5))
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.view_init(elev=24, azim=-58)


def render_png(
    result: MedialAxis3D,
    path: str | os.PathLike[str],
    *,
    solid: Any = None,
    dpi: int = 150,
    scene: Scene | None = None,
) -> None:
    """Draw a 3D medial axis to a PNG, atomically.

    Left: the solid (translucent), the sheets coloured by radius, seams and skeletal edges
    (dark lines), rims (dotted) and junctions (dots); right: the profile with its 2D medial
    axis, branch points and the largest maximal disks.

    Args:
        result: a :class:`~medialcad.mat3d.result.MedialAxis3D`.
        path: the PNG to write (a failed call leaves nothing behind).
        solid: the solid to draw (default ``result.recognition.solid``).
        dpi: resolution.
        scene: a ready :func:`tessellate` (default: computed with a budget of
            :data:`PNG_MAX_TRIANGLES`).
    """
    from matplotlib import colormaps
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure

    from medialcad.occ.io import _atomic_target

    if scene is None:
        scene = tessellate(result, solid=solid, max_triangles=PNG_MAX_TRIANGLES)
    cmap = colormaps["viridis"]
    norm = Normalize(0.0, max(scene.rmax, 1e-300))
    fig = Figure(figsize=(14, 6.5))
    FigureCanvasAgg(fig)
    ax3 = fig.add_subplot(1, 2, 1, projection="3d", computed_zorder=False)
    _draw_3d(ax3, scene, norm, cmap)
    c = scene.counts
    ax3.set_title(
        f"{scene.kind}: {c.get('sheets', 0)} sheets, {c.get('seams', 0)} seams, "
        f"{c.get('skeletal_edges', 0)} skeletal edges, {c.get('junctions', 0)} junctions"
        + (" (mesh decimated)" if scene.decimated else ""),
        fontsize=10,
    )
    fig.colorbar(
        ScalarMappable(norm=norm, cmap=cmap),
        ax=ax3,
        orientation="horizontal",
        shrink=0.6,
        pad=0.06,
        label="radius",
    )
    ax2 = fig.add_subplot(1, 2, 2)
    draw_profile(ax2, result.mat2d, norm=norm)
    with _atomic_target(Path(os.fspath(path))) as tmp:
        fig.savefig(tmp, dpi=dpi, format="png", bbox_inches="tight")
