"""``index.html`` of ``ddg-oracle check --report DIR``: one self-contained page to look at.

No network and no external file: the data (the records of ``results.json``) and
every script and style are inlined.  The page has the counts, filters by
status, implementation and catalog ID, the table of results, and for a clicked
non-passing result its message, expected vs observed, the bound, and a view of
its counterexample mesh:

- a mesh in R^3 is drawn in 3-D (drag to rotate, wheel to zoom), faces shaded,
  the failing element in red (a vertex, an edge, a face or a corner), boundary
  edges in orange (what R1.6 and the turning-angle sums are about);
- a planar case (every z = 0) is drawn in 2-D: the triangulation the
  implementation *returned* when the message names it (``result faces``), and
  the circle of an in-circle failure through its three points, the point inside
  it marked.

The viewer is a canvas with a painter's-algorithm renderer written here (no
WebGL, no library), so the page renders the same in any browser, headless too.
"""

from __future__ import annotations

import html
import json
from pathlib import Path

_PAGE = r"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>ddg-oracle check: __TITLE__</title>
<style>
body { font: 14px/1.4 system-ui, sans-serif; margin: 0; color: #222; }
header { padding: 10px 16px; background: #f3f4f6; border-bottom: 1px solid #ddd; }
h1 { font-size: 18px; margin: 0 0 4px 0; }
#counts span { margin-right: 14px; }
#filters { padding: 8px 16px; }
#filters label { margin-right: 12px; }
main { display: flex; gap: 12px; padding: 0 16px 16px 16px; }
#list { flex: 1 1 55%; max-height: 80vh; overflow: auto; }
#detail { flex: 1 1 45%; min-width: 420px; }
table { border-collapse: collapse; width: 100%; }
th, td { text-align: left; padding: 3px 6px; border-bottom: 1px solid #eee; }
tr.result { cursor: pointer; }
tr.result:hover { background: #eef4ff; }
tr.selected { background: #dbe7ff !important; }
.s-FAILED, .s-crashed, .s-internal { color: #b00020; font-weight: 600; }
.s-incomplete { color: #9a5b00; font-weight: 600; }
.s-tie { color: #8a5a00; } .s-convention { color: #555; } .s-passed { color: #1b7a1b; }
pre { white-space: pre-wrap; background: #fafafa; border: 1px solid #eee; padding: 6px;
      max-height: 30vh; overflow: auto; font-size: 12px; }
canvas { border: 1px solid #ccc; background: #fff; width: 100%; height: 420px; }
#errors { color: #b00020; }
</style></head>
<body>
<header><h1>ddg-oracle check</h1><div id="command"></div><div id="counts"></div></header>
<div id="filters">
  <label>status <select id="f-status"><option value="">all</option></select></label>
  <label>implementation <select id="f-impl"><option value="">all</option></select></label>
  <label>catalog ID <input id="f-id" size="10" placeholder="e.g. L4.3"></label>
  <label><input type="checkbox" id="f-na"> show not applicable</label>
</div>
<main>
  <div id="list"><table><thead><tr><th>ID</th><th>property</th><th>implementation</th>
    <th>status</th><th>examples</th><th>finding</th></tr></thead><tbody id="rows"></tbody></table></div>
  <div id="detail"><p id="hint">Click a result that did not pass to see its counterexample.</p>
    <div id="view" hidden>
      <h2 id="v-title" style="font-size:16px"></h2>
      <div id="v-values"></div>
      <canvas id="canvas" width="800" height="600"></canvas>
      <div id="v-legend" style="font-size:12px;color:#555"></div>
      <pre id="v-text"></pre>
    </div>
  </div>
</main>
<div id="errors"></div>
<script type="application/json" id="data">__DATA__</script>
<script>
"use strict";
window.addEventListener("error", function (e) {
  document.getElementById("errors").textContent += "error: " + e.message + "\n";
});
const DATA = JSON.parse(document.getElementById("data").textContent);
const RESULTS = DATA.results;
const KNOWN = DATA.known || {};
const $ = (id) => document.getElementById(id);

function statusClass(s) { return "s-" + s.split(" ")[0]; }

function init() {
  const c = DATA.command || {};
  $("command").textContent = "profile " + c.profile + (c.seed != null ? ", seed " + c.seed : "") +
    "; implementations: " + (c.implementations || []).join(", ");
  $("counts").innerHTML = Object.entries(DATA.counts).filter(([s, n]) => n)
    .map(([s, n]) => '<span class="' + statusClass(s) + '">' + n + " " + s + "</span>").join("");
  const statuses = [...new Set(RESULTS.map(r => r.status))];
  for (const s of statuses) $("f-status").add(new Option(s, s));
  for (const i of [...new Set(RESULTS.map(r => r.implementation))]) $("f-impl").add(new Option(i, i));
  for (const id of ["f-status", "f-impl", "f-id", "f-na"])
    for (const ev of ["input", "change"]) $(id).addEventListener(ev, render);
  render();
}

function visible(r) {
  const st = $("f-status").value, im = $("f-impl").value, id = $("f-id").value.trim();
  if (!$("f-na").checked && !st && r.status === "not applicable") return false;
  if (st && r.status !== st) return false;
  if (im && r.implementation !== im) return false;
  if (id && !r.property_id.split("/").some(p => p.trim().startsWith(id)) &&
      !r.property_id.startsWith(id)) return false;
  return true;
}

function render() {
  const body = $("rows");
  body.innerHTML = "";
  RESULTS.forEach((r, k) => {
    if (!visible(r)) return;
    const tr = document.createElement("tr");
    tr.className = "result";
    tr.dataset.index = k;
    const ran = r.status === "incomplete" ? r.examples + " of " + r.wanted : r.examples;
    for (const v of [r.property_id, r.property_name, r.implementation, r.status, ran,
                     KNOWN[k] || ""]) {
      const td = document.createElement("td");
      td.textContent = v;
      tr.appendChild(td);
    }
    tr.children[3].className = statusClass(r.status);
    tr.addEventListener("click", () => show(k));
    body.appendChild(tr);
  });
}

// ---- the viewer ---------------------------------------------------------------------
let view = null;

function show(k) {
  const r = RESULTS[k];
  document.querySelectorAll("tr.selected").forEach(t => t.classList.remove("selected"));
  const row = document.querySelector('tr[data-index="' + k + '"]');
  if (row) row.classList.add("selected");
  $("hint").hidden = true;
  $("view").hidden = false;
  $("view").dataset.index = k;
  $("v-title").textContent = "[" + r.property_id + "] " + r.implementation + ": " + r.status;
  const f = r.failure;
  let values = "";
  if (f) {
    values = "<div>" + esc(f.message) + "</div>";
    if (f.element != null) values += "<div>at: " + esc(JSON.stringify(f.element)) + "</div>";
    if (f.expected != null || f.observed != null)
      values += "<div>expected: <b>" + esc(JSON.stringify(f.expected)) + "</b>, observed: <b>" +
                esc(JSON.stringify(f.observed)) + "</b></div>";
    if (f.bound != null) values += "<div>error " + fmt(f.error) + " = " + fmt(f.error_in_bounds) +
                                   " x the derived bound " + fmt(f.bound) + "</div>";
  } else if (r.crash) {
    values = "<div>" + esc(r.crash) + "</div>";
  }
  if (r.note) values += "<div><i>" + esc(r.note) + "</i></div>";
  if (KNOWN[k]) values += "<div>documented finding <b>" + esc(KNOWN[k]) +
                          "</b> (docs/findings.md)</div>";
  $("v-values").innerHTML = values;
  $("v-text").textContent = (r.files ? "files: " + r.files.obj + ", " + r.files.snippet + "\n" : "") +
    (r.mesh && r.mesh.V ? "V = " + JSON.stringify(r.mesh.V) + "\nF = " + JSON.stringify(r.mesh.F) : "");
  view = r.mesh && r.mesh.V ? makeView(r) : null;
  draw();
}

function esc(s) { return String(s).replace(/[&<>]/g, c => ({"&": "&amp;", "<": "&lt;", ">": "&gt;"}[c])); }
function fmt(x) { return x == null ? "-" : Number(x).toPrecision(3); }

function makeView(r) {
  const V = r.mesh.V.map(p => [p[0], p[1], p.length > 2 ? p[2] : 0]);
  let F = r.mesh.F;
  const msg = (r.failure && r.failure.message) || r.crash || "";
  const planar = V.every(p => p[2] === 0);
  const res = msg.match(/result faces (\[\[[\d,\s\[\]]*\]\])/);
  if (res) { try { F = JSON.parse(res[1]); } catch (e) { /* keep the input's faces */ } }
  const ids = (r.failure && r.failure.element_ids) || {};
  const hl = {vertices: [], edges: [], faces: []};
  if (ids.vertex != null) hl.vertices.push(ids.vertex);
  if (ids.edge) hl.edges.push(ids.edge);
  if (ids.face != null) hl.faces.push(ids.face);
  let circle = null;
  const m = msg.match(/point (\d+) is inside the circle through \((\d+), (\d+)\) and (\d+)/);
  if (m) { circle = [+m[2], +m[3], +m[4]]; hl.vertices.push(+m[1]); hl.edges.push([+m[2], +m[3]]); }
  const em = msg.match(/edge \((\d+), (\d+)\)/);
  if (em && !m) hl.edges.push([+em[1], +em[2]]);
  // boundary edges: those of one face
  const count = new Map();
  for (const f of F) for (let c = 0; c < 3; c++) {
    const a = f[c], b = f[(c + 1) % 3], key = Math.min(a, b) + "," + Math.max(a, b);  // b: the corner after c
    count.set(key, (count.get(key) || 0) + 1);
  }
  const boundary = [...count].filter(([k, n]) => n === 1).map(([k]) => k.split(",").map(Number));
  // centre and scale
  const lo = [0, 1, 2].map(i => Math.min(...V.map(p => p[i])));
  const hi = [0, 1, 2].map(i => Math.max(...V.map(p => p[i])));
  const centre = [0, 1, 2].map(i => (lo[i] + hi[i]) / 2);
  const size = Math.max(1e-300, ...[0, 1, 2].map(i => hi[i] - lo[i]));
  const P = V.map(p => p.map((x, i) => (x - centre[i]) / size));
  return {P, F, planar, hl, circle, boundary, yaw: planar ? 0 : 0.6, pitch: planar ? 0 : -0.5,
          zoom: 1};
}

function project(v, p) {
  const cy = Math.cos(v.yaw), sy = Math.sin(v.yaw), cp = Math.cos(v.pitch), sp = Math.sin(v.pitch);
  const x = cy * p[0] + sy * p[2], z0 = -sy * p[0] + cy * p[2];
  const y = cp * p[1] - sp * z0, z = sp * p[1] + cp * z0;
  const cv = $("canvas"), s = 0.6 * Math.min(cv.width, cv.height) * v.zoom;
  return [cv.width / 2 + s * x, cv.height / 2 - s * y, z];
}

function draw() {
  const cv = $("canvas"), g = cv.getContext("2d");
  g.clearRect(0, 0, cv.width, cv.height);
  if (!view) { $("v-legend").textContent = "no mesh for this result"; return; }
  const v = view, Q = v.P.map(p => project(v, p));
  const order = v.F.map((f, k) => k).sort((a, b) =>
    (Q[v.F[a][0]][2] + Q[v.F[a][1]][2] + Q[v.F[a][2]][2]) -
    (Q[v.F[b][0]][2] + Q[v.F[b][1]][2] + Q[v.F[b][2]][2]));
  for (const k of order) {
    const f = v.F[k];
    const a = v.P[f[0]], b = v.P[f[1]], c = v.P[f[2]];
    const n = cross(sub(b, a), sub(c, a)), len = Math.hypot(...n) || 1;
    const shade = v.planar ? 0.92 : 0.55 + 0.4 * Math.abs(n[2] * Math.cos(v.pitch) + n[0] * 0.3) / len;
    g.beginPath();
    g.moveTo(Q[f[0]][0], Q[f[0]][1]); g.lineTo(Q[f[1]][0], Q[f[1]][1]); g.lineTo(Q[f[2]][0], Q[f[2]][1]);
    g.closePath();
    g.fillStyle = v.hl.faces.includes(k) ? "rgba(220,40,40,0.75)"
      : "rgb(" + [120, 160, 210].map(x => Math.round(x * shade + 255 * (1 - shade) * 0.3)).join(",") + ")";
    g.fill();
    g.strokeStyle = "#445"; g.lineWidth = 1; g.stroke();
  }
  const line = (i, j, colour, width) => {
    g.beginPath(); g.moveTo(Q[i][0], Q[i][1]); g.lineTo(Q[j][0], Q[j][1]);
    g.strokeStyle = colour; g.lineWidth = width; g.stroke();
  };
  for (const [i, j] of v.boundary) line(i, j, "#f08c00", 3);
  for (const [i, j] of v.hl.edges) if (i < Q.length && j < Q.length) line(i, j, "#d00", 4);
  if (v.circle && v.planar) {
    const [A, B, C] = v.circle.map(i => Q[i]);
    const cc = circumcentre(A, B, C);
    if (cc) { g.beginPath(); g.arc(cc[0], cc[1], Math.hypot(A[0] - cc[0], A[1] - cc[1]), 0, 2 * Math.PI);
              g.strokeStyle = "#0a7"; g.lineWidth = 2; g.stroke(); }
  }
  Q.forEach((q, i) => {
    const hot = v.hl.vertices.includes(i);
    g.beginPath(); g.arc(q[0], q[1], hot ? 6 : 3, 0, 2 * Math.PI);
    g.fillStyle = hot ? "#d00" : "#223"; g.fill();
    g.fillStyle = "#000"; g.font = "12px sans-serif"; g.fillText(String(i), q[0] + 5, q[1] - 5);
  });
  $("v-legend").textContent = (v.planar ? "planar: drawn in 2-D" : "drag to rotate, wheel to zoom") +
    "; red: the failing element; orange: boundary edges" + (v.circle ? "; green: the circle" : "");
}

function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function circumcentre(A, B, C) {
  const d = 2 * (A[0] * (B[1] - C[1]) + B[0] * (C[1] - A[1]) + C[0] * (A[1] - B[1]));
  if (!d) return null;
  const a2 = A[0] ** 2 + A[1] ** 2, b2 = B[0] ** 2 + B[1] ** 2, c2 = C[0] ** 2 + C[1] ** 2;
  return [(a2 * (B[1] - C[1]) + b2 * (C[1] - A[1]) + c2 * (A[1] - B[1])) / d,
          (a2 * (C[0] - B[0]) + b2 * (A[0] - C[0]) + c2 * (B[0] - A[0])) / d];
}

let drag = null;
$("canvas").addEventListener("mousedown", e => { drag = [e.clientX, e.clientY]; });
window.addEventListener("mouseup", () => { drag = null; });
window.addEventListener("mousemove", e => {
  if (!drag || !view || view.planar) return;
  view.yaw += (e.clientX - drag[0]) * 0.01; view.pitch += (e.clientY - drag[1]) * 0.01;
  drag = [e.clientX, e.clientY]; draw();
});
$("canvas").addEventListener("wheel", e => {
  if (!view) return;
  e.preventDefault(); view.zoom *= Math.exp(-e.deltaY * 0.001); draw();
}, {passive: false});

init();
if (location.hash.startsWith("#result-")) show(+location.hash.slice(8));
</script>
</body></html>
"""


def write_html(directory, results_json: str, known: dict | None = None) -> Path:
    """Write ``index.html`` for ``results_json`` (the text of results.json); ``known`` maps
    a result's index to the documented finding it is (docs/findings.md), shown beside it."""
    path = Path(directory) / "index.html"
    doc = json.loads(results_json)
    if known:
        doc["known"] = {str(i): k for i, k in known.items()}
        results_json = json.dumps(doc, sort_keys=True)
    data = results_json.replace("</", "<\\/")          # safe inside <script>
    title = html.escape(", ".join(f"{n} {s}" for s, n in doc.get("counts", {}).items() if n))
    path.write_text(_PAGE.replace("__TITLE__", title).replace("__DATA__", data),
                    encoding="utf-8")
    return path
