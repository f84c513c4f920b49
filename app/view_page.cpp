#include "app/view_page.h"

namespace quiver {

// The API it calls is the one app/view_server.cpp serves: /api/scene once,
// then /api/frame per stage of each view, /api/command and /api/png on
// demand, every request with the token of the page's own address.
const std::string_view kViewPage = R"page(<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>quiver view</title>
<link rel="icon" href="data:,">
<style>
  :root { color-scheme: dark; --bg: #1a1b1d; --panel: #232427; --field: #17181a; --line: #34363a;
          --text: #d8d8d8; --dim: #8b8e93; --accent: #7aa7e8; --error: #ff7b72; }
  * { box-sizing: border-box; }
  html, body { height: 100%; margin: 0; }
  body { display: grid; grid-template-columns: minmax(0, 1fr) 250px; grid-template-rows: minmax(0, 1fr) auto;
         background: var(--bg); color: var(--text); font: 13px/1.4 system-ui, sans-serif; }
  #view { grid-area: 1 / 1; display: flex; align-items: center; justify-content: center;
          padding: 12px; overflow: hidden; }
  #frame { max-width: 100%; max-height: 100%; background: #000; cursor: grab; touch-action: none;
           image-rendering: pixelated; box-shadow: 0 0 0 1px var(--line); }
  #frame.dragging { cursor: grabbing; }
  #status { grid-area: 2 / 1; padding: 6px 12px; border-top: 1px solid var(--line); color: var(--dim);
            font-variant-numeric: tabular-nums; white-space: nowrap; overflow: hidden; text-overflow: ellipsis; }
  #status.error { color: var(--error); white-space: pre-wrap; }
  #panel { grid-area: 1 / 2 / 3 / 3; display: flex; flex-direction: column; gap: 10px; padding: 14px;
           background: var(--panel); border-left: 1px solid var(--line); overflow-y: auto; }
  h1 { margin: 0; font-size: 15px; font-weight: 600; }
  .dim { color: var(--dim); font-size: 12px; overflow-wrap: anywhere; }
  label { display: grid; grid-template-columns: 72px 1fr; align-items: center; gap: 8px; }
  input { width: 100%; padding: 4px 6px; font: inherit; color: var(--text); background: var(--field);
          border: 1px solid var(--line); border-radius: 4px; }
  input:focus { outline: none; border-color: var(--accent); }
  input:disabled { color: var(--dim); }
  .buttons { display: flex; gap: 8px; }
  button, #download { flex: 1; padding: 6px 8px; font: inherit; text-align: center; text-decoration: none;
                      cursor: pointer; color: var(--text); background: #2f3134; border: 1px solid var(--line);
                      border-radius: 4px; }
  button:hover, #download:hover { border-color: var(--accent); }
  #command { display: block; padding: 6px; font: 11px/1.4 ui-monospace, monospace; overflow-wrap: anywhere;
             background: var(--field); border-radius: 4px; user-select: all; }
  #command:empty { display: none; }
  kbd { padding: 0 4px; font: 11px ui-monospace, monospace; border: 1px solid var(--line); border-radius: 3px; }
  ul { margin: 0; padding-left: 16px; }
</style>
</head>
<body>
<div id="view"><canvas id="frame" width="1" height="1"></canvas></div>
<div id="status">loading…</div>
<aside id="panel">
  <div><h1>quiver view</h1><div class="dim" id="scene"></div></div>
  <label>width <input id="width" type="number" min="1" step="1"></label>
  <label>height <input id="height" type="number" min="1" step="1"></label>
  <label>aa <input id="aa" type="text" spellcheck="false"
                   title="none, grid:N, jitter:N, adaptive:T:D, corners, refine:T:N[:grid]"></label>
  <label>max depth <input id="max_depth" type="number" min="0" step="1"></label>
  <label>fov <input id="fov" type="number" min="0" max="180" step="any" title="degrees, across the longer side"></label>
  <div class="dim" id="locked" hidden>aa and max depth: set by --preset spd</div>
  <div class="buttons">
    <button id="copy" type="button">Copy command</button>
    <a id="download" download>Download PNG</a>
  </div>
  <code id="command"></code>
  <ul class="dim">
    <li>drag: orbit</li>
    <li>right- or shift-drag: pan</li>
    <li>wheel: dolly</li>
    <li><kbd>f</kbd> frame the scene, <kbd>r</kbd> reset</li>
  </ul>
  <div class="dim" id="about"></div>
</aside>
<script>
"use strict";

// Vectors are arrays of three doubles.
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.sqrt(dot(a, a));
const unit = (a) => mul(a, 1 / norm(a));

const $ = (id) => document.getElementById(id);
const token = new URLSearchParams(location.search).get("token") || "";
const canvas = $("frame");
const context = canvas.getContext("2d");
const scratch = document.createElement("canvas");  // the coarse frame at its own size, scaled up from here
const scratchContext = scratch.getContext("2d");
const statusLine = $("status");
const fields = { width: $("width"), height: $("height"), aa: $("aa"), max_depth: $("max_depth"), fov: $("fov") };

const ORBIT_PER_PIXEL = 0.008;  // radians per CSS pixel of drag
const DOLLY_PER_DELTA = 0.0015; // distance factor exp(k * wheel deltaY)
const POLE_MARGIN = 0.01;       // radians kept between the view and the up pole
const SETTLE_MS = 250;          // the full chain starts this long after the last wheel event

let scene = null;        // /api/scene
let initial = null;      // the initial camera, for "r"
let camera = null;       // {from, at, up, fov, width, height, aa, max_depth}: what the next view shows
let current = null;      // the latest view: {id, camera, start, signal}
let controller = null;   // aborts the requests of the views before the current one
let interacting = false; // dragging or wheeling: coarse frames only
let coarseInFlight = false;
let settleTimer = 0;
const timings = [];      // {view, stage, ms_since_view_start} per frame drawn

const copyCamera = (c) => ({ ...c, from: [...c.from], at: [...c.at], up: [...c.up] });
const vector = (v) => v.map(String).join(",");
const aaNone = (c) => c.aa.trim() === "none";

function query(c, extra = {}) {
  const p = new URLSearchParams({ token, from: vector(c.from), at: vector(c.at), up: vector(c.up), fov: String(c.fov),
                                  width: String(c.width), height: String(c.height) });
  if (!scene.aa_locked) {
    p.set("aa", c.aa);
    p.set("max_depth", String(c.max_depth));
  }
  for (const [key, value] of Object.entries(extra)) p.set(key, value);
  return p.toString();
}

// ---- status --------------------------------------------------------------

function showError(message) {
  statusLine.className = "error";
  statusLine.textContent = message;
}

function showFrameStatus(frame, c) {
  const mrays = frame.ms > 0 ? (frame.rays / frame.ms / 1000).toFixed(2) : "–";
  statusLine.className = "";
  statusLine.textContent = `${frame.stage} · ${frame.ms.toFixed(1)} ms · ${mrays} Mrays/s · ${c.width}×${c.height}`;
}

function reportFailure(error, view) {
  if (error.name === "AbortError" || view !== current) return;  // a newer view took over
  showError(error.message);
}

// ---- frames --------------------------------------------------------------

// One stage of a camera's image, or null when the server cancelled it for a newer request (409).
async function fetchFrame(c, stage, signal) {
  const response = await fetch(`/api/frame?${query(c, { stage })}`, { signal, cache: "no-store" });
  if (response.status === 409) return null;
  if (!response.ok) throw new Error(`${stage} frame: ${response.status} ${(await response.text()).trim()}`);
  const header = (name) => response.headers.get(`X-Quiver-${name}`);
  const width = Number(header("Width")), height = Number(header("Height"));
  const pixels = new Uint8ClampedArray(await response.arrayBuffer());
  if (pixels.length !== width * height * 4) {
    throw new Error(`${stage} frame: ${pixels.length} bytes for ${width}×${height}`);
  }
  return { stage, width, height, pixels, ms: Number(header("Render-Ms")), rays: Number(header("Rays")) };
}

// Coarse frames are scaled up to the canvas without smoothing; the others are its pixels as they came.
function draw(frame, view) {
  const c = view.camera;
  if (frame.stage !== "coarse" && (frame.width !== c.width || frame.height !== c.height)) {
    throw new Error(`${frame.stage} frame: ${frame.width}×${frame.height}, not ${c.width}×${c.height}`);
  }
  if (canvas.width !== c.width || canvas.height !== c.height) {
    canvas.width = c.width;
    canvas.height = c.height;
  }
  const image = new ImageData(frame.pixels, frame.width, frame.height);
  if (frame.stage === "coarse") {
    scratch.width = frame.width;
    scratch.height = frame.height;
    scratchContext.putImageData(image, 0, 0);
    context.imageSmoothingEnabled = false;
    context.drawImage(scratch, 0, 0, canvas.width, canvas.height);
  } else {
    context.putImageData(image, 0, 0);
  }
  document.body.dataset.stage = frame.stage;
  timings.push({ view: view.id, stage: frame.stage, ms_since_view_start: performance.now() - view.start });
  if (timings.length > 500) timings.splice(0, timings.length - 500);
  showFrameStatus(frame, c);
}

// coarse, full, then final (full is final without anti-aliasing), until a newer view aborts it.
// A stage superseded while its view is still the latest (by a PNG download, another tab) is asked for
// again, twice at most.
async function refine(view) {
  const stages = aaNone(view.camera) ? ["coarse", "full"] : ["coarse", "full", "final"];
  let retries = 2;
  for (const stage of stages) {
    let frame = await fetchFrame(view.camera, stage, view.signal);
    while (!frame && view === current && retries-- > 0) {
      await new Promise((resume) => setTimeout(resume, 200));
      if (view === current) frame = await fetchFrame(view.camera, stage, view.signal);
    }
    if (!frame || view !== current) return;
    draw(frame, view);
  }
  document.body.dataset.final = "1";
}

// While interacting, one coarse request at a time: when it returns, the latest view is requested.
function requestCoarse() {
  if (coarseInFlight) return;
  const view = current;
  controller?.abort();
  controller = new AbortController();
  coarseInFlight = true;
  fetchFrame(view.camera, "coarse", controller.signal)
    .then((frame) => { if (frame && interacting) draw(frame, view); })
    .catch((error) => { if (error.name !== "AbortError") showError(error.message); })
    .finally(() => {
      coarseInFlight = false;
      if (interacting && current !== view) requestCoarse();
    });
}

// The camera changed: a new view, coarse only while interacting, else the whole chain.
function newView(interactive = false) {
  current = { id: (current?.id ?? 0) + 1, camera: copyCamera(camera), start: performance.now(), signal: null };
  document.body.dataset.view = String(current.id);
  delete document.body.dataset.final;
  $("download").href = `/api/png?${query(current.camera)}`;
  if (interactive) {
    requestCoarse();
    return;
  }
  controller?.abort();
  controller = new AbortController();
  current.signal = controller.signal;
  const view = current;
  refine(view).catch((error) => reportFailure(error, view));
}

// ---- camera moves --------------------------------------------------------

// The tangent-plane size of one pixel at unit distance: fov spans the outermost pixel centres of the longer side.
function pixelSize(c) {
  return 2 * Math.tan(c.fov * Math.PI / 360) / Math.max(1, Math.max(c.width, c.height) - 1);
}

// Around the look-at point: azimuth about the up vector, elevation kept short of its poles.
function orbit(dx, dy) {
  const pole = unit(camera.up);
  const offset = sub(camera.from, camera.at);
  const distance = norm(offset);
  let radial = sub(offset, mul(pole, dot(offset, pole)));
  if (norm(radial) < 1e-12 * distance) radial = cross(pole, Math.abs(pole[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0]);
  radial = unit(radial);
  const turn = -dx * ORBIT_PER_PIXEL;
  radial = add(mul(radial, Math.cos(turn)), mul(cross(pole, radial), Math.sin(turn)));
  const polar = Math.acos(Math.max(-1, Math.min(1, dot(offset, pole) / distance)));
  const elevated = Math.max(POLE_MARGIN, Math.min(Math.PI - POLE_MARGIN, polar - dy * ORBIT_PER_PIXEL));
  camera.from = add(camera.at, mul(add(mul(radial, Math.sin(elevated)), mul(pole, Math.cos(elevated))), distance));
}

// from and at together in the view plane, so that the point at the look-at distance follows the cursor.
function pan(dx, dy) {
  const forward = sub(camera.at, camera.from);
  const right = cross(forward, camera.up);
  if (norm(right) < 1e-12 * norm(forward) * norm(camera.up)) return;
  const across = unit(right), upward = unit(cross(right, forward));
  const imagePixelsPerCssPixel = canvas.width / canvas.getBoundingClientRect().width;
  const scale = pixelSize(camera) * norm(forward) * imagePixelsPerCssPixel;
  const shift = add(mul(across, -dx * scale), mul(upward, dy * scale));
  camera.from = add(camera.from, shift);
  camera.at = add(camera.at, shift);
}

function dolly(deltaY) {
  const offset = sub(camera.from, camera.at);
  const distance = norm(offset) * Math.exp(DOLLY_PER_DELTA * deltaY);
  if (!(distance > 1e-9)) return;
  camera.from = add(camera.at, mul(unit(offset), distance));
}

// The same direction, at the bounds' centre, from where their bounding sphere fills the shorter side.
function frameScene() {
  const b = scene.bounds;
  if (!b || ![...b.min, ...b.max].every(Number.isFinite) || b.min.some((m, i) => m > b.max[i])) {
    showError("nothing bounded to frame");
    return;
  }
  const centre = mul(add(b.min, b.max), 0.5);
  const radius = Math.max(norm(sub(b.max, b.min)) / 2, 1e-6);
  const longer = Math.max(camera.width, camera.height), shorter = Math.min(camera.width, camera.height);
  const tanHalf = Math.tan(camera.fov * Math.PI / 360) * (longer > 1 ? Math.max(shorter - 1, 1) / (longer - 1) : 1);
  const distance = radius / Math.sin(Math.atan(tanHalf));
  camera.from = sub(centre, mul(unit(sub(camera.at, camera.from)), distance));
  camera.at = centre;
  newView();
}

function reset() {
  Object.assign(camera, { from: [...initial.from], at: [...initial.at], up: [...initial.up], fov: initial.fov });
  fillFields();
  newView();
}

// ---- input ---------------------------------------------------------------

let drag = null;  // {x, y, pan, moved}

canvas.addEventListener("contextmenu", (event) => event.preventDefault());
canvas.addEventListener("pointerdown", (event) => {
  if (!camera || (event.button !== 0 && event.button !== 2)) return;
  event.preventDefault();
  canvas.setPointerCapture(event.pointerId);
  canvas.classList.add("dragging");
  drag = { x: event.clientX, y: event.clientY, pan: event.button === 2 || event.shiftKey, moved: false };
  interacting = true;
});
canvas.addEventListener("pointermove", (event) => {
  if (!drag) return;
  const dx = event.clientX - drag.x, dy = event.clientY - drag.y;
  if (dx === 0 && dy === 0) return;
  drag.x = event.clientX;
  drag.y = event.clientY;
  drag.moved = true;
  if (drag.pan) pan(dx, dy); else orbit(dx, dy);
  newView(true);
});
function endDrag() {
  if (!drag) return;
  const moved = drag.moved;
  drag = null;
  interacting = false;
  canvas.classList.remove("dragging");
  if (moved) newView();
}
canvas.addEventListener("pointerup", endDrag);
canvas.addEventListener("pointercancel", endDrag);

canvas.addEventListener("wheel", (event) => {
  if (!camera) return;
  event.preventDefault();
  const lines = event.deltaMode === WheelEvent.DOM_DELTA_LINE ? 33 : 1;
  dolly(event.deltaY * lines);
  interacting = true;
  newView(true);
  clearTimeout(settleTimer);
  settleTimer = setTimeout(() => {
    if (drag) return;
    interacting = false;
    newView();
  }, SETTLE_MS);
}, { passive: false });

document.addEventListener("keydown", (event) => {
  if (!camera || event.target instanceof HTMLInputElement || event.ctrlKey || event.metaKey || event.altKey) return;
  if (event.key === "f") frameScene();
  else if (event.key === "r") reset();
});

function fillFields() {
  for (const [name, input] of Object.entries(fields)) input.value = String(camera[name]);
}

for (const [name, input] of Object.entries(fields)) {
  input.addEventListener("change", () => {
    if (name === "aa") {
      if (!input.value.trim()) {
        input.value = camera.aa;
        return;
      }
      camera.aa = input.value.trim();
    } else {
      const value = Number(input.value);
      if (input.value.trim() === "" || !Number.isFinite(value)) {
        showError(`${name.replace("_", " ")}: "${input.value}" is not a number`);
        input.value = String(camera[name]);
        return;
      }
      camera[name] = value;
    }
    newView();
  });
}

$("copy").addEventListener("click", async () => {
  if (!current) return;
  try {
    const response = await fetch(`/api/command?${query(current.camera)}`, { cache: "no-store" });
    const text = (await response.text()).trim();
    if (!response.ok) throw new Error(`command: ${response.status} ${text}`);
    $("command").textContent = text;
    if (navigator.clipboard?.writeText) navigator.clipboard.writeText(text).catch(() => {});
  } catch (error) {
    showError(error.message);
  }
});

// ---- start ---------------------------------------------------------------

async function start() {
  if (!token) throw new Error("no token in this page's address: open the URL quiver view printed");
  const response = await fetch(`/api/scene?token=${encodeURIComponent(token)}`, { cache: "no-store" });
  if (!response.ok) throw new Error(`scene: ${response.status} ${(await response.text()).trim()}`);
  scene = await response.json();
  const v = scene.view;
  initial = { from: v.from, at: v.at, up: v.up, fov: v.fov, width: scene.width, height: scene.height,
              aa: scene.aa, max_depth: scene.max_depth };
  camera = copyCamera(initial);
  canvas.width = camera.width;
  canvas.height = camera.height;
  document.title = `quiver view · ${scene.scene}`;
  $("scene").textContent = scene.scene;
  $("about").textContent = `${scene.threads} threads · ${scene.isa} · ${scene.version}`;
  if (scene.aa_locked) {
    fields.aa.disabled = fields.max_depth.disabled = true;
    $("locked").hidden = false;
  }
  fillFields();
  newView();
}

window.quiverView = {
  get view() { return current ? current.id : 0; },
  state: () => (camera ? copyCamera(camera) : null),
  timings,
};

start().catch((error) => showError(error.message));
</script>
</body>
</html>
)page";

}  // namespace quiver
