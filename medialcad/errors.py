"""One error hierarchy for medialcad.

Every failure a user can see is a :class:`MedialCadError`. Input problems (the shape
cannot be handled) derive from :class:`InputError`; failures of our own computation or of
OpenCascade derive from :class:`ComputationError`. The CLI maps ``InputError`` to exit
code 2 and everything else to exit code 1.
"""

from __future__ import annotations

__all__ = [
    "ComputationError",
    "DegenerateFaceError",
    "InputError",
    "MedialCadError",
    "NoSolidError",
    "NonPlanarFaceError",
    "NotAFaceError",
    "NotExtrusionOrRevolutionError",
    "OCCError",
    "OpenWireError",
    "ReadError",
    "SelfIntersectingBoundaryError",
    "UnsupportedGeometryError",
    "UnsupportedSolidError",
]


class MedialCadError(Exception):
    """Root of every error raised by medialcad."""


class InputError(MedialCadError):
    """The input cannot be handled (bad file, bad shape, unsupported geometry)."""


class NotAFaceError(InputError):
    """The object given is not a single face."""


class NonPlanarFaceError(InputError):
    """The face does not lie on a plane."""


class OpenWireError(InputError):
    """A boundary loop of the face is not closed."""


class SelfIntersectingBoundaryError(InputError):
    """The boundary of the face intersects itself."""


class DegenerateFaceError(InputError):
    """The face has (near) zero area or a degenerate boundary."""


class UnsupportedGeometryError(InputError):
    """A boundary curve type that cannot be converted to an exact representation."""


class BelowToleranceError(InputError):
    """The input has a feature (an edge between corners) shorter than the tolerance can
    resolve; the message says where and how long."""


class ReadError(InputError):
    """A file could not be read (missing, empty, not STEP/BREP, no usable shape)."""


class NoSolidError(InputError):
    """The input holds no solid (e.g. a STEP file of loose faces)."""


class OpenShellError(NoSolidError):
    """The input holds a shell that does not close (free edges) instead of a solid."""


class NotExtrusionOrRevolutionError(InputError):
    """The solid is neither a (right) extrusion nor a revolution; the message says why."""


class UnsupportedSolidError(InputError):
    """The solid is recognised but its medial axis is not supported (e.g. a pie slice)."""


class ComputationError(MedialCadError):
    """The computation failed on a valid input (an internal failure)."""


class OCCError(ComputationError):
    """An OpenCascade call failed (``Standard_Failure``, ``IsDone() == False``)."""
