"""Face geometry helpers shared by the bench methods and the fallback oracle.

Everything here is plain OCP + numpy + shapely (no ``medialcad`` import), so the
baselines and the fallback oracle stay independent of the engine under test.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from OCP.Bnd import Bnd_Box
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepTools import BRepTools, BRepTools_WireExplorer
from OCP.GCPnts import GCPnts_QuasiUniformDeflection, GCPnts_UniformAbscissa
from OCP.GeomAbs import GeomAbs_Plane
from OCP.gp import gp_Pnt, gp_Vec
from OCP.TopAbs import TopAbs_REVERSED, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Face
from shapely.geometry import Polygon

__all__ = [
    "PlaneFrame",
    "bbox_diag",
    "boundary_samples",
    "face_frame",
    "face_polygon",
    "face_wires",
]


@dataclass(frozen=True)
class PlaneFrame:
    """``X = origin + x * xdir + y * ydir`` for the face's plane."""

    origin: np.ndarray
    xdir: np.ndarray
    ydir: np.ndarray

    def to_3d(self, p2: np.ndarray) -> np.ndarray:
        p2 = np.asarray(p2, dtype=float).reshape(-1, 2)
        return self.origin + p2[:, :1] * self.xdir + p2[:, 1:2] * self.ydir

    def to_2d(self, p3: np.ndarray) -> np.ndarray:
        d = np.asarray(p3, dtype=float).reshape(-1, 3) - self.origin
        return np.stack([d @ self.xdir, d @ self.ydir], axis=1)

    def height(self, p3: np.ndarray) -> np.ndarray:
        d = np.asarray(p3, dtype=float).reshape(-1, 3) - self.origin
        return d @ np.cross(self.xdir, self.ydir)


def _xyz(p) -> np.ndarray:
    return np.array([p.X(), p.Y(), p.Z()], dtype=float)


def face_frame(face: TopoDS_Face) -> PlaneFrame:
    surf = BRepAdaptor_Surface(face, False)
    if surf.GetType() != GeomAbs_Plane:
        raise ValueError("face is not planar")
    ax = surf.Plane().Position()
    return PlaneFrame(_xyz(ax.Location()), _xyz(ax.XDirection()), _xyz(ax.YDirection()))


def bbox_diag(face: TopoDS_Face) -> float:
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(face, box, False, False)
    x0, y0, z0, x1, y1, z1 = box.Get()
    return float(np.linalg.norm([x1 - x0, y1 - y0, z1 - z0]))


def face_wires(face: TopoDS_Face) -> list:
    """The face's wires, the outer one first."""
    outer = BRepTools.OuterWire_s(face)
    wires = [outer]
    exp = TopExp_Explorer(face, TopAbs_WIRE)
    while exp.More():
        w = TopoDS.Wire_s(exp.Current())
        if not w.IsSame(outer):
            wires.append(w)
        exp.Next()
    return wires


def _ordered_edges(wire, face) -> list:
    out = []
    it = BRepTools_WireExplorer(wire, face)
    while it.More():
        out.append(it.Current())
        it.Next()
    return out


def _edge_params_deflection(edge, deflection: float) -> np.ndarray:
    c = BRepAdaptor_Curve(edge)
    d = GCPnts_QuasiUniformDeflection(c, deflection)
    if d.IsDone() and d.NbPoints() >= 2:
        return np.array([d.Parameter(i) for i in range(1, d.NbPoints() + 1)])
    return np.linspace(c.FirstParameter(), c.LastParameter(), 64)


def _edge_params_abscissa(edge, step: float, refine_ends: bool = True) -> np.ndarray:
    c = BRepAdaptor_Curve(edge)
    u0, u1 = c.FirstParameter(), c.LastParameter()
    d = GCPnts_UniformAbscissa(c, step, -1.0)
    if d.IsDone() and d.NbPoints() >= 2:
        u = np.array([d.Parameter(i) for i in range(1, d.NbPoints() + 1)])
    else:
        u = np.linspace(u0, u1, 64)
    u[0], u[-1] = u0, u1
    if refine_ends and len(u) >= 2:
        # geometric refinement towards both vertices, so discs much smaller than
        # ``step`` (near convex corners) still see the boundary
        k = 0.5 ** np.arange(1, 25)
        u = np.unique(np.concatenate([u, u[0] + (u[1] - u[0]) * k, u[-1] - (u[-1] - u[-2]) * k]))
    return u


def _wire_polyline(wire, face, frame: PlaneFrame, deflection: float) -> np.ndarray:
    chunks = []
    for edge in _ordered_edges(wire, face):
        c = BRepAdaptor_Curve(edge)
        u = _edge_params_deflection(edge, deflection)
        if edge.Orientation() == TopAbs_REVERSED:
            u = u[::-1]
        pts = np.array([_xyz(c.Value(float(t))) for t in u])
        chunks.append(frame.to_2d(pts)[:-1])
    return np.concatenate(chunks)


def face_polygon(face: TopoDS_Face, frame: PlaneFrame, deflection: float) -> Polygon:
    """The face as a shapely polygon in ``frame`` coordinates; each edge discretized with
    ``GCPnts_QuasiUniformDeflection``."""
    rings = [_wire_polyline(w, face, frame, deflection) for w in face_wires(face)]
    poly = Polygon(rings[0], rings[1:])
    if not poly.is_valid:
        poly = shapely.make_valid(poly)
        if poly.geom_type != "Polygon":
            poly = max(getattr(poly, "geoms", [poly]), key=lambda g: g.area)
    return shapely.geometry.polygon.orient(poly)


def boundary_samples(
    face: TopoDS_Face, frame: PlaneFrame, step: float, fan_step: float = 0.05
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Dense boundary samples for the fallback oracle.

    Returns ``(points (M, 2), normals (K, 2), origin (K,), wire (K,), next (M,))``: ``points`` are
    uniform-abscissa samples (spacing ``step``) of every edge, vertices included; the
    ``K`` rays ``points[origin] + t * normals`` are the unit normals at each sample plus
    a fan of directions between the two edge normals at each vertex (every MA point is
    the centre of a maximal disc tangent to one such ray). Normals are the tangents
    turned by +90 degrees in the wire's traversal direction: their side is constant
    per wire (``wire`` gives the wire index of each ray) but not yet known. ``next``
    is the index of the following sample along the same wire (closed polylines).
    """
    pts: list[np.ndarray] = []
    nrm: list[np.ndarray] = []
    origin: list[np.ndarray] = []
    wire_of: list[np.ndarray] = []
    base = 0
    rot = np.array([[0.0, -1.0], [1.0, 0.0]])
    basis = np.stack([frame.xdir, frame.ydir], axis=1)
    wire_ranges: list[tuple[int, int]] = []
    for iw, wire in enumerate(face_wires(face)):
        edges = _ordered_edges(wire, face)
        wire_start = base
        starts: list[int] = []
        tangents: list[tuple[np.ndarray, np.ndarray]] = []
        for edge in edges:
            c = BRepAdaptor_Curve(edge)
            u = _edge_params_abscissa(edge, step)
            rev = edge.Orientation() == TopAbs_REVERSED
            if rev:
                u = u[::-1]
            p3, t3 = [], []
            for t in u:
                p, v = gp_Pnt(), gp_Vec()
                c.D1(float(t), p, v)
                p3.append(_xyz(p))
                t3.append(_xyz(v) * (-1.0 if rev else 1.0))
            p2 = frame.to_2d(np.array(p3))
            d2 = np.array(t3) @ basis
            d2 /= np.maximum(np.linalg.norm(d2, axis=1, keepdims=True), 1e-300)
            tangents.append((d2[0], d2[-1]))
            k = len(p2) - 1  # the end point is the next edge's start
            starts.append(base)
            pts.append(p2[:k])
            nrm.append(d2[:k] @ rot.T)
            origin.append(base + np.arange(k))
            wire_of.append(np.full(k, iw))
            base += k
        wire_ranges.append((wire_start, base))
        for i in range(len(edges)):
            j = (i + 1) % len(edges)
            n_in = tangents[i][1] @ rot.T
            n_out = tangents[j][0] @ rot.T
            a0 = np.arctan2(n_in[1], n_in[0])
            da = np.arctan2(n_in[0] * n_out[1] - n_in[1] * n_out[0], n_in @ n_out)
            m = int(np.ceil(abs(da) / fan_step))
            if m < 2:
                continue
            ang = a0 + da * np.linspace(0, 1, m + 1)[1:-1]
            nrm.append(np.stack([np.cos(ang), np.sin(ang)], axis=1))
            origin.append(np.full(len(ang), starts[j]))
            wire_of.append(np.full(len(ang), iw))
    nxt = np.arange(1, base + 1)
    for a, b in wire_ranges:
        nxt[b - 1] = a
    return (
        np.concatenate(pts),
        np.concatenate(nrm),
        np.concatenate(origin),
        np.concatenate(wire_of),
        nxt,
    )
