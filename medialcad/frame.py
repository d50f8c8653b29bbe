"""A rigid frame mapping a plane's 2D coordinates to model space."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["Frame", "projection_along"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Frame:
    """Orthonormal frame: ``X = origin + x * xdir + y * ydir (+ z * zdir)``."""

    origin: FloatArray
    xdir: FloatArray
    ydir: FloatArray

    @cached_property
    def zdir(self) -> FloatArray:
        """The plane normal (right-handed; computed once)."""
        return np.cross(self.xdir, self.ydir)

    def to_3d(self, pts: ArrayLike) -> FloatArray:
        """Map ``(..., 2)`` or ``(..., 3)`` local coordinates to model space."""
        p = np.asarray(pts, dtype=float)
        out = self.origin + p[..., 0:1] * self.xdir + p[..., 1:2] * self.ydir
        if p.shape[-1] == 3:
            out = out + p[..., 2:3] * self.zdir
        return np.asarray(out)

    def to_2d(self, pts: ArrayLike) -> FloatArray:
        """Map ``(..., 3)`` model points to local ``(..., 2)`` (drops the normal part)."""
        d = np.asarray(pts, dtype=float) - self.origin
        return np.stack([d @ self.xdir, d @ self.ydir], axis=-1)

    def height(self, pts: ArrayLike) -> FloatArray:
        """Signed distance of model points from the plane."""
        return np.asarray((np.asarray(pts, dtype=float) - self.origin) @ self.zdir)


def projection_along(d: FloatArray, m: FloatArray) -> FloatArray:
    """The linear map ``x -> x - (d.x) d + (m.x) d`` (3 x 3): on the plane with unit
    normal ``m`` it is the projection along the unit ``d`` onto the plane across ``d``
    (an oblique prism's cap onto its cross-section); invertible, its determinant is
    ``m.d``."""
    return np.asarray(np.eye(3) + np.outer(d, m - d))
