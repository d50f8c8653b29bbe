"""medialcad: the exact medial axis transform of CAD solids and faces on OpenCascade."""

from __future__ import annotations

import logging

from medialcad.api import MedialAxis2D, medial_axis_2d
from medialcad.errors import (
    ComputationError,
    DegenerateFaceError,
    InputError,
    MedialCadError,
    NonPlanarFaceError,
    NotAFaceError,
    OCCError,
    OpenWireError,
    ReadError,
    SelfIntersectingBoundaryError,
    UnsupportedGeometryError,
)
from medialcad.frame import Frame
from medialcad.mat2d.graph import Branch, Footpoint, MedialGraph, Node, NodeKind

__all__ = [
    "Branch",
    "ComputationError",
    "DegenerateFaceError",
    "Footpoint",
    "Frame",
    "InputError",
    "MedialAxis2D",
    "MedialCadError",
    "MedialGraph",
    "Node",
    "NodeKind",
    "NonPlanarFaceError",
    "NotAFaceError",
    "OCCError",
    "OpenWireError",
    "ReadError",
    "SelfIntersectingBoundaryError",
    "UnsupportedGeometryError",
    "medial_axis_2d",
]

__version__ = "0.1.0"

logging.getLogger(__name__).addHandler(logging.NullHandler())
