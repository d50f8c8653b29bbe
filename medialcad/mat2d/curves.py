"""Exact planar curves as numpy data, evaluated vectorized with two derivatives.

These mirror OCC's ``Geom2d`` curves one to one (same parameterization), so a
parameter computed here is the OCC parameter of the edge's curve in the face frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import BSpline

__all__ = [
    "AffineCurve",
    "CircleCurve",
    "Curve",
    "EllipseCurve",
    "LineCurve",
    "NurbsCurve",
    "OffsetCurve",
    "linear_image",
]

FloatArray = NDArray[np.float64]
Derivs = tuple[FloatArray, FloatArray, FloatArray]
Derivs3 = tuple[FloatArray, FloatArray, FloatArray, FloatArray]


class Curve:
    """Base: ``derivs(t)`` returns ``(point, first, second)`` each ``(n, 2)``."""

    def derivs(self, t: ArrayLike) -> Derivs:  # pragma: no cover - abstract
        raise NotImplementedError

    def derivs3(self, t: ArrayLike) -> Derivs3:
        """``(point, first, second, third)``: what an offset of the curve needs."""
        raise NotImplementedError(f"{type(self).__name__} has no third derivative")

    def point(self, t: ArrayLike) -> FloatArray:
        return self.derivs(t)[0]

    @property
    def constant_curvature(self) -> float | None:
        """Unsigned curvature if constant along the curve (lines 0, circles 1/R), else None."""
        return None


@dataclass(frozen=True)
class LineCurve(Curve):
    origin: FloatArray
    direction: FloatArray  # unit

    def derivs(self, t: ArrayLike) -> Derivs:
        tt = np.atleast_1d(np.asarray(t, dtype=float))[:, None]
        p = self.origin + tt * self.direction
        d1 = np.broadcast_to(self.direction, p.shape).copy()
        return p, d1, np.zeros_like(p)

    def derivs3(self, t: ArrayLike) -> Derivs3:
        p, d1, d2 = self.derivs(t)
        return p, d1, d2, d2.copy()

    def point(self, t: ArrayLike) -> FloatArray:
        tt = np.atleast_1d(np.asarray(t, dtype=float))[:, None]
        return np.asarray(self.origin + tt * self.direction)

    @property
    def constant_curvature(self) -> float | None:
        return 0.0


@dataclass(frozen=True)
class CircleCurve(Curve):
    center: FloatArray
    radius: float
    xaxis: FloatArray  # unit
    yaxis: FloatArray  # unit; may be clockwise of xaxis (indirect frame)

    def derivs(self, t: ArrayLike) -> Derivs:
        tt = np.atleast_1d(np.asarray(t, dtype=float))[:, None]
        c, s = np.cos(tt), np.sin(tt)
        r = self.radius
        p = self.center + r * (c * self.xaxis + s * self.yaxis)
        d1 = r * (-s * self.xaxis + c * self.yaxis)
        d2 = -r * (c * self.xaxis + s * self.yaxis)
        return p, d1, d2

    def derivs3(self, t: ArrayLike) -> Derivs3:
        p, d1, d2 = self.derivs(t)
        return p, d1, d2, -d1

    @property
    def constant_curvature(self) -> float | None:
        return 1.0 / self.radius


@dataclass(frozen=True)
class EllipseCurve(Curve):
    """``center + cos t major xaxis + sin t minor yaxis`` (OCC's ``Geom2d_Ellipse``:
    perpendicular unit axes, ``yaxis`` either way round)."""

    center: FloatArray
    major: float
    minor: float
    xaxis: FloatArray
    yaxis: FloatArray

    def derivs(self, t: ArrayLike) -> Derivs:
        tt = np.atleast_1d(np.asarray(t, dtype=float))[:, None]
        c, s = np.cos(tt), np.sin(tt)
        ax, ay = self.major * self.xaxis, self.minor * self.yaxis
        p = self.center + c * ax + s * ay
        d1 = -s * ax + c * ay
        d2 = -c * ax - s * ay
        return p, d1, d2

    def derivs3(self, t: ArrayLike) -> Derivs3:
        p, d1, d2 = self.derivs(t)
        return p, d1, d2, -d1


@dataclass(frozen=True)
class NurbsCurve(Curve):
    """A clamped (possibly rational) B-spline; periodic curves are unwrapped onto one
    period ``[knots[deg], knots[-deg-1]]`` and evaluated modulo it."""

    knots: FloatArray
    poles: FloatArray  # (n, 2)
    weights: FloatArray  # (n,)
    degree: int
    period: float | None = None

    def _spline(self) -> BSpline:
        cache = self.__dict__.get("_cache")
        if cache is None:
            hom = np.column_stack([self.poles * self.weights[:, None], self.weights])
            cache = BSpline(self.knots, hom, self.degree, extrapolate=True)
            object.__setattr__(self, "_cache", cache)
        return cache

    def _homogeneous(self, t: ArrayLike, n: int) -> list[FloatArray]:
        """The weighted poles' spline and its first ``n`` derivatives at ``t``."""
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        if self.period is not None:
            lo = self.knots[self.degree]
            tt = lo + np.mod(tt - lo, self.period)
        a = self._spline()
        # derivatives evaluated directly (one-sided at a knot of high multiplicity:
        # BSpline.derivative refuses a C1 knot of a cubic)
        h = a(tt)
        return [h] + [
            a(tt, nu=k) if self.degree >= k else np.zeros_like(h) for k in range(1, n + 1)
        ]

    def derivs(self, t: ArrayLike) -> Derivs:
        h, h1, h2 = self._homogeneous(t, 2)
        w, w1, w2 = h[:, 2:3], h1[:, 2:3], h2[:, 2:3]
        p = h[:, :2] / w
        d1 = (h1[:, :2] - w1 * p) / w
        d2 = (h2[:, :2] - 2.0 * w1 * d1 - w2 * p) / w
        return p, d1, d2

    def derivs3(self, t: ArrayLike) -> Derivs3:
        h, h1, h2, h3 = self._homogeneous(t, 3)
        w, w1, w2, w3 = h[:, 2:3], h1[:, 2:3], h2[:, 2:3], h3[:, 2:3]
        p = h[:, :2] / w
        d1 = (h1[:, :2] - w1 * p) / w
        d2 = (h2[:, :2] - 2.0 * w1 * d1 - w2 * p) / w
        d3 = (h3[:, :2] - 3.0 * w1 * d2 - 3.0 * w2 * d1 - w3 * p) / w
        return p, d1, d2, d3


@dataclass(frozen=True)
class OffsetCurve(Curve):
    """OCC's ``Geom2d_OffsetCurve``: ``basis + offset * N``, ``N`` the basis's unit tangent
    turned clockwise (``(ty, -tx)``), on the basis's parameter; evaluated exactly from the
    basis's first three derivatives (the offset's second derivative needs the third)."""

    basis: Curve
    offset: float

    @property
    def period(self) -> float | None:
        """The basis's period (a whole circle or ellipse: 2 pi), if it has one."""
        if isinstance(self.basis, (CircleCurve, EllipseCurve)):
            return 2.0 * np.pi
        return getattr(self.basis, "period", None)

    def derivs(self, t: ArrayLike) -> Derivs:
        b, b1, b2, b3 = self.basis.derivs3(t)
        s2 = np.einsum("ij,ij->i", b1, b1)[:, None]
        s = np.sqrt(s2)
        u = b1 / s  # unit tangent
        ds = np.einsum("ij,ij->i", b1, b2)[:, None] / s  # |b'|'
        dds = (np.einsum("ij,ij->i", b2, b2)[:, None] + np.einsum("ij,ij->i", b1, b3)[:, None]) / s
        dds = dds - ds * ds / s
        u1 = b2 / s - b1 * ds / s2
        u2 = b3 / s - 2.0 * b2 * ds / s2 - b1 * dds / s2 + 2.0 * b1 * ds * ds / (s2 * s)
        d = self.offset

        def turn(v: FloatArray) -> FloatArray:
            return np.column_stack([v[:, 1], -v[:, 0]])

        return b + d * turn(u), b1 + d * turn(u1), b2 + d * turn(u2)


@dataclass(frozen=True)
class AffineCurve(Curve):
    """``matrix @ inner(t)``: the image of a curve under a linear map of the plane, on
    the inner curve's parameter (for curves whose image has no closed form of the same
    kind: an offset curve's image is no offset curve)."""

    inner: Curve
    matrix: FloatArray  # (2, 2)

    @property
    def period(self) -> float | None:
        """The inner curve's period (an offset of a whole circle or closed B-spline)."""
        return getattr(self.inner, "period", None)

    def derivs(self, t: ArrayLike) -> Derivs:
        p, d1, d2 = self.inner.derivs(t)
        a = self.matrix.T
        return p @ a, d1 @ a, d2 @ a

    def derivs3(self, t: ArrayLike) -> Derivs3:
        p, d1, d2, d3 = self.inner.derivs3(t)
        a = self.matrix.T
        return p @ a, d1 @ a, d2 @ a, d3 @ a


def _unit(v: FloatArray) -> tuple[FloatArray, float]:
    n = float(np.linalg.norm(v))
    return v / n, n


def _principal(center: FloatArray, a: FloatArray, b: FloatArray) -> tuple[EllipseCurve, float]:
    """The ellipse ``center + cos t a + sin t b`` (conjugate semi-diameters ``a``, ``b``)
    on its principal axes, and the shift ``s`` of its parameter: ``t' = t - s``."""
    s = 0.5 * math.atan2(2.0 * float(a @ b), float(a @ a - b @ b))
    big = a * math.cos(s) + b * math.sin(s)  # the extreme diameters, perpendicular
    small = -a * math.sin(s) + b * math.cos(s)
    if float(np.linalg.norm(small)) > float(np.linalg.norm(big)):
        big, small, s = small, -big, s + 0.5 * math.pi
    x, rx = _unit(big)
    y, ry = _unit(small)
    return EllipseCurve(center, rx, ry, x, y), s


def linear_image(
    curve: Curve, matrix: ArrayLike, t0: float, t1: float
) -> tuple[Curve, float, float]:
    """The image of ``curve`` (traversed from ``t0`` to ``t1``) under the invertible
    linear map ``matrix`` (2 x 2), exact, with its new ends: circles and ellipses become
    ellipses on their principal axes (a shifted parameter), B-splines map their poles,
    lines become degree-1 B-splines, anything else is wrapped (:class:`AffineCurve`).

    (A line as a :class:`LineCurve` tangent to an ellipse arc whose curvature is
    greatest at their joint left the branch from that curvature centre 3e-4 off, 6e-5
    of the diagonal, where the same line as a B-spline did not: a sheared fillet,
    build123d fuzz seed 6024.)"""
    a = np.asarray(matrix, dtype=float)
    if isinstance(curve, LineCurve):
        lo, hi = min(t0, t1), max(t0, t1)
        ends = np.array([curve.origin + lo * curve.direction, curve.origin + hi * curve.direction])
        line = NurbsCurve(np.array([lo, lo, hi, hi]), ends @ a.T, np.ones(2), 1)
        return line, t0, t1
    if isinstance(curve, (CircleCurve, EllipseCurve)):
        if isinstance(curve, CircleCurve):
            ra = rb = curve.radius
        else:
            ra, rb = curve.major, curve.minor
        conic, shift = _principal(a @ curve.center, ra * (a @ curve.xaxis), rb * (a @ curve.yaxis))
        return conic, t0 - shift, t1 - shift
    if isinstance(curve, NurbsCurve):
        poles = curve.poles @ a.T
        image = NurbsCurve(curve.knots, poles, curve.weights, curve.degree, curve.period)
        return image, t0, t1
    return AffineCurve(curve, a), t0, t1
