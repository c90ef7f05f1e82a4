// The simulation's page: the history of the part (SimHistory) and the program's text as data,
// and a script that draws the top view (or a lathe's half-section), the section, the part cut
// up to the slider's block, and a WebGL view of the height field. Nothing is loaded from the
// network.
#include "camgen/simulation/pictures.hpp"
#include "camgen/common/markup.hpp"

#include <cmath>
#include <cstring>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/common/number_text.hpp"

namespace camgen {

namespace {

// Little-endian bytes as base64 (the page's typed arrays).
std::string sim_base64(const std::vector<unsigned char>& bytes) {
    static constexpr char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t k = 0; k < bytes.size(); k += 3) {
        const std::uint32_t v = (static_cast<std::uint32_t>(bytes[k]) << 16) |
                                (k + 1 < bytes.size() ? static_cast<std::uint32_t>(bytes[k + 1]) << 8 : 0u) |
                                (k + 2 < bytes.size() ? static_cast<std::uint32_t>(bytes[k + 2]) : 0u);
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += k + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
        out += k + 2 < bytes.size() ? digits[v & 63] : '=';
    }
    return out;
}

template <typename T>
void sim_put(std::vector<unsigned char>& bytes, T value) {
    std::uint32_t bits;
    static_assert(sizeof(T) == 4);
    std::memcpy(&bits, &value, 4);
    for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<unsigned char>((bits >> (8 * k)) & 0xff));
}

std::string sim_floats(const std::vector<float>& values) {
    std::vector<unsigned char> bytes;
    bytes.reserve(values.size() * 4);
    for (float v : values) sim_put(bytes, v);
    return sim_base64(bytes);
}

constexpr const char* sim_style = R"CSS(
body{margin:0;font:14px/1.4 "DejaVu Sans",Arial,Helvetica,sans-serif;color:#222;background:#f4f4f4}
header{padding:8px 16px;background:#fff;border-bottom:1px solid #ccc}
h1{font-size:18px;margin:0}h2{font-size:14px;margin:12px 0 6px}
header p{margin:2px 0 0;color:#555;font-size:12px}
main{display:flex;flex-wrap:wrap;gap:12px;padding:12px}
#views{flex:1 1 660px;min-width:320px}
#views section,aside section{background:#fff;border:1px solid #ccc;padding:4px 12px 10px;margin-bottom:12px}
canvas{display:block;max-width:100%}
aside{flex:0 1 460px;min-width:300px}
.controls{display:flex;gap:6px;align-items:center}
.controls input[type=range]{flex:1}
pre{margin:0;font:12px/1.35 "DejaVu Sans Mono",monospace;white-space:pre-wrap;word-break:break-all}
#nc-before,#nc-after{color:#888}
#nc-current{background:#fff3b0;border-left:3px solid #e0a800;padding-left:4px}
#gl{cursor:grab;background:#fff}
.note{color:#666;font-size:12px}
[hidden]{display:none!important}
)CSS";

constexpr const char* sim_script = R"JS(
"use strict";
(function () {
  const data = JSON.parse(document.getElementById("camgen-sim").textContent);
  const ncText = JSON.parse(document.getElementById("camgen-nc").textContent);
  const $ = (id) => document.getElementById(id);
  const nc = ncText.split("\n");
  function bytes(b64) {
    const s = atob(b64), out = new Uint8Array(s.length);
    for (let i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
    return out.buffer;
  }
  const initial = new Float32Array(bytes(data.initial));
  const evCell = new Int32Array(bytes(data.cells)), evLine = new Int32Array(bytes(data.lines));
  const evValue = new Float32Array(bytes(data.values));
  const evValue2 = data.lathe ? new Float32Array(bytes(data.values2)) : null;
  const nx = data.nx, ny = data.ny, n = nx * ny;
  const state = new Float32Array(initial.length);
  // The part cut up to block b: each coarse cell at the lowest of its changes at lines <= b.
  function stateAt(b) {
    state.set(initial);
    for (let k = 0; k < evCell.length; ++k) {
      if (evLine[k] > b) continue;
      const c = evCell[k];
      if (evValue[k] < state[c]) state[c] = evValue[k];
      if (evValue2 && evValue2[k] > state[n + c]) state[n + c] = evValue2[k];
    }
  }
  function ramp(t) {
    t = Math.min(1, Math.max(0, t));
    const s = data.stops;
    for (let k = 1; k < s.length; ++k) {
      if (t <= s[k][0]) {
        const u = (t - s[k - 1][0]) / (s[k][0] - s[k - 1][0]);
        return [0, 1, 2].map((i) => Math.round(s[k - 1][1][i] + (s[k][1][i] - s[k - 1][1][i]) * u));
      }
    }
    return s[s.length - 1][1];
  }
  const thick = data.top - data.bottom;

  // ---- the top view (mill) or the half-section (lathe) ----
  const top = $("top"), tctx = top.getContext("2d");
  const image = document.createElement("canvas");
  image.width = nx; image.height = ny;
  const ictx = image.getContext("2d"), pixels = ictx.createImageData(nx, ny);
  let cutCells = 0;
  function drawTop() {
    tctx.fillStyle = "#fff";
    tctx.fillRect(0, 0, top.width, top.height);
    if (data.lathe) return drawLathe();
    const sc = top.width / (nx * data.cell);
    cutCells = 0;
    const at = (i, j) => state[Math.min(ny - 1, Math.max(0, j)) * nx + Math.min(nx - 1, Math.max(0, i))];
    const lx = -0.5, ly = 0.5, lz = Math.SQRT1_2;
    for (let j = 0; j < ny; ++j) {
      for (let i = 0; i < nx; ++i) {
        const c = j * nx + i, h = state[c], p = 4 * ((ny - 1 - j) * nx + i);
        if (h < initial[c] - 1e-6) ++cutCells;
        let rgb = data.none;
        if (h > data.bottom) {
          rgb = ramp(thick > 0 ? (data.top - h) / thick : 0);
          const gx = (at(i + 1, j) - at(i - 1, j)) / (2 * data.cell), gy = (at(i, j + 1) - at(i, j - 1)) / (2 * data.cell);
          const len = Math.sqrt(gx * gx + gy * gy + 1);
          const shade = Math.min(1.3, Math.max(0.55, (-gx * lx - gy * ly + lz) / len / lz));
          rgb = rgb.map((v) => Math.min(255, Math.round(v * shade)));
        }
        pixels.data[p] = rgb[0]; pixels.data[p + 1] = rgb[1]; pixels.data[p + 2] = rgb[2]; pixels.data[p + 3] = 255;
      }
    }
    ictx.putImageData(pixels, 0, 0);
    tctx.imageSmoothingEnabled = false;
    tctx.drawImage(image, 0, 0, top.width, top.height);
    if (data.section) {
      const s = data.section, X = (x) => (x - data.x0) * sc, Y = (y) => top.height - (y - data.y0) * sc;
      for (const [w, col] of [[4, "#fff"], [1.5, "#000"]]) {
        tctx.strokeStyle = col; tctx.lineWidth = w;
        tctx.beginPath(); tctx.moveTo(X(s[0]), Y(s[1])); tctx.lineTo(X(s[2]), Y(s[3])); tctx.stroke();
      }
      tctx.fillStyle = "#000"; tctx.font = "13px DejaVu Sans, sans-serif";
      tctx.fillText("A", X(s[0]) - 12, Y(s[1]) - 4); tctx.fillText("B", X(s[2]) + 4, Y(s[3]) - 4);
    }
  }
  function drawLathe() {
    const sc = top.width / (nx * data.cell), base = top.height - 20;
    const X = (z) => (z - data.x0) * sc, Y = (r) => base - r * sc;
    cutCells = 0;
    tctx.fillStyle = "rgb(150,160,176)";
    for (let c = 0; c < nx; ++c) {
      if (state[c] < initial[c] - 1e-6 || state[n + c] > initial[n + c] + 1e-6) ++cutCells;
      if (!(state[c] > state[n + c])) continue;
      const a = Math.round(X(data.x0 + c * data.cell)), b = Math.round(X(data.x0 + (c + 1) * data.cell));
      tctx.fillRect(a, Math.round(Y(state[c])), b - a, Math.round(Y(state[n + c])) - Math.round(Y(state[c])));
    }
    tctx.strokeStyle = "#c01a1a"; tctx.setLineDash([5, 4]); tctx.lineWidth = 1;
    tctx.strokeRect(X(data.x0), Y(data.top), nx * data.cell * sc, data.top * sc);
    tctx.setLineDash([12, 3, 2, 3]); tctx.strokeStyle = "#000";
    tctx.beginPath(); tctx.moveTo(0, base); tctx.lineTo(top.width, base); tctx.stroke();
    tctx.setLineDash([]);
  }

  // ---- the section: the part's height along A-B, to scale (Z stretched where stated) ----
  const sec = $("section");
  function drawSection() {
    if (!sec) return;
    const ctx = sec.getContext("2d"), s = data.section;
    const len = Math.hypot(s[2] - s[0], s[3] - s[1]), sx = sec.width / Math.max(len, 1e-9), sz = sx * data.exaggeration;
    const base = sec.height - 20, Y = (z) => base - (z - data.bottom) * sz;
    ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, sec.width, sec.height);
    const steps = Math.min(4000, Math.max(2, Math.ceil(4 * len / data.cell)));
    let prev = null;
    ctx.beginPath();
    for (let k = 0; k <= steps; ++k) {
      const t = k / steps, x = s[0] + (s[2] - s[0]) * t, y = s[1] + (s[3] - s[1]) * t;
      const i = Math.floor((x - data.x0) / data.cell), j = Math.floor((y - data.y0) / data.cell);
      const inside = i >= 0 && j >= 0 && i < nx && j < ny;
      const h = inside ? state[j * nx + i] : null, h0 = inside ? initial[j * nx + i] : null;
      const px = Math.round(t * len * sx), w = Math.max(1, Math.round((k + 1) / steps * len * sx) - px);
      if (inside && h > data.bottom) { ctx.fillStyle = "rgb(150,160,176)"; ctx.fillRect(px, Y(h), w, Y(data.bottom) - Y(h)); }
      if (inside && h0 > data.bottom) { ctx.fillStyle = "#c01a1a"; ctx.fillRect(px, Y(data.top), w, 1); ctx.fillRect(px, Y(data.bottom), w, 1); }
      if (inside) { if (prev === null) ctx.moveTo(px, Y(h)); else ctx.lineTo(px, Y(h)); ctx.lineTo(px + w, Y(h)); prev = h; }
    }
    ctx.strokeStyle = "#000"; ctx.lineWidth = 1.5; ctx.stroke();
    ctx.fillStyle = "#000"; ctx.font = "13px DejaVu Sans, sans-serif";
    ctx.fillText("A", 2, sec.height - 4); ctx.fillText("B", sec.width - 12, sec.height - 4);
  }

  // ---- the 3D view of the height field (WebGL) ----
  const glCanvas = $("gl");
  let gl = null;
  try { gl = glCanvas.getContext("webgl", {preserveDrawingBuffer: true}) || glCanvas.getContext("experimental-webgl", {preserveDrawingBuffer: true}); } catch (e) { gl = null; }
  let draw3d = () => {};
  if (!gl || data.lathe) {
    glCanvas.hidden = true;
    $("gl-missing").hidden = false;
  } else {
    const vs = "attribute vec3 p;attribute vec3 nrm;attribute vec3 col;uniform mat4 m;varying vec3 c;" +
               "void main(){gl_Position=m*vec4(p,1.0);float l=max(dot(normalize(nrm),normalize(vec3(-0.4,0.5,0.75))),0.0);c=col*(0.35+0.75*l);}";
    const fs = "precision mediump float;varying vec3 c;void main(){gl_FragColor=vec4(min(c,vec3(1.0)),1.0);}";
    const shader = (type, src) => { const s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s); return s; };
    const prog = gl.createProgram();
    gl.attachShader(prog, shader(gl.VERTEX_SHADER, vs)); gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, fs));
    gl.linkProgram(prog); gl.useProgram(prog);
    const buffers = {p: gl.createBuffer(), nrm: gl.createBuffer(), col: gl.createBuffer()};
    const quads = Math.max(0, nx - 1) * Math.max(0, ny - 1), count = quads * 6;
    const pos = new Float32Array(count * 3), nor = new Float32Array(count * 3), col = new Float32Array(count * 3);
    const cx = data.x0 + nx * data.cell / 2, cy = data.y0 + ny * data.cell / 2, cz = (data.top + data.bottom) / 2;
    const size = Math.max(nx, ny) * data.cell;
    let yaw = -0.6, pitch = 0.9, zoom = 1.0;
    function mul(a, b) {
      const o = new Float32Array(16);
      for (let i = 0; i < 4; ++i) for (let j = 0; j < 4; ++j) {
        let s = 0; for (let k = 0; k < 4; ++k) s += a[k * 4 + j] * b[i * 4 + k]; o[i * 4 + j] = s;
      }
      return o;
    }
    function matrix() {
      const d = 1.45 * size / zoom, f = 1 / Math.tan(0.4), asp = glCanvas.width / glCanvas.height, near = d / 20, far = d * 4;
      const proj = new Float32Array([f / asp, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0]);
      const cyw = Math.cos(yaw), syw = Math.sin(yaw), cp = Math.cos(pitch), sp = Math.sin(pitch);
      // The part turned about Z by yaw, tipped by pitch, d in front of the eye.
      const rz = new Float32Array([cyw, syw, 0, 0, -syw, cyw, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
      const rx = new Float32Array([1, 0, 0, 0, 0, cp, sp, 0, 0, -sp, cp, 0, 0, 0, 0, 1]);
      const tr = new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -cx, -cy, -cz, 1]);
      const back = new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -d, 1]);
      return mul(proj, mul(back, mul(rx, mul(rz, tr))));
    }
    function rebuild() {
      let v = 0;
      const hx = (i, j) => state[Math.min(ny - 1, Math.max(0, j)) * nx + Math.min(nx - 1, Math.max(0, i))];
      const put = (i, j) => {
        const h = hx(i, j);
        pos[3 * v] = data.x0 + (i + 0.5) * data.cell; pos[3 * v + 1] = data.y0 + (j + 0.5) * data.cell; pos[3 * v + 2] = h;
        nor[3 * v] = -(hx(i + 1, j) - hx(i - 1, j)) / (2 * data.cell); nor[3 * v + 1] = -(hx(i, j + 1) - hx(i, j - 1)) / (2 * data.cell); nor[3 * v + 2] = 1;
        const rgb = h > data.bottom ? ramp(thick > 0 ? (data.top - h) / thick : 0) : [235, 235, 235];
        col[3 * v] = rgb[0] / 255; col[3 * v + 1] = rgb[1] / 255; col[3 * v + 2] = rgb[2] / 255;
        ++v;
      };
      for (let j = 0; j + 1 < ny; ++j) for (let i = 0; i + 1 < nx; ++i) {
        put(i, j); put(i + 1, j); put(i + 1, j + 1); put(i, j); put(i + 1, j + 1); put(i, j + 1);
      }
      for (const [name, arr] of [["p", pos], ["nrm", nor], ["col", col]]) {
        gl.bindBuffer(gl.ARRAY_BUFFER, buffers[name]);
        gl.bufferData(gl.ARRAY_BUFFER, arr, gl.DYNAMIC_DRAW);
        const loc = gl.getAttribLocation(prog, name);
        gl.enableVertexAttribArray(loc);
        gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
      }
    }
    function render() {
      gl.viewport(0, 0, glCanvas.width, glCanvas.height);
      gl.clearColor(1, 1, 1, 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.enable(gl.DEPTH_TEST);
      gl.uniformMatrix4fv(gl.getUniformLocation(prog, "m"), false, matrix());
      gl.drawArrays(gl.TRIANGLES, 0, count);
    }
    draw3d = () => { rebuild(); render(); };
    let drag = null;
    glCanvas.addEventListener("mousedown", (e) => { drag = [e.clientX, e.clientY]; });
    window.addEventListener("mouseup", () => { drag = null; });
    window.addEventListener("mousemove", (e) => {
      if (!drag) return;
      yaw += (e.clientX - drag[0]) * 0.01; pitch = Math.min(1.55, Math.max(0, pitch + (e.clientY - drag[1]) * 0.01));
      drag = [e.clientX, e.clientY]; render();
    });
    glCanvas.addEventListener("wheel", (e) => { e.preventDefault(); zoom = Math.min(20, Math.max(0.2, zoom * Math.exp(-e.deltaY * 0.001))); render(); });
  }

  // ---- the block slider, as on the backplot page ----
  const slider = $("slider");
  function numbered(from, to) {
    const out = [];
    for (let k = Math.max(1, from); k <= Math.min(nc.length, to); ++k) out.push(k + "  " + nc[k - 1]);
    return out.join("\n");
  }
  function show(b) {
    b = Math.min(Math.max(1, Math.round(b) || 1), nc.length);
    $("line-no").textContent = b;
    $("nc-before").textContent = numbered(b - 3, b - 1);
    $("nc-no").textContent = b;
    $("nc-text").textContent = nc[b - 1];
    $("nc-after").textContent = numbered(b + 1, b + 3);
    stateAt(b);
    drawTop();
    drawSection();
    draw3d();
    $("cut").textContent = cutCells;
  }
  slider.addEventListener("input", () => show(+slider.value));
  function step(by) { slider.value = +slider.value + by; slider.dispatchEvent(new Event("input")); }
  $("prev").addEventListener("click", () => step(-1));
  $("next").addEventListener("click", () => step(1));
  function painted(canvas, ctx2d) {
    // Pixels that are not the background (white): the part as drawn.
    let w = canvas.width, h = canvas.height, px;
    if (ctx2d) px = ctx2d.getImageData(0, 0, w, h).data;
    else { px = new Uint8Array(w * h * 4); gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px); }
    let k = 0, sum = 0;
    for (let i = 0; i < px.length; i += 4) if (px[i] !== 255 || px[i + 1] !== 255 || px[i + 2] !== 255) { ++k; sum = (sum * 31 + px[i] + 7 * px[i + 1] + 13 * px[i + 2]) % 1000000007; }
    return [k, sum];
  }
  // #block=N shows the part cut up to block N; #block=A,B&check steps the slider to each as a
  // user would and records what the page draws (a browser test).
  function fromHash() {
    const m = /^#block=([0-9]+(?:,[0-9]+)*)(&check)?$/.exec(location.hash);
    if (!m) return;
    const log = [];
    for (const b of m[1].split(",")) {
      slider.value = b;
      slider.dispatchEvent(new Event("input"));
      if (!m[2]) continue;
      const t = painted(top, tctx), g = gl && !glCanvas.hidden ? painted(glCanvas, null) : null;
      const s = sec ? painted(sec, sec.getContext("2d")) : null;
      log.push(JSON.stringify({block: +b, line: +$("line-no").textContent, nc: $("nc-text").textContent, cut: cutCells,
                               top: t[0], topSum: t[1], section: s ? s[0] : null, sectionSum: s ? s[1] : null,
                               gl: g ? g[0] : null, glSum: g ? g[1] : null, webgl: !!gl}));
    }
    $("steps").textContent = log.join("\n");
  }
  window.addEventListener("hashchange", fromHash);
  slider.max = nc.length;
  slider.value = nc.length;
  show(nc.length);
  fromHash();
})();
)JS";

}  // namespace

void write_simulation_html(std::ostream& out, const SimResult& r, const SimHistory& history,
                           const std::optional<SectionLine>& section, const PictureLabels& labels,
                           const std::function<std::istream&()>& text) {
    const bool lathe = r.kind == MachineKind::lathe;
    if (lathe && section) throw SimInputError("a section is a mill's picture; a lathe's page shows its half-section");
    nlohmann::json d;
    d["lathe"] = lathe;
    d["nx"] = history.nx, d["ny"] = history.ny;
    d["x0"] = history.x0, d["y0"] = history.y0, d["cell"] = history.cell;
    d["top"] = history.top, d["bottom"] = history.bottom;
    nlohmann::json stops = nlohmann::json::array();
    for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        const Rgb c = depth_colour(t);
        stops.push_back({t, {c.r, c.g, c.b}});
    }
    d["stops"] = stops;
    d["none"] = {no_material_colour.r, no_material_colour.g, no_material_colour.b};
    d["initial"] = sim_floats(history.initial);
    std::vector<unsigned char> cells, event_lines;
    std::vector<float> values, values2;
    for (const SimHistory::Event& e : history.events) {
        sim_put(cells, e.cell);
        sim_put(event_lines, e.line);
        values.push_back(e.value);
        values2.push_back(e.value2);
    }
    d["cells"] = sim_base64(cells), d["lines"] = sim_base64(event_lines), d["values"] = sim_floats(values);
    if (lathe) d["values2"] = sim_floats(values2);
    // The views' sizes, px: 640 wide, the part to scale.
    const double w_mm = history.nx * history.cell;
    const double h_mm = lathe ? std::max(history.top, 1e-3) : history.ny * history.cell;
    const double view = 640;
    const double sc = std::min(view / w_mm, 480 / h_mm);
    const int top_w = std::max(1, static_cast<int>(std::lround(w_mm * sc)));
    const int top_h = std::max(1, static_cast<int>(std::lround(h_mm * sc))) + (lathe ? 30 : 0);
    int sec_w = 0, sec_h = 0;
    if (section) {
        d["section"] = {section->a.x, section->a.y, section->b.x, section->b.y};
        const double len = std::max(distance(section->a, section->b), 1e-9);
        sec_w = top_w;
        const double sx = sec_w / len, thick_px = (history.top - history.bottom) * sx;
        const double ex = thick_px >= 60 || !(thick_px > 0) ? 1.0 : std::ceil(60 / thick_px);
        d["exaggeration"] = ex;
        sec_h = static_cast<int>(std::ceil(thick_px * ex)) + 30;
    }
    const std::string title = fmt::format("{} on {}", labels.program, labels.machine);
    out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        << fmt::format("<title>camgen simulate: {}</title>\n<style>{}</style>\n</head>\n<body>\n", html_text(title), sim_style)
        << fmt::format("<header><h1>camgen simulate: {}</h1>\n", html_text(title));
    if (lathe)
        out << fmt::format("<p>Turned profile of {} samples of {} mm; the page shows {} bands of {} mm (each the smallest "
                           "outside and largest bore of its samples).</p>\n",
                           r.cells, number_text(r.resolution), history.nx, number_text(history.cell, 4));
    else
        out << fmt::format("<p>Height field of {} x {} cells of {} mm; the page shows {} x {} cells of {} mm (each the "
                           "lowest of its cells).</p>\n",
                           r.field.nx, r.field.ny, number_text(r.resolution), history.nx, history.ny,
                           number_text(history.cell, 4));
    out << fmt::format("<p>Block slider history: {} changes logged (a change of at least {} mm; {} left out to keep "
                       "within {}).</p>\n</header>\n",
                       history.events.size(), number_text(history.quantum, 4), history.thinned, history.budget);
    out << "<main>\n<div id=\"views\">\n<section><h2>" << (lathe ? "Half-section (radius up, Z to the right)" : "Top view, coloured by depth")
        << "</h2>\n"
        << fmt::format("<canvas id=\"top\" width=\"{}\" height=\"{}\"></canvas>\n", top_w, top_h);
    if (!lathe)
        out << fmt::format("<p class=\"note\">Z {} (light) to {} (dark); white: no material. {} mm across.</p>\n",
                           number_text(history.top, 3), number_text(history.bottom, 3), number_text(w_mm, 3));
    out << "</section>\n";
    if (section)
        out << fmt::format("<section><h2>Section A-B{}</h2>\n<canvas id=\"section\" width=\"{}\" height=\"{}\"></canvas>\n"
                           "<p class=\"note\">Material grey, the stock as it was red.</p></section>\n",
                           d["exaggeration"].get<double>() > 1 ? fmt::format(" (Z drawn {} times larger)",
                                                                             number_text(d["exaggeration"].get<double>(), 0))
                                                               : "",
                           sec_w, sec_h);
    out << fmt::format("<section{}><h2>3D view</h2>\n<canvas id=\"gl\" width=\"640\" height=\"420\"></canvas>\n"
                       "<p id=\"gl-missing\" class=\"note\" hidden>This browser has no WebGL: the 3D view cannot be "
                       "drawn.</p>\n<p class=\"note\">Drag to turn, wheel to zoom.</p></section>\n</div>\n",
                       lathe ? " hidden" : "");
    out << fmt::format("<aside>\n<section><h2>Cut up to block <span id=\"line-no\"></span></h2>\n<div class=\"controls\">"
                       "<button id=\"prev\" type=\"button\">&lt;</button><input id=\"slider\" type=\"range\" min=\"1\" "
                       "max=\"1\" value=\"1\"><button id=\"next\" type=\"button\">&gt;</button></div>\n")
        << "<pre id=\"nc-before\"></pre><pre id=\"nc-current\"><span id=\"nc-no\"></span>  <span id=\"nc-text\"></span></pre>"
           "<pre id=\"nc-after\"></pre>\n<p class=\"note\">Cells cut so far: <span id=\"cut\"></span>.</p></section>\n</aside>\n"
           "</main>\n<pre id=\"steps\" hidden></pre>\n";
    out << "<script type=\"application/json\" id=\"camgen-sim\">" << script_json(d) << "</script>\n";
    // The program's text, a line at a time, as one JSON string.
    out << "<script type=\"application/json\" id=\"camgen-nc\">\"";
    std::istream& in = text();
    std::string line;
    bool first = true;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::string quoted = script_json(nlohmann::json(line));
        if (!first) out << "\\n";
        out << std::string_view(quoted).substr(1, quoted.size() - 2);
        first = false;
    }
    out << "\"</script>\n<script>" << sim_script << "</script>\n</body>\n</html>\n";
}

}  // namespace camgen
