"""Reliability: mutated STEP files never crash the process; results are deterministic;
degenerate extrusion lengths and revolution angles give valid, sound complexes."""

from __future__ import annotations

import json
import math
import os
import random
import subprocess
import sys
from pathlib import Path

import cadquery as cq
import numpy as np
import pytest
from OCP.BRepCheck import BRepCheck_Analyzer

from medialcad.api import medial_axis
from medialcad.mat3d.solid import medial_axis_of
from medialcad.recognition import recognize
from tests import oracles3d as O

ROOT = Path(__file__).resolve().parents[1]
BOX = (ROOT / "fixtures" / "step" / "solids" / "box.step").read_bytes()


def _mutations(seed: int) -> list[tuple[str, bytes]]:
    rng = random.Random(seed)
    lines = BOX.split(b"\n")
    out = [("truncated-half", BOX[: len(BOX) // 2]), ("truncated-tail", BOX[:-40])]
    shuffled = lines[:]
    head, body = shuffled[:20], shuffled[20:-5]
    rng.shuffle(body)
    out.append(("shuffled", b"\n".join(head + body + shuffled[-5:])))
    for k in range(4):
        data = bytearray(BOX)
        for _ in range(8):
            i = rng.randrange(len(data))
            data[i] ^= 1 << rng.randrange(8)
        out.append((f"bitflips-{k}", bytes(data)))
    dropped = [ln for ln in lines if rng.random() > 0.05]
    out.append(("dropped-lines", b"\n".join(dropped)))
    return out


@pytest.mark.parametrize(
    ("name", "data"), _mutations(7), ids=lambda x: x if isinstance(x, str) else ""
)
def test_a_mutated_step_file_never_crashes_the_process(
    tmp_path: Path, name: str, data: bytes
) -> None:
    src = tmp_path / f"{name}.step"
    src.write_bytes(data)
    out = tmp_path / "out.step"
    res = subprocess.run(
        [sys.executable, "-m", "medialcad", str(src), "-o", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )
    assert res.returncode in (0, 1, 2), res.stderr  # never a signal (negative code)
    assert "Traceback" not in res.stderr
    if res.returncode != 0:
        assert len(res.stderr.strip().splitlines()) == 1
        assert not out.exists()


def test_the_same_input_gives_the_same_output() -> None:
    solid = (
        cq.Workplane()
        .polyline([(0, 0), (30, 0), (30, 10), (10, 10), (10, 25), (0, 25)])
        .close()
        .extrude(6)
    )
    a = medial_axis(solid.val()).radius_data()
    b = medial_axis(solid.val()).radius_data()
    assert json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)


def _check(solid: object, mat: object, n: int = 200) -> tuple[float, float]:
    sb = O.SolidBoundary(solid)
    pts = O.sample_compound(mat.compound, 10, 4)  # type: ignore[attr-defined]
    if len(pts) > n:
        pts = pts[np.random.default_rng(0).choice(len(pts), n, replace=False)]
    # (samples above tol re-measured as their distance to the MAT: a 1e-3 notch's narrow
    # parabolas magnify the ray error ~20x)
    snd = O.soundness(sb, pts, refine_above=float(mat.tol))  # type: ignore[attr-defined]
    assert not np.any(np.isinf(snd)), "a sample lies outside the solid"
    cmp_ = O.completeness(sb, mat.compound, 60)  # type: ignore[attr-defined]
    assert BRepCheck_Analyzer(mat.compound).IsValid()  # type: ignore[attr-defined]
    assert O.topology(mat.compound) == (1, O.solid_euler(solid))  # type: ignore[attr-defined]
    return float(np.nanmax(snd)), float(np.max(cmp_))


@pytest.mark.parametrize("length", [20.0, 20.0 * (1 + 1e-9), 20.0 * (1 - 1e-9)])
def test_an_extrusion_exactly_twice_as_long_as_its_largest_radius(length: float) -> None:
    # a 40 x 20 rectangle has Rmax = 10; L = 2 Rmax is the degenerate boundary where the
    # mid sheet vanishes into the central seam (and its neighbours on either side)
    solid = cq.Workplane().rect(40, 20).extrude(length).val()
    mat = medial_axis(solid)
    snd, cmp_ = _check(solid, mat)
    assert max(snd, cmp_) <= mat.tol


def test_a_branch_point_with_radius_rmax_a_square_prism() -> None:
    solid = cq.Workplane().rect(20, 20).extrude(35).val()
    mat = medial_axis(solid)
    snd, cmp_ = _check(solid, mat)
    assert max(snd, cmp_) <= mat.tol


@pytest.mark.parametrize("factor", [1.0 - 1e-9, 1.0, 1.0 + 1e-9, 0.5, 2.0])
def test_a_revolution_at_the_mid_sheet_threshold_angle(factor: float) -> None:
    # profile 10 x 4 at x in [40, 50]: Rmax = 2 at x = 42..48; threshold 2 asin(Rmax / x)
    # is smallest at x = 48 (the branch's far end): angles around it must all work
    theta = 2.0 * math.asin(2.0 / 48.0) * factor
    solid = (
        cq.Workplane("XY")
        .moveTo(45, 0)
        .rect(10, 4)
        .revolve(math.degrees(theta), (0, 0, 0), (0, 1, 0))
        .val()
    )
    reading = recognize(solid)
    rev = reading if reading.kind == "revolution" else reading.alternative
    assert rev is not None
    mat = medial_axis_of(rev, None, {})
    snd, cmp_ = _check(solid, mat)
    assert max(snd, cmp_) <= mat.tol
