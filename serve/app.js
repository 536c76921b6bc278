// hilite serve's page: plain JS, no build step. Controls come from /api/registry; every change asks the
// server to measure and render both materials (/api/render) and draws the answer.
"use strict";

const SIDES = ["a", "b"];
// Material parameters are per side; every other table's are shared by both sides.
const MATERIAL_TABLE = "material";
// The starting pair: Phong against GGX, Fresnel off and f proportional to D (the eccentricity experiment's
// scene), A's exponent matched to B's width at normal incidence by /api/match.
const START = {
  a: { model: "phong", fresnel: "none", geometry: "implicit" },
  b: { model: "ggx", roughness: "0.1", fresnel: "none", geometry: "implicit" },
  shared: { size: "256" },
};
// The analysis's flags in words (analysis/highlight.hpp).
const FLAG_WORDS = {
  clipped: "the region touches the frame's border: it may go on outside it",
  horizon_cut: "the region ends at the horizon, not at the half-maximum level",
  under_resolved: "too few pixels across the minor axis",
  no_highlight: "no highlight: the peak is 0 or not visible",
  covers_frame: "every visible pixel is in the region: the frame shows no outside",
  mirror: "a perfect mirror: the lobe is a delta with no finite shape",
  effectively_mirror: "narrower than float32 directions resolve: the numbers are quantization-limited",
  unbounded_at_horizon: "the lobe grows without bound towards the horizon: no half-maximum region",
  not_star_shaped: "the region is not star-shaped about its peak (a ring, two lobes)",
  parts_not_measured: "parts of the region were not measured",
  not_converged: "the reference's quadrature ran out of budget",
  light_undersampled: "the light's rule is too sparse for the lobe (raise light rings)",
  float_overflow: "the radiance left float32's range: shape not measured",
  float_underflow: "the region's level is below float32's smallest normal: shape not measured",
  peak_on_horizon: "the peak is on the horizon",
  no_mirror_lobe: "no lobe about the mirror direction",
  saddle_cut: "the region is cut at a saddle between lobes",
};

const state = {
  registry: [],
  values: { a: { ...START.a }, b: { ...START.b }, shared: { ...START.shared } },
  busy: false,
  pending: null, // the latest change's start time while a request is in flight
  seq: 0,
  plot: { a: new Map(), b: new Map() },
  latencies: [],
};
window.hilite = state; // the browser test reads state.latencies

const $ = (id) => document.getElementById(id);

async function api(path, body) {
  const res = await fetch("/api/" + path, body === undefined ? {} : {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  });
  const text = await res.text();
  if (!res.ok) throw new Error(text.trim());
  return JSON.parse(text);
}

function incidence() { return $("incidence").value; }

/// The values of a side as the API takes them: the shared ones, the side's own, the slider's angle.
function valuesOf(side) {
  return { ...state.values.shared, ...state.values[side], incidence: incidence() };
}

// ---- controls from the registry ----
function control(p, side) {
  const id = side ? `p-${side}-${p.name}` : `p-${p.name}`;
  const store = side ? state.values[side] : state.values.shared;
  const row = document.createElement("div");
  row.className = "control";
  const label = document.createElement("label");
  label.htmlFor = id;
  label.textContent = p.name;
  label.title = `${p.help} (${p.allowed}${p.unit ? " " + p.unit : ""}; default ${p.default || "unset"})`;
  let input;
  if (p.kind === "choice") {
    input = document.createElement("select");
    for (const c of p.choices) {
      const o = document.createElement("option");
      o.value = o.textContent = c;
      input.appendChild(o);
    }
    input.value = store[p.name] ?? p.default;
  } else if (p.kind === "switch") {
    input = document.createElement("input");
    input.type = "checkbox";
    input.checked = (store[p.name] ?? p.default) === "true";
  } else {
    input = document.createElement("input");
    input.type = "text";
    input.value = store[p.name] ?? "";
    input.placeholder = p.default || (p.automatic ? p.automatic : "unset");
    if (p.kind === "path") input.setAttribute("list", "files");
  }
  input.id = id;
  input.title = label.title;
  input.dataset.param = p.name;
  input.addEventListener("change", () => {
    let v = input.type === "checkbox" ? (input.checked ? "true" : "false") : input.value.trim();
    if (v === "" || (input.type === "checkbox" && v === p.default)) delete store[p.name];
    else store[p.name] = v;
    if (p.name === "incidence") return;
    resetPlot();
    if ($("match").checked && side && (p.name === "model" || side === "b")) matchWidths().then(update);
    else update();
  });
  const unit = document.createElement("span");
  unit.className = "unit";
  unit.textContent = p.kind === "choice" || p.kind === "switch" ? "" : `${p.allowed}${p.unit ? " " + p.unit : ""}`;
  row.append(label, input, unit);
  return row;
}

function buildControls() {
  for (const side of SIDES) {
    const box = $("controls-" + side);
    for (const p of state.registry) if (p.table === MATERIAL_TABLE) box.appendChild(control(p, side));
  }
  const shared = $("controls-shared");
  let table = "";
  for (const p of state.registry) {
    if (p.table === MATERIAL_TABLE || p.name === "incidence") continue; // the slider is the incidence
    if (p.table !== table) {
      table = p.table;
      const h = document.createElement("h3");
      h.textContent = `[${table}]`;
      shared.appendChild(h);
    }
    shared.appendChild(control(p, null));
  }
  const inc = state.registry.find((p) => p.name === "incidence");
  if (inc) $("incidence").title = inc.help;
}

function setControl(side, name, value) {
  const input = $(`p-${side}-${name}`);
  if (input) input.value = value;
}

// ---- width matching ----
async function matchWidths() {
  if (!$("match").checked) return;
  const material = (v) => Object.fromEntries(Object.entries(v).filter(([k]) => paramTable(k) === MATERIAL_TABLE));
  try {
    const m = await api("match", { target: material(state.values.b), values: material(state.values.a) });
    delete state.values.a.exponent;
    delete state.values.a.roughness;
    state.values.a[m.parameter] = String(m.value);
    setControl("a", "exponent", state.values.a.exponent ?? "");
    setControl("a", "roughness", state.values.a.roughness ?? "");
    $("error-a").textContent = "";
  } catch (e) {
    $("error-a").textContent = e.message;
  }
}

function paramTable(name) {
  const p = state.registry.find((q) => q.name === name);
  return p ? p.table : "";
}

// ---- drawing ----
function loadImage(png) {
  const img = new Image();
  img.src = "data:image/png;base64," + png;
  return img.decode().then(() => img);
}

function drawView(canvas, view, img) {
  const ctx = canvas.getContext("2d");
  ctx.fillStyle = "#000";
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  const sx = canvas.width / view.width, sy = canvas.height / view.height;
  ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
  ctx.strokeStyle = "#ff3b30";
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  let open = false;
  const pts = view.ellipse.concat(view.ellipse.length ? [view.ellipse[0]] : []);
  for (const p of pts) {
    if (!p) { open = false; continue; }
    if (open) ctx.lineTo(p[0] * sx, p[1] * sy);
    else ctx.moveTo(p[0] * sx, p[1] * sy);
    open = true;
  }
  ctx.stroke();
}

const fmt = (v, d) => (typeof v === "number" ? v.toFixed(d) : String(v ?? "–"));

function showRow(side, row, values) {
  const a = $("aspect-" + side);
  a.textContent = fmt(row.aspect, 5);
  a.dataset.aspect = String(row.aspect); // full precision: the browser test compares it with the CLI's
  a.dataset.values = JSON.stringify(values);
  $("ecc-" + side).textContent = fmt(row.eccentricity, 5);
  $("major-" + side).textContent = fmt(row.major_deg, 3);
  $("minor-" + side).textContent = fmt(row.minor_deg, 3);
  $("model-" + side).textContent = `${row.model ?? ""} ${row.exponent !== undefined ? "exponent " + fmt(row.exponent, 1) : ""}${row.roughness !== undefined ? "roughness " + row.roughness : ""}`;
  const flags = $("flags-" + side);
  flags.innerHTML = "";
  for (const f of row.flags || []) {
    const li = document.createElement("li");
    li.textContent = `${f}: ${FLAG_WORDS[f] || f}`;
    flags.appendChild(li);
  }
  if (typeof row.aspect === "number") state.plot[side].set(Number(values.incidence), row.aspect);
}

// ---- the update: both sides measured and rendered, coalesced while one is in flight ----
async function update(start = performance.now()) {
  if (state.busy) { state.pending = state.pending ?? start; return; }
  state.busy = true;
  const seq = ++state.seq;
  try {
    const values = { a: valuesOf("a"), b: valuesOf("b") };
    const answers = await Promise.all(SIDES.map((s) => api("render", { values: values[s] }).then(
      async (r) => ({ r, photo: await loadImage(r.photo.png), measure: await loadImage(r.measure.png) }),
      (e) => ({ error: e.message }))));
    SIDES.forEach((s, i) => {
      const ans = answers[i];
      $("error-" + s).textContent = ans.error || "";
      if (ans.error) return;
      drawView($("photo-" + s), ans.r.photo, ans.photo);
      drawView($("measure-" + s), ans.r.measure, ans.measure);
      showRow(s, ans.r.row, values[s]);
    });
    drawPlot();
    state.latencies.push(performance.now() - start);
    $("status").dataset.seq = String(seq);
    $("status").dataset.incidence = values.a.incidence;
    $("status").textContent = `updated in ${(performance.now() - start).toFixed(0)} ms`;
  } finally {
    state.busy = false;
  }
  scheduleSide();
  if (state.pending !== null) {
    const p = state.pending;
    state.pending = null;
    update(p);
  }
}

// Slices and the effects, after the views (CPU only, never in the slider's path).
let sideTimer = null;
function scheduleSide() {
  clearTimeout(sideTimer);
  sideTimer = setTimeout(async () => {
    const material = (side) => {
      const v = valuesOf(side), out = {};
      for (const [k, x] of Object.entries(v))
        if (paramTable(k) === MATERIAL_TABLE || k === "incidence" || k === "azimuth") out[k] = x;
      return out;
    };
    try {
      const s = await api("slice", { curves: SIDES.map((side) => ({ label: side.toUpperCase(), values: material(side) })), step: 1 });
      drawSlice(s.points);
    } catch (e) { $("status").textContent = e.message; }
    for (const side of SIDES) {
      try {
        const e = await api("explain", { values: valuesOf(side) });
        const ul = $("effects-" + side);
        ul.innerHTML = "";
        for (const t of e.effects) { const li = document.createElement("li"); li.textContent = t; ul.appendChild(li); }
      } catch (e) { $("error-" + side).textContent = e.message; }
    }
  }, 150);
}

const COLORS = { a: "#0a84ff", b: "#ff9f0a", A: "#0a84ff", B: "#ff9f0a" };

function axes(ctx, w, h, m, xr, yr, xlabel, ylabel) {
  ctx.clearRect(0, 0, w, h);
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, w, h);
  ctx.strokeStyle = "#888";
  ctx.strokeRect(m, 10, w - m - 10, h - m - 10);
  ctx.fillStyle = "#333";
  ctx.font = "11px sans-serif";
  ctx.fillText(xlabel, w / 2 - 30, h - 6);
  ctx.fillText(`${xr[0]}`, m, h - m + 14);
  ctx.fillText(`${xr[1]}`, w - 30, h - m + 14);
  ctx.fillText(ylabel, 4, 22);
  ctx.fillText(`${yr[1].toPrecision(3)}`, 4, 38);
  ctx.fillText(`${yr[0]}`, 4, h - m);
  return (x, y) => [m + ((x - xr[0]) / (xr[1] - xr[0])) * (w - m - 10), h - m - ((y - yr[0]) / (yr[1] - yr[0])) * (h - m - 20)];
}

function drawPlot() {
  const c = $("plot"), ctx = c.getContext("2d");
  const at = axes(ctx, c.width, c.height, 40, [0, 90], [0, 1.05], "theta_i (deg)", "aspect");
  ctx.setLineDash([4, 4]);
  ctx.strokeStyle = "#999";
  ctx.beginPath();
  for (let x = 0; x <= 90; x += 1) { const [px, py] = at(x, Math.cos((x * Math.PI) / 180)); x ? ctx.lineTo(px, py) : ctx.moveTo(px, py); }
  ctx.stroke();
  ctx.setLineDash([]);
  for (const side of SIDES) {
    const pts = [...state.plot[side].entries()].sort((p, q) => p[0] - q[0]);
    ctx.strokeStyle = ctx.fillStyle = COLORS[side];
    ctx.beginPath();
    pts.forEach(([x, y], i) => { const [px, py] = at(x, y); i ? ctx.lineTo(px, py) : ctx.moveTo(px, py); });
    ctx.stroke();
    for (const [x, y] of pts) { const [px, py] = at(x, y); ctx.fillRect(px - 2, py - 2, 4, 4); }
    ctx.fillText(side.toUpperCase(), c.width - 30, side === "a" ? 30 : 45);
  }
}

function drawSlice(points) {
  const c = $("slice"), ctx = c.getContext("2d");
  const inPlane = points.filter((p) => p.plane === "in");
  const ymax = Math.max(1e-12, ...inPlane.map((p) => p.f_cos));
  const at = axes(ctx, c.width, c.height, 40, [-90, 90], [0, ymax], "theta_o (deg)", "f cos");
  for (const label of ["A", "B"]) {
    const pts = inPlane.filter((p) => p.curve === label);
    ctx.strokeStyle = ctx.fillStyle = COLORS[label];
    ctx.beginPath();
    pts.forEach((p, i) => { const [px, py] = at(p.angle_deg, p.f_cos); i ? ctx.lineTo(px, py) : ctx.moveTo(px, py); });
    ctx.stroke();
    ctx.fillText(label, c.width - 30, label === "A" ? 30 : 45);
  }
}

function resetPlot() {
  state.plot.a.clear();
  state.plot.b.clear();
  drawPlot();
}

// ---- downloads and result folders ----
async function download(side) {
  try {
    const e = await api("explain", { values: valuesOf(side) });
    const a = document.createElement("a");
    a.href = URL.createObjectURL(new Blob([e.scene_toml], { type: "application/toml" }));
    a.download = `scene-${side}.toml`;
    document.body.appendChild(a);
    a.click();
    a.remove();
  } catch (e) { $("error-" + side).textContent = e.message; }
}

const RESULT_COLUMNS = ["config", "model", "incidence_deg", "aspect", "eccentricity", "major_deg", "minor_deg", "flags"];

async function showFolder(folder) {
  const table = $("results-table"), pics = $("results-pictures");
  table.innerHTML = "";
  pics.innerHTML = "";
  if (!folder) return;
  try {
    const r = await api("results/" + folder.split("/").map(encodeURIComponent).join("/"));
    $("results-info").textContent = `${r.rows.length} rows${r.rows_cut ? " (cut)" : ""}, ${r.pictures.length} pictures`;
    const cols = RESULT_COLUMNS.filter((c) => r.rows.some((row) => c in row));
    const head = table.createTHead().insertRow();
    for (const c of cols) { const th = document.createElement("th"); th.textContent = c; head.appendChild(th); }
    const body = table.createTBody();
    for (const row of r.rows.slice(0, 1000)) {
      const tr = body.insertRow();
      for (const c of cols) {
        const v = row[c];
        tr.insertCell().textContent = Array.isArray(v) ? v.join(",") : typeof v === "number" ? String(Number(v.toPrecision(6))) : String(v ?? "");
      }
    }
    for (const p of r.pictures) {
      const fig = document.createElement("figure");
      const img = document.createElement("img");
      img.src = "/results/" + (r.folder + "/" + p).split("/").map(encodeURIComponent).join("/");
      img.alt = p;
      const cap = document.createElement("figcaption");
      cap.textContent = p;
      fig.append(img, cap);
      pics.appendChild(fig);
    }
  } catch (e) { $("results-info").textContent = e.message; }
}

async function loadLists() {
  try {
    const r = await api("results");
    const sel = $("results-folder");
    for (const f of r.folders) { const o = document.createElement("option"); o.value = o.textContent = f; sel.appendChild(o); }
    const files = await api("files");
    for (const f of files.files) { const o = document.createElement("option"); o.value = f; $("files").appendChild(o); }
  } catch (e) { $("results-info").textContent = e.message; }
}

async function main() {
  state.registry = (await api("registry")).parameters;
  buildControls();
  $("incidence").addEventListener("input", () => {
    $("incidence-value").textContent = incidence();
    update(performance.now());
  });
  $("match").addEventListener("change", () => { resetPlot(); matchWidths().then(update); });
  $("plot-reset").addEventListener("click", resetPlot);
  for (const side of SIDES) $("download-" + side).addEventListener("click", () => download(side));
  $("results-folder").addEventListener("change", (e) => showFolder(e.target.value));
  drawPlot();
  await loadLists();
  await matchWidths();
  await update();
  document.body.dataset.ready = "true";
}

main().catch((e) => { $("status").textContent = "failed: " + e.message; });
