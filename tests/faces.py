"""Test faces for the 2D medial axis: builders, placements and hypothesis strategies.

Every builder returns a ``TopoDS_Face`` in the xy-plane of model space (its own "local"
frame, in which the closed forms of THEORY.md Sec. 4 are written). :class:`Placement` moves
a face rigidly to any plane anywhere in space and maps points between the local frame and
model space, so the closed forms can be checked on placed faces too.

Nothing here imports medialcad.
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import cadquery as cq
import numpy as np
from hypothesis import assume
from hypothesis import strategies as st
from numpy.typing import ArrayLike, NDArray
from OCP.BinTools import BinTools
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_Transform
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepTools import BRepTools
from OCP.gp import gp_Trsf
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape

__all__ = [
    "IDENTITY",
    "TILTED_FAR",
    "Placement",
    "annulus",
    "any_profile",
    "bspline_blob",
    "circle",
    "dump_on_failure",
    "ellipse",
    "ellipse_with_hole",
    "filleted_polygon",
    "is_valid",
    "l_shape",
    "line_arc_fillet_mix",
    "nearly_symmetric_star",
    "notched_square",
    "place",
    "polygon",
    "polygon_with_holes",
    "polygon_with_holes_strategy",
    "random_bspline_blob",
    "random_placement",
    "read_exact",
    "rectangle",
    "regular_ngon",
    "rounded_rectangle",
    "slot_with_holes",
    "square",
    "star_polygon",
    "star_polygon_strategy",
]

FloatArray = NDArray[np.float64]


# --------------------------------------------------------------------------- placements


@dataclass(frozen=True)
class Placement:
    """A rigid motion ``X = R @ x + t`` from the local frame (face in z = 0) to model space."""

    rotation: FloatArray  # (3, 3), orthonormal, det +1
    translation: FloatArray  # (3,)

    def to_model(self, pts: ArrayLike) -> FloatArray:
        """Map local ``(..., 2)`` or ``(..., 3)`` points to model space."""
        p = np.asarray(pts, dtype=float)
        if p.shape[-1] == 2:
            p = np.concatenate([p, np.zeros((*p.shape[:-1], 1))], axis=-1)
        return np.asarray(p @ self.rotation.T + self.translation)

    def to_local(self, pts: ArrayLike) -> FloatArray:
        """Map model-space ``(..., 3)`` points to local ``(..., 3)`` (z = distance off-plane)."""
        p = np.asarray(pts, dtype=float)
        return np.asarray((p - self.translation) @ self.rotation)

    def trsf(self) -> gp_Trsf:
        r, t = self.rotation, self.translation
        tr = gp_Trsf()
        tr.SetValues(
            r[0, 0], r[0, 1], r[0, 2], t[0],
            r[1, 0], r[1, 1], r[1, 2], t[1],
            r[2, 0], r[2, 1], r[2, 2], t[2],
        )  # fmt: skip
        return tr


IDENTITY = Placement(np.eye(3), np.zeros(3))


def _rotation(axis: ArrayLike, angle: float) -> FloatArray:
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.asarray(np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k)


#: A fixed, generic placement: tilted plane, far from the origin.
TILTED_FAR = Placement(
    _rotation([0.3, -0.8, 0.52], 1.1) @ _rotation([0, 0, 1], 0.4),
    np.array([1234.5, -876.25, 421.0]),
)


def random_placement(seed: int, distance: float = 1000.0) -> Placement:
    """A random rigid motion (uniform rotation) translated ``distance`` away from the origin."""
    rng = np.random.default_rng(seed)
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    w, x, y, z = q
    rot = np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )
    d = rng.normal(size=3)
    return Placement(rot, distance * d / np.linalg.norm(d))


def place(face: TopoDS_Face, placement: Placement) -> TopoDS_Face:
    """A copy of ``face`` moved by ``placement``."""
    if placement is IDENTITY:
        return face
    shape = BRepBuilderAPI_Transform(face, placement.trsf(), True).Shape()
    return TopoDS.Face_s(shape)


def is_valid(face: TopoDS_Face) -> bool:
    return bool(BRepCheck_Analyzer(face).IsValid())


# --------------------------------------------------------------------------- builders


DATA = Path(__file__).resolve().parent / "data"


def read_exact(name: str) -> TopoDS_Shape:
    """A shape kept exactly (binary BREP, as :func:`dump_on_failure` writes it) under
    ``tests/data/``: the text BREP's rounding of a placement once changed an answer."""
    shape = TopoDS_Shape()
    BinTools.Read_s(shape, str(DATA / name))
    if shape.IsNull():
        raise FileNotFoundError(DATA / name)
    return shape


@contextmanager
def dump_on_failure(
    shape: object, label: str, env: str = "MEDIALCAD_FAILED_SHAPES"
) -> Iterator[None]:
    """Write ``shape`` as BREP to the folder ``$env`` (if set) when the block raises, so a
    fuzzing failure can be replayed outside hypothesis.

    With ``$MEDIALCAD_FUZZ_LOG`` set (the long fuzzing run, ``scripts/fuzz.sh``) every
    example is appended to that JSON-lines log as passed, refused (a medialcad
    ``InputError``: a clear refusal is an allowed answer) or failed, and the exception is
    swallowed, so hypothesis goes on drawing instead of stopping at the first failure."""
    log = os.environ.get("MEDIALCAD_FUZZ_LOG")
    t0 = time.perf_counter()
    try:
        yield
    except Exception as exc:
        path = None
        dump = os.environ.get(env)
        if dump:
            Path(dump).mkdir(parents=True, exist_ok=True)
            path = Path(dump) / f"{label.replace(' ', '_')}-{abs(hash(shape)) % 10**8}.brep"
            BRepTools.Write_s(shape, str(path))
            # the text BREP rounds coordinates (to ~1e-15 relative); the binary one is exact
            BinTools.Write_s(shape, str(path.with_suffix(".bbrep")))
            print(f"failing shape written to {path} (exact copy: .bbrep)")
        if not log or type(exc).__module__.startswith("hypothesis"):
            raise  # (hypothesis's own control flow, e.g. assume(), is not an outcome)
        refused = any(c.__name__ == "InputError" for c in type(exc).__mro__)
        _fuzz_record(log, label, "refused" if refused else "failed", t0, exc, path)
    else:
        if log:
            _fuzz_record(log, label, "passed", t0)


def _fuzz_record(
    log: str,
    label: str,
    outcome: str,
    t0: float,
    exc: BaseException | None = None,
    path: Path | None = None,
) -> None:
    """Append one example's outcome to the fuzzing log (one JSON object a line)."""
    test = os.environ.get("PYTEST_CURRENT_TEST", "").split(" ")[0].split("::")[-1]
    entry = {
        "test": test,
        "label": label,
        "outcome": outcome,
        "seconds": round(time.perf_counter() - t0, 3),
        "error": None
        if exc is None
        else f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"[:400],
        "shape": None if path is None else str(path.with_suffix(".bbrep")),
    }
    with open(log, "a", encoding="utf-8") as fh:
        fh.write(json.dumps(entry) + "\n")


def _face(outer: cq.Wire, inners: Sequence[cq.Wire] = ()) -> TopoDS_Face:
    return cq.Face.makeFromWires(outer, list(inners)).wrapped


def _poly_wire(pts: ArrayLike) -> cq.Wire:
    p = np.asarray(pts, dtype=float)
    return cq.Wire.makePolygon([cq.Vector(float(x), float(y), 0.0) for x, y in p], close=True)


def _circle_wire(r: float, centre: ArrayLike = (0.0, 0.0)) -> cq.Wire:
    c = np.asarray(centre, dtype=float)
    edge = cq.Edge.makeCircle(r, cq.Vector(float(c[0]), float(c[1]), 0.0))
    return cq.Wire.assembleEdges([edge])


def _signed_area(pts: FloatArray) -> float:
    x, y = pts[:, 0], pts[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def rectangle(a: float = 2.0, b: float = 1.0) -> TopoDS_Face:
    """The rectangle ``[-a, a] x [-b, b]``."""
    return polygon([(-a, -b), (a, -b), (a, b), (-a, b)])


def square(a: float = 1.0) -> TopoDS_Face:
    """The square ``[-a, a]^2``."""
    return rectangle(a, a)


def ellipse(a: float = 3.0, b: float = 1.0, seam: float | None = None) -> TopoDS_Face:
    """The ellipse with semi-axes ``a`` (along x) and ``b``, centred at the origin; with
    ``seam``, one closed edge whose ends sit at that parameter (angle from +x)."""
    if seam is None:
        edge = cq.Edge.makeEllipse(a, b, cq.Vector(0, 0, 0), cq.Vector(0, 0, 1), cq.Vector(1, 0, 0))
        return _face(cq.Wire.assembleEdges([edge]))
    from OCP.Geom import Geom_Ellipse
    from OCP.gp import gp_Ax2, gp_Dir, gp_Elips, gp_Pnt

    ax = gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0))
    curve = Geom_Ellipse(gp_Elips(ax, a, b))
    closed = cq.Edge(BRepBuilderAPI_MakeEdge(curve, seam, seam + 2 * math.pi).Edge())
    return _face(cq.Wire.assembleEdges([closed]))


def circle(r: float = 1.0) -> TopoDS_Face:
    """The disk of radius ``r`` centred at the origin."""
    return _face(_circle_wire(r))


def annulus(ri: float = 1.0, ro: float = 2.0) -> TopoDS_Face:
    """The annulus ``ri <= |x| <= ro``."""
    return _face(_circle_wire(ro), [_circle_wire(ri)])


def ellipse_with_hole(
    a: float = 3.0, b: float = 1.6, r: float = 0.5, centre: ArrayLike = (1.5, 0.2)
) -> TopoDS_Face:
    """The ellipse of :func:`ellipse` with a circular hole of radius ``r`` at ``centre``.
    Near an end of the ellipse its MAT is a loop round the hole from one branch point
    back to it, and a branch from there to the other end."""
    edge = cq.Edge.makeEllipse(a, b, cq.Vector(0, 0, 0), cq.Vector(0, 0, 1), cq.Vector(1, 0, 0))
    return _face(cq.Wire.assembleEdges([edge]), [_circle_wire(r, centre)])


def _stadium_wire(half_length: float, radius: float) -> cq.Wire:
    L, R = half_length, radius
    edges = [
        cq.Edge.makeLine(cq.Vector(-L, -R, 0), cq.Vector(L, -R, 0)),
        cq.Edge.makeThreePointArc(cq.Vector(L, -R, 0), cq.Vector(L + R, 0, 0), cq.Vector(L, R, 0)),
        cq.Edge.makeLine(cq.Vector(L, R, 0), cq.Vector(-L, R, 0)),
        cq.Edge.makeThreePointArc(
            cq.Vector(-L, R, 0), cq.Vector(-L - R, 0, 0), cq.Vector(-L, -R, 0)
        ),
    ]
    return cq.Wire.assembleEdges(edges)


def slot_with_holes(
    half_length: float = 3.0,
    radius: float = 1.0,
    holes: Sequence[tuple[float, float]] = ((-1.5, 0.25), (1.5, 0.25)),
) -> TopoDS_Face:
    """A stadium (segment ``|x| <= half_length`` dilated by ``radius``) with circular holes
    ``(centre_x, hole_radius)`` centred on the x-axis."""
    inner = [_circle_wire(rh, (cx, 0.0)) for cx, rh in holes]
    return _face(_stadium_wire(half_length, radius), inner)


def l_shape(size: float = 2.0, width: float = 1.0) -> TopoDS_Face:
    """The L ``[0,size]^2 minus (width,size]^2``; reflex vertex at ``(width, width)``."""
    s, w = size, width
    return polygon([(0, 0), (s, 0), (s, w), (w, w), (w, s), (0, s)])


def regular_ngon(n: int, r: float = 1.0) -> TopoDS_Face:
    """Regular ``n``-gon with circumradius ``r``, a vertex at angle 0."""
    t = 2 * np.pi * np.arange(n) / n
    return polygon(np.c_[r * np.cos(t), r * np.sin(t)])


def rounded_rectangle(a: float = 2.0, b: float = 1.0, rf: float = 0.4) -> TopoDS_Face:
    """The rectangle ``[-a, a] x [-b, b]`` with its 4 corners filleted with radius ``rf``."""
    return filleted_polygon([(-a, -b), (a, -b), (a, b), (-a, b)], [rf] * 4)


def notched_square(
    a: float = 1.0, notch_width: float = 0.4, notch_depth: float = 0.6
) -> TopoDS_Face:
    """The square ``[-a, a]^2`` with a rectangular notch cut into the top edge."""
    w, d = notch_width / 2, notch_depth
    return polygon([(-a, -a), (a, -a), (a, a), (w, a), (w, a - d), (-w, a - d), (-w, a), (-a, a)])


def bspline_blob(radii: ArrayLike, centre: ArrayLike = (0.0, 0.0)) -> TopoDS_Face:
    """A face bounded by one periodic B-spline interpolating ``radii[i]`` at equal angles."""
    r = np.asarray(radii, dtype=float)
    c = np.asarray(centre, dtype=float)
    t = 2 * np.pi * np.arange(len(r)) / len(r)
    pts = [
        cq.Vector(float(c[0] + ri * math.cos(ti)), float(c[1] + ri * math.sin(ti)), 0.0)
        for ri, ti in zip(r, t, strict=True)
    ]
    edge = cq.Edge.makeSpline(pts, periodic=True)
    return _face(cq.Wire.assembleEdges([edge]))


def clamped_closed_blob(kink: float) -> TopoDS_Face:
    """A blob bounded by one closed clamped cubic B-spline through 16 points of
    :func:`bspline_blob`'s test blob (not periodic, as other systems write a closed curve),
    its end tangent turned by ``kink`` rad from its start tangent: a corner of ``|kink|``
    at its seam, convex for ``kink < 0``."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.GeomAPI import GeomAPI_Interpolate
    from OCP.gp import gp_Vec
    from OCP.TColgp import TColgp_HArray1OfPnt

    blob = bspline_blob([0.6274, 0.7225, 0.7523, 0.7767, 0.9978, 0.8963, 0.8111, 0.9945])
    c = BRepAdaptor_Curve(cq.Face(blob).Edges()[0].wrapped)
    ts = np.linspace(c.FirstParameter(), c.LastParameter(), 17)[:-1]
    pts = TColgp_HArray1OfPnt(1, len(ts) + 1)
    for i, t in enumerate([*ts, ts[0]]):
        pts.SetValue(i + 1, c.Value(float(t)))
    d = c.DN(float(ts[0]), 1)
    cs, sn = math.cos(kink), math.sin(kink)
    turned = gp_Vec(cs * d.X() - sn * d.Y(), sn * d.X() + cs * d.Y(), 0.0)
    fit = GeomAPI_Interpolate(pts, False, 1e-9)
    fit.Load(d, turned, True)
    fit.Perform()
    return _face(cq.Wire.assembleEdges([cq.Edge(BRepBuilderAPI_MakeEdge(fit.Curve()).Edge())]))


def spline_pieces(n: int, bulge: float = 0.02, size: float = 50.0) -> TopoDS_Face:
    """A smooth star (``r = size (1 + 0.15 sin 7t + 0.05 sin 23t)``) written as ``n``
    B-spline edges, each through 3 of its points, the middle one moved radially by up
    to ``bulge / n`` (a fixed pseudo-random draw per ``n``): many small corners, most
    convex and nearly flat."""
    rng = np.random.default_rng(n)

    def p(a: float) -> cq.Vector:
        r = size * (1 + 0.15 * math.sin(7 * a) + 0.05 * math.sin(23 * a))
        return cq.Vector(r * math.cos(a), r * math.sin(a), 0.0)

    edges = []
    for i in range(n):
        a0, a1 = 2 * math.pi * i / n, 2 * math.pi * (i + 1) / n
        m = p(0.5 * (a0 + a1)) * (1 + bulge * (2 * rng.random() - 1) / n)
        edges.append(cq.Edge.makeSpline([p(a0), m, p(a1)]))
    return _face(cq.Wire.assembleEdges(edges))


def near_circle_pieces(n: int, amp: float, k: int, seed: int = 0) -> TopoDS_Face:
    """A nearly circular outline (``r = 0.75 (1 + amp cos(k t + p))``) written as ``n``
    B-spline edges through 3 of its points each, the joints jittered by up to a fifth of a
    piece (a fixed pseudo-random draw per ``seed``): its medial axis is a tree of
    branches crowding within ``~amp k^2`` of the centre, the spokes nearly parallel to
    them, the map ill-conditioned (``r ~ 1/k`` along every piece)."""
    rng = np.random.default_rng(seed)
    phase = 2 * math.pi * rng.random()

    def p(a: float) -> cq.Vector:
        r = 0.75 * (1 + amp * math.cos(k * a + phase))
        return cq.Vector(r * math.cos(a), r * math.sin(a), 0.0)

    t = 2 * math.pi * (np.arange(n) + rng.uniform(-0.2, 0.2, n)) / n
    tm = t + 0.5 * np.diff(np.r_[t, t[0] + 2 * math.pi])
    edges = [cq.Edge.makeSpline([p(t[i]), p(tm[i]), p(t[(i + 1) % n])]) for i in range(n)]
    return _face(cq.Wire.assembleEdges(edges))


def with_seam_at(face: TopoDS_Face, t: float, relative: bool = False) -> TopoDS_Face:
    """The face bounded by one periodic B-spline edge, with the curve's seam moved to its
    parameter ``t`` (``relative``: that fraction of the way along its range; a knot
    inserted there becomes the origin): the same point set, starting elsewhere."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer

    edge = TopoDS.Edge_s(TopExp_Explorer(face, TopAbs_EDGE).Current())
    curve = BRep_Tool.Curve_s(edge, 0.0, 0.0).Copy()
    if relative:
        t0, t1 = curve.FirstParameter(), curve.LastParameter()
        t = t0 + t * (t1 - t0)
    curve.InsertKnot(t, 1, 1e-12)
    curve.SetOrigin(min(range(1, curve.NbKnots() + 1), key=lambda i: abs(curve.Knot(i) - t)))
    return _face(cq.Wire.assembleEdges([cq.Edge(BRepBuilderAPI_MakeEdge(curve).Edge())]))


def polygon(pts: ArrayLike) -> TopoDS_Face:
    """A polygonal face (vertices in either orientation)."""
    return _face(_poly_wire(pts))


def polygon_with_holes(outer: ArrayLike, holes: Sequence[ArrayLike]) -> TopoDS_Face:
    """A polygon with polygonal holes."""
    return _face(_poly_wire(outer), [_poly_wire(h) for h in holes])


def star_polygon(n: int = 5, r_out: float = 1.0, r_in: float = 0.45) -> TopoDS_Face:
    """A star with ``n`` tips at ``r_out`` and reflex vertices at ``r_in``."""
    t = np.pi * np.arange(2 * n) / n
    r = np.where(np.arange(2 * n) % 2 == 0, r_out, r_in)
    return polygon(np.c_[r * np.cos(t), r * np.sin(t)])


def nearly_symmetric_star(skew: float) -> TopoDS_Face:
    """A 6-pointed star (tips 0.8, reflex vertices 0.35) symmetric about the x-axis but for
    one reflex vertex moved by ``skew`` along y: its 6-fold branch point splits into nearby
    ones (several within the tolerance for small ``skew``), and on the branches around them
    the two sides change element ``~skew`` apart (a fuzzed profile met 1.2e-7 and 4.9e-8)."""
    t = np.arange(12) * math.pi / 6
    r = np.where(np.arange(12) % 2 == 0, 0.8, 0.35)
    pts = np.column_stack([r * np.cos(t), r * np.sin(t)])
    pts[1, 1] += skew
    return polygon(pts)


def filleted_polygon(pts: ArrayLike, radii: Sequence[float]) -> TopoDS_Face:
    """A simple polygon whose vertex ``i`` is rounded with a tangent arc of ``radii[i]``
    (0: sharp). Convex and reflex vertices alike. Raises ValueError if fillets overlap."""
    p = np.asarray(pts, dtype=float)
    if _signed_area(p) < 0:
        p, radii = p[::-1], list(radii)[::-1]
    n = len(p)
    starts, ends, mids = [], [], []  # per vertex: tangent point on incoming edge, outgoing, arc mid
    for i in range(n):
        v, prev, nxt = p[i], p[i - 1], p[(i + 1) % n]
        r = float(radii[i])
        d_in = (v - prev) / np.linalg.norm(v - prev)
        d_out = (nxt - v) / np.linalg.norm(nxt - v)
        turn = math.atan2(
            float(d_in[0] * d_out[1] - d_in[1] * d_out[0]), float(d_in @ d_out)
        )  # >0: convex (CCW)
        if r <= 0 or abs(turn) < 1e-9:
            starts.append(v), ends.append(v), mids.append(None)
            continue
        t = r * math.tan(abs(turn) / 2)
        a, b = v - t * d_in, v + t * d_out
        nrm = np.array([-d_in[1], d_in[0]]) * math.copysign(1.0, turn)  # towards the centre
        centre = a + r * nrm
        bis = (v - centre) / np.linalg.norm(v - centre)
        starts.append(a), ends.append(b), mids.append(centre + r * bis)
    edges = []
    for i in range(n):
        j = (i + 1) % n
        if np.linalg.norm(starts[j] - ends[i]) < 1e-9 or (starts[j] - ends[i]) @ (p[j] - p[i]) <= 0:
            raise ValueError("fillets overlap")
        edges.append(_line(ends[i], starts[j]))
        if mids[j] is not None:
            edges.append(_arc(starts[j], mids[j], ends[j]))
    return _face(cq.Wire.assembleEdges(edges))


def _v(p: FloatArray) -> cq.Vector:
    return cq.Vector(float(p[0]), float(p[1]), 0.0)


def _line(a: FloatArray, b: FloatArray) -> cq.Edge:
    return cq.Edge.makeLine(_v(a), _v(b))


def _arc(a: FloatArray, m: FloatArray, b: FloatArray) -> cq.Edge:
    return cq.Edge.makeThreePointArc(_v(a), _v(m), _v(b))


# --------------------------------------------------------------------------- strategies


def _star_shaped_radii(draw: st.DrawFn, n: int, lo: float, hi: float) -> FloatArray:
    return np.array(draw(st.lists(st.floats(lo, hi), min_size=n, max_size=n)))


@st.composite
def random_bspline_blob(draw: st.DrawFn) -> TopoDS_Face:
    """A periodic B-spline blob: 5-10 radii in [0.5, 1] at equal angles."""
    n = draw(st.integers(5, 10))
    r = _star_shaped_radii(draw, n, 0.5, 1.0)
    face = bspline_blob(r)
    assume(is_valid(face))
    return face


@st.composite
def star_polygon_strategy(draw: st.DrawFn) -> TopoDS_Face:
    """A star-shaped polygon with 3-9 tips and random inner/outer radii (a reflex vertex
    between each pair of tips)."""
    n = draw(st.integers(3, 9))
    r_out = _star_shaped_radii(draw, n, 0.7, 1.0)
    r_in = _star_shaped_radii(draw, n, 0.25, 0.6)
    jitter = np.array(draw(st.lists(st.floats(-0.25, 0.25), min_size=2 * n, max_size=2 * n)))
    t = np.pi * (np.arange(2 * n) + jitter) / n
    r = np.empty(2 * n)
    r[0::2], r[1::2] = r_out, r_in
    face = polygon(np.c_[r * np.cos(t), r * np.sin(t)])
    assume(is_valid(face))
    return face


@st.composite
def polygon_with_holes_strategy(draw: st.DrawFn) -> TopoDS_Face:
    """A star-shaped outer polygon (radii in [0.8, 1]) with 1-3 disjoint small polygonal holes
    inside the disk of radius 0.49 (the outer polygon contains the disk of radius 0.56)."""
    n = draw(st.integers(4, 10))
    r = _star_shaped_radii(draw, n, 0.8, 1.0)
    t = 2 * np.pi * np.arange(n) / n
    outer = np.c_[r * np.cos(t), r * np.sin(t)]
    k = draw(st.integers(1, 3))
    holes: list[FloatArray] = []
    centres: list[FloatArray] = []
    for _ in range(k):
        c = np.array([draw(st.floats(-0.35, 0.35)), draw(st.floats(-0.35, 0.35))])
        assume(np.linalg.norm(c) <= 0.35)
        m = draw(st.integers(3, 7))
        rh = draw(st.floats(0.05, 0.14))
        phase = draw(st.floats(0, 2 * np.pi))
        th = phase + 2 * np.pi * np.arange(m) / m
        assume(all(np.linalg.norm(c - o) > 0.32 for o in centres))
        centres.append(c)
        holes.append(c + rh * np.c_[np.cos(th), np.sin(th)])
    face = polygon_with_holes(outer, holes)
    assume(is_valid(face))
    return face


@st.composite
def line_arc_fillet_mix(draw: st.DrawFn) -> TopoDS_Face:
    """A star-shaped polygon (5-9 vertices, some reflex) with random fillets (convex and
    concave) at some of its vertices: lines, arcs, G1 joints."""
    n = draw(st.integers(5, 9))
    r = _star_shaped_radii(draw, n, 0.45, 1.0)
    jitter = np.array(draw(st.lists(st.floats(-0.2, 0.2), min_size=n, max_size=n)))
    t = 2 * np.pi * (np.arange(n) + jitter) / n
    pts = np.c_[r * np.cos(t), r * np.sin(t)]
    radii = [draw(st.sampled_from([0.0, 0.0, 0.05, 0.1, 0.2])) for _ in range(n)]
    assume(any(radii))
    try:
        face = filleted_polygon(pts, radii)
    except (ValueError, Exception):  # overlapping fillets, OCC refusing the wire
        assume(False)
        raise
    assume(is_valid(face))
    return face


@st.composite
def bspline_chain(draw: st.DrawFn) -> TopoDS_Face:
    """A closed loop of 3-30 B-spline edges, each through 3 points of a smooth
    star-shaped outline (``r = 0.75 + sum a_k cos(k t + p_k)``, three harmonics), the
    middle points bulged off it by 0 to 5 %: C0 joints whose corners run from nearly
    flat (no bulge: only the pieces' own tangents differ) to sharp, convex and reflex
    (other systems often write one curve as many spline pieces)."""
    n = draw(st.integers(3, 30))
    amp = _star_shaped_radii(draw, 3, -0.1, 0.1)
    phase = _star_shaped_radii(draw, 3, 0.0, 2 * np.pi)
    size = draw(st.sampled_from([0.0, 1e-4, 1e-3, 1e-2, 0.05]))
    bulge = size * _star_shaped_radii(draw, n, -1.0, 1.0)
    jitter = np.array(draw(st.lists(st.floats(-0.2, 0.2), min_size=n, max_size=n)))

    def outline(t: FloatArray) -> FloatArray:
        k = np.arange(1, 4)
        r = 0.75 + (amp * np.cos(np.outer(t, k) + phase)).sum(axis=1)
        return np.c_[r * np.cos(t), r * np.sin(t)]

    t = 2 * np.pi * (np.arange(n) + jitter) / n
    tm = t + 0.5 * np.diff(np.r_[t, t[0] + 2 * np.pi])
    pts, mid = outline(t), outline(tm) * (1 + bulge)[:, None]
    edges = [cq.Edge.makeSpline([_v(pts[i]), _v(mid[i]), _v(pts[(i + 1) % n])]) for i in range(n)]
    try:
        face = cq.Face.makeFromWires(cq.Wire.assembleEdges(edges)).wrapped
    except Exception:  # OCC refusing the wire
        assume(False)
        raise
    assume(is_valid(face))
    return face


def any_profile() -> st.SearchStrategy[TopoDS_Face]:
    """A face from any of the four profile strategies (star polygons, polygons with
    holes, line-arc-fillet mixes, B-spline blobs)."""
    return st.one_of(
        star_polygon_strategy(),
        polygon_with_holes_strategy(),
        line_arc_fillet_mix(),
        random_bspline_blob(),
    )


def cusped_notch(fillet: float = 1.0, shift: float = 0.0) -> TopoDS_Face:
    """A 6 x 4 rectangle (``y`` in ``[0, 4]``) whose bottom edge is notched by two disks of
    radius ``fillet`` touching at ``(0, fillet)``, moved by ``shift`` along ``x``: the arcs
    meet there tangent to each other, a reflex cusp (the meridian section of a rounded
    rectangle revolved about its side)."""
    import build123d as bd

    f = fillet
    with bd.BuildSketch() as sk:
        with bd.Locations((0, 2)):
            bd.Rectangle(6, 4)
        with bd.Locations((0, f / 2)):
            bd.Rectangle(2 * f, f, mode=bd.Mode.SUBTRACT)
        with bd.Locations((f, f), (-f, f)):
            bd.Circle(f)
    return sk.sketch.faces()[0].translate((shift, 0, 0)).wrapped
