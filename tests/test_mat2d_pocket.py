"""The pocket solver's partner search against the closed-form MAT of an ellipse: the
maximal disk tangent at ``(a cos t, b sin t)`` near the major vertex touches again at
the mirror point ``-t``, its radius ``b N / a`` with ``N = |(b cos t, a sin t)|``."""

from __future__ import annotations

import numpy as np

from medialcad.mat2d.pocket import _tangent_partners

A, B = 3.0, 1.0


def _points(t: np.ndarray) -> np.ndarray:
    return np.column_stack([A * np.cos(t), B * np.sin(t)])


def _chords(t: np.ndarray, u: np.ndarray) -> np.ndarray:
    """``P(u) - P(t)`` in closed form (products of sines: no cancellation)."""
    s, d = 0.5 * (u + t[:, None]), 0.5 * (u - t[:, None])
    return np.stack([-2.0 * A * np.sin(s) * np.sin(d), 2.0 * B * np.cos(s) * np.sin(d)], axis=-1)


def _feet(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    n = np.column_stack([B * np.cos(t), A * np.sin(t)])
    return _points(t), -n / np.linalg.norm(n, axis=1)[:, None]


def test_partners_are_the_mirror_feet_with_the_closed_form_radius() -> None:
    t = -np.linspace(0.02, 0.3, 15)
    bq, nq = _feet(t)
    u, r = _tangent_partners(bq, nq, t, _chords, 0.0, 0.8)
    radius = B * np.hypot(B * np.cos(t), A * np.sin(t)) / A
    assert np.allclose(u, -t, atol=1e-8)
    assert np.allclose(r, radius, rtol=1e-12, atol=1e-12)


def test_a_least_at_the_branch_points_foot_is_taken_there() -> None:
    t = np.array([-0.5, -0.4])
    bq, nq = _feet(t)
    u, r = _tangent_partners(bq, nq, t, _chords, 0.0, 0.2)  # mirrors at 0.5, 0.4: beyond
    q = _points(np.array([0.2])) - bq
    assert np.allclose(u, 0.2, atol=1e-12)
    assert np.allclose(r, (q * q).sum(1) / (2.0 * (q * nq).sum(1)), rtol=1e-12)


def test_no_partner_when_the_least_is_at_the_maximum() -> None:
    t = np.array([-0.05, -0.1])
    bq, nq = _feet(t)
    u, r = _tangent_partners(bq, nq, t, _chords, 0.3, 0.8)  # mirrors before the stretch
    assert np.isnan(u).all() and np.isnan(r).all()


def test_no_partner_when_the_stretch_is_on_the_outer_side() -> None:
    t = np.array([-0.2, -0.1])
    bq, nq = _feet(t)
    u, r = _tangent_partners(bq, -nq, t, _chords, 0.0, 0.8)  # outward normals
    assert np.isnan(u).all() and np.isnan(r).all()
