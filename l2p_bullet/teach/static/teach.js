// The teach page: a top-down view of a random scene; the person drags block A, marks the start and the
// end of the demonstration, and saves it. Samples [t, x, y, yaw] of A (seconds, scene frame, metres) are
// taken on every change and by a 30 Hz timer while A rests; the server resamples, validates and writes.
// A composite action ("make a row of A, B and C"): any named block but the first can be dragged, one
// after another; each drag (pointer down .. up) is one segment [t, x, y, yaw] of that block, and saving
// posts the segments in the order they were made.
"use strict";

const SCALE = 680;          // pixels per metre
const TOP_X = 0.3;          // scene x at the top edge of the canvas (the robot is at the bottom)
const ROTATE = Math.PI / 36; // 5 degrees per wheel notch or key press
const NUDGE = 0.002;        // m per arrow key press (held: the key's repeat slides A at about 6 cm/s); Shift: 5x
// arrow key -> (dx, dy) in the scene frame as the view shows it (+x up, away from the robot; +y to the left)
const ARROWS = { ArrowUp: [1, 0], ArrowDown: [-1, 0], ArrowLeft: [0, 1], ArrowRight: [0, -1] };
const SAMPLE_MS = 1000 / 30;
const STEP = 0.25;          // largest move of a block's corner between two checked poses of a jump, in sides
const TOLERANCE = 0.25;     // how deep a jump's straight path may cut into another block, in sides (teach/checks.py)

const canvas = document.getElementById("view");
const ctx = canvas.getContext("2d");
const $ = (id) => document.getElementById(id);

let config = null;
let scene = null;         // the scene as the server drew it
let blocks = [];          // {name, rgb, size, x, y, yaw}
let mover = null;         // the block being moved (A)
let seed = 0;
let samples = [];
let marks = { start: null, end: null };
let drag = null;          // {dx, dy} while dragging
let polling = null;
let segments = [];        // composite: the drags saved so far [{block, samples}]
let segment = null;       // composite: the drag under way

function now() { return performance.now() / 1000; }

// scene frame (+x away from the robot, +y to its left) -> canvas pixels, robot at the bottom
function toScreen(x, y) { return [canvas.width / 2 - y * SCALE, 10 + (TOP_X - x) * SCALE]; }
function toScene(px, py) { return [TOP_X - (py - 10) / SCALE, (canvas.width / 2 - px) / SCALE]; }

function corners(b, x = b.x, y = b.y, yaw = b.yaw) {
  const h = b.size / 2, c = Math.cos(yaw), s = Math.sin(yaw);
  return [[h, h], [-h, h], [-h, -h], [h, -h]].map(([u, v]) => [x + c * u - s * v, y + s * u + c * v]);
}

// separating-axis test for two convex polygons (touching is not overlapping); margin < 0: overlapping by
// more than -margin along every axis (as if q were shrunk by -margin on each side), as in core/geometry.py
function overlap(p, q, margin = 0) {
  for (const poly of [p, q]) {
    for (let i = 0; i < poly.length; i++) {
      const [x1, y1] = poly[i], [x2, y2] = poly[(i + 1) % poly.length];
      const n = Math.hypot(x2 - x1, y2 - y1) || 1, ax = -(y2 - y1) / n, ay = (x2 - x1) / n;  // unit: margin in metres
      const proj = (pts) => pts.map(([x, y]) => x * ax + y * ay);
      const a = proj(p), b = proj(q);
      if (Math.max(...a) + margin <= Math.min(...b) + 1e-12 || Math.max(...b) + margin <= Math.min(...a) + 1e-12) return false;
    }
  }
  return true;
}

function allowed(x, y, yaw) {
  const mine = corners(mover, x, y, yaw);
  const t = scene.table;
  if (!mine.every(([cx, cy]) => Math.abs(cx) <= t.half_x && Math.abs(cy) <= t.half_y)) return false;
  if (!blocks.every((b) => b === mover || !overlap(mine, corners(b)))) return false;
  // The jump from where the block stands, as the server checks it when saving (teach/checks.py): refused
  // here, live, when its straight path passes through a block; not when it only cuts a corner the block
  // was dragged against (it stuck there, then jumps once the pointer clears the corner).
  const dx = x - mover.x, dy = y - mover.y, dyaw = yaw - mover.yaw;
  const corner = Math.hypot(dx, dy) + Math.abs(dyaw) * mover.size * Math.SQRT1_2;
  const parts = Math.max(1, Math.ceil(corner / (STEP * mover.size)));
  for (let i = 1; i < parts; i++) {
    const f = i / parts, path = corners(mover, mover.x + f * dx, mover.y + f * dy, mover.yaw + f * dyaw);
    if (blocks.some((b) => b !== mover && overlap(path, corners(b), -TOLERANCE * Math.min(mover.size, b.size)))) return false;
  }
  return true;
}

function sample() {
  if (!mover) return;
  if (scene && scene.composite) { if (segment) segment.samples.push([now(), mover.x, mover.y, mover.yaw]); return; }
  samples.push([now(), mover.x, mover.y, mover.yaw]);
}

function moveTo(x, y, yaw) {
  if (!allowed(x, y, yaw)) return false;
  mover.x = x; mover.y = y; mover.yaw = yaw;
  sample();
  draw();
  return true;
}

function draw() {
  if (!scene) return;
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const [tx0, ty0] = toScreen(scene.table.half_x, scene.table.half_y);
  const [tx1, ty1] = toScreen(-scene.table.half_x, -scene.table.half_y);
  ctx.fillStyle = "#e3d5bd";
  ctx.fillRect(tx0, ty0, tx1 - tx0, ty1 - ty0);
  const [wx, wy] = toScreen(scene.workspace.x, scene.workspace.y);
  ctx.setLineDash([6, 6]);
  ctx.strokeStyle = "#9a8a70";
  ctx.beginPath(); ctx.arc(wx, wy, scene.workspace.r * SCALE, 0, 2 * Math.PI); ctx.stroke();
  if (scene.workspace.near !== undefined) {  // an arm's reach ring cuts the disk (issue 22): its two circles
    const [bx, by] = toScreen(scene.workspace.base_x, scene.workspace.base_y);
    for (const r of [scene.workspace.near, scene.workspace.far]) {
      ctx.beginPath(); ctx.arc(bx, by, r * SCALE, 0, 2 * Math.PI); ctx.stroke();
    }
  }
  const anchors = scene.anchors.map((n) => blocks.find((b) => b.name === n));
  if (config.viewer) {  // the line of sight from the viewer to the (first) anchor: left is the viewer's left
    const [vx, vy] = toScreen(...config.viewer);
    const [ax, ay] = toScreen(anchors[0].x, anchors[0].y);
    ctx.strokeStyle = "#6b8fb3";
    ctx.beginPath(); ctx.moveTo(vx, vy); ctx.lineTo(ax, ay); ctx.stroke();
  }
  if (anchors.length === 2) {
    const [bx, by] = toScreen(anchors[0].x, anchors[0].y), [cx, cy] = toScreen(anchors[1].x, anchors[1].y);
    ctx.strokeStyle = "#6b8fb3";
    ctx.beginPath(); ctx.moveTo(bx, by); ctx.lineTo(cx, cy); ctx.stroke();
  }
  ctx.setLineDash([]);
  const [rx, ry] = toScreen(...config.robot);
  ctx.fillStyle = "#555";
  ctx.beginPath(); ctx.arc(rx, Math.min(ry, canvas.height - 4), 14, Math.PI, 2 * Math.PI); ctx.fill();
  ctx.fillText("robot", rx + 18, canvas.height - 8);
  if (marks.start !== null) {  // the path since the start mark
    ctx.strokeStyle = "#c33";
    ctx.beginPath();
    samples.filter((s) => s[0] >= marks.start && (marks.end === null || s[0] <= marks.end)).forEach((s, i) => {
      const [px, py] = toScreen(s[1], s[2]);
      if (i === 0) ctx.moveTo(px, py); else ctx.lineTo(px, py);
    });
    ctx.stroke();
  }
  for (const b of blocks) {
    const pts = corners(b).map(([x, y]) => toScreen(x, y));
    ctx.fillStyle = `rgb(${b.rgb.join(",")})`;
    ctx.beginPath();
    pts.forEach(([px, py], i) => (i === 0 ? ctx.moveTo(px, py) : ctx.lineTo(px, py)));
    ctx.closePath(); ctx.fill();
    ctx.strokeStyle = b === mover ? "#000" : "#444";
    ctx.lineWidth = b === mover ? 2 : 1;
    ctx.stroke();
    ctx.lineWidth = 1;
    const [cx, cy] = toScreen(b.x, b.y);
    ctx.fillStyle = "#fff";
    ctx.font = "bold 14px sans-serif";
    ctx.textAlign = "center"; ctx.textBaseline = "middle";
    ctx.fillText(b.name, cx, cy);
    ctx.textAlign = "start"; ctx.textBaseline = "alphabetic"; ctx.font = "12px sans-serif";
  }
}

function status(text, error = false) {
  $("status").textContent = text;
  $("status").classList.toggle("error", error);
}

function setState(state) {
  document.body.dataset.state = state;
  $("start").classList.toggle("done", marks.start !== null);
  $("end").classList.toggle("done", marks.end !== null);
}

// fetch's own "Failed to fetch" says nothing to a person: what happened, and what to do
const OFFLINE = "the teach server does not answer (was it stopped? start it again, then retry)";

async function api(method, path, body) {
  let r;
  try {
    r = await fetch(path, { method, headers: { "Content-Type": "application/json" },
                            body: body === undefined ? undefined : JSON.stringify(body) });
  } catch (e) { throw new Error(OFFLINE); }
  const data = await r.json().catch(() => ({ error: `HTTP ${r.status}` }));
  if (!r.ok) throw new Error(data.error || `HTTP ${r.status}`);
  return data;
}

async function loadScene(s) {
  const next = await api("GET", `/api/scene?seed=${s}`);  // the seed changes with the scene, never before it:
  seed = s;  // a scene that failed to load left the old one on the page under the new seed, and saving it was refused
  scene = next;
  blocks = scene.objects.map((o) => ({ ...o }));
  mover = scene.composite ? null : blocks.find((b) => b.name === scene.mover);
  samples = [];
  segments = [];
  segment = null;
  $("sentence").textContent = `“${scene.sentence}”`;
  marks = { start: null, end: null };
  sample();
  document.body.dataset.seed = String(s);
  status("");
  setState("ready");
  draw();
}

function markStart() {
  marks = { start: now(), end: null };
  sample();
  status("recording: slide A, then mark the end");
  setState("recording");
  draw();
}

function markEnd() {
  if (marks.start === null) { status("mark the start first", true); return; }
  marks.end = now();
  sample();
  status("marked the end: save it (Enter), or start this scene again (R)");
  setState("marked");
  draw();
}

// One saved demonstration (a single drag marked start to end, or a row of drags), then the next scene.
async function post(path, body, stateOnError) {
  if (document.body.dataset.state === "saving") return;  // Enter pressed twice: one request, not a 409 after it
  setState("saving");
  let r;
  try {
    r = await api("POST", path, body);
  } catch (e) {
    status(e.message, true);
    setState(stateOnError);
    return;
  }
  showCount(r.count, r.demos);
  try {  // saved: a failure from here on is about the next scene, not about the demonstration
    await loadScene(seed + 1);
    status(`saved (${r.count} in all); here is another scene` + (r.note ? ` (${r.note})` : ""));
  } catch (e) {
    status(`saved (${r.count} in all), but the next scene cannot be shown: ${e.message}`, true);
    setState("ready");
  }
  document.body.dataset.saved = String(r.count);
}

let count = 0;  // demonstrations in the demos file, as the server last said

function showCount(n, demos) {
  count = n;
  $("count").textContent = `${n} demonstration${n === 1 ? "" : "s"} in ${demos}`;
  $("remove").hidden = n === 0;
  document.body.dataset.count = String(n);
}

// The first click only asks (a click by mistake must not cost a demonstration); the second, within a few
// seconds, removes the last one saved: a mistaken save, or room under the number training reads.
let armed = null;

function disarm() {
  clearTimeout(armed);
  armed = null;
  $("remove").textContent = "remove the last demonstration";
}

async function removeLast() {
  if (count === 0) return;
  if (armed === null) {
    $("remove").textContent = `click again to remove demonstration ${count}`;
    armed = setTimeout(disarm, 4000);
    return;
  }
  disarm();
  try {
    const r = await api("DELETE", `/api/demos/${count}`);
    showCount(r.count, r.demos);
    status(`removed demonstration ${r.removed} (${r.count} left)`);
  } catch (e) {
    status(e.message, true);
  }
}

async function saveRow() {
  if (!segments.length) { status("drag the blocks into a row first", true); return; }
  await post("/api/rows", { scene: seed, segments }, "ready");
}

async function save() {
  if (scene && scene.composite) { await saveRow(); return; }
  if (marks.start === null || marks.end === null) { status("mark the start and the end first", true); return; }
  sample();
  await post("/api/demos", { scene: seed, samples, start: marks.start, end: marks.end }, "marked");
}

async function train() {
  try {
    await api("POST", "/api/train");
  } catch (e) {
    trainStatus(e.message, true);
    return;
  }
  $("progress").hidden = false;
  status("");  // an earlier error ("block A moved 0.00 blocks") is not about the training (issue 26)
  $("video").hidden = true;
  $("verdict").textContent = "";
  document.body.dataset.train = "training";
  clearInterval(polling);
  polling = setInterval(poll, 500);
}

function trainStatus(text, error) {
  $("train-status").textContent = text;
  $("train-status").classList.toggle("error", error);
}

// R and N: a scene that cannot be loaded says so (it was an unhandled rejection, nothing on the page)
async function changeScene(s) {
  try { await loadScene(s); } catch (e) { status(`cannot show the scene: ${e.message}`, true); }
}

async function poll() {
  let s;
  try { s = await api("GET", "/api/train"); } catch (e) { trainStatus(e.message, true); return; }
  $("progress").max = Math.max(s.total, 1);
  $("progress").value = s.done;
  trainStatus(`${s.message} (${s.seconds.toFixed(0)} s)`, s.state === "failed");
  document.body.dataset.train = s.state;
  if (s.state === "done" || s.state === "failed") {
    clearInterval(polling);
    $("progress").hidden = true;
    if (s.state === "done" && s.run) {
      const v = s.run.verdict;
      $("verdict").textContent = `“${s.run.sentence}” on a new scene: ${v.success ? "success" : "failed"} ` +
                                 `(${v.judge}: ${v.reason})`;
      if (s.run.video) {
        $("video").src = `${s.run.video}?t=${Date.now()}`;
        $("video").hidden = false;
        $("video").play().catch(() => {});
      }
    }
  }
}

function under(b, x, y) {
  const c = Math.cos(-b.yaw), s = Math.sin(-b.yaw);
  const u = c * (x - b.x) - s * (y - b.y), v = s * (x - b.x) + c * (y - b.y);
  return Math.abs(u) <= b.size / 2 && Math.abs(v) <= b.size / 2;
}

canvas.addEventListener("pointerdown", (ev) => {
  const r = canvas.getBoundingClientRect();
  const [x, y] = toScene(ev.clientX - r.left, ev.clientY - r.top);
  if (scene && scene.composite) {  // pick the named block under the pointer: this drag is its segment
    mover = blocks.find((b) => scene.movers.includes(b.name) && under(b, x, y)) || null;
    if (!mover) return;
    segment = { block: mover.name, samples: [] };
    sample();
    document.body.dataset.dragging = mover.name;
  }
  if (!mover) return;
  const c = Math.cos(-mover.yaw), s = Math.sin(-mover.yaw);
  const u = c * (x - mover.x) - s * (y - mover.y), v = s * (x - mover.x) + c * (y - mover.y);
  if (Math.abs(u) > mover.size / 2 || Math.abs(v) > mover.size / 2) return;
  drag = { dx: mover.x - x, dy: mover.y - y };
  canvas.setPointerCapture(ev.pointerId);
  canvas.classList.add("dragging");
  canvas.focus();
});
canvas.addEventListener("pointermove", (ev) => {
  if (!drag) return;
  const r = canvas.getBoundingClientRect();
  const [x, y] = toScene(ev.clientX - r.left, ev.clientY - r.top);
  moveTo(x + drag.dx, y + drag.dy, mover.yaw);
});
const stopDrag = () => {
  if (segment) {
    sample();
    if (segment.samples.length >= 2) segments.push(segment);
    segment = null;
    status(`${segments.length} drag${segments.length === 1 ? "" : "s"}: drag the next block, or save (Enter)`);
    document.body.dataset.segments = String(segments.length);
    delete document.body.dataset.dragging;
  }
  drag = null; canvas.classList.remove("dragging");
};
canvas.addEventListener("pointerup", stopDrag);
canvas.addEventListener("pointercancel", stopDrag);
canvas.addEventListener("wheel", (ev) => {
  ev.preventDefault();
  if (mover) moveTo(mover.x, mover.y, mover.yaw + (ev.deltaY < 0 ? ROTATE : -ROTATE));
}, { passive: false });

document.addEventListener("keydown", (ev) => {
  if (ev.target instanceof HTMLInputElement || ev.ctrlKey || ev.metaKey || ev.altKey) return;  // Ctrl+R reloads, no more
  // a button or the video reached with Tab does what it says on Enter or Space (Enter on a focused "train"
  // saved instead); the canvas keeps Enter for save
  const focused = document.activeElement;
  if (focused && focused !== canvas && focused !== document.body && (ev.key === "Enter" || ev.key === " ")) return;
  const k = ev.key.toLowerCase();
  if (k === "s") markStart();
  else if (k === "e") markEnd();
  else if (k === "enter") { ev.preventDefault(); save(); }
  else if (k === "r") changeScene(seed);
  else if (k === "n") changeScene(seed + 1);
  else if (k === "t") train();
  else if (k === "q" && mover) moveTo(mover.x, mover.y, mover.yaw + ROTATE);
  else if (k === "w" && mover) moveTo(mover.x, mover.y, mover.yaw - ROTATE);
  else if (ARROWS[ev.key] && mover && !(scene && scene.composite)) {
    // a demonstration without a pointer: the arrows slide A as a drag does (each step checked and sampled)
    ev.preventDefault();
    const [dx, dy] = ARROWS[ev.key], step = ev.shiftKey ? 5 * NUDGE : NUDGE;
    moveTo(mover.x + dx * step, mover.y + dy * step, mover.yaw);
  }
});
$("start").addEventListener("click", markStart);
$("end").addEventListener("click", markEnd);
$("save").addEventListener("click", save);
$("reset").addEventListener("click", () => changeScene(seed));
$("next").addEventListener("click", () => changeScene(seed + 1));
document.addEventListener("click", (ev) => {  // a mouse click (detail > 0) leaves no focus behind: Enter saves
  const b = ev.target instanceof Element && ev.target.closest("button");
  if (b && ev.detail > 0) b.blur();
});
$("train").addEventListener("click", train);
$("remove").addEventListener("click", removeLast);
setInterval(() => { if (!drag) sample(); }, SAMPLE_MS);

// for tests and scripts: where a scene point is on the page, and what is being recorded
window.teach = {
  toPage(x, y) { const r = canvas.getBoundingClientRect(); const [px, py] = toScreen(x, y); return [r.left + px, r.top + py]; },
  mover() { return mover && { x: mover.x, y: mover.y, yaw: mover.yaw }; },
  block(name) { const b = blocks.find((o) => o.name === name); return b && { x: b.x, y: b.y, yaw: b.yaw, size: b.size }; },
  segments() { return segments.length; },
  samples() { return samples.length; },
};

(async () => {
  try {
    config = await api("GET", "/api/config");
    $("sentence").textContent = `“${config.sentence}”`;
    if (config.composite) {  // no start and end marks: each drag is a step of the row
      $("start").closest("li").hidden = true;
      $("end").closest("li").hidden = true;
      document.querySelector(".hint").textContent =
        "Drag the blocks the sentence names, one after another, into a row (each drag is one step); then save.";
    }
    $("frame").textContent = config.viewer
      ? `Left, right, in front and behind as seen from the ${config.frame === "viewer" ? "robot (bottom of the view)" : config.frame}.`
      : (config.anchors === 2 ? "Two reference blocks: B and C." : "");
    showCount(config.count, config.demos);
    const first = Number(new URLSearchParams(location.search).get("seed") || config.seed || 0);
    await loadScene(first);
  } catch (e) {
    status(e.message, true);
  }
})();
