"""Revolved sheets are exact: their rows are circular arcs written as rational quadratic
B-splines (``medialcad.mat3d.arcs``), a few poles across whatever the angle.

* An arc's poles put every point of it on its circle, from its start angle to its end,
  monotonically, for spans from 0 to nearly a full turn.
* Interpolating rows of arcs across ``w`` (homogeneous coordinates) reproduces each row,
  and columns of unit weight (the arcs' ends) stay polynomial, so a cap sharing that
  side has the same curve.
* On real revolutions, the revolved sheets OCC evaluates keep their rows on circles about
  the axis (checked on the surface itself: exactly at the interpolated rows, and between
  them within the rows' tolerance, exactly for full turns), with ``2k + 1`` poles
  across (``k`` quarter turns or fewer), and a partial turn's rims are circles to
  rounding.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.gp import gp_Pnt

from medialcad.mat3d.arcs import (
    arc_knots,
    arc_net,
    arc_pieces,
    arc_points,
    homogeneous,
    interp_rational,
)
from tests import faces as F
from tests.test_mat3d_revolution import cylindrical, revolution_mat, revolve

A, D = np.eye(3)[0], np.eye(3)[1]  # the frame's x direction and axis


def _model(q: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """``X(q, phi) = y D + x (cos(phi) A + sin(phi) B)`` about the y-axis."""
    x, y = q[..., 0], q[..., 1]
    b = np.cross(D, A)
    return y[..., None] * D + x[..., None] * (
        np.cos(phi)[..., None] * A + np.sin(phi)[..., None] * b
    )


def _polar(p: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    b = np.cross(D, A)
    u, w = p @ A, p @ b
    return np.hypot(u, w), p @ D, np.arctan2(w, u)


@pytest.mark.parametrize("span_deg", [0.0, 1e-6, 10.0, 90.0, 91.0, 179.9, 250.0, 359.0])
def test_arc_net_points_lie_on_their_circles(span_deg: float) -> None:
    rng = np.random.default_rng(7)
    n = 9
    q = np.column_stack([rng.uniform(0.1, 5.0, n), rng.uniform(-3, 3, n)])
    phi0 = rng.uniform(-1.0, 1.0, n)
    span = np.full(n, math.radians(span_deg)) * rng.uniform(0.2, 1.0, n)
    k = arc_pieces(math.radians(span_deg))
    poles, weights = arc_net(_model, q, phi0, span, k)
    assert poles.shape == (n, 2 * k + 1, 3) and weights.shape == (n, 2 * k + 1)
    assert np.all(weights >= math.cos(math.pi / 4) - 1e-15)
    t = np.linspace(0.0, 1.0, 801)
    pts = arc_points(homogeneous(poles, weights), t)
    rho, y, phi = _polar(pts)
    assert np.abs(rho - q[:, :1]).max() <= 1e-14 * 5
    assert np.abs(y - q[:, 1:]).max() <= 1e-14 * 5
    rel = np.unwrap(phi - phi0[:, None], axis=1)
    assert np.abs(rel[:, 0]).max() <= 1e-14 and np.abs(rel[:, -1] - span).max() <= 1e-13
    assert np.all(np.diff(rel, axis=1) >= -1e-15)  # monotone: no back-tracking


def test_arc_pieces_are_at_most_quarter_turns() -> None:
    assert [arc_pieces(math.radians(a)) for a in (5, 90, 90.0001, 180, 270, 359)] == [
        1, 1, 2, 2, 3, 4,
    ]  # fmt: skip
    assert arc_knots(3).tolist() == [0, 0, 0, 1 / 3, 1 / 3, 2 / 3, 2 / 3, 1, 1, 1]


def test_interpolated_rows_are_reproduced_and_unit_columns_stay_polynomial() -> None:
    w = np.linspace(0.0, 1.0, 12) ** 1.3
    q = np.column_stack([2 + np.sin(3 * w), w**2])
    phi0 = 0.4 * np.sqrt(w)  # spans changing fast at one end, as next to a level end
    span = 4.0 - 2 * phi0
    k = arc_pieces(float(span.max()))
    poles, weights = arc_net(_model, q, phi0, span, k)
    tu, ku, cp, cw = interp_rational(w, poles, weights)
    assert np.all(cw[:, ::2] == 1.0)  # the arcs' ends and joints: polynomial columns
    # de Boor across u, then the rows' arcs: each row comes back exactly
    from scipy.interpolate import BSpline

    rows = BSpline(tu, homogeneous(cp, cw), ku, axis=0)(w)
    back = arc_points(rows, np.linspace(0, 1, 41))
    exact = arc_points(homogeneous(poles, weights), np.linspace(0, 1, 41))
    assert np.abs(back - exact).max() <= 1e-12


def _revolved_sheets(result) -> list:
    return [s for s in result.sheets if s.role == "revolved"]


def _spread_along_v(surf, placement: F.Placement, angle: float, us: np.ndarray) -> float:
    """Max spread of the distance to the axis and of the height along ``v`` at ``us``."""
    _, _, v0, v1 = surf.Bounds()
    worst = 0.0
    for u in us:
        pts = []
        for v in np.linspace(v0, v1, 31):
            p = gp_Pnt()
            surf.D0(float(u), float(v), p)
            pts.append([p.X(), p.Y(), p.Z()])
        rho, y, _ = cylindrical(np.array(pts), placement, angle)
        worst = max(worst, float(np.ptp(rho)), float(np.ptp(y)))
    return worst


@pytest.mark.parametrize("rounded", [True, False])
@pytest.mark.parametrize(("angle_deg", "seed"), [(60.0, 1), (250.0, 2), (359.0, 3), (360.0, 4)])
def test_revolved_sheets_are_exact_arcs_with_few_poles(
    angle_deg: float, seed: int, rounded: bool
) -> None:
    angle = math.radians(angle_deg)
    placement = F.random_placement(seed, distance=50.0)
    profile = F.rounded_rectangle(1.5, 0.8, 0.5) if rounded else F.rectangle(1.5, 0.8)
    face = F.place(profile, F.Placement(np.eye(3), np.array([3.5, 0.5, 0.0])))
    solid = revolve(face, angle, placement)
    result = revolution_mat(solid)
    sheets = _revolved_sheets(result)
    assert sheets
    k = 1 if angle_deg == 360.0 else arc_pieces(angle)
    for s in sheets:
        surf = BRep_Tool.Surface_s(s.face)
        assert surf.IsVRational() and surf.VDegree() == 2
        assert surf.NbVPoles() == 2 * k + 1
        # the interpolated rows (the knots of a not-a-knot cubic) are circles; between
        # them a partial turn's weights vary, within the rows' tolerance (full: exact)
        knots = np.array([surf.UKnot(i) for i in range(1, surf.NbUKnots() + 1)])
        assert _spread_along_v(surf, placement, angle, knots) <= 1e-12 * 50
        between = 0.5 * (knots[1:] + knots[:-1])
        bound = 1e-12 * 50 if angle_deg == 360.0 else 0.1 * result.tol
        assert _spread_along_v(surf, placement, angle, between) <= bound
    if not rounded:  # the rims: the corners' circles, sheets ending on them exactly
        circles = 0
        for rim in result.rims:
            c = BRepAdaptor_Curve(rim.edge)
            ts = np.linspace(c.FirstParameter(), c.LastParameter(), 17)
            pts = np.array([[c.Value(t).X(), c.Value(t).Y(), c.Value(t).Z()] for t in ts])
            rho, y, phi = cylindrical(pts, placement, angle)
            if np.ptp(phi) > 1e-3:  # (the other rims are cap outlines in the end planes)
                assert np.ptp(rho) <= 1e-12 * 50 and np.ptp(y) <= 1e-12 * 50
                assert min(abs(rho[0] - 2.0), abs(rho[0] - 5.0)) <= 1e-12 * 50
                circles += 1
        assert circles == (4 if angle_deg < 360.0 else 16)  # (a full turn: in quarters)
