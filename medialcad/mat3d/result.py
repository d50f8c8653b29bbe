"""The 3D medial axis transform of a solid: named entities with their radius function."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import BSpline

__all__ = ["Junction", "MedialAxis3D", "Seam", "Sheet"]

FloatArray = NDArray[np.float64]

RADIUS_FORMAT = "medialcad-radius/1"


def _bspline(knots: FloatArray, coeffs: FloatArray, degree: int, u: ArrayLike) -> FloatArray:
    return np.asarray(BSpline(knots, coeffs, degree, extrapolate=True)(np.asarray(u, dtype=float)))


@dataclass(frozen=True)
class Sheet:
    """A medial sheet (a face, 2 touch points).

    The radius is ``(1 - v) R0(u) + v R1(u)`` with ``R0``/``R1`` B-splines on ``knots``
    (the face's own ``(u, v)`` parameters); planar mid sheets have a constant radius.
    """

    name: str
    face: Any
    role: str  # vertical, cap, mid, revolved
    knots: FloatArray
    degree: int
    radius0: FloatArray
    radius1: FloatArray
    v_knots: FloatArray | None = None  # tensor sheets: radius poles (nu, nv) on (knots, v_knots)
    v_degree: int = 1
    radius_grid: FloatArray | None = None
    slope: float = 0.0  # mid sheets: radius = radius0[0] + slope * u (u along the plane's x)

    def radius(self, u: ArrayLike, v: ArrayLike) -> FloatArray:
        """Radius at face parameters ``(u, v)``."""
        if self.role == "mid":
            uu = np.asarray(u, dtype=float)
            return np.asarray(float(self.radius0[0]) + self.slope * uu + 0.0 * np.asarray(v))
        if self.radius_grid is not None and self.v_knots is not None:
            shape = np.broadcast(np.asarray(u, dtype=float), np.asarray(v, dtype=float)).shape
            uu = np.broadcast_to(np.asarray(u, dtype=float), shape).ravel()
            vv = np.broadcast_to(np.asarray(v, dtype=float), shape).ravel()
            cu = _bspline(self.knots, self.radius_grid, self.degree, uu)  # (n, nv)
            # the v-basis at every vv: evaluate the identity coefficients once
            nv = self.radius_grid.shape[1]
            basis = _bspline(self.v_knots, np.eye(nv), self.v_degree, vv)  # (n, nv)
            return np.asarray(np.einsum("ij,ij->i", cu, basis).reshape(shape))
        vv = np.asarray(v, dtype=float)
        r0 = _bspline(self.knots, self.radius0, self.degree, u)
        r1 = _bspline(self.knots, self.radius1, self.degree, u)
        return np.asarray((1.0 - vv) * r0 + vv * r1)

    def to_json(self) -> dict[str, Any]:
        if self.role == "mid":
            if self.slope:
                return {
                    "role": self.role,
                    "type": "linear",
                    "radius": float(self.radius0[0]),
                    "slope_u": self.slope,
                }
            return {"role": self.role, "type": "constant", "radius": float(self.radius0[0])}
        if self.radius_grid is not None and self.v_knots is not None:
            return {
                "role": self.role,
                "type": "tensor",
                "u_knots": self.knots.tolist(),
                "u_degree": self.degree,
                "v_knots": self.v_knots.tolist(),
                "v_degree": self.v_degree,
                "poles": self.radius_grid.tolist(),
            }
        return {
            "role": self.role,
            "type": "ruled",
            "u_knots": self.knots.tolist(),
            "degree": self.degree,
            "radius_v0": self.radius0.tolist(),
            "radius_v1": self.radius1.tolist(),
        }


@dataclass(frozen=True)
class Seam:
    """A curve of the complex: a seam (3 touch points), a skeletal edge or a rim.

    Its radius is a B-spline in the edge's parameter (``[0, 1]``).
    """

    name: str
    edge: Any
    role: str  # seam, skeletal, rim
    knots: FloatArray
    degree: int
    radius_poles: FloatArray

    def radius(self, t: ArrayLike) -> FloatArray:
        return _bspline(self.knots, self.radius_poles, self.degree, t)

    def to_json(self) -> dict[str, Any]:
        return {
            "type": "bspline",
            "knots": self.knots.tolist(),
            "degree": self.degree,
            "poles": self.radius_poles.tolist(),
            "points": _edge_points(self.edge),
        }


def _edge_points(edge: Any) -> list[list[float]]:
    """Start, middle and end point of an edge (to find it again in a BREP/STEP file)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    c = BRepAdaptor_Curve(edge)
    t0, t1 = c.FirstParameter(), c.LastParameter()
    out = []
    for t in (t0, 0.5 * (t0 + t1), t1):
        p = c.Value(t)
        out.append([p.X(), p.Y(), p.Z()])
    return out


@dataclass(frozen=True)
class Junction:
    """A junction point (4 or more touch points)."""

    name: str
    vertex: Any
    point: FloatArray
    radius: float


@dataclass(frozen=True)
class MedialAxis3D:
    """The medial axis transform of an extrusion or a revolution.

    Attributes:
        kind: ``"extrusion"`` or ``"revolution"``.
        recognition: the :class:`~medialcad.recognition.Extrusion` or
            :class:`~medialcad.recognition.Revolution` it was computed from.
        mat2d: the 2D MAT of the profile.
        sheets, seams, junctions, skeletal_edges, rims: the named entities.
        compound: the sewn complex (``TopoDS_Compound``: faces sharing their edges, plus
            isolated edges/vertices).
        tol: geometric tolerance.
        timings: seconds per stage.
    """

    kind: str
    recognition: Any
    mat2d: Any
    tol: float
    sheets: tuple[Sheet, ...]
    seams: tuple[Seam, ...]
    junctions: tuple[Junction, ...]
    skeletal_edges: tuple[Seam, ...]
    rims: tuple[Seam, ...]
    compound: Any
    timings: dict[str, float] = field(default_factory=dict)

    def to_compound(self) -> Any:
        """The complex as one ``TopoDS_Compound``."""
        return self.compound

    @property
    def input_tolerance(self) -> float:
        """How far the solid's own faces may lie from the recognised profile swept: the
        B-rep's largest recorded tolerance, or the recognition's measured deviation."""
        rec = self.recognition
        return max(float(rec.brep_tolerance), float(rec.tolerance))

    @property
    def error_bound(self) -> float:
        """Bound on the distance of the complex (and of its radius) from the exact MAT of
        the solid's faces: ``tol`` for the recognised profile plus :attr:`input_tolerance`."""
        return self.tol + self.input_tolerance

    @property
    def rmax(self) -> float:
        """Largest radius on the complex (the largest inscribed ball of the solid)."""
        vals = [0.0]
        for s in self.sheets:
            vals += [float(np.max(s.radius0)), float(np.max(s.radius1))]
            if s.radius_grid is not None:
                vals.append(float(np.max(s.radius_grid)))
        vals += [float(np.max(c.radius_poles)) for c in self._curves()]
        vals += [j.radius for j in self.junctions]
        return max(vals)

    def counts(self) -> dict[str, int]:
        g = self.mat2d
        return {
            "branches": len(g.branches),
            "branch_points": len(g.branch_points),
            "junctions": len(self.junctions),
            "seams": len(self.seams),
            "sheets": len(self.sheets),
            "skeletal_edges": len(self.skeletal_edges),
        }

    # -- radius ----------------------------------------------------------------------
    def radius_at(self, point: ArrayLike) -> float:
        """Radius of the MAT at (the point of the complex nearest to) ``point``."""
        from medialcad.occ.query import nearest_entity

        kind, index, params = nearest_entity(self.compound, self._entity_shapes(), point)
        if kind == "face":
            return float(self.sheets[index].radius(params[0], params[1]))
        if kind == "edge":
            return float(self._curves()[index].radius(params[0]))
        return float(self.junctions[index].radius)

    def thickness_at(self, point: ArrayLike) -> float:
        """Wall thickness ``2 r`` at the medial point nearest to ``point``
        (:func:`medialcad.thickness.thickness_at`)."""
        from medialcad.thickness import thickness_at

        return thickness_at(self, point)

    def thickness(self, *, min_angle: float = 120.0) -> Any:
        """Minimum and maximum wall thickness with their locations
        (:func:`medialcad.thickness.wall_thickness`)."""
        from medialcad.thickness import wall_thickness

        return wall_thickness(self, min_angle=min_angle)

    def _curves(self) -> tuple[Seam, ...]:
        return self.seams + self.skeletal_edges + self.rims

    def _entity_shapes(self) -> tuple[list[Any], list[Any], list[Any]]:
        return (
            [s.face for s in self.sheets],
            [c.edge for c in self._curves()],
            [j.vertex for j in self.junctions],
        )

    def radius_data(self) -> dict[str, Any]:
        """The radius function of every named entity (the CLI's sidecar file; README)."""
        return {
            "format": RADIUS_FORMAT,
            "kind": self.kind,
            "tol": self.tol,
            "sheets": {s.name: s.to_json() for s in self.sheets},
            "curves": {c.name: {"role": c.role, **c.to_json()} for c in self._curves()},
            "junctions": {
                j.name: {"point": j.point.tolist(), "radius": j.radius} for j in self.junctions
            },
        }

    def names(self) -> list[tuple[Any, str]]:
        """``(shape, name)`` of every named entity."""
        out: list[tuple[Any, str]] = [(s.face, s.name) for s in self.sheets]
        out += [(c.edge, c.name) for c in self._curves()]
        out += [(j.vertex, j.name) for j in self.junctions]
        return out

    # -- export ----------------------------------------------------------------------
    def write_step(self, path: str | os.PathLike[str], *, timestamp: str | None = None) -> None:
        """Write the complex to STEP with its entities named (XCAF labels)."""
        from medialcad.occ.io import write_step_named

        write_step_named(self.compound, self.names(), path, timestamp=timestamp)

    def write_brep(self, path: str | os.PathLike[str]) -> None:
        from medialcad.occ.io import write_brep

        write_brep(self.compound, path)

    def write_radius(self, path: str | os.PathLike[str]) -> None:
        """Write :meth:`radius_data` as JSON (atomically)."""
        from medialcad.occ.io import atomic_text

        atomic_text(path, json.dumps(self.radius_data(), indent=1))

    def write_png(self, path: str | os.PathLike[str], *, dpi: int = 150) -> None:
        """Picture: the solid (translucent) with the complex coloured by radius, beside
        the profile's 2D medial axis (:func:`medialcad.plot3d.render_png`); headless."""
        from medialcad.plot3d import render_png

        render_png(self, path, dpi=dpi)

    def write_html(self, path: str | os.PathLike[str]) -> None:
        """Self-contained interactive 3D viewer (:func:`medialcad.viewer.write_html`)."""
        from medialcad.viewer import write_html

        write_html(self, path)
