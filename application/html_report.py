"""``index.html`` of ``ddg-oracle check --report DIR``: one self-contained page to look at.

No network and no external file but the report's own PNGs: the data (the records of
``results.json`` and what the page adds: the command line, the root causes, the catalog
statements and errata, the findings' text, the replay snippets, the neighbourhood of a
mesh file's failing element) and every script and style are inlined.  The page:

- a header naming the run: profile, seed, implementations, meshes, the command line,
  the counts;
- the root causes first (:func:`ddg_oracle.application.causes.root_causes`: the failures of one
  implementation that one protocol method explains, with its wrong answer; crashes
  with one message), each a link to its smallest counterexample;
- a heatmap, property x implementation, one coloured cell per result;
- the table of results, failures first, with a message column, sortable by any column
  and filtered by status, implementation and catalog ID (typed filters never rebuild
  the rows under the pointer: a click right after typing selects);
- for a clicked result: the statement from the notes (catalog ID, text, the erratum
  when there is one), expected vs observed with the error in units of its bound, the
  documented finding's text, a copyable replay snippet, the PNG the run wrote, and a
  viewer of its counterexample: a mesh in R^3 in 3-D (drag to rotate, wheel to zoom,
  one scale on both axes), the failing element in red and the boundary edges in orange;
  a planar case in 2-D with the triangulation the implementation returned and the
  circle of an in-circle failure; for a mesh file, the faces around the failing element
  (the whole mesh when it is small).

The viewer is a canvas with a painter's-algorithm renderer written here (no WebGL, no
library), so the page renders the same in any browser, headless too.
"""

from __future__ import annotations

import html
import json
import re
from pathlib import Path

_PAGE = r"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>ddg-oracle check: __TITLE__</title>
<style>
body { font: 14px/1.4 system-ui, sans-serif; margin: 0; color: #222; }
header { padding: 10px 16px; background: #f3f4f6; border-bottom: 1px solid #ddd; }
h1 { font-size: 18px; margin: 0 0 4px 0; }
h2 { font-size: 15px; margin: 12px 0 4px 0; }
code, pre { font-family: ui-monospace, monospace; }
#run { font-size: 12px; color: #444; word-break: break-word; }
#counts span { margin-right: 14px; }
section { padding: 4px 16px; }
#causes li { margin: 2px 0; cursor: pointer; }
#causes li:hover { background: #eef4ff; }
#heatmap table { border-collapse: collapse; font-size: 11px; }
#heatmap td, #heatmap th { border: 1px solid #fff; padding: 1px 4px; white-space: nowrap; }
#heatmap td.cell { width: 16px; height: 14px; cursor: pointer; }
#filters { padding: 8px 16px; }
#filters label { margin-right: 12px; }
main { display: flex; gap: 12px; padding: 0 16px 16px 16px; align-items: flex-start; }
#list { flex: 1 1 55%; min-width: 0; max-height: 80vh; overflow: auto; }
#detail { flex: 1 1 45%; min-width: 0; }
@media (max-width: 1200px) {
  main { flex-direction: column; }
  #list, #detail { flex: 1 1 auto; width: 100%; max-height: none; }
}
table.results { border-collapse: collapse; width: 100%; table-layout: fixed; }
table.results col.c-id { width: 7.5em; } table.results col.c-impl { width: 11em; }
table.results col.c-status { width: 7.5em; } table.results col.c-examples { width: 6em; }
table.results col.c-finding { width: 7.5em; }
table.results td { overflow-wrap: anywhere; }
table.results th, table.results td { text-align: left; padding: 3px 6px;
  border-bottom: 1px solid #eee; vertical-align: top; }
table.results th { cursor: pointer; user-select: none; position: sticky; top: 0; background: #fff; }
td.msg { max-width: 40ch; overflow: hidden; text-overflow: ellipsis; white-space: nowrap; }
tr.result { cursor: pointer; }
tr.result:hover { background: #eef4ff; }
tr.selected { background: #dbe7ff !important; }
.s-FAILED, .s-crashed, .s-internal { color: #b00020; font-weight: 600; }
.s-incomplete { color: #9a5b00; font-weight: 600; }
.s-tie { color: #8a5a00; } .s-convention { color: #555; } .s-passed { color: #1b7a1b; }
.c-FAILED, .c-crashed, .c-internal { background: #d93a3a; } .c-incomplete { background: #e8a33d; }
.c-tie, .c-undecided { background: #f1d38a; } .c-convention { background: #b9b9b9; }
.c-passed { background: #7fc47f; } .c-not { background: #eeeeee; }
pre { white-space: pre-wrap; background: #fafafa; border: 1px solid #eee; padding: 6px;
      max-height: 30vh; overflow: auto; font-size: 12px; }
canvas { border: 1px solid #ccc; background: #fff; width: 100%; height: 420px; display: block; }
#v-png { max-width: 100%; border: 1px solid #eee; }
#errors { color: #b00020; }
button { font-size: 12px; }
</style></head>
<body>
<header><h1>ddg-oracle check</h1><div id="run"></div><div id="counts"></div></header>
<section id="causes-box" hidden><h2>Root causes</h2><ul id="causes"></ul></section>
<section id="heatmap"><h2>Property x implementation</h2><div id="grid"></div></section>
<div id="filters">
  <label>status <select id="f-status"><option value="">all</option></select></label>
  <label>implementation <select id="f-impl"><option value="">all</option></select></label>
  <label>catalog ID <input id="f-id" size="10" placeholder="e.g. L4.3"></label>
  <label><input type="checkbox" id="f-na"> show not applicable</label>
</div>
<main>
  <div id="list"><table class="results"><colgroup><col class="c-id"><col class="c-impl">
    <col class="c-status"><col class="c-msg"><col class="c-examples"><col class="c-finding">
    </colgroup><thead><tr><th data-key="id">ID</th>
    <th data-key="impl">implementation</th><th data-key="status">status</th>
    <th data-key="msg">message</th><th data-key="examples">examples</th>
    <th data-key="finding">finding</th></tr></thead><tbody id="rows"></tbody></table></div>
  <div id="detail"><p id="hint">Click a result that did not pass to see its counterexample.</p>
    <div id="view" hidden>
      <h2 id="v-title"></h2>
      <div id="v-statement"></div>
      <div id="v-values"></div>
      <div id="v-finding"></div>
      <canvas id="canvas"></canvas>
      <div id="v-legend" style="font-size:12px;color:#555"></div>
      <div id="v-snippet-box" hidden><h2>Replay <button id="copy">copy</button></h2>
        <pre id="v-snippet"></pre></div>
      <img id="v-png" hidden alt="the picture this run wrote">
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
const PAGE = DATA.page || {};
const $ = (id) => document.getElementById(id);
const SEVERITY = ["internal error", "FAILED", "crashed", "incomplete", "tie disagreement",
                  "undecided", "convention", "passed", "not applicable"];

function statusClass(s) { return "s-" + s.split(" ")[0]; }
function esc(s) { return String(s).replace(/[&<>"]/g, c => ({"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;"}[c])); }
function fmt(x) { return x == null ? "-" : Number(x).toPrecision(3); }
function message(r) {
  const t = (r.failure && r.failure.message) || r.crash
    || (r.status !== "passed" || r.unjudged ? r.note : "") || "";
  return t.split("\n")[0];
}

// ---- header, causes, heatmap ---------------------------------------------------------
function init() {
  const c = DATA.command || {};
  const parts = ["profile " + c.profile + (c.seed != null ? ", seed " + c.seed : "")];
  parts.push("implementations: " + (c.implementations || []).join(", "));
  if (c.meshes) parts.push("meshes: " + c.meshes.join(", "));
  if (PAGE.argv) parts.push("command: ddg-oracle check " + PAGE.argv.join(" "));
  if (DATA.interrupted) parts.push("INTERRUPTED: a partial report");
  $("run").textContent = parts.join(" \u00b7 ");
  $("counts").innerHTML = Object.entries(DATA.counts).filter(([s, n]) => n)
    .map(([s, n]) => '<span class="' + statusClass(s) + '">' + n + " " + esc(s) + "</span>").join("");
  const causes = PAGE.causes || [];
  if (causes.length) {
    $("causes-box").hidden = false;
    for (const cause of causes) {
      const li = document.createElement("li");
      li.textContent = cause.text;
      li.addEventListener("click", () => select(cause.first));
      $("causes").appendChild(li);
    }
  }
  heatmap();
  const statuses = [...new Set(RESULTS.map(r => r.status))];
  for (const s of statuses) $("f-status").add(new Option(s, s));
  for (const i of [...new Set(RESULTS.map(r => r.implementation))]) $("f-impl").add(new Option(i, i));
  // selects and the checkbox: "change"; the typed ID: "input" only (a "change" fired by the
  // blur of a click on a row must not touch the rows under the pointer)
  for (const id of ["f-status", "f-impl", "f-na"]) $(id).addEventListener("change", filter);
  $("f-id").addEventListener("input", filter);
  for (const th of document.querySelectorAll("table.results th"))
    th.addEventListener("click", () => sortBy(th.dataset.key));
  buildRows();
  filter();
}

function heatmap() {
  const ids = [...new Set(RESULTS.map(r => r.property_id))];
  const impls = [...new Set(RESULTS.map(r => r.implementation))];
  const at = new Map(RESULTS.map((r, k) => [r.property_id + "\u0000" + r.implementation, k]));
  let h = "<table><tr><th></th>" + impls.map(i => "<th>" + esc(i) + "</th>").join("") + "</tr>";
  for (const id of ids) {
    h += "<tr><th>" + esc(id) + "</th>";
    for (const im of impls) {
      const k = at.get(id + "\u0000" + im);
      const s = k == null ? "" : RESULTS[k].status;
      h += k == null ? "<td></td>" : '<td class="cell c-' + esc(s.split(" ")[0]) +
           '" data-index="' + k + '" title="' + esc(id + " " + im + ": " + s) + '"></td>';
    }
    h += "</tr>";
  }
  $("grid").innerHTML = h + "</table>";
  for (const td of document.querySelectorAll("#grid td.cell"))
    td.addEventListener("click", () => select(+td.dataset.index));
}

// ---- the table: rows built once, then only shown, hidden and reordered ------------------
const ROWS = [];
let order = {key: "status", dir: 1};

function cells(r, k) {
  const ran = r.status === "incomplete" ? r.examples + " of " + r.wanted
    : r.unjudged ? r.examples + " (" + r.unjudged + " partly judged)" : r.examples;
  return {id: r.property_id, impl: r.implementation, status: r.status, msg: message(r),
          examples: ran, finding: KNOWN[k] || ""};
}

function buildRows() {
  RESULTS.forEach((r, k) => {
    const tr = document.createElement("tr");
    tr.className = "result";
    tr.dataset.index = k;
    const c = cells(r, k);
    for (const key of ["id", "impl", "status", "msg", "examples", "finding"]) {
      const td = document.createElement("td");
      td.textContent = c[key];
      if (key === "msg") { td.className = "msg"; td.title = c.msg; }
      if (key === "status") td.className = statusClass(r.status);
      tr.appendChild(td);
    }
    tr.addEventListener("click", () => show(k));
    ROWS.push({tr, k, c});
  });
  sortBy("status", 1);
}

function sortBy(key, dir) {
  order = {key, dir: dir || (order.key === key ? -order.dir : 1)};
  const rank = (x) => key === "status" ? SEVERITY.indexOf(x.c.status)
    : key === "examples" ? +String(x.c.examples).split(" ")[0] : String(x.c[key]);
  ROWS.sort((a, b) => {
    const p = rank(a), q = rank(b);
    return (p < q ? -1 : p > q ? 1 : a.k - b.k) * (p === q ? 1 : order.dir);
  });
  const body = $("rows");
  for (const row of ROWS) body.appendChild(row.tr);          // moves, keeps the nodes
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

function filter() { for (const row of ROWS) row.tr.hidden = !visible(RESULTS[row.k]); }

// ---- one result ---------------------------------------------------------------------------
let view = null;

function select(k) {
  const r = RESULTS[k];
  if (r.status === "not applicable") $("f-na").checked = true;
  filter();
  show(k);
  const row = document.querySelector('tr[data-index="' + k + '"]');
  if (row) row.scrollIntoView({block: "nearest"});
}

function show(k) {
  const r = RESULTS[k];
  document.querySelectorAll("tr.selected").forEach(t => t.classList.remove("selected"));
  const row = document.querySelector('tr[data-index="' + k + '"]');
  if (row) row.classList.add("selected");
  $("hint").hidden = true;
  $("view").hidden = false;
  $("view").dataset.index = k;
  $("v-title").textContent = "[" + r.property_id + "] " + r.implementation + ": " + r.status +
    (r.source !== "generated" ? " on " + r.source : "");
  const st = (PAGE.statements || {})[r.property_id] || [];
  $("v-statement").innerHTML = (r.statement ? "<div><i>" + esc(r.statement) + "</i></div>" : "") +
    st.map(s => "<div><b>" + esc(s.id) + "</b> (the notes): " + esc(s.statement) +
      (s.erratum ? ' <details><summary>erratum ' + esc(s.erratum) +
       '</summary><pre>' + esc((PAGE.errata || {})[s.erratum] || "") + "</pre></details>" : "") +
      "</div>").join("");
  const f = r.failure;
  let values = "";
  if (f) {
    values = "<div>" + esc(f.message) + "</div>";
    if (f.element != null) values += "<div>at: " + esc(JSON.stringify(f.element)) + "</div>";
    if (f.expected != null || f.observed != null)
      values += "<div>expected: <b>" + esc(JSON.stringify(f.expected)) + "</b>, observed: <b>" +
                esc(JSON.stringify(f.observed)) + "</b></div>";
    // the error in units of the bound only where both are numbers
    if (f.bound != null && f.error != null)
      values += "<div>error " + fmt(f.error) + " = " + fmt(f.error_in_bounds) +
                " x the derived bound " + fmt(f.bound) + "</div>";
    else if (f.bound != null) values += "<div>derived bound " + fmt(f.bound) + "</div>";
  } else if (r.crash) {
    values = "<div>" + esc(r.crash) + "</div>";
  }
  const cause = (PAGE.cause_of || {})[k];
  if (cause) values += "<div>root cause: <b>" + esc(cause) + "</b></div>";
  if (r.note) values += "<div><i>" + esc(r.note) + "</i></div>";
  $("v-values").innerHTML = values;
  const known = KNOWN[k];
  $("v-finding").innerHTML = known ? "<div>documented finding <b>" + esc(known) +
    "</b> (docs/findings.md)</div><details><summary>" + esc(known) + "</summary><pre>" +
    esc((PAGE.findings || {})[known] || "") + "</pre></details>" : "";
  const snippet = (PAGE.snippets || {})[k];
  $("v-snippet-box").hidden = !snippet;
  $("v-snippet").textContent = snippet || "";
  const png = r.files && r.files.png;
  $("v-png").hidden = !png;
  if (png) $("v-png").src = png;
  const hood = (PAGE.neighbourhoods || {})[k];
  const mesh = r.mesh && r.mesh.V ? r.mesh : hood;
  $("v-text").textContent = (r.files ? "files: " + r.files.obj + ", " + r.files.snippet + "\n" : "") +
    (hood ? hood.about + "\n" : "") +
    (mesh ? "V = " + JSON.stringify(mesh.V) + "\nF = " + JSON.stringify(mesh.F) : "");
  view = mesh ? makeView(r, mesh) : null;
  draw();
}

$("copy").addEventListener("click", () => {
  const text = $("v-snippet").textContent;
  if (navigator.clipboard) navigator.clipboard.writeText(text).catch(() => {});
  const range = document.createRange();
  range.selectNodeContents($("v-snippet"));
  const sel = window.getSelection(); sel.removeAllRanges(); sel.addRange(range);
});

// ---- the viewer -----------------------------------------------------------------------
function makeView(r, mesh) {
  const V = mesh.V.map(p => [p[0], p[1], p.length > 2 ? p[2] : 0]);
  let F = mesh.F;
  const msg = (r.failure && r.failure.message) || r.crash || "";
  const planar = V.every(p => p[2] === 0);
  const res = msg.match(/result faces (\[\[[\d,\s\[\]]*\]\])/);
  if (res && !mesh.map) { try { F = JSON.parse(res[1]); } catch (e) { /* the input's faces */ } }
  // a mesh file's neighbourhood renumbers its vertices: mesh.map[file index] = ours
  const to = (i) => mesh.map ? mesh.map[i] : i;
  const ids = (r.failure && r.failure.element_ids) || {};
  const hl = {vertices: [], edges: [], faces: []};
  if (ids.vertex != null && to(ids.vertex) != null) hl.vertices.push(to(ids.vertex));
  if (ids.edge && to(ids.edge[0]) != null && to(ids.edge[1]) != null)
    hl.edges.push([to(ids.edge[0]), to(ids.edge[1])]);
  if (ids.face != null && mesh.faces_map && mesh.faces_map[ids.face] != null)
    hl.faces.push(mesh.faces_map[ids.face]);
  else if (ids.face != null && !mesh.map) hl.faces.push(ids.face);
  let circle = null;
  const m = msg.match(/point (\d+) is inside the circle through \((\d+), (\d+)\) and (\d+)/);
  if (m && !mesh.map) { circle = [+m[2], +m[3], +m[4]]; hl.vertices.push(+m[1]); hl.edges.push([+m[2], +m[3]]); }
  const em = msg.match(/edge \((\d+), (\d+)\)/);
  if (em && !m && to(+em[1]) != null && to(+em[2]) != null) hl.edges.push([to(+em[1]), to(+em[2])]);
  const count = new Map();
  for (const f of F) for (let c = 0; c < 3; c++) {
    const a = f[c], b = f[(c + 1) % 3], key = Math.min(a, b) + "," + Math.max(a, b);
    count.set(key, (count.get(key) || 0) + 1);
  }
  const boundary = mesh.map ? [] :       // a cut-out neighbourhood's rim is not a boundary
    [...count].filter(([k, n]) => n === 1).map(([k]) => k.split(",").map(Number));
  if (mesh.map) faceTheViewer(V, F);        // a patch of a larger surface: seen from above
  const lo = [0, 1, 2].map(i => Math.min(...V.map(p => p[i])));
  const hi = [0, 1, 2].map(i => Math.max(...V.map(p => p[i])));
  const centre = [0, 1, 2].map(i => (lo[i] + hi[i]) / 2);
  const size = Math.max(1e-300, ...[0, 1, 2].map(i => hi[i] - lo[i]));
  const P = V.map(p => p.map((x, i) => (x - centre[i]) / size));
  const flat = planar || !!mesh.map;
  return {P, F, planar, hl, circle, boundary, yaw: flat ? 0 : 0.6, pitch: flat ? 0 : -0.5,
          zoom: 1, labels: V.length <= 60};
}

function faceTheViewer(V, F) {
  // rotate V in place so that the faces' mean normal points along +z (Rodrigues' formula)
  let n = [0, 0, 0];
  for (const f of F) {
    const c = cross(sub(V[f[1]], V[f[0]]), sub(V[f[2]], V[f[0]]));
    n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
  }
  const len = Math.hypot(...n);
  if (!len) return;
  n = n.map(x => x / len);
  const k = cross(n, [0, 0, 1]), s = Math.hypot(...k), c = n[2];
  if (s < 1e-12) { if (c < 0) for (const p of V) { p[1] = -p[1]; p[2] = -p[2]; } return; }
  const u = k.map(x => x / s);
  for (const p of V) {
    const d = u[0] * p[0] + u[1] * p[1] + u[2] * p[2], w = cross(u, p);
    for (let i = 0; i < 3; i++) p[i] = p[i] * c + w[i] * s + u[i] * d * (1 - c);
  }
}

function fitCanvas() {
  // the drawing buffer is the canvas's own displayed size: one scale on both axes
  const cv = $("canvas"), box = cv.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(box.width * dpr)), h = Math.max(1, Math.round(box.height * dpr));
  if (cv.width !== w || cv.height !== h) { cv.width = w; cv.height = h; }
}

function project(v, p) {
  const cy = Math.cos(v.yaw), sy = Math.sin(v.yaw), cp = Math.cos(v.pitch), sp = Math.sin(v.pitch);
  const x = cy * p[0] + sy * p[2], z0 = -sy * p[0] + cy * p[2];
  const y = cp * p[1] - sp * z0, z = sp * p[1] + cp * z0;
  const cv = $("canvas"), s = 0.8 * Math.min(cv.width, cv.height) * v.zoom;
  return [cv.width / 2 + s * x, cv.height / 2 - s * y, z];
}

function draw() {
  fitCanvas();
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
    if (!hot && !v.labels) return;
    g.beginPath(); g.arc(q[0], q[1], hot ? 6 : 3, 0, 2 * Math.PI);
    g.fillStyle = hot ? "#d00" : "#223"; g.fill();
    if (v.labels) { g.fillStyle = "#000"; g.font = "12px sans-serif"; g.fillText(String(i), q[0] + 5, q[1] - 5); }
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
window.addEventListener("resize", () => { if (!$("view").hidden) draw(); });

init();
if (location.hash.startsWith("#result-")) select(+location.hash.slice(8));
</script>
</body></html>
"""

#: a mesh file's failure shows the faces this many rings around its failing element, or the
#: whole mesh when it has at most FACES_WHOLE faces
RINGS, FACES_WHOLE = 3, 2000


def neighbourhood(V, F, element_ids: dict | None) -> dict | None:
    """The part of a mesh file around a failing element (``element_ids``: a vertex, an edge
    or a face of the file), :data:`RINGS` rings of faces, renumbered: ``{"V", "F", "map"
    (file vertex -> ours), "faces_map" (file face -> ours), "about"}``; the whole mesh when
    it is small, None when it is large and the failure names no element."""
    n_faces = len(F)
    seeds = set()
    ids = element_ids or {}
    if ids.get("vertex") is not None:
        seeds.add(int(ids["vertex"]))
    if ids.get("edge"):
        seeds.update(int(v) for v in ids["edge"])
    if ids.get("face") is not None and 0 <= int(ids["face"]) < n_faces:
        seeds.update(int(v) for v in F[int(ids["face"])])
    if n_faces <= FACES_WHOLE:
        keep = list(range(n_faces))
        about = f"the whole mesh: {len(V)} vertices, {n_faces} faces"
    elif seeds:
        by_vertex: dict = {}
        for f, face in enumerate(F):
            for v in face:
                by_vertex.setdefault(int(v), []).append(f)
        verts, faces = set(seeds), set()
        for _ in range(RINGS):
            ring = {f for v in verts for f in by_vertex.get(v, ())} - faces
            faces |= ring
            verts |= {int(v) for f in ring for v in F[f]}
        keep = sorted(faces)
        about = (f"{len(keep)} of the mesh's {n_faces} faces: {RINGS} rings around the failing "
                 "element")
    else:
        return None
    used = sorted({int(v) for f in keep for v in F[f]})
    ours = {v: k for k, v in enumerate(used)}
    return {"V": [[float(c) for c in V[v]] for v in used],
            "F": [[ours[int(v)] for v in F[f]] for f in keep],
            "map": {str(v): k for v, k in ours.items()},
            "faces_map": {str(f): k for k, f in enumerate(keep)}, "about": about}


def _statements() -> tuple[dict, dict]:
    """({catalog ID part: [{"id", "statement", "erratum"}]}, {erratum ID: its text}) from the
    traceability table and docs/errata.md (both installed as package data)."""
    from . import traceability
    _, entries = traceability.load()
    by_id = {e.id: {"id": e.id, "statement": e.statement, "erratum": e.erratum}
             for e in entries}
    text = (traceability.DATA / "errata.md").read_text(encoding="utf-8")
    errata = {m[1]: m[0].strip() for m in re.finditer(r"^## (ER-\d+):.*?(?=^## |\Z)", text,
                                                     re.M | re.S)}
    return by_id, errata


def _findings_text() -> dict:
    """{finding ID: its section of docs/findings.md (installed as package data)}."""
    path = Path(__file__).with_name("data") / "findings.md"
    text = path.read_text(encoding="utf-8")
    return {m[1]: m[0].strip() for m in re.finditer(r"^## (F-[\w-]+)\n.*?(?=^## |\Z)", text,
                                                    re.M | re.S)}


def page_data(results, known: dict, argv=None, snippets: dict | None = None) -> dict:
    """What the page shows beyond results.json (which stays byte-identical across runs):
    the command line, the root causes, the notes' statements and errata of each catalog
    ID, the documented findings' text, the replay snippets and, for mesh-file failures,
    the neighbourhood of the failing element (a mesh file's result carries its mesh)."""
    from .causes import element_ids, group_hint, root_causes
    causes, crashes = root_causes(results)
    by_id, errata = _statements()
    cause_text, cause_of = [], {}
    for c in causes:
        blame = " or ".join(c.methods) or "an answer"
        hint = group_hint(results, c.members)
        text = (f"{c.implementation}: {blame} wrong, {len(c.members)} "
                f"propert{'ies' if len(c.members) != 1 else 'y'}" + (f"; {c.where}" if c.where else "")
                + (f"; {hint}" if hint else ""))
        cause_text.append({"text": text, "first": c.first})
        for k in c.members:
            cause_of[str(k)] = f"{c.implementation}: {blame} wrong"
    for c in crashes:
        first = (results[c.first].error or "").splitlines()[0] if results[c.first].error else ""
        cause_text.append({"text": f"{c.implementation} crashed {len(c.members)} time"
                                   f"{'s' if len(c.members) != 1 else ''}: {first[:160]}",
                           "first": c.first})
    statements = {}
    for r in results:
        parts = [x.strip() for x in r.property_id.split("/")]
        statements[r.property_id] = [by_id[p] for p in parts if p in by_id]
    used = set(known.values())
    findings = {k: v for k, v in _findings_text().items() if k in used}
    needed = {s["erratum"] for rows in statements.values() for s in rows if s["erratum"]}
    hoods = {}
    for k, r in enumerate(results):
        if r.source != "generated" and r.mesh is not None and \
                r.status not in ("passed", "not applicable"):
            V, F = r.mesh
            ids = element_ids(r.failure.element) if r.failure is not None else None
            hood = neighbourhood(V, F, ids)
            if hood is not None:
                hoods[str(k)] = hood
    return {"argv": list(argv or []), "causes": cause_text, "cause_of": cause_of,
            "statements": statements, "errata": {e: errata.get(e, "") for e in needed},
            "findings": findings, "snippets": {str(k): s for k, s in (snippets or {}).items()},
            "neighbourhoods": hoods}


def write_html(directory, results_json: str, known: dict | None = None,
               page: dict | None = None) -> Path:
    """Write ``index.html`` for ``results_json`` (the text of results.json); ``known`` maps
    a result's index to the documented finding it is (docs/findings.md), shown beside it;
    ``page``: what :func:`page_data` adds."""
    path = Path(directory) / "index.html"
    doc = json.loads(results_json)
    if known:
        doc["known"] = {str(i): k for i, k in known.items()}
    if page:
        doc["page"] = page
    data = json.dumps(doc, sort_keys=True).replace("</", "<\\/")     # safe inside <script>
    title = html.escape(", ".join(f"{n} {s}" for s, n in doc.get("counts", {}).items() if n))
    from .files import write_atomically
    write_atomically(path, _PAGE.replace("__TITLE__", title).replace("__DATA__", data))
    return path
