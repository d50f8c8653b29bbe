"""Plain-numpy B-splines (clamped, non-rational) and least-effort fitting within a tolerance."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import BSpline, make_interp_spline

__all__ = ["Spline", "fit_spline"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Spline:
    """A clamped B-spline ``u in [knots[0], knots[-1]] -> R^dim``."""

    knots: FloatArray
    coeffs: FloatArray  # (n, dim)
    degree: int

    def __call__(self, u: ArrayLike) -> FloatArray:
        return np.asarray(self._bspline(u))

    @cached_property
    def _bspline(self) -> BSpline:
        """scipy's evaluator, built once (its construction costs more than a call)."""
        return BSpline(self.knots, self.coeffs, self.degree, extrapolate=False)

    def derivative(self, nu: int = 1) -> Spline | None:
        """The ``nu``-th derivative as a spline (None where it vanishes: ``nu > degree``)."""
        if nu > self.degree:
            return None
        d = self._bspline.derivative(nu)
        return Spline(np.asarray(d.t, dtype=float), np.asarray(d.c, dtype=float), int(d.k))

    @property
    def domain(self) -> tuple[float, float]:
        return float(self.knots[0]), float(self.knots[-1])


def _chord_params(pts: FloatArray) -> FloatArray:
    d = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    u = np.concatenate([[0.0], np.cumsum(d)])
    return u / u[-1] if u[-1] > 0 else np.linspace(0.0, 1.0, len(pts))


def fit_spline(values: ArrayLike, params: ArrayLike | None = None, degree: int = 3) -> Spline:
    """Interpolate ``values (n, dim)`` at ``params`` (chord length of the first two
    columns when omitted) with a clamped spline of ``degree`` (lowered for few points)."""
    v = np.asarray(values, dtype=float)
    u = _chord_params(v[:, :2]) if params is None else np.asarray(params, dtype=float)
    keep = np.concatenate([[True], np.diff(u) > 1e-11])  # OCC merges closer knots
    keep[-1] = True
    if not keep[-2] and len(u) > 2:
        keep[-2] = False
    v, u = v[keep], u[keep]
    if len(u) > 1 and u[-1] <= u[-2]:
        v, u = np.delete(v, -2, axis=0), np.delete(u, -2)
    k = min(degree, len(u) - 1)
    if k < 1:
        v = np.vstack([v, v])
        u = np.array([0.0, 1.0])
        k = 1
    sp = make_interp_spline(u, v, k=k)
    return Spline(np.asarray(sp.t, dtype=float), np.asarray(sp.c, dtype=float), int(sp.k))
