"""The only part of medialcad that talks to OpenCascade (OCP).

Submodules:

- :mod:`medialcad.occ.io`: STEP/BREP reading and atomic writing, :func:`occ_guard`.
- :mod:`medialcad.occ.shapes`: accepting cadquery / build123d / raw shapes, topology helpers.
"""

from __future__ import annotations

from medialcad.occ.io import occ_guard, quiet_messenger, read_shapes, write_brep, write_step
from medialcad.occ.shapes import as_topods, faces, single_face, solids

__all__ = [
    "as_topods",
    "faces",
    "occ_guard",
    "quiet_messenger",
    "read_shapes",
    "single_face",
    "solids",
    "write_brep",
    "write_step",
]
