"""The medial graph of a planar face: frozen dataclasses over numpy arrays.

Coordinates: every 2D quantity (``*_2d``) is in the face's own frame
(:class:`medialcad.frame.Frame`), every 3D quantity is in model space. The frame
maps one to the other exactly (a rigid motion).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum

import numpy as np
from numpy.typing import NDArray

from medialcad.frame import Frame
from medialcad.mat2d.spline import Spline

__all__ = ["Branch", "ElementKind", "Footpoint", "MedialGraph", "Node", "NodeKind"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


class NodeKind(StrEnum):
    """What a medial node is (paper Sec. 2.2)."""

    BRANCH_POINT = "branch_point"  # 3 or more footpoints
    CONVEX_VERTEX = "convex_vertex"  # end point with r = 0 at a convex corner
    CURVATURE_CENTRE = "curvature_centre"  # end point r = 1/k at a curvature maximum


class ElementKind(StrEnum):
    """Boundary elements the medial axis is equidistant to."""

    EDGE = "edge"
    REFLEX_VERTEX = "reflex_vertex"


@dataclass(frozen=True)
class Footpoint:
    """A touch point of a maximal disk on the boundary.

    ``element`` indexes :attr:`MedialGraph.elements`; ``param`` is the curve
    parameter of the edge (its OCC parameter) or, for a reflex vertex, the angle of
    the disk's normal at the vertex in the face frame.
    """

    element: int
    param: float
    point_2d: FloatArray


@dataclass(frozen=True)
class BoundaryElement:
    """One boundary element: an edge of the face or a reflex vertex."""

    index: int
    kind: ElementKind
    loop: int
    # index of the OCC edge in face order (one edge may be two elements: a closed curve
    # split at a convex seam corner); for a vertex: the edge it ends
    edge_index: int
    point_2d: FloatArray | None = None  # reflex vertices only


@dataclass(frozen=True)
class Node:
    """A branch point or an end point of the medial axis."""

    index: int
    kind: NodeKind
    point_2d: FloatArray
    point: FloatArray
    radius: float
    footpoints: tuple[Footpoint, ...]


@dataclass(frozen=True)
class Branch:
    """A simplified segment of the medial axis between two nodes (or a closed loop).

    The arrays run along the branch from ``start`` to ``end``. ``foot_a_*`` and
    ``foot_b_*`` are the two footpoints of each normal point: the boundary element
    index, its parameter and the footpoint itself. ``spline`` is a B-spline of
    ``(x, y, r)`` in the face frame (radius travels in the same parameter), fitted
    within the tolerance of the graph.
    """

    index: int
    start: int | None
    end: int | None
    points_2d: FloatArray  # (n, 2)
    radius: FloatArray  # (n,)
    foot_a_element: IntArray  # (n,)
    foot_a_param: FloatArray  # (n,)
    foot_a_point: FloatArray  # (n, 2)
    foot_b_element: IntArray
    foot_b_param: FloatArray
    foot_b_point: FloatArray
    spline: Spline

    @property
    def closed(self) -> bool:
        """True for a branch with no end nodes (an annulus' circle)."""
        return self.start is None


@dataclass(frozen=True)
class MedialGraph:
    """The 2D medial axis transform of a planar face."""

    frame: Frame
    tol: float
    nodes: tuple[Node, ...]
    branches: tuple[Branch, ...]
    elements: tuple[BoundaryElement, ...] = field(default=())

    @property
    def rmax(self) -> float:
        """Largest radius on the medial axis."""
        radii = [n.radius for n in self.nodes] + [float(b.radius.max()) for b in self.branches]
        return max(radii) if radii else 0.0
