"""Orchestration of the 3D MAT: recognition -> 2D MAT of the profile -> lifted complex."""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
from numpy.typing import NDArray

from medialcad.errors import ComputationError, MedialCadError, UnsupportedSolidError
from medialcad.mat3d.assemble import build_complex
from medialcad.mat3d.extrusion import extrusion_rows
from medialcad.mat3d.result import MedialAxis3D
from medialcad.mat3d.segments import split_branches
from medialcad.occ.complex import check_valid
from medialcad.recognition import Extrusion, Revolution

__all__ = ["medial_axis_of"]

FloatArray = NDArray[np.float64]


def _solid_diag(reading: Extrusion | Revolution) -> float:
    from medialcad.occ.recognize import solid_diagonal

    return solid_diagonal(reading)


def _refuse_pinched_slice(reading: Revolution, within: float) -> None:
    """A partial revolution whose profile is tangent to its axis at a point (a pinched
    pie slice: the caps meet only there) is refused. Its level curve ``d = x sin(Theta/2)``
    runs into the pinch with a cusp, and the slices of a disk tangent to its axis came
    out 0.34-0.49 diag unsound. A full turn of such a profile, a vertex of it on the axis,
    and a profile along its axis are answered."""
    from medialcad.occ.recognize import tangent_axis_points

    if reading.touches_axis:
        return
    pts = tangent_axis_points(reading, within)
    if pts:
        p = pts[0]
        raise UnsupportedSolidError(
            "a partial revolution whose profile is tangent to its axis at a point "
            f"({p[0]:.6g}, {p[1]:.6g}, {p[2]:.6g}; the solid is pinched there) is not "
            "supported"
        )


def medial_axis_of(
    reading: Extrusion | Revolution, tol: float | None, timings: dict[str, float]
) -> MedialAxis3D:
    """The MAT of a recognised solid (see :func:`medialcad.medial_axis`)."""
    from medialcad.api import medial_axis_2d

    diag = _solid_diag(reading)
    tol_abs = tol if tol is not None else 1e-5 * diag
    if isinstance(reading, Revolution) and not reading.full:
        _refuse_pinched_slice(reading, max(tol_abs, 10.0 * reading.brep_tolerance))
    t0 = time.perf_counter()
    tol_2d = tol_abs * _shear_contraction(reading)
    if isinstance(reading, Extrusion) and reading.cap_normal is not None:
        from medialcad.api import medial_axis_of_planar
        from medialcad.occ.face2d import sheared_planar_face

        section = sheared_planar_face(
            reading.cap,
            reading.frame.origin,
            reading.direction,
            reading.cap_normal,
            reading.profile,
        )
        mat2d = medial_axis_of_planar(section, tol_2d)
    else:
        mat2d = medial_axis_2d(reading.profile, tol=tol_abs)
    timings["mat2d"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    try:
        if isinstance(reading, Extrusion):
            parts = _extrusion(reading, mat2d, diag, tol_2d)
        else:
            from medialcad.mat3d.revolution import revolution_parts

            parts = revolution_parts(reading, mat2d, diag, tol_abs)
    except MedialCadError:
        raise
    except (ArithmeticError, ValueError, IndexError, KeyError, TypeError, AssertionError) as err:
        raise ComputationError(f"3D medial axis failed: {type(err).__name__}: {err}") from err
    sheets, seams, skeletal, rims, junctions, comp = parts
    if not sheets and not seams and not skeletal and not junctions:
        raise UnsupportedSolidError("the medial axis of this solid came out empty")
    check_valid(comp)
    timings["mat3d"] = time.perf_counter() - t0
    return MedialAxis3D(
        reading.kind,
        reading,
        mat2d,
        tol_abs,
        sheets,
        seams,
        junctions,
        skeletal,
        rims,
        comp,
        timings,
    )


def _shear_contraction(reading: Extrusion | Revolution) -> float:
    """How much finer than the 3D tolerance the profile's MAT is traced: an oblique
    prism's shear ``(p, z) -> (p, k.p + z / cos)`` (``|k| = tan``) stretches distances
    by at most ``sqrt(1 + sin) / cos``, its largest singular value; 1 otherwise."""
    if not isinstance(reading, Extrusion) or reading.cap_normal is None:
        return 1.0
    cos = float(reading.cap_normal @ reading.direction)
    sin = math.sqrt(max(0.0, 1.0 - cos * cos))
    return cos / math.sqrt(1.0 + sin)


def _roles(key: tuple) -> str | None:
    return {"SB": "seam", "ST": "seam", "OFF": "seam", "F0": "rim", "FL": "rim"}.get(key[0])


def _extrusion(reading: Extrusion, mat2d: Any, diag: float, tol: float) -> tuple:
    """A right prism's MAT from its profile's; an oblique prism's is the image of the
    right prism's on its cross-section, of its caps' distance (THEORY.md Sec. 1), under
    the shear that slants the caps: the distance to a side is the cross-section's, to a
    cap the height above its plane, so the shear carries the distance function, hence
    its ridge and its values (the radius), over exactly."""
    H = reading.height
    d = reading.direction
    m = reading.cap_normal if reading.cap_normal is not None else d
    cos = float(m @ d)
    origin = reading.frame.origin
    frame = mat2d.frame
    h = 0.5 * H
    level = h if mat2d.rmax > h + tol else None
    segments = split_branches(mat2d.graph, mat2d.boundary, level)

    def to_model(p: FloatArray) -> FloatArray:
        p = np.asarray(p, dtype=float)
        x = frame.to_3d(p[:, :2])
        # along d from the cross-section up to the bottom cap, then the height's share
        t = (p[:, 2] - (x - origin) @ m) / cos
        return np.asarray(x + t[:, None] * d)

    patches, offsets, lines, junctions = extrusion_rows(
        segments, to_model, H, level, mat2d.boundary
    )
    mid = None
    if level is not None:
        # the plane z = h of the canonical frame, turned as the profile's frame is (for a
        # right prism its own axes: the mid sheet's loops are nested in that orientation)
        up = m if float(frame.zdir @ d) > 0 else -m
        u = frame.xdir - (frame.xdir @ m) * m
        u = u / np.linalg.norm(u)
        mid = (to_model(np.array([[0.0, 0.0, h]]))[0], u, np.cross(up, u))
    return build_complex(
        patches,
        offsets,
        lines,
        junctions,
        diag=diag,
        mid_plane=mid,
        mid_radius=h,
        seam_roles=_roles,
    )
