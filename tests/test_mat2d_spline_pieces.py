"""Profiles written as many short B-spline edges (other systems split one curve into
pieces): the joints are small corners, most of them convex and nearly flat, whose
spokes are fed by boundary stretches far shorter than a candidate cell of the curves.
Each face is checked by the oracles; the smaller tests pin the medial map itself."""

from __future__ import annotations

import cadquery as cq
import numpy as np
import pytest

import medialcad
import medialcad.mat2d.trace as trace
from medialcad.mat2d.boundary import build_boundary
from medialcad.mat2d.medial_map import build_candidates, pair_minima
from medialcad.occ.face2d import planar_face
from tests import faces as F
from tests.test_mat2d_oracle import check_with_oracles


def _tracer(n: int) -> trace._Tracer:
    """The tracer the engine builds for ``F.spline_pieces(n)`` (stopped before tracing)."""
    made: list[trace._Tracer] = []
    init = trace._Tracer.__init__

    class _Stop(Exception):
        pass

    def stop(self: trace._Tracer, *a: object, **k: object) -> None:
        init(self, *a, **k)  # type: ignore[arg-type]
        made.append(self)
        raise _Stop

    with pytest.MonkeyPatch.context() as m:
        m.setattr(trace._Tracer, "__init__", stop)
        with pytest.raises(_Stop):
            medialcad.medial_axis_2d(F.spline_pieces(n))
    return made[0]


@pytest.mark.parametrize("n", [120, 160, 200])
def test_star_written_as_many_spline_pieces(n: int) -> None:
    """Refused before ("did not reach the tolerance"): 120 pieces lost a corner's spoke
    where every candidate point of the next piece lay behind the sample's tangent, 160
    where the first candidate cell held a larger maximum of ``f`` beyond the spoke's
    minimum, and 200 took a fit check's midpoint exactly on a corner (the disk tangent
    to one piece there) for half of a branch point."""
    check_with_oracles(F.spline_pieces(n), f"{n} spline pieces", n_boundary=200, per_branch=6)


def test_partner_across_a_nearly_flat_corner_between_splines_is_the_spoke() -> None:
    """A sample 0.015 before a convex corner of 1.6 degrees between two B-spline pieces
    that both bend away from its tangent: its disk is bounded by the next piece just
    past the corner (the spoke, radius ~1.1), not by the far side (6.44), although every
    candidate point of the next piece reads ``f = inf``."""
    tr = _tracer(120)
    corner = [c for c in tr.b.corners if abs(c.s - 171.49) < 0.01]
    assert len(corner) == 1 and 0.02 < corner[0].turn < 0.035
    s = np.array([corner[0].s - 0.015])
    before, after = tr.b.element_at(0, s[0] - 1e-9), tr.b.element_at(0, corner[0].s + 1e-9)
    loop = np.zeros(1, dtype=np.int64)
    across = pair_minima(tr.b, tr.cands, loop, s, np.array([after.index]), tr.cfg.tol)[0]
    assert 0.5 < across < 2.0
    sample = tr.eval(loop, s)
    assert sample.element[0] == before.index
    assert sample.partner_element[0] == after.index
    assert abs(sample.radius[0] - across) < 1e-12


def test_a_sample_exactly_on_a_convex_corner_is_moved_off_it() -> None:
    """The medial map at a convex corner is the limit from one side (radius -> 0 along
    the corner's spoke), not the disk tangent to one edge there: samples asked exactly
    there are taken a thousandth of the bisection resolution to the side they were on."""
    tr = _tracer(200)
    c = max((c for c in tr.b.corners if c.turn > 0), key=lambda c: c.turn)
    loop = np.zeros(3, dtype=np.int64)
    s = np.array([c.s, c.s + 1e-12, c.s - 0.5 * tr.cfg.eps_s])
    moved = tr._off_corners(loop, s)
    delta = 1e-3 * tr.cfg.eps_s
    assert moved[0] == pytest.approx(c.s - delta, abs=1e-15)
    assert moved[1] == pytest.approx(c.s + delta, abs=1e-15)
    assert moved[2] == s[2]
    at = tr.eval(loop[:1], s[:1])
    assert at.radius[0] < 1e3 * delta  # the spoke's disk, not a far side's


def test_fit_next_to_a_merged_node_converges() -> None:
    """A loop of 19 spline pieces drawn by ``bspline_chain`` (kept exactly as binary
    BREP): two branch points 0.3 tol apart merge into one node, whose point lies off
    each; the fit check's midpoint beside it missed by 0.74 tol, and the samples it asked
    for, inside the radius round the node where samples are thinned, were dropped again
    round after round ("did not reach the tolerance"). There the node's spread rules."""
    face = F.read_exact("chain_fit_inside_a_merged_node.bbrep")
    check_with_oracles(face, "chain, merged node", n_boundary=80, per_branch=12)


def test_joint_seeds_run_only_at_convex_corners() -> None:
    """The extra partner solve next to a joint is for corners: at a joint the boundary
    takes as smooth (turning by less than its angle tolerance) the candidates see the
    partners, and a seed would find a real but tiny spoke the tracer has no corner for."""
    star = _tracer(120)
    convex = sum(1 for c in star.b.corners if c.turn > 0)
    assert convex > 0
    assert int(star.cands.convex_end.sum()) == 2 * convex  # both edges at each corner
    halves = [
        cq.Edge.makeThreePointArc(cq.Vector(1, 0, 0), cq.Vector(0, 1, 0), cq.Vector(-1, 0, 0)),
        cq.Edge.makeThreePointArc(cq.Vector(-1, 0, 0), cq.Vector(0, -1, 0), cq.Vector(1, 0, 0)),
    ]
    disk = cq.Face.makeFromWires(cq.Wire.assembleEdges(halves)).wrapped
    pf = planar_face(disk)
    C = build_candidates(build_boundary(pf.loops, gap_tol=pf.gap_tol, angle_tol=1e-6), 0.1)
    assert not C.convex_end.any()


def test_near_circular_loop_of_30_pieces() -> None:
    """A loop of 30 spline pieces on a nearly circular outline (r = 0.74997), drawn by
    ``bspline_chain`` in CI's derandomized run (kept exactly as binary BREP). Its 90-odd
    branch points crowd within 1e-3 of the centre, and chains of them a tolerance apart
    merge into nodes whose point lies farther than the merge radius (1.3 tol) from a
    branch's own event: the fit check on the branch's last step, bent from its event to
    the node, asked for the same dropped samples round after round ("did not reach the
    tolerance"). Within two spreads of such a node the node's displacement rules."""
    face = F.read_exact("chain_near_circular_30_pieces.bbrep")
    check_with_oracles(face, "chain, near-circular", n_boundary=80, per_branch=12)


@pytest.mark.parametrize(("n", "amp", "k"), [(20, 1e-4, 3), (30, 1e-3, 2), (8, 1e-2, 3)])
def test_near_circular_outlines_written_as_spline_pieces(n: int, amp: float, k: int) -> None:
    """A circle of radius 0.75 perturbed by ``amp cos(k t)``, written as ``n`` pieces: a
    tree of 20 to 90 branches within ``~amp k^2`` of the centre, every one fed by spokes
    nearly parallel to it. Each passes the oracles (the first read 3 tol unsound where
    the ray depth magnified a 0.5 tol fit error across a branch ninefold, before the
    oracle's same-edge bisector)."""
    check_with_oracles(
        F.near_circle_pieces(n, amp, k), f"near circle {n} {amp} {k}", n_boundary=80, per_branch=12
    )
