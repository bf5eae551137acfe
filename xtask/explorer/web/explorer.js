// The explorer page's script. All the geometry is the `raster` and `scenes`
// code in explorer.wasm (xtask/explorer/engine/src/exports.rs documents the calls);
// this script only draws what the module returns, handles the pointer, and
// keeps the address's fragment in step with the state.
"use strict";

const WIDTH = 320;
const HEIGHT = 200;
const SUBPIXELS = 256;
const VIEWPORT = { width: 640, height: 400 };
const ZOOMS = [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64];
const I32_MIN = -2147483648;
const I32_MAX = 2147483647;
// How close (CSS px) the pointer must come to a vertex to grab it.
const GRAB_RADIUS = 8;
// The difference view's colours, as view.rs paints them.
const ADDED = "rgb(255,48,48)";
const MISSED = "rgb(0,170,255)";
const AGREED = "rgb(230,230,230)";
const CLASSES = ["degenerate", "triangle", "convex", "simple", "complex"];

const encoder = new TextEncoder();
const decoder = new TextDecoder();

let compiled = null;
let engine = null;
let methods = [];
let builtins = [];
let results = null;
let panes = [];
let renders = 0;

const view = { a: "abrash_int", b: "", mode: "diff", judge: "exact", zoom: 2, panX: 0, panY: 0 };
// The last state that rendered cleanly, as a fragment: what a restarted
// engine goes back to.
let lastGoodFragment = "";

const $ = (id) => document.getElementById(id);

function showMessage(text, kind) {
  const box = $("message");
  box.textContent = text;
  box.className = text ? kind : "";
}

// ---- the engine ----

async function startEngine() {
  if (!compiled) {
    const response = await fetch("explorer.wasm");
    if (!response.ok) throw new Error(`explorer.wasm: ${response.status} ${response.statusText}`);
    compiled = await WebAssembly.compile(await response.arrayBuffer());
  }
  engine = (await WebAssembly.instantiate(compiled, {})).exports;
}

function readOutput(len) {
  return decoder.decode(new Uint8Array(engine.memory.buffer, engine.ex_output(), len));
}

function writeInput(text) {
  const bytes = encoder.encode(text);
  const at = engine.ex_input(bytes.length);
  new Uint8Array(engine.memory.buffer, at, bytes.length).set(bytes);
}

// Text answers are lines of `key<TAB>value`.
function keyValues(text) {
  const out = {};
  for (const line of text.split("\n")) {
    const tab = line.indexOf("\t");
    if (tab > 0) out[line.slice(0, tab)] = line.slice(tab + 1);
  }
  return out;
}

// Runs `work` against the engine. A trap (a bug: the methods never panic)
// leaves the instance unusable, so a fresh one takes its place and goes
// back to the last state that rendered.
async function guarded(work) {
  try {
    return work();
  } catch (error) {
    if (!(error instanceof WebAssembly.RuntimeError)) throw error;
    const fragment = lastGoodFragment;
    await startEngine();
    applyFragment(fragment);
    render();
    showMessage(`The engine stopped (${error.message}) and was restarted at the last good state.`, "error");
    return undefined;
  }
}

function methodIndex(name) {
  return methods.indexOf(name);
}

function loadBuiltin(name) {
  writeInput(name);
  if (engine.ex_load_builtin() !== 0) {
    showMessage(readOutput(engine.ex_output_len()), "error");
    return false;
  }
  return true;
}

function loadText(text) {
  writeInput(text);
  if (engine.ex_load_text() !== 0) {
    showMessage(`Scene file not opened: ${readOutput(engine.ex_output_len())}`, "error");
    return false;
  }
  return true;
}

function vertices() {
  const count = engine.ex_vertex_count();
  const at = engine.ex_vertices();
  return Array.from(new Int32Array(engine.memory.buffer, at, count * 3));
}

// ---- the fragment ----

function fragment() {
  const params = new URLSearchParams();
  const origin = readOutput(engine.ex_origin()).split("\t");
  if (origin[0] === "builtin") {
    params.set("scene", origin[1]);
    const edits = readOutput(engine.ex_edits());
    if (edits) params.set("edits", edits);
  } else {
    params.set("text", readOutput(engine.ex_scene_text()));
  }
  params.set("a", view.a);
  if (view.b) params.set("b", view.b);
  params.set("view", view.mode);
  params.set("judge", view.judge);
  params.set("poly", String(engine.ex_selected()));
  params.set("zoom", String(view.zoom));
  params.set("x", view.panX.toFixed(1));
  params.set("y", view.panY.toFixed(1));
  return "#" + params.toString();
}

function currentPolygon() {
  return engine.ex_selected();
}

function writeFragment() {
  const hash = fragment();
  history.replaceState(null, "", hash);
  lastGoodFragment = hash;
}

// Sets the state from a fragment; anything unusable in it is named in the
// message and left at its default.
function applyFragment(hash) {
  const params = new URLSearchParams(hash.replace(/^#/, ""));
  const problems = [];
  let loaded = false;
  if (params.has("text")) {
    writeInput(params.get("text"));
    if (engine.ex_load_text() === 0) loaded = true;
    else problems.push(`the scene in the address: ${readOutput(engine.ex_output_len())}`);
  } else if (params.has("scene")) {
    writeInput(params.get("scene"));
    if (engine.ex_load_builtin() === 0) loaded = true;
    else problems.push(readOutput(engine.ex_output_len()));
  }
  if (!loaded) loadBuiltin("abrash38-3");
  if (loaded && params.has("edits")) {
    writeInput(params.get("edits"));
    if (engine.ex_apply_edits() !== 0) problems.push(`edits in the address: ${readOutput(engine.ex_output_len())}`);
  }
  const pickMethod = (key, fallback, allowNone) => {
    if (!params.has(key)) return fallback;
    const name = params.get(key);
    if ((allowNone && name === "") || methods.includes(name)) return name;
    problems.push(`unknown method \`${name}\`; the methods are ${methods.join(", ")}`);
    return fallback;
  };
  view.a = pickMethod("a", "abrash_int", false);
  view.b = pickMethod("b", "", true);
  view.mode = params.get("view") === "picture" ? "picture" : "diff";
  view.judge = params.get("judge") === "own" ? "own" : "exact";
  const zoom = Number(params.get("zoom"));
  view.zoom = ZOOMS.includes(zoom) ? zoom : 2;
  const pan = (key) => {
    const value = Number(params.get(key));
    return Number.isFinite(value) && Math.abs(value) < 1e6 ? value : 0;
  };
  view.panX = pan("x");
  view.panY = pan("y");
  const count = engine.ex_polygon_count();
  const poly = params.has("poly") ? Number(params.get("poly")) : count - 1;
  engine.ex_select(Number.isInteger(poly) && poly >= 0 ? Math.min(poly, 0xffffffff) : 0);
  showMessage(problems.join("; "), "error");
}

// ---- drawing ----

function makePanes() {
  const template = $("pane-template");
  for (const id of ["a", "b"]) {
    const node = template.content.firstElementChild.cloneNode(true);
    node.id = `pane-${id}`;
    $("panes").appendChild(node);
    const overlay = node.querySelector(".overlay");
    overlay.width = VIEWPORT.width * devicePixelRatio;
    overlay.height = VIEWPORT.height * devicePixelRatio;
    const pane = {
      id,
      index: panes.length,
      node,
      picture: node.querySelector(".picture"),
      overlay,
      field: (name) => node.querySelector(`[data-field="${name}"]`),
    };
    attachPointer(pane);
    panes.push(pane);
  }
}

function paneMethod(pane) {
  return pane.id === "a" ? view.a : view.b;
}

function render() {
  renders += 1;
  const selected = keyValues(readOutput(engine.ex_selected_info()));
  for (const pane of panes) {
    const method = paneMethod(pane);
    pane.node.hidden = !method;
    if (!method) continue;
    const at = engine.ex_render(pane.index, methodIndex(method), view.mode === "diff" ? 1 : 0, view.judge === "own" ? 1 : 0);
    const rgba = new Uint8ClampedArray(engine.memory.buffer, at, WIDTH * HEIGHT * 4).slice();
    pane.picture.getContext("2d").putImageData(new ImageData(rgba, WIDTH, HEIGHT), 0, 0);
    const report = keyValues(readOutput(engine.ex_report(pane.index)));
    const info = keyValues(readOutput(engine.ex_method_info(methodIndex(method))));
    describePane(pane, method, report, info, selected);
    drawOverlay(pane, info);
  }
  placePictures();
  describePolygon(selected);
  document.body.dataset.renders = String(renders);
}

function describePane(pane, method, report, info, selected) {
  const judge = report.judge === "own" ? "the reference at its own sample point" : "exact";
  const millions = (v) => (Number(v) / 1e6).toFixed(0);
  const fallback =
    view.judge === "own" && report.judge !== "own"
      ? ` (the reference would make ${millions(report.reference_work)} million pixel-edge tests on this scene; the page's limit is ${millions(report.reference_budget)} million)`
      : "";
  pane.field("title").textContent = `${method} against ${judge}${fallback}`;
  const legend = pane.field("legend");
  legend.replaceChildren();
  if (view.mode === "diff") {
    for (const [colour, words] of [[ADDED, "added (drawn, not wanted)"], [MISSED, "missed (wanted, not drawn)"], [AGREED, "agreed"]]) {
      const swatch = document.createElement("span");
      swatch.className = "swatch";
      swatch.style.background = colour;
      legend.append(swatch, words);
    }
    legend.append(" — the selected polygon over the darkened scene");
  } else {
    legend.textContent = "the scene as the method draws it, in the VGA default palette";
  }
  for (const key of ["added", "missed", "overdrawn", "strays"]) {
    pane.field(`selected_${key}`).textContent = report[`selected_${key}`] ?? "";
    pane.field(`scene_${key}`).textContent = report[`scene_${key}`] ?? "";
  }
  const refusals = pane.field("refusals");
  const words = [];
  if (report.selected_refusal) words.push(`${method} refuses the selected polygon: ${report.selected_refusal}.`);
  if (Number(report.refused) > 0) {
    words.push(`It refuses ${report.refused} of the scene's ${report.polygons} polygons (first: ${report.scene_refusal}).`);
  } else {
    words.push(`It refuses none of the scene's ${report.polygons} polygons.`);
  }
  refusals.textContent = words.join(" ");
  refusals.className = report.selected_refusal || Number(report.refused) > 0 ? "refused" : "";
  const rules = (info.rules || "").split(", ");
  const rule = pane.field("rule");
  const beyond = CLASSES.indexOf(selected.class) > CLASSES.indexOf(info.handles);
  rule.textContent =
    `Selected polygon: ${selected.class || "none"}, ${selected.rule || "no"} rule; ` +
    (rules.includes(selected.rule) ? `${method} honours that rule` : `${method} does not honour that rule`) +
    (beyond ? `; it is beyond what ${method} handles (${info.handles}).` : ".");
  for (const key of ["source", "sample", "convention", "arithmetic", "handles", "rules", "heap"]) {
    pane.field(key).textContent = info[key] || "";
  }
  describeLab(pane, method, selected);
}

function describeLab(pane, method, selected) {
  const box = pane.field("lab");
  if (!results) {
    box.textContent = "No lab results loaded (see below).";
    return;
  }
  const family = results.families.find((f) => f.name === selected.family);
  const row = results.rows.find((r) => r.name === method && r.family === selected.family);
  const lines = [`Nearest lab family: ${selected.family} (${selected.family_reason})` + (family ? ` — ${family.description}.` : ".")];
  if (!row) {
    lines.push(`results.json has no row for ${method} on ${selected.family}.`);
  } else {
    const number = (v, digits) => (typeof v === "number" ? v.toFixed(digits) : "n/a");
    const percent = (v) => (typeof v === "number" && row.pixels > 0 ? `${((100 * v) / row.pixels).toFixed(2)}%` : "n/a");
    // The spread of the repeats and the ratio to exact's time with its
    // interval, where the results carry them.
    const spread = typeof row.ns_min === "number" && typeof row.ns_max === "number"
      ? ` (${number(row.ns_min, 0)}–${number(row.ns_max, 0)} over the repeats)` : "";
    const vs = row.vs_exact;
    const interval = vs && typeof vs.low === "number" && typeof vs.high === "number"
      ? ` (95% interval ${vs.low.toFixed(2)}–${vs.high.toFixed(2)})` : "";
    const ratio = vs && method !== "exact" && typeof vs.ratio === "number" ? `, ${vs.ratio.toFixed(2)}x exact's${interval}` : "";
    lines.push(
      `Time: ${number(row.ns_per_polygon, 0)} ns a polygon${spread}${ratio}, ${number(row.time_vs_memset, 2)}x the memset bound.`,
      `Wrong pixels: ${row.wrong_pixels ?? "n/a"} under our convention (${percent(row.wrong_pixels)} of ${row.pixels}), ` +
        `${row.wrong_pixels_own ?? "n/a"} under its own (${percent(row.wrong_pixels_own)}).`,
      `Overdrawn ${row.overdraw ?? "n/a"}, faulty polygons ${row.faulty_polygons ?? "n/a"} of ${row.polygons}, ` +
        `refusals ${row.refusals ?? "n/a"}, failures ${row.failures ?? "n/a"}` + (results.quick ? " (a --quick run)." : "."),
    );
  }
  box.replaceChildren(...lines.map((line) => Object.assign(document.createElement("div"), { textContent: line })));
}

function describePolygon(selected) {
  const count = engine.ex_polygon_count();
  $("poly-count").textContent = String(count);
  $("poly").max = String(Math.max(0, count - 1));
  $("poly").value = selected.index ?? "0";
  if (!selected.line) {
    $("polygon-summary").textContent = "The scene has no polygon.";
    $("line").value = "";
    return;
  }
  $("polygon-summary").textContent =
    `Polygon ${selected.index}: ${selected.class}, ${selected.vertices} vertices in ${selected.contours} contour(s), ` +
    `colour ${selected.color}, ${selected.rule} rule.`;
  $("line").value = selected.line;
}

function placePictures() {
  for (const pane of panes) {
    pane.picture.style.transform = `translate(${view.panX}px, ${view.panY}px) scale(${view.zoom})`;
  }
  $("zoom-label").textContent = `${view.zoom}x`;
}

// Screen position (CSS px in the viewport) of a subpixel coordinate.
function toScreen(x, y) {
  return [view.panX + (x / SUBPIXELS) * view.zoom, view.panY + (y / SUBPIXELS) * view.zoom];
}

function drawOverlay(pane, info) {
  const ctx = pane.overlay.getContext("2d");
  ctx.setTransform(devicePixelRatio, 0, 0, devicePixelRatio, 0, 0);
  ctx.clearRect(0, 0, VIEWPORT.width, VIEWPORT.height);
  const z = view.zoom;
  const firstX = Math.max(0, Math.floor(-view.panX / z));
  const lastX = Math.min(WIDTH, Math.ceil((VIEWPORT.width - view.panX) / z));
  const firstY = Math.max(0, Math.floor(-view.panY / z));
  const lastY = Math.min(HEIGHT, Math.ceil((VIEWPORT.height - view.panY) / z));
  if (z >= 8) {
    ctx.strokeStyle = "rgba(128,128,128,0.45)";
    ctx.lineWidth = 1;
    ctx.beginPath();
    for (let x = firstX; x <= lastX; x++) {
      const sx = Math.round(view.panX + x * z) + 0.5;
      ctx.moveTo(sx, view.panY + firstY * z);
      ctx.lineTo(sx, view.panY + lastY * z);
    }
    for (let y = firstY; y <= lastY; y++) {
      const sy = Math.round(view.panY + y * z) + 0.5;
      ctx.moveTo(view.panX + firstX * z, sy);
      ctx.lineTo(view.panX + lastX * z, sy);
    }
    ctx.stroke();
  }
  if (z >= 16) {
    // The method's sample point in every pixel: where it decides in or out.
    const match = /^\((-?\d+), (-?\d+)\)/.exec(info.sample || "");
    if (match) {
      const [sx, sy] = [Number(match[1]) / SUBPIXELS, Number(match[2]) / SUBPIXELS];
      ctx.fillStyle = "rgba(255,255,0,0.8)";
      for (let y = firstY; y < lastY; y++) {
        for (let x = firstX; x < lastX; x++) {
          ctx.fillRect(view.panX + (x + sx) * z - 1, view.panY + (y + sy) * z - 1, 2, 2);
        }
      }
    }
  }
  const points = vertices();
  if (points.length === 0) return;
  // Far vertices (up to 2^23 px away) are drawn clamped: the canvas needs
  // no more than to know the direction of the edge.
  const clamp = (v) => Math.max(-1e7, Math.min(1e7, v));
  // Thin and faint: the difference marks lie along the edges.
  ctx.lineWidth = 1;
  ctx.strokeStyle = "rgba(255,255,0,0.55)";
  ctx.beginPath();
  for (let i = 0; i < points.length; i += 3) {
    const [sx, sy] = toScreen(points[i + 1], points[i + 2]).map(clamp);
    if (i === 0 || points[i] !== points[i - 3]) ctx.moveTo(sx, sy);
    else ctx.lineTo(sx, sy);
    const next = i + 3;
    if (next >= points.length || points[next] !== points[i]) ctx.closePath();
  }
  ctx.stroke();
  ctx.font = "11px sans-serif";
  for (let i = 0; i < points.length; i += 3) {
    const [sx, sy] = toScreen(points[i + 1], points[i + 2]);
    if (sx < -10 || sy < -10 || sx > VIEWPORT.width + 10 || sy > VIEWPORT.height + 10) continue;
    ctx.fillStyle = "#ffff00";
    ctx.strokeStyle = "#000";
    ctx.beginPath();
    ctx.arc(sx, sy, 4, 0, 2 * Math.PI);
    ctx.fill();
    ctx.stroke();
    ctx.fillText(String(i / 3), sx + 6, sy - 6);
  }
}

// ---- the pointer ----

function pointerInViewport(pane, event) {
  const rect = pane.overlay.getBoundingClientRect();
  return [event.clientX - rect.left, event.clientY - rect.top];
}

// The vertex of the selected polygon under viewport point (vx, vy), or -1.
function vertexNear(vx, vy) {
  const points = vertices();
  let best = -1;
  let bestDistance = GRAB_RADIUS;
  for (let i = 0; i < points.length; i += 3) {
    const [sx, sy] = toScreen(points[i + 1], points[i + 2]);
    const distance = Math.hypot(sx - vx, sy - vy);
    if (distance <= bestDistance) {
      best = i / 3;
      bestDistance = distance;
    }
  }
  return best;
}

let drag = null;
let renderQueued = false;

function queueRender() {
  if (renderQueued) return;
  renderQueued = true;
  requestAnimationFrame(() => {
    renderQueued = false;
    guarded(render);
  });
}

function attachPointer(pane) {
  const target = pane.overlay;
  target.addEventListener("pointerdown", (event) => {
    if (event.button !== 0) return;
    const [vx, vy] = pointerInViewport(pane, event);
    const vertex = vertexNear(vx, vy);
    target.setPointerCapture(event.pointerId);
    if (vertex >= 0) {
      const points = vertices();
      drag = { kind: "vertex", vertex, x: points[vertex * 3 + 1], y: points[vertex * 3 + 2], cx: event.clientX, cy: event.clientY };
    } else {
      drag = { kind: "pan", panX: view.panX, panY: view.panY, cx: event.clientX, cy: event.clientY, moved: false, vx, vy };
    }
  });
  target.addEventListener("pointermove", (event) => {
    const [vx, vy] = pointerInViewport(pane, event);
    showCursor(vx, vy);
    if (!drag) return;
    const dx = event.clientX - drag.cx;
    const dy = event.clientY - drag.cy;
    if (drag.kind === "vertex") {
      // Relative to where the vertex was grabbed, snapped to 1/256 px.
      const clampI32 = (v) => Math.max(I32_MIN, Math.min(I32_MAX, v));
      const x = clampI32(drag.x + Math.round((dx * SUBPIXELS) / view.zoom));
      const y = clampI32(drag.y + Math.round((dy * SUBPIXELS) / view.zoom));
      guarded(() => engine.ex_set_vertex(drag.vertex, x, y));
      queueRender();
    } else {
      drag.moved = drag.moved || Math.abs(dx) + Math.abs(dy) > 3;
      if (drag.moved) {
        view.panX = drag.panX + dx;
        view.panY = drag.panY + dy;
        placePictures();
        queueRender();
      }
    }
  });
  const finish = (event) => {
    if (!drag) return;
    const ended = drag;
    drag = null;
    if (ended.kind === "pan" && !ended.moved && event.type === "pointerup") {
      const x = Math.floor((ended.vx - view.panX) / view.zoom);
      const y = Math.floor((ended.vy - view.panY) / view.zoom);
      const index = engine.ex_polygon_at(x, y);
      if (index >= 0) engine.ex_select(index);
    }
    guarded(() => {
      render();
      writeFragment();
    });
  };
  target.addEventListener("pointerup", finish);
  target.addEventListener("pointercancel", finish);
  target.addEventListener(
    "wheel",
    (event) => {
      event.preventDefault();
      const [vx, vy] = pointerInViewport(pane, event);
      zoomBy(event.deltaY < 0 ? 1 : -1, vx, vy);
    },
    { passive: false },
  );
}

function showCursor(vx, vy) {
  const px = (vx - view.panX) / view.zoom;
  const py = (vy - view.panY) / view.zoom;
  const sx = Math.round(px * SUBPIXELS);
  const sy = Math.round(py * SUBPIXELS);
  const inside = px >= 0 && py >= 0 && px < WIDTH && py < HEIGHT;
  $("cursor").textContent = `Pointer at (${(sx / SUBPIXELS).toFixed(4)}, ${(sy / SUBPIXELS).toFixed(4)})` + (inside ? `, pixel (${Math.floor(px)}, ${Math.floor(py)}).` : ", off screen.");
}

// Zooms one step in (+1) or out (-1), keeping viewport point (vx, vy) still.
function zoomBy(step, vx, vy) {
  const at = ZOOMS.indexOf(view.zoom);
  const zoom = ZOOMS[Math.max(0, Math.min(ZOOMS.length - 1, at + step))];
  if (zoom === view.zoom) return;
  view.panX = vx - ((vx - view.panX) * zoom) / view.zoom;
  view.panY = vy - ((vy - view.panY) * zoom) / view.zoom;
  view.zoom = zoom;
  guarded(() => {
    render();
    writeFragment();
  });
}

// ---- controls ----

function fillSelect(select, names) {
  for (const name of names) select.append(new Option(name, name));
}

function syncControls() {
  const origin = readOutput(engine.ex_origin()).split("\t");
  const scene = $("scene");
  scene.querySelector('option[value=""]')?.remove();
  if (origin[0] === "builtin") {
    scene.value = origin[1];
  } else {
    scene.prepend(new Option("(scene file)", ""));
    scene.value = "";
  }
  $("method-a").value = view.a;
  $("method-b").value = view.b;
  $("view").value = view.mode;
  $("judge").value = view.judge;
}

// Applies a change made through the controls, then redraws.
function change(work) {
  guarded(() => {
    showMessage("", "");
    work();
    syncControls();
    render();
    writeFragment();
  });
}

function wireControls() {
  fillSelect($("scene"), builtins);
  fillSelect($("method-a"), methods);
  fillSelect($("method-b"), methods);
  $("scene").addEventListener("change", (event) => {
    const name = event.target.value;
    if (name) change(() => loadBuiltin(name) && engine.ex_select(engine.ex_polygon_count() - 1));
  });
  $("method-a").addEventListener("change", (event) => change(() => (view.a = event.target.value)));
  $("method-b").addEventListener("change", (event) => change(() => (view.b = event.target.value)));
  $("view").addEventListener("change", (event) => change(() => (view.mode = event.target.value)));
  $("judge").addEventListener("change", (event) => change(() => (view.judge = event.target.value)));
  $("zoom-in").addEventListener("click", () => zoomBy(1, VIEWPORT.width / 2, VIEWPORT.height / 2));
  $("zoom-out").addEventListener("click", () => zoomBy(-1, VIEWPORT.width / 2, VIEWPORT.height / 2));
  $("zoom-fit").addEventListener("click", () =>
    change(() => {
      view.zoom = 2;
      view.panX = 0;
      view.panY = 0;
    }),
  );
  const selectPolygon = (index) => change(() => engine.ex_select(Math.max(0, index)));
  $("poly-prev").addEventListener("click", () => selectPolygon(currentPolygon() - 1));
  $("poly-next").addEventListener("click", () => selectPolygon(currentPolygon() + 1));
  $("poly").addEventListener("change", (event) => {
    const index = Number(event.target.value);
    if (Number.isInteger(index) && index >= 0) selectPolygon(Math.min(index, 0xffffffff));
    else showMessage(`Polygon numbers are whole numbers from 0.`, "error");
  });
  $("copy-line").addEventListener("click", async () => {
    const line = $("line").value;
    try {
      await navigator.clipboard.writeText(line);
      showMessage("The selected polygon's line is on the clipboard.", "info");
    } catch {
      $("line").select();
      showMessage("The clipboard is not available here: the line is selected, copy it by hand.", "info");
    }
  });
  $("open-text").addEventListener("click", () =>
    change(() => {
      if (loadText($("scene-text").value)) {
        engine.ex_select(Math.max(0, engine.ex_polygon_count() - 1));
        showMessage("Scene file opened.", "info");
      }
    }),
  );
  $("show-text").addEventListener("click", () => {
    guarded(() => {
      $("scene-text").value = readOutput(engine.ex_scene_text());
    });
  });
  $("scene-file").addEventListener("change", async (event) => {
    const file = event.target.files[0];
    if (!file) return;
    const text = await file.text();
    $("scene-text").value = text;
    change(() => {
      if (loadText(text)) {
        engine.ex_select(Math.max(0, engine.ex_polygon_count() - 1));
        showMessage(`Opened ${file.name}.`, "info");
      }
    });
  });
  $("results-file").addEventListener("change", async (event) => {
    const file = event.target.files[0];
    if (file) useResults(await file.text(), file.name);
  });
  window.addEventListener("hashchange", () => {
    if (location.hash === lastGoodFragment) return;
    guarded(() => {
      applyFragment(location.hash);
      syncControls();
      render();
      writeFragment();
    });
  });
}

// ---- lab results ----

function useResults(text, from) {
  try {
    const parsed = JSON.parse(text);
    if (!Array.isArray(parsed.rows) || !Array.isArray(parsed.families)) throw new Error("no rows or families in it");
    results = parsed;
    $("lab-status").textContent = `Lab results from ${from}: ${parsed.rows.length} rows over ${parsed.families.length} families` + (parsed.quick ? " (a --quick run)." : ".");
  } catch (error) {
    showMessage(`${from} is not a lab results.json: ${error.message}`, "error");
  }
  guarded(render);
}

// Whether the address `hash` names a scene of its own.
function namesScene(hash) {
  const params = new URLSearchParams(hash.replace(/^#/, ""));
  return params.has("text") || params.has("scene");
}

// The scene `cargo xtask explore --scene FILE` (or `--svg FILE`) put beside
// the page, opened unless the address the page was opened at named one.
async function loadServedScene(addressNamedOne) {
  if (addressNamedOne) return;
  let response;
  try {
    response = await fetch("scene.scene");
  } catch {
    return;
  }
  if (!response.ok) return;
  const text = await response.text();
  $("scene-text").value = text;
  guarded(() => {
    if (loadText(text)) {
      engine.ex_select(Math.max(0, engine.ex_polygon_count() - 1));
      showMessage("Opened the scene given to `cargo xtask explore`.", "info");
    }
    syncControls();
    render();
    writeFragment();
  });
}

async function loadServedResults() {
  try {
    const response = await fetch("results.json");
    if (response.ok) {
      useResults(await response.text(), "results.json beside the page");
      return;
    }
  } catch {
    // No server file: the picker below is the way.
  }
  $("lab-status").textContent = "No results.json beside the page: give one to `cargo xtask explore --results FILE`, or load one here.";
}

// ---- start ----

window.addEventListener("unhandledrejection", (event) => {
  showMessage(`Unexpected error: ${event.reason?.message ?? event.reason}`, "error");
});
window.addEventListener("error", (event) => {
  showMessage(`Unexpected error: ${event.message}`, "error");
});

async function main() {
  try {
    await startEngine();
  } catch (error) {
    showMessage(`The engine did not load: ${error.message}`, "error");
    return;
  }
  methods = readOutput(engine.ex_methods()).split("\n");
  builtins = readOutput(engine.ex_builtins()).split("\n");
  makePanes();
  wireControls();
  const addressNamedScene = namesScene(location.hash);
  await guarded(() => {
    applyFragment(location.hash);
    syncControls();
    render();
    writeFragment();
  });
  await loadServedScene(addressNamedScene);
  await loadServedResults();
  document.body.dataset.ready = "1";
}

// A small interface for people at the console and for the browser tests.
window.explorer = {
  // Where vertex `vertex` of the selected polygon is on screen, in client
  // (CSS px) coordinates of pane `pane` ("a" or "b").
  vertexOnScreen(pane, vertex) {
    const rect = $(`pane-${pane}`).querySelector(".overlay").getBoundingClientRect();
    const points = vertices();
    const [sx, sy] = toScreen(points[vertex * 3 + 1], points[vertex * 3 + 2]);
    return { x: rect.left + sx, y: rect.top + sy };
  },
};

main();
