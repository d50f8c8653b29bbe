"""What a solid is: an extrusion or a revolution, with its exact profile and frame.

The descriptions are frozen dataclasses; the B-rep analysis that produces them lives in
:mod:`medialcad.occ.recognize`.

Canonical frames (THEORY.md):

- extrusion: the profile lies in ``z = 0`` of :attr:`Extrusion.frame` and the solid is
  ``profile x [0, length]`` along ``frame.zdir`` (= :attr:`Extrusion.direction`); an
  oblique prism's caps lie across the direction at a slant (:attr:`Extrusion.cap_normal`):
  the solid is the points ``x + t d`` of the profile's plane's lines along ``d`` between
  the caps' planes, for ``x`` in the profile (its cross-section);
- revolution: the profile lies in the half-plane ``x >= 0`` of the frame's ``xy``-plane
  and the solid is swept by rotating it about ``frame.ydir`` (= the axis direction, right
  hand) from 0 to :attr:`Revolution.angle`.

A solid that is both (a cylinder, a tube) is reported as an extrusion, with the
revolution reading in ``alternative``: the extrusion's MAT needs no special handling of
the axis and its profile is an exact cap face of the solid.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from medialcad.frame import Frame

__all__ = ["Extrusion", "Revolution", "SolidKind", "read_step", "recognize"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Extrusion:
    """An extrusion: a right prism ``profile x [0, length]``, or an oblique one (a
    profile swept along a slanted vector: sides along ``direction``, caps in two
    parallel planes with normal ``cap_normal``).

    Attributes:
        direction: unit extrusion direction in model space (from the profile's cap to
            the other one): the direction of the side faces' rulings.
        length: how far the sweep goes along ``direction`` (the distance between the
            caps for a right prism; ``height / cos`` of the slant for an oblique one).
        profile: the exact planar profile face (``TopoDS_Face``) in model space: a cap of
            the solid, or the cap faces merged when the cap is split. For an oblique
            prism, its cross-section across ``direction`` through ``frame.origin`` (the
            cap projected along ``direction``), for drawing: OCC's conversion
            approximates offset curves in it; the MAT maps ``cap``'s exact curves.
        frame: maps canonical coordinates (profile in ``z = 0``, extrusion along ``+z``)
            to model space.
        tolerance: the largest deviation from an exact extrusion measured on the B-rep
            (length units).
        alternative: the revolution reading of the same solid, if there is one.
        solid: the ``TopoDS_Solid`` it describes; diag: its bounding-box diagonal.
        brep_tolerance: the largest tolerance the B-rep records on its vertices, edges
            and faces: how far apart its faces may lie where they meet.
        cap_normal: an oblique prism's unit cap normal (``cap_normal @ direction > 0``);
            ``None`` for a right prism. ``frame.origin`` lies on the bottom cap.
        cap: an oblique prism's bottom cap face (the exact curves its cross-section is
            computed from); ``None`` for a right prism (``profile`` is its cap).
    """

    direction: FloatArray
    length: float
    profile: Any
    frame: Frame
    tolerance: float
    alternative: Revolution | None = None
    solid: Any = None
    diag: float = 0.0
    brep_tolerance: float = 0.0
    cap_normal: FloatArray | None = None
    cap: Any = None

    kind = "extrusion"

    @property
    def height(self) -> float:
        """Distance between the caps' planes (``length`` for a right prism)."""
        if self.cap_normal is None:
            return float(self.length)
        return float(self.length * (self.cap_normal @ self.direction))


@dataclass(frozen=True)
class Revolution:
    """A solid swept by revolving a planar profile about an axis.

    Attributes:
        axis_point: a point of the axis (the foot of the solid's centroid on it).
        axis_direction: unit axis direction; the sweep turns right-handed about it.
        angle: swept angle in radians, ``2*pi`` for a full revolution.
        profile: the exact planar profile (``TopoDS_Face``) in model space: the start cap
            for a partial revolution, a meridian section for a full one.
        frame: maps canonical coordinates (profile in ``x >= 0`` of the ``xy``-plane,
            revolved about ``+y``) to model space; ``frame.xdir`` points into the profile's
            half-plane.
        touches_axis: an edge of the profile lies on the axis (shafts, pins).
        tolerance: the largest deviation from an exact revolution measured on the B-rep.
        alternative: the extrusion reading of the same solid, if there is one.
        solid: the ``TopoDS_Solid`` it describes; diag: its bounding-box diagonal.
        brep_tolerance: the largest tolerance the B-rep records on its vertices, edges
            and faces: how far apart its faces may lie where they meet.
    """

    axis_point: FloatArray
    axis_direction: FloatArray
    angle: float
    profile: Any
    frame: Frame
    touches_axis: bool
    tolerance: float
    alternative: Extrusion | None = None
    solid: Any = None
    diag: float = 0.0
    brep_tolerance: float = 0.0

    kind = "revolution"

    @property
    def full(self) -> bool:
        """True for a revolution through 360 degrees."""
        return bool(abs(self.angle - 2.0 * math.pi) < 1e-12)


SolidKind = Extrusion | Revolution


def recognize(solid: Any, tol: float | None = None) -> SolidKind:
    """Recognise an extrusion or a revolution from the B-rep alone.

    Args:
        solid: a ``TopoDS_Solid`` (or a shape holding exactly one solid), a cadquery
            ``Workplane``/``Shape`` or a build123d shape.
        tol: linear tolerance of the tests; default ``max(1e-6 x diagonal, the largest
            tolerance of the shape's sub-shapes)``.

    Raises:
        NoSolidError: the input holds no solid.
        InputError: it holds several solids (use :func:`read_step` / iterate).
        NotExtrusionOrRevolutionError: the solid is neither; the message says which face
            breaks each reading.
    """
    from medialcad.occ.recognize import recognize_solid

    return recognize_solid(solid, tol)


def read_step(path: Any) -> list[Any]:
    """The solids of a STEP (or BREP) file, in file order, as ``TopoDS_Solid``.

    Raises:
        ReadError: the file is missing, empty, not STEP/BREP or unreadable.
        NoSolidError: the file holds no solid (e.g. only faces); closed shells outside
            every solid count as solids, an open one raises :class:`OpenShellError`.
    """
    from medialcad.errors import NoSolidError
    from medialcad.occ.io import read_shapes
    from medialcad.occ.shapes import solids_or_shells

    found = []
    for shape in read_shapes(path):
        found.extend(solids_or_shells(shape))
    if not found:
        raise NoSolidError(f"{path}: the file holds no solid")
    return found
