"""medialcad: the exact medial axis transform of CAD solids and faces on OpenCascade."""

from __future__ import annotations

import logging

from medialcad.api import MedialAxis2D, medial_axis, medial_axis_2d
from medialcad.errors import (
    BelowToleranceError,
    ComputationError,
    DegenerateFaceError,
    InputError,
    MedialCadError,
    NonPlanarFaceError,
    NoSolidError,
    NotAFaceError,
    NotExtrusionOrRevolutionError,
    OCCError,
    OpenShellError,
    OpenWireError,
    ReadError,
    SelfIntersectingBoundaryError,
    UnsupportedGeometryError,
    UnsupportedSolidError,
)
from medialcad.frame import Frame
from medialcad.mat2d.graph import Branch, Footpoint, MedialGraph, Node, NodeKind
from medialcad.mat3d.result import Junction, MedialAxis3D, Seam, Sheet
from medialcad.recognition import Extrusion, Revolution, read_step, recognize

__all__ = [
    "BelowToleranceError",
    "Branch",
    "ComputationError",
    "DegenerateFaceError",
    "Extrusion",
    "Footpoint",
    "Frame",
    "InputError",
    "Junction",
    "MedialAxis2D",
    "MedialAxis3D",
    "MedialCadError",
    "MedialGraph",
    "NoSolidError",
    "Node",
    "NodeKind",
    "NonPlanarFaceError",
    "NotAFaceError",
    "NotExtrusionOrRevolutionError",
    "OCCError",
    "OpenShellError",
    "OpenWireError",
    "ReadError",
    "Revolution",
    "Seam",
    "SelfIntersectingBoundaryError",
    "Sheet",
    "UnsupportedGeometryError",
    "UnsupportedSolidError",
    "medial_axis",
    "medial_axis_2d",
    "read_step",
    "recognize",
]

__version__ = "0.1.0"

logging.getLogger(__name__).addHandler(logging.NullHandler())
