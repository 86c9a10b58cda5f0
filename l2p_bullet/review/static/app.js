// l2p-bullet review: one run at a time, graded or labelled with the keyboard.
// Every answer is sent to the server and shown as saved only after the server committed it.
"use strict";

const $ = (id) => document.getElementById(id);
const S = {
  config: null, reviewer: null, item: null, motion: null,
  history: [],        // this reviewer's answers, oldest first (from the server)
  pos: null,          // index into history while changing an earlier answer; null on a new run
  grade: null, label: null, busy: false,
  speed: 2, clock0: 0, raf: 0, frames: [],
};
const SPEEDS = [0.5, 1, 2, 4];
const NAME_KEY = "l2p-review-name";
const DRAFT_KEY = "l2p-review-draft";  // the answer being given, not yet sent: a reload (F5) keeps it (this tab only)

// fetch's own "Failed to fetch" says nothing to a reviewer: what happened, and what to do
const OFFLINE = "the review server does not answer (was it stopped? start it again, then retry)";

async function api(method, path, body) {
  const opts = { method, headers: {} };
  if (body !== undefined) { opts.headers["Content-Type"] = "application/json"; opts.body = JSON.stringify(body); }
  let r;
  try { r = await fetch(path, opts); } catch (e) { const err = new Error(OFFLINE); err.offline = true; throw err; }
  let data = null;
  try { data = await r.json(); } catch (e) { data = { error: `HTTP ${r.status}` }; }
  if (!r.ok) { const err = new Error(data.error || `HTTP ${r.status}`); err.status = r.status; err.reason = data.reason; throw err; }
  return data;
}

function setState(state) {
  document.body.dataset.state = state;
  for (const id of ["login", "review", "done"]) $(id).hidden = id !== state;
}

function status(text, kind) { const el = $("status"); el.textContent = text || ""; el.className = kind || ""; }

// --- start ------------------------------------------------------------------------------------
async function init() {
  S.config = await api("GET", "/api/config");
  $("mode").textContent = S.config.mode === "blind" ? "blind mode: which action is it?" : "graded mode";
  buildButtons();
  showProblems(S.config.problems);
  const name = localStorage.getItem(NAME_KEY);
  if (name) { await start(name); } else { setState("login"); $("name").focus(); }
}

function showProblems(problems) {
  const b = $("banner");
  if (!problems || !problems.length) { b.hidden = true; return; }
  const missing = problems.filter((p) => p.problem === "missing").length;
  const changed = problems.length - missing;
  b.textContent = `${problems.length} run(s) are not shown: ${missing} folder(s) disappeared, ` +
    `${changed} trajectory file(s) changed since the review started (the terminal and the report list them).`;
  b.hidden = false;
}

async function start(name) {
  S.reviewer = name;
  localStorage.setItem(NAME_KEY, name);
  $("who").innerHTML = "";
  $("who").append(`reviewer: ${name} `);
  const change = document.createElement("a");
  change.href = "#"; change.textContent = "(change)";
  change.onclick = (e) => { e.preventDefault(); localStorage.removeItem(NAME_KEY); location.reload(); };
  $("who").append(change);
  await loadHistory();
  await loadNext();
}

async function loadHistory() {
  const h = await api("GET", `/api/history?reviewer=${encodeURIComponent(S.reviewer)}`);
  S.history = h.answers;
  showCount(h.progress);
}

function showCount(p) { if (p) $("count").textContent = `${p.answered} / ${p.total} answered`; }

// a label is an installed plugin's entry-point name, any text: put in as text, never parsed as HTML
function kbd(key, hidden = false) {
  const k = document.createElement("kbd");
  k.textContent = key;
  if (hidden) k.setAttribute("aria-hidden", "true");  // a button's key hint: not part of its name
  return k;
}

function buildButtons() {
  const grades = $("grades");
  for (let g = 0; g <= 10; g++) {
    const b = document.createElement("button");
    b.type = "button"; b.dataset.grade = g;
    b.innerHTML = `<kbd aria-hidden="true">${g === 10 ? "t" : g}</kbd>${g}`;  // its name is "7", not "77"
    b.onclick = () => setGrade(g);
    grades.append(b);
  }
  if (S.config.mode !== "blind") return;
  $("labels").hidden = false; $("label-keys-help").hidden = false;
  $("grade-question").textContent = "How well does it do the action you picked? 0 = not at all, 10 = perfectly";
  const help = $("label-keys-help");  // the served table of keys, so the page says what each letter does
  help.textContent = "";
  for (const { label, key } of S.config.labels) {
    const item = document.createElement("span");
    item.append(kbd(key), `: ${label === "none" ? "none of these" : label}`);
    help.append(item, " ");
  }
  for (const { label, key } of S.config.labels) {
    const b = document.createElement("button");
    b.type = "button"; b.dataset.label = label;
    b.append(kbd(key, true), label === "none" ? "none of these" : label);
    b.onclick = () => setLabel(label);
    $("label-buttons").append(b);
  }
}

// --- showing a run ----------------------------------------------------------------------------
async function loadNext() {
  S.pos = null;
  const r = await api("GET", `/api/next?reviewer=${encodeURIComponent(S.reviewer)}`);
  showCount(r.progress);
  if (!r.item) { stopPlayback(); S.item = null; document.body.dataset.key = ""; setState("done"); return; }
  await show(r.item);
}

async function loadHistoryItem(pos) {
  const a = S.history[pos];
  const r = await api("GET", `/api/item/${a.key}?view=${a.view}&reviewer=${encodeURIComponent(S.reviewer)}`);
  S.pos = pos;
  await show(r.item);
}

async function show(item) {
  S.item = item;
  S.grade = item.answer ? item.answer.grade : null;
  S.label = item.answer ? item.answer.label : null;
  $("comment").value = item.answer ? item.answer.comment : "";
  const draft = takeDraft(item);
  $("sentence").textContent = item.sentence ? `“${item.sentence}”` : "";
  $("viewname").textContent = (item.view === "3d" ? "the robot (3-D rendering)" : "seen from above (2-D)")
    + (item.viewpoint ? `; you stand ${item.viewpoint}` : "");
  document.body.classList.toggle("editing", S.pos !== null);
  refreshButtons();
  S.missing = null;
  status(item.answer ? `your answer from ${item.answer.updated_at.replace("T", " ").slice(0, 19)}: change it and press Enter` : "");
  if (draft) {
    S.grade = draft.grade; S.label = draft.label; $("comment").value = draft.comment;
    refreshButtons(); keepDraft();
    status("your answer from before the page was reloaded, not saved yet: press Enter to submit it");
  }
  setState("review");
  S.motion = await api("GET", item.motion);
  document.body.dataset.key = `${item.key}:${item.view}`;
  play();
}

function refreshButtons() {  // aria-pressed: a screen reader says which one is picked
  for (const b of $("grades").children) pressed(b, Number(b.dataset.grade) === S.grade);
  for (const b of $("label-buttons").children) pressed(b, b.dataset.label === S.label);
}

function pressed(b, on) { b.classList.toggle("selected", on); b.setAttribute("aria-pressed", String(on)); }

function setGrade(g) { S.grade = g; refreshButtons(); answered("grade"); keepDraft(); }
function setLabel(l) { S.label = l; refreshButtons(); answered("label"); keepDraft(); }

function keepDraft() {
  if (!S.item) return;
  const base = S.item.answer ? S.item.answer.updated_at : null;
  sessionStorage.setItem(DRAFT_KEY, JSON.stringify({ reviewer: S.reviewer, key: S.item.key, view: S.item.view, base,
    grade: S.grade, label: S.label, comment: $("comment").value }));
}

// the draft kept for this run (same reviewer, and the stored answer it changes unchanged since), else none;
// any other draft is dropped: moving on to another run leaves it, as before
function takeDraft(item) {
  let d = null;
  try { d = JSON.parse(sessionStorage.getItem(DRAFT_KEY)); } catch (e) { d = null; }
  sessionStorage.removeItem(DRAFT_KEY);
  const base = item.answer ? item.answer.updated_at : null;
  return d && d.reviewer === S.reviewer && d.key === item.key && d.view === item.view && d.base === base ? d : null;
}
// "pick the action first" / "give a grade first" is answered by picking it: the red line goes (issue 26)
function answered(what) { if (S.missing === what) { S.missing = null; status(""); } }

// --- answering ----------------------------------------------------------------------------------
async function submit() {
  if (!S.item || S.busy) return;
  if (S.config.mode === "blind" && S.label === null) {
    S.missing = "label"; status("pick the action first (the letter keys)", "error"); return;
  }
  if (S.grade === null) { S.missing = "grade"; status("give a grade first: 0-9, or t for 10", "error"); return; }
  const body = {
    reviewer: S.reviewer, key: S.item.key, view: S.item.view, grade: S.grade,
    label: S.config.mode === "blind" ? S.label : null, comment: $("comment").value,
    replaces: S.item.answer ? S.item.answer.updated_at : null,
  };
  S.busy = true;
  try { await send(body); } finally { S.busy = false; }
}

async function send(body) {
  let r;
  try {
    r = await api("POST", "/api/answer", body);
  } catch (e) {
    if (e.offline) { status(`not saved: ${e.message}; your answer stays on this page until then`, "error"); return; }
    status(`not saved: ${e.message}`, "error");
    if (e.status === 409 || e.status === 410) {
      S.config = await api("GET", "/api/config");
      showProblems(S.config.problems);
      await loadHistory();
      if (e.reason === "changed" || e.reason === "missing") {  // this run is out of the queue: go on
        await loadNext();
        status(`not saved: ${e.message}`, "error");
      } else {  // answered or changed in another window: show the stored answer, to change it from there
        const r = await api("GET", `/api/item/${body.key}?view=${body.view}&reviewer=${encodeURIComponent(S.reviewer)}`);
        await show(r.item);
        status(`not saved: ${e.message}; this is the stored answer now`, "error");
      }
    }
    return;
  }
  sessionStorage.removeItem(DRAFT_KEY);
  try {  // saved: a failure from here on is about showing the next run, not about the answer
    const i = S.history.findIndex((a) => a.key === body.key && a.view === body.view);
    if (i >= 0) S.history[i] = r.answer; else S.history.push(r.answer);
    showCount(r.progress);
    status("saved", "ok");
    await loadNext();
  } catch (e) {
    status(`saved, but the next run cannot be shown: ${e.message}`, "error");
  }
}

async function skip() {
  if (!S.item || S.busy || S.pos !== null) return;
  S.busy = true;
  try { await api("POST", "/api/skip", { reviewer: S.reviewer, key: S.item.key, view: S.item.view }); await loadNext(); }
  catch (e) { status(`cannot skip: ${e.message}`, "error"); }
  finally { S.busy = false; }
}

async function back() {
  if (S.busy) return;
  if (!S.history.length) { status("no earlier answer to go back to"); return; }
  const pos = S.pos === null ? S.history.length - 1 : Math.max(0, S.pos - 1);
  try { await loadHistoryItem(pos); } catch (e) { status(`cannot go back: ${e.message}`, "error"); }
}

async function forward() {
  if (S.busy || S.pos === null) return;
  try { if (S.pos + 1 < S.history.length) await loadHistoryItem(S.pos + 1); else await loadNext(); }
  catch (e) { status(`cannot go forward: ${e.message}`, "error"); }
}

// --- playback -----------------------------------------------------------------------------------
function stopPlayback() { cancelAnimationFrame(S.raf); const v = $("video"); v.pause(); }

function play() {
  stopPlayback();
  const it = S.item, v = $("video"), flip = $("flip"), top = $("top");
  v.hidden = !it.video; flip.hidden = !it.frames || !!it.video; top.hidden = it.view !== "2d";
  $("progress").hidden = !Array.isArray(S.motion.progress);
  $("speed").textContent = `${S.speed}x`;
  if (it.video) {
    if (v.dataset.src !== it.video) { v.src = it.video; v.dataset.src = it.video; }
    v.currentTime = 0; v.playbackRate = S.speed;
    v.play().catch(() => {});
  } else if (it.frames) {
    S.frames = [];
    for (let i = 0; i < it.frames; i++) { const img = new Image(); img.src = `/api/media/${it.key}/frames/${i}`; S.frames.push(img); }
  }
  S.clock0 = performance.now();
  delete document.body.dataset.ended;
  const tick = () => {
    const t = now();
    draw(t);
    if (t >= S.item.duration) document.body.dataset.ended = "1";  // played to the end (tests, benchmark)
    S.raf = requestAnimationFrame(tick);
  };
  tick();
}

function now() {
  const d = S.item.duration;
  if (S.item.video) { const v = $("video"); return v.ended ? d : Math.min(d, v.currentTime); }
  return Math.min(d, (performance.now() - S.clock0) / 1000 * S.speed);
}

function changeSpeed(dir) {
  const t = now();
  S.speed = SPEEDS[Math.max(0, Math.min(SPEEDS.length - 1, SPEEDS.indexOf(S.speed) + dir))];
  $("speed").textContent = `${S.speed}x`;
  if (S.item && S.item.video) $("video").playbackRate = S.speed;
  else S.clock0 = performance.now() - t / S.speed * 1000;
}

function frameAt(t) {  // index of the last trajectory frame at or before t
  const ts = S.motion.t; let lo = 0, hi = ts.length - 1;
  while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (ts[mid] <= t + 1e-9) lo = mid; else hi = mid - 1; }
  return lo;
}

function segmentAt(k) {  // a chain run's clause holding frame k (null for a one-clause run)
  const segs = S.motion.segments;
  if (!Array.isArray(segs) || !segs.length) return null;
  return segs.find((s) => k >= s.first_frame && k <= s.last_frame) || segs[segs.length - 1];
}

function draw(t) {
  const k = frameAt(t), seg = segmentAt(k);
  if (seg && seg.text) {
    const line = `“${S.item.sentence}” — now ${seg.clause}/${S.motion.segments.length}: ${seg.text}`;
    if ($("sentence").textContent !== line) $("sentence").textContent = line;
  }
  if (S.item.view === "2d") drawTop(k);
  else if (!S.item.video && S.frames.length) drawFlip(t);
  if (Array.isArray(S.motion.progress)) drawProgress(k);
}

function drawFlip(t) {
  const fps = S.item.frame_fps || 10;
  const img = S.frames[Math.min(S.frames.length - 1, Math.floor(t * fps + 1e-6))];
  if (!img || !img.complete || !img.naturalWidth) return;
  const c = $("flip");
  if (c.width !== img.naturalWidth) { c.width = img.naturalWidth; c.height = img.naturalHeight; }
  c.getContext("2d").drawImage(img, 0, 0);
}

function drawTop(k) {
  // Top-down view: +x (away from the robot) points up, +y (the robot's left) points left.
  const c = $("top"), g = c.getContext("2d"), m = S.motion;
  let ext = 0.3;
  for (const o of Object.values(m.objects)) for (const p of o.poses) ext = Math.max(ext, Math.abs(p[0]) + o.size, Math.abs(p[1]) + o.size);
  const sc = (c.width / 2 - 10) / ext, cx = c.width / 2, cy = c.height / 2;
  const P = (x, y) => [cx - y * sc, cy - x * sc];
  g.clearRect(0, 0, c.width, c.height);
  g.setLineDash([4, 4]); g.strokeStyle = "#bbb"; g.beginPath(); g.arc(cx, cy, 0.25 * sc, 0, 2 * Math.PI); g.stroke(); g.setLineDash([]);
  g.fillStyle = "#888"; g.font = "12px sans-serif"; g.textAlign = "center"; g.fillText("robot", cx, c.height - 4);
  const seg = segmentAt(k), mover = seg ? seg.mover : m.mover, anchor = seg ? seg.anchor : m.anchor;
  const trail = m.objects[mover].poses;
  g.strokeStyle = "rgba(200,40,40,0.5)"; g.lineWidth = 2; g.beginPath();
  for (let i = seg ? seg.first_frame : 0; i <= k; i++) { const [u, v] = P(trail[i][0], trail[i][1]); if (i) g.lineTo(u, v); else g.moveTo(u, v); }
  g.stroke(); g.lineWidth = 1;
  for (const [name, o] of Object.entries(m.objects)) {
    const [x, y, yaw] = o.poses[k], h = o.size / 2, c0 = Math.cos(yaw), s0 = Math.sin(yaw);
    g.fillStyle = name === mover ? "#d33" : name === anchor ? "#2a2" : "#888";
    g.beginPath();
    [[h, h], [-h, h], [-h, -h], [h, -h]].forEach(([a, b], i) => {
      const [u, v] = P(x + a * c0 - b * s0, y + a * s0 + b * c0);
      if (i) g.lineTo(u, v); else g.moveTo(u, v);
    });
    g.closePath(); g.fill();
    const [u, v] = P(x, y); g.fillStyle = "#fff"; g.font = "bold 13px sans-serif"; g.textBaseline = "middle"; g.fillText(name, u, v);
  }
  g.textBaseline = "alphabetic";
}

function drawProgress(k) {
  // The action's learned progress per frame (the paper's Fig. 7), with the current frame marked.
  const c = $("progress"), g = c.getContext("2d"), m = S.motion, n = m.t.length, T = Math.max(m.t[n - 1], 1e-6);
  const L = 34, R = c.width - 6, top = 6, bot = c.height - 16;
  const X = (t) => L + (R - L) * t / T, Y = (p) => bot - (bot - top) * p;
  g.clearRect(0, 0, c.width, c.height);
  g.strokeStyle = "#ccc"; g.strokeRect(L, top, R - L, bot - top);
  g.fillStyle = "#666"; g.font = "11px sans-serif"; g.textAlign = "right";
  g.fillText("1", L - 4, top + 8); g.fillText("0", L - 4, bot);
  g.strokeStyle = "#2a8a4a"; g.lineWidth = 2; g.beginPath();
  let started = false;
  for (let i = 0; i < n; i++) {
    const p = m.progress[i]; if (p === null) continue;
    if (started) g.lineTo(X(m.t[i]), Y(p)); else { g.moveTo(X(m.t[i]), Y(p)); started = true; }
  }
  g.stroke(); g.lineWidth = 1;
  g.strokeStyle = "#d33"; g.beginPath(); g.moveTo(X(m.t[k]), top); g.lineTo(X(m.t[k]), bot); g.stroke();
  const p = m.progress[k];
  g.fillStyle = "#333"; g.textAlign = "left";
  g.fillText(`learned progress ${p === null ? "n/a" : p.toFixed(2)}   t = ${m.t[k].toFixed(1)} s`, L, c.height - 3);
}

// --- keyboard -----------------------------------------------------------------------------------
function onKey(e) {
  if (document.body.dataset.state === "login" || e.ctrlKey || e.metaKey || e.altKey) return;
  const comment = $("comment");
  if (document.activeElement === comment) {
    if (e.key === "Enter" && !e.shiftKey) { e.preventDefault(); comment.blur(); submit(); }
    else if (e.key === "Escape") comment.blur();
    return;
  }
  // A button or link reached with Tab does what it says on Enter or Space (Enter on a focused "skip" submitted
  // the grade; Space replayed the run). A button clicked with the mouse gives its focus back (below), so
  // Enter still submits after a grade picked with the mouse.
  const focused = document.activeElement;
  if (focused && (focused.tagName === "BUTTON" || focused.tagName === "A") && (e.key === "Enter" || e.key === " ")) return;
  const key = e.key;
  if (document.body.dataset.state === "done") {
    if (key === "ArrowLeft" || key === "Backspace") { e.preventDefault(); back(); }
    return;
  }
  let handled = true;
  if (/^[0-9]$/.test(key)) setGrade(Number(key));
  else if (key === "t") setGrade(10);
  else if (key === "Enter") submit();
  else if (key === "s") skip();
  else if (key === "ArrowLeft" || key === "Backspace") back();
  else if (key === "ArrowRight") forward();
  else if (key === " ") play();
  else if (key === "-") changeSpeed(-1);
  else if (key === "+" || key === "=") changeSpeed(1);
  else if (key === "/") comment.focus();
  else {
    const hit = S.config.mode === "blind" && S.config.labels.find((l) => l.key === key.toLowerCase());
    if (hit) setLabel(hit.label); else handled = false;
  }
  if (handled) e.preventDefault();
}

document.addEventListener("keydown", onKey);
document.addEventListener("click", (e) => {  // a mouse click (detail > 0) leaves no focus behind: the keys go on working
  const b = e.target instanceof Element && e.target.closest("button");
  if (b && e.detail > 0) b.blur();
});
$("login-form").addEventListener("submit", (e) => {
  e.preventDefault();
  const name = $("name").value.trim();
  if (!name) { $("name").value = ""; $("name").reportValidity(); return; }  // spaces only: say so, do not ignore it
  start(name).catch((err) => alert(`cannot start: ${err.message}`));
});
$("comment").addEventListener("input", keepDraft);
$("submit").onclick = submit;
$("skip").onclick = skip;
$("back").onclick = back;
init().catch((e) => { document.body.dataset.state = "error"; $("banner").textContent = `cannot start: ${e.message}`; $("banner").hidden = false; });
