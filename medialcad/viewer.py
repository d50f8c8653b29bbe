"""A self-contained HTML viewer of a 3D medial axis (no network, no external script).

The page holds the tessellated scene (:func:`medialcad.plot3d.tessellate`) as JSON with
base64 ``float32``/``uint32`` arrays, and a small WebGL renderer written here; where WebGL
is unavailable (or with ``#2d`` after the file's URL) it draws with a 2D canvas instead.

Mouse: drag to rotate, shift-drag or right-drag to pan, wheel to zoom, double-click to
reset; hovering shows the entity and radius at the nearest vertex, a click pins it.

When the first frame is drawn the page records on its ``<html>`` element
``data-state="ok"``, ``data-renderer`` (``webgl`` or ``canvas2d``) and ``data-pixels``
(pixels that differ from the background); a script error sets ``data-state="error"`` and
``data-error``. Tests read these with a headless browser (``--dump-dom``).
"""

from __future__ import annotations

import base64
import html
import json
import os
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

if TYPE_CHECKING:
    from medialcad.mat3d.result import MedialAxis3D
    from medialcad.plot3d import Mesh, Polylines, Scene

__all__ = ["HTML_MAX_TRIANGLES", "scene_data", "write_html"]

HTML_MAX_TRIANGLES = 150_000
"""Triangle budget of the page (solid + sheets)."""


def _b64(a: ArrayLike, dtype: str) -> str:
    return base64.b64encode(np.ascontiguousarray(np.asarray(a), dtype=dtype).tobytes()).decode(
        "ascii"
    )


def _mesh_json(m: Mesh, *, radius: bool) -> dict[str, Any]:
    out: dict[str, Any] = {
        "p": _b64(m.points, "<f4"),
        "t": _b64(m.triangles, "<u4"),
        "names": list(m.names),
        "starts": [int(x) for x in m.starts],
    }
    if radius:
        out["r"] = _b64(m.radius, "<f4")
    return out


def _lines_json(c: Polylines) -> dict[str, Any]:
    pts = np.vstack(c.points) if c.points else np.zeros((0, 3))
    rad = np.concatenate(c.radius) if c.radius else np.zeros(0)
    starts = np.concatenate([[0], np.cumsum([len(p) for p in c.points])]).astype(int)
    return {
        "p": _b64(pts, "<f4"),
        "r": _b64(rad, "<f4"),
        "names": list(c.names),
        "starts": [int(x) for x in starts],
    }


def _colormap(n: int = 64) -> list[list[float]]:
    from matplotlib import colormaps

    rgba = colormaps["viridis"](np.linspace(0.0, 1.0, n))
    return [[round(float(x), 4) for x in row[:3]] for row in rgba]


def scene_data(scene: Scene) -> dict[str, Any]:
    """The JSON the page embeds."""
    every = [scene.solid.points, scene.sheets.points, scene.junction_points]
    every += [p for c in scene.curves.values() for p in c.points]
    every = [p for p in every if len(p)]
    if every:
        allp = np.vstack(every)
        lo, hi = allp.min(axis=0), allp.max(axis=0)
    else:
        lo = hi = np.zeros(3)
    return {
        "kind": scene.kind,
        "rmax": scene.rmax,
        "counts": scene.counts,
        "decimated": scene.decimated,
        "center": [float(x) for x in 0.5 * (lo + hi)],
        "size": max(float(np.linalg.norm(hi - lo)), 1e-9),
        "colormap": _colormap(),
        "solid": _mesh_json(scene.solid, radius=False),
        "sheets": _mesh_json(scene.sheets, radius=True),
        "curves": {k: _lines_json(v) for k, v in scene.curves.items()},
        "junctions": {
            "p": _b64(scene.junction_points, "<f4"),
            "r": _b64(scene.junction_radius, "<f4"),
            "names": list(scene.junction_names),
            "starts": list(range(len(scene.junction_names) + 1)),
        },
    }


def write_html(
    result: MedialAxis3D,
    path: str | os.PathLike[str],
    *,
    solid: Any = None,
    scene: Scene | None = None,
) -> None:
    """Write a self-contained interactive viewer of ``result`` (atomically).

    Args:
        result: a :class:`~medialcad.mat3d.result.MedialAxis3D`.
        path: the HTML file to write (a failed call leaves nothing behind).
        solid: the solid to show (default ``result.recognition.solid``).
        scene: a ready :func:`~medialcad.plot3d.tessellate` (default: computed with a
            budget of :data:`HTML_MAX_TRIANGLES`).
    """
    from medialcad.occ.io import atomic_text
    from medialcad.plot3d import tessellate

    if scene is None:
        scene = tessellate(result, solid=solid, max_triangles=HTML_MAX_TRIANGLES)
    data = json.dumps(scene_data(scene), separators=(",", ":"), allow_nan=False)
    # inside <script>: no "</script>" nor "<!--" can appear
    data = data.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
    c = scene.counts
    title = (
        f"medialcad: {scene.kind}, {c.get('sheets', 0)} sheets, {c.get('seams', 0)} seams, "
        f"{c.get('junctions', 0)} junctions"
    )
    page = (
        _PAGE.replace("@TITLE@", html.escape(title))
        .replace("@CSS@", _CSS)
        .replace("@JS@", _JS)
        .replace("@DATA@", data)
    )
    atomic_text(path, page)


_CSS = """
html, body { margin: 0; height: 100%; overflow: hidden; font: 13px/1.35 system-ui, sans-serif;
  background: #fff; color: #222; }
#view { position: absolute; inset: 0; width: 100%; height: 100%; display: block;
  cursor: grab; touch-action: none; }
#panel { position: absolute; top: 8px; left: 8px; background: rgba(255,255,255,.88);
  border: 1px solid #ccc; border-radius: 6px; padding: 8px 10px; max-width: 300px; }
#panel h1 { font-size: 14px; margin: 0 0 4px; }
#panel label { display: block; white-space: nowrap; }
#panel .sw { display: inline-block; width: 10px; height: 10px; margin: 0 4px 0 2px;
  border-radius: 2px; vertical-align: -1px; }
#legend { margin-top: 6px; }
#legend canvas { width: 180px; height: 10px; display: block; border: 1px solid #999; }
#legend .ticks { display: flex; justify-content: space-between; width: 182px; font-size: 11px; }
#info { margin-top: 6px; font-size: 12px; white-space: pre; min-height: 3.9em; }
#help { margin-top: 4px; font-size: 11px; color: #666; }
#tip { position: absolute; pointer-events: none; background: rgba(20,20,20,.85); color: #fff;
  padding: 3px 6px; border-radius: 4px; font-size: 12px; white-space: pre; display: none; }
"""

_PAGE = """<!DOCTYPE html>
<html lang="en" data-state="loading">
<head>
<meta charset="utf-8">
<title>@TITLE@</title>
<script>
(function () {
  function fail(msg) {
    var h = document.documentElement;
    h.setAttribute("data-state", "error");
    var old = h.getAttribute("data-error");
    h.setAttribute("data-error", (old ? old + " | " : "") + String(msg));
  }
  window.__fail = fail;
  window.addEventListener("error", function (e) {
    fail((e.message || "error") + " at " + (e.lineno || "?") + ":" + (e.colno || "?"));
  });
  window.addEventListener("unhandledrejection", function (e) { fail("rejection: " + e.reason); });
  var ce = console.error;
  console.error = function () {
    fail("console.error: " + Array.prototype.join.call(arguments, " "));
    return ce.apply(console, arguments);
  };
})();
</script>
<style>@CSS@</style>
</head>
<body>
<canvas id="view"></canvas>
<div id="panel">
  <h1>@TITLE@</h1>
  <div id="toggles"></div>
  <div id="legend"><canvas id="ramp" width="180" height="1"></canvas>
    <div class="ticks"><span>0</span><span>radius</span><span id="rmax"></span></div></div>
  <div id="info"></div>
  <div id="help">drag: rotate &middot; shift/right-drag: pan &middot; wheel: zoom<br>
    double-click: reset &middot; click: pin the value</div>
</div>
<div id="tip"></div>
<script id="scene" type="application/json">@DATA@</script>
<script>@JS@</script>
</body>
</html>
"""

_JS = r"""
"use strict";
(function () {
const D = JSON.parse(document.getElementById("scene").textContent);
const BG = [1, 1, 1];

function b64(s, T) {
  if (!s) return new T(0);
  const bin = atob(s), u = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) u[i] = bin.charCodeAt(i);
  return new T(u.buffer);
}
function group(g, withTris) {
  return {
    p: b64(g.p, Float32Array), t: withTris ? b64(g.t, Uint32Array) : null,
    r: g.r ? b64(g.r, Float32Array) : null, names: g.names, starts: g.starts,
  };
}
const solid = group(D.solid, true), sheets = group(D.sheets, true);
const curves = {};
for (const k of Object.keys(D.curves)) curves[k] = group(D.curves[k], false);
const junctions = group(D.junctions, false);
const RMAX = D.rmax > 0 ? D.rmax : 1;
const CMAP = D.colormap;

// -- layers -------------------------------------------------------------------------
const LAYERS = [
  { key: "solid", label: "solid", on: true, colour: [0.62, 0.64, 0.7], alpha: 0.14 },
  { key: "solid_edge", label: "solid edges", on: true, colour: [0.5, 0.5, 0.5], alpha: 1 },
  { key: "sheets", label: "sheets (radius)", on: true, colour: null, alpha: 1 },
  { key: "seam", label: "seams", on: true, colour: [0.08, 0.08, 0.08], alpha: 1 },
  { key: "skeletal", label: "skeletal edges", on: true, colour: [0.55, 0.05, 0.05], alpha: 1 },
  { key: "rim", label: "rims", on: false, colour: [0.2, 0.35, 0.75], alpha: 1 },
  { key: "junctions", label: "junctions", on: true, colour: [0.86, 0.08, 0.24], alpha: 1 },
];
const L = {};
for (const l of LAYERS) L[l.key] = l;
function count(key) {
  if (key === "solid") return solid.names.length;
  if (key === "sheets") return sheets.names.length;
  if (key === "junctions") return junctions.names.length;
  return curves[key] ? curves[key].names.length : 0;
}
function rgbCss(c) { return "rgb(" + c.map(function (x) { return Math.round(255 * x); }).join(",") + ")"; }
const toggles = document.getElementById("toggles");
for (const l of LAYERS) {
  const n = count(l.key);
  const lab = document.createElement("label");
  const box = document.createElement("input");
  box.type = "checkbox"; box.checked = l.on && n > 0; box.disabled = n === 0; box.id = "show-" + l.key;
  l.on = box.checked;
  box.addEventListener("change", function () { l.on = box.checked; redraw(); });
  const sw = document.createElement("span");
  sw.className = "sw";
  sw.style.background = l.colour ? rgbCss(l.colour) : "linear-gradient(90deg," + rgbCss(CMAP[0]) + "," + rgbCss(CMAP[CMAP.length >> 1]) + "," + rgbCss(CMAP[CMAP.length - 1]) + ")";
  lab.appendChild(box); lab.appendChild(sw);
  lab.appendChild(document.createTextNode(l.label + " (" + n + ")"));
  toggles.appendChild(lab);
}
(function () {
  const c = document.getElementById("ramp"), g = c.getContext("2d");
  for (let i = 0; i < c.width; i++) {
    g.fillStyle = rgbCss(cmap(i / (c.width - 1))); g.fillRect(i, 0, 1, 1);
  }
  document.getElementById("rmax").textContent = fmt(RMAX);
})();
function cmap(x) {
  x = Math.min(1, Math.max(0, x)) * (CMAP.length - 1);
  const i = Math.min(CMAP.length - 2, Math.floor(x)), f = x - i, a = CMAP[i], b = CMAP[i + 1];
  return [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])];
}
function fmt(x) { return isFinite(x) ? Number(x).toPrecision(5) : "n/a"; }

// -- camera (z up) ------------------------------------------------------------------
const C0 = D.center, SIZE = D.size;
const cam = {};
function resetCamera() {
  cam.yaw = -2.2; cam.pitch = 0.5; cam.dist = 1.9 * SIZE; cam.target = C0.slice();
}
resetCamera();
function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function norm(a) { const n = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / n, a[1] / n, a[2] / n]; }
function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function basis() {
  const cp = Math.cos(cam.pitch), sp = Math.sin(cam.pitch);
  const back = [cp * Math.cos(cam.yaw), cp * Math.sin(cam.yaw), sp];
  const eye = [cam.target[0] + cam.dist * back[0], cam.target[1] + cam.dist * back[1], cam.target[2] + cam.dist * back[2]];
  const zc = back, xc = norm(cross([0, 0, 1], zc)), yc = cross(zc, xc);
  return { eye: eye, x: xc, y: yc, z: zc };
}
// column-major 4x4
function matrices(aspect) {
  const b = basis();
  const view = [
    b.x[0], b.y[0], b.z[0], 0, b.x[1], b.y[1], b.z[1], 0, b.x[2], b.y[2], b.z[2], 0,
    -dot(b.x, b.eye), -dot(b.y, b.eye), -dot(b.z, b.eye), 1];
  const near = Math.max(cam.dist - SIZE, cam.dist * 0.02), far = cam.dist + 1.5 * SIZE;
  const f = 1 / Math.tan(0.5 * 0.6);
  const proj = [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1,
    0, 0, 2 * far * near / (near - far), 0];
  const mvp = new Array(16);
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) {
    let s = 0;
    for (let k = 0; k < 4; k++) s += proj[k * 4 + r] * view[c * 4 + k];
    mvp[c * 4 + r] = s;
  }
  return { view: view, proj: proj, mvp: mvp };
}
// model points -> screen pixels (x, y) and view depth; behind the eye: depth <= 0
function project(P, mvp, W, H, out) {
  const n = P.length / 3;
  for (let i = 0; i < n; i++) {
    const x = P[3 * i], y = P[3 * i + 1], z = P[3 * i + 2];
    const cx = mvp[0] * x + mvp[4] * y + mvp[8] * z + mvp[12];
    const cy = mvp[1] * x + mvp[5] * y + mvp[9] * z + mvp[13];
    const cz = mvp[2] * x + mvp[6] * y + mvp[10] * z + mvp[14];
    const cw = mvp[3] * x + mvp[7] * y + mvp[11] * z + mvp[15];
    out[3 * i] = (cx / cw + 1) * 0.5 * W;
    out[3 * i + 1] = (1 - cy / cw) * 0.5 * H;
    out[3 * i + 2] = cw;
    void cz;
  }
  return out;
}

// -- flat-shaded triangle soup ------------------------------------------------------
function soup(m) {
  const t = m.t, p = m.p, n = t.length;
  const P = new Float32Array(3 * n), N = new Float32Array(3 * n), V = new Float32Array(n);
  for (let i = 0; i < n; i += 3) {
    const a = 3 * t[i], b = 3 * t[i + 1], c = 3 * t[i + 2];
    const u = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
    const v = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
    const nn = norm(cross(u, v));
    for (let k = 0; k < 3; k++) {
      const s = 3 * t[i + k], o = 3 * (i + k);
      P[o] = p[s]; P[o + 1] = p[s + 1]; P[o + 2] = p[s + 2];
      N[o] = nn[0]; N[o + 1] = nn[1]; N[o + 2] = nn[2];
      const r = m.r ? m.r[t[i + k]] : -1;
      V[i + k] = isFinite(r) ? r : -1;
    }
  }
  return { P: P, N: N, V: V, n: n };
}
function segs(g) {
  const out = [];
  for (let e = 0; e + 1 < g.starts.length; e++)
    for (let i = g.starts[e]; i + 1 < g.starts[e + 1]; i++) out.push(i, i + 1);
  return out;
}

// -- picking (nearest projected vertex) ---------------------------------------------
function entityOf(g, i) {
  let lo = 0, hi = g.starts.length - 2;
  while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (g.starts[mid] <= i) lo = mid; else hi = mid - 1; }
  return g.names[lo];
}
function pickables() {
  const out = [];
  if (L.sheets.on) out.push(["sheet", sheets]);
  for (const k of ["seam", "skeletal", "rim"]) if (L[k] && L[k].on && curves[k]) out.push([k === "skeletal" ? "skeletal edge" : k, curves[k]]);
  if (L.junctions.on) out.push(["junction", junctions]);
  return out;
}
let scratch = new Float32Array(0);
function pick(mx, my, W, H, mvp) {
  let best = null, bestScore = 12;
  for (const [kind, g] of pickables()) {
    const n = g.p.length / 3;
    if (scratch.length < 3 * n) scratch = new Float32Array(3 * n);
    project(g.p, mvp, W, H, scratch);
    const bias = kind === "sheet" ? 3 : kind === "junction" ? 0 : 1;  // junctions, then curves win ties
    for (let i = 0; i < n; i++) {
      if (scratch[3 * i + 2] <= 0) continue;
      const d = Math.hypot(scratch[3 * i] - mx, scratch[3 * i + 1] - my) + bias;
      if (d < bestScore || (best && Math.abs(d - bestScore) < 1 && scratch[3 * i + 2] < best.depth)) {
        bestScore = d;
        best = { kind: kind, name: entityOf(g, i), r: g.r ? g.r[i] : NaN, depth: scratch[3 * i + 2],
          x: g.p[3 * i], y: g.p[3 * i + 1], z: g.p[3 * i + 2] };
      }
    }
  }
  return best;
}
function describe(h) {
  return h.name + " (" + h.kind + ")\nradius " + fmt(h.r) + "\nat (" + fmt(h.x) + ", " + fmt(h.y) + ", " + fmt(h.z) + ")";
}

// -- WebGL renderer -----------------------------------------------------------------
const canvas = document.getElementById("view");
function makeGL() {
  if (/(^|[#&])2d\b/.test(location.hash)) return null;
  let gl = null;
  try {
    const opts = { antialias: true, preserveDrawingBuffer: true, alpha: false };
    gl = canvas.getContext("webgl", opts) || canvas.getContext("experimental-webgl", opts);
  } catch (e) { gl = null; }
  return gl;
}
function glRenderer(gl) {
  function shader(type, src) {
    const s = gl.createShader(type);
    gl.shaderSource(s, src); gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error("shader: " + gl.getShaderInfoLog(s));
    return s;
  }
  function program(vs, fs) {
    const p = gl.createProgram();
    gl.attachShader(p, shader(gl.VERTEX_SHADER, vs));
    gl.attachShader(p, shader(gl.FRAGMENT_SHADER, fs));
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error("link: " + gl.getProgramInfoLog(p));
    const loc = {};
    const na = gl.getProgramParameter(p, gl.ACTIVE_ATTRIBUTES), nu = gl.getProgramParameter(p, gl.ACTIVE_UNIFORMS);
    for (let i = 0; i < na; i++) { const a = gl.getActiveAttrib(p, i).name; loc[a] = gl.getAttribLocation(p, a); }
    for (let i = 0; i < nu; i++) { const u = gl.getActiveUniform(p, i).name; loc[u] = gl.getUniformLocation(p, u); }
    return { p: p, loc: loc };
  }
  const tri = program(
    "attribute vec3 aPos; attribute vec3 aNrm; attribute float aVal;" +
    "uniform mat4 uMVP; uniform mat4 uView; varying float vVal; varying float vShade;" +
    "void main() { gl_Position = uMVP * vec4(aPos, 1.0);" +
    " vec3 n = normalize((uView * vec4(aNrm, 0.0)).xyz); vShade = 0.5 + 0.5 * abs(n.z); vVal = aVal; }",
    "precision mediump float; uniform sampler2D uMap; uniform float uRmax; uniform vec4 uColor;" +
    " uniform float uUseMap; varying float vVal; varying float vShade;" +
    "void main() { vec3 c = uColor.rgb;" +
    " if (uUseMap > 0.5) { c = vVal < 0.0 ? vec3(0.7) : texture2D(uMap, vec2(clamp(vVal / uRmax, 0.0, 1.0) * 0.984375 + 0.0078125, 0.5)).rgb; }" +
    " gl_FragColor = vec4(c * vShade, uColor.a); }");
  const line = program(
    "attribute vec3 aPos; uniform mat4 uMVP; uniform float uSize;" +
    "void main() { gl_Position = uMVP * vec4(aPos, 1.0); gl_PointSize = uSize; }",
    "precision mediump float; uniform vec4 uColor; uniform float uRound;" +
    "void main() { if (uRound > 0.5 && length(gl_PointCoord - vec2(0.5)) > 0.5) discard; gl_FragColor = uColor; }");
  const tex = gl.createTexture();
  const px = new Uint8Array(4 * 64);
  for (let i = 0; i < 64; i++) {
    const c = cmap(i / 63);
    px[4 * i] = Math.round(255 * c[0]); px[4 * i + 1] = Math.round(255 * c[1]); px[4 * i + 2] = Math.round(255 * c[2]); px[4 * i + 3] = 255;
  }
  gl.bindTexture(gl.TEXTURE_2D, tex);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, 64, 1, 0, gl.RGBA, gl.UNSIGNED_BYTE, px);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  function buffer(data) {
    const b = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW); return b;
  }
  function triBuffers(m) {
    const s = soup(m);
    return { P: buffer(s.P), N: buffer(s.N), V: buffer(s.V), n: s.n };
  }
  function lineBuffers(g) {
    const idx = segs(g), P = new Float32Array(3 * idx.length);
    for (let i = 0; i < idx.length; i++) for (let k = 0; k < 3; k++) P[3 * i + k] = g.p[3 * idx[i] + k];
    return { P: buffer(P), n: idx.length };
  }
  const B = { solid: triBuffers(solid), sheets: triBuffers(sheets), junctions: { P: buffer(junctions.p), n: junctions.p.length / 3 } };
  for (const k of Object.keys(curves)) B[k] = lineBuffers(curves[k]);
  function attrib(loc, buf, size) {
    if (loc === undefined || loc < 0) return;
    gl.bindBuffer(gl.ARRAY_BUFFER, buf); gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, 0);
  }
  function drawTris(b, M, layer, useMap) {
    if (!b.n) return;
    gl.useProgram(tri.p);
    gl.uniformMatrix4fv(tri.loc.uMVP, false, M.mvp);
    gl.uniformMatrix4fv(tri.loc.uView, false, M.view);
    gl.uniform1f(tri.loc.uRmax, RMAX);
    gl.uniform1f(tri.loc.uUseMap, useMap ? 1 : 0);
    const c = layer.colour || [0, 0, 0];
    gl.uniform4f(tri.loc.uColor, c[0], c[1], c[2], layer.alpha);
    gl.activeTexture(gl.TEXTURE0); gl.bindTexture(gl.TEXTURE_2D, tex); gl.uniform1i(tri.loc.uMap, 0);
    attrib(tri.loc.aPos, b.P, 3); attrib(tri.loc.aNrm, b.N, 3); attrib(tri.loc.aVal, b.V, 1);
    gl.drawArrays(gl.TRIANGLES, 0, b.n);
    for (const a of ["aPos", "aNrm", "aVal"]) if (tri.loc[a] >= 0) gl.disableVertexAttribArray(tri.loc[a]);
  }
  function drawPrims(b, M, layer, mode, size) {
    if (!b.n) return;
    gl.useProgram(line.p);
    gl.uniformMatrix4fv(line.loc.uMVP, false, M.mvp);
    gl.uniform1f(line.loc.uSize, size);
    gl.uniform1f(line.loc.uRound, mode === gl.POINTS ? 1 : 0);
    const c = layer.colour;
    gl.uniform4f(line.loc.uColor, c[0], c[1], c[2], layer.alpha);
    attrib(line.loc.aPos, b.P, 3);
    gl.drawArrays(mode, 0, b.n);
    gl.disableVertexAttribArray(line.loc.aPos);
  }
  return {
    name: "webgl",
    draw: function (W, H, M) {
      gl.viewport(0, 0, W, H);
      gl.clearColor(BG[0], BG[1], BG[2], 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.enable(gl.DEPTH_TEST); gl.depthFunc(gl.LEQUAL); gl.depthMask(true); gl.disable(gl.BLEND);
      if (L.sheets.on) {
        gl.enable(gl.POLYGON_OFFSET_FILL); gl.polygonOffset(1, 1);
        drawTris(B.sheets, M, L.sheets, true);
        gl.disable(gl.POLYGON_OFFSET_FILL);
      }
      for (const k of ["solid_edge", "rim", "seam", "skeletal"]) if (L[k].on && B[k]) drawPrims(B[k], M, L[k], gl.LINES, 1);
      const dpr = window.devicePixelRatio || 1;
      if (L.solid.on) {
        gl.enable(gl.BLEND); gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA); gl.depthMask(false);
        drawTris(B.solid, M, L.solid, false);
        gl.depthMask(true); gl.disable(gl.BLEND);
      }
      // hidden curves show faintly through the sheets; junctions are always on top
      gl.disable(gl.DEPTH_TEST); gl.enable(gl.BLEND); gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
      for (const k of ["seam", "skeletal"]) if (L[k].on && B[k]) drawPrims(B[k], M, { colour: L[k].colour, alpha: 0.3 }, gl.LINES, 1);
      if (L.junctions.on) drawPrims(B.junctions, M, L.junctions, gl.POINTS, 8 * dpr);
      gl.disable(gl.BLEND); gl.enable(gl.DEPTH_TEST);
    },
    pixels: function (W, H) {
      const buf = new Uint8Array(4 * W * H);
      gl.readPixels(0, 0, W, H, gl.RGBA, gl.UNSIGNED_BYTE, buf);
      return countPixels(buf);
    },
  };
}
function countPixels(buf) {
  let n = 0;
  const r = Math.round(255 * BG[0]), g = Math.round(255 * BG[1]), b = Math.round(255 * BG[2]);
  for (let i = 0; i < buf.length; i += 4) if (buf[i] !== r || buf[i + 1] !== g || buf[i + 2] !== b) n++;
  return n;
}

// -- 2D canvas renderer (painter's algorithm) ---------------------------------------
function canvasRenderer(ctx) {
  const S = { solid: soup(solid), sheets: soup(sheets) };
  let buf = new Float32Array(0);
  function tris(s, M, W, H, layer, useMap, items) {
    if (buf.length < s.P.length) buf = new Float32Array(s.P.length);
    project(s.P, M.mvp, W, H, buf);
    const v = M.view;
    for (let i = 0; i < s.n; i += 3) {
      const d0 = buf[3 * i + 2], d1 = buf[3 * i + 5], d2 = buf[3 * i + 8];
      if (d0 <= 0 || d1 <= 0 || d2 <= 0) continue;
      const nz = Math.abs(v[2] * s.N[3 * i] + v[6] * s.N[3 * i + 1] + v[10] * s.N[3 * i + 2]);
      const shade = 0.5 + 0.5 * nz;
      let c;
      if (useMap) {
        const r = (s.V[i] + s.V[i + 1] + s.V[i + 2]) / 3;
        c = s.V[i] < 0 ? [0.7, 0.7, 0.7] : cmap(r / RMAX);
      } else c = layer.colour;
      const col = "rgba(" + Math.round(255 * c[0] * shade) + "," + Math.round(255 * c[1] * shade) + "," + Math.round(255 * c[2] * shade) + "," + layer.alpha + ")";
      items.push([d0 + d1 + d2, buf[3 * i], buf[3 * i + 1], buf[3 * i + 3], buf[3 * i + 4], buf[3 * i + 6], buf[3 * i + 7], col]);
    }
  }
  return {
    name: "canvas2d",
    draw: function (W, H, M) {
      ctx.setTransform(1, 0, 0, 1, 0, 0);
      ctx.fillStyle = rgbCss(BG); ctx.fillRect(0, 0, W, H);
      const items = [];
      if (L.sheets.on) tris(S.sheets, M, W, H, L.sheets, true, items);
      if (L.solid.on) tris(S.solid, M, W, H, L.solid, false, items);
      items.sort(function (a, b) { return b[0] - a[0]; });
      for (const it of items) {
        ctx.beginPath(); ctx.moveTo(it[1], it[2]); ctx.lineTo(it[3], it[4]); ctx.lineTo(it[5], it[6]); ctx.closePath();
        ctx.fillStyle = it[7]; ctx.fill();
        if (it[7].endsWith(",1)")) { ctx.strokeStyle = it[7]; ctx.lineWidth = 0.5; ctx.stroke(); }
      }
      const dpr = window.devicePixelRatio || 1;
      for (const k of ["solid_edge", "rim", "seam", "skeletal"]) {
        const g = curves[k];
        if (!L[k].on || !g) continue;
        const q = project(g.p, M.mvp, W, H, new Float32Array(g.p.length));
        ctx.strokeStyle = rgbCss(L[k].colour); ctx.lineWidth = dpr; ctx.beginPath();
        for (let e = 0; e + 1 < g.starts.length; e++) {
          for (let i = g.starts[e]; i < g.starts[e + 1]; i++) {
            if (i === g.starts[e]) ctx.moveTo(q[3 * i], q[3 * i + 1]); else ctx.lineTo(q[3 * i], q[3 * i + 1]);
          }
        }
        ctx.stroke();
      }
      if (L.junctions.on) {
        const q = project(junctions.p, M.mvp, W, H, new Float32Array(junctions.p.length));
        ctx.fillStyle = rgbCss(L.junctions.colour);
        for (let i = 0; i < q.length / 3; i++) {
          if (q[3 * i + 2] <= 0) continue;
          ctx.beginPath(); ctx.arc(q[3 * i], q[3 * i + 1], 4 * dpr, 0, 2 * Math.PI); ctx.fill();
        }
      }
    },
    pixels: function (W, H) { return countPixels(ctx.getImageData(0, 0, W, H).data); },
  };
}

// -- main loop and interaction ------------------------------------------------------
let R = null, el = canvas;
let W = 0, H = 0, M = null, pending = false, hover = null, pinned = null;
const gl = makeGL();
if (gl) {
  try { R = glRenderer(gl); } catch (e) { console.warn("WebGL failed, using a 2D canvas: " + e.message); }
}
if (!R) {
  if (gl) {  // the canvas holds a WebGL context: swap in a fresh one
    el = canvas.cloneNode(false);
    canvas.parentNode.replaceChild(el, canvas);
  }
  R = canvasRenderer(el.getContext("2d"));
}
bind(el);

function size() {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(el.clientWidth * dpr)), h = Math.max(1, Math.round(el.clientHeight * dpr));
  if (w !== el.width || h !== el.height) { el.width = w; el.height = h; }
  W = w; H = h;
}
function render() {
  pending = false;
  size();
  M = matrices(W / H);
  R.draw(W, H, M);
}
function redraw() { if (!pending) { pending = true; requestAnimationFrame(render); } }
function showInfo() {
  const h = pinned || hover;
  document.getElementById("info").textContent = h ? (pinned ? "pinned: " : "") + describe(h) : "kind: " + D.kind + "\nrmax " + fmt(D.rmax) + (D.decimated ? "\n(mesh decimated)" : "");
}
function bind(c) {
  let drag = null;
  const tip = document.getElementById("tip");
  c.addEventListener("contextmenu", function (e) { e.preventDefault(); });
  c.addEventListener("pointerdown", function (e) {
    drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2, moved: false };
    try { c.setPointerCapture(e.pointerId); } catch (err) { /* synthetic pointer */ }
    c.style.cursor = "grabbing";
  });
  c.addEventListener("pointerup", function (e) {
    if (drag && !drag.moved) { pinned = hover ? Object.assign({}, hover) : null; showInfo(); }
    drag = null; c.style.cursor = "grab";
  });
  c.addEventListener("pointermove", function (e) {
    if (drag) {
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 2) drag.moved = true;
      drag.x = e.clientX; drag.y = e.clientY;
      if (drag.pan) {
        const b = basis(), s = 2 * cam.dist * Math.tan(0.3) / c.clientHeight;
        for (let k = 0; k < 3; k++) cam.target[k] += s * (-dx * b.x[k] + dy * b.y[k]);
      } else {
        cam.yaw -= 0.008 * dx;
        cam.pitch = Math.max(-1.55, Math.min(1.55, cam.pitch + 0.008 * dy));
      }
      tip.style.display = "none";
      redraw();
      return;
    }
    if (!M) return;
    const rect = c.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
    hover = pick((e.clientX - rect.left) * dpr, (e.clientY - rect.top) * dpr, W, H, M.mvp);
    if (hover) {
      tip.textContent = describe(hover); tip.style.display = "block";
      tip.style.left = (e.clientX + 14) + "px"; tip.style.top = (e.clientY + 12) + "px";
    } else tip.style.display = "none";
    showInfo();
  });
  c.addEventListener("pointerleave", function () { tip.style.display = "none"; hover = null; showInfo(); });
  c.addEventListener("wheel", function (e) {
    e.preventDefault();
    cam.dist *= Math.exp(0.0015 * Math.max(-300, Math.min(300, e.deltaY)));
    cam.dist = Math.max(0.02 * SIZE, Math.min(50 * SIZE, cam.dist));
    redraw();
  }, { passive: false });
  c.addEventListener("dblclick", function () { resetCamera(); redraw(); });
}
window.addEventListener("resize", redraw);
// hooks for scripts and tests (coordinates in CSS pixels of the canvas)
window.medialViewer = {
  camera: cam, layers: L, redraw: redraw,
  render: function () { render(); return R.pixels(W, H); },
  project: function (x, y, z) {
    const q = project(new Float32Array([x, y, z]), M.mvp, W, H, new Float32Array(3)), dpr = window.devicePixelRatio || 1;
    return [q[0] / dpr, q[1] / dpr];
  },
  pick: function (x, y) { const dpr = window.devicePixelRatio || 1; return M ? pick(x * dpr, y * dpr, W, H, M.mvp) : null; },
};

showInfo();
render();
const h = document.documentElement;
h.setAttribute("data-renderer", R.name);
h.setAttribute("data-pixels", String(R.pixels(W, H)));
if (h.getAttribute("data-state") !== "error") h.setAttribute("data-state", "ok");
})();
"""
