"""Circular arcs about an axis as exact rational quadratic B-splines, and tensor patches
whose rows are such arcs (the revolved sheets of a revolution).

An arc of angle ``2h`` is the rational quadratic Bezier with poles at its ends (weight 1)
and at the intersection of their tangents (distance ``x / cos(h)`` from the axis, weight
``cos(h)``). A row's arc is split into ``k`` equal pieces (``h <= pi/4``) and written as
one B-spline of degree 2 with double interior knots: ``2k + 1`` poles instead of the
dozens a cubic interpolation needs to stay on the circle. All rows of a patch use the
same ``k``, so patches sharing a row's arc share its poles exactly.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import make_interp_spline

from medialcad.errors import ComputationError

__all__ = ["arc_knots", "arc_net", "arc_pieces", "arc_points", "homogeneous", "interp_rational"]

FloatArray = NDArray[np.float64]
Model = Callable[[FloatArray, FloatArray], FloatArray]


def arc_pieces(span: float) -> int:
    """Pieces for arcs of up to ``span`` radians: at most a quarter turn each."""
    return max(1, math.ceil(span / (0.5 * math.pi) - 1e-12))


def arc_knots(k: int) -> FloatArray:
    """The clamped knots of ``k`` quadratic pieces on ``[0, 1]`` (interior knots double)."""
    inner = np.repeat(np.arange(1, k) / k, 2)
    return np.concatenate([[0.0, 0.0, 0.0], inner, [1.0, 1.0, 1.0]])


def arc_net(
    model: Model, q: FloatArray, phi0: FloatArray, span: FloatArray, k: int
) -> tuple[FloatArray, FloatArray]:
    """Poles ``(n, 2k + 1, 3)`` and weights ``(n, 2k + 1)`` of the arcs from ``phi0`` to
    ``phi0 + span`` of the points ``q (n, 2)`` (canonical ``(x, y)``, ``x >= 0``) about the
    axis; ``model(q, phi)`` maps canonical points at angles to model space."""
    q = np.asarray(q, dtype=float)
    phi0, span = np.asarray(phi0, dtype=float), np.asarray(span, dtype=float)
    t = np.arange(2 * k + 1) / (2 * k)
    odd = (np.arange(2 * k + 1) % 2 == 1)[None, :]
    phi = phi0[:, None] + t[None, :] * span[:, None]
    cos_h = np.cos(span / (2 * k))[:, None]
    qq = np.repeat(q[:, None, :], 2 * k + 1, axis=1)
    qq[..., 0] *= np.where(odd, 1.0 / cos_h, 1.0)
    weights = np.where(odd, cos_h, 1.0)
    return np.asarray(model(qq, phi)), np.asarray(weights)


def homogeneous(poles: FloatArray, weights: FloatArray) -> FloatArray:
    """``(w P, w)``: the coordinates a rational spline is linear in."""
    return np.concatenate([poles * weights[..., None], weights[..., None]], axis=-1)


def arc_points(hnet: FloatArray, t: FloatArray) -> FloatArray:
    """Points ``(n, m, 3)`` at parameters ``t (m,)`` in ``[0, 1]`` of the rows of
    homogeneous poles ``hnet (n, 2k + 1, 4)`` (``k`` rational quadratic pieces)."""
    k = (hnet.shape[1] - 1) // 2
    t = np.asarray(t, dtype=float)
    p = np.minimum(np.floor(t * k).astype(int), k - 1)
    s = (t * k - p)[None, :, None]
    h = (
        (1 - s) ** 2 * hnet[:, 2 * p]
        + 2 * s * (1 - s) * hnet[:, 2 * p + 1]
        + s**2 * hnet[:, 2 * p + 2]
    )
    return np.asarray(h[..., :3] / h[..., 3:])


def interp_rational(
    w: FloatArray, poles: FloatArray, weights: FloatArray
) -> tuple[FloatArray, int, FloatArray, FloatArray]:
    """Interpolate rows of arcs (``poles (nu, nv, 3)``, ``weights (nu, nv)``) at ``w`` in
    homogeneous coordinates: knots in ``u``, degree, poles and weights of the surface.
    Each row at ``w`` is reproduced exactly; a column of unit weights (the arcs' ends)
    stays polynomial, so it is the same curve as a polynomial patch's side on those
    points."""
    ku = int(min(3, len(w) - 1))
    sp = make_interp_spline(w, homogeneous(poles, weights), k=ku, axis=0)
    c = np.asarray(sp.c)
    wts = c[..., 3].copy()
    unit = np.all(weights == 1.0, axis=0)
    wts[:, unit] = 1.0
    if not np.all(wts > 1e-3):
        raise ComputationError("a revolved sheet's interpolated weights are not positive")
    out = np.where(unit[None, :, None], c[..., :3], c[..., :3] / wts[..., None])
    return np.asarray(sp.t), ku, np.asarray(out), wts
