"""Pictures of a 3D medial axis: the PNG (matplotlib) and the HTML viewer (headless Chromium).

The Chromium tests need Debian's ``chromium`` (``apt-get install chromium``) and are
skipped without it. The page reports on its ``<html>`` element (``data-state``,
``data-renderer``, ``data-pixels``, ``data-error``), read back with ``--dump-dom``.
"""

from __future__ import annotations

import json
import re
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

cq = pytest.importorskip("cadquery")

from medialcad.api import medial_axis  # noqa: E402
from medialcad.plot3d import render_png, tessellate  # noqa: E402
from medialcad.viewer import write_html  # noqa: E402
from tests._browser import Attrs, console_errors, dump_dom, needs_chromium  # noqa: E402

L_PROFILE = [(0.0, 0.0), (4.0, 0.0), (4.0, 1.0), (1.0, 1.0), (1.0, 3.0), (0.0, 3.0)]
L_HEIGHT = 2.0
BOX = (4.0, 2.0, 1.0)


@pytest.fixture(scope="module")
def box_mat() -> Any:
    return medial_axis(cq.Workplane().box(*BOX))


@pytest.fixture(scope="module")
def l_mat() -> Any:
    return medial_axis(cq.Workplane().polyline(L_PROFILE).close().extrude(L_HEIGHT))


@pytest.fixture(scope="module")
def tube_mat() -> Any:
    """No junction, curved sheets."""
    return medial_axis(cq.Workplane().circle(2.0).circle(1.0).extrude(3.0))


FIXTURES = {"box": "box_mat", "L": "l_mat", "tube": "tube_mat"}


@pytest.fixture(params=["box", "L"])
def mat(request: pytest.FixtureRequest) -> Any:
    return request.getfixturevalue("box_mat" if request.param == "box" else "l_mat")


# --------------------------------------------------------------------------- oracles
def _box_distance(p: np.ndarray) -> np.ndarray:
    half = np.array(BOX) / 2.0
    return np.min(half - np.abs(p), axis=1)


def _l_distance(p: np.ndarray) -> np.ndarray:
    """Distance from points inside the L extrusion to its boundary."""
    poly = np.array(L_PROFILE)
    a, b = poly, np.roll(poly, -1, axis=0)
    q = p[:, None, :2]
    d = b - a
    t = np.clip(((q - a) * d).sum(axis=2) / (d * d).sum(axis=1), 0.0, 1.0)
    side = np.linalg.norm(q - (a + t[..., None] * d), axis=2).min(axis=1)
    return np.minimum(side, np.minimum(p[:, 2], L_HEIGHT - p[:, 2]))


def _distance(name: str, p: np.ndarray) -> np.ndarray:
    return _box_distance(p) if name == "box" else _l_distance(p)


@pytest.mark.parametrize("name", ["box", "L"])
def test_scene_radius_is_the_distance_to_the_boundary(name: str, request: pytest.FixtureRequest):
    """Every sheet vertex, curve point and junction carries the radius of the maximal
    ball there: its distance to the solid's boundary (exact for these polyhedra)."""
    result = request.getfixturevalue("box_mat" if name == "box" else "l_mat")
    scene = tessellate(result)
    tol = 1e-6 * scene.diag
    s = scene.sheets
    assert len(s.triangles) > 0 and len(s.names) == len(result.sheets)
    assert s.starts[0] == 0 and s.starts[-1] == len(s.points)
    assert np.all(np.diff(s.starts) > 0)
    assert np.all(np.isfinite(s.radius)) and np.all(np.isfinite(s.tri_radius))
    np.testing.assert_allclose(s.radius, _distance(name, s.points), atol=tol)
    for kind in ("seam", "skeletal", "rim"):
        c = scene.curves[kind]
        for pts, rad in zip(c.points, c.radius, strict=True):
            np.testing.assert_allclose(rad, _distance(name, pts), atol=tol)
    np.testing.assert_allclose(
        scene.junction_radius, _distance(name, scene.junction_points), atol=tol
    )
    assert len(scene.curves["seam"].names) == len(result.seams)
    assert len(scene.curves["rim"].names) == len(result.rims)
    assert len(scene.solid.triangles) >= 12
    # the triangle colour is the radius at its (u, v) centroid: near its corners'
    r = s.radius[s.triangles]
    spread = r.max(axis=1) - r.min(axis=1) + tol
    assert np.all(s.tri_radius >= r.min(axis=1) - spread)
    assert np.all(s.tri_radius <= r.max(axis=1) + spread)
    assert np.all((s.tri_radius >= -tol) & (s.tri_radius <= result.rmax + tol))


def test_tessellate_keeps_to_its_budget(l_mat: Any):
    scene = tessellate(l_mat, max_triangles=300)
    assert scene.decimated
    assert len(scene.solid.triangles) + len(scene.sheets.triangles) <= 300


def test_tessellate_draws_the_solid_it_is_given(l_mat: Any):
    scene = tessellate(l_mat, solid=cq.Workplane().box(1.0, 1.0, 1.0))
    assert len(scene.solid.triangles) == 12
    assert len(scene.curves["solid_edge"].names) == 12


def test_tessellate_leaves_the_input_unmeshed(l_mat: Any):
    from OCP.BRep import BRep_Tool
    from OCP.TopLoc import TopLoc_Location

    from medialcad.occ.shapes import faces

    tessellate(l_mat)
    for f in faces(l_mat.recognition.solid) + [s.face for s in l_mat.sheets]:
        assert BRep_Tool.Triangulation_s(f, TopLoc_Location()) is None


# --------------------------------------------------------------------------- PNG
def test_png_is_a_picture(mat: Any, tmp_path: Path):
    out = tmp_path / "mat.png"
    t0 = time.perf_counter()
    render_png(mat, out)
    assert time.perf_counter() - t0 < 30
    assert out.stat().st_size > 30_000
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mat.png"]  # no temp file left
    import matplotlib.image as mpimg

    img = mpimg.imread(out)
    assert img.ndim == 3 and img.shape[0] > 400 and img.shape[1] > 800
    rgb = img[..., :3]
    assert np.mean(np.all(rgb > 0.98, axis=2)) < 0.9  # not blank
    colours = np.unique((rgb.reshape(-1, 3) * 31).round().astype(int), axis=0)
    assert len(colours) > 100
    # the sheets' colour map reaches both ends of viridis (radius 0 at the rims, rmax)
    purple = np.all(np.abs(rgb - [0.27, 0.0, 0.33]) < 0.08, axis=2)
    assert purple.sum() > 50


def test_png_failure_leaves_the_old_file(l_mat: Any, tmp_path: Path, monkeypatch: Any):
    import matplotlib.figure

    out = tmp_path / "mat.png"
    out.write_bytes(b"old")

    def broken(self: Any, fname: Any, **kw: Any) -> None:
        Path(fname).write_bytes(b"partial")
        raise RuntimeError("disk full")

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", broken)
    with pytest.raises(RuntimeError):
        render_png(l_mat, out)
    assert out.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["mat.png"]


# --------------------------------------------------------------------------- HTML
def _scene_json(page: str) -> dict[str, Any]:
    m = re.search(r'<script id="scene" type="application/json">(.*?)</script>', page, re.S)
    assert m is not None
    return dict(json.loads(m.group(1)))


def test_html_is_self_contained(mat: Any, tmp_path: Path):
    out = tmp_path / "mat.html"
    write_html(mat, out)
    page = out.read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>")
    assert "<script src" not in page and "<link" not in page
    assert not re.search(r"https?://", page)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mat.html"]
    data = _scene_json(page)
    assert data["counts"]["sheets"] == len(mat.sheets)
    assert len(data["sheets"]["names"]) == len(mat.sheets)
    assert len(data["junctions"]["names"]) == len(mat.junctions)
    assert data["rmax"] == pytest.approx(mat.rmax)
    import base64

    p = np.frombuffer(base64.b64decode(data["sheets"]["p"]), dtype="<f4")
    t = np.frombuffer(base64.b64decode(data["sheets"]["t"]), dtype="<u4")
    r = np.frombuffer(base64.b64decode(data["sheets"]["r"]), dtype="<f4")
    assert len(p) == 3 * len(r) and len(t) % 3 == 0 and t.max() < len(r)


# --------------------------------------------------------------------------- Chromium
@needs_chromium
@pytest.mark.parametrize(
    ("name", "fragment"), [("box", ""), ("L", ""), ("L", "#2d"), ("tube", ""), ("tube", "#2d")]
)
def test_html_draws_in_chromium(name: str, fragment: str, request, tmp_path: Path):
    result = request.getfixturevalue(FIXTURES[name])
    out = tmp_path / "mat.html"
    write_html(result, out)
    dom, log = dump_dom(out, fragment)
    p = Attrs()
    p.feed(dom)
    assert p.html.get("data-state") == "ok", p.html.get("data-error")
    assert not console_errors(log), console_errors(log)
    renderer = p.html.get("data-renderer")
    # WebGL where the browser has it (swiftshader), the 2D canvas otherwise or on request
    assert renderer == "canvas2d" if fragment == "#2d" else renderer in ("webgl", "canvas2d")
    assert int(p.html.get("data-pixels", "0")) > 20_000  # of 1000 x 700


HARNESS = """
<script>
(function () {
  var h = document.documentElement, V = window.medialViewer;
  var D = JSON.parse(document.getElementById("scene").textContent);
  var bin = atob(D.junctions.p), u = new Uint8Array(bin.length);
  for (var i = 0; i < bin.length; i++) u[i] = bin.charCodeAt(i);
  var j = new Float32Array(u.buffer);
  var xy = V.project(j[0], j[1], j[2]);
  var canvas = document.querySelector("canvas#view");
  canvas.dispatchEvent(new PointerEvent("pointermove",
    { clientX: xy[0] + 1, clientY: xy[1] + 1, bubbles: true }));
  h.setAttribute("data-tip", document.getElementById("tip").textContent);
  var boxes = document.querySelectorAll("#toggles input");
  boxes.forEach(function (b) { if (b.checked) { b.checked = false; b.dispatchEvent(new Event("change")); } });
  h.setAttribute("data-empty-pixels", String(V.render()));
  document.getElementById("show-sheets").click();
  h.setAttribute("data-sheet-pixels", String(V.render()));
  // rotate, pan and zoom: the camera moves and the page keeps drawing
  var yaw = V.camera.yaw, dist = V.camera.dist;
  function ev(type, x, y, extra) {
    var o = { clientX: x, clientY: y, bubbles: true, pointerId: 1, button: 0 };
    for (var k in extra || {}) o[k] = extra[k];
    canvas.dispatchEvent(new PointerEvent(type, o));
  }
  ev("pointerdown", 500, 350); ev("pointermove", 560, 380); ev("pointerup", 560, 380);
  ev("pointerdown", 500, 350, { shiftKey: true }); ev("pointermove", 520, 360, { shiftKey: true });
  ev("pointerup", 520, 360);
  canvas.dispatchEvent(new WheelEvent("wheel", { deltaY: 200, bubbles: true, cancelable: true }));
  h.setAttribute("data-moved", String(V.camera.yaw !== yaw && V.camera.dist > dist));
  h.setAttribute("data-moved-pixels", String(V.render()));
})();
</script>
"""


@needs_chromium
@pytest.mark.parametrize("fragment", ["", "#2d"])
def test_html_hover_and_toggles(l_mat: Any, fragment: str, tmp_path: Path):
    out = tmp_path / "mat.html"
    write_html(l_mat, out)
    page = out.read_text(encoding="utf-8")
    out.write_text(page.replace("</body>", HARNESS + "</body>"), encoding="utf-8")
    dom, log = dump_dom(out, fragment)
    p = Attrs()
    p.feed(dom)
    assert p.html.get("data-state") == "ok", p.html.get("data-error")
    assert not console_errors(log)
    j = l_mat.junctions[0]
    tip = p.html.get("data-tip", "")
    assert j.name in tip and "junction" in tip
    shown = float(re.search(r"radius ([0-9.eE+-]+)", tip).group(1))  # type: ignore[union-attr]
    assert shown == pytest.approx(j.radius, rel=1e-4)
    assert int(p.html["data-empty-pixels"]) == 0  # every layer off: background only
    assert int(p.html["data-sheet-pixels"]) > 10_000
    assert p.html.get("data-moved") == "true"
    assert int(p.html["data-moved-pixels"]) > 5_000


# --------------------------------------------------------------------------- size
@pytest.mark.slow
def test_png_of_a_large_complex_is_quick(tmp_path: Path):
    """~800 sheets: meshing, refinement and drawing stay within seconds."""
    n = 60
    ang = np.linspace(0, 2 * np.pi, 2 * n, endpoint=False)
    rad = np.where(np.arange(2 * n) % 2 == 0, 10.0, 8.5)
    pts = [(float(r * np.cos(a)), float(r * np.sin(a))) for r, a in zip(rad, ang, strict=True)]
    result = medial_axis(cq.Workplane().polyline(pts).close().extrude(3))
    assert len(result.sheets) > 500
    t0 = time.perf_counter()
    render_png(result, tmp_path / "big.png")
    t1 = time.perf_counter()
    write_html(result, tmp_path / "big.html")
    t2 = time.perf_counter()
    assert t1 - t0 < 20 and t2 - t1 < 20, (t1 - t0, t2 - t1)
